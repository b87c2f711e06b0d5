! SPDX-License-Identifier: MIT
!> Function expressions of an ADAMS dataset (`FUNCTION = e`): compiled once to a small stack
!> program, then evaluated at any time with no allocation.
!>
!> The subset: numbers (with `D` after a number for degrees), `TIME`, `PI`, `DTOR`; `+ - * /`
!> and `**` (right-associative, binding tighter than a sign, as in Fortran); the functions
!> `SIN COS TAN ATAN2 EXP LOG SQRT ABS MIN MAX`, `STEP(x, x0, h0, x1, h1)` (cubic step),
!> `HAVSIN(x, x0, h0, x1, h1)` (haversine step) and `IF(e: neg, zero, pos)`. Names are read in
!> any case. A value outside a function's domain (LOG of a negative number, STEP with x1 <= x0)
!> evaluates to NaN: callers check the result with ieee_is_finite and name the expression.
module rollcon_adm_expression
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: expression_type, compile_expression, evaluate_expression, max_stack

    !> Deepest stack a compiled expression may need
    integer, parameter :: max_stack = 64

    ! operation codes of the stack program
    integer, parameter :: op_constant = 1, op_time = 2, op_add = 3, op_subtract = 4, &
        & op_multiply = 5, op_divide = 6, op_power = 7, op_negate = 8, op_sin = 9, op_cos = 10, &
        & op_tan = 11, op_exp = 12, op_log = 13, op_sqrt = 14, op_abs = 15, op_atan2 = 16, &
        & op_min = 17, op_max = 18, op_step = 19, op_havsin = 20, op_if = 21

    !> Function names, their operation codes and argument counts (IF is parsed apart)
    character(len=*), parameter :: function_names(12) = [character(len=6) :: "SIN", "COS", &
        & "TAN", "ATAN2", "EXP", "LOG", "SQRT", "ABS", "MIN", "MAX", "STEP", "HAVSIN"]
    integer, parameter :: function_codes(12) = [op_sin, op_cos, op_tan, op_atan2, op_exp, &
        & op_log, op_sqrt, op_abs, op_min, op_max, op_step, op_havsin]
    integer, parameter :: function_arguments(12) = [1, 1, 1, 2, 1, 1, 1, 1, 2, 2, 5, 5]

    real(wp), parameter :: pi = acos(-1.0_wp)

    !> A compiled expression
    type :: expression_type
        !> The expression as written
        character(len=:), allocatable :: text
        !> Operation codes, in order
        integer, allocatable :: op(:)
        !> The constant of each op_constant operation (0 elsewhere)
        real(wp), allocatable :: constant(:)
        !> True when the expression depends on TIME
        logical :: uses_time = .false.
    end type expression_type

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

    !> Value of the expression at `time` [s]; NaN outside a function's domain.
    pure function evaluate_expression(expression, time) result(value)
        type(expression_type), intent(in) :: expression
        real(wp), intent(in) :: time
        real(wp) :: value
        real(wp) :: stack(max_stack)
        integer :: i, top

        top = 0
        do i = 1, size(expression%op)
            select case (expression%op(i))
            case (op_constant)
                top = top + 1
                stack(top) = expression%constant(i)
            case (op_time)
                top = top + 1
                stack(top) = time
            case (op_negate)
                stack(top) = -stack(top)
            case (op_sin:op_abs)
                stack(top) = unary(expression%op(i), stack(top))
            case (op_add:op_power, op_atan2:op_max)
                top = top - 1
                stack(top) = binary(expression%op(i), stack(top), stack(top + 1))
            case (op_step, op_havsin)
                top = top - 4
                stack(top) = smooth_step(expression%op(i) == op_havsin, stack(top:top + 4))
            case (op_if)
                top = top - 3
                if (stack(top) < 0.0_wp) then
                    stack(top) = stack(top + 1)
                else if (stack(top) > 0.0_wp) then
                    stack(top) = stack(top + 3)
                else
                    stack(top) = stack(top + 2)
                end if
            end select
        end do
        value = stack(1)
    end function evaluate_expression

    pure function unary(op, x) result(y)
        integer, intent(in) :: op
        real(wp), intent(in) :: x
        real(wp) :: y

        select case (op)
        case (op_sin)
            y = sin(x)
        case (op_cos)
            y = cos(x)
        case (op_tan)
            y = tan(x)
        case (op_exp)
            y = exp(x)
        case (op_log)
            y = nan()
            if (x > 0.0_wp) y = log(x)
        case (op_sqrt)
            y = nan()
            if (x >= 0.0_wp) y = sqrt(x)
        case default
            y = abs(x)
        end select
    end function unary

    pure function binary(op, a, b) result(y)
        integer, intent(in) :: op
        real(wp), intent(in) :: a, b
        real(wp) :: y

        select case (op)
        case (op_add)
            y = a + b
        case (op_subtract)
            y = a - b
        case (op_multiply)
            y = a*b
        case (op_divide)
            y = nan()
            if (b /= 0.0_wp) y = a/b
        case (op_power)
            ! a negative base only with a whole exponent, as Fortran's real power allows
            y = nan()
            if (a > 0.0_wp .or. (a == 0.0_wp .and. b > 0.0_wp)) then
                y = a**b
            else if (a < 0.0_wp .and. b == aint(b) .and. abs(b) < 1.0e9_wp) then
                y = a**nint(b)
            end if
        case (op_atan2)
            y = atan2(a, b)
        case (op_min)
            y = min(a, b)
        case default
            y = max(a, b)
        end select
    end function binary

    !> ADAMS's STEP (cubic, C1) or HAVSIN (haversine) from h0 at x0 to h1 at x1; NaN unless
    !> x0 < x1. Arguments: x, x0, h0, x1, h1.
    pure function smooth_step(haversine, arguments) result(y)
        logical, intent(in) :: haversine
        real(wp), intent(in) :: arguments(5)
        real(wp) :: y
        real(wp) :: s

        associate (x => arguments(1), x0 => arguments(2), h0 => arguments(3), &
            & x1 => arguments(4), h1 => arguments(5))
            if (.not. x0 < x1) then
                y = nan()
            else if (x <= x0) then
                y = h0
            else if (x >= x1) then
                y = h1
            else
                s = (x - x0)/(x1 - x0)
                if (haversine) then
                    y = 0.5_wp*(h0 + h1) + 0.5_wp*(h1 - h0)*sin(pi*s - 0.5_wp*pi)
                else
                    y = h0 + (h1 - h0)*s**2*(3.0_wp - 2.0_wp*s)
                end if
            end if
        end associate
    end function smooth_step

    pure function nan()
        real(wp) :: nan

        nan = ieee_value(nan, ieee_quiet_nan)
    end function nan

    ! ---- parser: sum := product {(+|-) product}; product := signed {(*|/) signed};
    ! signed := (+|-) signed | power; power := primary [** signed]

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

        k = findloc(function_names, name, dim=1)
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

end module rollcon_adm_expression
