! SPDX-License-Identifier: MIT
!> Reads an ADAMS/Solver dataset (.adm) as text: the title line, then statements
!> `NAME/id, ARG, KEY=v1, v2, ..., KEY=expression`, with continuation lines that start with a
!> comma and `!` comments. It knows no statement's meaning: rollcon_adm_keywords resolves names.
!>
!> Arguments are split at commas outside parentheses. A field `KEY=...` starts an assignment; a
!> field that is a plain number continues the list of the assignment before it (`QG = 0, 0, 1`);
!> any other field is a conditional argument (`GROUND`, `DYNAMIC`). A backslash ends an
!> expression, as in ADAMS. Every argument keeps the line it started on, for messages.
module rollcon_adm_lexer
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, upper_case
    use rollcon_input_files, only : input_file_type, text_input_limit
    implicit none
    private

    public :: adm_argument_type, adm_statement_type, adm_text_type, read_adm_text, is_number_text
    public :: upper_case

    !> The value of one list entry or expression, as written
    type :: adm_value_type
        character(len=:), allocatable :: text
    end type adm_value_type

    !> One argument of a statement
    type :: adm_argument_type
        !> Keyword as written, upper-cased
        character(len=:), allocatable :: keyword
        !> False for a conditional argument (a keyword alone)
        logical :: assigned = .false.
        !> The values after '=' (one for an expression, several for a list)
        type(adm_value_type), allocatable :: values(:)
        !> Line the argument starts on
        integer :: line = 0
    end type adm_argument_type

    !> One statement
    type :: adm_statement_type
        !> Statement name as written, upper-cased (PART, MARK, ...)
        character(len=:), allocatable :: name
        !> Identifier after the slash (0 when the statement has none)
        integer :: id = 0
        logical :: has_id = .false.
        !> Line the statement starts on
        integer :: line = 0
        type(adm_argument_type), allocatable :: arguments(:)
    end type adm_statement_type

    !> A dataset as text
    type :: adm_text_type
        !> The file, for messages
        character(len=:), allocatable :: file
        !> The first line
        character(len=:), allocatable :: title
        type(adm_statement_type), allocatable :: statements(:)
    end type adm_text_type

