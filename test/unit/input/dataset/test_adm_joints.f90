! SPDX-License-Identifier: MIT
!> JOINT and JPRIM statements (suite adm-joints): every joint type against a case with a known
!> answer, the primitives held and free where they should be, a joint between two parts, a
!> joint whose part is re-based during the run, the initial-conditions analysis pulling a joint
!> together, and the refusals (docs/datasets.md, "JOINT and JPRIM").
module test_adm_joints
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_adm_joints

    character(len=*), parameter :: work_dir = "build/rollcon-test"
    character(len=*), parameter :: nl = new_line("a")
    real(wp), parameter :: g = 9.81_wp
    !> The joints' residuals: position constraints held by IDA at rtol = atol = 1e-10 stay a
    !> few atol off (the pendulum's measured largest is 3.4e-11 m); 1e-8 is 100 atol, and a
    !> joint not held at all is off by the motion itself, 0.1 to 1 m
    real(wp), parameter :: tol_residual = 1.0e-8_wp
    !> Energy drift relative to E0: the run's own bound at rtol 1e-10 is some 1e-8 (the
    !> pendulum: 2.9e-8 measured against 5.7e-8 allowed); a joint that does work (a wrong
    !> partial in its force) changes E by percents
    real(wp), parameter :: tol_energy = 1.0e-6_wp

