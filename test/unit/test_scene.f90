! SPDX-License-Identifier: MIT
!> Tests of scene input: the files in data/ and every kind of bad input, with its message.
module test_scene
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_scene, only : scene_type, read_scene, scene_path
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_scene

    real(wp), parameter :: pi = acos(-1.0_wp)
    !> Values read from a file are the nearest doubles of what is written: exact
    real(wp), parameter :: tol_exact = 0.0_wp
    !> Derived values (no-slip velocity, R sin(theta)): a few roundings
    real(wp), parameter :: tol_derived = 1.0e-15_wp
    !> Steady-motion residual relative to m g R cos(theta): psidot has 17 digits
    real(wp), parameter :: tol_steady = 1.0e-12_wp
    !> Width of the lines of a test file
    integer, parameter :: width = 100

contains

    !> Tests of this suite.
    subroutine collect_scene(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("scene-path", test_scene_path), &
            & new_unittest("coin", test_coin), &
            & new_unittest("tipping-coin", test_tipping_coin), &
            & new_unittest("steady-circle", test_steady_circle), &
            & new_unittest("fast-upright", test_fast_upright), &
            & new_unittest("spinning-coin", test_spinning_coin), &
            & new_unittest("near-flat", test_near_flat), &
            & new_unittest("long-run", test_long_run), &
            & new_unittest("defaults", test_defaults), &
            & new_unittest("choices-any-case", test_choices_case), &
            & new_unittest("missing-file", test_missing_file), &
            & new_unittest("unknown-group", test_unknown_group), &
            & new_unittest("unknown-key", test_unknown_key), &
            & new_unittest("duplicate-group", test_duplicate_group), &
            & new_unittest("duplicate-key", test_duplicate_key), &
            & new_unittest("unclosed-group", test_unclosed_group), &
            & new_unittest("text-outside-group", test_outside_group), &
            & new_unittest("wrong-type", test_wrong_type), &
            & new_unittest("nan-value", test_nan_value), &
            & new_unittest("radius-not-positive", test_radius), &
            & new_unittest("density-not-positive", test_density), &
            & new_unittest("end-time-not-positive", test_end_time), &
            & new_unittest("rtol-not-positive", test_rtol), &
            & new_unittest("bad-choice", test_bad_choice), &
            & new_unittest("adams-needs-cvode", test_adams_ida), &
            & new_unittest("theta-out-of-range", test_theta_range), &
            & new_unittest("z-off-contact", test_z_contact), &
            & new_unittest("velocity-slips", test_velocity_slips), &
            & new_unittest("velocity-incomplete", test_velocity_incomplete), &
            & new_unittest("velocity-consistent", test_velocity_consistent), &
            & new_unittest("error-leaves-defaults", test_error_defaults)]
    end subroutine collect_scene

    !> Read a scene file of data/ and fail on any error.
    subroutine read_data(name, scene, error)
        character(len=*), intent(in) :: name
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        call check(error, scene%name == name .and. scene%path == "data/" // name // ".nml", &
            & "path and name of " // name)
    end subroutine read_data

    !> Write lines to a file under build/, read it as a scene, delete it.
    subroutine read_text(name, lines, scene, found, path)
        character(len=*), intent(in) :: name, lines(:)
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: found
        character(len=:), allocatable, intent(out) :: path
        integer :: unit, i

        path = "build/test_scene_" // name // ".nml"
        open(newunit=unit, file=path, status="replace", action="write")
        do i = 1, size(lines)
            write(unit, "(a)") trim(lines(i))
        end do
        close(unit)
        call read_scene(path, scene, found)
        open(newunit=unit, file=path, status="old")
        close(unit, status="delete")
    end subroutine read_text

    !> Reading lines must fail with an input error whose message holds every fragment; a
    !> leading '@' in a fragment stands for the file's path.
    subroutine expect_input_error(error, name, lines, fragments)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, lines(:), fragments(:)
        type(scene_type) :: scene
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path, fragment
        integer :: i

        call read_text(name, lines, scene, found, path)
        if (.not. allocated(found)) then
            call check(error, .false., name // ": no error reported")
            return
        end if
        call check(error, found%stat == stat_input, name // ": stat is not stat_input: " &
            & // found%message)
        if (allocated(error)) return
        do i = 1, size(fragments)
            fragment = trim(fragments(i))
            if (fragment(1:1) == "@") fragment = path // fragment(2:)
            call check(error, index(found%message, fragment) > 0, name // ": message '" &
                & // found%message // "' lacks '" // fragment // "'")
            if (allocated(error)) return
        end do
    end subroutine expect_input_error

    !> Reading lines must succeed.
    subroutine expect_accepted(name, lines, scene, error)
        character(len=*), intent(in) :: name, lines(:)
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        call read_text(name, lines, scene, error, path)
    end subroutine expect_accepted

    !> Centre velocity of rolling without slip, from the constraints F1, F2, F3 = 0.
    pure function no_slip_velocity(s) result(v)
        type(scene_type), intent(in) :: s
        real(wp) :: v(3)

        v(1) = -s%radius*cos(s%psi)*(s%phidot + s%psidot*cos(s%theta)) &
            & + s%radius*s%thetadot*sin(s%psi)*sin(s%theta)
        v(2) = -s%radius*sin(s%psi)*(s%phidot + s%psidot*cos(s%theta)) &
            & - s%radius*s%thetadot*cos(s%psi)*sin(s%theta)
        v(3) = s%radius*s%thetadot*cos(s%theta)
    end function no_slip_velocity

    !> Checks every scene in data/ shares: the paper's disk, start at the origin, contact and
    !> no slip completed, the default choices unless the scene says otherwise.
    subroutine check_common(scene, error)
        type(scene_type), intent(in) :: scene
        type(error_type), allocatable, intent(out) :: error

        call check(error, [scene%radius, scene%thickness, scene%density, scene%gravity], &
            & [0.1_wp, 0.003_wp, 7800.0_wp, 9.81_wp], scene%name // ": disk and gravity", &
            & abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, [scene%x, scene%y, scene%psi, scene%phi, scene%thetadot], &
            & [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], scene%name // ": X, Y, psi, phi, thetadot")
        if (allocated(error)) return
        call check(error, scene%z, scene%radius*sin(scene%theta), scene%name // ": z", &
            & abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, [scene%xdot, scene%ydot, scene%zdot], no_slip_velocity(scene), &
            & scene%name // ": centre velocity", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, .not. (scene%z_given .or. scene%velocity_given), &
            & scene%name // ": z or velocity marked as given")
        if (allocated(error)) return
        call check(error, scene%formulation == "ida" .and. scene%method == "bdf" &
            & .and. scene%drift == "projection" .and. scene%jacobian == "analytic" &
            & .and. scene%height == "velocity", scene%name // ": default choices")
    end subroutine check_common

    subroutine test_scene_path(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, scene_path("coin") == "data/coin.nml", "coin")
        if (allocated(error)) return
        call check(error, scene_path("my/own") == "my/own", "a name with '/' is a path")
        if (allocated(error)) return
        call check(error, scene_path("own.nml") == "own.nml", "a name ending in .nml is a path")
    end subroutine test_scene_path

    subroutine test_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("coin", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%theta, s%psidot, s%phidot, s%end_time, s%output_step, s%rtol, &
            & s%atol, s%theta_min], [pi/2, 0.0_wp, -1.0_wp, 10.0_wp, 0.01_wp, 1.0e-8_wp, &
            & 1.0e-10_wp, 0.05_wp], "coin: state and run", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, s%xdot, 0.1_wp, "coin: rolls along +X at 0.1 m/s", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%has_strike .and. s%stop_on_liftoff, "coin: strike and liftoff")
        if (allocated(error)) return
        call check(error, [s%strike_time, s%strike_duration, s%strike_impulse], &
            & [2.0_wp, 0.01_wp, 0.01_wp], "coin: strike", abs_tol=tol_exact)
    end subroutine test_coin

    subroutine test_tipping_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("tipping_coin", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, .not. s%has_strike, "tipping_coin: no strike")
        if (allocated(error)) return
        call check(error, [s%theta, s%psidot, s%phidot, s%end_time], &
            & [pi/2 - 0.01_wp, 0.0_wp, -1.0_wp, 10.0_wp], "tipping_coin", abs_tol=tol_exact)
    end subroutine test_tipping_coin

    !> psidot is the slow root of the steady-motion relation (DESIGN.md section 5).
    subroutine test_steady_circle(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        real(wp) :: m, a, c, omega, w3, residual, scale, other

        call read_data("steady_circle", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%theta, s%phidot, s%end_time], [pi/3, -20.0_wp, 5.0_wp], &
            & "steady_circle", abs_tol=tol_exact)
        if (allocated(error)) return
        m = s%density*pi*s%radius**2*s%thickness
        c = m*s%radius**2/2
        a = m*(3*s%radius**2 + s%thickness**2)/12
        omega = s%psidot
        w3 = s%phidot + omega*cos(s%theta)
        scale = m*s%gravity*s%radius*cos(s%theta)
        residual = a*omega**2*sin(s%theta)*cos(s%theta) - (c + m*s%radius**2)*omega*w3 &
            & *sin(s%theta) - scale
        call check(error, residual, 0.0_wp, "steady_circle: steady-motion residual", &
            & abs_tol=tol_steady*scale)
        if (allocated(error)) return
        ! the product of the roots of a2 Omega^2 + a1 Omega + a0 is a0/a2: the other root
        other = -scale/((a - c - m*s%radius**2)*sin(s%theta)*cos(s%theta))/omega
        call check(error, abs(omega) < abs(other), "steady_circle: psidot is not the slow root")
    end subroutine test_steady_circle

    subroutine test_fast_upright(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("fast_upright", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%theta, s%psidot, s%phidot, s%end_time], &
            & [pi/2 - 0.05_wp, 0.0_wp, -20.0_wp, 10.0_wp], "fast_upright", abs_tol=tol_exact)
    end subroutine test_fast_upright

    subroutine test_spinning_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("spinning_coin", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%theta, s%psidot, s%phidot, s%end_time], &
            & [75*pi/180, 30.0_wp, -7.0_wp, 3.0_wp], "spinning_coin", abs_tol=tol_derived)
    end subroutine test_spinning_coin

    subroutine test_near_flat(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("near_flat", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%theta, s%psidot, s%end_time, s%theta_min], &
            & [15*pi/180, 10.0_wp, 2.0_wp, 0.01_wp], "near_flat", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%phidot + s%psidot*cos(s%theta), 0.0_wp, "near_flat: w3", &
            & abs_tol=tol_derived*10)
    end subroutine test_near_flat

    subroutine test_long_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("long_run", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%theta, s%phidot, s%end_time, s%output_step], &
            & [pi/2 - 0.01_wp, -8.0_wp, 200.0_wp, 0.05_wp], "long_run", abs_tol=tol_exact)
    end subroutine test_long_run

    !> A file with comments only gives the documented defaults, strings included.
    subroutine test_defaults(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call expect_accepted("defaults", [character(len=width) :: "! nothing but a comment"], &
            & s, error)
        if (allocated(error)) return
        call check(error, s%name == "test_scene_defaults", "name is the base name: " // s%name)
        if (allocated(error)) return
        call check(error, .not. s%has_strike .and. s%stop_on_liftoff .and. &
            & s%max_steps == 500000, "flags and max_steps")
        if (allocated(error)) return
        call check(error, [s%theta, s%end_time, s%output_step, s%baumgarte_rate, s%z], &
            & [pi/2, 10.0_wp, 0.01_wp, 10.0_wp, 0.1_wp], "defaults", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%formulation == "ida" .and. s%method == "bdf" .and. &
            & s%drift == "projection" .and. s%jacobian == "analytic" .and. &
            & s%height == "velocity", "default choices")
    end subroutine test_defaults

    !> Choices are case-insensitive and stored lowercase; groups and keys too. Two keys may
    !> share a line; a carriage return (CRLF line ends) is a blank.
    subroutine test_choices_case(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        character(len=width) :: lines(3)

        lines(1) = "&RUN Formulation = 'CVode', METHOD = ""Adams"", drift='Baumgarte'" // achar(13)
        lines(2) = "  jacobian = 'DQ' height = 'Position'  ! two keys on one line" // achar(13)
        lines(3) = "  max_steps = 1000" // achar(13) // " /"
        call expect_accepted("case", lines, s, error)
        if (allocated(error)) return
        call check(error, s%formulation == "cvode" .and. s%method == "adams" .and. &
            & s%drift == "baumgarte" .and. s%jacobian == "dq" .and. s%height == "position", &
            & "choices: " // s%formulation // " " // s%method // " " // s%drift // " " &
            & // s%jacobian // " " // s%height)
        if (allocated(error)) return
        call check(error, s%max_steps, 1000, "max_steps")
    end subroutine test_choices_case

    subroutine test_missing_file(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        type(error_type), allocatable :: found

        call read_scene("data/no_such_scene.nml", s, found)
        if (.not. allocated(found)) then
            call check(error, .false., "no error for a missing file")
            return
        end if
        call check(error, found%stat == stat_input .and. &
            & index(found%message, "data/no_such_scene.nml: no such scene file") == 1, &
            & "message: " // found%message)
        if (allocated(error)) return
        call read_scene("data", s, found)
        if (.not. allocated(found)) then
            call check(error, .false., "no error for a directory")
            return
        end if
        call check(error, found%message == "data: is a directory, not a scene file", &
            & "message: " // found%message)
    end subroutine test_missing_file

    subroutine test_unknown_group(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "unknown_group", [character(len=width) :: &
            & "! a misspelt group", "&disc radius = 0.1 /"], [character(len=width) :: &
            & "@:2: unknown group '&disc'", &
            & "known groups are &disk, &environment, &initial, &strike, &run, &limits"])
    end subroutine test_unknown_group

    subroutine test_unknown_key(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "unknown_key", [character(len=width) :: &
            & "&run", "    end_time = 1.0", "    foo = 2.0", "/"], [character(len=width) :: &
            & "@:3: 'foo' is not a key of &run; keys are end_time, output_step, formulation"])
    end subroutine test_unknown_key

    subroutine test_duplicate_group(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "duplicate_group", [character(len=width) :: &
            & "&disk radius = 0.1 /", "&run end_time = 1.0 /", "&DISK density = 7000.0 /"], &
            & [character(len=width) :: "@:3: group '&disk' given twice (lines 1 and 3)"])
    end subroutine test_duplicate_group

    subroutine test_duplicate_key(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "duplicate_key", [character(len=width) :: &
            & "&disk", "radius = 0.1", "Radius = 0.2", "/"], &
            & [character(len=width) :: "@:3: 'radius' given twice in '&disk' (lines 2 and 3)"])
    end subroutine test_duplicate_key

    subroutine test_unclosed_group(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "unclosed", [character(len=width) :: &
            & "&disk radius = 0.1", "&run end_time = 1.0 /"], [character(len=width) :: &
            & "@:2: group '&run' begins before '&disk' (line 1) is closed with '/'"])
        if (allocated(error)) return
        call expect_input_error(error, "unclosed_end", [character(len=width) :: &
            & "&disk radius = 0.1 ! / in a comment does not close"], [character(len=width) :: &
            & "@:1: group '&disk' is not closed with '/'"])
    end subroutine test_unclosed_group

    subroutine test_outside_group(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "outside", [character(len=width) :: &
            & "&disk /", "radius = 0.2"], [character(len=width) :: &
            & "@:2: 'radius' is outside any namelist group"])
    end subroutine test_outside_group

    !> A string for a number, a real for an integer, a number for a logical or a string.
    subroutine test_wrong_type(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "type_real", [character(len=width) :: &
            & "&disk", "  radius = 'large'", "/"], [character(len=width) :: &
            & "@:2: 'radius' in &disk must be a real number, got 'large'"])
        if (allocated(error)) return
        call expect_input_error(error, "type_integer", [character(len=width) :: &
            & "&run max_steps = 1.5e5 /"], [character(len=width) :: &
            & "@:1: 'max_steps' in &run must be an integer, got 1.5e5"])
        if (allocated(error)) return
        call expect_input_error(error, "type_logical", [character(len=width) :: &
            & "&limits stop_on_liftoff = 7 /"], [character(len=width) :: &
            & "@:1: 'stop_on_liftoff' in &limits must be .true. or .false., got 7"])
        if (allocated(error)) return
        call expect_input_error(error, "type_string", [character(len=width) :: &
            & "&run formulation = ida /"], [character(len=width) :: &
            & "@:1: 'formulation' in &run must be a quoted string, as in 'ida', got ida"])
        if (allocated(error)) return
        call expect_input_error(error, "two_values", [character(len=width) :: &
            & "&disk radius = 0.1 0.2 /"], [character(len=width) :: &
            & "@:1: 'radius' takes one value, got 2"])
        if (allocated(error)) return
        call expect_input_error(error, "no_value", [character(len=width) :: &
            & "&disk radius = , density = 7800.0 /"], [character(len=width) :: &
            & "@:1: 'radius' has no value"])
    end subroutine test_wrong_type

    subroutine test_nan_value(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "nan", [character(len=width) :: &
            & "&initial", "theta = 1.0", "psidot = NaN", "/"], [character(len=width) :: &
            & "@:3: 'psidot' in &initial must be a finite number, got NaN"])
        if (allocated(error)) return
        call expect_input_error(error, "infinity", [character(len=width) :: &
            & "&strike impulse = -Infinity /"], [character(len=width) :: &
            & "@:1: 'impulse' in &strike must be a finite number, got -Infinity"])
        if (allocated(error)) return
        call expect_input_error(error, "overflow", [character(len=width) :: &
            & "&run end_time = 1.0e400 /"], [character(len=width) :: &
            & "@:1: 'end_time' in &run must be a finite number, got 1.0e400"])
    end subroutine test_nan_value

    subroutine test_radius(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "radius", [character(len=width) :: &
            & "&disk", "  thickness = 0.003", "  radius = -0.1  ! [m]", "/"], &
            & [character(len=width) :: "@:3: 'radius' must be > 0 [m], got -0.1"])
        if (allocated(error)) return
        call expect_input_error(error, "radius_zero", [character(len=width) :: &
            & "&disk radius = 0.0 /"], [character(len=width) :: "@:1: 'radius' must be > 0 [m]"])
    end subroutine test_radius

    subroutine test_density(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "density", [character(len=width) :: &
            & "&disk density = 0 /"], &
            & [character(len=width) :: "@:1: 'density' must be > 0 [kg/m^3], got 0"])
    end subroutine test_density

    subroutine test_end_time(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "end_time", [character(len=width) :: &
            & "&run", "  end_time = -5.0", "/"], &
            & [character(len=width) :: "@:2: 'end_time' must be > 0 [s], got -5"])
        if (allocated(error)) return
        call expect_input_error(error, "output_step", [character(len=width) :: &
            & "&run end_time = 1.0, output_step = 2.0 /"], [character(len=width) :: &
            & "@:1: 'output_step' must be > 0 and <= end_time = 1 [s], got 2"])
    end subroutine test_end_time

    subroutine test_rtol(error)
        type(error_type), allocatable, intent(out) :: error
        ! built apart: gfortran 12 sizes a constructor item holding to_text(...) wrongly
        character(len=width) :: fragment

        fragment = "@:1: 'rtol' must be > 0 and < 1, got " // to_text(-1.0e-8_wp)
        call expect_input_error(error, "rtol", [character(len=width) :: &
            & "&run rtol = -1.0e-8 /"], [fragment])
        if (allocated(error)) return
        call expect_input_error(error, "atol", [character(len=width) :: &
            & "&run atol = 0.0 /"], [character(len=width) :: "@:1: 'atol' must be > 0, got 0"])
    end subroutine test_rtol

    subroutine test_bad_choice(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "choice", [character(len=width) :: &
            & "&run", "  formulation = 'RK4'", "/"], [character(len=width) :: &
            & "@:2: 'formulation' must be 'ida' or 'cvode', got 'rk4'"])
        if (allocated(error)) return
        call expect_input_error(error, "choice_drift", [character(len=width) :: &
            & "&run formulation = 'cvode', drift = 'stabilise' /"], [character(len=width) :: &
            & "@:1: 'drift' must be 'projection', 'baumgarte' or 'none', got 'stabilise'"])
    end subroutine test_bad_choice

    subroutine test_adams_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "adams", [character(len=width) :: &
            & "&run method = 'adams' /"], [character(len=width) :: &
            & "@:1: 'method' must be 'bdf' with formulation 'ida'"])
    end subroutine test_adams_ida

    subroutine test_theta_range(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=width) :: fragments(2)

        call expect_input_error(error, "theta_pi", [character(len=width) :: &
            & "&initial theta = 3.2 /"], [character(len=width) :: &
            & "@:1: 'theta' must be in (0, pi) [rad], got 3.2"])
        if (allocated(error)) return
        call expect_input_error(error, "theta_zero", [character(len=width) :: &
            & "&initial theta = 0.0 /"], [character(len=width) :: &
            & "@:1: 'theta' must be in (0, pi) [rad], got 0"])
        if (allocated(error)) return
        fragments(1) = "@: 'theta_min' must be at least " // to_text(1.0e-3_wp)
        fragments(2) = "min(theta, pi - theta) = " // to_text(0.04_wp) // " [rad], got " &
            & // to_text(0.05_wp) // " (the default of &limits)"
        call expect_input_error(error, "theta_min", [character(len=width) :: &
            & "&initial theta = 0.04 /"], fragments)
    end subroutine test_theta_range

    subroutine test_z_contact(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call expect_input_error(error, "z", [character(len=width) :: &
            & "&initial", "  theta = 1.5707963267948966", "  z = 0.2", "/"], &
            & [character(len=width) :: "@:3: 'z' must be R sin(theta) = 0.1 [m]", "got 0.2"])
        if (allocated(error)) return
        call expect_accepted("z_ok", [character(len=width) :: &
            & "&disk radius = 0.2 /", "&initial theta = 0.5235987755982988, z = 0.1 /"], &
            & s, error)
        if (allocated(error)) return
        call check(error, s%z_given, "z not marked as given")
        if (allocated(error)) return
        call check(error, s%z, s%radius*sin(s%theta), "z given in contact is set to R sin(theta)", &
            & abs_tol=tol_exact)
    end subroutine test_z_contact

    subroutine test_velocity_slips(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=width) :: fragments(2)

        fragments(1) = "@:4: 'zdot' must be 0 [m/s] to roll without slip"
        fragments(2) = "got " // to_text(0.01_wp)
        call expect_input_error(error, "slip", [character(len=width) :: &
            & "&initial", "  phidot = -1.0", "  xdot = 0.1, ydot = 0.0", "  zdot = 0.01", "/"], &
            & fragments)
        if (allocated(error)) return
        call expect_input_error(error, "slip_x", [character(len=width) :: &
            & "&initial phidot = -1.0, xdot = 0.2, ydot = 0.0, zdot = 0.0 /"], &
            & [character(len=width) :: "@:1: 'xdot' must be 0.1 [m/s] to roll without slip"])
    end subroutine test_velocity_slips

    subroutine test_velocity_incomplete(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "incomplete", [character(len=width) :: &
            & "&initial", "  phidot = -1.0", "  xdot = 0.1", "  zdot = 0.0", "/"], &
            & [character(len=width) :: "@:4: 'ydot' must be given with the other velocity keys", &
            & "rolling without slip it is 0 [m/s]"])
    end subroutine test_velocity_incomplete

    !> A general state: tilted, turned, all three rates; the velocity from F1 = F2 = F3 = 0.
    subroutine test_velocity_consistent(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s, t
        character(len=width) :: lines(5)
        real(wp) :: v(3)

        call expect_accepted("state", [character(len=width) :: "&initial", &
            & "psi = 0.7, theta = 1.1, phi = 0.3", &
            & "psidot = 2.5, thetadot = -0.4, phidot = 3.0", &
            & "/"], s, error)
        if (allocated(error)) return
        v = no_slip_velocity(s)
        call check(error, [s%xdot, s%ydot, s%zdot], v, "completed velocity", abs_tol=tol_derived)
        if (allocated(error)) return
        lines(1) = "&initial psi = 0.7, theta = 1.1, phi = 0.3"
        lines(2) = "psidot = 2.5, thetadot = -0.4, phidot = 3.0"
        write(lines(3), '("xdot = ", es24.16e3, ", ydot = ", es24.16e3)') v(1:2)
        write(lines(4), '("zdot = ", es24.16e3)') v(3)
        lines(5) = "/"
        call expect_accepted("velocity_ok", lines, t, error)
        if (allocated(error)) return
        call check(error, t%velocity_given .and. .not. t%z_given, "velocity marked as given")
        if (allocated(error)) return
        call check(error, [t%xdot, t%ydot, t%zdot], v, "given velocity kept", &
            & abs_tol=tol_derived)
    end subroutine test_velocity_consistent

    !> A scene that fails holds the defaults, not the values read before the failure.
    subroutine test_error_defaults(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path

        call read_text("half", [character(len=width) :: "&disk radius = 0.3 /", &
            & "&run end_time = 0.0 /"], s, found, path)
        call check(error, allocated(found), "no error for end_time = 0")
        if (allocated(error)) return
        call check(error, s%radius, 0.1_wp, "radius after an error", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, s%formulation == "ida", "formulation after an error")
    end subroutine test_error_defaults

end module test_scene
