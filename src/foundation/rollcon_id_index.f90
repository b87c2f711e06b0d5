! SPDX-License-Identifier: MIT
!> Where each id stands, found in constant time: an open-addressing hash table from an id (a
!> 64-bit key, so that a kind and an id fit in one) to a position. A dataset's statements
!> (its reader and checks), a model's UCONs and parts (rollcon_model's setup_model) and the
!> UCOVAR declarations (rollcon_ucovar_registry) are found by it, so that duplicate ids and
!> references are checked in time linear in their number, not quadratic (a dataset of 20 000
!> markers reads in a fraction of a second; a chain of 640 links sets up in linear time).
module rollcon_id_index
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: id_index_type, new_id_index

    !> Smallest table
    integer, parameter :: least_capacity = 16
    !> Modulus and multiplier of the scrambling (Park and Miller's minimal standard generator):
    !> ids in a regular pattern (every 1000th) still spread over the table
    integer(int64), parameter :: modulus = 2147483647_int64, multiplier = 48271_int64

    !> Positions by id
    type :: id_index_type
        !> Key of each slot, and its position (0: the slot is free)
        integer(int64), allocatable :: keys(:)
        integer, allocatable :: positions(:)
        !> Keys held
        integer :: count = 0
    contains
        procedure :: find => find_id
        procedure :: add => add_id
    end type id_index_type

contains

    !> An empty index for about `expected` keys.
    pure function new_id_index(expected) result(index)
        !> Keys the index will likely hold (it grows beyond)
        integer, intent(in) :: expected
        type(id_index_type) :: index
        integer :: capacity

        capacity = least_capacity
        do while (capacity < 2*expected)
            capacity = 2*capacity
        end do
        allocate(index%keys(0:capacity - 1), index%positions(0:capacity - 1))
        index%keys = 0
        index%positions = 0
        index%count = 0
    end function new_id_index

    !> The position stored for `key`; 0 when it has none.
    pure integer function find_id(self, key) result(position)
        class(id_index_type), intent(in) :: self
        integer(int64), intent(in) :: key
        integer :: slot

        position = 0
        if (.not. allocated(self%keys)) return
        slot = first_slot(key, size(self%keys))
        do while (self%positions(slot) /= 0)
            if (self%keys(slot) == key) then
                position = self%positions(slot)
                return
            end if
            slot = iand(slot + 1, size(self%keys) - 1)
        end do
    end function find_id

    !> Store `position` (> 0) for `key` unless the key is held already; `previous` is then the
    !> position it has (0 when the key was new and is now stored).
    pure subroutine add_id(self, key, position, previous)
        class(id_index_type), intent(inout) :: self
        integer(int64), intent(in) :: key
        integer, intent(in) :: position
        integer, intent(out) :: previous
        integer :: slot

        if (.not. allocated(self%keys)) then
            allocate(self%keys(0:least_capacity - 1), self%positions(0:least_capacity - 1))
            self%keys = 0
            self%positions = 0
            self%count = 0
        end if
        if (2*(self%count + 1) > size(self%keys)) call grow(self%keys, self%positions)
        previous = 0
        slot = first_slot(key, size(self%keys))
        do while (self%positions(slot) /= 0)
            if (self%keys(slot) == key) then
                previous = self%positions(slot)
                return
            end if
            slot = iand(slot + 1, size(self%keys) - 1)
        end do
        self%keys(slot) = key
        self%positions(slot) = position
        self%count = self%count + 1
    end subroutine add_id

    !> Twice the slots, every key stored again.
    pure subroutine grow(keys, positions)
        integer(int64), allocatable, intent(inout) :: keys(:)
        integer, allocatable, intent(inout) :: positions(:)
        integer(int64), allocatable :: old_keys(:)
        integer, allocatable :: old_positions(:)
        integer :: old, slot

        call move_alloc(keys, old_keys)
        call move_alloc(positions, old_positions)
        allocate(keys(0:2*size(old_keys) - 1), positions(0:2*size(old_keys) - 1))
        keys = 0
        positions = 0
        do old = 0, size(old_keys) - 1
            if (old_positions(old) == 0) cycle
            slot = first_slot(old_keys(old), size(keys))
            do while (positions(slot) /= 0)
                slot = iand(slot + 1, size(keys) - 1)
            end do
            keys(slot) = old_keys(old)
            positions(slot) = old_positions(old)
        end do
    end subroutine grow

    !> The slot where the search for `key` starts, in a table of `capacity` (a power of two).
    pure integer function first_slot(key, capacity) result(slot)
        integer(int64), intent(in) :: key
        integer, intent(in) :: capacity

        slot = int(iand(modulo(modulo(key, modulus)*multiplier, modulus), &
            & int(capacity - 1, int64)))
    end function first_slot

end module rollcon_id_index
