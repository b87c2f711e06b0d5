! SPDX-License-Identifier: MIT
!> Helpers of the study tests: a study CSV's lines, its rows without the CPU time (the one
!> column that differs between runs), sorted, and a CSV cut short as a killed run leaves it.
module study_rows
    implicit none
    private

    public :: csv_rows, without_cpu, sorted, remove_file, cut_after

    !> Longest line the helpers keep
    integer, parameter :: line_length = 2048

contains

    !> The lines of a text file (none when it is missing).
    function csv_rows(path) result(rows)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: rows(:)
        character(len=line_length) :: line
        integer :: unit, stat, n

        allocate(character(len=line_length) :: rows(0))
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        n = 0
        do
            read(unit, "(a)", iostat=stat) line
            if (stat /= 0) exit
            rows = [character(len=line_length) :: rows, line]
        end do
        close(unit)
    end function csv_rows

    !> The rows without their cpu_s field, the one before the quoted message that ends a row.
    pure function without_cpu(rows) result(kept)
        character(len=*), intent(in) :: rows(:)
        character(len=len(rows)) :: kept(size(rows))
        integer :: i, quote, comma

        do i = 1, size(rows)
            quote = index(rows(i), ',"', back=.true.)
            comma = 0
            if (quote > 1) comma = index(rows(i)(:quote - 1), ",", back=.true.)
            if (comma > 0) then
                kept(i) = rows(i)(:comma) // rows(i)(quote + 1:)
            else
                kept(i) = rows(i)
            end if
        end do
    end function without_cpu

    !> The rows in ascending order (insertion sort: the tests' files are small).
    pure function sorted(rows) result(order)
        character(len=*), intent(in) :: rows(:)
        character(len=len(rows)) :: order(size(rows)), item
        integer :: i, j

        order = rows
        do i = 2, size(order)
            item = order(i)
            j = i - 1
            do while (j >= 1)
                if (order(j) <= item) exit
                order(j + 1) = order(j)
                j = j - 1
            end do
            order(j + 1) = item
        end do
    end function sorted

    subroutine remove_file(path)
        character(len=*), intent(in) :: path
        integer :: unit, stat

        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete")
    end subroutine remove_file

    !> Copy the first `lines` lines of source to target, then `partial` characters of the next
    !> line without its line end: a file as a run killed while writing a row leaves it.
    subroutine cut_after(source, target, lines, partial)
        character(len=*), intent(in) :: source, target
        integer, intent(in) :: lines, partial
        character(len=:), allocatable :: rows(:)
        integer :: unit, i

        rows = csv_rows(source)
        call remove_file(target)
        open(newunit=unit, file=target, access="stream", form="unformatted", status="new", &
            & action="write")
        do i = 1, lines
            write(unit) trim(rows(i)) // achar(10)
        end do
        write(unit) rows(lines + 1)(:partial)
        close(unit)
    end subroutine cut_after

end module study_rows
