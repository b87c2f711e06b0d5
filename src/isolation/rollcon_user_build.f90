! SPDX-License-Identifier: MIT
!> Compiles a user's UCOSUB (fixed-form or free-form source, or an object file) together with
!> the forwarding shim into a shared library, kept in a cache folder and reused while neither
!> the file nor the flags change.
!>
!> A cache entry is a folder named after a 64-bit hash of the file's bytes, the compiler, its
!> flags and the shim's source. It holds a copy of the file, which must match byte for byte
!> before the entry is reused (so a hash collision costs a rebuild, never a wrong routine), the
!> shim's source, the objects, build.log, libucosub.so and libucosub.so.check, the library's
!> size and FNV-1a hash when it was built: a library cut or changed on disk since (which would
!> crash the process that loads it) is rebuilt, never loaded. An entry is built in a scratch
!> folder named after the process and renamed into place, so concurrent runs do not see half
!> an entry. Folders are made and removed through the C library (no shell); the compiler is
!> looked up on PATH first, so a missing one is named as such; a full disk under the cache is
!> said to be one, whichever step it stopped.
module rollcon_user_build
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_io, stat_ucon
    use rollcon_text, only : to_text, shell_quote, lower_case
    use rollcon_dlopen, only : process_id
    use rollcon_user_shim, only : shim_source_lines
    use rollcon_user_files, only : read_bytes, write_bytes, write_lines, file_exists, &
        & text_head
    use rollcon_output_files, only : make_folders
    use rollcon_system, only : remove_flat_folder, rename_path, is_executable
    use rollcon_input_files, only : read_input_file, text_input_limit, &
        & library_input_limit, file_record
    use rollcon_c_stream, only : c_stream_type
    use rollcon_hash, only : fnv1a64_type
    implicit none
    private

    public :: user_build_options_type, build_user_library, default_cache_dir
    public :: kind_fixed, kind_free, kind_object, kind_c, source_kind

    !> What the user's file is: fixed-form source, free-form source, object, C source
    integer, parameter :: kind_fixed = 1, kind_free = 2, kind_object = 3, kind_c = 4

    !> How to build
    type :: user_build_options_type
        !> Folder of the cache entries; when unallocated, default_cache_dir()
        character(len=:), allocatable :: cache_dir
        !> Fortran compiler, found on PATH
        character(len=64) :: compiler = "gfortran"
        !> C compiler for a routine written in C (.c), found on PATH
        character(len=64) :: c_compiler = "cc"
    end type user_build_options_type

    !> Name of the shared library inside a cache entry
    character(len=*), parameter :: library_name = "libucosub.so"
    !> Name of the record of the library's size and hash inside a cache entry
    character(len=*), parameter :: record_name = "libucosub.so.check"
    !> Diagnostics lines quoted in an error message at most
    integer, parameter :: quoted_lines = 40

