! SPDX-License-Identifier: MIT
!> Dataset statements of bodies: PART (mass, inertia, pose, initial velocities) and MARKER.
!> An IP with products of inertia gives its principal moments and axes (rollcon_inertia_axes).
module rollcon_adm_bodies
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_adm_lexer, only : adm_statement_type, adm_argument_type, upper_case
    use rollcon_adm_keywords, only : read_reals, read_integer, argument_key, arg_place
    use rollcon_adm_units, only : units_type
    use rollcon_inertia_axes, only : principal_axes
    use rollcon_adm_model, only : adm_part_type, adm_marker_type
    implicit none
    private

    public :: read_part, read_marker

    character(len=*), parameter :: part_keys(13) = [character(len=6) :: "GROUND", "MASS", &
        & "CM", "IP", "QG", "REULER", "VX", "VY", "VZ", "WX", "WY", "WZ", "EXACT"]
    !> The coordinates EXACT may name, in the order of a part's q (X, Y, Z, psi, theta, phi)
    character(len=*), parameter :: exact_names(6) = [character(len=5) :: "X", "Y", "Z", "PSI", &
        & "THETA", "PHI"]
    character(len=*), parameter :: marker_keys(3) = [character(len=6) :: "PART", "QP", "REULER"]

contains

    !> PART/id as read (whether its id is new is the reader's to check).
    subroutine read_part(path, where, statement, units, part, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        !> The dataset's units
        type(units_type), intent(in) :: units
        type(adm_part_type), intent(out) :: part
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        integer :: k, axis
        real(wp) :: speed, rate

        part%id = statement%id
        part%line = statement%line
        speed = units%length/units%time
        rate = 1.0_wp/units%time
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, part_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("GROUND")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                    return
                end if
                part%ground = .true.
            case ("CM")
                call read_integer(statement%arguments(k), at, part%cm, error)
            case ("MASS")
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, &
                    & units%mass)
                if (.not. allocated(error)) part%mass = values(1)
            case ("IP")
                call read_reals(statement%arguments(k), at, 3, 6, .false., values, error, &
                    & units%mass*units%length**2)
                if (allocated(error)) return
                part%ip = values(1:3)
                if (size(values) == 6) then
                    ! products: the principal moments and axes of the tensor (LAPACK)
                    part%products = values(4:6)
                    call principal_axes(values, part%ip, part%principal, error)
                    if (allocated(error)) error%message = at // ": " // error%message
                end if
            case ("QG")
                call read_reals(statement%arguments(k), at, 3, 3, .false., values, error, &
                    & units%length)
                if (.not. allocated(error)) part%qg = values
            case ("REULER")
                call read_reals(statement%arguments(k), at, 3, 3, .true., values, error)
                if (.not. allocated(error)) part%reuler = values
            case ("VX", "VY", "VZ")
                axis = iachar(key(2:2)) - iachar("X") + 1
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, speed)
                if (allocated(error)) return
                part%velocity(axis) = values(1)
                part%velocity_given(axis) = .true.
            case ("WX", "WY", "WZ")
                axis = iachar(key(2:2)) - iachar("X") + 1
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, rate)
                if (allocated(error)) return
                part%angular_velocity(axis) = values(1)
                part%angular_velocity_given(axis) = .true.
            case ("EXACT")
                call read_exact(statement%arguments(k), at, part%exact, error)
            end select
            if (allocated(error)) return
        end do
    end subroutine read_part

    !> EXACT=c1:...:c6, each c one of X, Y, Z, PSI, THETA, PHI (any case, any order, as ADAMS).
    pure subroutine read_exact(argument, at, exact, error)
        type(adm_argument_type), intent(in) :: argument
        character(len=*), intent(in) :: at
        logical, intent(inout) :: exact(6)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, word
        integer :: start, colon, c

        if (.not. argument%assigned .or. size(argument%values) /= 1) then
            call fatal_error(error, at // ": expected names of coordinates separated by " &
                & // "colons, from X, Y, Z, PSI, THETA, PHI (EXACT=X:Y:PSI)", stat_input)
            return
        end if
        text = upper_case(trim(adjustl(argument%values(1)%text))) // ":"
        start = 1
        do while (start <= len(text))
            colon = start + index(text(start:), ":") - 1
            word = trim(adjustl(text(start:colon - 1)))
            do c = 1, size(exact_names)
                if (word == trim(exact_names(c))) exit
            end do
            if (c > size(exact_names)) then
                call fatal_error(error, at // ": '" // word // "' is not a coordinate; " &
                    & // "expected X, Y, Z, PSI, THETA or PHI, separated by colons", stat_input)
                return
            end if
            exact(c) = .true.
            start = colon + 1
        end do
    end subroutine read_exact

    !> MARKER/id as read (whether its id is new is the reader's to check).
    subroutine read_marker(path, where, statement, units, marker, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        !> The dataset's units
        type(units_type), intent(in) :: units
        type(adm_marker_type), intent(out) :: marker
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        integer :: k

        marker%id = statement%id
        marker%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, marker_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("PART")
                call read_integer(statement%arguments(k), at, marker%part, error)
            case ("QP")
                call read_reals(statement%arguments(k), at, 3, 3, .false., values, error, &
                    & units%length)
                if (.not. allocated(error)) marker%qp = values
            case ("REULER")
                call read_reals(statement%arguments(k), at, 3, 3, .true., values, error)
                if (.not. allocated(error)) marker%reuler = values
            end select
            if (allocated(error)) return
        end do
        if (marker%part == 0) then
            call fatal_error(error, where // ": PART=id is missing (the part the marker is on)", &
                & stat_input)
            return
        end if
    end subroutine read_marker

end module rollcon_adm_bodies
