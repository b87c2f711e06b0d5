! SPDX-License-Identifier: MIT
!> `rollcon check FILE --model MODEL.adm` for a dataset whose forces are served by the file's
!> routines (SFOSUB, VFOSUB, GFOSUB, VTOSUB; docs/checker.md, "Checking a force routine"):
!>
!> - implicit typing (a Fortran file; C has none): the file compiled once more with
!>   gfortran's -Wconversion, each warning
!>   of a conversion that may change a value (a DOUBLE PRECISION value into a variable typed
!>   INTEGER or REAL by its first letter) a finding naming the routine and the line;
!> - in a child process (the routines' own, with the time limit per call and the guards of a
!>   run, rollcon_force_routine_guard), the model built as a run builds it (the
!>   initialisation calls included) and every force routine called at its start and at
!>   random states about it: the same inputs twice must give the same RESULT (no hidden
!>   state), RESULT must be finite, and continuous (a step of 1e-7 in the state changes it by
!>   little: a jump is a finding), and its SYSFNC and SYSARY calls must name only what its
!>   initialisation call named. Each finding names the statement, the routine, the call and
!>   the state.
module rollcon_force_routine_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_ucon
    use rollcon_text, only : to_text, shell_quote
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_problem, only : problem_type
    use rollcon_force, only : profile_statement
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_user_build, only : user_build_options_type, build_user_library, source_kind, &
        & kind_c
    use rollcon_user_library, only : user_ucosub_type, load_user_routines
    use rollcon_user_forces, only : clear_force_routines, evaluate_user_forces, &
        & take_user_force_error, system_notes, clear_system_notes, force_routine_label
    use rollcon_force_routine_guard, only : install_force_guard
    use rollcon_ucosub_guard, only : install_guard, attach_call_record, guarded_ucosub
    use rollcon_child_process, only : isolated_task_type, stream_receiver_type, &
        & call_record_type, isolation_outcome_type, run_in_child, outcome_finished
    use rollcon_frames, only : send_frame, frame_buffer_type
    use rollcon_isolation_text, only : outcome_text
    implicit none
    private

    public :: dataset_has_user_forces, check_force_routines, implicit_typing_findings

    !> States probed about the start, besides the start itself
    integer, parameter :: probed_states = 20
    !> Relative step of the continuity probe: small enough that a smooth force changes by
    !> about 1e-7 of its scale, far above rounding
    real(wp), parameter :: continuity_step = 1.0e-7_wp
    !> A change beyond this fraction of the force's scale (1 + |RESULT|) across the step is a
    !> jump: 1e4 times what a smooth force with derivatives of its own size would change
    real(wp), parameter :: jump_fraction = 1.0e-3_wp

    !> The child's work
    type, extends(isolated_task_type) :: force_check_task_type
        type(job_type) :: job
        character(len=:), allocatable :: library
        integer :: seed = 1
    contains
        procedure :: run => run_force_check
    end type force_check_task_type

    !> In this process: the findings the child sends, a line each
    type, extends(stream_receiver_type) :: findings_receiver_type
        type(frame_buffer_type) :: frames
        character(len=:), allocatable :: text
        integer :: count = 0
    contains
        procedure :: receive
    end type findings_receiver_type

