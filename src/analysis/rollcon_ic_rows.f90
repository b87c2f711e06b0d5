! SPDX-License-Identifier: MIT
!> The rows of one level of the initial-conditions analysis (positions or velocities): their
!> tolerances, the least weighted change that meets them, and the verdict on what is left
!> (docs/initial-conditions.md).
module rollcon_ic_rows
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_least_squares, only : minimum_norm_solve, left_null_space
    use rollcon_sparse_qr, only : sparse_minimum_norm, sparse_dependent_rows
    use rollcon_model, only : model_type
    implicit none
    private

    public :: level_type, tolerance, least_change, verdict, name_rows, dense_rows
    public :: ic_fraction, ic_rcond, sparse_ic_columns

    !> A UCON is met when |F_k| <= ic_fraction (atol + rtol s_k), s_k the size of the terms of
    !> F_k (sum over its variables of |dF_k/dx_j x_j|, plus the rest of F): a hundredth of the
    !> error the integrator allows a state in one step, so the start is as good as exact to it
    real(wp), parameter :: ic_fraction = 1.0e-2_wp
    !> Rank threshold on unit rows: sqrt(machine epsilon). Two constraint normals closer than
    !> 1.5e-8 rad count as one (a Newton step across them would be amplified 1e8 times)
    real(wp), parameter :: ic_rcond = 1.4901161193847656e-8_wp
    !> A UCON takes part in a dependency when its entry in a left null vector of the rows
    !> exceeds this (the entries of uninvolved rows are rounding, ~1e-16)
    real(wp), parameter :: involvement = 1.0e-6_wp
    !> A level with at least this many free columns (100 parts' coordinates) is solved and
    !> judged sparse, by SuiteSparseQR on its compressed rows (rollcon_sparse_qr), below it by
    !> LAPACK's SVD on the rows made whole. The SVD holds the m x n free rows and costs
    !> O(m n^2) a step: on a chain (5 rows a link, 6 columns a part) 600 columns are 500 rows,
    !> 2.4 MB and ~2e8 flops a step, and it grows as the square and the cube of the model
    !> (640 links: 160 MB, 3e11 flops), against the QR's nonzeros, linear in the model on a
    !> chain (a row touches two links). Every shipped dataset, scene and test model but the
    !> sparse path's own tests has fewer (data/bicycle.adm: 8 parts, 48 columns), and keeps the
    !> SVD's numbers bit for bit
    integer, parameter :: sparse_ic_columns = 600
    !> One level's rows (position or velocity): what is solved and what it is called
    type :: level_type
        character(len=:), allocatable :: name
        !> UCON number (model order) and UCON statement id of each row
        integer, allocatable :: ucon(:), ids(:)
        !> The model whose UCONs the rows are, for their names in the user's words (name_rows;
        !> without it a row is named "UCON/<id>")
        type(model_type), pointer :: model => null()
        !> Residuals, tolerances
        real(wp), allocatable :: residual(:), tolerance(:)
        !> The rows over the system's coordinates (or rates), compressed: row i's entries at
        !> start(i) .. start(i + 1) - 1 of column and value, over its UCON's own coordinates in
        !> ascending order (zeros among them kept), of `columns` in all. Memory and time grow
        !> as the number of UCONs, not as m n (docs/design.md §4, "Many parts": start-up); a
        !> level whose rows are given whole (rows allocated) has none
        integer :: columns = 0
        integer, allocatable :: start(:), column(:)
        real(wp), allocatable :: value(:)
        !> The rows whole (m x columns): given so by a caller (held_steps' reduced rows), else
        !> made from the compressed ones (dense_rows) only where a least-squares solve or a
        !> verdict needs them, when the rows are not met
        real(wp), allocatable :: rows(:, :)
        !> Free columns from which the level goes the sparse way (sparse_ic_columns unless the
        !> caller chooses: rollcon_initial_conditions' options)
        integer :: sparse_columns = sparse_ic_columns
    end type level_type

contains

    !> The rows' ids and names from the model whose UCONs they are (level%ucon set): every
    !> message then names the statement and line the user wrote (rollcon_model's rows_text).
    subroutine name_rows(level, model)
        type(level_type), intent(inout) :: level
        type(model_type), intent(in), target :: model

        level%ids = model%ucons(level%ucon)%id
        level%model => model
    end subroutine name_rows

    !> ic_fraction (atol + rtol s), s = sum |row_j x_j| + |residual - row . x| (the size of the
    !> terms that F adds up).
    pure real(wp) function tolerance(atol, rtol, row, x, residual)
        !> The run's tolerances [state units, -]
        real(wp), intent(in) :: atol, rtol
        real(wp), intent(in) :: row(:), x(:), residual

        tolerance = ic_fraction*(atol + rtol*(sum(abs(row*x)) &
            & + abs(residual - dot_product(row, x))))
    end function tolerance

    !> The rows of a level whole (m x n): level%rows when given so, else made from the
    !> compressed rows (zeros off them).
    pure function dense_rows(level) result(rows)
        type(level_type), intent(in) :: level
        real(wp), allocatable :: rows(:, :)
        integer :: i, e

        if (allocated(level%rows)) then
            rows = level%rows
            return
        end if
        allocate(rows(size(level%start) - 1, level%columns), source=0.0_wp)
        do i = 1, size(level%start) - 1
            do e = level%start(i), level%start(i + 1) - 1
                rows(i, level%column(e)) = level%value(e)
            end do
        end do
    end function dense_rows

    !> The rows restricted to the free columns, scaled by the weights and to unit length (a row
    !> with nothing free left stays zero).
    pure subroutine unit_rows(level, free, weight, a, row_scale)
        type(level_type), intent(in) :: level
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        real(wp), allocatable, intent(out) :: a(:, :)
        !> 1 / length of each scaled row (1 for a zero row)
        real(wp), allocatable, intent(out) :: row_scale(:)
        real(wp) :: length
        real(wp), allocatable :: rows(:, :)
        integer :: i, j, col

        rows = dense_rows(level)
        allocate(a(size(level%ucon), count(free)), row_scale(size(level%ucon)))
        col = 0
        do j = 1, size(free)
            if (.not. free(j)) cycle
            col = col + 1
            a(:, col) = rows(:, j)*weight(j)
        end do
        do i = 1, size(a, 1)
            length = norm2(a(i, :))
            row_scale(i) = 1.0_wp
            ! a row that only the held values carry is no row at all for the solve
            if (length <= ic_rcond*norm2(rows(i, :)*weight)) then
                a(i, :) = 0.0_wp
            else
                row_scale(i) = 1.0_wp/length
                a(i, :) = a(i, :)*row_scale(i)
            end if
        end do
    end subroutine unit_rows

    !> unit_rows kept compressed (a level's start, column and value, never given whole): row i's
    !> entries at row_start(i) .. row_start(i + 1) - 1 of column (numbered among the free
    !> columns, ascending) and values; a row that only the held values carry has none.
    pure subroutine sparse_unit_rows(level, free, weight, row_start, column, values, row_scale)
        type(level_type), intent(in) :: level
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        integer, allocatable, intent(out) :: row_start(:), column(:)
        real(wp), allocatable, intent(out) :: values(:)
        real(wp), allocatable, intent(out) :: row_scale(:)
        integer, allocatable :: free_number(:)
        real(wp) :: length, whole
        integer :: i, j, e, m, k, first

        m = size(level%start) - 1
        allocate(free_number(size(free)), row_start(m + 1), row_scale(m))
        allocate(column(level%start(m + 1) - 1), values(level%start(m + 1) - 1))
        k = 0
        do j = 1, size(free)
            if (free(j)) k = k + 1
            free_number(j) = k
        end do
        k = 0
        row_start(1) = 1
        do i = 1, m
            first = k + 1
            whole = 0.0_wp
            do e = level%start(i), level%start(i + 1) - 1
                j = level%column(e)
                whole = whole + (level%value(e)*weight(j))**2
                if (.not. free(j)) cycle
                k = k + 1
                column(k) = free_number(j)
                values(k) = level%value(e)*weight(j)
            end do
            length = norm2(values(first:k))
            row_scale(i) = 1.0_wp
            ! a row that only the held values carry is no row at all for the solve
            if (length <= ic_rcond*sqrt(whole)) then
                k = first - 1
            else
                row_scale(i) = 1.0_wp/length
                values(first:k) = values(first:k)*row_scale(i)
            end if
            row_start(i + 1) = k + 1
        end do
    end subroutine sparse_unit_rows

    !> The least weighted change dx of the free values that minimises the scaled residuals: by
    !> LAPACK's SVD (dgelss) on the rows made whole, or, with sparse_columns free columns or
    !> more, by SuiteSparseQR on them compressed (sparse_minimum_norm: the same least-norm
    !> change, the rank judged by Heath's rule with the same threshold).
    subroutine least_change(level, free, weight, dx, error)
        type(level_type), intent(in) :: level
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        real(wp), allocatable, intent(out) :: dx(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), row_scale(:), y(:), values(:)
        integer, allocatable :: row_start(:), column(:)
        integer :: rank, j, col

        if (count(free) >= level%sparse_columns) then
            call sparse_unit_rows(level, free, weight, row_start, column, values, row_scale)
            allocate(y(count(free)), dx(size(free)))
            call sparse_minimum_norm(count(free), row_start, column, values, &
                & -level%residual*row_scale, ic_rcond, y, error)
        else
            call unit_rows(level, free, weight, a, row_scale)
            allocate(y(size(a, 2)), dx(size(free)))
            call minimum_norm_solve(a, -level%residual*row_scale, ic_rcond, y, rank, error)
        end if
        if (allocated(error)) return
        dx = 0.0_wp
        col = 0
        do j = 1, size(free)
            if (.not. free(j)) cycle
            col = col + 1
            dx(j) = y(col)*weight(j)
        end do
    end subroutine least_change

    !> Refuse what the rows left. Met, the rows may be dependent (redundant): the run sets aside
    !> those that repeat others (rollcon_redundancy) and says which. Not met: contradictory when
    !> the rows over the free columns are dependent (one UCON alone: its free columns are
    !> gone), else no convergence. Rank and the rows in a dependency: by the SVD's left null
    !> space, or, with sparse_columns free columns or more, by SuiteSparseQR's QR of the
    !> compressed rows' transpose (sparse_dependent_rows: Heath's rule with the same threshold,
    !> the rows unit), the same messages.
    subroutine verdict(level, free, weight, met, steps, error)
        type(level_type), intent(in) :: level
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        logical, intent(in) :: met
        integer, intent(in) :: steps
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), row_scale(:), null(:, :), values(:)
        integer, allocatable :: row_start(:), column(:)
        logical, allocatable :: involved(:)
        integer :: rank, i, m

        m = size(level%ucon)
        ! redundant rows that are all met: consistent, the run sets the repeated ones aside
        if (met) return
        allocate(involved(m))
        if (count(free) >= level%sparse_columns) then
            call sparse_unit_rows(level, free, weight, row_start, column, values, row_scale)
            call sparse_dependent_rows(count(free), row_start, column, values, ic_rcond, &
                & involvement, rank, involved, error)
            if (allocated(error)) return
        else
            call unit_rows(level, free, weight, a, row_scale)
            call left_null_space(a, ic_rcond, rank, null, error)
            if (allocated(error)) return
            do i = 1, m
                involved(i) = any(abs(null(i, :)) > involvement)
            end do
        end if
        if (rank < m .and. count(involved) == 1) then
            call fatal_error(error, "initial conditions: " // ucon_list(level, involved) &
                & // " cannot be met at " // level%name // " level with the values marked " &
                & // "exact held (none of its variables is free): " &
                & // residual_list(level, involved), stat_input)
        else if (rank < m) then
            call fatal_error(error, "initial conditions: " // ucon_list(level, involved) &
                & // " are contradictory at " // level%name // " level: their rows are " &
                & // "linearly dependent (rank " // to_text(rank) // " of " // to_text(m) &
                & // " over the values not marked exact) and no " // level%name &
                & // " meets them all; least-squares residuals after " // to_text(steps) &
                & // " step(s): " // residual_list(level, involved), stat_input)
        else
            call fatal_error(error, "initial conditions: the " // level%name // " UCONs are " &
                & // "not met after " // to_text(steps) // " step(s) (no convergence): " &
                & // residual_list(level, abs(level%residual) > level%tolerance), &
                & stat_input)
        end if
    end subroutine verdict

    !> "UCON/3 and UCON/4" (or "UCON/1, UCON/3 and UCON/4") for the flagged rows; with the
    !> model, its statements and lines, "JOINT/1 (line 14: translation along ground Z) and
    !> UCON/3 (line 9)" (rollcon_model's rows_text).
    function ucon_list(level, flagged) result(text)
        type(level_type), intent(in) :: level
        logical, intent(in) :: flagged(:)
        character(len=:), allocatable :: text
        logical, allocatable :: rows(:)
        integer :: i, seen, total

        if (associated(level%model)) then
            allocate(rows(size(level%model%ucons)), source=.false.)
            rows(level%ucon) = flagged
            text = level%model%rows_text(rows)
            return
        end if
        text = ""
        seen = 0
        total = count(flagged)
        do i = 1, size(flagged)
            if (.not. flagged(i)) cycle
            seen = seen + 1
            if (seen > 1 .and. seen == total) then
                text = text // " and "
            else if (seen > 1) then
                text = text // ", "
            end if
            text = text // "UCON/" // to_text(level%ids(i))
        end do
    end function ucon_list

    !> "UCON/3 |F| = 0.05 (tolerance 1.1e-11), ..." for the flagged rows (with the model: each
    !> row in its words, rollcon_model's row_words).
    function residual_list(level, flagged) result(text)
        type(level_type), intent(in) :: level
        logical, intent(in) :: flagged(:)
        character(len=:), allocatable :: text
        integer :: i

        text = ""
        do i = 1, size(flagged)
            if (.not. flagged(i)) cycle
            if (len(text) > 0) text = text // ", "
            if (associated(level%model)) then
                text = text // level%model%row_words(level%ucon(i))
            else
                text = text // "UCON/" // to_text(level%ids(i))
            end if
            text = text &
                & // " |F| = " // to_text(abs(level%residual(i))) // " (tolerance " &
                & // to_text(level%tolerance(i)) // ")"
        end do
    end function residual_list

end module rollcon_ic_rows
