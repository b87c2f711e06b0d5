! SPDX-License-Identifier: MIT
!> Tests of the calls rollcon makes to the C library itself (src/foundation/rollcon_system.f90,
!> rollcon_output_files's make_folders, rollcon_hash): folders made level by level without a
!> shell, every failure named (a file in the way, a name or a path too long for the system);
!> a flat folder removed; FNV-1a 64 against its published test vectors.
module test_system_calls
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_files, only : make_folders
    use rollcon_system, only : remove_flat_folder, path_kind, kind_directory, kind_missing
    use rollcon_hash, only : fnv1a64_type
    use rollcon_file_lock, only : file_lock_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: collect_system_calls

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_system_calls"

contains

    !> Tests of this suite.
    subroutine collect_system_calls(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("folders-made-level-by-level", test_make_folders), &
            & new_unittest("folder-failures-named", test_folder_failures), &
            & new_unittest("flat-folder-removed", test_remove_flat), &
            & new_unittest("fnv1a64-test-vectors", test_fnv), &
            & new_unittest("lock-held-once", test_lock)]
    end subroutine collect_system_calls

    !> a/b/c made with its parents, again without complaint, and with doubled and trailing
    !> slashes.
    subroutine test_make_folders(error)
        type(error_type), allocatable, intent(out) :: error

        call remove_folder(scratch)
        call make_folders(scratch // "/a/b/c", error)
        if (.not. allocated(error)) call make_folders(scratch // "/a/b/c", error)
        if (.not. allocated(error)) call make_folders(scratch // "//a//b/d/", error)
        if (.not. allocated(error)) then
            call check(error, is_folder(scratch // "/a/b/c") .and. is_folder(scratch &
                & // "/a/b/d"), "a/b/c and a/b/d are not folders")
        end if
        call remove_folder(scratch)
    end subroutine test_make_folders

    !> A file where a folder should be, a name longer than the system's 255 bytes and a path
    !> beyond PATH_MAX are each an error that names the folder and the reason.
    subroutine test_folder_failures(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: found
        character(len=:), allocatable :: long_name, long_path
        character(len=120) :: fragment

        call make_folder(scratch)
        call write_lines(scratch // "/file", [character(len=4) :: "text"])
        call make_folders(scratch // "/file/sub", found)
        call expect(error, found, "a file in the way", [character(len=120) :: scratch &
            & // "/file/sub: cannot create the folder: " // scratch // "/file exists and is " &
            & // "not a folder"])
        if (.not. allocated(error)) then
            long_name = repeat("n", 300)
            call make_folders(scratch // "/" // long_name // "/x", found)
            call expect(error, found, "a name of 300 bytes", [character(len=120) :: &
                & ": cannot create the folder " // scratch // "/nnn", ": File name too long"])
        end if
        if (.not. allocated(error)) then
            long_path = scratch // repeat("/p", 2100)
            call make_folders(long_path, found)
            ! a variable first: gfortran 12 sizes an array constructor's non-constant
            ! element wrongly
            fragment = "the folder's path is " // to_text(len(long_path)) // " characters " &
                & // "long; the system takes paths of at most 4095 (PATH_MAX)"
            call expect(error, found, "a path of 4223 characters", [fragment])
        end if
        call remove_folder(scratch)
    end subroutine test_folder_failures

    !> A folder of files is removed with them; a missing one is no error.
    subroutine test_remove_flat(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: status, kind, errno_value
        integer(int64) :: size

        call make_folder(scratch // "/flat")
        call write_lines(scratch // "/flat/one", [character(len=4) :: "1"])
        call write_lines(scratch // "/flat/.two", [character(len=4) :: "2"])
        status = remove_flat_folder(scratch // "/flat")
        call path_kind(scratch // "/flat", kind, size, errno_value)
        call check(error, status == 0 .and. kind == kind_missing, "the folder is still there " &
            & // "(errno " // to_text(status) // ")")
        if (.not. allocated(error)) call check(error, remove_flat_folder(scratch // "/flat") &
            & == 0, "removing a missing folder failed")
        call remove_folder(scratch)
    end subroutine test_remove_flat

    !> The published FNV-1a 64 values (Fowler, Noll, Vo): "", "a", "foobar", and one byte of
    !> each value 0..255 fed one by one equals the same bytes fed at once.
    subroutine test_fnv(error)
        type(error_type), allocatable, intent(out) :: error
        type(fnv1a64_type) :: empty, a, foobar, one_by_one, at_once
        character(len=256) :: bytes
        integer :: i

        call a%add("a")
        call foobar%add("foo")
        call foobar%add("bar")
        call check(error, empty%hex() == "cbf29ce484222325" .and. a%hex() == "af63dc4c8601ec8c" &
            & .and. foobar%hex() == "85944171f73967e8", "FNV-1a 64 of '', 'a', 'foobar': " &
            & // empty%hex() // " " // a%hex() // " " // foobar%hex())
        if (allocated(error)) return
        do i = 0, 255
            bytes(i + 1:i + 1) = achar(i)
            call one_by_one%add(achar(i))
        end do
        call at_once%add(bytes)
        call check(error, one_by_one%hex() == at_once%hex(), "bytes one by one and at once")
    end subroutine test_fnv

    !> A lock file held by one lock is refused to a second (flock locks belong to an open
    !> file, so even within one process), which is told the holder; released, its file goes
    !> and the second takes it.
    subroutine test_lock(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/study.csv.lock"
        type(file_lock_type) :: first, second
        character(len=:), allocatable :: holder
        logical :: held

        call make_folder(scratch)
        call first%acquire(path, held, holder, error)
        if (.not. allocated(error)) call check(error, .not. held .and. first%is_held(), &
            & "the first lock was not taken")
        if (.not. allocated(error)) call second%acquire(path, held, holder, error)
        if (.not. allocated(error)) call check(error, held .and. .not. second%is_held() &
            & .and. index(holder, "process ") == 1 .and. index(holder, " on host ") > 0, &
            & "the second lock: held " // merge("yes", "no ", held) // ", holder '" // holder &
            & // "'")
        if (.not. allocated(error)) then
            call first%release()
            call check(error, .not. is_there(path), "the lock file stayed after release")
        end if
        if (.not. allocated(error)) call second%acquire(path, held, holder, error)
        if (.not. allocated(error)) call check(error, .not. held .and. second%is_held(), &
            & "the lock was not taken after its release")
        call second%release()
        call remove_folder(scratch)
    end subroutine test_lock

    logical function is_there(path)
        character(len=*), intent(in) :: path

        inquire(file=path, exist=is_there)
    end function is_there

    logical function is_folder(path)
        character(len=*), intent(in) :: path
        integer :: kind, errno_value
        integer(int64) :: size

        call path_kind(path, kind, size, errno_value)
        is_folder = kind == kind_directory
    end function is_folder

    !> found must be an error holding every fragment.
    subroutine expect(error, found, name, fragments)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable, intent(in) :: found
        character(len=*), intent(in) :: name, fragments(:)
        integer :: i

        call check(error, allocated(found), name // ": no error")
        do i = 1, size(fragments)
            if (allocated(error)) return
            call check(error, index(found%message, trim(fragments(i))) > 0, name &
                & // ": message '" // found%message // "' lacks '" // trim(fragments(i)) // "'")
        end do
    end subroutine expect

end module test_system_calls
