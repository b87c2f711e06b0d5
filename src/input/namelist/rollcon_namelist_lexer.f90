! SPDX-License-Identifier: MIT
!> Reads a namelist file as text and splits it into groups of `key = value` assignments, with
!> line numbers, so that every mistake can be reported at its place; rollcon_key_values then
!> converts each value.
module rollcon_namelist_lexer
    use rollcon_error, only : error_type, input_error, stat_input
    use rollcon_input_files, only : input_file_type, text_input_limit
    use rollcon_text, only : to_text, to_lower => lower_case
    implicit none
    private

    public :: line_type, assignment_type, group_type
    public :: read_lines, scan_groups, to_lower

    !> One line of the file
    type :: line_type
        character(len=:), allocatable :: text
    end type line_type

    !> One `key = value` of a group
    type :: assignment_type
        !> Key, lowercase
        character(len=:), allocatable :: key
        !> Value as written (a quoted string keeps its quotes)
        character(len=:), allocatable :: value
        !> The value is a quoted string
        logical :: quoted = .false.
        !> Line of the key
        integer :: line = 0
    end type assignment_type

    !> One namelist group, `&name ... /`
    type :: group_type
        !> Name without the ampersand, lowercase
        character(len=:), allocatable :: name
        !> Line of `&name`
        integer :: line = 0
        !> Its assignments, in file order
        type(assignment_type), allocatable :: assignments(:)
    end type group_type

    !> Token kinds
    integer, parameter :: token_group = 1, token_end = 2, token_equals = 3, token_comma = 4, &
        & token_word = 5, token_string = 6

    type :: token_type
        integer :: kind = token_word
        character(len=:), allocatable :: text
        integer :: line = 0
    end type token_type

    !> Blanks: space, tab, and the carriage return of a file with CRLF line ends
    character(len=*), parameter :: blanks = " " // achar(9) // achar(13)
    !> Characters that end a word
    character(len=*), parameter :: delimiters = blanks // ",=/!&'"""

