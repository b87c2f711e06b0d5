! SPDX-License-Identifier: MIT
!> `rollcon run SCENE --vtk FPS`: the run as a VTK time series for ParaView.
module rollcon_command_run_vtk
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, to_text, base_name, run_record_type, read_run, &
        & write_vtk_series
    use rollcon_command_plot, only : make_folder
    implicit none
    private

    public :: write_run_vtk, write_csv_vtk

contains

    !> After `rollcon run`: the VTK series of the run of a scene or dataset, whose CSV is
    !> output_dir/<name>.csv, <name> the file name less '.nml' or '.adm'.
    subroutine write_run_vtk(name, output_dir, fps, error)
        !> Scene or dataset name or path, as given to run
        character(len=*), intent(in) :: name
        !> Output folder of the run
        character(len=*), intent(in) :: output_dir
        !> Frames per second of simulated time [1/s]
        real(wp), intent(in) :: fps
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: run_name

        run_name = base_name(name, ".nml")
        run_name = base_name(run_name, ".adm")
        call write_csv_vtk(output_dir // "/" // run_name // ".csv", fps, error)
    end subroutine write_run_vtk

    !> Write DIR/<base>_vtk/<base>.pvd and its frames from DIR/<base>.csv and the part shapes
    !> beside it (DIR/<base>.parts).
    subroutine write_csv_vtk(csv_path, fps, error)
        !> The run's CSV
        character(len=*), intent(in) :: csv_path
        !> Frames per second of simulated time [1/s]
        real(wp), intent(in) :: fps
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        character(len=:), allocatable :: folder, name
        integer :: frames

        call read_run(csv_path, run, error)
        if (allocated(error)) return
        name = base_name(csv_path, ".csv")
        folder = csv_path(:len(csv_path) - len(base_name(csv_path, ""))) // name // "_vtk"
        call make_folder(folder, error)
        if (allocated(error)) return
        call write_vtk_series(folder, name, run, fps, frames, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "vtk: wrote " // folder // "/" // name // ".pvd (" &
            & // to_text(frames) // " frames, " // to_text(size(run%shapes)) // " part" &
            & // trim(merge("s", " ", size(run%shapes) /= 1)) // "; open it in ParaView)"
    end subroutine write_csv_vtk

end module rollcon_command_run_vtk
