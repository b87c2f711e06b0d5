! SPDX-License-Identifier: MIT
!> The rows a picture draws (suite figure-rows): a run of many rows is thinned to at most
!> figure_rows rows for a figure, and a spike between them survives (a figure of 10^6 rows took
!> gnuplot 5.5 minutes); a short run is drawn whole; the animation's paths keep at most
!> path_points points.
module test_figure_rows
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_figure_rows, only : write_figure_rows, path_stride, figure_rows, path_points
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_figure_rows

contains

    subroutine collect_figure_rows(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("long-run-thinned-spike-kept", test_thinned), &
            & new_unittest("short-run-whole", test_whole), &
            & new_unittest("path-stride", test_stride)]
    end subroutine collect_figure_rows

    !> 10^6 rows of (t, sin t, a path x): one spike of 7 at row 123457 in column 2; the
    !> figure gets at most figure_rows rows, column 2's largest value is the spike, its
    !> smallest -1 (sin's), and the path column keeps rows of its own (first and last).
    subroutine test_thinned(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 1000000
        real(wp), allocatable :: data(:, :), read_back(:, :)
        integer :: j, unit, stat, rows

        allocate(data(3, n))
        do j = 1, n
            data(:, j) = [1.0e-3_wp*j, sin(1.0e-3_wp*j), real(j, wp)]
        end do
        data(2, 123457) = 7.0_wp
        open(newunit=unit, status="scratch", action="readwrite", form="formatted")
        call write_figure_rows(unit, data, [.false., .false., .true.], stat)
        call check(error, stat == 0, "write failed")
        if (allocated(error)) return
        rewind(unit)
        allocate(read_back(3, figure_rows + 1))
        rows = 0
        do
            read(unit, *, iostat=stat) read_back(:, min(rows + 1, size(read_back, 2)))
            if (stat /= 0) exit
            rows = rows + 1
        end do
        close(unit)
        call check(error, rows <= figure_rows .and. rows > figure_rows/2, to_text(rows) &
            & // " rows written (at most " // to_text(figure_rows) // ")")
        if (allocated(error)) return
        call check(error, maxval(read_back(2, :rows)) == 7.0_wp .and. &
            & minval(read_back(2, :rows)) < -0.999_wp, "column 2 between " &
            & // to_text(minval(read_back(2, :rows))) // " and " &
            & // to_text(maxval(read_back(2, :rows))) // " (the spike of 7 lost?)")
        if (allocated(error)) return
        call check(error, read_back(3, 1) == 1.0_wp .and. read_back(3, rows) == real(n, wp), &
            & "the path column does not keep its own first and last rows")
    end subroutine test_thinned

    !> Fewer rows than figure_rows: every row, unchanged.
    subroutine test_whole(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: data(2, 50), back(2)
        integer :: j, unit, stat, rows

        data(1, :) = [(real(j, wp), j = 1, 50)]
        data(2, :) = data(1, :)**2
        open(newunit=unit, status="scratch", action="readwrite", form="formatted")
        call write_figure_rows(unit, data, [.false., .false.], stat)
        rewind(unit)
        rows = 0
        do
            read(unit, *, iostat=stat) back
            if (stat /= 0) exit
            rows = rows + 1
            if (any(back /= data(:, rows))) exit
        end do
        close(unit)
        call check(error, rows, 50, "rows read back unchanged")
    end subroutine test_whole

    !> A path keeps every row up to path_points rows, then at most path_points points.
    subroutine test_stride(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: n

        call check(error, path_stride(path_points), 1, "stride at path_points rows")
        if (allocated(error)) return
        n = 1000003
        call check(error, (n - 1)/path_stride(n) + 1 <= path_points, "points of a path of " &
            & // to_text(n) // " rows: " // to_text((n - 1)/path_stride(n) + 1))
    end subroutine test_stride

end module test_figure_rows
