! SPDX-License-Identifier: MIT
!> The initial state of a dataset's part in ADAMS coordinates (rollcon_part_frames' part_start
!> of its PART's QG and REULER, its CM marker's QP and REULER, its principal axes, VX, VY, VZ
!> and WX, WY, WZ): the centre of mass and the 3-1-3 Euler angles of the principal axes, and
!> their rates. A part whose principal z-axis starts parallel to ground z, where the angles are
!> singular, is given in its principal axes turned as a re-basing turns them (basis 1 or 20,
!> docs/rebasing.md).
module rollcon_adm_state
    use rollcon_kinds, only : wp
    use rollcon_part_frames, only : part_start, principal_frame, singular => starts_singular
    use rollcon_adm_model, only : adm_model_type, adm_part_type
    implicit none
    private

    public :: part_state, starts_singular

contains

    !> q = (X, Y, Z, psi, theta, phi) [m, rad] and u = dq/dt of a non-ground part, in the
    !> basis `basis` of its principal axes: 0, the CM marker's axes (turned onto those of an
    !> IP with products), or 1 or 20, those axes turned about x or y (rollcon_part_frames'
    !> part_start) when they start at the singularity (starts_singular).
    pure subroutine part_state(model, part, q, u, basis)
        type(adm_model_type), intent(in) :: model
        type(adm_part_type), intent(in) :: part
        real(wp), intent(out) :: q(6), u(6)
        !> The basis of q and u
        integer, intent(out), optional :: basis
        integer :: m

        m = findloc(model%markers%id, part%cm, dim=1)
        call part_start(part%qg, part%reuler, model%markers(m)%qp, model%markers(m)%reuler, &
            & part%principal, part%velocity, part%angular_velocity, q, u, basis)
    end subroutine part_state

    !> True when the part's principal z-axis is parallel to ground z at t = 0 (rollcon_part_frames).
    pure logical function starts_singular(model, part)
        type(adm_model_type), intent(in) :: model
        type(adm_part_type), intent(in) :: part
        integer :: m

        m = findloc(model%markers%id, part%cm, dim=1)
        starts_singular = singular(principal_frame(part%reuler, model%markers(m)%reuler, &
            & part%principal))
    end function starts_singular

end module rollcon_adm_state