contains

    !> Read every line of a text file: a regular file of at most text_input_limit bytes
    !> (rollcon_input_files; a FIFO, a device or a larger file is refused, naming the file).
    subroutine read_lines(path, lines, error, what)
        !> File to read
        character(len=*), intent(in) :: path
        !> Its lines, without line ends
        type(line_type), allocatable, intent(out) :: lines(:)
        type(error_type), allocatable, intent(out) :: error
        !> What the file is, for messages (default "scene file")
        character(len=*), intent(in), optional :: what
        type(line_type), allocatable :: grown(:)
        type(input_file_type) :: file
        character(len=:), allocatable :: text
        logical :: done
        integer :: n

        if (present(what)) then
            call file%open(path, what, text_input_limit, error)
        else
            call file%open(path, "scene file", text_input_limit, error)
        end if
        if (allocated(error)) then
            ! an input that cannot be read is the input's fault, as the readers report theirs
            error%stat = stat_input
            return
        end if
        allocate(lines(64))
        n = 0
        do
            call file%next_line(text, done, error)
            if (done .or. allocated(error)) exit
            if (n == size(lines)) then
                allocate(grown(2*n))
                grown(:n) = lines
                call move_alloc(grown, lines)
            end if
            n = n + 1
            call move_alloc(text, lines(n)%text)
        end do
        call file%close()
        if (allocated(error)) then
            ! the reader's own message, as the scene readers report theirs: file: reason
            error%stat = stat_input
            return
        end if
        lines = lines(:n)
    end subroutine read_lines

    !> Split the lines into groups; report stray text, unknown and repeated groups, unclosed
    !> groups, assignments without a value or with several, and keys given twice.
    subroutine scan_groups(path, lines, known, groups, error)
        !> File the lines come from, for messages
        character(len=*), intent(in) :: path
        !> Lines of the file
        type(line_type), intent(in) :: lines(:)
        !> Names of the groups a file may hold, lowercase
        character(len=*), intent(in) :: known(:)
        !> The groups found, in file order
        type(group_type), allocatable, intent(out) :: groups(:)
        type(error_type), allocatable, intent(out) :: error
        type(token_type), allocatable :: tokens(:)
        type(group_type) :: group
        integer :: i, n

        allocate(tokens(0))  ! silences gfortran -Wmaybe-uninitialized
        call tokenize(path, lines, tokens, n, error)
        if (allocated(error)) return
        allocate(groups(0))
        i = 1
        do while (i <= n)
            if (tokens(i)%kind /= token_group) then
                call input_error(error, path, tokens(i)%line, "", "'" // tokens(i)%text &
                    & // "' is outside any namelist group; a group reads &name key = value /")
                return
            end if
            call check_group_name(path, tokens(i), known, groups, error)
            if (allocated(error)) return
            group%name = tokens(i)%text
            group%line = tokens(i)%line
            groups = [groups, group]
            call scan_body(path, tokens(:n), i, groups(size(groups)), error)
            if (allocated(error)) return
        end do
    end subroutine scan_groups

    !> The group must be known and not seen before.
    subroutine check_group_name(path, token, known, groups, error)
        character(len=*), intent(in) :: path
        type(token_type), intent(in) :: token
        character(len=*), intent(in) :: known(:)
        type(group_type), intent(in) :: groups(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: list
        integer :: k

        if (.not. any(known == token%text)) then
            list = "&" // trim(known(1))
            do k = 2, size(known)
                list = list // ", &" // trim(known(k))
            end do
            call input_error(error, path, token%line, "", "unknown group '&" // token%text &
                & // "'; known groups are " // list)
            return
        end if
        do k = 1, size(groups)
            if (groups(k)%name == token%text) then
                call input_error(error, path, token%line, "", "group '&" // token%text &
                    & // "' given twice (lines " // to_text(groups(k)%line) // " and " &
                    & // to_text(token%line) // "); give each group at most once")
                return
            end if
        end do
    end subroutine check_group_name

    !> Read the assignments of the group opened at tokens(i) up to its '/'; leave i after it.
    !> Its length is one token loop whose cases (name, '=', value, ',', '/') share the position
    !> and the pending name; split, they would pass all of it around.
    subroutine scan_body(path, tokens, i, group, error)
        character(len=*), intent(in) :: path
        type(token_type), intent(in) :: tokens(:)
        integer, intent(inout) :: i
        type(group_type), intent(inout) :: group
        type(error_type), allocatable, intent(out) :: error
        type(assignment_type) :: assignment
        integer :: n, count, k

        n = size(tokens)
        allocate(group%assignments(0))
        i = i + 1
        do
            if (i > n) then
                if (size(group%assignments) > 0) then
                    ! the file ends in the last value: name its key
                    associate (last => group%assignments(size(group%assignments)))
                        call input_error(error, path, last%line, last%key, "= '" &
                            & // last%value // "': the file ends here, inside group '&" &
                            & // group%name // "' (line " // to_text(group%line) &
                            & // "), which is not closed with '/'")
                    end associate
                else
                    call input_error(error, path, group%line, "", "group '&" // group%name &
                        & // "' is not closed with '/'")
                end if
                return
            end if
            select case (tokens(i)%kind)
            case (token_end)
                i = i + 1
                return
            case (token_comma)
                i = i + 1
                cycle
            case (token_group)
                call input_error(error, path, tokens(i)%line, "", "group '&" // tokens(i)%text &
                    & // "' begins before '&" // group%name // "' (line " &
                    & // to_text(group%line) // ") is closed with '/'")
                return
            end select
            if (.not. is_key(tokens, i)) then
                call input_error(error, path, tokens(i)%line, "", "expected key = value in '&" &
                    & // group%name // "', got '" // tokens(i)%text // "'")
                return
            end if
            assignment%key = to_lower(tokens(i)%text)
            assignment%value = ""
            assignment%quoted = .false.
            assignment%line = tokens(i)%line
            i = i + 2
            count = 0
            do while (i <= n)
                if (is_key(tokens, i)) exit
                if (tokens(i)%kind == token_word .or. tokens(i)%kind == token_string) then
                    count = count + 1
                    if (count == 1) then
                        assignment%value = tokens(i)%text
                        assignment%quoted = tokens(i)%kind == token_string
                    else
                        assignment%value = assignment%value // " " // tokens(i)%text
                    end if
                else if (tokens(i)%kind /= token_comma) then
                    exit
                end if
                i = i + 1
            end do
            if (count == 0) then
                call input_error(error, path, assignment%line, assignment%key, "has no value")
                return
            else if (count > 1) then
                call input_error(error, path, assignment%line, assignment%key, &
                    & "takes one value, got " // to_text(count) // ": " // assignment%value)
                return
            end if
            do k = 1, size(group%assignments)
                if (group%assignments(k)%key == assignment%key) then
                    call input_error(error, path, assignment%line, assignment%key, &
                        & "given twice in '&" // group%name // "' (lines " &
                        & // to_text(group%assignments(k)%line) // " and " &
                        & // to_text(assignment%line) // ")")
                    return
                end if
            end do
            group%assignments = [group%assignments, assignment]
        end do
    end subroutine scan_body

    !> A word followed by '=' starts an assignment.
    pure logical function is_key(tokens, i)
        type(token_type), intent(in) :: tokens(:)
        integer, intent(in) :: i

        is_key = .false.
        if (i + 1 > size(tokens)) return
        is_key = tokens(i)%kind == token_word .and. tokens(i + 1)%kind == token_equals
    end function is_key

    !> Split the lines into tokens; '!' starts a comment outside strings.
    subroutine tokenize(path, lines, tokens, n, error)
        character(len=*), intent(in) :: path
        type(line_type), intent(in) :: lines(:)
        type(token_type), allocatable, intent(out) :: tokens(:)
        integer, intent(out) :: n
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name
        integer :: i, j, k, last
        character :: c

        allocate(tokens(64))
        n = 0
        do i = 1, size(lines)
            associate (line => lines(i)%text)
                last = len(line)
                j = 1
                do while (j <= last)
                    c = line(j:j)
                    if (scan(c, blanks) > 0) then
                        j = j + 1
                        cycle
                    end if
                    select case (c)
                    case ("!")
                        exit
                    case (",")
                        call push(tokens, n, token_type(token_comma, c, i))
                        k = j
                    case ("=")
                        call push(tokens, n, token_type(token_equals, c, i))
                        k = j
                    case ("/")
                        call push(tokens, n, token_type(token_end, c, i))
                        k = j
                    case ("'", '"')
                        k = closing_quote(line, j)
                        if (k == 0) then
                            ! name the key the string was to be the value of (key = 'open...)
                            if (n >= 2) then
                                if (tokens(n)%kind == token_equals .and. tokens(n - 1)%kind &
                                    & == token_word) then
                                    call input_error(error, path, i, tokens(n - 1)%text, &
                                        & "= " // line(j:) // ": the string is not closed on " &
                                        & // "its line")
                                    return
                                end if
                            end if
                            call input_error(error, path, i, "", "string " // line(j:) &
                                & // " is not closed on its line")
                            return
                        end if
                        call push(tokens, n, token_type(token_string, line(j:k), i))
                    case ("&")
                        k = j
                        do while (k < last)
                            if (scan(line(k + 1:k + 1), delimiters) > 0) exit
                            k = k + 1
                        end do
                        if (k == j) then
                            call input_error(error, path, i, "", "'&' must be followed by a " &
                                & // "group name, as in &disk")
                            return
                        end if
                        name = to_lower(line(j + 1:k))
                        call push(tokens, n, token_type(token_group, name, i))
                    case default
                        k = j
                        do while (k < last)
                            if (scan(line(k + 1:k + 1), delimiters) > 0) exit
                            k = k + 1
                        end do
                        call push(tokens, n, token_type(token_word, line(j:k), i))
                    end select
                    j = k + 1
                end do
            end associate
        end do
    end subroutine tokenize

    !> Position of the quote closing the string opened at line(j:j), 0 when none; a doubled
    !> quote inside the string stands for one quote.
    pure integer function closing_quote(line, j) result(k)
        character(len=*), intent(in) :: line
        integer, intent(in) :: j

        k = j + 1
        do while (k <= len(line))
            if (line(k:k) == line(j:j)) then
                if (k == len(line)) return
                if (line(k + 1:k + 1) /= line(j:j)) return
                k = k + 1
            end if
            k = k + 1
        end do
        k = 0
    end function closing_quote

    !> Append a token, growing the array geometrically.
    subroutine push(tokens, n, token)
        type(token_type), allocatable, intent(inout) :: tokens(:)
        integer, intent(inout) :: n
        type(token_type), intent(in) :: token
        type(token_type), allocatable :: grown(:)

        if (n == size(tokens)) then
            allocate(grown(2*n))
            grown(:n) = tokens
            call move_alloc(grown, tokens)
        end if
        n = n + 1
        tokens(n) = token
    end subroutine push


end module rollcon_namelist_lexer
