! SPDX-License-Identifier: MIT
!> The switches of the model's force expressions that depend on the state (an IF of a
!> measure, MIN, MAX or DIM of measures, a STEP, STEP5, HAVSIN, IMPACT or BISTOP of a measure,
!> ABS or SIGN of one, or TIME in a way not affine: rollcon_expression's switch_kinds): each
!> is an event function, zero where its expression has a corner, and when one fires the run
!> starts the integrator again there with no history (docs/design.md §7). A switch on TIME
!> alone is a corner known in advance, a stop time of the run instead (force_corners). The
!> watch adds no columns and no summary lines.
module rollcon_switch_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_force, only : applied_force_type, profile_statement
    use rollcon_marker_force, only : marker_force_switches
    use rollcon_expression, only : switch_kinds, switch_count, switch_watched
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_watch, only : watch_type, watch_event_type, action_corner
    implicit none
    private

    public :: switch_watch_type, has_state_switches

    !> One force expression with watched switches
    type :: watched_expression_type
        !> The force (model order) and its expression (1 to 6: FX, FY, FZ, TX, TY, TZ)
        integer :: force = 0, slot = 0
        !> switch_kinds of the expression, and its first event function's place among the
        !> watch's and how many it has
        integer, allocatable :: kinds(:)
        integer :: first = 0, count = 0
    end type watched_expression_type

    type, extends(watch_type) :: switch_watch_type
        type(watched_expression_type), allocatable :: watched(:)
        !> Total number of event functions
        integer :: total = 0
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: fired
    end type switch_watch_type

    !> Names of a force statement's six expressions, for messages
    character(len=*), parameter :: slot_names(6) = ["FX", "FY", "FZ", "TX", "TY", "TZ"]

contains

    !> True when an expression of the forces switches on the state (or on TIME in a way
    !> switching_times cannot solve): the run then needs a switch watch.
    pure logical function has_state_switches(forces)
        type(applied_force_type), intent(in) :: forces(:)
        integer :: i, k

        has_state_switches = .false.
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            do k = 1, 6
                if (.not. forces(i)%statement%given(k)) cycle
                if (any(switch_kinds(forces(i)%statement%functions(k)) == switch_watched)) then
                    has_state_switches = .true.
                    return
                end if
            end do
        end do
    end function has_state_switches

    !> Find every expression of the model's forces with watched switches and number their
    !> event functions in force and expression order.
    subroutine prepare(self, eq, settings, error)
        class(switch_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        type(watched_expression_type) :: one
        integer :: i, k

        ! a second prepare (the bench prepares one problem twice) starts again from none
        if (allocated(self%watched)) deallocate(self%watched)
        allocate(self%watched(0))
        self%total = 0
        do i = 1, size(eq%model%forces)
            if (eq%model%forces(i)%profile /= profile_statement) cycle
            associate (statement => eq%model%forces(i)%statement)
                do k = 1, 6
                    if (.not. statement%given(k)) cycle
                    one%kinds = switch_kinds(statement%functions(k))
                    one%count = switch_count(statement%functions(k), one%kinds)
                    if (one%count == 0) cycle
                    one%force = i
                    one%slot = k
                    one%first = self%total + 1
                    self%total = self%total + one%count
                    self%watched = [self%watched, one]
                end do
            end associate
        end do
    end subroutine prepare

    pure integer function root_count(self, eq)
        class(switch_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = self%total
    end function root_count

    !> Every watched switch function at (t, q, u), in the order prepare numbered them.
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(switch_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)
        integer :: w

        do w = 1, size(self%watched)
            associate (one => self%watched(w))
                call marker_force_switches(eq%model%forces(one%force)%statement, one%slot, &
                    & time, q, u, one%kinds, g(one%first:one%first + one%count - 1))
            end associate
        end do
    end subroutine roots

    !> A switch of an expression switched: start the integrator again there.
    function fired(self, eq, k, time, q, u) result(event)
        class(switch_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event
        integer :: w

        event%action = action_corner
        event%limit = "switch"
        event%message = "a force expression switched at t = " // to_text(time) // " s"
        do w = 1, size(self%watched)
            associate (one => self%watched(w))
                if (k < one%first .or. k >= one%first + one%count) cycle
                if (allocated(eq%model%forces(one%force)%name)) event%message = &
                    & eq%model%forces(one%force)%name // " " // trim(slot_names(one%slot)) &
                    & // " switched at t = " // to_text(time) // " s"
            end associate
        end do
    end function fired

end module rollcon_switch_watch
