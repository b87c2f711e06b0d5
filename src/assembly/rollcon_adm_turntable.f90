! SPDX-License-Identifier: MIT
!> A CONTACT's plane on a turntable: a PLANE on a part held to the ground by a REVOLUTE whose
!> axis is along ground Z and driven by a rotational MOTION of constant rate (FUNCTION =
!> Omega*TIME, or with VELOCITY, FUNCTION = Omega). The table's top is the plane's RM marker:
!> its origin's height, its z along ground +Z. A contact on it holds the no-slip rows relative
!> to the table (the contact point's velocity equals the table's material velocity
!> Omega e_Z x (r_C - c) there, c on the axis): rollcon_adm_contact serves them by the
!> generated turntable_ball and turntable_disk routines (ucon/specs/turntable_*.py), whose
!> parameters are the rate and the axis' position. The table's motion is prescribed, so the
!> contact acts on the sphere or rim alone (docs/datasets.md, "CONTACT on a turntable").
module rollcon_adm_turntable
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, place
    use rollcon_rotation, only : rotation_matrix
    use rollcon_expression, only : evaluate_expression, op_constant, op_time, op_multiply
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_motions, only : motion_displacement_form, motion_velocity_form
    implicit none
    private

    public :: turntable_type, find_turntable

    !> Tolerance of the axis' direction and the plane's normal (the numbers a dataset writes to
    !> full precision agree to rounding, 1e-16; off by more than 1e-9 is another geometry)
    real(wp), parameter :: direction_tolerance = 1.0e-9_wp

    !> A contact's plane on a turntable
    type :: turntable_type
        !> The table's part: its id and its place in adm%parts
        integer :: part_id = 0, part = 0
        !> The rate about ground +Z [rad/s] (SI), and the same per the dataset's time unit
        real(wp) :: rate = 0.0_wp, dataset_rate = 0.0_wp
        !> The axis' ground X and Y [m], and the table's top's height Z [m]
        real(wp) :: axis(2) = 0.0_wp, height = 0.0_wp
        !> "JOINT/id" and "MOTION/id" that make it
        character(len=:), allocatable :: joint_name, motion_name
    end type turntable_type

