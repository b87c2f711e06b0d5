! SPDX-License-Identifier: MIT
!> The dataset reader's refusals: one table per kind, each case a one-line change of a
!> dataset that reads cleanly (adm_datasets) and the exact message it must give.
module test_adm_refusals
    use rollcon_error, only : error_type
    use rollcon_testing, only : unittest_type, new_unittest
    use rollcon_adm_model, only : adm_model_type
    use adm_datasets, only : check_refusals, read_dataset, base
    implicit none
    private

    public :: collect_adm_refusals

    !> The supported statements, as a refusal lists them
    character(len=*), parameter :: supported = &
        & "(ACCGRAV, ARRAY, BUSHING, CONTACT, COUPLER, DIFF, END, GCON, GEAR, GFORCE, " &
        & // "INTEGRATOR, JOINT," &
        & // " JPRIM, MARKER, MOTION, OUTPUT, PART, PINPUT, POUTPUT, SFORCE, SIMULATE, SPLINE," &
        & // " SPRINGDAMPER, STRING, UCON, UNITS, VARIABLE, VFORCE, VTORQUE)"

contains

    subroutine collect_adm_refusals(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("statements-outside-the-subset", test_statements), &
            & new_unittest("keyword-refusals", test_keywords), &
            & new_unittest("references", test_references), &
            & new_unittest("duplicate-ids", test_duplicates), &
            & new_unittest("values-out-of-range", test_values), &
            & new_unittest("ucon-refusals", test_ucons), &
            & new_unittest("integrator-refusals", test_integrator), &
            & new_unittest("principal-axes-at-start", test_principal_axes), &
            & new_unittest("lists-with-values-not-finite", test_nonfinite_lists), &
            & new_unittest("keywords-by-their-whole-names", test_whole_names)]
    end subroutine collect_adm_refusals

    !> Statements outside the subset, ambiguous, misplaced, repeated, with or without an id.
    subroutine test_statements(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(16)
        character(len=480) :: expected(16)

        replaced(1) = "PTCV/9, I=3, J=4"
        expected(1) = ":7: 'PTCV' is not a statement of the supported subset " // supported &
            & // "; rollcon's constraints are UCONs, JOINTs, JPRIMs, GCONs, COUPLERs and" &
            & // " GEARs: state this one as a GCON expression, or as a UCON served by a" &
            & // " UCOSUB (ucon/)"
        replaced(2) = "cvcv/1, i=3"
        expected(2) = ":7: 'CVCV' is not a statement of the supported subset " // supported &
            & // "; rollcon's constraints are UCONs, JOINTs, JPRIMs, GCONs, COUPLERs and" &
            & // " GEARs: state this one as a GCON expression, or as a UCON served by a" &
            & // " UCOSUB (ucon/)"
        replaced(3) = "SENSOR/1, VALUE=0"
        expected(3) = ":7: 'SENSOR' is not a statement of the supported subset " // supported &
            & // "; sensors change a run as it goes (stop it, change its step): not in the" &
            & // " subset"
        replaced(4) = "BEAM/1, I=3, J=4"
        expected(4) = ":7: 'BEAM' is not a statement of the supported subset " // supported &
            & // "; force elements other than SFORCE, VFORCE, GFORCE, VTORQUE, SPRINGDAMPER" &
            & // " and BUSHING are not in the subset: write the force as a GFORCE with" &
            & // " FUNCTION expressions"
        replaced(5) = "ARRAY/1, X, SIZE=2"
        expected(5) = ":7: ARRAY/1 X: an ARRAY of the inputs, states or outputs of an LSE, " &
            & // "GSE or TFSISO (X, Y, U, VARIABLES) is not supported: those statements are " &
            & // "not in the subset; an ARRAY here holds NUMBERS=r1, ... for a user's " &
            & // "routine (GTARAY)"
        replaced(6) = "FLEX_BODY/1"
        expected(6) = ":7: 'FLEX_BODY' is not a statement of the supported subset " // supported &
            & // "; rollcon's bodies are rigid PARTs"
        replaced(7) = "FOO/1"
        expected(7) = ":7: 'FOO' is not a statement of the supported subset " // supported
        replaced(8) = "S/1, I=3"
        expected(8) = ":7: 'S' is too short an abbreviation of a statement: the shortest ADAMS" &
            & // " takes are SF for SFORCE, SI for SIMULATE, SPL for SPLINE, SPR for" &
            & // " SPRINGDAMPER, ST for STRING (docs/datasets.md, Abbreviations)"
        replaced(9) = "END|PART/6, MASS=1"
        expected(9) = ":15: a statement after END"
        replaced(10) = "INTEGRATOR/ERROR=1e-8|INTEG/ERROR=1e-9"
        expected(10) = ":13: a second INTEGRATOR statement (a dataset has at most one)"
        replaced(11) = "ACCGRAV/1, KGRAV=-9.81"
        expected(11) = ":9: ACCGRAV takes no id (write ACCGRAV/ARG=...)"
        replaced(12) = "MARKER, PART=1"
        expected(12) = ":7: MARKER needs an id (MARKER/id, ...)"
        replaced(13) = "OUTPUT/REQSAVE=1"
        expected(13) = ":13: OUTPUT REQSAVE takes no value"
        ! the data of user routines (GTARAY, GTSTRG)
        replaced(14) = "ARRAY/2, IC, SIZE=3, NUMBERS=1, 2"
        expected(14) = ":7: ARRAY/2: SIZE=3 but NUMBERS gives 2 values"
        replaced(15) = "ARRAY/4, IC"
        expected(15) = ":7: ARRAY/4: NUMBERS=r1, ... is missing (an ARRAY holds the numbers a " &
            & // "user's routine reads with GTARAY)"
        replaced(16) = "STRING/3"
        expected(16) = ":7: STRING/3: STRING=text is missing (a STRING holds the text a " &
            & // "user's routine reads with GTSTRG)"
        call check_refusals(error, [7, 7, 7, 7, 7, 7, 7, 7, 14, 12, 9, 7, 13, 7, 7, 7], &
            & replaced, expected)
    end subroutine test_statements

    !> Unknown, ambiguous, repeated keywords and values of the wrong form.
    subroutine test_keywords(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(13)
        character(len=480) :: expected(13)

        replaced(1) = "PART/2, MASS=1, CM=3, IP=2, 2, 3, DENSITY=7800"
        expected(1) = ":4: PART/2: 'DENSITY' is not a PART argument of the supported subset" &
            & // " (GROUND, MASS, CM, IP, QG, REULER, VX, VY, VZ, WX, WY, WZ, EXACT)"
        replaced(2) = "INTEGRATOR/STIFF"
        expected(2) = ":12: INTEGRATOR: 'STIFF' is not an INTEGRATOR argument of the supported" &
            & // " subset (ERROR, RTOL, ATOL, MAXSTEPS, BAUMGARTE, FORMULATION, METHOD," &
            & // " DRIFT, JACOBIAN, SOLVER, GSTIFF, WSTIFF, DSTIFF, CONSTANT_BDF, HASTIFF, HHT," &
            & // " NEWMARK, RKF45, ABAM, I3, SI2, SI1, HMAX, HMIN, HINIT, ALPHA, BETA, GAMMA," &
            & // " ADAPTIVITY, KMAX, MAXIT, CORRECTOR, INTERPOLATE, PATTERN)"
        replaced(3) = ", QG=0, 0, 1, W=1"
        expected(3) = ":5: PART/2: 'W' is too short an abbreviation of a PART argument: the" &
            & // " shortest ADAMS takes are WX for WX, WY for WY, WZ for WZ (docs/datasets.md," &
            & // " Abbreviations)"
        ! H begins five of ADAMS's keywords, each abbreviated to two letters at least
        replaced(4) = "INTEGRATOR/H=10"
        expected(4) = ":12: INTEGRATOR: 'H' is too short an abbreviation of an INTEGRATOR" &
            & // " argument: the shortest ADAMS takes are HA for HASTIFF, HH for HHT, HMA for" &
            & // " HMAX, HMI for HMIN, HI for HINIT (docs/datasets.md, Abbreviations)"
        replaced(5) = ", QG=0, 0, 1, VX=0.5, VX=1"
        expected(5) = ":5: PART/2: VX is given twice"
        replaced(6) = "PART/1, GROUND=1"
        expected(6) = ":3: PART/1 GROUND takes no value"
        replaced(7) = ", QG=0, 0"
        expected(7) = ":5: PART/2 QG: expected 3 numbers, got 2"
        replaced(8) = "PART/2, MASS=heavy, CM=3, IP=2, 2, 3"
        expected(8) = ":4: PART/2 MASS: 'heavy' is not a number (expected 1 number)"
        replaced(9) = "PART/2, MASS=1D, CM=3, IP=2, 2, 3"
        expected(9) = ":4: PART/2 MASS: '1D': D (degrees) is for angles only"
        replaced(10) = "MARKER/3, PART=2.5, REULER=0D, 90D, 0D"
        expected(10) = ":6: MARKER/3 PART: expected an id (a positive integer), got '2.5'"
        replaced(11) = "UNITS/LENGTH=FURLONG"
        expected(11) = ":2: UNITS LENGTH: 'FURLONG' is not a length unit of the supported subset" &
            & // " (METER, MILLIMETER, CENTIMETER, KILOMETER, INCH, FOOT)"
        replaced(12) = "SIM/STATICS, END=1"
        expected(12) = ":11: SIMULATE: 'STATICS' is not a SIMULATE argument of the supported" &
            & // " subset (DYNAMIC, END, STEPS, DTOUT, DURATION, STATIC, KINEMATIC)"
        replaced(13) = "INTEGRATOR/FORM=ode"
        expected(13) = ":12: INTEGRATOR FORMULATION: 'ode' is not a formulation of the supported" &
            & // " subset (IDA, CVODE, MAGGI)"
        call check_refusals(error, [4, 12, 5, 12, 5, 3, 5, 4, 4, 6, 2, 11, 12], replaced, expected)
    end subroutine test_keywords

    !> A list holding NaN, Inf or a word: each refused as that list's entry, by name (NaN in
    !> the middle of IP said "a value '3' follows NAN, which takes none", Inf at its end
    !> "expected from 3 to 6 numbers, got 2").
    subroutine test_nonfinite_lists(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(7)
        character(len=480) :: expected(7)

        replaced(1) = "PART/2, MASS=1, CM=3, IP=2, NaN, 3"
        expected(1) = ":4: PART/2 IP: 'NaN' is not a finite number (expected from 3 to 6 numbers)"
        replaced(2) = "PART/2, MASS=1, CM=3, IP=2, 2, Inf"
        expected(2) = ":4: PART/2 IP: 'Inf' is not a finite number (expected from 3 to 6 numbers)"
        replaced(3) = "PART/2, MASS=1, CM=3, IP=2, 2, 3, NaN, 0, 0"
        expected(3) = ":4: PART/2 IP: 'NaN' is not a finite number (expected from 3 to 6 numbers)"
        replaced(4) = "PART/2, MASS=1, CM=3, IP=2, 2, -infinity"
        expected(4) = ":4: PART/2 IP: '-infinity' is not a finite number (expected from 3 to 6" &
            & // " numbers)"
        replaced(5) = "PART/2, MASS=1, CM=3, IP=2, heavy, 3"
        expected(5) = ":4: PART/2 IP: 'heavy' is not a number (it stands in the list of IP: the" &
            & // " value '3' follows it)"
        replaced(6) = ", QG=0, NaN, 1, VX=0.5"
        expected(6) = ":5: PART/2 QG: 'NaN' is not a finite number (expected 3 numbers)"
        replaced(7) = "MARKER/3, PART=2, REULER=0D, Inf, 0D"
        expected(7) = ":6: MARKER/3 REULER: 'Inf' is not a finite number (expected 3 numbers)"
        call check_refusals(error, [4, 4, 4, 4, 4, 5, 6], replaced, expected)
    end subroutine test_nonfinite_lists

    !> Keywords by their whole ADAMS names, however long: MAXIMUM_DEFORMATION (19 letters, once
    !> cut to 13 in the table of a JOINT's refused keywords) is the joint's friction, refused
    !> as such, as is its abbreviation.
    subroutine test_whole_names(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(2)
        character(len=480) :: expected(2)

        replaced(1) = "MARKER/4, PART=1|JOINT/9, REVOLUTE, I=3, J=4, MAXIMUM_DEFORMATION=0.01"
        expected(1) = ":8: JOINT/9 MAXIMUM_DEFORMATION: a joint's initial conditions and its " &
            & // "friction are not supported: rollcon's initial-conditions analysis places the " &
            & // "parts (docs/initial-conditions.md); give the parts' QG, REULER and velocities" &
            & // " instead"
        replaced(2) = "MARKER/4, PART=1|JOINT/9, REVOLUTE, I=3, J=4, MAXIMUM_DEF=0.01"
        expected(2) = expected(1)
        call check_refusals(error, [7, 7], replaced, expected)
    end subroutine test_whole_names

    !> References to parts and markers that do not exist, a CM marker on another part, no ground.
    subroutine test_references(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(10)
        character(len=480) :: expected(10)

        replaced(1) = "MARKER/3, PART=9, REULER=0D, 90D, 0D"
        expected(1) = ":6: MARKER/3 PART: no PART/9"
        replaced(2) = "PART/2, MASS=1, CM=8, IP=2, 2, 3"
        expected(2) = ":4: PART/2 CM: no MARKER/8 (the centre-of-mass marker must be a MARKER on" &
            & // " this part)"
        replaced(3) = "PART/2, MASS=1, CM=4, IP=2, 2, 3"
        expected(3) = ":4: PART/2 CM: MARKER/4 is on PART/1, not on this part"
        replaced(4) = "PART/2, MASS=1, IP=2, 2, 3"
        expected(4) = ":4: PART/2 CM: a MARKER on this part must give the centre of mass (CM=id)"
        replaced(5) = "SFORCE/5, I=9, J=4, TRANSLATION, FUNCTION=TIME"
        expected(5) = ":10: SFORCE/5 I: no MARKER/9"
        replaced(6) = "SFORCE/5, I=3, J=9, TRANSLATION, FUNCTION=TIME"
        expected(6) = ":10: SFORCE/5 J: no MARKER/9"
        replaced(7) = "SFORCE/5, I=3, TRANSLATION, FUNCTION=TIME"
        expected(7) = ":10: SFORCE/5 J: an SFORCE acts between I and J (J=id)"
        replaced(8) = "MARKER/4"
        expected(8) = ":7: MARKER/4: PART=id is missing (the part the marker is on)"
        replaced(9) = "! no ground"
        expected(9) = ": a dataset needs exactly one PART with GROUND, found 0"
        replaced(10) = "! no SIMULATE"
        expected(10) = ": no SIMULATE statement, and no run given apart from the dataset: run" &
            & // " it from an ADAMS command file (rollcon run MODEL.acf: its first line names" &
            & // " the dataset, its second the output name, then SIMULATE/DYNAMIC, END=t," &
            & // " STEPS=n and STOP), or give the run on the command line (rollcon run" &
            & // " build/rollcon-test/refusal.adm --end T --steps N), or add SIMULATE/DYNAMIC," &
            & // " END=t, STEPS=n to the dataset"
        call check_refusals(error, [6, 4, 4, 4, 10, 10, 10, 7, 3, 11], replaced, expected)
    end subroutine test_references

    !> A second statement of a kind with an id already used.
    subroutine test_duplicates(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(4)
        character(len=480) :: expected(4)

        replaced(1) = "PART/1, MASS=1, CM=3, IP=2, 2, 3"
        expected(1) = ":4: PART/1: a second PART with this id"
        replaced(2) = "MARKER/3, PART=1"
        expected(2) = ":7: MARKER/3: a second MARKER with this id"
        replaced(3) = "UCON/1, FUNCTION=USER(1)|UCON/1, FUNCTION=USER(2)"
        expected(3) = ":9: UCON/1: a second UCON with this id"
        replaced(4) = "SFORCE/5, I=3, J=4, FUNCTION=TIME|SFORCE/5, I=3, J=4, FUNCTION=1"
        expected(4) = ":11: SFORCE/5: a second SFORCE with this id"
        call check_refusals(error, [4, 7, 8, 10], replaced, expected)
    end subroutine test_duplicates

    !> Masses, inertias, end time and output steps out of range, with the range in the message.
    subroutine test_values(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(17)
        character(len=480) :: expected(17)

        ! positive definite, but its principal moments 1 - 0.5, 1 + 0.5 and 2.4 > 0.5 + 1.5
        replaced(17) = "PART/2, MASS=1, CM=3, IP=1, 1, 2.4, 0.5, 0, 0"
        expected(17) = ":4: PART/2 IP: no rigid body has this inertia tensor: its principal " &
            & // "moments *2.4 kg m^2 break the triangle inequality (each must be at most the " &
            & // "sum of the other two)"
        replaced(16) = "PART/1, GROUND, QG=0, 0, 1"
        expected(16) = ":3: PART/1: the ground part takes no MASS, CM, IP, QG, REULER or " &
            & // "velocities (it is the ground frame, at rest)"
        replaced(1) = "PART/2, MASS=0, CM=3, IP=2, 2, 3"
        expected(1) = ":4: PART/2 MASS must be > 0 [kg], got 0"
        replaced(2) = "PART/2, MASS=-2, CM=3, IP=2, 2, 3"
        expected(2) = ":4: PART/2 MASS must be > 0 [kg], got -2"
        replaced(3) = "PART/2, MASS=1, CM=3, IP=1, 1, 3"
        expected(3) = ":4: PART/2 IP: no rigid body has these principal moments (each must be at" &
            & // " most the sum of the other two)"
        replaced(4) = "PART/2, MASS=1, CM=3, IP=0, 2, 3"
        expected(4) = ":4: PART/2 IP: three principal moments > 0 [kg m^2] are needed"
        ! products of inertia: the tensor [[2, -2.5, 0], [-2.5, 2, 0], [0, 0, 3]] has the
        ! eigenvalues 2 - 2.5 < 0, 3 and 2 + 2.5 (the digits LAPACK rounds are not compared)
        replaced(5) = "PART/2, MASS=1, CM=3, IP=2, 2, 3, 2.5, 0, 0"
        expected(5) = ":4: PART/2 IP: the inertia tensor [[xx, -xy, -xz], [-xy, yy, -yz], " &
            & // "[-xz, -yz, zz]] (ADAMS's products are positive integrals) is not positive " &
            & // "definite: its eigenvalues are -0.5*4.5 kg m^2, and a rigid body's principal " &
            & // "moments are all > 0"
        replaced(6) = "PART/1, GROUND, MASS=1"
        expected(6) = ":3: PART/1: the ground part takes no MASS, CM, IP, QG, REULER or " &
            & // "velocities (it is the ground frame, at rest)"
        replaced(7) = "SIMULATE/DYNAMIC, END=0, STEPS=10"
        expected(7) = ":11: SIMULATE END must be >= 1e-9 and <= 1000000000 [s] (as &run" &
            & // " end_time), got 0 s"
        replaced(8) = "SIMULATE/DYNAMIC, END=-1, STEPS=10"
        expected(8) = ":11: SIMULATE END must be >= 1e-9 and <= 1000000000 [s] (as &run" &
            & // " end_time), got -1 s"
        replaced(9) = "SIMULATE/DYNAMIC, END=1, STEPS=10.5"
        expected(9) = ":11: SIMULATE STEPS must be a whole number of output steps >= 1, got 10.5"
        replaced(10) = "SIMULATE/DYNAMIC, END=1, STEPS=0"
        expected(10) = ":11: SIMULATE STEPS must be a whole number of output steps >= 1, got 0"
        replaced(11) = "SIMULATE/DYNAMIC, END=1, STEPS=1e10"
        expected(11) = ":11: SIMULATE STEPS gives an output step of 1e-10 s; it must be >= 1e-9" &
            & // " and <= 1000000000 [s] (as &run output_step)"
        replaced(12) = "SIMULATE/DYNAMIC, END=1, STEPS=10, DTOUT=0.1"
        expected(12) = ":11: SIMULATE: give one of STEPS=n and DTOUT=dt"
        replaced(13) = "SIMULATE/DYNAMIC, END=1, DTOUT=2"
        expected(13) = ":11: SIMULATE DTOUT must be <= END = 1 s (as &run output_step <=" &
            & // " end_time), got 2 s"
        replaced(14) = "SIMULATE/END=1, STEPS=10"
        expected(14) = ":11: SIMULATE: give one analysis: SIMULATE/DYNAMIC (or /KINEMATIC)," &
            & // " END=..., STEPS=..., or SIMULATE/STATIC"
        replaced(15) = "SIMULATE/DYNAMIC, STEPS=10"
        expected(15) = ":11: SIMULATE: END=t (the end time) is missing (or" &
            & // " DURATION=t, from where the run is)"
        call check_refusals(error, [4, 4, 4, 4, 4, 3, 11, 11, 11, 11, 11, 11, 11, 11, 11, 3, 4], &
            & replaced, expected)
    end subroutine test_values

    !> UCON: ROUTINE without a name, too many or no constants, FUNCTION missing or not
    !> USER(...). (A ROUTINE that names no built-in routine is the assembly's to refuse: suite
    !> assembly.)
    subroutine test_ucons(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(7)
        character(len=700) :: expected(7)

        replaced(1) = "UCON/1, FUNCTION=USER(2, 21, 1), ROUTINE="
        expected(1) = ":8: UCON/1 ROUTINE: expected the name of a built-in UCOSUB (ROUTINE=name)"
        replaced(2) = "UCON/1, FUNCTION=USER(2, 21, 1), ROUTINE"
        expected(2) = ":8: UCON/1 ROUTINE: expected the name of a built-in UCOSUB (ROUTINE=name)"
        replaced(3) = "UCON/1," &
            & // " FUNCTION=USER(1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23" &
            & // ",24,25,26,27,28,29,30,31)"
        expected(3) = ":8: UCON/1 FUNCTION USER: expected from 1 to 30 numbers, got 31"
        replaced(4) = "UCON/1, FUNCTION=USER()"
        expected(4) = ":8: UCON/1 FUNCTION: USER() holds no constant; a UCON passes 1 to 30" &
            & // " constants to its UCOSUB (PAR)"
        replaced(5) = "UCON/1, ROUTINE=disk"
        expected(5) = ":8: UCON/1: FUNCTION=USER(r1, ..., r30) is missing (the constants passed" &
            & // " to the UCOSUB as PAR)"
        replaced(6) = "UCON/1, FUNCTION=2*TIME"
        expected(6) = ":8: UCON/1 FUNCTION: expected USER(r1, ..., r30) (a UCON is served by the" &
            & // " model's UCOSUB), got '2*TIME'"
        replaced(7) = "UCON/1, FUNCTION=USER(2, x, 1)"
        expected(7) = ":8: UCON/1 FUNCTION USER: 'x' is not a number (expected from 1 to 30" &
            & // " numbers)"
        call check_refusals(error, [8, 8, 8, 8, 8, 8, 8], replaced, expected)
    end subroutine test_ucons

    !> INTEGRATOR values outside the ranges of the scenes' &run keys, and the scenes' rule on the
    !> solver choices.
    subroutine test_integrator(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(13)
        character(len=480) :: expected(13)

        replaced(1) = "INTEGRATOR/ERROR=2"
        expected(1) = ":12: INTEGRATOR ERROR must be >= 1e-15 and < 1 (as &run rtol), got 2"
        replaced(2) = "INTEGRATOR/RTOL=0"
        expected(2) = ":12: INTEGRATOR RTOL must be >= 1e-15 and < 1 (as &run rtol), got 0"
        replaced(3) = "INTEGRATOR/ATOL=1e-30"
        expected(3) = ":12: INTEGRATOR ATOL must be >= 1e-20 and <= 1000 (as &run atol), got" &
            & // " 1e-30"
        replaced(4) = "INTEGRATOR/MAXSTEPS=0"
        expected(4) = ":12: INTEGRATOR MAXSTEPS must be a whole number >= 1 and <= 2147483647" &
            & // " (as &run max_steps), got 0"
        replaced(5) = "INTEGRATOR/MAXSTEPS=10.5"
        expected(5) = ":12: INTEGRATOR MAXSTEPS must be a whole number >= 1 and <= 2147483647" &
            & // " (as &run max_steps), got 10.5"
        replaced(6) = "INTEGRATOR/BAUMGARTE=0"
        expected(6) = ":12: INTEGRATOR BAUMGARTE must be > 0 and <= 1000000 [1/s] (as &run" &
            & // " baumgarte_rate), got 0"
        replaced(7) = "INTEGRATOR/ERROR=1e-8, RTOL=1e-8"
        expected(7) = ":12: INTEGRATOR RTOL: give ERROR or RTOL, not both (ERROR sets RTOL)"
        replaced(8) = "INTEGRATOR/METHOD=ADAMS"
        expected(8) = ":12: INTEGRATOR METHOD must be 'bdf' with formulation 'ida' (IDA is a BDF" &
            & // " code; 'adams' needs 'cvode' or 'maggi'), got 'adams'"
        replaced(9) = "INTEGRATOR/FORM=CVODE|, METHOD=ADAMS"
        expected(9) = ":12: INTEGRATOR DRIFT must be 'baumgarte' or 'none' with method = 'adams'" &
            & // " (CVODE projects only with BDF), got 'projection' (DRIFT not given: the" &
            & // " default)"
        replaced(10) = "INTEGRATOR/FORM=CVODE, METH=ADAMS|, DRIFT=PROJ"
        expected(10) = ":13: INTEGRATOR DRIFT must be 'baumgarte' or 'none' with method = 'adams'" &
            & // " (CVODE projects only with BDF), got 'projection'"
        replaced(11) = "INTEGRATOR/DRIFT=NONE"
        expected(11) = ":12: INTEGRATOR DRIFT must be left out with formulation 'ida' (IDA has no" &
            & // " drift; 'baumgarte' and 'none' are for 'cvode' and 'maggi'), got 'none'"
        replaced(12) = "INTEGRATOR/JACOBIAN=DQ, SOLVER=SPARSE"
        expected(12) = ":12: INTEGRATOR SOLVER must be 'dense' or 'auto' unless jacobian =" &
            & // " 'analytic' (the sparse Newton matrix is built from the UCOSUBs' partials)," &
            & // " got 'sparse'"
        replaced(13) = "INTEGRATOR/FORM=CVODE, JACOBIAN=DQ, SOLVER=SPARSE"
        expected(13) = expected(12)
        call check_refusals(error, [12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12], &
            & replaced, expected)
    end subroutine test_integrator

    !> The principal-axes rule at t = 0: a part whose CM marker's z-axis is along ground z is
    !> read (it starts in turned axes, docs/rebasing.md), whether its marker or the part's REULER
    !> puts the axis there, with EXACT translations; EXACT angles are refused, naming the part,
    !> the key and the angle, since the turned axes' angles are not the CM marker's.
    subroutine test_principal_axes(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: tail = ") is parallel to ground z at t = 0 (sin(theta)" &
            & // " = *), so the part starts in those axes turned 90 degrees about x" &
            & // " (docs/rebasing.md), whose Euler angles are not the CM marker's: hold only" &
            & // " X, Y, Z, or turn the CM marker off ground z"
        !> Lines 5 (the PART's continuation) and 6 (its CM marker) of datasets that read
        character(len=60), parameter :: accepted(2, 3) = reshape([character(len=60) :: &
            & ", QG=0, 0, 1, VX=0.5", "MARKER/3, PART=2", &
            & ", QG=0, 0, 1, VX=0.5, EXACT=X:Y:Z", "MARKER/3, PART=2, REULER=45D, 0.01D, 0D", &
            & ", QG=0, 0, 1, EXACT=z", "MARKER/3, PART=2, REULER=0D, 180D, 0D"], [2, 3])
        character(len=120) :: replaced(2)
        character(len=480) :: expected(2)
        character(len=len(base) + 60) :: lines(size(base))
        type(adm_model_type) :: model
        integer :: i

        do i = 1, size(accepted, 2)
            lines = base
            lines(5:6) = accepted(:, i)
            call read_dataset("principal-axes.adm", lines, model, error)
            if (allocated(error)) then
                error%message = trim(accepted(2, i)) // ": " // error%message
                return
            end if
        end do
        replaced(1) = ", QG=0, 0, 1, VX=0.5, REULER=0D, -90D, 0D, EXACT=X:PSI"
        expected(1) = ":4: PART/2 EXACT=PSI: the z-axis of its principal axes (its CM marker," &
            & // " MARKER/3" // tail
        replaced(2) = ", QG=0, 0, 1, VX=0.5, EXACT=phi:Theta, REULER=0D, 270D, 0D"
        expected(2) = ":4: PART/2 EXACT=THETA: the z-axis of its principal axes (its CM" &
            & // " marker, MARKER/3" // tail
        call check_refusals(error, [5, 5], replaced, expected)
    end subroutine test_principal_axes

end module test_adm_refusals
