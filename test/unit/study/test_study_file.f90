! SPDX-License-Identifier: MIT
!> Tests of study files (docs/studies.md): the shipped studies read as documented, a grid's
!> cases come in the documented order with short exact values, random samples are
!> reproducible and in range, and every kind of bad input is refused with file, line and key.
module test_study_file
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_study_type, only : study_type, sampling_random
    use rollcon_study_reader, only : read_study
    use rollcon_study_parameters, only : case_count, case_values, value_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use study_texts, only : write_study, expect_study_error
    implicit none
    private

    public :: collect_study_file

    !> A scene's first lines in the refusal tests
    character(len=*), parameter :: head(2) = [character(len=40) :: "&study", &
        & "    scene = 'data/upright.nml' /"]

contains

    !> Tests of this suite.
    subroutine collect_study_file(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("shipped-studies", test_shipped), &
            & new_unittest("grid-order-and-values", test_grid), &
            & new_unittest("random-samples-reproducible", test_random), &
            & new_unittest("missing-study-file", test_missing_file), &
            & new_unittest("unknown-key", test_unknown_key), &
            & new_unittest("unknown-group", test_unknown_group), &
            & new_unittest("not-a-scene-key", test_not_scene_key), &
            & new_unittest("not-a-number-key", test_choice_key), &
            & new_unittest("empty-range", test_empty_range), &
            & new_unittest("range-form", test_range_form), &
            & new_unittest("outside-key-range", test_outside_range), &
            & new_unittest("scene-missing-or-unreadable", test_scene_missing), &
            & new_unittest("grid-and-random", test_grid_and_random), &
            & new_unittest("bad-rules", test_bad_rules), &
            & new_unittest("bad-map", test_bad_map), &
            & new_unittest("dataset-parameters", test_dataset_parameters)]
    end subroutine collect_study_file

    !> The two studies of data/ read with their parameters, case counts, rules and maps.
    subroutine test_shipped(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study

        call read_study("data/upright_stability.nml", study, error)
        if (allocated(error)) return
        call check(error, size(study%parameters) == 2 .and. case_count(study) == 20*61, &
            & "upright_stability: 2 parameters and 1220 cases")
        if (allocated(error)) return
        call check(error, study%parameters(2)%key == "speed" .and. study%map%curve &
            & == "critical_speed" .and. study%otherwise == "stays_upright" &
            & .and. size(study%rules) == 1, "upright_stability: speed, curve, classes")
        if (allocated(error)) return
        call check(error, study%rules(1)%measure == "tilt_max" .and. study%rules(1)%bound &
            & == 0.3_wp, "upright_stability: falls when tilt_max > 0.3")
        if (allocated(error)) return
        call read_study("data/friction_needed.nml", study, error)
        if (allocated(error)) return
        call check(error, case_count(study) == 41*29 .and. size(study%rules) == 4 &
            & .and. study%rules(1)%class == "lifts_off", "friction_needed: 1189 cases, " &
            & // "4 rules, lift-off first")
        if (allocated(error)) return
        call read_study("data/no_slip_validity.nml", study, error)
        if (allocated(error)) return
        call check(error, case_count(study) == 41*29 .and. size(study%rules) == 3 &
            & .and. study%rules(1)%measure == "t_flight" .and. study%rules(2)%measure &
            & == "mode_end" .and. study%rules(3)%measure == "t_sliding" .and. study%otherwise &
            & == "keeps rolling", "no_slip_validity: 1189 cases, a flight, sliding at the " &
            & // "end, some time sliding, else keeps rolling")
        if (allocated(error)) return
        ! the table's friction: one value each of mu_static and mu_kinetic, in every row
        call check(error, size(study%parameters) == 4 .and. study%parameters(3)%key &
            & == "mu_static" .and. study%parameters(3)%count == 1 .and. study%parameters(4)%key &
            & == "mu_kinetic" .and. study%parameters(4)%count == 1, "no_slip_validity: " &
            & // "impulse, speed, and one mu_static and one mu_kinetic")
    end subroutine test_shipped

    !> The first parameter varies slowest, both ends are included, and the values are the
    !> short decimals of the grid ('0.2', not '0.20000000000000001').
    subroutine test_grid(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        real(wp), allocatable :: values(:, :)
        character(len=:), allocatable :: path

        call write_study("test_study_grid", [character(len=60) :: head, "&grid", &
            & "    disk%thickness = '0.1 0.3 3'", "    run%max_steps = '1000 3000 2'", "/"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call case_values(study, values)
        call check(error, size(values, 2) == 6, "6 cases")
        if (allocated(error)) return
        call check(error, all(values(1, :) == [0.1_wp, 0.1_wp, 0.2_wp, 0.2_wp, 0.3_wp, 0.3_wp]) &
            & .and. all(values(2, :) == [1000.0_wp, 3000.0_wp, 1000.0_wp, 3000.0_wp, &
            & 1000.0_wp, 3000.0_wp]), "grid order or values")
        if (allocated(error)) return
        call check(error, value_text(study%parameters(1), values(1, 3)) == "0.2" .and. &
            & value_text(study%parameters(2), values(2, 2)) == "3000", "value texts")
    end subroutine test_grid

    !> The same seed draws the same samples, another seed others; all lie in their ranges.
    subroutine test_random(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        real(wp), allocatable :: first(:, :), again(:, :), other(:, :)
        character(len=:), allocatable :: path

        call write_study("test_study_random", [character(len=60) :: head, "&random", &
            & "    samples = 50", "    seed = 3", "    strike%impulse = '0.001 0.05'", &
            & "    initial%speed = '0.2 2'", "/"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call check(error, study%sampling == sampling_random .and. case_count(study) == 50, &
            & "50 random cases")
        if (allocated(error)) return
        call case_values(study, first)
        call case_values(study, again)
        study%seed = 4
        call case_values(study, other)
        call check(error, all(first == again), "the same seed drew other samples")
        if (allocated(error)) return
        call check(error, any(first /= other), "another seed drew the same samples")
        if (allocated(error)) return
        call check(error, all(first(1, :) >= 0.001_wp .and. first(1, :) <= 0.05_wp) .and. &
            & all(first(2, :) >= 0.2_wp .and. first(2, :) <= 2.0_wp), "a sample out of range")
    end subroutine test_random

    subroutine test_missing_file(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(error_type), allocatable :: found

        call read_study("build/no_such_study.nml", study, found)
        call check(error, allocated(found), "no error for a missing study file")
        if (allocated(error)) return
        call check(error, found%message == "build/no_such_study.nml: no such study file", &
            & "message: " // found%message)
    end subroutine test_missing_file

    subroutine test_unknown_key(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_unknown_key", [character(len=60) :: &
            & "&study", "    scene = 'data/upright.nml'", "    scenery = 'x' /", "&grid", &
            & "    disk%thickness = '0.1 0.3 3' /"], [character(len=60) :: "@:3: 'scenery'", &
            & "not a key of &study"])
    end subroutine test_unknown_key

    subroutine test_unknown_group(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_unknown_group", [character(len=60) :: &
            & head, "&grids", "    disk%thickness = '0.1 0.3 3' /"], [character(len=60) :: &
            & "@:3:", "unknown group '&grids'", "&grid, &random"])
    end subroutine test_unknown_group

    !> A parameter must be group%key of a scene file.
    subroutine test_not_scene_key(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_not_key", [character(len=60) :: head, &
            & "&grid", "    disk%thickness = '0.1 0.3 3'", "    disk%thikness = '0.1 0.3 3' /"], &
            & [character(len=60) :: "@:5: 'disk%thikness'", "is not a scene key"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_no_group", [character(len=60) :: head, &
            & "&grid", "    speed = '0.1 0.3 3' /"], [character(len=60) :: "@:4: 'speed'", &
            & "group%key"])
    end subroutine test_not_scene_key

    !> Choices and switches are not varied.
    subroutine test_choice_key(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_choice", [character(len=60) :: head, &
            & "&grid", "    run%formulation = '1 2 2' /"], [character(len=60) :: &
            & "@:4: 'run%formulation'", "cannot be varied"])
    end subroutine test_choice_key

    !> A count below 1, one point with two ends, random samples from an empty interval.
    subroutine test_empty_range(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_count_zero", [character(len=60) :: head, &
            & "&grid", "    disk%thickness = '0.1 0.3 0' /"], [character(len=60) :: &
            & "@:4: 'disk%thickness'", "empty range"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_one_point", [character(len=60) :: head, &
            & "&grid", "    disk%thickness = '0.1 0.3 1' /"], [character(len=60) :: &
            & "@:4: 'disk%thickness'", "count 1"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_random_empty", [character(len=60) :: head, &
            & "&random", "    samples = 3", "    initial%speed = '0.5 0.5' /"], &
            & [character(len=60) :: "@:5: 'initial%speed'", "empty range"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_no_samples", [character(len=60) :: head, &
            & "&random", "    initial%speed = '0.5 0.7' /"], [character(len=60) :: &
            & "@:3: 'samples'", "is missing"])
    end subroutine test_empty_range

    !> Three words on a grid, two for samples, numbers only, a whole count.
    subroutine test_range_form(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_two_words", [character(len=60) :: head, &
            & "&grid", "    disk%thickness = '0.1 0.3' /"], [character(len=60) :: &
            & "@:4: 'disk%thickness'", "'from to count'"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_word", [character(len=60) :: head, &
            & "&grid", "    disk%thickness = '0.1 thick 3' /"], [character(len=60) :: &
            & "@:4: 'disk%thickness'", "'thick' is not a number"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_count", [character(len=60) :: head, &
            & "&grid", "    disk%thickness = '0.1 0.3 2.5' /"], [character(len=60) :: &
            & "@:4: 'disk%thickness'", "not a whole number"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_integer_random", [character(len=60) :: &
            & head, "&random", "    samples = 3", "    run%max_steps = '10 100' /"], &
            & [character(len=60) :: "@:5: 'run%max_steps'", "on a &grid"])
    end subroutine test_range_form

    !> The ends must lie in the scene key's own range.
    subroutine test_outside_range(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_negative", [character(len=60) :: head, &
            & "&grid", "    disk%radius = '-0.1 0.3 3' /"], [character(len=60) :: &
            & "@:4: 'disk%radius'", "scene key's range", "got -0.1"])
    end subroutine test_outside_range

    subroutine test_scene_missing(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_no_scene", [character(len=60) :: "&study", &
            & "    title = 'x' /", "&grid", "    disk%radius = '0.1 0.3 3' /"], &
            & [character(len=60) :: "@:1: 'scene'", "is missing"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_scene_file", [character(len=60) :: &
            & "&study", "    scene = 'data/no_such_scene.nml' /", "&grid", &
            & "    disk%radius = '0.1 0.3 3' /"], [character(len=60) :: "@:2: 'scene'", &
            & "data/no_such_scene.nml"])
    end subroutine test_scene_missing

    subroutine test_grid_and_random(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_study_both", [character(len=60) :: head, &
            & "&grid", "    disk%radius = '0.1 0.3 3' /", "&random", "    samples = 2", &
            & "    disk%radius = '0.1 0.3' /"], [character(len=60) :: "@:5:", "give one"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_neither", [character(len=60) :: head], &
            & [character(len=60) :: "@:", "neither &grid nor &random"])
    end subroutine test_grid_and_random

    !> A rule names a measure, a relation and a number; failed and refused are taken.
    subroutine test_bad_rules(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=60), parameter :: grid(2) = [character(len=60) :: "&grid", &
            & "    disk%radius = '0.1 0.3 3' /"]

        call expect_study_error(error, "test_study_measure", [character(len=60) :: head, grid, &
            & "&classify", "    falls = 'tilt > 0.3' /"], [character(len=60) :: &
            & "@:6: 'falls'", "'tilt' is not a measure", "tilt_max"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_relation", [character(len=60) :: head, grid, &
            & "&classify", "    falls = 'tilt_max = 0.3' /"], [character(len=60) :: &
            & "@:6: 'falls'", "a relation"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_bound", [character(len=60) :: head, grid, &
            & "&classify", "    falls = 'tilt_max > high' /"], [character(len=60) :: &
            & "@:6: 'falls'", "'high' is not a number"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_taken", [character(len=60) :: head, grid, &
            & "&classify", "    failed = 'steps > 10' /"], [character(len=60) :: &
            & "@:6: 'failed'", "another name"])
    end subroutine test_bad_rules

    !> Map axes must be parameters; the critical speed needs speed on y.
    subroutine test_bad_map(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=60), parameter :: grid(3) = [character(len=60) :: "&grid", &
            & "    disk%radius = '0.1 0.3 3'", "    initial%speed = '0.5 1 3' /"]

        call expect_study_error(error, "test_study_axis", [character(len=60) :: head, grid, &
            & "&map", "    x = 'disk%density' /"], [character(len=60) :: "@:7: 'x'", &
            & "disk%radius, initial%speed"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_curve", [character(len=60) :: head, grid, &
            & "&map", "    x = 'initial%speed'", "    y = 'disk%radius'", &
            & "    curve = 'critical_speed' /"], [character(len=60) :: "@:6: 'curve'", &
            & "y = 'initial%speed'"])
    end subroutine test_bad_map

    !> A dataset study's parameters name statement, id, keyword and element; one the dataset
    !> does not have is refused with the study's line and key and the dataset's reason.
    subroutine test_dataset_parameters(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        character(len=:), allocatable :: path
        character(len=60), parameter :: adm_head(2) = [character(len=60) :: "&study", &
            & "    scene = 'data/coin.adm' /"]

        call write_study("test_study_adm", [character(len=60) :: adm_head, "&grid", &
            & "    part%2%vx = '0.1 0.2 2'", "    marker%3%qp%3 = '0 0.01 2'", &
            & "    accgrav%kgrav = '-9.81 -5 2' /"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call check(error, study%dataset .and. study%parameters(2)%group == "marker%3" .and. &
            & study%parameters(2)%key == "qp%3" .and. study%parameters(3)%group == "accgrav", &
            & "dataset parameters read")
        if (allocated(error)) return
        call expect_study_error(error, "test_study_adm_part", [character(len=60) :: adm_head, &
            & "&grid", "    part%7%vx = '0.1 0.2 2' /"], [character(len=60) :: &
            & "@:4: 'part%7%vx'", "PART/7 VX(1): the dataset has no such statement"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_adm_element", [character(len=60) :: &
            & adm_head, "&grid", "    marker%3%qp%4 = '0 1 2' /"], [character(len=60) :: &
            & "@:4: 'marker%3%qp%4'", "the argument has 3 value(s)"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_adm_form", [character(len=60) :: adm_head, &
            & "&grid", "    vx = '0 1 2' /"], [character(len=60) :: "@:4: 'vx'", &
            & "statement%id%keyword"])
    end subroutine test_dataset_parameters

end module test_study_file
