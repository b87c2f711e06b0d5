! SPDX-License-Identifier: MIT
!> Runs a task in a child process (POSIX fork) so that whatever a user's routine does there (a
!> signal, an endless loop, a STOP) cannot take the host down; the host watches the child and
!> turns its end into an outcome.
!>
!> Before forking, the host maps an anonymous shared page (mmap MAP_SHARED) holding a
!> call_record_type: the child writes the UCOSUB call in progress there (rollcon_ucosub_guard
!> does) and, when its task returns, the task's error and the "finished" flag. The host polls
!> waitpid(WNOHANG) with short sleeps, times each call by watching the call counter, and kills
!> the child (SIGKILL) when one call lasts longer than the limit. When the host gives a
!> receiver, the child also has a pipe to it (the task's stream_fd): the host reads it while it
!> waits and hands every byte to the receiver, so the child computes and the host keeps what
!> it sends (rollcon_isolated_run). The child dies with the host (PR_SET_PDEATHSIG): a host
!> killed by any signal leaves no child behind. Linux x86-64 / glibc values.
module rollcon_child_process
    use, intrinsic :: iso_c_binding, only : c_int, c_long, c_int64_t, c_double, c_char, c_ptr, &
        & c_funptr, c_size_t, c_intptr_t, c_null_ptr, c_null_funptr, c_null_char, c_sizeof, &
        & c_f_pointer, c_short
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit, int64
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_fatal
    implicit none
    private

    public :: call_record_type, isolated_task_type, isolation_outcome_type, run_in_child
    public :: stream_receiver_type
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
        !> The routine of the call: 0 a UCOSUB (ucon_id its UCON), else a force routine's kind
        !> (rollcon_force_routine_contract: 1 SFOSUB, 2 VFOSUB, 3 GFOSUB; ucon_id its statement)
        integer(c_int) :: routine_kind
        !> The task's error: 0 none, else its stat; length of its message
        integer(c_int) :: error_stat, message_length
        !> TIME and Q of the call
        real(c_double) :: time, q(30)
        !> The task's error message (first record_capacity characters)
        character(kind=c_char) :: message(record_capacity)
    end type call_record_type

    !> Work to do in a child: extend it and implement run
    type, abstract :: isolated_task_type
        !> In the child, when the host gave a receiver: the write end of the pipe to the host
        !> (rollcon_frames); -1 otherwise
        integer :: stream_fd = -1
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

    !> What the host does with the bytes the child sends on its pipe
    type, abstract :: stream_receiver_type
    contains
        procedure(receive_interface), deferred :: receive
    end type stream_receiver_type

    abstract interface
        !> The next bytes from the pipe (any number; frames may be cut anywhere).
        subroutine receive_interface(self, bytes)
            import :: stream_receiver_type
            class(stream_receiver_type), intent(inout) :: self
            character(len=*), intent(in) :: bytes
        end subroutine receive_interface
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
        & map_anonymous = 32, wnohang = 1, sigkill = 9, rlimit_core = 4, pr_set_pdeathsig = 1, &
        & pollin = 1
    !> Bytes read from the pipe at a time
    integer, parameter :: chunk_bytes = 65536
    !> Signals whose default action replaces gfortran's backtrace handler in a quiet child
    integer(c_int), parameter :: fatal_signals(5) = [4_c_int, 6_c_int, 7_c_int, 8_c_int, 11_c_int]
    !> Polling of the child: first and longest sleep [microseconds]
    integer(c_int), parameter :: first_poll = 200, longest_poll = 5000

    type, bind(c) :: rlimit_type
        integer(c_long) :: current, maximum
    end type rlimit_type

    !> poll(2)'s struct pollfd
    type, bind(c) :: pollfd_type
        integer(c_int) :: fd
        integer(c_short) :: events, revents
    end type pollfd_type

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
        function c_pipe(fds) result(rc) bind(c, name="pipe")
            import :: c_int
            integer(c_int), intent(out) :: fds(2)
            integer(c_int) :: rc
        end function c_pipe
        function c_close(fd) result(rc) bind(c, name="close")
            import :: c_int
            integer(c_int), value :: fd
            integer(c_int) :: rc
        end function c_close
        function c_read(fd, buffer, count) result(got) bind(c, name="read")
            import :: c_int, c_char, c_size_t, c_long
            integer(c_int), value :: fd
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_size_t), value :: count
            integer(c_long) :: got
        end function c_read
        function c_poll(fds, count, timeout) result(rc) bind(c, name="poll")
            import :: c_int, c_long, pollfd_type
            type(pollfd_type), intent(inout) :: fds(*)
            integer(c_long), value :: count
            integer(c_int), value :: timeout
            integer(c_int) :: rc
        end function c_poll
        function c_prctl(option, argument, unused3, unused4, unused5) result(rc) &
                & bind(c, name="prctl")
            import :: c_int, c_long
            integer(c_int), value :: option
            integer(c_long), value :: argument, unused3, unused4, unused5
            integer(c_int) :: rc
        end function c_prctl
        function c_getpid() result(pid) bind(c, name="getpid")
            import :: c_int
            integer(c_int) :: pid
        end function c_getpid
        function c_getppid() result(pid) bind(c, name="getppid")
            import :: c_int
            integer(c_int) :: pid
        end function c_getppid
    end interface

