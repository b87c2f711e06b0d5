! SPDX-License-Identifier: MIT
!> Drift that tells the truth: the position-level height residual Z - R sin(theta) in the CSV
!> and the summary, energy and height drift judged against what the tolerances promise
!> (rollcon_drift), the two forms of the height constraint, no drift growth over a long run.
module test_drift
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene, choice_code
    use rollcon_problem, only : problem_type
    use rollcon_watch, only : watch_measure_type
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : run_options_type, simulate, history_type, run_summary_type, &
        & status_completed, status_inaccurate
    use rollcon_output_layout, only : output_layout_type, read_layout, name_length, time_column, &
        & coord_x, coord_z, coord_theta, coord_phi
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory, tipping_coin
    use rollcon_load, only : load_job, input_override_type
    use rollcon_job, only : job_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_output_files, only : make_folders, write_text_file
    use command_runs, only : file_text
    use override_lists, only : add_override
    implicit none
    private

    public :: collect_drift

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_drift"

contains

    subroutine collect_drift(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("height-residual-in-csv-and-summary", test_height_column), &
            & new_unittest("drift-none-judged-inaccurate", test_drift_none_warned), &
            & new_unittest("sound-run-within-drift-bounds", test_sound_run), &
            & new_unittest("position-height-holds-z-to-atol", test_position_height_holds), &
            & new_unittest("position-height-matches-velocity-form", test_position_height), &
            & new_unittest("long-run-energy-and-no-drift-growth", test_long_run), &
            & new_unittest("energy-judged-from-zero", test_energy_from_zero), &
            & new_unittest("right-pendulums-complete", test_right_pendulums), &
            & new_unittest("loose-pendulum-inaccurate", test_loose_pendulum), &
            & new_unittest("energy-advice-fits-the-integrator", test_energy_advice)]
    end subroutine collect_drift

    !> The CSV's last column is the height residual Z - R sin(theta) of each row, and the
    !> summary's height_residual_max is its largest magnitude.
    subroutine test_height_column(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = "build/test_events_height.csv"
        !> Z and theta are printed with 17 significant digits: the residual recomputed from
        !> them is good to ~1e-17 m
        real(wp), parameter :: tol_printed = 1.0e-15_wp
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        real(wp) :: q0(6), u0(6), largest
        real(wp), allocatable :: row(:)
        type(output_layout_type) :: layout
        character(len=name_length), allocatable :: names(:)
        character(len=:), allocatable :: message
        character(len=2048) :: line
        integer :: unit, stat, rows, z, theta, height

        scene = tipping_coin("ida", 1.0e-6_wp)
        scene%run%end_time = 2.0_wp
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        options%end_time = scene%run%end_time
        options%output_step = 0.1_wp
        options%csv_path = path
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        read(unit, '(a)') line
        ! the header names the layout of a disk scene: one part, three UCONs, the contact last
        allocate(names(count([(line(stat:stat) == ",", stat = 1, len_trim(line))]) + 1))
        read(line, *) names
        call read_layout(names, layout, message)
        if (allocated(message)) call check(error, .false., "header: " // message)
        if (.not. allocated(error)) call check(error, layout%column("height_residual") > 0 .and. &
            & size(layout%ucon_ids) == 3 .and. names(size(names)) == "height_residual", &
            & "header: " // trim(line))
        if (allocated(error)) then
            close(unit, status="delete")
            return
        end if
        allocate(row(layout%columns()))
        z = layout%part_column(1, coord_z)
        theta = layout%part_column(1, coord_theta)
        height = layout%column("height_residual")
        rows = 0
        largest = 0.0_wp
        do
            read(unit, *, iostat=stat) row
            if (stat /= 0) exit
            rows = rows + 1
            largest = max(largest, abs(row(height)))
            call check(error, row(height), row(z) - scene%disk%radius*sin(row(theta)), &
                & "height residual at t = " // to_text(row(time_column)), abs_tol=tol_printed)
            if (allocated(error)) exit
        end do
        close(unit, status="delete")
        if (allocated(error)) return
        call check(error, rows, int(summary%rows), "rows read")
        if (allocated(error)) return
        call check(error, largest > 0.0_wp, "the velocity form's height residual is exactly 0")
        if (allocated(error)) return
        call check(error, height_of(summary), largest, "summary's height residual [m]", &
            & rel_tol=1.0e-12_wp)
    end subroutine test_height_column

    !> Without drift control CVODE lets the constraints wander: on the tipping coin at rtol 1e-4
    !> the height residual grows like the number of steps N, to 7.8 sqrt(N) (atol + rtol R)
    !> over 10 s, beyond its bound of 3 sqrt(N) (energy: 9.2 sqrt(N) rtol, just below its 10).
    !> The run is judged inaccurate, not completed, and says why.
    subroutine test_drift_none_warned(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        scene = drifting_scene()
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_inaccurate, "status " &
            & // to_text(summary%status) // ", energy drift " // to_text(summary%energy_drift) &
            & // " (bound " // to_text(summary%energy_bound) // "), height residual " &
            & // to_text(height_of(summary)) // " m (bound " &
            & // to_text(bound_of(summary)) // " m)")
        if (allocated(error)) return
        call check(error, index(summary%message, "drifted beyond what its tolerances promise") &
            & > 0 .and. index(summary%message, "height residual |Z - R sin(theta)| ") > 0, &
            & "message: " // summary%message)
    end subroutine test_drift_none_warned

    !> The scene of test_drift_none_warned.
    function drifting_scene() result(scene)
        type(scene_type) :: scene

        scene = tipping_coin("cvode", 1.0e-4_wp)
        scene%run%drift = choice_code("drift", "none")
    end function drifting_scene

    !> The same scene with projection (0.7 and 0.12 sqrt(N) units measured) and with IDA stays
    !> within both bounds, and they are set.
    subroutine test_sound_run(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=5), parameter :: formulations(2) = ["cvode", "ida  "]
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        integer :: i

        do i = 1, 2
            scene = drifting_scene()
            scene%run%formulation = choice_code("formulation", trim(formulations(i)))
            scene%run%drift = choice_code("drift", "projection")
            call run_in_memory(scene, history, summary, error)
            if (allocated(error)) return
            call check(error, summary%status == status_completed .and. &
                & summary%energy_bound > 0.0_wp .and. bound_of(summary) > 0.0_wp, &
                & trim(formulations(i)) // ": status " // to_text(summary%status) // ", bounds " &
                & // to_text(summary%energy_bound) // ", " // to_text(bound_of(summary)))
            if (allocated(error)) return
        end do
    end subroutine test_sound_run

    !> The position form of the height constraint holds Z = R sin(theta) to the absolute
    !> tolerance over the tipping coin's 10 s (fall to theta ~ 0.12 rad and back), where the
    !> velocity form lets it drift by orders of magnitude more; both within their bound.
    subroutine test_position_height_holds(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: velocity_form, position_form

        scene = tipping_coin("ida", 1.0e-8_wp)
        call run_in_memory(scene, history, velocity_form, error)
        if (allocated(error)) return
        scene%run%height = choice_code("height", "position")
        call run_in_memory(scene, history, position_form, error)
        if (allocated(error)) return
        call check(error, velocity_form%status == status_completed .and. &
            & position_form%status == status_completed, "status " &
            & // to_text(velocity_form%status) // ", " // to_text(position_form%status))
        if (allocated(error)) return
        call check(error, height_of(position_form) <= scene%run%atol, "position form: " &
            & // "|Z - R sin(theta)| " // to_text(height_of(position_form)) &
            & // " m above atol")
        if (allocated(error)) return
        call check(error, height_of(velocity_form) > 10.0_wp*scene%run%atol, &
            & "velocity form: |Z - R sin(theta)| " // to_text(height_of(velocity_form)) &
            & // " m, no worse than the position form's")
    end subroutine test_position_height_holds

    !> long_run (200 s at 0.8 m/s): energy within 1000 rtol, and IDA's constraint residual in
    !> the last 20 s no larger than ten times that of the first 20 s (no drift growth).
    subroutine test_long_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        real(wp), allocatable :: t(:), residual(:)
        real(wp) :: early, late

        call read_scene("data/long_run.nml", scene, error)
        if (allocated(error)) return
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check(error, summary%energy_drift, 0.0_wp, "energy drift over 200 s", &
            & abs_tol=1.0e3_wp*scene%run%rtol)
        if (allocated(error)) return
        t = history%column(time_column)
        residual = maxval(abs(history%rows(history%layout%residual_column(1) &
            & :history%layout%residual_column(size(history%layout%ucon_ids)), &
            & :history%count)), dim=1)
        early = maxval(residual, mask=t <= 20.0_wp)
        late = maxval(residual, mask=t >= 180.0_wp)
        call check(error, late <= 10.0_wp*early + 1.0e-2_wp*scene%run%atol, "residual grew from " &
            & // to_text(early) // " (first 20 s) to " // to_text(late) // " (last 20 s)")
    end subroutine test_long_run

    !> A pendulum released level with the origin has E0 = 0 J (test/drift/energy_from_zero.adm):
    !> its drift is judged all the same, against the energy it exchanges, m g L = 19.6 J (the
    !> scale is that to the drift itself: T_max = m g L + the drift). At ERROR = 1e-3 the energy
    !> wanders by 0.5 J, 2.5 % of it: INACCURATE, the message naming the energy and a tighter
    !> rtol; at ERROR = 1e-6 by 1.2e-3 J (6e-5 of it, 0.3 of its bound): completed, and judged.
    subroutine test_energy_from_zero(error)
        type(error_type), allocatable, intent(out) :: error
        !> m g L of the dataset [J]
        real(wp), parameter :: exchanged = 9.80665_wp*2.0_wp
        type(run_summary_type) :: summary

        call run_drift_dataset("energy_from_zero", "1e-3", summary, error)
        if (allocated(error)) return
        call check(error, summary%energy_reference == 0.0_wp .and. summary%status &
            & == status_inaccurate .and. index(summary%message, "energy drift") > 0 .and. &
            & index(summary%message, "a tighter rtol") > 0, "ERROR = 1e-3: status " &
            & // to_text(summary%status) // ", E0 " // to_text(summary%energy_reference) &
            & // " J: " // summary%message)
        if (allocated(error)) return
        ! the scale is m g L to the drift: at most the 0.5 J it wandered above it
        call check(error, summary%energy_scale, exchanged, "the energy scale [J]", &
            & abs_tol=summary%energy_drift*summary%energy_scale + 1.0e-12_wp)
        if (allocated(error)) return
        call run_drift_dataset("energy_from_zero", "1e-6", summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_completed .and. summary%energy_bound > 0.0_wp &
            & .and. summary%energy_drift > 0.0_wp .and. summary%energy_drift &
            & <= summary%energy_bound, "ERROR = 1e-6: status " // to_text(summary%status) &
            & // ", drift " // to_text(summary%energy_drift) // ", bound " &
            & // to_text(summary%energy_bound))
    end subroutine test_energy_from_zero

    !> Right runs complete: a compound pendulum from 60 degrees and a double pendulum at ERROR
    !> = 1e-10 (their periods and angles right to 1e-8 and better) drift by 7.7e-8 and 2.0e-8
    !> of their energy scales, within the bound: one step's allowance there is atol-bound
    !> (1e-10 on states of 0.1 to 1), which the bound takes in.
    subroutine test_right_pendulums(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=15), parameter :: names(2) = ["pendulum_swing ", "double_pendulum"]
        type(run_summary_type) :: summary
        integer :: k

        do k = 1, size(names)
            call run_drift_dataset(trim(names(k)), "", summary, error)
            if (allocated(error)) return
            call check(error, summary%status == status_completed .and. summary%energy_bound &
                & > 0.0_wp .and. summary%energy_drift <= summary%energy_bound, trim(names(k)) &
                & // ": status " // to_text(summary%status) // ", drift " &
                & // to_text(summary%energy_drift) // ", bound " &
                & // to_text(summary%energy_bound) // ": " // text_of(summary%message))
            if (allocated(error)) return
        end do
    end subroutine test_right_pendulums

    !> A deliberately loose run, the compound pendulum at ERROR = 1e-2: its energy drifts by
    !> 63 % of its scale (0.77 J of 1.23 J) and the run is INACCURATE; on IDA the advice is a
    !> tighter rtol, never a drift control IDA does not take.
    subroutine test_loose_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary

        call run_drift_dataset("pendulum_swing", "1e-2", summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_inaccurate .and. summary%energy_drift &
            & > 0.1_wp .and. index(summary%message, "a tighter rtol (now 0.01)") > 0 .and. &
            & index(summary%message, "projection") == 0, "status " &
            & // to_text(summary%status) // ", drift " // to_text(summary%energy_drift) &
            & // ": " // text_of(summary%message))
    end subroutine test_loose_pendulum

    !> The advice names a setting the run's integrator takes and does not use yet: CVODE BDF
    !> without drift control is told drift = 'projection'; CVODE with projection, and CVODE
    !> Adams with Baumgarte terms, only a tighter rtol (the pendulum released level at ERROR =
    !> 1e-3, INACCURATE on each).
    subroutine test_energy_advice(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: settings(3) = [character(len=48) :: &
            & "FORMULATION=CVODE, DRIFT=NONE", "FORMULATION=CVODE, DRIFT=PROJECTION", &
            & "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE"]
        logical, parameter :: projection(3) = [.true., .false., .false.]
        character(len=:), allocatable :: text, variant
        type(run_summary_type) :: summary
        integer :: k, at

        text = file_text("test/drift/energy_from_zero.adm")
        at = index(text, "INTEGRATOR/ERROR = 1e-3")
        do k = 1, size(settings)
            variant = text(:at - 1) // "INTEGRATOR/ERROR = 1e-3, " // trim(settings(k)) &
                & // text(at + len("INTEGRATOR/ERROR = 1e-3"):)
            call make_folders(scratch, error)
            if (allocated(error)) return
            call write_text_file(scratch // "/advice.adm", variant, error)
            if (allocated(error)) return
            call run_dataset_file(scratch // "/advice.adm", "", summary, error)
            if (allocated(error)) return
            call check(error, summary%status == status_inaccurate .and. &
                & (index(summary%message, "drift = 'projection'") > 0 .eqv. projection(k)) &
                & .and. index(summary%message, "a tighter rtol") > 0, trim(settings(k)) &
                & // ": status " // to_text(summary%status) // ": " // text_of(summary%message))
            if (allocated(error)) return
        end do
    end subroutine test_energy_advice

    !> Run test/drift/NAME.adm (at ERROR = error_value unless ""), no files.
    subroutine run_drift_dataset(name, error_value, summary, error)
        character(len=*), intent(in) :: name, error_value
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error

        call run_dataset_file("test/drift/" // name // ".adm", error_value, summary, error)
    end subroutine run_drift_dataset

    !> Run a dataset file (at INTEGRATOR ERROR = error_value unless ""), no files.
    subroutine run_dataset_file(path, error_value, summary, error)
        character(len=*), intent(in) :: path, error_value
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(input_override_type), allocatable :: set(:)
        type(job_type) :: job
        type(job_result_type) :: ran

        allocate(set(0))
        if (len(error_value) > 0) call add_override(set, "integrator%error", error_value)
        call load_job(path, job, error, overrides=set)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error)
        if (allocated(error)) return
        summary = ran%summary
    end subroutine run_dataset_file

    !> An allocatable text, "" when it is not allocated.
    pure function text_of(text) result(value)
        character(len=:), allocatable, intent(in) :: text
        character(len=:), allocatable :: value

        value = ""
        if (allocated(text)) value = text
    end function text_of

    !> The contact height as a position UCON (Z - R sin(theta) = 0, GGL form in IDA, projection
    !> in CVODE) gives the motion of its velocity form F3, and holds Z = R sin(theta).
    subroutine test_position_height(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=5), parameter :: formulations(2) = ["ida  ", "cvode"]
        type(scene_type) :: scene
        type(history_type) :: velocity_form, position_form
        type(run_summary_type) :: summary
        real(wp) :: difference, height
        integer :: i, x, phi

        do i = 1, 2
            scene = tipping_coin(trim(formulations(i)), 1.0e-9_wp)
            scene%run%end_time = 1.0_wp
            call run_in_memory(scene, velocity_form, summary, error)
            if (allocated(error)) return
            scene%run%height = choice_code("height", "position")
            call run_in_memory(scene, position_form, summary, error)
            if (allocated(error)) return
            ! same motion to the integration error over 1 s (1e3 rtol, as for CVODE vs IDA)
            x = velocity_form%layout%part_column(1, coord_x)
            phi = velocity_form%layout%part_column(1, coord_phi)
            difference = maxval(abs(velocity_form%rows(x:phi, :velocity_form%count) &
                & - position_form%rows(x:phi, :position_form%count)))
            call check(error, difference, 0.0_wp, trim(formulations(i)) // ": largest " &
                & // "difference between the two forms", abs_tol=1.0e-6_wp)
            if (allocated(error)) return
            height = maxval(abs(position_form%part_values(1, coord_z) - scene%disk%radius &
                & *sin(position_form%part_values(1, coord_theta))))
            call check(error, height, 0.0_wp, trim(formulations(i)) // ": |Z - R sin(theta)| [m]", &
                & abs_tol=1.0e-9_wp)
            if (allocated(error)) return
        end do
    end subroutine test_position_height

    !> The largest height residual a run's contact watch measured [m].
    function height_of(summary) result(height)
        type(run_summary_type), intent(in) :: summary
        real(wp) :: height
        type(watch_measure_type) :: measure

        measure = summary%measure("height_residual")
        height = measure%value
    end function height_of

    !> What the tolerances allow of the height residual [m].
    function bound_of(summary) result(bound)
        type(run_summary_type), intent(in) :: summary
        real(wp) :: bound
        type(watch_measure_type) :: measure

        measure = summary%measure("height_residual")
        bound = measure%bound
    end function bound_of

end module test_drift
