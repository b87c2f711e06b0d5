! SPDX-License-Identifier: MIT
!> A dataset's JOINT and JPRIM statements as UCONs (docs/datasets.md, "JOINT and JPRIM"):
!> their markers checked, and each primitive of each joint served by its generated routine
!> (ucon/specs/_joint.py), one UCON per component, with PAR filled from the markers:
!> `jp_<primitive>` between two moving parts, `gnd_<primitive>` when marker J is on the ground
!> (which has no coordinates; J's origin and axes in ground are then constants of PAR). A
!> marker's origin and axes in its part's principal axes are the geometry the driver owns
!> (ucon_statement_type's geometry_par), turned with the part at each re-basing.
!>
!> The UCONs of the joints take the ids after the largest UCON id of the dataset, in the order
!> of the file: joint by joint, primitive by primitive as rollcon_adm_joints lists them,
!> component by component (their CSV columns F_<id>, lambda_<id>).
module rollcon_adm_joint_build
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, lower_case
    use rollcon_marker, only : marker_type
    use rollcon_adm_markers, only : adm_marker, marker_index
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_model, only : model_type
    use rollcon_adm_keywords, only : place
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_joints, only : adm_joint_type, joint_primitives, primitive_names, &
        & primitive_atpoint, primitive_inline, primitive_inplane, primitive_parallel_axes, &
        & primitive_perpendicular, primitive_orientation
    use rollcon_gen_gnd_atpoint, only : gnd_atpoint_ucosub, gnd_atpoint_codes
    use rollcon_gen_gnd_inline, only : gnd_inline_ucosub, gnd_inline_codes
    use rollcon_gen_gnd_inplane, only : gnd_inplane_ucosub, gnd_inplane_codes
    use rollcon_gen_gnd_parallel_axes, only : gnd_parallel_axes_ucosub, gnd_parallel_axes_codes
    use rollcon_gen_gnd_perpendicular, only : gnd_perpendicular_ucosub, gnd_perpendicular_codes
    use rollcon_gen_gnd_orientation, only : gnd_orientation_ucosub, gnd_orientation_codes
    use rollcon_gen_jp_atpoint, only : jp_atpoint_ucosub, jp_atpoint_codes
    use rollcon_gen_jp_inline, only : jp_inline_ucosub, jp_inline_codes
    use rollcon_gen_jp_inplane, only : jp_inplane_ucosub, jp_inplane_codes
    use rollcon_gen_jp_parallel_axes, only : jp_parallel_axes_ucosub, jp_parallel_axes_codes
    use rollcon_gen_jp_perpendicular, only : jp_perpendicular_ucosub, jp_perpendicular_codes
    use rollcon_gen_jp_orientation, only : jp_orientation_ucosub, jp_orientation_codes
    implicit none
    private

    public :: check_joints, add_joint_ucons

    !> The vectors a primitive's PAR holds, in PAR order (ucon/specs/_joint.py): I's origin,
    !> z and x axes (in part i's principal axes), J's origin, x, y and z axes (in ground)
    integer, parameter :: vector_ip = 1, vector_iz = 2, vector_ix = 3, vector_jp = 4, &
        & vector_jx = 5, vector_jy = 6, vector_jz = 7

contains

    !> Every JOINT and JPRIM: its markers exist and lie on two parts, I's not on the ground.
    subroutine check_joints(adm, error)
        type(adm_model_type), intent(in) :: adm
        type(error_type), allocatable, intent(out) :: error
        integer :: k, mi, mj, pi, pj

        if (.not. allocated(adm%joints)) return
        do k = 1, size(adm%joints)
            associate (joint => adm%joints(k))
                mi = marker_index(adm, joint%i)
                mj = marker_index(adm, joint%j)
                if (mi == 0 .or. mj == 0) then
                    call fatal_error(error, where(adm, joint) // trim(merge(" I: no MARKER/", &
                        & " J: no MARKER/", mi == 0)) // to_text(merge(joint%i, joint%j, &
                        & mi == 0)), stat_input)
                    return
                end if
                pi = part_index(adm, adm%markers(mi)%part)
                pj = part_index(adm, adm%markers(mj)%part)
                if (pi == pj) then
                    call fatal_error(error, where(adm, joint) // ": its markers I (MARKER/" &
                        & // to_text(joint%i) // ") and J (MARKER/" // to_text(joint%j) &
                        & // ") are both on PART/" // to_text(adm%parts(pi)%id) // "; a " &
                        & // "joint connects two parts", stat_input)
                    return
                end if
                if (adm%parts(pi)%ground .and. .not. swappable(joint)) then
                    call fatal_error(error, where(adm, joint) // " I: MARKER/" &
                        & // to_text(joint%i) // " is on the ground part; an " // joint%kind &
                        & // " primitive is not symmetric in I and J (it holds I's origin to " &
                        & // "J's " // trim(merge("z axis  ", "xy plane", joint%kind == "INLINE")) &
                        & // "), so rollcon, which serves a primitive from the part of I, needs " &
                        & // "marker I on a moving part: swap I and J, turning the markers to " &
                        & // "keep its meaning", stat_input)
                    return
                end if
            end associate
        end do
    end subroutine check_joints

    !> A joint or primitive whose I marker is on the ground is served with I and J swapped
    !> (the routines hold the part of I): every JOINT type is symmetric in its markers (its
    !> INLINE, I's origin on J's z axis, is J's origin on I's z axis once its other primitive
    !> makes the axes parallel), and so are ATPOINT, PARALLEL_AXES, PERPENDICULAR and
    !> ORIENTATION; a JPRIM INLINE or INPLANE is not.
    pure logical function swappable(joint)
        type(adm_joint_type), intent(in) :: joint

        swappable = .not. (joint%primitive .and. (joint%kind == "INLINE" &
            & .or. joint%kind == "INPLANE"))
    end function swappable

    !> The joint as the routines serve it: I and J swapped when I is on the ground.
    pure function served(adm, joint) result(turned)
        type(adm_model_type), intent(in) :: adm
        type(adm_joint_type), intent(in) :: joint
        type(adm_joint_type) :: turned

        turned = joint
        if (adm%parts(part_index(adm, adm%markers(marker_index(adm, joint%i))%part))%ground) &
            & then
            turned%i = joint%j
            turned%j = joint%i
        end if
    end function served

    !> The UCONs of every JOINT and JPRIM, appended to the model (after the dataset's UCONs).
    subroutine add_joint_ucons(adm, model)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(inout) :: model
        procedure(ucosub_interface), pointer :: routine
        character(len=:), allocatable :: name
        real(wp) :: vectors(3, 7)
        real(wp), allocatable :: par(:), values(:)
        integer, allocatable :: primitives(:), codes(:), used(:)
        integer :: k, n, c, next_id, part_i, part_j, components, first, v
        logical :: ground
        type(adm_joint_type) :: joint

        if (.not. allocated(adm%joints)) return
        next_id = 0
        if (size(adm%ucons) > 0) next_id = maxval(adm%ucons%id)
        do k = 1, size(adm%joints)
            joint = served(adm, adm%joints(k))
            part_i = adm%markers(marker_index(adm, joint%i))%part
            part_j = adm%markers(marker_index(adm, joint%j))%part
            ground = adm%parts(part_index(adm, part_j))%ground
            call marker_vectors(adm, joint, vectors)
            primitives = joint_primitives(joint%kind)
            do n = 1, size(primitives)
                call primitive_routine(primitives(n), ground, routine, codes, first, used, &
                    & components)
                values = reshape(vectors(:, used), [3*size(used)])
                name = merge("gnd_", "jp_ ", ground)
                name = trim(name) // lower_case(trim(primitive_names(primitives(n))))
                do c = 1, components
                    if (ground) then
                        par = [real(part_i, wp), real(codes, wp), values]
                    else
                        par = [real(part_i, wp), real(codes(:first), wp), &
                            & real(part_j, wp), real(codes(first + 1:), wp), values]
                    end if
                    if (components > 1) par = [par, real(c, wp)]
                    next_id = next_id + 1
                    call model%add_ucon(next_id, par, routine, time_free=.true., &
                        & routine=name)
                    associate (ucon => model%ucons(size(model%ucons)))
                        ! each vector's PAR index and the part (model order) it is fixed in
                        ucon%geometry_par = [(size(par) - merge(1, 0, components > 1) &
                            & - 3*size(used) + 3*(v - 1) + 1, v = 1, size(used))]
                        ucon%geometry_parts = [(model_part(adm, merge(part_i, part_j, &
                            & used(v) <= vector_ix)), v = 1, size(used))]
                        ! J's vectors are in ground when J is on the ground: never turned
                        ucon%geometry_par = pack(ucon%geometry_par, ucon%geometry_parts > 0)
                        ucon%geometry_parts = pack(ucon%geometry_parts, &
                            & ucon%geometry_parts > 0)
                    end associate
                end do
            end do
        end do
    end subroutine add_joint_ucons

    !> A primitive's routine (gnd_<primitive> with J on the ground, jp_<primitive> between two
    !> parts), its codes (first: how many are part i's), the vectors its PAR holds and its
    !> number of components.
    subroutine primitive_routine(primitive, ground, routine, codes, first, used, components)
        integer, intent(in) :: primitive
        logical, intent(in) :: ground
        procedure(ucosub_interface), pointer, intent(out) :: routine
        integer, allocatable, intent(out) :: codes(:), used(:)
        integer, intent(out) :: first, components

        select case (primitive)
        case (primitive_atpoint)
            routine => gnd_atpoint_ucosub
            codes = gnd_atpoint_codes
            if (.not. ground) routine => jp_atpoint_ucosub
            if (.not. ground) codes = jp_atpoint_codes
            used = [vector_ip, vector_jp]
            components = 3
        case (primitive_inline)
            routine => gnd_inline_ucosub
            codes = gnd_inline_codes
            if (.not. ground) routine => jp_inline_ucosub
            if (.not. ground) codes = jp_inline_codes
            used = [vector_ip, vector_jp, vector_jx, vector_jy]
            components = 2
        case (primitive_inplane)
            routine => gnd_inplane_ucosub
            codes = gnd_inplane_codes
            if (.not. ground) routine => jp_inplane_ucosub
            if (.not. ground) codes = jp_inplane_codes
            used = [vector_ip, vector_jp, vector_jz]
            components = 1
        case (primitive_parallel_axes)
            routine => gnd_parallel_axes_ucosub
            codes = gnd_parallel_axes_codes
            if (.not. ground) routine => jp_parallel_axes_ucosub
            if (.not. ground) codes = jp_parallel_axes_codes
            used = [vector_iz, vector_jx, vector_jy]
            components = 2
        case (primitive_perpendicular)
            routine => gnd_perpendicular_ucosub
            codes = gnd_perpendicular_codes
            if (.not. ground) routine => jp_perpendicular_ucosub
            if (.not. ground) codes = jp_perpendicular_codes
            used = [vector_iz, vector_jz]
            components = 1
        case default
            routine => gnd_orientation_ucosub
            codes = gnd_orientation_codes
            if (.not. ground) routine => jp_orientation_ucosub
            if (.not. ground) codes = jp_orientation_codes
            used = [vector_iz, vector_ix, vector_jx, vector_jy]
            components = 3
        end select
        ! part i's coordinates: X, Y, Z with I's origin, and the three angles
        first = merge(6, 3, any(used == vector_ip))
    end subroutine primitive_routine

    !> The model's number of the part with this id (the dataset's non-ground parts in order);
    !> 0 for the ground.
    pure integer function model_part(adm, id)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: id
        integer :: p

        p = part_index(adm, id)
        model_part = 0
        if (.not. adm%parts(p)%ground) model_part = count(.not. adm%parts(:p)%ground)
    end function model_part

    !> The seven vectors of a joint (vector_* order): I's origin [dataset length] and axes in
    !> its part's principal axes, J's origin [dataset length] and axes in ground (adm_marker:
    !> the same pose every statement naming a marker takes).
    subroutine marker_vectors(adm, joint, vectors)
        type(adm_model_type), intent(in) :: adm
        type(adm_joint_type), intent(in) :: joint
        real(wp), intent(out) :: vectors(3, 7)
        type(marker_type) :: marker

        marker = adm_marker(adm, joint%i)
        vectors(:, vector_ip) = marker%point/adm%units%length
        vectors(:, vector_iz) = marker%axes(:, 3)
        vectors(:, vector_ix) = marker%axes(:, 1)
        marker = adm_marker(adm, joint%j)
        vectors(:, vector_jp) = marker%point/adm%units%length
        vectors(:, vector_jx) = marker%axes(:, 1)
        vectors(:, vector_jy) = marker%axes(:, 2)
        vectors(:, vector_jz) = marker%axes(:, 3)
    end subroutine marker_vectors

    !> "file:line: JOINT/id" or "file:line: JPRIM/id"
    function where(adm, joint) result(text)
        type(adm_model_type), intent(in) :: adm
        type(adm_joint_type), intent(in) :: joint
        character(len=:), allocatable :: text

        text = place(adm%file, joint%line) // ": " // trim(merge("JPRIM", "JOINT", &
            & joint%primitive)) // "/" // to_text(joint%id)
    end function where

    pure integer function part_index(adm, id)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: id

        part_index = findloc(adm%parts%id, id, dim=1)
    end function part_index

end module rollcon_adm_joint_build
