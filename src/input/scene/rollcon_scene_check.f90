! SPDX-License-Identifier: MIT
!> The checks of a scene that involve more than one key: a start away from flat, an output
!> step within the run, compatible solver choices, an initial state in contact and rolling
!> without slip (docs/design.md §5, §6), and physical bounds on what the values imply.
module rollcon_scene_check
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : group_type
    use rollcon_namelist_bytes, only : visible
    use rollcon_scene_type, only : scene_type
    use rollcon_run_settings, only : formulation_speeds
    use rollcon_physical_ranges, only : light
    use rollcon_run_keys, only : run_choice_rule
    use rollcon_scene_state, only : disk_mass_properties, angular_velocity, disk_initial_state
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: check_scene, key_line

    !> Relative tolerance of the contact and no-slip checks of a given initial state
    real(wp), parameter :: contact_tol = 1.0e-9_wp
    !> Closest start to flat that is accepted [rad]: the 3-1-3 angles are singular where
    !> sin(theta) = 0 (docs/design.md §3)
    real(wp), parameter :: flat_margin = 1.0e-3_wp
    !> Largest mass [kg], moment of inertia [kg m^2] and energy [J] accepted: their squares,
    !> formed in norms and Newton matrices, stay below the 1.8e308 of doubles. The key ranges
    !> (docs/scenes.md) keep them far below; this guards any range widened later.
    real(wp), parameter :: derived_max = 1.0e100_wp

