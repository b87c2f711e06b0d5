! SPDX-License-Identifier: MIT
!> The scene type with its defaults, and the checks a scene must pass: physical values, known
!> choices, and an initial state in contact and rolling without slip (DESIGN.md sections 5, 6).
module rollcon_scene_type
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text
    use rollcon_scene_lexer, only : group_type
    use rollcon_scene_keys, only : key_line
    implicit none
    private

    public :: scene_type, check_scene, rolling_velocity

    real(wp), parameter :: pi = acos(-1.0_wp)
    !> Relative tolerance of the contact and no-slip checks of a given initial state
    real(wp), parameter :: contact_tol = 1.0e-9_wp

    !> A scene: disk, environment, initial state, strike, run settings and limits
    type :: scene_type
        !> File it was read from
        character(len=:), allocatable :: path
        !> File base name without .nml
        character(len=:), allocatable :: name
        !> &disk: radius [m] > 0
        real(wp) :: radius = 0.1_wp
        !> &disk: thickness [m] > 0; enters the inertia only
        real(wp) :: thickness = 0.003_wp
        !> &disk: density [kg/m^3] > 0
        real(wp) :: density = 7800.0_wp
        !> &environment: gravity [m/s^2] >= 0, along -Z
        real(wp) :: gravity = 9.81_wp
        !> &initial: 3-1-3 Euler angles of the principal axes [rad]; theta in (0, pi)
        real(wp) :: psi = 0.0_wp, theta = pi/2, phi = 0.0_wp
        !> &initial: Euler-angle rates [rad/s]
        real(wp) :: psidot = 0.0_wp, thetadot = 0.0_wp, phidot = 0.0_wp
        !> &initial: centre position [m]
        real(wp) :: x = 0.0_wp, y = 0.0_wp
        !> &initial: z was given (it must then be R sin(theta) within 1e-9 R)
        logical :: z_given = .false.
        !> &initial: centre height [m]; read_scene sets it to R sin(theta), given or not
        real(wp) :: z = 0.0_wp
        !> &initial: xdot, ydot, zdot were given (all three, rolling without slip within
        !> 1e-9 (R |omega| + 1e-12))
        logical :: velocity_given = .false.
        !> &initial: centre velocity [m/s]; read_scene sets it to the no-slip value
        !> R omega x e_y2, given or not
        real(wp) :: xdot = 0.0_wp, ydot = 0.0_wp, zdot = 0.0_wp
        !> The file has a &strike group
        logical :: has_strike = .false.
        !> &strike time: start of the pulse [s] >= 0
        real(wp) :: strike_time = 2.0_wp
        !> &strike duration: length of the half-sine pulse [s] > 0
        real(wp) :: strike_duration = 0.01_wp
        !> &strike impulse: along +Y at the top of the rim [N s]
        real(wp) :: strike_impulse = 0.01_wp
        !> &run: end time [s] > 0
        real(wp) :: end_time = 10.0_wp
        !> &run: output step [s], > 0 and <= end_time
        real(wp) :: output_step = 0.01_wp
        !> &run: 'ida' (DAE) or 'cvode' (ODE)
        character(len=:), allocatable :: formulation
        !> &run: 'bdf' or 'adams' (cvode only)
        character(len=:), allocatable :: method
        !> &run: 'projection', 'baumgarte' or 'none' (the last two cvode only)
        character(len=:), allocatable :: drift
        !> &run: 'analytic' or 'dq' (difference quotients)
        character(len=:), allocatable :: jacobian
        !> &run: 'velocity' (F3 as a velocity constraint) or 'position' (Z - R sin(theta) = 0)
        character(len=:), allocatable :: height
        !> &run: relative tolerance, in (0, 1)
        real(wp) :: rtol = 1.0e-8_wp
        !> &run: absolute tolerance, > 0
        real(wp) :: atol = 1.0e-10_wp
        !> &run: Baumgarte stabilisation rate [1/s] > 0
        real(wp) :: baumgarte_rate = 10.0_wp
        !> &run: most integrator steps, > 0
        integer :: max_steps = 500000
        !> &limits: stop when theta comes within this of flat, on either side (sin(theta) <
        !> sin(theta_min)) [rad]; >= 1e-3 and < min(theta, pi - theta) initially
        real(wp) :: theta_min = 0.05_wp
        !> &limits: stop when the normal force turns negative
        logical :: stop_on_liftoff = .true.
    end type scene_type

