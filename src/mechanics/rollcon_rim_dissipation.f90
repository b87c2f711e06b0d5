! SPDX-License-Identifier: MIT
!> Dissipation at a rim rolling on the ground (docs/design.md §5, "Dissipation"): rolling
!> resistance and Moffatt's viscous air layer, as generalised forces on the part's 3-1-3
!> Euler-angle rates (the coordinates of rollcon_body: u = (Xdot, Ydot, Zdot, psidot,
!> thetadot, phidot)). The equations (rollcon_equations) apply them in every solve.
!>
!> Rolling resistance, lever arm delta [m]: the energy lost per length of rim rolled over the
!> ground is delta F_n / R (the rolling-resistance coefficient delta / R times the normal force
!> F_n). The contact point runs over the ground at R |phidot| (phidot the rolling rate, the
!> spin of the part relative to its tilt frame, which carries the rim through the contact),
!> so the law is the generalised force Q_phi = -delta F_n sign(phidot) on phi alone, power
!> delta F_n |phidot|. Its size depends on the normal multiplier, so the equations couple it
!> exactly, as sliding's friction (rollcon_sliding_contact).
!>
!> The air layer after Moffatt, Nature 404 (2000) 833-834: the air between a disk nearly flat
!> and the table is sheared as the gap's narrow side runs round with the precession psidot;
!> the rate of dissipation is Phi = (pi/4) mu_air R^3 psidot^2 / sin(theta), a Rayleigh
!> dissipation function D = Phi / 2 whose force is Q_psi = -(pi/4) mu_air R^3 psidot /
!> sin(theta) on psi alone. In steady precession near flat (psidot^2 sin(theta) = 4 g / R) it
!> is Moffatt's Phi = pi mu_air g R^2 / alpha^2, alpha = sin(theta), with which the energy
!> E = (3/2) m g R alpha falls to zero at his t0 = alpha0^3 m / (2 pi mu_air R).
module rollcon_rim_dissipation
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    implicit none
    private

    public :: rim_dissipation_type, air_coefficient

    type :: rim_dissipation_type
        !> The part whose rim dissipates (model order); 0: none
        integer :: part = 0
        !> The contact's normal row in the model's constraints and the column of the part's
        !> centre height Z
        integer :: normal = 0, height_column = 0
        !> Rolling resistance's lever arm delta [m] >= 0
        real(wp) :: rolling_resistance = 0.0_wp
        !> The air layer's coefficient c = (pi/4) mu_air R^3 [N m s] >= 0 (air_coefficient)
        real(wp) :: air = 0.0_wp
        !> The sign of rolling resistance's law in effect, held between the roots of phidot = 0
        !> that rollcon_dissipation_watch locates: +1 or -1 (Q_phi = -delta F_n rolling_sign),
        !> 0 for none; used when sign_given, else sign(phidot) (docs/design.md §5)
        real(wp) :: rolling_sign = 0.0_wp
        logical :: sign_given = .false.
        !> Held: phidot stays zero under the moment it needs (held_moment, on phi [N m]), while
        !> that is within delta F_n (rollcon_equations' held_coupling; the watch releases it)
        logical :: held = .false.
        real(wp) :: held_moment = 0.0_wp
        !> At the last solve: the normal force [N] and the power each law dissipates [W] >= 0
        real(wp) :: normal_force = 0.0_wp, rolling_power = 0.0_wp, air_power = 0.0_wp
        !> The work each law did from the run's start to the state of the row being made [J]
        !> >= 0: its power integrated with the state by the integrator, set by the run
        !> (rollcon_simulation) before each row for the row's columns
        real(wp) :: rolling_work = 0.0_wp, air_work = 0.0_wp
        !> The run's integrator integrates those works (CVODE); false (IDA): the dissipation
        !> watch sums them over the rows by the trapezoidal rule instead
        logical :: works_integrated = .false.
    contains
        procedure :: active
        procedure :: air_force
        procedure :: rolling_direction
        procedure :: power
    end type rim_dissipation_type

contains

    !> The air layer's coefficient (pi/4) mu_air R^3 [N m s] for the air's dynamic viscosity
    !> mu_air [Pa s] and the rim radius R [m] (Moffatt 2000, as above).
    pure real(wp) function air_coefficient(viscosity, radius)
        real(wp), intent(in) :: viscosity, radius

        air_coefficient = 0.25_wp*pi*viscosity*radius**3
    end function air_coefficient

    !> Some law acts.
    pure logical function active(self)
        class(rim_dissipation_type), intent(in) :: self

        active = self%part > 0 .and. (self%rolling_resistance > 0.0_wp .or. self%air > 0.0_wp)
    end function active

    !> The air layer's generalised force on psi [N m] at the part's theta [rad] and psidot
    !> [rad/s], -c psidot / sin(theta); records its power c psidot^2 / sin(theta) [W].
    function air_force(self, theta, psidot) result(q_psi)
        class(rim_dissipation_type), intent(inout) :: self
        real(wp), intent(in) :: theta, psidot
        real(wp) :: q_psi

        q_psi = -self%air*psidot/abs(sin(theta))
        self%air_power = -q_psi*psidot
    end function air_force

    !> The law's sign: rolling_sign when the watch gave it (held between the roots of
    !> phidot = 0, so that no step crosses the switch), else sign(phidot) (0 at phidot = 0):
    !> the generalised force of rolling resistance per unit delta F_n is minus this on phi.
    pure real(wp) function rolling_direction(self, phidot)
        class(rim_dissipation_type), intent(in) :: self
        real(wp), intent(in) :: phidot

        rolling_direction = 0.0_wp
        if (.not. self%rolling_resistance > 0.0_wp) return
        if (self%sign_given) then
            rolling_direction = self%rolling_sign
        else if (phidot /= 0.0_wp) then
            rolling_direction = sign(1.0_wp, phidot)
        end if
    end function rolling_direction

    !> The power both laws dissipated at the last solve [W] >= 0.
    pure real(wp) function power(self)
        class(rim_dissipation_type), intent(in) :: self

        power = self%rolling_power + self%air_power
    end function power

end module rollcon_rim_dissipation
