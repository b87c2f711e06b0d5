! SPDX-License-Identifier: MIT
!> The initial state of a dataset's part in ADAMS coordinates: the centre of mass and the 3-1-3
!> Euler angles of the principal axes (the CM marker's pose in ground, turned onto the
!> principal axes of an IP with products), their rates from the part's VX, VY, VZ (ground
!> axes) and WX, WY, WZ (CM marker axes). A part whose principal z-axis starts parallel to
!> ground z, where the angles are singular, is given in its principal axes turned as a
!> re-basing turns them (basis 1, docs/rebasing.md).
module rollcon_adm_state
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : rotation_matrix, euler_angles
    use rollcon_rebasing, only : basis_turn, to_new_basis, angle_rates
    use rollcon_adm_model, only : adm_model_type, adm_part_type
    implicit none
    private

    public :: part_state, euler_angles, starts_singular, min_sin_theta

    !> Below this sin(theta) of the CM marker's axes at t = 0 (as for the scenes), the angle
    !> rates, which divide by it, cannot be written in those axes: the part starts in basis 1
    real(wp), parameter :: min_sin_theta = 1.0e-3_wp

contains

    !> q = (X, Y, Z, psi, theta, phi) [m, rad] and u = dq/dt of a non-ground part, in the
    !> basis `basis` of its principal axes: 0, the CM marker's axes, or 1, those axes turned
    !> by basis_turn (R_cm T, omega' turned with T^T) when they start at the singularity
    !> (starts_singular).
    pure subroutine part_state(model, part, q, u, basis)
        type(adm_model_type), intent(in) :: model
        type(adm_part_type), intent(in) :: part
        real(wp), intent(out) :: q(6), u(6)
        !> The basis of q and u
        integer, intent(out), optional :: basis
        real(wp) :: r_part(3, 3), r_cm(3, 3), omega(3)
        integer :: m

        m = findloc(model%markers%id, part%cm, dim=1)
        r_part = rotation_matrix(part%reuler(1), part%reuler(2), part%reuler(3))
        q(1:3) = part%qg + matmul(r_part, model%markers(m)%qp)
        r_cm = cm_rotation(model, part)
        ! WX, WY, WZ are about the CM marker's axes: in the principal axes
        omega = matmul(transpose(part%principal), part%angular_velocity)
        if (present(basis)) basis = 0
        if (starts_singular(model, part)) then
            r_cm = matmul(r_cm, basis_turn)
            omega = to_new_basis(omega)
            if (present(basis)) basis = 1
        end if
        q(4:6) = euler_angles(r_cm)
        u(1:3) = part%velocity
        u(4:6) = angle_rates(q(5), q(6), omega)
    end subroutine part_state

    !> True when the part's principal z-axis is parallel to ground z at t = 0, to
    !> sin(theta) < min_sin_theta.
    pure logical function starts_singular(model, part)
        type(adm_model_type), intent(in) :: model
        type(adm_part_type), intent(in) :: part
        real(wp) :: r(3, 3)

        r = cm_rotation(model, part)
        starts_singular = hypot(r(1, 3), r(2, 3)) < min_sin_theta
    end function starts_singular

    !> The principal axes in ground at t = 0: the part's REULER, then the CM marker's, then the
    !> principal axes in the CM marker's (the identity without products of inertia).
    pure function cm_rotation(model, part) result(r_cm)
        type(adm_model_type), intent(in) :: model
        type(adm_part_type), intent(in) :: part
        real(wp) :: r_cm(3, 3)
        integer :: m

        m = findloc(model%markers%id, part%cm, dim=1)
        r_cm = matmul(rotation_matrix(part%reuler(1), part%reuler(2), part%reuler(3)), &
            & rotation_matrix(model%markers(m)%reuler(1), model%markers(m)%reuler(2), &
            & model%markers(m)%reuler(3)))
        r_cm = matmul(r_cm, part%principal)
    end function cm_rotation

end module rollcon_adm_state
