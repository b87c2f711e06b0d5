! SPDX-License-Identifier: MIT
!> A CSV file written cheaply: each row is made text in C (rollcon_row_text.c: the characters of
!> Fortran's es24.16e3, in exact integer arithmetic for the usual magnitudes and by the C library's
!> conversion for the others, at a fraction of Fortran's cost), whole rows are kept in a buffer and
!> handed to the system in one write when it fills, at least every flush_seconds of wall time, on
!> close and on failure, so a run that fails or is killed leaves a valid prefix and a crash loses
!> at most about a second of rows. Every write and the close are checked: a full disk is an error
!> naming the file.
module rollcon_csv_writer
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: iso_c_binding, only : c_int, c_double, c_char
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_c_stream, only : c_stream_type
    implicit none
    private

    public :: csv_writer_type, csv_row_bytes, row_text, fortran_row_text

    !> Characters of one number in a row: es24.16e3 and its comma (or the line end)
    integer, parameter :: number_bytes = 25
    !> Bytes kept before a write to the file (a few hundred rows of the disk's 22 columns)
    integer, parameter :: buffer_bytes = 65536
    !> Wall time after which buffered rows are written out even if the buffer is not full [s]
    real(wp), parameter, public :: flush_seconds = 1.0_wp

    interface
        !> values as one line of es24.16e3 numbers separated by commas; its length, or -1
        !> when capacity is too small (rollcon_row_text.c)
        function c_row_text(values, count, line, capacity) result(length) &
                & bind(c, name="rollcon_row_text")
            import :: c_int, c_double, c_char
            real(c_double), intent(in) :: values(*)
            integer(c_int), value :: count, capacity
            character(kind=c_char), intent(out) :: line(*)
            integer(c_int) :: length
        end function c_row_text
    end interface

    !> An open CSV file
    type :: csv_writer_type
        !> The file, written through C stdio so that every failure is seen (rollcon_c_stream)
        type(c_stream_type) :: file
        !> True between open and close
        logical :: opened = .false.
        integer :: columns = 0
        character(len=:), allocatable :: path
        !> Rows not yet written to the file: buffer(:used)
        character(len=:), allocatable :: buffer
        integer :: used = 0
        !> Wall clock (system_clock counts) of the last write to the file, and counts per second
        integer(int64) :: last_flush = 0, clock_rate = 1
    contains
        procedure :: open => csv_open
        procedure :: write_row => csv_write_row
        procedure :: flush => csv_flush
        procedure :: close => csv_close
    end type csv_writer_type

contains

    !> Bytes of one row of a CSV of this many columns (the header aside).
    pure function csv_row_bytes(columns) result(bytes)
        !> Number of columns
        integer, intent(in) :: columns
        integer :: bytes

        bytes = number_bytes*columns
    end function csv_row_bytes

    !> Create (replace) the file and write the header line.
    subroutine csv_open(self, path, header, error)
        class(csv_writer_type), intent(inout) :: self
        character(len=*), intent(in) :: path
        !> Column names
        character(len=*), intent(in) :: header(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: line
        integer :: i, at, width

        ! unbuffered by C stdio: the writer keeps whole rows itself, so each flush is one
        ! write of whole lines to the system
        call self%file%open_file(path, error, unbuffered=.true.)
        if (allocated(error)) return
        self%opened = .true.
        self%path = path
        self%columns = size(header)
        if (.not. allocated(self%buffer)) allocate(character(len=buffer_bytes) :: self%buffer)
        self%used = 0
        call system_clock(self%last_flush, self%clock_rate)
        ! the header's length counted first, then filled (thousands of columns of a long
        ! chain: the line grown by a copy per column took a sizeable share of its start-up)
        allocate(character(len=sum(len_trim(header)) + size(header) - 1) :: line)
        at = 0
        do i = 1, size(header)
            if (i > 1) then
                line(at + 1:at + 1) = ","
                at = at + 1
            end if
            width = len_trim(header(i))
            line(at + 1:at + width) = header(i)(:width)
            at = at + width
        end do
        call append(self, line // new_line("a"), error)
        if (allocated(error)) return
        call self%flush(error)
    end subroutine csv_open

    !> Add one row, with full precision (17 significant digits, three-digit exponents); the
    !> file is written when the buffer is full or flush_seconds have passed (a clock read per
    !> row, 20 ns against the row's microseconds).
    subroutine csv_write_row(self, values, error)
        class(csv_writer_type), intent(inout) :: self
        real(wp), intent(in) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        ! the row's text and its line end, appended at once (no concatenation's copy)
        character(len=number_bytes*size(values) + 1) :: line
        integer(int64) :: now
        integer :: length

        if (.not. self%opened) then
            call fatal_error(error, "CSV output: a row written to a file that is not open", &
                & stat_io)
            return
        end if
        if (size(values) /= self%columns) then
            call fatal_error(error, self%path // ": a row of wrong length", stat_io)
            return
        end if
        call row_text(values, line, length)
        line(length + 1:length + 1) = new_line("a")
        call append(self, line(:length + 1), error)
        if (allocated(error)) return
        call system_clock(now)
        if (real(now - self%last_flush, wp) >= flush_seconds*real(self%clock_rate, wp)) then
            call self%flush(error)
        end if
    end subroutine csv_write_row

    !> values as the characters of a row (no line end) in line(:length), exactly as
    !> fortran_row_text makes them; line holds at least number_bytes per value.
    subroutine row_text(values, line, length)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(out) :: line
        integer, intent(out) :: length

        length = int(c_row_text(values, int(size(values), c_int), line, int(len(line), c_int)))
    end subroutine row_text

    !> The same row by Fortran's formatted write, '(*(es24.16e3, :, ","))' and trim: the
    !> definition of a row's characters, which row_text must reproduce (the csv-writer suite
    !> compares them), and the cost it saves (rollcon bench's unit costs).
    function fortran_row_text(values) result(text)
        real(wp), intent(in) :: values(:)
        character(len=:), allocatable :: text
        character(len=number_bytes*size(values)) :: line

        write(line, '(*(es24.16e3, :, ","))') values
        text = trim(line)
    end function fortran_row_text

    !> Write the buffered rows to the file and flush it.
    subroutine csv_flush(self, error)
        class(csv_writer_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error

        if (.not. self%opened) return
        call self%file%put(self%buffer(:self%used), error)
        self%used = 0
        if (.not. allocated(error)) call self%file%hand_over(error)
        call system_clock(self%last_flush)
    end subroutine csv_flush

    !> Write what is buffered and close the file; error is set when a write or the close
    !> fails (e.g. the disk is full). The file is closed in any case.
    subroutine csv_close(self, error)
        class(csv_writer_type), intent(inout) :: self
        type(error_type), allocatable, intent(out), optional :: error
        type(error_type), allocatable :: failure, close_failure

        if (.not. self%opened) return
        call self%flush(failure)
        call self%file%close_file(close_failure)
        self%opened = .false.
        if (.not. allocated(failure) .and. allocated(close_failure)) &
            & call move_alloc(close_failure, failure)
        if (present(error) .and. allocated(failure)) call move_alloc(failure, error)
    end subroutine csv_close

    !> Add text to the buffer, writing the buffer out first when the text would not fit.
    subroutine append(self, text, error)
        type(csv_writer_type), intent(inout) :: self
        character(len=*), intent(in) :: text
        type(error_type), allocatable, intent(out) :: error

        if (self%used + len(text) > len(self%buffer)) then
            call self%flush(error)
            if (allocated(error)) return
        end if
        if (len(text) > len(self%buffer)) then
            ! A row longer than the buffer (hundreds of columns) goes out whole.
            deallocate(self%buffer)
            allocate(character(len=len(text)) :: self%buffer)
        end if
        self%buffer(self%used + 1:self%used + len(text)) = text
        self%used = self%used + len(text)
    end subroutine append

end module rollcon_csv_writer
