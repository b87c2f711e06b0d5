! SPDX-License-Identifier: MIT
!> Static and kinematic analyses, run from datasets and a command file (suite analyses): a
!> slider-crank driven at constant speed by a rotational MOTION, kinematic, against the
!> closed-form slider position and velocity and the driving torque by virtual work; the static
!> sag of a bar hung on an SFORCE spring and the angle of a pendulum held by a rotational
!> spring, against their hand-computed equilibria; a static then dynamic command file that
!> stays at rest; the refusal of a kinematic analysis of a model with a degree of freedom; and
!> Newton's failures, named.
module test_analyses
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    use dataset_texts, only : texts_dir, run_text, write_text
    use rollcon_run_settings, only : analysis_static
    implicit none
    private

    public :: collect_analyses

    character(len=*), parameter :: nl = new_line("a")
    real(wp), parameter :: g = 9.81_wp

    !> A pendulum of 2 kg, its centre 0.5 m from a REVOLUTE about ground Z, horizontal at the
    !> start, held up by a rotational SFORCE of 30 N m/rad about the joint's axis
    character(len=*), parameter :: pendulum = "pendulum on a rotational spring" // nl &
        & // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl // "MARKER/10, PART=1" // nl &
        & // "PART/2, MASS=2, CM=20, IP=0.01, 0.02, 0.02, QG=0.5, 0, 0" // nl &
        & // "MARKER/20, PART=2" // nl // "MARKER/21, PART=2, QP=-0.5, 0, 0" // nl &
        & // "JOINT/1, REVOLUTE, I=21, J=10" // nl &
        & // "SFORCE/1, ROTATION, I=21, J=10, FUNCTION=-30*AZ(21, 10)" // nl &
        & // "ACCGRAV/JGRAV=-9.81" // nl
    real(wp), parameter :: pendulum_mass = 2.0_wp, pendulum_arm = 0.5_wp, &
        & pendulum_stiffness = 30.0_wp

