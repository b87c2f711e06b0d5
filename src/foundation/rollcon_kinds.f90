! SPDX-License-Identifier: MIT
!> Real kind used throughout rollcon.
module rollcon_kinds
    use, intrinsic :: iso_fortran_env, only : real64
    implicit none
    private

    public :: wp

    !> Working precision: IEEE double, the DOUBLE PRECISION of ADAMS user subroutines
    integer, parameter :: wp = real64

end module rollcon_kinds
