! SPDX-License-Identifier: MIT
!> The user's UCOSUBs of a model with several files of user routines, and the routines a
!> statement's `ROUTINE=library::name` names by any name. ADAMS names a UCON's routine
!> `ROUTINE=library::subroutine`; here library is a `--ucosub` file as given or its name
!> without folder and extension, and subroutine any external subroutine of that file with the
!> calling sequence of the statement's kind (UCOSUB's for a UCON, SFOSUB's for an SFORCE, ...).
!>
!> The table holds each user UCOSUB under the names ROUTINE= may give; a UCON served by one is
!> bound to it by its id (bind_user_ucon), and the model calls user_ucosub_entry for it: the
!> driver's calling sequence carries no handle, so the entry point (dispatch_user_ucosub, or a
!> guard a child process installs in front of it: set_user_ucosub_entry) finds the routine by
!> the UCON's ID. A UCON bound to none is served by the model's own (the entry named "").
!>
!> A routine named by a name the loader did not register (ROUTINE=lib::MYFORCE) is found with
!> the resolver the loader installs (set_routine_resolver: the symbol of that name in the
!> library's shared object), so this module needs no knowledge of shared libraries.
module rollcon_user_ucosubs
    use, intrinsic :: iso_c_binding, only : c_funptr, c_null_funptr, c_associated, &
        & c_f_procpointer
    use rollcon_kinds, only : wp
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_force_routine_contract, only : force_routine_interface, routine_kinds
    use rollcon_system_routine_contract, only : request_routine_interface, routine_reqsub, &
        & variable_routine_interface, routine_varsub, routine_difsub, motion_routine_interface, &
        & routine_motsub
    use rollcon_user_forces, only : find_force_routine, register_force_routine, &
        & register_request_routine, register_variable_routine, register_diff_routine, &
        & register_motion_routine
    implicit none
    private

    public :: register_user_ucosub, find_user_ucosub, bind_user_ucon, clear_user_ucosubs
    public :: dispatch_user_ucosub, user_ucosub_entry, set_user_ucosub_entry
    public :: user_ucosub_source, user_ucosub_files, mark_user_ucosub_used
    public :: user_ucosub_unused, user_ucon_routine, routine_resolver_interface
    public :: set_routine_resolver, resolve_routine, is_library_routine, find_named_routine
    public :: find_named_ucosub

    abstract interface
        !> The address of subroutine name in the user's library (a file as given or its stem)
        !> and the file it was built from; a null address when either is unknown.
        subroutine routine_resolver_interface(library, name, address, source)
            import :: c_funptr
            character(len=*), intent(in) :: library, name
            type(c_funptr), intent(out) :: address
            character(len=:), allocatable, intent(out) :: source
        end subroutine routine_resolver_interface
    end interface

    !> A user UCOSUB under one name
    type :: ucosub_entry_type
        !> The ROUTINE= text that names it ("" for the model's own)
        character(len=:), allocatable :: name
        !> The file it was built from
        character(len=:), allocatable :: source
        procedure(ucosub_interface), pointer, nopass :: routine => null()
        !> A UCON is served by it
        logical :: used = .false.
    end type ucosub_entry_type

    type(ucosub_entry_type), allocatable, save :: table(:)
    !> UCON ids and the entries serving them
    integer, allocatable, save :: bound_ids(:), bound_entries(:)
    procedure(ucosub_interface), pointer, save :: entry_point => null()
    procedure(routine_resolver_interface), pointer, save :: resolver => null()

contains

    !> Empty the table and the bindings; the entry point becomes dispatch_user_ucosub.
    subroutine clear_user_ucosubs()
        if (allocated(table)) deallocate(table)
        allocate(table(0))
        if (allocated(bound_ids)) deallocate(bound_ids, bound_entries)
        allocate(bound_ids(0), bound_entries(0))
        entry_point => null()
    end subroutine clear_user_ucosubs

    !> Add a user UCOSUB under name ("" for the model's own; "FILE::NAME" else), built from
    !> source.
    subroutine register_user_ucosub(name, source, routine)
        character(len=*), intent(in) :: name, source
        procedure(ucosub_interface) :: routine
        type(ucosub_entry_type), allocatable :: longer(:)
        integer :: k, n

        if (.not. allocated(table)) call clear_user_ucosubs()
        n = size(table)
        allocate(longer(n + 1))
        do k = 1, n
            call move_alloc(table(k)%name, longer(k)%name)
            call move_alloc(table(k)%source, longer(k)%source)
            longer(k)%routine => table(k)%routine
            longer(k)%used = table(k)%used
        end do
        longer(n + 1)%name = name
        longer(n + 1)%source = source
        longer(n + 1)%routine => routine
        call move_alloc(longer, table)
    end subroutine register_user_ucosub

    !> The entry registered under name (matched in any case), 0 when none.
    integer function find_user_ucosub(name) result(entry)
        character(len=*), intent(in) :: name
        integer :: k

        entry = 0
        if (.not. allocated(table)) return
        do k = 1, size(table)
            if (upper_case(table(k)%name) == upper_case(trim(name))) then
                entry = k
                return
            end if
        end do
    end function find_user_ucosub

    !> UCON id is served by entry (find_user_ucosub); the entries of that routine's file and
    !> symbol are marked used.
    subroutine bind_user_ucon(id, entry)
        integer, intent(in) :: id, entry
        integer :: k

        if (.not. allocated(bound_ids)) call clear_user_ucosubs()
        k = findloc(bound_ids, id, dim=1)
        if (k > 0) then
            bound_entries(k) = entry
        else
            bound_ids = [bound_ids, id]
            bound_entries = [bound_entries, entry]
        end if
        call mark_user_ucosub_used(entry)
    end subroutine bind_user_ucon

    !> Mark entry's routine used (every entry of the same routine and file).
    subroutine mark_user_ucosub_used(entry)
        integer, intent(in) :: entry
        integer :: k

        if (entry < 1 .or. entry > size(table)) return
        do k = 1, size(table)
            if (table(k)%source == table(entry)%source .and. associated(table(k)%routine, &
                & table(entry)%routine)) table(k)%used = .true.
        end do
    end subroutine mark_user_ucosub_used

    !> The file of entry's routine.
    function user_ucosub_source(entry) result(source)
        integer, intent(in) :: entry
        character(len=:), allocatable :: source

        source = ""
        if (entry >= 1 .and. entry <= size(table)) source = table(entry)%source
    end function user_ucosub_source

    !> The files whose UCOSUB (the symbol UCOSUB) the table holds, each once, in order,
    !> separated by ", "; n: how many.
    subroutine user_ucosub_files(files, n)
        character(len=:), allocatable, intent(out) :: files
        integer, intent(out) :: n
        integer :: k

        files = ""
        n = 0
        if (.not. allocated(table)) return
        do k = 1, size(table)
            if (len(table(k)%name) < 8) cycle
            if (upper_case(table(k)%name(len(table(k)%name) - 7:)) /= "::UCOSUB") cycle
            if (index(", " // files // ",", ", " // table(k)%source // ",") > 0) cycle
            if (n > 0) files = files // ", "
            files = files // table(k)%source
            n = n + 1
        end do
    end subroutine user_ucosub_files

    !> The file of the first user UCOSUB no UCON is served by, "" when every one serves one.
    function user_ucosub_unused() result(source)
        character(len=:), allocatable :: source
        integer :: k

        source = ""
        if (.not. allocated(table)) return
        do k = 1, size(table)
            if (table(k)%used) cycle
            source = table(k)%source
            return
        end do
    end function user_ucosub_unused

    !> The entry that serves UCON id: its binding, else the model's own (""); 0 for none.
    integer function user_ucon_routine(id) result(entry)
        integer, intent(in) :: id
        integer :: k

        entry = 0
        if (allocated(bound_ids)) then
            k = findloc(bound_ids, id, dim=1)
            if (k > 0) entry = bound_entries(k)
        end if
        if (entry == 0) entry = find_user_ucosub("")
    end function user_ucon_routine

    !> The routine the model calls for a UCON served by a user's UCOSUB: the entry point set
    !> by set_user_ucosub_entry, else dispatch_user_ucosub.
    subroutine user_ucosub_entry(routine)
        procedure(ucosub_interface), pointer, intent(out) :: routine

        if (associated(entry_point)) then
            routine => entry_point
        else
            routine => dispatch_user_ucosub
        end if
    end subroutine user_ucosub_entry

    !> The routine the model calls for a user-served UCON (a guard in front of
    !> dispatch_user_ucosub).
    subroutine set_user_ucosub_entry(routine)
        procedure(ucosub_interface) :: routine

        entry_point => routine
    end subroutine set_user_ucosub_entry

    !> ADAMS's UCOSUB calling sequence: the routine serving UCON id (user_ucon_routine) called
    !> with the same arguments. A UCON served by none leaves the outputs untouched (the model
    !> binds every UCON it serves this way).
    subroutine dispatch_user_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, &
            & xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)
        procedure(ucosub_interface), pointer :: routine
        integer :: entry

        entry = user_ucon_routine(id)
        if (entry == 0) return
        routine => table(entry)%routine
        call routine(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
    end subroutine dispatch_user_ucosub

    !> The resolver of names the loader did not register (the loader's).
    subroutine set_routine_resolver(routine)
        procedure(routine_resolver_interface) :: routine

        resolver => routine
    end subroutine set_routine_resolver

    !> True when text has the form library::name (both parts non-empty).
    pure logical function is_library_routine(text)
        character(len=*), intent(in) :: text
        integer :: at

        at = index(text, "::", back=.true.)
        is_library_routine = at > 1 .and. at < len_trim(text) - 1
    end function is_library_routine

    !> The address of the routine ROUTINE=library::name names, and its file; a null address
    !> (source "") when the text has no library, no resolver is installed, the library is not
    !> one of the user's files or it defines no subroutine of that name.
    subroutine resolve_routine(text, address, source)
        character(len=*), intent(in) :: text
        type(c_funptr), intent(out) :: address
        character(len=:), allocatable, intent(out) :: source
        integer :: at

        address = c_null_funptr
        source = ""
        if (.not. is_library_routine(text) .or. .not. associated(resolver)) return
        at = index(text, "::", back=.true.)
        call resolver(trim(text(:at - 1)), trim(text(at + 2:)), address, source)
        if (.not. c_associated(address)) source = ""
    end subroutine resolve_routine

    !> The entry of rollcon_user_forces' table serving a statement of kind (routine_sfosub ..
    !> routine_difsub) that names routine ("" for the model's own): as registered, else, for
    !> ROUTINE=library::name, the subroutine of that name in that user's file (resolve_routine),
    !> registered under the text as written. 0 when there is none; the routine must have the
    !> calling sequence of kind (ADAMS's rule: the statement's kind fixes it).
    integer function find_named_routine(kind, routine) result(entry)
        integer, intent(in) :: kind
        character(len=*), intent(in) :: routine
        type(c_funptr) :: address
        character(len=:), allocatable :: source
        procedure(force_routine_interface), pointer :: force
        procedure(request_routine_interface), pointer :: request
        procedure(variable_routine_interface), pointer :: variable
        procedure(motion_routine_interface), pointer :: motion

        entry = find_force_routine(kind, routine)
        if (entry > 0) return
        call resolve_routine(routine, address, source)
        if (.not. c_associated(address)) return
        ! the symbol is an external routine of the user's file; its calling sequence is the
        ! statement kind's (the contract of rollcon_force_routine_contract and
        ! rollcon_system_routine_contract)
        if (kind >= 1 .and. kind <= routine_kinds) then
            call c_f_procpointer(address, force)
            call register_force_routine(kind, trim(routine), source, force)
        else if (kind == routine_reqsub) then
            call c_f_procpointer(address, request)
            call register_request_routine(trim(routine), source, request)
        else if (kind == routine_varsub) then
            call c_f_procpointer(address, variable)
            call register_variable_routine(trim(routine), source, variable)
        else if (kind == routine_difsub) then
            call c_f_procpointer(address, variable)
            call register_diff_routine(trim(routine), source, variable)
        else if (kind == routine_motsub) then
            call c_f_procpointer(address, motion)
            call register_motion_routine(trim(routine), source, motion)
        else
            return
        end if
        entry = find_force_routine(kind, routine)
    end function find_named_routine

    !> The entry serving a UCON whose ROUTINE= is routine (not a built-in one): as
    !> registered, else the subroutine ROUTINE=library::name names in that user's file
    !> (resolve_routine), registered under the text as written. 0 when there is none.
    integer function find_named_ucosub(routine) result(entry)
        character(len=*), intent(in) :: routine
        type(c_funptr) :: address
        character(len=:), allocatable :: source
        procedure(ucosub_interface), pointer :: ucosub

        entry = 0
        if (len_trim(routine) == 0) return
        entry = find_user_ucosub(routine)
        if (entry > 0) return
        call resolve_routine(routine, address, source)
        if (.not. c_associated(address)) return
        ! an external subroutine of the user's file with UCOSUB's calling sequence
        call c_f_procpointer(address, ucosub)
        call register_user_ucosub(trim(routine), source, ucosub)
        entry = find_user_ucosub(routine)
    end function find_named_ucosub

    pure function upper_case(text) result(upper)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: upper
        integer :: k

        upper = text
        do k = 1, len(text)
            if (text(k:k) >= "a" .and. text(k:k) <= "z") upper(k:k) = achar(iachar(text(k:k)) &
                & - 32)
        end do
    end function upper_case

end module rollcon_user_ucosubs
