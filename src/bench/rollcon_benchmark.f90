! SPDX-License-Identifier: MIT
!> Work-precision measurements: each way of solving a scene on a ladder of tolerances, against a
!> tight-tolerance solution of the same scene computed by the other formulation.
module rollcon_benchmark
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_lapack, only : factor_dense, solve_factored
    use rollcon_dae, only : dae_size, dae_residual
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_scene, only : scene_type, choice_code
    use rollcon_disk_scene, only : build_disk_problem, simulate_scene
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_summary_type, history_type, status_completed, column_time, &
        & column_x, column_z
    implicit none
    private

    public :: method_type, benchmark_methods, benchmark_row_type, benchmark_scene
    public :: benchmark_header, write_benchmark_row, evaluation_costs

    !> One way of solving: formulation, method, drift control, Jacobian
    type :: method_type
        character(len=32) :: name = ""
        character(len=12) :: formulation = "ida", method = "bdf", drift = "projection"
        character(len=12) :: jacobian = "analytic"
    end type method_type

    !> What one (scene, method, tolerance) measured
    type :: benchmark_row_type
        character(len=32) :: scene = "", method = ""
        real(wp) :: rtol = 0.0_wp
        !> Median CPU time of the repeated runs [s]
        real(wp) :: cpu = 0.0_wp
        integer :: steps = 0, functions = 0, jacobians = 0
        !> Largest distance of the centre from the reference's at the output times [m]
        real(wp) :: position_error = 0.0_wp
        !> Largest constraint residual [m/s] and relative energy drift
        real(wp) :: residual = 0.0_wp, energy_drift = 0.0_wp
        !> 'completed', or why not
        character(len=:), allocatable :: status
    end type benchmark_row_type

