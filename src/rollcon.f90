! SPDX-License-Identifier: MIT
!> rollcon: user-defined kinematic constraints (ADAMS UCON/UCOSUB) for multibody dynamics.
!> The library's API and nothing else: every name exported here is documented in the tables of
!> docs/library.md ("One module: the facade rollcon"), and every name those tables document is
!> exported here (.ci/layers checks both ways). A program of yours, and example/, use this
!> module only; the rollcon program's own plumbing is rollcon_program's (app/ only).
module rollcon
    ! kinds, errors, numbers as text
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_io, stat_ucon
    use rollcon_text, only : to_text

    ! the version and the system
    use rollcon_version, only : rollcon_version_number, version_text
    use rollcon_lapack, only : use_one_blas_thread
    use rollcon_system, only : system_reason

    ! the ADAMS contract: the calling sequence, its codes, UCOVAR, the calls as ADAMS makes them
    use rollcon_ucosub_contract, only : ucosub_interface, ucovar, errmes, max_ucon_vars, &
        & max_ucon_par, iflag_init, iflag_eval, scalar_none, scalar_value, scalar_time_part, &
        & scalar_dt, scalar_dtt, array_none, array_dq, array_dtdq, xmatrx_none, xmatrx_dqdq, &
        & code_x, code_y, code_z, code_psi, code_theta, code_phi, code_xdot, code_ydot, &
        & code_zdot, code_psidot, code_thetadot, code_phidot, code_name
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_ucon_call, only : declare_ucon, evaluate_ucon
    use rollcon_ucosub_units, only : ucosub_units_type

    ! UCOSUBs: the hand-checked rolling disk, the built-in ones by name, a user's file
    use rollcon_disk_par, only : disk_nvars, disk_npar, disk_codes, disk_par
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names, &
        & builtin_ucosub_par, builtin_ucosub_summary, builtin_ucosubs_for_par
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub

    ! a model built in code: parts, markers, UCONs, joints, forces
    use rollcon_body, only : part_type
    use rollcon_model, only : model_type, ucon_statement_type, setup_model, &
        & served_by_model_ucosub
    use rollcon_marker, only : marker_type, part_marker
    use rollcon_motion, only : motion_type, prepare_motion, motion_form_displacement, &
        & motion_form_velocity, motion_form_acceleration
    use rollcon_motion_geometry, only : motion_x, motion_y, motion_z, motion_b1, motion_b2, &
        & motion_b3, motion_rotation
    use rollcon_part_frames, only : part_start
    use rollcon_inertia_axes, only : principal_axes
    use rollcon_rotation, only : rotation_matrix
    use rollcon_force, only : applied_force_type, profile_constant, profile_half_sine, &
        & profile_statement, frame_body, frame_tilt
    use rollcon_marker_force, only : marker_force_type, kind_translation, kind_rotation, &
        & kind_vector, kind_general, kind_spring, marker_force_action
    use rollcon_spring_force, only : spring_type, spring_translational, spring_rotational, &
        & spring_bushing
    use rollcon_expression, only : expression_type
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_equations, only : equations_type

    ! how to integrate
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, formulation_ida, &
        & formulation_speeds, method_bdf, method_adams, drift_none, drift_projection, &
        & drift_baumgarte, jacobian_analytic, jacobian_dq, linear_dense, linear_sparse, &
        & linear_auto

    ! a problem, what it watches, a run of it, its rows
    use rollcon_problem, only : problem_type
    use rollcon_watch, only : watch_type, watch_measure_type, watch_event_type, action_stop, &
        & action_rebase
    use rollcon_theta_watch, only : theta_watch_type, new_theta_watch
    use rollcon_contact_watch, only : contact_watch_type
    use rollcon_simulation, only : run_options_type, run_summary_type, simulate, &
        & status_completed, status_stopped, status_failed, status_inaccurate
    use rollcon_history, only : history_type
    use rollcon_output_layout, only : output_layout_type, new_output_layout, coord_x, coord_y, &
        & coord_z, coord_psi, coord_theta, coord_phi, coord_xdot, coord_ydot, coord_zdot, &
        & coord_psidot, coord_thetadot, coord_phidot

    ! inputs: scenes and datasets, read and assembled
    use rollcon_scene, only : scene_type, read_scene, scene_path
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem, adm_theta_min

    ! the one route: a job (any input, or a model built in code), loaded and run
    use rollcon_built_model, only : built_model_source_type, new_model_source
    use rollcon_job, only : job_type, new_job, user_file_type
    use rollcon_load, only : load_job, add_user_file, input_override_type, is_dataset, &
        & output_name, is_command_file, run_times_type, outputs_name_of
    use rollcon_run_job, only : run_job, job_result_type

    ! the initial-conditions analysis
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of, &
        & analyse_initial_conditions
    use rollcon_ic_report, only : ic_change_type, ic_report_type, ic_report_text

    ! linear analysis
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise
    use rollcon_linear_report, only : linear_table_text, natural_frequency, damped_frequency, &
        & damping_ratio
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type, speed_table, &
        & stability_changes, reference_speed
    use rollcon_linear_job, only : linearise_job, write_eigen_csv, eigen_csv_path, &
        & linear_speeds_job, write_speed_csv, speed_csv_path

    ! checking a user's UCOSUB
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub
    use rollcon_ucon_request, only : read_ucon_request
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    use rollcon_audit_report, only : report_text
    use rollcon_audit_json, only : report_json, write_report_json

    ! parameter studies (docs/studies.md)
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_parameters, only : case_count
    use rollcon_study_measures, only : case_result_type, outcome_failed, outcome_refused
    use rollcon_study_run, only : study_plan_type, study_progress_type, plan_cases, plan_study, &
        & run_case, append_row, run_study, row_file_type, lock_study_csv, prepare_study_routines
    use rollcon_file_lock, only : file_lock_type

    ! pictures (docs/pictures.md)
    use rollcon_part_shapes, only : part_shape_type, shape_disk, shape_ellipsoid, &
        & part_shapes_of, write_part_shapes, read_part_shapes, write_model_shapes, parts_path
    use rollcon_run_record, only : run_record_type, read_run
    use rollcon_figures, only : plot_output
    use rollcon_gif, only : animate_output
    use rollcon_vtk, only : write_vtk_series
    use rollcon_study_map, only : draw_study_map
    use rollcon_eigen_speed_figure, only : draw_eigen_speed_figure
    implicit none
    public
end module rollcon
