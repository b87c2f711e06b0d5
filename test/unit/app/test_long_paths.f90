! SPDX-License-Identifier: MIT
!> Long paths through the program: an --output of 603 characters takes
!> run, plot and sweep exactly there; a path the system cannot take (beyond PATH_MAX, or a
!> name beyond 255 bytes) is refused with one line that names it and says why; a cache folder
!> named by an XDG_CACHE_HOME longer than 4096 characters is used as named (cut to a
!> 4096-character buffer, it would make rollcon build in ~/.cache instead and exit 0).
module test_long_paths
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines, command_available
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count
    implicit none
    private

    public :: collect_long_paths

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_long_paths"

contains

    !> Tests of this suite.
    subroutine collect_long_paths(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("output-of-603-characters", test_output_603), &
            & new_unittest("path-beyond-path-max-refused", test_beyond_path_max), &
            & new_unittest("name-beyond-255-refused", test_long_name), &
            & new_unittest("cache-folder-not-cut", test_long_cache)]
    end subroutine collect_long_paths

    !> run, plot and sweep write into an --output folder of 603 characters (folders of 50
    !> characters), and nowhere else.
    subroutine test_output_603(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, folder, found
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        folder = long_folder(scratch // "/o", 603)
        call make_folder(scratch // "/in")
        call write_lines(scratch // "/in/short.nml", [character(len=24) :: "&run", &
            & "end_time = 0.5", "/"])
        call write_lines(scratch // "/in/pair.nml", [character(len=40) :: "&study", &
            & "scene = 'data/upright.nml' /", "&grid", "initial%speed = '0.5 0.6 2' /"])
        call run_rollcon(program, "run " // scratch // "/in/short.nml -q -o " // folder, &
            & scratch // "/run.out", scratch // "/run.err", status)
        call check(error, status == 0 .and. line_count(file_text(folder // "/short.csv")) &
            & == 52, "run: exit status " // to_text(status) // ", stderr: " // file_text(scratch &
            & // "/run.err"))
        if (.not. allocated(error) .and. command_available("gnuplot")) then
            call run_rollcon(program, "plot " // folder // "/short.csv -o " // folder, &
                & scratch // "/plot.out", scratch // "/plot.err", status)
            call check(error, status == 0 .and. file_exists(folder // "/short_theta.png"), &
                & "plot: exit status " // to_text(status) // ", stderr: " // file_text(scratch &
                & // "/plot.err"))
        end if
        if (.not. allocated(error)) then
            call run_rollcon(program, "sweep " // scratch // "/in/pair.nml -q --no-map -o " &
                & // folder, scratch // "/sweep.out", scratch // "/sweep.err", status)
            call check(error, status == 0 .and. line_count(file_text(folder // "/pair.csv")) &
                & == 3, "sweep: exit status " // to_text(status) // ", stderr: " &
                & // file_text(scratch // "/sweep.err"))
        end if
        if (.not. allocated(error)) then
            ! every CSV under the scratch folder is in the long one
            call execute_command_line("find " // scratch // " -name '*.csv' | awk '{ print " &
                & // "length($0) }' | sort -u > " // scratch // "/lengths.txt")
            found = file_text(scratch // "/lengths.txt")
            call check(error, found == to_text(len(folder) + len("/pair.csv")) // new_line("a") &
                & // to_text(len(folder) + len("/short.csv")) // new_line("a"), "CSVs written " &
                & // "with path lengths " // found)
        end if
        call remove_folder(scratch)
    end subroutine test_output_603

    !> An --output of 4200 characters is refused with one line: its length and PATH_MAX.
    subroutine test_beyond_path_max(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run coin -q -o " // long_folder(scratch // "/o", 4200), &
            & scratch // "/max.out", scratch // "/max.err", status)
        err = file_text(scratch // "/max.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, "the " &
            & // "folder's path is 4200 characters long; the system takes paths of at most " &
            & // "4095 (PATH_MAX)") > 0, "exit status " // to_text(status) // ", stderr: " &
            & // err(:min(len(err), 300)))
    end subroutine test_beyond_path_max

    !> A folder name of 300 bytes (the system's limit is 255) is refused with one line that
    !> names the level and the system's reason.
    subroutine test_long_name(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err, folder
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        folder = scratch // "/" // repeat("n", 300) // "/out"
        call run_rollcon(program, "run coin -q -o " // folder, scratch // "/name.out", &
            & scratch // "/name.err", status)
        err = file_text(scratch // "/name.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
            & "rollcon: error: " // folder // ": cannot create the folder " // scratch // "/" &
            & // repeat("n", 300) // ": File name too long") == 1, "exit status " &
            & // to_text(status) // ", stderr: " // err)
    end subroutine test_long_name

    !> XDG_CACHE_HOME of 4300 characters: the build is refused naming that folder's length,
    !> instead of going to another folder.
    subroutine test_long_cache(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err, cache
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        cache = long_folder(scratch // "/c", 4300)
        call run_rollcon("HOME=" // scratch // "/home XDG_CACHE_HOME=" // cache // " " &
            & // program, "run coin -q --ucosub ucon/adams/rolling_disk/ucosub.f -o " &
            & // scratch // "/out", scratch // "/cache.out", scratch // "/cache.err", status)
        err = file_text(scratch // "/cache.err")
        call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
            & "characters long; the system takes paths of at most 4095 (PATH_MAX)") > 0 &
            & .and. .not. file_exists(scratch // "/home/.cache/rollcon"), "exit status " &
            & // to_text(status) // ", stderr: " // err(:min(len(err), 300)))
        call remove_folder(scratch)
    end subroutine test_long_cache

    !> start followed by folders of 50 characters, cut to length characters.
    pure function long_folder(start, length) result(folder)
        character(len=*), intent(in) :: start
        integer, intent(in) :: length
        character(len=:), allocatable :: folder

        folder = start
        do while (len(folder) < length)
            folder = folder // "/" // repeat("x", 49)
        end do
        folder = folder(:length)
    end function long_folder

end module test_long_paths
