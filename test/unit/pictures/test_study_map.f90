! SPDX-License-Identifier: MIT
!> Tests of a study's map (rollcon_study_map): the PNG drawn from a hand-written study CSV
!> (grid cells and random points), each class's cases in the script, the critical speed curve
!> equal to the analytic one, and the refusals (no such CSV, another study's CSV, a class the
!> study lacks, a study of one parameter). Drawing is skipped without gnuplot.
module test_study_map
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene_lines, scene_override_type
    use rollcon_scene_state, only : upright_critical_speed
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_csv, only : study_header
    use rollcon_study_map, only : draw_study_map, map_script_path, curve_points, curve_title
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines, expect_message
    use command_runs, only : text_file => file_text
    use study_map_files, only : scratch, width, thickness_range, failed_case, refused_case, &
        & have_gnuplot, grid_study, grid_point, count_classes, measures, png_file, &
        & block_size, read_block
    implicit none
    private

    public :: collect_study_map

    !> The curve is the same function of the same scene: only the 17 digits of the script's
    !> numbers stand between them
    real(wp), parameter :: tol_curve = 1.0e-12_wp
    !> The paper's disk: v_crit = 0.572 m/s to the three digits docs/design.md §5 gives
    real(wp), parameter :: paper_speed = 0.572_wp, tol_paper = 5.0e-4_wp

