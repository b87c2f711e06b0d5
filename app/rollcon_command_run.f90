! SPDX-License-Identifier: MIT
!> `rollcon run`: simulate a disk scene and write its CSV and summary.
module rollcon_command_run
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, rolling_disk_ucosub, fatal_error, stat_io, stat_input, &
        & to_text, shell_quote, ucosub_interface, scene_type, read_scene, scene_path, choice_name, &
        & formulation_cvode, method_adams, simulate_scene, run_summary_type, &
        & status_failed, default_max_csv_bytes, partial_name, write_text_file, rename_file, &
        & delete_file, run_summary_text
    implicit none
    private

    public :: run_scene

contains

    !> Read the scene, simulate it, write output_dir/<scene>.csv and <scene>.summary.txt. The
    !> run writes <scene>.partial-<pid>.csv and renames it (and its summary) into place only
    !> when it succeeded; a failed run leaves its rows and summary under the partial name, and
    !> the files of an earlier run untouched.
    subroutine run_scene(name, output_dir, ucosub, quiet, summary, error, allow_large_output)
        !> Scene name ('coin') or path of a namelist file
        character(len=*), intent(in) :: name
        !> Folder for the outputs (created if missing)
        character(len=*), intent(in) :: output_dir
        !> The routine serving the disk's UCONs
        procedure(ucosub_interface) :: ucosub
        !> No progress lines
        logical, intent(in) :: quiet
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        !> Lift the limit on the size of the CSV a run may plan (default: keep it)
        logical, intent(in), optional :: allow_large_output
        type(scene_type) :: scene
        type(error_type), allocatable :: run_error, cleanup_error
        character(len=:), allocatable :: text, csv_path, partial_csv, partial_summary
        real(wp) :: max_csv_bytes
        integer :: stat

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        call execute_command_line("mkdir -p " // shell_quote(output_dir), exitstat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // ": cannot create the output folder", stat_io)
            return
        end if
        max_csv_bytes = default_max_csv_bytes
        if (present(allow_large_output)) then
            if (allow_large_output) max_csv_bytes = huge(1.0_wp)
        end if
        csv_path = output_dir // "/" // scene%name // ".csv"
        partial_csv = partial_name(output_dir, scene%name, ".csv")
        partial_summary = partial_name(output_dir, scene%name, ".summary.txt")
        call simulate_scene(scene, ucosub, summary, run_error, csv_path=partial_csv, &
            & progress=.not. quiet, max_csv_bytes=max_csv_bytes)
        if (allocated(run_error) .and. summary%rows == 0) then
            ! refused before any integration (e.g. a UCOSUB error at set-up): nothing to keep
            call delete_file(partial_csv, cleanup_error)
            call move_alloc(run_error, error)
            ! An output request no disk holds: the scene's end_time and output_step
            if (error%stat == stat_input) error%message = scene%path // ": " // error%message
            return
        end if
        if (.not. allocated(run_error)) then
            call place_outputs(summary_text(scene, csv_path, summary), run_error)
            if (.not. allocated(run_error)) then
                write(output_unit, '(a)') summary_text(scene, csv_path, summary)
                return
            end if
        end if
        ! The run failed, or its files could not be put in place: no "completed" anywhere.
        summary%status = status_failed
        summary%message = run_error%message
        text = summary_text(scene, partial_csv, summary)
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

        !> Write the summary beside the partial CSV, remove an earlier run's summary, then
        !> rename the CSV and the summary to their final names.
        subroutine place_outputs(summary_text, error)
            character(len=*), intent(in) :: summary_text
            type(error_type), allocatable, intent(out) :: error
            character(len=:), allocatable :: summary_path

            summary_path = output_dir // "/" // scene%name // ".summary.txt"
            call write_text_file(partial_summary, summary_text, error)
            if (allocated(error)) return
            ! An older run's summary must never sit beside this run's CSV.
            call delete_file(summary_path, error)
            if (allocated(error)) return
            call rename_file(partial_csv, csv_path, error)
            if (allocated(error)) return
            call rename_file(partial_summary, summary_path, error)
        end subroutine place_outputs

    end subroutine run_scene

    !> The run's summary as text: the scene and its integrator settings, then what every run
    !> reports (rollcon_summary_text).
    function summary_text(scene, csv_path, summary) result(text)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: csv_path
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text
        character(len=:), allocatable :: method

        if (scene%run%formulation == formulation_cvode) then
            method = "CVODE (ODE form, "
            if (scene%run%method == method_adams) then
                method = method // "Adams, drift " // choice_name("drift", scene%run%drift) // ")"
            else
                method = method // "BDF, drift " // choice_name("drift", scene%run%drift) // ")"
            end if
        else
            method = "IDA (DAE form, index 2)"
        end if
        text = run_summary_text("scene " // scene%name // " (" // scene%path // "): " // method &
            & // ", " // choice_name("jacobian", scene%run%jacobian) // " Jacobian, rtol " &
            & // to_text(scene%run%rtol) // ", atol " // to_text(scene%run%atol), csv_path, &
            & summary)
    end function summary_text

end module rollcon_command_run
