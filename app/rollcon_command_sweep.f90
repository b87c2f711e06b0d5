! SPDX-License-Identifier: MIT
!> `rollcon sweep STUDY.nml [--output DIR] [--quiet]`: run a parameter study (docs/studies.md)
!> on one process or under mpirun, writing DIR/STUDY.csv as cases end, then its map. Part of
!> the program rollcon-sweep (app/rollcon_sweep_main.f90), the one that links Open MPI.
module rollcon_command_sweep
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use mpi_f08, only : MPI_Init, MPI_Finalize, MPI_Bcast, MPI_INTEGER, MPI_COMM_WORLD
    use rollcon, only : wp, error_type, fatal_error, stat_input, to_text, study_type, &
        & read_study, study_plan_type, study_progress_type, plan_cases, plan_study, case_count, &
        & draw_study_map, file_lock_type, lock_study_csv, prepare_study_routines, user_file_type
    use rollcon_program, only : check_at_start, default_call_timeout
    use rollcon_command_run, only : call_timeout_of
    use rollcon_cli, only : cli_request_type
    use rollcon_app_files, only : make_folder
    use rollcon_sweep_mpi, only : sweep_ranks, rank_of_world, size_of_world
    use rollcon_sweep_help, only : print_sweep_help
    implicit none
    private

    public :: sweep_command

