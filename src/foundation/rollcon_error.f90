! SPDX-License-Identifier: MIT
!> Error object returned by every rollcon procedure that can fail, and its constructors.
module rollcon_error
    use rollcon_text, only : to_text
    implicit none
    private

    public :: error_type
    public :: fatal_error, input_error, ucon_error
    public :: stat_fatal, stat_input, stat_lapack, stat_solver, stat_ucon, stat_io, stat_skipped

    !> Unspecified failure
    integer, parameter :: stat_fatal = 1
    !> Bad input: a file, key or value that is not what was expected
    integer, parameter :: stat_input = 2
    !> A LAPACK routine reported a problem
    integer, parameter :: stat_lapack = 3
    !> An integrator (SUNDIALS) reported a problem
    integer, parameter :: stat_solver = 4
    !> A UCOSUB or its UCOVAR declaration is wrong
    integer, parameter :: stat_ucon = 5
    !> Reading or writing a file failed
    integer, parameter :: stat_io = 6
    !> Used by the test harness: the test was skipped, not failed
    integer, parameter :: stat_skipped = 77

    !> An error: allocated only when something went wrong
    type :: error_type
        !> One of the stat_* codes
        integer :: stat = stat_fatal
        !> What happened, where, and what was expected
        character(len=:), allocatable :: message
    end type error_type

contains

    !> Allocate an error with a message and an optional status code.
    pure subroutine fatal_error(error, message, stat)
        !> The error to create
        type(error_type), allocatable, intent(out) :: error
        !> What went wrong
        character(len=*), intent(in) :: message
        !> Status code, default stat_fatal
        integer, intent(in), optional :: stat

        allocate(error)
        error%message = message
        if (present(stat)) error%stat = stat
    end subroutine fatal_error

    !> An input error in the form `file:line: 'key' expected`.
    pure subroutine input_error(error, file, line, key, expected)
        !> The error to create
        type(error_type), allocatable, intent(out) :: error
        !> File being read
        character(len=*), intent(in) :: file
        !> Line number in the file, 0 when not known
        integer, intent(in) :: line
        !> Offending key, empty when the problem is not tied to one key
        character(len=*), intent(in) :: key
        !> What was expected, and what was found
        character(len=*), intent(in) :: expected

        character(len=:), allocatable :: where

        where = file
        if (line > 0) where = where // ":" // to_text(line)
        allocate(error)
        error%stat = stat_input
        if (len(key) > 0) then
            error%message = where // ": '" // key // "' " // expected
        else
            error%message = where // ": " // expected
        end if
    end subroutine input_error

    !> An error in a UCOSUB or its declaration, prefixed by the UCON statement id.
    pure subroutine ucon_error(error, id, message)
        !> The error to create
        type(error_type), allocatable, intent(out) :: error
        !> UCON statement id
        integer, intent(in) :: id
        !> What is wrong
        character(len=*), intent(in) :: message

        allocate(error)
        error%stat = stat_ucon
        error%message = "UCON/" // to_text(id) // ": " // message
    end subroutine ucon_error

end module rollcon_error
