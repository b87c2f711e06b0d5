! SPDX-License-Identifier: MIT
!> The impact of a contact point on the ground: the impulse P = (P_t, P_n) at the point
!> (tangential ground X, Y, then normal Z) from the contact point's velocity v before it and
!> the Delassus matrix W = J M^-1 J^T (J the point's velocity Jacobian, so that an impulse P
!> changes its velocity by W P and the rates by M^-1 J^T P), with Poisson's restitution e on
!> the normal impulse and Coulomb friction mu in the tangential one (docs/design.md §5,
!> "Flight and impacts"). Two phases:
!>
!> - compression: the normal impulse P_n1 > 0 that brings the point's normal velocity to
!>   zero, the tangential impulse at each P_n the one of least kinetic energy in the disk
!>   |P_t| <= mu P_n (sticking, v_t = 0 after, when that disk holds the impulse that sticks;
!>   otherwise on its rim, against the point's slip after: Coulomb's law on the velocity
!>   after the phase);
!> - restitution: the normal impulse e P_n1, its tangential impulse chosen the same way.
!>
!> The kinetic energy never rises: with v1 the velocity after compression (v1_n = 0,
!> v1_t . P1_t <= 0), compression changes T by v1 . P1 - P1' W P1 / 2 <= 0; restitution's
!> choice makes T least over a disk that holds e P1, whose change would be
!> e v1 . P1 + e^2 P1' W P1 / 2, so that the sum is at most (1 + e) v1_t . P1_t
!> - (1 - e^2) P1' W P1 / 2 <= 0 for 0 <= e <= 1.
module rollcon_contact_impact
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_text, only : to_text
    implicit none
    private

    public :: impact_type, contact_impact, least_energy_tangential

    !> Doublings of the frictionless normal impulse searched for the end of compression: a
    !> normal velocity still negative at 2^60 times it is a friction that keeps the point
    !> pressing into the ground (Painlevé's paradox in an impact), refused
    integer, parameter :: most_doublings = 60
    !> Bisection steps (each halves the bracket; 200 exhaust a double's range)
    integer, parameter :: most_halvings = 200

    !> An impact's outcome
    type :: impact_type
        !> The whole impulse on the part at the contact point and compression's [N s]
        !> (ground X, Y, Z)
        real(wp) :: impulse(3) = 0.0_wp, compression(3) = 0.0_wp
        !> The contact point's velocity after the impact and after compression [m/s]
        real(wp) :: velocity(3) = 0.0_wp, compressed(3) = 0.0_wp
        !> Restitution applied [-]
        real(wp) :: restitution = 0.0_wp
        !> Change of the kinetic energy, v . P + P' W P / 2 [J] (<= 0 up to rounding)
        real(wp) :: energy_change = 0.0_wp
        !> The tangential impulse stuck in compression and in restitution
        logical :: stuck(2) = .true.
    end type impact_type

contains

    !> The impact of a point approaching the ground at velocity v (v(3) < 0) [m/s] with
    !> Delassus matrix w (3 x 3, symmetric positive definite) [1/kg], friction mu >= 0 and
    !> restitution 0 <= e <= 1 (Poisson's, on the normal impulse). An error (stat_ucon) when
    !> no normal impulse ends compression (the friction drives the point into the ground:
    !> Painlevé's paradox of an impact).
    pure subroutine contact_impact(w, v, mu, e, impact, error)
        real(wp), intent(in) :: w(3, 3), v(3), mu, e
        type(impact_type), intent(out) :: impact
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: low, high, middle, p_t(2), w_tt(2, 2)
        integer :: k

        impact%restitution = e
        w_tt = w(1:2, 1:2)
        if (.not. v(3) < 0.0_wp) then
            ! not approaching: no impulse
            impact%velocity = v
            impact%compressed = v
            return
        end if
        ! compression: the first normal impulse, by doubling the frictionless one, where the
        ! normal velocity is no longer negative; then bisection to the end of the bracket
        low = 0.0_wp
        high = -v(3)/w(3, 3)
        do k = 1, most_doublings
            if (normal_velocity(high) >= 0.0_wp) exit
            low = high
            high = 2.0_wp*high
        end do
        if (normal_velocity(high) < 0.0_wp) then
            call fatal_error(error, "the impact is ill-posed: with friction " // to_text(mu) &
                & // " no normal impulse up to " // to_text(high) // " N s stops the contact " &
                & // "point's approach at " // to_text(-v(3)) // " m/s (Painlevé's paradox of " &
                & // "an impact: the friction drives the point into the ground)", stat_ucon)
            return
        end if
        do k = 1, most_halvings
            middle = 0.5_wp*(low + high)
            if (middle <= low .or. middle >= high) exit
            if (normal_velocity(middle) < 0.0_wp) then
                low = middle
            else
                high = middle
            end if
        end do
        call least_energy_tangential(w_tt, v(1:2) + w(1:2, 3)*high, mu*high, p_t, &
            & impact%stuck(1))
        impact%compression = [p_t, high]
        impact%compressed = v + matmul(w, impact%compression)
        impact%impulse = impact%compression
        impact%velocity = impact%compressed
        impact%stuck(2) = impact%stuck(1)
        if (e > 0.0_wp) then
            ! restitution: e times compression's normal impulse
            call least_energy_tangential(w_tt, impact%compressed(1:2) + w(1:2, 3)*e &
                & *high, mu*e*high, p_t, impact%stuck(2))
            impact%impulse = impact%compression + [p_t, e*high]
            impact%velocity = v + matmul(w, impact%impulse)
        end if
        impact%energy_change = dot_product(v, impact%impulse) &
            & + 0.5_wp*dot_product(impact%impulse, matmul(w, impact%impulse))

    contains

        !> The normal velocity after a normal impulse p_n [N s] and its least-energy
        !> tangential impulse [m/s].
        pure real(wp) function normal_velocity(p_n)
            real(wp), intent(in) :: p_n
            real(wp) :: x(2)
            logical :: stuck

            call least_energy_tangential(w_tt, v(1:2) + w(1:2, 3)*p_n, mu*p_n, x, stuck)
            normal_velocity = v(3) + w(3, 3)*p_n + dot_product(w(3, 1:2), x)
        end function normal_velocity

    end subroutine contact_impact

    !> The tangential impulse x [N s] of least kinetic energy b . x + x' A x / 2 in the disk
    !> |x| <= radius [N s]: A (2 x 2, symmetric positive definite) [1/kg] and b [m/s] the
    !> tangential block of W and the tangential velocity the normal impulse leaves. Inside
    !> (stuck): x = -A^-1 b, the tangential velocity after b + A x = 0. On the rim: x =
    !> -(A + kappa I)^-1 b with kappa > 0 where |x| = radius (|x| falls as kappa grows, to
    !> radius at kappa <= |b| / radius: bisection), so the velocity after, -kappa x, is
    !> against the impulse (Coulomb's law; the trust-region problem of optimisation).
    pure subroutine least_energy_tangential(a, b, radius, x, stuck)
        real(wp), intent(in) :: a(2, 2), b(2), radius
        real(wp), intent(out) :: x(2)
        logical, intent(out) :: stuck
        real(wp) :: low, high, middle
        integer :: k

        stuck = .true.
        x = 0.0_wp
        if (.not. radius > 0.0_wp) then
            stuck = norm2(b) == 0.0_wp
            return
        end if
        x = shifted_solve(0.0_wp)
        if (norm2(x) <= radius) return
        stuck = .false.
        low = 0.0_wp
        high = norm2(b)/radius
        do k = 1, most_halvings
            middle = 0.5_wp*(low + high)
            if (middle <= low .or. middle >= high) exit
            if (norm2(shifted_solve(middle)) > radius) then
                low = middle
            else
                high = middle
            end if
        end do
        x = shifted_solve(high)
        x = x*(radius/norm2(x))

    contains

        !> -(A + kappa I)^-1 b, by Cramer's rule (A + kappa I is symmetric positive definite).
        pure function shifted_solve(kappa) result(y)
            real(wp), intent(in) :: kappa
            real(wp) :: y(2), determinant

            determinant = (a(1, 1) + kappa)*(a(2, 2) + kappa) - a(1, 2)*a(2, 1)
            y(1) = -((a(2, 2) + kappa)*b(1) - a(1, 2)*b(2))/determinant
            y(2) = -((a(1, 1) + kappa)*b(2) - a(2, 1)*b(1))/determinant
        end function shifted_solve

    end subroutine least_energy_tangential

end module rollcon_contact_impact
