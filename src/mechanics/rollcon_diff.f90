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
!> needs w at (t, q, u, x): solve_rates solves G = 0 for it by Newton's method over the
!> partials dG/dw (one step when no equation reads a DIF1: then dG/dw is the identity on
!> the explicit ones), as ADAMS solves a DIFF that reads DIF1s; a DAE formulation takes G
!> itself as its residual, with IDA's w. The partials of an expression's G with respect to
!> q, u, x and w (partials) are exact: forward mode over the expression
!> (rollcon_expression_jet, through rollcon_measures' jets of the markers' measures), never
!> differences; a DIFSUB's are differenced (below), the only way into code rollcon cannot
!> see.
!>
!> A DIFF/id, FUNCTION=USER(r1, ...) is served by a user's DIFSUB (rollcon_user_forces'
!> call_diff_routine): its VALUE is e, read at (t, q, u, x, w) through SYSFNC and SYSARY
!> (SYSFNC('DIF', id), SYSFNC('DIF1', id) for the DIFFs' state). Its partials are central
!> differences (rollcon_central_differences) over what its initialisation call (IFLAG =
!> .TRUE.) declared: the coordinates of the parts of the markers it named (and their rates
!> when it read rates), the DIFs and the DIF1s it named; each call with DFLAG = .TRUE., as
!> ADAMS/Solver forms a routine's partials.
!>
!> A DIFSUB may read the accelerations (SYSARY('TACC'|'RACC'), SYSFNC('ACCX' ... 'WDTM')):
!> they are answered from rollcon_user_forces' set_system_accelerations, which the
!> formulations set before they evaluate G (IDA: its u'; the ODE form: the accelerations
!> solved at (t, q, u), before the rates are solved again), and its partials in them
!> (acceleration_partials, differenced as its others) enter the Newton matrices: scaled by
!> cj beside dG/du on IDA, chained through da/d(q, u) in the ODE form (docs/datasets.md,
!> "Accelerations read by a user routine"). A DIFSUB may read a constraint's reaction
!> (SYSFNC's force measures summing a JOINT's, JPRIM's or MOTION's multipliers), answered from
!> the multipliers the formulations set (IDA: its lambda; the ODE form: those solved at (t, q,
!> u)); its partials in the multipliers of the rows its initialisation call's force measures
!> summed (multiplier_partials, differenced as its others) enter the Newton matrices: by
!> IDA's lambda columns, chained through dlambda/d(q, u) in the ODE form.
!>
!> The forces and VARIABLEs read DIF and DIF1 through the values set in their statements
!> (diff_inputs, rollcon_diff_inputs); the formulations set them before every evaluation
!> (rollcon_model's set_diff_state).
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
    use rollcon_diff_inputs, only : diff_inputs, diff_input_jets
    use rollcon_user_forces, only : routine_declaration_type, declare_diff_routine, &
        & call_diff_routine, take_user_force_error, set_system_accelerations, &
        & system_accelerations, set_system_multipliers, system_multipliers
    use rollcon_central_differences, only : central_differences
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
        !> FUNCTION=USER(r1, ...): the entry of its DIFSUB in rollcon_user_forces' table (0:
        !> FUNCTION is an expression), the constants, and what its initialisation call declared
        !> (declare_routines)
        integer :: routine = 0
        real(wp), allocatable :: par(:)
        type(routine_declaration_type) :: declaration
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
        procedure :: declare_routines
        procedure :: residuals
        procedure :: partials
        procedure :: reads_accelerations
        procedure :: acceleration_partials
        procedure :: reads_constraint_forces
        procedure :: multiplier_partials
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
    subroutine start(self)
        class(diff_set_type), intent(inout) :: self
        integer :: k

        allocate(self%x(self%count()), self%w(self%count()), self%ids(self%count()))
        do k = 1, self%count()
            self%ids(k) = self%diffs(k)%id
            if (allocated(self%diffs(k)%function%inputs)) self%reads_rates = self%reads_rates &
                & .or. any(self%diffs(k)%function%inputs%quantity == quantity_dif1)
            ! a DIFSUB may read DIF1s until its declaration says (declare_routines)
            if (self%diffs(k)%routine > 0) self%reads_rates = .true.
            self%x(k) = self%diffs(k)%ic(1)
            self%w(k) = self%diffs(k)%ic(2)
        end do
    end subroutine start

    !> G(t, q, u, x, w) (module header), one per DIFF, in the FUNCTION's units.
    subroutine residuals(self, time, q, u, x, w, g)
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
                if (diff%routine > 0) then
                    g(k) = routine_value(self, k, time, q, u, x, w, .false.)
                    if (.not. diff%implicit) g(k) = w(k) - g(k)
                    cycle
                end if
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

    !> G and its partials at (t, q, u, x, w): g_q(k, j) = dG_k/dq_j, g_u, g_x, g_w likewise
    !> (forward mode over each FUNCTION, first order; a DIFSUB's by central differences over
    !> its declaration, routine_partials; module header). nd = count():
    !> g_q, g_u are nd x size(q), g_x, g_w nd x nd.
    subroutine partials(self, time, q, u, x, w, g, g_q, g_u, g_x, g_w)
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
                if (diff%routine > 0) then
                    call routine_partials(self, k, time, q, u, x, w, g(k), g_q(k, :), &
                        & g_u(k, :), g_x(k, :), g_w(k, :))
                    cycle
                end if
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

    !> True when the initialisation call of a DIFF's DIFSUB read accelerations.
    pure logical function reads_accelerations(self) result(reads)
        class(diff_set_type), intent(in) :: self
        integer :: k

        reads = .false.
        do k = 1, self%count()
            if (self%diffs(k)%routine == 0) cycle
            if (self%diffs(k)%declaration%accelerations) reads = .true.
        end do
    end function reads_accelerations

    !> g_a(k, j) = dG_k/da_j at (t, q, u, x, w) and the accelerations a [SI] (nd x size(a)):
    !> for a DIFSUB whose initialisation call read accelerations, central differences
    !> (rollcon_central_differences) of its VALUE over the accelerations of its declared
    !> parts, each call with DFLAG = .TRUE. and the shifted accelerations answered to it
    !> (those set before restored after); an explicit DIFF's G_k = w_k - VALUE takes the
    !> opposite sign. The other rows are 0 (an expression reads no acceleration). A failed
    !> call leaves its entry 0 and its error for take_user_force_error.
    subroutine acceleration_partials(self, time, q, u, x, w, a, g_a)
        class(diff_set_type), intent(in) :: self
        real(wp), intent(in) :: time, q(:), u(:), x(:), w(:), a(:)
        real(wp), intent(out) :: g_a(:, :)
        real(wp), allocatable :: kept(:), block(:, :)
        integer, allocatable :: entries(:)
        integer :: k, p, c

        g_a = 0.0_wp
        if (.not. self%reads_accelerations()) return
        kept = system_accelerations(size(a))
        do k = 1, self%count()
            if (self%diffs(k)%routine == 0) cycle
            associate (declared => self%diffs(k)%declaration)
                if (.not. declared%accelerations) cycle
                entries = [((6*(declared%parts(p) - 1) + c, c = 1, 6), &
                    & p = 1, size(declared%parts))]
            end associate
            if (size(entries) == 0) cycle
            allocate(block(size(entries), 1), source=0.0_wp)
            call central_differences(a, entries, accelerations_moved, block)
            g_a(k, entries) = block(:, 1)
            if (.not. self%diffs(k)%implicit) g_a(k, :) = -g_a(k, :)
            deallocate(block)
        end do
        call set_system_accelerations(kept)

    contains

        subroutine accelerations_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call set_system_accelerations(shifted)
            values(1) = routine_value(self, k, time, q, u, x, w, .true.)
            failed = .not. ieee_is_finite(values(1))
        end subroutine accelerations_moved

    end subroutine acceleration_partials

    !> True when the initialisation call of a DIFF's DIFSUB read a constraint's reaction
    !> (SYSFNC's force measures summing a JOINT's, JPRIM's or MOTION's multipliers: the
    !> declaration's rows).
    pure logical function reads_constraint_forces(self) result(reads)
        class(diff_set_type), intent(in) :: self
        integer :: k

        reads = .false.
        do k = 1, self%count()
            if (self%diffs(k)%routine == 0) cycle
            if (.not. allocated(self%diffs(k)%declaration%rows)) cycle
            if (size(self%diffs(k)%declaration%rows) > 0) reads = .true.
        end do
    end function reads_constraint_forces

    !> g_lambda(k, r) = dG_k/dlambda_r at (t, q, u, x, w) and the multipliers the force
    !> measures read (rollcon_user_forces' system_multipliers: the state's, set by the
    !> formulation before; nd x nc): for a DIFSUB whose initialisation call read a
    !> constraint's reaction, central differences (rollcon_central_differences) of its VALUE
    !> over the multipliers of the rows it declared, as a VARSUB's (each call with DFLAG =
    !> .TRUE., the shifted multipliers answered to it, those set before restored after); an
    !> explicit DIFF's G_k = w_k - VALUE takes the opposite sign. The other entries are 0 (an
    !> expression reads no reaction). A failed call leaves its entry 0 and its error for
    !> take_user_force_error.
    subroutine multiplier_partials(self, time, q, u, x, w, g_lambda)
        class(diff_set_type), intent(in) :: self
        real(wp), intent(in) :: time, q(:), u(:), x(:), w(:)
        real(wp), intent(out) :: g_lambda(:, :)
        real(wp), allocatable :: kept(:), block(:, :)
        integer :: k

        g_lambda = 0.0_wp
        if (.not. self%reads_constraint_forces()) return
        kept = system_multipliers(size(g_lambda, 2))
        do k = 1, self%count()
            if (self%diffs(k)%routine == 0) cycle
            if (.not. allocated(self%diffs(k)%declaration%rows)) cycle
            if (size(self%diffs(k)%declaration%rows) == 0) cycle
            associate (rows => self%diffs(k)%declaration%rows)
                allocate(block(size(rows), 1), source=0.0_wp)
                call central_differences(kept, rows, multipliers_moved, block)
                g_lambda(k, rows) = block(:, 1)
                deallocate(block)
            end associate
            if (.not. self%diffs(k)%implicit) g_lambda(k, :) = -g_lambda(k, :)
        end do
        call set_system_multipliers(kept)

    contains

        subroutine multipliers_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call set_system_multipliers(shifted)
            values(1) = routine_value(self, k, time, q, u, x, w, .true.)
            failed = .not. ieee_is_finite(values(1))
        end subroutine multipliers_moved

    end subroutine multiplier_partials

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
            if (any(self%diffs%routine > 0)) then
                call take_user_force_error(error)
                if (allocated(error)) return
            end if
            if (.not. all(ieee_is_finite(w))) then
                call take_user_force_error(error)
                if (allocated(error)) return
                call fatal_error(error, trim(self%diffs(first_nonfinite(w))%name) &
                    & // " FUNCTION: " // equation_text(self%diffs(first_nonfinite(w))) &
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
            call take_user_force_error(error)
            if (allocated(error)) return
            if (.not. all(ieee_is_finite(g)) .or. .not. all(ieee_is_finite(g_w))) then
                call fatal_error(error, trim(self%diffs(first_nonfinite(g))%name) &
                    & // " FUNCTION: " // equation_text(self%diffs(first_nonfinite(g))) &
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

    !> The initialisation call (IFLAG = .TRUE.) of every DIFSUB at (t, q, u) and the DIFFs'
    !> state last set (x, w): each one's declaration (rollcon_user_forces'
    !> declare_diff_routine), and reads_rates again (a DIFSUB that named no DIF1 reads none).
    !> An ERRMES or a utility's refusal is an error naming the DIFF.
    subroutine declare_routines(self, time, q, u, error)
        class(diff_set_type), intent(inout) :: self
        !> Time [s], coordinates and rates of all parts [SI]
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        if (.not. any(self%diffs%routine > 0)) return
        self%reads_rates = .false.
        do k = 1, self%count()
            associate (diff => self%diffs(k))
                if (diff%routine > 0) then
                    call declare_diff_routine(diff%routine, diff%id, diff%name, diff%par, &
                        & self%time_unit, time, q, u, self%ids, self%x, self%w, &
                        & diff%declaration, error)
                    if (allocated(error)) return
                    self%reads_rates = self%reads_rates .or. size(diff%declaration%dif1s) > 0
                else if (allocated(diff%function%inputs)) then
                    self%reads_rates = self%reads_rates &
                        & .or. any(diff%function%inputs%quantity == quantity_dif1)
                end if
            end associate
        end do
    end subroutine declare_routines

    !> VALUE of DIFF k's DIFSUB at (t, q, u, x, w) (e: G_k is e, IMPLICIT, or w_k - e); NaN when
    !> the call failed (its error kept for take_user_force_error). dflag: a difference's call.
    function routine_value(self, k, time, q, u, x, w, dflag) result(g)
        type(diff_set_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:), x(:), w(:)
        logical, intent(in) :: dflag
        real(wp) :: g
        real(wp) :: value
        logical :: failed

        associate (diff => self%diffs(k))
            call call_diff_routine(diff%routine, diff%id, diff%name, diff%par, &
                & self%time_unit, time, q, u, self%ids, x, w, dflag, diff%declaration, value, &
                & failed)
            g = value
            if (failed) g = nan()
        end associate
    end function routine_value

    !> G_k of DIFF k, a DIFSUB's, and its partials (rows of partials' g_q, g_u, g_x, g_w): its
    !> VALUE's by central differences over the declared entries (module header), the rest
    !> zero; an explicit DIFF's G_k = w_k - VALUE has the exact 1 of w_k.
    subroutine routine_partials(self, k, time, q, u, x, w, g, g_q, g_u, g_x, g_w)
        type(diff_set_type), intent(in) :: self
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:), x(:), w(:)
        real(wp), intent(out) :: g, g_q(:), g_u(:), g_x(:), g_w(:)
        integer, allocatable :: entries(:)
        real(wp), allocatable :: block(:, :)
        integer :: p, c

        g = routine_value(self, k, time, q, u, x, w, .false.)
        g_q = 0.0_wp
        g_u = 0.0_wp
        g_x = 0.0_wp
        g_w = 0.0_wp
        associate (declared => self%diffs(k)%declaration)
            if (.not. allocated(declared%markers)) then
                if (.not. self%diffs(k)%implicit) then
                    g = w(k) - g
                    g_w(k) = 1.0_wp
                end if
                return
            end if
            entries = [((6*(declared%parts(p) - 1) + c, c = 1, 6), &
                & p = 1, size(declared%parts))]
            allocate(block(size(entries), 1))
            block = 0.0_wp
            call central_differences(q, entries, coordinates_moved, block)
            g_q(entries) = block(:, 1)
            if (declared%rates) then
                block = 0.0_wp
                call central_differences(u, entries, rates_moved, block)
                g_u(entries) = block(:, 1)
            end if
            entries = pack([(p, p = 1, self%count())], [(any(declared%difs == self%ids(p)), &
                & p = 1, self%count())])
            deallocate(block)
            allocate(block(size(entries), 1), source=0.0_wp)
            call central_differences(x, entries, states_moved, block)
            g_x(entries) = block(:, 1)
            entries = pack([(p, p = 1, self%count())], [(any(declared%dif1s == self%ids(p)), &
                & p = 1, self%count())])
            deallocate(block)
            allocate(block(size(entries), 1), source=0.0_wp)
            call central_differences(w, entries, rates_of_states_moved, block)
            g_w(entries) = block(:, 1)
        end associate
        if (.not. self%diffs(k)%implicit) then
            g = w(k) - g
            g_q = -g_q
            g_u = -g_u
            g_x = -g_x
            g_w = -g_w
            g_w(k) = g_w(k) + 1.0_wp
        end if

    contains

        subroutine coordinates_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            values(1) = routine_value(self, k, time, shifted, u, x, w, .true.)
            failed = .not. ieee_is_finite(values(1))
        end subroutine coordinates_moved

        subroutine rates_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            values(1) = routine_value(self, k, time, q, shifted, x, w, .true.)
            failed = .not. ieee_is_finite(values(1))
        end subroutine rates_moved

        subroutine states_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            values(1) = routine_value(self, k, time, q, u, shifted, w, .true.)
            failed = .not. ieee_is_finite(values(1))
        end subroutine states_moved

        subroutine rates_of_states_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            values(1) = routine_value(self, k, time, q, u, x, shifted, .true.)
            failed = .not. ieee_is_finite(values(1))
        end subroutine rates_of_states_moved

    end subroutine routine_partials

    !> A DIFF's equation for messages: its FUNCTION, or USER(...) for a DIFSUB's.
    function equation_text(diff) result(text)
        type(diff_type), intent(in) :: diff
        character(len=:), allocatable :: text

        text = "USER(...) (its DIFSUB)"
        if (diff%routine == 0 .and. allocated(diff%function%text)) text = diff%function%text
    end function equation_text

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
    pure subroutine part_rebased(self, p, turn)
        class(diff_set_type), intent(inout) :: self
        !> The part (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn
        integer :: k, m

        do k = 1, self%count()
            if (.not. allocated(self%diffs(k)%markers)) cycle
            do m = 1, size(self%diffs(k)%markers)
                call turn_marker(self%diffs(k)%markers(m), p, turn)
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
