! SPDX-License-Identifier: MIT
!> A job whose routine is a user's file: the routine never runs in this process. This process
!> compiles the file into the cache (rollcon_user_build), then a child process
!> (rollcon_child_process) loads the library, builds the model, makes the start consistent and
!> simulates, every call of the routine guarded and timed (rollcon_ucosub_guard). The child
!> only computes: it sends what it finds on a pipe (rollcon_frames) — the report of the start,
!> the parts' shapes, the rows' layout, each row, the summary — and this process writes every
!> output and keeps every clock. A child that crashes, overruns a call or stops leaves the rows
!> it sent; a host that is killed takes the child with it (PR_SET_PDEATHSIG), and the child has
!> no file to write.
module rollcon_isolated_run
    use, intrinsic :: iso_c_binding, only : c_double
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_text, only : to_text, place
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_wire, only : wire_writer_type, wire_reader_type
    use rollcon_output_layout, only : output_layout_type
    use rollcon_row_sink, only : row_sink_type
    use rollcon_problem, only : problem_type
    use rollcon_part_shapes, only : part_shape_type
    use rollcon_run_wire, only : pack_summary, unpack_summary, pack_layout, unpack_layout, &
        & pack_shapes, unpack_shapes
    use rollcon_progress, only : progress_type
    use rollcon_csv_writer, only : csv_writer_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, &
        & status_failed
    use rollcon_child_process, only : isolated_task_type, stream_receiver_type, &
        & call_record_type, isolation_outcome_type, run_in_child, outcome_finished
    use rollcon_frames, only : send_frame, frame_buffer_type
    use rollcon_isolation_text, only : outcome_text, outcome_statement, quote_stderr, &
        & scratch_path
    use rollcon_dataset_source, only : dataset_source_type
    use rollcon_adm_model, only : adm_model_type, adm_request_type, force_names
    use rollcon_ucosub_guard, only : install_guard, attach_call_record, guarded_ucosub
    use rollcon_user_build, only : build_user_library
    use rollcon_user_library, only : user_ucosub_type, load_user_routines, library_named
    use rollcon_user_ucosubs, only : clear_user_ucosubs, find_user_ucosub, &
        & dispatch_user_ucosub, set_user_ucosub_entry, user_ucosub_source
    use rollcon_user_forces, only : clear_force_routines, check_user_motions, find_force_routine
    use rollcon_model, only : served_by_model_ucosub
    use rollcon_force_routine_contract, only : routine_kinds, routine_names
    use rollcon_system_routine_contract, only : routine_reqsub, request_routine_name, &
        & routine_varsub, variable_routine_name, routine_motsub, motion_routine_name, &
        & routine_difsub, diff_routine_name
    use rollcon_force_routine_guard, only : install_force_guard
    use rollcon_job, only : job_type, user_file_type
    use rollcon_analysis_run, only : run_analysis
    implicit none
    private

    public :: run_isolated, compile_user_files, build_apart, hand_on_stderr, statement_place
    public :: defined_text

    !> Kinds of frame the child sends
    integer, parameter :: frame_report = 1, frame_shapes = 2, frame_started = 3, &
        & frame_layout = 4, frame_row = 5, frame_summary = 6, frame_time = 7, &
        & frame_defined = 8

    !> The child's work
    type, extends(isolated_task_type) :: job_task_type
        type(job_type) :: job
        type(run_options_type) :: options
        !> The shared library built from the user's file
        character(len=:), allocatable :: library
        !> Those built from the job's more files (job%more_files), in order
        type(user_file_type), allocatable :: more_libraries(:)
    contains
        procedure :: run => run_task
    end type job_task_type

    !> In the child: the rows go to the pipe
    type, extends(row_sink_type) :: pipe_sink_type
        integer :: fd = -1
    contains
        procedure :: open => pipe_open
        procedure :: put => pipe_put
        procedure :: between_chunks => pipe_between_chunks
    end type pipe_sink_type

    !> In this process: what the child sent, written and kept as it comes
    type, extends(stream_receiver_type) :: job_receiver_type
        type(frame_buffer_type) :: frames
        logical :: quiet = .false.
        type(output_layout_type) :: layout
        logical :: has_layout = .false., started = .false., has_summary = .false.
        type(part_shape_type), allocatable :: shapes(:)
        type(run_summary_type) :: summary
        !> Rows received, and the time of the last [s]
        integer :: rows = 0
        real(wp) :: t_last = 0.0_wp
        type(csv_writer_type) :: csv
        character(len=:), allocatable :: csv_path
        type(history_type), pointer :: history => null()
        type(progress_type) :: progress
        real(wp) :: t0 = 0.0_wp, end_time = 1.0_wp
        !> What the warning of grinding steps says to run (check_hint)
        character(len=:), allocatable :: check_hint
        !> What the user's files define (defined_text), once the child sent it
        character(len=:), allocatable :: defined
        !> The first failure here (a write of the CSV, a frame that does not read)
        type(error_type), allocatable :: failure
    contains
        procedure :: receive
        procedure :: take_frame
    end type job_receiver_type

