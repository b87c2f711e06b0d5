! SPDX-License-Identifier: MIT
!> The principal axes of an inertia tensor given as ADAMS's PART IP=xx, yy, zz, xy, xz, yz:
!> the moments and the axes (docs/datasets.md "PART", docs/design.md §7).
!>
!> ADAMS defines the products as positive integrals about the CM marker's axes, Ixy = ∫ x y dm,
!> Ixz = ∫ x z dm, Iyz = ∫ y z dm, so the tensor in those axes is
!>
!>     [  Ixx  -Ixy  -Ixz ]
!>     [ -Ixy   Iyy  -Iyz ]
!>     [ -Ixz  -Iyz   Izz ]
!>
!> Its eigenvalues are the principal moments and its eigenvectors the principal axes (LAPACK
!> dsyev, rollcon_lapack's symmetric_eigen). Which eigenvector becomes x, y and z, and its
!> sign, is chosen so that the principal frame is right-handed and as close as it can be to
!> the CM marker's own axes: of the 24 right-handed assignments (6 orders times the 4 sign
!> choices with determinant +1) the one whose rotation from the CM marker's axes is smallest,
!> which is the one with the largest trace (trace = 1 + 2 cos(angle)); the first in a fixed
!> order on a tie. A marker with tiny products so keeps its axes, turned by little.
!>
!> Repeated moments (two within repeated_moments of the largest, relatively) leave the axes in
!> their plane free: there the pair is turned in its plane to come closest to the CM marker's
!> two axes they stand for (the trace again), so the answer does not depend on the vectors
!> LAPACK happened to return. Three repeated moments (a sphere's tensor) keep the CM marker's
!> axes. Products all exactly 0 keep the axes and the moments as written, bit for bit.
module rollcon_inertia_axes
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_lapack, only : symmetric_eigen
    implicit none
    private

    public :: inertia_tensor, principal_axes, repeated_moments

    !> Moments closer than this fraction of the largest are taken as one repeated moment: their
    !> eigenvectors are then known only to about eps/fraction (1e-7 rad), and which pair of
    !> axes in their plane is chosen changes the inertia by less than this fraction
    real(wp), parameter :: repeated_moments = 1.0e-9_wp
    !> The 6 orders of the eigenvectors along x, y, z
    integer, parameter :: orders(3, 6) = reshape([1, 2, 3, 1, 3, 2, 2, 1, 3, 2, 3, 1, 3, 1, 2, &
        & 3, 2, 1], [3, 6])
    !> The 4 sign choices of each order's columns before making the determinant +1 with z's sign
    real(wp), parameter :: signs(2, 4) = reshape([1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, -1.0_wp, &
        & 1.0_wp, -1.0_wp, -1.0_wp], [2, 4])

contains

    !> The inertia tensor of IP=xx, yy, zz, xy, xz, yz in the CM marker's axes [kg m^2]: the
    !> products are ADAMS's positive integrals, so they enter with a minus sign.
    pure function inertia_tensor(ip) result(tensor)
        !> xx, yy, zz, xy, xz, yz [kg m^2]
        real(wp), intent(in) :: ip(6)
        real(wp) :: tensor(3, 3)

        tensor(:, 1) = [ip(1), -ip(4), -ip(5)]
        tensor(:, 2) = [-ip(4), ip(2), -ip(6)]
        tensor(:, 3) = [-ip(5), -ip(6), ip(3)]
    end function inertia_tensor

    !> The principal moments and axes of IP=xx, yy, zz, xy, xz, yz (module doc). A tensor that
    !> is not positive definite is an error saying so with its eigenvalues (the caller adds
    !> where it was read).
    subroutine principal_axes(ip, moments, axes, error)
        !> xx, yy, zz, xy, xz, yz about the CM marker's axes [kg m^2]
        real(wp), intent(in) :: ip(6)
        !> Principal moments about the principal x, y, z [kg m^2]
        real(wp), intent(out) :: moments(3)
        !> Columns: the principal x, y, z in the CM marker's axes (a rotation, det +1)
        real(wp), intent(out) :: axes(3, 3)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: values(3), vectors(3, 3), candidate(3, 3), score, best
        integer :: o, s

        axes = identity()
        moments = ip(1:3)
        if (all(ip(4:6) == 0.0_wp)) return
        call symmetric_eigen(inertia_tensor(ip), values, vectors, error)
        if (allocated(error)) return
        if (.not. values(1) > 0.0_wp) then
            call fatal_error(error, "the inertia tensor [[xx, -xy, -xz], [-xy, yy, -yz], " &
                & // "[-xz, -yz, zz]] (ADAMS's products are positive integrals) is not " &
                & // "positive definite: its eigenvalues are " // to_text(values(1)) // ", " &
                & // to_text(values(2)) // ", " // to_text(values(3)) // " kg m^2, and a " &
                & // "rigid body's principal moments are all > 0", stat_input)
            return
        end if
        best = -huge(1.0_wp)
        do o = 1, size(orders, 2)
            do s = 1, size(signs, 2)
                candidate(:, 1) = signs(1, s)*vectors(:, orders(1, o))
                candidate(:, 2) = signs(2, s)*vectors(:, orders(2, o))
                candidate(:, 3) = vectors(:, orders(3, o))
                if (determinant(candidate) < 0.0_wp) candidate(:, 3) = -candidate(:, 3)
                call settle_repeated(values(orders(:, o)), candidate)
                score = candidate(1, 1) + candidate(2, 2) + candidate(3, 3)
                if (score > best) then
                    best = score
                    axes = candidate
                    moments = values(orders(:, o))
                end if
            end do
        end do
        ! three repeated moments: any axes are principal; keep the CM marker's
        if (maxval(moments) - minval(moments) <= repeated_moments*maxval(moments)) then
            axes = identity()
            moments = values
        end if
    end subroutine principal_axes

    !> Two repeated moments (axes i and j, the third k apart): the pair turned in its plane to
    !> the largest axes(i, i) + axes(j, j), which keeps the frame right-handed.
    pure subroutine settle_repeated(moments, axes)
        real(wp), intent(in) :: moments(3)
        real(wp), intent(inout) :: axes(3, 3)
        real(wp) :: a(3), b(3), angle, tolerance
        integer :: i, j

        tolerance = repeated_moments*maxval(moments)
        do i = 1, 2
            do j = i + 1, 3
                if (abs(moments(i) - moments(j)) > tolerance) cycle
                a = axes(:, i)
                b = axes(:, j)
                ! axes(i, i) + axes(j, j) = cos(angle) (a_i + b_j) + sin(angle) (b_i - a_j)
                angle = atan2(b(i) - a(j), a(i) + b(j))
                axes(:, i) = cos(angle)*a + sin(angle)*b
                axes(:, j) = -sin(angle)*a + cos(angle)*b
                return
            end do
        end do
    end subroutine settle_repeated

    pure real(wp) function determinant(m)
        real(wp), intent(in) :: m(3, 3)

        determinant = dot_product(m(:, 1), [m(2, 2)*m(3, 3) - m(3, 2)*m(2, 3), &
            & m(3, 2)*m(1, 3) - m(1, 2)*m(3, 3), m(1, 2)*m(2, 3) - m(2, 2)*m(1, 3)])
    end function determinant

    pure function identity() result(m)
        real(wp) :: m(3, 3)
        integer :: k

        m = 0.0_wp
        do k = 1, 3
            m(k, k) = 1.0_wp
        end do
    end function identity

end module rollcon_inertia_axes
