! SPDX-License-Identifier: MIT
!> `rollcon linear MODEL.adm`: the dataset's model linearised on its constraint manifold about
!> its consistent start (docs/linear.md); prints the eigenvalue table and writes
!> DIR/MODEL.eigen.csv.
module rollcon_command_linear
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : error_type, fatal_error, stat_input, job_type, load_job, is_dataset, &
        & add_user_file, &
        & linear_result_type, linearise_job, write_eigen_csv, linear_table_text, wp, &
        & speed_table_type, stability_change_type, linear_speeds_job, write_speed_csv, &
        & draw_eigen_speed_figure, to_text
    use rollcon_program, only : command_line_text, fixed_text, check_at_start
    use rollcon_command_run, only : call_timeout_of
    use rollcon_cli, only : cli_request_type
    implicit none
    private

    public :: linear_command, print_linear_help

contains

    !> Run the command (error: a refusal or a failure).
    subroutine linear_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(linear_result_type) :: result
        character(len=:), allocatable :: path, report, written, defined
        integer :: k

        path = request%positional
        if (len(path) == 0) then
            call fatal_error(error, "rollcon linear needs a dataset, MODEL.adm; run 'rollcon " &
                & // "linear --help' for the usage", stat_input)
            return
        end if
        if (.not. is_dataset(path)) then
            call fatal_error(error, path // ": not a dataset: rollcon linear takes an ADAMS " &
                & // "dataset, a file named MODEL.adm (docs/datasets.md)", stat_input)
            return
        end if
        call load_job(path, job, error, ucosub=request%nth("--ucosub", 1))
        if (allocated(error)) return
        ! more files of user routines, run with the first in its child process, as a run's
        do k = 2, request%count("--ucosub")
            call add_user_file(job, request%nth("--ucosub", k), error)
            if (allocated(error)) return
        end do
        job%quiet = request%has("--quiet")
        call call_timeout_of(request, job%call_timeout, error)
        if (allocated(error)) return
        ! a user's UCOSUB is checked at the consistent start, before the linearisation
        if (.not. request%has("--no-check")) job%start_check => check_at_start
        if (len(job%source%input_warning()) > 0) write(error_unit, '(a)') "rollcon: warning: " &
            & // job%source%input_warning()
        job%output_dir = request%text("--output", "output")
        job%command_line = command_line_text()
        if (request%has("--speeds")) then
            call speeds_command(request, path, job, error)
            return
        end if
        call linearise_job(job, result, report, error, defined=defined)
        if (allocated(error)) return
        if (.not. request%has("--quiet") .and. len(report) > 0) write(output_unit, '(a)') report
        write(output_unit, '(a)') linear_table_text(result, path // " at t = 0 s")
        if (.not. result%invariant) write(error_unit, '(a)') "rollcon: warning: " // path &
            & // ": the tangent space of the constraints is not invariant at the start (the " &
            & // "start is no steady motion): the eigenvalues are those of the equations " &
            & // "frozen there"
        call write_eigen_csv(job, result, written, error, defined)
        if (allocated(error)) return
        write(output_unit, '(a)') "output: " // written
    end subroutine linear_command

    !> --speeds FROM,TO,COUNT: the eigenvalues at COUNT speeds from FROM to TO [m/s], the
    !> speeds where stability changes printed, the CSV and the figure written.
    subroutine speeds_command(request, path, job, error)
        type(cli_request_type), intent(in) :: request
        character(len=*), intent(in) :: path
        type(job_type), intent(inout) :: job
        type(error_type), allocatable, intent(out) :: error
        type(speed_table_type) :: table
        type(stability_change_type), allocatable :: changes(:)
        character(len=:), allocatable :: report, written, png, defined
        real(wp) :: grid(3)
        real(wp), allocatable :: speeds(:)
        integer :: points, k

        grid = 0.0_wp
        call request%real_list("--speeds", grid, error)
        if (allocated(error)) return
        points = nint(grid(3))
        if (abs(grid(3) - points) > 0.0_wp .or. points < 2 .or. points > 100000 &
            & .or. grid(1) < 0.0_wp .or. grid(2) <= grid(1)) then
            call fatal_error(error, "--speeds expects FROM,TO,COUNT with 0 <= FROM < TO [m/s] " &
                & // "and a whole COUNT from 2 to 100000 (the speeds, ends included), got '" &
                & // request%text("--speeds", "") // "'", stat_input)
            return
        end if
        ! both ends exactly as given
        speeds = [(grid(1)*real(points - 1 - k, wp)/real(points - 1, wp) &
            & + grid(2)*real(k, wp)/real(points - 1, wp), k = 0, points - 1)]
        call linear_speeds_job(job, speeds, table, changes, report, error, defined=defined)
        if (allocated(error)) return
        if (.not. request%has("--quiet") .and. len(report) > 0) write(output_unit, '(a)') report
        write(output_unit, '(a)') "eigenvalues of " // path // " at " // trim(int_text(points)) &
            & // " speeds from " // to_text(grid(1)) // " to " &
            & // to_text(grid(2)) // " m/s (every velocity of the start scaled), " &
            & // trim(int_text(size(table%real_part, 1))) // " after " &
            & // trim(int_text(count(table%struck) + table%deflations)) &
            & // " structural zeros taken out"
        if (size(changes) == 0) write(output_unit, '(a)') "stability does not change in that range"
        do k = 1, size(changes)
            write(output_unit, '(a)') "stability changes at " // fixed_text(changes(k)%speed, 6) &
                & // " m/s: " // trim(merge("oscillatory (a complex pair: weave)   ", &
                & "divergent (a real eigenvalue: capsize)", changes(k)%oscillatory)) &
                & // merge("; stable above", "; stable below", changes(k)%stable_above)
        end do
        call write_speed_csv(job, table, changes, written, error, defined)
        if (allocated(error)) return
        write(output_unit, '(a)') "output: " // written
        png = written(:len(written) - len(".csv")) // ".png"
        call draw_eigen_speed_figure(table, changes, "Eigenvalues of " // path &
            & // " against speed", png, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "output: " // png
    end subroutine speeds_command

    pure function int_text(n) result(text)
        integer, intent(in) :: n
        character(len=12) :: text

        write(text, '(i0)') n
    end function int_text

    subroutine print_linear_help()
        write(output_unit, '(a)') &
            & "usage: rollcon linear MODEL.adm [--output DIR] [--ucosub FILE|NAME]... [--quiet]", &
            & "                      [--speeds FROM,TO,COUNT] [--no-check]", &
            & "                      [--call-timeout SECONDS]", &
            & "", &
            & "Linear analysis (as ADAMS's LINEAR/EIGENSOL): the dataset's model, its start made", &
            & "consistent by the initial-conditions analysis (a steady motion such as straight", &
            & "rolling, or an equilibrium), linearised on its constraint manifold in independent", &
            & "coordinates and speeds (no eigenvalues from the constraint rows or Baumgarte", &
            & "terms). Prints every eigenvalue [1/s], by decreasing real part, with its undamped", &
            & "natural frequency |lambda|/(2 pi) and damped frequency " &
            & // "|Im lambda|/(2 pi) [Hz] and", &
            & "its damping ratio -Re lambda/|lambda|, and writes DIR/MODEL.eigen.csv (MODEL the", &
            & "file name without .adm; DIR defaults to ./output): # lines with the record, then", &
            & "the columns real,imag [1/s], one row per eigenvalue. See docs/linear.md.", &
            & "  --output DIR   folder of the CSV (made when missing)", &
            & "  --ucosub FILE|NAME", &
            & "                 the model's user routines, as rollcon run takes them: a file", &
            & "                 of your own (.f, .f90, .o; given again for more files, named by", &
            & "                 ROUTINE=FILE::NAME) serves the UCONs that name no ROUTINE and", &
            & "                 the statements with FUNCTION=USER(...); it is compiled, cached", &
            & "                 and run in a child process with the time limit per call, and", &
            & "                 its own partials are the linearisation's. NAME: a built-in", &
            & "                 routine (disk, rolling_disk, ...) when no file NAME exists", &
            & "  --no-check     do not compare your UCOSUB's partials with differences at the", &
            & "                 consistent start before linearising (rollcon run --help)", &
            & "  --call-timeout SECONDS", &
            & "                 the longest one call of your routine may take (default 10)", &
            & "  --quiet        do not print what the initial-conditions analysis moved", &
            & "  --speeds FROM,TO,COUNT", &
            & "                 eigenvalues against speed: every velocity of the start scaled", &
            & "                 so that the first moving part's centre of mass moves at each", &
            & "                 of COUNT speeds from FROM to TO [m/s] (a steady motion whose", &
            & "                 velocities all scale with its speed: straight rolling); the", &
            & "                 structural zeros (cyclic coordinates, conserved speeds) taken", &
            & "                 out; prints the speeds where stability changes (to 1e-9 m/s),", &
            & "                 writes DIR/MODEL.eigen-speed.csv and its figure .png", &
            & "", &
            & "Exit status: 0 when the CSV is written, 1 on bad input (not a dataset, a start", &
            & "off the constraints, a singular constraint Jacobian) or a failure."
    end subroutine print_linear_help

end module rollcon_command_linear
