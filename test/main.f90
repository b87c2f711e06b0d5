! SPDX-License-Identifier: MIT
!> Runs the test suites: all, one suite (`unit SUITE`), or one test (`unit SUITE TEST`).
program tester
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon_testing, only : testsuite_type, new_testsuite, run_testsuite, test_counts_type
    use test_text, only : collect_text
    use test_ucovar, only : collect_ucovar
    use test_adams_utilities, only : collect_adams_utilities
    use test_disk_reference, only : collect_disk_reference
    use test_partials_check, only : collect_partials_check
    use test_generated, only : collect_generated
    use test_scene_files, only : collect_scene_files
    use test_scene_errors, only : collect_scene_errors
    use test_scene_fuzz, only : collect_scene_fuzz
    use test_dynamics, only : collect_dynamics
    use test_motion, only : collect_motion
    use test_events, only : collect_events
    use test_corners, only : collect_corners
    use test_drift, only : collect_drift
    use test_extremes, only : collect_extremes
    use test_pictures, only : collect_pictures
    use test_part_shapes, only : collect_part_shapes
    use test_picture_vtk, only : collect_picture_vtk
    use test_user_ucosub, only : collect_user_ucosub
    use test_adm_expression, only : collect_adm_expression
    use test_adm_lexer, only : collect_adm_lexer
    use test_adm_reader, only : collect_adm_reader
    use test_adm_refusals, only : collect_adm_refusals
    use test_adm_statements, only : collect_adm_statements
    use test_adm_build, only : collect_adm_build
    use test_adm_joints, only : collect_adm_joints
    use test_adm_joint_motions, only : collect_adm_joint_motions
    use test_adm_text, only : collect_adm_text
    use test_adm_fuzz, only : collect_adm_fuzz
    use test_expression_fuzz, only : collect_expression_fuzz
    use test_adm_forces, only : collect_adm_forces
    use test_dataset_command, only : collect_dataset_command
    use test_linear_command, only : collect_linear_command
    use test_joint_command, only : collect_joint_command
    use test_output, only : collect_output
    use test_command, only : collect_command
    use test_csv_fuzz, only : collect_csv_fuzz
    use test_isolation, only : collect_isolation
    use test_ucon_request_fuzz, only : collect_ucon_request_fuzz
    use test_allocations, only : collect_allocations
    use test_ida_first_step, only : collect_ida_first_step
    use test_cvode_event_rates, only : collect_cvode_event_rates
    use test_newton_pattern, only : collect_newton_pattern
    use test_int_buffer, only : collect_int_buffer
    use test_reduced, only : collect_reduced
    use test_reduced_bicycle, only : collect_reduced_bicycle
    use test_layout, only : collect_layout
    use test_ucosub_catalog, only : collect_ucosub_catalog
    use test_initial_conditions, only : collect_initial_conditions
    use test_linearisation, only : collect_linearisation
    use test_analyses, only : collect_analyses
    use test_linear_speeds, only : collect_linear_speeds
    use test_bicycle, only : collect_bicycle
    use test_mode_rates, only : collect_mode_rates
    use test_rebasing, only : collect_rebasing
    use test_singular_start, only : collect_singular_start
    use test_rebasing_restarts, only : collect_rebasing_restarts
    use test_models, only : collect_models
    use test_study_file, only : collect_study_file
    use test_study_fuzz, only : collect_study_fuzz
    use test_study_run, only : collect_study_run
    use test_study_map, only : collect_study_map
    use test_sweep_mpi, only : collect_sweep_mpi
    use test_run_apart, only : collect_run_apart
    use test_user_forces, only : collect_user_forces
    use test_user_force_measures, only : collect_user_force_measures
    use test_provenance, only : collect_provenance
    use test_ucosub_units, only : collect_ucosub_units
    use test_adm_physical, only : collect_adm_physical
    use test_study_paths, only : collect_study_paths
    use test_figure_rows, only : collect_figure_rows
    use test_mode_path, only : collect_mode_path
    use test_wire, only : collect_wire
    use test_least_squares, only : collect_least_squares
    use test_small_dense, only : collect_small_dense
    use test_bench, only : collect_bench
    use test_check_reliability, only : collect_check_reliability
    use test_check_findings, only : collect_check_findings
    use test_user_routine_check, only : collect_user_routine_check
    use test_input_files, only : collect_input_files
    use test_input_refusals, only : collect_input_refusals
    use test_system_calls, only : collect_system_calls
    use test_user_builds, only : collect_user_builds
    use test_long_paths, only : collect_long_paths
    use test_study_limits, only : collect_study_limits
    use test_sweep_guards, only : collect_sweep_guards
    use test_adm_outputs, only : collect_adm_outputs
    use test_adm_system, only : collect_adm_system
    use test_adm_language, only : collect_adm_language
    use test_acf_reader, only : collect_acf_reader
    use test_acf_command, only : collect_acf_command
    use test_fpm_dependency, only : collect_fpm_dependency
    use test_main_script, only : collect_main_script
    use test_multiplier_units, only : collect_multiplier_units
    use test_inertia_axes, only : collect_inertia_axes
    use test_inertia_command, only : collect_inertia_command
    use test_adm_bicycle, only : collect_adm_bicycle
    use test_independent_speeds, only : collect_independent_speeds
    use test_disk_fleet, only : collect_disk_fleet
    use test_link_chain, only : collect_link_chain
    use test_assembly, only : collect_assembly
    use test_model_elements, only : collect_model_elements

    use test_expression_functions, only : collect_expression_functions
    use test_gcon, only : collect_gcon
    use test_couplers, only : collect_couplers
    use test_motions, only : collect_motions
    use test_system_runs, only : collect_system_runs
    use test_diff_runs, only : collect_diff_runs
    use test_springs, only : collect_springs
    use test_adm_springs, only : collect_adm_springs
    use test_spring_partials, only : collect_spring_partials
    use test_force_partials, only : collect_force_partials
    use test_motion_partials, only : collect_motion_partials
    use test_redundancy, only : collect_redundancy
    use test_reactions, only : collect_reactions
    use test_request_answers, only : collect_request_answers
    use test_contact_modes, only : collect_contact_modes
    use test_dissipation, only : collect_dissipation
    use test_contact_flight, only : collect_contact_flight
    use test_contact_datasets, only : collect_contact_datasets
    use test_contact_turntable, only : collect_contact_turntable
    implicit none
    type(testsuite_type), allocatable :: suites(:)
    type(test_counts_type) :: counts
    character(len=:), allocatable :: suite_name, test_name
    character(len=256) :: argument
    logical :: found
    integer :: i

    suites = [new_testsuite("text", collect_text), &
        & new_testsuite("ucovar", collect_ucovar), &
        & new_testsuite("adams-utilities", collect_adams_utilities), &
        & new_testsuite("disk-reference", collect_disk_reference), &
        & new_testsuite("partials-check", collect_partials_check), &
        & new_testsuite("generated", collect_generated), &
        & new_testsuite("scene", collect_scene_files), &
        & new_testsuite("scene-errors", collect_scene_errors), &
        & new_testsuite("scene-fuzz", collect_scene_fuzz), &
        & new_testsuite("dynamics", collect_dynamics), &
        & new_testsuite("motion", collect_motion), &
        & new_testsuite("events", collect_events), &
        & new_testsuite("corners", collect_corners), &
        & new_testsuite("drift", collect_drift), &
        & new_testsuite("extremes", collect_extremes), &
        & new_testsuite("pictures", collect_pictures), &
        & new_testsuite("part-shapes", collect_part_shapes), &
        & new_testsuite("picture-vtk", collect_picture_vtk), &
        & new_testsuite("user-ucosub", collect_user_ucosub), &
        & new_testsuite("adm-expression", collect_adm_expression), &
        & new_testsuite("adm-lexer", collect_adm_lexer), &
        & new_testsuite("adm-reader", collect_adm_reader), &
        & new_testsuite("adm-refusals", collect_adm_refusals), &
        & new_testsuite("adm-statements", collect_adm_statements), &
        & new_testsuite("adm-forces", collect_adm_forces), &
        & new_testsuite("adm-springs", collect_adm_springs), &
        & new_testsuite("adm-build", collect_adm_build), &
        & new_testsuite("adm-joints", collect_adm_joints), &
        & new_testsuite("adm-joint-motions", collect_adm_joint_motions), &
        & new_testsuite("adm-text", collect_adm_text), &
        & new_testsuite("adm-fuzz", collect_adm_fuzz), &
        & new_testsuite("expression-fuzz", collect_expression_fuzz), &
        & new_testsuite("output", collect_output), &
        & new_testsuite("command", collect_command), &
        & new_testsuite("csv-fuzz", collect_csv_fuzz), &
        & new_testsuite("isolation", collect_isolation), &
        & new_testsuite("ucon-request-fuzz", collect_ucon_request_fuzz), &
        & new_testsuite("allocations", collect_allocations), &
        & new_testsuite("ida-first-step", collect_ida_first_step), &
        & new_testsuite("cvode-event-rates", collect_cvode_event_rates), &
        & new_testsuite("newton-pattern", collect_newton_pattern), &
        & new_testsuite("int-buffer", collect_int_buffer), &
        & new_testsuite("reduced", collect_reduced), &
        & new_testsuite("reduced-bicycle", collect_reduced_bicycle), &
        & new_testsuite("layout", collect_layout), &
        & new_testsuite("ucosub-catalog", collect_ucosub_catalog), &
        & new_testsuite("dataset-command", collect_dataset_command), &
        & new_testsuite("linear-command", collect_linear_command), &
        & new_testsuite("joint-command", collect_joint_command), &
        & new_testsuite("initial-conditions", collect_initial_conditions), &
        & new_testsuite("linearisation", collect_linearisation), &
        & new_testsuite("analyses", collect_analyses), &
        & new_testsuite("linear-speeds", collect_linear_speeds), &
        & new_testsuite("bicycle", collect_bicycle), &
        & new_testsuite("mode-rates", collect_mode_rates), &
        & new_testsuite("rebasing", collect_rebasing), &
        & new_testsuite("singular-start", collect_singular_start), &
        & new_testsuite("rebasing-restarts", collect_rebasing_restarts), &
        & new_testsuite("models", collect_models), &
        & new_testsuite("study-file", collect_study_file), &
        & new_testsuite("study-fuzz", collect_study_fuzz), &
        & new_testsuite("study-run", collect_study_run), &
        & new_testsuite("study-map", collect_study_map), &
        & new_testsuite("sweep-mpi", collect_sweep_mpi), &
        & new_testsuite("run-apart", collect_run_apart), &
        & new_testsuite("user-forces", collect_user_forces), &
        & new_testsuite("force-measures", collect_user_force_measures), &
        & new_testsuite("provenance", collect_provenance), &
        & new_testsuite("ucosub-units", collect_ucosub_units), &
        & new_testsuite("adm-physical", collect_adm_physical), &
        & new_testsuite("study-paths", collect_study_paths), &
        & new_testsuite("figure-rows", collect_figure_rows), &
        & new_testsuite("mode-path", collect_mode_path), &
        & new_testsuite("wire", collect_wire), &
        & new_testsuite("least-squares", collect_least_squares), &
        & new_testsuite("small-dense", collect_small_dense), &
        & new_testsuite("bench", collect_bench), &
        & new_testsuite("check-reliability", collect_check_reliability), &
        & new_testsuite("check-findings", collect_check_findings), &
        & new_testsuite("user-routine-check", collect_user_routine_check), &
        & new_testsuite("input-files", collect_input_files), &
        & new_testsuite("input-refusals", collect_input_refusals), &
        & new_testsuite("system-calls", collect_system_calls), &
        & new_testsuite("user-builds", collect_user_builds), &
        & new_testsuite("long-paths", collect_long_paths), &
        & new_testsuite("study-limits", collect_study_limits), &
        & new_testsuite("sweep-guards", collect_sweep_guards), &
        & new_testsuite("adm-outputs", collect_adm_outputs), &
        & new_testsuite("adm-system", collect_adm_system), &
        & new_testsuite("adm-language", collect_adm_language), &
        & new_testsuite("acf-reader", collect_acf_reader), &
        & new_testsuite("acf-command", collect_acf_command), &
        & new_testsuite("fpm-dependency", collect_fpm_dependency), &
        & new_testsuite("main-script", collect_main_script), &
        & new_testsuite("multiplier-units", collect_multiplier_units), &
        & new_testsuite("inertia-axes", collect_inertia_axes), &
        & new_testsuite("inertia-command", collect_inertia_command), &
        & new_testsuite("adm-bicycle", collect_adm_bicycle), &
        & new_testsuite("independent-speeds", collect_independent_speeds), &
        & new_testsuite("disk-fleet", collect_disk_fleet), &
        & new_testsuite("link-chain", collect_link_chain), &
        & new_testsuite("assembly", collect_assembly), &
        & new_testsuite("model-elements", collect_model_elements), &

        & new_testsuite("expression-functions", collect_expression_functions), &
        & new_testsuite("gcon", collect_gcon), &
        & new_testsuite("couplers", collect_couplers), &
        & new_testsuite("motions", collect_motions), &
        & new_testsuite("system-runs", collect_system_runs), &
        & new_testsuite("diff-runs", collect_diff_runs), &
        & new_testsuite("springs", collect_springs), &
        & new_testsuite("spring-partials", collect_spring_partials), &
        & new_testsuite("force-partials", collect_force_partials), &
        & new_testsuite("motion-partials", collect_motion_partials), &
        & new_testsuite("redundancy", collect_redundancy), &
        & new_testsuite("reactions", collect_reactions), &
        & new_testsuite("requests", collect_request_answers), &
        & new_testsuite("contact-modes", collect_contact_modes), &
        & new_testsuite("contact-flight", collect_contact_flight), &
        & new_testsuite("contact-datasets", collect_contact_datasets), &
        & new_testsuite("contact-turntable", collect_contact_turntable), &
        & new_testsuite("dissipation", collect_dissipation)]

    if (command_argument_count() >= 1) then
        call get_command_argument(1, argument)
        suite_name = trim(argument)
        if (suite_name == "--help" .or. suite_name == "-h") then
            write(output_unit, '(a)') "usage: fpm test unit -- [SUITE [TEST]]", &
                & "Runs every test, the tests of SUITE, or one TEST of SUITE. Suites:"
            do i = 1, size(suites)
                write(output_unit, '(2x, a)') suites(i)%name
            end do
            stop
        end if
    end if
    if (command_argument_count() >= 2) then
        call get_command_argument(2, argument)
        test_name = trim(argument)
    end if

    found = .false.
    do i = 1, size(suites)
        if (allocated(suite_name)) then
            if (suites(i)%name /= suite_name) cycle
        end if
        if (allocated(test_name)) then
            call run_testsuite(suites(i), output_unit, counts, test_name, found)
        else
            call run_testsuite(suites(i), output_unit, counts, found=found)
        end if
    end do
    if (.not. found) then
        write(error_unit, '(a)') "tester: error: no suite or test matches the command line; " &
            & // "run with --help for the list"
        stop 1, quiet=.true.
    end if

    if (counts%skipped > 0) then
        write(output_unit, '(i0, " passed, ", i0, " failed, ", i0, " skipped")') &
            & counts%passed, counts%failed, counts%skipped
    else
        write(output_unit, '(i0, " passed, ", i0, " failed")') counts%passed, counts%failed
    end if
    flush(output_unit)
    ! a failure is already reported above: no backtrace, just the exit status
    if (counts%failed > 0) stop 1, quiet=.true.
end program tester
