! SPDX-License-Identifier: MIT
!> What `rollcon bench` does besides its runs: the cost of a `rollcon run` as a process of its
!> own and the scene file that runs a row's setting (rollcon_bench_process), the coordinator's
!> CPU per row read from a sweep's log (rollcon_bench_sweep), and one work-precision plot per
!> scene (rollcon_bench_plot). No test here judges a time: each checks that the numbers are
!> found and where they come from.
module test_bench
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_bench_process, only : process_cost_type, measure_process, &
        & write_scene_with_settings, write_dataset_with_settings
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, method_adams, &
        & drift_baumgarte, jacobian_none
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_bench_sweep, only : coordinator_row_us
    use rollcon_bench_plot, only : plot_work_precision
    use rollcon_benchmark, only : benchmark_methods, benchmark_row_type, split_costs
    use rollcon_bench_costs, only : part_costs_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program, file_text, run_rollcon, count_of
    use picture_files, only : make_folder, remove_folder, write_lines
    use study_map_files, only : have_gnuplot, png_file
    implicit none
    private

    public :: collect_bench

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_bench"

contains

    !> Tests of this suite.
    subroutine collect_bench(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("process-cost-of-a-run", test_process_cost), &
            & new_unittest("process-cost-of-a-failed-run", test_process_failed), &
            & new_unittest("scene-with-a-row-settings", test_scene_settings), &
            & new_unittest("dataset-with-a-row-settings", test_dataset_settings), &
            & new_unittest("coordinator-cpu-per-row-from-log", test_row_us), &
            & new_unittest("work-precision-plot-per-scene", test_plots), &
            & new_unittest("split-by-formulation", test_split), &
            & new_unittest("bicycle-bench-through-the-program", test_bicycle_bench)]
    end subroutine collect_bench

    !> A scene file written with a benchmark row's settings loads as the same scene with exactly
    !> those settings (every run key, rtol to the last bit), its other groups as they were.
    subroutine test_scene_settings(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type) :: settings
        type(job_type) :: original, copy

        call make_folder(scratch)
        call load_job("tipping_coin", original, error)
        if (allocated(error)) return
        settings = original%source%settings
        settings%formulation = formulation_cvode
        settings%method = method_adams
        settings%drift = drift_baumgarte
        settings%jacobian = jacobian_none
        settings%rtol = 10.0_wp**(-7.5_wp)
        settings%atol = 1.0e-2_wp*settings%rtol
        settings%end_time = 3.0_wp
        call write_scene_with_settings(original%source%path, settings, scratch &
            & // "/variant.nml", error)
        if (allocated(error)) return
        call load_job(scratch // "/variant.nml", copy, error)
        if (allocated(error)) return
        associate (got => copy%source%settings)
            call check(error, got%formulation == settings%formulation .and. got%method &
                & == settings%method .and. got%drift == settings%drift .and. got%jacobian &
                & == settings%jacobian .and. got%rtol == settings%rtol .and. got%atol &
                & == settings%atol .and. got%end_time == settings%end_time .and. &
                & got%output_step == settings%output_step .and. got%max_steps &
                & == settings%max_steps, "the settings read back: " // got%text())
        end associate
        call remove_folder(scratch)
    end subroutine test_scene_settings

    !> A copy of data/bicycle.adm written with a benchmark row's settings loads with exactly
    !> those settings (every INTEGRATOR keyword, rtol to the last bit, the end time and output
    !> step of its SIMULATE), and is the same model (parts, UCONs, the push).
    subroutine test_dataset_settings(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type) :: settings
        type(job_type) :: original, copy

        call make_folder(scratch)
        call load_job("data/bicycle.adm", original, error)
        if (allocated(error)) return
        settings = original%source%settings
        settings%formulation = formulation_cvode
        settings%method = method_adams
        settings%drift = drift_baumgarte
        settings%jacobian = jacobian_none
        settings%rtol = 10.0_wp**(-7.5_wp)
        settings%atol = 1.0e-2_wp*settings%rtol
        settings%end_time = 3.0_wp
        settings%output_step = 0.03_wp
        call write_dataset_with_settings(original%source%path, settings, scratch &
            & // "/variant.adm", error)
        if (allocated(error)) return
        call load_job(scratch // "/variant.adm", copy, error)
        if (allocated(error)) return
        associate (got => copy%source%settings)
            call check(error, got%formulation == settings%formulation .and. got%method &
                & == settings%method .and. got%drift == settings%drift .and. got%jacobian &
                & == settings%jacobian .and. got%rtol == settings%rtol .and. got%atol &
                & == settings%atol .and. got%end_time == settings%end_time .and. &
                & got%output_step == settings%output_step .and. got%max_steps &
                & == settings%max_steps .and. got%linear_solver == settings%linear_solver &
                & .and. got%baumgarte_rate == settings%baumgarte_rate, &
                & "the settings read back: " // got%text())
        end associate
        if (allocated(error)) return
        call check(error, index(file_text(scratch // "/variant.adm"), "GFORCE/1") > 0 .and. &
            & index(file_text(scratch // "/variant.adm"), "UCON/6") > 0 .and. &
            & index(file_text(scratch // "/variant.adm"), "ERROR=1E-10") == 0, &
            & "the model kept, its own INTEGRATOR left out")
        call remove_folder(scratch)
    end subroutine test_dataset_settings

    !> `rollcon run steady_circle` timed as a child: its times are read from getrusage and the
    !> run's summary (an error otherwise), finite and not negative; the integration's CPU time
    !> is the summary's, which a run of hundreds of steps makes positive. Three runs, the
    !> median's: its CPU time holds its integration's (the split is of one run, not of three).
    subroutine test_process_cost(error)
        type(error_type), allocatable, intent(out) :: error
        type(process_cost_type) :: cost
        character(len=:), allocatable :: program

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call measure_process(program, "steady_circle", "steady_circle", scratch, cost, error, 3)
        if (allocated(error)) return
        call check(error, all(ieee_is_finite([cost%wall, cost%cpu, cost%startup_cpu, &
            & cost%integration_cpu, cost%rest_cpu])), "finite times")
        if (allocated(error)) return
        call check(error, cost%wall >= 0.0_wp .and. cost%cpu >= 0.0_wp .and. &
            & cost%startup_cpu >= 0.0_wp, "times not negative")
        if (allocated(error)) return
        call check(error, cost%integration_cpu > 0.0_wp .and. cost%integration_cpu <= cost%cpu, &
            & "the summary's CPU time, within the same run's")
        if (allocated(error)) return
        call check(error, index(file_text(scratch // "/steady_circle.summary.txt"), "CPU time:") &
            & > 0, "the run's summary is where the cost was read")
        call remove_folder(scratch)
    end subroutine test_process_cost

    !> A run that fails (no such scene) is an error naming the command and its log.
    subroutine test_process_failed(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failed
        type(process_cost_type) :: cost
        character(len=:), allocatable :: program

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call measure_process(program, "no_such_scene", "no_such_scene", scratch, cost, failed)
        call check(error, allocated(failed), "a failed run is an error")
        if (allocated(error)) return
        call check(error, failed%message == "'" // program // " run no_such_scene' failed " &
            & // "(exit 1); see " // scratch // "/process_run.log", "the message: " &
            & // failed%message)
        if (allocated(error)) return
        call check(error, len(file_text(scratch // "/process_run.log")) > 0, &
            & "the log holds the run's refusal")
        call remove_folder(scratch)
    end subroutine test_process_failed

    !> The closing lines of a sweep's log as app/rollcon_command_sweep.f90 writes them: the
    !> microseconds a row is the number before " us a row"; a log without that line, or no
    !> log, gives 0.
    subroutine test_row_us(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: log = scratch // "/sweep.log"

        call remove_folder(scratch)
        call make_folder(scratch)
        call write_lines(log, [character(len=100) :: &
            & "sweep: 12 cases run now (6 failed, 0 refused), 0 from an earlier run: all 12 " &
            & // "in out/s.csv", &
            & "sweep: the coordinator spent 0.003 s of CPU on messages and rows, 250 us a row"])
        call check(error, coordinator_row_us(log), 250, "microseconds a row")
        if (allocated(error)) return
        call write_lines(log, [character(len=100) :: "sweep: 1 cases run now (0 failed, 0 " &
            & // "refused), 0 from an earlier run: all 1 in out/s.csv"])
        call check(error, coordinator_row_us(log), 0, "a log without the line")
        if (allocated(error)) return
        call remove_folder(scratch)
        call check(error, coordinator_row_us(log), 0, "no log")
    end subroutine test_row_us

    !> The shipped benchmark's rows (data/bench/bench.csv) plotted for two of its scenes: one
    !> PNG for each and none for the others, and in the script a curve for every method of the
    !> benchmark in each plot. Skipped without gnuplot.
    subroutine test_plots(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: script
        integer :: curves, at, found

        if (.not. have_gnuplot(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call execute_command_line("cp data/bench/bench.csv " // scratch // "/bench.csv")
        call plot_work_precision(scratch, "coin,near_flat", error)
        if (allocated(error)) return
        call check(error, png_file(scratch // "/bench_coin.png") .and. &
            & png_file(scratch // "/bench_near_flat.png"), "a PNG for each scene asked for")
        if (allocated(error)) return
        call check(error, .not. png_file(scratch // "/bench_tipping_coin.png"), &
            & "none for a scene not asked for")
        if (allocated(error)) return
        script = file_text(scratch // "/bench.gp")
        curves = 0
        at = 1
        do
            found = index(script(at:), " with linespoints title ")
            if (found == 0) exit
            curves = curves + 1
            at = at + found
        end do
        call check(error, curves, 2*size(benchmark_methods()), "a curve per method and scene")
        if (allocated(error)) return
        call remove_folder(scratch)
    end subroutine test_plots

    !> A row's CPU time split into counts times its formulation's unit costs: residuals for IDA,
    !> right-hand sides in independent speeds for 'maggi', the ODE form's for CVODE; events as
    !> each integrator calls them; the remainder is SUNDIALS'. Costs picked so that every
    !> pairing gives another number.
    subroutine test_split(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: forms(3) = [character(len=5) :: "ida", "cvode", "maggi"]
        ! functions 10, events 100, rows 1000: rhs, residual, in speeds 1, 2, 3; events alone,
        ! given rates, given multipliers 4e-3, 5e-3, 6e-3; output 1e-4
        real(wp), parameter :: expected_rhs(3) = [20.0_wp, 10.0_wp, 30.0_wp], &
            & expected_roots(3) = [0.6_wp, 0.5_wp, 0.4_wp]
        type(part_costs_type) :: costs
        type(benchmark_row_type) :: row
        integer :: k

        costs%rhs = 1.0_wp
        costs%residual = 2.0_wp
        costs%rhs_speeds = 3.0_wp
        costs%root = 4.0e-3_wp
        costs%root_given_rates = 5.0e-3_wp
        costs%root_given_multipliers = 6.0e-3_wp
        costs%output = 1.0e-4_wp
        do k = 1, size(forms)
            row%cpu = 100.0_wp
            row%functions = 10
            row%root_evaluations = 100
            row%output_rows = 1000
            call split_costs(row, costs, trim(forms(k)))
            call check(error, abs(row%rhs_cpu - expected_rhs(k)) < 1.0e-12_wp .and. &
                & abs(row%roots_cpu - expected_roots(k)) < 1.0e-12_wp .and. &
                & abs(row%output_cpu - 0.1_wp) < 1.0e-12_wp .and. abs(row%sundials_cpu &
                & - (100.0_wp - expected_rhs(k) - expected_roots(k) - 0.1_wp)) < 1.0e-12_wp, &
                & trim(forms(k)) // ": the split is not its formulation's")
            if (allocated(error)) return
        end do
    end subroutine test_split

    !> `rollcon bench --quick --scenes bicycle` through the built program: every method at both
    !> quick tolerances completes and the command exits 0. The bench prepares one problem twice
    !> (the ODE form's unit costs, then the independent speeds'); the bicycle's reaction watch
    !> allocated its list a second time, and the program stopped with a runtime error (exit 2)
    !> after its first line.
    subroutine test_bicycle_bench(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, table
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "bench --quick --scenes bicycle --end-time 0.1 --output " &
            & // scratch, scratch // "/bench.out", scratch // "/bench.err", status)
        call check(error, status == 0, "exit status " // to_text(status) // ": " &
            & // file_text(scratch // "/bench.err"))
        if (allocated(error)) return
        table = file_text(scratch // "/bench.csv")
        ! 12 methods (rollcon's nine, the reduced ODE's three) at rtol 1e-4 and 1e-6
        call check(error, count_of(table, ",completed") == 24 .and. count_of(table, &
            & new_line("a") // "bicycle,") == 24, "24 completed rows of the bicycle: " // table)
        if (allocated(error)) return
        call remove_folder(scratch)
    end subroutine test_bicycle_bench

end module test_bench
