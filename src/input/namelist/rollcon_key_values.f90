! SPDX-License-Identifier: MIT
!> Converts the text of each `key = value` of a scene file to its key's kind, checks it
!> against the key's range or choices, and stores it in the scene: one pass, no namelist read.
module rollcon_key_values
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : group_type, assignment_type, to_lower
    use rollcon_keys, only : key_type, find_key, key_list, kind_real, kind_integer, &
        & kind_logical, kind_choice
    use rollcon_namelist_bytes, only : visible
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: store_values, range_text, in_range, choice_text, is_real_text

contains

    !> Every assignment must name a key of its group and hold a value of the key's kind within
    !> its range; the values are stored through the table's pointers.
    subroutine store_values(path, groups, keys, error)
        !> Scene file, for messages
        character(len=*), intent(in) :: path
        !> Groups as scanned
        type(group_type), intent(in) :: groups(:)
        !> The table, bound to the scene being read
        type(key_type), intent(inout) :: keys(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: i, j, k

        do i = 1, size(groups)
            do j = 1, size(groups(i)%assignments)
                associate (assignment => groups(i)%assignments(j))
                    k = find_key(keys, groups(i)%name, assignment%key)
                    if (k == 0) then
                        call input_error(error, visible(path), assignment%line, &
                            & visible(assignment%key), "is not a key of &" // groups(i)%name &
                            & // "; keys are " // key_list(keys, groups(i)%name))
                        return
                    end if
                    call store_value(path, assignment, keys(k), error)
                    if (allocated(error)) return
                end associate
            end do
        end do
    end subroutine store_values

    !> Convert, check and store one value.
    subroutine store_value(path, assignment, key, error)
        character(len=*), intent(in) :: path
        type(assignment_type), intent(in) :: assignment
        type(key_type), intent(inout) :: key
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: expected, word
        real(wp) :: real_value
        integer :: stat, k
        logical :: ok

        ok = .not. assignment%quoted
        select case (key%kind)
        case (kind_real)
            expected = "a real number"
            if (ok) ok = is_real_text(assignment%value)
            if (ok) then
                read(assignment%value, *, iostat=stat) real_value
                ok = stat == 0
            end if
            if (ok .and. .not. ieee_is_finite(real_value)) expected = "a finite number"
            if (ok) ok = ieee_is_finite(real_value)
            if (ok .and. .not. in_range(key, real_value)) then
                call fail("must be " // range_text(key))
                return
            end if
            if (ok) key%real_value = real_value
        case (kind_integer)
            expected = "an integer " // range_text(key)
            if (ok) ok = verify(assignment%value, "+-0123456789") == 0 &
                & .and. verify(assignment%value(2:), "0123456789") == 0 &
                & .and. len(assignment%value) <= 12
            if (ok) then
                read(assignment%value, *, iostat=stat) real_value
                ok = stat == 0
            end if
            if (ok) ok = in_range(key, real_value)
            if (ok) key%integer_value = nint(real_value)
        case (kind_logical)
            expected = ".true. or .false."
            select case (to_lower(assignment%value))
            case (".true.", "t", ".t.", "true")
                key%logical_value = .true.
            case (".false.", "f", ".f.", "false")
                key%logical_value = .false.
            case default
                ok = .false.
            end select
        case (kind_choice)
            expected = choice_text(key) // " (a quoted string)"
            ok = assignment%quoted
            if (ok) then
                ! choices are case-insensitive and surrounding blanks do not count
                word = to_lower(trim(adjustl(assignment%value(2:len(assignment%value) - 1))))
                ok = .false.
                do k = 1, size(key%options)
                    if (key%options(k)%name /= word) cycle
                    key%integer_value = key%options(k)%code
                    ok = .true.
                end do
            end if
        end select
        if (.not. ok) call fail("must be " // expected)

    contains

        subroutine fail(what)
            character(len=*), intent(in) :: what

            call input_error(error, visible(path), assignment%line, trim(key%name), "in &" &
                & // trim(key%group) // " " // what // ", got " // visible(assignment%value))
        end subroutine fail

    end subroutine store_value

    !> The value lies in the key's range.
    pure logical function in_range(key, value)
        type(key_type), intent(in) :: key
        real(wp), intent(in) :: value

        in_range = value >= key%lower .and. value <= key%upper
        if (key%lower_open) in_range = in_range .and. value > key%lower
        if (key%upper_open) in_range = in_range .and. value < key%upper
    end function in_range

    !> The key's range and unit as a message states them: "> 0 and <= 1000000 [m]".
    pure function range_text(key) result(text)
        type(key_type), intent(in) :: key
        character(len=:), allocatable :: text

        if (key%kind == kind_integer) then
            text = ">= " // to_text(nint(key%lower)) // " and <= " // to_text(nint(key%upper))
        else
            text = trim(merge("> ", ">=", key%lower_open)) // " " // to_text(key%lower) &
                & // " and " // trim(merge("< ", "<=", key%upper_open)) // " " &
                & // to_text(key%upper)
        end if
        if (len_trim(key%unit) > 0) text = text // " [" // trim(key%unit) // "]"
    end function range_text

    !> The options of a choice key: "'ida' or 'cvode'".
    pure function choice_text(key) result(text)
        type(key_type), intent(in) :: key
        character(len=:), allocatable :: text
        integer :: k

        text = "'" // trim(key%options(1)%name) // "'"
        do k = 2, size(key%options)
            if (k < size(key%options)) then
                text = text // ", '" // trim(key%options(k)%name) // "'"
            else
                text = text // " or '" // trim(key%options(k)%name) // "'"
            end if
        end do
    end function choice_text

    !> A real as Fortran writes one: [sign] digits [. digits] [e|d [sign] digits], with at
    !> least one digit in the mantissa; or NaN, Inf, Infinity with a sign (then refused as not
    !> finite). Forms a list-directed read also takes, as 1.0+5 for 1e5, are refused.
    pure logical function is_real_text(text) result(ok)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: lower
        integer :: j, digits

        lower = to_lower(text)
        j = 1
        if (len(lower) > 0) then
            if (scan(lower(1:1), "+-") > 0) j = 2
        end if
        ok = any(lower(j:) == [character(len=8) :: "nan", "inf", "infinity"])
        if (ok) return
        digits = 0
        do while (j <= len(lower))
            if (scan(lower(j:j), "0123456789") == 0) exit
            digits = digits + 1
            j = j + 1
        end do
        if (j <= len(lower)) then
            if (lower(j:j) == ".") then
                j = j + 1
                do while (j <= len(lower))
                    if (scan(lower(j:j), "0123456789") == 0) exit
                    digits = digits + 1
                    j = j + 1
                end do
            end if
        end if
        ok = digits > 0
        if (.not. ok .or. j > len(lower)) return
        ok = scan(lower(j:j), "ed") > 0 .and. j < len(lower)
        if (.not. ok) return
        j = j + 1
        if (scan(lower(j:j), "+-") > 0) j = j + 1
        ok = j <= len(lower)
        if (ok) ok = verify(lower(j:), "0123456789") == 0
    end function is_real_text

end module rollcon_key_values
