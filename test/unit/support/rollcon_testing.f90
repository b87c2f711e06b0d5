! SPDX-License-Identifier: MIT
!> Test harness shaped like test-drive: named tests per suite, checks with tolerances, skips.
module rollcon_testing
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_skipped
    use rollcon_text, only : to_text
    use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
    implicit none
    private

    public :: error_type, unittest_type, testsuite_type, test_interface, collect_interface
    public :: new_unittest, new_testsuite, check, skip_test, run_testsuite, test_counts_type

    abstract interface
        !> One test: returns with error allocated when it fails (or is skipped)
        subroutine test_interface(error)
            import :: error_type
            type(error_type), allocatable, intent(out) :: error
        end subroutine test_interface
    end interface

    !> A named test
    type :: unittest_type
        character(len=:), allocatable :: name
        procedure(test_interface), pointer, nopass :: test => null()
        !> The test passes when it fails (to prove a check can catch something)
        logical :: should_fail = .false.
    end type unittest_type

    abstract interface
        !> Returns the tests of a suite
        subroutine collect_interface(tests)
            import :: unittest_type
            type(unittest_type), allocatable, intent(out) :: tests(:)
        end subroutine collect_interface
    end interface

    !> A named suite
    type :: testsuite_type
        character(len=:), allocatable :: name
        procedure(collect_interface), pointer, nopass :: collect => null()
    end type testsuite_type

    !> Tally of a run
    type :: test_counts_type
        integer :: passed = 0, failed = 0, skipped = 0
    end type test_counts_type

    !> Check a condition, or a value against an expectation within tolerances
    interface check
        module procedure :: check_condition
        module procedure :: check_real
        module procedure :: check_real_array
        module procedure :: check_integer
    end interface check

contains

    !> A named test.
    function new_unittest(name, test, should_fail) result(unittest)
        character(len=*), intent(in) :: name
        procedure(test_interface) :: test
        logical, intent(in), optional :: should_fail
        type(unittest_type) :: unittest

        unittest%name = name
        unittest%test => test
        if (present(should_fail)) unittest%should_fail = should_fail
    end function new_unittest

    !> A named suite.
    function new_testsuite(name, collect) result(suite)
        character(len=*), intent(in) :: name
        procedure(collect_interface) :: collect
        type(testsuite_type) :: suite

        suite%name = name
        suite%collect => collect
    end function new_testsuite

    !> Fail with message unless condition holds.
    subroutine check_condition(error, condition, message)
        type(error_type), allocatable, intent(out) :: error
        logical, intent(in) :: condition
        character(len=*), intent(in) :: message

        if (.not. condition) call fatal_error(error, message)
    end subroutine check_condition

    !> Pass when |actual - expected| <= max(abs_tol, rel_tol*|expected|); NaN always fails.
    subroutine check_real(error, actual, expected, message, abs_tol, rel_tol)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: actual, expected
        character(len=*), intent(in) :: message
        real(wp), intent(in), optional :: abs_tol, rel_tol
        real(wp) :: bound

        bound = 0.0_wp
        if (present(abs_tol)) bound = abs_tol
        if (present(rel_tol)) bound = max(bound, rel_tol*abs(expected))
        if (ieee_is_nan(actual) .or. ieee_is_nan(expected) .or. &
            & .not. abs(actual - expected) <= bound) then
            call fatal_error(error, message // ": got " // to_text(actual) // ", expected " &
                & // to_text(expected) // " within " // to_text(bound))
        end if
    end subroutine check_real

    !> Element-wise check_real; the message names the first failing index.
    subroutine check_real_array(error, actual, expected, message, abs_tol, rel_tol)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: actual(:), expected(:)
        character(len=*), intent(in) :: message
        real(wp), intent(in), optional :: abs_tol, rel_tol
        integer :: i

        if (size(actual) /= size(expected)) then
            call fatal_error(error, message // ": size " // to_text(size(actual)) &
                & // ", expected " // to_text(size(expected)))
            return
        end if
        do i = 1, size(actual)
            call check_real(error, actual(i), expected(i), message // " (" // to_text(i) // ")", &
                & abs_tol, rel_tol)
            if (allocated(error)) return
        end do
    end subroutine check_real_array

    !> Exact integer comparison.
    subroutine check_integer(error, actual, expected, message)
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in) :: actual, expected
        character(len=*), intent(in) :: message

        if (actual /= expected) then
            call fatal_error(error, message // ": got " // to_text(actual) // ", expected " &
                & // to_text(expected))
        end if
    end subroutine check_integer

    !> Mark the test as skipped, with the reason.
    subroutine skip_test(error, reason)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: reason

        call fatal_error(error, reason, stat_skipped)
    end subroutine skip_test

    !> Run the tests of a suite (or only the one named), print a line each, add to counts.
    subroutine run_testsuite(suite, unit, counts, only, found)
        type(testsuite_type), intent(in) :: suite
        integer, intent(in) :: unit
        type(test_counts_type), intent(inout) :: counts
        !> Name of the single test to run; all when absent
        character(len=*), intent(in), optional :: only
        !> Set to true when at least one test ran
        logical, intent(inout) :: found
        type(unittest_type), allocatable :: tests(:)
        type(error_type), allocatable :: error
        integer :: i

        call suite%collect(tests)
        do i = 1, size(tests)
            if (present(only)) then
                if (tests(i)%name /= only) cycle
            end if
            found = .true.
            call tests(i)%test(error)
            if (allocated(error)) then
                if (error%stat == stat_skipped) then
                    counts%skipped = counts%skipped + 1
                    write(unit, '(a)') "  SKIP " // suite%name // "/" // tests(i)%name // ": " &
                        & // error%message
                    flush(unit)
                    cycle
                end if
            end if
            if (allocated(error) .neqv. tests(i)%should_fail) then
                counts%failed = counts%failed + 1
                if (allocated(error)) then
                    write(unit, '(a)') "  FAIL " // suite%name // "/" // tests(i)%name // ": " &
                        & // error%message
                else
                    write(unit, '(a)') "  FAIL " // suite%name // "/" // tests(i)%name &
                        & // ": expected to fail, but passed"
                end if
            else
                counts%passed = counts%passed + 1
                write(unit, '(a)') "  PASS " // suite%name // "/" // tests(i)%name
            end if
            flush(unit)
        end do
    end subroutine run_testsuite

end module rollcon_testing
