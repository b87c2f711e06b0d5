! SPDX-License-Identifier: MIT
!> The accelerations of markers, from the parts' coordinates q, rates u and accelerations a
!> (the equations of motion's, rollcon_equations), and ADAMS's acceleration measures of them
!> (docs/datasets.md, "Accelerations and forces in a REQUEST"):
!>
!> - a marker's angular acceleration: with its part's 3-1-3 angles, w = psi' Z + theta' n +
!>   phi' z_b (n = Rz(psi) x the line of nodes, z_b = R z the part's z axis), so
!>   alpha = psi'' Z + theta'' n + theta' (psi' Z x n) + phi'' z_b + phi' (w x z_b);
!> - its origin's acceleration: a_cm + alpha x r + w x (w x r), r from the centre of mass;
!> - ACCX, ACCY, ACCZ(i, j, k, l): the second time derivative of d = r_i - r_j taken in marker
!>   l's frame, (a_i - a_j) - 2 w_l x d'_l - alpha_l x d - w_l x (w_l x d) with
!>   d'_l = v_i - v_j - w_l x d, along k's x, y, z; ACCM(i, j, l) its magnitude;
!> - WDTX, WDTY, WDTZ(i, j, k, l): the time derivative of w_i - w_j taken in l's frame,
!>   (alpha_i - alpha_j) - w_l x (w_i - w_j), along k's axes; WDTM(i, j, l) its magnitude.
!>
!> A marker not given is the ground's origin and axes (marker_type()). SI units throughout
!> [m/s^2, rad/s^2]. Exact: no difference of rows enters.
module rollcon_marker_acceleration
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : cross
    use rollcon_marker, only : marker_type, marker_motion
    use rollcon_expression, only : quantity_accx, quantity_accm, quantity_wdtx, quantity_wdtm
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: marker_acceleration, acceleration_measure, relative_accelerations

contains

    !> A marker's origin's acceleration [m/s^2] and its axes' angular acceleration [rad/s^2],
    !> ground components, at coordinates q, rates u and accelerations a of all parts.
    pure subroutine marker_acceleration(marker, q, u, a, acceleration, alpha)
        type(marker_type), intent(in) :: marker
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp), intent(out) :: acceleration(3), alpha(3)
        real(wp) :: position(3), velocity(3), axes(3, 3), omega(3), arm(3), nodes(3), &
            & z_axis(3), vertical(3)
        integer :: i0

        acceleration = 0.0_wp
        alpha = 0.0_wp
        if (marker%part == 0) return
        i0 = 6*(marker%part - 1)
        call marker_motion(marker, q, u, position, velocity, axes, omega)
        associate (psi => q(i0 + 4), theta => q(i0 + 5), rates => u(i0 + 4:i0 + 6), &
                & second => a(i0 + 4:i0 + 6))
            vertical = [0.0_wp, 0.0_wp, 1.0_wp]
            nodes = [cos(psi), sin(psi), 0.0_wp]
            z_axis = [sin(psi)*sin(theta), -cos(psi)*sin(theta), cos(theta)]
            alpha = second(1)*vertical + second(2)*nodes + rates(2)*rates(1) &
                & *cross(vertical, nodes) + second(3)*z_axis + rates(3)*cross(omega, z_axis)
        end associate
        arm = position - q(i0 + 1:i0 + 3)
        acceleration = a(i0 + 1:i0 + 3) + cross(alpha, arm) + cross(omega, cross(omega, arm))
    end subroutine marker_acceleration

    !> The relative acceleration of markers(1) from markers(2) taken in markers(4)'s frame
    !> (translational: the second derivative of d, `translational`; rotational: the derivative
    !> of w_i - w_j, `rotational`), ground components (module header).
    pure subroutine relative_accelerations(markers, q, u, a, translational, rotational)
        type(marker_type), intent(in) :: markers(4)
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp), intent(out) :: translational(3), rotational(3)
        real(wp) :: r(3, 4), v(3, 4), w(3, 4), axes(3, 3), acc(3, 4), alpha(3, 4), d(3), &
            & rate(3)
        integer :: m

        do m = 1, 4
            if (m == 3) cycle
            call marker_motion(markers(m), q, u, r(:, m), v(:, m), axes, w(:, m))
            call marker_acceleration(markers(m), q, u, a, acc(:, m), alpha(:, m))
        end do
        d = r(:, 1) - r(:, 2)
        rate = v(:, 1) - v(:, 2) - cross(w(:, 4), d)
        translational = acc(:, 1) - acc(:, 2) - 2.0_wp*cross(w(:, 4), rate) &
            & - cross(alpha(:, 4), d) - cross(w(:, 4), cross(w(:, 4), d))
        rotational = alpha(:, 1) - alpha(:, 2) - cross(w(:, 4), w(:, 1) - w(:, 2))
    end subroutine relative_accelerations

    !> ACCX ... ACCM, WDTX ... WDTM (quantity codes of rollcon_expression) of markers i, j, k, l
    !> [m/s^2, rad/s^2]; NaN for another quantity.
    pure function acceleration_measure(quantity, markers, q, u, a) result(value)
        integer, intent(in) :: quantity
        type(marker_type), intent(in) :: markers(4)
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp) :: value
        real(wp) :: translational(3), rotational(3), r(3), v(3), axes(3, 3), w(3)

        call relative_accelerations(markers, q, u, a, translational, rotational)
        call marker_motion(markers(3), q, u, r, v, axes, w)
        select case (quantity)
        case (quantity_accx:quantity_accx + 2)
            value = dot_product(translational, axes(:, quantity - quantity_accx + 1))
        case (quantity_accm)
            value = norm2(translational)
        case (quantity_wdtx:quantity_wdtx + 2)
            value = dot_product(rotational, axes(:, quantity - quantity_wdtx + 1))
        case (quantity_wdtm)
            value = norm2(rotational)
        case default
            value = ieee_value(value, ieee_quiet_nan)
        end select
    end function acceleration_measure

end module rollcon_marker_acceleration
