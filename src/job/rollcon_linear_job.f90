! SPDX-License-Identifier: MIT
!> A job's linear analysis (docs/linear.md): the job's model built as a run builds it, with the
!> start its initial-conditions analysis made consistent, linearised on its constraint manifold
!> (src/analysis/rollcon_linearisation), and the eigenvalues written to DIR/MODEL.eigen.csv
!> whole or not at all (written under a partial name, renamed into place when complete).
module rollcon_linear_job
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : lower_case
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_output_files, only : partial_name, write_text_file, rename_file, delete_file, &
        & make_folders
    use rollcon_problem, only : problem_type
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise
    use rollcon_linear_report, only : eigen_csv_rows
    use rollcon_job, only : job_type
    use rollcon_provenance, only : provenance_lines
    implicit none
    private

    public :: linearise_job, write_eigen_csv, eigen_csv_path

contains

    !> Build the job's model and its consistent start (t = 0) and linearise there. A job whose
    !> UCONs a user's file serves is refused: that routine runs only in a child process
    !> (docs/checker.md), which the linear analysis does not use. report: what making the
    !> start consistent changed, in lines ("" when nothing was analysed).
    subroutine linearise_job(job, result, report, error, options)
        type(job_type), intent(inout) :: job
        type(linear_result_type), intent(out) :: result
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        !> How to linearise (default: no Baumgarte terms, the default step)
        type(linear_options_type), intent(in), optional :: options
        type(problem_type), target :: problem
        type(linear_options_type) :: chosen
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:)

        report = ""
        if (present(options)) chosen = options
        if (len(job%user_file) > 0) then
            call fatal_error(error, "--ucosub " // job%user_file // ": the linear analysis " &
                & // "runs built-in routines only (a user's routine runs in a child process, " &
                & // "docs/checker.md, which it does not use); give --ucosub NAME of a " &
                & // "built-in routine, or check and simulate your routine with rollcon check " &
                & // "and rollcon run", stat_input)
            return
        end if
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call linearise(problem, 0.0_wp, q0, u0, chosen, result, error)
        if (allocated(error) .and. len(job%source%path) > 0) &
            & error%message = job%source%path // ": " // error%message
    end subroutine linearise_job

    !> DIR/MODEL.eigen.csv: MODEL the input's file name without its .adm or .nml (the job's
    !> name for a model built in code).
    function eigen_csv_path(job) result(path)
        type(job_type), intent(in) :: job
        character(len=:), allocatable :: path

        path = job%output_dir // "/" // eigen_stem(job) // ".eigen.csv"
    end function eigen_csv_path

    !> The stem of the eigenvalue CSV.
    pure function eigen_stem(job) result(stem)
        type(job_type), intent(in) :: job
        character(len=:), allocatable :: stem
        integer :: n

        stem = job%name
        n = len(stem)
        if (n > 4) then
            if (lower_case(stem(n - 3:)) == ".adm" .or. lower_case(stem(n - 3:)) == ".nml") &
                & stem = stem(:n - 4)
        end if
    end function eigen_stem

    !> Write the eigenvalues to eigen_csv_path(job) (the folder made when missing): the
    !> record (rollcon_provenance) and a line saying what the numbers are, as # comments, then
    !> `real,imag` [1/s] and one row per eigenvalue. Written under a partial name and renamed
    !> into place: an earlier file stays whole until the new one is.
    subroutine write_eigen_csv(job, result, path, error)
        type(job_type), intent(in) :: job
        type(linear_result_type), intent(in) :: result
        !> The file written
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: cleanup_error
        character(len=:), allocatable :: partial, text, record
        integer :: cut

        path = eigen_csv_path(job)
        call make_folders(job%output_dir, error)
        if (allocated(error)) return
        partial = partial_name(job%output_dir, eigen_stem(job), ".eigen.csv")
        record = provenance_lines(job)
        text = ""
        do while (len(record) > 0)
            cut = index(record, new_line("a"))
            text = text // "# " // record(:cut)
            record = record(cut + 1:)
        end do
        text = text // "# eigenvalues [1/s] of the linearisation on the constraint manifold at " &
            & // "t = 0 s (docs/linear.md), by decreasing real part" // new_line("a") &
            & // eigen_csv_rows(result)
        call write_text_file(partial, text(:len(text) - 1), error)
        if (.not. allocated(error)) call rename_file(partial, path, error)
        if (allocated(error)) call delete_file(partial, cleanup_error)
    end subroutine write_eigen_csv

end module rollcon_linear_job
