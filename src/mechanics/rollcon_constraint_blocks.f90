! SPDX-License-Identifier: MIT
!> The blocks of a model's constraints (docs/design.md §4, "Cost as models grow"): UCONs that
!> share a part belong to one block, and so do the parts they constrain. The saddle-point
!> system's Schur complement C M^-1 C^T and the independent speeds' partition are block
!> diagonal over them, so each is factored block by block: N independent disks cost N times
!> one disk, where the whole dense matrix cost N^3. Found once, from the UCONs' declared
!> variables (which parts a UCON touches never changes during a run).
module rollcon_constraint_blocks
    use rollcon_model, only : model_type
    use rollcon_ucosub_contract, only : max_ucon_vars
    implicit none
    private

    public :: constraint_blocks_type, ascending

    !> The blocks, each listing its UCONs and its coordinates in ascending order
    type :: constraint_blocks_type
        !> Blocks, largest UCONs and coordinates in one block
        integer :: count = 0, most_rows = 0, most_coordinates = 0
        !> Block b's UCONs: rows(row_start(b) : row_start(b + 1) - 1)
        integer, allocatable :: row_start(:), rows(:)
        !> Block b's coordinates (6 per part): coordinates(coordinate_start(b) : ...)
        integer, allocatable :: coordinate_start(:), coordinates(:)
        !> The block of each UCON
        integer, allocatable :: row_block(:)
        !> Each UCON's coordinates, ascending, each once: ucon_coordinates(ucon_start(k) : ...)
        integer, allocatable :: ucon_start(:), ucon_coordinates(:)
    contains
        procedure :: init
        procedure :: block_rows
        procedure :: block_coordinates
        procedure :: active_subset
    end type constraint_blocks_type

