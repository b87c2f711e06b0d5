! SPDX-License-Identifier: MIT
!> A run's provenance: which rollcon, when, the command that asked for it, and which UCOSUB
!> served the model's UCONs (a built-in routine's name, or the user's file with its size and
!> FNV-1a 64 hash), so that a result can be traced to what made it. The summary file opens
!> with these lines, the .parts file carries them as comments.
module rollcon_provenance
    use rollcon_error, only : error_type
    use rollcon_version, only : version_text
    use rollcon_text, only : shell_quote
    use rollcon_input_files, only : file_record, text_input_limit
    use rollcon_job, only : job_type
    implicit none
    private

    public :: provenance_lines, user_file_record, time_stamp, command_line_text

contains

    !> Two lines, each ending in a newline:
    !>     rollcon 0.2.0, 2026-11-26 04:45:12 +0000: rollcon run data/coin.nml
    !>     the model's UCOSUB: disk (built in)
    !> (the second: "none (every UCON names its ROUTINE)" for a model whose every UCON has its
    !> own routine, "none (the model has no UCON)" for one with no UCON, and a user's file with its
    !> size and hash), then the job's files of user routines. With defined (what the run's child
    !> found the files define: rollcon_isolated_run's defined_text, the file of the model's own
    !> UCOSUB, "" for none, then a line of words per file), the second line names the file whose
    !> UCOSUB served the model's UCONs, or none, and each file that does more than that gets a
    !> line "user routines: FILE (SFOSUB, ...; its size and hash)"; without it or with it ""
    !> (no child told: a built-in routine), the job's first file is named as the model's UCOSUB
    !> and each more file as "more user routines: FILE (its size and hash)" (rollcon_load's
    !> add_user_file).
    function provenance_lines(job, defined) result(text)
        type(job_type), intent(in) :: job
        character(len=*), intent(in), optional :: defined
        character(len=:), allocatable :: text, own, words, path
        integer :: k, start, finish, more
        logical :: told

        text = version_text() // ", " // time_stamp()
        if (allocated(job%command_line)) then
            if (len(job%command_line) > 0) text = text // ": " // job%command_line
        end if
        text = text // new_line("a") // "the model's UCOSUB: "
        told = .false.
        if (present(defined)) told = len(defined) > 0
        if (told) then
            ! the first line: the file of the model's own UCOSUB; then the files' words
            finish = index(defined, new_line("a"))
            if (finish == 0) finish = len(defined) + 1
            own = defined(:finish - 1)
            if (len(own) > 0) then
                text = text // own // " (" // user_file_record(own) // ")"
            else if (job%source%no_ucons) then
                text = text // "none (the model has no UCON)"
            else
                text = text // "none (every UCON names its ROUTINE)"
            end if
            text = text // new_line("a")
            more = 0
            if (allocated(job%more_files)) more = size(job%more_files)
            do k = 0, more
                start = finish + 1
                if (start > len(defined)) exit
                finish = start - 1 + index(defined(start:), new_line("a"))
                if (finish < start) finish = len(defined) + 1
                words = defined(start:finish - 1)
                if (k == 0) then
                    path = job%user_file
                else
                    path = job%more_files(k)%path
                end if
                ! a file whose one role is the model's UCOSUB is named on that line
                if (path == own .and. words == "UCOSUB") cycle
                if (len(words) > 0) words = words // "; "
                text = text // "user routines: " // path // " (" // words &
                    & // user_file_record(path) // ")" // new_line("a")
            end do
            return
        end if
        if (len(job%user_file) > 0) then
            text = text // job%user_file // " (" // user_file_record(job%user_file) // ")"
        else if (job%source%own_routines .and. job%source%no_ucons) then
            text = text // "none (the model has no UCON)"
        else if (job%source%own_routines) then
            text = text // "none (every UCON names its ROUTINE)"
        else
            text = text // job%routine_name // " (built in)"
        end if
        text = text // new_line("a")
        ! more files of user routines (rollcon run --ucosub A.f --ucosub B.f)
        if (allocated(job%more_files)) then
            do k = 1, size(job%more_files)
                text = text // "more user routines: " // job%more_files(k)%path // " (" &
                    & // user_file_record(job%more_files(k)%path) // ")" // new_line("a")
            end do
        end if
    end function provenance_lines

    !> "N bytes, FNV-1a 64 HHHHHHHHHHHHHHHH" of a user's file (rollcon_input_files), or
    !> "unreadable" with the reason.
    function user_file_record(path) result(record)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: record
        type(error_type), allocatable :: error

        call file_record(path, "UCOSUB source", text_input_limit, record, error)
        if (allocated(error)) record = "unreadable: " // error%message
    end function user_file_record

    !> The program's command as typed, for a run's record: "rollcon run data/coin.nml -o out";
    !> an argument is quoted for the shell when it holds more than letters, digits and ./_-=+,:@%
    function command_line_text() result(text)
        character(len=:), allocatable :: text, argument
        character(len=*), parameter :: plain = "abcdefghijklmnopqrstuvwxyz" &
            & // "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789./_-=+,:@%"
        integer :: i, length

        text = "rollcon"
        do i = 1, command_argument_count()
            call get_command_argument(i, length=length)
            allocate(character(len=length) :: argument)
            if (length > 0) call get_command_argument(i, argument)
            if (length == 0 .or. verify(argument, plain) > 0) argument = shell_quote(argument)
            text = text // " " // argument
            deallocate(argument)
        end do
    end function command_line_text

    !> The local time with its offset from UTC: "2026-11-26 04:45:12 +0000".
    function time_stamp() result(text)
        character(len=:), allocatable :: text
        character(len=8) :: date
        character(len=10) :: time
        character(len=5) :: zone

        call date_and_time(date, time, zone)
        text = date(1:4) // "-" // date(5:6) // "-" // date(7:8) // " " // time(1:2) // ":" &
            & // time(3:4) // ":" // time(5:6) // " " // zone
    end function time_stamp

end module rollcon_provenance
