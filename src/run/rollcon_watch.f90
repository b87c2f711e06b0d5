! SPDX-License-Identifier: MIT
!> What a run watches besides the parts, UCONs and forces every run has: a pluggable watch
!> brings its own event functions (and what the run does when one fires: stop, re-base a part,
!> or start the integrator again), its own output columns, its own measures judged against what
!> the tolerances promise, and its own summary lines. The driver (rollcon_simulation) knows
!> watches only through this interface: a part's Euler-angle limit (rollcon_theta_watch), a
!> rim's contact with the ground (rollcon_contact_watch) and the switches of force expressions
!> on the state (rollcon_switch_watch) are three of them.
!>
!> A watch works on the model's equations (rollcon_equations): the state it is given and, when
!> the integrator knows them without a solve, the multipliers or the accelerations at it.
!> Event functions and columns never allocate (the hot path); prepare sizes what they need.
module rollcon_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    implicit none
    private

    public :: watch_type, watch_slot_type, watch_measure_type, watch_event_type
    public :: action_stop, action_rebase, action_restart, action_corner, append_watch

    !> What the run does when a watch's event function fires: stop there (a limit the input
    !> sets: the run ends `stopped`, exit status 0), re-base a part's principal axes and go
    !> on (docs/rebasing.md), let the watch change the problem (restart_problem: the rows
    !> set aside as redundant chosen again) and start the integrator again from the same state,
    !> or start the integrator again there with no history, the problem unchanged (an input's
    !> corner: docs/design.md §7)
    integer, parameter :: action_stop = 1, action_rebase = 2, action_restart = 3, &
        & action_corner = 4

    !> The watch's answer when one of its event functions fired
    type :: watch_event_type
        integer :: action = action_stop
        !> The part to re-base (model order), with action_rebase
        integer :: part = 0
        !> Which limit stopped the run, a word for tables (a study's outcome): "theta_limit",
        !> "liftoff"
        character(len=:), allocatable :: limit
        !> Why the run stopped, in words, with the time and the state
        character(len=:), allocatable :: message
    end type watch_event_type

    !> A measure a watch took over the output rows, and its bound
    type :: watch_measure_type
        !> Short name, for code and tables ("height_residual")
        character(len=:), allocatable :: name
        !> What it is, for the summary ("largest height residual |Z - R sin(theta)|")
        character(len=:), allocatable :: label
        !> Its unit ("m"; "" for none)
        character(len=:), allocatable :: unit
        real(wp) :: value = 0.0_wp
        !> What the tolerances allow (0: not judged), how the bound is made ("3 sqrt(N)
        !> (atol + rtol R)") and the remedy when it is passed ("height = 'position'")
        real(wp) :: bound = 0.0_wp
        character(len=:), allocatable :: bound_rule, remedy
    end type watch_measure_type

    type, abstract :: watch_type
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: roots_use_accelerations
        procedure :: fired
        procedure :: restart_problem
        procedure :: start_problem
        procedure :: stop_request
        procedure :: part_rebased
        procedure :: parts_to_rebase
        procedure :: column_names
        procedure :: take_accelerations
        procedure :: fill_columns
        procedure :: measures
        procedure :: summary_lines
    end type watch_type

    !> A watch in an array of watches of any kinds
    type :: watch_slot_type
        class(watch_type), allocatable :: watch
    end type watch_slot_type

contains

    !> Before a run: check what the watch refers to against the model (eq%model), size its
    !> scratch arrays and forget the measures of any earlier run. A refusal is an error.
    subroutine prepare(self, eq, settings, error)
        class(watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
    end subroutine prepare

    !> Number of event functions (default none).
    pure integer function root_count(self, eq)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = 0
    end function root_count

    !> The event functions at (t, q, u): root_count() values into g. lambda: the multipliers
    !> at the state when the integrator carries them (IDA); a: the accelerations when it knows
    !> them (CVODE's polynomial). ierr: 0, or -1 with error set.
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)

        g = 0.0_wp
    end subroutine roots

    !> Its event functions use the accelerations a when the integrator gives them (roots), so
    !> that the integrator should work them out (default: they do not).
    pure logical function roots_use_accelerations(self, eq)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        roots_use_accelerations = .false.
    end function roots_use_accelerations

    !> Event function k (of this watch's) fired at (t, q, u): what the run does.
    function fired(self, eq, k, time, q, u) result(event)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event

        event%limit = "event"
        event%message = "an event"
    end function fired

    !> The change an event of action_restart asks for, made at (t, q, u) before the run starts
    !> the integrator again from that state (default: none). A watch may change the rates u
    !> there (an impact's jump of the velocities); the run restarts from the rates it leaves.
    subroutine restart_problem(self, eq, time, q, u, error)
        class(watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(error_type), allocatable, intent(out) :: error
    end subroutine restart_problem

    !> A new state (t, q, u): the start, before the integrator is set up on it, or rates that
    !> a watch's restart_problem made jump (an impact): a watch may set a mode of the
    !> equations there (default: nothing).
    subroutine start_problem(self, eq, time, q, u, error)
        class(watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
    end subroutine start_problem

    !> A stop the watch's last start_problem or restart_problem found (a state its equations
    !> do not model): the run records the row there and stops with this event (action
    !> action_stop); any other action: none (the default).
    function stop_request(self) result(event)
        class(watch_type), intent(in) :: self
        type(watch_event_type) :: event

        event%action = action_restart
    end function stop_request

    !> The run re-based part p (model order): its coordinates are now in its principal axes
    !> turned once more (docs/rebasing.md).
    subroutine part_rebased(self, p, turn)
        class(watch_type), intent(inout) :: self
        !> The part (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn
    end subroutine part_rebased

    !> The parts (model order) to re-base before the first row, at the start (q) as given
    !> (default none).
    function parts_to_rebase(self, eq, q) result(parts)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: q(:)
        integer, allocatable :: parts(:)

        allocate(parts(0))
    end function parts_to_rebase

    !> Names of the columns this watch adds to the rows (default none).
    subroutine column_names(self, eq, names)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)

        allocate(names(0))
    end subroutine column_names

    !> The accelerations at the output row fill_columns is about to be given (the equations of
    !> motion's at that state, as the run's last evaluation there left them: a [m/s^2, rad/s^2],
    !> one per coordinate), for a watch whose columns read them (default: not kept).
    subroutine take_accelerations(self, eq, a)
        class(watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: a(:)
    end subroutine take_accelerations

    !> The values of its columns at an output row (t, q, u), with the equations as the run's
    !> last evaluation at this state left them and its multipliers lambda; the watch takes its
    !> measures here (called once per output row).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)

        values = 0.0_wp
    end subroutine fill_columns

    !> Its measures after a run of steps integrator steps, with their bounds (default none).
    function measures(self, eq, settings, steps) result(taken)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        type(run_settings_type), intent(in) :: settings
        integer, intent(in) :: steps
        type(watch_measure_type), allocatable :: taken(:)

        allocate(taken(0))
    end function measures

    !> Lines for the run's summary, each ending in a new line ("" for none).
    function summary_lines(self, eq) result(text)
        class(watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=:), allocatable :: text

        text = ""
    end function summary_lines

    !> A copy of watch at the end of slots (allocated empty first if need be).
    subroutine append_watch(slots, watch)
        type(watch_slot_type), allocatable, intent(inout) :: slots(:)
        class(watch_type), intent(in) :: watch
        type(watch_slot_type), allocatable :: grown(:)
        integer :: k

        if (.not. allocated(slots)) allocate(slots(0))
        allocate(grown(size(slots) + 1))
        do k = 1, size(slots)
            call move_alloc(slots(k)%watch, grown(k)%watch)
        end do
        allocate(grown(size(grown))%watch, source=watch)
        call move_alloc(grown, slots)
    end subroutine append_watch

end module rollcon_watch
