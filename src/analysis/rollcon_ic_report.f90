! SPDX-License-Identifier: MIT
!> What an initial-conditions analysis did: the values it moved (part, coordinate, old, new,
!> unit), its iterations, and the text a program prints (docs/initial-conditions.md).
module rollcon_ic_report
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : coordinate_names
    implicit none
    private

    public :: ic_change_type, ic_report_type, ic_report_text, coordinate_unit

    !> One value the analysis moved
    type :: ic_change_type
        !> Id of the part (as in its PART statement)
        integer :: part_id = 0
        !> Which of the part's 12 quantities: 1..6 X, Y, Z, psi, theta, phi; 7..12 their rates
        !> (numbered as rollcon_output_layout's coordinate_names)
        integer :: coordinate = 0
        !> Value given and value after the analysis [m, rad, m/s or rad/s: coordinate_unit]
        real(wp) :: old = 0.0_wp, new = 0.0_wp
    contains
        procedure :: name => change_name
    end type ic_change_type

    !> The analysis's account
    type :: ic_report_type
        !> Values moved by more than the report floor (a hundredth of the tolerance's atol), in
        !> model order: positions first, then rates
        type(ic_change_type), allocatable :: changes(:)
        !> Newton iterations on the position UCONs, least-squares steps on the velocity rows
        integer :: newton_iterations = 0, velocity_steps = 0
        !> Number of position UCONs and of velocity rows (every UCON has one)
        integer :: position_rows = 0, velocity_rows = 0
        !> Largest |F| of any UCON after the analysis, at position and at velocity level
        real(wp) :: position_residual = 0.0_wp, velocity_residual = 0.0_wp
        !> The velocities the input gives could not all be kept with the UCONs met: they were
        !> moved with the rest (rollcon_initial_conditions)
        logical :: given_moved = .false.
    end type ic_report_type

contains

    !> The column name of a change's quantity: `Z_2`, `Xdot_2`.
    pure function change_name(self) result(name)
        class(ic_change_type), intent(in) :: self
        character(len=:), allocatable :: name

        name = trim(coordinate_names(self%coordinate)) // "_" // to_text(self%part_id)
    end function change_name

    !> Unit of quantity c (1..12): m, rad, m/s, rad/s.
    pure function coordinate_unit(c) result(unit)
        integer, intent(in) :: c
        character(len=:), allocatable :: unit

        select case (c)
        case (1:3)
            unit = "m"
        case (4:6)
            unit = "rad"
        case (7:9)
            unit = "m/s"
        case default
            unit = "rad/s"
        end select
    end function coordinate_unit

    !> The report as lines to print: a heading, then one line per moved value, e.g.
    !> `  part 2: Z_2 0.101 m -> 0.1 m (by -0.001 m)`.
    pure function ic_report_text(report) result(text)
        type(ic_report_type), intent(in) :: report
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        integer :: i

        text = "initial conditions: " // to_text(report%position_rows) // " position UCON(s), " &
            & // to_text(report%newton_iterations) // " Newton iteration(s); " &
            & // to_text(report%velocity_rows) // " velocity row(s), " &
            & // to_text(report%velocity_steps) // " least-squares step(s); largest |F| after: " &
            & // to_text(report%position_residual) // " (positions), " &
            & // to_text(report%velocity_residual) // " (velocities)"
        if (report%given_moved) text = text // nl // "  the velocities given (VX ... WZ) " &
            & // "cannot all be kept with the UCONs met: they were moved with the rest"
        if (size(report%changes) == 0) then
            text = text // nl // "  nothing moved: the start meets every UCON as given"
            return
        end if
        text = text // nl // "  moved to meet the UCONs (" // to_text(size(report%changes)) &
            & // " value(s)):"
        do i = 1, size(report%changes)
            associate (c => report%changes(i))
                text = text // nl // "  part " // to_text(c%part_id) // ": " // c%name() // " " &
                    & // to_text(c%old) // " " // coordinate_unit(c%coordinate) // " -> " &
                    & // to_text(c%new) // " " // coordinate_unit(c%coordinate) // " (by " &
                    & // to_text(c%new - c%old) // " " // coordinate_unit(c%coordinate) // ")"
            end associate
        end do
    end function ic_report_text

end module rollcon_ic_report
