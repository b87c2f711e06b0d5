! SPDX-License-Identifier: MIT
!> Runs a problem from t0 to the end time in the formulation its settings choose (made once,
!> where the integrator starts: rollcon_formulation_choice) with the integrator that takes it
!> (CVODE or IDA, through rollcon_integrator): output rows, the watches' events (stop, or
!> re-base a part), the summary. The driver knows parts, UCONs, forces and watches; what a
!> model watches is the watches'; the state's layout is the formulation's.
module rollcon_simulation
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_text, only : to_text
    use rollcon_force, only : force_breakpoints, force_corners, forces_idle_after
    use rollcon_user_forces, only : take_user_force_error
    use rollcon_model, only : model_type, served_by_model_ucosub
    use rollcon_integrator, only : integrator_type, integrator_statistics_type
    use rollcon_integrator_choice, only : start_integrator
    use rollcon_dynamic_system, only : dynamic_system_type
    use rollcon_problem, only : problem_type
    use rollcon_formulation_choice, only : new_formulation
    use rollcon_watch, only : watch_event_type, watch_measure_type, action_rebase, &
        & action_stop, action_restart, action_corner
    use rollcon_switch_watch, only : switch_watch_type, has_state_switches
    use rollcon_csv_writer, only : csv_writer_type
    use rollcon_row_sink, only : row_sink_type
    use rollcon_progress, only : progress_type
    use rollcon_grind_watch, only : grind_watch_type
    use rollcon_run_summary, only : run_summary_type, status_completed, status_stopped, &
        & status_failed, status_inaccurate, judge_drift
    use rollcon_output_layout, only : output_layout_type
    use rollcon_output_rows, only : run_options_type, default_max_csv_bytes, planned_rows, &
        & output_layout, output_row, output_time
    use rollcon_history, only : history_type
    use rollcon_rebase_step, only : rebase_part, restart_state
    use rollcon_rebasing, only : turns_from_own
    implicit none
    private

    public :: run_options_type, run_summary_type, history_type, simulate
    !> How a run ended and what it did (rollcon_run_summary), for the callers of simulate
    public :: status_completed, status_stopped, status_failed, status_inaccurate
    !> The output rows' limit and layout (rollcon_output_rows), for the callers of simulate
    public :: default_max_csv_bytes, output_layout, start_summary, deliver_row

    !> A run in progress: what the steps of simulate share
    type :: simulation_type
        type(problem_type), pointer :: problem => null()
        !> The problem's formulation (new_formulation), the system the integrator integrates
        class(dynamic_system_type), allocatable :: system
        class(integrator_type), allocatable :: integrator
        type(run_options_type) :: options
        type(output_layout_type) :: layout
        type(csv_writer_type) :: csv
        !> The integrator's state and its derivative (IDA), the time
        real(wp), allocatable :: y(:), yp(:)
        !> The coordinates and rates at y (system%unpack_state)
        real(wp), allocatable :: q(:), u(:)
        real(wp) :: t = 0.0_wp
        !> Force kinks the integrator must not step over, and among them the corners, where it
        !> also starts again (corner_times)
        real(wp), allocatable :: breaks(:), corners(:)
        !> Where the integrator last started again at a corner [s]
        real(wp) :: t_corner = -huge(1.0_wp)
        !> Energy drift is measured from the first row at or after this time [s]
        real(wp) :: t_reference = 0.0_wp
        logical :: have_reference = .false.
        !> Over the rows from the reference on (the judged rows): their count, the largest
        !> |E - E_reference| [J], the largest kinetic energy and the potential energy's range
        !> [J] (|E + W - E_reference| with a rim's dissipated work W), the sum of what one step's
        !> tolerance allows the energy [J], the explicit work of
        !> the constraint forces [J] and the power and time of the last row [W, s]
        integer :: judged_rows = 0
        real(wp) :: energy_change = 0.0_wp, kinetic_max = 0.0_wp
        real(wp) :: potential_min = huge(1.0_wp), potential_max = -huge(1.0_wp)
        real(wp) :: step_energy_sum = 0.0_wp, constraint_work = 0.0_wp
        real(wp) :: last_power = 0.0_wp, last_time = 0.0_wp
        !> The dissipated power (problem%dissipated_power: a sliding contact's friction, a rim's
        !> rolling resistance and air) over the judged rows: its work [J] (integrated with the
        !> state by the integrator, or by the trapezoidal rule over the rows from one that does
        !> not) plus the impacts' losses, the rows' rule's estimated error [J], the last two
        !> rows' powers [W], and the parts of the work the friction and the impacts did [J]
        real(wp) :: dissipated_work = 0.0_wp, dissipation_uncertainty = 0.0_wp
        real(wp) :: last_dissipation(2) = 0.0_wp, last_friction = 0.0_wp
        real(wp) :: friction_work = 0.0_wp, impact_work = 0.0_wp
        !> The time of the quadrature's last point (a row or a switch) and of the one before [s]
        real(wp) :: dissipation_time = 0.0_wp, before_last_time = 0.0_wp
        !> The energy a contact's impacts had taken at the last judged row [J]
        real(wp) :: impact_loss = 0.0_wp
        !> The work the drives of moving planes (turntables) had done in the impacts at the last
        !> judged row, and over the judged rows [J], signed (rollcon_equations'
        !> impact_drive_works): the energy judged is E + W less it
        real(wp) :: impact_drive = 0.0_wp, drive_work = 0.0_wp
        !> The integrator's dissipated works (integrator_type work) at the first judged row [J]
        real(wp), allocatable :: work_reference(:)
        !> Counters of the integrator's segments before its last restart
        type(integrator_statistics_type) :: earlier
        !> Re-basings of each part (model order)
        integer, allocatable :: bases(:)
        real(wp) :: cpu_start = 0.0_wp
        !> Progress lines on stderr (options%progress)
        type(progress_type) :: progress
        !> Told between the integrator's chunks of steps: progress, grinding steps
        type(grind_watch_type) :: chunk_watch
    contains
        procedure :: begin
        procedure :: start
        procedure :: next_stop
        procedure :: record
        procedure :: handle_events
        procedure :: split_dissipation
        procedure :: rebase
        procedure :: repartition
        procedure :: restart_at_corner
        procedure :: rebase_at_start
        procedure :: count_rebasing
        procedure :: finish
        procedure :: name_runaway
    end type simulation_type

contains

    !> Integrate problem from (q0, u0), writing a row per output time to the CSV of options,
    !> to history and to sink (each when given). The loop over output times with its stops,
    !> events and failures is here; start, rows, events and the end are simulation_type's.
    subroutine simulate(problem, q0, u0, options, summary, error, history, sink)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(out) :: summary
        !> Set on a solver or output failure; summary still describes the run so far
        type(error_type), allocatable, intent(out) :: error
        !> When present, every output row is also kept here
        type(history_type), intent(inout), optional :: history
        !> When present, every output row is also handed to it
        ! target: the run's chunk watch tells it of the time between rows
        class(row_sink_type), intent(inout), optional, target :: sink
        ! target: the integrator keeps pointers to the run's system
        type(simulation_type), target :: run
        real(wp) :: t_out
        integer :: root
        integer(int64) :: k_output, n_output
        logical :: stop_here

        call run%begin(problem, q0, u0, options, summary, n_output, error, history, sink)
        if (allocated(error)) then
            call run%finish(summary, error)
            return
        end if
        run%chunk_watch%progress => run%progress
        if (present(sink)) run%chunk_watch%sink => sink
        k_output = 1
        do while (k_output <= n_output)
            t_out = output_time(options, k_output)
            ! an output time closer after a restart than the time's round-off (an output at a
            ! corner's time written another way): the integrators refuse to start towards it,
            ! and the state there is the same
            if (t_out - run%t <= 4.0_wp*epsilon(1.0_wp)*(abs(run%t) + abs(t_out))) then
                run%t = t_out
                root = 0
            else
                ! whichever integrator the last start made tells the watch
                run%integrator%watch => run%chunk_watch
                call run%integrator%advance(t_out, run%next_stop(run%t), run%t, run%y, &
                    & run%yp, root, error)
            end if
            if (allocated(error)) then
                ! a load or the motion that ran away is why, whatever the integrator's words
                call run%name_runaway(error)
                summary%status = status_failed
                summary%message = error%message
                summary%solver_flag = run%integrator%failed_flag
                ! where the integrator got to, past the last row
                summary%t_reached = max(summary%t_reached, run%t)
                exit
            end if
            if (root /= 0) then
                call run%handle_events(summary, stop_here, error, history, sink)
                if (stop_here .or. allocated(error)) exit
            else if (any(run%corners == run%t)) then
                ! at an input's corner (a stop time): start again with no history
                call run%restart_at_corner(summary, error)
                if (allocated(error)) then
                    summary%status = status_failed
                    summary%message = error%message
                    exit
                end if
            end if
            ! the formulation's choices worn (in independent speeds, its partition): a restart
            ! that makes them again
            if (run%system%worn(run%t, run%y)) then
                call run%repartition(error)
                if (allocated(error)) then
                    summary%status = status_failed
                    summary%message = error%message
                    exit
                end if
            end if
            if (run%t < t_out) cycle
            call run%record(summary, error, history, sink)
            if (allocated(error)) exit
            k_output = k_output + 1
            call run%progress%report(run%t)
        end do
        call run%finish(summary, error)
        if (.not. allocated(error)) call judge_drift(summary, problem%settings)
    end subroutine simulate

    !> Everything before the first step: the watches prepared, the layout, what the summary
    !> measures, the planned rows (refused beyond the size limit), the CSV opened, parts
    !> re-based at the start when they must be, a consistent start (accelerations and
    !> multipliers from the saddle-point system), the integrator set up and the first row.
    subroutine begin(self, problem, q0, u0, options, summary, n_output, error, history, sink)
        class(simulation_type), intent(inout), target :: self
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(inout) :: summary
        integer(int64), intent(out) :: n_output
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        real(wp), allocatable :: q(:), u(:)
        character(len=:), allocatable :: refusal
        type(watch_event_type) :: event
        logical :: fell
        integer :: k

        self%problem => problem
        self%options = options
        n_output = 0
        call add_switch_watch(problem)
        call problem%prepare(error)
        if (allocated(error)) return
        self%layout = output_layout(problem)
        call start_summary(problem, self%layout, summary)
        if (present(history)) history%layout = self%layout
        allocate(self%bases(size(problem%model%parts)), source=0)
        self%breaks = force_breakpoints(problem%model%forces)
        self%t_reference = options%t0
        if (size(self%breaks) > 0) self%t_reference = maxval(self%breaks)
        ! forces acting after the reference do work: no drift to judge (constraints that do
        ! work are found from the rows, record, and judged by judge_drift)
        summary%energy_conserved = forces_idle_after(problem%model%forces, self%t_reference, &
            & options%end_time)
        self%breaks = pack(self%breaks, self%breaks > options%t0 .and. self%breaks &
            & < options%end_time)
        self%corners = corner_times(problem%model)
        self%corners = pack(self%corners, self%corners > options%t0 .and. self%corners &
            & < options%end_time)
        self%breaks = [self%breaks, pack(self%corners, [(.not. any(self%breaks &
            & == self%corners(k)), k = 1, size(self%corners))])]
        call planned_rows(options, self%layout%columns(), n_output, error)
        if (allocated(error)) return
        if (allocated(options%csv_path)) then
            call self%csv%open(options%csv_path, self%layout%header(), error)
            if (allocated(error)) return
        end if
        if (present(sink)) then
            call sink%open(self%layout, error)
            if (allocated(error)) return
        end if
        call cpu_time(self%cpu_start)
        q = q0
        u = u0
        call self%rebase_at_start(q, u, refusal, fell, error)
        if (allocated(error)) return
        ! the whole turns of the expressions' angles counted from here (rollcon_measures)
        call problem%model%count_turns(q, u, restart=.true.)
        ! the modes the watches set at the start (rolling resistance's sign)
        do k = 1, size(problem%watches)
            call problem%watches(k)%watch%start_problem(problem%eq, options%t0, q, u, error)
            if (allocated(error)) return
        end do
        call self%start(q, u, error)
        if (allocated(error)) return
        call self%record(summary, error, history, sink)
        if (allocated(error)) return
        ! a watch's stop at the start: the first row is the run
        do k = 1, size(problem%watches)
            event = problem%watches(k)%watch%stop_request()
            if (event%action /= action_stop) cycle
            summary%status = status_stopped
            summary%message = event%message
            summary%limit = event%limit
            n_output = 0
            return
        end do
        if (.not. allocated(refusal)) return
        ! a re-basing refused: the run cannot go on as asked: a fall ends it at its first row,
        ! anything else is a failure (docs/rebasing.md)
        if (fell) then
            summary%status = status_stopped
            summary%message = refusal
            summary%limit = "fall"
            n_output = 0
        else
            call fatal_error(error, refusal, stat_ucon)
        end if
    end subroutine begin

    !> The consistent start at (options%t0, q, u), the formulation the settings choose (the
    !> one choice of a run) packed there and its integrator set up on it.
    subroutine start(self, q, u, error)
        class(simulation_type), intent(inout), target :: self
        real(wp), intent(in) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        associate (problem => self%problem)
            ! the rows set aside as redundant, chosen here (rollcon_redundancy)
            call problem%choose_rows(self%options%t0, q, u, error)
            if (allocated(error)) return
            call problem%accelerations(self%options%t0, q, u, error)
            if (allocated(error)) return
            self%t = self%options%t0
            call self%progress%start(self%options%progress, self%options%t0, &
                & self%options%end_time)
            call new_formulation(problem, self%system)
            allocate(self%y(self%system%state_size()), self%yp(self%system%state_size()))
            allocate(self%q(problem%eq%n), self%u(problem%eq%n))
            call self%system%pack_state(q, u, self%y, self%yp)
            call start_integrator(self%system, problem%settings, self%t, self%y, self%yp, &
                & self%next_stop(self%t), self%integrator, error)
        end associate
    end subroutine start

    !> The next time the integrator must not step past: a force kink or the end.
    pure function next_stop(self, time) result(stop_time)
        class(simulation_type), intent(in) :: self
        real(wp), intent(in) :: time
        real(wp) :: stop_time

        stop_time = self%options%end_time
        if (any(self%breaks > time)) stop_time = minval(self%breaks, mask=self%breaks > time)
    end function next_stop

    !> Write the output row at the current state and update the summary's measures.
    subroutine record(self, summary, error, history, sink)
        class(simulation_type), intent(inout) :: self
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        real(wp) :: energy, potential, power, dissipation, friction, rim, impacts, estimate, &
            & drive
        real(wp), allocatable :: row(:)
        logical :: integrated

        call self%system%unpack_state(self%t, self%y, self%q, self%u, error)
        if (allocated(error)) return
        integrated = allocated(self%integrator%work)
        associate (problem => self%problem, q => self%q, u => self%u, time => self%t)
            call problem%accelerations(time, q, u, error)
            if (allocated(error)) return
            ! the rim's laws' work to this row, as the integrator integrated it, for its columns
            ! (the works are those of problem%powers_at: friction, rolling resistance, air)
            problem%eq%dissipation%works_integrated = integrated
            if (integrated) then
                problem%eq%dissipation%rolling_work = self%integrator%work(2)
                problem%eq%dissipation%air_work = self%integrator%work(3)
            end if
            row = output_row(problem, self%layout, time, q, u)
            ! a user routine a watch called (a REQSUB) that failed: its error, naming it
            call take_user_force_error(error)
            if (allocated(error)) return
            ! a value that is not finite is never written as a result
            if (.not. all(ieee_is_finite(row))) then
                call problem%nonfinite_state(time, q, u, error)
                error%message = "the row at t = " // to_text(time) // " s is not finite (" &
                    & // trim(self%layout%column_name(findloc(ieee_is_finite(row), .false., &
                    & dim=1))) // " first): " // error%message
                return
            end if
            energy = row(self%layout%energy_column())
            ! Energy is conserved once the last force pulse is over: measure drift from the
            ! first row at or after that time, with what the judge needs (rollcon_drift)
            if (time >= self%t_reference) then
                if (.not. self%have_reference) summary%energy_reference = energy
                self%have_reference = .true.
                potential = problem%eq%potential_energy(q)
                power = problem%constraint_power(u)
                ! the dissipated power (friction, rolling resistance, air): its work W since the
                ! first judged row, as the integrator integrated it with the state; or, from an
                ! integrator that does not, by the trapezoidal rule over the rows, whose error
                ! over a row's step h is h^3 |P''| / 12, estimated as
                ! h |P_i - 2 P_(i-1) + P_(i-2)| / 12 from the last three rows; the impacts'
                ! losses since the last row (their impulses' work, rollcon_contact_impact) added
                ! exactly; the energy plus W is judged, less the estimates' sum (0 for W
                ! integrated)
                call problem%dissipated_power(friction, rim)
                dissipation = friction + rim
                if (integrated) then
                    if (self%judged_rows == 0) self%work_reference = self%integrator%work
                    self%friction_work = self%integrator%work(1) - self%work_reference(1)
                    self%dissipated_work = sum(self%integrator%work - self%work_reference) &
                        & + self%impact_work
                else if (self%judged_rows > 0) then
                    self%dissipated_work = self%dissipated_work + 0.5_wp*(dissipation &
                        & + self%last_dissipation(1))*(time - self%dissipation_time)
                    self%friction_work = self%friction_work + 0.5_wp*(friction &
                        & + self%last_friction)*(time - self%dissipation_time)
                    if (self%judged_rows > 1) then
                        estimate = (time - self%dissipation_time)*abs(dissipation &
                            & - 2.0_wp*self%last_dissipation(1) + self%last_dissipation(2)) &
                            & /12.0_wp
                        ! a friction's first step, which had no estimate of its own, takes
                        ! this one too (a rim's dissipation alone starts smoothly from rest)
                        if (self%judged_rows == 2 .and. (friction /= 0.0_wp .or. &
                            & self%last_friction /= 0.0_wp)) estimate = 2.0_wp*estimate
                        self%dissipation_uncertainty = self%dissipation_uncertainty + estimate
                    end if
                end if
                ! the impacts before the first judged row took their losses out of its energy
                ! E0 already: not work since E0 (an impact during a force pulse)
                if (self%judged_rows == 0) self%impact_loss = problem%eq%impact_losses()
                impacts = problem%eq%impact_losses() - self%impact_loss
                self%impact_loss = problem%eq%impact_losses()
                if (impacts /= 0.0_wp) then
                    self%dissipated_work = self%dissipated_work + impacts
                    self%impact_work = self%impact_work + impacts
                end if
                ! an impact on a turntable: the table's drive did work V_table . P in it (its
                ! motion prescribed, its MOTION's impulse takes the reaction), which the
                ! energy takes beside the loss: E + W - D is what is conserved
                drive = problem%eq%impact_drive_works() - self%impact_drive
                self%impact_drive = problem%eq%impact_drive_works()
                self%drive_work = self%drive_work + drive
                self%last_dissipation = [dissipation, self%last_dissipation(1)]
                self%last_friction = friction
                self%before_last_time = self%dissipation_time
                self%dissipation_time = time
                self%energy_change = max(self%energy_change, max(0.0_wp, &
                    & abs(energy + self%dissipated_work - self%drive_work &
                    & - summary%energy_reference) &
                    & - self%dissipation_uncertainty))
                self%kinetic_max = max(self%kinetic_max, energy - potential)
                self%potential_min = min(self%potential_min, potential)
                self%potential_max = max(self%potential_max, potential)
                self%step_energy_sum = self%step_energy_sum + problem%eq%energy_tolerance(q, &
                    & u, problem%settings%rtol, problem%settings%atol)
                if (self%judged_rows > 0) self%constraint_work = self%constraint_work &
                    & + 0.5_wp*(power + self%last_power)*(time - self%last_time)
                self%last_power = power
                self%last_time = time
                self%judged_rows = self%judged_rows + 1
            end if
            if (problem%eq%nc > 0) then
                summary%ucon_residual_max = max(summary%ucon_residual_max, &
                    & abs(problem%constraint_values()))
                summary%residual_max = maxval(summary%ucon_residual_max)
            end if
            call deliver_row(problem, time, q, u, row, self%csv, summary, error, history, &
                & sink)
        end associate
    end subroutine record

    !> Event functions fired at the current state: each watch says what to do. When none stops
    !> the run, the parts to re-base are re-based and the integrator starts again (carefully),
    !> or, when no part is, it starts again at the corner of an input (a force's switch on the
    !> state); otherwise the run records the row there and stops with the first stopping
    !> event's message.
    subroutine handle_events(self, summary, stop_here, error, history, sink)
        class(simulation_type), intent(inout) :: self
        type(run_summary_type), intent(inout) :: summary
        logical, intent(out) :: stop_here
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        type(watch_event_type), allocatable :: events(:)
        type(watch_event_type) :: stop_event
        real(wp), allocatable :: rates_before(:)
        character(len=:), allocatable :: refusal
        integer, allocatable :: owners(:)
        integer :: r, w, k, stopping
        logical :: fell

        call self%system%unpack_state(self%t, self%y, self%q, self%u, error)
        if (allocated(error)) return
        allocate(events(0), owners(0))
        stopping = 0
        do r = 1, size(self%integrator%fired)
            if (self%integrator%fired(r) == 0) cycle
            call self%problem%root_owner(r, w, k)
            events = [events, self%problem%watches(w)%watch%fired(self%problem%eq, k, self%t, &
                & self%q, self%u)]
            owners = [owners, w]
            if (events(size(events))%action == action_stop .and. stopping == 0) &
                & stopping = size(events)
        end do
        stop_here = stopping > 0
        if (stop_here) then
            call self%record(summary, error, history, sink)
            summary%status = status_stopped
            summary%message = events(stopping)%message
            summary%limit = events(stopping)%limit
            return
        end if
        ! the changes the watches ask for (each once), the dissipated work's quadrature split
        ! there (the power jumps or kinks at a switch of a contact's mode)
        if (any(events%action == action_restart)) then
            call self%split_dissipation(.false., error)
            if (allocated(error)) return
        end if
        rates_before = self%u
        do k = 1, size(events)
            if (events(k)%action /= action_restart .or. any(owners(:k - 1) == owners(k))) cycle
            call self%problem%watches(owners(k))%watch%restart_problem(self%problem%eq, &
                & self%t, self%q, self%u, error)
            if (allocated(error)) return
            ! a state the watch's equations do not model: the run stops at its row
            stop_event = self%problem%watches(owners(k))%watch%stop_request()
            if (stop_event%action == action_stop) then
                stop_here = .true.
                call self%record(summary, error, history, sink)
                summary%status = status_stopped
                summary%message = stop_event%message
                summary%limit = stop_event%limit
                return
            end if
        end do
        if (any(self%u /= rates_before)) then
            ! the rates jumped (an impact): every watch sets its modes for the new state
            do k = 1, size(self%problem%watches)
                call self%problem%watches(k)%watch%start_problem(self%problem%eq, self%t, &
                    & self%q, self%u, error)
                if (allocated(error)) return
            end do
        end if
        if (any(events%action == action_restart)) then
            call self%split_dissipation(.true., error)
            if (allocated(error)) return
        end if
        if (all(events%action == action_corner)) then
            ! only corners: the integrator starts again with no history, once where a switch
            ! fired (IDA may report a root again at the time it was started from)
            if (self%t > self%t_corner) call self%restart_at_corner(summary, error)
            return
        end if
        ! the re-basings and the restart
        call self%rebase(pack([(events(k)%part, k = 1, size(events))], &
            & [(events(k)%action == action_rebase, k = 1, size(events))]), refusal, fell, error)
        if (allocated(error)) return
        if (allocated(refusal)) then
            stop_here = .true.
            call self%record(summary, error, history, sink)
            if (allocated(error)) return
            ! a fall is the run's outcome, reported as a stop at the last valid row
            if (fell) then
                summary%status = status_stopped
                summary%message = refusal
                summary%limit = "fall"
            else
                call fatal_error(error, refusal, stat_ucon)
            end if
        end if
    end subroutine handle_events

    !> From an integrator that does not integrate the dissipated work (integrator_type work
    !> not allocated): split the rows' trapezoidal rule at a switch of a contact's mode, where the
    !> friction's power jumps (a touchdown into sliding) or kinks (a slide's start or end): a
    !> step of the rule across it would be wrong by up to the jump times the row step. Before
    !> the switch (after = .false.), the rule's piece from the last point (a row or a switch)
    !> to the switch, at the power of the mode that ends, with its estimated error
    !> h^3 |P''| / 12 from the second divided difference of the last two points and the
    !> switch; after it, the switch is the rule's last point, at the power of the mode that
    !> starts (the next row's estimate, from the second difference of the two powers at the
    !> switch and its own, so takes in the jump). The state is self%q, self%u at self%t;
    !> nothing is done before the first judged row.
    subroutine split_dissipation(self, after, error)
        class(simulation_type), intent(inout) :: self
        logical, intent(in) :: after
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: friction, rim, dissipation, h0, h1

        ! a work integrated with the state is not the rows'
        if (self%judged_rows == 0 .or. allocated(self%integrator%work)) return
        associate (problem => self%problem)
            call problem%accelerations(self%t, self%q, self%u, error)
            if (allocated(error)) return
            call problem%dissipated_power(friction, rim)
        end associate
        dissipation = friction + rim
        if (after) then
            self%last_dissipation(1) = dissipation
            self%last_friction = friction
            return
        end if
        if (.not. self%t > self%dissipation_time) return
        h1 = self%t - self%dissipation_time
        self%dissipated_work = self%dissipated_work + 0.5_wp*(dissipation &
            & + self%last_dissipation(1))*h1
        self%friction_work = self%friction_work + 0.5_wp*(friction + self%last_friction)*h1
        h0 = self%dissipation_time - self%before_last_time
        if (self%judged_rows > 1 .and. h0 > 0.0_wp) self%dissipation_uncertainty = &
            & self%dissipation_uncertainty + h1**3/12.0_wp &
            & *abs(2.0_wp*((dissipation - self%last_dissipation(1))/h1 &
            & - (self%last_dissipation(1) - self%last_dissipation(2))/h0)/(h0 + h1))
        self%last_dissipation = [dissipation, self%last_dissipation(1)]
        self%last_friction = friction
        self%before_last_time = self%dissipation_time
        self%dissipation_time = self%t
    end subroutine split_dissipation

    !> Re-base the given parts at the current state (self%q, self%u, as handle_events unpacked
    !> it and the watches' restart_problem left it: rollcon_rebase_step), then start the
    !> integrator again from the same physical state in the new coordinates, on the
    !> constraints, with y' from the saddle-point system for IDA (mu = 0): restart_state.
    subroutine rebase(self, parts, refusal, fell, error)
        class(simulation_type), intent(inout) :: self
        !> Parts to re-base (model order)
        integer, intent(in) :: parts(:)
        character(len=:), allocatable, intent(out) :: refusal
        !> The refusal is a fall (rollcon_rebase_step)
        logical, intent(out) :: fell
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:), u(:)
        integer :: k, turn

        q = self%q
        u = self%u
        fell = .false.
        do k = 1, size(parts)
            call rebase_part(self%problem, parts(k), self%t, q, u, turn, refusal, error, fell)
            if (allocated(error) .or. allocated(refusal)) return
            call self%count_rebasing(parts(k), turn)
        end do
        call restart_state(self%problem, self%system, self%t, q, u, self%y, self%yp, error)
        if (allocated(error)) return
        call self%earlier%add(self%integrator%statistics())
        call self%integrator%restart(self%t, self%y, self%yp, error)
    end subroutine rebase

    !> The system's choices have worn (in independent speeds, its partition): start the
    !> integrator again at the current state with new ones (made by restart_state's
    !> pack_state), the same physical state.
    subroutine repartition(self, error)
        class(simulation_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:), u(:)

        call self%system%unpack_state(self%t, self%y, self%q, self%u, error)
        if (allocated(error)) return
        q = self%q
        u = self%u
        call restart_state(self%problem, self%system, self%t, q, u, self%y, self%yp, error)
        if (allocated(error)) return
        call self%earlier%add(self%integrator%statistics())
        call self%integrator%restart(self%t, self%y, self%yp, error)
    end subroutine repartition

    !> At a corner of an input, time t (a force that switches, a pulse's end): start the
    !> integrator again there with no history, from the state put back on the constraints
    !> (restart_state) and y' as the run goes on (the accelerations just after t, where a force
    !> that switches at t has its new value), without the careful start of a re-basing: a
    !> history across the corner holds a force the solution no longer has, and the error
    !> estimates that come from it let the error stop falling with the tolerance
    !> (docs/design.md §7).
    subroutine restart_at_corner(self, summary, error)
        class(simulation_type), intent(inout) :: self
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:), u(:)

        call self%system%unpack_state(self%t, self%y, self%q, self%u, error)
        if (allocated(error)) return
        q = self%q
        u = self%u
        call restart_state(self%problem, self%system, self%t, q, u, self%y, self%yp, error)
        if (allocated(error)) return
        call self%problem%accelerations(nearest(self%t, 1.0_wp), q, u, error)
        if (allocated(error)) return
        call self%system%pack_state(q, u, self%y, self%yp)
        call self%earlier%add(self%integrator%statistics())
        call self%integrator%restart(self%t, self%y, self%yp, error, careful=.false.)
        if (allocated(error)) return
        self%t_corner = self%t
        summary%corner_restarts = summary%corner_restarts + 1
    end subroutine restart_at_corner

    !> Where the model's inputs have corners known in advance [s]: the forces' (force_corners).
    !> A MOTION's switching times, when the datasets have MOTION, join them here.
    function corner_times(model) result(times)
        type(model_type), intent(in) :: model
        real(wp), allocatable :: times(:)

        times = force_corners(model%forces)
    end function corner_times

    !> A row at (time [s], q, u) made, as every analysis ends it: the whole turns counted from
    !> the row before (the next goes on from them), the summary's last state and count, the
    !> row kept (history), written (CSV) and sent (sink).
    subroutine deliver_row(problem, time, q, u, row, csv, summary, error, history, sink)
        type(problem_type), intent(inout) :: problem
        real(wp), intent(in) :: time, q(:), u(:), row(:)
        type(csv_writer_type), intent(inout) :: csv
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink

        call problem%model%count_turns(q, u, restart=.false.)
        summary%t_reached = time
        summary%q = q
        summary%u = u
        summary%rows = summary%rows + 1
        if (present(history)) call history%add(row)
        if (csv%opened) call csv%write_row(row, error)
        if (allocated(error)) return
        if (present(sink)) call sink%put(row, error)
    end subroutine deliver_row

    !> The summary of a prepared problem before its first row, as every analysis starts it:
    !> its rows' layout, each UCON's largest residual (0 so far), which are position UCONs,
    !> the routines serving the statements and each UCON in the user's words.
    subroutine start_summary(problem, layout, summary)
        type(problem_type), intent(in) :: problem
        type(output_layout_type), intent(in) :: layout
        type(run_summary_type), intent(inout) :: summary

        summary%layout = layout
        summary%ucon_residual_max = spread(0.0_wp, 1, problem%eq%nc)
        summary%ucon_position = problem%model%holonomic_number > 0
        summary%routines = problem%routines_text()
        summary%ucon_labels = problem%ucon_labels()
    end subroutine start_summary

    !> A model whose force expressions switch on the state is watched for those switches (once:
    !> a problem run again keeps its watch).
    subroutine add_switch_watch(problem)
        type(problem_type), intent(inout) :: problem
        type(switch_watch_type) :: watch
        integer :: k

        if (.not. has_state_switches(problem%model%forces)) return
        if (allocated(problem%watches)) then
            do k = 1, size(problem%watches)
                select type (w => problem%watches(k)%watch)
                type is (switch_watch_type)
                    return
                end select
            end do
        end if
        call problem%add_watch(watch)
    end subroutine add_switch_watch

    !> Before the first row: the parts that start in a turned basis (problem%start_bases)
    !> counted as re-based, then every part a watch wants re-based at the start (a part at
    !> or below the threshold of a watch that re-bases there) re-based. A refusal fails the run
    !> after that row (the start as given).
    subroutine rebase_at_start(self, q, u, refusal, fell, error)
        class(simulation_type), intent(inout) :: self
        real(wp), intent(inout) :: q(:), u(:)
        character(len=:), allocatable, intent(out) :: refusal
        !> The refusal is a fall (rollcon_rebase_step)
        logical, intent(out) :: fell
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: parts(:), turns(:)
        integer :: w, k, turn

        fell = .false.
        if (allocated(self%problem%start_bases)) then
            do k = 1, size(self%problem%start_bases)
                turns = turns_from_own(self%problem%start_bases(k))
                do w = 1, size(turns)
                    call self%count_rebasing(k, turns(w))
                end do
            end do
        end if
        do w = 1, size(self%problem%watches)
            parts = self%problem%watches(w)%watch%parts_to_rebase(self%problem%eq, q)
            do k = 1, size(parts)
                call rebase_part(self%problem, parts(k), self%options%t0, q, u, turn, refusal, &
                    & error, fell)
                if (allocated(error) .or. allocated(refusal)) return
                call self%count_rebasing(parts(k), turn)
            end do
        end do
    end subroutine rebase_at_start

    !> One more re-basing of part p (model order), by `turn` (rollcon_rebasing), told to every
    !> watch.
    subroutine count_rebasing(self, p, turn)
        class(simulation_type), intent(inout) :: self
        integer, intent(in) :: p, turn
        integer :: w

        self%bases(p) = self%bases(p) + 1
        do w = 1, size(self%problem%watches)
            call self%problem%watches(w)%watch%part_rebased(p, turn)
        end do
    end subroutine count_rebasing

    !> Add to an integrator's failure the load or rate that ran away at its last state
    !> (problem_type's runaway_text: a load beyond runaway_weights times the parts' weight),
    !> when one has and the message does not say it already: an integrator that cannot follow
    !> a load of 1e33 N on a coin of 7 N says only that it took too many steps.
    subroutine name_runaway(self, error)
        class(simulation_type), intent(inout) :: self
        type(error_type), allocatable, intent(inout) :: error
        !> A load a million times the weight of every part together is no load the model was
        !> written for (the coin's strike peaks at a fifth of its weight)
        real(wp), parameter :: runaway_weights = 1.0e6_wp
        type(error_type), allocatable :: unpacked
        character(len=:), allocatable :: why

        call self%system%unpack_state(self%t, self%y, self%q, self%u, unpacked)
        if (allocated(unpacked)) return
        why = self%problem%runaway_text(self%t, self%q, self%u, runaway_weights)
        if (len(why) > 0 .and. index(error%message, why) == 0) error%message = error%message &
            & // "; " // why
    end subroutine name_runaway

    !> The summary's counters, CPU time, re-basings and the watches' measures and lines; the
    !> integrator freed; the CSV closed (its failure, a full disk, fails the run unless it
    !> failed already).
    subroutine finish(self, summary, error)
        class(simulation_type), intent(inout) :: self
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(inout) :: error
        type(error_type), allocatable :: close_error
        type(watch_measure_type), allocatable :: taken(:)
        real(wp) :: cpu_now
        integer :: k

        if (allocated(self%bases)) summary%rebasings = self%bases
        if (self%judged_rows > 0) then
            summary%energy_scale = max(self%kinetic_max, self%potential_max - self%potential_min)
            if (summary%energy_scale > 0.0_wp) summary%energy_drift = &
                & self%energy_change/summary%energy_scale
            summary%energy_step = self%step_energy_sum/real(self%judged_rows, wp)
            summary%constraint_work = self%constraint_work
            summary%dissipated_work = self%dissipated_work
            summary%friction_work = self%friction_work
            summary%impact_work = self%impact_work
            summary%drive_work = self%drive_work
            summary%dissipation_uncertainty = self%dissipation_uncertainty
            ! a friction's work by the rows' rule over fewer than three rows: no estimate of
            ! the rule's error, so W is known only to within itself
            if (self%judged_rows < 3 .and. .not. allocated(self%work_reference)) &
                & summary%dissipation_uncertainty = max( &
                & summary%dissipation_uncertainty, self%friction_work)
        end if
        call cpu_time(cpu_now)
        summary%cpu_seconds = cpu_now - self%cpu_start
        if (allocated(self%integrator)) then
            ! a restart zeroes the counters: the run's are the segments' sums
            call self%earlier%add(self%integrator%statistics())
            call self%integrator%destroy()
        end if
        if (allocated(self%system)) call self%system%release()
        summary%steps = self%earlier%steps
        summary%functions = self%earlier%functions
        summary%jacobians = self%earlier%jacobians
        summary%failures = self%earlier%failures
        summary%root_evaluations = self%earlier%roots
        summary%sparse_newton = self%earlier%sparse
        allocate(summary%measures(0))
        summary%watch_lines = ""
        associate (problem => self%problem)
            do k = 1, size(problem%watches)
                taken = problem%watches(k)%watch%measures(problem%eq, problem%settings, &
                    & summary%steps)
                summary%measures = [summary%measures, taken]
                summary%watch_lines = summary%watch_lines &
                    & // problem%watches(k)%watch%summary_lines(problem%eq)
            end do
        end associate
        call self%csv%close(close_error)
        if (allocated(close_error)) then
            summary%status = status_failed
            if (.not. allocated(error)) then
                summary%message = close_error%message
                call move_alloc(close_error, error)
            end if
        end if
        if (allocated(error)) then
            summary%status = status_failed
            summary%message = error%message
        end if
    end subroutine finish

end module rollcon_simulation
