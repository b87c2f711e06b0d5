! SPDX-License-Identifier: MIT
!> Where a sparse Newton matrix can hold nonzeros, as a compressed-column pattern (0-based row
!> indices, SUNDIALS' CSC layout): from a list of entries (what each element's block of the
!> matrix covers, gathered without an n x n array: memory and time O(entries)), from each
!> state's block (every entry of a block kept) or from a relation between states; and a dense
!> matrix copied onto a pattern.
module rollcon_newton_pattern
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: newton_pattern_type, pattern_of_blocks

    !> A compressed-column pattern of an n-square matrix: column j's rows (0-based)
    !> rows(starts(j) + 1 : starts(j + 1)), ascending
    type :: newton_pattern_type
        integer :: n = 0
        integer, allocatable :: starts(:), rows(:)
    contains
        procedure :: entries
        procedure :: from_entries
        procedure :: from_relation
        procedure :: gather
        procedure :: clear
    end type newton_pattern_type

contains

    !> The entries kept.
    pure integer function entries(self)
        class(newton_pattern_type), intent(in) :: self

        entries = 0
        if (allocated(self%starts)) entries = self%starts(self%n + 1)
    end function entries

    !> The entries (rows(e), columns(e)), e = 1 .. count (1-based, each in 1 .. n; repeats
    !> kept once), and the diagonal of an n-square matrix: by a count of each column's entries,
    !> then each column's rows sorted (insertion: a column holds a few dozen) and repeats
    !> dropped. Memory and time O(n + count); the pattern from_relation makes of the same
    !> relation.
    subroutine from_entries(self, n, rows, columns, count)
        class(newton_pattern_type), intent(inout) :: self
        integer, intent(in) :: n, rows(:), columns(:), count
        integer, allocatable :: fill(:), sorted(:)
        integer :: e, j, i, a, first, next, row

        self%n = n
        if (allocated(self%starts)) deallocate(self%starts, self%rows)
        ! each column's entries with its diagonal, placed by a count, then sorted in place
        allocate(fill(n + 1), source=1)
        do e = 1, count
            fill(columns(e) + 1) = fill(columns(e) + 1) + 1
        end do
        fill(1) = 0
        do j = 2, n + 1
            fill(j) = fill(j) + fill(j - 1)
        end do
        allocate(self%starts(n + 1), sorted(fill(n + 1)))
        self%starts = fill
        do j = 1, n
            fill(j) = fill(j) + 1
            sorted(fill(j)) = j - 1
        end do
        do e = 1, count
            j = columns(e)
            fill(j) = fill(j) + 1
            sorted(fill(j)) = rows(e) - 1
        end do
        next = 0
        do j = 1, n
            first = self%starts(j) + 1
            do i = first + 1, self%starts(j + 1)
                row = sorted(i)
                a = i - 1
                do while (a >= first)
                    if (sorted(a) <= row) exit
                    sorted(a + 1) = sorted(a)
                    a = a - 1
                end do
                sorted(a + 1) = row
            end do
            ! the column's distinct rows, packed after the previous columns'
            self%starts(j) = next
            do i = first, fill(j)
                if (i > first) then
                    if (sorted(i) == sorted(i - 1)) cycle
                end if
                next = next + 1
                sorted(next) = sorted(i)
            end do
        end do
        self%starts(n + 1) = next
        self%rows = sorted(:next)
    end subroutine from_entries

    !> Every entry (i, j) with keep(i, j) true, and the diagonal.
    subroutine from_relation(self, keep)
        class(newton_pattern_type), intent(inout) :: self
        logical, intent(in) :: keep(:, :)
        integer :: i, j, next

        self%n = size(keep, 2)
        if (allocated(self%starts)) deallocate(self%starts, self%rows)
        allocate(self%starts(self%n + 1), self%rows(count(keep) + self%n))
        next = 0
        do j = 1, self%n
            self%starts(j) = next
            do i = 1, self%n
                if (.not. (keep(i, j) .or. i == j)) cycle
                next = next + 1
                self%rows(next) = i - 1
            end do
        end do
        self%starts(self%n + 1) = next
        self%rows = self%rows(:next)
    end subroutine from_relation

    !> Every entry (i, j) of states of one block: blocks(i) == blocks(j). Each block's states
    !> listed once, by a count (block numbers from their least to their largest: a model's
    !> blocks number at most its states), each column then given its block's list: memory and
    !> time linear in the states and entries (no pass over every (i, j)).
    function pattern_of_blocks(blocks) result(pattern)
        integer, intent(in) :: blocks(:)
        type(newton_pattern_type) :: pattern
        integer, allocatable :: member_start(:), members(:), filled(:)
        integer :: low, b, i, j, n, total

        n = size(blocks)
        pattern%n = n
        if (n == 0) then
            allocate(pattern%starts(1), pattern%rows(0))
            pattern%starts(1) = 0
            return
        end if
        low = minval(blocks)
        allocate(member_start(maxval(blocks) - low + 2), source=0)
        do i = 1, n
            b = blocks(i) - low + 1
            member_start(b + 1) = member_start(b + 1) + 1
        end do
        total = 0
        do b = 2, size(member_start)
            total = total + member_start(b)**2
        end do
        member_start(1) = 1
        do b = 1, size(member_start) - 1
            member_start(b + 1) = member_start(b + 1) + member_start(b)
        end do
        allocate(members(n), filled(size(member_start) - 1), source=0)
        do i = 1, n
            b = blocks(i) - low + 1
            members(member_start(b) + filled(b)) = i - 1
            filled(b) = filled(b) + 1
        end do
        allocate(pattern%starts(n + 1), pattern%rows(total))
        pattern%starts(1) = 0
        do j = 1, n
            b = blocks(j) - low + 1
            pattern%starts(j + 1) = pattern%starts(j) + member_start(b + 1) - member_start(b)
            pattern%rows(pattern%starts(j) + 1:pattern%starts(j + 1)) = &
                & members(member_start(b):member_start(b + 1) - 1)
        end do
    end function pattern_of_blocks

    !> Zero the pattern's entries of the dense matrix full (the others are left as they are).
    pure subroutine clear(self, full)
        class(newton_pattern_type), intent(in) :: self
        real(wp), intent(inout) :: full(:, :)
        integer :: j, e

        do j = 1, self%n
            do e = self%starts(j) + 1, self%starts(j + 1)
                full(self%rows(e) + 1, j) = 0.0_wp
            end do
        end do
    end subroutine clear

    !> The pattern's entries of the dense matrix full, column by column (values(e) is entry e
    !> of the pattern).
    pure subroutine gather(self, full, values)
        class(newton_pattern_type), intent(in) :: self
        real(wp), intent(in) :: full(:, :)
        real(wp), intent(out) :: values(:)
        integer :: j, e

        do j = 1, self%n
            do e = self%starts(j) + 1, self%starts(j + 1)
                values(e) = full(self%rows(e) + 1, j)
            end do
        end do
    end subroutine gather

end module rollcon_newton_pattern
