! SPDX-License-Identifier: MIT
!> The dataset language as ADAMS/View writes it (suite adm-language): a statement's name and
!> slash alone on a line with its arguments on the comma lines below reads as the same
!> statement written compactly, to the last bit of every row of the run; ADAMS's minimum
!> abbreviations accepted where ADAMS accepts them (REQUEST's C, D, F) and refused with the
!> shortest forms where ADAMS refuses them; an expression continued on comma lines at depth 0
!> is one expression, with its value checked; `\`-separated REQUEST expressions; SFORCE's
!> TRANSLATIONAL and ROTATIONAL; a keyword rollcon does not know in a statement of ADAMS's
!> outputs named in the warning, never a refusal; the abbreviation table itself unambiguous.
module test_adm_language
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_expression, only : evaluate_expression
    use rollcon_simulation, only : history_type
    use rollcon_adm_model, only : adm_model_type, request_displacement, request_force, &
        & request_expressions
    use rollcon_adm_outputs, only : unused_warning
    use rollcon_adm_abbreviations, only : abbreviation_places, place_names, &
        & minimum_abbreviation
    use rollcon_adm_run, only : run_times_type
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use adm_datasets, only : read_dataset, check_refusals
    implicit none
    private

    public :: collect_adm_language

    !> The pendulum as ADAMS/View exports it (test/view/view_export_pendulum.adm)
    character(len=*), parameter :: view_file = "test/view/view_export_pendulum.adm"
    !> The same statements written compactly, one line each, names in full
    character(len=80), parameter :: compact(13) = [character(len=80) :: &
        & "pendulum, compact", &
        & "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND", &
        & "PART/1, GROUND", &
        & "MARKER/10, PART=1, REULER=180D, 90D, 180D", &
        & "PART/2, MASS=1, CM=20, IP=0.04, 0.1, 0.1", &
        & "MARKER/20, PART=2, QP=2, 0, 0, REULER=180D, 90D, 180D", &
        & "MARKER/21, PART=2, QP=0, 0, 0, REULER=180D, 90D, 180D", &
        & "JOINT/1, REVOLUTE, I=10, J=21", &
        & "ACCGRAV/KGRAV=-9.80665", &
        & "REQUEST/1, DISPLACEMENT, I=20, J=10, COMMENT=DISPLACEMENT", &
        & "REQUEST/2, FORCE, I=10, J=21, COMMENT=JOINT FORCE", &
        & "OUTPUT/REQSAVE", &
        & "END"]
    !> Values are decimal literals converted once, or a product of two: a few ulp
    real(wp), parameter :: tol = 1.0e-14_wp

contains

    subroutine collect_adm_language(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("view-layout-as-compact", test_view_layout), &
            & new_unittest("abbreviations-as-adams", test_abbreviations), &
            & new_unittest("abbreviations-refused-as-adams", test_short_refused), &
            & new_unittest("expression-continued-at-depth-0", test_continued_expression), &
            & new_unittest("request-expressions-by-backslash", test_request_expressions), &
            & new_unittest("sforce-view-spellings", test_sforce_spellings), &
            & new_unittest("unknown-output-keywords-warned", test_unknown_warned), &
            & new_unittest("abbreviation-table-unambiguous", test_table_unambiguous), &
            & new_unittest("springdamper-export-only-its-elements", test_springdamper)]
    end subroutine collect_adm_language

    !> The View export and its compact twin read to the same model, and their runs (5 s of
    !> 500 steps, given as `rollcon run --end 5 --steps 500` gives them) hold the same rows,
    !> bit for bit; the View layout's UNITS, ACCGRAV and OUTPUT arguments are read from their
    !> comma lines.
    subroutine test_view_layout(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        type(history_type) :: rows(2)
        type(run_times_type) :: times
        character(len=:), allocatable :: paths(:)
        integer :: k
        type(error_type), allocatable :: refused

        ! the compact twin has no SIMULATE either: read alone, it is refused for that only
        call read_dataset("view_compact.adm", compact, model, refused)
        call check(error, allocated(refused), "the compact twin read without a SIMULATE")
        if (allocated(error)) return
        call check(error, index(refused%message, "no SIMULATE statement") > 0, &
            & "compact twin: " // refused%message)
        if (allocated(error)) return
        times%end_given = .true.
        times%steps_given = .true.
        times%end_time = 5.0_wp
        times%steps = 500.0_wp
        times%written = "--end 5 --steps 500"
        paths = [character(len=64) :: view_file, "build/rollcon-test/view_compact.adm"]
        do k = 1, 2
            call run_rows(trim(paths(k)), times, rows(k), error)
            if (allocated(error)) return
        end do
        call check(error, rows(1)%count == 501 .and. rows(2)%count == 501 .and. &
            & size(rows(1)%rows, 1) == size(rows(2)%rows, 1), "501 rows of one layout each, got " &
            & // to_text(rows(1)%count) // " and " // to_text(rows(2)%count))
        if (allocated(error)) return
        call check(error, all(rows(1)%rows(:, :501) == rows(2)%rows(:, :501)), "the View " &
            & // "layout's rows are the compact dataset's, bit for bit")
        if (allocated(error)) return
        ! gravity along -Z from ACCGRAV's comma line: the pendulum falls from level at t = 0
        call check(error, rows(1)%rows(rows(1)%layout%column("Z_2"), 2) < 0.0_wp, &
            & "the pendulum falls under the gravity of ACCGRAV's comma line")
    end subroutine test_view_layout

    !> Load the dataset at path with the run's times and run it, its rows kept.
    subroutine run_rows(path, times, rows, error)
        character(len=*), intent(in) :: path
        type(run_times_type), intent(in) :: times
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result

        call load_job(path, job, error, times=times)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
    end subroutine run_rows

    !> ADAMS's abbreviations: REQUEST's D (DISPLACEMENT), F (FORCE) and C= (COMMENT) although
    !> other REQUEST keywords begin with those letters; CN= is CNAMES, CU= CUNITS; statements
    !> and keywords of the other statements at their shortest (SF, MAR, PA, SI/DY, E, STE).
    subroutine test_abbreviations(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model

        call read_dataset("abbreviated.adm", [character(len=80) :: "ADAMS's shortest forms", &
            & "UN/SY=SI", "PA/1, G", "PA/2, M=1, C=3, IP=2, 2, 3, Q=0, 0, 1", &
            & "MAR/3, PA=2, R=0D, 90D, 0D", "MAR/4, PA=1", "AC/K=-9.81", &
            & "SF/5, I=3, J=4, T, F=TIME", &
            & "REQ/6, D, I=3, J=4, C=centre, CN=x, y, CU=m, CL=a", &
            & "REQ/7, F, I=3, J=4, C=the force", &
            & "SI/DY, E=1, STE=10", "END"], model, error)
        if (allocated(error)) return
        call check(error, size(model%requests) == 1 .and. size(model%other_requests) == 1, &
            & "one displacement request honoured, one force request kept")
        if (allocated(error)) return
        associate (d => model%requests(1), f => model%other_requests(1))
            call check(error, d%id == 6 .and. d%kind == request_displacement .and. d%i == 3 &
                & .and. d%j == 4 .and. d%comment == "centre", "REQ/6: D, C=centre")
            if (allocated(error)) return
            call check(error, f%id == 7 .and. f%kind == request_force .and. f%i == 3 .and. &
                & f%j == 4 .and. f%comment == "the force", "REQ/7: F, C=the force")
            if (allocated(error)) return
        end associate
        call check(error, model%forces(1)%translation .and. model%parts(2)%cm == 3 .and. &
            & model%gravity(3) == -9.81_wp .and. model%run%settings%end_time == 1.0_wp .and. &
            & model%run%settings%output_step == 0.1_wp, "SF T, PA C, AC K, SI E and STE")
        if (allocated(error)) return
        ! both requests are answered: the warning names neither
        call check(error, index(unused_warning(model), "REQUEST") == 0, &
            & "warning: " // unused_warning(model))
    end subroutine test_abbreviations

    !> Where ADAMS refuses an abbreviation, rollcon does, naming the shortest forms: a
    !> statement (S: SFORCE or SIMULATE; G: GFORCE or GRAPHICS), a keyword of a simulated
    !> statement (PART's I: IP needs two letters; SIMULATE's ST: STEPS needs three).
    subroutine test_short_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=80) :: replaced(5)
        character(len=400) :: expected(5)

        replaced(1) = "S/5, I=3, J=4, TRANSLATION, FUNCTION=TIME"
        expected(1) = ":10: 'S' is too short an abbreviation of a statement: the shortest ADAMS" &
            & // " takes are SF for SFORCE, SI for SIMULATE, SPL for SPLINE, SPR for" &
            & // " SPRINGDAMPER, ST for STRING (docs/datasets.md, Abbreviations)"
        replaced(2) = "G/5, I=3, FX=0, FY=0, FZ=1, TX=0, TY=0, TZ=0"
        expected(2) = ":10: 'G' is too short an abbreviation of a statement: the shortest ADAMS" &
            & // " takes are GC for GCON, GE for GEAR, GF for GFORCE, GR for GRAPHICS" &
            & // " (docs/datasets.md, Abbreviations)"
        replaced(3) = "PART/2, MASS=1, CM=3, I=2, 2, 3"
        expected(3) = ":4: PART/2: 'I' is too short an abbreviation of a PART argument: the" &
            & // " shortest ADAMS takes is IP for IP (docs/datasets.md, Abbreviations)"
        replaced(4) = "SIMULATE/DYNAMIC, END=1, ST=10"
        expected(4) = ":11: SIMULATE: 'ST' is too short an abbreviation of a SIMULATE" &
            & // " argument: the shortest ADAMS takes are STE for STEPS, STA for STATIC" &
            & // " (docs/datasets.md, Abbreviations)"
        replaced(5) = "SFORCE/5, I=3, J=4, R, FUNCTION=TIME"
        expected(5) = ":10: SFORCE/5: 'R' is too short an abbreviation of an SFORCE argument:" &
            & // " the shortest ADAMS takes are ROT for ROTATION, ROTATIONA for ROTATIONAL," &
            & // " ROU for ROUTINE (docs/datasets.md, Abbreviations)"
        call check_refusals(error, [10, 10, 4, 11, 10], replaced, expected)
    end subroutine test_short_refused

    !> FUNCTION = -100*(DX(3)-2) then `, - 1.0*VX(3)` then `, + 0.5` is one expression (ADAMS
    !> reads an expression to a backslash or the statement's end, the commas that begin its
    !> lines dropped); so is one continued inside parentheses and past them, and one whose line
    !> ends with an operator before a name alone.
    subroutine test_continued_expression(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model

        call read_dataset("continued.adm", [character(len=80) :: "expressions on comma lines", &
            & "PART/1, GROUND", "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1", &
            & "MARKER/3, PART=2, REULER=0D, 90D, 0D", "MARKER/4, PART=1", &
            & "SFORCE/5, TRANSLATIONAL, I=3, J=4", ", FUNCTION = -100*(TIME-2.0)", &
            & ", - 1.0*TIME", ", + 0.5", &
            & "SFORCE/6, I=3, J=4, FUNCTION=STEP(TIME, 0, 0,", ", 1, 5)", ", - 1", &
            & "SFORCE/7, I=3, J=4, FUNCTION=3*", ", TIME, ROTATIONAL", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "END"], model, error)
        if (allocated(error)) return
        ! at t = 1: -100*(1 - 2) - 1 + 0.5 = 99.5; STEP at its end is 5, less 1; 3*1
        call check(error, [evaluate_expression(model%forces(1)%functions(1), 1.0_wp), &
            & evaluate_expression(model%forces(2)%functions(1), 1.0_wp), &
            & evaluate_expression(model%forces(3)%functions(1), 1.0_wp)], [99.5_wp, 4.0_wp, &
            & 3.0_wp], "the continued expressions at t = 1", abs_tol=tol)
        if (allocated(error)) return
        ! and at t = 3, where a comma taken for a separator would have cut each short
        call check(error, [evaluate_expression(model%forces(1)%functions(1), 3.0_wp), &
            & evaluate_expression(model%forces(3)%functions(1), 3.0_wp)], [-102.5_wp, 9.0_wp], &
            & "at t = 3", abs_tol=tol)
        if (allocated(error)) return
        call check(error, model%forces(1)%translation .and. .not. model%forces(3)%translation, &
            & "TRANSLATIONAL after the I=, J= line; ROTATIONAL after the expression")
    end subroutine test_continued_expression

    !> F1 ... F8 separated by backslashes, on one line and over comma lines (a comma after a
    !> backslash is the same separator): one request of expressions, each column's text kept.
    subroutine test_request_expressions(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model

        call read_dataset("request_columns.adm", [character(len=80) :: "request columns", &
            & "PART/1, GROUND", "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1", &
            & "MARKER/3, PART=2, REULER=0D, 90D, 0D", "MARKER/4, PART=1", &
            & "REQUEST/8, C=joint reaction", ", F2=JOINT(1,0,2,0)\F3=JOINT(1,0,3,0)\", &
            & ", F4=DX(3)", ", - DX(4)\", ", F6=VZ(3)", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "END"], model, error)
        if (allocated(error)) return
        call check(error, size(model%other_requests) == 1, "one request kept")
        if (allocated(error)) return
        associate (r => model%other_requests(1))
            call check(error, r%id == 8 .and. r%kind == request_expressions .and. r%comment == &
                & "joint reaction" .and. r%columns(1)%text == "" .and. r%columns(2)%text == &
                & "JOINT(1,0,2,0)" .and. r%columns(3)%text == "JOINT(1,0,3,0)" .and. &
                & r%columns(4)%text == "DX(3) - DX(4)" .and. r%columns(6)%text == "VZ(3)" &
                & .and. r%columns(8)%text == "", "columns: '" // r%columns(2)%text // "', '" &
                & // r%columns(3)%text // "', '" // r%columns(4)%text // "', '" &
                & // r%columns(6)%text // "'")
        end associate
        if (allocated(error)) return
        ! answered where the dataset is assembled: not in the warning
        call check(error, index(unused_warning(model), "REQUEST") == 0, &
            & "warning: " // unused_warning(model))
    end subroutine test_request_expressions

    !> SFORCE's TRANSLATIONAL and ROTATIONAL (ADAMS/View's spellings) are TRANSLATION and
    !> ROTATION; both together are refused.
    subroutine test_sforce_spellings(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        character(len=80) :: replaced(1)
        character(len=400) :: expected(1)

        call read_dataset("spellings.adm", [character(len=80) :: "SFORCE spellings", &
            & "PART/1, GROUND", "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1", &
            & "MARKER/3, PART=2, REULER=0D, 90D, 0D", "MARKER/4, PART=1", &
            & "SFORCE/5, TRANSLATIONAL, I=3, J=4, FUNCTION=1", &
            & "SFORCE/6, ROTATIONAL, I=3, J=4, FUNCTION=1", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "END"], model, error)
        if (allocated(error)) return
        call check(error, model%forces(1)%translation .and. .not. model%forces(2)%translation, &
            & "TRANSLATIONAL, ROTATIONAL")
        if (allocated(error)) return
        replaced(1) = "SFORCE/5, I=3, J=4, TRANSLATIONAL, ROTATION, FUNCTION=TIME"
        expected(1) = ":10: SFORCE/5 ROTATION: TRANSLATION (TRANSLATIONAL) and ROTATION" &
            & // " (ROTATIONAL) are given together; an SFORCE is one of them"
        call check_refusals(error, [10], replaced, expected)
    end subroutine test_sforce_spellings

    !> GRAPHICS's LD, DD and FACETING_TOLERANCE are read; a keyword rollcon does not know in a
    !> GRAPHICS, a REQUEST, OUTPUT or RESULTS is named in the warning apart, and the dataset
    !> reads; a REQUEST of a kind rollcon does not know is not refused either.
    subroutine test_unknown_warned(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        character(len=:), allocatable :: warning

        call read_dataset("unknown_keywords.adm", [character(len=96) :: "unknown keywords", &
            & "PART/1, GROUND", "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1", &
            & "MARKER/3, PART=2, REULER=0D, 90D, 0D", "MARKER/4, PART=1", &
            & "GRAPHICS/1, SPDP, I=3, J=4, DA=0.1, DB=0.2, DC=0.16, LA=0.5, LB=0.5", &
            & ", LC=1.3, LD=1.3, DD=0.1, FACETING_TOLERANCE=300", &
            & "GRAPHICS/2, CYLINDER, CM=3, LENGTH=1, RADIUS=0.1, COLOR=RED, SEGMENTS=20", &
            & "REQUEST/3, DISPLACEMENT, I=3, J=4, VARIABLES=2", "REQUEST/4, NEWKIND, I=3", &
            & "OUTPUT/REQSAVE, LOADS", "RESULTS/XRF, CX", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "END"], model, error)
        if (allocated(error)) return
        warning = unused_warning(model)
        call check(error, index(warning, "read and checked but not used: GRAPHICS (lines 6, " &
            & // "8), OUTPUT REQSAVE (line 11), RESULTS (line 12); not known to rollcon, not " &
            & // "read: GRAPHICS COLOR (line 8), GRAPHICS SEGMENTS (line 8), REQUEST " &
            & // "VARIABLES (line 9), REQUEST NEWKIND (line 10), OUTPUT LOADS (line 11), " &
            & // "RESULTS CX (line 12); rollcon writes its own outputs") > 0, "warning: " &
            & // warning)
        if (allocated(error)) return
        call check(error, size(model%requests) == 1, "REQUEST/3 honoured")
    end subroutine test_unknown_warned

    !> No written word stands for two names of one place in the table: for each pair, the
    !> beginnings at least as long as both shortest forms differ (or one name is the other's
    !> exact beginning, which an exact name decides). And every name's shortest form is at
    !> least one letter and at most the name.
    subroutine test_table_unambiguous(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=12), allocatable :: places(:)
        character(len=32), allocatable :: names(:)
        integer :: p, a, b, ma, mb, k

        places = abbreviation_places()
        do p = 1, size(places)
            names = place_names(trim(places(p)))
            do a = 1, size(names)
                ma = minimum_abbreviation(trim(places(p)), trim(names(a)))
                call check(error, ma >= 1 .and. ma <= len_trim(names(a)), trim(places(p)) &
                    & // " " // trim(names(a)) // ": shortest form of " // to_text(ma))
                if (allocated(error)) return
                do b = a + 1, size(names)
                    mb = minimum_abbreviation(trim(places(p)), trim(names(b)))
                    k = max(ma, mb)
                    if (k > min(len_trim(names(a)), len_trim(names(b)))) cycle
                    call check(error, names(a)(:k) /= names(b)(:k), trim(places(p)) // ": " &
                        & // names(a)(:k) // " would stand for " // trim(names(a)) // " and " &
                        & // trim(names(b)))
                    if (allocated(error)) return
                end do
            end do
        end do
    end subroutine test_table_unambiguous

    !> A spring-damper as ADAMS/View exports one (an SFORCE TRANSLATIONAL whose FUNCTION goes
    !> on over comma lines at depth 0, a VARIABLE, a GRAPHICS SPDP with LD): read as it is, its
    !> VARIABLE reading DM(10,20) and its FUNCTION the two-marker measures DM(10,20) and
    !> VR(10,20).
    subroutine test_springdamper(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=96) :: lines(15)
        type(adm_model_type) :: model
        type(error_type), allocatable :: refused
        character(len=*), parameter :: file = "build/rollcon-test/springdamper.adm"

        lines = [character(len=96) :: "mass on a spring-damper as ADAMS/View exports it", &
            & "UNITS/FORCE = NEWTON, MASS = KILOGRAM, LENGTH = METER, TIME = SECOND", &
            & "PART/1, GROUND", "MARKER/10, PART = 1", &
            & "PART/2, MASS = 1, CM = 20, IP = 0.04, 0.1, 0.1", &
            & "MARKER/20, PART = 2, QP = 0, 2, 0", &
            & "SFORCE/1, TRANSLATIONAL, I = 10, J = 20", ", FUNCTION = - 100.0*(DM(10,20)-2.0)", &
            & ", - 1.0*VR(10,20)", ", + 0.0", "VARIABLE/1, FUNCTION = DM(10,20) - 2.0", &
            & "GRAPHICS/1, SPDP, I = 10, J = 20, DA = 0.1, DB = 0.2, DC = 0.16, LD = 1.34", &
            & "ACCGRAV/KGRAV = -9.80665", "SIMULATE/DYNAMIC, END = 5, STEPS = 500", "END"]
        call read_dataset("springdamper.adm", lines, model, error)
        if (allocated(error)) return
        call check(error, size(model%variables) == 1, "the export's VARIABLE read")
        if (allocated(error)) return
        call check(error, model%variables(1)%id == 1 .and. model%variables(1)%line == 11 &
            & .and. size(model%variables(1)%function%inputs) == 1, "VARIABLE/1 at line 11 " &
            & // "reads one measure")
        if (allocated(error)) return
        call check(error, model%variables(1)%function%inputs(1)%marker == 10 .and. &
            & model%variables(1)%function%inputs(1)%j == 20, "VARIABLE/1 reads DM(10,20)")
        if (allocated(error)) return
        call check(error, size(model%forces(1)%functions(1)%inputs) == 2, &
            & "the FUNCTION reads two measures, DM(10,20) and VR(10,20)")
        if (allocated(error)) return
        call check(error, all(model%forces(1)%functions(1)%inputs%marker == 10) .and. &
            & all(model%forces(1)%functions(1)%inputs%j == 20), "both of 10 from 20")
        if (allocated(error)) return
        call check(error, model%forces(1)%translation .and. model%forces(1)%i == 10 .and. &
            & model%forces(1)%j == 20, "the SFORCE, translational between 10 and 20")
    end subroutine test_springdamper

end module test_adm_language
