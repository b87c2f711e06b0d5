! SPDX-License-Identifier: MIT
!> `rollcon check FILE --model MODEL.adm` on VARSUBs and REQSUBs (suite user-routine-check;
!> rollcon_user_routine_check): the routines of the user-forces suite checked clean, and each
!> fault test/user_forces/checked/planted_faults.f plants (chosen by a fourth constant of
!> USER(...)) reported by its rule, naming the statement and its line, the routine and the
!> state; an implicit-typing slip reported with its line and routine; the UCONs of a model of
!> two files, each naming its routine (ROUTINE=FILE::NAME), checked against that routine.
module test_user_routine_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_output_files, only : make_folders, write_text_file
    use rollcon_user_build, only : user_build_options_type
    use rollcon_user_routine_check, only : check_user_routines, routine_units_lines
    use rollcon_job, only : user_file_type
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type
    use rollcon_audit_report, only : report_text
    use rollcon_check_rules, only : rule_derivative
    use rollcon_dataset_ucon_check, only : check_dataset_ucons
    use command_runs, only : file_text, count_of, rollcon_program, run_rollcon
    implicit none
    private

    public :: collect_user_routine_check

    !> The test data
    character(len=*), parameter :: folder = "test/user_forces/"
    character(len=*), parameter :: faults = folder // "checked/planted_faults.f"
    !> The tests' cache of compiled routines (the user-ucosub suite's)
    character(len=*), parameter :: test_cache = "build/rollcon-test-user-cache"
    !> Scratch folder of the suite: the datasets with a fault chosen
    character(len=*), parameter :: scratch = "build/test_user_routine_check"
    !> Findings at every state probed: the start and 20 states about it
    !> What a grouped [hidden state] finding ends with when every state showed it
    character(len=*), parameter :: at_every_state = "; so in 21 of the 21 states probed"
    !> The planted jump, SIGN(0.1, VZ): from -0.1 to 0.1. The check halves the way to the
    !> jump 40 times, so the two outputs it quotes differ from the jump by the smooth part's
    !> change over 2**-40 of the way (of order 1e-12: the displacement's rate is of order 1):
    !> 1e-9 catches a search that stopped tenfold short (2**-10 of the way: 1e-3)
    real(wp), parameter :: planted_jump = 0.2_wp, jump_tolerance = 1.0e-9_wp

contains

    subroutine collect_user_routine_check(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("varsub-clean", test_varsub_clean), &
            & new_unittest("reqsub-clean", test_reqsub_clean), &
            & new_unittest("varsub-hidden-state", test_varsub_hidden), &
            & new_unittest("reqsub-hidden-state", test_reqsub_hidden), &
            & new_unittest("varsub-nan", test_varsub_nan), &
            & new_unittest("reqsub-nan", test_reqsub_nan), &
            & new_unittest("varsub-jump", test_varsub_jump), &
            & new_unittest("reqsub-jump", test_reqsub_jump), &
            & new_unittest("varsub-undeclared-sysary", test_varsub_undeclared), &
            & new_unittest("reqsub-undeclared-sysary", test_reqsub_undeclared), &
            & new_unittest("varsub-implicit-typing", test_varsub_typing), &
            & new_unittest("two-files-checked", test_two_files), &
            & new_unittest("motsub-checked", test_motsub), &
            & new_unittest("difsub-checked", test_difsub), &
            & new_unittest("varval-at-probed-state", test_varval_probed), &
            & new_unittest("accelerations-read-checked", test_accelerations_read), &
            & new_unittest("units-line-per-routine", test_units_lines), &
            & new_unittest("named-ucons-checked", test_named_ucons)]
    end subroutine collect_user_routine_check

    !> variable_stretch.f on variable.adm (declared types, no state, smooth, its SYSFNC call
    !> that of its initialisation call): clean.
    subroutine test_varsub_clean(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_clean(folder // "variable_stretch.f", folder // "variable.adm", error)
    end subroutine test_varsub_clean

    !> request_measures.f on request.adm: clean.
    subroutine test_reqsub_clean(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_clean(folder // "request_measures.f", folder // "request.adm", error)
    end subroutine test_reqsub_clean

    !> A SAVEd call counter in VALUE: one [hidden state] finding, counting every state.
    subroutine test_varsub_hidden(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings

        call expect_fault("variable", 1, "[hidden state]", 1, error, findings)
        if (.not. allocated(error)) call check(error, index(findings, at_every_state) > 0, &
            & "the finding does not count 21 states: " // findings)
    end subroutine test_varsub_hidden

    !> The same counter in RESULT(4).
    subroutine test_reqsub_hidden(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings

        call expect_fault("request", 1, "[hidden state]", 1, error, findings)
        if (.not. allocated(error)) call check(error, index(findings, at_every_state) > 0, &
            & "the finding does not count 21 states: " // findings)
    end subroutine test_reqsub_hidden

    !> 0/0 in VALUE past 0.1 s: one [finite] finding quoting the NaN (the routine is probed no
    !> further).
    subroutine test_varsub_nan(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings

        call expect_fault("variable", 2, "[finite]", 1, error, findings)
        if (allocated(error)) return
        call check(error, index(findings, "returned VALUE = NaN") > 0, findings)
    end subroutine test_varsub_nan

    !> The same in RESULT(4).
    subroutine test_reqsub_nan(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings

        call expect_fault("request", 2, "[finite]", 1, error, findings)
        if (allocated(error)) return
        call check(error, index(findings, "returned RESULT = (") > 0 .and. index(findings, &
            & "NaN") > 0, findings)
    end subroutine test_reqsub_nan

    !> SIGN(0.1, VZ) in VALUE: [jump] findings only, the first quoting a jump of 0.2.
    subroutine test_varsub_jump(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_jump("variable", 1, error)
    end subroutine test_varsub_jump

    !> The same in RESULT(4) (the third of the six entries ADAMS writes).
    subroutine test_reqsub_jump(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_jump("request", 6, error)
    end subroutine test_reqsub_jump

    !> SYSARY('TVEL') read in the evaluations but not in the initialisation call: one
    !> [declaration] finding (a note is reported once a statement) naming the call.
    subroutine test_varsub_undeclared(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_undeclared("variable", error)
    end subroutine test_varsub_undeclared

    !> The same in the REQSUB.
    subroutine test_reqsub_undeclared(error)
        type(error_type), allocatable, intent(out) :: error

        call expect_undeclared("request", error)
    end subroutine test_reqsub_undeclared

    !> implicit_varsub.f on variable.adm: exactly one finding, its slip of implicit typing
    !> (LFREE, INTEGER by its first letter, receiving PAR(3)), naming the line and the routine.
    subroutine test_varsub_typing(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call check_file(folder // "checked/implicit_varsub.f", folder // "variable.adm", &
            & findings, count, error)
        if (allocated(error)) return
        call check(error, count == 1 .and. index(findings, "[typing] " // folder &
            & // "checked/implicit_varsub.f:15 (in SUBROUTINE VARSUB)") > 0 .and. &
            & index(findings, "REAL(8) to INTEGER(4)") > 0 .and. index(findings, &
            & "'LFREE = PAR(3)'") > 0, to_text(count) // " findings: " // findings)
    end subroutine test_varsub_typing

    !> file on model: no finding.
    subroutine expect_clean(file, model, error)
        character(len=*), intent(in) :: file, model
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call check_file(file, model, findings, count, error)
        if (allocated(error)) return
        call check(error, count == 0, to_text(count) // " findings: " // findings)
    end subroutine expect_clean

    !> The jump's finding of model (variable or request) with fault 3: every finding a [jump],
    !> some; the first's two quoted outputs (entries values each) differ by planted_jump.
    subroutine expect_jump(model, values, error)
        character(len=*), intent(in) :: model
        integer, intent(in) :: values
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        real(wp) :: before(values), after(values)
        integer :: count, jumps, at, close, stat

        call run_fault(model, 3, findings, count, error)
        if (allocated(error)) return
        jumps = count_of(findings, "[jump] ")
        call check(error, count >= 1 .and. jumps == count, to_text(count) // " findings: " &
            & // findings)
        if (allocated(error)) return
        ! "... jumps from (a, ...) to (b, ...) at ..."
        at = index(findings, " jumps from (") + 13
        close = at + index(findings(at:), ")") - 2
        read(findings(at:close), *, iostat=stat) before
        if (stat == 0) then
            at = close + 7
            close = at + index(findings(at:), ")") - 2
            read(findings(at:close), *, iostat=stat) after
        end if
        call check(error, stat == 0, "the jump's outputs do not read: " // findings)
        if (allocated(error)) return
        call check(error, abs(maxval(abs(after - before)) - planted_jump) <= jump_tolerance, &
            & "the jump quoted is " // to_text(maxval(abs(after - before))) // ", planted " &
            & // to_text(planted_jump) // ": " // findings)
    end subroutine expect_jump

    !> The [declaration] finding of model (variable or request) with fault 4.
    subroutine expect_undeclared(model, error)
        character(len=*), intent(in) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings

        call expect_fault(model, 4, "[declaration]", 1, error, findings)
        if (allocated(error)) return
        call check(error, index(findings, "SYSARY('TVEL') read velocities, which the " &
            & // "initialisation call (IFLAG = .TRUE.) did not read") > 0, findings)
    end subroutine expect_undeclared

    !> model (variable or request) with fault checked: count findings, every one rule's,
    !> naming the statement and its line, the routine and the state (the first's).
    subroutine expect_fault(model, fault, rule, count, error, findings)
        character(len=*), intent(in) :: model
        integer, intent(in) :: fault
        character(len=*), intent(in) :: rule
        integer, intent(in) :: count
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable, intent(out), optional :: findings
        character(len=:), allocatable :: found, statement
        integer :: found_count

        call run_fault(model, fault, found, found_count, error)
        if (allocated(error)) return
        if (model == "variable") then
            statement = "variable_" // to_text(fault) // ".adm:10: VARIABLE/3, its VARSUB of "
        else
            statement = "request_" // to_text(fault) // ".adm:12: REQUEST/7, its REQSUB of "
        end if
        call check(error, found_count == count .and. count_of(found, rule // " ") == count &
            & .and. index(found, rule // " " // scratch // "/" // statement // faults &
            & // " at state ") > 0, to_text(found_count) // " findings (" // to_text(count) &
            & // " " // rule // " expected): " // found)
        if (present(findings)) findings = found
    end subroutine expect_fault

    !> planted_faults.f on MODEL.adm (variable or request) with fault as its fourth constant
    !> (written to the scratch folder as MODEL_FAULT.adm): the findings and their number.
    subroutine run_fault(model, fault, findings, count, error)
        character(len=*), intent(in) :: model
        integer, intent(in) :: fault
        character(len=:), allocatable, intent(out) :: findings
        integer, intent(out) :: count
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text, constants, path
        integer :: at

        if (model == "variable") then
            constants = "USER(20, 2, 1)"
        else
            constants = "USER(20, 2, 2.5)"
        end if
        text = file_text(folder // model // ".adm")
        at = index(text, constants)
        call check(error, at > 0, folder // model // ".adm has no " // constants)
        if (allocated(error)) return
        text = text(:at + len(constants) - 2) // ", " // to_text(fault) // ")" &
            & // text(at + len(constants):)
        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/" // model // "_" // to_text(fault) // ".adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
        call check_file(faults, path, findings, count, error)
    end subroutine run_fault

    !> two_files.adm, whose SFORCE/3 names the routine of a second file
    !> (ROUTINE=sforce_cubic::SFOSUB): with that file given as a run takes it, the check is
    !> clean; with a file of that name holding hidden_state.f's SFOSUB instead, every finding
    !> is SFORCE/3's hidden state, at every state, and SFORCE/2 (the first file's) has none.
    subroutine test_two_files(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings, path
        integer :: count

        call check_file(folder // "sforce_spring.f", folder // "two_files.adm", findings, &
            & count, error, [user_file_type(folder // "sforce_cubic.f")])
        if (allocated(error)) return
        call check(error, count == 0, to_text(count) // " findings: " // findings)
        if (allocated(error)) return
        call make_folders(scratch // "/second", error)
        if (allocated(error)) return
        path = scratch // "/second/sforce_cubic.f"
        call write_text_file(path, file_text(folder // "hidden_state.f"), error)
        if (allocated(error)) return
        call check_file(folder // "sforce_spring.f", folder // "two_files.adm", findings, &
            & count, error, [user_file_type(path)])
        if (allocated(error)) return
        call check(error, count == 1 .and. count_of(findings, "[hidden state]") == 1 &
            & .and. count_of(findings, "SFORCE/3") == 1 .and. count_of(findings, "SFORCE/2") &
            & == 0 .and. index(findings, at_every_state) > 0, to_text(count) // " findings: " &
            & // findings)
        if (allocated(error)) return
        ! an SFOSUB's RESULT is one value: the finding quotes one value of each call (the
        ! statement's six force and torque values once came out as six), the two 2000 N apart
        call check(error, one_value_after(findings, "the same inputs gave RESULT (") .and. &
            & one_value_after(findings, ") and then ("), "the hidden-state finding quotes " &
            & // "more than the SFOSUB's one RESULT value: " // findings)
    end subroutine test_two_files

    !> True when text holds lead followed by a single value (no comma) and ")".
    logical function one_value_after(text, lead) result(one)
        character(len=*), intent(in) :: text, lead
        integer :: at, close

        one = .false.
        at = index(text, lead)
        if (at == 0) return
        at = at + len(lead)
        close = index(text(at:), ")")
        if (close <= 1) return
        one = index(text(at:at + close - 2), ",") == 0
    end function one_value_after

    !> variable_sign.adm: an SFOSUB (sforce_variable_sign.f) returning -5 SIGN(1, VARVAL(3))
    !> through SYSFNC('VARVAL'), VARIABLE/3 a VARSUB's stretch (variable_stretch.f) of 0.01 at
    !> the start that changes sign on the way to some probed states: the check evaluates the
    !> VARSUB at each probed state, so it finds the SFOSUB's jump there ([jump] findings, all
    !> of SFORCE/2, the first quoting a jump of 10: the force is constant on each side, so
    !> exactly 10), and none of the VARSUB (its stretch is continuous). Read at the start's
    !> value, VARVAL would make the force constant and the jump go unseen.
    subroutine test_varval_probed(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        real(wp) :: before, after
        integer :: count, at, close, stat

        call check_file(folder // "sforce_variable_sign.f", folder // "variable_sign.adm", &
            & findings, count, error, [user_file_type(folder // "variable_stretch.f")])
        if (allocated(error)) return
        call check(error, count >= 1 .and. count_of(findings, "[jump] ") == count .and. &
            & count_of(findings, "variable_sign.adm:12: SFORCE/2, its SFOSUB") == count, &
            & to_text(count) // " findings: " // findings)
        if (allocated(error)) return
        at = index(findings, " jumps from (") + 13
        close = at + index(findings(at:), ")") - 2
        read(findings(at:close), *, iostat=stat) before
        if (stat == 0) then
            at = close + 7
            close = at + index(findings(at:), ")") - 2
            read(findings(at:close), *, iostat=stat) after
        end if
        call check(error, stat == 0, "the jump's outputs do not read: " // findings)
        if (allocated(error)) return
        call check(error, abs(abs(after - before) - 10.0_wp) <= jump_tolerance, "the jump " &
            & // "quoted is " // to_text(abs(after - before)) // ", not 10: " // findings)
    end subroutine test_varval_probed

    !> accelerations_read.f's VARSUB, SFOSUB (reading the VARSUB's VARVAL) and DIFSUB, which
    !> read accelerations (SYSFNC('ACCZ')), are clean on accelerations_read.adm, and its REQSUB
    !> (SYSARY('TACC', 'RACC')) on request_accelerations.adm: the check answers their reads
    !> (the accelerations last set) as a run does, where a refusal would be a finding at
    !> every call; a MOTSUB reading TACC (faulty/motsub_accelerations.f) is one finding naming
    !> MOTION/1 and ADAMS's rule.
    subroutine test_accelerations_read(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call expect_clean(folder // "accelerations_read.f", folder // "accelerations_read.adm", &
            & error)
        if (allocated(error)) return
        call expect_clean(folder // "accelerations_read.f", folder &
            & // "request_accelerations.adm", error)
        if (allocated(error)) return
        call check_file(folder // "faulty/motsub_accelerations.f", folder // "motion.adm", &
            & findings, count, error)
        if (allocated(error)) return
        call check(error, count == 1 .and. count_of(findings, "motion.adm:17: MOTION/1") == 1 &
            & .and. count_of(findings, "a MOTSUB may not call SYSFNC or SYSARY") == 1, &
            & to_text(count) // " findings: " // findings)
    end subroutine test_accelerations_read

    !> motion.adm's MOTSUB (motsub_sine.f) is clean; the same with a SAVEd counter that moves
    !> the acceleration (IORD = 2) by 1e-3 at each call is [hidden state] at every state,
    !> naming MOTION/1.
    subroutine test_motsub(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: findings
        integer :: count

        call expect_clean(folder // "motsub_sine.f", folder // "motion.adm", error)
        if (allocated(error)) return
        call check_file(folder // "checked/motsub_hidden.f", folder // "motion.adm", findings, &
            & count, error)
        if (allocated(error)) return
        call check(error, count == 1 .and. count_of(findings, "[hidden state]") == 1 &
            & .and. count_of(findings, "MOTION/1, its MOTSUB") == 1 .and. index(findings, &
            & at_every_state) > 0, &
            & to_text(count) // " findings: " // findings)
    end subroutine test_motsub

    !> The user-forces suite's lag (a part moving along x at 1 m/s, DIFF/3 explicit and DIFF/4
    !> IMPLICIT served by diff_lag.f's DIFSUB, reading DX, DIF and DIF1) is clean; an explicit
    !> DIFF/3 served by a DIFSUB whose SAVEd counter moves its rate by 1e-3 at each call is
    !> [hidden state] at every state, naming DIFF/3 (line 7).
    subroutine test_difsub(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: nl = new_line("a")
        character(len=*), parameter :: mover = "lag" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, " &
            & // "VX = 1" // nl // "MARKER/20, PART = 2" // nl &
            & // "ACCGRAV/IGRAV = 0, JGRAV = 0, KGRAV = 0" // nl
        character(len=*), parameter :: tail = "SIMULATE/DYNAMIC, END = 2, STEPS = 100" // nl &
            & // "END" // nl
        character(len=:), allocatable :: findings, path
        integer :: count

        call make_folders(scratch, error)
        if (allocated(error)) return
        path = scratch // "/difsub_lag.adm"
        call write_text_file(path, mover // "DIFF/3, FUNCTION = USER(20, 0.5, 0), IC = 0" // nl &
            & // "DIFF/4, FUNCTION = USER(20, 0.5, 1), IC = 0, 1, IMPLICIT" // nl // tail, error)
        if (allocated(error)) return
        call expect_clean(folder // "diff_lag.f", path, error)
        if (allocated(error)) return
        path = scratch // "/difsub_hidden.adm"
        call write_text_file(path, mover // "DIFF/3, FUNCTION = USER(20, 0.5), IC = 0" // nl &
            & // tail, error)
        if (allocated(error)) return
        call check_file(folder // "checked/difsub_hidden.f", path, findings, count, error)
        if (allocated(error)) return
        call check(error, count == 1 .and. count_of(findings, "[hidden state]") == 1 &
            & .and. count_of(findings, "DIFF/3 (line 7), its DIFSUB") == 1 .and. &
            & index(findings, at_every_state) > 0, &
            & to_text(count) // " findings: " // findings)
    end subroutine test_difsub

    !> check_user_routines of file (and more files) on model, the tests' cache, seed 1, a
    !> call's limit 10 s.
    subroutine check_file(file, model, findings, count, error, more_files)
        character(len=*), intent(in) :: file, model
        character(len=:), allocatable, intent(out) :: findings
        integer, intent(out) :: count
        type(error_type), allocatable, intent(out) :: error
        type(user_file_type), intent(in), optional :: more_files(:)
        type(user_build_options_type) :: options

        options%cache_dir = test_cache
        call check_user_routines(file, model, options, 10.0_wp, 1, findings, count, error, &
            & more_files)
    end subroutine check_file

    !> `rollcon check FILE --model` prints, for each statement a user's routine serves, a line
    !> saying the units its SYSFNC and SYSARY answers arrive in and its outputs are read in:
    !> the field's dataset (SI) gets one for GFORCE/1 (force in NEWTON, torque in
    !> NEWTON*METER) and one for SFORCE/2, before the verdict; the same dataset in MMKS with a
    !> rotational SFORCE gets METER replaced by MILLIMETER, the torque in NEWTON*MILLIMETER
    !> and the angular velocities in radians/SECOND (the library call the command makes).
    subroutine test_units_lines(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: answers = ": SYSFNC and SYSARY answer in NEWTON, " &
            & // "KILOGRAM, METER, SECOND (the dataset's UNITS), angles in radians, velocities " &
            & // "in METER/SECOND, angular velocities in radians/SECOND; "
        character(len=:), allocatable :: program, out, text, lines, mmks
        integer :: status

        call make_folders(scratch, error)
        if (allocated(error)) return
        call rollcon_program(program, error)
        if (allocated(error)) return
        call run_rollcon(program, "check " // folder // "field_forces.f --model " // folder &
            & // "field_forces.adm", scratch // "/units.out", scratch // "/units.err", status)
        out = file_text(scratch // "/units.out")
        call check(error, status == 0 .and. index(out, "units: GFORCE/1 (line 12), its GFOSUB" &
            & // answers // "RESULT(1:3) is read as the force in RM's axes, in NEWTON, " &
            & // "RESULT(4:6) as the torque, in NEWTON*METER") > 0 .and. index(out, "units: " &
            & // "SFORCE/2 (line 13), its SFOSUB" // answers // "RESULT is read as the force " &
            & // "along the line from J to I, in NEWTON") > 0 .and. index(out, "units: ") &
            & < index(out, "verdict: clean"), "exit " // to_text(status) // ": " // out)
        if (allocated(error)) return
        ! the clean verdict counts what was checked: GFORCE/1 and SFORCE/2 at the start and 20
        ! states, each called twice there (hidden state) and 40 times on the way to each of the
        ! 20 (the search for a jump): 2 (2 21 + 20 40) = 1684 calls; the RESULT entries each
        ! routine's kind defines (the GFOSUB's six, the SFOSUB's one) at each of the 21
        ! states: 21 (6 + 1) = 147
        call check(error, index(out, "verdict: clean: 2 statement(s) checked at 21 states " &
            & // "each, 1684 calls of their routines, 147 values compared, no finding") > 0, &
            & "the clean verdict does not count the check: " // out)
        if (allocated(error)) return
        text = file_text(folder // "field_forces.adm")
        mmks = text(:index(text, "UNITS/") - 1) // "UNITS/SYSTEM = MMKS" // new_line("a") &
            & // text(index(text, "PART/1"):index(text, "SFORCE/2") - 1) // "SFORCE/2, " &
            & // "ROTATION, I = 20, J = 2, FUNCTION = USER(20, 2, 1000, 10, 1)" // new_line("a") &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 10" // new_line("a") // "END" &
            & // new_line("a")
        call write_text_file(scratch // "/units_mmks.adm", mmks, error)
        if (allocated(error)) return
        call routine_units_lines(scratch // "/units_mmks.adm", lines, error)
        if (allocated(error)) return
        call check(error, index(lines, "units: SFORCE/2 (line 13), its SFOSUB: SYSFNC and " &
            & // "SYSARY answer in NEWTON, KILOGRAM, MILLIMETER, SECOND (the dataset's UNITS), " &
            & // "angles in radians, velocities in MILLIMETER/SECOND, angular velocities in " &
            & // "radians/SECOND; RESULT is read as the torque about J's z axis, in " &
            & // "NEWTON*MILLIMETER") > 0 .and. index(lines, "GFORCE/1 (line 12)") > 0, lines)
    end subroutine test_units_lines

    !> `rollcon check A.f --ucosub B.f --model M.adm` checks every UCON against the routine its
    !> ROUTINE=FILE::NAME names (rollcon_dataset_ucon_check): ucon_two_files.adm's UCON/1
    !> (TURNVEL of ucon_turn_velocity.f) and UCON/2 (CIRCLE of ucon_circle.f) both clean, each
    !> headed by its statement, line, ROUTINE and file (the library call). With UCON/2 naming
    !> ucon_circle_wrong.f's CIRCLE (dF/dX returned as X, half of 2X) and turntable.f given too
    !> (the program): exit 1, UCON/1 clean, UCON/2 named with its line and ROUTINE, its ARRAY(1)
    !> returned at half the differences' value and XMATRX(1,1), the derivative of that ARRAY(1),
    !> at twice it (2 against 1), and turntable.f said to serve no UCON. The ratios are
    !> exact but for rounding: sixth-order differences of a quadratic (F) and of a linear
    !> ARRAY are exact up to rounding of order 1e-10 relative at the check's steps; 1e-6
    !> catches any other factor.
    subroutine test_named_ucons(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_build_options_type) :: build
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        type(ucon_request_type), allocatable :: given(:)
        character(len=:), allocatable :: library, notes, text, program, out, model
        logical :: from_cache
        integer :: checked, status, g
        real(wp) :: array_ratio, xmatrx_ratio

        build%cache_dir = test_cache
        options%states = 5
        allocate(given(0))
        call check_dataset_ucons([user_file_type(folder // "ucon_turn_velocity.f"), &
            & user_file_type(folder // "ucon_circle.f")], folder // "ucon_two_files.adm", &
            & build, given, options, 10.0_wp, checked, report, library, from_cache, notes, &
            & error)
        if (allocated(error)) return
        text = report_text(report, "two files", library)
        call check(error, checked == 2 .and. report%clean() .and. report%ucons(1)%states == 5 &
            & .and. report%ucons(2)%states == 5 .and. index(text, "UCON/1 (line 9, " &
            & // "ROUTINE=ucon_turn_velocity::TURNVEL of " // folder // "ucon_turn_velocity.f)" &
            & // "  PAR = 2, 3.5") > 0 .and. index(text, "UCON/2 (line 10, ROUTINE=" &
            & // "ucon_circle::circle of " // folder // "ucon_circle.f)  PAR = 2, 0.1") > 0 &
            & .and. len(notes) == 0, to_text(checked) // " checked; notes: " // notes // text)
        if (allocated(error)) return
        call make_folders(scratch, error)
        if (allocated(error)) return
        model = scratch // "/ucon_wrong.adm"
        text = file_text(folder // "ucon_two_files.adm")
        g = index(text, "ucon_circle::circle")
        call write_text_file(model, text(:g - 1) // "ucon_circle_wrong::CIRCLE" &
            & // text(g + len("ucon_circle::circle"):), error)
        if (allocated(error)) return
        call check_dataset_ucons([user_file_type(folder // "ucon_turn_velocity.f"), &
            & user_file_type(folder // "ucon_circle_wrong.f")], model, build, given, options, &
            & 10.0_wp, checked, report, library, from_cache, notes, error)
        if (allocated(error)) return
        array_ratio = 0.0_wp
        xmatrx_ratio = 0.0_wp
        do g = 1, size(report%ucons(2)%groups)
            associate (group => report%ucons(2)%groups(g))
                if (group%code /= rule_derivative .or. group%row /= 1) cycle
                if (group%output == "ARRAY (dF/dq)") array_ratio = group%returned/group%expected
                if (group%output == "XMATRX (d2F/dq dq)" .and. group%column == 1) &
                    & xmatrx_ratio = group%returned/group%expected
            end associate
        end do
        call check(error, checked == 2 .and. size(report%ucons(1)%groups) == 0 .and. &
            & size(report%ucons(2)%groups) == 2 .and. abs(array_ratio - 0.5_wp) <= 1.0e-6_wp &
            & .and. abs(xmatrx_ratio - 2.0_wp) <= 1.0e-6_wp, "ARRAY(1) returned/differences " &
            & // to_text(array_ratio) // ", XMATRX(1,1) " // to_text(xmatrx_ratio) // ": " &
            & // report_text(report, "two files", library))
        if (allocated(error)) return
        call rollcon_program(program, error)
        if (allocated(error)) return
        call run_rollcon(program, "check " // folder // "ucon_turn_velocity.f --ucosub " &
            & // folder // "ucon_circle_wrong.f --ucosub test/turntable/turntable.f --model " &
            & // model // " --states 5", scratch // "/named.out", scratch // "/named.err", status)
        out = file_text(scratch // "/named.out")
        call check(error, status == 1 .and. index(out, "check: test/turntable/turntable.f " &
            & // "serves no UCON of " // model) > 0 .and. index(out, "UCON/2 (line 10, " &
            & // "ROUTINE=ucon_circle_wrong::CIRCLE of " // folder // "ucon_circle_wrong.f)") &
            & > 0 .and. index(out, "ARRAY(1) = dF/d(X): 5 of 5 states") > 0 .and. index(out, &
            & "verdict: MISMATCHES in 1 of 2 UCON(s)") > 0, "exit " // to_text(status) // ": " &
            & // out // file_text(scratch // "/named.err"))
    end subroutine test_named_ucons

end module test_user_routine_check
