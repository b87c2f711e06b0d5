! SPDX-License-Identifier: MIT
!> Shared set-up of the user-ucosub suite: the tests' cache and data, loading a file, checking
!> it as the disk's UCONs, and the expectations on a check report.
module user_ucosub_support
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_disk_par, only : disk_par
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, ucon_report_type, check_user_ucosub
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_cache, faulty, disk_source, test_states
    public :: load, check_disk_file, expect_group, expect_clean, expect_in, listing

    !> Cache of the libraries built by these tests
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    !> Faulty routines (test data)
    character(len=*), parameter :: faulty = "test/faulty_ucosubs/"
    !> The generated ADAMS-ready disk routine
    character(len=*), parameter :: disk_source = "ucon/adams/rolling_disk/ucosub.f"
    !> States per UCON: every planted mistake shows at any generic state, so a few suffice
    integer, parameter :: test_states = 6

contains

    !> Load a file with the tests' cache.
    subroutine load(path, user, error)
        character(len=*), intent(in) :: path
        type(user_ucosub_type), intent(out) :: user
        type(error_type), allocatable, intent(out) :: error
        type(user_build_options_type) :: options

        options%cache_dir = test_cache
        call new_user_ucosub(user, path, error, options)
    end subroutine load

    !> Load a file and check it as the disk's three UCONs (ids 1, 2, 3 = components), part id
    !> part, radius 0.1 m.
    subroutine check_disk_file(path, report, error, part)
        character(len=*), intent(in) :: path
        type(user_check_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: part
        type(user_ucosub_type) :: user
        type(ucon_request_type) :: requests(3)
        type(user_check_options_type) :: options
        integer :: k, disk_part

        disk_part = 1
        if (present(part)) disk_part = part
        call load(path, user, error)
        if (allocated(error)) return
        do k = 1, 3
            requests(k)%id = k
            requests(k)%par = disk_par(disk_part, 0.1_wp, k)
        end do
        options%states = test_states
        call check_user_ucosub(user%ucosub, requests, options, report, error)
        call user%destroy()
    end subroutine check_disk_file

    !> Pass when UCON k of the report has a group of rule on output at (row, column).
    subroutine expect_group(error, report, k, rule, output, row, column, found)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type), intent(in) :: report
        integer, intent(in) :: k, row, column
        character(len=*), intent(in) :: rule, output
        !> Index of the group
        integer, intent(out), optional :: found
        integer :: g

        associate (ucon => report%ucons(k))
            do g = 1, size(ucon%groups)
                if (ucon%groups(g)%rule == rule .and. ucon%groups(g)%output == output &
                    & .and. ucon%groups(g)%row == row .and. ucon%groups(g)%column == column) then
                    if (present(found)) found = g
                    return
                end if
            end do
            call check(error, .false., "UCON/" // to_text(ucon%id) // ": no [" // rule // "] " &
                & // output // " (" // to_text(row) // "," // to_text(column) // ") among " &
                & // to_text(size(ucon%groups)) // " groups" // listing(ucon))
        end associate
    end subroutine expect_group

    !> Pass when UCON k of the report has no group.
    subroutine expect_clean(error, report, k)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type), intent(in) :: report
        integer, intent(in) :: k

        call check(error, size(report%ucons(k)%groups) == 0, "UCON/" &
            & // to_text(report%ucons(k)%id) // " has findings" // listing(report%ucons(k)))
    end subroutine expect_clean

    !> The groups of a UCON, for a failure message.
    function listing(ucon) result(text)
        type(ucon_report_type), intent(in) :: ucon
        character(len=:), allocatable :: text
        integer :: g

        text = ":"
        do g = 1, size(ucon%groups)
            text = text // " [" // ucon%groups(g)%rule // "] " // ucon%groups(g)%output // "(" &
                & // to_text(ucon%groups(g)%row) // "," // to_text(ucon%groups(g)%column) // ")"
        end do
    end function listing

    !> Pass when message contains part.
    subroutine expect_in(error, message, part)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: message, part

        call check(error, index(message, part) > 0, "message lacks '" // part // "': " // message)
    end subroutine expect_in

end module user_ucosub_support
