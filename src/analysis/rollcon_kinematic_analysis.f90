! SPDX-License-Identifier: MIT
!> Kinematic analysis, as ADAMS's SIMULATE/KINEMATIC runs it (docs/analyses.md): a model whose
!> constraints (its joints and the MOTIONs that drive them) leave no degree of freedom is moved
!> by them alone, solved at each output time t with no integration of forces:
!>
!> 1. positions: Newton's method on the position UCONs F_h(q, t) = 0, each step the
!>    minimum-norm least-squares solution of G dq = -F (G = dF_h/dq, the UCOSUBs' own first
!>    partials; rows scaled to unit length, so that repeated rows of a closed loop are judged by
!>    their geometry), from the last time's positions moved on by its velocities and
!>    accelerations; met when every row is within the run's tolerances (rollcon_ic_rows);
!> 2. velocities: G u = -dF_h/dt, one linear solve;
!> 3. accelerations and reactions: the saddle-point system of the equations of motion
!>    (rollcon_equations' accelerations): with no degree of freedom its constraint rows fix
!>    the accelerations, C a = gamma (the time partials and XMATRX), and its momentum rows give
!>    the multipliers, M a - f = C^T lambda: the forces the constraints and the MOTIONs must
!>    apply for the motion to happen, gravity and the applied forces included.
!>
!> A model with degrees of freedom left (n less the rank of G at the start) is refused, naming
!> how many; so is one with a velocity UCON (its positions are not fixed by constraints).
module rollcon_kinematic_analysis
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_constraints, only : need_value, need_first, need_time
    use rollcon_least_squares, only : minimum_norm_solve
    use rollcon_problem, only : problem_type
    use rollcon_ic_rows, only : tolerance, ic_rcond
    implicit none
    private

    public :: kinematic_freedom, kinematic_positions, kinematic_velocities

    !> Most Newton iterations on the positions at one time (ADAMS's KINEMATICS MAXIT default)
    integer, parameter :: max_iterations = 25
    !> Largest change of an angle in one iteration [rad] (ADAMS's KINEMATICS ALIMIT default,
    !> 30 degrees): a longer step is shortened along its direction
    real(wp), parameter :: angle_limit = 0.5235987755982988_wp

contains

    !> Refuse a model a kinematic analysis cannot move: a velocity UCON, or degrees of freedom
    !> left at (t, q): n less the rank of the position rows, scaled.
    subroutine kinematic_freedom(problem, time, q, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: g(:, :), f(:), dq(:)
        integer :: k, rank, n

        n = problem%eq%n
        do k = 1, problem%eq%nc
            if (problem%model%holonomic_number(k) > 0) cycle
            call fatal_error(error, "SIMULATE/KINEMATIC: " // problem%model%row_words(k) &
                & // " is a velocity constraint: a kinematic analysis moves a model by its " &
                & // "position constraints and MOTIONs alone; run SIMULATE/DYNAMIC", stat_input)
            return
        end do
        call position_rows(problem, time, q, g, f, error)
        if (allocated(error)) return
        call scaled_solve(g, f, dq, rank, error)
        if (allocated(error)) return
        if (rank < n) call fatal_error(error, "SIMULATE/KINEMATIC: the model has " &
            & // to_text(n - rank) // " degree(s) of freedom left (" // to_text(n) &
            & // " coordinates, " // to_text(rank) // " independent constraint equations); " &
            & // "a kinematic analysis needs none: drive each with a MOTION, or run " &
            & // "SIMULATE/DYNAMIC", stat_input)
    end subroutine kinematic_freedom

    !> Newton's method on the position UCONs at time t from q (a prediction), to every row met.
    subroutine kinematic_positions(problem, time, q, iterations, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time
        !> Coordinates [m, rad]: the prediction on entry, the solution on exit
        real(wp), intent(inout) :: q(:)
        !> Iterations taken
        integer, intent(out) :: iterations
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: g(:, :), f(:), dq(:)
        real(wp) :: largest
        integer :: rank, p, worst

        iterations = 0
        do
            call position_rows(problem, time, q, g, f, error)
            if (allocated(error)) return
            if (rows_met(problem, g, q, f, worst)) return
            if (iterations >= max_iterations .or. .not. all(ieee_is_finite(f))) exit
            call scaled_solve(g, f, dq, rank, error)
            if (allocated(error)) return
            largest = 0.0_wp
            do p = 1, size(q)/6
                largest = max(largest, maxval(abs(dq(6*p - 2:6*p))))
            end do
            if (largest > angle_limit) dq = dq*(angle_limit/largest)
            q = q - dq
            iterations = iterations + 1
        end do
        call fatal_error(error, "SIMULATE/KINEMATIC: no convergence after " &
            & // to_text(iterations) // " Newton iterations on the positions at t = " &
            & // to_text(time) // " s: the largest residual is " // to_text(abs(f(worst))) &
            & // " (" // problem%model%row_words(row_ucon(problem, worst)) // "); the " &
            & // "mechanism cannot be assembled there (a MOTION beyond its reach?)", stat_input)
    end subroutine kinematic_positions

    !> The velocities at (t, q): G u = -dF_h/dt.
    subroutine kinematic_velocities(problem, time, q, u, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(out) :: u(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: g(:, :), f(:), solution(:)
        integer :: rank, k, h

        call position_rows(problem, time, q, g, f, error)
        if (allocated(error)) return
        do k = 1, problem%eq%nc
            h = problem%model%holonomic_number(k)
            if (h > 0) f(h) = problem%eq%constraints%dt(k)
        end do
        call scaled_solve(g, f, solution, rank, error)
        if (allocated(error)) return
        u = -solution
    end subroutine kinematic_velocities

    !> The position rows G and values F at (t, q) (position UCONs in model order), with their
    !> time partials evaluated too (constraints%dt).
    subroutine position_rows(problem, time, q, g, f, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:)
        real(wp), allocatable, intent(out) :: g(:, :), f(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: u(size(q))
        integer :: k, h

        u = 0.0_wp
        call problem%eq%constraints%evaluate(problem%model, time, q, u, need_value + need_first &
            & + need_time, error)
        if (allocated(error)) return
        allocate(g(problem%eq%nh, size(q)), f(problem%eq%nh))
        do k = 1, problem%eq%nc
            h = problem%model%holonomic_number(k)
            if (h == 0) cycle
            call problem%eq%constraints%fill_grad_q_row(k, g(h, :))
            f(h) = problem%eq%constraints%value(k)
        end do
    end subroutine position_rows

    !> Every position row met within the run's tolerances; worst: the row of the largest |F|.
    logical function rows_met(problem, g, q, f, worst) result(met)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: g(:, :), q(:), f(:)
        integer, intent(out) :: worst
        integer :: h

        met = .true.
        worst = 1
        do h = 1, size(f)
            if (abs(f(h)) > abs(f(worst))) worst = h
            if (.not. abs(f(h)) <= tolerance(problem%settings%atol, problem%settings%rtol, &
                & g(h, :), q, f(h))) met = .false.
        end do
    end function rows_met

    !> The model's number (ucons) of position row h.
    pure integer function row_ucon(problem, h) result(k)
        type(problem_type), intent(in) :: problem
        integer, intent(in) :: h

        k = findloc(problem%model%holonomic_number, h, dim=1)
        if (k == 0) k = 1
    end function row_ucon

    !> x = A^+ b, the minimum-norm least-squares solution with A's rows scaled to unit length
    !> (a consistent system's solution is unchanged; the rank is judged by the geometry).
    subroutine scaled_solve(a, b, x, rank, error)
        real(wp), intent(in) :: a(:, :), b(:)
        real(wp), allocatable, intent(out) :: x(:)
        integer, intent(out) :: rank
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: scaled(:, :), rhs(:)
        real(wp) :: length
        integer :: i

        scaled = a
        rhs = b
        do i = 1, size(a, 1)
            length = norm2(a(i, :))
            if (length == 0.0_wp) cycle
            scaled(i, :) = scaled(i, :)/length
            rhs(i) = rhs(i)/length
        end do
        allocate(x(size(a, 2)))
        call minimum_norm_solve(scaled, rhs, ic_rcond, x, rank, error)
    end subroutine scaled_solve

end module rollcon_kinematic_analysis
