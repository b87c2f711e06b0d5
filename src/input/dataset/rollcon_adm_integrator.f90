! SPDX-License-Identifier: MIT
!> The INTEGRATOR statement: the tolerance and the solver choices of the run settings. Every
!> keyword maps to one run key, and its value is checked against that key's range or options
!> in the run settings' one table (rollcon_run_keys); the choices together obey its rule
!> (run_choice_rule). Nothing here restates a bound.
!>
!> ADAMS's keyword: ERROR = e (sets RTOL, and ATOL unless ATOL is given). rollcon's own:
!> RTOL, ATOL [SI state units], MAXSTEPS (most steps per output interval), BAUMGARTE (rate
!> [1/s]), FORMULATION = IDA | CVODE | MAGGI, METHOD = BDF | ADAMS, DRIFT = PROJECTION |
!> BAUMGARTE | NONE, JACOBIAN = ANALYTIC | DQ | NONE, SOLVER = DENSE | SPARSE. ADAMS's choice
!> of integrator (GSTIFF, WSTIFF, ..., HHT) and its tuning (HMAX, KMAX, CORRECTOR, ...) are
!> read, each value checked for its form, and recorded as not used (rollcon_adm_outputs):
!> rollcon integrates with the settings above.
module rollcon_adm_integrator
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type, adm_argument_type, upper_case
    use rollcon_adm_keywords, only : read_reals, argument_key, arg_place, resolve_name, &
        & name_index, place
    use rollcon_adm_model, only : adm_run_type, adm_unused_type
    use rollcon_adm_outputs, only : read_form, record_unused, form_flag, form_number, &
        & form_whole, form_text
    use rollcon_run_settings, only : run_settings_type
    use rollcon_keys, only : key_type, find_key, kind_integer, kind_choice
    use rollcon_run_keys, only : bind_run_keys, run_choice_rule
    use rollcon_key_values, only : in_range, range_text
    implicit none
    private

    public :: read_integrator, integrator_keys

    !> The keywords of INTEGRATOR
    character(len=*), parameter :: integrator_keys(10) = [character(len=11) :: "ERROR", &
        & "RTOL", "ATOL", "MAXSTEPS", "BAUMGARTE", "FORMULATION", "METHOD", "DRIFT", "JACOBIAN", &
        & "SOLVER"]
    !> ADAMS's keywords of INTEGRATOR that rollcon reads and does not use: its integrators and
    !> formulations, then its tuning, and the form of each value
    character(len=*), parameter :: adams_keys(24) = [character(len=12) :: "GSTIFF", "WSTIFF", &
        & "DSTIFF", "CONSTANT_BDF", "HASTIFF", "HHT", "NEWMARK", "RKF45", "ABAM", "I3", "SI2", &
        & "SI1", "HMAX", "HMIN", "HINIT", "ALPHA", "BETA", "GAMMA", "ADAPTIVITY", "KMAX", &
        & "MAXIT", "CORRECTOR", "INTERPOLATE", "PATTERN"]
    integer, parameter :: adams_forms(size(adams_keys)) = [spread(form_flag, 1, 12), &
        & spread(form_number, 1, 7), form_whole, form_whole, form_text, form_text, form_text]
    !> The &run key each keyword sets (ERROR: rtol, and atol unless ATOL is given)
    character(len=*), parameter :: run_keys(10) = [character(len=14) :: "rtol", "rtol", &
        & "atol", "max_steps", "baumgarte_rate", "formulation", "method", "drift", "jacobian", &
        & "linear_solver"]

