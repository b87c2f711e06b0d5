! SPDX-License-Identifier: MIT
!> Seeded mutations of a scene file's lines for the fuzz test: bytes flipped, lines cut,
!> duplicated, swapped or dropped, numbers replaced by extremes.
module scene_mutations
    use rollcon_kinds, only : wp
    use rollcon_namelist_lexer, only : line_type
    implicit none
    private

    public :: mutate

    !> Numbers that break readers: overflow, underflow, denormals, signed zero, not-a-number,
    !> and very long mantissas
    character(len=*), parameter :: extremes(*) = [character(len=24) :: "1e308", "-1e308", &
        & "1.7976931348623157e308", "1e-320", "4.9e-324", "-1e-320", "0", "-0", "0.0", "NaN", &
        & "-NaN", "Infinity", "-Infinity", "Inf", "1e400", "-1e400", "1e-400", "1e200", "1e6", &
        & "-1e6", "1e9", "1d5", "1.0+5", "+.5e-3"]

contains

    !> Apply one to three random mutations to lines (the generator must be seeded).
    subroutine mutate(lines)
        type(line_type), allocatable, intent(inout) :: lines(:)
        integer :: count, k

        count = 1 + draw(3)
        do k = 1, count
            if (size(lines) == 0) return
            select case (draw(7))
            case (0)
                call flip_byte(lines)
            case (1)
                call cut_line(lines)
            case (2)
                lines = [lines, lines(1 + draw(size(lines)))]
                call swap_lines(lines, size(lines), 1 + draw(size(lines)))
            case (3)
                call swap_lines(lines, 1 + draw(size(lines)), 1 + draw(size(lines)))
            case (4)
                call drop_line(lines, 1 + draw(size(lines)))
            case default
                call replace_number(lines)
            end select
        end do
    end subroutine mutate

    !> A random integer in [0, n).
    integer function draw(n)
        integer, intent(in) :: n
        real(wp) :: u

        call random_number(u)
        draw = min(int(u*n), n - 1)
    end function draw

    !> One byte of a random line set to a random value (any of 0..255).
    subroutine flip_byte(lines)
        type(line_type), intent(inout) :: lines(:)
        integer :: i, j

        i = 1 + draw(size(lines))
        if (len(lines(i)%text) == 0) then
            lines(i)%text = achar(draw(256))
            return
        end if
        j = 1 + draw(len(lines(i)%text))
        lines(i)%text(j:j) = achar(draw(256))
    end subroutine flip_byte

    !> A random line cut at a random place.
    subroutine cut_line(lines)
        type(line_type), intent(inout) :: lines(:)
        integer :: i

        i = 1 + draw(size(lines))
        lines(i)%text = lines(i)%text(:draw(len(lines(i)%text) + 1))
    end subroutine cut_line

    subroutine swap_lines(lines, i, j)
        type(line_type), intent(inout) :: lines(:)
        integer, intent(in) :: i, j
        type(line_type) :: kept

        kept = lines(i)
        lines(i) = lines(j)
        lines(j) = kept
    end subroutine swap_lines

    subroutine drop_line(lines, i)
        type(line_type), allocatable, intent(inout) :: lines(:)
        integer, intent(in) :: i

        lines = [lines(:i - 1), lines(i + 1:)]
    end subroutine drop_line

    !> The first number at or after a random place of a random line, replaced by an extreme
    !> or by a number of several hundred digits.
    subroutine replace_number(lines)
        type(line_type), intent(inout) :: lines(:)
        character(len=:), allocatable :: number, text
        integer :: i, j, k, start, tries

        do tries = 1, 8
            i = 1 + draw(size(lines))
            text = lines(i)%text
            start = 1 + draw(len(text) + 1)
            j = scan(text(start:), "0123456789")
            if (j > 0) then
                j = j + start - 1
            else
                j = scan(text, "0123456789")
            end if
            if (j == 0) cycle
            k = j
            do while (k < len(text))
                if (scan(text(k + 1:k + 1), "0123456789.eEdD+-") == 0) exit
                k = k + 1
            end do
            select case (draw(4))
            case (0)
                number = "1." // repeat("0", 300 + draw(400)) // "1"
            case (1)
                number = repeat("9", 300 + draw(20)) // ".5"
            case default
                number = trim(extremes(1 + draw(size(extremes))))
            end select
            lines(i)%text = text(:j - 1) // number // text(k + 1:)
            return
        end do
    end subroutine replace_number

end module scene_mutations
