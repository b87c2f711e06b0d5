! SPDX-License-Identifier: MIT
!> The assembly of a dataset (src/assembly/): what the readers leave to it is refused there,
!> naming the file, the line and the statement. A ROUTINE that names no built-in routine; a
!> UCON that names none when no model's UCOSUB is given; a JOINT or JPRIM whose markers the
!> model cannot join (model%add_joint, model%add_jprim judge them); a CONVEL whose markers' z
!> axes start less than 90 degrees apart. Each dataset reads cleanly first: these are not the
!> text's to refuse.
module test_assembly
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_build, only : build_adm_problem
    use adm_datasets, only : read_dataset, base, base_file
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_assembly

    !> The built-in UCOSUBs, as a refusal lists them
    character(len=*), parameter :: builtin = &
        & "(disk, rolling_disk, chaplygin_sled, disk_height, gnd_atpoint, gnd_homokinetic," &
        & // " gnd_inline, gnd_inplane, gnd_motion_angle, gnd_orientation, gnd_parallel_axes," &
        & // " gnd_perpendicular, jp_atpoint, jp_homokinetic, jp_inline, jp_inplane," &
        & // " jp_motion_angle, jp_orientation, jp_parallel_axes, jp_perpendicular, knife_edge," &
        & // " planar_hold, rolling_sphere, turntable_ball, turntable_disk)"
    !> A pendulum (data/pendulum.adm's parts and markers): ground marker 10, the bob's CM
    !> marker 20 and hinge marker 21; line 8 is the statement under test
    character(len=60), parameter :: pendulum(10) = [character(len=60) :: &
        & "pendulum", &
        & "PART/1, GROUND", &
        & "MARKER/10, PART=1, REULER=180D, 90D, 0D", &
        & "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01", &
        & ", REULER=90D, 60D, -90D", &
        & "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=0, 90D, 0", &
        & "MARKER/21, PART=2, REULER=180D, 90D, 0D", &
        & "", &
        & "MARKER/11, PART=1", &
        & "SIMULATE/DYNAMIC, END=1, STEPS=10"]

contains

    subroutine collect_assembly(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("routine-that-is-not-built-in", test_routine), &
            & new_unittest("ucon-without-a-routine", test_no_routine), &
            & new_unittest("joint-markers-the-model-refuses", test_joint_markers)]
    end subroutine collect_assembly

    !> ROUTINE=my_lib::ucosub reads (a name), and the assembly refuses it where it was written
    !> when no user's file my_lib is given (none is, here).
    subroutine test_routine(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=len(base) + 60) :: lines(size(base))
        procedure(ucosub_interface), pointer :: disk

        disk => rolling_disk_ucosub
        lines = base
        lines(8) = "UCON/1, FUNCTION=USER(2, 21, 1), ROUTINE=my_lib::ucosub"
        call refused(lines, disk, ":8: UCON/1 ROUTINE: 'my_lib::ucosub' is neither a " &
            & // "built-in UCOSUB " // builtin // " nor a subroutine of a user's file: " &
            & // "ROUTINE=FILE::NAME names the subroutine NAME, with UCOSUB's calling sequence, " &
            & // "of FILE given with rollcon run MODEL.adm --ucosub FILE", error)
    end subroutine test_routine

    !> A UCON that names no ROUTINE, and no model's UCOSUB to serve it.
    subroutine test_no_routine(error)
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: none

        none => null()
        call refused(base, none, ":8: UCON/1: no UCOSUB serves this UCON: name a built-in " &
            & // "routine with ROUTINE=name " // builtin // " or give the model's UCOSUB " &
            & // "(rollcon run MODEL.adm --ucosub FILE|NAME)", error)
    end subroutine test_no_routine

    !> Markers on one part, on the ground both, and an asymmetric primitive with I on the
    !> ground: the model's refusals, with the statement's line. A CONVEL on the pendulum's
    !> hinge markers, whose z axes are one (a REVOLUTE's), and on the bob's hinge marker (z
    !> along ground Y) and a ground marker whose z is 30 degrees from it: refused by the
    !> assembly; with that marker's z 150 degrees from the hinge's (its shafts bent by 30
    !> degrees, ADAMS's CONVEL markers), the problem is made.
    subroutine test_joint_markers(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: statements(6) = [character(len=70) :: &
            & "JOINT/1, REVOLUTE, I=21, J=20", "JOINT/1, SPHERICAL, I=10, J=11", &
            & "JPRIM/1, INLINE, I=10, J=21", "JPRIM/1, INPLANE, I=10, J=21", &
            & "JOINT/1, CONVEL, I=21, J=10", &
            & "JOINT/1, CONVEL, I=21, J=12|MARKER/12, PART=1, REULER=180D, 60D, 0"]
        character(len=*), parameter :: expected(6) = [character(len=300) :: &
            & ":8: JOINT/1: its markers I (MARKER/21) and J (MARKER/20) are both on PART/2; " &
            & // "a joint connects two parts", &
            & ":8: JOINT/1: its markers I (MARKER/10) and J (MARKER/11) are both on the " &
            & // "ground; a joint connects two parts", &
            & ":8: JPRIM/1 I: MARKER/10 is on the ground part; an INLINE primitive is not " &
            & // "symmetric in I and J", &
            & ":8: JPRIM/1 I: MARKER/10 is on the ground part; an INPLANE primitive is not " &
            & // "symmetric in I and J", &
            & ":8: JOINT/1: a CONVEL's markers' z axes point along its two shafts, away from " &
            & // "the joint's centre (opposite when the shafts are in line), but at the start " &
            & // "I's (MARKER/21) and J's (MARKER/10) are 0 degrees apart, more than 90 " &
            & // "degrees from opposite: turn one of them half a turn about its x axis", &
            & ":8: JOINT/1: a CONVEL's markers' z axes point along its two shafts, away from " &
            & // "the joint's centre (opposite when the shafts are in line), but at the start " &
            & // "I's (MARKER/21) and J's (MARKER/12) are 30 degrees apart"]
        character(len=80) :: lines(size(pendulum))
        procedure(ucosub_interface), pointer :: disk
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)
        integer :: k

        disk => rolling_disk_ucosub
        do k = 1, size(statements)
            lines = pendulum
            lines(8) = statements(k)
            call refused(lines, disk, trim(expected(k)), error)
            if (allocated(error)) return
        end do
        lines = pendulum
        lines(8) = "JOINT/1, CONVEL, I=21, J=12|MARKER/12, PART=1, REULER=0, 60D, 0"
        call read_dataset("convel.adm", lines, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, problem, q0, u0, error)
        call problem%release()
    end subroutine test_joint_markers

    !> The dataset of these lines reads cleanly, and its assembly is refused with a message
    !> that begins with the file's name and `expected`.
    subroutine refused(lines, routine, expected, error)
        character(len=*), intent(in) :: lines(:)
        procedure(ucosub_interface), pointer, intent(in) :: routine
        character(len=*), intent(in) :: expected
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(error_type), allocatable :: failure
        real(wp), allocatable :: q0(:), u0(:)

        call read_dataset("refusal.adm", lines, adm, failure)
        if (allocated(failure)) then
            call check(error, .false., "the reader refused " // trim(lines(8)) // ": " &
                & // failure%message)
            return
        end if
        call build_adm_problem(adm, routine, problem, q0, u0, failure)
        call problem%release()
        call check(error, allocated(failure), "assembled: " // trim(lines(8)))
        if (allocated(error)) return
        call check(error, index(failure%message, base_file // expected) == 1, "message '" &
            & // failure%message // "', expected '" // base_file // expected // "'")
    end subroutine refused

end module test_assembly
