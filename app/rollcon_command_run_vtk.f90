! SPDX-License-Identifier: MIT
!> `rollcon run SCENE --vtk FPS`: the run as a VTK time series for ParaView.
module rollcon_command_run_vtk
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, to_text, scene_type, read_scene, scene_path, history_type, &
        & read_output_csv, write_vtk_series
    use rollcon_command_plot, only : make_folder
    implicit none
    private

    public :: write_run_vtk

contains

    !> After `rollcon run`: write output_dir/<scene>_vtk/<scene>.pvd and its frames from the
    !> run's CSV, the disk's radius and thickness from the scene.
    subroutine write_run_vtk(name, output_dir, fps, error)
        !> Scene name or path, as given to run
        character(len=*), intent(in) :: name
        !> Output folder of the run
        character(len=*), intent(in) :: output_dir
        !> Frames per second of simulated time [1/s]
        real(wp), intent(in) :: fps
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        character(len=:), allocatable :: folder
        real(wp) :: radius
        integer :: frames

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        call read_output_csv(output_dir // "/" // scene%name // ".csv", history, radius, error)
        if (allocated(error)) return
        folder = output_dir // "/" // scene%name // "_vtk"
        call make_folder(folder, error)
        if (allocated(error)) return
        call write_vtk_series(folder, scene%name, history, scene%disk%radius, &
            & scene%disk%thickness, fps, frames, error)
        if (allocated(error)) return
        write(output_unit, '(a)') "vtk: wrote " // folder // "/" // scene%name // ".pvd (" &
            & // to_text(frames) // " frames; open it in ParaView)"
    end subroutine write_run_vtk

end module rollcon_command_run_vtk
