! SPDX-License-Identifier: MIT
!> The built-in UCOSUBs by name, as a dataset's `UCON/id, ..., ROUTINE=name` or
!> `rollcon run MODEL.adm --ucosub NAME` names them: `disk`, the hand-checked rolling disk
!> (rollcon_disk_reference), and every generated spec under its spec name (`rolling_disk`,
!> `disk_height`, `knife_edge`, `rolling_sphere`, `turntable_disk`). Names are read in any case.
module rollcon_ucosub_catalog
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : hand_disk_ucosub => rolling_disk_ucosub
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_time_free
    use rollcon_gen_knife_edge, only : knife_edge_ucosub, knife_edge_time_free
    use rollcon_gen_rolling_disk, only : rolling_disk_ucosub, rolling_disk_time_free
    use rollcon_gen_rolling_sphere, only : rolling_sphere_ucosub, rolling_sphere_time_free
    use rollcon_gen_turntable_disk, only : turntable_disk_ucosub, turntable_disk_time_free
    implicit none
    private

    public :: find_builtin_ucosub, builtin_ucosub_names

    !> The names, in the order they are listed
    character(len=*), parameter :: names(6) = [character(len=14) :: "disk", "rolling_disk", &
        & "disk_height", "knife_edge", "rolling_sphere", "turntable_disk"]

contains

    !> The built-in routine called name (any case); found is false when there is none.
    subroutine find_builtin_ucosub(name, ucosub, time_free, found)
        character(len=*), intent(in) :: name
        !> The routine (null when not found)
        procedure(ucosub_interface), pointer, intent(out) :: ucosub
        !> Its F has no explicit time: the driver need not ask for time partials
        logical, intent(out) :: time_free
        logical, intent(out) :: found

        ucosub => null()
        time_free = .false.
        found = .true.
        select case (lower_case(trim(name)))
        case ("disk")
            ! the hand-checked routine's F has no explicit time (docs/design.md §5)
            ucosub => hand_disk_ucosub
            time_free = .true.
        case ("rolling_disk")
            ucosub => rolling_disk_ucosub
            time_free = rolling_disk_time_free
        case ("disk_height")
            ucosub => disk_height_ucosub
            time_free = disk_height_time_free
        case ("knife_edge")
            ucosub => knife_edge_ucosub
            time_free = knife_edge_time_free
        case ("rolling_sphere")
            ucosub => rolling_sphere_ucosub
            time_free = rolling_sphere_time_free
        case ("turntable_disk")
            ucosub => turntable_disk_ucosub
            time_free = turntable_disk_time_free
        case default
            found = .false.
        end select
    end subroutine find_builtin_ucosub

    !> The names as a list for messages: "disk, rolling_disk, ...".
    pure function builtin_ucosub_names() result(list)
        character(len=:), allocatable :: list
        integer :: i

        list = trim(names(1))
        do i = 2, size(names)
            list = list // ", " // trim(names(i))
        end do
    end function builtin_ucosub_names

    !> text with A-Z turned to a-z.
    pure function lower_case(text) result(lower)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: lower
        integer :: i

        lower = text
        do i = 1, len(text)
            if (text(i:i) >= "A" .and. text(i:i) <= "Z") lower(i:i) = achar(iachar(text(i:i)) + 32)
        end do
    end function lower_case

end module rollcon_ucosub_catalog
