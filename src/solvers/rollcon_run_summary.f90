! SPDX-License-Identifier: MIT
!> What a run did and how it ended (status, measures, counters, re-basings), and the judge of
!> its drift against what its tolerances promise (rollcon_drift).
module rollcon_run_summary
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_drift, only : drift_bounds, drift_findings
    use rollcon_output_layout, only : output_layout_type
    implicit none
    private

    public :: run_summary_type, judge_drift
    public :: status_completed, status_stopped, status_failed, status_inaccurate
    public :: limit_none, limit_theta, limit_liftoff

    !> How a run ended: as planned, at an event limit, by a failure, or at its end or a limit
    !> with an energy or height drift beyond what its tolerances promise (rollcon_drift)
    integer, parameter :: status_completed = 0, status_stopped = 1, status_failed = 2, &
        & status_inaccurate = 3
    !> Which limit stopped a run: none, a part's theta limit (&limits theta_min, the Euler
    !> singularity), or the lift-off of the part in contact
    integer, parameter :: limit_none = 0, limit_theta = 1, limit_liftoff = 2
    !> What a run did
    type :: run_summary_type
        integer :: status = status_completed
        !> Why it stopped, when it did not complete
        character(len=:), allocatable :: message
        !> The limit that stopped it (status_stopped): limit_theta or limit_liftoff
        integer :: limit = limit_none
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
        !> What the rows hold: the parts and UCONs (their ids, in model order) and whether the
        !> model has a watched contact
        type(output_layout_type) :: layout
        !> Largest |F_k| over the output rows and every UCON (the UCON's own unit)
        real(wp) :: residual_max = 0.0_wp
        !> Largest |F_k| over the output rows, for each UCON (model order)
        real(wp), allocatable :: ucon_residual_max(:)
        !> For each UCON: a position-level (holonomic) one, F in its coordinates' units; else a
        !> velocity-level one, F in their units per second
        logical, allocatable :: ucon_position(:)
        !> Largest position-level residual |Z - R sin(theta)| of the part in contact [m] (0
        !> when the problem has no watched contact)
        real(wp) :: height_residual_max = 0.0_wp
        !> What the tolerances allow of energy_drift and height_residual_max (rollcon_drift);
        !> 0 when not judged
        real(wp) :: energy_bound = 0.0_wp, height_bound = 0.0_wp
        !> For each part (model order), its re-basings (docs/rebasing.md): the final q and u
        !> are in the principal axes turned that many times
        integer, allocatable :: rebasings(:)
        !> Integrator statistics
        integer :: steps = 0, functions = 0, jacobians = 0, failures = 0
        !> Output rows written (64 bits: a long run at a fine step passes 2**31)
        integer(int64) :: rows = 0
        !> CPU time of the integration [s]
        real(wp) :: cpu_seconds = 0.0_wp
    end type run_summary_type

contains

    !> Judge a run that reached its end or a limit against what its tolerances promise
    !> (rollcon_drift): beyond a bound its results are not what was asked, status_inaccurate,
    !> with the measures and bounds in the message.
    subroutine judge_drift(problem, summary)
        type(problem_type), intent(in) :: problem
        type(run_summary_type), intent(inout) :: summary
        character(len=:), allocatable :: findings

        if (summary%status /= status_completed .and. summary%status /= status_stopped) return
        call drift_bounds(problem, summary%steps, summary%energy_bound, summary%height_bound)
        ! no reference energy to be relative to: not judged
        if (summary%energy_reference == 0.0_wp) summary%energy_bound = 0.0_wp
        ! forces doing work after the reference: a change of energy is no drift
        if (.not. summary%energy_conserved) summary%energy_bound = 0.0_wp
        findings = drift_findings(summary%steps, summary%energy_drift, summary%energy_bound, &
            & summary%height_residual_max, summary%height_bound)
        if (len(findings) == 0) return
        if (summary%status == status_stopped) then
            summary%message = summary%message // "; and the results drifted: " // findings
        else
            summary%message = "the run reached t = " // to_text(summary%t_reached) &
                & // " s but its results drifted beyond what its tolerances promise: " // findings
        end if
        summary%status = status_inaccurate
    end subroutine judge_drift

end module rollcon_run_summary
