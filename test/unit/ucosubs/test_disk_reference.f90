! SPDX-License-Identifier: MIT
!> Tests of the hand-checked rolling-disk UCOSUB: derivatives, sparsity, selectors, bad PAR.
module test_disk_reference
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_partials_check, only : ucon_check_options_type, ucon_check_result_type, &
        & check_ucon_state
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_disk_par, only : disk_par, disk_codes, disk_npar
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_testing, only : unittest_type, new_unittest, check
    use disk_states, only : seed_random, random_disk_state
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_positive_inf, ieee_quiet_nan
    implicit none
    private

    public :: collect_disk_reference

    !> A generic state: no angle at a multiple of pi/2, all rates non-zero
    real(wp), parameter :: generic_q(8) = [0.1_wp, 0.02_wp, -0.01_wp, 0.3_wp, 1.2_wp, 0.5_wp, &
        & -0.2_wp, -1.0_wp]

contains

    !> Tests of this suite.
    subroutine collect_disk_reference(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("derivatives-1000-random-states", test_random_derivatives), &
            & new_unittest("forty-nine-non-zeros", test_count), &
            & new_unittest("matches-vector-form", test_vector_form), &
            & new_unittest("rolling-state-satisfies", test_rolling_state), &
            & new_unittest("selector-zero-untouched", test_selector_zero), &
            & new_unittest("several-selectors-one-call", test_several_selectors), &
            & new_unittest("bad-par-short", test_bad_npar), &
            & new_unittest("bad-par-component", test_bad_component), &
            & new_unittest("bad-par-radius", test_bad_radius), &
            & new_unittest("bad-par-code", test_bad_code), &
            & new_unittest("bad-par-part-id", test_bad_part_id)]
    end subroutine collect_disk_reference

    !> Every ARRAY and XMATRX entry against sixth-order central differences of the lower-order
    !> outputs, on 1000 seeded states per component (tolerance: ucon_check_options_type).
    subroutine test_random_derivatives(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_options_type) :: options
        type(ucon_check_result_type) :: result
        real(wp) :: q(8), radius
        integer :: k, component

        call seed_random(2024)
        do k = 1, 1000
            call random_disk_state(k, q, radius)
            do component = 1, 3
                call check_ucon_state(rolling_disk_ucosub, 1, disk_par(1, radius, component), &
                    & disk_codes, 0.0_wp, q, options, result, error)
                if (allocated(error)) return
                if (size(result%mismatches) > 0) then
                    associate (m => result%mismatches(1))
                        call check(error, .false., "state " // to_text(k) // ", component " &
                            & // to_text(component) // ": " // m%rule // " " // m%output // "(" &
                            & // to_text(m%row) // "," // to_text(m%column) // ") returned " &
                            & // to_text(m%returned) // ", expected " // to_text(m%expected))
                    end associate
                    return
                end if
            end do
        end do
        call check(error, result%compared > 3000*80, "too few entries compared: " &
            & // to_text(result%compared))
    end subroutine test_random_derivatives

    !> 3 values + 15 first partials + 31 second partials = 49 (the paper's count); everything
    !> outside the 8 x 8 block and every symbolically zero entry stays exactly zero.
    subroutine test_count(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: expected_first(3) = [6, 6, 3], expected_second(3) = [14, 14, 3]
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30)
        integer :: component, total

        q = 0.0_wp
        q(:8) = generic_q
        total = 0
        do component = 1, 3
            call evaluate_ucon(rolling_disk_ucosub, 1, 0.0_wp, q, disk_par(1, 0.1_wp, component), &
                & [1, 1, 1], scalar, array, xmatrx, error)
            if (allocated(error)) return
            call check(error, count(array /= 0.0_wp), expected_first(component), &
                & "non-zero first partials of component " // to_text(component))
            if (allocated(error)) return
            call check(error, count(xmatrx /= 0.0_wp), expected_second(component), &
                & "non-zero second partials of component " // to_text(component))
            if (allocated(error)) return
            call check(error, all(xmatrx == transpose(xmatrx)), "XMATRX is not symmetric")
            if (allocated(error)) return
            total = total + count([scalar /= 0.0_wp]) + count(array /= 0.0_wp) &
                & + count(xmatrx /= 0.0_wp)
        end do
        call check(error, total, 49, "non-zero expressions over the three components")
    end subroutine test_count

    !> F against an independent vector form: v_G + omega x r_GC with omega from docs/design.md §3.
    subroutine test_vector_form(error)
        type(error_type), allocatable, intent(out) :: error
        ! The two forms round differently; terms are at most R * max rate, so 1e-13 of that.
        real(wp), parameter :: tol_rel = 1.0e-13_wp
        real(wp) :: q(8), radius, omega(3), e_y2(3), slip(3), qq(30), scalar
        real(wp) :: array(30), xmatrx(30, 30), scale
        integer :: k, component

        call seed_random(77)
        qq = 0.0_wp
        do k = 1, 200
            call random_disk_state(k, q, radius)
            associate (psi => q(4), theta => q(5), psidot => q(6), thetadot => q(7), &
                & phidot => q(8))
                omega = psidot*[0.0_wp, 0.0_wp, 1.0_wp] &
                    & + thetadot*[cos(psi), sin(psi), 0.0_wp] &
                    & + phidot*[sin(theta)*sin(psi), -sin(theta)*cos(psi), cos(theta)]
                e_y2 = [-cos(theta)*sin(psi), cos(theta)*cos(psi), sin(theta)]
            end associate
            slip = q(1:3) + cross(omega, -radius*e_y2)
            scale = maxval(abs(q(1:3))) + radius*maxval(abs(q(6:8)))
            qq(:8) = q
            do component = 1, 3
                call evaluate_ucon(rolling_disk_ucosub, 1, 0.0_wp, qq, &
                    & disk_par(1, radius, component), [1, 0, 0], scalar, array, xmatrx, error)
                if (allocated(error)) return
                call check(error, scalar, slip(component), "F" // to_text(component) &
                    & // " at state " // to_text(k), abs_tol=tol_rel*scale)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_vector_form

    pure function cross(a, b) result(c)
        real(wp), intent(in) :: a(3), b(3)
        real(wp) :: c(3)

        c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
    end function cross

    !> Upright, rolling in +X at v with phidot = -v/R (docs/design.md §5): every F is zero.
    subroutine test_rolling_state(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: radius = 0.1_wp, speed = 0.1_wp
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30)
        integer :: component

        q = 0.0_wp
        q(:8) = [speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.5_wp*pi, 0.0_wp, 0.0_wp, -speed/radius]
        do component = 1, 3
            call evaluate_ucon(rolling_disk_ucosub, 1, 0.0_wp, q, &
                & disk_par(1, radius, component), [1, 0, 0], scalar, array, xmatrx, error)
            if (allocated(error)) return
            ! cos(pi/2) is 6e-17, not 0: F3 picks up R*thetadot*that, zero here; F1, F2 exact.
            call check(error, scalar, 0.0_wp, "F" // to_text(component) // " of pure rolling", &
                & abs_tol=1.0e-16_wp)
            if (allocated(error)) return
        end do
    end subroutine test_rolling_state

    !> Outputs not selected come back untouched, even when others are asked for.
    subroutine test_selector_zero(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: sentinel = -777.0_wp
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30), par(disk_npar)

        q = 0.0_wp
        q(:8) = generic_q
        par = disk_par(1, 0.1_wp, 1)
        scalar = sentinel
        array = sentinel
        xmatrx = sentinel
        call rolling_disk_ucosub(1, 0.0_wp, q, par, disk_npar, [0, 0, 0], 0, scalar, array, xmatrx)
        call check(error, scalar == sentinel .and. all(array == sentinel) &
            & .and. all(xmatrx == sentinel), "IDRSEL = (0, 0, 0) changed an output")
        if (allocated(error)) return
        call rolling_disk_ucosub(1, 0.0_wp, q, par, disk_npar, [0, 1, 0], 0, scalar, array, xmatrx)
        call check(error, scalar == sentinel .and. all(xmatrx == sentinel) &
            & .and. any(array /= sentinel), "IDRSEL = (0, 1, 0) touched SCALAR or XMATRX")
        if (allocated(error)) return
        call take_ucon_error(error)
    end subroutine test_selector_zero

    !> One call with (1, 1, 1) returns what three single-selector calls return.
    subroutine test_several_selectors(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: q(30), s_all, a_all(30), x_all(30, 30), s1, a1(30), x1(30, 30), s0, a0(30)
        real(wp) :: x0(30, 30)
        integer :: component

        q = 0.0_wp
        q(:8) = generic_q
        do component = 1, 3
            associate (par => disk_par(3, 0.25_wp, component))
                call evaluate_ucon(rolling_disk_ucosub, 2, 0.0_wp, q, par, [1, 1, 1], s_all, &
                    & a_all, x_all, error)
                if (allocated(error)) return
                call evaluate_ucon(rolling_disk_ucosub, 2, 0.0_wp, q, par, [1, 0, 0], s1, a0, &
                    & x0, error)
                if (allocated(error)) return
                call evaluate_ucon(rolling_disk_ucosub, 2, 0.0_wp, q, par, [0, 1, 0], s0, a1, &
                    & x0, error)
                if (allocated(error)) return
                call evaluate_ucon(rolling_disk_ucosub, 2, 0.0_wp, q, par, [0, 0, 1], s0, a0, &
                    & x1, error)
                if (allocated(error)) return
            end associate
            call check(error, s_all == s1 .and. all(a_all == a1) .and. all(x_all == x1), &
                & "combined selectors differ from single ones, component " // to_text(component))
            if (allocated(error)) return
        end do
    end subroutine test_several_selectors

    !> Call with a PAR and expect the error channel to carry fragment, outputs untouched.
    subroutine expect_par_error(error, par, npar, fragment)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: par(:)
        integer, intent(in) :: npar
        character(len=*), intent(in) :: fragment
        type(error_type), allocatable :: found
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30)

        q = 0.0_wp
        q(:8) = generic_q
        scalar = 0.0_wp
        array = 0.0_wp
        xmatrx = 0.0_wp
        call rolling_disk_ucosub(9, 0.0_wp, q, par, npar, [1, 1, 1], 0, scalar, array, xmatrx)
        call take_ucon_error(found)
        if (.not. allocated(found)) then
            call check(error, .false., "bad PAR not reported; expected '" // fragment // "'")
            return
        end if
        call check(error, index(found%message, "UCON/9: ") == 1 &
            & .and. index(found%message, fragment) > 0, &
            & "message '" // found%message // "' lacks 'UCON/9: ' or '" // fragment // "'")
        if (allocated(error)) return
        call check(error, scalar == 0.0_wp .and. all(array == 0.0_wp) .and. all(xmatrx == 0.0_wp), &
            & "outputs were written despite a bad PAR")
    end subroutine expect_par_error

    subroutine test_bad_npar(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_par_error(error, disk_par(1, 0.1_wp, 1), 10, "NPAR >= 11")
    end subroutine test_bad_npar

    subroutine test_bad_component(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: par(disk_npar)

        par = disk_par(1, 0.1_wp, 1)
        par(11) = 4.0_wp
        call expect_par_error(error, par, disk_npar, &
            & "PAR(11) (no-slip component) must be 1, 2 or 3")
        if (allocated(error)) return
        par(11) = 1.5_wp
        call expect_par_error(error, par, disk_npar, "got 1.5")
    end subroutine test_bad_component

    subroutine test_bad_radius(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: par(disk_npar), bad(3)
        integer :: i

        bad = [0.0_wp, -0.1_wp, ieee_value(1.0_wp, ieee_positive_inf)]
        do i = 1, size(bad)
            par = disk_par(1, 0.1_wp, 2)
            par(10) = bad(i)
            call expect_par_error(error, par, disk_npar, "PAR(10) (disk radius R [m]) must be " &
                & // "positive and finite")
            if (allocated(error)) return
        end do
        par(10) = ieee_value(1.0_wp, ieee_quiet_nan)
        call expect_par_error(error, par, disk_npar, "got NaN")
    end subroutine test_bad_radius

    subroutine test_bad_code(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: par(disk_npar)

        par = disk_par(1, 0.1_wp, 3)
        par(5) = 16.0_wp
        call expect_par_error(error, par, disk_npar, "PAR(5) must be code 14")
    end subroutine test_bad_code

    !> A part id that is not a positive whole number a default integer holds is refused, by
    !> the quick test of a valid PAR as by the checks that word the message.
    subroutine test_bad_part_id(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: par(disk_npar), bad(6)
        integer :: i

        bad = [0.0_wp, -2.0_wp, 1.5_wp, 1.0e12_wp, ieee_value(1.0_wp, ieee_positive_inf), &
            & ieee_value(1.0_wp, ieee_quiet_nan)]
        do i = 1, size(bad)
            par = disk_par(1, 0.1_wp, 2)
            par(1) = bad(i)
            call expect_par_error(error, par, disk_npar, "PAR(1) (part id) must be a positive " &
                & // "whole number")
            if (allocated(error)) return
        end do
    end subroutine test_bad_part_id

end module test_disk_reference
