! SPDX-License-Identifier: MIT
!> `rollcon bench`: work-precision of every way of solving, on a ladder of tolerances, against
!> the reduced ODE of the disk (reference and limit), with per-part and whole-process costs.
module rollcon_command_bench
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, fatal_error, stat_input, stat_io, to_text, job_type, &
        & load_job, run_settings_type, is_dataset, output_name
    use rollcon_program, only : method_type, benchmark_methods, benchmark_row_type, &
        & benchmark_scene, benchmark_header, write_benchmark_row, evaluation_costs, &
        & part_costs_type, measure_part_costs, accuracy_line, process_cost_type, &
        & measure_process, plot_work_precision, machine_name, sundials_build, method_settings, &
        & cheapest_row, write_scene_with_settings, write_dataset_with_settings, &
        & scaling_row_type, measure_scaling, scaling_table, short_scaling_methods, &
        & bicycle_table_type, read_bicycle_table
    use rollcon_cli, only : cli_request_type
    use rollcon_app_files, only : make_folder
    implicit none
    private

    public :: bench_command

    !> The accuracy the headline ratio is quoted at [m] (docs/benchmark.md)
    real(wp), parameter :: accuracy_target = 1.0e-6_wp
    !> Runs of each whole process timed (the median kept): one child of some 30 ms varied by a
    !> quarter between two benchmark runs an hour apart
    integer, parameter :: process_repeats = 5

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

    !> Run the benchmark: DIR/bench.csv and one plot per scene.
    subroutine bench_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        type(bench_options_type) :: options
        character(len=:), allocatable :: name, labels
        integer :: unit, stat, start, comma, process_unit

        if (request%has("--help")) then
            call print_help()
            return
        end if
        call read_bench_options(request, options, error)
        if (allocated(error)) return
        call make_folder(options%output_dir, error)
        if (allocated(error)) return
        open(newunit=unit, file=options%output_dir // "/bench.csv", status="replace", &
            & action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, options%output_dir // "/bench.csv: cannot write", stat_io)
            return
        end if
        write(unit, '(a)') benchmark_header()
        write(output_unit, '(a)') "bench: " // machine_name() // "; " // sundials_build()
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
        labels = ""
        do
            comma = index(options%scene_list(start:), ",")
            if (comma == 0) then
                name = options%scene_list(start:)
            else
                name = options%scene_list(start:start + comma - 2)
            end if
            call bench_scene(name, options, unit, process_unit, error)
            if (allocated(error)) return
            labels = labels // trim(merge(",", " ", len(labels) > 0)) // bench_label(name)
            if (comma == 0) exit
            start = start + comma
        end do
        close(unit)
        if (process_unit /= -1) close(process_unit)
        call plot_work_precision(options%output_dir, labels, error)
        if (allocated(error)) return
        call scaling_summary(options, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "bench: wrote " // options%output_dir // "/bench.csv and " &
            & // options%output_dir // "/bench_<scene>.png"
    end subroutine bench_command

    !> The options of `rollcon bench`, checked.
    subroutine read_bench_options(request, options, error)
        type(cli_request_type), intent(in) :: request
        type(bench_options_type), intent(out) :: options
        type(error_type), allocatable, intent(out) :: error
        integer :: i

        options%output_dir = request%text("--output", "output")
        options%scene_list = request%text("--scenes", "")
        options%quick = request%has("--quick")
        call request%integer_value("--repeats", options%repeats, 3, 1, error)
        if (allocated(error)) return
        call request%real_value("--end-time", options%end_time, -1.0_wp, error)
        if (allocated(error)) return
        ! the scenes' own range of end_time (docs/scenes.md)
        if (request%has("--end-time") .and. .not. (options%end_time >= 1.0e-9_wp .and. &
            & options%end_time <= 1.0e9_wp)) then
            call fatal_error(error, "--end-time expects a time from 1e-9 to 1e9 s (a scene's " &
                & // "end_time), got '" // request%text("--end-time", "") // "'", stat_input)
            return
        end if
        if (options%quick) then
            ! one scene, two tolerances, one second: the check the test suite runs
            if (len(options%scene_list) == 0) options%scene_list = "tipping_coin"
            options%tolerances = [1.0e-4_wp, 1.0e-6_wp]
            options%reference_rtol = 1.0e-10_wp
            options%repeats = 1
            if (options%end_time < 0.0_wp) options%end_time = 1.0_wp
        else
            if (len(options%scene_list) == 0) options%scene_list = "coin,tipping_coin," &
                & // "fast_upright,near_flat,long_run,bicycle"
            ! half a decade apart: a decade's grid put the cheapest run within 1e-6 m up to
            ! ten times tighter than it needs, the reduced ODE's and a method's differently
            options%tolerances = [(10.0_wp**(-3.0_wp - 0.5_wp*i), i = 0, 18)]
            options%reference_rtol = 1.0e-13_wp
        end if
    end subroutine read_bench_options

    !> The rows' scene name of a name of --scenes: a dataset's file name without its folder and
    !> .adm (the benchmark's subject name), else the name itself.
    pure function bench_label(name) result(label)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: label

        label = name
        if (.not. is_dataset(name)) return
        label = label(index(label, "/", back=.true.) + 1:len(label) - 4)
    end function bench_label

    !> What a name of --scenes runs: a disk scene (its name or file), or a bicycle's dataset
    !> with the table it is written from (data/bicycle/write_adm.py): `bicycle` is
    !> data/bicycle.adm and data/bicycle/benchmark.txt, `DIR/NAME.adm` has its table at
    !> DIR/NAME/benchmark.txt.
    subroutine bench_input(name, input, table_path)
        character(len=*), intent(in) :: name
        !> The input to load; the table ("" for a disk scene)
        character(len=:), allocatable, intent(out) :: input, table_path

        input = name
        table_path = ""
        if (name == "bicycle") input = "data/bicycle.adm"
        if (is_dataset(input)) table_path = input(:len(input) - 4) // "/benchmark.txt"
    end subroutine bench_input

    !> One scene: its unit costs, every method on the tolerance ladder (rows to unit), the
    !> headline ratio per method, and (outside --quick) the whole-process cost.
    subroutine bench_scene(name, options, unit, process_unit, error)
        character(len=*), intent(in) :: name
        type(bench_options_type), intent(in) :: options
        integer, intent(in) :: unit, process_unit
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(benchmark_row_type), allocatable :: rows(:)
        type(part_costs_type) :: costs
        type(method_type) :: methods(size(benchmark_methods()))
        type(bicycle_table_type) :: table
        character(len=:), allocatable :: input, table_path
        real(wp) :: rhs_seconds, residual_seconds, solve_seconds
        integer :: i

        call bench_input(name, input, table_path)
        if (len(table_path) > 0) then
            call read_bicycle_table(table_path, table, error)
            if (allocated(error)) then
                error%message = "rollcon bench compares a dataset with the reduced bicycle of " &
                    & // "the table it is written from: " // error%message
                return
            end if
        end if
        call load_job(input, job, error)
        if (allocated(error)) return
        associate (settings => job%source%settings)
            if (options%end_time > 0.0_wp) settings%end_time = min(settings%end_time, &
                & options%end_time)
            settings%output_step = min(settings%output_step, settings%end_time)
        end associate
        call evaluation_costs(job, 20000, rhs_seconds, residual_seconds, solve_seconds, error)
        if (allocated(error)) return
        write(output_unit, '(a, 3(f8.3, a), f6.2, a)') "bench: " // name &
            & // ": one ODE right-hand side", 1.0e6_wp*rhs_seconds, " us, one DAE residual", &
            & 1.0e6_wp*residual_seconds, " us, one LAPACK factor+solve of the saddle-point " &
            & // "system", 1.0e6_wp*solve_seconds, " us (right-hand side / solve = ", &
            & rhs_seconds/solve_seconds, ")"
        call measure_part_costs(job, 20000, options%output_dir // "/bench_scratch.csv", costs, &
            & error)
        if (allocated(error)) return
        write(output_unit, '(a, 8(f8.3, a))') "bench: " // name &
            & // ": unit costs: right-hand side", 1.0e6_wp*costs%rhs, " us (in independent " &
            & // "speeds", 1.0e6_wp*costs%rhs_speeds, " us), residual", &
            & 1.0e6_wp*costs%residual, " us, event functions", 1.0e6_wp*costs%root, &
            & " us (given CVODE's accelerations", 1.0e6_wp*costs%root_given_rates, &
            & " us), output row", 1.0e6_wp*costs%output, " us, its CSV line", &
            & 1.0e6_wp*costs%csv_line, " us (Fortran's formatted write of it", &
            & 1.0e6_wp*costs%fortran_line, " us)"
        if (len(table_path) > 0) then
            call benchmark_scene(job, benchmark_methods(), options%tolerances, &
                & options%reference_rtol, options%repeats, rows, error, output_unit, costs, &
                & table)
        else
            call benchmark_scene(job, benchmark_methods(), options%tolerances, &
                & options%reference_rtol, options%repeats, rows, error, output_unit, costs)
        end if
        if (allocated(error)) return
        methods = benchmark_methods()
        if (.not. options%quick) then
            call headline_processes(bench_label(name), job, methods, options%output_dir, rows, &
                & error)
            if (allocated(error)) return
        end if
        do i = 1, size(rows)
            write(unit, '(a)') write_benchmark_row(rows(i))
        end do
        flush(unit)
        do i = 1, size(methods)
            if (methods(i)%formulation == "reduced") cycle
            write(output_unit, '(a)') accuracy_line(rows, bench_label(name), &
                & trim(methods(i)%name), accuracy_target, merge("(rad, m)", "m       ", &
                & len(table_path) > 0))
        end do
        if (.not. options%quick) call process_cost(bench_label(name), input, &
            & options%output_dir, process_unit, error)
    end subroutine bench_scene

    !> The per-part scaling table (the full one is `rollcon bench scaling`): the
    !> default way of solving on N disks and on a chain of N links, N = 1, 4, 16, 64 over 2 s
    !> (the chain a tenth of it); with --quick N = 1, 2 over 0.2 s. Datasets in DIR/scaling.
    subroutine scaling_summary(options, error)
        type(bench_options_type), intent(in) :: options
        type(error_type), allocatable, intent(out) :: error
        type(scaling_row_type), allocatable :: rows(:)
        real(wp) :: end_time

        call make_folder(options%output_dir // "/scaling", error)
        if (allocated(error)) return
        end_time = merge(0.2_wp, 2.0_wp, options%quick)
        write(output_unit, '(a)') "bench: cost per step and part as models grow (the default " &
            & // "solver; N disks over " // to_text(end_time) // " s, a chain of N links over " &
            & // "a tenth of that; the full table: rollcon bench scaling)"
        if (options%quick) then
            call measure_scaling(options%output_dir // "/scaling", [1, 2], end_time, rows, &
                & error, short_scaling_methods())
        else
            call measure_scaling(options%output_dir // "/scaling", [1, 4, 16, 64], end_time, &
                & rows, error, short_scaling_methods())
        end if
        if (allocated(error)) return
        write(output_unit, '(a)', advance="no") scaling_table(rows)
    end subroutine scaling_summary

    !> The whole process of each method's headline row (its cheapest run within
    !> accuracy_target): `rollcon run` of a copy of the scene with that row's settings, as a
    !> child; its user + system CPU goes into the row (process_cpu).
    subroutine headline_processes(scene, job, methods, output_dir, rows, error)
        character(len=*), intent(in) :: scene, output_dir
        type(job_type), intent(in) :: job
        type(method_type), intent(in) :: methods(:)
        type(benchmark_row_type), intent(inout) :: rows(:)
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type) :: settings
        type(process_cost_type) :: cost
        character(len=:), allocatable :: folder, variant
        integer :: m, best

        folder = output_dir // "/process"
        call make_folder(folder, error)
        if (allocated(error)) return
        do m = 1, size(methods)
            if (methods(m)%formulation == "reduced") cycle
            best = cheapest_row(rows, scene, trim(methods(m)%name), accuracy_target)
            if (best == 0) cycle
            settings = method_settings(job, methods(m), rows(best)%rtol)
            variant = scene // "-" // trim(methods(m)%name)
            if (is_dataset(job%source%path)) then
                call write_dataset_with_settings(job%source%path, settings, folder // "/" &
                    & // variant // ".adm", error)
                if (allocated(error)) return
                call measure_process(executable_path(), folder // "/" // variant // ".adm", &
                    & variant // ".adm", folder, cost, error, process_repeats)
            else
                call write_scene_with_settings(job%source%path, settings, folder // "/" &
                    & // variant // ".nml", error)
                if (allocated(error)) return
                call measure_process(executable_path(), folder // "/" // variant // ".nml", &
                    & variant, folder, cost, error, process_repeats)
            end if
            if (allocated(error)) return
            rows(best)%process_cpu = cost%cpu
        end do
    end subroutine headline_processes

    !> How this program was started (argument 0), whole however long: a cut path would time
    !> another program, or none.
    function executable_path() result(executable)
        character(len=:), allocatable :: executable
        integer :: length

        call get_command_argument(0, length=length)
        allocate(character(len=length) :: executable)
        call get_command_argument(0, executable)
    end function executable_path

    !> Time `rollcon run INPUT` (scene's input) as a child process; print it and add a line
    !> to process_unit.
    subroutine process_cost(scene, input, output_dir, process_unit, error)
        character(len=*), intent(in) :: scene, input, output_dir
        integer, intent(in) :: process_unit
        type(error_type), allocatable, intent(out) :: error
        type(process_cost_type) :: cost
        character(len=200) :: numbers

        call make_folder(output_dir // "/process", error)
        if (allocated(error)) return
        call measure_process(executable_path(), input, output_name(input), output_dir &
            & // "/process", cost, error, process_repeats)
        if (allocated(error)) return
        write(numbers, '(5(es13.5e3, :, ","))') cost%wall, cost%cpu, cost%startup_cpu, &
            & cost%integration_cpu, cost%rest_cpu
        write(process_unit, '(a)') scene // "," // trim(numbers)
        flush(process_unit)
        write(output_unit, '(a, 5(f8.3, a))') "bench: " // scene // ": whole process 'rollcon " &
            & // "run " // input // "': wall", cost%wall, " s, CPU", cost%cpu, " s = start-up", &
            & cost%startup_cpu, " s + integration with output rows", cost%integration_cpu, &
            & " s + scene reading, set-up and summary", cost%rest_cpu, " s"
    end subroutine process_cost

    subroutine print_help()
        write(output_unit, '(a)') &
            & "usage: rollcon bench [--quick] [--scenes A,B,...] [--repeats N] [--end-time T]", &
            & "                     [--output DIR]", &
            & "", &
            & "Work-precision benchmark. For each scene (default: coin, tipping_coin,", &
            & "fast_upright, near_flat, long_run, and bicycle: data/bicycle.adm, against the", &
            & "Whipple bicycle's reduced ODE of its table data/bicycle/benchmark.txt; a", &
            & "dataset DIR/NAME.adm is compared with the bicycle of DIR/NAME/benchmark.txt)", &
            & "and each way of solving (IDA; CVODE BDF with", &
            & "projection, Baumgarte or no drift control; CVODE Adams with Newton's method and", &
            & "with fixed-point iteration; CVODE Adams on the independent speeds, maggi-adams;", &
            & "analytic against difference-quotient Jacobians) on the tolerances rtol = 1e-3,", &
            & "10^-3.5, ... 1e-12 (half a decade apart; atol = 1e-2 rtol) it measures the CPU", &
            & "time (median of N runs, default 3; runs", &
            & "over a second are not repeated), steps, function and Jacobian evaluations, the", &
            & "largest distance of the disk's centre from the independent reference, the", &
            & "disk's reduced ODE (minimal coordinates, ucon/reduced/) by CVODE Adams at rtol", &
            & "1e-13 [m] (the bicycle: the largest difference of roll and steer [rad] and of the", &
            & "rear contact point [m]), the largest constraint residual and the energy drift.", &
            & "The reduced ODE is also the limit: every row carries the CPU time of the reduced", &
            & "ODE at the same rtol, multistep method and iteration, measured in the same run,", &
            & "and the ratio; per scene the cheapest run within 1e-6 m of the reference is", &
            & "compared with the cheapest reduced run within it, and (outside --quick) so is", &
            & "the whole 'rollcon run' of its setting as a child. Each row splits its CPU time", &
            & "into right-hand sides (or residuals), event functions, output rows (counts times", &
            & "unit costs measured in the same run) and SUNDIALS' remainder. " &
            & // "Outside --quick, the", &
            & "whole process 'rollcon run SCENE' is timed as a child (DIR/bench_process.csv).", &
            & "Writes DIR/bench.csv and DIR/bench_<scene>.png (gnuplot); DIR defaults to output.", &
            & "The first line names the machine and the SUNDIALS build measured (the library", &
            & "file loaded: Debian's, or .ci/setup's ROLLCON_SUNDIALS=optimised build).", &
            & "Last, the cost per step and part of the default way of solving on N disks and", &
            & "on a chain of N links, N = 1, 4, 16, 64 (rollcon bench scaling: the full table).", &
            & "  --quick       tipping_coin over 1 s at rtol 1e-4 and 1e-6, one run each; the", &
            & "                scaling table on N = 1, 2", &
            & "  --end-time T  cut every scene at T seconds"
    end subroutine print_help

end module rollcon_command_bench