contains

    !> Check what involves several keys; set z and the centre velocity to the exact contact
    !> and no-slip values (a given value has passed the check within its tolerance).
    subroutine check_scene(path, groups, scene, error)
        !> Scene file, for messages
        character(len=*), intent(in) :: path
        !> Its groups, to find the line of a key
        type(group_type), intent(in) :: groups(:)
        !> The scene read; z, xdot, ydot, zdot exact on return
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, expected, got

        associate (i => scene%initial, r => scene%run)
            call require(sin(i%theta) >= flat_margin, "initial", "theta", "at least " &
                & // to_text(flat_margin) // " rad from flat (0 or pi), where the 3-1-3 Euler " &
                & // "angles are singular (sin(theta) = 0) [rad]", to_text(i%theta))
            call require(r%output_step <= r%end_time, "run", "output_step", "<= end_time = " &
                & // to_text(r%end_time) // " [s]", to_text(r%output_step))
            ! theta_min guards both sides of flat (sin(theta) = sin(theta_min)); at 0 the run
            ! would go on into the singularity itself, where the solvers fail
            call require(scene%limits%theta_min >= flat_margin .and. scene%limits%theta_min &
                & < min(i%theta, pi - i%theta), "limits", "theta_min", "at least " &
                & // to_text(flat_margin) // " (closer to flat the 3-1-3 Euler angles are " &
                & // "singular) and less than the initial distance from flat " &
                & // "min(theta, pi - theta) = " // to_text(min(i%theta, pi - i%theta)) &
                & // " [rad]", to_text(scene%limits%theta_min))
            call run_choice_rule(r%run_settings_type, key, expected, got)
            call require(len(key) == 0, "run", key, expected, got)
        end associate
        if (scene%contact%enabled) then
            associate (c => scene%contact)
                call require(key_line(groups, "contact", "mu_static") > 0, "contact", &
                    & "mu_static", "given in a &contact group (the friction coefficient " &
                    & // "that ends rolling)", "none")
                call require(c%mu_kinetic <= c%mu_static, "contact", "mu_kinetic", &
                    & "<= mu_static = " // to_text(c%mu_static) // " (kinetic friction " &
                    & // "exceeding static would stop a slip that rolling cannot hold)", &
                    & to_text(c%mu_kinetic))
                ! the modes drop rows: the ODE and DAE forms model it, not independent speeds
                ! (docs/design.md §5)
                call require(scene%run%formulation /= formulation_speeds, "run", &
                    & "formulation", "'cvode' or 'ida' in a scene with &contact (the " &
                    & // "contact's modes are integrated in the ODE and DAE forms)", "'maggi'")
            end associate
        end if
        if (scene%dissipation%rolling_resistance > 0.0_wp &
            & .or. scene%dissipation%air_viscosity > 0.0_wp) then
            ! rolling resistance is coupled to the normal force in the ODE form's
            ! accelerations and the DAE form's residual (docs/design.md §5, "Dissipation")
            call require(scene%run%formulation /= formulation_speeds, "run", "formulation", &
                & "'cvode' or 'ida' in a scene with &dissipation (its laws are integrated in " &
                & // "the ODE and DAE forms)", "'maggi'")
        end if
        if (allocated(error)) return
        call check_contact(path, groups, scene, error)
        if (allocated(error)) return
        call check_bounds(path, groups, scene, error)

    contains

        !> Record the first failed condition as an input error at the key's line.
        subroutine require(condition, group, key, expected, got)
            logical, intent(in) :: condition
            character(len=*), intent(in) :: group, key, expected, got

            if (allocated(error) .or. condition) return
            call key_error(path, groups, group, key, "must be " // expected // ", got " // got, &
                & error)
        end subroutine require

    end subroutine check_scene

    !> An input error at the line of key, or naming the default when the key is not given.
    subroutine key_error(path, groups, group, key, text, error)
        character(len=*), intent(in) :: path, group, key, text
        type(group_type), intent(in) :: groups(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: line

        line = key_line(groups, group, key)
        if (line > 0) then
            call input_error(error, visible(path), line, key, "in &" // group // " " // text)
        else
            call input_error(error, visible(path), 0, key, "in &" // group // " " // text &
                & // " (the default of &" // group // ")")
        end if
    end subroutine key_error

    !> A given z must put the rim on the ground, or above it when &contact has a restitution
    !> (the disk starts in flight, its centre's velocity the keys given, 0 for those not given);
    !> on the ground a given velocity must roll without slip, or, with &contact, keep the rim on
    !> the ground (zdot; xdot and ydot may slip).
    subroutine check_contact(path, groups, scene, error)
        character(len=*), intent(in) :: path
        type(group_type), intent(in) :: groups(:)
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: velocity_keys(3) = ["xdot", "ydot", "zdot"]
        type(scene_type) :: derived
        real(wp) :: q(6), u(6), given(3), tolerance
        integer :: lines(3), k

        derived = scene
        derived%initial%z_given = .false.
        derived%initial%velocity_given = .false.
        call disk_initial_state(derived, q, u)
        associate (i => scene%initial)
            if (i%z_given .and. scene%contact%flight .and. i%z > q(3) &
                & + contact_tol*scene%disk%radius) then
                ! flight modelled and the rim above the ground: the disk starts in flight, its
                ! centre's velocity as given, 0 where not given (a disk let go)
                i%velocity_given = .true.
                return
            end if
            if (i%z_given .and. .not. abs(i%z - q(3)) <= contact_tol*scene%disk%radius) then
                if (scene%contact%flight) then
                    call key_error(path, groups, "initial", "z", "must be at least R sin(theta) " &
                        & // "= " // to_text(q(3)) // " [m] (the rim on the ground, or above " &
                        & // "it: in flight), got " // to_text(i%z), error)
                else
                    call key_error(path, groups, "initial", "z", "must be R sin(theta) = " &
                        & // to_text(q(3)) // " [m] (rim on the ground), got " &
                        & // to_text(i%z), error)
                end if
                return
            end if
            i%z = q(3)
            if (i%velocity_given) then
                given = [i%xdot, i%ydot, i%zdot]
                lines = [(key_line(groups, "initial", velocity_keys(k)), k = 1, 3)]
                tolerance = contact_tol*(scene%disk%radius*norm2(angular_velocity(scene)) &
                    & + 1.0e-12_wp)
                do k = 1, 3
                    ! with friction a key not given takes its rolling value
                    if (lines(k) == 0 .and. scene%contact%enabled) given(k) = u(k)
                    if (lines(k) == 0 .and. .not. scene%contact%enabled) then
                        call input_error(error, visible(path), maxval(lines), velocity_keys(k), &
                            & "in &initial must be given with the other velocity keys (all of " &
                            & // "xdot, ydot, zdot or none); rolling without slip it is " &
                            & // to_text(u(k)) // " [m/s]")
                        return
                    end if
                    ! with friction the rim may slip along the ground, never into it
                    if (scene%contact%enabled .and. k < 3) cycle
                    if (.not. abs(given(k) - u(k)) <= tolerance) then
                        call key_error(path, groups, "initial", velocity_keys(k), "must be " &
                            & // to_text(u(k)) // " [m/s] to roll without slip (v_G = R omega " &
                            & // "x e_y2), got " // to_text(given(k)), error)
                        return
                    end if
                end do
            end if
            ! with friction the rim may slip along the ground, so the centre's horizontal
            ! velocity is the one given
            if (scene%contact%enabled .and. i%velocity_given) u(1:2) = given(1:2)
            i%xdot = u(1)
            i%ydot = u(2)
            i%zdot = u(3)
        end associate
    end subroutine check_contact

    !> What the values imply must be physical: speeds below light's, a strike that leaves the
    !> disk slower than light, finite mass, inertia and energies below derived_max.
    subroutine check_bounds(path, groups, scene, error)
        character(len=*), intent(in) :: path
        type(group_type), intent(in) :: groups(:)
        type(scene_type), intent(in) :: scene
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: rate_keys(3) = ["psidot  ", "thetadot", "phidot  "]
        real(wp) :: mass, inertia(3), q(6), u(6), speed, kinetic, potential, spin
        integer :: k

        call disk_mass_properties(scene, mass, inertia)
        if (.not. (ieee_is_finite(mass) .and. all(ieee_is_finite(inertia)) .and. mass > 0.0_wp &
            & .and. mass <= derived_max .and. maxval(inertia) <= derived_max .and. &
            & minval(inertia) > 0.0_wp)) then
            call key_error(path, groups, "disk", "density", "with radius " &
                & // to_text(scene%disk%radius) // " m and thickness " &
                & // to_text(scene%disk%thickness) // " m gives mass " // to_text(mass) &
                & // " kg, moments " // to_text(inertia(1)) // ", " // to_text(inertia(3)) &
                & // " kg m^2; they must be > 0 and <= " // to_text(derived_max), error)
            return
        end if
        call disk_initial_state(scene, q, u)
        speed = norm2(u(1:3)) + scene%disk%radius*norm2(angular_velocity(scene))
        k = maxloc(abs(u(4:6)), dim=1)
        if (.not. speed <= light) then
            call key_error(path, groups, "initial", trim(rate_keys(k)), "gives a rim speed " &
                & // "|v_G| + R |omega| = " // to_text(speed) // " m/s with radius " &
                & // to_text(scene%disk%radius) // " m; it must be <= the speed of light " &
                & // to_text(light) // " [m/s] (the mechanics is Newtonian)", error)
            return
        end if
        if (scene%strike%enabled .and. .not. abs(scene%strike%impulse)/mass <= light) then
            call key_error(path, groups, "strike", "impulse", "gives the disk of mass " &
                & // to_text(mass) // " kg a speed change |impulse|/mass = " &
                & // to_text(abs(scene%strike%impulse)/mass) // " m/s; it must be <= the " &
                & // "speed of light " // to_text(light) // " [m/s] (the mechanics is Newtonian)", &
                & error)
            return
        end if
        spin = u(6) + u(4)*cos(q(5))
        kinetic = 0.5_wp*(mass*sum(u(1:3)**2) + inertia(1)*(u(5)**2 + (u(4)*sin(q(5)))**2) &
            & + inertia(3)*spin**2)
        potential = mass*scene%environment%gravity*q(3)
        if (.not. (abs(kinetic) <= derived_max .and. abs(potential) <= derived_max)) then
            call key_error(path, groups, "initial", trim(rate_keys(k)), "gives a kinetic " &
                & // "energy " // to_text(kinetic) // " J and a potential energy " &
                & // to_text(potential) // " J; both must be <= " // to_text(derived_max) &
                & // " [J]", error)
        end if
    end subroutine check_bounds

    !> Line where key is given in group, 0 when it is not given.
    pure integer function key_line(groups, group, key) result(line)
        !> Groups as scanned
        type(group_type), intent(in) :: groups(:)
        !> Group and key, lowercase
        character(len=*), intent(in) :: group, key
        integer :: i, j

        line = 0
        do i = 1, size(groups)
            if (groups(i)%name /= group) cycle
            do j = 1, size(groups(i)%assignments)
                if (groups(i)%assignments(j)%key == key) line = groups(i)%assignments(j)%line
            end do
        end do
    end function key_line

end module rollcon_scene_check
