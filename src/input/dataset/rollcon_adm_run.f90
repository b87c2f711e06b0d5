! SPDX-License-Identifier: MIT
!> The SIMULATE statement: SIMULATE/DYNAMIC, END = t, and STEPS = n or DTOUT = dt. The end time
!> and the output step are checked against the ranges of the run keys end_time and
!> output_step (rollcon_run_keys) and obey the scenes' rule output_step <= end_time.
module rollcon_adm_run
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type
    use rollcon_adm_keywords, only : read_reals, argument_key, arg_place, name_index, place
    use rollcon_adm_units, only : units_type
    use rollcon_adm_model, only : adm_run_type
    use rollcon_adm_integrator, only : read_integrator
    use rollcon_run_settings, only : run_settings_type
    use rollcon_keys, only : key_type, find_key
    use rollcon_run_keys, only : bind_run_keys
    use rollcon_key_values, only : in_range, range_text
    implicit none
    private

    public :: read_simulate, read_integrator, simulate_keys

    !> The keywords of SIMULATE
    character(len=*), parameter :: simulate_keys(4) = [character(len=7) :: "DYNAMIC", "END", &
        & "STEPS", "DTOUT"]

contains

    !> SIMULATE/DYNAMIC, END=t, STEPS=n or DTOUT=dt (t, dt in the dataset's time unit). About 90
    !> lines with its internal set_times, which shares the keywords' lines for its messages.
    subroutine read_simulate(path, where, statement, units, run, error)
        !> Dataset file, for messages
        character(len=*), intent(in) :: path
        !> "file:line: SIMULATE"
        character(len=*), intent(in) :: where
        type(adm_statement_type), intent(in) :: statement
        type(units_type), intent(in) :: units
        type(adm_run_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        real(wp) :: given(size(simulate_keys))
        integer :: lines(size(simulate_keys)), k, slot

        run%line = statement%line
        lines = 0
        given = 0.0_wp
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, simulate_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            slot = name_index(key, simulate_keys)
            lines(slot) = statement%arguments(k)%line
            if (key == "DYNAMIC") then
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                    return
                end if
                cycle
            end if
            call read_reals(statement%arguments(k), at, 1, 1, .false., values, error)
            if (allocated(error)) return
            given(slot) = values(1)
        end do
        if (lines(1) == 0) then
            call fatal_error(error, where // ": only SIMULATE/DYNAMIC is supported (a dynamic " &
                & // "analysis); write SIMULATE/DYNAMIC, END=..., STEPS=...", stat_input)
        else if (lines(2) == 0) then
            call fatal_error(error, where // ": END=t (the end time) is missing", stat_input)
        else if ((lines(3) > 0) .eqv. (lines(4) > 0)) then
            call fatal_error(error, where // ": give one of STEPS=n and DTOUT=dt", stat_input)
        end if
        if (allocated(error)) return
        call set_times(given(2)*units%time, given(3), given(4)*units%time, error)

    contains

        !> End time and output step [s] within the ranges of &run end_time and output_step.
        subroutine set_times(end_time, steps, output_step, error)
            real(wp), intent(in) :: end_time, steps, output_step
            type(error_type), allocatable, intent(out) :: error
            type(run_settings_type), target :: scratch
            type(key_type), allocatable :: keys(:)
            character(len=:), allocatable :: head

            keys = bind_run_keys(scratch)
            head = where(index(where, ": ", back=.true.):)
            associate (end_key => keys(find_key(keys, "run", "end_time")), &
                    & step_key => keys(find_key(keys, "run", "output_step")))
                if (.not. in_range(end_key, end_time)) then
                    call fatal_error(error, place(path, lines(2)) // head // " END must be " &
                        & // range_text(end_key) // " (as &run end_time), got " &
                        & // to_text(end_time) // " s", stat_input)
                    return
                end if
                run%settings%end_time = end_time
                if (lines(3) > 0) then
                    if (.not. (steps >= 1.0_wp .and. steps == aint(steps))) then
                        call fatal_error(error, place(path, lines(3)) // head // " STEPS must " &
                            & // "be a whole number of output steps >= 1, got " &
                            & // to_text(steps), stat_input)
                        return
                    end if
                    run%settings%output_step = end_time/steps
                else
                    run%settings%output_step = output_step
                end if
                if (.not. in_range(step_key, run%settings%output_step)) then
                    call fatal_error(error, place(path, maxval(lines(3:4))) // head // " " &
                        & // trim(merge("STEPS", "DTOUT", lines(3) > 0)) // " gives an output " &
                        & // "step of " // to_text(run%settings%output_step) // " s; it must be " &
                        & // range_text(step_key) // " (as &run output_step)", stat_input)
                else if (run%settings%output_step > end_time) then
                    call fatal_error(error, place(path, lines(4)) // head // " DTOUT must be " &
                        & // "<= END = " // to_text(end_time) // " s (as &run output_step <= " &
                        & // "end_time), got " // to_text(run%settings%output_step) // " s", &
                        & stat_input)
                end if
            end associate
        end subroutine set_times

    end subroutine read_simulate

end module rollcon_adm_run
