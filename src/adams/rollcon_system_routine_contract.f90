! SPDX-License-Identifier: MIT
!> The user subroutines of ADAMS/Solver's system elements rollcon serves, with ADAMS's calling
!> sequence (docs/datasets.md, "User routines of requests", "... of variables", "... of
!> motions", "... of differential equations"):
!>
!>     SUBROUTINE REQSUB(ID, TIME, PAR, NPAR, IFLAG, RESULT)
!>     INTEGER ID, NPAR; DOUBLE PRECISION TIME, PAR(*), RESULT(8); LOGICAL IFLAG
!>
!>     SUBROUTINE VARSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
!>     INTEGER ID, NPAR; DOUBLE PRECISION TIME, PAR(*), VALUE; LOGICAL DFLAG, IFLAG
!>
!>     SUBROUTINE MOTSUB(ID, TIME, PAR, NPAR, IORD, IFLAG, VALUE)
!>     INTEGER ID, NPAR, IORD; DOUBLE PRECISION TIME, PAR(*), VALUE; LOGICAL IFLAG
!>
!>     SUBROUTINE DIFSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, VALUE)
!>     (VARSUB's calling sequence: variable_routine_interface)
!>
!> MOTSUB computes the displacement a MOTION/id, FUNCTION=USER(r1, ...) prescribes at TIME
!> (IORD = 0) and its first and second TIME derivatives (IORD = 1, 2), in the dataset's units;
!> a MOTION is a function of TIME alone, so a MOTSUB reads no
!> state (its initialisation call may declare none).
!> VARSUB computes the value of a VARIABLE/id, FUNCTION=USER(r1, ...), read by VARVAL(id).
!> DIFSUB computes, for a DIFF/id, FUNCTION=USER(r1, ...), the rate d DIF(id)/dt, or with
!> IMPLICIT the residual e of its equation 0 = e (which reads DIF1 through SYSFNC('DIF1')).
!> REQSUB computes the eight values of a REQUEST/id, FUNCTION=USER(r1, ...); ADAMS writes
!> RESULT(2:4) and RESULT(6:8) (request_columns), the components, and so does rollcon. IFLAG =
!> .TRUE. is the initialisation call, whose SYSFNC and SYSARY calls declare what the routine
!> reads, as for a force routine (rollcon_force_routine_contract).
!>
!> The kinds continue rollcon_force_routine_contract's (routine_sfosub ... routine_vtosub), so
!> that one table (rollcon_user_forces) holds every routine of a model.
!> Every constant ADAMS gives meaning to is named here, once (docs/design.md §2).
module rollcon_system_routine_contract
    use rollcon_kinds, only : wp
    use rollcon_force_routine_contract, only : routine_kinds
    implicit none
    private

    public :: request_routine_interface
    public :: routine_reqsub, request_routine_name, request_routine_symbol, request_results
    public :: request_columns
    public :: variable_routine_interface, routine_varsub, variable_routine_name, &
        & variable_routine_symbol
    public :: motion_routine_interface, routine_motsub, motion_routine_name, &
        & motion_routine_symbol, motion_orders
    public :: routine_difsub, diff_routine_name, diff_routine_symbol

    !> The kind of a REQSUB in the table of a model's routines (after the force routines')
    integer, parameter :: routine_reqsub = routine_kinds + 1
    !> Its name and its external symbol as gfortran spells it
    character(len=*), parameter :: request_routine_name = "REQSUB", &
        & request_routine_symbol = "reqsub_"
    !> The kind of a VARSUB, its name and symbol
    integer, parameter :: routine_varsub = routine_kinds + 2
    character(len=*), parameter :: variable_routine_name = "VARSUB", &
        & variable_routine_symbol = "varsub_"
    !> The kind of a MOTSUB, its name and symbol
    integer, parameter :: routine_motsub = routine_kinds + 3
    character(len=*), parameter :: motion_routine_name = "MOTSUB", &
        & motion_routine_symbol = "motsub_"
    !> The orders IORD of TIME derivative a MOTSUB is asked for: 0 (the displacement), 1, 2
    integer, parameter :: motion_orders = 2
    !> The kind of a DIFSUB, its name and symbol (it is called as a VARSUB is)
    integer, parameter :: routine_difsub = routine_kinds + 4
    character(len=*), parameter :: diff_routine_name = "DIFSUB", &
        & diff_routine_symbol = "difsub_"
    !> Number of RESULT entries of a REQSUB
    integer, parameter :: request_results = 8
    !> The entries ADAMS writes (the components of the two vectors; 1 and 5 are not written)
    integer, parameter :: request_columns(6) = [2, 3, 4, 6, 7, 8]

    abstract interface
        !> A user-written request, called exactly as ADAMS/Solver calls REQSUB; the values in
        !> whatever units the routine computes them (SYSFNC and SYSARY answer in the
        !> dataset's).
        subroutine request_routine_interface(id, time, par, npar, iflag, result)
            import :: wp
            !> Id of the REQUEST (REQUEST/5: 5)
            integer, intent(in) :: id
            !> Simulation time, dataset units
            real(wp), intent(in) :: time
            !> Constants of FUNCTION=USER(r1, ..., r30)
            real(wp), intent(in) :: par(*)
            !> Number of constants
            integer, intent(in) :: npar
            !> True in the initialisation call, where SYSFNC and SYSARY calls declare what the
            !> routine reads
            logical, intent(in) :: iflag
            !> The request's eight values
            real(wp), intent(inout) :: result(*)
        end subroutine request_routine_interface

        !> A user-written VARIABLE, called exactly as ADAMS/Solver calls VARSUB; the value in
        !> the units the routine computes it in (SYSFNC and SYSARY answer in the dataset's).
        !> A DIFSUB is called the same way (ID a DIFF's, VALUE its rate or implicit residual).
        subroutine variable_routine_interface(id, time, par, npar, dflag, iflag, value)
            import :: wp
            !> Id of the VARIABLE (VARIABLE/3: 3)
            integer, intent(in) :: id
            !> Simulation time, dataset units
            real(wp), intent(in) :: time
            !> Constants of FUNCTION=USER(r1, ..., r30)
            real(wp), intent(in) :: par(*)
            !> Number of constants
            integer, intent(in) :: npar
            !> True in a call made to form a difference of the partials
            logical, intent(in) :: dflag
            !> True in the initialisation call, where SYSFNC and SYSARY calls declare what the
            !> routine reads
            logical, intent(in) :: iflag
            !> The variable's value
            real(wp), intent(inout) :: value
        end subroutine variable_routine_interface

        !> A user-written MOTION, called exactly as ADAMS/Solver calls MOTSUB: the displacement
        !> it prescribes, or a TIME derivative of it, in the dataset's units (a length, or an
        !> angle in radians, per time unit to the power IORD).
        subroutine motion_routine_interface(id, time, par, npar, iord, iflag, value)
            import :: wp
            !> Id of the MOTION (MOTION/3: 3)
            integer, intent(in) :: id
            !> Simulation time, dataset units
            real(wp), intent(in) :: time
            !> Constants of FUNCTION=USER(r1, ..., r30)
            real(wp), intent(in) :: par(*)
            !> Number of constants
            integer, intent(in) :: npar
            !> The order of the TIME derivative asked for: 0, 1 or 2 (motion_orders)
            integer, intent(in) :: iord
            !> True in the initialisation call
            logical, intent(in) :: iflag
            !> The displacement (IORD = 0) or its IORD-th TIME derivative
            real(wp), intent(inout) :: value
        end subroutine motion_routine_interface
    end interface

end module rollcon_system_routine_contract
