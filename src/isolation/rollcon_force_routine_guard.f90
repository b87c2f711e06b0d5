! SPDX-License-Identifier: MIT
!> Calls a user's force routine (SFOSUB, VFOSUB, GFOSUB, VTOSUB), REQSUB, VARSUB or MOTSUB with
!> guarded outputs and protected inputs, and records each call where a watching host can read
!> it (rollcon_child_process), as rollcon_ucosub_guard does for UCOSUB: RESULT (a VARSUB's or
!> MOTSUB's VALUE) is handed to the routine inside a larger buffer whose other entries hold a
!> canary (a signalling-NaN bit pattern), and ID, TIME, PAR, NPAR, DFLAG and IFLAG (a REQSUB
!> takes no DFLAG; a MOTSUB takes IORD in its place) reach it as copies the guard owns (PAR
!> padded with zeros to 30
!> entries). After the call an overwritten canary or a changed copy is reported
!> (rollcon_user_forces' report_call_problem), so that the call's error names the statement,
!> the routine and the entry ("wrote RESULT(7), beyond the 6 entries of a GFOSUB's RESULT").
!>
!> guarded_force_call has the call hook's interface (rollcon_user_forces'
!> force_call_interface); install_force_guard points the hook at it. One guard per process.
module rollcon_force_routine_guard
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_force_routine_contract, only : force_routine_interface, max_routine_par
    use rollcon_system_routine_contract, only : request_routine_interface, routine_reqsub, &
        & variable_routine_interface, routine_varsub, routine_difsub
    use rollcon_system_routine_contract, only : motion_routine_interface, routine_motsub
    use rollcon_user_forces, only : force_call_interface, set_force_call_hook, &
        & get_force_routine, report_call_problem, get_request_routine, routine_name_of, &
        & get_variable_routine
    use rollcon_user_forces, only : get_motion_routine, user_motion_order
    use rollcon_child_process, only : call_record_type
    implicit none
    private

    public :: install_force_guard, guarded_force_call

    !> Canary entries before RESULT(1) and after RESULT(6)
    integer, parameter :: result_lead = 34, result_trail = 226
    !> The canary: a signalling NaN with a payload no arithmetic produces
    integer(int64), parameter :: canary_bits = int(z'7FF4C0DE5AFE1234', int64)

    type(call_record_type), pointer, save :: record => null()
    real(wp), save :: result_buffer(1 - result_lead:6 + result_trail)
    integer, save :: id_copy, npar_copy
    real(wp), save :: time_copy
    real(wp), allocatable, save :: par_copy(:)
    logical, save :: dflag_copy, iflag_copy
    integer, save :: iord_copy

contains

    !> Route every call of a user's force routine through guarded_force_call, recording each
    !> in shared (a child's record; null: none).
    subroutine install_force_guard(shared)
        type(call_record_type), pointer, intent(in) :: shared
        procedure(force_call_interface), pointer :: hook

        record => shared
        hook => guarded_force_call
        call set_force_call_hook(hook)
    end subroutine install_force_guard

    !> The routine of entry, its RESULT guarded and its inputs passed as copies compared after
    !> the call (the call hook's interface).
    subroutine guarded_force_call(entry, id, time, par, npar, dflag, iflag, result, n)
        integer, intent(in) :: entry, id, npar, n
        real(wp), intent(in) :: time, par(:)
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: result(n)
        procedure(force_routine_interface), pointer :: routine
        procedure(request_routine_interface), pointer :: request
        procedure(variable_routine_interface), pointer :: variable
        procedure(motion_routine_interface), pointer :: motion
        real(wp) :: canary
        integer :: kind, i, np, iord

        call get_force_routine(entry, routine, kind)
        canary = transfer(canary_bits, canary)
        result_buffer = canary
        result_buffer(1:n) = result
        np = max(0, min(npar, size(par)))
        if (.not. allocated(par_copy)) allocate(par_copy(max_routine_par))
        if (size(par_copy) < np) then
            deallocate(par_copy)
            allocate(par_copy(np))
        end if
        par_copy = 0.0_wp
        par_copy(:np) = par(:np)
        id_copy = id
        time_copy = time
        npar_copy = npar
        dflag_copy = dflag
        iflag_copy = iflag
        iord = user_motion_order()
        iord_copy = iord
        if (associated(record)) then
            record%routine_kind = kind
            record%ucon_id = id
            record%iflag = merge(1, 0, iflag)
            record%time = time
            record%nq = 0
            record%calls = record%calls + 1
            record%in_call = 1
        end if
        ! Sequence association: the routine's RESULT starts at result_buffer(1), so what it
        ! writes past its entries lands on canaries.
        if (kind == routine_reqsub) then
            call get_request_routine(entry, request)
            call request(id_copy, time_copy, par_copy, npar_copy, iflag_copy, result_buffer(1))
        else if (kind == routine_varsub .or. kind == routine_difsub) then
            ! a DIFSUB is called as a VARSUB is
            call get_variable_routine(entry, variable)
            call variable(id_copy, time_copy, par_copy, npar_copy, dflag_copy, iflag_copy, &
                & result_buffer(1))
        else if (kind == routine_motsub) then
            call get_motion_routine(entry, motion)
            call motion(id_copy, time_copy, par_copy, npar_copy, iord_copy, iflag_copy, &
                & result_buffer(1))
        else
            call routine(id_copy, time_copy, par_copy, npar_copy, dflag_copy, iflag_copy, &
                & result_buffer(1))
        end if
        if (associated(record)) record%in_call = 0
        result = result_buffer(1:n)
        do i = lbound(result_buffer, 1), ubound(result_buffer, 1)
            if (i >= 1 .and. i <= n) cycle
            if (transfer(result_buffer(i), canary_bits) == canary_bits) cycle
            call report_call_problem("the routine wrote RESULT(" // to_text(i) // ") = " &
                & // to_text(result_buffer(i)) // ", outside " // routine_name_of(kind) &
                & // "'s RESULT(" // to_text(n) // ")")
            exit
        end do
        if (id_copy /= id) call changed("ID", 0, real(id, wp), real(id_copy, wp))
        if (differs(time_copy, time)) call changed("TIME", 0, time, time_copy)
        if (npar_copy /= npar) call changed("NPAR", 0, real(npar, wp), real(npar_copy, wp))
        do i = 1, size(par_copy)
            if (i <= np) then
                if (differs(par_copy(i), par(i))) call changed("PAR", i, par(i), par_copy(i))
            else if (differs(par_copy(i), 0.0_wp)) then
                call changed("PAR", i, 0.0_wp, par_copy(i))
            end if
        end do
        if (dflag_copy .neqv. dflag) call report_call_problem("the routine changed DFLAG, " &
            & // "which it may only read")
        if (iflag_copy .neqv. iflag) call report_call_problem("the routine changed IFLAG, " &
            & // "which it may only read")
        if (iord_copy /= iord) call changed("IORD", 0, real(iord, wp), real(iord_copy, wp))
    contains
        subroutine changed(name, k, before, after)
            character(len=*), intent(in) :: name
            integer, intent(in) :: k
            real(wp), intent(in) :: before, after
            character(len=:), allocatable :: what

            what = name
            if (k > 0) what = what // "(" // to_text(k) // ")"
            call report_call_problem("the routine changed " // what // " from " &
                & // to_text(before) // " to " // to_text(after) // ", which it may only read")
        end subroutine changed
    end subroutine guarded_force_call

    !> True when two reals differ in a bit.
    elemental logical function differs(a, b)
        real(wp), intent(in) :: a, b

        differs = transfer(a, 0_int64) /= transfer(b, 0_int64)
    end function differs

end module rollcon_force_routine_guard
