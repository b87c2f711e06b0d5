! SPDX-License-Identifier: MIT
!> A compiled expression (rollcon_expression) evaluated in jets (rollcon_jet): its value and
!> its exact first (and second) partials in whatever variables the jets of TIME and of its
!> inputs are taken in (docs/datasets-model.md, "Exact partials of an expression"). The stack
!> program runs as on the value path, each operation applying the chain rule; the functions
!> are those of rollcon_expression_functions, the same code the value path of ADAMS's further
!> functions runs, and the functions of SIN to IF their own jet forms, the same definitions as
!> rollcon_expression's value code (tested value for value).
module rollcon_expression_jet
    use rollcon_kinds, only : wp
    use rollcon_jet, only : jet_type, jet_constant, operator(+), operator(-), operator(*), &
        & sin, cos, tan, exp, atan2, abs
    use rollcon_expression, only : expression_type, op_constant, op_time, op_input, op_add, &
        & op_subtract, op_multiply, op_divide, op_power, op_negate, op_sin, op_cos, op_tan, &
        & op_exp, op_log, op_sqrt, op_abs, op_atan2, op_min, op_max, op_step, op_havsin, op_if, &
        & op_akispl, op_cubspl, first_further_op, last_further_op, operation_arity, max_stack, &
        & spline_id_of, spline_order_of, further_jet
    use rollcon_expression_functions, only : jet_step, jet_havsin, jet_if, jet_min, jet_max, &
        & jet_power, jet_log_domain, jet_sqrt_domain, jet_divide, jet_spline, nan_jet
    use rollcon_spline, only : method_akima, method_cubic
    implicit none
    private

    public :: evaluate_expression_jet

contains

    !> The expression's jet at TIME's jet `time` (in the expression's time units) with its
    !> inputs' jets (in the expression's units, in order); NaN outside a function's domain, and
    !> where an input is read that is not given.
    pure function evaluate_expression_jet(expression, time, inputs) result(value)
        type(expression_type), intent(in) :: expression
        type(jet_type), intent(in) :: time
        type(jet_type), intent(in) :: inputs(:)
        type(jet_type) :: value
        type(jet_type) :: stack(max_stack), curve
        integer :: i, top, k, op, s

        top = 0
        do i = 1, size(expression%op)
            op = expression%op(i)
            select case (op)
            case (op_constant)
                top = top + 1
                stack(top) = jet_constant(expression%constant(i))
            case (op_time)
                top = top + 1
                stack(top) = time
            case (op_input)
                top = top + 1
                k = nint(expression%constant(i))
                stack(top) = nan_jet()
                if (k <= size(inputs)) stack(top) = inputs(k)
            case (op_negate)
                stack(top) = -stack(top)
            case (op_sin)
                stack(top) = sin(stack(top))
            case (op_cos)
                stack(top) = cos(stack(top))
            case (op_tan)
                stack(top) = tan(stack(top))
            case (op_exp)
                stack(top) = exp(stack(top))
            case (op_log)
                stack(top) = jet_log_domain(stack(top))
            case (op_sqrt)
                stack(top) = jet_sqrt_domain(stack(top))
            case (op_abs)
                stack(top) = abs(stack(top))
            case (op_add)
                top = top - 1
                stack(top) = stack(top) + stack(top + 1)
            case (op_subtract)
                top = top - 1
                stack(top) = stack(top) - stack(top + 1)
            case (op_multiply)
                top = top - 1
                stack(top) = stack(top)*stack(top + 1)
            case (op_divide)
                top = top - 1
                stack(top) = jet_divide(stack(top), stack(top + 1))
            case (op_power)
                top = top - 1
                stack(top) = jet_power(stack(top), stack(top + 1))
            case (op_atan2)
                top = top - 1
                stack(top) = atan2(stack(top), stack(top + 1))
            case (op_min)
                top = top - 1
                stack(top) = jet_min(stack(top), stack(top + 1))
            case (op_max)
                top = top - 1
                stack(top) = jet_max(stack(top), stack(top + 1))
            case (op_step, op_havsin)
                top = top - 4
                if (op == op_step) then
                    stack(top) = jet_step(stack(top), stack(top + 1), stack(top + 2), &
                        & stack(top + 3), stack(top + 4))
                else
                    stack(top) = jet_havsin(stack(top), stack(top + 1), stack(top + 2), &
                        & stack(top + 3), stack(top + 4))
                end if
            case (op_if)
                top = top - 3
                stack(top) = jet_if(stack(top), stack(top + 1), stack(top + 2), stack(top + 3))
            case (first_further_op:last_further_op)
                k = operation_arity(op, expression%constant(i))
                top = top - k + 1
                if (op == op_akispl .or. op == op_cubspl) then
                    ! the curve at its argument x, stack(top); NaN without the curve
                    curve = nan_jet()
                    if (allocated(expression%splines)) then
                        s = findloc(expression%splines%id, &
                            & spline_id_of(expression%constant(i)), dim=1)
                        if (s > 0) curve = jet_spline(stack(top), expression%splines(s), &
                            & merge(method_akima, method_cubic, op == op_akispl), &
                            & spline_order_of(expression%constant(i)))
                    end if
                    stack(top) = curve
                else
                    stack(top) = further_jet(op, stack(top:top + k - 1))
                end if
            end select
        end do
        value = stack(1)
    end function evaluate_expression_jet

end module rollcon_expression_jet
