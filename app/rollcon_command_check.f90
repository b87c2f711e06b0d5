! SPDX-License-Identifier: MIT
!> `rollcon check FILE --ucon ID:PAR,...`: check a user's own UCOSUB without ADAMS.
module rollcon_command_check
    use, intrinsic :: iso_fortran_env, only : output_unit
    use rollcon, only : wp, error_type, fatal_error, stat_input, stat_io, user_ucosub_type, &
        & new_user_ucosub, ucon_request_type, user_check_options_type, user_check_report_type, &
        & sampling_ranges, check_user_ucosub_isolated, adm_model_type, read_adm, read_ucon_option, report_text, report_json, &
        & default_call_timeout
    use rollcon_command_line, only : real_option
    implicit none
    private

    public :: check_command, call_timeout_option

    !> Longest time limit per call accepted [s] (a day: beyond it, no limit is meant)
    real(wp), parameter :: longest_call_timeout = 86400.0_wp

contains

    !> Run the subcommand on the arguments from index first on; status is 0 when the routine
    !> is clean, 1 when something was found (error is for what prevents the check).
    subroutine check_command(first, status, error)
        !> Index of the first argument after "check"
        integer, intent(in) :: first
        !> 0 clean, 1 mismatches
        integer, intent(out) :: status
        !> Bad command line, or a file that cannot be built or loaded
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type), allocatable :: requests(:)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        type(user_ucosub_type) :: user
        character(len=:), allocatable :: path, json_path, library
        real(wp) :: call_timeout
        logical :: help
        integer :: unit, stat

        status = 0
        call read_arguments(first, path, requests, options, json_path, call_timeout, help, error)
        if (allocated(error) .or. help) return
        call new_user_ucosub(user, path, error)
        if (allocated(error)) return
        library = user%library // merge(" (from the cache)", " (compiled now)  ", user%from_cache)
        ! Each UCON is checked in a child process: a crash, a hang or a STOP in the routine
        ! becomes a finding, not the end of rollcon.
        call check_user_ucosub_isolated(user%ucosub, requests, options, call_timeout, report, &
            & error)
        if (allocated(error)) then
            call user%destroy()
            return
        end if
        write(output_unit, '(a)') report_text(report, path, trim(library))
        if (allocated(json_path)) then
            open(newunit=unit, file=json_path, status="replace", action="write", iostat=stat)
            if (stat == 0) write(unit, '(a)', iostat=stat) &
                & report_json(report, path, user%library, user%from_cache)
            if (stat == 0) close(unit, iostat=stat)
            if (stat /= 0) call fatal_error(error, json_path // ": cannot write the JSON report", &
                & stat_io)
        end if
        if (.not. report%clean()) status = 1
        call user%destroy()
    end subroutine check_command

    subroutine read_arguments(first, path, requests, options, json_path, call_timeout, help, &
            & error)
        integer, intent(in) :: first
        character(len=:), allocatable, intent(out) :: path, json_path
        type(ucon_request_type), allocatable, intent(out) :: requests(:)
        type(user_check_options_type), intent(out) :: options
        real(wp), intent(out) :: call_timeout
        logical, intent(out) :: help
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: argument
        type(ucon_request_type) :: request
        integer :: i

        allocate(requests(0))
        help = .false.
        call_timeout = default_call_timeout
        i = first
        do while (i <= command_argument_count())
            argument = get_argument(i)
            select case (argument)
            case ("-h", "--help")
                call print_help()
                help = .true.
                return
            case ("--ucon")
                if (i + 1 > command_argument_count()) then
                    call fatal_error(error, "--ucon needs ID:PAR1,PAR2,...", stat_input)
                    return
                end if
                call read_ucon_option(get_argument(i + 1), request, error)
                if (allocated(error)) return
                requests = [requests, request]
                i = i + 1
            case ("--model")
                if (i + 1 > command_argument_count()) then
                    call fatal_error(error, "--model needs a dataset (MODEL.adm)", stat_input)
                    return
                end if
                call model_requests(get_argument(i + 1), requests, error)
                if (allocated(error)) return
                i = i + 1
            case ("--call-timeout")
                i = i + 1
                call call_timeout_option(i, call_timeout, error)
                if (allocated(error)) return
            case ("--states")
                call read_integer("--states", i + 1, 1, options%states, error)
                if (allocated(error)) return
                i = i + 1
            case ("--seed")
                call read_integer("--seed", i + 1, -huge(1), options%seed, error)
                if (allocated(error)) return
                i = i + 1
            case ("--json")
                if (i + 1 > command_argument_count()) then
                    call fatal_error(error, "--json needs a file name", stat_input)
                    return
                end if
                json_path = get_argument(i + 1)
                i = i + 1
            case default
                if (argument(1:min(1, len(argument))) == "-" .or. allocated(path)) then
                    call fatal_error(error, "check: unexpected argument '" // argument &
                        & // "'; run 'rollcon check --help' for the usage", stat_input)
                    return
                end if
                path = argument
            end select
            i = i + 1
        end do
        if (.not. allocated(path)) then
            call fatal_error(error, "check: no UCOSUB file given; usage: rollcon check FILE " &
                & // "--ucon ID:PAR1,PAR2,... (rollcon check --help)", stat_input)
        else if (size(requests) == 0) then
            call fatal_error(error, "check: no --ucon ID:PAR1,PAR2,... or --model MODEL.adm " &
                & // "given; the routine is called as these UCON statements would call it", &
                & stat_input)
        end if
    end subroutine read_arguments

    !> The UCON statements of a dataset that its own UCOSUB serves (those naming no ROUTINE),
    !> appended to requests.
    subroutine model_requests(path, requests, error)
        character(len=*), intent(in) :: path
        type(ucon_request_type), allocatable, intent(inout) :: requests(:)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(ucon_request_type) :: request
        integer :: k, found

        call read_adm(path, adm, error)
        if (allocated(error)) return
        found = 0
        do k = 1, size(adm%ucons)
            if (allocated(adm%ucons(k)%routine)) then
                if (len(adm%ucons(k)%routine) > 0) cycle
            end if
            request%id = adm%ucons(k)%id
            request%par = adm%ucons(k)%par
            requests = [requests, request]
            found = found + 1
        end do
        if (found == 0) call fatal_error(error, path // ": no UCON statement is served by the " &
            & // "model's UCOSUB (each names a built-in ROUTINE): nothing to check", stat_input)
    end subroutine model_requests

    !> Read argument i as the value of --call-timeout: seconds, > 0 and at most a day.
    subroutine call_timeout_option(i, seconds, error)
        !> Index of the argument holding the value
        integer, intent(in) :: i
        !> Longest one call of a user's UCOSUB may take [s]
        real(wp), intent(out) :: seconds
        !> Set when the value is missing, not a number, not positive or too large
        type(error_type), allocatable, intent(out) :: error

        call real_option("--call-timeout", i, seconds, error)
        if (allocated(error)) return
        if (.not. (seconds > 0.0_wp .and. seconds <= longest_call_timeout)) then
            call fatal_error(error, "--call-timeout expects seconds, > 0 and at most 86400 " &
                & // "(a day), that one call of the UCOSUB may take", stat_input)
        end if
    end subroutine call_timeout_option

    subroutine read_integer(name, i, minimum, value, error)
        character(len=*), intent(in) :: name
        integer, intent(in) :: i, minimum
        integer, intent(inout) :: value
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        integer :: stat

        stat = 1
        if (i <= command_argument_count()) then
            text = get_argument(i)
            if (verify(text, "+-0123456789") == 0) read(text, *, iostat=stat) value
        else
            text = ""
        end if
        if (stat /= 0 .or. value < minimum) then
            call fatal_error(error, name // " expects an integer >= " // trim(int_text(minimum)) &
                & // ", got '" // text // "'", stat_input)
        end if
    end subroutine read_integer

    pure function int_text(value) result(text)
        integer, intent(in) :: value
        character(len=16) :: text

        write(text, '(i0)') value
    end function int_text

    function get_argument(i) result(argument)
        integer, intent(in) :: i
        character(len=:), allocatable :: argument
        integer :: length

        call get_command_argument(i, length=length)
        allocate(character(len=length) :: argument)
        if (length > 0) call get_command_argument(i, argument)
    end function get_argument

    subroutine print_help()
        character(len=80) :: ranges(4)
        integer :: i

        ranges = sampling_ranges()
        write(output_unit, '(a)') &
            & "usage: rollcon check FILE --ucon ID:PAR1,PAR2,... [--ucon ...] [--states N]", &
            & "                          [--seed S] [--json OUT] [--call-timeout SECONDS]", &
            & "       rollcon check FILE --model MODEL.adm [...]", &
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
            & "  --model MODEL.adm  every UCON of an ADAMS dataset that names no ROUTINE (those", &
            & "                 the model's own UCOSUB serves), with its id and PAR", &
            & "  --states N     random states per UCON (default 25)", &
            & "  --seed S       seed of the states (default 1); a run is reproducible", &
            & "  --json OUT     also write the report as JSON to OUT", &
            & "  --call-timeout SECONDS  longest one call of the routine may take (default 10)", &
            & "", &
            & "Each UCON is checked in a child process with ARRAY and XMATRX inside guarded", &
            & "buffers: a crash (SIGFPE, SIGSEGV, ...), a call longer than the time limit or a", &
            & "STOP in the routine ends only that process and is reported as a finding ([crash],", &
            & "[timeout], [stop]) with the call (IFLAG, IDRSEL) and the state; a write outside", &
            & "the declared block or outside ARRAY(30), XMATRX(30,30) is an [outside-block]", &
            & "finding with the index written.", &
            & "", &
            & "For each UCON: the initialisation call (IFLAG = 3) must declare the variables", &
            & "with one UCOVAR call (at most 30, known codes, part ids that appear among the PAR", &
            & "entries). Then, at each random state, every entry of SCALAR, ARRAY and XMATRX is", &
            & "compared with sixth-order central differences of the routine's own lower-order", &
            & "outputs, and the rules are checked: XMATRX symmetric, no second derivative in two", &
            & "velocities (linear in the velocities), outputs not asked for (IDRSEL = 0) left", &
            & "untouched, nothing beyond the declared variables, same inputs give the same", &
            & "outputs, no NaN or Infinity, no ERRMES call. States are drawn in:"
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
