! SPDX-License-Identifier: MIT
!> The report of a UCOSUB check as readable text and as JSON.
module rollcon_audit_report
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : code_name
    use rollcon_ucosub_audit, only : user_check_report_type, ucon_report_type, finding_group_type, &
        & sampling_ranges
    use rollcon_check_rules, only : rule_order, rule_name, rule_meaning, rule_declaration, &
        & rule_derivative, rule_symmetry, rule_velocity_linear, rule_selector_0, rule_repeat, &
        & rule_outside_block, rule_signal, rule_timeout, rule_exit
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: report_text, report_json, entry_label

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

        text = "UCON/" // to_text(ucon%id) // "  PAR = " // real_list(ucon%par, ", ") // nl
        if (ucon%declared) then
            text = text // "  UCOVAR: " // to_text(size(ucon%codes)) // " variables:"
            do i = 1, size(ucon%codes)
                text = text // " " // variable_name(ucon, i)
            end do
            write(worst, '(es9.2)') ucon%worst
            text = text // nl // "  " // to_text(ucon%states) // " states, " &
                & // to_text(ucon%compared) // " entries compared, largest relative deviation " &
                & // trim(adjustl(worst))
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

    !> The entry of a finding, with the names of its variables: "XMATRX(5,4) = d2F/d(theta)
    !> d(psi)", "ARRAY(4) = dF/d(psi)", "SCALAR (dF/dt)", "UCOVAR".
    function entry_label(ucon, group) result(label)
        !> The UCON (for the variable names)
        type(ucon_report_type), intent(in) :: ucon
        !> The finding
        type(finding_group_type), intent(in) :: group
        character(len=:), allocatable :: label

        label = group%output
        if (group%row == 0 .or. group%code == rule_declaration) return
        if (group%code == rule_outside_block .and. (group%output == "ARRAY" &
            & .or. group%output == "XMATRX")) then
            ! the guard's finding: the index written, which has no variable name
            label = group%output // "(" // to_text(group%row)
            if (group%output == "XMATRX") label = label // "," // to_text(group%column)
            label = label // ")"
            return
        end if
        select case (group%output)
        case ("ARRAY (dF/dq)", "ARRAY")
            label = "ARRAY(" // to_text(group%row) // ") = dF/d(" &
                & // variable_name(ucon, group%row) // ")"
        case ("ARRAY (d2F/dt dq)")
            label = "ARRAY(" // to_text(group%row) // ") = d2F/dt d(" &
                & // variable_name(ucon, group%row) // ")"
        case ("XMATRX (d2F/dq dq)", "XMATRX")
            label = "XMATRX(" // to_text(group%row) // "," // to_text(group%column) &
                & // ") = d2F/d(" // variable_name(ucon, group%row) // ") d(" &
                & // variable_name(ucon, group%column) // ")"
        end select
    end function entry_label

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

    !> Code name of variable i, with its part when the UCON spans several parts.
    function variable_name(ucon, i) result(name)
        type(ucon_report_type), intent(in) :: ucon
        integer, intent(in) :: i
        character(len=:), allocatable :: name

        if (.not. allocated(ucon%codes)) then
            name = "q" // to_text(i)
        else if (i < 1 .or. i > size(ucon%codes)) then
            name = "q" // to_text(i)
        else
            name = code_name(ucon%codes(i))
            if (any(ucon%parts /= ucon%parts(1))) name = name // "@" // to_text(ucon%parts(i))
        end if
    end function variable_name

    !> The report as a JSON document (non-finite numbers as null).
    function report_json(report, source, library, from_cache) result(json)
        !> What the check found
        type(user_check_report_type), intent(in) :: report
        !> The user's file and the library built from it
        character(len=*), intent(in) :: source, library
        !> Whether the library came from the cache
        logical, intent(in) :: from_cache
        character(len=:), allocatable :: json
        character(len=80) :: ranges(4)
        integer :: k, i

        ranges = sampling_ranges()
        json = '{"file": ' // json_string(source) // ', "library": ' // json_string(library) &
            & // ', "from_cache": ' // logical_json(from_cache) // ',' // nl &
            & // ' "states": ' // to_text(report%options%states) // ', "seed": ' &
            & // to_text(report%options%seed) // ', "rel_tol": ' &
            & // number(report%options%compare%rel_tol) // ', "ranges": ['
        do i = 1, size(ranges)
            if (i > 1) json = json // ", "
            json = json // json_string(trim(ranges(i)))
        end do
        json = json // '],' // nl // ' "clean": ' // logical_json(report%clean()) &
            & // ', "findings": ' // to_text(report%findings()) // ',' // nl // ' "ucons": ['
        do k = 1, size(report%ucons)
            if (k > 1) json = json // ','
            json = json // nl // ucon_json(report%ucons(k))
        end do
        json = json // nl // ' ]' // nl // '}'
    end function report_json

    function ucon_json(ucon) result(json)
        type(ucon_report_type), intent(in) :: ucon
        character(len=:), allocatable :: json
        integer :: g, i

        json = '  {"id": ' // to_text(ucon%id) // ', "par": [' // real_list(ucon%par, ",") &
            & // '], "declared": ' // logical_json(ucon%declared)
        if (ucon%declared) then
            json = json // ', "parts": [' // integer_list(ucon%parts) // '], "codes": [' &
                & // integer_list(ucon%codes) // '], "names": ['
            do i = 1, size(ucon%codes)
                if (i > 1) json = json // ', '
                json = json // json_string(variable_name(ucon, i))
            end do
            json = json // ']'
        end if
        json = json // ',' // nl // '   "states": ' // to_text(ucon%states) // ', "compared": ' &
            & // to_text(ucon%compared) // ', "worst_relative_deviation": ' // number(ucon%worst) &
            & // ', "groups": ['
        do g = 1, size(ucon%groups)
            if (g > 1) json = json // ','
            json = json // nl // group_json(ucon, ucon%groups(g))
        end do
        json = json // ']}'
    end function ucon_json

    function group_json(ucon, group) result(json)
        type(ucon_report_type), intent(in) :: ucon
        type(finding_group_type), intent(in) :: group
        character(len=:), allocatable :: json

        json = '    {"rule": ' // json_string(rule_name(group%code)) // ', "code": ' &
            & // to_text(group%code) // ', "output": ' // json_string(group%output) &
            & // ', "row": ' // to_text(group%row) // ', "column": ' // to_text(group%column) &
            & // ', "entry": ' // json_string(entry_label(ucon, group)) // ', "count": ' &
            & // to_text(group%count) // ',' // nl // '     "worst": {"state": ' &
            & // to_text(group%state) // ', "time": ' // number(group%time) // ', "expected": ' &
            & // number(group%expected) // ', "returned": ' // number(group%returned)
        if (allocated(group%q)) json = json // ', "q": [' // real_list(group%q, ",") // ']'
        if (allocated(group%message)) json = json // ', "message": ' // json_string(group%message)
        json = json // '}}'
    end function group_json

    !> Six significant digits, for reading (the JSON report has every digit).
    pure function short(value) result(text)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        real(wp) :: rounded
        integer :: shift

        if (value == 0.0_wp .or. .not. ieee_is_finite(value)) then
            text = to_text(value)
            return
        end if
        shift = 5 - floor(log10(abs(value)))
        ! An integer over an exact power of ten rounds to the nearest double of the decimal,
        ! whose shortest text is that decimal.
        if (shift >= 0 .and. shift <= 22) then
            rounded = real(nint(value*10.0_wp**shift, kind=int64), wp) / 10.0_wp**shift
        else if (shift < 0 .and. shift >= -22) then
            rounded = real(nint(value/10.0_wp**(-shift), kind=int64), wp) * 10.0_wp**(-shift)
        else
            rounded = value
        end if
        text = to_text(rounded)
    end function short

    !> JSON string: quotes, backslashes and control characters escaped.
    pure function json_string(text) result(json)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: json
        character(len=*), parameter :: hex = "0123456789abcdef"
        integer :: i, code

        json = '"'
        do i = 1, len(text)
            code = iachar(text(i:i))
            select case (code)
            case (34, 92)
                json = json // "\" // text(i:i)
            case (10)
                json = json // "\n"
            case (0:9, 11:31)
                json = json // "\u00" // hex(code/16 + 1:code/16 + 1) &
                    & // hex(mod(code, 16) + 1:mod(code, 16) + 1)
            case default
                json = json // text(i:i)
            end select
        end do
        json = json // '"'
    end function json_string

    pure function number(value) result(json)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: json

        if (ieee_is_finite(value)) then
            json = to_text(value)
        else
            json = "null"
        end if
    end function number

    pure function logical_json(value) result(json)
        logical, intent(in) :: value
        character(len=:), allocatable :: json

        json = merge("true ", "false", value)
        json = trim(json)
    end function logical_json

    !> Values separated by separator: "," gives JSON numbers, anything else plain text.
    pure function real_list(values, separator) result(text)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: separator
        character(len=:), allocatable :: text
        integer :: i

        text = ""
        do i = 1, size(values)
            if (i > 1) text = text // separator
            if (separator == ",") then
                text = text // number(values(i))
            else
                text = text // to_text(values(i))
            end if
        end do
    end function real_list

    pure function integer_list(values) result(text)
        integer, intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: i

        text = ""
        do i = 1, size(values)
            if (i > 1) text = text // ","
            text = text // to_text(values(i))
        end do
    end function integer_list

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
