! SPDX-License-Identifier: MIT
!> Tests of scene errors: every kind of bad input is refused with a message naming the file,
!> the line and the key, and what was expected.
module test_scene_errors
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_scene, only : scene_type, read_scene
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use scene_texts, only : expect_input_error, expect_accepted, width
    use scene_bytes, only : test_control_byte, test_non_ascii
    implicit none
    private

    public :: collect_scene_errors

    !> Values read from a file are the nearest doubles of what is written: exact
    real(wp), parameter :: tol_exact = 0.0_wp

contains

    !> Tests of this suite.
    subroutine collect_scene_errors(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("missing-file", test_missing_file), &
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
            & new_unittest("speed-with-phidot", test_speed_with_phidot), &
            & new_unittest("contact-keys-refused", test_contact_keys), &
            & new_unittest("flight-start", test_flight_start), &
            & new_unittest("huge-values-refused", test_huge_values), &
            & new_unittest("faster-than-light-refused", test_speed_of_light), &
            & new_unittest("tiny-values-refused", test_tiny_values), &
            & new_unittest("control-byte-shown", test_control_byte), &
            & new_unittest("non-ascii-shown", test_non_ascii)]
    end subroutine collect_scene_errors

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
            & "@:1: 'radius' = '0.1': the file ends here, inside group '&disk' (line 1), " &
            & // "which is not closed with '/'"])
        if (allocated(error)) return
        ! a file cut inside a number or a string names the key it was the value of
        call expect_input_error(error, "cut_number", [character(len=width) :: &
            & "&disk", "radius = 0.1", "thickness = 0.00"], [character(len=width) :: &
            & "@:3: 'thickness' = '0.00': the file ends here, inside group '&disk' (line 1), " &
            & // "which is not closed with '/'"])
        if (allocated(error)) return
        call expect_input_error(error, "cut_string", [character(len=width) :: &
            & "&run", "formulation = 'cvo"], [character(len=width) :: &
            & "@:2: 'formulation' = 'cvo: the string is not closed on its line"])
        if (allocated(error)) return
        call expect_input_error(error, "empty_group_end", [character(len=width) :: &
            & "&disk"], [character(len=width) :: "@:1: group '&disk' is not closed with '/'"])
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
            & "@:1: 'max_steps' in &run must be an integer >= 1 and <= 2147483647, got 1.5e5"])
        if (allocated(error)) return
        call expect_input_error(error, "type_logical", [character(len=width) :: &
            & "&limits stop_on_liftoff = 7 /"], [character(len=width) :: &
            & "@:1: 'stop_on_liftoff' in &limits must be .true. or .false., got 7"])
        if (allocated(error)) return
        call expect_input_error(error, "type_string", [character(len=width) :: &
            & "&run formulation = ida /"], [character(len=width) :: &
            & "@:1: 'formulation' in &run must be 'ida', 'cvode' or 'maggi' (a quoted string), " &
            & // "got ida"])
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
            & [character(len=width) :: &
            & "@:3: 'radius' in &disk must be >= 1e-6 and <= 1000000 [m], got -0.1"])
        if (allocated(error)) return
        call expect_input_error(error, "radius_zero", [character(len=width) :: &
            & "&disk radius = 0.0 /"], [character(len=width) :: &
            & "@:1: 'radius' in &disk must be >= 1e-6"])
    end subroutine test_radius

    subroutine test_density(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "density", [character(len=width) :: &
            & "&disk density = 0 /"], &
            & [character(len=width) :: &
            & "@:1: 'density' in &disk must be >= 0.001 and <= 100000 [kg/m^3], got 0"])
    end subroutine test_density

    subroutine test_end_time(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "end_time", [character(len=width) :: &
            & "&run", "  end_time = -5.0", "/"], &
            & [character(len=width) :: &
            & "@:2: 'end_time' in &run must be >= 1e-9 and <= 1000000000 [s], got -5.0"])
        if (allocated(error)) return
        call expect_input_error(error, "output_step", [character(len=width) :: &
            & "&run end_time = 1.0, output_step = 2.0 /"], [character(len=width) :: &
            & "@:1: 'output_step' in &run must be <= end_time = 1 [s], got 2"])
    end subroutine test_end_time

    subroutine test_rtol(error)
        type(error_type), allocatable, intent(out) :: error
        ! built apart: gfortran 12 sizes a constructor item holding to_text(...) wrongly
        character(len=width) :: fragment

        fragment = "@:1: 'rtol' in &run must be >= 1e-15 and < 1, got -1.0e-8"
        call expect_input_error(error, "rtol", [character(len=width) :: &
            & "&run rtol = -1.0e-8 /"], [fragment])
        if (allocated(error)) return
        call expect_input_error(error, "atol", [character(len=width) :: &
            & "&run atol = 0.0 /"], [character(len=width) :: &
            & "@:1: 'atol' in &run must be >= 1e-20 and <= 1000, got 0.0"])
    end subroutine test_rtol

    subroutine test_bad_choice(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "choice", [character(len=width) :: &
            & "&run", "  formulation = 'RK4'", "/"], [character(len=width) :: &
            & "@:2: 'formulation' in &run must be 'ida', 'cvode' or 'maggi' (a quoted string), " &
            & // "got 'RK4'"])
        if (allocated(error)) return
        call expect_input_error(error, "choice_drift", [character(len=width) :: &
            & "&run formulation = 'cvode', drift = 'stabilise' /"], [character(len=width) :: &
            & "@:1: 'drift' in &run must be 'projection', 'baumgarte' or 'none'", &
            & "got 'stabilise'"])
    end subroutine test_bad_choice

    subroutine test_adams_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "adams", [character(len=width) :: &
            & "&run method = 'adams' /"], [character(len=width) :: &
            & "@:1: 'method' in &run must be 'bdf' with formulation 'ida'"])
        if (allocated(error)) return
        ! fixed-point iteration is CVODE's: IDA solves with Newton's method
        call expect_input_error(error, "fixed_point_ida", [character(len=width) :: &
            & "&run jacobian = 'none' /"], [character(len=width) :: &
            & "@:1: 'jacobian' in &run must be 'analytic' or 'dq' with formulation 'ida'", &
            & "got 'none'"])
    end subroutine test_adams_ida

    subroutine test_theta_range(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=width) :: fragments(2)

        call expect_input_error(error, "theta_pi", [character(len=width) :: &
            & "&initial theta = 3.2 /"], [character(len=width) :: &
            & "@:1: 'theta' in &initial must be > 0 and < 3.141592653589793 [rad], got 3.2"])
        if (allocated(error)) return
        call expect_input_error(error, "theta_zero", [character(len=width) :: &
            & "&initial theta = 0.0 /"], [character(len=width) :: &
            & "@:1: 'theta' in &initial must be > 0 and < 3.141592653589793 [rad], got 0.0"])
        if (allocated(error)) return
        fragments(1) = "@: 'theta_min' in &limits must be at least " // to_text(1.0e-3_wp)
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
            & [character(len=width) :: "@:3: 'z' in &initial must be R sin(theta) = 0.1 [m]", &
            & "got 0.2"])
        if (allocated(error)) return
        call expect_accepted("z_ok", [character(len=width) :: &
            & "&disk radius = 0.2 /", "&initial theta = 0.5235987755982988, z = 0.1 /"], &
            & s, error)
        if (allocated(error)) return
        call check(error, s%initial%z_given, "z not marked as given")
        if (allocated(error)) return
        call check(error, s%initial%z, s%disk%radius*sin(s%initial%theta), &
            & "z given in contact is set to R sin(theta)", &
            & abs_tol=tol_exact)
    end subroutine test_z_contact

    subroutine test_velocity_slips(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=width) :: fragments(2)

        fragments(1) = "@:4: 'zdot' in &initial must be 0 [m/s] to roll without slip"
        fragments(2) = "got " // to_text(0.01_wp)
        call expect_input_error(error, "slip", [character(len=width) :: &
            & "&initial", "  phidot = -1.0", "  xdot = 0.1, ydot = 0.0", "  zdot = 0.01", "/"], &
            & fragments)
        if (allocated(error)) return
        call expect_input_error(error, "slip_x", [character(len=width) :: &
            & "&initial phidot = -1.0, xdot = 0.2, ydot = 0.0, zdot = 0.0 /"], &
            & [character(len=width) :: "@:1: 'xdot' in &initial must be 0.1 [m/s] to roll"])
    end subroutine test_velocity_slips

    subroutine test_velocity_incomplete(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "incomplete", [character(len=width) :: &
            & "&initial", "  phidot = -1.0", "  xdot = 0.1", "  zdot = 0.0", "/"], &
            & [character(len=width) :: &
            & "@:4: 'ydot' in &initial must be given with the other velocity keys", &
            & "rolling without slip it is 0 [m/s]"])
    end subroutine test_velocity_incomplete

    !> &contact: mu_static must be given, mu_kinetic may not exceed it, the formulation must
    !> be the ODE form's, and a start may slip along the ground but never into it.
    subroutine test_contact_keys(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene

        call expect_input_error(error, "contact_no_mu", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact", "  mu_kinetic = 0.2", "/"], &
            & [character(len=width) :: "'mu_static' in &contact must be given in a &contact " &
            & // "group"])
        if (allocated(error)) return
        call expect_input_error(error, "contact_kinetic", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact", "  mu_static = 0.3", &
            & "  mu_kinetic = 0.4", "/"], [character(len=width) :: &
            & "@:4: 'mu_kinetic' in &contact must be <= mu_static = 0.3", "got 0.4"])
        if (allocated(error)) return
        call expect_input_error(error, "contact_maggi", [character(len=width) :: &
            & "&run formulation = 'maggi' /", "&contact mu_static = 0.3 /"], &
            & [character(len=width) :: "'formulation' in &run must be 'cvode' or 'ida' in a " &
            & // "scene with &contact"])
        if (allocated(error)) return
        call expect_input_error(error, "contact_zero", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.0 /"], &
            & [character(len=width) :: "@:2: 'mu_static'"])
        if (allocated(error)) return
        call expect_input_error(error, "contact_into_ground", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3 /", &
            & "&initial xdot = 1.0, zdot = 0.01 /"], [character(len=width) :: &
            & "@:3: 'zdot' in &initial must be 0 [m/s] to roll without slip"])
        if (allocated(error)) return
        call expect_accepted("contact_thrown", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3 /", &
            & "&initial xdot = 1.0 /"], scene, error)
        if (allocated(error)) return
        ! thrown without spin: the slip kept, the rim on the ground, mu_kinetic = mu_static
        call check(error, [scene%initial%xdot, scene%initial%ydot, scene%initial%zdot, &
            & scene%contact%mu_kinetic], [1.0_wp, 0.0_wp, 0.0_wp, 0.3_wp], &
            & "xdot, ydot, zdot, mu_kinetic", abs_tol=tol_exact)
    end subroutine test_contact_keys

    !> &contact restitution: within [0, 1]; with it a z above R sin(theta) starts in flight
    !> (the centre's velocity as given, 0 where not), a z below it is refused; without it a z
    !> above is refused as off the contact.
    subroutine test_flight_start(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene

        call expect_input_error(error, "restitution_high", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3, restitution = 1.5 /"], &
            & [character(len=width) :: "@:2: 'restitution'"])
        if (allocated(error)) return
        call expect_input_error(error, "restitution_negative", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3, restitution = -0.1 /"], &
            & [character(len=width) :: "@:2: 'restitution'"])
        if (allocated(error)) return
        call expect_input_error(error, "flight_no_restitution", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3 /", &
            & "&initial z = 0.2 /"], [character(len=width) :: &
            & "@:3: 'z' in &initial must be R sin(theta) = 0.1 [m] (rim on the ground)"])
        if (allocated(error)) return
        call expect_input_error(error, "flight_into_ground", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3, restitution = 0.5 /", &
            & "&initial z = 0.05 /"], [character(len=width) :: &
            & "@:3: 'z' in &initial must be at least R sin(theta) = 0.1 [m]", "got 0.05"])
        if (allocated(error)) return
        call expect_accepted("flight_dropped", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3, restitution = 0.5 /", &
            & "&initial z = 0.2, phidot = 3.0, ydot = 0.5 /"], scene, error)
        if (allocated(error)) return
        ! in flight: z kept, the velocity as given and 0 where not (not rolling's 0.3 m/s)
        call check(error, [scene%initial%z, scene%initial%xdot, scene%initial%ydot, &
            & scene%initial%zdot, scene%contact%restitution], [0.2_wp, 0.0_wp, 0.5_wp, &
            & 0.0_wp, 0.5_wp], "z, xdot, ydot, zdot, restitution", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, scene%contact%flight .and. scene%initial%velocity_given, &
            & "flight modelled, the velocity the scene's")
        if (allocated(error)) return
        call expect_accepted("flight_on_ground", [character(len=width) :: &
            & "&run formulation = 'cvode' /", "&contact mu_static = 0.3, restitution = 0.0 /", &
            & "&initial phidot = -1.0 /"], scene, error)
        if (allocated(error)) return
        ! on the ground: rolling's velocity, e = 0 given is flight modelled
        call check(error, [scene%initial%z, scene%initial%xdot], [0.1_wp, 0.1_wp], &
            & "z, xdot on the ground", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, scene%contact%flight, "restitution = 0 given: flight modelled")
    end subroutine test_flight_start

    !> speed and phidot both set the spin: one of them.
    subroutine test_speed_with_phidot(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "speed_phidot", [character(len=width) :: &
            & "&initial", "  phidot = -1.0", "  speed = 0.1", "/"], [character(len=width) :: &
            & "@:3: 'speed' in &initial cannot be given with 'phidot' (line 2)"])
    end subroutine test_speed_with_phidot

    !> Huge finite values are refused at their key, with the bound.
    subroutine test_huge_values(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "huge_radius", [character(len=width) :: &
            & "&disk", "radius = 1e200", "/"], [character(len=width) :: &
            & "@:2: 'radius' in &disk must be >= 1e-6 and <= 1000000 [m], got 1e200"])
        if (allocated(error)) return
        call expect_input_error(error, "huge_density", [character(len=width) :: &
            & "&disk density = 1.7e308 /"], [character(len=width) :: &
            & "@:1: 'density' in &disk must be >= 0.001 and <= 100000 [kg/m^3], got 1.7e308"])
        if (allocated(error)) return
        call expect_input_error(error, "huge_rate", [character(len=width) :: &
            & "&initial phidot = -1e250 /"], [character(len=width) :: &
            & "@:1: 'phidot' in &initial must be >= -1000000 and <= 1000000 [rad/s]"])
        if (allocated(error)) return
        call expect_input_error(error, "huge_end_time", [character(len=width) :: &
            & "&run end_time = 1e300, output_step = 1e299 /"], [character(len=width) :: &
            & "@:1: 'end_time' in &run must be >= 1e-9 and <= 1000000000 [s], got 1e300"])
        if (allocated(error)) return
        call expect_input_error(error, "huge_steps", [character(len=width) :: &
            & "&run max_steps = 99999999999 /"], [character(len=width) :: &
            & "@:1: 'max_steps' in &run must be an integer >= 1 and <= 2147483647"])
    end subroutine test_huge_values

    !> Values within their keys' ranges whose combination is not physical: a rim faster than
    !> light, a strike that would push the disk beyond it.
    subroutine test_speed_of_light(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=width) :: fragments(2)

        ! R |omega| = 1e6 m * 1e3 rad/s = 1e9 m/s
        call expect_input_error(error, "rim_speed", [character(len=width) :: &
            & "&disk radius = 1e6 /", "&initial", "phidot = -1e3", "/"], &
            & [character(len=width) :: "@:3: 'phidot' in &initial gives a rim speed", &
            & "it must be <= the speed of light 299792458 [m/s]"])
        if (allocated(error)) return
        ! 1e9 N s on the paper's 0.735 kg disk
        fragments(1) = "@:2: 'impulse' in &strike gives the disk of mass"
        fragments(2) = "must be <= the speed of light 299792458 [m/s]"
        call expect_input_error(error, "strike_speed", [character(len=width) :: "&strike", &
            & "impulse = 1e9", "/"], fragments)
    end subroutine test_speed_of_light

    !> Tiny values that would make the mass matrix singular or the error weights overflow.
    subroutine test_tiny_values(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_input_error(error, "tiny_thickness", [character(len=width) :: &
            & "&disk thickness = 1e-320 /"], [character(len=width) :: &
            & "@:1: 'thickness' in &disk must be >= 1e-6 and <= 1000000 [m], got 1e-320"])
        if (allocated(error)) return
        call expect_input_error(error, "tiny_atol", [character(len=width) :: &
            & "&run atol = 1e-320 /"], [character(len=width) :: &
            & "@:1: 'atol' in &run must be >= 1e-20"])
        if (allocated(error)) return
        call expect_input_error(error, "tiny_duration", [character(len=width) :: &
            & "&strike duration = 4.9e-324 /"], [character(len=width) :: &
            & "@:1: 'duration' in &strike must be >= 1e-9"])
        if (allocated(error)) return
        call expect_input_error(error, "plus_exponent", [character(len=width) :: &
            & "&disk radius = 1.0+1 /"], [character(len=width) :: &
            & "@:1: 'radius' in &disk must be a real number, got 1.0+1"])
    end subroutine test_tiny_values

end module test_scene_errors
