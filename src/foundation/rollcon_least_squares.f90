! SPDX-License-Identifier: MIT
!> Minimum-norm least squares and rank through LAPACK's singular value decomposition: the
!> linear algebra of the initial-conditions analysis (docs/initial-conditions.md).
!>
!> Rank: a singular value counts when it exceeds rcond times the largest one. The callers pass
!> rows scaled to unit length, so rcond is the sine of the smallest angle two constraint normals
!> may make before they count as the same constraint.
module rollcon_least_squares
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    implicit none
    private

    public :: minimum_norm_solve, left_null_space, smallest_singular_value

    interface
        !> Minimum-norm least-squares solution by the SVD (LAPACK)
        pure subroutine dgelss(m, n, nrhs, a, lda, b, ldb, s, rcond, rank, work, lwork, info)
            import :: wp
            integer, intent(in) :: m, n, nrhs, lda, ldb, lwork
            real(wp), intent(inout) :: a(lda, *), b(ldb, *)
            real(wp), intent(out) :: s(*)
            real(wp), intent(in) :: rcond
            integer, intent(out) :: rank
            real(wp), intent(inout) :: work(*)
            integer, intent(out) :: info
        end subroutine dgelss

        !> Singular value decomposition A = U S V^T (LAPACK)
        pure subroutine dgesvd(jobu, jobvt, m, n, a, lda, s, u, ldu, vt, ldvt, work, lwork, info)
            import :: wp
            character(len=1), intent(in) :: jobu, jobvt
            integer, intent(in) :: m, n, lda, ldu, ldvt, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: s(*), u(ldu, *), vt(ldvt, *)
            real(wp), intent(inout) :: work(*)
            integer, intent(out) :: info
        end subroutine dgesvd
    end interface

