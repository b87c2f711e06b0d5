! SPDX-License-Identifier: MIT
!> `rollcon run`: simulate a disk scene and write its CSV and summary.
module rollcon_command_run
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, rolling_disk_ucosub
    use rollcon_error, only : fatal_error, stat_io, stat_input
    use rollcon_text, only : to_text, shell_quote
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_scene, only : scene_type, read_scene, scene_path
    use rollcon_disk_scene, only : simulate_scene
    use rollcon_simulation, only : run_summary_type, status_completed, status_stopped, &
        & status_inaccurate
    implicit none
    private

    public :: run_scene

contains

    !> Read the scene, simulate it, write output_dir/<scene>.csv and <scene>.summary.txt.
    subroutine run_scene(name, output_dir, ucosub, quiet, summary, error)
        !> Scene name ('coin') or path of a namelist file
        character(len=*), intent(in) :: name
        !> Folder for the outputs (created if missing)
        character(len=*), intent(in) :: output_dir
        !> The routine serving the disk's UCONs
        procedure(ucosub_interface) :: ucosub
        !> No progress lines
        logical, intent(in) :: quiet
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(error_type), allocatable :: run_error
        character(len=:), allocatable :: summary_path, text, csv_path
        integer :: stat, unit

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        call execute_command_line("mkdir -p " // shell_quote(output_dir), exitstat=stat)
        if (stat /= 0) then
            call fatal_error(error, output_dir // ": cannot create the output folder", stat_io)
            return
        end if
        csv_path = output_dir // "/" // scene%name // ".csv"
        call simulate_scene(scene, ucosub, summary, run_error, csv_path=csv_path, &
            & progress=.not. quiet)
        if (allocated(run_error) .and. summary%rows == 0) then
            ! refused before any integration (e.g. a UCOSUB error at set-up): nothing to sum up
            call move_alloc(run_error, error)
            return
        end if
        text = summary_text(scene, csv_path, summary)
        write(output_unit, '(a)') text
        summary_path = output_dir // "/" // scene%name // ".summary.txt"
        open(newunit=unit, file=summary_path, status="replace", action="write", iostat=stat)
        if (stat == 0) then
            write(unit, '(a)') text
            close(unit)
        end if
        if (allocated(run_error)) then
            call move_alloc(run_error, error)
            error%message = error%message // " (the " // to_text(summary%rows) &
                & // " rows written to " // csv_path // " up to t = " &
                & // to_text(summary%t_reached) // " s are valid)"
        end if
    end subroutine run_scene

    !> The run's summary as text.
    function summary_text(scene, csv_path, summary) result(text)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: csv_path
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        character(len=:), allocatable :: method
        character(len=16), parameter :: names(12) = [character(len=16) :: "X [m]", "Y [m]", &
            & "Z [m]", "psi [rad]", "theta [rad]", "phi [rad]", "Xdot [m/s]", "Ydot [m/s]", &
            & "Zdot [m/s]", "psidot [rad/s]", "thetadot [rad/s]", "phidot [rad/s]"]
        character(len=32) :: value
        integer :: i

        if (scene%formulation == "cvode") then
            method = "CVODE (ODE form, "
            if (scene%method == "adams") then
                method = method // "Adams, drift " // scene%drift // ")"
            else
                method = method // "BDF, drift " // scene%drift // ")"
            end if
        else
            method = "IDA (DAE form, index 2)"
        end if
        text = "scene " // scene%name // " (" // scene%path // "): " // method // ", " &
            & // scene%jacobian // " Jacobian, rtol " // to_text(scene%rtol) // ", atol " &
            & // to_text(scene%atol) // nl
        select case (summary%status)
        case (status_completed)
            text = text // "status: completed at t = " // to_text(summary%t_reached) // " s" // nl
        case (status_stopped)
            text = text // "status: stopped: " // summary%message // nl
        case (status_inaccurate)
            text = text // "status: INACCURATE: " // summary%message // nl
        case default
            text = text // "status: FAILED: " // summary%message // nl
        end select
        if (allocated(summary%q)) then
            text = text // "final state:" // nl
            do i = 1, 6
                write(value, '(es23.15)') summary%q(i)
                text = text // "  " // names(i) // trim(value)
                write(value, '(es23.15)') summary%u(i)
                text = text // "    " // names(6 + i) // trim(value) // nl
            end do
        end if
        write(value, '(es10.3)') summary%energy_drift
        text = text // "energy drift: " // trim(adjustl(value)) // " (largest |E - E0|/|E0|, E0 = " &
            & // to_text(summary%energy_reference) // " J after the last applied force)" &
            & // allowed(summary%energy_bound, "") // nl
        write(value, '(es10.3)') summary%residual_max
        text = text // "largest constraint residual: " // trim(adjustl(value)) &
            & // " (F1..F3: m/s, or m for height = 'position')" // nl
        write(value, '(es10.3)') summary%height_residual_max
        text = text // "largest height residual |Z - R sin(theta)|: " // trim(adjustl(value)) &
            & // " m" // allowed(summary%height_bound, " m") // nl
        text = text // "steps " // to_text(summary%steps) // ", function evaluations " &
            & // to_text(summary%functions) // ", Jacobian evaluations " &
            & // to_text(summary%jacobians) // ", error-test failures " &
            & // to_text(summary%failures) // nl
        write(value, '(f12.4)') summary%cpu_seconds
        text = text // "CPU time: " // trim(adjustl(value)) // " s" // nl
        text = text // "output: " // csv_path // " (" // to_text(summary%rows) // " rows)"

    contains

        !> ", allowed <bound><unit>" when the drift was judged (bound > 0).
        function allowed(bound, unit) result(phrase)
            real(wp), intent(in) :: bound
            character(len=*), intent(in) :: unit
            character(len=:), allocatable :: phrase

            phrase = ""
            if (bound <= 0.0_wp) return
            write(value, '(es10.3)') bound
            phrase = ", allowed " // trim(adjustl(value)) // unit
        end function allowed

    end function summary_text

end module rollcon_command_run
