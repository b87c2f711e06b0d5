! SPDX-License-Identifier: MIT
!> HOOKE, CONVEL and PLANAR joints in dataset runs (suite adm-joint-motions): the relative
!> motion each permits against its closed form, the motion it removes held, and its reactions
!> (docs/datasets.md, "JOINT and JPRIM").
!>
!> Two shafts meet at the origin, bent by beta = 30 degrees: the input (PART/2) turns about
!> ground z on a REVOLUTE, the output (PART/3) about a2 = (sin beta, 0, cos beta), held in
!> that direction by a JPRIM PARALLEL_AXES to ground, and the joint under test joins them at
!> the centre (no constraint is redundant: 5 + 4 + 2 equations leave the one rotation). Its
!> markers are ADAMS's CONVEL markers: z along each shaft away from the centre, the y axes
!> parallel (z_i = -Z, y_i = y_j = Y, z_j = a2), so a HOOKE's cross pins are x_i = -X and
!> y_j = Y. Each shaft's angle, phi1 about Z and phi2 about a2, both 0 with the pins in the
!> start's places, is read from a marker 0.1 m off its axis by a displacement request in a
!> ground marker whose x-y plane is the shaft's plane of turning. Without gravity or forces,
!> started at phi1 = 0 with the input turning at omega0 = 2 pi rad/s:
!>
!> - HOOKE: x_i.y_j = 0 is tan(phi2) cos(beta) = tan(phi1), Cardan's relation; its rate is
!>   phi2' = K(phi1) phi1', K = cos(beta) / (1 - sin(beta)^2 cos(phi1)^2), between cos(beta)
!>   and 1/cos(beta); the torque the pins pass, lambda dF/dphi2 with dF/dphi2 = cos(phi1)
!>   cos(phi2) cos(beta) + sin(phi1) sin(phi2), is the output's I2 phi2'', which the energy
!>   I1 phi1'^2/2 + I2 phi2'^2/2 fixes: I2 phi1'^2 K'(phi1) I1 / (I1 + I2 K^2).
!> - CONVEL: phi2 = phi1 at every instant; the two shafts then keep their speed (the energy
!>   with phi2' = phi1' fixes it), phi1 = phi2 = omega0 t, and the joint passes no force.
module test_adm_joint_motions
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_run_job, only : job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    use dataset_texts, only : run_text
    implicit none
    private

    public :: collect_adm_joint_motions

    character(len=*), parameter :: nl = new_line("a")
    real(wp), parameter :: g = 9.81_wp
    !> The shafts' bend [rad], the input's start rate [rad/s] and moments about their axes
    !> (PART/2's and PART/3's IP about their CM markers' y axes, the shafts' axes) [kg m^2]
    real(wp), parameter :: beta = pi/6.0_wp, omega0 = 2.0_wp*pi, i1 = 0.01_wp, i2 = 0.015_wp
    !> An angle read against its closed form at every row: IDA at ERROR = 1e-10 holds the
    !> joints to a few 1e-10 (the largest residual measured, 2.8e-10, is a PARALLEL_AXES
    !> component of the CONVEL run), and an angle read 0.1 m off an axis moves by no more; the
    !> largest differences measured are 8.5e-11 rad (HOOKE) and 4.8e-10 rad (CONVEL). The
    !> relation a HOOKE follows and the one a CONVEL follows differ by 0.072 rad at 30 degrees
    real(wp), parameter :: tol_angle = 3.0e-9_wp
    !> The output's rate over the input's against K(phi1): 1.8e-10 (HOOKE) and 1.9e-10 (CONVEL)
    !> measured, the rates being IDA's to its rtol; K ranges over 0.29
    real(wp), parameter :: tol_ratio = 2.0e-9_wp
    !> phi1 and phi2 against omega0 t over 2 s (12.6 rad) of the CONVEL run: the phase error
    !> IDA accumulates at rtol 1e-10, 1.2e-8 rad measured
    real(wp), parameter :: tol_phase = 1.0e-7_wp
    !> A multiplier the motion makes zero, or one against its closed form [N or N m]: 5e-15
    !> measured for the zeros, 6e-11 N m for the HOOKE's torque (0.083 N m at most)
    real(wp), parameter :: tol_reaction = 1.0e-9_wp
    !> The PLANAR block's points against their closed forms over 1 s (2.45 m down the plane):
    !> 4.4e-10 m measured, a few times the 1e-10 absolute tolerance
    real(wp), parameter :: tol_position = 3.0e-9_wp
    !> The joints' residuals and the energy, as suite adm-joints holds them
    real(wp), parameter :: tol_residual = 1.0e-8_wp, tol_energy = 1.0e-6_wp