contains

    !> The blocks of a model that setup_model has prepared.
    subroutine init(self, model)
        class(constraint_blocks_type), intent(inout) :: self
        type(model_type), intent(in) :: model
        integer, allocatable :: parent(:), part_block(:), rows_in(:), parts_in(:)
        integer :: parts, k, i, p, root, b, next

        parts = model%n/6
        allocate(parent(parts), part_block(parts))
        parent = [(p, p = 1, parts)]
        ! union of the parts each UCON touches
        do k = 1, model%nc
            associate (ucon => model%ucons(k))
                root = find(parent, part_of(ucon%coordinate(1)))
                do i = 2, ucon%nvars
                    p = find(parent, part_of(ucon%coordinate(i)))
                    if (p /= root) parent(p) = root
                end do
            end associate
        end do
        ! blocks numbered in the order of their first UCON
        part_block = 0
        if (allocated(self%row_block)) deallocate(self%row_block, self%row_start, self%rows, &
            & self%coordinate_start, self%coordinates)
        allocate(self%row_block(model%nc))
        self%count = 0
        do k = 1, model%nc
            root = find(parent, part_of(model%ucons(k)%coordinate(1)))
            if (part_block(root) == 0) then
                self%count = self%count + 1
                part_block(root) = self%count
            end if
            self%row_block(k) = part_block(root)
        end do
        allocate(rows_in(self%count), parts_in(self%count), source=0)
        do k = 1, model%nc
            rows_in(self%row_block(k)) = rows_in(self%row_block(k)) + 1
        end do
        do p = 1, parts
            b = part_block(find(parent, p))
            if (b > 0) parts_in(b) = parts_in(b) + 1
        end do
        allocate(self%row_start(self%count + 1), self%coordinate_start(self%count + 1))
        self%row_start(1) = 1
        self%coordinate_start(1) = 1
        do b = 1, self%count
            self%row_start(b + 1) = self%row_start(b) + rows_in(b)
            self%coordinate_start(b + 1) = self%coordinate_start(b) + 6*parts_in(b)
        end do
        allocate(self%rows(model%nc), self%coordinates(self%coordinate_start(self%count + 1) - 1))
        ! ascending within each block: fill in order
        rows_in = 0
        do k = 1, model%nc
            b = self%row_block(k)
            self%rows(self%row_start(b) + rows_in(b)) = k
            rows_in(b) = rows_in(b) + 1
        end do
        parts_in = 0
        do p = 1, parts
            b = part_block(find(parent, p))
            if (b == 0) cycle
            next = self%coordinate_start(b) + 6*parts_in(b)
            self%coordinates(next:next + 5) = [(6*(p - 1) + i, i = 1, 6)]
            parts_in(b) = parts_in(b) + 1
        end do
        call ucon_lists(self, model)
        self%most_rows = 0
        self%most_coordinates = 0
        do b = 1, self%count
            self%most_rows = max(self%most_rows, self%row_start(b + 1) - self%row_start(b))
            self%most_coordinates = max(self%most_coordinates, &
                & self%coordinate_start(b + 1) - self%coordinate_start(b))
        end do
    end subroutine init

    !> Each UCON's coordinates, ascending and each once (a rate and its coordinate share one):
    !> counted first, then filled (O(nc) in all; the list grown by a copy per UCON was
    !> O(nc^2), a sizeable share of a long chain's start-up).
    subroutine ucon_lists(self, model)
        type(constraint_blocks_type), intent(inout) :: self
        type(model_type), intent(in) :: model
        integer :: list(max_ucon_vars)
        integer :: k, count

        if (allocated(self%ucon_start)) deallocate(self%ucon_start, self%ucon_coordinates)
        allocate(self%ucon_start(model%nc + 1))
        self%ucon_start(1) = 1
        do k = 1, model%nc
            call distinct(model%ucons(k)%coordinate(:model%ucons(k)%nvars), list, count)
            self%ucon_start(k + 1) = self%ucon_start(k) + count
        end do
        allocate(self%ucon_coordinates(self%ucon_start(model%nc + 1) - 1))
        do k = 1, model%nc
            call distinct(model%ucons(k)%coordinate(:model%ucons(k)%nvars), list, count)
            self%ucon_coordinates(self%ucon_start(k):self%ucon_start(k + 1) - 1) &
                & = ascending(list(:count))
        end do
    contains
        !> The distinct values of coordinates, in their first order: list(:count)
        pure subroutine distinct(coordinates, list, count)
            integer, intent(in) :: coordinates(:)
            integer, intent(out) :: list(:), count
            integer :: i

            count = 0
            do i = 1, size(coordinates)
                if (any(list(:count) == coordinates(i))) cycle
                count = count + 1
                list(count) = coordinates(i)
            end do
        end subroutine distinct
    end subroutine ucon_lists

    !> The values in ascending order (insertion sort: for the short lists of a block's UCONs
    !> and coordinates).
    pure function ascending(values) result(ordered)
        integer, intent(in) :: values(:)
        integer :: ordered(size(values))
        integer :: i, j, key

        ordered = values
        do i = 2, size(ordered)
            key = ordered(i)
            j = i - 1
            do while (j >= 1)
                if (ordered(j) <= key) exit
                ordered(j + 1) = ordered(j)
                j = j - 1
            end do
            ordered(j + 1) = key
        end do
    end function ascending

    !> The blocks with only the active UCONs in their rows (active(k) for UCON k; every block
    !> keeps its coordinates, its number and at least one row when the choice of rows set aside
    !> is rollcon_redundancy's): what the independent speeds partition over.
    pure function active_subset(self, active) result(subset)
        class(constraint_blocks_type), intent(in) :: self
        logical, intent(in) :: active(:)
        type(constraint_blocks_type) :: subset
        integer :: b

        subset = self
        subset%rows = pack(self%rows, active(self%rows))
        subset%most_rows = 0
        do b = 1, self%count
            subset%row_start(b + 1) = subset%row_start(b) + count(active(self%block_rows(b)))
            subset%most_rows = max(subset%most_rows, subset%row_start(b + 1) &
                & - subset%row_start(b))
        end do
    end function active_subset

    !> Block b's UCONs, ascending.
    pure function block_rows(self, b) result(rows)
        class(constraint_blocks_type), intent(in) :: self
        integer, intent(in) :: b
        integer :: rows(self%row_start(b + 1) - self%row_start(b))

        rows = self%rows(self%row_start(b):self%row_start(b + 1) - 1)
    end function block_rows

    !> Block b's coordinates, ascending.
    pure function block_coordinates(self, b) result(coordinates)
        class(constraint_blocks_type), intent(in) :: self
        integer, intent(in) :: b
        integer :: coordinates(self%coordinate_start(b + 1) - self%coordinate_start(b))

        coordinates = self%coordinates(self%coordinate_start(b):self%coordinate_start(b + 1) - 1)
    end function block_coordinates

    !> The part of system coordinate j.
    pure integer function part_of(j)
        integer, intent(in) :: j

        part_of = (j - 1)/6 + 1
    end function part_of

    !> The root of p's set (path halving).
    integer function find(parent, p) result(root)
        integer, intent(inout) :: parent(:)
        integer, intent(in) :: p

        root = p
        do while (parent(root) /= root)
            parent(root) = parent(parent(root))
            root = parent(root)
        end do
    end function find

end module rollcon_constraint_blocks
