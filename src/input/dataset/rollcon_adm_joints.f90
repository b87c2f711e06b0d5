! SPDX-License-Identifier: MIT
!> Dataset statements JOINT and JPRIM (docs/datasets.md, "JOINT and JPRIM"): ADAMS's joints
!> and joint primitives between marker I and marker J, read and checked as the text states
!> them: a type of rollcon_joint_types, and the two markers (that they are MARKERs is checked
!> with every reference, rollcon_adm_checks). The model makes each one UCONs
!> (model%add_joint, model%add_jprim), which also judges the markers' parts.
module rollcon_adm_joints
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_joint_types, only : joint_names, primitive_names, name_list
    use rollcon_adm_lexer, only : adm_statement_type
    use rollcon_adm_keywords, only : argument_key, arg_place, read_integer
    implicit none
    private

    public :: adm_joint_type, read_joint

    !> ADAMS's keywords of a JOINT that rollcon reads and refuses (initial conditions, friction,
    !> the joints it does not simulate)
    character(len=*), parameter :: joint_refused(7) = [character(len=19) :: "IC", "ICTRAN", &
        & "ICROT", "DELTA_V", "MAXIMUM_DEFORMATION", "RACKPIN", "SCREW"]

    !> JOINT/id or JPRIM/id
    type :: adm_joint_type
        integer :: id = 0, line = 0
        !> True for a JPRIM statement
        logical :: primitive = .false.
        !> The joint's or primitive's type as written in full (REVOLUTE, INPLANE, ...)
        character(len=:), allocatable :: kind
        !> Marker I and marker J
        integer :: i = 0, j = 0
    end type adm_joint_type

contains

    !> JOINT/id, type, I=id, J=id or JPRIM/id, type, I=id, J=id (name says which); that the
    !> markers exist is checked once the file is read (rollcon_adm_checks).
    subroutine read_joint(path, where, name, statement, joint, error)
        character(len=*), intent(in) :: path, where, name
        type(adm_statement_type), intent(in) :: statement
        type(adm_joint_type), intent(out) :: joint
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        character(len=32), allocatable :: allowed(:)
        integer :: k

        joint%id = statement%id
        joint%line = statement%line
        joint%primitive = name == "JPRIM"
        if (joint%primitive) then
            allowed = [character(len=32) :: primitive_names, "I", "J"]
        else
            allowed = [character(len=32) :: joint_names, "I", "J", joint_refused]
        end if
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, allowed, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("I")
                call read_integer(statement%arguments(k), at, joint%i, error)
            case ("J")
                call read_integer(statement%arguments(k), at, joint%j, error)
            case ("IC", "ICTRAN", "ICROT", "DELTA_V", "MAXIMUM_DEFORMATION")
                call fatal_error(error, at // ": a joint's initial conditions and its friction " &
                    & // "are not supported: rollcon's initial-conditions analysis places the " &
                    & // "parts (docs/initial-conditions.md); give the parts' QG, REULER and " &
                    & // "velocities instead", stat_input)
            case ("RACKPIN", "SCREW")
                call fatal_error(error, at // ": a " // key // " joint is not supported " &
                    & // "(supported: " // name_list(joint_names) // ", and JPRIM)", stat_input)
            case default
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                else if (allocated(joint%kind)) then
                    call fatal_error(error, at // ": the type is given twice (" // joint%kind &
                        & // " and " // key // ")", stat_input)
                else
                    joint%kind = key
                end if
            end select
            if (allocated(error)) return
        end do
        if (.not. allocated(joint%kind)) then
            if (joint%primitive) then
                call fatal_error(error, where // ": the type is missing (one of " &
                    & // name_list(primitive_names) // ")", stat_input)
            else
                call fatal_error(error, where // ": the type is missing (one of " &
                    & // name_list(joint_names) // ")", stat_input)
            end if
        else if (joint%i == 0) then
            call fatal_error(error, where // ": I=id is missing (the marker on the first " &
                & // "part)", stat_input)
        else if (joint%j == 0) then
            call fatal_error(error, where // ": J=id is missing (the marker on the second " &
                & // "part, or on ground)", stat_input)
        end if
    end subroutine read_joint

end module rollcon_adm_joints
