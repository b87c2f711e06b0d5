! SPDX-License-Identifier: MIT
!> The integrators start again where an input has a corner (docs/design.md §7): a force
!> expression's STEP on TIME at the times it switches, known in advance (stop times), and an IF
!> of a state function where it switches, located by root finding (rollcon_switch_watch); a
!> SPLINE's curve read by AKISPL of TIME at its interior points, and by CUBSPL of a state
!> function where it passes them. The model is a free ball pushed along ground X, whose motion
!> is a closed form (or, pushed by a force of its position, keeps an energy integral).
module test_corners
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : run_summary_type, history_type, status_completed
    use rollcon_output_layout, only : coord_x, coord_xdot
    use rollcon_switch_watch, only : has_state_switches
    use rollcon_force, only : force_corners
    use rollcon_problem, only : problem_type
    use rollcon_spline, only : spline_type, new_spline, spline_derivatives, method_akima, &
        & method_cubic
    use restart_models, only : build_dataset, run_analysed
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_corners

    character(len=*), parameter :: nl = new_line("a")
    !> The ball's distance from the closed form [m] at ERROR = 1e-10 over 3 s: the STEP
    !> measured 2.6e-9 m started again at both corners (1.2e-7 m when IDA only stopped at them
    !> and went on on its history); the IF 2.0e-9 m. 1e-8 m, so that the STEP stepped over
    !> fails by ten times
    real(wp), parameter :: tol_closed_form = 1.0e-8_wp
    !> The ball pushed by AKISPL of TIME from its closed form [m] at ERROR = 1e-10 over 3 s:
    !> measured 5.2e-9 m started again at the curve's four interior points, 1.6e-8 m going on
    !> across them (3.2e-11 and 1.2e-10 m at ERROR = 1e-12): 1e-8 m, which the knots stepped
    !> over fail, and so would a tenfold loss. A spline's corners are mild (Akima's curve has a
    !> continuous slope), and the restart's own order-1 start costs some of what it saves: the
    !> gain is threefold, not the STEP's fiftyfold
    real(wp), parameter :: tol_akispl = 1.0e-8_wp
    !> The ball pushed by CUBSPL of its X, its energy integral v^2/2 - int f dX [J/kg] at
    !> ERROR = 1e-10 over 3 s: measured 1.2e-8 started again at the five knots it passes
    !> (1.9e-8 going on across them: the cubic spline's corners, a jump of its third
    !> derivative, hardly matter; the test holds that the knots are found on the state):
    !> 3e-8, so that a tenfold loss fails
    real(wp), parameter :: tol_cubspl = 3.0e-8_wp
    !> The SPLINE both push with: its points (t [s] or X [m], F [N]), the AKISPL's without
    !> LINEAR_EXTRAPOLATE (its corners the 4 interior points), the CUBSPL's with it (all 5)
    real(wp), parameter :: knots_time(6) = [0.0_wp, 0.4_wp, 0.9_wp, 1.3_wp, 2.0_wp, 2.6_wp], &
        & forces_time(6) = [0.0_wp, 1.0_wp, -0.5_wp, 2.0_wp, 0.3_wp, 1.0_wp], &
        & knots_place(5) = [0.3_wp, 0.8_wp, 1.4_wp, 1.9_wp, 2.5_wp], &
        & forces_place(5) = [0.5_wp, -0.3_wp, 0.8_wp, 0.2_wp, 0.6_wp]

