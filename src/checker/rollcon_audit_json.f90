! SPDX-License-Identifier: MIT
!> The report of a UCOSUB check as a JSON document.
module rollcon_audit_json
    use rollcon_text, only : to_text
    use rollcon_error, only : error_type
    use rollcon_output_files, only : write_text_file, delete_file
    use rollcon_ucosub_audit, only : user_check_report_type, ucon_report_type, finding_group_type, &
        & sampling_ranges
    use rollcon_check_rules, only : rule_name
    use rollcon_audit_words, only : entry_label, variable_name, number, real_list
    implicit none
    private

    public :: report_json, write_report_json

    character(len=*), parameter :: nl = new_line("a")

contains

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
            & // to_text(report%options%seed) // ', "error_multiple": ' &
            & // number(report%options%compare%error_multiple) // ', "ranges": ['
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

    !> Write report_json to a file (replaced). Every write and the close are checked through
    !> the C library (gfortran 12 reports no full disk): a report that did not reach the disk
    !> whole is an error naming the file and the reason, and the cut file is removed.
    subroutine write_report_json(path, report, source, library, from_cache, error)
        !> File to write
        character(len=*), intent(in) :: path
        !> What the check found
        type(user_check_report_type), intent(in) :: report
        !> The user's file and the library built from it
        character(len=*), intent(in) :: source, library
        !> Whether the library came from the cache
        logical, intent(in) :: from_cache
        !> Set when the file cannot be written whole
        type(error_type), allocatable, intent(out) :: error

        type(error_type), allocatable :: ignored

        call write_text_file(path, report_json(report, source, library, from_cache), error)
        if (.not. allocated(error)) return
        error%message = "the JSON report was not written: " // error%message
        ! what reached the disk is a cut document, which no reader should take for the report
        call delete_file(path, ignored)
    end subroutine write_report_json

    !> One UCON's object of the JSON report.
    function ucon_json(ucon) result(json)
        type(ucon_report_type), intent(in) :: ucon
        character(len=:), allocatable :: json
        integer :: g, i

        json = '  {"id": ' // to_text(ucon%id)
        ! the statement as its dataset names it, when the UCON came from one (--model)
        if (allocated(ucon%statement)) json = json // ', "statement": ' &
            & // json_string(ucon%statement)
        json = json // ', "par": [' // real_list(ucon%par, ",") // '], "declared": ' &
            & // logical_json(ucon%declared)
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
            & // to_text(ucon%compared) // ', "not_checkable": ' // to_text(ucon%not_checkable) &
            & // ', "worst_relative_deviation": ' // number(ucon%worst) // ', "groups": ['
        do g = 1, size(ucon%groups)
            if (g > 1) json = json // ','
            json = json // nl // group_json(ucon, ucon%groups(g))
        end do
        json = json // ']}'
    end function ucon_json

    !> One finding group's object of the JSON report.
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

    !> A JSON literal true or false.
    pure function logical_json(value) result(json)
        logical, intent(in) :: value
        character(len=:), allocatable :: json

        json = merge("true ", "false", value)
        json = trim(json)
    end function logical_json

    !> Integers separated by commas.
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

end module rollcon_audit_json
