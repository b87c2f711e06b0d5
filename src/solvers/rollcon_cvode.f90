! SPDX-License-Identifier: MIT
!> CVODE on the ODE form: BDF or Adams, dense Newton solves with the analytic Jacobian or
!> CVODE's difference quotients, optional projection onto the constraints, root finding.
module rollcon_cvode
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_long, c_int64_t, &
        & c_double, c_funloc, c_loc, c_f_pointer, c_associated
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type, method_adams, drift_projection
    use fsundials_context_mod, only : FSUNContext_Create, FSUNContext_Free
    use fsundials_nvector_mod, only : N_Vector, FN_VDestroy, FN_VGetArrayPointer
    use fsundials_matrix_mod, only : SUNMatrix, FSUNMatDestroy
    use fsundials_linearsolver_mod, only : SUNLinearSolver, FSUNLinSolFree
    use fnvector_serial_mod, only : FN_VMake_Serial
    use fsunmatrix_dense_mod, only : FSUNDenseMatrix, FSUNDenseMatrix_Data
    use fsunlinsol_dense_mod, only : FSUNLinSol_Dense
    use fcvode_mod, only : FCVodeCreate, FCVodeInit, FCVodeSStolerances, FCVodeSetUserData, &
        & FCVodeSetLinearSolver, FCVodeSetJacFn, FCVodeSetMaxNumSteps, FCVodeSetStopTime, &
        & FCVode, FCVodeRootInit, FCVodeGetRootInfo, FCVodeSetProjFn, FCVodeFree, &
        & FCVodeGetNumSteps, FCVodeGetNumRhsEvals, FCVodeGetNumJacEvals, &
        & FCVodeGetNumLinRhsEvals, FCVodeGetNumErrTestFails, FCVodeGetDky, FCVodeSetErrFile, &
        & FCVodeReInit, &
        & CV_BDF, CV_ADAMS, CV_NORMAL, &
        & CV_SUCCESS, CV_ROOT_RETURN, CV_TSTOP_RETURN, CV_TOO_MUCH_WORK, CV_TOO_MUCH_ACC, &
        & CV_ERR_FAILURE, CV_CONV_FAILURE
    implicit none
    private

    public :: cvode_solver_type

    !> What the callbacks receive as user data: the problem, and what the event function needs
    !> to read the state's derivative off CVODE's interpolating polynomial
    type :: callback_data_type
        type(problem_type), pointer :: problem => null()
        type(c_ptr) :: memory = c_null_ptr
        !> y'(t) from CVodeGetDky, and its storage
        type(N_Vector), pointer :: rates => null()
        real(c_double), allocatable :: rate_values(:)
    end type callback_data_type

    !> One CVODE integration of a problem
    type :: cvode_solver_type
        type(c_ptr) :: context = c_null_ptr
        type(c_ptr) :: memory = c_null_ptr
        !> The flag of the last failed step (0 when none failed)
        integer :: failed_flag = 0
        type(N_Vector), pointer :: y => null()
        type(callback_data_type) :: data
        type(SUNMatrix), pointer :: matrix => null()
        type(SUNLinearSolver), pointer :: solver => null()
        !> Storage behind y
        real(c_double), allocatable :: values(:)
        !> After a root return: non-zero for every event function that fired (its direction)
        integer(c_int), allocatable :: fired(:)
    contains
        procedure :: init
        procedure :: reinit
        procedure :: advance
        procedure :: statistics
        procedure :: destroy
    end type cvode_solver_type

