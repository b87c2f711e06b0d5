! SPDX-License-Identifier: MIT
!> Where a study's base and its CSV are looked for (suite study-paths): a base dataset named
!> without a folder (scene = 'base.adm') is that file, not data/base.adm.nml; a CSV whose lines
!> end in CR LF (saved on Windows) is refused saying so, where the two headers it was compared
!> with printed identically.
module test_study_paths
    use rollcon_error, only : error_type
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_run, only : study_plan_type, plan_study
    use rollcon_study_csv, only : study_header
    use rollcon_testing, only : unittest_type, new_unittest, check
    use study_texts, only : write_study
    implicit none
    private

    public :: collect_study_paths

contains

    subroutine collect_study_paths(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("bare-dataset-name-is-the-file", test_bare_dataset), &
            & new_unittest("crlf-csv-refused-saying-so", test_crlf)]
    end subroutine collect_study_paths

    !> scene = 'no_such_base.adm': the message names that file, never data/...nml.
    subroutine test_bare_dataset(error)
        type(error_type), allocatable, intent(out) :: error
        type(study_type) :: study
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path

        call write_study("test_study_bare", [character(len=60) :: "&study", &
            & "    scene = 'no_such_base.adm' /", "&grid", "    part%2%vx = '0 1 2' /"], path)
        call read_study(path, study, found)
        call check(error, allocated(found), "a missing base dataset was accepted")
        if (allocated(error)) return
        call check(error, index(found%message, "no_such_base.adm") > 0 .and. &
            & index(found%message, ".adm.nml") == 0 .and. index(found%message, "data/") == 0, &
            & "message: " // found%message)
    end subroutine test_bare_dataset

    !> The study's own CSV, its lines ending in CR LF: plan_study refuses it, saying so.
    subroutine test_crlf(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: csv = "build/test_study_crlf.csv"
        type(study_type) :: study
        type(study_plan_type) :: plan
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path
        integer :: unit

        call write_study("test_study_crlf", [character(len=60) :: "&study", &
            & "    scene = 'coin' /", "&grid", "    initial%speed = '0.5 1 2' /"], path)
        call read_study(path, study, error)
        if (allocated(error)) return
        open(newunit=unit, file=csv, status="replace", access="stream", form="unformatted")
        write(unit) study_header(study) // achar(13) // achar(10)
        close(unit)
        call plan_study(study, csv, plan, found)
        call check(error, allocated(found), "a CSV with CR LF line ends was accepted")
        if (allocated(error)) return
        call check(error, index(found%message, csv // ":1: its lines end in CR LF") == 1, &
            & "message: " // found%message)
    end subroutine test_crlf

end module test_study_paths
