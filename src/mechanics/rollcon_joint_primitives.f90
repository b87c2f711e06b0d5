! SPDX-License-Identifier: MIT
!> A joint or joint primitive between two markers as UCONs (docs/datasets.md, "JOINT and
!> JPRIM"): each primitive of the joint (rollcon_joint_types) served by its generated routine
!> (ucon/specs/_joint.py), one UCON per component, with PAR filled from the markers:
!> `jp_<primitive>` between two moving parts, `gnd_<primitive>` when marker J is on the ground
!> (which has no coordinates; J's origin and axes in ground are then constants of PAR). A
!> marker's origin and axes in its part's principal axes are the geometry the driver owns
!> (ucon_statement_type's geometry_par), turned with the part at each re-basing.
!>
!> A HOOKE's PERPENDICULAR takes its cross pins, I's x axis and J's y axis, where a UNIVERSAL's
!> and a JPRIM's take the z axes; a CONVEL's homokinetic condition is served by
!> `jp_homokinetic` and `gnd_homokinetic`, which take I's and J's x and y axes.
!>
!> The routines hold the part of marker I; a statement whose I is on the ground is served with
!> I and J swapped when it means the same so (rollcon_joint_types' primitive_symmetric; a
!> HOOKE's pins stay with their markers), and refused otherwise. model%add_joint and
!> model%add_jprim (rollcon_model) append these UCONs.
module rollcon_joint_primitives
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, lower_case
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_marker, only : marker_type
    use rollcon_joint_types, only : joint_names, primitive_names, joint_primitives, &
        & is_joint_name, primitive_index, primitive_symmetric, name_list, primitive_atpoint, &
        & primitive_inline, primitive_inplane, primitive_parallel_axes, primitive_perpendicular, &
        & primitive_orientation, primitive_homokinetic
    use rollcon_gen_gnd_atpoint, only : gnd_atpoint_ucosub, gnd_atpoint_codes
    use rollcon_gen_gnd_homokinetic, only : gnd_homokinetic_ucosub, gnd_homokinetic_codes
    use rollcon_gen_gnd_inline, only : gnd_inline_ucosub, gnd_inline_codes
    use rollcon_gen_gnd_inplane, only : gnd_inplane_ucosub, gnd_inplane_codes
    use rollcon_gen_gnd_parallel_axes, only : gnd_parallel_axes_ucosub, gnd_parallel_axes_codes
    use rollcon_gen_gnd_perpendicular, only : gnd_perpendicular_ucosub, gnd_perpendicular_codes
    use rollcon_gen_gnd_orientation, only : gnd_orientation_ucosub, gnd_orientation_codes
    use rollcon_gen_jp_atpoint, only : jp_atpoint_ucosub, jp_atpoint_codes
    use rollcon_gen_jp_homokinetic, only : jp_homokinetic_ucosub, jp_homokinetic_codes
    use rollcon_gen_jp_inline, only : jp_inline_ucosub, jp_inline_codes
    use rollcon_gen_jp_inplane, only : jp_inplane_ucosub, jp_inplane_codes
    use rollcon_gen_jp_parallel_axes, only : jp_parallel_axes_ucosub, jp_parallel_axes_codes
    use rollcon_gen_jp_perpendicular, only : jp_perpendicular_ucosub, jp_perpendicular_codes
    use rollcon_gen_jp_orientation, only : jp_orientation_ucosub, jp_orientation_codes
    implicit none
    private

    public :: primitive_ucon_type, joint_ucons

    !> The vectors a primitive's PAR holds, in PAR order (ucon/specs/_joint.py): I's origin,
    !> z, x and y axes (in part i's principal axes), J's origin, x, y and z axes (in J's part's
    !> principal axes, or in ground)
    integer, parameter :: vector_ip = 1, vector_iz = 2, vector_ix = 3, vector_iy = 4, &
        & vector_jp = 5, vector_jx = 6, vector_jy = 7, vector_jz = 8

    !> One UCON of a joint: what model%add_ucon takes, and the geometry it holds
    type :: primitive_ucon_type
        real(wp), allocatable :: par(:)
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
        !> The routine's name, for the run's record (gnd_atpoint, jp_parallel_axes, ...)
        character(len=:), allocatable :: routine
        !> PAR indices where a 3-vector fixed in a part starts, and that part (model order)
        integer, allocatable :: geometry_par(:), geometry_parts(:)
    end type primitive_ucon_type

contains

    !> The UCONs of JOINT/id (primitive false) or JPRIM/id (primitive true) of type `kind`
    !> between marker i and marker j, in the order of the primitives (joint_primitives), then
    !> of the components. Refused, naming the statement: an unknown type, markers on parts the
    !> model does not have, both markers on one part (or both on the ground), an asymmetric
    !> primitive whose marker I is on the ground.
    subroutine joint_ucons(primitive, id, kind, i, j, part_ids, length_unit, ucons, error)
        !> JPRIM (true) or JOINT (false)
        logical, intent(in) :: primitive
        !> The statement's id (for messages)
        integer, intent(in) :: id
        !> Its type, upper case and in full (REVOLUTE, INPLANE, ...)
        character(len=*), intent(in) :: kind
        !> Marker I and marker J, as the model holds them (part 0: ground)
        type(marker_type), intent(in) :: i, j
        !> The ids of the model's parts, in model order
        integer, intent(in) :: part_ids(:)
        !> The length unit the routines compute in [m] (the model's ucosub_units%length)
        real(wp), intent(in) :: length_unit
        type(primitive_ucon_type), allocatable, intent(out) :: ucons(:)
        type(error_type), allocatable, intent(out) :: error
        type(marker_type) :: first, second
        character(len=:), allocatable :: where
        integer, allocatable :: primitives(:)
        real(wp) :: pins(3, 2)

        allocate(ucons(0))
        where = trim(merge("JPRIM", "JOINT", primitive)) // "/" // to_text(id)
        if (primitive .and. primitive_index(kind) == 0) then
            call fatal_error(error, where // ": '" // kind // "' is not a joint primitive (" &
                & // name_list(primitive_names) // ")", stat_input)
            return
        else if (.not. primitive .and. .not. is_joint_name(kind)) then
            call fatal_error(error, where // ": '" // kind // "' is not a joint (" &
                & // name_list(joint_names) // ")", stat_input)
            return
        end if
        if (i%part < 0 .or. i%part > size(part_ids) .or. j%part < 0 &
            & .or. j%part > size(part_ids)) then
            call fatal_error(error, where // ": its markers I (MARKER/" // to_text(i%id) &
                & // ") and J (MARKER/" // to_text(j%id) // ") must be on parts of the " &
                & // "model (1 to " // to_text(size(part_ids)) // ") or on the ground (0)", &
                & stat_input)
            return
        end if
        if (i%part == j%part) then
            call fatal_error(error, where // ": its markers I (MARKER/" // to_text(i%id) &
                & // ") and J (MARKER/" // to_text(j%id) // ") are both on " &
                & // part_words(i%part, part_ids) // "; a joint connects two parts", stat_input)
            return
        end if
        first = i
        second = j
        ! the axes a PERPENDICULAR holds perpendicular, first's and second's: the z axes, or a
        ! HOOKE's cross pins, I's x axis and J's y axis (each with its marker when swapped)
        pins(:, 1) = i%axes(:, 3)
        pins(:, 2) = j%axes(:, 3)
        if (.not. primitive .and. kind == "HOOKE") then
            pins(:, 1) = i%axes(:, 1)
            pins(:, 2) = j%axes(:, 2)
        end if
        if (i%part == 0) then
            if (.not. primitive_symmetric(kind, primitive)) then
                call fatal_error(error, where // " I: MARKER/" // to_text(i%id) // " is on " &
                    & // "the ground part; an " // kind // " primitive is not symmetric in I " &
                    & // "and J (it holds I's origin to J's " // trim(merge("z axis  ", &
                    & "xy plane", kind == "INLINE")) // "), so rollcon, which serves a " &
                    & // "primitive from the part of I, needs marker I on a moving part: swap " &
                    & // "I and J, turning the markers to keep its meaning", stat_input)
                return
            end if
            first = j
            second = i
            pins = pins(:, [2, 1])
        end if
        primitives = joint_primitives(kind)
        call primitive_list(primitives, first, second, pins, part_ids, length_unit, ucons)
    end subroutine joint_ucons

    !> "PART/3", or "the ground" for part 0.
    function part_words(part, part_ids) result(words)
        integer, intent(in) :: part, part_ids(:)
        character(len=:), allocatable :: words

        words = "the ground"
        if (part > 0) words = "PART/" // to_text(part_ids(part))
    end function part_words

    !> The UCONs of the primitives, marker I (i) on a moving part; a PERPENDICULAR holds
    !> pins(:, 1), fixed in i's part, perpendicular to pins(:, 2), fixed in j's.
    subroutine primitive_list(primitives, i, j, pins, part_ids, length_unit, ucons)
        integer, intent(in) :: primitives(:)
        type(marker_type), intent(in) :: i, j
        real(wp), intent(in) :: pins(3, 2)
        integer, intent(in) :: part_ids(:)
        real(wp), intent(in) :: length_unit
        type(primitive_ucon_type), allocatable, intent(inout) :: ucons(:)
        type(primitive_ucon_type) :: ucon
        procedure(ucosub_interface), pointer :: routine
        character(len=:), allocatable :: name
        real(wp) :: vectors(3, 8)
        real(wp), allocatable :: par(:), values(:)
        integer, allocatable :: codes(:), used(:)
        integer :: n, c, v, components, first, part_i, part_j
        logical :: ground

        ground = j%part == 0
        part_i = part_ids(i%part)
        part_j = 0
        if (.not. ground) part_j = part_ids(j%part)
        vectors(:, vector_ip) = i%point/length_unit
        vectors(:, vector_iz) = i%axes(:, 3)
        vectors(:, vector_ix) = i%axes(:, 1)
        vectors(:, vector_iy) = i%axes(:, 2)
        vectors(:, vector_jp) = j%point/length_unit
        vectors(:, vector_jx) = j%axes(:, 1)
        vectors(:, vector_jy) = j%axes(:, 2)
        vectors(:, vector_jz) = j%axes(:, 3)
        do n = 1, size(primitives)
            call primitive_routine(primitives(n), ground, routine, codes, first, used, &
                & components, name)
            values = reshape(vectors(:, used), [3*size(used)])
            ! its z_i and z_j: the pins (a HOOKE's x_i and y_j)
            if (primitives(n) == primitive_perpendicular) values = [pins(:, 1), pins(:, 2)]
            do c = 1, components
                if (ground) then
                    par = [real(part_i, wp), real(codes, wp), values]
                else
                    par = [real(part_i, wp), real(codes(:first), wp), real(part_j, wp), &
                        & real(codes(first + 1:), wp), values]
                end if
                if (components > 1) par = [par, real(c, wp)]
                ucon%par = par
                ucon%ucosub => routine
                ucon%routine = name
                ! each vector's PAR index and the part (model order) it is fixed in
                ucon%geometry_par = [(size(par) - merge(1, 0, components > 1) &
                    & - 3*size(used) + 3*(v - 1) + 1, v = 1, size(used))]
                ucon%geometry_parts = [(merge(i%part, j%part, used(v) <= vector_iy), &
                    & v = 1, size(used))]
                ! J's vectors are in ground when J is on the ground: never turned
                ucon%geometry_par = pack(ucon%geometry_par, ucon%geometry_parts > 0)
                ucon%geometry_parts = pack(ucon%geometry_parts, ucon%geometry_parts > 0)
                call append(ucons, ucon)
            end do
        end do
    end subroutine primitive_list

    !> Append one UCON (element by element: gfortran 12 may mishandle an array constructor of
    !> a type with a deferred-length component).
    subroutine append(ucons, ucon)
        type(primitive_ucon_type), allocatable, intent(inout) :: ucons(:)
        type(primitive_ucon_type), intent(in) :: ucon
        type(primitive_ucon_type), allocatable :: grown(:)
        integer :: k

        allocate(grown(size(ucons) + 1))
        do k = 1, size(ucons)
            grown(k) = ucons(k)
        end do
        grown(size(grown)) = ucon
        call move_alloc(grown, ucons)
    end subroutine append

    !> A primitive's routine (gnd_<primitive> with J on the ground, jp_<primitive> between two
    !> parts), its codes (first: how many are part i's), the vectors its PAR holds, its number
    !> of components and the routine's name (its spec's: gnd_atpoint, jp_homokinetic, ...).
    subroutine primitive_routine(primitive, ground, routine, codes, first, used, components, &
        & name)
        integer, intent(in) :: primitive
        logical, intent(in) :: ground
        procedure(ucosub_interface), pointer, intent(out) :: routine
        integer, allocatable, intent(out) :: codes(:), used(:)
        integer, intent(out) :: first, components
        character(len=:), allocatable, intent(out) :: name

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
        case (primitive_orientation)
            routine => gnd_orientation_ucosub
            codes = gnd_orientation_codes
            if (.not. ground) routine => jp_orientation_ucosub
            if (.not. ground) codes = jp_orientation_codes
            used = [vector_iz, vector_ix, vector_jx, vector_jy]
            components = 3
        case default
            routine => gnd_homokinetic_ucosub
            codes = gnd_homokinetic_codes
            if (.not. ground) routine => jp_homokinetic_ucosub
            if (.not. ground) codes = jp_homokinetic_codes
            used = [vector_ix, vector_iy, vector_jx, vector_jy]
            components = 1
        end select
        ! part i's coordinates: X, Y, Z with I's origin, and the three angles
        first = merge(6, 3, any(used == vector_ip))
        if (primitive == primitive_homokinetic) then
            name = "homokinetic"
        else
            name = lower_case(trim(primitive_names(primitive)))
        end if
        name = trim(merge("gnd_", "jp_ ", ground)) // name
    end subroutine primitive_routine

end module rollcon_joint_primitives
