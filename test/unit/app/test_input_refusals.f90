! SPDX-License-Identifier: MIT
!> Every input file the `rollcon` program reads, given as a link to /dev/zero, as a FIFO that
!> nobody writes to, and one byte beyond its size limit (a sparse file): each is refused at
!> once, with one line naming the file and what it is (or the limit), exit status 1. Read
!> naively, these inputs are read or waited on forever: each run is given a time limit
!> (timeout), so such a run fails the test instead of holding it.
module test_input_refusals
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_input_files, only : text_input_limit, csv_input_limit, limit_text
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : make_folder, remove_folder, write_lines
    use command_runs, only : rollcon_program, run_rollcon, file_text, line_count
    implicit none
    private

    public :: collect_input_refusals

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_input_refusals"
    !> Seconds a refused run may take: it is refused before anything is read, in
    !> milliseconds; the old reader ran until this limit
    character(len=*), parameter :: time_limit = "20"
    !> The three kinds of bad input file
    character(len=*), parameter :: bad_kinds(3) = [character(len=4) :: "zero", "fifo", "big"]

contains

    !> Tests of this suite.
    subroutine collect_input_refusals(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("scene", test_scene), &
            & new_unittest("study", test_study), &
            & new_unittest("dataset", test_dataset), &
            & new_unittest("output-csv", test_output_csv), &
            & new_unittest("parts", test_parts), &
            & new_unittest("ucosub-source", test_ucosub_source), &
            & new_unittest("study-csv-on-resume", test_study_csv)]
    end subroutine collect_input_refusals

    !> rollcon run SCENE.nml
    subroutine test_scene(error)
        type(error_type), allocatable, intent(out) :: error

        call refuse_each("scene", "x.nml", "run @ -q -o " // scratch // "/out", &
            & text_input_limit, error)
    end subroutine test_scene

    !> rollcon sweep STUDY.nml
    subroutine test_study(error)
        type(error_type), allocatable, intent(out) :: error

        call refuse_each("study", "x.nml", "sweep @ -q -o " // scratch // "/out", &
            & text_input_limit, error)
    end subroutine test_study

    !> rollcon run MODEL.adm
    subroutine test_dataset(error)
        type(error_type), allocatable, intent(out) :: error

        call refuse_each("dataset", "x.adm", "run @ -q -o " // scratch // "/out", &
            & text_input_limit, error)
    end subroutine test_dataset

    !> rollcon plot RUN.csv
    subroutine test_output_csv(error)
        type(error_type), allocatable, intent(out) :: error

        call refuse_each("csv", "x.csv", "plot @ -o " // scratch // "/out", csv_input_limit, &
            & error)
    end subroutine test_output_csv

    !> rollcon plot RUN.csv of a sound run whose RUN.parts is the bad file.
    subroutine test_parts(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run coin -q -o " // scratch // "/good", scratch &
            & // "/good.out", scratch // "/good.err", status)
        call check(error, status == 0, "the coin's run failed: " // file_text(scratch &
            & // "/good.err"))
        if (.not. allocated(error)) call refuse_each("parts", "coin.parts", "plot " &
            & // "#/coin.csv -o " // scratch // "/out", text_input_limit, error, &
            & "cp " // scratch // "/good/coin.csv #/")
        call remove_folder(scratch)
    end subroutine test_parts

    !> rollcon run coin --ucosub FILE.f
    subroutine test_ucosub_source(error)
        type(error_type), allocatable, intent(out) :: error

        call refuse_each("ucosub", "x.f", "run coin -q -o " // scratch // "/out --ucosub @", &
            & text_input_limit, error)
    end subroutine test_ucosub_source

    !> rollcon sweep STUDY.nml resuming into a folder whose STUDY.csv is the bad file.
    subroutine test_study_csv(error)
        type(error_type), allocatable, intent(out) :: error

        call make_folder(scratch)
        call write_lines(scratch // "/small.nml", [character(len=40) :: "&study", &
            & "scene = 'data/upright.nml' /", "&grid", "initial%speed = '0.5 0.6 2' /"])
        call refuse_each("study-csv", "small.csv", "sweep " // scratch // "/small.nml -q " &
            & // "--no-map -o #", csv_input_limit, error)
        call remove_folder(scratch)
    end subroutine test_study_csv

    !> Run the command three times, with name in a folder of its own as a link to /dev/zero,
    !> as a FIFO, and as a sparse file one byte beyond limit; '@' in arguments stands for
    !> that file, '#' for its folder. Each run must be refused within the time limit with
    !> one line naming the file and what is wrong with it. prepare, when given, is a shell
    !> command run in each folder first ('#' stands for the folder there too).
    subroutine refuse_each(label, name, arguments, limit, error, prepare)
        character(len=*), intent(in) :: label, name, arguments
        integer(int64), intent(in) :: limit
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: prepare
        character(len=:), allocatable :: program, folder, path, make, expected, err, out
        integer :: k, status

        call rollcon_program(program, error)
        if (allocated(error)) return
        do k = 1, size(bad_kinds)
            folder = scratch // "/" // label // "-" // trim(bad_kinds(k))
            path = folder // "/" // name
            call make_folder(folder)
            if (present(prepare)) then
                call execute_command_line(replaced(replaced(prepare, "#", folder), "@", path), &
                    & exitstat=status)
            end if
            select case (bad_kinds(k))
            case ("zero")
                make = "ln -sf /dev/zero " // path
                expected = path // ": is a character device (such as /dev/zero or a " &
                    & // "terminal), not a regular file"
            case ("fifo")
                make = "rm -f " // path // " && mkfifo " // path
                expected = path // ": is a FIFO (named pipe), not a regular file"
            case default
                make = "rm -f " // path // " && truncate -s " // to_text(limit + 1) // " " // path
                expected = path // ": is larger than"
            end select
            call execute_command_line(make, exitstat=status)
            if (status /= 0) then
                call skip_test(error, "cannot make the test file: " // make)
                exit
            end if
            call run_rollcon("timeout " // time_limit // " " // program, &
                & replaced(replaced(arguments, "@", path), "#", folder), scratch // "/" &
                & // label // ".out", scratch // "/" // label // ".err", status)
            err = file_text(scratch // "/" // label // ".err")
            out = file_text(scratch // "/" // label // ".out")
            call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
                & "rollcon: error: " // expected) == 1, label // ", " // trim(bad_kinds(k)) &
                & // ": exit status " // to_text(status) // " (124: still reading after " &
                & // time_limit // " s), stderr: " // err // "; stdout: " // out)
            if (allocated(error)) exit
            if (bad_kinds(k) == "big") then
                call check(error, index(err, to_text(limit + 1) // " bytes; the limit is " &
                    & // limit_text(limit)) > 0, label // ": the size and the limit are not " &
                    & // "named: " // err)
                if (allocated(error)) exit
            end if
        end do
        call remove_folder(scratch // "/" // label // "-*")
    end subroutine refuse_each

    !> text with every `mark` replaced by `by`.
    pure function replaced(text, mark, by) result(result_text)
        character(len=*), intent(in) :: text, mark, by
        character(len=:), allocatable :: result_text
        integer :: j

        result_text = ""
        do j = 1, len(text)
            if (text(j:j) == mark) then
                result_text = result_text // by
            else
                result_text = result_text // text(j:j)
            end if
        end do
    end function replaced

end module test_input_refusals
