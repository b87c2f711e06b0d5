! SPDX-License-Identifier: MIT
!> The run of a dataset: its SIMULATE statement (SIMULATE/DYNAMIC, END = t or DURATION = t,
!> and STEPS = n or DTOUT = dt), the SIMULATE commands of an ADAMS command file, or the
!> options of `rollcon run` that replace them; and the run's times from them. Each SIMULATE
!> goes on from where the one before ended, as ADAMS continues one run: the output times are
!> each segment's own. The end time and the output step are checked against the ranges of the
!> run keys end_time and output_step (rollcon_run_keys) and obey the scenes' rule
!> output_step <= end_time, for each segment.
module rollcon_adm_run
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type
    use rollcon_adm_keywords, only : read_reals, argument_key, arg_place, name_index, place, &
        & resolve_keyword
    use rollcon_adm_units, only : units_type
    use rollcon_adm_model, only : adm_run_type, adm_segment_type
    use rollcon_adm_integrator, only : read_integrator
    use rollcon_run_settings, only : run_settings_type, analysis_dynamic, analysis_kinematic, &
        & analysis_static
    use rollcon_keys, only : key_type, find_key
    use rollcon_run_keys, only : bind_run_keys
    use rollcon_key_values, only : in_range, range_text
    implicit none
    private

    public :: read_simulate, read_integrator, simulate_keys, read_segment, set_run_times
    public :: run_times_type, apply_run_times, no_simulate_message

    !> The keywords of SIMULATE: the end, the output steps, and the analysis (DYNAMIC,
    !> KINEMATIC, STATIC; ADAMS's others refused with the reason)
    character(len=*), parameter :: simulate_keys(7) = [character(len=9) :: "DYNAMIC", "END", &
        & "STEPS", "DTOUT", "DURATION", "STATIC", "KINEMATIC"]
    !> ADAMS's other analyses, refused with the reason
    character(len=*), parameter :: other_analyses(2) = [character(len=18) :: "TRANSIENT", &
        & "INITIAL_CONDITIONS"]
    !> An output time within this many output steps of a segment's end is at its end (as the
    !> run's planned rows count them: rollcon_output_rows)
    real(wp), parameter :: grid_tolerance = 1.0e-9_wp

    !> The run's times given apart from the dataset (`rollcon run --end T --steps N`, or
    !> --dtout DT), in the dataset's time unit: they replace its SIMULATE (and a command
    !> file's), keeping what they do not give
    type :: run_times_type
        logical :: end_given = .false., steps_given = .false., dtout_given = .false.
        real(wp) :: end_time = 0.0_wp, steps = 0.0_wp, dtout = 0.0_wp
        !> The options as the user wrote them, for messages ("--end 5 --steps 500")
        character(len=:), allocatable :: written
    end type run_times_type

