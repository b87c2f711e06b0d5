! SPDX-License-Identifier: MIT
!> The formulation in independent speeds (docs/design.md §4, 'maggi'): the state is
!> y = (q, v), the coordinates and the n - nc independent rates of a partition
!> (rollcon_speed_partition). At every evaluation the dependent rates are solved from the
!> velocity-level constraints, so the velocity UCONs hold exactly:
!>
!>     C_d u_d = -r(q, u0),   u0 = (u_d = 0, u_i = v),
!>     r_k = F_k (velocity UCON),  r_h = dF_h/dq u + dF_h/dt + alpha F_h (position UCON),
!>
!> and alpha (the Baumgarte rate in effect) makes a position UCON's drift decay,
!> F_h' = -alpha F_h. Then y' = (u, a_i) with a the accelerations of the saddle-point system
!> (rollcon_equations, with the same alpha: on the partition's manifold its gamma is exactly
!> the derivative of the dependent-speed equations). This is coordinate partitioning; it has
!> the motion of Maggi's equations N^T M N v' = N^T (f - M N' v) with N = [-C_d^-1 C_i; I].
!> Its Newton matrix follows by the chain rule from the ODE form's (rollcon_equations):
!> d(u, a_i)/d(q, v) with du_d/dq = -C_d^-1 dr/dq and du_d/dv = -C_d^-1 C_i. The dependent
!> speeds are numbered by the partition's slots (rollcon_speed_partition). Rows set aside as
!> redundant (rollcon_redundancy) are not partitioned: nc is the active rows, and the n - nc
!> independent speeds are the mechanism's own.
module rollcon_independent_speeds
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_text, only : to_text
    use rollcon_constraints, only : local_dot, need_value, need_first, need_time
    use rollcon_equations, only : equations_type
    use rollcon_speed_partition, only : speed_partition_type
    implicit none
    private

    public :: independent_speeds_type

    !> The partition and the workspace of the formulation (allocated in init; the Newton
    !> matrix's, dense or by blocks, by its first evaluations)
    type :: independent_speeds_type
        !> Rates, constraint rows partitioned (the active ones), independent speeds n - nc, and
        !> the model's rows (active or set aside)
        integer :: n = 0, nc = 0, ni = 0, rows = 0
        !> Which rows were active when the partition was sized (init)
        logical, allocatable :: active(:)
        type(speed_partition_type) :: partition
        !> The dense Newton matrix's (jacobian): the ODE form's Jacobian d(q', u')/d(q, u)
        !> (2n x 2n), -C_d^-1 dr/dq (nc x n) and -C_d^-1 C_i (nc x ni), the dependent speeds'
        !> partials (allocated by its first evaluation: none on the sparse path)
        real(wp), allocatable :: full(:, :)
        real(wp), allocatable :: dud_dq(:, :), dud_dv(:, :)
        !> The sparse Newton matrix's (jacobian_blocks): one block's dependent speeds' partials
        !> (its UCONs x its coordinates, x its independent speeds; grown to the largest block
        !> by the first evaluations), each coordinate's slot (0: independent) and independent
        !> speed (0: dependent), each slot's row in its block's, one block's independent
        !> speeds' coordinates
        real(wp), allocatable :: block_dq(:, :), block_dv(:, :)
        integer, allocatable :: slot_of(:), speed_of(:), local_row(:), block_speeds(:)
        !> Right-hand side of the dependent speeds' solve (nc)
        real(wp), allocatable :: r(:)
    contains
        procedure :: init
        procedure :: state_size
        procedure :: choose
        procedure :: pack
        procedure :: speeds
        procedure :: rhs
        procedure :: jacobian
        procedure :: by_blocks
        procedure :: jacobian_blocks
    end type independent_speeds_type

contains

    !> Size for the equations eq (initialised on their model) and the rows active in them now.
    subroutine init(self, eq)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq

        self%n = eq%n
        self%rows = eq%nc
        self%active = eq%active_rows()
        self%nc = count(self%active)
        self%ni = eq%n - self%nc
        if (self%nc == self%rows) then
            call self%partition%init(self%n, self%nc, eq%blocks)
        else
            call self%partition%init(self%n, self%nc, eq%blocks%active_subset(self%active), &
                & self%rows)
        end if
        if (allocated(self%full)) deallocate(self%full, self%dud_dq, self%dud_dv)
        if (allocated(self%block_dq)) deallocate(self%block_dq, self%block_dv)
        if (allocated(self%r)) deallocate(self%r, self%slot_of, self%speed_of, self%local_row, &
            & self%block_speeds)
        allocate(self%r(max(self%rows, 1)), source=0.0_wp)
        allocate(self%slot_of(self%n), self%speed_of(self%n), self%local_row(max(self%rows, 1)), &
            & self%block_speeds(self%n), source=0)
    end subroutine init

    !> Size of the integrator's state: n coordinates and n - nc independent speeds.
    pure integer function state_size(self)
        class(independent_speeds_type), intent(in) :: self

        state_size = self%n + self%ni
    end function state_size

    !> Choose the partition at (q, u) from the constraint matrix eq%c (C by rows over each
    !> UCON's own coordinates) as the last evaluation left it (an accelerations call at that
    !> state).
    subroutine choose(self, eq, error)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        type(error_type), allocatable, intent(out) :: error

        call self%partition%choose(eq%c, error)
    end subroutine choose

    !> y = (q, u_i) for the partition chosen.
    pure subroutine pack(self, q, u, y)
        class(independent_speeds_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:)

        y(:self%n) = q
        y(self%n + 1:) = u(self%partition%independent)
    end subroutine pack

    !> The rates u at (t, q) from the independent speeds v: the dependent ones solved from the
    !> velocity-level constraints (module text), alpha the Baumgarte rate in effect [1/s].
    !> Leaves eq%c (C by rows) and C_d's factors at q.
    subroutine speeds(self, eq, time, q, v, alpha, u, error)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:), v(:), alpha
        real(wp), intent(out) :: u(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: k, needs

        u = 0.0_wp
        u(self%partition%independent) = v
        if (self%nc == 0) return
        needs = need_value + need_first
        if (eq%nh > 0) needs = needs + need_time
        call eq%constraints%evaluate(eq%model, time, q, u, needs, error)
        if (allocated(error)) return
        call eq%constraint_matrix()
        associate (cs => eq%constraints)
            do k = 1, self%rows
                if (eq%model%ucons(k)%holonomic) then
                    ! over the UCON's own coordinates (its partials are zero elsewhere): the
                    ! dense sum's nonzero terms in their order, O(1) a UCON, not O(n)
                    self%r(k) = -(cs%grad_q_dot(k, u) + cs%dt(k) + alpha*cs%value(k))
                else
                    self%r(k) = -cs%value(k)
                end if
            end do
        end associate
        call self%partition%factor(eq%c, error)
        if (allocated(error)) return
        call self%partition%solve(self%r, 1, error)
        if (allocated(error)) return
        u(self%partition%dependent) = self%r(:self%nc)
    end subroutine speeds

    !> y' = (u, a_i) at (t, y), y = (q, v); u, a and lambda of the whole system are left in
    !> the arguments.
    subroutine rhs(self, eq, time, y, alpha, ydot, u, a, lambda, error)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, y(:), alpha
        real(wp), intent(out) :: ydot(:), u(:), a(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error

        associate (n => self%n)
            call self%speeds(eq, time, y(:n), y(n + 1:), alpha, u, error)
            if (allocated(error)) return
            call eq%accelerations(time, y(:n), u, alpha, a, lambda, error)
            if (allocated(error)) return
            ydot(:n) = u
            ydot(n + 1:) = a(self%partition%independent)
        end associate
    end subroutine rhs

    !> d(u, a_i)/d(q, v) at (t, y) by the chain rule through the ODE form's Jacobian (module
    !> text); u is work space of size n.
    subroutine jacobian(self, eq, time, y, alpha, u, jac, error)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, y(:), alpha
        real(wp), intent(out) :: u(:)
        !> (n + ni) square
        real(wp), intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, nc, ni, i, j, jj, k, row, x

        n = self%n
        nc = self%nc
        ni = self%ni
        call self%speeds(eq, time, y(:n), y(n + 1:), alpha, u, error)
        if (allocated(error)) return
        if (.not. allocated(self%full)) allocate(self%full(2*n, 2*n), &
            & self%dud_dq(max(self%rows, 1), n), self%dud_dv(max(self%rows, 1), ni), &
            & source=0.0_wp)
        ! C_d's factors stay those of q: the evaluation below changes neither q nor C
        call eq%ode_jacobian(time, y(:n), u, alpha, self%full, error)
        if (allocated(error)) return
        jac = 0.0_wp
        if (nc > 0) then
            ! dr/dq at fixed u (module text), then -C_d^-1 of it; -C_d^-1 C_i
            associate (cs => eq%constraints)
                do k = 1, self%rows
                    if (eq%model%ucons(k)%holonomic) then
                        ! d2F/dq dq's column j and dF/dq's entry are zero off the UCON's own
                        ! coordinates: there the sum below is -(0 + 0 + alpha 0)
                        do j = 1, n
                            self%dud_dq(k, j) = -(0.0_wp + 0.0_wp + alpha*0.0_wp)
                        end do
                        associate (at => cs%local(:cs%local_count(k), k))
                            do jj = 1, size(at)
                                j = at(jj)
                                self%dud_dq(k, j) = -(local_dot(cs%hqq(:, jj, k), u, at) &
                                    & + cs%dt_grad_q(jj, k) + alpha*cs%grad_q_local(jj, k))
                            end do
                        end associate
                    else
                        call cs%fill_grad_q_row(k, self%dud_dq(k, :))
                        self%dud_dq(k, :) = -self%dud_dq(k, :)
                    end if
                    ! -C(k, independent speeds): -0 off the UCON's own coordinates, as the
                    ! dense row's zeros negated
                    do j = 1, ni
                        self%dud_dv(k, j) = -0.0_wp
                    end do
                    do x = eq%c%start(k), eq%c%start(k + 1) - 1
                        j = independent_slot(self%partition%independent, eq%c%column(x))
                        if (j > 0) self%dud_dv(k, j) = -eq%c%value(x)
                    end do
                end do
            end associate
            call self%partition%solve(self%dud_dq, n, error)
            if (allocated(error)) return
            call self%partition%solve(self%dud_dv, ni, error)
            if (allocated(error)) return
        end if
        ! rows of q' = u
        do k = 1, nc
            jac(self%partition%dependent(k), :n) = self%dud_dq(k, :)
            jac(self%partition%dependent(k), n + 1:) = self%dud_dv(k, :)
        end do
        do i = 1, ni
            jac(self%partition%independent(i), n + i) = 1.0_wp
        end do
        ! rows of v' = a_i: da_i/dq + da_i/du_d du_d/dq, da_i/du_i + da_i/du_d du_d/dv
        do i = 1, ni
            row = n + self%partition%independent(i)
            jac(n + i, :n) = self%full(row, :n)
            do j = 1, ni
                jac(n + i, n + j) = self%full(row, n + self%partition%independent(j))
            end do
            do k = 1, nc
                associate (slope => self%full(row, n + self%partition%dependent(k)))
                    ! zero across blocks: skipping those keeps N parts N times one
                    if (slope == 0.0_wp) cycle
                    jac(n + i, :n) = jac(n + i, :n) + slope*self%dud_dq(k, :)
                    jac(n + i, n + 1:) = jac(n + i, n + 1:) + slope*self%dud_dv(k, :)
                end associate
            end do
        end do
    end subroutine jacobian

    !> The slot of coordinate j among the independent speeds (ascending) by bisection; 0 when
    !> j is a dependent speed.
    pure integer function independent_slot(independent, j) result(slot)
        integer, intent(in) :: independent(:), j
        integer :: low, high, middle

        slot = 0
        low = 1
        high = size(independent)
        do while (low <= high)
            middle = (low + high)/2
            if (independent(middle) == j) then
                slot = middle
                return
            else if (independent(middle) < j) then
                low = middle + 1
            else
                high = middle - 1
            end if
        end do
    end function independent_slot

    !> The Newton matrix can be formed by blocks (jacobian_blocks): no rows set aside (the
    !> partition's blocks are then the equations') and no algebraic loop.
    logical function by_blocks(self, eq)
        class(independent_speeds_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        by_blocks = self%nc == self%rows .and. .not. eq%reads_loop()
    end function by_blocks

    !> jacobian's matrix d(u, a_i)/d(q, v) over the pattern of the form's state blocks,
    !> compressed by columns (CVODE's sparse Newton matrix): column j's rows (0-based,
    !> ascending) rows(starts(j) + 1 : starts(j + 1)) are the coordinates of state j's block,
    !> then its block's independent speeds (n + i), values written at the same places; formed
    !> block by block with no n x n array: the ODE form's block (the equations'
    !> jacobian_block), the dependent speeds' partials over the block's UCONs and columns,
    !> C_d^-1 by the partition's blocks there (solve_block), and the chain rule's sums as
    !> jacobian makes them (over the block's slots, ascending: the others add exact zeros it
    !> skips), so each entry is jacobian's bit for bit. Only where by_blocks; u is work space
    !> of size n.
    subroutine jacobian_blocks(self, eq, time, y, alpha, u, starts, rows, values, error)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, y(:), alpha
        real(wp), intent(out) :: u(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, j, nb, nv, listed, m, i, b, r, x, k, c, s, t, a, slot, v0

        n = self%n
        call self%speeds(eq, time, y(:n), y(n + 1:), alpha, u, error)
        if (allocated(error)) return
        self%slot_of = 0
        self%speed_of = 0
        do k = 1, self%nc
            self%slot_of(self%partition%dependent(k)) = k
        end do
        do i = 1, self%ni
            self%speed_of(self%partition%independent(i)) = i
        end do
        ! C_d's factors stay those of q: the evaluation below changes neither q nor C
        call eq%prepare_jacobian_blocks(time, y(:n), u, alpha, error)
        if (allocated(error)) return
        associate (w => eq%work, bl => self%partition%blocks, cs => eq%constraints)
            do j = 1, n
                if (rows(starts(j) + 1) + 1 /= j) cycle
                nb = count(rows(starts(j) + 1:starts(j + 1)) < n)
                nv = starts(j + 1) - starts(j) - nb
                call eq%jacobian_block(rows(starts(j) + 1:starts(j) + nb), u, alpha, listed, &
                    & error)
                if (allocated(error)) return
                ! the block's independent speeds (ascending: their coordinates' order)
                s = 0
                do c = 1, nb
                    if (self%speed_of(w%block_coordinates(c)) == 0) cycle
                    s = s + 1
                    self%block_speeds(s) = w%block_coordinates(c)
                end do
                m = 0
                do i = 1, listed
                    m = m + bl%row_start(w%block_list(i) + 1) - bl%row_start(w%block_list(i))
                end do
                if (s /= nv) then
                    call fatal_error(error, "independent speeds by blocks: column " &
                        & // to_text(j) // "'s pattern holds " // to_text(nv) // " speeds, " &
                        & // "its block " // to_text(s), stat_ucon)
                    return
                end if
                call size_block(self, m, nb, nv)
                ! -dr/dq (module text) and -C_i over the block's UCONs and columns, row by
                ! row of its constraints' blocks (their UCONs in order), as jacobian's rows
                r = 0
                do i = 1, listed
                    b = w%block_list(i)
                    do x = bl%row_start(b), bl%row_start(b + 1) - 1
                        k = bl%rows(x)
                        r = r + 1
                        self%local_row(x) = r
                        associate (at => cs%local(:cs%local_count(k), k))
                            if (eq%model%ucons(k)%holonomic) then
                                self%block_dq(r, :nb) = -(0.0_wp + 0.0_wp + alpha*0.0_wp)
                                do a = 1, size(at)
                                    self%block_dq(r, w%block_place(at(a))) = &
                                        & -(local_dot(cs%hqq(:, a, k), u, at) &
                                        & + cs%dt_grad_q(a, k) + alpha*cs%grad_q_local(a, k))
                                end do
                            else
                                self%block_dq(r, :nb) = 0.0_wp
                                do a = 1, size(at)
                                    self%block_dq(r, w%block_place(at(a))) = &
                                        & cs%grad_q_local(a, k)
                                end do
                                self%block_dq(r, :nb) = -self%block_dq(r, :nb)
                            end if
                        end associate
                        do t = 1, nv
                            self%block_dv(r, t) = -eq%c%entry(k, self%block_speeds(t))
                        end do
                    end do
                end do
                ! C_d^-1 by the partition's blocks: row r is then slot x's (local_row(x) = r)
                r = 0
                do i = 1, listed
                    b = w%block_list(i)
                    call self%partition%solve_block(b, self%block_dq(r + 1, 1), &
                        & size(self%block_dq, 1), nb, error)
                    if (allocated(error)) return
                    if (nv > 0) call self%partition%solve_block(b, self%block_dv(r + 1, 1), &
                        & size(self%block_dv, 1), nv, error)
                    if (allocated(error)) return
                    r = r + bl%row_start(b + 1) - bl%row_start(b)
                end do
                ! columns of the coordinates: q' rows (du_d/dq, 0), v' rows (the chain rule)
                do c = 1, nb
                    v0 = starts(w%block_coordinates(c))
                    do i = 1, nb
                        slot = self%slot_of(w%block_coordinates(i))
                        values(v0 + i) = 0.0_wp
                        if (slot > 0) values(v0 + i) = self%block_dq(self%local_row(slot), c)
                    end do
                    do t = 1, nv
                        values(v0 + nb + t) = chain_total(t, c, self%block_dq(:m, c))
                    end do
                end do
                ! columns of the independent speeds: q' rows (du_d/dv, the identity), v' rows
                do s = 1, nv
                    v0 = starts(n + self%speed_of(self%block_speeds(s)))
                    do i = 1, nb
                        slot = self%slot_of(w%block_coordinates(i))
                        values(v0 + i) = 0.0_wp
                        if (slot > 0) then
                            values(v0 + i) = self%block_dv(self%local_row(slot), s)
                        else if (w%block_coordinates(i) == self%block_speeds(s)) then
                            values(v0 + i) = 1.0_wp
                        end if
                    end do
                    do t = 1, nv
                        values(v0 + nb + t) = chain_total(t, nb + w%block_place( &
                            & self%block_speeds(s)), self%block_dv(:m, s))
                    end do
                end do
            end do
        end associate

    contains

        !> The chain rule's v' row of the block's independent speed t in the ODE form's column
        !> `column` (block_top): its own entry plus its slopes to the block's dependent speeds
        !> times their partials d (the block's rows in order), the zero slopes skipped
        real(wp) function chain_total(t, column, d) result(total)
            integer, intent(in) :: t, column
            real(wp), intent(in) :: d(:)
            real(wp) :: slope
            integer :: place, x

            associate (top => eq%work%block_top, places => eq%work%block_place)
                place = places(self%block_speeds(t))
                total = top(place, column)
                do x = 1, size(d)
                    slope = top(place, nb + places(self%partition%dependent(slot_at(x))))
                    if (slope == 0.0_wp) cycle
                    total = total + slope*d(x)
                end do
            end associate
        end function chain_total

        !> The slot of the block's x-th row (its constraints' blocks' slots, in order)
        integer function slot_at(x) result(slot)
            integer, intent(in) :: x
            integer :: ii, rows_b

            slot = x
            do ii = 1, listed
                rows_b = self%partition%blocks%row_start(eq%work%block_list(ii) + 1) &
                    & - self%partition%blocks%row_start(eq%work%block_list(ii))
                if (slot <= rows_b) then
                    slot = self%partition%blocks%row_start(eq%work%block_list(ii)) + slot - 1
                    return
                end if
                slot = slot - rows_b
            end do
        end function slot_at

    end subroutine jacobian_blocks

    !> block_dq (m x nb) and block_dv (m x nv) at least, grown (a first use or a larger block).
    subroutine size_block(self, m, nb, nv)
        type(independent_speeds_type), intent(inout) :: self
        integer, intent(in) :: m, nb, nv

        if (allocated(self%block_dq)) then
            if (size(self%block_dq, 1) >= max(m, 1) .and. size(self%block_dq, 2) >= nb .and. &
                & size(self%block_dv, 2) >= max(nv, 1)) return
            deallocate(self%block_dq, self%block_dv)
        end if
        allocate(self%block_dq(max(m, 1), nb), self%block_dv(max(m, 1), max(nv, 1)), &
            & source=0.0_wp)
    end subroutine size_block

end module rollcon_independent_speeds
