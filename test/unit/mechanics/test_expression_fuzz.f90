! SPDX-License-Identifier: MIT
!> Fuzz test of the expression compiler (compile_expression, the FUNCTION= expressions of the
!> force statements): seeded mutations of the expressions of the shipped datasets and of
!> written ones covering every operator and function must each give a clean refusal (an input
!> error naming where the expression was read and the column, in visible characters) or a
!> program that is sound (expression_checks); never a crash or a hang. The inputs the fuzzer
!> found bugs with are kept as deterministic tests.
module test_expression_fuzz
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_expression, only : expression_type, evaluate_expression, switching_times
    use rollcon_adm_expression_parser, only : compile_expression, max_nesting
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_testing, only : unittest_type, new_unittest, check
    use fuzz_mutations, only : seed_fuzz, draw, mutate_text, printable
    use expression_checks, only : check_expression_program
    implicit none
    private

    public :: collect_expression_fuzz

    !> Mutated expressions compiled
    integer, parameter :: mutation_count = 20000
    !> Least share of each outcome: a compiler that refuses or accepts everything fails
    real(wp), parameter :: least_share = 0.05_wp
    !> Seed of the mutations
    integer, parameter :: seed = 20260523
    !> Where the expressions are said to be read (messages start with it)
    character(len=*), parameter :: where = "fuzz.adm:7: SFORCE/1 FUNCTION"
    !> Datasets whose force expressions are fuzzed
    character(len=*), parameter :: datasets(*) = [character(len=20) :: "data/coin.adm", &
        & "data/disk_height.adm"]
    !> Written expressions: every operator, function and state function, degrees, exponents
    character(len=*), parameter :: written(*) = [character(len=60) :: &
        & "STEP(TIME, 2, 0, 2.01, 1)*10", &
        & "HAVSIN(TIME, 0, 0, 1, 5) - 2**3**2", &
        & "ATAN2(DY(3), DX(3)) + MIN(1, MAX(2, 3))", &
        & "SQRT(ABS(-4)) + LOG(EXP(1))/TAN(0.5D)", &
        & "IF(TIME - 1: -1, 0, 1)*COS(PSI(3))", &
        & "-(-(+1.5e3))*DTOR + PI - .5E-2 + 1.5D-3", &
        & "WX(21)*VX(21) - THETA(21)**2 + PHI(21)/WZ(21)", &
        & "DZ(3) + VY(3) + VZ(3) + WY(3) + 90D", &
        & "sin(time)*step(time, 0, 0, 1d, 1) + if(dx(4): 1, 2, 3)", &
        & "((((1 + 2)*(3 - 4))/5)**2)", &
        & "1e308*10 - 1e-308/1e10"]
    !> Words a mutation may insert
    character(len=*), parameter :: words(*) = [character(len=8) :: "TIME", "PI", "DTOR", &
        & "SIN(", "COS(", "TAN(", "ATAN2(", "EXP(", "LOG(", "SQRT(", "ABS(", "MIN(", "MAX(", &
        & "STEP(", "HAVSIN(", "IF(", "DX(3)", "VZ(", "WY(21", "PSI(", "THETA(", "PHI(0)", &
        & "FOO(", "**", "*", "/", "-", "+", ":", ",", "(", ")", "1D", "1E", "1.5e-3", "\"]

contains

    !> Tests of this suite.
    subroutine collect_expression_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("mutated-expressions", test_mutated_expressions), &
            & new_unittest("deep-nesting-refused", test_deep_nesting), &
            & new_unittest("beyond-largest-number-refused", test_beyond_largest), &
            & new_unittest("bytes-shown-visibly", test_bytes_visible), &
            & new_unittest("overflowing-switch-times-left-out", test_switch_overflow)]
    end subroutine collect_expression_fuzz

    subroutine test_mutated_expressions(error)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type), allocatable :: bases(:)
        type(expression_type) :: expression
        type(error_type), allocatable :: found
        character(len=:), allocatable :: text
        integer :: m, refused, accepted, steps, k

        call base_expressions(bases, error)
        if (allocated(error)) return
        refused = 0
        accepted = 0
        call seed_fuzz(seed)
        do m = 1, mutation_count
            text = bases(1 + mod(m - 1, size(bases)))%text
            steps = 1 + draw(4)
            do k = 1, steps
                call mutate_text(text, words)
            end do
            call compile_expression(text, where, expression, found)
            if (allocated(found)) then
                refused = refused + 1
                call check_refusal(found, m, error)
            else
                accepted = accepted + 1
                call check_expression_program(expression, "mutation " // to_text(m), error)
            end if
            if (allocated(error)) return
        end do
        call check(error, min(refused, accepted) >= least_share*mutation_count, &
            & "outcomes too one-sided: " // to_text(refused) // " refused, " &
            & // to_text(accepted) // " accepted")
    end subroutine test_mutated_expressions

    !> The expressions to mutate: those of the shipped datasets' force statements and the
    !> written ones, each compiled as it is.
    subroutine base_expressions(bases, error)
        type(expression_type), allocatable, intent(out) :: bases(:)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        integer :: d, i, k

        allocate(bases(size(written)))
        do i = 1, size(written)
            call compile_expression(trim(written(i)), where, bases(i), error)
            if (allocated(error)) return
        end do
        do d = 1, size(datasets)
            call read_adm(trim(datasets(d)), model, error)
            if (allocated(error)) return
            do i = 1, size(model%forces)
                do k = 1, 6
                    if (model%forces(i)%given(k)) bases = [bases, model%forces(i)%functions(k)]
                end do
            end do
        end do
    end subroutine base_expressions

    !> An input error that starts with where, says what is wrong and at which column, and
    !> shows only printable ASCII.
    subroutine check_refusal(found, m, error)
        type(error_type), intent(in) :: found
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error

        call check(error, found%stat == stat_input .and. allocated(found%message), &
            & "mutation " // to_text(m) // ": not an input error")
        if (allocated(error)) return
        call check(error, printable(found%message), "mutation " // to_text(m) &
            & // ": invisible character in: " // found%message)
        if (allocated(error)) return
        call check(error, index(found%message, where // ": ") == 1 .and. &
            & index(found%message, " at column ") > len(where) + 3, "mutation " // to_text(m) &
            & // ": message without the place and the column: " // found%message)
    end subroutine check_refusal

    !> A million parentheses (a dataset may continue an expression over any number of lines)
    !> drove the recursive descent through the stack (a segmentation fault): nesting beyond
    !> max_nesting is refused; at max_nesting it compiles.
    subroutine test_deep_nesting(error)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        type(error_type), allocatable :: found
        integer, parameter :: depth = 1000000

        call compile_expression(repeat("(", depth) // "1" // repeat(")", depth), where, &
            & expression, found)
        call check(error, allocated(found), "a million parentheses compiled")
        if (allocated(error)) return
        call check(error, found%message == where // ": nested too deeply (more than " &
            & // to_text(max_nesting) // " levels of parentheses, signs and powers) at column " &
            & // to_text(max_nesting + 1) // " of '" // repeat("(", 400) // "... (" &
            & // to_text(2*depth + 1) // " characters)'", found%message(:min(600, &
            & len(found%message))))
        if (allocated(error)) return
        deallocate(found)
        call compile_expression(repeat("-", depth) // "1", where, expression, found)
        call check(error, allocated(found), "a million signs compiled")
        if (allocated(error)) return
        deallocate(found)
        ! max_nesting levels: max_nesting - 1 parentheses around a number (the whole
        ! expression is one level)
        call compile_expression(repeat("(", max_nesting - 1) // "2" // repeat(")", &
            & max_nesting - 1), where, expression, found)
        call check(error, .not. allocated(found), "nesting at the limit refused")
        if (allocated(error)) return
        call check(error, evaluate_expression(expression, 0.0_wp), 2.0_wp, &
            & "nesting at the limit: its value")
    end subroutine test_deep_nesting

    !> A number beyond the largest double (1.8e308) was read as infinity and compiled as a
    !> constant (the fuzzer's '...9999.5' of 315 digits in data/coin.adm's FY): refused. A
    !> finite number in degrees near the largest double stays finite.
    subroutine test_beyond_largest(error)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        type(error_type), allocatable :: found

        call compile_expression("TIME - " // repeat("9", 314) // ".5", where, expression, found)
        call check(error, allocated(found), "a constant of 315 digits compiled")
        if (allocated(error)) return
        call check(error, found%message == where // ": '" // repeat("9", 314) // ".5' is not a " &
            & // "finite number at column 8 of 'TIME - " // repeat("9", 314) // ".5'", &
            & found%message)
        if (allocated(error)) return
        deallocate(found)
        call compile_expression("1e309", where, expression, found)
        call check(error, allocated(found), "1e309 compiled")
        if (allocated(error)) return
        ! 1.7e308 written out, in degrees: value*pi would overflow, value*(pi/180) does not
        call compile_expression("17" // repeat("0", 307) // "D", where, expression, found)
        call check(error, .not. allocated(found), "1.7e308 degrees refused")
        if (allocated(error)) return
        call check(error, evaluate_expression(expression, 0.0_wp), 1.7e308_wp*(acos(-1.0_wp) &
            & /180.0_wp), "1.7e308 degrees in radians", rel_tol=epsilon(1.0_wp))
    end subroutine test_beyond_largest

    !> A control or non-ASCII byte in an expression is named visibly in the message.
    subroutine test_bytes_visible(error)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        type(error_type), allocatable :: found

        call compile_expression("1 + " // achar(0) // "2", where, expression, found)
        call check(error, allocated(found), "NUL compiled")
        if (allocated(error)) return
        call check(error, found%message == where // ": unexpected '\x00' at column 5 of " &
            & // "'1 + \x002'", found%message)
        if (allocated(error)) return
        deallocate(found)
        call compile_expression("2*" // achar(206) // achar(184), where, expression, found)
        call check(error, allocated(found), "theta compiled")
        if (allocated(error)) return
        call check(error, printable(found%message) .and. index(found%message, "U+03B8") > 0, &
            & found%message)
    end subroutine test_bytes_visible

    !> Constants that overflow when folded made switching times of Infinity or NaN (the
    !> fuzzer's 'HAVSIN(TIME, 1.7976931348623157e308*3, 0, 1, 5)'): such a switch never
    !> happens and is left out; the finite one beside it is kept.
    subroutine test_switch_overflow(error)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression
        real(wp), allocatable :: times(:)

        call compile_expression("HAVSIN(TIME, 1.7976931348623157e308*3, 0, 1, 5)", where, &
            & expression, error)
        if (allocated(error)) return
        times = switching_times(expression)
        call check(error, size(times) == 1, "switching times: " // to_text(size(times)))
        if (allocated(error)) return
        call check(error, times(1), 1.0_wp, "the finite switching time")
        if (allocated(error)) return
        call compile_expression("IF(TIME - 1e308*10 + 1e308*10: 0, 1, 2)", where, expression, &
            & error)
        if (allocated(error)) return
        times = switching_times(expression)
        call check(error, size(times) == 0, "a switch at Infinity - Infinity kept")
    end subroutine test_switch_overflow

end module test_expression_fuzz
