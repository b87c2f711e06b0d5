! SPDX-License-Identifier: MIT
!> Sparse LU factors of one square matrix of fixed pattern, through KLU (SuiteSparse, linked by
!> fpm.toml as "klu"; the C side is rollcon_klu.c): the pattern analysed once (fill-reducing
!> order), then factored at each new set of values and solved for any number of right-hand
!> sides. For matrices too large for a dense LU whose nonzeros grow as their order (the
!> Schur complement of a chain's joints: rollcon_saddle_point).
module rollcon_sparse_lu
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_double, c_associated
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    implicit none
    private

    public :: sparse_lu_type

    !> One matrix in compressed columns (0-based, KLU's form) and its factors
    type :: sparse_lu_type
        !> Order
        integer :: n = 0
        !> Column starts (n + 1) and row numbers (nonzeros), 0-based
        integer(c_int), allocatable :: column_start(:), row(:)
        !> Values, in the order of row
        real(c_double), allocatable :: values(:)
        !> KLU's symbolic and numeric objects (rollcon_klu.c)
        type(c_ptr) :: handle = c_null_ptr
    contains
        procedure :: analyse
        procedure :: factor
        procedure :: solve
        procedure :: release
    end type sparse_lu_type

    interface
        function rollcon_klu_analyse(n, ap, ai, status) result(handle) &
                & bind(c, name="rollcon_klu_analyse")
            import :: c_ptr, c_int
            integer(c_int), value :: n
            integer(c_int), intent(in) :: ap(*), ai(*)
            integer(c_int), intent(out) :: status
            type(c_ptr) :: handle
        end function rollcon_klu_analyse

        function rollcon_klu_factor(handle, ap, ai, ax) result(status) &
                & bind(c, name="rollcon_klu_factor")
            import :: c_ptr, c_int, c_double
            type(c_ptr), value :: handle
            integer(c_int), intent(in) :: ap(*), ai(*)
            real(c_double), intent(in) :: ax(*)
            integer(c_int) :: status
        end function rollcon_klu_factor

        function rollcon_klu_solve(handle, ldb, nrhs, b) result(status) &
                & bind(c, name="rollcon_klu_solve")
            import :: c_ptr, c_int, c_double
            type(c_ptr), value :: handle
            integer(c_int), value :: ldb, nrhs
            real(c_double), intent(inout) :: b(*)
            integer(c_int) :: status
        end function rollcon_klu_solve

        subroutine rollcon_klu_free(handle) bind(c, name="rollcon_klu_free")
            import :: c_ptr
            type(c_ptr), value :: handle
        end subroutine rollcon_klu_free
    end interface

contains

    !> Take the pattern of an n x n matrix (compressed columns, 1-based: column j's rows are
    !> row(column_start(j) : column_start(j + 1) - 1)) and analyse it; values are set later.
    !> Called again, it frees the last pattern's objects and takes the new one.
    subroutine analyse(self, n, column_start, row, error)
        class(sparse_lu_type), intent(inout) :: self
        integer, intent(in) :: n, column_start(:), row(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: status

        call self%release()
        self%n = n
        self%column_start = int(column_start - 1, c_int)
        self%row = int(row - 1, c_int)
        ! a pattern analysed again (a speed partition chosen anew) replaces the last one's
        if (allocated(self%values)) deallocate(self%values)
        allocate(self%values(size(row)), source=0.0_c_double)
        self%handle = rollcon_klu_analyse(int(n, c_int), self%column_start, self%row, status)
        if (.not. c_associated(self%handle)) call fatal_error(error, &
            & "KLU could not analyse a sparse matrix of order " // to_text(n) // ": status " &
            & // to_text(int(status)), stat_lapack)
    end subroutine analyse

    !> Factor the current values (self%values, in the pattern's order).
    subroutine factor(self, error)
        class(sparse_lu_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: status

        if (.not. c_associated(self%handle)) then
            call fatal_error(error, "KLU: a sparse matrix was factored before its pattern was " &
                & // "analysed", stat_lapack)
            return
        end if
        status = rollcon_klu_factor(self%handle, self%column_start, self%row, self%values)
        if (status == 1) then
            call fatal_error(error, "KLU: the sparse matrix of order " // to_text(self%n) &
                & // " is singular", stat_lapack)
        else if (status /= 0) then
            call fatal_error(error, "KLU could not factor a sparse matrix of order " &
                & // to_text(self%n) // ": status " // to_text(int(status)), stat_lapack)
        end if
    end subroutine factor

    !> Solve with the factors for nrhs right-hand sides b(1:n, :) (leading dimension ldb).
    subroutine solve(self, b, ldb, nrhs, error)
        class(sparse_lu_type), intent(inout) :: self
        integer, intent(in) :: ldb, nrhs
        real(wp), intent(inout) :: b(ldb, *)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: status

        status = rollcon_klu_solve(self%handle, int(ldb, c_int), int(nrhs, c_int), b)
        if (status /= 0) call fatal_error(error, "KLU could not solve with a sparse matrix " &
            & // "of order " // to_text(self%n) // ": status " // to_text(int(status)), &
            & stat_lapack)
    end subroutine solve

    !> Free KLU's objects (the holder of a copy must not call it: the copy shares them).
    subroutine release(self)
        class(sparse_lu_type), intent(inout) :: self

        if (c_associated(self%handle)) call rollcon_klu_free(self%handle)
        self%handle = c_null_ptr
    end subroutine release

end module rollcon_sparse_lu
