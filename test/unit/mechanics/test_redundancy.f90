! SPDX-License-Identifier: MIT
!> Redundant equations set aside (suite redundancy, docs/design.md §4): closed loops of joints
!> and a cart whose two rolling wheels repeat each other's sideways no-slip run, each against a
!> solution of its own one degree of freedom or a closed form, on every formulation where the
!> choice wears; a loop that contradicts itself is refused in the user's words; the split of a
!> redundant joint's reaction does not depend on units. Datasets: test/redundant/.
module test_redundancy
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_load, only : load_job, input_override_type
    use rollcon_job, only : job_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_linearisation, only : linear_result_type
    use rollcon_linear_job, only : linearise_job
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : count_of
    use rollcon_problem, only : problem_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_least_squares, only : minimum_norm_solve, smallest_singular_value
    use rollcon_model, only : statement_joint
    use rollcon_lapack, only : symmetric_eigen, factor_dense, solve_factored
    implicit none
    private

    public :: collect_redundancy

    !> Gravity of the datasets [m/s^2]
    real(wp), parameter :: g = 9.81_wp
    !> Scratch folder for datasets written by a test
    character(len=*), parameter :: scratch = "build/test_redundancy"

contains

    subroutine collect_redundancy(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("fourbar-one-degree-of-freedom", test_fourbar), &
            & new_unittest("slider-crank-one-degree-of-freedom", test_slider_crank), &
            & new_unittest("cart-on-its-circle-ida", test_cart_ida), &
            & new_unittest("cart-on-its-circle-cvode", test_cart_cvode), &
            & new_unittest("cart-on-its-circle-independent-speeds", test_cart_speeds), &
            & new_unittest("welded-cart-chosen-again-sparse", test_cart_welded), &
            & new_unittest("contradictory-loop-refused", test_contradictory), &
            & new_unittest("fourbar-linear-hanging", test_linear), &
            & new_unittest("least-norm-split-independent-of-units", test_units), &
            & new_unittest("large-block-sets-aside-the-loops-rows", test_large_block), &
            & new_unittest("train-of-four-bars-sparse-choice", test_train), &
            & new_unittest("long-train-of-four-bars-sparse-choice", test_long_train)]
    end subroutine collect_redundancy

    !> test/redundant/fourbar.adm: a parallelogram of four REVOLUTEs (3 redundant equations)
    !> swinging from -30 degrees. Its crank angle theta (from +X to the crank) obeys the loop's
    !> Lagrange equation I theta'' = -(m_c + m_k) g L cos(theta), I = 2 (I_c + m_c L^2/4) +
    !> m_k L^2 (the coupler translates): theta and theta' at every row against RK4 on that
    !> equation, and its energy integral I theta'^2/2 + (m_c + m_k) g L sin(theta) held. The
    !> reactions the four joints share are the
    !> least-norm split: out of the plane, where gravity and the motion ask for nothing, they
    !> are zero; in the plane they are unique, and the two ground joints' forces on the cranks
    !> sum to the mechanism's m a less its weight. The summary names the joints and lines whose
    !> equations were set aside, never a generated UCON id.
    subroutine test_fourbar(error)
        type(error_type), allocatable, intent(out) :: error
        !> Crank and coupler masses [kg], crank length [m], crank moment about its CM [kg m^2]
        real(wp), parameter :: crank_mass = 1.0_wp, coupler_mass = 2.0_wp, length = 1.0_wp, &
            & crank_moment = 0.09_wp
        !> IDA at ERROR = 1e-10 over 2 s: theta within 1.2e-8 rad and theta' within 4.0e-8 rad/s
        !> of RK4 (h = 1e-4 s, its own error 1e-14), the energy within 3.3e-7 J of its start
        !> (of 14.7 J; measured); 5e-8, 2e-7 and 1.5e-6 catch a tenfold loss
        real(wp), parameter :: tol_angle = 5.0e-8_wp, tol_rate = 2.0e-7_wp, &
            & tol_energy = 1.5e-6_wp
        !> Reactions: the out-of-plane ones are rounding of forces of 36 N (measured 7e-14);
        !> the sum of the ground forces against m a - m g of the row's own theta, theta'
        !> (measured 2.7e-9 N of 36 N)
        real(wp), parameter :: tol_out_of_plane = 1.0e-10_wp, tol_sum = 1.0e-8_wp
        real(wp), parameter :: step = 1.0e-4_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: inertia, state(2), t, x, y, theta, rate, acceleration, expected(3), total(3)
        integer :: k, c

        call run_dataset("test/redundant/fourbar.adm", "", result, rows, error)
        if (allocated(error)) return
        associate (lines => result%summary%watch_lines)
            call check(error, index(lines, "warning: redundant equations set aside") > 0 &
                & .and. index(lines, "JOINT/") > 0 .and. index(lines, "(line ") > 0 .and. &
                & index(lines, "UCON/") == 0 .and. &
                & index(lines, "the split reported is the least-norm one") > 0, &
                & "the summary: " // lines)
        end associate
        if (allocated(error)) return
        inertia = 2.0_wp*(crank_moment + crank_mass*(0.5_wp*length)**2) + coupler_mass*length**2
        state = [-pi/6.0_wp, 0.0_wp]
        t = 0.0_wp
        associate (layout => rows%layout)
            do k = 1, rows%count
                do while (t < rows%rows(1, k) - 0.5_wp*step)
                    call rk4_pendulum(state, step, 3.0_wp*g/inertia)
                    t = t + step
                end do
                x = rows%rows(layout%column("X_2"), k)
                y = rows%rows(layout%column("Y_2"), k)
                theta = atan2(y, x)
                rate = (x*rows%rows(layout%column("Ydot_2"), k) &
                    & - y*rows%rows(layout%column("Xdot_2"), k))/(x**2 + y**2)
                call check(error, theta, state(1), "crank angle at t = " &
                    & // to_text(rows%rows(1, k)) // " s [rad]", abs_tol=tol_angle)
                if (allocated(error)) return
                call check(error, rate, state(2), "crank rate at t = " &
                    & // to_text(rows%rows(1, k)) // " s [rad/s]", abs_tol=tol_rate)
                if (allocated(error)) return
                ! energy: I theta'^2 / 2 + 3 g L sin(theta) = 3 g L sin(theta_0)
                call check(error, 0.5_wp*inertia*rate**2 + 3.0_wp*g*length*sin(theta), &
                    & 3.0_wp*g*length*sin(-pi/6.0_wp), "the loop's energy at t = " &
                    & // to_text(rows%rows(1, k)) // " s [J]", abs_tol=tol_energy)
                if (allocated(error)) return
                do c = 1, 4
                    call check(error, maxval(abs([rows%rows(layout%column("joint" // to_text(c) &
                        & // "_fz"), k), rows%rows(layout%column("joint" // to_text(c) &
                        & // "_tx"), k), rows%rows(layout%column("joint" // to_text(c) &
                        & // "_ty"), k)])) <= tol_out_of_plane, "JOINT/" // to_text(c) &
                        & // "'s out-of-plane reaction at t = " // to_text(rows%rows(1, k)) &
                        & // " s is not zero")
                    if (allocated(error)) return
                end do
                ! the cranks' and the coupler's CMs move as L/2, L/2 and L times the crank tip
                acceleration = -3.0_wp*g*cos(theta)/inertia
                expected(1:2) = (0.5_wp*crank_mass + 0.5_wp*crank_mass + coupler_mass)*length &
                    & *(acceleration*[-sin(theta), cos(theta)] - rate**2*[cos(theta), sin(theta)])
                expected(2) = expected(2) + (2.0_wp*crank_mass + coupler_mass)*g
                expected(3) = 0.0_wp
                total = rows%rows(layout%column("joint1_fx"):layout%column("joint1_fz"), k) &
                    & + rows%rows(layout%column("joint4_fx"):layout%column("joint4_fz"), k)
                call check(error, total, expected, "the ground joints' forces on the cranks " &
                    & // "at t = " // to_text(rows%rows(1, k)) // " s [N]", abs_tol=tol_sum)
                if (allocated(error)) return
            end do
        end associate
    end subroutine test_fourbar

    !> One RK4 step of theta'' = -k cos(theta), state (theta, theta').
    pure subroutine rk4_pendulum(state, h, k)
        real(wp), intent(inout) :: state(2)
        real(wp), intent(in) :: h, k
        real(wp) :: k1(2), k2(2), k3(2), k4(2)

        k1 = [state(2), -k*cos(state(1))]
        k2 = [state(2) + 0.5_wp*h*k1(2), -k*cos(state(1) + 0.5_wp*h*k1(1))]
        k3 = [state(2) + 0.5_wp*h*k2(2), -k*cos(state(1) + 0.5_wp*h*k2(1))]
        k4 = [state(2) + h*k3(2), -k*cos(state(1) + h*k3(1))]
        state = state + h/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
    end subroutine rk4_pendulum

    !> test/redundant/slider_crank.adm: three REVOLUTEs and a TRANSLATIONAL (3 redundant
    !> equations), driven from rest at 30 degrees by tau = 1 N m against gravity. One degree of
    !> freedom: with T = M(theta) theta'^2 / 2 (M from the linkage's kinematics, slider at
    !> x = r cos(theta) + sqrt(l^2 - r^2 sin^2(theta))) and V(theta) the weights' potential,
    !> Lagrange gives M theta'' + M'(theta) theta'^2 / 2 = tau - V'(theta). theta at every row
    !> against RK4 on it (M' by the complex step: exact to rounding), theta' against the energy
    !> integral M theta'^2 / 2 + V - tau (theta - theta_0) = V(theta_0).
    subroutine test_slider_crank(error)
        type(error_type), allocatable, intent(out) :: error
        !> IDA at ERROR = 1e-10 over 3.6 turns to 65 rad/s: theta within 5.2e-7 rad of RK4 (h =
        !> 2e-5 s: its own error 2e-10), theta' within 2.5e-6 rad/s of the energy (measured);
        !> 2e-6 and 1e-5 catch a tenfold loss
        real(wp), parameter :: tol_angle = 2.0e-6_wp, tol_rate = 1.0e-5_wp
        real(wp), parameter :: step = 2.0e-5_wp, theta_0 = pi/6.0_wp, torque = 1.0_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: state(2), t, x, y, theta, rate, energy
        integer :: k

        call run_dataset("test/redundant/slider_crank.adm", "", result, rows, error)
        if (allocated(error)) return
        state = [theta_0, 0.0_wp]
        t = 0.0_wp
        theta = theta_0
        associate (layout => rows%layout)
            do k = 1, rows%count
                do while (t < rows%rows(1, k) - 0.5_wp*step)
                    call rk4_slider(state, step, torque)
                    t = t + step
                end do
                x = rows%rows(layout%column("X_2"), k)
                y = rows%rows(layout%column("Y_2"), k)
                ! the crank's angle, continued through whole turns
                theta = theta + modulo(atan2(y, x) - theta + pi, 2.0_wp*pi) - pi
                rate = (x*rows%rows(layout%column("Ydot_2"), k) &
                    & - y*rows%rows(layout%column("Xdot_2"), k))/(x**2 + y**2)
                call check(error, theta, state(1), "crank angle at t = " &
                    & // to_text(rows%rows(1, k)) // " s [rad]", abs_tol=tol_angle)
                if (allocated(error)) return
                energy = slider_potential(theta_0) - slider_potential(theta) &
                    & + torque*(theta - theta_0)
                call check(error, rate, sqrt(max(0.0_wp, 2.0_wp*energy &
                    & /real(slider_mass(cmplx(theta, 0.0_wp, wp)), wp))), "crank rate at t = " &
                    & // to_text(rows%rows(1, k)) // " s [rad/s]", abs_tol=tol_rate)
                if (allocated(error)) return
            end do
            call check(error, theta > theta_0 + 6.0_wp*pi, "the crank turned " &
                & // to_text((theta - theta_0)/(2.0_wp*pi)) // " times, not 3 or more")
        end associate
    end subroutine test_slider_crank

    !> The slider-crank's M(theta) [kg m^2] (test_slider_crank), in complex arithmetic for the
    !> complex step: crank r = 0.1 m, 0.5 kg, r^2/12 per kg about its CM at mid-length; rod
    !> l = 0.3 m, 1 kg, l^2/12 per kg; slider 2 kg.
    pure function slider_mass(theta) result(m)
        complex(wp), intent(in) :: theta
        complex(wp) :: m
        real(wp), parameter :: r = 0.1_wp, l = 0.3_wp, crank = 0.5_wp, rod = 1.0_wp, &
            & slider = 2.0_wp
        complex(wp) :: root, slide, rod_x, rod_y, rod_turn

        root = sqrt(l**2 - r**2*sin(theta)**2)
        ! dx/dtheta of the slider, of the rod's centre (midway from pin to slider)
        slide = -r*sin(theta) - r**2*sin(theta)*cos(theta)/root
        rod_x = 0.5_wp*(-r*sin(theta) + slide)
        rod_y = 0.5_wp*r*cos(theta)
        ! the rod's turn: its angle phi has l sin(phi) = -r sin(theta)
        rod_turn = -r*cos(theta)/root
        m = crank*(0.25_wp*r**2 + r**2/12.0_wp) + rod*(rod_x**2 + rod_y**2 &
            & + rod_turn**2*l**2/12.0_wp) + slider*slide**2
    end function slider_mass

    !> The slider-crank's potential [J]: the crank's CM at r/2 sin(theta), the rod's at
    !> r/2 sin(theta), the slider on the X axis.
    pure real(wp) function slider_potential(theta)
        real(wp), intent(in) :: theta

        slider_potential = g*(0.5_wp*0.05_wp + 1.0_wp*0.05_wp)*sin(theta)
    end function slider_potential

    !> One RK4 step of M theta'' = tau - V' - M' theta'^2 / 2, state (theta, theta').
    pure subroutine rk4_slider(state, h, torque)
        real(wp), intent(inout) :: state(2)
        real(wp), intent(in) :: h, torque
        real(wp) :: k1(2), k2(2), k3(2), k4(2)

        k1 = slope(state)
        k2 = slope(state + 0.5_wp*h*k1)
        k3 = slope(state + 0.5_wp*h*k2)
        k4 = slope(state + h*k3)
        state = state + h/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
    contains
        pure function slope(s) result(ds)
            real(wp), intent(in) :: s(2)
            real(wp) :: ds(2)
            !> The complex step: M'(theta) = Im M(theta + i h) / h, exact to rounding
            real(wp), parameter :: tiny_step = 1.0e-30_wp
            real(wp) :: m, dm

            m = real(slider_mass(cmplx(s(1), 0.0_wp, wp)), wp)
            dm = aimag(slider_mass(cmplx(s(1), tiny_step, wp)))/tiny_step
            ds = [s(2), (torque - g*(0.5_wp*0.05_wp + 1.0_wp*0.05_wp)*cos(s(1)) &
                & - 0.5_wp*dm*s(2)**2)/m]
        end function slope
    end subroutine rk4_slider

    !> test/redundant/two_wheeled_cart.adm on IDA (the DAE form).
    subroutine test_cart_ida(error)
        type(error_type), allocatable, intent(out) :: error

        ! IDA at ERROR = 1e-10: radius within 1.1e-8 m, loads within 6.7e-8 N (measured)
        call check_cart("", 5.0e-8_wp, 3.0e-7_wp, error)
    end subroutine test_cart_ida

    !> The cart on CVODE (the ODE form, projection onto the constraints).
    subroutine test_cart_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        ! CVODE at ERROR = 1e-10: radius within 9.0e-9 m, loads within 6.0e-8 N (measured)
        call check_cart("CVODE", 4.0e-8_wp, 3.0e-7_wp, error)
    end subroutine test_cart_cvode

    !> The cart in independent speeds (the partition over the active rows).
    subroutine test_cart_speeds(error)
        type(error_type), allocatable, intent(out) :: error

        ! independent speeds at ERROR = 1e-10: radius within 6.7e-9 m, loads within 3.7e-11 N
        ! (measured: the velocity UCONs hold exactly, docs/design.md §4)
        call check_cart("MAGGI", 3.0e-8_wp, 2.0e-10_wp, error)
    end subroutine test_cart_speeds

    !> test/redundant/two_wheeled_cart_welded.adm: the cart with eight links welded to its body
    !> at its CM (the body of 4.8 kg), one block of 64 rows: its choice and every choice again as
    !> the heading turns are the sparse ones (rollcon_redundancy's choose_sparse_block, the
    !> measure of sparse_measure watched): the circle and the loads held as the cart alone's.
    subroutine test_cart_welded(error)
        type(error_type), allocatable, intent(out) :: error

        ! IDA at ERROR = 1e-10: radius within 6.2e-9 m, loads within 1.5e-8 N (measured; the
        ! cart alone's 1.1e-8 m and 6.7e-8 N); 3e-8 and 1e-7 catch a tenfold loss
        call check_cart("", 3.0e-8_wp, 1.0e-7_wp, error, &
            & "test/redundant/two_wheeled_cart_welded.adm", 4.8_wp)
    end subroutine test_cart_welded

    !> test/redundant/two_wheeled_cart.adm in the given formulation ("": the dataset's IDA): a
    !> body of 4 kg on an axle of half-track d = 0.3 m, two wheels (1 kg, C = 0.02 kg m^2 about
    !> the axle, radius 0.2 m) each rolling without slip; its one redundant equation (the two
    !> wheels' sideways no-slip repeat each other through the axle) changes with the heading.
    !> Pushed at 1 m/s and 1 rad/s it must stay on its circle, radius 1 m about (0, 1), at every
    !> row of a whole turn (every heading), and the wheels' loads (the height UCONs' vertical
    !> force, ucon3_fz and ucon6_fz) are constant. Moments about the heading axis at the
    !> ground, the sideways friction's line through it: d (N_in - N_out) = -h sum m_i a_i -
    !> C Omega sum s_i (h = 0.2 m the centres' height, a_i = Omega^2 R_i towards the centre,
    !> s_i = Omega R_i / 0.2 the wheels' spin, the last term the spinning wheels' gyroscopic
    !> moment), N_in + N_out = M g: N_in = 27.0967 N, N_out = 31.7633 N. The choice wears as
    !> the heading turns (the row set aside has a coefficient like cos(heading) in the
    !> dependency): it is chosen again, and other rows set aside, at least three times a turn.
    subroutine check_cart(formulation, tol_radius, tol_load, error, path, body_mass)
        character(len=*), intent(in) :: formulation
        !> The circle's and the loads' tolerances [m, N] (the callers': a few times measured)
        real(wp), intent(in) :: tol_radius, tol_load
        type(error_type), allocatable, intent(out) :: error
        !> Another dataset of the cart (default two_wheeled_cart.adm) and its body's mass [kg]
        !> with what is welded to it at its CM (default 4)
        character(len=*), intent(in), optional :: path
        real(wp), intent(in), optional :: body_mass
        real(wp), parameter :: omega = 1.0_wp, half_track = 0.3_wp, height = 0.2_wp, &
            & radius = 0.2_wp, axial_moment = 0.02_wp, circles(3) = [1.0_wp, 0.7_wp, 1.3_wp]
        real(wp) :: masses(3)
        character(len=:), allocatable :: dataset
        logical :: closed_form
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: roll, inner, outer
        integer :: k, choices, at

        dataset = "test/redundant/two_wheeled_cart.adm"
        if (present(path)) dataset = path
        masses = [4.0_wp, 1.0_wp, 1.0_wp]
        if (present(body_mass)) masses(1) = body_mass
        call run_dataset(dataset, formulation, result, rows, error)
        if (allocated(error)) return
        roll = (height*sum(masses*omega**2*circles) &
            & + axial_moment*omega*sum(omega*circles(2:)/radius))/half_track
        inner = 0.5_wp*(sum(masses)*g - roll)
        outer = 0.5_wp*(sum(masses)*g + roll)
        ! the dataset's comment's numbers for the cart alone
        closed_form = abs(inner - 27.0967_wp) < 1.0e-4_wp .and. abs(outer - 31.7633_wp) &
            & < 1.0e-4_wp
        call check(error, closed_form .or. present(body_mass), "the closed form's loads " &
            & // to_text(inner) // " and " // to_text(outer) // " N")
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. abs(rows%rows(1, &
            & rows%count) - 2.0_wp*pi) < 1.0e-9_wp, "a whole turn: status " &
            & // to_text(result%summary%status) // " at t = " // to_text(rows%rows(1, &
            & rows%count)))
        if (allocated(error)) return
        associate (layout => rows%layout)
            do k = 1, rows%count
                call check(error, hypot(rows%rows(layout%column("X_2"), k), &
                    & rows%rows(layout%column("Y_2"), k) - 1.0_wp), 1.0_wp, "the cart's " &
                    & // "distance from the circle's centre at t = " // to_text(rows%rows(1, k)) &
                    & // " s [m]", abs_tol=tol_radius)
                if (allocated(error)) return
                call check(error, rows%rows(layout%column("ucon3_fz"), k), inner, "the inner " &
                    & // "wheel's load at t = " // to_text(rows%rows(1, k)) // " s [N]", &
                    & abs_tol=tol_load)
                if (allocated(error)) return
                call check(error, rows%rows(layout%column("ucon6_fz"), k), outer, "the outer " &
                    & // "wheel's load at t = " // to_text(rows%rows(1, k)) // " s [N]", &
                    & abs_tol=tol_load)
                if (allocated(error)) return
            end do
        end associate
        at = index(result%summary%watch_lines, "chosen again ")
        choices = 0
        if (at > 0) read(result%summary%watch_lines(at + 13:), *) choices
        call check(error, choices >= 3 .and. index(result%summary%watch_lines, "UCON/5 (line ") &
            & > 0, &
            & "chosen again " // to_text(choices) // " times over a turn; summary: " &
            & // result%summary%watch_lines)
    end subroutine check_cart

    !> The four-bar with JOINT/2's marker on the coupler 0.1 m out of the plane: the loop's
    !> out-of-plane equations, redundant when they agree, now contradict each other (no
    !> position meets them all). Refused by the initial-conditions analysis, naming the joints'
    !> statements and lines, never a generated UCON id.
    subroutine test_contradictory(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result
        type(history_type) :: rows
        type(error_type), allocatable :: refused

        call copy_replacing("test/redundant/fourbar.adm", scratch // "/contradictory.adm", &
            & ["MARKER/31, PART=3, QP=0.8660254037844386, -0.5, 0  "], &
            & ["MARKER/31, PART=3, QP=0.8660254037844386, -0.5, 0.1"], error)
        if (allocated(error)) return
        call load_job(scratch // "/contradictory.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, refused, rows)
        call check(error, allocated(refused), "the contradictory loop ran")
        if (allocated(error)) return
        call check(error, index(refused%message, "contradictory at position level") > 0 &
            & .and. index(refused%message, "JOINT/2 (line 25: ") > 0 &
            & .and. index(refused%message, "translation along ground Z") > 0 &
            & .and. index(refused%message, "UCON/") == 0 .and. result%summary%rows == 0, &
            & "the refusal: " // refused%message)
    end subroutine test_contradictory

    !> The four-bar hanging at rest (cranks straight down, theta = -90 degrees): `rollcon
    !> linear` on its active rows (the rows set aside repeat them) finds the one mode of the
    !> loop's equation linearised there, I theta'' = -3 g L (theta + pi/2): lambda = +-i
    !> sqrt(3 g L / I), on an invariant tangent space (the start is steady).
    subroutine test_linear(error)
        type(error_type), allocatable, intent(out) :: error
        !> The linearisation's differences are good to 1e-10 relative (docs/linear.md)
        real(wp), parameter :: tol_frequency = 1.0e-8_wp
        real(wp), parameter :: inertia = 2.0_wp*(0.09_wp + 0.25_wp) + 2.0_wp
        character(len=*), parameter :: lines(*) = [character(len=70) :: &
            & "MARKER/20, PART=2, QP=0.4330127018922193, -0.25, 0, REULER=0D, 90D, 0D", &
            & "MARKER/22, PART=2, QP=0.8660254037844386, -0.5, 0", &
            & "MARKER/30, PART=3, QP=1.8660254037844386, -0.5, 0, REULER=0D, 90D, 0D", &
            & "MARKER/31, PART=3, QP=0.8660254037844386, -0.5, 0", &
            & "MARKER/32, PART=3, QP=2.8660254037844386, -0.5, 0", &
            & "MARKER/40, PART=4, QP=2.4330127018922193, -0.25, 0, REULER=0D, 90D, 0D", &
            & "MARKER/41, PART=4, QP=2.8660254037844386, -0.5, 0"]
        character(len=*), parameter :: hanging(*) = [character(len=70) :: &
            & "MARKER/20, PART=2, QP=0, -0.5, 0, REULER=0D, 90D, 0D", &
            & "MARKER/22, PART=2, QP=0, -1, 0", &
            & "MARKER/30, PART=3, QP=1, -1, 0, REULER=0D, 90D, 0D", &
            & "MARKER/31, PART=3, QP=0, -1, 0", "MARKER/32, PART=3, QP=2, -1, 0", &
            & "MARKER/40, PART=4, QP=2, -0.5, 0, REULER=0D, 90D, 0D", &
            & "MARKER/41, PART=4, QP=2, -1, 0"]
        type(job_type) :: job
        type(linear_result_type) :: result
        character(len=:), allocatable :: report

        call copy_replacing("test/redundant/fourbar.adm", scratch // "/hanging.adm", lines, &
            & hanging, error)
        if (allocated(error)) return
        call load_job(scratch // "/hanging.adm", job, error)
        if (allocated(error)) return
        call linearise_job(job, result, report, error)
        if (allocated(error)) return
        call check(error, result%reduced == 2 .and. result%invariant .and. &
            & index(report, "redundant equations set aside") > 0, to_text(result%reduced) &
            & // " independent states, invariance " // to_text(result%invariance) &
            & // "; report: " // report)
        if (allocated(error)) return
        call check(error, [result%real_part(1), abs(result%imag_part(1))], [0.0_wp, &
            & sqrt(3.0_wp*g/inertia)], "the hanging loop's eigenvalue [1/s]", &
            & abs_tol=tol_frequency)
    end subroutine test_linear

    !> test/redundant/door.adm: a door of 10 kg on two REVOLUTEs on one vertical axis (5
    !> redundant equations), held still: the weight's pull along the axis and its moment about
    !> the horizontal may be split between the hinges' forces and moments in many ways. The
    !> split reported is the least-norm one in the mass metric, so the same door written in
    !> millimetres (positions 1000 times, moments of inertia 1e6 times, gravity 9810 mm/s^2)
    !> gives the same reactions [N, N m]; the least norm in the plain multipliers would not
    !> (its moments in N mm weigh 1e6 times more). And they balance the weight: their forces sum
    !> to (0, 0, m g), each hinge bearing m g / 2 along the axis (the two are alike), and their
    !> moments about the centre of mass sum to zero.
    subroutine test_units(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: mass = 10.0_wp
        !> A still state: the split from one least-squares solve of a well-conditioned block,
        !> forces of 50 N (the two runs agree to the last bit, measured); 1e-9 N allows their
        !> rounding to differ
        real(wp), parameter :: tol_same = 1.0e-9_wp
        character(len=*), parameter :: lines(*) = [character(len=70) :: &
            & "UNITS/SYSTEM=SI", "MARKER/10, PART=1, QP=0, 0, 0.5", &
            & "MARKER/11, PART=1, QP=0, 0, 1.5", "PART/2, MASS=10, CM=20, IP=1, 0.8, 0.3", &
            & "MARKER/20, PART=2, QP=0.5, 0, 1, REULER=0D, 90D, 0D", &
            & "MARKER/21, PART=2, QP=0, 0, 0.5", "MARKER/22, PART=2, QP=0, 0, 1.5", &
            & "ACCGRAV/KGRAV=-9.81"]
        character(len=*), parameter :: millimetres(*) = [character(len=70) :: &
            & "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=MILLIMETER, TIME=SECOND", &
            & "MARKER/10, PART=1, QP=0, 0, 500", "MARKER/11, PART=1, QP=0, 0, 1500", &
            & "PART/2, MASS=10, CM=20, IP=1e6, 8e5, 3e5", &
            & "MARKER/20, PART=2, QP=500, 0, 1000, REULER=0D, 90D, 0D", &
            & "MARKER/21, PART=2, QP=0, 0, 500", "MARKER/22, PART=2, QP=0, 0, 1500", &
            & "ACCGRAV/KGRAV=-9810"]
        type(job_result_type) :: si, scaled
        type(history_type) :: si_rows, scaled_rows
        real(wp) :: hinges(6, 2), moment(3), arm(3)
        integer :: h, first

        call copy_replacing("test/redundant/door.adm", scratch // "/door_mm.adm", lines, &
            & millimetres, error)
        if (allocated(error)) return
        call run_dataset("test/redundant/door.adm", "", si, si_rows, error)
        if (allocated(error)) return
        call run_dataset(scratch // "/door_mm.adm", "", scaled, scaled_rows, error)
        if (allocated(error)) return
        do h = 1, 2
            first = si_rows%layout%column("joint" // to_text(h) // "_fx")
            hinges(:, h) = si_rows%rows(first:first + 5, 1)
            first = scaled_rows%layout%column("joint" // to_text(h) // "_fx")
            call check(error, scaled_rows%rows(first:first + 5, 1), hinges(:, h), "JOINT/" &
                & // to_text(h) // "'s force and torque in millimetres against metres " &
                & // "[N, N m]", abs_tol=tol_same)
            if (allocated(error)) return
            call check(error, hinges(3, h), 0.5_wp*mass*g, "JOINT/" // to_text(h) &
                & // "'s share of the weight [N]", abs_tol=tol_same)
            if (allocated(error)) return
        end do
        call check(error, hinges(1:3, 1) + hinges(1:3, 2), [0.0_wp, 0.0_wp, mass*g], &
            & "the hinges' forces [N]", abs_tol=tol_same)
        if (allocated(error)) return
        ! about the centre of mass (0.5, 0, 1): each hinge's torque at its marker (0, 0, 0.5)
        ! and (0, 0, 1.5), and its force's moment
        moment = hinges(4:6, 1) + hinges(4:6, 2)
        do h = 1, 2
            arm = [-0.5_wp, 0.0_wp, real(2*h - 3, wp)*0.5_wp]
            moment = moment + [arm(2)*hinges(3, h) - arm(3)*hinges(2, h), &
                & arm(3)*hinges(1, h) - arm(1)*hinges(3, h), &
                & arm(1)*hinges(2, h) - arm(2)*hinges(1, h)]
        end do
        call check(error, moment, [0.0_wp, 0.0_wp, 0.0_wp], "the hinges' moments about the " &
            & // "centre of mass [N m]", abs_tol=tol_same)
    end subroutine test_units

    !> test/redundant/fourbar_chain.adm: the four-bar with a chain of 8 links hanging from its
    !> coupler, one block of 60 rows, 3 of them redundant: large enough for SuiteSparseQR's
    !> choice (40 rows or more). Its rows set aside are three of the four-bar's JOINTs' (JOINT/1
    !> to 4), none of the chain's (JOINT/51 to 58), as many as the four-bar alone sets aside
    !> (its dense choice): the sparse choice (greedy in its column order, then the swaps of a
    !> strong rank-revealing QR) may set aside other rows of the loop than the dense pivoted
    !> QR, an equally valid choice, which check_choice asserts (the rows kept independent and
    !> about as well conditioned as any, each row set aside a combination of them), with the
    !> words naming the four joints and their lines.
    subroutine test_large_block(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_result_type) :: alone, with_chain
        type(history_type) :: rows
        character(len=:), allocatable :: words
        integer :: k

        call run_dataset("test/redundant/fourbar.adm", "", alone, rows, error)
        if (allocated(error)) return
        call run_dataset("test/redundant/fourbar_chain.adm", "", with_chain, rows, error)
        if (allocated(error)) return
        words = set_aside_words(with_chain%summary%watch_lines)
        call check(error, len(words) > 0 .and. index(words, "JOINT/5") == 0, &
            & "the loop's rows set aside, none of the chain's: " // words)
        if (allocated(error)) return
        call check(error, count_rows(alone%summary%watch_lines) == 3, "the four-bar alone: " &
            & // set_aside_words(alone%summary%watch_lines))
        if (allocated(error)) return
        ! each loop's dependency spans its four joints: the words name them all, on the lines
        ! they are written on (24 to 27), as the four-bar alone's do
        do k = 1, 4
            call check(error, index(words, "JOINT/" // to_text(k) // " (line " &
                & // to_text(23 + k) // ")") > 0 .and. index(set_aside_words( &
                & alone%summary%watch_lines), "JOINT/" // to_text(k) // " (line " &
                & // to_text(23 + k) // ")") > 0, "JOINT/" // to_text(k) // " is not named: " &
                & // words)
            if (allocated(error)) return
        end do
        ! sigma / sigma_r measured 0.81 (the dense choice's: 0.94); 0.1 catches a tenfold loss
        call check_choice("test/redundant/fourbar_chain.adm", 3, 0.1_wp, error)
    end subroutine test_large_block

    !> A train of 4 four-bars written by fourbar_train (65 rows in one block, at least
    !> sparse_schur_rows = 40: the sparse choice): 3 rows set aside per loop, 12, each a
    !> combination of the rows kept, which are independent, named in JOINTs' words with their
    !> lines; the run conserves the train's energy (check_train_run).
    subroutine test_train(error)
        type(error_type), allocatable, intent(out) :: error

        ! sigma / sigma_r of the rows kept measured 1.0, the best (0.27 without the swaps of
        ! strong rank-revealing QR: 0.5 catches that); the energy held to 3.2e-9 of the weight
        ! times the crank (1e-8 catches a tenfold loss)
        call check_train(4, 1.0_wp, 0.5_wp, 1.0e-8_wp, error)
    end subroutine test_train

    !> The same for a train of 20 four-bars, 305 rows in one block, 60 of them set aside.
    subroutine test_long_train(error)
        type(error_type), allocatable, intent(out) :: error

        ! sigma / sigma_r of the rows kept measured 1.0, as the dense choice's (0.064 without the
        ! swaps of strong rank-revealing QR: the greedy order alone keeps a set 16 times worse
        ! conditioned; 0.5 catches that); the energy held to 8.3e-10 of the weight times the
        ! crank (4e-9 catches a tenfold loss)
        call check_train(20, 0.25_wp, 0.5_wp, 4.0e-9_wp, error)
    end subroutine test_long_train

    !> A train of loops four-bars (fourbar_train) run for duration s: its choice (check_choice,
    !> 3 rows per loop set aside, JOINT statements named with the lines fourbar_train wrote them
    !> on) and its energy. One degree of freedom, the cranks' angle theta (all parallel, the
    !> couplers translate): I theta'' = -dV/dtheta with I = (loops + 1) (I_c + m_c L^2/4) +
    !> loops m_k L^2 and V = ((loops + 1) m_c L/2 + loops m_k L) g sin(theta): the energy
    !> I theta'^2/2 + V(theta) held at every output row (theta from the first crank's CM).
    subroutine check_train(loops, duration, least_ratio, tol_energy, error)
        integer, intent(in) :: loops
        !> duration [s]; least_ratio: check_choice's; tol_energy: the energy within this of its
        !> start, relative to the train's weight times the crank (m g L, some 15 J per loop)
        real(wp), intent(in) :: duration, least_ratio, tol_energy
        type(error_type), allocatable, intent(out) :: error
        !> Crank and coupler masses [kg], crank length [m], crank moment about its CM [kg m^2]
        !> (fourbar.adm's)
        real(wp), parameter :: crank_mass = 1.0_wp, coupler_mass = 2.0_wp, length = 1.0_wp, &
            & crank_moment = 0.09_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        character(len=:), allocatable :: path
        integer, allocatable :: joint_lines(:, :)
        real(wp) :: inertia, weight, x, y, theta, rate, energy0
        integer :: k

        call fourbar_train(loops, duration, path, joint_lines)
        call check_choice(path, 3*loops, least_ratio, error, joint_lines)
        if (allocated(error)) return
        call run_dataset(path, "", result, rows, error)
        if (allocated(error)) return
        call check(error, index(result%summary%watch_lines, "warning: redundant equations " &
            & // "set aside") > 0 .and. index(result%summary%watch_lines, "UCON/") == 0, &
            & "the summary: " // result%summary%watch_lines)
        if (allocated(error)) return
        inertia = (loops + 1)*(crank_moment + crank_mass*(0.5_wp*length)**2) &
            & + loops*coupler_mass*length**2
        weight = ((loops + 1)*crank_mass*0.5_wp*length + loops*coupler_mass*length)*g
        call check(error, rows%count >= 10, "output rows: " // to_text(rows%count))
        if (allocated(error)) return
        associate (layout => rows%layout)
            do k = 1, rows%count
                x = rows%rows(layout%column("X_100"), k)
                y = rows%rows(layout%column("Y_100"), k)
                theta = atan2(y, x)
                rate = (x*rows%rows(layout%column("Ydot_100"), k) &
                    & - y*rows%rows(layout%column("Xdot_100"), k))/(x**2 + y**2)
                if (k == 1) energy0 = 0.5_wp*inertia*rate**2 + weight*sin(theta)
                call check(error, 0.5_wp*inertia*rate**2 + weight*sin(theta), energy0, &
                    & "the train's energy at t = " // to_text(rows%rows(1, k)) // " s [J]", &
                    & abs_tol=tol_energy*weight)
                if (allocated(error)) return
            end do
            ! it moved: the cranks fell from -30 degrees
            call check(error, abs(theta + pi/6.0_wp) > 0.05_wp, "the cranks did not move: " &
                & // to_text(theta))
        end associate
    end subroutine check_train

    !> The dataset's choice at its start (as a run makes it): expected rows set aside; the rows
    !> kept independent and each row set aside a combination of them, in C's rows scaled to
    !> unit length (the choice's own metric differs by the mass matrix: independence does
    !> not); the words name a JOINT statement for every row set aside, with its line (when
    !> joint_lines, ids and lines, is given, the line it was written on) and no UCON id; the
    !> multipliers reported there the least-norm split of the same force.
    subroutine check_choice(path, expected, least_ratio, error, joint_lines)
        character(len=*), intent(in) :: path
        integer, intent(in) :: expected
        !> The rows kept independent: their smallest singular value sigma at least this
        !> fraction of sigma_r, the r-th of all the rows (r kept): no r of them do better
        !> (interlacing), and rows kept that repeat others would have it at rounding, 1e-15
        real(wp), intent(in) :: least_ratio
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: joint_lines(:, :)
        !> A row set aside: its least-squares residual on the rows kept at most this (rounding
        !> of unit rows of some 300 coordinates: measured 2.3e-15 to 3.8e-13 on the trains; a
        !> row not repeated leaves at least sigma above, 1e-3 or more). The Gram matrix's
        !> eigenvalues: those of the dependencies are its rounding (nc eps, some 1e-13), the
        !> least of the others sigma_r^2 (measured 6.3e-4 on 20 loops)
        real(wp), parameter :: tol_residual = 1.0e-11_wp, tol_gram = 1.0e-10_wp
        !> The split's force against C^T lambda's, relative (rounding: measured 5.7e-16 to
        !> 7.8e-16), and its weighted multipliers' cosine with a dependency (measured 2.9e-16
        !> at most): each catches a tenfold loss
        real(wp), parameter :: tol_force = 5.0e-15_wp, tol_null = 2.0e-15_wp
        type(job_type) :: job
        type(problem_type), target :: problem
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:), kept(:, :), row(:), x(:), all_rows(:, :), &
            & gram(:, :), values(:), vectors(:, :), c_rows(:, :), lambda(:), split(:), &
            & weights(:), force(:), null(:), coefficients(:)
        real(wp) :: part_mass(6, 6), solved(6, 1)
        integer :: pivots(6), p
        character(len=:), allocatable :: report, name
        integer, allocatable :: kept_rows(:)
        real(wp) :: smallest, residual
        integer :: k, i, rank, nc, n, s, line

        call load_job(path, job, error)
        if (allocated(error)) return
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        associate (eq => problem%eq)
            nc = eq%nc
            n = size(q0)
            call check(error, eq%redundancy%set_aside == expected, path // ": " &
                & // to_text(eq%redundancy%set_aside) // " rows set aside; expected " &
                & // to_text(expected))
            if (allocated(error)) return
            kept_rows = pack([(k, k = 1, nc)], eq%redundancy%active)
            allocate(all_rows(n, nc), row(n), x(size(kept_rows)), values(nc), &
                & vectors(nc, nc))
            allocate(c_rows(n, nc))
            do k = 1, nc
                call eq%c%fill_row(k, row)
                c_rows(:, k) = row
                all_rows(:, k) = row/norm2(row)
            end do
            kept = all_rows(:, kept_rows)
            ! the rank of all the rows, from the eigenvalues of their Gram matrix (ascending)
            gram = matmul(transpose(all_rows), all_rows)
            call symmetric_eigen(gram, values, vectors, error)
            if (allocated(error)) return
            call check(error, count(values > tol_gram) == nc - expected, path // ": the rows' " &
                & // "rank is " // to_text(count(values > tol_gram)) // " of " // to_text(nc) &
                & // ", not " // to_text(nc - expected))
            if (allocated(error)) return
            smallest = smallest_singular_value(kept, error)
            if (allocated(error)) return
            call check(error, smallest >= least_ratio*sqrt(values(expected + 1)), path &
                & // ": the rows kept are not independent: their smallest singular value " &
                & // to_text(smallest) // ", all rows' r-th " // to_text(sqrt(values(expected &
                & + 1))))
            if (allocated(error)) return
            do k = 1, nc
                if (eq%redundancy%active(k)) cycle
                call eq%c%fill_row(k, row)
                row = row/norm2(row)
                call minimum_norm_solve(kept, row, 1.0e-8_wp, x, rank, error)
                if (allocated(error)) return
                residual = norm2(matmul(kept, x) - row)
                call check(error, residual <= tol_residual, path // ": row " // to_text(k) &
                    & // " set aside is not a combination of those kept: residual " &
                    & // to_text(residual))
                if (allocated(error)) return
                s = problem%model%ucons(k)%statement
                name = problem%model%statement_name(s)
                call check(error, problem%model%statements(s)%kind == statement_joint .and. &
                    & index(problem%set_aside_text, name) > 0 .and. index(name, "(line ") > 0, &
                    & path // ": " // name // " is not named: " // problem%set_aside_text)
                if (allocated(error)) return
                if (present(joint_lines)) then
                    line = joint_lines(2, findloc(joint_lines(1, :), &
                        & problem%model%statements(s)%id, dim=1))
                    call check(error, name == "JOINT/" // to_text(problem%model%statements(s)%id) &
                        & // " (line " // to_text(line) // ")", path // ": " // name &
                        & // ", written on line " // to_text(line))
                    if (allocated(error)) return
                end if
            end do
            call check(error, index(problem%set_aside_text, "UCON/") == 0, path // ": " &
                & // problem%set_aside_text)
            if (allocated(error)) return
            ! the multipliers reported (the split of least norm): multipliers on the rows kept,
            ! split over all the rows; the same force C^T lambda, and mu = w o lambda (w_k =
            ! sqrt(c_k M^-1 c_k^T), the choice's metric) orthogonal to each dependency e_k - x
            ! (x: dependency's coefficients of the row set aside k), which span the null space
            ! of the unit columns: least norm (the multipliers unchanged, zero on the rows set
            ! aside, give the same force and fail it by O(1))
            allocate(lambda(nc), weights(nc), coefficients(nc))
            lambda = 0.0_wp
            do k = 1, nc
                if (eq%redundancy%active(k)) lambda(k) = sin(real(k, wp))
            end do
            force = matmul(c_rows, lambda)
            split = lambda
            call eq%redundancy%multipliers(eq%c, eq%mass, eq%blocks, split, error)
            if (allocated(error)) return
            call check(error, norm2(matmul(c_rows, split) - force) <= tol_force &
                & *norm2(force), path // ": the split's force differs from C^T lambda's by " &
                & // to_text(norm2(matmul(c_rows, split) - force)))
            if (allocated(error)) return
            weights = 0.0_wp
            do p = 1, n/6
                part_mass = eq%mass(:, :, p)
                call factor_dense(part_mass, pivots, error)
                if (allocated(error)) return
                do k = 1, nc
                    solved(:, 1) = c_rows(6*p - 5:6*p, k)
                    call solve_factored(part_mass, pivots, solved, error)
                    if (allocated(error)) return
                    weights(k) = weights(k) + dot_product(c_rows(6*p - 5:6*p, k), solved(:, 1))
                end do
            end do
            weights = sqrt(weights)
            do k = 1, nc
                if (eq%redundancy%active(k)) cycle
                call eq%redundancy%dependency(k, eq%c, eq%mass, eq%blocks, coefficients, error)
                if (allocated(error)) return
                null = -coefficients
                null(k) = 1.0_wp
                call check(error, abs(dot_product(null, weights*split)) <= tol_null &
                    & *norm2(null)*norm2(weights*split), path // ": the split is not of least " &
                    & // "norm: row " // to_text(k))
                if (allocated(error)) return
            end do
        end associate
        call problem%release()
    end subroutine check_choice

    !> A dataset (in scratch) of a train of loops four-bars, fourbar.adm's repeated along X:
    !> loops + 1 cranks of 1 m (1 kg, CM at mid-length, 0.09 kg m^2 about Z; PART/100 + i)
    !> hinged to ground at X = 2 i by JOINT/100 + i, at -30 degrees, and loops couplers (2 kg;
    !> PART/200 + i) joining the tips of cranks i - 1 and i (JOINT/200 + i and JOINT/300 + i);
    !> gravity along -Y, run for duration s by IDA at ERROR = 1e-10, 10 output steps. 3 loops +
    !> 1 REVOLUTEs hold 2 loops + 1 parts: 15 loops + 5 rows, rank 12 loops + 5 (one degree of
    !> freedom), so 3 per loop repeat others. joint_lines: each JOINT's id and line.
    subroutine fourbar_train(loops, duration, path, joint_lines)
        integer, intent(in) :: loops
        real(wp), intent(in) :: duration
        character(len=:), allocatable, intent(out) :: path
        integer, allocatable, intent(out) :: joint_lines(:, :)
        character(len=*), parameter :: c30 = "0.8660254037844386", s30 = "-0.5"
        integer :: unit, i, line, joint

        call execute_command_line("mkdir -p " // scratch)
        path = scratch // "/fourbar_train_" // to_text(loops) // ".adm"
        allocate(joint_lines(2, 3*loops + 1))
        open(newunit=unit, file=path, status="replace", action="write")
        line = 0
        joint = 0
        call put("train of " // to_text(loops) // " four-bars (test_redundancy.f90)")
        call put("UNITS/SYSTEM=SI")
        call put("PART/1, GROUND")
        do i = 0, loops
            call put("MARKER/" // to_text(1000 + i) // ", PART=1, QP=" // to_text(2*i) &
                & // ", 0, 0")
        end do
        do i = 0, loops
            call put("PART/" // to_text(100 + i) // ", MASS=1, CM=" // to_text(10000 + 10*i) &
                & // ", IP=0.045, 0.09, 0.045")
            call put("MARKER/" // to_text(10000 + 10*i) // ", PART=" // to_text(100 + i) &
                & // ", QP=" // to_text(2*i) // ".4330127018922193, -0.25, 0, " &
                & // "REULER=0D, 90D, 0D")
            call put("MARKER/" // to_text(10001 + 10*i) // ", PART=" // to_text(100 + i) &
                & // ", QP=" // to_text(2*i) // ", 0, 0")
            call put("MARKER/" // to_text(10002 + 10*i) // ", PART=" // to_text(100 + i) &
                & // ", QP=" // to_text(2*i) // c30(2:) // ", " // s30 // ", 0")
        end do
        do i = 1, loops
            call put("PART/" // to_text(200 + i) // ", MASS=2, CM=" // to_text(20000 + 10*i) &
                & // ", IP=0.1, 0.1, 0.1")
            call put("MARKER/" // to_text(20000 + 10*i) // ", PART=" // to_text(200 + i) &
                & // ", QP=" // to_text(2*i - 1) // c30(2:) // ", " // s30 // ", 0")
            call put("MARKER/" // to_text(20001 + 10*i) // ", PART=" // to_text(200 + i) &
                & // ", QP=" // to_text(2*i - 2) // c30(2:) // ", " // s30 // ", 0")
            call put("MARKER/" // to_text(20002 + 10*i) // ", PART=" // to_text(200 + i) &
                & // ", QP=" // to_text(2*i) // c30(2:) // ", " // s30 // ", 0")
        end do
        do i = 0, loops
            call put_joint(100 + i, 10001 + 10*i, 1000 + i)
        end do
        do i = 1, loops
            call put_joint(200 + i, 20001 + 10*i, 10002 + 10*(i - 1))
            call put_joint(300 + i, 20002 + 10*i, 10002 + 10*i)
        end do
        call put("ACCGRAV/JGRAV=-9.81")
        call put("SIMULATE/DYNAMIC, END=" // to_text(duration) // ", STEPS=10")
        call put("INTEGRATOR/ERROR=1e-10")
        call put("END")
        close(unit)

    contains

        subroutine put(text)
            character(len=*), intent(in) :: text

            write(unit, '(a)') text
            line = line + 1
        end subroutine put

        subroutine put_joint(id, i_marker, j_marker)
            integer, intent(in) :: id, i_marker, j_marker

            call put("JOINT/" // to_text(id) // ", REVOLUTE, I=" // to_text(i_marker) // ", J=" &
                & // to_text(j_marker))
            joint = joint + 1
            joint_lines(:, joint) = [id, line]
        end subroutine put_joint
    end subroutine fourbar_train

    !> How many equations the summary's words say were set aside (the count of "its"
    !> equations named: their commas, "and"s and ": its" of each statement).
    integer function count_rows(summary)
        character(len=*), intent(in) :: summary
        character(len=:), allocatable :: words, part
        integer :: first, last

        words = set_aside_words(summary)
        count_rows = 0
        do
            first = index(words, ": its ")
            if (first == 0) exit
            last = index(words(first:), " repeat")
            part = words(first + 6:first + last - 2)
            count_rows = count_rows + 1 + count_of(part, ", ") + count_of(part, " and ")
            words = words(first + last:)
        end do
    end function count_rows

    !> The summary's words of the rows set aside (its warning line, "" without one).
    function set_aside_words(summary) result(words)
        character(len=*), intent(in) :: summary
        character(len=:), allocatable :: words
        integer :: first, last

        words = ""
        first = index(summary, "warning: redundant equations set aside")
        if (first == 0) return
        last = index(summary(first:), "; chosen again")
        if (last == 0) return
        words = summary(first:first + last - 2)
    end function set_aside_words

    !> Run a dataset (formulation: INTEGRATOR/FORMULATION= put in place, "" as it is) without
    !> files, its rows kept; a run that does not complete is an error.
    subroutine run_dataset(path, formulation, result, rows, error)
        character(len=*), intent(in) :: path, formulation
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job

        if (len(formulation) > 0) then
            call load_job(path, job, error, overrides=[input_override_type( &
                & "integrator%formulation", formulation)])
        else
            call load_job(path, job, error)
        end if
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed, path // ": status " &
            & // to_text(result%summary%status) // ": " // result%summary%watch_lines)
    end subroutine run_dataset

    !> Copy a text file, each line equal to one of old replaced by the new one of the same
    !> place; every old line must be found.
    subroutine copy_replacing(from, to, old, new, error)
        character(len=*), intent(in) :: from, to
        character(len=*), intent(in) :: old(:), new(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: line
        logical :: found(size(old))
        integer :: in, out, status, k

        call execute_command_line("mkdir -p " // scratch)
        found = .false.
        open(newunit=in, file=from, status="old", action="read")
        open(newunit=out, file=to, status="replace", action="write")
        do
            read(in, '(a)', iostat=status) line
            if (status /= 0) exit
            do k = 1, size(old)
                if (trim(line) /= trim(old(k))) cycle
                line = new(k)
                found(k) = .true.
            end do
            write(out, '(a)') trim(line)
        end do
        close(in)
        close(out)
        call check(error, all(found), from // ": a line to replace is missing")
    end subroutine copy_replacing

end module test_redundancy
