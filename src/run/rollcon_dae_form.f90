! SPDX-License-Identifier: MIT
!> The DAE form of a problem (docs/design.md §4, formulation 'ida'), the DAE system IDA
!> integrates: y = (q, u, lambda, mu, x), one mu per position UCON (the GGL form), x the
!> DIFFs' states, and its residual and Newton matrix (rollcon_dae; the DIFFs' residuals G and
!> their exact partials, rollcon_diff, in the last rows: diff_entries); the multipliers
!> algebraic; the Newton matrix's
!> pattern over each part and each UCON's own coordinates; the watches' event functions, given
!> the multipliers the state holds.
module rollcon_dae_form
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_dae, only : dae_size, dae_differential_kinds => dae_differential, &
        & residual_of_dae => dae_residual, jacobian_of_dae => dae_jacobian, &
        & sparse_jacobian_of_dae => dae_sparse_jacobian, newton_places_type
    use rollcon_int_buffer, only : append
    use rollcon_dynamic_system, only : dae_system_type
    use rollcon_newton_pattern, only : newton_pattern_type
    use rollcon_output_layout, only : coord_psi
    use rollcon_problem, only : problem_type
    use rollcon_error, only : fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_user_forces, only : take_user_force_error, set_system_accelerations
    use rollcon_force, only : profile_statement
    use rollcon_force_partials, only : statement_parts
    implicit none
    private

    public :: dae_form_type

    !> The DAE form of a problem
    type, extends(dae_system_type) :: dae_form_type
        !> The problem it integrates: its model, equations, settings and watches
        type(problem_type), pointer :: problem => null()
        !> Where the sparse Newton matrix's writes went at its last evaluation (rollcon_dae)
        type(newton_places_type) :: places
    contains
        procedure :: init
        procedure :: state_size
        procedure :: pack_state
        procedure :: unpack_state
        procedure :: dae_residual
        procedure :: dae_jacobian
        procedure :: dae_sparse_jacobian
        procedure :: dae_differential
        procedure :: dae_pattern
        procedure :: dae_euler_parts
        procedure :: multiplier_scale
        procedure :: state_blocks
        procedure :: root_count
        procedure :: roots
        procedure :: failure_text
        procedure :: power_count
        procedure :: powers
    end type dae_form_type

