! SPDX-License-Identifier: MIT
!> Checks a UCOSUB entry by entry: every partial against finite differences of its own
!> lower-order outputs, and the rules a UCOSUB must keep (docs/design.md §2).
module rollcon_partials_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface, max_ucon_vars, is_velocity_code, &
        & scalar_none, scalar_value, scalar_dt, scalar_dtt, array_none, array_dq, array_dtdq, &
        & xmatrx_none, xmatrx_dqdq
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_check_rules, only : rule_derivative, rule_symmetry, rule_velocity_linear, &
        & rule_selector_0, rule_repeat, rule_outside_block, rule_finite, rule_name
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: ucon_check_options_type, ucon_mismatch_type, ucon_check_result_type
    public :: check_ucon_state, huge_output

    !> Largest magnitude of an output the check accepts. The comparison's tolerance scales
    !> with the values compared, so a routine returning F = 1e308 would pass every comparison;
    !> no constraint in any system of units comes near 1e100, and beyond it the integrators'
    !> products of outputs overflow. A larger finite value is a finite finding.
    real(wp), parameter :: huge_output = 1.0e100_wp

    !> How the comparison is made
    type :: ucon_check_options_type
        !> Relative step: h_j = step * max(1, |q_j|) [variable units], likewise for time
        real(wp) :: step = 1.0e-3_wp
        !> An entry fails when |returned - difference| > rel_tol * scale, where scale is the
        !> largest magnitude among the returned entry and the differenced values. Sixth-order
        !> central differences with h = 1e-3 carry ~1e-18 truncation and ~1e-12 round-off
        !> relative to that scale for trigonometric constraints, so 1e-8 leaves a wide margin
        !> yet catches any wrong term that is not itself 1e-8 of the rest.
        real(wp) :: rel_tol = 1.0e-8_wp
    end type ucon_check_options_type

    !> One entry found wrong
    type :: ucon_mismatch_type
        !> Which rule (rollcon_check_rules): rule_derivative, rule_symmetry,
        !> rule_velocity_linear, rule_selector_0, rule_repeat, rule_outside_block (an entry
        !> beyond the declared variables is non-zero)
        integer :: code = 0
        !> The rule's name, for messages: rule_name(code)
        character(len=:), allocatable :: rule
        !> Which output: "ARRAY (dF/dq)", "XMATRX (d2F/dq dq)", "SCALAR (dF/dt)", ...
        character(len=:), allocatable :: output
        !> Row and column of the entry in q's numbering (0 when not applicable); for
        !> "selector-0", the first entry written although not asked for
        integer :: row = 0, column = 0
        !> What the check computed and what the routine returned
        real(wp) :: expected = 0.0_wp, returned = 0.0_wp
    end type ucon_mismatch_type

    !> What one check found
    type :: ucon_check_result_type
        !> Entries found wrong
        type(ucon_mismatch_type), allocatable :: mismatches(:)
        !> Number of entries compared
        integer :: compared = 0
        !> Largest |returned - expected| / scale over all compared entries
        real(wp) :: worst = 0.0_wp
    end type ucon_check_result_type

    !> The factor by which the step shrinks when an entry is judged again
    integer, parameter :: refinement = 4

    !> Sixth-order central difference weights for offsets -3..3, divided by 60 h
    real(wp), parameter :: fd_weights(-3:3) = [-1.0_wp, 9.0_wp, -45.0_wp, 0.0_wp, 45.0_wp, &
        & -9.0_wp, 1.0_wp] / 60.0_wp

