! SPDX-License-Identifier: MIT
!> `rollcon table`: the rolling-disk UCOSUB's value and non-zero partials at one state.
module rollcon_command_table
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, fatal_error, stat_input, disk_par, disk_codes, &
        & disk_nvars, max_ucon_vars, code_name, rolling_disk_ucosub, evaluate_ucon, &
        & declare_ucon, ucovar_registry_type
    use rollcon_cli, only : cli_request_type
    implicit none
    private

    public :: table_command

    !> The documented default state: tilted, turning, all rates non-zero, so that every
    !> non-zero expression shows (Xdot, Ydot, Zdot [m/s], psi, theta [rad], rates [rad/s])
    real(wp), parameter :: default_state(disk_nvars) = [0.1_wp, 0.02_wp, -0.01_wp, 0.3_wp, &
        & 1.2_wp, 0.5_wp, -0.2_wp, -1.0_wp]
    !> The paper's disk radius [m]
    real(wp), parameter :: default_radius = 0.1_wp

contains

    !> --radius R [m] and --state Xdot,Ydot,Zdot,psi,theta,psidot,thetadot,phidot, then the
    !> table.
    subroutine table_command(request, error)
        type(cli_request_type), intent(in) :: request
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: state(disk_nvars), radius

        call request%real_value("--radius", radius, default_radius, error)
        if (allocated(error)) return
        if (.not. (radius > 0.0_wp .and. radius < huge(1.0_wp))) then
            call fatal_error(error, "--radius must be a positive finite length [m]", stat_input)
            return
        end if
        state = default_state
        call request%real_list("--state", state, error)
        if (allocated(error)) return
        call print_table(state, radius, error)
    end subroutine table_command

    !> Print F and every non-zero first and second partial of the three components.
    subroutine print_table(state, radius, error)
        real(wp), intent(in) :: state(:), radius
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        real(wp) :: q(max_ucon_vars), scalar, array(max_ucon_vars)
        real(wp) :: xmatrx(max_ucon_vars, max_ucon_vars)
        integer :: component, i, j, n_value, n_first, n_second
        character(len=*), parameter :: row_format = '(2x, a, t34, es25.16e3)'

        q = 0.0_wp
        q(:disk_nvars) = state
        write(output_unit, '(a)') "Rolling-disk UCOSUB (hand-checked), UCON/1..3, FUNCTION=USER(" &
            & // "1, 21,22,23,14,15,24,25,26, R, component)"
        write(output_unit, '(a, es13.5e3, a)') "R = ", radius, " m; state:"
        do i = 1, disk_nvars
            write(output_unit, '(2x, a, t14, es25.16e3)') code_name(disk_codes(i)), state(i)
        end do
        write(output_unit, '(a)') "Units: F [m/s]; partials in m/s per unit of the variable."
        n_value = 0
        n_first = 0
        n_second = 0
        do component = 1, 3
            associate (par => disk_par(1, radius, component))
                call declare_ucon(rolling_disk_ucosub, component, par, registry, error)
                if (allocated(error)) return
                call evaluate_ucon(rolling_disk_ucosub, component, 0.0_wp, q, par, [1, 1, 1], &
                    & scalar, array, xmatrx, error)
                if (allocated(error)) return
            end associate
            write(output_unit, '(/, a, i0)') "Component F", component
            write(output_unit, row_format) "F", scalar
            if (scalar /= 0.0_wp) n_value = n_value + 1
            do j = 1, disk_nvars
                if (array(j) == 0.0_wp) cycle
                n_first = n_first + 1
                write(output_unit, row_format) "dF/d" // code_name(disk_codes(j)), array(j)
            end do
            do j = 1, disk_nvars
                do i = 1, disk_nvars
                    if (xmatrx(i, j) == 0.0_wp) cycle
                    n_second = n_second + 1
                    write(output_unit, row_format) "d2F/d" // code_name(disk_codes(i)) // " d" &
                        & // code_name(disk_codes(j)), xmatrx(i, j)
                end do
            end do
        end do
        write(output_unit, '(/, a, i0, a, i0, a, i0, a, i0, a)') "Non-zero: ", n_value, &
            & " values + ", n_first, " first partials + ", n_second, &
            & " second partials (both triangles) = ", n_value + n_first + n_second, " expressions"
    end subroutine print_table

end module rollcon_command_table
