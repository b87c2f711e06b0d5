! SPDX-License-Identifier: MIT
!> What every compiled function expression must be, whatever text it came from: a stack
!> program of known operations whose every step has its operands, that never holds more than
!> max_stack values and leaves exactly one, whose constants are finite, whose inputs are state
!> functions of markers with positive ids, and that evaluates and yields its switching times
!> without a fault (the fuzz suites of the dataset reader and of the expression compiler).
module expression_checks
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_expression, only : expression_type, evaluate_expression, switching_times, &
        & max_stack, max_inputs, op_constant, op_time, op_input, op_add, op_power, op_negate, &
        & op_if, function_codes, function_arguments, quantity_names, max_arguments
    use rollcon_testing, only : check
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: check_expression_program

    !> Times the program is evaluated at (in the expression's units): before, at and after the
    !> switching times of the shipped datasets, and far off
    real(wp), parameter :: times(*) = [-1.0_wp, 0.0_wp, 0.5_wp, 2.005_wp, 1.0e6_wp]

contains

    !> The checks above; label names the expression in a failure's message.
    subroutine check_expression_program(expression, label, error)
        type(expression_type), intent(in) :: expression
        character(len=*), intent(in) :: label
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: inputs(:), switches(:)
        real(wp) :: value
        integer :: i, depth, deepest, change, k
        logical :: known

        call check(error, allocated(expression%op) .and. allocated(expression%constant) &
            & .and. allocated(expression%inputs) .and. allocated(expression%text), label &
            & // ": a compiled expression with a part missing")
        if (allocated(error)) return
        call check(error, size(expression%constant) == size(expression%op) .and. &
            & all(ieee_is_finite(expression%constant)), label // ": a constant that is not " &
            & // "finite in '" // expression%text // "'")
        if (allocated(error)) return
        depth = 0
        deepest = 0
        do i = 1, size(expression%op)
            call stack_change(expression%op(i), expression%constant(i), change, known)
            call check(error, known .and. depth + min(change, 0) >= 1 - merge(1, 0, change > 0), &
                & label // ": operation " // to_text(i) // " has no operands in '" &
                & // expression%text // "'")
            if (allocated(error)) return
            if (expression%op(i) == op_input) then
                k = nint(expression%constant(i))
                call check(error, k >= 1 .and. k <= size(expression%inputs), label &
                    & // ": an input that is not listed in '" // expression%text // "'")
                if (allocated(error)) return
            end if
            depth = depth + change
            deepest = max(deepest, depth)
        end do
        call check(error, depth == 1 .and. deepest <= max_stack, label // ": the program " &
            & // "does not leave one value within the stack in '" // expression%text // "'")
        if (allocated(error)) return
        call check(error, size(expression%inputs) <= max_inputs .and. &
            & all(expression%inputs%marker > 0) .and. all(expression%inputs%quantity >= 1) &
            & .and. all(expression%inputs%quantity <= size(quantity_names)), label &
            & // ": an input that is not a measure of markers in '" &
            & // expression%text // "'")
        if (allocated(error)) return
        ! any value, NaN included (a domain error is the caller's to report), but no fault
        inputs = [(0.25_wp*k - 1.0_wp, k = 1, size(expression%inputs))]
        do i = 1, size(times)
            value = evaluate_expression(expression, times(i), inputs)
        end do
        switches = switching_times(expression)
        call check(error, all(ieee_is_finite(switches)), label // ": a switching time that " &
            & // "is not finite in '" // expression%text // "'")
    end subroutine check_expression_program

    !> How an operation changes the depth of the stack; known is false for an unknown code, or
    !> a function of a variable number of arguments whose count (in its constant slot) is out
    !> of its range.
    pure subroutine stack_change(op, constant, change, known)
        integer, intent(in) :: op
        real(wp), intent(in) :: constant
        integer, intent(out) :: change
        logical, intent(out) :: known
        integer :: k

        known = .true.
        select case (op)
        case (op_constant, op_time, op_input)
            change = 1
        case (op_add:op_power)
            change = -1
        case (op_negate)
            change = 0
        case (op_if)
            change = -3
        case default
            k = findloc(function_codes, op, dim=1)
            known = k > 0
            change = 0
            if (.not. known) return
            if (function_arguments(k) > 0) then
                change = 1 - function_arguments(k)
            else
                known = nint(constant) >= -function_arguments(k) .and. nint(constant) &
                    & <= max_arguments
                change = 1 - nint(constant)
            end if
        end select
    end subroutine stack_change

end module expression_checks
