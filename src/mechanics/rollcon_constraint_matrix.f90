! SPDX-License-Identifier: MIT
!> C, the constraint matrix of the saddle-point system (docs/design.md §4, "Memory"), held by
!> rows: row k over UCON k's own coordinates only (dF_k/du, or dF_k/dq for a position UCON),
!> as compressed rows whose pattern is the constraint blocks' `ucon_start`/`ucon_coordinates`
!> (the same index x: value(x) is C(k, column(x)) for x in start(k) : start(k + 1) - 1). Every
!> other entry is an exact zero. Its storage is linear in the model (a chain of N links holds
!> about 60 N reals where the dense nc x n array held 30 N^2). Readers go through the row
!> operations below, or loop over start/column/value themselves on a hot path.
module rollcon_constraint_matrix
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: constraint_matrix_type

    !> C (nc x n) by rows over each UCON's coordinates
    type :: constraint_matrix_type
        !> Coordinates n and rows (UCONs) nc
        integer :: n = 0, nc = 0
        !> Row k's entries: column(start(k) : start(k + 1) - 1), ascending, each once
        integer, allocatable :: start(:), column(:)
        !> The entries' values [a row's units per coordinate's unit]
        real(wp), allocatable :: value(:)
    contains
        procedure :: init
        procedure :: entry
        procedure :: entry_along
        procedure :: gather
        procedure :: row_dot
        procedure :: add_row
        procedure :: fill_row
        procedure :: times
        procedure :: transpose_times
        procedure :: dense
    end type constraint_matrix_type

contains

    !> Size C (n coordinates, nc rows) on the pattern start (nc + 1), column (start(nc + 1) - 1,
    !> each row's columns ascending and in 1..n); every value zero.
    subroutine init(self, n, nc, start, column)
        class(constraint_matrix_type), intent(inout) :: self
        integer, intent(in) :: n, nc, start(:), column(:)

        self%n = n
        self%nc = nc
        self%start = start(:nc + 1)
        self%column = column(:start(nc + 1) - 1)
        if (allocated(self%value)) deallocate(self%value)
        allocate(self%value(start(nc + 1) - 1), source=0.0_wp)
    end subroutine init

    !> C(k, j): row k (1..nc), column j (1..n); zero off row k's pattern.
    pure real(wp) function entry(self, k, j)
        class(constraint_matrix_type), intent(in) :: self
        integer, intent(in) :: k, j
        integer :: x

        entry = 0.0_wp
        do x = self%start(k), self%start(k + 1) - 1
            if (self%column(x) == j) then
                entry = self%value(x)
                return
            else if (self%column(x) > j) then
                return
            end if
        end do
    end function entry

    !> C(k, j) on a walk along row k with j ascending: x is the row's next entry (start(k) at
    !> the walk's start), moved past column j when the row has it; zero off the pattern. A
    !> whole row read as the dense one, one entry a column, without a search.
    pure subroutine entry_along(self, k, j, x, value)
        class(constraint_matrix_type), intent(in) :: self
        integer, intent(in) :: k, j
        integer, intent(inout) :: x
        real(wp), intent(out) :: value

        value = 0.0_wp
        if (x >= self%start(k + 1)) return
        if (self%column(x) /= j) return
        value = self%value(x)
        x = x + 1
    end subroutine entry_along

    !> out(i) = C(k, first + i - 1) for i = 1..size(out): a contiguous slice of row k (a part's
    !> six coordinates, say), zeros off its pattern. The slice must lie in 1..n.
    pure subroutine gather(self, k, first, out)
        class(constraint_matrix_type), intent(in) :: self
        integer, intent(in) :: k, first
        real(wp), intent(out) :: out(:)
        integer :: x, j

        out = 0.0_wp
        do x = self%start(k), self%start(k + 1) - 1
            j = self%column(x) - first + 1
            if (j > size(out)) return
            if (j >= 1) out(j) = self%value(x)
        end do
    end subroutine gather

    !> C(k, :) . v, v of length n.
    pure real(wp) function row_dot(self, k, v) result(total)
        class(constraint_matrix_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(in) :: v(:)
        integer :: x

        total = 0.0_wp
        do x = self%start(k), self%start(k + 1) - 1
            total = total + self%value(x)*v(self%column(x))
        end do
    end function row_dot

    !> y = y + s C(k, :), y of length n.
    pure subroutine add_row(self, k, s, y)
        class(constraint_matrix_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(in) :: s
        real(wp), intent(inout) :: y(:)
        integer :: x

        do x = self%start(k), self%start(k + 1) - 1
            y(self%column(x)) = y(self%column(x)) + s*self%value(x)
        end do
    end subroutine add_row

    !> row = C(k, :), dense (length n).
    pure subroutine fill_row(self, k, row)
        class(constraint_matrix_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(out) :: row(:)
        integer :: x

        row = 0.0_wp
        do x = self%start(k), self%start(k + 1) - 1
            row(self%column(x)) = self%value(x)
        end do
    end subroutine fill_row

    !> y = C v: v of length n, y of length nc.
    pure subroutine times(self, v, y)
        class(constraint_matrix_type), intent(in) :: self
        real(wp), intent(in) :: v(:)
        real(wp), intent(out) :: y(:)
        integer :: k

        do k = 1, self%nc
            y(k) = self%row_dot(k, v)
        end do
    end subroutine times

    !> y = C^T lambda: lambda of length nc, y of length n (a constraint force's generalised
    !> force is -C^T lambda).
    pure subroutine transpose_times(self, lambda, y)
        class(constraint_matrix_type), intent(in) :: self
        real(wp), intent(in) :: lambda(:)
        real(wp), intent(out) :: y(:)
        integer :: k

        y = 0.0_wp
        do k = 1, self%nc
            call self%add_row(k, lambda(k), y)
        end do
    end subroutine transpose_times

    !> C as a dense nc x n array, for the dense analyses (static, linear, kinematic) and the
    !> tests that compare against a dense solve; never on a path sized by the model's growth.
    pure subroutine dense(self, d)
        class(constraint_matrix_type), intent(in) :: self
        real(wp), allocatable, intent(out) :: d(:, :)
        integer :: k, x

        allocate(d(self%nc, self%n), source=0.0_wp)
        do k = 1, self%nc
            do x = self%start(k), self%start(k + 1) - 1
                d(k, self%column(x)) = self%value(x)
            end do
        end do
    end subroutine dense

end module rollcon_constraint_matrix
