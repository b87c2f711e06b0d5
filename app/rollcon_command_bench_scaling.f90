! SPDX-License-Identifier: MIT
!> `rollcon bench scaling`: the CPU time per step and per part of N independent rolling disks
!> and of a chain of N links, N = 1, 2, 4, ..., 64, on IDA, CVODE's ODE form and the
!> independent speeds, dense and sparse, and CVODE's ODE form by fixed-point iteration, as
!> ratios to N = 1's, the start-up of each run and its memory per part; the chain on the sparse
!> Newton matrix also at 128, 256 and 640 links (docs/benchmark.md "Cost as models grow").
!> A benchmark, not a test.
module rollcon_command_bench_scaling
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, fatal_error, stat_io, to_text
    use rollcon_program, only : machine_name, make_folders, scaling_row_type, measure_scaling, &
        & scaling_header, scaling_csv_row, scaling_table, check_scaling_end_time, &
        & long_chain_methods
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
        !> The long chains, on the sparse Newton matrix only (N = 1 again: their ratios' base)
        integer, parameter :: long_counts(4) = [1, 128, 256, 640]
        type(scaling_row_type), allocatable :: rows(:), long_rows(:)
        character(len=:), allocatable :: output_dir
        real(wp) :: end_time
        integer :: k, unit, stat

        if (request%has("--help")) then
            call print_help()
            return
        end if
        output_dir = request%text("--output", "output/bench_scaling")
        call request%real_value("--end-time", end_time, 2.0_wp, error)
        if (allocated(error)) return
        ! before the folder is made or anything printed
        call check_scaling_end_time(end_time, error)
        if (allocated(error)) return
        call make_folders(output_dir, error)
        if (allocated(error)) return
        write(output_unit, "(a)") "bench scaling: " // machine_name() // "; N disks, " &
            & // to_text(end_time) // " s; a chain of N links, a tenth of that; rtol 1e-8, " &
            & // "atol 1e-10"
        call measure_scaling(output_dir, counts, end_time, rows, error)
        if (allocated(error)) return
        call measure_scaling(output_dir, long_counts, end_time, long_rows, error, &
            & long_chain_methods())
        if (allocated(error)) return
        rows = [rows, long_rows]
        open(newunit=unit, file=output_dir // "/scaling.csv", status="replace", &
            & action="write", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // "/scaling.csv: cannot write", stat_io)
            return
        end if
        write(unit, "(a)") scaling_header()
        do k = 1, size(rows)
            write(unit, "(a)") scaling_csv_row(rows(k))
        end do
        close(unit)
        write(output_unit, "(a)", advance="no") scaling_table(rows)
        write(output_unit, "(a)") "bench scaling: wrote " // output_dir // "/scaling.csv"
    end subroutine bench_scaling_command

    subroutine print_help()
        write(output_unit, "(a)") &
            & "usage: rollcon bench scaling [--end-time T] [--output DIR]", &
            & "", &
            & "Cost as models grow. N independent rolling disks (the tipping coin's start,", &
            & "each its own part with its three rolling UCONs, 0.5 m apart) and a chain of", &
            & "N links hinged by REVOLUTE joints (a many-link pendulum falling from 60", &
            & "degrees), N = 1, 2, 4, ..., 64, each a dataset run to T [s] (default 2, from", &
            & "1e-8 to 1e9; the chain to T/10; output every 0.1 s, or T when shorter) on the", &
            & "default (IDA, the Newton matrix chosen by size), IDA,", &
            & "CVODE Adams with Baumgarte terms and, on the disks, CVODE Adams in", &
            & "independent speeds, each with the dense and the sparse Newton matrix (KLU),", &
            & "and CVODE Adams with fixed-point iteration (no Newton matrix; on the chain", &
            & "in independent speeds too) (rtol 1e-8, atol 1e-10): the CPU time of the", &
            & "integration per step and per part [us], its ratio to N = 1's, and the CPU", &
            & "time of the rest of the run [ms] (reading, building, initial conditions),", &
            & "the peak resident memory [MB] and the run's memory per part [kB] (the peak", &
            & "over what the process held before the run; Linux's VmHWM). The chain on the", &
            & "default and on IDA with KLU runs to 128, 256 and 640 links too.", &
            & "Writes the datasets and DIR/scaling.csv (default output/bench_scaling). A", &
            & "benchmark: run it on a quiet machine."
    end subroutine print_help

end module rollcon_command_bench_scaling
