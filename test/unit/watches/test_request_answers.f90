! SPDX-License-Identifier: MIT
!> A dataset's REQUESTs of velocity, acceleration, force and expressions (suite requests,
!> docs/outputs.md "The columns of a dataset's other requests"; datasets in test/requests/):
!> a pendulum's velocity and acceleration against the closed form, a force request with RM
!> against the same vector turned, a force request between markers only an SFORCE joins
!> against the spring's force, F1 ... F8 with FX, JOINT, SFORCE, ACCX ... against the columns
!> they repeat and Newton's law; SPDP, BUSH, VARVAL, AKISPL and CUBSPL against the columns of
!> the elements and VARIABLE they read and the SPLINE's points, and the requests' COMMENTs in
!> the summary; a marker's acceleration against the derivative of its velocity; a force or an
!> acceleration read in a force's FUNCTION refused by statement and line; ADAMS's ORIENT of a
!> part turned by known angles against those angles and the Euler parameters worked by hand,
!> and DIF, DIF1 against the DIFF's own columns.
module test_request_answers
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix, transpose_times
    use rollcon_marker, only : marker_type, marker_motion
    use rollcon_marker_acceleration, only : marker_acceleration
    use rollcon_load, only : load_job
    use rollcon_job, only : job_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_request_answers

    !> Gravity of the datasets [m/s^2]
    real(wp), parameter :: g = 9.81_wp
    !> The pendulum: mass [kg], hinge to centre [m], moment of inertia about the hinge's axis
    !> [kg m^2] (0.01 about the centre: the principal z axis, along the hinge, plus m L^2),
    !> released at rest at 70 degrees
    real(wp), parameter :: mass = 2.0_wp, length = 0.8_wp, inertia = 0.01_wp + mass*length**2
    !> Where the tests write their datasets
    character(len=*), parameter :: work_dir = "build/rollcon-test"
    character(len=*), parameter :: nl = new_line("a")

