! SPDX-License-Identifier: MIT
!> Applied forces on parts: a fixed ground direction, a time profile, a point of application.
module rollcon_force
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : rotation_matrix, cross, times
    implicit none
    private

    public :: applied_force_type, force_and_moment, force_breakpoints
    public :: profile_constant, profile_half_sine, frame_body, frame_tilt

    !> Time profiles: constant magnitude, or one half-sine pulse carrying a given impulse
    integer, parameter :: profile_constant = 1, profile_half_sine = 2
    !> Frames the application point is given in: the body's principal axes, or the tilt frame
    !> Rz(psi) Rx(theta) (without the spin phi), where (0, R, 0) is the top of a disk's rim
    integer, parameter :: frame_body = 1, frame_tilt = 2


    !> A force of fixed ground direction acting on one part
    type :: applied_force_type
        !> Index of the part in the model
        integer :: part = 1
        !> Unit direction, ground components
        real(wp) :: direction(3) = [1.0_wp, 0.0_wp, 0.0_wp]
        !> profile_constant or profile_half_sine
        integer :: profile = profile_constant
        !> Magnitude of a constant force [N]
        real(wp) :: magnitude = 0.0_wp
        !> Pulse start [s], length [s] and impulse [N s]
        real(wp) :: start = 0.0_wp, duration = 1.0_wp, impulse = 0.0_wp
        !> frame_body or frame_tilt
        integer :: frame = frame_body
        !> Point of application relative to the centre of mass, in that frame [m]
        real(wp) :: point(3) = 0.0_wp
    end type applied_force_type

contains

    !> Magnitude of the force at time t [N].
    pure function force_magnitude(force, time) result(magnitude)
        type(applied_force_type), intent(in) :: force
        real(wp), intent(in) :: time
        real(wp) :: magnitude

        select case (force%profile)
        case (profile_half_sine)
            magnitude = 0.0_wp
            if (time >= force%start .and. time <= force%start + force%duration) then
                ! the integral of A sin(pi s / T) over one half period is 2 A T / pi
                magnitude = 0.5_wp*pi*force%impulse/force%duration &
                    & * sin(pi*(time - force%start)/force%duration)
            end if
        case default
            magnitude = force%magnitude
        end select
    end function force_magnitude

    !> Sum of the forces on part p and their moment about its centre, ground components.
    pure subroutine force_and_moment(forces, p, time, q, force, moment)
        !> All applied forces of the model
        type(applied_force_type), intent(in) :: forces(:)
        !> Part index
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> The part's coordinates [m, rad]
        real(wp), intent(in) :: q(6)
        !> Resultant force [N] and moment about the centre of mass [N m]
        real(wp), intent(out) :: force(3), moment(3)
        real(wp) :: f(3), arm(3), frame(3, 3)
        integer :: i

        force = 0.0_wp
        moment = 0.0_wp
        do i = 1, size(forces)
            if (forces(i)%part /= p) cycle
            f = force_magnitude(forces(i), time)*forces(i)%direction
            if (all(f == 0.0_wp)) cycle
            if (forces(i)%frame == frame_tilt) then
                frame = rotation_matrix(q(4), q(5), 0.0_wp)
            else
                frame = rotation_matrix(q(4), q(5), q(6))
            end if
            arm = times(frame, forces(i)%point)
            force = force + f
            moment = moment + cross(arm, f)
        end do
    end subroutine force_and_moment

    !> Times the integrator must stop at: the ends of each pulse and points inside it. An
    !> implicit step that jumps over a pulse samples the force only where it is zero, and a
    !> step-size limit set between steps takes effect only after the next step; stopping at
    !> pulse_points points per pulse resolves its shape whatever the step size was.
    pure function force_breakpoints(forces) result(times)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), allocatable :: times(:)
        integer, parameter :: pulse_points = 20
        integer :: i, k

        allocate(times(0))
        do i = 1, size(forces)
            if (forces(i)%profile == profile_half_sine) then
                times = [times, (forces(i)%start + k*forces(i)%duration/pulse_points, &
                    & k = 0, pulse_points)]
            end if
        end do
    end function force_breakpoints

end module rollcon_force
