! SPDX-License-Identifier: MIT
!> Function expressions of an ADAMS dataset (`FUNCTION = e`) as small stack programs, evaluated
!> at any time and state with no allocation on the path of the functions below
!> (rollcon_adm_expression_parser compiles them; docs/datasets.md, "Function expressions",
!> defines every function).
!>
!> Numbers (with `D` after a number for degrees), `TIME`, `PI`, `DTOR`, `RTOD`; `+ - * /` and
!> `**` (right-associative, binding tighter than a sign, as in Fortran); the functions
!> `SIN COS TAN ATAN2 EXP LOG SQRT ABS MIN MAX`, `STEP(x, x0, h0, x1, h1)` (cubic step),
!> `HAVSIN(x, x0, h0, x1, h1)` (haversine step) and `IF(e: neg, zero, pos)`; ADAMS's further
!> functions of numbers `ASIN ACOS ATAN SINH COSH TANH LOG10 STEP5 SHF POLY CHEBY FORCOS FORSIN
!> IMPACT BISTOP DIM MOD AINT ANINT SIGN` and the curves `AKISPL CUBSPL` (rollcon_expression_
!> functions, rollcon_spline); and the measures of markers and the values of other statements
!> (quantity_names: `DX(i[,j[,k]])`, `VX(i[,j[,k[,l]]])`, `AX(i[,j])`, `FX(i[,j[,k]])`,
!> `JOINT(id, jflag, comp, rm)`, `VARVAL(id)`, ...). Names are read in any case. A compiled
!> expression lists the measures it reads as inputs (expression_input_type); the caller
!> computes their values and passes them in that order (rollcon_measures). A value outside a
!> function's domain (LOG of a negative number, STEP with x1 <= x0) evaluates to NaN: callers
!> check the result with ieee_is_finite and name the expression. The functions of SIN to IF
!> keep their own value code here; those after them are evaluated through their jet form
!> (rollcon_expression_functions) with constant arguments, the same code their partials use.
!>
!> Where an expression switches (an IF's condition; a STEP's, STEP5's or HAVSIN's x at x0 and
!> x1; MIN, MAX and DIM where their arguments are equal; ABS at zero; SIGN(a, b) where a or b
!> is zero; IMPACT's and BISTOP's x at their free lengths and the ends of their damping;
!> AKISPL's and CUBSPL's x at the corners of their curve, rollcon_spline's spline_corners) it
!> has a corner, which an integrator must not step across (docs/design.md §7): a switch on
!> TIME alone is found here as a time (switching_times), any other is a function of the state
!> whose zero an integrator locates (switch_values).
module rollcon_expression
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_jet, only : jet_type, jet_constant
    use rollcon_spline, only : spline_type, method_akima, method_cubic, spline_corners, &
        & spline_corner_switch
    use rollcon_expression_functions, only : jet_step5, jet_shf, jet_poly, jet_cheby, &
        & jet_fourier, jet_impact, jet_bistop, jet_dim, jet_mod, jet_aint, jet_anint, jet_sign, &
        & jet_asin_domain, jet_acos_domain, jet_spline, nan_jet
    use rollcon_jet, only : atan, sinh, cosh, tanh, log10
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_is_finite
    implicit none
    private

    public :: expression_type, expression_input_type, evaluate_expression, switching_times
    public :: switch_kinds, switch_count, switch_values, switch_none, switch_timed, switch_watched
    public :: max_stack, max_inputs, max_arguments
    public :: op_constant, op_time, op_input, op_add, op_subtract, op_multiply, op_divide, &
        & op_power, op_negate, op_sin, op_cos, op_tan, op_exp, op_log, op_sqrt, op_abs, &
        & op_atan2, op_min, op_max, op_step, op_havsin, op_if
    public :: op_step5, op_shf, op_poly, op_cheby, op_forcos, op_forsin, op_impact, op_bistop, &
        & op_dim, op_mod, op_aint, op_anint, op_sign, op_asin, op_acos, op_atan, op_sinh, &
        & op_cosh, op_tanh, op_log10, op_akispl, op_cubspl, first_further_op, last_further_op
    public :: function_names, function_codes, function_arguments, operation_arity
    public :: spline_reference, spline_id_of, spline_order_of, further_jet
    public :: quantity_names, quantity_dx, quantity_vx, quantity_wx, quantity_psi
    public :: quantity_dm, quantity_vm, quantity_vr, quantity_wm, quantity_ax, quantity_yaw, &
        & quantity_accx, quantity_accm, quantity_wdtx, quantity_wdtm, quantity_fx, quantity_fm, &
        & quantity_tx, quantity_tm, quantity_varval, quantity_dif, quantity_dif1, &
        & quantity_joint, quantity_orient, quantity_least_markers, quantity_most_markers, &
        & quantity_kind, orient_systems, orient_components
    public :: kind_length, kind_velocity, kind_angular_velocity, kind_angle, kind_acceleration, &
        & kind_angular_acceleration, kind_force, kind_torque, kind_element, kind_element_force

    !> Deepest stack a compiled expression may need
    integer, parameter :: max_stack = 64
    !> Most distinct state functions one expression may use
    integer, parameter :: max_inputs = 32

    ! operation codes of the stack program
    integer, parameter :: op_constant = 1, op_time = 2, op_add = 3, op_subtract = 4, &
        & op_multiply = 5, op_divide = 6, op_power = 7, op_negate = 8, op_sin = 9, op_cos = 10, &
        & op_tan = 11, op_exp = 12, op_log = 13, op_sqrt = 14, op_abs = 15, op_atan2 = 16, &
        & op_min = 17, op_max = 18, op_step = 19, op_havsin = 20, op_if = 21, op_input = 22
    ! ADAMS's further functions, evaluated through their jet form (rollcon_expression_functions)
    integer, parameter :: op_step5 = 23, op_shf = 24, op_poly = 25, op_cheby = 26, &
        & op_forcos = 27, op_forsin = 28, op_impact = 29, op_bistop = 30, op_dim = 31, &
        & op_mod = 32, op_aint = 33, op_anint = 34, op_sign = 35, op_asin = 36, op_acos = 37, &
        & op_atan = 38, op_sinh = 39, op_cosh = 40, op_tanh = 41, op_log10 = 42, &
        & op_akispl = 43, op_cubspl = 44
    integer, parameter :: first_further_op = op_step5, last_further_op = op_cubspl
    !> Most arguments of one function (FORCOS: x, x0, w and a0 ... a30)
    integer, parameter :: max_arguments = 34

    !> Function names, their operation codes and argument counts (IF is parsed apart). A
    !> negative count -m: at least m arguments and at most max_arguments (POLY, CHEBY: x, x0,
    !> a0, ..., a30; FORCOS, FORSIN: x, x0, w, a0, ..., a30), the count kept in the operation's
    !> constant slot. AKISPL and CUBSPL take (x, z, id[, iord]): x and z are expressions, id
    !> and iord whole numbers kept in the constant slot (spline_reference).
    character(len=*), parameter :: function_names(34) = [character(len=6) :: "SIN", "COS", &
        & "TAN", "ATAN2", "EXP", "LOG", "SQRT", "ABS", "MIN", "MAX", "STEP", "HAVSIN", &
        & "STEP5", "SHF", "POLY", "CHEBY", "FORCOS", "FORSIN", "IMPACT", "BISTOP", "DIM", "MOD", &
        & "AINT", "ANINT", "SIGN", "ASIN", "ACOS", "ATAN", "SINH", "COSH", "TANH", "LOG10", &
        & "AKISPL", "CUBSPL"]
    integer, parameter :: function_codes(34) = [op_sin, op_cos, op_tan, op_atan2, op_exp, &
        & op_log, op_sqrt, op_abs, op_min, op_max, op_step, op_havsin, op_step5, op_shf, &
        & op_poly, op_cheby, op_forcos, op_forsin, op_impact, op_bistop, op_dim, op_mod, &
        & op_aint, op_anint, op_sign, op_asin, op_acos, op_atan, op_sinh, op_cosh, op_tanh, &
        & op_log10, op_akispl, op_cubspl]
    integer, parameter :: function_arguments(34) = [1, 1, 1, 2, 1, 1, 1, 1, 2, 2, 5, 5, 5, 6, &
        & -3, -3, -4, -4, 7, 8, 2, 2, 1, 1, 2, 1, 1, 1, 1, 1, 1, 1, 2, 2]

    !> What an operation of a program is as a switch (switch_kinds): none; a switch on TIME
    !> alone, at times switching_times gives; a switch on anything else, whose zero an
    !> integrator locates (switch_values)
    integer, parameter :: switch_none = 0, switch_timed = 1, switch_watched = 2
    !> Most switch functions of one operation (BISTOP's four) and the most arguments they read
    !> (BISTOP's d is its eighth)
    integer, parameter :: max_switches = 4, max_switch_arguments = 8

    !> Measures of markers and values of other statements an expression reads; quantity code
    !> q is quantity_names(q). The markers each takes (i, j, k, l; those not given are the
    !> ground origin and axes): quantity_least_markers to quantity_most_markers. The element
    !> functions (JOINT ... CONTACT) take (id, jflag, comp, rm), VARVAL, DIF and DIF1 an id;
    !> ORIENT(system, component, i[, j]) its system and component (expression_input_type's) and
    !> markers i, j.
    character(len=*), parameter :: quantity_names(58) = [character(len=8) :: "DX", "DY", "DZ", &
        & "VX", "VY", "VZ", "WX", "WY", "WZ", "PSI", "THETA", "PHI", "DM", "VM", "VR", "WM", &
        & "AX", "AY", "AZ", "YAW", "PITCH", "ROLL", "ACCX", "ACCY", "ACCZ", "ACCM", "WDTX", &
        & "WDTY", "WDTZ", "WDTM", "FX", "FY", "FZ", "FM", "TX", "TY", "TZ", "TM", "VARVAL", &
        & "DIF", "DIF1", "JOINT", "JPRIM", "MOTION", "SFORCE", "VFORCE", "VTORQUE", "GFORCE", &
        & "BUSHING", "BEAM", "FIELD", "SPDP", "NFORCE", "PTCV", "CVCV", "FRICTION", "CONTACT", &
        & "ORIENT"]
    !> First code of each group (x, y, z or psi, theta, phi follow in order)
    integer, parameter :: quantity_dx = 1, quantity_vx = 4, quantity_wx = 7, quantity_psi = 10, &
        & quantity_dm = 13, quantity_vm = 14, quantity_vr = 15, quantity_wm = 16, &
        & quantity_ax = 17, quantity_yaw = 20, quantity_accx = 23, quantity_accm = 26, &
        & quantity_wdtx = 27, quantity_wdtm = 30, quantity_fx = 31, quantity_fm = 34, &
        & quantity_tx = 35, quantity_tm = 38, quantity_varval = 39, quantity_dif = 40, &
        & quantity_dif1 = 41, quantity_joint = 42, quantity_orient = 58
    !> ADAMS's ORIENT: the orientation systems (1 to 29) and the number of components of each:
    !> 1-24 three angles, 25 AX, AY, AZ, 26 YAW, PITCH, ROLL, 27 four Euler parameters, 28
    !> three Rodrigues parameters, 29 nine direction cosines (docs/datasets.md, "ORIENT")
    integer, parameter :: orient_systems = 29
    integer, parameter :: orient_components(orient_systems) = [3, 3, 3, 3, 3, 3, 3, 3, 3, 3, &
        & 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 4, 3, 9]
    integer, parameter :: quantity_least_markers(58) = [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, &
        & 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, &
        & 1, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 1]
    integer, parameter :: quantity_most_markers(58) = [3, 3, 3, 4, 4, 4, 3, 3, 3, 2, 2, 2, 2, &
        & 3, 3, 2, 2, 2, 2, 2, 2, 2, 4, 4, 4, 3, 4, 4, 4, 3, 3, 3, 3, 3, 3, 3, 3, 3, 1, 1, 1, &
        & 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 2]
    !> What each measures, for its units: a length, a velocity, an angular velocity, an angle,
    !> an acceleration, an angular acceleration, a force, a torque, the value of a VARIABLE or
    !> DIFF (its own units), an element's force or torque (by its comp); ORIENT's angles and
    !> parameters are counted as angles (no unit to scale)
    integer, parameter :: kind_length = 1, kind_velocity = 2, kind_angular_velocity = 3, &
        & kind_angle = 4, kind_acceleration = 5, kind_angular_acceleration = 6, kind_force = 7, &
        & kind_torque = 8, kind_element = 9, kind_element_force = 10
    integer, parameter :: quantity_kind(58) = [1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 1, 2, 2, &
        & 3, 4, 4, 4, 4, 4, 4, 5, 5, 5, 5, 6, 6, 6, 6, 7, 7, 7, 7, 8, 8, 8, 8, 9, 9, 9, 10, &
        & 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 4]

    !> One measure (or value of another statement) an expression reads
    type :: expression_input_type
        !> Marker i (as in the dataset); for an element function its id, for VARVAL, DIF and
        !> DIF1 the VARIABLE's or DIFF's id
        integer :: marker = 0
        !> Quantity code (quantity_names)
        integer :: quantity = 0
        !> Markers j, k and l (0: not given, the ground origin and axes); for an element
        !> function jflag, comp and rm
        integer :: j = 0, k = 0, l = 0
        !> ORIENT's orientation system (1 to orient_systems) and component (0 for the others)
        integer :: system = 0, component = 0
    end type expression_input_type

    !> A compiled expression
    type :: expression_type
        !> The expression as written
        character(len=:), allocatable :: text
        !> Operation codes, in order
        integer, allocatable :: op(:)
        !> The constant of each op_constant operation; for op_input, the input's number; for a
        !> function of a variable number of arguments, their count; for AKISPL and CUBSPL,
        !> spline_reference (0 elsewhere)
        real(wp), allocatable :: constant(:)
        !> The measures read, in the order their values are passed
        type(expression_input_type), allocatable :: inputs(:)
        !> True when the expression depends on TIME
        logical :: uses_time = .false.
        !> For each input that is an angle ADAMS counts whole turns of (AX, AY, AZ): the value
        !> it had where its turns were last counted [rad] (rollcon_measures' count_turns); the
        !> value passed is the one of its 2 pi branches nearest to it (0 when not allocated)
        real(wp), allocatable :: anchors(:)
        !> The curves AKISPL and CUBSPL read, by their SPLINE id (given by whoever assembles
        !> the expression; a curve not given evaluates to NaN)
        type(spline_type), allocatable :: splines(:)
    end type expression_type

contains

    !> Value of the expression at `time` with its inputs' values; NaN outside a function's
    !> domain, and where an input is read that is not given.
    pure function evaluate_expression(expression, time, inputs) result(value)
        type(expression_type), intent(in) :: expression
        !> Time, in the expression's units
        real(wp), intent(in) :: time
        !> Values of expression%inputs, in that order, in the expression's units
        real(wp), intent(in), optional :: inputs(:)
        real(wp) :: value

        call run_program(expression, time, value, inputs)
    end function evaluate_expression

    !> Run the stack program at `time` with the inputs' values: its value and, when kinds and g
    !> are given, the switch functions of its watched switches (switch_values).
    pure subroutine run_program(expression, time, value, inputs, kinds, g)
        type(expression_type), intent(in) :: expression
        real(wp), intent(in) :: time
        real(wp), intent(out) :: value
        real(wp), intent(in), optional :: inputs(:)
        integer, intent(in), optional :: kinds(:)
        real(wp), intent(out), optional :: g(:)
        real(wp) :: stack(max_stack)
        integer :: i, top, k, j

        top = 0
        j = 0
        do i = 1, size(expression%op)
            if (present(kinds) .and. present(g)) then
                if (kinds(i) == switch_watched) then
                    k = operation_arity(expression%op(i), expression%constant(i))
                    if (is_spline(expression%op(i))) then
                        ! the curve's corner switch of its x, the first argument
                        j = j + 1
                        g(j) = spline_corner_switch(expression%splines(spline_index(expression, &
                            & i)), stack(top - k + 1))
                    else
                        call add_switch(expression%op(i), stack(top - k + 1:top), g, j)
                    end if
                end if
            end if
            select case (expression%op(i))
            case (op_constant)
                top = top + 1
                stack(top) = expression%constant(i)
            case (op_time)
                top = top + 1
                stack(top) = time
            case (op_input)
                top = top + 1
                k = nint(expression%constant(i))
                stack(top) = nan()
                if (present(inputs)) then
                    if (k <= size(inputs)) stack(top) = inputs(k)
                end if
            case (op_negate)
                stack(top) = -stack(top)
            case (op_sin:op_abs)
                stack(top) = unary(expression%op(i), stack(top))
            case (op_add:op_power, op_atan2:op_max)
                top = top - 1
                stack(top) = binary(expression%op(i), stack(top), stack(top + 1))
            case (op_step, op_havsin)
                top = top - 4
                stack(top) = smooth_step(expression%op(i) == op_havsin, stack(top:top + 4))
            case (op_if)
                top = top - 3
                stack(top) = if_branch(stack(top:top + 3))
            case (first_further_op:last_further_op)
                k = operation_arity(expression%op(i), expression%constant(i))
                top = top - k + 1
                stack(top) = further_value(expression, i, stack(top:top + k - 1))
            end select
        end do
        value = stack(1)
    end subroutine run_program

    !> The switch functions of operation op as combinations of its arguments: switch r (1 to
    !> n) is the sum over k of c(r, k) times argument k (n = 0: op does not switch). IF: its
    !> condition; ABS: its argument; MIN, MAX, DIM: a - b; STEP, STEP5, HAVSIN: x - x0,
    !> x - x1; SIGN(a, b): b, a; IMPACT(x, xdot, x1, k, e, cmax, d): x - (x1 - d), x - x1;
    !> BISTOP(x, xdot, x1, x2, k, e, cmax, d): x - (x1 - d), x - x1, x - x2, x - (x2 + d).
    !> MOD, AINT and ANINT jump wherever their argument passes a whole number (of b): such
    !> periodic switches are not among them.
    pure subroutine switch_combinations(op, c, n)
        integer, intent(in) :: op
        real(wp), intent(out) :: c(max_switches, max_switch_arguments)
        integer, intent(out) :: n

        c = 0.0_wp
        select case (op)
        case (op_if, op_abs)
            n = 1
            c(1, 1) = 1.0_wp
        case (op_min, op_max, op_dim)
            n = 1
            c(1, 1:2) = [1.0_wp, -1.0_wp]
        case (op_step, op_step5, op_havsin)
            n = 2
            c(1, 1:2) = [1.0_wp, -1.0_wp]
            c(2, [1, 4]) = [1.0_wp, -1.0_wp]
        case (op_sign)
            n = 2
            c(1, 2) = 1.0_wp
            c(2, 1) = 1.0_wp
        case (op_impact)
            n = 2
            c(1, [1, 3, 7]) = [1.0_wp, -1.0_wp, 1.0_wp]
            c(2, [1, 3]) = [1.0_wp, -1.0_wp]
        case (op_bistop)
            n = 4
            c(1, [1, 3, 8]) = [1.0_wp, -1.0_wp, 1.0_wp]
            c(2, [1, 3]) = [1.0_wp, -1.0_wp]
            c(3, [1, 4]) = [1.0_wp, -1.0_wp]
            c(4, [1, 4, 8]) = [1.0_wp, -1.0_wp, -1.0_wp]
        case default
            n = 0
        end select
    end subroutine switch_combinations

    !> The switch functions of the watched switch op from its arguments' values, into g after
    !> the j already there (j counts them).
    pure subroutine add_switch(op, arguments, g, j)
        integer, intent(in) :: op
        real(wp), intent(in) :: arguments(:)
        real(wp), intent(inout) :: g(:)
        integer, intent(inout) :: j
        real(wp) :: c(max_switches, max_switch_arguments)
        integer :: n, r, k

        call switch_combinations(op, c, n)
        do r = 1, n
            g(j + r) = 0.0_wp
            do k = 1, min(size(arguments), max_switch_arguments)
                if (c(r, k) /= 0.0_wp) g(j + r) = g(j + r) + c(r, k)*arguments(k)
            end do
        end do
        j = j + n
    end subroutine add_switch

    !> The value of operation i (one of ADAMS's further functions) of the program from its
    !> arguments, through the function's jet form with constant arguments.
    pure function further_value(expression, i, arguments) result(value)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: i
        real(wp), intent(in) :: arguments(:)
        real(wp) :: value
        type(jet_type) :: args(size(arguments)), result
        integer :: s

        args = jet_constant(arguments)
        select case (expression%op(i))
        case (op_akispl, op_cubspl)
            result = nan_jet()
            if (allocated(expression%splines)) then
                s = findloc(expression%splines%id, spline_id_of(expression%constant(i)), dim=1)
                if (s > 0) result = jet_spline(args(1), expression%splines(s), &
                    & merge(method_akima, method_cubic, expression%op(i) == op_akispl), &
                    & spline_order_of(expression%constant(i)))
            end if
        case default
            result = further_jet(expression%op(i), args)
        end select
        value = result%v
    end function further_value

    !> One of ADAMS's further functions of numbers (not AKISPL or CUBSPL) of its arguments'
    !> jets: the one code of its value and of its partials (rollcon_expression_jet).
    pure function further_jet(op, args) result(y)
        integer, intent(in) :: op
        type(jet_type), intent(in) :: args(:)
        type(jet_type) :: y

        select case (op)
        case (op_step5)
            y = jet_step5(args(1), args(2), args(3), args(4), args(5))
        case (op_shf)
            y = jet_shf(args(1), args(2), args(3), args(4), args(5), args(6))
        case (op_poly)
            y = jet_poly(args)
        case (op_cheby)
            y = jet_cheby(args)
        case (op_forcos, op_forsin)
            y = jet_fourier(op == op_forcos, args)
        case (op_impact)
            y = jet_impact(args(1), args(2), args(3), args(4), args(5), args(6), args(7))
        case (op_bistop)
            y = jet_bistop(args(1), args(2), args(3), args(4), args(5), args(6), args(7), &
                & args(8))
        case (op_dim)
            y = jet_dim(args(1), args(2))
        case (op_mod)
            y = jet_mod(args(1), args(2))
        case (op_aint)
            y = jet_aint(args(1))
        case (op_anint)
            y = jet_anint(args(1))
        case (op_sign)
            y = jet_sign(args(1), args(2))
        case (op_asin)
            y = jet_asin_domain(args(1))
        case (op_acos)
            y = jet_acos_domain(args(1))
        case (op_atan)
            y = atan(args(1))
        case (op_sinh)
            y = sinh(args(1))
        case (op_cosh)
            y = cosh(args(1))
        case (op_tanh)
            y = tanh(args(1))
        case (op_log10)
            y = nan_jet()
            if (args(1)%v > 0.0_wp) y = log10(args(1))
        case default
            y = nan_jet()
        end select
    end function further_jet

    !> How many values operation `op` takes from the stack (1 for a value it pushes: the
    !> constants, TIME and inputs take none and leave one); `constant` is its constant slot.
    pure integer function operation_arity(op, constant) result(arity)
        integer, intent(in) :: op
        real(wp), intent(in) :: constant
        integer :: k

        select case (op)
        case (op_constant, op_time, op_input)
            arity = 0
        case (op_negate, op_sin:op_abs)
            arity = 1
        case (op_step, op_havsin)
            arity = 5
        case (op_if)
            arity = 4
        case (first_further_op:last_further_op)
            k = findloc(function_codes, op, dim=1)
            arity = function_arguments(k)
            ! a variadic function keeps its count in the constant slot
            if (arity < 0) arity = nint(constant)
        case default
            arity = 2
        end select
    end function operation_arity

    !> The constant slot of AKISPL or CUBSPL: SPLINE/id and the order of the derivative.
    pure real(wp) function spline_reference(id, order)
        integer, intent(in) :: id, order

        spline_reference = 4.0_wp*real(id, wp) + real(order, wp)
    end function spline_reference

    !> The SPLINE id of a constant slot made by spline_reference.
    pure integer function spline_id_of(constant)
        real(wp), intent(in) :: constant

        spline_id_of = nint(constant)/4
    end function spline_id_of

    !> The order of the derivative of a constant slot made by spline_reference.
    pure integer function spline_order_of(constant)
        real(wp), intent(in) :: constant

        spline_order_of = mod(nint(constant), 4)
    end function spline_order_of

    !> IF(e: negative, zero, positive) from its four values.
    pure function if_branch(arguments) result(y)
        real(wp), intent(in) :: arguments(4)
        real(wp) :: y

        if (arguments(1) < 0.0_wp) then
            y = arguments(2)
        else if (arguments(1) > 0.0_wp) then
            y = arguments(4)
        else
            y = arguments(3)
        end if
    end function if_branch

    !> The times at which the expression switches: where a switch function of an operation
    !> (switch_combinations: an IF's condition, x - x0 and x - x1 of a STEP, STEP5 or HAVSIN,
    !> a - b of MIN, MAX or DIM, the argument of ABS, ...) is a TIME + b (a /= 0, a and b
    !> constants) and crosses zero, and where the x of AKISPL or CUBSPL, a TIME + b, meets a
    !> corner of its curve (spline_corners). A switch on anything else (a state function, a
    !> product of TIME) is not found here: switch_kinds calls it watched. In the expression's
    !> time units, in the order the program meets them (an inner IF before the IF around it). A
    !> time that is not finite (constants whose product or sum overflows: the switch never
    !> happens) is left out.
    pure function switching_times(expression) result(times)
        type(expression_type), intent(in) :: expression
        real(wp), allocatable :: times(:)
        integer, allocatable :: kinds(:)

        call analyse_switches(expression, kinds, times)
    end function switching_times

    !> For each operation of the program: switch_none, switch_timed (its times are among
    !> switching_times) or switch_watched (a switch whose argument is not affine in TIME: a
    !> state function, or TIME in a non-affine way).
    pure function switch_kinds(expression) result(kinds)
        type(expression_type), intent(in) :: expression
        integer, allocatable :: kinds(:)
        real(wp), allocatable :: times(:)

        call analyse_switches(expression, kinds, times)
    end function switch_kinds

    !> Number of switch functions switch_values gives for these kinds: each watched
    !> operation's (switch_combinations; two for a STEP, STEP5, HAVSIN, SIGN or IMPACT, four
    !> for a BISTOP, one for the others, and one for AKISPL or CUBSPL, zero at every corner of
    !> its curve).
    pure integer function switch_count(expression, kinds)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: kinds(:)
        real(wp) :: c(max_switches, max_switch_arguments)
        integer :: i, n

        switch_count = 0
        do i = 1, size(kinds)
            if (kinds(i) /= switch_watched) cycle
            if (is_spline(expression%op(i))) then
                ! one switch function for all the curve's corners (spline_corner_switch)
                n = 1
            else
                call switch_combinations(expression%op(i), c, n)
            end if
            switch_count = switch_count + n
        end do
    end function switch_count

    !> The switch functions of the watched switches (kinds from switch_kinds) at `time` with
    !> the inputs' values, in program order, each zero where its switch switches: an IF's
    !> condition, x - x0 and x - x1 of a STEP, STEP5 or HAVSIN, a - b of MIN(a, b), MAX(a, b)
    !> and DIM(a, b), the argument of ABS, ... (switch_combinations), and AKISPL's and
    !> CUBSPL's spline_corner_switch of their x. g has switch_count
    !> values. Allocates nothing (an event function of the integrators).
    pure subroutine switch_values(expression, time, inputs, kinds, g)
        type(expression_type), intent(in) :: expression
        !> Time, in the expression's units
        real(wp), intent(in) :: time
        !> Values of expression%inputs, in that order, in the expression's units
        real(wp), intent(in) :: inputs(:)
        integer, intent(in) :: kinds(:)
        real(wp), intent(out) :: g(:)
        real(wp) :: value

        call run_program(expression, time, value, inputs, kinds, g)
    end subroutine switch_values

    !> The switches of the program: each pending value as slope*TIME + offset when affine
    !> (slope 0: a constant), each switch function of an operation (switch_combinations) the
    !> same combination of its arguments' forms.
    pure subroutine analyse_switches(expression, kinds, times)
        type(expression_type), intent(in) :: expression
        integer, allocatable, intent(out) :: kinds(:)
        real(wp), allocatable, intent(out) :: times(:)
        real(wp) :: slope(max_stack), offset(max_stack)
        logical :: affine(max_stack)
        real(wp) :: c(max_switches, max_switch_arguments)
        real(wp) :: slopes(max_switches), offsets(max_switches)
        logical :: affines(max_switches)
        integer :: i, top, op, arity, n, r, k

        allocate(times(0))
        allocate(kinds(size(expression%op)), source=switch_none)
        top = 0
        do i = 1, size(expression%op)
            op = expression%op(i)
            select case (op)
            case (op_constant, op_time, op_input)
                top = top + 1
                affine(top) = op /= op_input
                slope(top) = merge(1.0_wp, 0.0_wp, op == op_time)
                offset(top) = merge(expression%constant(i), 0.0_wp, op == op_constant)
                cycle
            case (op_negate)
                slope(top) = -slope(top)
                offset(top) = -offset(top)
                cycle
            end select
            arity = operation_arity(op, expression%constant(i))
            top = top - arity + 1
            if (is_spline(op)) then
                call classify_knots(expression, i, kinds(i), times, slope(top), offset(top), &
                    & affine(top))
                call combine(op, arity, slope(top:top + arity - 1), &
                    & offset(top:top + arity - 1), affine(top:top + arity - 1))
                cycle
            end if
            call switch_combinations(op, c, n)
            do r = 1, n
                slopes(r) = 0.0_wp
                offsets(r) = 0.0_wp
                affines(r) = .true.
                do k = 1, min(arity, max_switch_arguments)
                    if (c(r, k) == 0.0_wp) cycle
                    slopes(r) = slopes(r) + c(r, k)*slope(top + k - 1)
                    offsets(r) = offsets(r) + c(r, k)*offset(top + k - 1)
                    affines(r) = affines(r) .and. affine(top + k - 1)
                end do
            end do
            if (n > 0) call classify(kinds(i), times, slopes(:n), offsets(:n), affines(:n))
            call combine(op, arity, slope(top:top + arity - 1), offset(top:top + arity - 1), &
                & affine(top:top + arity - 1))
        end do
    end subroutine analyse_switches

    !> The switch of AKISPL or CUBSPL (operation i) at the corners of its curve
    !> (spline_corners), its x = slope*TIME + offset when affine: timed at the times x meets
    !> them when x is affine and not constant, watched when x is not affine; none for a curve
    !> without corners (or one the expression does not hold, whose value is NaN) or a constant
    !> x. z is not a switch: the curve does not depend on it.
    pure subroutine classify_knots(expression, i, kind, times, slope, offset, affine)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: i
        integer, intent(inout) :: kind
        real(wp), allocatable, intent(inout) :: times(:)
        real(wp), intent(in) :: slope, offset
        logical, intent(in) :: affine
        real(wp), allocatable :: corners(:)
        integer :: s

        s = spline_index(expression, i)
        if (s == 0) return
        corners = spline_corners(expression%splines(s))
        if (size(corners) == 0) return
        if (.not. affine) then
            kind = switch_watched
        else if (slope /= 0.0_wp) then
            kind = switch_timed
            call add_finite(times, (corners - offset)/slope)
        end if
    end subroutine classify_knots

    !> True for the curves AKISPL and CUBSPL.
    pure logical function is_spline(op)
        integer, intent(in) :: op

        is_spline = op == op_akispl .or. op == op_cubspl
    end function is_spline

    !> The place among expression%splines of the curve operation i (AKISPL or CUBSPL) reads,
    !> 0 when the expression does not hold it.
    pure integer function spline_index(expression, i) result(s)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: i
        integer :: k

        s = 0
        if (.not. allocated(expression%splines)) return
        do k = 1, size(expression%splines)
            if (expression%splines(k)%id == spline_id_of(expression%constant(i))) then
                s = k
                return
            end if
        end do
    end function spline_index

    !> A switch where each slope*TIME + offset (when affine) is zero: timed, its times added,
    !> when every one is affine (a constant one, of slope 0, never switches), else watched.
    pure subroutine classify(kind, times, slopes, offsets, affines)
        integer, intent(inout) :: kind
        real(wp), allocatable, intent(inout) :: times(:)
        real(wp), intent(in) :: slopes(:), offsets(:)
        logical, intent(in) :: affines(:)

        if (.not. all(affines)) then
            kind = switch_watched
        else if (any(slopes /= 0.0_wp)) then
            kind = switch_timed
            call add_finite(times, pack(-offsets/slopes, slopes /= 0.0_wp))
        end if
    end subroutine classify

    !> Append the finite ones of candidates to times.
    pure subroutine add_finite(times, candidates)
        real(wp), allocatable, intent(inout) :: times(:)
        real(wp), intent(in) :: candidates(:)

        times = [times, pack(candidates, ieee_is_finite(candidates))]
    end subroutine add_finite

    !> The affine form of an operation's result from its arguments' (first element on return).
    pure subroutine combine(op, arity, slope, offset, affine)
        integer, intent(in) :: op, arity
        real(wp), intent(inout) :: slope(arity), offset(arity)
        logical, intent(inout) :: affine(arity)
        real(wp) :: values(max_arguments)
        type(jet_type) :: folded

        if (op == op_akispl .or. op == op_cubspl) then
            ! a curve's points are not known here: not a constant
            affine(1) = .false.
            return
        end if
        if (all(affine) .and. all(slope == 0.0_wp)) then
            ! constants only: fold
            values(:arity) = offset
            select case (op)
            case (op_sin:op_abs)
                offset(1) = unary(op, values(1))
            case (op_step, op_havsin)
                offset(1) = smooth_step(op == op_havsin, values(:5))
            case (op_if)
                offset(1) = if_branch(values(:4))
            case (first_further_op:last_further_op)
                folded = further_jet(op, jet_constant(values(:arity)))
                offset(1) = folded%v
            case default
                offset(1) = binary(op, values(1), values(2))
            end select
            return
        end if
        affine(1) = all(affine) .and. arity == 2
        if (.not. affine(1)) return
        select case (op)
        case (op_add)
            slope(1) = slope(1) + slope(2)
            offset(1) = offset(1) + offset(2)
        case (op_subtract)
            slope(1) = slope(1) - slope(2)
            offset(1) = offset(1) - offset(2)
        case (op_multiply)
            affine(1) = slope(1) == 0.0_wp .or. slope(2) == 0.0_wp
            slope(1) = slope(1)*offset(2) + slope(2)*offset(1)
            offset(1) = offset(1)*offset(2)
        case (op_divide)
            affine(1) = slope(2) == 0.0_wp .and. offset(2) /= 0.0_wp
            if (affine(1)) slope(1) = slope(1)/offset(2)
            if (affine(1)) offset(1) = offset(1)/offset(2)
        case default
            affine(1) = .false.
        end select
    end subroutine combine

    pure function unary(op, x) result(y)
        integer, intent(in) :: op
        real(wp), intent(in) :: x
        real(wp) :: y

        select case (op)
        case (op_sin)
            y = sin(x)
        case (op_cos)
            y = cos(x)
        case (op_tan)
            y = tan(x)
        case (op_exp)
            y = exp(x)
        case (op_log)
            y = nan()
            if (x > 0.0_wp) y = log(x)
        case (op_sqrt)
            y = nan()
            if (x >= 0.0_wp) y = sqrt(x)
        case default
            y = abs(x)
        end select
    end function unary

    pure function binary(op, a, b) result(y)
        integer, intent(in) :: op
        real(wp), intent(in) :: a, b
        real(wp) :: y

        select case (op)
        case (op_add)
            y = a + b
        case (op_subtract)
            y = a - b
        case (op_multiply)
            y = a*b
        case (op_divide)
            y = nan()
            if (b /= 0.0_wp) y = a/b
        case (op_power)
            ! a negative base only with a whole exponent, as Fortran's real power allows
            y = nan()
            if (a > 0.0_wp .or. (a == 0.0_wp .and. b > 0.0_wp)) then
                y = a**b
            else if (a < 0.0_wp .and. b == aint(b) .and. abs(b) < 1.0e9_wp) then
                y = a**nint(b)
            end if
        case (op_atan2)
            y = atan2(a, b)
        case (op_min)
            y = min(a, b)
        case default
            y = max(a, b)
        end select
    end function binary

    !> ADAMS's STEP (cubic, C1) or HAVSIN (haversine) from h0 at x0 to h1 at x1; NaN unless
    !> x0 < x1. Arguments: x, x0, h0, x1, h1.
    pure function smooth_step(haversine, arguments) result(y)
        logical, intent(in) :: haversine
        real(wp), intent(in) :: arguments(5)
        real(wp) :: y
        real(wp) :: s

        associate (x => arguments(1), x0 => arguments(2), h0 => arguments(3), &
            & x1 => arguments(4), h1 => arguments(5))
            if (.not. x0 < x1) then
                y = nan()
            else if (x <= x0) then
                y = h0
            else if (x >= x1) then
                y = h1
            else
                s = (x - x0)/(x1 - x0)
                if (haversine) then
                    y = 0.5_wp*(h0 + h1) + 0.5_wp*(h1 - h0)*sin(pi*s - 0.5_wp*pi)
                else
                    y = h0 + (h1 - h0)*s**2*(3.0_wp - 2.0_wp*s)
                end if
            end if
        end associate
    end function smooth_step

    pure function nan()
        real(wp) :: nan

        nan = ieee_value(nan, ieee_quiet_nan)
    end function nan

end module rollcon_expression
