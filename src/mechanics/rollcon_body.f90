! SPDX-License-Identifier: MIT
!> Rigid part in ADAMS coordinates: centre of mass and 3-1-3 Euler angles of the principal axes.
!>
!> Equations of motion M(q) a = f(q, u, t) (+ constraint forces), with q = (X, Y, Z, psi, theta,
!> phi), u = dq/dt, a = du/dt (docs/design.md §3). The rotational rows are Euler's
!> equations J alpha' + omega' x J omega' = tau' premultiplied by B^T, where omega' = B u_rot:
!> B^T J B is the Lagrangian mass matrix and B^T tau' the generalised moment.
module rollcon_body
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : rotation_matrix, rate_matrix, rate_matrix_dtheta, &
        & rate_matrix_dphi, rate_matrix_dtheta2, rate_matrix_dtheta_dphi, rate_matrix_dphi2, &
        & cross, &
        & times, transpose_times, rate_matrices
    implicit none
    private

    public :: part_type, body_residual, body_mass_matrix, body_residual_jacobian
    public :: kinetic_energy, body_angular_velocity, body_mass_and_force, energy_gradient

    !> A rigid part with principal (diagonal) inertia at its centre of mass
    type :: part_type
        !> ADAMS part id, as UCOVAR declarations refer to it
        integer :: id = 1
        !> Mass [kg]
        real(wp) :: mass = 1.0_wp
        !> Principal moments of inertia about the body x, y, z axes [kg m^2]
        real(wp) :: inertia(3) = 1.0_wp
    end type part_type

