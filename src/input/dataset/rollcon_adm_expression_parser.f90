! SPDX-License-Identifier: MIT
!> Compiles a dataset function expression into the stack program of rollcon_expression, by
!> recursive descent: sum := product {(+|-) product}; product := signed {(*|/) signed};
!> signed := (+|-) signed | power; power := primary [** signed]. A syntax error names where the
!> expression was read and the column. A measure takes its marker ids as whole numbers,
!> DX(i[, j[, k]]) (0 for j, k or l: the ground origin and axes), an element function its id
!> and three whole numbers, JOINT(id, jflag, comp, rm). Whether the markers and elements exist,
!> and whether the place the expression is used can compute what it reads, is judged where the
!> dataset is assembled (rollcon_adm_build).
module rollcon_adm_expression_parser
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi, degree
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_expression, only : expression_type, expression_input_type, max_stack, &
        & max_inputs, op_time, op_input, op_add, op_subtract, op_multiply, op_divide, op_power, &
        & op_negate, op_if, function_names, function_codes, function_arguments, quantity_names, &
        & quantity_least_markers, quantity_most_markers, quantity_kind, kind_element_force, &
        & max_arguments, op_akispl, op_cubspl, spline_reference, quantity_vm, quantity_vr, &
        & quantity_accm, quantity_wdtm, quantity_orient, quantity_ax, quantity_yaw, &
        & orient_systems, orient_components
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
        allocate(expression%anchors(size(expression%inputs)), source=0.0_wp)
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
            case ("RTOD")
                call emit_constant(p, 180.0_wp/pi)
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
        integer :: k, i, least, most, count

        k = 0
        do i = 1, size(function_names)
            if (trim(function_names(i)) == name) k = i
        end do
        if (k == 0) then
            do i = 1, size(quantity_names)
                if (trim(quantity_names(i)) == name) k = i
            end do
            ! ADAMS's own short names of two element functions
            if (name == "BUSH") k = findloc(quantity_names, "BUSHING", dim=1)
            if (name == "VTORQ") k = findloc(quantity_names, "VTORQUE", dim=1)
            if (k == quantity_orient) then
                call parse_orient(p, name, problem)
                return
            end if
            if (k > 0) then
                call parse_measure(p, name, k, problem)
                return
            end if
            p%at = p%at - len(name)
            if (name == "USER") then
                ! FUNCTION=USER(...) where no user routine serves the statement (SFORCE,
                ! VFORCE, GFORCE and UCON read theirs before any expression)
                problem = "USER(...): user routines of this kind (this statement's user " &
                    & // "subroutine: COUSUB of a COUPLER, ...) are not supported; rollcon " &
                    & // "runs the user routines of UCON (UCOSUB), SFORCE (SFOSUB), VFORCE " &
                    & // "(VFOSUB), GFORCE (GFOSUB), VTORQUE (VTOSUB), VARIABLE (VARSUB), " &
                    & // "MOTION (MOTSUB), REQUEST (REQSUB) and DIFF (DIFSUB) " &
                    & // "(docs/datasets.md, User force " &
                    & // "routines); write this FUNCTION as an expression"
                return
            end if
            problem = "unknown name '" // name // "': not a function, measure or constant " &
                & // "rollcon reads (docs/datasets.md, Function expressions, lists them)"
            return
        end if
        if (function_codes(k) == op_akispl .or. function_codes(k) == op_cubspl) then
            call parse_spline(p, name, function_codes(k), problem)
            return
        end if
        least = function_arguments(k)
        most = least
        if (least < 0) then
            least = -least
            most = max_arguments
        end if
        call expect(p, "(", problem)
        count = 0
        do while (len(problem) == 0)
            if (count > 0) then
                if (count >= least .and. peek(p) == ")") exit
                call expect(p, ",", problem)
                if (len(problem) > 0) exit
            end if
            if (count == most) then
                problem = "too many arguments"
                exit
            end if
            call parse_sum(p, problem)
            count = count + 1
            if (count == least .and. least == most) exit
        end do
        if (len(problem) == 0) call expect(p, ")", problem)
        if (len(problem) > 0) then
            if (least == most) then
                problem = problem // " (" // name // " takes " // to_text(least) &
                    & // " argument" // trim(merge("s", " ", least > 1)) // ")"
            else
                problem = problem // " (" // name // " takes " // to_text(least) // " to " &
                    & // to_text(most) // " arguments)"
            end if
            return
        end if
        call emit(p, function_codes(k), 1 - count)
        ! a variadic function keeps its count in the constant slot
        if (least /= most) p%constant(p%count) = real(count, wp)
    end subroutine parse_call

    !> AKISPL(x, z, id[, iord]) or CUBSPL(...): x and z expressions, id the SPLINE's id and
    !> iord the order of the derivative in x (0, 1 or 2), both whole numbers.
    recursive subroutine parse_spline(p, name, op, problem)
        type(parser_type), intent(inout) :: p
        character(len=*), intent(in) :: name
        integer, intent(in) :: op
        character(len=:), allocatable, intent(inout) :: problem
        integer :: id, order

        call expect(p, "(", problem)
        if (len(problem) == 0) call parse_sum(p, problem)
        if (len(problem) == 0) call expect(p, ",", problem)
        if (len(problem) == 0) call parse_sum(p, problem)
        if (len(problem) == 0) call expect(p, ",", problem)
        if (len(problem) == 0) call read_whole(p, name // "'s id", 1, huge(1)/4, id, problem)
        order = 0
        if (len(problem) == 0 .and. peek(p) == ",") then
            p%at = p%at + 1
            call read_whole(p, name // "'s iord", 0, 2, order, problem)
        end if
        if (len(problem) == 0) call expect(p, ")", problem)
        if (len(problem) > 0) then
            problem = problem // " (" // name // " is written " // name // "(x, z, id[, iord]): " &
                & // "x and z expressions, id a SPLINE id, iord 0, 1 or 2)"
            return
        end if
        call emit(p, op, -1)
        p%constant(p%count) = spline_reference(id, order)
    end subroutine parse_spline

    !> A whole number from least to most at the parser's place, named `what` in a refusal.
    subroutine read_whole(p, what, least, most, value, problem)
        type(parser_type), intent(inout) :: p
        character(len=*), intent(in) :: what
        integer, intent(in) :: least, most
        integer, intent(out) :: value
        character(len=:), allocatable, intent(inout) :: problem
        integer :: first, stat

        call skip_blanks(p)
        first = p%at
        call skip_digits(p)
        value = -1
        stat = 1
        if (p%at > first .and. p%at - first <= 9) read(p%text(first:p%at - 1), *, iostat=stat) &
            & value
        if (stat /= 0 .or. value < least .or. value > most) then
            p%at = first
            problem = what // " must be a whole number from " // to_text(least) // " to " &
                & // to_text(most)
        end if
    end subroutine read_whole

    !> NAME(i[, j[, k[, l]]]): a measure of markers (or, for an element function, its id,
    !> jflag, comp and rm; for VARVAL, DIF and DIF1 an id); an input of the expression (one per
    !> distinct measure).
    subroutine parse_measure(p, name, quantity, problem)
        type(parser_type), intent(inout) :: p
        character(len=*), intent(in) :: name
        integer, intent(in) :: quantity
        character(len=:), allocatable, intent(inout) :: problem
        integer :: ids(4), count, least, most
        character(len=:), allocatable :: form
        type(expression_input_type) :: input

        least = quantity_least_markers(quantity)
        most = quantity_most_markers(quantity)
        form = measure_form(name, quantity)
        call expect(p, "(", problem)
        if (len(problem) > 0) then
            problem = problem // " (" // name // " is written " // form // ")"
            return
        end if
        ids = 0
        count = 0
        do
            if (count == most) exit
            if (count > 0) then
                if (peek(p) /= ",") exit
                p%at = p%at + 1
            end if
            count = count + 1
            call read_whole(p, "x", merge(1, 0, count == 1 .or. (quantity_kind(quantity) &
                & == kind_element_force .and. count == 3)), huge(1), ids(count), problem)
            if (len(problem) > 0) then
                problem = name // "'s " // argument_name(quantity, count) // " must be " &
                    & // argument_meaning(quantity, count) // " (" // name // " is written " &
                    & // form // ")"
                return
            end if
        end do
        if (count < least) then
            problem = name // " takes " // to_text(least) // " whole numbers, " // form
            return
        end if
        if (peek(p) == ",") then
            problem = name // " takes at most " // to_text(most) // " marker id" &
                & // trim(merge("s", " ", most > 1)) // ", " // form
            return
        end if
        call expect(p, ")", problem)
        if (len(problem) > 0) then
            problem = problem // " (" // name // " is written " // form // ")"
            return
        end if
        if (quantity_kind(quantity) == kind_element_force .and. ids(2) > 1) then
            problem = name // "'s jflag must be " // argument_meaning(quantity, 2)
            return
        end if
        if (quantity_kind(quantity) == kind_element_force .and. ids(3) > 8) then
            problem = name // "'s comp must be " // argument_meaning(quantity, 3)
            return
        end if
        input = expression_input_type(marker=ids(1), quantity=quantity, j=ids(2), k=ids(3), &
            & l=ids(4))
        if (frame_third(quantity)) then
            ! VM, VR, ACCM, WDTM (i, j, l): the third is the frame of the time derivative
            input%l = ids(3)
            input%k = 0
        end if
        call add_input(p, input, problem)
    end subroutine parse_measure

    !> ORIENT(system, component, i[, j]): ADAMS's orientation of marker i's axes in j's (0 or
    !> not given: the ground's) in another convention (docs/datasets.md, "ORIENT"); system a
    !> whole number from 1 to orient_systems, component from 1 to its count
    !> (orient_components). Systems 25 and 26 are AX, AY, AZ and YAW, PITCH, ROLL of (i, j),
    !> read as those measures.
    subroutine parse_orient(p, name, problem)
        type(parser_type), intent(inout) :: p
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(inout) :: problem
        integer :: system, component, i, j
        type(expression_input_type) :: input

        system = 1
        j = 0
        call expect(p, "(", problem)
        if (len(problem) == 0) call read_whole(p, name // "'s system", 1, orient_systems, &
            & system, problem)
        if (len(problem) == 0) call expect(p, ",", problem)
        if (len(problem) == 0) call read_whole(p, name // "'s component", 1, &
            & orient_components(system), component, problem)
        if (len(problem) == 0) call expect(p, ",", problem)
        if (len(problem) == 0) call read_whole(p, name // "'s i", 1, huge(1), i, problem)
        if (len(problem) == 0 .and. peek(p) == ",") then
            p%at = p%at + 1
            call read_whole(p, name // "'s j", 0, huge(1), j, problem)
        end if
        if (len(problem) == 0) call expect(p, ")", problem)
        if (len(problem) > 0) then
            problem = problem // " (" // name // " is written " // name // "(system, " &
                & // "component, i[, j]): system 1 to " // to_text(orient_systems) // ", i and " &
                & // "j marker ids, j 0 or left out for the ground's axes)"
            return
        end if
        select case (system)
        case (25)
            input = expression_input_type(marker=i, quantity=quantity_ax + component - 1, j=j)
        case (26)
            input = expression_input_type(marker=i, quantity=quantity_yaw + component - 1, j=j)
        case default
            input = expression_input_type(marker=i, quantity=quantity_orient, j=j, &
                & system=system, component=component)
        end select
        call add_input(p, input, problem)
    end subroutine parse_orient

    !> An input of the expression at the parser's place (one per distinct measure).
    subroutine add_input(p, input, problem)
        type(parser_type), intent(inout) :: p
        type(expression_input_type), intent(in) :: input
        character(len=:), allocatable, intent(inout) :: problem
        integer :: k, slot

        slot = 0
        do k = 1, size(p%inputs)
            if (same_input(p%inputs(k), input)) slot = k
        end do
        if (slot == 0) then
            if (size(p%inputs) == max_inputs) then
                problem = "more than " // to_text(max_inputs) // " different measures in one " &
                    & // "expression"
                return
            end if
            p%inputs = [p%inputs, input]
            slot = size(p%inputs)
        end if
        ! the input's number rides in the constant slot of its operation
        call emit_constant(p, real(slot, wp))
        p%op(p%count) = op_input
    end subroutine add_input

    !> How a measure is written, for messages: "DX(i[, j[, k]])".
    pure function measure_form(name, quantity) result(form)
        character(len=*), intent(in) :: name
        integer, intent(in) :: quantity
        character(len=:), allocatable :: form
        integer :: k

        if (quantity_kind(quantity) == kind_element_force) then
            form = name // "(id, jflag, comp, rm)"
            return
        end if
        form = name // "(" // argument_name(quantity, 1)
        do k = 2, quantity_most_markers(quantity)
            form = form // "[, " // argument_name(quantity, k)
        end do
        form = form // repeat("]", quantity_most_markers(quantity) - 1) // ")"
    end function measure_form

    !> The name of a measure's argument k: i, j, k, l (for DX to WDTM: the velocity's frame is
    !> l, the fourth; VM, VR, ACCM and WDTM take i, j, l), or id, jflag, comp, rm.
    pure function argument_name(quantity, k) result(name)
        integer, intent(in) :: quantity, k
        character(len=:), allocatable :: name
        character(len=5), parameter :: markers(4) = ["i    ", "j    ", "k    ", "l    "]
        character(len=5), parameter :: element(4) = ["id   ", "jflag", "comp ", "rm   "]

        if (quantity_kind(quantity) == kind_element_force) then
            name = trim(element(k))
        else if (quantity_most_markers(quantity) == 1) then
            name = "id"
        else if (k == 3 .and. frame_third(quantity)) then
            name = "l"
        else
            name = trim(markers(k))
        end if
    end function argument_name

    !> What a measure's argument k must be, for messages.
    pure function argument_meaning(quantity, k) result(text)
        integer, intent(in) :: quantity, k
        character(len=:), allocatable :: text

        if (quantity_kind(quantity) == kind_element_force) then
            select case (k)
            case (1)
                text = "the element's id (a whole number > 0)"
            case (2)
                text = "0 (the force on the I marker) or 1 (on J)"
            case (3)
                text = "a component from 1 to 8 (FM, FX, FY, FZ, TM, TX, TY, TZ)"
            case default
                text = "a marker id (0: ground axes)"
            end select
        else if (quantity_most_markers(quantity) == 1) then
            text = "an id (a whole number > 0)"
        else if (k == 1) then
            text = "a marker id (a whole number > 0)"
        else
            text = "a marker id (a whole number; 0: the ground's origin and axes)"
        end if
    end function argument_meaning

    !> VM, VR, ACCM and WDTM take (i, j, l): their third marker is the frame of the derivative.
    pure logical function frame_third(quantity)
        integer, intent(in) :: quantity

        frame_third = any(quantity == [quantity_vm, quantity_vr, quantity_accm, quantity_wdtm])
    end function frame_third

    pure logical function same_input(a, b)
        type(expression_input_type), intent(in) :: a, b

        same_input = a%marker == b%marker .and. a%quantity == b%quantity .and. a%j == b%j &
            & .and. a%k == b%k .and. a%l == b%l .and. a%system == b%system &
            & .and. a%component == b%component
    end function same_input

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
