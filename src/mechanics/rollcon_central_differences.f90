! SPDX-License-Identifier: MIT
!> Central differences of a user routine's values over chosen entries of a state vector: the
!> partials of code rollcon cannot see into (a force routine's, a VARSUB's, a DIFSUB's), as
!> ADAMS/Solver forms them with calls made with DFLAG = .TRUE. One code for every kind
!> (rollcon_user_force_partials, rollcon_user_forces' difference_user_variables, rollcon_diff).
!>
!> Value k's partial in entry y is (v_k(y + h) - v_k(y - h))/((y + h) - (y - h)) with
!> h = eps^(1/3) max(|y|, 1) (y in m, rad, m/s, rad/s, or a DIFF's own units): the truncation
!> error h^2 v'''/6 and the rounding error eps |v|/h then both stand near eps^(2/3) = 4e-11 of
!> the values' scale (|v| and its third partials over a unit of the state), the least their
!> sum can be. Dividing by the steps as represented: (y + h) - (y - h) may differ from 2 h.
module rollcon_central_differences
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: difference_step, central_differences, shifted_values_interface

    abstract interface
        !> The values of a routine at the state with one entry shifted (shifted: the whole
        !> vector); failed when the call failed (its error kept by the caller's routine).
        subroutine shifted_values_interface(shifted, values, failed)
            import :: wp
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed
        end subroutine shifted_values_interface
    end interface

contains

    !> The step of a central difference in a state entry of value y: eps^(1/3) max(|y|, 1)
    !> (module doc).
    elemental real(wp) function difference_step(y) result(h)
        real(wp), intent(in) :: y

        h = epsilon(1.0_wp)**(1.0_wp/3.0_wp)*max(abs(y), 1.0_wp)
    end function difference_step

    !> gradients(e, :) = the values' partials in y(entries(e)) by central differences, two
    !> calls of evaluate each (module doc); a row whose calls failed is left as it is.
    subroutine central_differences(y, entries, evaluate, gradients)
        !> The state the differences are taken about
        real(wp), intent(in) :: y(:)
        !> The entries of y to difference
        integer, intent(in) :: entries(:)
        procedure(shifted_values_interface) :: evaluate
        !> size(entries) x the number of values
        real(wp), intent(inout) :: gradients(:, :)
        real(wp) :: shifted(size(y)), plus(size(gradients, 2)), minus(size(gradients, 2)), &
            & h, high, low
        integer :: e
        logical :: failed_plus, failed_minus

        do e = 1, size(entries)
            shifted = y
            h = difference_step(y(entries(e)))
            high = y(entries(e)) + h
            low = y(entries(e)) - h
            shifted(entries(e)) = high
            call evaluate(shifted, plus, failed_plus)
            shifted(entries(e)) = low
            call evaluate(shifted, minus, failed_minus)
            if (.not. (failed_plus .or. failed_minus)) &
                & gradients(e, :) = (plus - minus)/(high - low)
        end do
    end subroutine central_differences

end module rollcon_central_differences
