! SPDX-License-Identifier: MIT
!> Compiles a dataset function expression into the stack program of rollcon_expression, by
!> recursive descent: sum := product {(+|-) product}; product := signed {(*|/) signed};
!> signed := (+|-) signed | power; power := primary [** signed]. A syntax error names where the
!> expression was read and the column. A state function takes one marker id, DX(i); the forms
!> with J (measured from another marker) or K (in another marker's axes) are refused. Whether
!> the marker exists is checked where the dataset's markers are known (rollcon_adm_build).
module rollcon_adm_expression_parser
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi, degree
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_expression, only : expression_type, expression_input_type, max_stack, &
        & max_inputs, op_time, op_input, op_add, op_subtract, op_multiply, op_divide, op_power, &
        & op_negate, op_if, function_names, function_codes, function_arguments, quantity_names
    use rollcon_adm_expression_scan, only : parser_type, emit, emit_constant, expect, peek, &
        & here, skip_blanks, skip_digits, read_name, is_digit, is_letter, column_text, &
        & exponent_follows
    use rollcon_namelist_bytes, only : visible
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_text, only : to_text
    implicit none
    private

    public :: compile_expression, max_nesting

    !> Deepest nesting of parentheses, function arguments, signs and powers an expression may
    !> have: far beyond any written one, and a bound on the parser's recursion, which a text of
    !> a million parentheses would otherwise drive through the stack
    integer, parameter :: max_nesting = 200
    !> Longest text a message quotes in full [characters]
    integer, parameter :: max_quoted = 400

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
        allocate(parser%op(max(8, len(text))), parser%constant(max(8, len(text))), &
            & parser%inputs(0))
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
            call fatal_error(error, where // ": " // visible(shortened(problem)) &
                & // " at column " // column_text(parser) // " of '" &
                & // visible(shortened(trim(adjustl(text)))) // "'", stat_input)
            return
        end if
        expression%text = trim(adjustl(text))
        expression%op = parser%op(:parser%count)
        expression%constant = parser%constant(:parser%count)
        expression%inputs = parser%inputs
        expression%uses_time = any(expression%op == op_time)
    end subroutine compile_expression

    !> A text as a message quotes it: its first max_quoted characters and its length when it
    !> is longer (an expression may run over thousands of continuation lines).
    pure function shortened(text) result(quoted)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: quoted

        quoted = text
        if (len(text) > max_quoted) quoted = text(:max_quoted) // "... (" &
            & // to_text(len(text)) // " characters)"
    end function shortened

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

    !> Every level of nesting (a parenthesis, a function's argument, a sign, a power) passes
    !> here once: the depth of the recursion is bounded by max_nesting, not by the text's length.
    recursive subroutine parse_signed(p, problem)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable, intent(inout) :: problem
        character :: c

        if (p%nesting >= max_nesting) then
            problem = "nested too deeply (more than " // to_text(max_nesting) // " levels of " &
                & // "parentheses, signs and powers)"
            return
        end if
        p%nesting = p%nesting + 1
        c = peek(p)
        if (c == "+" .or. c == "-") then
            p%at = p%at + 1
            call parse_signed(p, problem)
            if (c == "-") call emit(p, op_negate, 0)
        else
            call parse_primary(p, problem)
            if (len(problem) == 0 .and. peek(p) == "*" .and. p%at < len(p%text)) then
                if (p%text(p%at + 1:p%at + 1) == "*") then
                    p%at = p%at + 2
                    call parse_signed(p, problem)
                    call emit(p, op_power, -1)
                end if
            end if
        end if
        p%nesting = p%nesting - 1
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
            do i = 1, size(quantity_names)
                if (trim(quantity_names(i)) == name) k = i
            end do
            if (k > 0) then
                call parse_state_function(p, name, k, problem)
                return
            end if
            p%at = p%at - len(name)
            problem = "unknown name '" // name // "' (the subset has TIME, PI, DTOR, SIN, " &
                & // "COS, TAN, ATAN2, EXP, LOG, SQRT, ABS, MIN, MAX, STEP, STEP5, HAVSIN, IF " &
                & // "and the state functions DX DY DZ VX VY VZ WX WY WZ PSI THETA PHI of one " &
                & // "marker)"
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

    !> NAME(i): the quantity of marker i, measured from ground in ground axes; an input of
    !> the expression (one per distinct marker and quantity).
    subroutine parse_state_function(p, name, quantity, problem)
        type(parser_type), intent(inout) :: p
        character(len=*), intent(in) :: name
        integer, intent(in) :: quantity
        character(len=:), allocatable, intent(inout) :: problem
        integer :: first, id, stat, k, slot

        call expect(p, "(", problem)
        if (len(problem) > 0) then
            problem = problem // " (" // name // " is written " // name // "(i), i a marker id)"
            return
        end if
        call skip_blanks(p)
        first = p%at
        call skip_digits(p)
        id = 0
        stat = 1
        if (p%at > first) read(p%text(first:p%at - 1), *, iostat=stat) id
        if (stat /= 0 .or. id <= 0) then
            p%at = first
            problem = name // "(i) takes a marker id (a whole number > 0)"
            return
        end if
        if (peek(p) == ",") then
            problem = name // "(i, ...): only the one-marker form " // name // "(i) is " &
                & // "supported, measured from ground in ground axes (a J or K marker, from or " &
                & // "in another marker, is not)"
            return
        end if
        call expect(p, ")", problem)
        if (len(problem) > 0) return
        slot = 0
        do k = 1, size(p%inputs)
            if (p%inputs(k)%marker == id .and. p%inputs(k)%quantity == quantity) slot = k
        end do
        if (slot == 0) then
            if (size(p%inputs) == max_inputs) then
                problem = "more than 32 different state functions in one expression"
                return
            end if
            p%inputs = [p%inputs, expression_input_type(marker=id, quantity=quantity)]
            slot = size(p%inputs)
        end if
        ! the input's number rides in the constant slot of its operation
        call emit_constant(p, real(slot, wp))
        p%op(p%count) = op_input
    end subroutine parse_state_function

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
        if (.not. ieee_is_finite(value)) then
            ! beyond the largest double (1.8e308): read as infinity, never a constant
            problem = "'" // p%text(first:p%at - 1) // "' is not a finite number"
            p%at = first
            return
        end if
        if (degrees) then
            p%at = p%at + 1
            value = value*degree
        end if
        call emit_constant(p, value)
    end subroutine parse_number

end module rollcon_adm_expression_parser
