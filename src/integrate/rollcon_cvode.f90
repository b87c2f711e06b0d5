! SPDX-License-Identifier: MIT
!> CVODE on an ODE system (rollcon_dynamic_system's ode_system_type): BDF or Adams, dense
!> Newton solves with the system's Jacobian or CVODE's difference quotients, or sparse ones
!> (KLU) with the system's Jacobian kept over its state blocks (or fixed-point iteration,
!> without any); the system's projection when it asks for one, root finding; the work of the
!> powers the system dissipates, integrated over every step on CVODE's own interpolant
!> (docs/design.md §7, "Dissipated work").
module rollcon_cvode
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_long, c_int64_t, &
        & c_double, c_funloc, c_loc, c_f_pointer, c_associated
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_run_settings, only : run_settings_type, method_adams, jacobian_none
    use rollcon_dynamic_system, only : ode_system_type
    use rollcon_newton_pattern, only : newton_pattern_type, pattern_of_blocks
    use rollcon_integrator, only : integrator_type, integrator_statistics_type, solver_failure, &
        & chunk_steps_default
    use fsundials_context_mod, only : FSUNContext_Create, FSUNContext_Free
    use fsundials_nvector_mod, only : N_Vector, FN_VDestroy, FN_VGetArrayPointer
    use fsundials_matrix_mod, only : SUNMatrix, FSUNMatDestroy
    use fsundials_linearsolver_mod, only : SUNLinearSolver, FSUNLinSolFree
    use fnvector_serial_mod, only : FN_VMake_Serial, FN_VEnableLinearCombination_Serial, &
        & FN_VEnableScaleAddMulti_Serial, FN_VEnableScaleVectorArray_Serial
    use fsunmatrix_dense_mod, only : FSUNDenseMatrix, FSUNDenseMatrix_Data
    use fsunlinsol_dense_mod, only : FSUNLinSol_Dense
    use fsunmatrix_sparse_mod, only : FSUNSparseMatrix, FSUNSparseMatrix_Data, &
        & FSUNSparseMatrix_IndexValues, FSUNSparseMatrix_IndexPointers, FSUNSparseMatrix_NNZ, &
        & CSC_MAT
    use fsunlinsol_klu_mod, only : FSUNLinSol_KLU, FSUNLinSol_KLUReInit, SUNKLU_REINIT_PARTIAL
    use fcvode_mod, only : FCVodeCreate, FCVodeInit, FCVodeSStolerances, FCVodeSetUserData, &
        & FCVodeSetLinearSolver, FCVodeSetJacFn, FCVodeSetMaxNumSteps, FCVodeSetStopTime, &
        & FCVode, FCVodeRootInit, FCVodeGetRootInfo, FCVodeSetProjFn, FCVodeFree, &
        & FCVodeGetNumSteps, FCVodeGetNumRhsEvals, FCVodeGetNumJacEvals, &
        & FCVodeGetNumLinRhsEvals, FCVodeGetNumErrTestFails, FCVodeGetNumNonlinSolvConvFails, &
        & FCVodeGetNumGEvals, FCVodeGetDky, FCVodeGetCurrentTime, &
        & FCVodeGetNonlinearSystemData, FCVodeGetLastStep, FCVodeSetErrFile, &
        & FCVodeReInit, &
        & CV_BDF, CV_ADAMS, CV_NORMAL, &
        & CV_SUCCESS, CV_ROOT_RETURN, CV_TSTOP_RETURN, CV_TOO_MUCH_WORK, CV_TOO_MUCH_ACC, &
        & CV_ERR_FAILURE, CV_CONV_FAILURE
    implicit none
    private

    public :: cvode_integrator_type, step_end_rates

    ! SUNDIALS' fixed-point solver, from the C library itself (libsundials_cvode holds it): its
    ! Fortran module is a library rollcon does not otherwise link
    interface
        !> SUNNonlinSol_FixedPoint(y, m, context): m = 0, no Anderson acceleration
        function c_fixed_point_solver(y, m, context) result(solver) &
                & bind(c, name="SUNNonlinSol_FixedPoint")
            import :: c_ptr, c_int
            type(c_ptr), value :: y, context
            integer(c_int), value :: m
            type(c_ptr) :: solver
        end function c_fixed_point_solver
        function c_set_nonlinear_solver(memory, solver) result(flag) &
                & bind(c, name="CVodeSetNonlinearSolver")
            import :: c_ptr, c_int
            type(c_ptr), value :: memory, solver
            integer(c_int) :: flag
        end function c_set_nonlinear_solver
        function c_free_nonlinear_solver(solver) result(flag) bind(c, name="SUNNonlinSolFree")
            import :: c_ptr, c_int
            type(c_ptr), value :: solver
            integer(c_int) :: flag
        end function c_free_nonlinear_solver
        !> N_VGetArrayPointer(v): the data of a serial vector, called directly (the callbacks'
        !> vectors, whose length the callback data holds: state_values)
        function c_array_pointer(v) result(data) bind(c, name="N_VGetArrayPointer")
            import :: c_ptr
            type(c_ptr), value :: v
            type(c_ptr) :: data
        end function c_array_pointer
    end interface

    !> What the callbacks receive as user data: the system, and what the event function needs
    !> to read the state's derivative off CVODE's interpolating polynomial
    type :: callback_data_type
        class(ode_system_type), pointer :: system => null()
        type(c_ptr) :: memory = c_null_ptr
        !> y'(t) from CVodeGetDky (or step_end_rates), and its storage
        type(N_Vector), pointer :: rates => null()
        real(c_double), allocatable :: rate_values(:)
        !> The system's event functions (fixed for a run, as CVodeRootInit was told) and
        !> whether they use y' (roots_use_rates): the interpolation is made only then
        integer :: root_count = 0
        logical :: roots_use_rates = .false.
        !> Length of the state (of every vector CVODE hands the callbacks: its clones of y)
        integer :: states = 0
        !> Sparse Newton matrices: each state's block (entries kept: those of one block) and
        !> their pattern by columns (rollcon_newton_pattern), which the system fills
        !> (ode_sparse_jacobian): no size(y)-square array
        logical :: sparse = .false.
        integer, allocatable :: blocks(:)
        type(newton_pattern_type) :: pattern
    end type callback_data_type

    !> One CVODE integration of an ODE system
    type, extends(integrator_type) :: cvode_integrator_type
        type(c_ptr) :: context = c_null_ptr
        type(c_ptr) :: memory = c_null_ptr
        type(N_Vector), pointer :: y => null()
        type(callback_data_type) :: data
        type(SUNMatrix), pointer :: matrix => null()
        type(SUNLinearSolver), pointer :: solver => null()
        !> The fixed-point (functional) nonlinear solver in place of Newton's (jacobian_none)
        type(c_ptr) :: fixed_point = c_null_ptr
        !> Storage behind y
        real(c_double), allocatable :: values(:)
        !> The dissipated work (integrator_type work): the state interpolated on the last step
        !> (CVodeGetDky, for powers_at) and its storage
        type(N_Vector), pointer :: dense => null()
        real(c_double), allocatable :: dense_values(:)
    contains
        procedure :: start
        procedure :: restart
        procedure :: advance
        procedure :: statistics
        procedure :: destroy
        procedure :: step_end
        procedure :: powers_at
    end type cvode_integrator_type

