! SPDX-License-Identifier: MIT
!> No false success of `rollcon check`: a write of XMATRX(0,0) is an
!> outside-block finding with its index; a huge output is a finite finding; a routine that
!> changes an argument it may only read (ID, NPAR, TIME, IFLAG, PAR(k)) gets a changed-argument
!> finding in check and an error naming the argument in run, both called through the same
!> guard; a JSON report that did not reach the disk fails the command.
module test_check_findings
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_disk_par, only : disk_par
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, finding_group_type
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    use rollcon_audit_report, only : report_text
    use rollcon_check_rules, only : rule_outside_block, rule_finite, rule_changed_argument, &
        & rule_name
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program, file_exists, mount_small, unmount
    use check_command_support, only : bounded_run_type, run_bounded, make_folder, &
        & remove_folder, expect_in
    implicit none
    private

    public :: collect_check_findings

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_check_findings"
    !> Faulty routines (test data)
    character(len=*), parameter :: faulty = "test/faulty_ucosubs/"
    !> Cache of the libraries built by these tests (shared with the user-ucosub suites)
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    !> The disk's UCON 1, as the documentation checks it
    character(len=*), parameter :: disk_ucon = "1:1,21,22,23,14,15,24,25,26,0.1,1"
    !> Bound of one run of the program [s] (the first compiles the routine)
    integer, parameter :: bound = 120
    !> States per UCON: every planted fault shows in each state
    integer, parameter :: test_states = 3
    !> Time limit of one call of the routine [s]
    real(wp), parameter :: call_timeout = 10.0_wp

