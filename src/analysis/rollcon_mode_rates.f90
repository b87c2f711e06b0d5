! SPDX-License-Identifier: MIT
!> The exponential rates of a signal sampled at equal steps (Prony's method; docs/linear.md,
!> "Rates measured from a run"): a signal that is a sum of k modes c_i exp(lambda_i t) obeys the
!> linear recurrence x(n) = a_1 x(n-1) + ... + a_k x(n-k), whose characteristic roots are
!> z_i = exp(lambda_i h). The coefficients are found by least squares over every sample of the
!> window (LAPACK, through rollcon_least_squares), the roots as the eigenvalues of the
!> recurrence's companion matrix (LAPACK dgeev), and lambda_i = log(z_i)/h. It measures from a
!> simulation what the linear analysis predicts: a growth or decay rate and a frequency.
module rollcon_mode_rates
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_lapack, only : general_eigenvalues
    use rollcon_least_squares, only : minimum_norm_solve
    implicit none
    private

    public :: exponential_rates

contains

    !> The order rates lambda [1/unit of step] of the samples x(1..n), taken step apart, with
    !> the relative rest of the recurrence's fit (|x - prediction| / |x| over the window: small
    !> when order modes describe the signal). An error when there are fewer than 3 order
    !> samples, or the window's samples are all zero.
    subroutine exponential_rates(step, x, order, re, im, rest, error)
        !> Sampling step (e.g. [s])
        real(wp), intent(in) :: step
        !> The samples
        real(wp), intent(in) :: x(:)
        !> How many modes
        integer, intent(in) :: order
        !> Real and imaginary parts of the rates [1/unit of step], order each; a conjugate pair
        !> for an oscillation
        real(wp), allocatable, intent(out) :: re(:), im(:)
        !> Relative rest of the fit
        real(wp), intent(out) :: rest
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), b(:), coefficients(:), companion(:, :), zr(:), zi(:)
        integer :: n, k, rows, rank

        n = size(x)
        rest = 0.0_wp
        allocate(re(0), im(0))
        if (order < 1 .or. n < 3*order .or. .not. step > 0.0_wp) then
            call fatal_error(error, "exponential rates: " // to_text(n) // " samples for " &
                & // to_text(order) // " modes at a step of " // to_text(step) // ": need " &
                & // "at least 3 samples a mode and a positive step", stat_input)
            return
        end if
        if (all(x == 0.0_wp)) then
            call fatal_error(error, "exponential rates: every sample is zero", stat_input)
            return
        end if
        rows = n - order
        allocate(a(rows, order), b(rows))
        do k = 1, order
            a(:, k) = x(order + 1 - k:n - k)
        end do
        b = x(order + 1:)
        allocate(coefficients(order))
        call minimum_norm_solve(a, b, 1.0e-14_wp, coefficients, rank, error)
        if (allocated(error)) return
        rest = norm2(matmul(a, coefficients) - b)/norm2(b)
        if (rank < order) then
            call fatal_error(error, "exponential rates: the samples hold fewer than " &
                & // to_text(order) // " modes (the recurrence's rank is " // to_text(rank) &
                & // "): ask for fewer", stat_input)
            return
        end if
        ! companion matrix of z^k - a_1 z^(k-1) - ... - a_k
        allocate(companion(order, order), source=0.0_wp)
        companion(1, :) = coefficients
        do k = 2, order
            companion(k, k - 1) = 1.0_wp
        end do
        allocate(zr(order), zi(order))
        call general_eigenvalues(companion, zr, zi, error)
        if (allocated(error)) return
        re = log(hypot(zr, zi))/step
        im = atan2(zi, zr)/step
    end subroutine exponential_rates

end module rollcon_mode_rates
