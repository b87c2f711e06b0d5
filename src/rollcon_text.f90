! SPDX-License-Identifier: MIT
!> Short decimal text of numbers, for messages and tables.
module rollcon_text
    use rollcon_kinds, only : wp
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
    implicit none
    private

    public :: to_text

    !> Decimal text of an integer or a real
    interface to_text
        module procedure :: integer_to_text
        module procedure :: real_to_text
    end interface to_text

contains

    !> Shortest decimal text of an integer.
    pure function integer_to_text(value) result(text)
        !> Value to print
        integer, intent(in) :: value
        character(len=:), allocatable :: text
        character(len=24) :: buffer

        write(buffer, '(i0)') value
        text = trim(buffer)
    end function integer_to_text

    !> Shortest decimal text that reads back as the same real (at most 17 digits).
    pure function real_to_text(value) result(text)
        !> Value to print
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=40) :: buffer
        character(len=12) :: form
        real(wp) :: back
        integer :: digits, stat

        if (ieee_is_nan(value)) then
            text = "NaN"
            return
        else if (.not. ieee_is_finite(value)) then
            text = merge("+Infinity", "-Infinity", value > 0.0_wp)
            return
        end if
        do digits = 1, 17
            write(form, '("(g0.", i0, ")")') digits
            write(buffer, form) value
            read(buffer, *, iostat=stat) back
            if (stat == 0 .and. back == value) exit
        end do
        text = trim(adjustl(buffer))
        text = trim_mantissa(text)
    end function real_to_text

    !> Remove trailing zeros of the mantissa: "0.1000E+01" -> "0.1E+01", "2.50" -> "2.5".
    pure function trim_mantissa(text) result(trimmed)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: trimmed
        character(len=:), allocatable :: mantissa, exponent
        integer :: e, last

        e = scan(text, "Ee")
        if (e > 0) then
            mantissa = text(:e - 1)
            exponent = text(e:)
        else
            mantissa = text
            exponent = ""
        end if
        if (index(mantissa, ".") > 0) then
            last = len_trim(mantissa)
            do while (last > 1 .and. mantissa(last:last) == "0")
                last = last - 1
            end do
            if (mantissa(last:last) == ".") last = last - 1
            mantissa = mantissa(:last)
        end if
        trimmed = mantissa // exponent
    end function trim_mantissa

end module rollcon_text
