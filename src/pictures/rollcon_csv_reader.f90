! SPDX-License-Identifier: MIT
!> Reads back the CSV that `rollcon run` writes, checking its header (through the output layout,
!> rollcon_output_layout) and every value, for the plots, animations and VTK series.
module rollcon_csv_reader
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, input_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_history, only : history_type
    use rollcon_output_layout, only : output_layout_type, read_layout, name_length
    use rollcon_input_files, only : input_file_type, csv_input_limit
    use rollcon_watch_columns, only : answer_column_patterns
    use rollcon_watch_columns, only : contact_names, contact_mode_names, dissipation_names, &
        & contact_column_patterns, &
        & basis_pattern, request_column_patterns, motion_column_patterns, &
        & reaction_column_patterns, variable_column_patterns, diff_column_patterns, &
        & element_reaction_column_patterns, element_force_column_patterns
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use, intrinsic :: ieee_exceptions, only : ieee_set_flag, ieee_overflow, ieee_underflow
    implicit none
    private

    public :: read_output_csv

    !> Largest magnitude a value may have: far beyond any quantity of a run, and small enough
    !> that the pictures' arithmetic (gnuplot's ranges and tick steps, squares in the mesh)
    !> cannot overflow, which it does for values near 1e308
    real(wp), parameter, public :: largest_value = 1.0e100_wp

contains

    !> Read an output CSV: a header line that the output layout reads (t, then X_<id> ...
    !> phidot_<id> per part, E, F_<id> and lambda_<id> per UCON, and the contact columns of a
    !> disk scene), then at least one row of as many finite numbers (of magnitude at most
    !> largest_value) as there are columns, in time order. Plot, animate and the VTK series all
    !> read through it.
    subroutine read_output_csv(path, layout, history, error)
        !> CSV file
        character(len=*), intent(in) :: path
        !> Its columns: which parts and UCONs, and whether the contact columns are there
        type(output_layout_type), intent(out) :: layout
        !> Its rows, column by column as in the file
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: line
        real(wp), allocatable :: row(:)
        type(input_file_type) :: file
        integer :: line_number
        logical :: exists, done

        inquire(file=path, exist=exists)
        if (.not. exists) then
            call fatal_error(error, path // ": cannot open (expected an output CSV of " &
                & // "'rollcon run'): no such file", stat_io)
            return
        end if
        ! a regular file of at most csv_input_limit bytes (rollcon_input_files)
        call file%open(path, "output CSV", csv_input_limit, error)
        if (allocated(error)) return
        call read_line(file, line, done, error)
        if (allocated(error)) then
            call file%close()
            return
        end if
        if (done) then
            call input_error(error, path, 1, "", "expected a header line, found an empty file")
        else
            call check_header(path, line, layout, error)
        end if
        line_number = 1
        if (.not. allocated(error)) allocate(row(layout%columns()))
        do while (.not. allocated(error))
            call read_line(file, line, done, error)
            if (done .or. allocated(error)) exit
            line_number = line_number + 1
            if (len_trim(line) == 0) cycle
            call parse_row(path, line_number, line, row, error)
            ! a last line without its end that does not read is the torn tail of a run killed
            ! while it wrote (docs/outputs.md): the rows before it are the run's, whole
            if (allocated(error) .and. file%unterminated) then
                deallocate(error)
                exit
            end if
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
        call file%close()
        if (allocated(error)) return
        history%layout = layout
        if (history%count == 0) call input_error(error, path, line_number, "", "expected at " &
            & // "least one row of numbers after the header, found none")
    end subroutine read_output_csv

    !> The layout of the header line, or an error naming the file, line 1 and the reason.
    subroutine check_header(path, line, layout, error)
        character(len=*), intent(in) :: path, line
        type(output_layout_type), intent(out) :: layout
        type(error_type), allocatable, intent(out) :: error
        character(len=name_length), allocatable :: names(:)
        character(len=:), allocatable :: field, message
        integer :: start, count

        count = 0
        start = 1
        do while (start <= len(line) + 1)
            call next_field(line, start, field)
            count = count + 1
            if (len_trim(adjustl(field)) > name_length) then
                call input_error(error, path, 1, "", "column " // to_text(count) // " of the " &
                    & // "header is not a column name 'rollcon run' writes (longer than " &
                    & // to_text(name_length) // " characters): '" // shortened(field) // "'")
                return
            end if
        end do
        allocate(names(count))
        count = 0
        start = 1
        do while (start <= len(line) + 1)
            call next_field(line, start, field)
            count = count + 1
            names(count) = trim(adjustl(field))
        end do
        ! the watches' columns rollcon writes: a rim contact's (and its modes'; of several
        ! contacts each one's after its prefix), a rim's
        ! dissipation's, a part's principal basis, a dataset's displacement requests, its
        ! MOTIONs' forces, its other requests, the statements' reactions (the elements' of one
        ! equation too), its SPRINGDAMPERs' and BUSHINGs' forces, its VARIABLEs' values, its
        ! DIFFs' states
        call read_layout(names, layout, message, [character(len=name_length) :: contact_names, &
            & contact_mode_names, dissipation_names, basis_pattern, request_column_patterns, &
            & motion_column_patterns, answer_column_patterns, reaction_column_patterns, &
            & element_reaction_column_patterns, element_force_column_patterns, &
            & variable_column_patterns, diff_column_patterns, contact_column_patterns])
        if (.not. allocated(message)) return
        ! A one-part header without the part's id (t, X, ...): say what it is.
        if (count > 1) then
            if (names(1) == "t" .and. names(2) == "X") message = message // " (a CSV of an " &
                & // "older rollcon, whose columns did not name the part: run the scene again)"
        end if
        call input_error(error, path, 1, "", "not the header 'rollcon run' writes: " // message)
    end subroutine check_header

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

    !> Read one line of any length; done at the end of the file.
    subroutine read_line(file, line, done, error)
        type(input_file_type), intent(inout) :: file
        character(len=:), allocatable, intent(out) :: line
        logical, intent(out) :: done
        type(error_type), allocatable, intent(out) :: error

        ! lines end at LF, CR LF or CR: a file written with CRLF line ends reads as well
        call file%next_line(line, done, error)
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
