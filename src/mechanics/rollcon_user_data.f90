! SPDX-License-Identifier: MIT
!> The data a user's routine reads with ADAMS's GTSTRG and GTARAY: the model's STRING and
!> ARRAY statements (docs/datasets.md, "STRING and ARRAY"), held once for the process as
!> ADAMS holds them for its routines (set where the model is built; the shim's GTSTRG and
!> GTARAY land in string_data and array_data).
!>
!>     CALL GTSTRG(ID, STRING, NCHARS, ISTAT)
!>     CALL GTARAY(ID, ARRAY, NUMBER, ISTAT)
module rollcon_user_data
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: user_string_type, user_array_type, set_user_data, string_data, array_data
    public :: data_found, data_missing, data_truncated

    !> ISTAT of GTSTRG and GTARAY: found; no statement of that id (GTARAY's -2 in ADAMS's
    !> reference); the STRING argument shorter than the text (GTSTRG: the text cut to it)
    integer, parameter :: data_found = 0, data_missing = -2, data_truncated = -3

    !> STRING/id, STRING=text
    type :: user_string_type
        integer :: id = 0
        character(len=:), allocatable :: text
    end type user_string_type

    !> ARRAY/id, NUMBERS=r1, ...
    type :: user_array_type
        integer :: id = 0
        real(wp), allocatable :: numbers(:)
    end type user_array_type

    type(user_string_type), allocatable, save :: strings(:)
    type(user_array_type), allocatable, save :: arrays(:)

contains

    !> The model's STRINGs and ARRAYs, replacing those of a model built before.
    subroutine set_user_data(model_strings, model_arrays)
        type(user_string_type), intent(in) :: model_strings(:)
        type(user_array_type), intent(in) :: model_arrays(:)

        strings = model_strings
        arrays = model_arrays
    end subroutine set_user_data

    !> GTSTRG(ID, STRING, NCHARS, ISTAT): STRING/id's text into string (blank-padded, or cut
    !> to its length with istat = data_truncated), nchars its length in characters; istat =
    !> data_missing, string blank and nchars 0, when the model has no STRING/id.
    subroutine string_data(id, string, nchars, istat)
        integer, intent(in) :: id
        character(len=*), intent(out) :: string
        integer, intent(out) :: nchars, istat
        integer :: k

        string = ""
        nchars = 0
        istat = data_missing
        if (.not. allocated(strings)) return
        do k = 1, size(strings)
            if (strings(k)%id /= id) cycle
            string = strings(k)%text
            nchars = len(strings(k)%text)
            istat = merge(data_truncated, data_found, nchars > len(string))
            return
        end do
    end subroutine string_data

    !> GTARAY(ID, ARRAY, NUMBER, ISTAT): the NUMBERS of ARRAY/id into values(1:number) (the
    !> caller's storage must hold them, as ADAMS's reference requires); istat = data_missing
    !> and number 0 when the model has no ARRAY/id.
    subroutine array_data(id, values, number, istat)
        integer, intent(in) :: id
        real(wp), intent(inout) :: values(*)
        integer, intent(out) :: number, istat
        integer :: k

        number = 0
        istat = data_missing
        if (.not. allocated(arrays)) return
        do k = 1, size(arrays)
            if (arrays(k)%id /= id) cycle
            number = size(arrays(k)%numbers)
            values(:number) = arrays(k)%numbers
            istat = data_found
            return
        end do
    end subroutine array_data

end module rollcon_user_data