contains

    !> The x of least norm among those that minimise |A x - b| (dgelss), and the rank of A.
    subroutine minimum_norm_solve(a, b, rcond, x, rank, error)
        !> m x n matrix (not changed)
        real(wp), intent(in) :: a(:, :)
        !> m right-hand sides
        real(wp), intent(in) :: b(:)
        !> Relative threshold of the singular values that count
        real(wp), intent(in) :: rcond
        !> n unknowns
        real(wp), intent(out) :: x(:)
        !> Numerical rank of A
        integer, intent(out) :: rank
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: work_a(:, :), work_b(:, :), s(:), work(:)
        real(wp) :: query(1)
        integer :: m, n, ldb, info

        m = size(a, 1)
        n = size(a, 2)
        x = 0.0_wp
        rank = 0
        if (m == 0 .or. n == 0) return
        ldb = max(m, n)
        work_a = a
        allocate(work_b(ldb, 1), source=0.0_wp)
        work_b(:m, 1) = b
        allocate(s(min(m, n)))
        call dgelss(m, n, 1, work_a, m, work_b, ldb, s, rcond, rank, query, -1, info)
        call svd_info_error("dgelss", info, error)
        if (allocated(error)) return
        allocate(work(max(1, int(query(1)))))
        call dgelss(m, n, 1, work_a, m, work_b, ldb, s, rcond, rank, work, size(work), info)
        call svd_info_error("dgelss", info, error)
        if (allocated(error)) return
        x = work_b(:n, 1)
    end subroutine minimum_norm_solve

    !> The rank of A and the left singular vectors beyond it: the columns of `null` span the
    !> vectors w with A^T w = 0 (the combinations of rows that vanish). The singular values
    !> come first, alone; the m x m left vectors (the dearer part of an SVD: O(m^3) rotations
    !> applied to them) are computed only when the rank is short of m, so a full-rank check,
    !> the usual answer, costs a fraction of a whole SVD on a large model.
    subroutine left_null_space(a, rcond, rank, null, error)
        !> m x n matrix (not changed)
        real(wp), intent(in) :: a(:, :)
        !> Relative threshold of the singular values that count
        real(wp), intent(in) :: rcond
        integer, intent(out) :: rank
        !> m x (m - rank)
        real(wp), allocatable, intent(out) :: null(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: u(:, :)
        real(wp) :: no_vectors(1, 1)
        integer :: m, n

        m = size(a, 1)
        n = size(a, 2)
        rank = 0
        if (n == 0 .or. m == 0) then
            null = identity(m)
            return
        end if
        call singular_values("N", a, rcond, rank, no_vectors, error)
        if (allocated(error)) return
        if (rank == m) then
            allocate(null(m, 0))
            return
        end if
        allocate(u(m, m), source=0.0_wp)
        call singular_values("A", a, rcond, rank, u, error)
        if (allocated(error)) return
        null = u(:, rank + 1:)
    end subroutine left_null_space

    !> The smallest of the min(m, n) singular values of A (dgesvd, values only): for A with
    !> unit columns, how near they come to dependent (0 when they are).
    function smallest_singular_value(a, error) result(smallest)
        !> m x n matrix (not changed)
        real(wp), intent(in) :: a(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: smallest
        real(wp), allocatable :: work_a(:, :), s(:), work(:)
        real(wp) :: query(1), no_vectors(1, 1)
        integer :: m, n, info

        m = size(a, 1)
        n = size(a, 2)
        smallest = 0.0_wp
        if (m == 0 .or. n == 0) return
        work_a = a
        allocate(s(min(m, n)), source=0.0_wp)
        call dgesvd("N", "N", m, n, work_a, m, s, no_vectors, 1, no_vectors, 1, query, -1, info)
        call svd_info_error("dgesvd", info, error)
        if (allocated(error)) return
        allocate(work(max(1, int(query(1)))))
        call dgesvd("N", "N", m, n, work_a, m, s, no_vectors, 1, no_vectors, 1, work, &
            & size(work), info)
        call svd_info_error("dgesvd", info, error)
        if (allocated(error)) return
        smallest = minval(s)
    end function smallest_singular_value

    !> dgesvd on a copy of A: the count of singular values above rcond times the largest and,
    !> with jobu = "A", the m x m left singular vectors in u (jobu = "N": u not referenced).
    subroutine singular_values(jobu, a, rcond, rank, u, error)
        character, intent(in) :: jobu
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(in) :: rcond
        integer, intent(out) :: rank
        real(wp), intent(inout) :: u(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: work_a(:, :), s(:), work(:)
        real(wp) :: query(1), vt(1, 1)
        integer :: m, n, info

        m = size(a, 1)
        n = size(a, 2)
        rank = 0
        work_a = a
        allocate(s(min(m, n)), source=0.0_wp)
        call dgesvd(jobu, "N", m, n, work_a, m, s, u, size(u, 1), vt, 1, query, -1, info)
        call svd_info_error("dgesvd", info, error)
        if (allocated(error)) return
        allocate(work(max(1, int(query(1)))))
        call dgesvd(jobu, "N", m, n, work_a, m, s, u, size(u, 1), vt, 1, work, size(work), info)
        call svd_info_error("dgesvd", info, error)
        if (allocated(error)) return
        if (s(1) > 0.0_wp) rank = count(s > rcond*s(1))
    end subroutine singular_values

    !> Turn the info of an SVD routine into an error (nothing when info is 0).
    pure subroutine svd_info_error(routine, info, error)
        character(len=*), intent(in) :: routine
        integer, intent(in) :: info
        type(error_type), allocatable, intent(out) :: error

        if (info < 0) then
            call fatal_error(error, routine // ": argument " // to_text(-info) // " is invalid", &
                & stat_lapack)
        else if (info > 0) then
            call fatal_error(error, routine // ": the singular value decomposition did not " &
                & // "converge (" // to_text(info) // " superdiagonals left)", stat_lapack)
        end if
    end subroutine svd_info_error

    !> The m x m identity.
    pure function identity(m) result(eye)
        integer, intent(in) :: m
        real(wp) :: eye(m, m)
        integer :: i

        eye = 0.0_wp
        do i = 1, m
            eye(i, i) = 1.0_wp
        end do
    end function identity

end module rollcon_least_squares
