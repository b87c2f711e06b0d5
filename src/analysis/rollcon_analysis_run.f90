! SPDX-License-Identifier: MIT
!> A run of the analysis its settings ask for (docs/analyses.md), from a consistent start:
!>
!> - dynamic (SIMULATE/DYNAMIC): the integration (rollcon_simulation), after the static
!>   equilibrium when one comes first (SIMULATE/STATIC then SIMULATE/DYNAMIC: settings'
!>   static_first), from it at rest, as ADAMS goes on from an equilibrium;
!> - static (SIMULATE/STATIC alone): the equilibrium (rollcon_static_equilibrium), one row at
!>   the start's time;
!> - kinematic (SIMULATE/KINEMATIC): a row at the start and at each output time, the state
!>   solved there (rollcon_kinematic_analysis).
!>
!> Every row is the one a dynamic run writes at that state (rollcon_output_rows: coordinates,
!> rates, energy, residuals, multipliers, the watches' columns: the statements' reactions and
!> each MOTION's force), to the CSV, the history and the sink alike; the summary says which
!> analysis ran and, for a static equilibrium, its iterations and what it left unbalanced.
module rollcon_analysis_run
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_run_settings, only : analysis_static, analysis_kinematic, formulation_speeds
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & status_completed, status_failed, output_layout, start_summary, deliver_row
    use rollcon_output_rows, only : output_row, output_time, planned_rows
    use rollcon_output_layout, only : output_layout_type
    use rollcon_csv_writer, only : csv_writer_type
    use rollcon_row_sink, only : row_sink_type
    use rollcon_watch, only : watch_measure_type
    use rollcon_static_equilibrium, only : static_report_type, find_static_equilibrium, &
        & static_report_text
    use rollcon_kinematic_analysis, only : kinematic_freedom, kinematic_positions, &
        & kinematic_velocities
    implicit none
    private

    public :: run_analysis

    character(len=*), parameter :: nl = new_line("a")

    !> The rows of a run that is not integrated: where they go
    type :: rows_type
        type(output_layout_type) :: layout
        type(csv_writer_type) :: csv
        real(wp) :: cpu_start = 0.0_wp
        !> The energy's measures over the rows [J]: the first row's, the largest change from
        !> it, the largest kinetic energy, the potential energy's range
        real(wp) :: first_energy = 0.0_wp, energy_change = 0.0_wp, kinetic_max = 0.0_wp
        real(wp) :: potential_min = huge(1.0_wp), potential_max = -huge(1.0_wp)
    end type rows_type

contains

    !> Run problem from (q0, u0) by the analysis of its settings, as simulate runs a dynamic
    !> one (same arguments; see the module's header).
    subroutine run_analysis(problem, q0, u0, options, summary, error, history, sink)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(out) :: summary
        !> A refusal (no row written) or a failure (summary%rows rows stay valid)
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        type(static_report_type) :: report
        real(wp), allocatable :: q(:), u(:)

        call check_diffs(problem, error)
        if (allocated(error)) return
        select case (problem%settings%analysis)
        case (analysis_kinematic)
            call kinematic_run(problem, q0, u0, options, summary, error, history, sink)
            return
        case (analysis_static)
        case default
            if (.not. problem%settings%static_first) then
                call simulate(problem, q0, u0, options, summary, error, history, sink)
                return
            end if
        end select
        q = q0
        call find_static_equilibrium(problem, options%t0, q, report, error)
        if (allocated(error)) then
            summary%status = status_failed
            summary%message = error%message
            return
        end if
        allocate(u(size(u0)), source=0.0_wp)
        if (problem%settings%analysis == analysis_static) then
            call static_run(problem, q, u, options, summary, error, history, sink)
            summary%analysis_lines = "analysis: static equilibrium (SIMULATE/STATIC)" // nl &
                & // static_report_text(report)
        else
            call simulate(problem, q, u, options, summary, error, history, sink)
            summary%analysis_lines = "analysis: static equilibrium, then dynamic from it " &
                & // "(SIMULATE/STATIC, SIMULATE/DYNAMIC)" // nl // static_report_text(report)
        end if
    end subroutine run_analysis

    !> The DIFFs (rollcon_diff) an analysis can take: the independent speeds integrate the
    !> parts' states alone, so a model with DIFFs is refused there; a kinematic analysis
    !> integrates nothing,
    !> so a model with DIFFs is refused there; a static equilibrium holds each DIFF's state
    !> where it is (STATIC_HOLD), and a DIFF without STATIC_HOLD, whose equation ADAMS solves
    !> with the equilibrium (e = 0, or e(DIF, DIF1 = 0) = 0), is refused, naming it.
    subroutine check_diffs(problem, error)
        type(problem_type), intent(in) :: problem
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        associate (diffs => problem%model%diffs)
            if (diffs%count() == 0) return
            if (problem%settings%formulation == formulation_speeds) then
                call fatal_error(error, trim(diffs%diffs(1)%name) // ": a DIFF's state is " &
                    & // "integrated in the formulations 'cvode' and 'ida' (docs/datasets.md, " &
                    & // "DIFF); the independent speeds ('maggi') integrate the parts' alone: " &
                    & // "choose another formulation", stat_input)
                return
            end if
            if (problem%settings%analysis == analysis_kinematic) then
                call fatal_error(error, trim(diffs%diffs(1)%name) // ": a kinematic analysis " &
                    & // "integrates no state, and a DIFF's is integrated: run the model " &
                    & // "dynamic (SIMULATE/DYNAMIC)", stat_input)
                return
            end if
            if (problem%settings%analysis /= analysis_static .and. &
                & .not. problem%settings%static_first) return
            do k = 1, diffs%count()
                if (diffs%diffs(k)%static_hold) cycle
                call fatal_error(error, trim(diffs%diffs(k)%name) // ": a static equilibrium " &
                    & // "holds a DIFF's state at its value only with STATIC_HOLD; rollcon " &
                    & // "does not solve its equation with the equilibrium (ADAMS's e = 0 " &
                    & // "for DIF): add STATIC_HOLD, or run it dynamic alone", stat_input)
                return
            end do
        end associate
    end subroutine check_diffs

    !> The equilibrium's one row.
    subroutine static_run(problem, q, u, options, summary, error, history, sink)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q(:), u(:)
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        type(rows_type) :: rows

        call begin_rows(rows, problem, options, q, u, summary, error, history, sink)
        if (allocated(error)) return
        call record(rows, problem, options%t0, q, u, summary, error, history, sink)
        call finish_rows(rows, problem, summary, error)
    end subroutine static_run

    !> A row at the start and at every output time, the state solved at each.
    subroutine kinematic_run(problem, q0, u0, options, summary, error, history, sink)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(run_options_type), intent(in) :: options
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        type(rows_type) :: rows
        real(wp), allocatable :: q(:), u(:)
        real(wp) :: t, t_next, dt
        integer(int64) :: k, n_output
        integer :: iterations, total

        summary%analysis_lines = "analysis: kinematic (SIMULATE/KINEMATIC): positions, " &
            & // "velocities, accelerations and reactions from the constraints and MOTIONs" // nl
        q = q0
        u = u0
        call kinematic_freedom(problem, options%t0, q, error)
        if (allocated(error)) return
        call begin_rows(rows, problem, options, q, u, summary, error, history, sink)
        if (allocated(error)) return
        call planned_rows(options, rows%layout%columns(), n_output, error)
        if (allocated(error)) return
        t = options%t0
        total = 0
        k = 0
        do
            call kinematic_positions(problem, t, q, iterations, error)
            if (allocated(error)) exit
            total = total + iterations
            call kinematic_velocities(problem, t, q, u, error)
            if (allocated(error)) exit
            call record(rows, problem, t, q, u, summary, error, history, sink)
            if (allocated(error)) exit
            k = k + 1
            if (k > n_output) exit
            t_next = output_time(options, k)
            dt = t_next - t
            ! the prediction: the motion of the last time carried on (problem%a: its row's)
            q = q + dt*u + 0.5_wp*dt**2*problem%a
            t = t_next
        end do
        if (allocated(error)) then
            summary%status = status_failed
            summary%message = error%message
            summary%t_reached = max(summary%t_reached, t)
        end if
        summary%analysis_lines = summary%analysis_lines // "kinematic analysis: " &
            & // to_text(summary%rows) // " times solved, " // to_text(total) &
            & // " Newton iterations on the positions" // nl
        call finish_rows(rows, problem, summary, error)
    end subroutine kinematic_run

    !> Before the first row: the watches prepared, the layout, what the summary keeps, the CSV
    !> and the sink opened, the rows set aside as redundant chosen at the start.
    subroutine begin_rows(rows, problem, options, q, u, summary, error, history, sink)
        type(rows_type), intent(inout) :: rows
        type(problem_type), intent(inout), target :: problem
        type(run_options_type), intent(in) :: options
        real(wp), intent(in) :: q(:), u(:)
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink

        call cpu_time(rows%cpu_start)
        call problem%prepare(error)
        if (allocated(error)) return
        rows%layout = output_layout(problem)
        call start_summary(problem, rows%layout, summary)
        if (present(history)) history%layout = rows%layout
        if (allocated(options%csv_path)) then
            call rows%csv%open(options%csv_path, rows%layout%header(), error)
            if (allocated(error)) return
        end if
        if (present(sink)) then
            call sink%open(rows%layout, error)
            if (allocated(error)) return
        end if
        call problem%model%count_turns(q, u, restart=.true.)
        call problem%choose_rows(options%t0, q, u, error)
    end subroutine begin_rows

    !> The row at (t, q, u): accelerations and multipliers from the equations of motion there.
    subroutine record(rows, problem, time, q, u, summary, error, history, sink)
        type(rows_type), intent(inout) :: rows
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(inout), optional :: history
        class(row_sink_type), intent(inout), optional :: sink
        real(wp), allocatable :: row(:)
        real(wp) :: energy, potential

        call problem%accelerations(time, q, u, error)
        if (allocated(error)) return
        row = output_row(problem, rows%layout, time, q, u)
        if (.not. all(ieee_is_finite(row))) then
            call problem%nonfinite_state(time, q, u, error)
            error%message = "the row at t = " // to_text(time) // " s is not finite (" &
                & // trim(rows%layout%column_name(findloc(ieee_is_finite(row), .false., &
                & dim=1))) // " first): " // error%message
            return
        end if
        if (problem%eq%nc > 0) then
            summary%ucon_residual_max = max(summary%ucon_residual_max, &
                & abs(problem%constraint_values()))
            summary%residual_max = maxval(summary%ucon_residual_max)
        end if
        ! the energy, measured as a dynamic run measures it (rollcon_simulation's record)
        energy = row(rows%layout%energy_column())
        potential = problem%eq%potential_energy(q)
        if (summary%rows == 0) rows%first_energy = energy
        rows%energy_change = max(rows%energy_change, abs(energy - rows%first_energy))
        rows%kinetic_max = max(rows%kinetic_max, energy - potential)
        rows%potential_min = min(rows%potential_min, potential)
        rows%potential_max = max(rows%potential_max, potential)
        call deliver_row(problem, time, q, u, row, rows%csv, summary, error, history, sink)
    end subroutine record

    !> After the last row: the watches' measures and lines, the CSV closed, the CPU time;
    !> completed unless it failed.
    subroutine finish_rows(rows, problem, summary, error)
        type(rows_type), intent(inout) :: rows
        type(problem_type), intent(inout) :: problem
        type(run_summary_type), intent(inout) :: summary
        type(error_type), allocatable, intent(inout) :: error
        type(error_type), allocatable :: close_error
        type(watch_measure_type), allocatable :: taken(:)
        real(wp) :: now
        integer :: k

        ! the watches' measures and lines, as a dynamic run's summary has them
        allocate(summary%measures(0))
        summary%watch_lines = ""
        do k = 1, size(problem%watches)
            taken = problem%watches(k)%watch%measures(problem%eq, problem%settings, 0)
            summary%measures = [summary%measures, taken]
            summary%watch_lines = summary%watch_lines &
                & // problem%watches(k)%watch%summary_lines(problem%eq)
        end do

        if (rows%csv%opened) then
            call rows%csv%close(close_error)
            if (allocated(close_error) .and. .not. allocated(error)) &
                & call move_alloc(close_error, error)
        end if
        call cpu_time(now)
        summary%cpu_seconds = now - rows%cpu_start
        ! the energy is not conserved where MOTIONs drive the model: measured, not judged
        summary%energy_reference = rows%first_energy
        summary%energy_scale = max(rows%kinetic_max, rows%potential_max - rows%potential_min)
        if (summary%energy_scale > 0.0_wp) summary%energy_drift = &
            & rows%energy_change/summary%energy_scale
        summary%energy_conserved = summary%energy_scale == 0.0_wp
        if (allocated(error)) then
            summary%status = status_failed
            summary%message = error%message
        else
            summary%status = status_completed
        end if
    end subroutine finish_rows

end module rollcon_analysis_run
