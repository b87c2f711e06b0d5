! SPDX-License-Identifier: MIT
!> A part without disk geometry as a picture: its inertia ellipsoid (rollcon_part_shapes) as a
!> triangle mesh in the part's true pose, with a marked lune so that its spin shows
!> (docs/design.md §3 for the pose).
module rollcon_ellipsoid_mesh
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : rotation_matrix
    implicit none
    private

    public :: ellipsoid_points, ellipsoid_triangle, equator_point, is_marked_triangle

    !> Segments round the body z axis (longitude)
    integer, parameter, public :: ellipsoid_sides = 16
    !> Bands from pole to pole (latitude); even, so that a ring is the equator
    integer, parameter, public :: ellipsoid_bands = 8
    !> Points: the pole at body +z, ellipsoid_bands - 1 rings of ellipsoid_sides points, the pole
    !> at body -z
    integer, parameter, public :: ellipsoid_point_count = 2 + ellipsoid_sides*(ellipsoid_bands - 1)
    !> Triangles: one per side in each polar band, two per side in every other band
    integer, parameter, public :: ellipsoid_triangle_count = 2*ellipsoid_sides &
        & *(ellipsoid_bands - 1)
    !> Longitude segments of the marked lune (45 degrees)
    integer, parameter :: marked_sides = ellipsoid_sides/8

contains

    !> Points of the ellipsoid with these semi-axes in the pose q, ground components [m]: point 1
    !> is the pole at body +z, then ring j (1 .. ellipsoid_bands - 1, at polar angle
    !> pi j/ellipsoid_bands) has its ellipsoid_sides points at body angles 2 pi (i - 1)/
    !> ellipsoid_sides from body x, and the last point is the pole at body -z.
    pure function ellipsoid_points(semi_axes, q) result(points)
        !> Semi-axes along the body x, y, z axes [m]
        real(wp), intent(in) :: semi_axes(3)
        !> X, Y, Z [m], psi, theta, phi [rad] of the centre and principal axes
        real(wp), intent(in) :: q(6)
        real(wp) :: points(3, ellipsoid_point_count)
        real(wp) :: r(3, 3), polar, angle
        integer :: i, j

        r = rotation_matrix(q(4), q(5), q(6))
        points(:, 1) = q(1:3) + matmul(r, [0.0_wp, 0.0_wp, semi_axes(3)])
        do j = 1, ellipsoid_bands - 1
            polar = pi*real(j, wp)/real(ellipsoid_bands, wp)
            do i = 1, ellipsoid_sides
                angle = 2.0_wp*pi*real(i - 1, wp)/real(ellipsoid_sides, wp)
                points(:, 1 + (j - 1)*ellipsoid_sides + i) = q(1:3) + matmul(r, semi_axes &
                    & *[sin(polar)*cos(angle), sin(polar)*sin(angle), cos(polar)])
            end do
        end do
        points(:, ellipsoid_point_count) = q(1:3) + matmul(r, [0.0_wp, 0.0_wp, -semi_axes(3)])
    end function ellipsoid_points

    !> Zero-based point indices of triangle t (1 .. ellipsoid_triangle_count): first the
    !> ellipsoid_sides triangles round the +z pole (side s is triangle s), then two per side
    !> for each band between two rings, then the ellipsoid_sides round the -z pole.
    pure function ellipsoid_triangle(t) result(ids)
        !> Triangle number
        integer, intent(in) :: t
        integer :: ids(3)
        integer :: s, next, band, k, upper, lower

        if (t <= ellipsoid_sides) then
            s = t
            next = modulo(s, ellipsoid_sides) + 1
            ids = [0, s, next]
        else if (t > ellipsoid_triangle_count - ellipsoid_sides) then
            s = t - (ellipsoid_triangle_count - ellipsoid_sides)
            next = modulo(s, ellipsoid_sides) + 1
            upper = (ellipsoid_bands - 2)*ellipsoid_sides
            ids = [ellipsoid_point_count - 1, upper + next, upper + s]
        else
            k = t - ellipsoid_sides - 1
            band = k/(2*ellipsoid_sides) + 1
            s = modulo(k, 2*ellipsoid_sides)/2 + 1
            next = modulo(s, ellipsoid_sides) + 1
            upper = (band - 1)*ellipsoid_sides
            lower = band*ellipsoid_sides
            if (modulo(k, 2) == 0) then
                ids = [upper + s, lower + s, lower + next]
            else
                ids = [upper + s, lower + next, upper + next]
            end if
        end if
    end function ellipsoid_triangle

    !> Zero-based index of point i (1 .. ellipsoid_sides) of the equator ring (body z = 0).
    elemental function equator_point(i) result(id)
        integer, intent(in) :: i
        integer :: id

        id = (ellipsoid_bands/2 - 1)*ellipsoid_sides + modulo(i - 1, ellipsoid_sides) + 1
    end function equator_point

    !> True for the triangles of the marked lune: the first marked_sides sides, pole to pole.
    elemental function is_marked_triangle(t) result(marked)
        !> Triangle number
        integer, intent(in) :: t
        logical :: marked
        integer :: s

        if (t <= ellipsoid_sides) then
            s = t
        else if (t > ellipsoid_triangle_count - ellipsoid_sides) then
            s = t - (ellipsoid_triangle_count - ellipsoid_sides)
        else
            s = modulo(t - ellipsoid_sides - 1, 2*ellipsoid_sides)/2 + 1
        end if
        marked = s <= marked_sides
    end function is_marked_triangle

end module rollcon_ellipsoid_mesh
