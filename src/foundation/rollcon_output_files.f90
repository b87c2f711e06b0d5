! SPDX-License-Identifier: MIT
!> Putting a run's output files in place: a run writes under a name of its own that says the
!> file is partial (it holds the process id, so two runs never share one), and renames it to
!> the final name only when it succeeded. Every write, close, removal and rename is checked.
module rollcon_output_files
    use, intrinsic :: iso_c_binding, only : c_int, c_char, c_null_char
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_c_stream, only : c_stream_type
    use rollcon_system, only : make_one_folder, path_kind, kind_directory, &
        & system_reason, errno_exists, path_max
    implicit none
    private

    public :: partial_name, write_text_file, rename_file, delete_file, close_checked
    public :: make_folders

    interface
        !> POSIX getpid(2)
        function c_getpid() result(pid) bind(c, name="getpid")
            import :: c_int
            integer(c_int) :: pid
        end function c_getpid
        !> C rename(3): atomic within one filesystem
        function c_rename(from, to) result(stat) bind(c, name="rename")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: from(*), to(*)
            integer(c_int) :: stat
        end function c_rename
        !> POSIX close(2)
        function c_close(descriptor) result(stat) bind(c, name="close")
            import :: c_int
            integer(c_int), value :: descriptor
            integer(c_int) :: stat
        end function c_close
    end interface

contains

    !> The name a run writes under before it succeeds: folder/<name>.partial-<pid><extension>,
    !> e.g. output/coin.partial-4242.csv.
    function partial_name(folder, name, extension) result(path)
        !> Folder, base name and extension (with its dot) of the final file
        character(len=*), intent(in) :: folder, name, extension
        character(len=:), allocatable :: path

        path = folder // "/" // name // ".partial-" // to_text(int(c_getpid())) // extension
    end function partial_name

    !> Write text (and a line end) to a new file, replacing any; every write and the close
    !> are checked, so a full disk is an error naming the file.
    subroutine write_text_file(path, text, error)
        character(len=*), intent(in) :: path, text
        type(error_type), allocatable, intent(out) :: error
        type(c_stream_type) :: file
        type(error_type), allocatable :: close_error

        call file%open_file(path, error)
        if (allocated(error)) return
        call file%put(text // new_line("a"), error)
        call file%close_file(close_error)
        if (.not. allocated(error) .and. allocated(close_error)) &
            & call move_alloc(close_error, error)
    end subroutine write_text_file

    !> Close a unit opened with access="stream", form="formatted", and check that the file
    !> holds every byte written: gfortran 12 reports no error when a write or the close
    !> fails (a full disk), so the file's size is compared with the unit's position.
    subroutine close_checked(unit, path, error)
        !> Unit to close
        integer, intent(in) :: unit
        !> Its file, for the check and the message
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        integer(int64) :: position, size_bytes
        integer :: stat, descriptor
        integer(c_int) :: ignored

        inquire(unit=unit, pos=position)
        descriptor = fnum(unit)  ! gfortran's file descriptor of the unit
        close(unit, iostat=stat)
        inquire(file=path, size=size_bytes)
        if (stat /= 0 .or. size_bytes /= position - 1) then
            ! gfortran 12 keeps the descriptor open when its last write fails: release it,
            ! or the filesystem stays busy until the program ends.
            ignored = c_close(int(descriptor, c_int))
            call fatal_error(error, path // ": write failed: the file holds " &
                & // to_text(size_bytes) // " of the " // to_text(position - 1) &
                & // " bytes written (is the disk full?)", stat_io)
        end if
    end subroutine close_checked

    !> Create a folder and the parents it lacks, as `mkdir -p` does, through mkdir(2) one
    !> level at a time: no shell and no PATH are needed. Every failure is an error naming the
    !> folder, the level that could not be made and the system's reason; a path the system
    !> cannot take (PATH_MAX) is refused as such.
    subroutine make_folders(folder, error)
        !> Folder to create
        character(len=*), intent(in) :: folder
        type(error_type), allocatable, intent(out) :: error
        integer :: j, errno_value, kind, stat_errno
        integer(int64) :: size

        if (len(folder) == 0) then
            call fatal_error(error, "an output folder must be named, got ''", stat_io)
            return
        end if
        if (len(folder) >= path_max) then
            call fatal_error(error, folder(:60) // "...: the folder's path is " &
                & // to_text(len(folder)) // " characters long; the system takes paths of " &
                & // "at most " // to_text(path_max - 1) // " (PATH_MAX): give a shorter one", &
                & stat_io)
            return
        end if
        do j = 1, len(folder)
            ! folder(:j) is a level when a slash follows it, or it is the whole path
            if (j < len(folder)) then
                if (folder(j + 1:j + 1) /= "/") cycle
            end if
            ! "/", "a//b" and a trailing slash: the level without the slash is made already
            if (folder(j:j) == "/") cycle
            errno_value = make_one_folder(folder(:j))
            if (errno_value == 0) cycle
            ! there already (or not to be made again, e.g. a parent without write permission)
            call path_kind(folder(:j), kind, size, stat_errno)
            if (kind == kind_directory) cycle
            if (errno_value == errno_exists) then
                call fatal_error(error, folder // ": cannot create the folder: " // folder(:j) &
                    & // " exists and is not a folder", stat_io)
            else if (j == len(folder)) then
                call fatal_error(error, folder // ": cannot create the folder: " &
                    & // system_reason(errno_value), stat_io)
            else
                call fatal_error(error, folder // ": cannot create the folder " // folder(:j) &
                    & // ": " // system_reason(errno_value), stat_io)
            end if
            return
        end do
    end subroutine make_folders

    !> Rename a file, replacing the target (atomically when both are in one folder).
    subroutine rename_file(from, to, error)
        character(len=*), intent(in) :: from, to
        type(error_type), allocatable, intent(out) :: error

        if (c_rename(from // c_null_char, to // c_null_char) /= 0) then
            call fatal_error(error, from // ": cannot rename it to " // to, stat_io)
        end if
    end subroutine rename_file

    !> Remove a file if it is there; failing to remove one that is there is an error.
    subroutine delete_file(path, error)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: message
        integer :: unit, stat
        logical :: exists

        inquire(file=path, exist=exists)
        if (.not. exists) return
        message = ""
        open(newunit=unit, file=path, status="old", iostat=stat, iomsg=message)
        if (stat == 0) close(unit, status="delete", iostat=stat, iomsg=message)
        if (stat /= 0) call fatal_error(error, path // ": cannot remove: " // trim(message), &
            & stat_io)
    end subroutine delete_file

end module rollcon_output_files
