! SPDX-License-Identifier: MIT
!> Reads back the CSV that `rollcon run` writes, checking its header and every value, for the
!> plots and animations.
module rollcon_csv_reader
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, input_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type, column_z, column_theta
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use, intrinsic :: ieee_exceptions, only : ieee_set_flag, ieee_overflow, ieee_underflow
    implicit none
    private

    public :: read_output_csv, standard_columns

    !> Length of the column names returned
    integer, parameter, public :: name_length = 64
    !> Largest magnitude a value may have: far beyond any quantity of a run, and small enough
    !> that the pictures' arithmetic (gnuplot's ranges and tick steps, squares in the mesh)
    !> cannot overflow, which it does for values near 1e308
    real(wp), parameter, public :: largest_value = 1.0e100_wp

    !> The columns every output CSV starts with, in order (rollcon_simulation's csv_header);
    !> one residual column per UCON follows
    character(len=*), parameter :: standard_columns(19) = [character(len=9) :: "t", "X", "Y", &
        & "Z", "psi", "theta", "phi", "Xdot", "Ydot", "Zdot", "psidot", "thetadot", "phidot", &
        & "E", "Fx", "Fy", "Fz", "Fn", "mu_needed"]

contains

    !> Read an output CSV: a header line starting with the standard columns, then at least one
    !> row of as many finite numbers (of magnitude at most largest_value) as there are columns,
    !> in time order; plot, animate and the VTK series all read through it. Also infers the disk
    !> radius from the first row, R = Z/sin(theta) (the contact constraint, docs/design.md §5).
    subroutine read_output_csv(path, history, radius, error, names)
        !> CSV file
        character(len=*), intent(in) :: path
        !> Its rows, column by column as in the file
        type(history_type), intent(out) :: history
        !> Disk radius [m]
        real(wp), intent(out) :: radius
        type(error_type), allocatable, intent(out) :: error
        !> The column names of the header (cut to name_length characters)
        character(len=name_length), allocatable, intent(out), optional :: names(:)
        character(len=:), allocatable :: line
        character(len=256) :: message
        real(wp), allocatable :: row(:)
        integer :: unit, stat, columns, line_number

        radius = 0.0_wp
        columns = 0
        open(newunit=unit, file=path, status="old", action="read", iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot open (expected an output CSV of " &
                & // "'rollcon run'): " // trim(message), stat_io)
            return
        end if
        call read_line(unit, line, stat)
        if (stat /= 0) then
            call input_error(error, path, 1, "", "expected a header line, found an empty file")
        else
            call check_header(path, line, columns, error)
            if (present(names) .and. .not. allocated(error)) call split_header(line, names)
        end if
        line_number = 1
        allocate(row(columns))
        do while (.not. allocated(error))
            call read_line(unit, line, stat)
            if (stat /= 0) exit
            line_number = line_number + 1
            if (len_trim(line) == 0) cycle
            call parse_row(path, line_number, line, row, error)
            if (allocated(error)) exit
            if (history%count > 0) then
                if (row(1) < history%rows(1, history%count)) then
                    call input_error(error, path, line_number, "", "rows must be in time " &
                        & // "order, got t = " // to_text(row(1)) // " s after t = " &
                        & // to_text(history%rows(1, history%count)) // " s")
                    exit
                end if
            end if
            call history%add(row)
        end do
        close(unit)
        if (allocated(error)) return
        if (history%count == 0) then
            call input_error(error, path, line_number, "", "expected at least one row of " &
                & // "numbers after the header, found none")
            return
        end if
        associate (z => history%rows(column_z, 1), theta => history%rows(column_theta, 1))
            ! Divide only when the quotient is a positive length no larger than largest_value,
            ! so no floating-point exception is raised.
            if (z > 0.0_wp .and. sin(theta) > 0.0_wp .and. z <= sin(theta)*largest_value) then
                radius = z/sin(theta)
            else
                call input_error(error, path, 2, "", "cannot infer the disk radius: " &
                    & // "Z/sin(theta) must be a positive length, got Z = " // to_text(z) &
                    & // " m, theta = " // to_text(theta) // " rad")
            end if
        end associate
    end subroutine read_output_csv

    !> Check the header line and count its columns.
    subroutine check_header(path, line, columns, error)
        character(len=*), intent(in) :: path, line
        integer, intent(out) :: columns
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: field, expected
        integer :: start, i
        logical :: matches

        expected = trim(standard_columns(1))
        do i = 2, size(standard_columns)
            expected = expected // "," // trim(standard_columns(i))
        end do
        columns = 0
        matches = .true.
        start = 1
        do while (start <= len(line) + 1)
            call next_field(line, start, field)
            columns = columns + 1
            if (columns <= size(standard_columns)) then
                matches = matches .and. field == trim(standard_columns(columns))
            end if
        end do
        if (.not. matches .or. columns < size(standard_columns)) then
            call input_error(error, path, 1, "", "the header must start with " // expected &
                & // " (the columns 'rollcon run' writes), got '" // shortened(line) // "'")
        end if
    end subroutine check_header

    !> The comma-separated names of a header line.
    subroutine split_header(line, names)
        character(len=*), intent(in) :: line
        character(len=name_length), allocatable, intent(out) :: names(:)
        character(len=:), allocatable :: field
        integer :: start, count

        count = 0
        start = 1
        do while (start <= len(line) + 1)
            call next_field(line, start, field)
            count = count + 1
        end do
        allocate(names(count))
        count = 0
        start = 1
        do while (start <= len(line) + 1)
            call next_field(line, start, field)
            count = count + 1
            names(count) = trim(adjustl(field))
        end do
    end subroutine split_header

    !> Read the comma-separated numbers of one row.
    subroutine parse_row(path, line_number, line, row, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: line_number
        character(len=*), intent(in) :: line
        real(wp), intent(out) :: row(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: field
        integer :: start, count, stat

        count = 0
        start = 1
        do while (start <= len(line) + 1)
            call next_field(line, start, field)
            count = count + 1
            if (count > size(row)) cycle
            field = trim(adjustl(field))
            stat = 1
            ! List-directed input would also take '', '/', '3*1.0', '1 2' and '1<tab>2':
            ! refuse them.
            if (len(field) > 0 .and. scan(field, " /*;" // achar(9)) == 0) then
                read(field, *, iostat=stat) row(count)
                ! Reading 1e999 or 1e-999 raises overflow or underflow: the value is refused
                ! or read as it is, so quiet the flags (flags signalling on entry to this
                ! procedure are restored on return).
                call ieee_set_flag([ieee_overflow, ieee_underflow], .false.)
            end if
            if (stat == 0) then
                if (.not. ieee_is_finite(row(count))) stat = 1
            end if
            if (stat /= 0) then
                call input_error(error, path, line_number, "", "value " // to_text(count) &
                    & // " must be a finite number, got '" // shortened(field) // "'")
                return
            end if
            if (abs(row(count)) > largest_value) then
                call input_error(error, path, line_number, "", "value " // to_text(count) &
                    & // " must be at most " // to_text(largest_value) // " in magnitude, got " &
                    & // shortened(field))
                return
            end if
        end do
        if (count /= size(row)) then
            call input_error(error, path, line_number, "", "expected " // to_text(size(row)) &
                & // " comma-separated values (one per header column), got " // to_text(count))
        end if
    end subroutine parse_row

    !> The field of line starting at start, up to the next comma; start moves past the comma
    !> (past the end of the line after the last field).
    subroutine next_field(line, start, field)
        character(len=*), intent(in) :: line
        integer, intent(inout) :: start
        character(len=:), allocatable, intent(out) :: field
        integer :: comma

        comma = index(line(start:), ",")
        if (comma == 0) then
            field = line(start:)
            start = len(line) + 2
        else
            field = line(start:start + comma - 2)
            start = start + comma
        end if
    end subroutine next_field

    !> Read one line of any length; stat is non-zero at the end of the file.
    subroutine read_line(unit, line, stat)
        integer, intent(in) :: unit
        character(len=:), allocatable, intent(out) :: line
        integer, intent(out) :: stat
        character(len=1024) :: buffer
        integer :: length

        line = ""
        do
            read(unit, '(a)', advance="no", iostat=stat, size=length) buffer
            line = line // buffer(:length)
            if (is_iostat_eor(stat)) then
                stat = 0
                exit
            end if
            if (stat /= 0) exit
        end do
        ! Tolerate a file written with CRLF line ends.
        if (len(line) > 0) then
            if (line(len(line):) == achar(13)) line = line(:len(line) - 1)
        end if
    end subroutine read_line

    !> Text for a message, cut to 60 characters.
    pure function shortened(text) result(short)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: short

        if (len(text) > 60) then
            short = text(:57) // "..."
        else
            short = text
        end if
    end function shortened

end module rollcon_csv_reader
