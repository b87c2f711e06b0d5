! SPDX-License-Identifier: MIT
!> Reads an ADAMS/Solver dataset (.adm) as text: the title line, then statements
!> `NAME/id, ARG, KEY=v1, v2, ..., KEY=expression`, with continuation lines that start with a
!> comma and `!` comments. It knows no statement's meaning: rollcon_adm_keywords resolves names.
!>
!> The layout is ADAMS's, as ADAMS/View writes it too: a statement's name and slash may stand
!> alone on a line with its arguments on the comma lines that follow (`UNITS/` then
!> `, FORCE = NEWTON`), and a comma that ends a line and one that begins the next are one.
!> Arguments are split at commas and backslashes outside parentheses. A field `KEY=...`
!> starts an assignment; a field that is a name alone (`GROUND`, `DYNAMIC`) is a conditional
!> argument; any other field continues the assignment before it: the next entry of a list
!> (`QG = 0, 0, 1`) or the next piece of an expression continued on comma lines at any depth
!> (`FUNCTION = -100*(DM(10,20)-2)` then `, - 1.0*VR(10,20)`), as ADAMS reads an expression
!> to a backslash or to the statement's end. A name alone continues an expression too when
!> the piece before it ends with an operator (`FUNCTION = 2*` then `, TIME`). A backslash
!> ends an expression (`F2=JOINT(1,0,2,0)\F3=...`); a comma after it is the same separator.
!> Every argument keeps the line it started on, for messages.
!>
!> The file is ASCII text: a UTF-8 byte-order mark at its start is skipped, a tab or the
!> carriage return of a CRLF line end is a blank, and a non-ASCII character is allowed inside a
!> `!` comment only (as in a scene file, rollcon_namelist_bytes). Reading takes time linear in
!> the size of the file, however its statements are split over lines.
module rollcon_adm_lexer
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, upper_case
    use rollcon_namelist_lexer, only : line_type, read_lines
    use rollcon_namelist_bytes, only : visible, utf8_length
    implicit none
    private

    public :: adm_argument_type, adm_statement_type, adm_text_type, read_adm_text, is_number_text
    public :: is_nonfinite_text
    public :: lex_adm_lines, read_dataset_lines, max_line_length
    public :: upper_case

    !> Longest line a dataset may hold [characters]
    integer, parameter :: max_line_length = 4095
    !> The UTF-8 encoding of U+FEFF, the byte-order mark
    character(len=*), parameter :: byte_order_mark = achar(239) // achar(187) // achar(191)
    !> What a field of a statement is (split_arguments)
    integer, parameter :: field_empty = 0, field_assignment = 1, field_value = 2, &
        & field_conditional = 3

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
        type(line_type), allocatable :: lines(:)

        call read_dataset_lines(path, lines, error)
        if (allocated(error)) then
            dataset%file = path
            dataset%title = ""
            allocate(dataset%statements(0))
            return
        end if
        call lex_adm_lines(path, lines, dataset, error)
    end subroutine read_adm_text

    !> Every line of the file at `path`, as it is (any length, without its line end): a
    !> regular file of at most text_input_limit bytes (rollcon_input_files; a FIFO, a device or
    !> a larger file is refused at once, naming the file).
    subroutine read_dataset_lines(path, lines, error)
        character(len=*), intent(in) :: path
        type(line_type), allocatable, intent(out) :: lines(:)
        type(error_type), allocatable, intent(out) :: error

        call read_lines(path, lines, error, "dataset")
    end subroutine read_dataset_lines

    !> The statements of a dataset's lines (read from `path`, which messages name). Each line
    !> is looked at once and each statement's text is joined once: the time is linear in the
    !> size of the dataset.
    subroutine lex_adm_lines(path, lines, dataset, error)
        character(len=*), intent(in) :: path
        !> The lines of the file, without line ends
        type(line_type), intent(in) :: lines(:)
        type(adm_text_type), intent(out) :: dataset
        type(error_type), allocatable, intent(out) :: error
        !> The lines as statements see them: comments dropped, tabs and carriage returns blank
        type(line_type), allocatable :: kept(:)
        type(adm_statement_type), allocatable :: statements(:)
        integer :: i, first, count

        dataset%file = path
        dataset%title = ""
        allocate(kept(size(lines)), statements(16))
        count = 0
        first = 0
        do i = 1, size(lines)
            call check_line(path, i, lines(i)%text, kept(i)%text, error)
            if (allocated(error)) exit
            if (i == 1) then
                ! the title, whatever it holds (comments are not dropped from it)
                dataset%title = trim(kept(1)%text)
                kept(1)%text = ""
                cycle
            end if
            if (len_trim(kept(i)%text) == 0) cycle
            if (kept(i)%text(first_nonblank(kept(i)%text):first_nonblank(kept(i)%text)) &
                & == ",") then
                if (first == 0) then
                    call fatal_error(error, path // ":" // to_text(i) // ": a continuation " &
                        & // "line (starting with ',') with no statement before it", stat_input)
                    exit
                end if
            else
                if (first > 0) call add_statement(path, kept, first, i - 1, statements, count, &
                    & error)
                if (allocated(error)) exit
                first = i
            end if
        end do
        if (.not. allocated(error) .and. first > 0) call add_statement(path, kept, first, &
            & size(lines), statements, count, error)
        dataset%statements = statements(:count)
    end subroutine lex_adm_lines

    !> Check the bytes of line `line` and give the text statements read from it (`kept`): a
    !> UTF-8 byte-order mark at the start of the file is skipped; tab (a blank) and the
    !> carriage return of a CRLF line end are the only control characters; a non-ASCII
    !> character is allowed in a comment only. Messages show a character visibly (`\x00`,
    !> `U+00E9`), never raw.
    subroutine check_line(path, line, text, kept, error)
        character(len=*), intent(in) :: path, text
        integer, intent(in) :: line
        character(len=:), allocatable, intent(out) :: kept
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        integer :: j, code, comment

        kept = text
        if (line == 1 .and. index(text, byte_order_mark) == 1) kept = text(len(byte_order_mark) &
            & + 1:)
        where = path // ":" // to_text(line) // ": "
        if (len_trim(kept) > max_line_length) then
            call fatal_error(error, where // "line longer than " // to_text(max_line_length) &
                & // " characters", stat_input)
            return
        end if
        ! the title has no comment: all of it is text
        comment = 0
        if (line > 1) comment = index(kept, "!")
        do j = 1, len_trim(kept)
            code = iachar(kept(j:j))
            if (code == 9 .or. code == 13) then
                kept(j:j) = " "
            else if (code < 32 .or. code == 127) then
                call fatal_error(error, where // "control character " // visible(kept(j:j)) &
                    & // " at column " // to_text(j) // "; a dataset is text (a tab is a " &
                    & // "blank)", stat_input)
                return
            else if (code > 127 .and. (comment == 0 .or. j < comment)) then
                call fatal_error(error, where // "non-ASCII character " &
                    & // visible(kept(j:j + utf8_length(kept(j:)) - 1)) // " at column " &
                    & // to_text(j) // "; outside comments a dataset is ASCII (a byte-order " &
                    & // "mark is allowed at the start only)", stat_input)
                return
            end if
        end do
        if (comment > 0) kept = kept(:comment - 1)
    end subroutine check_line

    !> Position of the first character that is not a blank (0: none).
    pure integer function first_nonblank(text)
        character(len=*), intent(in) :: text

        first_nonblank = verify(text, " ")
    end function first_nonblank

    !> Lines first..last (blank ones skipped) joined as one statement, split into name, id and
    !> arguments, and appended to statements(:count), which grows by doubling.
    subroutine add_statement(path, kept, first, last, statements, count, error)
        character(len=*), intent(in) :: path
        type(line_type), intent(in) :: kept(:)
        integer, intent(in) :: first, last
        type(adm_statement_type), allocatable, intent(inout) :: statements(:)
        integer, intent(inout) :: count
        type(error_type), allocatable, intent(out) :: error
        type(adm_statement_type), allocatable :: grown(:)
        character(len=:), allocatable :: text
        integer, allocatable :: line_of(:)
        character :: last_char
        integer :: i, n, at, c

        n = 0
        do i = first, last
            if (len_trim(kept(i)%text) > 0) n = n + len_trim(kept(i)%text) + 1
        end do
        allocate(character(len=n) :: text)
        allocate(line_of(n))
        at = 0
        last_char = " "
        do i = first, last
            n = len_trim(kept(i)%text)
            if (n == 0) cycle
            text(at + 1:at + n + 1) = kept(i)%text(:n) // " "
            line_of(at + 1:at + n + 1) = i
            if (i > first .and. last_char == ",") then
                ! a comma that ends a line and one that opens the next are one separator
                c = at + first_nonblank(kept(i)%text)
                text(c:c) = " "
            end if
            c = len_trim(text(at + 1:at + n))
            if (c > 0) last_char = text(at + c:at + c)
            at = at + n + 1
        end do
        if (count == size(statements)) then
            allocate(grown(2*count))
            grown(:count) = statements
            call move_alloc(grown, statements)
        end if
        call split_statement(path, text, line_of, first, statements(count + 1), error)
        if (allocated(error)) return
        count = count + 1
    end subroutine add_statement

    !> Split one statement's text (its lines joined) into name, id and arguments.
    subroutine split_statement(path, text, line_of, start_line, statement, error)
        character(len=*), intent(in) :: path, text
        integer, intent(in) :: line_of(:), start_line
        type(adm_statement_type), intent(out) :: statement
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        integer :: slash, first, comma, stat

        where = path // ":" // to_text(start_line) // ": "
        statement%line = start_line
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
                ! NAME/ alone on its line, its arguments on the comma lines below (ADAMS/View's
                ! layout): the comma that begins them follows the slash
                if (first <= len(text)) then
                    if (first_nonblank(text(first:)) > 0) then
                        if (text(first + first_nonblank(text(first:)) - 1:first &
                            & + first_nonblank(text(first:)) - 1) == ",") first = first &
                            & + first_nonblank(text(first:))
                    end if
                end if
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
    end subroutine split_statement

    !> The arguments from position `first` on. The fields are found and classed first, then
    !> every argument and list is allocated once at its size: linear in the statement's length.
    subroutine split_arguments(text, line_of, first, where, statement, error)
        character(len=*), intent(in) :: text, where
        integer, intent(in) :: line_of(:), first
        type(adm_statement_type), intent(inout) :: statement
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: field
        !> Each field's place, kind, and argument (the one a value belongs to)
        integer, allocatable :: starts(:), finishes(:), kinds(:), argument_of(:), filled(:)
        !> For each argument: a backslash ended it; its last piece is open (empty, or ends
        !> with an operator), so a name alone after it continues it
        logical, allocatable :: closed(:), open_end(:)
        integer :: start, finish, n, k, a, last, equals
        logical :: backslash

        n = count([(text(k:k) == "," .or. text(k:k) == "\", k = first, len(text))]) + 1
        allocate(starts(n), finishes(n), kinds(n), argument_of(n), closed(n), open_end(n))
        closed = .false.
        open_end = .false.
        ! pass 1: each field's place, kind and argument; refusals in the order of the text
        n = 0
        a = 0
        last = 0
        start = first
        do while (start <= len(text))
            call next_field(text, start, finish, error, where)
            if (allocated(error)) return
            backslash = .false.
            if (finish <= len(text)) backslash = text(finish:finish) == "\"
            field = trim(adjustl(text(start:finish - 1)))
            n = n + 1
            starts(n) = start
            finishes(n) = finish
            if (len(field) == 0) then
                kinds(n) = field_empty
                if (finish <= len(text)) then
                    call fatal_error(error, line_text(where, line_of, start) // ": an empty " &
                        & // "argument (" // trim(merge("a backslash", "two commas ", &
                        & backslash)) // " with no argument before it)", stat_input)
                    return
                end if
            else if (top_level_equals(field) > 0) then
                kinds(n) = field_assignment
                a = a + 1
                argument_of(n) = a
                last = n
                closed(a) = backslash
                open_end(a) = ends_open(field(top_level_equals(field) + 1:))
            else if (is_name(field) .and. .not. continues(a) .and. &
                & .not. is_nonfinite_text(field)) then
                kinds(n) = field_conditional
                a = a + 1
                argument_of(n) = a
                last = n
                closed(a) = backslash
            else
                ! the next entry of a list, or the next piece of an expression
                if (a == 0) then
                    call fatal_error(error, line_text(where, line_of, start) // ": '" // field &
                        & // "' is not an argument (expected KEY=value or a keyword)", stat_input)
                    return
                end if
                if (kinds(last) /= field_assignment) then
                    call fatal_error(error, line_text(where, line_of, start) &
                        & // stray_value(text, starts, finishes, kinds, last, field, &
                        & statement), stat_input)
                    return
                end if
                if (closed(a)) then
                    call fatal_error(error, line_text(where, line_of, start) // ": '" // field &
                        & // "' follows " // upper_case(field_key(text(starts(last): &
                        & finishes(last) - 1))) // ", which a backslash ended (a value or " &
                        & // "expression goes before the backslash)", stat_input)
                    return
                end if
                kinds(n) = field_value
                argument_of(n) = a
                closed(a) = backslash
                open_end(a) = ends_open(field)
            end if
            start = finish + 1
            ! a comma after a backslash is the same separator
            if (backslash .and. start <= len(text)) then
                if (first_nonblank(text(start:)) > 0) then
                    if (text(start + first_nonblank(text(start:)) - 1:start &
                        & + first_nonblank(text(start:)) - 1) == ",") start = start &
                        & + first_nonblank(text(start:))
                end if
            end if
        end do
        ! pass 2: the arguments, each list allocated at its length
        allocate(statement%arguments(a), filled(a))
        filled = 0
        do k = 1, n
            if (kinds(k) /= field_empty) filled(argument_of(k)) = filled(argument_of(k)) + 1
        end do
        do k = 1, n
            if (kinds(k) == field_empty) cycle
            field = trim(adjustl(text(starts(k):finishes(k) - 1)))
            associate (argument => statement%arguments(argument_of(k)))
                select case (kinds(k))
                case (field_assignment)
                    equals = top_level_equals(field)
                    argument%keyword = upper_case(trim(field(:equals - 1)))
                    argument%assigned = .true.
                    argument%line = line_of(min(starts(k), size(line_of)))
                    allocate(argument%values(filled(argument_of(k))))
                    argument%values(1)%text = trim(adjustl(field(equals + 1:)))
                    filled(argument_of(k)) = 1
                case (field_value)
                    filled(argument_of(k)) = filled(argument_of(k)) + 1
                    argument%values(filled(argument_of(k)))%text = field
                case default
                    argument%keyword = upper_case(field)
                    argument%assigned = .false.
                    argument%line = line_of(min(starts(k), size(line_of)))
                    allocate(argument%values(0))
                end select
            end associate
        end do

    contains

        !> Argument j is an assignment still open: a name alone after it continues it.
        pure logical function continues(j)
            integer, intent(in) :: j

            continues = .false.
            if (j == 0) return
            continues = kinds(last) == field_assignment .and. open_end(j) .and. .not. closed(j)
        end function continues

    end subroutine split_arguments

    !> The keyword of an assignment's field as written (before its '='), or the field.
    pure function field_key(raw) result(key)
        character(len=*), intent(in) :: raw
        character(len=:), allocatable :: key

        key = trim(adjustl(raw))
        if (top_level_equals(key) > 0) key = trim(key(:top_level_equals(key) - 1))
    end function field_key

    !> A piece of a value that an expression must go on from: empty, or ending with an
    !> operator (+ - * / or the ':' and '(' of a function's arguments).
    pure logical function ends_open(piece)
        character(len=*), intent(in) :: piece
        integer :: n

        n = len_trim(piece)
        ends_open = n == 0
        if (n > 0) ends_open = index("+-*/:(", piece(n:n)) > 0
    end function ends_open

    !> A name alone: a letter, then letters, digits and underscores.
    pure logical function is_name(field)
        character(len=*), intent(in) :: field
        character(len=:), allocatable :: word

        word = upper_case(trim(field))
        is_name = len(word) > 0
        if (.not. is_name) return
        is_name = verify(word(1:1), "ABCDEFGHIJKLMNOPQRSTUVWXYZ") == 0 .and. &
            & verify(word, "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") == 0
    end function is_name

    !> The end of the field starting at `start`: the next comma or backslash outside
    !> parentheses (len(text) + 1 at the end of the statement).
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
            case (",", "\")
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

    !> Why a value follows a conditional argument, in words that go after the statement's
    !> name. A word right after an assignment's list (`IP=2, heavy, 3`) stands in that list
    !> and is not a number ("/2 IP: 'heavy' is not a number (it stands in the list of IP: the
    !> value '3' follows it)"); else the value follows a word that takes none (": a value '1'
    !> follows GROUND, which takes none").
    function stray_value(text, starts, finishes, kinds, last, value, statement) result(words)
        character(len=*), intent(in) :: text, value
        integer, intent(in) :: starts(:), finishes(:), kinds(:), last
        type(adm_statement_type), intent(in) :: statement
        character(len=:), allocatable :: words, word
        integer :: list

        word = trim(adjustl(text(starts(last):finishes(last) - 1)))
        words = ": a value '" // value // "' follows " // upper_case(word) // ", which takes none"
        if (last <= 1) return
        if (kinds(last - 1) /= field_assignment .and. kinds(last - 1) /= field_value) return
        ! the assignment whose list the word stands in
        list = last - 1
        do while (kinds(list) /= field_assignment)
            list = list - 1
        end do
        words = upper_case(trim(adjustl(text(starts(list):starts(list) &
            & + index(text(starts(list):finishes(list) - 1), "=") - 2))))
        words = " " // words // ": '" // word // "' is not a number (it stands in the list of " &
            & // words // ": the value '" // value // "' follows it)"
        if (statement%has_id) words = "/" // to_text(statement%id) // words
    end function stray_value

    !> NaN or Inf written as a number (NAN, INF, INFINITY, any case, a sign allowed): a value
    !> that Fortran reads but no list may hold.
    pure logical function is_nonfinite_text(text)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: t

        t = upper_case(trim(adjustl(text)))
        if (len(t) > 0) then
            if (t(1:1) == "+" .or. t(1:1) == "-") t = t(2:)
        end if
        is_nonfinite_text = t == "NAN" .or. t == "INF" .or. t == "INFINITY"
    end function is_nonfinite_text

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
