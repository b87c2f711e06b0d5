! SPDX-License-Identifier: MIT
!> Tests of the one reader of input files (src/foundation/rollcon_input_files.f90): lines split
!> as gfortran's formatted read splits them (LF, CR LF, a lone CR, a last line without its
!> end), across the reader's 64 KiB chunks; whole files as bytes; a file beyond its limit
!> refused naming the file and the limit, before reading and while reading; a directory, a
!> missing file, a FIFO and a character device refused at once, saying what they are.
module test_input_files
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_input_files, only : input_file_type, read_input_file, text_input_limit
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder
    implicit none
    private

    public :: collect_input_files

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_input_files"
    !> The reader's chunk: lines that cross it test the refill
    integer, parameter :: chunk = 65536

contains

    !> Tests of this suite.
    subroutine collect_input_files(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("lines-as-gfortran-reads-them", test_lines), &
            & new_unittest("lines-across-chunks", test_long_lines), &
            & new_unittest("whole-file-bytes", test_whole_file), &
            & new_unittest("beyond-limit-refused", test_limit), &
            & new_unittest("not-regular-refused", test_not_regular)]
    end subroutine collect_input_files

    !> Every line ending gfortran's formatted sequential read knows gives the same lines:
    !> the reader replaces those reads, so scenes must read as before.
    subroutine test_lines(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: cr = achar(13), lf = achar(10)
        character(len=32) :: texts(6)
        integer :: k

        texts(1) = "a" // lf // "bc" // lf
        texts(2) = "a" // cr // lf // "b" // cr // lf // lf
        texts(3) = "a" // cr // "b" // cr // cr // "c"
        texts(4) = "last line without its end" // lf // "x"
        texts(5) = lf // lf // " " // lf
        texts(6) = "tab" // achar(9) // "and NUL" // achar(0) // lf
        call make_folder(scratch)
        do k = 1, size(texts)
            call compare_with_gfortran(trim(texts(k)), "text " // to_text(k), error)
            if (allocated(error)) exit
        end do
        if (.not. allocated(error)) call compare_with_gfortran("", "an empty file", error)
        call remove_folder(scratch)
    end subroutine test_lines

    !> Lines longer than the chunk, and a CR LF whose CR ends a chunk: one line end each.
    subroutine test_long_lines(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text

        call make_folder(scratch)
        text = repeat("x", 3*chunk + 17) // achar(10) // repeat("y", chunk - 1) // achar(13) &
            & // achar(10) // "z" // achar(13)
        call compare_with_gfortran(text, "long lines", error)
        call remove_folder(scratch)
    end subroutine test_long_lines

    !> read_input_file gives the bytes as they are, across chunks.
    subroutine test_whole_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/whole.bin"
        character(len=:), allocatable :: text, content
        integer :: i

        call make_folder(scratch)
        allocate(character(len=2*chunk + 3) :: text)
        do i = 1, len(text)
            text(i:i) = achar(mod(i*7, 256))
        end do
        call write_bytes(path, text)
        call read_input_file(path, "test file", text_input_limit, content, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, len(content) == len(text) .and. content == text, "read back " &
            & // to_text(len(content)) // " bytes of " // to_text(len(text)))
    end subroutine test_whole_file

    !> A file one byte beyond the limit is refused before it is read, naming the file, its
    !> size and the limit; at the limit it reads.
    subroutine test_limit(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/big.txt"
        integer(int64), parameter :: limit = 100
        character(len=:), allocatable :: content

        call make_folder(scratch)
        call write_bytes(path, repeat("a", int(limit)))
        call read_input_file(path, "test file", limit, content, error)
        if (.not. allocated(error)) call check(error, len(content) == limit, &
            & "a file at the limit reads whole")
        if (.not. allocated(error)) then
            call write_bytes(path, repeat("a", int(limit) + 1))
            call read_input_file(path, "test file", limit, content, error)
            call expect(error, "beyond the limit", [character(len=200) :: path // ": is larger " &
                & // "than a test file may be: 101 bytes; the limit is 100 bytes"])
        end if
        call remove_folder(scratch)
    end subroutine test_limit

    !> A directory, a missing file, a FIFO nobody writes to and /dev/zero are refused at
    !> once (no wait, no endless read), each named with what it is.
    subroutine test_not_regular(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: fifo = scratch // "/fifo.nml", zero = scratch // "/zero"
        character(len=:), allocatable :: content
        integer :: status

        call remove_folder(scratch)
        call make_folder(scratch)
        call execute_command_line("mkfifo " // fifo // " && ln -s /dev/zero " // zero, &
            & exitstat=status)
        call check(error, status == 0, "mkfifo and ln -s failed")
        if (.not. allocated(error)) then
            call read_input_file(fifo, "scene file", text_input_limit, content, error)
            call expect(error, "a FIFO", [character(len=200) :: fifo // ": is a FIFO (named " &
                & // "pipe), not a regular file; a scene file is read from a regular file only"])
        end if
        if (.not. allocated(error)) then
            call read_input_file(zero, "dataset", text_input_limit, content, error)
            call expect(error, "/dev/zero", [character(len=200) :: zero // ": is a character " &
                & // "device", "; a dataset is read from a regular file only"])
        end if
        if (.not. allocated(error)) then
            call read_input_file(scratch, "study file", text_input_limit, content, error)
            call expect(error, "a directory", [character(len=200) :: scratch // ": is a " &
                & // "directory, not a study file"])
        end if
        if (.not. allocated(error)) then
            call read_input_file(scratch // "/none", "output CSV", text_input_limit, content, &
                & error)
            call expect(error, "a missing file", [character(len=200) :: scratch // "/none: no " &
                & // "such output CSV"])
        end if
        call remove_folder(scratch)
    end subroutine test_not_regular

    !> The reader's lines of text equal gfortran's formatted reads of the same bytes.
    subroutine compare_with_gfortran(text, name, error)
        character(len=*), intent(in) :: text, name
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/lines.txt"
        type(input_file_type) :: file
        character(len=:), allocatable :: line, expected
        integer :: unit, stat, got, count
        character(len=1000) :: piece
        logical :: done

        call write_bytes(path, text)
        call file%open(path, "test file", text_input_limit, error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read", form="formatted", &
            & access="sequential")
        count = 0
        do
            call file%next_line(line, done, error)
            if (allocated(error)) exit
            ! gfortran's line, read in pieces as the old reader did
            expected = ""
            do
                read(unit, "(a)", advance="no", size=got, iostat=stat) piece
                expected = expected // piece(:got)
                if (stat /= 0) exit
            end do
            if (is_iostat_end(stat) .and. len(expected) == 0) then
                call check(error, done, name // ": the reader has a line " // to_text(count + 1) &
                    & // " that gfortran does not")
                exit
            end if
            count = count + 1
            call check(error, .not. done, name // ": gfortran has a line " // to_text(count) &
                & // " that the reader does not")
            if (allocated(error)) exit
            call check(error, len(line) == len(expected) .and. line == expected, name &
                & // ": line " // to_text(count) // " differs (" // to_text(len(line)) &
                & // " against " // to_text(len(expected)) // " characters)")
            if (allocated(error) .or. is_iostat_end(stat)) exit
        end do
        close(unit)
        if (.not. allocated(error) .and. is_iostat_end(stat) .and. .not. done) then
            call file%next_line(line, done, error)
            if (.not. allocated(error)) call check(error, done, name // ": the reader has " &
                & // "more lines than gfortran")
        end if
        call file%close()
    end subroutine compare_with_gfortran

    !> error must be an input error holding every fragment.
    subroutine expect(error, name, fragments)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: name, fragments(:)
        type(error_type), allocatable :: found
        integer :: i

        call move_alloc(error, found)
        call check(error, allocated(found), name // ": no error")
        if (allocated(error)) return
        call check(error, found%stat == stat_input, name // ": not an input error: " &
            & // found%message)
        do i = 1, size(fragments)
            if (allocated(error)) return
            call check(error, index(found%message, trim(fragments(i))) > 0, name &
                & // ": message '" // found%message // "' lacks '" // trim(fragments(i)) // "'")
        end do
    end subroutine expect

    !> Write bytes as a whole file.
    subroutine write_bytes(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit

        open(newunit=unit, file=path, access="stream", form="unformatted", status="replace", &
            & action="write")
        if (len(text) > 0) write(unit) text
        close(unit)
    end subroutine write_bytes

end module test_input_files
