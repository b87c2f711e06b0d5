! SPDX-License-Identifier: MIT
!> Curves through data points, as ADAMS's AKISPL and CUBSPL functions fit a SPLINE's points
!> (docs/datasets.md, "Function expressions"): on each interval a cubic
!> y = y_i + b_i s + c_i s^2 + d_i s^3, s = x - x_i, with
!>
!> - AKISPL: Akima's slopes (H. Akima, J. ACM 17 (1970) 589-602): at each point the weighted
!>   mean of the neighbouring chords' slopes, weights |m_{i+1} - m_i| and |m_{i-1} - m_{i-2}|
!>   (their plain mean where both weights vanish), the chords extended past each end by
!>   Akima's two fictitious points (slopes continued linearly); continuous first derivative;
!> - CUBSPL: the interpolating cubic spline with continuous first and second derivatives and
!>   zero second derivative at both ends (the natural spline).
!>
!> Outside [x_1, x_n] the end interval's cubic goes on; with LINEAR_EXTRAPOLATE (the SPLINE's
!> option) the curve goes on along the straight line of its value and slope at that end. A
!> curve needs at least 4 points for CUBSPL and at least 2 for AKISPL (ADAMS asks for 4), its
!> x strictly increasing.
!>
!> A curve's **corners** are the points where a derivative jumps (spline_corners): every
!> interior point (Akima's second derivative jumps there, the cubic spline's third), and with
!> LINEAR_EXTRAPOLATE both end points too (where the cubic gives way to its tangent); without
!> it the end interval's cubic goes on smoothly past the end. An integrator stops at them and
!> starts again (docs/design.md §7).
module rollcon_spline
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: spline_type, new_spline, spline_derivatives, method_akima, method_cubic
    public :: spline_corners, spline_corner_switch

    !> The fitting methods
    integer, parameter :: method_akima = 1, method_cubic = 2

    !> One curve's points and both fits' coefficients (index 1: Akima, 2: cubic)
    type :: spline_type
        !> The SPLINE's id
        integer :: id = 0
        !> LINEAR_EXTRAPOLATE: beyond the end points, the end's tangent line
        logical :: linear = .false.
        !> The points, x strictly increasing
        real(wp), allocatable :: x(:), y(:)
        !> b, c, d of each interval (n - 1 of them; the last row repeats the last interval
        !> for x beyond the last point) for each method
        real(wp), allocatable :: b(:, :), c(:, :), d(:, :)
    end type spline_type

