! SPDX-License-Identifier: MIT
!> The rules a UCOSUB check reports on, as codes: every finding carries one, and whatever sorts,
!> groups or words findings goes by the code (never by the text of a message).
module rollcon_check_rules
    implicit none
    private

    public :: rule_declaration, rule_errmes, rule_finite, rule_derivative, rule_symmetry
    public :: rule_velocity_linear, rule_selector_0, rule_repeat, rule_outside_block
    public :: rule_signal, rule_timeout, rule_exit, rule_changed_argument, rule_count, rule_order
    public :: rule_name, rule_meaning

    !> The UCOVAR declaration is wrong
    integer, parameter :: rule_declaration = 1
    !> The routine called ERRMES
    integer, parameter :: rule_errmes = 2
    !> A NaN or Infinity came back
    integer, parameter :: rule_finite = 3
    !> An entry differs from central differences
    integer, parameter :: rule_derivative = 4
    !> XMATRX is not symmetric
    integer, parameter :: rule_symmetry = 5
    !> A second derivative in two velocities is not zero
    integer, parameter :: rule_velocity_linear = 6
    !> An output not asked for was written
    integer, parameter :: rule_selector_0 = 7
    !> The same call gave another answer
    integer, parameter :: rule_repeat = 8
    !> A write outside the declared block (or outside the arrays)
    integer, parameter :: rule_outside_block = 9
    !> The routine was killed by a signal (run in a child process)
    integer, parameter :: rule_signal = 10
    !> A call did not return within the time limit
    integer, parameter :: rule_timeout = 11
    !> The routine ended the process (STOP) inside a call
    integer, parameter :: rule_exit = 12
    !> The routine changed an argument it may only read (ID, TIME, Q, PAR, NPAR, IDRSEL, IFLAG)
    integer, parameter :: rule_changed_argument = 13
    !> Number of rules
    integer, parameter :: rule_count = 13
    !> Rules in the order a report lists them: the most telling first
    integer, parameter :: rule_order(rule_count) = [rule_signal, rule_timeout, rule_exit, &
        & rule_declaration, rule_errmes, rule_finite, rule_outside_block, &
        & rule_changed_argument, rule_symmetry, rule_velocity_linear, rule_selector_0, &
        & rule_repeat, rule_derivative]

contains

    !> Short name of a rule, as the reports print it ("derivative", "outside-block", ...).
    pure function rule_name(rule) result(name)
        !> Rule code
        integer, intent(in) :: rule
        character(len=:), allocatable :: name

        select case (rule)
        case (rule_declaration)
            name = "declaration"
        case (rule_errmes)
            name = "errmes"
        case (rule_finite)
            name = "finite"
        case (rule_derivative)
            name = "derivative"
        case (rule_symmetry)
            name = "symmetry"
        case (rule_velocity_linear)
            name = "velocity-linear"
        case (rule_selector_0)
            name = "selector-0"
        case (rule_repeat)
            name = "repeat"
        case (rule_outside_block)
            name = "outside-block"
        case (rule_signal)
            name = "crash"
        case (rule_timeout)
            name = "timeout"
        case (rule_exit)
            name = "stop"
        case (rule_changed_argument)
            name = "changed-argument"
        case default
            name = "unknown"
        end select
    end function rule_name

    !> What a rule asks of the routine, in a few words.
    pure function rule_meaning(rule) result(meaning)
        !> Rule code
        integer, intent(in) :: rule
        character(len=:), allocatable :: meaning

        select case (rule)
        case (rule_derivative)
            meaning = "differs from central differences of the routine's own outputs (ARRAY " &
                & // "from F, XMATRX from ARRAY: fix the lowest order first)"
        case (rule_symmetry)
            meaning = "XMATRX must be symmetric: both triangles filled with the same value"
        case (rule_velocity_linear)
            meaning = "non-zero second derivative in two velocities: F is not linear in them"
        case (rule_selector_0)
            meaning = "written although IDRSEL asked for nothing there"
        case (rule_repeat)
            meaning = "the same call gave a different answer the second time"
        case (rule_outside_block)
            meaning = "written beyond the declared variables, or outside ARRAY(30) and " &
                & // "XMATRX(30,30)"
        case (rule_finite)
            meaning = "a non-finite value (NaN or Infinity), or a huge one (magnitude above " &
                & // "1e100), was returned"
        case (rule_changed_argument)
            meaning = "the routine changed an argument it may only read (ID, TIME, Q, PAR, " &
                & // "NPAR, IDRSEL, IFLAG)"
        case (rule_errmes)
            meaning = "the routine reported an error through ERRMES"
        case (rule_declaration)
            meaning = "the UCOVAR declaration is wrong"
        case (rule_signal)
            meaning = "the routine crashed (killed by a signal); the rest of this UCON was " &
                & // "not checked"
        case (rule_timeout)
            meaning = "a call did not return within the time limit (--call-timeout); the " &
                & // "rest of this UCON was not checked"
        case (rule_exit)
            meaning = "the routine ended the process (STOP or CALL EXIT) inside a call; the " &
                & // "rest of this UCON was not checked"
        case default
            meaning = "unknown rule"
        end select
    end function rule_meaning

end module rollcon_check_rules
