! SPDX-License-Identifier: MIT
!> The UNITS statement: the dataset's units of force, mass, length and time as factors to SI.
!>
!> rollcon computes in SI, so every value read is multiplied by its factor; the units need not
!> be consistent with one another (ADAMS's UCF is then not needed). Supported names:
!> FORCE = NEWTON, KNEWTON, MILLINEWTON, DYNE, KILOGRAM_FORCE, POUND_FORCE;
!> MASS = KILOGRAM, GRAM, MEGAGRAM, POUND_MASS, SLUG; LENGTH = METER, MILLIMETER, CENTIMETER,
!> KILOMETER, INCH, FOOT; TIME = SECOND, MILLISECOND, MINUTE, HOUR; SYSTEM = SI or MKS
!> (N, kg, m, s), CGS (dyne, g, cm, s), MMKS (N, kg, mm, s). Angles are radians (D after a
!> number for degrees). Anything else is refused with the list.
module rollcon_adm_units
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_adm_keywords, only : resolve_name, name_index
    implicit none
    private

    public :: units_type, set_unit, unit_keywords, unit_names

    !> Factors to SI: a value v in dataset units is v * factor in SI
    type :: units_type
        real(wp) :: force = 1.0_wp, mass = 1.0_wp, length = 1.0_wp, time = 1.0_wp
    end type units_type

    character(len=*), parameter :: unit_keywords(5) = [character(len=6) :: "FORCE", "MASS", &
        & "LENGTH", "TIME", "SYSTEM"]

    character(len=*), parameter :: force_names(6) = [character(len=14) :: "NEWTON", &
        & "KNEWTON", "MILLINEWTON", "DYNE", "KILOGRAM_FORCE", "POUND_FORCE"]
    real(wp), parameter :: force_factors(6) = [1.0_wp, 1.0e3_wp, 1.0e-3_wp, 1.0e-5_wp, &
        & 9.80665_wp, 4.4482216152605_wp]
    character(len=*), parameter :: mass_names(5) = [character(len=10) :: "KILOGRAM", "GRAM", &
        & "MEGAGRAM", "POUND_MASS", "SLUG"]
    real(wp), parameter :: mass_factors(5) = [1.0_wp, 1.0e-3_wp, 1.0e3_wp, 0.45359237_wp, &
        & 14.593902937206_wp]
    character(len=*), parameter :: length_names(6) = [character(len=10) :: "METER", &
        & "MILLIMETER", "CENTIMETER", "KILOMETER", "INCH", "FOOT"]
    real(wp), parameter :: length_factors(6) = [1.0_wp, 1.0e-3_wp, 1.0e-2_wp, 1.0e3_wp, &
        & 0.0254_wp, 0.3048_wp]
    character(len=*), parameter :: time_names(4) = [character(len=11) :: "SECOND", &
        & "MILLISECOND", "MINUTE", "HOUR"]
    real(wp), parameter :: time_factors(4) = [1.0_wp, 1.0e-3_wp, 60.0_wp, 3600.0_wp]
    character(len=*), parameter :: system_names(4) = [character(len=4) :: "SI", "MKS", "CGS", &
        & "MMKS"]

contains

    !> Set one unit from `KEYWORD = name` (keyword already resolved).
    subroutine set_unit(units, keyword, written, where, error)
        type(units_type), intent(inout) :: units
        character(len=*), intent(in) :: keyword, written, where
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name

        select case (keyword)
        case ("FORCE")
            call resolve_name(written, force_names, "force unit", where, name, error)
            if (.not. allocated(error)) &
                & units%force = force_factors(name_index(name, force_names))
        case ("MASS")
            call resolve_name(written, mass_names, "mass unit", where, name, error)
            if (.not. allocated(error)) &
                & units%mass = mass_factors(name_index(name, mass_names))
        case ("LENGTH")
            call resolve_name(written, length_names, "length unit", where, name, error)
            if (.not. allocated(error)) &
                & units%length = length_factors(name_index(name, length_names))
        case ("TIME")
            call resolve_name(written, time_names, "time unit", where, name, error)
            if (.not. allocated(error)) &
                & units%time = time_factors(name_index(name, time_names))
        case default
            call resolve_name(written, system_names, "unit system", where, name, error)
            if (allocated(error)) return
            select case (name)
            case ("CGS")
                units = units_type(force=1.0e-5_wp, mass=1.0e-3_wp, length=1.0e-2_wp)
            case ("MMKS")
                units = units_type(length=1.0e-3_wp)
            case default
                units = units_type()
            end select
        end select
    end subroutine set_unit

    !> The dataset's units by their names: force, mass, length and time ("NEWTON", "KILOGRAM",
    !> "METER", "SECOND" for SI); a factor no name has is written as the factor to SI.
    subroutine unit_names(units, force, mass, length, time)
        type(units_type), intent(in) :: units
        character(len=:), allocatable, intent(out) :: force, mass, length, time

        force = name_of(units%force, force_names, force_factors)
        mass = name_of(units%mass, mass_names, mass_factors)
        length = name_of(units%length, length_names, length_factors)
        time = name_of(units%time, time_names, time_factors)
    contains
        function name_of(factor, names, factors) result(name)
            real(wp), intent(in) :: factor, factors(:)
            character(len=*), intent(in) :: names(:)
            character(len=:), allocatable :: name
            character(len=24) :: written
            integer :: k

            do k = 1, size(factors)
                if (abs(factor - factors(k)) <= 1.0e-12_wp*factors(k)) then
                    name = trim(names(k))
                    return
                end if
            end do
            write(written, '(es24.16)') factor
            name = trim(adjustl(written)) // " SI"
        end function name_of
    end subroutine unit_names

end module rollcon_adm_units
