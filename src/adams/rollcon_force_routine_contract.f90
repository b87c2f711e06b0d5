! SPDX-License-Identifier: MIT
!> The force user subroutines of ADAMS/Solver: SFOSUB (SFORCE), VFOSUB (VFORCE), GFOSUB
!> (GFORCE), VTOSUB (VTORQUE), with ADAMS's calling sequence, and the utilities they call
!> (SYSFNC, SYSARY, TIMGET, ERRMES) with theirs (docs/datasets.md, "User force routines").
!>
!>     SUBROUTINE SFOSUB(ID, TIME, PAR, NPAR, DFLAG, IFLAG, RESULT)
!>     INTEGER ID, NPAR; DOUBLE PRECISION TIME, PAR(*), RESULT; LOGICAL DFLAG, IFLAG
!>
!> VFOSUB and VTOSUB return RESULT(3) (components in RM's axes), GFOSUB RESULT(6) (force, then
!> torque, in RM's axes). The four share one interface here (force_routine_interface, RESULT
!> assumed size): a scalar RESULT and RESULT(3) or RESULT(6) are the same address in ADAMS's
!> Fortran calling convention. IFLAG = .TRUE. is the initialisation call: the routine's SYSFNC
!> and SYSARY calls then declare what of the state it reads (ADAMS learns the force's
!> dependencies from them). DFLAG = .TRUE. says the call is one of a difference (a partial
!> derivative being formed); a routine must give the same RESULT either way.
!>
!> Every constant ADAMS gives meaning to is named here, once (docs/design.md §2).
module rollcon_force_routine_contract
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: force_routine_interface
    public :: routine_sfosub, routine_vfosub, routine_gfosub, routine_vtosub, routine_kinds
    public :: routine_names, routine_symbols, routine_statements, routine_results
    public :: max_routine_par

    !> Kinds of force routine: SFOSUB, VFOSUB, GFOSUB, VTOSUB
    integer, parameter :: routine_sfosub = 1, routine_vfosub = 2, routine_gfosub = 3, &
        & routine_vtosub = 4
    !> Number of kinds
    integer, parameter :: routine_kinds = 4
    !> Names of the routines, by kind
    character(len=*), parameter :: routine_names(routine_kinds) = [character(len=6) :: &
        & "SFOSUB", "VFOSUB", "GFOSUB", "VTOSUB"]
    !> Symbols of the external subroutines as gfortran spells them, by kind
    character(len=*), parameter :: routine_symbols(routine_kinds) = [character(len=7) :: &
        & "sfosub_", "vfosub_", "gfosub_", "vtosub_"]
    !> The statement each kind serves
    character(len=*), parameter :: routine_statements(routine_kinds) = [character(len=7) :: &
        & "SFORCE", "VFORCE", "GFORCE", "VTORQUE"]
    !> Number of RESULT entries of each kind
    integer, parameter :: routine_results(routine_kinds) = [1, 3, 6, 3]
    !> Most constants in FUNCTION=USER(r1, ..., r30)
    integer, parameter :: max_routine_par = 30

    abstract interface
        !> A user-written force, called exactly as ADAMS/Solver calls SFOSUB, VFOSUB, GFOSUB or
        !> VTOSUB. The values are in the dataset's units (force, or force times length for a
        !> torque).
        subroutine force_routine_interface(id, time, par, npar, dflag, iflag, result)
            import :: wp
            !> Id of the force statement (SFORCE/2: 2)
            integer, intent(in) :: id
            !> Simulation time, dataset units
            real(wp), intent(in) :: time
            !> Constants of FUNCTION=USER(r1, ..., r30)
            real(wp), intent(in) :: par(*)
            !> Number of constants
            integer, intent(in) :: npar
            !> True in a call made to form a difference (a partial derivative)
            logical, intent(in) :: dflag
            !> True in the initialisation call, where SYSFNC and SYSARY calls declare what the
            !> routine reads
            logical, intent(in) :: iflag
            !> The force: 1 (SFOSUB), 3 (VFOSUB, VTOSUB) or 6 (GFOSUB) values
            real(wp), intent(inout) :: result(*)
        end subroutine force_routine_interface
    end interface

end module rollcon_force_routine_contract
