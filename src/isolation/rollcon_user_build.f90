! SPDX-License-Identifier: MIT
!> Compiles a user's UCOSUB (fixed-form or free-form source, or an object file) together with
!> the forwarding shim into a shared library, kept in a cache folder and reused while neither
!> the file nor the flags change.
!>
!> A cache entry is a folder named after a 64-bit hash of the file's bytes, the compiler, its
!> flags and the shim's source. It holds a copy of the file, which must match byte for byte
!> before the entry is reused (so a hash collision costs a rebuild, never a wrong routine), the
!> shim's source, the objects, build.log and libucosub.so. An entry is built in a scratch folder
!> named after the process and renamed into place, so concurrent runs do not see half an entry.
module rollcon_user_build
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_io, stat_ucon
    use rollcon_text, only : to_text, shell_quote, lower_case
    use rollcon_dlopen, only : process_id
    use rollcon_user_shim, only : shim_source_lines
    use rollcon_user_files, only : read_bytes, write_bytes, write_lines, file_exists, &
        & text_head
    implicit none
    private

    public :: user_build_options_type, build_user_library, default_cache_dir
    public :: kind_fixed, kind_free, kind_object, source_kind

    !> What the user's file is: fixed-form source, free-form source, object
    integer, parameter :: kind_fixed = 1, kind_free = 2, kind_object = 3

    !> How to build
    type :: user_build_options_type
        !> Folder of the cache entries; when unallocated, default_cache_dir()
        character(len=:), allocatable :: cache_dir
        !> Fortran compiler, found on PATH
        character(len=64) :: compiler = "gfortran"
    end type user_build_options_type

    !> Name of the shared library inside a cache entry
    character(len=*), parameter :: library_name = "libucosub.so"
    !> Diagnostics lines quoted in an error message at most
    integer, parameter :: quoted_lines = 40