contains

    subroutine collect_corners(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("step-on-time-restarts-at-its-corners", test_step_on_time), &
            & new_unittest("if-on-the-state-restarts-where-it-switches", test_if_on_state), &
            & new_unittest("akispl-on-time-restarts-at-its-knots", test_akispl_on_time), &
            & new_unittest("cubspl-on-the-state-restarts-at-its-knots", test_cubspl_on_state)]
    end subroutine collect_corners

    !> FX = STEP(TIME, 1, 0, 1.5, 2) N on 1 kg moving at 1 m/s: its corners, 1 and 1.5 s, are
    !> the forces' corners, the integrator starts again at exactly those two, and X follows
    !> t + 2 T^2 (s^4/4 - s^5/10) with s = (t - 1)/T, T = 0.5 s, in the step, and
    !> t + 0.3 T^2 + T (t - 1.5) + (t - 1.5)^2 after it.
    subroutine test_step_on_time(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_summary_type) :: summary
        type(history_type) :: history
        real(wp), allocatable :: q0(:), u0(:), times(:)
        real(wp) :: end_time, output_step

        call build_dataset("corner-step", ball_text("STEP(TIME, 1, 0, 1.5, 2)"), problem, q0, &
            & u0, end_time, output_step, error)
        if (allocated(error)) return
        times = force_corners(problem%model%forces)
        call check(error, size(times) == 2 .and. .not. has_state_switches(problem%model%forces), &
            & to_text(size(times)) // " corners, expected 1 and 1.5 s on TIME alone")
        if (allocated(error)) return
        call check(error, times, [1.0_wp, 1.5_wp], "the STEP's corners [s]", abs_tol=0.0_wp)
        if (allocated(error)) return
        call run_analysed("corner-step", ball_text("STEP(TIME, 1, 0, 1.5, 2)"), summary, &
            & history, error)
        if (allocated(error)) return
        call check_run(summary, history, 2, step_position, error)
    end subroutine test_step_on_time

    !> FX = IF(DX(21) - 0.5: 0, 0, 2) N: a switch on the state, watched; the ball passes
    !> X = 0.5 m at t = 0.5 s, where the integrator starts again once, and X follows t, then
    !> t + (t - 0.5)^2.
    subroutine test_if_on_state(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_summary_type) :: summary
        type(history_type) :: history
        real(wp), allocatable :: q0(:), u0(:)
        real(wp) :: end_time, output_step

        call build_dataset("corner-if", ball_text("IF(DX(21) - 0.5: 0, 0, 2)"), problem, q0, &
            & u0, end_time, output_step, error)
        if (allocated(error)) return
        call check(error, size(force_corners(problem%model%forces)) == 0 .and. &
            & has_state_switches(problem%model%forces), "the IF on DX should be watched, " &
            & // "not a time")
        if (allocated(error)) return
        call run_analysed("corner-if", ball_text("IF(DX(21) - 0.5: 0, 0, 2)"), summary, &
            & history, error)
        if (allocated(error)) return
        call check_run(summary, history, 1, if_position, error)
    end subroutine test_if_on_state

    !> FX = AKISPL(TIME, 0, 1) N of SPLINE/1 through (knots_time, forces_time): its corners are
    !> the curve's interior points, the integrator starts again at exactly those four, and X
    !> follows t + int_0^t (t - s) f(s) ds (Gauss-Legendre of 3 points on each interval between
    !> the knots, exact for the quartic integrand).
    subroutine test_akispl_on_time(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_summary_type) :: summary
        type(history_type) :: history
        real(wp), allocatable :: q0(:), u0(:), times(:), t(:), x(:)
        real(wp) :: end_time, output_step, worst
        character(len=:), allocatable :: text
        type(spline_type) :: spline
        integer :: i

        text = ball_text("AKISPL(TIME, 0, 1)", spline_statement(knots_time, forces_time, .false.))
        call build_dataset("corner-akispl", text, problem, q0, u0, end_time, output_step, error)
        if (allocated(error)) return
        times = force_corners(problem%model%forces)
        call check(error, size(times) == 4 .and. .not. has_state_switches(problem%model%forces), &
            & to_text(size(times)) // " corners, expected the 4 interior knots on TIME alone")
        if (allocated(error)) return
        call check(error, times, knots_time(2:5), "the AKISPL's corners [s]", abs_tol=0.0_wp)
        if (allocated(error)) return
        call run_analysed("corner-akispl", text, summary, history, error)
        if (allocated(error)) return
        call check_restarts(summary, 4, error)
        if (allocated(error)) return
        spline = curve(knots_time, forces_time, .false., error)
        if (allocated(error)) return
        t = history%column(1)
        x = history%part_values(1, coord_x)
        worst = 0.0_wp
        do i = 1, size(t)
            worst = max(worst, abs(x(i) - t(i) - pushed_distance(spline, method_akima, t(i))))
        end do
        call check(error, worst <= tol_akispl, "largest distance from the closed form " &
            & // to_text(worst) // " m")
    end subroutine test_akispl_on_time

    !> FX = CUBSPL(DX(21), 0, 1) N of SPLINE/1 through (knots_place, forces_place) with
    !> LINEAR_EXTRAPOLATE: a switch on the state, watched; the ball passes all five points
    !> (the corners of a curve that goes on along its end tangents), where the integrator starts
    !> again, and keeps its energy integral v^2/2 - int_0^X f (a unit mass; the integral by
    !> Gauss-Legendre of 2 points between the knots, exact for the cubic pieces).
    subroutine test_cubspl_on_state(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_summary_type) :: summary
        type(history_type) :: history
        real(wp), allocatable :: q0(:), u0(:), x(:), v(:)
        real(wp) :: end_time, output_step, worst
        character(len=:), allocatable :: text
        type(spline_type) :: spline
        integer :: i

        text = ball_text("CUBSPL(DX(21), 0, 1)", spline_statement(knots_place, forces_place, &
            & .true.))
        call build_dataset("corner-cubspl", text, problem, q0, u0, end_time, output_step, error)
        if (allocated(error)) return
        call check(error, size(force_corners(problem%model%forces)) == 0 .and. &
            & has_state_switches(problem%model%forces), "the CUBSPL of DX should be watched, " &
            & // "not a time")
        if (allocated(error)) return
        call run_analysed("corner-cubspl", text, summary, history, error)
        if (allocated(error)) return
        x = history%part_values(1, coord_x)
        call check(error, x(size(x)) > knots_place(5), "the ball ends at X = " &
            & // to_text(x(size(x))) // " m, short of the last knot")
        if (allocated(error)) return
        call check_restarts(summary, 5, error)
        if (allocated(error)) return
        spline = curve(knots_place, forces_place, .true., error)
        if (allocated(error)) return
        v = history%part_values(1, coord_xdot)
        worst = 0.0_wp
        do i = 1, size(x)
            worst = max(worst, abs(0.5_wp*v(i)**2 - work_done(spline, x(i)) - 0.5_wp))
        end do
        call check(error, worst <= tol_cubspl, "largest change of v^2/2 - int f dX " &
            & // to_text(worst) // " J/kg")
    end subroutine test_cubspl_on_state

    !> The run completed and started the integrator again restarts times at corners.
    subroutine check_restarts(summary, restarts, error)
        type(run_summary_type), intent(in) :: summary
        integer, intent(in) :: restarts
        type(error_type), allocatable, intent(out) :: error

        call check(error, summary%status == status_completed .and. summary%corner_restarts &
            & == restarts, "status " // to_text(summary%status) // ", " &
            & // to_text(summary%corner_restarts) // " restarts at corners, expected " &
            & // to_text(restarts))
    end subroutine check_restarts

    !> The curve through (x, y), as the dataset's SPLINE/1 has it.
    function curve(x, y, linear, error) result(spline)
        real(wp), intent(in) :: x(:), y(:)
        logical, intent(in) :: linear
        type(error_type), allocatable, intent(out) :: error
        type(spline_type) :: spline
        character(len=:), allocatable :: problem

        call new_spline(1, x, y, spline, problem, linear_extrapolate=linear)
        call check(error, problem == "", "the test's curve: " // problem)
    end function curve

    !> int_0^t (t - s) f(s) ds [m] for the Akima curve f [N on 1 kg] of TIME: Gauss-Legendre of
    !> 3 points on each stretch between 0, the curve's points and t (a quartic there: exact).
    function pushed_distance(spline, method, t) result(distance)
        type(spline_type), intent(in) :: spline
        integer, intent(in) :: method
        real(wp), intent(in) :: t
        real(wp) :: distance
        real(wp), parameter :: nodes(3) = [-sqrt(0.6_wp), 0.0_wp, sqrt(0.6_wp)], &
            & gauss_weights(3) = [5.0_wp, 8.0_wp, 5.0_wp]/9.0_wp
        real(wp), allocatable :: ends(:)
        real(wp) :: f(0:3), s
        integer :: k, j

        ends = [0.0_wp, pack(spline%x, spline%x > 0.0_wp .and. spline%x < t), t]
        distance = 0.0_wp
        do k = 1, size(ends) - 1
            associate (middle => 0.5_wp*(ends(k) + ends(k + 1)), half => 0.5_wp*(ends(k + 1) &
                & - ends(k)))
                do j = 1, size(nodes)
                    s = middle + half*nodes(j)
                    f = spline_derivatives(spline, method, s)
                    distance = distance + half*gauss_weights(j)*(t - s)*f(0)
                end do
            end associate
        end do
    end function pushed_distance

    !> int_0^x f(X) dX [J per kg] for the cubic spline f [N on 1 kg] of X: Gauss-Legendre of 2
    !> points on each stretch between 0, the curve's points and x (a cubic, or the end
    !> tangents' line: exact).
    function work_done(spline, x) result(work)
        type(spline_type), intent(in) :: spline
        real(wp), intent(in) :: x
        real(wp) :: work
        real(wp), parameter :: nodes(2) = [-1.0_wp, 1.0_wp]/sqrt(3.0_wp)
        real(wp), allocatable :: ends(:)
        real(wp) :: f(0:3)
        integer :: k, j

        ends = [0.0_wp, pack(spline%x, spline%x > 0.0_wp .and. spline%x < x), x]
        work = 0.0_wp
        do k = 1, size(ends) - 1
            associate (middle => 0.5_wp*(ends(k) + ends(k + 1)), half => 0.5_wp*(ends(k + 1) &
                & - ends(k)))
                do j = 1, size(nodes)
                    f = spline_derivatives(spline, method_cubic, middle + half*nodes(j))
                    work = work + half*f(0)
                end do
            end associate
        end do
    end function work_done

    !> SPLINE/1 through (x, y), with LINEAR_EXTRAPOLATE when linear.
    function spline_statement(x, y, linear) result(text)
        real(wp), intent(in) :: x(:), y(:)
        logical, intent(in) :: linear
        character(len=:), allocatable :: text
        integer :: k

        text = "SPLINE/1, X="
        do k = 1, size(x)
            if (k > 1) text = text // ", "
            text = text // to_text(x(k))
        end do
        text = text // ", Y="
        do k = 1, size(y)
            if (k > 1) text = text // ", "
            text = text // to_text(y(k))
        end do
        if (linear) text = text // ", LINEAR_EXTRAPOLATE"
        text = text // nl
    end function spline_statement

    !> The run completed, started the integrator again restarts times at corners, and its X
    !> is the closed form's within tol_closed_form on every row.
    subroutine check_run(summary, history, restarts, position, error)
        type(run_summary_type), intent(in) :: summary
        type(history_type), intent(in) :: history
        integer, intent(in) :: restarts
        interface
            pure real(wp) function position(t)
                import :: wp
                real(wp), intent(in) :: t
            end function position
        end interface
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: t(:), x(:)
        real(wp) :: worst
        integer :: i

        call check(error, summary%status == status_completed .and. summary%corner_restarts &
            & == restarts, "status " // to_text(summary%status) // ", " &
            & // to_text(summary%corner_restarts) // " restarts at corners, expected " &
            & // to_text(restarts))
        if (allocated(error)) return
        t = history%column(1)
        x = history%part_values(1, coord_x)
        worst = 0.0_wp
        do i = 1, size(t)
            worst = max(worst, abs(x(i) - position(t(i))))
        end do
        call check(error, worst <= tol_closed_form, "largest distance from the closed form " &
            & // to_text(worst) // " m")
    end subroutine check_run

    !> X [m] of the ball pushed by STEP(TIME, 1, 0, 1.5, 2) N at time t [s].
    pure real(wp) function step_position(t) result(x)
        real(wp), intent(in) :: t
        real(wp), parameter :: duration = 0.5_wp
        real(wp) :: s

        if (t <= 1.0_wp) then
            x = t
        else if (t <= 1.5_wp) then
            s = (t - 1.0_wp)/duration
            x = t + 2.0_wp*duration**2*(s**4/4.0_wp - s**5/10.0_wp)
        else
            x = t + 0.3_wp*duration**2 + duration*(t - 1.5_wp) + (t - 1.5_wp)**2
        end if
    end function step_position

    !> X [m] of the ball pushed by IF(DX(21) - 0.5: 0, 0, 2) N at time t [s].
    pure real(wp) function if_position(t) result(x)
        real(wp), intent(in) :: t

        x = t
        if (t > 0.5_wp) x = t + (t - 0.5_wp)**2
    end function if_position

    !> A ball of 1 kg (no gravity, no UCON) at the origin moving at 1 m/s along ground X,
    !> pushed along X by the force expression fx [N], 3 s at ERROR = 1e-10 on IDA.
    function ball_text(fx, more) result(text)
        character(len=*), intent(in) :: fx
        !> Further statements (a SPLINE), each line ending in a new line
        character(len=*), intent(in), optional :: more
        character(len=:), allocatable :: text

        text = "a free ball pushed along X" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/1, PART=1" // nl &
            & // "PART/2, MASS=1, CM=21, IP=0.4, 0.4, 0.4, QG=0, 0, 0, VX=1" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl // "ACCGRAV/KGRAV=0" // nl &
            & // "VFORCE/1, I=21, JFLOAT=1, RM=1, FX=" // fx // ", FY=0, FZ=0" // nl &
            & // "SIMULATE/DYNAMIC, END=3, STEPS=300" // nl &
            & // "INTEGRATOR/FORMULATION=IDA, ERROR=1E-10" // nl
        if (present(more)) text = text // more
        text = text // "END"
    end function ball_text

end module test_corners
