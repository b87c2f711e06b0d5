! SPDX-License-Identifier: MIT
!> The linear analysis on the constraint manifold (rollcon_linearisation, docs/linear.md):
!> the upright rolling disk's critical speed and eigenvalues against the linearised disk's
!> closed form, the reduced matrix against the analytic ODE Jacobian, the invariance of the
!> tangent space, independence of Baumgarte terms and of the integrator the dataset chooses,
!> the refusals (a start off the constraints, a singular constraint Jacobian), and a user's
!> file linearised in a child process as the built-in routine is here.
!>
!> The linearised upright disk (docs/linear.md): rolling straight at speed v, spin W = v/R,
!> the tilt e from upright and the heading psi obey (A + m R^2) e'' = m g R e - (C + m R^2) W psi'
!> and A psi'' = C W e', so the tilt, its rate and the heading rate have the characteristic
!> polynomial lambda (lambda^2 - s) with s = (m g R A - C (C + m R^2) W^2)/(A (A + m R^2)); every
!> other independent coordinate is cyclic or the forward speed: zero eigenvalues. s changes
!> sign at v_c^2 = m g R^3 A / (C (C + m R^2)) (docs/design.md §5).
module test_linearisation
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise
    use rollcon_linear_report, only : damping_ratio, natural_frequency, linear_table_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job, input_override_type
    use rollcon_linear_job, only : linearise_job
    use ic_models, only : coin_problem, coin_start, ucon_noslip, ucon_height, coin_radius
    use rollcon_testing, only : unittest_type, new_unittest, check
    use override_lists, only : add_override
    implicit none
    private

    public :: collect_linearisation

    !> data/coin.adm's disk: mass [kg], moments about a diameter and the axis [kg m^2],
    !> radius [m], gravity [m/s^2]
    real(wp), parameter :: mass = 0.73513268094001172_wp, inertia_a = 1.8383830518607345e-3_wp, &
        & inertia_c = 3.6756634047000595e-3_wp, radius = 0.1_wp, gravity = 9.81_wp
    !> The task's demand on the critical speed. The secant below works on s(v^2), which is
    !> linear in v^2, from speeds where |s| ~ 10..100 1/s^2 and each s carries the differences'
    !> error (~1e-12 relative, docs/linear.md): measured 3e-12 relative on both datasets
    real(wp), parameter :: tol_critical = 1.0e-8_wp
    !> Eigenvalues against the closed form: the differences' error, measured 1.5e-13 (2 m/s)
    !> and 2.3e-12 (0.3 m/s) relative; 1e-9 leaves room for other speeds and machines, and is
    !> far below the 1e-6 the benchmark bicycle needs. Also the Baumgarte terms' effect
    !> (measured 1.4e-11 of the largest eigenvalue: differences of other terms' rounding)
    real(wp), parameter :: tol_eigen = 1.0e-9_wp
    !> The reduced matrix against the analytic ODE Jacobian (exact for velocity UCONs without
    !> applied moments, docs/design.md §4): measured 8e-14 of its largest entry
    real(wp), parameter :: tol_matrix = 1.0e-9_wp
    !> The zero eigenvalues of the upright disk: a defective zero (the heading rate's mode
    !> drives the heading, a Jordan chain) is spread by the square root of the differences'
    !> error, measured 1e-8 of the wobble at 2 m/s; 1e-7 of it still tells zero from a mode
    real(wp), parameter :: tol_zero = 1.0e-7_wp
    !> A steady motion's invariance rest: measured 5e-13 and 2e-12 (the differences' rounding)
    real(wp), parameter :: tol_invariance = 1.0e-9_wp

