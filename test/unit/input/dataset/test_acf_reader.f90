! SPDX-License-Identifier: MIT
!> ADAMS command files and the run's times given apart from a dataset (suite acf-reader): the
!> dataset a command file names (without .adm, from the command file's folder), the output
!> name, its commands (comments, `&` lines, INTEGRATOR, STOP); several SIMULATE commands
!> continuing one run, the same rows as one run where their steps agree and each segment's
!> own times where they do not; `rollcon run --end/--steps/--dtout` replacing a SIMULATE; and
!> the refusals, each with the file, the line and what was expected.
module test_acf_reader
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type
    use rollcon_adm_run, only : run_times_type
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, write_lines
    implicit none
    private

    public :: collect_acf_reader

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_acf_reader"
    !> The View pendulum (test/view): no SIMULATE of its own
    character(len=*), parameter :: pendulum = "test/view/view_export_pendulum.adm"
    !> A small dataset with no SIMULATE and an INTEGRATOR of its own
    character(len=48), parameter :: model(11) = [character(len=48) :: &
        & "a part falling freely", &
        & "PART/1, GROUND", &
        & "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1", &
        & "MARKER/3, PART=2, REULER=0D, 90D, 0D", &
        & "MARKER/4, PART=1", &
        & "ACCGRAV/", &
        & ", KGRAV=-9.81", &
        & "INTEGRATOR/", &
        & ", ERROR=1e-7", &
        & "OUTPUT/REQSAVE", &
        & "END"]
    !> Output times computed as the run computes them (k times a step, or a segment's end):
    !> equal to the last bit
    real(wp), parameter :: tol_times = 0.0_wp

contains

    subroutine collect_acf_reader(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("command-file-as-adams-reads-it", test_read), &
            & new_unittest("segments-of-one-step-as-one-run", test_same_step), &
            & new_unittest("segments-of-their-own-steps", test_own_steps), &
            & new_unittest("options-replace-simulate", test_options), &
            & new_unittest("command-file-refusals", test_refusals)]
    end subroutine collect_acf_reader

    !> A command file in a folder below its dataset names it without .adm and with `..`;
    !> its second line names the outputs (its comment dropped); comments, a command joined by
    !> `&`, INTEGRATOR (after the dataset's), two SIMULATE commands (DTOUT, then DURATION
    !> with STEPS), OUTPUT warned with the command file's name, and nothing after STOP read.
    subroutine test_read(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job

        call make_folder(scratch // "/commands")
        call write_lines(scratch // "/falling.adm", model)
        call write_lines(scratch // "/commands/run.acf", [character(len=60) :: &
            & "../falling", "first_run   ! ADAMS's output name", &
            & "! the analysis", "INTEGRATOR/RTOL=1e-9, &", "  FORMULATION=CVODE", &
            & "SIM/DYN, END=0.5, DTOUT=0.1", "SIMULATE/DYNAMIC, DURATION=0.5, STEPS=2", &
            & "OUTPUT/NOSEPARATOR", "STOP", "THIS IS NOT READ"])
        call load_job(scratch // "/commands/run.acf", job, error)
        if (allocated(error)) return
        call check(error, job%name == "first_run" .and. job%source%path == scratch &
            & // "/commands/../falling.adm", "output name '" // job%name // "', dataset '" &
            & // job%source%path // "'")
        if (allocated(error)) return
        associate (settings => job%source%settings)
            call check(error, settings%rtol == 1.0e-9_wp .and. settings%atol == 1.0e-7_wp &
                & .and. settings%uses_cvode(), "INTEGRATOR: the command file's RTOL and " &
                & // "FORMULATION after the dataset's ERROR (its ATOL kept)")
            if (allocated(error)) return
            call check(error, allocated(settings%output_times), "the output times")
            if (allocated(error)) return
            call check(error, settings%output_times, [0.1_wp, 2*0.1_wp, 3*0.1_wp, 4*0.1_wp, &
                & 0.5_wp, 0.5_wp + 0.25_wp, 1.0_wp], "the segments' output times", &
                & abs_tol=tol_times)
            if (allocated(error)) return
            call check(error, settings%end_time == 1.0_wp, "the end: " &
                & // to_text(settings%end_time))
            if (allocated(error)) return
        end associate
        call check(error, index(job%source%input_warning(), "OUTPUT REQSAVE (line 10), " &
            & // "run.acf: OUTPUT NOSEPARATOR (line 8)") > 0, "warning: " &
            & // job%source%input_warning())
    end subroutine test_read

    !> SIMULATE END=2, STEPS=200 then END=5, STEPS=300 (the step 0.01 s of both): the rows of
    !> one run to END=5, STEPS=500, bit for bit, the pendulum of test/view.
    subroutine test_same_step(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows(2)

        call make_folder(scratch)
        call write_lines(scratch // "/two.acf", [character(len=60) :: "../../" // pendulum, &
            & "two", "SIMULATE/DYNAMIC, END=2, STEPS=200", "SIMULATE/DYNAMIC, END=5, STEPS=300", &
            & "STOP"])
        call write_lines(scratch // "/one.acf", [character(len=60) :: "../../" // pendulum, &
            & "one", "SIMULATE/DYNAMIC, END=5, STEPS=500", "STOP"])
        call run_rows(scratch // "/two.acf", rows(1), error)
        if (allocated(error)) return
        call run_rows(scratch // "/one.acf", rows(2), error)
        if (allocated(error)) return
        call check(error, rows(1)%count == 501 .and. rows(2)%count == 501, "rows: " &
            & // to_text(rows(1)%count) // " and " // to_text(rows(2)%count))
        if (allocated(error)) return
        call check(error, all(rows(1)%rows(:, :501) == rows(2)%rows(:, :501)), "two SIMULATE " &
            & // "commands of one step are one run, bit for bit")
    end subroutine test_same_step

    !> SIMULATE END=1, STEPS=10 then END=2, DTOUT=0.05: rows at 0.1 ... 1 then 1.05 ... 2, and
    !> the state at t = 1 and t = 2 that of one run to END=2, DTOUT=0.1, bit for bit: the
    !> integrator's steps do not depend on where rows are written past the first (it steps to
    !> the end and interpolates to each output time; its first step is chosen from the first
    !> output time, 0.1 s in both).
    subroutine test_own_steps(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows(2)
        real(wp), allocatable :: expected(:)
        integer :: k

        call make_folder(scratch)
        call write_lines(scratch // "/steps.acf", [character(len=60) :: "../../" // pendulum, &
            & "", "SIMULATE/DYNAMIC, END=1, STEPS=10", "SIMULATE/DYNAMIC, END=2, DTOUT=0.05", &
            & "STOP"])
        call write_lines(scratch // "/fine.acf", [character(len=60) :: "../../" // pendulum, &
            & "", "SIMULATE/DYNAMIC, END=2, DTOUT=0.1", "STOP"])
        call run_rows(scratch // "/steps.acf", rows(1), error)
        if (allocated(error)) return
        call run_rows(scratch // "/fine.acf", rows(2), error)
        if (allocated(error)) return
        expected = [0.0_wp, (k*(1.0_wp/10), k = 1, 10), (1.0_wp + k*0.05_wp, k = 1, 20)]
        expected(size(expected)) = 2.0_wp
        call check(error, rows(1)%count == size(expected), "rows: " // to_text(rows(1)%count) &
            & // ", expected " // to_text(size(expected)))
        if (allocated(error)) return
        call check(error, rows(1)%rows(1, :rows(1)%count), expected, "the rows' times", &
            & abs_tol=tol_times)
        if (allocated(error)) return
        ! t = 1 is row 11 of both runs; t = 2 the last of each
        call check(error, rows(2)%count == 21, "the one run's rows: " // to_text(rows(2)%count))
        if (allocated(error)) return
        call check(error, rows(1)%rows(:, 11), rows(2)%rows(:, 11), "the state at t = 1", &
            & abs_tol=0.0_wp)
        if (allocated(error)) return
        call check(error, rows(1)%rows(:, rows(1)%count), rows(2)%rows(:, rows(2)%count), &
            & "the state at t = 2", abs_tol=0.0_wp)
    end subroutine test_own_steps

    !> --end, --steps and --dtout: each replaces its part of the dataset's SIMULATE and keeps
    !> the rest; with no SIMULATE, both are needed; they replace a command file's too.
    subroutine test_options(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(run_times_type) :: times

        call make_folder(scratch)
        call write_lines(scratch // "/timed.adm", [character(len=48) :: model(:10), &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "END"])
        times = given(end_time=2.0_wp)
        call load_job(scratch // "/timed.adm", job, error, times=times)
        if (allocated(error)) return
        call check(error, [job%source%settings%end_time, job%source%settings%output_step], &
            & [2.0_wp, 0.2_wp], "--end 2 keeps STEPS=10")
        if (allocated(error)) return
        times = given(steps=4.0_wp)
        call load_job(scratch // "/timed.adm", job, error, times=times)
        if (allocated(error)) return
        call check(error, [job%source%settings%end_time, job%source%settings%output_step], &
            & [1.0_wp, 0.25_wp], "--steps 4 keeps END=1")
        if (allocated(error)) return
        times = given(end_time=3.0_wp, dtout=0.5_wp)
        call load_job(scratch // "/timed.adm", job, error, times=times)
        if (allocated(error)) return
        call check(error, [job%source%settings%end_time, job%source%settings%output_step], &
            & [3.0_wp, 0.5_wp], "--end 3 --dtout 0.5")
        if (allocated(error)) return
        ! a dataset without SIMULATE, both given
        call write_lines(scratch // "/untimed.adm", model)
        times = given(end_time=2.0_wp, steps=8.0_wp)
        call load_job(scratch // "/untimed.adm", job, error, times=times)
        if (allocated(error)) return
        call check(error, [job%source%settings%end_time, job%source%settings%output_step], &
            & [2.0_wp, 0.25_wp], "--end 2 --steps 8 without SIMULATE")
        if (allocated(error)) return
        ! a command file's two SIMULATE commands, replaced by one
        call write_lines(scratch // "/replaced.acf", [character(len=48) :: "untimed", "", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "SIMULATE/DYNAMIC, END=3, STEPS=5"])
        times = given(dtout=0.5_wp)
        call load_job(scratch // "/replaced.acf", job, error, times=times)
        if (allocated(error)) return
        call check(error, [job%source%settings%end_time, job%source%settings%output_step], &
            & [3.0_wp, 0.5_wp], "--dtout 0.5 over the command file's END=3")
        if (allocated(error)) return
        call check(error, .not. allocated(job%source%settings%output_times), "one segment")
    end subroutine test_options

    !> The options of `rollcon run` as run_times_type holds them.
    function given(end_time, steps, dtout) result(times)
        real(wp), intent(in), optional :: end_time, steps, dtout
        type(run_times_type) :: times

        times%written = ""
        if (present(end_time)) then
            times%end_given = .true.
            times%end_time = end_time
            times%written = times%written // "--end " // to_text(end_time)
        end if
        if (present(steps)) then
            times%steps_given = .true.
            times%steps = steps
            times%written = trim(times%written // " --steps " // to_text(steps))
        end if
        if (present(dtout)) then
            times%dtout_given = .true.
            times%dtout = dtout
            times%written = trim(times%written // " --dtout " // to_text(dtout))
        end if
        times%written = trim(adjustl(times%written))
    end function given

    !> Each refused with the file, the line and what was expected.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: file = scratch // "/refused.acf"
        character(len=60) :: commands(9, 3)
        character(len=600) :: expected(9)
        type(job_type) :: job
        type(error_type), allocatable :: refused
        type(run_times_type) :: times
        integer :: k

        call make_folder(scratch)
        call write_lines(scratch // "/untimed.adm", model)
        commands = ""
        commands(1, :) = [character(len=60) :: "", "out", "STOP"]
        expected(1) = file // ":1: the first line of a command file names the dataset (MODEL " &
            & // "or MODEL.adm, from the command file's folder), got an empty line"
        commands(2, :) = [character(len=60) :: "nothere", "", "STOP"]
        expected(2) = file // ":1: no dataset " // scratch // "/nothere.adm (the first line " &
            & // "names it, from the command file's folder; .adm is added to a name without " &
            & // "an extension)"
        commands(3, :) = [character(len=60) :: "untimed", "runs/out", "STOP"]
        expected(3) = file // ":2: the output name 'runs/out' holds a folder; rollcon writes " &
            & // "its outputs into --output DIR (output/ by default): give a name only"
        commands(4, :) = [character(len=60) :: "untimed", "", "SAVE/FILE=x"]
        expected(4) = file // ":3: 'SAVE' is not a command of the supported subset (SIMULATE, " &
            & // "INTEGRATOR, OUTPUT, STOP, DEBUG, PREFERENCES, EQUILIBRIUM, IC, KINEMATICS); a " &
            & // "run is not saved and reloaded"
        commands(5, :) = [character(len=60) :: "untimed", "", "SIMULATE/TRANSIENT"]
        expected(5) = file // ":3: SIMULATE TRANSIENT: rollcon runs SIMULATE/DYNAMIC, " &
            & // "/KINEMATIC and /STATIC; a dynamic run starts from the start its " &
            & // "initial-conditions analysis makes consistent (docs/initial-conditions.md)"
        commands(6, :) = [character(len=60) :: "untimed", "", &
            & "SIM/DYN, END=2, STEPS=2|SIM/DYN, END=1, STEPS=2"]
        expected(6) = file // ":4: SIMULATE END gives an end of 1 s, not after the end of the " &
            & // "SIMULATE before it (2 s): each SIMULATE goes on from where the one before ended"
        commands(7, :) = [character(len=60) :: "untimed", "", &
            & "SIM/DYN, END=2, STEPS=2|INTEGRATOR/ERROR=1e-9"]
        expected(7) = file // ":4: INTEGRATOR after a SIMULATE: rollcon runs the SIMULATE " &
            & // "commands as one run with one integrator; give INTEGRATOR before the first " &
            & // "SIMULATE"
        commands(8, :) = [character(len=60) :: "untimed", "", "OUTPUT/REQSAVE|STOP"]
        expected(8) = file // ": no SIMULATE command, and " // scratch // "/untimed.adm has " &
            & // "no SIMULATE statement: add SIMULATE/DYNAMIC, END=t, STEPS=n to the command " &
            & // "file (before STOP), or give rollcon run " // file // " --end T --steps N"
        commands(9, :) = [character(len=60) :: "untimed", "", "FILE/MODEL=x|SHOW/STATUS"]
        expected(9) = file // ": 2 commands are not read by rollcon (SIMULATE, INTEGRATOR, " &
            & // "OUTPUT, STOP, DEBUG, PREFERENCES, EQUILIBRIUM, IC, KINEMATICS); nothing was " &
            & // "run:" // new_line("a") // "  " // file // ":3: 'FILE' is not a command of " &
            & // "the supported subset (SIMULATE, INTEGRATOR, OUTPUT, STOP, DEBUG, " &
            & // "PREFERENCES, EQUILIBRIUM, IC, KINEMATICS); a command file runs the one " &
            & // "dataset its first line names" // new_line("a") // "  " // file // ":4: " &
            & // "'SHOW' is not a command of the supported subset (SIMULATE, INTEGRATOR, " &
            & // "OUTPUT, STOP, DEBUG, PREFERENCES, EQUILIBRIUM, IC, KINEMATICS)"
        do k = 1, size(expected)
            call write_lines(file, bars(commands(k, :)))
            call load_job(file, job, refused, times=times)
            call check(error, allocated(refused), "case " // to_text(k) // ": accepted")
            if (allocated(error)) return
            call check(error, refused%message == trim(expected(k)), "case " // to_text(k) &
                & // ": got '" // refused%message // "', expected '" // trim(expected(k)) &
                & // "'")
            if (allocated(error)) return
            deallocate(refused)
        end do
        ! the dataset without SIMULATE, run with no command file: both ways named
        call load_job(scratch // "/untimed.adm", job, refused)
        call check(error, allocated(refused), "a dataset with no run accepted")
        if (allocated(error)) return
        call check(error, index(refused%message, "no SIMULATE statement") > 0 .and. &
            & index(refused%message, "rollcon run MODEL.acf") > 0 .and. &
            & index(refused%message, "--end T --steps N") > 0, refused%message)
    end subroutine test_refusals

    !> The lines, each '|' a new line.
    function bars(lines) result(split)
        character(len=*), intent(in) :: lines(:)
        character(len=60), allocatable :: split(:)
        character(len=:), allocatable :: rest
        integer :: i, bar

        allocate(split(0))
        do i = 1, size(lines)
            rest = trim(lines(i))
            bar = index(rest, "|")
            do while (bar > 0)
                split = [character(len=60) :: split, rest(:bar - 1)]
                rest = rest(bar + 1:)
                bar = index(rest, "|")
            end do
            split = [character(len=60) :: split, rest]
        end do
    end function bars

    !> Load the input at path and run it, its rows kept.
    subroutine run_rows(path, rows, error)
        character(len=*), intent(in) :: path
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
    end subroutine run_rows

end module test_acf_reader
