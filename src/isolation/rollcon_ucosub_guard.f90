! SPDX-License-Identifier: MIT
!> Calls a user's UCOSUB with guarded outputs and protected inputs, and records each call where a
!> watching host can read it (rollcon_child_process). `check` and `run` call the routine
!> through this guard alike.
!>
!> ARRAY and XMATRX are handed to the routine inside larger buffers. Every entry the routine
!> may not write holds a canary, a signalling-NaN bit pattern: the entries before and beyond
!> the 30 (XMATRX: two columns before its 30 x 30 storage, so XMATRX(0,0) is seen, and four
!> after) and, once the UCON's number n of declared variables is known
!> (declare_guarded_count), ARRAY(n+1:30) and XMATRX outside (1:n, 1:n). After the call every
!> canary is compared bit for bit; an overwritten one is an outside-block violation with the
!> exact index. Only the declared block goes back to the caller, so a stray write never
!> reaches the driver's data.
!>
!> ID, TIME, Q, PAR, NPAR, IDRSEL and IFLAG, which the routine may only read, reach it as
!> copies the guard owns (PAR padded with zeros to 30 entries), whatever the caller passed (a
!> constant, a model's data): a routine that writes one of them cannot crash on read-only
!> memory or change the caller's data, and after the call each copy is compared bit for bit
!> with what the caller passed; a change is an argument violation naming the argument and
!> the entry ("the routine changed PAR(10)").
!>
!> guarded_ucosub has ADAMS's calling sequence, which carries no handle: the routine it
!> forwards to, the buffers and the violations are module state, like rollcon_adams_runtime's.
!> One guard per process; guarded calls do not nest.
module rollcon_ucosub_guard
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface, max_ucon_vars, max_ucon_par
    use rollcon_adams_runtime, only : report_ucon_error
    use rollcon_child_process, only : call_record_type
    implicit none
    private

    public :: guard_violation_type, install_guard, attach_call_record, guarded_ucosub
    public :: declare_guarded_count, note_stage, take_guard_violations, violation_text
    public :: array_lead, array_trail, xmatrx_lead_columns, xmatrx_trail_columns
    public :: violation_outside, violation_argument

    !> Kinds of violation: a write outside the block, a change of an argument to be read only
    integer, parameter :: violation_outside = 1, violation_argument = 2

    !> A write the routine made outside the entries it may write, or to an argument it may only
    !> read
    type :: guard_violation_type
        !> UCON id, IFLAG and IDRSEL of the call (as the caller passed them)
        integer :: id = 0, iflag = 0, idrsel(3) = 0
        !> "ARRAY" or "XMATRX" (outside the block); "ID", "TIME", "Q", "PAR", "NPAR",
        !> "IDRSEL" or "IFLAG" (an argument changed)
        character(len=6) :: output = ""
        !> Index written: ARRAY(row); XMATRX(row, column), row in 1..30 (column-major storage
        !> with leading dimension 30, so XMATRX(31,31) lands on XMATRX(1,32)), except that
        !> before XMATRX(1,1) row 0 stands for row 30 of the column before (XMATRX(0,0) is
        !> XMATRX(30,-1)); an argument's entry (0 for a scalar)
        integer :: row = 0, column = 0
        !> Number of declared variables when it happened (30 when not known)
        integer :: declared = max_ucon_vars
        !> The value written
        real(wp) :: value = 0.0_wp
        !> violation_outside or violation_argument
        integer :: kind = violation_outside
        !> An argument's value before the call
        real(wp) :: before = 0.0_wp
    end type guard_violation_type

    !> Canary entries before ARRAY(1) and after ARRAY(30)
    integer, parameter :: array_lead = 34, array_trail = 226
    !> Canary columns (of 30) before XMATRX(1,1) and after XMATRX(30,30): two before, so that
    !> XMATRX(0,0), 31 entries before XMATRX(1,1), lands on a canary
    integer, parameter :: xmatrx_lead_columns = 2, xmatrx_trail_columns = 4
    !> The canary: a signalling NaN with a payload no arithmetic produces
    integer(int64), parameter :: canary_bits = int(z'7FF4C0DE5AFE1234', int64)

    procedure(ucosub_interface), pointer, save :: guarded => null()
    type(call_record_type), pointer, save :: record => null()
    !> Turn violations into UCOSUB errors (ERRMES-like) instead of keeping them for a checker
    logical, save :: violations_are_errors = .false.
    real(wp), save :: array_buffer(1 - array_lead:max_ucon_vars + array_trail)
    real(wp), save :: xmatrx_buffer(max_ucon_vars, 1 - xmatrx_lead_columns:max_ucon_vars &
        & + xmatrx_trail_columns)
    integer, allocatable, save :: declared_ids(:), declared_counts(:)
    type(guard_violation_type), allocatable, save :: violations(:)
    !> The routine's copies of the arguments it may only read
    integer, save :: id_copy, npar_copy, idrsel_copy(3), iflag_copy
    real(wp), save :: time_copy, q_copy(max_ucon_vars)
    real(wp), allocatable, save :: par_copy(:)

contains

    !> Route guarded_ucosub to ucosub; with as_errors, a violation is reported like an ERRMES
    !> call (the driver's next check returns it as an error), else kept for take_guard_violations.
    subroutine install_guard(ucosub, as_errors)
        !> The user's routine
        procedure(ucosub_interface) :: ucosub
        !> Violations become errors (a run) rather than findings (a check)
        logical, intent(in) :: as_errors

        guarded => ucosub
        violations_are_errors = as_errors
        if (allocated(declared_ids)) deallocate(declared_ids, declared_counts)
        allocate(declared_ids(0), declared_counts(0))
        if (allocated(violations)) deallocate(violations)
        allocate(violations(0))
    end subroutine install_guard

    !> Record every call in record, shared with the watching host (in a child process).
    subroutine attach_call_record(shared)
        !> The child's shared record
        type(call_record_type), pointer, intent(in) :: shared

        record => shared
    end subroutine attach_call_record

    !> UCON id declared n variables: guard ARRAY(n+1:30) and XMATRX outside (1:n, 1:n) too.
    subroutine declare_guarded_count(id, n)
        !> UCON id
        integer, intent(in) :: id
        !> Number of declared variables
        integer, intent(in) :: n
        integer :: k

        if (.not. allocated(declared_ids)) allocate(declared_ids(0), declared_counts(0))
        k = findloc(declared_ids, id, dim=1)
        if (k == 0) then
            declared_ids = [declared_ids, id]
            declared_counts = [declared_counts, max(0, min(n, max_ucon_vars))]
        else
            declared_counts(k) = max(0, min(n, max_ucon_vars))
        end if
    end subroutine declare_guarded_count

    !> What the caller is doing (a checker's state number; 0 for the initialisation call).
    subroutine note_stage(stage)
        !> Stage number
        integer, intent(in) :: stage

        if (associated(record)) record%stage = stage
    end subroutine note_stage

    !> Move the violations seen since the last take to the caller.
    subroutine take_guard_violations(found)
        !> The violations, each index once
        type(guard_violation_type), allocatable, intent(out) :: found(:)

        if (.not. allocated(violations)) allocate(violations(0))
        call move_alloc(violations, found)
        allocate(violations(0))
    end subroutine take_guard_violations

    !> The user's routine with ADAMS's calling sequence, its outputs guarded and its inputs
    !> passed as copies that are compared after the call.
    subroutine guarded_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)
        real(wp) :: canary
        integer :: n, k, np

        n = max_ucon_vars
        if (allocated(declared_ids)) then
            k = findloc(declared_ids, id, dim=1)
            if (k > 0 .and. iflag /= 3) n = declared_counts(k)
        end if
        canary = transfer(canary_bits, canary)
        array_buffer = canary
        xmatrx_buffer = canary
        array_buffer(1:n) = array(1:n)
        xmatrx_buffer(1:n, 1:n) = xmatrx(1:n, 1:n)
        np = max(0, npar)
        if (.not. allocated(par_copy)) allocate(par_copy(max_ucon_par))
        if (size(par_copy) < np) then
            deallocate(par_copy)
            allocate(par_copy(np))
        end if
        id_copy = id
        time_copy = time
        q_copy = q
        par_copy = 0.0_wp
        par_copy(:np) = par(:np)
        npar_copy = npar
        idrsel_copy = idrsel
        iflag_copy = iflag
        call begin_call(id, time, q, idrsel, iflag)
        ! Sequence association: the routine's ARRAY(30) and XMATRX(30,30) start at these
        ! elements, so what it writes past them lands on canaries, not on our data.
        call guarded(id_copy, time_copy, q_copy, par_copy, npar_copy, idrsel_copy, iflag_copy, &
            & scalar, array_buffer(1), xmatrx_buffer(1, 1))
        if (associated(record)) record%in_call = 0
        array(1:n) = array_buffer(1:n)
        xmatrx(1:n, 1:n) = xmatrx_buffer(1:n, 1:n)
        call inspect(id, iflag, idrsel, n)
        call compare_inputs(id, time, q, par, npar, idrsel, iflag)
    end subroutine guarded_ucosub

    !> Compare the routine's copies of its inputs with what the caller passed; note each change.
    subroutine compare_inputs(id, time, q, par, npar, idrsel, iflag)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        integer :: i, np

        np = max(0, npar)
        if (id_copy /= id) call changed("ID", 0, real(id, wp), real(id_copy, wp))
        if (differs(time_copy, time)) call changed("TIME", 0, time, time_copy)
        do i = 1, max_ucon_vars
            if (differs(q_copy(i), q(i))) call changed("Q", i, q(i), q_copy(i))
        end do
        do i = 1, size(par_copy)
            if (i <= np) then
                if (differs(par_copy(i), par(i))) call changed("PAR", i, par(i), par_copy(i))
            else if (differs(par_copy(i), 0.0_wp)) then
                ! past NPAR: the zeros of the padding
                call changed("PAR", i, 0.0_wp, par_copy(i))
            end if
        end do
        if (npar_copy /= npar) call changed("NPAR", 0, real(npar, wp), real(npar_copy, wp))
        do i = 1, 3
            if (idrsel_copy(i) /= idrsel(i)) call changed("IDRSEL", i, real(idrsel(i), wp), &
                & real(idrsel_copy(i), wp))
        end do
        if (iflag_copy /= iflag) call changed("IFLAG", 0, real(iflag, wp), real(iflag_copy, wp))
    contains
        subroutine changed(name, entry, before, after)
            character(len=*), intent(in) :: name
            integer, intent(in) :: entry
            real(wp), intent(in) :: before, after
            type(guard_violation_type) :: found

            found = guard_violation_type(id, iflag, idrsel, name, entry, 0, max_ucon_vars, &
                & after, violation_argument, before)
            call note(found)
        end subroutine changed
    end subroutine compare_inputs

    !> True when two reals differ in a bit (a NaN equals itself, -0 differs from 0).
    elemental logical function differs(a, b)
        real(wp), intent(in) :: a, b

        differs = transfer(a, 0_int64) /= transfer(b, 0_int64)
    end function differs

    !> Write the call about to be made into the shared record.
    subroutine begin_call(id, time, q, idrsel, iflag)
        integer, intent(in) :: id, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30)
        integer :: n, k

        if (.not. associated(record)) return
        n = max_ucon_vars
        k = 0
        if (allocated(declared_ids)) k = findloc(declared_ids, id, dim=1)
        if (k > 0) n = declared_counts(k)
        if (iflag == 3) n = 0
        record%ucon_id = id
        record%iflag = iflag
        record%idrsel = idrsel
        record%time = time
        record%q = q
        record%nq = n
        record%calls = record%calls + 1
        record%in_call = 1
    end subroutine begin_call

    !> Compare every canary with its pattern; note each overwritten one.
    subroutine inspect(id, iflag, idrsel, n)
        integer, intent(in) :: id, iflag, idrsel(3), n
        integer :: i, j

        do i = lbound(array_buffer, 1), ubound(array_buffer, 1)
            if (i >= 1 .and. i <= n) cycle
            if (transfer(array_buffer(i), canary_bits) /= canary_bits) then
                call note(guard_violation_type(id, iflag, idrsel, "ARRAY", i, 0, n, &
                    & array_buffer(i)))
            end if
        end do
        do j = lbound(xmatrx_buffer, 2), ubound(xmatrx_buffer, 2)
            do i = 1, max_ucon_vars
                if (i <= n .and. j >= 1 .and. j <= n) cycle
                if (transfer(xmatrx_buffer(i, j), canary_bits) /= canary_bits) then
                    if (j < 1 .and. i == max_ucon_vars) then
                        ! before XMATRX(1,1): row 30 of column j is XMATRX(0, j + 1)
                        call note(guard_violation_type(id, iflag, idrsel, "XMATRX", 0, j + 1, &
                            & n, xmatrx_buffer(i, j)))
                    else
                        call note(guard_violation_type(id, iflag, idrsel, "XMATRX", i, j, n, &
                            & xmatrx_buffer(i, j)))
                    end if
                end if
            end do
        end do
    end subroutine inspect

    !> Keep a violation (each UCON and index once), or report it as an error.
    subroutine note(found)
        type(guard_violation_type), intent(in) :: found
        integer :: k

        if (violations_are_errors) then
            call report_ucon_error(found%id, violation_text(found))
            return
        end if
        if (.not. allocated(violations)) allocate(violations(0))
        do k = 1, size(violations)
            if (violations(k)%id == found%id .and. violations(k)%output == found%output &
                & .and. violations(k)%row == found%row .and. violations(k)%column &
                & == found%column) return
        end do
        violations = [violations, found]
    end subroutine note

    !> A violation in words: the index written or the argument changed, the value, the call.
    function violation_text(found) result(text)
        !> The violation
        type(guard_violation_type), intent(in) :: found
        character(len=:), allocatable :: text

        if (found%kind == violation_argument) then
            text = "the routine changed " // trim(found%output)
            if (found%row > 0) text = text // "(" // to_text(found%row) // ")"
            text = text // " from " // to_text(found%before) // " to " // to_text(found%value) &
                & // " in the call IFLAG = " // to_text(found%iflag) // ", IDRSEL = (" &
                & // to_text(found%idrsel(1)) // ", " // to_text(found%idrsel(2)) // ", " &
                & // to_text(found%idrsel(3)) // "); ID, TIME, Q, PAR, NPAR, IDRSEL and IFLAG " &
                & // "are the routine's to read only (ADAMS may pass them in read-only memory)"
            return
        end if
        if (found%output == "ARRAY") then
            text = "the UCOSUB wrote ARRAY(" // to_text(found%row) // ")"
        else
            text = "the UCOSUB wrote XMATRX(" // to_text(found%row) // "," &
                & // to_text(found%column) // ")"
            if (found%row < 1 .or. found%column < 1 .or. found%column > max_ucon_vars) then
                text = text // " (storage entry " // to_text(found%row + max_ucon_vars &
                    & * (found%column - 1)) // " of XMATRX(30,30), outside its 900)"
            end if
        end if
        text = text // " = " // to_text(found%value) // ", outside the block it may write ("
        if (found%declared < max_ucon_vars) then
            text = text // to_text(found%declared) // " variables declared"
        else
            text = text // "ARRAY(30), XMATRX(30,30)"
        end if
        text = text // "), in the call IFLAG = " // to_text(found%iflag) // ", IDRSEL = (" &
            & // to_text(found%idrsel(1)) // ", " // to_text(found%idrsel(2)) // ", " &
            & // to_text(found%idrsel(3)) // ")"
    end function violation_text

end module rollcon_ucosub_guard
