! SPDX-License-Identifier: MIT
!> A study's cases handed out over MPI (mpi_f08): rank 0 coordinates, every other rank runs
!> cases. A worker says it is ready, then runs the cases it is sent and sends back each case's
!> CSV row; the coordinator writes each row as it arrives (flushed) and sends the next pending
!> case, keeping each worker one case ahead, or 0 (stop) once the worker holds none and none
!> is left. Cases whose cost differs by 100x then keep every worker busy,
!> and the rows do not depend on the number of ranks (only their order does). Between messages
!> the coordinator sleeps (1 ms polls), so it takes a core only briefly: start it beside as
!> many workers as there are cores (mpirun --oversubscribe -np CORES+1). On one rank, the
!> one process runs every case itself.
module rollcon_sweep_mpi
    use, intrinsic :: iso_c_binding, only : c_int
    use mpi_f08, only : MPI_Comm_rank, MPI_Comm_size, MPI_COMM_WORLD, MPI_Send, MPI_Recv, &
        & MPI_Iprobe, MPI_Status, MPI_INTEGER, MPI_CHARACTER, MPI_ANY_SOURCE, MPI_ANY_TAG
    use rollcon, only : wp, study_type, study_plan_type, study_progress_type, case_result_type, &
        & error_type, run_case, run_study, row_file_type
    implicit none
    private

    public :: sweep_ranks, rank_of_world, size_of_world

    !> Message tags: a worker is free (no data), a case's outcome and row length, the row, a
    !> case to run (0: stop)
    integer, parameter :: tag_ready = 1, tag_result = 2, tag_row = 3, tag_case = 4
    !> Cases a worker holds at most (the one it runs and the next)
    integer, parameter :: queue_depth = 2

    interface
        !> POSIX usleep: the coordinator's pause between polls
        integer(c_int) function usleep(microseconds) bind(c, name="usleep")
            import :: c_int
            integer(c_int), value :: microseconds
        end function usleep
    end interface

contains

    integer function rank_of_world() result(rank)
        call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    end function rank_of_world

    integer function size_of_world() result(ranks)
        call MPI_Comm_size(MPI_COMM_WORLD, ranks)
    end function size_of_world

    !> Run the plan's pending cases on the ranks of MPI_COMM_WORLD (all ranks call this).
    !> error is set on rank 0 only (a row it could not write).
    subroutine sweep_ranks(study, csv_path, plan, progress, error)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: csv_path
        type(study_plan_type), intent(in) :: plan
        type(study_progress_type), intent(inout) :: progress
        type(error_type), allocatable, intent(out) :: error

        if (size_of_world() == 1) then
            call run_study(study, csv_path, plan, progress, error)
        else if (rank_of_world() == 0) then
            call coordinate(csv_path, plan, progress, error)
        else
            call work(study, plan)
        end if
    end subroutine sweep_ranks

    !> Rank 0: hand out the pending cases, write the rows that come back. A worker is kept
    !> `queue_depth` cases ahead (it finds its next case waiting when it sends a row), so the
    !> coordinator's polling adds nothing to a worker's time. The CPU time spent on messages
    !> (receiving, writing the row, sending) goes to progress%coordinator_cpu. If the CSV
    !> cannot be opened or written, no case is handed out (the workers are told to stop) and
    !> error says why.
    subroutine coordinate(csv_path, plan, progress, error)
        character(len=*), intent(in) :: csv_path
        type(study_plan_type), intent(in) :: plan
        type(study_progress_type), intent(inout) :: progress
        type(error_type), allocatable, intent(out) :: error
        type(MPI_Status) :: status
        integer, allocatable :: cases(:), held(:)
        character(len=:), allocatable :: row
        type(row_file_type) :: file
        integer :: next, stopped, header(3), source, dummy, k
        logical :: waiting
        real(wp) :: handling_start, handling_end

        call file%open(csv_path, error, rows_before=plan%rows_in_csv)
        cases = plan%pending()
        next = 1
        stopped = 0
        allocate(held(size_of_world() - 1), source=0)
        do while (stopped < size(held))
            call MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, waiting, status)
            if (.not. waiting) then
                dummy = usleep(1000_c_int)
                cycle
            end if
            call cpu_time(handling_start)
            source = status%MPI_SOURCE
            if (status%MPI_TAG == tag_ready) then
                call MPI_Recv(dummy, 0, MPI_INTEGER, source, tag_ready, MPI_COMM_WORLD, status)
            else
                call MPI_Recv(header, 3, MPI_INTEGER, source, tag_result, MPI_COMM_WORLD, &
                    & status)
                allocate(character(len=header(3)) :: row)
                call MPI_Recv(row, header(3), MPI_CHARACTER, source, tag_row, MPI_COMM_WORLD, &
                    & status)
                held(source) = held(source) - 1
                if (.not. allocated(error)) call file%write(row, error)
                deallocate(row)
                call progress%add(header(2))
            end if
            ! fill the worker's queue; after a write failure no new case is handed out
            do k = held(source) + 1, queue_depth
                if (next > size(cases) .or. allocated(error)) exit
                call MPI_Send(cases(next), 1, MPI_INTEGER, source, tag_case, MPI_COMM_WORLD)
                next = next + 1
                held(source) = held(source) + 1
            end do
            if (held(source) == 0) then
                call MPI_Send(0, 1, MPI_INTEGER, source, tag_case, MPI_COMM_WORLD)
                stopped = stopped + 1
            end if
            call cpu_time(handling_end)
            progress%coordinator_cpu = progress%coordinator_cpu + handling_end - handling_start
        end do
        if (allocated(error)) then
            call file%close()
        else
            call file%close(error)
        end if
    end subroutine coordinate

    !> A worker rank: ask for cases, run them, send their rows, until told to stop.
    subroutine work(study, plan)
        type(study_type), intent(in) :: study
        type(study_plan_type), intent(in) :: plan
        type(MPI_Status) :: status
        type(case_result_type) :: result
        character(len=:), allocatable :: row
        integer :: i, dummy

        dummy = 0
        call MPI_Send(dummy, 0, MPI_INTEGER, 0, tag_ready, MPI_COMM_WORLD)
        do
            call MPI_Recv(i, 1, MPI_INTEGER, 0, tag_case, MPI_COMM_WORLD, status)
            if (i == 0) exit
            call run_case(study, plan, i, row, result)
            call MPI_Send([i, result%outcome, len(row)], 3, MPI_INTEGER, 0, tag_result, &
                & MPI_COMM_WORLD)
            call MPI_Send(row, len(row), MPI_CHARACTER, 0, tag_row, MPI_COMM_WORLD)
        end do
    end subroutine work

end module rollcon_sweep_mpi