contains

    !> Body components of the angular velocity [rad/s].
    pure function body_angular_velocity(q, u) result(omega)
        !> Coordinates [m, rad]
        real(wp), intent(in) :: q(6)
        !> Their rates [m/s, rad/s]
        real(wp), intent(in) :: u(6)
        real(wp) :: omega(3)

        omega = times(rate_matrix(q(5), q(6)), u(4:6))
    end function body_angular_velocity

    !> Kinetic energy [J].
    pure function kinetic_energy(part, q, u) result(energy)
        type(part_type), intent(in) :: part
        real(wp), intent(in) :: q(6), u(6)
        real(wp) :: energy
        real(wp) :: omega(3)

        omega = body_angular_velocity(q, u)
        energy = 0.5_wp*part%mass*sum(u(1:3)**2) + 0.5_wp*sum(part%inertia*omega**2)
    end function kinetic_energy

    !> The gradient of the part's energy, kinetic plus gravitational potential, with respect to
    !> its coordinates and their rates [J/m, J/rad; kg m/s, kg m^2/s]: dT/dq (0 for X, Y, Z,
    !> psi; (J omega) . (dB/dtheta u_rot) and (J omega) . (dB/dphi u_rot) for theta and phi)
    !> minus m g for X, Y, Z; dT/du = M(q) u (m v, and B^T J omega). Exact (docs/design.md §3).
    pure subroutine energy_gradient(part, q, u, gravity, d_q, d_u)
        type(part_type), intent(in) :: part
        !> Coordinates [m, rad] and their rates [m/s, rad/s]
        real(wp), intent(in) :: q(6), u(6)
        !> Gravity, ground components [m/s^2]
        real(wp), intent(in) :: gravity(3)
        real(wp), intent(out) :: d_q(6), d_u(6)
        real(wp) :: b(3, 3), j_omega(3)

        b = rate_matrix(q(5), q(6))
        j_omega = part%inertia*times(b, u(4:6))
        d_q(1:3) = -part%mass*gravity
        d_q(4) = 0.0_wp
        d_q(5) = dot_product(j_omega, times(rate_matrix_dtheta(q(5), q(6)), u(4:6)))
        d_q(6) = dot_product(j_omega, times(rate_matrix_dphi(q(5), q(6)), u(4:6)))
        d_u(1:3) = part%mass*u(1:3)
        d_u(4:6) = transpose_times(b, j_omega)
    end subroutine energy_gradient

    !> M(q) = diag(m, m, m, B^T J B).
    pure function body_mass_matrix(part, q) result(m)
        type(part_type), intent(in) :: part
        real(wp), intent(in) :: q(6)
        real(wp) :: m(6, 6)
        real(wp) :: b(3, 3)
        integer :: i, j

        m = 0.0_wp
        do i = 1, 3
            m(i, i) = part%mass
        end do
        b = rate_matrix(q(5), q(6))
        do j = 1, 3
            do i = 1, 3
                m(3 + i, 3 + j) = sum(b(:, i)*part%inertia*b(:, j))
            end do
        end do
    end function body_mass_matrix

    !> M(q) and f = -(M a - f) at a = 0 together: what body_mass_matrix and body_residual give,
    !> with each sine and cosine computed once and no rotation when no moment acts (the hot
    !> path of every right-hand side and residual).
    pure subroutine body_mass_and_force(part, q, u, force, torque, gravity, m, f)
        type(part_type), intent(in) :: part
        !> Coordinates and rates
        real(wp), intent(in) :: q(6), u(6)
        !> Applied force and moment about the centre of mass, ground components [N, N m]
        real(wp), intent(in) :: force(3), torque(3)
        !> Gravitational acceleration, ground components [m/s^2]
        real(wp), intent(in) :: gravity(3)
        !> Mass matrix and generalised forces
        real(wp), intent(out) :: m(6, 6), f(6)
        real(wp) :: b(3, 3), b_t(3, 3), b_p(3, 3), omega(3), drift(3), torque_body(3)
        integer :: i, j

        call rate_matrices(q(5), q(6), b, b_t, b_p)
        m = 0.0_wp
        do i = 1, 3
            m(i, i) = part%mass
        end do
        do j = 1, 3
            do i = 1, 3
                m(3 + i, 3 + j) = sum(b(:, i)*part%inertia*b(:, j))
            end do
        end do
        f(1:3) = part%mass*gravity + force
        torque_body = 0.0_wp
        if (any(torque /= 0.0_wp)) torque_body = transpose_times(rotation_matrix(q(4), q(5), &
            & q(6)), torque)
        omega = times(b, u(4:6))
        drift = u(5)*times(b_t, u(4:6)) + u(6)*times(b_p, u(4:6))
        f(4:6) = -transpose_times(b, part%inertia*drift + cross(omega, part%inertia*omega) &
            & - torque_body)
    end subroutine body_mass_and_force

    !> r = M a - f: zero when the part moves as the applied loads say.
    pure function body_residual(part, q, u, a, force, torque, gravity) result(r)
        type(part_type), intent(in) :: part
        !> Coordinates, rates and accelerations
        real(wp), intent(in) :: q(6), u(6), a(6)
        !> Applied force and moment about the centre of mass, ground components [N, N m]
        real(wp), intent(in) :: force(3), torque(3)
        !> Gravitational acceleration, ground components [m/s^2]
        real(wp), intent(in) :: gravity(3)
        real(wp) :: r(6)
        real(wp) :: b(3, 3), omega(3), alpha(3), torque_body(3), rot(3, 3)

        r(1:3) = part%mass*(a(1:3) - gravity) - force
        b = rate_matrix(q(5), q(6))
        rot = rotation_matrix(q(4), q(5), q(6))
        torque_body = transpose_times(rot, torque)
        omega = times(b, u(4:6))
        alpha = times(b, a(4:6)) + rate_drift(q, u)
        r(4:6) = transpose_times(b, part%inertia*alpha + cross(omega, part%inertia*omega) &
            & - torque_body)
    end function body_residual

    !> dB/dt u_rot: the part of the body angular acceleration not proportional to a.
    pure function rate_drift(q, u) result(d)
        real(wp), intent(in) :: q(6), u(6)
        real(wp) :: d(3)

        d = u(5)*times(rate_matrix_dtheta(q(5), q(6)), u(4:6)) &
            & + u(6)*times(rate_matrix_dphi(q(5), q(6)), u(4:6))
    end function rate_drift

    !> d(M a - f)/dq and d(M a - f)/du; d/da is the mass matrix. The applied moment is held at
    !> its body components (it acts during short pulses only), so orientation terms of the
    !> loads are left out: an approximation of the Newton matrix, not of the equations.
    pure subroutine body_residual_jacobian(part, q, u, a, torque, dr_dq, dr_du)
        type(part_type), intent(in) :: part
        real(wp), intent(in) :: q(6), u(6), a(6)
        !> Applied moment about the centre of mass, ground components [N m]
        real(wp), intent(in) :: torque(3)
        real(wp), intent(out) :: dr_dq(6, 6), dr_du(6, 6)
        real(wp) :: b(3, 3), b_t(3, 3), b_p(3, 3), b_tt(3, 3), b_tp(3, 3), b_pp(3, 3)
        real(wp) :: omega(3), alpha(3), w(3), jw(3), ur(3), ar(3), torque_body(3)
        real(wp) :: d_omega(3), d_alpha(3)
        integer :: j

        associate (theta => q(5), phi => q(6), inertia => part%inertia)
            b = rate_matrix(theta, phi)
            b_t = rate_matrix_dtheta(theta, phi)
            b_p = rate_matrix_dphi(theta, phi)
            b_tt = rate_matrix_dtheta2(theta, phi)
            b_tp = rate_matrix_dtheta_dphi(theta, phi)
            b_pp = rate_matrix_dphi2(theta, phi)
            ur = u(4:6)
            ar = a(4:6)
            torque_body = transpose_times(rotation_matrix(q(4), theta, phi), torque)
            omega = times(b, ur)
            jw = inertia*omega
            alpha = times(b, ar) + u(5)*times(b_t, ur) + u(6)*times(b_p, ur)
            w = inertia*alpha + cross(omega, jw) - torque_body

            dr_dq = 0.0_wp
            dr_du = 0.0_wp
            ! theta
            d_omega = times(b_t, ur)
            d_alpha = times(b_t, ar) + u(5)*times(b_tt, ur) + u(6)*times(b_tp, ur)
            dr_dq(4:6, 5) = transpose_times(b_t, w) + transpose_times(b, dw())
            ! phi
            d_omega = times(b_p, ur)
            d_alpha = times(b_p, ar) + u(5)*times(b_tp, ur) + u(6)*times(b_pp, ur)
            dr_dq(4:6, 6) = transpose_times(b_p, w) + transpose_times(b, dw())
            ! psidot, thetadot, phidot
            do j = 1, 3
                d_omega = b(:, j)
                d_alpha = u(5)*b_t(:, j) + u(6)*b_p(:, j)
                if (j == 2) d_alpha = d_alpha + times(b_t, ur)
                if (j == 3) d_alpha = d_alpha + times(b_p, ur)
                dr_du(4:6, 3 + j) = transpose_times(b, dw())
            end do
        end associate

    contains

        !> Derivative of w for the current d_omega, d_alpha.
        pure function dw() result(dw_value)
            real(wp) :: dw_value(3)

            dw_value = part%inertia*d_alpha + cross(d_omega, jw) &
                & + cross(omega, part%inertia*d_omega)
        end function dw

    end subroutine body_residual_jacobian

end module rollcon_body
