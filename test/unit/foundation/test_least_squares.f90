! SPDX-License-Identifier: MIT
!> The linear algebra of the initial-conditions analysis (rollcon_least_squares) on matrices
!> whose answers are known in closed form: the least-norm solution of an underdetermined
!> system, the least-squares solution of an inconsistent one, the rank as the angle between
!> unit rows against rcond, and the left null space; and the rank of a sparse matrix by
!> SuiteSparseQR (rollcon_sparse_qr), the choice of its columns in an order held with the
!> swaps of a strong rank-revealing QR and a column's combination of the others (the large
!> blocks' of the redundancy choice), and its least-norm solution and dependent rows, a large
!> model's initial-conditions analysis'.
module test_least_squares
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_least_squares, only : minimum_norm_solve, left_null_space
    use rollcon_sparse_qr, only : sparse_rank, sparse_minimum_norm, sparse_dependent_rows, &
        & sparse_grouped_rank, sparse_combination
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_least_squares

    !> LAPACK's SVD is backward stable: on these 2 x 3 and 3 x 3 matrices of order-one entries
    !> and condition below 10, the answers are within a few tens of roundings
    real(wp), parameter :: tol_svd = 100.0_wp*epsilon(1.0_wp)
    !> The threshold of the rank: the sine of the smallest angle between two unit rows that
    !> still count as two constraints
    real(wp), parameter :: rcond = 1.0e-8_wp

