! SPDX-License-Identifier: MIT
!> The force or torque each MOTION takes to drive its motion (docs/outputs.md, "MOTION
!> columns"): one column per MOTION of the model, the multiplier of its UCON F = s(q) - h(t)
!> (rollcon_motion). Its generalised force on the parts is lambda dF/dq = lambda ds/dq, so
!> lambda is the force on marker I's part along the axis of J that s measures along (a
!> translation, `motion<id>_force` [N]) or the torque on it about the axis s turns about (an
!> angle, `motion<id>_torque` [N m]); the reaction on J's part is its opposite. For a slider of
!> mass m driven along the unit axis e under gravity g: lambda = m (x'' - g.e).
module rollcon_motion_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : motion_column_patterns
    use rollcon_watch, only : watch_type
    implicit none
    private

    public :: motion_watch_type, motion_column_name

    type, extends(watch_type) :: motion_watch_type
        !> The MOTION UCONs' places in the model (model order) and their MOTIONs' ids
        integer, allocatable :: ucon(:), id(:)
        !> Each one drives an angle (a torque column) rather than a displacement
        logical, allocatable :: rotational(:)
    contains
        procedure :: prepare
        procedure :: column_names
        procedure :: fill_columns
    end type motion_watch_type

contains

    !> The column of MOTION/id: motion<id>_force, or motion<id>_torque for an angle.
    pure function motion_column_name(id, rotational) result(name)
        integer, intent(in) :: id
        logical, intent(in) :: rotational
        character(len=name_length) :: name
        character(len=:), allocatable :: pattern

        pattern = trim(motion_column_patterns(merge(2, 1, rotational)))
        name = pattern(:index(pattern, "<n>") - 1) // to_text(id) &
            & // pattern(index(pattern, "<n>") + 3:)
    end function motion_column_name

    !> The model's MOTION UCONs, in model order.
    subroutine prepare(self, eq, settings, error)
        class(motion_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        ! a second prepare (the bench prepares one problem twice) starts again from none
        if (allocated(self%ucon)) deallocate(self%ucon, self%id, self%rotational)
        allocate(self%ucon(0), self%id(0), self%rotational(0))
        if (.not. allocated(eq%model%ucons)) return
        do k = 1, size(eq%model%ucons)
            associate (ucon => eq%model%ucons(k))
                if (.not. allocated(ucon%motion)) cycle
                self%ucon = [self%ucon, k]
                self%id = [self%id, ucon%motion%id]
                self%rotational = [self%rotational, ucon%motion%rotational]
            end associate
        end do
    end subroutine prepare

    !> motion<id>_force or motion<id>_torque for every MOTION.
    subroutine column_names(self, eq, names)
        class(motion_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: k

        allocate(names(size(self%ucon)))
        do k = 1, size(self%ucon)
            names(k) = motion_column_name(self%id(k), self%rotational(k))
        end do
    end subroutine column_names

    !> Each MOTION's multiplier (module header).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(motion_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)

        values(:size(self%ucon)) = lambda(self%ucon)
    end subroutine fill_columns

end module rollcon_motion_watch
