! SPDX-License-Identifier: MIT
!> The maths of re-basing a part's principal axes (docs/rebasing.md): when a part's 3-1-3
!> Euler angles come near their singularity (sin(theta) small: the body z axis nearly along
!> ground Z), its principal frame is turned by 90 degrees about its body x or its body y axis
!> (both nearly horizontal there), the principal moments are permuted to match, and the
!> coordinates and rates are recomputed from the same physical state: the same rotation
!> matrix R and the same angular velocity.
!>
!> A turn T (columns: the new axes in the old ones) about body x takes new x = old x,
!> new y = -old z, new z = old y; about body y, new x = -old z, new y = old y, new z = old x.
!> R_new = R_old T, and the new theta satisfies cos(theta_new) = R_old(3, 2) =
!> sin(theta_old) cos(phi_old) (about x) or R_old(3, 1) = sin(theta_old) sin(phi_old)
!> (about y): near the singularity the new theta is within theta_old of pi/2. The turn taken
!> (chosen_turn) makes the new z the one of old x and old y that the angular velocity carries
!> away from the horizontal plane slowest.
!>
!> A basis is numbered by its axes in the part's own principal axes (basis 0): basis 4 f + k
!> has its x axis along own axis f (0 to 5: +x, +y, +z, -x, -y, -z) and is the reference
!> basis of that x axis (basis_reference) turned k times (k = 0 to 3) about its x axis.
module rollcon_rebasing
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : rotation_matrix, rate_matrix, times, transpose_times
    implicit none
    private

    public :: turn_about_x, turn_about_y, basis_turns, chosen_turn, rebased_state
    public :: rebased_inertia, to_new_basis, euler_angles_near, basis_axes, next_basis
    public :: turns_from_own, own_axes_rotation, own_axes_inertia, angle_rates

    !> The two turns of a re-basing (the last index of basis_turns)
    integer, parameter :: turn_about_x = 1, turn_about_y = 2

    !> The turns of a re-basing: columns the new principal axes in the old ones. About body x
    !> (new x = old x, new y = -old z, new z = old y) and about body y (new x = -old z,
    !> new y = old y, new z = old x), 90 degrees each
    real(wp), parameter :: basis_turns(3, 3, 2) = reshape([ &
        & 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, &
        & 0.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], [3, 3, 2])

    !> The reference basis of each x axis f (basis 4 f): columns its axes in the own ones.
    !> f = 0: the own axes; 1 (+y): a quarter turn about own z; 2 (+z): a quarter turn about
    !> own y taking x to z; 3 (-x): a half turn about own z; 4 (-y): a quarter turn about own z
    !> taking x to -y; 5 (-z): a quarter turn about own y taking x to -z (basis_turns(:, :, 2))
    real(wp), parameter :: basis_reference(3, 3, 0:5) = reshape([ &
        & 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
        & 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
        & 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 0.0_wp, &
        & -1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
        & 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
        & 0.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], [3, 3, 6])

