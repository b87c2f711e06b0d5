! SPDX-License-Identifier: MIT
!> The ODE form of a problem (docs/design.md §4, formulation 'cvode'), the ODE system CVODE
!> integrates: y = (q, u, x), y' = (u, a, w/T) with a the accelerations of the saddle-point
!> system at (t, q, u) (rollcon_equations, with the settings' drift control), x the DIFFs'
!> states and w their rates (rollcon_diff's solve_rates; T the dataset's time unit [s]); the
!> Newton matrix from the UCOSUBs' partials and the DIFFs' exact partials; the mass-weighted
!> projection onto the constraints when the settings ask
!> for it; the watches' event functions, given the accelerations CVODE interpolates when they
!> use them.
module rollcon_ode_form
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_dynamic_system, only : ode_system_type, dense_sparse_jacobian
    use rollcon_problem, only : problem_type
    use rollcon_lapack, only : factor_dense, solve_factored
    use rollcon_user_forces, only : set_system_accelerations
    implicit none
    private

    public :: ode_form_type

    !> The ODE form of a problem
    type, extends(ode_system_type) :: ode_form_type
        !> The problem it integrates: its model, equations, settings and watches
        type(problem_type), pointer :: problem => null()
    contains
        procedure :: init
        procedure :: state_size
        procedure :: pack_state
        procedure :: unpack_state
        procedure :: ode_rhs
        procedure :: ode_jacobian
        procedure :: ode_sparse_jacobian
        procedure :: projects
        procedure :: project
        procedure :: state_blocks
        procedure :: root_count
        procedure :: roots
        procedure :: roots_use_rates
        procedure :: failure_text
        procedure :: power_count
        procedure :: powers
    end type ode_form_type

contains

    !> The ODE form of problem (prepared: rollcon_problem's prepare), which must outlive it.
    subroutine init(self, problem)
        class(ode_form_type), intent(inout) :: self
        type(problem_type), intent(inout), target :: problem

        self%problem => problem
        ! its projection's arrays, once (no evaluation allocates); the Jacobian's by its first
        ! evaluation, dense (n x 2n right-hand sides) or by blocks (CVODE's sparse Newton
        ! matrix: no n x 2n array)
        call problem%eq%size_ode_form(dense_jacobian=.false.)
    end subroutine init

    !> 2n + nd: the coordinates, the rates and the DIFFs' states.
    integer function state_size(self)
        class(ode_form_type), intent(in) :: self

        state_size = 2*self%problem%eq%n + self%problem%model%diffs%count()
    end function state_size

    !> y = (q, u, x), x the DIFFs' state last set; y' is not used (0).
    subroutine pack_state(self, q, u, y, yp)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)

        associate (n => self%problem%eq%n)
            y = 0.0_wp
            yp = 0.0_wp
            y(:n) = q
            y(n + 1:2*n) = u
            if (self%problem%model%diffs%count() > 0) y(2*n + 1:) = self%problem%model%diffs%x
        end associate
    end subroutine pack_state

    !> (q, u), y's own; the DIFFs' state x set in the model.
    subroutine unpack_state(self, time, y, q, u, error)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        associate (n => self%problem%eq%n, model => self%problem%model)
            q = y(:n)
            u = y(n + 1:2*n)
            if (model%diffs%count() > 0) call model%set_diff_state(y(2*n + 1:), model%diffs%w)
        end associate
    end subroutine unpack_state

    !> y' = (u, a, w/T); ierr 0 on success, -1 on failure (kept as the problem's failure).
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n, &
                & diffs => self%problem%model%diffs)
            if (diffs%count() > 0) call problem%model%set_diff_state(y(2*n + 1:), diffs%w)
            call problem%accelerations(time, y(:n), y(n + 1:2*n), error)
            if (.not. allocated(error) .and. .not. all(ieee_is_finite(problem%a))) &
                & call problem%nonfinite_state(time, y(:n), y(n + 1:2*n), error)
            ierr = problem%keep_failure(error)
            if (ierr /= 0) return
            ydot(:n) = y(n + 1:2*n)
            ydot(n + 1:2*n) = problem%a
            if (diffs%count() > 0) ydot(2*n + 1:) = diffs%w/diffs%time_unit
        end associate
    end function ode_rhs

    !> The Newton matrix d(u, a, w/T)/d(q, u, x) from the UCOSUBs' partials (rollcon_equations)
    !> and the DIFFs' (diff_rows).
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n, &
                & diffs => self%problem%model%diffs)
            if (diffs%count() == 0) then
                call problem%eq%ode_jacobian(time, y(:n), y(n + 1:), &
                    & problem%settings%baumgarte(), matrix, error)
            else
                matrix = 0.0_wp
                call problem%model%set_diff_state(y(2*n + 1:), diffs%w)
                call problem%diff_rates(time, y(:n), y(n + 1:2*n), error)
                if (.not. allocated(error)) call problem%eq%ode_jacobian(time, y(:n), &
                    & y(n + 1:2*n), problem%settings%baumgarte(), matrix(:2*n, :2*n), error)
                ! a DIFSUB reading accelerations reads those ode_jacobian solved for
                if (.not. allocated(error) .and. diffs%reads_accelerations()) &
                    & call set_system_accelerations(problem%eq%work%a)
                if (.not. allocated(error)) call diff_rows(problem, time, y(:n), &
                    & y(n + 1:2*n), matrix(n + 1:2*n, :2*n), matrix(2*n + 1:, :), error)
            end if
            ierr = problem%keep_failure(error)
        end associate
    end function ode_jacobian

    !> The Newton matrix over its state_blocks' entries, compressed by columns (CVODE's sparse
    !> one; rollcon_dynamic_system's ode_sparse_jacobian): formed block by block by the
    !> equations' ode_jacobian_blocks, no size(y)-square array nor n x 2n right-hand sides,
    !> each entry ode_jacobian's. With DIFFs (one block of every state: the dense matrix is
    !> the block) or an algebraic loop (whose (n + nc)-square matrix is dense anyway), the
    !> dense matrix's entries (ode_system_type's).
    integer function ode_sparse_jacobian(self, time, y, starts, rows, values) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n)
            if (problem%model%diffs%count() > 0 .or. problem%eq%reads_loop()) then
                ierr = dense_sparse_jacobian(self, time, y, starts, rows, values)
                return
            end if
            call problem%eq%ode_jacobian_blocks(time, y(:n), y(n + 1:2*n), &
                & problem%settings%baumgarte(), starts, rows, values, error)
            ierr = problem%keep_failure(error)
        end associate
    end function ode_sparse_jacobian

    !> The DIFFs' rows of the ODE form's Newton matrix, d(w/T)/d(q, u, x) = -(dG/dw)^-1
    !> dG/d(q, u, x) / T at the rates w solved there (rollcon_diff: G(t, q, u, x, w) = 0
    !> defines w; exact partials). A DIFSUB reading accelerations adds dG/da da/d(q, u) to
    !> dG/d(q, u) (its partials in a differenced, rollcon_diff's acceleration_partials;
    !> da/d(q, u) the Newton matrix's acceleration rows, accelerations_rows: n x 2n); one
    !> reading a constraint's reaction adds dG/dlambda dlambda/d(q, u) (its partials in the
    !> multipliers of the rows it declared differenced, rollcon_diff's multiplier_partials;
    !> dlambda/d(q, u) solved with da/d(q, u) by the equations' ode_jacobian, the work's
    !> rhs_bottom: nc x 2n). The
    !> accelerations' partials in x (a force that reads DIF) are left out of the matrix, as
    !> the expression forces' other partials are.
    subroutine diff_rows(problem, time, q, u, accelerations_rows, rows, error)
        type(problem_type), intent(inout) :: problem
        real(wp), intent(in) :: time, q(:), u(:), accelerations_rows(:, :)
        !> nd x (2n + nd)
        real(wp), intent(out) :: rows(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: g(:), g_q(:, :), g_u(:, :), g_x(:, :), g_w(:, :), w(:), &
            & right(:, :), g_a(:, :), g_lambda(:, :)
        integer, allocatable :: pivots(:)
        integer :: n, nd

        n = size(q)
        associate (diffs => problem%model%diffs)
            nd = diffs%count()
            allocate(g(nd), g_q(nd, n), g_u(nd, n), g_x(nd, nd), g_w(nd, nd), pivots(nd))
            w = diffs%w
            call diffs%solve_rates(time, q, u, diffs%x, w, error, g_w, pivots)
            if (allocated(error)) return
            call diffs%partials(time, q, u, diffs%x, w, g, g_q, g_u, g_x, g_w)
            ! contiguous right-hand sides for LAPACK (rows is a section of the matrix)
            allocate(right(nd, 2*n + nd))
            right(:, :n) = g_q
            right(:, n + 1:2*n) = g_u
            right(:, 2*n + 1:) = g_x
            if (diffs%reads_accelerations()) then
                allocate(g_a(nd, n))
                call diffs%acceleration_partials(time, q, u, diffs%x, w, problem%eq%work%a, g_a)
                right(:, :2*n) = right(:, :2*n) + matmul(g_a, accelerations_rows)
            end if
            if (diffs%reads_constraint_forces()) then
                ! the multipliers solved at (t, q, u) (the equations' loop set them for the
                ! force measures) and their partials in (q, u) beside the accelerations'
                allocate(g_lambda(nd, problem%eq%nc))
                call diffs%multiplier_partials(time, q, u, diffs%x, w, g_lambda)
                right(:, :2*n) = right(:, :2*n) + matmul(g_lambda, problem%eq%work%rhs_bottom)
            end if
            call factor_dense(g_w, pivots, error)
            if (allocated(error)) return
            call solve_factored(g_w, pivots, right, error)
            if (allocated(error)) return
            rows = -right/diffs%time_unit
        end associate
    end subroutine diff_rows

    !> Projection onto the constraints, when the settings ask for it and there are UCONs.
    logical function projects(self)
        class(ode_form_type), intent(in) :: self

        projects = self%problem%projection_asked()
    end function projects

    !> The mass-weighted correction of (q, u) onto the constraints (exact, one step).
    integer function project(self, time, y, correction) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: correction(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n)
            correction = 0.0_wp
            call problem%eq%project(time, y(:n), y(n + 1:2*n), correction(:n), &
                & correction(n + 1:2*n), error)
            ierr = problem%keep_failure(error)
        end associate
    end function project

    !> A coordinate and its rate are of the coordinate's block (rollcon_problem's
    !> coordinate_blocks); with DIFFs, every state is of one block.
    function state_blocks(self, n) result(blocks)
        class(ode_form_type), intent(in) :: self
        integer, intent(in) :: n
        integer :: blocks(n)

        associate (nq => self%problem%eq%n)
            blocks(:nq) = self%problem%coordinate_blocks()
            blocks(nq + 1:2*nq) = blocks(:nq)
            ! a DIFF may read every part: one block
            if (self%problem%model%diffs%count() > 0) blocks = 1
        end associate
    end function state_blocks

    !> Every watch's event functions.
    integer function root_count(self)
        class(ode_form_type), intent(in) :: self

        root_count = self%problem%root_count()
    end function root_count

    !> The watches' event functions at y = (q, u), with the accelerations of CVODE's
    !> interpolated y' when given.
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)

        associate (n => self%problem%eq%n, model => self%problem%model)
            ! the DIFFs' state at y, for the forces' switches that read it
            if (model%diffs%count() > 0) call model%set_diff_state(y(2*n + 1:), model%diffs%w)
            if (present(ydot)) then
                ierr = self%problem%root_values(time, y(:n), y(n + 1:2*n), g, a=ydot(n + 1:2*n))
            else
                ierr = self%problem%root_values(time, y(:n), y(n + 1:2*n), g)
            end if
        end associate
    end function roots

    !> CVODE should give the event functions y' = (u, a) when a watch's use the accelerations.
    logical function roots_use_rates(self)
        class(ode_form_type), intent(in) :: self

        roots_use_rates = self%problem%roots_use_accelerations()
    end function roots_use_rates

    !> The first failure a callback kept ("" when none).
    function failure_text(self) result(text)
        class(ode_form_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = self%problem%failure_text()
    end function failure_text

    !> The powers the problem dissipates: rollcon_problem's power_count.
    integer function power_count(self)
        class(ode_form_type), intent(in) :: self

        power_count = self%problem%power_count()
    end function power_count

    !> The powers dissipated at the state y at time [s] [W]: rollcon_problem's state_powers,
    !> (q, u) read from y by this form's unpack_state.
    integer function powers(self, time, y, values) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: values(:)

        ierr = self%problem%state_powers(self, time, y, values)
    end function powers

end module rollcon_ode_form
