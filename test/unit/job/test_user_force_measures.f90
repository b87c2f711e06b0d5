! SPDX-License-Identifier: MIT
!> Force measures read by a user's force routine through SYSFNC (suite force-measures; data
!> and routines in test/user_forces/): a pendulum's pivot friction proportional to the
!> revolute joint's reaction, FM(I, J), an algebraic loop in the joint's multipliers, against
!> the same pendulum whose routine computes the reaction in closed form; a VFOSUB reading a
!> spring's force through SFORCE(id, jflag, comp, rm) and FZ(i, j, k) against the same VFORCE
!> written with the spring's expression; the friction written as a VARIABLE whose VARSUB
!> reads the reaction, and a DIFF whose DIFSUB integrates it, against the closed form; each
!> on IDA (the multipliers among its unknowns) and CVODE (Newton on the accelerations and
!> multipliers), and that model's steps, evaluations and Newton matrices against its twin's
!> (the DIFSUB's and VARSUB's partials in the multipliers in the Newton matrices); a crank
!> driven by a MOTION, its driving torque read as TZ, TM and
!> SYSFNC('MOTION') against the closed form; a force reading its own force refused, and a
!> MOTSUB reading one; and `rollcon check` of the friction routine, its force measures
!> answered at every probed state.
module test_user_force_measures
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_history, only : history_type
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : status_completed, run_summary_type
    use rollcon_user_build, only : user_build_options_type
    use rollcon_user_routine_check, only : check_user_routines
    use rollcon_run_settings, only : formulation_cvode, formulation_ida
    implicit none
    private

    public :: collect_user_force_measures

    !> The test data
    character(len=*), parameter :: folder = "test/user_forces/"
    !> The tests' cache of compiled routines (the user-ucosub suite's)
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    !> Largest difference allowed between a run and its twin in every coordinate and rate of
    !> the first part [m, rad, m/s, rad/s]: both integrate at rtol 1e-8, atol 1e-10 (the
    !> datasets' default) equations that are the same functions of the state, reached by
    !> different arithmetic (a loop solved to 1e-10 relative against a closed form, an element
    !> summed against its expression), which can change the step sequence: the rows then differ
    !> by the integrators' global error, bounded by 1e-6 (100 rtol over a 1 s run of motions of
    !> size 1). What each twin would differ by with the force measure lost is in each test.
    real(wp), parameter :: twin_tolerance = 1.0e-6_wp
    !> Largest difference allowed between a DIFF integrating a reaction (some 20 to 40 N over
    !> 1 s) and its twin's [N s, N]: the twins' rows differ by the integrators' global error
    !> (above), the reaction by M g = 20 N per radian of the angle's, and the DIFF integrates
    !> that over 1 s: 20 twin_tolerance (measured 4.8e-7 on CVODE, 5.3e-6 on IDA).
    real(wp), parameter :: diff_tolerance = 2.0e-5_wp

