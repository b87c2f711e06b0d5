! SPDX-License-Identifier: MIT
!> Work-precision measurements: each way of solving a scene on a ladder of tolerances, against an
!> independent reference (a reduced ODE at a tight tolerance: the disk's for a disk scene, the
!> Whipple bicycle's for the bicycle's dataset), each row with its CPU ratio to the reduced ODE at
!> the same tolerance, measured in the same call.
module rollcon_benchmark
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_lapack, only : factor_dense, solve_factored
    use rollcon_dae, only : dae_size, dae_residual
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_run_settings, only : run_settings_type
    use rollcon_run_keys, only : choice_code
    use rollcon_scene, only : scene_type
    use rollcon_scene_source, only : scene_source_type
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_simulation, only : run_summary_type, history_type, status_completed
    use rollcon_job, only : job_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_output_layout, only : coord_x, coord_z
    use rollcon_reduced_scene, only : simulate_reduced_scene
    use rollcon_reduced_bicycle, only : bicycle_table_type, simulate_reduced_bicycle, &
        & bicycle_distance
    use rollcon_bench_costs, only : part_costs_type
    implicit none
    private

    public :: method_type, benchmark_methods, benchmark_row_type, benchmark_scene, &
        & method_settings
    public :: benchmark_header, write_benchmark_row, evaluation_costs, bench_scene_of, split_costs
    public :: bench_subject_type, bench_subject_of

    !> The scene formulation code the benchmark gives its reduced-ODE runs (not a scene choice)
    integer, parameter :: formulation_reduced = -1

    !> One way of solving: formulation, method, drift control, Jacobian
    type :: method_type
        character(len=40) :: name = ""
        character(len=12) :: formulation = "ida", method = "bdf", drift = "projection"
        character(len=12) :: jacobian = "analytic"
    end type method_type

    !> What the benchmark compares a job with: a disk scene's reduced ODE, or (bicycle) the
    !> Whipple bicycle's of the table the job's dataset is written from
    type :: bench_subject_type
        !> The rows' scene name
        character(len=:), allocatable :: name
        logical :: bicycle = .false.
        !> A disk scene (with the job's settings), or the bicycle's table
        type(scene_type) :: scene
        type(bicycle_table_type) :: table
        !> The job's run settings (end time and output step among them)
        type(run_settings_type) :: settings
    end type bench_subject_type

    !> What one (scene, method, tolerance) measured
    type :: benchmark_row_type
        character(len=40) :: scene = "", method = ""
        real(wp) :: rtol = 0.0_wp
        !> Median CPU time of the repeated runs [s]
        real(wp) :: cpu = 0.0_wp
        integer :: steps = 0, functions = 0, jacobians = 0
        !> Largest distance of the centre from the reference's at the output times [m] (the
        !> bicycle: the largest difference of roll and steer [rad] and of the rear contact [m])
        real(wp) :: position_error = 0.0_wp
        !> Largest constraint residual [m/s] and relative energy drift
        real(wp) :: residual = 0.0_wp, energy_drift = 0.0_wp
        !> Median CPU time of the reduced ODE at the same rtol and multistep method, measured in
        !> the same call [s], and cpu / reduced_cpu
        real(wp) :: reduced_cpu = 0.0_wp, ratio = 0.0_wp
        !> Event-function evaluations and output rows of the run
        integer :: root_evaluations = 0, output_rows = 0
        !> CPU time of the run's right-hand sides (or residuals), event functions, output rows
        !> (counts times unit costs), and SUNDIALS' remainder with Jacobians and solves [s]
        real(wp) :: rhs_cpu = 0.0_wp, roots_cpu = 0.0_wp, output_cpu = 0.0_wp, sundials_cpu = 0.0_wp
        !> User + system CPU time of `rollcon run` of the same setting as a child process [s]:
        !> measured for each method's cheapest run within the headline's accuracy (rollcon
        !> bench), 0 on the other rows
        real(wp) :: process_cpu = 0.0_wp
        !> 'completed', or why not
        character(len=:), allocatable :: status
    end type benchmark_row_type

