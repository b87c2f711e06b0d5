! SPDX-License-Identifier: MIT
!> Function expressions of ADAMS datasets: every operator and function against hand values,
!> precedence, degrees, the smooth steps, state functions as inputs, the switching times found
!> for breakpoints and corners, the switches on the state (their kinds and event-function
!> values), and one refusal per kind of syntax error.
module test_adm_expression
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_expression, only : expression_type, evaluate_expression, switching_times, &
        & switch_kinds, switch_count, switch_values, switch_none, switch_timed, switch_watched
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_testing, only : unittest_type, new_unittest, check
    use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
    implicit none
    private

    public :: collect_adm_expression

    !> Hand values are written to 16 digits or come from the same intrinsics: a few ulp
    real(wp), parameter :: tol = 4.0e-15_wp

contains

    subroutine collect_adm_expression(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("arithmetic-and-precedence", test_precedence), &
            & new_unittest("functions", test_functions), &
            & new_unittest("names-any-case-and-degrees", test_names), &
            & new_unittest("step-and-havsin", test_steps), &
            & new_unittest("if-three-branches", test_if), &
            & new_unittest("domain-gives-nan", test_domain), &
            & new_unittest("state-functions-as-inputs", test_state_functions), &
            & new_unittest("state-function-forms-refused", test_state_function_refusals), &
            & new_unittest("switching-times", test_switching_times), &
            & new_unittest("step5-quintic", test_step5), &
            & new_unittest("switches-on-the-state", test_state_switches), &
            & new_unittest("unknown-name-refused", test_unknown_name), &
            & new_unittest("syntax-errors-refused", test_syntax_errors)]
    end subroutine collect_adm_expression

    !> Value of `text` at `time`, or the compile error.
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

    subroutine check_value(error, text, time, expected)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: text
        real(wp), intent(in) :: time, expected
        real(wp) :: value

        call value_of(text, time, value, error)
        if (allocated(error)) return
        call check(error, value, expected, text, abs_tol=tol, rel_tol=tol)
    end subroutine check_value

    subroutine test_precedence(error)
        type(error_type), allocatable, intent(out) :: error

        call check_value(error, "1 + 2*3", 0.0_wp, 7.0_wp)
        if (allocated(error)) return
        call check_value(error, "(1 + 2)*3", 0.0_wp, 9.0_wp)
        if (allocated(error)) return
        call check_value(error, "-2**2", 0.0_wp, -4.0_wp)
        if (allocated(error)) return
        call check_value(error, "2**3**2", 0.0_wp, 512.0_wp)
        if (allocated(error)) return
        call check_value(error, "2*-3 - 4/8", 0.0_wp, -6.5_wp)
        if (allocated(error)) return
        call check_value(error, "2**-1", 0.0_wp, 0.5_wp)
        if (allocated(error)) return
        call check_value(error, "(-2)**3", 0.0_wp, -8.0_wp)
        if (allocated(error)) return
        call check_value(error, "10 - 4 - 3", 0.0_wp, 3.0_wp)
        if (allocated(error)) return
        call check_value(error, "1.5E2 + 2.5D-1 + .5", 0.0_wp, 150.75_wp)
    end subroutine test_precedence

    subroutine test_functions(error)
        type(error_type), allocatable, intent(out) :: error

        call check_value(error, "SIN(0.5) + COS(0.25)", 0.0_wp, sin(0.5_wp) + cos(0.25_wp))
        if (allocated(error)) return
        call check_value(error, "TAN(0.3)", 0.0_wp, tan(0.3_wp))
        if (allocated(error)) return
        call check_value(error, "ATAN2(1, -1)", 0.0_wp, 0.75_wp*pi)
        if (allocated(error)) return
        call check_value(error, "EXP(1)*LOG(10)", 0.0_wp, exp(1.0_wp)*log(10.0_wp))
        if (allocated(error)) return
        call check_value(error, "SQRT(2) + ABS(-3)", 0.0_wp, sqrt(2.0_wp) + 3.0_wp)
        if (allocated(error)) return
        call check_value(error, "MIN(3, -1) + MAX(3, -1)", 0.0_wp, 2.0_wp)
        if (allocated(error)) return
        call check_value(error, "2*TIME + 1", 1.25_wp, 3.5_wp)
    end subroutine test_functions

    subroutine test_names(error)
        type(error_type), allocatable, intent(out) :: error

        call check_value(error, "sin(pi/6)", 0.0_wp, sin(pi/6.0_wp))
        if (allocated(error)) return
        call check_value(error, "Time*DtoR", 90.0_wp, 0.5_wp*pi)
        if (allocated(error)) return
        ! a D after a number is degrees; D with digits is a double-precision exponent
        call check_value(error, "90D + 1D1", 0.0_wp, 0.5_wp*pi + 10.0_wp)
        if (allocated(error)) return
        call check_value(error, "COS(180d)", 0.0_wp, -1.0_wp)
    end subroutine test_names

    !> STEP is ADAMS's cubic h0 + (h1 - h0) s^2 (3 - 2 s), HAVSIN the haversine: both at the
    !> ends, halfway, and with zero slope at the ends (central differences, h = 1e-6).
    subroutine test_steps(error)
        type(error_type), allocatable, intent(out) :: error
        !> Slope at the ends: O(h) for the cubic (its slope is 6 a s (1 - s)), h = 1e-6
        real(wp), parameter :: tol_slope = 1.0e-5_wp
        character(len=*), parameter :: step = "STEP(TIME, 1, 2, 3, 6)", &
            & havsin = "HAVSIN(TIME, 1, 2, 3, 6)"
        real(wp) :: a, b

        call check_value(error, step, 0.5_wp, 2.0_wp)
        if (allocated(error)) return
        call check_value(error, step, 3.5_wp, 6.0_wp)
        if (allocated(error)) return
        call check_value(error, step, 2.0_wp, 4.0_wp)
        if (allocated(error)) return
        ! s = 1/4: 2 + 4 (1/16)(3 - 1/2) = 2.625
        call check_value(error, step, 1.5_wp, 2.625_wp)
        if (allocated(error)) return
        call check_value(error, havsin, 2.0_wp, 4.0_wp)
        if (allocated(error)) return
        ! s = 1/4: 4 + 2 sin(-pi/4)
        call check_value(error, havsin, 1.5_wp, 4.0_wp - sqrt(2.0_wp))
        if (allocated(error)) return
        call value_of(step, 1.0_wp + 1.0e-6_wp, a, error)
        if (allocated(error)) return
        call value_of(step, 1.0_wp - 1.0e-6_wp, b, error)
        if (allocated(error)) return
        call check(error, (a - b)/2.0e-6_wp, 0.0_wp, "STEP slope at x0", abs_tol=tol_slope)
        if (allocated(error)) return
        call value_of(havsin, 3.0_wp + 1.0e-6_wp, a, error)
        if (allocated(error)) return
        call value_of(havsin, 3.0_wp - 1.0e-6_wp, b, error)
        if (allocated(error)) return
        call check(error, (a - b)/2.0e-6_wp, 0.0_wp, "HAVSIN slope at x1", abs_tol=tol_slope)
    end subroutine test_steps

    subroutine test_if(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: text = "IF(TIME - 2: 10, 20, 30*TIME)"

        call check_value(error, text, 1.0_wp, 10.0_wp)
        if (allocated(error)) return
        call check_value(error, text, 2.0_wp, 20.0_wp)
        if (allocated(error)) return
        call check_value(error, text, 3.0_wp, 90.0_wp)
        if (allocated(error)) return
        ! nested, as a pulse is written: zero outside [2, 2.01]
        call check_value(error, "IF(TIME-2: 0, 0, IF(TIME-2.01: SIN(PI*(TIME-2)/0.01), 0, 0))", &
            & 2.005_wp, 1.0_wp)
    end subroutine test_if

    subroutine test_domain(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(5) = [character(len=24) :: "LOG(-1)", "SQRT(-2)", &
            & "1/(TIME - 1)", "(-2)**0.5", "STEP(TIME, 2, 0, 1, 1)"]
        real(wp) :: value
        integer :: i

        do i = 1, size(texts)
            call value_of(trim(texts(i)), 1.0_wp, value, error)
            if (allocated(error)) return
            call check(error, ieee_is_nan(value), trim(texts(i)) // " should be NaN")
            if (allocated(error)) return
        end do
    end subroutine test_domain

    !> Each state function is an input (marker id, quantity), listed once however often it is
    !> read, in the order first read; its value comes from the caller's array.
    subroutine test_state_functions(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: names(12) = [character(len=5) :: "DX", "DY", "DZ", &
            & "VX", "VY", "VZ", "WX", "WY", "WZ", "PSI", "THETA", "PHI"]
        type(expression_type) :: expression
        integer :: k

        call compile_expression("dx(3) + 2*Theta(3) - VX(14)*DX(3) + TIME", "test.adm:1: " &
            & // "GFORCE/1 FX", expression, error)
        if (allocated(error)) return
        call check(error, size(expression%inputs) == 3, "three distinct inputs")
        if (allocated(error)) return
        call check(error, all(expression%inputs%marker == [3, 3, 14]) &
            & .and. all(expression%inputs%quantity == [1, 11, 4]), "markers and quantities")
        if (allocated(error)) return
        ! 0.5 + 2*0.25 - 4*0.5 + 10
        call check(error, evaluate_expression(expression, 10.0_wp, [0.5_wp, 0.25_wp, 4.0_wp]), &
            & 9.0_wp, "value from the inputs", abs_tol=tol)
        if (allocated(error)) return
        call check(error, ieee_is_nan(evaluate_expression(expression, 10.0_wp)), &
            & "inputs not given: NaN")
        if (allocated(error)) return
        do k = 1, size(names)
            call compile_expression(trim(names(k)) // "( 7 )", "test.adm:1: GFORCE/1 FX", &
                & expression, error)
            if (allocated(error)) return
            call check(error, size(expression%inputs) == 1, names(k))
            if (allocated(error)) return
            call check(error, expression%inputs(1)%marker == 7 &
                & .and. expression%inputs(1)%quantity == k, names(k))
            if (allocated(error)) return
            call check(error, evaluate_expression(expression, 0.0_wp, [-1.5_wp]), -1.5_wp, &
                & names(k), abs_tol=tol)
            if (allocated(error)) return
        end do
    end subroutine test_state_functions

    !> A measure with more markers than it takes, markers that are not ids, a call without its
    !> parentheses, an element function's flag out of range, a marker i of 0: each refused
    !> with how the measure is written.
    subroutine test_state_function_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(6) = [character(len=20) :: "DX(1, 2, 3, 4)", &
            & "PSI(3,2,1)", "VZ(a)", "WX 3", "JOINT(1, 2, 3, 0)", "DM(0)"]
        character(len=*), parameter :: expected(6) = [character(len=240) :: &
            & "test.adm:1: SFORCE/1 FUNCTION: DX takes at most 3 marker ids, DX(i[, j[, k]]) " &
            & // "at column 11 of 'DX(1, 2, 3, 4)'", &
            & "test.adm:1: SFORCE/1 FUNCTION: PSI takes at most 2 marker ids, PSI(i[, j]) at " &
            & // "column 8 of 'PSI(3,2,1)'", &
            & "test.adm:1: SFORCE/1 FUNCTION: VZ's i must be a marker id (a whole number > 0) " &
            & // "(VZ is written VZ(i[, j[, k[, l]]])) at column 4 of 'VZ(a)'", &
            & "test.adm:1: SFORCE/1 FUNCTION: '(' expected, found '3' (WX is written " &
            & // "WX(i[, j[, k]])) at column 4 of 'WX 3'", &
            & "test.adm:1: SFORCE/1 FUNCTION: JOINT's jflag must be 0 (the force on the I " &
            & // "marker) or 1 (on J) at column 18 of 'JOINT(1, 2, 3, 0)'", &
            & "test.adm:1: SFORCE/1 FUNCTION: DM's i must be a marker id (a whole number > 0) " &
            & // "(DM is written DM(i[, j])) at column 4 of 'DM(0)'"]
        real(wp) :: value
        type(error_type), allocatable :: refused
        integer :: i

        do i = 1, size(texts)
            call value_of(trim(texts(i)), 0.0_wp, value, refused)
            call check(error, allocated(refused), "'" // trim(texts(i)) // "' accepted")
            if (allocated(error)) return
            call check(error, refused%message == trim(expected(i)), refused%message)
            if (allocated(error)) return
            deallocate(refused)
        end do
    end subroutine test_state_function_refusals

    !> IF, STEP, STEP5 and HAVSIN switching on TIME - c (or a TIME + b), MIN and MAX whose
    !> arguments' difference is one, ABS of one, give their switching times exactly as -b/a,
    !> inner ones first; a switch on a state function or a non-affine TIME is not one, nor MAX
    !> of two arguments that never meet.
    subroutine test_switching_times(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(12) = [character(len=64) :: &
            & "IF(TIME-2: 0, 0, IF(TIME-2.01: SIN(PI*(TIME-2)/0.01), 0, 0))", &
            & "STEP(TIME, 1, 0, 3, 5) + 1", "HAVSIN(-(1 - TIME)/2, 0.5, 0, 1, 1)", &
            & "IF(2*TIME - 10**-1: 1, 0, 0)", "IF(DX(1) - 2: 0, 0, 1)", &
            & "STEP(TIME*TIME, 1, 0, 2, 1)", "STEP(TIME, DX(2), 0, 2, 1)", &
            & "STEP5(TIME, 0.5, 0, 0.75, 1)", "MAX(TIME - 1, 0) + MIN(4, 2*TIME)", &
            & "ABS(3 - TIME)", "MAX(TIME, TIME + 1)", "MIN(DX(1), TIME)"]
        integer, parameter :: counts(12) = [2, 2, 2, 1, 0, 0, 0, 2, 2, 1, 0, 0]
        real(wp), parameter :: expected(12) = [2.01_wp, 2.0_wp, 1.0_wp, 3.0_wp, 2.0_wp, 3.0_wp, &
            & 0.05_wp, 0.5_wp, 0.75_wp, 1.0_wp, 2.0_wp, 3.0_wp]
        type(expression_type) :: expression
        real(wp), allocatable :: times(:)
        integer :: i, first

        first = 1
        do i = 1, size(texts)
            call compile_expression(trim(texts(i)), "test.adm:1: SFORCE/1 FUNCTION", &
                & expression, error)
            if (allocated(error)) return
            times = switching_times(expression)
            call check(error, size(times) == counts(i), trim(texts(i)) // ": count")
            if (allocated(error)) return
            if (counts(i) == 0) cycle
            call check(error, times, expected(first:first + counts(i) - 1), trim(texts(i)), &
                & abs_tol=tol)
            if (allocated(error)) return
            first = first + counts(i)
        end do
        ! exactly, as the breakpoints of coin.adm and coin.nml must agree
        call compile_expression(trim(texts(1)), "x", expression, error)
        if (allocated(error)) return
        times = switching_times(expression)
        call check(error, times(1) == 2.01_wp .and. times(2) == 2.0_wp, "exact switching times")
    end subroutine test_switching_times

    !> STEP5 is ADAMS's quintic h0 + (h1 - h0) s^3 (10 - 15 s + 6 s^2): at the ends, halfway,
    !> at s = 1/4, and without a jump of its second derivative at x0 (a second difference).
    subroutine test_step5(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: step5 = "STEP5(TIME, 1, 2, 3, 6)"
        !> The second difference at x0 = 1, (y(1 + h) - 2 y(1) + y(1 - h))/h^2 with y constant
        !> before: 4 * 10 (h/2)^3 / h^2 = 5 h = 5e-4 for the quintic (s = (t - 1)/2), and
        !> 4 * 3 (h/2)^2 / h^2 = 3 for a cubic STEP, whose curvature jumps there; 0.05 between
        real(wp), parameter :: tol_curvature = 0.05_wp, h = 1.0e-4_wp
        real(wp) :: a, b, c

        call check_value(error, step5, 0.5_wp, 2.0_wp)
        if (allocated(error)) return
        call check_value(error, step5, 3.5_wp, 6.0_wp)
        if (allocated(error)) return
        call check_value(error, step5, 2.0_wp, 4.0_wp)
        if (allocated(error)) return
        ! s = 1/4: 2 + 4 (1/64)(10 - 15/4 + 6/16) = 2.4140625
        call check_value(error, step5, 1.5_wp, 2.4140625_wp)
        if (allocated(error)) return
        call value_of(step5, 1.0_wp + h, a, error)
        if (allocated(error)) return
        call value_of(step5, 1.0_wp, b, error)
        if (allocated(error)) return
        call value_of(step5, 1.0_wp - h, c, error)
        if (allocated(error)) return
        call check(error, (a - 2.0_wp*b + c)/h**2, 0.0_wp, "STEP5 curvature at x0", &
            & abs_tol=tol_curvature)
    end subroutine test_step5

    !> A switch whose argument is not affine in TIME is watched: switch_kinds says which
    !> operations, switch_count how many event functions, and switch_values gives them, each
    !> zero where its switch switches (an IF's condition; x - x0 and x - x1 of a STEP; a - b of
    !> MAX; the argument of ABS), in program order; a switch on TIME alone is timed.
    subroutine test_state_switches(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: text = "IF(DX(1) - 2: STEP(VX(1), 0, 0, 1, 5), 0, " &
            & // "MAX(DY(1), TIME)) + ABS(DZ(1)) + STEP(TIME, 1, 0, 2, 1) + SIN(TIME*TIME)"
        type(expression_type) :: expression
        integer, allocatable :: kinds(:)
        real(wp) :: g(5)

        call compile_expression(text, "test.adm:1: SFORCE/1 FUNCTION", expression, error)
        if (allocated(error)) return
        kinds = switch_kinds(expression)
        call check(error, count(kinds == switch_watched) == 4 .and. count(kinds &
            & == switch_timed) == 1 .and. count(kinds == switch_none) == size(kinds) - 5 &
            & .and. switch_count(expression, kinds) == 5, "kinds of '" // text // "'")
        if (allocated(error)) return
        ! inputs in the order the expression reads them: DX(1), VX(1), DY(1), DZ(1)
        call switch_values(expression, 0.25_wp, [2.5_wp, 0.75_wp, -1.0_wp, -0.5_wp], kinds, g)
        ! in the order their operations close: the STEP on VX and the MAX inside the IF, the IF,
        ! then ABS
        call check(error, g, [0.75_wp, 0.75_wp - 1.0_wp, -1.0_wp - 0.25_wp, 2.5_wp - 2.0_wp, &
            & -0.5_wp], "switch functions of '" // text // "'", abs_tol=tol)
        if (allocated(error)) return
        call check(error, switching_times(expression), [1.0_wp, 2.0_wp], "its timed switch", &
            & abs_tol=tol)
    end subroutine test_state_switches

    subroutine test_unknown_name(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value
        type(error_type), allocatable :: refused

        call value_of("2*VMX(1, 2)", 0.0_wp, value, refused)
        call check(error, allocated(refused), "VMX accepted")
        if (allocated(error)) return
        call check(error, refused%message == "test.adm:1: SFORCE/1 FUNCTION: unknown name 'VMX': " &
            & // "not a function, measure or constant rollcon reads (docs/datasets.md, Function " &
            & // "expressions, lists them) at column 3 of '2*VMX(1, 2)'", refused%message)
    end subroutine test_unknown_name

    subroutine test_syntax_errors(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(8) = [character(len=20) :: "", "1 +", "(1 + 2", &
            & "SIN(1, 2)", "STEP(TIME, 1, 2)", "1 2", "IF(TIME, 1, 2, 3)", "3 $ 4"]
        character(len=*), parameter :: expected(8) = [character(len=60) :: &
            & "an operand is missing at column 1", "an operand is missing at column 4", &
            & "')' expected at the end at column 7", "')' expected, found ','", &
            & "',' expected, found ')'", "unexpected '2' at column 3", &
            & "':' expected, found ','", "unexpected '$' at column 3"]
        real(wp) :: value
        type(error_type), allocatable :: refused
        integer :: i

        do i = 1, size(texts)
            call value_of(trim(texts(i)), 0.0_wp, value, refused)
            call check(error, allocated(refused), "'" // trim(texts(i)) // "' accepted")
            if (allocated(error)) return
            call check(error, index(refused%message, trim(expected(i))) > 0, refused%message)
            if (allocated(error)) return
            deallocate(refused)
        end do
    end subroutine test_syntax_errors

end module test_adm_expression
