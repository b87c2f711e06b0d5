! SPDX-License-Identifier: MIT
!> The saddle-point system of constrained motion, solved through its structure
!> (docs/design.md §4):
!>
!>     [M  -C^T] [a     ]   [r1]        S = C M^-1 C^T (rows x rows)
!>     [C   0  ] [lambda] = [r2],       S lambda = r2 - C M^-1 r1,  a = M^-1 (r1 + C^T lambda).
!>
!> M is block diagonal, one 6 x 6 block per part, and each block is m I (translation) beside
!> the 3 x 3 rotational block B^T J B (principal axes at the centre of mass: no coupling). So
!> M^-1 costs a division and a 3 x 3 Cholesky solve per part (dpotf2's and dpotrs's arithmetic
!> in rollcon_small_dense) and only the small Schur complement S is factored with
!> pivoting (dgetf2's and dgetrs's arithmetic, rollcon_small_dense), in place of
!> the whole (n + nc) x (n + nc) matrix. Given the constraints' blocks (rollcon_constraint_blocks:
!> UCONs that share no part do not couple), S is block diagonal and every step goes block by
!> block, each row over its block's coordinates only, so N independent disks cost N times one:
!> the sums are those of the dense path without its terms that are exact zeros, in the same
!> order, and the blocks' LU factors those of the dense S: the same numbers, except that an
!> exact zero may keep the sign the dense path's added zeros took from it (-0 for +0, with two
!> blocks or more). A block of sparse_schur_rows rows or more (a long chain: S has a band of
!> UCONs sharing a part, its dense LU would cost rows^3) has S formed over its nonzeros only and
!> factored by KLU (rollcon_sparse_lu), its pattern analysed once in init: the dense path's
!> numbers to round-off. Nothing here allocates after init, except KLU's first factorisation
!> of a sparse block (and a fresh one when reusing the pivot order would lose accuracy).
!>
!> C comes by rows over each UCON's coordinates (rollcon_constraint_matrix, the blocks' pattern):
!> the block paths read its entries where they are (index x of ucon_coordinates), the dense path
!> fills one row at a time into a row of n (row_scratch) and sums as over the dense matrix. The
!> position projection solves C too, its rows other than the active position UCONs' set aside.
!>
!> Rows set aside (rollcon_redundancy: a redundant row; the projection's velocity rows; given as
!> `active` false to factor) keep their place: their multiplier is zero, their row and column of
!> S become the identity's and their right-hand side zero, so lambda_k = 0 and they add nothing
!> to a. Without rows set
!> aside every operation is the one above.
module rollcon_saddle_point
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    use rollcon_lapack, only : lapack_info_error
    use rollcon_small_dense, only : factor_lu, solve_lu, factor_cholesky3, solve_cholesky3
    use rollcon_sparse_lu, only : sparse_lu_type
    use rollcon_constraint_blocks, only : constraint_blocks_type, ascending
    use rollcon_constraint_matrix, only : constraint_matrix_type
    use rollcon_int_buffer, only : append, trimmed
    implicit none
    private

    public :: saddle_point_type, sparse_schur_rows

    !> Blocks of at least this many constraint rows go the sparse way (KLU on S's nonzeros):
    !> a dense LU of S costs m^3/3 and forming it m^2 times the block's coordinates, against
    !> O(m) for a chain's S (UCONs sharing a part: about 15 entries per row). Measured on the
    !> chain (docs/benchmark.md): at 20 rows (4 links) both paths cost the same, at 40 (8 links)
    !> the sparse one makes CVODE's ODE form 1.6 times cheaper. Every shipped dataset and scene
    !> has smaller blocks (data/bicycle.adm's, the largest, 21 rows), and keeps the dense path's
    !> numbers bit for bit.
    integer, parameter :: sparse_schur_rows = 40
    !> Right-hand sides a sparse block's solve hands KLU at a time: klu_solve's own group of
    !> columns (KLU 1.3: four), so that each is solved as in one call with all of them
    integer, parameter :: klu_group = 4

    !> Factors of one saddle-point matrix and the workspace to solve with them
    type :: saddle_point_type
        !> Coordinates, largest number of constraint rows, parts
        integer :: n = 0, nc = 0, parts = 0
        !> Constraint rows of the current factorisation (<= nc)
        integer :: rows = 0
        !> Translational mass of each part [kg]
        real(wp), allocatable :: part_mass(:)
        !> Cholesky factor (lower) of each part's rotational mass block (3, 3, parts)
        real(wp), allocatable :: rotational(:, :, :)
        !> M^-1 C^T (n, nc), columns 1..rows in use: allocated by the first factorisation that
        !> is not by blocks (the projection's rows), none on a model whose solves all go by
        !> blocks
        real(wp), allocatable :: minv_ct(:, :)
        !> One row of C written whole (n): the dense path's sums run over it as over a row of the
        !> dense matrix (allocated by init)
        real(wp), allocatable :: row_scratch(:)
        !> M^-1 C^T by blocks, each UCON's column over the coordinates where it can be nonzero
        !> (M is block diagonal by parts): a dense block's UCON over the block's coordinates, a
        !> sparse block's over its own parts' (6 each, as ucon_parts). Column k is
        !> minv_values(minv_start(k) : minv_start(k + 1) - 1); memory linear in the model
        !> (docs/design.md §4 "Memory")
        real(wp), allocatable :: minv_values(:)
        integer, allocatable :: minv_start(:)
        !> Each coordinate's place in its block's coordinates (0 for a part in no block)
        integer, allocatable :: coordinate_place(:)
        !> LU factors of S unblocked (leading dimension nc; allocated by the first factorisation
        !> that is not by blocks) and the pivots
        real(wp), allocatable :: schur(:, :)
        integer, allocatable :: pivots(:)
        !> Factorisations done since init: one per saddle-point solve of a new matrix
        integer :: factorisations = 0
        !> The constraints' blocks, when given to init (then the factorisations of all nc rows
        !> go block by block; without them, or with fewer rows, the dense path: the tests'
        !> reference)
        logical :: blocked = .false.
        type(constraint_blocks_type) :: blocks
        !> Each block's LU factors of S, packed (offset of block b: schur_start(b)), and the
        !> right-hand sides of one dense block gathered (its most rows, up to 2 n columns)
        real(wp), allocatable :: block_schur(:), gathered(:, :)
        !> The right-hand sides of one sparse block gathered, klu_group at a time (its most
        !> rows, klu_group)
        real(wp), allocatable :: sparse_gathered(:, :)
        integer, allocatable :: schur_start(:)
        !> For each entry of a dense block's S (packed as block_schur): whether its two UCONs
        !> share a part (else the entry is an exact zero, not summed)
        logical, allocatable :: block_shares(:)
        !> The terms of each entry e of a dense block's S, row k and column l (packed as
        !> block_schur), in runs: runs run_start(e) : run_start(e + 1) - 1, run r the
        !> run_length(r) terms t = 0, 1, ..., each the product of C's entry run_value(r) + t
        !> (c's index: C(k, j) on a coordinate j of k's on a part of l's, ascending) with
        !> M^-1 c_l^T's entry minv_values(run_minv(r) + t) there (a run ends where either
        !> index jumps); none for UCONs that share no part (set by init)
        integer, allocatable :: run_start(:), run_value(:), run_minv(:), run_length(:)
        !> For each part, the UCONs with a coordinate on it, ascending (a dense block's in its
        !> rows' order, a sparse block's as part_ucons): columns column_start(p) :
        !> column_start(p + 1) - 1,
        !> each with its UCON column_ucon(i), the place of its part's six rows of M^-1 c_k^T in
        !> minv_values (column_offset(i) + 1 : + 6) and C's entries on the part
        !> (column_first(i) : column_last(i), c's index); set by init. A block's UCON with no
        !> coordinate on a part has exact zeros there in minv_values: init's, which the
        !> factorisations leave as they are
        integer, allocatable :: column_start(:), column_ucon(:), column_offset(:), &
            & column_first(:), column_last(:)
        !> Each column's UCON's place among its dense block's rows (1 for the first; 0 in a
        !> sparse block)
        integer, allocatable :: column_row(:)
        !> Whether the current factorisation went block by block
        logical :: by_blocks = .false.
        !> Whether the current factorisation sets rows aside, and which rows are active (nc)
        logical :: masked = .false.
        logical, allocatable :: active(:)
        !> For each part, whether a block holds it (a part no UCON touches is in none)
        logical, allocatable :: part_blocked(:)
        !> The rotational rows of one part's right-hand sides gathered for one dpotrs:
        !> (3, 1 + most_rows)
        real(wp), allocatable :: rotational_rows(:, :)
        !> Blocks with at least this many rows are factored sparse (sparse_schur_rows unless
        !> init was told otherwise), and which blocks those are
        integer :: sparse_from = sparse_schur_rows
        logical, allocatable :: block_sparse(:)
        !> The sparse blocks' S (KLU), one per block (analysed for the sparse ones only)
        type(sparse_lu_type), allocatable :: sparse(:)
        !> Each UCON's parts (ucon_parts(ucon_part_start(k) : ...)), each part's UCONs
        !> (part_ucons(part_ucon_start(p) : ...)), each UCON's place in its block's rows
        integer, allocatable :: ucon_part_start(:), ucon_parts(:), part_ucon_start(:), &
            & part_ucons(:), row_local(:)
        !> The sparse blocks' entries of S, in the order of their KLU values (block b's from
        !> entry_start(b)): S(entry_row(e), entry_column(e)) (UCON numbers k, l) sums C(k, j)
        !> M^-1 c_l^T(j) over j = ucon_coordinates(q) (the blocks'), q = entry_places(
        !> entry_coordinate_start(e) : ...): q is also C's entry (rollcon_constraint_matrix)
        integer, allocatable :: entry_start(:), entry_row(:), entry_column(:), &
            & entry_coordinate_start(:), entry_places(:)
    contains
        procedure :: init
        procedure :: factor
        procedure :: solve
        procedure :: solve_local
        procedure :: apply_inverse_mass
        procedure :: release
    end type saddle_point_type

