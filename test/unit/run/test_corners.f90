! SPDX-License-Identifier: MIT
!> The integrators start again where an input has a corner (docs/design.md §7): a force
!> expression's STEP on TIME at the times it switches, known in advance (stop times), and an IF
!> of a state function where it switches, located by root finding (rollcon_switch_watch). The
!> model is a free ball pushed along ground X, whose motion is a closed form.
module test_corners
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : run_summary_type, history_type, status_completed
    use rollcon_output_layout, only : coord_x
    use rollcon_switch_watch, only : has_state_switches
    use rollcon_force, only : force_corners
    use rollcon_problem, only : problem_type
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

contains

    subroutine collect_corners(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("step-on-time-restarts-at-its-corners", test_step_on_time), &
            & new_unittest("if-on-the-state-restarts-where-it-switches", test_if_on_state)]
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
    function ball_text(fx) result(text)
        character(len=*), intent(in) :: fx
        character(len=:), allocatable :: text

        text = "a free ball pushed along X" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl // "MARKER/1, PART=1" // nl &
            & // "PART/2, MASS=1, CM=21, IP=0.4, 0.4, 0.4, QG=0, 0, 0, VX=1" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl // "ACCGRAV/KGRAV=0" // nl &
            & // "VFORCE/1, I=21, JFLOAT=1, RM=1, FX=" // fx // ", FY=0, FZ=0" // nl &
            & // "SIMULATE/DYNAMIC, END=3, STEPS=300" // nl &
            & // "INTEGRATOR/FORMULATION=IDA, ERROR=1E-10" // nl // "END"
    end function ball_text

end module test_corners
