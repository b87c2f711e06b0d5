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
    use rollcon_error, only : error_type
    use rollcon_constraints, only : local_dot, need_value, need_first, need_time
    use rollcon_equations, only : equations_type
    use rollcon_speed_partition, only : speed_partition_type
    implicit none
    private

    public :: independent_speeds_type

    !> The partition and the workspace of the formulation (allocated once, in init)
    type :: independent_speeds_type
        !> Rates, constraint rows partitioned (the active ones), independent speeds n - nc, and
        !> the model's rows (active or set aside)
        integer :: n = 0, nc = 0, ni = 0, rows = 0
        !> Which rows were active when the partition was sized (init)
        logical, allocatable :: active(:)
        type(speed_partition_type) :: partition
        !> The ODE form's Jacobian d(q', u')/d(q, u) (2n x 2n)
        real(wp), allocatable :: full(:, :)
        !> -C_d^-1 dr/dq (nc x n) and -C_d^-1 C_i (nc x ni): the dependent speeds' partials
        real(wp), allocatable :: dud_dq(:, :), dud_dv(:, :)
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
        if (allocated(self%full)) deallocate(self%full, self%dud_dq, self%dud_dv, self%r)
        allocate(self%full(2*self%n, 2*self%n), self%dud_dq(max(self%rows, 1), self%n), &
            & self%dud_dv(max(self%rows, 1), self%ni), self%r(max(self%rows, 1)), source=0.0_wp)
    end subroutine init

    !> Size of the integrator's state: n coordinates and n - nc independent speeds.
    pure integer function state_size(self)
        class(independent_speeds_type), intent(in) :: self

        state_size = self%n + self%ni
    end function state_size

    !> Choose the partition at (q, u) from the constraint matrix eq%cm (C by rows over each
    !> UCON's own coordinates) as the last evaluation left it (an accelerations call at that
    !> state).
    subroutine choose(self, eq, error)
        class(independent_speeds_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        type(error_type), allocatable, intent(out) :: error

        call self%partition%choose(eq%cm, error)
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
    !> Leaves eq%cm (C by rows) and C_d's factors at q.
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
        call self%partition%factor(eq%cm, error)
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
                    do x = eq%cm%start(k), eq%cm%start(k + 1) - 1
                        j = independent_slot(self%partition%independent, eq%cm%column(x))
                        if (j > 0) self%dud_dv(k, j) = -eq%cm%value(x)
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

end module rollcon_independent_speeds
