! SPDX-License-Identifier: MIT
!> The initial-conditions analysis (rollcon_initial_conditions): a perturbed coin start
!> recovered, the documented weights, exact values held, redundant UCONs met and set aside by
!> name, contradictory and unreachable UCONs refused by name, and the namelist scenes' starts
!> as its special case; a long chain on the sparse way (ic_chain).
module test_initial_conditions
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of, &
        & analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type, ic_report_text
    use ic_models, only : coin_problem, coin_start, ucon_noslip, ucon_height, coin_radius, &
        & coin_rho
    use ic_scene_starts, only : test_scene_starts, test_scene_velocities
    use ic_datasets, only : test_exact_read, test_exact_refused, test_dataset_exact, &
        & test_dataset_run, test_given_kept, test_defaulted_moved, test_given_contradicted
    use ic_chain, only : test_chain_sparse_start, test_chain_sparse_contradiction
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_initial_conditions

    !> The issue's demand for a recovered start. The free values enter these UCONs linearly
    !> (Z in Z - R sin(theta) with theta held, the centre velocity in F1, F2 and the height's
    !> velocity form), so one least-squares step lands on the exact start up to the rounding of
    !> O(0.1) values (~1e-17); 1e-12 leaves room for the SVD's rounding
    real(wp), parameter :: tol_recovered = 1.0e-12_wp
    !> Weighted changes against their closed form: both come from the same O(1) arithmetic in a
    !> different order; 1e-15 relative is a few ulps of it
    real(wp), parameter :: tol_weights = 1.0e-15_wp

