! SPDX-License-Identifier: MIT
!> Redundant constraint rows (docs/design.md §4, "Redundant constraints"): the rows of a block
!> (rollcon_constraint_blocks) that repeat others are found and set aside, so that the rows
!> left, the active ones, are independent and every formulation can solve them.
!>
!> The rows are compared in a metric that does not depend on units: row k of C (dF_k/du, or
!> dF_k/dq for a position UCON) becomes the column L^-1 c_k^T / |L^-1 c_k^T| over its block's
!> coordinates, L L^T = M the mass matrix (part by part: sqrt(m) for translations, the Cholesky
!> factor of B^T J B for the angles). Its Gram matrix is the Schur complement C M^-1 C^T with
!> unit diagonal: a UCON's scale, the units and the coordinates (a re-basing) do not change it.
!> The choice is LAPACK's QR with column pivoting (dgeqp3) on those unit columns, position
!> UCONs first: their rows are chosen among themselves (a position UCON also holds its
!> position, which the velocity rows cannot), then fixed in front while the others are
!> pivoted. |R(k,k)| of a unit column is its distance from the span of those chosen before it:
!> a row whose distance is at most rank_tolerance repeats them and is set aside. A block of
!> sparse_schur_rows rows or more (a long chain, one block: its dense QRs would cost the cube of
!> its rows and hold rows x coordinates) is chosen by SuiteSparseQR on the same unit columns
!> held sparse (rollcon_sparse_qr's sparse_grouped_rank, the same tolerance), with the column
!> order held: the position UCONs' first among themselves, then every column with those kept
!> in front, each a greedy choice in that order (COLAMD's within each group) followed by the
!> swaps of a strong rank-revealing QR (swap_bound), which keep the better-conditioned rows a
!> pivoted QR would; its distances are |R(k,k)| in that order, its measure, the words'
!> dependencies and the multipliers' split come from sparse factors (choose_sparse_block,
!> sparse_measure, sparse_dependency, sparse_multipliers): no rows x coordinates array and no
!> SVD. The rows it sets aside may differ from the dense choice's, equally valid.
!>
!> A set-aside row's multiplier is zero; the constraint force C^T lambda is the same for any
!> split of it between dependent rows, so the split reported (multipliers) is the one of least
!> norm in the same metric, lambda_k |L^-1 c_k^T| (a UCON's scale does not change it). The
!> choice wears when the configuration moves (a cart's redundant row changes with its
!> heading): its measure, the smallest singular value of the active unit columns (the Schur
!> complement of the active rows has condition sigma_max^2 / sigma_min^2, sigma_max <=
!> sqrt(rows); on a large block the smallest |R(k,k)| of their sparse QR in the order of the
!> choice held, at least sigma_min and zero where it is: sparse_measure), is watched against its
!> value at the choice (margin), and a block is chosen again (rechoose) with the same number of
!> rows when it has fallen to measure_ratio of it.
module rollcon_redundancy
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_lapack, only : pivoted_columns
    use rollcon_least_squares, only : minimum_norm_solve, smallest_singular_value
    use rollcon_sparse_qr, only : sparse_grouped_rank, sparse_combination, sparse_minimum_norm
    use rollcon_constraint_blocks, only : constraint_blocks_type
    use rollcon_constraint_matrix, only : constraint_matrix_type
    use rollcon_saddle_point, only : sparse_schur_rows
    implicit none
    private

    public :: redundancy_type, rank_tolerance, measure_ratio

    !> A unit row is set aside when its distance from the span of the rows chosen before it
    !> (|R(k,k)| of the pivoted QR) is at most this, sqrt(machine epsilon), the rank threshold of
    !> the initial-conditions analysis (rollcon_ic_rows' ic_rcond). Measured at the start of
    !> every shipped dataset and field case (docs/design.md §4): the rows that repeat others lie
    !> at round-off, 5.6e-17 (a four-bar of REVOLUTEs), 1.3e-16 (a slider-crank), 2.1e-16 (a
    !> two-wheeled cart); the nearest a row kept comes is 7.5e-3 (a double pendulum of light
    !> links), 0.19 (data/bicycle.adm's 21 rows): the threshold sits 7.8 decades above the one
    !> and 5.7 below the other
    real(wp), parameter :: rank_tolerance = 1.4901161193847656e-8_wp
    !> A block is chosen again when its measure (module text) has fallen to this fraction of its
    !> value at the choice: the active rows' Schur complement is then at most 1/0.3^2 = 11
    !> times worse conditioned than at the choice, and its multipliers' errors grow with it.
    !> The speed partition's worn_ratio (rollcon_speed_partition), measured there
    real(wp), parameter :: measure_ratio = 0.3_wp
    !> A large block's sparse choice (choose_sparse_block) keeps a row set aside instead of a
    !> row kept where the kept one's coefficient in its combination exceeds this: Gu and
    !> Eisenstat's f of a strong rank-revealing QR (their bounds: the kept rows' singular
    !> values within a factor sqrt(1 + f^2 r (m - r)) of the best); 2: each swap at least
    !> doubles the volume of the rows kept, so swaps are few
    real(wp), parameter :: swap_bound = 2.0_wp

    !> The rows set aside, block by block
    type :: redundancy_type
        !> Constraint rows
        integer :: nc = 0
        !> Which rows are active (true) or set aside
        logical, allocatable :: active(:)
        !> Rows set aside
        integer :: set_aside = 0
        !> Each block's active rows, and how many of those are position UCONs (fixed at the
        !> first choice: a choice again keeps them)
        integer, allocatable :: kept(:), kept_position(:)
        !> Each block's measure at its choice, and whether it has rows set aside
        real(wp), allocatable :: measure_chosen(:)
        logical, allocatable :: redundant(:)
        !> For each row, its distance |R(k,k)| at the first choice (the rank gap; 0 for a row
        !> pivoted past its block's coordinates, and on a large block for a row set aside)
        real(wp), allocatable :: distance(:)
        !> For each row of a large block (sparse_schur_rows rows or more), its place in the
        !> column order of the block's last sparse choice (the rows kept first): the order its
        !> measure's QR holds (margin), 0 on a small block
        integer, allocatable :: sequence(:)
        !> Choices made since init (the first included), and the choices again that changed
        !> the rows set aside
        integer :: choices = 0, changes = 0
        !> The rows the first choice set aside, in the user's words (rollcon_redundancy_words;
        !> set by the equations' choose_active): "" when none
        character(len=:), allocatable :: words
        !> The rows that take part in a dependency (the rows set aside and those they repeat):
        !> their multipliers are not unique (rollcon_redundancy_words; false until described)
        logical, allocatable :: involved(:)
    contains
        procedure :: init
        procedure :: choose
        procedure :: rechoose
        procedure :: margin
        procedure :: multipliers
        procedure :: dependency
    end type redundancy_type

contains

    !> Every row active, for nc rows in the given blocks; no choice yet.
    subroutine init(self, nc, blocks)
        class(redundancy_type), intent(inout) :: self
        integer, intent(in) :: nc
        type(constraint_blocks_type), intent(in) :: blocks

        self%nc = nc
        self%set_aside = 0
        self%words = ""
        self%choices = 0
        self%changes = 0
        if (allocated(self%active)) deallocate(self%active, self%kept, self%kept_position, &
            & self%measure_chosen, self%redundant, self%distance, self%involved, self%sequence)
        allocate(self%active(nc), source=.true.)
        allocate(self%sequence(nc), source=0)
        allocate(self%involved(nc), source=.false.)
        allocate(self%kept(blocks%count), self%kept_position(blocks%count), source=0)
        allocate(self%measure_chosen(blocks%count), self%distance(nc), source=0.0_wp)
        allocate(self%redundant(blocks%count), source=.false.)
    end subroutine init

    !> The first choice, every block's: its rank from rank_tolerance (module text), at the
    !> state where c (C, nc x n by rows over each UCON's own coordinates,
    !> rollcon_constraint_matrix: dF/du of a velocity UCON, dF/dq of a position UCON) and mass
    !> (the parts' 6 x 6 blocks, 6 x 6 x parts) were assembled.
    subroutine choose(self, c, mass, blocks, holonomic, error)
        class(redundancy_type), intent(inout) :: self
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        !> Which rows are position UCONs
        logical, intent(in) :: holonomic(:)
        type(error_type), allocatable, intent(out) :: error
        logical :: changed
        integer :: b

        self%choices = self%choices + 1
        self%active = .true.
        do b = 1, blocks%count
            call choose_block(self, b, c, mass, blocks, holonomic, .true., changed, error)
            if (allocated(error)) return
        end do
        self%set_aside = count(.not. self%active)
    end subroutine choose

    !> Block b chosen again with the ranks of the first choice (changed: other rows set aside
    !> now); its measure at this state becomes the reference either way.
    subroutine rechoose(self, b, c, mass, blocks, holonomic, changed, error)
        class(redundancy_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        logical, intent(in) :: holonomic(:)
        logical, intent(out) :: changed
        type(error_type), allocatable, intent(out) :: error

        self%choices = self%choices + 1
        call choose_block(self, b, c, mass, blocks, holonomic, .false., changed, error)
        if (changed) self%changes = self%changes + 1
        self%set_aside = count(.not. self%active)
    end subroutine rechoose

    !> Block b's choice (first: its ranks from the tolerance; else those of the first choice):
    !> dense below sparse_schur_rows rows, else choose_sparse_block.
    subroutine choose_block(self, b, c, mass, blocks, holonomic, first, changed, error)
        type(redundancy_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        logical, intent(in) :: holonomic(:), first
        logical, intent(out) :: changed
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), norms(:), diagonal(:), position_diagonal(:), &
            & position_columns(:, :)
        integer, allocatable :: rows(:), order(:), position(:), position_order(:)
        logical, allocatable :: leading(:), before(:)
        integer :: m, r, rp, k

        changed = .false.
        rows = blocks%block_rows(b)
        m = size(rows)
        if (m >= sparse_schur_rows) then
            ! a large block (a long chain: its dense QRs would cost the cube of its rows and
            ! hold rows x coordinates): the choice by SuiteSparseQR
            call choose_sparse_block(self, b, c, mass, blocks, holonomic, first, changed, &
                & error)
            return
        end if
        call unit_columns(c, mass, blocks%block_coordinates(b), rows, a, norms)
        position = pack([(k, k = 1, m)], holonomic(rows))
        allocate(leading(m), source=.false.)
        rp = self%kept_position(b)
        if (size(position) > 0) then
            allocate(position_order(size(position)), &
                & position_diagonal(min(size(a, 1), size(position))))
            position_columns = a(:, position)
            call pivoted_columns(position_columns, position_order, position_diagonal, error)
            if (allocated(error)) return
            if (first) rp = leading_count(position_diagonal)
            leading(position(position_order(:rp))) = .true.
        else
            rp = 0
        end if
        allocate(order(m), diagonal(min(size(a, 1), m)))
        call pivoted_columns(a, order, diagonal, error, leading)
        if (allocated(error)) return
        r = self%kept(b)
        if (first) r = rp + leading_count(diagonal(rp + 1:))
        before = self%active(rows)
        self%active(rows) = .false.
        self%active(rows(order(:r))) = .true.
        changed = any(before .neqv. self%active(rows))
        if (first) then
            self%kept(b) = r
            self%kept_position(b) = rp
            self%distance(rows) = 0.0_wp
            self%distance(rows(order(:size(diagonal)))) = diagonal
        end if
        self%redundant(b) = r < m
        self%measure_chosen(b) = 0.0_wp
        if (self%redundant(b)) then
            self%measure_chosen(b) = smallest_singular_value(a(:, order(:r)), error)
            if (allocated(error)) return
        end if
    end subroutine choose_block

    !> choose_block for a large block b (module text): its unit columns held sparse
    !> (sparse_unit_columns), the choice of SuiteSparseQR with the column order held
    !> (sparse_grouped_rank, rank_tolerance). The position UCONs' columns first among
    !> themselves (COLAMD's order): rp kept (first: by the tolerance; else kept_position(b), the
    !> first rp of those kept then those not); then every column, those rp in front and the
    !> others after them (COLAMD's order within each): r kept likewise (first: by the
    !> tolerance; else kept(b)). A column kept is farther than rank_tolerance from the span of
    !> those kept before it; one not kept lies within it. Distances: |R(k,k)| in that order (0
    !> for a row set aside); the measure: sparse_measure of the rows kept, in that order.
    subroutine choose_sparse_block(self, b, c, mass, blocks, holonomic, first, changed, error)
        type(redundancy_type), intent(inout) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        logical, intent(in) :: holonomic(:), first
        logical, intent(out) :: changed
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: rows(:), column_start(:), row(:), order(:), position(:), &
            & position_start(:), position_row(:), position_order(:)
        real(wp), allocatable :: values(:), diagonal(:), position_values(:), &
            & position_diagonal(:)
        logical, allocatable :: before(:), leading(:)
        integer :: m, r, rp, k, rank

        changed = .false.
        rows = blocks%block_rows(b)
        m = size(rows)
        position = pack([(k, k = 1, m)], holonomic(rows))
        allocate(leading(m), source=.false.)
        rp = 0
        if (size(position) > 0) then
            call sparse_unit_columns(c, mass, blocks, rows(position), position_start, &
                & position_row, position_values)
            allocate(position_order(size(position)), position_diagonal(size(position)))
            call sparse_grouped_rank(c%n, position_start, position_row, position_values, &
                & rank_tolerance, [(.false., k = 1, size(position))], .true., swap_bound, rp, &
                & position_order, position_diagonal, error)
            if (allocated(error)) return
            if (.not. first) rp = self%kept_position(b)
            leading(position(position_order(:rp))) = .true.
        end if
        call sparse_unit_columns(c, mass, blocks, rows, column_start, row, values)
        allocate(order(m), diagonal(m))
        call sparse_grouped_rank(c%n, column_start, row, values, rank_tolerance, leading, &
            & .true., swap_bound, rank, order, diagonal, error)
        if (allocated(error)) return
        r = rank
        if (.not. first) r = self%kept(b)
        before = self%active(rows)
        self%active(rows) = .false.
        self%active(rows(order(:r))) = .true.
        changed = any(before .neqv. self%active(rows))
        do k = 1, m
            self%sequence(rows(order(k))) = k
        end do
        if (first) then
            self%kept(b) = r
            self%kept_position(b) = rp
            self%distance(rows(order)) = diagonal
        end if
        self%redundant(b) = r < m
        self%measure_chosen(b) = 0.0_wp
        if (self%redundant(b)) then
            self%measure_chosen(b) = sparse_measure(self, b, c, mass, blocks, error)
            if (allocated(error)) return
        end if
    end subroutine choose_sparse_block

    !> The measure of a large block b's rows kept (module text): the smallest |R(k,k)| of
    !> SuiteSparseQR's QR of their unit columns in the order of its last choice (sequence)
    !> held. It is at least their smallest singular value (sigma_min <= min |R(k,k)| for any
    !> QR) and, R's determinant being the product of the singular values, it falls to zero
    !> where theirs does: where the rows kept lose their rank. The order held makes it a
    !> continuous function of the state (a watched event function).
    function sparse_measure(self, b, c, mass, blocks, error) result(value)
        type(redundancy_type), intent(in) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value
        integer, allocatable :: rows(:), placed(:), column_start(:), row(:), order(:)
        real(wp), allocatable :: values(:), diagonal(:)
        integer :: k, rank

        value = 0.0_wp
        rows = blocks%block_rows(b)
        allocate(placed(size(rows)), source=0)
        do k = 1, size(rows)
            if (self%active(rows(k))) placed(self%sequence(rows(k))) = rows(k)
        end do
        rows = pack(placed, placed > 0)
        if (size(rows) == 0) return
        call sparse_unit_columns(c, mass, blocks, rows, column_start, row, values)
        allocate(order(size(rows)), diagonal(size(rows)))
        call sparse_grouped_rank(c%n, column_start, row, values, -1.0_wp, &
            & [(.true., k = 1, size(rows))], .false., 0.0_wp, rank, order, diagonal, error)
        if (allocated(error)) return
        value = minval(diagonal)
    end function sparse_measure

    !> The unit columns of unit_columns for the rows k, in compressed columns (1-based), over
    !> the system's coordinates (n rows, c%n): each row's column nonzero over the parts of its
    !> UCON's own coordinates only (C, held by rows over each UCON's own coordinates, is zero on
    !> the block's other parts, and so are unit_columns' entries there), 6 per part, ascending.
    subroutine sparse_unit_columns(c, mass, blocks, rows, column_start, row, values, norms)
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        integer, intent(in) :: rows(:)
        integer, allocatable, intent(out) :: column_start(:), row(:)
        real(wp), allocatable, intent(out) :: values(:)
        !> The columns' lengths before they were scaled to unit length
        real(wp), intent(out), optional :: norms(:)
        real(wp) :: factor(3, 3), rotational(3, 3), length, entries(6)
        integer :: i, k, x0, p, last, i0, e, first_entry

        allocate(column_start(size(rows) + 1))
        allocate(row(6*(blocks%ucon_start(size(blocks%ucon_start)) - 1)), &
            & values(6*(blocks%ucon_start(size(blocks%ucon_start)) - 1)))
        e = 0
        column_start(1) = 1
        do i = 1, size(rows)
            k = rows(i)
            first_entry = e + 1
            last = 0
            do x0 = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                p = (blocks%ucon_coordinates(x0) - 1)/6 + 1
                if (p == last) cycle
                last = p
                i0 = 6*(p - 1)
                rotational = mass(4:6, 4:6, p)
                factor = cholesky_3(rotational)
                row(e + 1:e + 6) = i0 + [1, 2, 3, 4, 5, 6]
                call c%gather(k, i0 + 1, entries)
                values(e + 1:e + 6) = part_unit(mass(1, 1, p), factor, entries)
                e = e + 6
            end do
            length = norm2(values(first_entry:e))
            if (present(norms)) norms(i) = length
            if (length > 0.0_wp) values(first_entry:e) = values(first_entry:e)/length
            column_start(i + 1) = e + 1
        end do
    end subroutine sparse_unit_columns

    !> How many leading entries of a pivoted QR's |R(k,k)| exceed rank_tolerance.
    pure integer function leading_count(diagonal)
        real(wp), intent(in) :: diagonal(:)

        leading_count = 0
        do while (leading_count < size(diagonal))
            if (.not. diagonal(leading_count + 1) > rank_tolerance) exit
            leading_count = leading_count + 1
        end do
    end function leading_count

    !> Block b's measure at the state of c and mass less measure_ratio times its value at the
    !> choice: positive while the choice suits, zero where it has worn (an event function).
    !> 1 for a block without rows set aside.
    function margin(self, b, c, mass, blocks, error) result(value)
        class(redundancy_type), intent(in) :: self
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value
        real(wp), allocatable :: a(:, :), norms(:)
        integer, allocatable :: rows(:)

        value = 1.0_wp
        if (.not. self%redundant(b)) return
        rows = blocks%block_rows(b)
        if (size(rows) >= sparse_schur_rows) then
            value = sparse_measure(self, b, c, mass, blocks, error) &
                & - measure_ratio*self%measure_chosen(b)
            return
        end if
        rows = pack(rows, self%active(rows))
        call unit_columns(c, mass, blocks%block_coordinates(b), rows, a, norms)
        value = smallest_singular_value(a, error) - measure_ratio*self%measure_chosen(b)
    end function margin

    !> The multipliers of the blocks with rows set aside replaced by the split of least norm
    !> (module text) of the same constraint force C^T lambda; the other blocks' are untouched.
    subroutine multipliers(self, c, mass, blocks, lambda, error)
        class(redundancy_type), intent(in) :: self
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        !> The multipliers of the active rows (0 for those set aside) on entry
        real(wp), intent(inout) :: lambda(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), norms(:), force(:), scaled(:), split(:)
        integer, allocatable :: rows(:), coordinates(:)
        real(wp) :: factor(3, 3), rotational(3, 3), entries(6)
        integer :: b, i, rank, p, i0, j0

        do b = 1, blocks%count
            if (.not. self%redundant(b)) cycle
            rows = blocks%block_rows(b)
            if (size(rows) >= sparse_schur_rows) then
                call sparse_multipliers(b, c, mass, blocks, lambda, error)
                if (allocated(error)) return
                cycle
            end if
            coordinates = blocks%block_coordinates(b)
            ! the constraint force over the block's coordinates (6 per part, ascending), and
            ! L^-1 of it (unit_columns' metric, not scaled to unit length)
            allocate(force(size(coordinates)), scaled(size(coordinates)), source=0.0_wp)
            do i = 1, size(rows)
                do p = 1, size(coordinates)/6
                    j0 = 6*(p - 1)
                    call c%gather(rows(i), coordinates(j0 + 1), entries)
                    force(j0 + 1:j0 + 6) = force(j0 + 1:j0 + 6) + lambda(rows(i))*entries
                end do
            end do
            do p = 1, size(coordinates)/6
                j0 = 6*(p - 1)
                i0 = coordinates(j0 + 1) - 1
                rotational = mass(4:6, 4:6, i0/6 + 1)
                factor = cholesky_3(rotational)
                scaled(j0 + 1:j0 + 6) = part_unit(mass(1, 1, i0/6 + 1), factor, &
                    & force(j0 + 1:j0 + 6))
            end do
            call unit_columns(c, mass, coordinates, rows, a, norms)
            allocate(split(size(rows)))
            call minimum_norm_solve(a, scaled, rank_tolerance, split, rank, error)
            if (allocated(error)) return
            do i = 1, size(rows)
                lambda(rows(i)) = 0.0_wp
                if (norms(i) > 0.0_wp) lambda(rows(i)) = split(i)/norms(i)
            end do
            deallocate(force, scaled, split)
        end do
    end subroutine multipliers

    !> How the set-aside row k repeats the active rows of its block: coefficients x (nc, zero
    !> off them) of least norm with c_k = sum x_l c_l in the unit metric (module text).
    subroutine dependency(self, k, c, mass, blocks, coefficients, error)
        class(redundancy_type), intent(in) :: self
        integer, intent(in) :: k
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        real(wp), intent(out) :: coefficients(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), norms(:), target_row(:, :), x(:)
        integer, allocatable :: rows(:), coordinates(:)
        integer :: b, rank

        coefficients = 0.0_wp
        b = blocks%row_block(k)
        rows = blocks%block_rows(b)
        if (size(rows) >= sparse_schur_rows) then
            call sparse_dependency(self, k, c, mass, blocks, coefficients, error)
            return
        end if
        rows = pack(rows, self%active(rows))
        coordinates = blocks%block_coordinates(b)
        call unit_columns(c, mass, coordinates, rows, a, norms)
        call unit_columns(c, mass, coordinates, [k], target_row, norms)
        allocate(x(size(rows)))
        call minimum_norm_solve(a, target_row(:, 1), rank_tolerance, x, rank, error)
        if (allocated(error)) return
        coefficients(rows) = x
    end subroutine dependency

    !> dependency for a set-aside row k of a large block: the active rows' unit columns in
    !> the order of the block's last choice (sequence), then k's, held sparse; how k's is the
    !> combination of theirs by SuiteSparseQR with that order held (sparse_combination). The
    !> active rows independent, it is the least-squares solution, the only one, the one of
    !> least norm; no rows x coordinates array.
    subroutine sparse_dependency(self, k, c, mass, blocks, coefficients, error)
        type(redundancy_type), intent(in) :: self
        integer, intent(in) :: k
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        real(wp), intent(out) :: coefficients(:)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: rows(:), placed(:), column_start(:), row(:)
        real(wp), allocatable :: values(:), x(:)
        integer :: i, rank

        coefficients = 0.0_wp
        rows = blocks%block_rows(blocks%row_block(k))
        allocate(placed(size(rows)), source=0)
        do i = 1, size(rows)
            if (self%active(rows(i))) placed(self%sequence(rows(i))) = rows(i)
        end do
        rows = [pack(placed, placed > 0), k]
        call sparse_unit_columns(c, mass, blocks, rows, column_start, row, values)
        allocate(x(size(rows) - 1))
        call sparse_combination(c%n, column_start, row, values, rank_tolerance, x, rank, error)
        if (allocated(error)) return
        coefficients(rows(:size(rows) - 1)) = x
    end subroutine sparse_dependency

    !> multipliers for a large block b: the least-norm split of the same force in the unit
    !> metric by SuiteSparseQR (sparse_minimum_norm, rank_tolerance) on the block's unit
    !> columns held sparse (sparse_unit_columns, by rows over the system's coordinates), with
    !> the force over them: no rows x coordinates array and no SVD.
    subroutine sparse_multipliers(b, c, mass, blocks, lambda, error)
        integer, intent(in) :: b
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        real(wp), intent(inout) :: lambda(:)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: rows(:), coordinates(:), column_start(:), row(:), &
            & row_start(:), column(:)
        real(wp), allocatable :: values(:), by_rows(:), force(:), scaled(:), norms(:), split(:)
        real(wp) :: factor(3, 3), rotational(3, 3), entries(6)
        integer :: i, p, i0, j0

        rows = blocks%block_rows(b)
        coordinates = blocks%block_coordinates(b)
        ! the constraint force over the system's coordinates, L^-1 of it on the block's parts
        allocate(force(c%n), scaled(c%n), source=0.0_wp)
        do i = 1, size(rows)
            do p = 1, size(coordinates)/6
                j0 = coordinates(6*(p - 1) + 1) - 1
                call c%gather(rows(i), j0 + 1, entries)
                force(j0 + 1:j0 + 6) = force(j0 + 1:j0 + 6) + lambda(rows(i))*entries
            end do
        end do
        do p = 1, size(coordinates)/6
            i0 = coordinates(6*(p - 1) + 1) - 1
            rotational = mass(4:6, 4:6, i0/6 + 1)
            factor = cholesky_3(rotational)
            scaled(i0 + 1:i0 + 6) = part_unit(mass(1, 1, i0/6 + 1), factor, &
                & force(i0 + 1:i0 + 6))
        end do
        allocate(norms(size(rows)), split(size(rows)))
        call sparse_unit_columns(c, mass, blocks, rows, column_start, row, values, norms)
        call columns_to_rows(c%n, column_start, row, values, row_start, column, by_rows)
        call sparse_minimum_norm(size(rows), row_start, column, by_rows, scaled, &
            & rank_tolerance, split, error)
        if (allocated(error)) return
        do i = 1, size(rows)
            lambda(rows(i)) = 0.0_wp
            if (norms(i) > 0.0_wp) lambda(rows(i)) = split(i)/norms(i)
        end do
    end subroutine sparse_multipliers

    !> The m-row matrix given in compressed columns (column_start, row, values; 1-based) by its
    !> rows (row_start, column, by_rows), each row's columns ascending (a counting sort).
    pure subroutine columns_to_rows(m, column_start, row, values, row_start, column, by_rows)
        integer, intent(in) :: m, column_start(:), row(:)
        real(wp), intent(in) :: values(:)
        integer, allocatable, intent(out) :: row_start(:), column(:)
        real(wp), allocatable, intent(out) :: by_rows(:)
        integer, allocatable :: next(:)
        integer :: j, e, nnz

        nnz = column_start(size(column_start)) - 1
        allocate(row_start(m + 1), source=0)
        allocate(column(nnz), by_rows(nnz))
        do e = 1, nnz
            row_start(row(e) + 1) = row_start(row(e) + 1) + 1
        end do
        row_start(1) = 1
        do j = 1, m
            row_start(j + 1) = row_start(j + 1) + row_start(j)
        end do
        next = row_start(:m)
        do j = 1, size(column_start) - 1
            do e = column_start(j), column_start(j + 1) - 1
                column(next(row(e))) = j
                by_rows(next(row(e))) = values(e)
                next(row(e)) = next(row(e)) + 1
            end do
        end do
    end subroutine columns_to_rows

    !> The columns L^-1 c_k^T over the coordinates (6 per part, ascending) for the rows k of C
    !> (c: by rows over each UCON's own coordinates, zero elsewhere), each of unit length (a
    !> zero row stays zero); norms their lengths.
    subroutine unit_columns(c, mass, coordinates, rows, a, norms)
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        integer, intent(in) :: coordinates(:), rows(:)
        real(wp), allocatable, intent(out) :: a(:, :), norms(:)
        real(wp) :: factor(3, 3), rotational(3, 3), entries(6)
        integer :: p, i0, j0, i

        allocate(a(size(coordinates), size(rows)), norms(size(rows)))
        do p = 1, size(coordinates)/6
            j0 = 6*(p - 1)
            i0 = coordinates(j0 + 1) - 1
            rotational = mass(4:6, 4:6, i0/6 + 1)
            factor = cholesky_3(rotational)
            do i = 1, size(rows)
                call c%gather(rows(i), i0 + 1, entries)
                a(j0 + 1:j0 + 6, i) = part_unit(mass(1, 1, i0/6 + 1), factor, entries)
            end do
        end do
        do i = 1, size(rows)
            norms(i) = norm2(a(:, i))
            if (norms(i) > 0.0_wp) a(:, i) = a(:, i)/norms(i)
        end do
    end subroutine unit_columns

    !> A part's six entries x of a row of C (or of a force over its coordinates) in the unit
    !> metric, L^-1 x: translations over sqrt(m) (m: mass11, the part's mass), the angles by
    !> the lower Cholesky factor (factor) of their 3 x 3 block of M.
    pure function part_unit(mass11, factor, x) result(y)
        real(wp), intent(in) :: mass11, factor(3, 3), x(6)
        real(wp) :: y(6)

        y(1:3) = x(1:3)/sqrt(mass11)
        y(4:6) = forward_3(factor, x(4:6))
    end function part_unit

    !> The lower Cholesky factor of a symmetric positive definite 3 x 3 matrix.
    pure function cholesky_3(m) result(l)
        real(wp), intent(in) :: m(3, 3)
        real(wp) :: l(3, 3)

        l = 0.0_wp
        l(1, 1) = sqrt(m(1, 1))
        l(2, 1) = m(2, 1)/l(1, 1)
        l(3, 1) = m(3, 1)/l(1, 1)
        l(2, 2) = sqrt(m(2, 2) - l(2, 1)**2)
        l(3, 2) = (m(3, 2) - l(3, 1)*l(2, 1))/l(2, 2)
        l(3, 3) = sqrt(m(3, 3) - l(3, 1)**2 - l(3, 2)**2)
    end function cholesky_3

    !> L^-1 x for a lower triangular 3 x 3 L.
    pure function forward_3(l, x) result(y)
        real(wp), intent(in) :: l(3, 3), x(3)
        real(wp) :: y(3)

        y(1) = x(1)/l(1, 1)
        y(2) = (x(2) - l(2, 1)*y(1))/l(2, 2)
        y(3) = (x(3) - l(3, 1)*y(1) - l(3, 2)*y(2))/l(3, 3)
    end function forward_3

end module rollcon_redundancy
