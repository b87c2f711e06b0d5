! SPDX-License-Identifier: MIT
!> A CSV file written cheaply: whole rows are kept in a buffer and written out when it fills,
!> at most every flush_seconds of wall time, on close and on failure, so a run that fails
!> leaves a valid prefix and a crash loses at most a few seconds of rows. Every write and the
!> close are checked: a full disk is an error naming the file.
module rollcon_csv_writer
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_c_stream, only : c_stream_type
    implicit none
    private

    public :: csv_writer_type, csv_row_bytes

    !> Characters of one number in a row: es24.16e3 and its comma (or the line end)
    integer, parameter :: number_bytes = 25
    !> Bytes kept before a write to the file (a few hundred rows of the disk's 22 columns)
    integer, parameter :: buffer_bytes = 65536
    !> Wall time after which buffered rows are written out even if the buffer is not full [s]
    real(wp), parameter, public :: flush_seconds = 1.0_wp

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
        integer :: i

        call self%file%open_file(path, error)
        if (allocated(error)) return
        self%opened = .true.
        self%path = path
        self%columns = size(header)
        if (.not. allocated(self%buffer)) allocate(character(len=buffer_bytes) :: self%buffer)
        self%used = 0
        call system_clock(self%last_flush, self%clock_rate)
        line = trim(header(1))
        do i = 2, size(header)
            line = line // "," // trim(header(i))
        end do
        call append(self, line // new_line("a"), error)
        if (allocated(error)) return
        call self%flush(error)
    end subroutine csv_open

    !> Add one row, with full precision (17 significant digits, three-digit exponents); the
    !> file is written when the buffer is full or flush_seconds have passed.
    subroutine csv_write_row(self, values, error)
        class(csv_writer_type), intent(inout) :: self
        real(wp), intent(in) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=number_bytes*size(values)) :: line
        integer(int64) :: now

        if (.not. self%opened) then
            call fatal_error(error, "CSV output: a row written to a file that is not open", &
                & stat_io)
            return
        end if
        if (size(values) /= self%columns) then
            call fatal_error(error, self%path // ": a row of wrong length", stat_io)
            return
        end if
        write(line, '(*(es24.16e3, :, ","))') values
        call append(self, trim(line) // new_line("a"), error)
        if (allocated(error)) return
        call system_clock(now)
        if (real(now - self%last_flush, wp) >= flush_seconds*real(self%clock_rate, wp)) then
            call self%flush(error)
        end if
    end subroutine csv_write_row

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
