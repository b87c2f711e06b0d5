! SPDX-License-Identifier: MIT
!> A model built in code with the rollcon library (docs/library.md walks through it): a disk
!> and a sphere rolling on the ground, each held by UCONs, the sphere pushed once.
!>
!> - Part 1, a disk (radius 0.1 m, 1.2 kg), upright, rolling straight along +X at 2 m/s (above
!>   its critical speed, so it stays upright): three UCONs (11, 12, 13) served by the built-in
!>   hand-checked routine `disk`.
!> - Part 2, a sphere (radius 0.05 m, 2 kg), rolling along +X at 1 m/s: UCONs 21 and 22 (no slip)
!>   served by the generated `rolling_sphere`, UCON 23 (its centre stays R above the ground)
!>   by the user's own routine, sphere_height_ucosub (example/sphere_height.f90).
!> - Gravity 9.81 m/s^2 along -Z; a push on the sphere's centre along +X, a half-sine pulse of
!>   0.5 N s over 20 ms at t = 0.5 s.
!>
!> It makes the model a job (new_model_source, new_job) and runs it as rollcon runs any input
!> (run_job), 2 s with IDA and with CVODE, reads the results from the history through the
!> output layout, and checks them against what the physics says: the disk keeps its speed;
!> the push raises the sphere's speed by J / (m + I/R^2) = J / (1.4 m); the energy rises by
!> what the push gives the sphere; the multipliers of the two height UCONs are the weights;
!> every UCON residual stays small. It prints the comparison and exits with status 1 when a
!> check fails.
program two_rollers
    use, intrinsic :: iso_fortran_env, only : error_unit
    use rollcon, only : wp, error_type, model_type, part_type, applied_force_type, &
        & profile_half_sine, setup_model, run_settings_type, formulation_ida, formulation_cvode, &
        & run_summary_type, history_type, status_completed, job_type, new_job, &
        & new_model_source, run_job, job_result_type, output_layout_type, &
        & find_builtin_ucosub, builtin_ucosub_par, ucosub_interface, use_one_blas_thread, &
        & coord_xdot, coord_ydot
    use sphere_height, only : sphere_height_ucosub, sphere_height_par
    implicit none

    !> Disk: radius, thickness [m], mass [kg], speed [m/s]
    real(wp), parameter :: disk_radius = 0.1_wp, disk_thickness = 0.01_wp, &
        & disk_mass = 1.2_wp, disk_speed = 2.0_wp
    !> Sphere: radius [m], mass [kg], speed [m/s]
    real(wp), parameter :: sphere_radius = 0.05_wp, sphere_mass = 2.0_wp, sphere_speed = 1.0_wp
    !> The push: impulse [N s], start and duration [s]; gravity [m/s^2]
    real(wp), parameter :: push_impulse = 0.5_wp, push_start = 0.5_wp, push_duration = 0.02_wp
    real(wp), parameter :: gravity = 9.81_wp
    !> Part ids, as the UCONs' PAR name them
    integer, parameter :: disk_id = 1, sphere_id = 2
    !> pi/2 [rad]
    real(wp), parameter :: upright = 0.5_wp*acos(-1.0_wp)

    type(model_type) :: model
    type(error_type), allocatable :: error
    character(len=:), allocatable :: blas_library
    integer :: failures

    ! dozen-unknown systems gain nothing from BLAS threads (rollcon_lapack)
    call use_one_blas_thread(blas_library)
    call build_model(model, error)
    if (allocated(error)) call fail(error%message)
    write(*, '(a)') "two_rollers: a disk (part 1) and a sphere (part 2) rolling on the ground, " &
        & // "the sphere pushed at t = 0.5 s; 2 s"
    failures = 0
    call run(formulation_ida, "IDA", failures)
    call run(formulation_cvode, "CVODE", failures)
    if (failures > 0) then
        write(*, '(a, i0, a)') "two_rollers: ", failures, " check(s) failed"
        stop 1, quiet=.true.
    end if
    write(*, '(a)') "two_rollers: every check passed"

