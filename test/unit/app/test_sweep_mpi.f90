! SPDX-License-Identifier: MIT
!> Tests of `rollcon sweep` as users run it, on one process and under mpirun (Open MPI;
!> --oversubscribe, and as root the two OMPI_ALLOW_RUN_AS_ROOT variables): the rows do not
!> depend on the number of ranks; failing cases are rows and the study completes; a study
!> whose worker rank is killed (SIGKILL) keeps the rows written and a rerun completes it; a
!> bad study file is refused with file, line and key and exit status 1. rollcon itself loads
!> no MPI library: `rollcon sweep` replaces it by the program rollcon-sweep beside it (under
!> mpirun on every rank), and says so, with exit status 1, when that program is missing.
module test_sweep_mpi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : make_folder, remove_folder
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count
    use study_texts, only : write_study
    use study_rows, only : csv_rows, without_cpu, sorted
    implicit none
    private

    public :: collect_sweep_mpi

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_sweep_mpi"
    !> How the tests start mpirun: as root Open MPI refuses to start unless told it may
    character(len=*), parameter :: mpirun = "env OMPI_ALLOW_RUN_AS_ROOT=1 " &
        & // "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe"

contains

    !> Tests of this suite.
    subroutine collect_sweep_mpi(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("ranks-give-the-same-rows", test_ranks), &
            & new_unittest("user-file-study", test_user_file), &
            & new_unittest("resume-after-kill", test_kill), &
            & new_unittest("bad-study-refused", test_bad_study), &
            & new_unittest("rollcon-loads-no-mpi", test_no_mpi), &
            & new_unittest("sweep-program-missing", test_program_missing)]
    end subroutine collect_sweep_mpi

    !> Twelve cases, six of which fail (max_steps 1), on one process, on 2 ranks (a
    !> coordinator and one worker) and on 3: the same rows once sorted, cpu_s apart, exit 0.
    subroutine test_ranks(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, study, reference(:), rows(:)
        integer :: ranks, status

        call mpi_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_study("test_sweep_ranks", [character(len=60) :: "&study", &
            & "    scene = 'data/struck_rolling.nml' /", "&grid", &
            & "    run%max_steps = '1 5001 2'", "    strike%impulse = '0.01 0.5 3'", &
            & "    initial%speed = '0.3 1.2 2' /"], study)
        do ranks = 1, 3
            call remove_folder(scratch // "/r" // to_text(ranks))
            if (ranks == 1) then
                call run_rollcon(program, "sweep " // study // " --no-map -o " // scratch &
                    & // "/r1", scratch // "/r1.out", scratch // "/r1.err", status)
            else
                call run_rollcon(mpirun // " -np " // to_text(ranks) // " " // program, &
                    & "sweep " // study // " --no-map -o " // scratch // "/r" // to_text(ranks), &
                    & scratch // "/r" // to_text(ranks) // ".out", scratch // "/r" &
                    & // to_text(ranks) // ".err", status)
            end if
            call check(error, status == 0, to_text(ranks) // " ranks: exit status " &
                & // to_text(status) // ": " // file_text(scratch // "/r" // to_text(ranks) &
                & // ".err"))
            if (allocated(error)) return
            rows = sorted(without_cpu(csv_rows(scratch // "/r" // to_text(ranks) &
                & // "/test_sweep_ranks.csv")))
            if (ranks == 1) then
                reference = rows
                call check(error, size(rows) == 13 .and. count(index(rows, ",failed,-1,") > 0) &
                    & == 6, "one process: 12 rows, 6 failed with flag -1")
            else
                call check(error, size(rows) == size(reference) .and. all(rows == reference), &
                    & to_text(ranks) // " ranks: rows differ from one process's")
            end if
            if (allocated(error)) return
        end do
        ! rollcon replaced itself by rollcon-sweep on every rank: MPI_Init there saw the job
        call check(error, index(file_text(scratch // "/r2.out"), "2 ranks: a coordinator and 1 " &
            & // "workers") > 0, "2 ranks: not said in the output: " // file_text(scratch &
            & // "/r2.out"))
        if (allocated(error)) return
        call check(error, index(file_text(scratch // "/r3.out"), "a coordinator and 2 workers") &
            & > 0, "3 ranks: not said in the output")
    end subroutine test_ranks

    !> `rollcon sweep STUDY --ucosub FILE` of data/coin.adm at two gravities with the generated
    !> rolling disk as a user's file (run apart in every case): on one process and on 2 ranks
    !> the same two completed rows (cpu_s apart), which are not those of the hand-checked disk
    !> built in (the study ran the file: its rounding differs). The library's suite
    !> study-run holds each row to the case's run alone; a --ucosub naming no file is refused.
    subroutine test_user_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, study, one(:), two(:), builtin(:), err
        integer :: status

        call mpi_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_study("test_sweep_user_file", [character(len=60) :: "&study", &
            & "    scene = 'data/coin.adm' /", "&grid", "    accgrav%kgrav = '-9.81 -5 2' /"], &
            & study)
        call remove_folder(scratch // "/u1")
        call remove_folder(scratch // "/u2")
        call remove_folder(scratch // "/u0")
        call run_rollcon(program, "sweep " // study // " --ucosub ucon/adams/rolling_disk/" &
            & // "ucosub.f --no-map -o " // scratch // "/u1", scratch // "/u1.out", scratch &
            & // "/u1.err", status)
        call check(error, status == 0, "one process: exit status " // to_text(status) // ": " &
            & // file_text(scratch // "/u1.err"))
        if (allocated(error)) return
        call run_rollcon(mpirun // " -np 2 " // program, "sweep " // study &
            & // " --ucosub ucon/adams/rolling_disk/ucosub.f --no-map -o " // scratch // "/u2", &
            & scratch // "/u2.out", scratch // "/u2.err", status)
        call check(error, status == 0, "2 ranks: exit status " // to_text(status) // ": " &
            & // file_text(scratch // "/u2.err"))
        if (allocated(error)) return
        call run_rollcon(program, "sweep " // study // " --no-map -o " // scratch // "/u0", &
            & scratch // "/u0.out", scratch // "/u0.err", status)
        call check(error, status == 0, "built-in disk: exit status " // to_text(status))
        if (allocated(error)) return
        one = sorted(without_cpu(csv_rows(scratch // "/u1/test_sweep_user_file.csv")))
        two = sorted(without_cpu(csv_rows(scratch // "/u2/test_sweep_user_file.csv")))
        builtin = sorted(without_cpu(csv_rows(scratch // "/u0/test_sweep_user_file.csv")))
        call check(error, size(one) == 3 .and. count(index(one, ",completed,") > 0) == 2, &
            & "one process: expected 2 completed rows: " // file_text(scratch &
            & // "/u1/test_sweep_user_file.csv"))
        if (allocated(error)) return
        call check(error, size(two) == size(one) .and. all(two == one), "2 ranks: rows differ " &
            & // "from one process's")
        if (allocated(error)) return
        call check(error, size(builtin) == size(one) .and. .not. all(builtin == one), &
            & "the rows of the file equal the built-in disk's to the last digit: was it run?")
        if (allocated(error)) return
        call run_rollcon(program, "sweep " // study // " --ucosub no_such_ucosub.f --no-map " &
            & // "-o " // scratch // "/u3", scratch // "/u3.out", scratch // "/u3.err", status)
        err = file_text(scratch // "/u3.err")
        call check(error, status == 1 .and. index(err, "rollcon: error: --ucosub " &
            & // "no_such_ucosub.f: no such file") == 1, "exit status " // to_text(status) &
            & // ", stderr: " // err)
    end subroutine test_user_file

    !> A worker rank killed part-way: mpirun fails, the rows written so far stay, and a rerun
    !> on one process runs only the missing cases and gives the rows of an uninterrupted run.
    !> 100 cases, the kill after 5 rows: the other worker goes on until mpirun has ended the
    !> job (about 30 rows here), far from the end.
    subroutine test_kill(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, study, output, csv, report, rows(:), whole(:)
        integer :: status, kept

        call mpi_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_study("test_sweep_kill", [character(len=60) :: "&study", &
            & "    scene = 'data/struck_rolling.nml' /", "&grid", &
            & "    strike%impulse = '0.01 0.1 10'", "    initial%speed = '0.3 1.2 10' /"], study)
        output = scratch // "/kill"
        csv = output // "/test_sweep_kill.csv"
        call remove_folder(output)
        call make_folder(output)
        call run_rollcon("bash test/sweep/kill_worker.sh", program // " " // study // " " &
            & // output // " " // csv // " 5", scratch // "/kill.out", scratch // "/kill.err", &
            & status)
        report = file_text(scratch // "/kill.out")
        call check(error, status == 0 .and. index(report, "killed") == 1, "no worker killed: " &
            & // report // file_text(scratch // "/kill.err"))
        if (allocated(error)) return
        call check(error, index(report, "mpirun-status 0") == 0, "mpirun exited 0 after a " &
            & // "rank was killed: " // report)
        if (allocated(error)) return
        kept = size(csv_rows(csv)) - 1
        call check(error, kept >= 5 .and. kept < 100, "rows kept after the kill: " &
            & // to_text(kept))
        if (allocated(error)) return
        call run_rollcon(program, "sweep " // study // " --no-map -o " // output, scratch &
            & // "/rerun.out", scratch // "/rerun.err", status)
        call check(error, status == 0 .and. index(file_text(scratch // "/rerun.out"), &
            & to_text(100 - kept) // " cases run now") > 0, "the rerun did not run the " &
            & // to_text(100 - kept) // " missing cases: " // file_text(scratch // "/rerun.out") &
            & // file_text(scratch // "/rerun.err"))
        if (allocated(error)) return
        call remove_folder(output // "-whole")
        call run_rollcon(program, "sweep " // study // " --no-map -o " // output // "-whole", &
            & scratch // "/whole.out", scratch // "/whole.err", status)
        rows = sorted(without_cpu(csv_rows(csv)))
        whole = sorted(without_cpu(csv_rows(output // "-whole/test_sweep_kill.csv")))
        call check(error, size(rows) == 101 .and. size(whole) == 101, "101 lines each")
        if (allocated(error)) return
        call check(error, all(rows == whole), "the resumed rows differ from a whole run's")
    end subroutine test_kill

    !> Under mpirun, a parameter that is not a scene key: one message, with file, line and
    !> key, exit status 1, no CSV.
    subroutine test_bad_study(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, study, messages
        integer :: status

        call mpi_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_study("test_sweep_bad", [character(len=60) :: "&study", &
            & "    scene = 'data/upright.nml' /", "&grid", "    disk%thick = '0.01 0.1 3' /"], &
            & study)
        call remove_folder(scratch // "/bad")
        call run_rollcon(mpirun // " -np 2 " // program, "sweep " // study // " -o " // scratch &
            & // "/bad", scratch // "/bad.out", scratch // "/bad.err", status)
        messages = file_text(scratch // "/bad.err")
        call check(error, status /= 0, "exit status 0 for a bad study")
        if (allocated(error)) return
        call check(error, index(messages, "rollcon: error: " // study // ":4: 'disk%thick' " &
            & // "in &grid is not a scene key") > 0, "message: " // messages)
        if (allocated(error)) return
        call check(error, index(messages, "rollcon: error:", back=.true.) == &
            & index(messages, "rollcon: error:"), "more than one rank reported the error")
        if (allocated(error)) return
        call check(error, .not. file_exists(scratch // "/bad/test_sweep_bad.csv"), &
            & "a CSV was written")
    end subroutine test_bad_study

    !> The shared objects rollcon loads (ldd) hold no MPI library, those of rollcon-sweep beside
    !> it do: MPI is linked into the study program alone (fpm.toml).
    subroutine test_no_mpi(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, objects
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon("ldd", program, scratch // "/ldd.out", scratch // "/ldd.err", status)
        objects = file_text(scratch // "/ldd.out")
        call check(error, status == 0 .and. index(objects, "libgfortran") > 0, "ldd " &
            & // program // ": exit status " // to_text(status) // ": " // objects)
        if (allocated(error)) return
        call check(error, index(objects, "libmpi") == 0 .and. index(objects, "libopen-pal") &
            & == 0, "rollcon loads MPI's libraries: " // objects)
        if (allocated(error)) return
        call run_rollcon("ldd", program // "-sweep", scratch // "/ldd-sweep.out", scratch &
            & // "/ldd-sweep.err", status)
        call check(error, status == 0 .and. index(file_text(scratch // "/ldd-sweep.out"), &
            & "libmpi_usempif08") > 0, "rollcon-sweep does not load libmpi_usempif08: " &
            & // file_text(scratch // "/ldd-sweep.out") // file_text(scratch // "/ldd-sweep.err"))
    end subroutine test_no_mpi

    !> rollcon copied alone into a folder: `rollcon sweep` says which program is missing
    !> where, and how to get it, with exit status 1 and no CSV; `rollcon sweep --help` still
    !> prints the help (rollcon's own).
    subroutine test_program_missing(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, study, folder, messages
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        folder = scratch // "/alone"
        call remove_folder(folder)
        call make_folder(folder)
        call execute_command_line("cp " // program // " " // folder // "/rollcon", &
            & exitstat=status)
        call check(error, status == 0, "cannot copy " // program)
        if (allocated(error)) return
        call write_study("test_sweep_alone", [character(len=60) :: "&study", &
            & "    scene = 'data/upright.nml' /", "&grid", "    disk%thickness = '0.01 0.1 2' /"], &
            & study)
        call run_rollcon(folder // "/rollcon", "sweep " // study // " --no-map -o " // folder &
            & // "/out", folder // ".out", folder // ".err", status)
        messages = file_text(folder // ".err")
        call check(error, status == 1, "exit status " // to_text(status) // ", not 1: " &
            & // messages)
        if (allocated(error)) return
        call check(error, index(messages, "rollcon: error: rollcon sweep runs the program " &
            & // "rollcon-sweep, which is not beside rollcon (") > 0 .and. index(messages, &
            & "/alone/rollcon-sweep is missing): build both with fpm build, or install both " &
            & // "with fpm install") > 0, "message: " // messages)
        if (allocated(error)) return
        call check(error, .not. file_exists(folder // "/out/test_sweep_alone.csv"), &
            & "a CSV was written")
        if (allocated(error)) return
        call run_rollcon(folder // "/rollcon", "sweep --help", folder // "-help.out", folder &
            & // "-help.err", status)
        call check(error, status == 0 .and. index(file_text(folder // "-help.out"), &
            & "usage: rollcon sweep STUDY.nml") == 1, "rollcon sweep --help without " &
            & // "rollcon-sweep: exit status " // to_text(status) // ": " // file_text(folder &
            & // "-help.out") // file_text(folder // "-help.err"))
    end subroutine test_program_missing

    !> The rollcon program, and mpirun on the PATH (else the test is skipped).
    subroutine mpi_program(program, error)
        character(len=:), allocatable, intent(out) :: program
        type(error_type), allocatable, intent(out) :: error
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("command -v mpirun > /dev/null 2>&1", exitstat=status)
        if (status /= 0) call skip_test(error, "mpirun is not on the PATH (Debian package " &
            & // "openmpi-bin; bash .ci/setup installs it)")
    end subroutine mpi_program

end module test_sweep_mpi
