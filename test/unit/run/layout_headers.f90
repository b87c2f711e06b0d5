! SPDX-License-Identifier: MIT
!> The layout suite's header tests: read_layout gives back the layout of every header the
!> layout writes (and of the disk scenes' header as docs/outputs.md prints it), and refuses
!> each kind of bad header with its exact message.
module layout_headers
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : output_layout_type, new_output_layout, read_layout, &
        & name_length
    use rollcon_watch_columns, only : contact_names
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_good_headers, test_bad_headers

    !> The disk scenes' header, as docs/outputs.md prints it
    character(len=*), parameter :: disk_header = "t,X_1,Y_1,Z_1,psi_1,theta_1,phi_1,Xdot_1," &
        & // "Ydot_1,Zdot_1,psidot_1,thetadot_1,phidot_1,E,F_1,F_2,F_3,lambda_1,lambda_2," &
        & // "lambda_3,Fx,Fy,Fz,Fn,mu_needed,height_residual"
    !> The header of the rows before the layout (refused: its columns have no part id)
    character(len=*), parameter :: old_header = "t,X,Y,Z,psi,theta,phi,Xdot,Ydot,Zdot,psidot," &
        & // "thetadot,phidot,E,Fx,Fy,Fz,Fn,mu_needed,F1,F2,F3,height_residual"

contains

    !> Layouts of one to three parts, with and without UCONs and the contact, read back from
    !> their headers; the documented disk header reads as one part, UCONs 1-3 and the contact.
    subroutine test_good_headers(error)
        type(error_type), allocatable, intent(out) :: error
        type(output_layout_type) :: layouts(5), read_back
        character(len=:), allocatable :: message
        integer :: i

        layouts = [new_output_layout([2, 5], [11, 12, 13]), &
            & new_output_layout([1], [1, 2, 3], contact_names), &
            & new_output_layout([7], [integer ::]), &
            & new_output_layout([1], [integer ::], contact_names), &
            & new_output_layout([3, 40, 10], [9], contact_names)]
        do i = 1, size(layouts)
            call read_layout(layouts(i)%header(), read_back, message)
            if (allocated(message)) then
                call check(error, .false., "layout " // to_text(i) // ": " // message)
                return
            end if
            call check(error, size(read_back%part_ids) == size(layouts(i)%part_ids) &
                & .and. size(read_back%ucon_ids) == size(layouts(i)%ucon_ids), &
                & "layout " // to_text(i) // ": counts of parts or UCONs differ")
            if (allocated(error)) return
            call check(error, all(read_back%part_ids == layouts(i)%part_ids) &
                & .and. all(read_back%ucon_ids == layouts(i)%ucon_ids) &
                & .and. all(read_back%extra == layouts(i)%extra) &
                & .and. read_back%columns() == layouts(i)%columns(), "layout " // to_text(i) &
                & // ": read back differently")
            if (allocated(error)) return
        end do
        call read_layout(split(disk_header), read_back, message)
        if (allocated(message)) then
            call check(error, .false., "disk header: " // message)
            return
        end if
        call check(error, size(read_back%part_ids) == 1 .and. size(read_back%ucon_ids) == 3 &
            & .and. read_back%column("Fn") == 24 .and. read_back%columns() == 26, &
            & "disk header read as " &
            & // to_text(size(read_back%part_ids)) // " parts, " &
            & // to_text(size(read_back%ucon_ids)) // " UCONs")
        if (allocated(error)) return
        call check(error, read_back%part_ids(1) == 1 .and. all(read_back%ucon_ids == [1, 2, 3]), &
            & "disk header: part or UCON ids")
    end subroutine test_good_headers

    !> Each kind of bad header, with its exact message.
    subroutine test_bad_headers(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=name_length), allocatable :: one_part(:), two_parts(:)
        type(output_layout_type) :: layout

        layout = new_output_layout([1], [1])
        one_part = layout%header()
        layout = new_output_layout([2, 5], [integer ::])
        two_parts = layout%header()
        call refused([character(len=name_length) ::], &
            & "expected a header starting with t, found no column", error)
        if (allocated(error)) return
        call refused([character(len=name_length) :: "time", "X_1"], &
            & "column 1 must be t, got 'time'", error)
        if (allocated(error)) return
        call refused(split(old_header), "column 2 must be X_<part id>, got 'X'", error)
        if (allocated(error)) return
        call refused([character(len=name_length) :: "t", "X_1", "Y_1"], "expected groups of " &
            & // "12 part columns (X_<id> ... phidot_<id>) after t, then E", error)
        if (allocated(error)) return
        call refused([character(len=name_length) :: one_part(:14), "F_a", "lambda_1"], &
            & "column 15 must be F_<UCON id>, got 'F_a'", error)
        if (allocated(error)) return
        call refused([character(len=name_length) :: one_part, "x"], "column 17 must be one " &
            & // "of Fx, Fy, Fz, Fn, mu_needed, height_residual, basis_<id>, got 'x'", error)
        if (allocated(error)) return
        call refused([character(len=name_length) :: one_part, "basis_7"], "column 17 must be " &
            & // "one of Fx, Fy, Fz, Fn, mu_needed, height_residual, basis_<id>, got 'basis_7'", &
            & error)
        if (allocated(error)) return
        call refused([character(len=name_length) :: one_part(:15), "lambda_2"], &
            & "column 16 must be lambda_1, got 'lambda_2'", error)
        if (allocated(error)) return
        two_parts(3) = "Y_1"
        call refused(two_parts, "column 3 must be Y_2, got 'Y_1'", error)
    end subroutine test_bad_headers

    !> read_layout refuses names with exactly this message.
    subroutine refused(names, expected, error)
        character(len=*), intent(in) :: names(:), expected
        type(error_type), allocatable, intent(out) :: error
        type(output_layout_type) :: layout
        character(len=:), allocatable :: message

        call read_layout(names, layout, message, [character(len=name_length) :: contact_names, &
            & "basis_<id>"])
        call check(error, allocated(message), "accepted: " // expected)
        if (allocated(error)) return
        call check(error, message == expected, "message '" // message // "', expected '" &
            & // expected // "'")
    end subroutine refused

    !> The comma-separated names of a header line.
    pure function split(line) result(names)
        character(len=*), intent(in) :: line
        character(len=name_length), allocatable :: names(:)
        integer :: start, comma, i

        allocate(names(count([(line(i:i) == ",", i = 1, len(line))]) + 1))
        start = 1
        do i = 1, size(names)
            comma = index(line(start:), ",")
            if (comma == 0) then
                names(i) = line(start:)
            else
                names(i) = line(start:start + comma - 2)
                start = start + comma
            end if
        end do
    end function split

end module layout_headers
