! SPDX-License-Identifier: MIT
!> Body-fixed 3-1-3 Euler angles: rotation matrix, the map from angle rates to body angular
!> velocity, and its derivatives (docs/design.md §3).
module rollcon_rotation
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: rotation_matrix, rotation_of_sines, rate_matrix, rate_matrix_dtheta, rate_matrix_dphi
    public :: rate_matrix_dtheta2, rate_matrix_dtheta_dphi, rate_matrix_dphi2, cross
    public :: times, transpose_times, rate_matrices, euler_angles

contains

    !> R = Rz(psi) Rx(theta) Rz(phi): body components to ground components.
    pure function rotation_matrix(psi, theta, phi) result(r)
        !> Euler angles [rad]
        real(wp), intent(in) :: psi, theta, phi
        real(wp) :: r(3, 3)
        real(wp) :: cps, sps, cth, sth, cph, sph

        cps = cos(psi)
        sps = sin(psi)
        cth = cos(theta)
        sth = sin(theta)
        cph = cos(phi)
        sph = sin(phi)
        r = sines_rotation(cps, sps, cth, sth, cph, sph)
    end function rotation_matrix

    !> rotation_matrix from the cosines and sines of the angles, for a caller that needs them
    !> too (rollcon_reactions' part_attitude): the same numbers.
    pure function rotation_of_sines(cps, sps, cth, sth, cph, sph) result(r)
        !> cos and sin of psi, theta and phi
        real(wp), intent(in) :: cps, sps, cth, sth, cph, sph
        real(wp) :: r(3, 3)

        r = sines_rotation(cps, sps, cth, sth, cph, sph)
    end function rotation_of_sines

    !> rotation_matrix's and rotation_of_sines' R from the cosines and sines (private: inlined
    !> into both, as an exported procedure of a shared library is not)
    pure function sines_rotation(cps, sps, cth, sth, cph, sph) result(r)
        real(wp), intent(in) :: cps, sps, cth, sth, cph, sph
        real(wp) :: r(3, 3)

        r(1, :) = [cps*cph - sps*cth*sph, -cps*sph - sps*cth*cph, sps*sth]
        r(2, :) = [sps*cph + cps*cth*sph, -sps*sph + cps*cth*cph, -cps*sth]
        r(3, :) = [sth*sph, sth*cph, cth]
    end function sines_rotation

    !> B with omega' = B (psidot, thetadot, phidot): body components of the angular velocity.
    !> Singular where sin(theta) = 0.
    pure function rate_matrix(theta, phi) result(b)
        !> Nutation and spin angles [rad]
        real(wp), intent(in) :: theta, phi
        real(wp) :: b(3, 3)

        b(:, 1) = [sin(theta)*sin(phi), sin(theta)*cos(phi), cos(theta)]
        b(:, 2) = [cos(phi), -sin(phi), 0.0_wp]
        b(:, 3) = [0.0_wp, 0.0_wp, 1.0_wp]
    end function rate_matrix

    !> B, dB/dtheta and dB/dphi together, from one sine and cosine of each angle (the
    !> right-hand side's path; the functions above give each alone).
    pure subroutine rate_matrices(theta, phi, b, b_theta, b_phi)
        !> Nutation and spin angles [rad]
        real(wp), intent(in) :: theta, phi
        !> B, dB/dtheta, dB/dphi
        real(wp), intent(out) :: b(3, 3), b_theta(3, 3), b_phi(3, 3)
        real(wp) :: cth, sth, cph, sph

        cth = cos(theta)
        sth = sin(theta)
        cph = cos(phi)
        sph = sin(phi)
        b(:, 1) = [sth*sph, sth*cph, cth]
        b(:, 2) = [cph, -sph, 0.0_wp]
        b(:, 3) = [0.0_wp, 0.0_wp, 1.0_wp]
        b_theta = 0.0_wp
        b_theta(:, 1) = [cth*sph, cth*cph, -sth]
        b_phi = 0.0_wp
        b_phi(:, 1) = [sth*cph, -sth*sph, 0.0_wp]
        b_phi(:, 2) = [-sph, -cph, 0.0_wp]
    end subroutine rate_matrices

    !> dB/dtheta.
    pure function rate_matrix_dtheta(theta, phi) result(b)
        real(wp), intent(in) :: theta, phi
        real(wp) :: b(3, 3)

        b = 0.0_wp
        b(:, 1) = [cos(theta)*sin(phi), cos(theta)*cos(phi), -sin(theta)]
    end function rate_matrix_dtheta

    !> dB/dphi.
    pure function rate_matrix_dphi(theta, phi) result(b)
        real(wp), intent(in) :: theta, phi
        real(wp) :: b(3, 3)

        b = 0.0_wp
        b(:, 1) = [sin(theta)*cos(phi), -sin(theta)*sin(phi), 0.0_wp]
        b(:, 2) = [-sin(phi), -cos(phi), 0.0_wp]
    end function rate_matrix_dphi

    !> d2B/dtheta2.
    pure function rate_matrix_dtheta2(theta, phi) result(b)
        real(wp), intent(in) :: theta, phi
        real(wp) :: b(3, 3)

        b = 0.0_wp
        b(:, 1) = [-sin(theta)*sin(phi), -sin(theta)*cos(phi), -cos(theta)]
    end function rate_matrix_dtheta2

    !> d2B/dtheta dphi.
    pure function rate_matrix_dtheta_dphi(theta, phi) result(b)
        real(wp), intent(in) :: theta, phi
        real(wp) :: b(3, 3)

        b = 0.0_wp
        b(:, 1) = [cos(theta)*cos(phi), -cos(theta)*sin(phi), 0.0_wp]
    end function rate_matrix_dtheta_dphi

    !> d2B/dphi2.
    pure function rate_matrix_dphi2(theta, phi) result(b)
        real(wp), intent(in) :: theta, phi
        real(wp) :: b(3, 3)

        b = 0.0_wp
        b(:, 1) = [-sin(theta)*sin(phi), -sin(theta)*cos(phi), 0.0_wp]
        b(:, 2) = [-cos(phi), sin(phi), 0.0_wp]
    end function rate_matrix_dphi2

    !> a v for a 3 x 3 matrix (written out: matmul may allocate a temporary in the hot path).
    pure function times(a, v) result(w)
        real(wp), intent(in) :: a(3, 3), v(3)
        real(wp) :: w(3)

        w = a(:, 1)*v(1) + a(:, 2)*v(2) + a(:, 3)*v(3)
    end function times

    !> a^T v for a 3 x 3 matrix.
    pure function transpose_times(a, v) result(w)
        real(wp), intent(in) :: a(3, 3), v(3)
        real(wp) :: w(3)

        w = [sum(a(:, 1)*v), sum(a(:, 2)*v), sum(a(:, 3)*v)]
    end function transpose_times

    !> Cross product a x b.
    pure function cross(a, b) result(c)
        real(wp), intent(in) :: a(3), b(3)
        real(wp) :: c(3)

        c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
    end function cross

    !> Body-fixed 3-1-3 Euler angles (psi, theta, phi) of R = Rz(psi) Rx(theta) Rz(phi) [rad]:
    !> theta in [0, pi], psi and phi in (-pi, pi]; where sin(theta) = 0 only psi + phi (or
    !> psi - phi) is defined, and phi = 0.
    pure function euler_angles(r) result(angles)
        real(wp), intent(in) :: r(3, 3)
        real(wp) :: angles(3)
        real(wp) :: sin_theta

        sin_theta = hypot(r(1, 3), r(2, 3))
        angles(2) = atan2(sin_theta, r(3, 3))
        if (sin_theta > 0.0_wp) then
            angles(1) = atan2(r(1, 3), -r(2, 3))
            angles(3) = atan2(r(3, 1), r(3, 2))
        else
            angles(1) = atan2(r(2, 1), r(1, 1))
            angles(3) = 0.0_wp
        end if
    end function euler_angles

end module rollcon_rotation
