! SPDX-License-Identifier: MIT
!> Interface blocks for the LAPACK routines rollcon calls, and wrappers that size them.
module rollcon_lapack
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    implicit none
    private

    public :: solve_dense, factor_dense, solve_factored, lapack_info_error

    !> Largest order factored with the unblocked routine
    integer, parameter :: small_matrix = 64

    interface
        !> LU factorisation with partial pivoting, blocked and recursive (LAPACK)
        pure subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*)
            integer, intent(out) :: info
        end subroutine dgetrf

        !> LU factorisation with partial pivoting, unblocked (LAPACK): faster for small n
        pure subroutine dgetf2(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*)
            integer, intent(out) :: info
        end subroutine dgetf2

        !> Solve with an LU factorisation from dgetrf (LAPACK)
        pure subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs
    end interface

contains

    !> Factor a square matrix in place (LU, partial pivoting).
    subroutine factor_dense(a, ipiv, error)
        !> Matrix on entry, its LU factors on exit
        real(wp), intent(inout) :: a(:, :)
        !> Pivot indices, size(a, 1) of them
        integer, intent(out) :: ipiv(:)
        !> Set when the matrix is singular or an argument is invalid
        type(error_type), allocatable, intent(out) :: error
        integer :: info

        if (size(a, 1) /= size(a, 2) .or. size(ipiv) < size(a, 1)) then
            call fatal_error(error, "factor_dense: matrix is " // to_text(size(a, 1)) // " x " &
                & // to_text(size(a, 2)) // " with " // to_text(size(ipiv)) // " pivots", &
                & stat_lapack)
            return
        end if
        ! The saddle-point systems here are a dozen or two unknowns: LAPACK's unblocked
        ! factorisation avoids the recursion and blocking overhead that dominates at that size.
        if (size(a, 1) <= small_matrix) then
            call dgetf2(size(a, 1), size(a, 2), a, size(a, 1), ipiv, info)
            call lapack_info_error("dgetf2", info, error)
        else
            call dgetrf(size(a, 1), size(a, 2), a, size(a, 1), ipiv, info)
            call lapack_info_error("dgetrf", info, error)
        end if
    end subroutine factor_dense

    !> Solve A x = b with the factors from factor_dense; b is overwritten by x.
    subroutine solve_factored(lu, ipiv, b, error)
        !> LU factors from factor_dense
        real(wp), intent(in) :: lu(:, :)
        !> Pivots from factor_dense
        integer, intent(in) :: ipiv(:)
        !> Right-hand sides on entry, solutions on exit
        real(wp), intent(inout) :: b(:, :)
        !> Set when an argument is invalid
        type(error_type), allocatable, intent(out) :: error
        integer :: info

        call dgetrs("N", size(lu, 1), size(b, 2), lu, size(lu, 1), ipiv, b, size(b, 1), info)
        call lapack_info_error("dgetrs", info, error)
    end subroutine solve_factored

    !> Solve A x = b for one right-hand side; a is overwritten by its factors, b by x.
    subroutine solve_dense(a, b, error)
        !> Square matrix on entry, its LU factors on exit
        real(wp), intent(inout) :: a(:, :)
        !> Right-hand side on entry, solution on exit
        real(wp), intent(inout) :: b(:)
        !> Set when the matrix is singular
        type(error_type), allocatable, intent(out) :: error
        integer :: ipiv(size(a, 1))
        real(wp) :: rhs(size(b), 1)

        call factor_dense(a, ipiv, error)
        if (allocated(error)) return
        rhs(:, 1) = b
        call solve_factored(a, ipiv, rhs, error)
        if (allocated(error)) return
        b = rhs(:, 1)
    end subroutine solve_dense

    !> Turn a LAPACK info code into an error (nothing when info is 0).
    pure subroutine lapack_info_error(routine, info, error)
        !> Name of the LAPACK routine
        character(len=*), intent(in) :: routine
        !> Its info output
        integer, intent(in) :: info
        !> Allocated when info /= 0
        type(error_type), allocatable, intent(out) :: error

        if (info < 0) then
            call fatal_error(error, routine // ": argument " // to_text(-info) // " is invalid", &
                & stat_lapack)
        else if (info > 0) then
            call fatal_error(error, routine // ": matrix is singular at pivot " // to_text(info), &
                & stat_lapack)
        end if
    end subroutine lapack_info_error

end module rollcon_lapack
