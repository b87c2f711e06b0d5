! SPDX-License-Identifier: MIT
!> A UCOSUB written by the user of the library, for example/two_rollers.f90: a sphere's centre
!> stays at its radius above the ground, F = Z - R = 0 [m], a position (holonomic) UCON.
!>
!> PAR(1) is the sphere's part id, PAR(2) its radius R [m]. The routine declares one variable,
!> the part's Z (code 13), on the initialisation call, and on an evaluation call returns what
!> IDRSEL asks: F, f(t) = -R (the part of F free of the variables), dF/dZ = 1. Every time
!> partial and second partial is zero; such entries may be left untouched, since the driver
!> zeroes the outputs before each call (docs/design.md §2).
module sphere_height
    use rollcon, only : wp, ucovar, errmes, iflag_init, iflag_eval, scalar_value, &
        & scalar_time_part, array_dq, code_z
    implicit none
    private

    public :: sphere_height_ucosub, sphere_height_par

contains

    !> The PAR list: part id, radius [m].
    pure function sphere_height_par(part, radius) result(par)
        !> Part id of the sphere
        integer, intent(in) :: part
        !> Its radius [m]
        real(wp), intent(in) :: radius
        real(wp) :: par(2)

        par = [real(part, wp), radius]
    end function sphere_height_par

    !> F = Z - R with ADAMS's calling sequence (ucosub_interface); bad PAR or IFLAG go to
    !> ERRMES, which rollcon turns into an error naming the UCON (it never stops).
    subroutine sphere_height_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, &
        & xmatrx)
        !> UCON statement id
        integer, intent(in) :: id
        !> Simulation time [s] (F does not depend on it)
        real(wp), intent(in) :: time
        !> The declared variable: q(1) = Z [m]
        real(wp), intent(in) :: q(30)
        !> PAR(1) part id, PAR(2) radius R [m]
        real(wp), intent(in) :: par(*)
        !> Number of constants (2)
        integer, intent(in) :: npar
        !> Output selectors
        integer, intent(in) :: idrsel(3)
        !> iflag_init (3): declare; iflag_eval (0): evaluate
        integer, intent(in) :: iflag
        !> F or f(t), as idrsel(1) asks [m]
        real(wp), intent(inout) :: scalar
        !> dF/dZ, as idrsel(2) asks
        real(wp), intent(inout) :: array(30)
        !> Second partials: all zero, left untouched
        real(wp), intent(inout) :: xmatrx(30, 30)

        if (npar < 2) then
            call errmes(.true., "sphere height needs PAR = (part id, radius R [m])", id, "STOP")
            return
        end if
        if (par(1) < 1.0_wp .or. .not. par(2) > 0.0_wp) then
            call errmes(.true., "sphere height: PAR(1) must be a part id >= 1 and PAR(2) a " &
                & // "radius > 0 [m]", id, "STOP")
            return
        end if
        select case (iflag)
        case (iflag_init)
            call ucovar(id, 1, [nint(par(1))], 1, [code_z])
        case (iflag_eval)
            if (idrsel(1) == scalar_value) scalar = q(1) - par(2)
            if (idrsel(1) == scalar_time_part) scalar = -par(2)
            if (idrsel(2) == array_dq) array(1) = 1.0_wp
        case default
            call errmes(.true., "IFLAG must be 3 (initialise) or 0 (evaluate)", id, "STOP")
        end select
    end subroutine sphere_height_ucosub

end module sphere_height
