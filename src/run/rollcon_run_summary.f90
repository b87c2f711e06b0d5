! SPDX-License-Identifier: MIT
!> What a run did and how it ended (status, measures, counters, re-basings), and the judge of
!> its drift against what its tolerances promise (rollcon_drift for the energy, each watch for
!> its own measures).
module rollcon_run_summary
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_drift, only : energy_bound, energy_allowance
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
        !> "theta_limit", "liftoff"; "" when none did
        character(len=:), allocatable :: limit
        !> SUNDIALS' flag when the integrator failed (status_failed), else 0
        integer :: solver_flag = 0
        !> Time reached [s]: of the last output row, or where the integrator failed
        real(wp) :: t_reached = 0.0_wp
        !> Final coordinates and rates
        real(wp), allocatable :: q(:), u(:)
        !> Energy at the reference time (start, or end of the last force pulse) [J]
        real(wp) :: energy_reference = 0.0_wp
        !> Largest |E - E_reference| / |E_reference| after the reference time
        real(wp) :: energy_drift = 0.0_wp
        !> False when an applied force acts after the reference time (rollcon_force
        !> forces_idle_after) or a UCON moves (problem%ucons_do_no_work): the energy is then not
        !> conserved, and its drift not judged
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
        !> What the energy drift is allowed (rollcon_drift); 0 when not judged
        real(wp) :: energy_bound = 0.0_wp
        !> The watches' measures, with their bounds (a rim contact's height residual, ...)
        type(watch_measure_type), allocatable :: measures(:)
        !> The watches' own lines for the summary text
        character(len=:), allocatable :: watch_lines
        !> Which routine served each UCON, in words ("UCON 1: the model's UCOSUB, UCON 4:
        !> disk_height")
        character(len=:), allocatable :: routines
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
    !> its results are not what was asked: status_inaccurate, with the measures and bounds in
    !> the message.
    subroutine judge_drift(summary, rtol)
        type(run_summary_type), intent(inout) :: summary
        !> The run's relative tolerance
        real(wp), intent(in) :: rtol
        character(len=:), allocatable :: findings, bounds, remedies
        integer :: k

        if (summary%status /= status_completed .and. summary%status /= status_stopped) return
        summary%energy_bound = energy_bound(summary%steps, rtol)
        ! no reference energy to be relative to: not judged
        if (summary%energy_reference == 0.0_wp) summary%energy_bound = 0.0_wp
        ! forces doing work after the reference: a change of energy is no drift
        if (.not. summary%energy_conserved) summary%energy_bound = 0.0_wp
        findings = ""
        bounds = to_text(energy_allowance) // " sqrt(N) rtol for the energy"
        remedies = "use drift = 'projection'"
        if (summary%energy_bound > 0.0_wp .and. &
            & .not. summary%energy_drift <= summary%energy_bound) findings = findings &
            & // "; energy drift " // to_text(summary%energy_drift) // " > " &
            & // to_text(summary%energy_bound) // " allowed"
        if (allocated(summary%measures)) then
            do k = 1, size(summary%measures)
                associate (m => summary%measures(k))
                    if (.not. m%bound > 0.0_wp) cycle
                    bounds = bounds // ", " // m%bound_rule // " for the " // m%name
                    remedies = remedies // ", " // m%remedy
                    if (m%value <= m%bound) cycle
                    findings = findings // "; " // m%label(index(m%label, " ") + 1:) // " " &
                        & // to_text(m%value) // " " // m%unit // " > " // to_text(m%bound) &
                        & // " " // m%unit // " allowed"
                end associate
            end do
        end if
        if (len(findings) == 0) return
        findings = findings(3:) // " (bounds: " // bounds // ", after N = " &
            & // to_text(summary%steps) // " steps; " // remedies // " or a tighter rtol)"
        if (summary%status == status_stopped) then
            summary%message = summary%message // "; and the results drifted: " // findings
        else
            summary%message = "the run reached t = " // to_text(summary%t_reached) &
                & // " s but its results drifted beyond what its tolerances promise: " // findings
        end if
        summary%status = status_inaccurate
    end subroutine judge_drift

end module rollcon_run_summary
