! SPDX-License-Identifier: MIT
!> The driver knows no disk: a model of two independent parts (a rolling disk, part 2, served
!> by three UCONs, and a free body, part 5, falling with a spin) run with CVODE and IDA, its
!> rows read through the output layout against the analytic motions; the CSV is the history;
!> the theta limit on every part, named by its id; the lift-off watched only with a contact;
!> the summary text for any model; read_layout on good and bad headers; the model built in
!> code run as a job, as the library's users run it.
module test_layout
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, formulation_ida
    use rollcon_model, only : model_type
    use rollcon_built_model, only : built_model_source_type, new_model_source
    use rollcon_job, only : job_type, new_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & status_completed, status_stopped
    use rollcon_output_layout, only : output_layout_type, new_output_layout, read_layout, &
        & name_length, time_column, coord_x, coord_y, coord_z, coord_psi, coord_theta, &
        & coord_phi, coord_xdot, coord_zdot, coord_phidot
    use rollcon_summary_text, only : run_summary_text
    use rollcon_theta_watch, only : new_theta_watch
    use rollcon_contact_watch, only : contact_watch_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use layout_models, only : two_part_model, two_part_problem, disk_id, free_id, disk_radius, &
        & disk_speed, free_spin, free_start, free_velocity, gravity, read_csv, failing_disk_ucosub
    use layout_headers, only : test_good_headers, test_bad_headers
    use rollcon_load, only : load_job
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_output_rows, only : output_layout
    use rollcon_output_layout, only : name_length
    use dataset_texts, only : write_text, texts_dir
    implicit none
    private

    public :: collect_layout

    !> Relative and absolute tolerances of the two-part runs
    real(wp), parameter :: rtol = 1.0e-10_wp, atol = 1.0e-12_wp
    !> Motion against the analytic one over 1 s: local errors of rtol add up over the steps,
    !> 1e3 rtol as the motion suite allows CVODE against IDA
    real(wp), parameter :: tol_motion = 1.0e3_wp*rtol
    !> Multipliers [N] from the saddle-point solve at states within tol_motion: m g to 1e-6
    real(wp), parameter :: tol_force = 1.0e-6_wp
    !> A CSV value is written with 17 significant digits: it reads back to 1e-15 relative
    real(wp), parameter :: tol_printed = 1.0e-15_wp

