! SPDX-License-Identifier: MIT
!> Which output rows an animation shows: nothing is interpolated, each frame is a row.
module rollcon_animation_rows
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: frame_rows

contains

    !> Rows shown by an animation with one frame every interval seconds: for k = 0, 1, ... up to
    !> the last row's time, the row whose time is nearest to times(1) + k interval (the earlier
    !> row on a tie). A row is shown at most once, so when the rows are further apart than
    !> interval there is one frame per row. times must not decrease.
    pure function frame_rows(times, interval) result(rows)
        !> Times of the output rows [s]
        real(wp), intent(in) :: times(:)
        !> Time between frames [s], > 0
        real(wp), intent(in) :: interval
        !> Indices into times, increasing
        integer, allocatable :: rows(:)
        integer, allocatable :: picked(:)
        real(wp) :: target
        integer :: n, k, k_last, j, count

        n = size(times)
        allocate(rows(0))
        if (n == 0 .or. .not. interval > 0.0_wp) return
        ! A frame time within 1e-9 of a step past the last row still counts (rounding).
        ! as a real first: an interval far below the rows' spacing must not overflow the count
        k_last = floor(min((times(n) - times(1))/interval + 1.0e-9_wp, &
            & real(huge(k_last) - 1, wp)))
        allocate(picked(min(n, k_last + 1)))
        count = 0
        j = 1
        do k = 0, k_last
            target = times(1) + real(k, wp)*interval
            do while (j < n)
                if (abs(times(j + 1) - target) >= abs(times(j) - target)) exit
                j = j + 1
            end do
            if (count > 0) then
                if (picked(count) == j) cycle
            end if
            if (count == size(picked)) exit
            count = count + 1
            picked(count) = j
        end do
        rows = picked(:count)
    end function frame_rows

end module rollcon_animation_rows
