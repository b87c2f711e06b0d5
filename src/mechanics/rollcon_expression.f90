! SPDX-License-Identifier: MIT
!> Function expressions of an ADAMS dataset (`FUNCTION = e`) as small stack programs, evaluated
!> at any time and state with no allocation (rollcon_adm_expression_parser compiles them).
!>
!> The subset: numbers (with `D` after a number for degrees), `TIME`, `PI`, `DTOR`; `+ - * /`
!> and `**` (right-associative, binding tighter than a sign, as in Fortran); the functions
!> `SIN COS TAN ATAN2 EXP LOG SQRT ABS MIN MAX`, `STEP(x, x0, h0, x1, h1)` (cubic step),
!> `STEP5(x, x0, h0, x1, h1)` (quintic step), `HAVSIN(x, x0, h0, x1, h1)` (haversine step)
!> and `IF(e: neg, zero, pos)`; and the state
!> functions of one marker i, measured from ground in ground axes: `DX(i) DY(i) DZ(i)`
!> (position), `VX(i) VY(i) VZ(i)` (velocity), `WX(i) WY(i) WZ(i)` (angular velocity),
!> `PSI(i) THETA(i) PHI(i)` (body 3-1-3 angles of the marker's axes). Names are read in any
!> case. A compiled expression lists its state functions as inputs (marker id, quantity); the
!> caller computes their values and passes them in that order. A value outside a function's
!> domain (LOG of a negative number, STEP with x1 <= x0) evaluates to NaN: callers check the
!> result with ieee_is_finite and name the expression.
!>
!> Where an expression switches (an IF's condition, a STEP's x at x0 and x1, MIN and MAX where
!> their arguments are equal, ABS at zero) it has a corner, which an integrator must not step
!> across (docs/design.md §7): a switch on TIME alone is found here as a time (switching_times),
!> any other is a function of the state whose zero an integrator locates (switch_values).
module rollcon_expression
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_is_finite
    implicit none
    private

    public :: expression_type, expression_input_type, evaluate_expression, switching_times
    public :: switch_kinds, switch_count, switch_values, switch_none, switch_timed, switch_watched
    public :: max_stack, max_inputs
    public :: op_constant, op_time, op_input, op_add, op_subtract, op_multiply, op_divide, &
        & op_power, op_negate, op_step, op_step5, op_havsin, op_if, op_min, op_max, op_abs
    public :: function_names, function_codes, function_arguments
    public :: quantity_names, quantity_dx, quantity_vx, quantity_wx, quantity_psi

    !> Deepest stack a compiled expression may need
    integer, parameter :: max_stack = 64
    !> Most distinct state functions one expression may use
    integer, parameter :: max_inputs = 32

    ! operation codes of the stack program
    integer, parameter :: op_constant = 1, op_time = 2, op_add = 3, op_subtract = 4, &
        & op_multiply = 5, op_divide = 6, op_power = 7, op_negate = 8, op_sin = 9, op_cos = 10, &
        & op_tan = 11, op_exp = 12, op_log = 13, op_sqrt = 14, op_abs = 15, op_atan2 = 16, &
        & op_min = 17, op_max = 18, op_step = 19, op_havsin = 20, op_if = 21, op_input = 22, &
        & op_step5 = 23

    !> Function names, their operation codes and argument counts (IF is parsed apart)
    character(len=*), parameter :: function_names(13) = [character(len=6) :: "SIN", "COS", &
        & "TAN", "ATAN2", "EXP", "LOG", "SQRT", "ABS", "MIN", "MAX", "STEP", "HAVSIN", "STEP5"]
    integer, parameter :: function_codes(13) = [op_sin, op_cos, op_tan, op_atan2, op_exp, &
        & op_log, op_sqrt, op_abs, op_min, op_max, op_step, op_havsin, op_step5]
    integer, parameter :: function_arguments(13) = [1, 1, 1, 2, 1, 1, 1, 1, 2, 2, 5, 5, 5]

    !> What an operation of a program is as a switch (switch_kinds): none; a switch on TIME
    !> alone, at times switching_times gives; a switch on anything else, whose zero an
    !> integrator locates (switch_values)
    integer, parameter :: switch_none = 0, switch_timed = 1, switch_watched = 2

    !> State functions of one marker; quantity code k is quantity_names(k). DX..DZ [length],
    !> VX..VZ [length/time], WX..WZ [rad/time], PSI, THETA, PHI [rad], in dataset units
    character(len=*), parameter :: quantity_names(12) = [character(len=5) :: "DX", "DY", "DZ", &
        & "VX", "VY", "VZ", "WX", "WY", "WZ", "PSI", "THETA", "PHI"]
    !> First code of each group of three (x, y, z or psi, theta, phi follow in order)
    integer, parameter :: quantity_dx = 1, quantity_vx = 4, quantity_wx = 7, quantity_psi = 10

    !> One state function an expression reads
    type :: expression_input_type
        !> Marker id (as in the dataset)
        integer :: marker = 0
        !> Quantity code (quantity_names)
        integer :: quantity = 0
    end type expression_input_type

    !> A compiled expression
    type :: expression_type
        !> The expression as written
        character(len=:), allocatable :: text
        !> Operation codes, in order
        integer, allocatable :: op(:)
        !> The constant of each op_constant operation; for op_input, the input's number
        !> (0 elsewhere)
        real(wp), allocatable :: constant(:)
        !> The state functions read, in the order their values are passed
        type(expression_input_type), allocatable :: inputs(:)
        !> True when the expression depends on TIME
        logical :: uses_time = .false.
    end type expression_type

contains

    !> Value of the expression at `time` with its inputs' values; NaN outside a function's
    !> domain, and where an input is read that is not given.
    pure function evaluate_expression(expression, time, inputs) result(value)
        type(expression_type), intent(in) :: expression
        !> Time, in the expression's units
        real(wp), intent(in) :: time
        !> Values of expression%inputs, in that order, in the expression's units
        real(wp), intent(in), optional :: inputs(:)
        real(wp) :: value

        call run_program(expression, time, value, inputs)
    end function evaluate_expression

    !> Run the stack program at `time` with the inputs' values: its value and, when kinds and g
    !> are given, the switch functions of its watched switches (switch_values).
    pure subroutine run_program(expression, time, value, inputs, kinds, g)
        type(expression_type), intent(in) :: expression
        real(wp), intent(in) :: time
        real(wp), intent(out) :: value
        real(wp), intent(in), optional :: inputs(:)
        integer, intent(in), optional :: kinds(:)
        real(wp), intent(out), optional :: g(:)
        real(wp) :: stack(max_stack)
        integer :: i, top, k, j

        top = 0
        j = 0
        do i = 1, size(expression%op)
            if (present(kinds) .and. present(g)) then
                if (kinds(i) == switch_watched) call add_switch(expression%op(i), stack, top, &
                    & g, j)
            end if
            select case (expression%op(i))
            case (op_constant)
                top = top + 1
                stack(top) = expression%constant(i)
            case (op_time)
                top = top + 1
                stack(top) = time
            case (op_input)
                top = top + 1
                k = nint(expression%constant(i))
                stack(top) = nan()
                if (present(inputs)) then
                    if (k <= size(inputs)) stack(top) = inputs(k)
                end if
            case (op_negate)
                stack(top) = -stack(top)
            case (op_sin:op_abs)
                stack(top) = unary(expression%op(i), stack(top))
            case (op_add:op_power, op_atan2:op_max)
                top = top - 1
                stack(top) = binary(expression%op(i), stack(top), stack(top + 1))
            case (op_step, op_havsin, op_step5)
                top = top - 4
                stack(top) = smooth_step(expression%op(i), stack(top:top + 4))
            case (op_if)
                top = top - 3
                stack(top) = if_branch(stack(top:top + 3))
            end select
        end do
        value = stack(1)
    end subroutine run_program

    !> The switch function(s) of the watched switch op, its arguments on the stack up to top,
    !> into g after the j already there (j counts them).
    pure subroutine add_switch(op, stack, top, g, j)
        integer, intent(in) :: op, top
        real(wp), intent(in) :: stack(:)
        real(wp), intent(inout) :: g(:)
        integer, intent(inout) :: j

        select case (op)
        case (op_step, op_havsin, op_step5)
            g(j + 1:j + 2) = stack(top - 4) - [stack(top - 3), stack(top - 1)]
            j = j + 2
        case (op_if)
            g(j + 1) = stack(top - 3)
            j = j + 1
        case (op_min, op_max)
            g(j + 1) = stack(top - 1) - stack(top)
            j = j + 1
        case default
            g(j + 1) = stack(top)
            j = j + 1
        end select
    end subroutine add_switch

    !> IF(e: negative, zero, positive) from its four values.
    pure function if_branch(arguments) result(y)
        real(wp), intent(in) :: arguments(4)
        real(wp) :: y

        if (arguments(1) < 0.0_wp) then
            y = arguments(2)
        else if (arguments(1) > 0.0_wp) then
            y = arguments(4)
        else
            y = arguments(3)
        end if
    end function if_branch

    !> The times at which the expression switches: where the condition of an IF, the argument
    !> of a STEP, STEP5 or HAVSIN, the difference of MIN's or MAX's arguments or the argument of
    !> ABS is a TIME - c (any a TIME + b, a /= 0, of constants) and crosses zero, x0 or x1
    !> (constants). A switch on anything else (a state function, a product of TIME) is not
    !> found here: switch_kinds calls it watched. In the expression's time units, in the order
    !> the program meets them (an inner IF before the IF around it). A time that is not finite
    !> (constants whose product or sum overflows: the switch never happens) is left out.
    pure function switching_times(expression) result(times)
        type(expression_type), intent(in) :: expression
        real(wp), allocatable :: times(:)
        integer, allocatable :: kinds(:)

        call analyse_switches(expression, kinds, times)
    end function switching_times

    !> For each operation of the program: switch_none, switch_timed (its times are among
    !> switching_times) or switch_watched (a switch whose argument is not affine in TIME: a
    !> state function, or TIME in a non-affine way).
    pure function switch_kinds(expression) result(kinds)
        type(expression_type), intent(in) :: expression
        integer, allocatable :: kinds(:)
        real(wp), allocatable :: times(:)

        call analyse_switches(expression, kinds, times)
    end function switch_kinds

    !> Number of switch functions switch_values gives for these kinds: two for a watched
    !> STEP, STEP5 or HAVSIN (x - x0, x - x1), one for a watched IF, MIN, MAX or ABS.
    pure integer function switch_count(expression, kinds)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: kinds(:)
        integer :: i

        switch_count = 0
        do i = 1, size(kinds)
            if (kinds(i) /= switch_watched) cycle
            select case (expression%op(i))
            case (op_step, op_havsin, op_step5)
                switch_count = switch_count + 2
            case default
                switch_count = switch_count + 1
            end select
        end do
    end function switch_count

    !> The switch functions of the watched switches (kinds from switch_kinds) at `time` with
    !> the inputs' values, in program order, each zero where its switch switches: an IF's
    !> condition, x - x0 and x - x1 of a STEP, STEP5 or HAVSIN, a - b of MIN(a, b) and
    !> MAX(a, b), the argument of ABS. g has switch_count values. Allocates nothing (an event
    !> function of the integrators).
    pure subroutine switch_values(expression, time, inputs, kinds, g)
        type(expression_type), intent(in) :: expression
        !> Time, in the expression's units
        real(wp), intent(in) :: time
        !> Values of expression%inputs, in that order, in the expression's units
        real(wp), intent(in) :: inputs(:)
        integer, intent(in) :: kinds(:)
        real(wp), intent(out) :: g(:)
        real(wp) :: value

        call run_program(expression, time, value, inputs, kinds, g)
    end subroutine switch_values

    !> The switches of the program (analyse_switches' walk): each pending value as
    !> slope*TIME + offset when affine (slope 0: a constant).
    pure subroutine analyse_switches(expression, kinds, times)
        type(expression_type), intent(in) :: expression
        integer, allocatable, intent(out) :: kinds(:)
        real(wp), allocatable, intent(out) :: times(:)
        real(wp) :: slope(max_stack), offset(max_stack)
        logical :: affine(max_stack)
        integer :: i, top, op, arity

        allocate(times(0))
        allocate(kinds(size(expression%op)), source=switch_none)
        top = 0
        do i = 1, size(expression%op)
            op = expression%op(i)
            select case (op)
            case (op_constant, op_time, op_input)
                top = top + 1
                affine(top) = op /= op_input
                slope(top) = merge(1.0_wp, 0.0_wp, op == op_time)
                offset(top) = merge(expression%constant(i), 0.0_wp, op == op_constant)
                cycle
            case (op_negate)
                slope(top) = -slope(top)
                offset(top) = -offset(top)
                cycle
            case (op_abs)
                arity = 1
                call classify(kinds(i), times, [slope(top)], [offset(top)], [affine(top)])
            case (op_sin:op_sqrt)
                arity = 1
            case (op_step, op_havsin, op_step5)
                arity = 5
                ! x - x0 and x - x1 (the arguments x, x0, h0, x1, h1 from top - 4 up)
                call classify(kinds(i), times, slope(top - 4) - [slope(top - 3), &
                    & slope(top - 1)], &
                    & offset(top - 4) - [offset(top - 3), offset(top - 1)], &
                    & [affine(top - 4) .and. affine(top - 3), &
                    & affine(top - 4) .and. affine(top - 1)])
            case (op_if)
                arity = 4
                call classify(kinds(i), times, [slope(top - 3)], [offset(top - 3)], &
                    & [affine(top - 3)])
            case (op_min, op_max)
                arity = 2
                call classify(kinds(i), times, [slope(top - 1) - slope(top)], &
                    & [offset(top - 1) - offset(top)], [affine(top - 1) .and. affine(top)])
            case default
                arity = 2
            end select
            top = top - arity + 1
            call combine(op, arity, slope(top:top + arity - 1), offset(top:top + arity - 1), &
                & affine(top:top + arity - 1))
        end do
    end subroutine analyse_switches

    !> A switch where each slope*TIME + offset (when affine) is zero: timed, its times added,
    !> when every one is affine (a constant one, of slope 0, never switches), else watched.
    pure subroutine classify(kind, times, slopes, offsets, affines)
        integer, intent(inout) :: kind
        real(wp), allocatable, intent(inout) :: times(:)
        real(wp), intent(in) :: slopes(:), offsets(:)
        logical, intent(in) :: affines(:)

        if (.not. all(affines)) then
            kind = switch_watched
        else if (any(slopes /= 0.0_wp)) then
            kind = switch_timed
            call add_finite(times, pack(-offsets/slopes, slopes /= 0.0_wp))
        end if
    end subroutine classify

    !> Append the finite ones of candidates to times.
    pure subroutine add_finite(times, candidates)
        real(wp), allocatable, intent(inout) :: times(:)
        real(wp), intent(in) :: candidates(:)

        times = [times, pack(candidates, ieee_is_finite(candidates))]
    end subroutine add_finite

    !> The affine form of an operation's result from its arguments' (first element on return).
    pure subroutine combine(op, arity, slope, offset, affine)
        integer, intent(in) :: op, arity
        real(wp), intent(inout) :: slope(arity), offset(arity)
        logical, intent(inout) :: affine(arity)
        real(wp) :: values(5)

        if (all(affine) .and. all(slope == 0.0_wp)) then
            ! constants only: fold
            values(:arity) = offset
            select case (op)
            case (op_sin:op_abs)
                offset(1) = unary(op, values(1))
            case (op_step, op_havsin, op_step5)
                offset(1) = smooth_step(op, values(:5))
            case (op_if)
                offset(1) = if_branch(values(:4))
            case default
                offset(1) = binary(op, values(1), values(2))
            end select
            return
        end if
        affine(1) = all(affine) .and. arity == 2
        if (.not. affine(1)) return
        select case (op)
        case (op_add)
            slope(1) = slope(1) + slope(2)
            offset(1) = offset(1) + offset(2)
        case (op_subtract)
            slope(1) = slope(1) - slope(2)
            offset(1) = offset(1) - offset(2)
        case (op_multiply)
            affine(1) = slope(1) == 0.0_wp .or. slope(2) == 0.0_wp
            slope(1) = slope(1)*offset(2) + slope(2)*offset(1)
            offset(1) = offset(1)*offset(2)
        case (op_divide)
            affine(1) = slope(2) == 0.0_wp .and. offset(2) /= 0.0_wp
            if (affine(1)) slope(1) = slope(1)/offset(2)
            if (affine(1)) offset(1) = offset(1)/offset(2)
        case default
            affine(1) = .false.
        end select
    end subroutine combine

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

    !> ADAMS's STEP (cubic, C1), STEP5 (quintic, C2) or HAVSIN (haversine, C1) from h0 at x0
    !> to h1 at x1, by the operation op; NaN unless x0 < x1. Arguments: x, x0, h0, x1, h1.
    pure function smooth_step(op, arguments) result(y)
        integer, intent(in) :: op
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
                select case (op)
                case (op_havsin)
                    y = 0.5_wp*(h0 + h1) + 0.5_wp*(h1 - h0)*sin(pi*s - 0.5_wp*pi)
                case (op_step5)
                    y = h0 + (h1 - h0)*s**3*(10.0_wp - 15.0_wp*s + 6.0_wp*s**2)
                case default
                    y = h0 + (h1 - h0)*s**2*(3.0_wp - 2.0_wp*s)
                end select
            end if
        end associate
    end function smooth_step

    pure function nan()
        real(wp) :: nan

        nan = ieee_value(nan, ieee_quiet_nan)
    end function nan

end module rollcon_expression
