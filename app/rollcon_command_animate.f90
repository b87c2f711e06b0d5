! SPDX-License-Identifier: MIT
!> `rollcon animate`: an animated GIF of a run's output CSV, drawn headlessly by gnuplot.
module rollcon_command_animate
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : error_type, to_text, base_name, animate_output
    use rollcon_command_plot, only : csv_argument, make_folder
    implicit none
    private

    public :: animate_command

contains

    !> Draw output_dir/<base>.gif from a CSV, <base> its file name less '.csv'.
    subroutine animate_command(argument, output_dir, error)
        !> A CSV file, or a scene name meaning output_dir/<name>.csv
        character(len=*), intent(in) :: argument
        !> Folder for the GIF (created if missing)
        character(len=*), intent(in) :: output_dir
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: csv_path, gif_path
        integer :: frames

        call make_folder(output_dir, error)
        if (allocated(error)) return
        csv_path = csv_argument(argument, output_dir)
        gif_path = output_dir // "/" // base_name(csv_path, ".csv") // ".gif"
        call animate_output(csv_path, gif_path, frames, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "animate: wrote " // gif_path // " (" // to_text(frames) &
            & // " frames)"
    end subroutine animate_command

end module rollcon_command_animate
