! SPDX-License-Identifier: MIT
!> The compressed-column pattern of a sparse Newton matrix (rollcon_newton_pattern) gathered
!> from a list of entries, without an n x n array, against the same relation held n x n.
module test_newton_pattern
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_newton_pattern, only : newton_pattern_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_newton_pattern

contains

    subroutine collect_newton_pattern(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("entries-as-relation", test_entries_as_relation)]
    end subroutine collect_newton_pattern

    !> A list of 400 entries of a 37-square matrix drawn with repeats (a quarter of them the
    !> same entries again, in another order; columns left empty, diagonal entries among them)
    !> gives the pattern from_relation makes of the same entries as an n x n relation: the same
    !> column starts and the same rows, ascending and each once, with the diagonal added.
    subroutine test_entries_as_relation(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 37, drawn = 300, repeats = 100
        type(newton_pattern_type) :: listed, related
        integer :: rows(drawn + repeats), columns(drawn + repeats), e
        logical :: keep(n, n)
        real(wp) :: x(2)

        keep = .false.
        call random_seed(put=[(7*e + 3, e = 1, 64)])
        do e = 1, drawn
            call random_number(x)
            rows(e) = 1 + int(n*x(1))
            ! columns 1 to 30 only: the last seven hold their diagonal alone
            columns(e) = 1 + int(30*x(2))
            keep(rows(e), columns(e)) = .true.
        end do
        do e = 1, repeats
            rows(drawn + e) = rows(drawn + 1 - 2*e)
            columns(drawn + e) = columns(drawn + 1 - 2*e)
        end do
        call listed%from_entries(n, rows, columns, size(rows))
        call related%from_relation(keep)
        call check(error, listed%n, related%n, "order")
        if (allocated(error)) return
        call check(error, listed%entries(), related%entries(), "entries (of " &
            & // to_text(count(keep)) // " drawn off the diagonal or on it)")
        if (allocated(error)) return
        call check(error, all(listed%starts == related%starts), "column starts")
        if (allocated(error)) return
        call check(error, all(listed%rows == related%rows), "rows")
    end subroutine test_entries_as_relation

end module test_newton_pattern
