! SPDX-License-Identifier: MIT
!> The maths of re-basing a part's principal axes (docs/rebasing.md): when a part's 3-1-3
!> Euler angles come near their singularity (sin(theta) small: the body z axis nearly along
!> ground Z), its principal frame is turned by 90 degrees about its body x axis, the principal
!> moments are permuted to match, and the coordinates and rates are recomputed from the same
!> physical state: the same rotation matrix R and the same angular velocity.
!>
!> The turn T (columns: the new axes in the old ones) takes new x = old x, new y = -old z,
!> new z = old y, so R_new = R_old T and the new theta satisfies
!> cos(theta_new) = R_old(3, 2) = sin(theta_old) cos(phi_old): near the singularity the new
!> theta is within theta_old of pi/2.
module rollcon_rebasing
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : rotation_matrix, rate_matrix, times, transpose_times
    implicit none
    private

    public :: basis_turn, rebased_state, rebased_inertia, to_new_basis, euler_angles_near
    public :: own_axes_rotation, own_axes_inertia, angle_rates

    !> The turn of a re-basing: its columns are the new principal axes in the old ones
    !> (new x = old x, new y = -old z, new z = old y: 90 degrees about body x)
    real(wp), parameter :: basis_turn(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, &
        & 0.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp], [3, 3])

contains

    !> A part's coordinates and rates in the turned basis, from the same physical state:
    !> centre of mass and its velocity unchanged, R_new = R_old basis_turn, psi and phi taken
    !> within pi of their old values (so that a plot does not jump by whole turns), and the
    !> angle rates from the body angular velocity omega'_new = basis_turn^T omega'_old.
    pure subroutine rebased_state(q_old, u_old, q_new, u_new)
        !> The part's X, Y, Z, psi, theta, phi [m, rad] and their rates [m/s, rad/s], old basis
        real(wp), intent(in) :: q_old(6), u_old(6)
        !> The same in the new basis
        real(wp), intent(out) :: q_new(6), u_new(6)
        real(wp) :: r_new(3, 3), omega_old(3), omega_new(3), angles(3)

        r_new = matmul(rotation_matrix(q_old(4), q_old(5), q_old(6)), basis_turn)
        angles = euler_angles_near(r_new, q_old(4), q_old(6))
        omega_old = times(rate_matrix(q_old(5), q_old(6)), u_old(4:6))
        omega_new = transpose_times(basis_turn, omega_old)
        q_new(1:3) = q_old(1:3)
        q_new(4:6) = angles
        u_new(1:3) = u_old(1:3)
        ! sin(theta) of the new basis is at least cos(theta_old) > 0 near the old singularity
        u_new(4:6) = angle_rates(angles(2), angles(3), omega_new)
    end subroutine rebased_state

    !> The 3-1-3 angle rates (psidot, thetadot, phidot) [rad/s] of a body angular velocity:
    !> the inverse of omega' = B (psidot, thetadot, phidot) (docs/design.md §3). sin(theta)
    !> must be away from 0 (the rates divide by it).
    pure function angle_rates(theta, phi, omega) result(rates)
        !> Nutation and spin angles [rad]
        real(wp), intent(in) :: theta, phi
        !> Angular velocity, body components [rad/s]
        real(wp), intent(in) :: omega(3)
        real(wp) :: rates(3)
        real(wp) :: sth, cth, sph, cph

        sth = sin(theta)
        cth = cos(theta)
        sph = sin(phi)
        cph = cos(phi)
        rates(1) = (omega(1)*sph + omega(2)*cph)/sth
        rates(2) = omega(1)*cph - omega(2)*sph
        rates(3) = omega(3) - rates(1)*cth
    end function angle_rates

    !> The principal moments about the new x, y, z axes: the old (A1, A3, A2) [kg m^2].
    pure function rebased_inertia(inertia) result(turned)
        !> Principal moments about the old x, y, z axes [kg m^2]
        real(wp), intent(in) :: inertia(3)
        real(wp) :: turned(3)

        turned = [inertia(1), inertia(3), inertia(2)]
    end function rebased_inertia

    !> Components in the new basis of a body-fixed vector given in the old one (a marker's
    !> origin or axis): basis_turn^T v.
    pure function to_new_basis(v) result(w)
        !> Components in the old principal axes
        real(wp), intent(in) :: v(3)
        real(wp) :: w(3)

        w = transpose_times(basis_turn, v)
    end function to_new_basis

    !> The rotation of a part's own principal axes (its CM marker's, basis 0) from the
    !> rotation R of basis number `basis` (a CSV's basis_<id>): R (basis_turn^T)^basis, for
    !> whoever draws a part in its own axes from a re-based row. The turn has order 4.
    pure function own_axes_rotation(r, basis) result(own)
        !> Rotation of the principal axes of the basis, body to ground
        real(wp), intent(in) :: r(3, 3)
        !> Number of the basis, >= 0
        integer, intent(in) :: basis
        real(wp) :: own(3, 3)
        integer :: k

        own = r
        do k = 1, modulo(basis, 4)
            own = matmul(own, transpose(basis_turn))
        end do
    end function own_axes_rotation

    !> The principal moments about a part's own principal axes (its CM marker's, basis 0) from
    !> those about the axes of basis number `basis` [kg m^2]: the permutation of a re-basing
    !> (rebased_inertia) has order 2.
    pure function own_axes_inertia(inertia, basis) result(own)
        !> Principal moments about the x, y, z axes of the basis [kg m^2]
        real(wp), intent(in) :: inertia(3)
        !> Number of the basis, >= 0
        integer, intent(in) :: basis
        real(wp) :: own(3)

        own = inertia
        if (modulo(basis, 2) == 1) own = rebased_inertia(inertia)
    end function own_axes_inertia

    !> The 3-1-3 angles (psi, theta, phi) of R = Rz(psi) Rx(theta) Rz(phi) [rad], theta in
    !> [0, pi], psi and phi the values within pi of psi_near and phi_near. R must be away from
    !> the singularity (sin(theta) > 0).
    pure function euler_angles_near(r, psi_near, phi_near) result(angles)
        real(wp), intent(in) :: r(3, 3)
        !> The angles to stay near [rad]
        real(wp), intent(in) :: psi_near, phi_near
        real(wp) :: angles(3)

        angles(2) = atan2(hypot(r(1, 3), r(2, 3)), r(3, 3))
        angles(1) = nearest_turn(atan2(r(1, 3), -r(2, 3)), psi_near)
        angles(3) = nearest_turn(atan2(r(3, 1), r(3, 2)), phi_near)
    end function euler_angles_near

    !> angle + 2 pi k for the whole k that brings it within pi of near [rad].
    elemental function nearest_turn(angle, near) result(shifted)
        real(wp), intent(in) :: angle, near
        real(wp) :: shifted

        shifted = angle + 2.0_wp*pi*anint((near - angle)/(2.0_wp*pi))
    end function nearest_turn

end module rollcon_rebasing
