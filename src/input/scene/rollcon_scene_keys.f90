! SPDX-License-Identifier: MIT
!> The table of every key a scene file may hold (rollcon_keys): its group, kind, unit, allowed
!> range or choices, and where its value goes in a scene_type. The &run keys are the run
!> settings' own table (rollcon_run_keys) plus the contact's `height`. Adding a key is one line
!> in bind_keys (and its component in rollcon_scene_type, its row in docs/scenes.md).
module rollcon_scene_keys
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_keys, only : key_type, option_type, real_key, logical_key, choice_key, &
        & option_code, option_name
    use rollcon_run_keys, only : bind_run_keys, time_min, time_max
    use rollcon_physical_ranges, only : light, length_max, length_min, position_max, angle_max, &
        & rate_max, gravity_max
    use rollcon_scene_type, only : scene_type, height_velocity, height_position
    implicit none
    private

    public :: bind_keys, scene_groups, choice_code, choice_name

    !> Groups of a scene file, in the order the documentation gives them
    character(len=*), parameter :: scene_groups(*) = [character(len=11) :: "disk", &
        & "environment", "initial", "strike", "run", "limits", "contact", "dissipation"]

    !> Densities [kg/m^3]: lighter than air is not a disk; 1e5 is four times osmium's
    real(wp), parameter :: density_min = 1.0e-3_wp, density_max = 1.0e5_wp
    !> Largest impulse [N s]
    real(wp), parameter :: impulse_max = 1.0e9_wp
    !> Largest friction coefficient [-]: far above any pair of real surfaces (rubber on dry
    !> rough stone reaches about 1.5); the contact never slides below it in practice
    real(wp), parameter :: friction_max = 100.0_wp
    !> Largest air viscosity [Pa s]: a thousand times glycerol's (1.4 Pa s at 20 C); air is
    !> 1.8e-5
    real(wp), parameter :: viscosity_max = 1.0e3_wp

contains

    !> The table of keys, each pointing into scene; the pointers live as long as scene.
    subroutine bind_keys(scene, keys)
        !> The scene the values go to
        type(scene_type), target, intent(inout) :: scene
        type(key_type), allocatable, intent(out) :: keys(:)

        associate (d => scene%disk, i => scene%initial, s => scene%strike, r => scene%run, &
                & l => scene%limits)
            keys = [ &
                & real_key("disk", "radius", d%radius, "m", length_min, length_max), &
                & real_key("disk", "thickness", d%thickness, "m", length_min, length_max), &
                & real_key("disk", "density", d%density, "kg/m^3", density_min, density_max), &
                & real_key("environment", "gravity", scene%environment%gravity, "m/s^2", &
                & 0.0_wp, gravity_max), &
                & real_key("initial", "psi", i%psi, "rad", -angle_max, angle_max), &
                & real_key("initial", "theta", i%theta, "rad", 0.0_wp, pi, .true., .true.), &
                & real_key("initial", "phi", i%phi, "rad", -angle_max, angle_max), &
                & real_key("initial", "psidot", i%psidot, "rad/s", -rate_max, rate_max), &
                & real_key("initial", "thetadot", i%thetadot, "rad/s", -rate_max, rate_max), &
                & real_key("initial", "phidot", i%phidot, "rad/s", -rate_max, rate_max), &
                & real_key("initial", "speed", i%speed, "m/s", -light, light), &
                & real_key("initial", "x", i%x, "m", -position_max, position_max), &
                & real_key("initial", "y", i%y, "m", -position_max, position_max), &
                & real_key("initial", "z", i%z, "m", -position_max, position_max), &
                & real_key("initial", "xdot", i%xdot, "m/s", -light, light), &
                & real_key("initial", "ydot", i%ydot, "m/s", -light, light), &
                & real_key("initial", "zdot", i%zdot, "m/s", -light, light), &
                & real_key("strike", "time", s%time, "s", 0.0_wp, time_max), &
                & real_key("strike", "duration", s%duration, "s", time_min, time_max), &
                & real_key("strike", "impulse", s%impulse, "N s", -impulse_max, impulse_max), &
                & bind_run_keys(r%run_settings_type), &
                & choice_key("run", "height", r%height, [option_type("velocity", &
                & height_velocity), option_type("position", height_position)]), &
                & real_key("limits", "theta_min", l%theta_min, "rad", 0.0_wp, pi, &
                & upper_open=.true.), &
                & logical_key("limits", "stop_on_liftoff", l%stop_on_liftoff), &
                & real_key("contact", "mu_static", scene%contact%mu_static, "", 0.0_wp, &
                & friction_max, lower_open=.true.), &
                & real_key("contact", "mu_kinetic", scene%contact%mu_kinetic, "", 0.0_wp, &
                & friction_max, lower_open=.true.), &
                & real_key("contact", "restitution", scene%contact%restitution, "", 0.0_wp, &
                & 1.0_wp), &
                & real_key("dissipation", "rolling_resistance", &
                & scene%dissipation%rolling_resistance, "m", 0.0_wp, length_max), &
                & real_key("dissipation", "air_viscosity", scene%dissipation%air_viscosity, &
                & "Pa s", 0.0_wp, viscosity_max)]
        end associate
    end subroutine bind_keys

    !> Code of the option named word (any case) of the &run choice key name of a scene
    !> ('formulation', 'cvode'; 'height', 'position'), 0 when none.
    function choice_code(name, word) result(code)
        character(len=*), intent(in) :: name, word
        integer :: code
        type(scene_type), target :: scene
        type(key_type), allocatable :: keys(:)

        call bind_keys(scene, keys)
        code = option_code(keys, "run", name, word)
    end function choice_code

    !> Name of the option with this code of the &run choice key name of a scene, "?" when none.
    function choice_name(name, code) result(word)
        character(len=*), intent(in) :: name
        integer, intent(in) :: code
        character(len=:), allocatable :: word
        type(scene_type), target :: scene
        type(key_type), allocatable :: keys(:)

        call bind_keys(scene, keys)
        word = option_name(keys, "run", name, code)
    end function choice_name

end module rollcon_scene_keys