contains

    !> The methods compared: IDA and CVODE (BDF, Adams), analytic against difference-quotient
    !> Jacobians, Newton against fixed-point iteration for Adams, each drift control of the
    !> ODE form, and the independent speeds. A new way of solving is one more line here (its
    !> formulation a run setting); the reduced ODE's rows are the limit, each row's ratio
    !> against the reduced run of its multistep method and iteration (reduced_partner).
    pure function benchmark_methods() result(methods)
        type(method_type) :: methods(12)

        methods(1) = method_type("ida", "ida", "bdf", "projection", "analytic")
        methods(2) = method_type("ida-dq", "ida", "bdf", "projection", "dq")
        methods(3) = method_type("cvode-bdf-projection", "cvode", "bdf", "projection", "analytic")
        methods(4) = method_type("cvode-bdf-projection-dq", "cvode", "bdf", "projection", "dq")
        methods(5) = method_type("cvode-bdf-baumgarte", "cvode", "bdf", "baumgarte", "analytic")
        methods(6) = method_type("cvode-bdf-none", "cvode", "bdf", "none", "analytic")
        ! CVODE projects only with BDF: Adams is stabilised by Baumgarte's method
        methods(7) = method_type("cvode-adams-baumgarte", "cvode", "adams", "baumgarte", &
            & "analytic")
        ! Adams on a non-stiff problem: fixed-point (functional) iteration, no Jacobian at all
        methods(8) = method_type("cvode-adams-baumgarte-fixed-point", "cvode", "adams", &
            & "baumgarte", "none")
        ! the limit: the disk in minimal coordinates (ucon/reduced/), no constraints to keep
        methods(9) = method_type("reduced-bdf", "reduced", "bdf", "none", "analytic")
        methods(10) = method_type("reduced-adams", "reduced", "adams", "none", "analytic")
        methods(11) = method_type("reduced-adams-fixed-point", "reduced", "adams", "none", &
            & "none")
        ! CVODE on q and the independent speeds (docs/design.md §4): the rolling UCONs hold
        ! exactly; Baumgarte's rate would act on position UCONs alone (the scenes have none)
        methods(12) = method_type("maggi-adams", "maggi", "adams", "baumgarte", "analytic")
    end function benchmark_methods

    !> The reduced runs every row is compared with, one per multistep method and iteration: BDF
    !> (Newton), Adams with Newton, Adams with fixed-point iteration.
    pure function reduced_methods() result(methods)
        type(method_type) :: methods(3)

        methods(1) = method_type("reduced-bdf", "reduced", "bdf", "none", "analytic")
        methods(2) = method_type("reduced-adams", "reduced", "adams", "none", "analytic")
        methods(3) = method_type("reduced-adams-fixed-point", "reduced", "adams", "none", "none")
    end function reduced_methods

    !> Which of reduced_methods a method is compared with: the same multistep method, and
    !> fixed-point iteration when the method iterates so.
    pure integer function reduced_partner(method) result(partner)
        type(method_type), intent(in) :: method

        partner = 1
        if (method%method == "adams") partner = merge(3, 2, method%jacobian == "none")
    end function reduced_partner

    !> Header of the benchmark CSV.
    pure function benchmark_header() result(header)
        character(len=:), allocatable :: header

        header = "scene,method,rtol,cpu_s,steps,function_evaluations,jacobian_evaluations," &
            & // "position_error_m,residual_max,energy_drift,reduced_cpu_s,cpu_ratio_to_reduced," &
            & // "root_evaluations,output_rows,rhs_cpu_s,roots_cpu_s,output_cpu_s,sundials_cpu_s," &
            & // "process_cpu_s,status"
    end function benchmark_header

    !> One CSV line.
    function write_benchmark_row(row) result(line)
        type(benchmark_row_type), intent(in) :: row
        character(len=:), allocatable :: line
        character(len=340) :: numbers

        write(numbers, '(es11.3e3, ",", es13.5e3, 3(",", i0), 5(",", es13.5e3), 2(",", i0), &
            & 5(",", es13.5e3))') row%rtol, row%cpu, row%steps, row%functions, row%jacobians, &
            & row%position_error, row%residual, row%energy_drift, row%reduced_cpu, row%ratio, &
            & row%root_evaluations, row%output_rows, row%rhs_cpu, row%roots_cpu, &
            & row%output_cpu, row%sundials_cpu, row%process_cpu
        line = trim(row%scene) // "," // trim(row%method) // "," // trim(numbers) // "," &
            & // row%status
    end function write_benchmark_row

    !> The disk scene a job runs, with the job's settings (the benchmark's reference is the
    !> disk's reduced ODE: it takes disk scenes only).
    subroutine bench_scene_of(job, scene, error)
        type(job_type), intent(in) :: job
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error

        select type (source => job%source)
        type is (scene_source_type)
            scene = source%scene
            scene%run%run_settings_type = source%settings
        class default
            call fatal_error(error, source%path // ": the benchmark compares with the disk's " &
                & // "reduced ODE and takes disk scenes only, not a " // source%kind, stat_input)
        end select
    end subroutine bench_scene_of

    !> What a job is measured against: with a bicycle's table, the job is that bicycle's
    !> dataset (data/bicycle/write_adm.py's) and the reduced bicycle its reference; else a disk
    !> scene's (bench_scene_of).
    subroutine bench_subject_of(job, subject, error, table)
        type(job_type), intent(in) :: job
        type(bench_subject_type), intent(out) :: subject
        type(error_type), allocatable, intent(out) :: error
        type(bicycle_table_type), intent(in), optional :: table
        integer :: n

        subject%settings = job%source%settings
        if (present(table)) then
            subject%bicycle = .true.
            subject%table = table
            subject%name = job%name
            n = len(subject%name)
            if (n > 4) then
                if (subject%name(n - 3:) == ".adm") subject%name = subject%name(:n - 4)
            end if
            return
        end if
        call bench_scene_of(job, subject%scene, error)
        if (allocated(error)) return
        subject%name = trim(subject%scene%name)
    end subroutine bench_subject_of

    !> Measure every method on every tolerance for one scene's job (load_job); rows are
    !> appended. Every row of the full model is a run of the job (run_job) with the method's
    !> settings. The reduced ODE is run at every tolerance with BDF and Adams whether or not the
    !> methods name it: each row's ratio is its CPU time over the reduced ODE's at the same rtol
    !> and with the same multistep method, both measured here, in this call. With a bicycle's
    !> table (read_bicycle_table) the job is that bicycle's dataset and the reduced ODE the
    !> bicycle's. Long because its two internal procedures (the reference run, one measurement)
    !> share the subject, the job and the progress unit of the host.
    subroutine benchmark_scene(job, methods, tolerances, reference_rtol, repeats, rows, &
            & error, progress, costs, table)
        !> A disk scene's job, or the bicycle's dataset's, as loaded (its own solver settings
        !> are replaced)
        type(job_type), intent(in) :: job
        type(method_type), intent(in) :: methods(:)
        !> Relative tolerances; atol = 1e-2 rtol (positions ~0.1 m, rates ~1 rad/s)
        real(wp), intent(in) :: tolerances(:)
        !> Tolerance of the reference solution (the reduced ODE, Adams)
        real(wp), intent(in) :: reference_rtol
        !> Runs per measurement (CPU median); runs longer than a second are not repeated
        integer, intent(in) :: repeats
        type(benchmark_row_type), allocatable, intent(inout) :: rows(:)
        type(error_type), allocatable, intent(out) :: error
        !> Unit for a line after each measurement (none when absent)
        integer, intent(in), optional :: progress
        !> Unit costs of the parts of a step: when given, rows get the per-part split
        type(part_costs_type), intent(in), optional :: costs
        !> The bicycle's table, when the job is its dataset
        type(bicycle_table_type), intent(in), optional :: table
        type(history_type) :: reference
        type(benchmark_row_type) :: row
        type(benchmark_row_type), allocatable :: reduced(:, :)
        type(bench_subject_type) :: subject
        type(method_type) :: limits(size(reduced_methods()))
        integer :: m, k, v, partner

        if (.not. allocated(rows)) allocate(rows(0))
        call bench_subject_of(job, subject, error, table)
        if (allocated(error)) return
        call reference_run(reference, error)
        if (allocated(error)) return
        ! reduced(k, v): reduced_methods()(v) at tolerances(k)
        limits = reduced_methods()
        allocate(reduced(size(tolerances), size(limits)))
        do k = 1, size(tolerances)
            do v = 1, size(limits)
                reduced(k, v) = measure(limits(v), tolerances(k), reference, repeats)
            end do
        end do
        do m = 1, size(methods)
            partner = reduced_partner(methods(m))
            do k = 1, size(tolerances)
                if (methods(m)%formulation == "reduced") then
                    row = reduced(k, partner)
                    row%method = methods(m)%name
                else
                    row = measure(methods(m), tolerances(k), reference, repeats)
                end if
                row%reduced_cpu = reduced(k, partner)%cpu
                row%ratio = row%cpu/max(row%reduced_cpu, tiny(1.0_wp))
                if (present(costs) .and. methods(m)%formulation /= "reduced") &
                    & call split_costs(row, costs, trim(methods(m)%formulation))
                rows = [rows, row]
                if (present(progress)) then
                    write(progress, '(a)') "bench: " // write_benchmark_row(row)
                    flush(progress)
                end if
            end do
        end do

    contains

        !> The reduced ODE by CVODE Adams at reference_rtol (loosened tenfold at most twice if
        !> it fails): at such tolerances Adams' high orders beat BDF's order 5. The distance of
        !> a BDF solution at the same rtol from it is reported as the reference's uncertainty,
        !> with that run's CPU time: the cost of BDF, the method IDA has, at the accuracy of the
        !> headline when the ladder's tightest rtol leaves BDF short of it (one run, not a median).
        subroutine reference_run(kept, run_error)
            type(history_type), intent(out) :: kept
            type(error_type), allocatable, intent(out) :: run_error
            type(run_summary_type) :: summary
            type(history_type) :: check_run
            integer :: attempt
            real(wp) :: rtol

            do attempt = 0, 2
                rtol = reference_rtol*10.0_wp**attempt
                call run_reduced(subject, method_type("reference", "reduced", "adams", "none", &
                    & "analytic"), rtol, kept, summary, run_error)
                if (allocated(run_error)) cycle
                call run_reduced(subject, method_type("reference", "reduced", "bdf", "none", &
                    & "analytic"), rtol, check_run, summary, run_error)
                if (allocated(run_error)) cycle
                if (present(progress)) write(progress, '(a, es10.2e3, a, es10.2e3, a)') "bench: " &
                    & // subject%name // ": reference by the reduced ODE (CVODE Adams) at " &
                    & // "rtol " // to_text(rtol) // "; BDF at that rtol differs by", &
                    & subject_distance(subject, check_run, kept), " " // error_unit(subject) &
                    & // " in", summary%cpu_seconds, " s of CPU"
                return
            end do
            run_error%message = "reference solution by the reduced ODE failed: " &
                & // run_error%message
        end subroutine reference_run

        !> One row: median CPU of up to repeats runs, statistics and errors of the last.
        function measure(method, rtol, reference, repeats) result(measured)
            type(method_type), intent(in) :: method
            real(wp), intent(in) :: rtol
            type(history_type), intent(in) :: reference
            integer, intent(in) :: repeats
            type(benchmark_row_type) :: measured
            type(history_type) :: history
            type(run_summary_type) :: summary
            type(error_type), allocatable :: run_error
            real(wp), allocatable :: times(:)
            integer :: r, roots

            measured%scene = subject%name
            measured%method = method%name
            measured%rtol = rtol
            allocate(times(0))
            roots = 0
            do r = 1, max(1, repeats)
                call run_case(job, subject, method, rtol, history, summary, roots, run_error)
                if (allocated(run_error)) then
                    ! a failed run is a measurement too: recorded, not fatal
                    measured%status = "failed: " // run_error%message
                    exit
                end if
                times = [times, summary%cpu_seconds]
                if (summary%cpu_seconds > 1.0_wp) exit
            end do
            if (size(times) > 0) then
                measured%cpu = median(times)
                measured%status = "completed"
                if (summary%status /= status_completed) measured%status = "stopped: " &
                    & // summary%message
            else
                measured%cpu = summary%cpu_seconds
            end if
            measured%steps = summary%steps
            measured%functions = summary%functions
            measured%jacobians = summary%jacobians
            measured%root_evaluations = roots
            measured%output_rows = summary%rows
            measured%residual = summary%residual_max
            measured%energy_drift = summary%energy_drift
            measured%position_error = subject_distance(subject, history, reference)
        end function measure

    end subroutine benchmark_scene

    !> The unit of a subject's errors: m (a disk's centre), or rad and m (the bicycle's roll
    !> and steer, its rear contact).
    pure function error_unit(subject) result(unit)
        type(bench_subject_type), intent(in) :: subject
        character(len=:), allocatable :: unit

        unit = "m"
        if (subject%bicycle) unit = "(rad, m)"
    end function error_unit

    !> How far a run is from the reference: the disk's centres' largest distance [m], or the
    !> bicycle's largest difference (bicycle_distance).
    function subject_distance(subject, run, reference) result(distance)
        type(bench_subject_type), intent(in) :: subject
        type(history_type), intent(in) :: run, reference
        real(wp) :: distance

        if (subject%bicycle) then
            distance = bicycle_distance(run, reference, subject%table%par(3), &
                & subject%table%par(5))
        else
            distance = position_error(run, reference)
        end if
    end function subject_distance

    !> The subject's reduced ODE with a method at rtol. The bicycle's has no analytic
    !> Jacobian: its Newton runs take CVODE's difference quotients.
    subroutine run_reduced(subject, method, rtol, history, summary, error)
        type(bench_subject_type), intent(in) :: subject
        type(method_type), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(history_type), intent(out) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type) :: settings
        type(method_type) :: chosen

        if (subject%bicycle) then
            chosen = method
            if (chosen%jacobian == "analytic") chosen%jacobian = "dq"
            settings = settings_with_method(subject%settings, chosen, rtol)
            call simulate_reduced_bicycle(subject%table, settings, settings%end_time, &
                & settings%output_step, history, summary, error)
        else
            call simulate_reduced_scene(with_method(subject%scene, method, rtol), history, &
                & summary, error)
        end if
    end subroutine run_reduced

    !> One run of a case: the job with the method's settings at rtol (run_job, no files) or
    !> the subject's reduced ODE; roots: the event-function evaluations of a full run (0 for
    !> the reduced ODE).
    subroutine run_case(job, subject, method, rtol, history, summary, roots, error)
        type(job_type), intent(in) :: job
        type(bench_subject_type), intent(in) :: subject
        type(method_type), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(history_type), intent(out) :: history
        type(run_summary_type), intent(out) :: summary
        integer, intent(out) :: roots
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: row_job
        type(job_result_type) :: ran

        roots = 0
        if (method%formulation == "reduced") then
            call run_reduced(subject, method, rtol, history, summary, error)
            return
        end if
        row_job = job
        row_job%output_dir = ""
        row_job%quiet = .true.
        row_job%source%settings = settings_with_method(subject%settings, method, rtol)
        call run_job(row_job, ran, error, history)
        summary = ran%summary
        roots = summary%root_evaluations
    end subroutine run_case

    !> A full-model row's CPU time split by parts: counts times unit costs, SUNDIALS the rest.
    !> The event functions cost what they cost as the row's integrator calls them: given the
    !> multipliers (IDA), given the accelerations (CVODE's ODE form; the interpolation that
    !> gives them is in SUNDIALS' remainder), alone (independent speeds).
    pure subroutine split_costs(row, costs, formulation)
        type(benchmark_row_type), intent(inout) :: row
        type(part_costs_type), intent(in) :: costs
        !> The method's formulation: "ida" (its functions are DAE residuals), "cvode", "maggi"
        character(len=*), intent(in) :: formulation
        logical :: dae

        dae = formulation == "ida"
        row%rhs_cpu = row%functions*merge(costs%residual, costs%rhs, dae)
        if (formulation == "maggi") row%rhs_cpu = row%functions*costs%rhs_speeds
        select case (formulation)
        case ("ida")
            row%roots_cpu = row%root_evaluations*costs%root_given_multipliers
        case ("cvode")
            row%roots_cpu = row%root_evaluations*costs%root_given_rates
        case default
            row%roots_cpu = row%root_evaluations*costs%root
        end select
        row%output_cpu = row%output_rows*costs%output
        row%sundials_cpu = row%cpu - row%rhs_cpu - row%roots_cpu - row%output_cpu
    end subroutine split_costs

    !> CPU seconds of one ODE right-hand side, one DAE residual, and one LAPACK factor-and-solve
    !> of the saddle-point system's size (the floor of a right-hand side), each the mean of
    !> count calls at the job's start, measured in the same run.
    subroutine evaluation_costs(job, count, rhs_seconds, residual_seconds, solve_seconds, error)
        type(job_type), intent(inout) :: job
        integer, intent(in) :: count
        real(wp), intent(out) :: rhs_seconds, residual_seconds, solve_seconds
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        procedure(ucosub_interface), pointer :: routine
        real(wp) :: start, finish, checksum
        real(wp), allocatable :: q0(:), u0(:)
        real(wp), allocatable :: y(:), ydot(:), yd(:), ypd(:), r(:), matrix(:, :), lu(:, :), b(:, :)
        character(len=:), allocatable :: report
        integer, allocatable :: pivots(:)
        integer :: i, ierr, n, j

        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        call ode%init(problem)
        y = [q0, u0]
        allocate(ydot(size(y)))
        ierr = ode%ode_rhs(0.0_wp, y, ydot)
        checksum = 0.0_wp
        call cpu_time(start)
        do i = 1, count
            ierr = ode%ode_rhs(0.0_wp, y, ydot)
            checksum = checksum + ydot(size(q0) + 1)
        end do
        call cpu_time(finish)
        rhs_seconds = (finish - start)/count
        ! the same saddle-point matrix, factored and solved alone
        n = problem%eq%n + problem%eq%nc
        allocate(matrix(n, n))
        call problem%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        matrix(:problem%eq%n, :problem%eq%n) = 0.0_wp
        do j = 1, problem%eq%n/6
            matrix(6*j - 5:6*j, 6*j - 5:6*j) = problem%eq%mass(:, :, j)
        end do
        ! -C^T and C (C held by rows over each UCON's coordinates; the others zero)
        matrix(:problem%eq%n, problem%eq%n + 1:) = 0.0_wp
        matrix(problem%eq%n + 1:, :) = 0.0_wp
        do i = 1, problem%eq%nc
            do j = problem%eq%c%start(i), problem%eq%c%start(i + 1) - 1
                matrix(problem%eq%c%column(j), problem%eq%n + i) = -problem%eq%c%value(j)
                matrix(problem%eq%n + i, problem%eq%c%column(j)) = problem%eq%c%value(j)
            end do
        end do
        allocate(lu(n, n), b(n, 1), pivots(n))
        call cpu_time(start)
        do i = 1, count
            lu = matrix
            b(:, 1) = 1.0_wp
            call factor_dense(lu, pivots, error)
            if (allocated(error)) return
            call solve_factored(lu, pivots, b, error)
            if (allocated(error)) return
            checksum = checksum + b(1, 1)
        end do
        call cpu_time(finish)
        solve_seconds = (finish - start)/count
        allocate(yd(dae_size(problem%eq)), ypd(dae_size(problem%eq)), r(dae_size(problem%eq)), &
            & source=0.0_wp)
        yd(:size(y)) = y
        ypd(:size(y)) = ydot
        call cpu_time(start)
        do i = 1, count
            call dae_residual(problem%eq, 0.0_wp, yd, ypd, r, error)
            if (allocated(error)) return
            checksum = checksum + r(1)
        end do
        call cpu_time(finish)
        residual_seconds = (finish - start)/count
        ! keep the loops from being optimised away
        if (checksum /= checksum) rhs_seconds = -1.0_wp
    end subroutine evaluation_costs

    !> The run settings a row of method at rtol ran with, for a job (what a `rollcon run` of
    !> the same setting needs: rollcon_bench_process).
    function method_settings(job, method, rtol) result(settings)
        type(job_type), intent(in) :: job
        type(method_type), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(run_settings_type) :: settings

        settings = settings_with_method(job%source%settings, method, rtol)
    end function method_settings

    !> Run settings with a method and tolerance in place of their own (atol = 1e-2 rtol).
    function settings_with_method(settings, method, rtol) result(changed)
        type(run_settings_type), intent(in) :: settings
        type(method_type), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(run_settings_type) :: changed

        changed = settings
        changed%formulation = formulation_reduced
        if (method%formulation /= "reduced") &
            & changed%formulation = choice_code("formulation", method%formulation)
        changed%method = choice_code("method", method%method)
        changed%drift = choice_code("drift", method%drift)
        changed%jacobian = choice_code("jacobian", method%jacobian)
        changed%rtol = rtol
        changed%atol = 1.0e-2_wp*rtol
        changed%max_steps = 10000000
    end function settings_with_method

    !> The scene with a method and tolerance in place of its own.
    function with_method(scene, method, rtol) result(changed)
        type(scene_type), intent(in) :: scene
        type(method_type), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(scene_type) :: changed

        changed = scene
        changed%run%run_settings_type = settings_with_method(scene%run%run_settings_type, &
            & method, rtol)
    end function with_method

    !> Largest distance between the centres of the first part at the output times both runs
    !> reached [m].
    pure function position_error(run, reference) result(distance)
        type(history_type), intent(in) :: run, reference
        real(wp) :: distance
        integer :: i, n

        n = min(run%count, reference%count)
        distance = 0.0_wp
        associate (a => run%layout, b => reference%layout)
            do i = 1, n
                ! column 1 is the time in every layout
                if (abs(run%rows(1, i) - reference%rows(1, i)) > 1.0e-9_wp) exit
                distance = max(distance, norm2(run%rows(a%part_column(1, coord_x) &
                    & :a%part_column(1, coord_z), i) - reference%rows(b%part_column(1, coord_x) &
                    & :b%part_column(1, coord_z), i)))
            end do
        end associate
    end function position_error

    !> Median of a few values.
    pure function median(values) result(middle)
        real(wp), intent(in) :: values(:)
        real(wp) :: middle
        real(wp) :: sorted(size(values)), swap
        integer :: i, j

        sorted = values
        do i = 2, size(sorted)
            do j = i, 2, -1
                if (sorted(j - 1) <= sorted(j)) exit
                swap = sorted(j)
                sorted(j) = sorted(j - 1)
                sorted(j - 1) = swap
            end do
        end do
        middle = sorted((size(sorted) + 1)/2)
        if (mod(size(sorted), 2) == 0) middle = 0.5_wp*(middle + sorted(size(sorted)/2 + 1))
    end function median

end module rollcon_benchmark