contains

    !> Read INTEGRATOR into run%settings, then check the choices together.
    subroutine read_integrator(path, where, statement, run, unused, unused_count, error)
        !> Dataset file, for messages
        character(len=*), intent(in) :: path
        !> "file:line: INTEGRATOR"
        character(len=*), intent(in) :: where
        type(adm_statement_type), intent(in) :: statement
        type(adm_run_type), intent(inout) :: run
        !> The dataset's statements and keywords read and not used: ADAMS's keywords are added
        type(adm_unused_type), allocatable, intent(inout) :: unused(:)
        !> The entries of unused that hold one (rollcon_adm_outputs' record_unused)
        integer, intent(inout) :: unused_count
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type), target :: settings
        type(key_type), allocatable :: keys(:)
        character(len=:), allocatable :: key, at
        integer :: lines(size(integrator_keys)), k, slot
        integer, allocatable :: ids(:)
        real(wp) :: error_value

        ! the table's pointers write into settings, which starts as the settings so far
        settings = run%settings
        keys = bind_run_keys(settings)
        lines = 0
        error_value = 0.0_wp
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, integrator_keys, key, error, &
                & also=adams_keys)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            slot = name_index(key, integrator_keys)
            if (slot == 0) then
                call read_form(statement%arguments(k), at, adams_forms(name_index(key, &
                    & adams_keys)), ids, error)
                if (allocated(error)) return
                call record_unused(unused, unused_count, "INTEGRATOR " // key, statement%line)
                cycle
            end if
            if (key == "FORMULATION" .and. adams_formulation(statement%arguments(k))) then
                ! ADAMS's own formulation of its integrators (I3, SI2, SI1): not rollcon's
                call record_unused(unused, unused_count, "INTEGRATOR FORMULATION=" &
                    & // upper_case(trim(statement%arguments(k)%values(1)%text)), &
                    & statement%line)
                cycle
            end if
            lines(slot) = statement%arguments(k)%line
            associate (entry => keys(find_key(keys, "run", trim(run_keys(slot)))))
                if (entry%kind == kind_choice) then
                    call store_choice(statement, k, at, entry, error)
                else
                    call store_number(statement, k, at, entry, error)
                    if (key == "ERROR" .and. .not. allocated(error)) error_value = entry%real_value
                end if
            end associate
            if (allocated(error)) return
        end do
        if (lines(1) > 0 .and. lines(2) > 0) then
            call fatal_error(error, place(path, lines(2)) // where(index(where, ": ", &
                & back=.true.):) // " RTOL: give ERROR or RTOL, not both (ERROR sets RTOL)", &
                & stat_input)
            return
        end if
        if (lines(1) > 0 .and. lines(3) == 0) then
            ! ERROR is ADAMS's one tolerance: it bounds the absolute error too
            associate (entry => keys(find_key(keys, "run", "atol")))
                if (.not. in_range(entry, error_value)) then
                    call fatal_error(error, place(path, lines(1)) // where(index(where, ": ", &
                        & back=.true.):) // " ERROR sets ATOL too (no ATOL given), so it must " &
                        & // "be " // range_text(entry) // " (as &run atol), got " &
                        & // to_text(error_value), stat_input)
                    return
                end if
                entry%real_value = error_value
            end associate
        end if
        run%settings = settings
        call check_choices(path, where, statement%line, lines, run, error)
    end subroutine read_integrator

    !> FORMULATION= one of ADAMS's formulations of its integrators (I3, SI2, SI1, any case).
    pure logical function adams_formulation(argument)
        type(adm_argument_type), intent(in) :: argument

        adams_formulation = .false.
        if (.not. argument%assigned) return
        if (size(argument%values) /= 1) return
        adams_formulation = any(upper_case(trim(argument%values(1)%text)) == &
            & [character(len=3) :: "I3", "SI2", "SI1"])
    end function adams_formulation

    !> A number for a real or integer &run key, within the key's range.
    subroutine store_number(statement, k, at, entry, error)
        type(adm_statement_type), intent(in) :: statement
        integer, intent(in) :: k
        !> "file:line: INTEGRATOR KEYWORD"
        character(len=*), intent(in) :: at
        type(key_type), intent(inout) :: entry
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:)
        character(len=:), allocatable :: expected
        logical :: whole

        call read_reals(statement%arguments(k), at, 1, 1, .false., values, error)
        if (allocated(error)) return
        whole = entry%kind /= kind_integer .or. values(1) == aint(values(1))
        if (.not. (whole .and. in_range(entry, values(1)))) then
            expected = range_text(entry)
            if (entry%kind == kind_integer) expected = "a whole number " // expected
            call fatal_error(error, at // " must be " // expected // " (as &run " &
                & // trim(entry%name) // "), got " // to_text(values(1)), stat_input)
            return
        end if
        if (entry%kind == kind_integer) then
            entry%integer_value = nint(values(1))
        else
            entry%real_value = values(1)
        end if
    end subroutine store_number

    !> One of the options of a choice &run key, in any case, abbreviated to a unique prefix.
    subroutine store_choice(statement, k, at, entry, error)
        type(adm_statement_type), intent(in) :: statement
        integer, intent(in) :: k
        character(len=*), intent(in) :: at
        type(key_type), intent(inout) :: entry
        type(error_type), allocatable, intent(out) :: error
        character(len=len(entry%options(1)%name)) :: names(size(entry%options))
        character(len=:), allocatable :: choice
        integer :: j

        if (.not. statement%arguments(k)%assigned .or. &
            & size(statement%arguments(k)%values) /= 1) then
            call fatal_error(error, at // ": expected one name", stat_input)
            return
        end if
        do j = 1, size(names)
            names(j) = upper_case(entry%options(j)%name)
        end do
        call resolve_name(statement%arguments(k)%values(1)%text, names, trim(entry%name), at, &
            & choice, error)
        if (allocated(error)) return
        entry%integer_value = entry%options(name_index(choice, names))%code
    end subroutine store_choice

    !> The scenes' rule on the solver choices, its message at the keyword's line.
    subroutine check_choices(path, where, line, lines, run, error)
        character(len=*), intent(in) :: path, where
        !> Line of the statement, and of each keyword given (0: not given)
        integer, intent(in) :: line, lines(:)
        type(adm_run_type), intent(in) :: run
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, expected, got, keyword, given
        integer :: slot

        call run_choice_rule(run%settings, key, expected, got)
        if (len(key) == 0) return
        slot = name_index(key, run_keys)
        keyword = trim(integrator_keys(slot))
        given = ""
        if (lines(slot) == 0) given = " (" // keyword // " not given: the default)"
        call fatal_error(error, place(path, merge(lines(slot), line, lines(slot) > 0)) &
            & // where(index(where, ": ", back=.true.):) // " " // keyword // " must be " &
            & // expected // ", got " // got // given, stat_input)
    end subroutine check_choices

end module rollcon_adm_integrator
