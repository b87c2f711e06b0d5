! SPDX-License-Identifier: MIT
!> Hand-derived UCOSUB of the rolling disk's no-slip condition (docs/design.md §5).
!>
!> The twin of the generated routine: written from the constraint, not from the paper's
!> listing, and checked against finite differences and against the generator's output.
module rollcon_disk_reference
    use rollcon_kinds, only : wp
    use rollcon_ucosub_contract, only : ucovar, errmes, iflag_init, iflag_eval, &
        & scalar_none, scalar_value, scalar_time_part, scalar_dt, scalar_dtt, &
        & array_none, array_dq, array_dtdq, xmatrx_none, xmatrx_dqdq
    use rollcon_disk_par, only : disk_nvars, disk_codes, read_disk_par
    implicit none
    private

    public :: rolling_disk_ucosub, rolling_disk_evaluate

    !> Positions of the variables in q (the order of disk_codes)
    integer, parameter :: i_xdot = 1, i_ydot = 2, i_zdot = 3, i_psi = 4, i_theta = 5, &
        & i_psidot = 6, i_thetadot = 7, i_phidot = 8

    !> What the value and the partials of one call share (disk_trig)
    type :: disk_trig_type
        real(wp) :: spsi = 0.0_wp, cpsi = 0.0_wp, sth = 0.0_wp, cth = 0.0_wp, spin = 0.0_wp
    end type disk_trig_type

