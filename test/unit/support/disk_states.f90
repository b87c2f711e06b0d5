! SPDX-License-Identifier: MIT
!> Seeded random states of the rolling disk for tests, including its extremes.
module disk_states
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    implicit none
    private

    public :: seed_random, random_disk_state


contains

    !> Seed the intrinsic generator so every run draws the same states.
    subroutine seed_random(seed)
        !> Any integer; different seeds give different sequences
        integer, intent(in) :: seed
        integer, allocatable :: put(:)
        integer :: n, i

        call random_seed(size=n)
        allocate(put(n))
        put = [(seed + 7919*i, i = 1, n)]
        call random_seed(put=put)
    end subroutine seed_random

    !> State k of a series: every 4th within 1e-6 rad of flat, every 4th (+1) within 1e-6 of
    !> upright; rates up to 1e3 rad/s; R log-uniform in [1e-3, 10] m.
    subroutine random_disk_state(k, q, radius)
        !> Index in the series, picks the kind of state
        integer, intent(in) :: k
        !> Xdot, Ydot, Zdot [m/s], psi, theta [rad], psidot, thetadot, phidot [rad/s]
        real(wp), intent(out) :: q(8)
        !> Disk radius [m]
        real(wp), intent(out) :: radius
        real(wp) :: u(12), rate_scale

        call random_number(u)
        radius = 10.0_wp**(-3.0_wp + 4.0_wp*u(1))
        q(4) = pi*(2.0_wp*u(2) - 1.0_wp)
        select case (mod(k, 4))
        case (0)
            q(5) = 1.0e-6_wp*(2.0_wp*u(3) - 1.0_wp)
        case (1)
            q(5) = 0.5_wp*pi + 1.0e-6_wp*(2.0_wp*u(3) - 1.0_wp)
        case default
            q(5) = pi*u(3)
        end select
        ! Rates log-uniform from 1e-2 to 1e3 rad/s, random sign.
        q(6:8) = sign(10.0_wp**(-2.0_wp + 5.0_wp*u(4:6)), u(7:9) - 0.5_wp)
        rate_scale = maxval(abs(q(6:8)))
        q(1:3) = radius*rate_scale*(2.0_wp*u(10:12) - 1.0_wp)
    end subroutine random_disk_state

end module disk_states
