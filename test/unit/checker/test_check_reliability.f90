! SPDX-License-Identifier: MIT
!> `rollcon check` ends, every time: each way of misusing the
!> initialisation call (UCOVAR with -1 variables, twice, NPARTS /= NVARS, code 99, a variable
!> twice, the wrong id, a part id of its own; ERRMES; three arguments; no UCOVAR) is checked
!> 20 times through the program and must end with its [declaration] finding within a time
!> bound each time; --ucon ID without PAR is checked with NPAR = 0; a count of states beyond
!> the maximum is refused with the reason.
module test_check_reliability
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucovar
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub, max_check_states
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program
    use check_command_support, only : bounded_run_type, run_bounded, make_folder, &
        & remove_folder, expect_in, timed_out
    implicit none
    private

    public :: collect_check_reliability

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_check_reliability"
    !> Faulty routines (test data)
    character(len=*), parameter :: faulty = "test/faulty_ucosubs/"
    !> The disk's UCON 1, as the documentation checks it
    character(len=*), parameter :: disk_ucon = "1:1,21,22,23,14,15,24,25,26,0.1,1"
    !> Runs of each case: a hang of the host reading a child's report comes in 30-50 % of the
    !> runs when the report's length is garbage (docs/design.md §7)
    integer, parameter :: repeats = 20
    !> Bound of one run [s]: a check that stops at the initialisation call takes milliseconds;
    !> the default time limit of one call of the routine is 10 s
    integer, parameter :: bound = 10
    !> Bound of the first run of a file, which compiles it [s]
    integer, parameter :: compile_bound = 120

    !> A routine that misuses the initialisation call, and what the check must say
    type :: misuse_case_type
        character(len=32) :: file
        character(len=40) :: ucon
        character(len=60) :: expected
    end type misuse_case_type

