! SPDX-License-Identifier: MIT
!> Names of the dataset subset and the typed reading of argument values.
!>
!> A statement name or argument keyword may be written in any case and abbreviated to any
!> prefix that is unique among the names allowed at that place (an exact name always wins).
!> Values are read strictly: one number per field, `D` after a number only where an angle is
!> expected (degrees), integers where ids are expected.
module rollcon_adm_keywords
    use rollcon_kinds, only : wp
    use rollcon_constants, only : degree
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, comma_list, place
    use rollcon_adm_lexer, only : adm_argument_type, adm_statement_type, is_number_text, &
        & is_nonfinite_text, &
        & upper_case
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: resolve_name, read_reals, read_integer, argument_key, arg_place, place
    public :: name_index, name_matches
    public :: statement_names

    !> The statements of the subset that are simulated (rollcon_adm_outputs has those read and
    !> not used)
    character(len=*), parameter :: statement_names(14) = [character(len=10) :: "ACCGRAV", &
        & "END", "GFORCE", "INTEGRATOR", "JOINT", "JPRIM", "MARKER", "OUTPUT", "PART", &
        & "SFORCE", "SIMULATE", "UCON", "UNITS", "VFORCE"]


contains

    !> The name of `allowed` that `written` stands for (exact, else a unique prefix); `what`
    !> says what is being named, for the message ("statement", "PART argument").
    subroutine resolve_name(written, allowed, what, where, resolved, error)
        character(len=*), intent(in) :: written, allowed(:), what, where
        character(len=:), allocatable, intent(out) :: resolved
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name, matches
        integer :: i, count

        name = upper_case(trim(written))
        resolved = ""
        count = 0
        matches = ""
        do i = 1, size(allowed)
            if (name == trim(allowed(i))) then
                resolved = trim(allowed(i))
                return
            end if
            if (len(name) == 0) cycle
            if (index(trim(allowed(i)), name) == 1) then
                count = count + 1
                resolved = trim(allowed(i))
                matches = matches // merge(", ", "  ", count > 1) // trim(allowed(i))
            end if
        end do
        if (count == 1) return
        if (count == 0) then
            call fatal_error(error, where // ": '" // trim(written) // "' is not " &
                & // trim(merge("an", "a ", scan(what(1:1), "AEIOaeio") > 0)) // " " // what &
                & // " of the supported subset (" // comma_list(allowed) // ")", stat_input)
        else
            call fatal_error(error, where // ": '" // trim(written) // "' is ambiguous: it may " &
                & // "be " // trim(adjustl(matches(2:))) // "; write more of the name", stat_input)
        end if
    end subroutine resolve_name

    !> How many of `allowed` the name `written` may stand for: 1 for an exact name, else the
    !> number of names it is a prefix of (any case).
    pure integer function name_matches(written, allowed)
        character(len=*), intent(in) :: written, allowed(:)
        character(len=:), allocatable :: name
        integer :: i

        name = upper_case(trim(written))
        name_matches = 0
        if (len(name) == 0) return
        if (any(allowed == name)) then
            name_matches = 1
            return
        end if
        do i = 1, size(allowed)
            if (index(trim(allowed(i)), name) == 1) name_matches = name_matches + 1
        end do
    end function name_matches

    !> The argument's values as reals: between `least` and `most` of them; angles accept `D`
    !> (degrees, converted to radians); with `factor`, converted to SI (each value finite there
    !> too). The message names the keyword and what was expected.
    subroutine read_reals(argument, where, least, most, angle, values, error, factor)
        type(adm_argument_type), intent(in) :: argument
        !> "file:line: STATEMENT/id KEYWORD"
        character(len=*), intent(in) :: where
        integer, intent(in) :: least, most
        logical, intent(in) :: angle
        real(wp), allocatable, intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        !> The value of the dataset's unit in SI (kilometre: 1000)
        real(wp), intent(in), optional :: factor
        character(len=:), allocatable :: text, expected
        integer :: i, stat, n

        expected = to_text(least) // " number" // trim(merge("s", " ", least > 1))
        if (most > least) expected = "from " // to_text(least) // " to " // to_text(most) &
            & // " numbers"
        n = 0
        if (argument%assigned) n = size(argument%values)
        if (.not. argument%assigned .or. n < least .or. n > most) then
            call fatal_error(error, where // ": expected " // expected // ", got " &
                & // to_text(n), stat_input)
            return
        end if
        allocate(values(n))
        do i = 1, n
            text = upper_case(argument%values(i)%text)
            if (is_nonfinite_text(text)) then
                call fatal_error(error, where // ": '" // argument%values(i)%text &
                    & // "' is not a finite number (expected " // expected // ")", stat_input)
                return
            end if
            if (.not. is_number_text(text)) then
                call fatal_error(error, where // ": '" // argument%values(i)%text &
                    & // "' is not a number (expected " // expected // ")", stat_input)
                return
            end if
            ! an exponent needs digits after its letter, so a final D is the degree mark
            if (text(len(text):len(text)) == "D") then
                if (.not. angle) then
                    call fatal_error(error, where // ": '" // argument%values(i)%text &
                        & // "': D (degrees) is for angles only", stat_input)
                    return
                end if
                read(text(:len(text) - 1), *, iostat=stat) values(i)
                values(i) = values(i)*degree
            else
                read(text, *, iostat=stat) values(i)
            end if
            if (stat /= 0 .or. .not. ieee_is_finite(values(i))) then
                call fatal_error(error, where // ": '" // argument%values(i)%text &
                    & // "' is not a finite number", stat_input)
                return
            end if
            if (.not. present(factor)) cycle
            values(i) = values(i)*factor
            if (.not. ieee_is_finite(values(i))) then
                call fatal_error(error, where // ": '" // argument%values(i)%text // "' is not " &
                    & // "a finite number once converted to SI (the dataset's unit is " &
                    & // to_text(factor) // " times SI's)", stat_input)
                return
            end if
        end do
    end subroutine read_reals

    !> One positive integer (an id).
    subroutine read_integer(argument, where, value, error)
        type(adm_argument_type), intent(in) :: argument
        character(len=*), intent(in) :: where
        integer, intent(out) :: value
        type(error_type), allocatable, intent(out) :: error
        integer :: stat
        character(len=:), allocatable :: text

        value = 0
        if (.not. argument%assigned) then
            call fatal_error(error, where // ": expected an id (a positive integer)", stat_input)
            return
        end if
        if (size(argument%values) /= 1) then
            call fatal_error(error, where // ": expected one id, got " &
                & // to_text(size(argument%values)) // " values", stat_input)
            return
        end if
        text = trim(argument%values(1)%text)
        stat = 1
        if (len(text) > 0 .and. len(text) < 10 .and. verify(text, "0123456789") == 0) &
            & read(text, *, iostat=stat) value
        if (stat /= 0 .or. value <= 0) then
            call fatal_error(error, where // ": expected an id (a positive integer), got '" &
                & // text // "'", stat_input)
            value = 0
        end if
    end subroutine read_integer

    !> Resolve argument k of a statement among `allowed`; refuse a keyword given twice. With
    !> `also`, a name that stands for none of `allowed` is resolved among `also` (keywords
    !> read and not used: an abbreviation keeps meaning what it meant without them).
    subroutine argument_key(path, where, statement, k, allowed, key, error, also)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        integer, intent(in) :: k
        character(len=*), intent(in) :: allowed(:)
        character(len=:), allocatable, intent(out) :: key
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: also(:)
        character(len=:), allocatable :: other
        integer :: j

        call tiered(statement%arguments(k)%keyword, arg_place(path, where, &
            & statement%arguments(k)), key)
        if (allocated(error)) return
        do j = 1, k - 1
            call tiered(statement%arguments(j)%keyword, where, other)
            if (allocated(error)) return
            if (other == key) then
                call fatal_error(error, arg_place(path, where, statement%arguments(k)) // ": " &
                    & // key // " is given twice", stat_input)
                return
            end if
        end do

    contains

        !> written resolved among allowed, else (when it stands for none of them) among also;
        !> a name of neither is refused with both lists.
        subroutine tiered(written, at, resolved)
            character(len=*), intent(in) :: written, at
            character(len=:), allocatable, intent(out) :: resolved
            character(len=32), allocatable :: both(:)
            integer :: i

            if (present(also)) then
                if (name_matches(written, allowed) == 0) then
                    if (name_matches(written, also) > 0) then
                        call resolve_name(written, also, statement_of(where) // " argument", &
                            & at, resolved, error)
                        return
                    end if
                    allocate(both(size(allowed) + size(also)))
                    both(:size(allowed)) = allowed
                    do i = 1, size(also)
                        both(size(allowed) + i) = also(i)
                    end do
                    call resolve_name(written, both, statement_of(where) // " argument", at, &
                        & resolved, error)
                    return
                end if
            end if
            call resolve_name(written, allowed, statement_of(where) // " argument", at, &
                & resolved, error)
        end subroutine tiered

    end subroutine argument_key

    !> The statement's name in "file:line: STATEMENT/id": "STATEMENT".
    pure function statement_of(where) result(name)
        character(len=*), intent(in) :: where
        character(len=:), allocatable :: name

        name = where(index(where, ": ", back=.true.) + 2:)
        if (index(name, "/") > 0) name = name(:index(name, "/") - 1)
    end function statement_of

    !> "file:line: STATEMENT/id" with the argument's own line.
    pure function arg_place(path, where, argument) result(text)
        character(len=*), intent(in) :: path, where
        type(adm_argument_type), intent(in) :: argument
        character(len=:), allocatable :: text

        text = place(path, argument%line) // where(index(where, ": ", back=.true.):)
    end function arg_place

    !> Position of `name` in `names` (0 when absent), blanks at the end ignored.
    pure integer function name_index(name, names)
        character(len=*), intent(in) :: name, names(:)
        integer :: i

        name_index = 0
        do i = 1, size(names)
            if (trim(names(i)) == trim(name)) then
                name_index = i
                return
            end if
        end do
    end function name_index

end module rollcon_adm_keywords