contains

    !> Tests of this suite.
    subroutine collect_check_findings(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("xmatrx-0-0-is-outside-block", test_xmatrx_zero), &
            & new_unittest("huge-output-is-a-finding", test_huge_output), &
            & new_unittest("changed-id-npar-time-iflag-are-findings", test_changed_scalars), &
            & new_unittest("changed-par-is-a-finding", test_changed_par), &
            & new_unittest("run-names-the-changed-argument", test_run_changed_par), &
            & new_unittest("json-to-full-disk-fails", test_json_full_disk)]
    end subroutine collect_check_findings

    !> Check file, each UCON in a child process; par(k) is the PAR of UCON k.
    subroutine check_file(path, pars, report, error)
        character(len=*), intent(in) :: path
        real(wp), intent(in) :: pars(:, :)
        type(user_check_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(user_build_options_type) :: build
        type(ucon_request_type), allocatable :: requests(:)
        type(user_check_options_type) :: options
        integer :: k

        build%cache_dir = test_cache
        call new_user_ucosub(user, path, error, build)
        if (allocated(error)) return
        allocate(requests(size(pars, 2)))
        do k = 1, size(requests)
            requests(k)%id = k
            requests(k)%par = pars(:, k)
        end do
        options%states = test_states
        call check_user_ucosub_isolated(user%ucosub, requests, options, call_timeout, report, &
            & error)
        call user%destroy()
    end subroutine check_file

    !> The one-variable routines' UCON 1: part 3, height 0.25.
    subroutine check_height_file(path, report, error)
        character(len=*), intent(in) :: path
        type(user_check_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error

        call check_file(path, reshape([3.0_wp, 0.25_wp], [2, 1]), report, error)
    end subroutine check_height_file

    !> Pass when UCON k of the report has a group of rule on output at (row, column), found
    !> in every state, whose message (if any) holds message; group is that group.
    subroutine expect_group(error, report, k, rule, output, row, column, message, group)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type), intent(in) :: report
        integer, intent(in) :: k, rule, row, column
        character(len=*), intent(in) :: output, message
        type(finding_group_type), intent(out) :: group
        integer :: g

        associate (ucon => report%ucons(k))
            do g = 1, size(ucon%groups)
                if (ucon%groups(g)%code /= rule .or. ucon%groups(g)%output /= output &
                    & .or. ucon%groups(g)%row /= row .or. ucon%groups(g)%column /= column) cycle
                group = ucon%groups(g)
                call check(error, group%count == test_states, "UCON/" // to_text(ucon%id) &
                    & // ": [" // rule_name(rule) // "] " // output // " in " &
                    & // to_text(group%count) // " of " // to_text(test_states) // " states")
                if (allocated(error)) return
                if (len(message) > 0) call expect_in(error, group%message, message, &
                    & "the finding's message")
                return
            end do
            call check(error, .false., "UCON/" // to_text(ucon%id) // ": no [" &
                & // rule_name(rule) // "] " // output // "(" // to_text(row) // "," &
                & // to_text(column) // ") among " // to_text(size(ucon%groups)) &
                & // " groups; the report: " // report_text(report, "file", "lib"))
        end associate
    end subroutine expect_group

    !> XMATRX(0,0), 31 entries before XMATRX(1,1), lands on a canary and is named as written.
    subroutine test_xmatrx_zero(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        type(finding_group_type) :: group

        call check_height_file(faulty // "xmatrx_zero.f", report, error)
        if (allocated(error)) return
        call expect_group(error, report, 1, rule_outside_block, "XMATRX", 0, 0, &
            & "the UCOSUB wrote XMATRX(0,0) (storage entry -30 of XMATRX(30,30)", group)
        if (allocated(error)) return
        call check(error, group%returned, 0.5_wp, "value written")
        if (allocated(error)) return
        call expect_in(error, report_text(report, "xmatrx_zero.f", "lib"), &
            & "    XMATRX(0,0): 3 of 3 states", "the text report")
        if (allocated(error)) return
        call check(error, size(report%ucons(1)%groups) == 1, "other findings: " &
            & // report_text(report, "xmatrx_zero.f", "lib"))
    end subroutine test_xmatrx_zero

    !> F = 1e308 passed every comparison (the tolerance scales with |F|): a finite finding.
    subroutine test_huge_output(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        type(finding_group_type) :: group

        call check_height_file(faulty // "huge_value.f", report, error)
        if (allocated(error)) return
        call expect_group(error, report, 1, rule_finite, "SCALAR", 0, 0, "", group)
        if (allocated(error)) return
        call check(error, group%returned, 1.0e308_wp, "value returned")
        if (allocated(error)) return
        call expect_in(error, report_text(report, "huge_value.f", "lib"), "returned 1e308, " &
            & // "beyond the largest magnitude the check accepts (1e100)", "the text report")
        if (allocated(error)) return
        call check(error, .not. report%clean(), "a routine returning F = 1e308 is clean")
    end subroutine test_huge_output

    !> ID, NPAR, TIME and IFLAG changed by the routine: a changed-argument finding each, with
    !> the values before and after (IFLAG was a constant: the routine crashed before).
    subroutine test_changed_scalars(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: files(4) = [character(len=16) :: "changes_id.f", &
            & "changes_npar.f", "changes_time.f", "changes_iflag.f"]
        character(len=*), parameter :: names(4) = [character(len=5) :: "ID", "NPAR", "TIME", &
            & "IFLAG"]
        character(len=*), parameter :: changes(4) = [character(len=40) :: &
            & "changed ID from 1 to 101 in the call", "changed NPAR from 2 to 0 in the call", &
            & "changed TIME from ", "changed IFLAG from 0 to 5 in the call"]
        type(user_check_report_type) :: report
        type(finding_group_type) :: group
        integer :: i

        do i = 1, size(files)
            call check_height_file(faulty // trim(files(i)), report, error)
            if (allocated(error)) return
            call expect_group(error, report, 1, rule_changed_argument, trim(names(i)), 0, 0, &
                & "UCON/1: the routine " // trim(changes(i)), group)
            if (allocated(error)) then
                error%message = trim(files(i)) // ": " // error%message
                return
            end if
            call check(error, size(report%ucons(1)%groups) == 1, trim(files(i)) &
                & // ": other findings: " // report_text(report, trim(files(i)), "lib"))
            if (allocated(error)) return
        end do
    end subroutine test_changed_scalars

    !> The disk routine that doubles PAR(10) in every evaluation: every UCON has the finding,
    !> and nothing else (each call gets a fresh copy, so its outputs stay right).
    subroutine test_changed_par(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        type(finding_group_type) :: group
        real(wp) :: pars(11, 3)
        integer :: k

        do k = 1, 3
            pars(:, k) = disk_par(1, 0.1_wp, k)
        end do
        call check_file(faulty // "changes_par.f", pars, report, error)
        if (allocated(error)) return
        do k = 1, 3
            call expect_group(error, report, k, rule_changed_argument, "PAR", 10, 0, &
                & "UCON/" // to_text(k) // ": the routine changed PAR(10) from 0.1 to 0.2", group)
            if (allocated(error)) return
            call check(error, size(report%ucons(k)%groups) == 1, "other findings: " &
                & // report_text(report, "changes_par.f", "lib"))
            if (allocated(error)) return
        end do
        call expect_in(error, report_text(report, "changes_par.f", "lib"), "    PAR(10): 3 of " &
            & // "3 states", "the text report")
    end subroutine test_changed_par

    !> The same routine serving a run: an error naming the UCON, the argument and the values
    !> (exit status 1), not a crash and not a run with a changed radius.
    subroutine test_run_changed_par(error)
        type(error_type), allocatable, intent(out) :: error
        type(bounded_run_type) :: run
        character(len=:), allocatable :: program

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_bounded(program, "tipping_coin --quiet --ucosub " // faulty // "changes_par.f" &
            & // " --output " // scratch // "/out", bound, scratch, "run", run)
        call remove_folder(scratch)
        call check(error, run%status == 1, "exit status " // to_text(run%status) &
            & // ", expected 1; stderr: " // run%err)
        if (allocated(error)) return
        call expect_in(error, run%err, "rollcon: error: UCON/1: the routine changed PAR(10) " &
            & // "from 0.1 to 0.2 in the call IFLAG = 0", "stderr")
    end subroutine test_run_changed_par

    !> check --json into a full filesystem: the verdict is printed, but the command fails
    !> (exit status 2) naming the file and the reason, and no cut report is left behind.
    subroutine test_json_full_disk(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: mount_point = scratch // "/small"
        character(len=*), parameter :: report = mount_point // "/report.json"
        type(bounded_run_type) :: run
        character(len=:), allocatable :: program
        logical :: left

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call mount_small(mount_point, "64k", error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        ! fill it: every later write fails with ENOSPC
        call execute_command_line("head -c 1048576 /dev/zero > " // mount_point &
            & // "/filler 2> /dev/null")
        call run_bounded(program, "check ucon/adams/rolling_disk/ucosub.f --ucon " // disk_ucon &
            & // " --states 3 --json " // report, bound, scratch, "json", run)
        left = file_exists(report)
        call unmount(mount_point)
        call remove_folder(scratch)
        call check(error, run%status == 2, "exit status " // to_text(run%status) &
            & // ", expected 2; stderr: " // run%err)
        if (allocated(error)) return
        call expect_in(error, run%out, "verdict: CLEAN", "stdout")
        if (allocated(error)) return
        call expect_in(error, run%err, "rollcon: error: the JSON report was not written: " &
            & // report // ": ", "stderr")
        if (allocated(error)) return
        call expect_in(error, run%err, "No space left on device", "stderr")
        if (allocated(error)) return
        call check(error, .not. left, "a cut report was left at " // report)
    end subroutine test_json_full_disk

end module test_check_findings
