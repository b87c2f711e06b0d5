! SPDX-License-Identifier: MIT
!> The study benchmark's measurement (`rollcon bench sweep`): a study run as `rollcon sweep`
!> in a process of its own, on one process or under mpirun, timed whole (wall time), with the
!> CSV's size per case and the coordinator's CPU per row from its log.
module rollcon_bench_sweep
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text, shell_quote
    use rollcon_study_type, only : study_type
    use rollcon_study_parameters, only : case_count
    implicit none
    private

    public :: time_sweep, coordinator_row_us

contains

    !> Run the study on `ranks` ranks (1: no mpirun) into folder; wall time [s], and the CSV's
    !> bytes per case. Every case must be in the CSV.
    subroutine time_sweep(program, study, study_path, folder, ranks, wall, bytes_per_case, &
            & error)
        character(len=*), intent(in) :: program, study_path, folder
        type(study_type), intent(in) :: study
        integer, intent(in) :: ranks
        real(wp), intent(out) :: wall, bytes_per_case
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: command, csv
        integer(int64) :: start, finish, rate
        integer :: status, bytes, lines

        csv = folder // "/" // study%name // ".csv"
        command = shell_quote(program) // " sweep " // shell_quote(study_path) // " --quiet " &
            & // "--no-map --output " // shell_quote(folder) // " > " // shell_quote(folder &
            & // ".log") // " 2>&1"
        if (ranks > 1) command = "mpirun --oversubscribe -np " // to_text(ranks) // " " // command
        call execute_command_line("rm -rf " // shell_quote(folder) // " && mkdir -p " &
            & // shell_quote(folder), exitstat=status)
        call system_clock(start, rate)
        call execute_command_line(command, exitstat=status)
        call system_clock(finish)
        wall = real(finish - start, wp)/real(rate, wp)
        lines = line_count(csv)
        if (status /= 0 .or. lines /= case_count(study) + 1) then
            call fatal_error(error, "bench sweep: the run on " // to_text(ranks) // " rank(s) " &
                & // "did not complete (exit status " // to_text(status) // ", " &
                & // to_text(lines - 1) // " rows): see " // folder // ".log", stat_io)
            return
        end if
        inquire(file=csv, size=bytes)
        bytes_per_case = real(bytes, wp)/real(case_count(study), wp)
    end subroutine time_sweep

    !> The coordinator's microseconds of CPU a row, from the closing line of a sweep's log.
    integer function coordinator_row_us(log) result(us)
        character(len=*), intent(in) :: log
        character(len=512) :: line
        integer :: unit, stat, cut, start

        us = 0
        open(newunit=unit, file=log, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        do
            read(unit, "(a)", iostat=stat) line
            if (stat /= 0) exit
            cut = index(line, " us a row")
            if (cut == 0) cycle
            start = index(line(:cut - 1), " ", back=.true.)
            read(line(start + 1:cut - 1), *, iostat=stat) us
        end do
        close(unit)
    end function coordinator_row_us

    !> Lines of a text file (0 when it is missing).
    integer function line_count(path) result(lines)
        character(len=*), intent(in) :: path
        character(len=16) :: head
        integer :: unit, stat

        lines = 0
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        do
            read(unit, "(a)", iostat=stat) head
            if (stat /= 0) exit
            lines = lines + 1
        end do
        close(unit)
    end function line_count

end module rollcon_bench_sweep
