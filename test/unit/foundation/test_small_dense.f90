! SPDX-License-Identifier: MIT
!> The small dense solves of the saddle-point system (rollcon_small_dense) against LAPACK's
!> dgetf2, dgetrs, dpotf2 and dpotrs, whose arithmetic they repeat, and on matrices whose
!> answers are known: a pivoting permutation, a singular matrix, a Cholesky factor; and on the
!> pattern of the bicycle's Schur complement (exact zeros, columns empty below a few rows).
module test_small_dense
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_lapack, only : dgetf2, dgetrs, dpotf2, dpotrs
    use rollcon_small_dense, only : factor_lu, solve_lu, factor_cholesky3, solve_cholesky3
    use rollcon_testing, only : unittest_type, new_unittest, check
    use disk_states, only : seed_random
    implicit none
    private

    public :: collect_small_dense

    !> The same operations in the same order as the reference LAPACK: with it, the numbers are
    !> equal; with another LAPACK (blocked, vectorised with fused multiply-adds) a few
    !> roundings apart on these well-conditioned matrices (condition below 1e3 by construction)
    real(wp), parameter :: tol = 1.0e-12_wp

contains

    subroutine collect_small_dense(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("lu-equals-lapack", test_lu_lapack), &
            & new_unittest("lu-pivots-and-solves", test_lu_known), &
            & new_unittest("lu-bicycle-pattern-equals-lapack", test_lu_pattern), &
            & new_unittest("lu-singular-column", test_singular), &
            & new_unittest("cholesky3-equals-lapack", test_cholesky), &
            & new_unittest("cholesky3-factor-equals-lapack", test_cholesky_factor)]
    end subroutine collect_small_dense

    !> Random matrices of 1 to 25 rows, diagonally weighted: factors, pivots and the solution of
    !> three right-hand sides as LAPACK's, and a x = b.
    subroutine test_lu_lapack(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), lu(:, :), reference(:, :), b(:, :), x(:, :)
        integer, allocatable :: pivots(:), reference_pivots(:)
        integer :: n, info, reference_info, trial

        call seed_random(31)
        do trial = 1, 50
            n = 1 + mod(trial - 1, 25)
            allocate(a(n, n), b(n, 3), pivots(n), reference_pivots(n))
            call random_number(a)
            call random_number(b)
            a = a - 0.5_wp
            a(1, 1) = a(1, 1) + 0.1_wp*n
            lu = a
            reference = a
            call factor_lu(n, lu, n, pivots, info)
            call dgetf2(n, n, reference, n, reference_pivots, reference_info)
            call check(error, info == reference_info .and. all(pivots == reference_pivots), &
                & "n = " // to_text(n) // ": pivots or info differ from dgetf2's")
            if (allocated(error)) return
            call check(error, reshape(lu, [n*n]), reshape(reference, [n*n]), "n = " &
                & // to_text(n) // ": factors", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            x = b
            call solve_lu(n, 3, lu, n, pivots, x, n)
            call dgetrs("N", n, 3, reference, n, reference_pivots, b, n, info)
            call check(error, reshape(x, [3*n]), reshape(b, [3*n]), "n = " // to_text(n) &
                & // ": solutions", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            deallocate(a, b, pivots, reference_pivots)
        end do
    end subroutine test_lu_lapack

    !> Random matrices on the pattern of data/bicycle.adm's S (21 rows: rear wheel, frame, fork,
    !> front wheel; UCONs couple through shared parts only), whose columns have exact zeros
    !> below a few rows and whose small diagonal makes rows interchange: factors, pivots and
    !> two right-hand sides' solutions (one with exact zeros) as dgetf2's and dgetrs's, and
    !> every exact zero of LAPACK's factors one of factor_lu's (a zero multiplier changes no
    !> entry, in any LAPACK).
    subroutine test_lu_pattern(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 21
        character(len=n), parameter :: pattern(n) = [character(len=n) :: &
            & "X.....X..XX..........", ".XX....X.XX..........", ".XX.....XXX..........", &
            & "...X............X..XX", "....XX...........X.XX", "....XX............XXX", &
            & "X.....XXXXXXXXXX.....", ".X....XXXXXXXXXX.....", "..X...XXXXXXXXXX.....", &
            & "XXX...XXXXXXXXXX.....", "XXX...XXXXXXXXXX.....", "......XXXXXXXXXXXXXXX", &
            & "......XXXXXXXXXXXXXXX", "......XXXXXXXXXXXXXXX", "......XXXXXXXXXXXXXXX", &
            & "......XXXXXXXXXXXXXXX", "...X.......XXXXXXXXXX", "....X......XXXXXXXXXX", &
            & ".....X.....XXXXXXXXXX", "...XXX.....XXXXXXXXXX", "...XXX.....XXXXXXXXXX"]
        real(wp) :: a(n, n), lu(n, n), reference(n, n), b(n, 2), x(n, 2)
        integer :: pivots(n), reference_pivots(n), info, reference_info, trial, i, j
        logical :: interchanged

        call seed_random(43)
        interchanged = .false.
        do trial = 1, 20
            call random_number(a)
            a = a - 0.5_wp
            do j = 1, n
                do i = 1, n
                    if (pattern(i)(j:j) == ".") a(i, j) = 0.0_wp
                end do
                ! a diagonal of about a tenth of the rest: rows interchange, none singular
                a(j, j) = a(j, j)*0.2_wp + sign(0.05_wp, a(j, j))
            end do
            lu = a
            reference = a
            call factor_lu(n, lu, n, pivots, info)
            call dgetf2(n, n, reference, n, reference_pivots, reference_info)
            call check(error, info == 0 .and. reference_info == 0 .and. all(pivots &
                & == reference_pivots), "trial " // to_text(trial) &
                & // ": pivots or info differ from dgetf2's")
            if (allocated(error)) return
            interchanged = interchanged .or. any(pivots /= [(i, i = 1, n)])
            call check(error, reshape(lu, [n*n]), reshape(reference, [n*n]), "trial " &
                & // to_text(trial) // ": factors", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            call check(error, all(reference /= 0.0_wp .or. lu == 0.0_wp), "trial " &
                & // to_text(trial) // ": an exact zero of dgetf2's factors is not one")
            if (allocated(error)) return
            call random_number(b)
            b(2:n:3, 2) = 0.0_wp
            x = b
            call solve_lu(n, 2, lu, n, pivots, x, n)
            call dgetrs("N", n, 2, reference, n, reference_pivots, b, n, info)
            call check(error, reshape(x, [2*n]), reshape(b, [2*n]), "trial " // to_text(trial) &
                & // ": solutions", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
        end do
        call check(error, interchanged, "no trial interchanged rows")
    end subroutine test_lu_pattern

    !> A matrix whose pivots are its second, then third row: P a = L U with the known factors,
    !> and the solution of a x = (1, 2, 3).
    subroutine test_lu_known(error)
        type(error_type), allocatable, intent(out) :: error
        ! a few roundings of numbers of order one
        real(wp), parameter :: exact = 4.0_wp*epsilon(1.0_wp)
        real(wp) :: a(3, 3), b(3, 1)
        integer :: pivots(3), info

        ! rows (0 1 1), (2 0 0), (0 4 0): x = (1, 3/4, 1/4) solves a x = (1, 2, 3)
        a = reshape([0.0_wp, 2.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 4.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], &
            & [3, 3])
        call factor_lu(3, a, 3, pivots, info)
        call check(error, info == 0 .and. all(pivots == [2, 3, 3]), "pivots")
        if (allocated(error)) return
        ! U = (2 0 0; 0 4 0; 0 0 1), L = (1; 0 1; 0 1/4 1)
        call check(error, reshape(a, [9]), [2.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 4.0_wp, 0.25_wp, &
            & 0.0_wp, 0.0_wp, 1.0_wp], "factors", abs_tol=exact)
        if (allocated(error)) return
        b(:, 1) = [1.0_wp, 2.0_wp, 3.0_wp]
        call solve_lu(3, 1, a, 3, pivots, b, 3)
        call check(error, b(:, 1), [1.0_wp, 0.75_wp, 0.25_wp], "solution", abs_tol=exact)
    end subroutine test_lu_known

    !> A matrix with a zero column beyond the first: info names the column, as dgetf2's.
    subroutine test_singular(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a(3, 3)
        integer :: pivots(3), info

        a = reshape([1.0_wp, 2.0_wp, 3.0_wp, 2.0_wp, 4.0_wp, 6.0_wp, 0.0_wp, 1.0_wp, 5.0_wp], &
            & [3, 3])
        call factor_lu(3, a, 3, pivots, info)
        call check(error, info, 2, "info of a matrix whose second column is twice its first")
    end subroutine test_singular

    !> The solve with a 3 x 3 Cholesky factor (dpotf2's) of random positive definite matrices,
    !> for five right-hand sides in a taller array, as dpotrs's, and m x = b; the array's other
    !> rows untouched.
    subroutine test_cholesky(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(3, 3), l(3, 3), b(7, 5), reference(7, 5), rhs(7, 5)
        integer :: trial, info

        call seed_random(37)
        do trial = 1, 50
            call random_number(l)
            m = matmul(l, transpose(l))
            m(1, 1) = m(1, 1) + 0.1_wp
            m(2, 2) = m(2, 2) + 0.1_wp
            m(3, 3) = m(3, 3) + 0.1_wp
            l = m
            call dpotf2("L", 3, l, 3, info)
            call check(error, info, 0, "dpotf2")
            if (allocated(error)) return
            call random_number(b)
            reference = b
            rhs = b
            call solve_cholesky3(l, 5, b, 7)
            call dpotrs("L", 3, 5, l, 3, reference, 7, info)
            call check(error, reshape(b, [35]), reshape(reference, [35]), "trial " &
                & // to_text(trial), abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            call check(error, reshape(matmul(m, b(:3, :)), [15]), reshape(rhs(:3, :), [15]), &
                & "m x", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            call check(error, all(b(4:, :) == rhs(4:, :)), "rows past the third touched")
            if (allocated(error)) return
        end do
    end subroutine test_cholesky

    !> The 3 x 3 Cholesky factor (factor_cholesky3) of random positive definite matrices, some
    !> with exact zeros off the diagonal (a part on its principal axes), as dpotf2's ("L"),
    !> l l^T = m, and the upper triangle untouched; of matrices that are not positive definite
    !> (a zero, a negative and a NaN pivot in the first, second or third column), info as
    !> dpotf2's.
    subroutine test_cholesky_factor(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: m(3, 3), l(3, 3), reference(3, 3), lower(3, 3)
        integer :: trial, info, reference_info, i, j

        call seed_random(41)
        do trial = 1, 60
            call random_number(l)
            l = l - 0.5_wp
            m = matmul(l, transpose(l))
            do i = 1, 3
                m(i, i) = m(i, i) + 0.1_wp
            end do
            ! exact zeros off the diagonal in every third trial, a pattern per trial
            if (mod(trial, 3) == 0) then
                m(2, 1) = 0.0_wp
                m(1, 2) = 0.0_wp
                if (mod(trial, 2) == 0) then
                    m(3, 1) = 0.0_wp
                    m(1, 3) = 0.0_wp
                end if
            end if
            l = m
            reference = m
            call factor_cholesky3(l, info)
            call dpotf2("L", 3, reference, 3, reference_info)
            call check(error, info == 0 .and. reference_info == 0, "trial " &
                & // to_text(trial) // ": info of a positive definite matrix")
            if (allocated(error)) return
            call check(error, reshape(l, [9]), reshape(reference, [9]), "trial " &
                & // to_text(trial) // ": factor", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            lower = 0.0_wp
            do j = 1, 3
                lower(j:, j) = l(j:, j)
            end do
            call check(error, reshape(matmul(lower, transpose(lower)), [9]), reshape(m, [9]), &
                & "trial " // to_text(trial) // ": l l^T", abs_tol=tol, rel_tol=tol)
            if (allocated(error)) return
            call check(error, l(1, 2) == m(1, 2) .and. l(1, 3) == m(1, 3) .and. l(2, 3) &
                & == m(2, 3), "trial " // to_text(trial) // ": upper triangle touched")
            if (allocated(error)) return
        end do
        ! not positive definite: column 1 zero, column 2 negative after column 1's share,
        ! column 3 NaN
        do trial = 1, 3
            m = reshape([4.0_wp, 2.0_wp, 1.0_wp, 2.0_wp, 5.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, &
                & 6.0_wp], [3, 3])
            select case (trial)
            case (1)
                m(1, 1) = 0.0_wp
            case (2)
                m(2, 2) = 0.5_wp
            case (3)
                m(3, 3) = ieee_value(1.0_wp, ieee_quiet_nan)
            end select
            l = m
            reference = m
            call factor_cholesky3(l, info)
            call dpotf2("L", 3, reference, 3, reference_info)
            call check(error, info, trial, "info of a matrix not positive definite in column " &
                & // to_text(trial))
            if (allocated(error)) return
            call check(error, reference_info, trial, "dpotf2's info (column " &
                & // to_text(trial) // ")")
            if (allocated(error)) return
        end do
    end subroutine test_cholesky_factor

end module test_small_dense