contains

    !> The spline of points (x, y); `problem` is "" or why they cannot be fitted (fewer than
    !> 2 points, x not strictly increasing, a value not finite). With `linear_extrapolate`
    !> true, the curve beyond its ends is the end's tangent line (default false: the end
    !> interval's cubic).
    pure subroutine new_spline(id, x, y, spline, problem, linear_extrapolate)
        integer, intent(in) :: id
        real(wp), intent(in) :: x(:), y(:)
        type(spline_type), intent(out) :: spline
        character(len=:), allocatable, intent(out) :: problem
        logical, intent(in), optional :: linear_extrapolate
        integer :: n

        problem = ""
        n = size(x)
        if (n < 2 .or. size(y) /= n) then
            problem = "a curve needs at least 2 points, as many x as y"
            return
        end if
        if (any(x(2:) <= x(:n - 1))) then
            problem = "x must increase strictly from point to point"
            return
        end if
        spline%id = id
        if (present(linear_extrapolate)) spline%linear = linear_extrapolate
        spline%x = x
        spline%y = y
        allocate(spline%b(n - 1, 2), spline%c(n - 1, 2), spline%d(n - 1, 2))
        call akima(x, y, spline%b(:, 1), spline%c(:, 1), spline%d(:, 1))
        call natural_cubic(x, y, spline%b(:, 2), spline%c(:, 2), spline%d(:, 2))
    end subroutine new_spline

    !> Akima's coefficients on each interval.
    pure subroutine akima(x, y, b, c, d)
        real(wp), intent(in) :: x(:), y(:)
        real(wp), intent(out) :: b(:), c(:), d(:)
        real(wp) :: m(-1:size(x) + 1), t(size(x)), w1, w2, h
        integer :: n, i

        n = size(x)
        do i = 1, n - 1
            m(i) = (y(i + 1) - y(i))/(x(i + 1) - x(i))
        end do
        if (n == 2) then
            m(0) = m(1)
            m(-1) = m(1)
            m(n) = m(1)
            m(n + 1) = m(1)
        else
            ! Akima's ends: the chords' slopes continued as a straight line
            m(0) = 2.0_wp*m(1) - m(2)
            m(-1) = 2.0_wp*m(0) - m(1)
            m(n) = 2.0_wp*m(n - 1) - m(n - 2)
            m(n + 1) = 2.0_wp*m(n) - m(n - 1)
        end if
        do i = 1, n
            w1 = abs(m(i + 1) - m(i))
            w2 = abs(m(i - 1) - m(i - 2))
            if (w1 + w2 == 0.0_wp) then
                t(i) = 0.5_wp*(m(i - 1) + m(i))
            else
                t(i) = (w1*m(i - 1) + w2*m(i))/(w1 + w2)
            end if
        end do
        do i = 1, n - 1
            h = x(i + 1) - x(i)
            b(i) = t(i)
            c(i) = (3.0_wp*m(i) - 2.0_wp*t(i) - t(i + 1))/h
            d(i) = (t(i) + t(i + 1) - 2.0_wp*m(i))/h**2
        end do
    end subroutine akima

    !> The natural cubic spline's coefficients (tridiagonal system for the second derivatives,
    !> zero at both ends); two points give their straight line.
    pure subroutine natural_cubic(x, y, b, c, d)
        real(wp), intent(in) :: x(:), y(:)
        real(wp), intent(out) :: b(:), c(:), d(:)
        real(wp) :: sigma(size(x)), diag(size(x)), rhs(size(x)), h(size(x) - 1), f
        integer :: n, i

        n = size(x)
        h = x(2:) - x(:n - 1)
        sigma = 0.0_wp
        if (n > 2) then
            do i = 2, n - 1
                diag(i) = 2.0_wp*(h(i - 1) + h(i))
                rhs(i) = 6.0_wp*((y(i + 1) - y(i))/h(i) - (y(i) - y(i - 1))/h(i - 1))
            end do
            ! forward elimination over the interior points, then back substitution
            do i = 3, n - 1
                f = h(i - 1)/diag(i - 1)
                diag(i) = diag(i) - f*h(i - 1)
                rhs(i) = rhs(i) - f*rhs(i - 1)
            end do
            sigma(n - 1) = rhs(n - 1)/diag(n - 1)
            do i = n - 2, 2, -1
                sigma(i) = (rhs(i) - h(i)*sigma(i + 1))/diag(i)
            end do
        end if
        do i = 1, n - 1
            b(i) = (y(i + 1) - y(i))/h(i) - h(i)*(2.0_wp*sigma(i) + sigma(i + 1))/6.0_wp
            c(i) = 0.5_wp*sigma(i)
            d(i) = (sigma(i + 1) - sigma(i))/(6.0_wp*h(i))
        end do
    end subroutine natural_cubic

    !> y and its first three derivatives in x at x (method_akima or method_cubic).
    pure function spline_derivatives(spline, method, x) result(values)
        type(spline_type), intent(in) :: spline
        integer, intent(in) :: method
        real(wp), intent(in) :: x
        real(wp) :: values(0:3)
        real(wp) :: s, b, c, d, h
        integer :: low, high, mid, n

        ! the interval holding x (the first or last beyond the ends)
        low = 1
        high = size(spline%x) - 1
        do while (low < high)
            mid = (low + high + 1)/2
            if (spline%x(mid) <= x) then
                low = mid
            else
                high = mid - 1
            end if
        end do
        s = x - spline%x(low)
        b = spline%b(low, method)
        c = spline%c(low, method)
        d = spline%d(low, method)
        n = size(spline%x)
        if (spline%linear .and. x < spline%x(1)) then
            values = [spline%y(1) + s*b, b, 0.0_wp, 0.0_wp]
            return
        else if (spline%linear .and. x > spline%x(n)) then
            ! the slope at the last point, of the last interval's cubic
            h = spline%x(n) - spline%x(low)
            b = b + h*(2.0_wp*c + 3.0_wp*h*d)
            values = [spline%y(n) + (x - spline%x(n))*b, b, 0.0_wp, 0.0_wp]
            return
        end if
        values(0) = spline%y(low) + s*(b + s*(c + s*d))
        values(1) = b + s*(2.0_wp*c + 3.0_wp*s*d)
        values(2) = 2.0_wp*c + 6.0_wp*s*d
        values(3) = 6.0_wp*d
    end function spline_derivatives

    !> The curve's corners [the unit of x], ascending: its interior points, and both ends as
    !> well when it extrapolates along its end tangents (the module's comment).
    pure function spline_corners(spline) result(corners)
        type(spline_type), intent(in) :: spline
        real(wp), allocatable :: corners(:)
        integer :: first, last

        call corner_range(spline, first, last)
        corners = spline%x(first:last)
    end function spline_corners

    !> A switch function of x that is zero at every corner of the curve (spline_corners) and
    !> changes sign there, and nowhere else: with c_1 < ... < c_m the corners, c_1 - x below the
    !> first, (-1)^k (x - c_k)(c_(k+1) - x)/(c_(k+1) - c_k) between c_k and c_(k+1), and
    !> (-1)^m (x - c_m) beyond the last [the unit of x]; continuous, of slope +-1 at each corner.
    !> 0 for a curve without corners. Allocates nothing (an event function of the integrators).
    pure real(wp) function spline_corner_switch(spline, x) result(g)
        type(spline_type), intent(in) :: spline
        real(wp), intent(in) :: x
        integer :: first, last, low, high, mid, k

        g = 0.0_wp
        call corner_range(spline, first, last)
        if (last < first) return
        if (x < spline%x(first)) then
            g = spline%x(first) - x
            return
        end if
        ! the last corner at or below x
        low = first
        high = last
        do while (low < high)
            mid = (low + high + 1)/2
            if (spline%x(mid) <= x) then
                low = mid
            else
                high = mid - 1
            end if
        end do
        k = low - first + 1
        if (low == last) then
            g = x - spline%x(last)
        else
            g = (x - spline%x(low))*(spline%x(low + 1) - x)/(spline%x(low + 1) - spline%x(low))
        end if
        if (mod(k, 2) == 1) g = -g
    end function spline_corner_switch

    !> The points of the curve that are corners: x(first:last) (empty when last < first).
    pure subroutine corner_range(spline, first, last)
        type(spline_type), intent(in) :: spline
        integer, intent(out) :: first, last

        first = 2
        last = size(spline%x) - 1
        if (spline%linear) then
            first = 1
            last = size(spline%x)
        end if
    end subroutine corner_range

end module rollcon_spline
