! SPDX-License-Identifier: MIT
!> The POSIX calls rollcon makes itself, through iso_c_binding, so that no shell and no PATH
!> are needed for them (Linux and glibc, as the rest of the isolation layer): what a path is
!> and its size (statx(2), whose record has one layout on every Linux architecture), open,
!> read, write and close of a descriptor, folders made one level at a time (mkdir(2)), an
!> advisory lock (flock(2)), whether a file may be executed (access(2)), the host's name, and
!> the system's text for the last error (errno, strerror).
module rollcon_system
    use, intrinsic :: iso_c_binding, only : c_int, c_char, c_null_char, c_ptr, c_size_t, &
        & c_int16_t, c_int32_t, c_int64_t, c_intptr_t, c_f_pointer, c_associated
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_text, only : to_text
    implicit none
    private

    public :: system_reason, last_errno, path_kind, path_kind_text, descriptor_kind
    public :: open_read, open_lock_file, read_bytes_into, write_descriptor, close_descriptor
    public :: lock_exclusive, truncate_descriptor, make_one_folder, is_executable, host_name
    public :: remove_flat_folder, rename_path, path_inode, descriptor_inode, remove_file_path
    public :: this_process
    public :: kind_missing, kind_regular, kind_directory, kind_character, kind_block, &
        & kind_fifo, kind_socket, kind_link, kind_unknown
    public :: errno_exists, errno_no_space, errno_would_block, errno_interrupted, &
        & errno_no_entry, errno_name_too_long, errno_not_directory, errno_no_locks, &
        & errno_not_supported, path_max

    !> What a path names (path_kind, descriptor_kind)
    integer, parameter :: kind_missing = 0, kind_regular = 1, kind_directory = 2, &
        & kind_character = 3, kind_block = 4, kind_fifo = 5, kind_socket = 6, kind_link = 7, &
        & kind_unknown = 8

    !> Linux's errno values (the same on x86_64 and aarch64)
    integer, parameter :: errno_no_entry = 2, errno_interrupted = 4, errno_would_block = 11, &
        & errno_exists = 17, errno_not_directory = 20, errno_no_space = 28, &
        & errno_name_too_long = 36, errno_no_locks = 37, errno_not_supported = 95
    !> Longest path the system takes, its terminating NUL included (Linux's PATH_MAX)
    integer, parameter :: path_max = 4096

    !> open(2) flags (Linux, x86_64 and the generic values of aarch64)
    integer(c_int), parameter :: o_rdonly = 0, o_rdwr = 2, o_creat = int(o'100', c_int), &
        & o_nonblock = int(o'4000', c_int), o_cloexec = int(o'2000000', c_int)
    !> statx(2): the descriptor itself (AT_EMPTY_PATH), relative to the working folder
    !> (AT_FDCWD), and the fields asked for (STATX_TYPE | STATX_SIZE)
    integer(c_int), parameter :: at_empty_path = int(z'1000', c_int), at_fdcwd = -100_c_int, &
        & statx_type_size = int(z'201', c_int), statx_ino = int(z'100', c_int)
    !> flock(2) operations
    integer(c_int), parameter :: lock_ex = 2_c_int, lock_nb = 4_c_int
    !> access(2): may be executed
    integer(c_int), parameter :: x_ok = 1_c_int

    !> struct statx of <linux/stat.h>: 256 bytes, fixed-width fields, one layout everywhere
    type, bind(c) :: statx_record_type
        integer(c_int32_t) :: mask = 0, blksize = 0
        integer(c_int64_t) :: attributes = 0
        integer(c_int32_t) :: nlink = 0, uid = 0, gid = 0
        integer(c_int16_t) :: mode = 0, spare0 = 0
        integer(c_int64_t) :: ino = 0, size = 0, blocks = 0, attributes_mask = 0
        !> the timestamps, device numbers and spare room: 256 - 64 bytes
        integer(c_int64_t) :: rest(24) = 0
    end type statx_record_type

    interface
        function c_statx(dirfd, path, flags, mask, record) result(stat) bind(c, name="statx")
            import :: c_int, c_char, statx_record_type
            integer(c_int), value :: dirfd, flags, mask
            character(kind=c_char), intent(in) :: path(*)
            type(statx_record_type), intent(out) :: record
            integer(c_int) :: stat
        end function c_statx
        !> open(2), called with its third argument always given
        function c_open(path, flags, mode) result(fd) bind(c, name="open")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: flags, mode
            integer(c_int) :: fd
        end function c_open
        function c_read(fd, buffer, count) result(got) bind(c, name="read")
            import :: c_int, c_char, c_size_t, c_intptr_t
            integer(c_int), value :: fd
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_size_t), value :: count
            integer(c_intptr_t) :: got
        end function c_read
        function c_write(fd, buffer, count) result(put) bind(c, name="write")
            import :: c_int, c_char, c_size_t, c_intptr_t
            integer(c_int), value :: fd
            character(kind=c_char), intent(in) :: buffer(*)
            integer(c_size_t), value :: count
            integer(c_intptr_t) :: put
        end function c_write
        function c_close(fd) result(stat) bind(c, name="close")
            import :: c_int
            integer(c_int), value :: fd
            integer(c_int) :: stat
        end function c_close
        function c_ftruncate(fd, length) result(stat) bind(c, name="ftruncate")
            import :: c_int, c_int64_t
            integer(c_int), value :: fd
            integer(c_int64_t), value :: length
            integer(c_int) :: stat
        end function c_ftruncate
        function c_mkdir(path, mode) result(stat) bind(c, name="mkdir")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: stat
        end function c_mkdir
        function c_flock(fd, operation) result(stat) bind(c, name="flock")
            import :: c_int
            integer(c_int), value :: fd, operation
            integer(c_int) :: stat
        end function c_flock
        function c_access(path, mode) result(stat) bind(c, name="access")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: stat
        end function c_access
        function c_gethostname(name, length) result(stat) bind(c, name="gethostname")
            import :: c_int, c_char, c_size_t
            character(kind=c_char), intent(out) :: name(*)
            integer(c_size_t), value :: length
            integer(c_int) :: stat
        end function c_gethostname
        function c_getpid() result(pid) bind(c, name="getpid")
            import :: c_int
            integer(c_int) :: pid
        end function c_getpid
        function c_rename(from, to) result(stat) bind(c, name="rename")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: from(*), to(*)
            integer(c_int) :: stat
        end function c_rename
        function c_unlink(path) result(stat) bind(c, name="unlink")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: stat
        end function c_unlink
        function c_rmdir(path) result(stat) bind(c, name="rmdir")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int) :: stat
        end function c_rmdir
        function c_opendir(path) result(dir) bind(c, name="opendir")
            import :: c_ptr, c_char
            character(kind=c_char), intent(in) :: path(*)
            type(c_ptr) :: dir
        end function c_opendir
        !> readdir(3); glibc's struct dirent on 64-bit Linux: d_ino, d_off (8 bytes each),
        !> d_reclen (2), d_type (1), then d_name at byte 19
        function c_readdir(dir) result(entry) bind(c, name="readdir")
            import :: c_ptr
            type(c_ptr), value :: dir
            type(c_ptr) :: entry
        end function c_readdir
        function c_closedir(dir) result(stat) bind(c, name="closedir")
            import :: c_ptr, c_int
            type(c_ptr), value :: dir
            integer(c_int) :: stat
        end function c_closedir
        !> glibc's (and musl's) location of errno
        function c_errno_location() result(location) bind(c, name="__errno_location")
            import :: c_ptr
            type(c_ptr) :: location
        end function c_errno_location
        function c_strerror(number) result(text) bind(c, name="strerror")
            import :: c_ptr, c_int
            integer(c_int), value :: number
            type(c_ptr) :: text
        end function c_strerror
    end interface

