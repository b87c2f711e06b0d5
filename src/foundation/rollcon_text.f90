! SPDX-License-Identifier: MIT
!> Short decimal text of numbers, for messages and tables; ASCII case of names.
module rollcon_text
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: iso_c_binding, only : c_double, c_char, c_int
    use rollcon_kinds, only : wp
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_is_nan
    implicit none
    private

    public :: to_text, fixed_text, single_quoted, shell_quote, lower_case, upper_case, unquoted
    public :: comma_list, number_list
    public :: place, decimal_value, es_text

    !> Decimal text of an integer or a real
    interface to_text
        module procedure :: integer_to_text
        module procedure :: long_to_text
        module procedure :: real_to_text
    end interface to_text

    !> The numbers, real or integer, as to_text writes them, separated by ", "
    interface number_list
        module procedure real_list, integer_list
    end interface number_list

    interface
        !> The fewest significant digits (1 to 17) of the finite, nonzero |value| that read back
        !> as it, written by snprintf's "%.*e" and read by strtod as libgfortran's es format and
        !> list-directed read do: the digits (no point, no sign) into digits, the decimal
        !> exponent of the first into exponent, their number into count (rollcon_real_text.c).
        pure subroutine c_shortest_digits(value, digits, exponent, count) &
                & bind(c, name="rollcon_shortest_digits")
            import :: c_double, c_char, c_int
            real(c_double), value :: value
            character(kind=c_char), intent(out) :: digits(17)
            integer(c_int), intent(out) :: exponent, count
        end subroutine c_shortest_digits

        !> The double of a decimal text by strtod, D taken as E (rollcon_real_text.c): read_all
        !> is 1 when every character was read.
        subroutine c_decimal_value(text, length, value, read_all) &
                & bind(c, name="rollcon_decimal_value")
            import :: c_double, c_char, c_int
            character(kind=c_char), intent(in) :: text(*)
            integer(c_int), value :: length
            real(c_double), intent(out) :: value
            integer(c_int), intent(out) :: read_all
        end subroutine c_decimal_value

        !> A finite value as Fortran's ES with decimals digits after the point and a
        !> three-digit exponent writes it, blanks before left out (rollcon_real_text.c).
        pure subroutine c_es_compact(value, decimals, text, length) &
                & bind(c, name="rollcon_es_compact")
            import :: c_double, c_char, c_int
            real(c_double), value :: value
            integer(c_int), value :: decimals
            character(kind=c_char), intent(out) :: text(*)
            integer(c_int), intent(out) :: length
        end subroutine c_es_compact
    end interface

