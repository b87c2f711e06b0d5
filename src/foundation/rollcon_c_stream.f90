! SPDX-License-Identifier: MIT
!> Output files written through C stdio (fopen, fwrite, fflush, fclose), because gfortran 12's
!> runtime drops the error of a failed write when it flushes or closes a unit: a full disk
!> then looks like success. Every call here is checked, and a failure is an error naming the
!> file and the system's reason ("No space left on device").
module rollcon_c_stream
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_associated, c_int, c_size_t, &
        & c_char, c_null_char
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_system, only : system_reason
    implicit none
    private

    public :: c_stream_type

    !> A file open for writing
    type :: c_stream_type
        !> The C FILE pointer; null when closed
        type(c_ptr) :: file = c_null_ptr
        !> Path, for messages
        character(len=:), allocatable :: path
    contains
        procedure :: open_file => stream_open
        procedure :: put => stream_write
        procedure :: hand_over => stream_flush
        procedure :: close_file => stream_close
        procedure :: is_open => stream_is_open
    end type c_stream_type

    interface
        function c_fopen(path, mode) result(file) bind(c, name="fopen")
            import :: c_ptr, c_char
            character(kind=c_char), intent(in) :: path(*), mode(*)
            type(c_ptr) :: file
        end function c_fopen
        function c_fwrite(data, size, count, file) result(written) bind(c, name="fwrite")
            import :: c_ptr, c_size_t, c_char
            character(kind=c_char), intent(in) :: data(*)
            integer(c_size_t), value :: size, count
            type(c_ptr), value :: file
            integer(c_size_t) :: written
        end function c_fwrite
        function c_fflush(file) result(stat) bind(c, name="fflush")
            import :: c_ptr, c_int
            type(c_ptr), value :: file
            integer(c_int) :: stat
        end function c_fflush
        function c_setvbuf(file, buffer, mode, size) result(stat) bind(c, name="setvbuf")
            import :: c_ptr, c_int, c_size_t
            type(c_ptr), value :: file, buffer
            integer(c_int), value :: mode
            integer(c_size_t), value :: size
            integer(c_int) :: stat
        end function c_setvbuf
        function c_fclose(file) result(stat) bind(c, name="fclose")
            import :: c_ptr, c_int
            type(c_ptr), value :: file
            integer(c_int) :: stat
        end function c_fclose
    end interface

contains

    !> Create (replace) the file for writing, or open it to append to it.
    subroutine stream_open(self, path, error, append, unbuffered)
        class(c_stream_type), intent(inout) :: self
        !> File to write
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        !> Append to the file (created when missing) instead of replacing it
        logical, intent(in), optional :: append
        !> No stdio buffer: each put is one write to the system (a caller that buffers whole
        !> lines itself, so that a killed process never leaves a line cut by stdio)
        logical, intent(in), optional :: unbuffered
        !> _IONBF of glibc's stdio.h
        integer(c_int), parameter :: no_buffering = 2
        character(len=2) :: mode

        mode = "wb"
        if (present(append)) then
            if (append) mode = "ab"
        end if
        self%path = path
        self%file = c_fopen(path // c_null_char, mode // c_null_char)
        if (.not. c_associated(self%file)) then
            call fatal_error(error, path // ": cannot write: " // system_reason(), stat_io)
            return
        end if
        if (present(unbuffered)) then
            if (unbuffered) then
                if (c_setvbuf(self%file, c_null_ptr, no_buffering, 0_c_size_t) /= 0) &
                    & call fatal_error(error, path // ": cannot write unbuffered", stat_io)
            end if
        end if
    end subroutine stream_open

    !> Write text (C stdio buffers it).
    subroutine stream_write(self, text, error)
        class(c_stream_type), intent(inout) :: self
        character(len=*), intent(in) :: text
        type(error_type), allocatable, intent(out) :: error

        if (len(text) == 0) return
        if (.not. c_associated(self%file)) then
            call fatal_error(error, "write to a file that is not open", stat_io)
        else if (c_fwrite(text, 1_c_size_t, int(len(text), c_size_t), self%file) &
            & /= int(len(text), c_size_t)) then
            call fatal_error(error, self%path // ": write failed: " // system_reason(), stat_io)
        end if
    end subroutine stream_write

    !> Hand everything written so far to the system.
    subroutine stream_flush(self, error)
        class(c_stream_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error

        if (.not. c_associated(self%file)) return
        if (c_fflush(self%file) /= 0) then
            call fatal_error(error, self%path // ": write failed: " // system_reason(), stat_io)
        end if
    end subroutine stream_flush

    !> Flush and close; the file is closed even when that fails (error then says why).
    subroutine stream_close(self, error)
        class(c_stream_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flushed, closed

        if (.not. c_associated(self%file)) return
        flushed = c_fflush(self%file)
        if (flushed /= 0) call fatal_error(error, self%path // ": write failed: " &
            & // system_reason(), stat_io)
        closed = c_fclose(self%file)
        self%file = c_null_ptr
        if (closed /= 0 .and. flushed == 0) call fatal_error(error, self%path &
            & // ": closing failed: " // system_reason(), stat_io)
    end subroutine stream_close

    !> True between open and close.
    logical function stream_is_open(self)
        class(c_stream_type), intent(in) :: self

        stream_is_open = c_associated(self%file)
    end function stream_is_open

end module rollcon_c_stream
