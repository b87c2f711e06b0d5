! SPDX-License-Identifier: MIT
!> `rollcon run`: simulate a disk scene or a dataset (MODEL.adm) and write its CSV, summary and
!> part shapes.
module rollcon_command_run
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, rolling_disk_ucosub, fatal_error, stat_io, stat_input, &
        & to_text, shell_quote, ucosub_interface, scene_type, read_scene, scene_path, choice_name, &
        & formulation_cvode, method_adams, run_summary_type, status_failed, &
        & default_max_csv_bytes, partial_name, write_text_file, rename_file, delete_file, &
        & run_summary_text, problem_type, run_options_type, simulate, build_disk_problem, &
        & scene_run_type, adm_model_type, read_adm, build_adm_problem, part_shape_type, &
        & part_shapes_of, write_part_shapes, lower_case, ic_report_type, ic_report_text, &
        & analyse_initial_conditions, adm_ic_options
    implicit none
    private

    public :: run_scene, is_dataset

    !> What a run is: its name (the file stem of its outputs), its input file, the setting line
    !> of its summary, its times and its parts' shapes for the pictures
    type :: run_job_type
        character(len=:), allocatable :: name, path, setting
        !> End time and output step [s]
        real(wp) :: end_time = 0.0_wp, output_step = 0.0_wp
        type(part_shape_type), allocatable :: shapes(:)
    end type run_job_type

