! SPDX-License-Identifier: MIT
!> IDA on a DAE system (rollcon_dynamic_system's dae_system_type): its algebraic components (a
!> model's multipliers) excluded from the error test, dense Newton solves with the system's
!> Jacobian or IDA's difference quotients, or sparse ones (KLU) with the system's Jacobian
!> written over its pattern (dae_pattern, dae_sparse_jacobian: no n x n array).
module rollcon_ida
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_long, c_int64_t, &
        & c_double, c_funloc, c_loc, c_f_pointer, c_associated
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_run_settings, only : run_settings_type
    use rollcon_dynamic_system, only : dae_system_type
    use rollcon_integrator, only : integrator_type, integrator_statistics_type, solver_failure, &
        & chunk_steps_default
    use fsundials_context_mod, only : FSUNContext_Create, FSUNContext_Free
    use fsundials_types_mod, only : SUNTRUE
    use fsundials_nvector_mod, only : N_Vector, FN_VDestroy, FN_VGetArrayPointer
    use fsundials_matrix_mod, only : SUNMatrix, FSUNMatDestroy
    use fsundials_linearsolver_mod, only : SUNLinearSolver, FSUNLinSolFree
    use fnvector_serial_mod, only : FN_VMake_Serial
    use fsunmatrix_dense_mod, only : FSUNDenseMatrix, FSUNDenseMatrix_Data
    use fsunlinsol_dense_mod, only : FSUNLinSol_Dense
    use fsunmatrix_sparse_mod, only : FSUNSparseMatrix, FSUNSparseMatrix_Data, &
        & FSUNSparseMatrix_IndexValues, FSUNSparseMatrix_IndexPointers, CSC_MAT
    use fsunlinsol_klu_mod, only : FSUNLinSol_KLU
    use rollcon_newton_pattern, only : newton_pattern_type
    use fida_mod, only : FIDACreate, FIDAInit, FIDAWFtolerances, FIDASetUserData, &
        & FIDASetInitStep, FIDASetLinearSolver, FIDASetJacFn, FIDASetMaxNumSteps, &
        & FIDASetStopTime, FIDASolve, FIDASetNonlinConvCoef, &
        & FIDARootInit, FIDAGetRootInfo, FIDASetId, FIDASetSuppressAlg, FIDAFree, FIDAReInit, &
        & FIDAGetNumSteps, FIDAGetNumResEvals, FIDAGetNumJacEvals, FIDAGetNumLinResEvals, &
        & FIDAGetNumErrTestFails, FIDAGetNumNonlinSolvConvFails, FIDAGetNumGEvals, &
        & FIDASetErrFile, FIDAGetLastStep, FIDAGetCurrentTime, FIDAGetDky, &
        & IDA_NORMAL, IDA_SUCCESS, &
        & IDA_ROOT_RETURN, &
        & IDA_TSTOP_RETURN, IDA_TOO_MUCH_WORK, IDA_TOO_MUCH_ACC, IDA_ERR_FAIL, IDA_CONV_FAIL
    implicit none
    private

    public :: ida_integrator_type

    !> The careful start after a re-basing (docs/rebasing.md). A restarted IDA has no history
    !> and begins at order 1, backward Euler, whose local error, held only to the run's
    !> tolerances, is all amplitude on an oscillating motion and always takes energy away:
    !> measured, some 20 such steps after each restart cost a rolling ball 4e-10 m of its orbit
    !> radius at rtol 1e-10. Over the first stretch after a re-basing, restart_fine_steps of the
    !> steps IDA was taking before it, the differential components' tolerances are
    !> restart_tolerance_factor finer; IDA reaches order 2 well within it and goes on from
    !> there, on the same history, with the run's own tolerances (measured with the tilt rate
    !> held to atol alone: the 1000 re-basings of data/ball_tumbling.adm drift its orbit radius
    !> by 1.0e-8 m with it, 7.4e-7 m without, for 1 % more steps). At an input's corner the
    !> start is plain (restart, careful false).
    real(wp), parameter :: restart_tolerance_factor = 1.0e-2_wp, restart_fine_steps = 2.0_wp
    !> The steps a careful stretch may take. IDA crosses one in a few dozen (measured: at most
    !> 56 over the 5,027 careful stretches of the test suite, 2026-11-30); one that takes more
    !> makes no progress (the struck coin on IDA stopping its slide, at 1e-2 of the
    !> tolerances, took 500,000 steps within 1e-15 s and failed: IDA_TOO_MUCH_WORK), and is
    !> made again as a plain start from the same state (advance)
    integer, parameter :: careful_steps_most = 1000
    !> The finest relative tolerance of that stretch [-]: 1000 eps, where the corrector of the
    !> index-2 DAE still converges (at 100 eps it fails on the first steps)
    real(wp), parameter :: finest_rtol = 1.0e3_wp*epsilon(1.0_wp)
    !> The shortest careful stretch, relative to its start time [-]: IDA refuses an output
    !> closer to its start than 2 eps of the time (IDA_ILL_INPUT, "tout too close to t0"), and
    !> locates a root to 100 eps of it; a stretch shorter than that is none
    real(wp), parameter :: restart_span_min = 1.0e2_wp*epsilon(1.0_wp)
    !> IDA's Newton iteration stops when its error is estimated below this fraction of the
    !> error weights (IDASetNonlinConvCoef; IDA's own default 0.33). What it leaves in each step
    !> is in the history whose differences estimate the local error and choose the order, where
    !> the (k+1)-th difference amplifies it: at 0.33 IDA chooses order 3 on 7,589 of the 17,573
    !> steps of data/ball_on_turntable.adm at ERROR = 1e-10, whose error on an undamped
    !> oscillation is all growth ((h w)^4 / 4 per step), and the orbit grows 3.6e-6 relative; at
    !> 0.02 it takes 9,185 steps, mostly of order 4 and 5, and the orbit moves 7.4e-8
    !> (docs/design.md §7; 0.1, 0.05, 0.033, 0.015 and 0.01 measured too)
    real(wp), parameter :: newton_coefficient = 0.02_wp
    !> But never a Newton error below this relative one, what the index-2 corrector can reach
    !> in the arithmetic (IDA's 0.33 of finest_rtol, the finest careful start, converges; at
    !> 0.02 of it IDA fails to converge on the tumbling ball at ERROR = 1e-11), nor above IDA's
    !> own coefficient
    real(wp), parameter :: finest_newton = 0.33_wp*finest_rtol, widest_newton = 0.33_wp
    !> The flattest tilt at which a part's Euler-angle rates are weighed as they are [-]: sin
    !> theta below it is taken as it (a start flatter than this is refused)
    real(wp), parameter :: flattest_sin_theta = 1.0e-3_wp

    !> What the callbacks receive as user data: the system, and what the error weights are
    !> made of
    type :: callback_data_type
        class(dae_system_type), pointer :: system => null()
        !> The run's relative tolerance [-] and each component's absolute one [state units]
        real(wp) :: rtol = 0.0_wp
        real(wp), allocatable :: absolute(:)
        !> 1 for a differential component, 0 for an algebraic one (IDA's id vector)
        real(wp), allocatable :: kinds(:)
        !> The parts whose orientation is a set of Euler angles (dae_euler_parts): (1, k) the
        !> index of the k-th one's psi, (2, k) of its psi'
        integer, allocatable :: euler(:, :)
        !> The differential components' tolerances are multiplied by this: 1, or finer on the
        !> careful start after a restart
        real(wp) :: scale = 1.0_wp
        !> Sparse Newton matrices (KLU): whether the Newton matrix is one, and its entries (the
        !> system's dae_pattern), which the system writes straight into (no n x n array)
        logical :: sparse = .false.
        type(newton_pattern_type) :: pattern
    end type callback_data_type

    !> One IDA integration of a DAE system
    type, extends(integrator_type) :: ida_integrator_type
        type(c_ptr) :: context = c_null_ptr
        type(c_ptr) :: memory = c_null_ptr
        type(callback_data_type) :: data
        type(N_Vector), pointer :: y => null(), yp => null(), id => null()
        type(SUNMatrix), pointer :: matrix => null()
        type(SUNLinearSolver), pointer :: solver => null()
        !> Storage behind y, y' and the id vector
        real(c_double), allocatable :: values(:), rates(:), kinds(:)
        !> The careful start after a restart: finer tolerances until fine_until [s]; its
        !> length fine_span [s] from the last restart that followed a step
        real(wp) :: fine_until = -huge(1.0_wp), fine_span = 0.0_wp
        !> Where the integration last began (start or restart) [s], and the state there: what a
        !> second try of a first step that failed starts from (advance)
        real(wp) :: t_begin = 0.0_wp
        real(c_double), allocatable :: begin_values(:), begin_rates(:)
        !> The dissipated work (integrator_type work), as CVODE integrates it: the state
        !> interpolated on the last step (IDAGetDky, for powers_at) and its storage, and the
        !> work at t_begin [J]
        type(N_Vector), pointer :: dense => null()
        real(c_double), allocatable :: dense_values(:)
        real(wp), allocatable :: work_begin(:)
    contains
        procedure :: start
        procedure :: restart
        procedure :: advance
        procedure :: statistics
        procedure :: destroy
        procedure :: step_end
        procedure :: powers_at
    end type ida_integrator_type

contains

    !> Create IDA for system from consistent (t0, y0, yp0) with the settings' tolerances, step
    !> limit and Jacobian, watching the system's event functions. Its length is SUNDIALS' set-up
    !> sequence, one checked call per line, in the order IDA requires.
    subroutine start(self, system, settings, t0, y0, yp0, t_stop, error)
        class(ida_integrator_type), intent(inout), target :: self
        class(dae_system_type), intent(inout), target :: system
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: t0, y0(:), yp0(:), t_stop
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag
        integer(c_int64_t) :: n

        n = size(y0)
        self%values = y0
        self%rates = yp0
        self%kinds = system%dae_differential(size(y0))
        ! The algebraic components (a model's multipliers: forces, not states) are out of the
        ! error test, and their absolute tolerance is set on their own scale (1e-3 of the
        ! largest at the start) so that Newton's convergence test does not ask them for digits
        ! an index-2 DAE cannot give (with atol on them, IDA fails to converge at tight
        ! tolerances). The error weights are rollcon's (weights, below): IDA's own with these
        ! tolerances, and finer ones on the careful start after a restart.
        ! Their floor, 1e-5 of the model's weight: constraints that carry almost nothing at
        ! the start (a part of 19.6 N held only by PARALLEL_AXES, its multipliers 4e-4 N m) set
        ! a scale Newton cannot meet at tight tolerances (IDA failed at t = 0 at ERROR 1e-8 and
        ! below; a floor of 1e-6, 5e-8 of its weight, still failed, and 1e-5, 5e-7 of it,
        ! passed: 1e-5 of the weight leaves a factor 20; docs/design.md §7).
        self%data%absolute = merge(settings%atol, &
            & max(1.0e-3_wp*maxval(abs(y0), mask=self%kinds == 0.0_wp), settings%atol, &
            & 1.0e-5_wp*system%multiplier_scale()), self%kinds == 1.0_wp)
        self%data%kinds = self%kinds
        ! A part's Euler-angle rates are the coordinates of one angular velocity: they are held
        ! to what an error of that angular velocity within rtol |omega| + atol makes in them
        ! (weights, below). Held to atol alone, a rate that stays near zero while the part spins
        ! (the tilt rate theta' of data/ball_on_turntable.adm, against 12.5 rad/s) failed IDA's
        ! error test on 240,866 of 240,903 steps (docs/design.md §7).
        self%data%euler = system%dae_euler_parts(size(y0))
        self%data%rtol = settings%rtol
        self%data%scale = 1.0_wp
        self%fine_until = -huge(1.0_wp)
        self%fine_span = 0.0_wp
        flag = FSUNContext_Create(c_null_ptr, self%context)
        if (check(flag, "SUNContext_Create", error)) return
        self%y => FN_VMake_Serial(n, self%values, self%context)
        self%yp => FN_VMake_Serial(n, self%rates, self%context)
        self%id => FN_VMake_Serial(n, self%kinds, self%context)
        if (.not. (associated(self%y) .and. associated(self%yp) .and. associated(self%id))) then
            call fatal_error(error, "IDA: could not create the state vectors", stat_solver)
            return
        end if
        self%memory = FIDACreate(self%context)
        if (.not. c_associated(self%memory)) then
            call fatal_error(error, "IDA: IDACreate failed", stat_solver)
            return
        end if
        ! every flag is checked and reported by rollcon: IDA prints nothing itself
        flag = FIDASetErrFile(self%memory, c_null_ptr)
        if (check(flag, "IDASetErrFile", error)) return
        flag = FIDAInit(self%memory, c_funloc(residual), t0, self%y, self%yp)
        if (check(flag, "IDAInit", error)) return
        self%data%system => system
        flag = FIDASetUserData(self%memory, c_loc(self%data))
        if (check(flag, "IDASetUserData", error)) return
        flag = FIDAWFtolerances(self%memory, c_funloc(weights))
        if (check(flag, "IDAWFtolerances", error)) return
        self%max_steps = settings%max_steps
        flag = FIDASetMaxNumSteps(self%memory, int(settings%max_steps, c_long))
        if (check(flag, "IDASetMaxNumSteps", error)) return
        flag = FIDASetNonlinConvCoef(self%memory, newton_fraction(self%data))
        if (check(flag, "IDASetNonlinConvCoef", error)) return
        ! Index 2: the algebraic components are kept out of the local error test.
        flag = FIDASetId(self%memory, self%id)
        if (check(flag, "IDASetId", error)) return
        flag = FIDASetSuppressAlg(self%memory, SUNTRUE)
        if (check(flag, "IDASetSuppressAlg", error)) return
        ! the Newton matrix: sparse (KLU) over the system's pattern when the settings choose
        ! it for its size and entries (sparse_newton), else dense
        call system%dae_pattern(size(y0), self%data%pattern)
        self%data%sparse = settings%sparse_newton(size(y0), self%data%pattern%entries())
        if (self%data%sparse) then
            self%matrix => FSUNSparseMatrix(n, n, int(self%data%pattern%entries(), c_int64_t), &
                & CSC_MAT, self%context)
            if (associated(self%matrix)) &
                & self%solver => FSUNLinSol_KLU(self%y, self%matrix, self%context)
        else
            self%matrix => FSUNDenseMatrix(n, n, self%context)
            self%solver => FSUNLinSol_Dense(self%y, self%matrix, self%context)
        end if
        if (.not. associated(self%matrix) .or. .not. associated(self%solver)) then
            call fatal_error(error, "IDA: could not create the linear solver", stat_solver)
            return
        end if
        flag = FIDASetLinearSolver(self%memory, self%solver, self%matrix)
        if (check(flag, "IDASetLinearSolver", error)) return
        if (self%data%sparse) then
            flag = FIDASetJacFn(self%memory, c_funloc(sparse_jacobian))
            if (check(flag, "IDASetJacFn", error)) return
        else if (settings%analytic_jacobian()) then
            flag = FIDASetJacFn(self%memory, c_funloc(jacobian))
            if (check(flag, "IDASetJacFn", error)) return
        end if
        flag = FIDASetStopTime(self%memory, t_stop)
        if (check(flag, "IDASetStopTime", error)) return
        if (system%root_count() > 0) then
            flag = FIDARootInit(self%memory, int(system%root_count(), c_int), &
                & c_funloc(events))
            if (check(flag, "IDARootInit", error)) return
        end if
        if (allocated(self%fired)) deallocate(self%fired)
        allocate(self%fired(system%root_count()), source=0_c_int)
        self%failed_flag = 0
        self%t_now = t0
        self%t_begin = t0
        self%begin_values = self%values
        self%begin_rates = self%rates
        if (allocated(self%work)) deallocate(self%work, self%work_end, self%work_begin)
        self%power_evaluations = 0
        if (system%power_count() > 0) then
            allocate(self%work(system%power_count()), self%work_end(system%power_count()), &
                & self%work_begin(system%power_count()), source=0.0_wp)
            self%t_work = t0
            if (allocated(self%dense_values)) deallocate(self%dense_values)
            allocate(self%dense_values(size(y0)), source=0.0_wp)
            if (associated(self%dense)) call FN_VDestroy(self%dense)
            self%dense => FN_VMake_Serial(int(size(y0), c_int64_t), self%dense_values, &
                & self%context)
            if (.not. associated(self%dense)) then
                call fatal_error(error, "IDA: could not create the interpolated state", &
                    & stat_solver)
                return
            end if
        end if
    end subroutine start

    !> Start again from consistent (t0, y0, yp0) with the settings, tolerances, callbacks and
    !> event functions of start (IDAReInit): after a re-basing has changed the coordinates,
    !> with the careful start (the differential components' tolerances
    !> restart_tolerance_factor finer up to restart_fine_steps of the last step taken before, or
    !> of the previous restart's stretch when none was taken since); at an input's corner
    !> (careful false) as at a start, whose first step IDA makes small (docs/design.md §7).
    subroutine restart(self, t0, y0, yp0, error, careful)
        class(ida_integrator_type), intent(inout) :: self
        real(wp), intent(in) :: t0, y0(:), yp0(:)
        type(error_type), allocatable, intent(out) :: error
        !> The careful start (default true)
        logical, intent(in), optional :: careful
        integer(c_int) :: flag
        real(c_double) :: h_last(1)

        flag = FIDAGetLastStep(self%memory, h_last)
        if (check(flag, "IDAGetLastStep", error)) return
        self%values(:) = y0
        self%rates(:) = yp0
        self%t_now = t0
        self%t_begin = t0
        self%begin_values = self%values
        self%begin_rates = self%rates
        ! the work goes on from its value at the restart's time (the last return's)
        if (allocated(self%work)) then
            self%work_end = self%work
            self%work_begin = self%work
            self%t_work = t0
            self%power_evaluations = 0
        end if
        flag = FIDAReInit(self%memory, t0, self%y, self%yp)
        if (check(flag, "IDAReInit", error)) return
        self%data%scale = 1.0_wp
        self%fine_until = t0
        if (present(careful)) then
            if (.not. careful) then
                flag = FIDASetNonlinConvCoef(self%memory, newton_fraction(self%data))
                if (check(flag, "IDASetNonlinConvCoef", error)) return
                return
            end if
        end if
        ! a last step too short to make a stretch IDA can start over (within the time's
        ! round-off: a root reported again just after the restart it was started from, a
        ! touchdown's rebound through the ground level) keeps the stretch of before
        if (restart_fine_steps*h_last(1) > restart_span_min*abs(t0)) &
            & self%fine_span = restart_fine_steps*h_last(1)
        self%fine_until = t0 + self%fine_span
        ! the run's own Newton coefficient, set before the finer stretch: IDA reads it only on
        ! the first call after IDAReInit (its epsNewt is set from it in IDASolve's first-call
        ! block), so whatever is set there stays for the rest of the run, the careful stretch's
        ! finer weights included
        flag = FIDASetNonlinConvCoef(self%memory, newton_fraction(self%data))
        if (check(flag, "IDASetNonlinConvCoef", error)) return
        if (self%fine_span > 0.0_wp) self%data%scale = min(1.0_wp, &
            & max(restart_tolerance_factor, finest_rtol/self%data%rtol))
    end subroutine restart

    !> Integrate towards t_out (never past t_stop); y, yp at t_reached; root fired (0 if none).
    !> A first step whose Newton iteration fails (no step taken since the start or restart) is
    !> tried once more from the same state with a first step of first_step_fraction of the way
    !> to t_out: IDA's own first step is small enough that h y' is small in the error weights,
    !> and components that begin at zero (a model released from rest) are weighed by atol alone,
    !> so on a large model it can be small enough (1.4e-11 s on a chain of 64 links of 0.1 kg at
    !> atol 1e-10) that the index-2 Newton matrix, whose condition grows as 1/h^2, cannot be
    !> solved; IDA then only shrinks it. A first step too large fails IDA's error test instead,
    !> which shrinks it by the error's own estimate. A careful start whose Newton iteration
    !> still fails before its first output (its finer tolerances beyond what the corrector
    !> reaches at that state: the SPHERICAL pendulum of the suite couplers, re-based at
    !> sin theta = 0.05, at ERROR = 1e-10, whose careful stretch asks 7e-14 relative of the
    !> corrector), or whose careful stretch takes more than careful_steps_most steps, is made
    !> again from the same state as a plain start. A run whose first step and careful starts
    !> succeed makes no retry, so its numbers do not depend on it.
    subroutine advance(self, t_out, t_stop, t_reached, y, yp, root, error)
        class(ida_integrator_type), intent(inout) :: self
        real(wp), intent(in) :: t_out, t_stop
        real(wp), intent(out) :: t_reached
        real(wp), intent(inout) :: y(:), yp(:)
        integer, intent(out) :: root
        type(error_type), allocatable, intent(out) :: error
        !> The second try's first step, as a fraction of the way to t_out (IDA's own first
        !> step before it is cut to make h y' small)
        real(wp), parameter :: first_step_fraction = 1.0e-3_wp
        real(c_double) :: t_return(1)
        integer(c_long) :: taken(1)
        integer(c_int) :: flag, ignored
        real(wp) :: t_entry

        root = 0
        t_entry = self%t_now
        flag = FIDASetStopTime(self%memory, t_stop)
        if (check(flag, "IDASetStopTime", error)) return
        call solve(flag)
        if (allocated(error)) return
        if (flag == IDA_CONV_FAIL) then
            taken(1) = -1
            if (FIDAGetNumSteps(self%memory, taken) /= IDA_SUCCESS) taken(1) = -1
            if (taken(1) == 0 .and. t_out > self%t_begin) then
                self%values(:) = self%begin_values
                self%rates(:) = self%begin_rates
                self%t_now = self%t_begin
                call begin_work()
                flag = FIDAReInit(self%memory, self%t_begin, self%y, self%yp)
                if (check(flag, "IDAReInit", error)) return
                flag = FIDASetInitStep(self%memory, first_step_fraction*(t_out - self%t_begin))
                if (check(flag, "IDASetInitStep", error)) return
                call solve(flag)
                if (allocated(error)) return
                ! IDA's own choice again for any later restart (0: IDA estimates it)
                ignored = FIDASetInitStep(self%memory, 0.0_wp)
            end if
        end if
        if ((flag == IDA_CONV_FAIL .or. flag == IDA_TOO_MUCH_WORK) &
            & .and. self%data%scale < 1.0_wp .and. t_entry == self%t_begin) then
            ! the careful start failed before its first output: plainly, from the same state
            self%values(:) = self%begin_values
            self%rates(:) = self%begin_rates
            self%t_now = self%t_begin
            call begin_work()
            self%data%scale = 1.0_wp
            self%fine_until = self%t_begin
            flag = FIDAReInit(self%memory, self%t_begin, self%y, self%yp)
            if (check(flag, "IDAReInit", error)) return
            flag = FIDASetNonlinConvCoef(self%memory, newton_fraction(self%data))
            if (check(flag, "IDASetNonlinConvCoef", error)) return
            call solve(flag)
            if (allocated(error)) return
        end if
        t_reached = t_return(1)
        self%t_now = t_reached
        y = self%values
        yp = self%rates
        if (flag == IDA_ROOT_RETURN) then
            flag = FIDAGetRootInfo(self%memory, self%fired)
            root = findloc(self%fired /= 0, .true., dim=1)
            return
        end if
        if (flag == IDA_SUCCESS .or. flag == IDA_TSTOP_RETURN) return
        self%failed_flag = int(flag)
        call solver_failure(error, "IDA", t_reached, int(flag), flag_meaning(flag), &
            & self%data%system)

    contains

        !> The work back at the start or restart's, with its state (a second try from there).
        subroutine begin_work()
            if (.not. allocated(self%work)) return
            self%work_end = self%work_begin
            self%work = self%work_begin
            self%t_work = self%t_begin
        end subroutine begin_work

        !> IDASolve towards t_out, t_return set: after a restart, the careful start first.
        subroutine solve(status)
            integer(c_int), intent(out) :: status

            ! where the integrator was, should it fail before it sets t_return
            t_return(1) = self%t_now
            if (self%fine_until > self%t_now) then
                ! the careful start after a restart: the finer stretch first, then the run's
                ! own tolerances on the same history
                call careful_chunk(min(t_out, self%fine_until), status)
                if ((status == IDA_SUCCESS .or. status == IDA_TSTOP_RETURN) &
                    & .and. t_return(1) >= self%fine_until) then
                    self%data%scale = 1.0_wp
                    if (status == IDA_SUCCESS .and. t_return(1) < t_out) &
                        & call chunked(t_out, status)
                end if
            else
                call chunked(t_out, status)
            end if
        end subroutine solve

        !> chunked towards t_goal within careful_steps_most steps (the run's max_steps, if
        !> fewer), the run's own budget set again after it.
        subroutine careful_chunk(t_goal, status)
            real(wp), intent(in) :: t_goal
            integer(c_int), intent(out) :: status
            integer(c_int) :: ignored
            integer :: budget

            budget = self%max_steps
            self%max_steps = min(budget, careful_steps_most)
            ignored = FIDASetMaxNumSteps(self%memory, int(self%max_steps, c_long))
            call chunked(t_goal, status)
            self%max_steps = budget
            ignored = FIDASetMaxNumSteps(self%memory, int(budget, c_long))
        end subroutine careful_chunk

        !> IDASolve towards t_goal; with a watch, the max_steps budget in chunks of
        !> chunk_steps_default, the watch told between them. IDASolve called again after
        !> IDA_TOO_MUCH_WORK goes on from its step as if it had not returned (IDA guide,
        !> IDASolve: the step counter of the limit is per call), so the steps and the state are
        !> those of one call.
        subroutine chunked(t_goal, status)
            real(wp), intent(in) :: t_goal
            integer(c_int), intent(out) :: status
            integer :: taken, chunk
            real(wp) :: t_start
            integer :: before

            if (allocated(self%work)) then
                call stepwise(t_goal, status)
                return
            end if
            if (.not. associated(self%watch)) then
                status = FIDASolve(self%memory, t_goal, t_return, self%y, self%yp, IDA_NORMAL)
                return
            end if
            taken = 0
            do
                chunk = min(chunk_steps_default, self%max_steps - taken)
                status = FIDASetMaxNumSteps(self%memory, int(chunk, c_long))
                if (status /= IDA_SUCCESS) return
                t_start = t_return(1)
                before = rejected()
                status = FIDASolve(self%memory, t_goal, t_return, self%y, self%yp, IDA_NORMAL)
                taken = taken + chunk
                if (status /= IDA_TOO_MUCH_WORK .or. taken >= self%max_steps) exit
                call self%watch%between_chunks(t_start, t_return(1), t_out, chunk, &
                    & rejected() - before)
            end do
        end subroutine chunked

        !> As chunked, one step a call (IDA's mxstep 1), the dissipated work integrated over
        !> each step as it is taken (integrate_work): IDASolve goes on after IDA_TOO_MUCH_WORK
        !> as if it had not returned, so the steps, the roots and the state are those of one
        !> call with the whole budget. The watch is told every chunk_steps_default steps.
        subroutine stepwise(t_goal, status)
            real(wp), intent(in) :: t_goal
            integer(c_int), intent(out) :: status
            integer :: taken, before
            real(wp) :: t_start

            status = FIDASetMaxNumSteps(self%memory, 1_c_long)
            if (status /= IDA_SUCCESS) return
            taken = 0
            t_start = t_return(1)
            before = rejected()
            do
                status = FIDASolve(self%memory, t_goal, t_return, self%y, self%yp, IDA_NORMAL)
                if (status /= IDA_SUCCESS .and. status /= IDA_TSTOP_RETURN .and. status &
                    & /= IDA_ROOT_RETURN .and. status /= IDA_TOO_MUCH_WORK) exit
                call self%integrate_work(t_return(1), error)
                if (allocated(error)) then
                    ! the power's failure: as a failed step, its message the error's
                    status = IDA_ERR_FAIL
                    return
                end if
                if (status /= IDA_TOO_MUCH_WORK) exit
                taken = taken + 1
                if (taken >= self%max_steps) exit
                if (associated(self%watch) .and. mod(taken, chunk_steps_default) == 0) then
                    call self%watch%between_chunks(t_start, t_return(1), t_out, &
                        & chunk_steps_default, rejected() - before)
                    t_start = t_return(1)
                    before = rejected()
                end if
            end do
        end subroutine stepwise

        !> Steps rejected so far: by the error test or for want of the corrector's convergence.
        integer function rejected()
            integer(c_long) :: count(1)
            integer(c_int) :: ignored_flag

            count(1) = 0
            ignored_flag = FIDAGetNumErrTestFails(self%memory, count)
            rejected = int(count(1))
            count(1) = 0
            ignored_flag = FIDAGetNumNonlinSolvConvFails(self%memory, count)
            rejected = rejected + int(count(1))
        end function rejected
    end subroutine advance

    !> Steps, residuals (own and for difference-quotient Jacobians), Jacobians, test failures.
    function statistics(self) result(counts)
        class(ida_integrator_type), intent(in) :: self
        type(integrator_statistics_type) :: counts
        integer(c_long) :: count(1), extra(1)
        integer(c_int) :: flag

        if (.not. c_associated(self%memory)) return
        flag = FIDAGetNumSteps(self%memory, count)
        counts%steps = int(count(1))
        flag = FIDAGetNumResEvals(self%memory, count)
        flag = FIDAGetNumLinResEvals(self%memory, extra)
        ! and the dissipated powers' evaluations (integrate_work), each an evaluation as one
        ! of the residual's
        counts%functions = int(count(1) + extra(1)) + self%power_evaluations
        flag = FIDAGetNumJacEvals(self%memory, count)
        counts%jacobians = int(count(1))
        flag = FIDAGetNumErrTestFails(self%memory, count)
        counts%failures = int(count(1))
        flag = FIDAGetNumGEvals(self%memory, count)
        counts%roots = int(count(1))
        counts%sparse = self%data%sparse
    end function statistics

    !> What a failure flag of IDA means (names of the IDA guide), for messages: SUNDIALS
    !> itself prints nothing (its error file is none).
    pure function flag_meaning(flag) result(text)
        integer(c_int), intent(in) :: flag
        character(len=:), allocatable :: text

        select case (flag)
        case (IDA_TOO_MUCH_WORK)
            text = "IDA_TOO_MUCH_WORK, max_steps internal steps taken before the next output time"
        case (IDA_TOO_MUCH_ACC)
            text = "IDA_TOO_MUCH_ACC, the tolerances ask for more accuracy than the arithmetic has"
        case (IDA_ERR_FAIL)
            text = "IDA_ERR_FAIL, the error test failed repeatedly or at the smallest step"
        case (IDA_CONV_FAIL)
            text = "IDA_CONV_FAIL, the corrector failed repeatedly or at the smallest step"
        case default
            text = "see the IDA guide's return codes"
        end select
    end function flag_meaning

    !> The Newton coefficient for the tolerances of the moment: newton_coefficient, within
    !> finest_newton relative (rtol times the careful start's scale) and widest_newton.
    pure function newton_fraction(data) result(fraction)
        type(callback_data_type), intent(in) :: data
        real(wp) :: fraction

        fraction = min(widest_newton, max(newton_coefficient, &
            & finest_newton/(data%rtol*data%scale)))
    end function newton_fraction

    !> Free in reverse order of creation.
    subroutine destroy(self)
        class(ida_integrator_type), intent(inout) :: self
        integer(c_int) :: flag

        if (c_associated(self%memory)) call FIDAFree(self%memory)
        if (associated(self%dense)) call FN_VDestroy(self%dense)
        nullify(self%dense)
        if (allocated(self%work)) deallocate(self%work, self%work_end, self%work_begin)
        if (associated(self%solver)) flag = FSUNLinSolFree(self%solver)
        if (associated(self%matrix)) call FSUNMatDestroy(self%matrix)
        if (associated(self%id)) call FN_VDestroy(self%id)
        if (associated(self%yp)) call FN_VDestroy(self%yp)
        if (associated(self%y)) call FN_VDestroy(self%y)
        if (c_associated(self%context)) flag = FSUNContext_Free(self%context)
        self%memory = c_null_ptr
        self%context = c_null_ptr
        nullify(self%solver, self%matrix, self%y, self%yp, self%id, self%data%system)
        self%data%sparse = .false.
        if (allocated(self%fired)) deallocate(self%fired)
    end subroutine destroy

    !> The end of IDA's last step, its tn [s] (integrator_type step_end).
    subroutine step_end(self, t_end, error)
        class(ida_integrator_type), intent(inout) :: self
        real(wp), intent(out) :: t_end
        type(error_type), allocatable, intent(out) :: error
        real(c_double) :: t_current(1)
        integer(c_int) :: flag

        t_end = 0.0_wp
        flag = FIDAGetCurrentTime(self%memory, t_current)
        if (check(flag, "IDAGetCurrentTime", error)) return
        t_end = t_current(1)
    end subroutine step_end

    !> The dissipated powers [W] at time [s] within IDA's last step, on the state it
    !> interpolates there (IDAGetDky; integrator_type powers_at).
    subroutine powers_at(self, time, power, error)
        class(ida_integrator_type), intent(inout) :: self
        real(wp), intent(in) :: time
        real(wp), intent(out) :: power(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag

        power = 0.0_wp
        flag = FIDAGetDky(self%memory, time, 0_c_int, self%dense)
        if (check(flag, "IDAGetDky (the state for the dissipated work)", error)) return
        if (self%data%system%powers(time, self%dense_values, power) /= 0) then
            call solver_failure(error, "IDA", time, -1, "the dissipated power could " &
                & // "not be evaluated", self%data%system)
        end if
    end subroutine powers_at

    function check(flag, routine, error) result(failed)
        integer(c_int), intent(in) :: flag
        character(len=*), intent(in) :: routine
        type(error_type), allocatable, intent(out) :: error
        logical :: failed

        failed = flag /= 0
        if (failed) call fatal_error(error, "IDA: " // routine // " returned flag " &
            & // to_text(int(flag)), stat_solver)
    end function check

    integer(c_int) function residual(t, y, yp, r, user_data) result(ierr) &
            & bind(c, name="rollcon_ida_residual")
        real(c_double), value :: t
        type(N_Vector) :: y, yp, r
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), ypv(:), rv(:)

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        ypv => FN_VGetArrayPointer(yp)
        rv => FN_VGetArrayPointer(r)
        ierr = int(data%system%dae_residual(t, yv, ypv, rv), c_int)
    end function residual

    integer(c_int) function jacobian(t, cj, y, yp, r, jac, user_data, tmp1, tmp2, tmp3) &
            & result(ierr) bind(c, name="rollcon_ida_jacobian")
        real(c_double), value :: t, cj
        type(N_Vector) :: y, yp, r, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), ypv(:), entries(:), matrix(:, :)

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        ypv => FN_VGetArrayPointer(yp)
        entries => FSUNDenseMatrix_Data(jac)
        call c_f_pointer(c_loc(entries(1)), matrix, [size(yv), size(yv)])
        ierr = int(data%system%dae_jacobian(t, cj, yv, ypv, matrix), c_int)
    end function jacobian

    !> The system's Jacobian written over its pattern (zeros included, so the pattern KLU
    !> analysed stays) as a compressed-column matrix: IDA zeroes the matrix, indices too,
    !> before each call.
    integer(c_int) function sparse_jacobian(t, cj, y, yp, r, jac, user_data, tmp1, tmp2, tmp3) &
            & result(ierr) bind(c, name="rollcon_ida_sparse_jacobian")
        real(c_double), value :: t, cj
        type(N_Vector) :: y, yp, r, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), ypv(:), values(:), first_value(:)
        integer(c_int64_t), pointer :: rows(:), starts(:), first_index(:)
        integer :: entries

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        ypv => FN_VGetArrayPointer(yp)
        ! SUNDIALS' Fortran interface hands the first element: the arrays by their sizes
        entries = data%pattern%entries()
        first_value => FSUNSparseMatrix_Data(jac)
        call c_f_pointer(c_loc(first_value(1)), values, [entries])
        first_index => FSUNSparseMatrix_IndexValues(jac)
        call c_f_pointer(c_loc(first_index(1)), rows, [entries])
        first_index => FSUNSparseMatrix_IndexPointers(jac)
        call c_f_pointer(c_loc(first_index(1)), starts, [size(yv) + 1])
        rows = int(data%pattern%rows, c_int64_t)
        starts = int(data%pattern%starts, c_int64_t)
        ierr = int(data%system%dae_sparse_jacobian(t, cj, yv, ypv, data%pattern%starts, &
            & data%pattern%rows, values), c_int)
    end function sparse_jacobian

    !> IDA's error weights, 1/(rtol |y_i| + atol_i), but for a part's Euler-angle rates: the
    !> angular velocity w = B(theta, phi) (psi', theta', phi') is held to
    !> tau = rtol |w| + atol (Euclidean, w's error in any direction), and each rate to the
    !> largest error such an error of w makes in it through B^-1: tau / sin(theta) for psi' and
    !> phi', tau for theta' (|w|^2 = psi'^2 + theta'^2 + phi'^2 + 2 psi' phi' cos(theta), the
    !> 3-1-3 angles of docs/design.md §3). The differential components' tolerances are
    !> multiplied by the scale of the moment (finer on the careful start after a restart).
    integer(c_int) function weights(y, ewt, user_data) result(ierr) &
            & bind(c, name="rollcon_ida_weights")
        type(N_Vector) :: y, ewt
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), wv(:)
        real(wp) :: omega, sin_theta
        integer :: i, k, a, r

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        wv => FN_VGetArrayPointer(ewt)
        ! element by element: called before every step, it allocates nothing
        do i = 1, size(wv)
            wv(i) = data%rtol*abs(yv(i)) + data%absolute(i)
        end do
        do k = 1, size(data%euler, 2)
            a = data%euler(1, k)
            r = data%euler(2, k)
            sin_theta = max(abs(sin(yv(a + 1))), flattest_sin_theta)
            omega = sqrt(max(0.0_wp, yv(r)**2 + yv(r + 1)**2 + yv(r + 2)**2 &
                & + 2.0_wp*yv(r)*yv(r + 2)*cos(yv(a + 1))))
            wv(r) = (data%rtol*omega + data%absolute(r))/sin_theta
            wv(r + 1) = data%rtol*omega + data%absolute(r + 1)
            wv(r + 2) = (data%rtol*omega + data%absolute(r + 2))/sin_theta
        end do
        do i = 1, size(wv)
            if (data%kinds(i) == 1.0_wp) wv(i) = data%scale*wv(i)
            wv(i) = 1.0_wp/wv(i)
        end do
        ierr = 0
    end function weights

    integer(c_int) function events(t, y, yp, gout, user_data) result(ierr) &
            & bind(c, name="rollcon_ida_events")
        real(c_double), value :: t
        type(N_Vector) :: y, yp
        real(c_double) :: gout(*)
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:)
        integer :: nroots

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        nroots = data%system%root_count()
        ierr = int(data%system%roots(t, yv, gout(:nroots)), c_int)
    end function events

end module rollcon_ida