contains

    !> The rolling-disk UCOSUB, with ADAMS's calling sequence (see ucosub_interface).
    !> PAR: (1) part id, (2:9) codes 21 22 23 14 15 24 25 26, (10) radius R [m],
    !> (11) component 1, 2 or 3. Bad PAR or selectors are reported through ERRMES.
    subroutine rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        !> UCON statement id
        integer, intent(in) :: id
        !> Simulation time [s] (the constraint does not depend on it)
        real(wp), intent(in) :: time
        !> Xdot, Ydot, Zdot [m/s], psi, theta [rad], psidot, thetadot, phidot [rad/s]
        real(wp), intent(in) :: q(30)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> Number of constants
        integer, intent(in) :: npar
        !> Output selectors
        integer, intent(in) :: idrsel(3)
        !> 3: declare variables; 0: evaluate
        integer, intent(in) :: iflag
        !> F or one of its time derivatives [m/s, m/s^2, ...]
        real(wp), intent(inout) :: scalar
        !> First partials
        real(wp), intent(inout) :: array(30)
        !> Second partials, both triangles
        real(wp), intent(inout) :: xmatrx(30, 30)
        character(len=:), allocatable :: message
        integer :: part, component
        real(wp) :: radius

        call read_disk_par(par, npar, part, radius, component, message)
        if (allocated(message)) then
            call errmes(.true., message, id, "STOP")
            return
        end if
        select case (iflag)
        case (iflag_init)
            call ucovar(id, disk_nvars, spread(part, 1, disk_nvars), disk_nvars, disk_codes)
        case (iflag_eval)
            if (.not. selectors_valid(idrsel)) then
                call errmes(.true., "IDRSEL must be (0..4, 0..2, 0..1)", id, "STOP")
                return
            end if
            ! F does not depend on time explicitly: time is not needed.
            call rolling_disk_evaluate(q(:disk_nvars), radius, component, idrsel, scalar, array, &
                & xmatrx)
        case default
            call errmes(.true., "IFLAG must be 3 (initialise) or 0 (evaluate)", id, "STOP")
        end select
    end subroutine rolling_disk_ucosub

    !> True when every selector is one the contract defines.
    pure function selectors_valid(idrsel) result(valid)
        integer, intent(in) :: idrsel(3)
        logical :: valid

        valid = idrsel(1) >= scalar_none .and. idrsel(1) <= scalar_dtt &
            & .and. idrsel(2) >= array_none .and. idrsel(2) <= array_dtdq &
            & .and. idrsel(3) >= xmatrx_none .and. idrsel(3) <= xmatrx_dqdq
    end function selectors_valid

    !> Evaluate what idrsel asks for; entries that are symbolically zero are left untouched.
    pure subroutine rolling_disk_evaluate(q, radius, component, idrsel, scalar, array, xmatrx)
        !> The eight variables, in the order of disk_codes
        real(wp), intent(in) :: q(:)
        !> Disk radius [m]
        real(wp), intent(in) :: radius
        !> Which no-slip component: 1 (X), 2 (Y) or 3 (Z)
        integer, intent(in) :: component
        !> Output selectors
        integer, intent(in) :: idrsel(3)
        !> Selected scalar
        real(wp), intent(inout) :: scalar
        !> Selected first partials
        real(wp), intent(inout) :: array(:)
        !> Selected second partials
        real(wp), intent(inout) :: xmatrx(:, :)

        type(disk_trig_type) :: trig

        ! the sines and cosines every selected output shares, once per call
        if (idrsel(1) == scalar_value .or. idrsel(2) == array_dq .or. idrsel(3) == xmatrx_dqdq) &
            & trig = disk_trig(q)
        select case (idrsel(1))
        case (scalar_value)
            scalar = constraint_value(q, trig, radius, component)
        case (scalar_time_part, scalar_dt, scalar_dtt)
            ! No term of F is free of the variables and none depends on time explicitly.
            scalar = 0.0_wp
        end select
        if (idrsel(2) == array_dq) call first_partials(q, trig, radius, component, array)
        ! idrsel(2) == array_dtdq: d2F/dt dq is zero, left untouched.
        if (idrsel(3) == xmatrx_dqdq) call second_partials(q, trig, radius, component, xmatrx)
    end subroutine rolling_disk_evaluate

    !> sin and cos of psi and theta, and the spin phidot + psidot cos(theta) (the angular
    !> velocity about the disk axis) at the variables q.
    pure function disk_trig(q) result(trig)
        real(wp), intent(in) :: q(:)
        type(disk_trig_type) :: trig

        trig%spsi = sin(q(i_psi))
        trig%cpsi = cos(q(i_psi))
        trig%sth = sin(q(i_theta))
        trig%cth = cos(q(i_theta))
        trig%spin = q(i_phidot) + q(i_psidot)*trig%cth
    end function disk_trig

    !> F of one component: v_G + omega x r_GC = 0 with r_GC = -R e_y2 (docs/design.md §5).
    pure function constraint_value(q, trig, radius, component) result(f)
        real(wp), intent(in) :: q(:)
        type(disk_trig_type), intent(in) :: trig
        real(wp), intent(in) :: radius
        integer, intent(in) :: component
        real(wp) :: f

        associate (psidot => q(i_psidot), thetadot => q(i_thetadot), spsi => trig%spsi, &
                & cpsi => trig%cpsi, sth => trig%sth, cth => trig%cth, spin => trig%spin)
            select case (component)
            case (1)
                f = q(i_xdot) + radius*cpsi*spin - radius*thetadot*spsi*sth
            case (2)
                f = q(i_ydot) + radius*spsi*spin + radius*thetadot*cpsi*sth
            case default
                f = q(i_zdot) - radius*thetadot*cth
            end select
        end associate
    end function constraint_value

    !> dF/dq_j: six non-zero entries for components 1 and 2, three for component 3.
    pure subroutine first_partials(q, trig, radius, component, array)
        real(wp), intent(in) :: q(:)
        type(disk_trig_type), intent(in) :: trig
        real(wp), intent(in) :: radius
        integer, intent(in) :: component
        real(wp), intent(inout) :: array(:)

        associate (psidot => q(i_psidot), thetadot => q(i_thetadot), spsi => trig%spsi, &
                & cpsi => trig%cpsi, sth => trig%sth, cth => trig%cth, spin => trig%spin)
            select case (component)
            case (1)
                array(i_xdot) = 1.0_wp
                array(i_psi) = -radius*(spsi*spin + thetadot*cpsi*sth)
                array(i_theta) = -radius*(cpsi*psidot*sth + thetadot*spsi*cth)
                array(i_psidot) = radius*cpsi*cth
                array(i_thetadot) = -radius*spsi*sth
                array(i_phidot) = radius*cpsi
            case (2)
                array(i_ydot) = 1.0_wp
                array(i_psi) = radius*(cpsi*spin - thetadot*spsi*sth)
                array(i_theta) = radius*(thetadot*cpsi*cth - spsi*psidot*sth)
                array(i_psidot) = radius*spsi*cth
                array(i_thetadot) = radius*cpsi*sth
                array(i_phidot) = radius*spsi
            case default
                array(i_zdot) = 1.0_wp
                array(i_theta) = radius*thetadot*sth
                array(i_thetadot) = -radius*cth
            end select
        end associate
    end subroutine first_partials

    !> d2F/dq_i dq_j, both triangles: 14 non-zero entries for components 1 and 2, 3 for 3.
    pure subroutine second_partials(q, trig, radius, component, xmatrx)
        real(wp), intent(in) :: q(:)
        type(disk_trig_type), intent(in) :: trig
        real(wp), intent(in) :: radius
        integer, intent(in) :: component
        real(wp), intent(inout) :: xmatrx(:, :)

        associate (psidot => q(i_psidot), thetadot => q(i_thetadot), spsi => trig%spsi, &
                & cpsi => trig%cpsi, sth => trig%sth, cth => trig%cth, spin => trig%spin)
            select case (component)
            case (1)
                xmatrx(i_psi, i_psi) = radius*(thetadot*spsi*sth - cpsi*spin)
                xmatrx(i_theta, i_theta) = radius*(thetadot*spsi*sth - cpsi*psidot*cth)
                call set_pair(xmatrx, i_psi, i_theta, radius*(spsi*psidot*sth - thetadot*cpsi*cth))
                call set_pair(xmatrx, i_psi, i_psidot, -radius*spsi*cth)
                call set_pair(xmatrx, i_psi, i_thetadot, -radius*cpsi*sth)
                call set_pair(xmatrx, i_psi, i_phidot, -radius*spsi)
                call set_pair(xmatrx, i_theta, i_psidot, -radius*cpsi*sth)
                call set_pair(xmatrx, i_theta, i_thetadot, -radius*spsi*cth)
            case (2)
                xmatrx(i_psi, i_psi) = -radius*(spsi*spin + thetadot*cpsi*sth)
                xmatrx(i_theta, i_theta) = -radius*(thetadot*cpsi*sth + spsi*psidot*cth)
                call set_pair(xmatrx, i_psi, i_theta, -radius*(cpsi*psidot*sth + thetadot*spsi*cth))
                call set_pair(xmatrx, i_psi, i_psidot, radius*cpsi*cth)
                call set_pair(xmatrx, i_psi, i_thetadot, -radius*spsi*sth)
                call set_pair(xmatrx, i_psi, i_phidot, radius*cpsi)
                call set_pair(xmatrx, i_theta, i_psidot, -radius*spsi*sth)
                call set_pair(xmatrx, i_theta, i_thetadot, radius*cpsi*cth)
            case default
                xmatrx(i_theta, i_theta) = radius*thetadot*cth
                call set_pair(xmatrx, i_theta, i_thetadot, radius*sth)
            end select
        end associate
    end subroutine second_partials

    !> Set a mixed second partial in both triangles.
    pure subroutine set_pair(xmatrx, i, j, value)
        real(wp), intent(inout) :: xmatrx(:, :)
        integer, intent(in) :: i, j
        real(wp), intent(in) :: value

        xmatrx(i, j) = value
        xmatrx(j, i) = value
    end subroutine set_pair

end module rollcon_disk_reference
