! SPDX-License-Identifier: MIT
!> Force statements served by a user's routines (suite user-forces): SFOSUB and GFOSUB files
!> written for the test (test/user_forces/, reading SYSFNC, SYSARY and TIMGET), run apart in a
!> child process, against the same forces written as FUNCTION expressions and run here; a
!> model with two files of routines (ROUTINE=FILE::SFOSUB); MOTSUBs against their MOTIONs
!> written as expressions, on IDA and CVODE, and the start's check of their derivatives; a
!> DIFSUB (diff_lag.f, a first-order lag, explicit and IMPLICIT) against its closed form and
!> its expression twin on CVODE and IDA, and a crash planted in it; the faults of the UCOSUB
!> corpus planted in an SFOSUB, each a clean error naming the statement; and the refusals of a
!> model whose user routine is missing or of a kind rollcon does not run.
module test_user_forces
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_history, only : history_type
    use rollcon_job, only : job_type, user_file_type
    use rollcon_load, only : load_job, add_user_file
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : status_completed
    use rollcon_output_files, only : make_folders, write_text_file
    use rollcon_user_forces, only : system_function, system_array
    use rollcon_user_build, only : user_build_options_type
    use rollcon_user_routine_check, only : check_user_routines
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type
    use rollcon_dataset_ucon_check, only : check_dataset_ucons
    use command_runs, only : file_text, rollcon_program, run_rollcon, count_of
    use rollcon_integrator, only : chunk_steps_default
    use rollcon_grind_watch, only : grinds
    use rollcon_run_check, only : check_at_start
    use rollcon_run_settings, only : formulation_cvode, formulation_ida
    use rollcon_output_layout, only : coord_x, coord_y, coord_z, coord_theta, coord_psidot, &
        & coord_phidot
    implicit none
    private

    public :: collect_user_forces

    !> The test data
    character(len=*), parameter :: folder = "test/user_forces/"
    !> The tests' cache of compiled routines (the user-ucosub suite's)
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_user_forces"
    !> Largest difference allowed between a run served by user routines and its expression
    !> twin, in every coordinate and rate [m, rad, m/s, rad/s]: both runs integrate with IDA at
    !> rtol 1e-8, atol 1e-10 (the datasets' default) and their forces are the same functions of
    !> the state computed from the same measures; the routines' arithmetic may round otherwise
    !> than the expressions', which can change the step sequence, so the rows may differ by the
    !> integrators' global error: here bounded by 1e-6 (100 rtol over a 1 s run of motions of
    !> size 1). A wrong measure (VR's sign, TDISP in the wrong axes) differs by 1e-2 or more.
    real(wp), parameter :: twin_tolerance = 1.0e-6_wp

contains

    subroutine collect_user_forces(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("sfosub-gfosub-as-expressions", test_against_expressions), &
            & new_unittest("vfosub-as-expressions", test_vfosub), &
            & new_unittest("vtosub-as-expressions", test_vtosub), &
            & new_unittest("vtosub-returns-nan", test_vtosub_nan), &
            & new_unittest("sfosub-vfosub-virtual-mass", test_virtual_mass), &
            & new_unittest("vtosub-virtual-inertia", test_virtual_inertia), &
            & new_unittest("varsub-difsub-read-accelerations", test_accelerations_read), &
            & new_unittest("reqsub-reads-accelerations", test_reqsub_accelerations), &
            & new_unittest("motsub-reads-accelerations", test_motsub_accelerations), &
            & new_unittest("reqsub-as-expressions", test_reqsub), &
            & new_unittest("reqsub-returns-nan", test_reqsub_nan), &
            & new_unittest("reqsub-missing", test_reqsub_missing), &
            & new_unittest("varsub-as-expression", test_varsub), &
            & new_unittest("varsub-returns-nan", test_varsub_nan), &
            & new_unittest("varsub-in-motion-gcon", test_varsub_refused), &
            & new_unittest("difsub-lag-closed-form-and-twin", test_difsub), &
            & new_unittest("difsub-crashes", test_difsub_crashes), &
            & new_unittest("utilities-as-expressions", test_utilities), &
            & new_unittest("data-utilities-as-expressions", test_data_utilities), &
            & new_unittest("c-sfosub-as-fortran", test_c_routine), &
            & new_unittest("two-user-files", test_two_files), &
            & new_unittest("field-sfosub-gfosub-as-expressions", test_field_forces), &
            & new_unittest("sfosub-by-its-own-name", test_named_sfosub), &
            & new_unittest("ucons-of-two-files-as-gcons", test_ucon_two_files), &
            & new_unittest("ucon-of-c-by-routine", test_ucon_c_routine), &
            & new_unittest("ucon-routine-refusals", test_ucon_refusals), &
            & new_unittest("ucon-named-routine-checked-at-start", test_ucon_named_checked), &
            & new_unittest("sfosub-crashes", test_crashes), &
            & new_unittest("sfosub-stops", test_stops), &
            & new_unittest("sfosub-endless-loop", test_endless), &
            & new_unittest("sfosub-writes-outside-result", test_writes_outside), &
            & new_unittest("sfosub-returns-nan", test_nan), &
            & new_unittest("sfosub-divides-by-zero", test_divide_by_zero), &
            & new_unittest("sfosub-endless-initialisation", test_endless_init), &
            & new_unittest("sfosub-changes-read-only-arguments", test_changes_arguments), &
            & new_unittest("ucosub-stop-names-line", test_ucosub_stop_line), &
            & new_unittest("sfosub-missing", test_missing), &
            & new_unittest("routine-names-no-file", test_unknown_routine), &
            & new_unittest("motsub-refusals", test_motion_user), &
            & new_unittest("motsub-as-expression", test_motsub), &
            & new_unittest("motsub-two-files", test_motsub_two_files), &
            & new_unittest("motsub-velocity-acceleration", test_motsub_rates), &
            & new_unittest("motsub-velocity-wrong-rate", test_motsub_velocity_wrong_rate), &
            & new_unittest("motsub-wrong-rate", test_motsub_wrong_rate), &
            & new_unittest("motsub-crashes", test_motsub_crashes), &
            & new_unittest("motsub-reads-state", test_motsub_reads_state), &
            & new_unittest("utilities-outside-a-call", test_utilities_refuse), &
            & new_unittest("check-reports-implicit-typing", test_check_typing), &
            & new_unittest("check-clean-spring", test_check_clean), &
            & new_unittest("check-reports-hidden-state", test_check_hidden), &
            & new_unittest("failure-points-at-check", test_failure_points_at_check), &
            & new_unittest("grinding-points-at-check", test_grinding_points_at_check), &
            & new_unittest("sound-run-no-grinding", test_sound_run_no_grinding)]
    end subroutine collect_user_forces

    !> user_forces.adm (SFORCE/2 by sforce_spring.f's SFOSUB, GFORCE/1 by gforce_bushing.f's
    !> GFOSUB) gives the rows of user_forces_expressions.adm to twin_tolerance.
    subroutine test_against_expressions(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("user_forces", ["sforce_spring.f ", "gforce_bushing.f"], error)
    end subroutine test_against_expressions

    !> vforce.adm (VFORCE/4 by vforce_spring.f's VFOSUB, components in a turned marker's
    !> axes) gives the rows of vforce_expressions.adm to twin_tolerance.
    subroutine test_vfosub(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("vforce", ["vforce_spring.f"], error)
    end subroutine test_vfosub

    !> vtorque.adm (VTORQUE/5 by vtorque_spring.f's VTOSUB: a torsional spring-damper read
    !> through SYSFNC's AX, AY, AZ and SYSARY's RVEL, in a turned marker's axes) gives the rows
    !> of vtorque_expressions.adm to twin_tolerance: the torque lands in TX, TY, TZ, in the
    !> dataset's force times length.
    subroutine test_vtosub(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("vtorque", ["vtorque_spring.f"], error)
    end subroutine test_vtosub

    !> virtual_mass.adm: an SFOSUB returning -1.5 ACCZ and a VFOSUB returning (3, 0, 0) - 0.5
    !> TACC (virtual_mass.f) on parts of mass 2 and 1 falling under g = 9.81: the algebraic
    !> loop solved, part 2 falls at Z'' = -2 g/3.5 and part 3 moves at X'' = 3/1.5, Z'' =
    !> -g/1.5, on IDA (its residual reads u') and on CVODE (the ODE form's Newton iteration),
    !> and the rows are those of virtual_mass_expressions.adm (the virtual masses added to
    !> the parts, the loop gone) to twin_tolerance.
    !> Tolerance: the closed forms are quadratics in t, which BDF (IDA, CVODE's default) of
    !> order 2 and more reproduces to the nonlinear solves' residuals; the runs' local error
    !> tests (rtol 1e-8, atol 1e-10) keep the rows within twin_tolerance (1e-6) of them over
    !> the 1 s run. Leaving the loop out (the accelerations read as 0) moves part 2 by 1.2 m,
    !> and a virtual mass 1 % wrong by 2e-2 m.
    subroutine test_virtual_mass(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: g = 9.81_wp
        type(history_type) :: history
        integer :: formulations(2), f

        formulations = [formulation_ida, formulation_cvode]
        do f = 1, 2
            call run_user(folder // "virtual_mass.adm", ["virtual_mass.f"], 10.0_wp, history, &
                & error, formulation=formulations(f))
            if (allocated(error)) return
            call closed_form(history, 1, coord_z, 5.0_wp, 0.5_wp, -2.0_wp*g/3.5_wp, error)
            if (allocated(error)) return
            call closed_form(history, 2, coord_x, 1.0_wp, -0.2_wp, 3.0_wp/1.5_wp, error)
            if (allocated(error)) return
            call closed_form(history, 2, coord_z, 5.0_wp, 0.0_wp, -g/1.5_wp, error)
            if (allocated(error)) return
        end do
        call compare_twins("virtual_mass", ["virtual_mass.f"], error)
    end subroutine test_virtual_mass

    !> virtual_inertia.adm: a VTOSUB returning (0, 0, 0.6) - 0.05 RACC (virtual_inertia.f) on a
    !> part of IZZ 0.15 spinning about ground Z at 1 rad/s: its angular velocity about Z,
    !> psi' + phi' cos(theta), grows at 0.6/(0.15 + 0.05) = 3 rad/s^2 at every row, on IDA and
    !> CVODE, to twin_tolerance (the tolerance of test_virtual_mass: a linear rate, which the
    !> integrators reproduce to their nonlinear solves' residuals; the loop left out gives 4
    !> rad/s^2, a rate 1 % wrong 3e-2 rad/s at the end); and the rows are those of
    !> virtual_inertia_expressions.adm (IZZ 0.2, the torque 0.6) to twin_tolerance.
    subroutine test_virtual_inertia(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        real(wp), allocatable :: spin(:), time(:)
        integer :: formulations(2), f

        formulations = [formulation_ida, formulation_cvode]
        do f = 1, 2
            call run_user(folder // "virtual_inertia.adm", ["virtual_inertia.f"], 10.0_wp, &
                & history, error, formulation=formulations(f))
            if (allocated(error)) return
            time = history%column(1)
            spin = history%part_values(1, coord_psidot) + history%part_values(1, coord_phidot) &
                & *cos(history%part_values(1, coord_theta))
            call check(error, maxval(abs(spin - (1.0_wp + 3.0_wp*time))) <= twin_tolerance, &
                & "virtual_inertia (formulation " // to_text(formulations(f)) // "): the spin " &
                & // "differs from 1 + 3 t by " // to_text(maxval(abs(spin - (1.0_wp &
                & + 3.0_wp*time)))) // " rad/s")
            if (allocated(error)) return
        end do
        call compare_twins("virtual_inertia", ["virtual_inertia.f"], error)
    end subroutine test_virtual_inertia

    !> accelerations_read.adm: VARIABLE/3 = 1.5 ACCZ(20) and VARIABLE/5 = 0.5 ACCZ(30), served by
    !> accelerations_read.f's VARSUB, read by SFORCE/3's expression (-VARVAL(3)) and by
    !> SFORCE/4's SFOSUB (SYSFNC('VARVAL')): virtual masses on parts of mass 2 and 1 falling
    !> under g = 9.81, so part 2 falls at Z'' = -2 g/3.5 and part 3 at -g/1.5, on IDA (the
    !> VARSUB reads the residual's u') and CVODE (the ODE form's Newton iteration on the
    !> accelerations), and the VARIABLEs' columns are 1.5 and 0.5 times those; DIFF/6
    !> (explicit) and DIFF/7 (IMPLICIT), served by its DIFSUB, integrate ACCZ(20) and
    !> ACCZ(30) from 0: -2 g t/3.5 and -g t/1.5 (and their rates the accelerations); and the
    !> rows of part 2 are those of accelerations_read_expressions.adm (the masses added). On
    !> CVODE the first solve starts from zero accelerations: with the VARSUBs' partials left
    !> out of the loop's matrix its Newton iteration would contract by 0.75 (part 2) and 0.5
    !> (part 3) a step, and 20 steps would stop the run unsettled.
    !> Tolerances: the parts' closed forms to twin_tolerance, as test_virtual_mass (measured:
    !> 2e-15 on IDA, 7e-8 on CVODE; the VARIABLEs read as 0 move part 2 by 1.2 m); the
    !> VARIABLEs and DIFFs, a constant and a line the integrators reproduce to their
    !> nonlinear solves' residuals, to 1e-8 (measured 2e-15 on both; a DIFF reading the other
    !> part's acceleration is off by 0.9 t, one reading zero by 5.6 t, and a virtual mass 1 %
    !> off moves var3 by 5e-2).
    subroutine test_accelerations_read(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: g = 9.81_wp, tol = 1.0e-8_wp
        character(len=*), parameter :: names(6) = [character(len=9) :: "var3", "var5", &
            & "diff6", "diff6_dot", "diff7", "diff7_dot"]
        type(history_type) :: history
        real(wp), allocatable :: time(:), expected(:)
        real(wp) :: worst
        integer :: formulations(2), f, k, c

        formulations = [formulation_ida, formulation_cvode]
        do f = 1, 2
            call run_user(folder // "accelerations_read.adm", ["accelerations_read.f"], &
                & 10.0_wp, history, error, formulation=formulations(f))
            if (allocated(error)) return
            call closed_form(history, 1, coord_z, 5.0_wp, 0.5_wp, -2.0_wp*g/3.5_wp, error)
            if (allocated(error)) return
            call closed_form(history, 2, coord_z, 5.0_wp, 0.0_wp, -g/1.5_wp, error)
            if (allocated(error)) return
            time = history%column(1)
            do k = 1, size(names)
                select case (k)
                case (1)
                    expected = [(-1.5_wp*2.0_wp*g/3.5_wp, c = 1, size(time))]
                case (2)
                    expected = [(-0.5_wp*g/1.5_wp, c = 1, size(time))]
                case (3)
                    expected = -2.0_wp*g/3.5_wp*time
                case (4)
                    expected = [(-2.0_wp*g/3.5_wp, c = 1, size(time))]
                case (5)
                    expected = -g/1.5_wp*time
                case default
                    expected = [(-g/1.5_wp, c = 1, size(time))]
                end select
                c = history%layout%column(trim(names(k)))
                if (c == 0) then
                    call fatal_error(error, "no column " // trim(names(k)))
                    return
                end if
                worst = maxval(abs(history%rows(c, :history%count) - expected))
                call check(error, worst <= tol, "accelerations_read (formulation " &
                    & // to_text(formulations(f)) // "): " // trim(names(k)) // " differs " &
                    & // "from its closed form by " // to_text(worst))
                if (allocated(error)) return
            end do
        end do
        call compare_twins("accelerations_read", ["accelerations_read.f"], error)
    end subroutine test_accelerations_read

    !> request_accelerations.adm: REQUEST/7 served by accelerations_read.f's REQSUB (marker
    !> 21's TACC and RACC through SYSARY) and REQUEST/8 the same six accelerations written as
    !> ACCX ... WDTZ, in one run on IDA and on CVODE: at every row the REQSUB's columns are the
    !> expressions'. Both are read at the row from the same accelerations with the same
    !> procedure (rollcon_marker_acceleration) and the dataset's units are 1, so they agree to
    !> the last bit but for rounding: 1e-13 on values up to 9. Each column moves by more than
    !> 1e-2 over the run (a constant could not tell a wrong component); accelerations read as
    !> zero, or another marker's, differ by 0.8 or more.
    subroutine test_reqsub_accelerations(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: columns(6) = [character(len=2) :: "f2", "f3", "f4", &
            & "f6", "f7", "f8"]
        type(history_type) :: history
        real(wp) :: largest
        integer :: formulations(2), f, k, user, expression

        formulations = [formulation_ida, formulation_cvode]
        do f = 1, 2
            call run_user(folder // "request_accelerations.adm", ["accelerations_read.f"], &
                & 10.0_wp, history, error, formulation=formulations(f))
            if (allocated(error)) return
            do k = 1, size(columns)
                user = history%layout%column("req7_" // columns(k))
                expression = history%layout%column("req8_" // columns(k))
                if (user == 0 .or. expression == 0) then
                    call fatal_error(error, "no column req7_" // columns(k) // " or req8_" &
                        & // columns(k))
                    return
                end if
                largest = maxval(abs(history%rows(user, :history%count) &
                    & - history%rows(expression, :history%count)))
                call check(error, largest <= 1.0e-13_wp, "formulation " &
                    & // to_text(formulations(f)) // ": req7_" // columns(k) // ", the " &
                    & // "REQSUB's, differs from the expression's by " // to_text(largest))
                if (allocated(error)) return
                call check(error, maxval(history%rows(user, :history%count)) &
                    & - minval(history%rows(user, :history%count)) > 1.0e-2_wp, "req7_" &
                    & // columns(k) // " hardly moves over the run")
                if (allocated(error)) return
            end do
        end do
    end subroutine test_reqsub_accelerations

    !> A MOTSUB reading an acceleration (SYSARY('TACC')) is refused before the run, naming the
    !> MOTION, its line, the markers and ADAMS's rule (a MOTSUB calls no SYSFNC or SYSARY).
    subroutine test_motsub_accelerations(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "motion.adm", ["faulty/motsub_accelerations.f"], 10.0_wp, &
            & history, run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "motion.adm:17: MOTION/1: its MOTSUB of", &
            & "read accelerations through SYSFNC or SYSARY (markers 31)", &
            & "a MOTSUB may not call SYSFNC or SYSARY (ADAMS's rule"], error)
    end subroutine test_motsub_accelerations

    !> Coordinate c of the p-th moving part at every row against x0 + v0 t + a t^2/2, and its
    !> rate against v0 + a t, within twin_tolerance (test_virtual_mass).
    subroutine closed_form(history, p, c, x0, v0, a, error)
        type(history_type), intent(in) :: history
        integer, intent(in) :: p, c
        real(wp), intent(in) :: x0, v0, a
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: time(:)
        real(wp) :: position, rate

        time = history%column(1)
        position = maxval(abs(history%part_values(p, c) - (x0 + v0*time + 0.5_wp*a*time**2)))
        rate = maxval(abs(history%part_values(p, c + 6) - (v0 + a*time)))
        call check(error, max(position, rate) <= twin_tolerance .and. time(history%count) &
            & > 0.99_wp, "part " // to_text(p) // ", coordinate " // to_text(c) &
            & // ": differs from its closed form by " // to_text(position) // " (and its " &
            & // "rate by " // to_text(rate) // ") over " // to_text(history%count) // " rows")
    end subroutine closed_form

    !> A VTOSUB returning NaN in TY after t = 0.1 s: the clean error of an SFOSUB's NaN,
    !> naming the file, line and statement, the routine, the values and a TIME past 0.1.
    subroutine test_vtosub_nan(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "vtorque.adm", ["faulty/vtosub_nan.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=60) :: &
            & "vtorque.adm:10: VTORQUE/5: its VTOSUB of", "faulty/vtosub_nan.f", &
            & ", NaN, ", ") at TIME = 0.1", "a force must be finite"], error)
    end subroutine test_vtosub_nan

    !> request.adm (REQUEST/7 by request_measures.f's REQSUB: TDISP through SYSARY, WX, WY,
    !> WZ through SYSFNC, in a turned marker's axes) gives the columns req7_f2, _f3, _f4, _f6,
    !> _f7, _f8 of request_expressions.adm (F2 ... F8 written as those measures) at every row.
    !> The REQUEST changes nothing of the motion, so both runs integrate the same equations
    !> with the same arithmetic and their part columns are equal to the last bit; the request's
    !> columns then differ only by the rounding of the unit scalings (1 here) and of PAR(3)
    !> times the measure: 1e-13 bounds that on values of size 1 to 5 (2.5 times rates of 2),
    !> and a component in the wrong axes or a wrong sign differs by 1e-2 or more.
    subroutine test_reqsub(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: user, expressions
        real(wp) :: largest, d
        integer :: k, worst, u_column, e_column, row
        character(len=*), parameter :: columns(6) = [character(len=7) :: "req7_f2", &
            & "req7_f3", "req7_f4", "req7_f6", "req7_f7", "req7_f8"]

        call run_twins("request", ["request_measures.f"], user, expressions, error)
        if (allocated(error)) return
        call part_difference(user, expressions, largest, worst)
        call check(error, largest == 0.0_wp, "the part columns differ by " // to_text(largest))
        if (allocated(error)) return
        do k = 1, size(columns)
            u_column = user%layout%column(columns(k))
            e_column = expressions%layout%column(columns(k))
            if (u_column == 0 .or. e_column == 0) then
                call fatal_error(error, "no column " // columns(k) // " (REQSUB run: " &
                    & // to_text(u_column) // ", expressions: " // to_text(e_column) // ")")
                return
            end if
            largest = 0.0_wp
            do row = 1, user%count
                d = abs(user%rows(u_column, row) - expressions%rows(e_column, row))
                largest = max(largest, d)
            end do
            call check(error, largest <= 1.0e-13_wp, columns(k) // ": the REQSUB's column " &
                & // "differs from the expression's by " // to_text(largest))
            if (allocated(error)) return
            ! the column moves: a constant (or a zero) could not tell a wrong component
            call check(error, maxval(user%rows(u_column, :user%count)) &
                & - minval(user%rows(u_column, :user%count)) > 1.0e-2_wp, columns(k) &
                & // " hardly moves over the run")
            if (allocated(error)) return
        end do
    end subroutine test_reqsub

    !> A REQSUB returning NaN in RESULT(3) after t = 0.1 s: a clean error naming the file, line
    !> and REQUEST, the routine, the values and a TIME past 0.1.
    subroutine test_reqsub_nan(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "request.adm", ["faulty/reqsub_nan.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=60) :: &
            & "request.adm:12: REQUEST/7: its REQSUB of", "faulty/reqsub_nan.f", &
            & ", NaN, ", ") at TIME = 0.1", "a request's values must be finite"], error)
    end subroutine test_reqsub_nan

    !> request.adm given a file with no REQSUB: refused naming the REQUEST, its line and what
    !> to give.
    subroutine test_reqsub_missing(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "request.adm", ["vtorque_spring.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "request.adm:12: REQUEST/7 FUNCTION=USER(...): no REQSUB serves it", &
            & "SUBROUTINE REQSUB"], error)
    end subroutine test_reqsub_missing

    !> variable.adm (SFORCE/2 reading VARVAL(3), VARIABLE/3 by variable_stretch.f's VARSUB:
    !> DM through SYSFNC less PAR(3)) gives the rows of variable_expressions.adm (VARIABLE/3 =
    !> DM(20, 2) - 1) to twin_tolerance in every part coordinate and rate, and its column var3
    !> the twin's to varsub_tolerance. The equations are the same functions of the state; a
    !> VARSUB's partials are differences where the expression's are exact (the force-partials
    !> suite), which may change the corrector's iterations and so the step sequence, not what
    !> the integrator converges to: the rows may differ by the integrators' global error
    !> (twin_tolerance, above). var3 is DM - 1 of the same rows, so it differs by no more than
    !> the positions: varsub_tolerance = twin_tolerance. A wrong free length (PAR(3) = 1.01)
    !> moves the rows by 0.086.
    subroutine test_varsub(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: varsub_tolerance = twin_tolerance
        type(history_type) :: user, expressions
        type(job_type) :: job
        type(job_result_type) :: ran
        real(wp) :: largest
        integer :: u_column, e_column

        call compare_twins("variable", ["variable_stretch.f"], error)
        if (allocated(error)) return
        call run_user(folder // "variable.adm", ["variable_stretch.f"], 10.0_wp, user, error)
        if (allocated(error)) return
        call load_job(folder // "variable_expressions.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error, expressions)
        if (allocated(error)) return
        u_column = user%layout%column("var3")
        e_column = expressions%layout%column("var3")
        if (u_column == 0 .or. e_column == 0 .or. user%count /= expressions%count) then
            call fatal_error(error, "no column var3, or not as many rows (VARSUB run: column " &
                & // to_text(u_column) // ", " // to_text(user%count) // " rows; expression: " &
                & // to_text(e_column) // ", " // to_text(expressions%count) // ")")
            return
        end if
        largest = maxval(abs(user%rows(u_column, :user%count) &
            & - expressions%rows(e_column, :expressions%count)))
        call check(error, largest <= varsub_tolerance, "var3: the VARSUB's value differs " &
            & // "from the expression's by " // to_text(largest))
        if (allocated(error)) return
        ! the spring stretches and relaxes: a constant could not tell a wrong value
        call check(error, maxval(user%rows(u_column, :user%count)) &
            & - minval(user%rows(u_column, :user%count)) > 1.0e-2_wp, "var3 hardly moves")
    end subroutine test_varsub

    !> A VARSUB returning NaN after t = 0.1 s: a clean error naming the file, line and
    !> VARIABLE, the routine, the value and a TIME past 0.1.
    subroutine test_varsub_nan(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "variable.adm", ["faulty/varsub_nan.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=60) :: &
            & "variable.adm:10: VARIABLE/3: its VARSUB of", "faulty/varsub_nan.f", &
            & "returned VALUE = NaN at TIME = 0.1", "a VARIABLE's value must be finite"], error)
    end subroutine test_varsub_nan

    !> DIFF/3 (explicit) and DIFF/4 (IMPLICIT) served by diff_lag.f's DIFSUB, the lag of a
    !> part moving at 1 m/s along x (X = t) with tau = 0.5 s: both are x = t - tau (1 -
    !> e^(-t/tau)), x' = 1 - e^(-t/tau). On CVODE and on IDA, the columns diff3, diff3_dot,
    !> diff4, diff4_dot against that closed form and against the expression twin (the diff-runs
    !> suite's lag, FUNCTION = (DX(20) - DIF(3))/0.5 and 0.5*DIF1(4) - (DX(20) - DIF(4))).
    !> At ERROR = 1e-10 over 2 s, measured from the closed form: 1.9e-9 (CVODE) and 1.0e-9
    !> (IDA) for the states, twice that for the rates; tol = 1.5e-8 leaves a factor of 4 over
    !> the larger (a tau 1 % off moves the state by 5e-3). From the twin: 0 and 4.4e-16 (the
    !> routine's arithmetic is the expression's; its differenced partials, 4e-11 from the
    !> exact ones, steer only the corrector's iterations): held to 1e-10, a tenth of the
    !> integrators' own error, so a run that wandered within that error would fail.
    subroutine test_difsub(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tol = 1.5e-8_wp, twin_tol = 1.0e-10_wp, tau = 0.5_wp
        character(len=*), parameter :: formulations(2) = ["CVODE", "IDA  "]
        character(len=*), parameter :: nl = new_line("a")
        character(len=*), parameter :: mover = "lag" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, " &
            & // "VX = 1" // nl // "MARKER/20, PART = 2" // nl &
            & // "ACCGRAV/IGRAV = 0, JGRAV = 0, KGRAV = 0" // nl
        character(len=*), parameter :: users = "DIFF/3, FUNCTION = USER(20, 0.5, 0), IC = 0" &
            & // nl // "DIFF/4, FUNCTION = USER(20, 0.5, 1), IC = 0, 1, IMPLICIT" // nl
        character(len=*), parameter :: expressions = "DIFF/3, FUNCTION = (DX(20) - DIF(3))/0.5" &
            & // ", IC = 0" // nl // "DIFF/4, FUNCTION = 0.5*DIF1(4) - (DX(20) - DIF(4)), " &
            & // "IC = 0, 1, IMPLICIT" // nl
        character(len=*), parameter :: names(4) = [character(len=9) :: "diff3", "diff3_dot", &
            & "diff4", "diff4_dot"]
        type(history_type) :: user, twin
        type(job_type) :: job
        type(job_result_type) :: ran
        character(len=:), allocatable :: tail, path
        real(wp) :: t, closed(4), worst(4), apart(4)
        integer :: f, k, c, uc, ec

        call make_folders(scratch, error)
        if (allocated(error)) return
        do f = 1, size(formulations)
            tail = "INTEGRATOR/ERROR = 1e-10, FORMULATION = " // trim(formulations(f)) // nl &
                & // "SIMULATE/DYNAMIC, END = 2, STEPS = 100" // nl // "END" // nl
            path = scratch // "/difsub_" // trim(formulations(f)) // ".adm"
            call write_text_file(path, mover // users // tail, error)
            if (allocated(error)) return
            call run_user(path, ["diff_lag.f"], 10.0_wp, user, error)
            if (allocated(error)) return
            path = scratch // "/difsub_" // trim(formulations(f)) // "_expressions.adm"
            call write_text_file(path, mover // expressions // tail, error)
            if (allocated(error)) return
            call load_job(path, job, error)
            if (allocated(error)) return
            job%output_dir = ""
            job%quiet = .true.
            ! (a fresh history: run_job adds to the one it is given)
            twin = history_type()
            call run_job(job, ran, error, twin)
            if (allocated(error)) return
            call check(error, user%count == 101 .and. twin%count == 101, &
                & trim(formulations(f)) // ": 101 rows each (" // to_text(user%count) // ", " &
                & // to_text(twin%count) // ")")
            if (allocated(error)) return
            worst = 0.0_wp
            apart = 0.0_wp
            do c = 1, 4
                uc = user%layout%column(trim(names(c)))
                ec = twin%layout%column(trim(names(c)))
                call check(error, uc > 0 .and. ec > 0, "column " // trim(names(c)))
                if (allocated(error)) return
                do k = 1, user%count
                    t = user%rows(1, k)
                    closed = [t - tau*(1.0_wp - exp(-t/tau)), 1.0_wp - exp(-t/tau), &
                        & t - tau*(1.0_wp - exp(-t/tau)), 1.0_wp - exp(-t/tau)]
                    worst(c) = max(worst(c), abs(user%rows(uc, k) - closed(c)))
                    apart(c) = max(apart(c), abs(user%rows(uc, k) - twin%rows(ec, k)))
                end do
            end do
            call check(error, all(worst <= tol) .and. all(apart <= twin_tol), &
                & trim(formulations(f)) // ": the DIFSUB's columns from the closed form: " &
                & // "explicit x " // to_text(worst(1)) // ", x' " // to_text(worst(2)) &
                & // "; implicit x " // to_text(worst(3)) // ", x' " // to_text(worst(4)) &
                & // "; from the expression twin: " // to_text(maxval(apart)))
            if (allocated(error)) return
        end do
    end subroutine test_difsub

    !> A crash planted in a DIFSUB (a write through a wild index after the initialisation
    !> call): the clean error of an SFOSUB's crash, naming the DIFF and the routine's call.
    subroutine test_difsub_crashes(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=*), parameter :: nl = new_line("a")
        character(len=:), allocatable :: path

        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/difsub_crash.adm"
        call write_text_file(path, "lag" // nl // "PART/1, GROUND" // nl // "MARKER/1, " &
            & // "PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, VX = 1" // nl &
            & // "MARKER/20, PART = 2" // nl // "DIFF/3, FUNCTION = USER(20, 0.5), IC = 0" &
            & // nl // "SIMULATE/DYNAMIC, END = 1, STEPS = 10" // nl // "END" // nl, error)
        if (allocated(error)) return
        call run_user(path, ["faulty/difsub_crashes.f"], 10.0_wp, history, run_error)
        call expect_message(run_error, [character(len=70) :: &
            & "difsub_crash.adm:6: DIFF/3: the process was killed by SIGSEGV", &
            & "inside DIFSUB call", &
            & "IFLAG = .FALSE."], error)
    end subroutine test_difsub_crashes

    !> A MOTION and a GCON reading a VARSUB's VARIABLE are refused, naming the statement and
    !> line (their derivatives are taken exactly; a VARSUB's are not known).
    subroutine test_varsub_refused(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "variable_motion.adm", ["variable_stretch.f"], 10.0_wp, &
            & history, run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "variable_motion.adm:11: MOTION/1 FUNCTION: VARVAL(3) is the value of a VARSUB", &
            & "a MOTION's function"], error)
        if (allocated(error)) return
        call run_user(folder // "variable_gcon.adm", ["variable_stretch.f"], 10.0_wp, &
            & history, run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "variable_gcon.adm:10: GCON/1 FUNCTION: VARVAL(3) is the value of a VARSUB", &
            & "a GCON's function"], error)
    end subroutine test_varsub_refused

    !> utilities.adm (SFORCE/2 by sforce_utilities.f's SFOSUB, calling AKISPL and CUBSPL on
    !> the model's SPLINE/3, STEP and RCNVRT) gives the rows of utilities_expressions.adm,
    !> where the same force is written with the expression functions AKISPL, CUBSPL and STEP
    !> and the Euler parameter in closed form, to twin_tolerance. A spline read at the wrong
    !> x, a STEP of the wrong shape or a wrong Euler parameter moves the part by 1e-3 or more.
    subroutine test_utilities(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("utilities", ["sforce_utilities.f"], error)
    end subroutine test_utilities

    !> data.adm (SFORCE/2 by sforce_data.f's SFOSUB, reading its constants from ARRAY/5 with
    !> GTARAY and its sense from STRING/7 with GTSTRG, and checking GTARAY's and GTSTRG's
    !> answers for a missing id and a short STRING, ISTRNG's and RSTRNG's texts, as it goes:
    !> a wrong answer stops the run) gives the rows of data_expressions.adm, the same force
    !> with the numbers written in, to twin_tolerance. A number read from the wrong place, or
    !> the sense reversed, moves the part by far more.
    subroutine test_data_utilities(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("data", ["sforce_data.f"], error)
    end subroutine test_data_utilities

    !> spring.adm with sforce_spring.c, the C twin of sforce_spring.f (the prototypes of
    !> docs/datasets.md), compiled by the system's C compiler: the rows of the Fortran
    !> routine's run, bit for bit. Both routines do the same IEEE operations in the same
    !> order (no reassociation at -O2 in either compiler) on the same SYSFNC values, so the
    !> integrator sees the same numbers and takes the same steps: any difference is a
    !> difference of the calls (an argument misread, a LOGICAL misread).
    subroutine test_c_routine(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: c_run, fortran_run
        real(wp) :: largest
        integer :: worst

        call run_user(folder // "spring.adm", ["sforce_spring.c"], 10.0_wp, c_run, error)
        if (allocated(error)) return
        call run_user(folder // "spring.adm", ["sforce_spring.f"], 10.0_wp, fortran_run, error)
        if (allocated(error)) return
        if (c_run%count /= fortran_run%count .or. c_run%count < 101) then
            call fatal_error(error, to_text(c_run%count) // " rows with the C routine, " &
                & // to_text(fortran_run%count) // " with the Fortran one")
            return
        end if
        call part_difference(c_run, fortran_run, largest, worst)
        call check(error, largest == 0.0_wp, "the C routine's rows differ from the " &
            & // "Fortran routine's by " // to_text(largest))
    end subroutine test_c_routine

    !> two_files.adm: SFORCE/2 by the first file's SFOSUB (the model's own), SFORCE/3 by the
    !> SFOSUB of the second file, which its ROUTINE=sforce_cubic::SFOSUB names (and which reads
    !> TIMGET): the rows of two_files_expressions.adm to twin_tolerance.
    subroutine test_two_files(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("two_files", ["sforce_spring.f", "sforce_cubic.f "], error)
    end subroutine test_two_files

    !> field_forces.adm, the field's user_force_routines.adm as it came (GFORCE/1 with
    !> USER(21, 20, 21, 20, 0.5, 0, 1000, 10, 1000, 10, 100, 1, 1), SFORCE/2 with USER(20, 2,
    !> 1000, 10, 1)), runs with field_forces.f's GFOSUB and SFOSUB (reading SYSARY's TDISP and
    !> TVEL, SYSFNC's WX, WY, WZ) and gives the rows of its expression twin to twin_tolerance.
    !> Its part starts at rest and only bounces on the spring, where the GFOSUB's offset stays
    !> at its free value; so the same pair is run again with the part thrown and spinning
    !> (VX = 0.4, VZ = -0.3, WX = 1, WZ = 2 added to both), where every term of the GFOSUB acts.
    subroutine test_field_forces(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: at_rest = "QG = 0, 0, 1" // new_line("a"), &
            & thrown = "QG = 0, 0, 1, VX = 0.4, VZ = -0.3, WX = 1, WZ = 2" // new_line("a")
        type(job_type) :: job
        type(job_result_type) :: ran
        type(history_type) :: user, expressions
        real(wp) :: largest
        integer :: worst

        call compare_twins("field_forces", ["field_forces.f"], error)
        if (allocated(error)) return
        call make_folders(scratch, error)
        if (allocated(error)) return
        call write_text_file(scratch // "/field_thrown.adm", replaced(file_text(folder &
            & // "field_forces.adm"), at_rest, thrown), error)
        if (allocated(error)) return
        call write_text_file(scratch // "/field_thrown_expressions.adm", replaced(file_text( &
            & folder // "field_forces_expressions.adm"), at_rest, thrown), error)
        if (allocated(error)) return
        call run_user(scratch // "/field_thrown.adm", [character(len=20) :: "field_forces.f"], &
            & 10.0_wp, user, error)
        if (allocated(error)) return
        call load_job(scratch // "/field_thrown_expressions.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error, expressions)
        if (allocated(error)) return
        call part_difference(user, expressions, largest, worst)
        call check(error, user%count == expressions%count .and. user%count >= 101 .and. &
            & largest <= twin_tolerance, "thrown: " // to_text(user%count) // " rows, " &
            & // to_text(expressions%count) // " of the twin; they differ by " &
            & // to_text(largest) // " in coordinate " // to_text(worst) // " of part 2")
    end subroutine test_field_forces

    !> two_files.adm with SFORCE/3 served by sforce_harden.f's HARDEN, a subroutine of its own
    !> name with SFOSUB's calling sequence (ROUTINE=sforce_harden::HARDEN): the rows of
    !> two_files_expressions.adm to twin_tolerance, as with the routine named SFOSUB.
    subroutine test_named_sfosub(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: ran
        type(history_type) :: user, expressions
        character(len=:), allocatable :: path
        real(wp) :: largest
        integer :: worst

        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/two_files_named.adm"
        call write_text_file(path, replaced(file_text(folder // "two_files.adm"), &
            & "ROUTINE = sforce_cubic::SFOSUB", "ROUTINE = sforce_harden::HARDEN"), error)
        if (allocated(error)) return
        call run_user(path, [character(len=40) :: "sforce_spring.f", "sforce_harden.f"], &
            & 10.0_wp, user, error)
        if (allocated(error)) return
        call load_job(folder // "two_files_expressions.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error, expressions)
        if (allocated(error)) return
        call part_difference(user, expressions, largest, worst)
        call check(error, user%count == expressions%count .and. user%count >= 101 .and. &
            & largest <= twin_tolerance, "HARDEN: " // to_text(user%count) // " rows, " &
            & // to_text(expressions%count) // " of the twin; they differ by " &
            & // to_text(largest) // " in coordinate " // to_text(worst) // " of part 2")
    end subroutine test_named_sfosub

    !> ucon_two_files.adm: UCON/1 served by ucon_turn_velocity.f's TURNVEL (a velocity
    !> constraint), UCON/2 by ucon_circle.f's CIRCLE (a position constraint), each named by
    !> ROUTINE=FILE::NAME, neither called UCOSUB: the rows of its GCON twin
    !> ucon_two_files_expressions.adm to twin_tolerance, and the exact motion X = R cos(W t),
    !> Y = R sin(W t) at the end (one turn, back at (0.1, 0) m): within 2e-7 m, the bound
    !> turntable.adm's one-turn run meets with the same steps (2.2e-8 m measured there), so a
    !> tenfold loss is caught; a constraint served by the wrong routine (both by TURNVEL, say)
    !> leaves the circle by far more.
    subroutine test_ucon_two_files(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: user, expressions
        real(wp) :: largest, x_end, y_end
        real(wp), allocatable :: x(:), y(:)
        integer :: worst

        call run_twins("ucon_two_files", [character(len=40) :: "ucon_turn_velocity.f", &
            & "ucon_circle.f"], user, expressions, error)
        if (allocated(error)) return
        call part_difference(user, expressions, largest, worst)
        call check(error, largest <= twin_tolerance, "ucon_two_files: the runs differ by " &
            & // to_text(largest) // " in coordinate " // to_text(worst) // " of part 2")
        if (allocated(error)) return
        x = user%part_values(1, coord_x)
        y = user%part_values(1, coord_y)
        x_end = x(size(x))
        y_end = y(size(y))
        call check(error, abs(x_end - 0.1_wp) <= 2.0e-7_wp .and. abs(y_end) <= 2.0e-7_wp, &
            & "after one turn (X, Y) = (" // to_text(x_end) // ", " // to_text(y_end) &
            & // ") m, not (0.1, 0) within 2e-7 m")
    end subroutine test_ucon_two_files

    !> ucon_two_files.adm with ucon_circle.c, the C twin of ucon_circle.f (CIRCLE as circle_,
    !> every argument by address, XMATRX in column order), given in its place: the same
    !> ROUTINE=ucon_circle::circle names it (the file's name without folder and extension).
    !> Run with the check at the start, its rows are the Fortran twin's bit for bit: both do
    !> the same IEEE operations in the same order (X*X + Y*Y - R*R, 2*X, 2*Y; no FMA at either
    !> compiler's -O2 on x86-64's base instructions), so the integrator takes the same steps
    !> and any difference is one of the call (an argument misread, XMATRX transposed or
    !> misplaced). `rollcon check` of the C file on the model (check_dataset_ucons): clean, 2
    !> UCONs, UCON/2 named with its line and ROUTINE as the C file's.
    subroutine test_ucon_c_routine(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: c_run, fortran_run
        type(user_build_options_type) :: build
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        type(ucon_request_type), allocatable :: given(:)
        character(len=:), allocatable :: library, notes
        real(wp) :: largest
        integer :: worst, checked
        logical :: from_cache

        call run_user(folder // "ucon_two_files.adm", [character(len=40) :: &
            & "ucon_turn_velocity.f", "ucon_circle.c"], 10.0_wp, c_run, error, checked=.true.)
        if (allocated(error)) return
        call run_user(folder // "ucon_two_files.adm", [character(len=40) :: &
            & "ucon_turn_velocity.f", "ucon_circle.f"], 10.0_wp, fortran_run, error, &
            & checked=.true.)
        if (allocated(error)) return
        if (c_run%count /= fortran_run%count .or. c_run%count < 101) then
            call fatal_error(error, to_text(c_run%count) // " rows with the C routine, " &
                & // to_text(fortran_run%count) // " with the Fortran one")
            return
        end if
        call part_difference(c_run, fortran_run, largest, worst)
        call check(error, largest == 0.0_wp, "the C routine's rows differ from the " &
            & // "Fortran routine's by " // to_text(largest) // " in coordinate " &
            & // to_text(worst))
        if (allocated(error)) return
        build%cache_dir = test_cache
        options%states = 5
        allocate(given(0))
        call check_dataset_ucons([user_file_type(folder // "ucon_turn_velocity.f"), &
            & user_file_type(folder // "ucon_circle.c")], folder // "ucon_two_files.adm", &
            & build, given, options, 10.0_wp, checked, report, library, from_cache, notes, &
            & error)
        if (allocated(error)) return
        call check(error, checked == 2 .and. report%clean() .and. report%ucons(2)%statement &
            & == "UCON/2 (line 10, ROUTINE=ucon_circle::circle of " // folder &
            & // "ucon_circle.c)" .and. report%ucons(2)%states == 5, to_text(checked) &
            & // " UCONs checked, " // to_text(report%findings()) // " finding(s); UCON/2: " &
            & // report%ucons(2)%statement)
    end subroutine test_ucon_c_routine

    !> The refusals of UCON routines of several files, each naming the file or the statement
    !> and its line: a UCON naming no ROUTINE when two files define UCOSUB (turntable.adm with
    !> turntable.f and its slipped twin); a file whose UCOSUB serves no UCON (ucon_two_files.adm
    !> given turntable.f too); ROUTINE=FILE::NAME naming no subroutine of the file.
    subroutine test_ucon_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=:), allocatable :: path

        call run_user("test/turntable/turntable.adm", [character(len=50) :: &
            & "../turntable/turntable.f", "../turntable/turntable_half_coriolis.f"], 10.0_wp, &
            & history, run_error)
        call expect_message(run_error, [character(len=100) :: &
            & "turntable.adm:8: UCON/1 names no ROUTINE, and several files given define " &
            & // "UCOSUB", &
            & "test/user_forces/../turntable/turntable.f, test/user_forces/../turntable/" &
            & // "turntable_half_coriolis.f", "ROUTINE=FILE::UCOSUB"], error)
        if (allocated(error)) return
        call run_user(folder // "ucon_two_files.adm", [character(len=50) :: &
            & "ucon_turn_velocity.f", "ucon_circle.f", "../turntable/turntable.f"], 10.0_wp, &
            & history, run_error)
        call expect_message(run_error, [character(len=90) :: "test/user_forces/../turntable/" &
            & // "turntable.f defines a UCOSUB that serves no UCON", &
            & "ROUTINE=turntable::UCOSUB"], error)
        if (allocated(error)) return
        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/ucon_no_such.adm"
        call write_text_file(path, replaced(file_text(folder // "ucon_two_files.adm"), &
            & "ucon_circle::circle", "ucon_circle::ellipse"), error)
        if (allocated(error)) return
        call run_user(path, [character(len=50) :: "ucon_turn_velocity.f", "ucon_circle.f"], &
            & 10.0_wp, history, run_error)
        call expect_message(run_error, [character(len=90) :: &
            & "ucon_no_such.adm:10: UCON/2 ROUTINE: 'ucon_circle::ellipse' is neither", &
            & "nor a subroutine of a user's file"], error)
    end subroutine test_ucon_refusals

    !> The check at the start covers a routine a UCON names: ucon_circle_wrong.f's CIRCLE
    !> (dF/dX returned as X, half its value) stops the run, naming UCON/2, its line, its
    !> ROUTINE and file, the entry and both values (0.1 returned for X = 0.1 m; the
    !> differences give 0.2), and the command that checks the model's UCONs at random states
    !> with the run's two files as the run takes them.
    subroutine test_ucon_named_checked(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=:), allocatable :: path

        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/ucon_wrong.adm"
        call write_text_file(path, replaced(file_text(folder // "ucon_two_files.adm"), &
            & "ucon_circle::circle", "ucon_circle_wrong::CIRCLE"), error)
        if (allocated(error)) return
        call run_user(path, [character(len=50) :: "ucon_turn_velocity.f", &
            & "ucon_circle_wrong.f"], 10.0_wp, history, run_error, checked=.true.)
        call expect_message(run_error, [character(len=160) :: &
            & "test/user_forces/ucon_circle_wrong.f fails its check", &
            & "UCON/2 (line 10, ROUTINE=ucon_circle_wrong::CIRCLE of " &
            & // "test/user_forces/ucon_circle_wrong.f) ARRAY(1) = dF/d(X_2)", &
            & "returned 0.1, differences give 0.2", "at random states: rollcon check " &
            & // "test/user_forces/ucon_turn_velocity.f --ucosub test/user_forces/" &
            & // "ucon_circle_wrong.f --model " // path // ";"], error)
    end subroutine test_ucon_named_checked

    !> text with every occurrence of old replaced by new.
    function replaced(text, old, new) result(out)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: out
        integer :: at, from

        out = ""
        from = 1
        do
            at = index(text(from:), old)
            if (at == 0) exit
            out = out // text(from:from + at - 2) // new
            from = from + at - 1 + len(old)
        end do
        out = out // text(from:)
    end function replaced

    !> A write through a wild index in an SFOSUB kills the child by SIGSEGV: the error names
    !> the statement, the signal and the call (not the initialisation call).
    subroutine test_crashes(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("crashes", 10.0_wp, [character(len=70) :: &
            & "user_forces.adm:15: SFORCE/2: the process was killed by SIGSEGV", &
            & "inside SFOSUB call", &
            & "IFLAG = .FALSE."], error)
    end subroutine test_crashes

    !> A STOP in an SFOSUB: the child ended before its work was done, said as for a UCOSUB,
    !> with the STOP's own text quoted from the child's stderr (which never reaches the host's).
    subroutine test_stops(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("stops", 10.0_wp, [character(len=70) :: &
            & "user_forces.adm:15: SFORCE/2: the process ended with exit status", &
            & "a STOP, ERROR STOP or CALL EXIT in the SFOSUB", "inside SFOSUB call", &
            & "its stderr: STOP spring broken"], error)
    end subroutine test_stops

    !> An endless loop in an SFOSUB: killed at the time limit per call (1 s here).
    subroutine test_endless(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("endless", 1.0_wp, [character(len=70) :: &
            & "user_forces.adm:15: SFORCE/2: a call of the SFOSUB did not return", &
            & "within 1 s, the time limit", &
            & "IFLAG = .FALSE."], error)
    end subroutine test_endless

    !> RESULT(2) written by an SFOSUB (whose RESULT is one value): the guard's canary sees it,
    !> in the initialisation call already, and the error names statement, file and entry.
    subroutine test_writes_outside(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("writes_result_2", 10.0_wp, [character(len=70) :: &
            & "user_forces.adm:15: SFORCE/2: its SFOSUB of", "writes_result_2.f", &
            & "initialisation call (IFLAG = .TRUE.)", &
            & "wrote RESULT(2) = 1, outside SFOSUB's RESULT(1)"], error)
    end subroutine test_writes_outside

    !> An SFOSUB returning NaN after t = 0.1 s: the run stops there, the error naming the
    !> statement, the routine, the value and a TIME past 0.1.
    subroutine test_nan(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("nan", 10.0_wp, [character(len=50) :: &
            & "user_forces.adm:15: SFORCE/2: its SFOSUB of", &
            & "returned RESULT = (NaN) at TIME = 0.1", &
            & "a force must be finite"], error)
    end subroutine test_nan

    !> An integer division by zero, NPAR / IZERO, in an SFOSUB: the child is killed by SIGFPE
    !> and the error names the statement, the signal and the call (not the initialisation
    !> call), as the UCOSUB corpus's divide_by_zero.f.
    subroutine test_divide_by_zero(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("divide_by_zero", 10.0_wp, [character(len=70) :: &
            & "user_forces.adm:15: SFORCE/2: the process was killed by SIGFPE", &
            & "inside SFOSUB call", &
            & "IFLAG = .FALSE."], error)
    end subroutine test_divide_by_zero

    !> An endless loop in an SFOSUB's initialisation call: killed at the time limit per call
    !> (1 s here), the call named as the initialisation call (IFLAG = .TRUE.), before any row.
    subroutine test_endless_init(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_fault("endless_init", 1.0_wp, [character(len=70) :: &
            & "user_forces.adm:15: SFORCE/2: a call of the SFOSUB did not return", &
            & "within 1 s, the time limit", &
            & "IFLAG = .TRUE., TIME = 0"], error)
    end subroutine test_endless_init

    !> An SFOSUB changing PAR(3), TIME or ID, which it may only read (ADAMS may pass them in
    !> read-only memory), in its first call after the initialisation call: the guard's copies
    !> see it, and the error names the statement, its line, the file, the argument and the
    !> values before and after (PAR(3) the stiffness 1000 raised by 1, ID 2 by 1; TIME moved by
    !> 1 s from the call's time, a value the test does not know, so only its name is matched).
    subroutine test_changes_arguments(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: names(3) = [character(len=12) :: "changes_par", &
            & "changes_time", "changes_id"]
        character(len=*), parameter :: changes(3) = [character(len=44) :: &
            & "the routine changed PAR(3) from 1000 to 1001", "the routine changed TIME from", &
            & "the routine changed ID from 2 to 3"]
        integer :: k

        do k = 1, size(names)
            call expect_fault(trim(names(k)), 10.0_wp, [character(len=60) :: &
                & "user_forces.adm:15: SFORCE/2: its SFOSUB of", trim(names(k)) // ".f", &
                & changes(k), "which it may only read"], error)
            if (allocated(error)) then
                error%message = trim(names(k)) // ".f: " // error%message
                return
            end if
        end do
    end subroutine test_changes_arguments

    !> The coin dataset run with the UCOSUB corpus's stops.f (a STOP in its first evaluation
    !> call): the error begins as a force routine's does, with the UCON's file and line
    !> (data/coin.adm:38: UCON/1), then what ended the process and the call.
    subroutine test_ucosub_stop_line(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user("data/coin.adm", ["../faulty_ucosubs/stops.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=60) :: &
            & "data/coin.adm:38: UCON/1: the process ended with exit status", &
            & "inside UCOSUB call", "IFLAG = 0"], error)
    end subroutine test_ucosub_stop_line

    !> user_forces.adm with only the GFOSUB's file: SFORCE/2 is refused before any call,
    !> naming its line and the routine it needs.
    subroutine test_missing(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "user_forces.adm", ["gforce_bushing.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "user_forces.adm:15: SFORCE/2 FUNCTION=USER(...): no SFOSUB serves it", &
            & "SUBROUTINE SFOSUB"], error)
    end subroutine test_missing

    !> A ROUTINE=FILE::SFOSUB naming no file given: refused, naming the ROUTINE.
    subroutine test_unknown_routine(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "two_files.adm", ["sforce_spring.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "two_files.adm:13: SFORCE/3 ROUTINE=sforce_cubic::SFOSUB: no SFOSUB", &
            & "ROUTINE=FILE::NAME names the subroutine NAME of FILE, with SFOSUB's"], error)
    end subroutine test_unknown_routine

    !> The MOTSUB refusals, each naming the MOTION and its line: a ROUTINE with no
    !> FUNCTION=USER, and motion.adm run with a file that has no MOTSUB.
    subroutine test_motion_user(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(history_type) :: history
        type(error_type), allocatable :: load_error
        character(len=:), allocatable :: path, text
        character(len=*), parameter :: nl = new_line("a")

        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/motion_user.adm"
        text = "a MOTION served by a MOTSUB" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 1, 1, 1" // nl &
            & // "MARKER/20, PART = 2" // nl // "JOINT/1, TRANSLATIONAL, I = 20, J = 1" // nl
        call write_text_file(path, text // "MOTION/1, JOINT = 1, TRANSLATION, " &
            & // "FUNCTION = TIME, ROUTINE = u::MOTSUB" // nl &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 10" // nl // "END" // nl, error)
        if (allocated(error)) return
        call load_job(path, job, load_error)
        call expect_message(load_error, [character(len=70) :: "motion_user.adm:7: MOTION/1", &
            & "ROUTINE: names a MOTSUB, which serves a FUNCTION=USER"], error)
        if (allocated(error)) return
        call run_user(folder // "motion.adm", ["sforce_spring.f"], 10.0_wp, history, &
            & load_error)
        call expect_message(load_error, [character(len=70) :: &
            & "motion.adm:17: MOTION/1 FUNCTION=USER(...): no MOTSUB serves it", &
            & "SUBROUTINE MOTSUB"], error)
    end subroutine test_motion_user

    !> motion.adm (REVOLUTE JOINT/1 turned by motsub_sine.f's MOTSUB, PAR(1) SIN(PAR(2) TIME)
    !> and its derivatives; a pendulum hinged on the rotor) gives the rows of
    !> motion_expressions.adm (the MOTION's FUNCTION = 0.5*SIN(3*TIME)) to motsub_tolerance in
    !> every column, on IDA and on CVODE. The MOTSUB's IORD = 0, 1, 2 values take the place of
    !> the expression's value and first and second TIME derivatives (forward mode in jets) in
    !> the same equations, computed with the same operations in the same order (measured: the
    !> rows agree bit for bit on both integrators); motsub_tolerance allows a few roundings
    !> of difference carried through the run without a change of the step sequence. A
    !> frequency off by 1e-5 (PAR(2) = 3.00001) moves the rows by 1.4e-5.
    subroutine test_motsub(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_motion_twins("motion", ["motsub_sine.f"], formulation_ida, error)
        if (allocated(error)) return
        call compare_motion_twins("motion", ["motsub_sine.f"], formulation_cvode, error)
    end subroutine test_motsub

    !> motion_two_files.adm (in millimetres): MOTION/1 by the model's MOTSUB (motsub_sine.f),
    !> MOTION/2 by the MOTSUB its ROUTINE=motsub_lift::MOTSUB names, a lift of 40 (1 - COS(5
    !> TIME)) mm: the rows of its expression twin to motsub_tolerance in every column (among
    !> them motion2_fz, the lift's force, 3 kg (h'' + g): h'' in mm/s^2 converted to SI), on
    !> IDA.
    subroutine test_motsub_two_files(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_motion_twins("motion_two_files", ["motsub_sine.f", "motsub_lift.f"], &
            & formulation_ida, error)
    end subroutine test_motsub_two_files

    !> motion_velocity.adm and motion_acceleration.adm: motion.adm's rotor turned by a VELOCITY
    !> MOTION whose MOTSUB (motsub_rates.f) returns 1.5 COS(3 TIME) at IORD = 0 and its rate
    !> at IORD = 1, and by an ACCELERATION MOTION (ICVEL = 1.5) whose MOTSUB returns -4.5
    !> SIN(3 TIME) at IORD = 0 (ADAMS asks no more of them; the routine stops on any other
    !> IORD): the rows of their expression twins (the same functions as FUNCTION
    !> expressions) to motsub_tolerance in every column, on IDA and CVODE. The MOTSUB's f is
    !> integrated by the expression's quadrature at the same points, the same operations
    !> computing f there, so the displacements agree to round-off; f' (IORD = 1) stands for
    !> the expression's forward-mode derivative, which rounds otherwise in its last bits.
    subroutine test_motsub_rates(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_motion_twins("motion_velocity", ["motsub_rates.f"], formulation_ida, &
            & error)
        if (allocated(error)) return
        call compare_motion_twins("motion_velocity", ["motsub_rates.f"], formulation_cvode, &
            & error)
        if (allocated(error)) return
        call compare_motion_twins("motion_acceleration", ["motsub_rates.f"], formulation_ida, &
            & error)
        if (allocated(error)) return
        call compare_motion_twins("motion_acceleration", ["motsub_rates.f"], &
            & formulation_cvode, error)
    end subroutine test_motsub_rates

    !> A VELOCITY MOTION's MOTSUB whose IORD = 1 is its IORD = 0's rate plus 1
    !> (faulty/motsub_velocity_wrong_rate.f) is stopped by the run's start check, naming the
    !> MOTION and its line, IORD = 1, the value returned (1 at TIME = 0, where the rate is 0)
    !> and --no-check; the right routine (motsub_rates.f) passes the same check.
    subroutine test_motsub_velocity_wrong_rate(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "motion_velocity.adm", ["faulty/motsub_velocity_wrong_rate.f"], &
            & 10.0_wp, history, run_error, checked=.true.)
        call expect_message(run_error, [character(len=80) :: &
            & "motion_velocity.adm:17: MOTION/1: its MOTSUB of", &
            & "returned VALUE = 1 at IORD = 1, TIME = 0, where differences of its IORD = 0", &
            & "--no-check"], error)
        if (allocated(error)) return
        call run_user(folder // "motion_velocity.adm", ["motsub_rates.f"], 10.0_wp, history, &
            & error, checked=.true.)
    end subroutine test_motsub_velocity_wrong_rate

    !> A MOTSUB whose IORD = 1 is twice the rate of its IORD = 0 (faulty/motsub_wrong_rate.f)
    !> is stopped by the run's start check (the job's start_check, as `rollcon run` sets it),
    !> naming the MOTION and its line, the IORD, the value returned (3 at TIME = 0) and the
    !> differences' (1.5), and --no-check.
    subroutine test_motsub_wrong_rate(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "motion.adm", ["faulty/motsub_wrong_rate.f"], 10.0_wp, &
            & history, run_error, checked=.true.)
        call expect_message(run_error, [character(len=70) :: &
            & "motion.adm:17: MOTION/1: its MOTSUB of", "faulty/motsub_wrong_rate.f", &
            & "returned VALUE = 3 at IORD = 1, TIME = 0", &
            & "differences of its IORD = 0 values give 1.5", "--no-check"], error)
        if (allocated(error)) return
        ! the right routine passes the same check
        call run_user(folder // "motion.adm", ["motsub_sine.f"], 10.0_wp, history, error, &
            & checked=.true.)
    end subroutine test_motsub_wrong_rate

    !> A write through a wild index in a MOTSUB kills the child by SIGSEGV: the error names the
    !> MOTION, the signal and the call (not the initialisation call), as for an SFOSUB.
    subroutine test_motsub_crashes(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "motion.adm", ["faulty/motsub_crashes.f"], 10.0_wp, history, &
            & run_error)
        call expect_message(run_error, [character(len=70) :: &
            & "motion.adm:17: MOTION/1: the process was killed by SIGSEGV", &
            & "inside MOTSUB call", &
            & "IFLAG = .FALSE."], error)
    end subroutine test_motsub_crashes

    !> A MOTSUB whose initialisation call reads the state (SYSFNC('DX') of markers 31, 1) is
    !> refused before the run, naming the MOTION, its line and the markers: a MOTION is a
    !> function of TIME alone.
    subroutine test_motsub_reads_state(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error

        call run_user(folder // "motion.adm", ["faulty/motsub_reads_state.f"], 10.0_wp, &
            & history, run_error)
        call expect_message(run_error, [character(len=80) :: &
            & "motion.adm:17: MOTION/1: its MOTSUB of", &
            & "in the initialisation call (IFLAG = .TRUE.) at TIME = 0, read the state", &
            & "(markers 31, 1): a MOTION is a function of TIME alone"], error)
    end subroutine test_motsub_reads_state

    !> NAME.adm run with files (apart) and NAME_expressions.adm run here, both with this
    !> formulation: as many rows (at least 101), each column equal to motsub_tolerance of its
    !> largest magnitude (at least 1).
    subroutine compare_motion_twins(name, files, formulation, error)
        character(len=*), intent(in) :: name, files(:)
        integer, intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        !> See test_motsub
        real(wp), parameter :: motsub_tolerance = 1.0e-10_wp
        type(history_type) :: user, expressions
        type(job_type) :: job
        type(job_result_type) :: ran
        real(wp) :: largest, scale
        integer :: c, worst

        call run_user(folder // name // ".adm", files, 10.0_wp, user, error, &
            & formulation=formulation)
        if (allocated(error)) return
        call load_job(folder // name // "_expressions.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        job%source%settings%formulation = formulation
        call run_job(job, ran, error, expressions)
        if (allocated(error)) return
        if (user%count /= expressions%count .or. user%count < 101 .or. size(user%rows, 1) &
            & /= size(expressions%rows, 1)) then
            call fatal_error(error, name // ": " // to_text(user%count) // " rows of " &
                & // to_text(size(user%rows, 1)) // " with MOTSUBs, " &
                & // to_text(expressions%count) // " of " // to_text(size(expressions%rows, 1)) &
                & // " with expressions")
            return
        end if
        largest = 0.0_wp
        worst = 0
        do c = 1, size(user%rows, 1)
            scale = max(1.0_wp, maxval(abs(expressions%rows(c, :expressions%count))))
            associate (d => maxval(abs(user%rows(c, :user%count) &
                & - expressions%rows(c, :expressions%count)))/scale)
                if (d > largest) worst = c
                largest = max(largest, d)
            end associate
        end do
        call check(error, largest <= motsub_tolerance, name // " (formulation " &
            & // to_text(formulation) // "): the runs differ by " // to_text(largest) &
            & // " (relative) in column " // to_text(worst))
    end subroutine compare_motion_twins

    !> SYSFNC and SYSARY refuse what they do not know, a force measure (FX), and a marker the
    !> model has not (here: no model at all, so RACC's markers too), setting ERRFLG and giving
    !> zeros.
    subroutine test_utilities_refuse(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value, states(3)
        integer :: nstates
        logical :: unknown, force, no_marker, array_acceleration

        call system_function("XYZZY", [1, 2], value, unknown)
        call system_function("FX", [1, 2], value, force)
        call system_array("RACC", [1, 2], states, nstates, array_acceleration)
        call system_function("DM", [987654, 2], value, no_marker)
        call check(error, unknown .and. force .and. no_marker .and. array_acceleration &
            & .and. value == 0.0_wp .and. nstates == 0 .and. all(states == 0.0_wp), &
            & "ERRFLG: unknown " // merge("T", "F", unknown) // ", FX " &
            & // merge("T", "F", force) // ", RACC " // merge("T", "F", &
            & array_acceleration) // ", missing marker " // merge("T", "F", no_marker))
    end subroutine test_utilities_refuse

    !> `rollcon check implicit_slip.f --model spring.adm`: exactly its two slips of implicit
    !> typing, each naming the routine, the line and the statement (KS truncated to an
    !> INTEGER, CD kept in REAL), and no finding of the probed states (the routine is smooth
    !> and keeps no state).
    subroutine test_check_typing(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call check_file("implicit_slip.f", findings, count, error)
        if (allocated(error)) return
        call check(error, count == 2 .and. index(findings, "implicit_slip.f:16 (in SUBROUTINE " &
            & // "SFOSUB)") > 0 .and. index(findings, "REAL(8) to INTEGER(4)") > 0 .and. &
            & index(findings, "'KS = PAR(3)'") > 0 .and. index(findings, "implicit_slip.f:17") &
            & > 0 .and. index(findings, "REAL(8) to REAL(4)") > 0 .and. index(findings, &
            & "'CD = PAR(4)'") > 0, to_text(count) // " findings: " // findings)
    end subroutine test_check_typing

    !> The same check of sforce_spring.f (declared types, no state, smooth, its SYSFNC calls
    !> those of its initialisation call): clean.
    subroutine test_check_clean(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call check_file("sforce_spring.f", findings, count, error)
        if (allocated(error)) return
        call check(error, count == 0, to_text(count) // " findings: " // findings)
    end subroutine test_check_clean

    !> The same check of hidden_state.f (a SAVEd counter in RESULT): one [hidden state]
    !> finding, naming the statement, the routine and the first state, that counts the states
    !> that showed it: all 21 (as a UCOSUB's findings are grouped, not a line per state).
    subroutine test_check_hidden(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call check_file("hidden_state.f", findings, count, error)
        if (allocated(error)) return
        call check(error, count == 1 .and. index(findings, "[hidden state] " // folder &
            & // "spring.adm:9: SFORCE/2, its SFOSUB of " // folder // "hidden_state.f at " &
            & // "state 0 (the start)") > 0 .and. index(findings, "; so in 21 of the 21 " &
            & // "states probed") > 0 .and. index(findings, "at state 1,") == 0, &
            & to_text(count) // " findings: " // findings)
    end subroutine test_check_hidden

    !> spring.adm with hidden_state.f (a force that flips its sign at each call) and at most
    !> 200 steps an output interval: IDA fails with too much work, and its message names the
    !> command that checks the routines (`rollcon check FILE --model MODEL`), since the
    !> failure names no routine of its own.
    subroutine test_failure_points_at_check(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=:), allocatable :: text, model
        integer :: at

        text = file_text(folder // "spring.adm")
        at = index(text, "ACCGRAV")
        call check(error, at > 0, folder // "spring.adm has no ACCGRAV")
        if (allocated(error)) return
        call make_folders(scratch, error)
        if (allocated(error)) return
        model = scratch // "/few_steps.adm"
        call write_text_file(model, text(:at - 1) // "INTEGRATOR/MAXSTEPS = 200" &
            & // new_line("a") // text(at:), error)
        if (allocated(error)) return
        call run_user(model, ["hidden_state.f"], 10.0_wp, history, run_error)
        call expect_message(run_error, [character(len=200) :: "IDA_TOO_MUCH_WORK", &
            & "the run's user routines are in " // folder // "hidden_state.f: rollcon check " &
            & // folder // "hidden_state.f --model " // model // " checks them at many states"], &
            & error)
    end subroutine test_failure_points_at_check

    !> `rollcon run` of spring.adm with hidden_state.f's SFOSUB (a 1000 N term flipping sign
    !> at each call) and MAXSTEPS 4 chunks (chunk_steps_default each): the steps grind (mean
    !> step near 1e-7 of the 0.01 s output interval, half of them rejected: measured), so
    !> standard error warns once, after the first chunk, naming `rollcon check FILE --model
    !> MODEL`, before the run fails at MAXSTEPS.
    subroutine test_grinding_points_at_check(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, model, program, said, command
        integer :: at, status

        text = file_text(folder // "spring.adm")
        at = index(text, "ACCGRAV")
        call check(error, at > 0, folder // "spring.adm has no ACCGRAV")
        if (allocated(error)) return
        call make_folders(scratch // "/grinding", error)
        if (allocated(error)) return
        model = scratch // "/grinding.adm"
        call write_text_file(model, text(:at - 1) // "INTEGRATOR/MAXSTEPS = " &
            & // to_text(4*chunk_steps_default) // new_line("a") // text(at:), error)
        if (allocated(error)) return
        call rollcon_program(program, error)
        if (allocated(error)) return
        call run_rollcon(program, "run " // model // " --ucosub " // folder // "hidden_state.f" &
            & // " -q -o " // scratch // "/grinding", scratch // "/grinding.out", &
            & scratch // "/grinding.err", status)
        said = file_text(scratch // "/grinding.err")
        call check(error, status /= 0, "the run of hidden_state.f did not fail: " // said)
        if (allocated(error)) return
        command = "rollcon check " // folder // "hidden_state.f --model " // model
        ! the warning's line, up to the failure's (which names the command too)
        at = index(said, "rollcon: warning: at t = ")
        if (at > 0) then
            said = said(at:)
            at = index(said, new_line("a"))
            if (at > 0) said = said(:at)
        end if
        call check(error, index(said, "rollcon: warning: at t = ") == 1 &
            & .and. index(said, "the steps grind") > 0 .and. index(said, command) > 0, &
            & "no warning of grinding steps naming `" // command // "` in: " &
            & // file_text(scratch // "/grinding.err"))
        if (allocated(error)) return
        said = file_text(scratch // "/grinding.err")
        call check(error, count_of(said, "the steps grind") == 1, "the warning of grinding " &
            & // "steps is not written once: " // said)
        if (allocated(error)) return
        ! the criterion on chunks of 500 steps towards an output time 0.01 s away: this run's
        ! (measured: mean step 5e-6 to 9e-6 of the way, half rejected) grinds; the same small
        ! steps with sforce_spring.f's share rejected (8 of 538), or the same share rejected
        ! at steps of 1e-3 of the way (a corner), do not
        call check(error, grinds(0.0_wp, 500*7.0e-8_wp, 0.01_wp, 500, 250) &
            & .and. .not. grinds(0.0_wp, 500*7.0e-8_wp, 0.01_wp, 500, 8) &
            & .and. .not. grinds(0.0_wp, 500*1.0e-5_wp, 0.01_wp, 500, 250), &
            & "the criterion of grinding steps misjudges a chunk")
    end subroutine test_grinding_points_at_check

    !> The same model with sforce_spring.f's SFOSUB (the spring without hidden state) in one
    !> output interval of 2 s: more steps than chunk_steps_default towards it (the watch is
    !> told between chunks), none grinding, the run completes without a warning.
    subroutine test_sound_run_no_grinding(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, said, summary
        integer :: status, at, steps, stat

        call make_folders(scratch // "/sound", error)
        if (allocated(error)) return
        call rollcon_program(program, error)
        if (allocated(error)) return
        call run_rollcon(program, "run " // folder // "spring.adm --ucosub " // folder &
            & // "sforce_spring.f --end 2 --steps 1 -q -o " // scratch // "/sound", &
            & scratch // "/sound.out", scratch // "/sound.err", status)
        said = file_text(scratch // "/sound.err")
        call check(error, status == 0, "exited " // to_text(status) // ": " // said)
        if (allocated(error)) return
        call check(error, index(said, "warning") == 0, "a warning on a sound run: " // said)
        if (allocated(error)) return
        summary = file_text(scratch // "/sound/spring.adm.summary.txt")
        at = index(summary, new_line("a") // "steps ")
        steps = 0
        stat = 1
        if (at > 0) read(summary(at + 7:), *, iostat=stat) steps
        call check(error, stat == 0 .and. steps > chunk_steps_default, "the run took " &
            & // to_text(steps) // " steps, not more than a chunk's " &
            & // to_text(chunk_steps_default) // ": no chunk was watched")
    end subroutine test_sound_run_no_grinding

    !> check_user_routines of folder//file on spring.adm, the tests' cache, seed 1.
    subroutine check_file(file, findings, count, error)
        character(len=*), intent(in) :: file
        character(len=:), allocatable, intent(out) :: findings
        integer, intent(out) :: count
        type(error_type), allocatable, intent(out) :: error
        type(user_build_options_type) :: options

        options%cache_dir = test_cache
        call check_user_routines(folder // file, folder // "spring.adm", options, 10.0_wp, 1, &
            & findings, count, error)
    end subroutine check_file

    !> Run NAME.adm served by files (run apart) and NAME_expressions.adm (here); both complete
    !> with the same number of rows, equal to twin_tolerance in every part coordinate and rate.
    subroutine compare_twins(name, files, error)
        character(len=*), intent(in) :: name, files(:)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: user, expressions
        real(wp) :: largest
        integer :: worst

        call run_twins(name, files, user, expressions, error)
        if (allocated(error)) return
        call part_difference(user, expressions, largest, worst)
        call check(error, largest <= twin_tolerance, name // ": the runs differ by " &
            & // to_text(largest) // " in coordinate " // to_text(worst) // " of part 2")
    end subroutine compare_twins

    !> folder//NAME.adm run with the user's files and its twin folder//NAME_expressions.adm run
    !> as a job: their rows (both at least 101, as many in each).
    subroutine run_twins(name, files, user, expressions, error)
        character(len=*), intent(in) :: name, files(:)
        type(history_type), intent(out) :: user, expressions
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: ran

        call run_user(folder // name // ".adm", files, 10.0_wp, user, error)
        if (allocated(error)) return
        call load_job(folder // name // "_expressions.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error, expressions)
        if (allocated(error)) return
        if (user%count /= expressions%count .or. user%count < 101) then
            call fatal_error(error, name // ": " // to_text(user%count) // " rows with user " &
                & // "routines, " // to_text(expressions%count) // " with expressions")
        end if
    end subroutine run_twins

    !> The largest difference between two runs' rows over the first part's 12 coordinates and
    !> rates, and the column (1..12) where it is (0 when the rows agree).
    subroutine part_difference(a, b, largest, worst)
        type(history_type), intent(in) :: a, b
        real(wp), intent(out) :: largest
        integer, intent(out) :: worst
        integer :: c

        largest = 0.0_wp
        worst = 0
        do c = 1, 12
            associate (d => maxval(abs(a%part_values(1, c) - b%part_values(1, c))))
                if (d > largest) worst = c
                largest = max(largest, d)
            end associate
        end do
    end subroutine part_difference

    !> Run folder//faulty/NAME.f (with gforce_bushing.f for GFORCE/1) on user_forces.adm with
    !> the time limit per call; the run must fail with an error holding every piece.
    subroutine expect_fault(name, timeout, pieces, error)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: timeout
        character(len=*), intent(in) :: pieces(:)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=64) :: files(2)

        ! (a local array: a typed constructor of a concatenation of assumed length is
        ! miscompiled by gfortran 12)
        files(1) = "faulty/" // name // ".f"
        files(2) = "gforce_bushing.f"
        call run_user(folder // "user_forces.adm", files, timeout, history, run_error)
        call expect_message(run_error, pieces, error)
    end subroutine expect_fault

    !> An error must have come, holding every piece (trimmed).
    subroutine expect_message(got, pieces, error)
        type(error_type), allocatable, intent(in) :: got
        character(len=*), intent(in) :: pieces(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        if (.not. allocated(got)) then
            call fatal_error(error, "no error; expected one saying '" // trim(pieces(1)) // "'")
            return
        end if
        do k = 1, size(pieces)
            if (index(got%message, trim(pieces(k))) > 0) cycle
            call fatal_error(error, "the error does not say '" // trim(pieces(k)) // "': " &
                & // got%message)
            return
        end do
    end subroutine expect_message

    !> Run a dataset with the user's files (folder//files(k)), no output files, every row
    !> kept; a run that does not complete is an error. Optionally with another formulation
    !> (formulation_cvode ...), and checked at the start as `rollcon run` checks (checked).
    subroutine run_user(path, files, timeout, history, error, formulation, checked)
        character(len=*), intent(in) :: path, files(:)
        real(wp), intent(in) :: timeout
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: formulation
        logical, intent(in), optional :: checked
        type(job_type) :: job
        type(job_result_type) :: ran
        integer :: k

        call load_job(path, job, error, ucosub=folder // trim(files(1)))
        if (allocated(error)) return
        do k = 2, size(files)
            call add_user_file(job, folder // trim(files(k)), error)
            if (allocated(error)) return
        end do
        job%output_dir = ""
        job%quiet = .true.
        job%call_timeout = timeout
        job%build_options%cache_dir = test_cache
        if (present(formulation)) job%source%settings%formulation = formulation
        if (present(checked)) then
            if (checked) job%start_check => check_at_start
        end if
        call run_job(job, ran, error, history)
        if (allocated(error)) return
        if (ran%summary%status /= status_completed) call fatal_error(error, path // ": " &
            & // ran%summary%message)
    end subroutine run_user

end module test_user_forces