contains

    subroutine collect_linearisation(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("critical-speed-coin", test_critical_coin), &
            & new_unittest("critical-speed-position-height", test_critical_height), &
            & new_unittest("upright-eigenvalues-closed-form", test_closed_form), &
            & new_unittest("reduced-matrix-analytic", test_reduced_matrix), &
            & new_unittest("baumgarte-and-integrator-free", test_settings_free), &
            & new_unittest("not-steady-reported", test_not_steady), &
            & new_unittest("start-off-constraints", test_off_constraints), &
            & new_unittest("singular-constraint-jacobian", test_singular), &
            & new_unittest("user-file-linearised-apart", test_user_file), &
            & new_unittest("zeros-by-structure-absolute", test_structural_zeros)]
    end subroutine collect_linearisation

    !> s (the wobble's lambda^2) of the upright disk [1/s^2] from the closed form.
    pure real(wp) function wobble_square(speed)
        real(wp), intent(in) :: speed

        associate (m => mass, a => inertia_a, c => inertia_c, r => radius)
            wobble_square = (m*gravity*r*a - c*(c + m*r**2)*(speed/r)**2)/(a*(a + m*r**2))
        end associate
    end function wobble_square

    !> The dataset at path rolling upright at speed [m/s] (part%2%vx, and part%2%wz = -v/R),
    !> with more overrides when given, linearised through the job.
    subroutine disk_at_speed(path, speed, result, error, options, more)
        character(len=*), intent(in) :: path
        real(wp), intent(in) :: speed
        type(linear_result_type), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error
        type(linear_options_type), intent(in), optional :: options
        type(input_override_type), intent(in), optional :: more(:)
        type(input_override_type), allocatable :: set(:)
        type(job_type) :: job
        character(len=:), allocatable :: report
        integer :: k

        call add_override(set, "part%2%vx", to_text(speed))
        call add_override(set, "part%2%wz", to_text(-speed/radius))
        if (present(more)) then
            do k = 1, size(more)
                call add_override(set, more(k)%name, more(k)%value)
            end do
        end if
        call load_job(path, job, error, overrides=set)
        if (allocated(error)) return
        call linearise_job(job, result, report, error, options)
    end subroutine disk_at_speed

    !> error set unless refused holds a message starting with expected.
    subroutine expect_refusal(refused, expected, error)
        type(error_type), allocatable, intent(in) :: refused
        character(len=*), intent(in) :: expected
        type(error_type), allocatable, intent(out) :: error

        if (.not. allocated(refused)) then
            call check(error, .false., "not refused; expected: " // expected)
        else
            call check(error, index(refused%message, expected) == 1, "refused with '" &
                & // refused%message // "'; expected it to start with '" // expected // "'")
        end if
    end subroutine expect_refusal

    !> The wobble's lambda^2 as the analysis finds it: that of the eigenvalue of largest
    !> modulus, Re(lambda^2) = re^2 - im^2 (s > 0: a real pair +-sqrt(s); s < 0: +-i sqrt(-s)).
    pure real(wp) function found_square(result)
        type(linear_result_type), intent(in) :: result
        integer :: k

        k = maxloc(hypot(result%real_part, result%imag_part), 1)
        found_square = result%real_part(k)**2 - result%imag_part(k)**2
    end function found_square

    !> The speed where the analysis's wobble lambda^2 changes sign, by the secant method on
    !> v^2 from 0.5 and 0.65 m/s (either side of v_c = 0.572 m/s), until the step is below
    !> 1e-14 of v^2.
    subroutine critical_speed(path, speed, error)
        character(len=*), intent(in) :: path
        real(wp), intent(out) :: speed
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: result
        real(wp) :: x0, x1, x2, s0, s1
        integer :: iteration

        x0 = 0.5_wp**2
        x1 = 0.65_wp**2
        call disk_at_speed(path, sqrt(x0), result, error)
        if (allocated(error)) return
        s0 = found_square(result)
        call disk_at_speed(path, sqrt(x1), result, error)
        if (allocated(error)) return
        s1 = found_square(result)
        call check(error, s0 > 0.0_wp .and. s1 < 0.0_wp, "the wobble's lambda^2 does not " &
            & // "change sign between 0.5 and 0.65 m/s: " // to_text(s0) // ", " // to_text(s1))
        if (allocated(error)) return
        do iteration = 1, 20
            x2 = x1 - s1*(x1 - x0)/(s1 - s0)
            if (abs(x2 - x1) <= 1.0e-14_wp*x1) exit
            x0 = x1
            s0 = s1
            x1 = x2
            call disk_at_speed(path, sqrt(x1), result, error)
            if (allocated(error)) return
            s1 = found_square(result)
            if (s1 == s0) exit
        end do
        speed = sqrt(x2)
    end subroutine critical_speed

    !> data/coin.adm (velocity-level height): the stability changes at v_c.
    subroutine test_critical_coin(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: speed, expected

        call critical_speed("data/coin.adm", speed, error)
        if (allocated(error)) return
        expected = sqrt(mass*gravity*radius**3*inertia_a/(inertia_c*(inertia_c &
            & + mass*radius**2)))
        call check(error, speed, expected, "critical speed of data/coin.adm [m/s]", &
            & rel_tol=tol_critical)
    end subroutine test_critical_coin

    !> data/disk_height.adm (the height a position UCON): the same critical speed.
    subroutine test_critical_height(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: speed, expected

        call critical_speed("data/disk_height.adm", speed, error)
        if (allocated(error)) return
        expected = sqrt(mass*gravity*radius**3*inertia_a/(inertia_c*(inertia_c &
            & + mass*radius**2)))
        call check(error, speed, expected, "critical speed of data/disk_height.adm [m/s]", &
            & rel_tol=tol_critical)
    end subroutine test_critical_height

    !> At 2 m/s (stable: +-i sqrt(-s)) and 0.3 m/s (unstable: +-sqrt(s)) the two non-zero
    !> eigenvalues are the closed form's; the others are zero: 7 of 9 (coin: 12 states less 3
    !> velocity rows), 6 of 8 with the position height (less 4 rows); the tangent space is
    !> invariant.
    subroutine test_closed_form(error)
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: result
        character(len=*), parameter :: paths(2) = ["data/coin.adm       ", "data/disk_height.adm"]
        real(wp), parameter :: speeds(2) = [2.0_wp, 0.3_wp]
        integer, parameter :: states(2) = [9, 8]
        real(wp) :: s, root
        real(wp), allocatable :: re(:), im(:)
        integer :: i, j

        do i = 1, size(paths)
            do j = 1, size(speeds)
                call disk_at_speed(trim(paths(i)), speeds(j), result, error)
                if (allocated(error)) return
                s = wobble_square(speeds(j))
                root = sqrt(abs(s))
                ! the two eigenvalues that are not zero, in the result's order
                re = pack(result%real_part, hypot(result%real_part, result%imag_part) &
                    & > result%zero_limit)
                im = pack(result%imag_part, hypot(result%real_part, result%imag_part) &
                    & > result%zero_limit)
                associate (what => trim(paths(i)) // " at " // to_text(speeds(j)) // " m/s: ")
                    call check(error, result%reduced == states(i) .and. result%zeros &
                        & == states(i) - 2 .and. size(re) == 2, what // to_text(result%reduced) &
                        & // " states, " // to_text(result%zeros) // " zero eigenvalues")
                    if (allocated(error)) return
                    if (s < 0.0_wp) then
                        ! sorted: equal real parts (rounding), +i before -i
                        call check(error, im(1), root, what // "wobble frequency [rad/s]", &
                            & rel_tol=tol_eigen)
                        if (.not. allocated(error)) call check(error, im(2), -root, what &
                            & // "its conjugate [rad/s]", rel_tol=tol_eigen)
                        if (.not. allocated(error)) call check(error, maxval(abs(re)), 0.0_wp, &
                            & what // "the wobble's real part [1/s]", abs_tol=tol_eigen*root)
                    else
                        call check(error, re(1), root, what // "growth rate [1/s]", &
                            & rel_tol=tol_eigen)
                        if (.not. allocated(error)) call check(error, re(2), -root, &
                            & what // "decay rate [1/s]", rel_tol=tol_eigen)
                        if (.not. allocated(error)) call check(error, maxval(abs(im)), 0.0_wp, &
                            & what // "largest imaginary part [1/s]", abs_tol=tol_eigen*root)
                        if (.not. allocated(error)) call check(error, damping_ratio(re(1), &
                            & im(1)), -1.0_wp, what // "damping ratio of the growing mode", &
                            & rel_tol=tol_eigen)
                    end if
                    if (.not. allocated(error)) call check(error, natural_frequency(re(1), &
                        & im(1)), root/(2.0_wp*acos(-1.0_wp)), what // "natural frequency " &
                        & // "[Hz]", rel_tol=tol_eigen)
                    if (.not. allocated(error)) call check(error, result%invariant .and. &
                        & result%invariance <= tol_invariance, what // "invariance rest " &
                        & // to_text(result%invariance))
                    if (.not. allocated(error)) call check(error, maxval(hypot( &
                        & result%real_part, result%imag_part), hypot(result%real_part, &
                        & result%imag_part) <= result%zero_limit), 0.0_wp, what &
                        & // "largest zero eigenvalue [1/s]", abs_tol=tol_zero*root)
                end associate
                if (allocated(error)) return
            end do
        end do
    end subroutine test_closed_form

    !> The reduced matrix equals the analytic ODE Jacobian (rollcon_equations, from the
    !> UCOSUB's second partials) restricted to the tangent space, (J T) in the independent
    !> rows; and the analytic J T has no part outside the tangent space either.
    subroutine test_reduced_matrix(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(problem_type), target :: problem
        type(linear_result_type) :: result
        type(linear_options_type) :: options
        type(input_override_type), allocatable :: set(:)
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:), jac(:, :), jt(:, :)
        character(len=:), allocatable :: report
        real(wp) :: largest

        call add_override(set, "part%2%vx", "1.3")
        call add_override(set, "part%2%wz", "-13")
        call load_job("data/coin.adm", job, error, overrides=set)
        if (allocated(error)) return
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call linearise(problem, 0.0_wp, q0, u0, options, result, error)
        if (allocated(error)) return
        allocate(jac(2*size(q0), 2*size(q0)))
        call problem%eq%ode_jacobian(0.0_wp, q0, u0, 0.0_wp, jac, error)
        if (allocated(error)) return
        jt = matmul(jac, result%basis)
        largest = maxval(abs(jt))
        call check(error, maxval(abs(result%reduced_matrix - jt(result%independent, :))), &
            & 0.0_wp, "reduced matrix against the analytic Jacobian (largest entry " &
            & // to_text(largest) // ")", abs_tol=tol_matrix*largest)
        if (allocated(error)) return
        call check(error, maxval(abs(jt - matmul(result%basis, jt(result%independent, :)))), &
            & 0.0_wp, "analytic J T outside the tangent space", abs_tol=tol_matrix*largest)
    end subroutine test_reduced_matrix

    !> The eigenvalues do not depend on Baumgarte terms (they vanish on the manifold) nor on
    !> the integrator the dataset chooses (CVODE Adams with Baumgarte drift control against
    !> IDA): equal to tol_eigen of the largest.
    subroutine test_settings_free(error)
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: plain, stabilised, cvode
        type(linear_options_type) :: options
        type(input_override_type), allocatable :: more(:)
        real(wp) :: largest

        call disk_at_speed("data/disk_height.adm", 1.0_wp, plain, error)
        if (allocated(error)) return
        options%baumgarte = 25.0_wp
        call disk_at_speed("data/disk_height.adm", 1.0_wp, stabilised, error, options)
        if (allocated(error)) return
        call add_override(more, "integrator%formulation", "CVODE")
        call add_override(more, "integrator%method", "ADAMS")
        call add_override(more, "integrator%drift", "BAUMGARTE")
        call disk_at_speed("data/disk_height.adm", 1.0_wp, cvode, error, more=more)
        if (allocated(error)) return
        largest = maxval(hypot(plain%real_part, plain%imag_part))
        call check(error, stabilised%zeros == plain%zeros .and. cvode%zeros == plain%zeros &
            & .and. plain%zeros == 6, "zero eigenvalues: " // to_text(plain%zeros) // ", " &
            & // to_text(stabilised%zeros) // " with Baumgarte terms, " // to_text(cvode%zeros) &
            & // " with CVODE")
        if (allocated(error)) return
        call check(error, largest_difference(stabilised, plain), 0.0_wp, &
            & "eigenvalues with Baumgarte rate 25 1/s against none [1/s]", &
            & abs_tol=tol_eigen*largest)
        if (allocated(error)) return
        call check(error, largest_difference(cvode, plain), 0.0_wp, &
            & "eigenvalues of the dataset with CVODE and Baumgarte against IDA [1/s]", &
            & abs_tol=tol_eigen*largest)
    end subroutine test_settings_free

    !> The largest difference between the eigenvalues that are not zero of two results of
    !> the same model, in their order [1/s] (huge when they are not as many).
    pure real(wp) function largest_difference(one, other)
        type(linear_result_type), intent(in) :: one, other
        real(wp), allocatable :: re1(:), im1(:), re2(:), im2(:)

        re1 = pack(one%real_part, hypot(one%real_part, one%imag_part) > one%zero_limit)
        im1 = pack(one%imag_part, hypot(one%real_part, one%imag_part) > one%zero_limit)
        re2 = pack(other%real_part, hypot(other%real_part, other%imag_part) > other%zero_limit)
        im2 = pack(other%imag_part, hypot(other%real_part, other%imag_part) > other%zero_limit)
        largest_difference = huge(1.0_wp)
        if (size(re1) == size(re2) .and. size(re1) > 0) largest_difference = &
            & maxval(abs(re1 - re2) + abs(im1 - im2))
    end function largest_difference

    !> A start that is no steady motion (the coin rolling upright while it turns: psidot
    !> 1 rad/s, so its lean must change) is reported: the tangent space is not invariant.
    subroutine test_not_steady(error)
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: result
        type(input_override_type), allocatable :: more(:)

        call add_override(more, "part%2%wy", "1")
        call disk_at_speed("data/coin.adm", 1.0_wp, result, error, more=more)
        if (allocated(error)) return
        call check(error, .not. result%invariant .and. result%invariance > 1.0e-3_wp, &
            & "invariance rest " // to_text(result%invariance) // " of a turning upright coin")
    end subroutine test_not_steady

    !> A start 1 mm/s off F1 is refused, naming the UCON.
    subroutine test_off_constraints(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(linear_result_type) :: result
        type(linear_options_type) :: options
        type(error_type), allocatable :: refused
        real(wp) :: q(6), u(6)

        call coin_problem([ucon_noslip, ucon_noslip, ucon_noslip], [1.0_wp, 2.0_wp, 3.0_wp], &
            & problem, error)
        if (allocated(error)) return
        call coin_start(q, u)
        u(1) = u(1) + 1.0e-3_wp
        call linearise(problem, 0.0_wp, q, u, options, result, refused)
        call expect_refusal(refused, "linearisation: the start is off the constraints: UCON/1 " &
            & // "F = ", error)
    end subroutine test_off_constraints

    !> F3 given twice (velocity rows) and the height given twice (position rows) are refused
    !> as a singular constraint Jacobian, naming the UCONs of the level.
    subroutine test_singular(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: twice_f3, twice_height
        type(linear_result_type) :: result
        type(linear_options_type) :: options
        type(error_type), allocatable :: refused
        real(wp) :: q(6), u(6)

        call coin_start(q, u)
        call coin_problem([ucon_noslip, ucon_noslip, ucon_noslip, ucon_noslip], [1.0_wp, &
            & 2.0_wp, 3.0_wp, 3.0_wp], twice_f3, error)
        if (allocated(error)) return
        call linearise(twice_f3, 0.0_wp, q, u, options, result, refused)
        call expect_refusal(refused, "linearisation: the constraints' Jacobian is singular at " &
            & // "the start: the velocity rows of UCON/1, UCON/2, UCON/3 and UCON/4 are " &
            & // "dependent", &
            & error)
        if (allocated(error)) return
        call coin_problem([ucon_noslip, ucon_noslip, ucon_height, ucon_height], [1.0_wp, &
            & 2.0_wp, coin_radius, coin_radius], twice_height, error)
        if (allocated(error)) return
        call linearise(twice_height, 0.0_wp, q, u, options, result, refused)
        call expect_refusal(refused, "linearisation: the constraints' Jacobian is singular at " &
            & // "the start: the position rows of UCON/3 and UCON/4 are dependent", error)
    end subroutine test_singular

    !> A turntable on a REVOLUTE (test/linear/turntable_revolute.adm): both eigenvalues are zero
    !> by structure, computed as +-4.5e-16 1/s. With every eigenvalue that small, 1e-6 of the
    !> largest is no limit at all: the limit's absolute part, 1e-6 of the model's frequency
    !> scale (sqrt(g/rho) = 7 1/s here), counts both as zeros, and the table prints no growing
    !> mode (no damping ratio of -1). A model with eigenvalues of its own keeps them (the other
    !> tests of the suite).
    subroutine test_structural_zeros(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(linear_result_type) :: result
        character(len=:), allocatable :: report, table

        call load_job("test/linear/turntable_revolute.adm", job, error)
        if (allocated(error)) return
        call linearise_job(job, result, report, error)
        if (allocated(error)) return
        table = linear_table_text(result, "turntable")
        call check(error, result%reduced == 2 .and. result%zeros == 2 .and. &
            & index(table, "-1.0000000") == 0, "zeros " // to_text(result%zeros) // " of " &
            & // to_text(result%reduced) // " (limit " // to_text(result%zero_limit) &
            & // " 1/s): " // table)
        if (allocated(error)) return
        ! the limit stays far below the model's own frequencies: 1e-6 of sqrt(g/rho), rho =
        ! sqrt(0.4/10) m
        call check(error, result%zero_limit, 1.0e-6_wp*sqrt(9.81_wp/0.2_wp), "zero limit [1/s]", &
            & rel_tol=1.0e-12_wp)
    end subroutine test_structural_zeros

    !> A user's file serving the UCONs (the generated rolling disk, ucon/adams/rolling_disk/
    !> ucosub.f) is linearised through the library's linearise_job in a child process: the
    !> same independent coordinates as the hand-checked disk built in, and its eigenvalues to
    !> 1e-10 of the largest (one constraint written apart: their partials differ by rounding,
    !> which the differences of relative step 2e-3 raise to about 1e-13; the linearisation's own
    !> error is about 1e-10, docs/linear.md), the invariance as small.
    subroutine test_user_file(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(linear_result_type) :: built_in, apart
        character(len=:), allocatable :: report

        call load_job("data/coin.adm", job, error)
        if (allocated(error)) return
        call linearise_job(job, built_in, report, error)
        if (allocated(error)) return
        call load_job("data/coin.adm", job, error, ucosub="ucon/adams/rolling_disk/ucosub.f")
        if (allocated(error)) return
        job%quiet = .true.
        call linearise_job(job, apart, report, error)
        if (allocated(error)) return
        call check(error, apart%reduced == built_in%reduced .and. size(apart%independent) &
            & == size(built_in%independent) .and. apart%invariant, "reduced " &
            & // to_text(apart%reduced) // " (built in: " // to_text(built_in%reduced) // ")")
        if (allocated(error)) return
        call check(error, all(apart%independent == built_in%independent), "the independent " &
            & // "coordinates differ")
        if (allocated(error)) return
        call check(error, maxval(abs(apart%real_part - built_in%real_part) &
            & + abs(apart%imag_part - built_in%imag_part)), 0.0_wp, "eigenvalues apart " &
            & // "against built in [1/s]", abs_tol=1.0e-10_wp*maxval(hypot(built_in%real_part, &
            & built_in%imag_part)))
    end subroutine test_user_file

end module test_linearisation
