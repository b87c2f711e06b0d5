! SPDX-License-Identifier: MIT
!> Running `rollcon check` (and `rollcon run`) from the checker's tests with a time bound: the
!> program found by command_runs, its cache under build/, its output in files under build/,
!> and how long each run took.
module check_command_support
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : check
    use command_runs, only : run_rollcon, file_text
    implicit none
    private

    public :: bounded_run_type, run_bounded, make_folder, remove_folder, expect_in, timed_out

    !> Cache of the libraries these tests build (the program's $XDG_CACHE_HOME)
    character(len=*), parameter :: test_cache = "build/rollcon-test-check-cache"
    !> Exit status of timeout(1) when it stopped the program
    integer, parameter :: timed_out = 124

    !> What one run of the program did
    type :: bounded_run_type
        !> Its exit status (timed_out when the bound stopped it)
        integer :: status = -1
        !> Its stdout and stderr
        character(len=:), allocatable :: out, err
        !> Its wall time [s]
        real(wp) :: seconds = 0.0_wp
    end type bounded_run_type

contains

    !> Run `program arguments` for at most limit seconds (timeout(1) stops it with SIGTERM, and
    !> SIGKILL 2 s later), its output in scratch/name.out and .err.
    subroutine run_bounded(program, arguments, limit, scratch, name, run)
        !> The rollcon program (command_runs%rollcon_program)
        character(len=*), intent(in) :: program
        !> Its arguments, for the shell
        character(len=*), intent(in) :: arguments
        !> Longest the run may take [s]
        integer, intent(in) :: limit
        !> Folder of the output files, and their name
        character(len=*), intent(in) :: scratch, name
        !> What happened
        type(bounded_run_type), intent(out) :: run
        integer(int64) :: start, finish, rate

        call system_clock(start, rate)
        call run_rollcon("XDG_CACHE_HOME=" // test_cache // " timeout -k 2 " // to_text(limit) &
            & // " " // program, arguments, scratch // "/" // name // ".out", scratch // "/" &
            & // name // ".err", run%status)
        call system_clock(finish)
        run%seconds = real(finish - start, wp) / real(rate, wp)
        run%out = file_text(scratch // "/" // name // ".out")
        run%err = file_text(scratch // "/" // name // ".err")
    end subroutine run_bounded

    !> Create a folder and its parents.
    subroutine make_folder(folder)
        character(len=*), intent(in) :: folder

        call execute_command_line("mkdir -p " // folder)
    end subroutine make_folder

    !> Remove a folder and what it holds.
    subroutine remove_folder(folder)
        character(len=*), intent(in) :: folder

        call execute_command_line("rm -rf " // folder)
    end subroutine remove_folder

    !> Pass when text contains part; the message says what was looked for and in what.
    subroutine expect_in(error, text, part, what)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: text, part, what

        call check(error, index(text, part) > 0, what // " lacks '" // part // "': " // text)
    end subroutine expect_in

end module check_command_support
