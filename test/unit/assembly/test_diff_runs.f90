! SPDX-License-Identifier: MIT
!> Datasets with DIFFs run (suite diff-runs, docs/datasets.md "DIFF"): a first-order lag of a
!> part's known motion, written explicitly and IMPLICIT, against its closed form on CVODE and
!> on IDA; an integral-action controller (a force reading DIF through a VARIABLE) against the
!> closed form of its third-order closed loop; the DIFFs' rows of the ODE form's and the DAE
!> form's Newton matrices against central differences of their right-hand side and residual,
!> entry by entry; the linear analysis of a mass on a spring with a lag of its position
!> (eigenvalues +-2i and -1/tau); and the refusals, each naming the statement and its line.
!> The same two DIFFs served by a DIFSUB written for the test (registered here, reading
!> SYSFNC's DX, VX, DY, WZ, DIF and DIF1) give the Newton matrices' DIFF rows of their
!> expression twin, to the differences' error.
module test_diff_runs
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_linearisation, only : linear_options_type, linear_result_type
    use rollcon_linear_job, only : linearise_job
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_user_forces, only : register_diff_routine, clear_force_routines, &
        & system_function
    use adm_datasets, only : read_dataset
    implicit none
    private

    public :: collect_diff_runs

    character(len=*), parameter :: work_dir = "build/rollcon-test"
    character(len=*), parameter :: nl = new_line("a")
    !> A part of 1 kg moving along ground x at 1 m/s from the origin, no gravity; the lag's
    !> time constant tau = 0.5 s
    character(len=*), parameter :: mover = "lag" // nl // "PART/1, GROUND" // nl &
        & // "MARKER/1, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, VX = 1" &
        & // nl // "MARKER/20, PART = 2" // nl // "ACCGRAV/IGRAV = 0, JGRAV = 0, KGRAV = 0" // nl

contains

    subroutine collect_diff_runs(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("lag-explicit-and-implicit-closed-form-cvode-and-ida", test_lag), &
            & new_unittest("integral-action-force-reads-dif-closed-form", test_integral), &
            & new_unittest("newton-matrix-diff-rows-against-differences", test_newton), &
            & new_unittest("difsub-newton-rows-against-expression-twin", test_difsub_newton), &
            & new_unittest("linear-analysis-lag-eigenvalue", test_linear), &
            & new_unittest("refusals-name-the-statement", test_refusals)]
    end subroutine collect_diff_runs

    !> DIFF/3: d x/dt = (X - x)/tau and DIFF/4: 0 = tau x' - (X - x) (IMPLICIT), X = t the
    !> part's x: both are x = t - tau (1 - e^(-t/tau)), x' = 1 - e^(-t/tau), from x(0) = 0.
    subroutine test_lag(error)
        type(error_type), allocatable, intent(out) :: error
        !> At ERROR = 1e-10 over 2 s (4 tau): measured 1.6e-9 (CVODE) and 1.0e-9 (IDA) for the
        !> state, twice that for its rate (x' = (X - x)/tau); 1.5e-8 leaves a factor of 4.5
        !> over the larger (a tau 1 % off moves the state by 5e-3)
        real(wp), parameter :: tol = 1.5e-8_wp, tau = 0.5_wp
        character(len=*), parameter :: formulations(2) = ["CVODE", "IDA  "]
        character(len=*), parameter :: diffs = "DIFF/3, FUNCTION = (DX(20) - DIF(3))/0.5, " &
            & // "IC = 0" // nl // "DIFF/4, FUNCTION = 0.5*DIF1(4) - (DX(20) - DIF(4)), " &
            & // "IC = 0, 1, IMPLICIT" // nl
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: t, worst(4)
        integer :: f, k, c3, c4

        do f = 1, size(formulations)
            call run_text("lag.adm", mover // diffs // "INTEGRATOR/ERROR = 1e-10, " &
                & // "FORMULATION = " // trim(formulations(f)) // nl // "SIMULATE/DYNAMIC, " &
                & // "END = 2, STEPS = 40" // nl // "END", result, rows, error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. rows%count == 41, &
                & trim(formulations(f)) // ": the run completes with 41 rows")
            if (allocated(error)) return
            c3 = result%summary%layout%column("diff3")
            c4 = result%summary%layout%column("diff4")
            call check(error, c3 > 0 .and. c4 == c3 + 2 .and. &
                & result%summary%layout%column("diff3_dot") == c3 + 1, &
                & "columns diff3, diff3_dot, diff4, diff4_dot")
            if (allocated(error)) return
            worst = 0.0_wp
            do k = 1, rows%count
                t = rows%rows(1, k)
                worst(1) = max(worst(1), abs(rows%rows(c3, k) - (t - tau*(1.0_wp - exp(-t/tau)))))
                worst(2) = max(worst(2), abs(rows%rows(c3 + 1, k) - (1.0_wp - exp(-t/tau))))
                worst(3) = max(worst(3), abs(rows%rows(c4, k) - (t - tau*(1.0_wp - exp(-t/tau)))))
                worst(4) = max(worst(4), abs(rows%rows(c4 + 1, k) - (1.0_wp - exp(-t/tau))))
            end do
            call check(error, all(worst <= tol), trim(formulations(f)) // ": largest " &
                & // "differences from the closed form: explicit x " // to_text(worst(1)) &
                & // ", x' " // to_text(worst(2)) // "; implicit x " // to_text(worst(3)) &
                & // ", x' " // to_text(worst(4)))
            if (allocated(error)) return
        end do
    end subroutine test_lag

    !> A 1 kg mass on ground x, pushed by FX = -11 x - 6 x' + VARVAL(5), VARIABLE/5 = -6 I and
    !> DIFF/1: I' = x (the integral of x): x''' + 6 x'' + 11 x' + 6 x = 0, roots -1, -2, -3.
    !> From x = 1, x' = 0, I = 0: x = -2.5 e^-t + 8 e^-2t - 4.5 e^-3t, I its integral from 0.
    subroutine test_integral(error)
        type(error_type), allocatable, intent(out) :: error
        !> At ERROR = 1e-10 over 4 s: measured 1.5e-9 (CVODE) and 7.4e-10 (IDA) for x, 6e-10
        !> and 2.6e-10 for I; 6e-9 leaves a factor of 4 (a gain 1 % off moves x by 2e-3);
        !> diff1_dot is x and var5 is -6 I from the row's own values (measured 0)
        real(wp), parameter :: tol = 6.0e-9_wp
        character(len=*), parameter :: formulations(2) = ["CVODE", "IDA  "]
        character(len=*), parameter :: text = "controller" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 1, 1, 1, " &
            & // "QG = 1, 0, 0" // nl // "MARKER/20, PART = 2" // nl &
            & // "ACCGRAV/IGRAV = 0, JGRAV = 0, KGRAV = 0" // nl &
            & // "VFORCE/1, I = 20, JFLOAT = 1, RM = 1, FX = -11*DX(20) - 6*VX(20) + " &
            & // "VARVAL(5), FY = 0, FZ = 0" // nl // "VARIABLE/5, FUNCTION = -6*DIF(1)" // nl &
            & // "DIFF/1, FUNCTION = DX(20), IC = 0" // nl
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: t, x, integral, worst(3)
        integer :: f, k, cx, cd, cv

        do f = 1, size(formulations)
            call run_text("controller.adm", text // "INTEGRATOR/ERROR = 1e-10, FORMULATION = " &
                & // trim(formulations(f)) // nl // "SIMULATE/DYNAMIC, END = 4, STEPS = 40" &
                & // nl // "END", result, rows, error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. rows%count == 41, &
                & trim(formulations(f)) // ": the run completes with 41 rows")
            if (allocated(error)) return
            cx = result%summary%layout%column("X_2")
            cd = result%summary%layout%column("diff1")
            cv = result%summary%layout%column("var5")
            call check(error, cx > 0 .and. cd > 0 .and. cv > 0, "columns X_2, diff1, var5")
            if (allocated(error)) return
            worst = 0.0_wp
            do k = 1, rows%count
                t = rows%rows(1, k)
                x = -2.5_wp*exp(-t) + 8.0_wp*exp(-2.0_wp*t) - 4.5_wp*exp(-3.0_wp*t)
                integral = -2.5_wp*(1.0_wp - exp(-t)) + 4.0_wp*(1.0_wp - exp(-2.0_wp*t)) &
                    & - 1.5_wp*(1.0_wp - exp(-3.0_wp*t))
                worst(1) = max(worst(1), abs(rows%rows(cx, k) - x))
                worst(2) = max(worst(2), abs(rows%rows(cd, k) - integral))
                ! diff1_dot is x itself, and var5 -6 I, from the row
                worst(3) = max(worst(3), abs(rows%rows(cd + 1, k) - rows%rows(cx, k)), &
                    & abs(rows%rows(cv, k) + 6.0_wp*rows%rows(cd, k)))
            end do
            call check(error, all(worst <= tol), trim(formulations(f)) // ": x against the " &
                & // "closed form " // to_text(worst(1)) // ", DIF(1) against its integral " &
                & // to_text(worst(2)) // ", diff1_dot and var5 against the row " &
                & // to_text(worst(3)))
            if (allocated(error)) return
        end do
    end subroutine test_integral

    !> Two DIFFs reading q, u, each other's DIF and DIF1 (one IMPLICIT) on a part moving in
    !> 3-D: the ODE form's rows of x' = w/T and the DAE form's rows of G in its Newton matrix
    !> against central differences of ode_rhs and dae_residual in every state (and, for the
    !> DAE, y' times cj), entry by entry. Without the DIFFs' partials (dG/dx, dG/dw, or the
    !> solve through dG/dw) the rows differ by O(1).
    subroutine test_newton(error)
        type(error_type), allocatable, intent(out) :: error
        !> Central differences of step 1e-6 on functions of unit scale: truncation ~1e-12,
        !> rounding ~1e-10; measured 4.4e-11 in both forms (entries up to 1.1 in the ODE
        !> form's rows, 16 in the DAE's); 2e-10 of the largest entry leaves a factor of 5 over
        !> the ODE form's; a missing partial is of order 1
        real(wp), parameter :: tol = 2.0e-10_wp, h = 1.0e-6_wp, cj = 7.0_wp
        character(len=*), parameter :: text = "newton" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART = 1" // nl // "PART/2, MASS = 2, CM = 20, IP = 1, 2, 3, " &
            & // "QG = 0.3, 0.2, 0.1, REULER = 0.4D, 0.5D, 0.6D, VX = 0.7, VY = -0.2, " &
            & // "WZ = 0.9" // nl // "MARKER/20, PART = 2, QP = 0.1, 0, 0" // nl &
            & // "ACCGRAV/KGRAV = -9.80665" // nl &
            & // "DIFF/1, FUNCTION = SIN(DX(20))*VX(20) - DIF(1)*DIF1(2) + DIF(2), IC = 0.3" &
            & // nl // "DIFF/2, FUNCTION = DIF1(2)*(2 + DIF(1)**2) - DY(20)*WZ(20) + DIF(2), " &
            & // "IC = -0.2, 0.1, IMPLICIT" // nl // "SIMULATE/DYNAMIC, END = 1, STEPS = 10" &
            & // nl // "END"
        type(job_type) :: job
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(dae_form_type) :: dae
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:), matrix(:, :), plus(:), minus(:), &
            & column(:), yd(:), ypd(:)
        character(len=:), allocatable :: report
        real(wp) :: worst, largest
        integer :: n, ns, j, ierr, m, unit

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/newton.adm", status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
        call load_job(work_dir // "/newton.adm", job, error)
        if (allocated(error)) return
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        n = size(q0)
        ! the ODE form
        call ode%init(problem)
        ns = ode%state_size()
        allocate(y(ns), yp(ns), matrix(ns, ns), plus(ns), minus(ns))
        call ode%pack_state(q0, u0, y, yp)
        ierr = ode%ode_jacobian(0.3_wp, y, matrix)
        call check(error, ierr == 0 .and. ns == 2*n + 2, "the ODE form's Newton matrix, " &
            & // "state 2n + 2")
        if (allocated(error)) return
        worst = 0.0_wp
        largest = maxval(abs(matrix(2*n + 1:, :)))
        do j = 1, ns
            yd = y
            yd(j) = y(j) + h
            ierr = ierr + ode%ode_rhs(0.3_wp, yd, plus)
            yd(j) = y(j) - h
            ierr = ierr + ode%ode_rhs(0.3_wp, yd, minus)
            column = (plus - minus)/(2.0_wp*h)
            worst = max(worst, maxval(abs(matrix(2*n + 1:, j) - column(2*n + 1:))))
        end do
        call check(error, ierr == 0 .and. largest > 0.1_wp .and. worst <= tol*largest, &
            & "ODE form: the DIFFs' rows against differences, largest difference " &
            & // to_text(worst) // " of entries up to " // to_text(largest))
        if (allocated(error)) return
        ! the DAE form, at the rates the ODE form solved (any y' would do)
        call dae%init(problem)
        call problem%accelerations(0.3_wp, q0, u0, error)
        if (allocated(error)) return
        ns = dae%state_size()
        m = ns - 2
        deallocate(y, yp, matrix, plus, minus)
        allocate(y(ns), yp(ns), matrix(ns, ns), plus(ns), minus(ns))
        call dae%pack_state(q0, u0, y, yp)
        yp(m + 1:) = yp(m + 1:) + [0.05_wp, -0.03_wp]
        matrix = 0.0_wp
        ierr = dae%dae_jacobian(0.3_wp, cj, y, yp, matrix)
        worst = 0.0_wp
        largest = maxval(abs(matrix(m + 1:, :)))
        do j = 1, ns
            yd = y
            ypd = yp
            yd(j) = y(j) + h
            ypd(j) = yp(j) + cj*h
            ierr = ierr + dae%dae_residual(0.3_wp, yd, ypd, plus)
            yd(j) = y(j) - h
            ypd(j) = yp(j) - cj*h
            ierr = ierr + dae%dae_residual(0.3_wp, yd, ypd, minus)
            column = (plus - minus)/(2.0_wp*h)
            worst = max(worst, maxval(abs(matrix(m + 1:, j) - column(m + 1:))))
        end do
        call check(error, ierr == 0 .and. largest > 0.1_wp .and. worst <= tol*largest, &
            & "DAE form: the DIFFs' rows against differences, largest difference " &
            & // to_text(worst) // " of entries up to " // to_text(largest))
    end subroutine test_newton

    !> test_newton's two DIFFs (DIFF/1 explicit, DIFF/2 IMPLICIT) served by newton_difsub
    !> (the same functions, read through SYSFNC) give the DIFF rows of the ODE form's and the
    !> DAE form's Newton matrices of the expressions (exact partials). The DIFSUB's partials
    !> are central differences of step eps^(1/3) max(|y|, 1) over what its IFLAG call declared
    !> (rollcon_central_differences): their error h^2 v'''/6 + eps |v|/h stands near eps^(2/3)
    !> = 4e-11 of the values' scale (functions of unit size here; entries up to 1.1 in the ODE
    !> form's rows, 16 in the DAE form's). Measured: 3.4e-12 and 1.3e-11, 3.0e-12 and 8.2e-13
    !> of the largest entry; 2e-11 of it leaves a factor of 7 over the larger and fails on a
    !> tenfold loss. Without the DIFSUB's partials the IMPLICIT DIFF's dG/dDIF1 is 0: the
    !> Newton matrix fails (singular), and dG/dq of SIN(DX), dG/dDIF are entries of order 1.
    subroutine test_difsub_newton(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tol = 2.0e-11_wp, cj = 7.0_wp
        character(len=120), parameter :: head(5) = [character(len=120) :: &
            & "newton twins", "PART/1, GROUND|MARKER/1, PART = 1", &
            & "PART/2, MASS = 2, CM = 20, IP = 1, 2, 3, QG = 0.3, 0.2, 0.1, REULER = 0.4D, " &
            & // "0.5D, 0.6D, VX = 0.7, VY = -0.2, WZ = 0.9", &
            & "MARKER/20, PART = 2, QP = 0.1, 0, 0", "ACCGRAV/KGRAV = -9.80665"]
        character(len=120), parameter :: expressions(2) = [character(len=120) :: &
            & "DIFF/1, FUNCTION = SIN(DX(20))*VX(20) - DIF(1)*DIF1(2) + DIF(2), IC = 0.3", &
            & "DIFF/2, FUNCTION = DIF1(2)*(2 + DIF(1)**2) - DY(20)*WZ(20) + DIF(2), " &
            & // "IC = -0.2, 0.1, IMPLICIT"]
        character(len=120), parameter :: users(2) = [character(len=120) :: &
            & "DIFF/1, FUNCTION = USER(20), IC = 0.3", &
            & "DIFF/2, FUNCTION = USER(20), IC = -0.2, 0.1, IMPLICIT"]
        character(len=120), parameter :: tail(2) = [character(len=120) :: &
            & "SIMULATE/DYNAMIC, END = 1, STEPS = 10", "END"]
        real(wp), allocatable :: exact(:, :), differenced(:, :)
        character(len=:), allocatable :: name
        real(wp) :: largest, worst
        integer :: form, n, rows

        do form = 1, 2
            call clear_force_routines()
            call register_diff_routine("", "test_diff_runs", newton_difsub)
            call twin_matrix([character(len=120) :: head, expressions, tail], form, exact, n, &
                & error)
            if (.not. allocated(error)) call twin_matrix([character(len=120) :: head, users, &
                & tail], form, differenced, n, error)
            call clear_force_routines()
            if (allocated(error)) return
            rows = size(exact, 1) - 1
            name = "ODE"
            if (form == 2) name = "DAE"
            largest = maxval(abs(exact(rows:, :)))
            worst = maxval(abs(differenced(rows:, :) - exact(rows:, :)))
            call check(error, largest > 0.5_wp, name // " form: the DIFF rows hold entries of " &
                & // "order 1")
            if (allocated(error)) return
            call check(error, worst <= tol*largest, name // " form: the DIFSUB's DIFF rows " &
                & // "differ from the expressions' by " // to_text(worst) // " of entries up " &
                & // "to " // to_text(largest))
            if (allocated(error)) return
        end do

    contains

        !> The ODE form's (form 1) or the DAE form's (2) Newton matrix of the dataset `lines`
        !> at t = 0.3 s from its start (the DAE form's DIF1s moved off the solved rates, as in
        !> test_newton); n the parts' coordinates.
        subroutine twin_matrix(lines, form, matrix, n, error)
            character(len=*), intent(in) :: lines(:)
            integer, intent(in) :: form
            real(wp), allocatable, intent(out) :: matrix(:, :)
            integer, intent(out) :: n
            type(error_type), allocatable, intent(out) :: error
            type(adm_model_type) :: adm
            type(problem_type), target :: problem
            type(ode_form_type) :: ode
            type(dae_form_type) :: dae
            procedure(ucosub_interface), pointer :: routine
            real(wp), allocatable :: q0(:), u0(:), y(:), yp(:)
            integer :: ns, ierr

            routine => null()
            call read_dataset("difsub_newton.adm", lines, adm, error)
            if (allocated(error)) return
            call build_adm_problem(adm, routine, problem, q0, u0, error)
            if (allocated(error)) return
            call problem%prepare(error)
            if (allocated(error)) return
            n = size(q0)
            if (form == 1) then
                call ode%init(problem)
                ns = ode%state_size()
                allocate(y(ns), yp(ns), matrix(ns, ns))
                call ode%pack_state(q0, u0, y, yp)
                ierr = ode%ode_jacobian(0.3_wp, y, matrix)
            else
                call dae%init(problem)
                call problem%accelerations(0.3_wp, q0, u0, error)
                if (allocated(error)) return
                ns = dae%state_size()
                allocate(y(ns), yp(ns), matrix(ns, ns))
                call dae%pack_state(q0, u0, y, yp)
                yp(ns - 1:) = yp(ns - 1:) + [0.05_wp, -0.03_wp]
                matrix = 0.0_wp
                ierr = dae%dae_jacobian(0.3_wp, cj, y, yp, matrix)
            end if
            call check(error, ierr == 0, trim(lines(1)) // ": the Newton matrix")
            call problem%release()
        end subroutine twin_matrix

    end subroutine test_difsub_newton

    !> test_newton's DIFF/1 (explicit: VALUE is d DIF/dt) and DIFF/2 (IMPLICIT: VALUE is the
    !> residual), of marker PAR(1), through SYSFNC's DX, VX, DY, WZ, DIF and DIF1; ADAMS's
    !> calling sequence (rollcon_system_routine_contract).
    subroutine newton_difsub(id, time, par, npar, dflag, iflag, value)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: value
        real(wp) :: dx, vx, dy, wz, dif1, dif2, rate2
        integer :: marker
        logical :: failed

        marker = nint(par(1))
        call system_function("DIF", [1], dif1, failed)
        call system_function("DIF", [2], dif2, failed)
        call system_function("DIF1", [2], rate2, failed)
        if (id == 1) then
            call system_function("DX", [marker], dx, failed)
            call system_function("VX", [marker], vx, failed)
            value = sin(dx)*vx - dif1*rate2 + dif2
        else
            call system_function("DY", [marker], dy, failed)
            call system_function("WZ", [marker], wz, failed)
            value = rate2*(2.0_wp + dif1**2) - dy*wz + dif2
        end if
    end subroutine newton_difsub

    !> A 2 kg mass on a spring to ground (k = 8 N/m, omega = 2 rad/s) with a lag of its x,
    !> tau = 0.25 s: the linear model has 13 states (12 of the part, 1 of the DIFF), the
    !> eigenvalues +-2i (three times: the spring pulls along its line in 3-D), six zeros and
    !> -1/tau = -4.
    subroutine test_linear(error)
        type(error_type), allocatable, intent(out) :: error
        !> The linearisation's central differences with a Richardson step: ~1e-10 relative
        !> (docs/linear.md); measured 3.6e-15 1/s here (the model is linear in the lag);
        !> 4e-10 1/s, 1e-10 of -4 1/s, the differences' own error
        real(wp), parameter :: tol = 4.0e-10_wp
        character(len=*), parameter :: text = "linear lag" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART = 1" // nl // "MARKER/21, PART = 1" // nl &
            & // "PART/2, MASS = 2, CM = 20, IP = 1, 1, 1, QG = 0.3, 0, 0" // nl &
            & // "MARKER/20, PART = 2" // nl // "SFORCE/1, TRANSLATION, I = 20, J = 21, " &
            & // "FUNCTION = -8*DM(20, 21)" // nl &
            & // "DIFF/3, FUNCTION = (DX(20) - DIF(3))/0.25, IC = 0.3" // nl &
            & // "ACCGRAV/IGRAV = 0, JGRAV = 0, KGRAV = 0" // nl &
            & // "SIMULATE/DYNAMIC, END = 1, STEPS = 10" // nl // "END"
        type(job_type) :: job
        type(linear_result_type) :: result
        type(linear_options_type) :: options
        character(len=:), allocatable :: report
        integer :: unit, lag

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/linear_lag.adm", status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
        call load_job(work_dir // "/linear_lag.adm", job, error)
        if (allocated(error)) return
        call linearise_job(job, result, report, error, options)
        if (allocated(error)) return
        call check(error, result%states == 13 .and. result%diff_states == 1 .and. &
            & result%reduced == 13, "13 states, one of them the DIFF's: " &
            & // to_text(result%states) // ", " // to_text(result%reduced) // " independent")
        if (allocated(error)) return
        lag = minloc(result%real_part, dim=1)
        call check(error, abs(result%real_part(lag) + 4.0_wp) <= tol .and. &
            & abs(result%imag_part(lag)) <= tol .and. count(abs(result%real_part) > tol) == 1, &
            & "one eigenvalue off the imaginary axis, -1/tau = -4: " &
            & // to_text(result%real_part(lag)))
        if (allocated(error)) return
        call check(error, count(abs(abs(result%imag_part) - 2.0_wp) <= tol) >= 2, &
            & "the spring's +-2i")
    end subroutine test_linear

    !> Each refusal names the statement and line and says why.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: tail = "SIMULATE/DYNAMIC, END = 1, STEPS = 10" // nl &
            & // "END"

        call expect("DIFF/3, FUNCTION = DIF(9), IC = 0" // nl // tail, &
            & "refuse_dif.adm:7: DIFF/3 FUNCTION: DIF(9): no DIFF/9 in the dataset", error)
        if (allocated(error)) return
        call expect("DIFF/3, FUNCTION = DX(20)" // nl // tail, &
            & "refuse_dif.adm:7: DIFF/3: IC=r1 is missing", error)
        if (allocated(error)) return
        call expect("DIFF/3, FUNCTION = DX(20), IC = 1, 2, 3" // nl // tail, &
            & "DIFF/3 IC: expected one or two numbers", error)
        if (allocated(error)) return
        call expect("DIFF/3, FUNCTION = DX(20) - DIF(3), IC = 0, IMPLICIT" // nl // tail, &
            & "refuse_dif.adm:7: DIFF/3 FUNCTION: an IMPLICIT DIFF's equation 0 = e must read " &
            & // "DIF1", error)
        if (allocated(error)) return
        call expect("DIFF/3, FUNCTION = ACCX(20), IC = 0" // nl // tail, &
            & "DIFF/3 FUNCTION: ACCX(20): an acceleration", error)
        if (allocated(error)) return
        ! singular only at the start's values: DIF1 read, times DIF(3) = 0
        call expect("DIFF/3, FUNCTION = DIF(3)*DIF1(3) - 1, IC = 0, IMPLICIT" // nl // tail, &
            & "DIFF/3 (line 7): the IMPLICIT equations 0 = e do not fix the DIF1s", error)
        if (allocated(error)) return
        call expect("DIFF/3, FUNCTION = 1, IC = 0" // nl // "INTEGRATOR/FORMULATION = MAGGI" &
            & // nl // tail, "DIFF/3 (line 7): a DIFF's state is integrated in the " &
            & // "formulations 'cvode' and 'ida'", error)
        if (allocated(error)) return
        call expect("DIFF/3, FUNCTION = 1, IC = 0" // nl // "SIMULATE/STATIC" // nl // "END", &
            & "DIFF/3 (line 7): a static equilibrium holds a DIFF's state at its value only " &
            & // "with STATIC_HOLD", error)

    contains

        !> The mover with `more` refused with a message holding `expected`.
        subroutine expect(more, expected, error)
            character(len=*), intent(in) :: more, expected
            type(error_type), allocatable, intent(out) :: error
            type(job_result_type) :: result
            type(history_type) :: rows
            type(error_type), allocatable :: refused

            call run_text("refuse_dif.adm", mover // more, result, rows, refused)
            if (.not. allocated(refused)) then
                call check(error, .false., "not refused: " // more)
                return
            end if
            call check(error, index(refused%message, expected) > 0, "refusal of " // more &
                & // nl // "  says: " // refused%message // nl // "  expected: " // expected)
        end subroutine expect
    end subroutine test_refusals

    !> Run the dataset at `path`, its rows kept in memory.
    subroutine run_file(path, result, rows, error)
        character(len=*), intent(in) :: path
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(error_type), allocatable :: failure

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, rows)
        if (allocated(failure)) call move_alloc(failure, error)
    end subroutine run_file

    !> Write text to work_dir/name and run it.
    subroutine run_text(name, text, result, rows, error)
        character(len=*), intent(in) :: name, text
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        integer :: unit

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
        call run_file(work_dir // "/" // name, result, rows, error)
    end subroutine run_text

end module test_diff_runs
