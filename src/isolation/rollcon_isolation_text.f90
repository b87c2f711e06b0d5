! SPDX-License-Identifier: MIT
!> Words for how an isolated child ended (rollcon_child_process), the useful lines of its
!> captured stderr, and the names of its scratch files.
module rollcon_isolation_text
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_dlopen, only : process_id
    use rollcon_force_routine_contract, only : routine_names, routine_statements, routine_kinds
    use rollcon_system_routine_contract, only : routine_reqsub, request_routine_name, &
        & routine_varsub, variable_routine_name, routine_motsub, motion_routine_name, &
        & routine_difsub, diff_routine_name
    use rollcon_child_process, only : isolation_outcome_type, outcome_signal, outcome_timeout, &
        & outcome_exit, signal_name, call_record_type
    implicit none
    private

    public :: outcome_text, outcome_statement, quote_stderr, scratch_path

    !> Lines of the child's stderr quoted at most
    integer, parameter :: quoted_lines = 4

contains

    !> "UCON/1: the UCOSUB was killed by SIGFPE (...) in call 57, IFLAG = 0, IDRSEL = (1, 1, 1),
    !> TIME = 2.5, Q = (...), state 3": what happened and the call it happened in. `where`, the
    !> statement as its user wrote it ("model.adm:12: UCON/1", the caller's from the dataset),
    !> takes the place of the statement the record names (outcome_statement: "UCON/1"), as
    !> every other error of a user's routine names it.
    function outcome_text(outcome, where) result(text)
        !> How the child ended
        type(isolation_outcome_type), intent(in) :: outcome
        !> The statement whose routine was called, with its file and line
        character(len=*), intent(in), optional :: where
        character(len=:), allocatable :: text
        integer :: i, n

        if (outcome%record%routine_kind > 0) then
            text = force_outcome_text(outcome, statement_named(outcome%record, where))
            return
        end if
        associate (record => outcome%record)
            text = ""
            if (record%calls > 0) text = statement_named(record, where) // ": "
            select case (outcome%kind)
            case (outcome_signal)
                text = text // "the process was killed by " // signal_name(outcome%signal)
            case (outcome_timeout)
                text = text // "a UCOSUB call did not return within " &
                    & // to_text(real(outcome%call_timeout, wp)) // " s, the time limit per " &
                    & // "call (--call-timeout SECONDS); the process was killed"
            case (outcome_exit)
                text = text // "the process ended with exit status " &
                    & // to_text(outcome%exit_status) // " before its work was done (a STOP, " &
                    & // "ERROR STOP or CALL EXIT in the UCOSUB? only rollcon may end the process)"
            case default
                text = text // "the process finished"
            end select
            if (record%calls == 0) then
                text = text // ", before the first UCOSUB call"
                return
            end if
            if (record%in_call == 1) then
                text = text // ", inside"
            else
                text = text // ", after"
            end if
            text = text // " UCOSUB call " // to_text(int(record%calls)) // ": IFLAG = " &
                & // to_text(int(record%iflag))
            if (record%iflag == 3) then
                text = text // " (the initialisation call)"
            else
                text = text // ", IDRSEL = (" // to_text(int(record%idrsel(1))) // ", " &
                    & // to_text(int(record%idrsel(2))) // ", " &
                    & // to_text(int(record%idrsel(3))) // "), TIME = " &
                    & // to_text(real(record%time, wp))
                n = min(int(record%nq), size(record%q))
                ! Declared count unknown (a run): up to the last non-zero entry.
                if (n == size(record%q)) n = max(1, findloc(record%q /= 0.0_wp, .true., dim=1, &
                    & back=.true.))
                text = text // ", Q(1:" // to_text(n) // ") = ("
                do i = 1, n
                    if (i > 1) text = text // ", "
                    text = text // to_text(real(record%q(i), wp))
                end do
                text = text // ")"
                if (record%stage > 0) text = text // " (state " &
                    & // to_text(int(record%stage)) // " of the check)"
            end if
        end associate
    end function outcome_text

    !> The statement whose routine a record's call is of, as its keyword and id: UCON/1 (a
    !> UCOSUB), SFORCE/2 (an SFOSUB), VFORCE, GFORCE, VTORQUE, REQUEST, VARIABLE, MOTION, DIFF;
    !> routine, the routine's name (UCOSUB, SFOSUB, ...).
    subroutine outcome_statement(record, keyword, id, routine)
        type(call_record_type), intent(in) :: record
        character(len=:), allocatable, intent(out) :: keyword, routine
        integer, intent(out) :: id

        id = int(record%ucon_id)
        if (record%routine_kind == routine_reqsub) then
            keyword = "REQUEST"
            routine = request_routine_name
        else if (record%routine_kind == routine_varsub) then
            keyword = "VARIABLE"
            routine = variable_routine_name
        else if (record%routine_kind == routine_motsub) then
            keyword = "MOTION"
            routine = motion_routine_name
        else if (record%routine_kind == routine_difsub) then
            keyword = "DIFF"
            routine = diff_routine_name
        else if (record%routine_kind > 0) then
            keyword = trim(routine_statements(min(routine_kinds, int(record%routine_kind))))
            routine = trim(routine_names(min(routine_kinds, int(record%routine_kind))))
        else
            keyword = "UCON"
            routine = "UCOSUB"
        end if
    end subroutine outcome_statement

    !> where when given and not empty, else the record's statement, "SFORCE/2".
    function statement_named(record, where) result(text)
        type(call_record_type), intent(in) :: record
        character(len=*), intent(in), optional :: where
        character(len=:), allocatable :: text, keyword, routine
        integer :: id

        if (present(where)) then
            if (len(where) > 0) then
                text = where
                return
            end if
        end if
        call outcome_statement(record, keyword, id, routine)
        text = keyword // "/" // to_text(id)
    end function statement_named

    !> outcome_text for a force routine's call: "SFORCE/2: the process was killed by SIGSEGV
    !> (...), inside SFOSUB call 57: IFLAG = .FALSE., TIME = 0.25", the statement named as
    !> `named` says.
    function force_outcome_text(outcome, named) result(text)
        type(isolation_outcome_type), intent(in) :: outcome
        character(len=*), intent(in) :: named
        character(len=:), allocatable :: text, routine, keyword
        integer :: id

        associate (record => outcome%record)
            call outcome_statement(record, keyword, id, routine)
            text = named // ": "
            select case (outcome%kind)
            case (outcome_signal)
                text = text // "the process was killed by " // signal_name(outcome%signal)
            case (outcome_timeout)
                text = text // "a call of the " // routine // " did not return within " &
                    & // to_text(real(outcome%call_timeout, wp)) // " s, the time limit per " &
                    & // "call (--call-timeout SECONDS); the process was killed"
            case (outcome_exit)
                text = text // "the process ended with exit status " &
                    & // to_text(outcome%exit_status) // " before its work was done (a STOP, " &
                    & // "ERROR STOP or CALL EXIT in the " // routine // "? only rollcon may " &
                    & // "end the process)"
            case default
                text = text // "the process finished"
            end select
            if (record%in_call == 1) then
                text = text // ", inside"
            else
                text = text // ", after"
            end if
            text = text // " " // routine // " call " // to_text(int(record%calls)) &
                & // ": IFLAG = " // trim(merge(".TRUE. ", ".FALSE.", record%iflag /= 0)) &
                & // ", TIME = " // to_text(real(record%time, wp))
        end associate
    end function force_outcome_text

    !> The useful lines of a child's captured stderr (what gfortran says of the signal, a STOP
    !> message, the source line of the UCOSUB in the backtrace), as "; its stderr: ..." or "".
    function quote_stderr(path) result(text)
        !> File holding the child's stderr
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        character(len=400) :: line
        integer :: unit, stat, quoted
        logical :: after_ucosub, useful

        text = ""
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        quoted = 0
        after_ucosub = .false.
        do while (quoted < quoted_lines)
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! gfortran's backtrace indents its "at FILE:LINE" lines with a tab
            where_tab: block
                integer :: i
                do i = 1, len_trim(line)
                    if (line(i:i) == achar(9)) line(i:i) = " "
                end do
            end block where_tab
            line = adjustl(line)
            useful = index(line, "Program received signal") == 1 .or. index(line, "STOP") == 1 &
                & .or. index(line, "ERROR STOP") == 1 .or. index(line, "Fortran runtime") == 1 &
                & .or. index(line, "At line") == 1 .or. (after_ucosub .and. index(line, "at ") == 1)
            after_ucosub = index(line, " in ucosub_") > 0 .or. index(line, " in sfosub_") > 0 &
                & .or. index(line, " in vfosub_") > 0 .or. index(line, " in gfosub_") > 0 &
                & .or. index(line, " in vtosub_") > 0 .or. index(line, " in reqsub_") > 0 &
                & .or. index(line, " in varsub_") > 0 .or. index(line, " in motsub_") > 0 &
                & .or. index(line, " in difsub_") > 0
            if (.not. useful .or. len_trim(line) == 0) cycle
            if (quoted == 0) then
                text = "; its stderr: "
            else
                text = text // " | "
            end if
            text = text // trim(line)
            quoted = quoted + 1
        end do
        close(unit)
    end function quote_stderr

    !> A scratch file for child number k of this process: $TMPDIR (else /tmp)
    !> /rollcon-<what>-<pid>-<k><extension>.
    function scratch_path(what, k, extension) result(path)
        !> What the file is for ("check", "run")
        character(len=*), intent(in) :: what
        !> Number of the child
        integer, intent(in) :: k
        !> File name extension, with its dot
        character(len=*), intent(in) :: extension
        character(len=:), allocatable :: path
        character(len=:), allocatable :: dir
        integer :: length, stat

        ! read whole, however long (a cut value would name another folder)
        call get_environment_variable("TMPDIR", length=length, status=stat)
        if (stat /= 0 .or. length == 0) then
            dir = "/tmp"
        else
            allocate(character(len=length) :: dir)
            call get_environment_variable("TMPDIR", dir)
        end if
        path = dir // "/rollcon-" // what // "-" // to_text(process_id()) // "-" &
            & // to_text(k) // extension
    end function scratch_path

end module rollcon_isolation_text
