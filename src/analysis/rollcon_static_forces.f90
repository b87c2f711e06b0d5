! SPDX-License-Identifier: MIT
!> The partials of a model's applied forces at rest: d f(q, 0, t)/dq, the stiffness the static
!> equilibrium's Newton method needs (rollcon_static_equilibrium), exact to rounding: every
!> force statement (SFORCE, VFORCE, GFORCE: rollcon_marker_force) evaluated in jets over the
!> parts' coordinates (rollcon_force_partials, the loads the integrators' Newton matrices
!> differentiate too: the markers by rollcon_measures' marker_jets, the expressions by
!> rollcon_expression_jet, as a GCON's partials are found).
!>
!> Part p's generalised force at rest (docs/design.md §3) is f = (m g + F, E^T tau): F the
!> resultant of the loads on it, tau their moment about its centre of mass, both in ground
!> components, and E = [e_Z, e_x1, e_z2] the axes its Euler angles turn about (omega = E u_rot,
!> so that the power tau . omega is (E^T tau) . u_rot; E^T tau is B^T R^T tau, the form
!> rollcon_body writes). Gravity is constant. A scene's force of fixed direction (a pulse, a
!> strike) has no partials here: only datasets have a static analysis.
module rollcon_static_forces
    use rollcon_kinds, only : wp
    use rollcon_jet, only : jet_type, jet_constant, jet_cross, jet_dot, operator(+), &
        & operator(-), operator(*), sin, cos
    use rollcon_model, only : model_type
    use rollcon_force, only : profile_statement
    use rollcon_marker_force, only : marker_force_type, kind_spring
    use rollcon_force_partials, only : statement_value_jets, statement_load_jets
    use rollcon_spring_partials, only : add_spring_partials
    use rollcon_momentum_partials, only : momentum_partials_type
    use rollcon_measures, only : state_jets_type, new_state_jets
    implicit none
    private

    public :: applied_force_partials

contains

    !> d f/dq at (t, q, u = 0), n x n: row i the generalised force i (N, or N m about an
    !> Euler axis), column j the coordinate j (m or rad). f itself is the equations' (assemble).
    !> A SPRINGDAMPER's or BUSHING's are its own exact partials (rollcon_spring_partials).
    subroutine applied_force_partials(model, time, q, dfdq)
        type(model_type), intent(in) :: model
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates of every part [m, rad]
        real(wp), intent(in) :: q(:)
        real(wp), intent(out) :: dfdq(:, :)
        type(state_jets_type) :: state
        integer, allocatable :: parts(:), q_variable(:, :), u_variable(:, :)
        type(momentum_partials_type) :: residual
        integer :: np, n, s, c, i

        n = size(q)
        np = n/6
        dfdq = 0.0_wp
        parts = [(s, s = 1, np)]
        allocate(q_variable(6, np), u_variable(6, np), source=0)
        do s = 1, np
            do c = 1, 6
                q_variable(c, s) = 6*(s - 1) + c
            end do
        end do
        state = new_state_jets(parts, reshape(q, [6, np]), spread(spread(0.0_wp, 1, 6), 2, np), &
            & q_variable, u_variable, n, .false.)
        do i = 1, size(model%forces)
            if (model%forces(i)%profile /= profile_statement) cycle
            associate (statement => model%forces(i)%statement)
                if (statement%kind == kind_spring) then
                    ! the partials of the momentum residual M a - f: -df/dq
                    if (.not. allocated(residual%dq)) call residual%init_dense(n)
                    call residual%clear()
                    call add_spring_partials(statement%spring, statement%i, statement%j, q, &
                        & spread(0.0_wp, 1, n), residual)
                    dfdq = dfdq - residual%dq
                else
                    call statement_partials(statement, time, state, dfdq)
                end if
            end associate
        end do
    end subroutine applied_force_partials

    !> One force statement's loads in jets (rollcon_force_partials' statement_value_jets and
    !> statement_load_jets), added to dfdq on the parts they act on.
    subroutine statement_partials(statement, time, state, dfdq)
        type(marker_force_type), intent(in) :: statement
        real(wp), intent(in) :: time
        type(state_jets_type), intent(in) :: state
        real(wp), intent(inout) :: dfdq(:, :)
        type(jet_type) :: points(3, 2), forces(3, 2), torques(3, 2)
        integer :: loaded(2), l

        call statement_load_jets(statement, statement_value_jets(statement, time, state), &
            & state, loaded, points, forces, torques)
        do l = 1, 2
            call add_load(loaded(l), points(:, l), forces(:, l), torques(:, l), state, dfdq)
        end do
    end subroutine statement_partials

    !> A force f at ground point r and a torque on model part p (0: ground, nothing): their
    !> generalised force's partials added to p's rows of dfdq.
    subroutine add_load(p, r, f, torque, state, dfdq)
        integer, intent(in) :: p
        type(jet_type), intent(in) :: r(3), f(3), torque(3)
        type(state_jets_type), intent(in) :: state
        real(wp), intent(inout) :: dfdq(:, :)
        type(jet_type) :: moment(3), axis(3), arm(3)
        integer :: i0, k

        if (p <= 0) return
        i0 = 6*(p - 1)
        associate (qp => state%q(:, p))
            arm = r - qp(1:3)
            moment = jet_cross(arm, f) + torque
            do k = 1, 3
                call add_gradient(dfdq(i0 + k, :), f(k))
            end do
            ! the Euler axes: e_Z, e_x1 = (cos psi, sin psi, 0), e_z2 = R e_z
            call add_gradient(dfdq(i0 + 4, :), moment(3))
            axis = [cos(qp(4)), sin(qp(4)), jet_constant(0.0_wp)]
            call add_gradient(dfdq(i0 + 5, :), jet_dot(moment, axis))
            axis = [sin(qp(5))*sin(qp(4)), jet_constant(0.0_wp) - sin(qp(5))*cos(qp(4)), &
                & cos(qp(5))]
            call add_gradient(dfdq(i0 + 6, :), jet_dot(moment, axis))
        end associate
    end subroutine add_load

    !> row = row + the jet's gradient (nothing for a constant).
    pure subroutine add_gradient(row, value)
        real(wp), intent(inout) :: row(:)
        type(jet_type), intent(in) :: value

        if (value%active) row = row + value%g
    end subroutine add_gradient

end module rollcon_static_forces