contains

    subroutine collect_initial_conditions(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("perturbed-coin-recovered", test_perturbed_coin), &
            & new_unittest("consistent-start-untouched", test_consistent_start), &
            & new_unittest("least-weighted-change", test_weights), &
            & new_unittest("exact-values-held", test_exact_held), &
            & new_unittest("redundant-f3-twice-set-aside", test_f3_twice), &
            & new_unittest("redundant-height-kept-over-f3", test_height_and_f3), &
            & new_unittest("contradictory-heights", test_contradictory_heights), &
            & new_unittest("no-convergence", test_no_convergence), &
            & new_unittest("held-ucon-unmet", test_held_ucon_unmet), &
            & new_unittest("angle-step-limited", test_angle_limit), &
            & new_unittest("scene-starts", test_scene_starts), &
            & new_unittest("scene-velocities", test_scene_velocities), &
            & new_unittest("exact-keyword-read", test_exact_read), &
            & new_unittest("exact-keyword-refused", test_exact_refused), &
            & new_unittest("dataset-exact-held", test_dataset_exact), &
            & new_unittest("dataset-run-report", test_dataset_run), &
            & new_unittest("given-velocities-kept", test_given_kept), &
            & new_unittest("defaulted-velocities-moved", test_defaulted_moved), &
            & new_unittest("given-velocities-contradicted", test_given_contradicted), &
            & new_unittest("long-chain-sparse-start", test_chain_sparse_start), &
            & new_unittest("long-chain-sparse-contradiction", test_chain_sparse_contradiction)]
    end subroutine collect_initial_conditions

    !> The coin with F1, F2 and the height Z - R sin(theta) as a position UCON.
    subroutine height_coin(problem, error)
        type(problem_type), intent(inout), target :: problem
        type(error_type), allocatable, intent(out) :: error

        call coin_problem([ucon_noslip, ucon_noslip, ucon_height], [1.0_wp, 2.0_wp, &
            & coin_radius], problem, error)
    end subroutine height_coin

    !> Options that hold X, Y, the angles and the rates: only Z and the centre velocity free.
    function centre_free(problem) result(options)
        type(problem_type), intent(in) :: problem
        type(ic_options_type) :: options

        options = ic_options_of(problem)
        options%exact_q = [.true., .true., .false., .true., .true., .true.]
        options%exact_u = [.false., .false., .false., .true., .true., .true.]
    end function centre_free

    !> Z 1e-3 m high and the centre velocity 1e-2 m/s off along X and Y: the exact start back
    !> to 1e-12, and the report names Z_2, Xdot_2, Ydot_2 with old, new and unit.
    subroutine test_perturbed_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        real(wp) :: q(6), u(6), q_exact(6), u_exact(6)
        character(len=:), allocatable :: text

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q_exact, u_exact)
        q = q_exact + [0.0_wp, 0.0_wp, 1.0e-3_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        u = u_exact + [1.0e-2_wp, 1.0e-2_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        call analyse_initial_conditions(problem, 0.0_wp, q, u, centre_free(problem), report, &
            & error)
        if (allocated(error)) return
        call check(error, q, q_exact, "coordinates", abs_tol=tol_recovered)
        if (allocated(error)) return
        call check(error, u, u_exact, "rates", abs_tol=tol_recovered)
        if (allocated(error)) return
        call check(error, size(report%changes) == 3, "three values moved, got " &
            & // to_text(size(report%changes)))
        if (allocated(error)) return
        call check(error, report%changes(1)%name() == "Z_2" .and. report%changes(2)%name() &
            & == "Xdot_2" .and. report%changes(3)%name() == "Ydot_2", "names " &
            & // report%changes(1)%name() // " " // report%changes(2)%name())
        if (allocated(error)) return
        call check(error, report%changes(1)%old, coin_radius + 1.0e-3_wp, "old Z", abs_tol=0.0_wp)
        if (allocated(error)) return
        call check(error, report%changes(2)%new, 0.1_wp, "new Xdot", abs_tol=tol_recovered)
        if (allocated(error)) return
        call check(error, report%newton_iterations == 1 .and. report%velocity_steps == 1, &
            & "one Newton iteration and one velocity step, got " &
            & // to_text(report%newton_iterations) // " and " // to_text(report%velocity_steps))
        if (allocated(error)) return
        text = ic_report_text(report)
        call check(error, index(text, "part 2: Z_2 0.101 m -> 0.1") > 0 .and. index(text, &
            & "part 2: Xdot_2 0.11 m/s -> 0.1") > 0 .and. index(text, "(by -0.01") > 0, text)
    end subroutine test_perturbed_coin

    !> The exact start meets every UCON: nothing moves, bit for bit, and the text says so.
    subroutine test_consistent_start(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        real(wp) :: q(6), u(6), q_exact(6), u_exact(6)

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q_exact, u_exact)
        q = q_exact
        u = u_exact
        call analyse_initial_conditions(problem, 0.0_wp, q, u, ic_options_of(problem), report, &
            & error)
        if (allocated(error)) return
        call check(error, all(q == q_exact) .and. all(u == u_exact) .and. size(report%changes) &
            & == 0 .and. report%newton_iterations == 0 .and. report%velocity_steps == 0, &
            & "untouched")
        if (allocated(error)) return
        call check(error, index(ic_report_text(report), "nothing moved") > 0, &
            & ic_report_text(report))
    end subroutine test_consistent_start

    !> Xdot 1e-2 m/s off, nothing exact: F1 = Xdot + R phidot (upright, psi = 0) is met by the
    !> least change of (Xdot, rho phidot), the documented weights: Xdot moves by
    !> -F/(1 + R^2/rho^2) and phidot by -F (R/rho^2)/(1 + R^2/rho^2); nothing else moves.
    subroutine test_weights(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        real(wp) :: q(6), u(6), q_exact(6), u_exact(6), expected(6), f, ratio

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q_exact, u_exact)
        q = q_exact
        f = 1.0e-2_wp
        u = u_exact + [f, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        call analyse_initial_conditions(problem, 0.0_wp, q, u, ic_options_of(problem), report, &
            & error)
        if (allocated(error)) return
        ratio = coin_radius**2/coin_rho()**2
        expected = u_exact + [f - f/(1.0_wp + ratio), 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
            & -f*(coin_radius/coin_rho()**2)/(1.0_wp + ratio)]
        call check(error, u, expected, "rates", abs_tol=tol_weights)
        if (allocated(error)) return
        call check(error, size(report%changes) == 2, "Xdot and phidot moved, got " &
            & // ic_report_text(report))
    end subroutine test_weights

    !> The same start with phidot held: the whole correction goes to Xdot; with Xdot held
    !> too (and the rest), to phidot: -(Xdot)/R.
    subroutine test_exact_held(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        type(ic_options_type) :: options
        real(wp) :: q(6), u(6), q_exact(6), u_exact(6)

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q_exact, u_exact)
        q = q_exact
        u = u_exact + [1.0e-2_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        options = ic_options_of(problem)
        options%exact_u(6) = .true.
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, error)
        if (allocated(error)) return
        call check(error, u, u_exact, "phidot held: Xdot back to 0.1 m/s", &
            & abs_tol=tol_recovered)
        if (allocated(error)) return
        u = u_exact + [1.0e-2_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
        options%exact_u = [.true., .true., .true., .true., .true., .false.]
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, error)
        if (allocated(error)) return
        call check(error, u, [0.11_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -1.1_wp], &
            & "Xdot held: phidot = -Xdot/R", abs_tol=tol_recovered)
        if (allocated(error)) return
        call check(error, q, q_exact, "positions untouched", abs_tol=0.0_wp)
    end subroutine test_exact_held

    !> Run the analysis on the coin's start (it must not refuse), then the run's choice of the
    !> rows to set aside there; its words (problem_type's set_aside_text).
    subroutine set_aside_of(kinds, parameters, q, words, error)
        integer, intent(in) :: kinds(:)
        real(wp), intent(in) :: parameters(:)
        !> Start coordinates (the exact rates are used)
        real(wp), intent(in) :: q(6)
        character(len=:), allocatable, intent(out) :: words
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        real(wp) :: q_start(6), u(6), q_exact(6)

        call coin_problem(kinds, parameters, problem, error)
        if (allocated(error)) return
        call coin_start(q_exact, u)
        q_start = q
        call analyse_initial_conditions(problem, 0.0_wp, q_start, u, ic_options_of(problem), &
            & report, error)
        if (allocated(error)) return
        call problem%choose_rows(0.0_wp, q_start, u, error)
        if (allocated(error)) return
        words = problem%set_aside_text
    end subroutine set_aside_of

    !> Run the analysis on the coin's exact start and return its refusal (a test error if none).
    subroutine refusal_of(kinds, parameters, q, message, error)
        integer, intent(in) :: kinds(:)
        real(wp), intent(in) :: parameters(:)
        !> Start coordinates (the exact rates are used)
        real(wp), intent(in) :: q(6)
        character(len=:), allocatable, intent(out) :: message
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        type(error_type), allocatable :: refused
        real(wp) :: q_start(6), u(6), q_exact(6)

        call coin_problem(kinds, parameters, problem, error)
        if (allocated(error)) return
        call coin_start(q_exact, u)
        q_start = q
        call analyse_initial_conditions(problem, 0.0_wp, q_start, u, ic_options_of(problem), &
            & report, refused)
        call check(error, allocated(refused), "not refused")
        if (allocated(error)) return
        message = refused%message
    end subroutine refusal_of

    !> F3 under two ids (UCON/3 and UCON/4): redundant at velocity level and met, so not
    !> refused; the run's choice (rollcon_redundancy) keeps the first and sets the second
    !> aside, naming both.
    subroutine test_f3_twice(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: words
        real(wp) :: q(6), u(6)

        call coin_start(q, u)
        call set_aside_of([ucon_noslip, ucon_noslip, ucon_noslip, ucon_noslip], [1.0_wp, &
            & 2.0_wp, 3.0_wp, 3.0_wp], q, words, error)
        if (allocated(error)) return
        call check(error, words == "UCON/4 repeats UCON/3; set aside", words)
    end subroutine test_f3_twice

    !> The height (UCON/4, a position UCON) beside the velocity F3 (UCON/3), its time
    !> derivative: redundant at velocity level, not refused; the position UCON is kept (it also
    !> holds the height, which F3 cannot) and F3 set aside, UCON/1 and UCON/2 not named.
    subroutine test_height_and_f3(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: words
        real(wp) :: q(6), u(6)

        call coin_start(q, u)
        call set_aside_of([ucon_noslip, ucon_noslip, ucon_noslip, ucon_height], [1.0_wp, &
            & 2.0_wp, 3.0_wp, coin_radius], q, words, error)
        if (allocated(error)) return
        call check(error, words == "UCON/3 repeats UCON/4; set aside", words)
    end subroutine test_height_and_f3

    !> Two heights with radii 0.1 m and 0.2 m: no Z meets both; contradictory at position
    !> level, both named with their least-squares residuals, +-0.05 m.
    subroutine test_contradictory_heights(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: message
        real(wp) :: q(6), u(6)

        call coin_start(q, u)
        call refusal_of([ucon_noslip, ucon_noslip, ucon_height, ucon_height], [1.0_wp, 2.0_wp, &
            & coin_radius, 2.0_wp*coin_radius], q, message, error)
        if (allocated(error)) return
        call check(error, index(message, "initial conditions: UCON/3 and UCON/4 are " &
            & // "contradictory at position level: their rows are linearly dependent (rank 1 " &
            & // "of 2 over the values not marked exact) and no position meets them all; " &
            & // "least-squares residuals after") == 1, message)
        if (allocated(error)) return
        ! the least-squares Z is 0.15 m, 0.05 m from both heights
        call check(error, [number_after(message, "UCON/3 |F| = "), number_after(message, &
            & "UCON/4 |F| = ")], [0.05_wp, 0.05_wp], message, abs_tol=tol_recovered)
    end subroutine test_contradictory_heights

    !> The height with Z held at 0.15 m > R and theta free: no theta has R sin(theta) = 0.15;
    !> Gauss-Newton runs its 25 iterations and the refusal names UCON/3 with |F| >= 0.05 m.
    subroutine test_no_convergence(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        type(ic_options_type) :: options
        type(error_type), allocatable :: refused
        real(wp) :: q(6), u(6)

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q, u)
        q(3) = 0.15_wp
        q(5) = 1.0_wp
        options = ic_options_of(problem)
        options%exact_q(3) = .true.
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, refused)
        call check(error, allocated(refused), "not refused")
        if (allocated(error)) return
        call check(error, index(refused%message, "initial conditions: the position UCONs are " &
            & // "not met after 25 step(s) (no convergence): UCON/3 |F| = ") == 1, &
            & refused%message)
        if (allocated(error)) return
        ! R sin(theta) <= R: |F| >= 0.15 - 0.1 m whatever theta the iterations reached
        call check(error, number_after(refused%message, "UCON/3 |F| = ") >= 0.05_wp, &
            & refused%message)
        if (allocated(error)) return
        call check(error, q(3) == 0.15_wp .and. q(5) == 1.0_wp, "start left as given")
    end subroutine test_no_convergence

    !> The height with Z and theta both held and Z off: nothing free is left to meet it.
    subroutine test_held_ucon_unmet(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        type(ic_options_type) :: options
        type(error_type), allocatable :: refused
        real(wp) :: q(6), u(6)

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q, u)
        q(3) = 0.11_wp
        options = ic_options_of(problem)
        options%exact_q(3) = .true.
        options%exact_q(5) = .true.
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, refused)
        call check(error, allocated(refused), "not refused")
        if (allocated(error)) return
        call check(error, index(refused%message, "initial conditions: UCON/3 cannot be met at " &
            & // "position level with the values marked exact held") == 1, refused%message)
    end subroutine test_held_ucon_unmet

    !> Z held at R/2, theta free from 1.5 rad, where dF/dtheta = -R cos(theta) is small: the
    !> full Newton step (-7 rad) would land on another branch (theta = pi/6 - 2 pi); steps of
    !> at most 30 degrees reach the branch in (0, pi) below the start, theta = pi/6.
    subroutine test_angle_limit(error)
        type(error_type), allocatable, intent(out) :: error
        !> |F| <= 0.01 (atol + rtol s) ~ 1.1e-11 m at convergence (s ~ 0.095 m) bounds the
        !> error of theta by 1.1e-11/(R cos(pi/6)) ~ 1.3e-10 rad; 1e-9 rad is above that
        real(wp), parameter :: tol_theta = 1.0e-9_wp
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        type(ic_options_type) :: options
        real(wp) :: q(6), u(6)

        call height_coin(problem, error)
        if (allocated(error)) return
        call coin_start(q, u)
        q(3) = 0.5_wp*coin_radius
        q(5) = 1.5_wp
        u = 0.0_wp
        options = ic_options_of(problem)
        options%exact_q(3) = .true.
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, error)
        if (allocated(error)) return
        call check(error, q(5), asin(0.5_wp), "theta", abs_tol=tol_theta)
        if (allocated(error)) return
        call check(error, report%newton_iterations > 2, "steps limited: " &
            & // to_text(report%newton_iterations) // " iterations")
    end subroutine test_angle_limit

    !> The number written after `key` in `text` (NaN when there is none).
    function number_after(text, key) result(value)
        character(len=*), intent(in) :: text, key
        real(wp) :: value
        integer :: start, finish, stat

        value = ieee_value(value, ieee_quiet_nan)
        start = index(text, key)
        if (start == 0) return
        start = start + len(key)
        finish = start + scan(text(start:) // " ", " ,)") - 2
        read(text(start:finish), *, iostat=stat) value
        if (stat /= 0) value = ieee_value(value, ieee_quiet_nan)
    end function number_after

end module test_initial_conditions
