! SPDX-License-Identifier: MIT
!> Scene files written by the tests under build/, read back, and their errors checked.
module scene_texts
    use rollcon_error, only : error_type, stat_input
    use rollcon_scene, only : scene_type, read_scene
    use rollcon_testing, only : check
    implicit none
    private

    public :: read_text, expect_input_error, check_input_error, expect_accepted, width

    !> Width of the lines of a test file
    integer, parameter :: width = 120

contains

    !> Write lines (trailing blanks removed) to a file under build/, read it as a scene, delete
    !> it.
    subroutine read_text(name, lines, scene, found, path)
        character(len=*), intent(in) :: name, lines(:)
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: found
        character(len=:), allocatable, intent(out) :: path
        integer :: unit, i

        path = "build/test_scene_" // name // ".nml"
        open(newunit=unit, file=path, status="replace", action="write")
        do i = 1, size(lines)
            write(unit, "(a)") trim(lines(i))
        end do
        close(unit)
        call read_scene(path, scene, found)
        open(newunit=unit, file=path, status="old")
        close(unit, status="delete")
    end subroutine read_text

    !> Reading lines must fail with an input error whose message holds every fragment; a
    !> leading '@' in a fragment stands for the file's path.
    subroutine expect_input_error(error, name, lines, fragments)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, lines(:), fragments(:)
        type(scene_type) :: scene
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path

        call read_text(name, lines, scene, found, path)
        call check_input_error(error, name, found, path, fragments)
    end subroutine expect_input_error

    !> found must be an input error whose message holds every fragment; a leading '@' in a
    !> fragment stands for path, the file read.
    subroutine check_input_error(error, name, found, path, fragments)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, path, fragments(:)
        type(error_type), allocatable, intent(in) :: found
        character(len=:), allocatable :: fragment
        integer :: i

        if (.not. allocated(found)) then
            call check(error, .false., name // ": no error reported")
            return
        end if
        call check(error, found%stat == stat_input, name // ": stat is not stat_input: " &
            & // found%message)
        if (allocated(error)) return
        do i = 1, size(fragments)
            fragment = trim(fragments(i))
            if (fragment(1:1) == "@") fragment = path // fragment(2:)
            call check(error, index(found%message, fragment) > 0, name // ": message '" &
                & // found%message // "' lacks '" // fragment // "'")
            if (allocated(error)) return
        end do
    end subroutine check_input_error

    !> Reading lines must succeed.
    subroutine expect_accepted(name, lines, scene, error)
        character(len=*), intent(in) :: name, lines(:)
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        call read_text(name, lines, scene, error, path)
    end subroutine expect_accepted

end module scene_texts
