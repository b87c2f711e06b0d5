! SPDX-License-Identifier: MIT
!> One UCON's part of a check report packed into bytes and read back (rollcon_wire): how an
!> isolated checker's child hands its findings to the host, as one frame on its pipe.
!>
!> Every allocatable component travels with a flag saying whether it is allocated, so what
!> arrives is what was sent, unallocated parts included. The reader trusts nothing: a length
!> that the bytes left cannot hold, bytes missing or bytes left over make the whole report an
!> error, never a guess or a long read.
module rollcon_audit_transfer
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_wire, only : wire_writer_type, wire_reader_type
    use rollcon_ucosub_audit, only : ucon_report_type, finding_group_type
    implicit none
    private

    public :: pack_ucon_report, unpack_ucon_report

    !> First and last value of a packed report: a report cut short or spliced shows
    integer(int64), parameter :: report_mark = int(z'52434F4E52455054', int64)
    !> Smallest number of bytes a packed group takes (for the bound on the group count)
    integer, parameter :: group_bytes = 64

contains

    !> Pack ucon into wire.
    subroutine pack_ucon_report(wire, ucon)
        !> Where the bytes go
        type(wire_writer_type), intent(inout) :: wire
        !> The UCON's report
        type(ucon_report_type), intent(in) :: ucon
        integer :: g

        call wire%put_int(report_mark)
        call wire%put_int(int(ucon%id, int64))
        call put_reals(wire, ucon%par)
        call wire%put_logical(ucon%declared)
        call put_ints(wire, ucon%parts)
        call put_ints(wire, ucon%codes)
        call wire%put_int(int(ucon%states, int64))
        call wire%put_int(int(ucon%compared, int64))
        call wire%put_int(int(ucon%not_checkable, int64))
        call wire%put_real(ucon%worst)
        call wire%put_logical(allocated(ucon%groups))
        if (allocated(ucon%groups)) then
            call wire%put_int(int(size(ucon%groups), int64))
            do g = 1, size(ucon%groups)
                call pack_group(wire, ucon%groups(g))
            end do
        end if
        call wire%put_int(report_mark)
    end subroutine pack_ucon_report

    !> Read what pack_ucon_report packed: every byte, no more.
    subroutine unpack_ucon_report(bytes, ucon, error)
        !> The packed report
        character(len=*), intent(in) :: bytes
        !> The UCON's report
        type(ucon_report_type), intent(out) :: ucon
        !> Set when the bytes are not one whole report
        type(error_type), allocatable, intent(out) :: error
        type(wire_reader_type) :: wire
        integer(int64) :: count
        integer :: g

        wire%bytes = bytes
        if (wire%get_int() /= report_mark) wire%failed = .true.
        ucon%id = int(wire%get_int())
        call get_reals(wire, ucon%par)
        ucon%declared = wire%get_logical()
        call get_ints(wire, ucon%parts)
        call get_ints(wire, ucon%codes)
        ucon%states = int(wire%get_int())
        ucon%compared = int(wire%get_int())
        ucon%not_checkable = int(wire%get_int())
        ucon%worst = wire%get_real()
        if (wire%get_logical()) then
            count = wire%get_int()
            if (count < 0 .or. count > int(len(bytes) / group_bytes, int64)) wire%failed = .true.
            if (wire%failed) count = 0
            allocate(ucon%groups(count))
            do g = 1, int(count)
                call unpack_group(wire, ucon%groups(g))
                if (wire%failed) exit
            end do
        end if
        if (wire%get_int() /= report_mark) wire%failed = .true.
        if (wire%failed .or. wire%at /= len(bytes) + 1) then
            call fatal_error(error, "the report of a UCON sent back by its checking process " &
                & // "is damaged (" // to_text(len(bytes)) // " bytes, not one whole report)", &
                & stat_io)
        end if
    end subroutine unpack_ucon_report

    subroutine pack_group(wire, group)
        type(wire_writer_type), intent(inout) :: wire
        type(finding_group_type), intent(in) :: group

        call wire%put_int(int(group%code, int64))
        call put_text(wire, group%rule)
        call put_text(wire, group%output)
        call wire%put_int(int(group%row, int64))
        call wire%put_int(int(group%column, int64))
        call wire%put_int(int(group%count, int64))
        call put_ints(wire, group%states)
        call wire%put_real(group%expected)
        call wire%put_real(group%returned)
        call wire%put_int(int(group%state, int64))
        call wire%put_real(group%time)
        call put_reals(wire, group%q)
        call put_text(wire, group%message)
    end subroutine pack_group

    subroutine unpack_group(wire, group)
        type(wire_reader_type), intent(inout) :: wire
        type(finding_group_type), intent(out) :: group

        group%code = int(wire%get_int())
        call get_text(wire, group%rule)
        call get_text(wire, group%output)
        group%row = int(wire%get_int())
        group%column = int(wire%get_int())
        group%count = int(wire%get_int())
        call get_ints(wire, group%states)
        group%expected = wire%get_real()
        group%returned = wire%get_real()
        group%state = int(wire%get_int())
        group%time = wire%get_real()
        call get_reals(wire, group%q)
        call get_text(wire, group%message)
    end subroutine unpack_group

    !> An allocatable integer array: whether it is allocated, then its values.
    subroutine put_ints(wire, values)
        type(wire_writer_type), intent(inout) :: wire
        integer, allocatable, intent(in) :: values(:)

        call wire%put_logical(allocated(values))
        if (allocated(values)) call wire%put_ints(values)
    end subroutine put_ints

    subroutine get_ints(wire, values)
        type(wire_reader_type), intent(inout) :: wire
        integer, allocatable, intent(out) :: values(:)

        if (wire%get_logical()) call wire%get_ints(values)
    end subroutine get_ints

    !> An allocatable real array: whether it is allocated, then its values.
    subroutine put_reals(wire, values)
        type(wire_writer_type), intent(inout) :: wire
        real(wp), allocatable, intent(in) :: values(:)

        call wire%put_logical(allocated(values))
        if (allocated(values)) call wire%put_reals(values)
    end subroutine put_reals

    subroutine get_reals(wire, values)
        type(wire_reader_type), intent(inout) :: wire
        real(wp), allocatable, intent(out) :: values(:)

        if (wire%get_logical()) call wire%get_reals(values)
    end subroutine get_reals

    !> An allocatable text: whether it is allocated, then the text.
    subroutine put_text(wire, text)
        type(wire_writer_type), intent(inout) :: wire
        character(len=:), allocatable, intent(in) :: text

        call wire%put_logical(allocated(text))
        if (allocated(text)) call wire%put_text(text)
    end subroutine put_text

    subroutine get_text(wire, text)
        type(wire_reader_type), intent(inout) :: wire
        character(len=:), allocatable, intent(out) :: text

        if (wire%get_logical()) text = wire%get_text()
    end subroutine get_text

end module rollcon_audit_transfer