contains

    !> The DAE form of problem (prepared: rollcon_problem's prepare), which must outlive it.
    subroutine init(self, problem)
        class(dae_form_type), intent(inout) :: self
        type(problem_type), intent(inout), target :: problem

        self%problem => problem
    end subroutine init

    !> 2n + nc + nh: the coordinates, the rates, a multiplier per UCON and one per position
    !> UCON (rollcon_dae).
    integer function state_size(self)
        class(dae_form_type), intent(in) :: self

        state_size = dae_size(self%problem%eq) + self%problem%model%diffs%count()
    end function state_size

    !> y = (q, u, lambda, 0), y' = (u, a, 0, 0) with the accelerations and multipliers of the
    !> problem's last evaluation (mu = 0: the GGL multipliers vanish on a consistent state).
    subroutine pack_state(self, q, u, y, yp)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)

        associate (n => self%problem%eq%n, nc => self%problem%eq%nc)
            y = 0.0_wp
            yp = 0.0_wp
            y(:n) = q
            y(n + 1:2*n) = u
            y(2*n + 1:2*n + nc) = self%problem%lambda
            yp(:n) = u
            yp(n + 1:2*n) = self%problem%a
            associate (diffs => self%problem%model%diffs, m => dae_size(self%problem%eq))
                if (diffs%count() > 0) then
                    y(m + 1:) = diffs%x
                    yp(m + 1:) = diffs%w/diffs%time_unit
                end if
            end associate
        end associate
    end subroutine pack_state

    !> (q, u), y's own.
    subroutine unpack_state(self, time, y, q, u, error)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        associate (n => self%problem%eq%n, model => self%problem%model, &
                & m => dae_size(self%problem%eq))
            q = y(:n)
            u = y(n + 1:2*n)
            if (model%diffs%count() > 0) call model%set_diff_state(y(m + 1:), model%diffs%w)
        end associate
    end subroutine unpack_state

    !> F(t, y, y') of rollcon_dae; ierr 0 on success, -1 on failure (kept as the problem's
    !> failure, a residual that is not finite named by its cause).
    integer function dae_residual(self, time, y, yp, residual) result(ierr)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:), yp(:)
        real(wp), intent(out) :: residual(:)
        type(error_type), allocatable :: error

        associate (problem => self%problem, n => self%problem%eq%n, &
                & m => dae_size(self%problem%eq), diffs => self%problem%model%diffs)
            if (diffs%count() > 0) call problem%model%set_diff_state(y(m + 1:), &
                & yp(m + 1:)*diffs%time_unit)
            call residual_of_dae(problem%eq, time, y(:m), yp(:m), residual(:m), error)
            ! a DIFSUB reading accelerations reads IDA's u'
            if (diffs%count() > 0) then
                if (diffs%reads_accelerations()) call set_system_accelerations(yp(n + 1:2*n))
            end if
            if (.not. allocated(error) .and. diffs%count() > 0) call diffs%residuals(time, &
                & y(:n), y(n + 1:2*n), y(m + 1:), yp(m + 1:)*diffs%time_unit, residual(m + 1:))
            ! a DIFSUB that failed: its error, naming it
            if (.not. allocated(error) .and. diffs%count() > 0) call take_user_force_error(error)
            if (.not. allocated(error) .and. .not. all(ieee_is_finite(residual))) then
                if (all(ieee_is_finite(residual(:m)))) then
                    call fatal_error(error, trim(diffs%diffs(findloc(ieee_is_finite( &
                        & residual(m + 1:)), .false., dim=1))%name) // " FUNCTION is not " &
                        & // "finite at t = " // to_text(time) // " s", stat_solver)
                else
                    call problem%nonfinite_state(time, y(:n), y(n + 1:2*n), error)
                end if
            end if
            ierr = problem%keep_failure(error)
        end associate
    end function dae_residual

    !> The Newton matrix of rollcon_dae from the UCOSUBs' partials, and the DIFFs' rows
    !> (diff_entries).
    integer function dae_jacobian(self, time, cj, y, yp, matrix) result(ierr)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        real(wp), intent(inout) :: matrix(:, :)
        type(error_type), allocatable :: error

        associate (m => dae_size(self%problem%eq), diffs => self%problem%model%diffs)
            if (diffs%count() == 0) then
                call jacobian_of_dae(self%problem%eq, time, cj, y, yp, matrix, error)
            else
                call self%problem%model%set_diff_state(y(m + 1:), yp(m + 1:)*diffs%time_unit)
                matrix = 0.0_wp
                call jacobian_of_dae(self%problem%eq, time, cj, y(:m), yp(:m), &
                    & matrix(:m, :m), error)
                if (.not. allocated(error)) call diff_entries(self, time, cj, y, yp, &
                    & dense=matrix)
            end if
        end associate
        ierr = self%problem%keep_failure(error)
    end function dae_jacobian

    !> The same Newton matrix over dae_pattern's entries (rollcon_dae's dae_sparse_jacobian).
    integer function dae_sparse_jacobian(self, time, cj, y, yp, starts, rows, values) &
            & result(ierr)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable :: error

        associate (m => dae_size(self%problem%eq), diffs => self%problem%model%diffs)
            if (diffs%count() == 0) then
                call sparse_jacobian_of_dae(self%problem%eq, time, cj, y, yp, starts, rows, &
                    & values, error, self%places)
            else
                call self%problem%model%set_diff_state(y(m + 1:), yp(m + 1:)*diffs%time_unit)
                call sparse_jacobian_of_dae(self%problem%eq, time, cj, y(:m), yp(:m), starts, &
                    & rows, values, error, self%places)
                if (.not. allocated(error)) call diff_entries(self, time, cj, y, yp, &
                    & starts=starts, rows=rows, values=values)
            end if
        end associate
        ierr = self%problem%keep_failure(error)
    end function dae_sparse_jacobian

    !> The DIFFs' rows of the Newton matrix dF/dy + cj dF/dy' (rollcon_diff's exact partials):
    !> row m + k by q, u (dG_k/dq, dG_k/du + cj dG_k/da for a DIFSUB reading the
    !> accelerations, IDA's u': rollcon_diff's acceleration_partials), by the multipliers of
    !> the rows whose reactions a DIFSUB's force measures read (dG_k/dlambda, IDA's lambda:
    !> rollcon_diff's multiplier_partials, differenced over the rows its initialisation call
    !> declared; a row set aside carries no reaction, its column none) and by x (dG_k/dx + cj
    !> T dG_k/dw, w = T x'),
    !> into the dense matrix or the compressed columns (dae_pattern keeps these entries). The
    !> momentum rows' partials in x (a force that reads DIF) are left out, as the expression
    !> forces' other partials are.
    subroutine diff_entries(self, time, cj, y, yp, dense, starts, rows, values)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        real(wp), intent(inout), optional :: dense(:, :)
        integer, intent(in), optional :: starts(:), rows(:)
        real(wp), intent(inout), optional :: values(:)
        real(wp), allocatable :: g(:), g_q(:, :), g_u(:, :), g_x(:, :), g_w(:, :), g_a(:, :), &
            & g_lambda(:, :)
        integer :: n, m, nd, k, j, r

        n = self%problem%eq%n
        m = dae_size(self%problem%eq)
        associate (diffs => self%problem%model%diffs)
            nd = diffs%count()
            allocate(g(nd), g_q(nd, n), g_u(nd, n), g_x(nd, nd), g_w(nd, nd))
            if (diffs%reads_accelerations()) call set_system_accelerations(yp(n + 1:2*n))
            call diffs%partials(time, y(:n), y(n + 1:2*n), y(m + 1:), &
                & yp(m + 1:)*diffs%time_unit, g, g_q, g_u, g_x, g_w)
            if (diffs%reads_accelerations()) then
                allocate(g_a(nd, n))
                call diffs%acceleration_partials(time, y(:n), y(n + 1:2*n), y(m + 1:), &
                    & yp(m + 1:)*diffs%time_unit, yp(n + 1:2*n), g_a)
                g_u = g_u + cj*g_a
            end if
            g_x = g_x + cj*diffs%time_unit*g_w
            if (diffs%reads_constraint_forces()) then
                ! the multipliers the residual's DIFSUBs read: IDA's (rollcon_dae's
                ! set_reactions, made by the momentum rows' Newton matrix before)
                allocate(g_lambda(nd, self%problem%eq%nc))
                call diffs%multiplier_partials(time, y(:n), y(n + 1:2*n), y(m + 1:), &
                    & yp(m + 1:)*diffs%time_unit, g_lambda)
                associate (redundancy => self%problem%eq%redundancy)
                    if (redundancy%set_aside > 0) then
                        do r = 1, size(g_lambda, 2)
                            if (.not. redundancy%active(r)) g_lambda(:, r) = 0.0_wp
                        end do
                    end if
                end associate
                do k = 1, nd
                    if (.not. allocated(diffs%diffs(k)%declaration%rows)) cycle
                    do j = 1, size(diffs%diffs(k)%declaration%rows)
                        r = diffs%diffs(k)%declaration%rows(j)
                        call put(m + k, 2*n + r, g_lambda(k, r))
                    end do
                end do
            end if
            do k = 1, nd
                do j = 1, n
                    call put(m + k, j, g_q(k, j))
                    call put(m + k, n + j, g_u(k, j))
                end do
                do j = 1, nd
                    call put(m + k, m + j, g_x(k, j))
                end do
            end do
        end associate

    contains

        !> Entry (i, j) set (in the pattern: found by bisection of column j's 0-based rows).
        subroutine put(i, j, value)
            integer, intent(in) :: i, j
            real(wp), intent(in) :: value
            integer :: low, high, middle

            if (present(dense)) then
                dense(i, j) = value
                return
            end if
            low = starts(j) + 1
            high = starts(j + 1)
            do while (low <= high)
                middle = (low + high)/2
                if (rows(middle) == i - 1) then
                    values(middle) = value
                    return
                else if (rows(middle) < i - 1) then
                    low = middle + 1
                else
                    high = middle - 1
                end if
            end do
        end subroutine put
    end subroutine diff_entries

    !> q and u differential, the multipliers algebraic, the DIFFs' states differential.
    function dae_differential(self, n) result(kinds)
        class(dae_form_type), intent(in) :: self
        integer, intent(in) :: n
        real(wp) :: kinds(n)
        integer :: m

        m = dae_size(self%problem%eq)
        kinds(:m) = dae_differential_kinds(self%problem%eq)
        kinds(m + 1:) = 1.0_wp
    end function dae_differential

    !> Where the Newton matrix (rollcon_dae's dae_jacobian) can be nonzero: the entries that
    !> routine writes, and no others. Per part, q' = u's diagonal and the momentum rows' 6 by 6
    !> blocks over its q and u (mass, forces), and over the q and u of each part a SPRINGDAMPER
    !> or BUSHING joins it to; per UCON k over its own coordinates a (its
    !> partials are zero elsewhere): the momentum rows a by the q columns a and by lambda_k, the
    !> UCON's row by q a and u a, and for a position UCON h the q rows a by q a and mu_h, and
    !> mu_h's row by q a. A chain of N links keeps O(N) entries (504 per link), where every
    !> state of neighbouring parts by every other would keep 1661. A model with rows set aside
    !> (rollcon_redundancy) keeps the diagonal of every lambda_k and mu_h too, where a row set
    !> aside has its equation lambda_k = 0 (mu_h = 0): whichever rows a choice again sets aside.
    !> A contact whose modes are watched keeps the diagonal of its three rows (a mode drops
    !> them), and a contact or a rim's dissipation the column of its normal multiplier in the
    !> part's momentum rows (sliding's friction, rolling resistance: rollcon_dae).
    !> Gathered as each element's entries (rollcon_newton_pattern's from_entries): memory and
    !> time O(entries), no n x n array.
    subroutine dae_pattern(self, n, pattern)
        class(dae_form_type), intent(in) :: self
        integer, intent(in) :: n
        type(newton_pattern_type), intent(out) :: pattern
        integer, allocatable :: rows(:), columns(:), parts(:)
        integer :: nq, nc, k, h, j, i0, row, column, count, a, b

        ! each element's block as a list of entries (repeats dropped by from_entries): memory
        ! O(entries), no n x n relation
        nq = self%problem%eq%n
        nc = self%problem%eq%nc
        count = 0
        allocate(rows(0), columns(0))
        do j = 1, min(nq, n - nq)
            call keep(j, nq + j)
        end do
        do i0 = 0, min(nq, n - nq) - 6, 6
            do b = i0 + 1, i0 + 6
                do a = i0 + 1, i0 + 6
                    call keep(nq + a, b)
                    call keep(nq + a, nq + b)
                end do
            end do
        end do
        ! a SPRINGDAMPER's or BUSHING's momentum rows of each part by the other's q and u
        associate (pairs => self%problem%eq%couplings)
            do k = 1, size(pairs, 2)
                if (6*max(pairs(1, k), pairs(2, k)) > min(nq, n - nq)) cycle
                call keep_coupling(pairs(1, k), pairs(2, k))
                call keep_coupling(pairs(2, k), pairs(1, k))
            end do
        end associate
        associate (bl => self%problem%eq%blocks)
            do k = 1, nc
                row = 2*nq + k
                if (row > n) exit
                associate (at => bl%ucon_coordinates(bl%ucon_start(k):bl%ucon_start(k + 1) - 1))
                    h = self%problem%model%holonomic_number(k)
                    column = 2*nq + nc + h
                    do b = 1, size(at)
                        do a = 1, size(at)
                            call keep(nq + at(a), at(b))
                            if (h > 0 .and. column <= n) call keep(at(a), at(b))
                        end do
                        call keep(nq + at(b), row)
                        call keep(row, at(b))
                        call keep(row, nq + at(b))
                        if (h > 0 .and. column <= n) then
                            call keep(at(b), column)
                            call keep(column, at(b))
                        end if
                    end do
                    if (self%problem%eq%redundancy%set_aside > 0) then
                        call keep(row, row)
                        if (h > 0 .and. column <= n) call keep(column, column)
                    end if
                end associate
            end do
        end associate
        ! a force whose routine reads a constraint's reaction: the momentum rows of the parts
        ! it loads by the multipliers of the rows it declared (rollcon_dae)
        if (allocated(self%problem%model%forces)) then
            do k = 1, size(self%problem%model%forces)
                associate (force => self%problem%model%forces(k))
                    if (force%profile /= profile_statement) cycle
                    if (.not. allocated(force%statement%declared_rows)) cycle
                    parts = statement_parts(force%statement)
                    do j = 1, size(force%statement%declared_rows)
                        column = 2*nq + force%statement%declared_rows(j)
                        if (column > n) cycle
                        do b = 1, size(parts)
                            do a = 1, 6
                                if (6*(parts(b) - 1) + a > min(nq, n - nq)) cycle
                                call keep(nq + 6*(parts(b) - 1) + a, column)
                            end do
                        end do
                    end do
                end associate
            end do
        end if
        ! a contact's modes (rollcon_contact_watch) and a rim's dissipation: the rows a mode
        ! drops keep their diagonal (lambda_k = 0), and the part's momentum rows its normal
        ! multiplier's column (sliding's friction, rolling resistance: rollcon_dae's
        ! add_mode_forces); their partials in q and u are in the part's blocks
        associate (contact => self%problem%eq%contact, diss => self%problem%eq%dissipation)
            if (contact%normal > 0) then
                do k = 1, 2
                    if (2*nq + contact%tangential(k) <= n) call keep(2*nq &
                        & + contact%tangential(k), 2*nq + contact%tangential(k))
                end do
                call keep_normal(contact%height_column, contact%normal)
            end if
            if (diss%part > 0) call keep_normal(diss%height_column, diss%normal)
        end associate
        ! each DIFF's row by every q and u (it may read any part), by the multipliers of the
        ! rows whose reactions its DIFSUB declared, and by every DIFF's state
        associate (m => dae_size(self%problem%eq), nd => self%problem%model%diffs%count(), &
                & diffs => self%problem%model%diffs%diffs)
            do k = 1, nd
                if (m + k > n) exit
                do j = 1, 2*nq
                    call keep(m + k, j)
                end do
                if (allocated(diffs(k)%declaration%rows)) then
                    do j = 1, size(diffs(k)%declaration%rows)
                        if (diffs(k)%declaration%rows(j) <= nc) &
                            & call keep(m + k, 2*nq + diffs(k)%declaration%rows(j))
                    end do
                end if
                do j = 1, nd
                    call keep(m + k, m + j)
                end do
            end do
        end associate
        call pattern%from_entries(n, rows, columns, count)

    contains

        !> Entry (i, j) kept.
        subroutine keep(i, j)
            integer, intent(in) :: i, j
            integer :: counted

            counted = count
            call append(rows, counted, i)
            call append(columns, count, j)
        end subroutine keep

        !> The diagonal of normal row n_row, and its column in the momentum rows of the part
        !> whose height is coordinate z.
        subroutine keep_normal(z, n_row)
            integer, intent(in) :: z, n_row
            integer :: i0, ia

            if (2*nq + n_row > n .or. z < 1 .or. z > nq) return
            call keep(2*nq + n_row, 2*nq + n_row)
            i0 = 6*((z - 1)/6)
            do ia = 1, 6
                call keep(nq + i0 + ia, 2*nq + n_row)
            end do
        end subroutine keep_normal

        !> The momentum rows of part a by part b's coordinates and rates.
        subroutine keep_coupling(a, b)
            integer, intent(in) :: a, b
            integer :: ia, jb

            do jb = 1, 6
                do ia = 1, 6
                    call keep(nq + 6*(a - 1) + ia, 6*(b - 1) + jb)
                    call keep(nq + 6*(a - 1) + ia, nq + 6*(b - 1) + jb)
                end do
            end do
        end subroutine keep_coupling
    end subroutine dae_pattern

    !> Every part's Euler angles and their rates in the DAE state (q, u, lambda, mu): part p's
    !> psi at 6 (p - 1) + coord_psi, its psi' n further (IDA's error weights, docs/design.md §7).
    function dae_euler_parts(self, n) result(parts)
        class(dae_form_type), intent(in) :: self
        integer, intent(in) :: n
        integer, allocatable :: parts(:, :)
        integer :: p

        allocate(parts(2, self%problem%eq%n/6))
        do p = 1, self%problem%eq%n/6
            parts(1, p) = 6*(p - 1) + coord_psi
            parts(2, p) = self%problem%eq%n + parts(1, p)
        end do
    end function dae_euler_parts

    !> The model's weight, the sum of m |g| [N]: a constraint force's scale, and a constraint
    !> moment's per metre (rollcon_ida: the floor of the multipliers' absolute tolerance).
    function multiplier_scale(self) result(scale)
        class(dae_form_type), intent(in) :: self
        real(wp) :: scale

        scale = 0.0_wp
        associate (model => self%problem%model)
            if (allocated(model%parts)) scale = sum(model%parts%mass)*norm2(model%gravity)
        end associate
    end function multiplier_scale

    !> A coordinate and its rate are of the coordinate's block (rollcon_problem's
    !> coordinate_blocks), a multiplier lambda_k or mu_h of its UCON's.
    function state_blocks(self, n) result(blocks)
        class(dae_form_type), intent(in) :: self
        integer, intent(in) :: n
        integer :: blocks(n)
        integer :: j, m

        associate (bl => self%problem%eq%blocks, nq => self%problem%eq%n, &
                & nc => self%problem%eq%nc, model => self%problem%model)
            if (model%diffs%count() > 0) then
                ! a DIFF may read every part: one block
                blocks = 1
                return
            end if
            blocks = 0
            blocks(:nq) = self%problem%coordinate_blocks()
            blocks(nq + 1:min(n, 2*nq)) = blocks(:min(nq, n - nq))
            do j = 2*nq + 1, min(n, 2*nq + nc)
                blocks(j) = bl%row_block(j - 2*nq)
            end do
            ! mu_h: its position UCON's
            do m = 1, nc
                j = 2*nq + nc + model%holonomic_number(m)
                if (model%holonomic_number(m) > 0 .and. j <= n) blocks(j) = bl%row_block(m)
            end do
        end associate
    end function state_blocks

    !> Every watch's event functions.
    integer function root_count(self)
        class(dae_form_type), intent(in) :: self

        root_count = self%problem%root_count()
    end function root_count

    !> The watches' event functions at y = (q, u, lambda, mu), given the multipliers (IDA
    !> gives no y').
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)

        associate (n => self%problem%eq%n, nc => self%problem%eq%nc, &
                & model => self%problem%model)
            ! the DIFFs' state at y, for the forces' switches that read it
            if (model%diffs%count() > 0) call model%set_diff_state(y(size(y) &
                & - model%diffs%count() + 1:), model%diffs%w)
            if (size(y) > 2*n) then
                ierr = self%problem%root_values(time, y(:n), y(n + 1:2*n), g, &
                    & lambda=y(2*n + 1:2*n + nc))
            else
                ! no UCON: no multipliers
                ierr = self%problem%root_values(time, y(:n), y(n + 1:2*n), g)
            end if
        end associate
    end function roots

    !> The first failure a callback kept ("" when none).
    function failure_text(self) result(text)
        class(dae_form_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = self%problem%failure_text()
    end function failure_text

    !> The powers the problem dissipates: rollcon_problem's power_count.
    integer function power_count(self)
        class(dae_form_type), intent(in) :: self

        power_count = self%problem%power_count()
    end function power_count

    !> The powers dissipated at the state y at time [s] [W]: rollcon_problem's state_powers,
    !> (q, u) read from y by this form's unpack_state.
    integer function powers(self, time, y, values) result(ierr)
        class(dae_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: values(:)

        ierr = self%problem%state_powers(self, time, y, values)
    end function powers

end module rollcon_dae_form