contains

    subroutine collect_request_answers(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("pendulum-velocity-and-acceleration", test_pendulum_motion), &
            & new_unittest("force-with-rm-turned", test_force_rm), &
            & new_unittest("pendulum-expressions", test_pendulum_expressions), &
            & new_unittest("force-between-spring-markers", test_spring), &
            & new_unittest("elements-variables-curves-comments", test_elements), &
            & new_unittest("marker-acceleration-is-the-derivative", test_marker_acceleration), &
            & new_unittest("motion-force-function", test_motion), &
            & new_unittest("force-functions-refused-in-forces", test_refusals), &
            & new_unittest("orient-of-known-angles", test_orient), &
            & new_unittest("dif-reads-the-diff-columns", test_dif)]
    end subroutine collect_request_answers

    !> test/requests/pendulum.adm, REQUEST/4 (VELOCITY) and /5 (ACCELERATION) of the centre
    !> (MARKER/20) from the hinge (MARKER/10, on ground), ground axes. With theta the angle from
    !> the downward vertical (x = L sin(theta), z = -L cos(theta)) and the hinge along ground Y,
    !> w_y = -theta' and the closed forms: v = L theta' (cos, sin), theta'^2 = 2 m g L (cos(theta)
    !> - cos(theta0)) / I (energy), a = L theta'' (cos, sin) + L theta'^2 (-sin, cos) with
    !> theta'' = -m g L sin(theta) / I (the equation of motion), alpha_y = -theta''. theta' is
    !> the row's own (from the centre's velocity across the bar).
    subroutine test_pendulum_motion(error)
        type(error_type), allocatable, intent(out) :: error
        !> The velocity across the bar against v (the row's own rate): the centre's velocity
        !> along the bar is the hinge's drift rate, held by IDA at ERROR = 1e-10 (measured:
        !> 5.3e-10 m/s of 3.6 m/s); 2e-9 catches a fourfold loss
        real(wp), parameter :: tol_velocity = 2.0e-9_wp
        !> theta'^2 against the energy's closed form: the integrator's energy error over 3 s
        !> (measured 1.1e-7 rad^2/s^2 of 20); 5e-7 catches a fivefold loss
        real(wp), parameter :: tol_rate = 5.0e-7_wp
        !> The accelerations against the equation of motion at the row's own state: exact but for
        !> the constraint's drift (measured 5.0e-10 m/s^2 of 22 and 6.4e-11 rad/s^2); 3e-9
        !> catches a sixfold loss, and an acceleration from differences of rows (0.005 s apart:
        !> errors of 1e-4) by far
        real(wp), parameter :: tol_acceleration = 3.0e-9_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: x, z, theta, rate, second, theta0, v(3), w(3), a(3), alpha(3), &
            & worst(4)
        integer :: k

        call run_dataset("test/requests/pendulum.adm", result, rows, error)
        if (allocated(error)) return
        theta0 = 70.0_wp*pi/180.0_wp
        worst = 0.0_wp
        associate (layout => rows%layout)
            do k = 1, rows%count
                x = rows%rows(layout%column("X_2"), k)
                z = rows%rows(layout%column("Z_2"), k)
                theta = atan2(x, -z)
                rate = (rows%rows(layout%column("Xdot_2"), k)*cos(theta) &
                    & + rows%rows(layout%column("Zdot_2"), k)*sin(theta))/length
                second = -mass*g*length*sin(theta)/inertia
                v = rows%rows(layout%column("req4_vx"):layout%column("req4_vz"), k)
                w = rows%rows(layout%column("req4_wx"):layout%column("req4_wz"), k)
                a = rows%rows(layout%column("req5_accx"):layout%column("req5_accz"), k)
                alpha = rows%rows(layout%column("req5_wdtx"):layout%column("req5_wdtz"), k)
                worst(1) = max(worst(1), maxval(abs(v - length*rate*[cos(theta), 0.0_wp, &
                    & sin(theta)])), maxval(abs(w - [0.0_wp, -rate, 0.0_wp])))
                worst(2) = max(worst(2), abs(rate**2 - 2.0_wp*mass*g*length*(cos(theta) &
                    & - cos(theta0))/inertia))
                worst(3) = max(worst(3), maxval(abs(a - (length*second*[cos(theta), 0.0_wp, &
                    & sin(theta)] + length*rate**2*[-sin(theta), 0.0_wp, cos(theta)]))))
                worst(4) = max(worst(4), maxval(abs(alpha - [0.0_wp, -second, 0.0_wp])))
            end do
        end associate
        call check(error, worst(1) <= tol_velocity .and. worst(2) <= tol_rate .and. &
            & worst(3) <= tol_acceleration .and. worst(4) <= tol_acceleration, &
            & "largest errors: velocity " // to_text(worst(1)) // " m/s, theta'^2 " &
            & // to_text(worst(2)) // " rad^2/s^2, acceleration " // to_text(worst(3)) &
            & // " m/s^2, angular " // to_text(worst(4)) // " rad/s^2")
    end subroutine test_pendulum_motion

    !> REQUEST/6 is REQUEST/1 (the hinge's force and torque on the bar at MARKER/21) with
    !> RM = MARKER/20, the bar's CM marker, whose axes are its principal axes: R(psi, theta,
    !> phi)^T times REQUEST/1's ground components, R from the row's own angles.
    subroutine test_force_rm(error)
        type(error_type), allocatable, intent(out) :: error
        !> Rounding of forces below 45 N turned (measured 0: the same products of the same
        !> axes); a wrong axis, or the rotation the other way, is off by newtons
        real(wp), parameter :: tol_turned = 1.0e-13_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: axes(3, 3), plain(6), turned(6), worst, largest
        integer :: k

        call run_dataset("test/requests/pendulum.adm", result, rows, error)
        if (allocated(error)) return
        worst = 0.0_wp
        largest = 0.0_wp
        associate (layout => rows%layout)
            do k = 1, rows%count
                axes = rotation_matrix(rows%rows(layout%column("psi_2"), k), &
                    & rows%rows(layout%column("theta_2"), k), &
                    & rows%rows(layout%column("phi_2"), k))
                plain = rows%rows(layout%column("req1_fx"):layout%column("req1_tz"), k)
                turned = rows%rows(layout%column("req6_fx"):layout%column("req6_tz"), k)
                worst = max(worst, maxval(abs(turned(1:3) - transpose_times(axes, &
                    & plain(1:3)))), maxval(abs(turned(4:6) - transpose_times(axes, &
                    & plain(4:6)))))
                largest = max(largest, norm2(plain(1:3)))
            end do
        end associate
        call check(error, worst <= tol_turned .and. largest > 10.0_wp, "REQUEST/6 against " &
            & // "REQUEST/1 turned into MARKER/20's axes: largest difference " // to_text(worst) &
            & // " N (forces up to " // to_text(largest) // " N)")
    end subroutine test_force_rm

    !> REQUEST/7's F2 ... F8 against the columns they repeat, at every row: FX(21, 10) (every
    !> force between the hinge's markers: the joint's) and JOINT(1, 0, 2, 0) are joint1_fx,
    !> JOINT(1, 1, 4, 0) (at J) is req2_fz, ACCX(20) is req5_accx, WDTY(20, 0, 0, 20) (the
    !> derivative in the bar's own frame, w x w = 0) is req5_wdty, all to the bit (the same
    !> numbers through another path); TM(21), the hinge's moment, is rounding; FM(21, 10) -
    !> JOINT(1, 0, 1, 20) is zero (a magnitude in any axes).
    subroutine test_pendulum_expressions(error)
        type(error_type), allocatable, intent(out) :: error
        !> The hinge's moment: rounding of 45 N times a metre (measured 1.4e-13 N m)
        real(wp), parameter :: tol_zero = 1.0e-12_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        logical :: same
        real(wp) :: worst
        integer :: k

        call run_dataset("test/requests/pendulum.adm", result, rows, error)
        if (allocated(error)) return
        same = .true.
        worst = 0.0_wp
        associate (layout => rows%layout, r => rows%rows)
            do k = 1, rows%count
                same = same .and. r(layout%column("req7_f2"), k) == r(layout%column("joint1_fx"), &
                    & k) .and. r(layout%column("req7_f3"), k) == r(layout%column("joint1_fx"), k) &
                    & .and. r(layout%column("req7_f4"), k) == r(layout%column("req2_fz"), k) &
                    & .and. r(layout%column("req7_f5"), k) == r(layout%column("req5_accx"), k) &
                    & .and. r(layout%column("req7_f6"), k) == r(layout%column("req5_wdty"), k) &
                    & .and. r(layout%column("req7_f8"), k) == 0.0_wp
                worst = max(worst, abs(r(layout%column("req7_f7"), k)))
            end do
            call check(error, same .and. worst <= tol_zero .and. abs(r(layout%column( &
                & "req7_f2"), 1)) > 1.0_wp, "REQUEST/7's expressions against their columns: " &
                & // "the same " // trim(merge("yes", "no ", same)) // ", TM(21) up to " &
                & // to_text(worst) // " N m")
        end associate
    end subroutine test_pendulum_expressions

    !> test/requests/spring.adm: a 1.5 kg ball on a spring (SFORCE between MARKER/20 and the
    !> ground's MARKER/11, -40 (|d| - 0.5) along d = r_20 - r_11), no joint. REQUEST/1, FORCE,
    !> I=20, J=11 is the spring's force on the ball, from REQUEST/2's d, with no torque;
    !> REQUEST/3: SFORCE(1, 0, 2, 0), FX(20, 11) are req1_fx and FZ(20) req1_fz to the bit
    !> (the spring is the only force at MARKER/20), SFORCE(1, 1, 4, 0) (at the anchor) their
    !> opposite; ACCX(20), ACCZ(20) and ACCM(20) are Newton's (F + m g)/m.
    subroutine test_spring(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: ball = 1.5_wp, stiffness = 40.0_wp, free_length = 0.5_wp
        !> Rounding of forces below 20 N and accelerations below 15 m/s^2 (measured 2.9e-15);
        !> a wrong direction or a missing g is off by units
        real(wp), parameter :: tol_rounding = 3.0e-14_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: d(3), force(6), expected(3), acceleration(3), worst
        logical :: same
        integer :: k

        call run_dataset("test/requests/spring.adm", result, rows, error)
        if (allocated(error)) return
        worst = 0.0_wp
        same = .true.
        associate (layout => rows%layout, r => rows%rows)
            do k = 1, rows%count
                d = r(layout%column("req2_x"):layout%column("req2_z"), k)
                force = r(layout%column("req1_fx"):layout%column("req1_tz"), k)
                expected = -stiffness*(norm2(d) - free_length)*d/norm2(d)
                acceleration = force(1:3)/ball + [0.0_wp, 0.0_wp, -g]
                worst = max(worst, maxval(abs(force(1:3) - expected)), &
                    & maxval(abs(force(4:6))), abs(r(layout%column("req3_f5"), k) &
                    & - acceleration(1)), abs(r(layout%column("req3_f6"), k) &
                    & - acceleration(3)), abs(r(layout%column("req3_f8"), k) &
                    & - norm2(acceleration)))
                same = same .and. r(layout%column("req3_f2"), k) == force(1) .and. &
                    & r(layout%column("req3_f3"), k) == force(1) .and. &
                    & r(layout%column("req3_f4"), k) == force(3) .and. &
                    & r(layout%column("req3_f7"), k) == -force(3)
            end do
            call check(error, worst <= tol_rounding .and. same .and. abs(r(layout%column( &
                & "req2_y"), rows%count)) > 0.01_wp, "the spring's requests: largest " &
                & // "difference " // to_text(worst) // ", the same numbers " &
                & // trim(merge("yes", "no ", same)))
        end associate
    end subroutine test_spring

    !> test/requests/elements.adm: REQUEST/3 reads SPRINGDAMPER/1 (SPDP), BUSHING/2 (BUSH, and
    !> BUSHING as rollcon names it), VARIABLE/5 and SPLINE/6. SPDP(1, 0, 2, 0) and BUSH(2, 0, 3,
    !> 0) are springdamper1_fx and bushing2_fy to the bit (the same force, ground axes);
    !> SPDP(1, 1, 4, 0), at J, is -springdamper1_fz; BUSHING(2, 1, 8, 0), the torque on J's part
    !> about J's origin, is -T_z - ((r_I - r_J) x F)_z from bushing2_... and REQUEST/1's r_I -
    !> r_J; 2*VARVAL(5) is 2*var5; AKISPL and CUBSPL of TIME at the rows on the knots (t = 0,
    !> 0.5, 1, 1.5, 2) are the SPLINE's Y there. REQUEST/4: VTORQ(4, 0, 8, 0) is VTORQUE/4's TZ,
    !> -0.05 WZ(20), VTORQ(4, 1, 8, 0) its opposite, VTORQ(4, 0, 1, 0) (a force) zero. No
    !> request is named in the warning, and the summary gives each COMMENT with its request's
    !> line and columns.
    subroutine test_elements(error)
        type(error_type), allocatable, intent(out) :: error
        !> The bushing's torque at J from its columns, 2*VARVAL(5) against 2*var5 and the
        !> VTORQUE's against its expression: rounding
        !> of terms below 1 N m (measured 0); a wrong sign or arm is off by the arm's moment, up
        !> to 0.08 N m (checked above 0.01 N m)
        real(wp), parameter :: tol_rounding = 1.0e-14_wp
        !> A curve at a knot: the row's time is the knot to rounding (1e-16 s) times slopes
        !> below 2, and the curve passes through its points (measured 1.4e-16); a curve read at
        !> the wrong knot or SPLINE is off by 0.1 or more
        real(wp), parameter :: tol_knot = 1.0e-13_wp
        real(wp), parameter :: knots(5) = [0.0_wp, 0.5_wp, 1.0_wp, 1.5_wp, 2.0_wp], &
            & points(5) = [0.0_wp, 0.3_wp, -0.2_wp, 0.4_wp, 0.1_wp]
        type(job_result_type) :: result
        type(history_type) :: rows
        type(job_type) :: job
        real(wp) :: arm(3), force(3), torque(3), worst, worst_curve, largest, time
        logical :: same
        integer :: k, m, on_knots

        call load_job("test/requests/elements.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed, "elements.adm: status " &
            & // to_text(result%summary%status))
        if (allocated(error)) return
        call check(error, index(job%source%warning, "REQUEST") == 0, "a request named in the " &
            & // "warning: " // job%source%warning)
        if (allocated(error)) return
        worst = 0.0_wp
        worst_curve = 0.0_wp
        largest = 0.0_wp
        same = .true.
        on_knots = 0
        associate (layout => rows%layout, r => rows%rows)
            do k = 1, rows%count
                arm = r(layout%column("req1_x"):layout%column("req1_z"), k)
                force = r(layout%column("bushing2_fx"):layout%column("bushing2_fz"), k)
                torque = r(layout%column("bushing2_tx"):layout%column("bushing2_tz"), k)
                worst = max(worst, abs(r(layout%column("req3_f5"), k) - (-torque(3) &
                    & - (arm(1)*force(2) - arm(2)*force(1)))))
                largest = max(largest, abs(arm(1)*force(2) - arm(2)*force(1)))
                same = same .and. r(layout%column("req3_f2"), k) &
                    & == r(layout%column("springdamper1_fx"), k) .and. &
                    & r(layout%column("req3_f3"), k) == -r(layout%column("springdamper1_fz"), k) &
                    & .and. r(layout%column("req3_f4"), k) == r(layout%column("bushing2_fy"), k)
                worst = max(worst, abs(r(layout%column("req3_f6"), k) &
                    & - 2.0_wp*r(layout%column("var5"), k)), abs(r(layout%column("req4_f2"), k) &
                    & + 0.05_wp*r(layout%column("req4_f3"), k)), abs(r(layout%column("req4_f4"), &
                    & k) + r(layout%column("req4_f2"), k)), abs(r(layout%column("req4_f5"), k)))
                time = r(1, k)
                do m = 1, size(knots)
                    if (abs(time - knots(m)) > 1.0e-9_wp) cycle
                    on_knots = on_knots + 1
                    worst_curve = max(worst_curve, abs(r(layout%column("req3_f7"), k) &
                        & - points(m)), abs(r(layout%column("req3_f8"), k) - points(m)))
                end do
            end do
        end associate
        call check(error, same .and. worst <= tol_rounding .and. worst_curve <= tol_knot .and. &
            & on_knots == size(knots) .and. largest > 0.01_wp, "REQUEST/3 against the columns " &
            & // "it repeats: the same numbers " // trim(merge("yes", "no ", same)) &
            & // ", largest difference " // to_text(worst) // ", the curves off their points " &
            & // "by " // to_text(worst_curve) // " at " // to_text(on_knots) // " knots, " &
            & // "the bushing's arm moment up to " // to_text(largest) // " N m")
        if (allocated(error)) return
        ! the notes the summary prints after the record and warning (rollcon_run_job)
        call check(error, index(job%source%model_notes(), "REQUEST/1 (line 22; req1_x ... " &
            & // "req1_phi): the bushing I from its J") > 0 .and. index(job%source%model_notes(), &
            & "REQUEST/3 (line 23; req3_f2, req3_f3, req3_f4, req3_f5, req3_f6, req3_f7, " &
            & // "req3_f8): elements and curves") > 0, "the comments in the summary's notes: " &
            & // job%source%model_notes())
    end subroutine test_elements

    !> rollcon_marker_acceleration against the derivative of marker_motion's velocity and
    !> angular velocity along a motion of constant accelerations (q = q0 + u0 t + a t^2/2),
    !> by central differences of step h (error h^2/6 times the third derivative: below 1e-8
    !> here), at a state away from every symmetry; and a part spinning about ground Z at a
    !> constant rate: the centripetal -w^2 r, no angular acceleration.
    subroutine test_marker_acceleration(error)
        type(error_type), allocatable, intent(out) :: error
        !> Central differences of step 1e-5: truncation h^2/6 times third derivatives of order
        !> 10 (~2e-10) and rounding 1e-16/1e-5 = 1e-11 (measured 7e-10, falling as h^2: 7e-8 at h =
        !> 1e-4); a missing term of the formulas is of order 1
        real(wp), parameter :: h = 1.0e-5_wp, tol_difference = 2.0e-9_wp
        !> The spin: rounding
        real(wp), parameter :: tol_spin = 1.0e-13_wp
        type(marker_type) :: marker
        real(wp) :: q0(6), u0(6), a(6), r(3), v_plus(3), v_minus(3), w_plus(3), w_minus(3), &
            & axes(3, 3), acceleration(3), alpha(3), spin, arm(3)

        marker = marker_type(id=7, part=1, point=[0.3_wp, -0.2_wp, 0.5_wp])
        q0 = [0.1_wp, 0.2_wp, -0.3_wp, 0.4_wp, 1.1_wp, -0.7_wp]
        u0 = [0.5_wp, -0.4_wp, 0.3_wp, 1.3_wp, -0.8_wp, 2.1_wp]
        a = [0.2_wp, 0.7_wp, -1.1_wp, -0.9_wp, 1.7_wp, 0.6_wp]
        call marker_acceleration(marker, q0, u0, a, acceleration, alpha)
        call marker_motion(marker, q0 + u0*h + a*h**2/2.0_wp, u0 + a*h, r, v_plus, axes, w_plus)
        call marker_motion(marker, q0 - u0*h + a*h**2/2.0_wp, u0 - a*h, r, v_minus, axes, &
            & w_minus)
        call check(error, [acceleration, alpha], [(v_plus - v_minus)/(2.0_wp*h), &
            & (w_plus - w_minus)/(2.0_wp*h)], "a marker's acceleration and angular " &
            & // "acceleration against the derivatives [m/s^2, rad/s^2]", abs_tol=tol_difference)
        if (allocated(error)) return
        spin = 3.0_wp
        q0 = [0.0_wp, 0.0_wp, 0.0_wp, 0.4_wp, 1.1_wp, -0.7_wp]
        u0 = [0.0_wp, 0.0_wp, 0.0_wp, spin, 0.0_wp, 0.0_wp]
        call marker_acceleration(marker, q0, u0, spread(0.0_wp, 1, 6), acceleration, alpha)
        call marker_motion(marker, q0, u0, arm, v_plus, axes, w_plus)
        call check(error, [acceleration, alpha], [-spin**2*arm(1), -spin**2*arm(2), 0.0_wp, &
            & 0.0_wp, 0.0_wp, 0.0_wp], "a marker spinning about Z at 3 rad/s [m/s^2, rad/s^2]", &
            & abs_tol=tol_spin)
    end subroutine test_marker_acceleration

    !> A 2 kg slider driven along a TRANSLATIONAL joint's axis e (MARKER/10's z, rising at 30
    !> degrees) by MOTION/1: MOTION(1, 0, 4, 10), the force the motion exerts on the slider along
    !> e (in MARKER/10's axes, whose z is e), is its column motion1_force (the multiplier, m (s''
    !> - g.e)); MOTION(1, 0, 2, 10), across e, and MOTION(1, 0, 8, 10), a torque about the
    !> slider's centre, are zero; MOTION(1, 1, 4, 10), at J on the ground, is the opposite.
    subroutine test_motion(error)
        type(error_type), allocatable, intent(out) :: error
        !> Rounding of a 10 N force through the constraint row's unit axis (measured 1e-31)
        real(wp), parameter :: tol_rounding = 1.0e-13_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: worst, largest
        integer :: k

        call write_text("motion_force.adm", "slider driven by a MOTION" // nl &
            & // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, REULER=90D, 60D, 0D" // nl &
            & // "PART/2, MASS=2, CM=20, IP=1, 1, 0.1" // nl &
            & // "MARKER/20, PART=2, REULER=90D, 60D, 0D" // nl &
            & // "JOINT/1, TRANSLATIONAL, I=20, J=10" // nl &
            & // "MOTION/1, JOINT=1, TRANSLATION, FUNCTION=-0.15 + 0.01*SIN(2*PI*TIME)" // nl &
            & // "REQUEST/2, F2=MOTION(1, 0, 4, 10)\F3=MOTION(1, 0, 2, 10)\" &
            & // "F4=MOTION(1, 1, 4, 10)\F8=MOTION(1, 0, 8, 10)" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl // "SIMULATE/DYNAMIC, END=1, STEPS=50" // nl &
            & // "END")
        call run_dataset(work_dir // "/motion_force.adm", result, rows, error)
        if (allocated(error)) return
        worst = 0.0_wp
        largest = 0.0_wp
        associate (layout => rows%layout, r => rows%rows)
            do k = 1, rows%count
                associate (force => r(layout%column("motion1_force"), k))
                    worst = max(worst, abs(r(layout%column("req2_f2"), k) - force), &
                        & abs(r(layout%column("req2_f3"), k)), abs(r(layout%column("req2_f4"), &
                        & k) + force), abs(r(layout%column("req2_f8"), k)))
                    largest = max(largest, abs(force))
                end associate
            end do
        end associate
        call check(error, worst <= tol_rounding .and. largest > 5.0_wp, "MOTION(1, ...) " &
            & // "against motion1_force: largest difference " // to_text(worst) // " N of " &
            & // to_text(largest) // " N")
    end subroutine test_motion

    !> A force or an acceleration read in a force's FUNCTION is an algebraic loop: refused with
    !> the statement, its line and the function; a REQUEST's element function naming a
    !> statement the dataset lacks (JOINT/7, BUSH(7, ...): no BUSHING/7, the function named as
    !> written and ADAMS names it, the statement in full), a VARVAL of a VARIABLE, an AKISPL of
    !> a SPLINE or a DIF1 of a DIFF it lacks: refused with the REQUEST, its line and Fk; an
    !> ORIENT (of a system with no exact partials) in a force: refused; one of a kind rollcon
    !> has no statement for (BEAM), or one it cannot read (an ORIENT system ADAMS does not
    !> have, 30): that column named in the warning, not answered.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: head = "refused" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/11, PART=1, QP=0, 0, 1" // nl &
            & // "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01" // nl // "MARKER/20, PART=2" // nl
        character(len=*), parameter :: tail = nl // "SIMULATE/DYNAMIC, END=1, STEPS=10"
        character(len=*), parameter :: statements(9) = [character(len=80) :: &
            & "SFORCE/1, TRANSLATIONAL, I=20, J=11, FUNCTION=-FX(20)", &
            & "SFORCE/1, TRANSLATIONAL, I=20, J=11, FUNCTION=ACCZ(20, 11)", &
            & "VFORCE/2, I=20, JFLOAT=11, RM=11, FX=JOINT(1, 0, 2, 0), FY=0, FZ=0", &
            & "REQUEST/3, F2=DX(20)\F3=JOINT(7, 0, 2, 0)", &
            & "REQUEST/3, F2=DX(20)\F3=BUSH(7, 0, 2, 0)", &
            & "REQUEST/3, F2=DX(20)\F3=VARVAL(9)", &
            & "REQUEST/3, F2=DX(20)\F3=AKISPL(TIME, 0, 9)", &
            & "SFORCE/1, TRANSLATIONAL, I=20, J=11, FUNCTION=ORIENT(27, 1, 20)", &
            & "REQUEST/3, F2=DX(20)\F3=DIF1(9)"]
        character(len=*), parameter :: expected(9) = [character(len=120) :: &
            & "refused.adm:7: SFORCE/1 FUNCTION: FX(20): a force, which rollcon solves for", &
            & "refused.adm:7: SFORCE/1 FUNCTION: ACCZ(20, 11): an acceleration", &
            & "refused.adm:7: VFORCE/2 FX: JOINT(1, 0, 2, 0): a force", &
            & "refused.adm:7: REQUEST/3 F3: JOINT(7, 0, 2, 0): no JOINT/7", &
            & "refused.adm:7: REQUEST/3 F3: BUSH(7, 0, 2, 0): no BUSHING/7", &
            & "refused.adm:7: REQUEST/3 F3: VARVAL(9): no VARIABLE/9", &
            & "refused.adm:7: REQUEST/3 F3: AKISPL reads SPLINE/9, which the dataset lacks", &
            & "refused.adm:7: SFORCE/1 FUNCTION: ORIENT(27, 1, 20): ORIENT of system 27 is " &
            & // "answered in a REQUEST only", &
            & "refused.adm:7: REQUEST/3 F3: DIF1(9): no DIFF/9 in the dataset"]
        type(job_type) :: job
        type(job_result_type) :: result
        type(error_type), allocatable :: failure
        integer :: k

        do k = 1, size(statements)
            call write_text("refused.adm", head // trim(statements(k)) // tail)
            call load_job(work_dir // "/refused.adm", job, failure)
            if (.not. allocated(failure)) then
                job%output_dir = ""
                job%quiet = .true.
                call run_job(job, result, failure)
            end if
            call check(error, allocated(failure), trim(statements(k)) // " is not refused")
            if (allocated(error)) return
            call check(error, index(failure%message, trim(expected(k))) > 0, "the refusal of " &
                & // trim(statements(k)) // ": " // failure%message)
            if (allocated(error)) return
            deallocate(failure)
        end do
        ! what rollcon has no statement for is not a refusal: that column is named in the
        ! warning, the others answered
        call write_text("warned.adm", head // "REQUEST/3, F2=DX(20)\F3=BEAM(7, 0, 2, 0)" &
            & // tail)
        call load_job(work_dir // "/warned.adm", job, failure)
        if (.not. allocated(failure)) then
            job%output_dir = ""
            job%quiet = .true.
            call run_job(job, result, failure)
        end if
        call check(error, .not. allocated(failure), "REQUEST/3 reading BEAM refused")
        if (allocated(error)) return
        call check(error, index(job%source%warning, "REQUEST F1..F8 reading BEAM (line 7)") &
            & > 0 .and. result%summary%layout%column("req3_f2") > 0 .and. &
            & result%summary%layout%column("req3_f3") == 0, "the warning: " &
            & // job%source%warning)
        if (allocated(error)) return
        ! nor is an expression rollcon cannot read (an ORIENT system that is not ADAMS's):
        ! named, the others answered
        call write_text("warned.adm", head // "REQUEST/3, F2=DX(20)\F3=ORIENT(30, 1, 20)" &
            & // tail)
        call load_job(work_dir // "/warned.adm", job, failure)
        if (.not. allocated(failure)) then
            job%output_dir = ""
            job%quiet = .true.
            call run_job(job, result, failure)
        end if
        call check(error, .not. allocated(failure), "REQUEST/3 reading ORIENT refused")
        if (allocated(error)) return
        call check(error, index(job%source%warning, "REQUEST F3 it cannot read (ORIENT's " &
            & // "system must be a whole number from 1 to 29") > 0 .and. &
            & result%summary%layout%column("req3_f2") > 0 .and. &
            & result%summary%layout%column("req3_f3") == 0, "the warning: " &
            & // job%source%warning)
    end subroutine test_refusals

    !> test/requests/orient.adm: MARKER/21's axes are A = Rz(30) Rx(40) Ry(50) (degrees) in
    !> the ground's, Rx(40) Ry(50) in MARKER/11's (the dataset's header), at every row (no
    !> force, no speed). Worked by hand: ORIENT(3, ...) (body 3-1-2) is 30, 40, 50; ORIENT(17,
    !> ...) (space 2-1-3) 50, 40, 30; ORIENT(1, ..., 21, 11) (body 1-2-3) 40, 50, 0; the Euler
    !> parameters (27) the Hamilton product of the three half-angle quaternions (c + s axis),
    !> relative to MARKER/11 (c20 + s20 i)(c25 + s25 j) = (c20 c25, s20 c25, c20 s25,
    !> s20 s25), the Rodrigues parameter (28) their e3/e0 = tan20 tan25; the direction
    !> cosines (29) of z_21 in ground axes Rz(30) Rx(40) (sin50, 0, cos50) = (c30 s50 + s30 s40
    !> c50, s30 s50 - c30 s40 c50, c40 c50); systems 11, 25, 26 the same numbers as PSI, PHI,
    !> AZ and YAW.
    subroutine test_orient(error)
        type(error_type), allocatable, intent(out) :: error
        !> Angles through the matrix of REULERs read in degrees and an atan2 of its entries:
        !> rounding of a few 1e-16 (measured 1.1e-16); a wrong sequence or sign is off by 0.1
        !> or more
        real(wp), parameter :: tol = 1.0e-14_wp
        real(wp), parameter :: d = pi/180.0_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: expected(8, 4), e(0:3), worst
        character(len=8) :: where_worst
        integer :: k, c, r, column

        call run_dataset("test/requests/orient.adm", result, rows, error)
        if (allocated(error)) return
        expected = 0.0_wp
        expected(1:6, 1) = [30.0_wp, 40.0_wp, 50.0_wp, 50.0_wp, 40.0_wp, 30.0_wp]*d
        expected(1:3, 2) = [40.0_wp, 50.0_wp, 0.0_wp]*d
        e = hamilton(half_turn(1, 40.0_wp*d), half_turn(2, 50.0_wp*d))
        expected(4:7, 2) = e
        expected(8, 2) = tan(20.0_wp*d)*tan(25.0_wp*d)
        expected(1:4, 3) = hamilton(hamilton(half_turn(3, 30.0_wp*d), half_turn(1, 40.0_wp*d)), &
            & half_turn(2, 50.0_wp*d))
        expected(5:7, 3) = [cos(30*d)*sin(50*d) + sin(30*d)*sin(40*d)*cos(50*d), &
            & sin(30*d)*sin(50*d) - cos(30*d)*sin(40*d)*cos(50*d), cos(40*d)*cos(50*d)]
        worst = 0.0_wp
        where_worst = ""
        associate (layout => rows%layout, x => rows%rows)
            do r = 1, 4
                do c = 1, 8
                    if (r == 1 .and. c > 6) cycle
                    if (r == 4 .and. (c == 1 .or. c == 4 .or. c == 5 .or. c > 6)) cycle
                    column = layout%column("req" // to_text(r) // "_f" // to_text(c))
                    call check(error, column > 0, "no column req" // to_text(r) // "_f" &
                        & // to_text(c))
                    if (allocated(error)) return
                    do k = 1, rows%count
                        if (abs(x(column, k) - expected(c, r)) <= worst) cycle
                        worst = abs(x(column, k) - expected(c, r))
                        where_worst = "req" // to_text(r) // "_f" // to_text(c)
                    end do
                end do
            end do
        end associate
        call check(error, worst <= tol .and. rows%count == 11, "ORIENT against the angles " &
            & // "worked by hand: off by " // to_text(worst) // " at " // trim(where_worst))
    end subroutine test_orient

    !> test/requests/orient.adm's DIFF/1 (d DIF/dt = 2 TIME, from 0): REQUEST/4's DIF(1) and
    !> DIF1(1) are its columns diff1 and diff1_dot at every row, to the bit (the same state and
    !> the same solve of its equation), and DIF1 is 2 t exactly (its FUNCTION at the row).
    subroutine test_dif(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_result_type) :: result
        type(history_type) :: rows
        logical :: same
        integer :: k

        call run_dataset("test/requests/orient.adm", result, rows, error)
        if (allocated(error)) return
        same = rows%count == 11
        associate (layout => rows%layout, x => rows%rows)
            do k = 1, rows%count
                same = same .and. x(layout%column("req4_f4"), k) == x(layout%column("diff1"), k) &
                    & .and. x(layout%column("req4_f5"), k) == x(layout%column("diff1_dot"), k) &
                    & .and. x(layout%column("req4_f5"), k) == 2.0_wp*x(1, k)
            end do
            call check(error, same .and. x(layout%column("req4_f4"), rows%count) > 0.99_wp, &
                & "DIF(1), DIF1(1) of REQUEST/4 against diff1, diff1_dot and 2 t: last row " &
                & // to_text(x(layout%column("req4_f4"), rows%count)) // ", " &
                & // to_text(x(layout%column("req4_f5"), rows%count)))
        end associate
    end subroutine test_dif

    !> The unit quaternion (cos(angle/2), sin(angle/2) e_axis) of a turn about axis 1, 2, 3.
    pure function half_turn(axis, angle) result(e)
        integer, intent(in) :: axis
        real(wp), intent(in) :: angle
        real(wp) :: e(0:3)

        e = 0.0_wp
        e(0) = cos(angle/2.0_wp)
        e(axis) = sin(angle/2.0_wp)
    end function half_turn

    !> The Hamilton product a b of quaternions (scalar first): the turn b then a, in a's axes.
    pure function hamilton(a, b) result(e)
        real(wp), intent(in) :: a(0:3), b(0:3)
        real(wp) :: e(0:3)

        e(0) = a(0)*b(0) - dot_product(a(1:3), b(1:3))
        e(1:3) = a(0)*b(1:3) + b(0)*a(1:3) + [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), &
            & a(1)*b(2) - a(2)*b(1)]
    end function hamilton

    !> Run a dataset without files, its rows kept; a run that does not complete is an error.
    subroutine run_dataset(path, result, rows, error)
        character(len=*), intent(in) :: path
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed, path // ": status " &
            & // to_text(result%summary%status) // ": " // result%summary%watch_lines)
    end subroutine run_dataset

    !> Write a text file in the tests' folder.
    subroutine write_text(name, text)
        character(len=*), intent(in) :: name, text
        integer :: unit

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
    end subroutine write_text

end module test_request_answers
