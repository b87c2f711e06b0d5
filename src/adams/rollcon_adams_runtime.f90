! SPDX-License-Identifier: MIT
!> Where the ADAMS utility routines UCOVAR and ERRMES deliver what a UCOSUB tells them.
!>
!> ADAMS's utilities take no handle: a UCOSUB calls UCOVAR and ERRMES by name, so the emulation
!> needs one place that is known globally. This module is that place and the only mutable module
!> state in rollcon: a pointer to the registry collecting declarations during an initialisation
!> call, and the first error a UCOSUB reported that nobody has collected yet.
module rollcon_adams_runtime
    use rollcon_error, only : error_type, ucon_error
    use rollcon_text, only : to_text
    use rollcon_ucovar_registry, only : ucovar_registry_type
    implicit none
    private

    public :: begin_declaration, end_declaration, record_ucovar
    public :: report_ucon_error, take_ucon_error, has_ucon_error

    !> Registry collecting UCOVAR calls, associated only during an initialisation call
    type(ucovar_registry_type), pointer, save :: collector => null()
    !> UCON id whose initialisation call is under way
    integer, save :: declaring_id = 0
    !> Number of UCOVAR calls made during the current initialisation call
    integer, save :: ucovar_calls = 0
    !> First error reported and not yet taken
    type(error_type), allocatable, save :: pending

contains

    !> Start collecting the UCOVAR calls of UCON id into registry (before calling with IFLAG = 3).
    subroutine begin_declaration(registry, id)
        !> Registry that receives the declarations
        type(ucovar_registry_type), target, intent(inout) :: registry
        !> UCON statement id about to be initialised
        integer, intent(in) :: id

        collector => registry
        declaring_id = id
        ucovar_calls = 0
    end subroutine begin_declaration

    !> Stop collecting; report a missing declaration or any error raised during the call.
    subroutine end_declaration(error)
        !> Set when the initialisation call made no valid UCOVAR call or reported an error
        type(error_type), allocatable, intent(out) :: error
        integer :: id

        id = declaring_id
        nullify(collector)
        declaring_id = 0
        call take_ucon_error(error)
        if (allocated(error)) return
        if (ucovar_calls == 0) then
            call ucon_error(error, id, "the initialisation call (IFLAG = 3) made no UCOVAR call; " &
                & // "a UCOSUB must declare its variables with UCOVAR")
        end if
    end subroutine end_declaration

    !> What the external UCOVAR does: validate and record, or report the mistake.
    subroutine record_ucovar(id, nparts, lparts, nvars, lvars)
        !> UCON statement id given to UCOVAR
        integer, intent(in) :: id
        !> Number of part ids
        integer, intent(in) :: nparts
        !> Part ids
        integer, intent(in) :: lparts(:)
        !> Number of codes
        integer, intent(in) :: nvars
        !> Codes
        integer, intent(in) :: lvars(:)
        type(error_type), allocatable :: error
        type(ucovar_registry_type) :: scratch

        if (.not. associated(collector)) then
            ! Outside a driver's initialisation call: still validate, so a legacy caller learns
            ! of a wrong declaration through UCOERR, but keep nothing.
            call scratch%declare(id, nparts, lparts, nvars, lvars, error)
            if (allocated(error)) call keep(error)
            return
        end if
        ucovar_calls = ucovar_calls + 1
        if (id /= declaring_id) then
            call ucon_error(error, declaring_id, "UCOVAR was called with ID = " // to_text(id) &
                & // "; pass the ID argument the UCOSUB received")
            call keep(error)
            return
        end if
        call collector%declare(id, nparts, lparts, nvars, lvars, error)
        if (allocated(error)) call keep(error)
    end subroutine record_ucovar

    !> What the external ERRMES does: keep the message as an error of UCON id.
    subroutine report_ucon_error(id, message)
        !> Id of the statement concerned
        integer, intent(in) :: id
        !> The message
        character(len=*), intent(in) :: message
        type(error_type), allocatable :: error

        call ucon_error(error, id, message)
        call keep(error)
    end subroutine report_ucon_error

    !> Move the first pending error, if any, to the caller and clear it.
    subroutine take_ucon_error(error)
        !> The pending error, unallocated when there is none
        type(error_type), allocatable, intent(out) :: error

        if (allocated(pending)) call move_alloc(pending, error)
    end subroutine take_ucon_error

    !> True when an error is pending.
    function has_ucon_error() result(pending_error)
        logical :: pending_error

        pending_error = allocated(pending)
    end function has_ucon_error

    !> Keep the first error; later ones are consequences more often than not.
    subroutine keep(error)
        type(error_type), allocatable, intent(inout) :: error

        if (.not. allocated(pending)) call move_alloc(error, pending)
    end subroutine keep

end module rollcon_adams_runtime