contains

    !> $XDG_CACHE_HOME/rollcon, else $HOME/.cache/rollcon; unallocated when neither is set.
    function default_cache_dir() result(dir)
        character(len=:), allocatable :: dir
        character(len=4096) :: value
        integer :: length, stat

        call get_environment_variable("XDG_CACHE_HOME", value, length, stat)
        if (stat == 0 .and. length > 0) then
            dir = value(:length) // "/rollcon"
            return
        end if
        call get_environment_variable("HOME", value, length, stat)
        if (stat == 0 .and. length > 0) dir = value(:length) // "/.cache/rollcon"
    end function default_cache_dir

    !> Kind of a file from its extension (.f .for .f77 fixed; .f90 .f95 .f03 .f08 free; .o),
    !> 0 when not one of these.
    pure function source_kind(path) result(kind)
        !> Path of the user's file
        character(len=*), intent(in) :: path
        integer :: kind
        character(len=:), allocatable :: extension
        integer :: dot

        kind = 0
        dot = index(path, ".", back=.true.)
        if (dot == 0 .or. dot < index(path, "/", back=.true.)) return
        extension = lower_case(path(dot + 1:))
        select case (extension)
        case ("f", "for", "f77")
            kind = kind_fixed
        case ("f90", "f95", "f03", "f08")
            kind = kind_free
        case ("o")
            kind = kind_object
        end select
    end function source_kind

    !> Path of a shared library holding the user's file and the shim: from the cache when an
    !> entry matches, else built now. Compiler diagnostics end up in the error message.
    subroutine build_user_library(path, options, library, from_cache, error)
        !> The user's file, as named (gfortran's diagnostics quote it so)
        character(len=*), intent(in) :: path
        !> Cache folder and compiler
        type(user_build_options_type), intent(in) :: options
        !> Path of the shared library
        character(len=:), allocatable, intent(out) :: library
        !> True when an existing entry was reused
        logical, intent(out) :: from_cache
        !> Set when the file is missing or of an unknown kind, or compiling or linking failed
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: content, cached, flags, cache_dir, entry, scratch, copy
        integer :: kind, stat

        from_cache = .false.
        kind = source_kind(path)
        if (kind == 0) then
            call fatal_error(error, path // ": expected a UCOSUB source (.f fixed form, .f90 " &
                & // "free form) or an object file (.o)", stat_input)
            return
        end if
        if (.not. file_exists(path)) then
            call fatal_error(error, path // ": no such file; expected a UCOSUB source (.f, .f90) " &
                & // "or object (.o)", stat_input)
            return
        end if
        call read_bytes(path, content, error)
        if (allocated(error)) return

        if (allocated(options%cache_dir)) then
            cache_dir = options%cache_dir
        else
            cache_dir = default_cache_dir()
            if (.not. allocated(cache_dir)) then
                call fatal_error(error, "no cache folder for compiled UCOSUBs: neither " &
                    & // "XDG_CACHE_HOME nor HOME is set", stat_io)
                return
            end if
        end if
        flags = compile_flags(kind)
        entry = cache_dir // "/" // content_key(content, trim(options%compiler) // " " // flags)
        copy = "/source" // extension_of(path)
        library = entry // "/" // library_name
        if (file_exists(library) .and. file_exists(entry // copy)) then
            call read_bytes(entry // copy, cached, error)
            if (.not. allocated(error)) then
                if (len(cached) == len(content) .and. cached == content) then
                    from_cache = .true.
                    return
                end if
            end if
            if (allocated(error)) deallocate(error)
        end if

        scratch = entry // ".build-" // to_text(process_id())
        call execute_command_line("mkdir -p " // shell_quote(scratch), exitstat=stat)
        if (stat /= 0) then
            call fatal_error(error, cache_dir // ": cannot create the cache folder " // scratch, &
                & stat_io)
            return
        end if
        call write_bytes(scratch // copy, content, error)
        if (allocated(error)) return
        call write_lines(scratch // "/rollcon_shim.f90", shim_source_lines, error)
        if (allocated(error)) return
        call compile_and_link(path, kind, trim(options%compiler), flags, scratch, &
            & entry // ".failed/build.log", error)
        if (allocated(error)) then
            ! Keep the last failed build of this content for inspection, one per entry.
            call execute_command_line("rm -rf " // shell_quote(entry // ".failed") // " && mv -T " &
                & // shell_quote(scratch) // " " // shell_quote(entry // ".failed"), exitstat=stat)
            return
        end if
        call execute_command_line("rm -rf " // shell_quote(entry) // " && mv -T " &
            & // shell_quote(scratch) // " " // shell_quote(entry), exitstat=stat)
        if (stat /= 0) library = scratch // "/" // library_name
    end subroutine build_user_library

    !> Run the compiler: the user's source, the shim, then the link; the first failure is an
    !> error quoting build.log (for the source: at the first line gfortran complains about).
    subroutine compile_and_link(path, kind, compiler, flags, dir, kept_log, error)
        character(len=*), intent(in) :: path
        integer, intent(in) :: kind
        character(len=*), intent(in) :: compiler, flags, dir
        !> Where build.log is kept after a failure, for the message
        character(len=*), intent(in) :: kept_log
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: log, object, form, diagnostics
        integer :: stat, command_stat

        log = dir // "/build.log"
        object = shell_quote(dir // "/user.o")
        if (kind == kind_object) then
            object = shell_quote(path)
        else
            call execute_command_line(compiler // " -c " // flags // " -J " // shell_quote(dir) &
                & // " " // shell_quote(path) // " -o " // object // " > " // shell_quote(log) &
                & // " 2>&1", exitstat=stat, cmdstat=command_stat)
            call compiler_missing(compiler, path, stat, command_stat, error)
            if (allocated(error)) return
            if (stat /= 0) then
                form = "free form"
                if (kind == kind_fixed) form = "fixed form, -std=legacy"
                call text_head(log, quoted_lines, diagnostics)
                call fatal_error(error, first_location(path, diagnostics) // ": " // compiler &
                    & // " could not compile this UCOSUB (" // form // "); its diagnostics " &
                    & // "(all in " // kept_log // "):" // new_line("a") // diagnostics, stat_ucon)
                return
            end if
        end if
        call execute_command_line(compiler // " -c " // compile_flags(kind_free) // " -J " &
            & // shell_quote(dir) // " " // shell_quote(dir // "/rollcon_shim.f90") // " -o " &
            & // shell_quote(dir // "/rollcon_shim.o") // " >> " // shell_quote(log) // " 2>&1", &
            & exitstat=stat, cmdstat=command_stat)
        call compiler_missing(compiler, path, stat, command_stat, error)
        if (allocated(error)) return
        if (stat /= 0) then
            call text_head(log, quoted_lines, diagnostics)
            call fatal_error(error, dir // "/rollcon_shim.f90: " // compiler // " could not " &
                & // "compile rollcon's shim (log: " // kept_log // "):" // new_line("a") &
                & // diagnostics, stat_ucon)
            return
        end if
        call execute_command_line(compiler // " -shared " // object // " " &
            & // shell_quote(dir // "/rollcon_shim.o") // " -o " &
            & // shell_quote(dir // "/" // library_name) // " >> " // shell_quote(log) // " 2>&1", &
            & exitstat=stat, cmdstat=command_stat)
        if (stat /= 0) then
            call text_head(log, quoted_lines, diagnostics)
            call fatal_error(error, path // ": linking it into a shared library failed (an " &
                & // "object must be compiled with -fPIC; it must not define UCOVAR or ERRMES " &
                & // "itself); " // compiler // " says (log: " // kept_log // "):" &
                & // new_line("a") // diagnostics, stat_ucon)
        end if
    end subroutine compile_and_link

    !> An error when the shell could not run the compiler at all.
    subroutine compiler_missing(compiler, path, stat, command_stat, error)
        character(len=*), intent(in) :: compiler, path
        integer, intent(in) :: stat, command_stat
        type(error_type), allocatable, intent(out) :: error

        ! 127 is the shell's status for a command it cannot find.
        if (command_stat /= 0 .or. stat == 127) then
            call fatal_error(error, path // ": cannot run the Fortran compiler '" // compiler &
                & // "' (is it installed and on PATH?); rollcon needs it to build the UCOSUB", &
                & stat_io)
        end if
    end subroutine compiler_missing

    !> "path:line" of the first diagnostic gfortran gives for path, or path when it gives none.
    pure function first_location(path, diagnostics) result(location)
        character(len=*), intent(in) :: path, diagnostics
        character(len=:), allocatable :: location
        integer :: start, finish

        location = path
        start = index(diagnostics, path // ":")
        if (start == 0) return
        start = start + len(path) + 1
        finish = start
        do while (finish <= len(diagnostics))
            if (verify(diagnostics(finish:finish), "0123456789") /= 0) exit
            finish = finish + 1
        end do
        if (finish > start) location = path // ":" // diagnostics(start:finish - 1)
    end function first_location

    !> Flags for the compile step of a file of this kind (objects are not compiled).
    pure function compile_flags(kind) result(flags)
        integer, intent(in) :: kind
        character(len=:), allocatable :: flags

        flags = "-O2 -g -fPIC"
        if (kind == kind_fixed) flags = flags // " -std=legacy"
    end function compile_flags

    !> Name of a cache entry: two 32-bit hashes (FNV-1a and sdbm) of content, flags and shim,
    !> as 16 hexadecimal digits. Products stay below 2**57, so int64 never overflows.
    pure function content_key(content, flags) result(key)
        character(len=*), intent(in) :: content, flags
        character(len=:), allocatable :: key
        integer(int64) :: fnv, sdbm
        character(len=16) :: buffer
        integer :: i

        fnv = 2166136261_int64
        sdbm = 0_int64
        call mix(content, fnv, sdbm)
        call mix(achar(0) // flags // achar(0), fnv, sdbm)
        do i = 1, size(shim_source_lines)
            call mix(trim(shim_source_lines(i)) // achar(10), fnv, sdbm)
        end do
        write(buffer, '(z8.8, z8.8)') fnv, sdbm
        key = lower_case(buffer)
    end function content_key

    !> Feed bytes to both hashes (each kept below 2**32).
    pure subroutine mix(text, fnv, sdbm)
        character(len=*), intent(in) :: text
        integer(int64), intent(inout) :: fnv, sdbm
        integer(int64), parameter :: modulus = 4294967296_int64
        integer(int64) :: byte
        integer :: j

        do j = 1, len(text)
            byte = iand(int(iachar(text(j:j)), int64), 255_int64)
            fnv = mod(ieor(fnv, byte)*16777619_int64, modulus)
            sdbm = mod(sdbm*65599_int64 + byte, modulus)
        end do
    end subroutine mix

    !> ".f" of "dir/name.f" (the extension as written, with its dot).
    pure function extension_of(path) result(extension)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: extension

        extension = path(index(path, ".", back=.true.):)
    end function extension_of


end module rollcon_user_build
