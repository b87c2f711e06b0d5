! SPDX-License-Identifier: MIT
!> The random states a UCOSUB check draws: uniform in documented ranges per variable code,
!> from a seed and the UCON id, the same on every compiler (xorshift64).
module rollcon_random_states
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    implicit none
    private

    public :: sampling_ranges, seed_state, draw_state

    !> Ranges of the random states: |X|, |Y|, |Z| [m]
    real(wp), parameter :: position_range = 1.0_wp
    !> |Xdot|, |Ydot|, |Zdot| [m/s]
    real(wp), parameter :: velocity_range = 1.0_wp
    !> |psidot|, |thetadot|, |phidot| [rad/s]
    real(wp), parameter :: rate_range = 10.0_wp
    !> theta stays this far from 0 and pi, the Euler-angle singularity [rad]
    real(wp), parameter :: theta_margin = 0.05_wp
    !> Time is drawn in [0, time_range] [s]
    real(wp), parameter :: time_range = 10.0_wp

contains

    !> The ranges the states are drawn from, as lines of text (for help and reports).
    pure function sampling_ranges() result(lines)
        character(len=80) :: lines(4)

        lines(1) = "psi, phi (codes 14, 16) in (-pi, pi) rad; theta (15) in (0.05, pi - 0.05) rad"
        lines(2) = "X, Y, Z (11-13) in (-1, 1) m; Xdot, Ydot, Zdot (21-23) in (-1, 1) m/s"
        lines(3) = "psidot, thetadot, phidot (24-26) in (-10, 10) rad/s"
        lines(4) = "time in [0, 10] s; uniform, from the seed and the UCON id"
    end function sampling_ranges

    !> Starting state of the generator for a seed and a UCON id (never zero).
    pure function seed_state(seed, id) result(state)
        integer, intent(in) :: seed, id
        integer(int64) :: state
        integer :: i

        state = ieor(int(seed, int64), ishft(int(id, int64), 32))
        state = ieor(state, 6755399441055744_int64)
        do i = 1, 8
            call xorshift(state)
        end do
    end function seed_state

    !> One step of Marsaglia's xorshift64 (shifts 13, 7, 17): only shifts and exclusive ors,
    !> so no integer overflow, and the same sequence on every compiler.
    pure subroutine xorshift(state)
        integer(int64), intent(inout) :: state

        state = ieor(state, ishft(state, 13))
        state = ieor(state, ishft(state, -7))
        state = ieor(state, ishft(state, 17))
    end subroutine xorshift

    !> Uniform number in (0, 1) from the top 53 bits of the next state.
    subroutine uniform(state, u)
        integer(int64), intent(inout) :: state
        real(wp), intent(out) :: u

        call xorshift(state)
        u = (real(ishft(state, -11), wp) + 0.5_wp) * 2.0_wp**(-53)
    end subroutine uniform

    !> A state in the documented ranges (sampling_ranges) for the declared codes.
    subroutine draw_state(state, codes, q, time)
        integer(int64), intent(inout) :: state
        integer, intent(in) :: codes(:)
        real(wp), intent(out) :: q(:), time
        real(wp) :: u
        integer :: i

        do i = 1, size(codes)
            call uniform(state, u)
            select case (codes(i))
            case (11:13)
                q(i) = position_range*(2.0_wp*u - 1.0_wp)
            case (14, 16)
                q(i) = pi*(2.0_wp*u - 1.0_wp)
            case (15)
                q(i) = theta_margin + (pi - 2.0_wp*theta_margin)*u
            case (21:23)
                q(i) = velocity_range*(2.0_wp*u - 1.0_wp)
            case default
                q(i) = rate_range*(2.0_wp*u - 1.0_wp)
            end select
        end do
        call uniform(state, u)
        time = time_range*u
    end subroutine draw_state

end module rollcon_random_states
