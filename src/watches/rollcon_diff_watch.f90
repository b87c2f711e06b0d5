! SPDX-License-Identifier: MIT
!> A dataset's DIFFs as columns (docs/outputs.md, "DIFF columns"): per DIFF/id, `diff<id>`,
!> its state DIF(id) in its user's units, and `diff<id>_dot`, its rate DIF1(id) in those units
!> per the dataset's time unit, at each output row. The state is the one the formulation last
!> unpacked (the row's: rollcon_diff, kept in the model's diffs); the rate solves the DIFFs'
!> equations there (rollcon_diff's solve_rates), so it is the row's own, whatever the
!> integrator last evaluated.
module rollcon_diff_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : diff_column_patterns
    use rollcon_watch, only : watch_type
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: diff_watch_type, diff_column_name

    type, extends(watch_type) :: diff_watch_type
    contains
        procedure :: column_names
        procedure :: fill_columns
    end type diff_watch_type

contains

    !> Column `which` (1: the state, 2: its rate) of DIFF/id: diff<id>, diff<id>_dot.
    pure function diff_column_name(id, which) result(name)
        integer, intent(in) :: id, which
        character(len=name_length) :: name
        character(len=:), allocatable :: pattern

        pattern = trim(diff_column_patterns(which))
        name = pattern(:index(pattern, "<n>") - 1) // to_text(id) &
            & // pattern(index(pattern, "<n>") + 3:)
    end function diff_column_name

    !> diff<id>, diff<id>_dot for every DIFF, in the model's order.
    subroutine column_names(self, eq, names)
        class(diff_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: k

        associate (diffs => eq%model%diffs)
            allocate(names(2*diffs%count()))
            do k = 1, diffs%count()
                names(2*k - 1) = diff_column_name(diffs%diffs(k)%id, 1)
                names(2*k) = diff_column_name(diffs%diffs(k)%id, 2)
            end do
        end associate
    end subroutine column_names

    !> Each DIFF's DIF and DIF1 at the row (module header); DIF1 NaN where its equations
    !> cannot be solved there (the run has stopped on that error already).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(diff_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        real(wp), allocatable :: w(:)
        type(error_type), allocatable :: error
        integer :: k

        associate (diffs => eq%model%diffs)
            w = diffs%w
            call diffs%solve_rates(time, q, u, diffs%x, w, error)
            if (allocated(error)) w = ieee_value(1.0_wp, ieee_quiet_nan)
            do k = 1, diffs%count()
                values(2*k - 1) = diffs%x(k)
                values(2*k) = w(k)
            end do
        end associate
    end subroutine fill_columns

end module rollcon_diff_watch
