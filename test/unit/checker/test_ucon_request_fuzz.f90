! SPDX-License-Identifier: MIT
!> Fuzz test of the `--ucon ID:PAR1,PAR2,...` parser (read_ucon_request): seeded mutations of
!> valid statements must each give a clean refusal (an input error that quotes the text, in
!> visible characters, and says what was expected) or a clean read (a positive id and at most
!> 30 finite constants); never a crash or a hang. The inputs the fuzzer found bugs with are
!> kept as deterministic tests.
module test_ucon_request_fuzz
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_namelist_bytes, only : visible
    use rollcon_ucosub_contract, only : max_ucon_par
    use rollcon_ucosub_audit, only : ucon_request_type
    use rollcon_ucon_request, only : read_ucon_request
    use rollcon_testing, only : unittest_type, new_unittest, check
    use fuzz_mutations, only : seed_fuzz, draw, mutate_text, printable
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: collect_ucon_request_fuzz

    !> Mutated statements read
    integer, parameter :: mutation_count = 20000
    !> Least share of each outcome: a parser that refuses or accepts everything fails
    real(wp), parameter :: least_share = 0.05_wp
    !> Seed of the mutations
    integer, parameter :: seed = 20260524
    !> Valid statements: the disk's three UCONs (docs/checker.md), the turntable disk's, an id
    !> alone, blanks and signs and exponents, and 30 constants (the most a UCON takes)
    character(len=*), parameter :: valid(*) = [character(len=100) :: &
        & "1:1,21,22,23,14,15,24,25,26,0.1,1", "2:1,21,22,23,14,15,24,25,26,0.1,2", &
        & "3:1,21,22,23,14,15,24,25,26,0.1,3", &
        & "1:2,11,12,21,22,23,14,15,24,25,26,0.1,0,0,3,0,0,1", "7", &
        & "12: 3, -0.5,1.0e-3,+2E2", "123456789:1e-300,-1E+300,.5,5.,0", &
        & "4:1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,26,27,28,29,30"]
    !> Words a mutation may insert
    character(len=*), parameter :: words(*) = [character(len=8) :: ":", ",", ",,", "1e308", &
        & "1e309", "nan", "inf", "2*", ";", "/", " ", "0x1", "1d0", "-", "+", ".", "e", "E+"]

contains

    !> Tests of this suite.
    subroutine collect_ucon_request_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("mutated-statements", test_mutated_statements), &
            & new_unittest("bytes-shown-visibly", test_bytes_visible), &
            & new_unittest("long-list-refused-early", test_long_list)]
    end subroutine collect_ucon_request_fuzz

    subroutine test_mutated_statements(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request
        type(error_type), allocatable :: found
        character(len=:), allocatable :: text
        integer :: m, refused, accepted, steps, k

        refused = 0
        accepted = 0
        call seed_fuzz(seed)
        do m = 1, mutation_count
            text = trim(valid(1 + mod(m - 1, size(valid))))
            steps = 1 + draw(3)
            do k = 1, steps
                call mutate_text(text, words)
            end do
            call read_ucon_request(text, request, found)
            if (allocated(found)) then
                refused = refused + 1
                call check_refusal(found, text, m, error)
            else
                accepted = accepted + 1
                call check(error, request%id >= 1 .and. allocated(request%par), "mutation " &
                    & // to_text(m) // ": no id or no PAR in a clean read of '" &
                    & // visible(text) // "'")
                if (allocated(error)) return
                call check(error, size(request%par) <= max_ucon_par .and. &
                    & all(ieee_is_finite(request%par)), "mutation " // to_text(m) &
                    & // ": more than 30 constants or one not finite in a clean read of '" &
                    & // visible(text) // "'")
            end if
            if (allocated(error)) return
        end do
        call check(error, min(refused, accepted) >= least_share*mutation_count, &
            & "outcomes too one-sided: " // to_text(refused) // " refused, " &
            & // to_text(accepted) // " accepted")
    end subroutine test_mutated_statements

    !> An input error that quotes the text (visibly) first, says what was expected, and shows
    !> only printable ASCII.
    subroutine check_refusal(found, text, m, error)
        type(error_type), intent(in) :: found
        character(len=*), intent(in) :: text
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: head

        call check(error, found%stat == stat_input .and. allocated(found%message), &
            & "mutation " // to_text(m) // ": not an input error")
        if (allocated(error)) return
        call check(error, printable(found%message), "mutation " // to_text(m) &
            & // ": invisible character in: " // visible(found%message))
        if (allocated(error)) return
        head = "--ucon '" // visible(text) // "': "
        call check(error, index(found%message, head) == 1 .and. len(found%message) > &
            & len(head) + 10, "mutation " // to_text(m) // ": message does not quote the " &
            & // "text and say what was expected: " // found%message)
    end subroutine check_refusal

    !> A control or non-ASCII byte in the text was copied raw into the message: it is shown
    !> visibly (the fuzzer's first refusal of a flipped byte).
    subroutine test_bytes_visible(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request
        type(error_type), allocatable :: found

        call read_ucon_request("1:1," // achar(27) // "2", request, found)
        call check(error, allocated(found), "an escape byte accepted")
        if (allocated(error)) return
        call check(error, found%message == "--ucon '1:1,\x1B2': PAR(2) must be one finite " &
            & // "decimal number (such as 21, -0.5 or 1.0e-3), got '\x1B2'; fields are " &
            & // "separated by commas", found%message)
        if (allocated(error)) return
        deallocate(found)
        call read_ucon_request(achar(195) // achar(169) // ":1", request, found)
        call check(error, allocated(found), "a non-ASCII id accepted")
        if (allocated(error)) return
        call check(error, found%message == "--ucon 'U+00E9:1': the UCON id must be a positive " &
            & // "integer (digits only), got 'U+00E9'; expected ID:PAR1,PAR2,...", &
            & found%message)
    end subroutine test_bytes_visible

    !> A list of 100 000 constants grew PAR one element at a time (quadratic: seconds) before
    !> its length was checked: refused at the 31st field.
    subroutine test_long_list(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request
        type(error_type), allocatable :: found
        integer, parameter :: fields = 100000

        call read_ucon_request("1:" // repeat("1,", fields - 1) // "1", request, found)
        call check(error, allocated(found), "100 000 constants accepted")
        if (allocated(error)) return
        call check(error, index(found%message, "': more than " // to_text(max_ucon_par) &
            & // " constants (PAR(31) is given); at most " // to_text(max_ucon_par)) > 0, &
            & found%message(:min(len(found%message), 300)))
    end subroutine test_long_list

end module test_ucon_request_fuzz
