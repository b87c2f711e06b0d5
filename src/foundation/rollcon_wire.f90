! SPDX-License-Identifier: MIT
!> Values packed into bytes and read back, in the order they were packed: how a child process
!> hands its results to its parent (rollcon_isolated_run). Integers are 64-bit, reals doubles,
!> logicals one byte, texts and arrays carry their length first; the bytes are the machine's
!> own (both ends are the same program on the same machine). A reader that runs past the end
!> or meets a length that cannot be stays failed and gives zeros and empty values.
module rollcon_wire
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: wire_writer_type, wire_reader_type

    !> Bytes of an integer and of a real as packed
    integer, parameter :: int_bytes = 8, real_bytes = 8

    !> Values packed so far: bytes(:used)
    type :: wire_writer_type
        character(len=:), allocatable :: bytes
        integer :: used = 0
    contains
        procedure :: put_int
        procedure :: put_ints
        procedure :: put_real
        procedure :: put_reals
        procedure :: put_logical
        procedure :: put_logicals
        procedure :: put_text
        procedure :: packed
    end type wire_writer_type

    !> Bytes to read from position at on
    type :: wire_reader_type
        character(len=:), allocatable :: bytes
        integer :: at = 1
        !> A read ran past the end or met an impossible length
        logical :: failed = .false.
    contains
        procedure :: get_int
        procedure :: get_ints
        procedure :: get_real
        procedure :: get_reals
        procedure :: get_logical
        procedure :: get_logicals
        procedure :: get_text
    end type wire_reader_type

contains

    !> Append raw bytes, growing the storage geometrically.
    subroutine append(self, text)
        class(wire_writer_type), intent(inout) :: self
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: grown

        if (.not. allocated(self%bytes)) allocate(character(len=max(256, len(text))) :: self%bytes)
        if (self%used + len(text) > len(self%bytes)) then
            allocate(character(len=max(2*len(self%bytes), self%used + len(text))) :: grown)
            grown(:self%used) = self%bytes(:self%used)
            call move_alloc(grown, self%bytes)
        end if
        self%bytes(self%used + 1:self%used + len(text)) = text
        self%used = self%used + len(text)
    end subroutine append

    subroutine put_int(self, value)
        class(wire_writer_type), intent(inout) :: self
        integer(int64), intent(in) :: value
        character(len=int_bytes) :: text

        text = transfer(value, text)
        call append(self, text)
    end subroutine put_int

    subroutine put_ints(self, values)
        class(wire_writer_type), intent(inout) :: self
        integer, intent(in) :: values(:)
        integer :: k

        call self%put_int(int(size(values), int64))
        do k = 1, size(values)
            call self%put_int(int(values(k), int64))
        end do
    end subroutine put_ints

    subroutine put_real(self, value)
        class(wire_writer_type), intent(inout) :: self
        real(wp), intent(in) :: value
        character(len=real_bytes) :: text

        text = transfer(value, text)
        call append(self, text)
    end subroutine put_real

    subroutine put_reals(self, values)
        class(wire_writer_type), intent(inout) :: self
        real(wp), intent(in) :: values(:)
        integer :: k

        call self%put_int(int(size(values), int64))
        do k = 1, size(values)
            call self%put_real(values(k))
        end do
    end subroutine put_reals

    subroutine put_logical(self, value)
        class(wire_writer_type), intent(inout) :: self
        logical, intent(in) :: value

        call append(self, merge("T", "F", value))
    end subroutine put_logical

    subroutine put_logicals(self, values)
        class(wire_writer_type), intent(inout) :: self
        logical, intent(in) :: values(:)
        integer :: k

        call self%put_int(int(size(values), int64))
        do k = 1, size(values)
            call self%put_logical(values(k))
        end do
    end subroutine put_logicals

    subroutine put_text(self, text)
        class(wire_writer_type), intent(inout) :: self
        character(len=*), intent(in) :: text

        call self%put_int(int(len(text), int64))
        call append(self, text)
    end subroutine put_text

    !> The bytes packed so far.
    function packed(self) result(bytes)
        class(wire_writer_type), intent(in) :: self
        character(len=:), allocatable :: bytes

        bytes = ""
        if (allocated(self%bytes)) bytes = self%bytes(:self%used)
    end function packed

    !> The next n raw bytes ("" and failed when there are fewer).
    function take(self, n) result(text)
        class(wire_reader_type), intent(inout) :: self
        integer(int64), intent(in) :: n
        character(len=:), allocatable :: text

        text = ""
        if (self%failed .or. .not. allocated(self%bytes)) then
            self%failed = .true.
            return
        end if
        if (n < 0 .or. n > int(len(self%bytes) - self%at + 1, int64)) then
            self%failed = .true.
            return
        end if
        text = self%bytes(self%at:self%at + int(n) - 1)
        self%at = self%at + int(n)
    end function take

    function get_int(self) result(value)
        class(wire_reader_type), intent(inout) :: self
        integer(int64) :: value
        character(len=:), allocatable :: text

        value = 0
        text = take(self, int(int_bytes, int64))
        if (.not. self%failed) value = transfer(text, value)
    end function get_int

    !> A length, refused (failed) beyond what the bytes left can hold at bytes_each a value.
    function get_count(self, bytes_each) result(count)
        class(wire_reader_type), intent(inout) :: self
        integer, intent(in) :: bytes_each
        integer :: count
        integer(int64) :: value

        count = 0
        value = self%get_int()
        if (self%failed) return
        ! compared by division: value*bytes_each could overflow for a forged count near 2**63
        if (value < 0 .or. value > int(len(self%bytes) - self%at + 1, int64)/max(bytes_each, 1)) &
            & then
            self%failed = .true.
            return
        end if
        count = int(value)
    end function get_count

    subroutine get_ints(self, values)
        class(wire_reader_type), intent(inout) :: self
        integer, allocatable, intent(out) :: values(:)
        integer :: k

        allocate(values(get_count(self, int_bytes)))
        do k = 1, size(values)
            values(k) = int(self%get_int())
        end do
    end subroutine get_ints

    function get_real(self) result(value)
        class(wire_reader_type), intent(inout) :: self
        real(wp) :: value
        character(len=:), allocatable :: text

        value = 0.0_wp
        text = take(self, int(real_bytes, int64))
        if (.not. self%failed) value = transfer(text, value)
    end function get_real

    subroutine get_reals(self, values)
        class(wire_reader_type), intent(inout) :: self
        real(wp), allocatable, intent(out) :: values(:)
        integer :: k

        allocate(values(get_count(self, real_bytes)))
        do k = 1, size(values)
            values(k) = self%get_real()
        end do
    end subroutine get_reals

    function get_logical(self) result(value)
        class(wire_reader_type), intent(inout) :: self
        logical :: value

        value = take(self, 1_int64) == "T"
    end function get_logical

    subroutine get_logicals(self, values)
        class(wire_reader_type), intent(inout) :: self
        logical, allocatable, intent(out) :: values(:)
        integer :: k

        allocate(values(get_count(self, 1)))
        do k = 1, size(values)
            values(k) = self%get_logical()
        end do
    end subroutine get_logicals

    function get_text(self) result(text)
        class(wire_reader_type), intent(inout) :: self
        character(len=:), allocatable :: text

        text = take(self, int(get_count(self, 1), int64))
    end function get_text

end module rollcon_wire
