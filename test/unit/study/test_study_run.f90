! SPDX-License-Identifier: MIT
!> Tests of running a study in the library (docs/studies.md): a case's scene is the base scene
!> with its parameters set; failed and refused cases are rows and the study goes on; the rows
!> do not depend on the order the cases run in; a rerun after an interruption completes the
!> CSV without running again what it holds; the classes of the upright-stability study
!> change at the analytic critical speed of docs/design.md §5; the classes of the no-slip
!> validity study (the struck coin on a table with friction) read what its run did.
module test_study_run
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene_lines, scene_override_type
    use rollcon_scene_state, only : upright_critical_speed
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_measures, only : case_result_type, outcome_completed, measure_index, &
        & measure_case, outcome_refused, outcome_words
    use rollcon_scene, only : read_scene
    use rollcon_job, only : job_type, user_file_type
    use rollcon_load, only : load_job, input_override_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : run_summary_type, history_type, status_stopped
    use rollcon_output_layout, only : coord_theta, coord_zdot
    use rollcon_study_run, only : study_plan_type, study_progress_type, plan_cases, plan_study, &
        & run_case, append_row, run_study, prepare_study_routines
    use rollcon_testing, only : unittest_type, new_unittest, check
    use study_texts, only : write_study
    use study_rows, only : csv_rows, without_cpu, sorted, remove_file, cut_after
    implicit none
    private

    public :: collect_study_run

    !> The test issue's bound: the simulated boundary of the upright-stability classes lies
    !> within 2 % of the analytic critical speed (measured: within 1 %, docs/studies.md)
    real(wp), parameter :: tol_boundary = 0.02_wp
    !> Speeds tried around the critical speed: +-4 % in steps of 0.5 %, so the boundary is
    !> located to 0.25 % of vc, well inside the bound
    real(wp), parameter :: speed_span = 0.04_wp
    integer, parameter :: speed_count = 17

