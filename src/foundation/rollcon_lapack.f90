! SPDX-License-Identifier: MIT
!> Interface blocks for the LAPACK routines rollcon calls, wrappers that size them, and the
!> choice of one BLAS thread.
!>
!> Which library: fpm.toml links `lapack` and `blas`, which the system resolves (Debian: the
!> update-alternatives of libblas.so.3 and liblapack.so.3) to reference LAPACK/BLAS or to an
!> optimised one such as OpenBLAS. The systems solved here have a dozen unknowns: threads gain
!> nothing on them, and an idle OpenBLAS worker that spins costs CPU time and makes timings
!> noisy. So programs call use_one_blas_thread first; with reference BLAS (single-threaded by
!> construction) it finds nothing to do.
module rollcon_lapack
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_funptr, c_int, c_char, &
        & c_null_char, c_associated, c_f_procpointer
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    implicit none
    private

    public :: factor_dense, solve_factored, lapack_info_error, symmetric_eigen
    public :: general_eigenvalues, pivoted_columns
    public :: dgetf2, dgetrs, dpotf2, dpotrs, dgeqp3
    public :: use_one_blas_thread

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

        !> Cholesky factorisation of a symmetric positive definite matrix, unblocked (LAPACK):
        !> for the 3 x 3 blocks here dpotrf's recursion costs more than the arithmetic
        pure subroutine dpotf2(uplo, n, a, lda, info)
            import :: wp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotf2

        !> Solve with a Cholesky factorisation from dpotf2 (LAPACK)
        pure subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
            import :: wp
            character(len=1), intent(in) :: uplo
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dpotrs

        !> Eigenvalues (and optionally eigenvectors) of a general real matrix, balanced (LAPACK)
        pure subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, &
                & info)
            import :: wp
            character(len=1), intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
            integer, intent(out) :: info
        end subroutine dgeev

        !> QR factorisation with column pivoting, A P = Q R (LAPACK)
        pure subroutine dgeqp3(m, n, a, lda, jpvt, tau, work, lwork, info)
            import :: wp
            integer, intent(in) :: m, n, lda, lwork
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(inout) :: jpvt(*)
            real(wp), intent(out) :: tau(*), work(*)
            integer, intent(out) :: info
        end subroutine dgeqp3

        !> Eigenvalues (ascending) and, with jobz = 'V', orthonormal eigenvectors of a
        !> symmetric matrix (LAPACK)
        pure subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
            import :: wp
            character(len=1), intent(in) :: jobz, uplo
            integer, intent(in) :: n, lda, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: w(*)
            real(wp), intent(inout) :: work(*)
            integer, intent(out) :: info
        end subroutine dsyev
    end interface

    interface
        !> The address of a symbol of the loaded libraries (POSIX; handle c_null_ptr is glibc's
        !> RTLD_DEFAULT: search them all)
        function dlsym(handle, symbol) result(address) bind(c, name="dlsym")
            import :: c_ptr, c_funptr, c_char
            type(c_ptr), value :: handle
            character(kind=c_char), intent(in) :: symbol(*)
            type(c_funptr) :: address
        end function dlsym
    end interface

    abstract interface
        !> openblas_set_num_threads(int) and mkl_set_num_threads(int)
        subroutine set_threads_interface(count) bind(c)
            import :: c_int
            integer(c_int), value :: count
        end subroutine set_threads_interface
    end interface

