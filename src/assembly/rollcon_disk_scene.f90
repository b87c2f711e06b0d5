! SPDX-License-Identifier: MIT
!> Turns a disk scene into a problem (the scene's assembly): the disk as a rigid part, three
!> no-slip UCONs served by a rolling-disk UCOSUB, gravity, the strike, the rim's dissipation,
!> solver settings, the watches of its theta limit, its rim contact and its dissipation, and
!> the initial state.
module rollcon_disk_scene
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, stat_ucon
    use rollcon_text, only : to_text
    use rollcon_ucosub_catalog, only : builtin_ucosub_name, builtin_ucosubs_for_par
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type, profile_half_sine, frame_tilt
    use rollcon_model, only : model_type, setup_model
    use rollcon_disk_par, only : disk_par
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_par, disk_height_time_free
    use rollcon_problem, only : problem_type
    use rollcon_theta_watch, only : theta_watch_type, new_theta_watch
    use rollcon_contact_watch, only : contact_watch_type, mode_sliding, mode_flight
    use rollcon_dissipation_watch, only : dissipation_watch_type
    use rollcon_rim_dissipation, only : air_coefficient
    use rollcon_scene, only : scene_type, height_position
    use rollcon_scene_state, only : disk_mass_properties, disk_initial_state
    implicit none
    private

    public :: build_disk_problem, disk_initial_state, disk_mass_properties

    !> Part id of the disk in every disk scene (and its place in model order)
    integer, parameter, public :: disk_part = 1
    !> Lift-off threshold as a fraction of the force scale, at least, and per unit rtol: a
    !> normal force that is exactly zero (steady motion without gravity) shows rounding noise
    !> (~1e-15 of the scale) and integration noise, measured at 6e-8 to 5e-5 of the scale for
    !> rtol 1e-8 to 1e-4 (0.5 rtol at most); the threshold stays 100 times above it and far
    !> below a real lift-off, where the force falls by the order of the scale
    real(wp), parameter :: liftoff_fraction = 1.0e-5_wp, liftoff_per_rtol = 100.0_wp

contains

    !> An error of a no-slip UCON from the routine that served it: when that routine is not one
    !> a disk's PAR suits (`--ucosub knife_edge` on a scene), the message says that this routine
    !> refused the scene's PAR, what that PAR is, and which built-in routines take it. Nothing is
    !> added when the routine is one of those (the error is then in a value).
    subroutine add_par_hint(model, ucosub, error)
        type(model_type), intent(in) :: model
        procedure(ucosub_interface) :: ucosub
        type(error_type), intent(inout) :: error
        procedure(ucosub_interface), pointer :: served
        character(len=:), allocatable :: name, suits
        logical :: time_free
        integer :: k

        if (error%stat /= stat_ucon) return
        do k = 1, size(model%ucons)
            associate (ucon => model%ucons(k))
                if (index(error%message, "UCON/" // to_text(ucon%id) // ":") /= 1) cycle
                if (len(ucon%routine) > 0) return
                served => ucosub
                name = builtin_ucosub_name(served, time_free)
                suits = builtin_ucosubs_for_par(ucon%par)
                if (len(name) > 0) then
                    if (index(", " // suits // ", ", ", " // name // ", ") > 0) return
                    name = "the built-in " // name
                else
                    name = "a routine of your own"
                end if
                error%message = error%message // "; the routine chosen for the scene's no-slip " &
                    & // "UCONs (--ucosub), here " // name // ", refused the PAR a disk scene " &
                    & // "gives them, the rolling disk's (part, codes 21 22 23 14 15 24 25 26, " &
                    & // "R, component)"
                if (len(suits) > 0) error%message = error%message // "; routines that take it: " &
                    & // suits
                return
            end associate
        end do
    end subroutine add_par_hint

    !> Model, settings and limits of a disk scene, with ucosub serving the three no-slip UCONs.
    subroutine build_disk_problem(scene, ucosub, problem, q0, u0, error)
        type(scene_type), intent(in) :: scene
        !> The routine of the no-slip UCONs
        procedure(ucosub_interface) :: ucosub
        !> Set up in place: its equations refer to its model
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(out) :: q0(6), u0(6)
        type(error_type), allocatable, intent(out) :: error
        type(model_type), target :: model
        type(part_type) :: disk
        type(applied_force_type) :: strike
        integer :: k

        disk%id = disk_part
        call disk_mass_properties(scene, disk%mass, disk%inertia)
        call model%add_part(disk)
        ! the rim contact watch reports the contact's force, the sum of the three UCONs' on the
        ! disk: no reaction columns of its own (rollcon_reaction_watch)
        model%report_reactions = .false.
        model%gravity = [0.0_wp, 0.0_wp, -scene%environment%gravity]
        ! the model's UCOSUB serves the no-slip UCONs; setup_model spares the driver their time
        ! partials when it is a built-in routine whose F has no explicit time (the hand-checked
        ! disk, docs/design.md §5, and the generated one), and asks any other (a user's)
        model%ucosub => ucosub
        do k = 1, 2
            call model%add_ucon(k, disk_par(disk_part, scene%disk%radius, k))
        end do
        if (scene%run%height == height_position) then
            ! Z - R sin(theta) = 0 in place of its time derivative F3 (docs/design.md §5)
            call model%add_ucon(3, disk_height_par(disk_part, scene%disk%radius), &
                & disk_height_ucosub, time_free=disk_height_time_free, routine="disk_height")
        else
            call model%add_ucon(3, disk_par(disk_part, scene%disk%radius, 3))
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
        if (allocated(error)) then
            call add_par_hint(model, ucosub, error)
            return
        end if
        call problem%init(model)
        problem%settings = scene%run%run_settings_type
        ! what the disk scene watches: its theta limit (a stop, in the disk's words), then its
        ! contact with the ground; the rows' contact columns and the lift-off come from there
        call problem%add_watch(disk_theta_watch(scene))
        call disk_initial_state(scene, q0, u0)
        call problem%add_watch(disk_contact_watch(scene, disk%mass, q0, u0))
        if (scene%dissipation%rolling_resistance > 0.0_wp &
            & .or. scene%dissipation%air_viscosity > 0.0_wp) then
            ! the rim's rolling resistance and air layer (docs/design.md §5, "Dissipation"):
            ! the normal force is UCON 3's, the centre height Z the part's third coordinate
            problem%eq%dissipation%part = disk_part
            problem%eq%dissipation%normal = 3
            problem%eq%dissipation%height_column = 3
            problem%eq%dissipation%rolling_resistance = scene%dissipation%rolling_resistance
            problem%eq%dissipation%air = air_coefficient(scene%dissipation%air_viscosity, &
                & scene%disk%radius)
            call problem%add_watch(dissipation_watch_type(part=disk_part))
        end if
    end subroutine build_disk_problem

    !> The disk's theta limit: a stop at &limits theta_min, worded for the disk.
    function disk_theta_watch(scene) result(watch)
        type(scene_type), intent(in) :: scene
        type(theta_watch_type) :: watch

        watch = new_theta_watch(scene%limits%theta_min, rebase=.false.)
        watch%worded_part = disk_part
        watch%flat_words = "the disk lies nearly flat"
    end function disk_theta_watch

    !> The disk's rim on the ground, with the scale its lift-off is judged by. Force scale: the
    !> weight m g, plus m R |omega0|^2 (the centripetal force of the initial spin, which sets
    !> the normal force without gravity), plus the strike's peak force; a lift-off is a normal
    !> force below -max(liftoff_fraction, liftoff_per_rtol rtol) times it.
    pure function disk_contact_watch(scene, mass, q0, u0) result(watch)
        type(scene_type), intent(in) :: scene
        !> Disk mass [kg]
        real(wp), intent(in) :: mass
        !> The start [m, rad, m/s, rad/s]: with &contact, a start that slips starts sliding,
        !> and with a restitution a start above the ground starts in flight
        real(wp), intent(in) :: q0(6), u0(6)
        type(contact_watch_type) :: watch
        real(wp) :: spin_squared, force_scale, slip(2)

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
        watch%part = disk_part
        watch%radius = scene%disk%radius
        watch%stop_on_liftoff = scene%limits%stop_on_liftoff
        watch%liftoff_force = max(liftoff_fraction, liftoff_per_rtol*scene%run%rtol)*force_scale
        if (.not. scene%contact%enabled) return
        ! the no-slip UCONs 1 and 2 are the contact point's horizontal velocity, UCON 3 its
        ! height's (docs/design.md §5)
        watch%mu_static = scene%contact%mu_static
        watch%mu_kinetic = scene%contact%mu_kinetic
        watch%tangential = [1, 2]
        watch%normal = 3
        ! a restitution given: flight and impacts modelled, a lift-off a switch (not a stop)
        watch%flight = scene%contact%flight
        watch%restitution = scene%contact%restitution
        if (watch%flight) watch%stop_on_liftoff = .false.
        ! a start slips when its slip is above the slip's integration error, atol + rtol (|v_G|
        ! + R |omega|) (rollcon_contact_watch): the no-slip rates the reader completes leave a
        ! slip of rounding (1e-17 m/s), which is none
        slip = watch%slip_velocity(q0, u0)
        if (norm2(slip) > scene%run%atol + scene%run%rtol*(norm2(u0(1:3)) &
            & + scene%disk%radius*norm2(u0(4:6)))) then
            watch%initial_mode = mode_sliding
            watch%initial_direction = slip/norm2(slip)
        end if
        ! the reader puts a rim on the ground at exactly R sin(theta)
        if (watch%flight .and. watch%height_residual(q0) > 0.0_wp) watch%initial_mode = mode_flight
    end function disk_contact_watch

end module rollcon_disk_scene
