! SPDX-License-Identifier: MIT
!> A CSV file written row by row and flushed after each row, so that a run that fails leaves
!> a valid prefix.
module rollcon_csv_writer
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    implicit none
    private

    public :: csv_writer_type

    !> An open CSV file
    type :: csv_writer_type
        integer :: unit = 0
        !> True between open and close
        logical :: opened = .false.
        integer :: columns = 0
        character(len=:), allocatable :: path
    contains
        procedure :: open => csv_open
        procedure :: write_row => csv_write_row
        procedure :: close => csv_close
    end type csv_writer_type

contains

    !> Create (replace) the file and write the header line.
    subroutine csv_open(self, path, header, error)
        class(csv_writer_type), intent(inout) :: self
        character(len=*), intent(in) :: path
        !> Column names
        character(len=*), intent(in) :: header(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: message
        integer :: stat, i

        open(newunit=self%unit, file=path, status="replace", action="write", iostat=stat, &
            & iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write: " // trim(message), stat_io)
            return
        end if
        self%opened = .true.
        self%path = path
        self%columns = size(header)
        do i = 1, size(header)
            if (i < size(header)) then
                write(self%unit, '(a)', advance="no") trim(header(i)) // ","
            else
                write(self%unit, '(a)') trim(header(i))
            end if
        end do
        flush(self%unit)
    end subroutine csv_open

    !> Write one row with full precision and flush it.
    subroutine csv_write_row(self, values, error)
        class(csv_writer_type), intent(inout) :: self
        real(wp), intent(in) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: message
        integer :: stat

        if (size(values) /= self%columns) then
            call fatal_error(error, self%path // ": a row of " // "wrong length", stat_io)
            return
        end if
        write(self%unit, '(*(es24.16e3, :, ","))', iostat=stat, iomsg=message) values
        if (stat == 0) flush(self%unit, iostat=stat)
        if (stat /= 0) call fatal_error(error, self%path // ": write failed: " // trim(message), &
            & stat_io)
    end subroutine csv_write_row

    !> Close the file.
    subroutine csv_close(self)
        class(csv_writer_type), intent(inout) :: self

        if (self%opened) close(self%unit)
        self%opened = .false.
    end subroutine csv_close

end module rollcon_csv_writer
