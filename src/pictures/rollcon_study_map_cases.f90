! SPDX-License-Identifier: MIT
!> What a study's map draws of its CSV (rollcon_study_csv): the classes a case may have, and
!> each case's two map parameters and class.
module rollcon_study_map_cases
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_input
    use rollcon_text, only : to_text, comma_list
    use rollcon_study_type, only : study_type
    use rollcon_study_csv, only : study_header, read_csv_text, split_fields
    use rollcon_study_measures, only : outcome_words, outcome_failed, outcome_refused
    implicit none
    private

    public :: map_cases_type, map_classes, read_map_cases

    !> The cases of a study's CSV as its map draws them
    type :: map_cases_type
        !> Each case's values of the map's x and y parameters, in their units
        real(wp), allocatable :: x(:), y(:)
        !> Each case's class, an index into the classes of map_classes
        integer, allocatable :: class(:)
    end type map_cases_type

    character(len=*), parameter :: lf = achar(10), cr = achar(13)

contains

    !> The classes a case of the study may have, each once: the rules' classes in file order,
    !> the class of the cases no rule fits, then failed and refused.
    pure function map_classes(study) result(classes)
        type(study_type), intent(in) :: study
        character(len=:), allocatable :: classes(:)
        character(len=:), allocatable :: candidates(:)
        integer :: k, n, rules, length

        rules = 0
        if (allocated(study%rules)) rules = size(study%rules)
        length = len_trim(outcome_words(outcome_refused))
        if (allocated(study%otherwise)) length = max(length, len(study%otherwise))
        do k = 1, rules
            length = max(length, len(study%rules(k)%class))
        end do
        allocate(character(len=length) :: candidates(rules + 3))
        do k = 1, rules
            candidates(k) = study%rules(k)%class
        end do
        candidates(rules + 1) = ""
        if (allocated(study%otherwise)) candidates(rules + 1) = study%otherwise
        candidates(rules + 2:) = outcome_words([outcome_failed, outcome_refused])
        allocate(character(len=length) :: classes(rules + 3))
        n = 0
        do k = 1, size(candidates)
            if (len_trim(candidates(k)) == 0 .or. any(classes(:n) == candidates(k))) cycle
            n = n + 1
            classes(n) = candidates(k)
        end do
        classes = classes(:n)
    end function map_classes

    !> Read the cases of a study's CSV: its header must be the study's; every complete row
    !> gives a case (a last line without its line end, a case being written, is left out).
    !> Errors name the file, and the line of a row that does not read.
    subroutine read_map_cases(study, csv_path, classes, cases, error)
        !> The study, with x and y of its map set
        type(study_type), intent(in) :: study
        !> The study's CSV
        character(len=*), intent(in) :: csv_path
        !> The classes of map_classes(study)
        character(len=*), intent(in) :: classes(:)
        !> The cases read
        type(map_cases_type), intent(out) :: cases
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, header
        integer :: start, stop, line, n

        call read_text(csv_path, text, error)
        if (allocated(error)) return
        header = study_header(study)
        stop = index(text, lf)
        if (stop == 0 .or. .not. same_text(text(:max(stop - 1, 0)), header)) then
            call fatal_error(error, csv_path // ":1: not the CSV of the study " // study%path &
                & // ": its header must be '" // header // "'", stat_input)
            return
        end if
        allocate(cases%x(count(transfer(text, "a", len(text)) == lf)))
        allocate(cases%y(size(cases%x)), cases%class(size(cases%x)))
        n = 0
        line = 1
        do
            start = stop + 1
            if (start > len(text)) exit
            stop = index(text(start:), lf)
            if (stop == 0) exit
            stop = start + stop - 1
            line = line + 1
            if (len_trim(text(start:stop - 1)) == 0) cycle
            n = n + 1
            call read_case(study, classes, text(start:stop - 1), cases%x(n), cases%y(n), &
                & cases%class(n), error)
            if (allocated(error)) then
                error%message = csv_path // ":" // to_text(line) // ": " // error%message
                return
            end if
        end do
        if (n == 0) then
            call fatal_error(error, csv_path // ": no case to draw: the study's CSV has no " &
                & // "complete row yet", stat_input)
            return
        end if
        cases%x = cases%x(:n)
        cases%y = cases%y(:n)
        cases%class = cases%class(:n)
    end subroutine read_map_cases

    !> The map parameters and class of one row.
    pure subroutine read_case(study, classes, row, x, y, class, error)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: classes(:), row
        real(wp), intent(out) :: x, y
        integer, intent(out) :: class
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: fields(:)
        integer :: np

        np = size(study%parameters)
        call split_fields(row, fields)
        if (size(fields) < np + 3) then
            call fatal_error(error, "a row of " // to_text(size(fields)) // " fields before " &
                & // "the message; the header has " // to_text(np + 3) // " up to the class", &
                & stat_input)
            return
        end if
        call read_value(fields(1 + study%map%x), x, error)
        if (allocated(error)) return
        call read_value(fields(1 + study%map%y), y, error)
        if (allocated(error)) return
        class = findloc(classes, trim(fields(np + 3)), dim=1)
        if (class == 0) call fatal_error(error, "class '" // trim(fields(np + 3)) // "' is " &
            & // "not one of the study's (" // comma_list(classes) // "): was the CSV written " &
            & // "with other &classify rules?", stat_input)
    end subroutine read_case

    !> A parameter's value in a field: a finite number.
    pure subroutine read_value(field, value, error)
        character(len=*), intent(in) :: field
        real(wp), intent(out) :: value
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        value = 0.0_wp
        stat = 1
        if (len_trim(field) > 0 .and. scan(field, "/*") == 0) &
            & read(field, *, iostat=stat) value
        if (stat /= 0 .or. .not. ieee_is_finite(value)) call fatal_error(error, "the " &
            & // "parameter '" // trim(field) // "' is not a finite number", stat_input)
    end subroutine read_value

    !> The whole CSV (rollcon_study_csv), carriage returns dropped; a missing file is an error.
    subroutine read_text(path, text, error)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: text
        type(error_type), allocatable, intent(out) :: error
        integer :: j, n

        call read_csv_text(path, text, error)
        if (allocated(error)) then
            error%message = error%message // " (the study's CSV)"
            return
        end if
        if (.not. allocated(text)) then
            call fatal_error(error, path // ": cannot open the study's CSV: no such file", &
                & stat_io)
            return
        end if
        n = 0
        do j = 1, len(text)
            if (text(j:j) == cr) cycle
            n = n + 1
            text(n:n) = text(j:j)
        end do
        text = text(:n)
    end subroutine read_text

    !> The texts are equal, trailing blanks included.
    pure logical function same_text(text, other)
        character(len=*), intent(in) :: text, other

        same_text = len(text) == len(other) .and. text == other
    end function same_text

end module rollcon_study_map_cases
