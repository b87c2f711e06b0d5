! SPDX-License-Identifier: MIT
!> The table of every key a scene file may hold: its group, kind, unit, allowed range or
!> choices, and where its value goes in a scene_type. Adding a key is one line in bind_keys
!> (and its component in rollcon_scene_type, its row in docs/scenes.md).
module rollcon_scene_keys
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_scene_lexer, only : to_lower
    use rollcon_scene_type, only : scene_type, formulation_cvode, formulation_ida, method_bdf, &
        & method_adams, drift_none, drift_projection, drift_baumgarte, jacobian_analytic, &
        & jacobian_dq, height_velocity, height_position
    implicit none
    private

    public :: key_type, option_type, bind_keys, find_key, key_list, scene_groups
    public :: kind_real, kind_integer, kind_logical, kind_choice, choice_code, choice_name

    !> Groups of a scene file, in the order the documentation gives them
    character(len=*), parameter :: scene_groups(*) = [character(len=11) :: "disk", &
        & "environment", "initial", "strike", "run", "limits"]

    !> Value kinds
    integer, parameter :: kind_real = 1, kind_integer = 2, kind_logical = 3, kind_choice = 4

    !> Speed of light [m/s]: the bound of every speed, rigid-body mechanics being Newtonian
    real(wp), parameter :: light = 299792458.0_wp
    !> Largest length [m] (1000 km) and smallest (1 um): beyond, a rigid disk with SI
    !> tolerances is not a meaningful model
    real(wp), parameter :: length_max = 1.0e6_wp, length_min = 1.0e-6_wp
    !> Largest position [m]: a start 1e9 m away still resolves 1e-7 m in a double
    real(wp), parameter :: position_max = 1.0e9_wp
    !> Largest angle [rad]: sin and cos of 1e6 rad still resolve 1e-10 rad
    real(wp), parameter :: angle_max = 1.0e6_wp
    !> Largest rate [rad/s]
    real(wp), parameter :: rate_max = 1.0e6_wp
    !> Densities [kg/m^3]: lighter than air is not a disk; 1e5 is four times osmium's
    real(wp), parameter :: density_min = 1.0e-3_wp, density_max = 1.0e5_wp
    !> Largest gravity [m/s^2], 36 times the Sun's surface gravity
    real(wp), parameter :: gravity_max = 1.0e4_wp
    !> Longest time [s] (about 32 years) and shortest (1 ns) a run, step or pulse may take
    real(wp), parameter :: time_max = 1.0e9_wp, time_min = 1.0e-9_wp
    !> Largest impulse [N s]
    real(wp), parameter :: impulse_max = 1.0e9_wp
    !> Tightest rtol: SUNDIALS cannot meet a relative accuracy near the 2.2e-16 of doubles
    real(wp), parameter :: rtol_min = 1.0e-15_wp
    !> atol [state units]: below 1e-20 the error weights 1/atol approach overflow in the
    !> weighted norms' squares; above 1e3 nothing is resolved
    real(wp), parameter :: atol_min = 1.0e-20_wp, atol_max = 1.0e3_wp
    !> Largest Baumgarte rate [1/s]: its square multiplies the drift
    real(wp), parameter :: baumgarte_max = 1.0e6_wp

    !> One option of a choice key and its code
    type :: option_type
        character(len=12) :: name = ""
        integer :: code = 0
    end type option_type

    !> A key: where it belongs, what it takes, where its value goes
    type :: key_type
        character(len=11) :: group = ""
        character(len=15) :: name = ""
        integer :: kind = kind_real
        !> Unit, for messages and docs ("" when none)
        character(len=8) :: unit = ""
        !> Allowed range of a real or integer value; an open end excludes its bound
        real(wp) :: lower = -huge(1.0_wp), upper = huge(1.0_wp)
        logical :: lower_open = .false., upper_open = .false.
        !> Options of a choice key
        type(option_type), allocatable :: options(:)
        !> The scene component the value goes to (one, by kind)
        real(wp), pointer :: real_value => null()
        integer, pointer :: integer_value => null()
        logical, pointer :: logical_value => null()
    end type key_type

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
                & real_key("run", "end_time", r%end_time, "s", time_min, time_max), &
                & real_key("run", "output_step", r%output_step, "s", time_min, time_max), &
                & choice_key("formulation", r%formulation, [option_type("ida", formulation_ida), &
                & option_type("cvode", formulation_cvode)]), &
                & choice_key("method", r%method, [option_type("bdf", method_bdf), &
                & option_type("adams", method_adams)]), &
                & choice_key("drift", r%drift, [option_type("projection", drift_projection), &
                & option_type("baumgarte", drift_baumgarte), option_type("none", drift_none)]), &
                & choice_key("jacobian", r%jacobian, [option_type("analytic", &
                & jacobian_analytic), option_type("dq", jacobian_dq)]), &
                & choice_key("height", r%height, [option_type("velocity", height_velocity), &
                & option_type("position", height_position)]), &
                & real_key("run", "rtol", r%rtol, "", rtol_min, 1.0_wp, upper_open=.true.), &
                & real_key("run", "atol", r%atol, "", atol_min, atol_max), &
                & real_key("run", "baumgarte_rate", r%baumgarte_rate, "1/s", 0.0_wp, &
                & baumgarte_max, .true.), &
                & integer_key("run", "max_steps", r%max_steps, 1, huge(1)), &
                & real_key("limits", "theta_min", l%theta_min, "rad", 0.0_wp, pi, &
                & upper_open=.true.), &
                & logical_key("limits", "stop_on_liftoff", l%stop_on_liftoff)]
        end associate
    end subroutine bind_keys

    !> A real key with its range [lower, upper] (an open end excludes its bound).
    function real_key(group, name, value, unit, lower, upper, lower_open, upper_open) &
            & result(key)
        character(len=*), intent(in) :: group, name, unit
        real(wp), target, intent(inout) :: value
        real(wp), intent(in) :: lower, upper
        logical, intent(in), optional :: lower_open, upper_open
        type(key_type) :: key

        key = key_type(group, name, kind_real, unit, lower, upper)
        if (present(lower_open)) key%lower_open = lower_open
        if (present(upper_open)) key%upper_open = upper_open
        key%real_value => value
    end function real_key

    !> An integer key with its range [lower, upper].
    function integer_key(group, name, value, lower, upper) result(key)
        character(len=*), intent(in) :: group, name
        integer, target, intent(inout) :: value
        integer, intent(in) :: lower, upper
        type(key_type) :: key

        key = key_type(group, name, kind_integer, "", real(lower, wp), real(upper, wp))
        key%integer_value => value
    end function integer_key

    !> A logical key.
    function logical_key(group, name, value) result(key)
        character(len=*), intent(in) :: group, name
        logical, target, intent(inout) :: value
        type(key_type) :: key

        key = key_type(group, name, kind_logical)
        key%logical_value => value
    end function logical_key

    !> A choice of &run: one of the options' names, stored as its code.
    function choice_key(name, value, options) result(key)
        character(len=*), intent(in) :: name
        integer, target, intent(inout) :: value
        type(option_type), intent(in) :: options(:)
        type(key_type) :: key

        key = key_type("run", name, kind_choice)
        key%options = options
        key%integer_value => value
    end function choice_key

    !> Code of the option named word (any case) of the choice key name, 0 when none.
    function choice_code(name, word) result(code)
        !> Choice key of &run, as 'formulation'
        character(len=*), intent(in) :: name
        !> Option, as 'cvode'
        character(len=*), intent(in) :: word
        integer :: code
        type(scene_type), target :: scene
        type(key_type), allocatable :: keys(:)
        integer :: k, j

        code = 0
        call bind_keys(scene, keys)
        k = find_key(keys, "run", name)
        if (k == 0) return
        if (keys(k)%kind /= kind_choice) return
        do j = 1, size(keys(k)%options)
            if (keys(k)%options(j)%name == to_lower(word)) code = keys(k)%options(j)%code
        end do
    end function choice_code

    !> Name of the option with code of the choice key name, "?" when none.
    function choice_name(name, code) result(word)
        !> Choice key of &run, as 'formulation'
        character(len=*), intent(in) :: name
        !> Option code, as formulation_cvode
        integer, intent(in) :: code
        character(len=:), allocatable :: word
        type(scene_type), target :: scene
        type(key_type), allocatable :: keys(:)
        integer :: k, j

        word = "?"
        call bind_keys(scene, keys)
        k = find_key(keys, "run", name)
        if (k == 0) return
        if (keys(k)%kind /= kind_choice) return
        do j = 1, size(keys(k)%options)
            if (keys(k)%options(j)%code == code) word = trim(keys(k)%options(j)%name)
        end do
    end function choice_name

    !> Index of key in the table of group, 0 when not there.
    pure integer function find_key(keys, group, name) result(k)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: group, name

        do k = 1, size(keys)
            if (keys(k)%group == group .and. keys(k)%name == name) return
        end do
        k = 0
    end function find_key

    !> Keys of a group, comma separated.
    pure function key_list(keys, group) result(list)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: list
        integer :: k

        list = ""
        do k = 1, size(keys)
            if (keys(k)%group /= group) cycle
            if (len(list) > 0) list = list // ", "
            list = list // trim(keys(k)%name)
        end do
    end function key_list

end module rollcon_scene_keys
