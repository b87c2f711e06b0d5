! SPDX-License-Identifier: MIT
!> Evaluates every UCON of a model through its UCOSUB and scatters the answers onto the
!> system's coordinates q and rates u.
module rollcon_constraints
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : max_ucon_vars, scalar_none, scalar_value, scalar_dt, &
        & scalar_dtt, &
        & array_none, array_dq, array_dtdq, xmatrx_none, xmatrx_dqdq
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_model, only : model_type, ucon_statement_type, statement_ucon
    use rollcon_text, only : to_text
    use rollcon_gcon, only : evaluate_gcon
    use rollcon_motion, only : take_motion_error, motion_form_displacement
    use rollcon_motion, only : motion_displacement, motion_residual, motion_user_jet, &
        & displacement_residual
    use rollcon_user_forces, only : call_user_motion
    implicit none
    private

    public :: constraint_state_type, local_dot, need_value, need_first, need_second, need_time

    !> What an evaluation needs (add them): F, first partials, second partials, time partials
    integer, parameter :: need_value = 1, need_first = 2, need_second = 4, need_time = 8

    !> Constraint values and partials over the whole system (k: UCON, i/j: coordinate number)
    type :: constraint_state_type
        !> F_k
        real(wp), allocatable :: value(:)
        !> dF_k/dq_i and dF_k/du_i over UCON k's own coordinates: grad_q_local(a, k) with
        !> i = local(a, k) (width, nc), zero past local_count(k); off them they are zeros, not
        !> stored (memory grows as the number of UCONs, not as nc n: docs/design.md §4
        !> "Memory"). A position UCON has no rate among its variables (rollcon_model's
        !> holonomic), so its grad_u_local is zero. Read them through grad_q_dot, grad_q_entry,
        !> fill_grad_q_row and their grad_u twins.
        real(wp), allocatable :: grad_q_local(:, :), grad_u_local(:, :)
        !> Some UCON has a rate among its variables (a velocity UCON)
        logical :: rates = .false.
        !> dF_k/dt and d2F_k/dt2
        real(wp), allocatable :: dt(:), dtt(:)
        !> d2F_k/dt dq_i and d2F_k/dt du_i over UCON k's own coordinates: dt_grad_q(a, k) with
        !> i = local(a, k) (width, nc), zero past local_count(k); off them they are zeros, not
        !> stored (memory grows as the number of UCONs, not as nc n)
        real(wp), allocatable :: dt_grad_q(:, :), dt_grad_u(:, :)
        !> Each UCON's own coordinates, ascending and each once (a rate and its coordinate
        !> share one): local(1:local_count(k), k), at most `width` (12 for a UCON on two parts)
        integer :: width = 0
        integer, allocatable :: local(:, :), local_count(:)
        !> The place in local(:, k) of each of UCON k's variables (max_ucon_vars, nc)
        integer, allocatable :: slot(:, :)
        !> For each UCON: every variable a coordinate (none a rate), declared in ascending order
        !> of its coordinates: its XMATRX is its d2F/dq dq as it stands (place_hessian)
        logical, allocatable :: plain_hessian(:)
        !> For each UCON: every variable a coordinate, none a rate (its grad_u_local, dt_grad_u
        !> and hqu are never written: zeros since allocate_state)
        logical, allocatable :: position_only(:)
        !> Second partials over each UCON's own coordinates (docs/design.md §4): hqq(a, b, k) is
        !> d2F_k/dq_i dq_j and hqu(a, b, k) d2F_k/dq_i du_j with i = local(a, k), j = local(b, k);
        !> d2F/du du is zero (docs/design.md §2). The rest of the n x n matrices are zeros, not
        !> stored: memory and time grow as the number of UCONs, not as n^2 of them.
        !>
        !> Which entries of grad_q_local, grad_u_local, dt_grad_q, dt_grad_u, hqq and hqu a UCON's
        !> evaluation writes depends on its variables alone (their kinds and slots), not on the
        !> state: place_row and place_hessian overwrite those entries at each call and never
        !> touch the others, which stay the zeros of allocate_state (no clearing per call).
        real(wp), allocatable :: hqq(:, :, :), hqu(:, :, :)
        !> Scratch for one UCOSUB call
        real(wp) :: local_q(max_ucon_vars) = 0.0_wp
    contains
        procedure :: allocate => allocate_state
        procedure :: evaluate => evaluate_constraints
        procedure :: grad_q_dot, grad_u_dot, grad_q_entry, grad_u_entry
        procedure :: fill_grad_q_row, fill_grad_u_row
    end type constraint_state_type

