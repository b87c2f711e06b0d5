! SPDX-License-Identifier: MIT
!> `rollcon linear MODEL.adm`: the dataset's model linearised on its constraint manifold about
!> its consistent start (docs/linear.md); prints the eigenvalue table and writes
!> DIR/MODEL.eigen.csv.
module rollcon_command_linear
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : error_type, fatal_error, stat_input, job_type, load_job, is_dataset, &
        & linear_result_type, linearise_job, write_eigen_csv, linear_table_text, &
        & command_line_text
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
        character(len=:), allocatable :: path, report, written

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
        call load_job(path, job, error, ucosub=request%text("--ucosub", ""))
        if (allocated(error)) return
        if (len(job%source%input_warning()) > 0) write(error_unit, '(a)') "rollcon: warning: " &
            & // job%source%input_warning()
        job%output_dir = request%text("--output", "output")
        job%command_line = command_line_text()
        call linearise_job(job, result, report, error)
        if (allocated(error)) return
        if (.not. request%has("--quiet") .and. len(report) > 0) write(output_unit, '(a)') report
        write(output_unit, '(a)') linear_table_text(result, path // " at t = 0 s")
        if (.not. result%invariant) write(error_unit, '(a)') "rollcon: warning: " // path &
            & // ": the tangent space of the constraints is not invariant at the start (the " &
            & // "start is no steady motion): the eigenvalues are those of the equations " &
            & // "frozen there"
        call write_eigen_csv(job, result, written, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "output: " // written
    end subroutine linear_command

    subroutine print_linear_help()
        write(output_unit, '(a)') &
            & "usage: rollcon linear MODEL.adm [--output DIR] [--ucosub NAME] [--quiet]", &
            & "", &
            & "Linear analysis (as ADAMS's LINEAR/EIGENSOL): the dataset's model, its start made", &
            & "consistent by the initial-conditions analysis (a steady motion such as straight", &
            & "rolling, or an equilibrium), linearised on its constraint manifold in independent", &
            & "coordinates and speeds (no eigenvalues from the constraint rows or Baumgarte", &
            & "terms). Prints every eigenvalue [1/s], by decreasing real part, with its undamped", &
            & "natural frequency |lambda|/(2 pi) and damped frequency |Im lambda|/(2 pi) [Hz] and", &
            & "its damping ratio -Re lambda/|lambda|, and writes DIR/MODEL.eigen.csv (MODEL the", &
            & "file name without .adm; DIR defaults to ./output): # lines with the record, then", &
            & "the columns real,imag [1/s], one row per eigenvalue. See docs/linear.md.", &
            & "  --output DIR   folder of the CSV (made when missing)", &
            & "  --ucosub NAME  serve the UCONs that name no ROUTINE with a built-in routine", &
            & "                 (disk, rolling_disk, ...); a file of your own is refused: it", &
            & "                 runs only in a child process, which linear does not use", &
            & "  --quiet        do not print what the initial-conditions analysis moved", &
            & "", &
            & "Exit status: 0 when the CSV is written, 1 on bad input (not a dataset, a start", &
            & "off the constraints, a singular constraint Jacobian) or a failure."
    end subroutine print_linear_help

end module rollcon_command_linear
