! SPDX-License-Identifier: MIT
!> The values of a model's user VARIABLEs (VARIABLE/id, FUNCTION=USER(...): a VARSUB's) at the
!> state last evaluated (rollcon_user_forces' evaluate_user_variables), which an expression's
!> VARVAL(id) reads (rollcon_measures), and their partials in the parts' coordinates and
!> rates where a Newton matrix is formed (rollcon_user_forces' difference_user_variables:
!> central differences over what each VARSUB declared), which VARVAL's jets carry. ADAMS's
!> VARVAL takes no handle and the routines run in a process of their own, one model per
!> process: the values are module state, as rollcon_user_forces' table.
module rollcon_user_variable_values
    use rollcon_kinds, only : wp
    use rollcon_jet, only : jet_type, jet_constant, operator(+), operator(-), operator(*)
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: set_user_variable_values, user_variable_value, user_variable_jet
    public :: set_user_variable_partials, clear_user_variable_partials, user_variable_parts
    public :: set_user_variable_parts

    integer, allocatable, save :: ids(:)
    real(wp), allocatable, save :: values(:)
    !> dv_dq(k, j), dv_du(k, j): variable k's partials in q(j), u(j) of all parts [dataset's
    !> units per m, rad, m/s, rad/s]; not allocated: none known (taken as zero)
    real(wp), allocatable, save :: dv_dq(:, :), dv_du(:, :)
    !> reads(k, p): variable k's VARSUB declared a marker of model part p (its initialisation
    !> call); not allocated: none declared
    logical, allocatable, save :: reads(:, :)

contains

    !> The values of the user VARIABLEs of these ids (in the dataset's units).
    subroutine set_user_variable_values(variable_ids, variable_values)
        integer, intent(in) :: variable_ids(:)
        real(wp), intent(in) :: variable_values(:)

        ids = variable_ids
        values = variable_values
    end subroutine set_user_variable_values

    !> The partials of the user VARIABLEs of these ids at the state last evaluated: q_partials(k,
    !> j) = d VARVAL(ids(k))/d q(j), u_partials likewise (q and u of all parts, SI).
    subroutine set_user_variable_partials(variable_ids, q_partials, u_partials)
        integer, intent(in) :: variable_ids(:)
        real(wp), intent(in) :: q_partials(:, :), u_partials(:, :)

        ids = variable_ids
        dv_dq = q_partials
        dv_du = u_partials
    end subroutine set_user_variable_partials

    !> Which model parts each VARIABLE's VARSUB declared it reads (reads(k, p) for the k-th of
    !> the ids given to set_user_variable_values): the parts its partials may involve.
    subroutine set_user_variable_parts(parts_read)
        logical, intent(in) :: parts_read(:, :)

        reads = parts_read
    end subroutine set_user_variable_parts

    !> Forget the partials: VARVAL's jets are constants again.
    subroutine clear_user_variable_partials()
        if (allocated(dv_dq)) deallocate(dv_dq)
        if (allocated(dv_du)) deallocate(dv_du)
    end subroutine clear_user_variable_partials

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

    !> VARVAL(id) as a jet over the variables of the held parts' coordinates q_jets(:, s) and
    !> rates u_jets(:, s) (parts(s): model index): its value, and its partials as set by
    !> set_user_variable_partials chained through those jets (first order: a VARSUB's second
    !> partials are not known); a constant when no partials are set.
    pure function user_variable_jet(id, parts, q_jets, u_jets) result(value)
        integer, intent(in) :: id, parts(:)
        type(jet_type), intent(in) :: q_jets(:, :), u_jets(:, :)
        type(jet_type) :: value
        integer :: k, s, c, j

        value = jet_constant(user_variable_value(id))
        if (.not. allocated(dv_dq) .or. .not. allocated(ids)) return
        k = findloc(ids, id, dim=1)
        if (k == 0) return
        do s = 1, size(parts)
            do c = 1, 6
                j = 6*(parts(s) - 1) + c
                if (j > size(dv_dq, 2)) cycle
                if (dv_dq(k, j) /= 0.0_wp) value = value + dv_dq(k, j)*(q_jets(c, s) &
                    & - q_jets(c, s)%v)
                if (dv_du(k, j) /= 0.0_wp) value = value + dv_du(k, j)*(u_jets(c, s) &
                    & - u_jets(c, s)%v)
            end do
        end do
    end function user_variable_jet

    !> The model parts (indices) whose coordinates or rates VARVAL(id)'s partials may involve:
    !> those of the markers its VARSUB declared (set_user_variable_parts); none before that.
    pure function user_variable_parts(id) result(parts)
        integer, intent(in) :: id
        integer, allocatable :: parts(:)
        integer :: k, p

        allocate(parts(0))
        if (.not. allocated(reads) .or. .not. allocated(ids)) return
        k = findloc(ids, id, dim=1)
        if (k == 0 .or. k > size(reads, 1)) return
        do p = 1, size(reads, 2)
            if (reads(k, p)) parts = [parts, p]
        end do
    end function user_variable_parts

end module rollcon_user_variable_values
