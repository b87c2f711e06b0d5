! SPDX-License-Identifier: MIT
!> Words and numbers shared by the text and JSON reports of a UCOSUB check: the entry of a
!> finding with its variables' names, and numbers for reading or for JSON.
module rollcon_audit_words
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : code_name
    use rollcon_ucosub_audit, only : ucon_report_type, finding_group_type
    use rollcon_check_rules, only : rule_declaration, rule_outside_block, rule_changed_argument
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: entry_label, variable_name, short, number, real_list

contains

    !> The entry of a finding, with the names of its variables: "XMATRX(5,4) = d2F/d(theta)
    !> d(psi)", "ARRAY(4) = dF/d(psi)", "SCALAR (dF/dt)", "UCOVAR".
    function entry_label(ucon, group) result(label)
        !> The UCON (for the variable names)
        type(ucon_report_type), intent(in) :: ucon
        !> The finding
        type(finding_group_type), intent(in) :: group
        character(len=:), allocatable :: label

        label = group%output
        if (group%code == rule_changed_argument) then
            ! the argument and its entry: "PAR(10)", "ID"
            if (group%row > 0) label = group%output // "(" // to_text(group%row) // ")"
            return
        end if
        if (group%code == rule_outside_block .and. (group%output == "ARRAY" &
            & .or. group%output == "XMATRX")) then
            ! the guard's finding: the index written (0 included), which has no variable name
            label = group%output // "(" // to_text(group%row)
            if (group%output == "XMATRX") label = label // "," // to_text(group%column)
            label = label // ")"
            return
        end if
        if (group%row == 0 .or. group%code == rule_declaration) return
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

    !> A JSON number: the shortest text that reads back, or null when not finite.
    pure function number(value) result(json)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: json

        if (ieee_is_finite(value)) then
            json = to_text(value)
        else
            json = "null"
        end if
    end function number

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

end module rollcon_audit_words