contains

    subroutine collect_adm_joints(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("revolute-pendulum-exact-period", test_pendulum_period), &
            & new_unittest("translational-slider-on-incline", test_slider), &
            & new_unittest("spherical-pendulum-conserves", test_spherical), &
            & new_unittest("joints-and-primitives-held-and-free", test_primitives), &
            & new_unittest("double-pendulum-two-parts", test_double_pendulum), &
            & new_unittest("joint-survives-rebasing", test_rebasing), &
            & new_unittest("two-part-joint-survives-rebasing-of-j", test_rebasing_j), &
            & new_unittest("marker-i-on-ground", test_i_on_ground), &
            & new_unittest("angles-only-on-ida", test_angles_on_ida), &
            & new_unittest("initial-conditions-pull-together", test_apart), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_adm_joints

    !> data/pendulum.adm: a bob of 1 kg, l = 0.5 m, I_O = 0.26 kg m^2 about the hinge,
    !> released at rest at 60 degrees. Its period, from the times the bob crosses below the
    !> hinge (X = 0) going the same way, against the exact large-amplitude period
    !> 4 sqrt(I_O/(m g l)) K(sin 30 deg), K the complete elliptic integral of the first kind
    !> computed here by the arithmetic-geometric mean: 1.55246 s, 7.3 % more than the
    !> small-amplitude 2 pi sqrt(I_O/(m g l)) = 1.44660 s.
    subroutine test_pendulum_period(error)
        type(error_type), allocatable, intent(out) :: error
        !> The crossing times are interpolated linearly between rows h = 1 ms apart; at X = 0
        !> the bob's X'' vanishes, so X - its line is at most |X'''| h^3 / 8, and the time
        !> |X'''/X'| h^3 / 8 = 28.3 s^-2 * 1e-9 s^3 / 8 = 3.5e-9 s per crossing (X' = l phi' =
        !> 1.54 m/s, X''' = l (phi''' - phi'^3) = -43.4 m/s^3 at the bottom): at most 3.5e-9 s
        !> on the period of three crossings. The integration's own, measured at ERROR = 1e-10:
        !> 9e-10 s. 5e-9 s holds both, and a tenfold loss of the integration's fails
        real(wp), parameter :: tol_period = 5.0e-9_wp
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: exact, small, crossings(8), t0, t1, x0, x1, i_o
        integer :: k, n, cx

        call run_file("data/pendulum.adm", result, rows, error)
        if (allocated(error)) return
        i_o = 0.01_wp + 1.0_wp*0.5_wp**2
        exact = 4.0_wp*sqrt(i_o/(1.0_wp*g*0.5_wp))*elliptic_k(sin(pi/6.0_wp))
        small = 2.0_wp*pi*sqrt(i_o/(1.0_wp*g*0.5_wp))
        cx = result%summary%layout%column("X_2")
        n = 0
        do k = 2, rows%count
            x0 = rows%rows(cx, k - 1)
            x1 = rows%rows(cx, k)
            ! released at X < 0: upward crossings (X from - to +)
            if (x0 < 0.0_wp .and. x1 >= 0.0_wp .and. n < size(crossings)) then
                t0 = rows%rows(1, k - 1)
                t1 = rows%rows(1, k)
                n = n + 1
                crossings(n) = t0 - x0*(t1 - t0)/(x1 - x0)
            end if
        end do
        call check(error, n >= 2, "fewer than two crossings in 4 s: " // to_text(n))
        if (allocated(error)) return
        call check(error, abs((crossings(n) - crossings(1))/(n - 1) - exact) <= tol_period &
            & .and. abs(exact - small) > 0.1_wp, "period " // to_text((crossings(n) &
            & - crossings(1))/(n - 1)) // " s, exact " // to_text(exact) // " s")
        if (allocated(error)) return
        call check_held(result, error)
    end subroutine test_pendulum_period

    !> A block on a TRANSLATIONAL joint whose axis (J's z) runs down a 30-degree incline:
    !> released at rest, it slides s = g sin(30 deg) t^2 / 2 along the axis and does not turn.
    subroutine test_slider(error)
        type(error_type), allocatable, intent(out) :: error
        !> X, Z of the CM against the formula at rtol = atol = 1e-10 over 1 s (s = 2.45 m):
        !> 1e-8 m is 100 atol; a wrong direction or a joint that brakes is off by the metre
        real(wp), parameter :: tol_position = 1.0e-8_wp
        !> The angles do not move at all but by round-off and the integrator's atol
        real(wp), parameter :: tol_angle = 1.0e-9_wp
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: s, t, worst, turned, alpha
        integer :: k, cx, cz, c

        alpha = pi/6.0_wp
        call run_text("slider.adm", "slider on an incline" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, REULER=90D, 120D, 0D   ! z: down the incline" // nl &
            & // "PART/2, MASS=3, CM=20, IP=0.1, 0.2, 0.25" // nl &
            & // "MARKER/20, PART=2, REULER=0, 90D, 0" // nl &
            & // "MARKER/21, PART=2, REULER=90D, 120D, 0D" // nl &
            & // "JOINT/4, TRANSLATIONAL, I=21, J=10" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "SIMULATE/DYNAMIC, END=1, DTOUT=0.01" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        cz = result%summary%layout%column("Z_2")
        worst = 0.0_wp
        turned = 0.0_wp
        do k = 1, rows%count
            t = rows%rows(1, k)
            s = 0.5_wp*g*sin(alpha)*t**2
            worst = max(worst, abs(rows%rows(cx, k) - s*cos(alpha)), &
                & abs(rows%rows(cz, k) + s*sin(alpha)))
            do c = 4, 6
                turned = max(turned, abs(rows%rows(cx + c - 1, k) - rows%rows(cx + c - 1, 1)))
            end do
        end do
        call check(error, worst <= tol_position .and. turned <= tol_angle .and. &
            & rows%rows(1, rows%count) > 0.99_wp, "largest distance from the formula " &
            & // to_text(worst) // " m, largest turn " // to_text(turned) // " rad")
        if (allocated(error)) return
        call check_held(result, error)
    end subroutine test_slider

    !> A spherical pendulum: a bob on a SPHERICAL joint at the origin, 0.4 m out at 50 degrees
    !> from the vertical, sent sideways. Its angular momentum about the vertical through the
    !> pivot, m (x ydot - y xdot) + I omega_Z (the bob's inertia is isotropic), and its energy
    !> are conserved.
    subroutine test_spherical(error)
        type(error_type), allocatable, intent(out) :: error
        !> H_Z relative to its start (0.76 kg m^2/s): the constraint force passes through the
        !> pivot and gravity is vertical, so only the integration errors (rtol 1e-10) change
        !> it; 1e-7 allows a thousand of them, and a spurious torque changes it by percents
        real(wp), parameter :: tol_momentum = 1.0e-7_wp
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: h0, h, worst, m, inertia
        integer :: k, c

        m = 2.0_wp
        inertia = 0.02_wp
        call run_text("spherical.adm", "spherical pendulum" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1" // nl &
            & // "PART/2, MASS=2, CM=20, IP=0.02, 0.02, 0.02, VY=1.2, WX=0.5, WZ=2" // nl &
            & // "MARKER/20, PART=2, QP=0.30641777724759, 0, -0.25711504387461, " &
            & // "REULER=20D, 70D, 10D" // nl &
            & // "MARKER/21, PART=2" // nl &
            & // "JOINT/2, SPHERICAL, I=21, J=10" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "SIMULATE/DYNAMIC, END=3, DTOUT=0.01" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) return
        c = result%summary%layout%column("X_2")
        worst = 0.0_wp
        do k = 1, rows%count
            associate (r => rows%rows(c:c + 11, k))
                ! omega_Z = psidot + phidot cos(theta) (docs/design.md §3)
                h = m*(r(1)*r(8) - r(2)*r(7)) + inertia*(r(10) + r(12)*cos(r(5)))
            end associate
            if (k == 1) h0 = h
            worst = max(worst, abs(h - h0))
        end do
        call check(error, worst <= tol_momentum*abs(h0) .and. abs(h0) > 0.1_wp, &
            & "H_Z changed by " // to_text(worst) // " kg m^2/s from " // to_text(h0))
        if (allocated(error)) return
        call check_held(result, error)
    end subroutine test_spherical

    !> A part tied to ground by each JOINT type and each JPRIM, started moving and turning
    !> under gravity: the joint's UCONs held and the energy conserved (check_held); what the
    !> joint fixes does not move (the part's angles for FIXED, TRANSLATIONAL and ORIENTATION;
    !> I's origin from J's, as a displacement request measures it in J's axes, along the
    !> constrained directions) and what it leaves free does (by more than 1e-3). With CVODE
    !> (BDF, projection) at ERROR = 1e-10: IDA fails its first step (IDA_CONV_FAIL at t = 0,
    !> at 1e-8 too) on the PARALLEL_AXES and ORIENTATION parts before their multipliers'
    !> tolerance got its floor; test_angles_on_ida runs those two on IDA.
    subroutine test_primitives(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: cases(14) = [character(len=28) :: &
            & "JOINT CYLINDRICAL", "JOINT UNIVERSAL", "JOINT FIXED", "JOINT REVOLUTE", &
            & "JPRIM ATPOINT", "JPRIM INLINE", "JPRIM INPLANE", "JPRIM PARALLEL_AXES", &
            & "JPRIM PERPENDICULAR", "JPRIM ORIENTATION", "JOINT TRANSLATIONAL", &
            & "JOINT HOOKE", "JOINT CONVEL", "JOINT PLANAR"]
        !> Whether each case leaves free: rotation, translation along J's z, in J's x-y plane
        logical, parameter :: turns(14) = [.true., .true., .false., .true., .true., .true., &
            & .true., .true., .true., .false., .false., .true., .true., .true.]
        logical, parameter :: along(14) = [.true., .false., .false., .false., .false., .true., &
            & .false., .true., .true., .true., .true., .false., .false., .false.]
        logical, parameter :: across(14) = [.false., .false., .false., .false., .false., &
            & .false., .true., .true., .true., .true., .false., .false., .false., .true.]
        type(history_type) :: rows
        type(job_result_type) :: result
        character(len=:), allocatable :: kind, i_angles
        real(wp) :: turn, moved_along, moved_across
        integer :: n, k, c, cq, cr

        do n = 1, size(cases)
            kind = trim(cases(n))
            ! PERPENDICULAR and UNIVERSAL need I's z across J's at the start, a CONVEL I's z
            ! opposite J's (its shafts in line, x_i = x_j); a HOOKE's x_i is across y_j as given
            i_angles = "0, 0, 0"
            if (index(kind, "PERPENDICULAR") > 0 .or. index(kind, "UNIVERSAL") > 0) &
                & i_angles = "0, 90D, 0"
            if (index(kind, "CONVEL") > 0) i_angles = "0, 180D, 0"
            call run_text("primitive.adm", "a part on a joint" // nl &
                & // "PART/1, GROUND" // nl &
                & // "MARKER/10, PART=1, QP=0.1, -0.2, 0.3, REULER=30D, 40D, 50D" // nl &
                & // "PART/2, MASS=2, CM=20, IP=0.02, 0.03, 0.04, QG=0.1, -0.2, 0.3" // nl &
                & // ", REULER=30D, 40D, 50D, VX=0.3, VY=-0.2, VZ=0.5, WX=1, WY=-2, WZ=3" // nl &
                & // "MARKER/20, PART=2, QP=0.05, 0.1, -0.2, REULER=10D, 70D, 20D" // nl &
                & // "MARKER/21, PART=2, REULER=" // i_angles // nl &
                & // kind(:5) // "/7, " // kind(7:) // ", I=21, J=10" // nl &
                & // "REQUEST/1, DISPLACEMENT, I=21, J=10, RM=10" // nl &
                & // "ACCGRAV/KGRAV=-9.81" // nl &
                & // "SIMULATE/DYNAMIC, END=1, DTOUT=0.01" // nl &
                & // "INTEGRATOR/ERROR=1e-10, FORMULATION=CVODE" // nl, result, rows, error)
            if (allocated(error)) then
                error%message = kind // ": " // error%message
                return
            end if
            call check_held(result, error)
            if (allocated(error)) then
                error%message = kind // ": " // error%message
                return
            end if
            cq = result%summary%layout%column("psi_2")
            cr = result%summary%layout%column("req1_x")
            turn = 0.0_wp
            moved_along = 0.0_wp
            moved_across = 0.0_wp
            do k = 1, rows%count
                do c = 0, 2
                    turn = max(turn, abs(rows%rows(cq + c, k) - rows%rows(cq + c, 1)))
                end do
                moved_along = max(moved_along, abs(rows%rows(cr + 2, k) - rows%rows(cr + 2, 1)))
                moved_across = max(moved_across, hypot(rows%rows(cr, k) - rows%rows(cr, 1), &
                    & rows%rows(cr + 1, k) - rows%rows(cr + 1, 1)))
            end do
            ! held: 1e-8 (a few atol); free: 1e-3, thousands of times below the motion
            call check(error, free_or_held(turns(n), turn) .and. free_or_held(along(n), &
                & moved_along) .and. free_or_held(across(n), moved_across), kind &
                & // ": largest turn " // to_text(turn) // " rad, move along J's z " &
                & // to_text(moved_along) // " m, across " // to_text(moved_across) // " m")
            if (allocated(error)) return
        end do
    end subroutine test_primitives

    !> A double pendulum: PART/2 hinged to ground, PART/3 hinged to PART/2 by a REVOLUTE joint
    !> between two moving parts, swinging through large angles for 3 s: energy conserved and
    !> both joints held, and the lower arm does swing about the elbow (its angle to the upper
    !> arm changes by more than 0.1 rad).
    subroutine test_double_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: bend, bend0, largest
        integer :: k, c2, c3

        call run_text("double.adm", "double pendulum" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, REULER=180D, 90D, 0D" // nl &
            & // "PART/2, MASS=1, CM=20, IP=0.02, 0.02, 0.005, REULER=90D, 70D, -90D" // nl &
            & // "MARKER/20, PART=2, QP=0, 0, -0.3, REULER=0, 90D, 0" // nl &
            & // "MARKER/21, PART=2, REULER=180D, 90D, 0D" // nl &
            & // "MARKER/22, PART=2, QP=0, 0, -0.6, REULER=180D, 90D, 0D" // nl &
            & // "PART/3, MASS=0.5, CM=30, IP=0.01, 0.01, 0.003, QG=-0.5638155, 0, -0.2052121" &
            & // nl // ", REULER=90D, 20D, -90D" // nl &
            & // "MARKER/30, PART=3, QP=0, 0, -0.25, REULER=0, 90D, 0" // nl &
            & // "MARKER/31, PART=3, REULER=180D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I=21, J=10" // nl &
            & // "JOINT/2, REVOLUTE, I=31, J=22" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "SIMULATE/DYNAMIC, END=3, DTOUT=0.01" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) return
        call check_held(result, error)
        if (allocated(error)) return
        ! both arms turn about ground Y, their body z along -Y: the angle between them is the
        ! difference of their phi
        c2 = result%summary%layout%column("phi_2")
        c3 = result%summary%layout%column("phi_3")
        bend0 = rows%rows(c3, 1) - rows%rows(c2, 1)
        largest = 0.0_wp
        do k = 1, rows%count
            bend = rows%rows(c3, k) - rows%rows(c2, k)
            largest = max(largest, abs(bend - bend0))
        end do
        call check(error, largest > 0.1_wp .and. index(result%summary%routines, "jp_atpoint") &
            & > 0, "the elbow bent by at most " // to_text(largest) // " rad; routines: " &
            & // result%summary%routines)
    end subroutine test_double_pendulum

    !> The pendulum with its CM marker's z axis in the plane of the swing, 5 degrees off the
    !> arm: as the bob first passes below the hinge that axis passes the vertical, and the part
    !> is re-based (its principal axes turned; the joint's marker geometry in PAR turned with
    !> it; the new z axis is 95 degrees off the arm and never vertical again).
    !> The run goes on with the joint held, and its motion is that of data/pendulum.adm, whose
    !> CM marker's z axis stays along the hinge (never re-based; the bob's inertia is
    !> isotropic, so the two are the same physical pendulum).
    subroutine test_rebasing(error)
        type(error_type), allocatable, intent(out) :: error
        !> Both runs at rtol = atol = 1e-10 over 4 s (two and a half swings): the re-based run
        !> restarts its integrator at each re-basing; 1e-7 m is a thousand atol, and a joint
        !> that jumps at a re-basing moves the bob by its geometry, 0.1 m
        real(wp), parameter :: tol_twin = 1.0e-7_wp
        type(history_type) :: rows, twin
        type(job_result_type) :: result, twin_result
        real(wp) :: worst, bases
        integer :: k, cx, tx, cb

        call run_file("data/pendulum.adm", twin_result, twin, error)
        if (allocated(error)) return
        call run_text("rebased.adm", "pendulum, re-based" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, REULER=180D, 90D, 0D" // nl &
            & // "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01" // nl &
            & // ", REULER=90D, 60D, -90D" // nl &
            & // "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=90D, 175D, 0" // nl &
            & // "MARKER/21, PART=2, REULER=180D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I=21, J=10" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "SIMULATE/DYNAMIC, END=4, DTOUT=0.001" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) return
        call check_held(result, error)
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        tx = twin_result%summary%layout%column("X_2")
        cb = result%summary%layout%column("basis_2")
        call check(error, cb > 0 .and. rows%count == twin%count, "no basis_2 column, or " &
            & // to_text(rows%count) // " rows against " // to_text(twin%count))
        if (allocated(error)) return
        worst = 0.0_wp
        do k = 1, rows%count
            worst = max(worst, abs(rows%rows(cx, k) - twin%rows(tx, k)), &
                & abs(rows%rows(cx + 2, k) - twin%rows(tx + 2, k)))
        end do
        bases = rows%rows(cb, rows%count)
        call check(error, bases >= 1.0_wp .and. worst <= tol_twin, to_text(bases) &
            & // " re-basings (1 expected); " &
            & // "largest distance from the twin " // to_text(worst) // " m")
    end subroutine test_rebasing

    !> The double pendulum (arms of isotropic inertia) twice: once with the upper arm's CM
    !> marker z axis along the hinges, never re-based, and once with it in the plane of the
    !> swing, 5 degrees off the arm, so that the upper arm, the part of the elbow joint's marker
    !> J, is re-based as it swings below its hinge (its PAR vectors of J turned with it). The
    !> two are one physical motion: both arms' centres agree, and both joints are held.
    subroutine test_rebasing_j(error)
        type(error_type), allocatable, intent(out) :: error
        !> rtol = atol = 1e-10 over 1.5 s of a double pendulum, whose nearby motions part at a
        !> Lyapunov rate of a few 1/s: the restarts' differences of 1e-10 grow a hundredfold,
        !> while a joint that jumps at the re-basing moves the arms by its geometry, 0.1 m
        !> (measured: 1.7e-9 m, one re-basing)
        real(wp), parameter :: tol_twin = 1.0e-7_wp
        type(history_type) :: rows(2)
        type(job_result_type) :: result(2)
        character(len=*), parameter :: cm_markers(2) = [character(len=60) :: &
            & "MARKER/20, PART=2, QP=0, 0, -0.3, REULER=0, 90D, 0", &
            & "MARKER/20, PART=2, QP=0, 0, -0.3, REULER=90D, 175D, 0"]
        real(wp) :: worst
        integer :: k, n, c(2), cb

        do n = 1, 2
            call run_text("double_" // to_text(n) // ".adm", "double pendulum" // nl &
                & // "PART/1, GROUND" // nl &
                & // "MARKER/10, PART=1, REULER=180D, 90D, 0D" // nl &
                & // "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01, REULER=90D, 70D, -90D" // nl &
                & // trim(cm_markers(n)) // nl &
                & // "MARKER/21, PART=2, REULER=180D, 90D, 0D" // nl &
                & // "MARKER/22, PART=2, QP=0, 0, -0.6, REULER=180D, 90D, 0D" // nl &
                & // "PART/3, MASS=0.5, CM=30, IP=0.01, 0.01, 0.003, QG=-0.5638155, 0, " &
                & // "-0.2052121" // nl // ", REULER=90D, 20D, -90D" // nl &
                & // "MARKER/30, PART=3, QP=0, 0, -0.25, REULER=0, 90D, 0" // nl &
                & // "MARKER/31, PART=3, REULER=180D, 90D, 0D" // nl &
                & // "JOINT/1, REVOLUTE, I=21, J=10" // nl &
                & // "JOINT/2, REVOLUTE, I=31, J=22" // nl &
                & // "ACCGRAV/KGRAV=-9.81" // nl &
                & // "SIMULATE/DYNAMIC, END=1.5, DTOUT=0.001" // nl &
                & // "INTEGRATOR/ERROR=1e-10" // nl, result(n), rows(n), error)
            if (allocated(error)) return
            call check_held(result(n), error)
            if (allocated(error)) return
        end do
        cb = result(2)%summary%layout%column("basis_2")
        call check(error, cb > 0 .and. rows(1)%count == rows(2)%count, "no basis_2 column, " &
            & // "or " // to_text(rows(1)%count) // " rows against " // to_text(rows(2)%count))
        if (allocated(error)) return
        call check(error, rows(2)%rows(cb, rows(2)%count) >= 1.0_wp, "the upper arm was not " &
            & // "re-based")
        if (allocated(error)) return
        worst = 0.0_wp
        do n = 1, 2
            c = [result(1)%summary%layout%column("X_" // to_text(n + 1)), &
                & result(2)%summary%layout%column("X_" // to_text(n + 1))]
            do k = 1, rows(1)%count
                worst = max(worst, abs(rows(1)%rows(c(1), k) - rows(2)%rows(c(2), k)), &
                    & abs(rows(1)%rows(c(1) + 2, k) - rows(2)%rows(c(2) + 2, k)))
            end do
        end do
        call check(error, worst <= tol_twin, "largest distance of the arms' centres from the " &
            & // "twin never re-based: " // to_text(worst) // " m")
    end subroutine test_rebasing_j

    !> A part held only in its angles (JPRIM PARALLEL_AXES, JPRIM ORIENTATION), spinning and
    !> falling freely, on IDA (the default) at ERROR = 1e-10: its multipliers start at 4e-4
    !> N m, 2e-5 of its weight, and IDA failed its first step until their absolute tolerance
    !> got a floor of 1e-5 of the model's weight (rollcon_ida). The run completes with the
    !> joint held and the energy kept (check_held), and falls as a free body: its centre
    !> 0.5 g t^2 below its start after 1 s, to 1e-8 m.
    subroutine test_angles_on_ida(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: kinds(2) = [character(len=13) :: "PARALLEL_AXES", &
            & "ORIENTATION"]
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: fall
        integer :: n, cz

        do n = 1, size(kinds)
            call run_text("angles.adm", "a part held in its angles, on IDA" // nl &
                & // "PART/1, GROUND" // nl &
                & // "MARKER/10, PART=1, QP=0.1, -0.2, 0.3, REULER=30D, 40D, 50D" // nl &
                & // "PART/2, MASS=2, CM=20, IP=0.02, 0.03, 0.04, QG=0.1, -0.2, 0.3" // nl &
                & // ", REULER=30D, 40D, 50D, WX=1, WY=-2, WZ=3" // nl &
                & // "MARKER/20, PART=2, QP=0.05, 0.1, -0.2, REULER=10D, 70D, 20D" // nl &
                & // "MARKER/21, PART=2, REULER=0, 0, 0" // nl &
                & // "JPRIM/7, " // trim(kinds(n)) // ", I=21, J=10" // nl &
                & // "ACCGRAV/KGRAV=-9.81" // nl &
                & // "SIMULATE/DYNAMIC, END=1, DTOUT=0.01" // nl &
                & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
            if (allocated(error)) then
                error%message = trim(kinds(n)) // ": " // error%message
                return
            end if
            call check_held(result, error)
            if (allocated(error)) then
                error%message = trim(kinds(n)) // ": " // error%message
                return
            end if
            cz = result%summary%layout%column("Z_2")
            fall = rows%rows(cz, 1) - rows%rows(cz, rows%count)
            call check(error, fall, 0.5_wp*9.81_wp, trim(kinds(n)) // ": the fall in 1 s [m]", &
                & abs_tol=1.0e-8_wp)
            if (allocated(error)) return
        end do
    end subroutine test_angles_on_ida

    !> data/pendulum.adm with its joint written the other way round, I on the ground and J on
    !> the bob (JOINT/1, REVOLUTE, I=10, J=21), and with its hinge a JPRIM ATPOINT plus a JPRIM
    !> PARALLEL_AXES written so: the same motion, the routines serving it from the bob's side
    !> (a joint is symmetric in its markers).
    subroutine test_i_on_ground(error)
        type(error_type), allocatable, intent(out) :: error
        !> The same equations, up to the order of their terms: round-off, amplified over 4 s
        !> of a pendulum by its step decisions at rtol 1e-10
        real(wp), parameter :: tol_same = 1.0e-8_wp
        character(len=*), parameter :: joints(2) = [character(len=80) :: &
            & "JOINT/1, REVOLUTE, I=10, J=21", &
            & "JPRIM/1, ATPOINT, I=10, J=21" // nl // "JPRIM/2, PARALLEL_AXES, I=10, J=21"]
        type(history_type) :: rows, twin
        type(job_result_type) :: result, twin_result
        real(wp) :: worst
        integer :: k, n, cx, tx

        call run_file("data/pendulum.adm", twin_result, twin, error)
        if (allocated(error)) return
        tx = twin_result%summary%layout%column("X_2")
        do n = 1, size(joints)
            call run_text("swapped.adm", "pendulum, I on the ground" // nl &
                & // "PART/1, GROUND" // nl &
                & // "MARKER/10, PART=1, REULER=180D, 90D, 0D" // nl &
                & // "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01" // nl &
                & // ", REULER=90D, 60D, -90D" // nl &
                & // "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=0, 90D, 0" // nl &
                & // "MARKER/21, PART=2, REULER=180D, 90D, 0D" // nl &
                & // trim(joints(n)) // nl &
                & // "ACCGRAV/KGRAV=-9.81" // nl &
                & // "SIMULATE/DYNAMIC, END=4, DTOUT=0.001" // nl &
                & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
            if (allocated(error)) return
            call check_held(result, error)
            if (allocated(error)) return
            cx = result%summary%layout%column("X_2")
            worst = 0.0_wp
            do k = 1, min(rows%count, twin%count)
                worst = max(worst, abs(rows%rows(cx, k) - twin%rows(tx, k)), &
                    & abs(rows%rows(cx + 2, k) - twin%rows(tx + 2, k)))
            end do
            call check(error, rows%count == twin%count .and. worst <= tol_same, &
                & trim(joints(n)) // ": " // to_text(rows%count) // " rows against " &
                & // to_text(twin%count) // ", largest distance from data/pendulum.adm " &
                & // to_text(worst) // " m")
            if (allocated(error)) return
        end do
    end subroutine test_i_on_ground

    !> The pendulum with its hinge marker J 1 mm above the bob's I: the initial-conditions
    !> analysis moves the part so that the two meet, and the bob is then 0.5 m from the
    !> hinge, where the joint holds it.
    subroutine test_apart(error)
        type(error_type), allocatable, intent(out) :: error
        !> The analysis's Newton steps end at round-off: 1e-12 m
        real(wp), parameter :: tol_meet = 1.0e-12_wp
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: distance, moved
        integer :: cx

        call run_text("apart.adm", "pendulum, 1 mm apart" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, QP=0, 0, 0.001, REULER=180D, 90D, 0D" // nl &
            & // "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01, REULER=90D, 60D, -90D" // nl &
            & // "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=0, 90D, 0" // nl &
            & // "MARKER/21, PART=2, REULER=180D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I=21, J=10" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "SIMULATE/DYNAMIC, END=0.1, DTOUT=0.01" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        distance = hypot(rows%rows(cx, 1), rows%rows(cx + 2, 1) - 0.001_wp)
        moved = hypot(rows%rows(cx, 1) + 0.5_wp*sin(pi/3.0_wp), rows%rows(cx + 2, 1) &
            & + 0.5_wp*cos(pi/3.0_wp))
        call check(error, abs(distance - 0.5_wp) <= tol_meet .and. moved > 1.0e-4_wp .and. &
            & moved < 1.0e-3_wp, "bob " // to_text(distance) // " m from the hinge at the " &
            & // "start, moved by " // to_text(moved) // " m")
        if (allocated(error)) return
        call check_held(result, error)
    end subroutine test_apart

    !> Each refusal names the file, the line, the statement and the keyword. (Which parts the
    !> markers join is the model's to judge: suite assembly.)
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error

        call refused("JOINT/1, REVOLUTE, J=10", ":8: JOINT/1: I=id is missing", error)
        if (allocated(error)) return
        call refused("JOINT/1, REVOLUTE, I=21", ":8: JOINT/1: J=id is missing", error)
        if (allocated(error)) return
        call refused("JOINT/1, REVOLUTE, I=21, J=99", ":8: JOINT/1 J: no MARKER/99", error)
        if (allocated(error)) return
        call refused("JOINT/1, HINGE, I=21, J=10", ":8: JOINT/1: 'HINGE' is not a JOINT " &
            & // "argument", error)
        if (allocated(error)) return
        call refused("JOINT/1, REVOLUTE, I=21, J=10, ICROT=0, 0", ":8: JOINT/1 ICROT: a " &
            & // "joint's initial conditions and its friction are not supported", error)
        if (allocated(error)) return
        call refused("JOINT/1, I=21, J=10", ":8: JOINT/1: the type is missing (one of " &
            & // "CONVEL, CYLINDRICAL, FIXED, HOOKE, PLANAR, REVOLUTE, SPHERICAL, " &
            & // "TRANSLATIONAL, UNIVERSAL; or a coupling, RACKPIN, SCREW)", error)
        if (allocated(error)) return
        call refused("JPRIM/1, INLINE, ORIENTATION, I=21, J=10", ":8: JPRIM/1 ORIENTATION: " &
            & // "the type is given twice (INLINE and ORIENTATION)", error)
        if (allocated(error)) return
        call refused("JOINT/1, REVOLUTE, I=21, J=10" // nl // "JOINT/1, SPHERICAL, I=21, J=10", &
            & ":9: JOINT/1: a second JOINT with this id", error)
        if (allocated(error)) return
        call refused("JPRIM/1, REVOLUTE, I=21, J=10", ":8: JPRIM/1: 'REVOLUTE' is not a " &
            & // "JPRIM argument", error)
        if (allocated(error)) return
        call refused("JOINT/1, SCREW, I=21, J=10", ":8: JOINT/1: a SCREW joint needs " &
            & // "PITCH=p /= 0, the translation per turn [length] (negative for a " &
            & // "left-handed thread)", error)
    end subroutine test_refusals

    !> data/pendulum.adm with its JOINT line replaced by `new` is refused by read_adm with a
    !> message holding `expected` after the file name.
    subroutine refused(new, expected, error)
        character(len=*), intent(in) :: new, expected
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(error_type), allocatable :: failure

        call write_text("refused.adm", "pendulum" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, REULER=180D, 90D, 0D" // nl &
            & // "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01" // nl &
            & // ", REULER=90D, 60D, -90D" // nl &
            & // "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=0, 90D, 0" // nl &
            & // "MARKER/21, PART=2, REULER=180D, 90D, 0D" // nl &
            & // new // nl &
            & // "SIMULATE/DYNAMIC, END=1, STEPS=10" // nl)
        call read_adm(work_dir // "/refused.adm", adm, failure)
        call check(error, allocated(failure), "accepted: " // new)
        if (allocated(error)) return
        call check(error, index(failure%message, work_dir // "/refused.adm" // expected) == 1, &
            & "message '" // failure%message // "', expected '" // expected // "'")
    end subroutine refused

    !> The run completed, its joints' UCONs held (largest residual) and its energy conserved.
    subroutine check_held(result, error)
        type(job_result_type), intent(in) :: result
        type(error_type), allocatable, intent(out) :: error

        call check(error, result%summary%status == status_completed .and. &
            & result%summary%residual_max <= tol_residual .and. &
            & result%summary%energy_drift <= tol_energy, "status " &
            & // to_text(result%summary%status) // ", largest residual " &
            & // to_text(result%summary%residual_max) // ", energy drift " &
            & // to_text(result%summary%energy_drift))
    end subroutine check_held

    !> A measure of a motion the joint leaves free is above 1e-3; one it holds is below 1e-8.
    pure logical function free_or_held(free, measure)
        logical, intent(in) :: free
        real(wp), intent(in) :: measure

        if (free) then
            free_or_held = measure > 1.0e-3_wp
        else
            free_or_held = measure <= 1.0e-8_wp
        end if
    end function free_or_held

    !> K(k), the complete elliptic integral of the first kind, pi / (2 AGM(1, sqrt(1 - k^2))).
    pure function elliptic_k(k) result(value)
        real(wp), intent(in) :: k
        real(wp) :: value, a, b, c
        integer :: i

        a = 1.0_wp
        b = sqrt(1.0_wp - k**2)
        do i = 1, 40
            c = 0.5_wp*(a + b)
            b = sqrt(a*b)
            a = c
        end do
        value = pi/(2.0_wp*a)
    end function elliptic_k

    !> Run a dataset written here.
    subroutine run_text(name, text, result, rows, error)
        character(len=*), intent(in) :: name, text
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error

        call write_text(name, text)
        call run_file(work_dir // "/" // name, result, rows, error)
    end subroutine run_text

    !> Run the dataset at path, writing no file, and keep its rows.
    subroutine run_file(path, result, rows, error)
        character(len=*), intent(in) :: path
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(error_type), allocatable :: failure

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, rows)
        if (allocated(failure)) call move_alloc(failure, error)
    end subroutine run_file

    !> Write text to work_dir/name.
    subroutine write_text(name, text)
        character(len=*), intent(in) :: name, text
        integer :: unit

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
    end subroutine write_text

end module test_adm_joints
