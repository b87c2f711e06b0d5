! SPDX-License-Identifier: MIT
!> The numerical rank of a sparse matrix through SuiteSparseQR (SuiteSparse's rank-revealing
!> sparse QR, linked by fpm.toml as "spqr" with CHOLMOD; the C side is rollcon_spqr.c): columns
!> ordered to reduce fill (SPQR_ORDERING_DEFAULT), a column whose norm after the reflections of
!> those before it is at most the tolerance counted dependent (Heath's rule; Davis, ACM TOMS
!> 38(1), 2011). For matrices whose nonzeros grow as their order and whose dense pivoted QR
!> (rollcon_lapack's pivoted_columns) would cost the cube of it: the unit rows of a long
!> chain's joints (rollcon_redundancy).
module rollcon_sparse_qr
    use, intrinsic :: iso_c_binding, only : c_int, c_double
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    implicit none
    private

    public :: sparse_rank

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

end module rollcon_sparse_qr
