! SPDX-License-Identifier: MIT
!> Small file and shell helpers for building a user's UCOSUB: whole files as bytes, text lines,
!> the head of a log, shell quoting.
module rollcon_user_files
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
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

    !> The whole file as a string of bytes.
    subroutine read_bytes(path, content, error)
        !> File to read
        character(len=*), intent(in) :: path
        !> Its bytes
        character(len=:), allocatable, intent(out) :: content
        !> Set when the file cannot be opened or read
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, length

        open(newunit=unit, file=path, access="stream", form="unformatted", action="read", &
            & status="old", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot open it for reading", stat_io)
            return
        end if
        inquire(unit=unit, size=length)
        if (length < 0) then
            close(unit)
            call fatal_error(error, path // ": cannot tell its size (is it a regular file?)", &
                & stat_io)
            return
        end if
        allocate(character(len=length) :: content)
        if (length > 0) read(unit, iostat=stat) content
        close(unit)
        if (stat /= 0) then
            call fatal_error(error, path // ": reading failed (is it a regular file?)", stat_io)
        end if
    end subroutine read_bytes

    !> Write a string of bytes as the whole file (replacing it).
    subroutine write_bytes(path, content, error)
        !> File to write
        character(len=*), intent(in) :: path
        !> Bytes to write
        character(len=*), intent(in) :: content
        !> Set when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat

        open(newunit=unit, file=path, access="stream", form="unformatted", action="write", &
            & status="replace", iostat=stat)
        if (stat == 0) then
            write(unit, iostat=stat) content
            close(unit)
        end if
        if (stat /= 0) call fatal_error(error, path // ": cannot write it", stat_io)
    end subroutine write_bytes

    !> Write lines (trailing blanks removed) as a text file.
    subroutine write_lines(path, lines, error)
        !> File to write
        character(len=*), intent(in) :: path
        !> Its lines
        character(len=*), intent(in) :: lines(:)
        !> Set when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, i

        open(newunit=unit, file=path, action="write", status="replace", iostat=stat)
        do i = 1, size(lines)
            if (stat /= 0) exit
            write(unit, '(a)', iostat=stat) trim(lines(i))
        end do
        if (stat == 0) close(unit)
        if (stat /= 0) call fatal_error(error, path // ": cannot write it", stat_io)
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
