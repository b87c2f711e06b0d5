! SPDX-License-Identifier: MIT
!> The rows a choice set aside as redundant (rollcon_redundancy) in the user's words: each
!> statement once, the equations of it set aside and the statements they repeat, "JOINT/3
!> (line 40): its rotation about J's x and rotation about J's y repeat JOINT/1 (line 37),
!> JOINT/2 (line 38) and JOINT/4 (line 39); set aside" (docs/design.md §4). Never an id the
!> program generated: a JOINT's equations are named by rollcon_model's statement words.
module rollcon_redundancy_words
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_model, only : model_type, statement_joint, statement_jprim
    use rollcon_redundancy, only : redundancy_type
    use rollcon_constraint_blocks, only : constraint_blocks_type
    use rollcon_constraint_matrix, only : constraint_matrix_type
    implicit none
    private

    public :: set_aside_words

    !> A row takes part in a dependency when its coefficient exceeds this fraction of the
    !> largest (the others are rounding, some 1e-16 of it)
    real(wp), parameter :: involvement = 1.0e-6_wp

contains

    !> The rows set aside by redundancy, each statement once with its equations set aside and
    !> the statements of the active rows they repeat (redundancy's dependency at the state of
    !> c and mass, where the choice was made); "" when none is set aside. involved: the rows
    !> that take part in a dependency (set aside, or repeated by one set aside).
    function set_aside_words(model, redundancy, c, mass, blocks, involved, error) result(text)
        type(model_type), intent(in) :: model
        type(redundancy_type), intent(in) :: redundancy
        !> The constraint rows (C, nc x n by rows over each UCON's own coordinates) and the
        !> mass matrix (its parts' 6 x 6 blocks) of the choice
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: mass(:, :, :)
        type(constraint_blocks_type), intent(in) :: blocks
        logical, intent(out) :: involved(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        real(wp) :: coefficients(c%nc)
        logical :: flagged(c%nc), repeated(c%nc), own(c%nc)
        integer :: s, k

        text = ""
        involved = .not. redundancy%active
        if (redundancy%set_aside == 0) return
        do s = 1, size(model%statements)
            flagged = .not. redundancy%active .and. model%ucons%statement == s
            if (.not. any(flagged)) cycle
            repeated = .false.
            do k = 1, size(flagged)
                if (.not. flagged(k)) cycle
                call redundancy%dependency(k, c, mass, blocks, coefficients, error)
                if (allocated(error)) return
                repeated = repeated .or. abs(coefficients) > involvement &
                    & *max(maxval(abs(coefficients)), tiny(1.0_wp))
            end do
            involved = involved .or. repeated
            ! the statements repeated: other statements' rows (its own too when only they)
            own = model%ucons%statement == s
            if (any(repeated .and. .not. own)) repeated = repeated .and. .not. own
            if (len(text) > 0) text = text // "; "
            text = text // model%statement_name(s) // equations_words(model, flagged) &
                & // " " // statements_words(model, repeated) // "; set aside"
        end do
    end function set_aside_words

    !> ": its rotation about J's x and rotation about J's y repeat" (a JOINT's or JPRIM's
    !> flagged equations), " repeats" for a UCON statement.
    pure function equations_words(model, flagged) result(words)
        type(model_type), intent(in) :: model
        logical, intent(in) :: flagged(:)
        character(len=:), allocatable :: words
        integer :: k, seen, total

        total = count(flagged)
        k = findloc(flagged, .true., dim=1)
        if (all(model%statements(model%ucons(k)%statement)%kind /= [statement_joint, &
            & statement_jprim])) then
            words = " repeats"
            return
        end if
        words = ": its"
        seen = 0
        do k = 1, size(flagged)
            if (.not. flagged(k)) cycle
            seen = seen + 1
            if (seen > 1 .and. seen == total) then
                words = words // " and"
            else if (seen > 1) then
                words = words // ","
            end if
            words = words // " " // model%ucons(k)%equation
        end do
        words = words // trim(merge(" repeats", " repeat ", total == 1))
    end function equations_words

    !> "JOINT/1 (line 37), JOINT/2 (line 38) and UCON/4" of the flagged rows' statements, each
    !> once, in model order.
    pure function statements_words(model, flagged) result(words)
        type(model_type), intent(in) :: model
        logical, intent(in) :: flagged(:)
        character(len=:), allocatable :: words
        integer, allocatable :: order(:)
        integer :: k, n

        allocate(order(0))
        do k = 1, size(flagged)
            if (flagged(k) .and. .not. any(order == model%ucons(k)%statement)) &
                & order = [order, model%ucons(k)%statement]
        end do
        words = ""
        do n = 1, size(order)
            if (n > 1 .and. n == size(order)) then
                words = words // " and "
            else if (n > 1) then
                words = words // ", "
            end if
            words = words // model%statement_name(order(n))
        end do
    end function statements_words

end module rollcon_redundancy_words
