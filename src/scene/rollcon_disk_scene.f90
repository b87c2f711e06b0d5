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
    use rollcon_disk_reference, only : rolling_disk_ucosub
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
        logical :: time_free

        disk%id = disk_part
        call disk_mass_properties(scene, disk%mass, disk%inertia)
        call model%add_part(disk)
        model%gravity = [0.0_wp, 0.0_wp, -scene%gravity]
        model%ucosub => ucosub
        ! the hand-checked routine's F has no explicit time (DESIGN section 5): the driver
        ! skips its time partials; any other routine is asked for them
        time_free = associated(model%ucosub, rolling_disk_ucosub)
        do k = 1, 2
            call model%add_ucon(k, disk_par(disk_part, scene%radius, k), time_free=time_free)
        end do
        if (scene%height == "position") then
            ! Z - R sin(theta) = 0 in place of its time derivative F3 (DESIGN section 5)
            call model%add_ucon(3, disk_height_par(disk_part, scene%radius), disk_height_ucosub)
        else
            call model%add_ucon(3, disk_par(disk_part, scene%radius, 3), time_free=time_free)
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
    end subroutine build_disk_problem

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
