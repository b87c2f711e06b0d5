! SPDX-License-Identifier: MIT
!> `rollcon bench scaling`: the CPU time per step and per part of N independent rolling disks,
!> N = 1, 2, 4, ..., 64, on IDA, CVODE's ODE form and the independent speeds, as ratios to
!> N = 1's (docs/benchmark.md "Cost as models grow"). A benchmark, not a test.
module rollcon_command_bench_scaling
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, fatal_error, stat_io, to_text, machine_name, &
        & make_folders, scaling_row_type, measure_scaling, scaling_header, scaling_csv_row
    use rollcon_cli, only : cli_request_type
    implicit none
    private

    public :: bench_scaling_command

contains

    !> Measure, write DIR/scaling.csv and print the table.
    subroutine bench_scaling_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: counts(7) = [1, 2, 4, 8, 16, 32, 64]
        type(scaling_row_type), allocatable :: rows(:)
        character(len=:), allocatable :: output_dir
        character(len=16) :: cell
        real(wp) :: end_time
        integer :: k, unit, stat

        if (request%has("--help")) then
            call print_help()
            return
        end if
        output_dir = request%text("--output", "output/bench_scaling")
        call request%real_value("--end-time", end_time, 2.0_wp, error)
        if (allocated(error)) return
        call make_folders(output_dir, error)
        if (allocated(error)) return
        write(output_unit, "(a)") "bench scaling: " // machine_name() // "; N disks, " &
            & // to_text(end_time) // " s, rtol 1e-8, atol 1e-10"
        call measure_scaling(output_dir, counts, end_time, rows, error)
        if (allocated(error)) return
        open(newunit=unit, file=output_dir // "/scaling.csv", status="replace", &
            & action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // "/scaling.csv: cannot write", stat_io)
            return
        end if
        write(unit, "(a)") scaling_header()
        write(output_unit, "(a)") "  method                    N   states   steps  " &
            & // "us/step/part  ratio to N = 1"
        do k = 1, size(rows)
            write(unit, "(a)") scaling_csv_row(rows(k))
            write(cell, "(f12.2)") rows(k)%per_step_part
            write(output_unit, "(2x, a24, i4, i9, i8, a14, f10.2, 2x, a)") rows(k)%method, &
                & rows(k)%parts, rows(k)%states, rows(k)%steps, cell, rows(k)%ratio, &
                & trim(rows(k)%status)
        end do
        close(unit)
        write(output_unit, "(a)") "bench scaling: wrote " // output_dir // "/scaling.csv"
    end subroutine bench_scaling_command

    subroutine print_help()
        write(output_unit, "(a)") &
            & "usage: rollcon bench scaling [--end-time T] [--output DIR]", &
            & "", &
            & "Cost as models grow. N independent rolling disks (the tipping coin's start,", &
            & "each its own part with its three rolling UCONs, 0.5 m apart), N = 1, 2, 4,", &
            & "..., 64, each a dataset run to T [s] (default 2) on IDA, CVODE Adams with", &
            & "Baumgarte terms and CVODE Adams in independent speeds, the two CVODE ones", &
            & "also with the sparse Newton matrix (KLU) (rtol 1e-8, atol 1e-10): the CPU", &
            & "time of the integration per step and per part [us] and its", &
            & "ratio to N = 1's. Writes the datasets and DIR/scaling.csv (default", &
            & "output/bench_scaling). A benchmark: run it on a quiet machine."
    end subroutine print_help

end module rollcon_command_bench_scaling
