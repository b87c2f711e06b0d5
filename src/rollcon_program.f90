! SPDX-License-Identifier: MIT
!> The rollcon program's own plumbing, for app/ only (.ci/layers checks that nothing else uses
!> it): command-line helpers, the limits and texts of `rollcon check`'s options, and the
!> benchmark's measurements and tables (`rollcon bench`, docs/benchmark.md). Not the library's
!> API: that is the facade rollcon (docs/library.md), which the program uses too.
module rollcon_program
    ! command-line helpers
    use rollcon_text, only : fixed_text
    use rollcon_output_files, only : make_folders
    use rollcon_provenance, only : command_line_text

    ! rollcon check: its options' limits and texts, and a dataset's UCONs as requests; the
    ! check of a user's UCOSUB before a dataset's run
    use rollcon_child_process, only : default_call_timeout
    use rollcon_ucosub_audit, only : sampling_ranges, max_check_states, states_refusal
    use rollcon_ucon_request, only : dataset_ucon_requests
    use rollcon_user_routine_check, only : dataset_has_user_routines, check_user_routines, &
        & routine_units_lines, check_tally_type
    use rollcon_run_check, only : check_at_start
    use rollcon_dataset_ucon_check, only : check_dataset_ucons

    ! rollcon bench: speed against accuracy, and the cost as models grow
    use rollcon_benchmark, only : method_type, benchmark_methods, benchmark_row_type, &
        & benchmark_scene, benchmark_header, write_benchmark_row, evaluation_costs, &
        & method_settings
    use rollcon_bench_costs, only : part_costs_type, measure_part_costs
    use rollcon_bench_process, only : process_cost_type, measure_process, &
        & write_scene_with_settings, write_dataset_with_settings
    use rollcon_reduced_bicycle, only : bicycle_table_type, read_bicycle_table
    use rollcon_bench_summary, only : accuracy_line, cheapest_row
    use rollcon_bench_plot, only : plot_work_precision, machine_name, sundials_build
    use rollcon_bench_sweep, only : time_sweep, coordinator_row_us
    use rollcon_bench_scaling, only : scaling_row_type, measure_scaling, scaling_header, &
        & scaling_csv_row, scaling_table, short_scaling_methods, check_scaling_end_time, &
        & long_chain_methods
    implicit none
    public
end module rollcon_program
