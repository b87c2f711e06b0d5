! SPDX-License-Identifier: MIT
!> Registry of UCOVAR declarations: for each UCON id, the parts and codes of its variables.
module rollcon_ucovar_registry
    use rollcon_error, only : error_type, ucon_error
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : max_ucon_vars, is_valid_code, code_name
    use rollcon_id_index, only : id_index_type
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: ucon_variables_type, ucovar_registry_type

    !> Variables one UCON statement declared
    type :: ucon_variables_type
        !> UCON statement id
        integer :: id = 0
        !> Part id of each variable
        integer, allocatable :: parts(:)
        !> UCOVAR code of each variable
        integer, allocatable :: codes(:)
    end type ucon_variables_type

    !> Every declaration made so far, one entry per UCON id
    type :: ucovar_registry_type
        !> Declarations, in the order they were made: entries(1:count()); past them, spare
        !> capacity (doubled when full, so that n declarations cost O(n), not O(n^2))
        type(ucon_variables_type), allocatable :: entries(:)
        !> How many entries are declarations (-1: every one of entries, as a registry given
        !> its entries by hand)
        integer :: used = -1
        !> The entry of each UCON id (found in constant time: n declarations are checked for
        !> repeats in O(n))
        type(id_index_type) :: index
    contains
        !> Validate and record one UCOVAR call
        procedure :: declare => registry_declare
        !> Index of a UCON id's entry, 0 when it has none
        procedure :: find => registry_find
        !> Number of UCON statements declared
        procedure :: count => registry_size
    end type ucovar_registry_type

contains

    !> Validate one UCOVAR call and record it; nothing is recorded when it is wrong.
    pure subroutine registry_declare(self, id, nparts, lparts, nvars, lvars, error)
        !> Registry to add to
        class(ucovar_registry_type), intent(inout) :: self
        !> UCON statement id
        integer, intent(in) :: id
        !> Number of part ids given
        integer, intent(in) :: nparts
        !> Part id of each variable
        integer, intent(in) :: lparts(:)
        !> Number of codes given
        integer, intent(in) :: nvars
        !> Code of each variable
        integer, intent(in) :: lvars(:)
        !> Names the UCON id and the bad entry when the declaration is wrong
        type(error_type), allocatable, intent(out) :: error
        type(ucon_variables_type) :: entry
        integer :: i, j

        if (nvars < 1 .or. nvars > max_ucon_vars) then
            call ucon_error(error, id, "UCOVAR declares " // to_text(nvars) &
                & // " variables (NVARS); expected 1 to " // to_text(max_ucon_vars))
            return
        end if
        if (nparts /= nvars) then
            call ucon_error(error, id, "UCOVAR has NPARTS = " // to_text(nparts) &
                & // " but NVARS = " &
                & // to_text(nvars) // "; LPARTS and LVARS must be of equal length")
            return
        end if
        if (size(lparts) < nvars .or. size(lvars) < nvars) then
            call ucon_error(error, id, "UCOVAR arrays hold fewer than NVARS = " // to_text(nvars) &
                & // " entries")
            return
        end if
        if (self%find(id) > 0) then
            call ucon_error(error, id, "UCOVAR called twice for this UCON; declare once, on the " &
                & // "initialisation call (IFLAG = 3)")
            return
        end if
        do i = 1, nvars
            if (.not. is_valid_code(lvars(i))) then
                call ucon_error(error, id, "UCOVAR variable " // to_text(i) // " has code " &
                    & // to_text(lvars(i)) &
                    & // "; expected one of 11 12 13 14 15 16 21 22 23 24 25 26")
                return
            end if
            if (lparts(i) < 1) then
                call ucon_error(error, id, "UCOVAR variable " // to_text(i) // " (" &
                    & // code_name(lvars(i)) // ") has part id " // to_text(lparts(i)) &
                    & // "; expected a positive part id")
                return
            end if
            do j = 1, i - 1
                if (lparts(j) == lparts(i) .and. lvars(j) == lvars(i)) then
                    call ucon_error(error, id, "UCOVAR variables " // to_text(j) // " and " &
                        & // to_text(i) // " are both " // code_name(lvars(i)) // " of part " &
                        & // to_text(lparts(i)) // "; each variable may be declared once")
                    return
                end if
            end do
        end do

        entry%id = id
        entry%parts = lparts(:nvars)
        entry%codes = lvars(:nvars)
        call append_entry(self, entry)
    end subroutine registry_declare

    !> Append an entry, the capacity doubled first when entries is full, and index its id.
    pure subroutine append_entry(self, entry)
        class(ucovar_registry_type), intent(inout) :: self
        type(ucon_variables_type), intent(in) :: entry
        type(ucon_variables_type), allocatable :: grown(:)
        integer :: k, count, previous

        count = self%count()
        if (.not. allocated(self%entries)) allocate(self%entries(0))
        if (count == size(self%entries)) then
            allocate(grown(max(8, 2*count)))
            do k = 1, count
                grown(k) = self%entries(k)
            end do
            call move_alloc(grown, self%entries)
        end if
        ! entries given by hand (used = -1) are indexed before the first one appended
        if (self%used < 0) then
            do k = 1, count
                call self%index%add(int(self%entries(k)%id, int64), k, previous)
            end do
        end if
        self%used = count + 1
        self%entries(self%used) = entry
        call self%index%add(int(entry%id, int64), self%used, previous)
    end subroutine append_entry

    !> Index of the entry for a UCON id, 0 when the id has not been declared.
    pure function registry_find(self, id) result(index)
        !> Registry to search
        class(ucovar_registry_type), intent(in) :: self
        !> UCON statement id
        integer, intent(in) :: id
        integer :: index

        if (self%used >= 0) then
            index = self%index%find(int(id, int64))
            return
        end if
        if (allocated(self%entries)) then
            do index = 1, size(self%entries)
                if (self%entries(index)%id == id) return
            end do
        end if
        index = 0
    end function registry_find

    !> Number of UCON statements declared.
    pure function registry_size(self) result(count)
        !> Registry to count
        class(ucovar_registry_type), intent(in) :: self
        integer :: count

        count = 0
        if (self%used >= 0) then
            count = self%used
        else if (allocated(self%entries)) then
            count = size(self%entries)
        end if
    end function registry_size

end module rollcon_ucovar_registry
