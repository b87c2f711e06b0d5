! SPDX-License-Identifier: MIT
!> Motion-suite runs off the default set-up: a solver that fails mid-run, and the generated
!> rolling-disk UCOSUB in place of the hand-checked one.
module motion_run_variants
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_scene, only : scene_type
    use rollcon_problem, only : problem_type
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_gen_rolling_disk, only : generated_disk_ucosub => rolling_disk_ucosub
    use rollcon_simulation, only : run_options_type, simulate, status_failed, history_type, &
        & run_summary_type
    use rollcon_output_layout, only : coord_x, coord_phi
    use rollcon_testing, only : check
    use motion_runs, only : run_in_memory, tipping_coin
    implicit none
    private

    public :: test_solver_failure, test_generated_trajectory

contains

    !> A run that fails (here: too few steps allowed) says so with the solver's flag and the
    !> time reached, and the CSV holds a header and only complete, finite rows.
    subroutine test_solver_failure(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = "build/test_motion_failure.csv"
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(error_type), allocatable :: failure
        real(wp) :: q0(6), u0(6), row(22)
        character(len=2048) :: line
        integer :: unit, stat, rows

        scene = tipping_coin("ida", 1.0e-8_wp)
        ! 200 steps per output interval: IDA takes them within 0.7 s (measured: it fails at
        ! 0.64 s), after a few rows every 0.1 s
        scene%run%max_steps = 200
        scene%run%output_step = 0.1_wp
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        options%end_time = scene%run%end_time
        options%output_step = scene%run%output_step
        options%csv_path = path
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, failure)
        call check(error, allocated(failure) .and. summary%status == status_failed, &
            & "the run did not fail")
        if (allocated(error)) return
        call check(error, index(failure%message, "IDA failed at t = ") == 1 .and. &
            & index(failure%message, "flag -1") > 0, "message: " // failure%message)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        read(unit, '(a)') line
        call check(error, index(line, "t,X,Y,Z,psi,theta,phi,Xdot,Ydot,Zdot,psidot,thetadot," &
            & // "phidot,E,Fx,Fy,Fz,Fn,mu_needed,F1,F2,F3") == 1, "header: " // trim(line))
        rows = 0
        do
            read(unit, *, iostat=stat) row
            if (stat /= 0) exit
            rows = rows + 1
        end do
        close(unit, status="delete")
        call check(error, rows, int(summary%rows), "complete rows in the CSV")
        if (allocated(error)) return
        call check(error, rows > 1, "no rows before the failure")
    end subroutine test_solver_failure

    !> The generated rolling-disk UCOSUB drives the same motion as the hand-checked one. The two
    !> agree to ~1e-16 per entry (generated suite), but that is enough for the adaptive
    !> integrator to accept or reject a step differently, after which the runs differ by the
    !> integration error: coordinates agree to 1e3 rtol over the first second, as CVODE and IDA.
    subroutine test_generated_trajectory(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: hand, generated
        type(run_summary_type) :: summary
        integer :: x, phi

        scene = tipping_coin("ida", 1.0e-10_wp)
        scene%run%end_time = 1.0_wp
        call run_in_memory(scene, hand, summary, error)
        if (allocated(error)) return
        call run_in_memory(scene, generated, summary, error, generated_disk_ucosub)
        if (allocated(error)) return
        call check(error, hand%count, generated%count, "output rows")
        if (allocated(error)) return
        x = hand%layout%part_column(1, coord_x)
        phi = hand%layout%part_column(1, coord_phi)
        call check(error, maxval(abs(hand%rows(x:phi, :hand%count) &
            & - generated%rows(x:phi, :generated%count))), 0.0_wp, &
            & "largest coordinate difference, hand-checked against generated", &
            & abs_tol=1.0e3_wp*scene%run%rtol)
    end subroutine test_generated_trajectory

end module motion_run_variants
