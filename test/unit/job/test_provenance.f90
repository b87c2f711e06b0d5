! SPDX-License-Identifier: MIT
!> A run's record of what made it (suite provenance): the summary opens with rollcon's version,
!> the time and the command, and the UCOSUB that served the model (a built-in's name, or the
!> user's file with its size and FNV-1a 64 hash); the .parts file carries the same lines as
!> comments and still reads; the summary names the routine of every UCON. Through the program.
module test_provenance
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_version, only : version_text
    use rollcon_provenance, only : user_file_record
    use rollcon_hash, only : fnv1a64_type
    use rollcon_part_shapes, only : part_shape_type, read_part_shapes
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program, run_rollcon, file_text
    implicit none
    private

    public :: collect_provenance

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_provenance"
    !> The generated rolling disk's fixed-form file
    character(len=*), parameter :: disk_file = "ucon/adams/rolling_disk/ucosub.f"

contains

    subroutine collect_provenance(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("fnv1a-64-test-vectors", test_vectors), &
            & new_unittest("fnv1a-64-in-pieces", test_pieces), &
            & new_unittest("summary-names-built-in", test_built_in), &
            & new_unittest("summary-names-user-file", test_user_file), &
            & new_unittest("summary-names-each-ucon-routine", test_each_ucon), &
            & new_unittest("unused-ucosub-file-is-said", test_unused_file), &
            & new_unittest("summary-of-a-model-without-ucon", test_no_ucon), &
            & new_unittest("summary-says-what-files-define", test_files_define)]
    end subroutine collect_provenance

    !> user_file_record of files holding "", "a" and "foobar": their sizes and the FNV-1a 64 values
    !> published with the algorithm (the empty input gives the offset basis).
    subroutine test_vectors(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(3) = [character(len=6) :: "", "a", "foobar"]
        character(len=*), parameter :: hashes(3) = [character(len=16) :: "cbf29ce484222325", &
            & "af63dc4c8601ec8c", "85944171f73967e8"]
        character(len=:), allocatable :: path, expected
        integer :: k, unit

        call execute_command_line("mkdir -p " // scratch)
        do k = 1, size(texts)
            path = scratch // "/vector" // to_text(k)
            open(newunit=unit, file=path, status="replace", access="stream", form="unformatted")
            write(unit) trim(texts(k))
            close(unit)
            expected = to_text(len_trim(texts(k))) // " bytes, FNV-1a 64 " // hashes(k)
            call check(error, user_file_record(path) == expected, "'" // trim(texts(k)) // "': " &
                & // user_file_record(path) // ", expected " // expected)
            if (allocated(error)) return
        end do
        call check(error, index(user_file_record(scratch // "/missing"), "unreadable: ") == 1, &
            & "a missing file: " // user_file_record(scratch // "/missing"))
    end subroutine test_vectors

    !> Bytes fed in pieces hash as the whole does (a file is hashed a chunk at a time), and
    !> every byte value counts: the 256 bytes 0..255 fed one by one, against the value computed
    !> by the definition (h = (h xor b) * 1099511628211 mod 2**64) in Python.
    subroutine test_pieces(error)
        type(error_type), allocatable, intent(out) :: error
        type(fnv1a64_type) :: whole, pieces
        character(len=256) :: bytes
        integer :: k

        do k = 0, 255
            bytes(k + 1:k + 1) = achar(k)
        end do
        call whole%add(bytes)
        call pieces%add(bytes(:1))
        call pieces%add(bytes(2:100))
        call pieces%add("")
        call pieces%add(bytes(101:))
        call check(error, whole%hex() == pieces%hex() .and. whole%hex() == &
            & "4242dc5249c33625", "0..255: " // whole%hex() // " whole, " // pieces%hex() &
            & // " in pieces, expected 4242dc5249c33625")
    end subroutine test_pieces

    !> `run coin --ucosub rolling_disk`: the summary's first line is the version, a time and
    !> the command; its second names the built-in routine; the .parts file carries both as
    !> comments and still reads as the coin's one disk.
    subroutine test_built_in(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: arguments, summary, parts
        type(part_shape_type), allocatable :: shapes(:)

        arguments = "run coin --ucosub rolling_disk -q -o " // scratch // "/built_in"
        call run_into(arguments, "built_in", error)
        if (allocated(error)) return
        summary = file_text(scratch // "/built_in/coin.summary.txt")
        call check(error, starts(summary, version_text() // ", 20"), "the summary does not " &
            & // "open with the version and the date: " // first_lines(summary))
        if (allocated(error)) return
        call check(error, index(summary, ": rollcon " // arguments // new_line("a") &
            & // "the model's UCOSUB: rolling_disk (built in)" // new_line("a")) > 0, &
            & "the command or the routine is not recorded: " // first_lines(summary))
        if (allocated(error)) return
        parts = file_text(scratch // "/built_in/coin.parts")
        call check(error, index(parts, "# " // version_text() // ", 20") > 0 .and. &
            & index(parts, "# the model's UCOSUB: rolling_disk (built in)") > 0, &
            & "the .parts file does not carry the record: " // parts)
        if (allocated(error)) return
        call read_part_shapes(scratch // "/built_in/coin.parts", shapes, error)
        if (allocated(error)) return
        call check(error, size(shapes) == 1, "the .parts file reads as " &
            & // to_text(size(shapes)) // " parts, not the coin's one")
    end subroutine test_built_in

    !> `run data/coin.adm --ucosub ucon/adams/rolling_disk/ucosub.f`: the summary names the
    !> file with its size and hash, as user_file_record gives them.
    subroutine test_user_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: summary, expected

        call run_into("run data/coin.adm --ucosub " // disk_file // " -q -o " // scratch &
            & // "/user_file", "user_file", error)
        if (allocated(error)) return
        summary = file_text(scratch // "/user_file/coin.adm.summary.txt")
        expected = "the model's UCOSUB: " // disk_file // " (" // user_file_record(disk_file) &
            & // ")"
        call check(error, index(user_file_record(disk_file), " bytes, FNV-1a 64 ") > 0 .and. &
            & index(summary, new_line("a") // expected // new_line("a")) > 0, "expected '" &
            & // expected // "' in: " // first_lines(summary))
    end subroutine test_user_file

    !> data/disk_height.adm names its routines (ROUTINE=): the summary says which served each,
    !> and that the model's UCOSUB served none.
    subroutine test_each_ucon(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: summary

        call run_into("run data/disk_height.adm -q -o " // scratch // "/each", "each", error)
        if (allocated(error)) return
        summary = file_text(scratch // "/each/disk_height.adm.summary.txt")
        call check(error, index(summary, "routines: UCON/1 (line 38): rolling_disk, UCON/2 " &
            & // "(line 39): rolling_disk, UCON/3 (line 40): disk_height" // new_line("a")) > 0 &
            & .and. &
            & index(summary, "the model's UCOSUB: none (every UCON names its ROUTINE)" &
            & // new_line("a")) > 0, "no line naming the routines, or the model's UCOSUB " &
            & // "named though it serves no UCON, in: " // summary)
    end subroutine test_each_ucon

    !> `run data/disk_height.adm --ucosub FILE` where every UCON names its ROUTINE: the file
    !> serves nothing, so it is not compiled (a file that does not compile passes), the run
    !> completes, standard error and the summary say the file is not used, and the record names
    !> no model UCOSUB.
    subroutine test_unused_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, summary, stderr_text, broken
        character(len=*), parameter :: said = "is not used: every UCON of the model names " &
            & // "its ROUTINE"
        integer :: status, unit

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // "/unused && mkdir -p " // scratch)
        broken = scratch // "/broken_ucosub.f90"
        open(newunit=unit, file=broken, status="replace", action="write")
        write(unit, '(a)') "this is not Fortran"
        close(unit)
        call run_rollcon(program, "run data/disk_height.adm --ucosub " // broken // " -q -o " &
            & // scratch // "/unused", scratch // "/unused.out", scratch // "/unused.err", status)
        stderr_text = file_text(scratch // "/unused.err")
        call check(error, status == 0, "exited " // to_text(status) // ": " // stderr_text)
        if (allocated(error)) return
        call check(error, index(stderr_text, "warning: --ucosub " // broken // " " // said) > 0, &
            & "standard error does not say the file is unused: " // stderr_text)
        if (allocated(error)) return
        summary = file_text(scratch // "/unused/disk_height.adm.summary.txt")
        call check(error, index(summary, said) > 0 .and. index(summary, "the model's UCOSUB: " &
            & // "none (every UCON names its ROUTINE)" // new_line("a")) > 0, "the summary " &
            & // "names the unused file or does not say it is unused: " // first_lines(summary))
    end subroutine test_unused_file

    !> data/pendulum.adm has no UCON (a REVOLUTE joint alone): the record says the model has
    !> none, not that each names its routine; a --ucosub file given to it is said unused for
    !> that reason.
    subroutine test_no_ucon(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, summary, stderr_text
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // "/no_ucon && mkdir -p " // scratch)
        call run_rollcon(program, "run data/pendulum.adm --ucosub ucon/adams/rolling_disk/" &
            & // "ucosub.f -q -o " // scratch // "/no_ucon", scratch // "/no_ucon.out", &
            & scratch // "/no_ucon.err", status)
        stderr_text = file_text(scratch // "/no_ucon.err")
        call check(error, status == 0, "exited " // to_text(status) // ": " // stderr_text)
        if (allocated(error)) return
        call check(error, index(stderr_text, "is not used: the model has no UCON") > 0, &
            & "standard error does not say why the file is unused: " // stderr_text)
        if (allocated(error)) return
        summary = file_text(scratch // "/no_ucon/pendulum.adm.summary.txt")
        call check(error, index(summary, "the model's UCOSUB: none (the model has no UCON)" &
            & // new_line("a")) > 0 .and. index(summary, "every UCON names") == 0, &
            & "the record does not say the model has no UCON: " // first_lines(summary))
    end subroutine test_no_ucon

    !> The record words each user file by what it defines, as the run's child found it: a
    !> first file defining only an SFOSUB (spring.adm, no UCON) is no "model's UCOSUB" but
    !> "user routines: FILE (SFOSUB; size and hash)"; two files whose subroutines the UCONs
    !> name (ucon_two_files.adm) are each "routines named by ROUTINE=", and the model's UCOSUB
    !> served none.
    subroutine test_files_define(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: spring = "test/user_forces/sforce_spring.f", &
            & velocity = "test/user_forces/ucon_turn_velocity.f", &
            & circle = "test/user_forces/ucon_circle.f"
        character(len=:), allocatable :: summary
        character(len=1), parameter :: nl = new_line("a")

        call run_into("run test/user_forces/spring.adm --ucosub " // spring // " -q -o " &
            & // scratch // "/defines", "defines", error)
        if (allocated(error)) return
        summary = file_text(scratch // "/defines/spring.adm.summary.txt")
        call check(error, index(summary, nl // "the model's UCOSUB: none (the model has no " &
            & // "UCON)" // nl // "user routines: " // spring // " (SFOSUB; " &
            & // user_file_record(spring) // ")" // nl) > 0 .and. index(summary, "the model's " &
            & // "UCOSUB: " // spring) == 0, "the record does not say the file defines an " &
            & // "SFOSUB: " // first_lines(summary))
        if (allocated(error)) return
        call run_into("run test/user_forces/ucon_two_files.adm --ucosub " // velocity &
            & // " --ucosub " // circle // " -q -o " // scratch // "/defines", "defines", error)
        if (allocated(error)) return
        summary = file_text(scratch // "/defines/ucon_two_files.adm.summary.txt")
        call check(error, index(summary, nl // "the model's UCOSUB: none (every UCON names " &
            & // "its ROUTINE)" // nl // "user routines: " // velocity // " (routines named by " &
            & // "ROUTINE=; " // user_file_record(velocity) // ")" // nl // "user routines: " &
            & // circle // " (routines named by ROUTINE=; " // user_file_record(circle) // ")" &
            & // nl) > 0, "the record does not word the two files by what they define: " &
            & // first_lines(summary))
    end subroutine test_files_define

    !> Run rollcon with arguments; it must exit 0 with nothing on stderr.
    subroutine run_into(arguments, label, error)
        character(len=*), intent(in) :: arguments, label
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // "/" // label // " && mkdir -p " &
            & // scratch)
        call run_rollcon(program, arguments, scratch // "/" // label // ".out", scratch // "/" &
            & // label // ".err", status)
        call check(error, status == 0, "'rollcon " // arguments // "' exited " &
            & // to_text(status) // ": " // file_text(scratch // "/" // label // ".err"))
    end subroutine run_into

    pure logical function starts(text, head)
        character(len=*), intent(in) :: text, head

        starts = .false.
        if (len(text) >= len(head)) starts = text(:len(head)) == head
    end function starts

    !> The first three lines of text, for a message.
    function first_lines(text) result(lines)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: lines
        integer :: k, at

        at = 0
        do k = 1, 3
            if (at >= len(text)) exit
            if (index(text(at + 1:), new_line("a")) == 0) then
                at = len(text)
            else
                at = at + index(text(at + 1:), new_line("a"))
            end if
        end do
        lines = text(:at)
    end function first_lines

end module test_provenance