contains

    !> Tests of this suite.
    subroutine collect_study_run(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("overrides-replace-and-add", test_overrides), &
            & new_unittest("failed-and-refused-recorded", test_failures), &
            & new_unittest("rows-independent-of-order", test_order), &
            & new_unittest("resume-after-cut", test_resume), &
            & new_unittest("other-study-csv-refused", test_other_header), &
            & new_unittest("stability-boundary", test_boundary), &
            & new_unittest("modes-classed-from-the-run", test_modes), &
            & new_unittest("modes-measured-over-every-contact", test_contacts_modes), &
            & new_unittest("struck-coin-classes-by-physics", test_struck_physics), &
            & new_unittest("dataset-base", test_dataset), &
            & new_unittest("user-file-cases-are-its-runs", test_user_file), &
            & new_unittest("user-file-faults-named", test_user_file_faults), &
            & new_unittest("stops-named-by-their-limit", test_stop_outcomes)]
    end subroutine collect_study_run

    !> An override replaces a key of the file, adds one to a group, and adds a group: an
    !> added &strike enables the strike.
    subroutine test_overrides(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(scene_type) :: scene
        character(len=:), allocatable :: path

        call write_study("test_study_overrides", [character(len=40) :: "&study", &
            & "    scene = 'data/upright.nml' /", "&grid", "    disk%radius = '0.1 0.1 1' /"], &
            & path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call read_scene_lines(study%scene_path, study%scene_lines, scene, error, &
            & [override("disk", "thickness", "0.02"), override("disk", "radius", "0.15"), &
            & override("strike", "impulse", "0.03")])
        if (allocated(error)) return
        call check(error, scene%disk%thickness == 0.02_wp .and. scene%disk%radius == 0.15_wp &
            & .and. scene%disk%density == 7800.0_wp, "disk keys replaced or kept")
        if (allocated(error)) return
        call check(error, scene%strike%enabled .and. scene%strike%impulse == 0.03_wp, &
            & "the added &strike is enabled with its impulse")
        if (allocated(error)) return
        ! the file's speed, 0.7 m/s, now on a disk of radius 0.15 m
        call check(error, abs(scene%initial%phidot + 0.7_wp/0.15_wp) < 1.0e-14_wp, &
            & "phidot follows the overridden radius")
    end subroutine test_overrides

    !> A case the integrator fails (max_steps 1: CV_TOO_MUCH_WORK, flag -1) and cases whose
    !> scene is refused (theta below theta_min) are rows; the study runs every case.
    subroutine test_failures(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(study_progress_type) :: progress
        character(len=:), allocatable :: path, csv
        character(len=:), allocatable :: rows(:)
        real(wp) :: t_reached

        call write_study("test_study_failures", [character(len=60) :: "&study", &
            & "    scene = 'data/upright.nml' /", "&grid", "    run%max_steps = '1 5001 2'", &
            & "    initial%theta = '0.03 1.5 2' /"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        csv = "build/test_study_failures.csv"
        call remove_file(csv)
        call plan_study(study, csv, plan, error)
        if (allocated(error)) return
        call run_study(study, csv, plan, progress, error)
        if (allocated(error)) return
        rows = csv_rows(csv)
        call check(error, size(rows) == 5, "header and 4 rows, got " // to_text(size(rows)))
        if (allocated(error)) return
        call check(error, index(rows(2), "1,1,0.03,refused,refused,0,") == 1 .and. &
            & index(rows(2), "'theta_min' in &limits") > 0, "case 1 refused: " // trim(rows(2)))
        if (allocated(error)) return
        call check(error, index(rows(3), "2,1,1.5,failed,failed,-1,") == 1 .and. &
            & index(rows(3), "CV_TOO_MUCH_WORK") > 0, "case 2 failed with flag -1: " &
            & // trim(rows(3)))
        if (allocated(error)) return
        ! the time reached is where CVODE gave up: past the start, before the first row
        read(rows(3)(len("2,1,1.5,failed,failed,-1,") + 1:), *) t_reached
        call check(error, t_reached > 0.0_wp .and. t_reached < 0.01_wp, "case 2: t_reached " &
            & // to_text(t_reached) // " s is not where the integrator failed")
        if (allocated(error)) return
        call check(error, index(rows(5), "4,5001,1.5,completed,") == 1, "case 4 completed: " &
            & // trim(rows(5)))
        if (allocated(error)) return
        call check(error, progress%done == 4 .and. progress%failed == 1 .and. &
            & progress%refused == 2, "progress counts")
    end subroutine test_failures

    !> The cases run backwards give the rows they give forwards, but for cpu_s.
    subroutine test_order(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(study_progress_type) :: progress
        type(case_result_type) :: result
        character(len=:), allocatable :: forward, backward, row
        integer :: i

        call small_study(study, error)
        if (allocated(error)) return
        forward = "build/test_study_forward.csv"
        backward = "build/test_study_backward.csv"
        call remove_file(forward)
        call remove_file(backward)
        call plan_study(study, forward, plan, error)
        if (allocated(error)) return
        call run_study(study, forward, plan, progress, error)
        if (allocated(error)) return
        call plan_study(study, backward, plan, error)
        if (allocated(error)) return
        do i = size(plan%done), 1, -1
            call run_case(study, plan, i, row, result)
            call append_row(backward, row, error)
            if (allocated(error)) return
        end do
        call check(error, same_rows(forward, backward), "rows differ with the order of cases")
    end subroutine test_order

    !> A CSV cut after two rows and half a third (a run killed while writing) is completed
    !> by a rerun: the half row is dropped, the two are not run again, and the rows are those
    !> of an uninterrupted run.
    subroutine test_resume(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(study_progress_type) :: progress
        character(len=:), allocatable :: whole, cut

        call small_study(study, error)
        if (allocated(error)) return
        whole = "build/test_study_whole.csv"
        cut = "build/test_study_cut.csv"
        call remove_file(whole)
        call plan_study(study, whole, plan, error)
        if (allocated(error)) return
        call run_study(study, whole, plan, progress, error)
        if (allocated(error)) return
        call cut_after(whole, cut, 3, 20)
        call plan_study(study, cut, plan, error)
        if (allocated(error)) return
        call check(error, count(plan%done) == 2 .and. plan%done(1) .and. plan%done(2), &
            & "the two whole rows count as done, the cut one not: " // to_text(count(plan%done)) &
            & // " done")
        if (allocated(error)) return
        call run_study(study, cut, plan, progress, error)
        if (allocated(error)) return
        call check(error, same_rows(whole, cut), "the resumed CSV differs from a whole run")
    end subroutine test_resume

    !> A CSV of another study is not appended to.
    subroutine test_other_header(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(error_type), allocatable :: found
        character(len=:), allocatable :: csv

        call small_study(study, error)
        if (allocated(error)) return
        csv = "build/test_study_other.csv"
        call remove_file(csv)
        call append_row(csv, "case,disk%radius,outcome", error)
        if (allocated(error)) return
        call plan_study(study, csv, plan, found)
        call check(error, allocated(found), "no error for another study's CSV")
        if (allocated(error)) return
        call check(error, index(found%message, csv // ":1: the header is not this study's") &
            & == 1, "message: " // found%message)
    end subroutine test_other_header

    !> At three thicknesses, the shipped study's classes change from falls to stays_upright
    !> once, between neighbouring speeds whose midpoint is within 2 % of the analytic vc.
    subroutine test_boundary(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: thicknesses(3) = [0.01_wp, 0.1_wp, 0.2_wp]
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result
        type(scene_type) :: scene
        character(len=:), allocatable :: row
        character(len=16) :: classes(speed_count)
        real(wp) :: vc, speeds(speed_count), boundary
        integer :: t, i, first_up

        call read_study("data/upright_stability.nml", study, error)
        if (allocated(error)) return
        do t = 1, size(thicknesses)
            call read_scene_lines(study%scene_path, study%scene_lines, scene, error, &
                & [override("disk", "thickness", to_text(thicknesses(t)))])
            if (allocated(error)) return
            vc = upright_critical_speed(scene)
            study%parameters(1)%lower = thicknesses(t)
            study%parameters(1)%upper = thicknesses(t)
            study%parameters(1)%count = 1
            study%parameters(2)%lower = (1.0_wp - speed_span)*vc
            study%parameters(2)%upper = (1.0_wp + speed_span)*vc
            study%parameters(2)%count = speed_count
            call plan_cases(study, plan)
            do i = 1, speed_count
                call run_case(study, plan, i, row, result)
                classes(i) = result%class
                read(plan%texts(2, i), *) speeds(i)
            end do
            first_up = findloc(classes == "stays_upright", .true., dim=1)
            call check(error, first_up > 1 .and. all(classes(:first_up - 1) == "falls") .and. &
                & all(classes(first_up:) == "stays_upright"), "thickness " &
                & // to_text(thicknesses(t)) // ": classes do not change once from falls to " &
                & // "stays_upright over speeds " // to_text(speeds(1)) // " to " &
                & // to_text(speeds(speed_count)))
            if (allocated(error)) return
            boundary = 0.5_wp*(speeds(first_up - 1) + speeds(first_up))
            call check(error, abs(boundary/vc - 1.0_wp) <= tol_boundary, "thickness " &
                & // to_text(thicknesses(t)) // ": boundary " // to_text(boundary) &
                & // " m/s, analytic " // to_text(vc) // " m/s")
            if (allocated(error)) return
        end do
    end subroutine test_boundary

    !> data/no_slip_validity.nml, the struck coin on a table (mu_s 0.5, mu_k 0.4, restitution
    !> 0.5), at four strikes whose runs did four things (docs/studies.md): at 1 m/s, no strike
    !> keeps rolling, 0.1 N s slides and rolls again, 0.3 N s hops (flies, lands and goes
    !> on); at 0.15 m/s, 0.05 N s leaves it sliding at the end. Each case's measures are its
    !> own run's: the time in each mode adds up to the time reached; the rows' mode column
    !> (every output_step) agrees with the summary's switches (the rows see at most as many;
    !> without flight with the same parity: a slide between two rows is unseen, while an
    !> impact that bounces is a switch from flight to flight) and time sliding (the rows'
    !> intervals that start sliding, within one output step per switch and one for the run's
    !> last row); the case that keeps rolling never needed more friction than mu_static.
    subroutine test_modes(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: impulses(4) = [0.0_wp, 0.1_wp, 0.3_wp, 0.05_wp], &
            & speeds(4) = [1.0_wp, 1.0_wp, 1.0_wp, 0.15_wp]
        character(len=*), parameter :: expected(4) = [character(len=17) :: "keeps rolling", &
            & "slides_then_rolls", "hops", "slides_to_the_end"]
        !> The base scene's mu_static and output step [s]
        real(wp), parameter :: mu_static = 0.5_wp, output_step = 0.002_wp
        !> The times in the modes are differences of event times up to a few seconds: they add
        !> up to the time reached within a few roundings of it
        real(wp), parameter :: tol_sum = 1.0e-12_wp
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result
        type(job_type) :: job
        type(job_result_type) :: ran
        type(history_type) :: history, no_rows
        character(len=:), allocatable :: row
        real(wp) :: switches, sliding, rolling, flight, row_sliding
        integer :: c, k, mode, row_switches
        integer, allocatable :: modes(:)

        call read_study("data/no_slip_validity.nml", study, error)
        if (allocated(error)) return
        do c = 1, size(impulses)
            study%parameters(1)%lower = impulses(c)
            study%parameters(1)%upper = impulses(c)
            study%parameters(1)%count = 1
            study%parameters(2)%lower = speeds(c)
            study%parameters(2)%upper = speeds(c)
            study%parameters(2)%count = 1
            call plan_cases(study, plan)
            call run_case(study, plan, 1, row, result)
            call check(error, result%class == trim(expected(c)), "impulse " &
                & // to_text(impulses(c)) // " N s at " // to_text(speeds(c)) // " m/s: " &
                & // "class " // result%class // ", expected " // trim(expected(c)) // ": " // row)
            if (allocated(error)) return
            switches = result%values(measure_index("switches"))
            rolling = result%values(measure_index("t_rolling"))
            sliding = result%values(measure_index("t_sliding"))
            flight = result%values(measure_index("t_flight"))
            call check(error, result%known(measure_index("switches")) .and. abs(rolling &
                & + sliding + flight - result%values(measure_index("t_reached"))) <= tol_sum, &
                & "case " &
                & // to_text(c) // ": the times in the modes do not add up to the time " &
                & // "reached: " // row)
            if (allocated(error)) return
            ! the same run alone, its rows' mode column
            call load_job(study%scene_path, job, error, overrides=[ &
                & input_override_type("strike%impulse", trim(plan%texts(1, 1))), &
                & input_override_type("initial%speed", trim(plan%texts(2, 1)))])
            if (allocated(error)) return
            job%output_dir = ""
            job%quiet = .true.
            ! run_job adds rows to those the history holds
            history = no_rows
            call run_job(job, ran, error, history)
            if (allocated(error)) return
            mode = history%layout%column("mode")
            modes = nint(history%rows(mode, :history%count))
            row_switches = count(modes(2:) /= modes(:history%count - 1))
            row_sliding = 0.0_wp
            do k = 1, history%count - 1
                if (modes(k) == 1) row_sliding = row_sliding + history%rows(1, k + 1) &
                    & - history%rows(1, k)
            end do
            call check(error, row_switches <= nint(switches) .and. (flight > 0.0_wp .or. &
                & modulo(nint(switches) - row_switches, 2) == 0) .and. abs(row_sliding &
                & - sliding) <= output_step &
                & *(switches + 1.0_wp) .and. modes(history%count) &
                & == nint(result%values(measure_index("mode_end"))), "case " // to_text(c) &
                & // ": the rows' modes (" // to_text(row_switches) // " switches, " &
                & // to_text(row_sliding) // " s sliding, ending in mode " &
                & // to_text(modes(history%count)) // ") disagree with the measures: " // row)
            if (allocated(error)) return
            if (c == 1) then
                call check(error, nint(switches) == 0 .and. sliding == 0.0_wp &
                    & .and. result%values(measure_index("mu_max")) <= mu_static, "the case " &
                    & // "that keeps rolling switched, or needed more friction than " &
                    & // "mu_static: " // row)
            else
                call check(error, nint(switches) >= 1 .and. sliding > 0.0_wp, "case " &
                    & // to_text(c) // " never slid: " // row)
            end if
            if (allocated(error)) return
        end do
    end subroutine test_modes

    !> A study of data/two_spheres_thrown.adm, its second ball's MU_DYNAMIC 0.1 and 0.2 (the
    !> dataset's): the contact measures are over both CONTACTs. Each ball's slip stops at
    !> t* = 2 v0 / (7 mu g) (the dataset's comments): the first's at 0.0970827 s, the
    !> second's, at mu = 0.1, at 0.582 s, after the run's 0.4 s, and at 0.2 at 0.291248 s. So
    !> the switches are 1 and 2 (their sum), t_sliding the mean of the balls' sliding times
    !> ((t1* + 0.4)/2, then (t1* + t2*)/2) with t_rolling the rest of 0.4 s, mode_end 1 with
    !> the second still sliding and 0 with both rolling at the end, mu_max the first ball's
    !> mu 0.3 (a sliding ball's |F_t|/F_n is its mu; rolling needs none), fn_min m g.
    subroutine test_contacts_modes(error)
        type(error_type), allocatable, intent(out) :: error
        !> The switch times are roots located to the event tolerance at rtol 1e-10 (the
        !> two-spheres test measures 1e-11 s); bound 1e-9 s on their mean
        real(wp), parameter :: time_tol = 1.0e-9_wp
        !> mu_needed while sliding is |mu F_n| / F_n to rounding; bound 1e-12
        real(wp), parameter :: mu_tol = 1.0e-12_wp
        !> F_n = m g on the level table, to rounding of the multipliers (1e-14 of 9.81 N);
        !> bound 1e-10 relative
        real(wp), parameter :: fn_tol = 1.0e-10_wp
        real(wp), parameter :: g = 9.81_wp, end_time = 0.4_wp
        real(wp), parameter :: mu2(2) = [0.1_wp, 0.2_wp]
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result
        character(len=:), allocatable :: path, row
        real(wp) :: t1, t2, sliding
        integer :: c

        call write_study("test_study_contacts", [character(len=60) :: "&study", &
            & "    scene = 'data/two_spheres_thrown.adm' /", "&grid", &
            & "    contact%2%mu_dynamic = '0.1 0.2 2' /"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call plan_cases(study, plan)
        t1 = 2.0_wp*1.0_wp/(7.0_wp*0.3_wp*g)
        do c = 1, 2
            call run_case(study, plan, c, row, result)
            call check(error, result%outcome == outcome_completed, "case " // to_text(c) &
                & // ": " // row)
            if (allocated(error)) return
            t2 = min(2.0_wp*2.0_wp/(7.0_wp*mu2(c)*g), end_time)
            sliding = 0.5_wp*(t1 + t2)
            call check(error, result%values(measure_index("switches")), real(c, wp), &
                & "case " // to_text(c) // ": switches of both contacts: " // row)
            if (allocated(error)) return
            call check(error, result%values(measure_index("t_sliding")), sliding, "case " &
                & // to_text(c) // ": t_sliding, the balls' mean [s]: " // row, &
                & abs_tol=time_tol)
            if (allocated(error)) return
            call check(error, result%values(measure_index("t_rolling")), end_time - sliding, &
                & "case " // to_text(c) // ": t_rolling, the balls' mean [s]: " // row, &
                & abs_tol=time_tol)
            if (allocated(error)) return
            call check(error, result%values(measure_index("t_flight")), 0.0_wp, "case " &
                & // to_text(c) // ": t_flight [s]: " // row)
            if (allocated(error)) return
            call check(error, result%values(measure_index("mode_end")), real(2 - c, wp), &
                & "case " // to_text(c) // ": mode_end, the highest of the contacts': " // row)
            if (allocated(error)) return
            call check(error, result%values(measure_index("mu_max")), 0.3_wp, "case " &
                & // to_text(c) // ": mu_max, the first ball's mu: " // row, abs_tol=mu_tol)
            if (allocated(error)) return
            call check(error, result%values(measure_index("fn_min")), g, "case " &
                & // to_text(c) // ": fn_min, m g [N]: " // row, rel_tol=fn_tol)
            if (allocated(error)) return
        end do
    end subroutine test_contacts_modes

    !> data/no_slip_validity.nml's classes against the physics of three of its cases at
    !> 1 m/s, each asserted from runs, mu_static the study's own (its &grid value): the
    !> no-slip model's run of the same case (data/struck_rolling.nml, the same disk, strike
    !> and tolerances without friction's limit) says where rolling needs more friction than
    !> mu_static, and the case's own run what the contact did.
    !> - 0.025 N s: the no-slip run never needs more than mu_static F_n and its normal force
    !>   stays positive, so rolling is admissible throughout and Coulomb's contact never
    !>   leaves it: the case keeps rolling (its class the study's otherwise), no switch, and
    !>   its motion is the no-slip run's (theta_min the same).
    !> - 0.1 N s: the no-slip run needs more than mu_static F_n (its normal force positive),
    !>   so the rim must slide, starting where rolling's need first passes mu_static: the
    !>   case's first sliding row is the no-slip run's first row above mu_static (both runs are
    !>   the same motion until then); no flight; a sliding class.
    !> - 0.2 N s: the case's normal force reaches zero (fn_min 0) and the disk flies: every
    !>   pair of successive flight rows has the centre's vertical speed fall by g dt (a free
    !>   flight) or rise (an impact between them: the table only pushes), at least one a free
    !>   flight; it comes down and ends on the table (mode_end not flight); class hops.
    subroutine test_struck_physics(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: impulses(3) = [0.025_wp, 0.1_wp, 0.2_wp], speed = 1.0_wp
        !> The base scene's gravity [m/s^2] and output step [s]
        real(wp), parameter :: g = 9.81_wp, output_step = 0.002_wp
        !> theta_min of the rolling case against the no-slip run's [rad]: while the contact
        !> rolls, the Coulomb run integrates the same equations with the same steps (its mode
        !> events watch, and never fire), so the two agree to rounding; measured 0 (the same
        !> bits), bound 1e-12 rad (a single slide of 2 ms changes theta by far more)
        real(wp), parameter :: tol_theta = 1.0e-12_wp
        !> A free flight's change of the vertical speed over a row, zdot(k+1) - zdot(k) + g dt
        !> [m/s]: in flight zdot is linear in t, which BDF integrates exactly, so only rounding
        !> of speeds ~1 m/s remains; measured 3.0e-15, bound 1e-12 (a bounce, whose rebound
        !> is at least the capture's least resolved speed, changes it by far more)
        real(wp), parameter :: tol_flight = 1.0e-12_wp
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result
        type(history_type) :: coulomb, no_slip
        character(len=:), allocatable :: row
        real(wp) :: mu_static, change
        real(wp), allocatable :: modes(:), needed(:), fn(:), zdot(:), time(:)
        integer :: c, k, first_sliding, first_over, free_flights

        call read_study("data/no_slip_validity.nml", study, error)
        if (allocated(error)) return
        k = findloc([(study%parameters(c)%key == "mu_static", c = 1, &
            & size(study%parameters))], .true., dim=1)
        call check(error, k > 0, "the study gives contact%mu_static in its &grid")
        if (allocated(error)) return
        mu_static = study%parameters(k)%lower
        do c = 1, size(impulses)
            study%parameters(1)%lower = impulses(c)
            study%parameters(1)%upper = impulses(c)
            study%parameters(1)%count = 1
            study%parameters(2)%lower = speed
            study%parameters(2)%upper = speed
            study%parameters(2)%count = 1
            call plan_cases(study, plan)
            call run_case(study, plan, 1, row, result)
            call run_rows(study%scene_path, plan, coulomb, error)
            if (allocated(error)) return
            call run_rows("data/struck_rolling.nml", plan, no_slip, error)
            if (allocated(error)) return
            modes = coulomb%rows(coulomb%layout%column("mode"), :coulomb%count)
            needed = no_slip%rows(no_slip%layout%column("mu_needed"), :no_slip%count)
            fn = no_slip%rows(no_slip%layout%column("Fn"), :no_slip%count)
            select case (c)
            case (1)
                call check(error, maxval(needed) <= mu_static .and. minval(fn) > 0.0_wp, &
                    & "the weak strike's no-slip run needs at most mu_static " &
                    & // to_text(mu_static) // " (" // to_text(maxval(needed)) // ") and " &
                    & // "pushes throughout (Fn >= " // to_text(minval(fn)) // " N)")
                if (allocated(error)) return
                call check(error, result%class == study%otherwise .and. nint(result%values( &
                    & measure_index("switches"))) == 0, "rolling admissible throughout, yet " &
                    & // "the case did not keep rolling: " // row)
                if (allocated(error)) return
                call check(error, abs(result%values(measure_index("theta_min")) &
                    & - minval(no_slip%rows(no_slip%layout%part_column(1, coord_theta), &
                    & :no_slip%count))) <= tol_theta, "the rolling case's theta_min is not " &
                    & // "the no-slip run's: " // row)
                if (allocated(error)) return
            case (2)
                first_over = findloc(needed > mu_static, .true., dim=1)
                first_sliding = findloc(nint(modes) == 1, .true., dim=1)
                call check(error, first_over > 0 .and. minval(fn) > 0.0_wp, "the no-slip " &
                    & // "run of " // to_text(impulses(c)) // " N s needs more than mu_static " &
                    & // "with its normal force positive")
                if (allocated(error)) return
                call check(error, first_sliding == first_over .and. result%values( &
                    & measure_index("t_sliding")) > 0.0_wp .and. result%values( &
                    & measure_index("t_flight")) == 0.0_wp .and. index(result%class, &
                    & "slides") == 1, "rolling needs more than mu_static from t = " &
                    & // to_text(no_slip%rows(1, max(first_over, 1))) // " s, the case " &
                    & // "slides from row " // to_text(first_sliding) // " (the no-slip run " &
                    & // "passes mu_static at row " // to_text(first_over) // "): " // row)
                if (allocated(error)) return
            case (3)
                call check(error, result%class == "hops" .and. result%values( &
                    & measure_index("fn_min")) == 0.0_wp .and. result%values( &
                    & measure_index("t_flight")) > 0.0_wp .and. nint(result%values( &
                    & measure_index("mode_end"))) /= 2, "the strong strike's normal force " &
                    & // "did not vanish into a flight that lands: " // row)
                if (allocated(error)) return
                zdot = coulomb%rows(coulomb%layout%part_column(1, coord_zdot), :coulomb%count)
                time = coulomb%rows(1, :coulomb%count)
                free_flights = 0
                do k = 1, coulomb%count - 1
                    if (nint(modes(k)) /= 2 .or. nint(modes(k + 1)) /= 2) cycle
                    change = zdot(k + 1) - zdot(k) + g*(time(k + 1) - time(k))
                    call check(error, change >= -tol_flight, "in flight from t = " &
                        & // to_text(time(k)) // " s the centre fell faster than gravity " &
                        & // "pulls it: " // to_text(change) // " m/s")
                    if (allocated(error)) return
                    if (abs(change) <= tol_flight) free_flights = free_flights + 1
                end do
                call check(error, free_flights > 0, "no free flight between two rows: " // row)
                if (allocated(error)) return
            end select
        end do

    contains

        !> The case of the plan's first values, run alone on the scene at path, its rows.
        subroutine run_rows(path, plan, history, error)
            character(len=*), intent(in) :: path
            type(study_plan_type), intent(in) :: plan
            type(history_type), intent(out) :: history
            type(error_type), allocatable, intent(out) :: error
            type(job_type) :: job
            type(job_result_type) :: ran

            call load_job(path, job, error, overrides=[ &
                & input_override_type("strike%impulse", trim(plan%texts(1, 1))), &
                & input_override_type("initial%speed", trim(plan%texts(2, 1)))])
            if (allocated(error)) return
            job%output_dir = ""
            job%quiet = .true.
            call run_job(job, ran, error, history)
        end subroutine run_rows
    end subroutine test_struck_physics

    !> A study of data/coin.adm: its case at the dataset's own gravity is the dataset's own run,
    !> so its theta_min is that run's to the last bit; at another gravity it differs.
    subroutine test_dataset(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result
        type(job_type) :: job
        type(job_result_type) :: ran
        type(history_type) :: history
        character(len=:), allocatable :: path, row
        real(wp) :: scene_theta_min, case_theta_min(2)
        integer :: i

        call write_study("test_study_dataset", [character(len=60) :: "&study", &
            & "    scene = 'data/coin.adm' /", "&grid", "    accgrav%kgrav = '-9.81 -5 2' /"], &
            & path)
        call read_study(path, study, error)
        if (allocated(error)) return
        call plan_cases(study, plan)
        do i = 1, 2
            call run_case(study, plan, i, row, result)
            call check(error, result%outcome == outcome_completed, "case " // to_text(i) &
                & // ": " // trim(row))
            if (allocated(error)) return
            case_theta_min(i) = result%values(measure_index("theta_min"))
        end do
        call load_job("data/coin.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error, history)
        if (allocated(error)) return
        scene_theta_min = minval(history%rows(history%layout%part_column(1, coord_theta), &
            & :history%count))
        call check(error, case_theta_min(1) == scene_theta_min, "the dataset case's theta_min " &
            & // to_text(case_theta_min(1)) // " is not the dataset run's " &
            & // to_text(scene_theta_min))
        if (allocated(error)) return
        call check(error, case_theta_min(2) /= scene_theta_min, "gravity changed nothing")
    end subroutine test_dataset

    !> A study of data/coin.adm whose cases take a user's file, the generated rolling disk
    !> (ucon/adams/rolling_disk/ucosub.f, run apart): each case's measures are those of the
    !> dataset run one by one with that file and the case's gravity (load_job with the
    !> override and --ucosub's file, run_job), exactly: the same runs (CPU time apart).
    subroutine test_user_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: file = "ucon/adams/rolling_disk/ucosub.f"
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result, alone
        type(job_type) :: job
        type(job_result_type) :: ran
        type(history_type) :: histories(2)
        character(len=:), allocatable :: path, row
        integer :: i, k, cpu

        call write_study("test_study_user_file", [character(len=60) :: "&study", &
            & "    scene = 'data/coin.adm' /", "&grid", "    accgrav%kgrav = '-9.81 -5 2' /"], &
            & path)
        call read_study(path, study, error)
        if (allocated(error)) return
        study%routines = [user_file_type(file)]
        call prepare_study_routines(study, error)
        if (allocated(error)) return
        call plan_cases(study, plan)
        cpu = measure_index("cpu_s")
        do i = 1, 2
            call run_case(study, plan, i, row, result)
            call check(error, result%outcome == outcome_completed, "case " // to_text(i) &
                & // ": " // trim(row))
            if (allocated(error)) return
            call load_job("data/coin.adm", job, error, ucosub=file, overrides=[ &
                & input_override_type("accgrav%kgrav", trim(plan%texts(1, i)))])
            if (allocated(error)) return
            call check(error, job%user_file == file, "the job's routine is not the file")
            if (allocated(error)) return
            job%output_dir = ""
            job%quiet = .true.
            call run_job(job, ran, error, histories(i))
            if (allocated(error)) return
            call measure_case(ran%summary, histories(i), 0.0_wp, alone)
            call check(error, all(pack(result%values == alone%values, &
                & [(k /= cpu, k = 1, size(result%values))])) .and. all(result%known &
                & .eqv. alone%known), "case " // to_text(i) // ": the study's measures " &
                & // "differ from the run's alone")
            if (allocated(error)) return
            ! the routine runs in a child process, and so does the integration: the case's
            ! cpu_s counts the child's time, so it is at least the integration's CPU time of
            ! the same run alone (the child's own measure, the summary's). The same work's CPU
            ! time varies by tens of percent between runs on a loaded machine, never twofold;
            ! the parent alone (waiting for the child) spends a small fraction of it.
            call check(error, result%values(cpu) >= 0.5_wp*ran%summary%cpu_seconds, "case " &
                & // to_text(i) // ": cpu_s " // to_text(result%values(cpu)) // " s misses " &
                & // "the child's integration, " // to_text(ran%summary%cpu_seconds) // " s")
            if (allocated(error)) return
        end do
    end subroutine test_user_file

    !> A study's routines that cannot serve are refused before any case, in `--ucosub`'s
    !> words (a missing file, a name that is no built-in routine); a routine that stops the
    !> program makes every case a failed row whose message quotes the STOP, the study going on.
    subroutine test_user_file_faults(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(case_result_type) :: result
        character(len=:), allocatable :: path, row, message
        integer :: i

        call write_study("test_study_user_faults", [character(len=60) :: "&study", &
            & "    scene = 'data/coin.adm' /", "&grid", "    accgrav%kgrav = '-9.81 -5 2' /"], &
            & path)
        call read_study(path, study, error)
        if (allocated(error)) return
        study%routines = [user_file_type("no/such/ucosub.f")]
        call prepare_study_routines(study, error)
        message = "(none)"
        if (allocated(error)) message = error%message
        call check(error, index(message, "--ucosub no/such/ucosub.f: no such file") == 1, &
            & "a missing file's refusal: " // message)
        if (allocated(error)) return
        study%routines = [user_file_type("test/faulty_ucosubs/stops.f")]
        call prepare_study_routines(study, error)
        if (allocated(error)) return
        call plan_cases(study, plan)
        do i = 1, 2
            call run_case(study, plan, i, row, result)
            call check(error, result%outcome /= outcome_completed .and. index(result%message, &
                & "STOP") > 0, "case " // to_text(i) // ": " // trim(row))
            if (allocated(error)) return
        end do
    end subroutine test_user_file_faults

    !> Six cases of the no-slip study's scene (its strike makes the rows differ).
    subroutine small_study(study, error)
        type(study_type), intent(out) :: study
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        call write_study("test_study_small", [character(len=60) :: "&study", &
            & "    scene = 'data/struck_rolling.nml' /", "&grid", &
            & "    strike%impulse = '0.01 0.03 3'", "    initial%speed = '0.8 1.2 2' /", &
            & "&classify", "    steep = 'mu_max > 0.2' /"], path)
        call read_study(path, study, error)
    end subroutine small_study

    !> The two CSVs hold the same rows, sorted, but for their CPU times.
    logical function same_rows(a, b)
        character(len=*), intent(in) :: a, b
        character(len=:), allocatable :: rows_a(:), rows_b(:)
        integer :: i

        rows_a = sorted(without_cpu(csv_rows(a)))
        rows_b = sorted(without_cpu(csv_rows(b)))
        same_rows = size(rows_a) == size(rows_b)
        if (.not. same_rows) return
        do i = 1, size(rows_a)
            same_rows = same_rows .and. rows_a(i) == rows_b(i)
        end do
    end function same_rows

    function override(group, key, value) result(item)
        character(len=*), intent(in) :: group, key, value
        type(scene_override_type) :: item

        item%group = group
        item%key = key
        item%value = value
    end function override

    !> A case stopped by a watch is classed by the limit that stopped it: a fall of a re-based
    !> part and the rolling resistance holding a sliding rim are not the theta limit, and a
    !> limit the study has no word for is `stopped`
    subroutine test_stop_outcomes(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: limits(5) = [character(len=12) :: "theta_limit", &
            & "liftoff", "fall", "rolling_held", "redundancy"]
        character(len=*), parameter :: expected(5) = [character(len=12) :: "theta_limit", &
            & "liftoff", "fall", "rolling_held", "stopped"]
        type(run_summary_type) :: summary
        type(history_type) :: history
        type(case_result_type) :: result
        integer :: k

        do k = 1, size(limits)
            summary%status = status_stopped
            summary%limit = trim(limits(k))
            call measure_case(summary, history, 0.0_wp, result)
            call check(error, trim(outcome_words(result%outcome)) == trim(expected(k)), &
                & "a stop at limit " // trim(limits(k)) // " is classed " &
                & // trim(outcome_words(result%outcome)) // ", expected " // trim(expected(k)))
            if (allocated(error)) return
        end do
    end subroutine test_stop_outcomes

end module test_study_run
