! SPDX-License-Identifier: MIT
!> What a run did and how it ended (status, measures, counters, re-basings), and the judge of
!> its drift against what its tolerances promise (rollcon_drift for the energy, each watch for
!> its own measures).
module rollcon_run_summary
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_drift, only : energy_bound, energy_allowance, energy_fraction, work_fraction
    use rollcon_run_settings, only : run_settings_type, formulation_ida, method_bdf, &
        & drift_projection, drift_none
    use rollcon_output_layout, only : output_layout_type
    use rollcon_watch, only : watch_measure_type
    implicit none
    private

    public :: run_summary_type, judge_drift
    public :: status_completed, status_stopped, status_failed, status_inaccurate

    !> How a run ended: as planned, at an event limit, by a failure, or at its end or a limit
    !> with an energy drift or a watch's measure beyond what its tolerances promise
    integer, parameter :: status_completed = 0, status_stopped = 1, status_failed = 2, &
        & status_inaccurate = 3
    !> What a run did
    type :: run_summary_type
        integer :: status = status_completed
        !> Why it stopped, when it did not complete
        character(len=:), allocatable :: message
        !> The limit that stopped it (status_stopped), a word of the watch that set it:
        !> "theta_limit", "liftoff", "fall", "rolling_held", …; "" when none did
        character(len=:), allocatable :: limit
        !> SUNDIALS' flag when the integrator failed (status_failed), else 0
        integer :: solver_flag = 0
        !> Time reached [s]: of the last output row, or where the integrator failed
        real(wp) :: t_reached = 0.0_wp
        !> Final coordinates and rates
        real(wp), allocatable :: q(:), u(:)
        !> Energy at the reference time (start, or end of the last force pulse) [J]
        real(wp) :: energy_reference = 0.0_wp
        !> Largest |E - E_reference| after the reference time, relative to energy_scale (0
        !> when the scale is 0: nothing moved)
        real(wp) :: energy_drift = 0.0_wp
        !> The energy scale over the rows after the reference time [J]: the larger of the
        !> largest kinetic energy and the range of the potential energy (rollcon_drift)
        real(wp) :: energy_scale = 0.0_wp
        !> The mean over those rows of what one step's error test allows the energy [J]
        !> (rollcon_equations energy_tolerance)
        real(wp) :: energy_step = 0.0_wp
        !> The explicit work of the constraint forces over those rows [J]: the integral of
        !> problem%constraint_power by the trapezoidal rule (a moving constraint's work)
        real(wp) :: constraint_work = 0.0_wp
        !> The energy dissipated over those rows [J]: a sliding contact's friction's and a rim's
        !> rolling resistance's and air layer's work (problem%dissipated_power integrated with
        !> the state by the integrator: integrator_type work; by the trapezoidal rule over the
        !> rows from one that does not) and the impacts' losses (exact,
        !> rollcon_contact_impact): the energy judged is E plus it. Its parts the friction's and
        !> the impacts' [J]
        real(wp) :: dissipated_work = 0.0_wp, friction_work = 0.0_wp, impact_work = 0.0_wp
        !> The work the drives of moving planes (a turntable's MOTION) did on the parts in the
        !> impacts over those rows [J], signed: V_table . P of each impulse P
        !> (rollcon_contact_watch), exact as the impacts' losses are; the energy judged is E + W
        !> less it. (The drives' work between impacts, a sliding contact's on a turntable or a
        !> moving constraint's, is constraint_work's, which leaves the energy not judged.)
        real(wp) :: drive_work = 0.0_wp
        !> The rows' trapezoidal rule's estimated error in dissipated_work [J]
        !> (rollcon_simulation record), subtracted from |E + W - E0|; 0 when the integrator
        !> integrated W with the state. Beyond the drift allowed the rows do not resolve the
        !> dissipated power and the energy is not judged (dissipation_resolved)
        real(wp) :: dissipation_uncertainty = 0.0_wp
        !> False when W came from the rows' rule, a contact's friction or impacts dissipated
        !> and dissipation_uncertainty exceeds the drift allowed: the output rows are too far
        !> apart for the dissipated work to be known to the allowance (a finer output_step
        !> resolves it), and the energy is not judged
        logical :: dissipation_resolved = .true.
        !> False when an applied force acts after the reference time (rollcon_force
        !> forces_idle_after) or the constraints do work (constraint_work beyond work_fraction of
        !> the drift allowed, rollcon_drift): the energy is then not conserved, and its drift
        !> not judged
        logical :: energy_conserved = .true.
        !> What the rows hold: the parts and UCONs (their ids, in model order) and the watches'
        !> columns
        type(output_layout_type) :: layout
        !> Largest |F_k| over the output rows and every UCON (the UCON's own unit)
        real(wp) :: residual_max = 0.0_wp
        !> Largest |F_k| over the output rows, for each UCON (model order)
        real(wp), allocatable :: ucon_residual_max(:)
        !> For each UCON: a position-level (holonomic) one, F in its coordinates' units; else a
        !> velocity-level one, F in their units per second
        logical, allocatable :: ucon_position(:)
        !> What the energy drift is allowed (rollcon_drift), relative to energy_scale; 0 when
        !> not judged
        real(wp) :: energy_bound = 0.0_wp
        !> The watches' measures, with their bounds (a rim contact's height residual, ...)
        type(watch_measure_type), allocatable :: measures(:)
        !> The watches' own lines for the summary text
        character(len=:), allocatable :: watch_lines
        !> Which routine served each statement, in words ("UCON 1: the model's UCOSUB, UCON 4:
        !> disk_height, JOINT/1 (line 14): gnd_atpoint, gnd_parallel_axes")
        character(len=:), allocatable :: routines
        !> Each UCON in the user's words, a line each ("UCON 3", "JOINT/1 (line 14), its
        !> translation along ground X"): the residual lines' names
        character(len=:), allocatable :: ucon_labels
        !> For each part (model order), its re-basings (docs/rebasing.md): the final q and u
        !> are in the principal axes turned that many times
        integer, allocatable :: rebasings(:)
        !> Integrator statistics, summed over the run's segments between re-basings: steps,
        !> right-hand sides or residuals, Newton matrices, error-test failures, event-function
        !> evaluations
        integer :: steps = 0, functions = 0, jacobians = 0, failures = 0, root_evaluations = 0
        !> Times the integrator started again at a corner of an input (a force's switch or a
        !> pulse's end: docs/design.md §7)
        integer :: corner_restarts = 0
        !> The Newton matrix was solved by SUNDIALS' sparse KLU (the summary says so: 'auto'
        !> chooses it on large sparse models)
        logical :: sparse_newton = .false.
        !> Output rows written (64 bits: a long run at a fine step passes 2**31)
        integer(int64) :: rows = 0
        !> CPU time of the integration [s]
        real(wp) :: cpu_seconds = 0.0_wp
        !> Which analysis ran, when not a dynamic run alone, with what it found (a static
        !> equilibrium's iterations and imbalance: rollcon_static_equilibrium), lines each ending
        !> in a newline; "" or unallocated for a dynamic run
        character(len=:), allocatable :: analysis_lines
    contains
        procedure :: measure
    end type run_summary_type

contains

    !> The watches' measure of this name (its value and bound); a measure of value 0 and no
    !> name when the run took none.
    function measure(self, name) result(found)
        class(run_summary_type), intent(in) :: self
        character(len=*), intent(in) :: name
        type(watch_measure_type) :: found
        integer :: k

        found%name = ""
        if (.not. allocated(self%measures)) return
        do k = 1, size(self%measures)
            if (self%measures(k)%name == name) then
                found = self%measures(k)
                return
            end if
        end do
    end function measure

    !> Judge a run that reached its end or a limit against what its tolerances promise: the
    !> energy drift (rollcon_drift) and every watch's measure that has a bound. Beyond a bound
    !> its results are not what was asked: status_inaccurate, with the measures, the bounds and
    !> the remedies that apply to the run's settings in the message.
    subroutine judge_drift(summary, settings)
        type(run_summary_type), intent(inout) :: summary
        !> The run's settings (tolerances; the integrator and its drift control, for the remedy)
        type(run_settings_type), intent(in) :: settings
        character(len=:), allocatable :: findings, bounds, remedies
        real(wp) :: allowed
        integer :: k

        if (summary%status /= status_completed .and. summary%status /= status_stopped) return
        summary%energy_bound = 0.0_wp
        findings = ""
        bounds = ""
        remedies = ""
        ! a scale of 0: nothing moved and nothing fell, so there is no drift to judge
        if (summary%energy_scale > 0.0_wp) then
            allowed = energy_bound(summary%steps, summary%energy_step, summary%energy_scale)
            ! constraints that do work: a change of energy is no drift
            if (summary%constraint_work > work_fraction*allowed) &
                & summary%energy_conserved = .false.
            ! a contact's friction or impacts in a dissipated work known only to more than the
            ! allowance (from the rows' rule: W integrated with the state has no such estimate):
            ! no verdict either way (a rim's rolling resistance and air alone vary smoothly: the
            ! estimate is subtracted and the drift judged)
            if (summary%dissipation_uncertainty > allowed .and. (summary%friction_work /= 0.0_wp &
                & .or. summary%impact_work /= 0.0_wp)) summary%dissipation_resolved = .false.
            if (summary%energy_conserved .and. summary%dissipation_resolved) &
                & summary%energy_bound = allowed/summary%energy_scale
        end if
        if (summary%energy_bound > 0.0_wp) then
            bounds = "for the energy the smaller of " // to_text(energy_allowance) &
                & // " sqrt(N) times the " // short(summary%energy_step) // " J one step's " &
                & // "tolerance allows it and " // to_text(energy_fraction) // " of its scale"
            if (.not. summary%energy_drift <= summary%energy_bound) then
                findings = findings // "; energy drift " &
                    & // short(summary%energy_drift*summary%energy_scale) // " J (" &
                    & // short(summary%energy_drift) // " of the energy scale " &
                    & // short(summary%energy_scale) // " J) > " &
                    & // short(summary%energy_bound*summary%energy_scale) // " J allowed"
                remedies = energy_remedies(settings)
            end if
        end if
        if (allocated(summary%measures)) then
            do k = 1, size(summary%measures)
                associate (m => summary%measures(k))
                    if (.not. m%bound > 0.0_wp) cycle
                    if (len(bounds) > 0) bounds = bounds // ", "
                    bounds = bounds // m%bound_rule // " for the " // m%name
                    if (m%value <= m%bound) cycle
                    findings = findings // "; " // m%label(index(m%label, " ") + 1:) // " " &
                        & // to_text(m%value) // " " // m%unit // " > " // to_text(m%bound) &
                        & // " " // m%unit // " allowed"
                    if (index(remedies, m%remedy) == 0) then
                        if (len(remedies) > 0) remedies = remedies // ", "
                        remedies = remedies // m%remedy
                    end if
                end associate
            end do
        end if
        if (len(findings) == 0) return
        if (index(remedies, "a tighter rtol") == 0) then
            if (len(remedies) > 0) remedies = remedies // " or "
            remedies = remedies // "a tighter rtol (now " // to_text(settings%rtol) // ")"
        end if
        findings = findings(3:) // " (bounds: " // bounds // ", after N = " &
            & // to_text(summary%steps) // " steps; use " // remedies // ")"
        if (summary%status == status_stopped) then
            summary%message = summary%message // "; and the results drifted: " // findings
        else
            summary%message = "the run reached t = " // to_text(summary%t_reached) &
                & // " s but its results drifted beyond what its tolerances promise: " // findings
        end if
        summary%status = status_inaccurate
    end subroutine judge_drift

    !> A value in 4 significant digits (1.982E-08).
    pure function short(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: value

        write(value, '(es11.3e3)') x
        text = trim(adjustl(value))
    end function short

    !> What may bring an energy drift within its bound, among the settings the run's
    !> integrator takes and does not use already: CVODE's projection onto the constraints
    !> (BDF only; Adams takes Baumgarte terms), then a tighter rtol (docs/outputs.md).
    pure function energy_remedies(settings) result(text)
        type(run_settings_type), intent(in) :: settings
        character(len=:), allocatable :: text

        text = ""
        if (settings%formulation == formulation_ida) then
            text = ""
        else if (settings%method == method_bdf .and. settings%drift /= drift_projection) then
            text = "drift = 'projection' (a dataset's INTEGRATOR/DRIFT=PROJECTION)"
        else if (settings%method /= method_bdf .and. settings%drift == drift_none) then
            text = "drift = 'baumgarte' (a dataset's INTEGRATOR/DRIFT=BAUMGARTE)"
        end if
    end function energy_remedies

end module rollcon_run_summary
