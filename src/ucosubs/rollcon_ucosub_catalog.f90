! SPDX-License-Identifier: MIT
!> The built-in UCOSUBs by name, as a dataset's `UCON/id, ..., ROUTINE=name`,
!> `rollcon run MODEL.adm --ucosub NAME` or a library caller names them: `disk`, the
!> hand-checked rolling disk (rollcon_disk_reference, listed here by hand), and every generated
!> spec under its spec name, taken from the generated catalog rollcon_gen_catalog (so a new spec
!> is served as soon as `python -m ucon write` has run). Names are read in any case.
!>
!> Every built-in routine reads the same PAR layout: the part id, the UCOVAR codes it
!> declares, its physical parameters, then the component when it has several;
!> builtin_ucosub_par builds that list.
module rollcon_ucosub_catalog
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, lower_case
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_par, only : disk_npar, disk_codes
    use rollcon_disk_reference, only : hand_disk_ucosub => rolling_disk_ucosub
    use rollcon_gen_catalog, only : generated_count, generated_names, generated_npar, &
        & generated_ncomponents, generated_time_free, generated_routine, generated_codes, &
        & generated_summary, generated_first_part_nvars
    implicit none
    private

    public :: find_builtin_ucosub, builtin_ucosub_names, builtin_ucosub_par, builtin_ucosub_name
    public :: builtin_ucosub_summary, builtin_ucosubs_for_par

    !> Name of the hand-checked disk routine, and of the generated routine of the same constraint
    character(len=*), parameter :: hand_disk_name = "disk", generated_twin = "rolling_disk"
    !> Number of no-slip components of the hand-checked disk routine (PAR(11))
    integer, parameter :: hand_disk_components = 3
    !> What lookup returns for the hand-checked routine, and for a name that is not built in
    integer, parameter :: entry_hand_disk = 0, entry_unknown = -1