contains

    !> Run the study the command names. error is set on rank 0 only, and only rank 0's status
    !> says whether the study ran: the other ranks return status 0 always. A worker that
    !> exited 1 first would let mpirun end the job, and so rank 0, before rank 0 had written
    !> its message (the job's exit status is non-zero when rank 0's is).
    subroutine sweep_command(request, status, error)
        type(cli_request_type), intent(in) :: request
        !> 0 when every case of the study is in the CSV, 1 otherwise
        integer, intent(out) :: status
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: study_path, output_dir, csv_path
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(study_progress_type) :: progress
        type(file_lock_type) :: lock
        logical :: quiet, map
        integer :: go, rank, k

        status = 0
        if (request%has("--help")) then
            call print_sweep_help()
            return
        end if
        status = 1
        study_path = request%positional
        output_dir = request%text("--output", "output")
        quiet = request%has("--quiet")
        map = .not. request%has("--no-map")
        if (len(study_path) == 0) then
            call fatal_error(error, "sweep: give a study file (data/upright_stability.nml, for " &
                & // "one); run 'rollcon sweep --help'", stat_input)
            return
        end if
        call make_folder(output_dir, error)
        if (allocated(error)) return
        call MPI_Init()
        rank = rank_of_world()
        call read_study(study_path, study, error)
        if (.not. allocated(error)) then
            ! every case's routines, as rollcon run takes them
            allocate(study%routines(request%count("--ucosub")))
            do k = 1, size(study%routines)
                study%routines(k)%path = request%nth("--ucosub", k)
            end do
            study%call_timeout = real(default_call_timeout, wp)
            call call_timeout_of(request, study%call_timeout, error)
            if (.not. request%has("--no-check")) study%start_check => check_at_start
        end if
        if (.not. allocated(error)) then
            csv_path = output_dir // "/" // study%name // ".csv"
            if (rank == 0) then
                ! one sweep at a time into a CSV: held until this process ends
                call lock_study_csv(csv_path, lock, error)
                ! a user's files compiled once, before any case: the cache serves every rank
                if (.not. allocated(error)) call prepare_study_routines(study, error)
                if (.not. allocated(error)) call plan_study(study, csv_path, plan, error)
            else
                call plan_cases(study, plan)
            end if
        end if
        go = merge(1, 0, .not. allocated(error))
        call MPI_Bcast(go, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
        if (go == 1) then
            if (rank == 0) call announce(study, plan, csv_path, quiet, progress)
            call sweep_ranks(study, csv_path, plan, progress, error)
        end if
        call MPI_Finalize()
        if (rank /= 0) then
            if (allocated(error)) deallocate(error)
            status = 0
            return
        end if
        if (go == 0 .and. .not. allocated(error)) call fatal_error(error, "the study " &
            & // study_path // " could not start on every rank", stat_input)
        if (.not. allocated(error)) call finish_sweep(study, plan, study_path, csv_path, &
            & output_dir, quiet, map, progress, status, error)
        ! the CSV's lock goes (with its file) once the map has read the CSV
        call lock%release()
    end subroutine sweep_command

    !> After the cases: the closing lines, and the map. status 0 when every case is in the CSV
    !> (and some case was not refused) and the map, when asked for, is drawn.
    subroutine finish_sweep(study, plan, study_path, csv_path, output_dir, quiet, map, &
            & progress, status, error)
        type(study_type), intent(in) :: study
        type(study_plan_type), intent(in) :: plan
        character(len=*), intent(in) :: study_path, csv_path, output_dir
        logical, intent(in) :: quiet, map
        type(study_progress_type), intent(in) :: progress
        integer, intent(inout) :: status
        type(error_type), allocatable, intent(out) :: error

        call close_study(study, plan, csv_path, progress)
        ! nothing of what was asked ran: a mistake in the study, not a result
        if (progress%refused > 0 .and. progress%refused == case_count(study)) then
            call fatal_error(error, "every case of " // study_path // " was refused: its " &
                & // "parameters do not make a scene that reads (the messages are in " &
                & // csv_path // ")", stat_input)
            return
        end if
        if (map .and. study%map%x == 0 .and. .not. quiet) write(output_unit, "(a)") "sweep: no " &
            & // "map: the study varies one parameter, a map needs two"
        if (map .and. study%map%x > 0) then
            call draw_study_map(study, csv_path, output_dir // "/" // study%name // ".png", &
                & error)
            if (allocated(error)) return
            if (.not. quiet) write(output_unit, "(a)") "sweep: map " // output_dir // "/" &
                & // study%name // ".png"
        end if
        status = 0
    end subroutine finish_sweep

    !> The opening line: cases, those already done, ranks.
    subroutine announce(study, plan, csv_path, quiet, progress)
        type(study_type), intent(in) :: study
        type(study_plan_type), intent(in) :: plan
        character(len=*), intent(in) :: csv_path
        logical, intent(in) :: quiet
        type(study_progress_type), intent(inout) :: progress
        integer :: done, ranks

        done = count(plan%done)
        ranks = size_of_world()
        call progress%start(case_count(study), done, quiet)
        if (quiet) return
        write(output_unit, "(a)") "sweep: " // study%path // ": " // to_text(case_count(study)) &
            & // " cases, " // to_text(done) // " of them in " // csv_path // " already; " &
            & // trim(rank_text(ranks))
        flush(output_unit)
    end subroutine announce

    pure function rank_text(ranks) result(text)
        integer, intent(in) :: ranks
        character(len=:), allocatable :: text

        if (ranks == 1) then
            text = "1 process runs them"
        else
            text = to_text(ranks) // " ranks: a coordinator and " // to_text(ranks - 1) &
                & // " workers"
        end if
    end function rank_text

    !> The closing lines: what ran, what the CSV holds.
    subroutine close_study(study, plan, csv_path, progress)
        type(study_type), intent(in) :: study
        type(study_plan_type), intent(in) :: plan
        character(len=*), intent(in) :: csv_path
        type(study_progress_type), intent(in) :: progress

        write(output_unit, "(a)") "sweep: " // to_text(progress%done) // " cases run now (" &
            & // to_text(progress%failed) // " failed, " // to_text(progress%refused) &
            & // " refused), " // to_text(progress%skipped) // " from an earlier run: all " &
            & // to_text(case_count(study)) // " in " // csv_path
        if (progress%coordinator_cpu > 0.0_wp .and. progress%done > 0) write(output_unit, "(a)") &
            & "sweep: the coordinator spent " // to_text(real(nint(progress%coordinator_cpu &
            & *1.0e3_wp), wp)/1.0e3_wp) // " s of CPU on messages and rows, " &
            & // to_text(nint(1.0e6_wp*progress%coordinator_cpu/progress%done)) // " us a row"
        if (plan%foreign > 0) write(output_unit, "(a)") "sweep: " // csv_path // " also holds " &
            & // to_text(plan%foreign) // " rows that are not cases of " // study%path &
            & // " (the study changed); they are kept"
    end subroutine close_study

end module rollcon_command_sweep
