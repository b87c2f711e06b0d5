! SPDX-License-Identifier: MIT
!> Markers: body-fixed points with axes, as ADAMS's MARKER statements give them, and what the
!> state functions of a dataset expression measure of one (position, velocity, angular
!> velocity, 3-1-3 angles of its axes), from ground in ground axes (docs/datasets-model.md).
!>
!> A marker on a part is fixed in the part's principal axes at its centre of mass (the CM
!> marker's frame), so it moves with the part's coordinates q(6 (p - 1) + 1 : 6 p) (docs/design.md
!> §3); a ground marker (part 0) is fixed in ground.
module rollcon_marker
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : rotation_matrix, times, cross, euler_angles
    use rollcon_body, only : body_angular_velocity
    use rollcon_rebasing, only : to_new_basis
    use rollcon_expression, only : quantity_dx, quantity_vx, quantity_wx, quantity_psi
    implicit none
    private

    public :: marker_type, marker_motion, marker_quantity, turn_marker, part_marker

    !> A marker
    type :: marker_type
        !> Its id, as expressions name it
        integer :: id = 0
        !> Index of its part in the model (0: ground)
        integer :: part = 0
        !> Origin: from the part's centre of mass in its principal axes (ground: in ground) [m]
        real(wp) :: point(3) = 0.0_wp
        !> Axes: the columns are the marker's x, y, z in the part's principal axes (ground: in
        !> ground axes)
        real(wp) :: axes(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
            & 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
        !> The axes are the part's principal axes (a CM marker): PSI, THETA, PHI are then the
        !> part's own coordinates, continuous in time
        logical :: principal = .false.
    end type marker_type

contains

    !> Position [m], velocity [m/s], axes in ground (columns) and angular velocity [rad/s] of
    !> a marker, ground components, for the system's coordinates q and rates u.
    pure subroutine marker_motion(marker, q, u, position, velocity, axes, omega)
        type(marker_type), intent(in) :: marker
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: position(3), velocity(3), axes(3, 3), omega(3)
        real(wp) :: rotation(3, 3), arm(3)
        integer :: i0, k

        if (marker%part == 0) then
            position = marker%point
            velocity = 0.0_wp
            axes = marker%axes
            omega = 0.0_wp
            return
        end if
        i0 = 6*(marker%part - 1)
        rotation = rotation_matrix(q(i0 + 4), q(i0 + 5), q(i0 + 6))
        arm = times(rotation, marker%point)
        position = q(i0 + 1:i0 + 3) + arm
        ! column by column: matmul may allocate a temporary, and this is the hot path
        do k = 1, 3
            axes(:, k) = times(rotation, marker%axes(:, k))
        end do
        omega = times(rotation, body_angular_velocity(q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6)))
        velocity = u(i0 + 1:i0 + 3) + cross(omega, arm)
    end subroutine marker_motion

    !> One state function of a marker in SI units (quantity codes of rollcon_expression): DX..DZ
    !> [m], VX..VZ [m/s], WX..WZ [rad/s], PSI, THETA, PHI [rad] of its axes in ground.
    pure function marker_quantity(marker, quantity, q, u) result(value)
        type(marker_type), intent(in) :: marker
        integer, intent(in) :: quantity
        !> Coordinates and rates of all parts
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: value
        real(wp) :: position(3), velocity(3), axes(3, 3), omega(3), angles(3)
        integer :: k

        if (quantity >= quantity_psi .and. marker%principal .and. marker%part > 0) then
            value = q(6*(marker%part - 1) + 4 + quantity - quantity_psi)
            return
        end if
        call marker_motion(marker, q, u, position, velocity, axes, omega)
        k = mod(quantity - 1, 3) + 1
        if (quantity >= quantity_psi) then
            angles = euler_angles(axes)
            value = angles(k)
        else if (quantity >= quantity_wx) then
            value = omega(k)
        else if (quantity >= quantity_vx) then
            value = velocity(k)
        else if (quantity >= quantity_dx) then
            value = position(k)
        else
            value = 0.0_wp
        end if
    end function marker_quantity

    !> A marker of part p given in p's principal axes turned by a re-basing (rollcon_rebasing's
    !> turn_about_x or turn_about_y); a marker of another part is left as it is. Its axes are
    !> then no longer the part's principal axes: a CM marker's angles are computed from its
    !> axes from here on.
    pure subroutine turn_marker(marker, p, turn)
        type(marker_type), intent(inout) :: marker
        !> The part re-based
        integer, intent(in) :: p
        !> The re-basing's turn
        integer, intent(in) :: turn
        integer :: axis

        if (marker%part /= p) return
        marker%point = to_new_basis(marker%point, turn)
        do axis = 1, 3
            marker%axes(:, axis) = to_new_basis(marker%axes(:, axis), turn)
        end do
        marker%principal = .false.
    end subroutine turn_marker

    !> Marker `id` on part p as ADAMS places it: from its origin and axes in the part's frame
    !> (a MARKER's QP, and the matrix of its REULER), the CM marker's origin and axes in the
    !> same frame and the principal axes in the CM marker's axes, its origin from the centre of
    !> mass and its axes, both in the principal axes (R_cm = cm_axes principal; point =
    !> R_cm^T (origin - cm_origin), axes = R_cm^T axes). A marker whose axes are the principal
    !> axes themselves (a CM marker without products of inertia) is better given as
    !> marker_type(id=id, part=p, principal=.true.): its angles are then the part's own.
    pure function part_marker(id, part, origin, axes, cm_origin, cm_axes, principal) &
            & result(marker)
        integer, intent(in) :: id
        !> Index of its part in the model (model order, from 1)
        integer, intent(in) :: part
        !> Origin [m] and axes (columns) in the part's frame
        real(wp), intent(in) :: origin(3), axes(3, 3)
        !> The CM marker's origin [m] and axes (columns) in the part's frame
        real(wp), intent(in) :: cm_origin(3), cm_axes(3, 3)
        !> The principal axes (columns) in the CM marker's axes
        real(wp), intent(in) :: principal(3, 3)
        type(marker_type) :: marker
        real(wp) :: r_cm(3, 3)

        marker%id = id
        marker%part = part
        r_cm = matmul(cm_axes, principal)
        marker%point = matmul(transpose(r_cm), origin - cm_origin)
        marker%axes = matmul(transpose(r_cm), axes)
    end function part_marker

end module rollcon_marker