contains

    !> Size the workspace for n coordinates (6 per part) and at most nc constraint rows, with
    !> the constraints' blocks when given.
    subroutine init(self, n, nc, blocks, sparse_from, error)
        class(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: n, nc
        type(constraint_blocks_type), intent(in), optional :: blocks
        !> Blocks of at least this many rows go the sparse way (default sparse_schur_rows)
        integer, intent(in), optional :: sparse_from
        !> Set when KLU cannot analyse a sparse block's pattern (out of memory)
        type(error_type), allocatable, intent(out), optional :: error
        type(error_type), allocatable :: failure
        integer :: b, m

        self%n = n
        self%nc = nc
        self%parts = n/6
        self%rows = 0
        self%factorisations = 0
        if (allocated(self%part_mass)) deallocate(self%part_mass, self%rotational, self%pivots)
        if (allocated(self%minv_ct)) deallocate(self%minv_ct)
        if (allocated(self%row_scratch)) deallocate(self%row_scratch)
        allocate(self%row_scratch(n), source=0.0_wp)
        if (allocated(self%minv_values)) deallocate(self%minv_values, self%minv_start, &
            & self%coordinate_place)
        if (allocated(self%schur)) deallocate(self%schur)
        if (allocated(self%run_start)) deallocate(self%run_start, self%run_value, &
            & self%run_minv, self%run_length, self%column_start, self%column_ucon, &
            & self%column_row, self%column_offset, self%column_first, self%column_last)
        allocate(self%part_mass(self%parts), source=0.0_wp)
        allocate(self%rotational(3, 3, self%parts), source=0.0_wp)
        allocate(self%pivots(max(nc, 1)), source=0)
        if (allocated(self%active)) deallocate(self%active)
        allocate(self%active(max(nc, 1)), source=.true.)
        self%masked = .false.
        self%blocked = present(blocks)
        self%by_blocks = .false.
        if (allocated(self%block_schur)) deallocate(self%block_schur, self%gathered, &
            & self%sparse_gathered, self%schur_start, self%part_blocked, self%rotational_rows, &
            & self%block_shares)
        if (allocated(self%sparse)) then
            do b = 1, size(self%sparse)
                call self%sparse(b)%release()
            end do
            deallocate(self%sparse, self%block_sparse)
        end if
        if (allocated(self%ucon_parts)) deallocate(self%ucon_part_start, self%ucon_parts, &
            & self%part_ucon_start, self%part_ucons, self%row_local, self%entry_start, &
            & self%entry_row, self%entry_column, self%entry_coordinate_start, &
            & self%entry_places)
        self%sparse_from = sparse_schur_rows
        if (present(sparse_from)) self%sparse_from = sparse_from
        if (.not. self%blocked) return
        self%blocks = blocks
        allocate(self%part_blocked(self%parts), source=.false.)
        do b = 1, blocks%count
            self%part_blocked((blocks%coordinates(blocks%coordinate_start(b): &
                & blocks%coordinate_start(b + 1) - 1) - 1)/6 + 1) = .true.
        end do
        allocate(self%rotational_rows(3, 1 + max(blocks%most_rows, 1)), source=0.0_wp)
        allocate(self%block_sparse(blocks%count), self%sparse(blocks%count))
        do b = 1, blocks%count
            self%block_sparse(b) = blocks%row_start(b + 1) - blocks%row_start(b) &
                & >= self%sparse_from
        end do
        ! a dense block's S packed m x m; a sparse block's is KLU's, over its nonzeros only
        ! (no m x m array: a chain of N links' S is 5N square)
        allocate(self%schur_start(blocks%count + 1))
        self%schur_start(1) = 1
        do b = 1, blocks%count
            m = blocks%row_start(b + 1) - blocks%row_start(b)
            if (self%block_sparse(b)) m = 0
            self%schur_start(b + 1) = self%schur_start(b) + m*m
        end do
        ! a dense block's right-hand sides gathered (a sparse block's solve in KLU's columns)
        m = 0
        do b = 1, blocks%count
            if (.not. self%block_sparse(b)) m = max(m, blocks%row_start(b + 1) &
                & - blocks%row_start(b))
        end do
        allocate(self%block_schur(max(self%schur_start(blocks%count + 1) - 1, 1)), &
            & self%gathered(max(m, 1), max(2*n, 1)), source=0.0_wp)
        m = 0
        do b = 1, blocks%count
            if (self%block_sparse(b)) m = max(m, blocks%row_start(b + 1) - blocks%row_start(b))
        end do
        allocate(self%sparse_gathered(max(m, 1), klu_group), source=0.0_wp)
        call find_shares(self)
        if (any(self%block_sparse)) then
            call sparse_pattern(self, failure)
            if (allocated(failure)) then
                if (present(error)) call move_alloc(failure, error)
                return
            end if
        end if
        call size_columns(self)
        call dense_terms(self)
    end subroutine init

    !> The terms of each dense block's S (run_start, run_value, run_minv, run_length) and the
    !> UCONs of each part (column_start, ...; a sparse block's parts too, for part_columns):
    !> found once, so that a factorisation sums
    !> only the products that can be nonzero, with their places looked up here and not in its
    !> loops, consecutive ones by a run's first places. The terms left out are C(k, j) times
    !> an exact zero of M^-1 c_l^T (j on a part l has no coordinate on): a sum that starts at
    !> +0 is never -0, so adding such a zero (C finite) leaves it as it is.
    subroutine dense_terms(self)
        type(saddle_point_type), intent(inout) :: self
        logical :: touches(self%parts)
        integer :: part_block(self%parts)
        integer :: b, i, j, k, l, m, p, x, e, runs, columns, first, last, pass, place, &
            & previous_x, previous_place

        allocate(self%run_start(size(self%block_schur) + 1), source=1)
        allocate(self%column_start(self%parts + 1), source=1)
        part_block = 0
        associate (blocks => self%blocks)
            do b = 1, blocks%count
                if (self%block_sparse(b)) cycle
                do j = blocks%coordinate_start(b), blocks%coordinate_start(b + 1) - 1, 6
                    part_block((blocks%coordinates(j) - 1)/6 + 1) = b
                end do
            end do
            ! the first pass counts, the second fills
            do pass = 1, 2
                runs = 0
                do b = 1, blocks%count
                    if (self%block_sparse(b)) cycle
                    m = blocks%row_start(b + 1) - blocks%row_start(b)
                    do j = 1, m
                        l = blocks%rows(blocks%row_start(b) + j - 1)
                        call parts_touched(blocks, l, touches)
                        do i = 1, m
                            k = blocks%rows(blocks%row_start(b) + i - 1)
                            e = self%schur_start(b) + i - 1 + m*(j - 1)
                            self%run_start(e) = runs + 1
                            if (.not. self%block_shares(e)) cycle
                            ! (no index is -1: the entry's first term starts a run)
                            previous_x = -2
                            previous_place = -2
                            do x = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                                if (.not. touches((blocks%ucon_coordinates(x) - 1)/6 + 1)) cycle
                                place = self%minv_start(l) - 1 &
                                    & + self%coordinate_place(blocks%ucon_coordinates(x))
                                if (x == previous_x + 1 .and. place == previous_place + 1) then
                                    if (pass == 2) self%run_length(runs) = &
                                        & self%run_length(runs) + 1
                                else
                                    runs = runs + 1
                                    if (pass == 2) then
                                        self%run_value(runs) = x
                                        self%run_minv(runs) = place
                                        self%run_length(runs) = 1
                                    end if
                                end if
                                previous_x = x
                                previous_place = place
                            end do
                        end do
                    end do
                end do
                self%run_start(size(self%run_start)) = runs + 1
                ! each part's columns: its block's UCONs with a coordinate on it (a dense
                ! block's by its rows, a sparse block's by the part's own UCONs, part_ucons)
                columns = 0
                do p = 1, self%parts
                    self%column_start(p) = columns + 1
                    b = part_block(p)
                    if (b == 0) then
                        ! a sparse block's part (or one in no block: no UCON then)
                        if (.not. allocated(self%part_ucon_start)) cycle
                        do i = self%part_ucon_start(p), self%part_ucon_start(p + 1) - 1
                            call add_column(p, self%part_ucons(i), 0)
                        end do
                        cycle
                    end if
                    do i = blocks%row_start(b), blocks%row_start(b + 1) - 1
                        call add_column(p, blocks%rows(i), i - blocks%row_start(b) + 1)
                    end do
                end do
                self%column_start(self%parts + 1) = columns + 1
                if (pass == 1) allocate(self%run_value(runs), self%run_minv(runs), &
                    & self%run_length(runs), &
                    & self%column_ucon(columns), self%column_row(columns), &
                    & self%column_offset(columns), &
                    & self%column_first(columns), self%column_last(columns))
            end do
        end associate

    contains

        !> Part p's column of UCON k, when k has a coordinate on p: C's entries on the part
        !> (first, last) and its place in minv_values; row, k's place among its dense block's
        !> rows (0 in a sparse block, whose S goes through KLU). The first pass counts.
        subroutine add_column(p, k, row)
            integer, intent(in) :: p, k, row
            integer :: x, first, last

            first = 0
            last = 0
            do x = self%blocks%ucon_start(k), self%blocks%ucon_start(k + 1) - 1
                if ((self%blocks%ucon_coordinates(x) - 1)/6 + 1 /= p) cycle
                if (first == 0) first = x
                last = x
            end do
            if (first == 0) return
            columns = columns + 1
            if (pass == 1) return
            self%column_ucon(columns) = k
            self%column_row(columns) = row
            self%column_offset(columns) = part_offset(self, p, k)
            self%column_first(columns) = first
            self%column_last(columns) = last
        end subroutine add_column
    end subroutine dense_terms

    !> The places of M^-1 C^T's columns by blocks (minv_start, coordinate_place) and their
    !> values, zero.
    subroutine size_columns(self)
        type(saddle_point_type), intent(inout) :: self
        integer :: b, i, k, total, width

        associate (blocks => self%blocks, nc => self%nc)
            allocate(self%coordinate_place(self%n), source=0)
            allocate(self%minv_start(nc + 1))
            do b = 1, blocks%count
                do i = blocks%coordinate_start(b), blocks%coordinate_start(b + 1) - 1
                    self%coordinate_place(blocks%coordinates(i)) = i &
                        & - blocks%coordinate_start(b) + 1
                end do
            end do
            ! a UCON in no block (none) has an empty column
            self%minv_start = 1
            total = 0
            do k = 1, nc
                self%minv_start(k) = total + 1
                b = blocks%row_block(k)
                width = 0
                if (b > 0) then
                    if (self%block_sparse(b)) then
                        width = 6*(self%ucon_part_start(k + 1) - self%ucon_part_start(k))
                    else
                        width = blocks%coordinate_start(b + 1) - blocks%coordinate_start(b)
                    end if
                end if
                total = total + width
            end do
            self%minv_start(nc + 1) = total + 1
            allocate(self%minv_values(max(total, 1)), source=0.0_wp)
        end associate
    end subroutine size_columns

    !> Where part p's six rows of M^-1 c_k^T are in minv_values (offset: rows offset + 1 ..
    !> offset + 6), -1 where the column holds none (an exact zero there).
    pure integer function part_offset(self, p, k) result(offset)
        type(saddle_point_type), intent(in) :: self
        integer, intent(in) :: p, k
        integer :: b, x

        offset = -1
        b = self%blocks%row_block(k)
        if (b <= 0) return
        if (self%block_sparse(b)) then
            do x = self%ucon_part_start(k), self%ucon_part_start(k + 1) - 1
                if (self%ucon_parts(x) == p) then
                    offset = self%minv_start(k) - 1 + 6*(x - self%ucon_part_start(k))
                    return
                end if
            end do
        else
            if (self%coordinate_place(6*(p - 1) + 1) == 0) return
            offset = self%minv_start(k) - 2 + self%coordinate_place(6*(p - 1) + 1)
        end if
    end function part_offset

    !> For each entry (k, l) of every dense block's S, whether UCONs k and l share a part: M is
    !> block diagonal by parts, so M^-1 c_l^T is zero outside l's parts, and c_k outside k's
    !> own coordinates.
    subroutine find_shares(self)
        type(saddle_point_type), intent(inout) :: self
        logical :: touches(self%parts)
        integer :: b, i, j, k, l, m, x

        allocate(self%block_shares(size(self%block_schur)), source=.false.)
        associate (blocks => self%blocks)
            do b = 1, blocks%count
                ! a sparse block's entries are found by sparse_pattern
                if (self%block_sparse(b)) cycle
                m = blocks%row_start(b + 1) - blocks%row_start(b)
                do j = 1, m
                    l = blocks%rows(blocks%row_start(b) + j - 1)
                    call parts_touched(blocks, l, touches)
                    do i = 1, m
                        k = blocks%rows(blocks%row_start(b) + i - 1)
                        do x = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                            if (touches((blocks%ucon_coordinates(x) - 1)/6 + 1)) &
                                & self%block_shares(self%schur_start(b) + i - 1 + m*(j - 1)) &
                                & = .true.
                        end do
                    end do
                end do
            end do
        end associate
    end subroutine find_shares

    !> The sparse blocks' patterns of S (UCONs k, l couple when they share a part), each
    !> analysed by KLU, and the coordinates each entry sums over.
    subroutine sparse_pattern(self, error)
        type(saddle_point_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: count_of(:), mark(:), column_start(:), row(:), list(:)
        integer :: k, l, i, j, p, b, e, m, x, y, q, first
        integer :: parts_count, list_count, entries, columns, coordinates, starts
        logical :: shared

        associate (blocks => self%blocks, nc => self%nc)
            ! each UCON's parts, ascending (from its ascending coordinates)
            allocate(self%ucon_part_start(nc + 1))
            parts_count = 0
            self%ucon_part_start(1) = 1
            do k = 1, nc
                do i = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                    p = (blocks%ucon_coordinates(i) - 1)/6 + 1
                    if (parts_count >= self%ucon_part_start(k)) then
                        if (self%ucon_parts(parts_count) == p) cycle
                    end if
                    call append(self%ucon_parts, parts_count, p)
                end do
                self%ucon_part_start(k + 1) = parts_count + 1
            end do
            call trimmed(self%ucon_parts, parts_count)
            ! each part's UCONs, ascending
            allocate(count_of(self%parts), source=0)
            do i = 1, size(self%ucon_parts)
                count_of(self%ucon_parts(i)) = count_of(self%ucon_parts(i)) + 1
            end do
            allocate(self%part_ucon_start(self%parts + 1))
            self%part_ucon_start(1) = 1
            do p = 1, self%parts
                self%part_ucon_start(p + 1) = self%part_ucon_start(p) + count_of(p)
            end do
            allocate(self%part_ucons(size(self%ucon_parts)))
            count_of = 0
            do k = 1, nc
                do i = self%ucon_part_start(k), self%ucon_part_start(k + 1) - 1
                    p = self%ucon_parts(i)
                    self%part_ucons(self%part_ucon_start(p) + count_of(p)) = k
                    count_of(p) = count_of(p) + 1
                end do
            end do
            allocate(self%row_local(nc), source=0)
            do b = 1, blocks%count
                do i = blocks%row_start(b), blocks%row_start(b + 1) - 1
                    self%row_local(blocks%rows(i)) = i - blocks%row_start(b) + 1
                end do
            end do
            ! the entries, block by block, column by column (rows ascending)
            allocate(self%entry_start(blocks%count + 1), mark(nc), list(nc), source=0)
            entries = 0
            columns = 0
            coordinates = 0
            starts = 0
            call append(self%entry_coordinate_start, starts, 1)
            self%entry_start(1) = 1
            do b = 1, blocks%count
                self%entry_start(b + 1) = self%entry_start(b)
                if (.not. self%block_sparse(b)) cycle
                m = blocks%row_start(b + 1) - blocks%row_start(b)
                allocate(column_start(m + 1))
                column_start(1) = 1
                first = entries + 1
                do j = 1, m
                    l = blocks%rows(blocks%row_start(b) + j - 1)
                    list_count = 0
                    do x = self%ucon_part_start(l), self%ucon_part_start(l + 1) - 1
                        p = self%ucon_parts(x)
                        do y = self%part_ucon_start(p), self%part_ucon_start(p + 1) - 1
                            k = self%part_ucons(y)
                            if (mark(k) /= 0) cycle
                            mark(k) = 1
                            list_count = list_count + 1
                            list(list_count) = k
                        end do
                    end do
                    list(:list_count) = ascending(list(:list_count))
                    do i = 1, list_count
                        k = list(i)
                        mark(k) = 0
                        call append(self%entry_column, columns, l)
                        call append(self%entry_row, entries, k)
                        ! k's coordinates on a part of l
                        do q = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                            p = (blocks%ucon_coordinates(q) - 1)/6 + 1
                            shared = any(self%ucon_parts(self%ucon_part_start(l): &
                                & self%ucon_part_start(l + 1) - 1) == p)
                            if (shared) call append(self%entry_places, coordinates, q)
                        end do
                        call append(self%entry_coordinate_start, starts, coordinates + 1)
                    end do
                    column_start(j + 1) = column_start(j) + list_count
                end do
                self%entry_start(b + 1) = entries + 1
                allocate(row(entries + 1 - first))
                do e = first, entries
                    row(e - first + 1) = self%row_local(self%entry_row(e))
                end do
                call self%sparse(b)%analyse(m, column_start, row, error)
                deallocate(column_start, row)
                if (allocated(error)) return
            end do
            call trimmed(self%entry_row, entries)
            call trimmed(self%entry_column, entries)
            call trimmed(self%entry_places, coordinates)
            call trimmed(self%entry_coordinate_start, starts)
        end associate
    end subroutine sparse_pattern

    !> Factor the saddle-point matrix of mass (n x n, block structure above: given as its
    !> parts' blocks) and the first `rows` rows of C (nc x n, by rows over each UCON's own
    !> coordinates). With r1, the first step of a solve for one right-hand side is taken too,
    !> r1 := M^-1 r1, in the LAPACK calls that give M^-1 C^T (solve then with `scaled`): the
    !> numbers apply_inverse_mass gives, at one call per part fewer. With active (nc, all the
    !> rows), the rows it marks false are set aside (module text).
    subroutine factor(self, mass, c, rows, error, r1, active)
        class(saddle_point_type), intent(inout) :: self
        !> Mass matrix [kg, kg m^2]: its parts' 6 x 6 blocks (6, 6, parts)
        real(wp), intent(in) :: mass(:, :, :)
        !> C by rows, row k over UCON k's own coordinates; with the blocks, its pattern is
        !> theirs (constraint_blocks_type's ucon_start, ucon_coordinates: the same index), over
        !> which the blocks' sums run
        type(constraint_matrix_type), intent(in) :: c
        !> How many rows of c take part
        integer, intent(in) :: rows
        !> Set when a mass block is not positive definite or the constraints are dependent
        type(error_type), allocatable, intent(out) :: error
        !> Momentum rows of one right-hand side (n) on entry, M^-1 times them on exit
        real(wp), intent(inout), optional :: r1(:)
        !> Which of the nc rows take part (rows must be nc); the others are set aside
        logical, intent(in), optional :: active(:)
        integer :: p

        call factor_mass(self, mass, rows, error, active)
        if (allocated(error)) return
        self%by_blocks = self%blocked .and. rows == self%nc .and. rows > 0
        if (self%by_blocks) then
            call factor_blocks(self, c, error, r1)
            if (allocated(error) .or. .not. present(r1)) return
            ! the parts no UCON touches, alone
            do p = 1, self%parts
                if (self%part_blocked(p)) cycle
                call inverse_mass_of_part(self, p, r1, error)
                if (allocated(error)) return
            end do
            return
        end if
        call factor_dense(self, rows, error, r1, c=c)
    end subroutine factor

    !> factor's first step: the rows taken, those set aside (active, as factor's) and the
    !> Cholesky factors of the parts' rotational mass blocks (dpotf2's arithmetic:
    !> factor_cholesky3).
    subroutine factor_mass(self, mass, rows, error, active)
        type(saddle_point_type), intent(inout) :: self
        real(wp), intent(in) :: mass(:, :, :)
        integer, intent(in) :: rows
        type(error_type), allocatable, intent(out) :: error
        logical, intent(in), optional :: active(:)
        integer :: p, info

        self%rows = rows
        self%masked = .false.
        if (present(active) .and. rows == self%nc) self%masked = .not. all(active(:rows))
        if (self%masked) self%active(:rows) = active(:rows)
        self%factorisations = self%factorisations + 1
        do p = 1, self%parts
            self%part_mass(p) = mass(1, 1, p)
            self%rotational(:, :, p) = mass(4:6, 4:6, p)
            call factor_cholesky3(self%rotational(:, :, p), info)
            if (info > 0) then
                call fatal_error(error, "the rotational mass matrix of part number " &
                    & // to_text(p) // " is singular (Euler angles at sin(theta) " &
                    & // "= 0?): dpotf2 info " // to_text(info), stat_lapack)
                return
            end if
        end do
    end subroutine factor_mass

    !> The dense path of factor (rows x rows S in nc x nc, M^-1 C^T in n x nc), on C by rows
    !> (c) or dense (d): each row written whole (n) and summed over as a row of the dense matrix.
    subroutine factor_dense(self, rows, error, r1, c, d)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: rows
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(inout), optional :: r1(:)
        type(constraint_matrix_type), intent(in), optional :: c
        real(wp), intent(in), optional :: d(:, :)
        integer :: k, j, info

        if (present(r1)) then
            call self%apply_inverse_mass(r1, 1, error)
            if (allocated(error)) return
        end if
        if (rows == 0) return
        ! S unblocked (rows x rows in nc x nc): allocated by the first factorisation that needs
        ! it, none on a model whose solves all go by blocks
        if (.not. allocated(self%schur)) allocate(self%schur(self%nc, self%nc), source=0.0_wp)
        if (.not. allocated(self%minv_ct)) allocate(self%minv_ct(self%n, max(self%nc, 1)), &
            & source=0.0_wp)
        do k = 1, rows
            if (present(c)) then
                call c%fill_row(k, self%minv_ct(:, k))
            else
                self%minv_ct(:, k) = d(k, :)
            end if
        end do
        call self%apply_inverse_mass(self%minv_ct, rows, error)
        if (allocated(error)) return
        if (self%masked) then
            do k = 1, rows
                if (.not. self%active(k)) self%minv_ct(:, k) = 0.0_wp
            end do
        end if
        ! row k of C written whole once, then its products with every column of M^-1 C^T
        do k = 1, rows
            call whole_row(self, k, c, d)
            do j = 1, rows
                self%schur(k, j) = dot_product(self%row_scratch, self%minv_ct(:, j))
            end do
        end do
        if (self%masked) then
            do k = 1, rows
                if (self%active(k)) cycle
                self%schur(k, :rows) = 0.0_wp
                self%schur(k, k) = 1.0_wp
            end do
        end if
        call factor_lu(rows, self%schur, self%nc, self%pivots, info)
        call lapack_info_error("dgetf2 (constraint Schur complement)", info, error)
    end subroutine factor_dense

    !> Row k of C written whole into row_scratch (n): from c by rows, else from the dense d.
    subroutine whole_row(self, k, c, d)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: k
        type(constraint_matrix_type), intent(in), optional :: c
        real(wp), intent(in), optional :: d(:, :)

        if (present(c)) then
            call c%fill_row(k, self%row_scratch)
        else
            self%row_scratch(:) = d(k, :)
        end if
    end subroutine whole_row

    !> Solve for m right-hand sides: r1 (n x m) becomes a, r2 (rows x m) becomes lambda;
    !> c (C by rows over each UCON's coordinates) must be the matrix given to factor.
    subroutine solve(self, c, r1, r2, m, error, scaled)
        class(saddle_point_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        !> Number of right-hand sides
        integer, intent(in) :: m
        !> Momentum rows on entry, accelerations on exit (leading dimension n)
        real(wp), intent(inout) :: r1(self%n, m)
        !> Constraint rows on entry, multipliers on exit (leading dimension rows)
        real(wp), intent(inout) :: r2(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        !> r1 holds M^-1 times the momentum rows already (factor's r1)
        logical, intent(in), optional :: scaled
        logical :: done

        done = .false.
        if (present(scaled)) done = scaled
        if (.not. done) then
            call self%apply_inverse_mass(r1, m, error)
            if (allocated(error)) return
        end if
        if (self%rows == 0) return
        if (self%by_blocks) then
            call solve_blocks(self, c, r1, r2, m, error)
            return
        end if
        call solve_dense(self, r1, r2, m, c=c)
    end subroutine solve

    !> The dense path of solve, after r1 := M^-1 r1, on C by rows (c) or dense (d).
    subroutine solve_dense(self, r1, r2, m, c, d)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: m
        real(wp), intent(inout) :: r1(self%n, m), r2(self%rows, m)
        type(constraint_matrix_type), intent(in), optional :: c
        real(wp), intent(in), optional :: d(:, :)
        integer :: j, k

        ! row k of C written whole once, then its products with every right-hand side
        do k = 1, self%rows
            call whole_row(self, k, c, d)
            do j = 1, m
                r2(k, j) = r2(k, j) - dot_product(self%row_scratch, r1(:, j))
            end do
        end do
        if (self%masked) then
            do k = 1, self%rows
                if (.not. self%active(k)) r2(k, :m) = 0.0_wp
            end do
        end if
        call solve_lu(self%rows, m, self%schur, self%nc, self%pivots, r2, self%rows)
        do j = 1, m
            do k = 1, self%rows
                r1(:, j) = r1(:, j) + r2(k, j)*self%minv_ct(:, k)
            end do
        end do
    end subroutine solve_dense

    !> The block path of factor: M^-1 C^T over each block's parts and rows (and M^-1 r1 there,
    !> with r1), each block's S from its rows and coordinates, and its LU factors (dgetf2).
    subroutine factor_blocks(self, c, error, r1)
        type(saddle_point_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(inout), optional :: r1(:)
        integer :: b, i, j, k, kj, m, first, last, info, s0

        associate (blocks => self%blocks)
            do b = 1, blocks%count
                first = blocks%coordinate_start(b)
                last = blocks%coordinate_start(b + 1) - 1
                ! M^-1 c_k^T over the block's parts, for every UCON of the block with a
                ! coordinate on the part (the others' are exact zeros there, set by init): a
                ! dense block's and a sparse one's alike (one call here, which gfortran inlines)
                do j = first, last, 6
                    call part_columns(self, (blocks%coordinates(j) - 1)/6 + 1, c, r1)
                end do
                if (self%block_sparse(b)) then
                    call factor_sparse_block(self, b, c, error)
                    if (allocated(error)) return
                    cycle
                end if
                m = blocks%row_start(b + 1) - blocks%row_start(b)
                s0 = self%schur_start(b) - 1
                if (self%masked) call set_aside_columns(self, b)
                ! each entry over UCON k's own coordinates on kj's parts (C(k, :) is zero off
                ! k's coordinates: c's entry x is C(k, ucon_coordinates(x)); M^-1 c_kj^T off
                ! kj's parts), and an exact zero where k and kj share no part (no terms): the
                ! terms the block's dense sum has beyond these are exact zeros, which change no
                ! sum
                ! (S = C M^-1 C^T is symmetric, but both S(k, kj) and S(kj, k) are summed: the two
                ! sums differ by rounding, and a copy of one moves the outputs, see docs/design.md)
                call schur_entries(m*m, self%run_start(s0 + 1), self%run_value, &
                    & self%run_minv, self%run_length, c%value, self%minv_values, &
                    & self%block_schur(s0 + 1))
                ! a row set aside: its own row and column of S are the identity's (written over
                ! the sums, which have no other effect)
                if (self%masked) then
                    do j = 1, m
                        kj = blocks%rows(blocks%row_start(b) + j - 1)
                        do i = 1, m
                            k = blocks%rows(blocks%row_start(b) + i - 1)
                            if (.not. (self%active(k) .and. self%active(kj))) &
                                & self%block_schur(s0 + i + m*(j - 1)) = merge(1.0_wp, 0.0_wp, &
                                & k == kj)
                        end do
                    end do
                end if
                call factor_lu(m, self%block_schur(self%schur_start(b)), m, &
                    & self%pivots(blocks%row_start(b)), info)
                call lapack_info_error("dgetf2 (constraint Schur complement, a block)", info, &
                    & error)
                if (allocated(error)) return
            end do
        end associate
    end subroutine factor_blocks

    !> The count entries of a dense block's S (schur, packed as block_schur), each the sum from
    !> zero of its terms in order, an exact zero when it has none: init's runs (entry e's are
    !> run_start(e) : run_start(e + 1) - 1, as saddle_point_type's, here from the block's
    !> first entry), each the products of C's values (c's value) by M^-1 C^T's (minv_values)
    !> at consecutive places. Explicit-shape arrays, so that the loops hold their places in
    !> registers (read through the derived type, each entry loaded them again); a run of a
    !> part's three or six coordinates (most of them) written out, the others summed one term
    !> after another (the terms' order is the sum's in every case; the directives only spare
    !> a short run the set-up of a vector or long unrolled loop).
    pure subroutine schur_entries(count, run_start, run_value, run_minv, run_length, value, &
            & minv, schur)
        integer, intent(in) :: count, run_start(count + 1), run_value(*), run_minv(*), &
            & run_length(*)
        real(wp), intent(in) :: value(*), minv(*)
        real(wp), intent(out) :: schur(count)
        real(wp) :: total
        integer :: e, r, t, x, o

        do e = 1, count
            total = 0.0_wp
            do r = run_start(e), run_start(e + 1) - 1
                x = run_value(r)
                o = run_minv(r)
                select case (run_length(r))
                case (3)
                    total = total + value(x)*minv(o)
                    total = total + value(x + 1)*minv(o + 1)
                    total = total + value(x + 2)*minv(o + 2)
                case (6)
                    total = total + value(x)*minv(o)
                    total = total + value(x + 1)*minv(o + 1)
                    total = total + value(x + 2)*minv(o + 2)
                    total = total + value(x + 3)*minv(o + 3)
                    total = total + value(x + 4)*minv(o + 4)
                    total = total + value(x + 5)*minv(o + 5)
                case default
                    !GCC$ novector
                    !GCC$ unroll 2
                    do t = 0, run_length(r) - 1
                        total = total + value(x + t)*minv(o + t)
                    end do
                end select
            end do
            schur(e) = total
        end do
    end subroutine schur_entries

    !> solve (after factor by blocks, all nc rows) for right-hand sides that are nonzero only
    !> over some of the constraints' blocks and their parts (a state block of the ODE form's
    !> Newton matrix: rollcon_equations' ode_jacobian_blocks), held locally: r1's rows are the
    !> coordinates listed (whole parts, ascending; place(j) is coordinate j's row there), r2's
    !> rows the UCONs of the blocks listed, block after block, each block's in its order
    !> (constraint_blocks_type's rows). Touches only those rows, blocks and parts: each entry
    !> is the number solve gives over all n coordinates and nc rows (the same operations in the
    !> same order; the rows and columns left out add exact zeros to none of these), at a cost
    !> and memory that follow the block.
    subroutine solve_local(self, c, coordinates, place, blocks, r1, r2, m, error)
        class(saddle_point_type), intent(inout) :: self
        !> C by rows over each UCON's coordinates, as given to factor
        type(constraint_matrix_type), intent(in) :: c
        !> The coordinates of r1's rows (whole parts, ascending), and each coordinate's row
        !> there (n; read at the coordinates listed only)
        integer, intent(in) :: coordinates(:), place(:)
        !> The constraints' blocks whose UCONs are r2's rows
        integer, intent(in) :: blocks(:)
        !> Number of right-hand sides
        integer, intent(in) :: m
        !> Momentum rows on entry, accelerations on exit (rows: the coordinates listed)
        real(wp), intent(inout) :: r1(:, :)
        !> Constraint rows on entry, multipliers on exit (rows: the blocks' UCONs)
        real(wp), intent(inout) :: r2(:, :)
        type(error_type), allocatable, intent(out) :: error

        if (.not. self%by_blocks .and. self%rows > 0) then
            call fatal_error(error, "saddle point: a solve restricted to blocks needs the " &
                & // "factors by blocks (all the constraint rows)", stat_lapack)
            return
        end if
        call local_solve(self, c, coordinates, place, blocks, size(r1, 1), size(r2, 1), r1, &
            & r2, m, error)
    end subroutine solve_local

    !> solve_local's work, on r1 (ld1 x m) and r2 (ld2 x m) as explicit-shape arrays (the
    !> parts' rotational rows handed over strided, as apply_inverse_mass does).
    subroutine local_solve(self, c, coordinates, place, blocks, ld1, ld2, r1, r2, m, error)
        type(saddle_point_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        integer, intent(in) :: coordinates(:), place(:), blocks(:), ld1, ld2, m
        real(wp), intent(inout) :: r1(ld1, m), r2(ld2, m)
        type(error_type), allocatable, intent(out) :: error
        integer :: i, l, p, b, k, x, j, col, first, width, rows_b, r0, il

        ! r1 := M^-1 r1, part by part, as apply_inverse_mass
        do l = 1, size(coordinates), 6
            p = (coordinates(l) - 1)/6 + 1
            r1(l:l + 2, :m) = r1(l:l + 2, :m)/self%part_mass(p)
            call solve_cholesky3(self%rotational(:, :, p), m, r1(l + 3, 1), ld1)
        end do
        if (self%rows == 0) return
        associate (bl => self%blocks)
            ! lambda, block by block (solve_blocks, solve_sparse_block)
            r0 = 0
            do i = 1, size(blocks)
                b = blocks(i)
                rows_b = bl%row_start(b + 1) - bl%row_start(b)
                if (self%block_sparse(b)) then
                    associate (chunk => self%sparse_gathered)
                        do first = 1, m, size(chunk, 2)
                            width = min(size(chunk, 2), m - first + 1)
                            do col = 1, width
                                call gather_local(self, c, b, place, r1(:, first + col - 1), &
                                    & r2(r0 + 1:r0 + rows_b, first + col - 1), chunk(:, col))
                            end do
                            call self%sparse(b)%solve(chunk, size(chunk, 1), width, error)
                            if (allocated(error)) return
                            r2(r0 + 1:r0 + rows_b, first:first + width - 1) = &
                                & chunk(:rows_b, :width)
                        end do
                    end associate
                else
                    do col = 1, m
                        call gather_local(self, c, b, place, r1(:, col), r2(r0 + 1:r0 + rows_b, &
                            & col), self%gathered(:, col))
                    end do
                    call solve_lu(rows_b, m, self%block_schur(self%schur_start(b)), rows_b, &
                        & self%pivots(bl%row_start(b)), self%gathered, size(self%gathered, 1))
                    r2(r0 + 1:r0 + rows_b, :m) = self%gathered(:rows_b, :m)
                end if
                r0 = r0 + rows_b
            end do
            ! a = M^-1 (r1 + C^T lambda): each row's column of M^-1 C^T over its block, a
            ! block's rows ascending as solve_blocks adds them (the other blocks' columns are
            ! zero on these coordinates); a dense block's part by part over init's columns, as
            ! solve_blocks
            do col = 1, m
                r0 = 0
                do i = 1, size(blocks)
                    b = blocks(i)
                    if (.not. self%block_sparse(b)) then
                        do j = bl%coordinate_start(b), bl%coordinate_start(b + 1) - 1, 6
                            p = (bl%coordinates(j) - 1)/6 + 1
                            l = place(bl%coordinates(j))
                            do il = self%column_start(p), self%column_start(p + 1) - 1
                                x = self%column_offset(il)
                                r1(l:l + 5, col) = r1(l:l + 5, col) + r2(r0 &
                                    & + self%column_row(il), col)*self%minv_values(x + 1:x + 6)
                            end do
                        end do
                        r0 = r0 + bl%row_start(b + 1) - bl%row_start(b)
                        cycle
                    end if
                    do il = bl%row_start(b), bl%row_start(b + 1) - 1
                        k = bl%rows(il)
                        r0 = r0 + 1
                        do j = self%ucon_part_start(k), self%ucon_part_start(k + 1) - 1
                            l = place(6*(self%ucon_parts(j) - 1) + 1)
                            x = self%minv_start(k) - 1 + 6*(j - self%ucon_part_start(k))
                            r1(l:l + 5, col) = r1(l:l + 5, col) &
                                & + r2(r0, col)*self%minv_values(x + 1:x + 6)
                        end do
                    end do
                end do
            end do
        end associate
    end subroutine local_solve

    !> Block b's rows of r2 - C M^-1 r1 (M^-1 r1 given) for one right-hand side held locally
    !> (r1 over the coordinates by place, r2 over the block's rows), each over its UCON's
    !> coordinates as solve sums it (C's row_dot); zero for a row set aside.
    pure subroutine gather_local(self, c, b, place, r1, r2, gathered)
        type(saddle_point_type), intent(in) :: self
        type(constraint_matrix_type), intent(in) :: c
        integer, intent(in) :: b, place(:)
        real(wp), intent(in) :: r1(:), r2(:)
        real(wp), intent(inout) :: gathered(:)
        real(wp) :: total
        integer :: i, k, x

        associate (bl => self%blocks)
            do i = 1, bl%row_start(b + 1) - bl%row_start(b)
                k = bl%rows(bl%row_start(b) + i - 1)
                total = 0.0_wp
                do x = bl%ucon_start(k), bl%ucon_start(k + 1) - 1
                    total = total + c%value(x)*r1(place(bl%ucon_coordinates(x)))
                end do
                gathered(i) = r2(i) - total
                if (self%masked) then
                    if (.not. self%active(k)) gathered(i) = 0.0_wp
                end if
            end do
        end associate
    end subroutine gather_local

    !> The block path of solve, after r1 := M^-1 r1: lambda block by block, then a.
    subroutine solve_blocks(self, c, r1, r2, m, error)
        type(saddle_point_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        integer, intent(in) :: m
        real(wp), intent(inout) :: r1(self%n, m), r2(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: total
        integer :: b, i, j, k, rows_b, first, last, col, x, p, i0

        associate (blocks => self%blocks)
            do b = 1, blocks%count
                first = blocks%coordinate_start(b)
                last = blocks%coordinate_start(b + 1) - 1
                rows_b = blocks%row_start(b + 1) - blocks%row_start(b)
                if (self%block_sparse(b)) then
                    call solve_sparse_block(self, b, c, r1, r2, m, error)
                    if (allocated(error)) return
                    cycle
                end if
                do col = 1, m
                    do i = 1, rows_b
                        k = blocks%rows(blocks%row_start(b) + i - 1)
                        ! C's row k times r1 (c%row_dot's sum, written out: a call a row cost
                        ! more than its few terms)
                        total = 0.0_wp
                        do x = c%start(k), c%start(k + 1) - 1
                            total = total + c%value(x)*r1(c%column(x), col)
                        end do
                        self%gathered(i, col) = r2(k, col) - total
                        if (self%masked) then
                            if (.not. self%active(k)) self%gathered(i, col) = 0.0_wp
                        end if
                    end do
                end do
                call solve_lu(rows_b, m, self%block_schur(self%schur_start(b)), rows_b, &
                    & self%pivots(blocks%row_start(b)), self%gathered, size(self%gathered, 1))
                call scatter_rows(blocks, b, self%gathered, m, r2)
            end do
            ! a = M^-1 (r1 + C^T lambda): each row's column of M^-1 C^T over its block, rows in
            ! ascending order as the dense path adds them; a dense block's part by part, over
            ! the UCONs with a coordinate on it (init's columns, ascending: the others' columns
            ! are exact zeros there)
            do col = 1, m
                do b = 1, blocks%count
                    if (self%block_sparse(b)) cycle
                    do j = blocks%coordinate_start(b), blocks%coordinate_start(b + 1) - 1, 6
                        p = (blocks%coordinates(j) - 1)/6 + 1
                        i0 = 6*(p - 1)
                        do i = self%column_start(p), self%column_start(p + 1) - 1
                            x = self%column_offset(i)
                            r1(i0 + 1:i0 + 6, col) = r1(i0 + 1:i0 + 6, col) &
                                & + r2(self%column_ucon(i), col)*self%minv_values(x + 1:x + 6)
                        end do
                    end do
                end do
                do k = 1, self%rows
                    b = blocks%row_block(k)
                    if (.not. self%block_sparse(b)) cycle
                    ! a sparse block's column of M^-1 C^T is over its UCON's parts only
                    do j = self%ucon_part_start(k), self%ucon_part_start(k + 1) - 1
                        i = 6*(self%ucon_parts(j) - 1)
                        x = self%minv_start(k) - 1 + 6*(j - self%ucon_part_start(k))
                        r1(i + 1:i + 6, col) = r1(i + 1:i + 6, col) &
                            & + r2(k, col)*self%minv_values(x + 1:x + 6)
                    end do
                end do
            end do
        end associate
    end subroutine solve_blocks

    !> M^-1 c_k^T over part p (zero elsewhere, as the dense path leaves it) for each UCON k
    !> with a coordinate on it (init's columns, column_start), and M^-1 r1 there with r1: the
    !> translational rows divided by the mass, the rotational rows of every UCON (and of r1)
    !> in one solve_cholesky3 (each column solved alone: the numbers of one solve per UCON).
    !> C(k, :) over the part is read from c's entries column_first(i) : column_last(i). For
    !> the parts of dense and of sparse blocks alike.
    subroutine part_columns(self, p, c, r1)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: p
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(inout), optional :: r1(:)
        real(wp) :: part_row(6)
        integer :: i, i0, col, extra, o, x

        extra = merge(1, 0, present(r1))
        i0 = 6*(p - 1)
        associate (rot => self%rotational_rows)
            if (present(r1)) then
                r1(i0 + 1:i0 + 3) = r1(i0 + 1:i0 + 3)/self%part_mass(p)
                rot(:, 1) = r1(i0 + 4:i0 + 6)
            end if
            col = extra
            do i = self%column_start(p), self%column_start(p + 1) - 1
                o = self%column_offset(i)
                x = self%column_first(i)
                col = col + 1
                if (self%column_last(i) - x == 5) then
                    ! all six of the part's coordinates (ascending): C(k, i0 + 1 : i0 + 6) are
                    ! c's entries x : x + 5 as they are
                    self%minv_values(o + 1:o + 3) = c%value(x:x + 2)/self%part_mass(p)
                    rot(:, col) = c%value(x + 3:x + 5)
                    cycle
                end if
                part_row = 0.0_wp
                do x = self%column_first(i), self%column_last(i)
                    part_row(c%column(x) - i0) = c%value(x)
                end do
                self%minv_values(o + 1:o + 3) = part_row(1:3)/self%part_mass(p)
                rot(:, col) = part_row(4:6)
            end do
            call solve_cholesky3(self%rotational(:, :, p), col, rot, 3)
            if (present(r1)) r1(i0 + 4:i0 + 6) = rot(:, 1)
            col = extra
            do i = self%column_start(p), self%column_start(p + 1) - 1
                col = col + 1
                o = self%column_offset(i)
                self%minv_values(o + 4:o + 6) = rot(:, col)
            end do
        end associate
    end subroutine part_columns

    !> factor_blocks for a sparse block b, after its parts' M^-1 C^T (part_columns): S's
    !> nonzeros (UCONs sharing a part) and their KLU factors.
    subroutine factor_sparse_block(self, b, c, error)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: total
        integer :: j, k, e, l, x, q

        associate (blocks => self%blocks)
            if (self%masked) call set_aside_columns(self, b)
            associate (lu => self%sparse(b))
                do e = self%entry_start(b), self%entry_start(b + 1) - 1
                    k = self%entry_row(e)
                    l = self%entry_column(e)
                    total = 0.0_wp
                    do x = self%entry_coordinate_start(e), self%entry_coordinate_start(e + 1) - 1
                        q = self%entry_places(x)
                        j = blocks%ucon_coordinates(q)
                        total = total + c%value(q)*self%minv_values(part_offset(self, (j - 1)/6 &
                            & + 1, l) + mod(j - 1, 6) + 1)
                    end do
                    if (self%masked) then
                        if (.not. (self%active(k) .and. self%active(l))) &
                            & total = merge(1.0_wp, 0.0_wp, k == l)
                    end if
                    lu%values(e - self%entry_start(b) + 1) = total
                end do
                call lu%factor(error)
            end associate
        end associate
    end subroutine factor_sparse_block

    !> solve_blocks for a sparse block b: lambda's rows of the block, r2 - C M^-1 r1 over each
    !> UCON's coordinates, through KLU.
    subroutine solve_sparse_block(self, b, c, r1, r2, m, error)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: b, m
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(inout) :: r1(self%n, m), r2(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: total
        integer :: i, k, x, col, rows_b, first, width

        associate (blocks => self%blocks, chunk => self%sparse_gathered)
            rows_b = blocks%row_start(b + 1) - blocks%row_start(b)
            ! size(chunk, 2) right-hand sides at a time, KLU's own group (klu_solve takes them
            ! four by four): the same arithmetic on each as all at once, in a rows x 4 array
            do first = 1, m, size(chunk, 2)
                width = min(size(chunk, 2), m - first + 1)
                do col = 1, width
                    do i = 1, rows_b
                        k = blocks%rows(blocks%row_start(b) + i - 1)
                        total = 0.0_wp
                        do x = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                            total = total + c%value(x) &
                                & *r1(blocks%ucon_coordinates(x), first + col - 1)
                        end do
                        chunk(i, col) = r2(k, first + col - 1) - total
                        if (self%masked) then
                            if (.not. self%active(k)) chunk(i, col) = 0.0_wp
                        end if
                    end do
                end do
                call self%sparse(b)%solve(chunk, size(chunk, 1), width, error)
                if (allocated(error)) return
                call scatter_rows(blocks, b, chunk, width, r2(:, first:first + width - 1))
            end do
        end associate
    end subroutine solve_sparse_block

    !> The columns of M^-1 C^T of block b's rows set aside zeroed (they add nothing to a).
    pure subroutine set_aside_columns(self, b)
        type(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: b
        integer :: i, k

        do i = self%blocks%row_start(b), self%blocks%row_start(b + 1) - 1
            k = self%blocks%rows(i)
            if (.not. self%active(k)) self%minv_values(self%minv_start(k): &
                & self%minv_start(k + 1) - 1) = 0.0_wp
        end do
    end subroutine set_aside_columns

    !> Block b's solved rows (gathered, in the block's order) into r2's rows of its UCONs, for
    !> m right-hand sides.
    pure subroutine scatter_rows(blocks, b, gathered, m, r2)
        type(constraint_blocks_type), intent(in) :: blocks
        integer, intent(in) :: b, m
        real(wp), intent(in) :: gathered(:, :)
        real(wp), intent(inout) :: r2(:, :)
        integer :: i, col

        do col = 1, m
            do i = 1, blocks%row_start(b + 1) - blocks%row_start(b)
                r2(blocks%rows(blocks%row_start(b) + i - 1), col) = gathered(i, col)
            end do
        end do
    end subroutine scatter_rows

    !> x := M^-1 x over part p's rows, for one column x (n).
    subroutine inverse_mass_of_part(self, p, x, error)
        type(saddle_point_type), intent(in) :: self
        integer, intent(in) :: p
        real(wp), intent(inout) :: x(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: rotational_rows(3)
        integer :: i0

        i0 = 6*(p - 1)
        x(i0 + 1:i0 + 3) = x(i0 + 1:i0 + 3)/self%part_mass(p)
        rotational_rows = x(i0 + 4:i0 + 6)
        call solve_cholesky3(self%rotational(:, :, p), 1, rotational_rows, 3)
        x(i0 + 4:i0 + 6) = rotational_rows
    end subroutine inverse_mass_of_part

    !> x := M^-1 x for the m columns of x (leading dimension n), part by part.
    subroutine apply_inverse_mass(self, x, m, error)
        class(saddle_point_type), intent(in) :: self
        real(wp), intent(inout) :: x(self%n, *)
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        integer :: p, i0

        do p = 1, self%parts
            i0 = 6*(p - 1)
            x(i0 + 1:i0 + 3, :m) = x(i0 + 1:i0 + 3, :m)/self%part_mass(p)
            ! rows i0+4..i0+6 of every column: the element x(i0 + 4, 1) with leading dimension n
            ! hands that strided block over without a copy
            call solve_cholesky3(self%rotational(:, :, p), m, x(i0 + 4, 1), self%n)
        end do
    end subroutine apply_inverse_mass

    !> Free the KLU factors of the sparse blocks (memory outside Fortran's, which leaving the
    !> object's scope does not free): a process that runs many models one after another (a
    !> study's cases) calls it when a model is done. The object may be initialised again.
    subroutine release(self)
        class(saddle_point_type), intent(inout) :: self
        integer :: b

        if (.not. allocated(self%sparse)) return
        do b = 1, size(self%sparse)
            call self%sparse(b)%release()
        end do
    end subroutine release

    !> Which parts (touches, one entry per part, model order) UCON l has a coordinate on:
    !> every part of its own coordinates (blocks' ucon_coordinates, six a part).
    pure subroutine parts_touched(blocks, l, touches)
        type(constraint_blocks_type), intent(in) :: blocks
        integer, intent(in) :: l
        logical, intent(out) :: touches(:)
        integer :: x

        touches = .false.
        do x = blocks%ucon_start(l), blocks%ucon_start(l + 1) - 1
            touches((blocks%ucon_coordinates(x) - 1)/6 + 1) = .true.
        end do
    end subroutine parts_touched

end module rollcon_saddle_point
