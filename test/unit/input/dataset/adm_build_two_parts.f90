! SPDX-License-Identifier: MIT
!> adm-build/disk-and-sphere: data/disk_and_sphere.adm, a disk on a steady circle and a sphere
!> rolling straight, two parts and two built-in routines from one dataset, run and checked
!> against their analytic motions.
module adm_build_two_parts
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & status_completed
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_disk_and_sphere

    !> Sphere radius [m] and speed [m/s], disk tilt [rad] and steady precession [rad/s] of
    !> data/disk_and_sphere.adm
    real(wp), parameter :: sphere_radius = 0.05_wp, sphere_speed = 0.5_wp
    real(wp), parameter :: disk_theta = pi/3.0_wp, disk_precession = 1.968673796419169_wp
    !> The sphere's straight rolling is exact and BDF integrates its constant velocity
    !> exactly (measured: 6e-14 in phi after 2 s); 1e-9 in state units
    real(wp), parameter :: tol_sphere = 1.0e-9_wp
    !> The disk's steady circle is exact too; the integration error (ERROR = 1e-10 and the
    !> default atol 1e-10 on rates of 20 rad/s) starts a nutation, measured at 9e-10 rad in
    !> theta and 4.2e-8 rad/s in psidot over 2 s. A wrong force, inertia or routine moves them
    !> by orders more within 0.1 s
    real(wp), parameter :: tol_theta = 1.0e-8_wp, tol_precession = 2.0e-7_wp
    !> Energy is conserved (no applied force; rolling does no work): the run's drift must stay
    !> within what its tolerances promise (rollcon_drift's bound, the run's own judge) and
    !> below 1e-7 (measured 1.05e-8: atol 1e-10 on rates of 20 rad/s)
    real(wp), parameter :: tol_energy = 1.0e-7_wp
    !> UCON residuals [m/s]: IDA enforces F = 0 within its Newton tolerance, a few atol
    !> (measured 1.4e-10)
    real(wp), parameter :: tol_residual = 1.0e-9_wp

contains

    subroutine test_disk_and_sphere(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(history_type) :: history
        real(wp), allocatable :: q0(:), u0(:)
        real(wp) :: omega(3)

        call read_adm("data/disk_and_sphere.adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q0, u0=u0, error=error)
        if (allocated(error)) return
        call check(error, size(problem%model%parts) == 2 .and. size(problem%model%ucons) == 6 &
            & .and. all(problem%model%parts%id == [2, 3]) .and. size(q0) == 12, &
            & "two parts, six UCONs")
        if (allocated(error)) return
        options%end_time = adm%run%settings%end_time
        options%output_step = adm%run%settings%output_step
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error, history)
        if (allocated(error)) return
        call check(error, summary%status == status_completed .and. summary%t_reached == 2.0_wp &
            & .and. history%count == 201, "the run completes, 201 rows")
        if (allocated(error)) return
        associate (q => summary%q(7:12), u => summary%u(7:12))
            ! straight at constant speed: X = v t, Y, Z and the velocity unchanged
            call check(error, [q(1:3), u(1:3)], [sphere_speed*2.0_wp, -0.5_wp, sphere_radius, &
                & sphere_speed, 0.0_wp, 0.0_wp], "sphere's centre at t = 2 s", abs_tol=tol_sphere)
            if (allocated(error)) return
            ! omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (docs/design.md §3): v/r about +Y
            omega = u(4)*[0.0_wp, 0.0_wp, 1.0_wp] + u(5)*[cos(q(4)), sin(q(4)), 0.0_wp] &
                & + u(6)*[sin(q(5))*sin(q(4)), -sin(q(5))*cos(q(4)), cos(q(5))]
            call check(error, omega, [0.0_wp, sphere_speed/sphere_radius, 0.0_wp], &
                & "sphere's angular velocity", abs_tol=tol_sphere)
            if (allocated(error)) return
            ! no slip: v = r omega x e_Z
            call check(error, u(1:3), sphere_radius*[omega(2), -omega(1), 0.0_wp], &
                & "sphere's no-slip velocity", abs_tol=tol_sphere)
            if (allocated(error)) return
        end associate
        ! the disk, part 1 (columns 2..13): theta and the precession rate stay the steady ones
        call check(error, maxval(abs(history%rows(6, :history%count) - disk_theta)), 0.0_wp, &
            & "largest |theta - 60 deg| of the disk [rad]", abs_tol=tol_theta)
        if (allocated(error)) return
        call check(error, maxval(abs(history%rows(11, :history%count) - disk_precession)), &
            & 0.0_wp, "largest |psidot - W| of the disk [rad/s]", abs_tol=tol_precession)
        if (allocated(error)) return
        call check(error, summary%energy_bound > 0.0_wp .and. summary%energy_drift &
            & <= summary%energy_bound, "energy drift within the run's bound")
        if (allocated(error)) return
        call check(error, summary%energy_drift, 0.0_wp, "energy drift", abs_tol=tol_energy)
        if (allocated(error)) return
        call check(error, summary%residual_max, 0.0_wp, "largest UCON residual", &
            & abs_tol=tol_residual)
    end subroutine test_disk_and_sphere

end module adm_build_two_parts
