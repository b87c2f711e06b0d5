! SPDX-License-Identifier: MIT
!> What a study records of each case (docs/studies.md): how the run ended, and measures
!> taken over its output rows and from its summary.
module rollcon_study_measures
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_watch, only : watch_measure_type
    use rollcon_simulation, only : run_summary_type, history_type, status_completed, &
        & status_stopped, status_failed, status_inaccurate
    use rollcon_output_layout, only : coord_theta
    use rollcon_watch_columns, only : contact_mode_words, contact_prefixes
    use rollcon_output_layout, only : name_length
    implicit none
    private

    public :: case_result_type, measure_names, measure_units, measure_index, measure_case
    public :: outcome_words, outcome_completed, outcome_theta_limit, outcome_liftoff, &
        & outcome_fall, outcome_rolling_held, outcome_stopped, outcome_inaccurate, &
        & outcome_failed, outcome_refused

    !> How a case ended: completed; stopped by the theta limit, by lift-off, by a fall (a part
    !> whose routine refuses its re-basing, docs/rebasing.md), by the rolling resistance
    !> holding the rim still while it slides, or by another watch's limit (`stopped`); reached
    !> its end or a limit with results beyond what its tolerances promise; failed (the
    !> integrator or the UCOSUB); refused (its scene does not read, e.g. a value out of range).
    !> failed and refused stay last (rollcon_study_rules reserves outcome_failed onwards)
    integer, parameter :: outcome_completed = 1, outcome_theta_limit = 2, outcome_liftoff = 3, &
        & outcome_fall = 4, outcome_rolling_held = 5, outcome_stopped = 6, &
        & outcome_inaccurate = 7, outcome_failed = 8, outcome_refused = 9
    character(len=*), parameter :: outcome_words(9) = [character(len=12) :: "completed", &
        & "theta_limit", "liftoff", "fall", "rolling_held", "stopped", "inaccurate", "failed", &
        & "refused"]

    !> The contact's modes (0 rolling, 1 sliding: rollcon_watch_columns)
    integer, parameter :: modes = size(contact_mode_words)
    !> Measures, in CSV column order, and their units. Over the output rows of the part in
    !> contact: theta's least and largest value, the largest tilt from upright |pi/2 - theta|,
    !> the largest friction coefficient rolling needs, the least normal force and the first
    !> time it is negative; of a contact with Coulomb friction (rollcon_contact_watch): its
    !> mode switches and the time in each mode from the run's summary (t_rolling, t_sliding, a
    !> column per mode), and its mode at the last row (mode_end, the `mode` column's number);
    !> from the summary: the time reached, the energy drift (relative), the largest UCON
    !> residual, the integrator steps; and the case's CPU time. A model with several contacts
    !> (a dataset's CONTACTs, their columns contact<id>_...) has its contact measures over
    !> all of them: mu_max the largest of any, fn_min the least, t_fn_negative the first row
    !> where any is negative, switches their sum, t_rolling ... each contact's time in the mode
    !> averaged over the contacts (so that they add up to t_reached), mode_end the highest
    !> mode number any is in at the last row (0 only when every contact rolls).
    character(len=*), parameter :: measure_names(13 + modes) = [character(len=13) :: &
        & "t_reached", "theta_min", "theta_max", "tilt_max", "mu_max", "fn_min", &
        & "t_fn_negative", "switches", "t_" // contact_mode_words, &
        & "mode_end", "energy_drift", "residual_max", "steps", "cpu_s"]
    character(len=*), parameter :: measure_units(13 + modes) = [character(len=5) :: "s", &
        & "rad", "rad", "rad", "-", "N", "s", "-", spread("s", 1, modes), "-", "-", "", "-", "s"]
    integer, parameter :: i_t_reached = 1, i_theta_min = 2, i_theta_max = 3, i_tilt_max = 4, &
        & i_mu_max = 5, i_fn_min = 6, i_t_fn_negative = 7, i_switches = 8, i_mode_time = 9, &
        & i_mode_end = i_mode_time + modes, i_energy_drift = i_mode_end + 1, &
        & i_residual_max = i_mode_end + 2, i_steps = i_mode_end + 3, i_cpu = i_mode_end + 4

    !> What a study records of one case
    type :: case_result_type
        integer :: outcome = outcome_refused
        !> SUNDIALS' flag of a failed case, else 0
        integer :: flag = 0
        !> The measures, measure_names order
        real(wp) :: values(size(measure_names)) = 0.0_wp
        !> Whether each measure has a value (none for a refused case, no t_fn_negative when
        !> the normal force never turned negative, no contact measures without a contact)
        logical :: known(size(measure_names)) = .false.
        !> The class its rules give it
        character(len=:), allocatable :: class
        !> Why it did not complete ("" when it did)
        character(len=:), allocatable :: message
    end type case_result_type

contains

    !> Index of a measure by name, 0 when there is none of that name.
    pure integer function measure_index(name) result(k)
        character(len=*), intent(in) :: name

        do k = 1, size(measure_names)
            if (measure_names(k) == name) return
        end do
        k = 0
    end function measure_index

    !> The measures of a case that ran, from its summary and output rows.
    subroutine measure_case(summary, history, cpu_seconds, result)
        type(run_summary_type), intent(in) :: summary
        type(history_type), intent(in) :: history
        real(wp), intent(in) :: cpu_seconds
        type(case_result_type), intent(inout) :: result
        real(wp), allocatable :: theta(:), fn(:), t(:)
        character(len=name_length), allocatable :: prefixes(:)
        type(watch_measure_type) :: taken
        real(wp) :: total, mode_end, mu_max, fn_min
        integer :: first, normal, needed, mode, k, c
        logical :: found, have_mode, have_force

        select case (summary%status)
        case (status_completed)
            result%outcome = outcome_completed
        case (status_stopped)
            ! the watch that stopped the run names its limit (rollcon_watch, rollcon_simulation)
            result%outcome = stop_outcome(summary%limit)
        case (status_inaccurate)
            result%outcome = outcome_inaccurate
        case default
            result%outcome = outcome_failed
        end select
        result%flag = summary%solver_flag
        result%message = ""
        if (summary%status /= status_completed .and. allocated(summary%message)) &
            & result%message = summary%message
        call put(i_t_reached, summary%t_reached)
        call put(i_energy_drift, summary%energy_drift)
        call put(i_residual_max, summary%residual_max)
        call put(i_steps, real(summary%steps, wp))
        call put(i_cpu, cpu_seconds)
        ! each contact by its columns' prefix ("" for a model's one contact)
        prefixes = contact_prefixes(history%layout)
        if (size(prefixes) == 0) prefixes = [character(len=name_length) :: ""]
        ! a contact with friction's switches and time in each mode (rollcon_contact_watch):
        ! summed, and averaged, over the contacts
        total = 0.0_wp
        found = .false.
        do c = 1, size(prefixes)
            taken = summary%measure(trim(prefixes(c)) // "switches")
            if (len(taken%name) == 0) cycle
            found = .true.
            total = total + taken%value
        end do
        if (found) call put(i_switches, total)
        do k = 1, modes
            total = 0.0_wp
            found = .false.
            do c = 1, size(prefixes)
                taken = summary%measure(trim(prefixes(c)) // "time_" &
                    & // trim(contact_mode_words(k - 1)))
                if (len(taken%name) == 0) cycle
                found = .true.
                total = total + taken%value
            end do
            if (found) call put(i_mode_time + k - 1, total/real(size(prefixes), wp))
        end do
        if (history%count == 0) return
        associate (layout => history%layout, n => history%count)
            theta = history%rows(layout%part_column(1, coord_theta), :n)
            call put(i_theta_min, minval(theta))
            call put(i_theta_max, maxval(theta))
            call put(i_tilt_max, maxval(abs(pi/2 - theta)))
            ! the contacts' measures, when contacts are watched (rollcon_contact_watch)
            t = history%rows(1, :n)
            first = 0
            have_mode = .false.
            have_force = .false.
            do c = 1, size(prefixes)
                mode = layout%column(trim(prefixes(c)) // "mode")
                if (mode > 0) then
                    if (have_mode) mode_end = max(mode_end, history%rows(mode, n))
                    if (.not. have_mode) mode_end = history%rows(mode, n)
                    have_mode = .true.
                end if
                normal = layout%column(trim(prefixes(c)) // "Fn")
                needed = layout%column(trim(prefixes(c)) // "mu_needed")
                if (normal == 0 .or. needed == 0) cycle
                fn = history%rows(normal, :n)
                if (have_force) then
                    mu_max = max(mu_max, maxval(history%rows(needed, :n)))
                    fn_min = min(fn_min, minval(fn))
                else
                    mu_max = maxval(history%rows(needed, :n))
                    fn_min = minval(fn)
                end if
                have_force = .true.
                k = findloc(fn < 0.0_wp, .true., dim=1)
                if (k > 0 .and. (first == 0 .or. k < first)) first = k
            end do
            if (have_mode) call put(i_mode_end, mode_end)
            if (have_force) then
                call put(i_mu_max, mu_max)
                call put(i_fn_min, fn_min)
            end if
            if (first > 0) call put(i_t_fn_negative, t(first))
        end associate

    contains

        subroutine put(k, value)
            integer, intent(in) :: k
            real(wp), intent(in) :: value

            result%values(k) = value
            result%known(k) = .true.
        end subroutine put

    end subroutine measure_case

    !> The outcome of a run stopped by a watch's limit (status_stopped), from the limit's word
    !> (run_summary_type%limit): theta_limit, liftoff, fall, rolling_held; any other word (or
    !> none) is `stopped`.
    pure integer function stop_outcome(limit) result(outcome)
        character(len=:), allocatable, intent(in) :: limit

        outcome = outcome_stopped
        if (.not. allocated(limit)) return
        select case (limit)
        case ("theta_limit")
            outcome = outcome_theta_limit
        case ("liftoff")
            outcome = outcome_liftoff
        case ("fall")
            outcome = outcome_fall
        case ("rolling_held")
            outcome = outcome_rolling_held
        end select
    end function stop_outcome

end module rollcon_study_measures
