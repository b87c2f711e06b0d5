! SPDX-License-Identifier: MIT
!> Linear analysis on the constraint manifold (docs/linear.md), the equivalent of ADAMS's
!> LINEAR/EIGENSOL: the eigenvalues of the constrained equations of motion linearised about a
!> start (q, u) that meets every UCON, in independent coordinates and speeds.
!>
!> The ODE form y = (q, u), y' = f(y) = (u, a(q, u)) (rollcon_equations, Baumgarte rate alpha,
!> 0 by default) keeps the constraints invariant: a velocity UCON F(q, u) = 0, a position UCON
!> Phi(q) = 0 with its rate G u + Phi_t = 0. Their Jacobian J with respect to y comes from the
!> UCOSUBs' own partials (ARRAY; for the rate's q-derivative XMATRX u + d2F/dt dq). Its null
!> space is the tangent space of the manifold; a basis T is built by coordinate partitioning:
!> QR with column pivoting (LAPACK dgeqp3) picks the dependent coordinates (among the q for the
!> position rows, among the u for the rate and velocity rows, where the integrators' saddle
!> point needs them independent), and T = [I; -J_D^-1 J_I] in the independent ones (LAPACK LU).
!> A T is formed column by column as directional central differences of f along T, with one
!> Richardson step (error O(h^4)); A_red is the independent rows of A T, and its eigenvalues
!> come from LAPACK dgeev. For a steady motion the tangent space is invariant, A T = T A_red;
!> the rest, the dependent rows of A T - T A_red, is measured and reported. Rows set aside as
!> redundant (rollcon_redundancy: the dataset's choice at its start) are checked met and left
!> out: the active rows span the same tangent space.
module rollcon_linearisation
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_lapack, only : general_eigenvalues, pivoted_columns, factor_dense, &
        & solve_factored
    use rollcon_constraints, only : local_dot, need_value, need_first, need_second, need_time
    use rollcon_problem, only : problem_type
    use rollcon_ic_rows, only : tolerance, ic_fraction, ic_rcond
    implicit none
    private

    public :: linear_options_type, linear_result_type, linearise, invariance_limit, &
        & sort_eigenvalues

    !> Largest relative rest |A T - T A_red| / |A T| (scaled) of a tangent space taken as
    !> invariant: the differences' own error is about 1e-10 (docs/linear.md), so a rest above
    !> this means the start is no steady motion (or f is not smooth there)
    real(wp), parameter :: invariance_limit = 1.0e-6_wp
    !> Relative size of the largest scaled component of a difference step (h; the Richardson
    !> step also uses h/2): truncation ~h^4, rounding ~eps/h, both near 1e-12 (docs/linear.md)
    real(wp), parameter :: default_step = 2.0e-3_wp
    !> An eigenvalue counts as zero when |lambda| <= zero_fraction max(max |lambda|, Omega),
    !> Omega the model's own frequency scale (frequency_scale): the difference error (~1e-10
    !> relative) spreads a zero of multiplicity k by ~(1e-10)^(1/k) at most; cyclic
    !> coordinates give exact zeros (their columns of A T are exactly zero). Omega keeps the
    !> limit absolute where every eigenvalue is zero by structure (a turntable on a REVOLUTE:
    !> its two computed as +-4.5e-16 1/s, which 1e-6 of the largest would call a growing mode)
    real(wp), parameter :: zero_fraction = 1.0e-6_wp

    !> How the linearisation runs
    type :: linear_options_type
        !> Baumgarte rate in the equations differentiated [1/s]; the terms vanish on the
        !> manifold and leave the eigenvalues as they are (docs/linear.md)
        real(wp) :: baumgarte = 0.0_wp
        !> Relative difference step (see default_step)
        real(wp) :: step = default_step
        !> The independent coordinates to take (numbers into y = (q, u), as a result's
        !> `independent`); not allocated: chosen by the pivoted QR (partition). The analysis
        !> against speed takes those of its reference speed at every speed: the blocks the
        !> choice is made on do not change with the speed, but their scaling does, and where
        !> columns tie (two equal wheels) rounding would pick others at other speeds, so that
        !> A_red's indices would name other coordinates
        integer, allocatable :: independent(:)
    end type linear_options_type

    !> What the linearisation found
    type :: linear_result_type
        !> Time of the start [s]
        real(wp) :: time = 0.0_wp
        !> State size 2n + nd and the manifold's dimension d = 2n + nd - (UCONs + position
        !> UCONs), nd the DIFFs' states (rollcon_diff), each a state of the linear model
        integer :: states = 0, reduced = 0, diff_states = 0
        !> Eigenvalues of A_red [1/s], sorted by decreasing real part, then decreasing
        !> |imaginary part|, + first (a conjugate pair adjacent)
        real(wp), allocatable :: real_part(:), imag_part(:)
        !> A_red, d x d [1/s]: the linearised equations in the independent coordinates
        real(wp), allocatable :: reduced_matrix(:, :)
        !> T, 2n x d: the tangent basis (identity in the independent rows)
        real(wp), allocatable :: basis(:, :)
        !> The independent coordinates, numbers into y = (q, u, x) (j <= n: q_j; j <= 2n:
        !> u_(j-n); else the state of the (j-2n)-th DIFF)
        integer, allocatable :: independent(:)
        !> |A T - T A_red| / |A T| in scaled units (0 for an invariant tangent space)
        real(wp) :: invariance = 0.0_wp
        !> invariance <= invariance_limit
        logical :: invariant = .true.
        !> Eigenvalues with |lambda| at or below this count as zero [1/s]
        real(wp) :: zero_limit = 0.0_wp
        !> How many do
        integer :: zeros = 0
    end type linear_result_type