contains

    !> $XDG_CACHE_HOME/rollcon, else $HOME/.cache/rollcon; unallocated when neither is set.
    !> The variables are read whole, however long.
    function default_cache_dir() result(dir)
        character(len=:), allocatable :: dir
        character(len=:), allocatable :: value

        call environment_value("XDG_CACHE_HOME", value)
        if (len(value) > 0) then
            dir = value // "/rollcon"
            return
        end if
        call environment_value("HOME", value)
        if (len(value) > 0) dir = value // "/.cache/rollcon"
    end function default_cache_dir

    !> An environment variable's value, whole ("" when it is not set).
    subroutine environment_value(name, value)
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(out) :: value
        integer :: length, stat

        call get_environment_variable(name, length=length, status=stat)
        if (stat /= 0 .or. length == 0) then
            value = ""
            return
        end if
        allocate(character(len=length) :: value)
        call get_environment_variable(name, value, status=stat)
        if (stat /= 0) value = ""
    end subroutine environment_value

    !> Kind of a file from its extension (.f .for .f77 fixed; .f90 .f95 .f03 .f08 free; .o;
    !> .c C), 0 when not one of these.
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
        case ("c")
            kind = kind_c
        end select
    end function source_kind

    !> Path of a shared library holding the user's file and the shim: from the cache when an
    !> entry matches (its copy of the file byte for byte, its library the size and hash
    !> recorded when it was built), else built now. Compiler diagnostics end up in the error
    !> message; a full disk under the cache folder is said to be one. Its length is the one
    !> sequence of a cache entry's life (look up, verify, build, record, rename into place),
    !> kept in one place so that each failure is named at the step it happens.
    subroutine build_user_library(path, options, library, from_cache, error, note)
        !> The user's file, as named (gfortran's diagnostics quote it so)
        character(len=*), intent(in) :: path
        !> Cache folder and compiler
        type(user_build_options_type), intent(in) :: options
        !> Path of the shared library
        character(len=:), allocatable, intent(out) :: library
        !> True when an existing entry was reused
        logical, intent(out) :: from_cache
        !> Set when the file is missing or of an unknown kind, the compiler is not on PATH, or
        !> compiling or linking failed
        type(error_type), allocatable, intent(out) :: error
        !> Why a cached library was not reused but rebuilt (it was cut or changed on disk);
        !> "" when there was nothing wrong with the cache
        character(len=:), allocatable, intent(out), optional :: note
        character(len=:), allocatable :: content, flags, cache_dir, entry, scratch, copy, &
            & compiler, damage, c_compiler, compilers
        integer :: kind, ignored
        logical :: disk_full

        from_cache = .false.
        if (present(note)) note = ""
        kind = source_kind(path)
        if (kind == 0) then
            call fatal_error(error, path // ": expected a UCOSUB source (.f fixed form, .f90 " &
                & // "free form, .c C) or an object file (.o)", stat_input)
            return
        end if
        if (.not. file_exists(path)) then
            call fatal_error(error, path // ": no such file; expected a UCOSUB source (.f, .f90, " &
                & // ".c) or object (.o)", stat_input)
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
        compilers = trim(options%compiler)
        if (kind == kind_c) compilers = compilers // " " // trim(options%c_compiler)
        entry = cache_dir // "/" // content_key(content, compilers // " " // flags)
        copy = "/source" // extension_of(path)
        library = entry // "/" // library_name
        call check_entry(entry, copy, content, from_cache, damage)
        if (from_cache) return
        if (present(note)) note = damage

        call find_compiler(trim(options%compiler), path, compiler, error)
        if (allocated(error)) return
        c_compiler = ""
        if (kind == kind_c) then
            call find_compiler(trim(options%c_compiler), path, c_compiler, error, "C")
            if (allocated(error)) return
        end if
        scratch = entry // ".build-" // to_text(process_id())
        ! a folder of an earlier process that had this process id
        ignored = remove_flat_folder(scratch)
        call make_folders(scratch, error)
        if (.not. allocated(error)) call write_bytes(scratch // copy, content, error)
        if (.not. allocated(error)) call write_lines(scratch // "/rollcon_shim.f90", &
            & shim_source_lines, error)
        if (.not. allocated(error)) call compile_and_link(path, kind, compiler, &
            & trim(options%compiler), flags, scratch, entry // ".failed/build.log", error, &
            & c_compiler, trim(options%c_compiler))
        if (.not. allocated(error)) call write_library_record(scratch, error)
        if (allocated(error)) then
            call say_when_disk_full(path, cache_dir, scratch, error, disk_full)
            ! Keep the last failed build of this content for inspection, one per entry; none
            ! on a full disk, where it would only hold the space.
            ignored = remove_flat_folder(entry // ".failed")
            if (disk_full) then
                ignored = remove_flat_folder(scratch)
            else if (rename_path(scratch, entry // ".failed") /= 0) then
                ignored = remove_flat_folder(scratch)
            end if
            return
        end if
        ! Another process may have put a sound entry of this content in place meanwhile: it
        ! is used as it is (replacing it could remove it under that process's feet).
        call check_entry(entry, copy, content, from_cache, damage)
        if (from_cache) then
            from_cache = .false.
            ignored = remove_flat_folder(scratch)
            return
        end if
        ! Into place: a damaged entry is replaced; if that fails, this build is used from its
        ! own folder.
        ignored = remove_flat_folder(entry)
        if (rename_path(scratch, entry) /= 0) library = scratch // "/" // library_name
    end subroutine build_user_library

    !> Whether the cache entry can be reused: it holds a copy of the file equal to content
    !> (else a hash collision or an unfinished entry: rebuilt without a word), and a library
    !> whose size and FNV-1a hash are those recorded when it was built (else damage says what
    !> is wrong: a library cut short on disk would crash the process that loads it).
    subroutine check_entry(entry, copy, content, reuse, damage)
        character(len=*), intent(in) :: entry, copy, content
        logical, intent(out) :: reuse
        character(len=:), allocatable, intent(out) :: damage
        type(error_type), allocatable :: error
        character(len=:), allocatable :: cached, recorded, actual, library

        reuse = .false.
        damage = ""
        library = entry // "/" // library_name
        if (.not. (file_exists(library) .and. file_exists(entry // copy))) return
        call read_bytes(entry // copy, cached, error)
        if (allocated(error)) return
        if (len(cached) /= len(content)) return
        if (cached /= content) return
        call library_record(library, actual, error)
        if (allocated(error)) then
            damage = "the cached library cannot be checked (" // error%message // ")"
            return
        end if
        call read_input_file(entry // "/" // record_name, "cache record", text_input_limit, &
            & recorded, error)
        if (allocated(error)) then
            damage = library // " has no record of its size and hash (" // error%message &
                & // ")"
            return
        end if
        recorded = trim(recorded)
        if (len(recorded) > 0) then
            if (recorded(len(recorded):) == new_line("a")) recorded = recorded(:len(recorded) - 1)
        end if
        if (recorded /= actual) then
            damage = library // " is '" // actual // "' but was '" // recorded // "' when it " &
                & // "was built (cut or changed on disk)"
            return
        end if
        reuse = .true.
    end subroutine check_entry

    !> Write the record of the library just built in dir: its size and hash.
    subroutine write_library_record(dir, error)
        character(len=*), intent(in) :: dir
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: record

        call library_record(dir // "/" // library_name, record, error)
        if (allocated(error)) return
        call write_bytes(dir // "/" // record_name, record // new_line("a"), error)
    end subroutine write_library_record

    !> "N bytes, FNV-1a 64 HHHHHHHHHHHHHHHH" of a library file.
    subroutine library_record(path, record, error)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: record
        type(error_type), allocatable, intent(out) :: error

        call file_record(path, "shared library", library_input_limit, record, error)
    end subroutine library_record

    !> The compiler to run: name itself when it holds a '/', else the first executable file
    !> of that name in the folders of PATH (as the shell would find it). An error saying so
    !> when PATH is empty or holds no such file: without a compiler no UCOSUB can be built.
    subroutine find_compiler(name, path, compiler, error, language)
        !> The compiler's name (gfortran) or path
        character(len=*), intent(in) :: name
        !> The user's file, for messages
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: compiler
        type(error_type), allocatable, intent(out) :: error
        !> The compiler's language, for messages (default Fortran)
        character(len=*), intent(in), optional :: language
        character(len=:), allocatable :: search, folder, kind
        integer :: length, stat, start, colon

        kind = "Fortran"
        if (present(language)) kind = language

        if (index(name, "/") > 0) then
            compiler = name
            if (is_executable(name)) return
            call fatal_error(error, path // ": cannot build this UCOSUB: the " // kind &
                & // " compiler " // name // " is not an executable file", stat_io)
            return
        end if
        call get_environment_variable("PATH", length=length, status=stat)
        if (stat /= 0 .or. length == 0) then
            call fatal_error(error, path // ": cannot build this UCOSUB: PATH is " &
                & // trim(merge("empty", "unset", stat == 0)) // ", so the " // kind &
                & // " compiler '" // name // "' cannot be found; set PATH to the folders of " &
                & // name &
                & // " and the system's tools (e.g. PATH=/usr/bin:/bin)", stat_io)
            return
        end if
        allocate(character(len=length) :: search)
        call get_environment_variable("PATH", search)
        start = 1
        do while (start <= len(search) + 1)
            colon = index(search(start:), ":")
            if (colon == 0) colon = len(search) - start + 2
            folder = search(start:start + colon - 2)
            ! an empty entry of PATH is the working folder
            if (len(folder) == 0) folder = "."
            compiler = folder // "/" // name
            if (is_executable(compiler)) return
            start = start + colon
        end do
        call fatal_error(error, path // ": cannot build this UCOSUB: the " // kind &
            & // " compiler '" // name // "' is in no folder of PATH (" // search &
            & // "); install it or add its " &
            & // "folder to PATH", stat_io)
    end subroutine find_compiler

    !> When building failed because the disk of the cache folder is full, say so: the
    !> compiler and the linker then fail with messages of their own, or none (their log is
    !> on the same disk). Seen in the error's message, in build.log, or by writing a probe.
    subroutine say_when_disk_full(path, cache_dir, dir, error, disk_full)
        character(len=*), intent(in) :: path, cache_dir, dir
        type(error_type), allocatable, intent(inout) :: error
        !> The disk is full (and error says so)
        logical, intent(out) :: disk_full
        character(len=*), parameter :: full = "No space left on device"
        character(len=:), allocatable :: log
        type(error_type), allocatable :: probe_error, ignored
        type(c_stream_type) :: probe

        disk_full = index(error%message, full) > 0
        if (.not. disk_full) then
            call read_input_file(dir // "/build.log", "build log", text_input_limit, log, &
                & ignored)
            if (.not. allocated(ignored)) disk_full = index(log, full) > 0
        end if
        if (.not. disk_full) then
            ! 64 KiB: more than a build writes at its last step, less than any real margin
            call probe%open_file(dir // "/space-probe", probe_error)
            if (.not. allocated(probe_error)) call probe%put(repeat(" ", 65536), probe_error)
            if (.not. allocated(probe_error)) call probe%close_file(probe_error)
            if (probe%is_open()) call probe%close_file(ignored)
            if (allocated(probe_error)) disk_full = index(probe_error%message, full) > 0
            call delete_probe(dir // "/space-probe")
        end if
        if (.not. disk_full) return
        error%message = path // ": cannot build this UCOSUB: no space left on device in the " &
            & // "cache folder " // cache_dir // " (" // full // "); free space there, or set " &
            & // "XDG_CACHE_HOME to a folder on another disk. The build stopped with: " &
            & // first_line(error%message)
        error%stat = stat_io
    end subroutine say_when_disk_full

    !> Remove the probe file of say_when_disk_full, if it is there.
    subroutine delete_probe(path)
        character(len=*), intent(in) :: path
        integer :: unit, stat

        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete", iostat=stat)
    end subroutine delete_probe

    !> The text up to its first line end.
    pure function first_line(text) result(line)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: line
        integer :: cut

        cut = index(text, new_line("a"))
        if (cut == 0) then
            line = text
        else
            line = text(:cut - 1)
        end if
    end function first_line

    !> Run the compiler: the user's source, the shim, then the link; the first failure is an
    !> error quoting build.log (for the source: at the first line gfortran complains about).
    subroutine compile_and_link(path, kind, compiler, name, flags, dir, kept_log, error, &
            & c_compiler, c_name)
        character(len=*), intent(in) :: path
        integer, intent(in) :: kind
        !> The compiler's path (find_compiler) and its name, for messages
        character(len=*), intent(in) :: compiler, name
        character(len=*), intent(in) :: flags, dir
        !> Where build.log is kept after a failure, for the message
        character(len=*), intent(in) :: kept_log
        type(error_type), allocatable, intent(out) :: error
        !> The C compiler's path and name, which compiles a .c file (kind_c)
        character(len=*), intent(in) :: c_compiler, c_name
        character(len=:), allocatable :: log, object, form, diagnostics, run, source_run, &
            & source_name
        integer :: stat, command_stat

        log = dir // "/build.log"
        run = shell_quote(compiler)
        object = shell_quote(dir // "/user.o")
        source_run = run // " -J " // shell_quote(dir)
        source_name = name
        if (kind == kind_c) then
            source_run = shell_quote(c_compiler)
            source_name = c_name
        end if
        if (kind == kind_object) then
            object = shell_quote(path)
        else
            call execute_command_line(source_run // " -c " // flags // " " // shell_quote(path) &
                & // " -o " // object // " > " // shell_quote(log) // " 2>&1", exitstat=stat, &
                & cmdstat=command_stat)
            call compiler_missing(source_name, path, stat, command_stat, error)
            if (allocated(error)) return
            if (stat /= 0) then
                form = "free form"
                if (kind == kind_fixed) form = "fixed form, -std=legacy"
                if (kind == kind_c) form = "C"
                call text_head(log, quoted_lines, diagnostics)
                call fatal_error(error, first_location(path, diagnostics) // ": " // source_name &
                    & // " could not compile this file of user routines (" // form // "); its " &
                    & // "diagnostics " &
                    & // "(all in " // kept_log // "):" // new_line("a") // diagnostics, stat_ucon)
                return
            end if
        end if
        call execute_command_line(run // " -c " // compile_flags(kind_free) // " -J " &
            & // shell_quote(dir) // " " // shell_quote(dir // "/rollcon_shim.f90") // " -o " &
            & // shell_quote(dir // "/rollcon_shim.o") // " >> " // shell_quote(log) // " 2>&1", &
            & exitstat=stat, cmdstat=command_stat)
        call compiler_missing(name, path, stat, command_stat, error)
        if (allocated(error)) return
        if (stat /= 0) then
            call text_head(log, quoted_lines, diagnostics)
            call fatal_error(error, dir // "/rollcon_shim.f90: " // name // " could not " &
                & // "compile rollcon's shim (log: " // kept_log // "):" // new_line("a") &
                & // diagnostics, stat_ucon)
            return
        end if
        call execute_command_line(run // " -shared " // object // " " &
            & // shell_quote(dir // "/rollcon_shim.o") // " -o " &
            & // shell_quote(dir // "/" // library_name) // " >> " // shell_quote(log) // " 2>&1", &
            & exitstat=stat, cmdstat=command_stat)
        call compiler_missing(name, path, stat, command_stat, error)
        if (allocated(error)) return
        if (stat /= 0) then
            call text_head(log, quoted_lines, diagnostics)
            call fatal_error(error, path // ": linking it into a shared library failed (an " &
                & // "object must be compiled with -fPIC; it must not define UCOVAR or ERRMES " &
                & // "itself); " // name // " says (log: " // kept_log // "):" &
                & // new_line("a") // diagnostics, stat_ucon)
        end if
    end subroutine compile_and_link

    !> An error when the shell could not run the compiler at all.
    subroutine compiler_missing(compiler, path, stat, command_stat, error)
        character(len=*), intent(in) :: compiler, path
        integer, intent(in) :: stat, command_stat
        type(error_type), allocatable, intent(out) :: error

        ! 127 is the shell's status for a command it cannot find (or run: /bin/sh missing)
        if (command_stat /= 0 .or. stat == 127) then
            call fatal_error(error, path // ": cannot run the compiler '" // compiler &
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

    !> Name of a cache entry: the FNV-1a 64 hash (rollcon_hash) of content, flags and shim, as
    !> 16 hexadecimal digits (the entry's source copy is also compared byte for byte).
    pure function content_key(content, flags) result(key)
        character(len=*), intent(in) :: content, flags
        character(len=:), allocatable :: key
        type(fnv1a64_type) :: hash
        integer :: i

        call hash%add(content)
        call hash%add(achar(0) // flags // achar(0))
        do i = 1, size(shim_source_lines)
            call hash%add(trim(shim_source_lines(i)) // achar(10))
        end do
        key = hash%hex()
    end function content_key

    !> ".f" of "dir/name.f" (the extension as written, with its dot).
    pure function extension_of(path) result(extension)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: extension

        extension = path(index(path, ".", back=.true.):)
    end function extension_of


end module rollcon_user_build
