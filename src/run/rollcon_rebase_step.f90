! SPDX-License-Identifier: MIT
!> One re-basing of a part during a run (docs/rebasing.md): the UCOSUB contract checked (every
!> UCON on the part gives the same F at the same physical state in both bases), the model's
!> part turned (rollcon_model's turn_part_axes) and its coordinates and rates replaced by those
!> of the turned basis (rollcon_rebasing); the state the integrator starts again from (on the
!> constraints, with its own accelerations and multipliers). The re-initialisation is the
!> caller's.
module rollcon_rebase_step
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_model, only : ucon_statement_type, statement_ucon
    use rollcon_ucosub_catalog, only : builtin_ucosub_name
    use rollcon_constraints, only : need_value, need_first
    use rollcon_rebasing, only : rebased_state, chosen_turn, turn_about_x, turn_about_y
    use rollcon_rotation, only : rate_matrix, times
    use rollcon_dynamic_system, only : dynamic_system_type
    implicit none
    private

    public :: rebase_part, compare_bases, basis_difference_type, restart_state, basis_rtol_floor

    !> A UCON whose F differs between two bases of a part (compare_bases)
    type :: basis_difference_type
        !> The UCON's number in the model (0: none differs)
        integer :: k = 0
        !> F in the first basis and in the second, and the difference allowed [F's unit, SI]
        real(wp) :: f_old = 0.0_wp, f_new = 0.0_wp, allowed = 0.0_wp
    end type basis_difference_type

    !> Least relative tolerance of the comparison of F in two bases [-]: a routine indifferent
    !> to the basis computes its terms from the sines and cosines of other angles, each term
    !> to a few rounding errors, summed over at most 30 variables: 1e3 eps of the terms' sizes
    real(wp), parameter :: basis_rtol_floor = 1.0e3_wp*epsilon(1.0_wp)

contains

    !> Re-base part p (model order) at (time, q, u), by the turn chosen_turn picks there
    !> (problem%rebase_turn when set). Before anything changes, every UCON on the part is
    !> evaluated at the same physical state in both bases (compare_bases): when some F
    !> differs by more than allowed, the other turn is tried (unless the turn is forced: a
    !> routine that takes body x, or body y, as an axis keeps its F under the turn about that
    !> axis alone); when it differs there too, the part is not re-based and `refusal` names the
    !> part, the UCON and the time (the first turn's values). Otherwise the model's part is
    !> turned and q and u hold the new basis's values (the caller counts the re-basing, with
    !> `turn`). A UCOSUB's own failure is an error.
    !>
    !> A fall (`fell`): the UCON that refuses is a built-in routine. Every built-in routine
    !> keeps the contract but the contacts whose geometry is the body's own z-axis (a disk's
    !> axle: disk, rolling_disk, disk_height, turntable_disk; a blade's normal: knife_edge),
    !> which have no contact point when that axis is vertical: the part lies flat on the ground,
    !> a state the model cannot pass. `refusal` then says what fell, when, and where it lies. A
    !> user's routine that refuses is named as breaking the contract (or lying flat: rollcon
    !> cannot tell which).
    subroutine rebase_part(problem, p, time, q, u, turn, refusal, error, fell)
        type(problem_type), intent(inout) :: problem
        !> Part index (model order)
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(inout) :: q(:), u(:)
        !> The turn (rollcon_rebasing's turn_about_x or turn_about_y)
        integer, intent(out) :: turn
        !> Why the part cannot be re-based (unallocated when it was)
        character(len=:), allocatable, intent(out) :: refusal
        type(error_type), allocatable, intent(out) :: error
        !> The refusal is a fall (see above)
        logical, intent(out), optional :: fell
        type(basis_difference_type) :: found, found_other
        real(wp), allocatable :: q_new(:), u_new(:), q_other(:), u_other(:)
        character(len=:), allocatable :: routine
        logical :: time_free
        integer :: i0, other

        if (present(fell)) fell = .false.
        i0 = 6*(p - 1)
        q_new = q
        u_new = u
        turn = problem%rebase_turn
        if (turn == 0) turn = chosen_turn(times(rate_matrix(q(i0 + 5), q(i0 + 6)), &
            & u(i0 + 4:i0 + 6)))
        call rebased_state(q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), q_new(i0 + 1:i0 + 6), &
            & u_new(i0 + 1:i0 + 6), turn)
        call compare_bases(problem, p, time, q, u, q_new, u_new, turn, found, error)
        if (allocated(error)) return
        if (found%k > 0 .and. problem%rebase_turn == 0) then
            other = merge(turn_about_x, turn_about_y, turn == turn_about_y)
            q_other = q
            u_other = u
            call rebased_state(q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), q_other(i0 + 1:i0 + 6), &
                & u_other(i0 + 1:i0 + 6), other)
            call compare_bases(problem, p, time, q, u, q_other, u_other, other, &
                & found_other, error)
            if (allocated(error)) return
            if (found_other%k == 0) then
                turn = other
                q_new = q_other
                u_new = u_other
                found = found_other
            end if
        end if
        if (found%k > 0) then
            routine = builtin_ucosub_name(problem%model%ucons(found%k)%ucosub, time_free)
            if (len(routine) > 0) then
                if (present(fell)) fell = .true.
                refusal = fall_words(problem, p, found%k, routine, time, q)
                return
            end if
            refusal = "part " // to_text(problem%model%parts(p)%id) &
                & // ": its principal axes cannot be re-based at t = " // to_text(time) &
                & // " s (theta = " // to_text(q(i0 + 5)) // " rad): " &
                & // ucon_words(problem, found%k) // " gives F = " &
                & // to_text(found%f_old) // " in the old basis and " // to_text(found%f_new) &
                & // " in the turned one (allowed difference " // to_text(found%allowed) &
                & // "): its UCOSUB depends on which principal axis is which (docs/rebasing.md; " &
                & // "if it is a contact about that axis, a wheel's axle, the part lies flat " &
                & // "on the ground: the model fell)"
            return
        end if
        call problem%model%turn_part_axes(p, turn, error)
        if (allocated(error)) return
        q = q_new
        u = u_new
    end subroutine rebase_part

    !> "UCON 3" (a UCON statement, as the message said it), or a JOINT's or JPRIM's equation in
    !> the user's words ("JOINT/1 (line 14), its translation along ground X").
    function ucon_words(problem, k) result(words)
        type(problem_type), intent(in) :: problem
        integer, intent(in) :: k
        character(len=:), allocatable :: words

        associate (statement => problem%model%statements(problem%model%ucons(k)%statement))
            if (statement%kind == statement_ucon .and. statement%line == 0) then
                words = "UCON " // to_text(problem%model%ucons(k)%id)
            else
                words = problem%model%row_words(k)
            end if
        end associate
    end function ucon_words

    !> "part 2 fell: it lies flat at t = 7.826 s, its principal z-axis 2.86 degrees from the
    !> vertical (theta = 0.05 rad) and its centre of mass 0.01499 m above the ground (Z): UCON
    !> 1 (rolling_disk), a contact about that axis, has no contact point there ..."
    function fall_words(problem, p, k, routine, time, q) result(words)
        type(problem_type), intent(in) :: problem
        !> The part (model order) and the UCON (model order) that cannot follow it
        integer, intent(in) :: p, k
        !> The UCON's routine
        character(len=*), intent(in) :: routine
        real(wp), intent(in) :: time, q(:)
        character(len=:), allocatable :: words
        real(wp), parameter :: degrees = 57.29577951308232_wp
        character(len=16) :: tilt, height

        associate (theta => q(6*p - 1), z => q(6*p - 3))
            write(tilt, '(f8.2)') degrees*min(theta, acos(-1.0_wp) - theta)
            write(height, '(es11.4)') z
            words = "part " // to_text(problem%model%parts(p)%id) // " fell: it lies flat at t = " &
                & // to_text(time) // " s, its principal z-axis " // trim(adjustl(tilt)) &
                & // " degrees from the vertical (theta = " // to_text(theta) &
                & // " rad) and its centre of mass at Z = " // trim(adjustl(height)) &
                & // " m: " // ucon_words(problem, k) // " (" // routine &
                & // "), a contact about that axis, has no contact point there, and the " &
                & // "motion cannot go on; the rows up to this one are valid"
        end associate
    end function fall_words

    !> The UCOSUB contract of a re-basing (docs/rebasing.md): every UCON on part p (a UCON
    !> with a variable of the part) evaluated at (time, q, u) and at (time, q_new, u_new), the
    !> same physical state in two bases of the part, the second the first turned by `turn`.
    !> `found` is the first whose F differs by more than atol + max(rtol, basis_rtol_floor) s_k
    !> (s_k: the sizes of F's terms at (q, u), term_sizes); found%k = 0 when none does.
    subroutine compare_bases(problem, p, time, q, u, q_new, u_new, turn, found, error)
        type(problem_type), intent(inout) :: problem
        !> Part index (model order)
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts in the two bases [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:), q_new(:), u_new(:)
        !> The turn from the first basis to the second (rollcon_rebasing)
        integer, intent(in) :: turn
        type(basis_difference_type), intent(out) :: found
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: f_old(:), f_new(:), scale(:)
        type(ucon_statement_type), allocatable :: saved(:)
        real(wp) :: allowed
        integer :: i0, k

        if (problem%eq%nc == 0) return
        i0 = 6*(p - 1)
        associate (constraints => problem%eq%constraints)
            call constraints%evaluate(problem%model, time, q, u, need_value + need_first, &
                & error)
            if (allocated(error)) return
            f_old = constraints%value
            scale = term_sizes(problem, q, u)
            ! the new basis with the geometry the driver owns turned with it (a joint's
            ! markers), as turn_part_axes will leave it; put back after the comparison
            saved = problem%model%ucons
            call problem%model%turn_ucon_geometry(p, turn)
            call constraints%evaluate(problem%model, time, q_new, u_new, need_value, error)
            problem%model%ucons = saved
            if (allocated(error)) return
            f_new = constraints%value
        end associate
        do k = 1, problem%eq%nc
            associate (ucon => problem%model%ucons(k))
                if (.not. any(ucon%coordinate > i0 .and. ucon%coordinate <= i0 + 6)) cycle
                allowed = problem%settings%atol &
                    & + max(problem%settings%rtol, basis_rtol_floor)*scale(k)
                if (abs(f_new(k) - f_old(k)) <= allowed) cycle
                found = basis_difference_type(k, f_old(k), f_new(k), allowed)
                return
            end associate
        end do
    end subroutine compare_bases

    !> The integrator's state (y, y') to start again from at (time, q, u), consistent to round-off
    !> (docs/rebasing.md): (q, u) put back on the constraints when the formulation holds them
    !> there (system%holds_constraints: IDA's DAE; an ODE form when it projects), by the model's
    !> mass-weighted least change (exact for velocity UCONs; Newton steps for position UCONs,
    !> until they no longer move q), then the accelerations and multipliers of the saddle-point
    !> system at that state, packed by the formulation (y' = (u, a, 0, 0) for IDA). The state at
    !> a root is IDA's or CVODE's interpolant, off the constraints by up to the tolerances: from
    !> there IDA's first step must move u by as much, whatever its size, and its error test
    !> failed at every step size (IDA_ERR_FAIL).
    subroutine restart_state(problem, system, time, q, u, y, yp, error)
        type(problem_type), intent(inout) :: problem
        !> The problem's formulation (rollcon_formulation_choice)
        class(dynamic_system_type), intent(inout) :: system
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]; on the constraints on return
        real(wp), intent(inout) :: q(:), u(:)
        !> The integrator's state and its derivative
        real(wp), intent(out) :: y(:), yp(:)
        type(error_type), allocatable, intent(out) :: error
        !> Newton steps on position UCONs: each squares the relative error of the last
        integer, parameter :: most_steps = 4
        real(wp) :: dq(size(q)), du(size(u))
        integer :: k

        if (problem%eq%nc > 0 .and. system%holds_constraints()) then
            do k = 1, most_steps
                call problem%eq%project(time, q, u, dq, du, error)
                if (allocated(error)) return
                q = q + dq
                u = u + du
                if (problem%eq%nh == 0 .or. all(q + dq == q)) exit
            end do
        end if
        call problem%accelerations(time, q, u, error)
        if (allocated(error)) return
        call system%pack_state(q, u, y, yp)
    end subroutine restart_state

    !> The size s_k of each UCON's F at (q, u), in F's unit, from the last evaluation's first
    !> partials: |F| + sum_j |dF/du_j u_j| + sum over translations |dF/dq_j q_j| + sum over
    !> angles |dF/dq_j| (1 rad). For a velocity UCON (linear in the rates) the middle sum is
    !> the sizes of its rate terms.
    function term_sizes(problem, q, u) result(sizes)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: sizes(problem%eq%nc)
        integer :: k, a, j

        associate (c => problem%eq%constraints)
            sizes = abs(c%value)
            ! over each UCON's own coordinates, ascending (its partials are zero elsewhere)
            do k = 1, size(sizes)
                do a = 1, c%local_count(k)
                    j = c%local(a, k)
                    ! (no dF/du where every UCON is a position UCON: its terms are zeros)
                    if (c%rates) sizes(k) = sizes(k) + abs(c%grad_u_local(a, k)*u(j))
                    if (mod(j - 1, 6) < 3) then
                        sizes(k) = sizes(k) + abs(c%grad_q_local(a, k)*q(j))
                    else
                        sizes(k) = sizes(k) + abs(c%grad_q_local(a, k))
                    end if
                end do
            end do
        end associate
    end function term_sizes

end module rollcon_rebase_step
