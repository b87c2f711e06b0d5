! SPDX-License-Identifier: MIT
!> A job's linear analysis when its routine is a user's file (docs/linear.md): as a run apart
!> (rollcon_isolated_run), the routine never runs in this process. This process compiles the
!> files into the cache; a child process loads them, builds the model with every call guarded
!> and timed, makes the start consistent, checks the routine there when the job asks, and
!> linearises (rollcon_linearisation) or tabulates the eigenvalues against speed
!> (rollcon_linear_speeds) with the routine's own partials, as a run's Newton matrices use
!> them. The child sends the report of the start and the result on its pipe (rollcon_frames);
!> every field read back is the one computed. A routine that crashes, overruns a call or stops
!> ends the child, and the message names the call, as a run's does.
module rollcon_isolated_linear
    use, intrinsic :: iso_c_binding, only : c_double
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_wire, only : wire_writer_type, wire_reader_type
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_summary_type
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type, speed_table, &
        & stability_changes
    use rollcon_child_process, only : isolated_task_type, stream_receiver_type, &
        & call_record_type, isolation_outcome_type, run_in_child, outcome_finished
    use rollcon_frames, only : send_frame, frame_buffer_type
    use rollcon_isolation_text, only : outcome_text, scratch_path
    use rollcon_job, only : job_type, user_file_type
    use rollcon_isolated_run, only : compile_user_files, build_apart, hand_on_stderr, &
        & defined_text
    implicit none
    private

    public :: linearise_apart, linear_speeds_apart
    public :: pack_linear_result, unpack_linear_result, pack_speed_table, unpack_speed_table

    !> Kinds of frame the child sends: the start's report, what the user's files define (for
    !> the record, as a run's child sends it), then the result
    integer, parameter :: frame_report = 1, frame_result = 2, frame_defined = 3
    !> What the child computes: the eigenvalues at the start, or against speed
    integer, parameter :: work_linear = 1, work_speeds = 2

    !> The child's work
    type, extends(isolated_task_type) :: linear_task_type
        type(job_type) :: job
        integer :: work = work_linear
        type(linear_options_type) :: options
        !> The speeds of work_speeds [m/s]
        real(wp), allocatable :: speeds(:)
        !> The shared libraries built from the job's files (rollcon_isolated_run)
        character(len=:), allocatable :: library
        type(user_file_type), allocatable :: more_libraries(:)
    contains
        procedure :: run => run_linear_task
    end type linear_task_type

    !> In this process: what the child sent
    type, extends(stream_receiver_type) :: linear_receiver_type
        type(frame_buffer_type) :: frames
        character(len=:), allocatable :: report, result
        !> What the user's files define (rollcon_isolated_run's defined_text), once sent
        character(len=:), allocatable :: defined
        logical :: has_result = .false.
        !> A frame of a kind the child does not send
        logical :: garbled = .false.
    contains
        procedure :: receive
    end type linear_receiver_type

