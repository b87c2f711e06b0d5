! SPDX-License-Identifier: MIT
!> `rollcon plot` and `rollcon animate`: the PNG figures and the animated GIF of a run's CSV,
!> drawn by gnuplot, beside the CSV unless --output names another folder.
module rollcon_command_plot
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : error_type, to_text, plot_output, animate_output
    use rollcon_cli, only : cli_request_type
    use rollcon_app_files, only : make_folder, file_stem, folder_of, csv_argument
    implicit none
    private

    public :: plot_command, animate_command, pictures_of

contains

    !> The CSV the command names (a CSV, or a scene, dataset or command file meaning the CSV
    !> its run wrote, output/<name>.csv: rollcon_app_files' csv_argument) and the
    !> folder for its pictures (--output, else the CSV's own folder), made when missing.
    subroutine pictures_of(request, csv_path, folder, error)
        type(cli_request_type), intent(in) :: request
        character(len=:), allocatable, intent(out) :: csv_path, folder
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: argument

        argument = request%positional
        if (len(argument) == 0) argument = "coin"
        call csv_argument(argument, request%text("--output", "output"), csv_path, error)
        if (allocated(error)) return
        folder = request%text("--output", folder_of(csv_path))
        call make_folder(folder, error)
    end subroutine pictures_of

    !> Draw the figures of a CSV and list the files written.
    subroutine plot_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: csv_path, folder, files(:)
        integer :: i

        call pictures_of(request, csv_path, folder, error)
        if (allocated(error)) return
        call plot_output(csv_path, folder, error, files)
        if (allocated(error)) return
        do i = 1, size(files)
            write(output_unit, '(a)') "plot: wrote " // trim(files(i))
        end do
    end subroutine plot_command

    !> Draw FOLDER/<base>.gif from a CSV, <base> its file name less '.csv'.
    subroutine animate_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: csv_path, folder, gif_path
        integer :: frames

        call pictures_of(request, csv_path, folder, error)
        if (allocated(error)) return
        gif_path = folder // "/" // file_stem(csv_path, ".csv") // ".gif"
        call animate_output(csv_path, gif_path, frames, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "animate: wrote " // gif_path // " (" // to_text(frames) &
            & // " frames)"
    end subroutine animate_command

end module rollcon_command_plot
