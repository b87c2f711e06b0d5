! SPDX-License-Identifier: MIT
!> Why an event stopped a run, in words: which part reached which Euler-angle singularity, or
!> the lift-off of the part in contact, with the time and the state there.
module rollcon_event_message
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    implicit none
    private

    public :: event_message

contains

    !> The message of event function `root` (rollcon_problem's root_values) at (time, q, u).
    !> The theta limit of a disk scene's disk keeps the disk's own words; any other part is
    !> named by its id, with the singularity it came near (body z-axis along ground +Z at
    !> theta = 0, along -Z at theta = pi).
    function event_message(problem, root, time, q, u) result(message)
        type(problem_type), intent(in) :: problem
        !> Number of the event function that fired
        integer, intent(in) :: root
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of every part at the event [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        character(len=:), allocatable :: message
        integer :: p

        p = problem%theta_root_part(root)
        if (p > 0) then
            if (problem%events%has_contact .and. p == problem%events%part) then
                message = disk_theta_message(problem, time, q(6*p - 2), q(6*p - 1), u(6*p - 2))
            else
                message = part_theta_message(problem, p, time, q(6*p - 2), q(6*p - 1), &
                    & u(6*p - 2))
            end if
        else if (root == problem%root_count() .and. problem%events%watches_liftoff()) then
            p = problem%events%part
            message = "the normal contact force turned negative (below -" &
                & // to_text(problem%events%liftoff_force) // " N) at t = " // to_text(time) &
                & // " s (theta = " // to_text(q(6*p - 1)) // " rad, thetadot = " &
                & // to_text(u(6*p - 1)) // " rad/s): the disk would leave the " &
                & // "ground, which a rolling constraint cannot represent"
        else
            message = "event " // to_text(root) // " at t = " // to_text(time) // " s"
        end if
    end function event_message

    !> The theta limit of the disk in contact, in the disk's words.
    function disk_theta_message(problem, time, psi, theta, psidot) result(message)
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: time, psi, theta, psidot
        character(len=:), allocatable :: message

        associate (theta_min => problem%events%theta_min)
            if (cos(theta) >= 0.0_wp) then
                message = "theta fell to the limit theta_min = " // to_text(theta_min) &
                    & // " rad at t = "
            else
                message = "theta rose to pi - theta_min = " // to_text(pi - theta_min) &
                    & // " rad (the limit theta_min = " // to_text(theta_min) &
                    & // " rad from flat on the theta = pi side) at t = "
            end if
        end associate
        message = message // to_text(time) &
            & // " s: the disk lies nearly flat, where the 3-1-3 Euler angles become " &
            & // "singular (psi = " // to_text(psi) // " rad, psidot = " // to_text(psidot) &
            & // " rad/s)"
    end function disk_theta_message

    !> The theta limit of part p (model order), named by its id.
    function part_theta_message(problem, p, time, psi, theta, psidot) result(message)
        type(problem_type), intent(in) :: problem
        integer, intent(in) :: p
        real(wp), intent(in) :: time, psi, theta, psidot
        character(len=:), allocatable :: message

        message = "part " // to_text(problem%model%parts(p)%id) // ": "
        associate (theta_min => problem%events%theta_min)
            if (cos(theta) >= 0.0_wp) then
                message = message // "theta fell to the limit theta_min = " &
                    & // to_text(theta_min) // " rad at t = " // to_text(time) &
                    & // " s: its principal z-axis is nearly along ground +Z (theta = 0)"
            else
                message = message // "theta rose to pi - theta_min = " &
                    & // to_text(pi - theta_min) // " rad (the limit theta_min = " &
                    & // to_text(theta_min) // " rad from theta = pi) at t = " &
                    & // to_text(time) &
                    & // " s: its principal z-axis is nearly along ground -Z (theta = pi)"
            end if
        end associate
        message = message // ", the singularity of the 3-1-3 Euler angles, where psi and phi " &
            & // "are no longer defined apart (psi = " // to_text(psi) // " rad, psidot = " &
            & // to_text(psidot) // " rad/s)"
    end function part_theta_message

end module rollcon_event_message
