! SPDX-License-Identifier: MIT
!> ADAMS's function library in expressions (suite expression-functions): every function of
!> numbers and every measure of markers against a value worked by hand; the curves (AKISPL,
!> CUBSPL) against hand-fitted cubics; the whole turns of AX, AY, AZ; the switching times of
!> the functions with corners, and their switch functions where they switch on the state; and
!> the exact partials: every expression's jet (its value,
!> gradient and Hessian over two parts' q, u and the time) against the value path and against
!> the values SymPy derives from the same definitions (ucon/expression_partials.py).
module test_expression_functions
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix
    use rollcon_jet, only : jet_type, jet_variable
    use rollcon_spline, only : spline_type, new_spline
    use rollcon_expression, only : expression_type, evaluate_expression, switching_times, &
        & switch_kinds, switch_count, switch_values, switch_none, switch_timed, switch_watched
    use rollcon_expression_jet, only : evaluate_expression_jet
    use rollcon_marker, only : marker_type
    use rollcon_measures, only : expression_input_values, expression_input_jets, &
        & state_jets_type, new_state_jets
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_testing, only : unittest_type, new_unittest, check
    use expression_reference, only : reference_count, reference_texts, reference_states, &
        & reference_values, reference_gradients, reference_products, reference_probes, &
        & reference_markers, reference_marker_parts, reference_marker_points, &
        & reference_marker_angles
    implicit none
    private

    public :: collect_expression_functions

    !> Hand values are written to 16 digits or are exact: a few ulp of the largest term
    real(wp), parameter :: tol = 1.0e-14_wp
    !> A jet's value and the value path's are the same definitions computed in a different
    !> order (a measure's dot products, the jet's chain of products): a few hundred ulp of the
    !> terms at most
    real(wp), parameter :: tol_paths = 1.0e-12_wp
    !> Jets against SymPy's 30-digit partials: each partial is a sum of products of up to some
    !> 30 rounded factors, over terms of size up to 1e3 (POLY, IMPACT's stiffness): 1e-11
    !> relative to the largest of the partials and 1; a wrong term is off by its own size
    real(wp), parameter :: tol_partials = 1.0e-11_wp

contains

    subroutine collect_expression_functions(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("functions-against-hand-values", test_functions), &
            & new_unittest("measures-against-hand-values", test_measures), &
            & new_unittest("angles-of-ground-markers", test_angles), &
            & new_unittest("whole-turns-counted", test_turns), &
            & new_unittest("curves-against-hand-fits", test_curves), &
            & new_unittest("switching-times-of-corners", test_corners), &
            & new_unittest("switches-on-the-state", test_state_switches), &
            & new_unittest("jets-equal-the-value-path", test_paths), &
            & new_unittest("partials-against-sympy", test_partials)]
    end subroutine collect_expression_functions

    !> The value of text (no measures) at time.
    subroutine value_of(text, time, value, error)
        character(len=*), intent(in) :: text
        real(wp), intent(in) :: time
        real(wp), intent(out) :: value
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression

        value = 0.0_wp
        call compile_expression(text, "test.adm:1: SFORCE/1 FUNCTION", expression, error)
        if (allocated(error)) return
        value = evaluate_expression(expression, time)
    end subroutine value_of

    !> Each of ADAMS's functions of numbers at points worked by hand (the arithmetic in the
    !> comments).
    subroutine test_functions(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 33
        character(len=*), parameter :: texts(n) = [character(len=48) :: &
            & "STEP5(0.5, 0, 1, 1, 3)", "STEP5(0.25, 0, 0, 1, 1)", "STEP5(-1, 0, 2, 1, 3)", &
            & "SHF(1, 0.5, 2, PI, 0, 3)", "SHF(0, 0, 1, 1, PI/2, 0)", &
            & "POLY(3, 1, 1, 2, 3)", "CHEBY(0.5, 0, 1, 2, 3, 4)", &
            & "FORCOS(0.5, 0, PI, 1, 2, 3)", "FORSIN(0.25, 0, PI, 1, 2, 3)", &
            & "IMPACT(0.9, -2, 1, 1000, 1.5, 10, 0.2)", "IMPACT(1.1, -2, 1, 1000, 1.5, 10, 0.2)", &
            & "IMPACT(0.9, 20, 1, 1000, 1.5, 10, 0.2)", &
            & "BISTOP(2.1, 1, 0, 2, 1000, 2, 10, 0.2)", "BISTOP(1, 1, 0, 2, 1000, 2, 10, 0.2)", &
            & "BISTOP(-0.1, -1, 0, 2, 1000, 2, 10, 0.2)", "RTOD", "DIM(5, 3)", "DIM(3, 5)", &
            & "MOD(7.5, 2)", "MOD(-7.5, 2)", "AINT(-2.7)", "ANINT(-2.5)", "ANINT(2.4)", &
            & "SIGN(3, -0.1)", "SIGN(-3, 2)", "ASIN(0.5)", "ACOS(0.5)", "ATAN(1)", "SINH(1)", &
            & "COSH(1)", "TANH(0.5)", "LOG10(1000)", "POLY(2, 0, 5)"]
        real(wp), parameter :: expected(n) = [ &
            ! 1 + 2 (1/8)(10 - 7.5 + 1.5); (1/64)(10 - 3.75 + 0.375); before x0: h0
            & 2.0_wp, 0.103515625_wp, 2.0_wp, &
            ! 2 sin(pi/2) + 3; sin(-pi/2)
            & 5.0_wp, -1.0_wp, &
            ! 1 + 2*2 + 3*4; T(0.5) = 1, 0.5, -0.5, -1: 1 + 1 - 1.5 - 4
            & 17.0_wp, -3.5_wp, &
            ! 1 + 2 cos(pi/2) + 3 cos(pi); 1 + 2 sin(pi/4) + 3 sin(pi/2)
            & -2.0_wp, 4.0_wp + sqrt(2.0_wp), &
            ! 1000 (0.1)^1.5 - STEP(0.9, 0.8, 10, 1, 0) (-2), STEP = 5; 0 beyond x1; negative: 0
            & 1000.0_wp*0.1_wp**1.5_wp + 10.0_wp, 0.0_wp, 0.0_wp, &
            ! -1000 (0.1)^2 - STEP(2.1, 2, 0, 2.2, 10) 1 = -10 - 5; 0 between; 10 + 5
            & -15.0_wp, 0.0_wp, 15.0_wp, &
            & 180.0_wp/pi, 2.0_wp, 0.0_wp, &
            & 1.5_wp, -1.5_wp, -2.0_wp, -3.0_wp, 2.0_wp, -3.0_wp, 3.0_wp, &
            & pi/6.0_wp, pi/3.0_wp, pi/4.0_wp, 1.1752011936438014_wp, 1.5430806348152437_wp, &
            & 0.46211715726000974_wp, 3.0_wp, 5.0_wp]
        real(wp) :: value
        integer :: i

        do i = 1, n
            call value_of(trim(texts(i)), 0.0_wp, value, error)
            if (allocated(error)) return
            call check(error, value, expected(i), trim(texts(i)), abs_tol=tol*(1.0_wp &
                & + abs(expected(i))), rel_tol=tol)
            if (allocated(error)) return
        end do
    end subroutine test_functions

    !> Part 1 at (1, 2, 3), turned pi/2 about ground z (psi = pi/2, theta = phi = 0), moving at
    !> (0.1, 0, 0) m/s and turning at psidot = 2 rad/s; marker 11 at (1, 0, 0) on it (in ground
    !> at (1, 3, 3), axes x = (0, 1, 0), y = (-1, 0, 0), z = (0, 0, 1), velocity
    !> (0.1, 0, 0) + (0, 0, 2) x (0, 1, 0) = (-1.9, 0, 0)); ground marker 2 at (1, 1, 1).
    subroutine test_measures(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 18
        character(len=*), parameter :: texts(n) = [character(len=24) :: "DX(11)", "DY(11)", &
            & "DZ(11)", "DM(11)", "DY(11, 2)", "DX(11, 2, 11)", "DY(11, 2, 11)", "DM(11, 2)", &
            & "VX(11)", "VM(11)", "VX(11, 2, 0, 11)", "VM(11, 2, 11)", "VR(11, 2)", "VR(11)", &
            & "WZ(11)", "WM(11, 2)", "WY(11, 0, 11)", "VY(11, 2, 11, 11)"]
        real(wp), parameter :: expected(n) = [1.0_wp, 3.0_wp, 3.0_wp, sqrt(19.0_wp), 2.0_wp, &
            ! d = (0, 2, 2): d . x_11 = 2, d . y_11 = 0; |d|
            & 2.0_wp, 0.0_wp, sqrt(8.0_wp), &
            ! in 11's frame: v - w x d = (-1.9, 0, 0) - (0, 0, 2) x (0, 2, 2) = (2.1, 0, 0)
            & -1.9_wp, 1.9_wp, 2.1_wp, 2.1_wp, &
            ! (-1.9, 0, 0) . (0, 2, 2) = 0; (-1.9, 0, 0) . (1, 3, 3)/sqrt(19)
            & 0.0_wp, -1.9_wp/sqrt(19.0_wp), &
            ! w = (0, 0, 2): WY in 11's axes: w . (-1, 0, 0); (2.1, 0, 0) . y_11
            & 2.0_wp, 2.0_wp, 0.0_wp, -2.1_wp]
        type(marker_type) :: markers(2)
        type(expression_type) :: expression
        real(wp) :: q(6), u(6), values(4)
        integer :: i

        markers(1) = marker_type(id=11, part=1, point=[1.0_wp, 0.0_wp, 0.0_wp])
        markers(2) = marker_type(id=2, part=0, point=[1.0_wp, 1.0_wp, 1.0_wp])
        q = [1.0_wp, 2.0_wp, 3.0_wp, 0.5_wp*pi, 0.0_wp, 0.0_wp]
        u = [0.1_wp, 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp]
        do i = 1, n
            call compile_expression(trim(texts(i)), "test", expression, error)
            if (allocated(error)) return
            call expression_input_values(expression, markers, 1.0_wp, 1.0_wp, q, u, &
                & values(:size(expression%inputs)))
            call check(error, evaluate_expression(expression, 0.0_wp, &
                & values(:size(expression%inputs))), expected(i), trim(texts(i)), &
                & abs_tol=tol*10.0_wp)
            if (allocated(error)) return
        end do
    end subroutine test_measures

    !> The angles of one ground marker's axes in another's: i's axes are j's turned by a known
    !> rotation, so PSI, THETA, PHI (3-1-3), YAW, PITCH, ROLL (3-2-1, PITCH the negative of the
    !> second) and AX, AY, AZ give its angles back.
    subroutine test_angles(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a_j(3, 3)

        a_j = rotation_matrix(0.1_wp, 0.3_wp, 0.2_wp)
        call check_angles(error, matmul(a_j, rotation_matrix(0.4_wp, 0.6_wp, -0.3_wp)), &
            & "PSI(5, 6) + 10*THETA(5, 6) + 100*PHI(5, 6)", 0.4_wp + 6.0_wp - 30.0_wp)
        if (allocated(error)) return
        call check_angles(error, matmul(a_j, matmul(rz(0.5_wp), matmul(ry(-0.2_wp), &
            & rx(0.7_wp)))), "YAW(5, 6) + 10*PITCH(5, 6) + 100*ROLL(5, 6)", 0.5_wp + 2.0_wp &
            & + 70.0_wp)
        if (allocated(error)) return
        call check_angles(error, matmul(a_j, rx(0.4_wp)), "AX(5, 6)", 0.4_wp)
        if (allocated(error)) return
        call check_angles(error, matmul(a_j, ry(-0.25_wp)), "AY(5, 6)", -0.25_wp)
        if (allocated(error)) return
        call check_angles(error, matmul(a_j, rz(2.5_wp)), "AZ(5, 6)", 2.5_wp)
    end subroutine test_angles

    subroutine check_angles(error, a_i, text, expected)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: a_i(3, 3)
        character(len=*), intent(in) :: text
        real(wp), intent(in) :: expected
        type(marker_type) :: markers(2)
        type(expression_type) :: expression
        real(wp) :: q(6), u(6), values(6)

        markers(1) = marker_type(id=5, part=0, axes=a_i)
        markers(2) = marker_type(id=6, part=0, axes=rotation_matrix(0.1_wp, 0.3_wp, 0.2_wp))
        q = 0.0_wp
        u = 0.0_wp
        call compile_expression(text, "test", expression, error)
        if (allocated(error)) return
        call expression_input_values(expression, markers, 1.0_wp, 1.0_wp, q, u, &
            & values(:size(expression%inputs)))
        call check(error, evaluate_expression(expression, 0.0_wp, &
            & values(:size(expression%inputs))), expected, text, abs_tol=100.0_wp*tol)
    end subroutine check_angles

    pure function rx(a) result(m)
        real(wp), intent(in) :: a
        real(wp) :: m(3, 3)

        m = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, cos(a), sin(a), 0.0_wp, -sin(a), &
            & cos(a)], [3, 3])
    end function rx

    pure function ry(a) result(m)
        real(wp), intent(in) :: a
        real(wp) :: m(3, 3)

        m = reshape([cos(a), 0.0_wp, -sin(a), 0.0_wp, 1.0_wp, 0.0_wp, sin(a), 0.0_wp, &
            & cos(a)], [3, 3])
    end function ry

    pure function rz(a) result(m)
        real(wp), intent(in) :: a
        real(wp) :: m(3, 3)

        m = reshape([cos(a), sin(a), 0.0_wp, -sin(a), cos(a), 0.0_wp, 0.0_wp, 0.0_wp, &
            & 1.0_wp], [3, 3])
    end function rz

    !> AZ of a marker turned 3.5 rad about ground z is 3.5 - 2 pi on its own (in (-pi, pi]),
    !> and 3.5 and 3.5 + 2 pi on the branches nearest anchors of 3 and 9 rad; its jet's value
    !> is on the same branch.
    subroutine test_turns(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: anchors(3) = [0.0_wp, 3.0_wp, 9.0_wp]
        real(wp), parameter :: expected(3) = [3.5_wp - 2.0_wp*pi, 3.5_wp, 3.5_wp + 2.0_wp*pi]
        type(marker_type) :: markers(1)
        type(expression_type) :: expression
        type(state_jets_type) :: state
        type(jet_type) :: inputs(1), value
        real(wp) :: q(6, 1), u(6, 1), values(1)
        integer :: k

        markers(1) = marker_type(id=5, part=1)
        ! theta = 0: the part turned psi + phi = 3.5 rad about ground z
        q(:, 1) = [0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 1.5_wp]
        u = 0.0_wp
        call compile_expression("AZ(5)", "test", expression, error)
        if (allocated(error)) return
        do k = 1, 3
            expression%anchors = anchors(k)
            call expression_input_values(expression, markers, 1.0_wp, 1.0_wp, q(:, 1), &
                & u(:, 1), values)
            call check(error, values(1), expected(k), "AZ near anchor " // to_text(anchors(k)), &
                & abs_tol=tol*10.0_wp)
            if (allocated(error)) return
            state = new_state_jets([1], q, u, reshape([(k, k = 1, 6)], [6, 1]), &
                & reshape([(0, k = 1, 6)], [6, 1]), 6, .true.)
            call expression_input_jets(expression, markers, 1.0_wp, 1.0_wp, state, inputs)
            value = evaluate_expression_jet(expression, jet_variable(0.0_wp, 1, 6, .true.), &
                & inputs)
            call check(error, value%v, expected(k), "AZ's jet near anchor " &
                & // to_text(anchors(k)), abs_tol=tol*10.0_wp)
            if (allocated(error)) return
        end do
    end subroutine test_turns

    !> Through (0, 0), (1, 1), (2, 0): the natural cubic spline has second derivative -3 at
    !> x = 1 (4 sigma = 6 (-1 - 1)), so on [0, 1] y = 1.5 x - 0.5 x^3: y(0.5) = 0.6875,
    !> y'(0.5) = 1.125, y''(0.5) = -1.5. Akima's slopes there are 2, 0, -2 (chords 1, -1 and the
    !> ends continued: 3, 5 and -3, -5, every weight 2), so on [0, 1] y = 2 x - x^2:
    !> y(0.5) = 0.75, y'(0.5) = 1, y''(0.5) = -2; past the last point the end cubic goes on.
    subroutine test_curves(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(7) = [character(len=32) :: "CUBSPL(TIME, 0, 4)", &
            & "CUBSPL(TIME, 0, 4, 1)", "CUBSPL(TIME, 0, 4, 2)", "AKISPL(TIME, 0, 4)", &
            & "AKISPL(TIME, 0, 4, 1)", "AKISPL(TIME, 0, 4, 2)", "AKISPL(TIME, 0, 9)"]
        ! Akima beyond x = 2 on [1, 2]: y = 1 + 0 s - s^2 (slopes 0, -2): y(2.5) = 1 - 2.25
        real(wp), parameter :: expected(7) = [0.6875_wp, 1.125_wp, -1.5_wp, 0.75_wp, 1.0_wp, &
            & -2.0_wp, 0.0_wp]
        type(spline_type) :: spline
        type(expression_type) :: expression
        character(len=:), allocatable :: problem
        real(wp) :: value
        integer :: i

        call new_spline(4, [0.0_wp, 1.0_wp, 2.0_wp], [0.0_wp, 1.0_wp, 0.0_wp], spline, problem)
        call check(error, len(problem) == 0, problem)
        if (allocated(error)) return
        do i = 1, size(texts)
            call compile_expression(trim(texts(i)), "test", expression, error)
            if (allocated(error)) return
            expression%splines = [spline]
            value = evaluate_expression(expression, 0.5_wp)
            if (i < 7) then
                call check(error, value, expected(i), trim(texts(i)), abs_tol=tol)
            else
                ! a SPLINE not given: NaN
                call check(error, value /= value, trim(texts(i)) // " should be NaN")
            end if
            if (allocated(error)) return
        end do
        call compile_expression("AKISPL(TIME, 0, 4)", "test", expression, error)
        if (allocated(error)) return
        expression%splines = [spline]
        call check(error, evaluate_expression(expression, 2.5_wp), -1.25_wp, &
            & "AKISPL past the last point", abs_tol=tol)
        if (allocated(error)) return
        call new_spline(5, [0.0_wp, 1.0_wp, 1.0_wp], [0.0_wp, 1.0_wp, 2.0_wp], spline, problem)
        call check(error, problem == "x must increase strictly from point to point", &
            & "a repeated x: " // problem)
    end subroutine test_curves

    !> The functions with corners switch where their argument, affine in TIME, meets them:
    !> STEP5 at x0 and x1; IMPACT at x1 - d and x1; BISTOP at x1 - d, x1, x2, x2 + d; DIM where
    !> its arguments cross; SIGN where its second argument (and its first) changes sign.
    subroutine test_corners(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(5) = [character(len=56) :: &
            & "STEP5(TIME, 1, 0, 3, 5)", "IMPACT(2*TIME, 1, 4, 10, 1.5, 1, 0.5)", &
            & "BISTOP(TIME - 1, 0, 1, 2, 10, 2, 1, 0.25)", "DIM(3*TIME, 6 - TIME)", &
            & "SIGN(TIME - 5, 2*TIME - 1)"]
        integer, parameter :: counts(5) = [2, 2, 4, 1, 2]
        real(wp), parameter :: expected(11) = [1.0_wp, 3.0_wp, 1.75_wp, 2.0_wp, 1.75_wp, &
            & 2.0_wp, 3.0_wp, 3.25_wp, 1.5_wp, 0.5_wp, 5.0_wp]
        type(expression_type) :: expression
        real(wp), allocatable :: times(:)
        integer :: i, first

        first = 1
        do i = 1, size(texts)
            call compile_expression(trim(texts(i)), "test", expression, error)
            if (allocated(error)) return
            times = switching_times(expression)
            call check(error, size(times) == counts(i), trim(texts(i)) // ": " &
                & // to_text(size(times)) // " times")
            if (allocated(error)) return
            call check(error, times, expected(first:first + counts(i) - 1), trim(texts(i)), &
                & abs_tol=tol*10.0_wp)
            if (allocated(error)) return
            first = first + counts(i)
        end do
    end subroutine test_corners

    !> The functions with corners whose arguments read measures are watched switches: IMPACT's
    !> x - (x1 - d) and x - x1; BISTOP's x - (x1 - d), x - x1, x - x2, x - (x2 + d); SIGN's b
    !> and a; DIM's a - b; each zero where its function switches, in program order. STEP5 on
    !> TIME alone is timed (its times 1 and 2); MOD, whose jumps are periodic, and SHF, smooth,
    !> are not switches.
    subroutine test_state_switches(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: text = "IMPACT(DZ(1), VZ(1), 1, 10, 1.5, 1, 0.5) + " &
            & // "BISTOP(DX(1), 0, 1, 2, 10, 2, 1, 0.25) + SIGN(DY(1), TIME - 3) + " &
            & // "DIM(DX(1), 2) + STEP5(TIME, 1, 0, 2, 1) + MOD(DZ(1), 2) " &
            & // "+ SHF(DX(1), 0, 1, 2, 0, 0)"
        type(expression_type) :: expression
        integer, allocatable :: kinds(:)
        real(wp) :: g(9)

        call compile_expression(text, "test.adm:1: SFORCE/1 FUNCTION", expression, error)
        if (allocated(error)) return
        kinds = switch_kinds(expression)
        call check(error, count(kinds == switch_watched) == 4 .and. count(kinds &
            & == switch_timed) == 1 .and. count(kinds == switch_none) == size(kinds) - 5 &
            & .and. switch_count(expression, kinds) == size(g), "kinds of '" // text // "'")
        if (allocated(error)) return
        ! inputs in the order the expression reads them: DZ(1), VZ(1), DX(1), DY(1)
        call switch_values(expression, 0.5_wp, [0.8_wp, -0.1_wp, 1.5_wp, -0.4_wp], kinds, g)
        call check(error, g, [0.8_wp - 0.5_wp, 0.8_wp - 1.0_wp, 1.5_wp - 0.75_wp, &
            & 1.5_wp - 1.0_wp, 1.5_wp - 2.0_wp, 1.5_wp - 2.25_wp, 0.5_wp - 3.0_wp, -0.4_wp, &
            & 1.5_wp - 2.0_wp], "switch functions of '" // text // "'", abs_tol=tol)
        if (allocated(error)) return
        call check(error, switching_times(expression), [1.0_wp, 2.0_wp], "its timed switch", &
            & abs_tol=tol)
    end subroutine test_state_switches

    !> The markers of the reference (expression_reference), as the model holds them.
    function reference_marker_list() result(markers)
        type(marker_type) :: markers(size(reference_markers))
        integer :: m

        do m = 1, size(reference_markers)
            markers(m)%id = reference_markers(m)
            markers(m)%part = reference_marker_parts(m)
            markers(m)%point = reference_marker_points(:, m)
            markers(m)%axes = rotation_matrix(reference_marker_angles(1, m), &
                & reference_marker_angles(2, m), reference_marker_angles(3, m))
            ! a marker of a moving part with no offset nor turn: its part's principal axes
            markers(m)%principal = markers(m)%part > 0 .and. all(reference_marker_points(:, m) &
                & == 0.0_wp) .and. all(reference_marker_angles(:, m) == 0.0_wp)
        end do
    end function reference_marker_list

    !> The jet of reference expression k over q (1:12), u (13:24) and t (25), second order.
    subroutine reference_jet(k, value, error)
        integer, intent(in) :: k
        type(jet_type), intent(out) :: value
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        type(state_jets_type) :: state
        type(jet_type), allocatable :: inputs(:)
        real(wp) :: states(25)
        integer :: c

        states = reference_states(:, (k - 1)/(reference_count/size(reference_states, 2)) + 1)
        call compile_expression(trim(reference_texts(k)), "reference", expression, error)
        if (allocated(error)) return
        allocate(inputs(size(expression%inputs)))
        state = new_state_jets([1, 2], reshape(states(1:12), [6, 2]), &
            & reshape(states(13:24), [6, 2]), reshape([(c, c = 1, 12)], [6, 2]), &
            & reshape([(c, c = 13, 24)], [6, 2]), 25, .true.)
        call expression_input_jets(expression, reference_marker_list(), 1.0_wp, 1.0_wp, &
            & state, inputs)
        value = evaluate_expression_jet(expression, jet_variable(states(25), 25, 25, .true.), &
            & inputs)
    end subroutine reference_jet

    !> Every reference expression: its jet's value equals the value path's (the force's
    !> expression_input_values and evaluate_expression) at its state.
    subroutine test_paths(error)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        type(jet_type) :: value
        real(wp) :: states(25), q(12), u(12)
        real(wp), allocatable :: values(:)
        integer :: k

        do k = 1, reference_count
            states = reference_states(:, (k - 1)/(reference_count/size(reference_states, 2)) + 1)
            q = states(1:12)
            u = states(13:24)
            call compile_expression(trim(reference_texts(k)), "reference", expression, error)
            if (allocated(error)) return
            allocate(values(size(expression%inputs)))
            call expression_input_values(expression, reference_marker_list(), 1.0_wp, 1.0_wp, &
                & q, u, values)
            call reference_jet(k, value, error)
            if (allocated(error)) return
            call check(error, value%v, evaluate_expression(expression, states(25), values), &
                & trim(reference_texts(k)) // ": jet and value path", abs_tol=tol_paths*(1.0_wp &
                & + abs(value%v)))
            if (allocated(error)) return
            deallocate(values)
        end do
    end subroutine test_paths

    !> Every reference expression: its jet's value, gradient and Hessian (times two probes)
    !> against SymPy's.
    subroutine test_partials(error)
        type(error_type), allocatable, intent(out) :: error
        type(jet_type) :: value
        real(wp) :: gradient(25), products(25, 2), scale
        integer :: k, p

        do k = 1, reference_count
            call reference_jet(k, value, error)
            if (allocated(error)) return
            gradient = 0.0_wp
            products = 0.0_wp
            if (value%active) then
                gradient = value%g
                do p = 1, 2
                    products(:, p) = matmul(value%h, reference_probes(:, p))
                end do
            end if
            scale = 1.0_wp + max(abs(reference_values(k)), maxval(abs(reference_gradients(:, &
                & k))), maxval(abs(reference_products(:, :, k))))
            call check(error, value%v, reference_values(k), trim(reference_texts(k)) &
                & // ": value", abs_tol=tol_partials*scale)
            if (allocated(error)) return
            call check(error, gradient, reference_gradients(:, k), trim(reference_texts(k)) &
                & // ": gradient", abs_tol=tol_partials*scale)
            if (allocated(error)) return
            call check(error, products(:, 1), reference_products(:, 1, k), &
                & trim(reference_texts(k)) // ": Hessian times probe 1", &
                & abs_tol=tol_partials*scale)
            if (allocated(error)) return
            call check(error, products(:, 2), reference_products(:, 2, k), &
                & trim(reference_texts(k)) // ": Hessian times probe 2", &
                & abs_tol=tol_partials*scale)
            if (allocated(error)) return
        end do
    end subroutine test_partials

end module test_expression_functions