contains

    subroutine collect_analyses(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("kinematic-slider-crank-closed-form-and-virtual-work", &
            & test_slider_crank), &
            & new_unittest("static-sag-of-a-bar-on-a-spring", test_sag), &
            & new_unittest("static-angle-of-a-pendulum-on-a-spring", test_pendulum), &
            & new_unittest("static-then-dynamic-stays-at-rest", test_static_then_dynamic), &
            & new_unittest("kinematic-refuses-a-degree-of-freedom", test_kinematic_refusal), &
            & new_unittest("static-newton-failures-named", test_newton_failures), &
            & new_unittest("equilibrium-limits-read-in-si", test_equilibrium_limits)]
    end subroutine collect_analyses

    !> The slider-crank of test/redundant (crank r = 0.1 m, 0.5 kg; rod l = 0.3 m, 1 kg;
    !> slider 2 kg on ground X; gravity -Y; three REVOLUTEs and a TRANSLATIONAL, 3 redundant
    !> equations) driven by MOTION/1 on the crank's joint at 2 pi rad/s from 30 degrees,
    !> SIMULATE/KINEMATIC over one turn. The crank angle is theta = pi/6 + 2 pi t; the slider
    !> is at x = r cos theta + sqrt(l^2 - r^2 sin^2 theta), with x' = dx/dtheta omega. The
    !> motion's torque T does all the work on the mechanism: T omega = dE/dt, E = kinetic +
    !> potential energy of the three parts, so T = dE/dtheta at constant omega (virtual work),
    !> E(theta) in closed form (each part's centre and angle, their theta-derivatives by the
    !> complex step), dE/dtheta by central differences.
    subroutine test_slider_crank(error)
        type(error_type), allocatable, intent(out) :: error
        !> Positions by Newton until every row is within 1e-2 (atol + rtol s) of zero (the run's
        !> atol 1e-10, rtol 1e-8: about 4e-11 m here, rollcon_ic_rows): measured 2.3e-11 m on
        !> x; 2e-10 m is 9 times that, 2e-9 of the 0.1 m crank
        real(wp), parameter :: tol_position = 2.0e-10_wp
        !> Velocities by one linear solve at the solved positions: measured 7.6e-12 m/s of the
        !> 0.7 m/s; 5e-11 m/s is 7 times that
        real(wp), parameter :: tol_velocity = 5.0e-11_wp
        !> The central difference of E (step h = 2e-5 rad) errs by h^2/6 E''' ~ 1e-10 N m; the
        !> torque from the multipliers measured within 3.4e-10 N m of it, the torque reaching
        !> 1.33 N m; 2e-9 N m is 6 times that, and a missing term (gravity's, the rod's
        !> inertia) is 1e8 times larger
        real(wp), parameter :: tol_torque = 2.0e-9_wp
        real(wp), parameter :: omega = 2.0_wp*pi, r = 0.1_wp, l = 0.3_wp, h = 2.0e-5_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        character(len=:), allocatable :: text
        real(wp) :: theta, t, x, xdot, torque, worst(3)
        integer :: k, cx, cv, ct

        text = crank_dataset()
        call run_text("kinematic_crank.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 101, &
            & "the kinematic run completes with 101 rows, got " // to_text(rows%count))
        if (allocated(error)) return
        call check(error, index(result%summary%analysis_lines, "kinematic") > 0, &
            & "the summary says the analysis was kinematic: " // result%summary%analysis_lines)
        if (allocated(error)) return
        cx = result%summary%layout%column("X_4")
        cv = result%summary%layout%column("Xdot_4")
        ct = result%summary%layout%column("motion1_torque")
        call check(error, cx > 0 .and. cv > 0 .and. ct > 0, "columns X_4, Xdot_4, motion1_torque")
        if (allocated(error)) return
        worst = 0.0_wp
        do k = 1, rows%count
            t = rows%rows(1, k)
            theta = pi/6.0_wp + omega*t
            x = r*cos(theta) + sqrt(l**2 - (r*sin(theta))**2)
            xdot = omega*(-r*sin(theta) - r**2*sin(theta)*cos(theta) &
                & /sqrt(l**2 - (r*sin(theta))**2))
            torque = (crank_energy(theta + h) - crank_energy(theta - h))/(2.0_wp*h)
            worst(1) = max(worst(1), abs(rows%rows(cx, k) - x))
            worst(2) = max(worst(2), abs(rows%rows(cv, k) - xdot))
            worst(3) = max(worst(3), abs(rows%rows(ct, k) - torque))
        end do
        call check(error, worst(1) <= tol_position, "largest |x - x(theta)| of the slider " &
            & // to_text(worst(1)) // " m")
        if (allocated(error)) return
        call check(error, worst(2) <= tol_velocity, "largest |x' - x'(theta)| of the slider " &
            & // to_text(worst(2)) // " m/s")
        if (allocated(error)) return
        call check(error, worst(3) <= tol_torque, "largest |T - dE/dtheta| of the motion's " &
            & // "torque " // to_text(worst(3)) // " N m")
    end subroutine test_slider_crank

    !> The slider-crank dataset, driven and kinematic.
    function crank_dataset() result(text)
        character(len=:), allocatable :: text

        text = "slider-crank driven at 2 pi rad/s" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART=1" // nl &
            & // "MARKER/11, PART=1, REULER=90D, 90D, 0D" // nl &
            & // "PART/2, MASS=0.5, CM=20, IP=2.0833333333333333e-4, 4.1666666666666667e-4, " &
            & // "2.0833333333333333e-4" // nl &
            & // "MARKER/20, PART=2, QP=0.04330127018922193, 0.025, 0, REULER=0D, 90D, 0D" // nl &
            & // "MARKER/21, PART=2" // nl &
            & // "MARKER/22, PART=2, QP=0.08660254037844388, 0.05, 0" // nl &
            & // "PART/3, MASS=1, CM=30, IP=0.00375, 0.0075, 0.00375" // nl &
            & // "MARKER/30, PART=3, QP=0.2345045349559343, 0.025, 0, REULER=0D, 90D, 0D" // nl &
            & // "MARKER/31, PART=3, QP=0.08660254037844388, 0.05, 0" // nl &
            & // "MARKER/32, PART=3, QP=0.3824065295334247, 0, 0" // nl &
            & // "PART/4, MASS=2, CM=40, IP=0.01, 0.01, 0.01" // nl &
            & // "MARKER/40, PART=4, QP=0.3824065295334247, 0, 0, REULER=0D, 90D, 0D" // nl &
            & // "MARKER/41, PART=4, QP=0.3824065295334247, 0, 0" // nl &
            & // "MARKER/42, PART=4, QP=0.3824065295334247, 0, 0, REULER=90D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I=21, J=10" // nl // "JOINT/2, REVOLUTE, I=31, J=22" // nl &
            & // "JOINT/3, REVOLUTE, I=41, J=32" // nl &
            & // "JOINT/4, TRANSLATIONAL, I=42, J=11" // nl &
            & // "MOTION/1, JOINT=1, ROTATION, FUNCTION=2*PI*TIME" // nl &
            & // "ACCGRAV/JGRAV=-9.81" // nl // "SIMULATE/KINEMATIC, END=1, STEPS=100" // nl &
            & // "END"
    end function crank_dataset

    !> The slider-crank's energy at crank angle theta turning at 2 pi rad/s [J]: each centre's
    !> and angle's theta-derivative by the complex step (exact to rounding), times omega.
    real(wp) function crank_energy(theta) result(energy)
        real(wp), intent(in) :: theta
        real(wp), parameter :: r = 0.1_wp, l = 0.3_wp, omega = 2.0_wp*pi, step = 1.0e-20_wp
        real(wp), parameter :: m_crank = 0.5_wp, i_crank = 4.1666666666666667e-4_wp, &
            & m_rod = 1.0_wp, i_rod = 0.0075_wp, m_slider = 2.0_wp
        complex(wp) :: z, pin(2), slider, rod_angle
        real(wp) :: d_pin(2), d_slider, d_rod

        z = cmplx(theta, step, kind=wp)
        pin = r*[cos(z), sin(z)]
        slider = r*cos(z) + sqrt(l**2 - (r*sin(z))**2)
        rod_angle = asin(-r*sin(z)/l)
        d_pin = aimag(pin)/step
        d_slider = aimag(slider)/step
        d_rod = aimag(rod_angle)/step
        ! the crank's centre is half way to the pin, the rod's half way from pin to slider
        energy = 0.5_wp*omega**2*(m_crank*sum((0.5_wp*d_pin)**2) + i_crank &
            & + m_rod*((0.5_wp*(d_pin(1) + d_slider))**2 + (0.5_wp*d_pin(2))**2) &
            & + i_rod*d_rod**2 + m_slider*d_slider**2) &
            & + g*(m_crank + m_rod)*0.5_wp*real(pin(2), wp)
    end function crank_energy

    !> A 3 kg bar on a TRANSLATIONAL joint along ground Y, hung at its centre from a ground
    !> point 1 m above by an SFORCE spring of 200 N/m and free length 1 m written with DM:
    !> -200*(DM(21, 11) - 1). From the unstretched start, SIMULATE/STATIC finds it sagged by
    !> m g / k = 0.14715 m. The spring is linear along the line, so Newton with its exact
    !> stiffness (the jets of DM) converges in a few iterations; without it, the Jacobian is
    !> singular along Y and Newton stalls. The same spring as a SPRINGDAMPER (K=200, LENGTH=1)
    !> sags as much, in as few iterations: its exact partials are in the static Jacobian too.
    subroutine test_sag(error)
        type(error_type), allocatable, intent(out) :: error
        !> Newton goes on to rounding: measured 1.1e-16 m off (a linear problem, solved to
        !> rounding); 1e-12 m is 1e-11 of the sag, where ADAMS's default ERROR alone would
        !> allow 1e-4 relative
        real(wp), parameter :: tol_sag = 1.0e-12_wp
        !> A linear problem: one step meets it, a second confirms, polishing stops at the third
        integer, parameter :: most_iterations = 4
        real(wp), parameter :: mass = 3.0_wp, stiffness = 200.0_wp
        character(len=*), parameter :: text = "bar on a spring" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART=1, REULER=0D, 90D, 0D" // nl &
            & // "MARKER/11, PART=1, QP=0, 1, 0" // nl &
            & // "PART/2, MASS=3, CM=20, IP=0.25, 0.25, 0.01" // nl &
            & // "MARKER/20, PART=2, REULER=0D, 90D, 0D" // nl // "MARKER/21, PART=2" // nl &
            & // "JOINT/1, TRANSLATIONAL, I=20, J=10" // nl &
            & // "SPRING" // nl &
            & // "ACCGRAV/JGRAV=-9.81" // nl // "SIMULATE/STATIC" // nl // "END"
        character(len=*), parameter :: springs(2) = [character(len=72) :: &
            & "SFORCE/1, TRANSLATION, I=21, J=11, FUNCTION=-200*(DM(21, 11) - 1)", &
            & "SPRINGDAMPER/1, TRANSLATIONAL, I=21, J=11, K=200, LENGTH=1"]
        type(job_result_type) :: result
        type(history_type) :: rows
        integer :: cy, iterations, k, at

        at = index(text, "SPRING" // nl)
        do k = 1, size(springs)
            call run_text("static_sag.adm", text(:at - 1) // trim(springs(k)) &
                & // text(at + len("SPRING"):), result, rows, error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. rows%count == 1, &
                & "the static run completes with one row, got " // to_text(rows%count))
            if (allocated(error)) return
            cy = result%summary%layout%column("Y_2")
            call check(error, rows%rows(cy, 1), -mass*g/stiffness, "the bar's height", &
                & abs_tol=tol_sag)
            if (allocated(error)) return
            iterations = newton_iterations(result%summary%analysis_lines)
            call check(error, iterations >= 1 .and. iterations <= most_iterations, "Newton " &
                & // "iterations " // to_text(iterations) // ", expected 1 to " &
                & // to_text(most_iterations) // ": " // result%summary%analysis_lines)
            if (allocated(error)) return
        end do
    end subroutine test_sag

    !> The pendulum on its rotational spring, SIMULATE/STATIC with ADAMS's default EQUILIBRIUM
    !> limits: at angle a below the horizontal the spring's k a balances gravity's m g l cos a
    !> (a = 0.31121... rad, solved here by Newton on that scalar equation); the joint's
    !> reaction is the weight, m g.
    subroutine test_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        !> Newton goes on after ADAMS's 1e-4 limits while each step halves the imbalance, to
        !> rounding: measured 0 rad off the scalar solution (both to rounding); 1e-12 rad,
        !> where stopping at the 1e-4 limits leaves about 1e-5 rad
        real(wp), parameter :: tol_angle = 1.0e-12_wp
        !> The reaction from the multipliers at rest: measured 3.6e-15 N of 19.6 N; 1e-10 N,
        !> where a multiplier without the spring's moment is off by newtons
        real(wp), parameter :: tol_force = 1.0e-10_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: angle, expected
        integer :: cx, cf

        call run_text("static_pendulum.adm", pendulum // "SIMULATE/STATIC" // nl // "END", &
            & result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 1, &
            & "the static run completes with one row")
        if (allocated(error)) return
        call check(error, index(result%summary%analysis_lines, "static equilibrium") > 0, &
            & "the summary names the static equilibrium: " // result%summary%analysis_lines)
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        cf = result%summary%layout%column("joint1_fx")
        angle = atan2(-rows%rows(cx + 1, 1), rows%rows(cx, 1))
        expected = spring_angle()
        call check(error, angle, expected, "the pendulum's angle below the horizontal", &
            & abs_tol=tol_angle)
        if (allocated(error)) return
        call check(error, norm2(rows%rows(cf:cf + 2, 1)), pendulum_mass*g, "|the joint's " &
            & // "reaction force|", abs_tol=tol_force)
    end subroutine test_pendulum

    !> A command file runs SIMULATE/STATIC, then SIMULATE/DYNAMIC: the dynamic run starts from
    !> the equilibrium at rest and stays there (every row's angle the equilibrium's, every
    !> rate zero).
    subroutine test_static_then_dynamic(error)
        type(error_type), allocatable, intent(out) :: error
        !> The forces balance to rounding (1e-15 N m), so the state stays put to rounding over
        !> 1 s: measured 4.1e-15 rad and 4.3e-14 rad/s; 1e-12 for both, where an equilibrium
        !> found only to ADAMS's default IMBALANCE (1e-4 N m) would swing by about 1e-5 rad and
        !> 1e-4 rad/s, and a dynamic run from the horizontal start by 0.3 rad
        real(wp), parameter :: tol_angle = 1.0e-12_wp, tol_rate = 1.0e-12_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        type(job_type) :: job
        type(error_type), allocatable :: failure
        real(wp) :: expected, worst_angle, worst_rate
        integer :: cx, cr, k

        call write_text("static_dynamic.adm", pendulum // "SIMULATE/DYNAMIC, END=1, STEPS=2" &
            & // nl // "END")
        call write_text("static_dynamic.acf", "static_dynamic" // nl // "static_dynamic_out" &
            & // nl // "SIMULATE/STATIC" // nl // "SIMULATE/DYNAMIC, END=1, STEPS=20" // nl &
            & // "STOP")
        call load_job(texts_dir // "/static_dynamic.acf", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, rows)
        if (allocated(failure)) call move_alloc(failure, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 21, &
            & "the run completes with 21 rows, got " // to_text(rows%count))
        if (allocated(error)) return
        call check(error, index(result%summary%analysis_lines, "then dynamic") > 0, &
            & "the summary says static, then dynamic: " // result%summary%analysis_lines)
        if (allocated(error)) return
        ! the settings line names both analyses
        call check(error, index(job%source%setting_line(), ": static equilibrium, then IDA") &
            & > 0, "the settings line: " // job%source%setting_line())
        if (allocated(error)) return
        ! and a static analysis alone runs no integrator: its settings line says so
        call load_job(texts_dir // "/static_dynamic.acf", job, error)
        if (allocated(error)) return
        job%source%settings%analysis = analysis_static
        call check(error, index(job%source%setting_line(), ": static equilibrium (Newton's " &
            & // "method on the forces at rest; no integrator)") > 0, "the settings line " &
            & // "of a static analysis: " // job%source%setting_line())
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        cr = result%summary%layout%column("psidot_2")
        expected = spring_angle()
        worst_angle = 0.0_wp
        worst_rate = 0.0_wp
        do k = 1, rows%count
            worst_angle = max(worst_angle, abs(atan2(-rows%rows(cx + 1, k), rows%rows(cx, k)) &
                & - expected))
            worst_rate = max(worst_rate, maxval(abs(rows%rows(cr:cr + 2, k))))
        end do
        call check(error, worst_angle <= tol_angle, "largest angle from the equilibrium " &
            & // to_text(worst_angle) // " rad")
        if (allocated(error)) return
        call check(error, worst_rate <= tol_rate, "largest angular rate " // to_text(worst_rate) &
            & // " rad/s")
    end subroutine test_static_then_dynamic

    !> SIMULATE/KINEMATIC of the pendulum, one degree of freedom, is refused, naming it.
    subroutine test_kinematic_refusal(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_result_type) :: result
        type(history_type) :: rows

        type(error_type), allocatable :: refusal

        call run_text("kinematic_free.adm", pendulum // "SIMULATE/KINEMATIC, END=1, STEPS=10" &
            & // nl // "END", result, rows, refusal)
        call check(error, allocated(refusal), "a kinematic analysis of a free pendulum refused")
        if (allocated(error)) return
        call check(error, index(refusal%message, "1 degree(s) of freedom left") > 0 .and. &
            & rows%count == 0, "a refusal naming one degree of freedom, no row: " &
            & // refusal%message)
    end subroutine test_kinematic_refusal

    !> Newton's failures, named: a free part under gravity has no equilibrium (the step cannot
    !> reduce the imbalance: the part and the force are named, never a NaN); the pendulum with
    !> EQUILIBRIUM/MAXIT=1 does not converge in one iteration (the iterations named).
    subroutine test_newton_failures(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: free = "free part" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl // "PART/2, MASS=1, CM=20, IP=0.1, 0.1, 0.1" // nl &
            & // "MARKER/20, PART=2" // nl // "ACCGRAV/JGRAV=-9.81" // nl // "SIMULATE/STATIC" &
            & // nl // "END"
        character(len=*), parameter :: wanted(2) = [character(len=60) :: &
            & "no equilibrium near the start", "did not converge in 1 iterations"]
        character(len=*), parameter :: named(2) = [character(len=60) :: &
            & "force imbalance 9.81", "(EQUILIBRIUM/MAXIT)"]
        type(job_result_type) :: result
        type(history_type) :: rows
        type(error_type), allocatable :: refusal
        integer :: k

        do k = 1, 2
            if (k == 1) then
                call run_text("static_free.adm", free, result, rows, refusal)
            else
                call run_text("static_maxit.adm", pendulum // "EQUILIBRIUM/MAXIT=1" // nl &
                    & // "SIMULATE/STATIC" // nl // "END", result, rows, refusal)
            end if
            call check(error, allocated(refusal), "case " // to_text(k) // " refused")
            if (allocated(error)) return
            call check(error, index(refusal%message, trim(wanted(k))) > 0 .and. &
                & index(refusal%message, trim(named(k))) > 0 .and. &
                & index(refusal%message, "NaN") == 0, "case " // to_text(k) // ": expected '" &
                & // trim(wanted(k)) // "' and '" // trim(named(k)) // "', got: " &
                & // refusal%message)
            if (allocated(error)) return
            deallocate(refusal)
        end do
    end subroutine test_newton_failures

    !> EQUILIBRIUM's limits in a dataset in centimetres and dynes are the run's in SI:
    !> IMBALANCE 2 dyn = 2e-5 N, TLIMIT 5 cm = 0.05 m, ALIMIT 3D = pi/60 rad, ERROR and MAXIT
    !> as written; STABILITY, which rollcon has no use for, is named in the warning; a MAXIT
    !> that is not a whole number is refused by its line and keyword.
    subroutine test_equilibrium_limits(error)
        type(error_type), allocatable, intent(out) :: error
        !> The unit conversions: a few roundings of the factors
        real(wp), parameter :: tol = 1.0e-15_wp
        character(len=*), parameter :: head = "limits" // nl &
            & // "UNITS/FORCE=DYNE, MASS=GRAM, LENGTH=CENTIMETER, TIME=SECOND" // nl &
            & // "PART/1, GROUND" // nl // "PART/2, MASS=1, CM=20, IP=1, 1, 1" // nl &
            & // "MARKER/20, PART=2" // nl
        type(job_type) :: job
        type(error_type), allocatable :: refusal

        call write_text("limits.adm", head // "EQUILIBRIUM/ERROR=1e-6, IMBALANCE=2, TLIMIT=5, " &
            & // "ALIMIT=3D, MAXIT=7, STABILITY=1e-5" // nl // "SIMULATE/STATIC" // nl // "END")
        call load_job(texts_dir // "/limits.adm", job, error)
        if (allocated(error)) return
        associate (settings => job%source%settings)
            call check(error, settings%equilibrium_error, 1.0e-6_wp, "ERROR", rel_tol=tol)
            if (allocated(error)) return
            call check(error, settings%equilibrium_imbalance, 2.0e-5_wp, "IMBALANCE [N]", &
                & rel_tol=tol)
            if (allocated(error)) return
            call check(error, settings%equilibrium_tlimit, 0.05_wp, "TLIMIT [m]", rel_tol=tol)
            if (allocated(error)) return
            call check(error, settings%equilibrium_alimit, pi/60.0_wp, "ALIMIT [rad]", &
                & rel_tol=tol)
            if (allocated(error)) return
            call check(error, settings%equilibrium_maxit == 7, "MAXIT " &
                & // to_text(settings%equilibrium_maxit))
            if (allocated(error)) return
        end associate
        call check(error, index(job%source%input_warning(), "EQUILIBRIUM STABILITY") > 0, &
            & "the warning names STABILITY: " // job%source%input_warning())
        if (allocated(error)) return
        call write_text("limits_bad.adm", head // "EQUILIBRIUM/MAXIT=2.5" // nl &
            & // "SIMULATE/STATIC" // nl // "END")
        call load_job(texts_dir // "/limits_bad.adm", job, refusal)
        call check(error, allocated(refusal), "MAXIT=2.5 refused")
        if (allocated(error)) return
        call check(error, index(refusal%message, "limits_bad.adm:6: EQUILIBRIUM MAXIT must be " &
            & // "a whole number") > 0, "the refusal names the line and keyword: " &
            & // refusal%message)
    end subroutine test_equilibrium_limits

    !> The pendulum's equilibrium angle: k a = m g l cos a, by Newton on the scalar.
    real(wp) function spring_angle() result(a)
        integer :: k

        a = 0.3_wp
        do k = 1, 50
            a = a - (pendulum_stiffness*a - pendulum_mass*g*pendulum_arm*cos(a)) &
                & /(pendulum_stiffness + pendulum_mass*g*pendulum_arm*sin(a))
        end do
    end function spring_angle

    !> The number before " Newton iterations" in the summary's analysis lines (-1: none).
    integer function newton_iterations(lines) result(count)
        character(len=*), intent(in) :: lines
        integer :: last, first, stat

        count = -1
        last = index(lines, " Newton iterations") - 1
        if (last < 1) return
        first = index(lines(:last), " ", back=.true.) + 1
        read(lines(first:last), *, iostat=stat) count
        if (stat /= 0) count = -1
    end function newton_iterations

end module test_analyses
