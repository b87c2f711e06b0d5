! SPDX-License-Identifier: MIT
!> Tests that the UCOSUB checker catches the mistakes people make (and passes a correct routine),
!> and that the random states it draws are the documented ones.
module test_partials_check
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text, number_list
    use rollcon_partials_check, only : ucon_check_options_type, ucon_check_result_type, &
        & check_ucon_state
    use rollcon_disk_par, only : disk_par, disk_codes
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_random_states, only : seed_state, draw_state
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_ucosub_contract, only : scalar_value, array_dq, xmatrx_none, xmatrx_dqdq
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_output_files, only : make_folders, write_text_file
    use command_runs, only : file_text, rollcon_program, run_rollcon
    implicit none
    private

    public :: collect_partials_check

    !> The incline disk's generated routine and the tests' cache of compiled routines
    character(len=*), parameter :: incline_routine = "test/incline/incline_roll_ucosub.f"
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    character(len=*), parameter :: scratch = "build/test_partials_check"

    !> The fixed relative tolerance the checker once judged every entry by (1e-8 of the
    !> largest value compared): a right routine's deviations stay below it where the
    !> differences resolve the function, and the states below are chosen where they do not
    real(wp), parameter :: fixed_tolerance = 1.0e-8_wp

    !> The entry test_small_slip's routine returns 1e-5 too large: ARRAY(row) when column is
    !> 0, else XMATRX(row, column) and XMATRX(column, row)
    integer :: slip_row = 0, slip_column = 0

    real(wp), parameter :: generic_q(8) = [0.1_wp, 0.02_wp, -0.01_wp, 0.3_wp, 1.2_wp, 0.5_wp, &
        & -0.2_wp, -1.0_wp]

