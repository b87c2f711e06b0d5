! SPDX-License-Identifier: MIT
!> One UCON's part of a check report written to a file and read back (unformatted stream):
!> how an isolated checker's child hands its findings to the host.
module rollcon_audit_transfer
    use rollcon_text, only : to_text
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_ucosub_audit, only : ucon_report_type, finding_group_type
    implicit none
    private

    public :: write_ucon_report, read_ucon_report

contains

    !> Write ucon to path (replaced).
    subroutine write_ucon_report(path, ucon, error)
        !> File to write
        character(len=*), intent(in) :: path
        !> The UCON's report
        type(ucon_report_type), intent(in) :: ucon
        !> Set when the file cannot be written
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, g

        open(newunit=unit, file=path, access="stream", form="unformatted", status="replace", &
            & action="write", iostat=stat)
        if (stat == 0) then
            write(unit, iostat=stat) ucon%id, size(ucon%par), ucon%par, ucon%declared, &
                & ucon%states, ucon%compared, ucon%worst, size(ucon%groups)
        end if
        if (stat == 0 .and. ucon%declared) write(unit, iostat=stat) size(ucon%codes), &
            & ucon%parts, ucon%codes
        do g = 1, size(ucon%groups)
            if (stat /= 0) exit
            associate (group => ucon%groups(g))
                write(unit, iostat=stat) group%code, len(group%rule), group%rule, &
                    & len(group%output), group%output, group%row, group%column, group%count, &
                    & size(group%states), group%states, group%expected, group%returned, &
                    & group%state, group%time, allocated(group%q), allocated(group%message)
                if (stat == 0 .and. allocated(group%q)) write(unit, iostat=stat) &
                    & size(group%q), group%q
                if (stat == 0 .and. allocated(group%message)) write(unit, iostat=stat) &
                    & len(group%message), group%message
            end associate
        end do
        if (stat == 0) close(unit, iostat=stat)
        if (stat /= 0) call fatal_error(error, path // ": cannot write the report of UCON/" &
            & // to_text(ucon%id), stat_io)
    end subroutine write_ucon_report

    !> Read what write_ucon_report wrote.
    subroutine read_ucon_report(path, ucon, error)
        !> File to read
        character(len=*), intent(in) :: path
        !> The UCON's report
        type(ucon_report_type), intent(out) :: ucon
        !> Set when the file is missing or truncated
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, g, n, groups

        open(newunit=unit, file=path, access="stream", form="unformatted", status="old", &
            & action="read", iostat=stat)
        if (stat == 0) read(unit, iostat=stat) ucon%id, n
        if (stat == 0) then
            allocate(ucon%par(n))
            read(unit, iostat=stat) ucon%par, ucon%declared, ucon%states, ucon%compared, &
                & ucon%worst, groups
        end if
        if (stat == 0 .and. ucon%declared) then
            read(unit, iostat=stat) n
            allocate(ucon%parts(n), ucon%codes(n))
            if (stat == 0) read(unit, iostat=stat) ucon%parts, ucon%codes
        end if
        if (stat == 0) allocate(ucon%groups(groups))
        do g = 1, groups
            if (stat /= 0) exit
            call read_group(unit, ucon%groups(g), stat)
        end do
        if (stat == 0) close(unit, iostat=stat)
        if (stat /= 0) call fatal_error(error, path // ": cannot read a UCON report back " &
            & // "from the checking process", stat_io)
    end subroutine read_ucon_report

    subroutine read_group(unit, group, stat)
        integer, intent(in) :: unit
        type(finding_group_type), intent(out) :: group
        integer, intent(out) :: stat
        integer :: n
        logical :: has_q, has_message

        read(unit, iostat=stat) group%code, n
        if (stat /= 0) return
        allocate(character(len=n) :: group%rule)
        read(unit, iostat=stat) group%rule, n
        if (stat /= 0) return
        allocate(character(len=n) :: group%output)
        read(unit, iostat=stat) group%output, group%row, group%column, group%count, n
        if (stat /= 0) return
        allocate(group%states(n))
        read(unit, iostat=stat) group%states, group%expected, group%returned, group%state, &
            & group%time, has_q, has_message
        if (stat == 0 .and. has_q) then
            read(unit, iostat=stat) n
            allocate(group%q(n))
            if (stat == 0) read(unit, iostat=stat) group%q
        end if
        if (stat == 0 .and. has_message) then
            read(unit, iostat=stat) n
            allocate(character(len=n) :: group%message)
            if (stat == 0) read(unit, iostat=stat) group%message
        end if
    end subroutine read_group

end module rollcon_audit_transfer