contains

    !> Tests of this suite.
    subroutine collect_study_map(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("map-png-written", test_png), &
            & new_unittest("map-cases-by-class", test_cases), &
            & new_unittest("map-curve-is-critical-speed", test_curve), &
            & new_unittest("map-random-samples", test_random), &
            & new_unittest("map-missing-csv", test_missing_csv), &
            & new_unittest("map-foreign-csv", test_foreign_csv), &
            & new_unittest("map-unknown-class", test_unknown_class), &
            & new_unittest("map-needs-two-parameters", test_one_parameter)]
    end subroutine collect_study_map

    !> The map of a grid study is a PNG file (skipped without gnuplot).
    subroutine test_png(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study

        if (.not. have_gnuplot(error)) return
        call grid_study(study, error)
        if (.not. allocated(error)) call draw_study_map(study, scratch // "/grid.csv", &
            & scratch // "/grid.png", error)
        if (.not. allocated(error)) call check(error, png_file(scratch // "/grid.png"), &
            & scratch // "/grid.png is missing, empty or not a PNG file")
        call remove_folder(scratch)
    end subroutine test_png

    !> Each class's cells hold its cases at their parameters: the quoted message with commas
    !> and the last line cut short do not count (skipped without gnuplot).
    subroutine test_cases(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        character(len=:), allocatable :: script
        real(wp), allocatable :: points(:, :)
        integer :: falls, stable

        if (.not. have_gnuplot(error)) return
        call grid_study(study, error)
        script = map_script_path(scratch // "/grid.png")
        if (.not. allocated(error)) call draw_study_map(study, scratch // "/grid.csv", &
            & scratch // "/grid.png", error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        call count_classes(falls, stable)
        call check(error, block_size(script, "class_1") == falls .and. &
            & block_size(script, "class_2") == stable, "falls and stable cells: " &
            & // to_text(block_size(script, "class_1")) // " and " &
            & // to_text(block_size(script, "class_2")) // ", expected " // to_text(falls) &
            & // " and " // to_text(stable))
        if (.not. allocated(error)) then
            call read_block(script, "class_3", points)
            call check(error, size(points, 2) == 1, "one failed case")
        end if
        if (.not. allocated(error)) call check(error, points(:, 1), grid_point(failed_case), &
            & "the failed case's cell", abs_tol=0.0_wp)
        if (.not. allocated(error)) then
            call read_block(script, "class_4", points)
            call check(error, size(points, 2) == 1, "one refused case")
        end if
        if (.not. allocated(error)) call check(error, points(:, 1), &
            & grid_point(refused_case), "the refused case's cell", abs_tol=0.0_wp)
        ! the class falls_over, its underscore a blank in the key
        if (.not. allocated(error)) call check(error, index(text_file(script), &
            & "title 'falls over (" // to_text(falls) // ")'") > 0, "the key lacks 'falls " &
            & // "over (" // to_text(falls) // ")'")
        call remove_folder(scratch)
    end subroutine test_cases

    !> The curve's points are the critical speed of the base scene with their thickness, across
    !> the thickness range; at 3 mm the paper's 0.572 m/s (skipped without gnuplot).
    subroutine test_curve(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(scene_type) :: scene
        type(scene_override_type) :: override(1)
        real(wp), allocatable :: points(:, :)
        integer :: i

        if (.not. have_gnuplot(error)) return
        call grid_study(study, error)
        if (.not. allocated(error)) call draw_study_map(study, scratch // "/grid.csv", &
            & scratch // "/grid.png", error)
        if (.not. allocated(error)) then
            call read_block(map_script_path(scratch // "/grid.png"), "curve", points)
            call check(error, size(points, 2) == curve_points .and. index(text_file( &
                & map_script_path(scratch // "/grid.png")), curve_title) > 0, &
                & to_text(size(points, 2)) // " curve points, or the key lacks the curve")
        end if
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, [points(1, 1), points(1, curve_points)], thickness_range, &
            & "the curve spans the thickness range", abs_tol=0.0_wp)
        if (allocated(error)) return
        call check(error, points(2, 1), paper_speed, "critical speed of the paper's disk", &
            & abs_tol=tol_paper)
        override(1)%group = "disk"
        override(1)%key = "thickness"
        do i = 1, size(points, 2)
            if (allocated(error)) return
            override(1)%value = to_text(points(1, i))
            call read_scene_lines(study%scene_path, study%scene_lines, scene, error, override)
            if (allocated(error)) return
            call check(error, points(2, i), upright_critical_speed(scene), "critical speed " &
                & // "at thickness " // override(1)%value, rel_tol=tol_curve)
        end do
    end subroutine test_curve

    !> Random samples are drawn as points (skipped without gnuplot).
    subroutine test_random(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        character(len=width) :: rows(4)

        if (.not. have_gnuplot(error)) return
        call make_folder(scratch)
        call write_lines(scratch // "/random.nml", [character(len=width) :: &
            & "&study scene = 'data/upright.nml' /", &
            & "&random strike%impulse = '0.001 0.02', initial%speed = '0.2 1.0'", &
            & "    samples = 3, seed = 4 /", "&classify mu_1 = 'mu_max > 1'," &
            & // " lifts = 'fn_min < 0', otherwise = 'valid' /"])
        call read_study(scratch // "/random.nml", study, error)
        if (.not. allocated(error)) then
            rows(1) = study_header(study)
            rows(2) = "1,0.0123,0.5,completed,valid,0" // measures() // ',""'
            rows(3) = "2,0.0031,0.9,completed,lifts,0" // measures() // ',""'
            rows(4) = "3,0.0188,0.25,liftoff,mu_1,0" // measures() // ',"lift-off at t = 2"'
            call write_lines(scratch // "/random.csv", rows)
            call draw_study_map(study, scratch // "/random.csv", scratch // "/random.png", &
                & error)
        end if
        if (.not. allocated(error)) call check(error, png_file(scratch // "/random.png") &
            & .and. index(text_file(map_script_path(scratch // "/random.png")), &
            & "with points") > 0, "no PNG, or the samples are not drawn as points")
        call remove_folder(scratch)
    end subroutine test_random

    !> A CSV that is not there: the message names it.
    subroutine test_missing_csv(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(study_type) :: study

        call grid_study(study, error)
        if (.not. allocated(error)) call draw_study_map(study, scratch // "/no-such.csv", &
            & scratch // "/no-such.png", failure)
        call remove_folder(scratch)
        if (.not. allocated(error)) call expect_message(error, failure, scratch &
            & // "/no-such.csv: cannot open")
    end subroutine test_missing_csv

    !> The CSV of another study (another header) is refused at its line 1.
    subroutine test_foreign_csv(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(study_type) :: study

        call grid_study(study, error)
        if (.not. allocated(error)) then
            call write_lines(scratch // "/other.csv", [character(len=width) :: &
                & "case,disk%radius,initial%speed,outcome,class,flag,message", &
                & "1,0.1,0.5,completed,stable,0,"""""])
            call draw_study_map(study, scratch // "/other.csv", scratch // "/other.png", &
                & failure)
        end if
        call remove_folder(scratch)
        if (.not. allocated(error)) call expect_message(error, failure, scratch &
            & // "/other.csv:1:", "header")
    end subroutine test_foreign_csv

    !> A row of a class the study does not have is refused at its line.
    subroutine test_unknown_class(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(study_type) :: study
        ! not an array constructor: gfortran 12 copies a function result of another length
        ! into [character(len=width) :: ...] past its end
        character(len=width) :: rows(3)

        call grid_study(study, error)
        if (.not. allocated(error)) then
            rows(1) = study_header(study)
            rows(2) = "1,0.003,0.2,completed,falls_over,0" // measures() // ',""'
            rows(3) = "2,0.003,0.4,completed,wobbles,0" // measures() // ',""'
            call write_lines(scratch // "/class.csv", rows)
            call draw_study_map(study, scratch // "/class.csv", scratch // "/class.png", &
                & failure)
        end if
        call remove_folder(scratch)
        if (.not. allocated(error)) call expect_message(error, failure, scratch &
            & // "/class.csv:3:", "'wobbles'")
    end subroutine test_unknown_class

    !> A study of one parameter has no map.
    subroutine test_one_parameter(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(study_type) :: study
        character(len=width) :: header

        call make_folder(scratch)
        call write_lines(scratch // "/line.nml", [character(len=width) :: &
            & "&study scene = 'data/upright.nml' /", "&grid initial%speed = '0.2 1.0 5' /"])
        call read_study(scratch // "/line.nml", study, error)
        if (.not. allocated(error)) then
            header = study_header(study)
            call write_lines(scratch // "/line.csv", [header])
            call draw_study_map(study, scratch // "/line.csv", scratch // "/line.png", failure)
        end if
        call remove_folder(scratch)
        if (.not. allocated(error)) call expect_message(error, failure, scratch &
            & // "/line.nml: no map")
    end subroutine test_one_parameter

end module test_study_map
