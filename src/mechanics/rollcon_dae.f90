! SPDX-License-Identifier: MIT
!> The DAE form for IDA (docs/design.md §4): unknowns y = (q, u, lambda, mu),
!>
!>     q' - u - G^T mu = 0          (mu: one per position UCON, stabilises F = 0; GGL form)
!>     M u' - f - C^T lambda = 0
!>     F_k = 0                       velocity UCON k
!>     dF_k/dq u + dF_k/dt = 0       position UCON k (its velocity form)
!>     F_h = 0                       position UCON h (with mu_h)
!>
!> which has index 2 with every constraint enforced directly: no drift by construction. A force
!> served by a user's routine that reads accelerations (SYSARY('TACC'|'RACC'), SYSFNC('ACCX'
!> ... 'WDTM')), or a VARSUB a force reads, reads u' itself: f = f(q, u, u', t) makes no
!> loop here, as in ADAMS's DAE form, and its partials in u' (differenced over what the
!> routine declared, rollcon_user_force_partials; rollcon_equations' acceleration_partials)
!> enter the Newton matrix scaled by cj, beside M's. Likewise a force whose routine reads a
!> constraint's reaction (SYSFNC's force measures, rollcon_force_measures) reads the
!> multipliers lambda among the unknowns y: its partials in them (differenced over the rows
!> it declared) enter the momentum rows' lambda columns beside -C^T. A row
!> set aside as redundant (rollcon_redundancy) keeps its place: its equation is lambda_k = 0
!> (and mu_h = 0 for a position UCON's), and its multipliers appear nowhere else; so does a
!> row a contact's mode drops (rollcon_sliding_contact: sliding, flight). Sliding's friction
!> -mu_k F_n D and rolling resistance's -delta F_n sign(phidot) take F_n = c_nz lambda_n from
!> the unknowns themselves, and a held phidot's row is phidot' = 0 (add_mode_forces;
!> docs/design.md §5, "Contact modes", "Dissipation").
module rollcon_dae
    use rollcon_user_forces, only : take_user_force_error, set_system_accelerations, &
        & reads_accelerations, reads_constraint_forces, set_system_constraint_forces
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_constraints, only : local_dot, need_value, need_first, need_second, need_time
    use rollcon_equations, only : equations_type
    use rollcon_sliding_contact, only : sliding_contact_type
    use rollcon_momentum_partials, only : part_run_end
    implicit none
    private

    public :: dae_size, dae_residual, dae_jacobian, dae_sparse_jacobian, dae_differential
    public :: newton_places_type

    !> Where the writes of the sparse Newton matrix (dae_sparse_jacobian) went at its last
    !> evaluation: for each entry written or subtracted into, in the order the routine makes
    !> them, its place in the compressed columns' values (0 outside the pattern). The next
    !> evaluation makes the same writes in the same order (the same model, contact modes and
    !> rows set aside) and tries each remembered place first, checked against the pattern
    !> itself (the place lies in the entry's column and holds its row): a write that differs
    !> (another mode, another pattern) is found by bisection as without places, and its place
    !> remembered. Memory O(writes): no search for a write that repeats.
    type :: newton_places_type
        !> The places, in the order of the writes (grown, doubling, when an evaluation makes
        !> more writes than any before)
        integer, allocatable :: place(:)
    end type newton_places_type

contains

    !> Number of DAE unknowns: 2 n + nc + nh.
    pure function dae_size(eq) result(size_dae)
        type(equations_type), intent(in) :: eq
        integer :: size_dae

        size_dae = 2*eq%n + eq%nc + eq%nh
    end function dae_size

    !> 1 for differential unknowns (q, u), 0 for algebraic ones (lambda, mu): IDA's id vector.
    pure function dae_differential(eq) result(id)
        type(equations_type), intent(in) :: eq
        real(wp) :: id(2*eq%n + eq%nc + eq%nh)

        id = 0.0_wp
        id(:2*eq%n) = 1.0_wp
    end function dae_differential

    !> Residual of the DAE at (t, y, y').
    subroutine dae_residual(eq, time, y, yp, r, error)
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, y(:), yp(:)
        real(wp), intent(out) :: r(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, nc, needs, k, h, j, i0, jj
        logical :: aside, loop, multipliers, drops

        loop = .false.
        multipliers = .false.
        if (allocated(eq%model%forces)) then
            loop = reads_accelerations(eq%model%forces)
            multipliers = reads_constraint_forces(eq%model%forces)
        end if
        n = eq%n
        nc = eq%nc
        ! a contact's mode drops rows only while it slides or flies (mode_drops)
        drops = mode_dropping(eq)
        needs = need_value + need_first
        if (eq%nh > 0) needs = needs + need_time
        associate (q => y(:n), u => y(n + 1:2*n), lambda => y(2*n + 1:2*n + nc), &
            & mu => y(2*n + nc + 1:), qp => yp(:n), up => yp(n + 1:2*n), cs => eq%constraints, &
            & bl => eq%blocks)
            call cs%evaluate(eq%model, time, q, u, needs, error)
            if (allocated(error)) return
            ! a user's force routine that reads accelerations reads IDA's u' (no loop to solve),
            ! one that reads a constraint's reaction the unknowns' lambda
            if (loop) call set_system_accelerations(up)
            if (multipliers) call set_reactions(eq, lambda)
            call eq%assemble(time, q, u)
            call take_user_force_error(error)
            if (allocated(error)) return
            r(:n) = qp - u
            r(n + 1:2*n) = -eq%force
            ! M u' part by part (M is the parts' 6 by 6 blocks), and each UCON's terms over its
            ! own coordinates: the dense sums' terms that are not exact zeros, in their order,
            ! at a cost per part that stays flat as the model grows
            do i0 = 0, n - 6, 6
                do j = i0 + 1, i0 + 6
                    r(n + i0 + 1:n + i0 + 6) = r(n + i0 + 1:n + i0 + 6) &
                        & + eq%mass(:, j - i0, i0/6 + 1)*up(j)
                end do
            end do
            do k = 1, nc
                h = eq%model%holonomic_number(k)
                aside = .false.
                if (eq%redundancy%set_aside > 0) aside = .not. eq%redundancy%active(k)
                ! a row the contact's mode drops (sliding, flight) is set aside alike
                if (drops) then
                    if (eq%mode_drops(k)) aside = .true.
                end if
                if (aside) then
                    r(2*n + k) = lambda(k)
                    if (h > 0) r(2*n + nc + h) = mu(h)
                    cycle
                end if
                associate (at => bl%ucon_coordinates(bl%ucon_start(k):bl%ucon_start(k + 1) - 1))
                    if (h > 0) then
                        do jj = 1, size(at)
                            j = at(jj)
                            r(j) = r(j) - mu(h)*cs%grad_q_local(jj, k)
                            r(n + j) = r(n + j) - lambda(k)*cs%grad_q_local(jj, k)
                        end do
                        r(2*n + k) = cs%grad_q_dot(k, u) + cs%dt(k)
                        r(2*n + nc + h) = cs%value(k)
                    else
                        do jj = 1, size(at)
                            j = at(jj)
                            r(n + j) = r(n + j) - lambda(k)*cs%grad_u_local(jj, k)
                        end do
                        r(2*n + k) = cs%value(k)
                    end if
                end associate
            end do
            if (mode_forces(eq)) call add_mode_forces(eq, u, up, lambda, r(n + 1:2*n))
        end associate
    end subroutine dae_residual

    !> The contact's mode or the rim's dissipation adds forces of the normal multiplier (or
    !> holds phidot): sliding's friction, rolling resistance, its held phidot.
    pure logical function mode_forces(eq)
        type(equations_type), intent(in) :: eq

        mode_forces = eq%contact%sliding .or. eq%more_sliding() .or. (eq%dissipation%part > 0 &
            & .and. (eq%dissipation%rolling_resistance > 0.0_wp .or. eq%dissipation%held))
    end function mode_forces

    !> A contact slides or flies: only then may its mode drop rows (rollcon_equations'
    !> mode_drops; rollcon_sliding_contact's dropped).
    pure logical function mode_dropping(eq)
        type(equations_type), intent(in) :: eq

        mode_dropping = eq%contact%sliding .or. eq%contact%flying .or. eq%more_sliding() &
            & .or. eq%more_flying()
    end function mode_dropping

    !> Row k's gradient in C at coordinate j, from the last evaluation (dF/dq for a position
    !> UCON, dF/du for a velocity UCON).
    pure real(wp) function row_gradient(eq, k, j)
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k, j

        if (eq%model%holonomic_number(k) > 0) then
            row_gradient = eq%constraints%grad_q_entry(k, j)
        else
            row_gradient = eq%constraints%grad_u_entry(k, j)
        end if
    end function row_gradient

    !> The normal force [N] c_nz lambda_n of normal row n_row (height column z) at the
    !> multipliers lambda: the force's vertical component on the part (C^T lambda's Z entry).
    pure real(wp) function normal_force_of(eq, n_row, z, lambda)
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: n_row, z
        real(wp), intent(in) :: lambda(:)

        normal_force_of = row_gradient(eq, n_row, z)*lambda(n_row)
    end function normal_force_of

    !> The sliding friction's multipliers on the contact's two tangential rows (dropped while it
    !> slides): the friction -mu_k F_n D, D = s_1 c_t1 + s_2 c_t2 (rollcon_sliding_contact), is
    !> -C_t^T m with m = -mu_k F_n s, F_n = c_nz lambda_n from the DAE's own normal multiplier
    !> and s the slip's direction (the tangential rows' values: the contact point's velocity).
    !> Also the slip [m/s] and its speed.
    pure subroutine friction_multipliers(eq, contact, lambda, m, s, slip)
        type(equations_type), intent(in) :: eq
        !> The sliding contact: eq's contact or one of its more_contacts
        type(sliding_contact_type), intent(in) :: contact
        real(wp), intent(in) :: lambda(:)
        real(wp), intent(out) :: m(2), s(2), slip(2)

        associate (t => contact%tangential)
            slip = [eq%constraints%value(t(1)), eq%constraints%value(t(2))]
            s = contact%direction(slip)
            m = -contact%mu*normal_force_of(eq, contact%normal, contact%height_column, lambda)*s
        end associate
    end subroutine friction_multipliers

    !> The forces a contact's mode and a rim's dissipation add to the momentum rows r
    !> (M u' - f - C^T lambda, n), from the DAE's normal multiplier itself (docs/design.md §5):
    !> sliding's friction -mu_k F_n D as its multipliers m on the tangential rows
    !> (friction_multipliers: r - C_t^T m), rolling resistance's -delta F_n sign(phidot) on phi
    !> (rollcon_rim_dissipation), and held rolling resistance's moment, whatever phidot' = 0
    !> needs, by phi's row replaced with phidot' = 0 (the moment acts on phi alone, so the
    !> other rows are those of the held motion).
    pure subroutine add_mode_forces(eq, u, up, lambda, r)
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: u(:), up(:), lambda(:)
        real(wp), intent(inout) :: r(:)
        integer :: phi, k

        if (eq%contact%sliding) call add_friction(eq%contact, r)
        if (allocated(eq%more_contacts)) then
            do k = 1, size(eq%more_contacts)
                if (eq%more_contacts(k)%sliding) call add_friction(eq%more_contacts(k), r)
            end do
        end if
        associate (diss => eq%dissipation)
            if (diss%part == 0) return
            phi = 6*(diss%part - 1) + 6
            if (diss%held) then
                r(phi) = up(phi)
            else if (diss%rolling_resistance > 0.0_wp) then
                r(phi) = r(phi) + diss%rolling_resistance*diss%rolling_direction(u(phi)) &
                    & *normal_force_of(eq, diss%normal, diss%height_column, lambda)
            end if
        end associate

    contains

        !> A sliding contact's friction: r - C_t^T m (friction_multipliers).
        pure subroutine add_friction(contact, r)
            type(sliding_contact_type), intent(in) :: contact
            !> The momentum rows (n)
            real(wp), intent(inout) :: r(:)
            real(wp) :: m(2), s(2), slip(2)
            integer :: i, j, jj

            call friction_multipliers(eq, contact, lambda, m, s, slip)
            associate (bl => eq%blocks, t => contact%tangential)
                do i = 1, 2
                    associate (at => bl%ucon_coordinates(bl%ucon_start(t(i)): &
                            & bl%ucon_start(t(i) + 1) - 1))
                        do jj = 1, size(at)
                            j = at(jj)
                            r(j) = r(j) - m(i)*row_gradient(eq, t(i), j)
                        end do
                    end associate
                end do
            end associate
        end subroutine add_friction
    end subroutine add_mode_forces

    !> Newton matrix dr/dy + cj dr/dy', analytic from the UCOSUB's first and second partials,
    !> into the dense matrix jac ((2n + nc + nh) square, cleared first). Written part by part
    !> (the mass, force and momentum terms: 6 by 6 per part) and over each UCON's own
    !> coordinates (its partials are zero elsewhere).
    subroutine dae_jacobian(eq, time, cj, y, yp, jac, error)
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        real(wp), intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error

        jac = 0.0_wp
        call write_jacobian(eq, time, cj, y, yp, error, jac=jac)
    end subroutine dae_jacobian

    !> The same Newton matrix as dae_jacobian, its entries written straight into a
    !> compressed-column matrix: column j's rows (0-based, ascending) are
    !> rows(starts(j) + 1 : starts(j + 1)) and its values values(the same); every entry this
    !> routine writes must be in the pattern (the DAE form's dae_pattern), the others are zero.
    !> No (2n + nc + nh)-square array: memory O(entries), time O(entries log(column length)).
    !> The entries are those of dae_jacobian's dense matrix, bit for bit (the same operations).
    !> With places (held by the caller from one evaluation to the next: newton_places_type),
    !> each write tries the place it had at the last evaluation before any search.
    !> Error: an entry outside the pattern (a pattern that misses an element's block).
    subroutine dae_sparse_jacobian(eq, time, cj, y, yp, starts, rows, values, error, places)
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        integer, intent(in) :: starts(:), rows(:)
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        type(newton_places_type), intent(inout), optional :: places

        values = 0.0_wp
        call write_jacobian(eq, time, cj, y, yp, error, starts=starts, rows=rows, &
            & values=values, places=places)
    end subroutine dae_sparse_jacobian

    !> dae_jacobian's entries into the dense jac, or into the compressed-column (starts, rows,
    !> values), already zero (with the places of the last evaluation's writes, if given:
    !> dae_sparse_jacobian).
    subroutine write_jacobian(eq, time, cj, y, yp, error, jac, starts, rows, values, places)
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, cj, y(:), yp(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(inout), optional :: jac(:, :)
        integer, intent(in), optional :: starts(:), rows(:)
        real(wp), intent(inout), optional :: values(:)
        type(newton_places_type), intent(inout), optional :: places
        logical :: aside, dense, loop, multipliers, placed, drops
        integer :: n, nc, k, h, i, j, row, ii, jj, i0, j0, outside(2), x, writes, remembered
        integer :: e_q, e_u
        integer :: first_a, last_a, first_b, last_b
        real(wp) :: m(2), s(2), slip(2), block_q(6, 6), block_u(6, 6)

        loop = .false.
        multipliers = .false.
        if (allocated(eq%model%forces)) then
            loop = reads_accelerations(eq%model%forces)
            multipliers = reads_constraint_forces(eq%model%forces)
        end if
        n = eq%n
        nc = eq%nc
        dense = present(jac)
        placed = present(places)
        writes = 0
        ! how many writes have a place remembered
        remembered = 0
        if (placed) then
            if (allocated(places%place)) remembered = size(places%place)
        end if
        outside = 0
        associate (q => y(:n), u => y(n + 1:2*n), lambda => y(2*n + 1:2*n + nc), &
            & mu => y(2*n + nc + 1:), up => yp(n + 1:2*n), cs => eq%constraints, &
            & bl => eq%blocks, dm => eq%work%dm)
            if (mode_forces(eq)) then
                ! Painlevé's test of the forces proportional to the normal force, as the ODE
                ! form makes it at every evaluation (rollcon_equations: 1 + mu c_nz lambda1_n),
                ! here at every Newton matrix: where it fails, this matrix is singular or
                ! nearly so and sliding is ill-posed
                call eq%accelerations(time, q, u, 0.0_wp, eq%work%a, eq%work%lambda, error)
                if (allocated(error)) return
            end if
            call cs%evaluate(eq%model, time, q, u, need_value + need_first + need_second &
                & + need_time, error)
            if (allocated(error)) return
            if (loop) call set_system_accelerations(up)
            if (multipliers) call set_reactions(eq, lambda)
            call eq%assemble(time, q, u)
            call eq%constraint_rows(u, 0.0_wp)  ! the DAE form keeps F itself: no Baumgarte terms
            drops = mode_dropping(eq)
            if (drops) then
                ! the rows the mode drops carry no force, sliding's friction its multipliers
                ! on the tangential rows (friction_multipliers): their second partials in
                ! dm/dq as a constraint force's (into the equations' scratch multipliers, free
                ! after Painlevé's test: no allocation)
                associate (effective => eq%work%lambda)
                    do k = 1, nc
                        effective(k) = 0.0_wp
                        if (eq%active_rows_of(k)) effective(k) = lambda(k)
                    end do
                    if (eq%contact%sliding) then
                        call friction_multipliers(eq, eq%contact, lambda, m, s, slip)
                        effective(eq%contact%tangential) = m
                    end if
                    if (allocated(eq%more_contacts)) then
                        do k = 1, size(eq%more_contacts)
                            if (.not. eq%more_contacts(k)%sliding) cycle
                            call friction_multipliers(eq, eq%more_contacts(k), lambda, m, s, &
                                & slip)
                            effective(eq%more_contacts(k)%tangential) = m
                        end do
                    end if
                    call eq%momentum_jacobian(q, u, up, effective, time)
                end associate
            else if (eq%redundancy%set_aside > 0) then
                ! the rows set aside carry no force, whatever the iterate's lambda_k
                call eq%momentum_jacobian(q, u, up, merge(lambda, 0.0_wp, &
                    & eq%redundancy%active), time)
            else
                call eq%momentum_jacobian(q, u, up, lambda, time)
            end if
            ! a user force routine's difference call that failed
            call take_user_force_error(error)
            if (allocated(error)) return
            ! the partials in u' of the forces whose routines read accelerations (they read
            ! IDA's u'), which enter scaled by cj as M does
            if (loop) then
                call eq%acceleration_partials(time, q, u, up, error)
                if (allocated(error)) return
            end if
            ! the partials in lambda of the forces whose routines read a constraint's reaction
            if (multipliers) then
                call eq%multiplier_partials(time, q, u, lambda, error)
                if (allocated(error)) return
            end if
            do j = 1, n
                call put(j, j, cj)
                call put(j, n + j, -1.0_wp)
            end do
            ! the momentum rows: each part's 6 by 6 blocks (M, its forces), then the UCONs'
            ! terms of dm/dq over their coordinates (rollcon_equations' momentum_jacobian)
            do i0 = 0, n - 6, 6
                call dm%q_block(i0/6 + 1, i0/6 + 1, block_q)
                call dm%u_block(i0/6 + 1, i0/6 + 1, block_u)
                do j = i0 + 1, i0 + 6
                    e_q = 0
                    e_u = 0
                    do i = i0 + 1, i0 + 6
                        call put_next(n + i, j, block_q(i - i0, j - i0), e_q)
                        if (loop) then
                            call put_next(n + i, n + j, block_u(i - i0, j - i0) &
                                & + cj*(eq%mass(i - i0, j - i0, i0/6 + 1) + eq%work%dm_da(i, j)), &
                                & e_u)
                        else
                            call put_next(n + i, n + j, block_u(i - i0, j - i0) &
                                & + cj*eq%mass(i - i0, j - i0, i0/6 + 1), e_u)
                        end if
                    end do
                end do
            end do
            ! a SPRINGDAMPER's or BUSHING's partials between its two parts (rollcon_force)
            do k = 1, size(eq%couplings, 2)
                call copy_coupling(eq%couplings(1, k), eq%couplings(2, k))
                call copy_coupling(eq%couplings(2, k), eq%couplings(1, k))
            end do
            ! a routine reading another part's accelerations: its partials between the parts
            if (loop) then
                do j = 1, n
                    do i = 1, n
                        if ((i - 1)/6 == (j - 1)/6 .or. eq%work%dm_da(i, j) == 0.0_wp) cycle
                        call subtract(n + i, n + j, -cj*eq%work%dm_da(i, j))
                    end do
                end do
            end if
            ! the UCONs' terms between two parts, each pair of parts' block read once (those
            ! within one part are the part's block, already written above with the same
            ! value: dm is complete)
            do k = 1, nc
                associate (at => bl%ucon_coordinates(bl%ucon_start(k):bl%ucon_start(k + 1) - 1))
                    first_b = 1
                    do while (first_b <= size(at))
                        last_b = part_run_end(at, first_b)
                        first_a = 1
                        do while (first_a <= size(at))
                            last_a = part_run_end(at, first_a)
                            i0 = 6*((at(first_a) - 1)/6)
                            j0 = 6*((at(first_b) - 1)/6)
                            if (i0 /= j0) then
                                call dm%q_block(i0/6 + 1, j0/6 + 1, block_q)
                                do jj = first_b, last_b
                                    e_q = 0
                                    do ii = first_a, last_a
                                        call put_next(n + at(ii), at(jj), &
                                            & block_q(at(ii) - i0, at(jj) - j0), e_q)
                                    end do
                                end do
                            end if
                            first_a = last_a + 1
                        end do
                        first_b = last_b + 1
                    end do
                end associate
            end do
            do k = 1, nc
                h = eq%model%holonomic_number(k)
                row = 2*n + k
                aside = .false.
                if (eq%redundancy%set_aside > 0) aside = .not. eq%redundancy%active(k)
                if (drops) then
                    if (eq%mode_drops(k)) aside = .true.
                end if
                if (aside) then
                    call put(row, row, 1.0_wp)
                    if (h > 0) call put(2*n + nc + h, 2*n + nc + h, 1.0_wp)
                    cycle
                end if
                associate (at => bl%ucon_coordinates(bl%ucon_start(k):bl%ucon_start(k + 1) - 1))
                    ! -C^T's column: row k's entries (C by rows over the UCON's coordinates)
                    e_q = 0
                    do x = eq%c%start(k), eq%c%start(k + 1) - 1
                        call put_next(n + eq%c%column(x), row, -eq%c%value(x), e_q)
                    end do
                    ! a force reading this row's reaction: its partials in lambda_k (on the
                    ! parts it loads; the DAE form's pattern keeps them)
                    if (multipliers) then
                        do i = 1, n
                            if (eq%work%dm_dlambda(i, k) /= 0.0_wp) &
                                & call subtract(n + i, row, -eq%work%dm_dlambda(i, k))
                        end do
                    end if
                    if (h > 0) then
                        ! mu_h G_h's partials and G_h u's
                        do jj = 1, size(at)
                            j = at(jj)
                            e_q = 0
                            do ii = 1, size(at)
                                i = at(ii)
                                call subtract_next(i, j, mu(h)*cs%hqq(ii, jj, k), e_q)
                            end do
                        end do
                        e_u = 0
                        do jj = 1, size(at)
                            j = at(jj)
                            call put(row, j, local_dot(cs%hqq(:, jj, k), u, at) &
                                & + cs%dt_grad_q(jj, k))
                            call put_next(j, 2*n + nc + h, -cs%grad_q_local(jj, k), e_u)
                            call put(row, n + j, cs%grad_q_local(jj, k))
                            call put(2*n + nc + h, j, cs%grad_q_local(jj, k))
                        end do
                    else
                        do jj = 1, size(at)
                            j = at(jj)
                            call put(row, j, cs%grad_q_local(jj, k))
                            call put(row, n + j, cs%grad_u_local(jj, k))
                        end do
                    end if
                end associate
            end do
            if (mode_forces(eq)) call mode_entries(u, lambda)
        end associate
        if (outside(1) > 0) call fatal_error(error, "the DAE's Newton matrix has entry (" &
            & // to_text(outside(1)) // ", " // to_text(outside(2)) // ") outside its " &
            & // "sparse pattern (the DAE form's dae_pattern misses an element's block)")

    contains

        !> The partials of add_mode_forces' terms not in dm/dq: sliding's friction by the normal
        !> multiplier (F_n = c_nz lambda_n) and by u and q through the slip's direction
        !> (ds/dv = (I - s s^T) / |w|, w = v + slip_floor r as rollcon_sliding_contact's
        !> direction, dv/du and dv/dq the tangential rows' gradients; none where w is zero,
        !> where s is the reference), exact; rolling resistance's by the normal
        !> multiplier; a held phidot's row, phidot' alone. c_nz's own partials in q (zero for
        !> a rim: the normal row's Z' coefficient is 1) are left out.
        subroutine mode_entries(u, lambda)
            real(wp), intent(in) :: u(:), lambda(:)
            real(wp) :: turned
            integer :: e, phi, k

            if (eq%contact%sliding) call friction_entries(eq%contact, lambda)
            if (allocated(eq%more_contacts)) then
                do k = 1, size(eq%more_contacts)
                    if (eq%more_contacts(k)%sliding) call friction_entries(eq%more_contacts(k), &
                        & lambda)
                end do
            end if
            associate (diss => eq%dissipation)
                if (diss%part == 0) return
                phi = 6*(diss%part - 1) + 6
                if (diss%held) then
                    ! phi's momentum row is phidot' = 0
                    if (dense) then
                        jac(n + phi, :) = 0.0_wp
                    else
                        do e = 1, size(rows)
                            if (rows(e) == n + phi - 1) values(e) = 0.0_wp
                        end do
                    end if
                    call put(n + phi, n + phi, cj)
                else if (diss%rolling_resistance > 0.0_wp) then
                    turned = diss%rolling_resistance*diss%rolling_direction(u(phi))
                    call subtract(n + phi, 2*n + diss%normal, &
                        & -turned*row_gradient(eq, diss%normal, diss%height_column))
                end if
            end associate
        end subroutine mode_entries

        !> A sliding contact's friction's partials (mode_entries): by its normal multiplier and
        !> through the slip's direction by u and q.
        subroutine friction_entries(contact, lambda)
            type(sliding_contact_type), intent(in) :: contact
            real(wp), intent(in) :: lambda(:)
            real(wp) :: projector(2, 2), speed, c_nz, weight, c_ti
            integer :: a, b, ia, ib, column

            associate (t => contact%tangential)
                call friction_multipliers(eq, contact, lambda, m, s, slip)
                c_nz = row_gradient(eq, contact%normal, contact%height_column)
                column = 2*n + contact%normal
                speed = contact%turning_speed(slip)
                projector = 0.0_wp
                if (speed > 0.0_wp) then
                    projector = -reshape([1.0_wp - s(1)**2, -s(1)*s(2), -s(1)*s(2), &
                        & 1.0_wp - s(2)**2], [2, 2])/speed
                    ! d m / d v = -mu F_n (I - s s^T) / |w|
                    projector = contact%mu*c_nz*lambda(contact%normal)*projector
                end if
                do a = 1, 2
                    associate (at => eq%blocks%ucon_coordinates(eq%blocks%ucon_start( &
                            & t(a)):eq%blocks%ucon_start(t(a) + 1) - 1))
                        do ia = 1, size(at)
                            i = at(ia)
                            ! C(t_a, i): row t_a's entry ia (C's pattern is the rows' own
                            ! coordinates, the same ascending list as at)
                            c_ti = eq%c%value(eq%c%start(t(a)) + ia - 1)
                            ! d(-c_ta m_a)/d lambda_n = mu c_nz s_a c_ta
                            call subtract(n + i, column, -contact%mu*c_nz*s(a)*c_ti)
                            do b = 1, 2
                                if (projector(a, b) == 0.0_wp) cycle
                                associate (by => eq%blocks%ucon_coordinates( &
                                        & eq%blocks%ucon_start(t(b)): &
                                        & eq%blocks%ucon_start(t(b) + 1) - 1))
                                    weight = -c_ti*projector(a, b)
                                    do ib = 1, size(by)
                                        j = by(ib)
                                        call subtract(n + i, n + j, &
                                            & -weight*eq%constraints%grad_u_local(ib, t(b)))
                                        call subtract(n + i, j, &
                                            & -weight*eq%constraints%grad_q_local(ib, t(b)))
                                    end do
                                end associate
                            end do
                        end do
                    end associate
                end do
            end associate
        end subroutine friction_entries

        !> Entry (i, j) = value.
        subroutine put(i, j, value)
            integer, intent(in) :: i, j
            real(wp), intent(in) :: value
            integer :: e

            if (dense) then
                jac(i, j) = value
                return
            end if
            e = located(i, j)
            if (e > 0) values(e) = value
        end subroutine put

        !> Entry (i, j) = entry (i, j) - value.
        subroutine subtract(i, j, value)
            integer, intent(in) :: i, j
            real(wp), intent(in) :: value
            integer :: e

            if (dense) then
                jac(i, j) = jac(i, j) - value
                return
            end if
            e = located(i, j)
            if (e > 0) values(e) = values(e) - value
        end subroutine subtract

        !> Entry (i, j) = value, where e is the place of the write before it in column j (0:
        !> none) and becomes this one's: the next place when it holds (i, j) (a column's rows
        !> written in ascending order), else located.
        subroutine put_next(i, j, value, e)
            integer, intent(in) :: i, j
            real(wp), intent(in) :: value
            integer, intent(inout) :: e

            if (dense) then
                jac(i, j) = value
                return
            end if
            e = following(i, j, e)
            if (e > 0) values(e) = value
        end subroutine put_next

        !> Entry (i, j) = entry (i, j) - value, e as put_next's.
        subroutine subtract_next(i, j, value, e)
            integer, intent(in) :: i, j
            real(wp), intent(in) :: value
            integer, intent(inout) :: e

            if (dense) then
                jac(i, j) = jac(i, j) - value
                return
            end if
            e = following(i, j, e)
            if (e > 0) values(e) = values(e) - value
        end subroutine subtract_next

        !> Where entry (i, j) is in values, given the place e of the write before it in column
        !> j (0: none): e + 1 when that holds row i, else located.
        integer function following(i, j, e) result(next)
            integer, intent(in) :: i, j, e

            if (e > 0 .and. e < starts(j + 1)) then
                if (rows(e + 1) == i - 1) then
                    next = e + 1
                    return
                end if
            end if
            next = located(i, j)
        end function following

        !> Where entry (i, j) is in values, 0 outside the pattern (the first such entry kept
        !> for the message): the place this write had at the last evaluation if it still
        !> holds (i, j), else found (and remembered).
        integer function located(i, j) result(e)
            integer, intent(in) :: i, j

            writes = writes + 1
            e = 0
            if (writes <= remembered) e = places%place(writes)
            if (e <= starts(j) .or. e > starts(j + 1)) then
                e = found(i, j)
            else if (rows(e) /= i - 1) then
                e = found(i, j)
            end if
        end function located

        !> Where entry (i, j) is in values, by bisection, remembered as this write's place
        !> (with places).
        integer function found(i, j) result(e)
            integer, intent(in) :: i, j

            e = searched(i, j)
            if (placed) call remember(e)
        end function found

        !> Where entry (i, j) is in values (bisection of column j's rows), 0 outside the
        !> pattern (the first such entry kept for the message).
        integer function searched(i, j) result(e)
            integer, intent(in) :: i, j
            integer :: low, high, middle

            low = starts(j) + 1
            high = starts(j + 1)
            do while (low <= high)
                middle = (low + high)/2
                if (rows(middle) == i - 1) then
                    e = middle
                    return
                else if (rows(middle) < i - 1) then
                    low = middle + 1
                else
                    high = middle - 1
                end if
            end do
            e = 0
            if (outside(1) == 0) outside = [i, j]
        end function searched

        !> Place e is that of write number writes (places grown, doubling, on a first use or
        !> an evaluation with more writes than any before).
        subroutine remember(e)
            integer, intent(in) :: e
            integer, allocatable :: more(:)

            if (.not. allocated(places%place)) allocate(places%place(max(64, writes)), source=0)
            if (writes > size(places%place)) then
                allocate(more(max(2*size(places%place), writes)))
                more(:size(places%place)) = places%place
                more(size(places%place) + 1:) = 0
                call move_alloc(more, places%place)
            end if
            remembered = size(places%place)
            places%place(writes) = e
        end subroutine remember

        !> The momentum rows of part a by the coordinates and rates of part b (a SPRINGDAMPER's
        !> or BUSHING's partials between its two parts).
        subroutine copy_coupling(a, b)
            integer, intent(in) :: a, b
            integer :: r0, c0, ia, jb, e_q, e_u
            real(wp) :: by_q(6, 6), by_u(6, 6)

            r0 = 6*(a - 1)
            c0 = 6*(b - 1)
            call eq%work%dm%q_block(a, b, by_q)
            call eq%work%dm%u_block(a, b, by_u)
            do jb = 1, 6
                e_q = 0
                e_u = 0
                do ia = 1, 6
                    call put_next(n + r0 + ia, c0 + jb, by_q(ia, jb), e_q)
                    call put_next(n + r0 + ia, n + c0 + jb, by_u(ia, jb), e_u)
                end do
            end do
        end subroutine copy_coupling
    end subroutine write_jacobian

    !> The constraint rows (C by rows over each UCON's coordinates) and multipliers a force
    !> routine's SYSFNC force measures read (the constraints evaluated at the state before):
    !> the unknowns' lambda, a row set aside carrying none.
    subroutine set_reactions(eq, lambda)
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: lambda(:)

        call eq%constraint_matrix()
        if (eq%redundancy%set_aside > 0) then
            call set_system_constraint_forces(eq%c, merge(lambda, 0.0_wp, eq%redundancy%active))
        else
            call set_system_constraint_forces(eq%c, lambda)
        end if
    end subroutine set_reactions

end module rollcon_dae
