! SPDX-License-Identifier: MIT
!> `rollcon run ... --ucosub`, through the program (suite run-apart): the one route with a
!> built-in routine by name and with a user's file, on a scene and on a dataset, and the run
!> apart from a user's routine: the child process only computes and rollcon writes every
!> output, so a routine that closes the standard units or changes the working directory
!> cannot touch the outputs, and a rollcon killed during the run takes its child with it and
!> leaves the earlier run's files as they were.
module test_run_apart
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists
    implicit none
    private

    public :: collect_run_apart

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_run_apart"
    !> The generated rolling disk's fixed-form file, what an ADAMS user would bring
    character(len=*), parameter :: disk_file = "ucon/adams/rolling_disk/ucosub.f"
    !> The longest a child may outlive its killed parent [ms]: PR_SET_PDEATHSIG is delivered as
    !> the parent dies (measured: 7 to 22 ms here); a second leaves room for a loaded machine
    integer, parameter :: child_grace_ms = 1000

contains

    subroutine collect_run_apart(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("scene-ucosub-builtin-name", test_scene_builtin), &
            & new_unittest("scene-ucosub-refusing-the-par", test_scene_refused_par), &
            & new_unittest("scene-ucosub-file", test_scene_file), &
            & new_unittest("dataset-ucosub-file", test_dataset_file), &
            & new_unittest("routine-closes-standard-units", test_closes_units), &
            & new_unittest("routine-changes-directory", test_chdir), &
            & new_unittest("routine-faulting-after-end", test_faults_after_end), &
            & new_unittest("sigterm-stops-the-child", test_sigterm), &
            & new_unittest("sigkill-stops-the-child", test_sigkill)]
    end subroutine collect_run_apart

    !> `run coin --ucosub disk` (the hand-checked routine by name) completes and writes the
    !> rows of `run coin`, whose default routine it is, to the bit.
    subroutine test_scene_builtin(error)
        type(error_type), allocatable, intent(out) :: error

        call same_rows("coin -q", "coin --ucosub disk -q", "coin", error)
    end subroutine test_scene_builtin

    !> `run coin --ucosub knife_edge`: the built-in knife edge refuses the rolling disk's PAR a
    !> disk scene gives its no-slip UCONs. The one-line error says that the routine chosen
    !> refused the scene's PAR, what that PAR is, and which built-in routines take it; nothing
    !> is written.
    subroutine test_scene_refused_par(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        call run_rollcon(program, "run coin --ucosub knife_edge -q -o " // scratch // "/out", &
            & scratch // "/par.out", scratch // "/par.err", status)
        err = file_text(scratch // "/par.err")
        call check(error, status == 1 .and. index(err, "rollcon: error: UCON/1: ") == 1 .and. &
            & index(err, "here the built-in knife_edge, refused the PAR a disk scene gives " &
            & // "them, the rolling disk's") > 0 .and. index(err, "routines that take it: " &
            & // "disk, rolling_disk") > 0 .and. .not. file_exists(scratch // "/out/coin.csv"), &
            & "exit status " // to_text(status) // ", stderr: " // err)
    end subroutine test_scene_refused_par

    !> `run coin --ucosub ucon/adams/rolling_disk/ucosub.f` (the generated routine's fixed-form
    !> file, run in a child process) completes and writes the rows of `--ucosub rolling_disk`
    !> (the same routine built in, in this process) to the bit.
    subroutine test_scene_file(error)
        type(error_type), allocatable, intent(out) :: error

        call same_rows("coin --ucosub rolling_disk -q", "coin --ucosub " // disk_file // " -q", &
            & "coin", error)
    end subroutine test_scene_file

    !> The same on the dataset data/coin.adm.
    subroutine test_dataset_file(error)
        type(error_type), allocatable, intent(out) :: error

        call same_rows("data/coin.adm --ucosub rolling_disk -q", "data/coin.adm --ucosub " &
            & // disk_file // " -q", "coin.adm", error)
    end subroutine test_dataset_file

    !> A routine that closes units 0, 5 and 6 in its initialisation call: the run completes
    !> (exit 0), the summary is printed on stdout and the outputs are whole.
    subroutine test_closes_units(error)
        type(error_type), allocatable, intent(out) :: error

        call odd_routine("closes_units", error)
    end subroutine test_closes_units

    !> A routine that changes the working directory in its initialisation call: the outputs
    !> land where rollcon was asked to write them.
    subroutine test_chdir(error)
        type(error_type), allocatable, intent(out) :: error

        call odd_routine("chdir", error)
    end subroutine test_chdir

    !> A routine that faults when called after the run's END: a run calls a user's routine at
    !> its own states and times only (whether its constraints do work is judged from the rows,
    !> rollcon_problem constraint_power), so it completes.
    subroutine test_faults_after_end(error)
        type(error_type), allocatable, intent(out) :: error

        call odd_routine("faults_after_end", error)
    end subroutine test_faults_after_end

    !> SIGTERM to rollcon while its child is in an endless call of the routine: the child is
    !> gone within child_grace_ms, and the earlier run's CSV is as it was.
    subroutine test_sigterm(error)
        type(error_type), allocatable, intent(out) :: error

        call kill_during_run("TERM", error)
    end subroutine test_sigterm

    !> The same with SIGKILL, which rollcon cannot catch.
    subroutine test_sigkill(error)
        type(error_type), allocatable, intent(out) :: error

        call kill_during_run("KILL", error)
    end subroutine test_sigkill

    !> Run rollcon with first and with second (each into its own folder); both exit 0 and write
    !> byte-identical NAME.csv.
    subroutine same_rows(first, second, name, error)
        character(len=*), intent(in) :: first, second, name
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, a, b
        integer :: status(2)

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        call run_rollcon(program, "run " // first // " -o " // scratch // "/a", scratch &
            & // "/a.out", scratch // "/a.err", status(1))
        call run_rollcon(program, "run " // second // " -o " // scratch // "/b", scratch &
            & // "/b.out", scratch // "/b.err", status(2))
        call check(error, all(status == 0), "exit status " // to_text(status(1)) // " and " &
            & // to_text(status(2)) // ": " // file_text(scratch // "/a.err") &
            & // file_text(scratch // "/b.err"))
        if (allocated(error)) return
        a = file_text(scratch // "/a/" // name // ".csv")
        b = file_text(scratch // "/b/" // name // ".csv")
        call check(error, len(a) > 0 .and. a == b, "the rows differ (" // to_text(len(a)) &
            & // " and " // to_text(len(b)) // " bytes): 'run " // first // "' against 'run " &
            & // second // "'")
    end subroutine same_rows

    !> The resting ball (test/run_apart/resting_ball.adm) with test/run_apart/height_KIND.f:
    !> exit 0, its 51 rows, its summary on stdout and on disk, where asked.
    subroutine odd_routine(kind, error)
        character(len=*), intent(in) :: kind
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out, csv, summary
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        call run_rollcon(program, "run test/run_apart/resting_ball.adm --ucosub " &
            & // "test/run_apart/height_" // kind // ".f -q -o " // scratch // "/out", &
            & scratch // "/run.out", scratch // "/run.err", status)
        out = file_text(scratch // "/run.out")
        csv = file_text(scratch // "/out/resting_ball.adm.csv")
        summary = file_text(scratch // "/out/resting_ball.adm.summary.txt")
        call check(error, status == 0 .and. len(file_text(scratch // "/run.err")) == 0, &
            & "exit status " // to_text(status) // ", stderr: " // file_text(scratch &
            & // "/run.err"))
        if (allocated(error)) return
        call check(error, count_lines(csv) == 52 .and. index(summary, "status: completed") > 0 &
            & .and. index(out, "status: completed") > 0, "outputs: " // to_text(count_lines(csv)) &
            & // " CSV lines (52 expected), summary file: " // summary // ", stdout: " // out)
    end subroutine odd_routine

    !> Kill rollcon with signal while its child runs test/faulty_ucosubs/endless_eval.f, into
    !> a folder that holds an earlier run's coin.csv (test/run_apart/kill_parent.sh does it).
    subroutine kill_during_run(signal, error)
        character(len=*), intent(in) :: signal
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: earlier = "earlier run's rows" // new_line("a")
        character(len=:), allocatable :: program, report, words
        integer :: status, unit, ms, stat

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch // "/out")
        open(newunit=unit, file=scratch // "/out/coin.csv", status="replace", action="write", &
            & access="stream", form="unformatted")
        write(unit) earlier
        close(unit)
        call execute_command_line("bash test/run_apart/kill_parent.sh " // signal // " " &
            & // scratch // "/killed " // program // " run coin --ucosub " &
            & // "test/faulty_ucosubs/endless_eval.f --call-timeout 100 -q -o " // scratch &
            & // "/out > " // scratch // "/report.txt 2> /dev/null", exitstat=status)
        report = file_text(scratch // "/report.txt")
        words = "child-gone "
        ms = -1
        if (index(report, words) == 1) read(report(len(words) + 1:), *, iostat=stat) ms
        call check(error, ms >= 0 .and. ms <= child_grace_ms, "after SIG" // signal &
            & // " to rollcon: " // report // " (at most " // to_text(child_grace_ms) &
            & // " ms allowed)")
        if (allocated(error)) return
        call check(error, file_text(scratch // "/out/coin.csv") == earlier .and. .not. &
            & file_exists(scratch // "/out/coin.summary.txt"), "the earlier run's coin.csv " &
            & // "was changed or a summary appeared")
    end subroutine kill_during_run

    !> Line ends in a text.
    pure integer function count_lines(text)
        character(len=*), intent(in) :: text
        integer :: i

        count_lines = 0
        do i = 1, len(text)
            if (text(i:i) == new_line("a")) count_lines = count_lines + 1
        end do
    end function count_lines

end module test_run_apart
