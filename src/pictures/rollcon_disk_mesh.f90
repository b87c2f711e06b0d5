! SPDX-License-Identifier: MIT
!> The rolling disk as a picture: its contact point and a cylinder mesh in its true pose,
!> with a marked sector on the faces so that rolling and spin show (docs/design.md §3, §5).
module rollcon_disk_mesh
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : rotation_matrix
    implicit none
    private

    public :: contact_point, disk_points, face_triangle, rim_quad, is_marked

    !> Segments of the disk's circumference
    integer, parameter, public :: disk_sides = 48
    !> Face triangles of the marked sector (a 45 degree sector)
    integer, parameter, public :: sector_sides = 6
    !> Points of the disk mesh: two rims of disk_sides points, then the two face centres
    integer, parameter, public :: disk_point_count = 2*disk_sides + 2


contains

    !> Contact point C = G - R e_y2 with e_y2 = (-cos(theta) sin(psi), cos(theta) cos(psi),
    !> sin(theta)): the lowest point of the mid-plane circle (docs/design.md §5).
    pure function contact_point(radius, q) result(c)
        !> Disk radius [m]
        real(wp), intent(in) :: radius
        !> X, Y, Z [m], psi, theta, phi [rad] of the centre and principal axes
        real(wp), intent(in) :: q(6)
        !> Contact point, ground components [m]
        real(wp) :: c(3)

        associate (psi => q(4), theta => q(5))
            c = q(1:3) - radius*[-cos(theta)*sin(psi), cos(theta)*cos(psi), sin(theta)]
        end associate
    end function contact_point

    !> Points of a cylinder of the disk's radius and thickness in the pose q, ground
    !> components [m]: points 1..disk_sides run round the face at body z = +h/2, the next
    !> disk_sides round the face at -h/2 (the disk axis is body z), then the two face centres.
    !> Point i of each rim is at body angle 2 pi (i - 1)/disk_sides from body x.
    pure function disk_points(radius, thickness, q) result(points)
        !> Disk radius and thickness [m]
        real(wp), intent(in) :: radius, thickness
        !> X, Y, Z [m], psi, theta, phi [rad]
        real(wp), intent(in) :: q(6)
        real(wp) :: points(3, disk_point_count)
        real(wp) :: r(3, 3), body(3), angle
        integer :: i, face

        r = rotation_matrix(q(4), q(5), q(6))
        do face = 1, 2
            do i = 1, disk_sides
                angle = 2.0_wp*pi*real(i - 1, wp)/real(disk_sides, wp)
                body = [radius*cos(angle), radius*sin(angle), face_height(face)]
                points(:, (face - 1)*disk_sides + i) = q(1:3) + matmul(r, body)
            end do
            points(:, 2*disk_sides + face) = q(1:3) + matmul(r, [0.0_wp, 0.0_wp, &
                & face_height(face)])
        end do

    contains

        pure function face_height(face) result(z)
            integer, intent(in) :: face
            real(wp) :: z

            z = merge(0.5_wp*thickness, -0.5_wp*thickness, face == 1)
        end function face_height

    end function disk_points

    !> Zero-based point indices of triangle i (1..disk_sides) of face 1 or 2: the face centre,
    !> then rim points i and i + 1 (as disk_points orders them).
    pure function face_triangle(face, i) result(ids)
        !> 1 for the face at +h/2, 2 for the face at -h/2
        integer, intent(in) :: face
        !> Triangle number, 1..disk_sides
        integer, intent(in) :: i
        integer :: ids(3)

        ids = [2*disk_sides + face - 1, (face - 1)*disk_sides + i - 1, &
            & (face - 1)*disk_sides + modulo(i, disk_sides)]
    end function face_triangle

    !> Zero-based point indices of rim quadrilateral i (1..disk_sides), between rim points i and
    !> i + 1 of both faces.
    pure function rim_quad(i) result(ids)
        !> Quadrilateral number, 1..disk_sides
        integer, intent(in) :: i
        integer :: ids(4)

        ids = [i - 1, modulo(i, disk_sides), disk_sides + modulo(i, disk_sides), disk_sides + i - 1]
    end function rim_quad

    !> True for the face triangles of the marked sector.
    elemental function is_marked(i) result(marked)
        !> Triangle number, 1..disk_sides
        integer, intent(in) :: i
        logical :: marked

        marked = i <= sector_sides
    end function is_marked

end module rollcon_disk_mesh
