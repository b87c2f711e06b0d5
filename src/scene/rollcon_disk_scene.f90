! SPDX-License-Identifier: MIT
!> Turns a disk scene into a problem: the disk as a rigid part, three no-slip UCONs served by
!> a rolling-disk UCOSUB, gravity, the strike, solver settings, limits and the initial state.
module rollcon_disk_scene
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_rotation, only : cross
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type, profile_half_sine, frame_tilt
    use rollcon_model, only : model_type, setup_model
    use rollcon_disk_par, only : disk_par
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_par
    use rollcon_equations, only : drift_none, drift_projection, drift_baumgarte
    use rollcon_problem, only : problem_type, formulation_cvode, formulation_ida, method_bdf, &
        & method_adams
    use rollcon_scene, only : scene_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate
    implicit none
    private

    public :: build_disk_problem, disk_initial_state, disk_mass_properties, simulate_scene

    real(wp), parameter :: pi = acos(-1.0_wp)
    !> Part id of the disk in every disk scene
    integer, parameter :: disk_part = 1
    !> Lift-off threshold as a fraction of the force scale, at least, and per unit rtol: a
    !> normal force that is exactly zero (steady motion without gravity) shows rounding noise
    !> (~1e-15 of the scale) and integration noise, measured at 6e-8 to 5e-5 of the scale for
    !> rtol 1e-8 to 1e-4 (0.5 rtol at most); the threshold stays 100 times above it and far
    !> below a real lift-off, where the force falls by the order of the scale
    real(wp), parameter :: liftoff_fraction = 1.0e-5_wp, liftoff_per_rtol = 100.0_wp

