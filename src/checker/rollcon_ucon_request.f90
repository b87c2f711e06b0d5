! SPDX-License-Identifier: MIT
!> The UCON statements the checker takes: those of a dataset that its model's UCOSUB serves
!> (`rollcon check --model`), and one written as "ID:PAR1,PAR2,..." (`rollcon check --ucon`), read
!> strictly: a positive integer id, then one decimal number per comma-separated field. (The
!> option itself is the program's; the text's format and its checks are the checker's, so that
!> they are tested and fuzzed in the library.) Fortran's list-directed read is not
!> used on the list: it takes "2*1" as two ones, ";" and "/" as separators or terminators
!> and an empty field as "leave unchanged". Messages quote the text with its control and
!> non-ASCII characters shown visibly (`\x1B`, `U+00E9`); a list is refused at its 31st field,
!> however long it is.
module rollcon_ucon_request
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : max_ucon_par
    use rollcon_ucosub_units, only : ucosub_units_type
    use rollcon_model, only : served_by_model_ucosub
    use rollcon_ucosub_audit, only : ucon_request_type
    use rollcon_namelist_bytes, only : visible
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: read_ucon_request, is_decimal_number, dataset_ucon_requests

contains

    !> The UCON statements of the dataset at path that the model's UCOSUB serves (those naming
    !> no ROUTINE: rollcon_model's served_by_model_ucosub), with their ids, PAR and the
    !> dataset's units, appended to requests. note: a line saying the routine is called in the
    !> dataset's units when they are not SI ("" otherwise). Refused: a dataset the reader
    !> refuses, or one whose every UCON names its ROUTINE (nothing to check).
    subroutine dataset_ucon_requests(path, requests, note, error)
        character(len=*), intent(in) :: path
        type(ucon_request_type), allocatable, intent(inout) :: requests(:)
        character(len=:), allocatable, intent(out) :: note
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(ucon_request_type) :: request
        integer :: k, found

        note = ""
        ! the check runs no simulation: a dataset without SIMULATE (run from an ADAMS command
        ! file) is checked as it is
        call read_adm(path, adm, error, run_given=.true.)
        if (allocated(error)) return
        found = 0
        ! the routine computes in the dataset's units, as in a run
        request%units = ucosub_units_type(length=adm%units%length, time=adm%units%time)
        do k = 1, size(adm%ucons)
            if (.not. served_by_model_ucosub(adm%ucons(k)%routine)) cycle
            request%id = adm%ucons(k)%id
            request%par = adm%ucons(k)%par
            requests = [requests, request]
            found = found + 1
        end do
        if (found > 0 .and. .not. request%units%is_si()) note = path // ": the routine is " &
            & // "called in the dataset's units, as in a run: lengths in " &
            & // to_text(request%units%length) // " m, time in " // to_text(request%units%time) &
            & // " s; PAR as written, each random state drawn in the ranges below and converted"
        if (found == 0) call fatal_error(error, path // ": no UCON statement is served by the " &
            & // "model's UCOSUB (each names a built-in ROUTINE): nothing to check", stat_input)
    end subroutine dataset_ucon_requests

    !> "ID:PAR1,PAR2,..." (or "ID" alone) as a UCON id and its constants.
    subroutine read_ucon_request(text, request, error)
        !> The statement's text
        character(len=*), intent(in) :: text
        !> The UCON statement
        type(ucon_request_type), intent(out) :: request
        !> Set when the id is not a positive integer or a field is not one finite number
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: id_text, field, quoted
        integer :: colon, stat, start, finish, k

        quoted = "--ucon '" // visible(text) // "': "
        colon = index(text, ":")
        if (colon == 0) colon = len(text) + 1
        id_text = trim(adjustl(text(:colon - 1)))
        stat = 1
        if (len(id_text) > 0 .and. len(id_text) <= 9 .and. verify(id_text, "0123456789") == 0) &
            & read(id_text, *, iostat=stat) request%id
        if (stat /= 0 .or. request%id < 1) then
            call fatal_error(error, quoted // "the UCON id must be a positive integer (digits " &
                & // "only), got '" // visible(id_text) // "'; expected ID:PAR1,PAR2,...", &
                & stat_input)
            return
        end if
        allocate(request%par(0))
        if (colon >= len(text)) then
            if (colon == len(text)) call fatal_error(error, quoted // "nothing after ':'; give " &
                & // "the constants (ID:PAR1,PAR2,...) or the id alone", stat_input)
            return
        end if
        start = colon + 1
        k = 0
        do
            finish = index(text(start:), ",")
            if (finish == 0) then
                finish = len(text)
            else
                finish = start + finish - 2
            end if
            k = k + 1
            if (k > max_ucon_par) then
                call fatal_error(error, quoted // "more than " // to_text(max_ucon_par) &
                    & // " constants (PAR(" // to_text(k) // ") is given); at most " &
                    & // to_text(max_ucon_par), stat_input)
                return
            end if
            field = trim(adjustl(text(start:finish)))
            call read_field(quoted, k, field, request%par, error)
            if (allocated(error)) return
            if (finish >= len(text)) exit
            start = finish + 2
            if (start > len(text)) then
                call fatal_error(error, quoted // "PAR(" // to_text(k + 1) // ") is empty (a " &
                    & // "trailing comma); one number per field", stat_input)
                return
            end if
        end do
    end subroutine read_ucon_request

    !> Field k of the list as one finite number, appended to par.
    subroutine read_field(quoted, k, field, par, error)
        !> "--ucon 'TEXT': ", the start of a message
        character(len=*), intent(in) :: quoted
        character(len=*), intent(in) :: field
        integer, intent(in) :: k
        real(wp), allocatable, intent(inout) :: par(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value
        integer :: stat

        stat = 1
        if (is_decimal_number(field)) read(field, *, iostat=stat) value
        if (stat == 0) then
            if (.not. ieee_is_finite(value)) stat = 1
        end if
        if (stat /= 0) then
            call fatal_error(error, quoted // "PAR(" // to_text(k) // ") must be one finite " &
                & // "decimal number (such as 21, -0.5 or 1.0e-3), got '" // visible(field) &
                & // "'; fields are separated by commas", stat_input)
            return
        end if
        par = [par, value]
    end subroutine read_field

    !> True for [sign] digits [. digits] [e|E [sign] digits] with at least one mantissa digit,
    !> and nothing else (no blanks, repeat counts, separators, D exponents, inf or nan).
    pure function is_decimal_number(text) result(valid)
        !> Candidate text
        character(len=*), intent(in) :: text
        logical :: valid
        integer :: i, mantissa_digits, exponent_digits

        valid = .false.
        i = 1
        if (len(text) == 0) return
        if (scan(text(1:1), "+-") == 1) i = 2
        mantissa_digits = 0
        do while (i <= len(text))
            if (verify(text(i:i), "0123456789") /= 0) exit
            mantissa_digits = mantissa_digits + 1
            i = i + 1
        end do
        if (i <= len(text)) then
            if (text(i:i) == ".") then
                i = i + 1
                do while (i <= len(text))
                    if (verify(text(i:i), "0123456789") /= 0) exit
                    mantissa_digits = mantissa_digits + 1
                    i = i + 1
                end do
            end if
        end if
        if (mantissa_digits == 0) return
        if (i <= len(text)) then
            if (scan(text(i:i), "eE") /= 1) return
            i = i + 1
            if (i <= len(text)) then
                if (scan(text(i:i), "+-") == 1) i = i + 1
            end if
            exponent_digits = 0
            do while (i <= len(text))
                if (verify(text(i:i), "0123456789") /= 0) return
                exponent_digits = exponent_digits + 1
                i = i + 1
            end do
            if (exponent_digits == 0) return
        end if
        valid = .true.
    end function is_decimal_number

end module rollcon_ucon_request
