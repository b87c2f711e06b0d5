! SPDX-License-Identifier: MIT
!> Exact partials of a SPRINGDAMPER's or BUSHING's generalised forces for the Newton matrices
!> (docs/design.md §4): the element's force F and torque T (rollcon_spring_force's
!> definitions) written once more over jets of the coordinates and rates of its two parts
!> (rollcon_jet, rollcon_measures' marker_jets: forward mode, first order, no differences).
!>
!> On part p the element's generalised force is (s F, B^T R^T M), s = 1 on I's part and -1
!> on J's, M = s (r_I - c_p) x F + s T its moment about p's centre c_p, R = Rz(psi) Rx(theta)
!> Rz(phi) and B(theta, phi) the body rate matrix (rollcon_body's body_mass_and_force). The
!> body's own partials (rollcon_body's body_residual_jacobian) differentiate B^T with the
!> moment held at its body components R^T M; here the rest: s dF/dy and B^T d(R^T M)/dy over
!> every coordinate and rate y of both parts, so that the two together are the whole
!> derivative. A part that is both I's and J's feels no net load: nothing is added.
module rollcon_spring_partials
    use rollcon_kinds, only : wp
    use rollcon_momentum_partials, only : momentum_partials_type
    use rollcon_rotation, only : rate_matrix
    use rollcon_marker, only : marker_type
    use rollcon_jet, only : jet_type, jet_constant, jet_dot, jet_cross, jet_norm, &
        & operator(+), operator(-), operator(*), operator(/), atan2
    use rollcon_measures, only : state_jets_type, new_state_jets, marker_jets
    use rollcon_spring_force, only : spring_type, spring_translational, spring_rotational, &
        & spring_angle
    implicit none
    private

    public :: add_spring_partials

contains

    !> Subtract the element's partials of the generalised forces from dm (dm/dq, dm/du), the
    !> partials of the momentum residual M a - f (rollcon_equations' momentum_jacobian), over
    !> the rows and columns of I's and J's parts (dm: dense or on pairs of parts, which hold
    !> the element's two: rollcon_momentum_partials).
    pure subroutine add_spring_partials(self, i, j, q, u, dm)
        type(spring_type), intent(in) :: self
        !> The markers I and J
        type(marker_type), intent(in) :: i, j
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        type(momentum_partials_type), intent(inout) :: dm
        type(state_jets_type) :: state
        type(jet_type) :: force(3), torque(3), moment(3), local(3), centre(3), rotation(3, 3), &
            & point(3), axes(3, 3), dummy(3)
        type(marker_type) :: frame
        integer, allocatable :: parts(:), q_variable(:, :), u_variable(:, :)
        real(wp), allocatable :: q_parts(:, :), u_parts(:, :)
        real(wp) :: b(3, 3), sign_of
        integer :: s, c, n, k

        if (i%part == j%part) return
        parts = pack([i%part, j%part], [i%part, j%part] > 0)
        n = 12*size(parts)
        allocate(q_variable(6, size(parts)), u_variable(6, size(parts)), &
            & q_parts(6, size(parts)), u_parts(6, size(parts)))
        do s = 1, size(parts)
            q_parts(:, s) = q(6*(parts(s) - 1) + 1:6*parts(s))
            u_parts(:, s) = u(6*(parts(s) - 1) + 1:6*parts(s))
            q_variable(:, s) = [(6*(s - 1) + c, c = 1, 6)]
            u_variable(:, s) = [(6*size(parts) + 6*(s - 1) + c, c = 1, 6)]
        end do
        state = new_state_jets(parts, q_parts, u_parts, q_variable, u_variable, n, .false.)
        call load_jets(self, i, j, state, force, torque)
        do s = 1, size(parts)
            sign_of = merge(1.0_wp, -1.0_wp, parts(s) == i%part)
            ! the part's centre and rotation: a marker at its centre with its principal axes
            frame%part = parts(s)
            call marker_jets(frame, state, .false., centre, rotation, dummy, dummy)
            call marker_jets(i, state, .false., point, axes, dummy, dummy)
            ! the moment about the centre (the sign applied in subtract), in body components
            moment = jet_cross(point - centre, force) + torque
            do k = 1, 3
                local(k) = jet_dot(rotation(:, k), moment)
            end do
            b = rate_matrix(q_parts(5, s), q_parts(6, s))
            do c = 1, size(parts)
                do k = 1, 6
                    call dm%subtract_q(parts(s), parts(c), k, 1, column(6*(c - 1) + k))
                    call dm%subtract_u(parts(s), parts(c), k, 1, &
                        & column(6*size(parts) + 6*(c - 1) + k))
                end do
            end do
        end do

    contains

        !> Column `variable` of the generalised force's partials (s F, B^T R^T M) on the rows
        !> of the part, to be subtracted.
        pure function column(variable)
            integer, intent(in) :: variable
            real(wp) :: column(6)
            real(wp) :: d_force(3), d_body(3)
            integer :: a

            do a = 1, 3
                d_force(a) = partial(force(a), variable)
                d_body(a) = partial(local(a), variable)
            end do
            column(1:3) = sign_of*d_force
            column(4:6) = sign_of*matmul(transpose(b), d_body)
        end function column

    end subroutine add_spring_partials

    !> dv/dx_variable of a jet (0 for a constant).
    pure real(wp) function partial(a, variable)
        type(jet_type), intent(in) :: a
        integer, intent(in) :: variable

        partial = 0.0_wp
        if (a%active) partial = a%g(variable)
    end function partial

    !> The element's force and torque on I's part (rollcon_spring_force's spring_loads) as jets
    !> of the state's variables.
    pure subroutine load_jets(self, i, j, state, force, torque)
        type(spring_type), intent(in) :: self
        type(marker_type), intent(in) :: i, j
        type(state_jets_type), intent(in) :: state
        type(jet_type), intent(out) :: force(3), torque(3)
        type(jet_type) :: r_i(3), r_j(3), v_i(3), v_j(3), axes_i(3, 3), axes_j(3, 3), w_i(3), &
            & w_j(3), d(3), line(3), length, scalar, rate(3), angle, values(3), spin(3)
        real(wp) :: raw, shift
        integer :: k

        call marker_jets(i, state, .true., r_i, axes_i, v_i, w_i)
        call marker_jets(j, state, .true., r_j, axes_j, v_j, w_j)
        d = r_i - r_j
        force = jet_constant(0.0_wp)
        torque = jet_constant(0.0_wp)
        select case (self%kind)
        case (spring_translational)
            length = jet_norm(d)
            line = d/length
            scalar = -self%stiffness(1)*(length - self%reference) &
                & - self%damping(1)*jet_dot(v_i - v_j, line) + self%preload(1)
            force = scalar*line
        case (spring_rotational)
            angle = atan2(jet_dot(axes_i(:, 1), axes_j(:, 2)), jet_dot(axes_i(:, 1), &
                & axes_j(:, 1)))
            ! the branch spring_angle takes: whole turns, constants of the partials
            raw = angle%v
            shift = spring_angle(self, axes_value(axes_i), axes_value(axes_j)) - raw
            scalar = -self%torsional_stiffness(3)*(angle + shift - self%reference) &
                & - self%torsional_damping(3)*jet_dot(w_i - w_j, axes_j(:, 3)) &
                & + self%preload_torque(3)
            torque = scalar*axes_j(:, 3)
        case default
            rate = v_i - v_j - jet_cross(w_j, d)
            values(1) = atan2(-jet_dot(axes_i(:, 3), axes_j(:, 2)), jet_dot(axes_i(:, 3), &
                & axes_j(:, 3)))
            values(2) = atan2(jet_dot(axes_i(:, 3), axes_j(:, 1)), jet_dot(axes_i(:, 3), &
                & axes_j(:, 3)))
            values(3) = atan2(jet_dot(axes_i(:, 1), axes_j(:, 2)), jet_dot(axes_i(:, 1), &
                & axes_j(:, 1)))
            spin = w_i - w_j
            do k = 1, 3
                scalar = -self%stiffness(k)*jet_dot(axes_j(:, k), d) &
                    & - self%damping(k)*jet_dot(axes_j(:, k), rate) + self%preload(k)
                force = force + scalar*axes_j(:, k)
                scalar = -self%torsional_stiffness(k)*values(k) &
                    & - self%torsional_damping(k)*jet_dot(axes_j(:, k), spin) &
                    & + self%preload_torque(k)
                torque = torque + scalar*axes_j(:, k)
            end do
        end select
    end subroutine load_jets

    !> The values of a 3 x 3 matrix of jets.
    pure function axes_value(axes) result(values)
        type(jet_type), intent(in) :: axes(3, 3)
        real(wp) :: values(3, 3)
        integer :: a, k

        do k = 1, 3
            do a = 1, 3
                values(a, k) = axes(a, k)%v
            end do
        end do
    end function axes_value

end module rollcon_spring_partials
