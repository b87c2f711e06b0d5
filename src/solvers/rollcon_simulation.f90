! SPDX-License-Identifier: MIT
!> Runs a problem from t0 to the end time with CVODE or IDA: output rows, events, summary.
module rollcon_simulation
    use, intrinsic :: iso_fortran_env, only : error_unit, int64
    use rollcon_kinds, only : wp
    use rollcon_clock, only : wall_seconds
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_ucon
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type, formulation_cvode
    use rollcon_cvode, only : cvode_solver_type
    use rollcon_ida, only : ida_solver_type
    use rollcon_dae, only : dae_size
    use rollcon_force, only : force_breakpoints, forces_idle_after
    use rollcon_csv_writer, only : csv_writer_type
    use rollcon_drift, only : height_residual
    use rollcon_run_summary, only : run_summary_type, status_completed, status_stopped, &
        & status_failed, status_inaccurate, judge_drift, limit_none, limit_theta, limit_liftoff
    use rollcon_output_layout, only : output_layout_type
    use rollcon_output_rows, only : run_options_type, default_max_csv_bytes, planned_rows, &
        & history_type, output_layout, output_row
    use rollcon_event_message, only : event_message
    use rollcon_rebase_step, only : rebase_part, needs_rebasing
    implicit none
    private

    public :: run_options_type, run_summary_type, history_type, simulate
    !> How a run ended and what it did (rollcon_run_summary), for the callers of simulate
    public :: status_completed, status_stopped, status_failed, status_inaccurate
    public :: limit_none, limit_theta, limit_liftoff
    !> The output rows' limit and layout (rollcon_output_rows), for the callers of simulate
    public :: default_max_csv_bytes, output_layout


