! SPDX-License-Identifier: MIT
!> Compiles a dataset function expression into the stack program of rollcon_expression, by
!> recursive descent: sum := product {(+|-) product}; product := signed {(*|/) signed};
!> signed := (+|-) signed | power; power := primary [** signed]. A syntax error names where the
!> expression was read and the column.
module rollcon_adm_expression_parser
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_expression, only : expression_type, max_stack, op_constant, op_time, op_add, &
        & op_subtract, op_multiply, op_divide, op_power, op_negate, op_if, function_names, &
        & function_codes, function_arguments
    implicit none
    private

    public :: compile_expression


    !> Parser state: the text and where reading stands
    type :: parser_type
        character(len=:), allocatable :: text
        integer :: at = 1
        integer, allocatable :: op(:)
        real(wp), allocatable :: constant(:)
        integer :: count = 0, depth = 0, deepest = 0
    end type parser_type

contains

    !> Compile `text`; a syntax error names `where` (file:line: key) and the column.
    subroutine compile_expression(text, where, expression, error)
        !> The expression
        character(len=*), intent(in) :: text
        !> Where it was read, for messages (e.g. "coin.adm:12: SFORCE/1 FUNCTION")
        character(len=*), intent(in) :: where
        type(expression_type), intent(out) :: expression
        type(error_type), allocatable, intent(out) :: error
        type(parser_type) :: parser
        character(len=:), allocatable :: problem

        parser%text = text
        allocate(parser%op(max(8, len(text))), parser%constant(max(8, len(text))))
        problem = ""
        call parse_sum(parser, problem)
        if (len(problem) == 0) then
            call skip_blanks(parser)
            if (parser%at <= len(parser%text)) problem = "unexpected '" &
                & // parser%text(parser%at:parser%at) // "'"
        end if
        if (len(problem) == 0 .and. parser%deepest > max_stack) problem = "nested too deeply " &
            & // "(more than 64 values pending)"
        if (len(problem) > 0) then
            call fatal_error(error, where // ": " // problem // " at column " &
                & // column_text(parser) // " of '" // trim(adjustl(text)) // "'", stat_input)
            return
        end if
        expression%text = trim(adjustl(text))
        expression%op = parser%op(:parser%count)
        expression%constant = parser%constant(:parser%count)
        expression%uses_time = any(expression%op == op_time)
    end subroutine compile_expression

    recursive subroutine parse_sum(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        character :: c

        call parse_product(p, problem)
        do while (len(problem) == 0)
            c = peek(p)
            if (c /= "+" .and. c /= "-") exit
            p%at = p%at + 1
            call parse_product(p, problem)
            if (c == "+") then
                call emit(p, op_add, -1)
            else
                call emit(p, op_subtract, -1)
            end if
        end do
    end subroutine parse_sum

    recursive subroutine parse_product(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        character :: c

        call parse_signed(p, problem)
        do while (len(problem) == 0)
            c = peek(p)
            if (c == "*" .and. p%text(min(p%at + 1, len(p%text)):min(p%at + 1, len(p%text))) &
                & == "*") exit
            if (c /= "*" .and. c /= "/") exit
            p%at = p%at + 1
            call parse_signed(p, problem)
            if (c == "*") then
                call emit(p, op_multiply, -1)
            else
                call emit(p, op_divide, -1)
            end if
        end do
    end subroutine parse_product

    recursive subroutine parse_signed(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        character :: c

        c = peek(p)
        if (c == "+" .or. c == "-") then
            p%at = p%at + 1
            call parse_signed(p, problem)
            if (c == "-") call emit(p, op_negate, 0)
            return
        end if
        call parse_primary(p, problem)
        if (len(problem) > 0) return
        if (peek(p) == "*" .and. p%at < len(p%text)) then
            if (p%text(p%at + 1:p%at + 1) == "*") then
                p%at = p%at + 2
                call parse_signed(p, problem)
                call emit(p, op_power, -1)
            end if
        end if
    end subroutine parse_signed

    recursive subroutine parse_primary(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        character :: c
        character(len=:), allocatable :: name

        c = peek(p)
        if (c == "(") then
            p%at = p%at + 1
            call parse_sum(p, problem)
            if (len(problem) == 0) call expect(p, ")", problem)
        else if (is_digit(c) .or. c == ".") then
            call parse_number(p, problem)
        else if (is_letter(c)) then
            name = read_name(p)
            select case (name)
            case ("TIME")
                call emit(p, op_time, 1)
            case ("PI")
                call emit_constant(p, pi)
            case ("DTOR")
                call emit_constant(p, pi/180.0_wp)
            case ("IF")
                call parse_if(p, problem)
            case default
                call parse_call(p, name, problem)
            end select
        else if (c == " ") then
            problem = "an operand is missing"
        else
            problem = "unexpected '" // c // "'"
        end if
    end subroutine parse_primary

    recursive subroutine parse_call(p, name, problem)
        type(parser_type), intent(inout) :: p
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(inout) :: problem
        integer :: k, i

        k = 0
        do i = 1, size(function_names)
            if (trim(function_names(i)) == name) k = i
        end do
        if (k == 0) then
            p%at = p%at - len(name)
            problem = "unknown name '" // name // "' (the subset has TIME, PI, DTOR, SIN, " &
                & // "COS, TAN, ATAN2, EXP, LOG, SQRT, ABS, MIN, MAX, STEP, HAVSIN, IF)"
            return
        end if
        call expect(p, "(", problem)
        do i = 1, function_arguments(k)
            if (len(problem) > 0) return
            if (i > 1) call expect(p, ",", problem)
            if (len(problem) > 0) return
            call parse_sum(p, problem)
        end do
        if (len(problem) == 0) call expect(p, ")", problem)
        if (len(problem) > 0) then
            problem = problem // " (" // name // " takes " &
                & // achar(48 + function_arguments(k)) // " argument" &
                & // merge("s", " ", function_arguments(k) > 1) // ")"
            problem = trim(problem)
            return
        end if
        call emit(p, function_codes(k), 1 - function_arguments(k))
    end subroutine parse_call

    recursive subroutine parse_if(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        character(len=1), parameter :: separators(4) = ["(", ":", ",", ","]
        integer :: i

        do i = 1, 4
            call expect(p, separators(i), problem)
            if (len(problem) > 0) exit
            call parse_sum(p, problem)
            if (len(problem) > 0) exit
        end do
        if (len(problem) == 0) call expect(p, ")", problem)
        if (len(problem) > 0) then
            problem = problem // " (IF is written IF(e: negative, zero, positive))"
            return
        end if
        call emit(p, op_if, -3)
    end subroutine parse_if

    subroutine parse_number(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        integer :: first, stat
        real(wp) :: value
        logical :: degrees

        first = p%at
        call skip_digits(p)
        if (here(p) == ".") then
            p%at = p%at + 1
            call skip_digits(p)
        end if
        degrees = .false.
        if (here(p) == "E" .or. here(p) == "e" .or. here(p) == "D" .or. here(p) == "d") then
            if (exponent_follows(p)) then
                p%at = p%at + 1
                if (here(p) == "+" .or. here(p) == "-") p%at = p%at + 1
                call skip_digits(p)
            else if (here(p) == "D" .or. here(p) == "d") then
                degrees = .true.
            end if
        end if
        read(p%text(first:p%at - 1), *, iostat=stat) value
        if (stat /= 0) then
            problem = "'" // p%text(first:p%at - 1) // "' is not a number"
            p%at = first
            return
        end if
        if (degrees) then
            p%at = p%at + 1
            value = value*pi/180.0_wp
        end if
        call emit_constant(p, value)
    end subroutine parse_number

    !> After E or D: digits, or a sign and digits, make an exponent.
    pure logical function exponent_follows(p)
        type(parser_type), intent(in) :: p
        integer :: k

        k = p%at + 1
        if (k <= len(p%text)) then
            if (p%text(k:k) == "+" .or. p%text(k:k) == "-") k = k + 1
        end if
        exponent_follows = .false.
        if (k <= len(p%text)) exponent_follows = is_digit(p%text(k:k))
    end function exponent_follows

    subroutine emit_constant(p, value)
        type(parser_type), intent(inout) :: p
        real(wp), intent(in) :: value

        call emit(p, op_constant, 1)
        p%constant(p%count) = value
    end subroutine emit_constant

    !> Append an operation that changes the stack depth by `change`.
    subroutine emit(p, op, change)
        type(parser_type), intent(inout) :: p
        integer, intent(in) :: op, change

        if (p%count == size(p%op)) then
            p%op = [p%op, p%op]
            p%constant = [p%constant, p%constant]
        end if
        p%count = p%count + 1
        p%op(p%count) = op
        p%constant(p%count) = 0.0_wp
        p%depth = p%depth + change
        p%deepest = max(p%deepest, p%depth)
    end subroutine emit

    subroutine expect(p, c, problem)
        type(parser_type), intent(inout) :: p
        character, intent(in) :: c
        character(len=:), allocatable, intent(inout) :: problem

        if (peek(p) == c) then
            p%at = p%at + 1
        else if (p%at > len(p%text)) then
            problem = "'" // c // "' expected at the end"
        else
            problem = "'" // c // "' expected, found '" // p%text(p%at:p%at) // "'"
        end if
    end subroutine expect

    !> The next non-blank character (a blank at the end of the text).
    character function peek(p)
        type(parser_type), intent(inout) :: p

        call skip_blanks(p)
        peek = here(p)
    end function peek

    pure character function here(p)
        type(parser_type), intent(in) :: p

        here = " "
        if (p%at <= len(p%text)) here = p%text(p%at:p%at)
    end function here

    subroutine skip_blanks(p)
        type(parser_type), intent(inout) :: p

        do while (p%at <= len(p%text))
            if (p%text(p%at:p%at) /= " " .and. p%text(p%at:p%at) /= achar(9)) exit
            p%at = p%at + 1
        end do
    end subroutine skip_blanks

    subroutine skip_digits(p)
        type(parser_type), intent(inout) :: p

        do while (p%at <= len(p%text))
            if (.not. is_digit(p%text(p%at:p%at))) exit
            p%at = p%at + 1
        end do
    end subroutine skip_digits

    !> A name (letters, digits, underscores), upper-cased.
    function read_name(p) result(name)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable :: name
        integer :: first, i

        first = p%at
        do while (p%at <= len(p%text))
            if (.not. (is_letter(p%text(p%at:p%at)) .or. is_digit(p%text(p%at:p%at)) &
                & .or. p%text(p%at:p%at) == "_")) exit
            p%at = p%at + 1
        end do
        name = p%text(first:p%at - 1)
        do i = 1, len(name)
            if (name(i:i) >= "a" .and. name(i:i) <= "z") name(i:i) = achar(iachar(name(i:i)) - 32)
        end do
    end function read_name

    pure logical function is_digit(c)
        character, intent(in) :: c

        is_digit = c >= "0" .and. c <= "9"
    end function is_digit

    pure logical function is_letter(c)
        character, intent(in) :: c

        is_letter = (c >= "A" .and. c <= "Z") .or. (c >= "a" .and. c <= "z")
    end function is_letter

    function column_text(p) result(text)
        type(parser_type), intent(in) :: p
        character(len=:), allocatable :: text
        character(len=12) :: buffer
        integer :: leading

        leading = len(p%text) - len(adjustl(p%text))
        write(buffer, '(i0)') max(1, min(p%at, len(p%text) + 1) - leading)
        text = trim(buffer)
    end function column_text

end module rollcon_adm_expression_parser