contains

    !> Run the BLAS on one thread when the linked library has threads (OpenBLAS, MKL); tell
    !> which setter was called ("" with reference BLAS, which has no threads).
    subroutine use_one_blas_thread(library)
        !> "openblas", "mkl" or "" (none found: a single-threaded BLAS)
        character(len=:), allocatable, intent(out) :: library
        character(len=*), parameter :: setters(2) = [character(len=24) :: &
            & "openblas_set_num_threads", "MKL_Set_Num_Threads"]
        character(len=*), parameter :: names(2) = [character(len=8) :: "openblas", "mkl"]
        procedure(set_threads_interface), pointer :: set_threads
        type(c_funptr) :: address
        integer :: i

        library = ""
        do i = 1, size(setters)
            address = dlsym(c_null_ptr, trim(setters(i)) // c_null_char)
            if (.not. c_associated(address)) cycle
            call c_f_procpointer(address, set_threads)
            call set_threads(1_c_int)
            library = trim(names(i))
            return
        end do
    end subroutine use_one_blas_thread

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

    !> The eigenvalues of a general square matrix (dgeev, with its balancing; no
    !> eigenvectors), in LAPACK's order: a complex conjugate pair is adjacent, positive
    !> imaginary part first.
    subroutine general_eigenvalues(a, re, im, error)
        !> n x n matrix (not changed)
        real(wp), intent(in) :: a(:, :)
        !> Real and imaginary parts, n each
        real(wp), intent(out) :: re(:), im(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: copy(:, :), work(:)
        real(wp) :: query(1), none(1, 1)
        integer :: n, info

        n = size(a, 1)
        if (size(a, 2) /= n .or. size(re) /= n .or. size(im) /= n) then
            call fatal_error(error, "general_eigenvalues: matrix is " // to_text(n) // " x " &
                & // to_text(size(a, 2)) // " with " // to_text(size(re)) // " and " &
                & // to_text(size(im)) // " places for the eigenvalues", stat_lapack)
            return
        end if
        if (n == 0) return
        copy = a
        call dgeev("N", "N", n, copy, n, re, im, none, 1, none, 1, query, -1, info)
        call lapack_info_error("dgeev", info, error)
        if (allocated(error)) return
        allocate(work(max(1, int(query(1)))))
        call dgeev("N", "N", n, copy, n, re, im, none, 1, none, 1, work, size(work), info)
        if (info > 0) then
            call fatal_error(error, "dgeev: the QR algorithm failed to find eigenvalue " &
                & // to_text(info) // " of " // to_text(n), stat_lapack)
            return
        end if
        call lapack_info_error("dgeev", info, error)
    end subroutine general_eigenvalues

    !> The columns of an m x n matrix in the order QR with column pivoting takes them (dgeqp3:
    !> at each step the column with the largest norm left), and the magnitudes |R(k,k)| of
    !> the triangular factor's diagonal: the first rank columns of `order` are the most
    !> independent ones, and |R(k,k)| falling towards zero measures how far the first k are from
    !> dependent.
    subroutine pivoted_columns(a, order, diagonal, error, leading)
        !> m x n matrix (not changed)
        real(wp), intent(in) :: a(:, :)
        !> The n column numbers in pivot order
        integer, intent(out) :: order(:)
        !> |R(k,k)|, min(m, n) of them
        real(wp), intent(out) :: diagonal(:)
        type(error_type), allocatable, intent(out) :: error
        !> Columns put first, in their own order and not pivoted (dgeqp3's fixed columns):
        !> the caller makes sure they are independent
        logical, intent(in), optional :: leading(:)
        real(wp), allocatable :: copy(:, :), work(:), tau(:)
        real(wp) :: query(1)
        integer :: m, n, k, info

        m = size(a, 1)
        n = size(a, 2)
        order = 0
        if (m == 0 .or. n == 0) then
            order = [(k, k = 1, n)]
            return
        end if
        if (present(leading)) order = merge(1, 0, leading)
        copy = a
        allocate(tau(min(m, n)))
        call dgeqp3(m, n, copy, m, order, tau, query, -1, info)
        call lapack_info_error("dgeqp3", info, error)
        if (allocated(error)) return
        allocate(work(max(1, int(query(1)))))
        call dgeqp3(m, n, copy, m, order, tau, work, size(work), info)
        call lapack_info_error("dgeqp3", info, error)
        if (allocated(error)) return
        do k = 1, min(m, n)
            diagonal(k) = abs(copy(k, k))
        end do
    end subroutine pivoted_columns
    !> Eigenvalues and eigenvectors of a small symmetric matrix (LAPACK dsyev): the values in
    !> ascending order, the vectors orthonormal, column k belonging to value k.
    subroutine symmetric_eigen(a, values, vectors, error)
        !> The symmetric matrix (its upper triangle is read)
        real(wp), intent(in) :: a(:, :)
        !> Eigenvalues, ascending, size(a, 1) of them
        real(wp), intent(out) :: values(:)
        !> Eigenvectors as columns, the shape of a
        real(wp), intent(out) :: vectors(:, :)
        !> Set when an argument is invalid or the iteration did not converge
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: work(max(1, 3*size(a, 1) - 1))
        integer :: info, n

        n = size(a, 1)
        if (size(a, 2) /= n .or. size(values) /= n .or. any(shape(vectors) /= [n, n])) then
            call fatal_error(error, "symmetric_eigen: matrix is " // to_text(n) // " x " &
                & // to_text(size(a, 2)) // " with " // to_text(size(values)) // " values", &
                & stat_lapack)
            return
        end if
        vectors = a
        ! the unblocked workspace 3 n - 1 suffices: the matrices here are 3 x 3
        call dsyev("V", "U", n, vectors, n, values, work, size(work), info)
        if (info < 0) then
            call fatal_error(error, "dsyev: argument " // to_text(-info) // " is invalid", &
                & stat_lapack)
        else if (info > 0) then
            call fatal_error(error, "dsyev: " // to_text(info) // " off-diagonal elements did " &
                & // "not converge to zero", stat_lapack)
        end if
    end subroutine symmetric_eigen

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
