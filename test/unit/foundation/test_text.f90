! SPDX-License-Identifier: MIT
!> Tests of number formatting used in every message.
module test_text
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_testing, only : error_type, unittest_type, new_unittest, check
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: collect_text

contains

    !> Tests of this suite.
    subroutine collect_text(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("shortest-round-trip", test_round_trip), &
            & new_unittest("integers-and-nan", test_special), &
            & new_unittest("check-fails-on-nan", test_nan_fails, should_fail=.true.)]
    end subroutine collect_text

    subroutine test_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: values(5), back
        character(len=:), allocatable :: text
        integer :: i

        values = [0.1_wp, -2.5_wp, 1.0e-300_wp, 7800.0_wp, 1.0_wp/3.0_wp]
        do i = 1, size(values)
            text = to_text(values(i))
            read(text, *) back
            call check(error, back == values(i), &
                & "to_text does not read back: " // to_text(values(i)))
            if (allocated(error)) return
        end do
        call check(error, to_text(0.1_wp) == "0.1" .and. to_text(-2.5_wp) == "-2.5" &
            & .and. to_text(7800.0_wp) == "7800" .and. to_text(1.0e-300_wp) == "1e-300" &
            & .and. to_text(0.04_wp) == "0.04" .and. to_text(-1.5e20_wp) == "-1.5e20", &
            & "0.1, -2.5, 7800, 1e-300, 0.04, -1.5e20 print as " // to_text(0.1_wp) // ", " &
            & // to_text(-2.5_wp) // ", " // to_text(7800.0_wp) // ", " // to_text(1.0e-300_wp) &
            & // ", " // to_text(0.04_wp) // ", " // to_text(-1.5e20_wp))
    end subroutine test_round_trip

    subroutine test_special(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, to_text(-42) == "-42", "integer text")
        if (allocated(error)) return
        ! Row counts pass 2**31: printed whole, not wrapped round.
        call check(error, to_text(1000000000000001_int64) == "1000000000000001", &
            & "64-bit integer text: " // to_text(1000000000000001_int64))
        if (allocated(error)) return
        call check(error, to_text(ieee_value(1.0_wp, ieee_quiet_nan)) == "NaN", "NaN text")
    end subroutine test_special

    !> The harness must reject NaN even with an infinite tolerance.
    subroutine test_nan_fails(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, ieee_value(1.0_wp, ieee_quiet_nan), 0.0_wp, "NaN", abs_tol=huge(1.0_wp))
    end subroutine test_nan_fails

end module test_text