contains

    !> Tests of this suite.
    subroutine collect_partials_check(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("correct-routine-clean", test_clean), &
            & new_unittest("sign-error-first-partial", test_sign_error), &
            & new_unittest("wrong-selector-guard", test_wrong_guard), &
            & new_unittest("missing-symmetric-entry", test_missing_symmetric), &
            & new_unittest("quadratic-in-velocity", test_quadratic), &
            & new_unittest("hidden-state", test_hidden_state), &
            & new_unittest("random-states-xorshift64", test_random_sequence), &
            & new_unittest("random-states-in-ranges", test_random_ranges), &
            & new_unittest("sharp-bend-judged-at-a-finer-step", test_sharp_bend), &
            & new_unittest("incline-disk-near-its-singularity", test_incline_disk), &
            & new_unittest("incline-disk-random-states-clean", test_incline_states), &
            & new_unittest("slip-1e-5-well-conditioned-found", test_small_slip), &
            & new_unittest("unresolved-entries-not-checkable", test_not_checkable)]
    end subroutine collect_partials_check

    !> Run the checker on component 2 of a disk-like routine at the generic state.
    subroutine run_check(ucosub, result, error)
        procedure(rolling_disk_ucosub) :: ucosub
        type(ucon_check_result_type), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_options_type) :: options

        call check_ucon_state(ucosub, 1, disk_par(1, 0.1_wp, 2), disk_codes, 0.0_wp, generic_q, &
            & options, result, error)
    end subroutine run_check

    !> Pass when the result holds a finding of rule at (row, column) (0 = any).
    subroutine expect_finding(error, result, rule, row, column)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type), intent(in) :: result
        character(len=*), intent(in) :: rule
        integer, intent(in) :: row, column
        integer :: i

        do i = 1, size(result%mismatches)
            associate (m => result%mismatches(i))
                if (m%rule == rule .and. (row == 0 .or. m%row == row) &
                    & .and. (column == 0 .or. m%column == column)) return
            end associate
        end do
        call check(error, .false., "no '" // rule // "' finding at (" // to_text(row) // "," &
            & // to_text(column) // ") among " // to_text(size(result%mismatches)) // " findings")
    end subroutine expect_finding

    subroutine test_clean(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result

        call run_check(rolling_disk_ucosub, result, error)
        if (allocated(error)) return
        call check(error, size(result%mismatches), 0, "findings on the hand-checked routine")
    end subroutine test_clean

    !> dF/dpsi with its sign flipped (the kind of slip the paper's section 2 shows).
    subroutine sign_error_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        if (idrsel(2) == 1) array(4) = -array(4)
    end subroutine sign_error_ucosub

    subroutine test_sign_error(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result

        call run_check(sign_error_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "derivative", 4, 0)
    end subroutine test_sign_error

    !> Second derivatives guarded by IDRSEL(3) .EQ. 0 instead of 1 (the paper's listing).
    subroutine wrong_guard_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, [idrsel(1), idrsel(2), 1 - idrsel(3)], &
            & iflag, scalar, array, xmatrx)
    end subroutine wrong_guard_ucosub

    subroutine test_wrong_guard(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result

        call run_check(wrong_guard_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "derivative", 4, 4)
        if (allocated(error)) return
        call expect_finding(error, result, "selector-0", 0, 0)
    end subroutine test_wrong_guard

    !> Only the upper triangle of one mixed partial filled.
    subroutine missing_symmetric_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, &
            & xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        if (idrsel(3) == 1) xmatrx(5, 4) = 0.0_wp
    end subroutine missing_symmetric_ucosub

    subroutine test_missing_symmetric(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result

        call run_check(missing_symmetric_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "symmetry", 5, 4)
    end subroutine test_missing_symmetric

    !> F + psidot*thetadot with consistent partials: right derivatives, illegal constraint.
    subroutine quadratic_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        if (iflag /= 0) return
        if (idrsel(1) == 1) scalar = scalar + q(6)*q(7)
        if (idrsel(2) == 1) array(6:7) = array(6:7) + [q(7), q(6)]
        if (idrsel(3) == 1) then
            xmatrx(6, 7) = xmatrx(6, 7) + 1.0_wp
            xmatrx(7, 6) = xmatrx(7, 6) + 1.0_wp
        end if
    end subroutine quadratic_ucosub

    subroutine test_quadratic(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result
        integer :: i

        call run_check(quadratic_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "velocity-linear", 6, 7)
        if (allocated(error)) return
        do i = 1, size(result%mismatches)
            call check(error, result%mismatches(i)%rule /= "derivative", &
                & "consistent partials of the quadratic term were reported as wrong")
            if (allocated(error)) return
        end do
    end subroutine test_quadratic

    !> A routine whose value drifts from call to call (state kept between calls).
    subroutine hidden_state_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)
        integer, save :: calls = 0

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        calls = calls + 1
        if (idrsel(1) == 1) scalar = scalar + 1.0e-3_wp*calls
    end subroutine hidden_state_ucosub

    subroutine test_hidden_state(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result

        call run_check(hidden_state_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "repeat", 0, 0)
    end subroutine test_hidden_state

    !> Seed 2024, UCON 13: the generator's states and the first draw for codes 11, 14, 15, 21,
    !> 24 against Marsaglia's xorshift64 (13, 7, 17) written apart in Python with unsigned
    !> 64-bit integers: the same on every compiler, as the checker's reports promise. The
    !> states must be equal; the values come from the same few operations on the same
    !> uniform numbers, a rounding or two apart at most (a fused multiply-add).
    subroutine test_random_sequence(error)
        type(error_type), allocatable, intent(out) :: error
        integer(int64), parameter :: seeded = 6963366699050944314_int64, &
            & drawn = 7344781435211780735_int64
        real(wp), parameter :: expected_q(5) = [-0.6287106138188773_wp, 2.988130153476352_wp, &
            & 0.8204572907220647_wp, 0.8242927336680732_wp, 1.8275865712337636_wp]
        real(wp), parameter :: expected_time = 3.981613994243907_wp
        real(wp), parameter :: tol_draw = 4.0_wp*epsilon(1.0_wp)
        integer(int64) :: state
        real(wp) :: q(5), time

        state = seed_state(2024, 13)
        call check(error, state == seeded, "the seeded state: " // to_text(state))
        if (allocated(error)) return
        call draw_state(state, [11, 14, 15, 21, 24], q, time)
        call check(error, state == drawn, "the state after one draw: " // to_text(state))
        if (allocated(error)) return
        call check(error, q, expected_q, "X, psi, theta, Xdot, psidot", rel_tol=tol_draw)
        if (allocated(error)) return
        call check(error, time, expected_time, "time", rel_tol=tol_draw)
    end subroutine test_random_sequence

    !> 10 000 draws of all twelve codes: every value inside its documented range
    !> (sampling_ranges) and, as uniform draws do, within 2 % of the range's ends (missing one
    !> by that much has a probability below e^-100); the same seed and UCON give the same
    !> states, another UCON others.
    subroutine test_random_ranges(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: draws = 10000, codes(12) = [11, 12, 13, 14, 15, 16, 21, 22, 23, &
            & 24, 25, 26]
        !> theta's distance from 0 and pi [rad]
        real(wp), parameter :: margin = 0.05_wp
        real(wp) :: low(13), high(13), q(12), time, smallest(13), largest(13), other(12)
        real(wp) :: other_time
        integer(int64) :: state, again, another
        logical :: inside
        integer :: i

        low = [-1.0_wp, -1.0_wp, -1.0_wp, -pi, margin, -pi, -1.0_wp, -1.0_wp, -1.0_wp, &
            & -10.0_wp, -10.0_wp, -10.0_wp, 0.0_wp]
        high = [1.0_wp, 1.0_wp, 1.0_wp, pi, pi - margin, pi, 1.0_wp, 1.0_wp, 1.0_wp, 10.0_wp, &
            & 10.0_wp, 10.0_wp, 10.0_wp]
        smallest = huge(1.0_wp)
        largest = -huge(1.0_wp)
        state = seed_state(7, 1)
        again = seed_state(7, 1)
        another = seed_state(7, 2)
        do i = 1, draws
            call draw_state(state, codes, q, time)
            smallest = min(smallest, [q, time])
            largest = max(largest, [q, time])
            if (i == 1) then
                call draw_state(again, codes, other, other_time)
                call check(error, all(other == q) .and. other_time == time, &
                    & "the same seed and UCON draw the same state")
                if (allocated(error)) return
                call draw_state(another, codes, other, other_time)
                call check(error, all(other /= q), "another UCON draws another state")
                if (allocated(error)) return
            end if
        end do
        do i = 1, 13
            if (i == 13) then
                ! time: the closed interval [0, 10] s
                inside = smallest(i) >= low(i) .and. largest(i) <= high(i)
            else
                inside = smallest(i) > low(i) .and. largest(i) < high(i)
            end if
            call check(error, inside, "value " // to_text(i) // " in range: " &
                & // to_text(smallest(i)) // " to " // to_text(largest(i)))
            if (allocated(error)) return
            call check(error, smallest(i) < low(i) + 0.02_wp*(high(i) - low(i)) .and. &
                & largest(i) > high(i) - 0.02_wp*(high(i) - low(i)), "value " // to_text(i) &
                & // " reaches the ends of its range")
            if (allocated(error)) return
        end do
    end subroutine test_random_ranges

    !> F = sin(k X) + sin(k t) + Y with k = 200 (1/m and 1/s), every partial exact; with
    !> slip, dF/dX returned 0.1 % too large.
    subroutine sharp_bend_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)
        real(wp) :: k

        k = par(1)
        ! IDRSEL(1): 1 F, 2 its explicit time part, 3 dF/dt, 4 d2F/dt2
        select case (idrsel(1))
        case (1)
            scalar = sin(k*q(1)) + sin(k*time) + q(2)
        case (2)
            scalar = sin(k*time)
        case (3)
            scalar = k*cos(k*time)
        case (4)
            scalar = -k**2*sin(k*time)
        end select
        if (idrsel(2) == 1) array(1:2) = [k*cos(k*q(1))*par(2), 1.0_wp]
        if (idrsel(3) == 1) xmatrx(1, 1) = -k**2*sin(k*q(1))
    end subroutine sharp_bend_ucosub

    !> A right routine where the function bends sharply: sin(200 X) at the step h = 1e-3
    !> leaves the sixth-order quotient (k h)^6/140 = 4.6e-7 off, 46 times the fixed tolerance
    !> 1e-8 the checker once used, and the quotient at h/4 is good to 1.1e-10: no finding, and
    !> the largest deviation reported (from the quotient the check settles on) below 1e-8.
    !> The same routine with dF/dX 0.1 % too large is still found (a deviation 1e5 times the
    !> quotients' error).
    subroutine test_sharp_bend(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result
        type(ucon_check_options_type) :: options
        real(wp), parameter :: q(2) = [0.3_wp, -0.4_wp]

        call check_ucon_state(sharp_bend_ucosub, 1, [200.0_wp, 1.0_wp], [11, 12], 0.2_wp, q, &
            & options, result, error)
        if (allocated(error)) return
        call check(error, size(result%mismatches), 0, "findings on a right routine")
        if (allocated(error)) return
        call check(error, result%worst <= fixed_tolerance, "largest deviation " &
            & // to_text(result%worst) // " after the finer step")
        if (allocated(error)) return
        call check_ucon_state(sharp_bend_ucosub, 1, [200.0_wp, 1.001_wp], [11, 12], 0.2_wp, &
            & q, options, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "derivative", 1, 0)
    end subroutine test_sharp_bend

    !> test/incline/incline_roll_ucosub.f, written by the project's generator from our spec
    !> test/incline/incline_roll_spec.py (a disk of radius 0.1 m rolling on a plane tilted by
    !> alpha = 20 degrees about X), at a state whose axle is 0.01 rad from the incline's
    !> normal, near the spec's singularity (the disk flat on the plane, where the contact
    !> direction's norm sqrt(1 - (n.k)^2) vanishes): there the sixth-order quotients at the
    !> checker's step (1e-3) miss some exact entry by more than the fixed tolerance 1e-8
    !> (measured here, so the state is one a fixed threshold calls a mismatch), and the check,
    !> which judges each entry against the differences' own estimated error at halved steps,
    !> finds nothing in any of the three components (the quotients at 1e-3 miss by 4.2e-5,
    !> measured, 4000 times the tolerance). A copy with dF/dpsi of component 1 returned 0.1 %
    !> too large (a slip 1e5 times the tolerance) is found at the same state. Through the
    !> program, with the dataset test/incline/incline_roll.adm (its disk spinning at that
    !> state): `rollcon check FILE --model` is CLEAN and the run, which checks the routine at
    !> its consistent start, completes with nothing on stderr; the copy gets a MISMATCH from
    !> the check and stops the run, naming UCON/1 (line 12) and ARRAY(4).
    subroutine test_incline_disk(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: alpha = 0.3490658503988659_wp, radius = 0.1_wp
        integer, parameter :: codes(8) = [21, 22, 23, 14, 15, 24, 25, 26]
        type(user_ucosub_type) :: user, slipped
        type(user_build_options_type) :: build
        type(ucon_check_options_type) :: options
        type(ucon_check_result_type) :: result
        real(wp) :: q(8), worst_coarse, par(12)
        character(len=:), allocatable :: text, copy
        integer :: component, at

        ! Xdot, Ydot, Zdot, psi, theta (alpha + 0.01: the axle 0.01 rad from the normal),
        ! psidot, thetadot, phidot: a disk spinning and wobbling near flat
        q = [0.3_wp, -0.2_wp, 0.05_wp, 0.0_wp, alpha + 0.01_wp, 1.5_wp, 0.5_wp, 8.0_wp]
        build%cache_dir = test_cache
        call new_user_ucosub(user, incline_routine, error, build)
        if (allocated(error)) return
        worst_coarse = 0.0_wp
        do component = 1, 3
            par = [2.0_wp, real(codes, wp), radius, alpha, real(component, wp)]
            worst_coarse = max(worst_coarse, coarse_deviation(user, par, q, options%step, error))
            if (allocated(error)) exit
            call check_ucon_state(user%ucosub, component, par, codes, 0.0_wp, q, options, &
                & result, error)
            if (allocated(error)) exit
            call check(error, size(result%mismatches), 0, "findings on the generated routine, " &
                & // "component " // to_text(component))
            if (allocated(error)) exit
        end do
        call user%destroy()
        if (allocated(error)) return
        call check(error, worst_coarse > fixed_tolerance, "the quotients at the step 1e-3 " &
            & // "miss the exact entries by at most " // to_text(worst_coarse) &
            & // ": the state is not one where a fixed threshold fails")
        if (allocated(error)) return
        ! the slip: ARRAY(4) of component 1 (the first ARRAY(5) follows it) scaled by 1.001
        text = file_text(incline_routine)
        at = index(text, "            ARRAY(5) = ")
        if (at == 0) then
            call check(error, .false., incline_routine // ": no ARRAY(5) to plant the slip at")
            return
        end if
        copy = text(:at - 1) // "            ARRAY(4) = 1.001D0*ARRAY(4)" // new_line("a") &
            & // text(at:)
        call make_folders(scratch, error)
        if (allocated(error)) return
        call write_text_file(scratch // "/incline_roll_slipped.f", copy, error)
        if (allocated(error)) return
        call new_user_ucosub(slipped, scratch // "/incline_roll_slipped.f", error, build)
        if (allocated(error)) return
        par = [2.0_wp, real(codes, wp), radius, alpha, 1.0_wp]
        call check_ucon_state(slipped%ucosub, 1, par, codes, 0.0_wp, q, options, result, &
            & error)
        call slipped%destroy()
        if (allocated(error)) return
        call expect_finding(error, result, "derivative", 4, 0)
        if (allocated(error)) return
        call program_verdicts(incline_routine, .true., error)
        if (allocated(error)) return
        call program_verdicts(scratch // "/incline_roll_slipped.f", .false., error)
    end subroutine test_incline_disk

    !> F = sqrt(X**2 + c**2), c = PAR(1) [m]: |X| rounded off within c of X = 0, every
    !> partial exact (dF/dX = X/F, d2F/dX2 = c**2/F**3).
    subroutine kink_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)
        real(wp) :: f

        f = sqrt(q(1)**2 + par(1)**2)
        if (idrsel(1) == 1) scalar = f
        if (idrsel(2) == 1) array(1) = q(1)/f
        if (idrsel(3) == 1) xmatrx(1, 1) = par(1)**2/f**3
    end subroutine kink_ucosub

    !> kink_ucosub with c = 1e-9 m at X = 3e-9 m: every step the check takes (1e-3 m down to
    !> 2e-6 m) straddles the bend, so no quotient knows dF/dX (0.95) or d2F/dX2 (3.2e7 1/m):
    !> at every step they change as much as they are. Both entries are counted not checkable
    !> here, neither a mismatch (the returned values are exact) nor a pass; the time entries
    !> (F holds no time: zero, and their differences exactly zero) pass. A check that called
    !> the two right or wrong fails here.
    subroutine test_not_checkable(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result
        type(ucon_check_options_type) :: options
        integer :: i

        call check_ucon_state(kink_ucosub, 1, [1.0e-9_wp], [11], 0.2_wp, [3.0e-9_wp], &
            & options, result, error)
        if (allocated(error)) return
        do i = 1, size(result%mismatches)
            call check(error, .false., "a finding where no step resolves the function: " &
                & // result%mismatches(i)%output // " (" // to_text(result%mismatches(i)%row) &
                & // "," // to_text(result%mismatches(i)%column) // "), returned " &
                & // to_text(result%mismatches(i)%returned) // ", differences give " &
                & // to_text(result%mismatches(i)%expected))
            if (allocated(error)) return
        end do
        call check(error, result%not_checkable, 2, "entries not checkable")
        if (allocated(error)) return
        call check(error, result%compared, 5, "entries compared")
    end subroutine test_not_checkable

    !> test/incline/incline_roll_ucosub.f (generated, exact) at every state `rollcon check FILE
    !> --model test/incline/incline_roll.adm --states 2000` draws with seeds 1 and 2 (the same
    !> generator, seed and UCON id; 12000 states, a few seconds): no finding. Among them the
    !> two where the fixed tolerance 1e-8 once found three false mismatches (seed 1, UCON/1
    !> state 1470: XMATRX(4,5) and (5,5), the quotients at the step 1e-3 6e-4 off, the axle
    !> 0.02 rad from the incline's normal; UCON/2 state 183: XMATRX(5,5) 6e-8 off, its values
    !> carrying some 2000 eps of rounding there): at both the quotients at the first step miss
    !> the exact entries by more than 1e-8 (measured, so the test holds states a fixed
    !> threshold fails).
    subroutine test_incline_states(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: alpha = 0.3490658503988659_wp, radius = 0.1_wp
        integer, parameter :: codes(8) = [21, 22, 23, 14, 15, 24, 25, 26], states = 2000
        integer, parameter :: hard_ucon(2) = [1, 2], hard_state(2) = [1470, 183]
        type(user_ucosub_type) :: user
        type(user_build_options_type) :: build
        type(ucon_check_options_type) :: options
        type(ucon_check_result_type) :: result
        real(wp) :: q(8), par(12), time, worst_coarse
        integer(int64) :: random
        character(len=:), allocatable :: first
        integer :: seed, component, s, found, checked
        logical :: hard

        build%cache_dir = test_cache
        call new_user_ucosub(user, incline_routine, error, build)
        if (allocated(error)) return
        worst_coarse = huge(1.0_wp)
        found = 0
        checked = 0
        first = ""
        outer: do seed = 1, 2
            do component = 1, 3
                par = [2.0_wp, real(codes, wp), radius, alpha, real(component, wp)]
                random = seed_state(seed, component)
                do s = 1, states
                    call draw_state(random, codes, q, time)
                    hard = seed == 1 .and. any(hard_ucon == component .and. hard_state == s)
                    if (hard) then
                        worst_coarse = min(worst_coarse, coarse_deviation(user, par, q, &
                            & options%step, error))
                        if (allocated(error)) exit outer
                    end if
                    result = ucon_check_result_type()
                    call check_ucon_state(user%ucosub, component, par, codes, time, q, &
                        & options, result, error)
                    if (allocated(error)) exit outer
                    checked = checked + 1
                    found = found + size(result%mismatches)
                    if (size(result%mismatches) > 0 .and. len(first) == 0) first = "seed " &
                        & // to_text(seed) // ", UCON/" // to_text(component) // ", state " &
                        & // to_text(s) // ": " // result%mismatches(1)%output // " (" &
                        & // to_text(result%mismatches(1)%row) // "," &
                        & // to_text(result%mismatches(1)%column) // ") returned " &
                        & // to_text(result%mismatches(1)%returned) // ", differences give " &
                        & // to_text(result%mismatches(1)%expected) // " at time " &
                        & // to_text(time) // ", q " // number_list(q)
                end do
            end do
        end do outer
        call user%destroy()
        if (allocated(error)) return
        call check(error, checked == 2*3*states .and. found == 0, to_text(found) &
            & // " findings in " // to_text(checked) // " states of the exact routine; the " &
            & // "first: " // first)
        if (allocated(error)) return
        call check(error, worst_coarse > fixed_tolerance, "at the two hard states the " &
            & // "quotients at the step 1e-3 miss the exact entries by " // to_text(worst_coarse) &
            & // " at least: not states where a fixed threshold fails")
    end subroutine test_incline_states

    !> The hand-checked disk with one entry 1e-5 too large (slip_row, slip_column).
    subroutine small_slip_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)
        real(wp), parameter :: slip = 1.0e-5_wp

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        if (iflag /= 0) return
        if (slip_column == 0 .and. idrsel(2) == 1) then
            array(slip_row) = (1.0_wp + slip)*array(slip_row)
        else if (slip_column > 0 .and. idrsel(3) == 1) then
            xmatrx(slip_row, slip_column) = (1.0_wp + slip)*xmatrx(slip_row, slip_column)
            if (slip_row /= slip_column) xmatrx(slip_column, slip_row) = (1.0_wp + slip) &
                & *xmatrx(slip_column, slip_row)
        end if
    end subroutine small_slip_ucosub

    !> A slip of 1e-5 (relative) in a well-conditioned entry is still found, so the estimate of
    !> the differences' error did not get loose: at the generic state, component 2 of the
    !> hand-checked disk, the largest entry of ARRAY and the largest of XMATRX (both triangles),
    !> each returned 1e-5 too large, each a derivative finding at that entry and nowhere else
    !> in its output (the right routine is clean: correct-routine-clean). A check that lets a
    !> tenth of the slip through misses it.
    subroutine test_small_slip(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_result_type) :: result
        real(wp) :: q30(30), f, a(30), x(30, 30)
        integer :: loc(2), i

        q30 = 0.0_wp
        q30(:8) = generic_q
        call evaluate_ucon(rolling_disk_ucosub, 1, 0.0_wp, q30, disk_par(1, 0.1_wp, 2), &
            & [scalar_value, array_dq, xmatrx_dqdq], f, a, x, error)
        if (allocated(error)) return
        slip_row = maxloc(abs(a(:8)), dim=1)
        slip_column = 0
        call run_check(small_slip_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "derivative", slip_row, 0)
        if (allocated(error)) return
        do i = 1, size(result%mismatches)
            call check(error, result%mismatches(i)%output /= "ARRAY (dF/dq)" .or. &
                & result%mismatches(i)%row == slip_row, "a finding at ARRAY(" &
                & // to_text(result%mismatches(i)%row) // "), the slip is at ARRAY(" &
                & // to_text(slip_row) // ")")
            if (allocated(error)) return
        end do
        loc = maxloc(abs(x(:8, :8)))
        slip_row = loc(1)
        slip_column = loc(2)
        call run_check(small_slip_ucosub, result, error)
        if (allocated(error)) return
        call expect_finding(error, result, "derivative", slip_row, slip_column)
        if (allocated(error)) return
        do i = 1, size(result%mismatches)
            call check(error, result%mismatches(i)%output == "XMATRX (d2F/dq dq)" .and. &
                & (result%mismatches(i)%row == slip_row .and. result%mismatches(i)%column &
                & == slip_column .or. result%mismatches(i)%row == slip_column .and. &
                & result%mismatches(i)%column == slip_row), "a finding at " &
                & // result%mismatches(i)%output // " (" // to_text(result%mismatches(i)%row) &
                & // "," // to_text(result%mismatches(i)%column) // "), the slip is at (" &
                & // to_text(slip_row) // "," // to_text(slip_column) // ")")
            if (allocated(error)) return
        end do
    end subroutine test_small_slip

    !> `rollcon check routine --model test/incline/incline_roll.adm` and `rollcon run` of that
    !> dataset with the routine: clean (CLEAN; the run completes, stderr empty) or not (a
    !> MISMATCH; the run stops at its start naming UCON/1 (line 12)'s ARRAY(4)).
    subroutine program_verdicts(routine, clean, error)
        character(len=*), intent(in) :: routine
        logical, intent(in) :: clean
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: model = "test/incline/incline_roll.adm"
        character(len=:), allocatable :: program, checked, ran_err
        integer :: check_status, run_status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call run_rollcon(program, "check " // routine // " --model " // model, scratch &
            & // "/check.out", scratch // "/check.err", check_status)
        call run_rollcon(program, "run " // model // " --ucosub " // routine // " -q -o " &
            & // scratch // "/run", scratch // "/run.out", scratch // "/run.err", run_status)
        checked = file_text(scratch // "/check.out")
        ran_err = file_text(scratch // "/run.err")
        if (clean) then
            call check(error, check_status == 0 .and. index(checked, "verdict: CLEAN: 3 " &
                & // "UCON(s) checked, no mismatch") > 0 .and. run_status == 0 .and. &
                & len_trim(ran_err) == 0, routine // ": check exit " // to_text(check_status) &
                & // ", run exit " // to_text(run_status) // "; check: " // checked &
                & // "; run's stderr: " // ran_err)
        else
            call check(error, check_status /= 0 .and. index(checked, "MISMATCH") > 0 .and. &
                & run_status /= 0 .and. index(ran_err, "UCON/1 (line 12) ARRAY(4) = " &
                & // "dF/d(psi_2) [derivative]") > 0, routine // ": check exit " &
                & // to_text(check_status) // ", run exit " // to_text(run_status) &
                & // "; check: " // checked // "; run's stderr: " // ran_err)
        end if
    end subroutine program_verdicts

    !> The largest relative deviation of the sixth-order quotients at the step step (relative,
    !> as the checker's) from the routine's own dF/dq and d2F/dq dq at q (PAR par), each judged
    !> against the largest magnitude of the entry and its differenced values: what a check
    !> with a fixed threshold compares with it.
    function coarse_deviation(user, par, q, step, error) result(worst)
        type(user_ucosub_type), intent(in) :: user
        real(wp), intent(in) :: par(:), q(:), step
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: worst
        real(wp), parameter :: weights(-3:3) = [-1.0_wp, 9.0_wp, -45.0_wp, 0.0_wp, 45.0_wp, &
            & -9.0_wp, 1.0_wp] / 60.0_wp
        real(wp) :: q30(30), f, a(30), x(30, 30), f_line(-3:3), a_line(30, -3:3), h, quotient
        real(wp) :: scratch_x(30, 30)
        integer :: n, i, j, k

        worst = 0.0_wp
        n = size(q)
        q30 = 0.0_wp
        q30(:n) = q
        call evaluate_ucon(user%ucosub, int(par(12)), 0.0_wp, q30, par, [scalar_value, &
            & array_dq, xmatrx_dqdq], f, a, x, error)
        if (allocated(error)) return
        do j = 1, n
            h = step*max(1.0_wp, abs(q(j)))
            do k = -3, 3
                q30(:n) = q
                q30(j) = q(j) + k*h
                call evaluate_ucon(user%ucosub, int(par(12)), 0.0_wp, q30, par, &
                    & [scalar_value, array_dq, xmatrx_none], f_line(k), a_line(:, k), &
                    & scratch_x, error)
                if (allocated(error)) return
            end do
            quotient = dot_product(weights, f_line)/h
            worst = max(worst, abs(quotient - a(j))/max(abs(a(j)), maxval(abs(f_line)), &
                & tiny(1.0_wp)))
            do i = 1, n
                quotient = dot_product(weights, a_line(i, :))/h
                worst = max(worst, abs(quotient - x(i, j))/max(abs(x(i, j)), &
                    & maxval(abs(a_line(i, :))), tiny(1.0_wp)))
            end do
        end do
    end function coarse_deviation

end module test_partials_check
