! SPDX-License-Identifier: MIT
!> The one way rollcon reads an input file: a scene, a study, a dataset, a .parts file, a CSV
!> read back for the pictures or a study's resume, a user's UCOSUB source. Only a regular file
!> is read (a directory, a FIFO, a device such as /dev/zero, a socket is refused, naming the
!> file and what it is), and never more than a limit for its kind (the file and the limit
!> are named): a link to /dev/zero cannot be read forever, a FIFO that nobody writes to
!> cannot hold the program, a huge file cannot take the memory.
!>
!> The file is opened without waiting (O_NONBLOCK), then what the open descriptor is, is
!> checked (so the file cannot be swapped between the check and the read), and the bytes are
!> counted while they are read (so a file that grows is stopped at the limit too).
!>
!>     type(input_file_type) :: file
!>     call file%open("data/coin.nml", "scene file", text_input_limit, error)
!>     do
!>         call file%next_line(line, done, error)
!>         if (done .or. allocated(error)) exit
!>     end do
!>     call file%close()
!>
!> Lines end at LF, CR LF or a lone CR, as gfortran's formatted read ends them; a last line
!> without its line end is a line.
module rollcon_input_files
    use, intrinsic :: iso_c_binding, only : c_int
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_io
    use rollcon_text, only : to_text
    use rollcon_hash, only : fnv1a64_type
    use rollcon_system, only : open_read, descriptor_kind, path_kind, path_kind_text, &
        & read_bytes_into, close_descriptor, system_reason, kind_missing, kind_regular, &
        & kind_directory, kind_unknown
    implicit none
    private

    public :: input_file_type, read_input_file, limit_text, file_record
    public :: text_input_limit, csv_input_limit, library_input_limit

    !> Largest file read as written by hand or by a tool for rollcon: a scene, a study, an
    !> ADAMS dataset, a .parts file, a UCOSUB source or object. The shipped scenes are under
    !> 2 KB and the datasets under 10 KB; the readers hold a file's lines and tokens in memory,
    !> several times its size, so 16 MiB keeps that well under a gigabyte.
    integer(int64), parameter :: text_input_limit = 16_int64*1024_int64**2
    !> Largest CSV read back: a run's CSV for the pictures (rows kept in memory as numbers),
    !> a study's CSV when a study resumes (read whole, as one string whose length is a default
    !> integer). A study of the largest size allowed (rollcon_study_parameters) writes about
    !> 0.5 GB, a 10 s coin run 0.5 MB.
    integer(int64), parameter :: csv_input_limit = 1024_int64**3
    !> Largest shared library hashed before a cached build is reused (rollcon_user_build); a
    !> UCOSUB's library is some 20 KB
    integer(int64), parameter :: library_input_limit = 256_int64*1024_int64**2

    !> Bytes read from the system at a time
    integer, parameter :: chunk_size = 65536

    !> An input file open for reading
    type :: input_file_type
        !> The file and what it is, for messages ("data/coin.nml", "scene file")
        character(len=:), allocatable :: path, what
        integer(c_int) :: fd = -1
        !> Most bytes read
        integer(int64) :: limit = 0
        !> Bytes read so far
        integer(int64) :: consumed = 0
        !> Bytes read but not yet handed out: buffer(next:filled)
        character(len=:), allocatable :: buffer
        integer :: next = 1, filled = 0
        !> The system said end of file
        logical :: at_end = .false.
        !> The last line handed out ended the file without a line end (a file cut while it was
        !> being written, or one whose last line has no end)
        logical :: unterminated = .false.
    contains
        procedure :: open => input_open
        procedure :: next_line => input_next_line
        procedure :: next_chunk => input_next_chunk
        procedure :: close => input_close
    end type input_file_type