contains

    !> Check the values of a scene read from path; set z and the centre velocity to the exact
    !> contact and no-slip values (a given value has passed the check within its tolerance).
    subroutine check_scene(path, groups, scene, error)
        !> Scene file, for messages
        character(len=*), intent(in) :: path
        !> Its groups, to find the line of a key
        type(group_type), intent(in) :: groups(:)
        !> The scene read; z, xdot, ydot, zdot exact on return
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        !> Closest start to flat that is accepted [rad]
        real(wp), parameter :: flat_margin = 1.0e-3_wp

        associate (s => scene)
            call require(s%radius > 0.0_wp, "disk", "radius", "> 0 [m]", to_text(s%radius))
            call require(s%thickness > 0.0_wp, "disk", "thickness", "> 0 [m]", &
                & to_text(s%thickness))
            call require(s%density > 0.0_wp, "disk", "density", "> 0 [kg/m^3]", &
                & to_text(s%density))
            call require(s%gravity >= 0.0_wp, "environment", "gravity", ">= 0 [m/s^2]", &
                & to_text(s%gravity))
            call require(s%theta > 0.0_wp .and. s%theta < pi, "initial", "theta", &
                & "in (0, pi) [rad]", to_text(s%theta))
            ! The 3-1-3 angles are singular where sin(theta) = 0: psi and phi are not defined
            ! apart there, and psidot, phidot grow without bound near it (DESIGN section 3).
            call require(sin(s%theta) >= flat_margin, "initial", "theta", "at least " &
                & // to_text(flat_margin) // " rad from flat (0 or pi), where the 3-1-3 Euler " &
                & // "angles are singular (sin(theta) = 0) [rad]", to_text(s%theta))
            call require(s%strike_time >= 0.0_wp, "strike", "time", ">= 0 [s]", &
                & to_text(s%strike_time))
            call require(s%strike_duration > 0.0_wp, "strike", "duration", "> 0 [s]", &
                & to_text(s%strike_duration))
            call require(s%end_time > 0.0_wp, "run", "end_time", "> 0 [s]", to_text(s%end_time))
            call require(s%output_step > 0.0_wp .and. s%output_step <= s%end_time, "run", &
                & "output_step", "> 0 and <= end_time = " // to_text(s%end_time) // " [s]", &
                & to_text(s%output_step))
            call require(s%rtol > 0.0_wp .and. s%rtol < 1.0_wp, "run", "rtol", &
                & "> 0 and < 1", to_text(s%rtol))
            call require(s%atol > 0.0_wp, "run", "atol", "> 0", to_text(s%atol))
            call require(s%baumgarte_rate > 0.0_wp, "run", "baumgarte_rate", "> 0 [1/s]", &
                & to_text(s%baumgarte_rate))
            call require(s%max_steps > 0, "run", "max_steps", "> 0", to_text(s%max_steps))
            ! theta_min guards both sides of flat (sin(theta) = sin(theta_min)); at 0 the run
            ! would go on into the singularity itself, where the solvers fail
            call require(s%theta_min >= flat_margin .and. s%theta_min < min(s%theta, &
                & pi - s%theta), "limits", "theta_min", "at least " // to_text(flat_margin) &
                & // " (closer to flat the 3-1-3 Euler angles are singular) and less than the " &
                & // "initial distance from flat min(theta, pi - theta) = " &
                & // to_text(min(s%theta, pi - s%theta)) // " [rad]", to_text(s%theta_min))
            call require_choice(s%formulation, "formulation", [character(len=10) :: "ida", &
                & "cvode"])
            call require_choice(s%method, "method", [character(len=10) :: "bdf", "adams"])
            call require_choice(s%drift, "drift", [character(len=10) :: "projection", &
                & "baumgarte", "none"])
            call require_choice(s%jacobian, "jacobian", [character(len=10) :: "analytic", "dq"])
            ! CVODE's projection works with BDF only (CVodeSetProjFn refuses Adams)
            call require(.not. (s%formulation == "cvode" .and. s%method == "adams" .and. &
                & s%drift == "projection"), "run", &
                & "drift", "'baumgarte' or 'none' with method = 'adams' (CVODE projects only " &
                & // "with BDF)", "'" // s%drift // "'")
            call require_choice(s%height, "height", [character(len=10) :: "velocity", &
                & "position"])
            if (s%formulation == "ida") then
                call require(s%method == "bdf", "run", "method", "'bdf' with formulation " &
                    & // "'ida' (IDA is a BDF code; 'adams' needs 'cvode')", "'" // s%method // "'")
                call require(s%drift == "projection", "run", "drift", "left out with " &
                    & // "formulation 'ida' (IDA has no drift; 'baumgarte' and 'none' are for " &
                    & // "'cvode')", "'" // s%drift // "'")
            end if
        end associate
        if (allocated(error)) return
        call check_contact(path, groups, scene, error)

    contains

        !> Record the first failed condition as an input error at the key's line.
        subroutine require(condition, group, key, expected, got)
            logical, intent(in) :: condition
            character(len=*), intent(in) :: group, key, expected, got
            integer :: line

            if (allocated(error) .or. condition) return
            line = key_line(groups, group, key)
            if (line > 0) then
                call input_error(error, path, line, key, "must be " // expected // ", got " &
                    & // got)
            else
                call input_error(error, path, 0, key, "must be " // expected // ", got " &
                    & // got // " (the default of &" // group // ")")
            end if
        end subroutine require

        !> A choice of &run must be one of the options.
        subroutine require_choice(value, key, options)
            character(len=*), intent(in) :: value, key, options(:)
            character(len=:), allocatable :: list
            integer :: k

            list = "'" // trim(options(1)) // "'"
            do k = 2, size(options)
                if (k < size(options)) then
                    list = list // ", '" // trim(options(k)) // "'"
                else
                    list = list // " or '" // trim(options(k)) // "'"
                end if
            end do
            call require(any(options == value), "run", key, list, "'" // value // "'")
        end subroutine require_choice

    end subroutine check_scene

    !> A given z must put the rim on the ground; a given velocity must roll without slip.
    subroutine check_contact(path, groups, scene, error)
        character(len=*), intent(in) :: path
        type(group_type), intent(in) :: groups(:)
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: velocity_keys(3) = ["xdot", "ydot", "zdot"]
        real(wp) :: z, velocity(3), given(3), tolerance
        integer :: lines(3), k

        z = scene%radius*sin(scene%theta)
        if (scene%z_given) then
            if (.not. abs(scene%z - z) <= contact_tol*scene%radius) then
                call input_error(error, path, key_line(groups, "initial", "z"), "z", &
                    & "must be R sin(theta) = " // to_text(z) // " [m] (rim on the ground), got " &
                    & // to_text(scene%z))
                return
            end if
        end if
        scene%z = z

        velocity = rolling_velocity(scene)
        if (scene%velocity_given) then
            given = [scene%xdot, scene%ydot, scene%zdot]
            do k = 1, 3
                lines(k) = key_line(groups, "initial", velocity_keys(k))
            end do
            tolerance = contact_tol*(scene%radius*norm2(angular_velocity(scene)) + 1.0e-12_wp)
            do k = 1, 3
                if (lines(k) == 0) then
                    call input_error(error, path, maxval(lines), velocity_keys(k), "must be " &
                        & // "given with the other velocity keys (all of xdot, ydot, zdot or " &
                        & // "none); rolling without slip it is " // to_text(velocity(k)) &
                        & // " [m/s]")
                    return
                end if
                if (.not. abs(given(k) - velocity(k)) <= tolerance) then
                    call input_error(error, path, lines(k), velocity_keys(k), "must be " &
                        & // to_text(velocity(k)) // " [m/s] to roll without slip " &
                        & // "(v_G = R omega x e_y2), got " // to_text(given(k)))
                    return
                end if
            end do
        end if
        scene%xdot = velocity(1)
        scene%ydot = velocity(2)
        scene%zdot = velocity(3)
    end subroutine check_contact

    !> Angular velocity of the disk in ground components [rad/s] (DESIGN.md section 3).
    pure function angular_velocity(scene) result(omega)
        type(scene_type), intent(in) :: scene
        real(wp) :: omega(3)

        associate (psi => scene%psi, theta => scene%theta)
            omega = scene%psidot*[0.0_wp, 0.0_wp, 1.0_wp] &
                & + scene%thetadot*[cos(psi), sin(psi), 0.0_wp] &
                & + scene%phidot*[sin(theta)*sin(psi), -sin(theta)*cos(psi), cos(theta)]
        end associate
    end function angular_velocity

    !> Centre velocity [m/s] of the disk rolling without slip: v_G = R omega x e_y2, from
    !> v_G + omega x r_GC = 0 with r_GC = -R e_y2 (DESIGN.md section 5).
    pure function rolling_velocity(scene) result(velocity)
        !> Scene with the disk and the initial angles and rates
        type(scene_type), intent(in) :: scene
        real(wp) :: velocity(3)
        real(wp) :: omega(3), e_y2(3)

        omega = angular_velocity(scene)
        associate (psi => scene%psi, theta => scene%theta)
            e_y2 = [-cos(theta)*sin(psi), cos(theta)*cos(psi), sin(theta)]
        end associate
        velocity = scene%radius*[omega(2)*e_y2(3) - omega(3)*e_y2(2), &
            & omega(3)*e_y2(1) - omega(1)*e_y2(3), omega(1)*e_y2(2) - omega(2)*e_y2(1)]
    end function rolling_velocity

end module rollcon_scene_type
