! SPDX-License-Identifier: MIT
!> The bytes a scene file may hold, and text made visible for messages: a UTF-8 byte-order
!> mark at the start is skipped; control bytes are refused anywhere, non-ASCII characters
!> outside comments; a message shows them as `\x00` or `U+FEFF`, never raw.
module rollcon_namelist_bytes
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : line_type
    implicit none
    private

    public :: check_bytes, visible, utf8_length

    !> The UTF-8 encoding of U+FEFF, the byte-order mark
    character(len=*), parameter :: byte_order_mark = achar(239) // achar(187) // achar(191)
    !> Control bytes allowed: tab, and the carriage return of CRLF line ends
    character(len=*), parameter :: allowed_controls = achar(9) // achar(13)
    character(len=*), parameter :: hex_digits = "0123456789ABCDEF"

contains

    !> Skip a byte-order mark at the start of the file; refuse control bytes (but tab and
    !> carriage return) anywhere and non-ASCII characters outside comments.
    subroutine check_bytes(path, lines, error)
        !> File the lines come from, for messages
        character(len=*), intent(in) :: path
        !> Lines of the file; the first loses its byte-order mark
        type(line_type), intent(inout) :: lines(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: i, j, code
        character :: quote

        if (size(lines) > 0) then
            if (index(lines(1)%text, byte_order_mark) == 1) lines(1)%text = lines(1)%text(4:)
        end if
        do i = 1, size(lines)
            associate (line => lines(i)%text)
                quote = " "
                do j = 1, len(line)
                    code = iachar(line(j:j))
                    if ((code < 32 .and. index(allowed_controls, line(j:j)) == 0) &
                        & .or. code == 127) then
                        call input_error(error, visible(path), i, "", "control character " &
                            & // visible(line(j:j)) // " at column " // to_text(j) &
                            & // "; a scene file is text (tab and line ends only)")
                        return
                    end if
                    if (code > 127 .and. quote /= "!") then
                        call input_error(error, visible(path), i, "", "non-ASCII character " &
                            & // visible(line(j:j + utf8_length(line(j:)) - 1)) &
                            & // " at column " // to_text(j) // "; outside comments a scene " &
                            & // "file is ASCII (a byte-order mark is allowed at the start only)")
                        return
                    end if
                    ! track strings and the comment, as the lexer does
                    if (quote == " ") then
                        if (line(j:j) == "'" .or. line(j:j) == '"' .or. line(j:j) == "!") &
                            & quote = line(j:j)
                    else if (line(j:j) == quote .and. quote /= "!") then
                        quote = " "
                    end if
                end do
            end associate
        end do
    end subroutine check_bytes

    !> Text with every control byte written `\xNN`, every well-formed UTF-8 character written
    !> `U+XXXX`, and any other byte above 127 written `\xNN`. Linear in the text's length (a
    !> byte is shown in at most 6 characters: the result is built in a buffer of that size).
    pure function visible(text) result(shown)
        !> Text to show
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: shown
        character(len=:), allocatable :: buffer
        character(len=:), allocatable :: piece
        integer :: j, n, code, at

        allocate(character(len=6*len(text)) :: buffer)
        at = 0
        j = 1
        do while (j <= len(text))
            code = iachar(text(j:j))
            if (code >= 32 .and. code < 127) then
                buffer(at + 1:at + 1) = text(j:j)
                at = at + 1
                j = j + 1
                cycle
            end if
            n = utf8_length(text(j:))
            if (code > 127 .and. n > 1) then
                piece = "U+" // hex(utf8_code(text(j:j + n - 1)), 4)
                j = j + n
            else
                piece = "\x" // hex(code, 2)
                j = j + 1
            end if
            buffer(at + 1:at + len(piece)) = piece
            at = at + len(piece)
        end do
        shown = buffer(:at)
    end function visible

    !> Bytes of the well-formed UTF-8 character at the start of text; 1 when it is not one.
    pure integer function utf8_length(text) result(n)
        character(len=*), intent(in) :: text
        integer :: code, k

        code = iachar(text(1:1))
        if (code >= 194 .and. code <= 223) then
            n = 2
        else if (code >= 224 .and. code <= 239) then
            n = 3
        else if (code >= 240 .and. code <= 244) then
            n = 4
        else
            n = 1
            return
        end if
        if (len(text) < n) then
            n = 1
            return
        end if
        do k = 2, n
            code = iachar(text(k:k))
            if (code < 128 .or. code > 191) then
                n = 1
                return
            end if
        end do
    end function utf8_length

    !> Code point of one well-formed UTF-8 character.
    pure integer function utf8_code(text) result(code)
        character(len=*), intent(in) :: text
        integer :: k

        select case (len(text))
        case (2)
            code = iand(iachar(text(1:1)), 31)
        case (3)
            code = iand(iachar(text(1:1)), 15)
        case default
            code = iand(iachar(text(1:1)), 7)
        end select
        do k = 2, len(text)
            code = 64*code + iand(iachar(text(k:k)), 63)
        end do
    end function utf8_code

    !> Uppercase hexadecimal, at least digits long.
    pure function hex(value, digits) result(text)
        integer, intent(in) :: value, digits
        character(len=:), allocatable :: text
        integer :: rest

        text = ""
        rest = value
        do while (rest > 0 .or. len(text) < digits)
            text = hex_digits(mod(rest, 16) + 1:mod(rest, 16) + 1) // text
            rest = rest/16
        end do
    end function hex

end module rollcon_namelist_bytes
