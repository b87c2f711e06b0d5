! SPDX-License-Identifier: MIT
!> A dataset's marker as the model holds it: on a moving part, its origin and axes in the
!> part's principal axes (the CM marker's, turned onto those of an IP with products of
!> inertia), origin at the centre of mass; on the ground, in ground. Every statement that names
!> a marker (forces, requests, joints) takes it from here, so all of them follow the same turn.
module rollcon_adm_markers
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : rotation_matrix
    use rollcon_marker, only : marker_type, part_marker
    use rollcon_adm_model, only : adm_model_type
    implicit none
    private

    public :: adm_marker, marker_index

contains

    !> Marker `id` of the dataset as the model holds it: its part's index among the non-ground
    !> parts (0: ground), its origin and axes in that part's principal axes (ground: in ground).
    function adm_marker(adm, id) result(marker)
        type(adm_model_type), intent(in) :: adm
        !> Marker id (it exists: the reader checked the references)
        integer, intent(in) :: id
        type(marker_type) :: marker
        real(wp) :: r_part(3, 3), r_marker(3, 3)
        integer :: m, p, c

        m = marker_index(adm, id)
        p = findloc(adm%parts%id, adm%markers(m)%part, dim=1)
        marker%id = id
        associate (point => adm%markers(m)%qp, angles => adm%markers(m)%reuler, &
            & part => adm%parts(p))
            r_marker = rotation_matrix(angles(1), angles(2), angles(3))
            if (part%ground) then
                r_part = rotation_matrix(part%reuler(1), part%reuler(2), part%reuler(3))
                marker%point = part%qg + matmul(r_part, point)
                marker%axes = matmul(r_part, r_marker)
                return
            end if
            c = marker_index(adm, part%cm)
            ! principal axes = the CM marker's turned onto those of IP's tensor (R_cm P, P the
            ! identity without products): coordinates in them are (R_cm P)^T times the part's
            marker = part_marker(id, count(.not. adm%parts(:p)%ground), point, r_marker, &
                & adm%markers(c)%qp, rotation_matrix(adm%markers(c)%reuler(1), &
                & adm%markers(c)%reuler(2), adm%markers(c)%reuler(3)), part%principal)
            ! the CM marker without products of inertia: the principal axes themselves
            marker%principal = c == m .and. all(part%products == 0.0_wp)
            if (marker%principal) marker%axes = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                & 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
        end associate
    end function adm_marker

    !> Position of marker `id` in the dataset's list (0: none).
    pure integer function marker_index(adm, id)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: id
        integer :: k

        marker_index = 0
        do k = 1, size(adm%markers)
            if (adm%markers(k)%id == id) marker_index = k
        end do
    end function marker_index

end module rollcon_adm_markers