contains

    !> Check every output of UCON id at one state; mismatches are appended to result. Long
    !> because each output (F, f(t), dF/dt, d2F/dt2, ARRAY, XMATRX) has its own short check in
    !> one sequence that shares the state's evaluations.
    subroutine check_ucon_state(ucosub, id, par, codes, time, q, options, result, error)
        !> The routine under test
        procedure(ucosub_interface) :: ucosub
        !> UCON statement id
        integer, intent(in) :: id
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(:)
        !> Codes the routine declared, in order (their number is the number of variables)
        integer, intent(in) :: codes(:)
        !> Time [s]
        real(wp), intent(in) :: time
        !> State: values of the declared variables
        real(wp), intent(in) :: q(:)
        !> Step and tolerance
        type(ucon_check_options_type), intent(in) :: options
        !> Findings, accumulated
        type(ucon_check_result_type), intent(inout) :: result
        !> Set when the routine reported an error or returned a non-finite value
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: q30(max_ucon_vars), f, ft, ftt, a(max_ucon_vars), atq(max_ucon_vars)
        real(wp) :: x(max_ucon_vars, max_ucon_vars), scratch(max_ucon_vars, max_ucon_vars)
        real(wp) :: f_line(-3:3), a_line(max_ucon_vars, -3:3), ft_line(-3:3), h
        real(wp) :: fine_line(max_ucon_vars, -3:3), fine_f_line(-3:3), fine_ft_line(-3:3)
        real(wp) :: fd_f, fine_f, fd_a(max_ucon_vars), fine_a(max_ucon_vars), fd_t(2), fine_t(2)
        real(wp) :: a_scale, x_scale, atq_scale
        real(wp) :: f_again, a_again(max_ucon_vars), x_again(max_ucon_vars, max_ucon_vars)
        integer :: n, i, j, loc(2)

        if (.not. allocated(result%mismatches)) allocate(result%mismatches(0))
        n = size(codes)
        q30 = 0.0_wp
        q30(:n) = q(:n)
        call evaluate_ucon(ucosub, id, time, q30, par, [scalar_value, array_dq, xmatrx_dqdq], &
            & f, a, x, error)
        if (allocated(error)) return
        call evaluate_ucon(ucosub, id, time, q30, par, [scalar_dt, array_dtdq, xmatrx_none], &
            & ft, atq, scratch, error)
        if (allocated(error)) return
        call evaluate_ucon(ucosub, id, time, q30, par, [scalar_dtt, array_none, xmatrx_none], &
            & ftt, scratch(:, 1), scratch, error)
        if (allocated(error)) return
        ! Huge outputs: every comparison below scales with them and would pass.
        if (huge_outputs(result, n, f, ft, ftt, a, atq, x)) return
        ! Nothing beyond the declared variables: the outputs were zeroed before the call.
        if (any(a(n + 1:) /= 0.0_wp)) then
            i = n + findloc(a(n + 1:) /= 0.0_wp, .true., dim=1)
            call add(result, rule_outside_block, "ARRAY (dF/dq)", i, 0, 0.0_wp, a(i))
        end if
        if (any(x /= 0.0_wp .and. .not. declared_block(n))) then
            loc = findloc(x /= 0.0_wp .and. .not. declared_block(n), .true.)
            call add(result, rule_outside_block, "XMATRX (d2F/dq dq)", loc(1), loc(2), 0.0_wp, &
                & x(loc(1), loc(2)))
        end if

        ! Same inputs, same outputs: a routine with hidden state fails here.
        call evaluate_ucon(ucosub, id, time, q30, par, [scalar_value, array_dq, xmatrx_dqdq], &
            & f_again, a_again, x_again, error)
        if (allocated(error)) return
        if (f_again /= f .or. any(a_again /= a) .or. any(x_again /= x)) then
            call add(result, rule_repeat, "all outputs", 0, 0, f, f_again)
        end if

        a_scale = maxval(abs(a(:n)))
        x_scale = maxval(abs(x(:n, :n)))
        atq_scale = maxval(abs(atq(:n)))
        do j = 1, n
            h = options%step * max(1.0_wp, abs(q30(j)))
            call q_lines(ucosub, id, time, q30, par, j, h, f, a, f_line, a_line, error)
            if (allocated(error)) return
            fd_f = dot_product(fd_weights, f_line) / h
            fd_a = matmul(a_line, fd_weights) / h
            ! a deviation beyond the tolerance is judged again at a quarter of the step
            fine_f = fd_f
            fine_a = fd_a
            if (beyond(options, fd_f, a(j), f_line, a_scale) .or. any([(beyond(options, &
                & fd_a(i), x(i, j), a_line(i, :), x_scale), i = 1, n)])) then
                call q_lines(ucosub, id, time, q30, par, j, h/refinement, f, a, f_line, &
                    & fine_line, error)
                if (allocated(error)) return
                fine_f = dot_product(fd_weights, f_line) / (h/refinement)
                fine_a = matmul(fine_line, fd_weights) / (h/refinement)
            end if
            call compare(result, options, "ARRAY (dF/dq)", j, 0, fd_f, fine_f, a(j), f_line, &
                & a_scale)
            do i = 1, n
                call compare(result, options, "XMATRX (d2F/dq dq)", i, j, fd_a(i), fine_a(i), &
                    & x(i, j), a_line(i, :), x_scale)
            end do
        end do

        h = options%step * max(1.0_wp, abs(time))
        call t_lines(ucosub, id, time, q30, par, h, f, ft, a, f_line, ft_line, a_line, error)
        if (allocated(error)) return
        fd_t = [dot_product(fd_weights, f_line), dot_product(fd_weights, ft_line)] / h
        fd_a = matmul(a_line, fd_weights) / h
        fine_t = fd_t
        fine_a = fd_a
        if (beyond(options, fd_t(1), ft, f_line, 0.0_wp) .or. beyond(options, fd_t(2), ftt, &
            & ft_line, 0.0_wp) .or. any([(beyond(options, fd_a(i), atq(i), a_line(i, :), &
            & atq_scale), i = 1, n)])) then
            call t_lines(ucosub, id, time, q30, par, h/refinement, f, ft, a, fine_f_line, &
                & fine_ft_line, fine_line, error)
            if (allocated(error)) return
            fine_t = [dot_product(fd_weights, fine_f_line), &
                & dot_product(fd_weights, fine_ft_line)] / (h/refinement)
            fine_a = matmul(fine_line, fd_weights) / (h/refinement)
        end if
        call compare(result, options, "SCALAR (dF/dt)", 0, 0, fd_t(1), fine_t(1), ft, f_line, &
            & 0.0_wp)
        call compare(result, options, "SCALAR (d2F/dt2)", 0, 0, fd_t(2), fine_t(2), ftt, &
            & ft_line, 0.0_wp)
        do i = 1, n
            call compare(result, options, "ARRAY (d2F/dt dq)", i, 0, fd_a(i), fine_a(i), &
                & atq(i), a_line(i, :), atq_scale)
        end do

        call check_rules(ucosub, id, time, q30, par, codes, x, result, error)
    end subroutine check_ucon_state

    !> Symmetry, linearity in the velocities, selector 0 (the declared block is checked above).
    subroutine check_rules(ucosub, id, time, q30, par, codes, x, result, error)
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: id
        real(wp), intent(in) :: time, q30(:), par(:)
        integer, intent(in) :: codes(:)
        real(wp), intent(in) :: x(:, :)
        type(ucon_check_result_type), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: sentinel = 12345.0_wp
        real(wp) :: scalar, array(max_ucon_vars), xmatrx(max_ucon_vars, max_ucon_vars)
        real(wp) :: scale
        integer :: n, i, j, s, loc(2)

        n = size(codes)
        scale = maxval(abs(x(:n, :n)))
        do j = 1, n
            do i = j + 1, n
                ! Both triangles must be filled with the same value; round-off of separately
                ! computed expressions is allowed for.
                if (abs(x(i, j) - x(j, i)) > 8.0_wp*epsilon(1.0_wp)*scale) then
                    call add(result, rule_symmetry, "XMATRX (d2F/dq dq)", i, j, x(j, i), x(i, j))
                end if
            end do
            do i = 1, n
                ! A UCON must be linear in the velocities: no product of two velocities.
                if (is_velocity_code(codes(i)) .and. is_velocity_code(codes(j)) &
                    & .and. x(i, j) /= 0.0_wp) then
                    call add(result, rule_velocity_linear, "XMATRX (d2F/dq dq)", i, j, &
                        & 0.0_wp, x(i, j))
                end if
            end do
        end do

        ! Selector 0: each output not asked for must come back untouched.
        do s = 1, 3
            scalar = sentinel
            array = sentinel
            xmatrx = sentinel
            call call_raw(ucosub, id, time, q30, par, selector_with(s), scalar, array, xmatrx)
            if (s /= 1 .and. scalar /= sentinel) then
                call add(result, rule_selector_0, "SCALAR", 0, 0, sentinel, scalar)
            end if
            if (s /= 2 .and. any(array /= sentinel)) then
                i = findloc(array /= sentinel, .true., dim=1)
                call add(result, rule_selector_0, "ARRAY", i, 0, sentinel, array(i))
            end if
            if (s /= 3 .and. any(xmatrx /= sentinel)) then
                loc = findloc(xmatrx /= sentinel, .true.)
                call add(result, rule_selector_0, "XMATRX", loc(1), loc(2), sentinel, &
                    & xmatrx(loc(1), loc(2)))
            end if
        end do
        call take_ucon_error(error)
    end subroutine check_rules

    !> Add a finite finding for each output holding a magnitude beyond huge_output (at its
    !> largest entry); true when there was one.
    function huge_outputs(result, n, f, ft, ftt, a, atq, x) result(found)
        type(ucon_check_result_type), intent(inout) :: result
        !> Number of declared variables
        integer, intent(in) :: n
        !> F, dF/dt, d2F/dt2, dF/dq, d2F/dt dq, d2F/dq dq
        real(wp), intent(in) :: f, ft, ftt, a(:), atq(:), x(:, :)
        logical :: found
        integer :: loc(2)

        found = .false.
        call one_value("SCALAR", f)
        call one_value("SCALAR (dF/dt)", ft)
        call one_value("SCALAR (d2F/dt2)", ftt)
        if (n < 1) return
        call one_row("ARRAY (dF/dq)", a(:n))
        call one_row("ARRAY (d2F/dt dq)", atq(:n))
        if (maxval(abs(x(:n, :n))) > huge_output) then
            loc = maxloc(abs(x(:n, :n)))
            call add(result, rule_finite, "XMATRX (d2F/dq dq)", loc(1), loc(2), huge_output, &
                & x(loc(1), loc(2)))
            found = .true.
        end if
    contains
        subroutine one_value(output, value)
            character(len=*), intent(in) :: output
            real(wp), intent(in) :: value

            if (abs(value) <= huge_output) return
            call add(result, rule_finite, output, 0, 0, huge_output, value)
            found = .true.
        end subroutine one_value
        subroutine one_row(output, values)
            character(len=*), intent(in) :: output
            real(wp), intent(in) :: values(:)
            integer :: i

            if (maxval(abs(values)) <= huge_output) return
            i = maxloc(abs(values), dim=1)
            call add(result, rule_finite, output, i, 0, huge_output, values(i))
            found = .true.
        end subroutine one_row
    end function huge_outputs

    !> True for the entries of XMATRX inside the block of the n declared variables.
    pure function declared_block(n) result(inside)
        integer, intent(in) :: n
        logical :: inside(max_ucon_vars, max_ucon_vars)

        inside = .false.
        inside(:n, :n) = .true.
    end function declared_block

    !> IDRSEL asking for output s only (1: scalar F, 2: array dF/dq, 3: xmatrx).
    pure function selector_with(s) result(idrsel)
        integer, intent(in) :: s
        integer :: idrsel(3)

        idrsel = [scalar_none, array_none, xmatrx_none]
        select case (s)
        case (1)
            idrsel(1) = scalar_value
        case (2)
            idrsel(2) = array_dq
        case (3)
            idrsel(3) = xmatrx_dqdq
        end select
    end function selector_with

    !> Call without zeroing the outputs first (to see what the routine leaves alone).
    subroutine call_raw(ucosub, id, time, q30, par, idrsel, scalar, array, xmatrx)
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: id
        real(wp), intent(in) :: time, q30(max_ucon_vars), par(:)
        integer, intent(in) :: idrsel(3)
        real(wp), intent(inout) :: scalar, array(max_ucon_vars)
        real(wp), intent(inout) :: xmatrx(max_ucon_vars, max_ucon_vars)

        call ucosub(id, time, q30, par, size(par), idrsel, 0, scalar, array, xmatrx)
    end subroutine call_raw

    !> The values F(q + k h e_j) and dF/dq(q + k h e_j), k = -3..3, of UCON id along variable
    !> j (f and a at k = 0 as already evaluated).
    subroutine q_lines(ucosub, id, time, q30, par, j, h, f, a, f_line, a_line, error)
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: id, j
        real(wp), intent(in) :: time, q30(max_ucon_vars), par(:), h, f, a(max_ucon_vars)
        real(wp), intent(out) :: f_line(-3:3), a_line(max_ucon_vars, -3:3)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: shifted(max_ucon_vars), scratch(max_ucon_vars, max_ucon_vars)
        integer :: k

        f_line(0) = f
        a_line(:, 0) = a
        do k = -3, 3
            if (k == 0) cycle
            shifted = q30
            shifted(j) = q30(j) + k*h
            call evaluate_ucon(ucosub, id, time, shifted, par, [scalar_value, array_dq, &
                & xmatrx_none], f_line(k), a_line(:, k), scratch, error)
            if (allocated(error)) return
        end do
    end subroutine q_lines

    !> The values F, dF/dt and dF/dq at times time + k h, k = -3..3 (f, ft and a at k = 0 as
    !> already evaluated).
    subroutine t_lines(ucosub, id, time, q30, par, h, f, ft, a, f_line, ft_line, a_line, error)
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: id
        real(wp), intent(in) :: time, q30(max_ucon_vars), par(:), h, f, ft, a(max_ucon_vars)
        real(wp), intent(out) :: f_line(-3:3), ft_line(-3:3), a_line(max_ucon_vars, -3:3)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: scratch(max_ucon_vars, max_ucon_vars)
        integer :: k

        f_line(0) = f
        ft_line(0) = ft
        a_line(:, 0) = a
        do k = -3, 3
            if (k == 0) cycle
            call evaluate_ucon(ucosub, id, time + k*h, q30, par, [scalar_value, array_dq, &
                & xmatrx_none], f_line(k), a_line(:, k), scratch, error)
            if (allocated(error)) return
            call evaluate_ucon(ucosub, id, time + k*h, q30, par, [scalar_dt, array_none, &
                & xmatrx_none], ft_line(k), scratch(:, 1), scratch, error)
            if (allocated(error)) return
        end do
    end subroutine t_lines

    !> True when returned differs from the difference quotient by more than the tolerance
    !> (relative to the largest magnitude among returned, the differenced values and the
    !> entries of the same output, output_scale).
    pure logical function beyond(options, expected, returned, line, output_scale)
        type(ucon_check_options_type), intent(in) :: options
        real(wp), intent(in) :: expected, returned, line(:), output_scale
        real(wp) :: scale

        scale = max(abs(returned), maxval(abs(line)), output_scale, tiny(1.0_wp))
        beyond = .not. (abs(returned - expected)/scale <= options%rel_tol)
    end function beyond

    !> Compare one returned entry with its difference quotients at the step h (expected) and
    !> at h/refinement (finer; equal to expected when the entry was within the tolerance at
    !> h). A sixth-order quotient's truncation error falls by refinement**6 = 4096 from one to
    !> the other, so |expected - finer| estimates the error of expected, and finer is good to
    !> about |expected - finer|/4095. The entry is wrong only when it differs from finer by
    !> more than the tolerance and by more than ten times that estimate of finer's own error:
    !> a right partial at a state where the function bends sharply (where the quotient at h
    !> is off by 1e-7, its terms' seventh derivative large) is not a finding; a wrong one
    !> differs from both quotients alike.
    pure subroutine compare(result, options, output, row, column, expected, finer, returned, &
            & line, output_scale)
        type(ucon_check_result_type), intent(inout) :: result
        type(ucon_check_options_type), intent(in) :: options
        character(len=*), intent(in) :: output
        integer, intent(in) :: row, column
        real(wp), intent(in) :: expected, finer, returned, line(:)
        !> The largest magnitude among the entries of the same output (ARRAY, XMATRX): an
        !> entry is judged against it too, so that an entry that is zero but for rounding (F's
        !> dependence on a variable it does not hold, at a start where F = 0 and so is every
        !> value differenced) is no finding
        real(wp), intent(in) :: output_scale
        real(wp) :: scale, deviation, truncation

        scale = max(abs(returned), maxval(abs(line)), output_scale, tiny(1.0_wp))
        deviation = abs(returned - finer) / scale
        truncation = abs(expected - finer) / scale / (real(refinement, wp)**6 - 1.0_wp)
        result%compared = result%compared + 1
        if (ieee_is_finite(deviation)) then
            result%worst = max(result%worst, deviation)
        else
            result%worst = huge(1.0_wp)
        end if
        if (.not. (deviation <= max(options%rel_tol, 10.0_wp*truncation))) then
            call add(result, rule_derivative, output, row, column, finer, returned)
        end if
    end subroutine compare

    !> Append a mismatch.
    pure subroutine add(result, code, output, row, column, expected, returned)
        type(ucon_check_result_type), intent(inout) :: result
        integer, intent(in) :: code
        character(len=*), intent(in) :: output
        integer, intent(in) :: row, column
        real(wp), intent(in) :: expected, returned
        type(ucon_mismatch_type) :: mismatch

        mismatch%code = code
        mismatch%rule = rule_name(code)
        mismatch%output = output
        mismatch%row = row
        mismatch%column = column
        mismatch%expected = expected
        mismatch%returned = returned
        result%mismatches = [result%mismatches, mismatch]
    end subroutine add

end module rollcon_partials_check
