! SPDX-License-Identifier: MIT
!> `rollcon plot`: the PNG figures of a run's output CSV, drawn by gnuplot.
module rollcon_command_plot
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : error_type, fatal_error, stat_io, plot_output
    implicit none
    private

    public :: plot_command, csv_argument, make_folder

contains

    !> Draw the figures of a CSV into output_dir and list the files written.
    subroutine plot_command(argument, output_dir, error)
        !> A CSV file, or a scene name meaning output_dir/<name>.csv
        character(len=*), intent(in) :: argument
        !> Folder for the PNG files (created if missing)
        character(len=*), intent(in) :: output_dir
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: csv_path, files(:)
        integer :: i

        call make_folder(output_dir, error)
        if (allocated(error)) return
        csv_path = csv_argument(argument, output_dir)
        call plot_output(csv_path, output_dir, error, files)
        if (allocated(error)) return
        do i = 1, size(files)
            write(output_unit, '(a)') "plot: wrote " // trim(files(i))
        end do
    end subroutine plot_command

    !> The CSV an argument names: itself when it ends in '.csv', else output_dir/<name>.csv
    !> (so `rollcon plot coin` plots the coin's run).
    pure function csv_argument(argument, output_dir) result(path)
        !> Command-line argument, and the output folder
        character(len=*), intent(in) :: argument, output_dir
        character(len=:), allocatable :: path

        path = output_dir // "/" // argument // ".csv"
        if (len(argument) >= 4) then
            if (argument(len(argument) - 3:) == ".csv") path = argument
        end if
    end function csv_argument

    !> Create a folder and its parents, if missing.
    subroutine make_folder(folder, error)
        !> Folder to create; a name holding a single quote is refused
        character(len=*), intent(in) :: folder
        type(error_type), allocatable, intent(out) :: error
        integer :: stat, command_stat

        stat = 1
        command_stat = 1
        if (index(folder, "'") == 0) then
            call execute_command_line("mkdir -p '" // folder // "'", exitstat=stat, &
                & cmdstat=command_stat)
        end if
        if (stat /= 0 .or. command_stat /= 0) call fatal_error(error, folder &
            & // ": cannot create the output folder", stat_io)
    end subroutine make_folder

end module rollcon_command_plot
