! SPDX-License-Identifier: MIT
!> The dataset lexer: title, statements with and without ids, continuation lines, comments,
!> value lists, expressions with commas inside parentheses, and one refusal per kind.
module test_adm_lexer
    use rollcon_error, only : error_type
    use rollcon_adm_lexer, only : adm_text_type, read_adm_text, is_number_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_adm_lexer

    character(len=*), parameter :: work_dir = "build/rollcon-test"

contains

    subroutine collect_adm_lexer(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("statements-and-arguments", test_statements), &
            & new_unittest("continuation-and-comments", test_continuation), &
            & new_unittest("numbers", test_numbers), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_adm_lexer

    !> Write `lines` (joined by new lines) to a file under build/ and read it.
    subroutine lex(name, lines, dataset, error)
        character(len=*), intent(in) :: name, lines(:)
        type(adm_text_type), intent(out) :: dataset
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, i

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        do i = 1, size(lines)
            write(unit, '(a)') trim(lines(i))
        end do
        close(unit)
        call read_adm_text(work_dir // "/" // name, dataset, error)
    end subroutine lex

    subroutine test_statements(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_text_type) :: dataset

        call lex("lexer_statements.adm", [character(len=80) :: "coin model", &
            & "units/force = newton, mass=kilogram", "PART/1, GROUND", &
            & "Part/2, MASS=0.735, CM=3, IP=1, 2, 3, QG=0, 0, 0.1", &
            & "SFORCE/4, I=3, J=5, TRANSLATION, FUNCTION=STEP(TIME, 2, 0, 2.01, 1)*10", &
            & "ACCGRAV/KGRAV=-9.81", "END"], dataset, error)
        if (allocated(error)) return
        call check(error, dataset%title == "coin model", "title: " // dataset%title)
        if (allocated(error)) return
        call check(error, size(dataset%statements) == 6, "statements")
        if (allocated(error)) return
        associate (s => dataset%statements)
            call check(error, s(1)%name == "UNITS" .and. .not. s(1)%has_id &
                & .and. size(s(1)%arguments) == 2 .and. s(1)%arguments(1)%keyword == "FORCE" &
                & .and. s(1)%arguments(1)%values(1)%text == "newton", "UNITS")
            if (allocated(error)) return
            call check(error, s(2)%name == "PART" .and. s(2)%id == 1 .and. s(2)%line == 3 &
                & .and. s(2)%arguments(1)%keyword == "GROUND" &
                & .and. .not. s(2)%arguments(1)%assigned, "PART/1")
            if (allocated(error)) return
            call check(error, s(3)%id == 2 .and. size(s(3)%arguments) == 4 &
                & .and. size(s(3)%arguments(3)%values) == 3 &
                & .and. s(3)%arguments(3)%values(3)%text == "3" &
                & .and. s(3)%arguments(4)%keyword == "QG" &
                & .and. s(3)%arguments(4)%values(3)%text == "0.1", "PART/2 lists")
            if (allocated(error)) return
            call check(error, size(s(4)%arguments) == 4 &
                & .and. s(4)%arguments(3)%keyword == "TRANSLATION" &
                & .and. s(4)%arguments(4)%values(1)%text == "STEP(TIME, 2, 0, 2.01, 1)*10", &
                & "SFORCE expression")
            if (allocated(error)) return
            call check(error, s(5)%name == "ACCGRAV" .and. .not. s(5)%has_id &
                & .and. s(5)%arguments(1)%values(1)%text == "-9.81", "ACCGRAV")
            if (allocated(error)) return
            call check(error, s(6)%name == "END" .and. size(s(6)%arguments) == 0, "END")
        end associate
    end subroutine test_statements

    subroutine test_continuation(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_text_type) :: dataset

        call lex("lexer_continuation.adm", [character(len=80) :: "title", &
            & "! a comment line", "", "MARKER/3, PART=2  ! centre of mass", &
            & "  , QP = 0, 0,", "  , 0.1", ", REULER=0D, 90D, 0D", &
            & "UCON/1, FUNCTION=USER(2, 21,22,23,14,15,24,25,26,", &
            & ", 0.1, 1)\"], dataset, error)
        if (allocated(error)) return
        call check(error, size(dataset%statements) == 2, "statements")
        if (allocated(error)) return
        associate (m => dataset%statements(1), u => dataset%statements(2))
            call check(error, size(m%arguments) == 3 .and. size(m%arguments(2)%values) == 3 &
                & .and. m%arguments(2)%values(3)%text == "0.1" .and. m%arguments(2)%line == 5 &
                & .and. m%arguments(3)%line == 7 .and. m%arguments(3)%values(2)%text == "90D", &
                & "MARKER over four lines")
            if (allocated(error)) return
            call check(error, u%line == 8 .and. size(u%arguments) == 1 .and. index( &
                & u%arguments(1)%values(1)%text, "26, , 0.1, 1)") == 0 .and. index( &
                & u%arguments(1)%values(1)%text, "0.1, 1)") > 0, &
                & "USER list across lines: " // u%arguments(1)%values(1)%text)
        end associate
    end subroutine test_continuation

    subroutine test_numbers(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: numbers(8) = [character(len=10) :: "1", "-2.5", &
            & ".5", "1e3", "1.5D-3", "90D", "+7.", "2E+10"]
        character(len=*), parameter :: others(8) = [character(len=10) :: "GROUND", "1e", &
            & "1.2.3", "-", "D", "1DX", "1e+", "."]
        integer :: i

        do i = 1, size(numbers)
            call check(error, is_number_text(numbers(i)), trim(numbers(i)) // " not a number")
            if (allocated(error)) return
        end do
        do i = 1, size(others)
            call check(error, .not. is_number_text(others(i)), trim(others(i)) // " a number")
            if (allocated(error)) return
        end do
    end subroutine test_numbers

    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: bodies(5) = [character(len=40) :: ", MASS=1", &
            & "PART/1,, MASS=1", "PART/1, MASS=1, 2", "PART/-3", "UCON/1, FUNCTION=USER(1, 2"]
        character(len=*), parameter :: expected(5) = [character(len=70) :: &
            & "lexer_refusal.adm:2: a continuation line", &
            & "lexer_refusal.adm:2: PART: an empty argument", &
            & "", &
            & "lexer_refusal.adm:2: PART: the id must be a positive integer, got '-3'", &
            & "lexer_refusal.adm:2: UCON: a '(' is not closed"]
        type(adm_text_type) :: dataset
        type(error_type), allocatable :: refused
        integer :: i

        do i = 1, size(bodies)
            call lex("lexer_refusal.adm", [character(len=40) :: "title", bodies(i)], dataset, &
                & refused)
            if (len_trim(expected(i)) == 0) then
                ! a number after an assignment extends its list: MASS gets two values, which
                ! the keyword layer refuses; the lexer must keep both
                call check(error, .not. allocated(refused), bodies(i))
                if (allocated(error)) return
                call check(error, size(dataset%statements(1)%arguments(1)%values) == 2, bodies(i))
            else
                call check(error, allocated(refused), trim(bodies(i)) // " accepted")
                if (allocated(error)) return
                call check(error, index(refused%message, trim(expected(i))) > 0, &
                    & refused%message)
                deallocate(refused)
            end if
            if (allocated(error)) return
        end do
    end subroutine test_refusals

end module test_adm_lexer
