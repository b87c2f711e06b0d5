! SPDX-License-Identifier: MIT
!> run_job: the one route every run takes (docs/design.md §1). It builds the job's model with
!> its routine, makes the start consistent, simulates and keeps the rows (the caller's history,
!> and with an output folder DIR/NAME.csv, NAME.summary.txt and NAME.parts); with a user's file
!> the building and simulating happen in a child process and this process writes every output
!> (rollcon_isolated_run). `rollcon run` of a scene or a dataset, a study's case, a benchmark's
!> row and the example program all come here.
!>
!> Outputs are written under DIR/NAME.partial-PID.* and renamed into place only when the run
!> succeeded: a run that fails leaves its rows (valid up to where it got) and its summary under
!> the partial names, and an earlier run's files untouched.
module rollcon_run_job
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_io, stat_input
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_output_files, only : partial_name, write_text_file, rename_file, delete_file, &
        & make_folders
    use rollcon_problem, only : problem_type
    use rollcon_part_shapes, only : part_shape_type, write_part_shapes
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, &
        & status_failed
    use rollcon_summary_text, only : run_summary_text
    use rollcon_job, only : job_type
    use rollcon_analysis_run, only : run_analysis
    use rollcon_isolated_run, only : run_isolated
    use rollcon_provenance, only : provenance_lines
    implicit none
    private

    public :: run_job, job_result_type, job_files_type

    !> What a job left
    type :: job_result_type
        type(run_summary_type) :: summary
        !> The summary as text (what the outputs' summary file holds)
        character(len=:), allocatable :: summary_text
        !> Where the rows are: DIR/NAME.csv, or the partial name after a failure ("" without
        !> an output folder)
        character(len=:), allocatable :: csv_path
        !> The simulation began: false when the job was refused before (its model could not be
        !> built, its start not made consistent)
        logical :: started = .false.
        !> What the user's files define, for the run's record (rollcon_isolated_run's
        !> run_isolated, rollcon_provenance's provenance_lines); unallocated for a run here
        character(len=:), allocatable :: defined
    end type job_result_type

    !> The output files of a job: final and partial names
    type :: job_files_type
        character(len=:), allocatable :: csv, summary, parts, partial_csv, partial_summary
    end type job_files_type

contains

    !> Run the job (see the module's header). error: a refusal (before the simulation began:
    !> result%started false), or a failure of the run or of its outputs, its message saying
    !> which rows stay valid; result%summary describes the run either way.
    subroutine run_job(job, result, error, history)
        type(job_type), intent(inout) :: job
        type(job_result_type), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error
        !> When present, every output row is kept here too
        type(history_type), intent(inout), optional :: history
        type(job_files_type) :: files
        type(part_shape_type), allocatable :: shapes(:)
        type(run_options_type) :: options
        type(error_type), allocatable :: run_error

        result%csv_path = ""
        result%summary_text = ""
        call job_options(job, options)
        if (len(job%output_dir) > 0) then
            call prepare_files(job, files, error)
            if (allocated(error)) return
            options%csv_path = files%partial_csv
        end if
        if (len(job%user_file) > 0) then
            call run_isolated(job, options, result%summary, shapes, result%started, run_error, &
                & history, result%defined)
        else
            call run_here(job, options, result%summary, shapes, result%started, run_error, &
                & history)
        end if
        if (len(job%output_dir) == 0) then
            if (allocated(run_error)) call move_alloc(run_error, error)
            return
        end if
        call finish_files(job, files, shapes, result, run_error, error)
    end subroutine run_job

    !> The simulation's options from the job's settings and output request.
    subroutine job_options(job, options)
        type(job_type), intent(in) :: job
        type(run_options_type), intent(out) :: options

        options%end_time = job%source%settings%end_time
        options%output_step = job%source%settings%output_step
        if (allocated(job%source%settings%output_times)) options%output_times = &
            & job%source%settings%output_times
        options%progress = .not. job%quiet
        options%max_csv_bytes = job%max_csv_bytes
    end subroutine job_options

    !> In this process: the job's routine is a built-in one.
    subroutine run_here(job, options, summary, shapes, started, error, history)
        type(job_type), intent(inout) :: job
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(out) :: summary
        type(part_shape_type), allocatable, intent(out) :: shapes(:)
        logical, intent(out) :: started
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        type(problem_type), target :: problem
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report

        started = .false.
        allocate(shapes(0))
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (.not. allocated(error)) then
            if (.not. job%quiet .and. len(report) > 0) write(output_unit, '(a)') report
            call job%source%shapes(problem, shapes, error)
        end if
        if (allocated(error)) then
            call problem%release()
            return
        end if
        started = .true.
        call run_analysis(problem, q0, u0, options, summary, error, history)
        call problem%release()
    end subroutine run_here

    !> The output folder (made when missing) and the names of the files.
    subroutine prepare_files(job, files, error)
        type(job_type), intent(in) :: job
        type(job_files_type), intent(out) :: files
        type(error_type), allocatable, intent(out) :: error

        ! through mkdir(2): no shell, no PATH (rollcon_output_files)
        call make_folders(job%output_dir, error)
        if (allocated(error)) return
        associate (dir => job%output_dir, name => job%name)
            files%csv = dir // "/" // name // ".csv"
            files%summary = dir // "/" // name // ".summary.txt"
            files%parts = dir // "/" // name // ".parts"
            files%partial_csv = partial_name(dir, name, ".csv")
            files%partial_summary = partial_name(dir, name, ".summary.txt")
        end associate
    end subroutine prepare_files

    !> After the run: a refusal leaves nothing; a success puts the files in place; a failure
    !> (of the run, or of putting the files in place) leaves the partial files with a summary
    !> that says FAILED, and an error saying which rows are valid.
    subroutine finish_files(job, files, shapes, result, run_error, error)
        type(job_type), intent(in) :: job
        type(job_files_type), intent(in) :: files
        type(part_shape_type), intent(in) :: shapes(:)
        type(job_result_type), intent(inout) :: result
        type(error_type), allocatable, intent(inout) :: run_error
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: cleanup_error
        character(len=:), allocatable :: record

        if (allocated(run_error) .and. result%summary%rows == 0) then
            ! refused before any row (e.g. a UCOSUB error at set-up): nothing to keep
            call delete_file(files%partial_csv, cleanup_error)
            call move_alloc(run_error, error)
            ! the simulation's own refusal, an output request no disk holds: the input's end
            ! time and output step
            if (result%started .and. error%stat == stat_input .and. len(job%source%path) > 0) &
                & error%message = job%source%path // ": " // error%message
            return
        end if
        ! once: the summary and the .parts file carry the same time and hash
        if (allocated(result%defined)) then
            record = provenance_lines(job, result%defined)
        else
            record = provenance_lines(job)
        end if
        if (.not. allocated(run_error)) then
            result%csv_path = files%csv
            result%summary_text = record // warning_line(job) // job%source%model_notes() &
                & // run_summary_text(job%source%setting_line(), files%csv, result%summary)
            call place_outputs(files, shapes, result%summary_text, record, run_error)
            if (.not. allocated(run_error)) return
        end if
        ! The run failed, or its files could not be put in place: no "completed" anywhere.
        result%summary%status = status_failed
        result%summary%message = run_error%message
        result%csv_path = files%partial_csv
        result%summary_text = record // warning_line(job) // job%source%model_notes() &
            & // run_summary_text(job%source%setting_line(), files%partial_csv, result%summary)
        call write_text_file(files%partial_summary, result%summary_text, cleanup_error)
        call move_alloc(run_error, error)
        if (error%stat == stat_io) then
            error%message = error%message // " (" // files%partial_csv // " holds what was " &
                & // "written before the failure)"
        else
            error%message = error%message // " (the " // to_text(result%summary%rows) &
                & // " rows written to " // files%partial_csv // " up to t = " &
                & // to_text(result%summary%t_reached) // " s are valid)"
        end if
        if (allocated(cleanup_error)) error%message = error%message // "; " &
            & // cleanup_error%message
    end subroutine finish_files

    !> "warning: " and the input's warning (what it holds that the run does not use), ending in
    !> a newline; "" when it has none.
    function warning_line(job) result(text)
        type(job_type), intent(in) :: job
        character(len=:), allocatable :: text

        text = job%source%input_warning()
        if (len(text) > 0) text = "warning: " // text // new_line("a")
    end function warning_line

    !> Write the summary and the part shapes beside the partial CSV, remove an earlier run's
    !> summary, then rename the CSV and the summary to their final names.
    subroutine place_outputs(files, shapes, summary_text, record, error)
        type(job_files_type), intent(in) :: files
        type(part_shape_type), intent(in) :: shapes(:)
        character(len=*), intent(in) :: summary_text
        !> The run's provenance lines, for the .parts file's comments
        character(len=*), intent(in) :: record
        type(error_type), allocatable, intent(out) :: error

        call write_text_file(files%partial_summary, summary_text, error)
        if (allocated(error)) return
        ! the pictures' geometry of this run's parts (rollcon_part_shapes)
        call write_part_shapes(files%parts, shapes, error, record)
        if (allocated(error)) return
        ! An older run's summary must never sit beside this run's CSV.
        call delete_file(files%summary, error)
        if (allocated(error)) return
        call rename_file(files%partial_csv, files%csv, error)
        if (allocated(error)) return
        call rename_file(files%partial_summary, files%summary, error)
    end subroutine place_outputs

end module rollcon_run_job
