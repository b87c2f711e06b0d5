! SPDX-License-Identifier: MIT
!> GCON: a constraint F = 0 written as a function expression of markers' measures and TIME
!> (ADAMS's `GCON/id, I=, FUNCTION=e`; docs/datasets.md, "GCON"), served to the driver as a
!> UCON: its variables are the coordinates (and, when it reads velocities, the rates) of every
!> part whose markers it reads, declared as a UCOSUB's UCOVAR would, and evaluate_gcon answers
!> exactly as evaluate_ucon does for a UCOSUB (SCALAR, ARRAY, XMATRX by IDRSEL over the
!> declared variables, the time partials), so every formulation, the initial-conditions
!> analysis and the linearisation use it unchanged. The partials are exact: the expression is
!> evaluated in jets (rollcon_expression_jet) over those variables and TIME, through the
!> markers' kinematics (rollcon_measures). A GCON that reads a velocity is a velocity
!> constraint, which must be linear in the rates (checked where it is made, new_gcon).
module rollcon_gcon
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_error, only : error_type, ucon_error
    use rollcon_ucosub_contract, only : max_ucon_vars, scalar_none, scalar_value, scalar_dt, &
        & scalar_dtt, array_none, array_dq, array_dtdq, xmatrx_none, xmatrx_dqdq, code_x, &
        & code_xdot
    use rollcon_ucon_call, only : stat_non_finite
    use rollcon_jet, only : jet_type, jet_variable, jet_constant, operator(*)
    use rollcon_expression, only : expression_type, quantity_names
    use rollcon_expression_jet, only : evaluate_expression_jet
    use rollcon_marker, only : marker_type, turn_marker
    use rollcon_measures, only : state_jets_type, new_state_jets, expression_input_jets, &
        & input_markers, reads_rates, input_refusal
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: gcon_type, new_gcon, gcon_codes, evaluate_gcon, gcon_jet, turn_gcon_markers

    !> One GCON
    type :: gcon_type
        !> The statement's id, for messages ("GCON/1")
        integer :: id = 0
        !> F, in the dataset's units
        type(expression_type) :: expression
        !> Every marker the expression reads
        type(marker_type), allocatable :: markers(:)
        !> The marker I= names, where the constraint's reaction is reported
        type(marker_type) :: reaction
        !> Size of the dataset's length [m] and time [s] units
        real(wp) :: length_unit = 1.0_wp, time_unit = 1.0_wp
        !> The model index of every moving part whose markers it reads, ascending
        integer, allocatable :: parts(:)
        !> True when it reads a velocity: its variables are then each part's coordinates and
        !> rates, else its coordinates alone
        logical :: velocity = .false.
    end type gcon_type

    !> States new_gcon tries the linearity in the rates at: coordinates and rates with no
    !> relation to one another or to a geometry [m, rad, m/s, rad/s]
    real(wp), parameter :: trial_values(6, 2) = reshape([0.31_wp, -0.17_wp, 0.83_wp, &
        & 0.47_wp, 1.13_wp, -0.59_wp, -0.61_wp, 0.29_wp, -0.37_wp, 2.03_wp, 0.71_wp, 1.61_wp], &
        & [6, 2])

contains

    !> GCON/id of `expression` (in the dataset's units), reading `markers` (every marker its
    !> measures name, as the model holds them), its reaction reported at `reaction`. `problem`
    !> is "" or why it cannot be a constraint: it reads an acceleration, a force or another
    !> statement's value (an algebraic loop), a marker not given, no moving part, more than
    !> max_ucon_vars variables, or velocities in a way that is not linear.
    subroutine new_gcon(id, expression, markers, reaction, length_unit, time_unit, gcon, &
            & problem)
        integer, intent(in) :: id
        type(expression_type), intent(in) :: expression
        type(marker_type), intent(in) :: markers(:), reaction
        !> Size of the dataset's length [m] and time [s] units
        real(wp), intent(in) :: length_unit, time_unit
        type(gcon_type), intent(out) :: gcon
        character(len=:), allocatable, intent(out) :: problem
        type(marker_type) :: chosen(4)
        logical :: found(4)
        integer :: k, m, nvars

        problem = ""
        gcon%id = id
        gcon%expression = expression
        gcon%markers = markers
        gcon%reaction = reaction
        gcon%length_unit = length_unit
        gcon%time_unit = time_unit
        allocate(gcon%parts(0))
        do k = 1, size(expression%inputs)
            associate (input => expression%inputs(k))
                problem = input_refusal(input, "a constraint's FUNCTION")
                if (len(problem) > 0) return
                call input_markers(input, markers, chosen, found)
                if (.not. all(found)) then
                    problem = trim(quantity_names(input%quantity)) // ": a marker that was not " &
                        & // "given"
                    return
                end if
                gcon%velocity = gcon%velocity .or. reads_rates(input%quantity)
                do m = 1, 4
                    if (chosen(m)%part > 0 .and. .not. any(gcon%parts == chosen(m)%part)) &
                        & gcon%parts = [gcon%parts, chosen(m)%part]
                end do
            end associate
        end do
        if (size(gcon%parts) == 0) then
            problem = "it reads no marker of a moving part: F = " // expression%text &
                & // " constrains nothing"
            return
        end if
        call sort(gcon%parts)
        nvars = size(gcon%parts)*merge(12, 6, gcon%velocity)
        if (nvars > max_ucon_vars) then
            problem = "it reads the markers of " // to_text(size(gcon%parts)) // " parts: " &
                & // to_text(nvars) // " variables (" // merge("12", " 6", gcon%velocity) &
                & // " a part), more than a UCON's " // to_text(max_ucon_vars)
            return
        end if
        if (gcon%velocity) call check_linear_in_rates(gcon, problem)
    end subroutine new_gcon

    !> A velocity GCON's d2F/du du, zero at two trial states: F must be linear in the rates
    !> (docs/design.md §2), as a UCON's velocity constraint is.
    subroutine check_linear_in_rates(gcon, problem)
        type(gcon_type), intent(in) :: gcon
        character(len=:), allocatable, intent(inout) :: problem
        real(wp) :: values(max_ucon_vars)
        type(jet_type) :: f
        integer :: trial, s, n, i, j

        n = 12*size(gcon%parts)
        do trial = 1, 2
            do s = 1, size(gcon%parts)
                values(12*(s - 1) + 1:12*s) = [trial_values(:, trial), &
                    & trial_values(:, 3 - trial)*(1.0_wp + 0.1_wp*s)]
            end do
            f = gcon_jet(gcon, 0.0_wp, values(:n), 2, .false.)
            if (.not. allocated(f%h)) cycle
            if (.not. all(ieee_is_finite(f%h))) cycle
            do j = 1, n
                do i = 1, n
                    ! the rates are variables 7 to 12 of each part's twelve
                    if (mod(i - 1, 12) < 6 .or. mod(j - 1, 12) < 6) cycle
                    if (f%h(i, j) /= 0.0_wp) then
                        problem = "it reads velocities, but F is not linear in them " &
                            & // "(d2F/du du is not zero): a velocity constraint must be " &
                            & // "linear in the rates (docs/datasets.md, GCON)"
                        return
                    end if
                end do
            end do
        end do
    end subroutine check_linear_in_rates

    pure subroutine sort(list)
        integer, intent(inout) :: list(:)
        integer :: i, j, v

        do i = 2, size(list)
            v = list(i)
            j = i - 1
            do while (j >= 1)
                if (list(j) <= v) exit
                list(j + 1) = list(j)
                j = j - 1
            end do
            list(j + 1) = v
        end do
    end subroutine sort

    !> The UCOVAR declaration of a GCON: for each part it reads (in the order of gcon%parts),
    !> X, Y, Z, psi, theta, phi and, for a velocity GCON, their rates; part_ids(p) is the id of
    !> model part p.
    pure subroutine gcon_codes(gcon, part_ids, parts, codes)
        type(gcon_type), intent(in) :: gcon
        integer, intent(in) :: part_ids(:)
        integer, allocatable, intent(out) :: parts(:), codes(:)
        integer :: s, c, stride

        stride = merge(12, 6, gcon%velocity)
        allocate(parts(stride*size(gcon%parts)), codes(stride*size(gcon%parts)))
        do s = 1, size(gcon%parts)
            do c = 1, 6
                parts(stride*(s - 1) + c) = part_ids(gcon%parts(s))
                codes(stride*(s - 1) + c) = code_x + c - 1
                if (.not. gcon%velocity) cycle
                parts(stride*(s - 1) + 6 + c) = part_ids(gcon%parts(s))
                codes(stride*(s - 1) + 6 + c) = code_xdot + c - 1
            end do
        end do
    end subroutine gcon_codes

    !> F as a jet of order `order` (0: its value alone; 1, 2) over the declared variables
    !> (their values `values`, SI) and, when `with_time`, TIME as one more variable after them.
    pure function gcon_jet(gcon, time, values, order, with_time) result(f)
        type(gcon_type), intent(in) :: gcon
        !> Time [s]
        real(wp), intent(in) :: time
        !> The declared variables' values, in order [m, rad, m/s, rad/s]
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: order
        logical, intent(in) :: with_time
        type(jet_type) :: f
        type(state_jets_type) :: state
        type(jet_type) :: time_jet, inputs(size(gcon%expression%inputs))
        real(wp) :: q(6, size(gcon%parts)), u(6, size(gcon%parts))
        integer :: q_variable(6, size(gcon%parts)), u_variable(6, size(gcon%parts))
        integer :: s, c, stride, n

        stride = merge(12, 6, gcon%velocity)
        n = size(values) + merge(1, 0, with_time)
        u = 0.0_wp
        u_variable = 0
        do s = 1, size(gcon%parts)
            do c = 1, 6
                q(c, s) = values(stride*(s - 1) + c)
                q_variable(c, s) = merge(stride*(s - 1) + c, 0, order > 0)
                if (.not. gcon%velocity) cycle
                u(c, s) = values(stride*(s - 1) + 6 + c)
                u_variable(c, s) = merge(stride*(s - 1) + 6 + c, 0, order > 0)
            end do
        end do
        state = new_state_jets(gcon%parts, q, u, q_variable, u_variable, n, order > 1)
        if (with_time .and. order > 0) then
            time_jet = (1.0_wp/gcon%time_unit)*jet_variable(time, n, n, order > 1)
        else
            time_jet = jet_constant(time/gcon%time_unit)
        end if
        call expression_input_jets(gcon%expression, gcon%markers, gcon%length_unit, &
            & gcon%time_unit, state, inputs)
        f = evaluate_expression_jet(gcon%expression, time_jet, inputs)
    end function gcon_jet

    !> One evaluation of a GCON as evaluate_ucon makes one of a UCOSUB (rollcon_ucon_call):
    !> the selected outputs over the nvars declared variables, the rest untouched; what was
    !> selected must come back finite (else an error of kind stat_non_finite naming the UCON
    !> and the GCON). IDRSEL(1) = 2 (f(t)) is not provided: the driver never asks for it.
    subroutine evaluate_gcon(gcon, id, time, q, idrsel, scalar, array, xmatrx, error, nvars)
        type(gcon_type), intent(in) :: gcon
        !> The UCON's id
        integer, intent(in) :: id
        !> Time [s]
        real(wp), intent(in) :: time
        !> Values of the declared variables [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(max_ucon_vars)
        integer, intent(in) :: idrsel(3)
        real(wp), intent(inout) :: scalar, array(max_ucon_vars), &
            & xmatrx(max_ucon_vars, max_ucon_vars)
        type(error_type), allocatable, intent(out) :: error
        !> Number of declared variables
        integer, intent(in) :: nvars
        type(jet_type) :: f
        logical :: with_time, finite
        integer :: order, n

        with_time = idrsel(1) == scalar_dt .or. idrsel(1) == scalar_dtt &
            & .or. idrsel(2) == array_dtdq
        order = 0
        if (idrsel(2) == array_dq .or. idrsel(1) == scalar_dt) order = 1
        if (idrsel(3) == xmatrx_dqdq .or. idrsel(2) == array_dtdq .or. idrsel(1) == scalar_dtt) &
            & order = 2
        if (all(idrsel == [scalar_none, array_none, xmatrx_none])) return
        if (idrsel(1) /= scalar_none .and. idrsel(1) /= scalar_value .and. &
            & idrsel(1) /= scalar_dt .and. idrsel(1) /= scalar_dtt) then
            call ucon_error(error, id, "its expression gives F, dF/dt and d2F/dt2, not " &
                & // "IDRSEL(1) = " // to_text(idrsel(1)))
            return
        end if
        f = gcon_jet(gcon, time, q(:nvars), order, with_time)
        n = nvars + merge(1, 0, with_time)
        select case (idrsel(1))
        case (scalar_value)
            scalar = f%v
        case (scalar_dt)
            scalar = first_partial(f, n)
        case (scalar_dtt)
            scalar = second_partial(f, n, n)
        end select
        if (idrsel(2) == array_dq) then
            array(:nvars) = 0.0_wp
            if (f%active) array(:nvars) = f%g(:nvars)
        else if (idrsel(2) == array_dtdq) then
            array(:nvars) = 0.0_wp
            if (allocated(f%h)) array(:nvars) = f%h(:nvars, n)
        end if
        if (idrsel(3) == xmatrx_dqdq) then
            xmatrx(:nvars, :nvars) = 0.0_wp
            if (allocated(f%h)) xmatrx(:nvars, :nvars) = f%h(:nvars, :nvars)
        end if
        finite = .true.
        if (idrsel(1) /= scalar_none) finite = ieee_is_finite(scalar)
        if (idrsel(2) /= array_none) finite = finite .and. all(ieee_is_finite(array(:nvars)))
        if (idrsel(3) /= xmatrx_none) finite = finite .and. &
            & all(ieee_is_finite(xmatrx(:nvars, :nvars)))
        if (.not. finite) then
            call ucon_error(error, id, "F = " // gcon%expression%text &
                & // " or its partials are not finite at t = " &
                & // to_text(time) // " s with IDRSEL = (" // to_text(idrsel(1)) // ", " &
                & // to_text(idrsel(2)) // ", " // to_text(idrsel(3)) // "): a function " &
                & // "outside its domain, or a measure where it has no derivative (a distance " &
                & // "of zero)")
            error%stat = stat_non_finite
        end if

    contains

        pure real(wp) function first_partial(jet, i)
            type(jet_type), intent(in) :: jet
            integer, intent(in) :: i

            first_partial = 0.0_wp
            if (jet%active) first_partial = jet%g(i)
        end function first_partial

        pure real(wp) function second_partial(jet, i, j)
            type(jet_type), intent(in) :: jet
            integer, intent(in) :: i, j

            second_partial = 0.0_wp
            if (allocated(jet%h)) second_partial = jet%h(i, j)
        end function second_partial
    end subroutine evaluate_gcon

    !> A GCON's markers on part p given in p's turned principal axes (rollcon_marker's
    !> turn_marker), when the part is re-based.
    pure subroutine turn_gcon_markers(gcon, p, turn)
        type(gcon_type), intent(inout) :: gcon
        !> The part re-based (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn
        integer :: k

        do k = 1, size(gcon%markers)
            call turn_marker(gcon%markers(k), p, turn)
        end do
        call turn_marker(gcon%reaction, p, turn)
    end subroutine turn_gcon_markers

end module rollcon_gcon