contains

    !> The built-in routine called name (any case); found is false when there is none.
    subroutine find_builtin_ucosub(name, ucosub, time_free, found)
        character(len=*), intent(in) :: name
        !> The routine (null when not found)
        procedure(ucosub_interface), pointer, intent(out) :: ucosub
        !> Its F has no explicit time: the driver need not ask for time partials
        logical, intent(out) :: time_free
        logical, intent(out) :: found
        integer :: entry

        ucosub => null()
        time_free = .false.
        entry = lookup(name)
        found = entry /= entry_unknown
        select case (entry)
        case (entry_unknown)
            return
        case (entry_hand_disk)
            ! the hand-checked routine's F has no explicit time (docs/design.md §5)
            ucosub => hand_disk_ucosub
            time_free = .true.
        case default
            call generated_routine(entry, ucosub)
            time_free = generated_time_free(entry)
        end select
    end subroutine find_builtin_ucosub

    !> The catalog's name of a routine ("" when it is no built-in one: a user's) and whether
    !> its F is free of time (false for a routine that is not built in).
    function builtin_ucosub_name(routine, time_free) result(name)
        procedure(ucosub_interface), pointer, intent(in) :: routine
        logical, intent(out) :: time_free
        character(len=:), allocatable :: name
        procedure(ucosub_interface), pointer :: candidate
        integer, allocatable :: entries(:)
        logical :: found
        integer :: i

        name = ""
        time_free = .false.
        entries = listed_entries()
        do i = 1, size(entries)
            call find_builtin_ucosub(entry_name(entries(i)), candidate, time_free, found)
            if (found .and. associated(routine, candidate)) then
                name = entry_name(entries(i))
                return
            end if
        end do
        time_free = .false.
    end function builtin_ucosub_name

    !> The names as a list for messages: "disk, rolling_disk, disk_height, ...": the two disk
    !> routines first (the hand-checked one and its generated twin, as the list has always
    !> begun), then every other generated routine in the generated catalog's (alphabetical) order.
    pure function builtin_ucosub_names() result(list)
        character(len=:), allocatable :: list
        integer, allocatable :: entries(:)
        integer :: i

        entries = listed_entries()
        list = entry_name(entries(1))
        do i = 2, size(entries)
            list = list // ", " // entry_name(entries(i))
        end do
    end function builtin_ucosub_names

    !> The built-in routines whose PAR layout the constants par fit, as a list for messages in
    !> the order of builtin_ucosub_names ("" for none): as many constants as the routine takes,
    !> a positive whole part id in PAR(1), the routine's UCOVAR codes from PAR(2) on, and a
    !> component in range when it has several. The physical parameters are not judged (the
    !> routine checks them when declared).
    pure function builtin_ucosubs_for_par(par) result(list)
        !> The constants of FUNCTION=USER(...)
        real(wp), intent(in) :: par(:)
        character(len=:), allocatable :: list
        integer, allocatable :: entries(:), codes(:)
        integer :: i, npar, ncomponents, first

        list = ""
        entries = listed_entries()
        do i = 1, size(entries)
            call entry_layout(entries(i), codes, npar, ncomponents, first)
            if (size(par) /= npar) cycle
            if (.not. whole_in(par(1), 1, huge(1))) cycle
            if (first > 0) then
                ! two parts: the second part's id and codes after the first's
                if (.not. whole_in(par(first + 2), 1, huge(1))) cycle
                if (any(par(2:1 + first) /= real(codes(:first), wp))) cycle
                if (any(par(first + 3:2 + size(codes)) /= real(codes(first + 1:), wp))) cycle
            else if (any(par(2:1 + size(codes)) /= real(codes, wp))) then
                cycle
            end if
            if (ncomponents > 1) then
                if (.not. whole_in(par(npar), 1, ncomponents)) cycle
            end if
            if (len(list) > 0) list = list // ", "
            list = list // entry_name(entries(i))
        end do
    end function builtin_ucosubs_for_par

    !> One line on what the built-in routine called name enforces; empty when there is none.
    pure function builtin_ucosub_summary(name) result(summary)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: summary
        integer :: entry

        entry = lookup(name)
        select case (entry)
        case (entry_unknown)
            summary = ""
        case (entry_hand_disk)
            summary = "The seed paper's rolling disk, hand-checked (docs/ucosub-disk.md): no " &
                & // "slip, no penetration at the contact."
        case default
            summary = generated_summary(entry)
        end select
    end function builtin_ucosub_summary

    !> The PAR list of one UCON served by the built-in routine called name: the part id, the
    !> routine's codes, the physical parameters in its order (units as its module documents:
    !> SI lengths [m] and rates [rad/s]), then the component when the routine has several.
    !> A routine of two parts (a joint primitive between two parts) takes the second part's id,
    !> part_j, after its first part's codes, and its codes after it (ucon/spec.py).
    !> Refused (stat_input) for an unknown name, the wrong number of parameters, a component
    !> out of range, or a routine of two parts without part_j; nothing else is checked here
    !> (the routine checks its PAR when declared).
    pure subroutine builtin_ucosub_par(name, part, parameters, component, par, error, part_j)
        !> Name of the routine (any case)
        character(len=*), intent(in) :: name
        !> Id of the part whose variables the UCON constrains (the first part of a routine of
        !> two parts)
        integer, intent(in) :: part
        !> Physical parameters, in the routine's PAR order (e.g. the radius [m])
        real(wp), intent(in) :: parameters(:)
        !> Which component, 1 to the routine's number of components (1 when it has one)
        integer, intent(in) :: component
        !> The constants of FUNCTION=USER(...)
        real(wp), allocatable, intent(out) :: par(:)
        type(error_type), allocatable, intent(out) :: error
        !> Id of the second part of a routine of two parts
        integer, intent(in), optional :: part_j
        integer, allocatable :: codes(:)
        integer :: entry, npar, ncomponents, nparameters, first

        entry = lookup(name)
        select case (entry)
        case (entry_unknown)
            call fatal_error(error, "no built-in UCOSUB is called '" // trim(name) &
                & // "'; the built-in routines are " // builtin_ucosub_names(), stat_input)
            return
        case default
            call entry_layout(entry, codes, npar, ncomponents, first)
        end select
        nparameters = npar - 1 - size(codes) - merge(1, 0, first > 0)
        if (ncomponents > 1) nparameters = nparameters - 1
        if (size(parameters) /= nparameters) then
            call fatal_error(error, "the built-in UCOSUB '" // trim(name) // "' takes " &
                & // to_text(nparameters) // " physical parameter(s) (PAR(" &
                & // to_text(2 + size(codes) + merge(1, 0, first > 0)) // ") on), got " &
                & // to_text(size(parameters)), stat_input)
            return
        end if
        if (first > 0 .and. .not. present(part_j)) then
            call fatal_error(error, "the built-in UCOSUB '" // trim(name) // "' constrains " &
                & // "two parts: give the second part's id (part_j)", stat_input)
            return
        end if
        if (component < 1 .or. component > ncomponents) then
            call fatal_error(error, "the built-in UCOSUB '" // trim(name) // "' has " &
                & // to_text(ncomponents) // " component(s); component must be 1 to " &
                & // to_text(ncomponents) // ", got " // to_text(component), stat_input)
            return
        end if
        if (first > 0) then
            par = [real(part, wp), real(codes(:first), wp), real(part_j, wp), &
                & real(codes(first + 1:), wp), parameters]
        else
            par = [real(part, wp), real(codes, wp), parameters]
        end if
        if (ncomponents > 1) par = [par, real(component, wp)]
    end subroutine builtin_ucosub_par

    !> The entries in the order of builtin_ucosub_names: the hand-checked disk, its generated
    !> twin, then the other generated routines in the generated catalog's order.
    pure function listed_entries() result(entries)
        integer, allocatable :: entries(:)
        integer :: i

        entries = [entry_hand_disk]
        if (lookup(generated_twin) > 0) entries = [entries, lookup(generated_twin)]
        do i = 1, generated_count
            if (generated_names(i) == generated_twin) cycle
            entries = [entries, i]
        end do
    end function listed_entries

    !> The name of an entry (not entry_unknown).
    pure function entry_name(entry) result(name)
        integer, intent(in) :: entry
        character(len=:), allocatable :: name

        if (entry == entry_hand_disk) then
            name = hand_disk_name
        else
            name = trim(generated_names(entry))
        end if
    end function entry_name

    !> The PAR layout of an entry (not entry_unknown): its UCOVAR codes, NPAR, number of
    !> components, and for a routine of two parts the number of its first part's codes (0: one
    !> part).
    pure subroutine entry_layout(entry, codes, npar, ncomponents, first)
        integer, intent(in) :: entry
        integer, allocatable, intent(out) :: codes(:)
        integer, intent(out) :: npar, ncomponents, first

        first = 0
        if (entry == entry_hand_disk) then
            codes = disk_codes
            npar = disk_npar
            ncomponents = hand_disk_components
        else
            codes = generated_codes(entry)
            npar = generated_npar(entry)
            ncomponents = generated_ncomponents(entry)
            first = generated_first_part_nvars(entry)
        end if
    end subroutine entry_layout

    !> True for a whole number from low to high.
    pure logical function whole_in(value, low, high)
        real(wp), intent(in) :: value
        integer, intent(in) :: low, high

        whole_in = value >= real(low, wp) .and. value <= real(high, wp)
        if (whole_in) whole_in = value == aint(value)
    end function whole_in

    !> entry_hand_disk, the generated catalog's entry number, or entry_unknown.
    pure integer function lookup(name)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: key
        integer :: i

        key = lower_case(trim(adjustl(name)))
        lookup = entry_unknown
        if (key == hand_disk_name) then
            lookup = entry_hand_disk
            return
        end if
        ! a loop, not findloc: gfortran 12's findloc on character arrays misbehaves
        do i = 1, generated_count
            if (key == trim(generated_names(i))) then
                lookup = i
                return
            end if
        end do
    end function lookup


end module rollcon_ucosub_catalog
