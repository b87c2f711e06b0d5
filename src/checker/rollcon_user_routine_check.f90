! SPDX-License-Identifier: MIT
!> `rollcon check FILE --model MODEL.adm` for a dataset whose statements are served by the
!> file's routines (docs/checker.md, "Checking a force, variable or request routine"): every
!> kind rollcon serves but UCOSUB (which rollcon_ucosub_audit checks), each a row of one table
!> (checked_kinds): SFOSUB, VFOSUB, GFOSUB, VTOSUB (force statements), VARSUB (VARIABLE) and
!> REQSUB (REQUEST).
!>
!> - implicit typing (a Fortran file; C has none): the file compiled once more with
!>   gfortran's -Wconversion, each warning
!>   of a conversion that may change a value (a DOUBLE PRECISION value into a variable typed
!>   INTEGER or REAL by its first letter) a finding naming the routine and the line;
!> - in a child process (the routines' own, with the time limit per call and the guards of a
!>   run, rollcon_force_routine_guard), the model built as a run builds it (the
!>   initialisation calls included) and every statement a user's routine serves called at its
!>   start and at random states about it: the same inputs twice must give the same outputs
!>   (no hidden state), the outputs must be finite, and continuous over the states probed (a
!>   jump found by halving the way from the start to each state: the change across a step
!>   that does not shrink as the step does), and the SYSFNC and SYSARY calls must name only
!>   what the initialisation call named. Each finding names the statement (file and line),
!>   the routine, the call and the state. A force routine that reads SYSFNC's force measures
!>   (a JOINT's reaction, another force) is called with the equations solved at each probed
!>   state (its multipliers and forces there are what it reads).
module rollcon_user_routine_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_ucon
    use rollcon_text, only : to_text, shell_quote, upper_case, number_list
    use rollcon_adm_model, only : adm_model_type, request_user, force_sforce, force_vforce, &
        & force_gforce, force_vtorque
    use rollcon_adm_units, only : unit_names
    use rollcon_adm_reader, only : read_adm
    use rollcon_job, only : job_type, user_file_type
    use rollcon_load, only : load_job, add_user_file
    use rollcon_isolated_run, only : compile_user_files, build_apart, statement_place
    use rollcon_problem, only : problem_type
    use rollcon_force, only : profile_statement
    use rollcon_system_routine_contract, only : request_results, request_columns, &
        & motion_orders
    use rollcon_user_build, only : user_build_options_type, source_kind, kind_c
    use rollcon_user_forces, only : evaluate_user_forces, &
        & take_user_force_error, system_notes, clear_system_notes, force_routine_label, &
        & call_user_request, evaluate_user_variable, user_variable_list, user_variable_type, &
        & user_motion_list, user_motion_type, call_user_motion, call_diff_routine, &
        & evaluate_user_variables, get_force_routine
    use rollcon_force_routine_contract, only : force_routine_interface, routine_sfosub, &
        & routine_vfosub, routine_vtosub
    use rollcon_user_variable_values, only : user_variable_value
    use rollcon_request_answers, only : request_answer_watch_type, answer_user
    use rollcon_child_process, only : isolated_task_type, stream_receiver_type, &
        & call_record_type, isolation_outcome_type, run_in_child, outcome_finished
    use rollcon_frames, only : send_frame, frame_buffer_type
    use rollcon_isolation_text, only : outcome_text
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: dataset_has_user_routines, check_user_routines, implicit_typing_findings
    public :: routine_units_lines, check_tally_type

    !> States probed about the start, besides the start itself
    integer, parameter :: probed_states = 20
    !> Halvings of the way from the start to a state in the search for a jump: the last step
    !> is 2**-40 (1e-12) of the way, where a force with a stiffness of 1e8 (in the dataset's
    !> units) changes by 1e-5 over a way of 0.1
    integer, parameter :: halvings = 40
    !> A jump is a change across the last step beyond this fraction of the outputs' scale
    !> (1 + their largest magnitude) that is still more than half the change across the step
    !> ten halvings before: a continuous output's change falls some 1000-fold over ten
    !> halvings, a jump's does not fall
    real(wp), parameter :: jump_fraction = 1.0e-3_wp
    integer, parameter :: jump_lag = 10

    abstract interface
        !> True when the dataset has a statement of the kind served by a user's routine.
        logical function in_dataset_interface(adm)
            import :: adm_model_type
            type(adm_model_type), intent(in) :: adm
        end function in_dataset_interface

        !> How many statements of the kind the built problem holds (served by a user's
        !> routine or not).
        integer function count_interface(problem)
            import :: problem_type
            type(problem_type), intent(in), target :: problem
        end function count_interface

        !> The k-th statement and its routine for findings, "x.adm:9: SFORCE/2, its SFOSUB
        !> of f.f"; "" when no user's routine serves it.
        function label_interface(problem, k) result(label)
            import :: problem_type
            type(problem_type), intent(in), target :: problem
            integer, intent(in) :: k
            character(len=:), allocatable :: label
        end function label_interface

        !> The outputs of the k-th statement's routine called at (time [s], q, u [SI]); error
        !> for a call that failed (an ERRMES, a utility's refusal, outputs not finite).
        subroutine values_interface(problem, k, time, q, u, values, error)
            import :: problem_type, wp, error_type
            type(problem_type), intent(inout), target :: problem
            integer, intent(in) :: k
            real(wp), intent(in) :: time, q(:), u(:)
            real(wp), allocatable, intent(out) :: values(:)
            type(error_type), allocatable, intent(out) :: error
        end subroutine values_interface
    end interface

    !> A kind of user routine the check probes: a row of checked_kinds
    type :: checked_kind_type
        !> What its outputs are called in ADAMS's calling sequence: RESULT, VALUE
        character(len=6) :: output = "RESULT"
        procedure(in_dataset_interface), pointer, nopass :: in_dataset => null()
        procedure(count_interface), pointer, nopass :: count => null()
        procedure(label_interface), pointer, nopass :: label => null()
        procedure(values_interface), pointer, nopass :: values => null()
    end type checked_kind_type

    !> The child's work
    type, extends(isolated_task_type) :: routine_check_task_type
        type(job_type) :: job
        !> The libraries of the job's files: its first, and its more files in order
        character(len=:), allocatable :: library
        type(user_file_type), allocatable :: more_libraries(:)
        integer :: seed = 1
    contains
        procedure :: run => run_routine_check
    end type routine_check_task_type

    !> What a check did: the statements it probed, the states each was probed at, the calls
    !> of their routines, and the outputs' values compared (each value of a call with its
    !> repeat's, for hidden state)
    type :: check_tally_type
        integer :: statements = 0, states = 0, calls = 0, compared = 0
    end type check_tally_type

    !> Frame kinds the child sends: a finding's line, the tally (four whole numbers)
    integer, parameter :: frame_finding = 1, frame_tally = 2

    !> In this process: the findings the child sends, a line each, and its tally
    type, extends(stream_receiver_type) :: findings_receiver_type
        type(frame_buffer_type) :: frames
        character(len=:), allocatable :: text
        integer :: count = 0
        type(check_tally_type) :: tally
    contains
        procedure :: receive
    end type findings_receiver_type

contains

    !> The kinds of user routine the check probes, a row each: what the outputs are called,
    !> and how the dataset's statements of the kind are found, named and evaluated.
    function checked_kinds() result(kinds)
        type(checked_kind_type), allocatable :: kinds(:)

        kinds = [checked_kind_type("RESULT", user_forces_in, force_count, force_label, &
            & force_values), &
            & checked_kind_type("VALUE", user_variables_in, variable_count, variable_label, &
            & variable_values), &
            & checked_kind_type("RESULT", user_requests_in, request_count, request_label, &
            & request_values), &
            & checked_kind_type("VALUE", user_motions_in, motion_count, &
            & motion_label, motion_values), &
            & checked_kind_type("VALUE", user_diffs_in, diff_count, diff_label, diff_values)]
    end function checked_kinds

    !> True when the dataset at path has a statement served by a user's routine of a kind
    !> this check probes (checked_kinds).
    function dataset_has_user_routines(path) result(has)
        character(len=*), intent(in) :: path
        logical :: has
        type(adm_model_type) :: adm
        type(error_type), allocatable :: error
        type(checked_kind_type), allocatable :: kinds(:)
        integer :: k

        has = .false.
        call read_adm(path, adm, error)
        if (allocated(error)) return
        kinds = checked_kinds()
        do k = 1, size(kinds)
            has = has .or. kinds(k)%in_dataset(adm)
        end do
    end function dataset_has_user_routines

    !> Check the user routines of file (and of more_files, for a model whose statements name
    !> routines of several files: ROUTINE=FILE::NAME) on the dataset at model: findings (a
    !> line each, "" for none) and their number. error is for what prevents the check (a file
    !> does not build, the model does not read).
    subroutine check_user_routines(file, model, options, call_timeout, seed, findings, count, &
            & error, more_files, tally)
        character(len=*), intent(in) :: file, model
        type(user_build_options_type), intent(in) :: options
        !> Longest one call may take [s]
        real(wp), intent(in) :: call_timeout
        !> Seed of the probed states
        integer, intent(in) :: seed
        character(len=:), allocatable, intent(out) :: findings
        integer, intent(out) :: count
        type(error_type), allocatable, intent(out) :: error
        !> The other files of the model's routines (as `rollcon run --ucosub` takes them)
        type(user_file_type), intent(in), optional :: more_files(:)
        !> What the check did (the child's tally; zero when it ended early)
        type(check_tally_type), intent(out), optional :: tally
        type(routine_check_task_type) :: task
        type(findings_receiver_type) :: receiver
        type(isolation_outcome_type) :: outcome
        type(user_file_type), allocatable :: files(:)
        character(len=:), allocatable :: typing
        integer :: typing_count, k

        findings = ""
        count = 0
        call load_job(model, task%job, error, ucosub=file)
        if (allocated(error)) return
        files = [user_file_type(file)]
        if (present(more_files)) then
            do k = 1, size(more_files)
                call add_user_file(task%job, more_files(k)%path, error)
                if (allocated(error)) return
            end do
            files = [files, more_files]
        end if
        task%job%build_options = options
        task%job%quiet = .true.
        call compile_user_files(task%job, task%library, task%more_libraries, error)
        if (allocated(error)) return
        task%seed = seed
        receiver%text = ""
        call run_in_child(task, real(call_timeout, wp), outcome, error, receiver=receiver)
        findings = receiver%text
        count = receiver%count
        if (present(tally)) tally = receiver%tally
        if (outcome%kind /= outcome_finished) then
            findings = findings // "[crash] " // outcome_text(outcome, &
                & statement_place(task%job, outcome%record)) // new_line("a")
            count = count + 1
            if (allocated(error)) deallocate(error)
        else if (allocated(error)) then
            if (error%stat /= stat_ucon) return
            ! a routine's failure in the initialisation call is a finding too
            findings = findings // "[error] " // error%message // new_line("a")
            count = count + 1
            deallocate(error)
        end if
        do k = 1, size(files)
            ! C has no implicit typing: its declarations are the programmer's own
            if (source_kind(files(k)%path) == kind_c) cycle
            call implicit_typing_findings(files(k)%path, options%compiler, typing, &
                & typing_count, error)
            if (allocated(error)) return
            findings = findings // typing
            count = count + typing_count
        end do
    end subroutine check_user_routines

    !> What "units as documented" means for each statement of the dataset at model served by a
    !> user's routine, a line each ("units: SFORCE/2 (line 13), its SFOSUB: ..."): every answer
    !> of SYSFNC and SYSARY arrives in the dataset's UNITS (force, mass, length, time by their
    !> names; angles in radians, rates per its time unit), and each output is read in them,
    !> as ADAMS reads it (a force in the force unit, a torque in force times length, a MOTSUB's
    !> rotation in radians). "" when none is; error when the dataset does not read.
    subroutine routine_units_lines(model, lines, error)
        character(len=*), intent(in) :: model
        character(len=:), allocatable, intent(out) :: lines
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        character(len=:), allocatable :: force, mass, length, time, answers, torque
        character(len=*), parameter :: nl = new_line("a")
        integer :: k

        lines = ""
        call read_adm(model, adm, error)
        if (allocated(error)) return
        call unit_names(adm%units, force, mass, length, time)
        answers = ": SYSFNC and SYSARY answer in " // force // ", " // mass // ", " // length &
            & // ", " // time // " (the dataset's UNITS), angles in radians, velocities in " &
            & // length // "/" // time // ", angular velocities in radians/" // time // "; "
        torque = force // "*" // length
        if (allocated(adm%forces)) then
            do k = 1, size(adm%forces)
                associate (f => adm%forces(k))
                    if (.not. f%user) cycle
                    select case (f%kind)
                    case (force_sforce)
                        if (f%translation) then
                            call add("SFORCE", f%id, f%line, "SFOSUB", "RESULT is read as the " &
                                & // "force along the line from J to I, in " // force)
                        else
                            call add("SFORCE", f%id, f%line, "SFOSUB", "RESULT is read as the " &
                                & // "torque about J's z axis, in " // torque)
                        end if
                    case (force_vforce)
                        call add("VFORCE", f%id, f%line, "VFOSUB", "RESULT(1:3) is read as " &
                            & // "the force in RM's axes, in " // force)
                    case (force_vtorque)
                        call add("VTORQUE", f%id, f%line, "VTOSUB", "RESULT(1:3) is read as " &
                            & // "the torque in RM's axes, in " // torque)
                    case (force_gforce)
                        call add("GFORCE", f%id, f%line, "GFOSUB", "RESULT(1:3) is read as " &
                            & // "the force in RM's axes, in " // force // ", RESULT(4:6) as " &
                            & // "the torque, in " // torque)
                    end select
                end associate
            end do
        end if
        if (allocated(adm%variables)) then
            do k = 1, size(adm%variables)
                if (.not. adm%variables(k)%user) cycle
                call add("VARIABLE", adm%variables(k)%id, adm%variables(k)%line, "VARSUB", &
                    & "VALUE is read in the dataset's units of what it stands for (as the " &
                    & // "FUNCTION it replaces)")
            end do
        end if
        if (allocated(adm%other_requests)) then
            do k = 1, size(adm%other_requests)
                if (adm%other_requests(k)%kind /= request_user) cycle
                call add("REQUEST", adm%other_requests(k)%id, adm%other_requests(k)%line, &
                    & "REQSUB", "RESULT(2:4), RESULT(6:8) are written as they are, in the " &
                    & // "dataset's units of the measures they report")
            end do
        end if
        if (allocated(adm%motions)) then
            do k = 1, size(adm%motions)
                if (.not. adm%motions(k)%user) cycle
                call add("MOTION", adm%motions(k)%id, adm%motions(k)%line, "MOTSUB", &
                    & "VALUE is read as the joint's displacement in " // length // " (a " &
                    & // "translation) or radians (a rotation), its derivatives per " // time)
            end do
        end if
        if (allocated(adm%diffs)) then
            do k = 1, size(adm%diffs)
                if (.not. adm%diffs(k)%user) cycle
                call add("DIFF", adm%diffs(k)%id, adm%diffs(k)%line, "DIFSUB", "VALUE is " &
                    & // "read as d DIF/dt in the equation's own units per " // time)
            end do
        end if
    contains
        subroutine add(statement, id, line, routine, outputs)
            character(len=*), intent(in) :: statement, routine, outputs
            integer, intent(in) :: id, line

            lines = lines // "units: " // statement // "/" // to_text(id) // " (line " &
                & // to_text(line) // "), its " // routine // answers // outputs // nl
        end subroutine add
    end subroutine routine_units_lines

    !> The file compiled again with -Wconversion (-fsyntax-only): each warning of a conversion
    !> that may change a value, "[typing] FILE:LINE (in SUBROUTINE NAME): what gfortran says:
    !> the source line", a line each. Under IMPLICIT typing a variable named from I to N is
    !> INTEGER and any other REAL, so `KR = PAR(3)` truncates the stiffness and `C1 = PAR(4)`
    !> keeps seven digits of the damping.
    subroutine implicit_typing_findings(file, compiler, findings, count, error)
        character(len=*), intent(in) :: file, compiler
        character(len=:), allocatable, intent(out) :: findings
        integer, intent(out) :: count
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: log, command, flags
        character(len=1000) :: line
        character(len=:), allocatable :: source_line, routine
        integer :: unit, stat, colon, number, at

        findings = ""
        count = 0
        log = "/tmp/rollcon-typing-" // to_text(getpid_value()) // ".log"
        flags = "-fsyntax-only -Wconversion"
        if (index(file, ".f90") == 0) flags = flags // " -std=legacy"
        command = trim(compiler) // " " // flags // " " // shell_quote(file) // " -J /tmp > " &
            & // shell_quote(log) // " 2>&1"
        call execute_command_line(command, exitstat=stat)
        open(newunit=unit, file=log, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        number = 0
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! "FILE:LINE:COLUMN:" then, lines later, "Warning: ... conversion from ..."
            if (index(line, file // ":") == 1) then
                colon = index(line(len(file) + 2:), ":")
                if (colon > 1) read(line(len(file) + 2:len(file) + colon), *, iostat=stat) number
                cycle
            end if
            at = index(line, "Warning:")
            if (at == 0 .or. index(line, "onversion") == 0) cycle
            call source_context(file, number, source_line, routine)
            findings = findings // "[typing] " // file // ":" // to_text(number) // " (in " &
                & // routine // "): " // trim(line(at + 9:)) // ": " // source_line &
                & // " (an IMPLICIT type? declare it DOUBLE PRECISION)" // new_line("a")
            count = count + 1
        end do
        close(unit, status="delete")
    end subroutine implicit_typing_findings

    !> The source line number of file, and the SUBROUTINE it is in ("?" when not found).
    subroutine source_context(file, number, text, routine)
        character(len=*), intent(in) :: file
        integer, intent(in) :: number
        character(len=:), allocatable, intent(out) :: text, routine
        character(len=400) :: line
        integer :: unit, stat, k, at

        text = "?"
        routine = "?"
        open(newunit=unit, file=file, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        do k = 1, number
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            at = index(upper_case(line), "SUBROUTINE ")
            if (at > 0 .and. line(1:1) /= "C" .and. line(1:1) /= "c" .and. line(1:1) /= "!") &
                & then
                routine = trim(adjustl(line(at + 11:)))
                if (index(routine, "(") > 0) routine = routine(:index(routine, "(") - 1)
                routine = "SUBROUTINE " // trim(routine)
            end if
            if (k == number) text = "'" // trim(adjustl(line)) // "'"
        end do
        close(unit)
    end subroutine source_context

    !> This process's id.
    function getpid_value() result(pid)
        use rollcon_dlopen, only : process_id
        integer :: pid

        pid = process_id()
    end function getpid_value

    !> In the child: load the routines, build the model (the initialisation calls), then probe
    !> every statement of every kind (checked_kinds) served by a user's routine at the same
    !> states: the start, and probed_states random states about it (positions within 0.05 m or
    !> rad, rates within 0.5 m/s or rad/s, the time within the run's span).
    subroutine run_routine_check(self, record, error)
        class(routine_check_task_type), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(checked_kind_type), allocatable :: kinds(:)
        real(wp), allocatable :: q0(:), u0(:), q(:, :), u(:, :)
        real(wp) :: times(0:probed_states), span
        character(len=:), allocatable :: report, label
        integer :: s, i, n, kind
        integer, allocatable :: seed(:)
        type(check_tally_type) :: tally
        type(error_type), allocatable :: ignored
        ! a statement's first hidden state's finding (probe), and the states that showed it
        character(len=:), allocatable :: hidden
        integer :: hidden_states

        call clear_system_notes()
        ! the job's routines loaded, guarded and the model built as a run apart does it (no
        ! start check: the UCONs' partials are checked on their own)
        self%job%start_check => null()
        call build_apart(self%job, self%library, self%more_libraries, record, 0.0_wp, &
            & problem, q0, u0, report, error)
        if (allocated(error)) return
        call random_seed(size=n)
        allocate(seed(n))
        seed = self%seed + 7919*[(i, i = 1, n)]
        call random_seed(put=seed)
        allocate(q(size(q0), 0:probed_states), u(size(u0), 0:probed_states))
        call random_number(q)
        call random_number(u)
        call random_number(times)
        span = problem%settings%end_time
        if (.not. span > 0.0_wp) span = 1.0_wp
        do s = 0, probed_states
            q(:, s) = q0 + 0.1_wp*(q(:, s) - 0.5_wp)
            u(:, s) = u0 + (u(:, s) - 0.5_wp)
        end do
        times = span*times
        q(:, 0) = q0
        u(:, 0) = u0
        times(0) = 0.0_wp
        kinds = checked_kinds()
        do kind = 1, size(kinds)
            do i = 1, kinds(kind)%count(problem)
                label = kinds(kind)%label(problem, i)
                if (len(label) == 0) cycle
                call probe(kinds(kind), i, label)
            end do
        end do
        tally%states = probed_states + 1
        call send_frame(self%stream_fd, frame_tally, number_list([tally%statements, &
            & tally%states, tally%calls, tally%compared]), ignored)
    contains
        !> The checks of one statement at every state. Hidden state is one finding, the first
        !> state's, with the number of states that showed it (as a UCOSUB's findings are
        !> grouped); every other finding is its state's.
        subroutine probe(row, k, label)
            type(checked_kind_type), intent(in) :: row
            integer, intent(in) :: k
            character(len=*), intent(in) :: label
            real(wp), allocatable :: start(:), first(:), second(:)
            character(len=:), allocatable :: where, reported
            type(error_type), allocatable :: failure
            integer :: s

            reported = ""
            hidden = ""
            hidden_states = 0
            tally%statements = tally%statements + 1
            do s = 0, probed_states
                where = label // " at state " // to_text(s) // trim(merge(" (the start)", &
                    & "            ", s == 0)) // ", in the call with IFLAG = .FALSE., t = " &
                    & // to_text(times(s)) // " s"
                call clear_system_notes()
                tally%calls = tally%calls + 1
                call row%values(problem, k, times(s), q(:, s), u(:, s), first, failure)
                if (.not. allocated(failure)) then
                    tally%calls = tally%calls + 1
                    call row%values(problem, k, times(s), q(:, s), u(:, s), second, failure)
                end if
                if (allocated(failure)) then
                    call hidden_finding(s)
                    ! a routine that fails is probed no further: the first failure says it
                    call finding(trim(merge("[finite]", "[error] ", index(failure%message, &
                        & "must be finite") > 0)) // " " // where // ": " &
                        & // failure_text(failure%message, label))
                    return
                end if
                tally%compared = tally%compared + size(first)
                if (s == 0) start = first
                if (any(first /= second)) then
                    hidden_states = hidden_states + 1
                    if (hidden_states == 1) hidden = "[hidden state] " // where &
                        & // ": the same inputs gave " // trim(row%output) // " (" &
                        & // number_list(first) // ") and then (" // number_list(second) // ")"
                else if (s > 0) then
                    call continuity(row, k, s, start, first, where)
                end if
                call declaration_notes(where, reported)
            end do
            call hidden_finding(probed_states + 1)
        end subroutine probe

        !> probe's finding of hidden state: the first state's, and how many of the states
        !> compared (all, or those before a failure) showed it.
        subroutine hidden_finding(compared)
            integer, intent(in) :: compared

            if (hidden_states == 0) return
            call finding(hidden // "; so in " // to_text(hidden_states) // " of the " &
                & // to_text(compared) // " states probed")
            hidden_states = 0
        end subroutine hidden_finding

        !> A jump of the k-th statement's outputs on the way from the start (outputs start)
        !> to state s (outputs there): the way halved, the half with the larger change kept,
        !> halvings times (module header).
        subroutine continuity(row, k, s, start, there, where)
            type(checked_kind_type), intent(in) :: row
            integer, intent(in) :: k, s
            real(wp), intent(in) :: start(:), there(:)
            character(len=*), intent(in) :: where
            real(wp), allocatable :: low(:), high(:), middle(:)
            real(wp) :: changes(0:halvings), a, b, c, scale
            type(error_type), allocatable :: failure
            integer :: h

            low = start
            high = there
            a = 0.0_wp
            b = 1.0_wp
            changes(0) = maxval(abs(high - low))
            scale = 1.0_wp + max(maxval(abs(start)), maxval(abs(there)))
            do h = 1, halvings
                c = 0.5_wp*(a + b)
                tally%calls = tally%calls + 1
                call row%values(problem, k, times(0) + c*(times(s) - times(0)), q(:, 0) &
                    & + c*(q(:, s) - q(:, 0)), u(:, 0) + c*(u(:, s) - u(:, 0)), middle, failure)
                ! a failure on the way is found where it is when the state probed is near it
                if (allocated(failure)) return
                if (maxval(abs(middle - low)) >= maxval(abs(high - middle))) then
                    b = c
                    high = middle
                else
                    a = c
                    low = middle
                end if
                changes(h) = maxval(abs(high - low))
            end do
            if (changes(halvings) <= jump_fraction*scale) return
            if (changes(halvings) <= 0.5_wp*changes(halvings - jump_lag)) return
            call finding("[jump] " // where // ": on the way from the start to this state, " &
                & // trim(row%output) // " jumps from (" // number_list(low) // ") to (" &
                & // number_list(high) // ") at " // to_text(a) // " of the way, across a step " &
                & // "of 1e-12 of it (a discontinuity the integrator cannot step over)")
        end subroutine continuity

        !> What the utilities noted in the calls at a state (a marker or a rate its
        !> initialisation call did not declare), each note once a statement.
        subroutine declaration_notes(where, reported)
            character(len=*), intent(in) :: where
            character(len=:), allocatable, intent(inout) :: reported
            character(len=:), allocatable :: notes
            integer :: end_of_line

            notes = system_notes()
            do while (len(notes) > 0)
                end_of_line = index(notes, new_line("a"))
                if (end_of_line == 0) end_of_line = len(notes) + 1
                if (index(reported, notes(:end_of_line - 1) // new_line("a")) == 0) then
                    call finding("[declaration] " // where // ": " // notes(:end_of_line - 1))
                    reported = reported // notes(:end_of_line - 1) // new_line("a")
                end if
                notes = notes(min(end_of_line + 1, len(notes) + 1):)
            end do
        end subroutine declaration_notes

        subroutine finding(text)
            character(len=*), intent(in) :: text
            type(error_type), allocatable :: ignored

            call send_frame(self%stream_fd, frame_finding, text, ignored)
        end subroutine finding
    end subroutine run_routine_check

    !> A force statement with FUNCTION=USER(...) in the dataset (SFORCE, VFORCE, GFORCE,
    !> VTORQUE).
    logical function user_forces_in(adm) result(has)
        type(adm_model_type), intent(in) :: adm

        has = .false.
        if (allocated(adm%forces)) has = any(adm%forces%user)
    end function user_forces_in

    !> The model's forces (statements and built-in elements alike).
    integer function force_count(problem) result(n)
        type(problem_type), intent(in), target :: problem

        n = size(problem%model%forces)
    end function force_count

    !> "x.adm:9: SFORCE/2, its SFOSUB of f.f"; "" for a force no user's routine serves.
    function force_label(problem, k) result(label)
        type(problem_type), intent(in), target :: problem
        integer, intent(in) :: k
        character(len=:), allocatable :: label

        label = ""
        associate (force => problem%model%forces(k))
            if (force%profile /= profile_statement) return
            if (force%statement%routine == 0) return
            label = force%name // ", its " // force_routine_label(force%statement%routine)
        end associate
    end function force_label

    !> The force's values as its routine gives them (SI): RESULT's entries of its kind, an
    !> SFOSUB's 1, a VFOSUB's or VTOSUB's 3, a GFOSUB's 6 (force then torque). A routine that
    !> reads force measures (a JOINT's reaction, another force) is called with the model's
    !> equations solved at the probed state first (rollcon_equations' accelerations: the
    !> multipliers there, and every force at that state, are what its SYSFNC calls read).
    subroutine force_values(problem, k, time, q, u, values, error)
        type(problem_type), intent(inout), target :: problem
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable, intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:), lambda(:)
        procedure(force_routine_interface), pointer :: routine
        integer :: kind

        ! the VARSUBs at the probed state: SYSFNC('VARVAL') reads their values there
        call evaluate_user_variables(time, q, u)
        if (problem%model%forces(k)%statement%declared_forces) then
            allocate(a(problem%eq%n), lambda(problem%eq%nc))
            ! the loop's solve from the same start at every probe: the same inputs, the same
            ! multipliers to the last bit
            if (allocated(problem%eq%work%loop_a)) problem%eq%work%loop_a = 0.0_wp
            if (allocated(problem%eq%work%loop_lambda)) problem%eq%work%loop_lambda = 0.0_wp
            call problem%eq%accelerations(time, q, u, 0.0_wp, a, lambda, error)
            if (allocated(error)) then
                error%message = "the equations at the probed state, whose constraint forces " &
                    & // "its SYSFNC force measures read: " // error%message
                return
            end if
        end if
        call evaluate_user_forces(problem%model%forces(k:k), time, q, u)
        values = problem%model%forces(k)%statement%user_values
        call take_user_force_error(error)
        ! only the entries of RESULT the routine's kind defines, in its order (the statement
        ! holds force then torque: an SFOSUB's one value first, a VTOSUB's torque last)
        call get_force_routine(problem%model%forces(k)%statement%routine, routine, kind)
        select case (kind)
        case (routine_sfosub)
            values = values(1:1)
        case (routine_vfosub)
            values = values(1:3)
        case (routine_vtosub)
            values = values(4:6)
        end select
    end subroutine force_values

    !> A VARIABLE with FUNCTION=USER(...) in the dataset.
    logical function user_variables_in(adm) result(has)
        type(adm_model_type), intent(in) :: adm

        has = .false.
        if (allocated(adm%variables)) has = any(adm%variables%user)
    end function user_variables_in

    !> The model's VARIABLEs served by a VARSUB.
    integer function variable_count(problem) result(n)
        type(problem_type), intent(in), target :: problem

        n = size(user_variable_list())
    end function variable_count

    !> "x.adm:10: VARIABLE/3, its VARSUB of f.f".
    function variable_label(problem, k) result(label)
        type(problem_type), intent(in), target :: problem
        integer, intent(in) :: k
        character(len=:), allocatable :: label
        type(user_variable_type), allocatable :: list(:)

        list = user_variable_list()
        label = list(k)%name // ", its " // force_routine_label(list(k)%routine)
    end function variable_label

    !> The VARIABLE's VALUE as its VARSUB gives it (the dataset's units).
    subroutine variable_values(problem, k, time, q, u, values, error)
        type(problem_type), intent(inout), target :: problem
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable, intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        type(user_variable_type), allocatable :: list(:)

        call evaluate_user_variable(k, time, q, u)
        list = user_variable_list()
        values = [user_variable_value(list(k)%id)]
        call take_user_force_error(error)
    end subroutine variable_values

    !> A MOTION with FUNCTION=USER(...) in the dataset.
    logical function user_motions_in(adm) result(has)
        type(adm_model_type), intent(in) :: adm

        has = .false.
        if (allocated(adm%motions)) has = any(adm%motions%user)
    end function user_motions_in

    !> The model's MOTIONs served by a MOTSUB.
    integer function motion_count(problem) result(n)
        type(problem_type), intent(in), target :: problem

        n = size(user_motion_list())
    end function motion_count

    !> "x.adm:7: MOTION/3, its MOTSUB of f.f".
    function motion_label(problem, k) result(label)
        type(problem_type), intent(in), target :: problem
        integer, intent(in) :: k
        character(len=:), allocatable :: label
        type(user_motion_type), allocatable :: list(:)

        list = user_motion_list()
        label = list(k)%name // ", its " // force_routine_label(list(k)%routine)
    end function motion_label

    !> The MOTION's VALUE with IORD = 0, 1 and 2 as its MOTSUB gives them (the dataset's
    !> units), or those ADAMS asks of it (a VELOCITY's 0 and 1, an ACCELERATION's 0); a
    !> function of time alone, so the state is not read.
    subroutine motion_values(problem, k, time, q, u, values, error)
        type(problem_type), intent(inout), target :: problem
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable, intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        type(user_motion_type), allocatable :: list(:)
        real(wp) :: orders(0:motion_orders)
        integer :: iord

        list = user_motion_list()
        call call_user_motion(list(k)%id, time, q, u, [(iord, iord = 0, list(k)%highest)], &
            & orders, error)
        values = orders(0:list(k)%highest)
    end subroutine motion_values

    !> A DIFF with FUNCTION=USER(...) in the dataset.
    logical function user_diffs_in(adm) result(has)
        type(adm_model_type), intent(in) :: adm

        has = .false.
        if (allocated(adm%diffs)) has = any(adm%diffs%user)
    end function user_diffs_in

    !> The model's DIFFs (those a DIFSUB serves are labelled).
    integer function diff_count(problem) result(n)
        type(problem_type), intent(in), target :: problem

        n = problem%model%diffs%count()
    end function diff_count

    !> "DIFF/3 (line 12), its DIFSUB of f.f"; "" for a DIFF of an expression.
    function diff_label(problem, k) result(label)
        type(problem_type), intent(in), target :: problem
        integer, intent(in) :: k
        character(len=:), allocatable :: label

        label = ""
        associate (diff => problem%model%diffs%diffs(k))
            if (diff%routine /= 0) label = diff%name // ", its " &
                & // force_routine_label(diff%routine)
        end associate
    end function diff_label

    !> The DIFF's VALUE as its DIFSUB gives it (a rate per the dataset's time unit, or an
    !> IMPLICIT DIFF's residual), the DIFFs' own state held at the start's (DIF at the ICs).
    subroutine diff_values(problem, k, time, q, u, values, error)
        type(problem_type), intent(inout), target :: problem
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable, intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value
        logical :: failed

        ! the VARSUBs at the probed state: SYSFNC('VARVAL') reads their values there
        call evaluate_user_variables(time, q, u)
        associate (set => problem%model%diffs, diff => problem%model%diffs%diffs(k))
            call call_diff_routine(diff%routine, diff%id, diff%name, diff%par, set%time_unit, &
                & time, q, u, set%ids, set%x, set%w, .false., diff%declaration, value, failed)
        end associate
        values = [value]
        call take_user_force_error(error)
    end subroutine diff_values

    !> A REQUEST with FUNCTION=USER(...) in the dataset.
    logical function user_requests_in(adm) result(has)
        type(adm_model_type), intent(in) :: adm

        has = .false.
        if (allocated(adm%other_requests)) has = any(adm%other_requests%kind == request_user)
    end function user_requests_in

    !> The requests the problem's request watch answers (none without one).
    integer function request_count(problem) result(n)
        type(problem_type), intent(in), target :: problem
        type(request_answer_watch_type), pointer :: watch

        n = 0
        watch => request_watch(problem)
        if (associated(watch)) n = size(watch%own_requests)
    end function request_count

    !> "x.adm:12: REQUEST/7, its REQSUB of f.f"; "" for a request no user's routine serves.
    function request_label(problem, k) result(label)
        type(problem_type), intent(in), target :: problem
        integer, intent(in) :: k
        character(len=:), allocatable :: label
        type(request_answer_watch_type), pointer :: watch

        label = ""
        watch => request_watch(problem)
        associate (request => watch%own_requests(k))
            if (request%kind /= answer_user) return
            label = request%name // ", its " // force_routine_label(request%routine)
        end associate
    end function request_label

    !> The request's RESULT(2:4) and RESULT(6:8), the entries ADAMS writes, as its REQSUB
    !> gives them (its first call is preceded by its initialisation call, as in a run).
    subroutine request_values(problem, k, time, q, u, values, error)
        type(problem_type), intent(inout), target :: problem
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable, intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        type(request_answer_watch_type), pointer :: watch
        real(wp) :: result(request_results)

        watch => request_watch(problem)
        ! the VARSUBs at the probed state: SYSFNC('VARVAL') reads their values there
        call evaluate_user_variables(time, q, u)
        associate (request => watch%own_requests(k))
            call call_user_request(request%routine, request%id, request%name, request%par, &
                & watch%time_unit, time, q, u, request%declared, request%declared_rates, result)
        end associate
        values = result(request_columns)
        call take_user_force_error(error)
    end subroutine request_values

    !> The problem's request watch (rollcon_adm_requests adds one at most); null when none.
    function request_watch(problem) result(watch)
        type(problem_type), intent(in), target :: problem
        type(request_answer_watch_type), pointer :: watch
        integer :: w

        watch => null()
        do w = 1, size(problem%watches)
            select type (found => problem%watches(w)%watch)
            type is (request_answer_watch_type)
                watch => found
                return
            end select
        end do
    end function request_watch

    !> A routine's error message without the statement and routine it starts with, which the
    !> finding names before it ("x.adm:9: SFORCE/2: its SFOSUB of f.f returned ..." after the
    !> label "x.adm:9: SFORCE/2, its SFOSUB of f.f": "returned ...").
    function failure_text(message, label) result(text)
        character(len=*), intent(in) :: message, label
        character(len=:), allocatable :: text, prefix
        integer :: comma

        text = message
        comma = index(label, ", its ")
        if (comma == 0) return
        prefix = label(:comma - 1) // ": its " // label(comma + 6:)
        if (index(message, prefix) == 1) text = adjustl(message(len(prefix) + 1:))
        if (index(text, ", ") == 1) text = text(3:)
    end function failure_text


    !> Bytes from the child: each finding a line, and the tally.
    subroutine receive(self, bytes)
        class(findings_receiver_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        character(len=:), allocatable :: payload
        integer :: kind, stat, numbers(4)
        logical :: found

        call self%frames%add(bytes)
        do
            call self%frames%next(kind, payload, found)
            if (.not. found) exit
            if (kind == frame_tally) then
                read(payload, *, iostat=stat) numbers
                if (stat == 0) self%tally = check_tally_type(numbers(1), numbers(2), &
                    & numbers(3), numbers(4))
                cycle
            end if
            if (.not. allocated(self%text)) self%text = ""
            self%text = self%text // payload
            if (payload(len(payload):) /= new_line("a")) self%text = self%text // new_line("a")
            self%count = self%count + 1
        end do
    end subroutine receive

end module rollcon_user_routine_check
