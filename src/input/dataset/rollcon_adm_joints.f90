! SPDX-License-Identifier: MIT
!> Dataset statements JOINT and JPRIM (docs/datasets.md, "JOINT and JPRIM"): ADAMS's joints
!> and joint primitives between marker I and marker J, read and checked as the text states
!> them: a type of rollcon_joint_types, and the two markers (that they are MARKERs is checked
!> with every reference, rollcon_adm_checks). The model makes each one UCONs
!> (model%add_joint, model%add_jprim), which also judges the markers' parts. RACKPIN (with its
!> pitch diameter PD) and SCREW (with its PITCH) couple the motions of the parts they join: the
!> assembly makes each a constraint of its markers' measures (rollcon_adm_build).
module rollcon_adm_joints
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_adm_units, only : units_type
    use rollcon_joint_types, only : joint_names, primitive_names, name_list
    use rollcon_adm_lexer, only : adm_statement_type
    use rollcon_adm_keywords, only : argument_key, arg_place, read_integer, read_reals
    implicit none
    private

    public :: adm_joint_type, read_joint

    !> ADAMS's keywords of a JOINT that rollcon reads and refuses (initial conditions, friction,
    !> the joints it does not simulate)
    character(len=*), parameter :: joint_refused(5) = [character(len=19) :: "IC", "ICTRAN", &
        & "ICROT", "DELTA_V", "MAXIMUM_DEFORMATION"]
    !> The joints that couple motions, and their keywords
    character(len=*), parameter :: coupling_joints(2) = [character(len=7) :: "RACKPIN", "SCREW"]
    character(len=*), parameter :: coupling_keys(2) = [character(len=5) :: "PD", "PITCH"]

    !> JOINT/id or JPRIM/id
    type :: adm_joint_type
        integer :: id = 0, line = 0
        !> True for a JPRIM statement
        logical :: primitive = .false.
        !> The joint's or primitive's type as written in full (REVOLUTE, INPLANE, ...)
        character(len=:), allocatable :: kind
        !> Marker I and marker J
        integer :: i = 0, j = 0
        !> RACKPIN: the pinion's pitch diameter [m]; SCREW: the translation per turn [m]
        real(wp) :: pd = 0.0_wp, pitch = 0.0_wp
    end type adm_joint_type

contains

    !> JOINT/id, type, I=id, J=id or JPRIM/id, type, I=id, J=id (name says which); that the
    !> markers exist is checked once the file is read (rollcon_adm_checks).
    subroutine read_joint(path, where, name, statement, units, joint, error)
        character(len=*), intent(in) :: path, where, name
        type(adm_statement_type), intent(in) :: statement
        !> The dataset's units (PD and PITCH are lengths)
        type(units_type), intent(in) :: units
        type(adm_joint_type), intent(out) :: joint
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, pd_at, pitch_at
        character(len=32), allocatable :: allowed(:)
        real(wp), allocatable :: values(:)
        integer :: k

        joint%id = statement%id
        joint%line = statement%line
        joint%primitive = name == "JPRIM"
        if (joint%primitive) then
            allowed = [character(len=32) :: primitive_names, "I", "J"]
        else
            allowed = [character(len=32) :: joint_names, "I", "J", joint_refused, &
                & coupling_joints, coupling_keys]
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
            case ("PD", "PITCH")
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, &
                    & units%length)
                if (allocated(error)) return
                if (key == "PD") then
                    joint%pd = values(1)
                    pd_at = at
                else
                    joint%pitch = values(1)
                    pitch_at = at
                end if
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
                    & // name_list(joint_names) // "; or a coupling, " &
                    & // name_list(coupling_joints) // ")", stat_input)
            end if
        else if (joint%i == 0) then
            call fatal_error(error, where // ": I=id is missing (the marker on the first " &
                & // "part)", stat_input)
        else if (joint%j == 0) then
            call fatal_error(error, where // ": J=id is missing (the marker on the second " &
                & // "part, or on ground)", stat_input)
        else if (allocated(pd_at) .and. joint%kind /= "RACKPIN") then
            call fatal_error(error, pd_at // ": PD is the pitch diameter of a RACKPIN " &
                & // "joint, not of a " // joint%kind // " joint", stat_input)
        else if (allocated(pitch_at) .and. joint%kind /= "SCREW") then
            call fatal_error(error, pitch_at // ": PITCH is the translation per turn of a " &
                & // "SCREW joint, not of a " // joint%kind // " joint", stat_input)
        else if (joint%kind == "RACKPIN" .and. .not. joint%pd > 0.0_wp) then
            call fatal_error(error, where // ": a RACKPIN joint needs PD=d > 0, the pinion's " &
                & // "pitch diameter [length]", stat_input)
        else if (joint%kind == "SCREW" .and. joint%pitch == 0.0_wp) then
            call fatal_error(error, where // ": a SCREW joint needs PITCH=p /= 0, the " &
                & // "translation per turn [length] (negative for a left-handed thread)", &
                & stat_input)
        end if
    end subroutine read_joint

end module rollcon_adm_joints
