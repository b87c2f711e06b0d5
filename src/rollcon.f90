! SPDX-License-Identifier: MIT
!> rollcon: user-defined kinematic constraints (ADAMS UCON/UCOSUB) for multibody dynamics.
!> The library's API (docs/library.md), and nothing of the program's own plumbing: the program
!> (app/) and the examples use this module only.
module rollcon
    ! kinds, errors, numbers as text
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_io, stat_ucon
    use rollcon_text, only : to_text, fixed_text
    use rollcon_output_files, only : make_folders
    use rollcon_system, only : system_reason
    use rollcon_lapack, only : use_one_blas_thread
    use rollcon_version, only : rollcon_version_number, version_text

    ! the ADAMS contract: the calling sequence, its codes, UCOVAR, the calls as ADAMS makes them
    use rollcon_ucosub_contract
    use rollcon_ucovar_registry, only : ucon_variables_type, ucovar_registry_type
    use rollcon_adams_runtime, only : begin_declaration, end_declaration, take_ucon_error
    use rollcon_ucon_call, only : declare_ucon, evaluate_ucon

    ! UCOSUBs: the hand-checked rolling disk, the generated ones, the catalog of built-ins
    use rollcon_disk_par, only : disk_nvars, disk_npar, disk_codes, disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub, rolling_disk_evaluate
    use rollcon_gen_rolling_disk, only : generated_rolling_disk_ucosub => rolling_disk_ucosub
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names, &
        & builtin_ucosub_par, builtin_ucosub_summary, builtin_ucosubs_for_par

    ! models built in code: parts, forces, UCONs; how to integrate them
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type, profile_constant, profile_half_sine, &
        & frame_body, frame_tilt
    use rollcon_model, only : model_type, ucon_statement_type, setup_model
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, formulation_ida, &
        & formulation_maggi, &
        & method_bdf, method_adams, drift_none, drift_projection, drift_baumgarte, &
        & jacobian_analytic, jacobian_dq, linear_dense, linear_sparse, linear_auto

    ! a run: the problem, its watches, the simulation, its rows and summary
    use rollcon_problem, only : problem_type
    use rollcon_watch, only : watch_type, watch_measure_type, watch_event_type, action_stop, &
        & action_rebase
    use rollcon_theta_watch, only : theta_watch_type, new_theta_watch
    use rollcon_contact_watch, only : contact_watch_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & status_completed, status_stopped, status_failed, status_inaccurate, &
        & default_max_csv_bytes, output_layout
    use rollcon_output_layout, only : output_layout_type, new_output_layout, read_layout, &
        & coord_x, coord_y, coord_z, coord_psi, coord_theta, coord_phi, coord_xdot, coord_ydot, &
        & coord_zdot, coord_psidot, coord_thetadot, coord_phidot
    use rollcon_summary_text, only : run_summary_text
    use rollcon_part_shapes, only : part_shape_type, part_shapes_of, write_part_shapes, &
        & read_part_shapes, shape_disk, shape_ellipsoid
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of, &
        & analyse_initial_conditions
    use rollcon_ic_report, only : ic_change_type, ic_report_type, ic_report_text
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise
    use rollcon_linear_report, only : linear_table_text, natural_frequency, damped_frequency, &
        & damping_ratio
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type, speed_table, &
        & stability_changes, reference_speed

    ! inputs: scenes and datasets
    use rollcon_scene, only : scene_type, read_scene, scene_path
    use rollcon_scene_state, only : upright_critical_speed
    use rollcon_disk_scene, only : build_disk_problem, disk_initial_state, disk_mass_properties
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem, adm_theta_min
    use rollcon_adm_initial, only : adm_ic_options

    ! the one route: a job (any input, or a model built in code), loaded and run
    use rollcon_model_source, only : model_source_type
    use rollcon_built_model, only : built_model_source_type, new_model_source
    use rollcon_job, only : job_type, new_job
    use rollcon_provenance, only : provenance_lines, user_file_record, command_line_text
    use rollcon_ucosub_units, only : ucosub_units_type
    use rollcon_load, only : load_job, input_override_type, is_dataset, output_name
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_linear_job, only : linearise_job, write_eigen_csv, eigen_csv_path, &
        & linear_speeds_job, write_speed_csv, speed_csv_path

    ! a user's own UCOSUB: built, loaded, checked apart from rollcon
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_child_process, only : default_call_timeout
    use rollcon_partials_check, only : ucon_check_options_type, ucon_mismatch_type, &
        & ucon_check_result_type, check_ucon_state
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub, sampling_ranges, max_check_states, &
        & states_refusal
    use rollcon_ucon_request, only : read_ucon_request
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    use rollcon_audit_report, only : report_text
    use rollcon_audit_json, only : report_json, write_report_json

    ! parameter studies (docs/studies.md); the MPI loop is the program's
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_parameters, only : case_count
    use rollcon_study_measures, only : case_result_type, outcome_failed, outcome_refused
    use rollcon_study_run, only : study_plan_type, study_progress_type, plan_cases, plan_study, &
        & run_case, append_row, run_study, row_file_type, lock_study_csv
    use rollcon_file_lock, only : file_lock_type

    ! pictures
    use rollcon_run_record, only : run_record_type, read_run
    use rollcon_figures, only : plot_output, figure_file, figure_names, model_figure_names
    use rollcon_gif, only : animate_output
    use rollcon_vtk, only : write_vtk_series
    use rollcon_study_map, only : draw_study_map
    use rollcon_eigen_speed_figure, only : draw_eigen_speed_figure

    ! speed against accuracy (docs/benchmark.md)
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
        & scaling_csv_row, chain_time_share, scaling_table, short_scaling_methods
    use rollcon_disk_fleet, only : disk_fleet_dataset
    use rollcon_link_chain, only : link_chain_dataset
    implicit none
    public
end module rollcon
