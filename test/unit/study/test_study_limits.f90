! SPDX-License-Identifier: MIT
!> Tests of what a study file may ask for: a study of 1e9 cases (one count,
!> a grid of 1e5 x 1e4, samples) or of 1e10 (a grid of 1e5 x 1e5, whose count once wrapped
!> round) is refused with its count and the memory its plan would need, before any case is
!> made; a rule against NaN (or infinity) is refused; a class name that would break the CSV
!> (a comma, a double quote) is refused, and one with blanks and other punctuation runs and
!> reads back with the header's fields in every row.
module test_study_limits
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_parameters, only : case_count, max_study_cases
    use rollcon_study_run, only : study_plan_type, study_progress_type, plan_study, run_study
    use rollcon_study_csv, only : study_header, read_done_cases, read_csv_text, split_fields
    use rollcon_testing, only : unittest_type, new_unittest, check
    use study_texts, only : write_study, expect_study_error
    implicit none
    private

    public :: collect_study_limits

    !> The first lines of every study here
    character(len=*), parameter :: head(2) = [character(len=40) :: "&study", &
        & "    scene = 'data/upright.nml' /"]

contains

    !> Tests of this suite.
    subroutine collect_study_limits(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("too-many-cases-refused", test_too_many), &
            & new_unittest("largest-study-accepted", test_largest), &
            & new_unittest("rule-against-nan-refused", test_nan_rule), &
            & new_unittest("class-breaking-csv-refused", test_bad_class), &
            & new_unittest("class-with-punctuation-reads-back", test_class_round_trip), &
            & new_unittest("header-alone-not-doubled", test_header_alone)]
    end subroutine collect_study_limits

    !> 1e9 cases three ways and 1e10 on a grid: each refused at the group's line, with the
    !> count as the study makes it and the memory its plan alone would take.
    subroutine test_too_many(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_study_error(error, "test_limits_count", [character(len=60) :: head, &
            & "&grid", "    initial%speed = '0.4 1.0 1000000000' /"], [character(len=100) :: &
            & "@:3: the study has 1000000000 cases (&grid: 1000000000); a study may have " &
            & // "at most 2000000", "about 72 GB of memory"])
        if (allocated(error)) return
        call expect_study_error(error, "test_limits_grid", [character(len=60) :: head, &
            & "&grid", "    initial%speed = '0.4 1.0 100000'", &
            & "    disk%thickness = '0.01 0.2 10000' /"], [character(len=100) :: &
            & "@:3: the study has 1000000000 cases (&grid: 100000 x 10000)", &
            & "about 128 GB of memory"])
        if (allocated(error)) return
        call expect_study_error(error, "test_limits_wrap", [character(len=60) :: head, &
            & "&grid", "    initial%speed = '0.4 1.0 100000'", &
            & "    disk%thickness = '0.01 0.2 100000' /"], [character(len=100) :: &
            & "@:3: the study has 10000000000 cases (&grid: 100000 x 100000)"])
        if (allocated(error)) return
        call expect_study_error(error, "test_limits_samples", [character(len=60) :: head, &
            & "&random", "    samples = 1000000000", "    initial%speed = '0.4 1.0' /"], &
            & [character(len=100) :: "@:3: the study has 1000000000 cases (&random samples = " &
            & // "1000000000)", "Split it into several studies"])
    end subroutine test_too_many

    !> A study of exactly the largest size reads (its plan is not made here).
    subroutine test_largest(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        character(len=:), allocatable :: path

        call write_study("test_limits_largest", [character(len=60) :: head, "&grid", &
            & "    initial%speed = '0.4 1.0 2000'", "    disk%thickness = '0.01 0.2 1000' /"], &
            & path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call check(error, case_count(study) == max_study_cases, "cases: " &
            & // to_text(case_count(study)))
    end subroutine test_largest

    !> NaN compares false with every number: a rule against it would never hold. It is
    !> refused with file, line and key, and so is infinity.
    subroutine test_nan_rule(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: grid(2) = [character(len=40) :: "&grid", &
            & "    initial%speed = '0.4 1.0 3' /"]

        call expect_study_error(error, "test_limits_nan", [character(len=40) :: head, grid, &
            & "&classify", "    slips = 'mu_max > NaN' /"], [character(len=100) :: &
            & "@:6: 'slips' reads 'measure relation number': 'NaN' is not a finite number"])
        if (allocated(error)) return
        call expect_study_error(error, "test_limits_inf", [character(len=40) :: head, grid, &
            & "&classify", "    slips = 'mu_max < -Inf' /"], [character(len=100) :: &
            & "@:6: 'slips' reads 'measure relation number': '-Inf' is not a finite number"])
    end subroutine test_nan_rule

    !> A class with a comma and a quote would give its rows 19 fields against the header's
    !> 18: refused with file, line and key, naming what it holds; so is an empty class.
    subroutine test_bad_class(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: grid(2) = [character(len=40) :: "&grid", &
            & "    initial%speed = '0.4 1.0 3' /"]

        call expect_study_error(error, "test_limits_comma", [character(len=40) :: head, grid, &
            & "&classify", "    falls = 'tilt_max > 0.3'", "    otherwise = 'a,""b' /"], &
            & [character(len=100) :: "@:7: 'otherwise' names the class 'a,""b', which holds " &
            & // "a comma (column 2)"])
        if (allocated(error)) return
        call expect_study_error(error, "test_limits_quote", [character(len=40) :: head, grid, &
            & "&classify", "    otherwise = 'stays ""up""' /"], [character(len=100) :: &
            & "@:6: 'otherwise' names the class 'stays ""up""', which holds a double quote"])
        if (allocated(error)) return
        call expect_study_error(error, "test_limits_empty", [character(len=40) :: head, grid, &
            & "&classify", "    otherwise = '' /"], [character(len=100) :: &
            & "@:6: 'otherwise' names an empty class"])
    end subroutine test_bad_class

    !> A class with blanks, a semicolon, parentheses and an ampersand: the study runs, every
    !> row read back has the header's fields and that class, and a rerun finds every case.
    subroutine test_class_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: csv = "build/test_limits_class.csv"
        character(len=*), parameter :: class = "stays up; (fine) & well"
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(study_progress_type) :: progress
        character(len=:), allocatable :: path, text, header_fields(:), fields(:), keys(:)
        integer, allocatable :: cases(:)
        integer :: start, stop, rows, class_field

        call write_study("test_limits_class", [character(len=50) :: head, "&grid", &
            & "    initial%speed = '0.8 0.9 2'", "    run%end_time = '0.2 0.2 1' /", &
            & "&classify", "    otherwise = 'stays up; (fine) & well' /"], path)
        call execute_command_line("rm -f " // csv)
        call read_study(path, study, error)
        if (allocated(error)) return
        call plan_study(study, csv, plan, error)
        if (allocated(error)) return
        call run_study(study, csv, plan, progress, error)
        if (allocated(error)) return
        call read_csv_text(csv, text, error)
        if (allocated(error)) return
        call split_fields(study_header(study), header_fields)
        class_field = findloc_field(header_fields, "class")
        rows = 0
        start = index(text, new_line("a")) + 1
        do while (start <= len(text))
            stop = start - 1 + index(text(start:), new_line("a"))
            call split_fields(text(start:stop - 1), fields)
            rows = rows + 1
            call check(error, size(fields) == size(header_fields) .and. trim(fields(class_field)) &
                & == class, "row " // to_text(rows) // ": " // to_text(size(fields)) &
                & // " fields (header " // to_text(size(header_fields)) // "), class '" &
                & // trim(fields(class_field)) // "'")
            if (allocated(error)) return
            start = stop + 1
        end do
        call check(error, rows == 2, "rows read back: " // to_text(rows))
        if (allocated(error)) return
        call read_done_cases(csv, study, cases, keys, error)
        if (allocated(error)) return
        call check(error, size(cases) == 2, "a rerun finds " // to_text(size(cases)) // " cases")
    end subroutine test_class_round_trip

    !> A CSV that holds only its header (a sweep stopped before its first row, or a full disk
    !> after it) keeps that one header when the study resumes.
    subroutine test_header_alone(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: csv = "build/test_limits_header.csv"
        type(study_type) :: study
        type(study_plan_type) :: plan
        character(len=:), allocatable :: path, text
        integer :: unit

        call write_study("test_limits_header", [character(len=50) :: head, "&grid", &
            & "    initial%speed = '0.8 0.9 2' /"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        open(newunit=unit, file=csv, status="replace", action="write")
        write(unit, "(a)") study_header(study)
        close(unit)
        call plan_study(study, csv, plan, error)
        if (allocated(error)) return
        call read_csv_text(csv, text, error)
        if (allocated(error)) return
        call check(error, text == study_header(study) // new_line("a") .and. &
            & size(plan%pending()) == 2, "the CSV after the plan: " // text)
    end subroutine test_header_alone

    pure integer function findloc_field(fields, name) result(k)
        character(len=*), intent(in) :: fields(:), name

        do k = 1, size(fields)
            if (trim(fields(k)) == name) return
        end do
        k = 0
    end function findloc_field

end module test_study_limits
