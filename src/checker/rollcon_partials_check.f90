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
        !> Largest relative step: h0 = step * max(1, |q_j|) [variable units], likewise for
        !> time; the differences are taken at h0, h0/2, h0/4, ... (judge_line)
        real(wp) :: step = 1.0e-3_wp
        !> An entry fails when |returned - difference| exceeds this multiple of the
        !> difference's own estimated error (judge_line). The estimate already overstates the
        !> error it measures (the truncation part by the change from the step twice as long,
        !> some 64 times the error once the step resolves the function; the round-off part as
        !> the sum of the weights' worst case); 10 more covers an estimate that is low by
        !> chance (two quotients agreeing where their errors happen to match, a noise sample
        !> below its typical size), and still leaves a deviation of 1e-5 of a well-conditioned
        !> entry (estimates near 1e-12 of it) a finding by six orders
        real(wp) :: error_multiple = 10.0_wp
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
        !> Entries whose differences do not know them to checkable_fraction (compare): not
        !> checkable at this state, neither a finding nor a pass
        integer :: not_checkable = 0
    end type ucon_check_result_type

    !> The most steps an entry is judged at: h0, h0/2, ..., h0/2**(max_levels - 1); the last,
    !> 2e-6 of a variable near 1, is where the round-off of the values of any routine (1e-16
    !> of terms up to 1e4 times the values, as near a singularity where they cancel) has
    !> overtaken the truncation of any function it resolves
    integer, parameter :: max_levels = 10

    !> An entry whose allowance (error_multiple times the difference's estimated error)
    !> reaches this fraction of the differences' own scale (their value, the values
    !> differenced, the output's other entries) is not checkable at that state: the
    !> differences do not know it to a tenth, so neither agreeing nor differing says anything
    real(wp), parameter :: checkable_fraction = 0.1_wp

    !> An entry that agrees with its differences stops the halving of the steps once their
    !> estimated error is below this fraction of its scale: then the allowance (10 times it)
    !> is finer than 1e-8, and a smaller step would change no verdict. At most states the
    !> first two steps give 1e-12; near a singularity the steps go on halving until the
    !> estimate gets there or stops falling, so a right entry is judged at the step that
    !> resolves it, and a wrong one against the smallest error the differences can reach
    real(wp), parameter :: resolved_fraction = 1.0e-10_wp

    !> Sixth-order central difference weights for offsets -3..3, divided by 60 h
    real(wp), parameter :: fd_weights(-3:3) = [-1.0_wp, 9.0_wp, -45.0_wp, 0.0_wp, 45.0_wp, &
        & -9.0_wp, 1.0_wp] / 60.0_wp
    !> Sum of |fd_weights|: a quotient's round-off is at most this times the values' noise / h
    real(wp), parameter :: weights_sum = 110.0_wp/60.0_wp
    !> Sixth difference of seven equally spaced values: noise of size sigma in the values
    !> leaves it about sqrt(sum of squares = 924) sigma; a smooth function h**6 times its
    !> sixth derivative
    real(wp), parameter :: sixth_difference(-3:3) = [1.0_wp, -6.0_wp, 15.0_wp, -20.0_wp, &
        & 15.0_wp, -6.0_wp, 1.0_wp]

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
        real(wp) :: returned(max_ucon_vars + 2), output_scale(max_ucon_vars + 2)
        real(wp) :: other_scale(max_ucon_vars + 2)
        real(wp) :: center(max_ucon_vars + 2)
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
        ! Along each variable: dF/dq_j from F, row j of XMATRX from dF/dq.
        do j = 1, n
            center(1) = f
            center(2:n + 1) = a(:n)
            returned(1) = a(j)
            returned(2:n + 1) = x(:n, j)
            output_scale(1) = a_scale
            output_scale(2:n + 1) = x_scale
            other_scale(1) = largest_other(a(:n), j)
            do i = 1, n
                other_scale(1 + i) = largest_other_entry(x, n, i, j)
            end do
            call judge_line(ucosub, id, time, q30, par, j, n + 1, &
                & options%step*max(1.0_wp, abs(q30(j))), center(:n + 1), returned(:n + 1), &
                & output_scale(:n + 1), other_scale(:n + 1), options, result, error)
            if (allocated(error)) return
        end do
        ! Along time: dF/dt from F, d2F/dt2 from dF/dt, d2F/dt dq from dF/dq.
        center(1) = f
        center(2) = ft
        center(3:n + 2) = a(:n)
        returned(1) = ft
        returned(2) = ftt
        returned(3:n + 2) = atq(:n)
        output_scale(1:2) = 0.0_wp
        output_scale(3:n + 2) = atq_scale
        other_scale(1:2) = 0.0_wp
        do i = 1, n
            other_scale(2 + i) = largest_other(atq(:n), i)
        end do
        call judge_line(ucosub, id, time, q30, par, 0, n + 2, &
            & options%step*max(1.0_wp, abs(time)), center(:n + 2), returned(:n + 2), &
            & output_scale(:n + 2), other_scale(:n + 2), options, result, error)
        if (allocated(error)) return

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

    !> Judge the entries differenced along one line, variable j of q (j >= 1) or time (j = 0):
    !> entry 1 is dF/dq_j from F and entry 1 + i is XMATRX(i, j) from dF/dq_i (j >= 1), or
    !> entries 1, 2 and 2 + i are dF/dt from F, d2F/dt2 from dF/dt and d2F/dt dq_i from dF/dq_i
    !> (j = 0). Each entry's sixth-order central quotient D(h) is taken at the steps h0, h0/2,
    !> h0/4, ... (at most max_levels of them), and the error of each quotient but the first
    !> and the last is estimated from its neighbours as
    !>     E(h) = max(|D(2h) - D(h)|, |D(h) - D(h/2)|) + w sigma (2/h + 1/h + 1/2h) + 8 eps s:
    !> truncation, bounded by the changes to the steps twice and half as long (D(2h)'s
    !> truncation error is 64 times D(h)'s once the step resolves the function, so the change
    !> overstates D(h)'s; before that the change is as large as the errors themselves; both
    !> changes, lest two quotients agree by chance, as the rounding inside a routine near its
    !> singularity makes them do: its values' rounding errors there are no white noise but
    !> pieces of smooth functions, which move D by the same 1e-10 at every small step);
    !> round-off, the values' own noise sigma times w = sum |weights| = 11/6 over the steps
    !> (sigma from the values: noise of size sigma leaves their sixth difference about
    !> sqrt(924) sigma, so the larger of this step's sixth difference and the last step's,
    !> over sqrt(924), and at least eps times the largest value differenced); and the returned
    !> entry's own rounding, 8 eps s (s the entry's scale: the largest of the returned entry,
    !> the values differenced and the entries of the same output). The quotient with the
    !> smallest E is the entry's expected value.
    !> Refining stops when every entry is settled (it agrees within options%error_multiple * E
    !> and E is below resolved_fraction of s), or when the estimate of each entry not settled
    !> yet has grown at two steps in a row (round-off rules there: finer steps only make it
    !> worse). Each entry is then compared (compare).
    subroutine judge_line(ucosub, id, time, q30, par, j, count, h0, center, returned, &
            & output_scale, other_scale, options, result, error)
        procedure(ucosub_interface) :: ucosub
        !> UCON id; the line: variable j, or time for j = 0; number of entries
        integer, intent(in) :: id, j, count
        !> Time [s], state, PAR; the largest step [variable's units, or s]
        real(wp), intent(in) :: time, q30(max_ucon_vars), par(:), h0
        !> The values differenced at the state itself, the returned entries, and each entry's
        !> output's largest magnitude (count of each)
        real(wp), intent(in) :: center(:), returned(:), output_scale(:)
        !> Each entry's output's largest magnitude but for the entry itself (and its twin
        !> across XMATRX's diagonal): with the values differenced and the differences, the
        !> scale the differences' trust is judged on, which a wrong returned entry cannot raise
        real(wp), intent(in) :: other_scale(:)
        type(ucon_check_options_type), intent(in) :: options
        type(ucon_check_result_type), intent(inout) :: result
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: m = max_ucon_vars + 2
        real(wp) :: values(m, -3:3), quotient(m), previous(m), before(m), best(m), estimate(m)
        real(wp) :: noise(m)
        real(wp) :: magnitude(m), scale(m), last_sixth(m), trial, sixth, h
        integer :: grown(m), level, i
        logical :: judged(m)

        h = h0
        best = 0.0_wp
        estimate = huge(1.0_wp)
        grown = 0
        judged = .false.
        magnitude = 0.0_wp
        noise = 0.0_wp
        last_sixth = 0.0_wp
        previous = 0.0_wp
        before = 0.0_wp
        do level = 0, max_levels - 1
            call line_values(ucosub, id, time, q30, par, j, count, h, center, values, error)
            if (allocated(error)) return
            do i = 1, count
                quotient(i) = dot_product(fd_weights, values(i, :))/h
                magnitude(i) = max(magnitude(i), maxval(abs(values(i, :))))
                ! this step's sixth difference and the last step's: two samples of the noise,
                ! the larger taken, so that one small by chance does not make it look small
                sixth = abs(dot_product(sixth_difference, values(i, :)))
                noise(i) = max(epsilon(1.0_wp)*magnitude(i), max(sixth, last_sixth(i)) &
                    & /sqrt(924.0_wp))
                last_sixth(i) = sixth
                scale(i) = max(abs(returned(i)), magnitude(i), output_scale(i), tiny(1.0_wp))
            end do
            if (level > 1) then
                ! the quotient at the step before this one, previous, judged by its changes
                ! from both neighbours
                do i = 1, count
                    trial = max(abs(previous(i) - before(i)), abs(quotient(i) - previous(i))) &
                        & + weights_sum*noise(i)*(1.0_wp + 0.5_wp + 0.25_wp)/h &
                        & + 8.0_wp*epsilon(1.0_wp)*scale(i)
                    if (trial < estimate(i)) then
                        best(i) = previous(i)
                        estimate(i) = trial
                        grown(i) = 0
                    else
                        grown(i) = grown(i) + 1
                    end if
                    judged(i) = abs(returned(i) - best(i)) <= options%error_multiple &
                        & *estimate(i) .and. estimate(i) < resolved_fraction*scale(i)
                end do
                if (all(judged(:count) .or. grown(:count) >= 2)) exit
            end if
            before(:count) = previous(:count)
            previous(:count) = quotient(:count)
            h = h/2.0_wp
        end do
        do i = 1, count
            if (j > 0 .and. i == 1) then
                call compare(result, options, "ARRAY (dF/dq)", j, 0, best(i), estimate(i), &
                    & returned(i), scale(i), max(magnitude(i), other_scale(i)))
            else if (j > 0) then
                call compare(result, options, "XMATRX (d2F/dq dq)", i - 1, j, best(i), &
                    & estimate(i), returned(i), scale(i), max(magnitude(i), other_scale(i)))
            else if (i == 1) then
                call compare(result, options, "SCALAR (dF/dt)", 0, 0, best(i), estimate(i), &
                    & returned(i), scale(i), max(magnitude(i), other_scale(i)))
            else if (i == 2) then
                call compare(result, options, "SCALAR (d2F/dt2)", 0, 0, best(i), estimate(i), &
                    & returned(i), scale(i), max(magnitude(i), other_scale(i)))
            else
                call compare(result, options, "ARRAY (d2F/dt dq)", i - 2, 0, best(i), &
                    & estimate(i), returned(i), scale(i), max(magnitude(i), other_scale(i)))
            end if
        end do
    end subroutine judge_line

    !> The values differenced along one line at the offsets k h, k = -3..3: along variable j
    !> (j >= 1) F and dF/dq_1..dF/dq_(count-1) at q + k h e_j; along time (j = 0) F, dF/dt
    !> and dF/dq_1..dF/dq_(count-2) at time + k h. The values at k = 0 are center.
    subroutine line_values(ucosub, id, time, q30, par, j, count, h, center, values, error)
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: id, j, count
        real(wp), intent(in) :: time, q30(max_ucon_vars), par(:), h, center(:)
        real(wp), intent(out) :: values(:, -3:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: shifted(max_ucon_vars), a(max_ucon_vars), scratch(max_ucon_vars, max_ucon_vars)
        integer :: k

        values = 0.0_wp
        values(:count, 0) = center(:count)
        do k = -3, 3
            if (k == 0) cycle
            if (j > 0) then
                shifted = q30
                shifted(j) = q30(j) + k*h
                call evaluate_ucon(ucosub, id, time, shifted, par, [scalar_value, array_dq, &
                    & xmatrx_none], values(1, k), a, scratch, error)
                if (allocated(error)) return
                values(2:count, k) = a(:count - 1)
            else
                call evaluate_ucon(ucosub, id, time + k*h, q30, par, [scalar_value, array_dq, &
                    & xmatrx_none], values(1, k), a, scratch, error)
                if (allocated(error)) return
                values(3:count, k) = a(:count - 2)
                call evaluate_ucon(ucosub, id, time + k*h, q30, par, [scalar_dt, array_none, &
                    & xmatrx_none], values(2, k), a, scratch, error)
                if (allocated(error)) return
            end if
        end do
    end subroutine line_values

    !> Compare one returned entry with its expected value (the differences' best quotient)
    !> and that quotient's estimated error (judge_line). When the allowance,
    !> options%error_multiple times the estimate, reaches checkable_fraction of the larger of
    !> the expected value and trust (the values differenced, the other entries of the output)
    !> the differences do not know the entry to a tenth (at a singularity of the routine, or
    !> where no step resolves the function): the entry is not checkable at this state, counted
    !> so, neither a finding nor a pass. Otherwise it is wrong when it differs from the
    !> expected value by more than the allowance.
    pure subroutine compare(result, options, output, row, column, expected, estimate, &
            & returned, scale, trust)
        type(ucon_check_result_type), intent(inout) :: result
        type(ucon_check_options_type), intent(in) :: options
        character(len=*), intent(in) :: output
        integer, intent(in) :: row, column
        !> The differences' value, its estimated error, the routine's value, the entry's scale
        !> (the largest of the returned entry, the values differenced, the output's entries),
        !> and the scale without the returned entry (the values differenced, the others)
        real(wp), intent(in) :: expected, estimate, returned, scale, trust
        real(wp) :: deviation, allowance

        deviation = abs(returned - expected)
        allowance = options%error_multiple*estimate
        result%compared = result%compared + 1
        if (ieee_is_finite(deviation/scale)) then
            result%worst = max(result%worst, deviation/scale)
        else
            result%worst = huge(1.0_wp)
        end if
        if (allowance >= checkable_fraction*max(abs(expected), trust, tiny(1.0_wp))) then
            result%not_checkable = result%not_checkable + 1
        else if (.not. (deviation <= allowance)) then
            call add(result, rule_derivative, output, row, column, expected, returned)
        end if
    end subroutine compare

    !> The largest |v(l)| over l /= k (0 when v has no other entry).
    pure real(wp) function largest_other(v, k) result(largest)
        real(wp), intent(in) :: v(:)
        integer, intent(in) :: k
        integer :: l

        largest = 0.0_wp
        do l = 1, size(v)
            if (l /= k) largest = max(largest, abs(v(l)))
        end do
    end function largest_other

    !> The largest |x(r, c)| over the declared n by n block but for (i, j) and (j, i).
    pure real(wp) function largest_other_entry(x, n, i, j) result(largest)
        real(wp), intent(in) :: x(:, :)
        integer, intent(in) :: n, i, j
        integer :: r, c

        largest = 0.0_wp
        do c = 1, n
            do r = 1, n
                if ((r == i .and. c == j) .or. (r == j .and. c == i)) cycle
                largest = max(largest, abs(x(r, c)))
            end do
        end do
    end function largest_other_entry

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