contains

    !> The methods compared: IDA and CVODE (BDF, Adams), analytic against difference-quotient
    !> Jacobians, and each drift control of the ODE form.
    pure function benchmark_methods() result(methods)
        type(method_type) :: methods(7)

        methods(1) = method_type("ida", "ida", "bdf", "projection", "analytic")
        methods(2) = method_type("ida-dq", "ida", "bdf", "projection", "dq")
        methods(3) = method_type("cvode-bdf-projection", "cvode", "bdf", "projection", "analytic")
        methods(4) = method_type("cvode-bdf-projection-dq", "cvode", "bdf", "projection", "dq")
        methods(5) = method_type("cvode-bdf-baumgarte", "cvode", "bdf", "baumgarte", "analytic")
        methods(6) = method_type("cvode-bdf-none", "cvode", "bdf", "none", "analytic")
        ! CVODE projects only with BDF: Adams is stabilised by Baumgarte's method
        methods(7) = method_type("cvode-adams-baumgarte", "cvode", "adams", "baumgarte", &
            & "analytic")
    end function benchmark_methods

    !> Header of the benchmark CSV.
    pure function benchmark_header() result(header)
        character(len=:), allocatable :: header

        header = "scene,method,rtol,cpu_s,steps,function_evaluations,jacobian_evaluations," &
            & // "position_error_m,residual_max,energy_drift,status"
    end function benchmark_header

    !> One CSV line.
    function write_benchmark_row(row) result(line)
        type(benchmark_row_type), intent(in) :: row
        character(len=:), allocatable :: line
        character(len=160) :: numbers

        write(numbers, '(es10.3, ",", es12.5, 3(",", i0), 3(",", es12.5))') row%rtol, row%cpu, &
            & row%steps, row%functions, row%jacobians, row%position_error, row%residual, &
            & row%energy_drift
        line = trim(row%scene) // "," // trim(row%method) // "," // trim(numbers) // "," // row%status
    end function write_benchmark_row

    !> Measure every method on every tolerance for one scene; rows are appended.
    subroutine benchmark_scene(scene, ucosub, methods, tolerances, reference_rtol, repeats, rows, &
            & error, progress)
        !> The scene as read (its own solver settings are replaced)
        type(scene_type), intent(in) :: scene
        procedure(ucosub_interface) :: ucosub
        type(method_type), intent(in) :: methods(:)
        !> Relative tolerances; atol = 1e-2 rtol (positions ~0.1 m, rates ~1 rad/s)
        real(wp), intent(in) :: tolerances(:)
        !> Tolerance of the reference solutions
        real(wp), intent(in) :: reference_rtol
        !> Runs per measurement (CPU median); runs longer than a second are not repeated
        integer, intent(in) :: repeats
        type(benchmark_row_type), allocatable, intent(inout) :: rows(:)
        type(error_type), allocatable, intent(out) :: error
        !> Unit for a line after each measurement (none when absent)
        integer, intent(in), optional :: progress
        type(history_type) :: reference(2), history
        type(run_summary_type) :: summary
        type(benchmark_row_type) :: row
        real(wp), allocatable :: times(:)
        integer :: m, k, r, other

        if (.not. allocated(rows)) allocate(rows(0))
        ! reference 1: IDA (for the CVODE methods' errors); 2: CVODE BDF (for IDA's). Where
        ! the requested tolerance is more than a formulation can meet (IDA's Newton iteration
        ! fails near 1e-13 on some scenes), it is loosened tenfold, at most twice.
        call reference_run(method_type("ref", "cvode", "bdf", "projection", "analytic"), &
            & reference(2), error)
        if (allocated(error)) return
        call reference_run(method_type("ref", "ida", "bdf", "projection", "analytic"), &
            & reference(1), error)
        if (allocated(error)) return
        do m = 1, size(methods)
            other = 1
            if (methods(m)%formulation == "ida") other = 2
            do k = 1, size(tolerances)
                row%scene = scene%name
                row%method = methods(m)%name
                row%rtol = tolerances(k)
                allocate(times(0))
                do r = 1, max(1, repeats)
                    call run(with_method(scene, methods(m), tolerances(k)), history, summary, &
                        & error)
                    if (allocated(error)) then
                        ! a failed run is a measurement too: recorded, not fatal
                        row%status = "failed: " // error%message
                        deallocate(error)
                        exit
                    end if
                    times = [times, summary%cpu_seconds]
                    if (summary%cpu_seconds > 1.0_wp) exit
                end do
                if (size(times) > 0) then
                    row%cpu = median(times)
                    row%status = "completed"
                    if (summary%status /= status_completed) row%status = "stopped: " &
                        & // summary%message
                else
                    row%cpu = summary%cpu_seconds
                end if
                deallocate(times)
                row%steps = summary%steps
                row%functions = summary%functions
                row%jacobians = summary%jacobians
                row%residual = summary%residual_max
                row%energy_drift = summary%energy_drift
                row%position_error = position_error(history, reference(other))
                rows = [rows, row]
                if (present(progress)) then
                    write(progress, '(a)') "bench: " // write_benchmark_row(row)
                    flush(progress)
                end if
            end do
        end do

    contains

        subroutine reference_run(method, kept, run_error)
            type(method_type), intent(in) :: method
            type(history_type), intent(out) :: kept
            type(error_type), allocatable, intent(out) :: run_error
            ! (rtol factor, atol) tried in turn: IDA's Newton iteration can fail to converge
            ! when atol asks for ~1e-15 m on coordinates that start at zero
            real(wp), parameter :: factors(4) = [1.0_wp, 1.0_wp, 10.0_wp, 100.0_wp]
            real(wp), parameter :: floors(4) = [0.0_wp, 1.0e-11_wp, 1.0e-11_wp, 1.0e-10_wp]
            type(scene_type) :: case_scene
            integer :: attempt

            do attempt = 1, size(factors)
                case_scene = with_method(scene, method, reference_rtol*factors(attempt))
                case_scene%run%atol = max(case_scene%run%atol, floors(attempt))
                call run(case_scene, kept, summary, run_error)
                if (.not. allocated(run_error)) then
                    if (present(progress)) write(progress, '(a)') "bench: " // trim(scene%name) &
                        & // ": reference by " // trim(method%formulation) // " at rtol " &
                        & // to_text(case_scene%run%rtol) // ", atol " &
                        & // to_text(case_scene%run%atol)
                    return
                end if
            end do
            run_error%message = "reference solution by " // trim(method%formulation) &
                & // " failed: " // run_error%message
        end subroutine reference_run

        subroutine run(case_scene, kept, case_summary, case_error)
            type(scene_type), intent(in) :: case_scene
            type(history_type), intent(out) :: kept
            type(run_summary_type), intent(out) :: case_summary
            type(error_type), allocatable, intent(out) :: case_error

            call simulate_scene(case_scene, ucosub, case_summary, case_error, kept)
        end subroutine run

    end subroutine benchmark_scene

    !> CPU seconds of one ODE right-hand side, one DAE residual, and one LAPACK factor-and-solve
    !> of the saddle-point system's size (the floor of a right-hand side), each the mean of
    !> count calls at the scene's initial state, measured in the same run.
    subroutine evaluation_costs(scene, ucosub, count, rhs_seconds, residual_seconds, &
            & solve_seconds, error)
        type(scene_type), intent(in) :: scene
        procedure(ucosub_interface) :: ucosub
        integer, intent(in) :: count
        real(wp), intent(out) :: rhs_seconds, residual_seconds, solve_seconds
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp) :: q0(6), u0(6), start, finish, checksum
        real(wp), allocatable :: y(:), ydot(:), yd(:), ypd(:), r(:), matrix(:, :), lu(:, :), b(:, :)
        integer, allocatable :: pivots(:)
        integer :: i, ierr, n

        call build_disk_problem(scene, ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        call problem%prepare()
        y = [q0, u0]
        allocate(ydot(size(y)))
        ierr = problem%ode_rhs(0.0_wp, y, ydot)
        checksum = 0.0_wp
        call cpu_time(start)
        do i = 1, count
            ierr = problem%ode_rhs(0.0_wp, y, ydot)
            checksum = checksum + ydot(7)
        end do
        call cpu_time(finish)
        rhs_seconds = (finish - start)/count
        ! the same saddle-point matrix, factored and solved alone
        n = problem%eq%n + problem%eq%nc
        allocate(matrix(n, n))
        call problem%eq%accelerations(0.0_wp, q0, u0, problem%a, problem%lambda, error)
        if (allocated(error)) return
        matrix(:problem%eq%n, :problem%eq%n) = problem%eq%mass
        matrix(:problem%eq%n, problem%eq%n + 1:) = -transpose(problem%eq%c)
        matrix(problem%eq%n + 1:, :problem%eq%n) = problem%eq%c
        matrix(problem%eq%n + 1:, problem%eq%n + 1:) = 0.0_wp
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
        yd(:12) = y
        ypd(:12) = ydot
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

    !> The scene with a method and tolerance in place of its own.
    function with_method(scene, method, rtol) result(changed)
        type(scene_type), intent(in) :: scene
        type(method_type), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(scene_type) :: changed

        changed = scene
        changed%run%formulation = choice_code("formulation", method%formulation)
        changed%run%method = choice_code("method", method%method)
        changed%run%drift = choice_code("drift", method%drift)
        changed%run%jacobian = choice_code("jacobian", method%jacobian)
        changed%run%rtol = rtol
        changed%run%atol = 1.0e-2_wp*rtol
        changed%run%max_steps = 10000000
    end function with_method

    !> Largest distance between the centres at the output times both runs reached [m].
    pure function position_error(run, reference) result(distance)
        type(history_type), intent(in) :: run, reference
        real(wp) :: distance
        integer :: i, n

        n = min(run%count, reference%count)
        distance = 0.0_wp
        do i = 1, n
            if (abs(run%rows(column_time, i) - reference%rows(column_time, i)) > 1.0e-9_wp) exit
            distance = max(distance, norm2(run%rows(column_x:column_z, i) &
                & - reference%rows(column_x:column_z, i)))
        end do
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
