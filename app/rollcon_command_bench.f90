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

    public :: bench_command

contains

    !> Parse the arguments after `bench`, run, write DIR/bench.csv and one plot per scene.
    subroutine bench_command(first_argument, error)
        !> Index of the first argument after `bench`
        integer, intent(in) :: first_argument
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: argument
        character(len=:), allocatable :: output_dir, scene_list
        type(benchmark_row_type), allocatable :: rows(:)
        type(scene_type) :: scene
        real(wp), allocatable :: tolerances(:)
        real(wp) :: rhs_seconds, residual_seconds, solve_seconds, reference_rtol, end_time
        type(part_costs_type) :: costs
        type(method_type) :: methods(size(benchmark_methods()))
        !> The accuracy the headline ratio is quoted at [m] (issue #13)
        real(wp), parameter :: accuracy_target = 1.0e-6_wp
        integer :: i, repeats, unit, stat, start, comma, process_unit
        logical :: quick

        output_dir = "output"
        quick = .false.
        repeats = 3
        scene_list = ""
        end_time = -1.0_wp
        i = first_argument
        do while (i <= command_argument_count())
            call get_command_argument(i, argument)
            select case (trim(argument))
            case ("-h", "--help")
                call print_help()
                return
            case ("--quick")
                quick = .true.
            case ("--output", "-o", "--scenes", "--repeats", "--end-time")
                i = i + 1
                if (i > command_argument_count()) then
                    call fatal_error(error, trim(argument) // " needs a value", stat_input)
                    return
                end if
                select case (trim(argument))
                case ("--output", "-o")
                    call get_command_argument(i, argument)
                    output_dir = trim(argument)
                case ("--scenes")
                    call get_command_argument(i, argument)
                    scene_list = trim(argument)
                case ("--repeats", "--end-time")
                    block
                        character(len=512) :: value
                        call get_command_argument(i, value)
                        if (trim(argument) == "--repeats") then
                            read(value, *, iostat=stat) repeats
                            if (stat == 0 .and. repeats < 1) stat = 1
                        else
                            read(value, *, iostat=stat) end_time
                            if (stat == 0 .and. .not. end_time > 0.0_wp) stat = 1
                        end if
                        if (stat /= 0) then
                            call fatal_error(error, trim(argument) // " expects a positive " &
                                & // "number, got '" // trim(value) // "'", stat_input)
                            return
                        end if
                    end block
                end select
            case default
                call fatal_error(error, "bench: unknown argument '" // trim(argument) &
                    & // "'; run 'rollcon bench --help'", stat_input)
                return
            end select
            i = i + 1
        end do

        if (quick) then
            ! one scene, two tolerances, one second: the check the test suite runs
            if (len(scene_list) == 0) scene_list = "tipping_coin"
            tolerances = [1.0e-4_wp, 1.0e-6_wp]
            reference_rtol = 1.0e-10_wp
            repeats = 1
            if (end_time < 0.0_wp) end_time = 1.0_wp
        else
            if (len(scene_list) == 0) scene_list = "coin,tipping_coin,fast_upright,near_flat," &
                & // "long_run"
            tolerances = [(10.0_wp**(-i), i = 3, 12)]
            reference_rtol = 1.0e-13_wp
        end if

        call execute_command_line("mkdir -p " // shell_quote(output_dir), exitstat=stat)
        open(newunit=unit, file=output_dir // "/bench.csv", status="replace", action="write", &
            & iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // "/bench.csv: cannot write", stat_io)
            return
        end if
        write(unit, '(a)') benchmark_header()
        write(output_unit, '(a)') "bench: " // machine_name()
        methods = benchmark_methods()
        process_unit = -1
        if (.not. quick) then
            open(newunit=process_unit, file=output_dir // "/bench_process.csv", &
                & status="replace", action="write", iostat=stat)
            if (stat /= 0) then
                call fatal_error(error, output_dir // "/bench_process.csv: cannot write", stat_io)
                return
            end if
            write(process_unit, '(a)') "scene,wall_s,cpu_s,startup_cpu_s,integration_cpu_s," &
                & // "reading_setup_summary_cpu_s"
        end if

        start = 1
        do
            comma = index(scene_list(start:), ",")
            if (comma == 0) then
                argument = scene_list(start:)
            else
                argument = scene_list(start:start + comma - 2)
            end if
            call read_scene(scene_path(trim(argument)), scene, error)
            if (allocated(error)) return
            if (end_time > 0.0_wp) scene%run%end_time = min(scene%run%end_time, end_time)
            scene%run%output_step = min(scene%run%output_step, scene%run%end_time)
            call evaluation_costs(scene, rolling_disk_ucosub, 20000, rhs_seconds, &
                & residual_seconds, solve_seconds, error)
            if (allocated(error)) return
            write(output_unit, '(a, 3(f8.3, a), f6.2, a)') "bench: " // trim(argument) &
                & // ": one ODE right-hand side", 1.0e6_wp*rhs_seconds, " us, one DAE residual", &
                & 1.0e6_wp*residual_seconds, " us, one LAPACK factor+solve of the saddle-point " &
                & // "system", 1.0e6_wp*solve_seconds, " us (right-hand side / solve = ", &
                & rhs_seconds/solve_seconds, ")"
            call measure_part_costs(scene, rolling_disk_ucosub, 20000, output_dir &
                & // "/bench_scratch.csv", costs, error)
            if (allocated(error)) return
            write(output_unit, '(a, 5(f8.3, a))') "bench: " // trim(argument) &
                & // ": unit costs: right-hand side", 1.0e6_wp*costs%rhs, " us, residual", &
                & 1.0e6_wp*costs%residual, " us, event functions", 1.0e6_wp*costs%root, &
                & " us, output row", 1.0e6_wp*costs%output, " us, its CSV line", &
                & 1.0e6_wp*costs%csv_line, " us"
            if (allocated(rows)) deallocate(rows)
            call benchmark_scene(scene, rolling_disk_ucosub, benchmark_methods(), tolerances, &
                & reference_rtol, repeats, rows, error, output_unit, costs)
            if (allocated(error)) return
            do i = 1, size(rows)
                write(unit, '(a)') write_benchmark_row(rows(i))
            end do
            flush(unit)
            do i = 1, size(methods)
                if (methods(i)%formulation == "reduced") cycle
                write(output_unit, '(a)') accuracy_line(rows, trim(argument), &
                    & trim(methods(i)%name), accuracy_target)
            end do
            if (.not. quick) then
                call process_cost(trim(argument), output_dir, process_unit, error)
                if (allocated(error)) return
            end if
            if (comma == 0) exit
            start = start + comma
        end do
        close(unit)
        if (process_unit /= -1) close(process_unit)
        call plot_work_precision(output_dir, scene_list, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "bench: wrote " // output_dir // "/bench.csv and " &
            & // output_dir // "/bench_<scene>.png"
    end subroutine bench_command

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
        write(numbers, '(5(es12.5, :, ","))') cost%wall, cost%cpu, cost%startup_cpu, &
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
