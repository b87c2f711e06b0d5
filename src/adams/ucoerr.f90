! SPDX-License-Identifier: MIT
!> FORTRAN 77 access to the error channel: CALL UCOERR(IERR, MESAGE) after a UCOSUB call.
!>
!> IERR is 0 when no error is pending; otherwise a rollcon status code (5 for a UCON error) and
!> MESAGE holds the message (cut to its length). The pending error is cleared.
subroutine ucoerr(ierr, mesage)
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_error, only : error_type
    implicit none
    !> 0 when no error is pending, else the error's status code
    integer, intent(out) :: ierr
    !> The message, blank when none
    character(len=*), intent(out) :: mesage
    type(error_type), allocatable :: error

    call take_ucon_error(error)
    ierr = 0
    mesage = " "
    if (allocated(error)) then
        ierr = error%stat
        mesage = error%message
    end if
end subroutine ucoerr
