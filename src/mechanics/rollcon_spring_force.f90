! SPDX-License-Identifier: MIT
!> Linear force elements between two markers, as ADAMS/Solver's SPRINGDAMPER and BUSHING
!> statements define them (docs/datasets-model.md, "Springs and bushings"), with d = r_I - r_J,
!> J's axes (x_J, y_J, z_J) and the measures of rollcon_measures:
!>
!> - translational SPRINGDAMPER: F = -K (DM - LENGTH) - C VR + FORCE along d/|d| on I at its
!>   origin (positive pushes I away from J), DM = |d|, VR = (v_I - v_J) . d/|d|;
!> - rotational SPRINGDAMPER: T = -KT (AZ - ANGLE) - CT WZ + TORQUE about z_J on I's part,
!>   AZ = atan2(x_I . y_J, x_I . x_J) with its whole turns counted (count_spring_turns),
!>   WZ = (w_I - w_J) . z_J;
!> - BUSHING: in J's axes, F = -K x - C v + FORCE and T = -KT a - CT w + TORQUE (products
!>   component by component), x = d in J's axes, v its time derivative in J's frame
!>   ((v_I - v_J - w_J x d) in J's axes), a = (AX, AY, AZ) of I's axes in J's (the small-angle
!>   measure, each in (-pi, pi]), w = (w_I - w_J) in J's axes.
!>
!> Each acts on I's part at I's origin with the force F and torque T; the reaction -F, -T acts
!> on J's part at the same point (for a BUSHING the reaction at J's origin is -F with the
!> torque -T - d x F, ADAMS's moment arm, which is the same load). Everything is in SI here;
!> the assembly converts the dataset's constants.
module rollcon_spring_force
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : times, transpose_times, cross
    use rollcon_marker, only : marker_type, marker_motion
    implicit none
    private

    public :: spring_type, spring_loads, spring_angle, count_spring_turns
    public :: spring_translational, spring_rotational, spring_bushing

    !> Kinds: a translational or rotational SPRINGDAMPER, a BUSHING
    integer, parameter :: spring_translational = 1, spring_rotational = 2, spring_bushing = 3

    !> One element's constants, SI
    type :: spring_type
        integer :: kind = spring_translational
        !> K, C along J's x, y, z (a translational SPRINGDAMPER's in the first) [N/m, N s/m]
        real(wp) :: stiffness(3) = 0.0_wp, damping(3) = 0.0_wp
        !> KT, CT about J's x, y, z (a rotational SPRINGDAMPER's in the third) [N m/rad,
        !> N m s/rad]
        real(wp) :: torsional_stiffness(3) = 0.0_wp, torsional_damping(3) = 0.0_wp
        !> FORCE and TORQUE: the preloads, in J's axes (a SPRINGDAMPER's in the first, the
        !> third) [N, N m]
        real(wp) :: preload(3) = 0.0_wp, preload_torque(3) = 0.0_wp
        !> A SPRINGDAMPER's LENGTH [m] or ANGLE [rad]
        real(wp) :: reference = 0.0_wp
        !> Rotational SPRINGDAMPER: the value of AZ where its whole turns were last counted
        !> [rad]
        real(wp) :: anchor = 0.0_wp
    end type spring_type

