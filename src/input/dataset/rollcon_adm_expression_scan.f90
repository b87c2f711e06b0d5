! SPDX-License-Identifier: MIT
!> The character-level work of the expression parser (rollcon_adm_expression_parser): where
!> reading stands in the text, names and digits, and the stack program being emitted.
module rollcon_adm_expression_scan
    use rollcon_kinds, only : wp
    use rollcon_expression, only : expression_input_type, op_constant
    implicit none
    private

    public :: parser_type, emit, emit_constant, expect, peek, here, skip_blanks, skip_digits
    public :: read_name, is_digit, is_letter, column_text, exponent_follows

    !> Parser state: the text, where reading stands, the program and inputs emitted so far
    type :: parser_type
        character(len=:), allocatable :: text
        integer :: at = 1
        integer, allocatable :: op(:)
        real(wp), allocatable :: constant(:)
        type(expression_input_type), allocatable :: inputs(:)
        integer :: count = 0, depth = 0, deepest = 0
        !> Levels of nesting open where reading stands (rollcon_adm_expression_parser)
        integer :: nesting = 0
    end type parser_type

contains

    !> After E or D: digits, or a sign and digits, make an exponent.
    pure logical function exponent_follows(p)
        type(parser_type), intent(in) :: p
        integer :: k

        k = p%at + 1
        if (k <= len(p%text)) then
            if (p%text(k:k) == "+" .or. p%text(k:k) == "-") k = k + 1
        end if
        exponent_follows = .false.
        if (k <= len(p%text)) exponent_follows = is_digit(p%text(k:k))
    end function exponent_follows

    subroutine emit_constant(p, value)
        type(parser_type), intent(inout) :: p
        real(wp), intent(in) :: value

        call emit(p, op_constant, 1)
        p%constant(p%count) = value
    end subroutine emit_constant

    !> Append an operation that changes the stack depth by `change`.
    subroutine emit(p, op, change)
        type(parser_type), intent(inout) :: p
        integer, intent(in) :: op, change

        if (p%count == size(p%op)) then
            p%op = [p%op, p%op]
            p%constant = [p%constant, p%constant]
        end if
        p%count = p%count + 1
        p%op(p%count) = op
        p%constant(p%count) = 0.0_wp
        p%depth = p%depth + change
        p%deepest = max(p%deepest, p%depth)
    end subroutine emit

    subroutine expect(p, c, problem)
        type(parser_type), intent(inout) :: p
        character, intent(in) :: c
        character(len=:), allocatable, intent(inout) :: problem

        if (peek(p) == c) then
            p%at = p%at + 1
        else if (p%at > len(p%text)) then
            problem = "'" // c // "' expected at the end"
        else
            problem = "'" // c // "' expected, found '" // p%text(p%at:p%at) // "'"
        end if
    end subroutine expect

    !> The next non-blank character (a blank at the end of the text).
    character function peek(p)
        type(parser_type), intent(inout) :: p

        call skip_blanks(p)
        peek = here(p)
    end function peek

    pure character function here(p)
        type(parser_type), intent(in) :: p

        here = " "
        if (p%at <= len(p%text)) here = p%text(p%at:p%at)
    end function here

    subroutine skip_blanks(p)
        type(parser_type), intent(inout) :: p

        do while (p%at <= len(p%text))
            if (p%text(p%at:p%at) /= " " .and. p%text(p%at:p%at) /= achar(9)) exit
            p%at = p%at + 1
        end do
    end subroutine skip_blanks

    subroutine skip_digits(p)
        type(parser_type), intent(inout) :: p

        do while (p%at <= len(p%text))
            if (.not. is_digit(p%text(p%at:p%at))) exit
            p%at = p%at + 1
        end do
    end subroutine skip_digits

    !> A name (letters, digits, underscores), upper-cased.
    function read_name(p) result(name)
        type(parser_type), intent(inout) :: p
        character(len=:), allocatable :: name
        integer :: first, i

        first = p%at
        do while (p%at <= len(p%text))
            if (.not. (is_letter(p%text(p%at:p%at)) .or. is_digit(p%text(p%at:p%at)) &
                & .or. p%text(p%at:p%at) == "_")) exit
            p%at = p%at + 1
        end do
        name = p%text(first:p%at - 1)
        do i = 1, len(name)
            if (name(i:i) >= "a" .and. name(i:i) <= "z") name(i:i) = achar(iachar(name(i:i)) - 32)
        end do
    end function read_name

    pure logical function is_digit(c)
        character, intent(in) :: c

        is_digit = c >= "0" .and. c <= "9"
    end function is_digit

    pure logical function is_letter(c)
        character, intent(in) :: c

        is_letter = (c >= "A" .and. c <= "Z") .or. (c >= "a" .and. c <= "z")
    end function is_letter

    function column_text(p) result(text)
        type(parser_type), intent(in) :: p
        character(len=:), allocatable :: text
        character(len=12) :: buffer
        integer :: leading

        leading = len(p%text) - len(adjustl(p%text))
        write(buffer, '(i0)') max(1, min(p%at, len(p%text) + 1) - leading)
        text = trim(buffer)
    end function column_text

end module rollcon_adm_expression_scan
