! SPDX-License-Identifier: MIT
!> Names of the dataset subset and the typed reading of argument values.
!>
!> A statement name or argument keyword may be written in any case and abbreviated as ADAMS
!> abbreviates it: to any beginning at least as long as the name's shortest form in ADAMS's
!> table (rollcon_adm_abbreviations; an exact name always wins). Choice values (unit names,
!> INTEGRATOR's choices) may be abbreviated to any beginning unique among the values allowed.
!> Values are read strictly: one number per field, `D` after a number only where an angle is
!> expected (degrees), integers where ids are expected.
module rollcon_adm_keywords
    use rollcon_kinds, only : wp
    use rollcon_constants, only : degree
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, comma_list, place, decimal_value
    use rollcon_adm_lexer, only : adm_argument_type, adm_statement_type, is_number_text, &
        & is_nonfinite_text, &
        & upper_case
    use rollcon_adm_abbreviations, only : minimum_abbreviation
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: resolve_name, resolve_keyword, read_reals, read_integer, argument_key, arg_place
    public :: place, name_index, argument_text
    public :: statement_names

    !> The statements of the subset that are simulated (rollcon_adm_outputs has those read and
    !> not used)
    character(len=*), parameter :: statement_names(29) = [character(len=12) :: "ACCGRAV", &
        & "ARRAY", "BUSHING", "CONTACT", "COUPLER", "DIFF", "END", "GCON", "GEAR", "GFORCE", &
        & "INTEGRATOR", "JOINT", "JPRIM", &
        & "MARKER", "MOTION", "OUTPUT", "PART", "PINPUT", "POUTPUT", "SFORCE", "SIMULATE", &
        & "SPLINE", "SPRINGDAMPER", "STRING", "UCON", "UNITS", "VARIABLE", "VFORCE", &
        & "VTORQUE"]


contains

    !> The choice value of `allowed` that `written` stands for (a unit name, an INTEGRATOR
    !> choice: exact, else a unique beginning); `what` says what is being named, for the
    !> message ("force unit", "method"). Statement names and keywords: resolve_keyword.
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

    !> The name of `allowed` that `written` stands for at `table_place` (a place of
    !> rollcon_adm_abbreviations: "statement", "command", or a statement's name for its
    !> arguments): the exact name, else the one name of which it is a beginning at least as
    !> long as that name's shortest form. `what` says what is being named, for the message
    !> ("statement", "PART argument"). Refused: a word that begins names only shorter than
    !> their shortest forms (with those forms), a word of no name (with the list), and, were
    !> the table to allow it, a word that two names take.
    subroutine resolve_keyword(written, allowed, table_place, what, where, resolved, error)
        character(len=*), intent(in) :: written, allowed(:), table_place, what, where
        character(len=:), allocatable, intent(out) :: resolved
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name, matches, short
        integer :: i, count, minimum, shorts

        name = upper_case(trim(written))
        resolved = ""
        do i = 1, size(allowed)
            if (name == trim(allowed(i))) then
                resolved = trim(allowed(i))
                return
            end if
        end do
        count = 0
        shorts = 0
        matches = ""
        short = ""
        do i = 1, size(allowed)
            minimum = minimum_abbreviation(table_place, trim(allowed(i)))
            if (minimum < 0) then
                call fatal_error(error, where // ": internal error: " // trim(allowed(i)) &
                    & // " has no shortest form at " // trim(table_place) // " in the table " &
                    & // "of rollcon_adm_abbreviations", stat_input)
                return
            end if
            if (len(name) == 0) cycle
            if (index(trim(allowed(i)), name) /= 1) cycle
            if (len(name) >= minimum) then
                count = count + 1
                resolved = trim(allowed(i))
                matches = matches // merge(", ", "  ", count > 1) // trim(allowed(i))
            else
                shorts = shorts + 1
                short = short // merge(", ", "  ", shorts > 1) // trim(allowed(i)(:minimum)) &
                    & // " for " // trim(allowed(i))
            end if
        end do
        if (count == 1) return
        resolved = ""
        if (count > 1) then
            call fatal_error(error, where // ": '" // trim(written) // "' is ambiguous: it may " &
                & // "be " // trim(adjustl(matches(2:))) // "; write more of the name", stat_input)
        else if (shorts > 0) then
            call fatal_error(error, where // ": '" // trim(written) // "' is too short an " &
                & // "abbreviation of " // article(what) // " " // what // ": the shortest " &
                & // "ADAMS takes " &
                & // trim(merge("is ", "are", shorts == 1)) // " " // trim(adjustl(short(2:))) &
                & // " (docs/datasets.md, Abbreviations)", stat_input)
        else
            call fatal_error(error, where // ": '" // trim(written) // "' is not " &
                & // article(what) // " " // what // " of the supported subset (" &
                & // comma_list(allowed) // ")", stat_input)
        end if
    end subroutine resolve_keyword

    !> "a" or "an" before `what` ("a PART argument", "an SFORCE argument", "an INTEGRATOR
    !> argument"): ADAMS's names are said as words, but SFORCE and MREQUEST by their first
    !> letter.
    pure function article(what) result(word)
        character(len=*), intent(in) :: what
        character(len=:), allocatable :: word

        word = "a"
        if (len(what) == 0) return
        if (scan(what(1:1), "AEIOaeio") > 0 .or. index(what, "SFORCE") == 1 .or. &
            & index(what, "MREQUEST") == 1) word = "an"
    end function article

    !> An argument's values as one text, separated by blanks: an expression continued on
    !> comma lines at any depth (ADAMS reads it to a backslash or to the statement's end, the
    !> commas that begin its lines dropped), or a value of one field as written.
    pure function argument_text(argument) result(text)
        type(adm_argument_type), intent(in) :: argument
        character(len=:), allocatable :: text
        integer :: i

        text = ""
        if (.not. argument%assigned) return
        do i = 1, size(argument%values)
            if (i > 1) text = text // " "
            text = text // trim(adjustl(argument%values(i)%text))
        end do
    end function argument_text

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
        integer :: i, n
        logical :: whole

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
                call decimal_value(text(:len(text) - 1), values(i), whole)
                values(i) = values(i)*degree
            else
                call decimal_value(text, values(i), whole)
            end if
            if (.not. whole .or. .not. ieee_is_finite(values(i))) then
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

    !> Resolve argument k of a statement among `allowed` by ADAMS's shortest forms at the
    !> statement (rollcon_adm_abbreviations); refuse a keyword given twice. With `also`, the
    !> names of `also` (keywords read and not used) are allowed too.
    subroutine argument_key(path, where, statement, k, allowed, key, error, also)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        integer, intent(in) :: k
        character(len=*), intent(in) :: allowed(:)
        character(len=:), allocatable, intent(out) :: key
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: also(:)
        type(error_type), allocatable :: earlier
        character(len=32), allocatable :: names(:)
        character(len=:), allocatable :: other, statement_name
        integer :: j

        allocate(names(size(allowed)))
        names = allowed
        if (present(also)) names = [character(len=32) :: names, also]
        statement_name = statement_of(where)
        call resolve_keyword(statement%arguments(k)%keyword, names, statement_name, &
            & statement_name // " argument", arg_place(path, where, statement%arguments(k)), &
            & key, error)
        if (allocated(error)) return
        do j = 1, k - 1
            ! an earlier keyword that names nothing is another message's (or the warning's)
            call resolve_keyword(statement%arguments(j)%keyword, names, statement_name, &
                & statement_name // " argument", where, other, earlier)
            if (allocated(earlier)) then
                deallocate(earlier)
                cycle
            end if
            if (other == key) then
                call fatal_error(error, arg_place(path, where, statement%arguments(k)) // ": " &
                    & // key // " is given twice", stat_input)
                return
            end if
        end do
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
