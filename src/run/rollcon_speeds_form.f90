! SPDX-License-Identifier: MIT
!> A problem in independent speeds (docs/design.md §4, formulation 'maggi'), the ODE system
!> CVODE integrates: y = (q, v), v the independent rates of a partition chosen at every start
!> and restart of the integrator (rollcon_independent_speeds, rollcon_speed_partition), the
!> dependent rates solved at every evaluation; y' = (u, a_i). Its Newton matrix by the chain
!> rule through the ODE form's; the projection of q alone onto the position UCONs when the
!> settings ask for it; a worn partition (its dependent block's condition) asks the run to
!> start the integrator again; the watches' event functions at (q, u).
module rollcon_speeds_form
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_independent_speeds, only : independent_speeds_type
    use rollcon_dynamic_system, only : ode_system_type, dense_sparse_jacobian
    use rollcon_problem, only : problem_type
    implicit none
    private

    public :: speeds_form_type

    !> A problem in independent speeds
    type, extends(ode_system_type) :: speeds_form_type
        !> The problem it integrates: its model, equations, settings and watches
        type(problem_type), pointer :: problem => null()
        !> The partition and its workspace (sized by init)
        type(independent_speeds_type) :: speeds
        !> The coordinates and rates the last evaluation used and the change of rates a
        !> projection would make (n each)
        real(wp), allocatable :: q(:), u(:), du(:)
    contains
        procedure :: init
        procedure :: state_size
        procedure :: pack_state
        procedure :: unpack_state
        procedure :: worn
        procedure :: ode_rhs
        procedure :: ode_jacobian
        procedure :: ode_sparse_jacobian
        procedure :: projects
        procedure :: project
        procedure :: state_blocks
        procedure :: root_count
        procedure :: roots
        procedure :: failure_text
        procedure :: power_count
        procedure :: powers
        procedure :: release
    end type speeds_form_type

contains

    !> The problem (prepared: rollcon_problem's prepare) in independent speeds, which must
    !> outlive it: the partition and the scratch arrays sized for its equations.
    subroutine init(self, problem)
        class(speeds_form_type), intent(inout) :: self
        type(problem_type), intent(inout), target :: problem

        self%problem => problem
        ! the ODE form's projection arrays, once; its Jacobian's (which this form's is formed
        ! from) by the first evaluation, dense (n x 2n) or by blocks (no n x 2n array)
        call problem%eq%size_ode_form(dense_jacobian=.false.)
        call self%speeds%init(problem%eq)
        if (allocated(self%q)) deallocate(self%q, self%u, self%du)
        allocate(self%q(problem%eq%n), self%u(problem%eq%n), self%du(problem%eq%n), &
            & source=0.0_wp)
    end subroutine init

    !> n plus the independent speeds, n - nc.
    integer function state_size(self)
        class(speeds_form_type), intent(in) :: self

        state_size = self%speeds%state_size()
    end function state_size

    !> y = (q, u_i), the partition chosen here from the constraint matrix of the problem's
    !> last evaluation (a start or a restart of the integrator: the only times it may change);
    !> y' is not used (0). A failed choice (constraint rows not independent) is kept as the
    !> problem's failure: the first evaluation then fails with it. Rows set aside otherwise
    !> than when the partition was sized (a choice again, rollcon_redundancy) size it anew:
    !> as many active rows, so as many independent speeds.
    subroutine pack_state(self, q, u, y, yp)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)
        type(error_type), allocatable :: error
        integer :: ierr

        y = 0.0_wp
        yp = 0.0_wp
        if (any(self%speeds%active .neqv. self%problem%eq%active_rows())) then
            call self%speeds%partition%release()
            call self%speeds%init(self%problem%eq)
        end if
        call self%speeds%choose(self%problem%eq, error)
        ierr = self%problem%keep_failure(error)
        call self%speeds%pack(q, u, y)
    end subroutine pack_state

    !> (q, u) at y = (q, v): the dependent rates solved at (t, q).
    subroutine unpack_state(self, time, y, q, u, error)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        associate (problem => self%problem, n => self%problem%eq%n)
            q = y(:n)
            call self%speeds%speeds(problem%eq, time, y(:n), y(n + 1:), &
                & problem%settings%baumgarte(), u, error)
        end associate
    end subroutine unpack_state

    !> The partition no longer suits the state y at t (its dependent block's condition has
    !> worn, rollcon_speed_partition), or the dependent rates cannot be solved there: the
    !> integrator should start again with a new one. Never without UCONs.
    function worn(self, time, y)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        logical :: worn
        type(error_type), allocatable :: error

        worn = .false.
        if (self%problem%eq%nc == 0) return
        call self%unpack_state(time, y, self%q, self%u, error)
        worn = allocated(error)
        if (.not. worn) worn = self%speeds%partition%worn(self%problem%eq%c)
    end function worn

    !> y' = (u, a_i); ierr 0 on success, -1 on failure (kept as the problem's failure; a
    !> partition that could not be chosen, pack_state, fails the first evaluation).
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)
        type(error_type), allocatable :: error

        ierr = -1
        if (allocated(self%problem%failure)) return
        associate (problem => self%problem, n => self%problem%eq%n)
            call self%speeds%rhs(problem%eq, time, y, problem%settings%baumgarte(), ydot, &
                & self%u, problem%a, problem%lambda, error)
            if (.not. allocated(error) .and. .not. all(ieee_is_finite(ydot))) &
                & call problem%nonfinite_state(time, y(:n), self%u, error)
            ierr = problem%keep_failure(error)
        end associate
    end function ode_rhs

    !> The Newton matrix d(u, a_i)/d(q, v) by the chain rule (rollcon_independent_speeds).
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)
        type(error_type), allocatable :: error

        associate (problem => self%problem)
            call self%speeds%jacobian(problem%eq, time, y, problem%settings%baumgarte(), &
                & self%u, matrix, error)
            ierr = problem%keep_failure(error)
        end associate
    end function ode_jacobian

    !> The Newton matrix over its state_blocks' entries, compressed by columns (CVODE's sparse
    !> one; rollcon_dynamic_system's ode_sparse_jacobian): formed block by block
    !> (rollcon_independent_speeds' jacobian_blocks), no size(y)-square array, each entry
    !> ode_jacobian's; with rows set aside or an algebraic loop, the dense matrix's entries
    !> (ode_system_type's).
    integer function ode_sparse_jacobian(self, time, y, starts, rows, values) result(ierr)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem)
            if (.not. self%speeds%by_blocks(problem%eq)) then
                ierr = dense_sparse_jacobian(self, time, y, starts, rows, values)
                return
            end if
            call self%speeds%jacobian_blocks(problem%eq, time, y, problem%settings%baumgarte(), &
                & self%u, starts, rows, values, error)
            ierr = problem%keep_failure(error)
        end associate
    end function ode_sparse_jacobian

    !> Projection of q onto the position UCONs, when the settings ask for it and there are
    !> some (the velocity UCONs hold by construction).
    logical function projects(self)
        class(speeds_form_type), intent(in) :: self

        projects = self%problem%projection_asked() .and. self%problem%eq%nh > 0
    end function projects

    !> The mass-weighted correction of the coordinates alone (the rates follow from the speeds
    !> at every evaluation).
    integer function project(self, time, y, correction) result(ierr)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: correction(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem)
            correction = 0.0_wp
            call self%unpack_state(time, y, self%q, self%u, error)
            if (.not. allocated(error)) call problem%eq%project(time, self%q, self%u, &
                & correction(:problem%eq%n), self%du, error)
            ierr = problem%keep_failure(error)
        end associate
    end function project

    !> A coordinate is of its block (rollcon_problem's coordinate_blocks), an independent speed
    !> of its rate's coordinate's.
    function state_blocks(self, n) result(blocks)
        class(speeds_form_type), intent(in) :: self
        integer, intent(in) :: n
        integer :: blocks(n)

        associate (nq => self%problem%eq%n)
            blocks(:nq) = self%problem%coordinate_blocks()
            blocks(nq + 1:) = blocks(self%speeds%partition%independent(:n - nq))
        end associate
    end function state_blocks

    !> Every watch's event functions.
    integer function root_count(self)
        class(speeds_form_type), intent(in) :: self

        root_count = self%problem%root_count()
    end function root_count

    !> The watches' event functions at (q, u), the rates solved from y = (q, v): y' = (u, a_i)
    !> carries no whole a, so the watches solve for what they need (roots_use_rates: never).
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)
        type(error_type), allocatable :: error

        call self%unpack_state(time, y, self%q, self%u, error)
        ierr = self%problem%keep_failure(error)
        if (ierr == 0) ierr = self%problem%root_values(time, self%q, self%u, g)
    end function roots

    !> The first failure a callback kept ("" when none).
    function failure_text(self) result(text)
        class(speeds_form_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = self%problem%failure_text()
    end function failure_text

    !> Free the partition's KLU factors (a block of 40 UCONs or more).
    subroutine release(self)
        class(speeds_form_type), intent(inout) :: self

        call self%speeds%partition%release()
    end subroutine release

    !> The powers the problem dissipates: rollcon_problem's power_count.
    integer function power_count(self)
        class(speeds_form_type), intent(in) :: self

        power_count = self%problem%power_count()
    end function power_count

    !> The powers dissipated at the state y at time [s] [W]: rollcon_problem's state_powers,
    !> (q, u) read from y by this form's unpack_state.
    integer function powers(self, time, y, values) result(ierr)
        class(speeds_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: values(:)

        ierr = self%problem%state_powers(self, time, y, values)
    end function powers

end module rollcon_speeds_form
