! SPDX-License-Identifier: MIT
!> What an integrator integrates: a model of rigid parts whose state y (and y' for a DAE) a
!> run makes from the parts' coordinates and rates (q, u) and reads them back from, with its
!> event functions; as an ODE y' = f(t, y) for CVODE (`ode_system_type`) or a DAE
!> F(t, y, y') = 0 for IDA (`dae_system_type`), with their Newton matrices.
!>
!> What every system must provide is deferred: a system that leaves one out does not compile.
!> The bindings with a body have a default that is true of a system that does not refine it
!> (one block of states, no projection, no release); the one that refuses, `project`, is
!> called only on a system whose `projects` says it projects, which then provides it.
!> Callbacks never print or stop: a failure is kept by the system and read by the integrator
!> through `failure_text` for its message.
!>
!> Callback codes, as SUNDIALS reads them: 0 success, > 0 recoverable (the integrator cuts the
!> step), < 0 unrecoverable.
module rollcon_dynamic_system
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_newton_pattern, only : newton_pattern_type
    implicit none
    private

    public :: dynamic_system_type, ode_system_type, dae_system_type, dense_sparse_jacobian

    !> What every system provides, whichever integrator takes it
    type, abstract :: dynamic_system_type
    contains
        procedure(state_size_interface), deferred :: state_size
        procedure(pack_state_interface), deferred :: pack_state
        procedure(unpack_state_interface), deferred :: unpack_state
        procedure(holds_constraints_interface), deferred :: holds_constraints
        procedure(root_count_interface), deferred :: root_count
        procedure(roots_interface), deferred :: roots
        procedure(failure_text_interface), deferred :: failure_text
        procedure :: state_blocks
        procedure :: worn
        procedure :: release
        procedure :: power_count
        procedure :: powers
    end type dynamic_system_type

    !> A system CVODE integrates: y' = f(t, y), its Newton matrix, an optional projection
    type, abstract, extends(dynamic_system_type) :: ode_system_type
        !> The dense Newton matrix whose entries the default ode_sparse_jacobian copies
        !> (size(y) square, allocated by its first call: none for a system that forms its sparse
        !> matrix by blocks)
        real(wp), allocatable :: dense_jacobian(:, :)
    contains
        procedure(ode_rhs_interface), deferred :: ode_rhs
        procedure(ode_jacobian_interface), deferred :: ode_jacobian
        procedure :: ode_sparse_jacobian
        procedure :: projects
        procedure :: project
        procedure :: roots_use_rates
        procedure :: holds_constraints => ode_holds_constraints
    end type ode_system_type

    !> A system IDA integrates: F(t, y, y') = 0, its Newton matrix and its pattern, which of
    !> its components are algebraic
    type, abstract, extends(dynamic_system_type) :: dae_system_type
    contains
        procedure(dae_residual_interface), deferred :: dae_residual
        procedure(dae_jacobian_interface), deferred :: dae_jacobian
        procedure(dae_sparse_jacobian_interface), deferred :: dae_sparse_jacobian
        procedure(dae_differential_interface), deferred :: dae_differential
        procedure(dae_pattern_interface), deferred :: dae_pattern
        procedure :: dae_euler_parts
        procedure :: multiplier_scale
        procedure :: holds_constraints => dae_holds_constraints
    end type dae_system_type

    abstract interface
        !> Size of the integrator's state y.
        integer function state_size_interface(self)
            import :: dynamic_system_type
            class(dynamic_system_type), intent(in) :: self
        end function state_size_interface

        !> The integrator's state y and its derivative y' (0 where the integrator takes none)
        !> at the coordinates and rates (q, u) of every part [m, rad, m/s, rad/s], at a start
        !> or a restart of the integrator: what else the state holds is the model's last
        !> evaluation at (q, u), and the choices a system makes for a stretch of integration
        !> (`worn`) are made here. A choice that fails is kept as the system's failure: its
        !> first evaluation then fails with it.
        subroutine pack_state_interface(self, q, u, y, yp)
            import :: dynamic_system_type, wp
            class(dynamic_system_type), intent(inout) :: self
            real(wp), intent(in) :: q(:), u(:)
            real(wp), intent(out) :: y(:), yp(:)
        end subroutine pack_state_interface

        !> The coordinates and rates (q, u) of every part at the state y at time [s].
        subroutine unpack_state_interface(self, time, y, q, u, error)
            import :: dynamic_system_type, wp, error_type
            class(dynamic_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, y(:)
            real(wp), intent(out) :: q(:), u(:)
            type(error_type), allocatable, intent(out) :: error
        end subroutine unpack_state_interface

        !> The system holds its states on the model's constraints (a DAE's algebraic equations,
        !> an ODE's projection): a state set from outside (a restart) must be put on them.
        logical function holds_constraints_interface(self)
            import :: dynamic_system_type
            class(dynamic_system_type), intent(in) :: self
        end function holds_constraints_interface

        !> Number of event functions (0: none).
        integer function root_count_interface(self)
            import :: dynamic_system_type
            class(dynamic_system_type), intent(in) :: self
        end function root_count_interface

        !> The event functions at (t, y): root_count() values. ydot is y' when the integrator
        !> knows it without a call of the system (CVODE's interpolating polynomial, when
        !> roots_use_rates asks for it).
        integer function roots_interface(self, time, y, g, ydot) result(ierr)
            import :: dynamic_system_type, wp
            class(dynamic_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, y(:)
            real(wp), intent(out) :: g(:)
            real(wp), intent(in), optional :: ydot(:)
        end function roots_interface

        !> What made a callback fail, when it kept a reason ("" when none).
        function failure_text_interface(self) result(text)
            import :: dynamic_system_type
            class(dynamic_system_type), intent(in) :: self
            character(len=:), allocatable :: text
        end function failure_text_interface

        !> y' = f(t, y).
        integer function ode_rhs_interface(self, time, y, ydot) result(ierr)
            import :: ode_system_type, wp
            class(ode_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, y(:)
            real(wp), intent(out) :: ydot(:)
        end function ode_rhs_interface

        !> The Newton matrix df/dy at (t, y), column-major, size(y) square.
        integer function ode_jacobian_interface(self, time, y, matrix) result(ierr)
            import :: ode_system_type, wp
            class(ode_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, y(:)
            real(wp), intent(out) :: matrix(:, :)
        end function ode_jacobian_interface

        !> F(t, y, y').
        integer function dae_residual_interface(self, time, y, yp, residual) result(ierr)
            import :: dae_system_type, wp
            class(dae_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, y(:), yp(:)
            real(wp), intent(out) :: residual(:)
        end function dae_residual_interface

        !> The Newton matrix dF/dy + cj dF/dy', dense (size(y) square).
        integer function dae_jacobian_interface(self, time, cj, y, yp, matrix) result(ierr)
            import :: dae_system_type, wp
            class(dae_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, cj, y(:), yp(:)
            real(wp), intent(inout) :: matrix(:, :)
        end function dae_jacobian_interface

        !> The same Newton matrix over dae_pattern's entries, compressed by columns: column j's
        !> rows (0-based, ascending) rows(starts(j) + 1 : starts(j + 1)), their values in
        !> values (the same places); no size(y)-square array (IDA's sparse Newton matrix).
        integer function dae_sparse_jacobian_interface(self, time, cj, y, yp, starts, rows, &
                & values) result(ierr)
            import :: dae_system_type, wp
            class(dae_system_type), intent(inout) :: self
            real(wp), intent(in) :: time, cj, y(:), yp(:)
            integer, intent(in) :: starts(:), rows(:)
            real(wp), intent(out) :: values(:)
        end function dae_sparse_jacobian_interface

        !> For each component of a DAE state of size n: 1 differential, 0 algebraic
        !> (IDASetId).
        function dae_differential_interface(self, n) result(kinds)
            import :: dae_system_type, wp
            class(dae_system_type), intent(in) :: self
            integer, intent(in) :: n
            real(wp) :: kinds(n)
        end function dae_differential_interface

        !> Where the DAE's Newton matrix dF/dy + cj dF/dy' (size n) can be nonzero: IDA's
        !> sparse Newton matrix keeps those entries.
        subroutine dae_pattern_interface(self, n, pattern)
            import :: dae_system_type, newton_pattern_type
            class(dae_system_type), intent(in) :: self
            integer, intent(in) :: n
            type(newton_pattern_type), intent(out) :: pattern
        end subroutine dae_pattern_interface
    end interface

contains

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

    !> The choices the system made at the last pack_state no longer suit the state y at t:
    !> the integrator should start again from it (pack_state choosing anew). Default: a
    !> system that makes no such choice, never.
    function worn(self, time, y)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        logical :: worn

        worn = .false.
    end function worn

    !> Number of the powers the system dissipates (powers), each integrated over time by the
    !> integrator with the state: the work they did (docs/design.md §7, "Dissipated work").
    !> Default: none.
    integer function power_count(self)
        class(dynamic_system_type), intent(in) :: self

        power_count = 0
    end function power_count

    !> The powers the system dissipates at the state y at time [s]: power_count() values [W],
    !> each >= 0. ierr as the callbacks' (a failure kept for failure_text). Default: none.
    integer function powers(self, time, y, values) result(ierr)
        class(dynamic_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: values(:)

        values = 0.0_wp
        ierr = 0
    end function powers

    !> Free what the system holds outside Fortran's memory, when a run is done. Default:
    !> nothing.
    subroutine release(self)
        class(dynamic_system_type), intent(inout) :: self
    end subroutine release

    !> The Newton matrix df/dy at (t, y) over the entries its state_blocks keep (those of states
    !> of one block), compressed by columns: column j's rows (0-based, ascending: every state of
    !> j's block) rows(starts(j) + 1 : starts(j + 1)), their values in values (the same places;
    !> CVODE's sparse Newton matrix). Default: ode_jacobian's dense matrix, formed whole in
    !> dense_jacobian (size(y) square, allocated by the first call), its entries there copied:
    !> for a system of one block, or whose blocks are small (the independent speeds,
    !> rollcon's benchmark's reduced models); a system that grows overrides it and forms the
    !> matrix by blocks (rollcon_ode_form), with no such array.
    integer function ode_sparse_jacobian(self, time, y, starts, rows, values) result(ierr)
        class(ode_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)

        ierr = dense_sparse_jacobian(self, time, y, starts, rows, values)
    end function ode_sparse_jacobian

    !> ode_sparse_jacobian's default, for a system that overrides it to call on some models:
    !> the entries of its dense ode_jacobian, formed whole in its dense_jacobian.
    integer function dense_sparse_jacobian(self, time, y, starts, rows, values) result(ierr)
        class(ode_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)
        integer :: j, x

        if (allocated(self%dense_jacobian)) then
            if (size(self%dense_jacobian, 1) /= size(y)) deallocate(self%dense_jacobian)
        end if
        if (.not. allocated(self%dense_jacobian)) &
            & allocate(self%dense_jacobian(size(y), size(y)), source=0.0_wp)
        ierr = self%ode_jacobian(time, y, self%dense_jacobian)
        if (ierr /= 0) return
        do j = 1, size(y)
            do x = starts(j) + 1, starts(j + 1)
                values(x) = self%dense_jacobian(rows(x) + 1, j)
            end do
        end do
    end function dense_sparse_jacobian

    !> The system keeps its states on a constraint manifold by projection (CVODE's projection
    !> interface) when true. Default: it does not.
    logical function projects(self)
        class(ode_system_type), intent(in) :: self

        projects = .false.
    end function projects

    !> The correction that takes y onto the constraints: y + correction satisfies them.
    !> Called only when projects() is true: a system that projects provides it; this one
    !> refuses (-1, unrecoverable).
    integer function project(self, time, y, correction) result(ierr)
        class(ode_system_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: correction(:)

        correction = 0.0_wp
        ierr = -1
    end function project

    !> The event functions use y' when the integrator gives it (roots' ydot): CVODE then works
    !> it out from its polynomial (CVodeGetDky) at every evaluation; otherwise it is not given.
    !> Default: they do not.
    logical function roots_use_rates(self)
        class(ode_system_type), intent(in) :: self

        roots_use_rates = .false.
    end function roots_use_rates

    !> An ODE's states are on the constraints only when it projects them there.
    logical function ode_holds_constraints(self) result(holds)
        class(ode_system_type), intent(in) :: self

        holds = self%projects()
    end function ode_holds_constraints

    !> A DAE's algebraic equations are its constraints: every state it integrates holds them.
    logical function dae_holds_constraints(self) result(holds)
        class(dae_system_type), intent(in) :: self

        holds = .true.
    end function dae_holds_constraints

    !> The parts whose orientation is a set of 3-1-3 Euler angles in the DAE state: for each,
    !> the index of its psi (theta, phi follow) and of its psi' (theta', phi' follow). IDA holds
    !> those rates to the error their part's angular velocity may have (rollcon_ida). Default:
    !> none.
    function dae_euler_parts(self, n) result(parts)
        class(dae_system_type), intent(in) :: self
        !> Size of the DAE state
        integer, intent(in) :: n
        !> (1, k): psi of the k-th part, (2, k): its psi'
        integer, allocatable :: parts(:, :)

        allocate(parts(2, 0))
    end function dae_euler_parts

    !> A size the loads on the constraints can be compared with, in the multipliers' units
    !> (IDA's absolute tolerance on the multipliers is at least 1e-5 of it). Default: 0, no
    !> such size.
    function multiplier_scale(self) result(scale)
        class(dae_system_type), intent(in) :: self
        real(wp) :: scale

        scale = 0.0_wp
    end function multiplier_scale

end module rollcon_dynamic_system
