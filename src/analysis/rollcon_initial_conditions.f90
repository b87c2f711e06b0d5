! SPDX-License-Identifier: MIT
!> Initial-conditions analysis, as ADAMS does before a dynamic run (docs/initial-conditions.md):
!> move a start (q, u) by the least weighted amount that satisfies every UCON.
!>
!> 1. Positions: Gauss-Newton on the position UCONs F_h(q, t) = 0, each step the minimum-norm
!>    least-squares solution of G dq = -F (G = dF_h/dq, the UCOSUBs' own first partials).
!> 2. Velocities: the minimum-norm least-squares solution of C du = -r, where C holds dF/du of
!>    every velocity UCON and dF/dq of every position UCON (its velocity form), and r their
!>    residuals; F is linear in u, so one step solves it (a second one only mops up rounding).
!> Weights: a part's translations count in metres and its angles times rho, the RMS distance
!> of its mass from its centre of mass, sqrt((J1 + J2 + J3)/(2 m)): a turn of d rad counts as
!> the rho d metres a typical point of the part moves. Rates likewise. Values marked exact are
!> held: their columns are removed. Velocities given (a dataset's VX ... WZ, each a linear
!> function of the rates) are held as ADAMS holds them: the least change is sought among the
!> rates that keep them, and only when the UCONs cannot be met so are they moved with the rest
!> (given_moved in the report); velocities not given are ADAMS's "inexact" zeros, free. Rows
!> are scaled to unit length before each solve (LAPACK dgelss, rcond below), so that rank and
!> least squares are judged by the constraints' geometry, not by their units. A large model
!> (options%sparse_columns free columns or more) is solved and judged by SuiteSparseQR on the
!> compressed rows, its given velocities held part by part (rollcon_ic_rows, part_held_steps):
!> no m x n or n x n array (docs/initial-conditions.md).
!> Refusals (stat_input), naming the statements and lines the user wrote: contradictory
!> (dependent rows, not all met), no convergence (independent rows still unmet after
!> max_iterations). Dependent rows that are all met are redundant, not refused: the run sets
!> aside those that repeat others (rollcon_redundancy).
module rollcon_initial_conditions
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_ic_rows, only : level_type, tolerance, least_change, verdict, ic_fraction, &
        & name_rows, ic_rcond, dense_rows, sparse_ic_columns
    use rollcon_constraints, only : constraint_state_type, need_value, need_first, need_time
    use rollcon_least_squares, only : left_null_space
    use rollcon_rotation, only : rate_matrix
    use rollcon_problem, only : problem_type
    use rollcon_ic_report, only : ic_change_type, ic_report_type
    implicit none
    private

    public :: ic_options_type, ic_options_of, analyse_initial_conditions

    !> Most least-squares steps on the velocity rows: one solves them (F is linear in u), a
    !> second removes rounding; more means they cannot be met
    integer, parameter :: max_velocity_steps = 3
    !> Largest change of any Euler angle in one Gauss-Newton step [rad], ADAMS's IC/ALIMIT
    !> default (30 degrees): a longer step is shortened along its direction, so that a poor
    !> start cannot jump across the Euler-angle singularity or to another branch
    real(wp), parameter :: angle_limit = 0.5235987755982988_wp

    !> How the analysis runs
    type :: ic_options_type
        !> Coordinates and rates held as given (system numbering; not allocated: none)
        logical, allocatable :: exact_q(:), exact_u(:)
        !> For each part (model order; not allocated: none), which of its velocities the input
        !> gives, held unless the UCONs cannot be met with them: VX, VY, VZ of the centre of
        !> mass (ground axes) and WX, WY, WZ, the angular velocity's components along the rows
        !> of given_axes
        logical, allocatable :: given_velocity(:, :)
        !> For each part, the axes of its given WX, WY, WZ (rows) in the principal axes the
        !> model holds the part in: (WX, WY, WZ) = given_axes omega', omega' = B(theta, phi)
        !> u_rot the body angular velocity (docs/design.md §3)
        real(wp), allocatable :: given_axes(:, :, :)
        !> Tolerances of the run [-, state units] (see ic_fraction)
        real(wp) :: rtol = 1.0e-8_wp, atol = 1.0e-10_wp
        !> Most Gauss-Newton iterations on the position UCONs (ADAMS's IC MAXIT default)
        integer :: max_iterations = 25
        !> Free columns from which a level goes the sparse way (rollcon_ic_rows'
        !> sparse_ic_columns, whose comment gives the choice): SuiteSparseQR's least squares and
        !> verdict, and velocities given held part by part (part_held_steps)
        integer :: sparse_columns = sparse_ic_columns
    end type ic_options_type

contains

    !> Options for a problem: its run's tolerances, nothing exact.
    pure function ic_options_of(problem) result(options)
        type(problem_type), intent(in) :: problem
        type(ic_options_type) :: options

        options%rtol = problem%settings%rtol
        options%atol = problem%settings%atol
        allocate(options%exact_q(problem%model%n), options%exact_u(problem%model%n), &
            & source=.false.)
    end function ic_options_of

    !> Move (q, u) onto the UCONs of a set-up problem by the least weighted change.
    subroutine analyse_initial_conditions(problem, time, q, u, options, report, error)
        !> Set up (problem%init); its constraint state is used as scratch
        type(problem_type), intent(inout), target :: problem
        !> Time of the start [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of every part [m, rad, m/s, rad/s]: the start on entry, the
        !> consistent start on exit (unchanged when the analysis refuses)
        real(wp), intent(inout) :: q(:), u(:)
        type(ic_options_type), intent(in) :: options
        type(ic_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q_new(:), u_new(:), weight(:)
        logical, allocatable :: free_q(:), free_u(:)
        integer :: n

        n = problem%model%n
        if (size(q) /= n .or. size(u) /= n) then
            call fatal_error(error, "initial conditions: q and u need " // to_text(n) &
                & // " values each (6 per part), got " // to_text(size(q)) // " and " &
                & // to_text(size(u)), stat_input)
            return
        end if
        weight = column_scales(problem)
        allocate(free_q(n), free_u(n), source=.true.)
        if (allocated(options%exact_q)) free_q = .not. options%exact_q
        if (allocated(options%exact_u)) free_u = .not. options%exact_u
        q_new = q
        u_new = u
        call position_level(problem, time, q_new, u_new, options, free_q, weight, report, error)
        if (allocated(error)) return
        call velocity_level(problem, time, q_new, u_new, options, free_u, weight, report, error)
        if (allocated(error)) return
        call list_changes(problem, q, q_new, u, u_new, options%atol, report)
        q = q_new
        u = u_new
    end subroutine analyse_initial_conditions

    !> The column scale of each coordinate: 1 for a translation, 1/rho_p for an angle (the
    !> solve's unknowns are then metres for both; see the module's header).
    pure function column_scales(problem) result(scale)
        type(problem_type), intent(in) :: problem
        real(wp) :: scale(problem%model%n)
        real(wp) :: rho
        integer :: p

        do p = 1, size(problem%model%parts)
            associate (part => problem%model%parts(p))
                rho = sqrt(sum(part%inertia)/(2.0_wp*part%mass))
                scale(6*p - 5:6*p - 3) = 1.0_wp
                scale(6*p - 2:6*p) = 1.0_wp/rho
            end associate
        end do
    end function column_scales

    !> Gauss-Newton on the position UCONs, then the verdict on them.
    subroutine position_level(problem, time, q, u, options, free, weight, report, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time
        real(wp), intent(inout) :: q(:)
        real(wp), intent(in) :: u(:)
        type(ic_options_type), intent(in) :: options
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        type(ic_report_type), intent(inout) :: report
        type(error_type), allocatable, intent(out) :: error
        type(level_type) :: level
        real(wp), allocatable :: dq(:)
        logical :: met, stalled

        level%name = "position"
        level%sparse_columns = options%sparse_columns
        level%ucon = holonomic_ucons(problem)
        call name_rows(level, problem%model)
        report%position_rows = size(level%ucon)
        if (size(level%ucon) == 0) return
        do
            call position_rows(problem, time, q, u, options, level, error)
            if (allocated(error)) return
            met = all(abs(level%residual) <= level%tolerance)
            if (met .or. report%newton_iterations >= options%max_iterations) exit
            call least_change(level, free, weight, dq, error)
            if (allocated(error)) return
            call limit_angles(dq)
            report%newton_iterations = report%newton_iterations + 1
            ! a least-squares stationary point (contradictory rows): no further progress
            stalled = all(abs(dq) <= 4.0_wp*epsilon(1.0_wp)*max(abs(q), 1.0_wp))
            q = q + dq
            if (stalled) then
                call position_rows(problem, time, q, u, options, level, error)
                if (allocated(error)) return
                met = all(abs(level%residual) <= level%tolerance)
                exit
            end if
        end do
        report%position_residual = maxval(abs(level%residual))
        call verdict(level, free, weight, met, report%newton_iterations, error)
    end subroutine position_level

    !> Least-squares steps on every UCON's velocity row, then the verdict on them. With
    !> velocities given (options%given_velocity), the steps are taken among the rates that keep
    !> them (held_steps); when the UCONs cannot be met so, the rates start again from u and
    !> every one that is not exact is free (report%given_moved).
    subroutine velocity_level(problem, time, q, u, options, free, weight, report, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(:)
        real(wp), intent(inout) :: u(:)
        type(ic_options_type), intent(in) :: options
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        type(ic_report_type), intent(inout) :: report
        type(error_type), allocatable, intent(out) :: error
        type(level_type) :: level
        real(wp), allocatable :: du(:), held(:, :), u_given(:)
        logical :: met, large
        integer :: k, held_count

        level%name = "velocity"
        level%sparse_columns = options%sparse_columns
        ! a contact's rows its mode drops at the start (a sliding or flying start: the
        ! equations' contact, rollcon_sliding_contact) are not made to hold
        level%ucon = pack([(k, k = 1, problem%model%nc)], [(.not. &
            & problem%eq%mode_drops(k), k = 1, problem%model%nc)])
        call name_rows(level, problem%model)
        report%velocity_rows = size(level%ucon)
        if (size(level%ucon) == 0) return
        ! a large model's held rows are never made whole: they are taken part by part
        large = count(free) >= options%sparse_columns
        if (large) then
            held_count = count_held(options, free)
        else
            held = held_rows(problem, q, options, free)
            held_count = size(held, 1)
        end if
        if (held_count > 0) then
            u_given = u
            if (large) then
                call part_held_steps(problem, time, q, u, options, free, weight, level, report, &
                    & met, error)
            else
                call held_steps(problem, time, q, u, options, held, weight, level, report, met, &
                    & error)
            end if
            if (allocated(error)) return
            if (met) then
                report%velocity_residual = maxval(abs(level%residual))
                call verdict(level, free, weight, met, report%velocity_steps, error)
                return
            end if
            ! the UCONs cannot be met with the given velocities held: ADAMS moves them too
            u = u_given
            report%velocity_steps = 0
            report%given_moved = .true.
        end if
        do
            call velocity_rows(problem, time, q, u, options, level, error)
            if (allocated(error)) return
            met = all(abs(level%residual) <= level%tolerance)
            if (met .or. report%velocity_steps >= max_velocity_steps) exit
            call least_change(level, free, weight, du, error)
            if (allocated(error)) return
            report%velocity_steps = report%velocity_steps + 1
            u = u + du
        end do
        report%velocity_residual = maxval(abs(level%residual))
        call verdict(level, free, weight, met, report%velocity_steps, error)
    end subroutine velocity_level

    !> The rows over u of every velocity held: each given VX, VY, VZ (a rate itself), each given
    !> WX, WY, WZ (given_axes(k, :) B(theta, phi) on the part's angle rates, at q), and each
    !> rate marked exact (not free). No rows when nothing is given.
    function held_rows(problem, q, options, free) result(rows)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: q(:)
        type(ic_options_type), intent(in) :: options
        logical, intent(in) :: free(:)
        real(wp), allocatable :: rows(:, :)
        real(wp) :: b(3, 3)
        integer :: p, k, i0, j, r

        allocate(rows(0, size(q)))
        if (.not. allocated(options%given_velocity)) return
        if (.not. any(options%given_velocity)) return
        deallocate(rows)
        allocate(rows(count(options%given_velocity) + count(.not. free), size(q)), &
            & source=0.0_wp)
        r = 0
        do p = 1, min(size(options%given_velocity, 2), size(problem%model%parts))
            i0 = 6*(p - 1)
            b = rate_matrix(q(i0 + 5), q(i0 + 6))
            do k = 1, 6
                if (.not. options%given_velocity(k, p)) cycle
                r = r + 1
                if (k <= 3) then
                    rows(r, i0 + k) = 1.0_wp
                else
                    rows(r, i0 + 4:i0 + 6) = matmul(options%given_axes(k - 3, :, p), b)
                end if
            end do
        end do
        do j = 1, size(free)
            if (free(j)) cycle
            r = r + 1
            rows(r, j) = 1.0_wp
        end do
    end function held_rows

    !> Least-squares steps on the velocity rows among the rates that keep the held rows: du =
    !> W Z dz, W the weights and Z an orthonormal basis of the null space of (held W), so that
    !> the least weighted change is found as before, in the coordinates z the held velocities
    !> leave free. met: the rows are met at the end.
    subroutine held_steps(problem, time, q, u, options, held, weight, level, report, met, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(ic_options_type), intent(in) :: options
        real(wp), intent(in) :: held(:, :), weight(:)
        type(level_type), intent(inout) :: level
        type(ic_report_type), intent(inout) :: report
        logical, intent(out) :: met
        type(error_type), allocatable, intent(out) :: error
        type(level_type) :: reduced
        real(wp), allocatable :: basis(:, :), dz(:), scaled(:, :), rows(:, :)
        integer :: rank, i, j

        scaled = held
        do j = 1, size(weight)
            scaled(:, j) = scaled(:, j)*weight(j)
        end do
        call left_null_space(transpose(scaled), ic_rcond, rank, basis, error)
        if (allocated(error)) return
        do j = 1, size(weight)
            basis(j, :) = basis(j, :)*weight(j)
        end do
        reduced%name = level%name
        reduced%ucon = level%ucon
        reduced%ids = level%ids
        ! its rows are given whole: the SVD's way at any size
        reduced%sparse_columns = huge(1)
        do
            call velocity_rows(problem, time, q, u, options, level, error)
            if (allocated(error)) return
            met = all(abs(level%residual) <= level%tolerance)
            if (met .or. report%velocity_steps >= max_velocity_steps .or. size(basis, 2) == 0) &
                & exit
            rows = dense_rows(level)
            reduced%rows = matmul(rows, basis)
            reduced%columns = size(basis, 2)
            ! a row that only the held rates carry (its part in the free coordinates z is
            ! rounding) is no row for the solve: judged, as unit_rows judges, against the whole
            ! weighted row, so that rounding is never scaled up to a step
            do i = 1, size(reduced%rows, 1)
                if (norm2(reduced%rows(i, :)) <= ic_rcond*norm2(rows(i, :)*weight)) &
                    & reduced%rows(i, :) = 0.0_wp
            end do
            reduced%residual = level%residual
            reduced%tolerance = level%tolerance
            call least_change(reduced, spread(.true., 1, size(basis, 2)), &
                & spread(1.0_wp, 1, size(basis, 2)), dz, error)
            if (allocated(error)) return
            report%velocity_steps = report%velocity_steps + 1
            u = u + matmul(basis, dz)
        end do
    end subroutine held_steps

    !> The number of held rows held_rows would make: none without a velocity given, else one
    !> per velocity given and per rate marked exact.
    pure integer function count_held(options, free)
        type(ic_options_type), intent(in) :: options
        logical, intent(in) :: free(:)

        count_held = 0
        if (.not. allocated(options%given_velocity)) return
        if (.not. any(options%given_velocity)) return
        count_held = count(options%given_velocity) + count(.not. free)
    end function count_held

    !> held_steps on a large model, with no n x n or m x n array: each held row (a velocity
    !> given, a rate marked exact) lies on one part's 6 rates, so (held W) is block diagonal by
    !> parts and so is the orthonormal basis Z of its null space: part p's block, 6 x (6 - r_p),
    !> from the SVD of its own held rows (left_null_space, 6 x h_p, rank r_p; the identity for a
    !> part with none). The reduced rows (rows W Z) stay compressed, each over the reduced
    !> columns of its UCON's parts, and are solved by SuiteSparseQR (rollcon_ic_rows'
    !> least_change, sparse way). The least weighted change is the same as held_steps' (any
    !> orthonormal basis of the same null space gives it) up to rounding, and but for a part
    !> whose held rows are near dependent: its rank is judged against its own largest singular
    !> value rather than the whole model's (both with ic_rcond).
    subroutine part_held_steps(problem, time, q, u, options, free, weight, level, report, &
            & met, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(ic_options_type), intent(in) :: options
        logical, intent(in) :: free(:)
        real(wp), intent(in) :: weight(:)
        type(level_type), intent(inout) :: level
        type(ic_report_type), intent(inout) :: report
        logical, intent(out) :: met
        type(error_type), allocatable, intent(out) :: error
        type(level_type) :: reduced
        real(wp), allocatable :: basis(:, :, :), dz(:), null(:, :)
        integer, allocatable :: kept(:), z0(:)
        real(wp) :: held(12, 6), b(3, 3), whole, length
        integer :: parts, p, k, i0, h, rank, j, i, e, f, c, out, first

        parts = size(q)/6
        allocate(basis(6, 6, parts), source=0.0_wp)
        allocate(kept(parts), z0(parts + 1))
        z0(1) = 0
        do p = 1, parts
            i0 = 6*(p - 1)
            h = 0
            held = 0.0_wp
            if (p <= size(options%given_velocity, 2)) then
                b = rate_matrix(q(i0 + 5), q(i0 + 6))
                do k = 1, 6
                    if (.not. options%given_velocity(k, p)) cycle
                    h = h + 1
                    if (k <= 3) then
                        held(h, k) = 1.0_wp
                    else
                        held(h, 4:6) = matmul(options%given_axes(k - 3, :, p), b)
                    end if
                end do
            end if
            do j = 1, 6
                if (free(i0 + j)) cycle
                h = h + 1
                held(h, :) = 0.0_wp
                held(h, j) = 1.0_wp
            end do
            if (h == 0) then
                kept(p) = 6
                do j = 1, 6
                    basis(j, j, p) = 1.0_wp
                end do
            else
                do j = 1, 6
                    held(:h, j) = held(:h, j)*weight(i0 + j)
                end do
                call left_null_space(transpose(held(:h, :)), ic_rcond, rank, null, error)
                if (allocated(error)) return
                kept(p) = size(null, 2)
                basis(:, :kept(p), p) = null
            end if
            do j = 1, 6
                basis(j, :, p) = basis(j, :, p)*weight(i0 + j)
            end do
            z0(p + 1) = z0(p) + kept(p)
        end do
        reduced%name = level%name
        reduced%ucon = level%ucon
        reduced%ids = level%ids
        reduced%sparse_columns = 0
        reduced%columns = z0(parts + 1)
        do
            call velocity_rows(problem, time, q, u, options, level, error)
            if (allocated(error)) return
            met = all(abs(level%residual) <= level%tolerance)
            if (met .or. report%velocity_steps >= max_velocity_steps .or. reduced%columns == 0) &
                & exit
            ! the rows times Z, part by part, over the reduced columns z0(p) + 1 .. z0(p + 1) of
            ! each part a row touches (a row's columns ascend, so its parts come in runs)
            if (.not. allocated(reduced%start)) then
                allocate(reduced%start(size(level%ucon) + 1), &
                    & reduced%column(6*size(level%column)), reduced%value(6*size(level%column)))
            end if
            out = 0
            reduced%start(1) = 1
            do i = 1, size(level%ucon)
                first = out + 1
                whole = 0.0_wp
                e = level%start(i)
                do while (e < level%start(i + 1))
                    p = (level%column(e) - 1)/6 + 1
                    f = e
                    do while (f + 1 < level%start(i + 1))
                        if ((level%column(f + 1) - 1)/6 + 1 /= p) exit
                        f = f + 1
                    end do
                    do c = 1, kept(p)
                        out = out + 1
                        reduced%column(out) = z0(p) + c
                        reduced%value(out) = 0.0_wp
                        do j = e, f
                            reduced%value(out) = reduced%value(out) + level%value(j) &
                                & *basis(level%column(j) - 6*(p - 1), c, p)
                        end do
                    end do
                    do j = e, f
                        whole = whole + (level%value(j)*weight(level%column(j)))**2
                    end do
                    e = f + 1
                end do
                ! a row that only the held rates carry (its part in the free coordinates z is
                ! rounding) is no row for the solve, judged as held_steps judges it
                length = norm2(reduced%value(first:out))
                if (length <= ic_rcond*sqrt(whole)) reduced%value(first:out) = 0.0_wp
                reduced%start(i + 1) = out + 1
            end do
            reduced%residual = level%residual
            reduced%tolerance = level%tolerance
            call least_change(reduced, spread(.true., 1, reduced%columns), &
                & spread(1.0_wp, 1, reduced%columns), dz, error)
            if (allocated(error)) return
            report%velocity_steps = report%velocity_steps + 1
            do p = 1, parts
                i0 = 6*(p - 1)
                u(i0 + 1:i0 + 6) = u(i0 + 1:i0 + 6) &
                    & + matmul(basis(:, :kept(p), p), dz(z0(p) + 1:z0(p + 1)))
            end do
        end do
    end subroutine part_held_steps

    !> Shorten dq along its direction so that no Euler angle changes by more than angle_limit.
    pure subroutine limit_angles(dq)
        real(wp), intent(inout) :: dq(:)
        real(wp) :: largest
        integer :: p

        largest = 0.0_wp
        do p = 1, size(dq)/6
            largest = max(largest, maxval(abs(dq(6*p - 2:6*p))))
        end do
        if (largest > angle_limit) dq = dq*(angle_limit/largest)
    end subroutine limit_angles

    !> The numbers (model order) of the position UCONs.
    pure function holonomic_ucons(problem) result(list)
        type(problem_type), intent(in) :: problem
        integer, allocatable :: list(:)
        integer :: k, h

        allocate(list(count([(problem%model%ucons(k)%holonomic, k = 1, problem%model%nc)])))
        h = 0
        do k = 1, problem%model%nc
            if (.not. problem%model%ucons(k)%holonomic) cycle
            h = h + 1
            list(h) = k
        end do
    end function holonomic_ucons

    !> The compressed rows of a level (rollcon_ic_rows' level_type): row i over the own
    !> coordinates of UCON level%ucon(i) (cs%local), sized once; n columns.
    pure subroutine shape_rows(level, cs, n)
        type(level_type), intent(inout) :: level
        type(constraint_state_type), intent(in) :: cs
        integer, intent(in) :: n
        integer :: i, m

        if (allocated(level%start)) return
        m = size(level%ucon)
        allocate(level%start(m + 1), level%residual(m), level%tolerance(m))
        level%start(1) = 1
        do i = 1, m
            level%start(i + 1) = level%start(i) + cs%local_count(level%ucon(i))
        end do
        allocate(level%column(level%start(m + 1) - 1), level%value(level%start(m + 1) - 1))
        do i = 1, m
            associate (k => level%ucon(i))
                level%column(level%start(i):level%start(i + 1) - 1) &
                    & = cs%local(:cs%local_count(k), k)
            end associate
        end do
        level%columns = n
    end subroutine shape_rows

    !> Row i of a level: UCON k's partials over its own coordinates, of F over q (position)
    !> or over u (velocity, of a velocity UCON).
    pure subroutine fill_row(level, i, cs, k, position)
        type(level_type), intent(inout) :: level
        integer, intent(in) :: i, k
        type(constraint_state_type), intent(in) :: cs
        logical, intent(in) :: position
        integer :: e

        do e = level%start(i), level%start(i + 1) - 1
            if (position) then
                level%value(e) = cs%grad_q_entry(k, level%column(e))
            else
                level%value(e) = cs%grad_u_entry(k, level%column(e))
            end if
        end do
    end subroutine fill_row

    !> Rows dF_h/dq, residuals F_h and tolerances of the position UCONs at (t, q).
    subroutine position_rows(problem, time, q, u, options, level, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        type(ic_options_type), intent(in) :: options
        type(level_type), intent(inout) :: level
        type(error_type), allocatable, intent(out) :: error
        integer :: i, m

        m = size(level%ucon)
        call problem%eq%constraints%evaluate(problem%model, time, q, u, need_value + need_first, &
            & error)
        if (allocated(error)) return
        associate (cs => problem%eq%constraints)
            call shape_rows(level, cs, size(q))
            do i = 1, m
                call fill_row(level, i, cs, level%ucon(i), .true.)
                level%residual(i) = cs%value(level%ucon(i))
                associate (e => level%start(i), f => level%start(i + 1) - 1)
                    level%tolerance(i) = tolerance(options%atol, options%rtol, &
                        & level%value(e:f), q(level%column(e:f)), level%residual(i))
                end associate
            end do
        end associate
    end subroutine position_rows

    !> Every UCON's velocity row at (t, q, u): dF/du and F for a velocity UCON, dF/dq and
    !> dF/dq u + dF/dt for a position UCON; and their tolerances.
    subroutine velocity_rows(problem, time, q, u, options, level, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        type(ic_options_type), intent(in) :: options
        type(level_type), intent(inout) :: level
        type(error_type), allocatable, intent(out) :: error
        integer :: k, m, row

        m = size(level%ucon)
        call problem%eq%constraints%evaluate(problem%model, time, q, u, need_value + need_first &
            & + need_time, error)
        if (allocated(error)) return
        associate (cs => problem%eq%constraints)
            call shape_rows(level, cs, size(u))
            do k = 1, m
                row = level%ucon(k)
                associate (e => level%start(k), f => level%start(k + 1) - 1)
                    if (problem%model%ucons(row)%holonomic) then
                        call fill_row(level, k, cs, row, .true.)
                        level%residual(k) = dot_product(level%value(e:f), u(level%column(e:f))) &
                            & + cs%dt(row)
                    else
                        call fill_row(level, k, cs, row, .false.)
                        level%residual(k) = cs%value(row)
                    end if
                    level%tolerance(k) = tolerance(options%atol, options%rtol, &
                        & level%value(e:f), u(level%column(e:f)), level%residual(k))
                end associate
            end do
        end associate
    end subroutine velocity_rows

    !> The values that moved by more than ic_fraction atol, positions then rates (counted
    !> first, then listed: a start that moves every value of a long chain lists them in linear
    !> time).
    pure subroutine list_changes(problem, q_old, q_new, u_old, u_new, atol, report)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: q_old(:), q_new(:), u_old(:), u_new(:), atol
        type(ic_report_type), intent(inout) :: report
        logical :: moved(2*size(q_old))
        integer :: j, p, c, i, listed

        do j = 1, size(q_old)
            moved(j) = .not. abs(q_new(j) - q_old(j)) <= ic_fraction*atol
            moved(size(q_old) + j) = .not. abs(u_new(j) - u_old(j)) <= ic_fraction*atol
        end do
        allocate(report%changes(count(moved)))
        listed = 0
        do j = 1, 2*size(q_old)
            if (.not. moved(j)) cycle
            listed = listed + 1
            p = (mod(j - 1, size(q_old)))/6 + 1
            c = mod(j - 1, 6) + 1
            if (j <= size(q_old)) then
                report%changes(listed) = ic_change_type(problem%model%parts(p)%id, c, &
                    & q_old(j), q_new(j))
            else
                i = j - size(q_old)
                report%changes(listed) = ic_change_type(problem%model%parts(p)%id, c + 6, &
                    & u_old(i), u_new(i))
            end if
        end do
    end subroutine list_changes

end module rollcon_initial_conditions