contains

    !> Create CVODE for system from (t0, y0) with the settings' method, tolerances, step limit
    !> and Jacobian, watching the system's event functions (yp0 is not used), never stepping
    !> past t_stop.
    subroutine start(self, system, settings, t0, y0, yp0, t_stop, error)
        class(cvode_integrator_type), intent(inout), target :: self
        class(ode_system_type), intent(inout), target :: system
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: t0, y0(:), yp0(:), t_stop
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag, lmm

        allocate(self%values(size(y0)))
        self%values = y0
        flag = FSUNContext_Create(c_null_ptr, self%context)
        if (check(flag, "SUNContext_Create", error)) return
        self%y => FN_VMake_Serial(int(size(y0), c_int64_t), self%values, self%context)
        if (.not. associated(self%y)) then
            call fatal_error(error, "CVODE: could not create the state vector", stat_solver)
            return
        end if
        call enable_fused_operations(self%y, flag)
        if (check(flag, "N_VEnable..._Serial (the state vector)", error)) return
        lmm = CV_BDF
        if (settings%method == method_adams) lmm = CV_ADAMS
        self%memory = FCVodeCreate(lmm, self%context)
        if (.not. c_associated(self%memory)) then
            call fatal_error(error, "CVODE: CVodeCreate failed", stat_solver)
            return
        end if
        ! every flag is checked and reported by rollcon: CVODE prints nothing itself
        flag = FCVodeSetErrFile(self%memory, c_null_ptr)
        if (check(flag, "CVodeSetErrFile", error)) return
        flag = FCVodeInit(self%memory, c_funloc(rhs), t0, self%y)
        if (check(flag, "CVodeInit", error)) return
        allocate(self%data%rate_values(size(y0)), source=0.0_wp)
        self%data%states = size(y0)
        self%data%rates => FN_VMake_Serial(int(size(y0), c_int64_t), self%data%rate_values, &
            & self%context)
        if (.not. associated(self%data%rates)) then
            call fatal_error(error, "CVODE: could not create the derivative vector", stat_solver)
            return
        end if
        call enable_fused_operations(self%data%rates, flag)
        if (check(flag, "N_VEnable..._Serial (the derivative vector)", error)) return
        self%data%system => system
        self%data%memory = self%memory
        flag = FCVodeSetUserData(self%memory, c_loc(self%data))
        if (check(flag, "CVodeSetUserData", error)) return
        flag = FCVodeSStolerances(self%memory, settings%rtol, settings%atol)
        if (check(flag, "CVodeSStolerances", error)) return
        self%max_steps = settings%max_steps
        flag = FCVodeSetMaxNumSteps(self%memory, int(settings%max_steps, c_long))
        if (check(flag, "CVodeSetMaxNumSteps", error)) return
        if (settings%jacobian == jacobian_none) then
            ! fixed-point (functional) iteration: no Newton matrix, no linear solver
            self%fixed_point = c_fixed_point_solver(c_loc(self%y), 0_c_int, self%context)
            if (.not. c_associated(self%fixed_point)) then
                call fatal_error(error, "CVODE: could not create the fixed-point solver", &
                    & stat_solver)
                return
            end if
            flag = c_set_nonlinear_solver(self%memory, self%fixed_point)
            if (check(flag, "CVodeSetNonlinearSolver", error)) return
        else
            call newton_solver(error)
            if (allocated(error)) return
        end if
        if (system%projects()) then
            flag = FCVodeSetProjFn(self%memory, c_funloc(projection))
            if (check(flag, "CVodeSetProjFn", error)) return
        end if
        flag = FCVodeSetStopTime(self%memory, t_stop)
        if (check(flag, "CVodeSetStopTime", error)) return
        self%data%root_count = system%root_count()
        self%data%roots_use_rates = system%roots_use_rates()
        if (self%data%root_count > 0) then
            flag = FCVodeRootInit(self%memory, int(self%data%root_count, c_int), &
                & c_funloc(events))
            if (check(flag, "CVodeRootInit", error)) return
        end if
        if (allocated(self%fired)) deallocate(self%fired)
        allocate(self%fired(system%root_count()), source=0_c_int)
        self%failed_flag = 0
        self%t_now = t0
        if (allocated(self%work)) deallocate(self%work, self%work_end)
        self%power_evaluations = 0
        if (system%power_count() > 0) then
            allocate(self%work(system%power_count()), self%work_end(system%power_count()), &
                & source=0.0_wp)
            self%t_work = t0
            allocate(self%dense_values(size(y0)), source=0.0_wp)
            self%dense => FN_VMake_Serial(int(size(y0), c_int64_t), self%dense_values, &
                & self%context)
            if (.not. associated(self%dense)) then
                call fatal_error(error, "CVODE: could not create the interpolated state", &
                    & stat_solver)
                return
            end if
        end if

    contains

        !> Newton's method with SUNDIALS' dense linear solver on the system's Jacobian or
        !> difference quotients, or its sparse one (KLU) on the Jacobian kept over the state
        !> blocks.
        subroutine newton_solver(failure)
            type(error_type), allocatable, intent(out) :: failure

            ! sparse when the settings choose it for the matrix's size and blocks
            self%data%blocks = system%state_blocks(size(y0))
            self%data%sparse = settings%sparse_newton(size(y0), &
                & block_entries(self%data%blocks))
            if (self%data%sparse) then
                ! room for every entry of the blocks; KLU factors those given
                self%data%pattern = pattern_of_blocks(self%data%blocks)
                self%matrix => FSUNSparseMatrix(int(size(y0), c_int64_t), int(size(y0), &
                    & c_int64_t), int(max(self%data%pattern%entries(), 1), c_int64_t), &
                    & CSC_MAT, self%context)
                if (associated(self%matrix)) &
                    & self%solver => FSUNLinSol_KLU(self%y, self%matrix, self%context)
            else
                self%matrix => FSUNDenseMatrix(int(size(y0), c_int64_t), int(size(y0), &
                    & c_int64_t), self%context)
                self%solver => FSUNLinSol_Dense(self%y, self%matrix, self%context)
            end if
            if (.not. associated(self%matrix) .or. .not. associated(self%solver)) then
                call fatal_error(failure, "CVODE: could not create the linear solver", &
                    & stat_solver)
                return
            end if
            flag = FCVodeSetLinearSolver(self%memory, self%solver, self%matrix)
            if (check(flag, "CVodeSetLinearSolver", failure)) return
            if (self%data%sparse) then
                flag = FCVodeSetJacFn(self%memory, c_funloc(sparse_jacobian))
                if (check(flag, "CVodeSetJacFn", failure)) return
            else if (settings%analytic_jacobian()) then
                flag = FCVodeSetJacFn(self%memory, c_funloc(jacobian))
                if (check(flag, "CVodeSetJacFn", failure)) return
            end if
        end subroutine newton_solver

    end subroutine start

    !> Start again from (t0, y0) with the settings, tolerances, callbacks and event functions of
    !> start: after a re-basing has changed the coordinates (CVodeReInit). No careful start as
    !> IDA's (rollcon_ida): measured on data/ball_tumbling.adm (docs/rebasing.md), a first
    !> stretch 100 times finer, or first steps of 0.2 to 0.01 of the last, moved CVODE's drift
    !> over 1000 re-basings anywhere between -3.7e-7 and +3.6e-7 m at rtol 1e-10 and made it
    !> 3 to 10 times larger at 1e-11: no consistent gain.
    subroutine restart(self, t0, y0, yp0, error, careful)
        class(cvode_integrator_type), intent(inout) :: self
        real(wp), intent(in) :: t0, y0(:), yp0(:)
        type(error_type), allocatable, intent(out) :: error
        !> Not used: CVODE starts again its own way (docs/rebasing.md)
        logical, intent(in), optional :: careful
        integer(c_int) :: flag

        integer, allocatable :: blocks(:)

        self%values(:) = y0
        self%t_now = t0
        ! the work goes on from its value at the restart's time (the last return's)
        if (allocated(self%work)) then
            self%work_end = self%work
            self%t_work = t0
            self%power_evaluations = 0
        end if
        flag = FCVodeReInit(self%memory, t0, self%y)
        if (check(flag, "CVodeReInit", error)) return
        if (.not. self%data%sparse) return
        ! a new partition of independent speeds may move states between blocks: KLU analyses
        ! the new pattern again
        blocks = self%data%system%state_blocks(size(y0))
        if (all(blocks == self%data%blocks)) return
        self%data%blocks = blocks
        self%data%pattern = pattern_of_blocks(blocks)
        flag = FSUNLinSol_KLUReInit(self%solver, self%matrix, &
            & int(max(self%data%pattern%entries(), 1), c_int64_t), SUNKLU_REINIT_PARTIAL)
        if (check(flag, "SUNLinSol_KLUReInit", error)) return
    end subroutine restart

    !> Integrate towards t_out (never past t_stop); y at t_reached (yp is left as it was).
    subroutine advance(self, t_out, t_stop, t_reached, y, yp, root, error)
        class(cvode_integrator_type), intent(inout) :: self
        real(wp), intent(in) :: t_out, t_stop
        real(wp), intent(out) :: t_reached
        real(wp), intent(inout) :: y(:), yp(:)
        integer, intent(out) :: root
        type(error_type), allocatable, intent(out) :: error
        real(c_double) :: t_return(1)
        integer(c_int) :: flag

        root = 0
        flag = FCVodeSetStopTime(self%memory, t_stop)
        if (check(flag, "CVodeSetStopTime", error)) return
        ! where the integrator was, should it fail before it sets t_return
        t_return(1) = self%t_now
        if (allocated(self%work)) then
            call stepwise(flag)
            if (allocated(error)) return
        else if (associated(self%watch)) then
            call chunked(flag)
            if (allocated(error)) return
        else
            flag = FCVode(self%memory, t_out, self%y, t_return, CV_NORMAL)
        end if
        t_reached = t_return(1)
        self%t_now = t_reached
        y = self%values
        if (flag == CV_ROOT_RETURN) then
            flag = FCVodeGetRootInfo(self%memory, self%fired)
            root = findloc(self%fired /= 0, .true., dim=1)
            return
        end if
        if (flag == CV_SUCCESS .or. flag == CV_TSTOP_RETURN) return
        self%failed_flag = int(flag)
        call solver_failure(error, "CVODE", t_reached, int(flag), flag_meaning(flag), &
            & self%data%system)

    contains

        !> The max_steps budget in chunks of chunk_steps_default, the watch told between them.
        !> CVode called again after CV_TOO_MUCH_WORK goes on from its step as if it had not
        !> returned (CVODE guide, CVode: the step counter of the limit is per call), so the
        !> steps and the state are those of one call.
        subroutine chunked(status)
            integer(c_int), intent(out) :: status
            integer :: taken, chunk
            real(wp) :: t_start
            integer :: before

            taken = 0
            do
                chunk = min(chunk_steps_default, self%max_steps - taken)
                status = FCVodeSetMaxNumSteps(self%memory, int(chunk, c_long))
                if (check(status, "CVodeSetMaxNumSteps", error)) return
                t_start = t_return(1)
                before = rejected()
                status = FCVode(self%memory, t_out, self%y, t_return, CV_NORMAL)
                taken = taken + chunk
                if (status /= CV_TOO_MUCH_WORK .or. taken >= self%max_steps) exit
                call self%watch%between_chunks(t_start, t_return(1), t_out, chunk, &
                    & rejected() - before)
            end do
        end subroutine chunked

        !> As chunked, one step a call (CVODE's mxstep 1), the dissipated work integrated over
        !> each step as it is taken (integrate_work): CVode goes on after CV_TOO_MUCH_WORK as
        !> if it had not returned, so the steps, the roots and the state are those of one call
        !> with the whole budget (the rows' state columns are the same, to the last bit, as
        !> without the work: docs/design.md §7, "Dissipated work"). The watch is told every
        !> chunk_steps_default steps, as chunked tells it.
        subroutine stepwise(status)
            integer(c_int), intent(out) :: status
            integer :: taken, before
            real(wp) :: t_start

            status = FCVodeSetMaxNumSteps(self%memory, 1_c_long)
            if (check(status, "CVodeSetMaxNumSteps", error)) return
            taken = 0
            t_start = t_return(1)
            before = rejected()
            do
                status = FCVode(self%memory, t_out, self%y, t_return, CV_NORMAL)
                if (status /= CV_SUCCESS .and. status /= CV_TSTOP_RETURN .and. status &
                    & /= CV_ROOT_RETURN .and. status /= CV_TOO_MUCH_WORK) exit
                call self%integrate_work(t_return(1), error)
                if (allocated(error)) return
                if (status /= CV_TOO_MUCH_WORK) exit
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
            ignored_flag = FCVodeGetNumErrTestFails(self%memory, count)
            rejected = int(count(1))
            count(1) = 0
            ignored_flag = FCVodeGetNumNonlinSolvConvFails(self%memory, count)
            rejected = rejected + int(count(1))
        end function rejected
    end subroutine advance

    !> Steps, right-hand sides (own and for difference-quotient Jacobians), Jacobians,
    !> error-test failures.
    function statistics(self) result(counts)
        class(cvode_integrator_type), intent(in) :: self
        type(integrator_statistics_type) :: counts
        integer(c_long) :: count(1), extra(1)
        integer(c_int) :: flag

        if (.not. c_associated(self%memory)) return
        flag = FCVodeGetNumSteps(self%memory, count)
        counts%steps = int(count(1))
        flag = FCVodeGetNumRhsEvals(self%memory, count)
        ! without a linear solver (fixed-point iteration) there are no Jacobians
        extra(1) = 0
        if (associated(self%solver)) flag = FCVodeGetNumLinRhsEvals(self%memory, extra)
        ! and the dissipated powers' evaluations (integrate_work), each an evaluation as one
        ! of the right-hand side's
        counts%functions = int(count(1) + extra(1)) + self%power_evaluations
        count(1) = 0
        if (associated(self%solver)) flag = FCVodeGetNumJacEvals(self%memory, count)
        counts%jacobians = int(count(1))
        flag = FCVodeGetNumErrTestFails(self%memory, count)
        counts%failures = int(count(1))
        flag = FCVodeGetNumGEvals(self%memory, count)
        counts%roots = int(count(1))
        counts%sparse = self%data%sparse
    end function statistics

    !> Free in reverse order of creation.
    subroutine destroy(self)
        class(cvode_integrator_type), intent(inout) :: self
        integer(c_int) :: flag

        if (c_associated(self%memory)) call FCVodeFree(self%memory)
        if (associated(self%solver)) flag = FSUNLinSolFree(self%solver)
        if (c_associated(self%fixed_point)) flag = c_free_nonlinear_solver(self%fixed_point)
        self%fixed_point = c_null_ptr
        if (associated(self%matrix)) call FSUNMatDestroy(self%matrix)
        if (associated(self%y)) call FN_VDestroy(self%y)
        if (associated(self%data%rates)) call FN_VDestroy(self%data%rates)
        if (associated(self%dense)) call FN_VDestroy(self%dense)
        if (c_associated(self%context)) flag = FSUNContext_Free(self%context)
        self%memory = c_null_ptr
        self%context = c_null_ptr
        nullify(self%solver, self%matrix, self%y, self%data%rates, self%data%system, self%dense)
        if (allocated(self%dense_values)) deallocate(self%dense_values)
        if (allocated(self%work)) deallocate(self%work, self%work_end)
        self%data%memory = c_null_ptr
        if (allocated(self%values)) deallocate(self%values)
        if (allocated(self%data%rate_values)) deallocate(self%data%rate_values)
        if (allocated(self%data%blocks)) deallocate(self%data%blocks)
        if (allocated(self%data%pattern%starts)) deallocate(self%data%pattern%starts, &
            & self%data%pattern%rows)
        self%data%sparse = .false.
        if (allocated(self%fired)) deallocate(self%fired)
    end subroutine destroy

    !> The end of CVODE's last step, its tn [s] (integrator_type step_end).
    subroutine step_end(self, t_end, error)
        class(cvode_integrator_type), intent(inout) :: self
        real(wp), intent(out) :: t_end
        type(error_type), allocatable, intent(out) :: error
        real(c_double) :: t_current(1)
        integer(c_int) :: flag

        t_end = 0.0_wp
        flag = FCVodeGetCurrentTime(self%memory, t_current)
        if (check(flag, "CVodeGetCurrentTime", error)) return
        t_end = t_current(1)
    end subroutine step_end

    !> The dissipated powers [W] at time [s] within CVODE's last step, on the state it
    !> interpolates there (CVodeGetDky; integrator_type powers_at).
    subroutine powers_at(self, time, power, error)
        class(cvode_integrator_type), intent(inout) :: self
        real(wp), intent(in) :: time
        real(wp), intent(out) :: power(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag

        power = 0.0_wp
        flag = FCVodeGetDky(self%memory, time, 0_c_int, self%dense)
        if (check(flag, "CVodeGetDky (the state for the dissipated work)", error)) return
        if (self%data%system%powers(time, self%dense_values, power) /= 0) then
            call solver_failure(error, "CVODE", time, -1, "the dissipated power could " &
                & // "not be evaluated", self%data%system)
        end if
    end subroutine powers_at

    !> SUNDIALS' fused vector operations that CVODE uses, on a serial vector (CVODE's own vectors
    !> are clones of its state vector and inherit them, so this comes before CVodeInit): the
    !> Nordsieck array's updates (N_VScaleAddMulti after every step and at order changes,
    !> N_VScaleVectorArray at step-size changes) and the interpolation (N_VLinearCombination,
    !> CVodeGetDky: an event function's y' inside a step, the output's y) in one call each, in
    !> place of one N_VLinearSum or N_VScale per column. Element by element they compute what
    !> those calls compute (y + a x with the same a, x, y; a x alone for a column that is
    !> scaled), so the integration is the same to the last bit. flag: 0, or the first call's
    !> failure.
    subroutine enable_fused_operations(vector, flag)
        type(N_Vector), intent(inout) :: vector
        integer(c_int), intent(out) :: flag

        flag = FN_VEnableLinearCombination_Serial(vector, 1_c_int)
        if (flag == 0) flag = FN_VEnableScaleAddMulti_Serial(vector, 1_c_int)
        if (flag == 0) flag = FN_VEnableScaleVectorArray_Serial(vector, 1_c_int)
    end subroutine enable_fused_operations

    !> What a failure flag of CVODE means (names of the CVODE guide), for messages: SUNDIALS
    !> itself prints nothing (its error file is none).
    pure function flag_meaning(flag) result(text)
        integer(c_int), intent(in) :: flag
        character(len=:), allocatable :: text

        select case (flag)
        case (CV_TOO_MUCH_WORK)
            text = "CV_TOO_MUCH_WORK, max_steps internal steps taken before the next output time"
        case (CV_TOO_MUCH_ACC)
            text = "CV_TOO_MUCH_ACC, the tolerances ask for more accuracy than the arithmetic has"
        case (CV_ERR_FAILURE)
            text = "CV_ERR_FAILURE, the error test failed repeatedly or at the smallest step"
        case (CV_CONV_FAILURE)
            text = "CV_CONV_FAILURE, the corrector failed repeatedly or at the smallest step"
        case default
            text = "see the CVODE guide's return codes"
        end select
    end function flag_meaning

    !> True (and error set) when a SUNDIALS call did not succeed.
    function check(flag, routine, error) result(failed)
        integer(c_int), intent(in) :: flag
        character(len=*), intent(in) :: routine
        type(error_type), allocatable, intent(out) :: error
        logical :: failed

        failed = flag /= 0
        if (failed) call fatal_error(error, "CVODE: " // routine // " returned flag " &
            & // to_text(int(flag)), stat_solver)
    end function check

    integer(c_int) function rhs(t, y, ydot, user_data) result(ierr) &
            & bind(c, name="rollcon_cvode_rhs")
        real(c_double), value :: t
        type(N_Vector), target :: y, ydot
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), ydv(:)

        call c_f_pointer(user_data, data)
        call c_f_pointer(c_array_pointer(c_loc(y)), yv, [data%states])
        call c_f_pointer(c_array_pointer(c_loc(ydot)), ydv, [data%states])
        ierr = int(data%system%ode_rhs(t, yv, ydv), c_int)
    end function rhs

    integer(c_int) function jacobian(t, y, fy, jac, user_data, tmp1, tmp2, tmp3) result(ierr) &
            & bind(c, name="rollcon_cvode_jacobian")
        real(c_double), value :: t
        type(N_Vector) :: y, fy, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), entries(:), matrix(:, :)

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        entries => FSUNDenseMatrix_Data(jac)
        call c_f_pointer(c_loc(entries(1)), matrix, [size(yv), size(yv)])
        ierr = int(data%system%ode_jacobian(t, yv, matrix), c_int)
    end function jacobian

    !> The system's Jacobian, kept over its blocks (entries (i, j) of states of one block,
    !> zeros included, so the pattern KLU analysed stays), as a compressed-column matrix: the
    !> system writes the values straight into KLU's (ode_sparse_jacobian), the pattern is
    !> copied beside them (SUNDIALS zeroes the matrix before each evaluation).
    integer(c_int) function sparse_jacobian(t, y, fy, jac, user_data, tmp1, tmp2, tmp3) &
            & result(ierr) bind(c, name="rollcon_cvode_sparse_jacobian")
        real(c_double), value :: t
        type(N_Vector) :: y, fy, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), values(:), first_value(:)
        integer(c_int64_t), pointer :: rows(:), starts(:), first_index(:)
        integer :: entries, capacity

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(y)
        entries = data%pattern%entries()
        ! SUNDIALS' Fortran interface hands the first element: the arrays by their sizes
        capacity = int(FSUNSparseMatrix_NNZ(jac))
        first_value => FSUNSparseMatrix_Data(jac)
        call c_f_pointer(c_loc(first_value(1)), values, [capacity])
        first_index => FSUNSparseMatrix_IndexValues(jac)
        call c_f_pointer(c_loc(first_index(1)), rows, [capacity])
        first_index => FSUNSparseMatrix_IndexPointers(jac)
        call c_f_pointer(c_loc(first_index(1)), starts, [size(yv) + 1])
        ierr = int(data%system%ode_sparse_jacobian(t, yv, data%pattern%starts, &
            & data%pattern%rows, values(:entries)), c_int)
        if (ierr /= 0) return
        starts(:) = int(data%pattern%starts, c_int64_t)
        rows(:entries) = int(data%pattern%rows, c_int64_t)
    end function sparse_jacobian

    !> Entries of a matrix kept over blocks: the sum of each block's size squared (by
    !> counting: linear in the states).
    pure integer function block_entries(blocks) result(total)
        integer, intent(in) :: blocks(:)
        integer, allocatable :: sizes(:)
        integer :: i, low

        low = minval(blocks)
        allocate(sizes(maxval(blocks) - low + 1), source=0)
        do i = 1, size(blocks)
            sizes(blocks(i) - low + 1) = sizes(blocks(i) - low + 1) + 1
        end do
        total = sum(sizes**2)
    end function block_entries

    integer(c_int) function projection(t, ycur, corr, eps_proj, err, user_data) result(ierr) &
            & bind(c, name="rollcon_cvode_projection")
        real(c_double), value :: t, eps_proj
        type(N_Vector) :: ycur, corr
        type(c_ptr), value :: err
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:), cv(:)

        call c_f_pointer(user_data, data)
        yv => FN_VGetArrayPointer(ycur)
        cv => FN_VGetArrayPointer(corr)
        ! The correction is the system's (exact, whatever eps_proj asks); the error estimate
        ! err, when given, is left as CVODE computed it.
        ierr = int(data%system%project(t, yv, cv), c_int)
    end function projection

    integer(c_int) function events(t, y, gout, user_data) result(ierr) &
            & bind(c, name="rollcon_cvode_events")
        real(c_double), value :: t
        type(N_Vector), target :: y
        real(c_double) :: gout(*)
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        real(c_double), pointer :: yv(:)

        call c_f_pointer(user_data, data)
        call c_f_pointer(c_array_pointer(c_loc(y)), yv, [data%states])
        associate (nroots => data%root_count)
            ! y' at t from CVODE's own polynomial, when the event functions use it: the system
            ! need not evaluate its right-hand side. At the end of the step just taken (most
            ! evaluations) read off its Nordsieck array (step_end_rates: CVodeGetDky's numbers
            ! without its sum over every column). Outside the last step (the start-up check
            ! just past t0) CVODE refuses; then the system works it out itself.
            if (.not. data%roots_use_rates) then
                ierr = int(data%system%roots(t, yv, gout(:nroots)), c_int)
            else if (step_end_rates(data%memory, t, data%rate_values)) then
                ierr = int(data%system%roots(t, yv, gout(:nroots), data%rate_values), c_int)
            else if (FCVodeGetDky(data%memory, t, 1_c_int, data%rates) == CV_SUCCESS) then
                ierr = int(data%system%roots(t, yv, gout(:nroots), data%rate_values), c_int)
            else
                ierr = int(data%system%roots(t, yv, gout(:nroots)), c_int)
            end if
        end associate
    end function events

    !> y'(t) [the state's units / s] into rates (size of the state) when t [s] is exactly t_n,
    !> the end of the step CVODE (memory) just completed: zn[1] (1/h), zn[1] = h y'(t_n) the
    !> Nordsieck array's first-derivative column and h the step taken (CVodeGetLastStep), read
    !> through CVodeGetNonlinearSystemData. It is CVodeGetDky(t_n, 1)'s result to the last bit
    !> (SUNDIALS 6.4.1, cvode.c): there s = (t - t_n)/h = 0, so its sum gives zn[2..q] the
    !> weights j s^(j-1) = 0 and zn[1] the weight 1 (the sum of those zeros and zn[1]'s entry
    !> is that entry, when it is not 0), and scales it by r = 1/h (SUNRpowerI(h, -1), then
    !> N_VScale: each entry times r). Where CVODE calls the event functions (cvRcheck1 at t0,
    !> before any step: CVodeGetLastStep is 0 there; cvRcheck2 and cvRcheck3, after a completed
    !> step) h is the step just taken: CVODE rescales zn and changes h only inside its next
    !> step (cvAdjustParams, the error test and the corrector's failures). False, rates left
    !> as they were, when t is not t_n, before the first step, or when an entry of zn[1] is 0
    !> (CVodeGetDky's sum of zeros then takes its sign from the columns not read here): the
    !> caller then asks CVodeGetDky.
    logical function step_end_rates(memory, t, rates) result(done)
        type(c_ptr), intent(in) :: memory
        real(c_double), intent(in) :: t
        real(c_double), intent(inout) :: rates(:)
        real(c_double) :: t_n(1), gamma(1), rl1(1), h(1), r
        type(c_ptr), target :: ypred, yn, fn, zn1, user_data
        real(c_double), pointer :: values(:)
        integer :: i

        done = .false.
        if (FCVodeGetNonlinearSystemData(memory, t_n, c_loc(ypred), c_loc(yn), c_loc(fn), &
            & gamma, rl1, c_loc(zn1), user_data) /= CV_SUCCESS) return
        if (t /= t_n(1)) return
        if (FCVodeGetLastStep(memory, h) /= CV_SUCCESS) return
        if (h(1) == 0.0_c_double) return
        ! zn[1] is a clone of the state vector: rates' length (N_VGetArrayPointer directly)
        call c_f_pointer(c_array_pointer(zn1), values, [size(rates)])
        do i = 1, size(values)
            if (values(i) == 0.0_c_double) return
        end do
        ! as SUNRpowerI(h, -1) computes it: 1/(1 h), 1 h being h
        r = 1.0_c_double/h(1)
        do i = 1, size(values)
            rates(i) = values(i)*r
        end do
        done = .true.
    end function step_end_rates

end module rollcon_cvode
