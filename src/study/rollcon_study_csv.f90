! SPDX-License-Identifier: MIT
!> A study's CSV (docs/studies.md): its header, one row per case, and what a rerun finds in
!> it. The columns: `case`, the parameters (named group%key), `outcome`, `class`, `flag`,
!> the measures (rollcon_study_measures), `message` (quoted). A row is written whole and
!> flushed when its case ends; a rerun keeps every complete row, drops a last line cut short
!> (a run killed while writing), and skips the cases whose parameters are already there.
module rollcon_study_csv
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_input
    use rollcon_text, only : to_text
    use rollcon_study_type, only : study_type
    use rollcon_study_measures, only : case_result_type, measure_names, outcome_words
    use rollcon_input_files, only : read_input_file, csv_input_limit
    use rollcon_c_stream, only : c_stream_type
    implicit none
    private

    public :: study_header, study_row, case_key, read_done_cases, read_csv_text, split_fields

    character(len=*), parameter :: lf = achar(10)

contains

    !> The header line (no line end).
    pure function study_header(study) result(line)
        type(study_type), intent(in) :: study
        character(len=:), allocatable :: line
        integer :: k

        line = "case"
        do k = 1, size(study%parameters)
            line = line // "," // study%parameters(k)%group // "%" // study%parameters(k)%key
        end do
        line = line // ",outcome,class,flag"
        do k = 1, size(measure_names)
            line = line // "," // trim(measure_names(k))
        end do
        line = line // ",message"
    end function study_header

    !> The row of case i with its parameters' texts (no line end). A measure the case lacks
    !> is an empty field.
    pure function study_row(i, texts, result) result(line)
        integer, intent(in) :: i
        character(len=*), intent(in) :: texts(:)
        type(case_result_type), intent(in) :: result
        character(len=:), allocatable :: line
        integer :: k

        line = to_text(i)
        do k = 1, size(texts)
            line = line // "," // trim(texts(k))
        end do
        line = line // "," // trim(outcome_words(result%outcome)) // "," // result%class &
            & // "," // to_text(result%flag)
        do k = 1, size(measure_names)
            line = line // ","
            if (result%known(k)) line = line // to_text(result%values(k))
        end do
        line = line // "," // csv_quoted(result%message)
    end function study_row

    !> What identifies a case across reruns: its parameters' texts.
    pure function case_key(texts) result(key)
        character(len=*), intent(in) :: texts(:)
        character(len=:), allocatable :: key
        integer :: k

        key = ""
        do k = 1, size(texts)
            key = key // trim(texts(k)) // ";"
        end do
    end function case_key

    !> The case numbers and keys of the rows already in the CSV at path (none when it does
    !> not exist). The header must be this study's. A last line without its line end (a run
    !> killed while writing it) is cut off the file; any other row that does not have the
    !> header's number of fields is an error naming its line.
    subroutine read_done_cases(path, study, cases, keys, error, lines)
        character(len=*), intent(in) :: path
        type(study_type), intent(in) :: study
        integer, allocatable, intent(out) :: cases(:)
        character(len=:), allocatable, intent(out) :: keys(:)
        type(error_type), allocatable, intent(out) :: error
        !> Whole lines the file holds, its header included (0: no file, or an empty one)
        integer, intent(out), optional :: lines
        character(len=:), allocatable :: text, header
        character(len=:), allocatable :: fields(:)
        integer :: start, stop, rows, row, np, complete, stat, width, k

        np = size(study%parameters)
        allocate(cases(0))
        allocate(character(len=0) :: keys(0))
        if (present(lines)) lines = 0
        call read_csv_text(path, text, error)
        if (allocated(error) .or. .not. allocated(text)) return
        header = study_header(study)
        complete = index(text, lf, back=.true.)
        if (complete < len(text)) then
            call cut_file(path, text(:complete), error)
            if (allocated(error)) return
            text = text(:complete)
        end if
        if (len(text) == 0) return
        stop = index(text, lf)
        if (stop > 1) then
            if (text(stop - 1:stop - 1) == achar(13)) then
                call fatal_error(error, path // ":1: its lines end in CR LF (a file saved on " &
                    & // "Windows?); rollcon writes and reads a study's CSV with LF line ends: " &
                    & // "convert it (dos2unix) or remove it to start again", stat_input)
                return
            end if
        end if
        if (text(:stop - 1) /= header) then
            call fatal_error(error, path // ":1: the header is not this study's (" // study%path &
                & // "); expected '" // header // "', found '" // text(:stop - 1) // "'. Give " &
                & // "another --output, or remove the file to start again", stat_input)
            return
        end if
        rows = count_of(text, lf) - 1
        if (present(lines)) lines = rows + 1
        deallocate(cases, keys)
        allocate(cases(rows))
        width = longest_line(text)
        allocate(character(len=width) :: keys(rows))
        do row = 1, rows
            start = stop + 1
            stop = start - 1 + index(text(start:), lf)
            call split_fields(text(start:stop - 1), fields)
            if (size(fields) /= count_of(header, ",") + 1) then
                call fatal_error(error, path // ":" // to_text(row + 1) // ": a row of " &
                    & // to_text(size(fields)) // " fields, the header has " &
                    & // to_text(count_of(header, ",") + 1) // "; the file is not a " &
                    & // "study's CSV as rollcon writes it", stat_input)
                return
            end if
            read(fields(1), *, iostat=stat) cases(row)
            if (stat /= 0) cases(row) = 0
            ! element by element: gfortran 12 passes a section of a deferred-length array
            ! to an assumed-length dummy as the wrong elements
            keys(row) = ""
            do k = 2, np + 1
                keys(row) = trim(keys(row)) // trim(fields(k)) // ";"
            end do
        end do
    end subroutine read_done_cases

    !> The whole file as bytes; text unallocated when the file does not exist. A regular file
    !> of at most csv_input_limit bytes (rollcon_input_files).
    subroutine read_csv_text(path, text, error)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: text
        type(error_type), allocatable, intent(out) :: error
        logical :: exists

        inquire(file=path, exist=exists)
        if (.not. exists) return
        call read_input_file(path, "study CSV", csv_input_limit, text, error)
        if (allocated(error)) deallocate(text)
    end subroutine read_csv_text

    !> Write text as the whole file (the rows kept, without a last line cut short), through
    !> the C library with every write checked (rollcon_c_stream).
    subroutine cut_file(path, text, error)
        character(len=*), intent(in) :: path, text
        type(error_type), allocatable, intent(out) :: error
        type(c_stream_type) :: file
        type(error_type), allocatable :: close_error

        call file%open_file(path, error)
        if (.not. allocated(error)) call file%put(text, error)
        call file%close_file(close_error)
        if (.not. allocated(error) .and. allocated(close_error)) &
            & call move_alloc(close_error, error)
        if (allocated(error)) error%message = path // ": cannot rewrite it without its last " &
            & // "line, cut short: " // error%message
    end subroutine cut_file

    !> Fields of a CSV line: commas separate them except inside double quotes.
    pure subroutine split_fields(line, fields)
        character(len=*), intent(in) :: line
        character(len=:), allocatable, intent(out) :: fields(:)
        integer :: j, start
        logical :: quoted

        allocate(character(len=len(line)) :: fields(0))
        quoted = .false.
        start = 1
        do j = 1, len(line) + 1
            if (j <= len(line)) then
                if (line(j:j) == '"') quoted = .not. quoted
                if (quoted .or. line(j:j) /= ",") cycle
            end if
            fields = [character(len=len(line)) :: fields, line(start:j - 1)]
            start = j + 1
        end do
    end subroutine split_fields

    !> Length of the longest line of text.
    pure integer function longest_line(text) result(longest)
        character(len=*), intent(in) :: text
        integer :: j, start

        longest = 0
        start = 1
        do j = 1, len(text)
            if (text(j:j) /= lf) cycle
            longest = max(longest, j - start)
            start = j + 1
        end do
    end function longest_line

    !> Occurrences of the character c in text.
    pure integer function count_of(text, c) result(n)
        character(len=*), intent(in) :: text
        character(len=1), intent(in) :: c
        integer :: j

        n = 0
        do j = 1, len(text)
            if (text(j:j) == c) n = n + 1
        end do
    end function count_of

    !> text in double quotes, a quote inside doubled, line ends as blanks.
    pure function csv_quoted(text) result(field)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: field
        integer :: j

        field = '"'
        do j = 1, len(text)
            select case (text(j:j))
            case ('"')
                field = field // '""'
            case (achar(10), achar(13))
                field = field // " "
            case default
                field = field // text(j:j)
            end select
        end do
        field = field // '"'
    end function csv_quoted

end module rollcon_study_csv