contains

    !> errno: the number of the last failed call's error.
    integer function last_errno()
        integer(c_int), pointer :: errno

        call c_f_pointer(c_errno_location(), errno)
        last_errno = int(errno)
    end function last_errno

    !> The system's text for errno ("No space left on device"), or for the given number.
    function system_reason(number) result(text)
        integer, intent(in), optional :: number
        character(len=:), allocatable :: text
        character(kind=c_char), pointer :: chars(:)
        type(c_ptr) :: address
        integer :: n, code

        if (present(number)) then
            code = number
        else
            code = last_errno()
        end if
        address = c_strerror(int(code, c_int))
        text = "unknown reason (errno " // to_text(code) // ")"
        if (.not. c_associated(address)) return
        call c_f_pointer(address, chars, [256])
        n = 0
        do while (n < size(chars))
            if (chars(n + 1) == c_null_char) exit
            n = n + 1
        end do
        if (n == 0) return
        deallocate(text)
        allocate(character(len=n) :: text)
        text = transfer(chars(:n), text)
    end function system_reason

    !> What path names, following links (kind_missing when nothing); its size in bytes for a
    !> regular file (else 0). errno_value is errno when statx failed for another reason than
    !> a missing path (then kind_unknown), else 0.
    subroutine path_kind(path, kind, size, errno_value)
        character(len=*), intent(in) :: path
        integer, intent(out) :: kind
        integer(int64), intent(out) :: size
        integer, intent(out) :: errno_value
        type(statx_record_type) :: record

        size = 0
        errno_value = 0
        if (c_statx(at_fdcwd, path // c_null_char, 0_c_int, statx_type_size, record) /= 0) then
            errno_value = last_errno()
            kind = kind_unknown
            if (errno_value == errno_no_entry .or. errno_value == errno_not_directory) then
                kind = kind_missing
                errno_value = 0
            end if
            return
        end if
        call kind_of_record(record, kind, size)
    end subroutine path_kind

    !> What an open descriptor is, and its size; kind_unknown when statx cannot tell (an
    !> old kernel: the reader's own limits still hold).
    subroutine descriptor_kind(fd, kind, size)
        integer(c_int), intent(in) :: fd
        integer, intent(out) :: kind
        integer(int64), intent(out) :: size
        type(statx_record_type) :: record

        size = 0
        kind = kind_unknown
        if (c_statx(fd, c_null_char, at_empty_path, statx_type_size, record) /= 0) return
        call kind_of_record(record, kind, size)
    end subroutine descriptor_kind

    !> The kind and size a statx record gives.
    subroutine kind_of_record(record, kind, size)
        type(statx_record_type), intent(in) :: record
        integer, intent(out) :: kind
        integer(int64), intent(out) :: size
        integer :: mode

        mode = iand(int(record%mode), int(o'170000'))
        select case (mode)
        case (int(o'100000'))
            kind = kind_regular
        case (int(o'040000'))
            kind = kind_directory
        case (int(o'020000'))
            kind = kind_character
        case (int(o'060000'))
            kind = kind_block
        case (int(o'010000'))
            kind = kind_fifo
        case (int(o'140000'))
            kind = kind_socket
        case (int(o'120000'))
            kind = kind_link
        case default
            kind = kind_unknown
        end select
        size = 0
        if (kind == kind_regular) size = int(record%size, int64)
    end subroutine kind_of_record

    !> The inode number of what path names (following links), -1 when there is none.
    integer(int64) function path_inode(path) result(inode)
        character(len=*), intent(in) :: path
        type(statx_record_type) :: record

        inode = -1
        if (c_statx(at_fdcwd, path // c_null_char, 0_c_int, statx_ino, record) == 0) &
            & inode = int(record%ino, int64)
    end function path_inode

    !> The inode number of an open descriptor, -1 when statx cannot tell.
    integer(int64) function descriptor_inode(fd) result(inode)
        integer(c_int), intent(in) :: fd
        type(statx_record_type) :: record

        inode = -1
        if (c_statx(fd, c_null_char, at_empty_path, statx_ino, record) == 0) &
            & inode = int(record%ino, int64)
    end function descriptor_inode

    !> unlink(2) of a file: 0 or errno.
    integer function remove_file_path(path) result(errno_value)
        character(len=*), intent(in) :: path

        errno_value = 0
        if (c_unlink(path // c_null_char) /= 0) errno_value = last_errno()
    end function remove_file_path

    !> A path's kind in words, for messages ("a FIFO (named pipe)").
    pure function path_kind_text(kind) result(text)
        integer, intent(in) :: kind
        character(len=:), allocatable :: text

        select case (kind)
        case (kind_missing)
            text = "missing"
        case (kind_regular)
            text = "a regular file"
        case (kind_directory)
            text = "a directory"
        case (kind_character)
            text = "a character device (such as /dev/zero or a terminal)"
        case (kind_block)
            text = "a block device (a disk)"
        case (kind_fifo)
            text = "a FIFO (named pipe)"
        case (kind_socket)
            text = "a socket"
        case (kind_link)
            text = "a symbolic link"
        case default
            text = "not a regular file"
        end select
    end function path_kind_text

    !> Open a file for reading without waiting: a FIFO that nobody writes to opens at once
    !> (and reads as empty) instead of blocking. -1 on failure (errno says why).
    integer(c_int) function open_read(path) result(fd)
        character(len=*), intent(in) :: path

        fd = c_open(path // c_null_char, ior(o_rdonly, ior(o_nonblock, o_cloexec)), 0_c_int)
    end function open_read

    !> Open (create when missing, mode 0644 less the umask) a file to hold a lock. -1 on
    !> failure (errno says why).
    integer(c_int) function open_lock_file(path) result(fd)
        character(len=*), intent(in) :: path

        fd = c_open(path // c_null_char, ior(o_rdwr, ior(o_creat, o_cloexec)), &
            & int(o'644', c_int))
    end function open_lock_file

    !> Read up to len(buffer) bytes; got is their number, 0 at the end, -1 on failure
    !> (errno says why; an interrupted read is retried).
    subroutine read_bytes_into(fd, buffer, got)
        integer(c_int), intent(in) :: fd
        character(len=*), intent(out) :: buffer
        integer, intent(out) :: got
        integer(c_intptr_t) :: n

        do
            n = c_read(fd, buffer, int(len(buffer), c_size_t))
            if (n >= 0 .or. last_errno() /= errno_interrupted) exit
        end do
        got = int(n)
    end subroutine read_bytes_into

    !> Write every byte of text; false on failure (errno says why).
    logical function write_descriptor(fd, text) result(ok)
        integer(c_int), intent(in) :: fd
        character(len=*), intent(in) :: text
        integer(c_intptr_t) :: n
        integer :: done

        done = 0
        ok = .true.
        do while (done < len(text))
            n = c_write(fd, text(done + 1:), int(len(text) - done, c_size_t))
            if (n < 0) then
                if (last_errno() == errno_interrupted) cycle
                ok = .false.
                return
            end if
            done = done + int(n)
        end do
    end function write_descriptor

    !> Cut an open file to length bytes; false on failure.
    logical function truncate_descriptor(fd, length) result(ok)
        integer(c_int), intent(in) :: fd
        integer(int64), intent(in) :: length

        ok = c_ftruncate(fd, int(length, c_int64_t)) == 0
    end function truncate_descriptor

    !> Close a descriptor (negative ones are ignored); false on failure.
    logical function close_descriptor(fd) result(ok)
        integer(c_int), intent(in) :: fd

        ok = .true.
        if (fd >= 0) ok = c_close(fd) == 0
    end function close_descriptor

    !> Take an exclusive flock(2) on fd without waiting: false when another open file holds
    !> it (or the call failed: errno says which). The lock goes with the descriptor's close,
    !> or with the process, however it ends.
    logical function lock_exclusive(fd) result(locked)
        integer(c_int), intent(in) :: fd

        do
            locked = c_flock(fd, ior(lock_ex, lock_nb)) == 0
            if (locked .or. last_errno() /= errno_interrupted) exit
        end do
    end function lock_exclusive

    !> mkdir(2) of one folder, mode 0755 less the umask; 0 or errno.
    integer function make_one_folder(path) result(errno_value)
        character(len=*), intent(in) :: path

        errno_value = 0
        if (c_mkdir(path // c_null_char, int(o'755', c_int)) /= 0) errno_value = last_errno()
    end function make_one_folder

    !> True when path is a regular file this process may execute.
    logical function is_executable(path)
        character(len=*), intent(in) :: path
        integer :: kind, errno_value
        integer(int64) :: size

        is_executable = .false.
        if (len(path) == 0) return
        call path_kind(path, kind, size, errno_value)
        if (kind /= kind_regular) return
        is_executable = c_access(path // c_null_char, x_ok) == 0
    end function is_executable

    !> This process's id.
    integer function this_process()
        this_process = int(c_getpid())
    end function this_process

    !> rename(2): 0 or errno.
    integer function rename_path(from, to) result(errno_value)
        character(len=*), intent(in) :: from, to

        errno_value = 0
        if (c_rename(from // c_null_char, to // c_null_char) /= 0) errno_value = last_errno()
    end function rename_path

    !> Remove a folder that holds files only (no sub-folders), and the files: 0 or the errno
    !> of the first call that failed. A missing folder is no error.
    integer function remove_flat_folder(path) result(errno_value)
        character(len=*), intent(in) :: path
        integer(c_intptr_t), parameter :: name_offset = 19
        character(kind=c_char), pointer :: chars(:)
        character(len=:), allocatable :: name
        type(c_ptr) :: dir, entry
        integer :: n, kind
        integer(int64) :: bytes

        errno_value = 0
        call path_kind(path, kind, bytes, errno_value)
        if (kind == kind_missing) return
        dir = c_opendir(path // c_null_char)
        if (.not. c_associated(dir)) then
            errno_value = last_errno()
            return
        end if
        do
            entry = c_readdir(dir)
            if (.not. c_associated(entry)) exit
            call c_f_pointer(transfer(transfer(entry, 0_c_intptr_t) + name_offset, entry), &
                & chars, [256])
            n = 0
            do while (n < size(chars))
                if (chars(n + 1) == c_null_char) exit
                n = n + 1
            end do
            allocate(character(len=n) :: name)
            name = transfer(chars(:n), name)
            if (name /= "." .and. name /= "..") then
                if (c_unlink(path // "/" // name // c_null_char) /= 0 .and. errno_value == 0) &
                    & errno_value = last_errno()
            end if
            deallocate(name)
        end do
        if (c_closedir(dir) /= 0 .and. errno_value == 0) errno_value = last_errno()
        if (errno_value /= 0) return
        if (c_rmdir(path // c_null_char) /= 0) errno_value = last_errno()
    end function remove_flat_folder

    !> The host's name ("" when it cannot be had).
    function host_name() result(name)
        character(len=:), allocatable :: name
        character(kind=c_char, len=256) :: buffer
        integer :: n

        name = ""
        buffer = repeat(c_null_char, len(buffer))
        if (c_gethostname(buffer, int(len(buffer) - 1, c_size_t)) /= 0) return
        n = index(buffer, c_null_char) - 1
        if (n > 0) name = buffer(:n)
    end function host_name

end module rollcon_system
