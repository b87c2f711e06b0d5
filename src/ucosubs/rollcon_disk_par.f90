! SPDX-License-Identifier: MIT
!> The rolling disk's PAR layout (the paper's) and its validation.
module rollcon_disk_par
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: disk_nvars, disk_npar, disk_codes, disk_par, read_disk_par

    !> Number of variables the disk declares
    integer, parameter :: disk_nvars = 8
    !> Number of constants in its UCON statement
    integer, parameter :: disk_npar = 11
    !> Codes of Xdot, Ydot, Zdot, psi, theta, psidot, thetadot, phidot
    integer, parameter :: disk_codes(disk_nvars) = [21, 22, 23, 14, 15, 24, 25, 26]

contains

    !> The PAR list of one disk UCON: part id, the eight codes, radius, component.
    pure function disk_par(part, radius, component) result(par)
        !> Part id of the disk
        integer, intent(in) :: part
        !> Disk radius [m]
        real(wp), intent(in) :: radius
        !> Which no-slip component: 1, 2 or 3
        integer, intent(in) :: component
        real(wp) :: par(disk_npar)

        par = [real(part, wp), real(disk_codes, wp), radius, real(component, wp)]
    end function disk_par

    !> Read and check PAR; message is allocated (and says what was expected) when PAR is wrong.
    pure subroutine read_disk_par(par, npar, part, radius, component, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> Number of constants
        integer, intent(in) :: npar
        !> Part id of the disk
        integer, intent(out) :: part
        !> Disk radius [m]
        real(wp), intent(out) :: radius
        !> Which component: 1, 2 or 3
        integer, intent(out) :: component
        !> Allocated when PAR is wrong
        character(len=:), allocatable, intent(out) :: message
        integer :: i

        ! the usual case, a valid PAR, in one test (the routine reads PAR at every call): the
        ! checks below, without their messages
        if (npar >= disk_npar) then
            if (par(1) >= 1.0_wp .and. par(1) < real(huge(1), wp)) then
                ! in int's range: int truncates as aint does, without aint's library call
                if (par(1) == real(int(par(1)), wp) &
                    & .and. all(par(2:1 + disk_nvars) == real(disk_codes, wp)) &
                    & .and. par(10) > 0.0_wp .and. par(10) <= huge(par(10)) &
                    & .and. (par(11) == 1.0_wp .or. par(11) == 2.0_wp .or. par(11) == 3.0_wp)) &
                    & then
                    part = int(par(1))
                    radius = par(10)
                    component = int(par(11))
                    return
                end if
            end if
        end if
        part = 0
        radius = 0.0_wp
        component = 0
        if (npar < disk_npar) then
            message = "rolling disk needs NPAR >= " // to_text(disk_npar) &
                & // " (part id, 8 codes, " &
                & // "R, component), got NPAR = " // to_text(npar)
            return
        end if
        if (.not. is_whole(par(1)) .or. par(1) < 1.0_wp) then
            message = "PAR(1) (part id) must be a positive whole number, got " // to_text(par(1))
            return
        end if
        part = nint(par(1))
        do i = 1, disk_nvars
            if (par(1 + i) /= real(disk_codes(i), wp)) then
                message = "PAR(" // to_text(1 + i) // ") must be code " // to_text(disk_codes(i)) &
                    & // " (codes 21 22 23 14 15 24 25 26 in PAR(2:9)), got " // to_text(par(1 + i))
                return
            end if
        end do
        radius = par(10)
        if (.not. ieee_is_finite(radius) .or. radius <= 0.0_wp) then
            message = "PAR(10) (disk radius R [m]) must be positive and finite, got " &
                & // to_text(radius)
            return
        end if
        if (par(11) /= 1.0_wp .and. par(11) /= 2.0_wp .and. par(11) /= 3.0_wp) then
            message = "PAR(11) (no-slip component) must be 1, 2 or 3, got " // to_text(par(11))
            return
        end if
        component = nint(par(11))
    end subroutine read_disk_par

    !> True for a finite real with no fractional part, small enough for a default integer.
    elemental function is_whole(value) result(whole)
        real(wp), intent(in) :: value
        logical :: whole

        whole = ieee_is_finite(value)
        if (whole) whole = abs(value) < real(huge(1), wp) .and. value == aint(value)
    end function is_whole

end module rollcon_disk_par
