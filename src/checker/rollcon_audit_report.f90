! SPDX-License-Identifier: MIT
!> The report of a UCOSUB check as readable text (the JSON report: rollcon_audit_json).
module rollcon_audit_report
    use rollcon_text, only : to_text
    use rollcon_ucosub_audit, only : user_check_report_type, ucon_report_type, finding_group_type, &
        & sampling_ranges
    use rollcon_check_rules, only : rule_order, rule_name, rule_meaning, rule_derivative, &
        & rule_symmetry, rule_velocity_linear, rule_selector_0, rule_repeat, &
        & rule_outside_block, rule_signal, rule_timeout, rule_exit, rule_finite
    use rollcon_audit_words, only : entry_label, variable_name, short, real_list
    implicit none
    private

    public :: report_text

    character(len=*), parameter :: nl = new_line("a")
    !> Outputs in the order the text report lists them (lower orders first)
    character(len=24), parameter :: output_order(10) = [character(len=24) :: "UCOVAR", &
        & "ERRMES", "all outputs", "SCALAR", "SCALAR (dF/dt)", "SCALAR (d2F/dt2)", &
        & "ARRAY", "ARRAY (dF/dq)", "ARRAY (d2F/dt dq)", "XMATRX (d2F/dq dq)"]

contains

    !> The whole report: what was checked, per UCON its declaration and grouped findings, and
    !> a closing verdict line.
    function report_text(report, source, library) result(text)
        !> What the check found
        type(user_check_report_type), intent(in) :: report
        !> The user's file
        character(len=*), intent(in) :: source
        !> Where it was built, and whether from the cache (free text)
        character(len=*), intent(in) :: library
        character(len=:), allocatable :: text
        character(len=80) :: ranges(4)
        integer :: k, failing, i

        ranges = sampling_ranges()
        text = "rollcon check: " // source // nl // "  loaded from " // library // nl &
            & // "  " // to_text(report%options%states) // " random states per UCON, seed " &
            & // to_text(report%options%seed) // ":" // nl
        do i = 1, size(ranges)
            text = text // "    " // trim(ranges(i)) // nl
        end do
        failing = 0
        do k = 1, size(report%ucons)
            text = text // nl // ucon_text(report%ucons(k))
            if (size(report%ucons(k)%groups) > 0) failing = failing + 1
        end do
        text = text // nl
        if (failing == 0) then
            text = text // "verdict: CLEAN: " // to_text(size(report%ucons)) // " UCON(s) " &
                & // "checked, no mismatch"
        else
            text = text // "verdict: MISMATCHES in " // to_text(failing) // " of " &
                & // to_text(size(report%ucons)) // " UCON(s), " // to_text(report%findings()) &
                & // " finding(s) in " // to_text(group_count(report)) // " group(s)"
        end if
    end function report_text

    !> One UCON's part of the text report.
    function ucon_text(ucon) result(text)
        type(ucon_report_type), intent(in) :: ucon
        character(len=:), allocatable :: text
        integer :: i, g, r, o
        character(len=16) :: worst

        ! the statement as its dataset names it (its line, its ROUTINE), else UCON/id
        if (allocated(ucon%statement)) then
            text = ucon%statement
        else
            text = "UCON/" // to_text(ucon%id)
        end if
        if (size(ucon%par) > 0) then
            text = text // "  PAR = " // real_list(ucon%par, ", ") // nl
        else
            text = text // "  PAR: none (NPAR = 0)" // nl
        end if
        if (ucon%declared) then
            text = text // "  UCOVAR: " // to_text(size(ucon%codes)) // " variables:"
            do i = 1, size(ucon%codes)
                text = text // " " // variable_name(ucon, i)
            end do
            write(worst, '(es10.2e3)') ucon%worst
            text = text // nl // "  " // to_text(ucon%states) // " states, " &
                & // to_text(ucon%compared) // " entries compared, largest relative deviation " &
                & // trim(adjustl(worst))
            if (ucon%not_checkable > 0) text = text // "; " // to_text(ucon%not_checkable) &
                & // " entries not checkable here (the differences do not know them to a " &
                & // "tenth: a singularity of the routine near the state)"
        else if (process_ended(ucon)) then
            text = text // "  the check of this UCON ended with its process (below)"
        else
            text = text // "  UCOVAR: no valid declaration, so no state was checked"
        end if
        if (size(ucon%groups) == 0) then
            text = text // ": clean" // nl
            return
        end if
        text = text // nl // "  " // to_text(size(ucon%groups)) // " kind(s) of finding:" // nl
        do r = 1, size(rule_order)
            if (.not. any(ucon%groups%code == rule_order(r))) cycle
            text = text // "  [" // rule_name(rule_order(r)) // "] " &
                & // rule_meaning(rule_order(r)) // nl
            do o = 1, size(output_order)
                do g = 1, size(ucon%groups)
                    if (ucon%groups(g)%code /= rule_order(r)) cycle
                    if (output_rank(ucon%groups(g)%output) /= o) cycle
                    text = text // group_text(ucon, ucon%groups(g))
                end do
            end do
        end do
    end function ucon_text

    !> Rank of an output in the order findings are listed (lower orders first).
    pure function output_rank(output) result(rank)
        character(len=*), intent(in) :: output
        integer :: rank

        rank = findloc(output_order == output, .true., dim=1)
        if (rank == 0) rank = size(output_order)
    end function output_rank

    !> One line per group: entry, in how many states, the worst case.
    function group_text(ucon, group) result(text)
        type(ucon_report_type), intent(in) :: ucon
        type(finding_group_type), intent(in) :: group
        character(len=:), allocatable :: text

        text = "    " // entry_label(ucon, group)
        if (is_process_rule(group%code)) then
            ! the message names the call, the state and what happened
            text = "    " // worst_text(ucon, group) // nl
        else if (group%state > 0) then
            text = text // ": " // to_text(group%count) // " of " // to_text(ucon%states) &
                & // " states; worst at state " // to_text(group%state) // " (t = " &
                & // short(group%time) // " s): " // worst_text(ucon, group) // nl
        else
            text = text // ": " // worst_text(ucon, group) // nl
        end if
    end function group_text

    !> True when the check of ucon ended with its process (a crash, a timeout, a STOP).
    pure function process_ended(ucon) result(ended)
        type(ucon_report_type), intent(in) :: ucon
        logical :: ended
        integer :: g

        ended = .false.
        do g = 1, size(ucon%groups)
            ended = ended .or. is_process_rule(ucon%groups(g)%code)
        end do
    end function process_ended

    !> True for the rules of a child process's end.
    elemental function is_process_rule(code) result(is_process)
        integer, intent(in) :: code
        logical :: is_process

        is_process = code == rule_signal .or. code == rule_timeout .or. code == rule_exit
    end function is_process_rule

    !> The worst case of a group in words.
    function worst_text(ucon, group) result(text)
        type(ucon_report_type), intent(in) :: ucon
        type(finding_group_type), intent(in) :: group
        character(len=:), allocatable :: text

        select case (group%code)
        case (rule_derivative)
            text = "returned " // short(group%returned) // ", differences give " &
                & // short(group%expected)
        case (rule_symmetry)
            text = "returned " // short(group%returned) // ", its mirror XMATRX(" &
                & // to_text(group%column) // "," // to_text(group%row) // ") holds " &
                & // short(group%expected)
        case (rule_velocity_linear)
            text = "returned " // short(group%returned) // ", must be 0"
        case (rule_selector_0)
            text = "the routine wrote " // short(group%returned) // " there"
        case (rule_repeat)
            text = "F = " // short(group%expected) // " then " // short(group%returned)
        case (rule_finite)
            if (allocated(group%message)) then
                text = group%message
            else
                text = "returned " // short(group%returned) // ", beyond the largest " &
                    & // "magnitude the check accepts (" // short(group%expected) // ")"
            end if
        case (rule_outside_block)
            if (allocated(group%message)) then
                text = group%message
            else
                text = "returned " // short(group%returned) // " with only " &
                    & // to_text(size(ucon%codes)) // " variables declared"
            end if
        case default
            text = "(no message)"
            if (allocated(group%message)) text = group%message
        end select
    end function worst_text

    !> Finding groups over every UCON of the report.
    pure function group_count(report) result(count)
        type(user_check_report_type), intent(in) :: report
        integer :: count
        integer :: k

        count = 0
        do k = 1, size(report%ucons)
            count = count + size(report%ucons(k)%groups)
        end do
    end function group_count

end module rollcon_audit_report
