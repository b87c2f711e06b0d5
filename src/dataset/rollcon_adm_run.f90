! SPDX-License-Identifier: MIT
!> Dataset statements of the run: SIMULATE/DYNAMIC (end time, output steps) and INTEGRATOR
!> (tolerance and the formulation choices the namelist scenes offer).
module rollcon_adm_run
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type
    use rollcon_adm_keywords, only : read_reals, argument_key, arg_place, resolve_name
    use rollcon_adm_units, only : units_type
    use rollcon_adm_model, only : adm_run_type
    use rollcon_scene_keys, only : choice_code
    implicit none
    private

    public :: read_simulate, read_integrator

    character(len=*), parameter :: simulate_keys(4) = [character(len=7) :: "DYNAMIC", "END", &
        & "STEPS", "DTOUT"]
    character(len=*), parameter :: integrator_keys(5) = [character(len=11) :: "ERROR", &
        & "FORMULATION", "METHOD", "DRIFT", "JACOBIAN"]
    character(len=*), parameter :: formulations(2) = [character(len=5) :: "IDA", "CVODE"]
    character(len=*), parameter :: methods(2) = [character(len=5) :: "BDF", "ADAMS"]
    character(len=*), parameter :: drifts(3) = [character(len=10) :: "PROJECTION", &
        & "BAUMGARTE", "NONE"]
    character(len=*), parameter :: jacobians(2) = [character(len=8) :: "ANALYTIC", "DQ"]

contains

    !> SIMULATE/DYNAMIC, END=t, STEPS=n or DTOUT=dt.
    subroutine read_simulate(path, where, statement, units, run, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(units_type), intent(in) :: units
        type(adm_run_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        real(wp) :: steps
        logical :: dynamic
        integer :: k

        dynamic = .false.
        steps = 0.0_wp
        run%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, simulate_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            if (key == "DYNAMIC") then
                dynamic = .not. statement%arguments(k)%assigned
                if (.not. dynamic) call fatal_error(error, at // " takes no value", stat_input)
                if (allocated(error)) return
                cycle
            end if
            call read_reals(statement%arguments(k), at, 1, 1, .false., values, error)
            if (allocated(error)) return
            if (.not. values(1) > 0.0_wp) then
                call fatal_error(error, at // " must be > 0, got " // to_text(values(1)), &
                    & stat_input)
                return
            end if
            select case (key)
            case ("END")
                run%end_time = values(1)*units%time
            case ("STEPS")
                if (values(1) /= aint(values(1)) .or. values(1) > 1.0e9_wp) then
                    call fatal_error(error, at // " must be a whole number of output steps " &
                        & // "(at most 1e9), got " // to_text(values(1)), stat_input)
                    return
                end if
                steps = values(1)
            case ("DTOUT")
                run%output_step = values(1)*units%time
            end select
        end do
        if (.not. dynamic) then
            call fatal_error(error, where // ": only SIMULATE/DYNAMIC is supported (a dynamic " &
                & // "analysis); write SIMULATE/DYNAMIC, END=..., STEPS=...", stat_input)
        else if (run%end_time <= 0.0_wp) then
            call fatal_error(error, where // ": END=t (the end time) is missing", stat_input)
        else if ((steps > 0.0_wp) .eqv. (run%output_step > 0.0_wp)) then
            call fatal_error(error, where // ": give one of STEPS=n and DTOUT=dt", stat_input)
        else if (steps > 0.0_wp) then
            run%output_step = run%end_time/steps
        end if
        run%settings%end_time = run%end_time
        run%settings%output_step = run%output_step
    end subroutine read_simulate

    !> INTEGRATOR/ERROR=rtol, FORMULATION=IDA|CVODE, METHOD=BDF|ADAMS,
    !> DRIFT=PROJECTION|BAUMGARTE|NONE, JACOBIAN=ANALYTIC|DQ.
    subroutine read_integrator(path, where, statement, run, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_run_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, choice
        real(wp), allocatable :: values(:)
        integer :: k

        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, integrator_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            if (key == "ERROR") then
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error)
                if (allocated(error)) return
                if (.not. (values(1) >= 1.0e-14_wp .and. values(1) <= 0.1_wp)) then
                    call fatal_error(error, at // " must be in [1e-14, 0.1], got " &
                        & // to_text(values(1)), stat_input)
                    return
                end if
                run%settings%rtol = values(1)
                cycle
            end if
            if (.not. statement%arguments(k)%assigned .or. &
                & size(statement%arguments(k)%values) /= 1) then
                call fatal_error(error, at // ": expected one name", stat_input)
                return
            end if
            associate (written => statement%arguments(k)%values(1)%text)
                select case (key)
                case ("FORMULATION")
                    call resolve_name(written, formulations, "formulation", at, choice, error)
                    if (.not. allocated(error)) run%settings%formulation = &
                        & choice_code("formulation", lower(choice))
                case ("METHOD")
                    call resolve_name(written, methods, "method", at, choice, error)
                    if (.not. allocated(error)) run%settings%method = &
                        & choice_code("method", lower(choice))
                case ("DRIFT")
                    call resolve_name(written, drifts, "drift control", at, choice, error)
                    if (.not. allocated(error)) run%settings%drift = &
                        & choice_code("drift", lower(choice))
                case ("JACOBIAN")
                    call resolve_name(written, jacobians, "Jacobian", at, choice, error)
                    if (.not. allocated(error)) run%settings%jacobian = &
                        & choice_code("jacobian", lower(choice))
                end select
            end associate
            if (allocated(error)) return
        end do
    end subroutine read_integrator

    pure function lower(text) result(low)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: low
        integer :: i

        low = text
        do i = 1, len(text)
            if (text(i:i) >= "A" .and. text(i:i) <= "Z") low(i:i) = achar(iachar(text(i:i)) + 32)
        end do
    end function lower

end module rollcon_adm_run
