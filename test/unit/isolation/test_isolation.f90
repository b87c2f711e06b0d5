! SPDX-License-Identifier: MIT
!> A user's routine cannot take rollcon down: each planted
!> fault of test/faulty_ucosubs/ (a signal, an endless call, a STOP, a write outside the block)
!> becomes the finding its header names; the --ucon option is read strictly; findings are
!> classified by their rule code.
module test_isolation
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : errmes, ucovar
    use rollcon_disk_par, only : disk_par
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    use rollcon_audit_report, only : report_text
    use rollcon_ucon_request, only : read_ucon_request
    use rollcon_check_rules, only : rule_signal, rule_timeout, rule_exit, rule_outside_block, &
        & rule_errmes, rule_finite, rule_name
    use rollcon_testing, only : unittest_type, new_unittest, check
    use isolation_run_child, only : test_run_child
    implicit none
    private

    public :: collect_isolation

    !> Cache of the libraries built by these tests (shared with test_user_ucosub)
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    !> Planted faults (test data)
    character(len=*), parameter :: faulty = "test/faulty_ucosubs/"
    !> The generated ADAMS-ready disk routine
    character(len=*), parameter :: disk_source = "ucon/adams/rolling_disk/ucosub.f"
    !> States per UCON: every planted fault shows in the first state
    integer, parameter :: test_states = 3
    !> Time limit per call for the endless loops [s]: an evaluation of these routines takes
    !> microseconds, so 0.5 s is far from any honest call even on a loaded machine
    real(wp), parameter :: short_timeout = 0.5_wp
    !> Time limit per call where no call hangs [s] (the default of the command line)
    real(wp), parameter :: usual_timeout = 10.0_wp