contains

    !> The model: parts, UCONs with their routines, gravity, the push. setup_model then makes
    !> every UCON's initialisation call and checks what the routines declare.
    subroutine build_model(model, error)
        type(model_type), intent(out) :: model
        type(error_type), allocatable, intent(out) :: error
        type(part_type) :: disk, sphere
        type(applied_force_type) :: push
        procedure(ucosub_interface), pointer :: disk_routine, sphere_routine
        real(wp), allocatable :: par(:)
        logical :: disk_time_free, sphere_time_free, found
        integer :: k

        ! principal moments about the body x, y, z axes [kg m^2]; the disk's axis is body z
        disk%id = disk_id
        disk%mass = disk_mass
        disk%inertia = [disk_mass*(3.0_wp*disk_radius**2 + disk_thickness**2)/12.0_wp, &
            & disk_mass*(3.0_wp*disk_radius**2 + disk_thickness**2)/12.0_wp, &
            & 0.5_wp*disk_mass*disk_radius**2]
        call model%add_part(disk)
        sphere%id = sphere_id
        sphere%mass = sphere_mass
        sphere%inertia = 0.4_wp*sphere_mass*sphere_radius**2
        call model%add_part(sphere)
        model%gravity = [0.0_wp, 0.0_wp, -gravity]

        call find_builtin_ucosub("disk", disk_routine, disk_time_free, found)
        if (.not. found) call fail("no built-in routine 'disk'")
        call find_builtin_ucosub("rolling_sphere", sphere_routine, sphere_time_free, found)
        if (.not. found) call fail("no built-in routine 'rolling_sphere'")
        do k = 1, 3
            call builtin_ucosub_par("disk", disk_id, [disk_radius], k, par, error)
            if (allocated(error)) return
            call model%add_ucon(10 + k, par, disk_routine, time_free=disk_time_free, &
                & routine="disk")
        end do
        do k = 1, 2
            call builtin_ucosub_par("rolling_sphere", sphere_id, [sphere_radius], k, par, error)
            if (allocated(error)) return
            call model%add_ucon(20 + k, par, sphere_routine, time_free=sphere_time_free, &
                & routine="rolling_sphere")
        end do
        call model%add_ucon(23, sphere_height_par(sphere_id, sphere_radius), &
            & sphere_height_ucosub, time_free=.true., routine="sphere_height")

        ! the push acts on the sphere (the second part added: part numbers are model order) at
        ! its centre (point 0 in its body axes), along ground +X
        push%part = 2
        push%direction = [1.0_wp, 0.0_wp, 0.0_wp]
        push%profile = profile_half_sine
        push%start = push_start
        push%duration = push_duration
        push%impulse = push_impulse
        call model%add_force(push)
        call setup_model(model, error)
    end subroutine build_model

    !> Start: both upright (theta = pi/2, psi = 0: the disk's axis and the sphere's body z axis
    !> along -Y), rolling along +X without slip, so phidot = -v/R for both.
    subroutine initial_state(q0, u0)
        real(wp), intent(out) :: q0(12), u0(12)

        q0 = [0.0_wp, 0.0_wp, disk_radius, 0.0_wp, upright, 0.0_wp, &
            & 0.0_wp, 0.5_wp, sphere_radius, 0.0_wp, upright, 0.0_wp]
        u0 = [disk_speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -disk_speed/disk_radius, &
            & sphere_speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -sphere_speed/sphere_radius]
    end subroutine initial_state

    !> Set up a problem in place (it must be a target and is not copied after init), simulate
    !> with the formulation given, and check the history.
    subroutine run(formulation, label, failures)
        integer, intent(in) :: formulation
        character(len=*), intent(in) :: label
        integer, intent(inout) :: failures
        type(run_settings_type) :: settings
        type(job_type) :: job
        type(job_result_type) :: result
        type(run_summary_type) :: summary
        type(history_type) :: history
        type(output_layout_type) :: layout
        type(error_type), allocatable :: error
        real(wp) :: q0(12), u0(12)

        settings%formulation = formulation
        settings%rtol = 1.0e-8_wp
        settings%atol = 1.0e-10_wp
        settings%end_time = 2.0_wp
        settings%output_step = 0.01_wp
        call initial_state(q0, u0)
        ! the one route of every run: a job of the model, run (no files: the rows go to history)
        job = new_job(new_model_source("two_rollers", model, q0, u0, settings))
        call run_job(job, result, error, history)
        if (allocated(error)) call fail(label // ": " // error%message)
        summary = result%summary
        if (summary%status /= status_completed) call fail(label // ": the run did not " &
            & // "complete: " // summary%message)
        ! the columns of the rows (t, each part's 12 coordinates, E, F_<id>, lambda_<id>): the
        ! history carries the layout it was written with
        layout = history%layout
        call check_run(label, layout, history, summary, failures)
    end subroutine run

    !> Compare the run with the physics; one line per check, failures counted.
    subroutine check_run(label, layout, history, summary, failures)
        character(len=*), intent(in) :: label
        type(output_layout_type), intent(in) :: layout
        type(history_type), intent(in) :: history
        type(run_summary_type), intent(in) :: summary
        integer, intent(inout) :: failures
        ! The disk rolls steadily and nothing acts on it: its speed is held to round-off
        ! within the integrators' per-step error control (rtol = 1e-8).
        real(wp), parameter :: tol_disk = 1.0e-8_wp
        ! The push is integrated between 21 stops inside the 20 ms pulse; the impulse it
        ! delivers is off by the global error of those steps, measured at rtol = 1e-8 as
        ! 2.5e-5 of the speed gain with IDA and 3e-6 with CVODE (it shrinks with rtol). 1e-4 of
        ! the gain still catches a pulse lost or doubled, the sphere's effective mass taken as
        ! m instead of 1.4 m (40 %), or slip.
        real(wp), parameter :: tol_push = 1.0e-4_wp
        ! Energy drift once the push is over, relative to the energy (rollcon's own measure)
        real(wp), parameter :: tol_drift = 1.0e-6_wp
        ! Multipliers are forces [N] from the saddle-point solve: round-off of the weight
        real(wp), parameter :: tol_force = 1.0e-8_wp
        ! Residuals: velocity UCONs [m/s], the position UCON [m]; IDA enforces them to its
        ! Newton tolerance, CVODE's projection to rtol times the scale of the state
        real(wp), parameter :: tol_residual = 1.0e-7_wp
        real(wp) :: speed_end(2), push_gain, energy_gain, residual_max
        integer :: last, p, k

        last = history%count
        associate (rows => history%rows)
            do p = 1, 2
                speed_end(p) = hypot(rows(layout%part_column(p, coord_xdot), last), &
                    & rows(layout%part_column(p, coord_ydot), last))
            end do
            ! a push F at the centre of a rolling sphere: m a = F - f, (2/5) m R^2 a/R = f R
            push_gain = push_impulse/(1.4_wp*sphere_mass)
            ! kinetic energy of a rolling sphere: (1/2) m v^2 + (1/2) (2/5) m R^2 (v/R)^2
            energy_gain = 0.7_wp*sphere_mass*((sphere_speed + push_gain)**2 - sphere_speed**2)
            call compare(label, "disk speed [m/s]", speed_end(1), disk_speed, &
                & tol_disk*disk_speed, failures)
            call compare(label, "sphere speed [m/s]", speed_end(2), sphere_speed + push_gain, &
                & tol_push*push_gain, failures)
            call compare(label, "energy gain [J]", rows(layout%energy_column(), last) &
                & - rows(layout%energy_column(), 1), energy_gain, tol_push*energy_gain, &
                & failures)
            call compare(label, "energy drift after the push [-]", summary%energy_drift, &
                & 0.0_wp, tol_drift, failures)
            ! UCONs 13 and 23 hold each centre up: their multipliers carry the weights
            call compare(label, "disk support, lambda_13 [N]", &
                & rows(layout%multiplier_column(3), last), disk_mass*gravity, &
                & tol_force*disk_mass*gravity, failures)
            call compare(label, "sphere support, lambda_23 [N]", &
                & rows(layout%multiplier_column(6), last), sphere_mass*gravity, &
                & tol_force*sphere_mass*gravity, failures)
            residual_max = 0.0_wp
            do k = 1, size(layout%ucon_ids)
                residual_max = max(residual_max, maxval(abs(rows(layout%residual_column(k), &
                    & :last))))
            end do
            call compare(label, "largest UCON residual", residual_max, 0.0_wp, tol_residual, &
                & failures)
        end associate
    end subroutine check_run

    !> One line: the value, what was expected and whether it is within tolerance.
    subroutine compare(label, what, value, expected, tolerance, failures)
        character(len=*), intent(in) :: label, what
        real(wp), intent(in) :: value, expected, tolerance
        integer, intent(inout) :: failures
        character(len=4) :: verdict

        verdict = "ok"
        if (.not. abs(value - expected) <= tolerance) then
            verdict = "FAIL"
            failures = failures + 1
        end if
        write(*, '(2x, a, t10, a, t42, es16.9, a, es16.9, a, es8.1, a, a)') label, what, value, &
            & " expected ", expected, " within ", tolerance, ": ", trim(verdict)
    end subroutine compare

    !> Report and stop with status 1 (only a program stops: the library returns errors).
    subroutine fail(message)
        character(len=*), intent(in) :: message

        write(error_unit, '(a)') "two_rollers: error: " // message
        stop 1, quiet=.true.
    end subroutine fail

end program two_rollers
