! SPDX-License-Identifier: MIT
!> Mathematical constants used across rollcon (one definition each).
module rollcon_constants
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: pi, degree

    !> pi, to the working precision
    real(wp), parameter :: pi = acos(-1.0_wp)
    !> One degree [rad]
    real(wp), parameter :: degree = pi/180.0_wp
end module rollcon_constants
