! SPDX-License-Identifier: MIT
!> `rollcon check FILE --model MODEL.adm [--ucosub MORE]...` on the dataset's UCONs: every UCON
!> served by one of the user's files checked against the routine that serves it in a run
!> (docs/checker.md): one naming no ROUTINE against the model's own UCOSUB (the first file's
!> that defines one; refused when several do, as a run refuses it), one naming
!> `ROUTINE=FILE::NAME` against that subroutine of that file (rollcon_user_ucosubs'
!> find_named_ucosub, as rollcon_adm_build's add_ucons finds it for a run). A UCON naming a
!> built-in routine is the suites' to check, not the user's. The files are compiled and loaded
!> in this process as a run's child loads them (nothing of them is called here); each UCON is
!> checked in a child process of its own (rollcon_isolated_audit) through
!> dispatch_user_ucosub, which finds the UCON's routine by its id. Each UCON's report is headed
!> by its statement as the start's check names it: "UCON/2 (line 10, ROUTINE=u::CIRCLE of
!> u.f)".
module rollcon_dataset_ucon_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_ucon
    use rollcon_text, only : to_text
    use rollcon_ucosub_units, only : ucosub_units_type
    use rollcon_model, only : served_by_model_ucosub
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_user_forces, only : clear_force_routines
    use rollcon_user_ucosubs, only : clear_user_ucosubs, find_user_ucosub, find_named_ucosub, &
        & bind_user_ucon, user_ucosub_files, user_ucosub_source, dispatch_user_ucosub, &
        & is_library_routine
    use rollcon_user_build, only : user_build_options_type, build_user_library
    use rollcon_user_library, only : user_ucosub_type, load_user_routines
    use rollcon_job, only : user_file_type
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    implicit none
    private

    public :: check_dataset_ucons

