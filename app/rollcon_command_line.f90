! SPDX-License-Identifier: MIT
!> Reading option values from the command line, with messages that name the option.
module rollcon_command_line
    use rollcon, only : wp, error_type, fatal_error, stat_input
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: real_option, real_option_list

contains

    !> Read argument i as one finite real, the value of option name.
    subroutine real_option(name, i, value, error)
        !> Option being read, for the message
        character(len=*), intent(in) :: name
        !> Index of the argument holding the value
        integer, intent(in) :: i
        !> The value
        real(wp), intent(out) :: value
        !> Set when the argument is missing or not a finite number
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: values(1)

        call real_option_list(name, i, values, error)
        value = values(1)
    end subroutine real_option

    !> Read argument i as exactly size(values) finite reals separated by commas.
    subroutine real_option_list(name, i, values, error)
        character(len=*), intent(in) :: name
        integer, intent(in) :: i
        real(wp), intent(inout) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=1024) :: argument
        character(len=64) :: extra
        integer :: stat, length

        if (i > command_argument_count()) then
            call fatal_error(error, name // " needs a value", stat_input)
            return
        end if
        call get_command_argument(i, argument, length)
        read(argument, *, iostat=stat) values
        if (stat == 0) then
            ! A further value means the list is too long.
            read(argument, *, iostat=stat) values, extra
            if (stat == 0) then
                call fatal_error(error, name // " expects " // count_text(size(values)) &
                    & // ", got '" // argument(:length) // "'", stat_input)
                return
            end if
            stat = 0
        end if
        if (stat /= 0 .or. .not. all(ieee_is_finite(values))) then
            call fatal_error(error, name // " expects " // count_text(size(values)) // ", got '" &
                & // argument(:length) // "'", stat_input)
        end if
    end subroutine real_option_list

    pure function count_text(n) result(text)
        integer, intent(in) :: n
        character(len=:), allocatable :: text
        character(len=16) :: buffer

        if (n == 1) then
            text = "one finite number"
        else
            write(buffer, '(i0)') n
            text = trim(buffer) // " finite numbers separated by commas"
        end if
    end function count_text

end module rollcon_command_line
