! SPDX-License-Identifier: MIT
!> The integrator interface a run drives: advance to a time (never past a stop time), start
!> again after the state was changed from outside (a re-basing) or at an input's corner,
!> counters, and the flag and message of a failure. CVODE (rollcon_cvode) and IDA (rollcon_ida)
!> extend it, each set up on the form of system it takes (its own `start`: an ODE, a DAE); a run
!> sets one up through rollcon_integrator_choice and never asks which one it has.
module rollcon_integrator
    use, intrinsic :: iso_c_binding, only : c_int
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_dynamic_system, only : dynamic_system_type
    implicit none
    private

    public :: integrator_type, integrator_statistics_type, solver_failure, chunk_watch_type, &
        & chunk_steps_default

    !> What an integrator did since it was set up or last started again
    type :: integrator_statistics_type
        !> Internal steps, evaluations of the right-hand side or residual (their own and those
        !> of difference-quotient Jacobians), Newton-matrix evaluations, error-test failures,
        !> event-function evaluations
        integer :: steps = 0, functions = 0, jacobians = 0, failures = 0, roots = 0
        !> The Newton matrix was solved by SUNDIALS' sparse KLU (linear_solver 'sparse', or
        !> 'auto' on a large sparse matrix), not the dense LU
        logical :: sparse = .false.
    contains
        procedure :: add => statistics_add
    end type integrator_statistics_type

    !> Internal steps an integrator takes in one call to SUNDIALS when a watch listens: the
    !> max_steps budget of an output interval is spent in chunks of this many, the watch told
    !> between them (docs/design.md, "A long output interval")
    integer, parameter :: chunk_steps_default = 500

    !> What a run does between two chunks of an integrator's steps on a long way to the next
    !> output time: a progress line, a warning when the steps grind
    type, abstract :: chunk_watch_type
    contains
        procedure(between_chunks_interface), deferred :: between_chunks
    end type chunk_watch_type

    type, abstract :: integrator_type
        !> The flag of the last failed step (0 when none failed)
        integer :: failed_flag = 0
        !> Internal steps allowed towards one output time (run_settings_type%max_steps)
        integer :: max_steps = 500000
        !> Told between chunks of chunk_steps_default steps; none: the whole budget in one call
        class(chunk_watch_type), pointer :: watch => null()
        !> The time the integrator reached last [s]
        real(wp) :: t_now = 0.0_wp
        !> After a root return: non-zero for every event function that fired (its direction)
        integer(c_int), allocatable :: fired(:)
        !> The work [J] each of the system's dissipated powers (dynamic_system_type powers) did
        !> from the start to t_now, integrated with the state over the integrator's own steps
        !> (docs/design.md §7, "Dissipated work"); not allocated when the integrator does not
        !> integrate them (the system has none, or the integrator cannot)
        real(wp), allocatable :: work(:)
        !> The time the work is integrated to (the integrator's own tn, the end of its last
        !> step) [s], the work there [J], the powers' evaluations since the start or restart;
        !> the scratch of one step's integral and of one node's powers (sized by their first
        !> use, so that a step allocates nothing)
        real(wp) :: t_work = 0.0_wp
        real(wp), allocatable :: work_end(:)
        integer :: power_evaluations = 0
        real(wp), allocatable, private :: work_piece(:), work_power(:)
    contains
        procedure(restart_interface), deferred :: restart
        procedure(advance_interface), deferred :: advance
        procedure(statistics_interface), deferred :: statistics
        procedure(destroy_interface), deferred :: destroy
        procedure(step_end_interface), deferred :: step_end
        procedure(powers_at_interface), deferred :: powers_at
        procedure :: integrate_work
    end type integrator_type

    !> The dissipated work's rule on each step: Gauss-Legendre's two points on [0, 1] and their
    !> weights, exact on cubics; the power along the integrator's interpolant is smooth within
    !> a step (its switches are located roots, where the integrator starts again). Its error is
    !> far below the state's: three points change W by at most 2.9e-11 J (a rolling coin with
    !> rolling resistance, 0.03 J dissipated) and 9e-12 J (data/euler_disk.nml, 0.05 J), where
    !> |E + W - E0| is 1.6e-7 J and 1.3e-8 J (docs/design.md §7, "Dissipated work")
    real(wp), parameter :: gauss_nodes(2) = [0.5_wp - sqrt(3.0_wp)/6.0_wp, &
        & 0.5_wp + sqrt(3.0_wp)/6.0_wp]
    real(wp), parameter :: gauss_weights(2) = [0.5_wp, 0.5_wp]

    abstract interface
        !> A chunk of steps [t_start, t_reached] [s] towards the output time t_out [s] ended
        !> short of it: steps internal steps taken in it, failures of them rejected (by the
        !> error test or for want of the corrector's convergence).
        subroutine between_chunks_interface(self, t_start, t_reached, t_out, steps, failures)
            import :: chunk_watch_type, wp
            class(chunk_watch_type), intent(inout) :: self
            real(wp), intent(in) :: t_start, t_reached, t_out
            integer, intent(in) :: steps, failures
        end subroutine between_chunks_interface

        !> Start again from (t0, y0, yp0) with everything else as set up and no history: the
        !> state was changed from outside (its coordinates re-based), or an input has a corner
        !> at t0 (careful false: the integrator begins as it would at a start).
        subroutine restart_interface(self, t0, y0, yp0, error, careful)
            import :: integrator_type, wp, error_type
            class(integrator_type), intent(inout) :: self
            real(wp), intent(in) :: t0, y0(:), yp0(:)
            type(error_type), allocatable, intent(out) :: error
            !> Begin carefully, as after a re-basing (default true; the integrator's own way)
            logical, intent(in), optional :: careful
        end subroutine restart_interface

        !> Integrate towards t_out, never past t_stop. On return y (and yp for a DAE) hold the
        !> state at t_reached; root is the number of the first event function that fired (0
        !> when none did, fired() says which did).
        subroutine advance_interface(self, t_out, t_stop, t_reached, y, yp, root, error)
            import :: integrator_type, wp, error_type
            class(integrator_type), intent(inout) :: self
            real(wp), intent(in) :: t_out, t_stop
            real(wp), intent(out) :: t_reached
            real(wp), intent(inout) :: y(:), yp(:)
            integer, intent(out) :: root
            type(error_type), allocatable, intent(out) :: error
        end subroutine advance_interface

        !> Counters since set-up or the last restart.
        function statistics_interface(self) result(counts)
            import :: integrator_type, integrator_statistics_type
            class(integrator_type), intent(in) :: self
            type(integrator_statistics_type) :: counts
        end function statistics_interface

        !> Free what start made; the integrator can be started again.
        subroutine destroy_interface(self)
            import :: integrator_type
            class(integrator_type), intent(inout) :: self
        end subroutine destroy_interface

        !> The end of the integrator's last step, its own tn [s] (an error if it cannot say).
        subroutine step_end_interface(self, t_end, error)
            import :: integrator_type, wp, error_type
            class(integrator_type), intent(inout) :: self
            real(wp), intent(out) :: t_end
            type(error_type), allocatable, intent(out) :: error
        end subroutine step_end_interface

        !> The system's dissipated powers [W] (power_count of them) at time [s] within the last
        !> step, on the state the integrator interpolates there; an error names a failure.
        subroutine powers_at_interface(self, time, power, error)
            import :: integrator_type, wp, error_type
            class(integrator_type), intent(inout) :: self
            real(wp), intent(in) :: time
            real(wp), intent(out) :: power(:)
            type(error_type), allocatable, intent(out) :: error
        end subroutine powers_at_interface
    end interface

contains

    !> After a return of the integrator at t_returned [s]: the dissipated work integrated over
    !> the step it took, from t_work to its end (step_end), and the work at t_returned (work):
    !> the work at the step's end less the integral from t_returned to it (a row or a root
    !> within the step). Each integral is Gauss-Legendre's rule (gauss_nodes) on the powers at
    !> the interpolated state (powers_at). An error is powers_at's or step_end's.
    subroutine integrate_work(self, t_returned, error)
        class(integrator_type), intent(inout) :: self
        real(wp), intent(in) :: t_returned
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: t_current

        if (.not. allocated(self%work_piece)) then
            allocate(self%work_piece(size(self%work)), self%work_power(size(self%work)))
        else if (size(self%work_piece) /= size(self%work)) then
            deallocate(self%work_piece, self%work_power)
            allocate(self%work_piece(size(self%work)), self%work_power(size(self%work)))
        end if
        call self%step_end(t_current, error)
        if (allocated(error)) return
        if (t_current > self%t_work) then
            call step_work(self, self%t_work, t_current, error)
            if (allocated(error)) return
            self%work_end = self%work_end + self%work_piece
            self%t_work = t_current
        end if
        self%work = self%work_end
        if (t_returned < self%t_work) then
            call step_work(self, t_returned, self%t_work, error)
            if (allocated(error)) return
            self%work = self%work_end - self%work_piece
        end if
    end subroutine integrate_work

    !> work_piece: the integral [J] of each dissipated power over [t_from, t_to] [s], within
    !> the integrator's last step (integrate_work).
    subroutine step_work(self, t_from, t_to, error)
        class(integrator_type), intent(inout) :: self
        real(wp), intent(in) :: t_from, t_to
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        self%work_piece = 0.0_wp
        do k = 1, size(gauss_nodes)
            self%power_evaluations = self%power_evaluations + 1
            call self%powers_at(t_from + gauss_nodes(k)*(t_to - t_from), self%work_power, error)
            if (allocated(error)) return
            self%work_piece = self%work_piece + gauss_weights(k)*(t_to - t_from)*self%work_power
        end do
    end subroutine step_work

    !> Sum of two sets of counters (a run's segments between restarts).
    pure subroutine statistics_add(self, other)
        class(integrator_statistics_type), intent(inout) :: self
        type(integrator_statistics_type), intent(in) :: other

        self%steps = self%steps + other%steps
        self%functions = self%functions + other%functions
        self%jacobians = self%jacobians + other%jacobians
        self%failures = self%failures + other%failures
        self%roots = self%roots + other%roots
        self%sparse = self%sparse .or. other%sparse
    end subroutine statistics_add

    !> The error of a failed step: "<name> failed at t = ... s with flag F: <meaning>", or with
    !> the system's own reason when a callback kept one.
    subroutine solver_failure(error, name, time, flag, meaning, system)
        type(error_type), allocatable, intent(out) :: error
        !> "CVODE" or "IDA"
        character(len=*), intent(in) :: name
        !> Where it failed [s]
        real(wp), intent(in) :: time
        integer, intent(in) :: flag
        !> The flag's meaning, in the guide's names
        character(len=*), intent(in) :: meaning
        class(dynamic_system_type), intent(in) :: system
        character(len=:), allocatable :: reason

        reason = system%failure_text()
        if (len(reason) > 0) then
            call fatal_error(error, name // " failed at t = " // to_text(time) // " s (flag " &
                & // to_text(flag) // "): " // reason, stat_solver)
        else
            call fatal_error(error, name // " failed at t = " // to_text(time) // " s with flag " &
                & // to_text(flag) // ": " // meaning, stat_solver)
        end if
    end subroutine solver_failure

end module rollcon_integrator
