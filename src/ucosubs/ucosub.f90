! SPDX-License-Identifier: MIT
!> The hand-checked rolling-disk UCOSUB as a plain external routine with ADAMS's calling sequence.
!>
!> Callable from FORTRAN 77 with explicit-shape arguments and no module: link the rollcon
!> library. It is alone in its object file, so a program that defines its own UCOSUB still links.
!> A wrong PAR is reported through ERRMES; a FORTRAN 77 caller reads it with UCOERR.
subroutine ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
    use rollcon_kinds, only : wp
    use rollcon_disk_reference, only : rolling_disk_ucosub
    implicit none
    !> UCON statement id
    integer, intent(in) :: id
    !> Simulation time [s]
    real(wp), intent(in) :: time
    !> Values of the declared variables
    real(wp), intent(in) :: q(30)
    !> Constants of the UCON statement
    real(wp), intent(in) :: par(*)
    !> Number of constants
    integer, intent(in) :: npar
    !> Output selectors
    integer, intent(in) :: idrsel(3)
    !> 3: initialise, 0: evaluate
    integer, intent(in) :: iflag
    !> Selected scalar output
    real(wp), intent(inout) :: scalar
    !> Selected first partials
    real(wp), intent(inout) :: array(30)
    !> Selected second partials
    real(wp), intent(inout) :: xmatrx(30, 30)

    call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
end subroutine ucosub
