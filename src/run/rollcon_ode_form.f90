! SPDX-License-Identifier: MIT
!> The ODE form of a problem (docs/design.md §4, formulation 'cvode'), the ODE system CVODE
!> integrates: y = (q, u), y' = (u, a) with a the accelerations of the saddle-point system at
!> (t, q, u) (rollcon_equations, with the settings' drift control); the Newton matrix from the
!> UCOSUBs' partials; the mass-weighted projection onto the constraints when the settings ask
!> for it; the watches' event functions, given the accelerations CVODE interpolates when they
!> use them.
module rollcon_ode_form
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_dynamic_system, only : ode_system_type
    use rollcon_problem, only : problem_type
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
        procedure :: projects
        procedure :: project
        procedure :: state_blocks
        procedure :: root_count
        procedure :: roots
        procedure :: roots_use_rates
        procedure :: failure_text
    end type ode_form_type

contains

    !> The ODE form of problem (prepared: rollcon_problem's prepare), which must outlive it.
    subroutine init(self, problem)
        class(ode_form_type), intent(inout) :: self
        type(problem_type), intent(inout), target :: problem

        self%problem => problem
    end subroutine init

    !> 2n: the coordinates and the rates.
    integer function state_size(self)
        class(ode_form_type), intent(in) :: self

        state_size = 2*self%problem%eq%n
    end function state_size

    !> y = (q, u); y' is not used (0).
    subroutine pack_state(self, q, u, y, yp)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)

        associate (n => self%problem%eq%n)
            y = 0.0_wp
            yp = 0.0_wp
            y(:n) = q
            y(n + 1:2*n) = u
        end associate
    end subroutine pack_state

    !> (q, u), y's own.
    subroutine unpack_state(self, time, y, q, u, error)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        associate (n => self%problem%eq%n)
            q = y(:n)
            u = y(n + 1:2*n)
        end associate
    end subroutine unpack_state

    !> y' = (u, a); ierr 0 on success, -1 on failure (kept as the problem's failure).
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n)
            call problem%accelerations(time, y(:n), y(n + 1:), error)
            if (.not. allocated(error) .and. .not. all(ieee_is_finite(problem%a))) &
                & call problem%nonfinite_state(time, y(:n), y(n + 1:2*n), error)
            ierr = problem%keep_failure(error)
            if (ierr /= 0) return
            ydot(:n) = y(n + 1:)
            ydot(n + 1:) = problem%a
        end associate
    end function ode_rhs

    !> The Newton matrix d(u, a)/d(q, u) from the UCOSUBs' partials (rollcon_equations).
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(ode_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n)
            call problem%eq%ode_jacobian(time, y(:n), y(n + 1:), problem%settings%baumgarte(), &
                & matrix, error)
            ierr = problem%keep_failure(error)
        end associate
    end function ode_jacobian

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
            call problem%eq%project(time, y(:n), y(n + 1:), correction(:n), correction(n + 1:), &
                & error)
            ierr = problem%keep_failure(error)
        end associate
    end function project

    !> A coordinate and its rate are of the coordinate's block (rollcon_problem's
    !> coordinate_blocks).
    function state_blocks(self, n) result(blocks)
        class(ode_form_type), intent(in) :: self
        integer, intent(in) :: n
        integer :: blocks(n)

        associate (nq => self%problem%eq%n)
            blocks(:nq) = self%problem%coordinate_blocks()
            blocks(nq + 1:) = blocks(:nq)
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

        associate (n => self%problem%eq%n)
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

end module rollcon_ode_form
