! SPDX-License-Identifier: MIT
!> What a run does between the integrator's chunks of steps on a long way to the next output
!> time (rollcon_integrator's chunk_watch_type): the progress line, so a long output interval
!> is not silent, and, once, word to the row sink that the steps grind: they are far finer
!> than a model the tolerance can follow needs (criterion in docs/design.md, "A long output
!> interval"). The sink of a run in a child process passes both on to its parent, which
!> writes them (rollcon_isolated_run).
module rollcon_grind_watch
    use rollcon_kinds, only : wp
    use rollcon_integrator, only : chunk_watch_type
    use rollcon_row_sink, only : row_sink_type
    use rollcon_progress, only : progress_type
    implicit none
    private

    public :: grind_watch_type, grinds

    !> A chunk grinds when its mean step is below this fraction of the way from its start to
    !> the output time (at that pace the way takes more than ten thousand steps) ...
    real(wp), parameter :: tiny_step_fraction = 1.0e-4_wp
    !> ... while at least this share of its steps are rejected
    real(wp), parameter :: failure_share = 0.25_wp

    type, extends(chunk_watch_type) :: grind_watch_type
        !> The run's progress lines
        type(progress_type), pointer :: progress => null()
        !> Where the run's rows go, told of the time and of grinding (none: nowhere)
        class(row_sink_type), pointer :: sink => null()
        !> The sink was told the steps grind (once a run)
        logical :: told = .false.
    contains
        procedure :: between_chunks
    end type grind_watch_type

contains

    !> A progress line at t_reached [s]; the sink told the time, and once that the steps grind
    !> (grinds).
    subroutine between_chunks(self, t_start, t_reached, t_out, steps, failures)
        class(grind_watch_type), intent(inout) :: self
        real(wp), intent(in) :: t_start, t_reached, t_out
        integer, intent(in) :: steps, failures
        logical :: grinding

        if (associated(self%progress)) call self%progress%report(t_reached)
        grinding = .not. self%told .and. grinds(t_start, t_reached, t_out, steps, failures)
        if (grinding) self%told = .true.
        if (associated(self%sink)) call self%sink%between_chunks(t_reached, grinding)
    end subroutine between_chunks

    !> A chunk of steps internal steps over [t_start, t_reached] [s] towards t_out [s], failures
    !> of them rejected (by the error test or for want of the corrector's convergence), grinds:
    !> its mean step is below tiny_step_fraction of the way t_out - t_start and at least
    !> failure_share of its steps were rejected (docs/design.md, "A long output interval").
    pure logical function grinds(t_start, t_reached, t_out, steps, failures)
        real(wp), intent(in) :: t_start, t_reached, t_out
        integer, intent(in) :: steps, failures

        grinds = .false.
        if (steps <= 0) return
        grinds = (t_reached - t_start)/real(steps, wp) < tiny_step_fraction*(t_out - t_start) &
            & .and. real(failures, wp) >= failure_share*real(steps, wp)
    end function grinds

end module rollcon_grind_watch
