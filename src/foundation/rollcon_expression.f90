! SPDX-License-Identifier: MIT
!> Function expressions of an ADAMS dataset (`FUNCTION = e`) as small stack programs, evaluated
!> at any time with no allocation (rollcon_adm_expression_parser compiles them).
!>
!> The subset: numbers (with `D` after a number for degrees), `TIME`, `PI`, `DTOR`; `+ - * /`
!> and `**` (right-associative, binding tighter than a sign, as in Fortran); the functions
!> `SIN COS TAN ATAN2 EXP LOG SQRT ABS MIN MAX`, `STEP(x, x0, h0, x1, h1)` (cubic step),
!> `HAVSIN(x, x0, h0, x1, h1)` (haversine step) and `IF(e: neg, zero, pos)`. Names are read in
!> any case. A value outside a function's domain (LOG of a negative number, STEP with x1 <= x0)
!> evaluates to NaN: callers check the result with ieee_is_finite and name the expression.
module rollcon_expression
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: expression_type, evaluate_expression, max_stack
    public :: op_constant, op_time, op_add, op_subtract, op_multiply, op_divide, op_power, &
        & op_negate, op_step, op_havsin, op_if
    public :: function_names, function_codes, function_arguments

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

contains

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

end module rollcon_expression