contains

    subroutine collect_adm_joint_motions(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("hooke-cardan-relation", test_hooke), &
            & new_unittest("convel-homokinetic", test_convel), &
            & new_unittest("planar-slides-and-spins", test_planar)]
    end subroutine collect_adm_joint_motions

    !> The HOOKE shafts: Cardan's relation between the angles and between the rates at every
    !> row; the output's largest lead on the input as Cardan's formula gives it (so not a
    !> homokinetic joint); the torque the pins pass; no force at the centre (the output's
    !> centre of mass is on its fixed axis, and its PARALLEL_AXES passes moments only).
    subroutine test_hooke(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: phi1, phi2, worst_angle, worst_ratio, worst_torque, lead, largest_lead, &
            & k, dk, rate1, torque, turned, previous, force
        integer :: n, c

        call run_shafts("HOOKE", omega0/cos(beta), result, rows, error)
        if (allocated(error)) return
        worst_angle = 0.0_wp
        worst_ratio = 0.0_wp
        worst_torque = 0.0_wp
        largest_lead = 0.0_wp
        turned = 0.0_wp
        previous = 0.0_wp
        force = 0.0_wp
        do n = 1, rows%count
            call shaft_angles(result, rows, n, phi1, phi2)
            if (n > 1) turned = turned + wrapped(phi1 - previous)
            previous = phi1
            worst_angle = max(worst_angle, abs(wrapped(phi2 - atan2(sin(phi1), &
                & cos(phi1)*cos(beta)))))
            lead = abs(wrapped(phi2 - phi1))
            largest_lead = max(largest_lead, lead)
            k = cos(beta)/(1.0_wp - sin(beta)**2*cos(phi1)**2)
            dk = -cos(beta)*2.0_wp*sin(beta)**2*cos(phi1)*sin(phi1)/(1.0_wp &
                & - sin(beta)**2*cos(phi1)**2)**2
            rate1 = rate(result, rows, n, 2)
            worst_ratio = max(worst_ratio, abs(rate(result, rows, n, 3)/rate1 - k))
            ! UCONs 1-5 the REVOLUTE, 6-8 the HOOKE's ATPOINT, 9 its PERPENDICULAR
            torque = rows%rows(result%summary%layout%column("lambda_9"), n)*(cos(phi1) &
                & *cos(phi2)*cos(beta) + sin(phi1)*sin(phi2))
            worst_torque = max(worst_torque, abs(torque - i2*rate1**2*dk*i1/(i1 + i2*k**2)))
            do c = 6, 8
                force = max(force, abs(rows%rows(result%summary%layout%column("lambda_" &
                    & // to_text(c)), n)))
            end do
        end do
        call check(error, worst_angle <= tol_angle .and. worst_ratio <= tol_ratio, &
            & "largest distance from Cardan's relation " // to_text(worst_angle) // " rad, " &
            & // "from its rate " // to_text(worst_ratio))
        if (allocated(error)) return
        ! the rows sample the lead every 0.06 rad of phi1: within 1 % of its peak
        call check(error, largest_lead >= 0.99_wp*cardan_lead() .and. largest_lead <= &
            & cardan_lead() + tol_angle .and. turned > 2.0_wp*pi, "the output's largest lead " &
            & // to_text(largest_lead) // " rad against Cardan's " // to_text(cardan_lead()) &
            & // ", the input turned " // to_text(turned) // " rad")
        if (allocated(error)) return
        call check(error, worst_torque <= tol_reaction .and. force <= tol_reaction, &
            & "the pins' torque off by " // to_text(worst_torque) // " N m, the force at " &
            & // "the centre " // to_text(force) // " N")
    end subroutine test_hooke

    !> The CONVEL shafts: the output's angle is the input's at every row, both turn at
    !> omega0, the joint's four multipliers are zero, and the output leads the input by what
    !> a HOOKE would make it (so not a Hooke joint).
    subroutine test_convel(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: phi1, phi2, t, worst_angle, worst_phase, worst_ratio, off_cardan, force
        integer :: n, c

        call run_shafts("CONVEL", omega0, result, rows, error)
        if (allocated(error)) return
        worst_angle = 0.0_wp
        worst_phase = 0.0_wp
        worst_ratio = 0.0_wp
        off_cardan = 0.0_wp
        force = 0.0_wp
        do n = 1, rows%count
            call shaft_angles(result, rows, n, phi1, phi2)
            t = rows%rows(1, n)
            worst_angle = max(worst_angle, abs(wrapped(phi2 - phi1)))
            worst_phase = max(worst_phase, abs(wrapped(phi1 - omega0*t)), &
                & abs(wrapped(phi2 - omega0*t)))
            worst_ratio = max(worst_ratio, abs(rate(result, rows, n, 3)/rate(result, rows, &
                & n, 2) - 1.0_wp))
            off_cardan = max(off_cardan, abs(wrapped(phi2 - atan2(sin(phi1), &
                & cos(phi1)*cos(beta)))))
            ! UCONs 6-8 the CONVEL's ATPOINT, 9 its homokinetic condition
            do c = 6, 9
                force = max(force, abs(rows%rows(result%summary%layout%column("lambda_" &
                    & // to_text(c)), n)))
            end do
        end do
        call check(error, worst_angle <= tol_angle .and. worst_ratio <= tol_ratio .and. &
            & worst_phase <= tol_phase, "largest difference of the angles " &
            & // to_text(worst_angle) // " rad, of the rates' ratio from 1 " &
            & // to_text(worst_ratio) // ", of the angles from omega0 t " &
            & // to_text(worst_phase) // " rad")
        if (allocated(error)) return
        call check(error, off_cardan >= 0.99_wp*cardan_lead() .and. force <= tol_reaction, &
            & "largest distance from Cardan's relation " // to_text(off_cardan) // " rad " &
            & // "(a HOOKE's lead is " // to_text(cardan_lead()) // "), largest multiplier " &
            & // to_text(force))
    end subroutine test_convel

    !> A block of 2 kg on a PLANAR joint to a ground plane tilted 30 degrees about X (J's x
    !> along X, y up the slope), its principal axes turned from the plane's by products of
    !> inertia, marker I at its centre of mass, sent at 0.5 m/s along x_j and 0.3 m/s up the
    !> slope, spinning at 2 rad/s about the plane's normal. The joint passes no force in the
    !> plane and no moment about the normal, so I's origin, in J's axes, is (x0 + 0.5 t,
    !> y0 + 0.3 t - g sin(30 deg) t^2/2, 0), a point 0.1 m from it along x_i turns about it at
    !> 2 rad/s from 20 degrees, and a point 0.1 m along z_i stays 0.1 m above I's origin; its
    !> INPLANE multiplier is the normal force m g cos(30 deg) (force on the block lambda z_j),
    !> the block's centre not accelerating off the plane. Three UCONs.
    subroutine test_planar(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: alpha = pi/6.0_wp, start(2) = [0.05_wp, 0.08_wp], &
            & j_origin(3) = [0.2_wp, -0.1_wp, 0.3_wp], spin = 2.0_wp, gamma0 = pi/9.0_wp
        type(history_type) :: rows
        type(job_result_type) :: result
        real(wp) :: t, x, y, worst, normal
        integer :: n, r1, r2, r3, cl

        call run_text("planar.adm", "a block sliding and spinning on a tilted plane" // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1, QP=0.2, -0.1, 0.3, REULER=0, 30D, 0" // nl &
            & // "PART/2, MASS=2, CM=20, IP=0.02, 0.03, 0.04, 0.002, -0.003, 0.001" // nl &
            & // ", QG=" // to_text(j_origin(1) + start(1)) // ", " &
            & // to_text(j_origin(2) + start(2)*cos(alpha)) // ", " &
            & // to_text(j_origin(3) + start(2)*sin(alpha)) // ", REULER=0, 30D, 0" // nl &
            & // ", VX=0.5, VY=" // to_text(0.3_wp*cos(alpha)) // ", VZ=" &
            & // to_text(0.3_wp*sin(alpha)) // ", WZ=2" // nl &
            & // "MARKER/20, PART=2" // nl &
            & // "MARKER/21, PART=2, REULER=20D, 0, 0" // nl &
            & // "MARKER/22, PART=2, QP=" // to_text(0.1_wp*cos(gamma0)) // ", " &
            & // to_text(0.1_wp*sin(gamma0)) // ", 0" // nl &
            & // "MARKER/23, PART=2, QP=0, 0, 0.1" // nl &
            & // "JOINT/5, PLANAR, I=21, J=10" // nl &
            & // "REQUEST/1, DISPLACEMENT, I=21, J=10, RM=10" // nl &
            & // "REQUEST/2, DISPLACEMENT, I=22, J=10, RM=10" // nl &
            & // "REQUEST/3, DISPLACEMENT, I=23, J=10, RM=10" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "SIMULATE/DYNAMIC, END=1, DTOUT=0.01" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) return
        call check_held(result, error)
        if (allocated(error)) return
        call check(error, size(result%summary%layout%ucon_ids) == 3, "a PLANAR is " &
            & // to_text(size(result%summary%layout%ucon_ids)) // " UCONs, not 3")
        if (allocated(error)) return
        r1 = result%summary%layout%column("req1_x")
        r2 = result%summary%layout%column("req2_x")
        r3 = result%summary%layout%column("req3_x")
        cl = result%summary%layout%column("lambda_1")
        worst = 0.0_wp
        normal = 0.0_wp
        do n = 1, rows%count
            t = rows%rows(1, n)
            x = start(1) + 0.5_wp*t
            y = start(2) + 0.3_wp*t - 0.5_wp*g*sin(alpha)*t**2
            associate (row => rows%rows(:, n))
                worst = max(worst, maxval(abs(row(r1:r1 + 2) - [x, y, 0.0_wp])), &
                    & maxval(abs(row(r2:r2 + 2) - [x + 0.1_wp*cos(gamma0 + spin*t), &
                    & y + 0.1_wp*sin(gamma0 + spin*t), 0.0_wp])), &
                    & maxval(abs(row(r3:r3 + 2) - [x, y, 0.1_wp])))
                normal = max(normal, abs(row(cl) - 2.0_wp*g*cos(alpha)))
            end associate
        end do
        call check(error, worst <= tol_position .and. normal <= tol_reaction, "largest " &
            & // "distance of the block's points from their closed forms " // to_text(worst) &
            & // " m, of its INPLANE multiplier from m g cos(alpha) " // to_text(normal) // " N")
    end subroutine test_planar

    !> The two shafts of the module's comment, joined by a `kind` joint, the output started at
    !> rate2 [rad/s]; 2 s, held and conserving energy, 11 UCONs (the joint's four among them).
    subroutine run_shafts(kind, rate2, result, rows, error)
        character(len=*), intent(in) :: kind
        real(wp), intent(in) :: rate2
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error

        call run_text("shafts.adm", "two shafts at 30 degrees joined by a " // kind // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART=1" // nl &
            & // "MARKER/11, PART=1, REULER=90D, 30D, -90D   ! x_j, y_j, z_j at the start" // nl &
            & // "MARKER/12, PART=1, REULER=180D, 0, 0       ! x_i, -y_i, -z_i at the start" &
            & // nl &
            & // "PART/2, MASS=1, CM=20, IP=0.02, 0.01, 0.02, WY=" // to_text(omega0) // nl &
            & // "MARKER/20, PART=2, QP=0, 0, -0.2, REULER=0, 90D, 0" // nl &
            & // "MARKER/21, PART=2" // nl &
            & // "MARKER/22, PART=2, REULER=180D, 180D, 0" // nl &
            & // "MARKER/23, PART=2, QP=-0.1, 0, 0" // nl &
            & // "PART/3, MASS=1.5, CM=30, IP=0.03, 0.015, 0.03, REULER=90D, 30D, -90D" // nl &
            & // ", WY=" // to_text(rate2) // nl &
            & // "MARKER/30, PART=3, QP=0, 0, 0.2, REULER=0, 90D, 0" // nl &
            & // "MARKER/31, PART=3" // nl &
            & // "MARKER/33, PART=3, QP=0.1, 0, 0" // nl &
            & // "JOINT/1, REVOLUTE, I=21, J=10" // nl &
            & // "JOINT/2, " // kind // ", I=22, J=31" // nl &
            & // "JPRIM/3, PARALLEL_AXES, I=31, J=11" // nl &
            & // "REQUEST/1, DISPLACEMENT, I=23, J=12, RM=12" // nl &
            & // "REQUEST/2, DISPLACEMENT, I=33, J=11, RM=11" // nl &
            & // "SIMULATE/DYNAMIC, END=2, DTOUT=0.01" // nl &
            & // "INTEGRATOR/ERROR=1e-10" // nl, result, rows, error)
        if (allocated(error)) then
            error%message = kind // ": " // error%message
            return
        end if
        call check_held(result, error)
        if (allocated(error)) then
            error%message = kind // ": " // error%message
            return
        end if
        call check(error, size(result%summary%layout%ucon_ids) == 11, kind // ": " &
            & // to_text(size(result%summary%layout%ucon_ids)) // " UCONs, not 5 + 4 + 2")
    end subroutine run_shafts

    !> The input's and the output's angles at row n, from the requests' points.
    subroutine shaft_angles(result, rows, n, phi1, phi2)
        type(job_result_type), intent(in) :: result
        type(history_type), intent(in) :: rows
        integer, intent(in) :: n
        real(wp), intent(out) :: phi1, phi2
        integer :: c1, c2

        c1 = result%summary%layout%column("req1_x")
        c2 = result%summary%layout%column("req2_x")
        phi1 = atan2(rows%rows(c1 + 1, n), rows%rows(c1, n))
        phi2 = atan2(rows%rows(c2 + 1, n), rows%rows(c2, n))
    end subroutine shaft_angles

    !> The size of PART/p's angular velocity at row n, from its Euler angles' rates:
    !> |omega|^2 = psidot^2 + thetadot^2 + phidot^2 + 2 psidot phidot cos(theta) [rad/s].
    real(wp) function rate(result, rows, n, p)
        type(job_result_type), intent(in) :: result
        type(history_type), intent(in) :: rows
        integer, intent(in) :: n, p
        integer :: c

        c = result%summary%layout%column("theta_" // to_text(p))
        associate (theta => rows%rows(c, n), psidot => rows%rows(c + 5, n), &
            & thetadot => rows%rows(c + 6, n), phidot => rows%rows(c + 7, n))
            rate = sqrt(psidot**2 + thetadot**2 + phidot**2 + 2.0_wp*psidot*phidot*cos(theta))
        end associate
    end function rate

    !> The largest lead of a Hooke joint's output on its input at the bend beta,
    !> atan((1 - cos beta) / (2 sqrt(cos beta))) [rad]: 0.0719 at 30 degrees.
    pure real(wp) function cardan_lead()
        cardan_lead = atan((1.0_wp - cos(beta))/(2.0_wp*sqrt(cos(beta))))
    end function cardan_lead

    !> An angle brought into (-pi, pi].
    pure real(wp) function wrapped(angle)
        real(wp), intent(in) :: angle

        wrapped = atan2(sin(angle), cos(angle))
    end function wrapped

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

end module test_adm_joint_motions
