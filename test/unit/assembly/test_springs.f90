! SPDX-License-Identifier: MIT
!> Datasets with SPRINGDAMPERs and BUSHINGs, run (suite springs): each motion against its
!> closed form. A mass hanging on a translational SPRINGDAMPER (free length, preload, damping)
!> under gravity follows the damped oscillation about its equilibrium on CVODE and on IDA, and
!> the same spring written as an SFORCE of DM and VR gives the same motion; a rotational
!> SPRINGDAMPER turns a part through its damped torsional oscillation; a BUSHING's three
!> stiffnesses, dampings and preloads along J's axes (one run) and its three about them (a run
!> each) give the damped oscillations of sqrt(k/m) and sqrt(kt/I). The force columns are
!> checked against the definitions at every row.
module test_springs
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix
    use rollcon_run_job, only : job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    use dataset_texts, only : run_text
    implicit none
    private

    public :: collect_springs

    real(wp), parameter :: g = 9.80665_wp
    character(len=*), parameter :: nl = new_line("a")

contains

    subroutine collect_springs(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("mass-on-a-springdamper-is-its-damped-oscillation", &
            & test_hanging_mass), &
            & new_unittest("rotational-springdamper-is-its-torsional-oscillation", &
            & test_torsion), &
            & new_unittest("bushing-stiffnesses-and-dampings-one-by-one", test_bushing), &
            & new_unittest("vtorque-turns-a-part-at-torque-over-inertia", test_vtorque)]
    end subroutine collect_springs

    !> x(t) of m x'' + c x' + k x = k x_e (an underdamped oscillator) from x(0) = x0 at rest
    !> plus v0: x_e + e^(-a t) ((x0 - x_e) cos(w t) + (v0 + a (x0 - x_e))/w sin(w t)),
    !> a = c/(2 m), w = sqrt(k/m - a^2); and its rate.
    pure subroutine damped(m, c, k, x_e, x0, v0, t, x, v)
        real(wp), intent(in) :: m, c, k, x_e, x0, v0, t
        real(wp), intent(out) :: x, v
        real(wp) :: a, w, p, s

        a = c/(2.0_wp*m)
        w = sqrt(k/m - a*a)
        p = x0 - x_e
        s = (v0 + a*p)/w
        x = x_e + exp(-a*t)*(p*cos(w*t) + s*sin(w*t))
        v = exp(-a*t)*(-a*(p*cos(w*t) + s*sin(w*t)) + (-p*w*sin(w*t) + s*w*cos(w*t)))
    end subroutine damped

    !> A 2 kg part hangs from a ground marker on SPRINGDAMPER/1: K = 200 N/m, C = 4 N s/m,
    !> LENGTH = 0.5 m, FORCE = 3 N (the force is -K (DM - LENGTH) - C VR + FORCE along the
    !> line from J to I), let go at rest 0.7 m below the marker under gravity. Its height is
    !> the oscillation about z_e = -(K LENGTH + FORCE + m g)/K, and springdamper1_fz is the
    !> force at every row, on CVODE and on IDA; the same force as an SFORCE reading DM and VR
    !> gives the same heights.
    subroutine test_hanging_mass(error)
        type(error_type), allocatable, intent(out) :: error
        !> Measured at ERROR = 1e-9: 4.3e-8 m (CVODE) and 2.2e-8 m (IDA) of the 0.07 m
        !> amplitude, and the SFORCE's heights 2.8e-8 m (CVODE) and 8.6e-9 m (IDA) from the
        !> SPRINGDAMPER's; 2e-7 m is 4.6 times the largest, below what a tenfold loss gives
        real(wp), parameter :: tol_height = 2.0e-7_wp
        !> The force column against the definition at the row's own state: measured 0 N of
        !> 37 N (the same operations); 1e-10 N allows rounding only
        real(wp), parameter :: tol_force = 1.0e-10_wp
        character(len=*), parameter :: head = "mass on a spring" // nl &
            & // "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART = 1" // nl &
            & // "PART/2, MASS = 2, CM = 20, IP = 1, 1, 1, QG = 0, 0, -0.7, " &
            & // "REULER = 30D, 40D, 0D" // nl // "MARKER/20, PART = 2" // nl
        character(len=*), parameter :: tail = nl // "ACCGRAV/KGRAV = -9.80665" // nl &
            & // "SIMULATE/DYNAMIC, END = 2, STEPS = 40" // nl // "END"
        character(len=*), parameter :: spring = "SPRINGDAMPER/1, TRANSLATIONAL, I = 20, " &
            & // "J = 10, K = 200, C = 4, LENGTH = 0.5, FORCE = 3"
        character(len=*), parameter :: sforce = "SFORCE/1, I = 20, J = 10, TRANSLATION, " &
            & // "FUNCTION = -200*(DM(20, 10) - 0.5) - 4*VR(20, 10) + 3"
        character(len=*), parameter :: formulations(2) = [character(len=5) :: "CVODE", "IDA"]
        real(wp), parameter :: m = 2.0_wp, k = 200.0_wp, c = 4.0_wp, length = 0.5_wp, &
            & preload = 3.0_wp
        type(job_result_type) :: result
        type(history_type) :: rows, other
        real(wp) :: z_e, z, v, worst, worst_force, worst_apart, t, expected_force
        integer :: f, r, cz, cf, cx

        z_e = -(k*length + preload + m*g)/k
        do f = 1, size(formulations)
            call run_text("springdamper.adm", head // spring // nl // "INTEGRATOR/ERROR = " &
                & // "1e-9, FORMULATION = " // trim(formulations(f)) // tail, result, rows, &
                & error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. &
                & rows%count == 41, trim(formulations(f)) // ": the run completes, 41 rows")
            if (allocated(error)) return
            cx = result%summary%layout%column("X_2")
            cz = result%summary%layout%column("Z_2")
            cf = result%summary%layout%column("springdamper1_fx")
            call check(error, cx > 0 .and. cz > 0 .and. cf > 0, "columns X_2, Z_2 and " &
                & // "springdamper1_fx ... _tz")
            if (allocated(error)) return
            worst = 0.0_wp
            worst_force = 0.0_wp
            do r = 1, rows%count
                t = rows%rows(1, r)
                call damped(m, c, k, z_e, -0.7_wp, 0.0_wp, t, z, v)
                worst = max(worst, abs(rows%rows(cz, r) - z), abs(rows%rows(cx, r)), &
                    & abs(rows%rows(cx + 1, r)))
                ! below the marker: DM = -Z, VR = -Z', the force on I along -z
                expected_force = -(-k*(-rows%rows(cz, r) - length) &
                    & - c*(-rows%rows(cz + 6, r)) + preload)
                worst_force = max(worst_force, abs(rows%rows(cf + 2, r) - expected_force), &
                    & maxval(abs(rows%rows([cf, cf + 1, cf + 3, cf + 4, cf + 5], r))))
            end do
            call check(error, worst <= tol_height, trim(formulations(f)) // ": largest " &
                & // "distance from the damped oscillation " // to_text(worst) // " m")
            if (allocated(error)) return
            call check(error, worst_force <= tol_force, trim(formulations(f)) // ": largest " &
                & // "difference of springdamper1_fx ... _tz from the definition " &
                & // to_text(worst_force) // " N")
            if (allocated(error)) return
            call run_text("sforce_spring.adm", head // sforce // nl // "INTEGRATOR/ERROR = " &
                & // "1e-9, FORMULATION = " // trim(formulations(f)) // tail, result, other, &
                & error)
            if (allocated(error)) return
            worst_apart = maxval(abs(other%rows(cz, :other%count) - rows%rows(cz, :rows%count)))
            call check(error, other%count == rows%count .and. worst_apart <= tol_height, &
                & trim(formulations(f)) // ": the SFORCE of DM and VR moves as the " &
                & // "SPRINGDAMPER, largest difference " // to_text(worst_apart) // " m")
            if (allocated(error)) return
        end do
    end subroutine test_hanging_mass

    !> A part of Izz = 0.5 kg m^2 about its z axis (along ground x: REULER 90D, 90D, 0D), its
    !> centre fixed by nothing but no force moving it, on ROTATIONAL SPRINGDAMPER/1 to a
    !> ground marker of the same axes: KT = 8 N m/rad, CT = 0.4 N m s/rad, ANGLE = 10D,
    !> TORQUE = 0.3 N m, started at AZ = 0 spinning at WZ = 1.5 rad/s. Its angle phi (its
    !> spin about z, AZ) is the damped oscillation about ANGLE + TORQUE/KT, and
    !> springdamper1_tx the torque -KT (AZ - ANGLE) - CT WZ + TORQUE about ground x.
    subroutine test_torsion(error)
        type(error_type), allocatable, intent(out) :: error
        !> Measured at ERROR = 1e-9: 5.7e-8 rad of a 0.4 rad swing; 2e-7 rad is 3.5 times that
        real(wp), parameter :: tol_angle = 2.0e-7_wp
        !> The torque column at the row's own state: measured 9e-16 N m (rounding)
        real(wp), parameter :: tol_torque = 1.0e-10_wp
        character(len=*), parameter :: text = "torsion spring" // nl &
            & // "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 2, 2.3, 0.5, REULER = 90D, 90D, 0D, WZ = 1.5" &
            & // nl // "MARKER/20, PART = 2" // nl &
            & // "SPRINGDAMPER/1, ROTATIONAL, I = 20, J = 10, KT = 8, CT = 0.4, ANGLE = 10D, " &
            & // "TORQUE = 0.3" // nl // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 3, STEPS = 60" // nl // "END"
        real(wp), parameter :: inertia = 0.5_wp, kt = 8.0_wp, ct = 0.4_wp, &
            & angle = 10.0_wp*pi/180.0_wp, preload = 0.3_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: a, w, worst, worst_torque, t, expected
        integer :: r, cphi, ct_column, cw

        call run_text("torsion.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 61, &
            & "the run completes with 61 rows")
        if (allocated(error)) return
        cphi = result%summary%layout%column("phi_2")
        cw = result%summary%layout%column("phidot_2")
        ct_column = result%summary%layout%column("springdamper1_tx")
        call check(error, cphi > 0 .and. cw > 0 .and. ct_column > 0, "columns phi_2, " &
            & // "phidot_2 and springdamper1_tx")
        if (allocated(error)) return
        worst = 0.0_wp
        worst_torque = 0.0_wp
        do r = 1, rows%count
            t = rows%rows(1, r)
            call damped(inertia, ct, kt, angle + preload/kt, 0.0_wp, 1.5_wp, t, a, w)
            worst = max(worst, abs(rows%rows(cphi, r) - a))
            expected = -kt*(rows%rows(cphi, r) - angle) - ct*rows%rows(cw, r) + preload
            worst_torque = max(worst_torque, abs(rows%rows(ct_column, r) - expected), &
                & abs(rows%rows(ct_column + 1, r)), abs(rows%rows(ct_column + 2, r)))
        end do
        call check(error, worst <= tol_angle, "largest distance from the torsional " &
            & // "oscillation " // to_text(worst) // " rad")
        if (allocated(error)) return
        call check(error, worst_torque <= tol_torque, "largest difference of " &
            & // "springdamper1_tx ... _tz from the definition " // to_text(worst_torque) &
            & // " N m")
    end subroutine test_torsion

    !> The part of test_torsion at rest, turned by VTORQUE/1, TX = 0.2 (ground axes: along its
    !> z axis, Izz = 0.5 kg m^2) on it and its reaction on ground: its spin phi is
    !> (TX/Izz) t^2/2 = 0.2 t^2 and its rate 0.4 t.
    subroutine test_vtorque(error)
        type(error_type), allocatable, intent(out) :: error
        !> Measured at ERROR = 1e-9: 4e-16 (a constant acceleration, which the integrator's
        !> polynomials hold exactly: rounding of the 0.8 rad); 1e-12 allows rounding only
        real(wp), parameter :: tol_angle = 1.0e-12_wp
        character(len=*), parameter :: text = "torque" // nl &
            & // "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART = 1" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 2, 2.3, 0.5, REULER = 90D, 90D, 0D" &
            & // nl // "MARKER/20, PART = 2" // nl &
            & // "VTORQUE/1, I = 20, JFLOAT = 10, TX = 0.2, TY = 0, TZ = 0" // nl &
            & // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 2, STEPS = 20" // nl // "END"
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: worst, t
        integer :: r, cphi, cw

        call run_text("vtorque.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 21, &
            & "the run completes with 21 rows")
        if (allocated(error)) return
        cphi = result%summary%layout%column("phi_2")
        cw = result%summary%layout%column("phidot_2")
        worst = 0.0_wp
        do r = 1, rows%count
            t = rows%rows(1, r)
            worst = max(worst, abs(rows%rows(cphi, r) - 0.2_wp*t**2), &
                & abs(rows%rows(cw, r) - 0.4_wp*t))
        end do
        call check(error, worst <= tol_angle, "largest distance from phi = 0.2 t^2 " &
            & // to_text(worst))
    end subroutine test_vtorque

    !> BUSHING/1 between a 2 kg part (principal moments 2, 3, 4 kg m^2 about its CM marker's
    !> axes) and a ground marker of the same axes, turned (REULER 30D, 40D, 20D) so that J's
    !> axes are not ground's: K = 100, 200, 300 N/m, C = 0.8, 1.2, 2 N s/m, KT = 50, 60,
    !> 80 N m/rad, CT = 0.4, 0.6, 0.8 N m s/rad. Displaced by (0.01, -0.02, 0.015) m in J's
    !> axes with FORCE = 2, -3, 4 N, each displacement (REQUEST/1 in J's axes) is its own
    !> damped oscillation of sqrt(k/m) about FORCE/K; spun at 0.3 rad/s about one of J's axes
    !> with TORQUE 0.5 N m about it (a run each), the part turns about that axis alone through
    !> the oscillation of sqrt(kt/I) about TORQUE/KT (I's axes in J's, from the part's angles,
    !> are the turn about that axis by AX, AY or AZ).
    subroutine test_bushing(error)
        type(error_type), allocatable, intent(out) :: error
        !> Measured at ERROR = 1e-9: 4.4e-9 m of displacements of 0.02 m, and 2.4e-10,
        !> 1.9e-10, 1.9e-10 of I's axes about x, y, z (swings of 0.06 rad); 3e-8 m and 2e-9,
        !> seven and eight times the largest, below what a tenfold loss gives
        real(wp), parameter :: tol_position = 3.0e-8_wp, tol_angle = 2.0e-9_wp
        character(len=*), parameter :: keys(3) = ["WX", "WY", "WZ"]
        character(len=*), parameter :: torques(3) = [character(len=11) :: "0.5, 0, 0", &
            & "0, 0.5, 0", "0, 0, 0.5"]
        real(wp), parameter :: m = 2.0_wp, inertia(3) = [2.0_wp, 3.0_wp, 4.0_wp], &
            & k(3) = [100.0_wp, 200.0_wp, 300.0_wp], c(3) = [0.8_wp, 1.2_wp, 2.0_wp], &
            & kt(3) = [50.0_wp, 60.0_wp, 80.0_wp], ct(3) = [0.4_wp, 0.6_wp, 0.8_wp], &
            & preload(3) = [2.0_wp, -3.0_wp, 4.0_wp], start(3) = [0.01_wp, -0.02_wp, 0.015_wp]
        type(job_result_type) :: result
        type(history_type) :: rows
        character(len=:), allocatable :: head, text
        real(wp) :: axes(3, 3), qg(3), relative(3, 3), x, v, worst, t, turned(3, 3)
        integer :: r, a, cx, cpsi, b

        axes = rotation_matrix(30.0_wp*pi/180.0_wp, 40.0_wp*pi/180.0_wp, 20.0_wp*pi/180.0_wp)
        head = "bushing" // nl &
            & // "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART = 1, REULER = 30D, 40D, 20D" // nl &
            & // "REQUEST/1, DISPLACEMENT, I = 20, J = 10, RM = 10" // nl
        ! along J's axes
        qg = matmul(axes, start)
        text = head // "PART/2, MASS = 2, CM = 20, IP = 2, 3, 4, REULER = 30D, 40D, 20D, " &
            & // "QG = " // number(qg(1)) // ", " // number(qg(2)) // ", " // number(qg(3)) &
            & // nl // "MARKER/20, PART = 2" // nl // bushing("0, 0, 0") // nl // tail()
        call run_text("bushing.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 41, &
            & "translations: the run completes with 41 rows")
        if (allocated(error)) return
        cx = result%summary%layout%column("req1_x")
        call check(error, cx > 0, "column req1_x")
        if (allocated(error)) return
        worst = 0.0_wp
        do r = 1, rows%count
            t = rows%rows(1, r)
            do a = 1, 3
                call damped(m, c(a), k(a), preload(a)/k(a), start(a), 0.0_wp, t, x, v)
                worst = max(worst, abs(rows%rows(cx + a - 1, r) - x))
            end do
        end do
        call check(error, worst <= tol_position, "translations: largest distance from the " &
            & // "oscillations along J's axes " // to_text(worst) // " m")
        if (allocated(error)) return
        do a = 1, 3
            text = head // "PART/2, MASS = 2, CM = 20, IP = 2, 3, 4, REULER = 30D, 40D, 20D, " &
                & // keys(a) // " = 0.3" // nl // "MARKER/20, PART = 2" // nl &
                & // bushing(trim(torques(a))) // nl // tail()
            call run_text("bushing_turn.adm", text, result, rows, error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. &
                & rows%count == 41, keys(a) // ": the run completes with 41 rows")
            if (allocated(error)) return
            cpsi = result%summary%layout%column("psi_2")
            worst = 0.0_wp
            do r = 1, rows%count
                t = rows%rows(1, r)
                call damped(inertia(a), ct(a), kt(a), 0.5_wp/kt(a), 0.0_wp, 0.3_wp, t, x, v)
                ! the part's principal axes are its CM marker's, I's
                relative = matmul(transpose(axes), rotation_matrix(rows%rows(cpsi, r), &
                    & rows%rows(cpsi + 1, r), rows%rows(cpsi + 2, r)))
                turned = about(a, x)
                do b = 1, 3
                    worst = max(worst, maxval(abs(relative(:, b) - turned(:, b))))
                end do
            end do
            call check(error, worst <= tol_angle, keys(a) // ": largest distance of I's " &
                & // "axes in J's from the torsional oscillation " // to_text(worst))
            if (allocated(error)) return
        end do

    contains

        !> The statement with this TORQUE.
        function bushing(torque_text) result(line)
            character(len=*), intent(in) :: torque_text
            character(len=:), allocatable :: line

            line = "BUSHING/1, I = 20, J = 10, K = 100, 200, 300, C = 0.8, 1.2, 2, " &
                & // "KT = 50, 60, 80, CT = 0.4, 0.6, 0.8, FORCE = 2, -3, 4, TORQUE = " &
                & // torque_text
        end function bushing

        function tail() result(line)
            character(len=:), allocatable :: line

            line = "INTEGRATOR/ERROR = 1e-9" // nl // "SIMULATE/DYNAMIC, END = 2, STEPS = 40" &
                & // nl // "END"
        end function tail

        !> The rotation by angle about axis a (1, 2, 3: x, y, z).
        pure function about(axis, angle) result(turn)
            integer, intent(in) :: axis
            real(wp), intent(in) :: angle
            real(wp) :: turn(3, 3)
            integer :: i, j

            turn = 0.0_wp
            turn(axis, axis) = 1.0_wp
            i = mod(axis, 3) + 1
            j = mod(axis + 1, 3) + 1
            turn(i, i) = cos(angle)
            turn(j, j) = cos(angle)
            turn(j, i) = sin(angle)
            turn(i, j) = -sin(angle)
        end function about

    end subroutine test_bushing

    !> A number in full.
    function number(value) result(text)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=32) :: buffer

        write(buffer, '(es24.16e3)') value
        text = trim(adjustl(buffer))
    end function number

end module test_springs
