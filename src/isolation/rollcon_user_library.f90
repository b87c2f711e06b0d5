! SPDX-License-Identifier: MIT
!> A user's own UCOSUB, loaded at run time: built into a cached shared library (with the shim
!> that serves its UCOVAR and ERRMES calls), opened with dlopen, and handed out as a procedure
!> pointer with ADAMS's calling sequence (ucosub_interface).
!>
!>     type(user_ucosub_type) :: user
!>     call new_user_ucosub(user, "my_ucosub.f", error)
!>     if (allocated(error)) return
!>     call declare_ucon(user%ucosub, 1, par, registry, error)
!>
!> Only the file the caller names is ever compiled or loaded.
module rollcon_user_library
    use, intrinsic :: iso_c_binding, only : c_ptr, c_funptr, c_null_ptr, c_null_funptr, &
        & c_associated, c_f_procpointer
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_dlopen, only : open_library, library_symbol, close_library, last_library_error
    use rollcon_user_shim, only : install_host_hooks
    use rollcon_user_build, only : user_build_options_type, build_user_library
    use rollcon_force_routine_contract, only : force_routine_interface, routine_symbols, &
        & routine_names, routine_kinds
    use rollcon_system_routine_contract, only : request_routine_interface, routine_reqsub, &
        & request_routine_name, request_routine_symbol, variable_routine_interface, &
        & routine_varsub, variable_routine_name, variable_routine_symbol, routine_difsub, &
        & diff_routine_name, diff_routine_symbol
    use rollcon_system_routine_contract, only : motion_routine_interface, routine_motsub, &
        & motion_routine_name, motion_routine_symbol
    use rollcon_user_forces, only : register_force_routine, find_force_routine, &
        & register_request_routine, register_variable_routine, register_diff_routine
    use rollcon_user_forces, only : register_motion_routine
    use rollcon_user_ucosubs, only : register_user_ucosub, find_user_ucosub, set_routine_resolver
    implicit none
    private

    public :: user_ucosub_type, user_build_options_type, new_user_ucosub, load_user_ucosub, &
        & ucosub_symbol, load_user_routines, library_stem, library_named, loaded_source

    !> Symbol of an external subroutine UCOSUB compiled by gfortran
    character(len=*), parameter :: ucosub_symbol = "ucosub_"

    !> A library load_user_routines opened, for routines named by any name
    !> (ROUTINE=library::name: resolve_symbol)
    type :: opened_library_type
        character(len=:), allocatable :: source
        type(c_ptr) :: handle = c_null_ptr
        !> A statement names one of its subroutines by name
        logical :: named = .false.
    end type opened_library_type

    type(opened_library_type), allocatable, save :: opened(:)

    !> A loaded UCOSUB; call destroy when done (ucosub dangles afterwards)
    type :: user_ucosub_type
        !> The file the user named
        character(len=:), allocatable :: source
        !> The shared library it was built into
        character(len=:), allocatable :: library
        !> True when the library came from the cache, false when built by this call
        logical :: from_cache = .false.
        !> Why a cached library was rebuilt (it was cut or changed on disk); "" otherwise
        character(len=:), allocatable :: note
        !> The routine, ready to pass wherever a procedure(ucosub_interface) is expected
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
        !> dlopen handle
        type(c_ptr) :: handle = c_null_ptr
        !> It defines none of the routines of fixed name (load_user_routines with
        !> named_only): only a statement's ROUTINE=FILE::NAME can use it
        logical :: defines_none = .false.
    contains
        !> Close the library
        procedure :: destroy => user_ucosub_destroy
    end type user_ucosub_type

