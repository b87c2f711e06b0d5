! SPDX-License-Identifier: MIT
!> Events and drift that tell the truth: the theta limit on both sides of flat, theta_min = 0
!> refused, lift-off against a threshold (no false stop at zero gravity, a real one caught),
!> the position-level height residual in the CSV and summary, drift judged against the
!> tolerances (issue #11, items 13-15).
module test_events
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene
    use rollcon_problem, only : problem_type
    use rollcon_disk_scene, only : build_disk_problem, disk_mass_properties
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : run_options_type, simulate, history_type, run_summary_type, &
        & status_completed, status_stopped, status_inaccurate, column_time, column_z, &
        & column_theta, column_fz
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory, default_scene
    implicit none
    private

    public :: collect_events

    real(wp), parameter :: pi = acos(-1.0_wp)

contains

    subroutine collect_events(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("theta-limit-stops-run", test_theta_event), &
            & new_unittest("theta-limit-near-pi-stops-on-that-side", test_theta_near_pi), &
            & new_unittest("theta-min-zero-refused", test_theta_min_zero), &
            & new_unittest("zero-gravity-circle-no-false-liftoff", test_zero_gravity_circle), &
            & new_unittest("liftoff-stops-run", test_liftoff_event), &
            & new_unittest("height-residual-in-csv-and-summary", test_height_column), &
            & new_unittest("drift-none-judged-inaccurate", test_drift_none_warned), &
            & new_unittest("sound-run-within-drift-bounds", test_sound_run), &
            & new_unittest("position-height-holds-z-to-atol", test_position_height_holds)]
    end subroutine collect_events

    !> The tipping coin: upright less 0.01 rad, rolling at 0.1 m/s, no strike, 10 s.
    function tipping_coin(rtol) result(scene)
        real(wp), intent(in) :: rtol
        type(scene_type) :: scene

        scene = default_scene()
        scene%theta = 0.5_wp*pi - 0.01_wp
        scene%phidot = -1.0_wp
        scene%end_time = 10.0_wp
        scene%output_step = 0.05_wp
        scene%rtol = rtol
        scene%atol = 1.0e-2_wp*rtol
    end function tipping_coin

    !> A theta limit stops the run cleanly with a message naming the time and the state.
    subroutine test_theta_event(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        scene = tipping_coin(1.0e-8_wp)
        scene%theta_min = 0.5_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped, "the run did not stop at the limit")
        if (allocated(error)) return
        call check(error, index(summary%message, "theta fell to the limit theta_min = 0.5") > 0 &
            & .and. index(summary%message, " at t = ") > 0, "message: " // summary%message)
        if (allocated(error)) return
        ! the root of sin(theta) - sin(0.5) is located to the solver's tolerance
        call check(error, history%rows(column_theta, history%count), 0.5_wp, &
            & "theta at the stop", abs_tol=1.0e-6_wp)
    end subroutine test_theta_event

    !> A disk at rest started 0.5 deg from theta = pi falls towards flat on that side (it
    !> reaches it at ~0.015 s): the limit theta_min = 0.005 rad stops it at theta = pi - 0.005
    !> with the centre above the floor, and the message names that side.
    subroutine test_theta_near_pi(error)
        type(error_type), allocatable, intent(out) :: error
        !> The root is located to the solver's tolerance, as on the theta = 0 side
        real(wp), parameter :: tol_root = 1.0e-6_wp
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        scene = default_scene()
        scene%theta = pi - 0.5_wp*pi/180.0_wp
        scene%theta_min = 0.005_wp
        scene%end_time = 1.0_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped, "status " // to_text(summary%status) &
            & // " at t = " // to_text(summary%t_reached) // ": the limit did not stop the run")
        if (allocated(error)) return
        call check(error, index(summary%message, "theta rose to pi - theta_min") == 1 .and. &
            & index(summary%message, "on the theta = pi side") > 0, "message: " // summary%message)
        if (allocated(error)) return
        call check(error, history%rows(column_theta, history%count), pi - scene%theta_min, &
            & "theta at the stop", abs_tol=tol_root)
        if (allocated(error)) return
        call check(error, minval(history%column(column_z)) > 0.0_wp, "the centre went below " &
            & // "the floor: Z = " // to_text(minval(history%column(column_z))) // " m")
    end subroutine test_theta_near_pi

    !> theta_min = 0 would let the run go on into the singularity, where the solvers fail
    !> (IDA: singular matrix; CVODE: root finding at t = NaN): the scene is refused, naming the
    !> key, its line and what is expected.
    subroutine test_theta_min_zero(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = "build/test_events_theta_min_zero.nml"
        type(scene_type) :: scene
        type(error_type), allocatable :: refused
        integer :: unit

        open(newunit=unit, file=path, status="replace", action="write")
        write(unit, '(a)') "&limits", "    theta_min = 0.0", "/"
        close(unit)
        call read_scene(path, scene, refused)
        open(newunit=unit, file=path, status="old")
        close(unit, status="delete")
        call check(error, allocated(refused), "theta_min = 0 was accepted")
        if (allocated(error)) return
        call check(error, refused%stat == stat_input .and. index(refused%message, path // ":2: " &
            & // "'theta_min' must be at least 0.001") == 1, "message: " // refused%message)
    end subroutine test_theta_min_zero

    !> Without gravity the normal force of a steady circle is exactly zero (m (g + Z'') = 0), so
    !> its rounding noise must not count as a lift-off: the run goes its full time. Steady
    !> motion at theta = 60 deg, phidot = -20 rad/s: A W^2 s c = (C + m R^2) W (phidot + W c) s
    !> gives W = (C + m R^2) phidot / (c (A - C - m R^2)) (DESIGN section 5, g = 0).
    subroutine test_zero_gravity_circle(error)
        type(error_type), allocatable, intent(out) :: error
        !> theta stays at 60 deg to the integration error (rtol 1e-8 over 0.5 s)
        real(wp), parameter :: tol_theta = 1.0e-6_wp
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        real(wp) :: mass, inertia(3)

        scene = default_scene()
        scene%gravity = 0.0_wp
        scene%theta = pi/3.0_wp
        scene%phidot = -20.0_wp
        call disk_mass_properties(scene, mass, inertia)
        associate (a => inertia(1), c => inertia(3), r => scene%radius)
            scene%psidot = (c + mass*r**2)*scene%phidot/(cos(scene%theta)*(a - c - mass*r**2))
        end associate
        scene%end_time = 0.5_wp
        scene%stop_on_liftoff = .true.
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_completed, "status " &
            & // to_text(summary%status) // ": " // summary%message)
        if (allocated(error)) return
        call check(error, summary%t_reached, scene%end_time, "time reached [s]", abs_tol=0.0_wp)
        if (allocated(error)) return
        call check(error, maxval(abs(history%column(column_theta) - pi/3.0_wp)), 0.0_wp, &
            & "largest |theta - 60 deg| [rad]", abs_tol=tol_theta)
    end subroutine test_zero_gravity_circle

    !> Without gravity, a disk precessing near flat needs the ground to pull it: the run stops
    !> when the normal force falls below minus the lift-off threshold, naming the time and tilt.
    subroutine test_liftoff_event(error)
        type(error_type), allocatable, intent(out) :: error
        !> The root is located to the solver's tolerance on a force of order m R psidot^2 ~ 7 N
        real(wp), parameter :: tol_force = 1.0e-5_wp
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        type(problem_type) :: problem
        real(wp) :: q0(6), u0(6)

        scene = default_scene()
        scene%gravity = 0.0_wp
        scene%theta = pi/12.0_wp
        scene%psidot = 10.0_wp
        scene%phidot = -10.0_wp*cos(pi/12.0_wp)
        scene%end_time = 2.0_wp
        scene%stop_on_liftoff = .true.
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped .and. &
            & index(summary%message, "normal contact force turned negative (below -") > 0, &
            & "no lift-off stop; status " // to_text(summary%status))
        if (allocated(error)) return
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        call check(error, problem%events%liftoff_force > 0.0_wp .and. &
            & problem%events%liftoff_force < tol_force, "lift-off threshold " &
            & // to_text(problem%events%liftoff_force) // " N: not a small positive force")
        if (allocated(error)) return
        call check(error, history%rows(column_fz, history%count), &
            & -problem%events%liftoff_force, "normal force at the stop [N]", abs_tol=tol_force)
    end subroutine test_liftoff_event

    !> The CSV's last column is the height residual Z - R sin(theta) of each row, and the
    !> summary's height_residual_max is its largest magnitude.
    subroutine test_height_column(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = "build/test_events_height.csv"
        !> Z and theta are printed with 17 significant digits: the residual recomputed from
        !> them is good to ~1e-17 m
        real(wp), parameter :: tol_printed = 1.0e-15_wp
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        real(wp) :: q0(6), u0(6), row(23), largest
        character(len=2048) :: line
        integer :: unit, stat, rows

        scene = tipping_coin(1.0e-6_wp)
        scene%end_time = 2.0_wp
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        options%end_time = scene%end_time
        options%output_step = 0.1_wp
        options%csv_path = path
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        read(unit, '(a)') line
        call check(error, index(line, ",F1,F2,F3,height_residual") > 0 .and. &
            & len_trim(line) == index(line, "height_residual") + 14, "header: " // trim(line))
        if (allocated(error)) then
            close(unit, status="delete")
            return
        end if
        rows = 0
        largest = 0.0_wp
        do
            read(unit, *, iostat=stat) row
            if (stat /= 0) exit
            rows = rows + 1
            largest = max(largest, abs(row(23)))
            call check(error, row(23), row(column_z) - scene%radius*sin(row(column_theta)), &
                & "height residual at t = " // to_text(row(column_time)), abs_tol=tol_printed)
            if (allocated(error)) exit
        end do
        close(unit, status="delete")
        if (allocated(error)) return
        call check(error, rows, summary%rows, "rows read")
        if (allocated(error)) return
        call check(error, largest > 0.0_wp, "the velocity form's height residual is exactly 0")
        if (allocated(error)) return
        call check(error, summary%height_residual_max, largest, "summary's height residual [m]", &
            & rel_tol=1.0e-12_wp)
    end subroutine test_height_column

    !> Without drift control CVODE lets the constraints wander: on the tipping coin at rtol 1e-4
    !> the height residual grows like the number of steps N, to 7.8 sqrt(N) (atol + rtol R)
    !> over 10 s, beyond its bound of 3 sqrt(N) (energy: 9.2 sqrt(N) rtol, just below its 10).
    !> The run is judged inaccurate, not completed, and says why.
    subroutine test_drift_none_warned(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        scene = drifting_scene()
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_inaccurate, "status " &
            & // to_text(summary%status) // ", energy drift " // to_text(summary%energy_drift) &
            & // " (bound " // to_text(summary%energy_bound) // "), height residual " &
            & // to_text(summary%height_residual_max) // " m (bound " &
            & // to_text(summary%height_bound) // " m)")
        if (allocated(error)) return
        call check(error, index(summary%message, "drifted beyond what its tolerances promise") &
            & > 0 .and. index(summary%message, "height residual |Z - R sin(theta)| ") > 0, &
            & "message: " // summary%message)
    end subroutine test_drift_none_warned

    !> The scene of test_drift_none_warned.
    function drifting_scene() result(scene)
        type(scene_type) :: scene

        scene = tipping_coin(1.0e-4_wp)
        scene%formulation = "cvode"
        scene%drift = "none"
    end function drifting_scene

    !> The same scene with projection (0.7 and 0.12 sqrt(N) units measured) and with IDA stays
    !> within both bounds, and they are set.
    subroutine test_sound_run(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=5), parameter :: formulations(2) = ["cvode", "ida  "]
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        integer :: i

        do i = 1, 2
            scene = drifting_scene()
            scene%formulation = trim(formulations(i))
            scene%drift = "projection"
            call run_in_memory(scene, history, summary, error)
            if (allocated(error)) return
            call check(error, summary%status == status_completed .and. &
                & summary%energy_bound > 0.0_wp .and. summary%height_bound > 0.0_wp, &
                & trim(formulations(i)) // ": status " // to_text(summary%status) // ", bounds " &
                & // to_text(summary%energy_bound) // ", " // to_text(summary%height_bound))
            if (allocated(error)) return
        end do
    end subroutine test_sound_run

    !> The position form of the height constraint holds Z = R sin(theta) to the absolute
    !> tolerance over the tipping coin's 10 s (fall to theta ~ 0.12 rad and back), where the
    !> velocity form lets it drift by orders of magnitude more; both within their bound.
    subroutine test_position_height_holds(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: velocity_form, position_form

        scene = tipping_coin(1.0e-8_wp)
        call run_in_memory(scene, history, velocity_form, error)
        if (allocated(error)) return
        scene%height = "position"
        call run_in_memory(scene, history, position_form, error)
        if (allocated(error)) return
        call check(error, velocity_form%status == status_completed .and. &
            & position_form%status == status_completed, "status " &
            & // to_text(velocity_form%status) // ", " // to_text(position_form%status))
        if (allocated(error)) return
        call check(error, position_form%height_residual_max <= scene%atol, "position form: " &
            & // "|Z - R sin(theta)| " // to_text(position_form%height_residual_max) &
            & // " m above atol")
        if (allocated(error)) return
        call check(error, velocity_form%height_residual_max > 10.0_wp*scene%atol, &
            & "velocity form: |Z - R sin(theta)| " // to_text(velocity_form%height_residual_max) &
            & // " m, no worse than the position form's")
    end subroutine test_position_height_holds

end module test_events