contains

    !> Size the arrays for a model (once, outside any hot path).
    subroutine allocate_state(self, model)
        class(constraint_state_type), intent(inout) :: self
        type(model_type), intent(in) :: model

        integer :: k, i, a, j, count
        logical :: rates

        associate (n => model%n, nc => model%nc)
            if (allocated(self%value)) deallocate(self%value, self%dt, self%dtt, &
                & self%grad_q_local, self%grad_u_local, self%dt_grad_q, self%dt_grad_u, &
                & self%hqq, self%hqu, self%local, self%local_count, self%slot, &
                & self%plain_hessian, self%position_only)
            allocate(self%value(nc), self%dt(nc), self%dtt(nc), source=0.0_wp)
            rates = .false.
            do k = 1, nc
                if (.not. model%ucons(k)%holonomic) rates = .true.
            end do
            self%rates = rates
            allocate(self%local(max_ucon_vars, nc), self%slot(max_ucon_vars, nc), &
                & self%local_count(nc), source=0)
            allocate(self%plain_hessian(nc), self%position_only(nc), source=.false.)
            ! each UCON's distinct coordinates in ascending order (insertion), then the slots
            self%width = 0
            do k = 1, nc
                associate (ucon => model%ucons(k), list => self%local(:, k))
                    count = 0
                    do i = 1, ucon%nvars
                        j = ucon%coordinate(i)
                        if (any(list(:count) == j)) cycle
                        a = count
                        do while (a >= 1)
                            if (list(a) <= j) exit
                            list(a + 1) = list(a)
                            a = a - 1
                        end do
                        list(a + 1) = j
                        count = count + 1
                    end do
                    do i = 1, ucon%nvars
                        self%slot(i, k) = findloc(list(:count), ucon%coordinate(i), 1)
                    end do
                    self%local_count(k) = count
                    self%width = max(self%width, count)
                    self%position_only(k) = .not. any(ucon%velocity(:ucon%nvars))
                    self%plain_hessian(k) = self%position_only(k) &
                        & .and. all(self%slot(:ucon%nvars, k) == [(i, i = 1, ucon%nvars)])
                end associate
            end do
            allocate(self%hqq(self%width, self%width, nc), self%hqu(self%width, self%width, nc), &
                & self%dt_grad_q(self%width, nc), self%dt_grad_u(self%width, nc), &
                & self%grad_q_local(self%width, nc), self%grad_u_local(self%width, nc), &
                & source=0.0_wp)
        end associate
    end subroutine allocate_state

    !> Call the UCOSUB of every UCON for what `needs` asks (a sum of need_* flags) at (t, q, u).
    subroutine evaluate_constraints(self, model, time, q, u, needs, error)
        class(constraint_state_type), intent(inout) :: self
        type(model_type), intent(in) :: model
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of the whole system
        real(wp), intent(in) :: q(:), u(:)
        !> Sum of need_value, need_first, need_second, need_time
        integer, intent(in) :: needs
        !> Set when a UCOSUB reports an error or returns a non-finite value
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: scalar, array(max_ucon_vars), xmatrx(max_ucon_vars, max_ucon_vars)
        real(wp) :: ucon_time, h(0:2), user_values(0:2)
        integer :: k, i, idrsel(3)
        logical :: first, second, selected

        first = iand(needs, need_first) /= 0
        second = iand(needs, need_second) /= 0
        idrsel = [scalar_none, array_none, xmatrx_none]
        if (iand(needs, need_value) /= 0) idrsel(1) = scalar_value
        if (first) idrsel(2) = array_dq
        if (second) idrsel(3) = xmatrx_dqdq
        selected = any(idrsel /= 0)
        do k = 1, model%nc
            associate (ucon => model%ucons(k))
                if (self%position_only(k)) then
                    do i = 1, ucon%nvars
                        self%local_q(i) = q(ucon%coordinate(i))
                    end do
                else
                    do i = 1, ucon%nvars
                        if (ucon%velocity(i)) then
                            self%local_q(i) = u(ucon%coordinate(i))
                        else
                            self%local_q(i) = q(ucon%coordinate(i))
                        end if
                    end do
                end if
                ! a routine in the model's units gets the state and the time in them
                ucon_time = time
                if (ucon%converted) then
                    self%local_q(:ucon%nvars) = ucon%scales*self%local_q(:ucon%nvars)
                    ucon_time = ucon%time_scale*time
                end if
                if (selected) then
                    call evaluate_one(ucon, ucon_time, self%local_q, idrsel, scalar, array, &
                        & xmatrx, error)
                    if (allocated(error)) call in_user_words(model, k, error)
                    if (allocated(error)) return
                    if (ucon%converted) call to_si(ucon, 0, idrsel /= 0, scalar, array, xmatrx)
                    if (idrsel(1) /= 0) self%value(k) = scalar
                    ! a MOTION: F = s(q) - h(t), s the routine's value (rollcon_motion)
                    if (idrsel(1) /= 0 .and. allocated(ucon%motion)) then
                        if (ucon%motion%user .and. ucon%motion%form &
                            & == motion_form_displacement) then
                            ! a MOTSUB's displacement (IORD = 0)
                            call call_user_motion(ucon%motion%id, time, q, u, [0], &
                                & user_values, error)
                            if (allocated(error)) return
                            h = motion_user_jet(ucon%motion, user_values)
                            self%value(k) = displacement_residual(ucon%motion, h(0), scalar)
                        else
                            self%value(k) = motion_residual(ucon%motion, time, scalar)
                            ! a MOTSUB's VELOCITY or ACCELERATION, integrated there
                            call take_motion_error(error)
                            if (allocated(error)) return
                        end if
                    end if
                    if (first) call place_row(ucon, self%slot(:, k), self%position_only(k), &
                        & array, self%grad_q_local(:, k), self%grad_u_local(:, k))
                    if (second) call place_hessian(ucon, self%slot(:, k), self%local_count(k), &
                        & self%plain_hessian(k), self%position_only(k), xmatrx, &
                        & self%hqq(:, :, k), self%hqu(:, :, k))
                end if
                ! a MOTION's time partials are its time part's: dF/dt = -h', d2F/dt2 = -h'',
                ! d2F/dt dq = 0 (its routine is time-free)
                if (iand(needs, need_time) /= 0 .and. allocated(ucon%motion)) then
                    if (ucon%motion%user .and. ucon%motion%form == motion_form_displacement) then
                        ! a MOTSUB's first and second TIME derivatives (IORD = 1, 2)
                        call call_user_motion(ucon%motion%id, time, q, u, [1, 2], &
                            & user_values, error)
                        if (allocated(error)) return
                        user_values(0) = 0.0_wp
                        h = motion_user_jet(ucon%motion, user_values)
                    else
                        h = motion_displacement(ucon%motion, time)
                        call take_motion_error(error)
                        if (allocated(error)) return
                    end if
                    self%dt(k) = -h(1)
                    self%dtt(k) = -h(2)
                end if
                ! a time-free UCON's time partials stay at the zeros of allocate_state
                if (iand(needs, need_time) /= 0 .and. .not. ucon%time_free &
                    & .and. .not. allocated(ucon%motion)) then
                    call evaluate_one(ucon, ucon_time, self%local_q, [scalar_dt, array_dtdq, &
                        & xmatrx_none], scalar, array, xmatrx, error)
                    if (allocated(error)) call in_user_words(model, k, error)
                    if (allocated(error)) return
                    if (ucon%converted) call to_si(ucon, 1, [.true., .true., .false.], scalar, &
                        & array, xmatrx)
                    self%dt(k) = scalar
                    call place_row(ucon, self%slot(:, k), self%position_only(k), array, &
                        & self%dt_grad_q(:, k), self%dt_grad_u(:, k))
                    if (ucon%holonomic) then
                        call evaluate_one(ucon, ucon_time, self%local_q, [scalar_dtt, &
                            & array_none, xmatrx_none], scalar, array, xmatrx, error)
                        if (allocated(error)) call in_user_words(model, k, error)
                        if (allocated(error)) return
                        if (ucon%converted) scalar = scalar*ucon%value_scale*ucon%time_scale**2
                        self%dtt(k) = scalar
                    end if
                end if
            end associate
        end do
    end subroutine evaluate_constraints

    !> One evaluation of a UCON as its UCOSUB gives it (rollcon_ucon_call's evaluate_ucon),
    !> or, for a GCON, as its expression gives it (rollcon_gcon's evaluate_gcon, the same
    !> contract).
    subroutine evaluate_one(ucon, time, q, idrsel, scalar, array, xmatrx, error)
        type(ucon_statement_type), intent(in) :: ucon
        real(wp), intent(in) :: time, q(max_ucon_vars)
        integer, intent(in) :: idrsel(3)
        real(wp), intent(inout) :: scalar, array(max_ucon_vars), &
            & xmatrx(max_ucon_vars, max_ucon_vars)
        type(error_type), allocatable, intent(out) :: error

        if (allocated(ucon%gcon)) then
            call evaluate_gcon(ucon%gcon, ucon%id, time, q, idrsel, scalar, array, xmatrx, &
                & error, ucon%nvars)
        else
            call evaluate_ucon(ucon%ucosub, ucon%id, time, q, ucon%par, idrsel, scalar, array, &
                & xmatrx, error, ucon%nvars)
        end if
    end subroutine evaluate_one

    !> A UCOSUB's error for an equation of a JOINT or JPRIM (a UCON the program numbered) named
    !> by its statement, line and equation instead of "UCON/<id>" (rollcon_model's row_words).
    pure subroutine in_user_words(model, k, error)
        type(model_type), intent(in) :: model
        integer, intent(in) :: k
        type(error_type), intent(inout) :: error
        character(len=:), allocatable :: prefix

        if (.not. allocated(model%statements) .or. model%ucons(k)%statement == 0) return
        if (model%statements(model%ucons(k)%statement)%kind == statement_ucon) return
        prefix = "UCON/" // to_text(model%ucons(k)%id) // ":"
        if (index(error%message, prefix) /= 1) return
        error%message = model%row_words(k) // ":" // error%message(len(prefix) + 1:)
    end subroutine in_user_words

    !> What a routine in the model's units returned, in SI (chain rule, rollcon_ucosub_units):
    !> scalar and array are F and dF/dq (time_order 0) or dF/dt and d2F/dt dq (time_order 1),
    !> xmatrx d2F/dq dq; only those selected are touched.
    pure subroutine to_si(ucon, time_order, selected, scalar, array, xmatrx)
        type(ucon_statement_type), intent(in) :: ucon
        integer, intent(in) :: time_order
        !> Which of scalar, array, xmatrx the call returned
        logical, intent(in) :: selected(3)
        real(wp), intent(inout) :: scalar, array(:), xmatrx(:, :)
        real(wp) :: factor
        integer :: j

        factor = ucon%value_scale*ucon%time_scale**time_order
        associate (n => ucon%nvars)
            if (selected(1)) scalar = factor*scalar
            if (selected(2)) array(:n) = factor*ucon%scales*array(:n)
            if (selected(3)) then
                do j = 1, n
                    xmatrx(:n, j) = ucon%value_scale*ucon%scales*ucon%scales(j)*xmatrx(:n, j)
                end do
            end if
        end associate
    end subroutine to_si

    !> Row k of dF/dq times v (v over the system's coordinates, n): the sum over UCON k's own
    !> coordinates in ascending order, as the dense row's dot product sums its nonzeros.
    pure real(wp) function grad_q_dot(self, k, v) result(total)
        class(constraint_state_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(in) :: v(:)

        total = local_dot(self%grad_q_local(:, k), v, self%local(:self%local_count(k), k))
    end function grad_q_dot

    !> Row k of dF/du times v (n), as grad_q_dot.
    pure real(wp) function grad_u_dot(self, k, v) result(total)
        class(constraint_state_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(in) :: v(:)

        total = local_dot(self%grad_u_local(:, k), v, self%local(:self%local_count(k), k))
    end function grad_u_dot

    !> dF_k/dq_j (j a system coordinate; zero off UCON k's own coordinates).
    pure real(wp) function grad_q_entry(self, k, j) result(entry)
        class(constraint_state_type), intent(in) :: self
        integer, intent(in) :: k, j

        entry = local_entry(self%local_count(k), self%local(:, k), self%grad_q_local(:, k), j)
    end function grad_q_entry

    !> dF_k/du_j (zero off UCON k's own coordinates).
    pure real(wp) function grad_u_entry(self, k, j) result(entry)
        class(constraint_state_type), intent(in) :: self
        integer, intent(in) :: k, j

        entry = local_entry(self%local_count(k), self%local(:, k), self%grad_u_local(:, k), j)
    end function grad_u_entry

    !> Row k of dF/dq written whole into row (n: the dense analyses' row; zeros off UCON k's
    !> own coordinates).
    pure subroutine fill_grad_q_row(self, k, row)
        class(constraint_state_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(out) :: row(:)

        call fill_local_row(self%local_count(k), self%local(:, k), self%grad_q_local(:, k), row)
    end subroutine fill_grad_q_row

    !> Row k of dF/du written whole into row (n), as fill_grad_q_row.
    pure subroutine fill_grad_u_row(self, k, row)
        class(constraint_state_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(out) :: row(:)

        call fill_local_row(self%local_count(k), self%local(:, k), self%grad_u_local(:, k), row)
    end subroutine fill_grad_u_row

    !> The entry in system coordinate j of a row held over a UCON's own coordinates (local, its
    !> first count; zero off them).
    pure real(wp) function local_entry(count, local, values, j) result(entry)
        integer, intent(in) :: count, local(:), j
        real(wp), intent(in) :: values(:)
        integer :: a

        entry = 0.0_wp
        do a = 1, count
            if (local(a) == j) entry = values(a)
        end do
    end function local_entry

    !> Such a row written whole into row (the system's coordinates; zeros off its own).
    pure subroutine fill_local_row(count, local, values, row)
        integer, intent(in) :: count, local(:)
        real(wp), intent(in) :: values(:)
        real(wp), intent(out) :: row(:)
        integer :: a

        row = 0.0_wp
        do a = 1, count
            row(local(a)) = values(a)
        end do
    end subroutine fill_local_row

    !> Place a UCON's partials ARRAY over its own coordinates (`slot` gives each variable's
    !> place): its coordinates' d/dq and its rates' d/du, as a dense row would over the
    !> system's. Only the places of its variables of each kind are written, the same at every
    !> call: the other kind's entry at a place stays the zero of allocate_state
    !> (constraint_state_type's hqq), as a dense row's would be.
    pure subroutine place_row(ucon, slot, position_only, array, local_q, local_u)
        type(ucon_statement_type), intent(in) :: ucon
        integer, contiguous, intent(in) :: slot(:)
        !> No variable is a rate (constraint_state_type's position_only)
        logical, intent(in) :: position_only
        real(wp), contiguous, intent(in) :: array(:)
        !> d/dq and d/du over the UCON's own coordinates (width)
        real(wp), contiguous, intent(inout) :: local_q(:), local_u(:)
        integer :: i

        if (position_only) then
            do i = 1, ucon%nvars
                local_q(slot(i)) = array(i)
            end do
            return
        end if
        do i = 1, ucon%nvars
            if (ucon%velocity(i)) then
                local_u(slot(i)) = array(i)
            else
                local_q(slot(i)) = array(i)
            end if
        end do
    end subroutine place_row

    !> Place a UCON's second partials (XMATRX) in its compact d2F/dq dq and d2F/dq du (over its
    !> own coordinates: `slot` gives each variable's place; d2F/du du is zero: F is linear in
    !> the rates, docs/design.md §2). A plain UCON (plain_hessian: coordinates only, in
    !> ascending order) has its XMATRX's count x count corner copied whole; another has the
    !> entries of its variables' places written, coordinate rows against coordinate columns in
    !> hqq and against rate columns in hqu, in the order of its variables (a place two
    !> variables of one kind share takes the later's). The entries written are the same at
    !> every call; the others are never written and stay the zeros of allocate_state
    !> (constraint_state_type's hqq), so nothing is cleared. A UCON without rates
    !> (position_only) never writes hqu.
    pure subroutine place_hessian(ucon, slot, count, plain, position_only, xmatrx, hqq, hqu)
        type(ucon_statement_type), intent(in) :: ucon
        integer, contiguous, intent(in) :: slot(:)
        !> Number of the UCON's own coordinates
        integer, intent(in) :: count
        !> Its plain_hessian and its position_only
        logical, intent(in) :: plain, position_only
        real(wp), contiguous, intent(in) :: xmatrx(:, :)
        real(wp), contiguous, intent(inout) :: hqq(:, :), hqu(:, :)
        integer :: i, j, a, b, b2

        if (plain) then
            hqq(:count, :count) = xmatrx(:count, :count)
            return
        end if
        if (position_only) then
            ! two columns a pass (each row's place looked up once): where two variables share
            ! a place, the entry still ends as the later row's of the later column, as one
            ! column at a time leaves it
            do j = 1, ucon%nvars - 1, 2
                b = slot(j)
                b2 = slot(j + 1)
                do i = 1, ucon%nvars
                    a = slot(i)
                    hqq(a, b) = xmatrx(i, j)
                    hqq(a, b2) = xmatrx(i, j + 1)
                end do
            end do
            if (mod(ucon%nvars, 2) == 1) then
                b = slot(ucon%nvars)
                do i = 1, ucon%nvars
                    hqq(slot(i), b) = xmatrx(i, ucon%nvars)
                end do
            end if
            return
        end if
        do j = 1, ucon%nvars
            b = slot(j)
            if (ucon%velocity(j)) then
                do i = 1, ucon%nvars
                    if (.not. ucon%velocity(i)) hqu(slot(i), b) = xmatrx(i, j)
                end do
            else
                do i = 1, ucon%nvars
                    if (.not. ucon%velocity(i)) hqq(slot(i), b) = xmatrx(i, j)
                end do
            end if
        end do
    end subroutine place_hessian

    !> h . x with h over a UCON's own coordinates `at` (ascending; h(i) belongs to at(i)): the
    !> dense sum's terms that are not exact zeros, in its order.
    pure function local_dot(h, x, at) result(total)
        real(wp), intent(in) :: h(:), x(:)
        integer, intent(in) :: at(:)
        real(wp) :: total
        integer :: i

        total = 0.0_wp
        do i = 1, size(at)
            total = total + h(i)*x(at(i))
        end do
    end function local_dot

end module rollcon_constraints
