! SPDX-License-Identifier: MIT
!> Checks a user's UCOSUB where its failure cannot take the host down: each UCON is checked by
!> check_user_ucosub in a child process of its own (rollcon_child_process), which sends its
!> part of the report back as one frame on its pipe (rollcon_frames, rollcon_audit_transfer).
!> A child killed by a signal, stopped at the time limit of one call, or ended by a STOP
!> inside the routine becomes a finding of that UCON (rule_signal, rule_timeout, rule_exit)
!> naming the call (IFLAG, IDRSEL), the state and what happened; the other UCONs are checked
!> as usual. A child that finished without a whole report is an error, never a wait.
module rollcon_isolated_audit
    use, intrinsic :: iso_c_binding, only : c_double
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_wire, only : wire_writer_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, ucon_report_type, finding_group_type, check_user_ucosub, &
        & check_requests, finding
    use rollcon_audit_transfer, only : pack_ucon_report, unpack_ucon_report
    use rollcon_check_rules, only : rule_signal, rule_timeout, rule_exit
    use rollcon_child_process, only : isolated_task_type, call_record_type, &
        & isolation_outcome_type, run_in_child, outcome_finished, outcome_signal, &
        & outcome_timeout, stream_receiver_type
    use rollcon_frames, only : send_frame, frame_buffer_type
    use rollcon_isolation_text, only : outcome_text, scratch_path, quote_stderr
    use rollcon_ucosub_guard, only : attach_call_record
    implicit none
    private

    public :: check_user_ucosub_isolated

    !> Kind of the one frame a checking child sends: its UCON's report
    integer, parameter :: frame_ucon_report = 1

    !> Checking one UCON, in the child
    type, extends(isolated_task_type) :: ucon_check_task
        !> The routine under test
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
        !> The UCON statement
        type(ucon_request_type) :: request
        !> States, seed, tolerance
        type(user_check_options_type) :: options
    contains
        procedure :: run => run_ucon_check
    end type ucon_check_task

    !> The host's side of the pipe: the report frame, once it is whole
    type, extends(stream_receiver_type) :: report_receiver_type
        type(frame_buffer_type) :: frames
        !> The packed report (allocated once its frame arrived)
        character(len=:), allocatable :: payload
        !> Frames of another kind, or a second report, arrived
        logical :: garbled = .false.
    contains
        procedure :: receive => receive_report
    end type report_receiver_type

contains

    !> check_user_ucosub, each UCON in a child process, each call limited to call_timeout.
    subroutine check_user_ucosub_isolated(ucosub, requests, options, call_timeout, report, error)
        !> The routine under test (loaded from the user's file)
        procedure(ucosub_interface) :: ucosub
        !> UCON statements to check (distinct ids)
        type(ucon_request_type), intent(in) :: requests(:)
        !> States, seed, tolerance
        type(user_check_options_type), intent(in) :: options
        !> Longest one UCOSUB call may take [s]
        real(wp), intent(in) :: call_timeout
        !> Findings
        type(user_check_report_type), intent(out) :: report
        !> Set when the request cannot be checked or no child process can be run
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_task) :: task
        type(report_receiver_type) :: receiver
        type(isolation_outcome_type) :: outcome
        character(len=:), allocatable :: stderr_path
        integer :: k

        call check_requests(requests, options, error)
        if (allocated(error)) return
        report%options = options
        allocate(report%ucons(size(requests)))
        task%ucosub => ucosub
        task%options = options
        do k = 1, size(requests)
            task%request = requests(k)
            stderr_path = scratch_path("check", k, ".stderr")
            receiver = report_receiver_type()
            call run_in_child(task, real(call_timeout, c_double), outcome, error, stderr_path, &
                & receiver)
            if (allocated(error)) then
                call remove_file(stderr_path)
                exit
            end if
            if (outcome%kind == outcome_finished) then
                call take_report(receiver, requests(k), report%ucons(k), error)
            else
                call fault_report(requests(k), outcome, quote_stderr(stderr_path), &
                    & report%ucons(k))
            end if
            call remove_file(stderr_path)
            if (allocated(error)) exit
            ! the statement as the dataset names it stays here (the child sends the findings)
            if (allocated(requests(k)%statement)) report%ucons(k)%statement = &
                & requests(k)%statement
        end do
    end subroutine check_user_ucosub_isolated

    !> In the child: check the UCON with the calls recorded, send its report to the host.
    subroutine run_ucon_check(self, record, error)
        class(ucon_check_task), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        type(wire_writer_type) :: wire

        call attach_call_record(record)
        call check_user_ucosub(self%ucosub, [self%request], self%options, report, error)
        if (allocated(error)) return
        call pack_ucon_report(wire, report%ucons(1))
        call send_frame(self%stream_fd, frame_ucon_report, wire%packed(), error)
    end subroutine run_ucon_check

    !> Bytes from a checking child: its report frame kept once whole.
    subroutine receive_report(self, bytes)
        class(report_receiver_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        character(len=:), allocatable :: payload
        integer :: kind
        logical :: found

        call self%frames%add(bytes)
        do
            call self%frames%next(kind, payload, found)
            if (.not. found) exit
            if (kind == frame_ucon_report .and. .not. allocated(self%payload)) then
                call move_alloc(payload, self%payload)
            else
                self%garbled = .true.
            end if
        end do
    end subroutine receive_report

    !> The report of a child that finished: the one whole frame it sent, unpacked.
    subroutine take_report(receiver, request, ucon, error)
        type(report_receiver_type), intent(inout) :: receiver
        type(ucon_request_type), intent(in) :: request
        type(ucon_report_type), intent(out) :: ucon
        type(error_type), allocatable, intent(out) :: error

        if (.not. allocated(receiver%payload) .or. receiver%garbled) then
            call fatal_error(error, "UCON/" // to_text(request%id) // ": the checking " &
                & // "process finished without handing back one whole report", stat_io)
            return
        end if
        call unpack_ucon_report(receiver%payload, ucon, error)
        if (allocated(error)) then
            error%message = "UCON/" // to_text(request%id) // ": " // error%message
        else if (ucon%id /= request%id) then
            call fatal_error(error, "UCON/" // to_text(request%id) // ": the checking " &
                & // "process handed back the report of UCON/" // to_text(ucon%id), stat_io)
        end if
    end subroutine take_report

    !> The report of a UCON whose child ended abnormally: one finding saying how and where.
    subroutine fault_report(request, outcome, stderr_excerpt, ucon)
        type(ucon_request_type), intent(in) :: request
        type(isolation_outcome_type), intent(in) :: outcome
        character(len=*), intent(in) :: stderr_excerpt
        type(ucon_report_type), intent(out) :: ucon
        type(finding_group_type) :: group
        integer :: code

        select case (outcome%kind)
        case (outcome_signal)
            code = rule_signal
        case (outcome_timeout)
            code = rule_timeout
        case default
            code = rule_exit
        end select
        ucon%id = request%id
        ucon%par = request%par
        group = finding(code, "call", outcome_text(outcome) // stderr_excerpt)
        associate (record => outcome%record)
            group%state = int(record%stage)
            group%states = [group%state]
            group%time = real(record%time, wp)
            group%q = real(record%q(:max(0, min(int(record%nq), 30))), wp)
            ! The state reached: the check's states before it were done.
            ucon%states = max(0, group%state)
        end associate
        ucon%groups = [group]
    end subroutine fault_report

    !> Delete a file if it exists.
    subroutine remove_file(path)
        character(len=*), intent(in) :: path
        integer :: unit, stat

        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete", iostat=stat)
    end subroutine remove_file

end module rollcon_isolated_audit
