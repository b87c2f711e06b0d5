! SPDX-License-Identifier: MIT
!> ADAMS utility ERRMES as an external routine: a UCOSUB's way to report an error.
!>
!> Unlike ADAMS, it never stops the program, whatever ENDFLG says: the message is kept and the
!> caller collects it (take_ucon_error in Fortran, UCOERR from FORTRAN 77) and decides. A
!> non-STOP report is kept too, marked with its ENDFLG.
subroutine errmes(errflg, mesage, id, endflg)
    use rollcon_adams_runtime, only : report_ucon_error
    implicit none
    !> True when there is an error to report
    logical, intent(in) :: errflg
    !> The message
    character(len=*), intent(in) :: mesage
    !> Id of the statement concerned
    integer, intent(in) :: id
    !> "STOP" or "NOSTOP" in ADAMS; both are kept the same way here
    character(len=*), intent(in) :: endflg

    if (.not. errflg) return
    if (adjustl(endflg) == "STOP") then
        call report_ucon_error(id, trim(mesage))
    else
        call report_ucon_error(id, trim(mesage) // " (reported with ENDFLG = '" // trim(endflg) &
            & // "')")
    end if
end subroutine errmes