contains

    !> Run job, whose routine is job%user_file, in a child process (see the module's header).
    subroutine run_isolated(job, options, summary, shapes, started, error, history, defined)
        type(job_type), intent(in) :: job
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(out) :: summary
        type(part_shape_type), allocatable, intent(out) :: shapes(:)
        logical, intent(out) :: started
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), target, optional :: history
        !> What the user's files define, as the child found them once it built the model
        !> (defined_text: the file of the model's own UCOSUB, then a line of words per file);
        !> unallocated when the child sent none
        character(len=:), allocatable, intent(out), optional :: defined
        type(job_task_type) :: task
        type(job_receiver_type) :: receiver
        type(isolation_outcome_type) :: outcome
        character(len=:), allocatable :: stderr_path

        started = .false.
        allocate(shapes(0))
        call compile_user_files(job, task%library, task%more_libraries, error)
        if (allocated(error)) return
        task%job = job
        task%options = options
        ! the child writes no file: this process keeps the rows
        if (allocated(task%options%csv_path)) deallocate(task%options%csv_path)
        task%options%progress = .false.
        receiver%quiet = job%quiet
        if (allocated(options%csv_path)) receiver%csv_path = options%csv_path
        if (present(history)) receiver%history => history
        call receiver%progress%start(options%progress, options%t0, options%end_time, wall=.true.)
        receiver%check_hint = check_hint(job)
        ! the child's stderr (a routine's STOP text, a backtrace) is kept apart: quoted in the
        ! message when the routine ends the child, passed on to this stderr otherwise
        stderr_path = scratch_path("run", 1, ".stderr")
        call run_in_child(task, real(job%call_timeout, c_double), outcome, error, &
            & stderr_path, receiver)
        call conclude(job, receiver, outcome, summary, error)
        call hand_on_stderr(stderr_path, outcome%kind /= outcome_finished, summary, error)
        started = receiver%started
        if (started .and. summary%status == status_failed) call point_at_check(job, summary, &
            & error)
        if (allocated(receiver%shapes)) shapes = receiver%shapes
        if (present(defined) .and. allocated(receiver%defined)) defined = receiver%defined
    end subroutine run_isolated

    !> Compile the job's user files into the cache (rollcon_user_build), in this process: the
    !> library of job%user_file and those of job%more_files, in order. Says which file is
    !> served from where unless job%quiet.
    subroutine compile_user_files(job, library, more_libraries, error)
        type(job_type), intent(in) :: job
        !> The shared library of job%user_file
        character(len=:), allocatable, intent(out) :: library
        !> Those of job%more_files, in order
        type(user_file_type), allocatable, intent(out) :: more_libraries(:)
        type(error_type), allocatable, intent(out) :: error
        logical :: from_cache
        character(len=:), allocatable :: note
        integer :: k

        allocate(more_libraries(0))
        call build_user_library(job%user_file, job%build_options, library, from_cache, &
            & error, note)
        if (allocated(error)) return
        ! what a file defines is known only once the child loaded it: the run's record says it
        if (.not. job%quiet .and. len(note) > 0) write(output_unit, '(a)') "user routines: " &
            & // note // ": rebuilt"
        if (.not. job%quiet) write(output_unit, '(a)') "user routines: " // job%user_file // " (" &
            & // library // trim(merge(", from the cache", ", compiled now  ", &
            & from_cache)) // ")"
        if (allocated(job%more_files)) then
            deallocate(more_libraries)
            allocate(more_libraries(size(job%more_files)))
        end if
        do k = 1, size(more_libraries)
            call build_user_library(job%more_files(k)%path, job%build_options, &
                & more_libraries(k)%path, from_cache, error, note)
            if (allocated(error)) return
            if (.not. job%quiet) write(output_unit, '(a)') "user routines: " &
                & // job%more_files(k)%path // " (" // more_libraries(k)%path &
                & // trim(merge(", from the cache", ", compiled now  ", from_cache)) // ")"
        end do
    end subroutine compile_user_files

    !> The child's process: load the job's libraries (compile_user_files), guard their
    !> routines (every call recorded in record, timed by the host), build the job's model with
    !> them and make its start consistent, then check the routine there when the job asks
    !> (job%start_check; with it, the MOTSUBs' derivatives: check_user_motions) at time [s].
    !> What a run apart, a linear analysis apart and a study's case apart do before their own
    !> work.
    subroutine build_apart(job, library, more_libraries, record, time, problem, q0, u0, &
            & report, error)
        type(job_type), intent(inout) :: job
        character(len=*), intent(in) :: library
        type(user_file_type), intent(in) :: more_libraries(:)
        type(call_record_type), pointer, intent(in) :: record
        !> Time of the start [s]
        real(wp), intent(in) :: time
        type(problem_type), intent(inout), target :: problem
        !> The consistent start: coordinates and rates (system numbering, SI)
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        !> What making the start consistent changed
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(user_ucosub_type) :: more(size(more_libraries))
        procedure(ucosub_interface), pointer :: guarded
        integer :: k

        call attach_call_record(record)
        call clear_force_routines()
        call clear_user_ucosubs()
        user%source = job%user_file
        user%library = library
        ! its UCOSUBs and force routines (rollcon_user_ucosubs', rollcon_user_forces' tables);
        ! a file may define only routines the dataset names by name (ROUTINE=FILE::NAME)
        call load_user_routines(user, error, named_only=.true.)
        if (allocated(error)) return
        do k = 1, size(more_libraries)
            more(k)%source = job%more_files(k)%path
            more(k)%library = more_libraries(k)%path
            call load_user_routines(more(k), error, named_only=.true.)
            if (allocated(error)) return
        end do
        call install_force_guard(record)
        ! every user UCOSUB behind one guard, which finds each UCON's routine by its id
        call install_guard(dispatch_user_ucosub, as_errors=.true.)
        call set_user_ucosub_entry(guarded_ucosub)
        guarded => null()
        if (find_user_ucosub("") > 0) guarded => guarded_ucosub
        call job%source%build(guarded, problem, q0, u0, report, error)
        if (allocated(error)) return
        call refuse_unused(user, error)
        if (allocated(error)) return
        do k = 1, size(more)
            call refuse_unused(more(k), error)
            if (allocated(error)) return
        end do
        if (.not. associated(job%start_check)) return
        call job%start_check(job%user_file, job%input_path, problem, time, q0, u0, error)
        if (allocated(error)) return
        ! the MOTSUBs' IORD = 1, 2 against differences of their IORD = 0, 1
        call check_user_motions(time, q0, u0, error)
    end subroutine build_apart

    !> In the child, once the job's model is built with its files loaded: the file whose
    !> UCOSUB is the model's own (serving a UCON that names no ROUTINE; "" when none is), then a
    !> line per file (job%user_file, then job%more_files) of what it defines, in words: the
    !> routines of fixed name it defines ("UCOSUB, SFOSUB") and "routines named by ROUTINE="
    !> when a statement names one of its subroutines by name; each line ends in a newline.
    !> For the record of a run or a linear analysis (rollcon_provenance's provenance_lines).
    function defined_text(job, problem) result(text)
        type(job_type), intent(in) :: job
        type(problem_type), intent(in) :: problem
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        if (find_user_ucosub("") > 0) then
            do k = 1, problem%model%nc
                if (.not. served_by_model_ucosub(problem%model%ucons(k)%routine)) cycle
                text = user_ucosub_source(find_user_ucosub(""))
                exit
            end do
        end if
        text = text // new_line("a") // file_words(job%user_file) // new_line("a")
        if (allocated(job%more_files)) then
            do k = 1, size(job%more_files)
                text = text // file_words(job%more_files(k)%path) // new_line("a")
            end do
        end if
    contains
        !> What the file at source defines, in words ("" for nothing).
        function file_words(source) result(words)
            character(len=*), intent(in) :: source
            character(len=:), allocatable :: words
            integer :: kind

            words = ""
            if (find_user_ucosub(source // "::UCOSUB") > 0) words = listed(words, "UCOSUB")
            do kind = 1, routine_kinds
                if (find_force_routine(kind, source // "::" // trim(routine_names(kind))) > 0) &
                    & words = listed(words, trim(routine_names(kind)))
            end do
            if (find_force_routine(routine_reqsub, source // "::" // request_routine_name) > 0) &
                & words = listed(words, request_routine_name)
            if (find_force_routine(routine_varsub, source // "::" // variable_routine_name) &
                & > 0) words = listed(words, variable_routine_name)
            if (find_force_routine(routine_motsub, source // "::" // motion_routine_name) > 0) &
                & words = listed(words, motion_routine_name)
            if (find_force_routine(routine_difsub, source // "::" // diff_routine_name) > 0) &
                & words = listed(words, diff_routine_name)
            if (library_named(source)) words = listed(words, "routines named by ROUTINE=")
        end function file_words
    end function defined_text

    !> list with word added after ", " (word alone for an empty list).
    pure function listed(list, word) result(longer)
        character(len=*), intent(in) :: list, word
        character(len=:), allocatable :: longer

        if (len(list) == 0) then
            longer = word
        else
            longer = list // ", " // word
        end if
    end function listed

    !> A user's file that defines none of the routines of fixed name (UCOSUB, SFOSUB, ...)
    !> and none of whose subroutines a statement names (ROUTINE=FILE::NAME): refused, as a
    !> file that serves nothing.
    subroutine refuse_unused(user, error)
        type(user_ucosub_type), intent(in) :: user
        type(error_type), allocatable, intent(out) :: error

        if (.not. user%defines_none .or. library_named(user%source)) return
        call fatal_error(error, user%source // ": defines none of the routines rollcon calls " &
            & // "(UCOSUB, SFOSUB, VFOSUB, GFOSUB, VTOSUB, REQSUB, VARSUB, MOTSUB, DIFSUB: " &
            & // "symbols 'ucosub_', 'sfosub_', ...), and no statement names one of its " &
            & // "subroutines (ROUTINE=FILE::NAME); check the names in its SUBROUTINE " &
            & // "statements and ROUTINE=, and that they are external subroutines, not inside " &
            & // "a module", stat_ucon)
    end subroutine refuse_unused

    !> The child's stderr at path: when the child did not finish (a STOP, a crash), its useful
    !> lines (quote_stderr) end the run's message; otherwise every line is written to this
    !> process's stderr, as the child would have. The file is removed.
    subroutine hand_on_stderr(path, faulted, summary, error)
        character(len=*), intent(in) :: path
        logical, intent(in) :: faulted
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(inout) :: error
        character(len=:), allocatable :: quoted
        character(len=1000) :: line
        integer :: unit, stat

        if (faulted) then
            quoted = quote_stderr(path)
            if (len(quoted) > 0) then
                summary%message = summary%message // quoted
                if (allocated(error)) error%message = error%message // quoted
            end if
        else
            open(newunit=unit, file=path, status="old", action="read", iostat=stat)
            if (stat == 0) then
                do
                    read(unit, '(a)', iostat=stat) line
                    if (stat /= 0) exit
                    write(error_unit, '(a)') trim(line)
                end do
                close(unit)
            end if
        end if
        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete")
    end subroutine hand_on_stderr

    !> An integrator that failed on a run with a user's routines: they are the first suspect
    !> (a wrong partial of a UCOSUB makes a wrong Newton matrix; hidden state, a jump or a NaN
    !> in a force, variable or request routine stalls the steps), so the message names the
    !> command that checks them at many states (the start's check saw one state, and only a
    !> UCOSUB's partials). Not for a routine that crashed, overran or stopped, nor for one
    !> whose failure is the message (stat_ucon, or "SFOSUB of FILE ...": it names the call).
    subroutine point_at_check(job, summary, error)
        type(job_type), intent(in) :: job
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(inout) :: error
        character(len=:), allocatable :: hint

        if (allocated(error)) then
            if (error%stat == stat_ucon) return
        end if
        ! a user routine's failure names its routine and call already (rollcon_user_forces'
        ! labels: "its SFOSUB of FILE", "its VARSUB of FILE", ...)
        if (index(summary%message, "SUB of ") > 0) return
        hint = "; " // check_hint(job)
        summary%message = summary%message // hint
        if (allocated(error)) error%message = error%message // hint
    end subroutine point_at_check

    !> Where the run's user routines are and the command that checks them at many states, for
    !> a failure's message (point_at_check) and the warning of grinding steps (take_frame).
    function check_hint(job) result(hint)
        type(job_type), intent(in) :: job
        character(len=:), allocatable :: hint
        logical :: dataset

        dataset = .false.
        if (allocated(job%input_path)) then
            if (len(job%input_path) > 4) dataset = job%input_path(len(job%input_path) - 3:) &
                & == ".adm"
        end if
        if (dataset) then
            ! `check FILE --model` checks every kind of routine the dataset's statements use
            hint = "the run's user routines are in " // job%user_file // ": rollcon check " &
                & // job%user_file // " --model " // job%input_path // " checks them at many " &
                & // "states (a wrong partial of a UCOSUB, hidden state, a NaN or a jump in a " &
                & // "force, variable or request routine: each stalls the integrators)"
        else
            hint = "the run's UCONs are served by " // job%user_file // ": rollcon check " &
                & // job%user_file // " checks its partials at many states (a wrong one " &
                & // "stalls the integrators)"
        end if
    end function check_hint

    !> The run's summary from what the child sent and how it ended: its own summary when it
    !> finished, else a failure at the last row received, naming the call it ended in.
    subroutine conclude(job, receiver, outcome, summary, error)
        !> The job run (its dataset names the statement of a routine that failed)
        type(job_type), intent(in) :: job
        type(job_receiver_type), intent(inout) :: receiver
        type(isolation_outcome_type), intent(in) :: outcome
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(inout) :: error
        type(error_type), allocatable :: close_error

        call receiver%csv%close(close_error)
        if (.not. allocated(receiver%failure) .and. allocated(close_error)) &
            & call move_alloc(close_error, receiver%failure)
        if (receiver%has_summary) summary = receiver%summary
        if (.not. receiver%has_summary) then
            summary%status = status_failed
            summary%layout = receiver%layout
            summary%t_reached = receiver%t_last
            summary%message = "the run did not complete"
        end if
        summary%rows = receiver%rows
        if (outcome%kind /= outcome_finished .and. .not. allocated(error)) then
            call fatal_error(error, outcome_text(outcome, statement_place(job, outcome%record)) &
                & // "; the run did not complete", stat_ucon)
        end if
        if (allocated(receiver%failure) .and. .not. allocated(error)) &
            & call move_alloc(receiver%failure, error)
        if (allocated(error)) then
            summary%status = status_failed
            summary%message = error%message
        end if
    end subroutine conclude

    !> The statement whose user routine a child's call record is of, as its user wrote it,
    !> "data/x.adm:15: SFORCE/2" (the form of every other error of a user's routine), for a
    !> job of a dataset holding that statement; "" otherwise (a scene's UCONs have no line:
    !> outcome_text then names "UCON/1").
    function statement_place(job, record) result(where)
        type(job_type), intent(in) :: job
        type(call_record_type), intent(in) :: record
        character(len=:), allocatable :: where
        character(len=:), allocatable :: keyword, routine
        integer :: id, line, k

        where = ""
        if (.not. allocated(job%source)) return
        call outcome_statement(record, keyword, id, routine)
        line = 0
        select type (source => job%source)
        type is (dataset_source_type)
            associate (adm => source%adm)
                select case (keyword)
                ! (loops, not the lists' id components: those would be copied into temporaries)
                case ("UCON")
                    if (allocated(adm%ucons)) then
                        do k = 1, size(adm%ucons)
                            if (adm%ucons(k)%id == id) line = adm%ucons(k)%line
                        end do
                    end if
                case ("REQUEST")
                    if (allocated(adm%requests)) line = request_line(adm%requests)
                    if (line == 0 .and. allocated(adm%force_requests)) &
                        & line = request_line(adm%force_requests)
                    if (line == 0 .and. allocated(adm%other_requests)) &
                        & line = request_line(adm%other_requests)
                case ("VARIABLE")
                    if (allocated(adm%variables)) then
                        do k = 1, size(adm%variables)
                            if (adm%variables(k)%id == id) line = adm%variables(k)%line
                        end do
                    end if
                case ("MOTION")
                    if (allocated(adm%motions)) then
                        do k = 1, size(adm%motions)
                            if (adm%motions(k)%id == id) line = adm%motions(k)%line
                        end do
                    end if
                case ("DIFF")
                    if (allocated(adm%diffs)) then
                        do k = 1, size(adm%diffs)
                            if (adm%diffs(k)%id == id) line = adm%diffs(k)%line
                        end do
                    end if
                case default
                    if (allocated(adm%forces)) then
                        do k = 1, size(adm%forces)
                            if (adm%forces(k)%id /= id) cycle
                            if (trim(force_names(adm%forces(k)%kind)) /= keyword) cycle
                            line = adm%forces(k)%line
                            exit
                        end do
                    end if
                end select
                if (line > 0) where = place(adm%file, line) // ": " // keyword // "/" &
                    & // to_text(id)
            end associate
        end select
    contains
        !> The line of the request of this id among requests (0: none).
        pure integer function request_line(requests)
            type(adm_request_type), intent(in) :: requests(:)
            integer :: i

            request_line = 0
            do i = 1, size(requests)
                if (requests(i)%id == id) request_line = requests(i)%line
            end do
        end function request_line
    end function statement_place

    !> In the child: load the routine, guard it, build, make the start consistent, check the
    !> routine there when the job asks (job%start_check) and simulate, sending everything to
    !> the host.
    subroutine run_task(self, record, error)
        class(job_task_type), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(pipe_sink_type) :: sink
        type(run_summary_type) :: summary
        type(part_shape_type), allocatable :: shapes(:)
        type(wire_writer_type) :: wire
        type(error_type), allocatable :: send_error
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report

        call build_apart(self%job, self%library, self%more_libraries, record, &
            & self%options%t0, problem, q0, u0, report, error)
        if (allocated(error)) return
        call send_frame(self%stream_fd, frame_report, report, error)
        if (allocated(error)) return
        call send_frame(self%stream_fd, frame_defined, defined_text(self%job, problem), error)
        if (allocated(error)) return
        call self%job%source%shapes(problem, shapes, error)
        if (allocated(error)) return
        call pack_shapes(wire, shapes)
        call send_frame(self%stream_fd, frame_shapes, wire%packed(), error)
        if (allocated(error)) return
        call send_frame(self%stream_fd, frame_started, "", error)
        if (allocated(error)) return
        sink%fd = self%stream_fd
        call run_analysis(problem, q0, u0, self%options, summary, error, sink=sink)
        wire = wire_writer_type()
        call pack_summary(wire, summary)
        call send_frame(self%stream_fd, frame_summary, wire%packed(), send_error)
        if (.not. allocated(error) .and. allocated(send_error)) call move_alloc(send_error, error)
    end subroutine run_task

    subroutine pipe_open(self, layout, error)
        class(pipe_sink_type), intent(inout) :: self
        type(output_layout_type), intent(in) :: layout
        type(error_type), allocatable, intent(out) :: error
        type(wire_writer_type) :: wire

        call pack_layout(wire, layout)
        call send_frame(self%fd, frame_layout, wire%packed(), error)
    end subroutine pipe_open

    !> A row as its doubles' bytes.
    subroutine pipe_put(self, row, error)
        class(pipe_sink_type), intent(inout) :: self
        real(wp), intent(in) :: row(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=8*size(row)) :: bytes

        bytes = transfer(row, bytes)
        call send_frame(self%fd, frame_row, bytes, error)
    end subroutine pipe_put

    !> The child's run is at time [s] between rows; grinding: its steps grind. Sent as the
    !> time's bytes and "1" or "0".
    subroutine pipe_between_chunks(self, time, grinding)
        class(pipe_sink_type), intent(inout) :: self
        real(wp), intent(in) :: time
        logical, intent(in) :: grinding
        type(error_type), allocatable :: ignored
        character(len=8) :: bytes

        bytes = transfer(time, bytes)
        ! a pipe that fails here fails again at the next row, which reports it
        call send_frame(self%fd, frame_time, bytes // merge("1", "0", grinding), ignored)
    end subroutine pipe_between_chunks

    !> Bytes from the child: every whole frame in them taken.
    subroutine receive(self, bytes)
        class(job_receiver_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        character(len=:), allocatable :: payload
        integer :: kind
        logical :: found

        call self%frames%add(bytes)
        do
            call self%frames%next(kind, payload, found)
            if (.not. found) exit
            call self%take_frame(kind, payload)
        end do
    end subroutine receive

    !> One frame from the child.
    subroutine take_frame(self, kind, payload)
        class(job_receiver_type), intent(inout) :: self
        integer, intent(in) :: kind
        character(len=*), intent(in) :: payload
        type(wire_reader_type) :: wire
        type(error_type), allocatable :: error
        real(wp), allocatable :: row(:)
        real(wp) :: time

        wire%bytes = payload
        select case (kind)
        case (frame_report)
            if (.not. self%quiet .and. len(payload) > 0) write(output_unit, '(a)') payload
        case (frame_shapes)
            call unpack_shapes(wire, self%shapes)
        case (frame_started)
            self%started = .true.
        case (frame_layout)
            call unpack_layout(wire, self%layout)
            self%has_layout = .not. wire%failed
            if (associated(self%history)) self%history%layout = self%layout
            if (allocated(self%csv_path)) call self%csv%open(self%csv_path, &
                & self%layout%header(), error)
        case (frame_row)
            if (.not. self%has_layout .or. len(payload) /= 8*self%layout%columns()) then
                wire%failed = .true.
            else
                allocate(row(self%layout%columns()))
                row = transfer(payload, row)
                self%rows = self%rows + 1
                self%t_last = row(1)
                if (associated(self%history)) call self%history%add(row)
                if (self%csv%opened) call self%csv%write_row(row, error)
                call self%progress%report(row(1))
            end if
        case (frame_time)
            if (len(payload) /= 9) then
                wire%failed = .true.
            else
                time = transfer(payload(1:8), time)
                call self%progress%report(time)
                if (payload(9:9) == "1") write(error_unit, '(a)') "rollcon: warning: at t = " &
                    & // to_text(time) // " s the steps grind (their mean step is below a " &
                    & // "ten-thousandth of the way to the next output time and a quarter of " &
                    & // "them are rejected: far finer than the tolerance needs); " &
                    & // self%check_hint
            end if
        case (frame_summary)
            call unpack_summary(wire, self%summary)
            self%has_summary = .not. wire%failed
        case (frame_defined)
            self%defined = payload
        case default
            wire%failed = .true.
        end select
        if (wire%failed .and. .not. allocated(error)) call fatal_error(error, "the child " &
            & // "process sent a message of kind " // to_text(kind) // " that does not read", &
            & stat_ucon)
        if (allocated(error) .and. .not. allocated(self%failure)) &
            & call move_alloc(error, self%failure)
    end subroutine take_frame

end module rollcon_isolated_run
