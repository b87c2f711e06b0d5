! SPDX-License-Identifier: MIT
!> Exact partials of a force statement's generalised forces (SFORCE, VFORCE, GFORCE, VTORQUE:
!> rollcon_marker_force) for the integrators' Newton matrices and the static Jacobian
!> (docs/design.md §4): the six values in jets over the coordinates and rates of every part
!> the statement touches (its I, J and RM markers' parts and the parts of every marker its
!> expressions read), the expressions by rollcon_expression_jet (forward mode over the
!> expression tree, no differences), the markers by rollcon_measures' marker_jets.
!>
!> The loads are those of marker_force_loads: a translational SFORCE's value along the line
!> from J to I on I at its origin and its reaction on J at J's; a rotational SFORCE's torque
!> about J's z axis; a VFORCE's or GFORCE's components in RM's axes on I at its origin and
!> the reaction on JFLOAT's part at the same point. On part p a load (F, T) at ground point r
!> is the generalised force (F, B^T R^T M), M = (r - c_p) x F + T its moment about p's centre
!> c_p (rollcon_body's body_mass_and_force). As for a SPRINGDAMPER (rollcon_spring_partials),
!> the body's own partials (rollcon_body's body_residual_jacobian) differentiate B^T with the
!> moment held at its body components R^T M; here the rest: dF/dy and B^T d(R^T M)/dy over
!> every coordinate and rate y of the parts touched.
module rollcon_force_partials
    use rollcon_kinds, only : wp
    use rollcon_momentum_partials, only : momentum_partials_type
    use rollcon_rotation, only : rate_matrix
    use rollcon_marker, only : marker_type
    use rollcon_jet, only : jet_type, jet_constant, jet_dot, jet_cross, jet_norm, &
        & operator(+), operator(-), operator(*), operator(/)
    use rollcon_measures, only : state_jets_type, new_state_jets, marker_jets, &
        & expression_input_jets
    use rollcon_expression_jet, only : evaluate_expression_jet
    use rollcon_diff_inputs, only : diff_input_jets
    use rollcon_expression, only : quantity_varval
    use rollcon_user_variable_values, only : user_variable_parts
    use rollcon_marker_force, only : marker_force_type, kind_translation, kind_rotation, &
        & kind_spring
    implicit none
    private

    public :: add_expression_force_partials, add_statement_load_partials
    public :: statement_parts, statement_state_jets, statement_value_jets, statement_load_jets
    public :: statement_couplings

