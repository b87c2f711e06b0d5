! SPDX-License-Identifier: MIT
!> The geometric part s(q) of a MOTION (rollcon_motion: F = s(q) - h(t)) as a generated
!> routine and its PAR, filled from the two markers as a joint's primitives are
!> (rollcon_joint_primitives; docs/datasets.md, "MOTION"):
!>
!> - a translation along an axis of J (X, Y, Z between markers; a TRANSLATIONAL or
!>   CYLINDRICAL joint's TRANSLATION along J's z): s = (r_I - r_J).e_J, served by
!>   `gnd_inplane` or `jp_inplane` given e_J as the plane's normal;
!> - a joint's ROTATION (REVOLUTE or CYLINDRICAL), the turn of I's x axis about the common z
!>   axis from J's x axis: s = atan2(x_I.y_J, x_I.x_J);
!> - B1, B2, B3, the body 1-2-3 angles of I's axes from J's: b1 = atan2(-z_I.y_J, z_I.z_J),
!>   b2 = atan2(z_I.x_J, sqrt((z_I.y_J)^2 + (z_I.z_J)^2)), b3 = atan2(-y_I.x_J, x_I.x_J),
!>
!> the angles served by `gnd_motion_angle` and `jp_motion_angle` (ucon/specs/_motion.py). The
!> routines hold the part of their first side: a MOTION whose marker I is on the ground is
!> served from J's part with the dot products' sides swapped (the same angle; b2 then as
!> atan2(x_J.z_I, sqrt((x_J.x_I)^2 + (x_J.y_I)^2))); a joint's TRANSLATION so is s =
!> (r_J - r_I).(-z_I), the same since the joint keeps z_I along z_J. X, Y and Z with I on the
!> ground are refused (the displacement is measured along J's axes, which move with the part
!> then). The geometry is SI (the routine's PAR in metres: a MOTION's UCON computes in SI,
!> whatever the dataset's units) and turns with its part at a re-basing (geometry_par).
module rollcon_motion_geometry
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_marker, only : marker_type
    use rollcon_joint_primitives, only : primitive_ucon_type
    use rollcon_gen_gnd_inplane, only : gnd_inplane_ucosub, gnd_inplane_codes
    use rollcon_gen_jp_inplane, only : jp_inplane_ucosub, jp_inplane_codes
    use rollcon_gen_gnd_motion_angle, only : gnd_motion_angle_ucosub, gnd_motion_angle_codes
    use rollcon_gen_jp_motion_angle, only : jp_motion_angle_ucosub, jp_motion_angle_codes
    implicit none
    private

    public :: motion_ucon, motion_x, motion_y, motion_z, motion_b1, motion_b2, motion_b3, &
        & motion_rotation, motion_component_names

    !> What a MOTION drives: I's displacement from J along J's x, y, z axis; the body 1-2-3
    !> angles B1, B2, B3; a joint's ROTATION
    integer, parameter :: motion_x = 1, motion_y = 2, motion_z = 3, motion_b1 = 4, &
        & motion_b2 = 5, motion_b3 = 6, motion_rotation = 7
    !> Their names (a joint's TRANSLATION is Z, its ROTATION rotation)
    character(len=*), parameter :: motion_component_names(7) = [character(len=8) :: "X", "Y", &
        & "Z", "B1", "B2", "B3", "ROTATION"]

contains

    !> The UCON of s(q) for a MOTION of `component` between marker i and marker j (as the model
    !> holds them: part 0 the ground); joint: the MOTION is on a joint (its TRANSLATION may then
    !> be served from J's part). Refused, naming `where`: both markers on one part or on the
    !> ground, markers on parts the model does not have, X, Y or Z with I on the ground.
    subroutine motion_ucon(where, component, joint, i, j, part_ids, ucon, error)
        !> The statement, for messages ("data/x.adm:12: MOTION/3")
        character(len=*), intent(in) :: where
        !> motion_x ... motion_rotation
        integer, intent(in) :: component
        logical, intent(in) :: joint
        type(marker_type), intent(in) :: i, j
        !> The ids of the model's parts, in model order
        integer, intent(in) :: part_ids(:)
        type(primitive_ucon_type), intent(out) :: ucon
        type(error_type), allocatable, intent(out) :: error
        type(marker_type) :: first, second
        real(wp) :: vectors(3, 5)
        integer :: angle
        logical :: swapped

        if (i%part < 0 .or. i%part > size(part_ids) .or. j%part < 0 &
            & .or. j%part > size(part_ids)) then
            call fatal_error(error, where // ": its markers I (MARKER/" // to_text(i%id) &
                & // ") and J (MARKER/" // to_text(j%id) // ") must be on parts of the model " &
                & // "or on the ground", stat_input)
            return
        end if
        if (i%part == j%part) then
            call fatal_error(error, where // ": its markers I (MARKER/" // to_text(i%id) &
                & // ") and J (MARKER/" // to_text(j%id) // ") are on one part; a MOTION " &
                & // "drives one part from another", stat_input)
            return
        end if
        swapped = i%part == 0
        first = i
        second = j
        if (swapped) then
            first = j
            second = i
        end if
        select case (component)
        case (motion_x, motion_y, motion_z)
            if (swapped .and. .not. joint) then
                call fatal_error(error, where // ": marker I (MARKER/" // to_text(i%id) &
                    & // ") is on the ground; a MOTION's " &
                    & // trim(motion_component_names(component)) // " is I's displacement " &
                    & // "along J's axis, and rollcon serves it from the part of I: put I on " &
                    & // "the moving part", stat_input)
                return
            end if
            if (swapped) then
                ! s = (r_I - r_J).z_J = (r_J - r_I).(-z_I): the joint keeps z_I along z_J
                call translation(first, second, -second%axes(:, 3), part_ids, ucon)
            else
                call translation(first, second, second%axes(:, component), part_ids, ucon)
            end if
            return
        case (motion_rotation)
            ! atan2(x_i.y_j, x_i.x_j)
            vectors = reshape([i%axes(:, 1), i%axes(:, 1), j%axes(:, 2), j%axes(:, 1), &
                & j%axes(:, 3)], [3, 5])
            if (swapped) vectors = reshape([j%axes(:, 2), j%axes(:, 1), i%axes(:, 1), &
                & i%axes(:, 1), i%axes(:, 3)], [3, 5])
            angle = 1
        case (motion_b1, motion_b2)
            ! atan2(z_i.(-y_j), z_i.z_j) and atan2(z_i.x_j, sqrt((z_i.y_j)^2 + (z_i.z_j)^2))
            vectors = reshape([i%axes(:, 3), i%axes(:, 3), -j%axes(:, 2), j%axes(:, 3), &
                & j%axes(:, 1)], [3, 5])
            if (swapped .and. component == motion_b1) vectors = reshape([-j%axes(:, 2), &
                & j%axes(:, 3), i%axes(:, 3), i%axes(:, 3), i%axes(:, 1)], [3, 5])
            ! b2 from J's side: atan2(x_j.z_i, sqrt((x_j.x_i)^2 + (x_j.y_i)^2))
            if (swapped .and. component == motion_b2) vectors = reshape([j%axes(:, 1), &
                & j%axes(:, 1), i%axes(:, 1), i%axes(:, 2), i%axes(:, 3)], [3, 5])
            angle = merge(1, 2, component == motion_b1)
        case default
            ! b3 = atan2(y_i.(-x_j), x_i.x_j)
            vectors = reshape([i%axes(:, 2), i%axes(:, 1), -j%axes(:, 1), j%axes(:, 1), &
                & j%axes(:, 3)], [3, 5])
            if (swapped) vectors = reshape([-j%axes(:, 1), j%axes(:, 1), i%axes(:, 2), &
                & i%axes(:, 1), i%axes(:, 3)], [3, 5])
            angle = 1
        end select
        call angle_ucon(first, second, vectors, angle, part_ids, ucon)
    end subroutine motion_ucon

    !> s = (r_first - r_second).normal, normal fixed in second's part (or the ground).
    subroutine translation(first, second, normal, part_ids, ucon)
        type(marker_type), intent(in) :: first, second
        real(wp), intent(in) :: normal(3)
        integer, intent(in) :: part_ids(:)
        type(primitive_ucon_type), intent(out) :: ucon
        real(wp), allocatable :: values(:)
        integer :: head

        values = [first%point, second%point, normal]
        if (second%part == 0) then
            ucon%par = [real(part_ids(first%part), wp), real(gnd_inplane_codes, wp), values]
            ucon%ucosub => gnd_inplane_ucosub
            ucon%routine = "gnd_inplane"
            ucon%geometry_par = [size(ucon%par) - 8]
            ucon%geometry_parts = [first%part]
        else
            ucon%par = [real(part_ids(first%part), wp), real(jp_inplane_codes(:6), wp), &
                & real(part_ids(second%part), wp), real(jp_inplane_codes(7:), wp), values]
            ucon%ucosub => jp_inplane_ucosub
            ucon%routine = "jp_inplane"
            head = size(ucon%par) - 9
            ucon%geometry_par = [head + 1, head + 4, head + 7]
            ucon%geometry_parts = [first%part, second%part, second%part]
        end if
    end subroutine translation

    !> The angle routine's UCON: vectors a, c fixed in first's part, b, d, e in second's (or in
    !> the ground); angle: its component, 1 (rotation) or 2 (tilt).
    subroutine angle_ucon(first, second, vectors, angle, part_ids, ucon)
        type(marker_type), intent(in) :: first, second
        real(wp), intent(in) :: vectors(3, 5)
        integer, intent(in) :: angle
        integer, intent(in) :: part_ids(:)
        type(primitive_ucon_type), intent(out) :: ucon
        integer :: head, v

        if (second%part == 0) then
            ucon%par = [real(part_ids(first%part), wp), real(gnd_motion_angle_codes, wp), &
                & reshape(vectors, [15]), real(angle, wp)]
            ucon%ucosub => gnd_motion_angle_ucosub
            ucon%routine = "gnd_motion_angle"
            head = size(ucon%par) - 16
            ucon%geometry_par = [head + 1, head + 4]
            ucon%geometry_parts = [first%part, first%part]
        else
            ucon%par = [real(part_ids(first%part), wp), real(jp_motion_angle_codes(:3), wp), &
                & real(part_ids(second%part), wp), real(jp_motion_angle_codes(4:), wp), &
                & reshape(vectors, [15]), real(angle, wp)]
            ucon%ucosub => jp_motion_angle_ucosub
            ucon%routine = "jp_motion_angle"
            head = size(ucon%par) - 16
            ucon%geometry_par = [(head + 3*(v - 1) + 1, v = 1, 5)]
            ucon%geometry_parts = [first%part, first%part, second%part, second%part, &
                & second%part]
        end if
    end subroutine angle_ucon

end module rollcon_motion_geometry
