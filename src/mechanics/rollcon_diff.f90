! SPDX-License-Identifier: MIT
!> A dataset's user differential equations (ADAMS's DIFF statement, docs/datasets.md "DIFF"),
!> their states integrated with the parts' in every formulation that takes them.
!>
!> DIFF/id has a state x = DIF(id), in its user's units, and its rate w = DIF1(id), in those
!> units per the dataset's time unit. Its FUNCTION e (an expression in the dataset's units of
!> TIME, the measures of the parts' markers, DIF and DIF1 of any DIFF) gives its equation
!>
!>     explicit:  w - e(t, q, u, x, w) = 0     (d DIF/dt = e)
!>     IMPLICIT:  e(t, q, u, x, w) = 0,
!>
!> the residuals G(t, q, u, x, w) of all DIFFs together. A formulation that integrates an ODE
!> needs w at (t, q, u, x): solve_rates solves G = 0 for it by Newton's method over the exact
!> partials dG/dw (one step when no equation reads a DIF1: then dG/dw is the identity on
!> the explicit ones), as ADAMS solves a DIFF that reads DIF1s; a DAE formulation takes G
!> itself as its residual, with IDA's w. The partials of G with respect to q, u, x and w
!> (partials) are exact: forward mode over the expression (rollcon_expression_jet, through
!> rollcon_measures' jets of the markers' measures), never differences.
!>
!> The forces and VARIABLEs read DIF and DIF1 through the values set in their statements
!> (diff_inputs); the formulations set them before every evaluation (rollcon_model's
!> set_diff_state).
module rollcon_diff
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_solver
    use rollcon_text, only : to_text
    use rollcon_lapack, only : factor_dense, solve_factored
    use rollcon_jet, only : jet_type, jet_variable, jet_constant
    use rollcon_expression, only : expression_type, evaluate_expression, quantity_dif, &
        & quantity_dif1
    use rollcon_expression_jet, only : evaluate_expression_jet
    use rollcon_marker, only : marker_type, turn_marker
    use rollcon_measures, only : expression_input_values, expression_input_jets, &
        & state_jets_type, new_state_jets, count_turns
    implicit none
    private

    public :: diff_type, diff_set_type, diff_inputs, diff_input_jets

    !> Most Newton steps of solve_rates; each is exact for an equation linear in the DIF1s
    integer, parameter :: most_steps = 20

    !> One DIFF statement
    type :: diff_type
        !> Its id (DIF(id) reads it)
        integer :: id = 0
        !> What it is, for messages: "DIFF/3 (line 12)"
        character(len=:), allocatable :: name
        !> FUNCTION, in the dataset's units (inputs: markers' measures, DIF, DIF1)
        type(expression_type) :: function
        !> Every marker the FUNCTION reads, as the model holds them (turned with their parts)
        type(marker_type), allocatable :: markers(:)
        !> IMPLICIT: 0 = e; else d DIF/dt = e
        logical :: implicit = .false.
        !> STATIC_HOLD: a static equilibrium holds DIF at its value
        logical :: static_hold = .false.
        !> IC: the initial DIF [user's units] and DIF1's first guess [user's units / time unit]
        real(wp) :: ic(2) = 0.0_wp
    end type diff_type

    !> A model's DIFFs and their state last set
    type :: diff_set_type
        type(diff_type), allocatable :: diffs(:)
        !> Size of the dataset's length [m] and time [s] units
        real(wp) :: length_unit = 1.0_wp, time_unit = 1.0_wp
        !> The state last set: DIF of each DIFF [user's units] and DIF1 [per time unit]
        real(wp), allocatable :: x(:), w(:)
        !> Each DIFF's id, in order (set by start)
        integer, allocatable :: ids(:)
        !> Some FUNCTION reads a DIF1 (set by start): else every DIFF is explicit and its rate
        !> is its FUNCTION's value, no Newton step needed
        logical :: reads_rates = .false.
    contains
        procedure :: count => diff_count
        procedure :: start
        procedure :: residuals
        procedure :: partials
        procedure :: solve_rates
        procedure :: part_rebased
        procedure :: count_turns => count_diff_turns
    end type diff_set_type

contains

    !> Number of DIFFs.
    pure integer function diff_count(self)
        class(diff_set_type), intent(in) :: self

        diff_count = 0
        if (allocated(self%diffs)) diff_count = size(self%diffs)
    end function diff_count

    !> The state at the start: x the ICs' first values, w their second (a first guess for
    !> solve_rates).
    pure subroutine start(self)
        class(diff_set_type), intent(inout) :: self
        integer :: k

        allocate(self%x(self%count()), self%w(self%count()), self%ids(self%count()))
        do k = 1, self%count()
            self%ids(k) = self%diffs(k)%id
            if (allocated(self%diffs(k)%function%inputs)) self%reads_rates = self%reads_rates &
                & .or. any(self%diffs(k)%function%inputs%quantity == quantity_dif1)
            self%x(k) = self%diffs(k)%ic(1)
            self%w(k) = self%diffs(k)%ic(2)
        end do
    end subroutine start

    !> The values of an expression's DIF(id) and DIF1(id) inputs from (x, w) of these DIFFs
    !> (ids), the other inputs left as they are. A DIF of no DIFF among ids is NaN (the
    !> dataset's reader refuses it first).
    pure subroutine diff_inputs(expression, ids, x, w, values)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)
        real(wp), intent(inout) :: values(:)
        integer :: n, k

        if (.not. allocated(expression%inputs)) return
        do n = 1, size(values)
            associate (input => expression%inputs(n))
                if (input%quantity /= quantity_dif .and. input%quantity /= quantity_dif1) cycle
                k = findloc(ids, input%marker, dim=1)
                values(n) = nan()
                if (k == 0) cycle
                if (input%quantity == quantity_dif) then
                    values(n) = x(k)
                else
                    values(n) = w(k)
                end if
            end associate
        end do
    end subroutine diff_inputs

    !> The jets of an expression's DIF(id) and DIF1(id) inputs as constants, from (x, w) of
    !> these DIFFs (ids), the other inputs left as they are (for a computation of partials in
    !> the parts' states alone, such as a static equilibrium's, where a DIFF is held).
    pure subroutine diff_input_jets(expression, ids, x, w, values)
        type(expression_type), intent(in) :: expression
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)
        type(jet_type), intent(inout) :: values(:)
        real(wp) :: plain(size(values))
        integer :: n

        if (.not. allocated(expression%inputs)) return
        plain = 0.0_wp
        call diff_inputs(expression, ids, x, w, plain)
        do n = 1, size(values)
            associate (quantity => expression%inputs(n)%quantity)
                if (quantity == quantity_dif .or. quantity == quantity_dif1) &
                    & values(n) = jet_constant(plain(n))
            end associate
        end do
    end subroutine diff_input_jets

    !> G(t, q, u, x, w) (module header), one per DIFF, in the FUNCTION's units.
    pure subroutine residuals(self, time, q, u, x, w, g)
        class(diff_set_type), intent(in) :: self
        !> Time [s]; coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: time, q(:), u(:)
        !> DIF and DIF1 of every DIFF [user's units, per time unit]
        real(wp), intent(in) :: x(:), w(:)
        real(wp), intent(out) :: g(:)
        real(wp), allocatable :: values(:)
        integer :: k

        do k = 1, self%count()
            associate (diff => self%diffs(k))
                allocate(values(size(diff%function%inputs)))
                call expression_input_values(diff%function, diff%markers, self%length_unit, &
                    & self%time_unit, q, u, values)
                call diff_inputs(diff%function, self%ids, x, w, values)
                g(k) = evaluate_expression(diff%function, time/self%time_unit, values)
                if (.not. diff%implicit) g(k) = w(k) - g(k)
                deallocate(values)
            end associate
        end do
    end subroutine residuals

    !> G and its exact partials at (t, q, u, x, w): g_q(k, j) = dG_k/dq_j, g_u, g_x, g_w
    !> likewise (forward mode over each FUNCTION, first order; module header). nd = count():
    !> g_q, g_u are nd x size(q), g_x, g_w nd x nd.
    pure subroutine partials(self, time, q, u, x, w, g, g_q, g_u, g_x, g_w)
        class(diff_set_type), intent(in) :: self
        real(wp), intent(in) :: time, q(:), u(:), x(:), w(:)
        real(wp), intent(out) :: g(:), g_q(:, :), g_u(:, :), g_x(:, :), g_w(:, :)
        type(state_jets_type) :: state
        type(jet_type), allocatable :: inputs(:)
        type(jet_type) :: value
        integer, allocatable :: parts(:), q_variable(:, :), u_variable(:, :)
        integer :: n, nd, np, total, k, m, p, c, j

        n = size(q)
        np = n/6
        nd = self%count()
        ! the variables: q (1 : n), u (n + 1 : 2 n), x (2 n + 1 : 2 n + nd), w (after)
        total = 2*n + 2*nd
        parts = [(p, p = 1, np)]
        allocate(q_variable(6, np), u_variable(6, np))
        do p = 1, np
            do c = 1, 6
                q_variable(c, p) = 6*(p - 1) + c
                u_variable(c, p) = n + 6*(p - 1) + c
            end do
        end do
        state = new_state_jets(parts, reshape(q, [6, np]), reshape(u, [6, np]), q_variable, &
            & u_variable, total, .false.)
        do k = 1, nd
            associate (diff => self%diffs(k))
                allocate(inputs(size(diff%function%inputs)))
                call expression_input_jets(diff%function, diff%markers, self%length_unit, &
                    & self%time_unit, state, inputs)
                do m = 1, size(inputs)
                    associate (input => diff%function%inputs(m))
                        if (input%quantity /= quantity_dif .and. &
                            & input%quantity /= quantity_dif1) cycle
                        j = findloc(self%ids, input%marker, dim=1)
                        if (j == 0) then
                            inputs(m) = jet_constant(nan())
                        else if (input%quantity == quantity_dif) then
                            inputs(m) = jet_variable(x(j), 2*n + j, total, .false.)
                        else
                            inputs(m) = jet_variable(w(j), 2*n + nd + j, total, .false.)
                        end if
                    end associate
                end do
                value = evaluate_expression_jet(diff%function, &
                    & jet_constant(time/self%time_unit), inputs)
                deallocate(inputs)
                g(k) = value%v
                if (allocated(value%g)) then
                    g_q(k, :) = value%g(:n)
                    g_u(k, :) = value%g(n + 1:2*n)
                    g_x(k, :) = value%g(2*n + 1:2*n + nd)
                    g_w(k, :) = value%g(2*n + nd + 1:)
                else
                    ! a FUNCTION of TIME alone (or a constant)
                    g_q(k, :) = 0.0_wp
                    g_u(k, :) = 0.0_wp
                    g_x(k, :) = 0.0_wp
                    g_w(k, :) = 0.0_wp
                end if
                if (.not. diff%implicit) then
                    g(k) = w(k) - g(k)
                    g_q(k, :) = -g_q(k, :)
                    g_u(k, :) = -g_u(k, :)
                    g_x(k, :) = -g_x(k, :)
                    g_w(k, :) = -g_w(k, :)
                    g_w(k, k) = g_w(k, k) + 1.0_wp
                end if
            end associate
        end do
    end subroutine partials

    !> The DIF1s w that solve G(t, q, u, x, w) = 0 (module header), from the first guess w, by
    !> Newton's method over dG/dw; dg_dw is left factored (LU, pivots ipiv) at the solution
    !> for the caller's partials dw/d(q, u, x) = -dG/dw^-1 dG/d(q, u, x). Refused: dG/dw
    !> singular (an IMPLICIT DIFF whose FUNCTION does not depend on the DIF1s, or equations
    !> that fix no DIF1), naming the DIFFs; no convergence in most_steps; a value that is not
    !> finite.
    subroutine solve_rates(self, time, q, u, x, w, error, dg_dw, ipiv)
        class(diff_set_type), intent(in) :: self
        real(wp), intent(in) :: time, q(:), u(:), x(:)
        !> First guess on entry, the solution on return [user's units per time unit]
        real(wp), intent(inout) :: w(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(out), optional :: dg_dw(:, :)
        integer, intent(out), optional :: ipiv(:)
        real(wp) :: g(self%count()), g_q(self%count(), size(q)), g_u(self%count(), size(q)), &
            & g_x(self%count(), self%count()), g_w(self%count(), self%count()), &
            & step(self%count(), 1)
        integer :: pivots(self%count()), iteration, nd
        logical :: converged

        nd = self%count()
        if (nd == 0) return
        if (.not. self%reads_rates) then
            ! every DIFF explicit, no DIF1 read: w = e(t, q, u, x), G's residual at w = 0
            w = 0.0_wp
            call self%residuals(time, q, u, x, w, g)
            w = -g
            if (.not. all(ieee_is_finite(w))) then
                call fatal_error(error, trim(self%diffs(first_nonfinite(w))%name) &
                    & // " FUNCTION: " // self%diffs(first_nonfinite(w))%function%text &
                    & // " is not finite at t = " // to_text(time) // " s (DIF = " &
                    & // to_text(x(first_nonfinite(w))) // ")", stat_solver)
                return
            end if
            if (present(dg_dw)) then
                dg_dw = 0.0_wp
                do iteration = 1, nd
                    dg_dw(iteration, iteration) = 1.0_wp
                end do
            end if
            if (present(ipiv)) ipiv = [(iteration, iteration = 1, nd)]
            return
        end if
        converged = .false.
        do iteration = 1, most_steps
            call self%partials(time, q, u, x, w, g, g_q, g_u, g_x, g_w)
            if (.not. all(ieee_is_finite(g)) .or. .not. all(ieee_is_finite(g_w))) then
                call fatal_error(error, trim(self%diffs(first_nonfinite(g))%name) &
                    & // " FUNCTION: " // self%diffs(first_nonfinite(g))%function%text &
                    & // " is not finite at t = " // to_text(time) // " s (DIF = " &
                    & // to_text(x(first_nonfinite(g))) // ")", stat_solver)
                return
            end if
            call factor_dense(g_w, pivots, error)
            if (allocated(error)) then
                deallocate(error)
                call fatal_error(error, singular_text(self), stat_input)
                return
            end if
            if (converged) exit
            step(:, 1) = -g
            call solve_factored(g_w, pivots, step, error)
            if (allocated(error)) return
            w = w + step(:, 1)
            ! linear in w (no DIF1 read, or read linearly): exact after one step
            converged = all(abs(step(:, 1)) <= 1.0e-12_wp*(1.0_wp + abs(w)))
            if (iteration == most_steps) then
                call fatal_error(error, trim(self%diffs(maxloc(abs(step(:, 1)), dim=1))%name) &
                    & // ": the equations for the DIF1s did not converge in " &
                    & // to_text(most_steps) // " Newton steps at t = " // to_text(time) &
                    & // " s", stat_solver)
                return
            end if
        end do
        if (present(dg_dw)) dg_dw = g_w
        if (present(ipiv)) ipiv = pivots
    end subroutine solve_rates

    !> The message of a singular dG/dw.
    function singular_text(self) result(text)
        type(diff_set_type), intent(in) :: self
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, self%count()
            if (.not. self%diffs(k)%implicit) cycle
            if (len(text) > 0) text = text // ", "
            text = text // trim(self%diffs(k)%name)
        end do
        text = text // ": the IMPLICIT equations 0 = e do not fix the DIF1s (de/dDIF1 is " &
            & // "singular): an IMPLICIT DIFF's FUNCTION must depend on DIF1 of the DIFFs " &
            & // "(write d DIF/dt = e without IMPLICIT otherwise)"
    end function singular_text

    !> The first index whose value is not finite (1 when all are).
    pure integer function first_nonfinite(values) result(k)
        real(wp), intent(in) :: values(:)

        k = max(1, findloc(ieee_is_finite(values), .false., dim=1))
    end function first_nonfinite

    !> Part p's principal axes were turned (a re-basing): the markers the FUNCTIONs read in
    !> its new axes.
    pure subroutine part_rebased(self, p)
        class(diff_set_type), intent(inout) :: self
        integer, intent(in) :: p
        integer :: k, m

        do k = 1, self%count()
            if (.not. allocated(self%diffs(k)%markers)) cycle
            do m = 1, size(self%diffs(k)%markers)
                call turn_marker(self%diffs(k)%markers(m), p)
            end do
        end do
    end subroutine part_rebased

    !> The whole turns of the FUNCTIONs' AX, AY, AZ counted at (q, u) (rollcon_measures'
    !> count_turns).
    pure subroutine count_diff_turns(self, q, u, restart)
        class(diff_set_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        logical, intent(in) :: restart
        integer :: k

        do k = 1, self%count()
            call count_turns(self%diffs(k)%function, self%diffs(k)%markers, self%length_unit, &
                & self%time_unit, q, u, restart)
        end do
    end subroutine count_diff_turns

    pure function nan()
        use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
        real(wp) :: nan

        nan = ieee_value(nan, ieee_quiet_nan)
    end function nan

end module rollcon_diff