contains

    !> Linearise the set-up problem's equations about (time, q, u) on its constraint manifold
    !> and find the eigenvalues. Errors (stat_input): a start off the UCONs, a singular
    !> constraint Jacobian; a UCOSUB's error as it is.
    subroutine linearise(problem, time, q, u, options, result, error)
        type(problem_type), intent(inout), target :: problem
        !> Time of the start [s]
        real(wp), intent(in) :: time
        !> The start: coordinates and rates of every part [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        type(linear_options_type), intent(in) :: options
        type(linear_result_type), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: jac(:, :), scale(:), at(:, :), x0(:), w0(:)
        integer, allocatable :: dependent(:)
        integer :: n, nd

        n = problem%model%n
        nd = problem%model%diffs%count()
        result%time = time
        ! y = (q, u, x): the DIFFs' states are states of the linear model (rhs)
        result%states = 2*n + nd
        result%diff_states = nd
        if (size(q) /= n .or. size(u) /= n) then
            call fatal_error(error, "linearisation: q and u need " // to_text(n) &
                & // " values each (6 per part), got " // to_text(size(q)) // " and " &
                & // to_text(size(u)), stat_input)
            return
        end if
        call constraint_jacobian(problem, time, q, u, jac, error)
        if (allocated(error)) return
        scale = state_scales(problem, q, u)
        if (nd > 0) then
            ! no constraint reads a DIFF's state: its columns are zero, its state independent
            jac = reshape([jac, spread(0.0_wp, 1, size(jac, 1)*nd)], [size(jac, 1), 2*n + nd])
            x0 = problem%model%diffs%x
            w0 = problem%model%diffs%w
            scale = [scale, max(1.0_wp, abs(x0))]
        end if
        if (allocated(options%independent)) then
            call given_partition(2*n + nd, options%independent, dependent, &
                & result%independent, error)
        else
            call partition(problem, jac, scale, dependent, result%independent, error)
        end if
        if (allocated(error)) return
        call tangent_basis(jac, dependent, result%independent, result%basis, error)
        if (allocated(error)) return
        result%reduced = size(result%independent)
        call directional_jacobian(problem, time, q, u, options, scale, result%basis, at, error)
        ! the DIFFs' state as it was at the start
        if (nd > 0) call problem%model%set_diff_state(x0, w0)
        if (allocated(error)) return
        result%reduced_matrix = at(result%independent, :)
        result%invariance = invariance_rest(at, result%basis, result%reduced_matrix, scale)
        result%invariant = result%invariance <= invariance_limit
        call sorted_eigenvalues(result, frequency_scale(problem, q, u), error)
    end subroutine linearise

    !> J = d(constraints)/dy at the start, one row per active UCON (a velocity UCON: dF/dq,
    !> dF/du; a position UCON: its rate's row, then a row of its own: dF/dq, 0), after checking
    !> that the start meets every row, those set aside too, to atol + rtol s (the error one
    !> integrator step allows).
    subroutine constraint_jacobian(problem, time, q, u, jac, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable, intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: all_rows(:, :)
        logical, allocatable :: kept(:)
        real(wp) :: residual
        integer :: n, k, row, j, jj

        n = problem%model%n
        allocate(jac(problem%model%nc + problem%model%nh, 2*n), source=0.0_wp)
        allocate(kept(size(jac, 1)), source=.true.)
        call problem%eq%constraints%evaluate(problem%model, time, q, u, need_value &
            & + need_first + need_second + need_time, error)
        if (allocated(error)) return
        row = 0
        associate (cs => problem%eq%constraints, ucons => problem%model%ucons)
            do k = 1, problem%model%nc
                row = row + 1
                if (ucons(k)%holonomic) then
                    ! d2F/dq dq's column j is zero off the UCON's own coordinates
                    do j = 1, n
                        jac(row, j) = 0.0_wp + 0.0_wp
                    end do
                    associate (at => cs%local(:cs%local_count(k), k))
                        do jj = 1, size(at)
                            jac(row, at(jj)) = local_dot(cs%hqq(:, jj, k), u, at) &
                                & + cs%dt_grad_q(jj, k)
                        end do
                    end associate
                    call cs%fill_grad_q_row(k, jac(row, n + 1:))
                    kept(row:row + 1) = problem%eq%active_rows_of(k)
                    residual = cs%grad_q_dot(k, u) + cs%dt(k)
                    ! (the tolerances read the rows of dF/dq and dF/du just placed in jac)
                    call check_met(problem, k, "its rate", residual, &
                        & tolerance(problem%settings%atol, problem%settings%rtol, &
                        & jac(row, n + 1:), u, residual)/ic_fraction, error)
                    if (allocated(error)) return
                    row = row + 1
                    call cs%fill_grad_q_row(k, jac(row, :n))
                    call check_met(problem, k, "F", cs%value(k), &
                        & tolerance(problem%settings%atol, problem%settings%rtol, &
                        & jac(row, :n), q, cs%value(k))/ic_fraction, error)
                else
                    call cs%fill_grad_q_row(k, jac(row, :n))
                    call cs%fill_grad_u_row(k, jac(row, n + 1:))
                    kept(row) = problem%eq%active_rows_of(k)
                    call check_met(problem, k, "F", cs%value(k), &
                        & tolerance(problem%settings%atol, problem%settings%rtol, &
                        & jac(row, n + 1:), u, cs%value(k))/ic_fraction, error)
                end if
                if (allocated(error)) return
            end do
        end associate
        ! the rows set aside repeat the active ones: left out
        if (all(kept)) return
        call move_alloc(jac, all_rows)
        jac = all_rows(pack([(j, j = 1, size(kept))], kept), :)
    end subroutine constraint_jacobian

    !> An error naming UCON k (model order) in the user's words when |value| > allowed: the
    !> start is off the constraints.
    subroutine check_met(problem, k, what, value, allowed, error)
        type(problem_type), intent(in) :: problem
        integer, intent(in) :: k
        character(len=*), intent(in) :: what
        real(wp), intent(in) :: value, allowed
        type(error_type), allocatable, intent(out) :: error

        if (abs(value) <= allowed) return
        call fatal_error(error, "linearisation: the start is off the constraints: " &
            & // problem%model%row_words(k) // " " // what // " = " // to_text(value) &
            & // ", allowed " &
            & // to_text(allowed) // " (atol + rtol times the size of its terms); make the " &
            & // "start consistent first (initial-conditions analysis, " &
            & // "docs/initial-conditions.md)", stat_input)
    end subroutine check_met

    !> The model's own frequency scale Omega [1/s]: the speed scale v_ref of state_scales (at
    !> least sqrt(|g| rho), the largest speed of the start) over the largest rho_p: a pendulum
    !> of the model's size swings at about sqrt(g/rho), and a part moving at v_ref passes its
    !> own size in rho/v_ref. Never 0 (without gravity or motion, 1/s).
    pure real(wp) function frequency_scale(problem, q, u) result(omega)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: rho(size(problem%model%parts)), v_ref

        omega = 1.0_wp
        if (size(rho) == 0) return
        call reference_sizes(problem, u, rho, v_ref)
        omega = v_ref/maxval(rho)
    end function frequency_scale

    !> Each part's rho_p (the RMS distance of its mass from its centre; 1 m for a part without
    !> inertia) [m] and the start's speed scale v_ref [m/s] (state_scales).
    pure subroutine reference_sizes(problem, u, rho, v_ref)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: u(:)
        real(wp), intent(out) :: rho(:), v_ref
        integer :: p, i0

        do p = 1, size(rho)
            rho(p) = sqrt(sum(problem%model%parts(p)%inertia)/(2.0_wp*problem%model%parts(p)%mass))
            ! a point mass has no size of its own: 1 m keeps the steps finite
            if (.not. rho(p) > 0.0_wp) rho(p) = 1.0_wp
        end do
        v_ref = sqrt(norm2(problem%model%gravity)*maxval(rho))
        do p = 1, size(rho)
            i0 = 6*(p - 1)
            v_ref = max(v_ref, maxval(abs(u(i0 + 1:i0 + 3))), rho(p)*maxval(abs(u(i0 + 4:i0 + 6))))
        end do
        if (.not. v_ref > 0.0_wp) v_ref = maxval(rho)*1.0_wp
    end subroutine reference_sizes

    !> The scale of each state component: a part's translations rho_p (the RMS distance of
    !> its mass from its centre) [m], its angles 1 rad, translational rates v_ref [m/s], angular
    !> rates v_ref/rho_p [rad/s], each at least the component's own size; v_ref is the largest
    !> speed of the start (|rates| and rho_p |angular rates|), at least sqrt(|g| rho) (and
    !> rho times 1/s without gravity); a part without inertia counts rho = 1 m.
    pure function state_scales(problem, q, u) result(scale)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: q(:), u(:)
        real(wp), allocatable :: scale(:)
        real(wp) :: rho(size(problem%model%parts)), v_ref
        integer :: n, p, i0

        n = problem%model%n
        allocate(scale(2*n))
        call reference_sizes(problem, u, rho, v_ref)
        do p = 1, size(rho)
            i0 = 6*(p - 1)
            scale(i0 + 1:i0 + 3) = rho(p)
            scale(i0 + 4:i0 + 6) = 1.0_wp
            scale(n + i0 + 1:n + i0 + 3) = v_ref
            scale(n + i0 + 4:n + i0 + 6) = v_ref/rho(p)
        end do
        scale(:n) = max(scale(:n), abs(q))
        scale(n + 1:) = max(scale(n + 1:), abs(u))
    end function state_scales

    !> The dependent coordinates: QR with column pivoting on the position rows over q, then on
    !> the rate and velocity rows over u (columns scaled, rows of unit length). A rank short of
    !> the rows is a singular constraint Jacobian, refused naming the UCONs of that level.
    subroutine partition(problem, jac, scale, dependent, independent, error)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: jac(:, :), scale(:)
        integer, allocatable, intent(out) :: dependent(:), independent(:)
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: position_rows(:), velocity_rows(:), q_dependent(:), &
            & u_dependent(:)
        logical, allocatable :: taken(:)
        integer :: n, k, row, j

        n = problem%model%n
        allocate(position_rows(0), velocity_rows(0))
        row = 0
        do k = 1, problem%model%nc
            ! jac's rows: the active UCONs' (constraint_jacobian)
            if (.not. problem%eq%active_rows_of(k)) cycle
            row = row + 1
            velocity_rows = [velocity_rows, row]
            if (problem%model%ucons(k)%holonomic) then
                row = row + 1
                position_rows = [position_rows, row]
            end if
        end do
        call pick_columns(problem, "position", position_rows, jac(position_rows, :n), &
            & scale(:n), q_dependent, error)
        if (allocated(error)) return
        call pick_columns(problem, "velocity", velocity_rows, jac(velocity_rows, n + 1:), &
            & scale(n + 1:), u_dependent, error)
        if (allocated(error)) return
        dependent = [q_dependent, n + u_dependent]
        ! and the DIFFs' states (jac's last columns), each independent
        allocate(taken(size(jac, 2)), source=.false.)
        taken(dependent) = .true.
        independent = pack([(j, j = 1, size(jac, 2))], .not. taken)
    end subroutine partition

    !> The partition of y = (q, u) with the given independent coordinates (checked: distinct
    !> numbers from 1 to 2n), the rest dependent.
    subroutine given_partition(states, given, dependent, independent, error)
        !> Size of y: 2n, and the DIFFs' states
        integer, intent(in) :: states
        integer, intent(in) :: given(:)
        integer, allocatable, intent(out) :: dependent(:), independent(:)
        type(error_type), allocatable, intent(out) :: error
        logical :: taken(states)
        integer :: j

        taken = .false.
        do j = 1, size(given)
            if (given(j) < 1 .or. given(j) > states) then
                call fatal_error(error, "linearisation: independent coordinate " &
                    & // to_text(given(j)) // " is not one of the " // to_text(states) &
                    & // " coordinates and rates", stat_input)
                return
            end if
            if (taken(given(j))) then
                call fatal_error(error, "linearisation: independent coordinate " &
                    & // to_text(given(j)) // " is given twice", stat_input)
                return
            end if
            taken(given(j)) = .true.
        end do
        independent = given
        dependent = pack([(j, j = 1, states)], .not. taken)
    end subroutine given_partition

    !> The size(rows) most independent columns of block (scaled by scale, rows to unit
    !> length), or an error when the rows are dependent. The translational columns (a part's
    !> X, Y, Z or their rates) are taken first, as many as are independent: the independent
    !> coordinates and speeds are then angles and angle rates wherever the constraints allow,
    !> which a turn of the whole model about the vertical leaves as they are (a heading, a
    !> spin angle: cyclic coordinates, whose columns of A_red are zero; docs/linear.md). The
    !> choice changes no eigenvalue, only which ones are zero by structure.
    subroutine pick_columns(problem, level, rows, block, scale, chosen, error)
        type(problem_type), intent(in) :: problem
        character(len=*), intent(in) :: level
        integer, intent(in) :: rows(:)
        real(wp), intent(in) :: block(:, :), scale(:)
        integer, allocatable, intent(out) :: chosen(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), diagonal(:)
        integer, allocatable :: order(:), translational(:)
        logical, allocatable :: leading(:)
        integer :: m, i, rank

        m = size(rows)
        allocate(chosen(0))
        if (m == 0) return
        a = block
        do i = 1, m
            a(i, :) = a(i, :)*scale
            if (norm2(a(i, :)) > 0.0_wp) a(i, :) = a(i, :)/norm2(a(i, :))
        end do
        ! first the translational columns alone: those of them that are independent lead
        translational = pack([(i, i = 1, size(a, 2))], modulo([(i, i = 0, size(a, 2) - 1)], &
            & 6) < 3)
        allocate(order(size(translational)), diagonal(min(m, size(translational))))
        call pivoted_columns(a(:, translational), order, diagonal, error)
        if (allocated(error)) return
        rank = count(diagonal > ic_rcond)
        allocate(leading(size(a, 2)), source=.false.)
        leading(translational(order(:rank))) = .true.
        deallocate(order, diagonal)
        allocate(order(size(a, 2)), diagonal(min(m, size(a, 2))))
        call pivoted_columns(a, order, diagonal, error, leading)
        if (allocated(error)) return
        if (m > size(a, 2) .or. .not. diagonal(min(m, size(a, 2))) > ic_rcond) then
            call fatal_error(error, "linearisation: the constraints' Jacobian is singular at " &
                & // "the start: the " // level // " rows of " // ucon_list(problem, level) &
                & // " are dependent (the smallest of " // to_text(m) // " pivots is " &
                & // to_text(diagonal(min(m, size(a, 2)))) // " of unit rows), so no " &
                & // "independent coordinates can be chosen (a singular configuration of " &
                & // "the mechanism)", stat_input)
            return
        end if
        chosen = order(:m)
    end subroutine pick_columns

    !> The active UCONs of a level (position: the position UCONs; velocity: all) in the user's
    !> words: "UCON/1, JOINT/2 (line 9: translation along ground X, ...)" (rollcon_model's
    !> rows_text).
    function ucon_list(problem, level) result(text)
        type(problem_type), intent(in) :: problem
        character(len=*), intent(in) :: level
        character(len=:), allocatable :: text
        logical :: flagged(problem%model%nc)
        integer :: k

        do k = 1, problem%model%nc
            flagged(k) = problem%eq%active_rows_of(k) .and. (level /= "position" .or. &
                & problem%model%ucons(k)%holonomic)
        end do
        text = problem%model%rows_text(flagged)
    end function ucon_list

    !> T (2n x d): identity in the independent rows, -J_D^-1 J_I in the dependent ones.
    subroutine tangent_basis(jac, dependent, independent, basis, error)
        real(wp), intent(in) :: jac(:, :)
        integer, intent(in) :: dependent(:), independent(:)
        real(wp), allocatable, intent(out) :: basis(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: lu(:, :), rhs(:, :)
        integer, allocatable :: ipiv(:)
        integer :: j

        allocate(basis(size(jac, 2), size(independent)), source=0.0_wp)
        do j = 1, size(independent)
            basis(independent(j), j) = 1.0_wp
        end do
        if (size(dependent) == 0) return
        lu = jac(:, dependent)
        rhs = -jac(:, independent)
        allocate(ipiv(size(dependent)))
        call factor_dense(lu, ipiv, error)
        if (allocated(error)) return
        call solve_factored(lu, ipiv, rhs, error)
        if (allocated(error)) return
        basis(dependent, :) = rhs
    end subroutine tangent_basis

    !> A T, column j the derivative of f along T_j: central differences at steps h and h/2
    !> combined by one Richardson step, h such that the largest scaled component of h T_j is
    !> options%step.
    subroutine directional_jacobian(problem, time, q, u, options, scale, basis, at, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        type(linear_options_type), intent(in) :: options
        real(wp), intent(in) :: scale(:), basis(:, :)
        real(wp), allocatable, intent(out) :: at(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: wide(:), narrow(:)
        real(wp) :: h
        integer :: j

        allocate(at(size(basis, 1), size(basis, 2)))
        do j = 1, size(basis, 2)
            h = options%step/maxval(abs(basis(:, j))/scale)
            call central_difference(problem, time, q, u, options%baumgarte, basis(:, j), h, &
                & wide, error)
            if (allocated(error)) return
            call central_difference(problem, time, q, u, options%baumgarte, basis(:, j), &
                & 0.5_wp*h, narrow, error)
            if (allocated(error)) return
            at(:, j) = (4.0_wp*narrow - wide)/3.0_wp
        end do
    end subroutine directional_jacobian

    !> (f(y + h t) - f(y - h t)) / (2 h).
    subroutine central_difference(problem, time, q, u, alpha, direction, h, slope, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:), alpha, direction(:), h
        real(wp), allocatable, intent(out) :: slope(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: plus(:), minus(:)

        call rhs(problem, time, q, u, alpha, h*direction, plus, error)
        if (allocated(error)) return
        call rhs(problem, time, q, u, alpha, -h*direction, minus, error)
        if (allocated(error)) return
        slope = (plus - minus)/(2.0_wp*h)
    end subroutine central_difference

    !> f(y + dy) = (u, a, w/T) of the ODE form (rollcon_ode_form): with DIFFs, y = (q, u, x)
    !> about the DIFFs' state x0 of the start, kept in x0 (model%diffs%x is the evaluation's).
    subroutine rhs(problem, time, q, u, alpha, dy, f, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:), alpha, dy(:)
        real(wp), allocatable, intent(out) :: f(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:), lambda(:), qs(:), us(:), x0(:)
        integer :: n, nd

        n = size(q)
        nd = problem%model%diffs%count()
        qs = q + dy(:n)
        us = u + dy(n + 1:2*n)
        allocate(a(n), lambda(problem%model%nc))
        if (nd > 0) then
            x0 = problem%model%diffs%x
            call problem%model%set_diff_state(x0 + dy(2*n + 1:), problem%model%diffs%w)
            call problem%diff_rates(time, qs, us, error)
            if (allocated(error)) return
        end if
        call problem%eq%accelerations(time, qs, us, alpha, a, lambda, error)
        if (nd > 0) then
            f = [us, a, problem%model%diffs%w/problem%model%diffs%time_unit]
            call problem%model%set_diff_state(x0, problem%model%diffs%w)
        else
            f = [us, a]
        end if
    end subroutine rhs

    !> max |A T - T A_red| / max |A T|, rows scaled by 1/scale, columns by the scaled size of
    !> T's column.
    pure function invariance_rest(at, basis, reduced, scale) result(rest)
        real(wp), intent(in) :: at(:, :), basis(:, :), reduced(:, :), scale(:)
        real(wp) :: rest
        real(wp), allocatable :: diff(:, :), sized(:, :)
        integer :: i, j
        real(wp) :: largest

        diff = at - matmul(basis, reduced)
        sized = at
        do j = 1, size(at, 2)
            largest = maxval(abs(basis(:, j))/scale)
            do i = 1, size(at, 1)
                diff(i, j) = diff(i, j)/(scale(i)*largest)
                sized(i, j) = sized(i, j)/(scale(i)*largest)
            end do
        end do
        rest = 0.0_wp
        if (size(at) == 0) return
        if (maxval(abs(sized)) > 0.0_wp) rest = maxval(abs(diff))/maxval(abs(sized))
    end function invariance_rest

    !> Eigenvalues of A_red, sorted (see before), and the count of zeros.
    subroutine sorted_eigenvalues(result, omega, error)
        type(linear_result_type), intent(inout) :: result
        !> The model's frequency scale [1/s] (frequency_scale)
        real(wp), intent(in) :: omega
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: re(:), im(:)
        integer :: d

        d = result%reduced
        allocate(re(d), im(d))
        call general_eigenvalues(result%reduced_matrix, re, im, error)
        if (allocated(error)) return
        call sort_eigenvalues(re, im)
        result%real_part = re
        result%imag_part = im
        result%zero_limit = zero_fraction*omega
        if (d > 0) result%zero_limit = zero_fraction*max(maxval(hypot(re, im)), omega)
        result%zeros = count(hypot(re, im) <= result%zero_limit)
    end subroutine sorted_eigenvalues

    !> Eigenvalues in the table's order: by decreasing real part, for equal real parts by
    !> decreasing |imaginary part|, + before - (insertion sort: a few dozen at most).
    pure subroutine sort_eigenvalues(re, im)
        real(wp), intent(inout) :: re(:), im(:)
        real(wp) :: r, m
        integer :: i, j

        do i = 2, size(re)
            r = re(i)
            m = im(i)
            j = i - 1
            do while (j >= 1)
                if (.not. before(r, m, re(j), im(j))) exit
                re(j + 1) = re(j)
                im(j + 1) = im(j)
                j = j - 1
            end do
            re(j + 1) = r
            im(j + 1) = m
        end do
    end subroutine sort_eigenvalues

    !> (r1, i1) comes before (r2, i2): a larger real part; for equal real parts a larger
    !> |imaginary part|, + before - (so a conjugate pair stays adjacent: LAPACK gives both the
    !> same real part)
    pure logical function before(r1, i1, r2, i2)
        real(wp), intent(in) :: r1, i1, r2, i2

        before = r1 > r2 .or. (r1 == r2 .and. (abs(i1) > abs(i2) .or. (abs(i1) == abs(i2) &
            & .and. i1 > i2)))
    end function before

end module rollcon_linearisation
