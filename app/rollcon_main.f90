! SPDX-License-Identifier: MIT
!> rollcon: command-line front end. For now: the rolling-disk UCOSUB's derivative table.
program rollcon_main
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : wp, error_type, disk_par, disk_codes, disk_nvars, max_ucon_vars, &
        & code_name, rolling_disk_ucosub, evaluate_ucon, declare_ucon, ucovar_registry_type
    use rollcon_cli, only : real_option_list, real_option
    implicit none
    !> The documented default state: tilted, turning, all rates non-zero, so that every
    !> non-zero expression shows (Xdot, Ydot, Zdot [m/s], psi, theta [rad], rates [rad/s])
    real(wp), parameter :: default_state(disk_nvars) = [0.1_wp, 0.02_wp, -0.01_wp, 0.3_wp, &
        & 1.2_wp, 0.5_wp, -0.2_wp, -1.0_wp]
    !> The paper's disk radius [m]
    real(wp), parameter :: default_radius = 0.1_wp
    type(error_type), allocatable :: error
    real(wp) :: state(disk_nvars), radius
    character(len=:), allocatable :: command

    call read_command_line(command, state, radius, error)
    if (allocated(error)) call fail(error)
    select case (command)
    case ("help")
        call print_help()
    case ("table")
        call print_table(state, radius, error)
        if (allocated(error)) call fail(error)
    end select

contains

    subroutine read_command_line(command, state, radius, error)
        character(len=:), allocatable, intent(out) :: command
        real(wp), intent(out) :: state(:), radius
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: argument
        integer :: i

        command = "table"
        state = default_state
        radius = default_radius
        i = 1
        do while (i <= command_argument_count())
            call get_command_argument(i, argument)
            select case (trim(argument))
            case ("-h", "--help", "help")
                command = "help"
                return
            case ("table")
                command = "table"
            case ("--radius")
                i = i + 1
                call real_option("--radius", i, radius, error)
                if (allocated(error)) return
                if (.not. (radius > 0.0_wp .and. radius < huge(1.0_wp))) then
                    call input_fail(error, "--radius must be a positive finite length [m]")
                    return
                end if
            case ("--state")
                i = i + 1
                call real_option_list("--state", i, state, error)
                if (allocated(error)) return
            case default
                call input_fail(error, "unknown argument '" // trim(argument) &
                    & // "'; run 'rollcon --help' for the usage")
                return
            end select
            i = i + 1
        end do
    end subroutine read_command_line

    subroutine input_fail(error, message)
        use rollcon_error, only : fatal_error, stat_input
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: message

        call fatal_error(error, message, stat_input)
    end subroutine input_fail

    subroutine print_help()
        write(output_unit, '(a)') &
            & "usage: rollcon [table] [--radius R] [--state XD,YD,ZD,PSI,THETA,PSID,THETAD,PHID]", &
            & "       rollcon --help", &
            & "", &
            & "Evaluates the hand-checked rolling-disk UCOSUB (the no-slip condition of a disk", &
            & "of radius R on the plane z = 0) through the ADAMS calling sequence and prints F", &
            & "and every non-zero first and second partial of its three components, with their", &
            & "count (49 at a generic state: 3 values, 15 first and 31 second partials).", &
            & "", &
            & "  --radius R   disk radius [m], default 0.1 (the paper's coin)", &
            & "  --state ...  the eight UCOVAR variables, comma-separated: Xdot, Ydot, Zdot [m/s],", &
            & "               psi, theta [rad] (3-1-3 Euler angles), psidot, thetadot, phidot", &
            & "               [rad/s]; default 0.1,0.02,-0.01,0.3,1.2,0.5,-0.2,-1", &
            & "", &
            & "Exit status: 0 on success, 1 on bad input or a UCOSUB error."
    end subroutine print_help

    subroutine print_table(state, radius, error)
        real(wp), intent(in) :: state(:), radius
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        real(wp) :: q(max_ucon_vars), scalar, array(max_ucon_vars)
        real(wp) :: xmatrx(max_ucon_vars, max_ucon_vars)
        integer :: component, i, j, n_value, n_first, n_second
        character(len=*), parameter :: row_format = '(2x, a, t34, es24.16)'

        q = 0.0_wp
        q(:disk_nvars) = state
        write(output_unit, '(a)') "Rolling-disk UCOSUB (hand-checked), UCON/1..3, FUNCTION=USER(" &
            & // "1, 21,22,23,14,15,24,25,26, R, component)"
        write(output_unit, '(a, es12.5, a)') "R = ", radius, " m; state:"
        do i = 1, disk_nvars
            write(output_unit, '(2x, a, t14, es24.16)') code_name(disk_codes(i)), state(i)
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

    subroutine fail(error)
        type(error_type), intent(in) :: error

        write(error_unit, '(a)') "rollcon: error: " // error%message
        error stop 1
    end subroutine fail

end program rollcon_main