contains

    !> The dataset's SIMULATE statement: its one segment, and the run's times from it.
    subroutine read_simulate(path, where, statement, units, run, error)
        !> Dataset file, for messages
        character(len=*), intent(in) :: path
        !> "file:line: SIMULATE"
        character(len=*), intent(in) :: where
        type(adm_statement_type), intent(in) :: statement
        type(units_type), intent(in) :: units
        type(adm_run_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error
        type(adm_segment_type) :: segment

        call read_segment(path, where, statement, units, segment, error)
        if (allocated(error)) return
        run%line = statement%line
        if (allocated(run%segments)) deallocate(run%segments)
        allocate(run%segments(1))
        run%segments(1) = segment
        call set_run_times(run, error)
    end subroutine read_simulate

    !> One SIMULATE/DYNAMIC or SIMULATE/KINEMATIC, END=t or DURATION=t, STEPS=n or DTOUT=dt
    !> (t, dt in the dataset's time unit, converted to s), or SIMULATE/STATIC (no times: the
    !> equilibrium where the run is), as a statement of a dataset or a command of a command
    !> file.
    subroutine read_segment(path, where, statement, units, segment, error)
        !> The file, for messages
        character(len=*), intent(in) :: path
        !> "file:line: SIMULATE"
        character(len=*), intent(in) :: where
        type(adm_statement_type), intent(in) :: statement
        type(units_type), intent(in) :: units
        type(adm_segment_type), intent(out) :: segment
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        real(wp) :: given(size(simulate_keys))
        integer :: lines(size(simulate_keys)), k, slot
        type(error_type), allocatable :: refused

        lines = 0
        given = 0.0_wp
        do k = 1, size(statement%arguments)
            call resolve_keyword(statement%arguments(k)%keyword, other_analyses, "SIMULATE", &
                & "analysis", where, key, refused)
            if (.not. allocated(refused)) then
                call fatal_error(error, arg_place(path, where, statement%arguments(k)) // " " &
                    & // key // ": rollcon runs SIMULATE/DYNAMIC, /KINEMATIC and /STATIC; " &
                    & // "a dynamic run starts from the start its initial-conditions analysis " &
                    & // "makes consistent (docs/initial-conditions.md)", stat_input)
                return
            end if
            deallocate(refused)
            call argument_key(path, where, statement, k, simulate_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            slot = name_index(key, simulate_keys)
            lines(slot) = statement%arguments(k)%line
            select case (key)
            case ("DYNAMIC", "STATIC", "KINEMATIC")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                    return
                end if
                cycle
            end select
            call read_reals(statement%arguments(k), at, 1, 1, .false., values, error)
            if (allocated(error)) return
            given(slot) = values(1)
        end do
        if (count(lines([1, 6, 7]) > 0) /= 1) then
            call fatal_error(error, where // ": give one analysis: SIMULATE/DYNAMIC (or " &
                & // "/KINEMATIC), END=..., STEPS=..., or SIMULATE/STATIC", stat_input)
            return
        end if
        if (lines(6) > 0) then
            segment%analysis = analysis_static
            if (any(lines(2:5) > 0)) call fatal_error(error, where // ": SIMULATE/STATIC is " &
                & // "the static equilibrium where the run is and takes no END, DURATION, " &
                & // "STEPS or DTOUT (ADAMS's quasi-static analysis is not run)", stat_input)
            segment%end_at = place(path, lines(6)) // where(index(where, ": ", back=.true.):) &
                & // " STATIC"
            segment%output_at = segment%end_at
            return
        end if
        if (lines(7) > 0) segment%analysis = analysis_kinematic
        if (lines(2) == 0 .and. lines(5) == 0) then
            call fatal_error(error, where // ": END=t (the end time) is missing (or " &
                & // "DURATION=t, from where the run is)", stat_input)
        else if (lines(2) > 0 .and. lines(5) > 0) then
            call fatal_error(error, where // ": give one of END=t (the end time) and " &
                & // "DURATION=t (from where the run is), not both", stat_input)
        else if ((lines(3) > 0) .eqv. (lines(4) > 0)) then
            call fatal_error(error, where // ": give one of STEPS=n and DTOUT=dt", stat_input)
        end if
        if (allocated(error)) return
        segment%by_duration = lines(5) > 0
        segment%end_time = given(2)*units%time
        segment%duration = given(5)*units%time
        segment%by_steps = lines(3) > 0
        segment%steps = given(3)
        segment%dtout = given(4)*units%time
        segment%end_at = place(path, maxval(lines([2, 5]))) // where(index(where, ": ", &
            & back=.true.):) // " " // trim(merge("DURATION", "END     ", segment%by_duration))
        segment%output_at = place(path, maxval(lines(3:4))) // where(index(where, ": ", &
            & back=.true.):) // " " // trim(merge("STEPS", "DTOUT", segment%by_steps))
    end subroutine read_segment

    !> The run's end time and output step from its segments (run%segments, at least one),
    !> each checked against the ranges of &run end_time and output_step: one segment gives
    !> end_time and output_step alone; several give the output times too, each segment's own,
    !> continuing the run. Where a segment has the step of the one before and that one ended
    !> on its grid, its times go on counting from the same origin, so that the rows are those
    !> of one run with the combined end, bit for bit.
    subroutine set_run_times(run, error)
        type(adm_run_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error
        type(adm_segment_type), allocatable :: timed(:)
        integer :: s, statics, kinematics

        statics = 0
        do s = 1, size(run%segments)
            if (run%segments(s)%analysis /= analysis_static) exit
            statics = s
        end do
        run%settings%static_first = statics > 0
        if (statics == size(run%segments)) then
            run%settings%analysis = analysis_static
            run%settings%static_first = .false.
            return
        end if
        kinematics = count(run%segments(statics + 1:)%analysis == analysis_kinematic)
        do s = statics + 1, size(run%segments)
            if (run%segments(s)%analysis == analysis_static) then
                call fatal_error(error, run%segments(s)%end_at // ": a static equilibrium " &
                    & // "after a dynamic or kinematic SIMULATE; rollcon finds it at the start " &
                    & // "only (SIMULATE/STATIC before the first SIMULATE/DYNAMIC)", stat_input)
                return
            end if
        end do
        if (kinematics > 0 .and. kinematics < size(run%segments) - statics) then
            call fatal_error(error, run%segments(statics + 1)%end_at // ": SIMULATE/KINEMATIC " &
                & // "and SIMULATE/DYNAMIC in one run; rollcon runs one of them (a model with " &
                & // "no degree of freedom: KINEMATIC)", stat_input)
            return
        end if
        if (kinematics > 0 .and. statics > 0) then
            call fatal_error(error, run%segments(1)%end_at // ": SIMULATE/STATIC before " &
                & // "SIMULATE/KINEMATIC; a kinematic run's positions are its constraints' " &
                & // "alone: leave the SIMULATE/STATIC out", stat_input)
            return
        end if
        run%settings%analysis = merge(analysis_kinematic, analysis_dynamic, kinematics > 0)
        timed = run%segments(statics + 1:)
        call segment_times(timed, run%settings, error)
    end subroutine set_run_times

    !> The run's times from its timed segments (see set_run_times).
    subroutine segment_times(segments, settings, error)
        type(adm_segment_type), intent(in) :: segments(:)
        type(run_settings_type), intent(inout) :: settings
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type), target :: scratch
        type(key_type), allocatable :: keys(:)
        real(wp), allocatable :: times(:)
        real(wp) :: start, finish, step, anchor, previous_step, span
        integer(int64) :: counted, n, j
        integer :: s, total
        logical :: aligned

        keys = bind_run_keys(scratch)
        start = 0.0_wp
        anchor = 0.0_wp
        counted = 0
        previous_step = -1.0_wp
        aligned = .true.
        allocate(times(0))
        total = 0
        do s = 1, size(segments)
            associate (segment => segments(s), end_key => keys(find_key(keys, "run", &
                    & "end_time")), step_key => keys(find_key(keys, "run", "output_step")))
                if (segment%by_duration) then
                    finish = start + segment%duration
                else
                    finish = segment%end_time
                end if
                if (.not. in_range(end_key, finish)) then
                    call fatal_error(error, segment%end_at // " must be " &
                        & // range_text(end_key) // " (as &run end_time), got " &
                        & // to_text(finish) // " s" // trim(merge(" (the end it gives)", &
                        & "                   ", segment%by_duration)), stat_input)
                    return
                end if
                if (s > 1 .and. .not. finish > start) then
                    call fatal_error(error, segment%end_at // " gives an end of " &
                        & // to_text(finish) // " s, not after the end of the SIMULATE before " &
                        & // "it (" // to_text(start) // " s): each SIMULATE goes on from " &
                        & // "where the one before ended", stat_input)
                    return
                end if
                if (segment%by_steps) then
                    if (.not. (segment%steps >= 1.0_wp .and. segment%steps == &
                        & aint(segment%steps) .and. segment%steps < 1.0e15_wp)) then
                        call fatal_error(error, segment%output_at // " must be a whole " &
                            & // "number of output steps >= 1, got " &
                            & // to_text(segment%steps), stat_input)
                        return
                    end if
                    step = (finish - start)/segment%steps
                else
                    step = segment%dtout
                end if
                if (.not. in_range(step_key, step)) then
                    call fatal_error(error, segment%output_at // " gives an output step of " &
                        & // to_text(step) // " s; it must be " // range_text(step_key) &
                        & // " (as &run output_step)", stat_input)
                    return
                else if (step > finish - start) then
                    call fatal_error(error, segment%output_at // " must be <= " &
                        & // trim(merge("END     ", "its span", s == 1)) // " = " &
                        & // to_text(finish - start) // " s (as &run output_step <= " &
                        & // "end_time), got " // to_text(step) // " s", stat_input)
                    return
                end if
                if (size(segments) == 1) then
                    settings%end_time = finish
                    settings%output_step = step
                    if (allocated(settings%output_times)) &
                        & deallocate(settings%output_times)
                    return
                end if
                ! a new origin unless the step and the grid go on
                if (.not. (step == previous_step .and. aligned)) then
                    anchor = start
                    counted = 0
                end if
                span = (finish - anchor)/step
                aligned = abs(span - anint(span)) <= grid_tolerance*max(1.0_wp, abs(span))
                if (segment%by_steps) then
                    n = nint(segment%steps, int64)
                else
                    n = max(1_int64, int(ceiling_real(span - grid_tolerance), int64) - counted)
                end if
                if (real(total, wp) + real(n, wp) > real(huge(total), wp)/2.0_wp) then
                    call fatal_error(error, segment%output_at // ": the SIMULATE commands ask " &
                        & // "for more than " // to_text(huge(total)/2) // " output rows", &
                        & stat_input)
                    return
                end if
                times = [times, (anchor + real(counted + j, wp)*step, j = 1, n)]
                total = total + int(n)
                ! the segment's last time is its end, as one run's last is at its end time
                if (.not. aligned .or. s == size(segments)) times(total) = min(times(total), &
                    & finish)
                if (.not. aligned) times(total) = finish
                counted = counted + n
                previous_step = step
                start = finish
                if (s == 1) settings%output_step = step
            end associate
        end do
        settings%end_time = start
        settings%output_times = times
    end subroutine segment_times

    !> Replace the run's segments by the options of `rollcon run` (times): END (--end), and
    !> STEPS (--steps) or DTOUT (--dtout), each kept from the last segment read when not
    !> given; with no segment read, both must be given. The run's times follow.
    subroutine apply_run_times(file, times, units, run, error)
        !> The dataset (or command file), for messages
        character(len=*), intent(in) :: file
        type(run_times_type), intent(in) :: times
        type(units_type), intent(in) :: units
        type(adm_run_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error
        type(adm_segment_type) :: segment
        type(adm_segment_type), allocatable :: segments(:)
        integer :: statics, k
        logical :: have

        if (.not. (times%end_given .or. times%steps_given .or. times%dtout_given)) return
        if (times%steps_given .and. times%dtout_given) then
            call fatal_error(error, "rollcon run: give one of --steps N and --dtout DT", &
                & stat_input)
            return
        end if
        have = .false.
        if (allocated(run%segments)) have = size(run%segments) > 0
        if (.not. have .and. .not. (times%end_given .and. (times%steps_given .or. &
            & times%dtout_given))) then
            call fatal_error(error, file // ": no SIMULATE to take the rest from: with " &
                & // times%written // ", give --end T and --steps N (or --dtout DT) both", &
                & stat_input)
            return
        end if
        if (have) then
            segment = run%segments(size(run%segments))
            if (segment%by_duration) then
                ! the last segment's end, from the start of the run
                segment%by_duration = .false.
                segment%end_time = final_end(run)
            end if
            ! its way of counting outputs, over the whole run now
            if (segment%by_steps .and. size(run%segments) > 1) segment%steps = &
                & real(total_outputs(run), wp)
        end if
        if (times%end_given) then
            segment%end_time = times%end_time*units%time
            segment%end_at = file // ": rollcon run --end"
        end if
        if (times%steps_given) then
            segment%by_steps = .true.
            segment%steps = times%steps
            segment%output_at = file // ": rollcon run --steps"
        else if (times%dtout_given) then
            segment%by_steps = .false.
            segment%dtout = times%dtout*units%time
            segment%output_at = file // ": rollcon run --dtout"
        end if
        if (segment%analysis == analysis_static) segment%analysis = analysis_dynamic
        ! the static equilibrium at the start, when one is asked, still comes first
        statics = 0
        if (have) statics = count_leading_statics(run)
        allocate(segments(statics + 1))
        do k = 1, statics
            segments(k) = run%segments(k)
        end do
        segments(statics + 1) = segment
        call move_alloc(segments, run%segments)
        call set_run_times(run, error)
    end subroutine apply_run_times

    !> The number of SIMULATE/STATIC segments before the first timed one.
    pure integer function count_leading_statics(run) result(statics)
        type(adm_run_type), intent(in) :: run
        integer :: s

        statics = 0
        do s = 1, size(run%segments)
            if (run%segments(s)%analysis /= analysis_static) exit
            statics = s
        end do
    end function count_leading_statics

    !> The end of the run's last segment [s].
    pure real(wp) function final_end(run) result(finish)
        type(adm_run_type), intent(in) :: run
        integer :: s

        finish = 0.0_wp
        do s = 1, size(run%segments)
            if (run%segments(s)%analysis == analysis_static) cycle
            if (run%segments(s)%by_duration) then
                finish = finish + run%segments(s)%duration
            else
                finish = run%segments(s)%end_time
            end if
        end do
    end function final_end

    !> The number of output times after the start of the run's times as set.
    pure integer function total_outputs(run) result(n)
        type(adm_run_type), intent(in) :: run

        if (allocated(run%settings%output_times)) then
            n = size(run%settings%output_times)
        else
            n = max(1, nint(run%settings%end_time/run%settings%output_step))
        end if
    end function total_outputs

    !> The refusal of a dataset with no SIMULATE statement and no run given apart from it:
    !> both ways of giving one.
    pure function no_simulate_message(file) result(text)
        character(len=*), intent(in) :: file
        character(len=:), allocatable :: text

        text = file // ": no SIMULATE statement, and no run given apart from the dataset: " &
            & // "run it from an ADAMS command file (rollcon run MODEL.acf: its first line " &
            & // "names the dataset, its second the output name, then SIMULATE/DYNAMIC, " &
            & // "END=t, STEPS=n and STOP), or give the run on the command line (rollcon run " &
            & // file // " --end T --steps N), or add SIMULATE/DYNAMIC, END=t, STEPS=n to the " &
            & // "dataset"
    end function no_simulate_message

    !> ceiling of a real of any size, as a real (no integer overflow).
    elemental function ceiling_real(x) result(c)
        real(wp), intent(in) :: x
        real(wp) :: c

        c = aint(x)
        if (c < x) c = c + 1.0_wp
    end function ceiling_real

end module rollcon_adm_run
