! SPDX-License-Identifier: MIT
!> What follows from a scene's values: the disk's mass properties, its angular velocity, and
!> the one initial state in contact and rolling without slip (docs/design.md §3 and §5).
module rollcon_scene_state
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_scene_type, only : scene_type
    implicit none
    private

    public :: disk_mass_properties, angular_velocity, disk_initial_state
    public :: upright_critical_speed


contains

    !> Mass [kg] and principal moments (A about a diameter, C about the axis) [kg m^2] of a
    !> uniform disk (docs/design.md §5).
    pure subroutine disk_mass_properties(scene, mass, inertia)
        !> Scene with the disk
        type(scene_type), intent(in) :: scene
        !> Mass [kg]
        real(wp), intent(out) :: mass
        !> Principal moments (A, A, C) [kg m^2]
        real(wp), intent(out) :: inertia(3)

        associate (r => scene%disk%radius, h => scene%disk%thickness)
            mass = scene%disk%density*pi*r**2*h
            inertia(1:2) = mass*(3.0_wp*r**2 + h**2)/12.0_wp
            inertia(3) = 0.5_wp*mass*r**2
        end associate
    end subroutine disk_mass_properties

    !> The speed [m/s] above which straight upright rolling is stable (docs/design.md §5):
    !> v^2 = m g R^3 A / (C (C + m R^2)); g R/3 for a thin disk. 0 without gravity.
    pure real(wp) function upright_critical_speed(scene) result(speed)
        type(scene_type), intent(in) :: scene
        real(wp) :: mass, inertia(3)

        call disk_mass_properties(scene, mass, inertia)
        associate (r => scene%disk%radius, g => scene%environment%gravity, a => inertia(1), &
                & c => inertia(3))
            speed = sqrt(mass*g*r**3*a/(c*(c + mass*r**2)))
        end associate
    end function upright_critical_speed

    !> Angular velocity of the disk at the start, ground components [rad/s] (docs/design.md
    !> §3): psidot e_Z + thetadot e_x1 + phidot e_z2.
    pure function angular_velocity(scene) result(omega)
        !> Scene with the initial angles and rates
        type(scene_type), intent(in) :: scene
        real(wp) :: omega(3)

        associate (s => scene%initial)
            omega = s%psidot*[0.0_wp, 0.0_wp, 1.0_wp] &
                & + s%thetadot*[cos(s%psi), sin(s%psi), 0.0_wp] &
                & + s%phidot*[sin(s%theta)*sin(s%psi), -sin(s%theta)*cos(s%psi), cos(s%theta)]
        end associate
    end function angular_velocity

    !> Coordinates and velocities at the start: the centre on the contact (Z = R sin(theta))
    !> and moving without slip (v_G = R omega x e_y2, from v_G + omega x r_GC = 0 with
    !> r_GC = -R e_y2), unless the scene gives z or the centre velocity (a scene read from a
    !> file holds these exact values, given or not).
    pure subroutine disk_initial_state(scene, q, u)
        !> Scene with the disk and the initial state
        type(scene_type), intent(in) :: scene
        !> (X, Y, Z, psi, theta, phi) [m, rad]
        real(wp), intent(out) :: q(6)
        !> Their rates [m/s, rad/s]
        real(wp), intent(out) :: u(6)
        real(wp) :: omega(3), e_y2(3)

        associate (s => scene%initial, r => scene%disk%radius)
            q = [s%x, s%y, r*sin(s%theta), s%psi, s%theta, s%phi]
            if (s%z_given) q(3) = s%z
            omega = angular_velocity(scene)
            e_y2 = [-cos(s%theta)*sin(s%psi), cos(s%theta)*cos(s%psi), sin(s%theta)]
            u(1:3) = r*[omega(2)*e_y2(3) - omega(3)*e_y2(2), &
                & omega(3)*e_y2(1) - omega(1)*e_y2(3), omega(1)*e_y2(2) - omega(2)*e_y2(1)]
            if (s%velocity_given) u(1:3) = [s%xdot, s%ydot, s%zdot]
            u(4:6) = [s%psidot, s%thetadot, s%phidot]
        end associate
    end subroutine disk_initial_state

end module rollcon_scene_state