contains

    !> The job's model linearised at its consistent start (t = 0), its routine job%user_file
    !> run in a child process (see the module's header); as rollcon_linear_job's
    !> linearise_job otherwise. report: what making the start consistent changed; defined:
    !> what the user's files define, as the child found them (for the record,
    !> rollcon_provenance's provenance_lines).
    subroutine linearise_apart(job, options, result, report, error, defined)
        type(job_type), intent(in) :: job
        type(linear_options_type), intent(in) :: options
        type(linear_result_type), intent(out) :: result
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable, intent(out) :: defined
        type(linear_task_type) :: task
        type(linear_receiver_type) :: receiver
        type(wire_reader_type) :: wire

        task%work = work_linear
        task%options = options
        allocate(task%speeds(0))
        call run_task_apart(job, task, receiver, report, error)
        if (allocated(error)) return
        if (allocated(receiver%defined)) call move_alloc(receiver%defined, defined)
        wire%bytes = receiver%result
        call unpack_linear_result(wire, result)
        if (wire%failed) call fatal_error(error, "the child process's linear analysis does " &
            & // "not read", stat_ucon)
    end subroutine linearise_apart

    !> The eigenvalues against speed at the job's consistent start (rollcon_linear_speeds'
    !> speed_table and stability_changes), its routine job%user_file run in a child process;
    !> defined as linearise_apart's.
    subroutine linear_speeds_apart(job, speeds, options, table, changes, report, error, &
            & defined)
        type(job_type), intent(in) :: job
        !> Speeds [m/s]
        real(wp), intent(in) :: speeds(:)
        type(linear_options_type), intent(in) :: options
        type(speed_table_type), intent(out) :: table
        type(stability_change_type), allocatable, intent(out) :: changes(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable, intent(out) :: defined
        type(linear_task_type) :: task
        type(linear_receiver_type) :: receiver
        type(wire_reader_type) :: wire

        allocate(changes(0))
        task%work = work_speeds
        task%options = options
        task%speeds = speeds
        call run_task_apart(job, task, receiver, report, error)
        if (allocated(error)) return
        if (allocated(receiver%defined)) call move_alloc(receiver%defined, defined)
        wire%bytes = receiver%result
        call unpack_speed_table(wire, table, changes)
        if (wire%failed) call fatal_error(error, "the child process's eigenvalues against " &
            & // "speed do not read", stat_ucon)
    end subroutine linear_speeds_apart

    !> Compile, run the task in a child with the job's time limit per call, and take what it
    !> sent: the report, and the packed result in receiver%result.
    subroutine run_task_apart(job, task, receiver, report, error)
        type(job_type), intent(in) :: job
        type(linear_task_type), intent(inout) :: task
        type(linear_receiver_type), intent(inout) :: receiver
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(isolation_outcome_type) :: outcome
        type(run_summary_type) :: unused
        character(len=:), allocatable :: stderr_path

        report = ""
        call compile_user_files(job, task%library, task%more_libraries, error)
        if (allocated(error)) return
        task%job = job
        receiver%report = ""
        receiver%result = ""
        stderr_path = scratch_path("linear", 1, ".stderr")
        call run_in_child(task, real(job%call_timeout, c_double), outcome, error, &
            & stderr_path, receiver)
        if (outcome%kind /= outcome_finished .and. .not. allocated(error)) &
            & call fatal_error(error, outcome_text(outcome) // "; the linear analysis did " &
            & // "not complete", stat_ucon)
        unused%message = ""
        call hand_on_stderr(stderr_path, outcome%kind /= outcome_finished, unused, error)
        if (allocated(error)) return
        report = receiver%report
        if (receiver%garbled .or. .not. receiver%has_result) call fatal_error(error, &
            & "the child process of the linear analysis ended without sending its result", &
            & stat_ucon)
    end subroutine run_task_apart

    !> In the child: build as a run apart does (build_apart), then linearise or tabulate, and
    !> send the report, what the user's files define and the result.
    subroutine run_linear_task(self, record, error)
        class(linear_task_type), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(linear_result_type) :: result
        type(speed_table_type) :: table
        type(stability_change_type), allocatable :: changes(:)
        type(wire_writer_type) :: wire
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report

        call build_apart(self%job, self%library, self%more_libraries, record, 0.0_wp, &
            & problem, q0, u0, report, error)
        if (allocated(error)) return
        call send_frame(self%stream_fd, frame_report, report, error)
        if (allocated(error)) return
        call send_frame(self%stream_fd, frame_defined, defined_text(self%job, problem), error)
        if (allocated(error)) return
        if (self%work == work_linear) then
            call linearise(problem, 0.0_wp, q0, u0, self%options, result, error)
            if (allocated(error)) return
            call pack_linear_result(wire, result)
        else
            call speed_table(problem, 0.0_wp, q0, u0, self%speeds, self%options, table, error)
            if (allocated(error)) return
            call stability_changes(problem, 0.0_wp, q0, u0, table, self%options, changes, &
                & error)
            if (allocated(error)) return
            call pack_speed_table(wire, table, changes)
        end if
        call send_frame(self%stream_fd, frame_result, wire%packed(), error)
    end subroutine run_linear_task

    !> Bytes from the child: every whole frame in them taken.
    subroutine receive(self, bytes)
        class(linear_receiver_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        character(len=:), allocatable :: payload
        integer :: kind
        logical :: found

        call self%frames%add(bytes)
        do
            call self%frames%next(kind, payload, found)
            if (.not. found) exit
            select case (kind)
            case (frame_report)
                self%report = payload
            case (frame_defined)
                self%defined = payload
            case (frame_result)
                self%result = payload
                self%has_result = .true.
            case default
                self%garbled = .true.
            end select
        end do
    end subroutine receive

    !> Every field of a linear result.
    subroutine pack_linear_result(wire, result)
        type(wire_writer_type), intent(inout) :: wire
        type(linear_result_type), intent(in) :: result

        call wire%put_real(result%time)
        call wire%put_int(int(result%states, int64))
        call wire%put_int(int(result%reduced, int64))
        call wire%put_reals(reals_of(result%real_part))
        call wire%put_reals(reals_of(result%imag_part))
        call put_matrix(wire, result%reduced_matrix)
        call put_matrix(wire, result%basis)
        call wire%put_ints(ints_of(result%independent))
        call wire%put_real(result%invariance)
        call wire%put_logical(result%invariant)
        call wire%put_real(result%zero_limit)
        call wire%put_int(int(result%zeros, int64))
    end subroutine pack_linear_result

    !> A linear result as pack_linear_result packed it (wire%failed when it does not read).
    subroutine unpack_linear_result(wire, result)
        type(wire_reader_type), intent(inout) :: wire
        type(linear_result_type), intent(out) :: result

        result%time = wire%get_real()
        result%states = int(wire%get_int())
        result%reduced = int(wire%get_int())
        call wire%get_reals(result%real_part)
        call wire%get_reals(result%imag_part)
        call get_matrix(wire, result%reduced_matrix)
        call get_matrix(wire, result%basis)
        call wire%get_ints(result%independent)
        result%invariance = wire%get_real()
        result%invariant = wire%get_logical()
        result%zero_limit = wire%get_real()
        result%zeros = int(wire%get_int())
    end subroutine unpack_linear_result

    !> Every field of the eigenvalues against speed and of the stability changes.
    subroutine pack_speed_table(wire, table, changes)
        type(wire_writer_type), intent(inout) :: wire
        type(speed_table_type), intent(in) :: table
        type(stability_change_type), intent(in) :: changes(:)
        integer :: k

        call wire%put_reals(reals_of(table%speed))
        call put_matrix(wire, table%real_part)
        call put_matrix(wire, table%imag_part)
        if (allocated(table%struck)) then
            call wire%put_logicals(table%struck)
        else
            call wire%put_logicals([logical ::])
        end if
        call wire%put_ints(ints_of(table%independent))
        call wire%put_int(int(table%deflations, int64))
        call wire%put_int(int(size(changes), int64))
        do k = 1, size(changes)
            call wire%put_real(changes(k)%speed)
            call wire%put_logical(changes(k)%oscillatory)
            call wire%put_real(changes(k)%frequency)
            call wire%put_logical(changes(k)%stable_above)
        end do
    end subroutine pack_speed_table

    !> The eigenvalues against speed and the changes as pack_speed_table packed them.
    subroutine unpack_speed_table(wire, table, changes)
        type(wire_reader_type), intent(inout) :: wire
        type(speed_table_type), intent(out) :: table
        type(stability_change_type), allocatable, intent(out) :: changes(:)
        integer(int64) :: count
        integer :: k

        call wire%get_reals(table%speed)
        call get_matrix(wire, table%real_part)
        call get_matrix(wire, table%imag_part)
        call wire%get_logicals(table%struck)
        call wire%get_ints(table%independent)
        table%deflations = int(wire%get_int())
        count = wire%get_int()
        if (count < 0 .or. count > size(table%speed)) then
            wire%failed = .true.
            count = 0
        end if
        allocate(changes(count))
        do k = 1, size(changes)
            changes(k)%speed = wire%get_real()
            changes(k)%oscillatory = wire%get_logical()
            changes(k)%frequency = wire%get_real()
            changes(k)%stable_above = wire%get_logical()
        end do
    end subroutine unpack_speed_table

    !> A matrix: its two extents, then its entries in column order (none when unallocated).
    subroutine put_matrix(wire, matrix)
        type(wire_writer_type), intent(inout) :: wire
        real(wp), allocatable, intent(in) :: matrix(:, :)

        if (.not. allocated(matrix)) then
            call wire%put_ints([0, 0])
            call wire%put_reals([real(wp) ::])
            return
        end if
        call wire%put_ints(shape(matrix))
        call wire%put_reals(reshape(matrix, [size(matrix)]))
    end subroutine put_matrix

    subroutine get_matrix(wire, matrix)
        type(wire_reader_type), intent(inout) :: wire
        real(wp), allocatable, intent(out) :: matrix(:, :)
        integer, allocatable :: extents(:)
        real(wp), allocatable :: entries(:)

        call wire%get_ints(extents)
        call wire%get_reals(entries)
        if (size(extents) /= 2) then
            wire%failed = .true.
        else if (any(extents < 0) .or. product(int(extents, int64)) /= size(entries)) then
            wire%failed = .true.
        end if
        if (wire%failed) then
            allocate(matrix(0, 0))
            return
        end if
        matrix = reshape(entries, [extents(1), extents(2)])
    end subroutine get_matrix

    !> The values, none when unallocated.
    pure function reals_of(values) result(copy)
        real(wp), allocatable, intent(in) :: values(:)
        real(wp), allocatable :: copy(:)

        if (allocated(values)) then
            copy = values
        else
            allocate(copy(0))
        end if
    end function reals_of

    pure function ints_of(values) result(copy)
        integer, allocatable, intent(in) :: values(:)
        integer, allocatable :: copy(:)

        if (allocated(values)) then
            copy = values
        else
            allocate(copy(0))
        end if
    end function ints_of

end module rollcon_isolated_linear
