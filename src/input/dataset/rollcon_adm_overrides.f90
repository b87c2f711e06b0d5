! SPDX-License-Identifier: MIT
!> Values of a dataset set apart from its file (a parameter study's case, docs/studies.md):
!> each replaces one value of one argument of one statement, before the dataset is read and
!> checked as usual; an argument the statement does not write is added to it.
module rollcon_adm_overrides
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, upper_case
    use rollcon_adm_lexer, only : adm_text_type, adm_argument_type
    implicit none
    private

    public :: adm_override_type, apply_adm_overrides, override_place, parse_override_name

    !> One value set apart from the file
    type :: adm_override_type
        !> Statement name in full, upper case (PART, MARKER, ACCGRAV, ...)
        character(len=:), allocatable :: statement
        !> Its id (0 for a statement without one, as ACCGRAV)
        integer :: id = 0
        !> The argument's keyword as the dataset writes it, upper case (VX, QP, KGRAV)
        character(len=:), allocatable :: keyword
        !> Which value of the argument's list (1 for a single value)
        integer :: element = 1
        !> The value, as it would be written
        character(len=:), allocatable :: value
    end type adm_override_type

contains

    !> The statement and argument an override names, as a message writes them: PART/2 VX(1).
    pure function override_place(override) result(text)
        type(adm_override_type), intent(in) :: override
        character(len=:), allocatable :: text

        text = override%statement
        if (override%id /= 0) text = text // "/" // to_text(override%id)
        text = text // " " // override%keyword // "(" // to_text(override%element) // ")"
    end function override_place

    !> Apply overrides to the statements of text; names(i) is statement i's name in full.
    !> The statement must be in the dataset; a keyword it does not write is added (element 1
    !> only); an element past the argument's list is an error.
    subroutine apply_adm_overrides(text, names, overrides, error)
        type(adm_text_type), intent(inout) :: text
        character(len=*), intent(in) :: names(:)
        type(adm_override_type), intent(in) :: overrides(:)
        type(error_type), allocatable, intent(out) :: error
        type(adm_argument_type) :: added
        integer :: k, s, a

        do k = 1, size(overrides)
            associate (o => overrides(k))
                s = 0
                do a = 1, size(text%statements)
                    if (names(a) == o%statement .and. text%statements(a)%id == o%id) s = a
                end do
                if (s == 0) then
                    call fatal_error(error, text%file // ": " // override_place(o) // ": the " &
                        & // "dataset has no such statement", stat_input)
                    return
                end if
                associate (statement => text%statements(s))
                    do a = 1, size(statement%arguments)
                        if (upper_case(statement%arguments(a)%keyword) == o%keyword) exit
                    end do
                    if (a > size(statement%arguments)) then
                        if (o%element /= 1) then
                            call fatal_error(error, text%file // ": " // override_place(o) &
                                & // ": the statement does not write " // o%keyword &
                                & // ", and only its first value can be added", stat_input)
                            return
                        end if
                        added%keyword = o%keyword
                        added%assigned = .true.
                        added%line = statement%line
                        allocate(added%values(1))
                        added%values(1)%text = o%value
                        statement%arguments = [statement%arguments, added]
                        deallocate(added%values)
                    else if (o%element > size(statement%arguments(a)%values)) then
                        call fatal_error(error, text%file // ": " // override_place(o) &
                            & // ": the argument has " // to_text(size(statement%arguments(a) &
                            & %values)) // " value(s)", stat_input)
                        return
                    else
                        statement%arguments(a)%values(o%element)%text = o%value
                    end if
                end associate
            end associate
        end do
    end subroutine apply_adm_overrides

    !> The override a name sets: `statement%id%keyword[%k]` or `statement%keyword[%k]` (a
    !> study's parameter: part%2%vx, marker%3%qp%3, accgrav%kgrav); group (statement%id) and
    !> key (keyword%k) as the name writes them, both empty when it does not read so.
    pure subroutine parse_override_name(text, o, group, key)
        character(len=*), intent(in) :: text
        type(adm_override_type), intent(out) :: o
        character(len=:), allocatable, intent(out) :: group, key
        character(len=len(text)) :: parts(4)
        integer :: n, start, cut, stat, next

        n = 0
        start = 1
        group = ""
        key = ""
        do
            cut = index(text(start:), "%")
            if (n == size(parts)) return
            n = n + 1
            if (cut == 0) then
                parts(n) = text(start:)
                exit
            end if
            parts(n) = text(start:start + cut - 2)
            start = start + cut
        end do
        if (n < 2 .or. any(len_trim(parts(:n)) == 0)) return
        o%statement = upper_case(trim(parts(1)))
        next = 2
        read(parts(2), *, iostat=stat) o%id
        if (stat == 0 .and. verify(trim(parts(2)), "0123456789") == 0) then
            next = 3
        else
            o%id = 0
        end if
        if (n < next .or. n > next + 1) return
        o%keyword = upper_case(trim(parts(next)))
        if (verify(o%keyword, "ABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789") /= 0) return
        o%element = 1
        if (n == next + 1) then
            if (verify(trim(parts(n)), "0123456789") /= 0) return
            read(parts(n), *, iostat=stat) o%element
            if (stat /= 0 .or. o%element < 1) return
        end if
        group = trim(parts(1))
        if (next == 3) group = group // "%" // trim(parts(2))
        key = trim(parts(next))
        if (n == next + 1) key = key // "%" // trim(parts(n))
    end subroutine parse_override_name

end module rollcon_adm_overrides