contains

    !> The turn of a re-basing of a part whose angular velocity has body components omega
    !> [rad/s]: the one whose new z axis the angular velocity carries away from the horizontal
    !> plane slowest. Near the singularity old x and old y are both nearly
    !> horizontal, and either can be the new z; the rate at which a body axis e tilts is
    !> |omega x e|, smallest for the axis with the larger body component of omega. So
    !> turn_about_y (new z = old x) when |omega'_x| > |omega'_y|, else turn_about_x (new z =
    !> old y). A part spinning about body x keeps its spin axis as the new z, and that axis
    !> stays away from the vertical as long as the spin lasts.
    pure integer function chosen_turn(omega) result(turn)
        !> Angular velocity, body components of the old basis [rad/s]
        real(wp), intent(in) :: omega(3)

        turn = turn_about_x
        if (abs(omega(1)) > abs(omega(2))) turn = turn_about_y
    end function chosen_turn

    !> A part's coordinates and rates in the basis turned by `turn`, from the same physical
    !> state: centre of mass and its velocity unchanged, R_new = R_old T, psi and phi taken
    !> within pi of their old values (so that a plot does not jump by whole turns), and the
    !> angle rates from the body angular velocity omega'_new = T^T omega'_old
    !> (T = basis_turns(:, :, turn)).
    pure subroutine rebased_state(q_old, u_old, q_new, u_new, turn)
        !> The part's X, Y, Z, psi, theta, phi [m, rad] and their rates [m/s, rad/s], old basis
        real(wp), intent(in) :: q_old(6), u_old(6)
        !> The same in the new basis
        real(wp), intent(out) :: q_new(6), u_new(6)
        !> turn_about_x or turn_about_y
        integer, intent(in) :: turn
        real(wp) :: r_new(3, 3), omega_old(3), omega_new(3), angles(3)

        r_new = matmul(rotation_matrix(q_old(4), q_old(5), q_old(6)), basis_turns(:, :, turn))
        angles = euler_angles_near(r_new, q_old(4), q_old(6))
        omega_old = times(rate_matrix(q_old(5), q_old(6)), u_old(4:6))
        omega_new = transpose_times(basis_turns(:, :, turn), omega_old)
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

    !> The principal moments about the new x, y, z axes [kg m^2]: the old (A1, A3, A2) for
    !> turn_about_x, (A3, A2, A1) for turn_about_y.
    pure function rebased_inertia(inertia, turn) result(turned)
        !> Principal moments about the old x, y, z axes [kg m^2]
        real(wp), intent(in) :: inertia(3)
        !> turn_about_x or turn_about_y
        integer, intent(in) :: turn
        real(wp) :: turned(3)

        turned = matmul(abs(transpose(basis_turns(:, :, turn))), inertia)
    end function rebased_inertia

    !> Components in the new basis of a body-fixed vector given in the old one (a marker's
    !> origin or axis): T^T v (T = basis_turns(:, :, turn)).
    pure function to_new_basis(v, turn) result(w)
        !> Components in the old principal axes
        real(wp), intent(in) :: v(3)
        !> turn_about_x or turn_about_y
        integer, intent(in) :: turn
        real(wp) :: w(3)

        w = transpose_times(basis_turns(:, :, turn), v)
    end function to_new_basis

    !> The axes of basis number `basis` (columns) in the part's own principal axes (basis 0):
    !> basis_reference(:, :, f) turned k times about its x axis, basis = 4 f + k.
    pure function basis_axes(basis) result(axes)
        !> Number of the basis, 0 to 23
        integer, intent(in) :: basis
        real(wp) :: axes(3, 3)
        integer :: k

        axes = basis_reference(:, :, modulo(basis, 24)/4)
        do k = 1, modulo(basis, 4)
            axes = matmul(axes, basis_turns(:, :, turn_about_x))
        end do
    end function basis_axes

    !> The number of the basis that basis number `basis` becomes when turned by `turn`
    !> (0 to 23): its axes basis_axes(basis) T, numbered as basis_axes numbers them.
    pure integer function next_basis(basis, turn) result(next)
        !> Number of the basis before the turn, 0 to 23
        integer, intent(in) :: basis
        !> turn_about_x or turn_about_y
        integer, intent(in) :: turn
        real(wp) :: axes(3, 3)
        integer :: f

        axes = matmul(basis_axes(basis), basis_turns(:, :, turn))
        do next = 0, 23
            f = next/4
            if (any(abs(basis_reference(:, 1, f) - axes(:, 1)) > 0.5_wp)) cycle
            if (all(abs(basis_axes(next) - axes) < 0.5_wp)) return
        end do
        next = 0
    end function next_basis

    !> The fewest turns that take the own axes (basis 0) to basis number `basis`, in order
    !> (a part that starts in a turned basis: the re-basings its start counts): none for
    !> basis 0, [turn_about_x] for basis 1, [turn_about_y] for basis 20. The two turns reach
    !> every one of the 24 bases (a breadth-first search over them; ties: turns about x first).
    pure function turns_from_own(basis) result(turns)
        !> Number of the basis, 0 to 23
        integer, intent(in) :: basis
        integer, allocatable :: turns(:)
        integer :: from(0:23), by(0:23), queue(24), head, tail, b, next, turn

        from = -1
        by = 0
        from(0) = 0
        queue(1) = 0
        head = 1
        tail = 1
        do while (head <= tail)
            b = queue(head)
            head = head + 1
            do turn = turn_about_x, turn_about_y
                next = next_basis(b, turn)
                if (from(next) >= 0) cycle
                from(next) = b
                by(next) = turn
                tail = tail + 1
                queue(tail) = next
            end do
        end do
        allocate(turns(0))
        b = modulo(basis, 24)
        do while (b /= 0)
            turns = [by(b), turns]
            b = from(b)
        end do
    end function turns_from_own

    !> The rotation of a part's own principal axes (its CM marker's, basis 0) from the
    !> rotation R of basis number `basis` (a CSV's basis_<id>): R C^T, C = basis_axes(basis),
    !> for whoever draws a part in its own axes from a re-based row.
    pure function own_axes_rotation(r, basis) result(own)
        !> Rotation of the principal axes of the basis, body to ground
        real(wp), intent(in) :: r(3, 3)
        !> Number of the basis, 0 to 23
        integer, intent(in) :: basis
        real(wp) :: own(3, 3)

        own = matmul(r, transpose(basis_axes(basis)))
    end function own_axes_rotation

    !> The principal moments about a part's own principal axes (its CM marker's, basis 0) from
    !> those about the axes of basis number `basis` [kg m^2]: the moment about own axis j is
    !> the one about the basis axis along it (|C| I, C = basis_axes(basis)).
    pure function own_axes_inertia(inertia, basis) result(own)
        !> Principal moments about the x, y, z axes of the basis [kg m^2]
        real(wp), intent(in) :: inertia(3)
        !> Number of the basis, 0 to 23
        integer, intent(in) :: basis
        real(wp) :: own(3)

        own = matmul(abs(basis_axes(basis)), inertia)
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
