! SPDX-License-Identifier: MIT
!> An integer array filled one value at a time: its capacity doubles when full, so n appends
!> cost O(n) in all (an array grown by [array, value] is copied whole at every append: O(n^2),
!> which a model of hundreds of UCONs feels at start-up).
module rollcon_int_buffer
    implicit none
    private

    public :: append, trimmed

contains

    !> values(count + 1) = value, count + 1, the capacity doubled first when values is full.
    pure subroutine append(values, count, value)
        integer, allocatable, intent(inout) :: values(:)
        integer, intent(inout) :: count
        integer, intent(in) :: value
        integer, allocatable :: larger(:)

        if (.not. allocated(values)) allocate(values(0))
        if (count >= size(values)) then
            allocate(larger(max(8, 2*size(values))))
            larger(:count) = values(:count)
            call move_alloc(larger, values)
        end if
        count = count + 1
        values(count) = value
    end subroutine append

    !> values cut to its first count entries.
    pure subroutine trimmed(values, count)
        integer, allocatable, intent(inout) :: values(:)
        integer, intent(in) :: count
        integer, allocatable :: exact(:)

        if (.not. allocated(values)) allocate(values(0))
        if (size(values) == count) return
        exact = values(:count)
        call move_alloc(exact, values)
    end subroutine trimmed

end module rollcon_int_buffer
