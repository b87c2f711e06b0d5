! SPDX-License-Identifier: MIT
!> LU factors with partial pivoting, their solves, and the Cholesky factor of a 3 x 3 matrix and
!> its solve, for the small dense matrices of the saddle-point system (a part's rotational mass,
!> a block's Schur complement of at most a few dozen rows): the arithmetic of the reference
!> LAPACK's dgetf2, dgetrs, dpotf2 ("L") and dpotrs ("L") with the reference BLAS they call
!> (idamax, dswap, dscal, dger, dlaswp, dtrsm, ddot, dgemv), operation for operation and in the
!> same order, without the cost of a library call per column (on the bicycle's 21 rows the calls
!> cost more than the arithmetic; a part's dpotf2 cost more than its 3 x 3 arithmetic). With the
!> reference LAPACK and BLAS, as the published figures use (docs/benchmark.md), the numbers are
!> theirs bit for bit; with another LAPACK they are those of the reference one.
module rollcon_small_dense
    use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: factor_lu, solve_lu, factor_cholesky3, solve_cholesky3

contains

    !> The LU factors of the n x n matrix a with partial pivoting, P a = L U (L unit lower, both
    !> in a), as dgetf2: the first largest magnitude of a column is its pivot, the multipliers
    !> are scaled by the pivot's reciprocal unless it is below the smallest normal number.
    !> info: 0, or the first column whose pivot is an exact zero (the factors are then
    !> complete but U is singular).
    pure subroutine factor_lu(n, a, lda, pivots, info)
        integer, intent(in) :: n, lda
        real(wp), intent(inout) :: a(lda, *)
        !> Row i was interchanged with row pivots(i)
        integer, intent(out) :: pivots(*)
        integer, intent(out) :: info
        real(wp) :: largest, swap, reciprocal, temp
        integer :: i, j, k, p

        info = 0
        do j = 1, n
            p = j
            largest = abs(a(j, j))
            do i = j + 1, n
                if (abs(a(i, j)) > largest) then
                    p = i
                    largest = abs(a(i, j))
                end if
            end do
            pivots(j) = p
            if (a(p, j) /= 0.0_wp) then
                if (p /= j) then
                    do k = 1, n
                        swap = a(j, k)
                        a(j, k) = a(p, k)
                        a(p, k) = swap
                    end do
                end if
                if (j < n) then
                    if (abs(a(j, j)) >= tiny(1.0_wp)) then
                        reciprocal = 1.0_wp/a(j, j)
                        do i = j + 1, n
                            a(i, j) = reciprocal*a(i, j)
                        end do
                    else
                        do i = j + 1, n
                            a(i, j) = a(i, j)/a(j, j)
                        end do
                    end if
                end if
            else if (info == 0) then
                info = j
            end if
            ! the trailing matrix less the outer product (dger with alpha = -1: a column whose
            ! row j entry is an exact zero is left as it is). The directives change no
            ! operation: column k is not column j (lda >= n), so no row's update depends on
            ! another's, and a column of a few dozen rows is cheaper without gfortran's
            ! eight-fold unrolling (its set-up cost more than it saved on the bicycle's S)
            do k = j + 1, n
                if (a(j, k) /= 0.0_wp) then
                    temp = -a(j, k)
                    !GCC$ ivdep
                    !GCC$ unroll 2
                    do i = j + 1, n
                        a(i, k) = a(i, k) + a(i, j)*temp
                    end do
                end if
            end do
        end do
    end subroutine factor_lu

    !> Solve a x = b for nrhs columns with factor_lu's factors, as dgetrs ("N"): the row
    !> interchanges, then L (unit) and U column by column, an exact zero skipped as dtrsm skips
    !> it. b (ldb x nrhs) becomes x.
    pure subroutine solve_lu(n, nrhs, a, lda, pivots, b, ldb)
        integer, intent(in) :: n, nrhs, lda, ldb
        real(wp), intent(in) :: a(lda, *)
        integer, intent(in) :: pivots(*)
        real(wp), intent(inout) :: b(ldb, *)
        real(wp) :: swap
        integer :: i, j, k

        do k = 1, n
            if (pivots(k) == k) cycle
            do j = 1, nrhs
                swap = b(k, j)
                b(k, j) = b(pivots(k), j)
                b(pivots(k), j) = swap
            end do
        end do
        ! (the directives as factor_lu's: row i is not row k, each row's update is its own)
        do j = 1, nrhs
            do k = 1, n
                if (b(k, j) /= 0.0_wp) then
                    !GCC$ ivdep
                    !GCC$ unroll 2
                    do i = k + 1, n
                        b(i, j) = b(i, j) - b(k, j)*a(i, k)
                    end do
                end if
            end do
            do k = n, 1, -1
                if (b(k, j) /= 0.0_wp) then
                    b(k, j) = b(k, j)/a(k, k)
                    !GCC$ ivdep
                    !GCC$ unroll 2
                    do i = 1, k - 1
                        b(i, j) = b(i, j) - b(k, j)*a(i, k)
                    end do
                end if
            end do
        end do
    end subroutine solve_lu

    !> The lower Cholesky factor l l^T = a of a symmetric 3 x 3 matrix (lower triangle read,
    !> the factor written over it; the upper triangle untouched), as dpotf2 ("L") with the
    !> reference BLAS: column j's diagonal a(j, j) less the sum (from zero, in order) of the
    !> squares of row j's factor, its square root, the entries below less row j's factor times
    !> theirs (dgemv: each earlier column's term added in turn), times the root's reciprocal
    !> (dscal). info: 0, or the first column whose diagonal is not positive (or NaN) before its
    !> root: that diagonal is left there, the later columns untouched.
    pure subroutine factor_cholesky3(a, info)
        real(wp), intent(inout) :: a(3, 3)
        integer, intent(out) :: info
        real(wp) :: ajj, dot, temp, reciprocal
        integer :: i, j, k

        info = 0
        do j = 1, 3
            dot = 0.0_wp
            do k = 1, j - 1
                dot = dot + a(j, k)*a(j, k)
            end do
            ajj = a(j, j) - dot
            if (ajj <= 0.0_wp .or. ieee_is_nan(ajj)) then
                a(j, j) = ajj
                info = j
                return
            end if
            ajj = sqrt(ajj)
            a(j, j) = ajj
            if (j < 3) then
                do k = 1, j - 1
                    temp = -a(j, k)
                    do i = j + 1, 3
                        a(i, j) = a(i, j) + temp*a(i, k)
                    end do
                end do
                reciprocal = 1.0_wp/ajj
                do i = j + 1, 3
                    a(i, j) = reciprocal*a(i, j)
                end do
            end if
        end do
    end subroutine factor_cholesky3

    !> Solve l l^T x = b for nrhs columns, l the lower Cholesky factor of a 3 x 3 matrix (its
    !> upper triangle not read), as dpotrs ("L"): l y = b (an exact zero of y skipped as dtrsm
    !> skips it), then l^T x = y. b (ldb x nrhs: rows 1 to 3 of each column) becomes x.
    pure subroutine solve_cholesky3(l, nrhs, b, ldb)
        real(wp), intent(in) :: l(3, 3)
        integer, intent(in) :: nrhs, ldb
        real(wp), intent(inout) :: b(ldb, *)
        real(wp) :: temp
        integer :: i, j, k

        do j = 1, nrhs
            do k = 1, 3
                if (b(k, j) /= 0.0_wp) then
                    b(k, j) = b(k, j)/l(k, k)
                    do i = k + 1, 3
                        b(i, j) = b(i, j) - b(k, j)*l(i, k)
                    end do
                end if
            end do
            do i = 3, 1, -1
                temp = b(i, j)
                do k = i + 1, 3
                    temp = temp - l(k, i)*b(k, j)
                end do
                b(i, j) = temp/l(i, i)
            end do
        end do
    end subroutine solve_cholesky3

end module rollcon_small_dense
