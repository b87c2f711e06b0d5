! SPDX-License-Identifier: MIT
!> ADAMS's joints and joint primitives by name (docs/datasets.md, "JOINT and JPRIM"): the
!> joints rollcon simulates, the six primitives, and ADAMS's own decomposition of a joint into
!> primitives, by the degrees of freedom each removes: SPHERICAL = ATPOINT; REVOLUTE = ATPOINT
!> + PARALLEL_AXES; UNIVERSAL = ATPOINT + PERPENDICULAR; CYLINDRICAL = INLINE + PARALLEL_AXES;
!> TRANSLATIONAL = INLINE + ORIENTATION; FIXED = ATPOINT + ORIENTATION; PLANAR = INPLANE +
!> PARALLEL_AXES; HOOKE = ATPOINT + PERPENDICULAR of its cross pins, x_i and y_j (UNIVERSAL's
!> pins are z_i and z_j); CONVEL = ATPOINT + the homokinetic condition x_i.y_j + y_i.x_j = 0,
!> which is no JPRIM (ucon/specs/_joint.py). The names a dataset's JOINT and JPRIM take
!> (rollcon_adm_joints) and the ones model%add_joint and model%add_jprim take
!> (rollcon_joint_primitives) are these.
module rollcon_joint_types
    implicit none
    private

    public :: joint_names, primitive_names, joint_primitives, primitive_index
    public :: is_joint_name, primitive_symmetric, name_list
    public :: primitive_atpoint, primitive_inline, primitive_inplane, primitive_parallel_axes, &
        & primitive_perpendicular, primitive_orientation, primitive_homokinetic

    !> The joint primitives, numbered as primitive_names lists them, and CONVEL's homokinetic
    !> condition after them (a joint's constraint, not a JPRIM)
    integer, parameter :: primitive_atpoint = 1, primitive_inline = 2, primitive_inplane = 3, &
        & primitive_parallel_axes = 4, primitive_perpendicular = 5, primitive_orientation = 6, &
        & primitive_homokinetic = 7
    character(len=*), parameter :: primitive_names(6) = [character(len=13) :: "ATPOINT", &
        & "INLINE", "INPLANE", "PARALLEL_AXES", "PERPENDICULAR", "ORIENTATION"]
    !> The joints rollcon simulates, in alphabetical order
    character(len=*), parameter :: joint_names(9) = [character(len=13) :: "CONVEL", &
        & "CYLINDRICAL", "FIXED", "HOOKE", "PLANAR", "REVOLUTE", "SPHERICAL", "TRANSLATIONAL", &
        & "UNIVERSAL"]

contains

    !> True when name (upper case, in full) is one of joint_names.
    pure logical function is_joint_name(name)
        character(len=*), intent(in) :: name

        is_joint_name = any(joint_names == name)
    end function is_joint_name

    !> The number of the primitive called name (upper case, in full); 0 for none.
    pure integer function primitive_index(name)
        character(len=*), intent(in) :: name

        primitive_index = findloc(primitive_names, name, dim=1)
    end function primitive_index

    !> The primitives (primitive_* numbers) a joint (joint_names) or a primitive
    !> (primitive_names) of this name is made of; empty for any other name. A HOOKE's
    !> PERPENDICULAR holds its cross pins perpendicular, x_i and y_j, not the z axes
    !> (rollcon_joint_primitives).
    pure function joint_primitives(name) result(primitives)
        character(len=*), intent(in) :: name
        integer, allocatable :: primitives(:)

        select case (name)
        case ("SPHERICAL")
            primitives = [primitive_atpoint]
        case ("REVOLUTE")
            primitives = [primitive_atpoint, primitive_parallel_axes]
        case ("UNIVERSAL", "HOOKE")
            primitives = [primitive_atpoint, primitive_perpendicular]
        case ("CONVEL")
            primitives = [primitive_atpoint, primitive_homokinetic]
        case ("PLANAR")
            primitives = [primitive_inplane, primitive_parallel_axes]
        case ("CYLINDRICAL")
            primitives = [primitive_inline, primitive_parallel_axes]
        case ("TRANSLATIONAL")
            primitives = [primitive_inline, primitive_orientation]
        case ("FIXED")
            primitives = [primitive_atpoint, primitive_orientation]
        case default
            primitives = pack([primitive_index(name)], primitive_index(name) > 0)
        end select
    end function joint_primitives

    !> True when the statement means the same with its markers I and J swapped: every JOINT
    !> (its INLINE, I's origin on J's z axis, is J's origin on I's z axis once its other
    !> primitive makes the axes parallel, and a PLANAR's INPLANE likewise; CONVEL's condition
    !> is symmetric; a HOOKE's pins, I's x axis and J's y axis, stay with their markers when
    !> they are swapped), and the primitives ATPOINT, PARALLEL_AXES, PERPENDICULAR and
    !> ORIENTATION; a JPRIM INLINE or INPLANE is not.
    pure logical function primitive_symmetric(name, primitive)
        !> The joint's or primitive's name (upper case, in full)
        character(len=*), intent(in) :: name
        !> True for a JPRIM, false for a JOINT
        logical, intent(in) :: primitive

        primitive_symmetric = .not. (primitive .and. (name == "INLINE" .or. name == "INPLANE"))
    end function primitive_symmetric

    !> "A, B, C" of a list of names.
    pure function name_list(names) result(text)
        character(len=*), intent(in) :: names(:)
        character(len=:), allocatable :: text
        integer :: k

        text = trim(names(1))
        do k = 2, size(names)
            text = text // ", " // trim(names(k))
        end do
    end function name_list

end module rollcon_joint_types