contains

    !> Tests of this suite.
    subroutine collect_isolation(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("sigfpe-is-a-finding", test_sigfpe), &
            & new_unittest("sigsegv-is-a-finding", test_sigsegv), &
            & new_unittest("endless-init-times-out", test_endless_init), &
            & new_unittest("endless-eval-times-out", test_endless_eval), &
            & new_unittest("stop-is-a-finding", test_stop), &
            & new_unittest("isolated-disk-clean", test_disk_clean), &
            & new_unittest("array-31-outside-block", test_array_31), &
            & new_unittest("array-100-outside-block", test_array_100), &
            & new_unittest("xmatrx-outside-block", test_xmatrx_outside), &
            & new_unittest("ucon-option-strict", test_ucon_option), &
            & new_unittest("errmes-classified-by-code", test_errmes_code), &
            & new_unittest("run-child-reports-fault", test_run_child)]
    end subroutine collect_isolation

    !> Check file as UCONs 1 and 2 of the one-variable routines (PAR = part 3, height), each
    !> in a child process.
    subroutine check_isolated(path, timeout, report, error)
        character(len=*), intent(in) :: path
        real(wp), intent(in) :: timeout
        type(user_check_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(user_build_options_type) :: build
        type(ucon_request_type) :: requests(2)
        type(user_check_options_type) :: options

        build%cache_dir = test_cache
        call new_user_ucosub(user, path, error, build)
        if (allocated(error)) return
        requests(1)%id = 1
        requests(1)%par = [3.0_wp, 0.25_wp]
        requests(2)%id = 2
        requests(2)%par = [3.0_wp, 0.5_wp]
        options%states = test_states
        call check_user_ucosub_isolated(user%ucosub, requests, options, timeout, report, error)
        call user%destroy()
    end subroutine check_isolated

    !> Both UCONs of the report hold one finding of rule whose message holds every part.
    subroutine expect_fault(error, report, rule, parts)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type), intent(in) :: report
        integer, intent(in) :: rule
        character(len=*), intent(in) :: parts(:)
        integer :: k, i

        do k = 1, size(report%ucons)
            associate (ucon => report%ucons(k))
                call check(error, size(ucon%groups) == 1, "UCON/" // to_text(ucon%id) // ": " &
                    & // to_text(size(ucon%groups)) // " groups, expected one")
                if (allocated(error)) return
                call check(error, ucon%groups(1)%code == rule, "UCON/" // to_text(ucon%id) &
                    & // ": rule " // rule_name(ucon%groups(1)%code) // ", expected " &
                    & // rule_name(rule))
                if (allocated(error)) return
                call check(error, index(ucon%groups(1)%message, "UCON/" // to_text(ucon%id) &
                    & // ": ") == 1, "the message does not name the UCON: " &
                    & // ucon%groups(1)%message)
                if (allocated(error)) return
                do i = 1, size(parts)
                    call expect_in(error, ucon%groups(1)%message, trim(parts(i)))
                    if (allocated(error)) return
                end do
            end associate
        end do
        call check(error, .not. report%clean(), "a report with a fault is clean")
    end subroutine expect_fault

    !> Pass when text contains part.
    subroutine expect_in(error, text, part)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: text, part

        call check(error, index(text, part) > 0, "'" // part // "' not in: " // text)
    end subroutine expect_in

    subroutine test_sigfpe(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "divide_by_zero.f", usual_timeout, report, error)
        if (allocated(error)) return
        call expect_fault(error, report, rule_signal, [character(len=40) :: "the process was " &
            & // "killed by SIGFPE", "IFLAG = 0, IDRSEL = (1, 1, 1)", "(state 1 of the check)"])
    end subroutine test_sigfpe

    subroutine test_sigsegv(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "wild_write.f", usual_timeout, report, error)
        if (allocated(error)) return
        call expect_fault(error, report, rule_signal, [character(len=40) :: "the process was " &
            & // "killed by SIGSEGV", "IFLAG = 0, IDRSEL = (1, 1, 1)", "(state 1 of the check)"])
    end subroutine test_sigsegv

    subroutine test_endless_init(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "endless_init.f", short_timeout, report, error)
        if (allocated(error)) return
        call expect_fault(error, report, rule_timeout, [character(len=60) :: "a UCOSUB call " &
            & // "did not return within 0.5 s", "IFLAG = 3 (the initialisation call)"])
    end subroutine test_endless_init

    subroutine test_endless_eval(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "endless_eval.f", short_timeout, report, error)
        if (allocated(error)) return
        call expect_fault(error, report, rule_timeout, [character(len=48) :: "a UCOSUB call " &
            & // "did not return within 0.5 s", "IFLAG = 0, IDRSEL = (1, 1, 1)"])
    end subroutine test_endless_eval

    subroutine test_stop(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "stops.f", usual_timeout, report, error)
        if (allocated(error)) return
        call expect_fault(error, report, rule_exit, [character(len=60) :: "the process ended " &
            & // "with exit status 0", "IFLAG = 0, IDRSEL = (1, 1, 1)"])
        if (allocated(error)) return
        call expect_in(error, report_text(report, "stops.f", "lib"), "verdict: MISMATCHES in 2")
    end subroutine test_stop

    !> The disk routine checked in child processes gives the report it gives in this process:
    !> the findings and counts travel back intact.
    subroutine test_disk_clean(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(user_build_options_type) :: build
        type(ucon_request_type) :: requests(3)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: isolated, in_process
        integer :: k

        build%cache_dir = test_cache
        call new_user_ucosub(user, disk_source, error, build)
        if (allocated(error)) return
        do k = 1, 3
            requests(k)%id = k
            requests(k)%par = disk_par(1, 0.1_wp, k)
        end do
        options%states = test_states
        call check_user_ucosub_isolated(user%ucosub, requests, options, usual_timeout, &
            & isolated, error)
        if (allocated(error)) return
        call check_user_ucosub(user%ucosub, requests, options, in_process, error)
        call user%destroy()
        if (allocated(error)) return
        call check(error, isolated%clean(), "the disk has findings when isolated")
        if (allocated(error)) return
        do k = 1, 3
            call check(error, isolated%ucons(k)%declared .and. all(isolated%ucons(k)%codes &
                & == in_process%ucons(k)%codes) .and. isolated%ucons(k)%compared &
                & == in_process%ucons(k)%compared .and. isolated%ucons(k)%compared > 0 .and. &
                & isolated%ucons(k)%worst == in_process%ucons(k)%worst, "UCON/" // to_text(k) &
                & // ": the isolated report differs from the one made in this process")
            if (allocated(error)) return
        end do
    end subroutine test_disk_clean

    !> Pass when UCON k has an outside-block group on output at (row, column) in every state,
    !> whose value is value.
    subroutine expect_outside(error, report, output, row, column, value)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type), intent(in) :: report
        character(len=*), intent(in) :: output
        integer, intent(in) :: row, column
        real(wp), intent(in) :: value
        integer :: g

        associate (ucon => report%ucons(1))
            do g = 1, size(ucon%groups)
                if (ucon%groups(g)%code /= rule_outside_block) cycle
                if (ucon%groups(g)%output /= output .or. ucon%groups(g)%row /= row &
                    & .or. ucon%groups(g)%column /= column) cycle
                call check(error, ucon%groups(g)%count, test_states, "states with " // output)
                if (allocated(error)) return
                call check(error, ucon%groups(g)%returned, value, "value written")
                return
            end do
            call check(error, .false., "no [outside-block] " // output // "(" // to_text(row) &
                & // "," // to_text(column) // ") among " // to_text(size(ucon%groups)) &
                & // " groups")
        end associate
    end subroutine expect_outside

    subroutine test_array_31(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "array_31.f", usual_timeout, report, error)
        if (allocated(error)) return
        call expect_outside(error, report, "ARRAY", 31, 0, 0.5_wp)
        if (allocated(error)) return
        ! Nothing is blamed on the entries the routine may write.
        call check(error, size(report%ucons(1)%groups), 1, "groups of UCON/1")
    end subroutine test_array_31

    subroutine test_array_100(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "array_100.f", usual_timeout, report, error)
        if (allocated(error)) return
        call expect_outside(error, report, "ARRAY", 100, 0, 0.0_wp)
        if (allocated(error)) return
        call check(error, index(report_text(report, "array_100.f", "lib"), "verdict: CLEAN") &
            & == 0, "a routine that writes ARRAY(100) is CLEAN")
    end subroutine test_array_100

    subroutine test_xmatrx_outside(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_isolated(faulty // "xmatrx_outside.f", usual_timeout, report, error)
        if (allocated(error)) return
        call expect_outside(error, report, "XMATRX", 2, 1, 0.25_wp)
        if (allocated(error)) return
        ! XMATRX(31,31) is storage entry 931 = 1 + 30*31, that is XMATRX(1,32).
        call expect_outside(error, report, "XMATRX", 1, 32, 0.125_wp)
    end subroutine test_xmatrx_outside

    !> One number per comma-separated field, a positive id: the misparsed lists are refused.
    subroutine test_ucon_option(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request
        type(error_type), allocatable :: refusal
        character(len=24), parameter :: refused(8) = [character(len=24) :: &
            & "1:1,21,,23", "1:2*1,3", "1:1;21;3", "-1:1,2", "0:1,2", "1:1,2,", "1:1 2,3", &
            & "x:1"]
        integer :: i

        do i = 1, size(refused)
            call read_ucon_request(trim(refused(i)), request, error)
            if (.not. allocated(error)) then
                call check(error, .false., "--ucon " // trim(refused(i)) // " was accepted")
                return
            end if
            deallocate(error)
        end do
        call read_ucon_request("1:1,21,,23", request, refusal)
        call expect_in(error, refusal%message, "PAR(3) must be one finite decimal number")
        if (allocated(error)) return
        call read_ucon_request("12: 3, -0.5,1.0e-3,+2E2", request, error)
        if (allocated(error)) return
        call check(error, request%id == 12 .and. size(request%par) == 4, "id or size of PAR")
        if (allocated(error)) return
        call check(error, request%par, [3.0_wp, -0.5_wp, 1.0e-3_wp, 200.0_wp], "PAR")
        if (allocated(error)) return
        call read_ucon_request("7", request, error)
        if (allocated(error)) return
        call check(error, request%id == 7 .and. size(request%par) == 0, "ID alone")
    end subroutine test_ucon_option

    !> A routine whose ERRMES message happens to say "non-finite value" is an errmes finding,
    !> and a routine returning NaN a finite finding: by code, whatever the words.
    subroutine test_errmes_code(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request(1)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report

        request(1)%id = 5
        request(1)%par = [3.0_wp, 0.25_wp]
        options%states = 1
        call check_user_ucosub(errmes_ucosub, request, options, report, error)
        if (allocated(error)) return
        call check(error, any(report%ucons(1)%groups%code == rule_errmes) .and. .not. &
            & any(report%ucons(1)%groups%code == rule_finite), "ERRMES call not classified " &
            & // "as [errmes]")
    end subroutine test_errmes_code

    !> Declares Z of part PAR(1); every evaluation calls ERRMES with a message that mentions
    !> a non-finite value.
    subroutine errmes_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        if (iflag == 3) then
            call ucovar(id, 1, [nint(par(1))], 1, [13])
            return
        end if
        call errmes(.true., "PAR(2) must not be a non-finite value", id, "NO")
        if (idrsel(1) == 1) scalar = q(1) - par(2)
        if (idrsel(2) == 1) array(1) = 1.0_wp
        if (idrsel(3) == 1) xmatrx(1, 1) = 0.0_wp
        if (npar < 0) scalar = time
    end subroutine errmes_ucosub

end module test_isolation
