! SPDX-License-Identifier: MIT
!> `rollcon sweep` where its CSV cannot simply be written: into a full disk
!> the sweep fails and says which rows the CSV holds, and the file holds exactly those;
!> a second sweep into the CSV another one is writing is refused, and the first one's CSV
!> resumes as a whole.
module test_sweep_guards
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count, &
        & mount_small, unmount
    implicit none
    private

    public :: collect_sweep_guards

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_sweep_guards"

contains

    !> Tests of this suite.
    subroutine collect_sweep_guards(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("full-disk-fails-and-names-rows", test_full_disk), &
            & new_unittest("second-sweep-into-one-csv-refused", test_two_sweeps)]
    end subroutine collect_sweep_guards

    !> 400 short cases into a 16 KiB filesystem: some 50 rows fit. The sweep exits 1 naming
    !> the system's reason and the lines the CSV holds whole, which are exactly the whole
    !> lines in it; it does not say that all 400 are there.
    subroutine test_full_disk(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: mount_point = scratch // "/small"
        character(len=:), allocatable :: program, err, out, csv, said
        integer :: status, start, whole

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call write_lines(scratch // "/big.nml", [character(len=44) :: "&study", &
            & "scene = 'data/upright.nml' /", "&grid", "run%end_time = '0.01 0.02 400' /"])
        call mount_small(mount_point, "16k", error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        call run_rollcon(program, "sweep " // scratch // "/big.nml --no-map -o " // mount_point, &
            & scratch // "/full.out", scratch // "/full.err", status)
        csv = file_text(mount_point // "/big.csv")
        call unmount(mount_point)
        err = file_text(scratch // "/full.err")
        out = file_text(scratch // "/full.out")
        call remove_folder(scratch)
        call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
            & "rollcon: error: " // mount_point // "/big.csv: write failed: No space left on " &
            & // "device; the file holds its first ") == 1 .and. index(out, "all 400") == 0, &
            & "exit status " // to_text(status) // ", stdout: " // out // ", stderr: " // err)
        if (allocated(error)) return
        ! the count it names is the count of whole lines in the file
        start = index(err, "holds its first ") + len("holds its first ")
        said = err(start:start - 1 + index(err(start:), " ") - 1)
        whole = line_count(csv)
        call check(error, said == to_text(whole) .and. whole > 10 .and. whole < 400, "the " &
            & // "error says " // said // " whole lines, the file has " // to_text(whole))
    end subroutine test_full_disk

    !> Sweep A runs (12 cases of 100 to 200 s of simulated rolling, a few seconds); sweep B of
    !> the same study into the same folder, started once A has written its header, is
    !> refused naming A; A completes, its lock file goes, and a rerun finds every case done.
    subroutine test_two_sweeps(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, sweep, err_b, out_c
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call write_lines(scratch // "/slow.nml", [character(len=44) :: "&study", &
            & "scene = 'data/upright.nml' /", "&grid", "run%end_time = '100 200 12' /"])
        sweep = program // " sweep " // scratch // "/slow.nml -q --no-map -o " // scratch &
            & // "/out"
        call execute_command_line(sweep // " > " // scratch // "/a.out 2> " // scratch &
            & // "/a.err & a=$!; i=0; while [ ! -s " // scratch // "/out/slow.csv ] && [ $i " &
            & // "-lt 600 ]; do sleep 0.05; i=$((i+1)); done; " // sweep // " > " // scratch &
            & // "/b.out 2> " // scratch // "/b.err; echo $? > " // scratch // "/b.status; " &
            & // "wait $a; echo $? > " // scratch // "/a.status", exitstat=status)
        err_b = file_text(scratch // "/b.err")
        call check(error, file_text(scratch // "/a.status") == "0" // new_line("a") .and. &
            & file_text(scratch // "/b.status") == "1" // new_line("a") .and. &
            & line_count(err_b) == 1 .and. index(err_b, "rollcon: error: " // scratch &
            & // "/out/slow.csv: another sweep is writing this study's CSV (process ") == 1, &
            & "A: " // file_text(scratch // "/a.status") // file_text(scratch // "/a.err") &
            & // "B: " // file_text(scratch // "/b.status") // err_b)
        if (.not. allocated(error)) then
            call check(error, line_count(file_text(scratch // "/out/slow.csv")) == 13 .and. &
                & .not. file_exists(scratch // "/out/slow.csv.lock"), "A's CSV has " &
                & // to_text(line_count(file_text(scratch // "/out/slow.csv"))) // " lines " &
                & // "(13 expected), or its lock file stayed")
        end if
        if (.not. allocated(error)) then
            call run_rollcon(program, "sweep " // scratch // "/slow.nml --no-map -o " // scratch &
                & // "/out", scratch // "/c.out", scratch // "/c.err", status)
            out_c = file_text(scratch // "/c.out")
            call check(error, status == 0 .and. index(out_c, "0 cases run now") > 0 .and. &
                & index(out_c, "12 from an earlier run") > 0, "the rerun: exit status " &
                & // to_text(status) // ", stdout: " // out_c // ", stderr: " &
                & // file_text(scratch // "/c.err"))
        end if
        call remove_folder(scratch)
    end subroutine test_two_sweeps

end module test_sweep_guards
