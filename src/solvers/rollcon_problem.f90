! SPDX-License-Identifier: MIT
!> What the integrators' callbacks work on: the equations, solver settings, event limits,
!> scratch arrays, and the first failure a callback met (callbacks never print or stop).
module rollcon_problem
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_equations, only : equations_type
    use rollcon_constraints, only : need_first
    implicit none
    private

    public :: problem_type, solver_settings_type, event_settings_type
    public :: formulation_cvode, formulation_ida, method_bdf, method_adams
    public :: root_theta, root_liftoff

    !> Formulations: CVODE on the ODE form, IDA on the DAE form
    integer, parameter :: formulation_cvode = 1, formulation_ida = 2
    !> CVODE's linear multistep methods
    integer, parameter :: method_bdf = 1, method_adams = 2
    !> Root function numbers: theta at its minimum, normal force at zero
    integer, parameter :: root_theta = 1, root_liftoff = 2

    !> How to integrate
    type :: solver_settings_type
        integer :: formulation = formulation_ida
        integer :: method = method_bdf
        !> Newton matrix from the UCOSUB's partials (true) or SUNDIALS' difference quotients
        logical :: analytic_jacobian = .true.
        !> Relative and absolute tolerances [-, state units]
        real(wp) :: rtol = 1.0e-8_wp, atol = 1.0e-10_wp
        !> Most internal steps per output interval
        integer :: max_steps = 500000
    end type solver_settings_type

    !> When to stop a run early
    type :: event_settings_type
        !> Part watched
        integer :: part = 1
        !> Stop when theta falls below this [rad] (disabled when negative)
        real(wp) :: theta_min = -1.0_wp
        !> Stop when the normal (ground Z) component of the constraint force turns negative
        logical :: stop_on_liftoff = .false.
    end type event_settings_type

    !> The integrators' user data
    type :: problem_type
        type(equations_type) :: eq
        type(solver_settings_type) :: settings
        type(event_settings_type) :: events
        !> Scratch: accelerations and multipliers
        real(wp), allocatable :: a(:), lambda(:)
        !> The first failure inside a callback, for the caller to report
        type(error_type), allocatable :: failure
        !> Event-function evaluations so far (the benchmark's per-part costs)
        integer :: root_evaluations = 0
    contains
        procedure :: prepare
        procedure :: ode_rhs
        procedure :: root_values
        procedure :: keep_failure
    end type problem_type

contains

    !> Size scratch arrays (once).
    subroutine prepare(self)
        class(problem_type), intent(inout) :: self

        if (allocated(self%a)) deallocate(self%a)
        if (allocated(self%lambda)) deallocate(self%lambda)
        allocate(self%a(self%eq%n), self%lambda(self%eq%nc), source=0.0_wp)
    end subroutine prepare

    !> y' = (u, a) for y = (q, u); ierr 0 on success, -1 on failure (kept in self%failure).
    function ode_rhs(self, time, y, ydot) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)
        integer :: ierr
        type(error_type), allocatable :: error

        associate (n => self%eq%n)
            call self%eq%accelerations(time, y(:n), y(n + 1:), self%a, self%lambda, error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            ydot(:n) = y(n + 1:)
            ydot(n + 1:) = self%a
        end associate
    end function ode_rhs

    !> Event functions at (t, q, u): theta - theta_min, normal force. The multipliers are
    !> given by a DAE state (IDA); otherwise they are solved for, as in a right-hand side.
    function root_values(self, time, q, u, g, lambda) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(2)
        !> Multipliers at (t, q, u), when known
        real(wp), intent(in), optional :: lambda(:)
        integer :: ierr
        type(error_type), allocatable :: error
        real(wp) :: force(3)

        ierr = 0
        self%root_evaluations = self%root_evaluations + 1
        g(root_theta) = q(6*(self%events%part - 1) + 5) - self%events%theta_min
        g(root_liftoff) = 1.0_wp
        if (.not. self%events%stop_on_liftoff) return
        if (present(lambda)) then
            ! only C is needed: first partials, no saddle-point solve
            call self%eq%constraints%evaluate(self%eq%model, time, q, u, need_first, error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            call self%eq%constraint_matrix()
            self%lambda = lambda
        else
            call self%eq%accelerations(time, q, u, self%a, self%lambda, error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
        end if
        force = self%eq%constraint_force(self%events%part, self%lambda)
        g(root_liftoff) = force(3)
    end function root_values

    !> Keep the first failure; return the callback code (0 ok, -1 unrecoverable).
    function keep_failure(self, error) result(ierr)
        class(problem_type), intent(inout) :: self
        type(error_type), allocatable, intent(inout) :: error
        integer :: ierr

        ierr = 0
        if (.not. allocated(error)) return
        ierr = -1
        if (.not. allocated(self%failure)) call move_alloc(error, self%failure)
    end function keep_failure

end module rollcon_problem