contains

    !> Mass [kg] and principal moments (A about a diameter, C about the axis) [kg m^2] of a
    !> uniform disk (DESIGN section 5).
    pure subroutine disk_mass_properties(scene, mass, inertia)
        type(scene_type), intent(in) :: scene
        real(wp), intent(out) :: mass, inertia(3)

        mass = scene%density*pi*scene%radius**2*scene%thickness
        inertia(1:2) = mass*(3.0_wp*scene%radius**2 + scene%thickness**2)/12.0_wp
        inertia(3) = 0.5_wp*mass*scene%radius**2
    end subroutine disk_mass_properties

    !> Centre and its velocity from the contact constraints, unless the scene gives them.
    pure subroutine disk_initial_state(scene, q, u)
        type(scene_type), intent(in) :: scene
        real(wp), intent(out) :: q(6), u(6)
        real(wp) :: omega(3), e_y2(3)

        q = [scene%x, scene%y, scene%radius*sin(scene%theta), scene%psi, scene%theta, scene%phi]
        if (scene%z_given) q(3) = scene%z
        associate (psi => scene%psi, theta => scene%theta)
            omega = scene%psidot*[0.0_wp, 0.0_wp, 1.0_wp] &
                & + scene%thetadot*[cos(psi), sin(psi), 0.0_wp] &
                & + scene%phidot*[sin(theta)*sin(psi), -sin(theta)*cos(psi), cos(theta)]
            e_y2 = [-cos(theta)*sin(psi), cos(theta)*cos(psi), sin(theta)]
        end associate
        ! no slip at the contact C = G - R e_y2: v_G = omega x (R e_y2)
        u(1:3) = scene%radius*cross(omega, e_y2)
        if (scene%velocity_given) u(1:3) = [scene%xdot, scene%ydot, scene%zdot]
        u(4:6) = [scene%psidot, scene%thetadot, scene%phidot]
    end subroutine disk_initial_state

    !> Model, settings and limits of a disk scene, with ucosub serving the three no-slip UCONs.
    subroutine build_disk_problem(scene, ucosub, problem, q0, u0, error)
        type(scene_type), intent(in) :: scene
        procedure(ucosub_interface) :: ucosub
        type(problem_type), intent(inout) :: problem
        real(wp), intent(out) :: q0(6), u0(6)
        type(error_type), allocatable, intent(out) :: error
        type(model_type), target :: model
        type(part_type) :: disk
        type(applied_force_type) :: strike
        integer :: k

        disk%id = disk_part
        call disk_mass_properties(scene, disk%mass, disk%inertia)
        call model%add_part(disk)
        model%gravity = [0.0_wp, 0.0_wp, -scene%gravity]
        model%ucosub => ucosub
        do k = 1, 2
            call model%add_ucon(k, disk_par(disk_part, scene%radius, k))
        end do
        if (scene%height == "position") then
            ! Z - R sin(theta) = 0 in place of its time derivative F3 (DESIGN section 5)
            call model%add_ucon(3, disk_height_par(disk_part, scene%radius), disk_height_ucosub)
        else
            call model%add_ucon(3, disk_par(disk_part, scene%radius, 3))
        end if
        if (scene%has_strike) then
            ! Horizontal, along +Y, at the top of the rim: (0, R, 0) in the tilt frame.
            strike%part = 1
            strike%direction = [0.0_wp, 1.0_wp, 0.0_wp]
            strike%profile = profile_half_sine
            strike%start = scene%strike_time
            strike%duration = scene%strike_duration
            strike%impulse = scene%strike_impulse
            strike%frame = frame_tilt
            strike%point = [0.0_wp, scene%radius, 0.0_wp]
            call model%add_force(strike)
        end if
        call setup_model(model, error)
        if (allocated(error)) return
        call problem%eq%init(model)

        problem%settings%formulation = formulation_ida
        if (scene%formulation == "cvode") problem%settings%formulation = formulation_cvode
        problem%settings%method = method_bdf
        if (scene%method == "adams") problem%settings%method = method_adams
        problem%settings%analytic_jacobian = scene%jacobian == "analytic"
        problem%settings%rtol = scene%rtol
        problem%settings%atol = scene%atol
        problem%settings%max_steps = scene%max_steps
        select case (scene%drift)
        case ("none")
            problem%eq%drift = drift_none
        case ("baumgarte")
            problem%eq%drift = drift_baumgarte
        case default
            problem%eq%drift = drift_projection
        end select
        problem%eq%baumgarte_rate = scene%baumgarte_rate
        problem%events%part = 1
        problem%events%theta_min = scene%theta_min
        problem%events%stop_on_liftoff = scene%stop_on_liftoff
        call disk_initial_state(scene, q0, u0)
        call set_disk_scales(scene, disk%mass, problem)
    end subroutine build_disk_problem

    !> The scales a disk scene's events are judged by. Force scale: the weight m g, plus
    !> m R |omega0|^2 (the centripetal force of the initial spin, which sets the normal force
    !> without gravity), plus the strike's peak force; a lift-off is a normal force below
    !> -max(liftoff_fraction, liftoff_per_rtol rtol) times it. The rim radius, for the height
    !> residual.
    pure subroutine set_disk_scales(scene, mass, problem)
        type(scene_type), intent(in) :: scene
        !> Disk mass [kg]
        real(wp), intent(in) :: mass
        type(problem_type), intent(inout) :: problem
        real(wp) :: spin_squared, force_scale

        ! |omega|^2 with omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (DESIGN section 3):
        ! e_x1 is normal to both others, and e_Z . e_z2 = cos(theta)
        spin_squared = scene%psidot**2 + scene%thetadot**2 + scene%phidot**2 &
            & + 2.0_wp*scene%psidot*scene%phidot*cos(scene%theta)
        force_scale = mass*(scene%gravity + scene%radius*max(spin_squared, 0.0_wp))
        ! a half-sine pulse of impulse J over T peaks at pi J / (2 T)
        if (scene%has_strike) force_scale = force_scale &
            & + 0.5_wp*pi*abs(scene%strike_impulse)/scene%strike_duration
        problem%events%liftoff_force = max(liftoff_fraction, liftoff_per_rtol*scene%rtol) &
            & *force_scale
        problem%events%contact_radius = scene%radius
    end subroutine set_disk_scales

    !> Build a disk scene's problem and simulate it over the scene's time with its output step.
    subroutine simulate_scene(scene, ucosub, summary, error, history, csv_path, progress)
        type(scene_type), intent(in) :: scene
        !> The routine serving the disk's UCONs
        procedure(ucosub_interface) :: ucosub
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        !> Keep every output row here
        type(history_type), intent(inout), optional :: history
        !> Write the rows to this CSV
        character(len=*), intent(in), optional :: csv_path
        !> Progress lines on stderr (default: none)
        logical, intent(in), optional :: progress
        type(problem_type), target :: problem
        type(run_options_type) :: options
        real(wp) :: q0(6), u0(6)

        call build_disk_problem(scene, ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        options%end_time = scene%end_time
        options%output_step = scene%output_step
        options%progress = .false.
        if (present(progress)) options%progress = progress
        if (present(csv_path)) options%csv_path = csv_path
        call simulate(problem, q0, u0, options, summary, error, history)
    end subroutine simulate_scene

end module rollcon_disk_scene
