! SPDX-License-Identifier: MIT
!> ADAMS utility UCOVAR as an external routine, callable from FORTRAN 77 with ADAMS's arguments.
!>
!> A host program that defines its own UCOVAR replaces this one at link time (it lives alone in
!> its object file for that reason).
subroutine ucovar(id, nparts, lparts, nvars, lvars)
    use rollcon_adams_runtime, only : record_ucovar
    implicit none
    !> UCON statement id
    integer, intent(in) :: id
    !> Number of entries in lparts
    integer, intent(in) :: nparts
    !> Part id of each variable
    integer, intent(in) :: lparts(*)
    !> Number of entries in lvars
    integer, intent(in) :: nvars
    !> Code of each variable
    integer, intent(in) :: lvars(*)

    call record_ucovar(id, nparts, lparts(:max(0, min(nparts, 30))), nvars, &
        & lvars(:max(0, min(nvars, 30))))
end subroutine ucovar