contains

    !> Create CVODE for problem from (t0, y0 = (q, u)), watching the problem's event
    !> functions (problem%root_count() of them).
    subroutine init(self, problem, t0, y0, t_stop, error)
        class(cvode_solver_type), intent(inout), target :: self
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: t0, y0(:), t_stop
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
        lmm = CV_BDF
        if (problem%settings%method == method_adams) lmm = CV_ADAMS
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
        self%data%rates => FN_VMake_Serial(int(size(y0), c_int64_t), self%data%rate_values, &
            & self%context)
        if (.not. associated(self%data%rates)) then
            call fatal_error(error, "CVODE: could not create the derivative vector", stat_solver)
            return
        end if
        self%data%problem => problem
        self%data%memory = self%memory
        flag = FCVodeSetUserData(self%memory, c_loc(self%data))
        if (check(flag, "CVodeSetUserData", error)) return
        flag = FCVodeSStolerances(self%memory, problem%settings%rtol, problem%settings%atol)
        if (check(flag, "CVodeSStolerances", error)) return
        flag = FCVodeSetMaxNumSteps(self%memory, int(problem%settings%max_steps, c_long))
        if (check(flag, "CVodeSetMaxNumSteps", error)) return
        self%matrix => FSUNDenseMatrix(int(size(y0), c_int64_t), int(size(y0), c_int64_t), &
            & self%context)
        self%solver => FSUNLinSol_Dense(self%y, self%matrix, self%context)
        if (.not. associated(self%matrix) .or. .not. associated(self%solver)) then
            call fatal_error(error, "CVODE: could not create the dense linear solver", stat_solver)
            return
        end if
        flag = FCVodeSetLinearSolver(self%memory, self%solver, self%matrix)
        if (check(flag, "CVodeSetLinearSolver", error)) return
        if (problem%settings%analytic_jacobian) then
            flag = FCVodeSetJacFn(self%memory, c_funloc(jacobian))
            if (check(flag, "CVodeSetJacFn", error)) return
        end if
        if (problem%settings%drift == drift_projection .and. problem%ucon_count() > 0) then
            flag = FCVodeSetProjFn(self%memory, c_funloc(projection))
            if (check(flag, "CVodeSetProjFn", error)) return
        end if
        flag = FCVodeSetStopTime(self%memory, t_stop)
        if (check(flag, "CVodeSetStopTime", error)) return
        if (problem%root_count() > 0) then
            flag = FCVodeRootInit(self%memory, int(problem%root_count(), c_int), &
                & c_funloc(events))
            if (check(flag, "CVodeRootInit", error)) return
        end if
    end subroutine init

    !> Start again from (t0, y0 = (q, u)) with the settings, tolerances, callbacks and event
    !> functions of init: after a re-basing has changed the coordinates (CVodeReInit).
    subroutine reinit(self, t0, y0, error)
        class(cvode_solver_type), intent(inout) :: self
        real(wp), intent(in) :: t0, y0(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag

        self%values(:) = y0
        flag = FCVodeReInit(self%memory, t0, self%y)
        if (check(flag, "CVodeReInit", error)) return
    end subroutine reinit

    !> Integrate towards t_out (never past t_stop). On return y holds the state at t_reached;
    !> root is the number of the event function that fired (0 if none).
    subroutine advance(self, problem, t_out, t_stop, t_reached, y, root, error)
        class(cvode_solver_type), intent(inout) :: self
        type(problem_type), intent(inout) :: problem
        real(wp), intent(in) :: t_out, t_stop
        real(wp), intent(out) :: t_reached, y(:)
        integer, intent(out) :: root
        type(error_type), allocatable, intent(out) :: error
        real(c_double) :: t_return(1)
        integer(c_int) :: flag

        root = 0
        flag = FCVodeSetStopTime(self%memory, t_stop)
        if (check(flag, "CVodeSetStopTime", error)) return
        flag = FCVode(self%memory, t_out, self%y, t_return, CV_NORMAL)
        t_reached = t_return(1)
        y = self%values
        if (flag == CV_ROOT_RETURN) then
            if (allocated(self%fired)) deallocate(self%fired)
            allocate(self%fired(problem%root_count()), source=0_c_int)
            flag = FCVodeGetRootInfo(self%memory, self%fired)
            root = findloc(self%fired /= 0, .true., dim=1)
            return
        end if
        if (flag == CV_SUCCESS .or. flag == CV_TSTOP_RETURN) return
        self%failed_flag = int(flag)
        if (allocated(problem%failure)) then
            call fatal_error(error, "CVODE failed at t = " // to_text(t_reached) // " s (flag " &
                & // to_text(int(flag)) // "): " // problem%failure%message, stat_solver)
        else
            call fatal_error(error, "CVODE failed at t = " // to_text(t_reached) &
                & // " s with flag " &
                & // to_text(int(flag)) // ": " // flag_meaning(flag), stat_solver)
        end if
    end subroutine advance

    !> Steps, right-hand sides (own and for difference-quotient Jacobians), Jacobians,
    !> error-test failures.
    subroutine statistics(self, steps, functions, jacobians, failures)
        class(cvode_solver_type), intent(in) :: self
        integer, intent(out) :: steps, functions, jacobians, failures
        integer(c_long) :: count(1), extra(1)
        integer(c_int) :: flag

        flag = FCVodeGetNumSteps(self%memory, count)
        steps = int(count(1))
        flag = FCVodeGetNumRhsEvals(self%memory, count)
        flag = FCVodeGetNumLinRhsEvals(self%memory, extra)
        functions = int(count(1) + extra(1))
        flag = FCVodeGetNumJacEvals(self%memory, count)
        jacobians = int(count(1))
        flag = FCVodeGetNumErrTestFails(self%memory, count)
        failures = int(count(1))
    end subroutine statistics

    !> Free in reverse order of creation.
    subroutine destroy(self)
        class(cvode_solver_type), intent(inout) :: self
        integer(c_int) :: flag

        if (c_associated(self%memory)) call FCVodeFree(self%memory)
        if (associated(self%solver)) flag = FSUNLinSolFree(self%solver)
        if (associated(self%matrix)) call FSUNMatDestroy(self%matrix)
        if (associated(self%y)) call FN_VDestroy(self%y)
        if (associated(self%data%rates)) call FN_VDestroy(self%data%rates)
        if (c_associated(self%context)) flag = FSUNContext_Free(self%context)
        self%memory = c_null_ptr
        self%context = c_null_ptr
        nullify(self%solver, self%matrix, self%y, self%data%rates, self%data%problem)
        self%data%memory = c_null_ptr
        if (allocated(self%values)) deallocate(self%values)
        if (allocated(self%data%rate_values)) deallocate(self%data%rate_values)
        if (allocated(self%fired)) deallocate(self%fired)
    end subroutine destroy

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
        type(N_Vector) :: y, ydot
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), ydv(:)

        call c_f_pointer(user_data, data)
        problem => data%problem
        yv => FN_VGetArrayPointer(y)
        ydv => FN_VGetArrayPointer(ydot)
        ierr = int(problem%ode_rhs(t, yv, ydv), c_int)
    end function rhs

    integer(c_int) function jacobian(t, y, fy, jac, user_data, tmp1, tmp2, tmp3) result(ierr) &
            & bind(c, name="rollcon_cvode_jacobian")
        real(c_double), value :: t
        type(N_Vector) :: y, fy, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), entries(:), matrix(:, :)
        type(error_type), allocatable :: error
        integer :: n

        call c_f_pointer(user_data, data)
        problem => data%problem
        yv => FN_VGetArrayPointer(y)
        entries => FSUNDenseMatrix_Data(jac)
        call c_f_pointer(c_loc(entries(1)), matrix, [size(yv), size(yv)])
        n = problem%eq%n
        call problem%eq%ode_jacobian(t, yv(:n), yv(n + 1:), problem%settings%baumgarte(), &
            & matrix, error)
        ierr = int(problem%keep_failure(error), c_int)
    end function jacobian

    integer(c_int) function projection(t, ycur, corr, eps_proj, err, user_data) result(ierr) &
            & bind(c, name="rollcon_cvode_projection")
        real(c_double), value :: t, eps_proj
        type(N_Vector) :: ycur, corr
        type(c_ptr), value :: err
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), cv(:)
        type(error_type), allocatable :: error
        integer :: n

        call c_f_pointer(user_data, data)
        problem => data%problem
        yv => FN_VGetArrayPointer(ycur)
        cv => FN_VGetArrayPointer(corr)
        n = problem%eq%n
        ! The correction is computed exactly (one mass-weighted step), whatever eps_proj asks;
        ! the error estimate err, when given, is left as CVODE computed it.
        call problem%eq%project(t, yv(:n), yv(n + 1:), cv(:n), cv(n + 1:), error)
        ierr = int(problem%keep_failure(error), c_int)
    end function projection

    integer(c_int) function events(t, y, gout, user_data) result(ierr) &
            & bind(c, name="rollcon_cvode_events")
        real(c_double), value :: t
        type(N_Vector) :: y
        real(c_double) :: gout(*)
        type(c_ptr), value :: user_data
        type(callback_data_type), pointer :: data
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:)
        integer :: n, nroots

        call c_f_pointer(user_data, data)
        problem => data%problem
        yv => FN_VGetArrayPointer(y)
        n = problem%eq%n
        nroots = problem%root_count()
        ! y' = (u, a) at t from CVODE's own polynomial: the normal force without a solve.
        ! Outside the last step (the start-up check just past t0) CVODE refuses; then solve.
        if (FCVodeGetDky(data%memory, t, 1_c_int, data%rates) == CV_SUCCESS) then
            ierr = int(problem%root_values(t, yv(:n), yv(n + 1:), gout(:nroots), &
                & a=data%rate_values(n + 1:)), c_int)
        else
            ierr = int(problem%root_values(t, yv(:n), yv(n + 1:), gout(:nroots)), c_int)
        end if
    end function events

end module rollcon_cvode
