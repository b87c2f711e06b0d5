! SPDX-License-Identifier: MIT
!> Running gnuplot on a script we generate: is it there, quoting of file names, and its exit
!> status and messages turned into an error.
module rollcon_gnuplot
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text, single_quoted, shell_quote
    implicit none
    private

    public :: gnuplot_available, require_gnuplot, run_gnuplot, gnuplot_string, base_name, &
        & remove_file, require_written

    !> What to install when gnuplot is missing
    character(len=*), parameter :: install_hint = "gnuplot with its pngcairo and gif " &
        & // "terminals is needed (Debian package gnuplot-nox; bash .ci/setup installs it)"

contains

    !> True when a program named gnuplot is on the PATH.
    function gnuplot_available() result(available)
        logical :: available
        integer :: exit_status, command_status

        exit_status = 1
        call execute_command_line("command -v gnuplot > /dev/null 2>&1", wait=.true., &
            & exitstat=exit_status, cmdstat=command_status)
        available = command_status == 0 .and. exit_status == 0
    end function gnuplot_available

    !> An error unless gnuplot is on the PATH.
    subroutine require_gnuplot(error)
        type(error_type), allocatable, intent(out) :: error

        if (.not. gnuplot_available()) then
            call fatal_error(error, "gnuplot not found on the PATH: " // install_hint, stat_io)
        end if
    end subroutine require_gnuplot

    !> Run gnuplot on a script; its messages go to script.log, which is removed when gnuplot
    !> succeeds and single_quoted in the error when it fails.
    subroutine run_gnuplot(script, error)
        !> Script file
        character(len=*), intent(in) :: script
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: command_message
        integer :: exit_status, command_status

        call require_gnuplot(error)
        if (allocated(error)) return
        command_message = ""
        exit_status = 0
        call execute_command_line("gnuplot " // shell_quote(script) // " > " &
            & // shell_quote(script // ".log") // " 2>&1", wait=.true., exitstat=exit_status, &
            & cmdstat=command_status, cmdmsg=command_message)
        if (command_status /= 0) then
            call fatal_error(error, "cannot run gnuplot on " // script // ": " &
                & // trim(command_message), stat_io)
        else if (exit_status /= 0) then
            call fatal_error(error, "gnuplot failed on " // script // " (exit status " &
                & // to_text(exit_status) // "; the script and its data are kept): " &
                & // text_head(script // ".log"), stat_io)
        else
            call remove_file(script // ".log")
        end if
    end subroutine run_gnuplot

    !> An error unless gnuplot, reporting success on script, did write the picture at path.
    subroutine require_written(path, script, error)
        character(len=*), intent(in) :: path, script
        type(error_type), allocatable, intent(out) :: error
        integer :: size_bytes

        size_bytes = 0
        inquire(file=path, size=size_bytes)
        if (size_bytes <= 0) call fatal_error(error, path // ": gnuplot reported success but " &
            & // "did not write this PNG file (see " // script // ")", stat_io)
    end subroutine require_written

    !> A gnuplot string constant holding text: single quotes, a quote doubled.
    pure function gnuplot_string(text) result(word)
        !> Any text, e.g. a file name
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: word

        word = single_quoted(text, "''")
    end function gnuplot_string

    !> File name without its folder and without the extension given: ("out/coin.csv", ".csv")
    !> gives "coin".
    pure function base_name(path, extension) result(name)
        !> File path, and the extension to drop when the name ends with it ("" for none)
        character(len=*), intent(in) :: path, extension
        character(len=:), allocatable :: name
        integer :: n

        name = path(index(path, "/", back=.true.) + 1:)
        n = len(name) - len(extension)
        if (n > 0) then
            if (name(n + 1:) == extension) name = name(:n)
        end if
    end function base_name

    !> Remove a file if it is there; a failure to remove is ignored.
    subroutine remove_file(path)
        !> File to remove
        character(len=*), intent(in) :: path
        integer :: unit, stat
        logical :: exists

        inquire(file=path, exist=exists)
        if (.not. exists) return
        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete", iostat=stat)
    end subroutine remove_file


    !> The first lines of a text file (at most 600 characters), joined by ' | '.
    function text_head(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        character(len=300) :: line
        integer :: unit, stat

        text = ""
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) then
            text = "(no messages in " // path // ")"
            return
        end if
        do while (len(text) < 600)
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (len_trim(line) == 0) cycle
            if (len(text) > 0) text = text // " | "
            text = text // trim(adjustl(line))
        end do
        close(unit)
        if (len(text) == 0) text = "(no messages in " // path // ")"
    end function text_head

end module rollcon_gnuplot
