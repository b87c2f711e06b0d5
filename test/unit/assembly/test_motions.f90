! SPDX-License-Identifier: MIT
!> Datasets with MOTIONs, run (suite motions): a slider on an incline driven along its joint by
!> a displacement, the same motion given as a velocity and as an acceleration (its integrals
!> against the displacement), the force the motion takes against m (x'' - g.e); a crank driven
!> at constant speed through whole turns against its angle and the torque gravity asks; and
!> what a MOTION may not say, refused by name.
module test_motions
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

    public :: collect_motions

    real(wp), parameter :: g = 9.80665_wp
    character(len=*), parameter :: nl = new_line("a")

contains

    subroutine collect_motions(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("slider-follows-its-motion-and-force-is-m-x2-minus-g", &
            & test_slider), &
            & new_unittest("crank-at-constant-speed-through-whole-turns", test_crank), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_motions

    !> A 2 kg slider on a TRANSLATIONAL joint whose axis e (J's z, REULER 90D, 60D, 0D) rises at
    !> 30 degrees in the ground's x-z plane, driven by MOTION/1 along it to
    !> s(t) = -150 + 10 sin(2 pi t) mm, in a dataset in millimetres under gravity -9806.65 mm/s^2
    !> along z. Its centre follows s e at every row, and the force the motion exerts on it along
    !> e is m (s'' - g.e) = m (s'' + g/2): the joint's other reactions are normal to e. The same
    !> motion as a VELOCITY (s', ICDISP = -150) and as an ACCELERATION (s'', ICDISP, ICVEL =
    !> 20 pi, a number) gives the same rows: their integrals are exact. The MOTION's reaction
    !> columns (motion1_fx ...) are its statement's, and along e they are the driving force;
    !> the summary names it MOTION/1 (line 8), never by its UCON's generated id.
    subroutine test_slider(error)
        type(error_type), allocatable, intent(out) :: error
        !> The position constraint is held by each step's Newton iteration: measured 3.1e-11 m
        !> (each form alike); 1e-9 m is 30 times that and 1e-7 of the 10 mm stroke
        real(wp), parameter :: tol_position = 1.0e-9_wp
        !> The force from the multiplier: measured 4e-15 N of the 10 N (the motion fixes the
        !> acceleration exactly); 1e-9 N, a millionth of what a missing g.e (9.8 N) gives
        real(wp), parameter :: tol_force = 1.0e-9_wp
        character(len=*), parameter :: head = "slider driven by a MOTION" // nl &
            & // "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = MILLIMETER, TIME = SECOND" &
            & // nl // "PART/1, GROUND" // nl // "MARKER/10, PART = 1, REULER = 90D, 60D, 0D" &
            & // nl // "PART/2, MASS = 2, CM = 20, IP = 1000, 1000, 100" // nl &
            & // "MARKER/20, PART = 2, REULER = 90D, 60D, 0D" // nl &
            & // "JOINT/1, TRANSLATIONAL, I = 20, J = 10" // nl
        character(len=*), parameter :: tail = nl // "ACCGRAV/KGRAV = -9806.65" // nl &
            & // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 100" // nl // "END"
        character(len=*), parameter :: motions(3) = [character(len=120) :: &
            & "MOTION/1, JOINT = 1, TRANSLATIONAL, FUNCTION = -150 + 10*SIN(2*PI*TIME)", &
            & "MOTION/1, JOINT = 1, TRANSLATION, VELOCITY, FUNCTION = 20*PI*COS(2*PI*TIME), " &
            & // "ICDISP = -150", &
            & "MOTION/1, JOINT = 1, TRANS, ACC, FUNCTION = -40*PI**2*SIN(2*PI*TIME), " &
            & // "ICDISP = -150, ICVEL = 62.831853071795865"]
        real(wp), parameter :: axis(3) = [sqrt(3.0_wp)/2.0_wp, 0.0_wp, 0.5_wp]
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: worst, worst_force, t, s, s2
        real(wp) :: worst_split
        integer :: k, m, cx, cf, cr

        do m = 1, size(motions)
            call run_text("motion_slider.adm", head // trim(motions(m)) // tail, result, rows, &
                & error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. rows%count == 101, &
                & "run " // to_text(m) // " completes with 101 rows")
            if (allocated(error)) return
            cx = result%summary%layout%column("X_2")
            cf = result%summary%layout%column("motion1_force")
            cr = result%summary%layout%column("motion1_fx")
            call check(error, cx > 0 .and. cf > 0 .and. cr > 0, "columns X_2, motion1_force " &
                & // "and motion1_fx")
            if (allocated(error)) return
            call check(error, index(result%summary%ucon_labels, "MOTION/1 (line 8)") > 0 &
                & .and. index(result%summary%ucon_labels, "UCON") == 0, "the summary's words " &
                & // "for the constraints: " // result%summary%ucon_labels)
            if (allocated(error)) return
            worst = 0.0_wp
            worst_force = 0.0_wp
            worst_split = 0.0_wp
            do k = 1, rows%count
                t = rows%rows(1, k)
                s = (-150.0_wp + 10.0_wp*sin(2.0_wp*pi*t))*1.0e-3_wp
                s2 = -10.0e-3_wp*(2.0_wp*pi)**2*sin(2.0_wp*pi*t)
                worst = max(worst, norm2(rows%rows(cx:cx + 2, k) - s*axis))
                worst_force = max(worst_force, abs(rows%rows(cf, k) - 2.0_wp*(s2 + g/2.0_wp)))
                worst_split = max(worst_split, abs(dot_product(rows%rows(cr:cr + 2, k), axis) &
                    & - rows%rows(cf, k)))
            end do
            ! both from the one multiplier: the same tolerance as the force's
            call check(error, worst_split <= tol_force, "run " // to_text(m) // ": largest " &
                & // "difference of motion1_fx..fz along e from motion1_force " &
                & // to_text(worst_split) // " N")
            if (allocated(error)) return
            call check(error, worst <= tol_position, "run " // to_text(m) // ": largest " &
                & // "distance of the centre from s(t) e " // to_text(worst) // " m")
            if (allocated(error)) return
            call check(error, worst_force <= tol_force, "run " // to_text(m) // ": largest " &
                & // "difference of motion1_force from m (s'' - g.e) " // to_text(worst_force) &
                & // " N")
            if (allocated(error)) return
        end do
    end subroutine test_slider

    !> A crank of 1 kg, its centre l = 0.5 m from a REVOLUTE to ground whose axis e is ground
    !> y (J's z; J's x is -x), driven by MOTION/1, ROTATION, FUNCTION = 2 pi TIME through one
    !> and a half turns (past the angle's branch cut at half a turn). Its centre follows
    !> l (-cos wt, 0, sin wt), and at constant speed about a principal axis its angular
    !> momentum about the pivot changes only by m r x a: the motion's torque about e is
    !> e.(r x m (a - g)) with a = -w^2 r, that is -m e.(r x g). The same crank with its
    !> principal z axis along the arm reaches the Euler singularity within a quarter turn: it
    !> is re-based once, turned about body y so that its rotation axis, body x, becomes its z
    !> (basis 20: docs/rebasing.md), which stays horizontal (turned about x each time it
    !> would pass the singularity twice a turn), the MOTION's routine turned with it.
    subroutine test_crank(error)
        type(error_type), allocatable, intent(out) :: error
        !> The angle is held by each step's Newton iteration at ERROR = 1e-9: measured 5.6e-10 m
        !> at the centre; 1e-8 m is 18 times that and 2e-8 of the radius
        real(wp), parameter :: tol_position = 1.0e-8_wp
        !> The torque from the multiplier: measured 3e-9 N m of the 4.9 N m; 1e-7 N m is 33
        !> times that
        real(wp), parameter :: tol_torque = 1.0e-7_wp
        character(len=*), parameter :: along = "PART/2, MASS = 1, CM = 20, IP = 0.1, 0.1, " &
            & // "0.01, QG = -0.5, 0, 0, REULER = 90D, 90D, 0D" // nl // "MARKER/20, PART = 2" &
            & // nl // "MARKER/21, PART = 2, QP = 0, 0, 0.5, REULER = 90D, 90D, -90D"
        character(len=*), parameter :: text = "crank driven by a MOTION" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART = 1, REULER = 180D, 90D, 0D" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.01, 0.1, 0.1, QG = -0.5, 0, 0, " &
            & // "REULER = 180D, 90D, 0D" // nl // "MARKER/20, PART = 2" // nl &
            & // "MARKER/21, PART = 2, QP = -0.5, 0, 0" // nl &
            & // "JOINT/1, REVOLUTE, I = 21, J = 10" // nl &
            & // "MOTION/1, JOINT = 1, ROTATION, FUNCTION = 2*PI*TIME" // nl &
            & // "ACCGRAV/KGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-9" // nl &
            & // "SIMULATE/DYNAMIC, END = 1.5, STEPS = 150" // nl // "END"
        real(wp), parameter :: l = 0.5_wp, mass = 1.0_wp, e(3) = [0.0_wp, 1.0_wp, 0.0_wp]
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: worst, worst_torque, t, r(3), torque
        integer :: k, cx, ct, n, first, last
        character(len=:), allocatable :: dataset

        do n = 1, 2
            dataset = text
            if (n == 2) then
                ! the part's frame and the pivot marker turned: the arm along the principal z axis
                first = index(dataset, "PART/2")
                last = index(dataset, "JOINT/1") - 1
                dataset = dataset(:first - 1) // along // nl // dataset(last + 1:)
            end if
            call run_text("motion_crank.adm", dataset, result, rows, error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. rows%count == 151, &
                & "run " // to_text(n) // " completes with 151 rows")
            if (allocated(error)) return
            if (n == 2) then
                k = result%summary%layout%column("basis_2")
                call check(error, k > 0, "column basis_2")
                if (allocated(error)) return
                call check(error, result%summary%rebasings(1) == 1 .and. nint(rows%rows(k, &
                    & rows%count)) == 20, "re-basings of the crank " &
                    & // to_text(result%summary%rebasings(1)) // ", expected 1; its basis " &
                    & // to_text(nint(rows%rows(k, rows%count))) // ", expected 20")
                if (allocated(error)) return
            end if
            cx = result%summary%layout%column("X_2")
            ct = result%summary%layout%column("motion1_torque")
            call check(error, cx > 0 .and. ct > 0, "columns X_2 and motion1_torque")
            if (allocated(error)) return
            worst = 0.0_wp
            worst_torque = 0.0_wp
            do k = 1, rows%count
                t = rows%rows(1, k)
                r = rows%rows(cx:cx + 2, k)
                worst = max(worst, norm2(r - l*[-cos(2.0_wp*pi*t), 0.0_wp, sin(2.0_wp*pi*t)]))
                ! -m e.(r x g), g = (0, 0, -g): e.(r x g) = r_z g_x - r_x g_z = g r_x
                torque = -mass*g*r(1)*e(2)
                worst_torque = max(worst_torque, abs(rows%rows(ct, k) - torque))
            end do
            call check(error, worst <= tol_position, "run " // to_text(n) // ": largest distance " &
                & // "of the centre from its circle at 2 pi t " // to_text(worst) // " m")
            if (allocated(error)) return
            call check(error, worst_torque <= tol_torque, "run " // to_text(n) // ": largest " &
                & // "difference of motion1_torque from -m e.(r x g) " // to_text(worst_torque) &
                & // " N m")
            if (allocated(error)) return
        end do
    end subroutine test_crank

    !> What a MOTION may not say, each refused with its line and why.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: head = "refused" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, REULER = 90D, 90D, 0D" // nl &
            & // "PART/2, MASS = 1, CM = 20, IP = 0.02, 0.02, 0.01" // nl &
            & // "MARKER/20, PART = 2, REULER = 90D, 90D, 0D" // nl &
            & // "JOINT/1, REVOLUTE, I = 20, J = 10" // nl
        character(len=*), parameter :: tail = nl // "SIMULATE/DYNAMIC, END = 1, STEPS = 10"
        character(len=*), parameter :: statements(7) = [character(len=72) :: &
            & "MOTION/1, JOINT = 1, TRANSLATION, FUNCTION = TIME", &
            & "MOTION/1, JOINT = 1, ROTATION, VELOCITY, FUNCTION = 1, ICVEL = 2", &
            & "MOTION/1, JOINT = 1, ROTATION, FUNCTION = DX(20)", &
            & "MOTION/1, JOINT = 1, ROTATION", &
            & "MOTION/1, JOINT = 9, ROTATION, FUNCTION = TIME", &
            & "MOTION/1, JOINT = 1, X, FUNCTION = TIME", &
            & "MOTION/1, I = 20, J = 10, B1, FUNCTION = TIME, ICDISP = 1"]
        character(len=*), parameter :: expected(7) = [character(len=120) :: &
            & ":7: MOTION/1: JOINT/1 is REVOLUTE; a TRANSLATION drives a TRANSLATIONAL or", &
            & ":7: MOTION/1 ICVEL: ICVEL is for an ACCELERATION motion", &
            & ":7: MOTION/1 FUNCTION: a MOTION's function is an expression of TIME alone", &
            & ":7: MOTION/1: FUNCTION=e is missing", &
            & ":7: MOTION/1 JOINT: no JOINT/9", &
            & ":7: MOTION/1: X is a direction between markers (I=, J=)", &
            & ":7: MOTION/1 ICDISP: a DISPLACEMENT motion's function is its displacement"]
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

end module test_motions
