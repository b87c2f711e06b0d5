! SPDX-License-Identifier: MIT
!> The DIF(id) and DIF1(id) inputs of an expression valued from a DIFF state (x, w) (ADAMS's
!> DIFF statement, rollcon_diff): what a force's, a VARIABLE's or a DIFF's FUNCTION reads of
!> the DIFFs. Apart from rollcon_diff so that the forces, which the DIFFs' user routines
!> (DIFSUB, through rollcon_user_forces) come after, can read them.
module rollcon_diff_inputs
    use rollcon_kinds, only : wp
    use rollcon_jet, only : jet_type, jet_constant
    use rollcon_expression, only : expression_type, quantity_dif, quantity_dif1
    implicit none
    private

    public :: diff_inputs, diff_input_jets

contains

    !> The values of an expression's DIF(id) and DIF1(id) inputs from (x, w) of these DIFFs
    !> (ids), the other inputs left as they are. A DIF of no DIFF among ids is NaN (the
    !> dataset's reader refuses it first).
    pure subroutine diff_inputs(expression, ids, x, w, values)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)
        real(wp), intent(inout) :: values(:)
        integer :: n, k

        if (.not. allocated(expression%inputs)) return
        do n = 1, size(values)
            associate (input => expression%inputs(n))
                if (input%quantity /= quantity_dif .and. input%quantity /= quantity_dif1) cycle
                k = findloc(ids, input%marker, dim=1)
                values(n) = nan()
                if (k == 0) cycle
                if (input%quantity == quantity_dif) then
                    values(n) = x(k)
                else
                    values(n) = w(k)
                end if
            end associate
        end do
    end subroutine diff_inputs

    !> The jets of an expression's DIF(id) and DIF1(id) inputs as constants, from (x, w) of
    !> these DIFFs (ids), the other inputs left as they are (for a computation of partials in
    !> the parts' states alone, such as a static equilibrium's, where a DIFF is held).
    pure subroutine diff_input_jets(expression, ids, x, w, values)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)
        type(jet_type), intent(inout) :: values(:)
        real(wp) :: plain(size(values))
        integer :: n

        if (.not. allocated(expression%inputs)) return
        plain = 0.0_wp
        call diff_inputs(expression, ids, x, w, plain)
        do n = 1, size(values)
            associate (quantity => expression%inputs(n)%quantity)
                if (quantity == quantity_dif .or. quantity == quantity_dif1) &
                    & values(n) = jet_constant(plain(n))
            end associate
        end do
    end subroutine diff_input_jets

    pure function nan()
        use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
        real(wp) :: nan

        nan = ieee_value(nan, ieee_quiet_nan)
    end function nan

end module rollcon_diff_inputs
