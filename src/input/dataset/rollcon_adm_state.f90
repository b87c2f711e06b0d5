! SPDX-License-Identifier: MIT
!> The initial state of a dataset's part in ADAMS coordinates: the centre of mass and the 3-1-3
!> Euler angles of the principal axes (the CM marker's pose in ground), their rates from the
!> part's VX, VY, VZ (ground axes) and WX, WY, WZ (CM marker axes).
module rollcon_adm_state
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : rotation_matrix, euler_angles
    use rollcon_adm_model, only : adm_model_type, adm_part_type
    implicit none
    private

    public :: part_state, euler_angles

contains

    !> q = (X, Y, Z, psi, theta, phi) [m, rad] and u = dq/dt of a non-ground part. The
    !> principal-axes rule (sin theta well away from 0) is checked when the dataset is read.
    pure subroutine part_state(model, part, q, u)
        type(adm_model_type), intent(in) :: model
        type(adm_part_type), intent(in) :: part
        real(wp), intent(out) :: q(6), u(6)
        real(wp) :: r_part(3, 3), r_cm(3, 3), omega(3)
        integer :: m

        m = findloc(model%markers%id, part%cm, dim=1)
        r_part = rotation_matrix(part%reuler(1), part%reuler(2), part%reuler(3))
        r_cm = matmul(r_part, rotation_matrix(model%markers(m)%reuler(1), &
            & model%markers(m)%reuler(2), model%markers(m)%reuler(3)))
        q(1:3) = part%qg + matmul(r_part, model%markers(m)%qp)
        q(4:6) = euler_angles(r_cm)
        u(1:3) = part%velocity
        ! omega' = B (psidot, thetadot, phidot) solved for the rates (docs/design.md §3)
        omega = part%angular_velocity
        associate (theta => q(5), phi => q(6))
            u(4) = (omega(1)*sin(phi) + omega(2)*cos(phi))/sin(theta)
            u(5) = omega(1)*cos(phi) - omega(2)*sin(phi)
            u(6) = omega(3) - u(4)*cos(theta)
        end associate
    end subroutine part_state

end module rollcon_adm_state