contains

    !> Read `path` into statements; errors name the file and line.
    subroutine read_adm_text(path, dataset, error)
        character(len=*), intent(in) :: path
        type(adm_text_type), intent(out) :: dataset
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, whole
        integer, allocatable :: line_of(:)
        integer :: line, start_line
        type(input_file_type) :: file
        character(len=4096) :: buffer
        logical :: done

        dataset%file = path
        dataset%title = ""
        allocate(dataset%statements(0))
        call file%open(path, "dataset", text_input_limit, error)
        if (allocated(error)) then
            error%stat = stat_input
            return
        end if
        text = ""
        allocate(line_of(0))
        start_line = 0
        line = 0
        do
            call file%next_line(whole, done, error)
            if (done .or. allocated(error)) exit
            buffer = whole
            line = line + 1
            if (len_trim(whole) >= len(buffer)) then
                call fatal_error(error, path // ":" // to_text(line) // ": line longer than " &
                    & // to_text(len(buffer) - 1) // " characters", stat_input)
                exit
            end if
            call check_characters(path, line, buffer, error)
            if (allocated(error)) exit
            if (line == 1) then
                dataset%title = trim(buffer)
                cycle
            end if
            call strip_comment(buffer)
            if (len_trim(buffer) == 0) cycle
            if (buffer(first_nonblank(buffer):first_nonblank(buffer)) == ",") then
                if (start_line == 0) then
                    call fatal_error(error, path // ":" // to_text(line) // ": a continuation " &
                        & // "line (starting with ',') with no statement before it", stat_input)
                    exit
                end if
            else
                if (start_line > 0) call add_statement(dataset, text, line_of, start_line, error)
                if (allocated(error)) exit
                text = ""
                deallocate(line_of)
                allocate(line_of(0))
                start_line = line
            end if
            if (start_line /= line .and. len_trim(text) > 0) then
                ! a comma that ends a line and one that opens the next are one separator
                if (text(len_trim(text):len_trim(text)) == ",") &
                    & buffer(first_nonblank(buffer):first_nonblank(buffer)) = " "
            end if
            line_of = [line_of, spread(line, 1, len_trim(buffer) + 1)]
            text = text // trim(buffer) // " "
        end do
        call file%close()
        if (allocated(error)) then
            error%stat = stat_input
            return
        end if
        if (start_line > 0) call add_statement(dataset, text, line_of, start_line, error)
    end subroutine read_adm_text

    !> A character a dataset cannot hold (control or non-ASCII) is refused by its code.
    subroutine check_characters(path, line, buffer, error)
        character(len=*), intent(in) :: path, buffer
        integer, intent(in) :: line
        type(error_type), allocatable, intent(out) :: error
        integer :: i, code

        do i = 1, len_trim(buffer)
            code = iachar(buffer(i:i))
            if (code == 9) cycle
            if (code < 32 .or. code > 126) then
                call fatal_error(error, path // ":" // to_text(line) // ": column " // to_text(i) &
                    & // ": character code " // to_text(code) // " (datasets are plain ASCII)", &
                    & stat_input)
                return
            end if
        end do
    end subroutine check_characters

    subroutine strip_comment(buffer)
        character(len=*), intent(inout) :: buffer
        integer :: k

        k = index(buffer, "!")
        if (k > 0) buffer(k:) = ""
    end subroutine strip_comment

    pure integer function first_nonblank(text)
        character(len=*), intent(in) :: text

        first_nonblank = verify(text, " " // achar(9))
    end function first_nonblank

    !> Split one statement's text (its lines joined) into name, id and arguments.
    subroutine add_statement(dataset, text, line_of, start_line, error)
        type(adm_text_type), intent(inout) :: dataset
        character(len=*), intent(in) :: text
        integer, intent(in) :: line_of(:), start_line
        type(error_type), allocatable, intent(out) :: error
        type(adm_statement_type) :: statement
        character(len=:), allocatable :: where
        integer :: slash, first, comma, stat

        where = dataset%file // ":" // to_text(start_line) // ": "
        statement%line = start_line
        allocate(statement%arguments(0))
        slash = index(text, "/")
        comma = index(text, ",")
        if (slash == 0 .or. (comma > 0 .and. comma < slash)) slash = min(len(text) + 1, &
            & merge(comma, len(text) + 1, comma > 0))
        statement%name = upper_case(trim(adjustl(text(:slash - 1))))
        if (len(statement%name) == 0 .or. verify(statement%name, &
            & "ABCDEFGHIJKLMNOPQRSTUVWXYZ_") > 0) then
            call fatal_error(error, where // "'" // trim(adjustl(text(:slash - 1))) &
                & // "' is not a statement name (expected NAME/id, ARG, ...)", stat_input)
            return
        end if
        first = slash + 1
        if (slash <= len(text)) then
            if (text(slash:slash) == "/") then
                comma = index(text(first:), ",")
                if (comma == 0) comma = len(text) - first + 2
                if (is_integer_text(text(first:first + comma - 2))) then
                    read(text(first:first + comma - 2), *, iostat=stat) statement%id
                    if (stat /= 0 .or. statement%id <= 0) then
                        call fatal_error(error, where // statement%name // ": the id must be " &
                            & // "a positive integer, got '" &
                            & // trim(adjustl(text(first:first + comma - 2))) // "'", stat_input)
                        return
                    end if
                    statement%has_id = .true.
                    first = first + comma
                end if
            end if
        end if
        call split_arguments(text, line_of, first, where // statement%name, statement, error)
        if (allocated(error)) return
        dataset%statements = [dataset%statements, statement]
    end subroutine add_statement

    !> The arguments from position `first` on.
    subroutine split_arguments(text, line_of, first, where, statement, error)
        character(len=*), intent(in) :: text, where
        integer, intent(in) :: line_of(:), first
        type(adm_statement_type), intent(inout) :: statement
        type(error_type), allocatable, intent(out) :: error
        type(adm_argument_type) :: argument
        character(len=:), allocatable :: field
        integer :: start, finish, equals, n

        start = first
        do while (start <= len(text))
            call next_field(text, start, finish, error, where)
            if (allocated(error)) return
            field = trim(adjustl(text(start:finish - 1)))
            if (len(field) > 0) then
                if (field(len(field):len(field)) == "\") field = trim(field(:len(field) - 1))
            end if
            n = size(statement%arguments)
            equals = top_level_equals(field)
            if (len(field) == 0) then
                if (finish <= len(text)) then
                    call fatal_error(error, line_text(where, line_of, start) // ": an empty " &
                        & // "argument (two commas in a row)", stat_input)
                    return
                end if
            else if (equals > 0) then
                argument%keyword = upper_case(trim(field(:equals - 1)))
                argument%assigned = .true.
                argument%line = line_of(min(start, size(line_of)))
                allocate(argument%values(1))
                argument%values(1)%text = trim(adjustl(field(equals + 1:)))
                statement%arguments = [statement%arguments, argument]
                deallocate(argument%values)
            else if (is_number_text(field) .and. n > 0) then
                if (.not. statement%arguments(n)%assigned) then
                    call fatal_error(error, line_text(where, line_of, start) // ": a value '" &
                        & // field // "' follows " // statement%arguments(n)%keyword &
                        & // ", which takes none", stat_input)
                    return
                end if
                statement%arguments(n)%values = [statement%arguments(n)%values, &
                    & adm_value_type(field)]
            else
                argument%keyword = upper_case(field)
                argument%assigned = .false.
                argument%line = line_of(min(start, size(line_of)))
                allocate(argument%values(0))
                statement%arguments = [statement%arguments, argument]
                deallocate(argument%values)
            end if
            start = finish + 1
        end do
    end subroutine split_arguments

    !> The end of the field starting at `start`: the next comma outside parentheses.
    subroutine next_field(text, start, finish, error, where)
        character(len=*), intent(in) :: text, where
        integer, intent(in) :: start
        integer, intent(out) :: finish
        type(error_type), allocatable, intent(out) :: error
        integer :: depth

        depth = 0
        finish = start
        do while (finish <= len(text))
            select case (text(finish:finish))
            case ("(")
                depth = depth + 1
            case (")")
                depth = depth - 1
                if (depth < 0) then
                    call fatal_error(error, where // ": a ')' with no '(' before it", stat_input)
                    return
                end if
            case (",")
                if (depth == 0) return
            end select
            finish = finish + 1
        end do
        if (depth > 0) call fatal_error(error, where // ": a '(' is not closed", stat_input)
    end subroutine next_field

    pure integer function top_level_equals(field)
        character(len=*), intent(in) :: field
        integer :: i, depth

        top_level_equals = 0
        depth = 0
        do i = 1, len(field)
            if (field(i:i) == "(") depth = depth + 1
            if (field(i:i) == ")") depth = depth - 1
            if (field(i:i) == "=" .and. depth == 0) then
                top_level_equals = i
                return
            end if
        end do
    end function top_level_equals

    function line_text(where, line_of, at) result(text)
        character(len=*), intent(in) :: where
        integer, intent(in) :: line_of(:), at
        character(len=:), allocatable :: text
        integer :: colon

        ! where is "file:line: NAME"; give the argument's own line instead
        colon = index(where, ": ", back=.true.)
        text = where
        if (colon > 0 .and. size(line_of) > 0) then
            text = where(:index(where(:colon - 1), ":", back=.true.)) &
                & // to_text(line_of(min(at, size(line_of)))) // where(colon:)
        end if
    end function line_text

    !> True for a number as a dataset writes it: [sign] digits [. digits] [E|D [sign] digits],
    !> then optionally D (degrees).
    pure logical function is_number_text(text)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: t
        integer :: i, digits

        t = upper_case(trim(adjustl(text)))
        is_number_text = .false.
        i = 1
        digits = 0
        if (len(t) > 0) then
            if (t(1:1) == "+" .or. t(1:1) == "-") i = 2
        end if
        call skip_digits(t, i, digits)
        if (i <= len(t)) then
            if (t(i:i) == ".") then
                i = i + 1
                call skip_digits(t, i, digits)
            end if
        end if
        if (digits == 0) return
        if (i < len(t)) then
            if (t(i:i) == "E" .or. t(i:i) == "D") then
                if (verify(t(i + 1:i + 1), "+-0123456789") == 0) then
                    i = i + 1
                    if (t(i:i) == "+" .or. t(i:i) == "-") i = i + 1
                    call skip_digits(t, i, digits)
                    if (t(i - 1:i - 1) == "+" .or. t(i - 1:i - 1) == "-") return
                end if
            end if
        end if
        if (i == len(t)) then
            if (t(i:i) == "D") i = i + 1
        end if
        is_number_text = i > len(t)
    end function is_number_text

    pure subroutine skip_digits(t, i, digits)
        character(len=*), intent(in) :: t
        integer, intent(inout) :: i, digits

        do while (i <= len(t))
            if (index("0123456789", t(i:i)) == 0) exit
            i = i + 1
            digits = digits + 1
        end do
    end subroutine skip_digits

    pure logical function is_integer_text(text)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: t

        t = trim(adjustl(text))
        is_integer_text = len(t) > 0 .and. verify(t, "+-0123456789") == 0
    end function is_integer_text


end module rollcon_adm_lexer