contains

    subroutine collect_layout(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("two-parts-cvode", test_two_parts_cvode), &
            & new_unittest("two-parts-ida", test_two_parts_ida), &
            & new_unittest("theta-limit-names-the-part", test_theta_limit_part), &
            & new_unittest("liftoff-only-with-contact", test_liftoff_only_with_contact), &
            & new_unittest("contact-part-checked", test_contact_checked), &
            & new_unittest("failures-name-the-ucon", test_failures_name_ucon), &
            & new_unittest("summary-text-any-model", test_summary_text), &
            & new_unittest("read-layout-good-headers", test_good_headers), &
            & new_unittest("read-layout-bad-headers", test_bad_headers), &
            & new_unittest("model-built-in-code-runs-as-a-job", test_model_source), &
            & new_unittest("problem-prepared-twice-same-columns", test_prepared_twice)]
    end subroutine collect_layout

    subroutine test_two_parts_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_two_parts(formulation_cvode, "build/test_layout_cvode.csv", error)
    end subroutine test_two_parts_cvode

    subroutine test_two_parts_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_two_parts(formulation_ida, "build/test_layout_ida.csv", error)
    end subroutine test_two_parts_ida

    !> Both parts over 1 s, read through the layout: the disk rolls straight and upright at
    !> its speed, carried by its weight (lambda_13 = m g, the others 0); the free body falls
    !> (X = X0 + vx t, Z = Z0 + vz t - g t^2/2) spinning about its principal z-axis
    !> (phi = w t, psi and theta fixed); energy is conserved; the summary's largest residual of
    !> each UCON is that of its column; the CSV holds the history's rows under its header.
    subroutine check_two_parts(formulation, csv_path, error)
        integer, intent(in) :: formulation
        character(len=*), intent(in) :: csv_path
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(history_type) :: history, csv
        type(output_layout_type) :: layout
        real(wp), allocatable :: q0(:), u0(:), t(:)
        real(wp) :: disk(12), free(12), expected(12), weight
        character(len=name_length), allocatable :: names(:)
        integer :: i, k

        call two_part_problem(problem, q0, u0, error)
        if (allocated(error)) return
        problem%settings%formulation = formulation
        problem%settings%rtol = rtol
        problem%settings%atol = atol
        options%end_time = 1.0_wp
        options%output_step = 0.05_wp
        options%progress = .false.
        options%csv_path = csv_path
        call simulate(problem, q0, u0, options, summary, error, history)
        if (allocated(error)) return
        call check(error, summary%status == status_completed, "status " &
            & // to_text(summary%status) // ": " // summary%message)
        if (allocated(error)) return
        layout = history%layout
        names = layout%header()
        ! then the three UCONs' reactions, six columns each (rollcon_reaction_watch)
        call check(error, size(names) == 50 .and. names(layout%part_column(1, coord_x)) == "X_2" &
            & .and. names(layout%part_column(2, coord_phidot)) == "phidot_5" &
            & .and. names(26) == "E" .and. names(27) == "F_11" .and. names(32) == "lambda_13" &
            & .and. names(33) == "ucon11_fx" .and. names(50) == "ucon13_tz" &
            & .and. layout%column("Fn") == 0, &
            & "layout: " // to_text(size(names)) // " columns, " // trim(names(2)) // " ... " &
            & // trim(names(size(names))))
        if (allocated(error)) return
        weight = problem%model%parts(1)%mass*gravity
        t = history%column(time_column)
        do i = 1, history%count
            disk = history%part_state(1, i)
            free = history%part_state(2, i)
            expected = [disk_speed*t(i), 0.0_wp, disk_radius, 0.0_wp, 0.5_wp*pi, &
                & -disk_speed/disk_radius*t(i), disk_speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
                & -disk_speed/disk_radius]
            call check(error, disk, expected, "part " // to_text(disk_id) // " at t = " &
                & // to_text(t(i)), abs_tol=tol_motion)
            if (allocated(error)) return
            expected = [free_start(1:3) + free_velocity*t(i) &
                & - [0.0_wp, 0.0_wp, 0.5_wp*gravity*t(i)**2], free_start(4:5), &
                & free_start(6) + free_spin*t(i), free_velocity - [0.0_wp, 0.0_wp, gravity*t(i)], &
                & 0.0_wp, 0.0_wp, free_spin]
            call check(error, free, expected, "part " // to_text(free_id) // " at t = " &
                & // to_text(t(i)), abs_tol=tol_motion)
            if (allocated(error)) return
            call check(error, history%rows(layout%multiplier_column(1) &
                & :layout%multiplier_column(3), i), [0.0_wp, 0.0_wp, weight], &
                & "lambda_11..13 [N] at t = " // to_text(t(i)), abs_tol=tol_force)
            if (allocated(error)) return
            ! the contact's height row carries the weight, up, at the disk's centre (its
            ! dF/dZdot is 1): (0, 0, m g), no moment about the centre
            call check(error, history%rows(layout%column("ucon13_fx"):layout%column("ucon13_tz"), &
                & i), [0.0_wp, 0.0_wp, weight, 0.0_wp, 0.0_wp, 0.0_wp], "UCON/13's reaction " &
                & // "[N, N m] at t = " // to_text(t(i)), abs_tol=tol_force)
            if (allocated(error)) return
        end do
        call check(error, history%column(layout%energy_column()), &
            & spread(history%rows(layout%energy_column(), 1), 1, history%count), "E [J]", &
            & abs_tol=tol_motion)
        if (allocated(error)) return
        do k = 1, 3
            call check(error, summary%ucon_residual_max(k) == maxval(abs(history%column( &
                & layout%residual_column(k)))), "summary's largest |F_" &
                & // to_text(layout%ucon_ids(k)) // "| is not its column's")
            if (allocated(error)) return
        end do
        call read_csv(csv_path, names, csv, error)
        if (allocated(error)) return
        call check(error, all(names == layout%header()) .and. csv%count == history%count, &
            & csv_path // ": header or row count differs from the history")
        if (allocated(error)) return
        do i = 1, history%count
            call check(error, csv%rows(:, i), history%rows(:, i), csv_path // " row " &
                & // to_text(i) // " against the history", rel_tol=tol_printed)
            if (allocated(error)) return
        end do
    end subroutine check_two_parts

    !> A free part turning about its principal x-axis at 1 rad/s from theta = 0.5 rad (or from
    !> pi - 0.5) reaches the limit 0.1 rad from flat at t = 0.4 s; the run stops there, and the
    !> message names the part (the second of the model: its own event function) and the side.
    subroutine test_theta_limit_part(error)
        type(error_type), allocatable, intent(out) :: error

        call check_theta_side(1, "part 5: theta fell to the limit theta_min = 0.1 rad at t = ", &
            & "nearly along ground +Z (theta = 0)", error)
        if (allocated(error)) return
        call check_theta_side(2, "part 5: theta rose to pi - theta_min = ", &
            & "nearly along ground -Z (theta = pi)", error)
    end subroutine test_theta_limit_part

    !> The theta limit of the free part on one side (1: theta = 0, 2: theta = pi): the
    !> message starts with start and says side_words.
    subroutine check_theta_side(side, start, side_words, error)
        integer, intent(in) :: side
        character(len=*), intent(in) :: start, side_words
        type(error_type), allocatable, intent(out) :: error
        !> The root is located to the solver's tolerance
        real(wp), parameter :: tol_root = 1.0e-6_wp
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        real(wp), allocatable :: q0(:), u0(:)

        call two_part_problem(problem, q0, u0, error)
        if (allocated(error)) return
        problem%watches(1)%watch = new_theta_watch(0.1_wp, rebase=.false.)
        q0(6 + coord_theta) = merge(0.5_wp, pi - 0.5_wp, side == 1)
        u0(7:12) = [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, merge(-1.0_wp, 1.0_wp, side == 1), 0.0_wp]
        options%end_time = 1.0_wp
        options%output_step = 0.1_wp
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error)
        if (allocated(error)) return
        call check(error, summary%status == status_stopped .and. &
            & index(summary%message, start) == 1 .and. &
            & index(summary%message, side_words) > 0, "message: " // summary%message)
        if (allocated(error)) return
        call check(error, summary%t_reached, 0.4_wp, "time of the limit [s]", abs_tol=tol_root)
    end subroutine check_theta_side

    !> A model without a contact watch has one event function per part (its theta watch), none
    !> for the lift-off; a rim contact that stops on lift-off adds one, after them.
    subroutine test_liftoff_only_with_contact(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(contact_watch_type) :: contact
        real(wp), allocatable :: q0(:), u0(:)
        integer :: watch, k

        call two_part_problem(problem, q0, u0, error)
        if (allocated(error)) return
        call check(error, problem%root_count(), 2, "event functions without a contact")
        if (allocated(error)) return
        contact%radius = disk_radius
        contact%stop_on_liftoff = .true.
        call problem%add_watch(contact)
        call check(error, problem%root_count(), 3, "event functions with the disk's contact")
        if (allocated(error)) return
        call problem%root_owner(2, watch, k)
        call check(error, watch == 1 .and. k == 2, "event 2 is the theta watch's second part")
        if (allocated(error)) return
        call problem%root_owner(3, watch, k)
        call check(error, watch == 2 .and. k == 1, "event 3 is the contact's lift-off")
    end subroutine test_liftoff_only_with_contact

    !> A watched contact must name one of the model's parts and a rim radius.
    subroutine test_contact_checked(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(contact_watch_type) :: contact
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(error_type), allocatable :: failure
        real(wp), allocatable :: q0(:), u0(:)

        call two_part_problem(problem, q0, u0, error)
        if (allocated(error)) return
        options%progress = .false.
        contact%part = 3
        contact%radius = disk_radius
        call problem%add_watch(contact)
        call simulate(problem, q0, u0, options, summary, failure)
        call check(error, allocated(failure), "a contact on part number 3 of 2 was accepted")
        if (allocated(error)) return
        call check(error, failure%message == "the part in contact is number 3 in model " &
            & // "order; the model has 2 parts", "message: " // failure%message)
        if (allocated(error)) return
        contact%part = 1
        contact%radius = 0.0_wp
        problem%watches(2)%watch = contact
        call simulate(problem, q0, u0, options, summary, failure)
        call check(error, allocated(failure), "a contact without a radius was accepted")
        if (allocated(error)) return
        call check(error, failure%message == "the contact of part 2 needs a rim radius > 0 " &
            & // "[m], got 0", "message: " // failure%message)
    end subroutine test_contact_checked

    !> In the two-part model, a UCON whose PAR names a part the model lacks is refused at
    !> set-up, and a UCOSUB returning NaN during the run fails it: both messages name the UCON.
    subroutine test_failures_name_ucon(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: refused, failing
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(error_type), allocatable :: failure
        real(wp), allocatable :: q0(:), u0(:)

        call two_part_problem(refused, q0, u0, failure, ucon_parts=[disk_id, 9, disk_id])
        call check(error, allocated(failure), "a UCON on the missing part 9 was accepted")
        if (allocated(error)) return
        call check(error, index(failure%message, "UCON/12: UCOVAR variable 1 (") == 1 .and. &
            & index(failure%message, "belongs to part 9, which the model does not have") > 0, &
            & "message: " // failure%message)
        if (allocated(error)) return
        call two_part_problem(failing, q0, u0, error, ucosub=failing_disk_ucosub)
        if (allocated(error)) return
        options%end_time = 1.0_wp
        options%progress = .false.
        call simulate(failing, q0, u0, options, summary, failure)
        call check(error, allocated(failure), "a UCOSUB returning NaN did not fail the run")
        if (allocated(error)) return
        call check(error, index(failure%message, "UCON/13: UCOSUB returned a non-finite value") &
            & > 0, "message: " // failure%message)
    end subroutine test_failures_name_ucon

    !> The summary names every part and UCON, and prints the height residual only with a
    !> contact, with its bound, and "none" for a model without UCONs; a measure without a bound
    !> (a study's, such as a contact's switches) is not among its lines.
    subroutine test_summary_text(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary
        character(len=:), allocatable :: text
        integer :: k

        summary%layout = new_output_layout([2, 5], [11, 12, 13])
        summary%q = [(real(k, wp), k = 1, 12)]
        summary%u = -summary%q
        summary%ucon_residual_max = [1.0e-9_wp, 2.0e-9_wp, 3.0e-12_wp]
        summary%ucon_position = [.false., .false., .true.]
        summary%residual_max = 2.0e-9_wp
        text = run_summary_text("model two (built in the test)", "out.csv", summary)
        call check(error, index(text, "model two (built in the test)" // new_line("a") &
            & // "status: completed at t = 0 s") == 1 &
            & .and. index(text, "final state of part 2:") > 0 &
            & .and. index(text, "final state of part 5:") > index(text, "final state of part 2:") &
            & .and. index(text, "  psi [rad]        1.000000000000000E+001    psidot [rad/s]  " &
            & // "-1.000000000000000E+001") > index(text, "final state of part 5:") &
            & .and. index(text, "  UCON 12: 2.000E-009 (velocity level)") > 0 &
            & .and. index(text, "  UCON 13: 3.000E-012 (position level)") > 0 &
            & .and. index(text, "height residual") == 0, "summary: " // text)
        if (allocated(error)) return
        allocate(summary%measures(2))
        summary%measures(1)%name = "height_residual"
        summary%measures(1)%label = "largest height residual |Z - R sin(theta)|"
        summary%measures(1)%unit = "m"
        summary%measures(1)%value = 4.0e-9_wp
        summary%measures(1)%bound = 2.0e-7_wp
        summary%measures(2)%name = "switches"
        summary%measures(2)%label = "contact mode switches"
        summary%measures(2)%unit = ""
        summary%measures(2)%value = 3.0_wp
        summary%layout%ucon_ids = [integer ::]
        summary%ucon_residual_max = [real(wp) ::]
        text = run_summary_text("scene", "out.csv", summary)
        call check(error, index(text, "largest height residual |Z - R sin(theta)|: 4.000E-009 m" &
            & // ", allowed 2.000E-007 m") > 0 .and. index(text, "largest constraint residual: " &
            & // "none (the model has no UCON)") > 0 .and. index(text, "contact mode switches") &
            & == 0, "summary: " // text)
    end subroutine test_summary_text

    !> The two-part model as a job's source (new_model_source, with the theta watch added),
    !> run by run_job on CVODE, gives the rows of the same model simulated directly, bit for
    !> bit: the source hands over the model, its start and its settings unchanged (the
    !> default settings, IDA, would give other rows).
    subroutine test_model_source(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(problem_type), target :: problem
        type(run_settings_type) :: settings
        type(built_model_source_type) :: source
        type(job_type) :: job
        type(job_result_type) :: result
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(history_type) :: rows, direct
        real(wp), allocatable :: q0(:), u0(:)

        settings%formulation = formulation_cvode
        settings%rtol = rtol
        settings%atol = atol
        settings%end_time = 1.0_wp
        settings%output_step = 0.05_wp
        call two_part_model(model, q0, u0, error)
        if (allocated(error)) return
        source = new_model_source("two_parts", model, q0, u0, settings)
        call source%add_watch(new_theta_watch(0.05_wp, rebase=.false.))
        job = new_job(source)
        call run_job(job, result, error, rows)
        if (allocated(error)) return
        call check(error, result%started .and. result%summary%status == status_completed, &
            & "the job ran: " // to_text(result%summary%status))
        if (allocated(error)) return

        call two_part_problem(problem, q0, u0, error)
        if (allocated(error)) return
        problem%settings = settings
        options%end_time = settings%end_time
        options%output_step = settings%output_step
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error, direct)
        if (allocated(error)) return
        call check(error, rows%count == direct%count .and. rows%count == 21, &
            & "rows: " // to_text(rows%count) // " as a job, " // to_text(direct%count) &
            & // " directly")
        if (allocated(error)) return
        call check(error, all(rows%layout%header() == direct%layout%header()), "the header")
        if (allocated(error)) return
        call check(error, all(rows%rows(:, :rows%count) == direct%rows(:, :direct%count)), &
            & "the rows, bit for bit")
        if (allocated(error)) return
        call check(error, result%summary%steps == summary%steps, "the steps")
    end subroutine test_model_source

    !> A problem prepared a second time (rollcon bench prepares one problem for the ODE form,
    !> then again for the independent speeds) starts its watches again: the same columns, no
    !> error. A model with every kind of watch that lists what it finds at prepare: reaction
    !> sites (two JOINTs and a MOTION), a MOTION, a REQUEST, an SFORCE switched on a speed.
    !> Before the fix the second prepare stopped the program (a runtime error: an array
    !> allocated twice), which fails this suite.
    subroutine test_prepared_twice(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: nl = new_line("a")
        character(len=*), parameter :: text = "prepared twice" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1, QP = 0, 0, 0" // nl // "PART/2, MASS = 2, CM = 22, " &
            & // "IP = 0.1, 0.1, 0.1, QG = 0, 0, 0, WZ = 1.5" // nl &
            & // "MARKER/20, PART = 2, QP = 0, 0, 0" // nl &
            & // "MARKER/22, PART = 2, QP = 0.8660254037844386, -0.5, 0" // nl &
            & // "PART/3, MASS = 1, CM = 30, IP = 0.1, 0.1, 0.1, QG = 2, 0, 0" // nl &
            & // "MARKER/30, PART = 3, QP = 2, 0, 0" // nl // "MARKER/31, PART = 1, QP = 2, 0, 0" &
            & // nl // "JOINT/1, REVOLUTE, I = 20, J = 10" // nl &
            & // "JOINT/2, REVOLUTE, I = 30, J = 31" // nl &
            & // "MOTION/7, JOINT = 1, ROTATION, FUNCTION = 1.5*TIME + 0.5*TIME**2" // nl &
            & // "SFORCE/3, ROTATION, I = 30, J = 31, FUNCTION = IF(WZ(30) - 0.5: 0, 0, -0.1)" &
            & // nl // "ACCGRAV/JGRAV = -9.81" // nl &
            & // "REQUEST/6, F2 = TZ(20, 10), F3 = MOTION(7, 0, 8, 0)" // nl &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 10" // nl // "END"
        type(job_type) :: job
        type(problem_type) :: problem
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report
        character(len=name_length), allocatable :: first(:), second(:)
        type(output_layout_type) :: layout

        call write_text("prepared_twice.adm", text)
        call load_job(texts_dir // "/prepared_twice.adm", job, error)
        if (allocated(error)) return
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        layout = output_layout(problem)
        first = layout%header()
        call problem%prepare(error)
        if (allocated(error)) return
        layout = output_layout(problem)
        second = layout%header()
        ! the reactions of both joints and of the MOTION, and the REQUEST's two columns
        call check(error, any(first == "joint2_tz") .and. any(first == "motion7_tz") &
            & .and. any(first == "req6_f3"), "the columns of every watch, " &
            & // to_text(size(first)) // " columns")
        if (allocated(error)) return
        call check(error, size(second) == size(first), "as many columns after a second " &
            & // "prepare: " // to_text(size(second)) // " against " // to_text(size(first)))
        if (allocated(error)) return
        call check(error, all(second == first), "the same columns after a second prepare")
    end subroutine test_prepared_twice

end module test_layout
