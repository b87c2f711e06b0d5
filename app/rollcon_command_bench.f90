! SPDX-License-Identifier: MIT
!> `rollcon bench`: work-precision of every way of solving, on a ladder of tolerances, against
!> the reduced ODE of the disk (reference and limit), with per-part and whole-process costs.
module rollcon_command_bench
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : wp, error_type, rolling_disk_ucosub, fatal_error, stat_input, stat_io, &
        & to_text, shell_quote, scene_type, read_scene, scene_path, method_type, &
        & benchmark_methods, benchmark_row_type, benchmark_scene, benchmark_header, &
        & write_benchmark_row, evaluation_costs, part_costs_type, measure_part_costs, &
        & accuracy_line, process_cost_type, measure_process, run_gnuplot, gnuplot_string
    implicit none
    private

    public :: bench_command, machine_name

    !> The accuracy the headline ratio is quoted at [m] (issue #13)
    real(wp), parameter :: accuracy_target = 1.0e-6_wp

    !> What `rollcon bench` was asked for
    type :: bench_options_type
        character(len=:), allocatable :: output_dir, scene_list
        logical :: quick = .false.
        integer :: repeats = 3
        !> Cut every scene here [s] (negative: no cut)
        real(wp) :: end_time = -1.0_wp
        real(wp), allocatable :: tolerances(:)
        real(wp) :: reference_rtol = 1.0e-13_wp
    end type bench_options_type

contains

    !> Parse the arguments after `bench`, run, write DIR/bench.csv and one plot per scene.
    subroutine bench_command(first_argument, error)
        !> Index of the first argument after `bench`
        integer, intent(in) :: first_argument
        type(error_type), allocatable, intent(out) :: error
        type(bench_options_type) :: options
        character(len=:), allocatable :: name
        integer :: unit, stat, start, comma, process_unit
        logical :: help

        call read_bench_options(first_argument, options, help, error)
        if (allocated(error) .or. help) return
        call execute_command_line("mkdir -p " // shell_quote(options%output_dir), exitstat=stat)
        open(newunit=unit, file=options%output_dir // "/bench.csv", status="replace", &
            & action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, options%output_dir // "/bench.csv: cannot write", stat_io)
            return
        end if
        write(unit, '(a)') benchmark_header()
        write(output_unit, '(a)') "bench: " // machine_name()
        process_unit = -1
        if (.not. options%quick) then
            open(newunit=process_unit, file=options%output_dir // "/bench_process.csv", &
                & status="replace", action="write", iostat=stat)
            if (stat /= 0) then
                call fatal_error(error, options%output_dir // "/bench_process.csv: cannot " &
                    & // "write", stat_io)
                return
            end if
            write(process_unit, '(a)') "scene,wall_s,cpu_s,startup_cpu_s,integration_cpu_s," &
                & // "reading_setup_summary_cpu_s"
        end if
        start = 1
        do
            comma = index(options%scene_list(start:), ",")
            if (comma == 0) then
                name = options%scene_list(start:)
            else
                name = options%scene_list(start:start + comma - 2)
            end if
            call bench_scene(name, options, unit, process_unit, error)
            if (allocated(error)) return
            if (comma == 0) exit
            start = start + comma
        end do
        close(unit)
        if (process_unit /= -1) close(process_unit)
        call plot_work_precision(options%output_dir, options%scene_list, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "bench: wrote " // options%output_dir // "/bench.csv and " &
            & // options%output_dir // "/bench_<scene>.png"
    end subroutine bench_command

    !> The command line of `rollcon bench`; help is true when --help was asked (and printed).
    subroutine read_bench_options(first_argument, options, help, error)
        integer, intent(in) :: first_argument
        type(bench_options_type), intent(out) :: options
        logical, intent(out) :: help
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: argument, value
        integer :: i, stat

        help = .false.
        options%output_dir = "output"
        options%scene_list = ""
        i = first_argument
        do while (i <= command_argument_count())
            call get_command_argument(i, argument)
            select case (trim(argument))
            case ("-h", "--help")
                call print_help()
                help = .true.
                return
            case ("--quick")
                options%quick = .true.
            case ("--output", "-o", "--scenes", "--repeats", "--end-time")
                i = i + 1
                if (i > command_argument_count()) then
                    call fatal_error(error, trim(argument) // " needs a value", stat_input)
                    return
                end if
                call get_command_argument(i, value)
                stat = 0
                select case (trim(argument))
                case ("--output", "-o")
                    options%output_dir = trim(value)
                case ("--scenes")
                    options%scene_list = trim(value)
                case ("--repeats")
                    read(value, *, iostat=stat) options%repeats
                    if (stat == 0 .and. options%repeats < 1) stat = 1
                case ("--end-time")
                    read(value, *, iostat=stat) options%end_time
                    if (stat == 0 .and. .not. options%end_time > 0.0_wp) stat = 1
                end select
                if (stat /= 0) then
                    call fatal_error(error, trim(argument) // " expects a positive number, " &
                        & // "got '" // trim(value) // "'", stat_input)
                    return
                end if
            case default
                call fatal_error(error, "bench: unknown argument '" // trim(argument) &
                    & // "'; run 'rollcon bench --help'", stat_input)
                return
            end select
            i = i + 1
        end do
        if (options%quick) then
            ! one scene, two tolerances, one second: the check the test suite runs
            if (len(options%scene_list) == 0) options%scene_list = "tipping_coin"
            options%tolerances = [1.0e-4_wp, 1.0e-6_wp]
            options%reference_rtol = 1.0e-10_wp
            options%repeats = 1
            if (options%end_time < 0.0_wp) options%end_time = 1.0_wp
        else
            if (len(options%scene_list) == 0) options%scene_list = "coin,tipping_coin," &
                & // "fast_upright,near_flat,long_run"
            options%tolerances = [(10.0_wp**(-i), i = 3, 12)]
            options%reference_rtol = 1.0e-13_wp
        end if
    end subroutine read_bench_options

    !> One scene: its unit costs, every method on the tolerance ladder (rows to unit), the
    !> headline ratio per method, and (outside --quick) the whole-process cost.
    subroutine bench_scene(name, options, unit, process_unit, error)
        character(len=*), intent(in) :: name
        type(bench_options_type), intent(in) :: options
        integer, intent(in) :: unit, process_unit
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(benchmark_row_type), allocatable :: rows(:)
        type(part_costs_type) :: costs
        type(method_type) :: methods(size(benchmark_methods()))
        real(wp) :: rhs_seconds, residual_seconds, solve_seconds
        integer :: i

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        if (options%end_time > 0.0_wp) scene%run%end_time = min(scene%run%end_time, &
            & options%end_time)
        scene%run%output_step = min(scene%run%output_step, scene%run%end_time)
        call evaluation_costs(scene, rolling_disk_ucosub, 20000, rhs_seconds, &
            & residual_seconds, solve_seconds, error)
        if (allocated(error)) return
        write(output_unit, '(a, 3(f8.3, a), f6.2, a)') "bench: " // name &
            & // ": one ODE right-hand side", 1.0e6_wp*rhs_seconds, " us, one DAE residual", &
            & 1.0e6_wp*residual_seconds, " us, one LAPACK factor+solve of the saddle-point " &
            & // "system", 1.0e6_wp*solve_seconds, " us (right-hand side / solve = ", &
            & rhs_seconds/solve_seconds, ")"
        call measure_part_costs(scene, rolling_disk_ucosub, 20000, options%output_dir &
            & // "/bench_scratch.csv", costs, error)
        if (allocated(error)) return
        write(output_unit, '(a, 5(f8.3, a))') "bench: " // name &
            & // ": unit costs: right-hand side", 1.0e6_wp*costs%rhs, " us, residual", &
            & 1.0e6_wp*costs%residual, " us, event functions", 1.0e6_wp*costs%root, &
            & " us, output row", 1.0e6_wp*costs%output, " us, its CSV line", &
            & 1.0e6_wp*costs%csv_line, " us"
        call benchmark_scene(scene, rolling_disk_ucosub, benchmark_methods(), &
            & options%tolerances, options%reference_rtol, options%repeats, rows, error, &
            & output_unit, costs)
        if (allocated(error)) return
        do i = 1, size(rows)
            write(unit, '(a)') write_benchmark_row(rows(i))
        end do
        flush(unit)
        methods = benchmark_methods()
        do i = 1, size(methods)
            if (methods(i)%formulation == "reduced") cycle
            write(output_unit, '(a)') accuracy_line(rows, name, trim(methods(i)%name), &
                & accuracy_target)
        end do
        if (.not. options%quick) call process_cost(name, options%output_dir, process_unit, error)
    end subroutine bench_scene

    !> One log-log plot per scene: largest position error against CPU time, a curve per method
    !> (the reduced ODE's among them), drawn by gnuplot through rollcon_gnuplot.
    subroutine plot_work_precision(output_dir, scene_list, error)
        character(len=*), intent(in) :: output_dir, scene_list
        type(error_type), allocatable, intent(out) :: error
        type(method_type) :: methods(size(benchmark_methods()))
        character(len=:), allocatable :: script_path, scene, csv
        integer :: unit, stat, m, start, comma

        methods = benchmark_methods()
        script_path = output_dir // "/bench.gp"
        csv = gnuplot_string(output_dir // "/bench.csv")
        open(newunit=unit, file=script_path, status="replace", action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, script_path // ": cannot write", stat_io)
            return
        end if
        write(unit, '(a)') "set datafile separator ','", "set terminal png size 900,650", &
            & "set logscale xy", "set format x '10^{%L}'", "set format y '10^{%L}'", &
            & "set xlabel 'CPU time [s]'", &
            & "set ylabel 'largest position error against the reduced ODE " &
            & // "(Adams, rtol 1e-13) [m]'", &
            & "set key outside right", "set grid"
        start = 1
        do
            comma = index(scene_list(start:), ",")
            if (comma == 0) then
                scene = scene_list(start:)
            else
                scene = scene_list(start:start + comma - 2)
            end if
            write(unit, '(a)') "set output " // gnuplot_string(output_dir // "/bench_" // scene &
                & // ".png"), "set title " // gnuplot_string("work-precision: " // scene &
                & // " (tolerances 1e-3 to 1e-12)") // " noenhanced"
            do m = 1, size(methods)
                write(unit, '(a)', advance="no") merge("plot ", "     ", m == 1) // csv &
                    & // " using (strcol(1) eq " // gnuplot_string(scene) // " && strcol(2) eq " &
                    & // gnuplot_string(trim(methods(m)%name)) // " ? $4 : 1/0):" &
                    & // "($8 > 0 ? $8 : 1/0) with linespoints title " &
                    & // gnuplot_string(trim(methods(m)%name)) // " noenhanced"
                if (m < size(methods)) then
                    write(unit, '(a)') ", \"
                else
                    write(unit, '(a)') ""
                end if
            end do
            if (comma == 0) exit
            start = start + comma
        end do
        close(unit)
        call run_gnuplot(script_path, error)
    end subroutine plot_work_precision

    !> Time `rollcon run SCENE` as a child process; print it and add a line to process_unit.
    subroutine process_cost(scene, output_dir, process_unit, error)
        character(len=*), intent(in) :: scene, output_dir
        integer, intent(in) :: process_unit
        type(error_type), allocatable, intent(out) :: error
        type(process_cost_type) :: cost
        character(len=1024) :: executable
        character(len=200) :: numbers

        call get_command_argument(0, executable)
        call execute_command_line("mkdir -p " // shell_quote(output_dir // "/process"))
        call measure_process(trim(executable), scene, output_dir // "/process", cost, error)
        if (allocated(error)) return
        write(numbers, '(5(es13.5e3, :, ","))') cost%wall, cost%cpu, cost%startup_cpu, &
            & cost%integration_cpu, cost%rest_cpu
        write(process_unit, '(a)') scene // "," // trim(numbers)
        flush(process_unit)
        write(output_unit, '(a, 5(f8.3, a))') "bench: " // scene // ": whole process 'rollcon " &
            & // "run " // scene // "': wall", cost%wall, " s, CPU", cost%cpu, " s = start-up", &
            & cost%startup_cpu, " s + integration with output rows", cost%integration_cpu, &
            & " s + scene reading, set-up and summary", cost%rest_cpu, " s"
    end subroutine process_cost

    !> CPU model and core count, for the record.
    function machine_name() result(name)
        character(len=:), allocatable :: name
        character(len=256) :: line
        integer :: unit, stat, cores

        name = "unknown CPU"
        cores = 0
        open(newunit=unit, file="/proc/cpuinfo", status="old", action="read", iostat=stat)
        if (stat /= 0) return
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, "model name") == 1) then
                name = trim(adjustl(line(index(line, ":") + 1:)))
                cores = cores + 1
            end if
        end do
        close(unit)
        name = name // ", " // to_text(cores) // " cores"
    end function machine_name

    subroutine print_help()
        write(output_unit, '(a)') &
            & "usage: rollcon bench [--quick] [--scenes A,B,...] [--repeats N] [--end-time T]", &
            & "                     [--output DIR]", &
            & "", &
            & "Work-precision benchmark. For each scene (default: coin, tipping_coin,", &
            & "fast_upright, near_flat, long_run) and each way of solving (IDA; CVODE BDF with", &
            & "projection, Baumgarte or no drift control; CVODE Adams; analytic against", &
            & "difference-quotient Jacobians) on the tolerances rtol = 1e-3 ... 1e-12", &
            & "(atol = 1e-2 rtol) it measures the CPU time (median of N runs, default 3; runs", &
            & "over a second are not repeated), steps, function and Jacobian evaluations, the", &
            & "largest distance of the disk's centre from the independent reference, the", &
            & "disk's reduced ODE (minimal coordinates, ucon/reduced/) by CVODE Adams at rtol", &
            & "1e-13 [m], the largest constraint residual [m/s] and the relative energy drift.", &
            & "The reduced ODE is also the limit: every row carries the CPU time of the reduced", &
            & "ODE at the same rtol and multistep method, measured in the same run, and the", &
            & "ratio; per scene the cheapest run within 1e-6 m of the reference is compared", &
            & "with the cheapest reduced run within it. Each row splits its CPU time into", &
            & "right-hand sides (or residuals), event functions, output rows (counts times unit", &
            & "costs measured in the same run) and SUNDIALS' remainder. Outside --quick, the", &
            & "whole process 'rollcon run SCENE' is timed as a child (DIR/bench_process.csv).", &
            & "Writes DIR/bench.csv and DIR/bench_<scene>.png (gnuplot); DIR defaults to output.", &
            & "  --quick       tipping_coin over 1 s at rtol 1e-4 and 1e-6, one run each", &
            & "  --end-time T  cut every scene at T seconds"
    end subroutine print_help

end module rollcon_command_bench