contains

    !> Check the UCONs of the dataset at model served by the user's files (files(1) is the
    !> command's FILE, the others its --ucosub MORE, as `rollcon run` takes them), and the
    !> given requests (--ucon: served by the model's own UCOSUB), each UCON in a child process
    !> (check_user_ucosub_isolated). checked: how many UCONs were checked (0: the model has
    !> none served by the files, and nothing was checked); report: the findings, each UCON's
    !> statement named (ucon_report_type's statement); notes: lines for the user before the report
    !> (a cache entry rebuilt, the dataset's units when not SI, each file that serves no UCON of
    !> the model). error: a file that does not build or load, a dataset the reader refuses, a
    !> UCON naming no ROUTINE when several files define UCOSUB or none does, a ROUTINE=FILE::NAME
    !> naming no subroutine of the files (each naming the statement and its line), or a request
    !> the check refuses.
    subroutine check_dataset_ucons(files, model, build, given, options, call_timeout, checked, &
            & report, library, from_cache, notes, error)
        type(user_file_type), intent(in) :: files(:)
        character(len=*), intent(in) :: model
        type(user_build_options_type), intent(in) :: build
        !> UCON statements given on the command line (--ucon), served by the model's UCOSUB
        type(ucon_request_type), intent(in) :: given(:)
        !> States, seed, tolerance
        type(user_check_options_type), intent(in) :: options
        !> Longest one call of a routine may take [s]
        real(wp), intent(in) :: call_timeout
        integer, intent(out) :: checked
        type(user_check_report_type), intent(out) :: report
        !> The libraries loaded (", " between), and whether every one came from the cache
        character(len=:), allocatable, intent(out) :: library
        logical, intent(out) :: from_cache
        character(len=:), allocatable, intent(out) :: notes
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: users(size(files))
        type(adm_model_type) :: adm
        type(ucon_request_type), allocatable :: requests(:)
        type(ucon_request_type) :: request
        procedure(ucosub_interface), pointer :: builtin
        character(len=:), allocatable :: defining_files, note, source
        logical :: served(size(files)), time_free, found
        integer :: k, f, entry, defining

        checked = 0
        library = ""
        from_cache = .true.
        notes = ""
        served = .false.
        ! the check runs no simulation: a dataset without SIMULATE (run from an ADAMS command
        ! file) is checked as it is
        call read_adm(model, adm, error, run_given=.true.)
        if (allocated(error)) return
        call clear_force_routines()
        call clear_user_ucosubs()
        do f = 1, size(files)
            users(f)%source = files(f)%path
            call build_user_library(files(f)%path, build, users(f)%library, &
                & users(f)%from_cache, error, note)
            if (allocated(error)) exit
            if (len(note) > 0) notes = notes // "check: " // note // ": rebuilt" // new_line("a")
            ! its UCOSUB as FILE::UCOSUB (and as the model's own when no file before has one),
            ! any other subroutine found when a UCON names it; nothing of it is called here
            call load_user_routines(users(f), error, named_only=.true.)
            if (allocated(error)) exit
            if (f > 1) library = library // ", "
            library = library // users(f)%library
            from_cache = from_cache .and. users(f)%from_cache
        end do
        if (.not. allocated(error)) then
            call user_ucosub_files(defining_files, defining)
            requests = given
            ! the routine computes in the dataset's units, as in a run
            request%units = ucosub_units_type(length=adm%units%length, time=adm%units%time)
            do k = 1, size(requests)
                if (find_user_ucosub("") == 0) then
                    call no_ucosub("--ucon " // to_text(requests(k)%id) // ": the UCON given " &
                        & // "is served by the model's UCOSUB")
                    exit
                end if
                call mark_served(user_ucosub_source(find_user_ucosub("")))
            end do
        end if
        if (.not. allocated(error)) then
            do k = 1, size(adm%ucons)
                associate (ucon => adm%ucons(k))
                    request%id = ucon%id
                    request%par = ucon%par
                    if (served_by_model_ucosub(ucon%routine)) then
                        if (defining > 1) then
                            call fatal_error(error, model // ":" // to_text(ucon%line) &
                                & // ": UCON/" // to_text(ucon%id) // " names no ROUTINE, and " &
                                & // "several files given define UCOSUB (" // defining_files &
                                & // "): name the one that serves it, ROUTINE=FILE::UCOSUB " &
                                & // "(FILE as given, or its name without folder and " &
                                & // "extension)", stat_input)
                            exit
                        end if
                        entry = find_user_ucosub("")
                        if (entry == 0) then
                            call no_ucosub(model // ":" // to_text(ucon%line) // ": UCON/" &
                                & // to_text(ucon%id) // " names no ROUTINE, so the model's " &
                                & // "UCOSUB serves it")
                            exit
                        end if
                        request%statement = "UCON/" // to_text(ucon%id) // " (line " &
                            & // to_text(ucon%line) // ")"
                    else
                        call find_builtin_ucosub(trim(ucon%routine), builtin, time_free, found)
                        ! a built-in routine: the suites check it
                        if (found) cycle
                        entry = find_named_ucosub(trim(ucon%routine))
                        if (entry == 0) then
                            call unknown_routine(ucon%routine, ucon%routine_at)
                            exit
                        end if
                        ! dispatch_user_ucosub finds the routine by the UCON's id
                        call bind_user_ucon(ucon%id, entry)
                        request%statement = "UCON/" // to_text(ucon%id) // " (line " &
                            & // to_text(ucon%line) // ", ROUTINE=" // trim(ucon%routine) &
                            & // " of " // user_ucosub_source(entry) // ")"
                    end if
                    call mark_served(user_ucosub_source(entry))
                    requests = [requests, request]
                end associate
            end do
        end if
        if (.not. allocated(error)) then
            checked = size(requests)
            if (checked > size(given) .and. .not. request%units%is_si()) notes = notes // model &
                & // ": the routines are called in the dataset's units, as in a run: lengths " &
                & // "in " // to_text(request%units%length) // " m, time in " &
                & // to_text(request%units%time) // " s; PAR as written, each random state " &
                & // "drawn in the ranges below and converted" // new_line("a")
            if (checked > 0) then
                do f = 1, size(files)
                    if (.not. served(f)) notes = notes // "check: " // files(f)%path &
                        & // " serves no UCON of " // model // new_line("a")
                end do
                call check_user_ucosub_isolated(dispatch_user_ucosub, requests, options, &
                    & call_timeout, report, error)
            end if
        end if
        do f = 1, size(files)
            call users(f)%destroy()
        end do
        call clear_user_ucosubs()
        call clear_force_routines()
    contains
        !> The file source serves a UCON.
        subroutine mark_served(source)
            character(len=*), intent(in) :: source

            where ([(files(f)%path == source, f = 1, size(files))]) served = .true.
        end subroutine mark_served

        !> A UCON the model's UCOSUB serves, and no file given defines one.
        subroutine no_ucosub(what)
            character(len=*), intent(in) :: what

            source = files(1)%path
            do f = 2, size(files)
                source = source // ", " // files(f)%path
            end do
            call fatal_error(error, what // ", and none of the files given defines UCOSUB (" &
                & // source // ": symbol 'ucosub_' not found); check the name in its " &
                & // "SUBROUTINE statement, or name the routine that serves the UCON with " &
                & // "ROUTINE=FILE::NAME", stat_ucon)
        end subroutine no_ucosub

        !> ROUTINE= names neither a built-in routine nor a subroutine of the files.
        subroutine unknown_routine(routine, routine_at)
            character(len=*), intent(in) :: routine, routine_at

            if (is_library_routine(routine)) then
                call fatal_error(error, routine_at // ": '" // trim(routine) // "' is neither " &
                    & // "a built-in UCOSUB (" // builtin_ucosub_names() // ") nor a " &
                    & // "subroutine of a file given: ROUTINE=FILE::NAME names the subroutine " &
                    & // "NAME, with UCOSUB's calling sequence, of FILE given as rollcon check " &
                    & // "FILE --model MODEL.adm [--ucosub MORE]... (FILE as given, or its " &
                    & // "name without folder and extension)", stat_input)
            else
                call fatal_error(error, routine_at // ": '" // trim(routine) // "' is not a " &
                    & // "built-in UCOSUB (" // builtin_ucosub_names() // "); a routine of " &
                    & // "your own is named ROUTINE=FILE::NAME, FILE given to rollcon check", &
                    & stat_input)
            end if
        end subroutine unknown_routine
    end subroutine check_dataset_ucons

end module rollcon_dataset_ucon_check