contains

    !> The element's force [N] and torque [N m] on I's part, ground components, acting at I's
    !> origin (the reaction, -force and -torque, acts on J's part at the same point).
    pure subroutine spring_loads(self, i, j, q, u, force, torque)
        type(spring_type), intent(in) :: self
        !> The markers I and J
        type(marker_type), intent(in) :: i, j
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: force(3), torque(3)
        real(wp) :: r_i(3), r_j(3), v_i(3), v_j(3), axes_i(3, 3), axes_j(3, 3), w_i(3), w_j(3)
        real(wp) :: d(3), length, line(3), local(3), rate(3), angles(3), spin(3)

        call marker_motion(i, q, u, r_i, v_i, axes_i, w_i)
        call marker_motion(j, q, u, r_j, v_j, axes_j, w_j)
        d = r_i - r_j
        force = 0.0_wp
        torque = 0.0_wp
        select case (self%kind)
        case (spring_translational)
            length = norm2(d)
            line = d/length
            force = (-self%stiffness(1)*(length - self%reference) &
                & - self%damping(1)*dot_product(v_i - v_j, line) + self%preload(1))*line
        case (spring_rotational)
            torque = (-self%torsional_stiffness(3)*(spring_angle(self, axes_i, axes_j) &
                & - self%reference) - self%torsional_damping(3)*dot_product(w_i - w_j, &
                & axes_j(:, 3)) + self%preload_torque(3))*axes_j(:, 3)
        case default
            local = transpose_times(axes_j, d)
            rate = transpose_times(axes_j, v_i - v_j - cross(w_j, d))
            angles = [axis_angle(1, axes_i, axes_j), axis_angle(2, axes_i, axes_j), &
                & axis_angle(3, axes_i, axes_j)]
            spin = transpose_times(axes_j, w_i - w_j)
            force = times(axes_j, -self%stiffness*local - self%damping*rate + self%preload)
            torque = times(axes_j, -self%torsional_stiffness*angles &
                & - self%torsional_damping*spin + self%preload_torque)
        end select
    end subroutine spring_loads

    !> A rotational SPRINGDAMPER's angle AZ(I, J) [rad] for I's and J's axes in ground
    !> (columns): on the branch nearest its anchor, so that whole turns are counted.
    pure real(wp) function spring_angle(self, axes_i, axes_j) result(angle)
        type(spring_type), intent(in) :: self
        real(wp), intent(in) :: axes_i(3, 3), axes_j(3, 3)
        real(wp) :: raw

        raw = axis_angle(3, axes_i, axes_j)
        angle = raw + 2.0_wp*pi*anint((self%anchor - raw)/(2.0_wp*pi))
    end function spring_angle

    !> Count a rotational SPRINGDAMPER's whole turns at (q, u): its anchor set to its angle
    !> there (restart: on the branch in (-pi, pi]). Made where the model counts the turns of
    !> its expressions' AX, AY, AZ (at a run's start and every output row), so an angle that
    !> turns by less than half a turn between rows is followed over any number of turns.
    pure subroutine count_spring_turns(self, i, j, q, u, restart)
        type(spring_type), intent(inout) :: self
        type(marker_type), intent(in) :: i, j
        real(wp), intent(in) :: q(:), u(:)
        logical, intent(in) :: restart
        real(wp) :: r(3), v(3), w(3), axes_i(3, 3), axes_j(3, 3)

        if (self%kind /= spring_rotational) return
        if (restart) self%anchor = 0.0_wp
        call marker_motion(i, q, u, r, v, axes_i, w)
        call marker_motion(j, q, u, r, v, axes_j, w)
        self%anchor = spring_angle(self, axes_i, axes_j)
    end subroutine count_spring_turns

    !> AX (axis 1), AY (2), AZ (3) of axes a_i in a_j, in (-pi, pi] (rollcon_measures'
    !> definitions).
    pure real(wp) function axis_angle(axis, a_i, a_j) result(angle)
        integer, intent(in) :: axis
        real(wp), intent(in) :: a_i(3, 3), a_j(3, 3)

        select case (axis)
        case (1)
            angle = atan2(-dot_product(a_i(:, 3), a_j(:, 2)), dot_product(a_i(:, 3), a_j(:, 3)))
        case (2)
            angle = atan2(dot_product(a_i(:, 3), a_j(:, 1)), dot_product(a_i(:, 3), a_j(:, 3)))
        case default
            angle = atan2(dot_product(a_i(:, 1), a_j(:, 2)), dot_product(a_i(:, 1), a_j(:, 1)))
        end select
    end function axis_angle

end module rollcon_spring_force
