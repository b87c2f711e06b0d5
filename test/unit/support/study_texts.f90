! SPDX-License-Identifier: MIT
!> Study files written by the tests under build/, read back, and their errors checked.
module study_texts
    use rollcon_error, only : error_type
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use scene_texts, only : check_input_error
    use picture_files, only : write_lines
    implicit none
    private

    public :: write_study, expect_study_error

contains

    !> Write lines (trailing blanks removed) to build/NAME.nml; path is that file.
    subroutine write_study(name, lines, path)
        character(len=*), intent(in) :: name, lines(:)
        character(len=:), allocatable, intent(out) :: path

        path = "build/" // name // ".nml"
        call write_lines(path, lines)
    end subroutine write_study

    !> Reading lines as a study must fail with an input error whose message holds every
    !> fragment; a leading '@' in a fragment stands for the file's path.
    subroutine expect_study_error(error, name, lines, fragments)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name, lines(:), fragments(:)
        type(study_type) :: study
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path

        call write_study(name, lines, path)
        call read_study(path, study, found)
        call check_input_error(error, name, found, path, fragments)
    end subroutine expect_study_error

end module study_texts