contains

    !> Integrate problem from (q0, u0), writing a row per output time. The host holds the one
    !> loop over output times with its stops, events and failures; the start, row, event,
    !> progress and summary work is in its internal procedures.
    subroutine simulate(problem, q0, u0, options, summary, error, history)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(out) :: summary
        !> Set on a solver or output failure; summary still describes the run so far
        type(error_type), allocatable, intent(out) :: error
        !> When present, every output row is also kept here
        type(history_type), intent(inout), optional :: history
        type(cvode_solver_type), target :: cvode
        type(ida_solver_type), target :: ida
        type(csv_writer_type) :: csv
        type(output_layout_type) :: layout
        real(wp), allocatable :: y(:), yp(:), breaks(:), q_start(:), u_start(:)
        character(len=:), allocatable :: refusal
        !> Integrator counters of the segments before the last re-initialisation
        integer :: earlier(4)
        real(wp) :: t, t_out, t_stop, t_reference, cpu_start, cpu_now, wall_last
        integer :: n, nc, root
        integer(int64) :: k_output, n_output
        type(error_type), allocatable :: close_error
        logical :: use_cvode, have_reference

        n = problem%eq%n
        nc = problem%eq%nc
        call check_events(problem, error)
        if (allocated(error)) return
        call problem%prepare()
        call start_measures()
        q_start = q0
        u_start = u0
        earlier = 0
        use_cvode = problem%settings%formulation == formulation_cvode
        breaks = force_breakpoints(problem%model%forces)
        t_reference = options%t0
        if (size(breaks) > 0) t_reference = maxval(breaks)
        ! forces acting after the reference, or moving constraints, do work: no drift to judge
        summary%energy_conserved = forces_idle_after(problem%model%forces, t_reference, &
            & options%end_time)
        if (summary%energy_conserved) summary%energy_conserved = &
            & problem%ucons_do_no_work(options%t0, q0)
        breaks = pack(breaks, breaks > options%t0 .and. breaks < options%end_time)

        call planned_rows(options, layout%columns(), n_output, error)
        if (allocated(error)) return
        if (allocated(options%csv_path)) then
            call csv%open(options%csv_path, layout%header(), error)
            if (allocated(error)) return
        end if

        call cpu_time(cpu_start)
        call rebase_at_start(refusal, error)
        if (allocated(error)) then
            call finish()
            return
        end if
        ! Consistent start: accelerations and multipliers from the saddle-point system.
        call problem%accelerations(options%t0, q_start, u_start, error)
        if (allocated(error)) return
        t = options%t0
        t_stop = next_stop(t)
        wall_last = wall_seconds()
        call start_integrator(error)
        if (allocated(error)) then
            call finish()
            return
        end if
        have_reference = .false.
        call record(t, y, error)
        ! a re-basing refused: the run cannot go on as asked, a failure (docs/rebasing.md)
        if (allocated(refusal)) call fatal_error(error, refusal, stat_ucon)
        if (allocated(error)) then
            call finish()
            return
        end if

        k_output = 1
        do while (k_output <= n_output)
            t_out = min(options%t0 + real(k_output, wp)*options%output_step, options%end_time)
            t_stop = next_stop(t)
            if (use_cvode) then
                call cvode%advance(problem, t_out, t_stop, t, y, root, error)
            else
                call ida%advance(problem, t_out, t_stop, t, y, yp, root, error)
            end if
            if (allocated(error)) then
                summary%status = status_failed
                summary%message = error%message
                summary%solver_flag = merge(cvode%failed_flag, ida%failed_flag, use_cvode)
                ! where the integrator got to, past the last row
                summary%t_reached = max(summary%t_reached, t)
                exit
            end if
            if (root /= 0) then
                if (.not. rebases()) then
                    call record(t, y, error)
                    summary%status = status_stopped
                    summary%message = event_message(problem, root, t, y(:n), y(n + 1:2*n))
                    summary%limit = limit_liftoff
                    if (problem%theta_root_part(root) > 0) summary%limit = limit_theta
                    exit
                end if
                call rebase_fired(refusal, error)
                if (allocated(error)) exit
                if (allocated(refusal)) then
                    call record(t, y, error)
                    if (.not. allocated(error)) call fatal_error(error, refusal, stat_ucon)
                    exit
                end if
            end if
            if (t < t_out) cycle
            call record(t, y, error)
            if (allocated(error)) exit
            k_output = k_output + 1
            call report_progress(t)
        end do
        call finish()
        if (.not. allocated(error)) call judge_drift(problem, summary)

    contains

        !> Every event function that fired is a theta limit of a model that re-bases.
        logical function rebases()
            integer, allocatable :: fired(:)
            integer :: r

            rebases = problem%events%rebase
            if (.not. rebases) return
            if (use_cvode) then
                fired = cvode%fired
            else
                fired = ida%fired
            end if
            do r = 1, size(fired)
                if (fired(r) /= 0 .and. problem%theta_root_part(r) == 0) rebases = .false.
            end do
        end function rebases

        !> Re-base every part at or below the threshold at the start, before the first row: a
        !> refusal fails the run after that row (the start as given).
        subroutine rebase_at_start(refusal, error)
            character(len=:), allocatable, intent(out) :: refusal
            type(error_type), allocatable, intent(out) :: error
            integer :: p

            if (.not. problem%events%rebase .or. problem%events%theta_min < 0.0_wp) return
            do p = 1, size(problem%model%parts)
                if (.not. needs_rebasing(problem, p, q_start)) cycle
                call rebase_part(problem, p, options%t0, q_start, u_start, refusal, error)
                if (allocated(error) .or. allocated(refusal)) return
            end do
        end subroutine rebase_at_start

        !> Re-base the parts whose theta limit fired at (t, y), then start the integrator
        !> again from the same physical state in the new coordinates: CVODE from (q, u), IDA
        !> from (q, u, lambda) with y' = (u, a) from the saddle-point system (mu = 0).
        subroutine rebase_fired(refusal, error)
            character(len=:), allocatable, intent(out) :: refusal
            type(error_type), allocatable, intent(out) :: error
            integer, allocatable :: fired(:)
            real(wp), allocatable :: q(:), u(:)
            integer :: r

            if (use_cvode) then
                fired = cvode%fired
            else
                fired = ida%fired
            end if
            q = y(:n)
            u = y(n + 1:2*n)
            do r = 1, size(fired)
                if (fired(r) == 0) cycle
                call rebase_part(problem, problem%theta_root_part(r), t, q, u, refusal, error)
                if (allocated(error) .or. allocated(refusal)) return
            end do
            call problem%accelerations(t, q, u, error)
            if (allocated(error)) return
            call add_statistics(earlier)
            if (use_cvode) then
                y = [q, u]
                call cvode%reinit(t, y, error)
            else
                y = 0.0_wp
                y(:2*n) = [q, u]
                y(2*n + 1:2*n + nc) = problem%lambda
                yp = 0.0_wp
                yp(:2*n) = [u, problem%a]
                call ida%reinit(t, y, yp, error)
            end if
        end subroutine rebase_fired

        !> The rows' layout, in the summary and the history; no UCON residual measured yet.
        subroutine start_measures()
            integer :: k

            layout = output_layout(problem)
            summary%layout = layout
            allocate(summary%ucon_residual_max(nc), source=0.0_wp)
            allocate(summary%ucon_position(nc))
            do k = 1, nc
                summary%ucon_position(k) = problem%model%ucons(k)%holonomic
            end do
            if (present(history)) history%layout = layout
        end subroutine start_measures

        !> Set up CVODE on (q0, u0), or IDA on (q0, u0, lambda) with its consistent rates.
        subroutine start_integrator(error)
            type(error_type), allocatable, intent(out) :: error

            if (use_cvode) then
                y = [q_start, u_start]
                call cvode%init(problem, t, y, t_stop, error)
            else
                allocate(y(dae_size(problem%eq)), yp(dae_size(problem%eq)), source=0.0_wp)
                y(:2*n) = [q_start, u_start]
                y(2*n + 1:2*n + nc) = problem%lambda
                yp(:2*n) = [u_start, problem%a]
                call ida%init(problem, t, y, yp, t_stop, error)
            end if
        end subroutine start_integrator

        !> The next time the integrator must not step past: a force kink or the end.
        function next_stop(time) result(stop_time)
            real(wp), intent(in) :: time
            real(wp) :: stop_time

            stop_time = options%end_time
            if (any(breaks > time)) stop_time = minval(breaks, mask=breaks > time)
        end function next_stop

        !> Write the output row at (t, y) and update the summary's measures.
        subroutine record(time, state, error)
            real(wp), intent(in) :: time, state(:)
            type(error_type), allocatable, intent(out) :: error
            real(wp) :: energy, height(1)
            real(wp), allocatable :: row(:)
            type(error_type), allocatable :: eval_error

            associate (q => state(:n), u => state(n + 1:2*n))
                call problem%accelerations(time, q, u, eval_error)
                if (allocated(eval_error)) then
                    call move_alloc(eval_error, error)
                    return
                end if
                row = output_row(problem, layout, time, q, u)
                energy = row(layout%energy_column())
                ! Energy is conserved once the last force pulse is over: measure drift from the
                ! first row at or after that time.
                if (time >= t_reference) then
                    if (.not. have_reference) summary%energy_reference = energy
                    have_reference = .true.
                    if (summary%energy_reference /= 0.0_wp) then
                        summary%energy_drift = max(summary%energy_drift, &
                            & abs(energy - summary%energy_reference)/abs(summary%energy_reference))
                    end if
                end if
                if (nc > 0) then
                    summary%ucon_residual_max = max(summary%ucon_residual_max, &
                        & abs(problem%constraint_values()))
                    summary%residual_max = maxval(summary%ucon_residual_max)
                end if
                height = height_residual(problem, q)
                summary%height_residual_max = max(summary%height_residual_max, abs(height(1)))
                summary%t_reached = time
                summary%q = q
                summary%u = u
                summary%rows = summary%rows + 1
                if (present(history)) call history%add(row)
                if (csv%opened) call csv%write_row(row, error)
            end associate
        end subroutine record

        !> At most once a second of wall time: the fraction of the simulated time done, the
        !> rate, and the time left at that rate, e.g. "rollcon: 82% of 10 s simulated
        !> (t = 8.2 s), 14.5 simulated s per CPU s, about 0.1 s left".
        subroutine report_progress(time)
            real(wp), intent(in) :: time
            real(wp) :: now, fraction, left

            if (.not. options%progress) return
            now = wall_seconds()
            if (now - wall_last < 1.0_wp) return
            wall_last = now
            call cpu_time(cpu_now)
            fraction = (time - options%t0)/(options%end_time - options%t0)
            left = (cpu_now - cpu_start)*(1.0_wp - fraction)/max(fraction, 1.0e-9_wp)
            write(error_unit, '(a, g0.3, a)') "rollcon: " &
                & // to_text(anint(1000.0_wp*fraction)/10.0_wp) // "% of " &
                & // to_text(options%end_time - options%t0) // " s simulated (t = " &
                & // to_text(anint(1000.0_wp*time)/1000.0_wp) // " s), ", &
                & (time - options%t0)/max(cpu_now - cpu_start, 1.0e-9_wp), &
                & " simulated s per CPU s, about " // to_text(anint(10.0_wp*left)/10.0_wp) &
                & // " s left"
            flush(error_unit)
        end subroutine report_progress

        !> Add the integrator's counters (steps, functions, Jacobians, failures) since its last
        !> (re-)initialisation to counts.
        subroutine add_statistics(counts)
            integer, intent(inout) :: counts(4)
            integer :: now(4)

            now = 0
            if (use_cvode) then
                if (allocated(cvode%values)) call cvode%statistics(now(1), now(2), now(3), now(4))
            else
                if (allocated(ida%values)) call ida%statistics(now(1), now(2), now(3), now(4))
            end if
            counts = counts + now
        end subroutine add_statistics

        subroutine finish()
            summary%rebasings = problem%bases
            call cpu_time(cpu_now)
            summary%cpu_seconds = cpu_now - cpu_start
            ! a re-initialisation restarts the counters: the run's are the segments' sums
            call add_statistics(earlier)
            summary%steps = earlier(1)
            summary%functions = earlier(2)
            summary%jacobians = earlier(3)
            summary%failures = earlier(4)
            if (use_cvode) then
                call cvode%destroy()
            else
                call ida%destroy()
            end if
            ! A write or the close failing (a full disk) fails the run, unless it failed already.
            call csv%close(close_error)
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

    end subroutine simulate

    !> A watched contact needs a part in contact among the model's parts and a rim radius.
    subroutine check_events(problem, error)
        type(problem_type), intent(in) :: problem
        type(error_type), allocatable, intent(out) :: error

        if (.not. problem%events%has_contact) return
        if (problem%events%part < 1 .or. problem%events%part > size(problem%model%parts)) then
            call fatal_error(error, "the part in contact is number " &
                & // to_text(problem%events%part) // " in model order; the model has " &
                & // to_text(size(problem%model%parts)) // " parts", stat_input)
        else if (.not. problem%events%contact_radius > 0.0_wp) then
            call fatal_error(error, "the contact of part " &
                & // to_text(problem%model%parts(problem%events%part)%id) &
                & // " needs a rim radius > 0 [m], got " &
                & // to_text(problem%events%contact_radius), stat_input)
        end if
    end subroutine check_events

end module rollcon_simulation
