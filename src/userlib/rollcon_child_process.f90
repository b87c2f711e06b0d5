! SPDX-License-Identifier: MIT
!> Runs a task in a child process (POSIX fork) so that whatever a user's routine does there (a
!> signal, an endless loop, a STOP) cannot take the host down; the host watches the child and
!> turns its end into an outcome.
!>
!> Before forking, the host maps an anonymous shared page (mmap MAP_SHARED) holding a
!> call_record_type: the child writes the UCOSUB call in progress there (rollcon_ucosub_guard
!> does) and, when its task returns, the task's error and the "finished" flag. The host polls
!> waitpid(WNOHANG) with short sleeps, times each call by watching the call counter, and kills
!> the child (SIGKILL) when one call lasts longer than the limit. Linux x86-64 / glibc values.
module rollcon_child_process
    use, intrinsic :: iso_c_binding, only : c_int, c_long, c_int64_t, c_double, c_char, c_ptr, &
        & c_funptr, c_size_t, c_intptr_t, c_null_ptr, c_null_funptr, c_null_char, c_sizeof, &
        & c_f_pointer
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit, int64
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_fatal
    implicit none
    private

    public :: call_record_type, isolated_task_type, isolation_outcome_type, run_in_child
    public :: outcome_finished, outcome_signal, outcome_timeout, outcome_exit, signal_name
    public :: record_capacity, default_call_timeout

    !> Time limit of one UCOSUB call when the user sets none [s]: far beyond any sane
    !> constraint evaluation (microseconds), short enough to notice an endless loop
    real(c_double), parameter :: default_call_timeout = 10.0_c_double

    !> How a child ended: its task returned, a signal killed it, it overran the time limit,
    !> or it exited without finishing (a STOP inside the user's routine)
    integer, parameter :: outcome_finished = 0, outcome_signal = 1, outcome_timeout = 2, &
        & outcome_exit = 3
    !> Characters of the task's error message the record carries back
    integer, parameter :: record_capacity = 4096

    !> What the child tells the host, in shared memory (zero-filled by mmap)
    type, bind(c) :: call_record_type
        !> UCOSUB calls begun so far
        integer(c_int64_t) :: calls
        !> 1 while a call is in progress
        integer(c_int) :: in_call
        !> 1 once the task returned (its error, if any, below)
        integer(c_int) :: finished
        !> The call in progress (or the last one): UCON id, IFLAG, IDRSEL, number of Q entries
        integer(c_int) :: ucon_id, iflag, idrsel(3), nq
        !> What the task was doing: a checker's state number (0: the initialisation call)
        integer(c_int) :: stage
        !> The task's error: 0 none, else its stat; length of its message
        integer(c_int) :: error_stat, message_length
        !> TIME and Q of the call
        real(c_double) :: time, q(30)
        !> The task's error message (first record_capacity characters)
        character(kind=c_char) :: message(record_capacity)
    end type call_record_type

    !> Work to do in a child: extend it and implement run
    type, abstract :: isolated_task_type
    contains
        !> Runs in the child; record is where the child reports its calls
        procedure(task_run), deferred :: run
    end type isolated_task_type

    abstract interface
        subroutine task_run(self, record, error)
            import :: isolated_task_type, call_record_type, error_type
            !> The task
            class(isolated_task_type), intent(inout) :: self
            !> The shared record (for rollcon_ucosub_guard)
            type(call_record_type), pointer, intent(in) :: record
            !> The task's own failure, passed back to the host
            type(error_type), allocatable, intent(out) :: error
        end subroutine task_run
    end interface

    !> How the child ended, and the call it was in
    type :: isolation_outcome_type
        !> outcome_finished, outcome_signal, outcome_timeout or outcome_exit
        integer :: kind = outcome_finished
        !> Signal that killed the child (outcome_signal), exit status (outcome_exit)
        integer :: signal = 0, exit_status = 0
        !> Copy of the shared record when the child ended
        type(call_record_type) :: record
        !> The time limit per call that applied [s]
        real(c_double) :: call_timeout = 0.0_c_double
    end type isolation_outcome_type

    integer(c_int), parameter :: prot_read = 1, prot_write = 2, map_shared = 1, &
        & map_anonymous = 32, wnohang = 1, sigkill = 9, rlimit_core = 4
    !> Signals whose default action replaces gfortran's backtrace handler in a quiet child
    integer(c_int), parameter :: fatal_signals(5) = [4_c_int, 6_c_int, 7_c_int, 8_c_int, 11_c_int]
    !> Polling of the child: first and longest sleep [microseconds]
    integer(c_int), parameter :: first_poll = 200, longest_poll = 5000

    type, bind(c) :: rlimit_type
        integer(c_long) :: current, maximum
    end type rlimit_type

    interface
        function c_fork() result(pid) bind(c, name="fork")
            import :: c_int
            integer(c_int) :: pid
        end function c_fork
        function c_waitpid(pid, status, options) result(rc) bind(c, name="waitpid")
            import :: c_int
            integer(c_int), value :: pid, options
            integer(c_int), intent(out) :: status
            integer(c_int) :: rc
        end function c_waitpid
        function c_kill(pid, signal) result(rc) bind(c, name="kill")
            import :: c_int
            integer(c_int), value :: pid, signal
            integer(c_int) :: rc
        end function c_kill
        subroutine c_exit(status) bind(c, name="_exit")
            import :: c_int
            integer(c_int), value :: status
        end subroutine c_exit
        function c_usleep(microseconds) result(rc) bind(c, name="usleep")
            import :: c_int
            integer(c_int), value :: microseconds
            integer(c_int) :: rc
        end function c_usleep
        function c_mmap(address, length, protection, flags, fd, offset) result(map) &
                & bind(c, name="mmap")
            import :: c_ptr, c_size_t, c_int, c_long
            type(c_ptr), value :: address
            integer(c_size_t), value :: length
            integer(c_int), value :: protection, flags, fd
            integer(c_long), value :: offset
            type(c_ptr) :: map
        end function c_mmap
        function c_munmap(address, length) result(rc) bind(c, name="munmap")
            import :: c_ptr, c_size_t, c_int
            type(c_ptr), value :: address
            integer(c_size_t), value :: length
            integer(c_int) :: rc
        end function c_munmap
        function c_signal(signal, handler) result(previous) bind(c, name="signal")
            import :: c_int, c_funptr
            integer(c_int), value :: signal
            type(c_funptr), value :: handler
            type(c_funptr) :: previous
        end function c_signal
        function c_creat(path, mode) result(fd) bind(c, name="creat")
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: fd
        end function c_creat
        function c_dup2(old, new) result(fd) bind(c, name="dup2")
            import :: c_int
            integer(c_int), value :: old, new
            integer(c_int) :: fd
        end function c_dup2
        function c_setrlimit(resource, limit) result(rc) bind(c, name="setrlimit")
            import :: c_int, rlimit_type
            integer(c_int), value :: resource
            type(rlimit_type), intent(in) :: limit
            integer(c_int) :: rc
        end function c_setrlimit
    end interface

contains

    !> Run task in a child process and wait for it, killing it when one UCOSUB call lasts
    !> longer than call_timeout. error is the task's own error (passed back from the child) or
    !> a failure to start the child; how the child ended is in outcome.
    subroutine run_in_child(task, call_timeout, outcome, error, stderr_path)
        !> The work; it runs in the child only
        class(isolated_task_type), intent(inout) :: task
        !> Longest a single UCOSUB call may take [s]
        real(c_double), intent(in) :: call_timeout
        !> How the child ended
        type(isolation_outcome_type), intent(out) :: outcome
        !> The task's error, or why no child could be started
        type(error_type), allocatable, intent(out) :: error
        !> When present, the child's stderr goes to this file (gfortran's backtrace included);
        !> when absent, it stays the host's and the child dies of a signal without a backtrace
        character(len=*), intent(in), optional :: stderr_path
        type(call_record_type), pointer :: record
        type(call_record_type) :: probe
        type(c_ptr) :: map
        integer(c_size_t) :: length
        integer(c_int) :: pid, rc

        length = c_sizeof(probe)
        map = c_mmap(c_null_ptr, length, ior(prot_read, prot_write), &
            & ior(map_shared, map_anonymous), -1_c_int, 0_c_long)
        if (transfer(map, 0_c_intptr_t) == -1_c_intptr_t) then
            call fatal_error(error, "cannot map the memory shared with a child process (mmap)", &
                & stat_io)
            return
        end if
        call c_f_pointer(map, record)
        outcome%call_timeout = call_timeout
        ! The child inherits the units' buffers: empty them, or both processes write them.
        flush(output_unit)
        flush(error_unit)
        pid = c_fork()
        if (pid < 0) then
            call fatal_error(error, "cannot start a child process (fork failed)", stat_io)
        else if (pid == 0) then
            call child_main(task, record, stderr_path)
        else
            call watch(pid, record, call_timeout, outcome)
            if (outcome%kind == outcome_finished .and. record%error_stat /= 0) then
                call fatal_error(error, message_of(record), int(record%error_stat))
            end if
        end if
        rc = c_munmap(map, length)
    end subroutine run_in_child

    !> The child's side: quiet signals or captured stderr, the task, the record; never returns.
    subroutine child_main(task, record, stderr_path)
        class(isolated_task_type), intent(inout) :: task
        type(call_record_type), pointer, intent(in) :: record
        character(len=*), intent(in), optional :: stderr_path
        type(error_type), allocatable :: error
        type(rlimit_type) :: no_core
        type(c_funptr) :: previous
        integer(c_int) :: fd, rc
        integer :: i

        no_core = rlimit_type(0_c_long, 0_c_long)
        rc = c_setrlimit(rlimit_core, no_core)
        if (present(stderr_path)) then
            fd = c_creat(stderr_path // c_null_char, int(o'644', c_int))
            if (fd >= 0) rc = c_dup2(fd, 2_c_int)
        else
            do i = 1, size(fatal_signals)
                previous = c_signal(fatal_signals(i), c_null_funptr)
            end do
        end if
        call task%run(record, error)
        if (allocated(error)) then
            record%error_stat = int(error%stat, c_int)
            if (record%error_stat == 0) record%error_stat = int(stat_fatal, c_int)
            record%message_length = int(min(len(error%message), record_capacity), c_int)
            do i = 1, record%message_length
                record%message(i) = error%message(i:i)
            end do
        end if
        record%finished = 1
        flush(output_unit)
        flush(error_unit)
        call c_exit(0_c_int)
    end subroutine child_main

    !> Wait for the child; time the call in progress by its counter; kill it past the limit.
    subroutine watch(pid, record, call_timeout, outcome)
        integer(c_int), intent(in) :: pid
        type(call_record_type), pointer, intent(in) :: record
        real(c_double), intent(in) :: call_timeout
        type(isolation_outcome_type), intent(inout) :: outcome
        integer(c_int) :: rc, status, sleep
        integer(c_int64_t) :: seen_calls
        integer(int64) :: clock, rate, call_start
        real(c_double) :: elapsed

        seen_calls = -1
        sleep = first_poll
        call system_clock(call_start, rate)
        do
            rc = c_waitpid(pid, status, wnohang)
            if (rc == pid) exit
            if (rc < 0) then
                ! the child cannot be waited for (it was reaped elsewhere): say so, do not spin
                outcome%kind = outcome_exit
                outcome%exit_status = -1
                outcome%record = record
                return
            end if
            call system_clock(clock)
            ! Read the counter through a copy: the child changes it between our reads.
            if (counter(record) /= seen_calls) then
                seen_calls = counter(record)
                call_start = clock
            end if
            elapsed = real(clock - call_start, c_double) / real(rate, c_double)
            if (in_call(record) .and. elapsed > call_timeout) then
                rc = c_kill(pid, sigkill)
                rc = c_waitpid(pid, status, 0_c_int)
                outcome%kind = outcome_timeout
                outcome%record = record
                return
            end if
            rc = c_usleep(sleep)
            sleep = min(2*sleep, longest_poll)
        end do
        outcome%record = record
        if (iand(status, 127) /= 0) then
            outcome%kind = outcome_signal
            outcome%signal = iand(status, 127)
        else if (record%finished /= 1) then
            outcome%kind = outcome_exit
            outcome%exit_status = iand(ishft(status, -8), 255)
        else
            outcome%kind = outcome_finished
        end if
    end subroutine watch

    !> The child's call counter, read afresh (the record is shared memory).
    function counter(record) result(calls)
        type(call_record_type), pointer, intent(in) :: record
        integer(c_int64_t) :: calls
        integer(c_int64_t), volatile, pointer :: shared

        shared => record%calls
        calls = shared
    end function counter

    !> True while the child is inside a UCOSUB call.
    function in_call(record) result(busy)
        type(call_record_type), pointer, intent(in) :: record
        logical :: busy
        integer(c_int), volatile, pointer :: shared

        shared => record%in_call
        busy = shared == 1
    end function in_call

    !> The task's error message carried by the record.
    function message_of(record) result(message)
        type(call_record_type), intent(in) :: record
        character(len=:), allocatable :: message
        integer :: i

        allocate(character(len=max(0, min(int(record%message_length), record_capacity))) &
            & :: message)
        do i = 1, len(message)
            message(i:i) = record%message(i)
        end do
    end function message_of

    !> Name and meaning of a signal number (Linux x86-64).
    pure function signal_name(signal) result(name)
        !> Signal number
        integer, intent(in) :: signal
        character(len=:), allocatable :: name
        character(len=16) :: number

        select case (signal)
        case (4)
            name = "SIGILL (illegal instruction)"
        case (6)
            name = "SIGABRT (abort: a failed check of the runtime, or a call to abort)"
        case (7)
            name = "SIGBUS (bus error: a misaligned or unmapped memory access)"
        case (8)
            name = "SIGFPE (erroneous arithmetic operation, such as an integer division by zero)"
        case (9)
            name = "SIGKILL (killed from outside, perhaps for lack of memory)"
        case (11)
            name = "SIGSEGV (segmentation fault: a read or write through a wild index or pointer)"
        case default
            write(number, '(i0)') signal
            name = "signal " // trim(number)
        end select
    end function signal_name

end module rollcon_child_process
