! SPDX-License-Identifier: MIT
!> Tests of Prony's method (src/analysis/rollcon_mode_rates.f90): the rates of a signal made of
!> known modes come back, and signals it cannot fit are refused.
module test_mode_rates
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_mode_rates, only : exponential_rates
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_mode_rates

    !> A signal given exactly in its modes is fitted to round-off: the recurrence's least
    !> squares and the companion's eigenvalues lose a few digits to the conditioning of
    !> samples 0.01 s apart (the roots z = exp(lambda h) lie near 1); 1e-7 relative leaves room
    real(wp), parameter :: tol_exact = 1.0e-7_wp

contains

    subroutine collect_mode_rates(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("three-modes-recovered", test_three_modes), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_mode_rates

    !> x(t) = 2 exp(-0.3 t) + exp(-0.8 t) cos(4.5 t + 0.4), sampled every 0.01 s for 8 s:
    !> the rates -0.3 and -0.8 +- 4.5 i, and a fit rest at round-off.
    subroutine test_three_modes(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: x(801), t, rest
        real(wp), allocatable :: re(:), im(:)
        real(wp), parameter :: expected_re(3) = [-0.3_wp, -0.8_wp, -0.8_wp], &
            & expected_im(3) = [0.0_wp, 4.5_wp, -4.5_wp]
        integer :: k, nearest

        do k = 1, size(x)
            t = 0.01_wp*(k - 1)
            x(k) = 2.0_wp*exp(-0.3_wp*t) + exp(-0.8_wp*t)*cos(4.5_wp*t + 0.4_wp)
        end do
        call exponential_rates(0.01_wp, x, 3, re, im, rest, error)
        if (allocated(error)) return
        do k = 1, 3
            nearest = minloc(hypot(re - expected_re(k), im - expected_im(k)), 1)
            call check(error, hypot(re(nearest) - expected_re(k), im(nearest) - expected_im(k)) &
                & <= tol_exact*hypot(expected_re(k), expected_im(k)), "rate " &
                & // to_text(expected_re(k)) // " + " // to_text(expected_im(k)) // " i: found " &
                & // to_text(re(nearest)) // " + " // to_text(im(nearest)) // " i")
            if (allocated(error)) return
        end do
        call check(error, rest <= 1.0e-10_wp, "fit rest " // to_text(rest))
    end subroutine test_three_modes

    !> Too few samples, a zero signal, and more modes than the signal holds are refused.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: refused
        real(wp), allocatable :: re(:), im(:)
        real(wp) :: rest, x(100)
        integer :: k

        call exponential_rates(0.01_wp, [1.0_wp, 0.5_wp, 0.25_wp], 3, re, im, rest, refused)
        call check(error, allocated(refused), "3 samples for 3 modes: not refused")
        if (allocated(error)) return
        call exponential_rates(0.01_wp, [(0.0_wp, k = 1, 50)], 2, re, im, rest, refused)
        call check(error, allocated(refused), "a zero signal: not refused")
        if (allocated(error)) return
        x = [(exp(-0.5_wp*0.01_wp*k), k = 1, 100)]
        call exponential_rates(0.01_wp, x, 3, re, im, rest, refused)
        call check(error, allocated(refused), "one mode asked for three: not refused")
    end subroutine test_refusals

end module test_mode_rates
