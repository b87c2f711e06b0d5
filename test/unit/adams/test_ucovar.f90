! SPDX-License-Identifier: MIT
!> Tests of the UCOVAR registry and of the initialisation call: every kind of bad declaration.
module test_ucovar
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucovar
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_ucon_call, only : declare_ucon
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_disk_par, only : disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_ucovar

contains

    !> Tests of this suite.
    subroutine collect_ucovar(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("disk-declares-eight", test_disk_declares), &
            & new_unittest("too-many-variables", test_too_many), &
            & new_unittest("unequal-lengths", test_unequal), &
            & new_unittest("unknown-code", test_unknown_code), &
            & new_unittest("duplicate-variable", test_duplicate), &
            & new_unittest("bad-part-id", test_bad_part), &
            & new_unittest("declared-twice", test_twice), &
            & new_unittest("many-declarations-found-by-id", test_many), &
            & new_unittest("no-ucovar-call", test_no_call), &
            & new_unittest("wrong-id", test_wrong_id), &
            & new_unittest("outside-initialisation", test_outside)]
    end subroutine collect_ucovar

    !> IFLAG = 3 declares codes 21 22 23 14 15 24 25 26 for the part in PAR(1).
    subroutine test_disk_declares(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        integer :: k

        call declare_ucon(rolling_disk_ucosub, 7, disk_par(4, 0.1_wp, 2), registry, error)
        if (allocated(error)) return
        k = registry%find(7)
        call check(error, k == 1 .and. registry%count() == 1, "UCON 7 not recorded once")
        if (allocated(error)) return
        call check(error, all(registry%entries(k)%codes == [21, 22, 23, 14, 15, 24, 25, 26]), &
            & "codes differ from 21 22 23 14 15 24 25 26")
        if (allocated(error)) return
        call check(error, all(registry%entries(k)%parts == 4) .and. &
            & size(registry%entries(k)%parts) == 8, "parts are not eight times part 4")
    end subroutine test_disk_declares

    !> Declare directly into a registry and return the message (empty when accepted).
    function declaration_message(nparts, lparts, nvars, lvars) result(message)
        integer, intent(in) :: nparts, lparts(:), nvars, lvars(:)
        character(len=:), allocatable :: message
        type(ucovar_registry_type) :: registry
        type(error_type), allocatable :: error

        call registry%declare(12, nparts, lparts, nvars, lvars, error)
        message = ""
        if (allocated(error)) message = error%message
    end function declaration_message

    subroutine expect_message(error, message, fragment)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: message, fragment

        call check(error, index(message, fragment) > 0 .and. index(message, "UCON/12") == 1, &
            & "message '" // message // "' should start with 'UCON/12' and contain '" &
            & // fragment // "'")
    end subroutine expect_message

    !> Pass when found is allocated and its message has the fragment.
    subroutine expect_error(error, found, fragment)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable, intent(in) :: found
        character(len=*), intent(in) :: fragment

        if (.not. allocated(found)) then
            call check(error, .false., "no error reported; expected '" // fragment // "'")
            return
        end if
        call expect_message(error, found%message, fragment)
    end subroutine expect_error

    subroutine test_too_many(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: parts(31), codes(31)

        parts = 1
        codes = 11
        call expect_message(error, declaration_message(31, parts, 31, codes), &
            & "declares 31 variables (NVARS); expected 1 to 30")
    end subroutine test_too_many

    subroutine test_unequal(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_message(error, declaration_message(2, [1, 1], 3, [11, 12, 13]), &
            & "NPARTS = 2 but NVARS = 3")
    end subroutine test_unequal

    subroutine test_unknown_code(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_message(error, declaration_message(3, [1, 1, 1], 3, [11, 17, 13]), &
            & "variable 2 has code 17; expected one of 11 12 13 14 15 16 21 22 23 24 25 26")
    end subroutine test_unknown_code

    subroutine test_duplicate(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_message(error, declaration_message(3, [2, 2, 2], 3, [22, 11, 22]), &
            & "variables 1 and 3 are both Ydot of part 2")
    end subroutine test_duplicate

    subroutine test_bad_part(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_message(error, declaration_message(2, [1, 0], 2, [11, 15]), &
            & "variable 2 (theta) has part id 0")
    end subroutine test_bad_part

    subroutine test_twice(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type) :: registry
        type(error_type), allocatable :: found

        call registry%declare(12, 1, [1], 1, [11], error)
        if (allocated(error)) return
        call registry%declare(12, 1, [1], 1, [12], found)
        call expect_error(error, found, "UCOVAR called twice")
    end subroutine test_twice

    !> 3000 declarations in a scrambled order of ids (the registry grows by doubling and finds
    !> an id through its index, rollcon_id_index): each id found at its own entry with its own
    !> part and code, an id never declared not found, the count exact, and a repeat of an id
    !> declared long before still refused.
    subroutine test_many(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type) :: registry
        type(error_type), allocatable :: found
        integer, parameter :: many = 3000
        integer :: k, id, entry

        do k = 1, many
            ! 7919 is prime to 3000: the ids 1000 .. 3999 in a scrambled order, each once
            id = 1000 + mod(7919*k, many)
            call registry%declare(id, 1, [id], 1, [11 + mod(id, 6)], error)
            if (allocated(error)) return
        end do
        call check(error, registry%count() == many, "count")
        if (allocated(error)) return
        do id = 1000, 1000 + many - 1
            entry = registry%find(id)
            call check(error, entry > 0, "id " // to_text(id) // " not found")
            if (allocated(error)) return
            call check(error, registry%entries(entry)%id == id .and. &
                & all(registry%entries(entry)%parts == [id]) .and. &
                & all(registry%entries(entry)%codes == [11 + mod(id, 6)]), &
                & "id " // to_text(id) // ": the entry found is another's")
            if (allocated(error)) return
        end do
        call check(error, registry%find(999) == 0 .and. registry%find(1000 + many) == 0, &
            & "an id never declared is found")
        if (allocated(error)) return
        id = 1000 + mod(7919, many)
        call registry%declare(id, 1, [1], 1, [12], found)
        call check(error, allocated(found), "UCON/" // to_text(id) // " declared twice: no error")
        if (allocated(error)) return
        call check(error, index(found%message, "UCON/" // to_text(id) // ": UCOVAR called twice") &
            & == 1 .and. registry%count() == many, "UCON/" // to_text(id) &
            & // " declared twice: " // found%message)
    end subroutine test_many

    !> A routine whose initialisation call forgets UCOVAR.
    subroutine silent_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        if (iflag == 0) scalar = time + q(1) + par(1) + real(id + npar + idrsel(1), wp) &
            & + array(1) + xmatrx(1, 1)
    end subroutine silent_ucosub

    subroutine test_no_call(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        type(error_type), allocatable :: found

        call declare_ucon(silent_ucosub, 12, [1.0_wp], registry, found)
        call expect_error(error, found, "made no UCOVAR call")
    end subroutine test_no_call

    !> A routine that declares under another id than the one it was called with.
    subroutine wrong_id_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        if (iflag == 3) call ucovar(id + 1, 1, [1], 1, [11])
        if (iflag == 0) scalar = time + q(1) + par(1) + real(npar + idrsel(1), wp) &
            & + array(1) + xmatrx(1, 1)
    end subroutine wrong_id_ucosub

    subroutine test_wrong_id(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        type(error_type), allocatable :: found

        call declare_ucon(wrong_id_ucosub, 12, [1.0_wp], registry, found)
        call expect_error(error, found, "UCOVAR was called with ID = 13")
    end subroutine test_wrong_id

    !> Outside a driver's initialisation call a wrong declaration is still reported.
    subroutine test_outside(error)
        type(error_type), allocatable, intent(out) :: error

        type(error_type), allocatable :: found

        call ucovar(12, 1, [1], 1, [99])
        call take_ucon_error(found)
        call expect_error(error, found, "code 99")
    end subroutine test_outside

end module test_ucovar