contains

    !> True when the dataset at path has a force with FUNCTION=USER(...).
    function dataset_has_user_forces(path) result(has)
        character(len=*), intent(in) :: path
        logical :: has
        type(adm_model_type) :: adm
        type(error_type), allocatable :: error

        has = .false.
        call read_adm(path, adm, error)
        if (allocated(error)) return
        if (.not. allocated(adm%forces)) return
        has = any(adm%forces%user)
    end function dataset_has_user_forces

    !> Check the force routines of file on the dataset at model: findings (a line each, "" for
    !> none) and their number. error is for what prevents the check (the file does not build,
    !> the model does not read).
    subroutine check_force_routines(file, model, options, call_timeout, seed, findings, count, &
            & error)
        character(len=*), intent(in) :: file, model
        type(user_build_options_type), intent(in) :: options
        !> Longest one call may take [s]
        real(wp), intent(in) :: call_timeout
        !> Seed of the probed states
        integer, intent(in) :: seed
        character(len=:), allocatable, intent(out) :: findings
        integer, intent(out) :: count
        type(error_type), allocatable, intent(out) :: error
        type(force_check_task_type) :: task
        type(findings_receiver_type) :: receiver
        type(isolation_outcome_type) :: outcome
        character(len=:), allocatable :: typing
        logical :: from_cache
        integer :: typing_count

        findings = ""
        count = 0
        call build_user_library(file, options, task%library, from_cache, error)
        if (allocated(error)) return
        call load_job(model, task%job, error, ucosub=file)
        if (allocated(error)) return
        task%job%build_options = options
        task%seed = seed
        receiver%text = ""
        call run_in_child(task, real(call_timeout, wp), outcome, error, receiver=receiver)
        findings = receiver%text
        count = receiver%count
        if (outcome%kind /= outcome_finished) then
            findings = findings // "[crash] " // outcome_text(outcome) // new_line("a")
            count = count + 1
            if (allocated(error)) deallocate(error)
        else if (allocated(error)) then
            if (error%stat /= stat_ucon) return
            ! a routine's failure in the initialisation call is a finding too
            findings = findings // "[error] " // error%message // new_line("a")
            count = count + 1
            deallocate(error)
        end if
        ! C has no implicit typing: its declarations are the programmer's own
        if (source_kind(file) == kind_c) return
        call implicit_typing_findings(file, options%compiler, typing, typing_count, error)
        if (allocated(error)) return
        findings = findings // typing
        count = count + typing_count
    end subroutine check_force_routines

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
            at = index(upper(line), "SUBROUTINE ")
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

    !> Upper case of text.
    pure function upper(text) result(up)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: up
        integer :: k

        up = text
        do k = 1, len(text)
            if (text(k:k) >= "a" .and. text(k:k) <= "z") up(k:k) = achar(iachar(text(k:k)) - 32)
        end do
    end function upper

    !> This process's id.
    function getpid_value() result(pid)
        use rollcon_dlopen, only : process_id
        integer :: pid

        pid = process_id()
    end function getpid_value

    !> In the child: load the routines, build the model (the initialisation calls), probe.
    subroutine run_force_check(self, record, error)
        class(force_check_task_type), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(problem_type), target :: problem
        procedure(ucosub_interface), pointer :: guarded
        real(wp), allocatable :: q0(:), u0(:), q(:), u(:), dq(:), du(:)
        real(wp) :: first(6), second(6), moved(6), scale
        character(len=:), allocatable :: report, state, name
        integer :: s, i, n
        integer, allocatable :: seed(:)

        call attach_call_record(record)
        call clear_force_routines()
        user%source = self%job%user_file
        user%library = self%library
        call load_user_routines(user, error)
        if (allocated(error)) return
        call install_force_guard(record)
        guarded => null()
        if (associated(user%ucosub)) then
            call install_guard(user%ucosub, as_errors=.true.)
            guarded => guarded_ucosub
        end if
        call clear_system_notes()
        call self%job%source%build(guarded, problem, q0, u0, report, error)
        if (allocated(error)) return
        call random_seed(size=n)
        allocate(seed(n))
        seed = self%seed + 7919*[(i, i = 1, n)]
        call random_seed(put=seed)
        allocate(dq(size(q0)), du(size(u0)))
        do s = 0, probed_states
            q = q0
            u = u0
            if (s > 0) then
                ! about the start: positions within 0.05 m or rad, rates within 0.5 m/s or rad/s
                call random_number(dq)
                call random_number(du)
                q = q0 + 0.1_wp*(dq - 0.5_wp)
                u = u0 + (du - 0.5_wp)
            end if
            state = "state " // to_text(s) // merge(" (the start)", "            ", s == 0)
            call random_number(dq)
            call random_number(du)
            do i = 1, size(problem%model%forces)
                if (problem%model%forces(i)%profile /= profile_statement) cycle
                if (problem%model%forces(i)%statement%routine == 0) cycle
                name = problem%model%forces(i)%name // ", its " // force_routine_label( &
                    & problem%model%forces(i)%statement%routine)
                call value_at(i, 0.0_wp, q, u, first, error)
                if (allocated(error)) call finding("[error] " // name // " at " // state &
                    & // ": " // error%message)
                if (allocated(error)) return
                call value_at(i, 0.0_wp, q, u, second, error)
                if (allocated(error)) return
                if (any(first /= second)) call finding("[hidden state] " // name // " at " &
                    & // state // ": the same inputs gave RESULT " // numbers(first) &
                    & // " and then " // numbers(second))
                scale = 1.0_wp + maxval(abs(first))
                call value_at(i, 0.0_wp, q + continuity_step*(1.0_wp + abs(q))*(dq - 0.5_wp), &
                    & u + continuity_step*(1.0_wp + abs(u))*(du - 0.5_wp), moved, error)
                if (allocated(error)) return
                if (maxval(abs(moved - first)) > jump_fraction*scale) call finding("[jump] " &
                    & // name // " at " // state // ": a step of 1e-7 in the state changed " &
                    & // "RESULT from " // numbers(first) // " to " // numbers(moved) &
                    & // " (a discontinuity the integrator cannot step over)")
            end do
        end do
        if (len(system_notes()) > 0) call finding("[declaration] " // system_notes())
    contains
        subroutine value_at(i, time, q, u, values, error)
            integer, intent(in) :: i
            real(wp), intent(in) :: time, q(:), u(:)
            real(wp), intent(out) :: values(6)
            type(error_type), allocatable, intent(out) :: error

            call evaluate_user_forces(problem%model%forces(i:i), time, q, u)
            values = problem%model%forces(i)%statement%user_values
            call take_user_force_error(error)
        end subroutine value_at

        subroutine finding(text)
            character(len=*), intent(in) :: text
            type(error_type), allocatable :: ignored

            call send_frame(self%stream_fd, 1, text, ignored)
        end subroutine finding
    end subroutine run_force_check

    !> "(1.5, -2)" of values.
    function numbers(values) result(text)
        real(wp), intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: k

        text = "("
        do k = 1, size(values)
            if (k > 1) text = text // ", "
            text = text // to_text(values(k))
        end do
        text = text // ")"
    end function numbers

    !> Bytes from the child: each finding a line.
    subroutine receive(self, bytes)
        class(findings_receiver_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        character(len=:), allocatable :: payload
        integer :: kind
        logical :: found

        call self%frames%add(bytes)
        do
            call self%frames%next(kind, payload, found)
            if (.not. found) exit
            if (.not. allocated(self%text)) self%text = ""
            self%text = self%text // payload
            if (payload(len(payload):) /= new_line("a")) self%text = self%text // new_line("a")
            self%count = self%count + 1
        end do
    end subroutine receive

end module rollcon_force_routine_check
