! SPDX-License-Identifier: MIT
!> Static equilibrium, as ADAMS's SIMULATE/STATIC finds it (docs/analyses.md): every velocity
!> and acceleration zero, the coordinates q and the multipliers lambda that balance the
!> applied forces with the constraint forces on the constraint manifold,
!>
!>     f(q, 0, t) + C(q)^T lambda = 0      (n rows: the equations of motion at rest)
!>     F_h(q, t) = 0                       (each position UCON)
!>
!> found by Newton's method with the model's own partials: d/dq of f by the force statements'
!> jets (rollcon_static_forces), of C^T lambda by the UCOSUBs' second partials (XMATRX, as the
!> integrators' Newton matrices take them: rollcon_equations' momentum_jacobian), d/dlambda
!> C^T, and the position rows G = dF_h/dq. Each step is the minimum-norm least-squares solution
!> of the scaled system (LAPACK dgelss), so that repeated rows (a closed loop) and directions
!> no force holds (a neutral equilibrium) leave the step defined; a step is shortened along its
!> direction to move no translation by more than TLIMIT and no angle by more than ALIMIT.
!>
!> Converged (ADAMS's EQUILIBRIUM: each a condition that must hold, not a target): every
!> generalised force balanced within IMBALANCE (the translational rows in N, the rotational
!> ones in N m about the Euler axes), the last relative correction max |dq_j| / (1 + |q_j|)
!> within ERROR, and every position UCON met within the run's tolerances (as the
!> initial-conditions analysis judges it: rollcon_ic_rows). Once met, Newton goes on while
!> each step at least halves the largest imbalance, to the accuracy of rounding. A velocity
!> UCON must hold at rest (F(q, 0, t) = 0): one that asks for motion is refused. Refusals
!> (stat_input) name what failed: the iterations (MAXIT), the largest imbalance and its part,
!> the largest residual and its statement; a step that can no longer reduce the imbalance
!> (no equilibrium near the start); a value that is not finite.
module rollcon_static_equilibrium
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_constraints, only : need_value, need_first, need_second
    use rollcon_least_squares, only : minimum_norm_solve
    use rollcon_problem, only : problem_type
    use rollcon_ic_rows, only : tolerance, ic_rcond
    use rollcon_static_forces, only : applied_force_partials
    implicit none
    private

    public :: static_report_type, find_static_equilibrium, static_report_text

    !> What the static analysis found
    type :: static_report_type
        !> Time of the equilibrium [s]
        real(wp) :: time = 0.0_wp
        !> Newton iterations taken
        integer :: iterations = 0
        !> The largest force [N] and moment [N m] left unbalanced on a part, the largest |F_h|
        !> of a position UCON (its own unit) and of |F| of a velocity UCON at rest
        real(wp) :: force_imbalance = 0.0_wp, moment_imbalance = 0.0_wp
        real(wp) :: constraint_residual = 0.0_wp
        !> The last relative correction max |dq_j| / (1 + |q_j|)
        real(wp) :: correction = 0.0_wp
        !> The multipliers at the equilibrium (model order)
        real(wp), allocatable :: lambda(:)
    end type static_report_type

    !> The state of one Newton iterate
    type :: iterate_type
        real(wp), allocatable :: residual(:), jacobian(:, :)
        real(wp) :: force = 0.0_wp, moment = 0.0_wp, constraint = 0.0_wp
        !> Where the largest imbalance and residual are: part, row (model order)
        integer :: worst_part = 0, worst_row = 0
        logical :: met = .false.
    end type iterate_type

