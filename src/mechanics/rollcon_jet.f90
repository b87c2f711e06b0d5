! SPDX-License-Identifier: MIT
!> Jets: a number with its exact partial derivatives in n independent variables, to first or
!> second order (forward-mode automatic differentiation; docs/datasets-model.md, "Exact
!> partials of an expression").
!>
!> A jet holds its value v, its gradient g (dv/dx_i, size n) and, at second order, its Hessian
!> h (d2v/dx_i dx_j, n x n, symmetric). A constant holds none of them (`active` false): it
!> costs a real number's work, so a function written once in jets serves both a value alone
!> (every argument constant) and its partials. Each operation applies the chain rule to its
!> arguments' jets: for c = f(a, b), g_c = f_a g_a + f_b g_b and
!> h_c = f_a h_a + f_b h_b + f_aa g_a g_a^T + f_ab (g_a g_b^T + g_b g_a^T) + f_bb g_b g_b^T,
!> so the result's partials are exact to rounding wherever f is twice differentiable. At a
!> corner (ABS at 0, MIN of equal arguments, a branch of IF) the partials are those of the
!> branch the value is taken from. Jets of one computation share n and their order.
module rollcon_jet
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: jet_type, jet_variable, jet_constant, jet_chain, jet_value
    public :: operator(+), operator(-), operator(*), operator(/), operator(**)
    public :: sin, cos, tan, asin, acos, atan, atan2, exp, log, log10, sqrt, abs, sinh, cosh, &
        & tanh
    public :: jet_dot, jet_cross, jet_norm, jet_times

    !> A number with its partials
    type :: jet_type
        !> The value
        real(wp) :: v = 0.0_wp
        !> First partials dv/dx_i (size n; unallocated for a constant)
        real(wp), allocatable :: g(:)
        !> Second partials d2v/dx_i dx_j (n x n; allocated at second order only)
        real(wp), allocatable :: h(:, :)
        !> False for a constant (g and h then unallocated: zeros)
        logical :: active = .false.
    end type jet_type

    interface operator(+)
        module procedure add_jj, add_jr, add_rj
    end interface
    interface operator(-)
        module procedure subtract_jj, subtract_jr, subtract_rj, negate
    end interface
    interface operator(*)
        module procedure multiply_jj, multiply_jr, multiply_rj
    end interface
    interface operator(/)
        module procedure divide_jj, divide_jr, divide_rj
    end interface
    interface operator(**)
        module procedure power_jr, power_ji, power_jj
    end interface
    interface sin
        module procedure jet_sin
    end interface
    interface cos
        module procedure jet_cos
    end interface
    interface tan
        module procedure jet_tan
    end interface
    interface asin
        module procedure jet_asin
    end interface
    interface acos
        module procedure jet_acos
    end interface
    interface atan
        module procedure jet_atan
    end interface
    interface atan2
        module procedure jet_atan2
    end interface
    interface exp
        module procedure jet_exp
    end interface
    interface log
        module procedure jet_log
    end interface
    interface log10
        module procedure jet_log10
    end interface
    interface sqrt
        module procedure jet_sqrt
    end interface
    interface abs
        module procedure jet_abs
    end interface
    interface sinh
        module procedure jet_sinh
    end interface
    interface cosh
        module procedure jet_cosh
    end interface
    interface tanh
        module procedure jet_tanh
    end interface

contains

    !> Independent variable number `index` of n, with value `value`; second: keep second
    !> partials.
    pure function jet_variable(value, index, n, second) result(c)
        real(wp), intent(in) :: value
        integer, intent(in) :: index, n
        logical, intent(in) :: second
        type(jet_type) :: c

        c%v = value
        c%active = .true.
        allocate(c%g(n), source=0.0_wp)
        c%g(index) = 1.0_wp
        if (second) allocate(c%h(n, n), source=0.0_wp)
    end function jet_variable

    !> A constant.
    elemental function jet_constant(value) result(c)
        real(wp), intent(in) :: value
        type(jet_type) :: c

        c%v = value
    end function jet_constant

    !> The value of a jet.
    elemental real(wp) function jet_value(a)
        type(jet_type), intent(in) :: a

        jet_value = a%v
    end function jet_value

    !> f(args) from its value and its partials with respect to its arguments: d1(k) = df/da_k,
    !> d2(k, l) = d2f/da_k da_l (symmetric; read only at second order). For a function of
    !> several arguments whose own partials are known (the chain rule over them).
    pure function jet_chain(args, value, d1, d2) result(c)
        type(jet_type), intent(in) :: args(:)
        real(wp), intent(in) :: value, d1(:), d2(:, :)
        type(jet_type) :: c
        integer :: k, l, first

        c%v = value
        first = 0
        do k = 1, size(args)
            if (args(k)%active) then
                first = k
                exit
            end if
        end do
        if (first == 0) return
        c%active = .true.
        allocate(c%g(size(args(first)%g)), source=0.0_wp)
        if (allocated(args(first)%h)) allocate(c%h(size(c%g), size(c%g)), source=0.0_wp)
        do k = first, size(args)
            if (.not. args(k)%active) cycle
            if (d1(k) /= 0.0_wp) c%g = c%g + d1(k)*args(k)%g
            if (.not. allocated(c%h)) cycle
            if (d1(k) /= 0.0_wp) c%h = c%h + d1(k)*args(k)%h
            do l = first, size(args)
                if (.not. args(l)%active) cycle
                if (d2(k, l) /= 0.0_wp) call add_outer(c%h, d2(k, l), args(k)%g, args(l)%g)
            end do
        end do
    end function jet_chain

    !> h = h + f a b^T.
    pure subroutine add_outer(h, f, a, b)
        real(wp), intent(inout) :: h(:, :)
        real(wp), intent(in) :: f, a(:), b(:)
        integer :: j

        do j = 1, size(b)
            if (b(j) /= 0.0_wp) h(:, j) = h(:, j) + (f*b(j))*a
        end do
    end subroutine add_outer

    !> c = f(a) with f' = f1, f'' = f2.
    elemental function unary(a, f, f1, f2) result(c)
        type(jet_type), intent(in) :: a
        real(wp), intent(in) :: f, f1, f2
        type(jet_type) :: c

        c%v = f
        if (.not. a%active) return
        c%active = .true.
        c%g = f1*a%g
        if (allocated(a%h)) then
            c%h = f1*a%h
            if (f2 /= 0.0_wp) call add_outer(c%h, f2, a%g, a%g)
        end if
    end function unary

    !> c = f(a, b) with its first partials fa, fb and second faa, fab, fbb.
    elemental function binary(a, b, f, fa, fb, faa, fab, fbb) result(c)
        type(jet_type), intent(in) :: a, b
        real(wp), intent(in) :: f, fa, fb, faa, fab, fbb
        type(jet_type) :: c

        if (.not. b%active) then
            c = unary(a, f, fa, faa)
            return
        end if
        if (.not. a%active) then
            c = unary(b, f, fb, fbb)
            return
        end if
        c%v = f
        c%active = .true.
        c%g = fa*a%g + fb*b%g
        if (allocated(a%h)) then
            c%h = fa*a%h + fb*b%h
            if (faa /= 0.0_wp) call add_outer(c%h, faa, a%g, a%g)
            if (fab /= 0.0_wp) then
                call add_outer(c%h, fab, a%g, b%g)
                call add_outer(c%h, fab, b%g, a%g)
            end if
            if (fbb /= 0.0_wp) call add_outer(c%h, fbb, b%g, b%g)
        end if
    end function binary

    elemental function add_jj(a, b) result(c)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: c

        c = binary(a, b, a%v + b%v, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)
    end function add_jj

    elemental function add_jr(a, b) result(c)
        type(jet_type), intent(in) :: a
        real(wp), intent(in) :: b
        type(jet_type) :: c

        c = a
        c%v = a%v + b
    end function add_jr

    elemental function add_rj(a, b) result(c)
        real(wp), intent(in) :: a
        type(jet_type), intent(in) :: b
        type(jet_type) :: c

        c = b
        c%v = a + b%v
    end function add_rj

    elemental function subtract_jj(a, b) result(c)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: c

        c = binary(a, b, a%v - b%v, 1.0_wp, -1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp)
    end function subtract_jj

    elemental function subtract_jr(a, b) result(c)
        type(jet_type), intent(in) :: a
        real(wp), intent(in) :: b
        type(jet_type) :: c

        c = a
        c%v = a%v - b
    end function subtract_jr

    elemental function subtract_rj(a, b) result(c)
        real(wp), intent(in) :: a
        type(jet_type), intent(in) :: b
        type(jet_type) :: c

        c = unary(b, a - b%v, -1.0_wp, 0.0_wp)
    end function subtract_rj

    elemental function negate(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c

        c = unary(a, -a%v, -1.0_wp, 0.0_wp)
    end function negate

    elemental function multiply_jj(a, b) result(c)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: c

        c = binary(a, b, a%v*b%v, b%v, a%v, 0.0_wp, 1.0_wp, 0.0_wp)
    end function multiply_jj

    elemental function multiply_jr(a, b) result(c)
        type(jet_type), intent(in) :: a
        real(wp), intent(in) :: b
        type(jet_type) :: c

        c = unary(a, a%v*b, b, 0.0_wp)
    end function multiply_jr

    elemental function multiply_rj(a, b) result(c)
        real(wp), intent(in) :: a
        type(jet_type), intent(in) :: b
        type(jet_type) :: c

        c = unary(b, a*b%v, a, 0.0_wp)
    end function multiply_rj

    elemental function divide_jj(a, b) result(c)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: c
        real(wp) :: r

        r = 1.0_wp/b%v
        c = binary(a, b, a%v*r, r, -a%v*r*r, 0.0_wp, -r*r, 2.0_wp*a%v*r*r*r)
    end function divide_jj

    elemental function divide_jr(a, b) result(c)
        type(jet_type), intent(in) :: a
        real(wp), intent(in) :: b
        type(jet_type) :: c

        c = unary(a, a%v/b, 1.0_wp/b, 0.0_wp)
    end function divide_jr

    elemental function divide_rj(a, b) result(c)
        real(wp), intent(in) :: a
        type(jet_type), intent(in) :: b
        type(jet_type) :: c
        real(wp) :: r

        r = 1.0_wp/b%v
        c = unary(b, a*r, -a*r*r, 2.0_wp*a*r*r*r)
    end function divide_rj

    !> a**p for a real exponent (a > 0, or a whole p).
    elemental function power_jr(a, p) result(c)
        type(jet_type), intent(in) :: a
        real(wp), intent(in) :: p
        type(jet_type) :: c

        if (p == aint(p) .and. abs(p) < 1.0e9_wp) then
            c = power_ji(a, nint(p))
            return
        end if
        c = unary(a, a%v**p, p*a%v**(p - 1.0_wp), p*(p - 1.0_wp)*a%v**(p - 2.0_wp))
    end function power_jr

    !> a**k for a whole k (any sign of a).
    elemental function power_ji(a, k) result(c)
        type(jet_type), intent(in) :: a
        integer, intent(in) :: k
        type(jet_type) :: c
        real(wp) :: f1, f2

        select case (k)
        case (0)
            c = jet_constant(1.0_wp)
            return
        case (1)
            c = a
            return
        case (2)
            f1 = 2.0_wp*a%v
            f2 = 2.0_wp
        case default
            f1 = k*a%v**(k - 1)
            f2 = k*(k - 1)*a%v**(k - 2)
        end select
        c = unary(a, a%v**k, f1, f2)
    end function power_ji

    !> a**b with both jets: exp(b log a) for a > 0; a whole constant b as power_ji.
    elemental function power_jj(a, b) result(c)
        type(jet_type), intent(in) :: a, b
        type(jet_type) :: c
        real(wp) :: f, la

        if (.not. b%active) then
            c = power_jr(a, b%v)
            return
        end if
        f = a%v**b%v
        la = log(a%v)
        c = binary(a, b, f, b%v*f/a%v, f*la, b%v*(b%v - 1.0_wp)*f/a%v**2, &
            & f*(1.0_wp + b%v*la)/a%v, f*la*la)
    end function power_jj

    elemental function jet_sin(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: s

        s = sin(a%v)
        c = unary(a, s, cos(a%v), -s)
    end function jet_sin

    elemental function jet_cos(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: s

        s = cos(a%v)
        c = unary(a, s, -sin(a%v), -s)
    end function jet_cos

    elemental function jet_tan(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: t, d

        t = tan(a%v)
        d = 1.0_wp + t*t
        c = unary(a, t, d, 2.0_wp*t*d)
    end function jet_tan

    elemental function jet_asin(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: r

        r = 1.0_wp/sqrt(1.0_wp - a%v*a%v)
        c = unary(a, asin(a%v), r, a%v*r*r*r)
    end function jet_asin

    elemental function jet_acos(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: r

        r = 1.0_wp/sqrt(1.0_wp - a%v*a%v)
        c = unary(a, acos(a%v), -r, -a%v*r*r*r)
    end function jet_acos

    elemental function jet_atan(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: r

        r = 1.0_wp/(1.0_wp + a%v*a%v)
        c = unary(a, atan(a%v), r, -2.0_wp*a%v*r*r)
    end function jet_atan

    !> atan2(y, x): the angle of (x, y); its partials are those of atan(y/x) everywhere but
    !> the origin.
    elemental function jet_atan2(y, x) result(c)
        type(jet_type), intent(in) :: y, x
        type(jet_type) :: c
        real(wp) :: r

        r = 1.0_wp/(x%v*x%v + y%v*y%v)
        c = binary(y, x, atan2(y%v, x%v), x%v*r, -y%v*r, -2.0_wp*x%v*y%v*r*r, &
            & (y%v*y%v - x%v*x%v)*r*r, 2.0_wp*x%v*y%v*r*r)
    end function jet_atan2

    elemental function jet_exp(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: e

        e = exp(a%v)
        c = unary(a, e, e, e)
    end function jet_exp

    elemental function jet_log(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c

        c = unary(a, log(a%v), 1.0_wp/a%v, -1.0_wp/a%v**2)
    end function jet_log

    elemental function jet_log10(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: m

        m = 1.0_wp/log(10.0_wp)
        c = unary(a, log10(a%v), m/a%v, -m/a%v**2)
    end function jet_log10

    elemental function jet_sqrt(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: s

        s = sqrt(a%v)
        c = unary(a, s, 0.5_wp/s, -0.25_wp/(s*a%v))
    end function jet_sqrt

    !> |a|; at 0 the partials of a (the branch a >= 0).
    elemental function jet_abs(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c

        if (a%v >= 0.0_wp) then
            c = a
        else
            c = negate(a)
        end if
    end function jet_abs

    elemental function jet_sinh(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: s

        s = sinh(a%v)
        c = unary(a, s, cosh(a%v), s)
    end function jet_sinh

    elemental function jet_cosh(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: s

        s = cosh(a%v)
        c = unary(a, s, sinh(a%v), s)
    end function jet_cosh

    elemental function jet_tanh(a) result(c)
        type(jet_type), intent(in) :: a
        type(jet_type) :: c
        real(wp) :: t, d

        t = tanh(a%v)
        d = 1.0_wp - t*t
        c = unary(a, t, d, -2.0_wp*t*d)
    end function jet_tanh

    !> a . b of 3-vectors.
    pure function jet_dot(a, b) result(c)
        type(jet_type), intent(in) :: a(3), b(3)
        type(jet_type) :: c

        c = a(1)*b(1) + a(2)*b(2) + a(3)*b(3)
    end function jet_dot

    !> a x b of 3-vectors.
    pure function jet_cross(a, b) result(c)
        type(jet_type), intent(in) :: a(3), b(3)
        type(jet_type) :: c(3)

        c(1) = a(2)*b(3) - a(3)*b(2)
        c(2) = a(3)*b(1) - a(1)*b(3)
        c(3) = a(1)*b(2) - a(2)*b(1)
    end function jet_cross

    !> |a| of a 3-vector.
    pure function jet_norm(a) result(c)
        type(jet_type), intent(in) :: a(3)
        type(jet_type) :: c

        c = sqrt(jet_dot(a, a))
    end function jet_norm

    !> m v for a 3 x 3 matrix of jets and a constant 3-vector.
    pure function jet_times(m, v) result(c)
        type(jet_type), intent(in) :: m(3, 3)
        real(wp), intent(in) :: v(3)
        type(jet_type) :: c(3)
        integer :: i

        do i = 1, 3
            c(i) = m(i, 1)*v(1) + m(i, 2)*v(2) + m(i, 3)*v(3)
        end do
    end function jet_times

end module rollcon_jet
