! SPDX-License-Identifier: MIT
!> Helpers of the tests that run the `rollcon` program itself: where it is, running it with
!> its output in files under build/, and reading those files.
module command_runs
    use rollcon_error, only : error_type
    use rollcon_testing, only : skip_test
    implicit none
    private

    public :: rollcon_program, run_rollcon, file_text, file_exists, line_count, mount_small, &
        & unmount, count_of

contains

    !> The rollcon program built beside this tester (fpm test builds it too): ROLLCON_TEST_EXE
    !> when set (to run these tests against another build), else <build>/app/rollcon for the
    !> tester <build>/test/unit. The test is skipped when it is not there.
    subroutine rollcon_program(path, error)
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        character(len=1024) :: buffer
        integer :: length, stat, cut

        call get_environment_variable("ROLLCON_TEST_EXE", buffer, length, stat)
        if (stat == 0 .and. length > 0) then
            path = buffer(:length)
        else
            call get_command_argument(0, buffer, length)
            path = buffer(:length)
            cut = index(path, "/test/", back=.true.)
            if (cut > 0) then
                path = path(:cut) // "app/rollcon"
            else
                path = "rollcon"
            end if
        end if
        if (.not. file_exists(path)) call skip_test(error, "the rollcon program is not at " &
            & // path // " (build it with fpm build)")
    end subroutine rollcon_program

    !> Run `program arguments` with its stdout and stderr in files; status is its exit status.
    subroutine run_rollcon(program, arguments, out_path, err_path, status)
        character(len=*), intent(in) :: program, arguments, out_path, err_path
        integer, intent(out) :: status
        integer :: command_status

        status = -1
        call execute_command_line(program // " " // arguments // " > " // out_path // " 2> " &
            & // err_path, exitstat=status, cmdstat=command_status)
        if (command_status /= 0) status = -1
    end subroutine run_rollcon

    !> Mount a tmpfs of the given size (e.g. '512k') on folder (created), for tests of a full
    !> disk; the test is skipped, with the reason, when that is not permitted (not root).
    !> The caller unmounts it with unmount(folder).
    subroutine mount_small(folder, size, error)
        character(len=*), intent(in) :: folder, size
        type(error_type), allocatable, intent(out) :: error
        integer :: status

        status = 1
        call execute_command_line("mkdir -p " // folder // " && mount -t tmpfs -o size=" &
            & // size // " tmpfs " // folder // " > " // folder // ".log 2>&1", &
            & exitstat=status)
        if (status /= 0) call skip_test(error, "cannot mount a " // size // " tmpfs (needs " &
            & // "root and mount permission): " // file_text(folder // ".log"))
    end subroutine mount_small

    !> Unmount what mount_small mounted: retried once after a second (the kernel may still be
    !> releasing a file just closed), then detached lazily, so no mount outlives the test.
    subroutine unmount(folder)
        character(len=*), intent(in) :: folder

        call execute_command_line("umount " // folder // " 2> /dev/null || (sleep 1; umount " &
            & // folder // " 2> /dev/null) || umount -l " // folder // " 2> /dev/null")
    end subroutine unmount

    !> The whole text of a file, lines joined by new_line; "" when it is missing.
    function file_text(path) result(text)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: text
        integer :: unit, stat, size_bytes

        text = ""
        if (.not. file_exists(path)) return
        inquire(file=path, size=size_bytes)
        if (size_bytes <= 0) return
        open(newunit=unit, file=path, status="old", action="read", access="stream", &
            & form="unformatted", iostat=stat)
        if (stat /= 0) return
        deallocate(text)
        allocate(character(len=size_bytes) :: text)
        read(unit, iostat=stat) text
        close(unit)
    end function file_text

    !> True when a file is there.
    logical function file_exists(path)
        character(len=*), intent(in) :: path

        inquire(file=path, exist=file_exists)
    end function file_exists

    !> Number of line ends in a text.
    integer function line_count(text)
        character(len=*), intent(in) :: text
        integer :: i

        line_count = 0
        do i = 1, len(text)
            if (text(i:i) == new_line("a")) line_count = line_count + 1
        end do
    end function line_count

    !> How many times part occurs in text.
    pure integer function count_of(text, part) result(n)
        character(len=*), intent(in) :: text, part
        integer :: at, found

        n = 0
        at = 1
        do
            found = index(text(at:), part)
            if (found == 0) return
            n = n + 1
            at = at + found + len(part) - 1
        end do
    end function count_of

end module command_runs
