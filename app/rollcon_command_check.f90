! SPDX-License-Identifier: MIT
!> `rollcon check FILE --ucon ID:PAR,...`: check a user's own UCOSUB without ADAMS.
module rollcon_command_check
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, fatal_error, stat_input, user_ucosub_type, &
        & new_user_ucosub, ucon_request_type, user_check_options_type, user_check_report_type, &
        & check_user_ucosub_isolated, read_ucon_request, report_text, write_report_json, &
        & user_build_options_type, user_file_type, to_text
    use rollcon_program, only : sampling_ranges, default_call_timeout, max_check_states, &
        & states_refusal, dataset_has_user_routines, check_user_routines, routine_units_lines, &
        & check_dataset_ucons, check_tally_type
    use rollcon_cli, only : cli_request_type
    use rollcon_command_run, only : call_timeout_of
    implicit none
    private

    public :: check_command

contains

    !> Run the command: status is 0 when the routine is clean, 1 when something was found
    !> (error is for what prevents the check).
    subroutine check_command(request, status, error)
        type(cli_request_type), intent(in) :: request
        !> 0 clean, 1 mismatches
        integer, intent(out) :: status
        !> Bad command line, or a file that cannot be built or loaded
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type), allocatable :: requests(:)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        type(user_ucosub_type) :: user
        character(len=:), allocatable :: library
        real(wp) :: call_timeout

        status = 0
        if (request%has("--help")) then
            call print_help()
            return
        end if
        if (request%has("--model") .and. len(request%positional) > 0) then
            call check_model(request, status, error)
            return
        end if
        call read_requests(request, requests, options, call_timeout, error)
        if (allocated(error)) return
        call new_user_ucosub(user, request%positional, error)
        if (allocated(error)) return
        library = user%library // merge(" (from the cache)", " (compiled now)  ", user%from_cache)
        if (len(user%note) > 0) write(output_unit, '(a)') "check: " // user%note // ": rebuilt"
        ! Each UCON is checked in a child process: a crash, a hang or a STOP in the routine
        ! becomes a finding, not the end of rollcon.
        call check_user_ucosub_isolated(user%ucosub, requests, options, call_timeout, report, &
            & error)
        if (allocated(error)) then
            call user%destroy()
            return
        end if
        call write_report(request, report, request%positional, library, user%library, &
            & user%from_cache, status, error)
        call user%destroy()
    end subroutine check_command

    !> `check FILE --model MODEL.adm [--ucosub MORE]...`: the dataset's statements served by
    !> FILE's (and MORE's) routines of every kind but UCOSUB (check_routines), then every UCON
    !> a user's routine serves, against that routine (check_dataset_ucons: one naming no
    !> ROUTINE against the model's UCOSUB, one naming ROUTINE=FILE::NAME against that
    !> subroutine). status: the worse of the two; error when neither has anything to check.
    subroutine check_model(request, status, error)
        type(cli_request_type), intent(in) :: request
        integer, intent(out) :: status
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type), allocatable :: given(:)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        type(user_build_options_type) :: build
        type(user_file_type), allocatable :: files(:)
        character(len=:), allocatable :: library, notes, model, sources
        real(wp) :: call_timeout
        integer :: checked, k
        logical :: routines, from_cache

        status = 0
        model = request%text("--model", "")
        routines = dataset_has_user_routines(model)
        if (routines) then
            call check_routines(request, status, error)
            if (allocated(error)) return
        end if
        call read_requests(request, given, options, call_timeout, error)
        if (allocated(error)) return
        ! the model's files of routines as `rollcon run` takes them: FILE, then each MORE
        allocate(files(1 + request%count("--ucosub")))
        files(1)%path = request%positional
        sources = request%positional
        do k = 2, size(files)
            files(k)%path = request%nth("--ucosub", k - 1)
            sources = sources // ", " // files(k)%path
        end do
        call check_dataset_ucons(files, model, build, given, options, call_timeout, checked, &
            & report, library, from_cache, notes, error)
        if (allocated(error)) return
        if (checked == 0) then
            if (routines) return
            call fatal_error(error, model // ": no UCON statement is served by the files " &
                & // "given (" // sources // "; each UCON names a built-in ROUTINE) and no " &
                & // "other statement by a user's routine: nothing to check", stat_input)
            return
        end if
        write(output_unit, '(a)', advance="no") notes
        call write_report(request, report, sources, library // merge(" (from the cache)", &
            & " (compiled now)  ", from_cache), library, from_cache, k, error)
        status = max(status, k)
    end subroutine check_model

    !> The report as text on standard output (report_text) and, with --json, as JSON; status
    !> 1 when it has findings, 0 else.
    subroutine write_report(request, report, source, library, library_path, from_cache, &
            & status, error)
        type(cli_request_type), intent(in) :: request
        type(user_check_report_type), intent(in) :: report
        !> The user's file(s), the libraries (with whether from the cache), for the text; the
        !> library's path and whether from the cache, for the JSON
        character(len=*), intent(in) :: source, library, library_path
        logical, intent(in) :: from_cache
        integer, intent(out) :: status
        type(error_type), allocatable, intent(out) :: error

        status = 0
        write(output_unit, '(a)') report_text(report, source, trim(library))
        if (request%has("--json")) then
            ! every write checked: a report that did not reach the disk fails the command
            call write_report_json(request%text("--json", ""), report, source, library_path, &
                & from_cache, error)
        end if
        if (.not. report%clean()) status = 1
    end subroutine write_report

    !> `check FILE --model MODEL.adm [--ucosub MORE]...` for a dataset whose force, variable,
    !> request, motion or DIFF statements FILE's (and MORE's) routines serve
    !> (rollcon_user_routine_check): the findings, a line each; status 1 when there are some.
    subroutine check_routines(request, status, error)
        type(cli_request_type), intent(in) :: request
        integer, intent(out) :: status
        type(error_type), allocatable, intent(out) :: error
        type(user_build_options_type) :: build
        type(user_file_type), allocatable :: more_files(:)
        character(len=:), allocatable :: findings, units, done
        type(check_tally_type) :: tally
        real(wp) :: call_timeout
        integer :: count, seed, k

        status = 0
        call_timeout = real(default_call_timeout, wp)
        call call_timeout_of(request, call_timeout, error)
        if (allocated(error)) return
        seed = 1
        call request%integer_value("--seed", seed, seed, -huge(1), error)
        if (allocated(error)) return
        ! the model's other files of routines, as `rollcon run` takes them
        allocate(more_files(request%count("--ucosub")))
        do k = 1, size(more_files)
            more_files(k)%path = request%nth("--ucosub", k)
        end do
        call check_user_routines(request%positional, request%text("--model", ""), build, &
            & call_timeout, seed, findings, count, error, more_files, tally)
        if (allocated(error)) return
        write(output_unit, '(a)') "check: the user routines of " // request%positional &
            & // trim(merge(" and more files", "               ", size(more_files) > 0)) &
            & // " on " // request%text("--model", "") // " (the start and 20 states about it)"
        ! what "units as documented" means for each routine checked (docs/checker.md)
        call routine_units_lines(request%text("--model", ""), units, error)
        if (allocated(error)) return
        write(output_unit, '(a)', advance="no") units
        ! what was checked, as the UCOSUB check's verdict counts its UCONs and comparisons
        done = to_text(tally%statements) // " statement(s) checked at " &
            & // to_text(tally%states) // " states each, " // to_text(tally%calls) &
            & // " calls of their routines, " // to_text(tally%compared) // " values compared"
        if (count == 0) then
            write(output_unit, '(a)') "verdict: clean: " // done // ", no finding"
        else
            write(output_unit, '(a)', advance="no") findings
            write(output_unit, '(a)') "verdict: " // to_text(count) // " finding(s); " // done
            status = 1
        end if
    end subroutine check_routines

    !> The UCON statements given (--ucon; a dataset's, --model, are check_model's) and the
    !> check's options.
    subroutine read_requests(request, requests, options, call_timeout, error)
        type(cli_request_type), intent(in) :: request
        type(ucon_request_type), allocatable, intent(out) :: requests(:)
        type(user_check_options_type), intent(out) :: options
        real(wp), intent(out) :: call_timeout
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: one
        integer :: k

        allocate(requests(0))
        if (len(request%positional) == 0) then
            call fatal_error(error, "check: no UCOSUB file given; usage: rollcon check FILE " &
                & // "--ucon ID:PAR1,PAR2,... (rollcon check --help)", stat_input)
            return
        end if
        do k = 1, request%count("--ucon")
            call read_ucon_request(request%nth("--ucon", k), one, error)
            if (allocated(error)) return
            requests = [requests, one]
        end do
        if (size(requests) == 0 .and. .not. request%has("--model")) then
            call fatal_error(error, "check: no --ucon ID:PAR1,PAR2,... or --model MODEL.adm " &
                & // "given; the routine is called as these UCON statements would call it", &
                & stat_input)
            return
        end if
        call_timeout = real(default_call_timeout, wp)
        call call_timeout_of(request, call_timeout, error)
        if (allocated(error)) return
        call request%integer_value("--states", options%states, options%states, 1, error)
        if (allocated(error)) return
        if (options%states > max_check_states) then
            call fatal_error(error, "check: --states " // states_refusal(options%states), &
                & stat_input)
            return
        end if
        call request%integer_value("--seed", options%seed, options%seed, -huge(1), error)
    end subroutine read_requests

    subroutine print_help()
        character(len=80) :: ranges(4)
        integer :: i

        ranges = sampling_ranges()
        write(output_unit, '(a)') &
            & "usage: rollcon check FILE --ucon ID:PAR1,PAR2,... [--ucon ...] [--states N]", &
            & "                          [--seed S] [--json OUT] [--call-timeout SECONDS]", &
            & "       rollcon check FILE --model MODEL.adm [--ucosub MORE]... [...]", &
            & "", &
            & "Check a UCOSUB written for ADAMS/Solver, without ADAMS. FILE is its source (.f", &
            & "fixed form, compiled with -std=legacy; .f90 free form) or an object (.o, built", &
            & "with -fPIC). It is compiled with gfortran into a shared library, cached in", &
            & "$XDG_CACHE_HOME/rollcon (or ~/.cache/rollcon) until the file changes, and loaded.", &
            & "Its calls to UCOVAR and ERRMES reach rollcon's versions; nothing else is linked.", &
            & "", &
            & "  --ucon ID:PAR1,PAR2,...  a UCON statement, UCON/ID, FUNCTION=USER(PAR1,...):", &
            & "                 the routine is called with this ID, PAR and NPAR; repeat for", &
            & "                 each UCON the routine serves (ids positive and distinct, one", &
            & "                 number per comma-separated field, at most 30 PAR)", &
            & "  --model MODEL.adm  every UCON of an ADAMS dataset a user's routine serves, with", &
            & "                 its id and PAR, against that routine: the model's own UCOSUB", &
            & "                 for one naming no ROUTINE, NAME of FILE for one naming", &
            & "                 ROUTINE=FILE::NAME (a file given, or its name without folder", &
            & "                 and extension); and every", &
            & "                 SFORCE, VFORCE, GFORCE, VTORQUE, VARIABLE, REQUEST, MOTION or", &
            & "                 DIFF with FUNCTION=USER(...) at the start and 20 states about", &
            & "                 it: hidden state, NaN, jumps, SYSFNC/SYSARY reads not", &
            & "                 declared, typing", &
            & "  --ucosub MORE  with --model: another file of the model's routines (those its", &
            & "                 statements name as ROUTINE=MORE::NAME), as rollcon run takes", &
            & "                 it; repeat for each", &
            & "  --states N     random states per UCON (default 25, at most 100000)", &
            & "  --seed S       seed of the states (default 1); a run is reproducible", &
            & "  --json OUT     also write the report as JSON to OUT", &
            & "  --call-timeout SECONDS  longest one call of the routine may take (default 10)", &
            & "", &
            & "Each UCON is checked in a child process with ARRAY and XMATRX inside guarded", &
            & "buffers: a crash (SIGFPE, SIGSEGV, ...), a call longer than the time limit or a", &
            & "STOP in the routine ends only that process and is reported as a finding ([crash],", &
            & "[timeout], [stop]) with the call (IFLAG, IDRSEL) and the state; a write outside", &
            & "the declared block or outside ARRAY(30), XMATRX(30,30) is an [outside-block]", &
            & "finding with the index written. ID, TIME, Q, PAR, NPAR, IDRSEL and IFLAG reach", &
            & "the routine as copies (as in a run): a change of one is a [changed-argument]", &
            & "finding naming it.", &
            & "", &
            & "For each UCON: the initialisation call (IFLAG = 3) must declare the variables", &
            & "with one UCOVAR call (at most 30, known codes, part ids that appear among the PAR", &
            & "entries). Then, at each random state, every entry of SCALAR, ARRAY and XMATRX is", &
            & "compared with sixth-order central differences of the routine's own lower-order", &
            & "outputs, and the rules are checked: XMATRX symmetric, no second derivative in two", &
            & "velocities (linear in the velocities), outputs not asked for (IDRSEL = 0) left", &
            & "untouched, nothing beyond the declared variables, same inputs give the same", &
            & "outputs, no NaN or Infinity and nothing beyond 1e100 in magnitude, no ERRMES", &
            & "call. States are drawn in:"
        do i = 1, size(ranges)
            write(output_unit, '(a)') "  " // trim(ranges(i))
        end do
        write(output_unit, '(a)') &
            & "", &
            & "Findings of the same UCON, rule and entry are grouped: count and worst case.", &
            & "Exit status: 0 clean, 1 mismatches found; 2 when the file cannot be built or", &
            & "loaded or the command line is wrong (message on stderr)."
    end subroutine print_help

end module rollcon_command_check
