! SPDX-License-Identifier: MIT
!> Runs a disk scene in memory for the tests.
module motion_runs
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_scene, only : scene_type, formulation_ida, method_bdf, drift_projection, &
        & jacobian_analytic, height_velocity, choice_code
    use rollcon_scene_source, only : new_scene_source
    use rollcon_job, only : job_type, new_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : run_summary_type, history_type
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_output_files, only : write_text_file, make_folders
    use rollcon_load, only : load_job
    use rollcon_simulation, only : status_completed
    implicit none
    private

    public :: run_in_memory, default_scene, tipping_coin, run_dataset_text


contains

    !> The paper's disk, upright, at rest, IDA, no strike, no limits: tests change what they need.
    function default_scene() result(scene)
        type(scene_type) :: scene

        scene%name = "test"
        scene%path = "(built in the test)"
        scene%run%formulation = formulation_ida
        scene%run%method = method_bdf
        scene%run%drift = drift_projection
        scene%run%jacobian = jacobian_analytic
        scene%run%height = height_velocity
        scene%limits%theta_min = -1.0_wp
        scene%limits%stop_on_liftoff = .false.
    end function default_scene

    !> The tipping coin: upright less 0.01 rad, rolling at 0.1 m/s, no strike, 10 s.
    function tipping_coin(formulation, rtol) result(scene)
        character(len=*), intent(in) :: formulation
        real(wp), intent(in) :: rtol
        type(scene_type) :: scene

        scene = default_scene()
        scene%initial%theta = 0.5_wp*pi - 0.01_wp
        scene%initial%phidot = -1.0_wp
        scene%run%end_time = 10.0_wp
        scene%run%output_step = 0.05_wp
        scene%run%formulation = choice_code("formulation", formulation)
        scene%run%rtol = rtol
        scene%run%atol = 1.0e-2_wp*rtol
    end function tipping_coin

    !> Run scene as a job (run_job, no files) with ucosub (default: the hand-checked disk) and
    !> keep every output row.
    subroutine run_in_memory(scene, history, summary, error, ucosub)
        type(scene_type), intent(in) :: scene
        type(history_type), intent(out) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), optional :: ucosub
        type(job_type) :: job
        type(job_result_type) :: result

        job = new_job(new_scene_source(scene))
        if (present(ucosub)) job%routine => ucosub
        call run_job(job, result, error, history)
        summary = result%summary
    end subroutine run_in_memory

    !> Write a dataset's text as folder/name.adm and run it (run_job, no files), keeping every
    !> output row; the run must complete (error otherwise, naming it and why).
    subroutine run_dataset_text(folder, name, text, history, error)
        character(len=*), intent(in) :: folder, name, text
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path
        type(job_type) :: job
        type(job_result_type) :: ran

        call make_folders(folder, error)
        if (allocated(error)) return
        path = folder // "/" // name // ".adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error, history)
        if (allocated(error)) return
        if (ran%summary%status /= status_completed) call fatal_error(error, path // ": " &
            & // ran%summary%message)
    end subroutine run_dataset_text

end module motion_runs
