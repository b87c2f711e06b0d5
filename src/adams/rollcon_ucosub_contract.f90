! SPDX-License-Identifier: MIT
!> The UCOSUB/UCOVAR contract of ADAMS/Solver: calling sequence, selector codes, variable codes.
!>
!> Every constant ADAMS gives meaning to is named here, once (docs/design.md §2).
module rollcon_ucosub_contract
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: ucosub_interface, ucovar, errmes
    public :: max_ucon_vars, max_ucon_par
    public :: iflag_init, iflag_eval
    public :: scalar_none, scalar_value, scalar_time_part, scalar_dt, scalar_dtt
    public :: array_none, array_dq, array_dtdq
    public :: xmatrx_none, xmatrx_dqdq
    public :: code_x, code_y, code_z, code_psi, code_theta, code_phi
    public :: code_xdot, code_ydot, code_zdot, code_psidot, code_thetadot, code_phidot
    public :: valid_codes, is_valid_code, is_velocity_code, code_coordinate, code_name

    !> Most variables one UCON may declare, and the leading dimension of XMATRX
    integer, parameter :: max_ucon_vars = 30
    !> Most constants in FUNCTION=USER(r1, ..., r30)
    integer, parameter :: max_ucon_par = 30

    !> IFLAG of the initialisation call: declare variables with UCOVAR
    integer, parameter :: iflag_init = 3
    !> IFLAG of an evaluation call
    integer, parameter :: iflag_eval = 0

    !> IDRSEL(1), what SCALAR returns: nothing, F, f(t), dF/dt, d2F/dt2
    integer, parameter :: scalar_none = 0, scalar_value = 1, scalar_time_part = 2, &
        & scalar_dt = 3, scalar_dtt = 4
    !> IDRSEL(2), what ARRAY returns: nothing, dF/dq_j, d2F/dt dq_j
    integer, parameter :: array_none = 0, array_dq = 1, array_dtdq = 2
    !> IDRSEL(3), what XMATRX returns: nothing, d2F/dq_i dq_j (both triangles)
    integer, parameter :: xmatrx_none = 0, xmatrx_dqdq = 1

    !> UCOVAR codes: centre-of-mass position and 3-1-3 Euler angles of the principal axes
    integer, parameter :: code_x = 11, code_y = 12, code_z = 13
    integer, parameter :: code_psi = 14, code_theta = 15, code_phi = 16
    !> UCOVAR codes: their time derivatives (Euler-angle rates, not angular velocity)
    integer, parameter :: code_xdot = 21, code_ydot = 22, code_zdot = 23
    integer, parameter :: code_psidot = 24, code_thetadot = 25, code_phidot = 26
    !> Every code UCOVAR accepts, in table order
    integer, parameter :: valid_codes(12) = [11, 12, 13, 14, 15, 16, 21, 22, 23, 24, 25, 26]

    abstract interface
        !> A user-written constraint, called exactly as ADAMS/Solver calls UCOSUB.
        !> Outputs are intent(inout): entries that are symbolically zero may be left untouched,
        !> so the caller zeroes them before every call.
        subroutine ucosub_interface(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
            import :: wp
            !> Id of the UCON statement being evaluated
            integer, intent(in) :: id
            !> Simulation time [s]
            real(wp), intent(in) :: time
            !> Values of the declared variables, in UCOVAR order [m, rad, m/s, rad/s]
            real(wp), intent(in) :: q(30)
            !> Constants of FUNCTION=USER(r1, ..., r30)
            real(wp), intent(in) :: par(*)
            !> Number of constants in par
            integer, intent(in) :: npar
            !> Selectors for scalar, array and xmatrx (see the *_none ... constants)
            integer, intent(in) :: idrsel(3)
            !> iflag_init (3) or iflag_eval (0)
            integer, intent(in) :: iflag
            !> F, f(t), dF/dt or d2F/dt2, as idrsel(1) asks
            real(wp), intent(inout) :: scalar
            !> dF/dq_j or d2F/dt dq_j, as idrsel(2) asks
            real(wp), intent(inout) :: array(30)
            !> d2F/dq_i dq_j, as idrsel(3) asks
            real(wp), intent(inout) :: xmatrx(30, 30)
        end subroutine ucosub_interface
    end interface

    interface
        !> ADAMS utility: declare the variables of UCON id (external, so a host may supply its own)
        subroutine ucovar(id, nparts, lparts, nvars, lvars)
            !> UCON statement id
            integer, intent(in) :: id
            !> Number of entries in lparts
            integer, intent(in) :: nparts
            !> Part id of each variable
            integer, intent(in) :: lparts(*)
            !> Number of entries in lvars, equal to nparts
            integer, intent(in) :: nvars
            !> Code of each variable (valid_codes)
            integer, intent(in) :: lvars(*)
        end subroutine ucovar

        !> ADAMS utility: report an error from a user subroutine (external, as ucovar)
        subroutine errmes(errflg, mesage, id, endflg)
            !> True when there is an error to report
            logical, intent(in) :: errflg
            !> The message
            character(len=*), intent(in) :: mesage
            !> Id of the statement concerned
            integer, intent(in) :: id
            !> "STOP" when the run cannot go on, anything else otherwise
            character(len=*), intent(in) :: endflg
        end subroutine errmes
    end interface

contains

    !> True for a code UCOVAR accepts.
    elemental function is_valid_code(code) result(valid)
        !> UCOVAR code
        integer, intent(in) :: code
        logical :: valid

        valid = any(valid_codes == code)
    end function is_valid_code

    !> True for a velocity code (21-26).
    elemental function is_velocity_code(code) result(velocity)
        !> UCOVAR code
        integer, intent(in) :: code
        logical :: velocity

        velocity = code >= code_xdot .and. code <= code_phidot
    end function is_velocity_code

    !> Which of the part's six coordinates (X, Y, Z, psi, theta, phi) a code refers to, 0 if none.
    elemental function code_coordinate(code) result(coordinate)
        !> UCOVAR code
        integer, intent(in) :: code
        integer :: coordinate

        coordinate = 0
        if (is_valid_code(code)) coordinate = mod(code, 10)
    end function code_coordinate

    !> Readable name of a code: "X", "thetadot", or "code 17" when invalid.
    pure function code_name(code) result(name)
        !> UCOVAR code
        integer, intent(in) :: code
        character(len=:), allocatable :: name
        character(len=*), parameter :: coordinate_names(6) = &
            & [character(len=5) :: "X", "Y", "Z", "psi", "theta", "phi"]
        character(len=16) :: buffer

        if (is_valid_code(code)) then
            name = trim(coordinate_names(code_coordinate(code)))
            if (is_velocity_code(code)) name = name // "dot"
        else
            write(buffer, '("code ", i0)') code
            name = trim(buffer)
        end if
    end function code_name

end module rollcon_ucosub_contract
