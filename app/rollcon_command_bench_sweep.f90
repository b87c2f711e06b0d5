! SPDX-License-Identifier: MIT
!> `rollcon bench sweep`: the wall time of one study on 1 process and under mpirun on 2 and 3
!> ranks (a coordinator and 1 or 2 workers), its parallel efficiency per worker, and what the
!> measurements say of a study at scale (docs/studies.md). A benchmark, not a test: run it on
!> a quiet machine.
module rollcon_command_bench_sweep
    use, intrinsic :: iso_fortran_env, only : output_unit, int64
    use rollcon, only : wp, error_type, fatal_error, stat_input, stat_io, to_text, shell_quote, &
        & study_type, read_study, case_count
    use rollcon_command_bench, only : machine_name
    implicit none
    private

    public :: bench_sweep_command

    !> Cases of the study at scale the note works out
    real(wp), parameter :: cases_at_scale = 1.0e6_wp

contains

    !> Parse the arguments after `bench sweep`, time the study on each rank count, write
    !> DIR/sweep_scaling.csv and print the table and the note at scale.
    subroutine bench_sweep_command(first, error)
        integer, intent(in) :: first
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: study_path, output_dir, program, folder
        type(study_type) :: study
        integer, parameter :: ranks(3) = [1, 2, 3]
        real(wp) :: wall(size(ranks)), bytes_per_case
        integer :: k, unit, stat, row_us

        call read_options(first, study_path, output_dir, error)
        if (allocated(error) .or. .not. allocated(study_path)) return
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

    subroutine read_options(first, study_path, output_dir, error)
        integer, intent(in) :: first
        character(len=:), allocatable, intent(out) :: study_path, output_dir
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: argument
        integer :: i

        study_path = "data/bench_sweep.nml"
        output_dir = "output/bench_sweep"
        i = first
        do while (i <= command_argument_count())
            call get_command_argument(i, argument)
            select case (trim(argument))
            case ("-h", "--help")
                write(output_unit, "(a)") "usage: rollcon bench sweep [--study FILE] " &
                    & // "[--output DIR]", "", &
                    & "Time a study (default data/bench_sweep.nml, about a minute on one " &
                    & // "core) on 1 process,", "and under mpirun on 2 and 3 ranks (a " &
                    & // "coordinator and 1 or 2 workers). Writes", "DIR/sweep_scaling.csv " &
                    & // "(default DIR output/bench_sweep): wall time, speedup and efficiency", &
                    & "per computing rank; prints cases per hour per core, CSV bytes per case " &
                    & // "and what", "a study of 1e6 cases needs. Run it on a quiet machine."
                deallocate(study_path)
                return
            case ("--study", "--output", "-o")
                i = i + 1
                if (i > command_argument_count()) then
                    call fatal_error(error, "bench sweep: " // trim(argument) // " needs a " &
                        & // "value", stat_input)
                    return
                end if
                if (trim(argument) == "--study") then
                    call get_command_argument(i, argument)
                    study_path = trim(argument)
                else
                    call get_command_argument(i, argument)
                    output_dir = trim(argument)
                end if
            case default
                call fatal_error(error, "bench sweep: unknown argument '" // trim(argument) &
                    & // "'; run 'rollcon bench sweep --help'", stat_input)
                return
            end select
            i = i + 1
        end do
    end subroutine read_options

    !> This program's own path, to run it again.
    subroutine get_program(program)
        character(len=:), allocatable, intent(out) :: program
        character(len=1024) :: buffer
        integer :: length

        call get_command_argument(0, buffer, length)
        program = buffer(:length)
    end subroutine get_program

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
