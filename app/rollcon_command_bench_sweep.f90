! SPDX-License-Identifier: MIT
!> `rollcon bench sweep`: the wall time of one study on 1 process and under mpirun on 2 and 3
!> ranks (a coordinator and 1 or 2 workers), its parallel efficiency per worker, and what the
!> measurements say of a study at scale (docs/studies.md). A benchmark, not a test: run it on
!> a quiet machine.
module rollcon_command_bench_sweep
    use, intrinsic :: iso_fortran_env, only : output_unit, int64
    use rollcon, only : wp, error_type, fatal_error, stat_io, to_text, study_type, read_study, &
        & case_count
    use rollcon_program, only : machine_name, time_sweep, coordinator_row_us
    use rollcon_cli, only : cli_request_type
    implicit none
    private

    public :: bench_sweep_command

    !> Cases of the study at scale the note works out
    real(wp), parameter :: cases_at_scale = 1.0e6_wp

contains

    !> Time the study on each rank count, write DIR/sweep_scaling.csv and print the table and
    !> the note at scale.
    subroutine bench_sweep_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: study_path, output_dir, program, folder
        type(study_type) :: study
        integer, parameter :: ranks(3) = [1, 2, 3]
        real(wp) :: wall(size(ranks)), bytes_per_case
        integer :: k, unit, stat, row_us

        if (request%has("--help")) then
            call print_help()
            return
        end if
        study_path = request%text("--study", "data/bench_sweep.nml")
        output_dir = request%text("--output", "output/bench_sweep")
        call read_study(study_path, study, error)
        if (allocated(error)) return
        call get_program(program)
        write(output_unit, "(a)") "bench sweep: " // machine_name() // "; " // study_path &
            & // ", " // to_text(case_count(study)) // " cases"
        do k = 1, size(ranks)
            folder = output_dir // "/ranks" // to_text(ranks(k))
            call time_sweep(program, study, study_path, folder, ranks(k), wall(k), &
                & bytes_per_case, error)
            if (allocated(error)) return
            write(output_unit, "(a)") "  " // to_text(ranks(k)) // " rank(s), " &
                & // to_text(max(ranks(k) - 1, 1)) // " computing: " // fixed(wall(k), 1) &
                & // " s wall"
        end do
        open(newunit=unit, file=output_dir // "/sweep_scaling.csv", status="replace", &
            & action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // "/sweep_scaling.csv: cannot write", stat_io)
            return
        end if
        write(unit, "(a)") "ranks,computing_ranks,cases,wall_s,speedup,efficiency"
        do k = 1, size(ranks)
            associate (workers => max(ranks(k) - 1, 1))
                write(unit, "(a)") to_text(ranks(k)) // "," // to_text(workers) // "," &
                    & // to_text(case_count(study)) // "," // fixed(wall(k), 2) // "," &
                    & // fixed(wall(1)/wall(k), 3) // "," // fixed(wall(1)/(workers*wall(k)), 3)
            end associate
        end do
        close(unit)
        row_us = coordinator_row_us(output_dir // "/ranks3.log")
        call print_at_scale(study, wall, bytes_per_case, row_us)
        write(output_unit, "(a)") "bench sweep: wrote " // output_dir // "/sweep_scaling.csv"
    end subroutine bench_sweep_command


    !> Cases per hour per core, bytes per case, the coordinator's CPU per row, and a study of
    !> 1e6 cases.
    subroutine print_at_scale(study, wall, bytes_per_case, row_us)
        type(study_type), intent(in) :: study
        real(wp), intent(in) :: wall(:), bytes_per_case
        !> The coordinator's CPU time per row [us] (rollcon sweep's closing line), 0 if unknown
        integer, intent(in) :: row_us
        real(wp) :: per_hour, core_hours

        per_hour = real(case_count(study), wp)/wall(1)*3600.0_wp
        core_hours = cases_at_scale/per_hour
        write(output_unit, "(a)") "  at scale: " // to_text(nint(per_hour)) // " cases per " &
            & // "hour per core; " // to_text(nint(bytes_per_case)) // " bytes of CSV per case; " &
            & // "efficiency on 2 workers " // fixed(wall(1)/(2.0_wp*wall(3)), 2), &
            & "  1e6 such cases: " // fixed(core_hours, 1) // " core-hours, " &
            & // to_text(nint(cases_at_scale*bytes_per_case/1.0e6_wp)) // " MB of CSV; on 128 " &
            & // "workers (129 ranks) " // fixed(60.0_wp*core_hours/128.0_wp/ &
            & (wall(1)/(2.0_wp*wall(3))), 1) // " min at the efficiency measured on 2", &
            & "  the coordinator spent " // to_text(row_us) // " us of CPU a row on messages " &
            & // "and rows: one coordinator serves up to " // to_text(nint(1.0e6_wp/ &
            & max(row_us, 1))) // " rows/s; 128 workers ask " // to_text(nint(128.0_wp*per_hour &
            & /3600.0_wp)) // " rows/s"
    end subroutine print_at_scale


    subroutine print_help()
        write(output_unit, "(a)") "usage: rollcon bench sweep [--study FILE] [--output DIR]", "", &
            & "Time a study (default data/bench_sweep.nml, about a minute on one core) on 1 " &
            & // "process,", "and under mpirun on 2 and 3 ranks (a coordinator and 1 or 2 " &
            & // "workers). Writes", "DIR/sweep_scaling.csv (default DIR output/bench_sweep): " &
            & // "wall time, speedup and efficiency", "per computing rank; prints cases per " &
            & // "hour per core, CSV bytes per case and what", "a study of 1e6 cases needs. Run " &
            & // "it on a quiet machine."
    end subroutine print_help

    !> This program's own path, to run it again.
    subroutine get_program(program)
        character(len=:), allocatable, intent(out) :: program
        integer :: length

        ! whole, however long: a cut path would run another program, or none
        call get_command_argument(0, length=length)
        allocate(character(len=length) :: program)
        call get_command_argument(0, program)
    end subroutine get_program


    !> value with `digits` decimals.
    function fixed(value, digits) result(text)
        real(wp), intent(in) :: value
        integer, intent(in) :: digits
        character(len=:), allocatable :: text
        character(len=32) :: buffer

        write(buffer, "(f32." // to_text(digits) // ")") value
        text = trim(adjustl(buffer))
    end function fixed

end module rollcon_command_bench_sweep
