! SPDX-License-Identifier: MIT
!> The generator's own checks, run from the Fortran tests: python -m ucon check (the committed
!> generated files are what the specs generate) and the generator's Python unit tests. Each
!> is skipped when python3 with the pinned SymPy is missing; its output goes to a log file.
!>
!> Not a suite: test_generated collects these tests.
module generated_python
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : check, skip_test
    implicit none
    private

    public :: test_partials_check, test_python_unittest

    !> Where the tests leave their logs (under fpm's build directory)
    character(len=*), parameter :: work_dir = "build/rollcon-test"

contains

    !> Skip unless python3 with SymPy 1.14.0 (the pinned version: another one may print the
    !> same expressions differently) is available.
    subroutine require_sympy(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: stat, command_stat

        call execute_command_line("python3 -c ""import sys, sympy; " &
            & // "sys.exit(sympy.__version__ != '1.14.0')"" > /dev/null 2>&1", exitstat=stat, &
            & cmdstat=command_stat)
        if (command_stat /= 0 .or. stat /= 0) then
            call skip_test(error, "python3 with sympy 1.14.0 not found (pip install -r " &
                & // "ucon/requirements.txt)")
        end if
    end subroutine require_sympy

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

    !> The committed generated files are what the specs generate today.
    subroutine test_partials_check(error)
        type(error_type), allocatable, intent(out) :: error

        call require_sympy(error)
        if (allocated(error)) return
        call run_logged(error, "python3 -m ucon check", work_dir // "/ucon-check.log", &
            & "python3 -m ucon check (regenerate with: python3 -m ucon write)")
    end subroutine test_partials_check

    !> The generator's unit tests: bad-spec messages, determinism, tables.
    subroutine test_python_unittest(error)
        type(error_type), allocatable, intent(out) :: error

        call require_sympy(error)
        if (allocated(error)) return
        call run_logged(error, "python3 -m unittest discover -s ucon/tests -t .", &
            & work_dir // "/ucon-unittest.log", "python3 -m unittest discover -s ucon/tests")
    end subroutine test_python_unittest

end module generated_python
