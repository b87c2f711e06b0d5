! SPDX-License-Identifier: MIT
!> The benchmark bicycle's dataset, data/bicycle.adm (docs/models.md): it is what its writer
!> makes of its table (python3 data/bicycle/write_adm.py data/bicycle/benchmark.txt --check),
!> its geometry is the paper's (data/bicycle/check_geometry.py, in Python, independent of the
!> Fortran), and, its JOINT statements left out, the reader and the model take it: the frames'
!> products of inertia give the principal moments and axes worked out by hand, and every part
!> starts where the table puts it.
module test_adm_bicycle
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    implicit none
    private

    public :: collect_adm_bicycle

    character(len=*), parameter :: dataset = "data/bicycle.adm"
    character(len=*), parameter :: table = "data/bicycle/benchmark.txt"
    !> Where the tests leave their logs and the dataset without its joints
    character(len=*), parameter :: work_dir = "build/rollcon-test"
    !> dsyev's eigenpairs of the frames' tensors (moments up to 11 kg m^2) are exact to a few
    !> eps of the largest: 1e-13 kg m^2 and 1e-14 in a unit vector's components. The numbers
    !> worked by hand differ from wrong ones (a product's sign, the paper's z-down axes kept)
    !> by 0.1 and more
    real(wp), parameter :: tol_moments = 1.0e-13_wp, tol_axes = 1.0e-14_wp

