! SPDX-License-Identifier: MIT
!> Tests of the generated UCOSUBs (ucon/): the disk against the hand-checked one, every spec
!> against finite differences and its physics, the constants that say which outputs can be
!> non-zero, the checks the modules share, the fixed form against the free form, and the
!> generator's own checks (python -m ucon check, its unit tests).
module test_generated
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucon_call, only : evaluate_ucon, declare_ucon
    use rollcon_partials_check, only : ucon_check_options_type, ucon_check_result_type, &
        & check_ucon_state
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_disk_par, only : disk_par
    use rollcon_disk_reference, only : hand_disk_ucosub => rolling_disk_ucosub
    use rollcon_gen_rolling_disk, only : generated_disk_ucosub => rolling_disk_ucosub
    use rollcon_testing, only : unittest_type, new_unittest, check
    use disk_states, only : seed_random, random_disk_state
    use generated_specs_list, only : generated_spec_type, generated_specs, random_state, &
        & random_parameters, spec_par
    use generated_fixed_form, only : test_fixed_form
    use generated_physics, only : test_turntable, test_sphere, test_knife_edge, test_disk_height
    use generated_constants, only : test_time_free, test_holonomic
    use generated_helpers, only : test_helper_messages, test_helper_edges
    use generated_python, only : test_partials_check, test_python_unittest
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf
    implicit none
    private

    public :: collect_generated

    !> Value every output starts from when a test must see what a routine leaves untouched
    real(wp), parameter :: sentinel = 12345.0_wp
    !> A generic disk state: no angle at a multiple of pi/2, all rates non-zero
    real(wp), parameter :: generic_q(8) = [0.1_wp, 0.02_wp, -0.01_wp, 0.3_wp, 1.2_wp, 0.5_wp, &
        & -0.2_wp, -1.0_wp]

