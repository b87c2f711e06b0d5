! SPDX-License-Identifier: MIT
!> A dataset's CONTACT statement and the GRAPHICS its IGEOM and JGEOM name (docs/datasets.md,
!> "CONTACT"), read as the text states them:
!>
!> - `CONTACT/id, IGEOM=g1, JGEOM=g2, POISSON, RESTITUTION_COEFFICIENT=e,
!>   COULOMB_FRICTION=ON, MU_STATIC=ms, MU_DYNAMIC=md`: a part's sphere (GRAPHICS ELLIPSOID of
!>   equal scales) or rim (GRAPHICS CYLINDER) on the ground's plane (GRAPHICS PLANE). rollcon
!>   holds it exactly: rolling, sliding and flight with the switches at roots
!>   (docs/design.md §5, "Contact modes"). ADAMS's keys of its penalty normal force and its
!>   regularised friction (IMPACT, STIFFNESS, DAMPING, DMAX, EXPONENT, PENALTY,
!>   STICTION_TRANSITION_VELOCITY, FRICTION_TRANSITION_VELOCITY,
!>   AUGMENTED_LAGRANGIAN_FORMULATION) are read and not used (named in the run's warning);
!>   the keys of user-written laws and flipped geometries are refused, with why.
!> - rollcon's own keys on it: ROLLING_RESISTANCE=delta [length] and AIR_VISCOSITY=mu
!>   [Pa s] (a rim's dissipation, docs/design.md §5 "Dissipation").
!>
!> The geometries are checked where the dataset is assembled (rollcon_adm_contact), once every
!> GRAPHICS and MARKER is read.
module rollcon_adm_contacts
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type, upper_case
    use rollcon_adm_keywords, only : argument_key, arg_place, read_reals, read_integer
    implicit none
    private

    public :: adm_graphics_type, adm_contact_type, read_contact, contact_keys
    public :: graphics_ellipsoid, graphics_cylinder, graphics_plane

    !> The shapes a CONTACT can name (an adm_graphics_type's shape)
    integer, parameter :: graphics_ellipsoid = 1, graphics_cylinder = 2, graphics_plane = 3

    !> The keywords of CONTACT: ADAMS's, then rollcon's own
    character(len=*), parameter :: contact_keys(24) = [character(len=32) :: "IGEOM", "JGEOM", &
        & "IFLIP_GEOMETRY", "JFLIP_GEOMETRY", "IMPACT", "POISSON", "STIFFNESS", "DAMPING", &
        & "DMAX", "EXPONENT", "PENALTY", "RESTITUTION_COEFFICIENT", "NORMAL_FUNCTION", &
        & "NORMAL_ROUTINE", "COULOMB_FRICTION", "MU_STATIC", "MU_DYNAMIC", &
        & "STICTION_TRANSITION_VELOCITY", "FRICTION_TRANSITION_VELOCITY", "FRICTION_FUNCTION", &
        & "FRICTION_ROUTINE", "AUGMENTED_LAGRANGIAN_FORMULATION", "ROLLING_RESISTANCE", &
        & "AIR_VISCOSITY"]
    !> The keys of ADAMS's penalty normal force and regularised friction: read, not used
    character(len=*), parameter :: regularisation_keys(9) = [character(len=32) :: "IMPACT", &
        & "STIFFNESS", "DAMPING", "DMAX", "EXPONENT", "PENALTY", &
        & "STICTION_TRANSITION_VELOCITY", "FRICTION_TRANSITION_VELOCITY", &
        & "AUGMENTED_LAGRANGIAN_FORMULATION"]
    !> Largest friction coefficient and viscosity accepted (the scenes' bounds)
    real(wp), parameter :: friction_max = 100.0_wp, viscosity_max = 1.0e3_wp

    !> A GRAPHICS statement of a shape a CONTACT can name (ELLIPSOID, CYLINDER, PLANE)
    type :: adm_graphics_type
        integer :: id = 0, line = 0
        !> graphics_ellipsoid, graphics_cylinder or graphics_plane
        integer :: shape = 0
        !> Its marker: CM (ELLIPSOID, CYLINDER) or RM (PLANE); 0 when not given
        integer :: marker = 0
        !> CYLINDER's RADIUS and LENGTH, ELLIPSOID's XSCALE, YSCALE, ZSCALE (its diameters
        !> along the marker's axes) [m]
        real(wp) :: radius = 0.0_wp, length = 0.0_wp, scales(3) = 0.0_wp
    end type adm_graphics_type

    !> CONTACT/id
    type :: adm_contact_type
        integer :: id = 0, line = 0
        !> IGEOM and JGEOM: GRAPHICS ids, and the lines they were written on
        integer :: igeom = 0, jgeom = 0, igeom_line = 0, jgeom_line = 0
        !> RESTITUTION_COEFFICIENT [-] in [0, 1]; given: flight and impacts are modelled
        real(wp) :: restitution = 0.0_wp
        logical :: restitution_given = .false.
        !> MU_STATIC and MU_DYNAMIC [-] (MU_DYNAMIC defaults to MU_STATIC); the lines of
        !> MU_STATIC and MU_DYNAMIC (0: not given)
        real(wp) :: mu_static = 0.0_wp, mu_dynamic = 0.0_wp
        integer :: mu_static_line = 0, mu_dynamic_line = 0
        !> rollcon's own: ROLLING_RESISTANCE [m] and AIR_VISCOSITY [Pa s], >= 0
        real(wp) :: rolling_resistance = 0.0_wp, air_viscosity = 0.0_wp
        !> The keys read and not used ("CONTACT PENALTY") and their lines
        character(len=64), allocatable :: unused(:)
        integer, allocatable :: unused_lines(:)
    end type adm_contact_type

contains

    !> CONTACT/id: every key read and checked (units: the dataset's length unit in SI,
    !> length). Errors, with the key and why: IGEOM or JGEOM missing or naming more than one
    !> GRAPHICS, a flipped geometry, a user-written normal or friction law, COULOMB_FRICTION
    !> other than ON, MU_STATIC missing or not in (0, 100], MU_DYNAMIC not in (0, MU_STATIC],
    !> RESTITUTION_COEFFICIENT not in [0, 1], a negative dissipation coefficient.
    subroutine read_contact(path, where, statement, length, contact, error)
        !> The dataset's path; "file:line: CONTACT/id", the start of messages
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        !> The dataset's length unit in metres
        real(wp), intent(in) :: length
        type(adm_contact_type), intent(out) :: contact
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, word
        real(wp), allocatable :: values(:)
        integer :: k

        contact%id = statement%id
        contact%line = statement%line
        allocate(contact%unused(0), contact%unused_lines(0))
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, contact_keys, key, error)
            if (allocated(error)) return
            associate (argument => statement%arguments(k))
                at = arg_place(path, where, argument) // " " // key
                if (any(regularisation_keys == key)) then
                    ! ADAMS's penalty force and friction regularisation: rollcon holds the
                    ! contact exactly, so these have nothing to set
                    call note_unused("CONTACT " // key, argument%line)
                    if (argument%assigned) then
                        call read_reals(argument, at, 1, 1, .false., values, error)
                        if (allocated(error)) return
                    end if
                    cycle
                end if
                select case (key)
                case ("IGEOM", "JGEOM")
                    if (.not. argument%assigned) then
                        call fatal_error(error, at // ": expected a GRAPHICS id", stat_input)
                        return
                    end if
                    if (size(argument%values) /= 1) then
                        call fatal_error(error, at // ": expected one GRAPHICS id, got " &
                            & // to_text(size(argument%values)) // " (rollcon's contact is " &
                            & // "one sphere or rim on the ground's plane: write one CONTACT " &
                            & // "per pair)", stat_input)
                        return
                    end if
                    if (key == "IGEOM") then
                        call read_integer(argument, at, contact%igeom, error)
                        contact%igeom_line = argument%line
                    else
                        call read_integer(argument, at, contact%jgeom, error)
                        contact%jgeom_line = argument%line
                    end if
                case ("IFLIP_GEOMETRY", "JFLIP_GEOMETRY")
                    call fatal_error(error, at // ": not supported: rollcon's contact is a " &
                        & // "sphere or rim above the ground's plane, whose normal is its " &
                        & // "marker's z (a flipped geometry would put the part below it)", &
                        & stat_input)
                case ("NORMAL_FUNCTION", "NORMAL_ROUTINE", "FRICTION_FUNCTION", &
                        & "FRICTION_ROUTINE")
                    call fatal_error(error, at // ": not supported: rollcon holds the contact " &
                        & // "exactly as constraints (rolling, sliding, flight), so there is " &
                        & // "no normal force law or friction law to write; give " &
                        & // "RESTITUTION_COEFFICIENT and MU_STATIC, MU_DYNAMIC", stat_input)
                case ("POISSON")
                    if (argument%assigned) call fatal_error(error, at // " takes no value " &
                        & // "(the restitution is RESTITUTION_COEFFICIENT=e)", stat_input)
                case ("RESTITUTION_COEFFICIENT")
                    call read_reals(argument, at, 1, 1, .false., values, error)
                    if (allocated(error)) return
                    if (.not. (values(1) >= 0.0_wp .and. values(1) <= 1.0_wp)) then
                        call fatal_error(error, at // ": expected a restitution in [0, 1], " &
                            & // "got " // to_text(values(1)), stat_input)
                        return
                    end if
                    contact%restitution = values(1)
                    contact%restitution_given = .true.
                case ("COULOMB_FRICTION")
                    if (.not. argument%assigned) then
                        call fatal_error(error, at // ": expected ON", stat_input)
                        return
                    else if (size(argument%values) /= 1) then
                        call fatal_error(error, at // ": expected ON", stat_input)
                        return
                    end if
                    word = upper_case(trim(adjustl(argument%values(1)%text)))
                    select case (word)
                    case ("ON")
                    case ("OFF")
                        call fatal_error(error, at // "=OFF: not supported: rollcon's contact " &
                            & // "rolls while static friction holds it and slides against " &
                            & // "Coulomb friction; frictionless sliding is not modelled " &
                            & // "(write COULOMB_FRICTION=ON with MU_STATIC, MU_DYNAMIC)", &
                            & stat_input)
                    case ("DYNAMICS_ONLY")
                        call fatal_error(error, at // "=DYNAMICS_ONLY: not supported: it " &
                            & // "leaves out static friction, and rollcon's contact rolls " &
                            & // "exactly where static friction holds it (write " &
                            & // "COULOMB_FRICTION=ON)", stat_input)
                    case default
                        call fatal_error(error, at // ": expected ON, OFF or DYNAMICS_ONLY " &
                            & // "(rollcon takes ON), got " // word, stat_input)
                    end select
                case ("MU_STATIC", "MU_DYNAMIC")
                    call read_reals(argument, at, 1, 1, .false., values, error)
                    if (allocated(error)) return
                    if (.not. (values(1) > 0.0_wp .and. values(1) <= friction_max)) then
                        call fatal_error(error, at // ": expected a friction coefficient in " &
                            & // "(0, " // to_text(friction_max) // "], got " &
                            & // to_text(values(1)), stat_input)
                        return
                    end if
                    if (key == "MU_STATIC") then
                        contact%mu_static = values(1)
                        contact%mu_static_line = argument%line
                    else
                        contact%mu_dynamic = values(1)
                        contact%mu_dynamic_line = argument%line
                    end if
                case ("ROLLING_RESISTANCE")
                    call read_reals(argument, at, 1, 1, .false., values, error, factor=length)
                    if (allocated(error)) return
                    if (.not. values(1) >= 0.0_wp) then
                        call fatal_error(error, at // ": expected a length >= 0 (the normal " &
                            & // "force's arm against rolling), got " // to_text(values(1)), &
                            & stat_input)
                        return
                    end if
                    contact%rolling_resistance = values(1)
                case ("AIR_VISCOSITY")
                    call read_reals(argument, at, 1, 1, .false., values, error)
                    if (allocated(error)) return
                    if (.not. (values(1) >= 0.0_wp .and. values(1) <= viscosity_max)) then
                        call fatal_error(error, at // ": expected a viscosity in [0, " &
                            & // to_text(viscosity_max) // "] Pa s, got " &
                            & // to_text(values(1)), stat_input)
                        return
                    end if
                    contact%air_viscosity = values(1)
                end select
                if (allocated(error)) return
            end associate
        end do
        if (contact%igeom == 0 .or. contact%jgeom == 0) then
            call fatal_error(error, where // ": IGEOM=id and JGEOM=id are both needed (the " &
                & // "part's sphere or cylinder and the ground's plane, GRAPHICS ids)", &
                & stat_input)
        else if (contact%mu_static_line == 0) then
            call fatal_error(error, where // ": MU_STATIC is needed (the friction " &
                & // "coefficient that ends rolling; rollcon's contact is COULOMB_FRICTION=ON)", &
                & stat_input)
        else if (contact%mu_dynamic_line == 0) then
            contact%mu_dynamic = contact%mu_static
        else if (contact%mu_dynamic > contact%mu_static) then
            call fatal_error(error, place_of(contact%mu_dynamic_line) // " MU_DYNAMIC: " &
                & // "expected <= MU_STATIC = " // to_text(contact%mu_static) // " (kinetic " &
                & // "friction exceeding static would stop a slip that rolling cannot hold), " &
                & // "got " // to_text(contact%mu_dynamic), stat_input)
        end if

    contains

        !> One more key read and not used, at line.
        subroutine note_unused(what, line)
            character(len=*), intent(in) :: what
            integer, intent(in) :: line
            character(len=64), allocatable :: names(:)
            integer :: n

            n = size(contact%unused)
            allocate(names(n + 1))
            names(:n) = contact%unused
            names(n + 1) = what
            call move_alloc(names, contact%unused)
            contact%unused_lines = [contact%unused_lines, line]
        end subroutine note_unused

        !> "file:line: CONTACT/id" at line.
        pure function place_of(line) result(text)
            integer, intent(in) :: line
            character(len=:), allocatable :: text

            text = where
            if (index(where, ": ") > 0) text = path // ":" // to_text(line) &
                & // where(index(where, ": ", back=.true.):)
        end function place_of
    end subroutine read_contact

end module rollcon_adm_contacts
