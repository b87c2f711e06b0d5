! SPDX-License-Identifier: MIT
!> The user-ucosub suite's tests of loading: files that cannot serve give clear errors; a
!> free-form source and an object file serve as well as fixed form.
module user_ucosub_loading
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_user_library, only : user_ucosub_type
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub
    use rollcon_testing, only : check
    use user_ucosub_support, only : test_cache, faulty, disk_source, test_states, load, &
        & check_disk_file, expect_clean, expect_in
    implicit none
    private

    public :: test_does_not_compile, test_no_ucosub, test_missing_file, test_free_form, &
        & test_object

contains

    !> gfortran's diagnostic is passed on, and the error names the file and the typo's line.
    subroutine test_does_not_compile(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        character(len=*), parameter :: path = faulty // "does_not_compile.f"
        character(len=200) :: line
        character(len=:), allocatable :: message
        integer :: unit, stat, number

        open(newunit=unit, file=path, action="read", status="old", iostat=stat)
        call check(error, stat == 0, "cannot read " // path)
        if (allocated(error)) return
        number = 0
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            number = number + 1
            if (index(line, "XMATRIX(") > 0 .and. line(1:1) == " ") exit
        end do
        close(unit)
        call load(path, user, error)
        if (.not. allocated(error)) then
            call user%destroy()
            call check(error, .false., "a file that does not compile was loaded")
            return
        end if
        message = error%message
        deallocate(error)
        call expect_in(error, message, path // ":" // to_text(number) // ": gfortran could " &
            & // "not compile this file of user routines")
        if (allocated(error)) return
        call expect_in(error, message, "xmatrix")
    end subroutine test_does_not_compile

    !> A file without UCOSUB is refused; one of a force routine (an SFOSUB, given to the
    !> UCOSUB check by mistake) is refused naming what it defines and the command that checks
    !> it, on the dataset its statements are in.
    subroutine test_no_ucosub(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: force_file = "test/user_forces/sforce_spring.f"

        call expect_load_error(error, faulty // "no_ucosub.f", "defines no subroutine UCOSUB")
        if (allocated(error)) return
        call expect_load_error(error, force_file, force_file // ": defines no subroutine " &
            & // "UCOSUB; it defines SFOSUB, checked on the dataset whose statements call it " &
            & // "(FUNCTION=USER(...)): rollcon check " // force_file // " --model MODEL.adm")
    end subroutine test_no_ucosub

    subroutine test_missing_file(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_load_error(error, faulty // "not_there.f", "not_there.f: no such file")
    end subroutine test_missing_file

    !> Loading path fails with a message containing part.
    subroutine expect_load_error(error, path, part)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: path, part
        type(user_ucosub_type) :: user
        character(len=:), allocatable :: message

        call load(path, user, error)
        if (.not. allocated(error)) then
            call user%destroy()
            call check(error, .false., path // " was loaded")
            return
        end if
        message = error%message
        deallocate(error)
        call expect_in(error, message, part)
    end subroutine expect_load_error

    !> A .f90 file compiles as free form: a holonomic UCON, Z - PAR(2) = 0 of part PAR(1).
    subroutine test_free_form(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = test_cache // "/height_ucosub.f90"
        type(user_ucosub_type) :: user
        type(ucon_request_type) :: request(1)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        integer :: unit, stat

        call execute_command_line("mkdir -p " // test_cache, exitstat=stat)
        open(newunit=unit, file=path, status="replace", action="write", iostat=stat)
        call check(error, stat == 0, "cannot write " // path)
        if (allocated(error)) return
        write(unit, '(a)') &
            & "subroutine ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)", &
            & "    implicit none", &
            & "    integer, intent(in) :: id, npar, idrsel(3), iflag", &
            & "    double precision, intent(in) :: time, q(30), par(*)", &
            & "    double precision, intent(inout) :: scalar, array(30), xmatrx(30, 30)", &
            & "    if (iflag == 3) then", &
            & "        call ucovar(id, 1, [nint(par(1))], 1, [13])", &
            & "        return", &
            & "    end if", &
            & "    if (idrsel(1) == 1) scalar = q(1) - par(2)", &
            & "    if (idrsel(2) == 1) array(1) = 1.0d0", &
            & "end subroutine ucosub"
        close(unit)
        call load(path, user, error)
        if (allocated(error)) return
        request(1)%id = 7
        request(1)%par = [3.0_wp, 0.25_wp]
        options%states = test_states
        call check_user_ucosub(user%ucosub, request, options, report, error)
        call user%destroy()
        if (allocated(error)) return
        call check(error, report%ucons(1)%declared .and. report%ucons(1)%codes(1) == 13 &
            & .and. report%ucons(1)%parts(1) == 3, "declaration of the free-form routine")
        if (allocated(error)) return
        call expect_clean(error, report, 1)
    end subroutine test_free_form

    !> An object compiled with -fPIC is linked as it is.
    subroutine test_object(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: object = test_cache // "/rolling_disk.o"
        type(user_check_report_type) :: report
        integer :: stat, command_stat

        call execute_command_line("mkdir -p " // test_cache // " && gfortran -c -fPIC " &
            & // "-std=legacy " // disk_source // " -o " // object, exitstat=stat, &
            & cmdstat=command_stat)
        call check(error, stat == 0 .and. command_stat == 0, "compiling " // object // " failed")
        if (allocated(error)) return
        call check_disk_file(object, report, error)
        if (allocated(error)) return
        call check(error, report%clean(), "the disk's object file has findings")
    end subroutine test_object

end module user_ucosub_loading