contains

    subroutine collect_user_force_measures(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("joint-reaction-friction-ida", test_friction_ida), &
            & new_unittest("joint-reaction-friction-cvode", test_friction_cvode), &
            & new_unittest("element-force-read-ida", test_force_read_ida), &
            & new_unittest("element-force-read-cvode", test_force_read_cvode), &
            & new_unittest("force-reading-itself-refused", test_cycle_refused), &
            & new_unittest("variable-reaction-friction-ida", test_variable_friction_ida), &
            & new_unittest("variable-reaction-friction-cvode", test_variable_friction_cvode), &
            & new_unittest("variable-reading-its-reader-refused", test_variable_cycle), &
            & new_unittest("expression-reading-reaction-refused", test_expression_refused), &
            & new_unittest("difsub-reaction-newton-counts-ida", test_difsub_counts_ida), &
            & new_unittest("difsub-reaction-newton-counts-cvode", test_difsub_counts_cvode), &
            & new_unittest("motion-driving-torque", test_motion_torque), &
            & new_unittest("motsub-force-measure-refused", test_motsub_refused), &
            & new_unittest("reqsub-force-measures", test_reqsub), &
            & new_unittest("check-joint-friction", test_check_friction)]
    end subroutine collect_user_force_measures

    !> joint_friction.adm (a pivot friction -0.05 FM(20, 10) WZ(20, 10), the revolute joint's
    !> reaction read through SYSFNC: a loop, the reaction depending on the torque through the
    !> angular acceleration) gives the rows of joint_friction_twin.adm (the reaction from
    !> Newton's and Euler's laws in the routine) to twin_tolerance on IDA. The pendulum with
    !> no friction (the reaction read as 0) differs by 0.27 rad in its angle psi and 0.85 in
    !> the rows over the run: a friction a tenth of its size, by some 0.24 rad.
    subroutine test_friction_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("joint_friction.adm", "joint_friction.f", "joint_friction_twin.adm", &
            & "joint_friction_twin.f", formulation_ida, error)
    end subroutine test_friction_ida

    !> test_friction_ida on CVODE (the ODE form: Newton on the accelerations and multipliers).
    subroutine test_friction_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("joint_friction.adm", "joint_friction.f", "joint_friction_twin.adm", &
            & "joint_friction_twin.f", formulation_cvode, error)
    end subroutine test_friction_cvode

    !> force_read.adm (VFORCE/4's VFOSUB reading SFORCE/1's force through SYSFNC's SFORCE(1,
    !> 0, 2, 2) and FZ(20, 2, 2)) gives the rows of force_read_expressions.adm (the spring's
    !> expression written into the VFORCE) to twin_tolerance on IDA; part 3's rows are
    !> compared (the pushed part). The force read as 0 moves it by 0.43 m in X and 4.5 m in
    !> Z over the run.
    subroutine test_force_read_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("force_read.adm", "force_read.f", "force_read_expressions.adm", &
            & "", formulation_ida, error, part=2)
    end subroutine test_force_read_ida

    !> test_force_read_ida on CVODE.
    subroutine test_force_read_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("force_read.adm", "force_read.f", "force_read_expressions.adm", &
            & "", formulation_cvode, error, part=2)
    end subroutine test_force_read_cvode

    !> force_cycle.adm: VFORCE/4's routine reads FZ(30, 2, 2), a sum holding its own force:
    !> refused with an error naming the statement, its line and the cycle.
    subroutine test_cycle_refused(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=*), parameter :: pieces(3) = [character(len=40) :: &
            & "force_cycle.adm:14: VFORCE/4", "SYSFNC('FZ')", "a cycle of forces"]
        integer :: k

        call run_user(folder // "force_cycle.adm", "force_read.f", formulation_ida, history, &
            & run_error)
        if (.not. allocated(run_error)) then
            call fatal_error(error, "force_cycle.adm ran: a force reading its own force " &
                & // "was not refused")
            return
        end if
        do k = 1, size(pieces)
            call check(error, index(run_error%message, trim(pieces(k))) > 0, "the error does " &
                & // "not say '" // trim(pieces(k)) // "': " // run_error%message)
            if (allocated(error)) return
        end do
    end subroutine test_cycle_refused

    !> variable_friction.adm (the pivot friction -0.05 VARVAL(4) WZ(20, 10), VARIABLE/4's
    !> VARSUB reading the joint's reaction as SYSFNC('JOINT', 1, 0, 1): the loop in the
    !> joint's multipliers closed through the VARIABLE; VARIABLE/5 the same reaction as FM(20,
    !> 10), SFORCE/8 the difference of the two) gives the rows of variable_friction_twin.adm
    !> (the reaction in closed form) to twin_tolerance on IDA, as test_friction_ida (the
    !> friction lost moves the angle by 0.27 rad); and DIFF/9, whose DIFSUB integrates the
    !> reaction read as SYSFNC('JOINT', 1, 0, 1), gives the twin's (its DIFSUB computing the
    !> reaction in closed form) to diff_tolerance (below). The reaction read as 0 leaves the
    !> DIFF at 0, 22 N s from the twin's at the end.
    subroutine test_variable_friction_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("variable_friction.adm", "variable_friction.f", &
            & "variable_friction_twin.adm", "joint_friction_twin.f", formulation_ida, error, &
            & diff="diff9")
    end subroutine test_variable_friction_ida

    !> test_variable_friction_ida on CVODE (Newton on the accelerations and multipliers, the
    !> VARSUB evaluated at each iterate and differenced over the joint's rows).
    subroutine test_variable_friction_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_twins("variable_friction.adm", "variable_friction.f", &
            & "variable_friction_twin.adm", "joint_friction_twin.f", formulation_cvode, error, &
            & diff="diff9")
    end subroutine test_variable_friction_cvode

    !> expression_friction.adm (VARIABLE/4, FUNCTION = FM(20, 10): variable_friction.adm's
    !> VARSUB written as an expression) and expression_diff.adm (DIFF/9, FUNCTION = JOINT(1, 0,
    !> 1, 0)): refused before the run, naming the statement, its line, the function read, the
    !> reason (partials the expressions' jets do not carry) and the routine that may read it
    !> (a VARSUB, a DIFSUB), on IDA and CVODE alike (the refusal is the reader's).
    subroutine test_expression_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: files(2) = [character(len=24) :: &
            & "expression_friction.adm", "expression_diff.adm"]
        character(len=60), parameter :: pieces(4, 2) = reshape([character(len=60) :: &
            & "expression_friction.adm:15: VARIABLE/4 FUNCTION", "FM(20, 10): a force", &
            & "partials rollcon's expressions do not carry", "read it in a VARSUB through SYSFNC", &
            & "expression_diff.adm:14: DIFF/9 FUNCTION", "JOINT(1, 0, 1, 0): a force", &
            & "partials rollcon's expressions do not carry", &
            & "read it in a DIFSUB through SYSFNC"], [4, 2])
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        integer :: f, k

        do f = 1, size(files)
            call run_user(folder // trim(files(f)), "", formulation_cvode, history, run_error)
            if (.not. allocated(run_error)) then
                call fatal_error(error, trim(files(f)) // " ran: an expression reading a " &
                    & // "reaction was not refused")
                return
            end if
            do k = 1, size(pieces, 1)
                call check(error, index(run_error%message, trim(pieces(k, f))) > 0, "the " &
                    & // "error does not say '" // trim(pieces(k, f)) // "': " &
                    & // run_error%message)
                if (allocated(error)) return
            end do
            deallocate(run_error)
        end do
    end subroutine test_expression_refused

    !> variable_friction.adm (its friction VARIABLE's VARSUB and its DIFF's DIFSUB reading the
    !> joint's reaction) on IDA takes no more steps, residual evaluations (its Newton
    !> iterations, and the matrices' difference calls) and Newton matrices than 1.25 times
    !> variable_friction_twin.adm (the same equations, the reaction in closed form: no
    !> multiplier read, Newton matrices exact to the differences' error) takes: with the DIFF's
    !> partials in the multipliers in IDA's matrix (and, on CVODE, the loop's matrix at its
    !> solution and the DIFF's chain through dlambda/d(q, u)), the two runs' Newton matrices
    !> are the same functions' partials and the counts differ by the step sequence's jitter
    !> alone (measured on IDA 244, 505, 40 against the twin's 278, 508, 42). Without them
    !> IDA took 442 steps, 922 residuals and 206 matrices (1.6 to 4.9 times the twin's), the
    !> Newton iteration of the DIFF's row lagging the multipliers: 1.25 separates the two.
    subroutine test_difsub_counts_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_counts(formulation_ida, error)
    end subroutine test_difsub_counts_ida

    !> test_difsub_counts_ida on CVODE (measured 159 steps, 192 right-hand sides, 3 Newton
    !> matrices against the twin's 162, 195, 3; without the partials 187, 563, 6: the
    !> right-hand sides 2.9 times the twin's, the matrices 2 times).
    subroutine test_difsub_counts_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_counts(formulation_cvode, error)
    end subroutine test_difsub_counts_cvode

    !> variable_friction.adm's steps, evaluations and Newton matrices on the formulation, each
    !> at most 1.25 times variable_friction_twin.adm's (test_difsub_counts_ida).
    subroutine compare_counts(formulation, error)
        integer, intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: most = 1.25_wp
        type(history_type) :: history
        type(run_summary_type) :: user, twin

        call run_user(folder // "variable_friction.adm", "variable_friction.f", formulation, &
            & history, error, user)
        if (allocated(error)) return
        call run_user(folder // "variable_friction_twin.adm", "joint_friction_twin.f", &
            & formulation, history, error, twin)
        if (allocated(error)) return
        call check(error, user%steps <= most*twin%steps .and. user%functions <= most &
            & *twin%functions .and. user%jacobians <= most*twin%jacobians .and. twin%steps > 0, &
            & "variable_friction.adm took " // to_text(user%steps) // " steps, " &
            & // to_text(user%functions) // " evaluations, " // to_text(user%jacobians) &
            & // " Newton matrices; its twin " // to_text(twin%steps) // ", " &
            & // to_text(twin%functions) // ", " // to_text(twin%jacobians) // " (formulation " &
            & // to_text(formulation) // ")")
    end subroutine compare_counts

    !> variable_cycle.adm: VARIABLE/5's VARSUB reads TM(20, 10), which sums SFORCE/3's torque,
    !> -0.05 VARVAL(5): refused with an error naming the VARIABLE, its line, the call and the
    !> SFORCE (the force is evaluated after the VARIABLEs it reads).
    subroutine test_variable_cycle(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=*), parameter :: pieces(4) = [character(len=40) :: &
            & "variable_cycle.adm:14: VARIABLE/5", "SYSFNC('TM')", "SFORCE/3", &
            & "evaluates after the VARIABLEs"]
        integer :: k

        call run_user(folder // "variable_cycle.adm", "variable_friction.f", formulation_ida, &
            & history, run_error)
        if (.not. allocated(run_error)) then
            call fatal_error(error, "variable_cycle.adm ran: a VARIABLE reading the force " &
                & // "that reads it was not refused")
            return
        end if
        do k = 1, size(pieces)
            call check(error, index(run_error%message, trim(pieces(k))) > 0, "the error does " &
                & // "not say '" // trim(pieces(k)) // "': " // run_error%message)
            if (allocated(error)) return
        end do
    end subroutine test_variable_cycle

    !> motion_crank.adm: MOTION/7 turns the crank at theta = 1.5 t + 0.5 t^2 on its revolute
    !> JOINT/1, the centre of mass (M = 2 kg, 1 m from the pivot, IZZ = 0.1 kg m^2) at phi =
    !> theta - 30 degrees under gravity g = 9.81 along -Y. The driving torque on the crank is
    !> T = (IZZ + M) theta'' + M g cos(phi) and the joint's force F = M (a - g), a = theta''
    !> (-sin, cos)(phi) - theta'^2 (cos, sin)(phi). At every row REQUEST/5's REQSUB reads
    !> TZ(20, 10) = T (the MOTION's torque summed with the joint's reaction, which has no
    !> Z torque), TM(20, 10) = |T| (the crank's motion is planar: no other torque),
    !> SYSFNC('MOTION', 7, 0, 8) = T and SYSFNC('MOTION', 7, 1, 8) = -T (at J, on the ground,
    !> whose origin is I's), FM(20, 10) = |F| and FX(20, 10) = F_x (the MOTION's force is zero:
    !> it turns the joint), and REQUEST/6's expressions TZ(20, 10) and MOTION(7, 0, 8, 0) give
    !> T: each within 1e-10 [N m, N] of its closed form, on IDA and CVODE. The MOTION holds
    !> the crank's angle at every row to round-off and the row's multipliers are solved there,
    !> so what is left is round-off in the solve and the sums (measured 1.7e-13, T being some
    !> 20 N m): 1e-10 is that with a wide margin; the MOTION's torque left out is T itself,
    !> between 2 and 22 N m, and its torque taken at the centre of mass instead of I differs
    !> by M g cos(phi), the same size.
    subroutine test_motion_torque(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tolerance = 1.0e-10_wp, gravity = 9.81_wp, mass = 2.0_wp, &
            & izz = 0.1_wp, pi = acos(-1.0_wp)
        character(len=*), parameter :: columns(8) = [character(len=8) :: "req5_f2", "req5_f3", &
            & "req5_f4", "req5_f6", "req5_f7", "req5_f8", "req6_f2", "req6_f3"]
        type(history_type) :: history
        real(wp), allocatable :: time(:), phi(:), rate(:), torque(:), fx(:), fy(:), &
            & expected(:), found(:)
        real(wp) :: largest
        integer, parameter :: formulations(2) = [formulation_cvode, formulation_ida]
        integer :: k, f, formulation

        do f = 1, size(formulations)
            formulation = formulations(f)
            call run_user(folder // "motion_crank.adm", "motion_crank.f", formulation, history, &
                & error)
            if (allocated(error)) return
            time = history%column(1)
            phi = 1.5_wp*time + 0.5_wp*time**2 - pi/6.0_wp
            rate = 1.5_wp + time
            torque = (izz + mass)*1.0_wp + mass*gravity*cos(phi)
            fx = mass*(-sin(phi) - rate**2*cos(phi))
            fy = mass*(cos(phi) - rate**2*sin(phi) + gravity)
            do k = 1, size(columns)
                if (history%layout%column(trim(columns(k))) == 0) then
                    call fatal_error(error, "no column " // trim(columns(k)))
                    return
                end if
                found = history%column(history%layout%column(trim(columns(k))))
                select case (k)
                case (2)
                    expected = abs(torque)
                case (4)
                    expected = -torque
                case (5)
                    expected = sqrt(fx**2 + fy**2)
                case (6)
                    expected = fx
                case default
                    expected = torque
                end select
                largest = maxval(abs(found - expected))
                call check(error, largest <= tolerance .and. time(history%count) > 0.99_wp, &
                    & "motion_crank.adm (formulation " // to_text(formulation) // "): " &
                    & // trim(columns(k)) // " differs from its closed form by " &
                    & // to_text(largest))
                if (allocated(error)) return
            end do
        end do
    end subroutine test_motion_torque

    !> A MOTSUB reading a force measure (SYSFNC('FM') of the hinge of motion.adm's pendulum) is
    !> refused before the run, naming the MOTION, its line, the call and ADAMS's rule (a
    !> MOTION is a function of TIME alone).
    subroutine test_motsub_refused(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(error_type), allocatable :: run_error
        character(len=*), parameter :: pieces(3) = [character(len=60) :: &
            & "motion.adm:17: MOTION/1: its MOTSUB of", "SYSFNC('FM')", &
            & "a MOTSUB's MOTION is a function of TIME alone"]
        integer :: k

        call run_user(folder // "motion.adm", "faulty/motsub_force_measure.f", &
            & formulation_ida, history, run_error)
        if (.not. allocated(run_error)) then
            call fatal_error(error, "motion.adm ran: a MOTSUB reading a force measure was " &
                & // "not refused")
            return
        end if
        do k = 1, size(pieces)
            call check(error, index(run_error%message, trim(pieces(k))) > 0, "the error does " &
                & // "not say '" // trim(pieces(k)) // "': " // run_error%message)
            if (allocated(error)) return
        end do
    end subroutine test_motsub_refused

    !> joint_friction.adm's REQUEST/5, its REQSUB reading FM(20, 10), FX(20, 10, 22) and
    !> TZ(20, 10) through SYSFNC at each output row, gives REQUEST/6's columns (the same
    !> functions as expressions, rollcon_request_answers) at every row to 1e-12 of max(1,
    !> |value|): both sum the same reaction (the row's multipliers) and the same friction
    !> torque, in another order, with the dataset's unit scalings of 1. FX in ground's axes
    !> instead of marker 22's differs by some 10 N, TZ without the friction by its size,
    !> which the test requires to exceed 0.1 N m somewhere.
    subroutine test_reqsub(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        real(wp), allocatable :: read(:), written(:)
        real(wp) :: largest
        integer :: k

        call run_user(folder // "joint_friction.adm", "joint_friction.f", formulation_ida, &
            & history, error)
        if (allocated(error)) return
        do k = 2, 4
            if (history%layout%column("req5_f" // to_text(k)) == 0 .or. &
                & history%layout%column("req6_f" // to_text(k)) == 0) then
                call fatal_error(error, "no column req5_f" // to_text(k) // " or req6_f" &
                    & // to_text(k))
                return
            end if
            read = history%column(history%layout%column("req5_f" // to_text(k)))
            written = history%column(history%layout%column("req6_f" // to_text(k)))
            largest = maxval(abs(read - written)/max(1.0_wp, abs(written)))
            call check(error, largest <= 1.0e-12_wp, "req5_f" // to_text(k) // " differs " &
                & // "from req6_f" // to_text(k) // " by " // to_text(largest) // " (relative)")
            if (allocated(error)) return
        end do
        call check(error, maxval(abs(written)) > 0.1_wp, "TZ(20, 10) is at most " &
            & // to_text(maxval(abs(written))) // " N m: the friction torque is not summed")
    end subroutine test_reqsub

    !> `rollcon check joint_friction.f --model joint_friction.adm`: no finding. Its FM is
    !> answered at every probed state (the equations solved there): a refused SYSFNC would be
    !> an [error] finding, an FM that moved between the two calls at a state [hidden state],
    !> and the routine's declaration covers what it reads (no [declaration] note).
    subroutine test_check_friction(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_build_options_type) :: options
        character(len=:), allocatable :: findings
        integer :: count

        options%cache_dir = test_cache
        call check_user_routines(folder // "joint_friction.f", folder // "joint_friction.adm", &
            & options, 10.0_wp, 1, findings, count, error)
        if (allocated(error)) return
        call check(error, count == 0, to_text(count) // " findings: " // findings)
    end subroutine test_check_friction

    !> Run model with file and twin with twin_file ("" for none) on the formulation; both
    !> complete with as many rows (at least 101), equal to twin_tolerance in every coordinate
    !> and rate of the part-th part (1 absent), and, given diff, in that DIFF's column (and
    !> its rate's, diff // "_dot") to diff_tolerance.
    subroutine compare_twins(model, file, twin, twin_file, formulation, error, part, diff)
        character(len=*), intent(in) :: model, file, twin, twin_file
        integer, intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: part
        character(len=*), intent(in), optional :: diff
        type(history_type) :: user, other
        character(len=:), allocatable :: name
        real(wp) :: largest, d
        integer :: c, worst, p

        p = 1
        if (present(part)) p = part
        call run_user(folder // model, file, formulation, user, error)
        if (allocated(error)) return
        call run_user(folder // twin, twin_file, formulation, other, error)
        if (allocated(error)) return
        if (user%count /= other%count .or. user%count < 101) then
            call fatal_error(error, model // ": " // to_text(user%count) // " rows, its twin " &
                & // to_text(other%count))
            return
        end if
        largest = 0.0_wp
        worst = 0
        do c = 1, 12
            d = maxval(abs(user%part_values(p, c) - other%part_values(p, c)))
            if (d > largest) worst = c
            largest = max(largest, d)
        end do
        call check(error, largest <= twin_tolerance, model // " (formulation " &
            & // to_text(formulation) // "): the runs differ by " // to_text(largest) &
            & // " in column " // to_text(worst) // " of part " // to_text(p))
        if (allocated(error) .or. .not. present(diff)) return
        do c = 1, 2
            name = diff
            if (c == 2) name = diff // "_dot"
            if (user%layout%column(name) == 0 .or. other%layout%column(name) == 0) then
                call fatal_error(error, model // ": no column " // name)
                return
            end if
            d = maxval(abs(user%column(user%layout%column(name)) &
                & - other%column(other%layout%column(name))))
            call check(error, d <= diff_tolerance, model // " (formulation " &
                & // to_text(formulation) // "): " // name // " differs from its twin's by " &
                & // to_text(d))
            if (allocated(error)) return
        end do
    end subroutine compare_twins

    !> Run path with the user's file ("" for none: the expressions run here) on the
    !> formulation; its rows in history. A run that does not complete is an error.
    subroutine run_user(path, file, formulation, history, error, summary)
        character(len=*), intent(in) :: path, file
        integer, intent(in) :: formulation
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        !> The run's summary (its integrator's counts)
        type(run_summary_type), intent(out), optional :: summary
        type(job_type) :: job
        type(job_result_type) :: ran

        if (len(file) > 0) then
            call load_job(path, job, error, ucosub=folder // file)
        else
            call load_job(path, job, error)
        end if
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        job%call_timeout = 10.0_wp
        job%build_options%cache_dir = test_cache
        job%source%settings%formulation = formulation
        call run_job(job, ran, error, history)
        if (allocated(error)) return
        if (ran%summary%status /= status_completed) call fatal_error(error, path // ": " &
            & // ran%summary%message)
        if (present(summary)) summary = ran%summary
    end subroutine run_user

end module test_user_force_measures
