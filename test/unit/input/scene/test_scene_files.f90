! SPDX-License-Identifier: MIT
!> Tests of reading scenes: the files in data/, the defaults, choices in any case.
module test_scene_files
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_scene, only : scene_type, read_scene, scene_path, formulation_ida, &
        & formulation_cvode, method_bdf, method_adams, drift_projection, drift_baumgarte, &
        & jacobian_analytic, jacobian_dq, height_velocity, height_position
    use rollcon_scene, only : choice_code, choice_name
    use rollcon_namelist_bytes, only : visible
    use rollcon_testing, only : unittest_type, new_unittest, check
    use scene_texts, only : read_text, expect_accepted, width
    implicit none
    private

    public :: collect_scene_files

    !> Values read from a file are the nearest doubles of what is written: exact
    real(wp), parameter :: tol_exact = 0.0_wp
    !> Derived values (no-slip velocity, R sin(theta)): a few roundings
    real(wp), parameter :: tol_derived = 1.0e-15_wp
    !> Steady-motion residual relative to m g R cos(theta): psidot has 17 digits
    real(wp), parameter :: tol_steady = 1.0e-12_wp

contains

    !> Tests of this suite.
    subroutine collect_scene_files(tests)
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
            & new_unittest("byte-order-mark-skipped", test_byte_order_mark), &
            & new_unittest("velocity-consistent", test_velocity_consistent), &
            & new_unittest("speed-sets-spin", test_speed_key), &
            & new_unittest("choice-codes-and-names", test_choice_codes), &
            & new_unittest("visible-characters", test_visible), &
            & new_unittest("error-leaves-defaults", test_error_defaults)]
    end subroutine collect_scene_files

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

    !> Centre velocity of rolling without slip, from the constraints F1, F2, F3 = 0.
    pure function no_slip_velocity(s) result(v)
        type(scene_type), intent(in) :: s
        real(wp) :: v(3)

        associate (r => s%disk%radius, i => s%initial)
            v(1) = -r*cos(i%psi)*(i%phidot + i%psidot*cos(i%theta)) &
                & + r*i%thetadot*sin(i%psi)*sin(i%theta)
            v(2) = -r*sin(i%psi)*(i%phidot + i%psidot*cos(i%theta)) &
                & - r*i%thetadot*cos(i%psi)*sin(i%theta)
            v(3) = r*i%thetadot*cos(i%theta)
        end associate
    end function no_slip_velocity

    !> Checks every scene in data/ shares: the paper's disk, start at the origin, contact and
    !> no slip completed, the default choices unless the scene says otherwise.
    subroutine check_common(scene, error)
        type(scene_type), intent(in) :: scene
        type(error_type), allocatable, intent(out) :: error

        call check(error, [scene%disk%radius, scene%disk%thickness, scene%disk%density, &
            & scene%environment%gravity], &
            & [0.1_wp, 0.003_wp, 7800.0_wp, 9.81_wp], scene%name // ": disk and gravity", &
            & abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, [scene%initial%x, scene%initial%y, scene%initial%psi, &
            & scene%initial%phi, scene%initial%thetadot], &
            & [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], scene%name // ": X, Y, psi, phi, thetadot")
        if (allocated(error)) return
        call check(error, scene%initial%z, scene%disk%radius*sin(scene%initial%theta), &
            & scene%name // ": z", &
            & abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, [scene%initial%xdot, scene%initial%ydot, scene%initial%zdot], &
            & no_slip_velocity(scene), &
            & scene%name // ": centre velocity", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, .not. (scene%initial%z_given .or. scene%initial%velocity_given), &
            & scene%name // ": z or velocity marked as given")
        if (allocated(error)) return
        call check(error, scene%run%formulation == formulation_ida .and. scene%run%method &
            & == method_bdf .and. scene%run%drift == drift_projection .and. scene%run%jacobian &
            & == jacobian_analytic .and. scene%run%height == height_velocity, &
            & scene%name // ": default choices")
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
        call check(error, [s%initial%theta, s%initial%psidot, s%initial%phidot, s%run%end_time, &
            & s%run%output_step, s%run%rtol, s%run%atol, s%limits%theta_min], &
            & [pi/2, 0.0_wp, -1.0_wp, 10.0_wp, 0.01_wp, 1.0e-8_wp, &
            & 1.0e-10_wp, 0.05_wp], "coin: state and run", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, s%initial%xdot, 0.1_wp, "coin: rolls along +X at 0.1 m/s", &
            & abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%strike%enabled .and. s%limits%stop_on_liftoff, &
            & "coin: strike and liftoff")
        if (allocated(error)) return
        call check(error, [s%strike%time, s%strike%duration, s%strike%impulse], &
            & [2.0_wp, 0.01_wp, 0.01_wp], "coin: strike", abs_tol=tol_exact)
    end subroutine test_coin

    subroutine test_tipping_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("tipping_coin", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, .not. s%strike%enabled, "tipping_coin: no strike")
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%initial%psidot, s%initial%phidot, s%run%end_time], &
            & [pi/2 - 0.01_wp, 0.0_wp, -1.0_wp, 10.0_wp], "tipping_coin", abs_tol=tol_exact)
    end subroutine test_tipping_coin

    !> psidot is the slow root of the steady-motion relation (docs/design.md §5).
    subroutine test_steady_circle(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        real(wp) :: m, a, c, omega, w3, residual, scale, other

        call read_data("steady_circle", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%initial%phidot, s%run%end_time], &
            & [pi/3, -20.0_wp, 5.0_wp], &
            & "steady_circle", abs_tol=tol_exact)
        if (allocated(error)) return
        m = s%disk%density*pi*s%disk%radius**2*s%disk%thickness
        c = m*s%disk%radius**2/2
        a = m*(3*s%disk%radius**2 + s%disk%thickness**2)/12
        omega = s%initial%psidot
        w3 = s%initial%phidot + omega*cos(s%initial%theta)
        scale = m*s%environment%gravity*s%disk%radius*cos(s%initial%theta)
        residual = a*omega**2*sin(s%initial%theta)*cos(s%initial%theta) &
            & - (c + m*s%disk%radius**2)*omega*w3 &
            & *sin(s%initial%theta) - scale
        call check(error, residual, 0.0_wp, "steady_circle: steady-motion residual", &
            & abs_tol=tol_steady*scale)
        if (allocated(error)) return
        ! the product of the roots of a2 Omega^2 + a1 Omega + a0 is a0/a2: the other root
        other = -scale/((a - c - m*s%disk%radius**2)*sin(s%initial%theta) &
            & *cos(s%initial%theta))/omega
        call check(error, abs(omega) < abs(other), "steady_circle: psidot is not the slow root")
    end subroutine test_steady_circle

    subroutine test_fast_upright(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("fast_upright", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%initial%psidot, s%initial%phidot, s%run%end_time], &
            & [pi/2 - 0.05_wp, 0.0_wp, -20.0_wp, 10.0_wp], "fast_upright", abs_tol=tol_exact)
    end subroutine test_fast_upright

    subroutine test_spinning_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("spinning_coin", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%initial%psidot, s%initial%phidot, s%run%end_time], &
            & [75*pi/180, 30.0_wp, -7.0_wp, 3.0_wp], "spinning_coin", abs_tol=tol_derived)
    end subroutine test_spinning_coin

    subroutine test_near_flat(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("near_flat", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%initial%psidot, s%run%end_time, s%limits%theta_min], &
            & [15*pi/180, 10.0_wp, 2.0_wp, 0.01_wp], "near_flat", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%initial%phidot + s%initial%psidot*cos(s%initial%theta), 0.0_wp, &
            & "near_flat: w3", &
            & abs_tol=tol_derived*10)
    end subroutine test_near_flat

    subroutine test_long_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s

        call read_data("long_run", s, error)
        if (allocated(error)) return
        call check_common(s, error)
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%initial%phidot, s%run%end_time, s%run%output_step], &
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
        call check(error, .not. s%strike%enabled .and. s%limits%stop_on_liftoff .and. &
            & s%run%max_steps == 500000, "flags and max_steps")
        if (allocated(error)) return
        call check(error, [s%initial%theta, s%run%end_time, s%run%output_step, &
            & s%run%baumgarte_rate, s%initial%z], &
            & [pi/2, 10.0_wp, 0.01_wp, 10.0_wp, 0.1_wp], "defaults", abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%run%formulation == formulation_ida .and. s%run%method == method_bdf &
            & .and. s%run%drift == drift_projection .and. s%run%jacobian == jacobian_analytic &
            & .and. s%run%height == height_velocity, "default choices")
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
        call check(error, s%run%formulation == formulation_cvode .and. s%run%method &
            & == method_adams .and. s%run%drift == drift_baumgarte .and. s%run%jacobian &
            & == jacobian_dq .and. s%run%height == height_position, "choices as codes")
        if (allocated(error)) return
        call check(error, s%run%max_steps, 1000, "max_steps")
    end subroutine test_choices_case

    !> A UTF-8 byte-order mark at the start of the file is skipped (editors on Windows write
    !> one); the scene reads as without it.
    subroutine test_byte_order_mark(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        character(len=*), parameter :: mark = achar(239) // achar(187) // achar(191)

        call expect_accepted("bom", [character(len=width) :: mark // "&disk radius = 0.2 /", &
            & "&run end_time = 3.0 /"], s, error)
        if (allocated(error)) return
        call check(error, [s%disk%radius, s%run%end_time], [0.2_wp, 3.0_wp], &
            & "values after a byte-order mark", abs_tol=tol_exact)
    end subroutine test_byte_order_mark

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
        call check(error, [s%initial%xdot, s%initial%ydot, s%initial%zdot], v, &
            & "completed velocity", abs_tol=tol_derived)
        if (allocated(error)) return
        lines(1) = "&initial psi = 0.7, theta = 1.1, phi = 0.3"
        lines(2) = "psidot = 2.5, thetadot = -0.4, phidot = 3.0"
        write(lines(3), '("xdot = ", es24.16e3, ", ydot = ", es24.16e3)') v(1:2)
        write(lines(4), '("zdot = ", es24.16e3)') v(3)
        lines(5) = "/"
        call expect_accepted("velocity_ok", lines, t, error)
        if (allocated(error)) return
        call check(error, t%initial%velocity_given .and. .not. t%initial%z_given, &
            & "velocity marked as given")
        if (allocated(error)) return
        call check(error, [t%initial%xdot, t%initial%ydot, t%initial%zdot], v, &
            & "given velocity kept", &
            & abs_tol=tol_derived)
    end subroutine test_velocity_consistent

    !> &initial speed sets phidot so that the centre rolls at that speed along the heading
    !> (cos psi, sin psi), whatever psidot and thetadot are.
    subroutine test_speed_key(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: s
        real(wp) :: v(3)

        call expect_accepted("speed", [character(len=width) :: "&initial", &
            & "psi = 0.7, theta = 1.1, psidot = 2.5, thetadot = -0.4, speed = 0.8", "/"], s, error)
        if (allocated(error)) return
        v = no_slip_velocity(s)
        call check(error, v(1)*cos(0.7_wp) + v(2)*sin(0.7_wp), 0.8_wp, "speed along the heading", &
            & abs_tol=tol_derived)
        if (allocated(error)) return
        call check(error, s%initial%phidot, -0.8_wp/s%disk%radius - 2.5_wp*cos(1.1_wp), &
            & "phidot from speed", abs_tol=tol_derived)
    end subroutine test_speed_key

    !> Choice names and codes convert both ways, in any case; unknown ones give 0 and "?".
    subroutine test_choice_codes(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, choice_code("formulation", "CVode") == formulation_cvode .and. &
            & choice_code("height", "position") == height_position .and. &
            & choice_code("jacobian", "dq") == jacobian_dq, "codes of names")
        if (allocated(error)) return
        call check(error, choice_code("formulation", "rk4") == 0 .and. &
            & choice_code("radius", "ida") == 0, "unknown name or key gives 0")
        if (allocated(error)) return
        call check(error, choice_name("drift", drift_baumgarte) == "baumgarte" .and. &
            & choice_name("method", method_adams) == "adams" .and. &
            & choice_name("method", -7) == "?", "names of codes")
    end subroutine test_choice_codes

    !> Control bytes and bytes above 127 that are not UTF-8 show as \xNN, UTF-8 characters
    !> (2 to 4 bytes) as U+XXXX; printable ASCII as itself.
    subroutine test_visible(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: text = achar(0) // "a=" // achar(194) // achar(160) &
            & // achar(239) // achar(187) // achar(191) // achar(240) // achar(159) &
            & // achar(152) // achar(128) // achar(255) // achar(9) // achar(127) // achar(206)

        call check(error, visible(text) == "\x00a=U+00A0U+FEFFU+1F600\xFF\x09\x7F\xCE", &
            & "visible: " // visible(text))
    end subroutine test_visible

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
        call check(error, s%disk%radius, 0.1_wp, "radius after an error", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, s%run%formulation == formulation_ida, "formulation after an error")
    end subroutine test_error_defaults

end module test_scene_files
