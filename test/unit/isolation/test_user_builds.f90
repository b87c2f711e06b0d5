! SPDX-License-Identifier: MIT
!> Tests of `rollcon run --ucosub FILE` against its surroundings:
!> an empty PATH is refused with the reason, and output folders are made without a shell; a
!> cached library cut short on disk is rebuilt, not loaded; a full cache disk is named as
!> such. Each runs the program with its own cache folder under build/.
module test_user_builds
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count, &
        & mount_small, unmount
    implicit none
    private

    public :: collect_user_builds

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_user_builds"
    !> The generated ADAMS-ready disk routine: serves the coin's no-slip UCONs
    character(len=*), parameter :: disk_source = "ucon/adams/rolling_disk/ucosub.f"
    !> A short coin: the strike at 2 s is not reached, the run takes a fraction of a second
    character(len=*), parameter :: short_coin(3) = [character(len=24) :: "&run", &
        & "end_time = 0.5", "/"]

contains

    !> Tests of this suite.
    subroutine collect_user_builds(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("empty-path-refused", test_empty_path), &
            & new_unittest("output-folder-without-path", test_folder_without_path), &
            & new_unittest("cut-library-rebuilt", test_cut_library), &
            & new_unittest("full-cache-disk-named", test_full_cache)]
    end subroutine collect_user_builds

    !> With PATH empty, or naming no folder with the compiler, the build is refused with
    !> one line that says so: no "mkdir: not found", no runtime error, no backtrace.
    subroutine test_empty_path(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        character(len=*), parameter :: paths(2) = [character(len=24) :: "", &
            & "/no/such/folder"]
        character(len=*), parameter :: reasons(2) = [character(len=80) :: &
            & "PATH is empty, so the Fortran compiler 'gfortran' cannot be found", &
            & "the Fortran compiler 'gfortran' is in no folder of PATH (/no/such/folder)"]
        integer :: status, k

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        do k = 1, size(paths)
            call run_rollcon("XDG_CACHE_HOME=" // scratch // "/cache PATH=" // trim(paths(k)) &
                & // " " // program, "run coin --ucosub " // disk_source // " -q -o " &
                & // scratch // "/out", scratch // "/path.out", scratch // "/path.err", status)
            err = file_text(scratch // "/path.err")
            call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
                & "rollcon: error: " // disk_source // ": cannot build this UCOSUB: " &
                & // trim(reasons(k))) == 1, "PATH='" // trim(paths(k)) // "': exit status " &
                & // to_text(status) // ", stderr: " // err)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_empty_path

    !> The output folder and its parents are made through mkdir(2): a run with the built-in
    !> routine needs no PATH at all.
    subroutine test_folder_without_path(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, folder
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch // "/in")
        call write_scene(scratch // "/in/short.nml")
        folder = scratch // "/out/a/b"
        call run_rollcon("PATH= " // program, "run " // scratch // "/in/short.nml -q -o " &
            & // folder, scratch // "/nopath.out", scratch // "/nopath.err", status)
        call check(error, status == 0 .and. file_exists(folder // "/short.csv") .and. &
            & file_exists(folder // "/short.summary.txt") .and. len(file_text(scratch &
            & // "/nopath.err")) == 0, "exit status " // to_text(status) // ", stderr: " &
            & // file_text(scratch // "/nopath.err"))
        call remove_folder(scratch)
    end subroutine test_folder_without_path

    !> A cached libucosub.so cut to 12000 bytes (as a full disk or a killed copy leaves it)
    !> would crash the run that loads it (SIGBUS): its size and hash no longer match the
    !> record made when it was built, so it is rebuilt, the run says so and completes, and
    !> the next run takes it from the cache again.
    subroutine test_cut_library(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, run, out
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch // "/in")
        call write_scene(scratch // "/in/short.nml")
        program = "XDG_CACHE_HOME=" // scratch // "/cache " // program
        run = "run " // scratch // "/in/short.nml --ucosub " // disk_source // " -o " // scratch &
            & // "/out"
        call run_rollcon(program, run, scratch // "/first.out", scratch // "/first.err", status)
        call check(error, status == 0 .and. index(file_text(scratch // "/first.out"), &
            & "compiled now") > 0, "the first run failed: exit status " // to_text(status) &
            & // ", stderr: " // file_text(scratch // "/first.err"))
        if (.not. allocated(error)) then
            call execute_command_line("for f in " // scratch // "/cache/rollcon/*/libucosub.so; " &
                & // "do truncate -s 12000 $f; done", exitstat=status)
            call run_rollcon(program, run, scratch // "/second.out", scratch // "/second.err", &
                & status)
            out = file_text(scratch // "/second.out")
            call check(error, status == 0 .and. index(out, "libucosub.so is '12000 bytes, " &
                & // "FNV-1a 64 ") > 0 .and. index(out, "when it was built (cut or changed " &
                & // "on disk): rebuilt") > 0 .and. index(out, "compiled now") > 0, &
                & "the run after the cut: exit status " // to_text(status) // ", stdout: " &
                & // out // ", stderr: " // file_text(scratch // "/second.err"))
        end if
        if (.not. allocated(error)) then
            call run_rollcon(program, run, scratch // "/third.out", scratch // "/third.err", &
                & status)
            out = file_text(scratch // "/third.out")
            call check(error, status == 0 .and. index(out, "from the cache") > 0 .and. &
                & index(out, "rebuilt") == 0, "the rebuilt library is not reused: exit " &
                & // "status " // to_text(status) // ", stdout: " // out)
        end if
        call remove_folder(scratch)
    end subroutine test_cut_library

    !> A 40 KiB filesystem as the cache folder holds the copy of the source and the shim but
    !> not the objects and the library: the build fails, and the message says that the disk
    !> is full (gfortran's own failure said nothing of it).
    subroutine test_full_cache(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: mount_point = scratch // "/small"
        character(len=:), allocatable :: program, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch // "/in")
        call write_scene(scratch // "/in/short.nml")
        call mount_small(mount_point, "40k", error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        call run_rollcon("XDG_CACHE_HOME=" // mount_point // " " // program, "run " // scratch &
            & // "/in/short.nml -q --ucosub " // disk_source // " -o " // scratch // "/out", &
            & scratch // "/full.out", scratch // "/full.err", status)
        call unmount(mount_point)
        err = file_text(scratch // "/full.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, "rollcon: " &
            & // "error: " // disk_source // ": cannot build this UCOSUB: no space left on " &
            & // "device in the cache folder " // mount_point // "/rollcon (No space left on " &
            & // "device)") == 1, "exit status " // to_text(status) // ", stderr: " // err)
    end subroutine test_full_cache

    !> The coin for half a second.
    subroutine write_scene(path)
        character(len=*), intent(in) :: path
        integer :: unit, k

        open(newunit=unit, file=path, status="replace", action="write")
        do k = 1, size(short_coin)
            write(unit, "(a)") trim(short_coin(k))
        end do
        close(unit)
    end subroutine write_scene

end module test_user_builds
