! SPDX-License-Identifier: MIT
!> Small file and shell helpers for building a user's UCOSUB: whole files as bytes, text lines,
!> the head of a log, shell quoting.
module rollcon_user_files
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_input_files, only : read_input_file, text_input_limit
    use rollcon_c_stream, only : c_stream_type
    implicit none
    private

    public :: file_exists, read_bytes, write_bytes, write_lines, text_head

contains

    !> True when path names an existing file.
    function file_exists(path) result(exists)
        !> Path to look at
        character(len=*), intent(in) :: path
        logical :: exists

        inquire(file=path, exist=exists)
    end function file_exists

    !> The whole file as bytes: a regular file of at most text_input_limit bytes
    !> (rollcon_input_files), so a UCOSUB named by a link to /dev/zero or a FIFO is refused.
    subroutine read_bytes(path, content, error)
        !> File to read
        character(len=*), intent(in) :: path
        !> Its bytes
        character(len=:), allocatable, intent(out) :: content
        !> Set when the file cannot be opened or read
        type(error_type), allocatable, intent(out) :: error

        call read_input_file(path, "UCOSUB source or object", text_input_limit, content, error)
    end subroutine read_bytes

    !> Write a string of bytes as the whole file (replacing it), through the C library so
    !> that a full disk is an error naming the file and the system's reason.
    subroutine write_bytes(path, content, error)
        !> File to write
        character(len=*), intent(in) :: path
        !> Bytes to write
        character(len=*), intent(in) :: content
        !> Set when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        type(c_stream_type) :: file
        type(error_type), allocatable :: close_error

        call file%open_file(path, error)
        if (allocated(error)) return
        call file%put(content, error)
        call file%close_file(close_error)
        if (.not. allocated(error) .and. allocated(close_error)) &
            & call move_alloc(close_error, error)
    end subroutine write_bytes

    !> Write lines (trailing blanks removed) as a text file, checked as write_bytes.
    subroutine write_lines(path, lines, error)
        !> File to write
        character(len=*), intent(in) :: path
        !> Its lines
        character(len=*), intent(in) :: lines(:)
        !> Set when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        integer :: i

        text = ""
        do i = 1, size(lines)
            text = text // trim(lines(i)) // new_line("a")
        end do
        call write_bytes(path, text, error)
    end subroutine write_lines

    !> The first max_lines lines of a text file, newline-separated, with a note of how many
    !> more there are; a note in place of the text when it cannot be read.
    subroutine text_head(path, max_lines, text)
        !> File to read
        character(len=*), intent(in) :: path
        !> Most lines to keep
        integer, intent(in) :: max_lines
        !> The lines
        character(len=:), allocatable, intent(out) :: text
        character(len=4096) :: line
        integer :: unit, stat, count, length

        text = ""
        open(newunit=unit, file=path, action="read", status="old", iostat=stat)
        if (stat /= 0) then
            text = "(" // path // " cannot be read)"
            return
        end if
        count = 0
        do
            read(unit, '(a)', iostat=stat, size=length, advance="no") line
            if (is_iostat_end(stat)) exit
            if (stat /= 0 .and. .not. is_iostat_eor(stat)) exit
            count = count + 1
            if (count <= max_lines) then
                if (count > 1) text = text // new_line("a")
                text = text // line(:length)
            end if
            ! The rest of a line longer than the buffer is skipped.
            if (.not. is_iostat_eor(stat)) read(unit, '(a)', iostat=stat)
        end do
        close(unit)
        if (count > max_lines) then
            text = text // new_line("a") // "... (" // to_text(count - max_lines) &
                & // " more lines)"
        end if
    end subroutine text_head


end module rollcon_user_files
