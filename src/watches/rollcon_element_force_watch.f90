! SPDX-License-Identifier: MIT
!> The force of each SPRINGDAMPER and BUSHING as output columns (docs/outputs.md, "Springs
!> and bushings"): `springdamper<id>_fx, _fy, _fz, _tx, _ty, _tz` and `bushing<id>_fx ... _tz`,
!> the force [N] and torque [N m] the element exerts on the part of its marker I, at I's
!> origin, ground axes (its reaction on J's part is the opposite force and torque at the same
!> point), the suffixes of the statements' reactions (rollcon_watch_columns). Computed by the
!> one procedure that gives an element's force and torque (rollcon_marker_force's
!> marker_force_action), from the model's own markers, so a re-based part changes nothing.
module rollcon_element_force_watch
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_marker_force, only : kind_spring, marker_force_action
    use rollcon_spring_force, only : spring_bushing
    use rollcon_force, only : profile_statement
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : suffixes => reaction_suffixes
    use rollcon_watch, only : watch_type
    implicit none
    private

    public :: element_force_watch_type, watches_elements

    type, extends(watch_type) :: element_force_watch_type
    contains
        procedure :: column_names
        procedure :: fill_columns
    end type element_force_watch_type

contains

    !> True when the model holds a SPRINGDAMPER or BUSHING (whose columns this watch adds).
    pure logical function watches_elements(eq)
        type(equations_type), intent(in) :: eq
        integer :: i

        watches_elements = .false.
        if (.not. allocated(eq%model%forces)) return
        do i = 1, size(eq%model%forces)
            if (is_element(eq, i)) watches_elements = .true.
        end do
    end function watches_elements

    !> The model's force i is a SPRINGDAMPER or BUSHING.
    pure logical function is_element(eq, i)
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: i

        is_element = eq%model%forces(i)%profile == profile_statement
        if (is_element) is_element = eq%model%forces(i)%statement%kind == kind_spring
    end function is_element

    !> Six per element, in the model's order: `springdamper<id>_fx ... _tz`, `bushing<id>_...`.
    subroutine column_names(self, eq, names)
        class(element_force_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        character(len=:), allocatable :: stem
        integer :: i, c, n

        allocate(names(0))
        if (.not. allocated(eq%model%forces)) return
        n = count([(is_element(eq, i), i = 1, size(eq%model%forces))])
        deallocate(names)
        allocate(names(6*n))
        n = 0
        do i = 1, size(eq%model%forces)
            if (.not. is_element(eq, i)) cycle
            associate (s => eq%model%forces(i)%statement)
                stem = "springdamper"
                if (s%spring%kind == spring_bushing) stem = "bushing"
                do c = 1, 6
                    names(n + c) = stem // to_text(s%id) // trim(suffixes(c))
                end do
            end associate
            n = n + 6
        end do
    end subroutine column_names

    !> Each element's force and torque on I's part at the row (module header).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(element_force_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        integer :: i, n

        n = 0
        do i = 1, size(eq%model%forces)
            if (.not. is_element(eq, i)) cycle
            call marker_force_action(eq%model%forces(i)%statement, time, q, u, &
                & values(n + 1:n + 3), values(n + 4:n + 6))
            n = n + 6
        end do
    end subroutine fill_columns

end module rollcon_element_force_watch
