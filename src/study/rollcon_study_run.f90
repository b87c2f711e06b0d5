! SPDX-License-Identifier: MIT
!> Running a study (docs/studies.md): its plan (every case's parameters, and which cases the
!> CSV already holds), one case run as the ordinary simulation of its scene, and the rows
!> appended as cases end. A case that fails or is refused is a row like any other: it never
!> stops the study. The loop over cases is the caller's: in one process (run_study) or
!> handed out to MPI ranks by the program (app/rollcon_sweep_mpi.f90).
module rollcon_study_run
    use, intrinsic :: iso_fortran_env, only : error_unit
    use rollcon_kinds, only : wp
    use rollcon_clock, only : wall_seconds, cpu_seconds, cpu_self, cpu_children
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_c_stream, only : c_stream_type
    use rollcon_file_lock, only : file_lock_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type
    use rollcon_job, only : job_type, user_file_type
    use rollcon_load, only : load_job, add_user_file, input_override_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_isolated_run, only : compile_user_files
    use rollcon_study_type, only : study_type
    use rollcon_study_parameters, only : case_count, case_values, value_text
    use rollcon_study_measures, only : case_result_type, outcome_refused, outcome_failed, &
        & measure_case
    use rollcon_study_rules, only : classify
    use rollcon_study_csv, only : study_header, study_row, case_key, read_done_cases
    implicit none
    private

    public :: study_plan_type, plan_cases, plan_study, run_case, append_row, run_study
    public :: lock_study_csv, prepare_study_routines
    public :: row_file_type
    public :: study_progress_type

    !> Every case of a study, and which are still to run
    type :: study_plan_type
        !> texts(k, i): parameter k of case i as its scene and its row take it
        character(len=:), allocatable :: texts(:, :)
        !> The case is in the CSV already
        logical, allocatable :: done(:)
        !> Rows of the CSV that are not cases of this study (the study file changed)
        integer :: foreign = 0
        !> Lines the CSV held when the plan was made, its header included
        integer :: rows_in_csv = 0
    contains
        procedure :: pending
        procedure :: case_texts
    end type study_plan_type

    !> A CSV kept open while rows are appended, each flushed as it is written. Written through
    !> the C library (rollcon_c_stream), every write and flush checked: gfortran 12 reports no
    !> error when a write or a flush fails on a full disk.
    type :: row_file_type
        type(c_stream_type) :: stream
        character(len=:), allocatable :: path
        !> Rows the file held when it was opened (the header and the cases of earlier runs)
        integer :: rows_before = 0
        !> Rows written and flushed since
        integer :: rows_written = 0
    contains
        procedure :: open => row_file_open
        procedure :: write => row_file_write
        procedure :: close => row_file_close
    end type row_file_type

    !> Counts for the progress lines and the closing summary
    type :: study_progress_type
        integer :: total = 0, skipped = 0, done = 0, failed = 0, refused = 0
        !> CPU time the coordinating rank spent on messages: receiving rows, writing them,
        !> handing out cases [s] (0 when one process ran the cases)
        real(wp) :: coordinator_cpu = 0.0_wp
        real(wp) :: started = 0.0_wp, last = 0.0_wp
        !> No progress lines (until start says otherwise)
        logical :: quiet = .true.
    contains
        procedure :: start => progress_start
        procedure :: add => progress_add
    end type study_progress_type

