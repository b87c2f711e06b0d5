! SPDX-License-Identifier: MIT
!> Equations of motion of a model: the ODE form (accelerations from the saddle-point system,
!> its Jacobian, velocity projection) shared by every formulation (docs/design.md §4).
!>
!> M(q) a = f(q, u, t) + C^T lambda,  C a = gamma, where C_k = dF_k/du for a velocity UCON and
!> dF_k/dq for a position UCON, and gamma makes the constraint's time derivative vanish.
module rollcon_equations
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_model, only : model_type
    use rollcon_body, only : body_mass_and_force, body_residual_jacobian, kinetic_energy
    use rollcon_force, only : force_and_moment
    use rollcon_constraints, only : constraint_state_type, need_value, need_first, need_second, &
        & need_time
    use rollcon_saddle_point, only : saddle_point_type
    implicit none
    private

    public :: equations_type, drift_none, drift_projection, drift_baumgarte

    !> Drift control of the ODE form: none, projection onto the constraints, Baumgarte
    integer, parameter :: drift_none = 0, drift_projection = 1, drift_baumgarte = 2

    !> A model, its drift control, and what evaluating its equations fills (allocated once, in
    !> init; no evaluation allocates). The saddle-point factors live in `saddle`.
    type :: equations_type
        !> The model, set up
        type(model_type) :: model
        !> Constraint values and partials at the last evaluation
        type(constraint_state_type) :: constraints
        !> drift_none, drift_projection or drift_baumgarte
        integer :: drift = drift_projection
        !> Baumgarte rate alpha [1/s]: F' = -alpha F (velocity), F'' = -2 alpha F' - alpha^2 F
        real(wp) :: baumgarte_rate = 10.0_wp
        !> Sizes: coordinates, constraints, holonomic constraints
        integer :: n = 0, nc = 0, nh = 0
        !> Mass matrix, applied and inertial forces f, constraint matrix C, gamma
        real(wp), allocatable :: mass(:, :), force(:), c(:, :), gamma(:)
        !> Applied moment about each part's centre, ground components [N m] (3, parts)
        real(wp), allocatable :: moments(:, :)
        !> The saddle-point system's factors, as the last accelerations call left them
        type(saddle_point_type) :: saddle
        !> Rows of C of the position UCONs alone (nh, n), for the position projection
        real(wp), allocatable :: holonomic_rows(:, :)
        !> Right-hand sides of the Jacobian's and the projection's solves: momentum rows (n, 2n)
        !> and constraint rows (nc, 2n)
        real(wp), allocatable :: rhs_top(:, :), rhs_bottom(:, :)
        !> Jacobian blocks of the momentum rows d(M a - f - C^T lambda)/d(q, u)
        real(wp), allocatable :: dm_dq(:, :), dm_du(:, :)
        !> Scratch: accelerations, multipliers, projected coordinates (automatic arrays would be
        !> allocated on the heap at every call)
        real(wp), allocatable :: a_work(:), lambda_work(:), q_work(:)
    contains
        procedure :: init
        procedure :: accelerations
        procedure :: ode_jacobian
        procedure :: project
        procedure :: energy
        procedure :: constraint_force
        procedure :: reaction_from_accelerations
        procedure :: assemble
        procedure :: constraint_rows
        procedure :: constraint_matrix
        procedure :: momentum_jacobian
    end type equations_type

