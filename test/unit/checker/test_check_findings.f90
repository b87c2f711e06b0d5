! SPDX-License-Identifier: MIT
!> No false success of `rollcon check` (issue #22, item 3): a JSON report that did not reach
!> the disk fails the command.
module test_check_findings
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program, file_exists, mount_small, unmount
    use check_command_support, only : bounded_run_type, run_bounded, make_folder, &
        & remove_folder, expect_in
    implicit none
    private

    public :: collect_check_findings

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_check_findings"
    !> The disk's UCON 1, as the documentation checks it
    character(len=*), parameter :: disk_ucon = "1:1,21,22,23,14,15,24,25,26,0.1,1"
    !> Bound of one run of the program [s] (the first compiles the routine)
    integer, parameter :: bound = 120

contains

    !> Tests of this suite.
    subroutine collect_check_findings(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("json-to-full-disk-fails", test_json_full_disk)]
    end subroutine collect_check_findings

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
