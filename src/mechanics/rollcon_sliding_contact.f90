! SPDX-License-Identifier: MIT
!> A contact's mode in the equations of motion: rolling (its no-slip rows hold), sliding
!> (its two tangential rows are dropped and a Coulomb friction force mu_k F_n acts at the
!> contact point against the slip velocity) or flight (all three rows dropped: the part is a
!> free rigid body). The equations (rollcon_equations) read it in every
!> solve; the contact's watch (rollcon_contact_watch) owns it and switches it at its events.
!>
!> Sliding's accelerations are exact, not lagged: the friction's magnitude depends on the
!> normal multiplier, so the saddle-point system with the tangential rows dropped is solved for
!> two right-hand sides, (f, gamma) giving (a0, lambda0) and (D, 0) giving (a1, lambda1), D the
!> generalised force of a unit force along the slip direction s at the contact point
!> (D = s_1 c_t1 + s_2 c_t2: the tangential rows are the contact point's velocity, so their
!> gradients are its Jacobian). By linearity the solution with the friction -mu F_n D is
!> a = a0 - mu F_n a1, lambda = lambda0 - mu F_n lambda1, and F_n = c_nz lambda_n gives
!> F_n (1 + mu c_nz lambda1_n) = c_nz lambda0_n (docs/design.md §5, "Contact modes"). Where
!> 1 + mu c_nz lambda1_n <= 0 the sliding problem has no solution or many (Painlevé's
!> paradox): it is refused, never integrated.
module rollcon_sliding_contact
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: sliding_contact_type, painleve_margin

    !> Smallest 1 + mu c_nz lambda1_n accepted: below it the normal force of sliding is
    !> amplified more than a hundredfold over the frictionless one (1 at no coupling), so the
    !> sliding equations are within 1 % of Painlevé's singular case and no solution is to be
    !> trusted
    real(wp), parameter :: painleve_margin = 1.0e-2_wp

    type :: sliding_contact_type
        !> The contact slides (its tangential rows dropped, friction acting)
        logical :: sliding = .false.
        !> The part flies (the contact's three rows dropped, no contact force)
        logical :: flying = .false.
        !> Its rows in the model's constraints: the two tangential (the contact point's
        !> horizontal velocity, X then Y) and the normal one
        integer :: tangential(2) = 0, normal = 0
        !> The coordinate of the part's centre height Z (its column of C)
        integer :: height_column = 0
        !> Kinetic friction coefficient [-] > 0
        real(wp) :: mu = 0.0_wp
        !> Slip direction used where the slip speed is exactly zero (the start of a slide,
        !> unit, ground X and Y)
        real(wp) :: reference(2) = [1.0_wp, 0.0_wp]
        !> The slip speed [m/s] within which the friction's direction turns smoothly to the
        !> reference (direction): the watch's, half the slip's integration error at the
        !> slide's start (0: the direction is the slip's own wherever it is not zero)
        real(wp) :: slip_floor = 0.0_wp
        !> At the last sliding solve: the slip velocity [m/s], the normal force [N], the
        !> friction force on the part [N] (ground X and Y), the power it dissipates [W] >= 0,
        !> and the Painlevé denominator 1 + mu c_nz lambda1_n [-]
        real(wp) :: slip(2) = 0.0_wp, normal_force = 0.0_wp, friction(2) = 0.0_wp
        real(wp) :: power = 0.0_wp, denominator = 1.0_wp
        !> Kinetic energy the impacts have taken so far [J] >= 0 (rollcon_contact_impact)
        real(wp) :: impact_loss = 0.0_wp
        !> Work the drive of a moving plane (a turntable's MOTION) has done on the part in the
        !> impacts so far [J], signed: each impulse P times the table's velocity under the
        !> contact point, V_table . P (0 on the ground)
        real(wp) :: impact_drive_work = 0.0_wp
        !> Scratch of the second right-hand side: accelerations (n) and multipliers (nc)
        real(wp), allocatable :: unit_a(:), unit_lambda(:)
    contains
        procedure :: direction
        procedure :: turning_speed
        procedure :: dropped
    end type sliding_contact_type

contains

    !> Unit direction of the friction's opposite for the slip velocity v = slip (ground X, Y)
    !> [m/s]: w / |w| with w = v + slip_floor r, r the reference, or r where w is exactly zero.
    !> Where |v| is far above the floor this is v / |v| to within slip_floor / |v|; within it,
    !> where the slip is not known better than its integration error and its direction is
    !> the rounding's (the first steps of a slide from rest, whose Newton iterations met a
    !> direction that turned with each iterate and failed: docs/design.md section 5), it
    !> turns smoothly to r, the slide's own direction. Along r (a straight slide) it is r
    !> exactly. Without a floor: v / |v|, or r at zero slip.
    pure function direction(self, slip) result(s)
        class(sliding_contact_type), intent(in) :: self
        real(wp), intent(in) :: slip(2)
        real(wp) :: s(2)
        real(wp) :: w(2), speed

        w = slip + self%slip_floor*self%reference
        speed = norm2(w)
        if (speed > 0.0_wp) then
            s = w/speed
        else
            s = self%reference
        end if
    end function direction

    !> |w| of direction (w = v + slip_floor r) [m/s]: the direction's partials in v are
    !> (I - s s^T) / |w| (none where it is zero).
    pure real(wp) function turning_speed(self, slip)
        class(sliding_contact_type), intent(in) :: self
        real(wp), intent(in) :: slip(2)

        turning_speed = norm2(slip + self%slip_floor*self%reference)
    end function turning_speed

    !> Whether the mode drops row k of the model's constraints: a tangential row while
    !> sliding or flying, the normal row while flying.
    pure logical function dropped(self, k)
        class(sliding_contact_type), intent(in) :: self
        integer, intent(in) :: k

        dropped = (self%sliding .or. self%flying) .and. any(self%tangential == k)
        if (self%flying .and. self%normal == k) dropped = .true.
    end function dropped

end module rollcon_sliding_contact
