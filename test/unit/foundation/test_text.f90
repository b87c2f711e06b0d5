! SPDX-License-Identifier: MIT
!> Tests of number formatting used in every message.
module test_text
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text, decimal_value, es_text
    use rollcon_testing, only : error_type, unittest_type, new_unittest, check, skip_test
    use, intrinsic :: iso_c_binding, only : c_char, c_int, c_ptr, c_null_char, c_associated, &
        & c_f_pointer, c_size_t
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_is_finite, &
        & ieee_next_after, ieee_positive_inf, ieee_negative_inf
    implicit none
    private

    public :: collect_text

    !> glibc's LC_ALL (locale.h)
    integer(c_int), parameter :: lc_all = 6

    !> The first member of C's struct lconv: the decimal point's text
    type, bind(c) :: lconv_head
        type(c_ptr) :: decimal_point
    end type lconv_head

    interface
        function setlocale(category, locale) bind(c, name="setlocale") result(name)
            import :: c_int, c_char, c_ptr
            integer(c_int), value :: category
            character(kind=c_char), intent(in) :: locale(*)
            type(c_ptr) :: name
        end function setlocale
        function localeconv() bind(c, name="localeconv") result(conventions)
            import :: c_ptr
            type(c_ptr) :: conventions
        end function localeconv
        function c_getcwd(buffer, size) bind(c, name="getcwd") result(path)
            import :: c_char, c_ptr, c_size_t
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_size_t), value :: size
            type(c_ptr) :: path
        end function c_getcwd
        function setenv(name, value, overwrite) bind(c, name="setenv") result(status)
            import :: c_char, c_int
            character(kind=c_char), intent(in) :: name(*), value(*)
            integer(c_int), value :: overwrite
            integer(c_int) :: status
        end function setenv
    end interface

