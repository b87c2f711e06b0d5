! SPDX-License-Identifier: MIT
!> The model's units at the UCOSUB boundary. ADAMS hands a UCOSUB everything in the model's
!> units: a dataset written in millimetres (UNITS/SYSTEM=MMKS) passes the state in mm and mm/s,
!> the time in its time unit and PAR as written; rollcon computes in SI. The factors here turn
!> one into the other, for every variable UCOVAR can declare:
!>
!>     q_model = scale * q_SI     X, Y, Z: 1/L   psi, theta, phi: 1
!>                                Xdot, Ydot, Zdot: T/L   psidot, thetadot, phidot: T
!>     t_model = t_SI / T
!>
!> where L and T are the dataset's length and time units in m and s. What comes back is
!> turned to SI by the chain rule: dF/dq_SI = scale * dF/dq_model, dF/dt_SI = dF/dt_model / T.
!> F itself is taken to be a length at position level and a velocity at velocity level (as
!> every contact constraint is): F_SI = L * F_model, or L/T * F_model. That choice only scales
!> the constraint's row, so the motion does not depend on it; it makes the residual and the
!> multiplier read in SI (m or m/s, and N) like those of the same model written in SI.
module rollcon_ucosub_units
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: ucosub_units_type, variable_scales, value_scale

    !> A model's units as factors to SI: a length of 1 model unit is `length` m
    type :: ucosub_units_type
        !> The length unit [m]
        real(wp) :: length = 1.0_wp
        !> The time unit [s]
        real(wp) :: time = 1.0_wp
    contains
        procedure :: is_si
    end type ucosub_units_type

contains

    !> True when both units are SI's own: nothing to convert.
    elemental logical function is_si(self)
        class(ucosub_units_type), intent(in) :: self

        is_si = self%length == 1.0_wp .and. self%time == 1.0_wp
    end function is_si

    !> dq_model/dq_SI of each declared variable, by its UCOVAR code (see the module's header).
    pure function variable_scales(units, codes) result(scales)
        type(ucosub_units_type), intent(in) :: units
        integer, intent(in) :: codes(:)
        real(wp) :: scales(size(codes))
        integer :: i

        do i = 1, size(codes)
            select case (codes(i))
            case (11:13)
                scales(i) = 1.0_wp/units%length
            case (21:23)
                scales(i) = units%time/units%length
            case (24:26)
                scales(i) = units%time
            case default
                scales(i) = 1.0_wp
            end select
        end do
    end function variable_scales

    !> F_SI/F_model: a length at position level, a velocity at velocity level.
    pure real(wp) function value_scale(units, holonomic)
        type(ucosub_units_type), intent(in) :: units
        !> The UCON declares no rate: a position constraint
        logical, intent(in) :: holonomic

        if (holonomic) then
            value_scale = units%length
        else
            value_scale = units%length/units%time
        end if
    end function value_scale

end module rollcon_ucosub_units
