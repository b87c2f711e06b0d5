! SPDX-License-Identifier: MIT
!> A part placed as ADAMS places it (docs/datasets-model.md): its frame in ground (PART's QG
!> and REULER), its centre-of-mass marker in that frame (the CM MARKER's QP and REULER) and its
!> principal axes in the CM marker's axes (the identity when the CM marker's axes are
!> principal; otherwise those of an IP with products, rollcon_inertia_axes). From these, the
!> principal axes in ground at t = 0, whether they start at the singularity of the 3-1-3 Euler
!> angles, and the part's start in ADAMS coordinates. A dataset's assembly and a program that
!> builds its model in code call the same functions, so both give the model the same numbers.
!>
!> A part whose principal z-axis starts parallel to ground z, where the angles are singular,
!> starts in its principal axes turned as a re-basing turns them (basis 1 or 20,
!> docs/rebasing.md).
module rollcon_part_frames
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : rotation_matrix, euler_angles
    use rollcon_rebasing, only : basis_turns, to_new_basis, angle_rates, chosen_turn, &
        & next_basis
    implicit none
    private

    public :: min_sin_theta, principal_frame, starts_singular, part_start

    !> Below this sin(theta) of the principal axes at t = 0 (as for the scenes), the angle
    !> rates, which divide by it, cannot be written in those axes: the part starts in basis 1
    !> or 20
    real(wp), parameter :: min_sin_theta = 1.0e-3_wp

contains

    !> The principal axes in ground at t = 0 (columns): R(frame) R(cm) P.
    pure function principal_frame(frame_angles, cm_angles, principal) result(r)
        !> The part frame's 3-1-3 Euler angles in ground (REULER of the PART) [rad]
        real(wp), intent(in) :: frame_angles(3)
        !> The CM marker's 3-1-3 Euler angles in the part frame (REULER of the MARKER) [rad]
        real(wp), intent(in) :: cm_angles(3)
        !> The principal axes (columns) in the CM marker's axes
        real(wp), intent(in) :: principal(3, 3)
        real(wp) :: r(3, 3)

        r = matmul(matmul(rotation_matrix(frame_angles(1), frame_angles(2), frame_angles(3)), &
            & rotation_matrix(cm_angles(1), cm_angles(2), cm_angles(3))), principal)
    end function principal_frame

    !> True when principal axes r (columns, in ground) have their z-axis parallel to ground z,
    !> to sin(theta) < min_sin_theta.
    pure logical function starts_singular(r)
        real(wp), intent(in) :: r(3, 3)

        starts_singular = hypot(r(1, 3), r(2, 3)) < min_sin_theta
    end function starts_singular

    !> The start of a part: q = (X, Y, Z, psi, theta, phi) [m, rad] of its centre of mass and
    !> principal axes, and u = dq/dt, in basis 0 (the principal axes themselves) or, when they
    !> start at the singularity (starts_singular), in those axes turned as a re-basing turns
    !> them (rollcon_rebasing's chosen_turn: about body y when |omega'_x| > |omega'_y|, else
    !> about body x): R T, omega' turned with T^T (T = basis_turns(:, :, turn)), basis 20 or 1.
    pure subroutine part_start(frame_origin, frame_angles, cm_origin, cm_angles, principal, &
            & velocity, angular_velocity, q, u, basis)
        !> The part frame's origin in ground (QG) [m] and 3-1-3 Euler angles (REULER) [rad]
        real(wp), intent(in) :: frame_origin(3), frame_angles(3)
        !> The CM marker's origin (QP) [m] and 3-1-3 Euler angles (REULER) [rad] in the frame
        real(wp), intent(in) :: cm_origin(3), cm_angles(3)
        !> The principal axes (columns) in the CM marker's axes
        real(wp), intent(in) :: principal(3, 3)
        !> Velocity of the centre of mass, ground axes [m/s] (VX, VY, VZ), and angular
        !> velocity in the CM marker's axes [rad/s] (WX, WY, WZ)
        real(wp), intent(in) :: velocity(3), angular_velocity(3)
        real(wp), intent(out) :: q(6), u(6)
        !> The basis of q and u: 0, 1 (turned about x) or 20 (turned about y)
        integer, intent(out), optional :: basis
        real(wp) :: r_part(3, 3), r_cm(3, 3), omega(3)
        integer :: turn

        r_part = rotation_matrix(frame_angles(1), frame_angles(2), frame_angles(3))
        q(1:3) = frame_origin + matmul(r_part, cm_origin)
        r_cm = principal_frame(frame_angles, cm_angles, principal)
        ! WX, WY, WZ are about the CM marker's axes: in the principal axes
        omega = matmul(transpose(principal), angular_velocity)
        if (present(basis)) basis = 0
        if (starts_singular(r_cm)) then
            turn = chosen_turn(omega)
            r_cm = matmul(r_cm, basis_turns(:, :, turn))
            omega = to_new_basis(omega, turn)
            if (present(basis)) basis = next_basis(0, turn)
        end if
        q(4:6) = euler_angles(r_cm)
        u(1:3) = velocity
        u(4:6) = angle_rates(q(5), q(6), omega)
    end subroutine part_start

end module rollcon_part_frames
