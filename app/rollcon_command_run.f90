! SPDX-License-Identifier: MIT
!> `rollcon run`: load the scene or dataset the command names (load_job) and run it (run_job),
!> then print its summary, and with --vtk write its VTK series.
module rollcon_command_run
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : wp, error_type, fatal_error, stat_input, to_text, job_type, load_job, &
        & add_user_file, &
        & run_job, job_result_type, status_inaccurate, run_record_type, read_run, &
        & write_vtk_series, run_times_type
    use rollcon_program, only : command_line_text, check_at_start
    use rollcon_cli, only : cli_request_type, command_names
    use rollcon_app_files, only : make_folder, file_stem
    implicit none
    private

    public :: run_command, call_timeout_of

    !> Longest time limit per call accepted [s] (a day: beyond it, no limit is meant)
    real(wp), parameter :: longest_call_timeout = 86400.0_wp

contains

    !> Run the command; status 3 when the run's results drifted beyond what its tolerances
    !> promise (its outputs written), else 0 (error: a refusal or a failure).
    subroutine run_command(request, status, error)
        type(cli_request_type), intent(in) :: request
        integer, intent(out) :: status
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result
        type(run_times_type) :: times
        real(wp) :: fps
        character(len=:), allocatable :: name
        integer :: k

        status = 0
        call request%real_value("--vtk", fps, 0.0_wp, error)
        if (allocated(error)) return
        ! a frame per output row at most; more than a million a simulated second is a mistake
        if (request%has("--vtk") .and. .not. (fps > 0.0_wp .and. fps <= 1.0e6_wp)) then
            call fatal_error(error, "--vtk needs a number of frames per second above 0 and " &
                & // "up to 1e6, got '" // request%text("--vtk", "") // "'", stat_input)
            return
        end if
        name = request%positional
        if (len(name) == 0) name = "coin"
        call run_times_of(request, times, error)
        if (allocated(error)) return
        call load_job(name, job, error, ucosub=request%nth("--ucosub", 1), times=times)
        if (allocated(error)) then
            ! a bare word that names no scene may be a command mistyped
            if (scan(name, "/.") == 0) error%message = error%message // "; and '" // name &
                & // "' is not a command (" // command_names() // ")"
            return
        end if
        ! more files of user routines, run with the first in its child process
        do k = 2, request%count("--ucosub")
            call add_user_file(job, request%nth("--ucosub", k), error)
            if (allocated(error)) return
        end do
        ! what the input holds and the run does not use: said once, before the run, --quiet
        ! or not
        if (len(job%source%input_warning()) > 0) write(error_unit, '(a)') "rollcon: warning: " &
            & // job%source%input_warning()
        job%output_dir = request%text("--output", "output")
        job%command_line = command_line_text()
        job%quiet = request%has("--quiet")
        if (request%has("--allow-large-output")) job%max_csv_bytes = huge(1.0_wp)
        call call_timeout_of(request, job%call_timeout, error)
        if (allocated(error)) return
        ! a user's file is checked at the run's consistent start, before the first step
        if (.not. request%has("--no-check")) job%start_check => check_at_start
        call run_job(job, result, error)
        if (len(result%summary_text) > 0) write(output_unit, '(a)') result%summary_text
        if (allocated(error)) return
        if (fps > 0.0_wp) call write_csv_vtk(result%csv_path, fps, error)
        if (allocated(error)) return
        ! results beyond what the tolerances promise: outputs written, but not a success
        if (result%summary%status == status_inaccurate) then
            write(error_unit, '(a)') "rollcon: warning: " // result%summary%message
            status = 3
        end if
    end subroutine run_command

    !> --end T, --steps N, --dtout DT: the run of a dataset or a command file given on the
    !> command line, in place of its SIMULATE (T and DT in the dataset's time unit, as
    !> SIMULATE's END and DTOUT; docs/datasets.md).
    subroutine run_times_of(request, times, error)
        type(cli_request_type), intent(in) :: request
        type(run_times_type), intent(out) :: times
        type(error_type), allocatable, intent(out) :: error
        integer :: steps

        times%written = ""
        times%end_given = request%has("--end")
        times%steps_given = request%has("--steps")
        times%dtout_given = request%has("--dtout")
        call request%real_value("--end", times%end_time, 0.0_wp, error)
        if (allocated(error)) return
        call request%real_value("--dtout", times%dtout, 0.0_wp, error)
        if (allocated(error)) return
        call request%integer_value("--steps", steps, 1, 1, error)
        if (allocated(error)) return
        times%steps = real(steps, wp)
        if (times%end_given) times%written = times%written // " --end " &
            & // request%text("--end", "")
        if (times%steps_given) times%written = times%written // " --steps " &
            & // request%text("--steps", "")
        if (times%dtout_given) times%written = times%written // " --dtout " &
            & // request%text("--dtout", "")
        times%written = trim(adjustl(times%written))
    end subroutine run_times_of

    !> --call-timeout SECONDS: the longest one call of a user's routine may take, a positive
    !> number up to a day (default: the job's own).
    subroutine call_timeout_of(request, seconds, error)
        type(cli_request_type), intent(in) :: request
        real(wp), intent(inout) :: seconds
        type(error_type), allocatable, intent(out) :: error

        call request%real_value("--call-timeout", seconds, seconds, error)
        if (allocated(error)) return
        if (.not. (seconds > 0.0_wp .and. seconds <= longest_call_timeout)) &
            & call fatal_error(error, "--call-timeout must be a positive number of seconds up " &
            & // "to " // to_text(longest_call_timeout) // ", got '" &
            & // request%text("--call-timeout", "") // "'", stat_input)
    end subroutine call_timeout_of

    !> Write DIR/<base>_vtk/<base>.pvd and its frames from DIR/<base>.csv and the part shapes
    !> beside it (DIR/<base>.parts).
    subroutine write_csv_vtk(csv_path, fps, error)
        !> The run's CSV
        character(len=*), intent(in) :: csv_path
        !> Frames per second of simulated time [1/s]
        real(wp), intent(in) :: fps
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        character(len=:), allocatable :: folder, name
        integer :: frames

        call read_run(csv_path, run, error)
        if (allocated(error)) return
        name = file_stem(csv_path, ".csv")
        folder = csv_path(:len(csv_path) - len(file_stem(csv_path, ""))) // name // "_vtk"
        call make_folder(folder, error)
        if (allocated(error)) return
        call write_vtk_series(folder, name, run, fps, frames, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "vtk: wrote " // folder // "/" // name // ".pvd (" &
            & // to_text(frames) // " frames, " // to_text(size(run%shapes)) // " part" &
            & // trim(merge("s", " ", size(run%shapes) /= 1)) // "; open it in ParaView)"
    end subroutine write_csv_vtk

end module rollcon_command_run
