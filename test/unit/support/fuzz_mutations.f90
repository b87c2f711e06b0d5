! SPDX-License-Identifier: MIT
!> Seeded mutations of texts and of files' lines for the fuzz suites of the readers (datasets,
!> function expressions, studies, `--ucon` statements): characters deleted, doubled, swapped or
!> set to any byte (NUL and non-ASCII included), UTF-8 characters and byte-order marks put in,
!> numbers replaced by extremes, specials and garbage, words cut short or doubled, parentheses
!> unbalanced, lines made very long; lines deleted, doubled, swapped, joined or cut off. The
!> mutations draw from the compiler's generator: seed_fuzz makes a run reproducible.
module fuzz_mutations
    use rollcon_kinds, only : wp
    use rollcon_namelist_lexer, only : line_type
    implicit none
    private

    public :: seed_fuzz, draw, mutate_text, mutate_lines, write_lines, printable, extremes

    !> Numbers that break readers: overflow, underflow, subnormals, signed zero, not-a-number,
    !> infinities, integers beyond 32 bits, and texts that are almost numbers
    character(len=*), parameter :: extremes(*) = [character(len=24) :: "1e308", "-1e308", &
        & "1.7976931348623157e308", "1.8e308", "1e309", "-1e400", "1e99999", "1e-320", &
        & "4.9e-324", "1e-400", "0", "-0", "0.0", "NaN", "nan", "-NaN", "Inf", "-Infinity", &
        & "infinity", "1d300", "1D308", "1D", "90D", "1e", "1e+", ".", "-", "+", "1.2.3", &
        & "0x1p3", "2*3", "1e9", "-1e9", "999999999", "2147483647", "2147483648", &
        & "-2147483649", "99999999999999999999", "1.0+5", "T", ".true.", "1/2", "1;2", "1 2", &
        & "", " ", "+.5e-3", "1e6", "-1", "1e-9", "1E+00000000000000000003"]
    !> Characters that mean something to one reader or another
    character(len=*), parameter :: punctuation = ",=/!\:()*-+.;'""&%@ DdEe" // achar(9)
    !> Non-ASCII texts: a byte-order mark, a no-break space, e acute, theta, an emoji, a lone
    !> continuation byte, a truncated sequence
    character(len=*), parameter :: utf8(7) = [character(len=4) :: achar(239) // achar(187) &
        & // achar(191), achar(194) // achar(160), achar(195) // achar(169), achar(206) &
        & // achar(184), achar(240) // achar(159) // achar(152) // achar(128), achar(128), &
        & achar(226) // achar(130)]

contains

    !> Seed the compiler's generator: the same mutations on every run.
    subroutine seed_fuzz(seed)
        integer, intent(in) :: seed
        integer, allocatable :: values(:)
        integer :: n, k

        call random_seed(size=n)
        allocate(values(n))
        values = seed + [(37*k, k = 1, n)]
        call random_seed(put=values)
    end subroutine seed_fuzz

    !> A random integer in [0, n).
    integer function draw(n)
        integer, intent(in) :: n
        real(wp) :: u

        call random_number(u)
        draw = min(int(u*n), n - 1)
    end function draw

    !> One to three random mutations of lines (the lines of a file); words are what may be
    !> inserted as a whole (the reader's keywords, names, functions).
    subroutine mutate_lines(lines, words)
        type(line_type), allocatable, intent(inout) :: lines(:)
        character(len=*), intent(in) :: words(:)
        type(line_type) :: kept
        integer :: count, k, i, j

        count = 1 + draw(3)
        do k = 1, count
            if (size(lines) == 0) then
                lines = [line_type("")]
            end if
            i = 1 + draw(size(lines))
            j = 1 + draw(size(lines))
            select case (draw(12))
            case (0)
                lines = [lines(:i - 1), lines(i + 1:)]
            case (1)
                lines = [lines(:i), lines(i:)]
            case (2)
                kept = lines(i)
                lines(i) = lines(j)
                lines(j) = kept
            case (3)
                ! a line moved elsewhere
                kept = lines(i)
                lines = [lines(:i - 1), lines(i + 1:)]
                j = 1 + draw(size(lines) + 1)
                lines = [lines(:j - 1), kept, lines(j:)]
            case (4)
                ! the file cut off after a random line
                lines = lines(:i - 1 + draw(2))
            case (5)
                ! two lines joined
                if (i < size(lines)) then
                    lines(i)%text = lines(i)%text // lines(i + 1)%text
                    lines = [lines(:i), lines(i + 2:)]
                end if
            case default
                call mutate_text(lines(i)%text, words)
            end select
        end do
    end subroutine mutate_lines

    !> One random mutation of a text.
    subroutine mutate_text(text, words)
        character(len=:), allocatable, intent(inout) :: text
        !> Words that may be inserted as a whole
        character(len=*), intent(in) :: words(:)
        integer :: i, n, j

        n = len(text)
        i = 1 + draw(n + 1)
        select case (draw(16))
        case (0)
            if (i <= n) text = text(:i - 1) // text(i + 1:)
        case (1)
            if (i <= n) text = text(:i) // text(i:)
        case (2)
            if (i < n) text = text(:i - 1) // text(i + 1:i + 1) // text(i:i) // text(i + 2:)
        case (3, 4)
            ! any byte, NUL and non-ASCII included
            if (i <= n) then
                text(i:i) = achar(draw(256))
            else
                text = text // achar(draw(256))
            end if
        case (5)
            text = text(:i - 1) // trim(utf8(1 + draw(size(utf8)))) // text(i:)
        case (6, 7, 8)
            call replace_number(text)
        case (9)
            call change_word(text)
        case (10)
            j = 1 + draw(len(punctuation))
            text = text(:i - 1) // punctuation(j:j) // text(i:)
        case (11)
            ! a parenthesis more or fewer
            j = scan(text, "()", back=draw(2) == 0)
            if (draw(2) == 0 .and. j > 0) then
                text = text(:j - 1) // text(j + 1:)
            else
                text = text(:i - 1) // merge("(", ")", draw(2) == 0) // text(i:)
            end if
        case (12)
            if (size(words) > 0) text = text(:i - 1) // trim(words(1 + draw(size(words)))) &
                & // text(i:)
        case (13)
            text = text(:i - 1)
        case (14)
            call lengthen(text)
        case default
            text = text(:i - 1) // repeat(" ", draw(5)) // achar(9) // text(i:)
        end select
    end subroutine mutate_text

    !> The first number at or after a random place replaced by an extreme or by a number of
    !> several hundred digits.
    subroutine replace_number(text)
        character(len=:), allocatable, intent(inout) :: text
        character(len=:), allocatable :: number
        integer :: j, k, start

        start = 1 + draw(len(text) + 1)
        j = 0
        if (start <= len(text)) j = scan(text(start:), "0123456789")
        if (j > 0) then
            j = j + start - 1
        else
            j = scan(text, "0123456789")
        end if
        if (j == 0) return
        k = j
        do while (k < len(text))
            if (scan(text(k + 1:k + 1), "0123456789.eEdD+-") == 0) exit
            k = k + 1
        end do
        select case (draw(5))
        case (0)
            number = "1." // repeat("0", 300 + draw(400)) // "1"
        case (1)
            number = repeat("9", 300 + draw(20)) // ".5"
        case default
            number = trim(extremes(1 + draw(size(extremes))))
        end select
        text = text(:j - 1) // number // text(k + 1:)
    end subroutine replace_number

    !> A word (letters, digits, underscores) at a random place cut to a shorter prefix, or
    !> doubled (with or without a separator).
    subroutine change_word(text)
        character(len=:), allocatable, intent(inout) :: text
        character(len=*), parameter :: letters = "ABCDEFGHIJKLMNOPQRSTUVWXYZ" &
            & // "abcdefghijklmnopqrstuvwxyz_"
        integer :: start, finish, j

        j = 1 + draw(len(text) + 1)
        start = 0
        if (j <= len(text)) start = scan(text(j:), letters)
        if (start == 0) then
            start = scan(text, letters)
        else
            start = start + j - 1
        end if
        if (start == 0) return
        finish = start
        do while (finish < len(text))
            if (scan(text(finish + 1:finish + 1), letters // "0123456789") == 0) exit
            finish = finish + 1
        end do
        select case (draw(3))
        case (0)
            text = text(:start + draw(finish - start + 1) - 1) // text(finish + 1:)
        case (1)
            text = text(:finish) // text(start:finish) // text(finish + 1:)
        case default
            text = text(:finish) // merge(", ", "/ ", draw(2) == 0) // text(start:)
        end select
    end subroutine change_word

    !> A text made very long: repeated, padded with blanks, or a run of one character, to
    !> about 4000 to 5000 characters (both sides of 4095, the longest dataset line).
    subroutine lengthen(text)
        character(len=:), allocatable, intent(inout) :: text
        integer :: target_length

        target_length = 4000 + draw(1000)
        select case (draw(3))
        case (0)
            if (len(text) > 0) text = repeat(text, target_length/len(text) + 1)
        case (1)
            text = text // repeat(" ", max(0, target_length - len(text)))
        case default
            text = text // repeat(text(max(1, len(text)):), target_length)
        end select
        text = text(:min(len(text), target_length))
    end subroutine lengthen

    !> Write lines, each ended by a line feed, byte for byte.
    subroutine write_lines(path, lines)
        character(len=*), intent(in) :: path
        type(line_type), intent(in) :: lines(:)
        integer :: unit, i

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="unformatted")
        do i = 1, size(lines)
            write(unit) lines(i)%text // new_line("a")
        end do
        close(unit)
    end subroutine write_lines

    !> True when every character of text is printable ASCII (a message shows nothing raw).
    pure logical function printable(text)
        character(len=*), intent(in) :: text
        integer :: j

        printable = .true.
        do j = 1, len(text)
            if (iachar(text(j:j)) < 32 .or. iachar(text(j:j)) > 126) then
                printable = .false.
                return
            end if
        end do
    end function printable

end module fuzz_mutations
