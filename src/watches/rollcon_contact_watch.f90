! SPDX-License-Identifier: MIT
!> A rim rolling on the ground: the contact of a part that touches the ground plane Z = 0 as a
!> rim of radius R about its body z-axis (a rolling disk, a coin, a wheel). The watch adds the
!> constraint force on the part, its normal part, the friction coefficient rolling needs and the
!> height residual Z - R sin(theta) to every output row; it may stop the run where the normal
!> force turns negative (the part would leave the ground, which a rolling constraint cannot
!> represent); and it judges the height residual, the position-level form of the contact that
!> a velocity-level UCON holds only through its integral, against what the tolerances promise.
module rollcon_contact_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    !> The columns it adds, in order (named where a CSV reader finds them too)
    use rollcon_watch_columns, only : contact_names
    use rollcon_watch, only : watch_type, watch_event_type, watch_measure_type, action_stop
    implicit none
    private

    public :: contact_watch_type, height_allowance

    !> K_H of the height residual's bound K_H sqrt(N) (atol + rtol R) after N steps: independent
    !> local errors add up like a random walk (rollcon_drift); measured on the data/ scenes,
    !> sound runs reach at most 0.82 of sqrt(N) (atol + rtol R), drift = 'none' 4.8 to 7800
    real(wp), parameter :: height_allowance = 3.0_wp

    type, extends(watch_type) :: contact_watch_type
        !> The part in contact (model order) and its rim radius [m] > 0
        integer :: part = 1
        real(wp) :: radius = 0.0_wp
        !> Stop where the normal force falls below -liftoff_force: a real lift-off, not the
        !> rounding noise of a force that is zero
        logical :: stop_on_liftoff = .false.
        !> Lift-off threshold [N] >= 0, a small fraction of the model's force scale
        real(wp) :: liftoff_force = 0.0_wp
        !> Largest |Z - R sin(theta)| over the output rows so far [m]
        real(wp) :: height_residual_max = 0.0_wp
        !> Scratch of an event function that must solve for the multipliers
        real(wp), allocatable :: a(:), lambda(:)
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: roots_use_accelerations
        procedure :: fired
        procedure :: column_names
        procedure :: fill_columns
        procedure :: measures
        procedure :: height_residual
    end type contact_watch_type

contains

    !> The part must be one of the model's and the radius positive.
    subroutine prepare(self, eq, settings, error)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        if (self%part < 1 .or. self%part > size(eq%model%parts)) then
            call fatal_error(error, "the part in contact is number " // to_text(self%part) &
                & // " in model order; the model has " // to_text(size(eq%model%parts)) &
                & // " parts", stat_input)
            return
        else if (.not. self%radius > 0.0_wp) then
            call fatal_error(error, "the contact of part " &
                & // to_text(eq%model%parts(self%part)%id) // " needs a rim radius > 0 [m], " &
                & // "got " // to_text(self%radius), stat_input)
            return
        end if
        if (allocated(self%a)) deallocate(self%a)
        if (allocated(self%lambda)) deallocate(self%lambda)
        allocate(self%a(eq%n), self%lambda(eq%nc), source=0.0_wp)
        self%height_residual_max = 0.0_wp
    end subroutine prepare

    !> The lift-off, when watched.
    pure integer function root_count(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = merge(1, 0, self%stop_on_liftoff)
    end function root_count

    !> The normal force on the part + liftoff_force. The normal force comes from the multipliers
    !> when a DAE state gives them (IDA), else from the accelerations when the integrator gives
    !> them (CVODE's polynomial: no UCOSUB call and no solve), else from a saddle-point solve as
    !> in a right-hand side.
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)
        real(wp) :: force(3)

        if (present(lambda)) then
            ! only C is needed: first partials, no saddle-point solve
            call eq%constraint_matrix_at(time, q, u, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, lambda)
        else if (present(a)) then
            force = eq%reaction_from_accelerations(self%part, time, q, u, a)
        else
            call eq%accelerations(time, q, u, settings%baumgarte(), self%a, self%lambda, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, self%lambda)
        end if
        g(1) = force(3) + self%liftoff_force
    end subroutine roots

    !> The lift-off's normal force comes from the accelerations when they are given.
    pure logical function roots_use_accelerations(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        roots_use_accelerations = self%root_count(eq) > 0
    end function roots_use_accelerations

    !> The lift-off: the run stops.
    function fired(self, eq, k, time, q, u) result(event)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event
        integer :: p

        p = self%part
        event%action = action_stop
        event%limit = "liftoff"
        event%message = "the normal contact force turned negative (below -" &
            & // to_text(self%liftoff_force) // " N) at t = " // to_text(time) &
            & // " s (theta = " // to_text(q(6*p - 1)) // " rad, thetadot = " &
            & // to_text(u(6*p - 1)) // " rad/s): the disk would leave the " &
            & // "ground, which a rolling constraint cannot represent"
    end function fired

    subroutine column_names(self, eq, names)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)

        allocate(names(size(contact_names)))
        names(:) = contact_names
    end subroutine column_names

    !> Force, normal force, friction needed, height residual (and its largest magnitude).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        real(wp) :: force(3), height

        force = eq%constraint_force(self%part, lambda)
        height = self%height_residual(q)
        self%height_residual_max = max(self%height_residual_max, abs(height))
        values(1:3) = force
        values(4) = force(3)
        values(5) = 0.0_wp
        if (force(3) > 0.0_wp) values(5) = norm2(force(1:2))/force(3)
        values(6) = height
    end subroutine fill_columns

    !> Z - R sin(theta) of the part in contact [m].
    pure real(wp) function height_residual(self, q)
        class(contact_watch_type), intent(in) :: self
        !> Coordinates of every part
        real(wp), intent(in) :: q(:)
        integer :: i0

        i0 = 6*(self%part - 1)
        height_residual = q(i0 + 3) - self%radius*sin(q(i0 + 5))
    end function height_residual

    !> The largest height residual, bound K_H sqrt(N) (atol + rtol R).
    function measures(self, eq, settings, steps) result(taken)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        type(run_settings_type), intent(in) :: settings
        integer, intent(in) :: steps
        type(watch_measure_type), allocatable :: taken(:)

        allocate(taken(1))
        taken(1)%name = "height_residual"
        taken(1)%label = "largest height residual |Z - R sin(theta)|"
        taken(1)%unit = "m"
        taken(1)%value = self%height_residual_max
        taken(1)%bound = height_allowance*sqrt(real(max(1, steps), wp)) &
            & *(settings%atol + settings%rtol*self%radius)
        taken(1)%bound_rule = to_text(height_allowance) // " sqrt(N) (atol + rtol R)"
        taken(1)%remedy = "height = 'position'"
    end function measures

end module rollcon_contact_watch
