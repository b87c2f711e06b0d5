! SPDX-License-Identifier: MIT
!> A dataset's statements of ADAMS's outputs and solver choices: read and checked, named in
!> one warning of a run that goes on (through the program); REQUEST/id, DISPLACEMENT honoured
!> as CSV columns, their values against the motion of a spinning part and of one re-based as
!> it turns; their syntax and references refused with file, line and key; every statement
!> outside the subset refused in one message; the README's walk-through dataset with REQUEST
!> and GRAPHICS left in.
module test_adm_outputs
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix
    use rollcon_output_layout, only : output_layout_type, coord_x, coord_psi, read_layout, &
        & name_length
    use rollcon_watch_columns, only : request_column_patterns
    use rollcon_simulation, only : history_type
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_adm_model, only : adm_model_type
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use adm_datasets, only : read_dataset, check_refusals, base, base_file
    use picture_files, only : make_folder, remove_folder, write_lines
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count
    implicit none
    private

    public :: collect_adm_outputs

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_adm_outputs"
    !> An integrated motion at ERROR=1e-10 against its closed form, over at most 2 s and 6 rad
    !> of turning: the global error is a few hundred local errors, below 1e-7; 1e-6 leaves
    !> room and is a thousand times below a marker misplaced by 1 mm
    real(wp), parameter :: tol_motion = 1.0e-6_wp
    !> Columns the watch computes from the very state a row holds: a few roundings
    real(wp), parameter :: tol_same = 1.0e-12_wp

    !> Every kind of statement read and not used, and a displacement request
    character(len=72), parameter :: outputs(17) = [character(len=72) :: &
        & "outputs: ADAMS's output statements, read and warned once", &
        & "UNITS/SYSTEM=SI", &
        & "PART/1, GROUND", &
        & "MARKER/4, PART=1", &
        & "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1, VX=0.5", &
        & "MARKER/3, PART=2, REULER=0D, 90D, 0D", &
        & "ACCGRAV/KGRAV=-9.81", &
        & "REQUEST/1, DISPLACEMENT, I=3, J=4, COMMENT=the centre", &
        & "REQUEST/2, VELOCITY, I=3, J=4", &
        & "RESULTS/FORMATTED", &
        & "GRAPHICS/1, CYLINDER, CM=3, LENGTH=0.1, RADIUS=0.05", &
        & "GRAPHICS/2, BOX, CORNER=4, X=1, Y=1, Z=0.01", &
        & "OUTPUT/REQSAVE, GRSAVE", &
        & "DEBUG/EPRINT", &
        & "SIMULATE/DYNAMIC, END=0.5, STEPS=10", &
        & "INTEGRATOR/GSTIFF, ERROR=1e-9, HMAX=0.01", &
        & "END"]

    !> A part spinning at 2 rad/s about its principal z (ground -Y) and moving along X at
    !> 0.5 m/s, no gravity: marker 5 circles in the X-Z plane; marker 4 on ground, turned 90
    !> degrees about Z, is request 1's J and RM
    character(len=72), parameter :: spin(11) = [character(len=72) :: &
        & "spin: a part turning steadily about a principal axis", &
        & "PART/1, GROUND", &
        & "MARKER/4, PART=1, QP=1, 2, 0.5, REULER=90D, 0D, 0D", &
        & "PART/2, MASS=1, CM=3, IP=2, 2, 3, QG=0, 0, 1, VX=0.5, WZ=2", &
        & "MARKER/3, PART=2, REULER=0D, 90D, 0D", &
        & "MARKER/5, PART=2, QP=0.1, 0, 0", &
        & "REQUEST/1, DISPLACEMENT, I=5, J=4, RM=4", &
        & "REQUEST/2, DISPLACEMENT, I=3", &
        & "SIMULATE/DYNAMIC, END=1, STEPS=20", &
        & "INTEGRATOR/ERROR=1e-10", &
        & "END"]

    !> A part turning at 3 rad/s about ground X, its principal x (the largest moment): its
    !> principal z passes along ground Z twice a turn, where the run re-bases its axes
    character(len=72), parameter :: tip(9) = [character(len=72) :: &
        & "tip: a part turning through the Euler-angle singularity", &
        & "PART/1, GROUND", &
        & "PART/2, MASS=1, CM=3, IP=3, 2, 2, QG=0, 0, 1, WX=3", &
        & "MARKER/3, PART=2, REULER=0D, 90D, 0D", &
        & "MARKER/5, PART=2, QP=0, 0.1, 0.2", &
        & "REQUEST/7, DISPLACEMENT, I=5", &
        & "SIMULATE/DYNAMIC, END=2, STEPS=40", &
        & "INTEGRATOR/ERROR=1e-10", &
        & "END"]

