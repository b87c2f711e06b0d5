! SPDX-License-Identifier: MIT
!> A job's linear analysis (docs/linear.md): the job's model built as a run builds it, with the
!> start its initial-conditions analysis made consistent, linearised on its constraint manifold
!> (src/analysis/rollcon_linearisation), and the eigenvalues written to DIR/MODEL.eigen.csv
!> whole or not at all (written under a partial name, renamed into place when complete).
module rollcon_linear_job
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : lower_case
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_output_files, only : partial_name, write_text_file, rename_file, delete_file, &
        & make_folders
    use rollcon_problem, only : problem_type
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise
    use rollcon_linear_report, only : eigen_csv_rows
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type, speed_table, &
        & stability_changes
    use rollcon_text, only : to_text, fixed_text
    use rollcon_job, only : job_type
    use rollcon_provenance, only : provenance_lines
    use rollcon_isolated_linear, only : linearise_apart, linear_speeds_apart
    implicit none
    private

    public :: linearise_job, write_eigen_csv, eigen_csv_path
    public :: linear_speeds_job, write_speed_csv, speed_csv_path

contains

    !> Build the job's model and its consistent start (t = 0) and linearise there. A job whose
    !> routines come from a user's file (job%user_file) builds and linearises in a child
    !> process (rollcon_isolated_linear), as its run does: the routine's own partials, its
    !> calls guarded and timed. report: what making the start consistent changed, in lines
    !> ("" when nothing was analysed). defined: what the user's files define, as the child
    !> found them ("" for a built-in routine), for the record of write_eigen_csv, worded as a
    !> run's (rollcon_provenance's provenance_lines).
    subroutine linearise_job(job, result, report, error, options, defined)
        type(job_type), intent(inout) :: job
        type(linear_result_type), intent(out) :: result
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        !> How to linearise (default: no Baumgarte terms, the default step)
        type(linear_options_type), intent(in), optional :: options
        character(len=:), allocatable, intent(out), optional :: defined
        type(problem_type), target :: problem
        type(linear_options_type) :: chosen
        real(wp), allocatable :: q0(:), u0(:)
        ! what the child told, through a local: gfortran 12 loses an optional deferred-length
        ! argument passed on as an optional one
        character(len=:), allocatable :: told

        if (present(options)) chosen = options
        if (present(defined)) defined = ""
        if (len(job%user_file) > 0) then
            call linearise_apart(job, chosen, result, report, error, told)
            if (present(defined) .and. allocated(told)) call move_alloc(told, defined)
        else
            call build_start(job, problem, q0, u0, report, error)
            if (.not. allocated(error)) call linearise(problem, 0.0_wp, q0, u0, chosen, result, &
                & error)
        end if
        if (allocated(error) .and. len(job%source%path) > 0) &
            & error%message = job%source%path // ": " // error%message
    end subroutine linearise_job

    !> Build the job's model and its consistent start (t = 0), linearise at every speed of the
    !> grid (the start's velocities scaled: rollcon_linear_speeds) and find where stability
    !> changes. A user's file runs in a child process, as for linearise_job; defined as
    !> linearise_job's, for write_speed_csv's record.
    subroutine linear_speeds_job(job, speeds, table, changes, report, error, options, defined)
        type(job_type), intent(inout) :: job
        !> Speeds [m/s]
        real(wp), intent(in) :: speeds(:)
        type(speed_table_type), intent(out) :: table
        type(stability_change_type), allocatable, intent(out) :: changes(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(linear_options_type), intent(in), optional :: options
        character(len=:), allocatable, intent(out), optional :: defined
        type(problem_type), target :: problem
        type(linear_options_type) :: chosen
        real(wp), allocatable :: q0(:), u0(:)
        ! what the child told, through a local: gfortran 12 loses an optional deferred-length
        ! argument passed on as an optional one
        character(len=:), allocatable :: told

        if (present(options)) chosen = options
        if (present(defined)) defined = ""
        if (len(job%user_file) > 0) then
            call linear_speeds_apart(job, speeds, chosen, table, changes, report, error, told)
            if (present(defined) .and. allocated(told)) call move_alloc(told, defined)
        else
            call build_start(job, problem, q0, u0, report, error)
            if (.not. allocated(error)) call speed_table(problem, 0.0_wp, q0, u0, speeds, &
                & chosen, table, error)
            if (.not. allocated(error)) call stability_changes(problem, 0.0_wp, q0, u0, table, &
                & chosen, changes, error)
        end if
        if (allocated(error) .and. len(job%source%path) > 0) &
            & error%message = job%source%path // ": " // error%message
    end subroutine linear_speeds_job

    !> DIR/MODEL.eigen-speed.csv, beside eigen_csv_path(job).
    function speed_csv_path(job) result(path)
        type(job_type), intent(in) :: job
        character(len=:), allocatable :: path

        path = job%output_dir // "/" // eigen_stem(job) // ".eigen-speed.csv"
    end function speed_csv_path

    !> Write the eigenvalues against speed to speed_csv_path(job), whole or not at all: the
    !> record and the stability changes as # lines, then `speed,real_1,imag_1,...` [m/s, 1/s]
    !> and one row per speed. defined: linear_speeds_job's, when it gave one (the record then
    !> words the user's files by what they define, as a run's does).
    subroutine write_speed_csv(job, table, changes, path, error, defined)
        type(job_type), intent(in) :: job
        type(speed_table_type), intent(in) :: table
        type(stability_change_type), intent(in) :: changes(:)
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: defined
        type(error_type), allocatable :: cleanup_error
        character(len=:), allocatable :: partial, text
        character(len=26) :: number
        integer :: k, i

        path = speed_csv_path(job)
        call make_folders(job%output_dir, error)
        if (allocated(error)) return
        partial = partial_name(job%output_dir, eigen_stem(job), ".eigen-speed.csv")
        text = comment_lines(provenance_lines(job, defined)) // "# eigenvalues [1/s] of the " &
            & // "linearisation on the constraint manifold against the speed [m/s] of the " &
            & // "first moving part (every velocity of the start scaled), the structural " &
            & // "zeros taken out (" // to_text(count(table%struck) + table%deflations) &
            & // "), by decreasing " &
            & // "real part (docs/linear.md)" // new_line("a")
        do k = 1, size(changes)
            write(number, '(es24.16e3)') changes(k)%speed
            text = text // "# stability changes at " // trim(adjustl(number)) // " m/s: " &
                & // change_words(changes(k)) // new_line("a")
        end do
        text = text // "speed"
        do i = 1, size(table%real_part, 1)
            text = text // ",real_" // to_text(i) // ",imag_" // to_text(i)
        end do
        do k = 1, size(table%speed)
            write(number, '(es24.16e3)') table%speed(k)
            text = text // new_line("a") // trim(adjustl(number))
            do i = 1, size(table%real_part, 1)
                write(number, '(es24.16e3)') table%real_part(i, k)
                text = text // "," // trim(adjustl(number))
                write(number, '(es24.16e3)') table%imag_part(i, k)
                text = text // "," // trim(adjustl(number))
            end do
        end do
        call write_text_file(partial, text, error)
        if (.not. allocated(error)) call rename_file(partial, path, error)
        if (allocated(error)) call delete_file(partial, cleanup_error)
    end subroutine write_speed_csv

    !> What a stability change is, in words: which kind of eigenvalue crosses, and on which
    !> side the motion is stable.
    function change_words(change) result(words)
        type(stability_change_type), intent(in) :: change
        character(len=:), allocatable :: words

        if (change%oscillatory) then
            words = "a complex pair crosses the imaginary axis (an oscillation at " &
                & // fixed_text(change%frequency, 6) // " rad/s, as a bicycle's weave)"
        else
            words = "a real eigenvalue passes through zero (a divergence, as a bicycle's capsize)"
        end if
        if (change%stable_above) then
            words = words // "; stable above"
        else
            words = words // "; stable below"
        end if
    end function change_words

    !> Lines as # comments, each ending with a new line.
    function comment_lines(lines) result(text)
        character(len=*), intent(in) :: lines
        character(len=:), allocatable :: text
        integer :: start, cut

        text = ""
        start = 1
        do while (start <= len(lines))
            cut = index(lines(start:), new_line("a"))
            if (cut == 0) cut = len(lines) - start + 2
            text = text // "# " // lines(start:start + cut - 2) // new_line("a")
            start = start + cut
        end do
    end function comment_lines

    !> The job's problem built as a run builds it in this process (a built-in routine), with
    !> the consistent start at t = 0 and the report of what making it consistent changed.
    subroutine build_start(job, problem, q0, u0, report, error)
        type(job_type), intent(inout) :: job
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine

        report = ""
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
    end subroutine build_start

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
    !> into place: an earlier file stays whole until the new one is. defined: linearise_job's,
    !> when it gave one (the record then words the user's files by what they define, as a
    !> run's does).
    subroutine write_eigen_csv(job, result, path, error, defined)
        type(job_type), intent(in) :: job
        type(linear_result_type), intent(in) :: result
        !> The file written
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: defined
        type(error_type), allocatable :: cleanup_error
        character(len=:), allocatable :: partial, text

        path = eigen_csv_path(job)
        call make_folders(job%output_dir, error)
        if (allocated(error)) return
        partial = partial_name(job%output_dir, eigen_stem(job), ".eigen.csv")
        text = comment_lines(provenance_lines(job, defined)) // "# eigenvalues [1/s] of the " &
            & // "linearisation on the constraint manifold at " &
            & // "t = 0 s (docs/linear.md), by decreasing real part" // new_line("a") &
            & // eigen_csv_rows(result)
        call write_text_file(partial, text(:len(text) - 1), error)
        if (.not. allocated(error)) call rename_file(partial, path, error)
        if (allocated(error)) call delete_file(partial, cleanup_error)
    end subroutine write_eigen_csv

end module rollcon_linear_job
