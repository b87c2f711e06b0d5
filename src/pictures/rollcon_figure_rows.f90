! SPDX-License-Identifier: MIT
!> A run's rows thinned to what a picture can show. A figure of a few hundred pixels gains
!> nothing from a million rows, and gnuplot takes minutes to draw them; the animation redraws
!> each part's path up to every frame. Figures get at most figure_rows rows: beyond that, bins
!> of consecutive rows, each drawn as two rows, the bin's largest values at its first time and
!> its smallest at its last, so that a curve against time still covers every value it took (a
!> spike stays); columns drawn against each other (a path's X and Y) take the bin's first and
!> last rows instead. A path of the animation keeps at most path_points points, every k-th row.
module rollcon_figure_rows
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: write_figure_rows, path_stride, figure_rows, path_points

    !> Rows a figure's data holds at most (5000 bins of two rows: several per pixel of a
    !> figure 900 pixels wide)
    integer, parameter :: figure_rows = 10000
    !> Points of one part's path in the animation at most
    integer, parameter :: path_points = 5000

contains

    !> Write the columns of data (one column per row of the figure: data(:, j) is row j; its
    !> first entry is the time) to unit, thinned as the module says; paired(c) marks the
    !> entries drawn against each other. stat: the writes' iostat.
    subroutine write_figure_rows(unit, data, paired, stat)
        integer, intent(in) :: unit
        real(wp), intent(in) :: data(:, :)
        logical, intent(in) :: paired(:)
        integer, intent(out) :: stat
        real(wp) :: high(size(data, 1)), low(size(data, 1))
        integer :: n, k, first, last, j

        stat = 0
        n = size(data, 2)
        if (n <= figure_rows) then
            do j = 1, n
                if (stat == 0) write(unit, '(*(es24.16e3, :, 1x))', iostat=stat) data(:, j)
            end do
            return
        end if
        k = (n + figure_rows/2 - 1)/(figure_rows/2)
        do first = 1, n, k
            last = min(first + k - 1, n)
            high = maxval(data(:, first:last), dim=2)
            low = minval(data(:, first:last), dim=2)
            high(1) = data(1, first)
            low(1) = data(1, last)
            where (paired)
                high = data(:, first)
                low = data(:, last)
            end where
            if (stat == 0) write(unit, '(*(es24.16e3, :, 1x))', iostat=stat) high
            if (stat == 0) write(unit, '(*(es24.16e3, :, 1x))', iostat=stat) low
        end do
    end subroutine write_figure_rows

    !> Every how many rows a path of n rows keeps a point (1: all).
    pure integer function path_stride(n)
        integer, intent(in) :: n

        path_stride = max(1, (n + path_points - 1)/path_points)
    end function path_stride

end module rollcon_figure_rows