contains

    !> Tests of this suite.
    subroutine collect_generated(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("disk-matches-hand", test_disk_matches_hand), &
            & new_unittest("disk-forty-nine-non-zeros", test_disk_count), &
            & new_unittest("disk-bad-par-like-hand", test_disk_bad_par), &
            & new_unittest("derivatives-all-specs", test_derivatives), &
            & new_unittest("declarations", test_declarations), &
            & new_unittest("bad-selectors-and-par", test_bad_calls), &
            & new_unittest("turntable-time-terms", test_turntable), &
            & new_unittest("rolling-sphere-physics", test_sphere), &
            & new_unittest("knife-edge-physics", test_knife_edge), &
            & new_unittest("disk-height-physics", test_disk_height), &
            & new_unittest("time-free-constants", test_time_free), &
            & new_unittest("holonomic-constants", test_holonomic), &
            & new_unittest("helper-messages", test_helper_messages), &
            & new_unittest("helper-edges", test_helper_edges), &
            & new_unittest("fixed-form-matches-module", test_fixed_form), &
            & new_unittest("partials-check", test_partials_check), &
            & new_unittest("ucon-python-unittest", test_python_unittest)]
    end subroutine collect_generated

    !> Call a routine with every output preset to the sentinel.
    subroutine call_raw(ucosub, id, time, q, par, idrsel, iflag, scalar, array, xmatrx)
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: id, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(:)
        real(wp), intent(out) :: scalar, array(30), xmatrx(30, 30)

        scalar = sentinel
        array = sentinel
        xmatrx = sentinel
        call ucosub(id, time, q, par, size(par), idrsel, iflag, scalar, array, xmatrx)
    end subroutine call_raw

    !> |generated - hand| / scale; 0 when both are untouched, huge when only one is.
    elemental function deviation(generated, hand, scale) result(d)
        real(wp), intent(in) :: generated, hand, scale
        real(wp) :: d

        if ((generated == sentinel) .neqv. (hand == sentinel)) then
            d = huge(1.0_wp)
        else if (generated == sentinel) then
            d = 0.0_wp
        else
            d = abs(generated - hand) / scale
        end if
    end function deviation

    !> Generated and hand-checked disk UCOSUB agree in every output, every IDRSEL selection and
    !> every component, on 1000 seeded states (theta near 0 and pi/2 included, rates up to
    !> 1e3 rad/s, R log-uniform in [1e-3, 10] m), and leave the same entries untouched.
    subroutine test_disk_matches_hand(error)
        type(error_type), allocatable, intent(out) :: error
        ! Both routines evaluate, per entry, a sum of at most four products of at most four
        ! factors, with sin and cos good to about an ulp: they can differ by a few tens of eps
        ! times the largest term. Each entry is compared relative to a bound on its terms
        ! (F: |v| + R sum|rates|; a partial by a velocity: 1; by an angle: R sum|rates|; by a
        ! rate: R), so 1e-13 (about 450 eps) leaves a wide margin yet flags a wrong sign or
        ! factor in any term above 1e-13 of that bound. Measured worst: 4e-16.
        real(wp), parameter :: tol_rel = 1.0e-13_wp
        real(wp) :: q8(8), radius, q(30), par(11), spin
        real(wp) :: s_hand, a_hand(30), x_hand(30, 30), s_gen, a_gen(30), x_gen(30, 30)
        real(wp) :: scale_a(30), scale_x(30, 30), scale_s, d_s, d_a(30), d_x(30, 30)
        integer :: k, component, s1, s2, s3, location(2)

        call seed_random(3003)
        q = 0.0_wp
        do k = 1, 1000
            call random_disk_state(k, q8, radius)
            q(:8) = q8
            spin = radius*sum(abs(q8(6:8)))
            scale_a = 1.0_wp
            scale_a(4:5) = spin
            scale_a(6:8) = radius
            scale_x = radius
            scale_x(4:5, 4:5) = spin
            do component = 1, 3
                par = disk_par(7, radius, component)
                do s3 = 0, 1
                    do s2 = 0, 2
                        do s1 = 0, 4
                            call call_raw(hand_disk_ucosub, 4, 0.0_wp, q, par, [s1, s2, s3], 0, &
                                & s_hand, a_hand, x_hand)
                            call call_raw(generated_disk_ucosub, 4, 0.0_wp, q, par, &
                                & [s1, s2, s3], 0, s_gen, a_gen, x_gen)
                            call take_ucon_error(error)
                            if (allocated(error)) return
                            scale_s = merge(maxval(abs(q8(1:3))) + spin, spin, s1 == 1)
                            d_s = deviation(s_gen, s_hand, scale_s)
                            d_a = deviation(a_gen, a_hand, scale_a)
                            d_x = deviation(x_gen, x_hand, scale_x)
                            if (d_s <= tol_rel .and. all(d_a <= tol_rel) &
                                & .and. all(d_x <= tol_rel)) cycle
                            location = maxloc(d_x)
                            call check(error, .false., "state " // to_text(k) // ", component " &
                                & // to_text(component) // ", IDRSEL (" // to_text(s1) // "," &
                                & // to_text(s2) // "," // to_text(s3) // "): SCALAR " &
                                & // to_text(s_gen) // " vs " // to_text(s_hand) // "; ARRAY(" &
                                & // to_text(maxloc(d_a, 1)) // ") " &
                                & // to_text(a_gen(maxloc(d_a, 1))) // " vs " &
                                & // to_text(a_hand(maxloc(d_a, 1))) // "; XMATRX(" &
                                & // to_text(location(1)) // "," // to_text(location(2)) // ") " &
                                & // to_text(x_gen(location(1), location(2))) // " vs " &
                                & // to_text(x_hand(location(1), location(2))))
                            return
                        end do
                    end do
                end do
            end do
        end do
    end subroutine test_disk_matches_hand

    !> 3 values + 15 first partials + 31 second partials = 49 non-zero entries (the paper's
    !> count), symmetric XMATRX.
    subroutine test_disk_count(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30)
        integer :: component, total

        q = 0.0_wp
        q(:8) = generic_q
        total = 0
        do component = 1, 3
            call evaluate_ucon(generated_disk_ucosub, 1, 0.0_wp, q, &
                & disk_par(1, 0.1_wp, component), [1, 1, 1], scalar, array, xmatrx, error)
            if (allocated(error)) return
            call check(error, all(xmatrx == transpose(xmatrx)), "XMATRX is not symmetric")
            if (allocated(error)) return
            total = total + count([scalar /= 0.0_wp]) + count(array /= 0.0_wp) &
                & + count(xmatrx /= 0.0_wp)
        end do
        call check(error, total, 49, "non-zero entries over the three components")
    end subroutine test_disk_count

    !> Every bad PAR the hand-checked routine rejects, the generated one rejects with the same
    !> words, through ERRMES, before declaring or evaluating anything.
    subroutine test_disk_bad_par(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: par(11), bad(5)
        integer :: i

        call expect_both(error, disk_par(1, 0.1_wp, 1), 10, "NPAR >= 11")
        if (allocated(error)) return
        par = disk_par(1, 0.1_wp, 1)
        par(11) = 4.0_wp
        call expect_both(error, par, 11, "PAR(11) (no-slip component) must be 1, 2 or 3")
        if (allocated(error)) return
        par(11) = 1.5_wp
        call expect_both(error, par, 11, "got 1.5")
        if (allocated(error)) return
        bad = [0.0_wp, -0.1_wp, ieee_value(1.0_wp, ieee_positive_inf), &
            & ieee_value(1.0_wp, ieee_quiet_nan), -huge(1.0_wp)]
        do i = 1, size(bad)
            par = disk_par(1, 0.1_wp, 2)
            par(10) = bad(i)
            call expect_both(error, par, 11, "PAR(10) (disk radius R [m]) must be positive " &
                & // "and finite")
            if (allocated(error)) return
        end do
        call expect_both(error, par, 11, "got -")
        if (allocated(error)) return
        par = disk_par(1, 0.1_wp, 3)
        par(5) = 16.0_wp
        call expect_both(error, par, 11, "PAR(5) must be code 14")
        if (allocated(error)) return
        par = disk_par(1, 0.1_wp, 3)
        par(1) = 2.5_wp
        call expect_both(error, par, 11, "PAR(1) (part id) must be a positive whole number")
    end subroutine test_disk_bad_par

    !> Both disk routines reject par (initialisation and evaluation calls alike) with a
    !> message containing fragment, and leave every output untouched.
    subroutine expect_both(error, par, npar, fragment)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: par(:)
        integer, intent(in) :: npar
        character(len=*), intent(in) :: fragment
        integer :: which, iflag

        do which = 1, 2
            do iflag = 0, 3, 3
                if (which == 1) then
                    call expect_rejected(error, hand_disk_ucosub, "hand", par(:npar), iflag, &
                        & [1, 1, 1], fragment)
                else
                    call expect_rejected(error, generated_disk_ucosub, "generated", par(:npar), &
                        & iflag, [1, 1, 1], fragment)
                end if
                if (allocated(error)) return
            end do
        end do
    end subroutine expect_both

    !> One call must report an error containing fragment through ERRMES, outputs untouched.
    subroutine expect_rejected(error, ucosub, label, par, iflag, idrsel, fragment)
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface) :: ucosub
        character(len=*), intent(in) :: label, fragment
        real(wp), intent(in) :: par(:)
        integer, intent(in) :: iflag, idrsel(3)
        type(error_type), allocatable :: found
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30)

        q = 0.0_wp
        q(:3) = [0.1_wp, 0.2_wp, 0.3_wp]
        call call_raw(ucosub, 9, 0.5_wp, q, par, idrsel, iflag, scalar, array, xmatrx)
        call take_ucon_error(found)
        if (.not. allocated(found)) then
            call check(error, .false., label // ": not reported; expected '" // fragment // "'")
            return
        end if
        call check(error, index(found%message, "UCON/9: ") == 1 &
            & .and. index(found%message, fragment) > 0, label // ": message '" &
            & // found%message // "' lacks 'UCON/9: ' or '" // fragment // "'")
        if (allocated(error)) return
        call check(error, scalar == sentinel .and. all(array == sentinel) &
            & .and. all(xmatrx == sentinel), label // ": outputs written despite '" &
            & // fragment // "'")
    end subroutine expect_rejected

    !> Every generated routine against sixth-order central differences of its own lower-order
    !> outputs (check_ucon_state: dF/dq, d2F/dq dq, dF/dt, d2F/dt2, d2F/dt dq, symmetry,
    !> linearity in the velocities, selector 0), 300 seeded states per spec and component,
    !> time in [0, 10] s; not the angles of a pole (pole_free false: motion-partials).
    subroutine test_derivatives(error)
        type(error_type), allocatable, intent(out) :: error
        type(generated_spec_type), allocatable :: specs(:)
        type(ucon_check_options_type) :: options
        type(ucon_check_result_type) :: result
        real(wp), allocatable :: values(:), q(:)
        real(wp) :: time
        integer :: s, k, component

        allocate(specs(0))  ! silences gfortran -Wmaybe-uninitialized
        call generated_specs(specs)
        call seed_random(4004)
        do s = 1, size(specs)
            if (.not. specs(s)%pole_free) cycle
            allocate(q(size(specs(s)%codes)))
            do k = 1, 300
                call random_state(k, specs(s)%codes, q)
                call random_parameters(specs(s), values)
                call random_number(time)
                time = 10.0_wp*time
                do component = 1, specs(s)%ncomponents
                    call check_ucon_state(specs(s)%ucosub, 1, spec_par(specs(s), 1, values, &
                        & component), specs(s)%codes, time, q, options, result, error)
                    if (allocated(error)) return
                    if (size(result%mismatches) == 0) cycle
                    associate (m => result%mismatches(1))
                        call check(error, .false., specs(s)%name // ", state " // to_text(k) &
                            & // ", component " // to_text(component) // ": " // m%rule // " " &
                            & // m%output // "(" // to_text(m%row) // "," // to_text(m%column) &
                            & // ") returned " // to_text(m%returned) // ", expected " &
                            & // to_text(m%expected))
                    end associate
                    return
                end do
            end do
            deallocate(q)
        end do
        call check(error, result%compared > 300*(2 + 2 + 3 + 3 + 3)*20, &
            & "too few entries compared: " // to_text(result%compared))
    end subroutine test_derivatives

    !> The initialisation call declares the spec's codes, all for the part in PAR(1) (a spec of
    !> two parts: the second part's for the part after its codes).
    subroutine test_declarations(error)
        type(error_type), allocatable, intent(out) :: error
        type(generated_spec_type), allocatable :: specs(:)
        type(ucovar_registry_type) :: registry
        real(wp), allocatable :: values(:)
        integer :: s, component, id, entry

        allocate(specs(0))  ! silences gfortran -Wmaybe-uninitialized
        call generated_specs(specs)
        id = 0
        do s = 1, size(specs)
            call random_parameters(specs(s), values)
            do component = 1, specs(s)%ncomponents
                id = id + 1
                call declare_ucon(specs(s)%ucosub, id, spec_par(specs(s), 3 + s, values, &
                    & component), registry, error)
                if (allocated(error)) return
                entry = registry%find(id)
                call check(error, entry > 0, specs(s)%name // ": nothing declared")
                if (allocated(error)) return
                associate (declared => registry%entries(entry))
                    call check(error, size(declared%codes) == size(specs(s)%codes), &
                        & specs(s)%name // ": wrong number of variables declared")
                    if (allocated(error)) return
                    call check(error, all(declared%codes == specs(s)%codes) &
                        & .and. all(declared%parts == expected_parts(specs(s), 3 + s)), &
                        & specs(s)%name &
                        & // ": declared codes or parts differ from the spec")
                    if (allocated(error)) return
                end associate
            end do
        end do
    end subroutine test_declarations

    !> Every generated routine reports a bad IDRSEL, IFLAG, NPAR or component through ERRMES
    !> and leaves its outputs untouched (as the hand-checked disk does).
    subroutine test_bad_calls(error)
        type(error_type), allocatable, intent(out) :: error
        type(generated_spec_type), allocatable :: specs(:)
        real(wp), allocatable :: values(:), par(:)
        integer :: s, i
        integer, parameter :: bad_idrsel(3, 5) = reshape([5, 0, 0, -1, 0, 0, 0, 3, 0, &
            & 0, 0, 2, 1, 1, -1], [3, 5])

        allocate(specs(0))  ! silences gfortran -Wmaybe-uninitialized
        call generated_specs(specs)
        do s = 1, size(specs)
            call random_parameters(specs(s), values)
            par = spec_par(specs(s), 2, values, 1)
            do i = 1, size(bad_idrsel, 2)
                call expect_rejected(error, specs(s)%ucosub, specs(s)%name, par, 0, &
                    & bad_idrsel(:, i), "IDRSEL must be (0..4, 0..2, 0..1)")
                if (allocated(error)) return
            end do
            call expect_rejected(error, specs(s)%ucosub, specs(s)%name, par, 1, [1, 1, 1], &
                & "IFLAG must be 3 (initialise) or 0 (evaluate)")
            if (allocated(error)) return
            call expect_rejected(error, specs(s)%ucosub, specs(s)%name, &
                & par(:size(par) - 1), 0, [1, 1, 1], "needs NPAR >= " // to_text(size(par)))
            if (allocated(error)) return
            if (specs(s)%ncomponents > 1) then
                par(size(par)) = real(specs(s)%ncomponents + 1, wp)
                call expect_rejected(error, specs(s)%ucosub, specs(s)%name, par, 0, &
                    & [1, 1, 1], "PAR(" // to_text(size(par)) // ") (" &
                    & // specs(s)%component_meaning // ") must be")
                if (allocated(error)) return
            end if
        end do
    end subroutine test_bad_calls

    !> The part of each variable a spec declares with `part` in PAR(1) (spec_par gives a
    !> second part the id part + 1).
    pure function expected_parts(spec, part) result(parts)
        type(generated_spec_type), intent(in) :: spec
        integer, intent(in) :: part
        integer :: parts(size(spec%codes))

        parts = part
        if (spec%first_part_nvars > 0) parts(spec%first_part_nvars + 1:) = part + 1
    end function expected_parts

end module test_generated