contains

    !> Take the lock of a study's CSV, CSV.lock beside it, for as long as rows may be read and
    !> written (until lock%release or the end of the process): a second sweep into the same
    !> CSV is refused, naming the sweep that holds it, instead of mixing its rows with the
    !> first one's into a CSV the next resume refuses.
    subroutine lock_study_csv(csv_path, lock, error)
        character(len=*), intent(in) :: csv_path
        type(file_lock_type), intent(inout) :: lock
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: holder
        logical :: held

        call lock%acquire(csv_path // ".lock", held, holder, error)
        if (allocated(error) .or. .not. held) return
        if (len(holder) == 0) holder = "a process that has not said which yet"
        call fatal_error(error, csv_path // ": another sweep is writing this study's CSV (" &
            & // holder // " holds " // csv_path // ".lock); two sweeps into one CSV would " &
            & // "mix their rows. Wait until it ends (then run the same command to resume), " &
            & // "or give another --output", stat_io)
    end subroutine lock_study_csv

    !> The study's routines made ready before its cases: the base input loaded with them (a
    !> file that does not exist, a name that is no built-in routine, refused here once rather
    !> than in every case's row) and a user's files compiled into the cache, so that every case
    !> (on any rank) finds them there. Refusals in the terms of `rollcon run --ucosub`.
    subroutine prepare_study_routines(study, error)
        type(study_type), intent(in) :: study
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(user_file_type), allocatable :: more_libraries(:)
        character(len=:), allocatable :: library
        integer :: k

        if (.not. allocated(study%routines)) return
        if (size(study%routines) == 0) return
        call load_job(study%scene_path, job, error, ucosub=study%routines(1)%path)
        if (allocated(error)) return
        do k = 2, size(study%routines)
            call add_user_file(job, study%routines(k)%path, error)
            if (allocated(error)) return
        end do
        if (len(job%user_file) == 0) return
        job%quiet = .true.
        call compile_user_files(job, library, more_libraries, error)
    end subroutine prepare_study_routines

    !> Every case's parameters, none done yet (what a worker rank needs).
    subroutine plan_cases(study, plan)
        type(study_type), intent(in) :: study
        type(study_plan_type), intent(out) :: plan
        real(wp), allocatable :: values(:, :)
        integer :: n, i, k, width

        call case_values(study, values)
        n = case_count(study)
        width = 1
        do i = 1, n
            do k = 1, size(study%parameters)
                width = max(width, len(value_text(study%parameters(k), values(k, i))))
            end do
        end do
        allocate(character(len=width) :: plan%texts(size(study%parameters), n))
        do i = 1, n
            do k = 1, size(study%parameters)
                plan%texts(k, i) = value_text(study%parameters(k), values(k, i))
            end do
        end do
        allocate(plan%done(n), source=.false.)
    end subroutine plan_cases

    !> The plan of a study whose rows go to csv_path: the cases' parameters, and those the CSV
    !> holds already (by parameters, not order: rollcon_study_csv). A new CSV gets its header.
    subroutine plan_study(study, csv_path, plan, error)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: csv_path
        type(study_plan_type), intent(out) :: plan
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: rows(:)
        character(len=:), allocatable :: keys(:), own(:)
        integer :: n, i, r

        call plan_cases(study, plan)
        n = size(plan%done)
        call read_done_cases(csv_path, study, rows, keys, error, plan%rows_in_csv)
        if (allocated(error)) return
        if (plan%rows_in_csv == 0) then
            ! a new CSV, or one left empty: its header (once: a CSV of a header alone, from a
            ! run stopped before its first row, keeps the one it has)
            call append_row(csv_path, study_header(study), error)
            if (.not. allocated(error)) plan%rows_in_csv = 1
            return
        end if
        if (size(keys) == 0) return
        allocate(character(len=(len(plan%texts) + 1)*size(study%parameters)) :: own(n))
        do i = 1, n
            own(i) = case_key(plan%case_texts(i))
        end do
        do r = 1, size(keys)
            i = rows(r)
            if (i >= 1 .and. i <= n) then
                if (own(i) == keys(r)) then
                    plan%done(i) = .true.
                    cycle
                end if
            end if
            i = findloc_key(own, keys(r))
            if (i > 0) then
                plan%done(i) = .true.
            else
                plan%foreign = plan%foreign + 1
            end if
        end do
    end subroutine plan_study

    !> The cases still to run, in case order.
    pure function pending(self) result(cases)
        class(study_plan_type), intent(in) :: self
        integer, allocatable :: cases(:)
        integer :: i

        cases = pack([(i, i = 1, size(self%done))], .not. self%done)
    end function pending

    !> The parameter texts of case i. Copied element by element: gfortran 12 passes a
    !> section plan%texts(:, i) of the deferred-length array as its first column.
    pure function case_texts(self, i) result(texts)
        class(study_plan_type), intent(in) :: self
        integer, intent(in) :: i
        character(len=len(self%texts)) :: texts(size(self%texts, 1))
        integer :: k

        do k = 1, size(texts)
            texts(k) = self%texts(k, i)
        end do
    end function case_texts

    !> Run case i: its scene (or dataset) is the base with the case's parameters set; it is
    !> loaded and run as `rollcon run` loads and runs an input (rollcon_load, rollcon_run_job),
    !> with the study's routines (study%routines: the hand-checked disk UCOSUB when none; a
    !> user's file runs apart, compiled once into the cache), no output files, quiet. Returns
    !> its CSV row.
    subroutine run_case(study, plan, i, row, result)
        type(study_type), intent(in) :: study
        type(study_plan_type), intent(in) :: plan
        integer, intent(in) :: i
        character(len=:), allocatable, intent(out) :: row
        type(case_result_type), intent(out) :: result
        type(input_override_type) :: overrides(size(study%parameters))
        type(job_type) :: job
        type(job_result_type) :: ran
        type(history_type) :: history
        type(error_type), allocatable :: error
        real(wp) :: cpu_start, cpu_end
        character(len=:), allocatable :: first
        integer :: k

        first = ""
        cpu_start = cpu_seconds(cpu_self) + cpu_seconds(cpu_children)
        do k = 1, size(study%parameters)
            overrides(k)%name = study%parameters(k)%group // "%" // study%parameters(k)%key
            overrides(k)%value = trim(plan%texts(k, i))
        end do
        if (allocated(study%routines)) then
            if (size(study%routines) > 0) first = study%routines(1)%path
        end if
        call load_job(study%scene_path, job, error, ucosub=first, overrides=overrides)
        if (.not. allocated(error) .and. allocated(study%routines)) then
            do k = 2, size(study%routines)
                call add_user_file(job, study%routines(k)%path, error)
                if (allocated(error)) exit
            end do
        end if
        if (.not. allocated(error)) then
            job%output_dir = ""
            job%quiet = .true.
            if (study%call_timeout > 0.0_wp) job%call_timeout = study%call_timeout
            job%start_check => study%start_check
            call run_job(job, ran, error, history)
        end if
        if (.not. ran%started) then
            result%outcome = outcome_refused
            result%message = error%message
        else
            ! the child that ran a user routine has ended and been waited for: its time counts
            cpu_end = cpu_seconds(cpu_self) + cpu_seconds(cpu_children)
            call measure_case(ran%summary, history, cpu_end - cpu_start, result)
            if (allocated(error)) then
                result%outcome = outcome_failed
                result%message = error%message
            end if
        end if
        result%class = classify(study, result)
        row = study_row(i, plan%case_texts(i), result)
    end subroutine run_case

    !> Open the CSV for appending rows (created when missing). rows_before: the lines it
    !> holds already (header included), for the message of a failed write.
    subroutine row_file_open(self, path, error, rows_before)
        class(row_file_type), intent(inout) :: self
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: rows_before

        self%path = path
        self%rows_before = 0
        if (present(rows_before)) self%rows_before = rows_before
        self%rows_written = 0
        call self%stream%open_file(path, error, append=.true.)
    end subroutine row_file_open

    !> Write one line and flush it: a row is in the file when its case ends. A failure (a
    !> full disk) says which rows the file holds: those written before, whole; the line that
    !> failed may be in it cut short (a rerun drops it and runs that case again).
    subroutine row_file_write(self, line, error)
        class(row_file_type), intent(inout) :: self
        character(len=*), intent(in) :: line
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: ignored

        if (.not. self%stream%is_open()) then
            call fatal_error(error, self%path // ": cannot write a row: the file is not open", &
                & stat_io)
            return
        end if
        call self%stream%put(line // new_line("a"), error)
        if (.not. allocated(error)) call self%stream%hand_over(error)
        if (.not. allocated(error)) then
            self%rows_written = self%rows_written + 1
            return
        end if
        error%message = error%message // "; the file holds its first " &
            & // to_text(self%rows_before + self%rows_written) // " lines whole (" &
            & // to_text(self%rows_written) // " rows of this run after " &
            & // to_text(self%rows_before) // " lines before it), the line that failed may " &
            & // "follow cut short; run the same command again once there is room: it drops " &
            & // "a cut line and runs the cases that are missing"
        ! nothing more goes to this file
        call self%stream%close_file(ignored)
    end subroutine row_file_write

    !> Close the file; a failure of the last flush is an error.
    subroutine row_file_close(self, error)
        class(row_file_type), intent(inout) :: self
        type(error_type), allocatable, intent(out), optional :: error
        type(error_type), allocatable :: failed

        call self%stream%close_file(failed)
        if (present(error) .and. allocated(failed)) call move_alloc(failed, error)
    end subroutine row_file_close

    !> Append one line to the CSV and flush it (opening and closing the file).
    subroutine append_row(path, line, error)
        character(len=*), intent(in) :: path, line
        type(error_type), allocatable, intent(out) :: error
        type(row_file_type) :: file

        call file%open(path, error)
        if (allocated(error)) return
        call file%write(line, error)
        if (allocated(error)) return
        call file%close(error)
    end subroutine append_row

    !> Run every pending case in this process, in case order.
    subroutine run_study(study, csv_path, plan, progress, error)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: csv_path
        type(study_plan_type), intent(in) :: plan
        type(study_progress_type), intent(inout) :: progress
        type(error_type), allocatable, intent(out) :: error
        type(case_result_type) :: result
        type(row_file_type) :: file
        character(len=:), allocatable :: row
        integer, allocatable :: cases(:)
        integer :: j

        call file%open(csv_path, error, rows_before=plan%rows_in_csv)
        if (allocated(error)) return
        cases = plan%pending()
        do j = 1, size(cases)
            call run_case(study, plan, cases(j), row, result)
            call file%write(row, error)
            if (allocated(error)) exit
            call progress%add(result%outcome)
        end do
        if (allocated(error)) return
        call file%close(error)
    end subroutine run_study

    pure integer function findloc_key(keys, key) result(i)
        character(len=*), intent(in) :: keys(:), key

        do i = 1, size(keys)
            if (keys(i) == key) return
        end do
        i = 0
    end function findloc_key

    !> Start counting: total cases, those skipped as already done.
    subroutine progress_start(self, total, skipped, quiet)
        class(study_progress_type), intent(inout) :: self
        integer, intent(in) :: total, skipped
        logical, intent(in) :: quiet

        self%total = total
        self%skipped = skipped
        self%quiet = quiet
        self%started = wall_seconds()
        self%last = self%started
    end subroutine progress_start

    !> One more case ended with this outcome (rollcon_study_measures); a progress line on
    !> stderr at most every 5 s of wall time.
    subroutine progress_add(self, outcome)
        class(study_progress_type), intent(inout) :: self
        integer, intent(in) :: outcome
        real(wp) :: now, rate
        integer :: left

        self%done = self%done + 1
        if (outcome == outcome_failed) self%failed = self%failed + 1
        if (outcome == outcome_refused) self%refused = self%refused + 1
        now = wall_seconds()
        if (self%quiet .or. now - self%last < 5.0_wp) return
        self%last = now
        left = self%total - self%skipped - self%done
        rate = real(self%done, wp)/max(now - self%started, 1.0e-9_wp)
        write(error_unit, "(a)") "sweep: " // to_text(self%skipped + self%done) // " of " &
            & // to_text(self%total) // " cases done (" // to_text(self%failed) &
            & // " failed, " // to_text(self%refused) // " refused), " &
            & // to_text(nint(now - self%started)) // " s so far, about " &
            & // to_text(nint(left/rate)) // " s to go"
    end subroutine progress_add

end module rollcon_study_run