contains

    !> Shortest decimal text of an integer.
    pure function integer_to_text(value) result(text)
        !> Value to print
        integer, intent(in) :: value
        character(len=:), allocatable :: text

        text = long_to_text(int(value, int64))
    end function integer_to_text

    !> Shortest decimal text of a 64-bit integer (row and byte counts): the characters of
    !> Fortran's i0 edit descriptor, made digit by digit (a formatted write costs some 4,000
    !> instructions; messages and names are made from hundreds of integers).
    pure function long_to_text(value) result(text)
        !> Value to print
        integer(int64), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=20) :: buffer
        integer(int64) :: rest
        integer :: first

        ! digits from the last, of the value made negative: -huge - 1 has no positive
        if (value < 0_int64) then
            rest = value
        else
            rest = -value
        end if
        first = len(buffer) + 1
        do
            first = first - 1
            buffer(first:first) = achar(iachar("0") - int(mod(rest, 10_int64)))
            rest = rest / 10_int64
            if (rest == 0_int64) exit
        end do
        if (value < 0_int64) then
            text = "-" // buffer(first:)
        else
            text = buffer(first:)
        end if
    end function long_to_text

    !> Shortest decimal text that reads back as the same real (at most 17 digits): plain
    !> notation for 1e-5 <= |value| < 1e15 ("0.1", "-2.5", "7800"), else "1.5e-300". The
    !> digits are the fewest that Fortran's es format writes and a list-directed read reads
    !> back as value (found in C: rollcon_real_text.c).
    pure function real_to_text(value) result(text)
        !> Value to print
        real(wp), intent(in) :: value
        character(len=:), allocatable :: text
        character(len=17) :: digits
        character(len=:), allocatable :: digits_text, sign
        integer :: count, exponent

        if (ieee_is_nan(value)) then
            text = "NaN"
            return
        else if (.not. ieee_is_finite(value)) then
            text = merge("+Infinity", "-Infinity", value > 0.0_wp)
            return
        else if (value == 0.0_wp) then
            text = "0"
            return
        end if
        call c_shortest_digits(value, digits, exponent, count)
        sign = ""
        if (value < 0.0_wp) sign = "-"
        ! trailing zeros removed
        do while (count > 1 .and. digits(count:count) == "0")
            count = count - 1
        end do
        digits_text = digits(:count)
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
            text = text // "e" // integer_to_text(exponent)
        end if
    end function real_to_text

    !> A real with a fixed number of decimals and a digit before the point: 0.571925, -0.5.
    pure function fixed_text(value, decimals) result(text)
        real(wp), intent(in) :: value
        !> Digits after the point
        integer, intent(in) :: decimals
        character(len=:), allocatable :: text
        character(len=64) :: buffer
        character(len=16) :: form

        write(form, '("(f0.", i0, ")")') decimals
        write(buffer, form) value
        text = trim(adjustl(buffer))
        if (text(1:1) == ".") then
            text = "0" // text
        else if (text(1:min(2, len(text))) == "-.") then
            text = "-0" // text(2:)
        end if
    end function fixed_text

    !> text between single quotes, each quote inside written as escape: "'\''" for a POSIX
    !> shell, "''" for gnuplot.
    pure function single_quoted(text, escape) result(word)
        !> Text to quote
        character(len=*), intent(in) :: text
        !> What stands for a single quote inside
        character(len=*), intent(in) :: escape
        character(len=:), allocatable :: word
        integer :: i

        word = "'"
        do i = 1, len(text)
            if (text(i:i) == "'") then
                word = word // escape
            else
                word = word // text(i:i)
            end if
        end do
        word = word // "'"
    end function single_quoted

    !> text as one word for a POSIX shell (single quotes, a quote inside written as '\'').
    pure function shell_quote(text) result(word)
        !> Text to quote
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: word

        word = single_quoted(text, "'\''")
    end function shell_quote

    !> text with A-Z turned to a-z (ASCII).
    pure function lower_case(text) result(lower)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: lower
        integer :: i, code

        lower = text
        do i = 1, len(text)
            code = iachar(text(i:i))
            if (code >= iachar("A") .and. code <= iachar("Z")) lower(i:i) = achar(code + 32)
        end do
    end function lower_case

    !> text with a-z turned to A-Z (ASCII).
    pure function upper_case(text) result(upper)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: upper
        integer :: i, code

        upper = text
        do i = 1, len(text)
            code = iachar(text(i:i))
            if (code >= iachar("a") .and. code <= iachar("z")) upper(i:i) = achar(code - 32)
        end do
    end function upper_case

    !> A namelist value without its enclosing quotes (single or double), as it was written.
    pure function unquoted(value) result(text)
        character(len=*), intent(in) :: value
        character(len=:), allocatable :: text

        text = value
        if (len(text) >= 2) then
            if (scan(text(1:1), "'""") > 0 .and. text(len(text):) == text(1:1)) &
                & text = text(2:len(text) - 1)
        end if
    end function unquoted

    !> The words, trimmed, separated by ", " (for messages that list what is allowed).
    pure function comma_list(words) result(text)
        character(len=*), intent(in) :: words(:)
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, size(words)
            if (k > 1) text = text // ", "
            text = text // trim(words(k))
        end do
    end function comma_list

    !> The numbers as to_text writes them, separated by ", " (for messages that quote values).
    function real_list(values) result(text)
        real(wp), intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, size(values)
            if (k > 1) text = text // ", "
            text = text // to_text(values(k))
        end do
    end function real_list

    !> Whole numbers as to_text writes them, separated by ", " ("20, 2").
    function integer_list(values) result(text)
        integer, intent(in) :: values(:)
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, size(values)
            if (k > 1) text = text // ", "
            text = text // to_text(values(k))
        end do
    end function integer_list

    !> value as Fortran's write with the edit descriptor es<width>.<decimals>e3 writes it: width
    !> characters, blanks before; width asterisks when it needs more. A finite value's digits
    !> come from C (rollcon_real_text.c: snprintf, as libgfortran makes them), without the
    !> formatted write's cost (some 10,000 instructions); NaN and infinities by the write.
    pure function es_text(value, width, decimals) result(field)
        !> Value to write
        real(wp), intent(in) :: value
        !> Characters of the field, and digits after the point (0 to 40)
        integer, intent(in) :: width, decimals
        character(len=width) :: field
        character(len=64) :: compact
        character(len=24) :: form
        integer :: length

        if (.not. ieee_is_finite(value) .or. decimals < 0 .or. decimals > 40) then
            write(form, '("(es", i0, ".", i0, "e3)")') width, decimals
            write(field, form) value
            return
        end if
        call c_es_compact(value, decimals, compact, length)
        if (length > width) then
            field = repeat("*", width)
        else
            field = repeat(" ", width - length) // compact(:length)
        end if
    end function es_text

    !> The real a decimal text stands for ("-1.5", "2.5E-3", "7.", ".5", "1D3"), the double
    !> that Fortran's list-directed read gives for it (libgfortran reads a real by strtod, as
    !> this does: rollcon_real_text.c); blanks around it are ignored. ok is false when the text
    !> is not one number as a whole, or holds a character other than digits, signs, a point
    !> and an exponent letter (strtod alone also takes "inf", "nan" and hexadecimal "0x1p3").
    !> Out of range: +-Infinity or 0, as the read gives.
    subroutine decimal_value(text, value, ok)
        !> Digits with an optional sign, point and exponent (letter E or D)
        character(len=*), intent(in) :: text
        real(wp), intent(out) :: value
        logical, intent(out) :: ok
        integer :: first, last, read_all

        first = verify(text, " ")
        last = len_trim(text)
        value = 0.0_wp
        ok = .false.
        if (first == 0) return
        if (verify(text(first:last), "0123456789+-.EeDd") /= 0) return
        call c_decimal_value(text(first:last), last - first + 1, value, read_all)
        ok = read_all == 1
    end subroutine decimal_value

    !> Where a statement of an input file stands, as messages begin: "data/coin.adm:12".
    pure function place(path, line) result(text)
        character(len=*), intent(in) :: path
        integer, intent(in) :: line
        character(len=:), allocatable :: text

        text = path // ":" // to_text(line)
    end function place

end module rollcon_text