contains

    !> Take a model that setup_model has prepared and size the workspace.
    subroutine init(self, model)
        class(equations_type), intent(inout) :: self
        type(model_type), intent(in) :: model

        self%model = model
        self%n = model%n
        self%nc = model%nc
        self%nh = model%nh
        call self%constraints%allocate(model)
        call self%saddle%init(self%n, self%nc)
        associate (n => self%n, nc => self%nc)
            allocate(self%mass(n, n), self%force(n), self%c(nc, n), self%gamma(nc), source=0.0_wp)
            allocate(self%moments(3, size(model%parts)), source=0.0_wp)
            allocate(self%holonomic_rows(self%nh, n), self%rhs_top(n, 2*n), &
                & self%rhs_bottom(nc, 2*n), source=0.0_wp)
            allocate(self%dm_dq(n, n), self%dm_du(n, n), source=0.0_wp)
            allocate(self%a_work(n), self%lambda_work(nc), self%q_work(n), source=0.0_wp)
        end associate
    end subroutine init

    !> Mass matrix and f = -(M a - f) at a = 0, part by part. Only the parts' diagonal blocks
    !> are written: the others stay zero from init.
    subroutine assemble(self, time, q, u)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: applied(3), part_mass(6, 6), part_force(6)
        integer :: p, i0

        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            call force_and_moment(self%model%forces, p, time, q(i0 + 1:i0 + 6), applied, &
                & self%moments(:, p))
            call body_mass_and_force(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), &
                & applied, self%moments(:, p), self%model%gravity, part_mass, part_force)
            self%mass(i0 + 1:i0 + 6, i0 + 1:i0 + 6) = part_mass
            self%force(i0 + 1:i0 + 6) = part_force
        end do
    end subroutine assemble

    !> C (velocity UCON: dF/du; position UCON: dF/dq) and gamma, from the last evaluation.
    subroutine constraint_rows(self, u)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: u(:)
        real(wp) :: alpha, rate
        integer :: k

        call self%constraint_matrix()
        alpha = 0.0_wp
        if (self%drift == drift_baumgarte) alpha = self%baumgarte_rate
        associate (cs => self%constraints)
            do k = 1, self%nc
                if (self%model%ucons(k)%holonomic) then
                    rate = dot_product(cs%grad_q(k, :), u) + cs%dt(k)
                    self%gamma(k) = -quadratic_form(cs%hqq(:, :, k), u) &
                        & - 2.0_wp*dot_product(cs%dt_grad_q(k, :), u) - cs%dtt(k) &
                        & - 2.0_wp*alpha*rate - alpha**2*cs%value(k)
                else
                    self%gamma(k) = -dot_product(cs%grad_q(k, :), u) - cs%dt(k) &
                        & - alpha*cs%value(k)
                end if
            end do
        end associate
    end subroutine constraint_rows

    !> C alone (velocity UCON: dF/du; position UCON: dF/dq), from first partials only.
    subroutine constraint_matrix(self)
        class(equations_type), intent(inout) :: self
        integer :: k

        do k = 1, self%nc
            if (self%model%ucons(k)%holonomic) then
                self%c(k, :) = self%constraints%grad_q(k, :)
            else
                self%c(k, :) = self%constraints%grad_u(k, :)
            end if
        end do
    end subroutine constraint_matrix

    !> Accelerations a and multipliers lambda at (t, q, u); leaves the saddle-point factors in
    !> `saddle` for the Jacobian.
    subroutine accelerations(self, time, q, u, a, lambda, error, second)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Accelerations [m/s^2, rad/s^2]
        real(wp), intent(out) :: a(self%n)
        !> Multipliers: the constraint forces' amplitudes
        real(wp), intent(out) :: lambda(self%nc)
        type(error_type), allocatable, intent(out) :: error
        !> Also evaluate second partials (needed by the Jacobian, or by position UCONs)
        logical, intent(in), optional :: second
        integer :: needs, n, nc

        n = self%n
        nc = self%nc
        needs = need_value + need_first + need_time
        if (self%nh > 0) needs = needs + need_second
        if (present(second)) then
            if (second .and. self%nh == 0) needs = needs + need_second
        end if
        call self%constraints%evaluate(self%model, time, q, u, needs, error)
        if (allocated(error)) return
        call self%assemble(time, q, u)
        call self%constraint_rows(u)
        call self%saddle%factor(self%mass, self%c, nc, error)
        if (allocated(error)) return
        a = self%force
        lambda = self%gamma
        call self%saddle%solve(self%c, a, lambda, 1, error)
    end subroutine accelerations

    !> d(M a - f - C^T lambda)/dq and /du at given a, lambda (into dm_dq, dm_du).
    subroutine momentum_jacobian(self, q, u, a, lambda)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp), intent(in) :: lambda(:)
        real(wp) :: part_dq(6, 6), part_du(6, 6)
        integer :: p, i0, k, j

        self%dm_dq = 0.0_wp
        self%dm_du = 0.0_wp
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            call body_residual_jacobian(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), &
                & a(i0 + 1:i0 + 6), self%moments(:, p), part_dq, part_du)
            self%dm_dq(i0 + 1:i0 + 6, i0 + 1:i0 + 6) = part_dq
            self%dm_du(i0 + 1:i0 + 6, i0 + 1:i0 + 6) = part_du
        end do
        ! -d(C^T lambda)/dq: second partials are why ADAMS asks a UCOSUB for XMATRX
        ! (docs/design.md §4)
        do k = 1, self%nc
            if (self%model%ucons(k)%holonomic) then
                self%dm_dq = self%dm_dq - lambda(k)*self%constraints%hqq(:, :, k)
            else
                do j = 1, self%n
                    self%dm_dq(:, j) = self%dm_dq(:, j) - lambda(k)*self%constraints%hqu(j, :, k)
                end do
            end if
        end do
    end subroutine momentum_jacobian

    !> Jacobian of the ODE right-hand side (q, u)' = (u, a(q, u, t)): da/dy = -K^-1 dG/dy with
    !> G = (M a - f - C^T lambda, C a - gamma) at fixed (a, lambda). For position UCONs the
    !> third partials of F in dgamma/dq are not available and are left out.
    subroutine ode_jacobian(self, time, q, u, jac, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> d(q', u')/d(q, u), 2n x 2n
        real(wp), intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, j

        n = self%n
        call self%accelerations(time, q, u, self%a_work, self%lambda_work, error, second=.true.)
        if (allocated(error)) return
        call self%momentum_jacobian(q, u, self%a_work, self%lambda_work)
        self%rhs_top(:, :n) = -self%dm_dq
        self%rhs_top(:, n + 1:) = -self%dm_du
        call jacobian_constraint_rows(self, u, self%a_work)
        call self%saddle%solve(self%c, self%rhs_top, self%rhs_bottom, 2*n, error)
        if (allocated(error)) return
        jac = 0.0_wp
        do j = 1, n
            jac(j, n + j) = 1.0_wp
        end do
        jac(n + 1:, :) = self%rhs_top
    end subroutine ode_jacobian

    !> Constraint rows of the Jacobian's right-hand sides, -d(C a - gamma)/d(q, u) at fixed a,
    !> into rhs_bottom.
    subroutine jacobian_constraint_rows(self, u, a)
        type(equations_type), intent(inout) :: self
        real(wp), intent(in) :: u(:), a(:)
        real(wp) :: alpha
        integer :: n, k, j

        n = self%n
        alpha = 0.0_wp
        if (self%drift == drift_baumgarte) alpha = self%baumgarte_rate
        associate (cs => self%constraints)
            do k = 1, self%nc
                if (self%model%ucons(k)%holonomic) then
                    do j = 1, n
                        self%rhs_bottom(k, j) = -dot_product(cs%hqq(:, j, k), a) &
                            & - 2.0_wp*alpha*(dot_product(cs%hqq(:, j, k), u) &
                            & + cs%dt_grad_q(k, j)) - alpha**2*cs%grad_q(k, j)
                        self%rhs_bottom(k, n + j) = -2.0_wp*dot_product(cs%hqq(:, j, k), u) &
                            & - 2.0_wp*cs%dt_grad_q(k, j) - 2.0_wp*alpha*cs%grad_q(k, j)
                    end do
                else
                    ! C a - gamma = dF/du a + dF/dq u + dF/dt + alpha F
                    do j = 1, n
                        self%rhs_bottom(k, j) = -(dot_product(cs%hqu(j, :, k), a) &
                            & + dot_product(cs%hqq(:, j, k), u) + cs%dt_grad_q(k, j) &
                            & + alpha*cs%grad_q(k, j))
                        self%rhs_bottom(k, n + j) = -(cs%grad_q(k, j) &
                            & + dot_product(cs%hqu(:, j, k), u) + cs%dt_grad_u(k, j) &
                            & + alpha*cs%grad_u(k, j))
                    end do
                end if
            end do
        end associate
    end subroutine jacobian_constraint_rows

    !> Correction (dq, du) that puts (q, u) back on the constraints: a mass-weighted least
    !> change, one Newton step for position UCONs, exact for velocity UCONs (linear in u).
    subroutine project(self, time, q, u, dq, du, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: dq(:), du(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, k, h

        n = self%n
        dq = 0.0_wp
        if (self%nh > 0) then
            call self%constraints%evaluate(self%model, time, q, u, need_value + need_first, error)
            if (allocated(error)) return
            call self%assemble(time, q, u)
            ! only position UCONs constrain q: [M, -G^T; G, 0] (dq, nu) = (0, -F_h)
            do k = 1, self%nc
                h = self%model%holonomic_number(k)
                if (h == 0) cycle
                self%holonomic_rows(h, :) = self%constraints%grad_q(k, :)
                self%rhs_bottom(h, 1) = -self%constraints%value(k)
            end do
            call self%saddle%factor(self%mass, self%holonomic_rows, self%nh, error)
            if (allocated(error)) return
            self%rhs_top(:, 1) = 0.0_wp
            call self%saddle%solve(self%holonomic_rows, self%rhs_top(:, 1), &
                & self%rhs_bottom(:, 1), 1, error)
            if (allocated(error)) return
            dq = self%rhs_top(:, 1)
        end if
        self%q_work = q + dq
        call self%constraints%evaluate(self%model, time, self%q_work, u, need_value + need_first &
            & + need_time, error)
        if (allocated(error)) return
        call self%assemble(time, self%q_work, u)
        call self%constraint_matrix()
        associate (cs => self%constraints)
            do k = 1, self%nc
                if (self%model%ucons(k)%holonomic) then
                    self%rhs_bottom(k, 1) = -(dot_product(cs%grad_q(k, :), u) + cs%dt(k))
                else
                    self%rhs_bottom(k, 1) = -cs%value(k)
                end if
            end do
        end associate
        call self%saddle%factor(self%mass, self%c, self%nc, error)
        if (allocated(error)) return
        self%rhs_top(:, 1) = 0.0_wp
        call self%saddle%solve(self%c, self%rhs_top(:, 1), self%rhs_bottom(:, 1), 1, error)
        if (allocated(error)) return
        du = self%rhs_top(:, 1)
    end subroutine project

    !> u^T H u for a square H.
    pure function quadratic_form(h, u) result(value)
        real(wp), intent(in) :: h(:, :), u(:)
        real(wp) :: value
        integer :: j

        value = 0.0_wp
        do j = 1, size(u)
            value = value + u(j)*dot_product(h(:, j), u)
        end do
    end function quadratic_form

    !> Total energy: kinetic plus gravitational potential [J].
    pure function energy(self, q, u) result(e)
        class(equations_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: e
        integer :: p, i0

        e = 0.0_wp
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            e = e + kinetic_energy(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6)) &
                & - self%model%parts(p)%mass*dot_product(self%model%gravity, q(i0 + 1:i0 + 3))
        end do
    end function energy

    !> Constraint force on part p, ground components [N]: the translational rows of C^T lambda,
    !> with C as left by the last accelerations call.
    pure function constraint_force(self, p, lambda) result(force)
        class(equations_type), intent(in) :: self
        integer, intent(in) :: p
        real(wp), intent(in) :: lambda(:)
        real(wp) :: force(3)

        integer :: k

        force = 0.0_wp
        do k = 1, size(lambda)
            force = force + lambda(k)*self%c(k, 6*(p - 1) + 1:6*(p - 1) + 3)
        end do
    end function constraint_force

    !> Constraint force on part p, ground components [N], from its accelerations: m a minus
    !> gravity and the applied forces (Newton's law for the centre of mass). No UCOSUB call
    !> and no solve: for event functions given the accelerations by the integrator.
    pure function reaction_from_accelerations(self, p, time, q, a) result(force)
        class(equations_type), intent(in) :: self
        !> Part index
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and accelerations of the whole system
        real(wp), intent(in) :: q(:), a(:)
        real(wp) :: force(3)
        real(wp) :: applied(3), moment(3)
        integer :: i0

        i0 = 6*(p - 1)
        call force_and_moment(self%model%forces, p, time, q(i0 + 1:i0 + 6), applied, moment)
        force = self%model%parts(p)%mass*(a(i0 + 1:i0 + 3) - self%model%gravity) - applied
    end function reaction_from_accelerations

end module rollcon_equations
