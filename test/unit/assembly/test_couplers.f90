! SPDX-License-Identifier: MIT
!> Datasets with GCONs and couplings of joint motions, run (suite couplers): the pendulum held
!> by GCON DM(20, 10) - 2 (the field's gcon_distance.adm) against its SPHERICAL twin and its
!> tension; a rack and pinion falling under gravity against a = g m/(m + I/r^2); a screw
!> against its pitch and its own closed form; a COUPLER of two revolutes with scale 2 and a GEAR
!> of two gears against the angle relation at every row; and what a coupling may not join,
!> refused by name.
module test_couplers
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
    implicit none
    private

    public :: collect_couplers

    real(wp), parameter :: g = 9.80665_wp
    character(len=*), parameter :: nl = new_line("a")
    !> The SPHERICAL twin of the field's GCON pendulum (test_pendulum says why it is one)
    character(len=*), parameter :: twin = "spherical twin" // nl // "PART/1, GROUND" // nl &
        & // "MARKER/10, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 0.36, 0.2, 0.2" &
        & // nl // "MARKER/20, PART = 2, QP = 0, 1.8, 0" // nl // "MARKER/21, PART = 2" &
        & // nl // "MARKER/22, PART = 2, QP = 0, 2, 0" // nl // "JOINT/1, SPHERICAL, I = " &
        & // "21, J = 10" // nl // "REQUEST/1, DISPLACEMENT, I = 22" // nl &
        & // "ACCGRAV/KGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-10" // nl &
        & // "SIMULATE/DYNAMIC, END = 5, STEPS = 500" // nl // "END"

contains

    subroutine collect_couplers(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("gcon-pendulum-is-its-spherical-twin", test_pendulum), &
            & new_unittest("field-gcon-distance-runs-unchanged", test_field_pendulum), &
            & new_unittest("rack-and-pinion-falls-at-g-m-over-m-plus-i-over-r2", test_rackpin), &
            & new_unittest("screw-advances-its-pitch-per-turn", test_screw), &
            & new_unittest("coupler-of-two-revolutes-scale-2", test_coupler), &
            & new_unittest("gear-ratio-from-the-contact-point", test_gear), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_couplers

    !> The field's pendulum: a 1 kg part whose CM marker 20 starts 2 m from ground marker 10,
    !> held by GCON/1 DM(20, 10) - 2 and released level. The constraint's force passes through
    !> the centre of mass, so the part does not turn and its centre swings as a point mass on
    !> a 2 m rod: theta'' = (g/2) cos(theta) for the angle theta below the level. The SPHERICAL
    !> twin holds a part at ground marker 10 whose centre of mass is at l = 1.8 m and whose
    !> moment about the swing's axis is I = m l (L - l) = 0.36 kg m^2 (IP 0.36, 0.2, 0.2): its
    !> point at L = 2 m is its centre of oscillation (l + I/(m l) = L, Huygens), which swings
    !> as the same point mass: theta'' = m g l cos(theta)/(I + m l^2) = (g/2) cos(theta). The
    !> GCON's centre and the twin's marker at 2 m (REQUEST/1) agree at every row, and the
    !> GCON's multiplier is the rod's tension: its generalised force lambda dF/dr on the centre
    !> is -T r/|r| with T = m v^2/L - m g r_z/L, so lambda = m g r_z/L - m v^2/L.
    subroutine test_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        !> Each run's global error at ERROR = 1e-10 over 5 s (two and a half swings of 2 m):
        !> measured 5e-8 m between the two; 1e-6 m is 20 times that and a thousandth of what a
        !> wrong inertia (the twin's part with its own 0.04 kg m^2 about the pivot, 1 %) gives
        real(wp), parameter :: tol_position = 1.0e-6_wp
        !> The tension from the rows' velocities (each to ~1e-8 relative): measured 2e-7 N of
        !> the 30 N at the bottom; 1e-5 N
        real(wp), parameter :: tol_tension = 1.0e-5_wp
        character(len=*), parameter :: gcon = &
            & "pendulum held by a distance constraint, ADAMS GCON with a two-marker " &
            & // "expression" // nl // "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, " &
            & // "TIME = SECOND" // nl // "PART/1, GROUND" // nl // "MARKER/10, PART = 1" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.04, 0.1, 0.1" // nl // "MARKER/20, PART = " &
            & // "2, QP = 0, 2, 0" // nl // "GCON/1, I = 10, FUNCTION = DM(20, 10) - 2" // nl &
            & // "ACCGRAV/KGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-10" // nl &
            & // "SIMULATE/DYNAMIC, END = 5, STEPS = 500" // nl // "END"
        type(job_result_type) :: result_gcon, result_twin
        type(history_type) :: rows_gcon, rows_twin
        real(wp) :: worst, worst_tension, worst_reaction, r(3), v(3), tension
        integer :: k, cx, cv, cl, cr, ce

        call run_text("gcon_distance.adm", gcon, result_gcon, rows_gcon, error)
        if (allocated(error)) return
        call run_text("spherical_twin.adm", twin, result_twin, rows_twin, error)
        if (allocated(error)) return
        call check(error, result_gcon%summary%status == status_completed .and. &
            & result_twin%summary%status == status_completed .and. rows_gcon%count == 501 &
            & .and. rows_twin%count == 501, "both runs complete, 501 rows each")
        if (allocated(error)) return
        cx = result_gcon%summary%layout%column("X_2")
        cv = result_gcon%summary%layout%column("Xdot_2")
        cl = result_gcon%summary%layout%column("lambda_1")
        cr = result_twin%summary%layout%column("req1_x")
        ! the GCON's reaction columns are its statement's (never its UCON's generated id)
        ce = result_gcon%summary%layout%column("gcon1_fx")
        call check(error, ce > 0, "column gcon1_fx")
        if (allocated(error)) return
        worst = 0.0_wp
        worst_tension = 0.0_wp
        worst_reaction = 0.0_wp
        do k = 1, rows_gcon%count
            r = rows_gcon%rows(cx:cx + 2, k)
            v = rows_gcon%rows(cv:cv + 2, k)
            worst = max(worst, maxval(abs(r - rows_twin%rows(cr:cr + 2, k))))
            ! m = 1 kg, L = 2 m
            tension = (1.0_wp*dot_product(v, v) - 1.0_wp*g*r(3))/2.0_wp
            worst_tension = max(worst_tension, abs(rows_gcon%rows(cl, k) + tension))
            worst_reaction = max(worst_reaction, abs(norm2(rows_gcon%rows(ce:ce + 2, k)) &
                & - abs(tension)))
        end do
        call check(error, worst <= tol_position, "largest distance between the GCON's centre " &
            & // "and the twin's centre of oscillation " // to_text(worst) // " m")
        if (allocated(error)) return
        call check(error, worst_tension <= tol_tension, "largest difference between lambda_1 " &
            & // "and -T " // to_text(worst_tension) // " N")
        if (allocated(error)) return
        ! the reaction is the tension along the string: the same tolerance
        call check(error, worst_reaction <= tol_tension, "largest difference between |gcon1_fx" &
            & // "..fz| and T " // to_text(worst_reaction) // " N")
        if (allocated(error)) return
        ! the swing reaches the bottom: the comparison is not of a pendulum at rest
        call check(error, minval(rows_gcon%rows(cx + 2, :rows_gcon%count)) < -1.99_wp, &
            & "the bob should reach the bottom")
    end subroutine test_pendulum

    !> The field's dataset as it was handed in (test/couplers/gcon_distance.adm, no INTEGRATOR:
    !> rollcon's default tolerances) runs to the motion of its SPHERICAL twin run at
    !> ERROR = 1e-10, and its multiplier is minus the rod's tension (test_pendulum).
    subroutine test_field_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        !> The default tolerances' global error over 5 s: measured 6.9e-7 m from the twin;
        !> 5e-6 m is 7 times that and 200 times below what a 1 % wrong inertia of the twin gives
        real(wp), parameter :: tol_position = 5.0e-6_wp
        !> Measured 6.2e-8 N of the 30 N at the bottom; 1e-6 N
        real(wp), parameter :: tol_tension = 1.0e-6_wp
        type(job_type) :: job
        type(job_result_type) :: result_gcon, result_twin
        type(history_type) :: rows_gcon, rows_twin
        type(error_type), allocatable :: failure
        real(wp) :: worst, worst_tension, r(3), v(3), tension
        integer :: k, cx, cv, cl, cr

        call load_job("test/couplers/gcon_distance.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result_gcon, failure, rows_gcon)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        call run_text("spherical_twin.adm", twin, result_twin, rows_twin, error)
        if (allocated(error)) return
        call check(error, result_gcon%summary%status == status_completed .and. &
            & rows_gcon%count == 501 .and. rows_twin%count == 501, &
            & "the field's dataset completes with 501 rows")
        if (allocated(error)) return
        cx = result_gcon%summary%layout%column("X_2")
        cv = result_gcon%summary%layout%column("Xdot_2")
        cl = result_gcon%summary%layout%column("lambda_1")
        cr = result_twin%summary%layout%column("req1_x")
        worst = 0.0_wp
        worst_tension = 0.0_wp
        do k = 1, rows_gcon%count
            r = rows_gcon%rows(cx:cx + 2, k)
            v = rows_gcon%rows(cv:cv + 2, k)
            worst = max(worst, maxval(abs(r - rows_twin%rows(cr:cr + 2, k))))
            ! m = 1 kg, L = 2 m
            tension = (1.0_wp*dot_product(v, v) - 1.0_wp*g*r(3))/2.0_wp
            worst_tension = max(worst_tension, abs(rows_gcon%rows(cl, k) + tension))
        end do
        call check(error, worst <= tol_position, "largest distance between the field's GCON " &
            & // "pendulum and its twin " // to_text(worst) // " m")
        if (allocated(error)) return
        call check(error, worst_tension <= tol_tension, "largest difference between lambda_1 " &
            & // "and -T " // to_text(worst_tension) // " N")
    end subroutine test_field_pendulum

    !> A pinion (PD = 0.2 m, I = 0.01 kg m^2 about its axis, ground x) on a REVOLUTE and a 1 kg
    !> rack on a vertical TRANSLATIONAL joint, joined by a RACKPIN: the rack falls at
    !> a = g m/(m + I/r^2) = g/2, Z = -a t^2/2, and the pinion turns Z/r (its phi, about its
    !> own z along ground x: -(Z - Z0)/r with the rack on its -y side).
    subroutine test_rackpin(error)
        type(error_type), allocatable, intent(out) :: error
        !> Constant acceleration: a BDF run at ERROR = 1e-9 follows a parabola to about
        !> 1e-9 of its size; Z reaches 2.5 m: 1e-7 m is 40 times that, 1e6 times below the
        !> 2.5 m a wrong ratio of I/r^2 by 1 % would miss by (0.025 m)
        real(wp), parameter :: tol_z = 1.0e-7_wp
        character(len=*), parameter :: text = "rack and pinion" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/11, PART = 1, QP = 0, 0.1, 0" // nl &
            & // "PART/2, MASS = 2, CM = 20, IP = 0.02, 0.02, 0.01" // nl &
            & // "MARKER/20, PART = 2, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/21, PART = 2, REULER = 90D, 90D, 90D" // nl &
            & // "PART/3, MASS = 1, CM = 30, IP = 0.1, 0.1, 0.1" // nl &
            & // "MARKER/30, PART = 3, QP = 0, 0.1, 0, REULER = 0D, 90D, 0D" // nl &
            & // "MARKER/31, PART = 3, QP = 0, 0.1, 0" // nl &
            & // "JOINT/1, REVOLUTE, I = 20, J = 10" // nl &
            & // "JOINT/2, TRANSLATIONAL, I = 31, J = 11" // nl &
            & // "JOINT/3, RACKPIN, I = 21, J = 31, PD = 0.2" // nl &
            & // "ACCGRAV/KGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 100" // nl // "END"
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: a, worst, worst_turn, t, z
        integer :: k, cz, cphi

        call run_text("rackpin.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 101, &
            & "the run completes with 101 rows")
        if (allocated(error)) return
        a = g*1.0_wp/(1.0_wp + 0.01_wp/0.1_wp**2)
        cz = result%summary%layout%column("Z_3")
        cphi = result%summary%layout%column("phi_2")
        worst = 0.0_wp
        worst_turn = 0.0_wp
        do k = 1, rows%count
            t = rows%rows(1, k)
            z = rows%rows(cz, k)
            worst = max(worst, abs(z - (-0.5_wp*a*t**2)))
            worst_turn = max(worst_turn, abs(abs(rows%rows(cphi, k) - rows%rows(cphi, 1)) &
                & - abs(z)/0.1_wp))
        end do
        call check(error, worst <= tol_z, "largest |Z - (-a t^2/2)| " // to_text(worst) // " m")
        if (allocated(error)) return
        call check(error, worst_turn <= tol_z/0.1_wp, "largest |turn - Z/r| " &
            & // to_text(worst_turn) // " rad")
    end subroutine test_rackpin

    !> A nut (m = 1 kg, I = 0.001 kg m^2 about its axis, ground x) on a CYLINDRICAL joint and a
    !> SCREW of pitch 0.1 m to ground, gravity along -x: it advances 0.1 m a turn
    !> (X = PITCH phi/(2 pi) from the start) and falls at a = g m/(m + I (2 pi/PITCH)^2).
    subroutine test_screw(error)
        type(error_type), allocatable, intent(out) :: error
        !> As the rack's: a parabola followed to ~1e-9 of its 0.5 m at ERROR = 1e-9
        real(wp), parameter :: tol_x = 1.0e-7_wp
        character(len=*), parameter :: text = "screw" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.002, 0.002, 0.001" // nl &
            & // "MARKER/20, PART = 2, REULER = 90D, 90D, 0D" // nl &
            & // "JOINT/1, CYLINDRICAL, I = 20, J = 10" // nl &
            & // "JOINT/2, SCREW, I = 20, J = 10, PITCH = 0.1" // nl &
            & // "ACCGRAV/IGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 100" // nl // "END"
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: a, worst, worst_pitch, t, x
        integer :: k, cx, cphi

        call run_text("screw.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 101, &
            & "the run completes with 101 rows")
        if (allocated(error)) return
        a = g/(1.0_wp + 0.001_wp*(2.0_wp*pi/0.1_wp)**2)
        cx = result%summary%layout%column("X_2")
        cphi = result%summary%layout%column("phi_2")
        worst = 0.0_wp
        worst_pitch = 0.0_wp
        do k = 1, rows%count
            t = rows%rows(1, k)
            x = rows%rows(cx, k)
            worst = max(worst, abs(x - (-0.5_wp*a*t**2)))
            worst_pitch = max(worst_pitch, abs(x - 0.1_wp*(rows%rows(cphi, k) &
                & - rows%rows(cphi, 1))/(2.0_wp*pi)))
        end do
        call check(error, worst <= tol_x, "largest |X - (-a t^2/2)| " // to_text(worst) // " m")
        if (allocated(error)) return
        call check(error, worst_pitch <= tol_x, "largest |X - PITCH turns| " &
            & // to_text(worst_pitch) // " m")
    end subroutine test_screw

    !> Two wheels on REVOLUTEs about ground x, the first a pendulum (its centre 0.3 m from its
    !> axis), COUPLER SCALES = 1, -2: the first turns twice the second, q1 = 2 q2, at every row
    !> (each measured from the start), over several swings.
    subroutine test_coupler(error)
        type(error_type), allocatable, intent(out) :: error
        !> The relation is a constraint IDA holds to its tolerance: measured 1e-10 rad at
        !> ERROR = 1e-9; 1e-8 rad, 1e7 times below the swing's 0.5 rad
        real(wp), parameter :: tol_angle = 1.0e-8_wp
        character(len=*), parameter :: text = "coupled wheels" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/11, PART = 1, QP = 0, 1, 0, REULER = 90D, 90D, 0D" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.02, 0.02, 0.01" // nl &
            & // "MARKER/20, PART = 2, QP = 0, 0.3, 0, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/21, PART = 2, REULER = 90D, 90D, 0D" // nl &
            & // "PART/3, MASS = 1, CM = 30, IP = 0.02, 0.02, 0.01" // nl &
            & // "MARKER/30, PART = 3, QP = 0, 1, 0, REULER = 90D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I = 21, J = 10" // nl &
            & // "JOINT/2, REVOLUTE, I = 30, J = 11" // nl &
            & // "COUPLER/1, JOINTS = 1, 2, TYPE = R:R, SCALES = 1, -2" // nl &
            & // "ACCGRAV/KGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 3, STEPS = 300" // nl // "END"
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: worst, swing
        integer :: k, c2, c3

        call run_text("coupler.adm", text, result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 301, &
            & "the run completes with 301 rows")
        if (allocated(error)) return
        c2 = result%summary%layout%column("phi_2")
        c3 = result%summary%layout%column("phi_3")
        worst = 0.0_wp
        swing = 0.0_wp
        do k = 1, rows%count
            worst = max(worst, abs((rows%rows(c2, k) - rows%rows(c2, 1)) &
                & - 2.0_wp*(rows%rows(c3, k) - rows%rows(c3, 1))))
            swing = max(swing, abs(rows%rows(c2, k) - rows%rows(c2, 1)))
        end do
        call check(error, worst <= tol_angle .and. swing > 0.5_wp, "largest |q1 - 2 q2| " &
            & // to_text(worst) // " rad over a swing of " // to_text(swing) // " rad")
    end subroutine test_coupler

    !> Gear 1 (radius 0.1 m, a pendulum) about ground x at the origin and gear 2 (radius 0.2 m)
    !> about ground x at y = 0.3 m, CV at the contact point (0, 0.1, 0) with z along ground z:
    !> c1 = (x x (0, 0.1, 0)) . z = 0.1, c2 = (x x (0, -0.2, 0)) . z = -0.2, so
    !> 0.1 q1 + 0.2 q2 = 0: gear 2 turns half as far the other way.
    subroutine test_gear(error)
        type(error_type), allocatable, intent(out) :: error
        !> As the coupler's
        real(wp), parameter :: tol_angle = 1.0e-8_wp
        character(len=*), parameter :: text = "gears" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/11, PART = 1, QP = 0, 0.3, 0, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/12, PART = 1, QP = 0, 0.1, 0" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.02, 0.02, 0.01" // nl &
            & // "MARKER/20, PART = 2, QP = 0, 0.05, 0.05, REULER = 90D, 90D, 0D" // nl &
            & // "MARKER/21, PART = 2, REULER = 90D, 90D, 0D" // nl &
            & // "PART/3, MASS = 1, CM = 30, IP = 0.02, 0.02, 0.04" // nl &
            & // "MARKER/30, PART = 3, QP = 0, 0.3, 0, REULER = 90D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I = 21, J = 10" // nl &
            & // "JOINT/2, REVOLUTE, I = 30, J = 11" // nl &
            & // "GEAR/1, JOINTS = 1, 2, CV = 12" // nl &
            & // "ACCGRAV/KGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 3, STEPS = 300" // nl // "END"
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: worst, swing
        integer :: k, c2, c3

        call run_text("gear.adm", text, result, rows, error)
        if (allocated(error)) return
        ! every row written (the run's own verdict on its energy is not what is tested here)
        call check(error, rows%count == 301, "301 rows expected, " // to_text(rows%count))
        if (allocated(error)) return
        c2 = result%summary%layout%column("phi_2")
        c3 = result%summary%layout%column("phi_3")
        worst = 0.0_wp
        swing = 0.0_wp
        do k = 1, rows%count
            worst = max(worst, abs((rows%rows(c2, k) - rows%rows(c2, 1)) &
                & + 2.0_wp*(rows%rows(c3, k) - rows%rows(c3, 1))))
            swing = max(swing, abs(rows%rows(c2, k) - rows%rows(c2, 1)))
        end do
        call check(error, worst <= tol_angle .and. swing > 0.5_wp, "largest |q1 + 2 q2| " &
            & // to_text(worst) // " rad over a swing of " // to_text(swing) // " rad")
    end subroutine test_gear

    !> What couplings and GCONs may not be, each refused with the statement's line and why.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: head = "refused" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.02, 0.02, 0.01" // nl &
            & // "MARKER/20, PART = 2, REULER = 90D, 90D, 0D" // nl &
            & // "JOINT/1, SPHERICAL, I = 20, J = 10" // nl &
            & // "JOINT/2, REVOLUTE, I = 20, J = 10" // nl
        character(len=*), parameter :: tail = nl // "SIMULATE/DYNAMIC, END = 1, STEPS = 10"
        character(len=*), parameter :: statements(6) = [character(len=64) :: &
            & "JOINT/3, RACKPIN, I = 20, J = 10", "JOINT/3, SCREW, I = 20, J = 10, PD = 1", &
            & "COUPLER/1, JOINTS = 1, 2, SCALES = 1, -2", "COUPLER/1, JOINTS = 2, 9, SCALES = 2", &
            & "GCON/1, I = 10, FUNCTION = FX(20)", "GCON/1, I = 10, FUNCTION = DX(20) + DM(99)"]
        character(len=*), parameter :: expected(6) = [character(len=160) :: &
            & ":8: JOINT/3: a RACKPIN joint needs PD=d > 0, the pinion's pitch diameter", &
            & ":8: JOINT/3 PD: PD is the pitch diameter of a RACKPIN joint, not of a SCREW", &
            & ":8: COUPLER/1: JOINT/1 is SPHERICAL; couplers relate TRANSLATIONAL, REVOLUTE and", &
            & ":8: COUPLER/1 JOINTS: no JOINT/9", &
            & ":8: GCON/1 FUNCTION: FX(20): a force, which rollcon solves for together with", &
            & ":8: GCON/1 FUNCTION: DM(99): no MARKER/99 in the dataset"]
        type(job_type) :: job
        type(job_result_type) :: result
        type(error_type), allocatable :: failure
        integer :: k

        do k = 1, size(statements)
            call write_text("refused.adm", head // trim(statements(k)) // tail)
            call load_job(texts_dir // "/refused.adm", job, failure)
            if (.not. allocated(failure)) then
                job%output_dir = ""
                job%quiet = .true.
                call run_job(job, result, failure)
            end if
            call check(error, allocated(failure), "accepted: " // trim(statements(k)))
            if (allocated(error)) return
            call check(error, index(failure%message, texts_dir // "/refused.adm" &
                & // trim(expected(k))) == 1, "message '" // failure%message // "', expected '" &
                & // trim(expected(k)) // "'")
            if (allocated(error)) return
            deallocate(failure)
        end do
    end subroutine test_refusals

end module test_couplers
