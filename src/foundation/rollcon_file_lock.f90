! SPDX-License-Identifier: MIT
!> An exclusive lock held through a lock file (flock(2) on PATH): one process at a time holds
!> it, and the system lets it go with the process, however that ends (a kill included), so a
!> lock is never left stale. The file names its holder ("process 4242 on host node7") for the
!> message of a process that finds it taken, and is removed when the lock is let go. flock
!> works across the nodes of a cluster on the filesystems Linux emulates it on (NFS: as a
!> POSIX lock); on a filesystem without locks (ENOLCK) the caller goes on unlocked.
!>
!>     type(file_lock_type) :: lock
!>     call lock%acquire("output/study.csv.lock", held, holder, error)
!>     if (held) ... another process has it: holder says which
!>     ...
!>     call lock%release()
module rollcon_file_lock
    use, intrinsic :: iso_c_binding, only : c_int
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_system, only : open_lock_file, lock_exclusive, close_descriptor, &
        & write_descriptor, truncate_descriptor, path_inode, descriptor_inode, remove_file_path, &
        & system_reason, last_errno, errno_would_block, host_name, this_process, &
        & errno_no_locks, errno_not_supported
    use rollcon_input_files, only : read_input_file
    implicit none
    private

    public :: file_lock_type

    !> Attempts when the lock file is removed between our open and our lock (its holder let go)
    integer, parameter :: attempts = 10

    !> A lock, held between acquire and release
    type :: file_lock_type
        character(len=:), allocatable :: path
        integer(c_int) :: fd = -1
    contains
        procedure :: acquire
        procedure :: release
        procedure :: is_held
    end type file_lock_type

contains

    !> Take the lock of path without waiting. held: another process holds it (holder: its
    !> line in the lock file, "" when it wrote none yet). error: the lock file cannot be made
    !> or locked for another reason.
    subroutine acquire(self, path, held, holder, error)
        class(file_lock_type), intent(inout) :: self
        character(len=*), intent(in) :: path
        logical, intent(out) :: held
        character(len=:), allocatable, intent(out) :: holder
        type(error_type), allocatable, intent(out) :: error
        integer :: k, reason
        logical :: ignored

        held = .false.
        holder = ""
        call self%release()
        do k = 1, attempts
            self%fd = open_lock_file(path)
            if (self%fd < 0) then
                call fatal_error(error, path // ": cannot create the lock file: " &
                    & // system_reason(), stat_io)
                return
            end if
            if (.not. lock_exclusive(self%fd)) then
                reason = last_errno()
                ignored = close_descriptor(self%fd)
                self%fd = -1
                ! a filesystem without locks (some network filesystems): nobody can hold one,
                ! so there is nothing to wait for; go on unlocked
                if (reason == errno_no_locks .or. reason == errno_not_supported) return
                if (reason /= errno_would_block) then
                    call fatal_error(error, path // ": cannot lock: " // system_reason(reason), &
                        & stat_io)
                    return
                end if
                held = .true.
                holder = holder_line(path)
                return
            end if
            ! the holder before us may have removed the file after we opened it: then our lock
            ! is on a file nobody else sees; take the one the path names now
            if (descriptor_inode(self%fd) == path_inode(path)) exit
            ignored = close_descriptor(self%fd)
            self%fd = -1
        end do
        if (self%fd < 0) then
            call fatal_error(error, path // ": cannot lock: the lock file keeps being replaced", &
                & stat_io)
            return
        end if
        self%path = path
        if (truncate_descriptor(self%fd, 0_int64)) ignored = write_descriptor(self%fd, &
            & "process " // to_text(this_process()) // " on host " // host_name() &
            & // new_line("a"))
    end subroutine acquire

    !> Let the lock go and remove its file (nothing when it is not held).
    subroutine release(self)
        class(file_lock_type), intent(inout) :: self
        integer :: ignored_errno
        logical :: ignored

        if (self%fd < 0) return
        ! removed first, while still locked: a process that opens it now finds it gone
        ignored_errno = remove_file_path(self%path)
        ignored = close_descriptor(self%fd)
        self%fd = -1
    end subroutine release

    !> True between a successful acquire and release.
    logical function is_held(self)
        class(file_lock_type), intent(in) :: self

        is_held = self%fd >= 0
    end function is_held

    !> The first line of the lock file, "" when it cannot be read.
    function holder_line(path) result(line)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: line
        character(len=:), allocatable :: content
        type(error_type), allocatable :: error
        integer :: cut

        line = ""
        call read_input_file(path, "lock file", 4096_int64, content, error)
        if (allocated(error)) return
        cut = index(content, new_line("a"))
        if (cut == 0) cut = len(content) + 1
        line = content(:cut - 1)
    end function holder_line

end module rollcon_file_lock
