! SPDX-License-Identifier: MIT
!> `rollcon sweep` runs the program rollcon-sweep: the one that links Open MPI (mpi_f08), so
!> that every other command starts without loading it (docs/studies.md, "On many processes").
!> rollcon finds rollcon-sweep in its own folder (/proc/self/exe: fpm builds and installs the
!> two side by side) and replaces itself by it (execv(2)) with the same arguments; the process,
!> its environment and, under mpirun, its rank stay the same, so MPI_Init in rollcon-sweep
!> sees the job mpirun started. POSIX calls through iso_c_binding (Linux and glibc).
module rollcon_sweep_program
    use, intrinsic :: iso_c_binding, only : c_int, c_char, c_ptr, c_size_t, c_intptr_t, &
        & c_null_char, c_null_ptr, c_loc
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : error_type, fatal_error, stat_input, stat_io, system_reason
    implicit none
    private

    public :: run_sweep_program, sweep_program_name

    !> The file name of the study program, beside rollcon
    character(len=*), parameter :: sweep_program_name = "rollcon-sweep"
    !> access(2): may be executed
    integer(c_int), parameter :: x_ok = 1_c_int
    !> Longest path the system takes, its NUL included (Linux's PATH_MAX)
    integer, parameter :: path_max = 4096

    interface
        function c_readlink(path, buffer, size) result(length) bind(c, name="readlink")
            import :: c_char, c_size_t, c_intptr_t
            character(kind=c_char), intent(in) :: path(*)
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_size_t), value :: size
            integer(c_intptr_t) :: length
        end function c_readlink
        function c_access(path, mode) result(stat) bind(c, name="access")
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
            integer(c_int), value :: mode
            integer(c_int) :: stat
        end function c_access
        function c_execv(path, argv) result(stat) bind(c, name="execv")
            import :: c_int, c_char, c_ptr
            character(kind=c_char), intent(in) :: path(*)
            type(c_ptr), intent(in) :: argv(*)
            integer(c_int) :: stat
        end function c_execv
    end interface

contains

    !> Replace this process by rollcon-sweep with this process's arguments. Returns only when
    !> that could not be done: error says why (the program missing, not executable, or the
    !> system's reason), with exit status 1 for the caller.
    subroutine run_sweep_program(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        character(kind=c_char), allocatable, target :: texts(:)
        type(c_ptr), allocatable :: argv(:)
        integer :: count, i, length, start, total
        integer(c_int) :: stat
        logical :: present

        call sweep_program_path(program, error)
        if (allocated(error)) return
        inquire(file=program, exist=present)
        if (.not. present) then
            call fatal_error(error, "rollcon sweep runs the program " // sweep_program_name &
                & // ", which is not beside rollcon (" // program // " is missing): build " &
                & // "both with fpm build, or install both with fpm install (docs/building.md)", &
                & stat_input)
            return
        end if
        if (c_access(program // c_null_char, x_ok) /= 0) then
            call fatal_error(error, "rollcon sweep runs the program " // program // ", which " &
                & // "cannot be executed: " // system_reason(), stat_io)
            return
        end if
        ! argv: the program's path, then this process's arguments, each ended by a NUL
        count = command_argument_count()
        total = len(program) + 1
        do i = 1, count
            call get_command_argument(i, length=length)
            total = total + length + 1
        end do
        allocate(texts(total), argv(count + 2))
        start = 1
        call put_text(program, texts, start, argv(1))
        do i = 1, count
            call get_command_argument(i, length=length)
            block
                character(len=length) :: argument
                call get_command_argument(i, argument)
                call put_text(argument, texts, start, argv(i + 1))
            end block
        end do
        argv(count + 2) = c_null_ptr
        flush(output_unit)
        flush(error_unit)
        ! returns only on failure
        stat = c_execv(program // c_null_char, argv)
        call fatal_error(error, "rollcon sweep could not start " // program // ": " &
            & // system_reason(), stat_io)
    end subroutine run_sweep_program

    !> rollcon-sweep's path: the folder of this program (/proc/self/exe, links resolved)
    !> and its name.
    subroutine sweep_program_path(path, error)
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        character(kind=c_char, len=path_max) :: buffer
        integer :: length, slash

        length = int(c_readlink("/proc/self/exe" // c_null_char, buffer, &
            & int(path_max, c_size_t)))
        if (length <= 0 .or. length >= path_max) then
            call fatal_error(error, "rollcon sweep cannot find its program " &
                & // sweep_program_name // ": this program's own path (/proc/self/exe) is " &
                & // "not readable: " // system_reason(), stat_io)
            return
        end if
        slash = index(buffer(:length), "/", back=.true.)
        path = buffer(:slash) // sweep_program_name
    end subroutine sweep_program_path

    !> text and a NUL into texts(start:), its address into pointer; start moves past it.
    subroutine put_text(text, texts, start, pointer)
        character(len=*), intent(in) :: text
        character(kind=c_char), target, intent(inout) :: texts(:)
        integer, intent(inout) :: start
        type(c_ptr), intent(out) :: pointer
        integer :: k

        do k = 1, len(text)
            texts(start + k - 1) = text(k:k)
        end do
        texts(start + len(text)) = c_null_char
        pointer = c_loc(texts(start))
        start = start + len(text) + 1
    end subroutine put_text

end module rollcon_sweep_program