contains

    !> Tests of this suite.
    subroutine collect_check_reliability(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("misuse-ends-with-finding-every-time", test_misuse_repeated), &
            & new_unittest("ucon-without-par-checked", test_ucon_without_par), &
            & new_unittest("states-beyond-maximum-refused", test_states_maximum), &
            & new_unittest("library-refuses-states-beyond-maximum", test_library_states)]
    end subroutine collect_check_reliability

    !> The misuses of the initialisation call.
    pure function misuse_cases() result(cases)
        type(misuse_case_type) :: cases(10)

        cases = [misuse_case_type("ucovar_negative.f", "1:3,0.25", &
            & "UCOVAR declares -1 variables (NVARS)"), &
            & misuse_case_type("ucovar_twice.f", "1:3,0.25", "UCOVAR called twice"), &
            & misuse_case_type("ucovar_counts_differ.f", "1:3,0.25", &
            & "UCOVAR has NPARTS = 1 but NVARS = 2"), &
            & misuse_case_type("ucovar_unknown_code.f", "1:3,0.25", &
            & "UCOVAR variable 1 has code 99"), &
            & misuse_case_type("ucovar_variable_twice.f", "1:3,0.25", &
            & "UCOVAR variables 1 and 2 are both Z of part 3"), &
            & misuse_case_type("ucovar_wrong_id.f", "1:3,0.25", &
            & "UCOVAR was called with ID = 2"), &
            & misuse_case_type("ucovar_part_7.f", "1:3,0.25", &
            & "UCOVAR declares part id 7 (variable 1)"), &
            & misuse_case_type("errmes_init.f", "1:3,0.25", "UCON/1: PAR(2) is out of range"), &
            & misuse_case_type("three_arguments.f", "1:3,0.25", "made no UCOVAR call"), &
            & misuse_case_type("no_ucovar.f", disk_ucon, "made no UCOVAR call")]
    end function misuse_cases

    !> Each case 20 times: exit status 1, its finding, nothing on stderr, within the bound.
    subroutine test_misuse_repeated(error)
        type(error_type), allocatable, intent(out) :: error
        type(misuse_case_type) :: cases(10)
        type(bounded_run_type) :: run
        character(len=:), allocatable :: program, arguments
        integer :: c, r

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        cases = misuse_cases()
        do c = 1, size(cases)
            arguments = "check " // faulty // trim(cases(c)%file) // " --ucon " &
                & // trim(cases(c)%ucon)
            ! the first run compiles the file into the cache
            call run_bounded(program, arguments, compile_bound, scratch, "compile", run)
            do r = 1, repeats
                call run_bounded(program, arguments, bound, scratch, "run", run)
                call expect_finding(error, run, trim(cases(c)%expected), trim(cases(c)%file) &
                    & // ", run " // to_text(r) // " of " // to_text(repeats))
                if (allocated(error)) exit
            end do
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_misuse_repeated

    !> One run ended in time with exit status 1 and the [declaration] finding expected.
    subroutine expect_finding(error, run, expected, what)
        type(error_type), allocatable, intent(out) :: error
        type(bounded_run_type), intent(in) :: run
        character(len=*), intent(in) :: expected, what

        call check(error, run%status /= timed_out .and. run%seconds < real(bound, wp), what &
            & // ": no end within " // to_text(bound) // " s (" // to_text(run%seconds) &
            & // " s, exit status " // to_text(run%status) // ")")
        if (allocated(error)) return
        call check(error, run%status == 1 .and. len(run%err) == 0, what // ": exit status " &
            & // to_text(run%status) // ", expected 1 (findings); stderr: " // run%err)
        if (allocated(error)) return
        call expect_in(error, run%out, "[declaration]", what // ": the report")
        if (allocated(error)) return
        call expect_in(error, run%out, expected, what // ": the report")
        if (allocated(error)) return
        call expect_in(error, run%out, "verdict: MISMATCHES in 1 of 1 UCON(s)", what &
            & // ": the report")
    end subroutine expect_finding

    !> --ucon ID alone: the routine is called with NPAR = 0, and what it does is reported (the
    !> disk routine refuses through ERRMES during the initialisation call).
    subroutine test_ucon_without_par(error)
        type(error_type), allocatable, intent(out) :: error
        type(bounded_run_type) :: run
        character(len=:), allocatable :: program
        integer :: r

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_bounded(program, "check ucon/adams/rolling_disk/ucosub.f --ucon 1", &
            & compile_bound, scratch, "compile", run)
        do r = 1, 5
            call run_bounded(program, "check ucon/adams/rolling_disk/ucosub.f --ucon 1", bound, &
                & scratch, "no_par", run)
            call expect_finding(error, run, "rolling disk needs NPAR >= 11", "--ucon 1, run " &
                & // to_text(r))
            if (allocated(error)) exit
            call expect_in(error, run%out, "UCON/1  PAR: none (NPAR = 0)", "the report")
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_ucon_without_par

    !> --states beyond the maximum: refused at once (exit status 2) with the maximum and why,
    !> before anything is compiled or called; the maximum itself is accepted by the reader.
    subroutine test_states_maximum(error)
        type(error_type), allocatable, intent(out) :: error
        type(bounded_run_type) :: run
        character(len=:), allocatable :: program

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_bounded(program, "check ucon/adams/rolling_disk/ucosub.f --ucon " // disk_ucon &
            & // " --states 100000000", bound, scratch, "states", run)
        call check(error, run%status == 2 .and. len(run%out) == 0, "--states 100000000: " &
            & // "exit status " // to_text(run%status) // ", expected 2; stdout: " // run%out)
        if (allocated(error)) return
        call expect_in(error, run%err, "100000000 states per UCON asked for; at most " &
            & // to_text(max_check_states) // " (each state costs", "stderr")
        if (allocated(error)) return
        ! written as a real, the count is no whole number: refused as well
        call run_bounded(program, "check ucon/adams/rolling_disk/ucosub.f --ucon " // disk_ucon &
            & // " --states 1e8", bound, scratch, "states", run)
        call remove_folder(scratch)
        call check(error, run%status == 2 .and. len(run%out) == 0, "--states 1e8: exit " &
            & // "status " // to_text(run%status) // ", expected 2; stdout: " // run%out)
        if (allocated(error)) return
        call expect_in(error, run%err, "--states expects a whole number", "stderr")
        if (allocated(error)) return
        call check(error, max_check_states == 100000, "the documented maximum (docs/checker.md)" &
            & // " is 100000, the code's " // to_text(max_check_states))
    end subroutine test_states_maximum

    !> The library refuses a count beyond the maximum before the first call of the routine.
    subroutine test_library_states(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request(1)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        type(error_type), allocatable :: refusal

        request(1)%id = 1
        request(1)%par = [3.0_wp, 0.25_wp]
        options%states = max_check_states + 1
        call check_user_ucosub(height_ucosub, request, options, report, refusal)
        if (.not. allocated(refusal)) then
            call check(error, .false., "a check of " // to_text(options%states) &
                & // " states was made")
            return
        end if
        call expect_in(error, refusal%message, "at most " // to_text(max_check_states), &
            & "the refusal")
    end subroutine test_library_states

    !> F = Z - PAR(2) of part PAR(1).
    subroutine height_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        if (iflag == 3) then
            call ucovar(id, 1, [nint(par(1))], 1, [13])
            return
        end if
        if (idrsel(1) == 1) scalar = q(1) - par(2)
        if (idrsel(2) == 1) array(1) = 1.0_wp
        if (npar < 0) xmatrx(1, 1) = time
    end subroutine height_ucosub

end module test_check_reliability