contains

    !> The turntable of the PLANE whose RM marker is plane_marker, on the moving part
    !> adm%parts(p): one REVOLUTE between that part and the ground, its J marker's z along
    !> ground +Z or -Z (the axis vertical), driven by one MOTION on that joint of ROTATION whose
    !> FUNCTION is Omega*TIME (TIME, Omega*TIME or TIME*Omega, displacement form) or with
    !> VELOCITY a constant Omega; the plane's normal along ground +Z. where: "file:line:
    !> CONTACT/id", the start of the messages. Errors, with the statement, its line and why: no
    !> such joint or two, an axis not vertical, no MOTION (free rotation), a MOTION of another
    !> form or of other than a constant rate, a user's MOTSUB, a plane not facing up.
    subroutine find_turntable(adm, where, plane_marker, plane_line, p, table, error)
        type(adm_model_type), intent(in) :: adm
        character(len=*), intent(in) :: where
        !> The PLANE's RM marker id and the GRAPHICS statement's line
        integer, intent(in) :: plane_marker, plane_line
        !> The plane's part, its place in adm%parts (not the ground)
        integer, intent(in) :: p
        type(turntable_type), intent(out) :: table
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: origin(3), axis(3), joint_origin(3), joint_axis(3), sense, rate
        integer :: k, joint, motion, pi, pj, count_joints, count_motions
        logical :: ground_j
        character(len=:), allocatable :: written

        table%part = p
        table%part_id = adm%parts(p)%id
        ! the REVOLUTE that holds the table to the ground
        joint = 0
        count_joints = 0
        pi = 0
        if (allocated(adm%joints)) then
            do k = 1, size(adm%joints)
                if (adm%joints(k)%primitive) cycle
                pi = part_of(adm%joints(k)%i)
                pj = part_of(adm%joints(k)%j)
                if (pi == 0 .or. pj == 0) cycle
                if (.not. ((pi == p .and. adm%parts(pj)%ground) .or. (pj == p .and. &
                    & adm%parts(pi)%ground))) cycle
                count_joints = count_joints + 1
                if (joint == 0) joint = k
            end do
        end if
        if (joint == 0) then
            call fatal_error(error, where // ": its PLANE (line " // to_text(plane_line) &
                & // ") is on PART/" // to_text(table%part_id) // ", which no JOINT holds to " &
                & // "the ground: a contact's plane is the ground's or a turntable's (a part " &
                & // "held by a REVOLUTE to the ground about ground Z and driven by a MOTION)", &
                & stat_input)
            return
        end if
        associate (j => adm%joints(joint))
            table%joint_name = "JOINT/" // to_text(j%id)
            if (j%kind /= "REVOLUTE" .or. count_joints > 1) then
                call fatal_error(error, place(adm%file, j%line) // ": " // table%joint_name &
                    & // ": " // where(index(where, "CONTACT/"):) // "'s plane is on PART/" &
                    & // to_text(table%part_id) // ", a turntable: rollcon holds it by one " &
                    & // "REVOLUTE to the ground, got " // j%kind // merge(" and more ", &
                    & "          ", count_joints > 1), stat_input)
                return
            end if
            call marker_frame(j%j, joint_origin, joint_axis)
            ground_j = adm%parts(part_of(j%j))%ground
            if (abs(abs(joint_axis(3)) - 1.0_wp) > direction_tolerance) then
                call fatal_error(error, place(adm%file, j%line) // ": " // table%joint_name &
                    & // ": the turntable's axis (its J marker's z) must be along ground Z: " &
                    & // "rollcon's contact holds a sphere or rim on a horizontal table; " &
                    & // "the axis is (" // to_text(joint_axis(1)) // ", " &
                    & // to_text(joint_axis(2)) // ", " // to_text(joint_axis(3)) // ")", &
                    & stat_input)
                return
            end if
            ! the table turns by the MOTION's angle about J's z when I is on it, by minus it
            ! when J is
            sense = sign(1.0_wp, joint_axis(3))*merge(1.0_wp, -1.0_wp, ground_j)
            table%axis = joint_origin(1:2)
            ! the MOTION that drives it
            motion = 0
            count_motions = 0
            if (allocated(adm%motions)) then
                do k = 1, size(adm%motions)
                    if (adm%motions(k)%joint /= j%id) cycle
                    count_motions = count_motions + 1
                    if (motion == 0) motion = k
                end do
            end if
            if (motion == 0) then
                call fatal_error(error, place(adm%file, j%line) // ": " // table%joint_name &
                    & // ": the turntable turns freely (no MOTION on its REVOLUTE): " &
                    & // "rollcon's contact holds a sphere or rim on a table turning at a " &
                    & // "prescribed rate (write MOTION/id, JOINT=" // to_text(j%id) &
                    & // ", ROTATION, FUNCTION=rate*TIME)", stat_input)
                return
            end if
        end associate
        associate (m => adm%motions(motion))
            table%motion_name = "MOTION/" // to_text(m%id)
            if (.not. constant_rate(m%form, m%function%op, m%user .or. m%component /= &
                & "ROTATION") .or. count_motions > 1) then
                if (m%user) then
                    written = "a MOTSUB"
                else
                    written = "FUNCTION = " // function_text(m%function%text)
                end if
                call fatal_error(error, place(adm%file, m%line) // ": " // table%motion_name &
                    & // ": the turntable's MOTION must be a constant rate, FUNCTION = " &
                    & // "rate*TIME (or with VELOCITY, FUNCTION = rate), one ROTATION on " &
                    & // table%joint_name // ": rollcon's table contact serves the rows of a " &
                    & // "table turning at a constant rate (ucon/specs/turntable_ball.py); " &
                    & // "got " // written, stat_input)
                return
            end if
            if (m%form == motion_velocity_form) then
                rate = evaluate_expression(m%function, 0.0_wp)
            else
                rate = evaluate_expression(m%function, 1.0_wp) &
                    & - evaluate_expression(m%function, 0.0_wp)
            end if
            table%dataset_rate = sense*rate
            table%rate = table%dataset_rate/adm%units%time
        end associate
        ! the table's top: its plane's RM, facing up
        call marker_frame(plane_marker, origin, axis)
        if (axis(3) < 1.0_wp - direction_tolerance) then
            call fatal_error(error, place(adm%file, plane_line) // ": " &
                & // where(index(where, "CONTACT/"):) // "'s plane on the turntable PART/" &
                & // to_text(table%part_id) // " must face up: its RM marker's z along " &
                & // "ground +Z; it is (" // to_text(axis(1)) // ", " // to_text(axis(2)) &
                & // ", " // to_text(axis(3)) // ")", stat_input)
            return
        end if
        table%height = origin(3)

    contains

        !> The place in adm%parts of marker id's part (0: no such marker).
        integer function part_of(id)
            integer, intent(in) :: id
            integer :: m

            part_of = 0
            m = findloc(adm%markers%id, id, dim=1)
            if (m == 0) return
            part_of = findloc(adm%parts%id, adm%markers(m)%part, dim=1)
        end function part_of

        !> Marker id's origin [m] and z-axis in ground at the dataset's start (zero when there
        !> is no such marker: the dataset's checks have refused it already).
        subroutine marker_frame(id, marker_origin, marker_z)
            integer, intent(in) :: id
            real(wp), intent(out) :: marker_origin(3), marker_z(3)
            real(wp) :: frame(3, 3)
            integer :: m, q

            marker_origin = 0.0_wp
            marker_z = 0.0_wp
            m = findloc(adm%markers%id, id, dim=1)
            if (m == 0) return
            q = findloc(adm%parts%id, adm%markers(m)%part, dim=1)
            associate (part => adm%parts(q), marker => adm%markers(m))
                frame = rotation_matrix(part%reuler(1), part%reuler(2), part%reuler(3))
                marker_origin = part%qg + matmul(frame, marker%qp)
                marker_z = matmul(matmul(frame, rotation_matrix(marker%reuler(1), &
                    & marker%reuler(2), marker%reuler(3))), [0.0_wp, 0.0_wp, 1.0_wp])
            end associate
        end subroutine marker_frame

        !> "3.5*TIME" as written, or "(not read)" when the text was not kept.
        function function_text(text) result(shown)
            character(len=:), allocatable, intent(in) :: text
            character(len=:), allocatable :: shown

            shown = "(not read)"
            if (allocated(text)) shown = text
        end function function_text
    end subroutine find_turntable

    !> A MOTION's program is a constant rate: in the displacement form TIME, c*TIME or TIME*c;
    !> in the velocity form a constant c. Never for a MOTSUB or another component (other).
    pure logical function constant_rate(form, op, other)
        integer, intent(in) :: form
        !> The FUNCTION's operation codes (rollcon_expression)
        integer, allocatable, intent(in) :: op(:)
        logical, intent(in) :: other

        constant_rate = .false.
        if (other .or. .not. allocated(op)) return
        select case (form)
        case (motion_displacement_form)
            if (size(op) == 1) then
                constant_rate = op(1) == op_time
            else if (size(op) == 3) then
                constant_rate = op(3) == op_multiply .and. ((op(1) == op_constant .and. &
                    & op(2) == op_time) .or. (op(1) == op_time .and. op(2) == op_constant))
            end if
        case (motion_velocity_form)
            constant_rate = size(op) == 1 .and. op(1) == op_constant
        end select
    end function constant_rate

end module rollcon_adm_turntable
