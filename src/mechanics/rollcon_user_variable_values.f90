! SPDX-License-Identifier: MIT
!> The values of a model's user VARIABLEs (VARIABLE/id, FUNCTION=USER(...): a VARSUB's) at the
!> state last evaluated (rollcon_user_forces' evaluate_user_variables), which an expression's
!> VARVAL(id) reads (rollcon_measures). ADAMS's VARVAL takes no handle and the routines run in
!> a process of their own, one model per process: the values are module state, as
!> rollcon_user_forces' table.
module rollcon_user_variable_values
    use rollcon_kinds, only : wp
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: set_user_variable_values, user_variable_value

    integer, allocatable, save :: ids(:)
    real(wp), allocatable, save :: values(:)

contains

    !> The values of the user VARIABLEs of these ids (in the dataset's units).
    subroutine set_user_variable_values(variable_ids, variable_values)
        integer, intent(in) :: variable_ids(:)
        real(wp), intent(in) :: variable_values(:)

        ids = variable_ids
        values = variable_values
    end subroutine set_user_variable_values

    !> VARVAL(id) of a user VARIABLE at the state last evaluated, in the dataset's units; NaN
    !> for an id of no user VARIABLE (a VARIABLE of an expression is put in place by the
    !> dataset's reader and never read here).
    pure real(wp) function user_variable_value(id) result(value)
        integer, intent(in) :: id
        integer :: k

        value = ieee_value(1.0_wp, ieee_quiet_nan)
        if (.not. allocated(ids)) return
        k = findloc(ids, id, dim=1)
        if (k > 0) value = values(k)
    end function user_variable_value

end module rollcon_user_variable_values
