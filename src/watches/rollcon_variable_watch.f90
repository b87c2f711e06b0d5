! SPDX-License-Identifier: MIT
!> A dataset's VARIABLEs as columns (docs/outputs.md, "VARIABLE columns"): one column
!> `var<id>` per VARIABLE/id, its FUNCTION's value at each output row, in the units the
!> expression gives in the dataset's units (a length in its length unit, a force in its force
!> unit, ...), as ADAMS reports a VARIABLE. The expression is the one VARVAL(id) reads, its
!> VARIABLEs in place (rollcon_adm_variables); its measures are of the model's markers, turned
!> with the parts a run re-bases, so the column is the same in any basis.
module rollcon_variable_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_expression, only : expression_type, evaluate_expression, max_inputs
    use rollcon_marker, only : marker_type, turn_marker
    use rollcon_measures, only : expression_input_values, count_turns
    use rollcon_diff, only : diff_inputs
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : variable_column_patterns
    use rollcon_watch, only : watch_type
    implicit none
    private

    public :: variable_watch_type, watched_variable_type, new_variable_watch
    public :: variable_column_name

    !> One VARIABLE: its id, its expression and the markers it reads as the model holds them
    type :: watched_variable_type
        integer :: id = 0
        type(expression_type) :: function
        type(marker_type), allocatable :: markers(:)
    end type watched_variable_type

    type, extends(watch_type) :: variable_watch_type
        !> The VARIABLEs, their markers in the model's current axes, and as given (each
        !> part's own principal axes)
        type(watched_variable_type), allocatable :: variables(:), own(:)
        !> Size of the dataset's length [m] and time [s] units
        real(wp) :: length_unit = 1.0_wp, time_unit = 1.0_wp
    contains
        procedure :: prepare
        procedure :: part_rebased
        procedure :: column_names
        procedure :: fill_columns
    end type variable_watch_type

contains

    !> A watch of these VARIABLEs in a dataset of these units [m, s].
    function new_variable_watch(variables, length_unit, time_unit) result(watch)
        type(watched_variable_type), intent(in) :: variables(:)
        real(wp), intent(in) :: length_unit, time_unit
        type(variable_watch_type) :: watch

        watch%own = variables
        watch%variables = variables
        watch%length_unit = length_unit
        watch%time_unit = time_unit
    end function new_variable_watch

    !> The column of VARIABLE/id: var<id>.
    pure function variable_column_name(id) result(name)
        integer, intent(in) :: id
        character(len=name_length) :: name
        character(len=:), allocatable :: pattern

        pattern = trim(variable_column_patterns(1))
        name = pattern(:index(pattern, "<n>") - 1) // to_text(id) &
            & // pattern(index(pattern, "<n>") + 3:)
    end function variable_column_name

    !> The markers as given (a run that re-based parts left them turned), the turns of their
    !> angles counted from none.
    subroutine prepare(self, eq, settings, error)
        class(variable_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        self%variables = self%own
    end subroutine prepare

    !> Part p's principal axes were turned: its markers in the new axes, as the model's.
    subroutine part_rebased(self, p, turn)
        class(variable_watch_type), intent(inout) :: self
        !> The part (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn
        integer :: k, m

        do k = 1, size(self%variables)
            do m = 1, size(self%variables(k)%markers)
                call turn_marker(self%variables(k)%markers(m), p, turn)
            end do
        end do
    end subroutine part_rebased

    !> var<id> for every VARIABLE.
    subroutine column_names(self, eq, names)
        class(variable_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: k

        allocate(names(size(self%variables)))
        do k = 1, size(self%variables)
            names(k) = variable_column_name(self%variables(k)%id)
        end do
    end subroutine column_names

    !> Each VARIABLE's value at (time, q, u) (module header); its AX, AY, AZ followed over
    !> whole turns from row to row (rollcon_measures' count_turns).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(variable_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        real(wp) :: inputs(max_inputs)
        integer :: k, n

        do k = 1, size(self%variables)
            associate (variable => self%variables(k))
                n = size(variable%function%inputs)
                call count_turns(variable%function, variable%markers, self%length_unit, &
                    & self%time_unit, q, u, .false.)
                call expression_input_values(variable%function, variable%markers, &
                    & self%length_unit, self%time_unit, q, u, inputs(:n))
                ! DIF, DIF1: the DIFFs' state at the row (rollcon_diff_watch's)
                if (eq%model%diffs%count() > 0) call diff_inputs(variable%function, &
                    & eq%model%diffs%ids, eq%model%diffs%x, eq%model%diffs%w, inputs(:n))
                values(k) = evaluate_expression(variable%function, time/self%time_unit, &
                    & inputs(:n))
            end associate
        end do
    end subroutine fill_columns

end module rollcon_variable_watch