contains

    !> Tests of this suite.
    subroutine collect_text(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("shortest-round-trip", test_round_trip), &
            & new_unittest("integers-and-nan", test_special), &
            & new_unittest("digits-as-fortran-io", test_fortran_io_digits), &
            & new_unittest("integers-as-i0", test_integers_as_i0), &
            & new_unittest("decimal-value-as-read", test_decimal_value), &
            & new_unittest("es-as-fortran-write", test_es_text), &
            & new_unittest("numbers-under-a-decimal-comma-locale", test_comma_locale), &
            & new_unittest("check-fails-on-nan", test_nan_fails, should_fail=.true.)]
    end subroutine collect_text

    subroutine test_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: values(5), back
        character(len=:), allocatable :: text
        integer :: i

        values = [0.1_wp, -2.5_wp, 1.0e-300_wp, 7800.0_wp, 1.0_wp/3.0_wp]
        do i = 1, size(values)
            text = to_text(values(i))
            read(text, *) back
            call check(error, back == values(i), &
                & "to_text does not read back: " // to_text(values(i)))
            if (allocated(error)) return
        end do
        call check(error, to_text(0.1_wp) == "0.1" .and. to_text(-2.5_wp) == "-2.5" &
            & .and. to_text(7800.0_wp) == "7800" .and. to_text(1.0e-300_wp) == "1e-300" &
            & .and. to_text(0.04_wp) == "0.04" .and. to_text(-1.5e20_wp) == "-1.5e20", &
            & "0.1, -2.5, 7800, 1e-300, 0.04, -1.5e20 print as " // to_text(0.1_wp) // ", " &
            & // to_text(-2.5_wp) // ", " // to_text(7800.0_wp) // ", " // to_text(1.0e-300_wp) &
            & // ", " // to_text(0.04_wp) // ", " // to_text(-1.5e20_wp))
    end subroutine test_round_trip

    subroutine test_special(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, to_text(-42) == "-42", "integer text")
        if (allocated(error)) return
        ! Row counts pass 2**31: printed whole, not wrapped round.
        call check(error, to_text(1000000000000001_int64) == "1000000000000001", &
            & "64-bit integer text: " // to_text(1000000000000001_int64))
        if (allocated(error)) return
        call check(error, to_text(ieee_value(1.0_wp, ieee_quiet_nan)) == "NaN", "NaN text")
    end subroutine test_special

    !> to_text of an integer (made digit by digit) must be what Fortran's i0 writes: zero, both
    !> extremes of both kinds, every power of 10 and its neighbours, both signs, and random
    !> values of every length.
    subroutine test_integers_as_i0(error)
        type(error_type), allocatable, intent(out) :: error
        integer(int64) :: state, power
        integer :: i, k

        call compare_long(0_int64)
        call compare_long(huge(0_int64))
        call compare_long(-huge(0_int64) - 1_int64)
        call compare_default(huge(0))
        call compare_default(-huge(0) - 1)
        if (allocated(error)) return
        power = 1_int64
        do k = 0, 18
            do i = -1, 1
                call compare_long(power + i)
                call compare_long(-power - i)
                if (power + i <= huge(0)) call compare_default(int(power + i))
                if (power + i <= huge(0)) call compare_default(-int(power + i))
            end do
            if (allocated(error)) return
            if (k < 18) power = power * 10_int64
        end do
        state = 88172645463325252_int64
        do i = 1, 2000
            state = ieor(state, ishft(state, 13))
            state = ieor(state, ishft(state, -7))
            state = ieor(state, ishft(state, 17))
            call compare_long(ishft(state, -mod(i, 64)))
            call compare_default(int(ishft(state, -33 - mod(i, 31))) * merge(-1, 1, mod(i, 2) == 1))
            if (allocated(error)) return
        end do

    contains

        subroutine compare_long(value)
            integer(int64), intent(in) :: value
            character(len=24) :: buffer

            if (allocated(error)) return
            write(buffer, '(i0)') value
            call check(error, to_text(value) == trim(buffer), "to_text(" // trim(buffer) &
                & // ") gives " // to_text(value))
        end subroutine compare_long

        subroutine compare_default(value)
            integer, intent(in) :: value
            character(len=24) :: buffer

            if (allocated(error)) return
            write(buffer, '(i0)') value
            call check(error, to_text(value) == trim(buffer), "to_text(" // trim(buffer) &
                & // ") gives " // to_text(value))
        end subroutine compare_default
    end subroutine test_integers_as_i0

    !> es_text (digits from C) must be character for character what Fortran's write with
    !> es<w>.<d>e3 writes, for the summary's three formats and a field too narrow for a sign
    !> (asterisks): random bit patterns of both signs, subnormals, zeros of both signs, values
    !> that round up to the next power of 10 (9.9995 -> 1.000E+001), every power of 10 and its
    !> neighbours, the extremes, NaN and both infinities.
    subroutine test_es_text(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: widths(4) = [23, 11, 10, 9], decimals(4) = [15, 3, 3, 3]
        integer(int64) :: state
        character(len=40) :: buffer
        real(wp) :: x
        integer :: i, k

        call compare(0.0_wp)
        call compare(-0.0_wp)
        call compare(huge(x))
        call compare(-huge(x))
        call compare(tiny(x))
        call compare(ieee_value(x, ieee_quiet_nan))
        call compare(ieee_value(x, ieee_positive_inf))
        call compare(ieee_value(x, ieee_negative_inf))
        call compare(9.9995_wp)
        call compare(-9.99949999_wp)
        call compare(0.99999999999999999_wp)
        if (allocated(error)) return
        state = 88172645463325252_int64
        do i = 1, 5000
            state = ieor(state, ishft(state, 13))
            state = ieor(state, ishft(state, -7))
            state = ieor(state, ishft(state, 17))
            x = transfer(state, x)
            call compare(x)
            x = transfer(ishft(state, -12), x)
            call compare(x)
            if (allocated(error)) return
        end do
        do k = -323, 308
            write(buffer, '("9.9995e", i0)') k
            read(buffer, *) x
            call compare(x)
            call compare(ieee_next_after(x, 0.0_wp))
            write(buffer, '("1e", i0)') k
            read(buffer, *) x
            call compare(x)
            call compare(ieee_next_after(x, 0.0_wp))
            call compare(-ieee_next_after(x, huge(x)))
            if (allocated(error)) return
        end do

    contains

        subroutine compare(value)
            real(wp), intent(in) :: value
            character(len=40) :: expected
            character(len=16) :: form
            integer :: j

            do j = 1, size(widths)
                write(form, '("(es", i0, ".", i0, "e3)")') widths(j), decimals(j)
                write(expected, form) value
                call check(error, es_text(value, widths(j), decimals(j)) &
                    & == expected(:widths(j)), trim(form) // " writes '" // expected(:widths(j)) &
                    & // "', es_text gives '" // es_text(value, widths(j), decimals(j)) // "'")
                if (allocated(error)) return
            end do
        end subroutine compare
    end subroutine test_es_text

    !> decimal_value (strtod, in C) must give the double Fortran's list-directed read gives, bit
    !> for bit, for every form a dataset's number takes: signs, no digits before or after the
    !> point, long significands (past 17 digits: rounding decided far down), E and D exponents
    !> with and without sign, long and out-of-range exponents (Infinity, 0, subnormals), and
    !> halfway cases at the bottom and top of the range; and it must refuse what is not one
    !> number.
    subroutine test_decimal_value(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: not_decimal(*) = [character(len=12) :: "inf", &
            & "-Infinity", "nan", "NAN(1)", "0x10", "0x1p3", "1.5e3f"]
        character(len=*), parameter :: edges(*) = [character(len=40) :: "1E400", "1E-400", &
            & "1D-320", "0.0", "-0", "5.", ".5", "+.5E3", "  2.5 ", "4.9406564584124654E-324", &
            & "2.4703282292062328E-324", "2.4703282292062329E-324", "1.7976931348623159E308", &
            & "1.797693134862315807E308", "-1.7976931348623158E+308", "9007199254740993", &
            & "0.1000000000000000055511151231257827", "1e0000000000000000000000000000001"]
        integer(int64) :: state
        character(len=:), allocatable :: text
        real(wp) :: value
        logical :: ok
        integer :: i, k, digits

        do i = 1, size(edges)
            call compare(edges(i))
            if (allocated(error)) return
        end do
        state = 88172645463325252_int64
        do i = 1, 20000
            text = ""
            if (draw(3) == 0) text = "-"
            if (draw(5) == 0 .and. len(text) == 0) text = "+"
            digits = draw(25)
            if (draw(10) == 0) digits = 40 + draw(30)
            do k = 1, digits
                text = text // achar(iachar("0") + draw(10))
            end do
            if (draw(2) == 0) then
                text = text // "."
                digits = draw(20)
                if (draw(10) == 0) digits = 30 + draw(40)
                do k = 1, digits
                    text = text // achar(iachar("0") + draw(10))
                end do
            end if
            if (verify(text, "+-.") == 0) text = text // "7"
            if (draw(2) == 0) then
                text = text // merge("E", "D", draw(2) == 0)
                k = draw(4)
                if (k == 0) text = text // "-"
                if (k == 1) text = text // "+"
                digits = 1 + draw(3)
                if (draw(20) == 0) digits = 5 + draw(20)
                do k = 1, digits
                    text = text // achar(iachar("0") + draw(10))
                end do
            end if
            call compare(text)
            if (allocated(error)) return
        end do
        ! not one number: refused
        call decimal_value("1.5 2", value, ok)
        call check(error, .not. ok, "'1.5 2' taken as one number")
        if (allocated(error)) return
        call decimal_value("1.5E", value, ok)
        call check(error, .not. ok, "'1.5E' taken as a number")
        if (allocated(error)) return
        call decimal_value("  ", value, ok)
        call check(error, .not. ok, "blanks taken as a number")
        if (allocated(error)) return
        ! what strtod takes and a number's digits, signs, point and exponent letter do not hold
        do k = 1, size(not_decimal)
            call decimal_value(trim(not_decimal(k)), value, ok)
            call check(error, .not. ok, "'" // trim(not_decimal(k)) // "' taken as a number")
            if (allocated(error)) return
        end do

    contains

        !> 0 to n - 1 from a 64-bit xorshift sequence: the same texts every run.
        integer function draw(n)
            integer, intent(in) :: n

            state = ieor(state, ishft(state, 13))
            state = ieor(state, ishft(state, -7))
            state = ieor(state, ishft(state, 17))
            draw = int(modulo(state, int(n, int64)))
        end function draw

        subroutine compare(number)
            character(len=*), intent(in) :: number
            real(wp) :: expected
            integer :: stat

            read(number, *, iostat=stat) expected
            call decimal_value(number, value, ok)
            call check(error, stat == 0 .and. ok, "'" // number // "' not read")
            if (allocated(error)) return
            call check(error, transfer(value, 0_int64) == transfer(expected, 0_int64), "'" &
                & // number // "' read as " // to_text(value) // ", Fortran's read gives " &
                & // to_text(expected))
        end subroutine compare
    end subroutine test_decimal_value

    !> A program using the library may set a locale whose decimal mark is a comma (German);
    !> snprintf and strtod follow it, Fortran's I/O does not. Under de_DE (compiled by localedef
    !> into build/locales, found through LOCPATH) to_text, es_text and decimal_value must give
    !> what they give under "C": "1.5", a point in the ES field, "2.25" read whole. Without the
    !> C code's own "C" locale, to_text(1.5) is "15" and "2.25" is not read. The process's
    !> locale is "C" again at the end. Skipped when localedef or de_DE's sources are missing.
    subroutine test_comma_locale(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: folder = "build/locales"
        character(kind=c_char) :: here(4096)
        character(len=:), allocatable :: folder_path
        type(lconv_head), pointer :: conventions
        character(kind=c_char), pointer :: mark
        character(len=:), allocatable :: field
        real(wp) :: value
        logical :: ok
        integer :: status

        call execute_command_line("mkdir -p " // folder // " && (test -d " // folder &
            & // "/de_DE.UTF-8 || localedef -i de_DE -f UTF-8 " // folder // "/de_DE.UTF-8)" &
            & // " > " // folder // ".log 2>&1", exitstat=status)
        if (status /= 0) then
            call skip_test(error, "cannot compile the de_DE locale (localedef, the locales " &
                & // "package's sources)")
            return
        end if
        if (.not. c_associated(c_getcwd(here, size(here, kind=c_size_t)))) then
            call skip_test(error, "getcwd failed")
            return
        end if
        folder_path = ""
        do status = 1, size(here)
            if (here(status) == c_null_char) exit
            folder_path = folder_path // here(status)
        end do
        folder_path = folder_path // "/" // folder
        if (setenv("LOCPATH" // c_null_char, folder_path // c_null_char, &
            & 1_c_int) /= 0 .or. .not. c_associated(setlocale(lc_all, "de_DE.UTF-8" &
            & // c_null_char))) then
            call skip_test(error, "the de_DE locale compiled in " // folder_path &
                & // " does not load")
            return
        end if
        call c_f_pointer(localeconv(), conventions)
        call c_f_pointer(conventions%decimal_point, mark)
        call check(error, mark == ",", "de_DE's decimal mark is a comma, got " // mark)
        if (.not. allocated(error)) then
            call check(error, to_text(1.5_wp) == "1.5" .and. to_text(-0.1_wp) == "-0.1" &
                & .and. to_text(6.02214076e23_wp) == "6.02214076e23", "to_text under de_DE: " &
                & // to_text(1.5_wp) // ", " // to_text(-0.1_wp) // ", " &
                & // to_text(6.02214076e23_wp))
        end if
        if (.not. allocated(error)) then
            field = es_text(1.25_wp, 23, 15)
            call check(error, field == " 1.250000000000000E+000", "es_text under de_DE: '" &
                & // field // "'")
        end if
        if (.not. allocated(error)) then
            call decimal_value("2.25", value, ok)
            call check(error, ok .and. value == 2.25_wp, "decimal_value('2.25') under de_DE: " &
                & // merge("read    ", "not read", ok) // " " // to_text(value))
        end if
        if (.not. c_associated(setlocale(lc_all, "C" // c_null_char))) then
            if (.not. allocated(error)) call check(error, .false., "the C locale back")
        end if
    end subroutine test_comma_locale

    !> to_text finds its digits in C (rollcon_real_text.c); they must be those of the search by
    !> Fortran's formatted I/O it replaced (reference_text, written here as it was), character
    !> for character, over 19,000 numbers: random bit patterns (both signs), subnormals, every
    !> power of 2 and of 10 with both neighbours, short decimals and their neighbours, the
    !> extremes and integers. Exact: a single digit that differs fails.
    subroutine test_fortran_io_digits(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=40) :: buffer
        integer(int64) :: state, bits
        real(wp) :: x
        integer :: i, k, checked

        state = 88172645463325252_int64
        checked = 0
        ! random bit patterns: every sign, exponent and significand (non-finite ones skipped)
        do i = 1, 6000
            bits = next_bits(state)
            x = transfer(bits, x)
            if (.not. ieee_is_finite(x)) cycle
            call compare(x)
            if (allocated(error)) return
        end do
        ! subnormals: random significands with a zero exponent field, and the two ends
        do i = 1, 1000
            bits = iand(next_bits(state), 4503599627370495_int64)
            if (i == 1) bits = 1_int64
            if (i == 2) bits = 4503599627370495_int64
            if (bits == 0_int64) cycle
            x = transfer(bits, x)
            if (mod(i, 2) == 0) x = -x
            call compare(x)
            if (allocated(error)) return
        end do
        ! every power of 2, with the doubles either side
        do k = -1074, 1023
            call compare_with_neighbours(2.0_wp**k)
            if (allocated(error)) return
        end do
        ! every power of 10 (as read from "1e<k>"), with the doubles either side
        do k = -323, 308
            write(buffer, '("1e", i0)') k
            read(buffer, *) x
            call compare_with_neighbours(x)
            if (allocated(error)) return
        end do
        ! short decimals d.ddd 10^k (0.1, 2.5e-7, ...), with the doubles either side
        do i = 1, 1500
            write(buffer, '(i0, "e", i0)') 1 + modulo(next_bits(state), 999999_int64), &
                & int(modulo(next_bits(state), 81_int64)) - 40
            read(buffer, *) x
            call compare_with_neighbours(x)
            if (allocated(error)) return
        end do
        ! extremes, and integers: small ones, round ones, random ones up to 2^63
        call compare_with_neighbours(huge(x))
        call compare_with_neighbours(tiny(x))
        call compare_with_neighbours(epsilon(x))
        do i = 1, 1000
            call compare(real(i, wp))
            call compare(-real(i * 1000, wp))
            call compare(real(ishft(next_bits(state), -int(modulo(next_bits(state), 64_int64))), &
                & wp))
            if (allocated(error)) return
        end do
        call check(error, checked > 19000, "too few numbers compared: " // to_text(checked))

    contains

        !> Next 64 bits of a xorshift sequence (Marsaglia): the same numbers every run.
        function next_bits(s) result(b)
            integer(int64), intent(inout) :: s
            integer(int64) :: b

            s = ieor(s, ishft(s, 13))
            s = ieor(s, ishft(s, -7))
            s = ieor(s, ishft(s, 17))
            b = s
        end function next_bits

        subroutine compare_with_neighbours(value)
            real(wp), intent(in) :: value

            call compare(value)
            if (allocated(error)) return
            call compare(ieee_next_after(value, -huge(value)))
            if (allocated(error)) return
            call compare(ieee_next_after(value, huge(value)))
        end subroutine compare_with_neighbours

        subroutine compare(value)
            real(wp), intent(in) :: value
            character(len=:), allocatable :: text, expected

            text = to_text(value)
            expected = reference_text(value)
            checked = checked + 1
            call check(error, text == expected, "to_text(" // expected // ") gives " // text)
        end subroutine compare
    end subroutine test_fortran_io_digits

    !> real_to_text as it was (before rollcon_real_text.c), for a finite value: the fewest digits
    !> written by es40.(d-1)e3 that a list-directed read reads back as value, laid out as
    !> to_text does.
    function reference_text(value) result(text)
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=40) :: buffer
        character(len=16) :: form
        character(len=:), allocatable :: digits_text, sign
        real(wp) :: back
        integer :: digits, stat, exponent, e

        if (value == 0.0_wp) then
            text = "0"
            return
        end if
        do digits = 1, 17
            write(form, '("(es40.", i0, "e3)")') digits - 1
            write(buffer, form) value
            read(buffer, *, iostat=stat) back
            if (stat == 0 .and. back == value) exit
        end do
        buffer = adjustl(buffer)
        sign = ""
        if (buffer(1:1) == "-") then
            sign = "-"
            buffer = buffer(2:)
        end if
        e = scan(buffer, "Ee")
        read(buffer(e + 1:), *) exponent
        digits_text = buffer(1:1) // buffer(3:e - 1)
        if (e == 2) digits_text = buffer(1:1)
        do while (len(digits_text) > 1 .and. digits_text(len(digits_text):) == "0")
            digits_text = digits_text(:len(digits_text) - 1)
        end do
        if (exponent >= -5 .and. exponent < 15) then
            if (exponent < 0) then
                text = sign // "0." // repeat("0", -exponent - 1) // digits_text
            else if (len(digits_text) > exponent + 1) then
                text = sign // digits_text(:exponent + 1) // "." // digits_text(exponent + 2:)
            else
                text = sign // digits_text // repeat("0", exponent + 1 - len(digits_text))
            end if
        else
            text = sign // digits_text(1:1)
            if (len(digits_text) > 1) text = text // "." // digits_text(2:)
            write(buffer, '(i0)') exponent
            text = text // "e" // trim(buffer)
        end if
    end function reference_text

    !> The harness must reject NaN even with an infinite tolerance.
    subroutine test_nan_fails(error)
        type(error_type), allocatable, intent(out) :: error

        call check(error, ieee_value(1.0_wp, ieee_quiet_nan), 0.0_wp, "NaN", abs_tol=huge(1.0_wp))
    end subroutine test_nan_fails

end module test_text
