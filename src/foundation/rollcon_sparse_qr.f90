! SPDX-License-Identifier: MIT
!> The numerical rank of a sparse matrix through SuiteSparseQR (SuiteSparse's rank-revealing
!> sparse QR, linked by fpm.toml as "spqr" with CHOLMOD; the C side is rollcon_spqr.c): columns
!> ordered to reduce fill (SPQR_ORDERING_DEFAULT), a column whose norm after the reflections of
!> those before it is at most the tolerance counted dependent (Heath's rule; Davis, ACM TOMS
!> 38(1), 2011). For matrices whose nonzeros grow as their order and whose dense pivoted QR
!> (rollcon_lapack's pivoted_columns) would cost the cube of it (sparse_rank). On a matrix given
!> by its rows (each ascending in its
!> columns): the least-squares solution of least norm (sparse_minimum_norm) and which rows take
!> part in a dependency (sparse_dependent_rows), both through the QR of its transpose: the
!> initial-conditions analysis on a large model (rollcon_ic_rows). With the columns' order held
!> (SPQR_ORDERING_FIXED, some columns put first): which columns a greedy choice in that order
!> keeps and their distances |R(k,k)| (sparse_grouped_rank), and how a last column is a
!> combination of the others (sparse_combination): which rows of a large block of joints
!> repeat others (rollcon_redundancy).
module rollcon_sparse_qr
    use, intrinsic :: iso_c_binding, only : c_int, c_double
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    implicit none
    private

    public :: sparse_rank, sparse_minimum_norm, sparse_dependent_rows, sparse_grouped_rank, &
        & sparse_combination

    interface
        function rollcon_spqr_rank(m, n, ap, ai, ax, tol, order, diagonal, status) &
                & result(rank) bind(c, name="rollcon_spqr_rank")
            import :: c_int, c_double
            integer(c_int), value :: m, n
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            real(c_double), value :: tol
            integer(c_int), intent(out) :: order(*)
            real(c_double), intent(out) :: diagonal(*)
            integer(c_int), intent(out) :: status
            integer(c_int) :: rank
        end function rollcon_spqr_rank

        function rollcon_spqr_min_norm(m, n, rp, rj, rx, tol, b, x, status) result(info) &
                & bind(c, name="rollcon_spqr_min_norm")
            import :: c_int, c_double
            integer(c_int), value :: m, n
            integer(c_int), intent(in) :: rp(*), rj(*)
            real(c_double), intent(in) :: rx(*)
            real(c_double), value :: tol
            real(c_double), intent(in) :: b(*)
            real(c_double), intent(out) :: x(*)
            integer(c_int), intent(out) :: status
            integer(c_int) :: info
        end function rollcon_spqr_min_norm

        function rollcon_spqr_dependent(m, n, rp, rj, rx, tol, involvement, involved, status) &
                & result(rank) bind(c, name="rollcon_spqr_dependent")
            import :: c_int, c_double
            integer(c_int), value :: m, n
            integer(c_int), intent(in) :: rp(*), rj(*)
            real(c_double), intent(in) :: rx(*)
            real(c_double), value :: tol, involvement
            integer(c_int), intent(out) :: involved(*)
            integer(c_int), intent(out) :: status
            integer(c_int) :: rank
        end function rollcon_spqr_dependent

        function rollcon_spqr_grouped_rank(m, n, ap, ai, ax, tol, group, fill, bound, order, &
                & diagonal, status) result(rank) bind(c, name="rollcon_spqr_grouped_rank")
            import :: c_int, c_double
            integer(c_int), value :: m, n
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            real(c_double), value :: tol
            integer(c_int), intent(in) :: group(*)
            integer(c_int), value :: fill
            real(c_double), value :: bound
            integer(c_int), intent(out) :: order(*)
            real(c_double), intent(out) :: diagonal(*)
            integer(c_int), intent(out) :: status
            integer(c_int) :: rank
        end function rollcon_spqr_grouped_rank

        function rollcon_spqr_combination(m, n, ap, ai, ax, tol, x, status) result(rank) &
                & bind(c, name="rollcon_spqr_combination")
            import :: c_int, c_double
            integer(c_int), value :: m, n
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            real(c_double), value :: tol
            real(c_double), intent(out) :: x(*)
            integer(c_int), intent(out) :: status
            integer(c_int) :: rank
        end function rollcon_spqr_combination
    end interface

contains

    !> The rank of the m x n matrix given in compressed columns (1-based: column j's entries
    !> at column_start(j) .. column_start(j + 1) - 1 of row and values; n = size(column_start)
    !> - 1), columns of norm at most tolerance after the reflections of those before them
    !> counted dependent. order (n): the columns in SPQR's order of elimination; diagonal (n):
    !> |R(k,k)| of column order(k), that column's distance from the span of the columns before
    !> it (0 past the rank). Error (stat_lapack) when SPQR fails (out of memory).
    subroutine sparse_rank(m, column_start, row, values, tolerance, rank, order, diagonal, &
            & error)
        integer, intent(in) :: m, column_start(:), row(:)
        real(wp), intent(in) :: values(:)
        real(wp), intent(in) :: tolerance
        integer, intent(out) :: rank
        integer, intent(out) :: order(:)
        real(wp), intent(out) :: diagonal(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int), allocatable :: ap(:), ai(:), found(:)
        real(c_double), allocatable :: ax(:), lengths(:)
        integer(c_int) :: status
        integer :: n

        n = size(column_start) - 1
        ap = int(column_start - 1, c_int)
        ai = int(row(:column_start(n + 1) - 1) - 1, c_int)
        ax = real(values(:column_start(n + 1) - 1), c_double)
        allocate(found(max(n, 1)), lengths(max(n, 1)))
        rank = int(rollcon_spqr_rank(int(m, c_int), int(n, c_int), ap, ai, ax, &
            & real(tolerance, c_double), found, lengths, status))
        if (rank < 0) then
            call fatal_error(error, "SuiteSparseQR could not factor a sparse matrix of " &
                & // to_text(m) // " rows and " // to_text(n) // " columns: CHOLMOD status " &
                & // to_text(int(status)), stat_lapack)
            return
        end if
        order = int(found(:n)) + 1
        diagonal = real(lengths(:n), wp)
    end subroutine sparse_rank

    !> The x (n) of least norm among those that minimise |A x - b|, A the m x n matrix given by
    !> its rows (1-based: row i's entries at row_start(i) .. row_start(i + 1) - 1 of column and
    !> values, columns ascending; m = size(row_start) - 1), b (m): the SVD's minimum-norm
    !> solution (rollcon_least_squares' minimum_norm_solve) with the rank judged by Heath's rule.
    !> SuiteSparseQR factors A^T (A^T E = Q [R11 R12], rows of A whose norm after the
    !> reflections of those before them is at most tolerance dead); all rows live, x = Q R^-T
    !> E^T b (SPQR's min2norm scheme); else the dead rows are the combinations R11^-1 R12 of the
    !> live ones A_L, the misfit is spread over all rows by SPQR's least squares on [I; K], and
    !> x is the least-norm solution of A_L x = v (rollcon_spqr.c). Memory and time grow as the
    !> nonzeros of A and of R, not as m n. Error (stat_lapack) when SPQR fails (out of memory).
    subroutine sparse_minimum_norm(n, row_start, column, values, b, tolerance, x, error)
        integer, intent(in) :: n, row_start(:), column(:)
        real(wp), intent(in) :: values(:), b(:), tolerance
        real(wp), intent(out) :: x(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int), allocatable :: rp(:), rj(:)
        real(c_double), allocatable :: rx(:), found(:)
        integer(c_int) :: status
        integer :: m, nnz

        m = size(row_start) - 1
        x = 0.0_wp
        if (m == 0 .or. n == 0) return
        nnz = row_start(m + 1) - 1
        rp = int(row_start - 1, c_int)
        rj = int(column(:nnz) - 1, c_int)
        rx = real(values(:nnz), c_double)
        allocate(found(n))
        if (rollcon_spqr_min_norm(int(m, c_int), int(n, c_int), rp, rj, rx, &
                & real(tolerance, c_double), real(b, c_double), found, status) < 0) then
            call fatal_error(error, "SuiteSparseQR could not solve a sparse least-squares " &
                & // "problem of " // to_text(m) // " rows and " // to_text(n) &
                & // " columns: CHOLMOD status " // to_text(int(status)), stat_lapack)
            return
        end if
        x = real(found, wp)
    end subroutine sparse_minimum_norm

    !> The rank of the m x n matrix A given by its rows (as sparse_minimum_norm), rows of norm at
    !> most tolerance after the reflections of those before them dependent (Heath's rule), and
    !> involved (m): the rows that have an entry above involvement in a unit vector w with
    !> A^T w = 0 (they take part in a dependency). The null vectors come from R of SPQR's QR of
    !> A^T, one per dependent row, by back substitution on R's triangle: no m x n array. Error
    !> (stat_lapack) when SPQR fails (out of memory).
    subroutine sparse_dependent_rows(n, row_start, column, values, tolerance, involvement, &
            & rank, involved, error)
        integer, intent(in) :: n, row_start(:), column(:)
        real(wp), intent(in) :: values(:), tolerance, involvement
        integer, intent(out) :: rank
        logical, intent(out) :: involved(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int), allocatable :: rp(:), rj(:), flags(:)
        real(c_double), allocatable :: rx(:)
        integer(c_int) :: status
        integer :: m, nnz

        m = size(row_start) - 1
        rank = 0
        involved = .false.
        if (m == 0) return
        nnz = row_start(m + 1) - 1
        rp = int(row_start - 1, c_int)
        rj = int(column(:max(nnz, 0)) - 1, c_int)
        rx = real(values(:max(nnz, 0)), c_double)
        if (nnz == 0) then
            rj = [0_c_int]
            rx = [0.0_c_double]
        end if
        allocate(flags(m))
        rank = int(rollcon_spqr_dependent(int(m, c_int), int(max(n, 1), c_int), rp, rj, rx, &
            & real(tolerance, c_double), real(involvement, c_double), flags, status))
        if (rank < 0) then
            call fatal_error(error, "SuiteSparseQR could not factor a sparse matrix of " &
                & // to_text(m) // " rows and " // to_text(n) // " columns: CHOLMOD status " &
                & // to_text(int(status)), stat_lapack)
            return
        end if
        involved = flags /= 0
    end subroutine sparse_dependent_rows

    !> The greedy choice of independent columns of the m x n matrix given in compressed columns
    !> (as sparse_rank) in a column order that puts the columns j with leading(j) first: within
    !> each group (leading, the others) in COLAMD's fill-reducing order (fill_reducing), or as
    !> given. SuiteSparseQR factors the columns in that order held (SPQR_ORDERING_FIXED): a
    !> column whose norm after the reflections of the columns kept before it is at most
    !> tolerance repeats them (Heath's rule) and is not kept; tolerance < 0: every column kept.
    !> With bound > 1, then swaps of strong rank-revealing QR (Gu and Eisenstat, SIAM J. Sci.
    !> Comput. 17(4), 1996): a column not kept, the combination c of those kept, is kept instead
    !> of a kept column j not leading where |c_j| > bound (the kept columns' volume |det R11|
    !> grows by |c_j|), refactored until none is left (rollcon_spqr.c): the choice of the
    !> better-conditioned rows that a pivoted QR makes, which the greedy order alone does not.
    !> rank: the columns kept; order (n): those kept in that order, then the others in it;
    !> diagonal (n): |R(k,k)| of a kept column order(k), its distance from the span of those
    !> kept before it, 0 for the others. Memory grows as the nonzeros of the matrix and of R;
    !> time as them for each factorisation, and a round of swaps as the columns not kept times
    !> R's nonzeros. Error (stat_lapack) when SPQR fails (out of memory).
    subroutine sparse_grouped_rank(m, column_start, row, values, tolerance, leading, &
            & fill_reducing, bound, rank, order, diagonal, error)
        integer, intent(in) :: m, column_start(:), row(:)
        real(wp), intent(in) :: values(:), tolerance
        logical, intent(in) :: leading(:), fill_reducing
        real(wp), intent(in) :: bound
        integer, intent(out) :: rank, order(:)
        real(wp), intent(out) :: diagonal(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int), allocatable :: ap(:), ai(:), found(:), group(:)
        real(c_double), allocatable :: ax(:), lengths(:)
        integer(c_int) :: status
        integer :: n, nnz

        n = size(column_start) - 1
        rank = 0
        if (n == 0) return
        nnz = column_start(n + 1) - 1
        ap = int(column_start - 1, c_int)
        allocate(ai(max(nnz, 1)), ax(max(nnz, 1)))
        ai = 0
        ax = 0.0_c_double
        ai(:nnz) = int(row(:nnz) - 1, c_int)
        ax(:nnz) = real(values(:nnz), c_double)
        group = merge(0_c_int, 1_c_int, leading)
        allocate(found(n), lengths(n))
        rank = int(rollcon_spqr_grouped_rank(int(max(m, 1), c_int), int(n, c_int), ap, ai, ax, &
            & real(tolerance, c_double), group, merge(1_c_int, 0_c_int, fill_reducing), &
            & real(bound, c_double), found, lengths, status))
        if (rank < 0) then
            call fatal_error(error, "SuiteSparseQR could not factor a sparse matrix of " &
                & // to_text(m) // " rows and " // to_text(n) // " columns: CHOLMOD status " &
                & // to_text(int(status)), stat_lapack)
            return
        end if
        order = int(found) + 1
        diagonal = real(lengths, wp)
    end subroutine sparse_grouped_rank

    !> How the last column b of the m x n matrix [A b] given in compressed columns (as
    !> sparse_rank) lies in the span of the others: x (n - 1) with A x the projection of b on
    !> the span of A's columns kept by a greedy choice in their order (Heath's rule with
    !> tolerance, as sparse_grouped_rank), 0 on those not kept: R11^-1 R(kept, b) from
    !> SuiteSparseQR's QR of [A b] in that order held, by back substitution. When A's columns
    !> are independent, the least-squares solution of A x = b. rank: A's columns kept. Error
    !> (stat_lapack) when SPQR fails (out of memory).
    subroutine sparse_combination(m, column_start, row, values, tolerance, x, rank, error)
        integer, intent(in) :: m, column_start(:), row(:)
        real(wp), intent(in) :: values(:), tolerance
        real(wp), intent(out) :: x(:)
        integer, intent(out) :: rank
        type(error_type), allocatable, intent(out) :: error
        integer(c_int), allocatable :: ap(:), ai(:)
        real(c_double), allocatable :: ax(:), found(:)
        integer(c_int) :: status
        integer :: n, nnz

        n = size(column_start) - 1
        x = 0.0_wp
        rank = 0
        if (n < 2) return
        nnz = column_start(n + 1) - 1
        ap = int(column_start - 1, c_int)
        allocate(ai(max(nnz, 1)), ax(max(nnz, 1)))
        ai = 0
        ax = 0.0_c_double
        ai(:nnz) = int(row(:nnz) - 1, c_int)
        ax(:nnz) = real(values(:nnz), c_double)
        allocate(found(n))
        rank = int(rollcon_spqr_combination(int(max(m, 1), c_int), int(n, c_int), ap, ai, ax, &
            & real(tolerance, c_double), found, status))
        if (rank < 0) then
            call fatal_error(error, "SuiteSparseQR could not factor a sparse matrix of " &
                & // to_text(m) // " rows and " // to_text(n) // " columns: CHOLMOD status " &
                & // to_text(int(status)), stat_lapack)
            return
        end if
        x = real(found(:n - 1), wp)
    end subroutine sparse_combination

end module rollcon_sparse_qr
