! SPDX-License-Identifier: MIT
!> What a user waits for: `rollcon run SCENE` timed as a child process (wall and CPU), split
!> into start-up (a `rollcon --help` child), the integration with its output rows (the CPU time
!> the run's summary reports) and the rest (reading the scene, setting up, the summary file).
module rollcon_bench_process
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text, shell_quote
    implicit none
    private

    public :: process_cost_type, measure_process

    !> Times of one `rollcon run` [s]
    type :: process_cost_type
        !> Wall and CPU (user + system) time of the whole child process
        real(wp) :: wall = 0.0_wp, cpu = 0.0_wp
        !> CPU time of a child that only starts and prints its help
        real(wp) :: startup_cpu = 0.0_wp
        !> CPU time of the integration, output rows included (the run's summary)
        real(wp) :: integration_cpu = 0.0_wp
        !> cpu - startup_cpu - integration_cpu: scene reading, set-up, summary
        real(wp) :: rest_cpu = 0.0_wp
    end type process_cost_type

contains

    !> Time `executable run scene --quiet --output work_dir` and `executable --help`.
    subroutine measure_process(executable, scene, work_dir, cost, error)
        !> How this program was started (argument 0)
        character(len=*), intent(in) :: executable, scene, work_dir
        type(process_cost_type), intent(out) :: cost
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: script, run_time, help_time
        real(wp) :: times(3)
        integer :: unit, stat

        script = work_dir // "/process.sh"
        run_time = work_dir // "/process_run.time"
        help_time = work_dir // "/process_help.time"
        open(newunit=unit, file=script, status="replace", action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, script // ": cannot write", stat_io)
            return
        end if
        ! bash's time keyword: wall, user and system seconds of the group
        write(unit, '(a)') "TIMEFORMAT='%R %U %S'", &
            & "{ time " // shell_quote(executable) // " run " // shell_quote(scene) &
            & // " --quiet --output " // shell_quote(work_dir) // " > " &
            & // shell_quote(work_dir // "/process_run.log") // " 2>&1; } 2> " &
            & // shell_quote(run_time) // " || exit 1", &
            & "{ time " // shell_quote(executable) // " --help > /dev/null 2>&1; } 2> " &
            & // shell_quote(help_time)
        close(unit)
        call execute_command_line("bash " // shell_quote(script), exitstat=stat)
        if (stat /= 0) then
            call fatal_error(error, "'" // executable // " run " // scene // "' failed (exit " &
                & // to_text(stat) // "); see " // work_dir // "/process_run.log", stat_io)
            return
        end if
        call read_times(run_time, times, error)
        if (allocated(error)) return
        cost%wall = times(1)
        cost%cpu = times(2) + times(3)
        call read_times(help_time, times, error)
        if (allocated(error)) return
        cost%startup_cpu = times(2) + times(3)
        call read_summary_cpu(work_dir // "/" // scene // ".summary.txt", cost%integration_cpu, &
            & error)
        if (allocated(error)) return
        cost%rest_cpu = cost%cpu - cost%startup_cpu - cost%integration_cpu
    end subroutine measure_process

    !> Three numbers written by bash's time.
    subroutine read_times(path, times, error)
        character(len=*), intent(in) :: path
        real(wp), intent(out) :: times(3)
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat

        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat == 0) read(unit, *, iostat=stat) times
        if (stat == 0) close(unit)
        if (stat /= 0) call fatal_error(error, path // ":1: expected three times [s] " &
            & // "(wall, user, system) from bash's time", stat_io)
    end subroutine read_times

    !> The number after "CPU time:" in a run's summary file [s].
    subroutine read_summary_cpu(path, seconds, error)
        character(len=*), intent(in) :: path
        real(wp), intent(out) :: seconds
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: line
        integer :: unit, stat, number
        logical :: opened

        seconds = 0.0_wp
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        opened = stat == 0
        number = 0
        do while (stat == 0)
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            number = number + 1
            if (index(line, "CPU time:") /= 1) cycle
            read(line(10:), *, iostat=stat) seconds
            close(unit)
            if (stat /= 0) call fatal_error(error, path // ":" // to_text(number) &
                & // ": 'CPU time:' must be followed by seconds, got '" // trim(line) // "'", &
                & stat_io)
            return
        end do
        if (opened) close(unit)
        call fatal_error(error, path // ": no line 'CPU time: <seconds> s'", stat_io)
    end subroutine read_summary_cpu

end module rollcon_bench_process