contains

    subroutine collect_adm_outputs(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("one-warning-and-the-run-goes-on", test_one_warning), &
            & new_unittest("displacement-of-a-spinning-part", test_spin), &
            & new_unittest("displacement-across-rebasings", test_tip), &
            & new_unittest("syntax-and-references-refused", test_refusals), &
            & new_unittest("every-outside-statement-at-once", test_outside), &
            & new_unittest("readme-walk-through-with-outputs", test_walk_through), &
            & new_unittest("request-columns-read-back", test_read_back)]
    end subroutine collect_adm_outputs

    !> Through the program: exit 0, one line on standard error naming every statement (and
    !> keyword) read and not used with its lines, the same in the summary; the displacement
    !> request's columns are the part's centre from the ground origin.
    subroutine test_one_warning(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/outputs.adm"
        character(len=:), allocatable :: program, stderr, summary, warning
        type(output_layout_type) :: layout
        type(history_type) :: rows
        integer :: status, k

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_lines(path, outputs)
        call run_rollcon(program, "run " // path // " -q -o " // scratch // "/out", scratch &
            & // "/run.out", scratch // "/run.err", status)
        stderr = file_text(scratch // "/run.err")
        summary = file_text(scratch // "/out/outputs.adm.summary.txt")
        warning = path // ": read and checked but not used: " &
            & // "RESULTS (line 10), GRAPHICS (lines 11, 12), OUTPUT REQSAVE (line 13), " &
            & // "OUTPUT GRSAVE (line 13), DEBUG (line 14), INTEGRATOR GSTIFF (line 16), " &
            & // "INTEGRATOR HMAX (line 16); rollcon writes its own outputs and integrates " &
            & // "with its own INTEGRATOR settings (docs/datasets.md)"
        call check(error, status == 0 .and. stderr == "rollcon: warning: " // warning &
            & // new_line("a") .and. index(summary, "warning: " // warning // new_line("a")) &
            & > 0 .and. index(summary, "status: completed at t = 0.5 s") > 0, "exit status " &
            & // to_text(status) // "; stderr: " // stderr // "; summary: " // summary)
        if (.not. allocated(error)) call read_output_csv(scratch // "/out/outputs.adm.csv", &
            & layout, rows, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, rows%count == 11 .and. layout%column("req1_x") > 0 .and. &
            & layout%column("req2_x") == 0, "11 rows, columns of REQUEST/1 only")
        do k = 0, 2
            if (allocated(error)) return
            call check(error, rows%column(layout%column("req1_" // trim(xyz(k)))), &
                & rows%column(layout%part_column(1, coord_x + k)), "req1_" // trim(xyz(k)) &
                & // " against the centre", abs_tol=tol_same)
        end do
    end subroutine test_one_warning

    !> The spinning part (in process): request 1, marker 5 from the turned ground marker 4 in
    !> its axes, and request 2, the CM marker from the ground origin, against the closed form
    !> of the motion.
    subroutine test_spin(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows
        real(wp) :: t, c, s, expected(3), turned(3, 3), own(3, 3)
        integer :: i

        call run_rows("spin.adm", spin, rows, error)
        if (allocated(error)) return
        call check(error, rows%count == 21, "21 rows, got " // to_text(rows%count))
        do i = 1, rows%count
            if (allocated(error)) return
            t = rows%rows(1, i)
            c = cos(2.0_wp*t)
            s = sin(2.0_wp*t)
            ! marker 5: (0.5 t + 0.1 cos 2t, 0, 1 + 0.1 sin 2t); marker 4 at (1, 2, 0.5) with
            ! x along ground Y, y along -X: x = dY, y = -dX, z = dZ
            expected = [-2.0_wp, 1.0_wp - 0.5_wp*t - 0.1_wp*c, 0.5_wp + 0.1_wp*s]
            call check(error, request(rows, 1, i, "xyz"), expected, "req1 x, y, z at t = " &
                & // to_text(t), abs_tol=tol_motion)
            if (allocated(error)) return
            ! marker 5's axes are the part's, turned by 2t about ground -Y; in marker 4's axes
            turned = matmul(transpose(rotation_matrix(0.5_wp*acos(-1.0_wp), 0.0_wp, 0.0_wp)), &
                & about_y(-2.0_wp*t))
            call check(error, reshape(axes_of(request(rows, 1, i, "angles")), [9]), &
                & reshape(turned, [9]), "req1 psi, theta, phi at t = " // to_text(t), &
                & abs_tol=tol_motion)
            if (allocated(error)) return
            call check(error, request(rows, 2, i, "xyz"), [0.5_wp*t, 0.0_wp, 1.0_wp], &
                & "req2 x, y, z at t = " // to_text(t), abs_tol=tol_motion)
            if (allocated(error)) return
            ! the CM marker's axes are the part's principal axes: the row's own angles
            own = rotation_matrix(rows%rows(rows%layout%part_column(1, coord_psi), i), &
                & rows%rows(rows%layout%part_column(1, coord_psi) + 1, i), &
                & rows%rows(rows%layout%part_column(1, coord_psi) + 2, i))
            call check(error, reshape(axes_of(request(rows, 2, i, "angles")), [9]), &
                & reshape(own, [9]), "req2 angles against psi_2, theta_2, phi_2 at t = " &
                & // to_text(t), abs_tol=tol_same)
        end do
    end subroutine test_spin

    !> The turning part: its principal axes are re-based as they pass the singularity, and
    !> marker 5's displacement stays that of the same body-fixed point and axes.
    subroutine test_tip(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: rows
        real(wp) :: t, c, s
        integer :: i

        call run_rows("tip.adm", tip, rows, error)
        if (allocated(error)) return
        call check(error, rows%count == 41 .and. rows%rows(rows%layout%column("basis_2"), &
            & rows%count) >= 2.0_wp, "41 rows and the axes re-based at least twice")
        do i = 1, rows%count
            if (allocated(error)) return
            t = rows%rows(1, i)
            c = cos(3.0_wp*t)
            s = sin(3.0_wp*t)
            call check(error, request(rows, 7, i, "xyz"), [0.0_wp, 0.1_wp*c - 0.2_wp*s, &
                & 1.0_wp + 0.1_wp*s + 0.2_wp*c], "req7 x, y, z at t = " // to_text(t) &
                & // " (basis " // to_text(rows%rows(rows%layout%column("basis_2"), i)) // ")", &
                & abs_tol=tol_motion)
            if (allocated(error)) return
            call check(error, reshape(axes_of(request(rows, 7, i, "angles")), [9]), &
                & reshape(about_x(3.0_wp*t), [9]), "req7 angles at t = " // to_text(t), &
                & abs_tol=tol_motion)
        end do
    end subroutine test_tip

    !> The syntax and references of the statements read and not used, refused as those of the
    !> statements simulated: the file, the line, the statement, the key.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(15)
        character(len=400) :: expected(15)

        replaced(1) = "REQUEST/1, DISPLACEMENT, I=99"
        expected(1) = ":13: REQUEST/1 I: no MARKER/99"
        replaced(2) = "REQUEST/1, DISPLACEMENT, I=3, J=4, RM=98"
        expected(2) = ":13: REQUEST/1 RM: no MARKER/98"
        replaced(3) = "GRAPHICS/2, CYLINDER, CM=97, LENGTH=1, RADIUS=0.1"
        expected(3) = ":13: GRAPHICS/2 CM: no MARKER/97"
        replaced(4) = "MREQUEST/3, DISPLACEMENT, PARTS=2, 9"
        expected(4) = ":13: MREQUEST/3 PARTS: no PART/9"
        ! a keyword rollcon knows is read as strictly as ever (one it does not know is warned)
        replaced(5) = "REQUEST/1, DISPLACEMENT, I=3, C"
        expected(5) = ":13: REQUEST/1 COMMENT: expected a value (COMMENT=...)"
        replaced(6) = "REQUEST/1, I=3"
        expected(6) = ":13: REQUEST/1: a REQUEST asks for one of DISPLACEMENT, VELOCITY," &
            & // " ACCELERATION, FORCE (of its I marker) or expressions (F1..F8," &
            & // " FUNCTION=USER(...)), got 0"
        replaced(7) = "REQUEST/1, VELOCITY, J=4"
        expected(7) = ":13: REQUEST/1 I: VELOCITY needs the marker it measures (I=id of a" &
            & // " MARKER)"
        replaced(8) = "GRAPHICS/2, CYLINDER, BOX, CM=3"
        expected(8) = ":13: GRAPHICS/2: give one shape (ARC, BOX, CIRCLE, CURVE, CYLINDER," &
            & // " ELLIPSOID, EXTERNAL, FORCE, FRUSTUM, PLANE, POINT, SPDP, TORUS or" &
            & // " OUTLINE=ids), got 2"
        replaced(9) = "RESULTS/SIGFIGS=2.5"
        expected(9) = ":13: RESULTS SIGFIGS must be a whole number >= 0, got 2.5"
        replaced(10) = "REQUEST/1, DISPLACEMENT, I=3|REQUEST/1, VELOCITY, I=3"
        expected(10) = ":14: REQUEST/1: a second REQUEST with this id"
        replaced(11) = "OUTPUT/REQSAVE=1"
        expected(11) = ":13: OUTPUT REQSAVE takes no value"
        replaced(12) = "REQUEST, DISPLACEMENT, I=3"
        expected(12) = ":13: REQUEST needs an id (REQUEST/id, ...)"
        replaced(13) = "INTEGRATOR/KMAX=2.5"
        expected(13) = ":12: INTEGRATOR KMAX must be a whole number >= 0, got 2.5"
        replaced(14) = "GRAPHICS/2, CIRCLE, CM=3, RADIUS=big"
        expected(14) = ":13: GRAPHICS/2 RADIUS: 'big' is not a number (expected 1 number)"
        replaced(15) = "RE/1, DISPLACEMENT, I=3"
        expected(15) = ":13: 'RE' is too short an abbreviation of a statement: the shortest" &
            & // " ADAMS takes are REQ for REQUEST, RES for RESULTS (docs/datasets.md," &
            & // " Abbreviations)"
        call check_refusals(error, [13, 13, 13, 13, 13, 13, 13, 13, 13, 13, 13, 13, 12, 13, &
            & 13], replaced, expected)
    end subroutine test_refusals

    !> Statements that would change the physics, and names rollcon does not know: all of them
    !> in one message, each with its line and why; through the program, one refusal and no run.
    subroutine test_outside(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=160) :: lines(size(base))
        character(len=:), allocatable :: expected, program, stderr
        character(len=*), parameter :: nl = new_line("a"), file = base_file
        type(adm_model_type) :: model
        type(error_type), allocatable :: refused
        integer :: status

        lines = base
        lines(13) = "PTCV/9, I=3, J=4|CVCV/1, I=3|BEAM/2, I=3, J=4|FOO/1" &
            & // "|REQUEST/1, DISPLACEMENT, I=3"
        call read_dataset("refusal.adm", lines, model, refused)
        expected = file // ": 4 statements are outside the supported subset (ACCGRAV, ARRAY," &
            & // " BUSHING, CONTACT, COUPLER, DIFF, END, GCON, GEAR, GFORCE, INTEGRATOR, JOINT," &
            & // " JPRIM," &
            & // " MARKER, MOTION, OUTPUT, PART, PINPUT, POUTPUT, SFORCE, SIMULATE, SPLINE," &
            & // " SPRINGDAMPER, STRING, UCON, UNITS, VARIABLE, VFORCE, VTORQUE;" &
            & // " read and not used: DEBUG, EQUILIBRIUM," &
            & // " GRAPHICS, IC, KINEMATICS, LIST, MREQUEST, NOLIST, PREFERENCES, REQUEST," &
            & // " RESULTS); nothing was run:" &
            & // nl // "  " // file // ":13: PTCV/9: rollcon's constraints are UCONs, JOINTs," &
            & // " JPRIMs, GCONs, COUPLERs and GEARs: state this one as a GCON expression, or" &
            & // " as a UCON served by a UCOSUB (ucon/)" // nl // "  " // file &
            & // ":14: CVCV/1: rollcon's constraints are UCONs, JOINTs, JPRIMs, GCONs," &
            & // " COUPLERs and GEARs: state this one as a GCON expression, or as a UCON served" &
            & // " by a UCOSUB (ucon/)" // nl // "  " // file // ":15: BEAM/2:" &
            & // " force elements other than SFORCE, VFORCE, GFORCE, VTORQUE, SPRINGDAMPER and" &
            & // " BUSHING are not in the subset: write the force as a GFORCE with FUNCTION" &
            & // " expressions" // nl // "  " &
            & // file // ":16: 'FOO' is not a statement of the supported subset"
        call check(error, allocated(refused), "the dataset was accepted")
        if (allocated(error)) return
        call check(error, refused%message == expected, "got '" // refused%message &
            & // "', expected '" // expected // "'")
        if (allocated(error)) return
        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run " // file // " -q -o " // scratch // "/out", scratch &
            & // "/run.out", scratch // "/run.err", status)
        stderr = file_text(scratch // "/run.err")
        call check(error, status == 1 .and. stderr == "rollcon: error: " // expected // nl &
            & .and. .not. file_exists(scratch // "/out"), "exit status " // to_text(status) &
            & // "; stderr: " // stderr)
        call remove_folder(scratch)
    end subroutine test_outside

    !> The README's "Your own model": data/coin.adm with a REQUEST and a GRAPHICS left in runs
    !> (exit 0, completed, one warning naming the GRAPHICS), its request is the disk's centre,
    !> and `rollcon plot` draws the CSV with the request's columns.
    subroutine test_walk_through(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/coin.adm"
        character(len=:), allocatable :: program, text, stderr, summary
        type(output_layout_type) :: layout
        type(history_type) :: rows
        integer :: status_run, status_plot, cut, k

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        text = file_text("data/coin.adm")
        cut = index(text, new_line("a") // "END" // new_line("a"), back=.true.)
        call check(error, cut > 0, "data/coin.adm has no END line")
        if (allocated(error)) return
        call write_text(path, text(:cut) // "REQUEST/1, DISPLACEMENT, I=3, J=1, " &
            & // "COMMENT=the disk's centre" // new_line("a") // "GRAPHICS/1, CYLINDER, CM=3, " &
            & // "LENGTH=0.003, RADIUS=0.1, SIDES=40" // text(cut:))
        call run_rollcon(program, "run " // path // " -q -o " // scratch // "/out", scratch &
            & // "/run.out", scratch // "/run.err", status_run)
        call run_rollcon(program, "plot " // scratch // "/out/coin.adm.csv -o " // scratch &
            & // "/out", scratch // "/plot.out", scratch // "/plot.err", status_plot)
        stderr = file_text(scratch // "/run.err")
        summary = file_text(scratch // "/out/coin.adm.summary.txt")
        call check(error, status_run == 0 .and. status_plot == 0 .and. line_count(stderr) == 1 &
            & .and. index(stderr, "rollcon: warning: " // path // ": read and checked but not " &
            & // "used: GRAPHICS (line ") == 1 .and. index(summary, "status: completed at t = " &
            & // "10 s") > 0 .and. file_exists(scratch // "/out/coin.adm_path.png"), &
            & "exit statuses " &
            & // to_text(status_run) // ", " // to_text(status_plot) // "; stderr: " // stderr &
            & // file_text(scratch // "/plot.err") // "; summary: " // summary)
        if (.not. allocated(error)) call read_output_csv(scratch // "/out/coin.adm.csv", layout, &
            & rows, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, rows%count == 1001, "1001 rows, got " // to_text(rows%count))
        do k = 0, 2
            if (allocated(error)) return
            call check(error, rows%column(layout%column("req1_" // trim(xyz(k)))), &
                & rows%column(layout%part_column(1, coord_x + k)), "req1_" // trim(xyz(k)) &
                & // " against the disk's centre", abs_tol=tol_same)
        end do
    end subroutine test_walk_through

    !> A CSV reader knows a request's columns by their pattern, for any id: req12_theta is
    !> read back; a name that is not the pattern's is refused.
    subroutine test_read_back(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=name_length), allocatable :: names(:)
        character(len=name_length) :: wrong(5)
        type(output_layout_type) :: layout
        character(len=:), allocatable :: message
        integer :: k

        names = [character(len=name_length) :: "t", "X_2", "Y_2", "Z_2", "psi_2", "theta_2", &
            & "phi_2", "Xdot_2", "Ydot_2", "Zdot_2", "psidot_2", "thetadot_2", "phidot_2", "E", &
            & "basis_2", "req12_theta", "req7_x"]
        call read_layout(names, layout, message, [character(len=name_length) :: "basis_<id>", &
            & request_column_patterns])
        if (allocated(message)) call check(error, .false., "refused: " // message)
        if (allocated(error)) return
        call check(error, layout%column("req12_theta") == 16 .and. layout%column("req7_x") &
            & == 17, "the request columns' places")
        wrong = [character(len=name_length) :: "req_x", "reqx_x", "req12_thetas", "req12_", &
            & "req1234567890_x"]
        do k = 1, size(wrong)
            if (allocated(error)) return
            names(17) = wrong(k)
            call read_layout(names, layout, message, [character(len=name_length) :: &
                & "basis_<id>", request_column_patterns])
            call check(error, allocated(message), trim(wrong(k)) // " read as a request's column")
            if (allocated(message)) deallocate(message)
        end do
    end subroutine test_read_back

    !> Run a dataset written from lines in this process (no files, quiet) and keep its rows.
    subroutine run_rows(name, lines, rows, error)
        character(len=*), intent(in) :: name, lines(:)
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result

        call make_folder(scratch)
        call write_lines(scratch // "/" // name, lines)
        call load_job(scratch // "/" // name, job, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
    end subroutine run_rows

    !> Write text to a file as it is.
    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: unit

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="unformatted")
        write(unit) text
        close(unit)
    end subroutine write_text

    !> Request id's x, y, z ("xyz") or psi, theta, phi ("angles") in row i.
    function request(rows, id, i, which) result(values)
        type(history_type), intent(in) :: rows
        integer, intent(in) :: id, i
        character(len=*), intent(in) :: which
        real(wp) :: values(3)
        integer :: first

        first = rows%layout%column("req" // to_text(id) // "_x")
        if (which == "angles") first = rows%layout%column("req" // to_text(id) // "_psi")
        values = huge(1.0_wp)
        if (first > 0) values = rows%rows(first:first + 2, i)
    end function request

    !> The axes (columns) of 3-1-3 angles.
    pure function axes_of(angles) result(r)
        real(wp), intent(in) :: angles(3)
        real(wp) :: r(3, 3)

        r = rotation_matrix(angles(1), angles(2), angles(3))
    end function axes_of

    !> The turn by angle a about ground Y (columns: the turned axes).
    pure function about_y(a) result(r)
        real(wp), intent(in) :: a
        real(wp) :: r(3, 3)

        r = reshape([cos(a), 0.0_wp, -sin(a), 0.0_wp, 1.0_wp, 0.0_wp, sin(a), 0.0_wp, &
            & cos(a)], [3, 3])
    end function about_y

    !> The turn by angle a about ground X (columns: the turned axes).
    pure function about_x(a) result(r)
        real(wp), intent(in) :: a
        real(wp) :: r(3, 3)

        r = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, cos(a), sin(a), 0.0_wp, -sin(a), &
            & cos(a)], [3, 3])
    end function about_x

    !> "x", "y", "z" for k = 0, 1, 2.
    pure function xyz(k) result(name)
        integer, intent(in) :: k
        character(len=1) :: name

        name = achar(iachar("x") + k)
    end function xyz

end module test_adm_outputs
