! SPDX-License-Identifier: MIT
!> `rollcon run` on datasets with JOINT statements, as a user runs them (suite joint-command):
!> data/pendulum.adm runs to completion served by the joint-primitive routines; a pendulum
!> given 1 mm apart is pulled together and the program prints what moved, with units; a bad
!> JOINT is refused with exit status 1 and a message naming file, line, statement and
!> keyword.
module test_joint_command
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines
    use command_runs, only : rollcon_program, run_rollcon, file_text
    implicit none
    private

    public :: collect_joint_command

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_joint_command"
    !> The pendulum's lines after its JOINT (data/pendulum.adm, shortened to 0.1 s)
    character(len=*), parameter :: tail(3) = [character(len=40) :: "ACCGRAV/KGRAV=-9.81", &
        & "SIMULATE/DYNAMIC, END=0.1, DTOUT=0.01", "INTEGRATOR/ERROR=1e-10"]

contains

    subroutine collect_joint_command(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("pendulum-runs", test_pendulum), &
            & new_unittest("apart-pulled-together-and-printed", test_apart), &
            & new_unittest("bad-joint-refused", test_refused)]
    end subroutine collect_joint_command

    !> `rollcon run data/pendulum.adm` completes (exit status 0), its five UCONs served by the
    !> generated gnd_atpoint and gnd_parallel_axes routines, as its summary says.
    subroutine test_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, summary
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run data/pendulum.adm -q -o " // scratch, scratch &
            & // "/run.out", scratch // "/run.err", status)
        summary = file_text(scratch // "/pendulum.adm.summary.txt")
        call remove_folder(scratch)
        call check(error, status == 0 .and. index(summary, "status: completed at t = 4 s") > 0 &
            & .and. index(summary, "UCON 3: gnd_atpoint, UCON 4: gnd_parallel_axes") > 0, &
            & "exit status " // to_text(status) // "; summary: " // summary)
    end subroutine test_pendulum

    !> The pendulum's hinge 1 mm above the bob's I marker: the run prints the analysis's moves
    !> of part 2, each coordinate with its units, and runs (exit status 0).
    subroutine test_apart(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_lines(scratch // "/apart.adm", [character(len=72) :: "pendulum, 1 mm apart", &
            & "PART/1, GROUND", "MARKER/10, PART=1, QP=0, 0, 0.001, REULER=180D, 90D, 0D", &
            & "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01, REULER=90D, 60D, -90D", &
            & "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=0, 90D, 0", &
            & "MARKER/21, PART=2, REULER=180D, 90D, 0D", "JOINT/1, REVOLUTE, I=21, J=10", tail])
        call run_rollcon(program, "run " // scratch // "/apart.adm -o " // scratch, scratch &
            & // "/run.out", scratch // "/run.err", status)
        out = file_text(scratch // "/run.out")
        call remove_folder(scratch)
        call check(error, status == 0 .and. index(out, "5 position UCON(s)") > 0 .and. &
            & index(out, "moved to meet the UCONs") > 0 .and. index(out, "part 2: X_2 ") > 0 &
            & .and. index(out, "part 2: Z_2 ") > 0 .and. index(out, " m (by ") > 0, &
            & "exit status " // to_text(status) // "; output: " // out)
    end subroutine test_apart

    !> A JOINT without its J marker: exit status 1 and the message on standard error.
    subroutine test_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_lines(scratch // "/bad.adm", [character(len=72) :: "pendulum", &
            & "PART/1, GROUND", "MARKER/10, PART=1, REULER=180D, 90D, 0D", &
            & "PART/2, MASS=1, CM=20, IP=0.01, 0.01, 0.01, REULER=90D, 60D, -90D", &
            & "MARKER/20, PART=2, QP=0, 0, -0.5, REULER=0, 90D, 0", &
            & "MARKER/21, PART=2, REULER=180D, 90D, 0D", "JOINT/1, REVOLUTE, I=21", tail])
        call run_rollcon(program, "run " // scratch // "/bad.adm -q -o " // scratch, scratch &
            & // "/run.out", scratch // "/run.err", status)
        err = file_text(scratch // "/run.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. index(err, scratch // "/bad.adm:7: JOINT/1: J=id " &
            & // "is missing") > 0, "exit status " // to_text(status) // "; error: " // err)
    end subroutine test_refused

end module test_joint_command
