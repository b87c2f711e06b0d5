! SPDX-License-Identifier: MIT
!> rollcon: user-defined kinematic constraints (ADAMS UCON/UCOSUB) for multibody dynamics.
module rollcon
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract
    use rollcon_ucovar_registry, only : ucon_variables_type, ucovar_registry_type
    use rollcon_adams_runtime, only : begin_declaration, end_declaration, take_ucon_error
    use rollcon_disk_par, only : disk_nvars, disk_npar, disk_codes, disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub, rolling_disk_evaluate
    use rollcon_ucon_call, only : declare_ucon, evaluate_ucon
    use rollcon_partials_check, only : ucon_check_options_type, ucon_mismatch_type, &
        & ucon_check_result_type, check_ucon_state
    use rollcon_gen_rolling_disk, only : generated_rolling_disk_ucosub => rolling_disk_ucosub
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type, profile_constant, profile_half_sine, &
        & frame_body, frame_tilt
    use rollcon_model, only : model_type, ucon_statement_type, setup_model
    use rollcon_problem, only : problem_type, solver_settings_type, event_settings_type, &
        & formulation_cvode, formulation_ida, method_bdf, method_adams, drift_none, &
        & drift_projection, drift_baumgarte
    use rollcon_equations, only : equations_type
    use rollcon_scene, only : scene_type, read_scene, scene_path
    use rollcon_scene_type, only : scene_run_type
    use rollcon_disk_scene, only : build_disk_problem, disk_initial_state, disk_mass_properties
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate
    use rollcon_output_layout, only : output_layout_type, new_output_layout, read_layout
    use rollcon_output_rows, only : output_layout
    use rollcon_summary_text, only : run_summary_text
    use rollcon_adm_build, only : build_adm_problem, adm_theta_min
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of, &
        & analyse_initial_conditions
    use rollcon_ic_report, only : ic_change_type, ic_report_type, ic_report_text
    use rollcon_adm_initial, only : adm_ic_options
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names, &
        & builtin_ucosub_par, builtin_ucosub_summary
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub
    use rollcon_audit_report, only : report_text
    use rollcon_audit_json, only : report_json
    use rollcon_bench_costs, only : part_costs_type, measure_part_costs
    use rollcon_bench_process, only : process_cost_type, measure_process
    use rollcon_bench_summary, only : accuracy_line
    use rollcon_benchmark, only : method_type, benchmark_methods, benchmark_row_type, &
        & benchmark_scene, benchmark_header, write_benchmark_row, evaluation_costs
    use rollcon_child_process, only : default_call_timeout, isolated_task_type, call_record_type, &
        & isolation_outcome_type, run_in_child, outcome_finished
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_part_shapes, only : part_shape_type, part_shapes_of, write_model_shapes, &
        & write_part_shapes, read_part_shapes, parts_path, shape_disk, shape_ellipsoid
    use rollcon_run_record, only : run_record_type, read_run
    use rollcon_disk_scene, only : simulate_scene
    use rollcon_error, only : fatal_error, stat_input, stat_io, stat_ucon
    use rollcon_figures, only : plot_output, figure_file, figure_names, model_figure_names
    use rollcon_gif, only : animate_output
    use rollcon_study_map, only : draw_study_map
    use rollcon_gnuplot, only : base_name, run_gnuplot, gnuplot_string
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    use rollcon_isolation_text, only : outcome_text
    use rollcon_lapack, only : use_one_blas_thread
    use rollcon_output_files, only : partial_name, write_text_file, rename_file, delete_file
    use rollcon_scene, only : choice_name
    use rollcon_simulation, only : status_completed, status_stopped, status_failed, &
        & status_inaccurate, default_max_csv_bytes
    use rollcon_text, only : to_text, shell_quote, lower_case
    use rollcon_ucon_option, only : read_ucon_option
    use rollcon_ucosub_audit, only : sampling_ranges
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_guard, only : install_guard, attach_call_record, guarded_ucosub
    use rollcon_vtk, only : write_vtk_series
    ! parameter studies (docs/studies.md); the MPI loop is the program's
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_parameters, only : case_count
    use rollcon_study_measures, only : case_result_type, outcome_failed, outcome_refused
    use rollcon_study_run, only : study_plan_type, study_progress_type, plan_cases, plan_study, &
        & run_case, append_row, run_study, row_file_type
    use rollcon_scene_state, only : upright_critical_speed
    ! the library API of docs/library.md: the coordinates of a part in the output layout
    use rollcon_output_layout, only : coord_x, coord_y, coord_z, coord_psi, coord_theta, &
        & coord_phi, coord_xdot, coord_ydot, coord_zdot, coord_psidot, coord_thetadot, &
        & coord_phidot
    implicit none
    public
end module rollcon