contains

    !> Tests of this suite.
    subroutine collect_least_squares(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("least-norm-of-underdetermined", test_underdetermined), &
            & new_unittest("least-squares-of-inconsistent", test_inconsistent), &
            & new_unittest("rank-from-the-angle-of-rows", test_rank), &
            & new_unittest("left-null-space", test_left_null), &
            & new_unittest("empty-matrices", test_empty), &
            & new_unittest("sparse-rank-from-the-angle-of-columns", test_sparse_rank), &
            & new_unittest("sparse-choice-held-order-and-swaps", test_sparse_choice), &
            & new_unittest("sparse-least-norm", test_sparse_least_norm), &
            & new_unittest("sparse-dependent-rows", test_sparse_dependent)]
    end subroutine collect_least_squares

    !> x1 + x2 = 1, x2 + x3 = 2: the solution of least norm is A^T (A A^T)^-1 b = (0, 1, 1)
    !> (A A^T = [2 1; 1 2]), of rank 2; the matrix is not changed.
    subroutine test_underdetermined(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a(2, 3), x(3)
        integer :: rank

        a = reshape([1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 3])
        call minimum_norm_solve(a, [1.0_wp, 2.0_wp], rcond, x, rank, error)
        if (allocated(error)) return
        call check(error, rank, 2, "rank")
        if (allocated(error)) return
        call check(error, x, [0.0_wp, 1.0_wp, 1.0_wp], "least-norm solution", abs_tol=tol_svd)
        if (allocated(error)) return
        call check(error, all(a == reshape([1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], &
            & [2, 3])), "the matrix is not changed")
    end subroutine test_underdetermined

    !> x = 1, x = 2, x = 6 has no solution: the least-squares one is their mean, 3.
    subroutine test_inconsistent(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a(3, 1), x(1)
        integer :: rank

        a = 1.0_wp
        call minimum_norm_solve(a, [1.0_wp, 2.0_wp, 6.0_wp], rcond, x, rank, error)
        if (allocated(error)) return
        call check(error, rank, 1, "rank")
        if (allocated(error)) return
        call check(error, x(1), 3.0_wp, "the mean", abs_tol=tol_svd)
    end subroutine test_inconsistent

    !> Two unit rows at an angle a of 1e-10 rad count as one constraint (rank 1) for
    !> rcond = 1e-8, and at 1e-6 rad as two. With b = (1, 1) the one constraint is the
    !> bisector's, of singular value sqrt(2) cos(a/2): x = (1, tan(a/2)).
    subroutine test_rank(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a(2, 2), x(2)
        real(wp), parameter :: close_angle = 1.0e-10_wp, apart_angle = 1.0e-6_wp
        integer :: rank

        a(1, :) = [1.0_wp, 0.0_wp]
        a(2, :) = [cos(close_angle), sin(close_angle)]
        call minimum_norm_solve(a, [1.0_wp, 1.0_wp], rcond, x, rank, error)
        if (allocated(error)) return
        call check(error, rank, 1, "rows 1e-10 rad apart")
        if (allocated(error)) return
        call check(error, x, [1.0_wp, tan(0.5_wp*close_angle)], &
            & "the solution of the one constraint", abs_tol=tol_svd)
        if (allocated(error)) return
        a(2, :) = [cos(apart_angle), sin(apart_angle)]
        call minimum_norm_solve(a, [1.0_wp, 1.0_wp], rcond, x, rank, error)
        if (allocated(error)) return
        call check(error, rank, 2, "rows 1e-6 rad apart")
    end subroutine test_rank

    !> Rows (1, 0, 0), (0, 1, 0), (1, 1, 0): rank 2, and the one combination of rows that
    !> vanishes is w = (1, 1, -1)/sqrt(3) up to its sign.
    subroutine test_left_null(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a(3, 3)
        real(wp), allocatable :: null(:, :)
        integer :: rank

        a = 0.0_wp
        a(1, 1) = 1.0_wp
        a(2, 2) = 1.0_wp
        a(3, 1:2) = 1.0_wp
        call left_null_space(a, rcond, rank, null, error)
        if (allocated(error)) return
        call check(error, rank, 2, "rank")
        if (allocated(error)) return
        call check(error, size(null, 1) == 3 .and. size(null, 2) == 1, "one null vector of 3")
        if (allocated(error)) return
        call check(error, abs(null(:, 1)), [1.0_wp, 1.0_wp, 1.0_wp]/sqrt(3.0_wp), &
            & "|w| by component", abs_tol=tol_svd)
        if (allocated(error)) return
        call check(error, null(1, 1)*null(3, 1) < 0.0_wp .and. null(1, 1)*null(2, 1) > 0.0_wp, &
            & "w is along (1, 1, -1)")
        if (allocated(error)) return
        call check(error, matmul(transpose(a), null(:, 1)), [0.0_wp, 0.0_wp, 0.0_wp], &
            & "A^T w = 0", abs_tol=tol_svd)
        if (allocated(error)) return
        ! full rank (the third row now (1, 1, 1)): rank 3 and no null vector, from the singular
        ! values alone (the left vectors are computed only when the rank falls short)
        a(3, 3) = 1.0_wp
        call left_null_space(a, rcond, rank, null, error)
        if (allocated(error)) return
        call check(error, rank == 3 .and. size(null, 1) == 3 .and. size(null, 2) == 0, &
            & "full rank: rank 3, a 3 x 0 null space")
    end subroutine test_left_null

    !> No rows or no columns: rank 0, x = 0, and every combination of the rows vanishes.
    subroutine test_empty(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: no_columns(2, 0), x(0), y(2)
        real(wp), allocatable :: null(:, :)
        real(wp) :: no_rows(0, 2)
        integer :: rank

        call minimum_norm_solve(no_rows, [real(wp) ::], rcond, y, rank, error)
        if (allocated(error)) return
        call check(error, rank == 0 .and. all(y == 0.0_wp), "no rows: rank 0, x = 0")
        if (allocated(error)) return
        call minimum_norm_solve(no_columns, [1.0_wp, 2.0_wp], rcond, x, rank, error)
        if (allocated(error)) return
        call check(error, rank, 0, "no columns: rank 0")
        if (allocated(error)) return
        call left_null_space(no_columns, rcond, rank, null, error)
        if (allocated(error)) return
        call check(error, rank == 0 .and. size(null, 1) == 2 .and. size(null, 2) == 2, &
            & "no columns: a 2 x 2 null space")
        if (allocated(error)) return
        call check(error, all(null == reshape([1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [2, 2])), &
            & "the identity")
    end subroutine test_empty

    !> SuiteSparseQR's rank of unit columns in compressed columns: the columns e1, e2 and
    !> (e1 + e2)/sqrt(2) of 3 rows have rank 2, the one SPQR takes last at distance 0 from the
    !> others' span, the second at distance sqrt(1 - (u . v)^2) from the first's (unit u, v);
    !> two unit columns at an angle a have rank 1 at a = 1e-10 rad and rank 2 at 1e-6 rad
    !> (tolerance rcond), the second's distance from the first's span sin(a). Each |R(k,k)| a
    !> Householder QR's, within a few roundings of its closed form (tol_svd).
    subroutine test_sparse_rank(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: close_angle = 1.0e-10_wp, apart_angle = 1.0e-6_wp
        integer :: rank, order(3), pair(2), k
        real(wp) :: diagonal(3), distance(2), columns(3, 3)

        columns = 0.0_wp
        columns(1, 1) = 1.0_wp
        columns(2, 2) = 1.0_wp
        columns(1:2, 3) = 1.0_wp/sqrt(2.0_wp)
        call sparse_rank(3, [1, 2, 3, 5], [1, 2, 1, 2], [1.0_wp, 1.0_wp, &
            & [1.0_wp, 1.0_wp]/sqrt(2.0_wp)], rcond, rank, order, diagonal, error)
        if (allocated(error)) return
        call check(error, rank, 2, "e1, e2, (e1 + e2)/sqrt(2): rank 2")
        if (allocated(error)) return
        call check(error, all([(any(order == k), k = 1, 3)]), "order: each column once")
        if (allocated(error)) return
        call check(error, diagonal, [1.0_wp, sqrt(1.0_wp - dot_product(columns(:, order(1)), &
            & columns(:, order(2)))**2), 0.0_wp], "|R(k,k)|: 1, the second's distance from " &
            & // "the first, 0 for the column in the others' span", abs_tol=tol_svd)
        if (allocated(error)) return
        call sparse_rank(2, [1, 2, 4], [1, 1, 2], [1.0_wp, cos(close_angle), &
            & sin(close_angle)], rcond, rank, pair, distance, error)
        if (allocated(error)) return
        call check(error, rank, 1, "columns 1e-10 rad apart")
        if (allocated(error)) return
        call sparse_rank(2, [1, 2, 4], [1, 1, 2], [1.0_wp, cos(apart_angle), &
            & sin(apart_angle)], rcond, rank, pair, distance, error)
        if (allocated(error)) return
        call check(error, rank, 2, "columns 1e-6 rad apart")
        if (allocated(error)) return
        call check(error, distance, [1.0_wp, sin(apart_angle)], &
            & "|R(k,k)|: 1, then the distance sin(a)", abs_tol=tol_svd)
    end subroutine test_sparse_rank

    !> The sparse choice with the order held (sparse_grouped_rank) on a = e1, b = (e1 + t e2)/s
    !> (s = sqrt(1 + t^2), t = 1e-3) and c = e2, in that order: without swaps the greedy keeps a
    !> and b (distances 1 and t/s) and sets c aside, c = (s b - a)/t; with swaps (bound 2) c is
    !> kept instead of b, its coefficient s/t the largest (distances 1 and 1). b leading
    !> (held first): b, a kept greedily, a's coefficient -1/t, so c is kept instead of a
    !> (distances 1 and 1/s, c's from b). sparse_combination of c over (a, b): (-1/t, s/t).
    !> Each within a few roundings of its closed form, amplified by 1/t in the combination
    !> (tol_svd/t).
    subroutine test_sparse_choice(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: t = 1.0e-3_wp
        integer, parameter :: column_start(4) = [1, 2, 4, 5], row(4) = [1, 1, 2, 2]
        real(wp) :: s, values(4), diagonal(3), x(2)
        integer :: rank, order(3)

        s = sqrt(1.0_wp + t**2)
        values = [1.0_wp, 1.0_wp/s, t/s, 1.0_wp]
        call sparse_grouped_rank(2, column_start, row, values, rcond, [.false., .false., &
            & .false.], .false., 0.0_wp, rank, order, diagonal, error)
        if (allocated(error)) return
        call check(error, rank == 2 .and. all(order == [1, 2, 3]), "greedy: a, b kept, c " &
            & // "set aside: rank " // to_text(rank))
        if (allocated(error)) return
        call check(error, diagonal, [1.0_wp, t/s, 0.0_wp], "greedy: distances", abs_tol=tol_svd)
        if (allocated(error)) return
        call sparse_grouped_rank(2, column_start, row, values, rcond, [.false., .false., &
            & .false.], .false., 2.0_wp, rank, order, diagonal, error)
        if (allocated(error)) return
        call check(error, rank == 2 .and. all(order == [1, 3, 2]), "swapped: a, c kept, b " &
            & // "set aside")
        if (allocated(error)) return
        call check(error, diagonal, [1.0_wp, 1.0_wp, 0.0_wp], "swapped: distances", &
            & abs_tol=tol_svd)
        if (allocated(error)) return
        call sparse_grouped_rank(2, column_start, row, values, rcond, [.false., .true., &
            & .false.], .false., 2.0_wp, rank, order, diagonal, error)
        if (allocated(error)) return
        call check(error, rank == 2 .and. all(order == [2, 3, 1]), "b leading: b, c kept, a " &
            & // "set aside")
        if (allocated(error)) return
        call check(error, diagonal, [1.0_wp, 1.0_wp/s, 0.0_wp], "b leading: distances", &
            & abs_tol=tol_svd)
        if (allocated(error)) return
        call sparse_combination(2, column_start, row, values, rcond, x, rank, error)
        if (allocated(error)) return
        call check(error, rank, 2, "combination: a and b kept")
        if (allocated(error)) return
        call check(error, x, [-1.0_wp/t, s/t], "c over a and b", abs_tol=tol_svd/t)
    end subroutine test_sparse_choice

    !> SuiteSparseQR's least-norm solution from rows: x1 + x2 = 1, x2 + x3 = 2 gives (0, 1, 1)
    !> as the SVD's (test_underdetermined); with the row x1 + 2 x2 + x3 = 3 added, their sum
    !> (dependent and consistent), still (0, 1, 1); with it = 4 instead (contradictory), the
    !> misfit spread over the three rows: A_L x = v = (4/3, 7/3) minimises (v1 - 1)^2 + (v2 -
    !> 2)^2 + (v1 + v2 - 4)^2, and x = (1/9, 11/9, 10/9) is the least-norm solution of it, the
    !> SVD's (dgelss) answer. A Householder QR of order-one rows: within a few tens of
    !> roundings (tol_svd).
    subroutine test_sparse_least_norm(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: x(3)

        call sparse_minimum_norm(3, [1, 3, 5], [1, 2, 2, 3], [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], &
            & [1.0_wp, 2.0_wp], rcond, x, error)
        if (allocated(error)) return
        call check(error, x, [0.0_wp, 1.0_wp, 1.0_wp], "least norm of two rows", &
            & abs_tol=tol_svd)
        if (allocated(error)) return
        call sparse_minimum_norm(3, [1, 3, 5, 8], [1, 2, 2, 3, 1, 2, 3], [1.0_wp, 1.0_wp, &
            & 1.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, 1.0_wp], [1.0_wp, 2.0_wp, 3.0_wp], rcond, x, error)
        if (allocated(error)) return
        call check(error, x, [0.0_wp, 1.0_wp, 1.0_wp], "least norm with a dependent row", &
            & abs_tol=tol_svd)
        if (allocated(error)) return
        call sparse_minimum_norm(3, [1, 3, 5, 8], [1, 2, 2, 3, 1, 2, 3], [1.0_wp, 1.0_wp, &
            & 1.0_wp, 1.0_wp, 1.0_wp, 2.0_wp, 1.0_wp], [1.0_wp, 2.0_wp, 4.0_wp], rcond, x, error)
        if (allocated(error)) return
        call check(error, x, [1.0_wp, 11.0_wp, 10.0_wp]/9.0_wp, "least squares of least norm " &
            & // "with a contradictory dependent row", abs_tol=tol_svd)
    end subroutine test_sparse_least_norm

    !> The rows of SuiteSparseQR's dependency: unit rows e1, e2, (e1 + e2)/sqrt(2) and e3 have
    !> rank 3, the first three in the dependency and e3 not; two rows 1e-10 rad apart (below
    !> rcond) count as one, both in it, and 1e-6 rad apart as two, none in any. Exact flags.
    subroutine test_sparse_dependent(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: close_angle = 1.0e-10_wp, apart_angle = 1.0e-6_wp
        logical :: involved(4), pair(2)
        integer :: rank

        call sparse_dependent_rows(3, [1, 2, 3, 5, 6], [1, 2, 1, 2, 3], [1.0_wp, 1.0_wp, &
            & [1.0_wp, 1.0_wp]/sqrt(2.0_wp), 1.0_wp], rcond, 1.0e-6_wp, rank, involved, error)
        if (allocated(error)) return
        call check(error, rank, 3, "e1, e2, (e1 + e2)/sqrt(2), e3: rank 3")
        if (allocated(error)) return
        call check(error, all(involved .eqv. [.true., .true., .true., .false.]), &
            & "the first three rows in the dependency, e3 not")
        if (allocated(error)) return
        call sparse_dependent_rows(2, [1, 2, 4], [1, 1, 2], [1.0_wp, cos(close_angle), &
            & sin(close_angle)], rcond, 1.0e-6_wp, rank, pair, error)
        if (allocated(error)) return
        call check(error, rank == 1 .and. all(pair), "rows 1e-10 rad apart: one, both in it")
        if (allocated(error)) return
        call sparse_dependent_rows(2, [1, 2, 4], [1, 1, 2], [1.0_wp, cos(apart_angle), &
            & sin(apart_angle)], rcond, 1.0e-6_wp, rank, pair, error)
        if (allocated(error)) return
        call check(error, rank == 2 .and. .not. any(pair), "rows 1e-6 rad apart: two, free")
    end subroutine test_sparse_dependent

end module test_least_squares
