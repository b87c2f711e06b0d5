! SPDX-License-Identifier: MIT
!> The user-ucosub suite's tests of the check's reports: the text and the JSON report of a
!> check, and numbers in them that keep their exponent letter.
module user_ucosub_reports
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_disk_par, only : disk_par, disk_codes
    use rollcon_ucosub_audit, only : user_check_report_type
    use rollcon_audit_report, only : report_text
    use rollcon_audit_json, only : report_json
    use rollcon_testing, only : check
    use user_ucosub_support, only : faulty, disk_source, test_states, check_disk_file, expect_in
    implicit none
    private

    public :: test_report, test_report_exponent

contains

    !> The text report names the rule, the entry with its variables and the verdict; the JSON
    !> report says the same.
    subroutine test_report(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        character(len=:), allocatable :: text

        call check_disk_file(faulty // "sign_error.f", report, error)
        if (allocated(error)) return
        text = report_text(report, "sign_error.f", "lib")
        call expect_in(error, text, "[derivative]")
        if (allocated(error)) return
        call expect_in(error, text, "ARRAY(5) = dF/d(theta): " // to_text(test_states) // " of " &
            & // to_text(test_states) // " states; worst at state ")
        if (allocated(error)) return
        call expect_in(error, text, "verdict: MISMATCHES in 1 of 3 UCON(s)")
        if (allocated(error)) return
        text = report_json(report, "sign_error.f", "lib", .false.)
        call expect_in(error, text, '"clean": false')
        if (allocated(error)) return
        call expect_in(error, text, '"entry": "ARRAY(5) = dF/d(theta)", "count": ' &
            & // to_text(test_states))
        if (allocated(error)) return
        call check_disk_file(disk_source, report, error)
        if (allocated(error)) return
        call expect_in(error, report_text(report, disk_source, "lib"), "verdict: CLEAN")
    end subroutine test_report

    !> A deviation of 1e-301 is printed with its exponent letter (an `es9.2` edit gives
    !> "1.00-301") and reads back as the number it was.
    subroutine test_report_exponent(error)
        type(error_type), allocatable, intent(out) :: error
        !> The text report prints three significant digits: the read-back is within half a unit
        !> of the third digit
        real(wp), parameter :: tol_three_digits = 5.0e-3_wp
        character(len=*), parameter :: lead = "largest relative deviation "
        type(user_check_report_type) :: report
        character(len=:), allocatable :: text, number
        real(wp) :: value
        integer :: start, stat

        allocate(report%ucons(1))
        report%ucons(1)%id = 1
        report%ucons(1)%par = disk_par(1, 0.1_wp, 1)
        report%ucons(1)%declared = .true.
        report%ucons(1)%codes = disk_codes
        report%ucons(1)%parts = [(1, start = 1, size(disk_codes))]
        report%ucons(1)%states = test_states
        report%ucons(1)%worst = 1.0e-301_wp
        allocate(report%ucons(1)%groups(0))
        text = report_text(report, "tiny.f", "lib")
        start = index(text, lead)
        call check(error, start > 0, "no '" // lead // "' in: " // text)
        if (allocated(error)) return
        number = text(start + len(lead):)
        number = number(:scan(number // ":", ":") - 1)
        call check(error, scan(number, "Ee") > 0, "exponent letter lost: '" // number // "'")
        if (allocated(error)) return
        read(number, *, iostat=stat) value
        call check(error, stat == 0, "'" // number // "' does not read as a number")
        if (allocated(error)) return
        call check(error, value, 1.0e-301_wp, "deviation read back from the text report", &
            & rel_tol=tol_three_digits)
    end subroutine test_report_exponent

end module user_ucosub_reports