contains

    !> Open path for reading: it must be a regular file of at most limit bytes. Messages
    !> name the file and say what it is, e.g. "data/x.nml: no such scene file",
    !> "data: is a directory, not a scene file", "x.nml: is a FIFO (named pipe), not a
    !> regular file; a scene file is read from a regular file only".
    subroutine input_open(self, path, what, limit, error)
        class(input_file_type), intent(inout) :: self
        !> File to read
        character(len=*), intent(in) :: path
        !> What it should be, for messages ("scene file", "dataset", "output CSV")
        character(len=*), intent(in) :: what
        !> Most bytes it may hold (text_input_limit, csv_input_limit)
        integer(int64), intent(in) :: limit
        type(error_type), allocatable, intent(out) :: error
        integer :: kind, errno_value
        integer(int64) :: size

        call self%close()
        self%path = path
        self%what = what
        self%limit = limit
        self%consumed = 0
        self%next = 1
        self%filled = 0
        self%at_end = .false.
        ! What the path names, before opening: a socket cannot be opened at all, so say what
        ! it is rather than the system's "No such device or address".
        call path_kind(path, kind, size, errno_value)
        if (kind /= kind_unknown) then
            call check_kind(self, kind, size, error)
            if (allocated(error)) return
        end if
        self%fd = open_read(path)
        if (self%fd < 0) then
            call fatal_error(error, path // ": cannot open the " // what // ": " &
                & // system_reason(), stat_io)
            return
        end if
        ! ... and again on what was opened, which cannot change under us
        call descriptor_kind(self%fd, kind, size)
        if (kind /= kind_unknown) call check_kind(self, kind, size, error)
        if (allocated(error)) then
            call self%close()
            return
        end if
        allocate(character(len=chunk_size) :: self%buffer)
    end subroutine input_open

    !> A regular file within the limit, or an error saying what the path is.
    subroutine check_kind(self, kind, size, error)
        type(input_file_type), intent(in) :: self
        integer, intent(in) :: kind
        integer(int64), intent(in) :: size
        type(error_type), allocatable, intent(out) :: error

        select case (kind)
        case (kind_regular)
            if (size > self%limit) call too_large(self, size, .false., error)
        case (kind_missing)
            call fatal_error(error, self%path // ": no such " // self%what, stat_input)
        case (kind_directory)
            call fatal_error(error, self%path // ": is a directory, not " &
                & // with_article(self%what), stat_input)
        case default
            call fatal_error(error, self%path // ": is " // path_kind_text(kind) // ", not a " &
                & // "regular file; " // with_article(self%what) // " is read from a regular " &
                & // "file only", stat_input)
        end select
    end subroutine check_kind

    !> The error of a file beyond its limit.
    subroutine too_large(self, size, at_least, error)
        type(input_file_type), intent(in) :: self
        integer(int64), intent(in) :: size
        !> The size is what was read so far (the file grew while it was read)
        logical, intent(in) :: at_least
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: amount

        amount = to_text(size) // " bytes"
        if (at_least) amount = "more than " // to_text(self%limit) // " bytes (it grew while " &
            & // "it was read)"
        call fatal_error(error, self%path // ": is larger than " // with_article(self%what) &
            & // " may be: " &
            & // amount // "; the limit is " // limit_text(self%limit) // " (docs/outputs.md, " &
            & // "input files)", stat_input)
    end subroutine too_large

    !> "a scene file", "an output CSV".
    pure function with_article(what) result(text)
        character(len=*), intent(in) :: what
        character(len=:), allocatable :: text

        text = "a " // what
        if (len(what) > 0) then
            if (index("aeiou", what(1:1)) > 0) text = "an " // what
        end if
    end function with_article

    !> A limit as people read it: "16 MiB (16777216 bytes)".
    pure function limit_text(limit) result(text)
        integer(int64), intent(in) :: limit
        character(len=:), allocatable :: text
        integer(int64), parameter :: mib = 1024_int64**2, gib = 1024_int64**3

        if (mod(limit, gib) == 0) then
            text = to_text(limit/gib) // " GiB"
        else if (mod(limit, mib) == 0) then
            text = to_text(limit/mib) // " MiB"
        else
            text = to_text(limit) // " bytes"
            return
        end if
        text = text // " (" // to_text(limit) // " bytes)"
    end function limit_text

    !> Read more bytes into the buffer (keeping those not handed out yet); at_end when the
    !> file has no more. An error when reading fails or passes the limit.
    subroutine refill(self, error)
        type(input_file_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: grown
        integer :: kept, got

        kept = self%filled - self%next + 1
        if (kept > 0 .and. self%next > 1) then
            self%buffer(:kept) = self%buffer(self%next:self%filled)
        end if
        self%next = 1
        self%filled = kept
        if (self%filled + chunk_size > len(self%buffer)) then
            ! a line longer than the buffer: grow it (the limit bounds the growth)
            allocate(character(len=2*len(self%buffer) + chunk_size) :: grown)
            grown(:self%filled) = self%buffer(:self%filled)
            call move_alloc(grown, self%buffer)
        end if
        call read_bytes_into(self%fd, self%buffer(self%filled + 1:self%filled + chunk_size), got)
        if (got < 0) then
            call fatal_error(error, self%path // ": cannot read the " // self%what // ": " &
                & // system_reason(), stat_io)
            return
        end if
        if (got == 0) then
            self%at_end = .true.
            return
        end if
        self%consumed = self%consumed + got
        self%filled = self%filled + got
        if (self%consumed > self%limit) call too_large(self, self%consumed, .true., error)
    end subroutine refill

    !> The next line, without its line end; done (and line "") when the file has no more.
    subroutine input_next_line(self, line, done, error)
        class(input_file_type), intent(inout) :: self
        character(len=:), allocatable, intent(out) :: line
        logical, intent(out) :: done
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: line_ends = achar(10) // achar(13)
        integer :: j, offset

        line = ""
        done = .false.
        if (self%fd < 0) then
            done = .true.
            return
        end if
        ! bytes after next already scanned and found without a line end
        offset = 0
        do
            j = 0
            if (self%next + offset <= self%filled) &
                & j = scan(self%buffer(self%next + offset:self%filled), line_ends)
            if (j > 0) then
                j = self%next + offset + j - 1
                ! a CR that ends the bytes read may be the first half of a CR LF
                if (self%buffer(j:j) == achar(13) .and. j == self%filled &
                    & .and. .not. self%at_end) then
                    offset = j - self%next
                    call refill(self, error)
                    if (allocated(error)) return
                    cycle
                end if
                line = self%buffer(self%next:j - 1)
                self%next = j + 1
                if (self%buffer(j:j) == achar(13) .and. self%next <= self%filled) then
                    if (self%buffer(self%next:self%next) == achar(10)) self%next = self%next + 1
                end if
                return
            end if
            if (self%at_end) then
                if (self%next > self%filled) then
                    done = .true.
                else
                    line = self%buffer(self%next:self%filled)
                    self%next = self%filled + 1
                    self%unterminated = .true.
                end if
                return
            end if
            offset = self%filled - self%next + 1
            call refill(self, error)
            if (allocated(error)) return
        end do
    end subroutine input_next_line

    !> The next bytes as they come (at most 64 KiB); done (and chunk "") at the end.
    subroutine input_next_chunk(self, chunk, done, error)
        class(input_file_type), intent(inout) :: self
        character(len=:), allocatable, intent(out) :: chunk
        logical, intent(out) :: done
        type(error_type), allocatable, intent(out) :: error

        chunk = ""
        done = .false.
        if (self%fd < 0) then
            done = .true.
            return
        end if
        if (self%next > self%filled) then
            if (.not. self%at_end) call refill(self, error)
            if (allocated(error)) return
        end if
        if (self%next > self%filled) then
            done = .true.
            return
        end if
        chunk = self%buffer(self%next:self%filled)
        self%next = self%filled + 1
    end subroutine input_next_chunk

    !> Close the file (nothing when it is not open).
    subroutine input_close(self)
        class(input_file_type), intent(inout) :: self
        logical :: ignored

        if (self%fd >= 0) ignored = close_descriptor(self%fd)
        self%fd = -1
        if (allocated(self%buffer)) deallocate(self%buffer)
        self%next = 1
        self%filled = 0
    end subroutine input_close

    !> The whole file as bytes, through input_file_type's checks.
    subroutine read_input_file(path, what, limit, content, error)
        !> File to read
        character(len=*), intent(in) :: path
        !> What it should be, for messages
        character(len=*), intent(in) :: what
        !> Most bytes it may hold
        integer(int64), intent(in) :: limit
        !> Its bytes
        character(len=:), allocatable, intent(out) :: content
        type(error_type), allocatable, intent(out) :: error
        type(input_file_type) :: file
        character(len=:), allocatable :: chunk, grown
        integer :: n
        logical :: done

        content = ""
        call file%open(path, what, limit, error)
        if (allocated(error)) return
        allocate(character(len=chunk_size) :: grown)
        n = 0
        do
            call file%next_chunk(chunk, done, error)
            if (done .or. allocated(error)) exit
            if (n + len(chunk) > len(grown)) then
                block
                    character(len=:), allocatable :: larger
                    allocate(character(len=max(2*len(grown), n + len(chunk))) :: larger)
                    larger(:n) = grown(:n)
                    call move_alloc(larger, grown)
                end block
            end if
            grown(n + 1:n + len(chunk)) = chunk
            n = n + len(chunk)
        end do
        call file%close()
        if (allocated(error)) return
        content = grown(:n)
    end subroutine read_input_file

    !> "N bytes, FNV-1a 64 HHHHHHHHHHHHHHHH" of a file, read through input_file_type's checks:
    !> what identifies a cached library and a user's source in a run's record.
    subroutine file_record(path, what, limit, record, error)
        !> File to read
        character(len=*), intent(in) :: path
        !> What it should be, for messages
        character(len=*), intent(in) :: what
        !> Most bytes it may hold
        integer(int64), intent(in) :: limit
        character(len=:), allocatable, intent(out) :: record
        type(error_type), allocatable, intent(out) :: error
        type(input_file_type) :: file
        type(fnv1a64_type) :: hash
        character(len=:), allocatable :: chunk
        integer(int64) :: size
        logical :: done

        record = ""
        call file%open(path, what, limit, error)
        if (allocated(error)) return
        size = 0
        do
            call file%next_chunk(chunk, done, error)
            if (done .or. allocated(error)) exit
            call hash%add(chunk)
            size = size + len(chunk)
        end do
        call file%close()
        if (allocated(error)) return
        record = to_text(size) // " bytes, FNV-1a 64 " // hash%hex()
    end subroutine file_record

end module rollcon_input_files
