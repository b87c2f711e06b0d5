! SPDX-License-Identifier: MIT
!> A dataset's part whose principal axes start at the Euler singularity (its CM marker's z-axis
!> parallel to ground z: rollcon_adm_state's starts_singular) starts in those axes turned as a
!> re-basing turns them (about body x or body y, as rollcon_rebasing's chosen_turn picks from
!> its angular velocity: basis 1 or 20; docs/rebasing.md), as a run re-bases a part near the
!> singularity before its first row: part_state gives its start in the turned axes, and here
!> the model's part is turned to match (model%turn_part_axes) and the problem told
!> (problem%start_bases), so that the run counts the part as re-based from its first row on.
!>
!> First, the UCOSUB contract a re-basing checks (rollcon_rebase_step's compare_bases): every
!> UCON on the part gives the same F in the CM marker's axes and in the turned ones. The CM
!> marker's axes cannot hold the start itself (its angle rates divide by sin(theta) = 0), and
!> the other bases that can differ from the turned one by a half turn that reverses its z axis,
!> which a routine taking body z as an axis cannot tell apart. So the two are compared where
!> a run compares them, at the theta limit: the start tilted to theta_min in the CM marker's
!> axes, with its own velocities, and with test velocities added (a UCON linear in the rates
!> gives F = 0 in any basis at rest).
module rollcon_adm_singular
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, place
    use rollcon_rotation, only : rotation_matrix, rate_matrix, times, euler_angles
    use rollcon_rebasing, only : basis_axes, own_axes_rotation, rebased_state, angle_rates, &
        & turns_from_own, turn_about_x
    use rollcon_problem, only : problem_type
    use rollcon_rebase_step, only : compare_bases, basis_difference_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_state, only : starts_singular, part_state
    implicit none
    private

    public :: start_singular_parts

    !> Test velocities added to the start's in the second comparison: the centre's, ground
    !> axes [m/s], and the angular velocity, body axes [rad/s]; of unit size, along no axis
    real(wp), parameter :: probe_velocity(3) = [1.0_wp, 2.0_wp, 3.0_wp]/sqrt(14.0_wp)
    real(wp), parameter :: probe_rate(3) = [3.0_wp, 1.0_wp, 2.0_wp]/sqrt(14.0_wp)

contains

    !> Every part of adm that starts at the singularity, its start (q0, u0) in the turned basis
    !> (part_state's, 1 or 20): its UCONs checked, the model's part turned,
    !> problem%start_bases(p) that basis.
    !> A UCON that depends on the basis is an input error naming the part and the UCON.
    subroutine start_singular_parts(adm, problem, q0, u0, theta_min, error)
        type(adm_model_type), intent(in) :: adm
        !> Built from adm, its parts in their CM markers' axes
        type(problem_type), intent(inout) :: problem
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q0(:), u0(:)
        !> The theta limit of the run's re-basings [rad]
        real(wp), intent(in) :: theta_min
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        real(wp) :: q(6), u(6)
        integer, allocatable :: turns(:)
        integer :: i, p, basis, turn

        p = 0
        do i = 1, size(adm%parts)
            if (adm%parts(i)%ground) cycle
            p = p + 1
            if (.not. starts_singular(adm, adm%parts(i))) cycle
            where = place(adm%file, adm%parts(i)%line) // ": PART/" // to_text(adm%parts(i)%id)
            ! the basis part_state started the part in (q0 and u0 hold that start)
            call part_state(adm, adm%parts(i), q, u, basis)
            turns = turns_from_own(basis)
            turn = turns(1)
            call check_turned_start(where, problem, p, q0, u0, theta_min, basis, turn, error)
            if (allocated(error)) return
            ! a force in a disk's tilt frame cannot be turned (none in a dataset): refused
            call problem%model%turn_part_axes(p, turn, error)
            if (allocated(error)) then
                error%message = where // ": " // error%message
                return
            end if
            problem%start_bases(p) = basis
        end do
    end subroutine start_singular_parts

    !> The UCONs on part p (model order) against the contract: F in the CM marker's axes and
    !> in the turned ones at the start tilted to theta_min, with its own velocities and with
    !> probe_velocity and probe_rate added. Refused, naming the part and the UCON, when some
    !> F differs by more than a re-basing allows.
    subroutine check_turned_start(where, problem, p, q0, u0, theta_min, basis, turn, error)
        !> "file:line: PART/id"
        character(len=*), intent(in) :: where
        type(problem_type), intent(inout) :: problem
        integer, intent(in) :: p
        real(wp), intent(in) :: q0(:), u0(:), theta_min
        !> The basis the start is in, and the turn that takes the own axes to it
        integer, intent(in) :: basis, turn
        type(error_type), allocatable, intent(out) :: error
        type(basis_difference_type) :: found
        real(wp), allocatable :: q_own(:), u_own(:), q_turned(:), u_turned(:)
        real(wp) :: angles(3), omega(3)
        integer :: i0, probe

        i0 = 6*(p - 1)
        associate (q => q0(i0 + 1:i0 + 6), u => u0(i0 + 1:i0 + 6))
            ! the CM marker's axes, R_1 T^T, and the body angular velocity in them, T omega'_1
            angles = euler_angles(own_axes_rotation(rotation_matrix(q(4), q(5), q(6)), basis))
            omega = times(basis_axes(basis), times(rate_matrix(q(5), q(6)), u(4:6)))
        end associate
        ! tilted to the limit on its side of flat (theta = 0 or pi)
        angles(2) = merge(theta_min, pi - theta_min, cos(angles(2)) > 0.0_wp)
        q_own = q0
        u_own = u0
        q_own(i0 + 4:i0 + 6) = angles
        do probe = 0, 1
            u_own(i0 + 1:i0 + 3) = u0(i0 + 1:i0 + 3) + probe*probe_velocity
            u_own(i0 + 4:i0 + 6) = angle_rates(angles(2), angles(3), omega + probe*probe_rate)
            q_turned = q_own
            u_turned = u_own
            call rebased_state(q_own(i0 + 1:i0 + 6), u_own(i0 + 1:i0 + 6), &
                & q_turned(i0 + 1:i0 + 6), u_turned(i0 + 1:i0 + 6), turn)
            call compare_bases(problem, p, 0.0_wp, q_own, u_own, q_turned, u_turned, turn, &
                & found, error)
            if (allocated(error)) return
            if (found%k == 0) cycle
            call fatal_error(error, where // ": the z-axis of its principal axes (its CM " &
                & // "marker) is parallel to ground z at t = 0, where the 3-1-3 Euler angles " &
                & // "are singular, so the part starts in those axes turned 90 degrees about " &
                & // trim(merge("x", "y", turn == turn_about_x)) // " " &
                & // "(docs/rebasing.md); but " // problem%model%row_words(found%k) &
                & // " gives F = " // to_text(found%f_old) // " in the CM marker's axes and " &
                & // to_text(found%f_new) // " in the turned ones (compared with the part " &
                & // "tilted to theta = " // to_text(angles(2)) // " rad" &
                & // trim(merge(", test velocities added", "                       ", &
                & probe == 1)) // "; allowed difference " // to_text(found%allowed) &
                & // "): its UCOSUB depends on which principal axis is which; start the part " &
                & // "with its CM marker's z-axis more than " // to_text(theta_min) &
                & // " rad from ground z, or serve it by a routine that does not depend on the " &
                & // "axes", stat_input)
            return
        end do
    end subroutine check_turned_start

end module rollcon_adm_singular