contains

    !> Read the scene (a namelist scene, or an ADAMS dataset MODEL.adm), simulate it, write
    !> output_dir/<name>.csv and <name>.summary.txt. The run writes <name>.partial-<pid>.csv and
    !> renames it (and its summary) into place only when it succeeded; a failed run leaves its
    !> rows and summary under the partial name, and the files of an earlier run untouched.
    subroutine run_scene(name, output_dir, ucosub, quiet, summary, error, allow_large_output)
        !> Scene name ('coin'), path of a namelist file, or path of a dataset (.adm)
        character(len=*), intent(in) :: name
        !> Folder for the outputs (created if missing)
        character(len=*), intent(in) :: output_dir
        !> The routine given with --ucosub (null: none). A scene: it serves the disk's UCONs
        !> (default: the hand-checked routine). A dataset: it serves every UCON that names no
        !> ROUTINE (default: the same hand-checked rolling-disk routine, named `disk`).
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        !> No progress lines
        logical, intent(in) :: quiet
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        !> Lift the limit on the size of the CSV a run may plan (default: keep it)
        logical, intent(in), optional :: allow_large_output
        type(problem_type), target :: problem
        type(run_job_type) :: job
        real(wp), allocatable :: q0(:), u0(:)
        real(wp) :: max_csv_bytes

        if (is_dataset(name)) then
            call prepare_dataset(name, ucosub, quiet, problem, q0, u0, job, error)
        else
            call prepare_scene(name, ucosub, problem, q0, u0, job, error)
        end if
        if (allocated(error)) return
        max_csv_bytes = default_max_csv_bytes
        if (present(allow_large_output)) then
            if (allow_large_output) max_csv_bytes = huge(1.0_wp)
        end if
        call run_job(job, problem, q0, u0, output_dir, quiet, max_csv_bytes, summary, error)
    end subroutine run_scene

    !> True when name is a dataset: its name ends in .adm (any case).
    pure logical function is_dataset(name)
        character(len=*), intent(in) :: name
        integer :: n

        n = len_trim(name)
        is_dataset = .false.
        if (n > 4) is_dataset = lower_case(name(n - 3:n)) == ".adm"
    end function is_dataset

    !> A namelist scene's problem: the disk, with ucosub (or the hand-checked routine).
    subroutine prepare_scene(name, ucosub, problem, q0, u0, job, error)
        character(len=*), intent(in) :: name
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(run_job_type), intent(out) :: job
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        allocate(q0(6), u0(6))
        if (associated(ucosub)) then
            call build_disk_problem(scene, ucosub, problem, q0, u0, error)
        else
            call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        end if
        if (allocated(error)) return
        job%name = scene%name
        job%path = scene%path
        job%setting = "scene " // scene%name // " (" // scene%path // "): " &
            & // settings_text(scene%run)
        job%end_time = scene%run%end_time
        job%output_step = scene%run%output_step
        call part_shapes_of(problem%model, job%shapes, error, disk_radius=scene%disk%radius, &
            & disk_thickness=scene%disk%thickness, disk_part=1)
    end subroutine prepare_scene

    !> A dataset's problem: its parts, UCONs (ROUTINE= or ucosub), forces and run; its start
    !> made consistent by the initial-conditions analysis, whose report is printed unless quiet.
    subroutine prepare_dataset(path, ucosub, quiet, problem, q0, u0, job, error)
        character(len=*), intent(in) :: path
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        logical, intent(in) :: quiet
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(run_job_type), intent(out) :: job
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(ic_report_type) :: report
        procedure(ucosub_interface), pointer :: hand_disk
        integer :: slash

        call read_adm(path, adm, error)
        if (allocated(error)) return
        if (associated(ucosub)) then
            call build_adm_problem(adm, ucosub, problem, q0, u0, error)
        else
            ! rollcon's own UCOSUB, as for the scenes: the hand-checked rolling disk
            hand_disk => rolling_disk_ucosub
            call build_adm_problem(adm, hand_disk, problem, q0, u0, error)
        end if
        if (allocated(error)) return
        ! as ADAMS before a dynamic run: the least change that meets every UCON
        call analyse_initial_conditions(problem, 0.0_wp, q0, u0, adm_ic_options(adm, problem), &
            & report, error)
        if (allocated(error)) then
            error%message = path // ": " // error%message
            return
        end if
        if (.not. quiet) write(output_unit, '(a)') ic_report_text(report)
        slash = index(path, "/", back=.true.)
        job%name = path(slash + 1:len_trim(path) - 4)
        job%path = path
        job%setting = "dataset " // job%name // " (" // path // "): " &
            & // settings_text(adm%run%settings)
        job%end_time = adm%run%end_time
        job%output_step = adm%run%output_step
        call part_shapes_of(problem%model, job%shapes, error)
    end subroutine prepare_dataset

    !> Simulate a prepared problem and put its files in place (see run_scene).
    subroutine run_job(job, problem, q0, u0, output_dir, quiet, max_csv_bytes, summary, error)
        type(run_job_type), intent(in) :: job
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        character(len=*), intent(in) :: output_dir
        logical, intent(in) :: quiet
        !> Largest CSV the run may plan [bytes]
        real(wp), intent(in) :: max_csv_bytes
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(run_options_type) :: options
        type(error_type), allocatable :: run_error, cleanup_error
        character(len=:), allocatable :: text, csv_path, partial_csv, partial_summary
        integer :: stat

        call execute_command_line("mkdir -p " // shell_quote(output_dir), exitstat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // ": cannot create the output folder", stat_io)
            return
        end if
        csv_path = output_dir // "/" // job%name // ".csv"
        partial_csv = partial_name(output_dir, job%name, ".csv")
        partial_summary = partial_name(output_dir, job%name, ".summary.txt")
        options%end_time = job%end_time
        options%output_step = job%output_step
        options%progress = .not. quiet
        options%csv_path = partial_csv
        options%max_csv_bytes = max_csv_bytes
        call simulate(problem, q0, u0, options, summary, run_error)
        if (allocated(run_error) .and. summary%rows == 0) then
            ! refused before any integration (e.g. a UCOSUB error at set-up): nothing to keep
            call delete_file(partial_csv, cleanup_error)
            call move_alloc(run_error, error)
            ! An output request no disk holds: the scene's end time and output step
            if (error%stat == stat_input) error%message = job%path // ": " // error%message
            return
        end if
        if (.not. allocated(run_error)) then
            text = run_summary_text(job%setting, csv_path, summary)
            call place_outputs(text, run_error)
            if (.not. allocated(run_error)) then
                write(output_unit, '(a)') text
                return
            end if
        end if
        ! The run failed, or its files could not be put in place: no "completed" anywhere.
        summary%status = status_failed
        summary%message = run_error%message
        text = run_summary_text(job%setting, partial_csv, summary)
        write(output_unit, '(a)') text
        call write_text_file(partial_summary, text, cleanup_error)
        call move_alloc(run_error, error)
        if (error%stat == stat_io) then
            error%message = error%message // " (" // partial_csv // " holds what was written " &
                & // "before the failure)"
        else
            error%message = error%message // " (the " // to_text(summary%rows) &
                & // " rows written to " // partial_csv // " up to t = " &
                & // to_text(summary%t_reached) // " s are valid)"
        end if
        if (allocated(cleanup_error)) error%message = error%message // "; " &
            & // cleanup_error%message

    contains

        !> Write the summary and the part shapes beside the partial CSV, remove an earlier run's
        !> summary, then rename the CSV and the summary to their final names.
        subroutine place_outputs(summary_text, error)
            character(len=*), intent(in) :: summary_text
            type(error_type), allocatable, intent(out) :: error
            character(len=:), allocatable :: summary_path

            summary_path = output_dir // "/" // job%name // ".summary.txt"
            call write_text_file(partial_summary, summary_text, error)
            if (allocated(error)) return
            ! the pictures' geometry of this run's parts (rollcon_part_shapes)
            call write_part_shapes(output_dir // "/" // job%name // ".parts", job%shapes, error)
            if (allocated(error)) return
            ! An older run's summary must never sit beside this run's CSV.
            call delete_file(summary_path, error)
            if (allocated(error)) return
            call rename_file(partial_csv, csv_path, error)
            if (allocated(error)) return
            call rename_file(partial_summary, summary_path, error)
        end subroutine place_outputs

    end subroutine run_job

    !> The integrator settings of a run, in words: "IDA (DAE form, index 2), analytic
    !> Jacobian, rtol 1e-8, atol 1e-10".
    function settings_text(run) result(text)
        type(scene_run_type), intent(in) :: run
        character(len=:), allocatable :: text

        if (run%formulation == formulation_cvode) then
            text = "CVODE (ODE form, "
            if (run%method == method_adams) then
                text = text // "Adams, drift " // choice_name("drift", run%drift) // ")"
            else
                text = text // "BDF, drift " // choice_name("drift", run%drift) // ")"
            end if
        else
            text = "IDA (DAE form, index 2)"
        end if
        text = text // ", " // choice_name("jacobian", run%jacobian) // " Jacobian, rtol " &
            & // to_text(run%rtol) // ", atol " // to_text(run%atol)
    end function settings_text


end module rollcon_command_run
