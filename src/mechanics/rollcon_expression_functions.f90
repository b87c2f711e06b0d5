! SPDX-License-Identifier: MIT
!> ADAMS's functions of numbers, each written once in jet arithmetic (rollcon_jet): called with
!> constant jets they give the value alone (the value path of rollcon_expression), with
!> variables' jets the value and its exact partials (rollcon_expression_jet). Each is ADAMS's
!> definition (docs/datasets.md, "Function expressions"); a value outside a function's domain
!> is NaN.
module rollcon_expression_functions
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_jet, only : jet_type, jet_constant, jet_chain, operator(+), operator(-), &
        & operator(*), operator(/), operator(**), sin, cos, abs, log, sqrt, asin, acos
    use rollcon_spline, only : spline_type, spline_derivatives
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: jet_step, jet_step5, jet_havsin, jet_shf, jet_poly, jet_cheby, jet_fourier
    public :: jet_impact, jet_bistop, jet_dim, jet_mod, jet_aint, jet_anint, jet_sign, jet_if
    public :: jet_min, jet_max, jet_power, jet_log_domain, jet_sqrt_domain, jet_divide
    public :: jet_asin_domain, jet_acos_domain, jet_spline, nan_jet

contains

    !> A NaN.
    elemental function nan_jet() result(c)
        type(jet_type) :: c

        c = jet_constant(ieee_value(1.0_wp, ieee_quiet_nan))
    end function nan_jet

    !> STEP(x, x0, h0, x1, h1): h0 up to x0, h1 from x1, the cubic
    !> h0 + (h1 - h0) s^2 (3 - 2 s), s = (x - x0)/(x1 - x0), between; NaN unless x0 < x1.
    pure function jet_step(x, x0, h0, x1, h1) result(y)
        type(jet_type), intent(in) :: x, x0, h0, x1, h1
        type(jet_type) :: y
        type(jet_type) :: s

        if (.not. x0%v < x1%v) then
            y = nan_jet()
        else if (x%v <= x0%v) then
            y = h0
        else if (x%v >= x1%v) then
            y = h1
        else
            s = (x - x0)/(x1 - x0)
            y = h0 + (h1 - h0)*s**2*(3.0_wp - 2.0_wp*s)
        end if
    end function jet_step

    !> STEP5(x, x0, h0, x1, h1): as STEP with the quintic h0 + (h1 - h0) s^3 (10 - 15 s + 6 s^2),
    !> continuous to the second derivative.
    pure function jet_step5(x, x0, h0, x1, h1) result(y)
        type(jet_type), intent(in) :: x, x0, h0, x1, h1
        type(jet_type) :: y
        type(jet_type) :: s

        if (.not. x0%v < x1%v) then
            y = nan_jet()
        else if (x%v <= x0%v) then
            y = h0
        else if (x%v >= x1%v) then
            y = h1
        else
            s = (x - x0)/(x1 - x0)
            y = h0 + (h1 - h0)*s**3*(10.0_wp + s*(6.0_wp*s - 15.0_wp))
        end if
    end function jet_step5

    !> HAVSIN(x, x0, h0, x1, h1): as STEP with the haversine
    !> (h0 + h1)/2 + (h1 - h0)/2 sin(pi s - pi/2).
    pure function jet_havsin(x, x0, h0, x1, h1) result(y)
        type(jet_type), intent(in) :: x, x0, h0, x1, h1
        type(jet_type) :: y
        type(jet_type) :: s

        if (.not. x0%v < x1%v) then
            y = nan_jet()
        else if (x%v <= x0%v) then
            y = h0
        else if (x%v >= x1%v) then
            y = h1
        else
            s = (x - x0)/(x1 - x0)
            y = 0.5_wp*(h0 + h1) + 0.5_wp*(h1 - h0)*sin(pi*s - 0.5_wp*pi)
        end if
    end function jet_havsin

    !> SHF(x, x0, a, w, phi, b) = a sin(w (x - x0) - phi) + b.
    pure function jet_shf(x, x0, a, w, phi, b) result(y)
        type(jet_type), intent(in) :: x, x0, a, w, phi, b
        type(jet_type) :: y

        y = a*sin(w*(x - x0) - phi) + b
    end function jet_shf

    !> POLY(x, x0, a0, ..., am) = sum a_j (x - x0)^j (Horner's scheme); args = x, x0, a0, ...
    pure function jet_poly(args) result(y)
        type(jet_type), intent(in) :: args(:)
        type(jet_type) :: y
        type(jet_type) :: t
        integer :: j

        t = args(1) - args(2)
        y = args(size(args))
        do j = size(args) - 1, 3, -1
            y = y*t + args(j)
        end do
    end function jet_poly

    !> CHEBY(x, x0, a0, ..., am) = sum a_j T_j(x - x0), T_0 = 1, T_1 = t,
    !> T_j = 2 t T_(j-1) - T_(j-2); args = x, x0, a0, ...
    pure function jet_cheby(args) result(y)
        type(jet_type), intent(in) :: args(:)
        type(jet_type) :: y
        type(jet_type) :: t, previous, current, next
        integer :: j

        t = args(1) - args(2)
        y = args(3)
        if (size(args) < 4) return
        previous = jet_constant(1.0_wp)
        current = t
        y = y + args(4)*current
        do j = 5, size(args)
            next = 2.0_wp*t*current - previous
            previous = current
            current = next
            y = y + args(j)*current
        end do
    end function jet_cheby

    !> FORCOS (cosine false: FORSIN) (x, x0, w, a0, ..., am) = a0 + sum_(j>=1) a_j cos(j w (x - x0))
    !> (sin for FORSIN); args = x, x0, w, a0, ...
    pure function jet_fourier(cosine, args) result(y)
        logical, intent(in) :: cosine
        type(jet_type), intent(in) :: args(:)
        type(jet_type) :: y
        type(jet_type) :: phase
        integer :: j

        phase = args(3)*(args(1) - args(2))
        y = args(4)
        do j = 5, size(args)
            if (cosine) then
                y = y + args(j)*cos(real(j - 4, wp)*phase)
            else
                y = y + args(j)*sin(real(j - 4, wp)*phase)
            end if
        end do
    end function jet_fourier

    !> IMPACT(x, xdot, x1, k, e, cmax, d): 0 for x >= x1, else
    !> max(0, k (x1 - x)^e - STEP(x, x1 - d, cmax, x1, 0) xdot); NaN unless k >= 0, e > 0,
    !> cmax >= 0 and d > 0.
    pure function jet_impact(x, xdot, x1, k, e, cmax, d) result(y)
        type(jet_type), intent(in) :: x, xdot, x1, k, e, cmax, d
        type(jet_type) :: y

        if (.not. (k%v >= 0.0_wp .and. e%v > 0.0_wp .and. cmax%v >= 0.0_wp &
            & .and. d%v > 0.0_wp)) then
            y = nan_jet()
        else if (x%v >= x1%v) then
            y = jet_constant(0.0_wp)
        else
            y = k*(x1 - x)**e - jet_step(x, x1 - d, cmax, x1, jet_constant(0.0_wp))*xdot
            if (.not. y%v > 0.0_wp) y = jet_constant(0.0_wp)
        end if
    end function jet_impact

    !> BISTOP(x, xdot, x1, x2, k, e, cmax, d): for x < x1 as IMPACT with free length x1; 0 from
    !> x1 to x2; for x > x2 min(0, -k (x - x2)^e - STEP(x, x2, 0, x2 + d, cmax) xdot); NaN
    !> unless x1 < x2, k >= 0, e > 0, cmax >= 0 and d > 0.
    pure function jet_bistop(x, xdot, x1, x2, k, e, cmax, d) result(y)
        type(jet_type), intent(in) :: x, xdot, x1, x2, k, e, cmax, d
        type(jet_type) :: y

        if (.not. (x1%v < x2%v .and. k%v >= 0.0_wp .and. e%v > 0.0_wp &
            & .and. cmax%v >= 0.0_wp .and. d%v > 0.0_wp)) then
            y = nan_jet()
        else if (x%v < x1%v) then
            y = k*(x1 - x)**e - jet_step(x, x1 - d, cmax, x1, jet_constant(0.0_wp))*xdot
            if (.not. y%v > 0.0_wp) y = jet_constant(0.0_wp)
        else if (x%v > x2%v) then
            y = -(k*(x - x2)**e) - jet_step(x, x2, jet_constant(0.0_wp), x2 + d, cmax)*xdot
            if (.not. y%v < 0.0_wp) y = jet_constant(0.0_wp)
        else
            y = jet_constant(0.0_wp)
        end if
    end function jet_bistop

    !> DIM(a, b) = a - b when a > b, else 0 (Fortran's DIM).
    pure function jet_dim(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (a%v > b%v) then
            y = a - b
        else
            y = jet_constant(0.0_wp)
        end if
    end function jet_dim

    !> MOD(a, b) = a - AINT(a/b) b (Fortran's MOD: the sign of a); NaN for b = 0.
    pure function jet_mod(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (b%v == 0.0_wp) then
            y = nan_jet()
        else
            y = a - aint(a%v/b%v)*b
        end if
    end function jet_mod

    !> AINT(x): x truncated to a whole number (towards 0); its partials are zero.
    pure function jet_aint(x) result(y)
        type(jet_type), intent(in) :: x
        type(jet_type) :: y

        y = jet_constant(aint(x%v))
    end function jet_aint

    !> ANINT(x): the nearest whole number (halves away from 0); its partials are zero.
    pure function jet_anint(x) result(y)
        type(jet_type), intent(in) :: x
        type(jet_type) :: y

        y = jet_constant(anint(x%v))
    end function jet_anint

    !> SIGN(a, b) = |a| when b >= 0, else -|a| (Fortran's SIGN).
    pure function jet_sign(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (b%v >= 0.0_wp) then
            y = abs(a)
        else
            y = -abs(a)
        end if
    end function jet_sign

    !> IF(e: negative, zero, positive).
    pure function jet_if(e, negative, zero, positive) result(y)
        type(jet_type), intent(in) :: e, negative, zero, positive
        type(jet_type) :: y

        if (e%v < 0.0_wp) then
            y = negative
        else if (e%v > 0.0_wp) then
            y = positive
        else
            y = zero
        end if
    end function jet_if

    !> MIN(a, b): a when a <= b.
    pure function jet_min(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (b%v < a%v) then
            y = b
        else
            y = a
        end if
    end function jet_min

    !> MAX(a, b): a when a >= b.
    pure function jet_max(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (b%v > a%v) then
            y = b
        else
            y = a
        end if
    end function jet_max

    !> a**b on the value path's domain: a > 0; a = 0 with b > 0 (d/db of a**b, a**b log a,
    !> is 0 there); a < 0 with a whole b.
    pure function jet_power(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (a%v > 0.0_wp) then
            y = a**b
        else if (a%v == 0.0_wp .and. b%v > 0.0_wp) then
            y = a**b%v
        else if (a%v < 0.0_wp .and. b%v == aint(b%v) .and. abs(b%v) < 1.0e9_wp) then
            y = a**nint(b%v)
        else
            y = nan_jet()
        end if
    end function jet_power

    !> a / b; NaN for b = 0.
    pure function jet_divide(a, b) result(y)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: y

        if (b%v == 0.0_wp) then
            y = nan_jet()
        else
            y = a/b
        end if
    end function jet_divide

    !> LOG(x); NaN for x <= 0.
    pure function jet_log_domain(x) result(y)
        type(jet_type), intent(in) :: x
        type(jet_type) :: y

        if (x%v > 0.0_wp) then
            y = log(x)
        else
            y = nan_jet()
        end if
    end function jet_log_domain

    !> SQRT(x); NaN for x < 0.
    pure function jet_sqrt_domain(x) result(y)
        type(jet_type), intent(in) :: x
        type(jet_type) :: y

        if (x%v >= 0.0_wp) then
            y = sqrt(x)
        else
            y = nan_jet()
        end if
    end function jet_sqrt_domain

    !> ASIN(x); NaN for |x| > 1.
    pure function jet_asin_domain(x) result(y)
        type(jet_type), intent(in) :: x
        type(jet_type) :: y

        if (abs(x%v) <= 1.0_wp) then
            y = asin(x)
        else
            y = nan_jet()
        end if
    end function jet_asin_domain

    !> ACOS(x); NaN for |x| > 1.
    pure function jet_acos_domain(x) result(y)
        type(jet_type), intent(in) :: x
        type(jet_type) :: y

        if (abs(x%v) <= 1.0_wp) then
            y = acos(x)
        else
            y = nan_jet()
        end if
    end function jet_acos_domain

    !> The iord-th derivative in x (0, 1 or 2) of a spline's curve at x (AKISPL, CUBSPL with
    !> method_akima or method_cubic), with its partials through x.
    pure function jet_spline(x, spline, method, iord) result(y)
        type(jet_type), intent(in) :: x
        type(spline_type), intent(in) :: spline
        integer, intent(in) :: method, iord
        type(jet_type) :: y
        real(wp) :: values(0:3), d2

        values = spline_derivatives(spline, method, x%v)
        d2 = 0.0_wp
        if (iord + 2 <= 3) d2 = values(iord + 2)
        y = jet_chain([x], values(iord), [values(iord + 1)], reshape([d2], [1, 1]))
    end function jet_spline

end module rollcon_expression_functions
