! SPDX-License-Identifier: MIT
!> The time part of a MOTION (docs/datasets.md, "MOTION"; docs/design.md §4): the
!> displacement h(t) it prescribes for one coordinate s(q) of the model, and h's first two
!> time derivatives, exactly. A MOTION is a position UCON with an explicit time part,
!>
!>     F(q, t) = s(q) - h(t)        (an angle: brought into (-pi, pi])
!>
!> whose geometric part s(q) a generated routine serves (rollcon_motion_geometry) and whose
!> time part is here: dF/dt = -h'(t), d2F/dt2 = -h''(t), d2F/dt dq = 0. Its FUNCTION f(t),
!> an expression of TIME alone in the dataset's units, is
!>
!> - DISPLACEMENT: h = f, h' = f', h'' = f'' (f' and f'' by forward-mode differentiation of the
!>   expression in jets of TIME, rollcon_expression_jet: no finite differences);
!> - VELOCITY: h = ICDISP + integral of f from 0 to t, h' = f, h'' = f';
!> - ACCELERATION: h = ICDISP + ICVEL t + integral of (t - tau) f(tau) from 0 to t,
!>   h' = ICVEL + integral of f, h'' = f,
!>
!> as ADAMS integrates a velocity or an acceleration to the displacement it imposes, with the
!> initial conditions as the constants of integration. The integrals are Gauss-Legendre
!> quadratures of f (8 points), adaptive (a panel is halved until its two halves agree with
!> it to quadrature_tolerance relative to the integrals of |f| and |tau f|), with the
!> expression's switching times (an IF, STEP or HAVSIN on TIME - c, ...: rollcon_expression's
!> switching_times) as panel ends; over a run they are kept at anchor_count + 1 equally spaced
!> times (prepare_motion), so that each evaluation integrates from the anchor before it only.
!>
!> A MOTION whose FUNCTION is USER(r1, ...) (motion_type's user) is served by a MOTSUB with
!> ADAMS's IORD, the order of the TIME derivative of f asked for: a DISPLACEMENT's h, h', h''
!> are its values at IORD = 0, 1, 2, which the caller obtains from the routine (rollcon_user_
!> forces' call_user_motion) and converts here (motion_user_jet); a VELOCITY's f and f' are
!> its values at IORD = 0, 1 and an ACCELERATION's f its value at IORD = 0 (ADAMS never asks
!> more of them), integrated here as an expression's f is, by the same quadrature at the same
!> points (motion_displacement: the MOTSUB called at each), so that a MOTSUB and the
!> expression it computes give the same h to round-off. A call that fails leaves its error
!> for take_motion_error. A MOTSUB has no corners (the routine is opaque: where it switches
!> is not known).
module rollcon_motion
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_expression, only : expression_type, switching_times, evaluate_expression
    use rollcon_jet, only : jet_type, jet_variable
    use rollcon_expression_jet, only : evaluate_expression_jet
    use rollcon_error, only : error_type
    use rollcon_user_forces, only : call_user_motion
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: motion_type, motion_displacement, motion_residual, motion_corners
    public :: prepare_motion, motion_integrals, motion_user_jet, displacement_residual
    public :: motion_form_displacement, motion_form_velocity, motion_form_acceleration
    public :: take_motion_error, motion_highest_order

    !> What FUNCTION gives: the displacement, its rate, or its second derivative
    integer, parameter :: motion_form_displacement = 1, motion_form_velocity = 2, &
        & motion_form_acceleration = 3
    !> Anchors of the integrals over a run: its span cut into this many equal panels
    integer, parameter :: anchor_count = 1024
    !> A panel's quadrature is accepted when its two halves agree with it to this, relative to
    !> the integrals of |f| and |tau f| over it (and the halves are taken otherwise), down to
    !> max_depth halvings: 1e-13 is 450 roundings, above what the 16 terms' sums round to
    !> (a tighter bound is never met, and every panel would be halved to max_depth); a
    !> panel's error shrinks 2^16 times a halving where f is smooth, so only the panels
    !> at a kink of f (an ABS, MIN or MAX of TIME) go deep, one path of them
    real(wp), parameter :: quadrature_tolerance = 1.0e-13_wp
    integer, parameter :: max_depth = 40
    !> Gauss-Legendre's 8 points on [-1, 1] (the positive half) and weights
    real(wp), parameter :: gauss_nodes(4) = [0.18343464249564980494_wp, &
        & 0.52553240991632898582_wp, 0.79666647741362673959_wp, 0.96028985649753623168_wp]
    real(wp), parameter :: gauss_weights(4) = [0.36268378337836198297_wp, &
        & 0.31370664587788728734_wp, 0.22238103445337447054_wp, 0.10122853629037625915_wp]

    !> One MOTION's time part
    type :: motion_type
        !> MOTION/id, and the statement for messages ("data/x.adm:12: MOTION/3")
        integer :: id = 0
        character(len=:), allocatable :: name
        !> FUNCTION, an expression of TIME alone, in the dataset's units (unused when user)
        type(expression_type) :: function
        !> FUNCTION=USER(r1, ...): a DISPLACEMENT served by the MOTSUB of MOTION/id
        logical :: user = .false.
        !> motion_form_displacement, motion_form_velocity or motion_form_acceleration
        integer :: form = motion_form_displacement
        !> The coordinate is an angle: F is brought into (-pi, pi]
        logical :: rotational = .false.
        !> The size of the function's time unit [s] and of its displacement's unit [m, or 1 for
        !> an angle in radians]: f's value is in that unit per time unit to the power form - 1
        real(wp) :: time_unit = 1.0_wp, value_unit = 1.0_wp
        !> ICDISP [m or rad] and ICVEL [m/s or rad/s], SI (VELOCITY and ACCELERATION)
        real(wp) :: initial_displacement = 0.0_wp, initial_velocity = 0.0_wp
        !> Switching times of the function [s], ascending (motion_corners)
        real(wp), allocatable :: corners(:)
        !> The anchors: integrals(1, k) of f and integrals(2, k) of tau f from 0 to k panel [SI]
        !> (k = 0 .. anchor_count); panel 0 before prepare_motion: none kept
        real(wp) :: panel = 0.0_wp
        real(wp), allocatable :: integrals(:, :)
    end type motion_type

    !> The first failure of a MOTSUB call made here (motion_displacement, prepare_motion), not
    !> yet taken (take_motion_error)
    type(error_type), allocatable, save :: pending

contains

    !> Move the first failure of a MOTSUB called by motion_displacement, motion_residual or
    !> prepare_motion, if any, to the caller.
    subroutine take_motion_error(error)
        type(error_type), allocatable, intent(out) :: error

        if (allocated(pending)) call move_alloc(pending, error)
    end subroutine take_motion_error

    !> The highest IORD a MOTSUB serving a MOTION of this form is called with (ADAMS's): 2 for
    !> a DISPLACEMENT, 1 for a VELOCITY, 0 for an ACCELERATION.
    pure integer function motion_highest_order(form) result(order)
        integer, intent(in) :: form

        order = 3 - form
    end function motion_highest_order

    !> The MOTSUB of a VELOCITY or ACCELERATION MOTION at time [s]: f and its TIME derivatives
    !> of orders 0 .. highest (the rest NaN), in the dataset's units (value_unit per
    !> time_unit^(form - 1 + iord)); a failure kept for take_motion_error (its values NaN).
    function user_function(motion, time, highest) result(f)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: time
        integer, intent(in) :: highest
        real(wp) :: f(0:2)
        real(wp) :: none(0)
        type(error_type), allocatable :: error
        integer :: k

        call call_user_motion(motion%id, time, none, none, [(k, k = 0, highest)], f, error)
        if (allocated(error)) then
            f = ieee_value(0.0_wp, ieee_quiet_nan)
            if (.not. allocated(pending)) call move_alloc(error, pending)
        end if
    end function user_function

    !> The function's value and first two derivatives at time t [s], SI: [m, m/s, m/s^2] per
    !> unit of form (a displacement's; a velocity's ...; radians for an angle).
    function function_jet(motion, time) result(jet)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: time
        real(wp) :: jet(0:2)
        real(wp) :: scale
        type(jet_type) :: f, none(0)

        if (motion%user) then
            ! the MOTSUB's f and the derivatives ADAMS asks of it (the others unused here)
            jet = user_function(motion, time, motion_highest_order(motion%form))
            jet(motion_highest_order(motion%form) + 1:) = 0.0_wp
        else
            ! TIME the one variable, to second order
            f = evaluate_expression_jet(motion%function, jet_variable(time/motion%time_unit, &
                & 1, 1, .true.), none)
            jet = [f%v, 0.0_wp, 0.0_wp]
            ! a function that does not change with time is a constant jet: no partials held
            if (f%active) then
                jet(1) = f%g(1)
                if (allocated(f%h)) jet(2) = f%h(1, 1)
            end if
        end if
        ! f is in value_unit / time_unit^(form - 1); each derivative divides by time_unit
        scale = motion%value_unit/motion%time_unit**(motion%form - 1)
        jet = scale*jet*[1.0_wp, 1.0_wp/motion%time_unit, 1.0_wp/motion%time_unit**2]
    end function function_jet

    !> h, h', h'' [SI] from a MOTSUB's values at IORD = 0, 1, 2 (values(iord), in the dataset's
    !> units: value_unit per time_unit^iord), as function_jet scales an expression's.
    pure function motion_user_jet(motion, values) result(h)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: values(0:2)
        real(wp) :: h(0:2)

        h = motion%value_unit*values*[1.0_wp, 1.0_wp/motion%time_unit, &
            & 1.0_wp/motion%time_unit**2]
    end function motion_user_jet

    !> h(t), h'(t), h''(t): the displacement the MOTION imposes at time t [s] and its first
    !> two derivatives [m, m/s, m/s^2; rad, rad/s, rad/s^2].
    function motion_displacement(motion, time) result(h)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: time
        real(wp) :: h(0:2)
        real(wp) :: f(0:2), integrals(2)

        f = function_jet(motion, time)
        select case (motion%form)
        case (motion_form_velocity)
            integrals = motion_integrals(motion, time)
            h = [motion%initial_displacement + integrals(1), f(0), f(1)]
        case (motion_form_acceleration)
            integrals = motion_integrals(motion, time)
            h = [motion%initial_displacement + motion%initial_velocity*time &
                & + time*integrals(1) - integrals(2), motion%initial_velocity + integrals(1), &
                & f(0)]
        case default
            h = f
        end select
    end function motion_displacement

    !> F = s - h(t) from the coordinate s the geometric routine measured at time t [s] (an
    !> angle's difference brought into (-pi, pi]).
    real(wp) function motion_residual(motion, time, coordinate) result(residual)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: time
        !> s(q) [m or rad]
        real(wp), intent(in) :: coordinate
        real(wp) :: h(0:2)

        h = motion_displacement(motion, time)
        residual = displacement_residual(motion, h(0), coordinate)
    end function motion_residual

    !> F = s - h from the coordinate s [m or rad] and the displacement h the MOTION imposes (an
    !> angle's difference brought into (-pi, pi]).
    pure real(wp) function displacement_residual(motion, displacement, coordinate) &
            & result(residual)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: displacement, coordinate

        residual = coordinate - displacement
        if (motion%rotational) residual = residual - 2.0_wp*pi*anint(residual/(2.0_wp*pi))
    end function displacement_residual

    !> The function's switching times [s], ascending and each once (rollcon_expression's
    !> switching_times in the function's time unit, converted): the corners of the motion,
    !> where its displacement or a derivative of it may jump.
    pure function motion_corners(motion) result(times)
        type(motion_type), intent(in) :: motion
        real(wp), allocatable :: times(:)
        real(wp), allocatable :: found(:)
        real(wp) :: t
        integer :: k, j

        allocate(times(0))
        ! a MOTSUB is opaque: its switching times are not known
        if (motion%user) return
        found = switching_times(motion%function)*motion%time_unit
        do k = 1, size(found)
            if (any(times == found(k))) cycle
            times = [times, found(k)]
        end do
        ! ascending (a handful of times: insertion)
        do k = 2, size(times)
            t = times(k)
            j = k - 1
            do while (j >= 1)
                if (times(j) <= t) exit
                times(j + 1) = times(j)
                j = j - 1
            end do
            times(j + 1) = t
        end do
    end function motion_corners

    !> Before a run to `horizon` [s]: the corners, and for VELOCITY and ACCELERATION the
    !> anchors of the integrals over [0, horizon].
    subroutine prepare_motion(motion, horizon)
        type(motion_type), intent(inout) :: motion
        real(wp), intent(in) :: horizon
        integer :: k

        motion%corners = motion_corners(motion)
        motion%panel = 0.0_wp
        if (allocated(motion%integrals)) deallocate(motion%integrals)
        if (motion%form == motion_form_displacement .or. .not. horizon > 0.0_wp) return
        allocate(motion%integrals(2, 0:anchor_count))
        motion%integrals(:, 0) = 0.0_wp
        ! the anchors at k panel exactly, where motion_integrals starts from them
        motion%panel = horizon/anchor_count
        do k = 1, anchor_count
            motion%integrals(:, k) = motion%integrals(:, k - 1) + integral(motion, &
                & real(k - 1, wp)*motion%panel, real(k, wp)*motion%panel)
        end do
    end subroutine prepare_motion

    !> The integrals of f and of tau f from 0 to t [s] (SI): from the anchor before t when
    !> prepare_motion kept them, else from 0.
    function motion_integrals(motion, time) result(values)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: time
        real(wp) :: values(2)
        integer :: k

        values = 0.0_wp
        k = 0
        if (motion%panel > 0.0_wp .and. allocated(motion%integrals)) then
            k = max(0, min(int(time/motion%panel), ubound(motion%integrals, 2)))
            values = motion%integrals(:, k)
        end if
        values = values + integral(motion, real(k, wp)*motion%panel, time)
    end function motion_integrals

    !> The integrals of f and tau f from a to b [s], panels ending at the corners between them.
    function integral(motion, a, b) result(values)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: a, b
        real(wp) :: values(2)
        real(wp) :: start, finish
        integer :: k

        values = 0.0_wp
        if (.not. abs(b - a) > 0.0_wp) return
        start = min(a, b)
        finish = max(a, b)
        if (allocated(motion%corners)) then
            do k = 1, size(motion%corners)
                if (motion%corners(k) <= start .or. motion%corners(k) >= finish) cycle
                values = values + adaptive(motion, start, motion%corners(k))
                start = motion%corners(k)
            end do
        end if
        values = values + adaptive(motion, start, finish)
        if (b < a) values = -values
    end function integral

    !> Adaptive Gauss-Legendre on [a, b]: a panel is kept when its two halves agree with it,
    !> else halved (an explicit stack of panels, depth at most max_depth).
    function adaptive(motion, a, b) result(values)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: a, b
        real(wp) :: values(2)
        real(wp) :: lower(max_depth + 1), upper(max_depth + 1), whole(4, max_depth + 1)
        real(wp) :: left(4), right(4), middle
        integer :: depth(max_depth + 1), top

        values = 0.0_wp
        top = 1
        lower(1) = a
        upper(1) = b
        whole(:, 1) = gauss(motion, a, b)
        depth(1) = 0
        do while (top > 0)
            middle = 0.5_wp*(lower(top) + upper(top))
            left = gauss(motion, lower(top), middle)
            right = gauss(motion, middle, upper(top))
            if (depth(top) >= max_depth .or. all(abs(left(1:2) + right(1:2) &
                & - whole(1:2, top)) <= quadrature_tolerance*(left(3:4) + right(3:4)))) then
                values = values + left(1:2) + right(1:2)
                top = top - 1
                cycle
            end if
            ! the right half waits; the left is worked on first
            lower(top + 1) = lower(top)
            upper(top + 1) = middle
            whole(:, top + 1) = left
            depth(top + 1) = depth(top) + 1
            lower(top) = middle
            whole(:, top) = right
            depth(top) = depth(top) + 1
            top = top + 1
        end do
    end function adaptive

    !> Gauss-Legendre (8 points) on [a, b] of f, tau f and |f|.
    function gauss(motion, a, b) result(values)
        type(motion_type), intent(in) :: motion
        real(wp), intent(in) :: a, b
        real(wp) :: values(4)
        real(wp) :: centre, half, tau, f, none(0), sampled(0:2)
        integer :: k, side

        values = 0.0_wp
        centre = 0.5_wp*(a + b)
        half = 0.5_wp*(b - a)
        do k = 1, size(gauss_nodes)
            do side = -1, 1, 2
                tau = centre + side*half*gauss_nodes(k)
                ! the value alone (in SI: value_unit per time_unit^(form - 1))
                if (motion%user) then
                    sampled = user_function(motion, tau, 0)
                    f = sampled(0)*motion%value_unit/motion%time_unit**(motion%form - 1)
                else
                    f = evaluate_expression(motion%function, tau/motion%time_unit, none) &
                        & *motion%value_unit/motion%time_unit**(motion%form - 1)
                end if
                values = values + gauss_weights(k)*[f, tau*f, abs(f), abs(tau*f)]
            end do
        end do
        values = half*values
    end function gauss

end module rollcon_motion
