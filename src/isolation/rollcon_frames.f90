! SPDX-License-Identifier: MIT
!> Frames on a pipe from a child process to its parent: each a kind (a small integer the two
!> ends agree on), a length and that many bytes. The child writes whole frames (write(2), every
!> byte, a broken pipe reported); the parent collects what the pipe gives in a buffer and takes
!> whole frames out of it as they complete.
module rollcon_frames
    use, intrinsic :: iso_c_binding, only : c_int, c_size_t, c_long, c_char
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type, fatal_error, stat_io
    implicit none
    private

    public :: send_frame, frame_buffer_type

    !> Bytes of a frame's head: its kind and its length, 8 bytes each
    integer, parameter :: head_bytes = 16

    !> What the pipe gave so far that is not yet taken as frames: bytes(first:used)
    type :: frame_buffer_type
        character(len=:), allocatable :: bytes
        integer :: first = 1, used = 0
    contains
        procedure :: add
        procedure :: next
    end type frame_buffer_type

    interface
        function c_write(fd, buffer, count) result(written) bind(c, name="write")
            import :: c_int, c_size_t, c_long, c_char
            integer(c_int), value :: fd
            character(kind=c_char), intent(in) :: buffer(*)
            integer(c_size_t), value :: count
            integer(c_long) :: written
        end function c_write
    end interface

contains

    !> Write one frame to fd, every byte of it.
    subroutine send_frame(fd, kind, payload, error)
        integer, intent(in) :: fd, kind
        character(len=*), intent(in) :: payload
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: frame
        character(len=8) :: field
        integer(c_long) :: written
        integer :: done

        frame = transfer(int(kind, int64), field) // transfer(int(len(payload), int64), field) &
            & // payload
        done = 0
        do while (done < len(frame))
            written = c_write(int(fd, c_int), frame(done + 1:), int(len(frame) - done, c_size_t))
            if (written <= 0) then
                call fatal_error(error, "cannot hand the results to the parent process (its " &
                    & // "pipe is closed: did it end?)", stat_io)
                return
            end if
            done = done + int(written)
        end do
    end subroutine send_frame

    !> Keep bytes the pipe gave.
    subroutine add(self, bytes)
        class(frame_buffer_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        character(len=:), allocatable :: grown

        if (.not. allocated(self%bytes)) allocate(character(len=65536) :: self%bytes)
        if (self%first > 1) then
            ! drop what was taken: the rest moves to the front
            self%bytes(:self%used - self%first + 1) = self%bytes(self%first:self%used)
            self%used = self%used - self%first + 1
            self%first = 1
        end if
        if (self%used + len(bytes) > len(self%bytes)) then
            allocate(character(len=max(2*len(self%bytes), self%used + len(bytes))) :: grown)
            grown(:self%used) = self%bytes(:self%used)
            call move_alloc(grown, self%bytes)
        end if
        self%bytes(self%used + 1:self%used + len(bytes)) = bytes
        self%used = self%used + len(bytes)
    end subroutine add

    !> Take the next whole frame out of the buffer: found false when it is not complete yet.
    !> A frame whose length cannot be (negative) gives kind -1.
    subroutine next(self, kind, payload, found)
        class(frame_buffer_type), intent(inout) :: self
        integer, intent(out) :: kind
        character(len=:), allocatable, intent(out) :: payload
        logical, intent(out) :: found
        integer(int64) :: head(2)
        integer :: total

        found = .false.
        kind = 0
        payload = ""
        if (self%used - self%first + 1 < head_bytes) return
        head = transfer(self%bytes(self%first:self%first + head_bytes - 1), head)
        if (head(2) < 0 .or. head(2) > huge(1) - head_bytes) then
            kind = -1
            found = .true.
            self%first = 1
            self%used = 0
            return
        end if
        total = head_bytes + int(head(2))
        if (self%used - self%first + 1 < total) return
        kind = int(head(1))
        payload = self%bytes(self%first + head_bytes:self%first + total - 1)
        self%first = self%first + total
        found = .true.
    end subroutine next

end module rollcon_frames
