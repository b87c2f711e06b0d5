! SPDX-License-Identifier: MIT
!> The growing integer buffer (rollcon_int_buffer) that start-up's pattern building fills:
!> every appended value kept in order across the capacity doublings, trimmed to the count.
module test_int_buffer
    use rollcon_error, only : error_type
    use rollcon_int_buffer, only : append, trimmed
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_int_buffer

contains

    subroutine collect_int_buffer(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("append-keeps-order", test_append), &
            & new_unittest("trimmed-to-count", test_trimmed)]
    end subroutine collect_int_buffer

    !> 1000 squares appended one by one from an unallocated array: the count is 1000, the
    !> first 1000 entries are the squares in order, and the capacity grew by doubling (a power
    !> of two times 8, not one entry per append).
    subroutine test_append(error)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: values(:)
        integer :: count, k

        count = 0
        do k = 1, 1000
            call append(values, count, k*k)
        end do
        call check(error, count, 1000, "count")
        if (allocated(error)) return
        call check(error, all(values(:count) == [(k*k, k = 1, 1000)]), "the squares in order")
        if (allocated(error)) return
        call check(error, size(values), 1024, "capacity after doublings from 8")
    end subroutine test_append

    !> Trimmed to its count, the array holds exactly the values; an unallocated one trims to
    !> an empty array.
    subroutine test_trimmed(error)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: values(:), none(:)
        integer :: count

        count = 0
        call append(values, count, 7)
        call append(values, count, -3)
        call trimmed(values, count)
        call check(error, size(values) == 2 .and. all(values == [7, -3]), "two values kept")
        if (allocated(error)) return
        call trimmed(none, 0)
        call check(error, allocated(none) .and. size(none) == 0, "empty")
    end subroutine test_trimmed

end module test_int_buffer
