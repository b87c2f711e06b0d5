! SPDX-License-Identifier: MIT
!> The few C library routines rollcon calls to load a user's routine at run time: dlopen,
!> dlsym, dlclose, dlerror (POSIX <dlfcn.h>) and getpid, with Fortran-string wrappers.
module rollcon_dlopen
    use, intrinsic :: iso_c_binding, only : c_ptr, c_funptr, c_char, c_int, c_size_t, &
        & c_null_char, c_null_ptr, c_associated, c_f_pointer
    implicit none
    private

    public :: rtld_now, rtld_local
    public :: open_library, library_symbol, close_library, last_library_error, process_id

    !> dlopen flag: resolve every symbol now, so a missing one is reported at load time
    integer(c_int), parameter :: rtld_now = 2
    !> dlopen flag: keep the library's symbols out of the global scope (glibc's value)
    integer(c_int), parameter :: rtld_local = 0

    interface
        function c_dlopen(filename, flag) result(handle) bind(c, name="dlopen")
            import :: c_ptr, c_char, c_int
            character(kind=c_char), intent(in) :: filename(*)
            integer(c_int), value :: flag
            type(c_ptr) :: handle
        end function c_dlopen

        function c_dlsym(handle, symbol) result(address) bind(c, name="dlsym")
            import :: c_ptr, c_funptr, c_char
            type(c_ptr), value :: handle
            character(kind=c_char), intent(in) :: symbol(*)
            type(c_funptr) :: address
        end function c_dlsym

        function c_dlclose(handle) result(status) bind(c, name="dlclose")
            import :: c_ptr, c_int
            type(c_ptr), value :: handle
            integer(c_int) :: status
        end function c_dlclose

        function c_dlerror() result(message) bind(c, name="dlerror")
            import :: c_ptr
            type(c_ptr) :: message
        end function c_dlerror

        function c_strlen(text) result(length) bind(c, name="strlen")
            import :: c_ptr, c_size_t
            type(c_ptr), value :: text
            integer(c_size_t) :: length
        end function c_strlen

        function c_getpid() result(pid) bind(c, name="getpid")
            import :: c_int
            integer(c_int) :: pid
        end function c_getpid
    end interface

contains

    !> dlopen(path, RTLD_NOW | RTLD_LOCAL); a null handle on failure (see last_library_error).
    function open_library(path) result(handle)
        !> Path of the shared library; it must contain a '/' to be taken as a path
        character(len=*), intent(in) :: path
        type(c_ptr) :: handle

        handle = c_dlopen(path // c_null_char, ior(rtld_now, rtld_local))
    end function open_library

    !> dlsym(handle, name); a null address when the library has no such symbol.
    function library_symbol(handle, name) result(address)
        !> Handle from open_library
        type(c_ptr), intent(in) :: handle
        !> Symbol as the linker spells it ("ucosub_" for a Fortran external UCOSUB)
        character(len=*), intent(in) :: name
        type(c_funptr) :: address

        address = c_dlsym(handle, name // c_null_char)
    end function library_symbol

    !> dlclose(handle) unless the handle is null; the handle is nulled.
    subroutine close_library(handle)
        !> Handle from open_library
        type(c_ptr), intent(inout) :: handle
        integer(c_int) :: status

        if (c_associated(handle)) status = c_dlclose(handle)
        handle = c_null_ptr
    end subroutine close_library

    !> dlerror() as Fortran text: what the last failed dl* call said, or "" when nothing failed.
    function last_library_error() result(message)
        character(len=:), allocatable :: message
        type(c_ptr) :: text
        character(kind=c_char), pointer :: chars(:)
        integer :: i, length

        text = c_dlerror()
        if (.not. c_associated(text)) then
            message = ""
            return
        end if
        length = int(c_strlen(text))
        call c_f_pointer(text, chars, [length])
        allocate(character(len=length) :: message)
        do i = 1, length
            message(i:i) = chars(i)
        end do
    end function last_library_error

    !> Id of this process (getpid), to make scratch names unique among concurrent runs.
    function process_id() result(pid)
        integer :: pid

        pid = int(c_getpid())
    end function process_id

end module rollcon_dlopen
