! SPDX-License-Identifier: MIT
!> Lists of a job's value overrides (load_job's `overrides`), grown one at a time: gfortran 12
!> cuts the values of an array constructor of input_override_type to the first one's length.
module override_lists
    use rollcon_load, only : input_override_type
    implicit none
    private

    public :: add_override

contains

    !> Append the override name = value.
    subroutine add_override(set, name, value)
        type(input_override_type), allocatable, intent(inout) :: set(:)
        character(len=*), intent(in) :: name, value
        type(input_override_type), allocatable :: grown(:)
        integer :: k

        if (.not. allocated(set)) allocate(set(0))
        allocate(grown(size(set) + 1))
        do k = 1, size(set)
            grown(k)%name = set(k)%name
            grown(k)%value = set(k)%value
        end do
        grown(size(grown))%name = name
        grown(size(grown))%value = value
        call move_alloc(grown, set)
    end subroutine add_override

end module override_lists