contains

    !> Build (or find in the cache) and load the UCOSUB of a user's file.
    subroutine new_user_ucosub(self, path, error, options)
        !> The loaded routine
        type(user_ucosub_type), intent(out) :: self
        !> The user's file: .f (fixed form, compiled with -std=legacy), .f90 (free form) or .o
        character(len=*), intent(in) :: path
        !> Set when the file is missing, does not compile, cannot be loaded or has no UCOSUB;
        !> the message names the file (and the line gfortran complains about)
        type(error_type), allocatable, intent(out) :: error
        !> Cache folder and compiler; defaults: $XDG_CACHE_HOME/rollcon or ~/.cache/rollcon,
        !> gfortran
        type(user_build_options_type), intent(in), optional :: options
        type(user_build_options_type) :: build_options

        if (present(options)) build_options = options
        self%source = path
        call build_user_library(path, build_options, self%library, self%from_cache, error, &
            & self%note)
        if (allocated(error)) return
        call load_user_ucosub(self, error)
    end subroutine new_user_ucosub

    !> Load the UCOSUB of self%library, the library built from self%source (build_user_library):
    !> a child process that runs a user's routine loads it itself, so that nothing of it is
    !> ever mapped into the process that writes the outputs.
    subroutine load_user_ucosub(self, error)
        type(user_ucosub_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        type(c_funptr) :: address
        character(len=:), allocatable :: defined

        self%handle = open_library(self%library)
        if (.not. c_associated(self%handle)) then
            call fatal_error(error, self%source // ": the shared library built from it cannot be " &
                & // "loaded (" // last_library_error() // "); a routine may call only UCOVAR, " &
                & // "ERRMES and what it defines itself", stat_ucon)
            return
        end if
        call install_host_hooks(self%handle, self%library, error)
        if (allocated(error)) then
            call self%destroy()
            return
        end if
        address = library_symbol(self%handle, ucosub_symbol)
        if (.not. c_associated(address)) then
            defined = other_routines(self%handle)
            if (len(defined) > 0) then
                ! a file of another kind of routine: what it defines, and the check it takes
                call fatal_error(error, self%source // ": defines no subroutine UCOSUB; it " &
                    & // "defines " // defined // ", checked on the dataset whose statements " &
                    & // "call it (FUNCTION=USER(...)): rollcon check " // self%source &
                    & // " --model MODEL.adm", stat_ucon)
            else
                call fatal_error(error, self%source // ": defines no subroutine UCOSUB " &
                    & // "(symbol '" // ucosub_symbol // "' not found: " &
                    & // last_library_error() // "); check the name in its SUBROUTINE " &
                    & // "statement, and that UCOSUB is an external subroutine, not inside " &
                    & // "a module", stat_ucon)
            end if
            call self%destroy()
            return
        end if
        ! The symbol is gfortran's external UCOSUB, whose calling convention is ucosub_interface.
        call c_f_procpointer(address, self%ucosub)
    end subroutine load_user_ucosub

    !> The routines other than UCOSUB a loaded library defines, of the kinds rollcon serves
    !> ("SFOSUB and VARSUB"); "" for none.
    function other_routines(handle) result(text)
        type(c_ptr), intent(in) :: handle
        character(len=:), allocatable :: text
        character(len=6), allocatable :: names(:)
        integer :: kind, k

        allocate(names(0))
        do kind = 1, routine_kinds
            if (c_associated(library_symbol(handle, trim(routine_symbols(kind))))) &
                & names = [character(len=6) :: names, routine_names(kind)]
        end do
        if (c_associated(library_symbol(handle, request_routine_symbol))) &
            & names = [character(len=6) :: names, request_routine_name]
        if (c_associated(library_symbol(handle, variable_routine_symbol))) &
            & names = [character(len=6) :: names, variable_routine_name]
        if (c_associated(library_symbol(handle, motion_routine_symbol))) &
            & names = [character(len=6) :: names, motion_routine_name]
        if (c_associated(library_symbol(handle, diff_routine_symbol))) &
            & names = [character(len=6) :: names, diff_routine_name]
        text = ""
        do k = 1, size(names)
            if (k > 1 .and. k == size(names)) then
                text = text // " and "
            else if (k > 1) then
                text = text // ", "
            end if
            text = text // trim(names(k))
        end do
    end function other_routines

    !> Load every routine of self%library, the library built from self%source: its UCOSUB
    !> (self%ucosub; null when it defines none; registered with rollcon_user_ucosubs as
    !> "FILE::UCOSUB", and as the model's own, "", when no file loaded before defines one),
    !> its force routines SFOSUB, VFOSUB, GFOSUB,
    !> VTOSUB, its REQSUB, its VARSUB, its MOTSUB and its DIFSUB,
    !> registered with rollcon_user_forces under the names ROUTINE= may give: FILE::NAME with
    !> FILE the file as given or its name without folder and extension (u.f: "u::SFOSUB"), and
    !> "" (the model's own, serving every statement naming no ROUTINE) when no file loaded
    !> before defines one of that kind. An error when it defines none of them. Any other
    !> subroutine of the file is found when a statement names it (ROUTINE=FILE::NAME:
    !> rollcon_user_ucosubs' resolve_routine, served by resolve_symbol).
    subroutine load_user_routines(self, error, named_only)
        type(user_ucosub_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        !> A file defining none of them is kept (self%defines_none) for the routines
        !> statements name by name; the caller refuses it when none does (library_named)
        logical, intent(in), optional :: named_only
        type(c_funptr) :: address
        procedure(force_routine_interface), pointer :: routine
        procedure(request_routine_interface), pointer :: request
        procedure(variable_routine_interface), pointer :: variable
        procedure(motion_routine_interface), pointer :: motion
        integer :: kind
        logical :: found

        self%handle = open_library(self%library)
        if (.not. c_associated(self%handle)) then
            call fatal_error(error, self%source // ": the shared library built from it cannot be " &
                & // "loaded (" // last_library_error() // "); a routine may call only UCOVAR, " &
                & // "ERRMES, SYSFNC, SYSARY, TIMGET, STEP, RCNVRT, AKISPL, CUBSPL, GTSTRG, " &
                & // "GTARAY, ISTRNG, RSTRNG and what it defines itself", stat_ucon)
            return
        end if
        call install_host_hooks(self%handle, self%library, error)
        if (allocated(error)) then
            call self%destroy()
            return
        end if
        address = library_symbol(self%handle, ucosub_symbol)
        found = c_associated(address)
        if (found) then
            call c_f_procpointer(address, self%ucosub)
            ! the model's own UCOSUB is the first file's that defines one; with several, a
            ! UCON naming no ROUTINE is refused (rollcon_adm_build's add_ucons)
            if (find_user_ucosub("") == 0) call register_user_ucosub("", self%source, &
                & self%ucosub)
            call register_user_ucosub(self%source // "::UCOSUB", self%source, self%ucosub)
            call register_user_ucosub(library_stem(self%source) // "::UCOSUB", self%source, &
                & self%ucosub)
        end if
        call remember_library(self%source, self%handle)
        call set_routine_resolver(resolve_symbol)
        do kind = 1, routine_kinds
            address = library_symbol(self%handle, trim(routine_symbols(kind)))
            if (.not. c_associated(address)) cycle
            found = .true.
            ! the symbol is gfortran's external routine: force_routine_interface's convention
            call c_f_procpointer(address, routine)
            if (find_force_routine(kind, "") == 0) call register_force_routine(kind, "", &
                & self%source, routine)
            call register_force_routine(kind, self%source // "::" // trim(routine_names(kind)), &
                & self%source, routine)
            call register_force_routine(kind, library_stem(self%source) // "::" &
                & // trim(routine_names(kind)), self%source, routine)
        end do
        address = library_symbol(self%handle, request_routine_symbol)
        if (c_associated(address)) then
            found = .true.
            ! gfortran's external REQSUB: request_routine_interface's convention
            call c_f_procpointer(address, request)
            if (find_force_routine(routine_reqsub, "") == 0) call register_request_routine("", &
                & self%source, request)
            call register_request_routine(self%source // "::" // request_routine_name, &
                & self%source, request)
            call register_request_routine(library_stem(self%source) // "::" &
                & // request_routine_name, self%source, request)
        end if
        address = library_symbol(self%handle, variable_routine_symbol)
        if (c_associated(address)) then
            found = .true.
            ! gfortran's external VARSUB: variable_routine_interface's convention
            call c_f_procpointer(address, variable)
            if (find_force_routine(routine_varsub, "") == 0) &
                & call register_variable_routine("", self%source, variable)
            call register_variable_routine(self%source // "::" // variable_routine_name, &
                & self%source, variable)
            call register_variable_routine(library_stem(self%source) // "::" &
                & // variable_routine_name, self%source, variable)
        end if
        address = library_symbol(self%handle, motion_routine_symbol)
        if (c_associated(address)) then
            found = .true.
            ! gfortran's external MOTSUB: motion_routine_interface's convention
            call c_f_procpointer(address, motion)
            if (find_force_routine(routine_motsub, "") == 0) &
                & call register_motion_routine("", self%source, motion)
            call register_motion_routine(self%source // "::" // motion_routine_name, &
                & self%source, motion)
            call register_motion_routine(library_stem(self%source) // "::" &
                & // motion_routine_name, self%source, motion)
        end if
        address = library_symbol(self%handle, diff_routine_symbol)
        if (c_associated(address)) then
            found = .true.
            ! gfortran's external DIFSUB: VARSUB's calling sequence
            call c_f_procpointer(address, variable)
            if (find_force_routine(routine_difsub, "") == 0) &
                & call register_diff_routine("", self%source, variable)
            call register_diff_routine(self%source // "::" // diff_routine_name, self%source, &
                & variable)
            call register_diff_routine(library_stem(self%source) // "::" // diff_routine_name, &
                & self%source, variable)
        end if
        self%defines_none = .not. found
        if (.not. found .and. present(named_only)) then
            if (named_only) return
        end if
        if (.not. found) then
            call fatal_error(error, self%source // ": defines none of the routines rollcon " &
                & // "calls (UCOSUB, SFOSUB, VFOSUB, GFOSUB, VTOSUB, REQSUB, VARSUB, MOTSUB, " &
                & // "DIFSUB: symbols 'ucosub_', 'sfosub_', 'vfosub_', 'gfosub_', 'vtosub_', " &
                & // "'reqsub_', 'varsub_', 'motsub_', 'difsub_'); " &
                & // "check the names in its " &
                & // "SUBROUTINE statements, " &
                & // "and that they are external subroutines, not inside a module", stat_ucon)
            call self%destroy()
        end if
    end subroutine load_user_routines

    !> The address of subroutine name (any case) in the library built from library (a file
    !> as load_user_routines was given it, or its name without folder and extension), and that
    !> file: gfortran's symbol of an external subroutine (name in lower case and "_"), else a
    !> C function's (name in lower case). A null address when neither is found.
    subroutine resolve_symbol(library, name, address, source)
        character(len=*), intent(in) :: library, name
        type(c_funptr), intent(out) :: address
        character(len=:), allocatable, intent(out) :: source
        character(len=:), allocatable :: symbol
        integer :: k, i

        address = c_null_funptr
        source = ""
        if (.not. allocated(opened)) return
        symbol = name
        do i = 1, len(symbol)
            if (symbol(i:i) >= "A" .and. symbol(i:i) <= "Z") symbol(i:i) = &
                & achar(iachar(symbol(i:i)) + 32)
        end do
        do k = size(opened), 1, -1
            if (opened(k)%source /= library .and. library_stem(opened(k)%source) /= library) &
                & cycle
            if (.not. c_associated(opened(k)%handle)) cycle
            address = library_symbol(opened(k)%handle, symbol // "_")
            if (.not. c_associated(address)) address = library_symbol(opened(k)%handle, symbol)
            if (c_associated(address)) then
                source = opened(k)%source
                opened(k)%named = .true.
            end if
            return
        end do
    end subroutine resolve_symbol

    !> Append a library opened from source to the list resolve_symbol searches.
    subroutine remember_library(source, handle)
        character(len=*), intent(in) :: source
        type(c_ptr), intent(in) :: handle
        type(opened_library_type), allocatable :: longer(:)
        integer :: k, n

        n = 0
        if (allocated(opened)) n = size(opened)
        allocate(longer(n + 1))
        do k = 1, n
            call move_alloc(opened(k)%source, longer(k)%source)
            longer(k)%handle = opened(k)%handle
            longer(k)%named = opened(k)%named
        end do
        longer(n + 1)%source = source
        longer(n + 1)%handle = handle
        call move_alloc(longer, opened)
    end subroutine remember_library

    !> True when a statement named a subroutine of the library built from source by its name
    !> (resolve_symbol found it).
    logical function library_named(source)
        character(len=*), intent(in) :: source
        integer :: k

        library_named = .false.
        if (.not. allocated(opened)) return
        do k = 1, size(opened)
            if (opened(k)%source == source .and. opened(k)%named) library_named = .true.
        end do
    end function library_named

    !> The k-th file whose library load_user_routines opened and is open, in the order loaded
    !> (a run's first file, then its more files), each once; "" past the last.
    function loaded_source(k) result(source)
        integer, intent(in) :: k
        character(len=:), allocatable :: source
        integer :: i, j, n
        logical :: again

        source = ""
        if (.not. allocated(opened)) return
        n = 0
        do i = 1, size(opened)
            if (.not. c_associated(opened(i)%handle)) cycle
            again = .false.
            do j = 1, i - 1
                again = again .or. (opened(j)%source == opened(i)%source .and. &
                    & c_associated(opened(j)%handle))
            end do
            if (again) cycle
            n = n + 1
            if (n < k) cycle
            source = opened(i)%source
            return
        end do
    end function loaded_source

    !> The name of a file without its folder and extension ("test/x/sfo_b.f": "sfo_b").
    pure function library_stem(path) result(stem)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: stem
        integer :: dot

        stem = path(index(path, "/", back=.true.) + 1:)
        dot = index(stem, ".", back=.true.)
        if (dot > 1) stem = stem(:dot - 1)
    end function library_stem

    !> Close the library; the routine must not be called afterwards.
    subroutine user_ucosub_destroy(self)
        !> The loaded routine
        class(user_ucosub_type), intent(inout) :: self

        integer :: k

        nullify(self%ucosub)
        if (allocated(opened)) then
            do k = 1, size(opened)
                if (c_associated(opened(k)%handle, self%handle)) opened(k)%handle = c_null_ptr
            end do
        end if
        call close_library(self%handle)
    end subroutine user_ucosub_destroy

end module rollcon_user_library
