! SPDX-License-Identifier: MIT
!> What an integrator integrates: an ODE y' = f(t, y) for CVODE or a DAE F(t, y, y') = 0 for
!> IDA, their Newton matrices, an optional projection onto constraints, and event functions.
!> A system implements the form its integrator asks for; the defaults refuse (a callback code
!> of -1, unrecoverable). Callbacks never print or stop: a failure is kept by the system and
!> read by the integrator through `failure_text` for its message.
!>
!> Callback codes, as SUNDIALS reads them: 0 success, > 0 recoverable (the integrator cuts the
!> step), < 0 unrecoverable.
module rollcon_dynamic_system
    use rollcon_kinds, only : wp
    use rollcon_newton_pattern, only : newton_pattern_type, pattern_of_blocks
    implicit none
    private

    public :: dynamic_system_type

    type, abstract :: dynamic_system_type
    contains
        procedure :: ode_rhs
        procedure :: ode_jacobian
        procedure :: projects
        procedure :: project
        procedure :: dae_residual
        procedure :: dae_jacobian
        procedure :: dae_differential
        procedure :: state_blocks
        procedure :: dae_pattern
        procedure :: dae_euler_parts
        procedure :: multiplier_scale
        procedure :: root_count
        procedure :: roots
        procedure :: roots_use_rates
        procedure :: failure_text
    end type dynamic_system_type

contains

    !> y' = f(t, y).
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)

        ydot = 0.0_wp
        ierr = -1
    end function ode_rhs

    !> The Newton matrix df/dy at (t, y), column-major, size(y) square.
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)

        matrix = 0.0_wp
        ierr = -1
    end function ode_jacobian

    !> The system keeps its states on a constraint manifold by projection (CVODE's projection
    !> interface) when true.
    logical function projects(self)
        class(dynamic_system_type), intent(in) :: self

        projects = .false.
    end function projects

    !> The correction that takes y onto the constraints: y + correction satisfies them.
    integer function project(self, time, y, correction) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: correction(:)

        correction = 0.0_wp
        ierr = -1
    end function project

    !> F(t, y, y').
    integer function dae_residual(self, time, y, yp, residual) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:), yp(:)
        real(wp), intent(out) :: residual(:)

        residual = 0.0_wp
        ierr = -1
    end function dae_residual

    !> The Newton matrix dF/dy + cj dF/dy'. With `zeroed` true the caller has zeroed every
    !> entry of dae_pattern and the others are zero: only those are written (a sparse matrix's
    !> full work space, kept zero outside its pattern, is not cleared whole).
    integer function dae_jacobian(self, time, cj, y, yp, matrix, zeroed) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        real(wp), intent(inout) :: matrix(:, :)
        logical, intent(in), optional :: zeroed

        matrix = 0.0_wp
        ierr = -1
    end function dae_jacobian

    !> For each component of a DAE state: 1 differential, 0 algebraic (IDASetId).
    function dae_differential(self, n) result(kinds)
        class(dynamic_system_type), intent(in) :: self
        !> Size of the DAE state
        integer, intent(in) :: n
        real(wp) :: kinds(n)

        kinds = 1.0_wp
    end function dae_differential

    !> For each state, its block: the Newton matrix's entry (i, j) can be nonzero only when
    !> states i and j are of one block (a sparse Newton matrix keeps those entries). Default:
    !> one block, every entry.
    function state_blocks(self, n) result(blocks)
        class(dynamic_system_type), intent(in) :: self
        !> Size of the state
        integer, intent(in) :: n
        integer :: blocks(n)

        blocks = 1
    end function state_blocks

    !> Where the DAE's Newton matrix dF/dy + cj dF/dy' can be nonzero (IDA's sparse Newton
    !> matrix keeps those entries). Default: every entry of states of one block (state_blocks).
    subroutine dae_pattern(self, n, pattern)
        class(dynamic_system_type), intent(in) :: self
        !> Size of the DAE state
        integer, intent(in) :: n
        type(newton_pattern_type), intent(out) :: pattern

        pattern = pattern_of_blocks(self%state_blocks(n))
    end subroutine dae_pattern

    !> For each component of a DAE state: 0 when its tolerance is relative to itself, or the
    !> first component of the vector it is a component of, whose largest component its
    !> tolerance is then relative to (IDA's error weights). The default: every component alone.
    !> A size the loads on the constraints can be compared with, in the multipliers' units
    !> (IDA's absolute tolerance on the multipliers is at least 1e-5 of it). The default: 0,
    !> no such size.
    function multiplier_scale(self) result(scale)
        class(dynamic_system_type), intent(in) :: self
        real(wp) :: scale

        scale = 0.0_wp
    end function multiplier_scale

    !> The parts whose orientation is a set of 3-1-3 Euler angles in the DAE state: for each,
    !> the index of its psi (theta, phi follow) and of its psi' (theta', phi' follow). IDA holds
    !> those rates to the error their part's angular velocity may have (rollcon_ida). Default:
    !> none.
    function dae_euler_parts(self, n) result(parts)
        class(dynamic_system_type), intent(in) :: self
        !> Size of the DAE state
        integer, intent(in) :: n
        !> (1, k): psi of the k-th part, (2, k): its psi'
        integer, allocatable :: parts(:, :)

        allocate(parts(2, 0))
    end function dae_euler_parts

    !> Number of event functions (0: none).
    integer function root_count(self)
        class(dynamic_system_type), intent(in) :: self

        root_count = 0
    end function root_count

    !> The event functions at (t, y): root_count() values. ydot is y' when the integrator
    !> knows it without a call of the system (CVODE's interpolating polynomial).
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)

        g = 0.0_wp
        ierr = -1
    end function roots

    !> The event functions use y' when the integrator gives it (roots' ydot): CVODE then works it
    !> out from its polynomial (CVodeGetDky) at every evaluation; otherwise it is not given. The
    !> default: they do not.
    logical function roots_use_rates(self)
        class(dynamic_system_type), intent(in) :: self

        roots_use_rates = .false.
    end function roots_use_rates

    !> What made a callback fail, when it kept a reason ("" when none).
    function failure_text(self) result(text)
        class(dynamic_system_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
    end function failure_text

end module rollcon_dynamic_system
