! SPDX-License-Identifier: MIT
!> A model as the integrators see it (rollcon_dynamic_system): the model (held here, once), its
!> equations, the run settings, the watches of the run, scratch arrays, and the first failure a
!> callback met (callbacks never print or stop). The ODE state is y = (q, u); the DAE state is
!> y = (q, u, lambda, mu) with y' = (u, a, 0, 0); the state in independent speeds is
!> y = (q, v), v the independent rates of a partition (docs/design.md §4).
module rollcon_problem
    use rollcon_kinds, only : wp
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_text, only : to_text
    use rollcon_force, only : nonfinite_load
    use rollcon_model, only : model_type
    use rollcon_equations, only : equations_type
    use rollcon_constraints, only : need_value
    use rollcon_dae, only : dae_size, dae_differential_kinds => dae_differential, &
        & residual_of_dae => dae_residual, jacobian_of_dae => dae_jacobian
    use rollcon_independent_speeds, only : independent_speeds_type
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, formulation_maggi, &
        & drift_projection
    use rollcon_dynamic_system, only : dynamic_system_type
    use rollcon_newton_pattern, only : newton_pattern_type
    use rollcon_watch, only : watch_type, watch_slot_type, append_watch
    use rollcon_output_layout, only : name_length, coord_psi
    implicit none
    private

    public :: problem_type

    type, extends(dynamic_system_type) :: problem_type
        !> The model, set up: the one copy
        type(model_type) :: model
        !> Its equations (pointing at `model`)
        type(equations_type) :: eq
        type(run_settings_type) :: settings
        !> What the run watches besides parts, UCONs and forces, in order: their event
        !> functions and their columns follow one another in this order
        type(watch_slot_type), allocatable :: watches(:)
        !> The number of columns each watch adds (set by prepare)
        integer, allocatable :: watch_columns(:)
        !> Scratch: accelerations and multipliers
        real(wp), allocatable :: a(:), lambda(:)
        !> The formulation in independent speeds: its partition and workspace (sized by
        !> prepare), the coordinates and rates its last evaluation used and the change of rates
        !> a projection would make (n each)
        type(independent_speeds_type) :: speeds
        real(wp), allocatable :: q(:), u(:), du(:)
        !> The first failure inside a callback, for the caller to report
        type(error_type), allocatable :: failure
        !> For each part (model order), the basis its start and the model's part are given in
        !> (docs/rebasing.md): 0, its own axes, unless the part starts where those are singular
        !> (a dataset's part flat at t = 0: 1). A run counts these as re-basings before its first
        !> row. Set by init to 0
        integer, allocatable :: start_bases(:)
    contains
        procedure :: init
        procedure :: add_watch
        procedure :: prepare
        procedure :: accelerations
        procedure :: ucon_count
        procedure :: ucon_id
        procedure :: constraint_values
        procedure :: state_size
        procedure :: pack_state
        procedure :: unpack_state
        procedure :: in_speeds
        procedure :: speeds_worn
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
        procedure :: root_values
        procedure :: root_owner
        procedure :: nonfinite_state
        procedure :: keep_failure
        procedure :: failure_text
        procedure :: ucons_do_no_work
        procedure :: release => release_problem
    end type problem_type

contains

    !> Keep a model that setup_model has prepared (the problem's copy is the only one the
    !> run uses: the equations refer to it) and set up its equations on it; no watches yet, every
    !> part's start in its own axes.
    subroutine init(self, model)
        class(problem_type), intent(inout), target :: self
        type(model_type), intent(in) :: model

        self%model = model
        call self%eq%init(self%model)
        if (allocated(self%watches)) deallocate(self%watches)
        allocate(self%watches(0))
        if (allocated(self%start_bases)) deallocate(self%start_bases)
        if (allocated(self%model%parts)) then
            allocate(self%start_bases(size(self%model%parts)), source=0)
        else
            allocate(self%start_bases(0))
        end if
    end subroutine init

    !> Watch this too (after the watches added before it).
    subroutine add_watch(self, watch)
        class(problem_type), intent(inout) :: self
        class(watch_type), intent(in) :: watch

        call append_watch(self%watches, watch)
    end subroutine add_watch

    !> Before a run: size scratch arrays, prepare every watch (it may refuse the model).
    subroutine prepare(self, error)
        class(problem_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        character(len=name_length), allocatable :: names(:)
        integer :: k

        if (allocated(self%a)) deallocate(self%a)
        if (allocated(self%lambda)) deallocate(self%lambda)
        if (allocated(self%u)) deallocate(self%q, self%u, self%du)
        allocate(self%a(self%eq%n), self%lambda(self%eq%nc), self%q(self%eq%n), &
            & self%u(self%eq%n), self%du(self%eq%n), source=0.0_wp)
        if (self%in_speeds()) call self%speeds%init(self%eq)
        if (allocated(self%failure)) deallocate(self%failure)
        if (.not. allocated(self%watches)) allocate(self%watches(0))
        if (allocated(self%watch_columns)) deallocate(self%watch_columns)
        allocate(self%watch_columns(size(self%watches)))
        do k = 1, size(self%watches)
            call self%watches(k)%watch%prepare(self%eq, self%settings, error)
            if (allocated(error)) return
            call self%watches(k)%watch%column_names(self%eq, names)
            self%watch_columns(k) = size(names)
        end do
    end subroutine prepare

    !> Accelerations and multipliers at (t, q, u) into self%a and self%lambda, with the
    !> settings' drift control.
    subroutine accelerations(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        call self%eq%accelerations(time, q, u, self%settings%baumgarte(), self%a, self%lambda, &
            & error)
    end subroutine accelerations

    !> Number of UCONs.
    pure integer function ucon_count(self)
        class(problem_type), intent(in) :: self

        ucon_count = self%eq%nc
    end function ucon_count

    !> Identifier of the k-th UCON (as in its UCON statement).
    pure integer function ucon_id(self, k)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: k

        ucon_id = self%model%ucons(k)%id
    end function ucon_id

    !> Each UCON's residual F_k at the last evaluation.
    pure function constraint_values(self) result(values)
        class(problem_type), intent(in) :: self
        real(wp) :: values(self%eq%nc)

        values = self%eq%constraints%value
    end function constraint_values

    !> The state is in independent speeds (formulation 'maggi').
    pure logical function in_speeds(self)
        class(problem_type), intent(in) :: self

        in_speeds = self%settings%formulation == formulation_maggi
    end function in_speeds

    !> Size of the integrator's state: 2n for the ODE form, the DAE's size for IDA, n plus the
    !> independent speeds in those.
    pure integer function state_size(self)
        class(problem_type), intent(in) :: self

        if (self%in_speeds()) then
            state_size = self%speeds%state_size()
        else if (self%settings%formulation == formulation_cvode) then
            state_size = 2*self%eq%n
        else
            state_size = dae_size(self%eq)
        end if
    end function state_size

    !> The integrator's state at (q, u) with the accelerations and multipliers of the last
    !> accelerations call: y = (q, u) for CVODE; y = (q, u, lambda, 0), y' = (u, a, 0, 0) for
    !> IDA (mu = 0: the GGL multipliers vanish on a consistent state); y = (q, u_i) in
    !> independent speeds, whose partition is chosen here, from the constraint matrix of that
    !> call (a start or a restart of the integrator: the only times it may change). A failed
    !> choice (constraint rows not independent) is kept as the problem's failure; the first
    !> evaluation then fails with it.
    subroutine pack_state(self, q, u, y, yp)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)
        type(error_type), allocatable :: error
        integer :: ierr

        associate (n => self%eq%n, nc => self%eq%nc)
            y = 0.0_wp
            yp = 0.0_wp
            if (self%in_speeds()) then
                call self%speeds%choose(self%eq, error)
                ierr = self%keep_failure(error)
                call self%speeds%pack(q, u, y)
                return
            end if
            y(:n) = q
            y(n + 1:2*n) = u
            if (self%settings%formulation == formulation_cvode) return
            y(2*n + 1:2*n + nc) = self%lambda
            yp(:n) = u
            yp(n + 1:2*n) = self%a
        end associate
    end subroutine pack_state

    !> The coordinates and rates (q, u) at a state y of the integrator: y's own for the ODE
    !> and DAE forms, the dependent rates solved at (t, q) in independent speeds.
    subroutine unpack_state(self, time, y, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        associate (n => self%eq%n)
            q = y(:n)
            if (self%in_speeds()) then
                call self%speeds%speeds(self%eq, time, y(:n), y(n + 1:), &
                    & self%settings%baumgarte(), u, error)
            else
                u = y(n + 1:2*n)
            end if
        end associate
    end subroutine unpack_state

    !> In independent speeds: the partition no longer suits the state y at t (its dependent
    !> block's condition has worn, rollcon_speed_partition), so the integrator should start
    !> again with a new one. Always false for the other forms.
    function speeds_worn(self, time, y) result(worn)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        logical :: worn
        type(error_type), allocatable :: error

        worn = .false.
        if (.not. self%in_speeds() .or. self%eq%nc == 0) return
        call self%unpack_state(time, y, self%q, self%u, error)
        worn = allocated(error)
        if (.not. worn) worn = self%speeds%partition%worn(self%eq%c)
    end function speeds_worn

    !> y' = (u, a) for y = (q, u), (u, a_i) for y = (q, v); ierr 0 on success, -1 on failure
    !> (kept in self%failure).
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)
        type(error_type), allocatable :: error

        if (self%in_speeds()) then
            ! a partition that could not be chosen (pack_state) fails the first evaluation
            ierr = -1
            if (allocated(self%failure)) return
            associate (n => self%eq%n)
                call self%speeds%rhs(self%eq, time, y, self%settings%baumgarte(), ydot, self%u, &
                    & self%a, self%lambda, error)
                if (.not. allocated(error) .and. .not. all(ieee_is_finite(ydot))) &
                    & call nonfinite_state(self, time, y(:n), self%u, error)
            end associate
            ierr = self%keep_failure(error)
            return
        end if
        associate (n => self%eq%n)
            call self%accelerations(time, y(:n), y(n + 1:), error)
            if (.not. allocated(error) .and. .not. all(ieee_is_finite(self%a))) &
                & call nonfinite_state(self, time, y(:n), y(n + 1:2*n), error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            ydot(:n) = y(n + 1:)
            ydot(n + 1:) = self%a
        end associate
    end function ode_rhs

    !> Why the equations are not finite at (t, q, u), in words: a force statement's load (named,
    !> with its expression), a UCON's value, or else the accelerations themselves.
    subroutine nonfinite_state(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: message
        integer :: k

        message = nonfinite_load(self%model%forces, size(self%model%parts), time, q, u)
        if (len(message) == 0 .and. self%eq%nc > 0) then
            k = findloc(ieee_is_finite(self%eq%constraints%value), .false., dim=1)
            if (k > 0) message = "UCON/" // to_text(self%model%ucons(k)%id) // ": F is not " &
                & // "finite at t = " // to_text(time) // " s"
        end if
        if (len(message) == 0) message = "the accelerations are not finite at t = " &
            & // to_text(time) // " s (a singular mass matrix or constraint matrix?)"
        call fatal_error(error, message, stat_ucon)
    end subroutine nonfinite_state

    !> The ODE form's Newton matrix from the UCOSUBs' partials.
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)
        type(error_type), allocatable :: error

        if (self%in_speeds()) then
            call self%speeds%jacobian(self%eq, time, y, self%settings%baumgarte(), self%u, &
                & matrix, error)
            ierr = self%keep_failure(error)
            return
        end if
        associate (n => self%eq%n)
            call self%eq%ode_jacobian(time, y(:n), y(n + 1:), self%settings%baumgarte(), matrix, &
                & error)
        end associate
        ierr = self%keep_failure(error)
    end function ode_jacobian

    !> Projection onto the constraints, when the settings ask for it and there are UCONs (in
    !> independent speeds: position UCONs, the velocity ones holding by construction).
    logical function projects(self)
        class(problem_type), intent(in) :: self

        projects = self%settings%drift == drift_projection .and. self%eq%nc > 0
        if (self%in_speeds()) projects = projects .and. self%eq%nh > 0
    end function projects

    !> The mass-weighted correction onto the constraints (exact, one step); in independent
    !> speeds the coordinates' part alone (the rates follow from the speeds at every
    !> evaluation).
    integer function project(self, time, y, correction) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: correction(:)
        type(error_type), allocatable :: error

        if (self%in_speeds()) then
            correction = 0.0_wp
            call self%unpack_state(time, y, self%q, self%u, error)
            if (.not. allocated(error)) call self%eq%project(time, self%q, self%u, &
                & correction(:self%eq%n), self%du, error)
            ierr = self%keep_failure(error)
            return
        end if
        associate (n => self%eq%n)
            call self%eq%project(time, y(:n), y(n + 1:), correction(:n), correction(n + 1:), error)
        end associate
        ierr = self%keep_failure(error)
    end function project

    integer function dae_residual(self, time, y, yp, residual) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:), yp(:)
        real(wp), intent(out) :: residual(:)
        type(error_type), allocatable :: error

        call residual_of_dae(self%eq, time, y, yp, residual, error)
        if (.not. allocated(error) .and. .not. all(ieee_is_finite(residual))) &
            & call nonfinite_state(self, time, y(:self%eq%n), y(self%eq%n + 1:2*self%eq%n), &
            & error)
        ierr = self%keep_failure(error)
    end function dae_residual

    integer function dae_jacobian(self, time, cj, y, yp, matrix, zeroed) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        real(wp), intent(inout) :: matrix(:, :)
        logical, intent(in), optional :: zeroed
        type(error_type), allocatable :: error

        call jacobian_of_dae(self%eq, time, cj, y, yp, matrix, error, zeroed)
        ierr = self%keep_failure(error)
    end function dae_jacobian

    !> q and u differential, the multipliers algebraic.
    function dae_differential(self, n) result(kinds)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: n
        real(wp) :: kinds(n)

        kinds = dae_differential_kinds(self%eq)
    end function dae_differential

    !> Each state's block (rollcon_dynamic_system): the block of its coordinate's UCONs
    !> (rollcon_constraint_blocks), or its part's own past the blocks for a part that no UCON
    !> holds; a rate and an independent speed as their coordinate; IDA's multipliers as their
    !> UCON.
    function state_blocks(self, n) result(blocks)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: n
        integer :: blocks(n)
        integer :: of_coordinate(self%eq%n), b, j, m

        associate (bl => self%eq%blocks, nq => self%eq%n)
            do j = 1, nq
                of_coordinate(j) = bl%count + (j - 1)/6 + 1
            end do
            do b = 1, bl%count
                of_coordinate(bl%coordinates(bl%coordinate_start(b): &
                    & bl%coordinate_start(b + 1) - 1)) = b
            end do
            blocks = 0
            blocks(:nq) = of_coordinate
            if (self%in_speeds()) then
                do m = 1, n - nq
                    blocks(nq + m) = of_coordinate(self%speeds%partition%independent(m))
                end do
            else
                blocks(nq + 1:min(n, 2*nq)) = of_coordinate
                do j = 2*nq + 1, min(n, 2*nq + self%eq%nc)
                    blocks(j) = bl%row_block(j - 2*nq)
                end do
                ! the DAE's mu_h: its position UCON's
                do m = 1, self%eq%nc
                    j = 2*nq + self%eq%nc + self%model%holonomic_number(m)
                    if (self%model%holonomic_number(m) > 0 .and. j <= n) &
                        & blocks(j) = bl%row_block(m)
                end do
            end if
        end associate
    end function state_blocks

    !> Where the DAE's Newton matrix (rollcon_dae's dae_jacobian) can be nonzero: the entries
    !> that routine writes, and no others. Per part, q' = u's diagonal and the momentum rows' 6
    !> by 6 blocks over its q and u (mass, forces); per UCON k over its own coordinates a (its
    !> partials are zero elsewhere): the momentum rows a by the q columns a and by lambda_k, the
    !> UCON's row by q a and u a, and for a position UCON h the q rows a by q a and mu_h, and
    !> mu_h's row by q a. A chain of N links keeps O(N) entries (504 per link), where the
    !> states of neighbouring parts (the pattern before issue #25's third round) kept 1661.
    subroutine dae_pattern(self, n, pattern)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: n
        type(newton_pattern_type), intent(out) :: pattern
        logical, allocatable :: keep(:, :)
        integer :: nq, nc, k, h, j, i0, row, column

        nq = self%eq%n
        nc = self%eq%nc
        allocate(keep(n, n), source=.false.)
        do j = 1, min(nq, n - nq)
            keep(j, nq + j) = .true.
        end do
        do i0 = 0, min(nq, n - nq) - 6, 6
            keep(nq + i0 + 1:nq + i0 + 6, i0 + 1:i0 + 6) = .true.
            keep(nq + i0 + 1:nq + i0 + 6, nq + i0 + 1:nq + i0 + 6) = .true.
        end do
        associate (bl => self%eq%blocks)
            do k = 1, nc
                row = 2*nq + k
                if (row > n) exit
                associate (at => bl%ucon_coordinates(bl%ucon_start(k):bl%ucon_start(k + 1) - 1))
                    keep(nq + at, at) = .true.
                    keep(nq + at, row) = .true.
                    keep(row, at) = .true.
                    keep(row, nq + at) = .true.
                    h = self%model%holonomic_number(k)
                    column = 2*nq + nc + h
                    if (h > 0 .and. column <= n) then
                        keep(at, at) = .true.
                        keep(at, column) = .true.
                        keep(column, at) = .true.
                    end if
                end associate
            end do
        end associate
        call pattern%from_relation(keep)
    end subroutine dae_pattern

    !> A part's three Euler-angle rates are held relative to the largest of them: they are the
    !> components of one angular velocity (docs/design.md §7, IDA's error test). Every other
    !> component alone.
    !> The model's weight, the sum of m |g| [N]: a constraint force's scale, and a constraint
    !> moment's per metre (rollcon_ida: the floor of the multipliers' absolute tolerance).
    function multiplier_scale(self) result(scale)
        class(problem_type), intent(in) :: self
        real(wp) :: scale

        scale = 0.0_wp
        if (allocated(self%model%parts)) scale = sum(self%model%parts%mass) &
            & *norm2(self%model%gravity)
    end function multiplier_scale

    !> Every part's Euler angles and their rates in the DAE state (q, u, lambda, mu): part p's
    !> psi at 6 (p - 1) + coord_psi, its psi' n further.
    function dae_euler_parts(self, n) result(parts)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: n
        integer, allocatable :: parts(:, :)
        integer :: p

        allocate(parts(2, self%eq%n/6))
        do p = 1, self%eq%n/6
            parts(1, p) = 6*(p - 1) + coord_psi
            parts(2, p) = self%eq%n + parts(1, p)
        end do
    end function dae_euler_parts

    !> Number of event functions: every watch's, in watch order.
    integer function root_count(self)
        class(problem_type), intent(in) :: self
        integer :: k

        root_count = 0
        if (.not. allocated(self%watches)) return
        do k = 1, size(self%watches)
            root_count = root_count + self%watches(k)%watch%root_count(self%eq)
        end do
    end function root_count

    !> The event functions at a state of the integrator: (q, u) for CVODE, with its
    !> interpolated y' when given; (q, u, lambda, mu) for IDA.
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)

        type(error_type), allocatable :: error

        associate (n => self%eq%n, nc => self%eq%nc)
            if (self%in_speeds()) then
                ! y' = (u, a_i) carries no whole a: the watches solve for what they need
                call self%unpack_state(time, y, self%q, self%u, error)
                ierr = self%keep_failure(error)
                if (ierr == 0) ierr = self%root_values(time, self%q, self%u, g)
            else if (size(y) > 2*n) then
                ierr = self%root_values(time, y(:n), y(n + 1:2*n), g, lambda=y(2*n + 1:2*n + nc))
            else if (present(ydot)) then
                ierr = self%root_values(time, y(:n), y(n + 1:2*n), g, a=ydot(n + 1:2*n))
            else
                ierr = self%root_values(time, y(:n), y(n + 1:2*n), g)
            end if
        end associate
    end function roots

    !> CVODE should give the event functions y' = (u, a): in the ODE form, when a watch's event
    !> functions use the accelerations. In independent speeds y' = (u, a_i) carries no whole a
    !> (roots solves for what the watches need), so it is never asked for.
    logical function roots_use_rates(self)
        class(problem_type), intent(in) :: self
        integer :: k

        roots_use_rates = .false.
        if (self%settings%formulation /= formulation_cvode .or. .not. allocated(self%watches)) &
            & return
        do k = 1, size(self%watches)
            if (self%watches(k)%watch%roots_use_accelerations(self%eq)) roots_use_rates = .true.
        end do
    end function roots_use_rates

    !> Every watch's event functions at (t, q, u), root_count() of them; lambda or a when the
    !> integrator knows them (rollcon_watch).
    function root_values(self, time, q, u, g, lambda, a) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: lambda(:), a(:)
        integer :: ierr
        type(error_type), allocatable :: error
        integer :: k, first, count

        ierr = 0
        first = 1
        do k = 1, size(self%watches)
            count = self%watches(k)%watch%root_count(self%eq)
            if (count == 0) cycle
            call self%watches(k)%watch%roots(self%eq, self%settings, time, q, u, &
                & g(first:first + count - 1), error, lambda, a)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            first = first + count
        end do
    end function root_values

    !> The watch whose event function `root` is (in root_values' order), and its own number
    !> there.
    pure subroutine root_owner(self, root, watch, k)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: root
        integer, intent(out) :: watch, k
        integer :: count

        k = root
        do watch = 1, size(self%watches)
            count = self%watches(watch)%watch%root_count(self%eq)
            if (k <= count) return
            k = k - count
        end do
        watch = 0
    end subroutine root_owner

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

    !> The first failure a callback kept ("" when none).
    function failure_text(self) result(text)
        class(problem_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
        if (allocated(self%failure)) text = self%failure%message
    end function failure_text

    !> True when the UCONs do no work at the start (t, q), so that they leave the energy
    !> alone: every velocity UCON's F vanishes at zero rates (F = C(q) u: every term carries a
    !> rate, as for a rolling contact on fixed ground) and no position UCON changes with time
    !> alone (F at t and at t + 1 s equal). A moving constraint (a turntable, a driven motion)
    !> fails this, and its constraint forces do work. The check is made at the one state given;
    !> a UCOSUB that cannot be evaluated at zero rates leaves the answer true (the run itself
    !> then reports its error). The UCONs are evaluated, so call this before the run's first
    !> evaluation.
    function ucons_do_no_work(self, time, q) result(no_work)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:)
        logical :: no_work
        !> A homogeneous form gives exact zeros (every term is a product with a rate that is 0),
        !> and a time-free one the same value twice; a moving constraint's terms are of the size
        !> of its motion, many orders above this
        real(wp), parameter :: tol_work = 1.0e-12_wp
        real(wp) :: still(size(q)), now(self%eq%nc)
        type(error_type), allocatable :: error
        integer :: k

        no_work = .true.
        if (self%eq%nc == 0) return
        still = 0.0_wp
        call self%eq%constraints%evaluate(self%model, time, q, still, need_value, error)
        if (allocated(error)) return
        now = self%eq%constraints%value
        call self%eq%constraints%evaluate(self%model, time + 1.0_wp, q, still, need_value, error)
        if (allocated(error)) return
        do k = 1, self%eq%nc
            if (self%model%ucons(k)%holonomic) then
                if (abs(self%eq%constraints%value(k) - now(k)) > tol_work) no_work = .false.
            else
                if (abs(now(k)) > tol_work .or. abs(self%eq%constraints%value(k)) > tol_work) &
                    & no_work = .false.
            end if
        end do
    end function ucons_do_no_work

    !> Free what the problem holds outside Fortran's memory (its equations' KLU factors): a
    !> process running many models one after another (a study's cases) would keep every one's
    !> until it ends.
    subroutine release_problem(self)
        class(problem_type), intent(inout) :: self

        call self%eq%release()
        call self%speeds%partition%release()
    end subroutine release_problem

end module rollcon_problem