contains

    !> Find the static equilibrium of a set-up problem at `time` from the coordinates q.
    subroutine find_static_equilibrium(problem, time, q, report, error)
        !> Set up (problem%init, problem%prepare); its equations' state is used as scratch
        type(problem_type), intent(inout), target :: problem
        !> Time of the analysis [s] (a MOTION's value, a force's time)
        real(wp), intent(in) :: time
        !> Coordinates of every part [m, rad]: the start on entry, the equilibrium on exit
        !> (unchanged when refused)
        real(wp), intent(inout) :: q(:)
        type(static_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(iterate_type) :: now
        real(wp), allocatable :: x(:), dx(:), best(:), step(:)
        real(wp) :: best_imbalance, previous
        integer :: n, nc, rank
        logical :: converged

        n = problem%eq%n
        nc = problem%eq%nc
        report%time = time
        allocate(x(n + nc), source=0.0_wp)
        x(:n) = q
        converged = .false.
        previous = huge(1.0_wp)
        best_imbalance = huge(1.0_wp)
        do
            call evaluate(problem, time, x, now, error)
            if (allocated(error)) return
            if (.not. (all(ieee_is_finite(now%residual)) .and. &
                & all(ieee_is_finite(now%jacobian)))) then
                call fatal_error(error, "static equilibrium: the equations at rest are not " &
                    & // "finite after " // to_text(report%iterations) // " Newton iterations " &
                    & // "(a force or constraint of the model is not defined there)", stat_input)
                return
            end if
            if (.not. converged) converged = report%iterations > 0 .and. now%met .and. &
                & max(now%force, now%moment) <= problem%settings%equilibrium_imbalance .and. &
                & report%correction <= problem%settings%equilibrium_error
            if (converged) then
                ! polishing: kept while each step at least halves the imbalance
                if (max(now%force, now%moment) > 0.5_wp*best_imbalance) then
                    x = best
                    exit
                end if
                best = x
                best_imbalance = max(now%force, now%moment)
                if (best_imbalance == 0.0_wp) exit
            end if
            if (report%iterations >= problem%settings%equilibrium_maxit) exit
            call newton_step(now, dx, rank, error)
            if (allocated(error)) return
            step = dx
            call limit_step(step, n, problem%settings%equilibrium_tlimit, &
                & problem%settings%equilibrium_alimit)
            report%iterations = report%iterations + 1
            report%correction = 0.0_wp
            if (n > 0) report%correction = maxval(abs(step(:n))/(1.0_wp + abs(x(:n))))
            if (.not. converged .and. report%correction <= 4.0_wp*epsilon(1.0_wp) .and. &
                & .not. (now%met .and. max(now%force, now%moment) <= &
                & problem%settings%equilibrium_imbalance) .and. max(now%force, now%moment) &
                & >= 0.5_wp*previous) then
                call stalled_error(problem, now, report, error)
                return
            end if
            previous = max(now%force, now%moment)
            x = x + step
        end do
        if (.not. converged) then
            call fatal_error(error, "static equilibrium: Newton's method did not converge in " &
                & // to_text(report%iterations) // " iterations (EQUILIBRIUM/MAXIT): " &
                & // imbalance_words(problem, now), stat_input)
            return
        end if
        call evaluate(problem, time, x, now, error)
        if (allocated(error)) return
        call velocity_rows_at_rest(problem, time, x(:n), report, error)
        if (allocated(error)) return
        report%force_imbalance = now%force
        report%moment_imbalance = now%moment
        report%constraint_residual = max(report%constraint_residual, now%constraint)
        report%lambda = x(n + 1:)
        q = x(:n)
    end subroutine find_static_equilibrium

    !> The residual and the Jacobian at x = (q, lambda), and their measures.
    subroutine evaluate(problem, time, x, now, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, x(:)
        type(iterate_type), intent(inout) :: now
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: u(:), dfdq(:, :)
        integer :: n, nc, nh, k, h, ii, jj, i, j, p, x_c
        real(wp) :: size_k

        n = problem%eq%n
        nc = problem%eq%nc
        nh = problem%eq%nh
        allocate(u(n), source=0.0_wp)
        associate (q => x(:n), lambda => x(n + 1:), eq => problem%eq, cs => problem%eq%constraints)
            call cs%evaluate(problem%model, time, q, u, need_value + need_first + need_second, &
                & error)
            if (allocated(error)) return
            call eq%assemble(time, q, u)
            call eq%constraint_matrix()
            if (.not. allocated(now%residual)) allocate(now%residual(n + nh), &
                & now%jacobian(n + nh, n + nc))
            allocate(dfdq(n, n))
            call applied_force_partials(problem%model, time, q, dfdq)
            now%residual = 0.0_wp
            now%jacobian = 0.0_wp
            ! f + C^T lambda, C by rows over each UCON's coordinates (its entries alone: the
            ! same sums as the dense product's, less exact zeros)
            call eq%c%transpose_times(lambda, now%residual(:n))
            now%residual(:n) = eq%force + now%residual(:n)
            now%jacobian(:n, :n) = dfdq
            do k = 1, nc
                ! C^T's column k: row k's entries
                do x_c = eq%c%start(k), eq%c%start(k + 1) - 1
                    now%jacobian(eq%c%column(x_c), n + k) = eq%c%value(x_c)
                end do
            end do
            do k = 1, nc
                h = problem%model%holonomic_number(k)
                associate (at => eq%blocks%ucon_coordinates(eq%blocks%ucon_start(k): &
                        & eq%blocks%ucon_start(k + 1) - 1))
                    do jj = 1, size(at)
                        j = at(jj)
                        do ii = 1, size(at)
                            i = at(ii)
                            if (h > 0) then
                                now%jacobian(i, j) = now%jacobian(i, j) &
                                    & + lambda(k)*cs%hqq(ii, jj, k)
                            else
                                now%jacobian(i, j) = now%jacobian(i, j) &
                                    & + lambda(k)*cs%hqu(jj, ii, k)
                            end if
                        end do
                    end do
                end associate
                if (h == 0) cycle
                now%residual(n + h) = cs%value(k)
                call cs%fill_grad_q_row(k, now%jacobian(n + h, :n))
            end do
            now%force = 0.0_wp
            now%moment = 0.0_wp
            now%worst_part = 0
            do p = 1, n/6
                if (maxval(abs(now%residual(6*p - 5:6*p))) > max(now%force, now%moment) .or. &
                    & now%worst_part == 0) now%worst_part = p
                now%force = max(now%force, maxval(abs(now%residual(6*p - 5:6*p - 3))))
                now%moment = max(now%moment, maxval(abs(now%residual(6*p - 2:6*p))))
            end do
            now%constraint = 0.0_wp
            now%worst_row = 0
            now%met = .true.
            do k = 1, nc
                h = problem%model%holonomic_number(k)
                if (h == 0) cycle
                ! (the row's dF/dq, set above)
                size_k = tolerance(problem%settings%atol, problem%settings%rtol, &
                    & now%jacobian(n + h, :n), q, cs%value(k))
                if (abs(cs%value(k)) > size_k) now%met = .false.
                if (abs(cs%value(k)) >= now%constraint) then
                    now%constraint = abs(cs%value(k))
                    now%worst_row = k
                end if
            end do
        end associate
    end subroutine evaluate

    !> The Newton step dx = -J^+ r, by the minimum-norm least-squares solution of the system
    !> with its columns scaled to unit length, then its rows (the solution of a consistent
    !> system is the same; the rank is judged by the geometry, not the units).
    subroutine newton_step(now, dx, rank, error)
        type(iterate_type), intent(in) :: now
        real(wp), allocatable, intent(out) :: dx(:)
        integer, intent(out) :: rank
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: a(:, :), b(:), column(:), row(:)
        integer :: i, j

        a = now%jacobian
        b = -now%residual
        allocate(column(size(a, 2)), row(size(a, 1)))
        do j = 1, size(a, 2)
            column(j) = norm2(a(:, j))
            if (column(j) == 0.0_wp) column(j) = 1.0_wp
            a(:, j) = a(:, j)/column(j)
        end do
        do i = 1, size(a, 1)
            row(i) = norm2(a(i, :))
            if (row(i) == 0.0_wp) row(i) = 1.0_wp
            a(i, :) = a(i, :)/row(i)
            b(i) = b(i)/row(i)
        end do
        allocate(dx(size(a, 2)))
        call minimum_norm_solve(a, b, ic_rcond, dx, rank, error)
        if (allocated(error)) return
        dx = dx/column
    end subroutine newton_step

    !> Shorten the step along its direction so that no translation moves by more than tlimit
    !> [m] and no angle by more than alimit [rad] (EQUILIBRIUM/TLIMIT, ALIMIT).
    pure subroutine limit_step(step, n, tlimit, alimit)
        real(wp), intent(inout) :: step(:)
        integer, intent(in) :: n
        real(wp), intent(in) :: tlimit, alimit
        real(wp) :: ratio
        integer :: p

        ratio = 1.0_wp
        do p = 1, n/6
            ratio = max(ratio, maxval(abs(step(6*p - 5:6*p - 3)))/tlimit, &
                & maxval(abs(step(6*p - 2:6*p)))/alimit)
        end do
        if (ratio > 1.0_wp) step = step/ratio
    end subroutine limit_step

    !> Every velocity UCON holds at rest (F(q, 0, t) = 0), within the run's tolerances; its
    !> |F| counts in the report's constraint residual.
    subroutine velocity_rows_at_rest(problem, time, q, report, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:)
        type(static_report_type), intent(inout) :: report
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: u(size(q)), row(size(q)), limit
        integer :: k

        u = 0.0_wp
        call problem%eq%constraints%evaluate(problem%model, time, q, u, need_value &
            & + need_first, error)
        if (allocated(error)) return
        do k = 1, problem%eq%nc
            if (problem%model%holonomic_number(k) > 0) cycle
            call problem%eq%constraints%fill_grad_u_row(k, row)
            associate (value => problem%eq%constraints%value(k))
                limit = tolerance(problem%settings%atol, problem%settings%rtol, &
                    & row, u, value)
                report%constraint_residual = max(report%constraint_residual, abs(value))
                if (abs(value) > limit) then
                    call fatal_error(error, "static equilibrium: " &
                        & // problem%model%row_words(k) // " is not met at rest (F = " &
                        & // to_text(value) // " with every velocity zero): it asks for " &
                        & // "motion, and the model has no static equilibrium", stat_input)
                    return
                end if
            end associate
        end do
    end subroutine velocity_rows_at_rest

    !> The refusal of a Newton step that no longer changes the coordinates while the forces
    !> are not balanced: no equilibrium near the start.
    subroutine stalled_error(problem, now, report, error)
        type(problem_type), intent(in) :: problem
        type(iterate_type), intent(in) :: now
        type(static_report_type), intent(in) :: report
        type(error_type), allocatable, intent(out) :: error

        call fatal_error(error, "static equilibrium: no equilibrium near the start: after " &
            & // to_text(report%iterations) // " Newton iterations the step no longer moves " &
            & // "the model and the forces stay unbalanced (no constraint or force holds it " &
            & // "there): " // imbalance_words(problem, now), stat_input)
    end subroutine stalled_error

    !> "force imbalance X N and moment imbalance Y N m (largest on PART/id), constraint
    !> residual Z (statement)".
    function imbalance_words(problem, now) result(text)
        type(problem_type), intent(in) :: problem
        type(iterate_type), intent(in) :: now
        character(len=:), allocatable :: text

        text = "force imbalance " // to_text(now%force) // " N and moment imbalance " &
            & // to_text(now%moment) // " N m (EQUILIBRIUM/IMBALANCE " &
            & // to_text(problem%settings%equilibrium_imbalance) // ")"
        if (now%worst_part > 0) text = text // ", the largest on PART/" &
            & // to_text(problem%model%parts(now%worst_part)%id)
        if (now%worst_row > 0) then
            text = text // "; constraint residual " // to_text(now%constraint) // " (" &
                & // problem%model%row_words(now%worst_row) // ")"
        else
            text = text // "; no position constraint"
        end if
    end function imbalance_words

    !> The summary's line of a static equilibrium, ending in a newline.
    function static_report_text(report) result(text)
        type(static_report_type), intent(in) :: report
        character(len=:), allocatable :: text

        text = "static equilibrium at t = " // to_text(report%time) // " s: " &
            & // to_text(report%iterations) // " Newton iterations; force imbalance " &
            & // to_text(report%force_imbalance) // " N, moment imbalance " &
            & // to_text(report%moment_imbalance) // " N m, constraint residual " &
            & // to_text(report%constraint_residual) // new_line("a")
    end function static_report_text

end module rollcon_static_equilibrium