contains

    !> Run task in a child process and wait for it, killing it when one UCOSUB call lasts
    !> longer than call_timeout. error is the task's own error (passed back from the child) or
    !> a failure to start the child; how the child ended is in outcome.
    subroutine run_in_child(task, call_timeout, outcome, error, stderr_path, receiver)
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
        !> When present, the child gets a pipe to the host (task%stream_fd) and what it sends
        !> is handed to the receiver as it comes
        class(stream_receiver_type), intent(inout), optional :: receiver
        type(call_record_type), pointer :: record
        type(call_record_type) :: probe
        type(c_ptr) :: map
        integer(c_size_t) :: length
        integer(c_int) :: pid, rc, host, fds(2)

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
        fds = -1
        if (present(receiver)) then
            if (c_pipe(fds) /= 0) then
                call fatal_error(error, "cannot make a pipe to a child process", stat_io)
                rc = c_munmap(map, length)
                return
            end if
        end if
        ! The child inherits the units' buffers: empty them, or both processes write them.
        flush(output_unit)
        flush(error_unit)
        host = c_getpid()
        pid = c_fork()
        if (pid < 0) then
            call fatal_error(error, "cannot start a child process (fork failed)", stat_io)
        else if (pid == 0) then
            if (fds(1) >= 0) rc = c_close(fds(1))
            task%stream_fd = int(fds(2))
            call child_main(task, record, host, stderr_path)
        else
            if (fds(2) >= 0) rc = c_close(fds(2))
            call watch(pid, record, call_timeout, outcome, fds(1), receiver)
            if (outcome%kind == outcome_finished .and. record%error_stat /= 0) then
                call fatal_error(error, message_of(record), int(record%error_stat))
            end if
        end if
        if (fds(1) >= 0) rc = c_close(fds(1))
        rc = c_munmap(map, length)
    end subroutine run_in_child

    !> The child's side: death with the host, quiet signals or captured stderr, the task, the
    !> record; never returns.
    subroutine child_main(task, record, host, stderr_path)
        class(isolated_task_type), intent(inout) :: task
        type(call_record_type), pointer, intent(in) :: record
        !> The host's process id
        integer(c_int), intent(in) :: host
        character(len=*), intent(in), optional :: stderr_path
        type(error_type), allocatable :: error
        type(rlimit_type) :: no_core
        type(c_funptr) :: previous
        integer(c_int) :: fd, rc
        integer :: i

        ! SIGKILL when the host ends, however it ends; a host gone before this line: end now
        rc = c_prctl(pr_set_pdeathsig, int(sigkill, c_long), 0_c_long, 0_c_long, 0_c_long)
        if (c_getppid() /= host) call c_exit(1_c_int)
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
        ! the routine may have closed these units: a failed flush is not the task's failure
        flush(output_unit, iostat=rc)
        flush(error_unit, iostat=rc)
        call c_exit(0_c_int)
    end subroutine child_main

    !> Wait for the child, reading its pipe (when it has one) into the receiver; time the call
    !> in progress by its counter; kill it past the limit.
    subroutine watch(pid, record, call_timeout, outcome, pipe, receiver)
        integer(c_int), intent(in) :: pid
        type(call_record_type), pointer, intent(in) :: record
        real(c_double), intent(in) :: call_timeout
        type(isolation_outcome_type), intent(inout) :: outcome
        !> Read end of the child's pipe (-1: none)
        integer(c_int), intent(in) :: pipe
        class(stream_receiver_type), intent(inout), optional :: receiver
        integer(c_int) :: rc, status, sleep
        integer(c_int64_t) :: seen_calls
        integer(int64) :: clock, rate, call_start
        real(c_double) :: elapsed
        logical :: open_pipe

        seen_calls = -1
        sleep = first_poll
        open_pipe = pipe >= 0 .and. present(receiver)
        call system_clock(call_start, rate)
        do
            ! bytes from the child: look again at once (the poll's wait is the loop's sleep)
            if (open_pipe) then
                if (drain(pipe, receiver, sleep)) sleep = first_poll/2
            end if
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
            if (.not. open_pipe) rc = c_usleep(sleep)
            sleep = min(2*sleep, longest_poll)
        end do
        ! what the child wrote before it ended
        if (open_pipe) then
            do while (drain(pipe, receiver, 0_c_int))
            end do
        end if
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

    !> Wait up to sleep microseconds for bytes on the pipe and hand what is there to the
    !> receiver: true when there were some (false on nothing, end of file or an error).
    function drain(pipe, receiver, sleep) result(got_bytes)
        integer(c_int), intent(in) :: pipe
        class(stream_receiver_type), intent(inout) :: receiver
        integer(c_int), intent(in) :: sleep
        logical :: got_bytes
        type(pollfd_type) :: fds(1)
        character(kind=c_char, len=chunk_bytes) :: buffer
        integer(c_long) :: got

        got_bytes = .false.
        fds(1) = pollfd_type(pipe, int(pollin, c_short), 0_c_short)
        if (c_poll(fds, 1_c_long, (sleep + 999_c_int)/1000_c_int) <= 0) return
        if (iand(int(fds(1)%revents), int(pollin)) == 0) return
        got = c_read(pipe, buffer, int(chunk_bytes, c_size_t))
        if (got <= 0) return
        call receiver%receive(buffer(:got))
        got_bytes = .true.
    end function drain

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
