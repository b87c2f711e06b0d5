! SPDX-License-Identifier: MIT
!> The rows set aside as redundant (rollcon_redundancy) chosen again when their choice wears:
!> one event function per block with rows set aside, its margin (the smallest singular value of
!> the block's active unit rows, on a large block the smallest |R(k,k)| of their sparse QR,
!> less measure_ratio of its value at the choice), so that the
!> integrator finds where the choice has worn at whatever step it happens, not only at an
!> output row. When one fires the run chooses the block's rows again at that state
!> (restart_problem, with the ranks of the first choice) and starts the integrator again from
!> the same state, as after a re-basing (docs/design.md §4, "Redundant constraints"). A model
!> without rows set aside has no event function here, no column and no summary line.
module rollcon_redundancy_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_watch, only : watch_type, watch_event_type, action_restart
    implicit none
    private

    public :: redundancy_watch_type

    type, extends(watch_type) :: redundancy_watch_type
        !> The choices again this run made (events that fired), and those that changed the
        !> rows set aside
        integer :: choices = 0, changes = 0
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: fired
        procedure :: restart_problem
        procedure :: summary_lines
    end type redundancy_watch_type

contains

    !> No choice again yet.
    subroutine prepare(self, eq, settings, error)
        class(redundancy_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        self%choices = 0
        self%changes = 0
    end subroutine prepare

    !> One per block with rows set aside (none before the run's choice at its start).
    pure integer function root_count(self, eq)
        class(redundancy_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = 0
        if (allocated(eq%redundancy%redundant)) root_count = count(eq%redundancy%redundant)
    end function root_count

    !> Each such block's margin at (t, q).
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(redundancy_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)

        call eq%redundancy_margins(time, q, u, g, error)
    end subroutine roots

    !> A block's choice has worn: choose again and restart.
    function fired(self, eq, k, time, q, u) result(event)
        class(redundancy_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event

        event%action = action_restart
        event%limit = "redundancy"
        event%message = ""
    end function fired

    !> Every block with rows set aside chosen again at (t, q, u) (one whose choice still suits
    !> keeps it, with the measure of now as its reference).
    subroutine restart_problem(self, eq, time, q, u, error)
        class(redundancy_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(error_type), allocatable, intent(out) :: error
        logical :: changed
        integer :: b

        do b = 1, eq%blocks%count
            if (.not. eq%redundancy%redundant(b)) cycle
            call eq%choose_block_again(b, time, q, u, changed, error)
            if (allocated(error)) return
            self%choices = self%choices + 1
            if (changed) self%changes = self%changes + 1
        end do
    end subroutine restart_problem

    !> "warning: redundant equations set aside (docs/design.md §4): ...; chosen again N times
    !> during the run, M of them setting other rows aside".
    function summary_lines(self, eq) result(text)
        class(redundancy_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=:), allocatable :: text

        text = ""
        if (.not. allocated(eq%redundancy%words)) return
        if (len(eq%redundancy%words) == 0) return
        text = "warning: redundant equations set aside (docs/design.md §4): " &
            & // eq%redundancy%words // "; chosen again " // to_text(self%choices) &
            & // " time(s) during the run as the configuration moved, " &
            & // to_text(self%changes) // " of them setting other equations aside" &
            & // new_line("a")
    end function summary_lines

end module rollcon_redundancy_watch