contains

    !> The model parts (ground left out, each once, ascending) a force statement's loads
    !> depend on: its I, J and RM markers' parts, the parts of every marker its expressions read
    !> (markers) and, for a user's routine, of the markers its initialisation call named
    !> (declared_parts).
    pure function statement_parts(statement) result(parts)
        type(marker_force_type), intent(in) :: statement
        integer, allocatable :: parts(:)
        integer, allocatable :: parts_read(:)
        integer :: k, m, p

        allocate(parts(0))
        call add_part(statement%i%part)
        call add_part(statement%j%part)
        call add_part(statement%rm%part)
        if (allocated(statement%markers)) then
            do k = 1, size(statement%markers)
                call add_part(statement%markers(k)%part)
            end do
        end if
        if (allocated(statement%declared_parts)) then
            do k = 1, size(statement%declared_parts)
                call add_part(statement%declared_parts(k))
            end do
        end if
        ! the parts a VARSUB's value read through VARVAL depends on (its differences)
        do k = 1, 6
            if (.not. statement%given(k)) cycle
            if (.not. allocated(statement%functions(k)%inputs)) cycle
            do m = 1, size(statement%functions(k)%inputs)
                if (statement%functions(k)%inputs(m)%quantity /= quantity_varval) cycle
                parts_read = user_variable_parts(statement%functions(k)%inputs(m)%marker)
                do p = 1, size(parts_read)
                    call add_part(parts_read(p))
                end do
            end do
        end do

    contains

        !> p among the parts, in ascending order (ground and repeats left out).
        pure subroutine add_part(p)
            integer, intent(in) :: p
            integer :: at

            if (p <= 0) return
            if (any(parts == p)) return
            at = count(parts < p)
            parts = [parts(:at), p, parts(at + 1:)]
        end subroutine add_part

    end function statement_parts

    !> The coordinates and rates of parts(s) at (q, u) (all parts, SI) as jets: q(c) of slot
    !> s is variable 6 (s - 1) + c, its rate 6 size(parts) + 6 (s - 1) + c, of 12 size(parts);
    !> rates false: the rates are constants.
    pure function statement_state_jets(parts, q, u, rates) result(state)
        integer, intent(in) :: parts(:)
        real(wp), intent(in) :: q(:), u(:)
        logical, intent(in) :: rates
        type(state_jets_type) :: state
        integer, allocatable :: q_variable(:, :), u_variable(:, :)
        real(wp), allocatable :: q_parts(:, :), u_parts(:, :)
        integer :: s, c, np

        np = size(parts)
        allocate(q_variable(6, np), u_variable(6, np), q_parts(6, np), u_parts(6, np))
        do s = 1, np
            q_parts(:, s) = q(6*(parts(s) - 1) + 1:6*parts(s))
            u_parts(:, s) = u(6*(parts(s) - 1) + 1:6*parts(s))
            q_variable(:, s) = [(6*(s - 1) + c, c = 1, 6)]
            u_variable(:, s) = 0
            if (rates) u_variable(:, s) = [(6*np + 6*(s - 1) + c, c = 1, 6)]
        end do
        state = new_state_jets(parts, q_parts, u_parts, q_variable, u_variable, 12*np, .false.)
    end function statement_state_jets

    !> The statement's six expression values FX ... TZ at time [s] in jets over the state's
    !> variables, in SI (N, N m): marker_force_values' values with their exact partials.
    pure function statement_value_jets(statement, time, state) result(values)
        type(marker_force_type), intent(in) :: statement
        real(wp), intent(in) :: time
        type(state_jets_type), intent(in) :: state
        type(jet_type) :: values(6)
        type(jet_type), allocatable :: inputs(:)
        integer :: k, m

        values = jet_constant(0.0_wp)
        do k = 1, 6
            if (.not. statement%given(k)) cycle
            m = size(statement%functions(k)%inputs)
            allocate(inputs(m))
            call expression_input_jets(statement%functions(k), statement%markers, &
                & statement%length_unit, statement%time_unit, state, inputs)
            ! a DIFF's state (DIF, DIF1) as last set: a constant here, so a force's partials
            ! in the DIFF's states are not in the Newton matrices (docs/datasets.md, DIFF)
            if (allocated(statement%dif_ids)) call diff_input_jets(statement%functions(k), &
                & statement%dif_ids, statement%dif(:, 1), statement%dif(:, 2), inputs)
            values(k) = evaluate_expression_jet(statement%functions(k), &
                & jet_constant(time/statement%time_unit), inputs)
            deallocate(inputs)
        end do
        values(1:3) = values(1:3)*statement%force_unit
        values(4:6) = values(4:6)*(statement%force_unit*statement%length_unit)
    end function statement_value_jets

    !> The statement's loads from its values (SI jets): load 1 on I's part, load 2 (the
    !> reaction) on J's (JFLOAT's) part, part 0 for none (ground, ACTIONONLY); each a force
    !> [N] at a ground point [m] and a torque [N m], ground components, as jets.
    pure subroutine statement_load_jets(statement, values, state, parts, points, forces, &
            & torques)
        type(marker_force_type), intent(in) :: statement
        type(jet_type), intent(in) :: values(6)
        type(state_jets_type), intent(in) :: state
        integer, intent(out) :: parts(2)
        type(jet_type), intent(out) :: points(3, 2), forces(3, 2), torques(3, 2)
        type(jet_type) :: r_i(3), r_j(3), axes_i(3, 3), axes_j(3, 3), axes_rm(3, 3), r_rm(3), &
            & v(3), w(3), f(3), torque(3), line(3), length
        integer :: k

        call marker_jets(statement%i, state, .false., r_i, axes_i, v, w)
        call marker_jets(statement%j, state, .false., r_j, axes_j, v, w)
        parts = [statement%i%part, statement%j%part]
        if (statement%action_only) parts(2) = 0
        torque = jet_constant(0.0_wp)
        points(:, 1) = r_i
        points(:, 2) = r_i
        select case (statement%kind)
        case (kind_translation)
            if (statement%action_only) then
                line = axes_j(:, 3)
            else
                line = r_i - r_j
                length = jet_norm(line)
                line = line/length
            end if
            f = values(1)*line
            points(:, 2) = r_j
        case (kind_rotation)
            ! the value is a torque: its unit is force times length
            torque = values(1)*statement%length_unit*axes_j(:, 3)
            f = jet_constant(0.0_wp)
            points(:, 2) = r_j
        case default
            call marker_jets(statement%rm, state, .false., r_rm, axes_rm, v, w)
            do k = 1, 3
                f(k) = axes_rm(k, 1)*values(1) + axes_rm(k, 2)*values(2) &
                    & + axes_rm(k, 3)*values(3)
                torque(k) = axes_rm(k, 1)*values(4) + axes_rm(k, 2)*values(5) &
                    & + axes_rm(k, 3)*values(6)
            end do
        end select
        forces(:, 1) = f
        torques(:, 1) = torque
        forces(:, 2) = jet_constant(0.0_wp) - f
        torques(:, 2) = jet_constant(0.0_wp) - torque
    end subroutine statement_load_jets

    !> Subtract an expression force statement's partials of the generalised forces from dm
    !> (dm/dq, dm/du), the partials of the momentum residual M a - f (n x n, n = 6 parts: dense
    !> or on pairs of parts, rollcon_momentum_partials), over the rows of the parts it loads
    !> and the columns of the parts it touches (statement_parts).
    !> A SPRINGDAMPER or BUSHING (rollcon_spring_partials) and a user's routine
    !> (rollcon_user_force_partials) are not served here: nothing is added.
    pure subroutine add_expression_force_partials(statement, time, q, u, dm)
        type(marker_force_type), intent(in) :: statement
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        type(momentum_partials_type), intent(inout) :: dm
        type(state_jets_type) :: state
        integer, allocatable :: parts(:)

        if (statement%kind == kind_spring .or. statement%routine > 0) return
        parts = statement_parts(statement)
        if (size(parts) == 0) return
        state = statement_state_jets(parts, q, u, .true.)
        call add_statement_load_partials(statement, statement_value_jets(statement, time, &
            & state), state, q, dm)
    end subroutine add_expression_force_partials

    !> Subtract the partials of the loads of a statement whose values are the jets `values`
    !> (over the variables of state, statement_state_jets of statement_parts) from dm (dm/dq,
    !> dm/du: module doc: s dF/dy and B^T d(R^T M)/dy, rows of each loaded part, columns of
    !> every part held).
    pure subroutine add_statement_load_partials(statement, values, state, q, dm)
        type(marker_force_type), intent(in) :: statement
        type(jet_type), intent(in) :: values(6)
        type(state_jets_type), intent(in) :: state
        !> Coordinates of all parts [m, rad]
        real(wp), intent(in) :: q(:)
        type(momentum_partials_type), intent(inout) :: dm
        type(jet_type) :: points(3, 2), forces(3, 2), torques(3, 2), centre(3), rotation(3, 3), &
            & moment(3), local(3), dummy(3)
        type(marker_type) :: frame
        integer :: loaded(2), l, p, np, c, k, a, variable
        real(wp) :: b(3, 3), d_force(3), d_body(3)

        call statement_load_jets(statement, values, state, loaded, points, forces, torques)
        np = size(state%parts)
        do l = 1, 2
            p = loaded(l)
            if (p <= 0) cycle
            ! the part's centre and rotation: a marker at its centre with its principal axes
            frame%part = p
            call marker_jets(frame, state, .false., centre, rotation, dummy, dummy)
            moment = jet_cross(points(:, l) - centre, forces(:, l)) + torques(:, l)
            do k = 1, 3
                local(k) = jet_dot(rotation(:, k), moment)
            end do
            b = rate_matrix(q(6*(p - 1) + 5), q(6*(p - 1) + 6))
            do c = 1, np
                do k = 1, 6
                    variable = 6*(c - 1) + k
                    do a = 1, 3
                        d_force(a) = partial(forces(a, l), variable)
                        d_body(a) = partial(local(a), variable)
                    end do
                    call dm%subtract_q(p, state%parts(c), k, 1, d_force)
                    call dm%subtract_q(p, state%parts(c), k, 4, matmul(transpose(b), d_body))
                    variable = 6*np + 6*(c - 1) + k
                    do a = 1, 3
                        d_force(a) = partial(forces(a, l), variable)
                        d_body(a) = partial(local(a), variable)
                    end do
                    call dm%subtract_u(p, state%parts(c), k, 1, d_force)
                    call dm%subtract_u(p, state%parts(c), k, 4, matmul(transpose(b), d_body))
                end do
            end do
        end do
    end subroutine add_statement_load_partials

    !> The pairs of parts (2 x m, the smaller first, ground and repeats left out) where a force
    !> statement that is not a SPRINGDAMPER or BUSHING writes partials outside a part's own
    !> block: each part it loads (I's; J's unless ACTIONONLY) with each part it touches
    !> (statement_parts).
    pure function statement_couplings(statement) result(pairs)
        type(marker_force_type), intent(in) :: statement
        integer, allocatable :: pairs(:, :)
        integer, allocatable :: parts(:)
        integer :: loaded(2), l, k, a, b, m

        allocate(pairs(2, 0))
        if (statement%kind == kind_spring) return
        parts = statement_parts(statement)
        loaded = [statement%i%part, statement%j%part]
        if (statement%action_only) loaded(2) = 0
        do l = 1, 2
            if (loaded(l) <= 0) cycle
            do k = 1, size(parts)
                if (parts(k) == loaded(l)) cycle
                a = min(parts(k), loaded(l))
                b = max(parts(k), loaded(l))
                do m = 1, size(pairs, 2)
                    if (pairs(1, m) == a .and. pairs(2, m) == b) exit
                end do
                if (m > size(pairs, 2)) pairs = reshape([pairs, a, b], [2, size(pairs, 2) + 1])
            end do
        end do
    end function statement_couplings

    !> dv/dx_variable of a jet (0 for a constant).
    pure real(wp) function partial(a, variable)
        type(jet_type), intent(in) :: a
        integer, intent(in) :: variable

        partial = 0.0_wp
        if (a%active) partial = a%g(variable)
    end function partial

end module rollcon_force_partials
