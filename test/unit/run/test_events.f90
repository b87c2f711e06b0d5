! SPDX-License-Identifier: MIT
!> Events that tell the truth: the theta limit on both sides of flat, theta_min = 0 refused,
!> lift-off against a threshold (no false stop at zero gravity, a real one caught).
module test_events
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene
    use rollcon_problem, only : problem_type
    use rollcon_contact_watch, only : contact_watch_type
    use rollcon_disk_scene, only : build_disk_problem, disk_mass_properties
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : history_type, run_summary_type, status_completed, &
        & status_stopped
    use rollcon_output_layout, only : coord_z, coord_theta
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory, default_scene, tipping_coin
    implicit none
    private

    public :: collect_events


contains

    subroutine collect_events(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("theta-limit-stops-run", test_theta_event), &
            & new_unittest("theta-limit-near-pi-stops-on-that-side", test_theta_near_pi), &
            & new_unittest("theta-min-zero-refused", test_theta_min_zero), &
            & new_unittest("zero-gravity-circle-no-false-liftoff", test_zero_gravity_circle), &
            & new_unittest("liftoff-stops-run", test_liftoff_event)]
    end subroutine collect_events

    !> A theta limit stops the run cleanly with a message naming the time and the state.
    subroutine test_theta_event(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        scene = tipping_coin("ida", 1.0e-8_wp)
        scene%limits%theta_min = 0.5_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped, "the run did not stop at the limit")
        if (allocated(error)) return
        call check(error, index(summary%message, "theta fell to the limit theta_min = 0.5") > 0 &
            & .and. index(summary%message, " at t = ") > 0, "message: " // summary%message)
        if (allocated(error)) return
        ! the root of sin(theta) - sin(0.5) is located to the solver's tolerance
        call check(error, history%rows(history%layout%part_column(1, coord_theta), &
            & history%count), 0.5_wp, &
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
        scene%initial%theta = pi - 0.5_wp*pi/180.0_wp
        scene%limits%theta_min = 0.005_wp
        scene%run%end_time = 1.0_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped, "status " // to_text(summary%status) &
            & // " at t = " // to_text(summary%t_reached) // ": the limit did not stop the run")
        if (allocated(error)) return
        call check(error, index(summary%message, "theta rose to pi - theta_min") == 1 .and. &
            & index(summary%message, "on the theta = pi side") > 0, "message: " // summary%message)
        if (allocated(error)) return
        call check(error, history%rows(history%layout%part_column(1, coord_theta), &
            & history%count), pi - scene%limits%theta_min, &
            & "theta at the stop", abs_tol=tol_root)
        if (allocated(error)) return
        call check(error, minval(history%part_values(1, coord_z)) > 0.0_wp, &
            & "the centre went below " &
            & // "the floor: Z = " // to_text(minval(history%part_values(1, coord_z))) // " m")
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
            & // "'theta_min' in &limits must be at least 0.001") == 1, &
            & "message: " // refused%message)
    end subroutine test_theta_min_zero

    !> Without gravity the normal force of a steady circle is exactly zero (m (g + Z'') = 0), so
    !> its rounding and integration noise must not count as a lift-off: the run goes its full
    !> time, under IDA at rtol 1e-8 and under CVODE at 1e-4 (noise up to 5e-5 of the force
    !> scale there). Steady motion at theta = 60 deg, phidot = -20 rad/s:
    !> A W^2 s c = (C + m R^2) W (phidot + W c) s gives W = (C + m R^2) phidot / (c (A - C -
    !> m R^2)) (docs/design.md §5, g = 0).
    subroutine test_zero_gravity_circle(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=5), parameter :: formulations(2) = ["ida  ", "cvode"]
        real(wp), parameter :: tolerances(2) = [1.0e-8_wp, 1.0e-4_wp]
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        real(wp) :: mass, inertia(3)
        integer :: i

        do i = 1, 2
            scene = tipping_coin(trim(formulations(i)), tolerances(i))
            scene%environment%gravity = 0.0_wp
            scene%initial%theta = pi/3.0_wp
            scene%initial%phidot = -20.0_wp
            call disk_mass_properties(scene, mass, inertia)
            associate (a => inertia(1), c => inertia(3), r => scene%disk%radius)
                scene%initial%psidot = (c + mass*r**2)*scene%initial%phidot &
                    & /(cos(scene%initial%theta)*(a - c - mass*r**2))
            end associate
            scene%run%end_time = 0.5_wp
            scene%limits%stop_on_liftoff = .true.
            call run_in_memory(scene, history, summary, error)
            if (allocated(error)) return
            call check(error, summary%status == status_completed, trim(formulations(i)) &
                & // ": status " // to_text(summary%status) // ": " // summary%message)
            if (allocated(error)) return
            call check(error, summary%t_reached, scene%run%end_time, "time reached [s]", &
                & abs_tol=0.0_wp)
            if (allocated(error)) return
            ! theta stays at 60 deg to the integration error: 100 rtol over 0.5 s
            call check(error, maxval(abs(history%part_values(1, coord_theta) - pi/3.0_wp)), &
                & 0.0_wp, &
                & trim(formulations(i)) // ": largest |theta - 60 deg| [rad]", &
                & abs_tol=1.0e2_wp*tolerances(i))
            if (allocated(error)) return
        end do
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
        type(problem_type), target :: problem
        real(wp) :: q0(6), u0(6)

        scene = default_scene()
        scene%environment%gravity = 0.0_wp
        scene%initial%theta = pi/12.0_wp
        scene%initial%psidot = 10.0_wp
        scene%initial%phidot = -10.0_wp*cos(pi/12.0_wp)
        scene%run%end_time = 2.0_wp
        scene%limits%stop_on_liftoff = .true.
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped .and. &
            & index(summary%message, "normal contact force turned negative (below -") > 0, &
            & "no lift-off stop; status " // to_text(summary%status))
        if (allocated(error)) return
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        select type (contact => problem%watches(2)%watch)
        type is (contact_watch_type)
            call check(error, contact%liftoff_force > 0.0_wp .and. &
                & contact%liftoff_force < tol_force, "lift-off threshold " &
                & // to_text(contact%liftoff_force) // " N: not a small positive force")
            if (allocated(error)) return
            call check(error, history%rows(history%layout%column("Fz"), history%count), &
                & -contact%liftoff_force, "normal force at the stop [N]", abs_tol=tol_force)
        class default
            call check(error, .false., "the disk scene's second watch is not its contact")
        end select
    end subroutine test_liftoff_event

end module test_events
