! SPDX-License-Identifier: MIT
!> rollcon as a plain fpm dependency (suite fpm-dependency, docs/library.md "From an fpm
!> project"): a throw-away project under build/ whose fpm.toml holds nothing but
!> `rollcon = { path = "../rollcon" }` builds and runs with `fpm build` and `fpm run` alone (no
!> --profile, no --flag, no FPM_FFLAGS), against a copy of the files a clone of rollcon holds.
module test_fpm_dependency
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_version, only : version_text
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use command_runs, only : file_text, rollcon_program
    implicit none
    private

    public :: collect_fpm_dependency

    !> Folder of the suite: rollcon/ the copy, project/ the dependent project, *.log the
    !> commands' output. Kept between runs, so that fpm rebuilds only what changed.
    character(len=*), parameter :: scratch = "build/fpm_dependency"
    !> The dependent program runs the coin to this time [s] with its output step, 0.01 s
    character(len=*), parameter :: end_time = "0.05"
    !> ... so its rows are t = 0, 0.01, ..., 0.05
    integer, parameter :: expected_rows = 6

contains

    subroutine collect_fpm_dependency(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("plain-fpm-build-of-a-dependent", test_plain_build), &
            & new_unittest("programs-without-the-tests-allocator", test_no_test_allocator)]
    end subroutine collect_fpm_dependency

    !> The files git would put in a clone of this working tree (tracked, and untracked files
    !> not ignored: never build/, .venv/ or anything .ci/setup made) are copied to
    !> scratch/rollcon; scratch/project depends on it by path and its program uses the library
    !> (`use rollcon`: load_job and run_job of the coin scene, on IDA). `fpm build` and then
    !> `fpm run` in the project, with FPM_FFLAGS and FPM_LDFLAGS unset, must succeed and print
    !> the library's version and the run's rows. Skipped without fpm or git on PATH, or outside
    !> a git checkout.
    subroutine test_plain_build(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: project = scratch // "/project"
        character(len=:), allocatable :: expected, log
        integer :: status

        call execute_command_line("mkdir -p " // scratch)
        if (.not. have_command("fpm") .or. .not. have_command("git")) then
            call skip_test(error, "fpm or git is not on PATH (bash .ci/setup; source .ci/env)")
            return
        end if
        call shell("mkdir -p " // project // "/app && rm -rf " // scratch // "/rollcon && " &
            & // "mkdir " // scratch // "/rollcon && git ls-files -z --cached --others " &
            & // "--exclude-standard | tar --null --ignore-failed-read -T - -cf - | tar -xf - " &
            & // "-C " // scratch // "/rollcon", scratch // "/copy.log", status)
        if (status /= 0) then
            call skip_test(error, "cannot copy the checkout's files with git ls-files and tar " &
                & // "(not a git checkout?): " // first_lines(file_text(scratch // "/copy.log")))
            return
        end if
        call write_project(project)
        log = scratch // "/build.log"
        call shell("cd " // project // " && env -u FPM_FFLAGS -u FPM_LDFLAGS fpm build", &
            & log, status)
        call check(error, status == 0, "fpm build in " // project // " exited with " &
            & // to_text(status) // ": " // error_lines(file_text(log)) // " (" // log // ")")
        if (allocated(error)) return
        log = scratch // "/run.log"
        call shell("cd " // project // " && env -u FPM_FFLAGS -u FPM_LDFLAGS fpm run", log, &
            & status)
        expected = "dependent: " // version_text() // ", " // to_text(expected_rows) // " rows"
        call check(error, status == 0 .and. index(file_text(log), expected) > 0, "fpm run in " &
            & // project // " exited with " // to_text(status) // ", expected '" // expected &
            & // "': " // error_lines(file_text(log)) // " (" // log // ")")
    end subroutine test_plain_build

    !> The dependent project: its manifest (the dependency, nothing else) and its program.
    subroutine write_project(project)
        character(len=*), intent(in) :: project
        character(len=*), parameter :: nl = new_line("a")

        call write_text(project // "/fpm.toml", "name = ""dependent""" // nl &
            & // "[dependencies]" // nl // "rollcon = { path = ""../rollcon"" }")
        call write_text(project // "/app/main.f90", &
            & "program dependent" // nl &
            & // "    use rollcon, only : job_type, job_result_type, error_type, &" // nl &
            & // "        & load_job, run_job, input_override_type, version_text" // nl &
            & // "    implicit none" // nl &
            & // "    type(job_type) :: job" // nl &
            & // "    type(job_result_type) :: result" // nl &
            & // "    type(error_type), allocatable :: error" // nl &
            & // "    call load_job(""../rollcon/data/coin.nml"", job, error, &" // nl &
            & // "        & overrides=[input_override_type(""run%end_time"", """ // end_time &
            & // """)])" // nl &
            & // "    if (.not. allocated(error)) then" // nl &
            & // "        job%output_dir = """"" // nl &
            & // "        job%quiet = .true." // nl &
            & // "        call run_job(job, result, error)" // nl &
            & // "    end if" // nl &
            & // "    if (allocated(error)) then" // nl &
            & // "        print '(a)', ""dependent: error: "" // error%message" // nl &
            & // "        error stop 1" // nl &
            & // "    end if" // nl &
            & // "    print '(a, i0, a)', ""dependent: "" // version_text() // "", "", &" // nl &
            & // "        & result%summary%rows, "" rows""" // nl &
            & // "end program dependent")
    end subroutine write_project

    !> The programs fpm builds beside the tester (rollcon, rollcon-sweep) hold none of the
    !> tests' code: test/malloc_counter.c defines malloc, calloc and realloc, and linked into a
    !> program it would replace the allocator of every run. Their symbol tables (binutils' nm,
    !> which gfortran needs) name neither the counter's functions nor a malloc of their own.
    !> Skipped without nm, or when the programs are not built.
    subroutine test_no_test_allocator(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, folder, symbols
        character(len=*), parameter :: programs(2) = [character(len=13) :: "rollcon", &
            & "rollcon-sweep"]
        integer :: status, i, cut

        call execute_command_line("mkdir -p " // scratch)
        if (.not. have_command("nm")) then
            call skip_test(error, "nm (binutils) is not on PATH")
            return
        end if
        call rollcon_program(program, error)
        if (allocated(error)) return
        cut = index(program, "/", back=.true.)
        folder = program(:cut)
        do i = 1, size(programs)
            associate (path => folder // trim(programs(i)))
                call shell("nm " // path, scratch // "/nm.log", status)
                call check(error, status == 0, "nm " // path // " failed: " &
                    & // first_lines(file_text(scratch // "/nm.log")))
                if (allocated(error)) return
                symbols = file_text(scratch // "/nm.log")
                call check(error, index(symbols, " rollcon_malloc_count") == 0, path &
                    & // " holds the tests' allocator counter (test/malloc_counter.c; built " &
                    & // "by plain fpm in a checkout updated in place, fpm's archive may keep " &
                    & // "an old object: .ci/test drops the archive, or rm -rf build)")
                if (allocated(error)) return
                call check(error, index(symbols, " T malloc" // new_line("a")) == 0, path &
                    & // " defines malloc: the tests' counter replaces the allocator")
                if (allocated(error)) return
            end associate
        end do
    end subroutine test_no_test_allocator

    !> Run a shell command with its stdout and stderr in log; status is its exit status.
    subroutine shell(command, log, status)
        character(len=*), intent(in) :: command, log
        integer, intent(out) :: status
        integer :: command_status

        status = -1
        call execute_command_line("(" // command // ") > " // log // " 2>&1", &
            & exitstat=status, cmdstat=command_status)
        if (command_status /= 0) status = -1
    end subroutine shell

    !> True when the shell finds the command.
    logical function have_command(name)
        character(len=*), intent(in) :: name
        integer :: status

        call shell("command -v " // name, scratch // "/which.log", status)
        have_command = status == 0
    end function have_command

    !> Write a text file (a line end added).
    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit

        open(newunit=unit, file=path, status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
    end subroutine write_text

    !> The lines of a log that say what went wrong (gfortran's "Error:", fpm's "<ERROR>", a
    !> program's "error:"), else its first lines; at most 400 characters, line ends as "; ".
    function error_lines(text) result(lines)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: lines
        integer :: start, finish

        lines = ""
        start = 1
        do while (start <= len(text))
            finish = index(text(start:), new_line("a"))
            if (finish == 0) finish = len(text) - start + 2
            associate (line => text(start:start + finish - 2))
                if (index(line, "Error:") > 0 .or. index(line, "error:") > 0 .or. &
                    & index(line, "<ERROR>") > 0) lines = lines // line // "; "
            end associate
            start = start + finish
        end do
        if (len(lines) == 0) lines = first_lines(text)
        if (len(lines) > 400) lines = lines(:400) // " ..."
    end function error_lines

    !> The first 400 characters of a text, line ends as "; ".
    function first_lines(text) result(lines)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: lines
        integer :: i

        lines = text(:min(len(text), 400))
        do i = 1, len(lines)
            if (lines(i:i) == new_line("a")) lines(i:i) = ";"
        end do
    end function first_lines

end module test_fpm_dependency
