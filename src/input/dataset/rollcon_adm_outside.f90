! SPDX-License-Identifier: MIT
!> Why a statement of the ADAMS/Solver language outside rollcon's subset is refused: the
!> reason added to the refusal of a well-known statement (each of them would change the
!> physics), so the message says what to write instead. A statement not listed here is refused
!> with the list of supported ones alone.
module rollcon_adm_outside
    use rollcon_adm_lexer, only : upper_case
    implicit none
    private

    public :: outside_reason

    !> Kinds of statement outside the subset, each with its reason
    integer, parameter :: kinds = 4
    character(len=*), parameter :: reasons(kinds) = [character(len=160) :: &
        & "rollcon's constraints are UCONs, JOINTs, JPRIMs, GCONs, COUPLERs and GEARs: state " &
        & // "this one as a GCON expression, or as a UCON served by a UCOSUB (ucon/)", &
        & "force elements other than SFORCE, VFORCE, GFORCE, VTORQUE, SPRINGDAMPER and " &
        & // "BUSHING are not in the subset: write the force as a GFORCE with FUNCTION " &
        & // "expressions", &
        & "sensors change a run as it goes (stop it, change its step): not in the subset", &
        & "rollcon's bodies are rigid PARTs"]
    !> Statement names and the kind of each (statements of ADAMS's outputs are read:
    !> rollcon_adm_outputs)
    character(len=*), parameter :: names(9) = [character(len=12) :: &
        & "PTCV", "CVCV", "BEAM", "FIELD", "FRICTION", "NFORCE", "SENSOR", &
        & "FLEX_BODY", "POINT_MASS"]
    integer, parameter :: kind_of(size(names)) = [1, 1, 2, 2, 2, 2, 3, 4, 4]

contains

    !> The reason a statement written `written` (any case; an abbreviation of at least three
    !> letters counts) is outside the subset; "" when it is not a listed one.
    pure function outside_reason(written) result(reason)
        character(len=*), intent(in) :: written
        character(len=:), allocatable :: reason
        character(len=:), allocatable :: name
        integer :: i

        reason = ""
        name = trim(upper_case(written))
        if (len(name) < 3) return
        do i = 1, size(names)
            if (index(trim(names(i)), name) == 1) then
                reason = trim(reasons(kind_of(i)))
                return
            end if
        end do
    end function outside_reason

end module rollcon_adm_outside
