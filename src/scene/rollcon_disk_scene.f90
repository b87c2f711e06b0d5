! SPDX-License-Identifier: MIT
!> Turns a disk scene into a problem: the disk as a rigid part, three no-slip UCONs served by
!> a rolling-disk UCOSUB, gravity, the strike, solver settings, limits and the initial state.
module rollcon_disk_scene
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type, profile_half_sine, frame_tilt
    use rollcon_model, only : model_type, setup_model
    use rollcon_disk_par, only : disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_par, disk_height_time_free
    use rollcon_gen_rolling_disk, only : generated_disk_ucosub => rolling_disk_ucosub, &
        & rolling_disk_time_free
    use rollcon_problem, only : problem_type
    use rollcon_scene, only : scene_type, jacobian_analytic, height_position
    use rollcon_scene_state, only : disk_mass_properties, disk_initial_state
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate
    implicit none
    private

    public :: build_disk_problem, disk_initial_state, disk_mass_properties, simulate_scene

    !> Part id of the disk in every disk scene
    integer, parameter :: disk_part = 1
    !> Lift-off threshold as a fraction of the force scale, at least, and per unit rtol: a
    !> normal force that is exactly zero (steady motion without gravity) shows rounding noise
    !> (~1e-15 of the scale) and integration noise, measured at 6e-8 to 5e-5 of the scale for
    !> rtol 1e-8 to 1e-4 (0.5 rtol at most); the threshold stays 100 times above it and far
    !> below a real lift-off, where the force falls by the order of the scale
    real(wp), parameter :: liftoff_fraction = 1.0e-5_wp, liftoff_per_rtol = 100.0_wp

contains

    !> Model, settings and limits of a disk scene, with ucosub serving the three no-slip UCONs.
    subroutine build_disk_problem(scene, ucosub, problem, q0, u0, error)
        type(scene_type), intent(in) :: scene
        procedure(ucosub_interface) :: ucosub
        !> Set up in place: its equations refer to its model
        type(problem_type), intent(inout), target :: problem
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
        model%gravity = [0.0_wp, 0.0_wp, -scene%environment%gravity]
        model%ucosub => ucosub
        ! the hand-checked routine's F has no explicit time (docs/design.md §5), nor has the
        ! generated one's (the generator says so): the driver skips their time partials; any
        ! other routine (a user's) is asked for them
        time_free = associated(model%ucosub, rolling_disk_ucosub) &
            & .or. (associated(model%ucosub, generated_disk_ucosub) .and. rolling_disk_time_free)
        do k = 1, 2
            call model%add_ucon(k, disk_par(disk_part, scene%disk%radius, k), time_free=time_free)
        end do
        if (scene%run%height == height_position) then
            ! Z - R sin(theta) = 0 in place of its time derivative F3 (docs/design.md §5)
            call model%add_ucon(3, disk_height_par(disk_part, scene%disk%radius), &
                & disk_height_ucosub, time_free=disk_height_time_free)
        else
            call model%add_ucon(3, disk_par(disk_part, scene%disk%radius, 3), time_free=time_free)
        end if
        if (scene%strike%enabled) then
            ! Horizontal, along +Y, at the top of the rim: (0, R, 0) in the tilt frame.
            strike%part = 1
            strike%direction = [0.0_wp, 1.0_wp, 0.0_wp]
            strike%profile = profile_half_sine
            strike%start = scene%strike%time
            strike%duration = scene%strike%duration
            strike%impulse = scene%strike%impulse
            strike%frame = frame_tilt
            strike%point = [0.0_wp, scene%disk%radius, 0.0_wp]
            call model%add_force(strike)
        end if
        call setup_model(model, error)
        if (allocated(error)) return
        call problem%init(model)

        ! the scene's choice codes are the problem's and the equations' own
        problem%settings%formulation = scene%run%formulation
        problem%settings%method = scene%run%method
        problem%settings%analytic_jacobian = scene%run%jacobian == jacobian_analytic
        problem%settings%rtol = scene%run%rtol
        problem%settings%atol = scene%run%atol
        problem%settings%max_steps = scene%run%max_steps
        problem%settings%drift = scene%run%drift
        problem%settings%baumgarte_rate = scene%run%baumgarte_rate
        problem%events%part = 1  ! the disk is the model's only part
        problem%events%theta_min = scene%limits%theta_min
        problem%events%stop_on_liftoff = scene%limits%stop_on_liftoff
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

        ! |omega|^2 with omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (docs/design.md §3):
        ! e_x1 is normal to both others, and e_Z . e_z2 = cos(theta)
        associate (i => scene%initial)
            spin_squared = i%psidot**2 + i%thetadot**2 + i%phidot**2 &
                & + 2.0_wp*i%psidot*i%phidot*cos(i%theta)
        end associate
        force_scale = mass*(scene%environment%gravity + scene%disk%radius*max(spin_squared, &
            & 0.0_wp))
        ! a half-sine pulse of impulse J over T peaks at pi J / (2 T)
        if (scene%strike%enabled) force_scale = force_scale &
            & + 0.5_wp*pi*abs(scene%strike%impulse)/scene%strike%duration
        problem%events%liftoff_force = max(liftoff_fraction, liftoff_per_rtol*scene%run%rtol) &
            & *force_scale
        problem%events%has_contact = .true.
        problem%events%contact_radius = scene%disk%radius
    end subroutine set_disk_scales

    !> Build a disk scene's problem and simulate it over the scene's time with its output step.
    subroutine simulate_scene(scene, ucosub, summary, error, history, csv_path, progress, &
        & max_csv_bytes)
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
        !> Largest CSV the run may plan to write [bytes] (default: rollcon_simulation's)
        real(wp), intent(in), optional :: max_csv_bytes
        type(problem_type), target :: problem
        type(run_options_type) :: options
        real(wp) :: q0(6), u0(6)

        call build_disk_problem(scene, ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        options%end_time = scene%run%end_time
        options%output_step = scene%run%output_step
        options%progress = .false.
        if (present(progress)) options%progress = progress
        if (present(csv_path)) options%csv_path = csv_path
        if (present(max_csv_bytes)) options%max_csv_bytes = max_csv_bytes
        call simulate(problem, q0, u0, options, summary, error, history)
    end subroutine simulate_scene

end module rollcon_disk_scene
