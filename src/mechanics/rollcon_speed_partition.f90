! SPDX-License-Identifier: MIT
!> A partition of the rates u into dependent and independent speeds (coordinate partitioning,
!> docs/design.md §4): the velocity-level constraint matrix C (nc x n, full row rank) has nc
!> columns chosen by LAPACK's QR with column pivoting (dgeqp3), the dependent speeds; the
!> n - nc others are the independent speeds an integrator carries. With C_d the chosen
!> columns, C u = b gives u_d = C_d^-1 (b - C_i u_i), solved with C_d's LU factors (dgetf2,
!> dgetrs). C is held by rows over each UCON's own coordinates (rollcon_constraint_matrix);
!> each block's rows are gathered from it at its coordinates into the workspace, never as a
!> whole nc x n array. All of it goes block by block over the constraints' blocks
!> (rollcon_constraint_blocks: UCONs that share no part do not couple), so each block chooses
!> its own columns and N independent disks cost N times one. How well a block's choice still
!> suits the state is the growth of its dependent speeds, the largest entry of C_d^-1 C_i
!> (how much an error of an independent speed is amplified in a dependent one; QR with
!> pivoting keeps it small when it chooses), against its value at the choice. The dependent
!> speeds are numbered by slot: block b's are slots row_start(b) ... in ascending coordinate
!> order. A block of sparse_partition_rows rows or more (a long chain) has C_d factored by KLU
!> over its nonzeros (a UCON's row holds its own coordinates only), its pattern analysed again
!> after each choice: its factors and solves then cost O(m), not m^3 and m^2. Nothing else
!> here allocates after init.
module rollcon_speed_partition
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_lapack, only : dgeqp3, dgetf2, dgetrs, lapack_info_error
    use rollcon_constraint_blocks, only : constraint_blocks_type, ascending
    use rollcon_sparse_lu, only : sparse_lu_type
    use rollcon_constraint_matrix, only : constraint_matrix_type
    implicit none
    private

    public :: speed_partition_type, worn_ratio, sparse_partition_rows

    !> Blocks of at least this many rows have C_d factored by KLU. Measured on the chain in
    !> independent speeds by fixed-point iteration (whole runs, pairs of processes): at 4 links
    !> (20 rows) the two paths cost the same (1.006); at 64 links (320 rows) the run took
    !> 0.23 s, 0.50 s with C_d dense. The threshold of rollcon_saddle_point's sparse Schur
    !> complement: every shipped model's blocks (21 rows at most) stay dense, their outputs bit
    !> for bit
    integer, parameter :: sparse_partition_rows = 40

    !> A block's partition is worn when the growth of its dependent speeds has risen above its
    !> value at the choice divided by this (and QR with pivoting would now choose other
    !> columns): the dependent speeds' errors grow with it. Measured on
    !> data/chaplygin_sled.adm (ERROR = 1e-10, the knife edge's columns turning with the sled),
    !> energy drift 3.2e-9 at 0.3 against 1.5e-9 for the ODE form; with C_d's condition number
    !> as the measure instead, 1.4e-6 at a ratio of 1e-2, 8.8e-9 at 0.1, 4.3e-9 at 0.3
    real(wp), parameter :: worn_ratio = 0.3_wp

    !> The chosen partition, C_d's factors and the workspace of the choice
    type :: speed_partition_type
        !> Rates and constraint rows (the rows partitioned: the active ones when rows are set
        !> aside), and the rows of the model (the leading dimension of solve's x)
        integer :: n = 0, nc = 0, rows = 0
        !> The blocks (one of every row and coordinate when init was given none)
        type(constraint_blocks_type) :: blocks
        !> Dependent speeds by slot (nc) and the independent ones (n - nc, ascending)
        integer, allocatable :: dependent(:), independent(:)
        !> Each block's LU factors of C_d, packed from lu_start(b), and their pivots by slot
        real(wp), allocatable :: lu(:)
        integer, allocatable :: lu_start(:), pivots(:)
        !> Each block's growth max |C_d^-1 C_i| when its partition was chosen [-]
        real(wp), allocatable :: growth_chosen(:)
        !> Partitions chosen since init
        integer :: choices = 0
        !> Workspace of dgeqp3, of a trial choice, of the growth and of solves
        real(wp), allocatable :: qr(:, :), tau(:), work(:), basis(:, :), buffer(:, :)
        integer, allocatable :: jpvt(:), trial(:)
        logical, allocatable :: is_dependent(:)
        !> Blocks factored by KLU, and whether their pattern is analysed for the dependent
        !> speeds of now
        logical, allocatable :: block_sparse(:), analysed(:)
        type(sparse_lu_type), allocatable :: sparse(:)
        !> Of a sparse block b's entries, from value_start(b): the index of each in C by rows
        !> (c%value, whose pattern is the blocks' ucon_start/ucon_coordinates), in KLU's order
        !> of values
        integer, allocatable :: value_start(:), value_entry(:)
        !> A coordinate's column in the block being gathered or analysed (0 otherwise)
        integer, allocatable :: column_of(:)
    contains
        procedure :: init
        procedure :: choose
        procedure :: factor
        procedure :: solve
        procedure :: solve_block
        procedure :: growth
        procedure :: worn
        procedure :: release
    end type speed_partition_type

contains

    !> Size for n rates and nc constraint rows (nc <= n) over the given blocks (none: one
    !> block of everything); every block's first rates dependent until the first choice. With
    !> rows, the model has that many rows and the blocks list the nc of them partitioned (the
    !> active ones: constraint_blocks_type's active_subset); solve's x is then rows long.
    subroutine init(self, n, nc, blocks, rows)
        class(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: n, nc
        type(constraint_blocks_type), intent(in), optional :: blocks
        integer, intent(in), optional :: rows
        real(wp) :: query(1)
        integer :: info, b, m, columns, lwork, total

        self%n = n
        self%nc = nc
        self%rows = nc
        if (present(rows)) self%rows = rows
        self%choices = 0
        if (present(blocks)) then
            self%blocks = blocks
        else
            call whole_block(self%blocks, n, nc)
        end if
        call self%release()
        if (allocated(self%dependent)) deallocate(self%dependent, self%independent, self%lu, &
            & self%lu_start, self%pivots, self%growth_chosen, self%qr, self%tau, self%work, &
            & self%basis, self%buffer, self%jpvt, self%trial, self%is_dependent, &
            & self%block_sparse, self%analysed, self%sparse, self%value_start, self%column_of)
        if (allocated(self%value_entry)) deallocate(self%value_entry)
        associate (bl => self%blocks)
            allocate(self%dependent(nc), self%independent(n - nc), self%trial(max(nc, 1)))
            allocate(self%lu_start(bl%count + 1), self%growth_chosen(max(bl%count, 1)))
            allocate(self%block_sparse(bl%count), self%analysed(bl%count), source=.false.)
            allocate(self%sparse(bl%count))
            allocate(self%value_start(bl%count + 1), self%column_of(max(n, 1)), source=0)
            self%growth_chosen = 1.0_wp
            self%lu_start(1) = 1
            do b = 1, bl%count
                m = bl%row_start(b + 1) - bl%row_start(b)
                ! (the UCONs' coordinates come with blocks given; one whole block has none)
                self%block_sparse(b) = m >= sparse_partition_rows &
                    & .and. allocated(bl%ucon_start)
                self%lu_start(b + 1) = self%lu_start(b) + merge(0, m*m, self%block_sparse(b))
                ! the block's first m coordinates until a choice
                self%dependent(bl%row_start(b):bl%row_start(b + 1) - 1) = &
                    & bl%coordinates(bl%coordinate_start(b):bl%coordinate_start(b) + m - 1)
            end do
            total = max(self%lu_start(bl%count + 1) - 1, 1)
            allocate(self%lu(total), self%qr(max(bl%most_rows, 1), max(bl%most_coordinates, 1)), &
                & self%tau(max(bl%most_rows, 1)), source=0.0_wp)
            allocate(self%basis(max(bl%most_rows, 1), max(bl%most_coordinates, 1)), &
                & self%buffer(max(self%rows, 1), max(n, 1)), source=0.0_wp)
            allocate(self%pivots(max(nc, 1)), self%jpvt(max(bl%most_coordinates, 1)), source=0)
            allocate(self%is_dependent(n), source=.false.)
            call set_independent(self)
            ! workspace query of dgeqp3 (lwork = -1) on the largest block
            columns = max(bl%most_coordinates, 1)
            lwork = 3*columns + 1
            if (bl%most_rows > 0) then
                call dgeqp3(bl%most_rows, columns, self%qr, size(self%qr, 1), self%jpvt, &
                    & self%tau, query, -1, info)
                if (info == 0) lwork = max(lwork, int(query(1)))
            end if
            allocate(self%work(lwork), source=0.0_wp)
        end associate
    end subroutine init

    !> One block of every row and every coordinate.
    subroutine whole_block(blocks, n, nc)
        type(constraint_blocks_type), intent(out) :: blocks
        integer, intent(in) :: n, nc
        integer :: j

        blocks%count = merge(1, 0, nc > 0)
        blocks%most_rows = nc
        blocks%most_coordinates = merge(n, 0, nc > 0)
        blocks%row_start = [1, nc + 1]
        blocks%coordinate_start = [1, n + 1]
        blocks%rows = [(j, j = 1, nc)]
        blocks%coordinates = [(j, j = 1, n)]
        blocks%row_block = [(1, j = 1, nc)]
        if (nc == 0) then
            blocks%row_start = [1]
            blocks%coordinate_start = [1]
        end if
    end subroutine whole_block

    !> Choose the partition for the constraint matrix c (C, nc x n by rows over each UCON's own
    !> coordinates, rollcon_constraint_matrix): in each block the first columns of QR with
    !> column pivoting are the dependent speeds; then factor C_d. An error when c has not full
    !> row rank (a dependent block is singular).
    subroutine choose(self, c, error)
        class(speed_partition_type), intent(inout) :: self
        !> Velocity-level constraint rows [UCON unit per rate unit]
        type(constraint_matrix_type), intent(in) :: c
        type(error_type), allocatable, intent(out) :: error
        integer :: b

        self%choices = self%choices + 1
        do b = 1, self%blocks%count
            call choose_block(self, b, c, error)
            if (allocated(error)) return
            associate (first => self%blocks%row_start(b), last => self%blocks%row_start(b + 1) - 1)
                self%dependent(first:last) = self%trial(first:last)
            end associate
            ! a sparse block's pattern follows its dependent speeds: analysed again at factor
            self%analysed(b) = .false.
        end do
        call set_independent(self)
        call self%factor(c, error)
        if (allocated(error)) return
        do b = 1, self%blocks%count
            self%growth_chosen(b) = block_growth(self, b, c)
        end do
    end subroutine choose

    !> Block b's choice of dependent speeds by QR with column pivoting into trial (its slots),
    !> ascending; the partition itself is not changed.
    subroutine choose_block(self, b, c, error)
        type(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        type(error_type), allocatable, intent(out) :: error
        integer :: i, j, m, columns, info

        associate (bl => self%blocks)
            m = bl%row_start(b + 1) - bl%row_start(b)
            columns = bl%coordinate_start(b + 1) - bl%coordinate_start(b)
            ! the block's rows at its coordinates (the zeros off each UCON's own ones)
            self%qr(:m, :columns) = 0.0_wp
            do j = 1, columns
                self%column_of(bl%coordinates(bl%coordinate_start(b) + j - 1)) = j
            end do
            call gather_block(c, bl%rows(bl%row_start(b):bl%row_start(b + 1) - 1), &
                & self%column_of, self%qr, size(self%qr, 1))
            do j = 1, columns
                self%column_of(bl%coordinates(bl%coordinate_start(b) + j - 1)) = 0
            end do
            self%jpvt(:columns) = 0
            call dgeqp3(m, columns, self%qr, size(self%qr, 1), self%jpvt, self%tau, self%work, &
                & size(self%work), info)
            call lapack_info_error("dgeqp3 (speed partition)", info, error)
            if (allocated(error)) return
            do i = 1, m
                self%trial(bl%row_start(b) + i - 1) = bl%coordinates(bl%coordinate_start(b) &
                    & + self%jpvt(i) - 1)
            end do
            self%trial(bl%row_start(b):bl%row_start(b + 1) - 1) = &
                & ascending(self%trial(bl%row_start(b):bl%row_start(b + 1) - 1))
        end associate
    end subroutine choose_block

    !> LU factors of each block's C_d = C(block's rows, its dependent speeds), c by rows over
    !> each UCON's own coordinates.
    subroutine factor(self, c, error)
        class(speed_partition_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        type(error_type), allocatable, intent(out) :: error
        integer :: b, j, m, first, info

        associate (bl => self%blocks)
            do b = 1, bl%count
                m = bl%row_start(b + 1) - bl%row_start(b)
                first = bl%row_start(b)
                if (self%block_sparse(b)) then
                    call factor_sparse(self, b, c, error)
                    if (allocated(error)) return
                    cycle
                end if
                self%lu(self%lu_start(b):self%lu_start(b) + m*m - 1) = 0.0_wp
                do j = 1, m
                    self%column_of(self%dependent(first + j - 1)) = j
                end do
                call gather_block(c, bl%rows(first:first + m - 1), self%column_of, &
                    & self%lu(self%lu_start(b)), m)
                do j = 1, m
                    self%column_of(self%dependent(first + j - 1)) = 0
                end do
                call dgetf2(m, m, self%lu(self%lu_start(b)), m, self%pivots(first), info)
                if (info > 0) then
                    call fatal_error(error, "the constraint rows are dependent where the speeds " &
                        & // "were partitioned (a singular block C_d: dgetf2 info > 0)", &
                        & stat_lapack)
                    return
                end if
                call lapack_info_error("dgetf2 (dependent speeds)", info, error)
                if (allocated(error)) return
            end do
        end associate
    end subroutine factor

    !> x := C_d^-1 x for m columns of x (leading dimension rows), with the last factors: x's
    !> rows are the constraint rows (UCON numbers) on entry, the dependent speeds' slots (the
    !> first nc) on return.
    subroutine solve(self, x, m, error)
        class(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        integer :: b, i, rows, first, col, info

        if (self%nc == 0) return
        associate (bl => self%blocks)
            do col = 1, m
                self%buffer(:self%rows, col) = x(:, col)
            end do
            do b = 1, bl%count
                first = bl%row_start(b)
                rows = bl%row_start(b + 1) - first
                do col = 1, m
                    do i = 1, rows
                        x(first + i - 1, col) = self%buffer(bl%rows(first + i - 1), col)
                    end do
                end do
                if (self%block_sparse(b)) then
                    call self%sparse(b)%solve(x(first, 1), self%rows, m, error)
                    if (allocated(error)) return
                    cycle
                end if
                call dgetrs("N", rows, m, self%lu(self%lu_start(b)), rows, self%pivots(first), &
                    & x(first, 1), self%rows, info)
                call lapack_info_error("dgetrs (dependent speeds)", info, error)
                if (allocated(error)) return
            end do
        end associate
    end subroutine solve

    !> solve for block b alone: x (leading dimension ldx, m columns) holds on entry the
    !> block's rows of the right-hand sides, in the block's order of its UCONs (constraint_
    !> blocks_type's rows), and on exit C_d^-1 of them by the block's slots (row i: slot
    !> row_start(b) + i - 1), as solve leaves them in those slots: the same operations (the
    !> independent speeds' Newton matrix by blocks).
    subroutine solve_block(self, b, x, ldx, m, error)
        class(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: b, ldx, m
        real(wp), intent(inout) :: x(ldx, *)
        type(error_type), allocatable, intent(out) :: error
        integer :: first, rows, info

        if (self%nc == 0) return
        first = self%blocks%row_start(b)
        rows = self%blocks%row_start(b + 1) - first
        if (self%block_sparse(b)) then
            call self%sparse(b)%solve(x, ldx, m, error)
            return
        end if
        call dgetrs("N", rows, m, self%lu(self%lu_start(b)), rows, self%pivots(first), x, ldx, &
            & info)
        call lapack_info_error("dgetrs (dependent speeds)", info, error)
    end subroutine solve_block

    !> The largest growth max |C_d^-1 C_i| of the blocks for the matrix c (C by rows over each
    !> UCON's own coordinates), with the factors of the last factor call, which must be of
    !> this c.
    function growth(self, c) result(largest)
        class(speed_partition_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        real(wp) :: largest
        integer :: b

        largest = 0.0_wp
        do b = 1, self%blocks%count
            largest = max(largest, block_growth(self, b, c))
        end do
    end function growth

    !> Block b's growth max |C_d^-1 C_i| (0 without independent speeds in it; huge when the
    !> solve fails), with the factors of the last factor call.
    function block_growth(self, b, c) result(largest)
        type(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp) :: largest
        integer :: j, m, columns, free, first, info, coordinate
        type(error_type), allocatable :: error

        largest = 0.0_wp
        associate (bl => self%blocks)
            first = bl%row_start(b)
            m = bl%row_start(b + 1) - first
            columns = bl%coordinate_start(b + 1) - bl%coordinate_start(b)
            ! C_i: the block's rows at its independent speeds
            free = 0
            do j = 1, columns
                coordinate = bl%coordinates(bl%coordinate_start(b) + j - 1)
                if (any(self%dependent(first:first + m - 1) == coordinate)) cycle
                free = free + 1
                self%column_of(coordinate) = free
            end do
            if (free == 0) return
            self%basis(:m, :free) = 0.0_wp
            call gather_block(c, bl%rows(first:first + m - 1), self%column_of, self%basis, &
                & size(self%basis, 1))
            do j = 1, columns
                self%column_of(bl%coordinates(bl%coordinate_start(b) + j - 1)) = 0
            end do
            largest = huge(1.0_wp)
            if (self%block_sparse(b)) then
                call self%sparse(b)%solve(self%basis, size(self%basis, 1), free, error)
                if (.not. allocated(error)) largest = maxval(abs(self%basis(:m, :free)))
                return
            end if
            call dgetrs("N", m, free, self%lu(self%lu_start(b)), m, self%pivots(first), &
                & self%basis, size(self%basis, 1), info)
            if (info == 0) largest = maxval(abs(self%basis(:m, :free)))
        end associate
    end function block_growth

    !> True when the partition no longer suits c (C by rows over each UCON's own
    !> coordinates): some block's C_d (factored again here)
    !> singular, or its growth above its choice's divided by worn_ratio while QR with pivoting
    !> would now choose other columns there. A block whose choice would stay keeps it, with
    !> the growth of now as its reference. The partition itself is never changed here (the
    !> integrator's state is in its speeds): a worn one is chosen again by choose.
    function worn(self, c) result(is_worn)
        class(speed_partition_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        logical :: is_worn
        type(error_type), allocatable :: error
        real(wp) :: now
        integer :: b, first, last

        is_worn = .false.
        if (self%nc == 0) return
        call self%factor(c, error)
        is_worn = allocated(error)
        if (is_worn) return
        do b = 1, self%blocks%count
            now = block_growth(self, b, c)
            if (worn_ratio*now <= self%growth_chosen(b)) cycle
            call choose_block(self, b, c, error)
            first = self%blocks%row_start(b)
            last = self%blocks%row_start(b + 1) - 1
            if (allocated(error)) then
                is_worn = .true.
            else if (any(self%trial(first:last) /= self%dependent(first:last))) then
                is_worn = .true.
            else
                self%growth_chosen(b) = now
            end if
            if (is_worn) return
        end do
    end function worn

    !> Block b's C_d (a sparse block) factored by KLU: its pattern analysed first when the
    !> dependent speeds changed since, then its values taken from c (C by rows, at the entries
    !> analyse_block kept). The error of a singular
    !> C_d is the dense path's.
    subroutine factor_sparse(self, b, c, error)
        type(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        integer :: e, offset

        if (.not. self%analysed(b)) then
            call analyse_block(self, b, error)
            if (allocated(error)) return
        end if
        offset = self%value_start(b) - 1
        associate (values => self%sparse(b)%values)
            do e = 1, size(values)
                values(e) = c%value(self%value_entry(offset + e))
            end do
        end associate
        call self%sparse(b)%factor(failure)
        if (allocated(failure)) call fatal_error(error, "the constraint rows are dependent " &
            & // "where the speeds were partitioned (a singular block C_d: " // failure%message &
            & // ")", stat_lapack)
    end subroutine factor_sparse

    !> Block b's pattern of C_d in compressed columns: column j is dependent speed j of the
    !> block, row i its UCON i, an entry where that UCON holds that coordinate; analysed by
    !> KLU. The sparse blocks' entries are kept from value_start(b) (the blocks before it
    !> analysed last keep theirs: each block's slice is rebuilt in place of its own).
    subroutine analyse_block(self, b, error)
        type(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: b
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: column_start(:), row(:), entry(:), fill(:)
        integer :: first, m, i, j, k, x, entries, e

        associate (bl => self%blocks)
            first = bl%row_start(b)
            m = bl%row_start(b + 1) - first
            do j = 1, m
                self%column_of(self%dependent(first + j - 1)) = j
            end do
            allocate(column_start(m + 1), fill(m), source=0)
            do i = 1, m
                k = bl%rows(first + i - 1)
                do x = bl%ucon_start(k), bl%ucon_start(k + 1) - 1
                    j = self%column_of(bl%ucon_coordinates(x))
                    if (j > 0) column_start(j + 1) = column_start(j + 1) + 1
                end do
            end do
            column_start(1) = 1
            do j = 1, m
                column_start(j + 1) = column_start(j) + column_start(j + 1)
            end do
            entries = column_start(m + 1) - 1
            allocate(row(entries), entry(entries))
            ! rows ascending within each column: the rows are taken in order
            do i = 1, m
                k = bl%rows(first + i - 1)
                do x = bl%ucon_start(k), bl%ucon_start(k + 1) - 1
                    j = self%column_of(bl%ucon_coordinates(x))
                    if (j == 0) cycle
                    e = column_start(j) + fill(j)
                    fill(j) = fill(j) + 1
                    row(e) = i
                    entry(e) = x
                end do
            end do
            do j = 1, m
                self%column_of(self%dependent(first + j - 1)) = 0
            end do
        end associate
        call place_entries(self, b, entry)
        call self%sparse(b)%analyse(m, column_start, row, error)
        if (allocated(error)) return
        self%analysed(b) = .true.
    end subroutine analyse_block

    !> Block b's entries (their indices in C by rows) into value_entry from value_start(b); the
    !> later blocks' slices move with it when its count changed.
    subroutine place_entries(self, b, entry)
        type(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: b, entry(:)
        integer, allocatable :: before(:), after(:)
        integer :: start, old_end, count

        if (.not. allocated(self%value_entry)) then
            allocate(self%value_entry(0))
            self%value_start = 1
        end if
        count = size(self%value_start) - 1
        start = self%value_start(b)
        old_end = self%value_start(b + 1) - 1
        before = self%value_entry(:start - 1)
        after = self%value_entry(old_end + 1:)
        self%value_entry = [before, entry, after]
        self%value_start(b + 1:count + 1) = self%value_start(b + 1:count + 1) &
            & + size(entry) - (old_end - start + 1)
    end subroutine place_entries

    !> The rows of C (c, by rows over each UCON's own coordinates) given in rows, at the
    !> coordinates numbered in column_of (coordinate -> column of a; 0: left out), into a
    !> (leading dimension lda; row i of a is rows(i)). a's entries there must be zero on entry
    !> (those off each UCON's own coordinates stay so). O(the rows' entries), no allocation.
    pure subroutine gather_block(c, rows, column_of, a, lda)
        type(constraint_matrix_type), intent(in) :: c
        integer, intent(in) :: rows(:), column_of(:), lda
        real(wp), intent(inout) :: a(lda, *)
        integer :: i, k, x, j

        do i = 1, size(rows)
            k = rows(i)
            do x = c%start(k), c%start(k + 1) - 1
                j = column_of(c%column(x))
                if (j > 0) a(i, j) = c%value(x)
            end do
        end do
    end subroutine gather_block

    !> Free the sparse blocks' KLU objects (the holder of a copy must not call it: the copy
    !> shares them).
    subroutine release(self)
        class(speed_partition_type), intent(inout) :: self
        integer :: b

        if (.not. allocated(self%sparse)) return
        do b = 1, size(self%sparse)
            call self%sparse(b)%release()
        end do
        if (allocated(self%analysed)) self%analysed = .false.
    end subroutine release

    !> The independent speeds: the rates not dependent, ascending.
    subroutine set_independent(self)
        type(speed_partition_type), intent(inout) :: self
        integer :: j, m

        self%is_dependent = .false.
        self%is_dependent(self%dependent) = .true.
        m = 0
        do j = 1, self%n
            if (self%is_dependent(j)) cycle
            m = m + 1
            self%independent(m) = j
        end do
    end subroutine set_independent

end module rollcon_speed_partition
