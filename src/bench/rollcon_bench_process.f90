! SPDX-License-Identifier: MIT
!> What a user waits for: `rollcon run SCENE` timed as a child process (wall, and user + system
!> CPU from getrusage of the children), split into start-up (a `rollcon --help` child), the
!> integration with its output rows (the CPU time the run's summary reports) and the rest
!> (reading the scene, setting up, the summary file); and the scene file or dataset that runs a
!> scene or a dataset with other run settings (the benchmark's whole-process column).
module rollcon_bench_process
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_clock, only : cpu_seconds, cpu_children
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text, shell_quote, lower_case, upper_case
    use rollcon_run_settings, only : run_settings_type
    use rollcon_run_keys, only : choice_name
    implicit none
    private

    public :: process_cost_type, measure_process, write_scene_with_settings
    public :: write_dataset_with_settings

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

    !> Time `executable run scene --quiet --output work_dir` (its outputs named output_name)
    !> and `executable --help`, each as a child of this process: CPU from getrusage of the
    !> children before and after (the shell that starts it included, about a millisecond).
    !> With repeats (default 1), each is run that many times and its median kept, the
    !> integration's CPU time that of the median run: one child of some 30 ms varied by a
    !> quarter from one benchmark run to the next (page faults, the loader, the CPU's clock).
    subroutine measure_process(executable, scene, output_name, work_dir, cost, error, repeats)
        !> How this program was started (argument 0); a scene's name or file; the name of the
        !> run's outputs (the scene's name: docs/outputs.md); the folder for them
        character(len=*), intent(in) :: executable, scene, output_name, work_dir
        type(process_cost_type), intent(out) :: cost
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: repeats
        real(wp), allocatable :: cpu(:), wall(:), startup(:), integration(:)
        integer :: stat, k, n, middle

        n = 1
        if (present(repeats)) n = max(1, repeats)
        allocate(cpu(n), wall(n), startup(n), integration(n))
        do k = 1, n
            call child_cpu(shell_quote(executable) // " run " // shell_quote(scene) &
                & // " --quiet --output " // shell_quote(work_dir) // " > " &
                & // shell_quote(work_dir // "/process_run.log") // " 2>&1", cpu(k), wall(k), &
                & stat)
            if (stat /= 0) then
                call fatal_error(error, "'" // executable // " run " // scene // "' failed (exit " &
                    & // to_text(stat) // "); see " // work_dir // "/process_run.log", stat_io)
                return
            end if
            call read_summary_cpu(work_dir // "/" // output_name // ".summary.txt", &
                & integration(k), error)
            if (allocated(error)) return
            call child_cpu(shell_quote(executable) // " --help > /dev/null 2>&1", startup(k), &
                & stat=stat)
        end do
        middle = median_index(cpu)
        cost%cpu = cpu(middle)
        cost%wall = wall(middle)
        cost%integration_cpu = integration(middle)
        cost%startup_cpu = startup(median_index(startup))
        cost%rest_cpu = cost%cpu - cost%startup_cpu - cost%integration_cpu
    end subroutine measure_process

    !> Index of the median of values (the lower middle one of an even count).
    pure integer function median_index(values) result(middle)
        real(wp), intent(in) :: values(:)
        integer :: i, below

        middle = 1
        do i = 1, size(values)
            below = count(values < values(i)) + count(values(:i - 1) == values(i))
            if (below == (size(values) - 1)/2) then
                middle = i
                return
            end if
        end do
    end function median_index

    !> Run command in a child shell; its user + system CPU [s] (getrusage of the children) and
    !> wall time [s], and its exit status.
    subroutine child_cpu(command, cpu, wall, stat)
        character(len=*), intent(in) :: command
        real(wp), intent(out) :: cpu
        real(wp), intent(out), optional :: wall
        integer, intent(out) :: stat
        real(wp) :: before
        integer(int64) :: start, finish, rate

        before = cpu_seconds(cpu_children)
        call system_clock(start, rate)
        call execute_command_line(command, exitstat=stat)
        call system_clock(finish)
        cpu = cpu_seconds(cpu_children) - before
        if (present(wall)) wall = real(finish - start, wp)/real(rate, wp)
    end subroutine child_cpu

    !> A copy of the scene file source_path at path whose &run group is settings (every run
    !> key written; the source's own &run group left out): the same scene run another way.
    subroutine write_scene_with_settings(source_path, settings, path, error)
        character(len=*), intent(in) :: source_path, path
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        character(len=1024) :: line
        integer :: source, copy, stat
        logical :: in_run

        call open_copy(source_path, path, source, copy, error)
        if (allocated(error)) return
        in_run = .false.
        do
            read(source, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! the &run group, from its first line to the line that closes it
            if (index(adjustl(lower_case(line)), "&run") == 1) in_run = .true.
            if (.not. in_run) write(copy, '(a)') trim(line)
            if (in_run .and. index(adjustl(line), "/") == 1) in_run = .false.
        end do
        close(source)
        write(copy, '(a)') "&run", &
            & "    end_time = " // real_text(settings%end_time), &
            & "    output_step = " // real_text(settings%output_step), &
            & "    formulation = '" // choice_name("formulation", settings%formulation) // "'", &
            & "    method = '" // choice_name("method", settings%method) // "'", &
            & "    drift = '" // choice_name("drift", settings%drift) // "'", &
            & "    jacobian = '" // choice_name("jacobian", settings%jacobian) // "'", &
            & "    rtol = " // real_text(settings%rtol), &
            & "    atol = " // real_text(settings%atol), &
            & "    baumgarte_rate = " // real_text(settings%baumgarte_rate), &
            & "    max_steps = " // to_text(settings%max_steps), &
            & "/"
        close(copy, iostat=stat)
        if (stat /= 0) call fatal_error(error, path // ": cannot write", stat_io)
    end subroutine write_scene_with_settings

    !> A copy of the dataset at source_path at path whose INTEGRATOR and SIMULATE statements
    !> are settings (every INTEGRATOR keyword of rollcon's written, SIMULATE's END and DTOUT;
    !> the source's own statements and their continuation lines left out, the new ones written
    !> before END): the same dataset run another way. A statement is known by its name or a
    !> prefix of it of three letters or more (INTEG, SIM).
    subroutine write_dataset_with_settings(source_path, settings, path, error)
        character(len=*), intent(in) :: source_path, path
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        character(len=4096) :: line
        character(len=:), allocatable :: word
        integer :: source, copy, stat, cut
        logical :: skipping

        call open_copy(source_path, path, source, copy, error)
        if (allocated(error)) return
        skipping = .false.
        read(source, '(a)', iostat=stat) line
        ! the title line, whatever it holds
        if (stat == 0) write(copy, '(a)') trim(line)
        do
            read(source, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! a continuation line belongs to the statement above
            if (index(adjustl(line), ",") == 1) then
                if (.not. skipping) write(copy, '(a)') trim(line)
                cycle
            end if
            cut = scan(adjustl(line), "/, !")
            word = upper_case(trim(adjustl(line)))
            if (cut > 1) word = word(:cut - 1)
            if (word == "END") exit
            skipping = (len(word) >= 3 .and. (index("INTEGRATOR", word) == 1 &
                & .or. index("SIMULATE", word) == 1))
            if (.not. skipping) write(copy, '(a)') trim(line)
        end do
        close(source)
        write(copy, '(a)') "INTEGRATOR/FORMULATION=" &
            & // choice_name("formulation", settings%formulation) &
            & // ", METHOD=" // choice_name("method", settings%method) &
            & // ", DRIFT=" // choice_name("drift", settings%drift), &
            & ", JACOBIAN=" // choice_name("jacobian", settings%jacobian) &
            & // ", SOLVER=" // choice_name("linear_solver", settings%linear_solver), &
            & ", RTOL=" // real_text(settings%rtol) // ", ATOL=" // real_text(settings%atol), &
            & ", BAUMGARTE=" // real_text(settings%baumgarte_rate) // ", MAXSTEPS=" &
            & // to_text(settings%max_steps), &
            & "SIMULATE/DYNAMIC, END=" // real_text(settings%end_time) // ", DTOUT=" &
            & // real_text(settings%output_step), &
            & "END"
        close(copy, iostat=stat)
        if (stat /= 0) call fatal_error(error, path // ": cannot write", stat_io)
    end subroutine write_dataset_with_settings

    !> Open source_path to read (unit source) and path to write anew (unit copy); an error
    !> names the file that cannot be opened (neither is left open then).
    subroutine open_copy(source_path, path, source, copy, error)
        character(len=*), intent(in) :: source_path, path
        integer, intent(out) :: source, copy
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        open(newunit=source, file=source_path, status="old", action="read", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, source_path // ": cannot read", stat_io)
            return
        end if
        open(newunit=copy, file=path, status="replace", action="write", iostat=stat)
        if (stat /= 0) then
            close(source)
            call fatal_error(error, path // ": cannot write", stat_io)
        end if
    end subroutine open_copy

    !> A number as the scene and dataset files write it: all 17 digits.
    function real_text(value) result(text)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=32) :: buffer

        write(buffer, '(es24.16e3)') value
        text = trim(adjustl(buffer))
    end function real_text

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
