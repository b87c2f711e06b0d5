! SPDX-License-Identifier: MIT
!> The example models of data/ against their textbook results, each on CVODE and IDA: the ball
!> on a turntable (its centre circles at 2/7 of the table's rate, for 20 turns and for 10
!> minutes), the Chaplygin sled (closed-form speed and turning rate from a near-sideways start),
!> and, in model_disks, the disk on a turntable and the coin with the holonomic height.
module test_models
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use model_runs, only : run_model, model_run_type, formulation_cvode, formulation_ida
    use model_disks, only : test_turntable_disk_ida, test_turntable_disk_cvode, &
        & test_disk_height_ida, test_disk_height_cvode
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_rebasing, only : turn_about_x
    implicit none
    private

    public :: collect_models

    !> data/ball_on_turntable.adm: table rate [rad/s], orbit radius [m] (the orbit is centred on
    !> the table's axis, the origin)
    real(wp), parameter :: table_rate = 3.5_wp, orbit_radius = 0.1_wp
    !> 20 turns and 10 minutes of turntable time [s]
    real(wp), parameter :: twenty_turns = 20.0_wp*2.0_wp*pi*7.0_wp/(2.0_wp*table_rate)
    real(wp), parameter :: ten_minutes = 600.0_wp
    !> The orbit's phase against (2/7) Omega t, relative to the angle travelled: the issue's
    !> 1e-6. Measured: 2.8e-9 (IDA at the dataset's ERROR = 1e-10; 1.6e-7 at IDA's default
    !> Newton coefficient, docs/design.md §7), 1.9e-11 (CVODE, 1e-12).
    !> A ball of another inertia (I/(I + m r^2) = 2/7 is the solid sphere's) misses by orders
    real(wp), parameter :: tol_orbit_rate = 1.0e-6_wp
    !> Orbit centre and radius held [m] over 10 minutes (95 turns of the orbit, 334 of the
    !> table): measured 1.2e-8 m (IDA at the dataset's ERROR = 1e-10, 44,227 steps), 3.1e-8 m
    !> (CVODE at cvode_ball_tolerance) on 0.1 m; 1e-6 m, 1e-5 of the radius
    real(wp), parameter :: tol_orbit_shape = 1.0e-6_wp
    !> CVODE's tolerance for the ball [1]: at 1e-10 its projection keeps the constraints but the
    !> radius shrinks by 1e-6 relative over 20 turns (measured); 1e-12 holds it to 3e-7. The
    !> turning table does work on the ball, so its energy is not judged (constraint_power)
    real(wp), parameter :: cvode_ball_tolerance = 1.0e-12_wp
    !> IDA on the ball over its 20 turns at the dataset's ERROR = 1e-10, against the closed form:
    !> the largest change of the orbit radius |v|/wc relative to the radius, and of the Jacobi
    !> integral E - Omega L_Z relative to itself (conserved: the contact does no work in the
    !> frame turning with the table). Measured 7.4e-8 and 1.5e-8 (9,185 steps); 3.6e-6 and
    !> 7.0e-7 at IDA's default Newton coefficient 0.33 (17,573 steps), 1.2e-8 and 2.3e-9 with the
    !> tilt rate held to atol alone, when the error test fails on 240,866 of 240,903 steps
    !> (docs/design.md §7). Bounds 4 times the measured: a tenfold loss fails
    real(wp), parameter :: tol_ball_radius = 3.0e-7_wp, tol_ball_jacobi = 6.0e-8_wp
    !> IDA's error-test failures per step on the ball [1]: 240,866 in 240,903 steps (every
    !> doubling of the step fails) with its tilt rate, near zero, held to atol alone; measured
    !> 2.7 % (244 in 9,185) with a part's Euler-angle rates held to their angular velocity's
    !> error (rollcon_ida); 5 %
    real(wp), parameter :: tol_failures_per_step = 0.05_wp
    !> IDA's constraint residual on the ball [m/s]: F = 0 within its Newton tolerance, a few
    !> atol (the dataset's 1e-10; measured 1.2e-10); 10 atol
    real(wp), parameter :: tol_ball_residual = 1.0e-9_wp

    !> data/chaplygin_sled.adm: blade offset a [m], initial speed along the blade u0 [m/s],
    !> initial turning rate w0 [rad/s]
    real(wp), parameter :: blade_offset = 0.1_wp, speed_along = -0.01_wp, turning_rate = 5.0_wp
    !> The sled's closed form u = U tanh(k U t + c), w = W sech(k U t + c): the integration
    !> error of ERROR = 1e-10 over 10 s, measured 1.8e-9 m/s and 5.4e-9 rad/s (IDA), 4.8e-9
    !> m/s and 1.0e-8 rad/s (CVODE); 3e-8 in both, so that a tenfold loss of either fails.
    !> A blade at the centre of mass (a = 0) or another inertia misses by orders
    real(wp), parameter :: tol_sled = 3.0e-8_wp
    !> Energy relative drift (no force does work: the blade's reaction is across the motion of
    !> its point, gravity is vertical): measured 3.6e-9 (IDA), 5.5e-9 (CVODE); 2e-8
    real(wp), parameter :: tol_sled_energy = 2.0e-8_wp

contains

    subroutine collect_models(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("ball-orbit-rate-ida", test_ball_rate_ida), &
            & new_unittest("ball-radius-and-jacobi-integral-ida", test_ball_invariants_ida), &
            & new_unittest("ball-orbit-rate-cvode", test_ball_rate_cvode), &
            & new_unittest("ball-ten-minutes-ida", test_ball_long_ida), &
            & new_unittest("ball-ten-minutes-cvode", test_ball_long_cvode), &
            & new_unittest("ball-tumbling-ida", test_ball_tumbling_ida), &
            & new_unittest("ball-ida-error-test-failures", test_ball_failures_ida), &
            & new_unittest("ball-tumbling-cvode", test_ball_tumbling_cvode), &
            & new_unittest("sled-sideways-ida", test_sled_ida), &
            & new_unittest("sled-sideways-cvode", test_sled_cvode), &
            & new_unittest("turntable-disk-steady-ida", test_turntable_disk_ida), &
            & new_unittest("turntable-disk-steady-cvode", test_turntable_disk_cvode), &
            & new_unittest("disk-height-as-velocity-form-ida", test_disk_height_ida), &
            & new_unittest("disk-height-as-velocity-form-cvode", test_disk_height_cvode)]
    end subroutine collect_models

    subroutine test_ball_rate_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ball(formulation_ida, twenty_turns, error)
    end subroutine test_ball_rate_ida

    subroutine test_ball_rate_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ball(formulation_cvode, twenty_turns, error)
    end subroutine test_ball_rate_cvode

    subroutine test_ball_long_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ball(formulation_ida, ten_minutes, error)
    end subroutine test_ball_long_ida

    subroutine test_ball_long_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ball(formulation_cvode, ten_minutes, error)
    end subroutine test_ball_long_cvode

    !> The ball whose axes tumble through the Euler-angle singularity (data/ball_tumbling.adm),
    !> re-based about four times a second: the same orbit as the ball whose axes never do.
    subroutine test_ball_tumbling_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ball(formulation_ida, twenty_turns, error, "ball_tumbling")
    end subroutine test_ball_tumbling_ida

    !> IDA on the ball over its 20 turns (the dataset as given, ERROR = 1e-10): on every row the
    !> orbit radius |v|/wc is the start's and the Jacobi integral E - Omega L_Z (L_Z the angular
    !> momentum about the table's axis, m (X Ydot - Y Xdot) + I (psi' + phi' cos theta) for a
    !> sphere) the start's, to tol_ball_radius and tol_ball_jacobi relative.
    subroutine test_ball_invariants_ida(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_run_type) :: run
        real(wp) :: orbit_rate, radius0, jacobi0, radius_change, jacobi_change
        integer :: i

        call run_model("ball_on_turntable", formulation_ida, run, error)
        if (allocated(error)) return
        orbit_rate = 2.0_wp*table_rate/7.0_wp
        radius_change = 0.0_wp
        jacobi_change = 0.0_wp
        do i = 1, run%history%count
            associate (row => run%history%rows(:, i))
                if (i == 1) then
                    radius0 = hypot(row(8), row(9))/orbit_rate
                    jacobi0 = jacobi(row)
                end if
                radius_change = max(radius_change, abs(hypot(row(8), row(9))/orbit_rate &
                    & - radius0)/radius0)
                jacobi_change = max(jacobi_change, abs(jacobi(row) - jacobi0)/abs(jacobi0))
            end associate
        end do
        call check(error, radius_change <= tol_ball_radius .and. jacobi_change &
            & <= tol_ball_jacobi, "largest relative change of the orbit radius " &
            & // to_text(radius_change) // " (<= " // to_text(tol_ball_radius) // "), of the " &
            & // "Jacobi integral " // to_text(jacobi_change) // " (<= " &
            & // to_text(tol_ball_jacobi) // ")")

    contains

        !> E - Omega L_Z of a row (t, X, Y, Z, psi, theta, phi, their rates, E, ...).
        pure real(wp) function jacobi(row)
            real(wp), intent(in) :: row(:)

            jacobi = row(14) - table_rate*(run%mass*(row(2)*row(9) - row(3)*row(8)) &
                & + run%inertia(1)*(row(11) + row(13)*cos(row(6))))
        end function jacobi
    end subroutine test_ball_invariants_ida

    !> IDA on the ball over its 20 turns (the dataset as given, ERROR = 1e-10): its error test
    !> fails on at most tol_failures_per_step of its steps (the run's own counters, as its
    !> summary prints them), and its constraint residual stays within a few atol.
    subroutine test_ball_failures_ida(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_run_type) :: run

        call run_model("ball_on_turntable", formulation_ida, run, error)
        if (allocated(error)) return
        call check(error, run%summary%steps > 0 .and. real(run%summary%failures, wp) &
            & <= tol_failures_per_step*real(run%summary%steps, wp), "error-test failures " &
            & // to_text(run%summary%failures) // " in " // to_text(run%summary%steps) &
            & // " steps")
        if (allocated(error)) return
        call check(error, run%summary%residual_max <= tol_ball_residual, "largest UCON " &
            & // "residual " // to_text(run%summary%residual_max) // " m/s")
    end subroutine test_ball_failures_ida

    subroutine test_ball_tumbling_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ball(formulation_cvode, twenty_turns, error, "ball_tumbling")
    end subroutine test_ball_tumbling_cvode

    !> The ball to end_time: on every row, the orbit's angle (unwrapped atan2(Y, X)) is
    !> (2/7) Omega t to tol_orbit_rate of the angle travelled by the end, and the orbit's centre
    !> (X - Ydot/wc, Y + Xdot/wc, from v = wc e_Z x (r - c)) and radius |v|/wc are held.
    subroutine check_ball(formulation, end_time, error, dataset)
        integer, intent(in) :: formulation
        real(wp), intent(in) :: end_time
        type(error_type), allocatable, intent(out) :: error
        !> The dataset (default ball_on_turntable); ball_tumbling, every re-basing turned about x
        !> (the rule would re-base it once: docs/rebasing.md), must be re-based > 100 times
        character(len=*), intent(in), optional :: dataset
        type(model_run_type) :: run
        character(len=:), allocatable :: name
        real(wp) :: orbit_rate, angle, previous, turn, phase_error, shape_error
        integer :: i, forced

        name = "ball_on_turntable"
        if (present(dataset)) name = dataset
        forced = 0
        if (name == "ball_tumbling") forced = turn_about_x
        if (formulation == formulation_cvode) then
            call run_model(name, formulation, run, error, end_time, cvode_ball_tolerance, &
                & rebase_turn=forced)
        else
            call run_model(name, formulation, run, error, end_time, rebase_turn=forced)
        end if
        if (allocated(error)) return
        if (name == "ball_tumbling") then
            ! its axes pass the singularity twice per spin turn (12.5 rad/s): ~1000 times
            call check(error, run%summary%rebasings(1) > 100, "re-basings of the tumbling " &
                & // "ball: " // to_text(run%summary%rebasings(1)))
            if (allocated(error)) return
        end if
        ! the turning table does work on the ball through the contact: no energy to judge
        call check(error, .not. run%summary%energy_conserved, "the turntable's UCONs taken " &
            & // "as doing no work")
        if (allocated(error)) return
        ! Omega I / (I + m r^2), I the ball's moment (IP) and r its radius (Z, the centre's height)
        associate (inertia => run%inertia(1), mass => run%mass, radius => run%history%rows(4, 1))
            orbit_rate = table_rate*inertia/(inertia + mass*radius**2)
        end associate
        call check(error, orbit_rate, 2.0_wp*table_rate/7.0_wp, "(2/7) Omega: a solid ball", &
            & rel_tol=1.0e-12_wp)
        if (allocated(error)) return
        turn = 0.0_wp
        previous = 0.0_wp
        phase_error = 0.0_wp
        shape_error = 0.0_wp
        do i = 1, run%history%count
            associate (row => run%history%rows(:, i))
                angle = atan2(row(3), row(2))
                if (angle - previous < -pi) turn = turn + 2.0_wp*pi
                previous = angle
                phase_error = max(phase_error, abs(angle + turn - orbit_rate*row(1)))
                shape_error = max(shape_error, hypot(row(2) - row(9)/orbit_rate, &
                    & row(3) + row(8)/orbit_rate), &
                    & abs(hypot(row(8), row(9))/orbit_rate - orbit_radius), &
                    & abs(hypot(row(2), row(3)) - orbit_radius))
            end associate
        end do
        call check(error, phase_error/(orbit_rate*end_time), 0.0_wp, "largest phase error of " &
            & // "the orbit over the angle travelled", abs_tol=tol_orbit_rate)
        if (allocated(error)) return
        call check(error, shape_error, 0.0_wp, "largest change of the orbit's centre or " &
            & // "radius [m]", abs_tol=tol_orbit_shape)
    end subroutine check_ball

    subroutine test_sled_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_sled(formulation_ida, error)
    end subroutine test_sled_ida

    subroutine test_sled_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_sled(formulation_cvode, error)
    end subroutine test_sled_cvode

    !> The sled from its near-sideways start: on every row the speed along the blade
    !> u = Xdot cos(psi) + Ydot sin(psi) and the turning rate psidot against the closed form
    !> (ucon/specs/chaplygin_sled.py), the kinetic energy conserved; at the end the turning
    !> has stopped and the speed is sqrt(2E/m).
    subroutine check_sled(formulation, error)
        integer, intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        type(model_run_type) :: run
        real(wp) :: energy0, speed_limit, k, rate_scale, c, x, worst_u, worst_w, worst_e
        integer :: i, last

        call run_model("chaplygin_sled", formulation, run, error)
        if (allocated(error)) return
        associate (m => run%mass, j => run%inertia(2), a => blade_offset)
            ! kinetic energy of the start: the centre at (u0, a w0) in blade axes, turning at w0
            energy0 = 0.5_wp*m*(speed_along**2 + (a*turning_rate)**2) + 0.5_wp*j*turning_rate**2
            speed_limit = sqrt(2.0_wp*energy0/m)
            k = m*a/(j + m*a**2)
            rate_scale = sqrt(m/(j + m*a**2))*speed_limit
            c = atanh(speed_along/speed_limit)
            worst_u = 0.0_wp
            worst_w = 0.0_wp
            worst_e = 0.0_wp
            do i = 1, run%history%count
                associate (row => run%history%rows(:, i))
                    x = k*speed_limit*row(1) + c
                    worst_u = max(worst_u, abs(row(8)*cos(row(5)) + row(9)*sin(row(5)) &
                        & - speed_limit*tanh(x)))
                    worst_w = max(worst_w, abs(row(11) - rate_scale/cosh(x)))
                    worst_e = max(worst_e, abs(0.5_wp*m*(row(8)**2 + row(9)**2) &
                        & + 0.5_wp*j*row(11)**2 - energy0)/energy0)
                end associate
            end do
        end associate
        call check(error, worst_u, 0.0_wp, "largest error of the speed along the blade " &
            & // "[m/s]", abs_tol=tol_sled)
        if (allocated(error)) return
        call check(error, worst_w, 0.0_wp, "largest error of the turning rate [rad/s]", &
            & abs_tol=tol_sled)
        if (allocated(error)) return
        call check(error, worst_e, 0.0_wp, "largest relative change of the kinetic energy", &
            & abs_tol=tol_sled_energy)
        if (allocated(error)) return
        last = run%history%count
        associate (row => run%history%rows(:, last))
            call check(error, [row(11), hypot(row(8), row(9))], [0.0_wp, speed_limit], &
                & "turning rate [rad/s] and speed [m/s] at the end: 0 and sqrt(2E/m)", &
                & abs_tol=tol_sled)
        end associate
    end subroutine check_sled

end module test_models