contains

    !> Tests of this suite.
    subroutine collect_adm_bicycle(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("writer-up-to-date", test_up_to_date), &
            & new_unittest("geometry-in-python", test_geometry), &
            & new_unittest("reads-without-joints", test_reads), &
            & new_unittest("writer-errors-named", test_writer_errors)]
    end subroutine collect_adm_bicycle

    !> The checked-in dataset is what the writer makes of the table today.
    subroutine test_up_to_date(error)
        type(error_type), allocatable, intent(out) :: error

        call require_python(error)
        if (allocated(error)) return
        call run_logged(error, "python3 data/bicycle/write_adm.py " // table // " --check " &
            & // dataset, work_dir // "/bicycle-write.log", dataset // " is not what " &
            & // table // " gives (regenerate: python3 data/bicycle/write_adm.py " // table &
            & // " -o " // dataset // ")")
    end subroutine test_up_to_date

    !> Joint markers at one point about one axis, the wheels' contacts on the ground, the
    !> front one at x = w, the trail c, the tilt lambda, the inertias in the paper's axes, the
    !> rolling start: checked from the dataset's text by check_geometry.py.
    subroutine test_geometry(error)
        type(error_type), allocatable, intent(out) :: error

        call require_python(error)
        if (allocated(error)) return
        call run_logged(error, "python3 data/bicycle/check_geometry.py " // table // " " &
            & // dataset, work_dir // "/bicycle-geometry.log", "the geometry check of " &
            & // dataset)
    end subroutine test_geometry

    !> The dataset without its JOINT statements (the frames and wheels alone; suite bicycle runs
    !> the whole dataset, joints and all)
    !> reads and builds. The rear frame's tensor in the CM marker's axes (x forward, z up) is
    !> [[9.2, 0, -2.4], [0, 11, 0], [-2.4, 0, 2.8]]: by hand its x-z block has the eigenvalues
    !> 6 +- sqrt(3.2^2 + 2.4^2) = 10 and 2, along (3, 0, -1)/sqrt(10) and (1, 0, 3)/sqrt(10),
    !> and 11 along y: the principal axes are the CM marker's turned by atan(1/3) about y, so
    !> the principal z starts tilted by theta = atan(1/3) from ground z. The front frame's,
    !> [[0.05892, 0, 0.00756], [0, 0.06, 0], [0.00756, 0, 0.00708]], has 0.033 +- 0.027 = 0.06
    !> along (7, 0, 1)/sqrt(50) and 0.006 along (-1, 0, 7)/sqrt(50), and 0.06 again along y:
    !> a repeated moment, whose pair closest to the CM marker's axes is x = (7, 0, 1)/sqrt(50),
    !> y = (0, 1, 0). The wheels keep IP as written, upright (theta = pi/2) at their axles.
    subroutine test_reads(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)
        character(len=4096) :: line
        integer :: in, out, stat
        logical :: joint

        open(newunit=in, file=dataset, status="old", action="read", iostat=stat)
        call check(error, stat == 0, "cannot open " // dataset)
        if (allocated(error)) return
        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=out, file=work_dir // "/bicycle_no_joints.adm", status="replace", &
            & action="write")
        joint = .false.
        do
            read(in, '(a)', iostat=stat) line
            if (stat /= 0) exit
            ! a JOINT statement and its continuation lines (which start with a comma)
            if (index(adjustl(line), ",") /= 1) joint = index(adjustl(line), "JOINT/") == 1
            if (.not. joint) write(out, '(a)') trim(line)
        end do
        close(in)
        close(out)
        call read_adm(work_dir // "/bicycle_no_joints.adm", adm, error)
        if (allocated(error)) return
        call check(error, size(adm%parts) == 5 .and. size(adm%ucons) == 6, "parts " &
            & // to_text(size(adm%parts)) // ", UCONs " // to_text(size(adm%ucons)))
        if (allocated(error)) return
        associate (rear => adm%parts(3), front => adm%parts(4))
            call check(error, all(abs(rear%ip - [10.0_wp, 11.0_wp, 2.0_wp]) <= tol_moments) &
                & .and. all(abs(rear%principal(:, 1) - [3.0_wp, 0.0_wp, -1.0_wp]/sqrt(10.0_wp)) &
                & <= tol_axes) .and. all(abs(rear%principal(:, 3) - [1.0_wp, 0.0_wp, 3.0_wp] &
                & /sqrt(10.0_wp)) <= tol_axes), "rear frame: moments " // to_text(rear%ip(1)) &
                & // ", " // to_text(rear%ip(2)) // ", " // to_text(rear%ip(3)))
            if (allocated(error)) return
            call check(error, all(abs(front%ip - [0.06_wp, 0.06_wp, 0.006_wp]) <= tol_moments) &
                & .and. all(abs(front%principal(:, 1) - [7.0_wp, 0.0_wp, 1.0_wp] &
                & /sqrt(50.0_wp)) <= tol_axes) .and. all(abs(front%principal(:, 2) &
                & - [0.0_wp, 1.0_wp, 0.0_wp]) <= tol_axes), "front frame: moments " &
                & // to_text(front%ip(1)) // ", " // to_text(front%ip(2)) // ", " &
                & // to_text(front%ip(3)) // "; x = (" // to_text(front%principal(1, 1)) &
                & // ", " // to_text(front%principal(2, 1)) // ", " &
                & // to_text(front%principal(3, 1)) // ")")
            if (allocated(error)) return
        end associate
        call check(error, all(adm%parts(2)%ip == [0.0603_wp, 0.0603_wp, 0.12_wp]) .and. &
            & all(adm%parts(5)%ip == [0.1405_wp, 0.1405_wp, 0.28_wp]), "the wheels' IP changed")
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q0, u0=u0, error=error)
        if (allocated(error)) return
        ! q of part p (model order R, B, H, F) is q0(6 p - 5 : 6 p): X, Y, Z, psi, theta, phi
        call check(error, all(abs(q0(1:3) - [0.0_wp, 0.0_wp, 0.3_wp]) <= tol_axes) .and. &
            & abs(q0(5) - pi/2) <= tol_axes .and. all(abs(q0(7:9) - [0.3_wp, 0.0_wp, 0.9_wp]) &
            & <= tol_axes) .and. abs(q0(11) - atan(1.0_wp/3.0_wp)) <= tol_axes .and. &
            & abs(q0(17) - atan(1.0_wp/7.0_wp)) <= tol_axes .and. all(abs(q0(19:21) &
            & - [1.02_wp, 0.0_wp, 0.35_wp]) <= tol_axes) .and. abs(q0(23) - pi/2) <= tol_axes &
            & .and. all(abs(u0(1:24:6) - 5.0_wp) <= tol_axes), "start: rear frame theta " &
            & // to_text(q0(11)) // " rad, front frame theta " // to_text(q0(17)) // " rad")
    end subroutine test_reads

    !> Skip unless python3 runs.
    subroutine require_python(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: stat, command_stat

        call execute_command_line("python3 -c 'import sys' > /dev/null 2>&1", exitstat=stat, &
            & cmdstat=command_stat)
        if (command_stat /= 0 .or. stat /= 0) call skip_test(error, "python3 not found")
    end subroutine require_python

    !> The writer's refusals are one line naming the file and what is wrong, never a Python
    !> traceback: -o in a folder that does not exist, -o naming a folder, a table that is not
    !> ASCII (its line), --check of a file that is not ASCII, a table that does not exist.
    subroutine test_writer_errors(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: bad = work_dir // "/not_ascii.txt"
        character(len=80) :: arguments(5), expected(5)
        character(len=:), allocatable :: err
        integer :: k, stat, command_stat, unit

        call require_python(error)
        if (allocated(error)) return
        call execute_command_line("mkdir -p " // work_dir, exitstat=stat, cmdstat=command_stat)
        open(newunit=unit, file=bad, status="replace", action="write", access="stream")
        write(unit) "w 1.02 m" // new_line("a") // achar(255) // new_line("a")
        close(unit)
        arguments = [character(len=80) :: table // " -o " // work_dir // "/no/such/x.adm", &
            & table // " -o " // work_dir, bad // " -o " // work_dir // "/x.adm", &
            & table // " --check " // bad, work_dir // "/none.txt -o " // work_dir // "/x.adm"]
        expected = [character(len=80) :: work_dir // "/no/such/x.adm: cannot write: no folder", &
            & work_dir // ": is a folder, not a file", bad // ":2: not ASCII text (byte 0xff", &
            & bad // ":2: not ASCII text (byte 0xff", work_dir // "/none.txt: no such file"]
        do k = 1, size(arguments)
            call execute_command_line("python3 data/bicycle/write_adm.py " &
                & // trim(arguments(k)) // " > " // work_dir // "/writer.out 2> " // work_dir &
                & // "/writer.err", exitstat=stat, cmdstat=command_stat)
            err = file_text(work_dir // "/writer.err")
            call check(error, command_stat == 0 .and. stat /= 0 .and. index(err, &
                & "write_adm.py: " // trim(expected(k))) == 1 .and. index(err, "Traceback") &
                & == 0 .and. count_lines(err) == 1, "write_adm.py " // trim(arguments(k)) &
                & // ": exit status " // to_text(stat) // ", stderr: " // err)
            if (allocated(error)) return
        end do
    end subroutine test_writer_errors

    !> The whole of a small text file ("" when it cannot be read).
    function file_text(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        integer :: unit, size_bytes, stat

        text = ""
        open(newunit=unit, file=path, status="old", action="read", access="stream", &
            & iostat=stat)
        if (stat /= 0) return
        inquire(unit=unit, size=size_bytes)
        if (size_bytes > 0) then
            deallocate(text)
            allocate(character(len=size_bytes) :: text)
            read(unit, iostat=stat) text
        end if
        close(unit)
    end function file_text

    !> Line ends in a text.
    pure integer function count_lines(text)
        character(len=*), intent(in) :: text
        integer :: i

        count_lines = 0
        do i = 1, len(text)
            if (text(i:i) == new_line("a")) count_lines = count_lines + 1
        end do
    end function count_lines

    !> Run a command with its output in a log file; fail naming the log if it exits non-zero.
    subroutine run_logged(error, command, log, what)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: command, log, what
        integer :: stat, command_stat

        call execute_command_line("mkdir -p " // work_dir, exitstat=stat, cmdstat=command_stat)
        call execute_command_line(command // " > " // log // " 2>&1", exitstat=stat, &
            & cmdstat=command_stat)
        call check(error, command_stat == 0 .and. stat == 0, what // " failed (exit status " &
            & // to_text(stat) // "); see " // log)
    end subroutine run_logged

end module test_adm_bicycle
