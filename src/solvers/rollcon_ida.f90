! SPDX-License-Identifier: MIT
!> IDA on the DAE form: constraints enforced directly, multipliers excluded from the error
!> test, dense Newton solves with the analytic Jacobian or IDA's difference quotients.
module rollcon_ida
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_long, c_int64_t, &
        & c_double, c_funloc, c_loc, c_f_pointer, c_associated
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_dae, only : dae_residual, dae_jacobian, dae_differential
    use fsundials_context_mod, only : FSUNContext_Create, FSUNContext_Free
    use fsundials_types_mod, only : SUNTRUE
    use fsundials_nvector_mod, only : N_Vector, FN_VDestroy, FN_VGetArrayPointer
    use fsundials_matrix_mod, only : SUNMatrix, FSUNMatDestroy
    use fsundials_linearsolver_mod, only : SUNLinearSolver, FSUNLinSolFree
    use fnvector_serial_mod, only : FN_VMake_Serial
    use fsunmatrix_dense_mod, only : FSUNDenseMatrix, FSUNDenseMatrix_Data
    use fsunlinsol_dense_mod, only : FSUNLinSol_Dense
    use fida_mod, only : FIDACreate, FIDAInit, FIDASVtolerances, FIDASetUserData, &
        & FIDASetLinearSolver, FIDASetJacFn, FIDASetMaxNumSteps, FIDASetStopTime, FIDASolve, &
        & FIDARootInit, FIDAGetRootInfo, FIDASetId, FIDASetSuppressAlg, FIDAFree, FIDAReInit, &
        & FIDAGetNumSteps, FIDAGetNumResEvals, FIDAGetNumJacEvals, FIDAGetNumLinResEvals, &
        & FIDAGetNumErrTestFails, FIDASetErrFile, IDA_NORMAL, IDA_SUCCESS, IDA_ROOT_RETURN, &
        & IDA_TSTOP_RETURN, IDA_TOO_MUCH_WORK, IDA_TOO_MUCH_ACC, IDA_ERR_FAIL, IDA_CONV_FAIL
    implicit none
    private

    public :: ida_solver_type

    !> One IDA integration of a problem
    type :: ida_solver_type
        type(c_ptr) :: context = c_null_ptr
        type(c_ptr) :: memory = c_null_ptr
        !> The flag of the last failed step (0 when none failed)
        integer :: failed_flag = 0
        type(N_Vector), pointer :: y => null(), yp => null(), id => null()
        type(SUNMatrix), pointer :: matrix => null()
        type(SUNLinearSolver), pointer :: solver => null()
        type(N_Vector), pointer :: tolerances => null()
        !> Storage behind y, y', the id vector and the absolute tolerances
        real(c_double), allocatable :: values(:), rates(:), kinds(:), absolute(:)
        !> After a root return: non-zero for every event function that fired (its direction)
        integer(c_int), allocatable :: fired(:)
    contains
        procedure :: init
        procedure :: reinit
        procedure :: advance
        procedure :: statistics
        procedure :: destroy
    end type ida_solver_type

contains

    !> Create IDA from consistent (t0, y0, yp0), watching the problem's event functions
    !> (problem%root_count() of them).
    subroutine init(self, problem, t0, y0, yp0, t_stop, error)
        class(ida_solver_type), intent(inout), target :: self
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: t0, y0(:), yp0(:), t_stop
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag
        integer(c_int64_t) :: n

        n = size(y0)
        self%values = y0
        self%rates = yp0
        self%kinds = dae_differential(problem%eq)
        ! The multipliers are forces, not states: they are out of the error test, and their
        ! absolute tolerance is set on their own scale (1e-3 of the largest at the start) so
        ! that Newton's convergence test does not ask them for digits an index-2 DAE cannot
        ! give (with atol on them, IDA fails to converge at tight tolerances).
        self%absolute = merge(problem%settings%atol, &
            & max(1.0e-3_wp*maxval(abs(y0), mask=self%kinds == 0.0_wp), problem%settings%atol), &
            & self%kinds == 1.0_wp)
        flag = FSUNContext_Create(c_null_ptr, self%context)
        if (check(flag, "SUNContext_Create", error)) return
        self%y => FN_VMake_Serial(n, self%values, self%context)
        self%yp => FN_VMake_Serial(n, self%rates, self%context)
        self%id => FN_VMake_Serial(n, self%kinds, self%context)
        self%tolerances => FN_VMake_Serial(n, self%absolute, self%context)
        if (.not. (associated(self%y) .and. associated(self%yp) .and. associated(self%id) &
            & .and. associated(self%tolerances))) then
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
        flag = FIDASetUserData(self%memory, c_loc(problem))
        if (check(flag, "IDASetUserData", error)) return
        flag = FIDASVtolerances(self%memory, problem%settings%rtol, self%tolerances)
        if (check(flag, "IDASVtolerances", error)) return
        flag = FIDASetMaxNumSteps(self%memory, int(problem%settings%max_steps, c_long))
        if (check(flag, "IDASetMaxNumSteps", error)) return
        ! Index 2: the multipliers are algebraic and kept out of the local error test.
        flag = FIDASetId(self%memory, self%id)
        if (check(flag, "IDASetId", error)) return
        flag = FIDASetSuppressAlg(self%memory, SUNTRUE)
        if (check(flag, "IDASetSuppressAlg", error)) return
        self%matrix => FSUNDenseMatrix(n, n, self%context)
        self%solver => FSUNLinSol_Dense(self%y, self%matrix, self%context)
        if (.not. associated(self%matrix) .or. .not. associated(self%solver)) then
            call fatal_error(error, "IDA: could not create the dense linear solver", stat_solver)
            return
        end if
        flag = FIDASetLinearSolver(self%memory, self%solver, self%matrix)
        if (check(flag, "IDASetLinearSolver", error)) return
        if (problem%settings%analytic_jacobian) then
            flag = FIDASetJacFn(self%memory, c_funloc(jacobian))
            if (check(flag, "IDASetJacFn", error)) return
        end if
        flag = FIDASetStopTime(self%memory, t_stop)
        if (check(flag, "IDASetStopTime", error)) return
        if (problem%root_count() > 0) then
            flag = FIDARootInit(self%memory, int(problem%root_count(), c_int), &
                & c_funloc(events))
            if (check(flag, "IDARootInit", error)) return
        end if
    end subroutine init

    !> Start again from consistent (t0, y0, yp0) with the settings, tolerances, callbacks and
    !> event functions of init: after a re-basing has changed the coordinates (IDAReInit).
    subroutine reinit(self, t0, y0, yp0, error)
        class(ida_solver_type), intent(inout) :: self
        real(wp), intent(in) :: t0, y0(:), yp0(:)
        type(error_type), allocatable, intent(out) :: error
        integer(c_int) :: flag

        self%values(:) = y0
        self%rates(:) = yp0
        flag = FIDAReInit(self%memory, t0, self%y, self%yp)
        if (check(flag, "IDAReInit", error)) return
    end subroutine reinit

    !> Integrate towards t_out (never past t_stop); y, yp at t_reached; root fired (0 if none).
    subroutine advance(self, problem, t_out, t_stop, t_reached, y, yp, root, error)
        class(ida_solver_type), intent(inout) :: self
        type(problem_type), intent(inout) :: problem
        real(wp), intent(in) :: t_out, t_stop
        real(wp), intent(out) :: t_reached, y(:), yp(:)
        integer, intent(out) :: root
        type(error_type), allocatable, intent(out) :: error
        real(c_double) :: t_return(1)
        integer(c_int) :: flag

        root = 0
        flag = FIDASetStopTime(self%memory, t_stop)
        if (check(flag, "IDASetStopTime", error)) return
        flag = FIDASolve(self%memory, t_out, t_return, self%y, self%yp, IDA_NORMAL)
        t_reached = t_return(1)
        y = self%values
        yp = self%rates
        if (flag == IDA_ROOT_RETURN) then
            if (allocated(self%fired)) deallocate(self%fired)
            allocate(self%fired(problem%root_count()), source=0_c_int)
            flag = FIDAGetRootInfo(self%memory, self%fired)
            root = findloc(self%fired /= 0, .true., dim=1)
            return
        end if
        if (flag == IDA_SUCCESS .or. flag == IDA_TSTOP_RETURN) return
        self%failed_flag = int(flag)
        if (allocated(problem%failure)) then
            call fatal_error(error, "IDA failed at t = " // to_text(t_reached) // " s (flag " &
                & // to_text(int(flag)) // "): " // problem%failure%message, stat_solver)
        else
            call fatal_error(error, "IDA failed at t = " // to_text(t_reached) // " s with flag " &
                & // to_text(int(flag)) // ": " // flag_meaning(flag), stat_solver)
        end if
    end subroutine advance

    !> Steps, residuals (own and for difference-quotient Jacobians), Jacobians, test failures.
    subroutine statistics(self, steps, functions, jacobians, failures)
        class(ida_solver_type), intent(in) :: self
        integer, intent(out) :: steps, functions, jacobians, failures
        integer(c_long) :: count(1), extra(1)
        integer(c_int) :: flag

        flag = FIDAGetNumSteps(self%memory, count)
        steps = int(count(1))
        flag = FIDAGetNumResEvals(self%memory, count)
        flag = FIDAGetNumLinResEvals(self%memory, extra)
        functions = int(count(1) + extra(1))
        flag = FIDAGetNumJacEvals(self%memory, count)
        jacobians = int(count(1))
        flag = FIDAGetNumErrTestFails(self%memory, count)
        failures = int(count(1))
    end subroutine statistics

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

    !> Free in reverse order of creation.
    subroutine destroy(self)
        class(ida_solver_type), intent(inout) :: self
        integer(c_int) :: flag

        if (c_associated(self%memory)) call FIDAFree(self%memory)
        if (associated(self%solver)) flag = FSUNLinSolFree(self%solver)
        if (associated(self%matrix)) call FSUNMatDestroy(self%matrix)
        if (associated(self%tolerances)) call FN_VDestroy(self%tolerances)
        if (associated(self%id)) call FN_VDestroy(self%id)
        if (associated(self%yp)) call FN_VDestroy(self%yp)
        if (associated(self%y)) call FN_VDestroy(self%y)
        if (c_associated(self%context)) flag = FSUNContext_Free(self%context)
        self%memory = c_null_ptr
        self%context = c_null_ptr
        nullify(self%solver, self%matrix, self%y, self%yp, self%id, self%tolerances)
        if (allocated(self%fired)) deallocate(self%fired)
    end subroutine destroy

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
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), ypv(:), rv(:)
        type(error_type), allocatable :: error

        call c_f_pointer(user_data, problem)
        yv => FN_VGetArrayPointer(y)
        ypv => FN_VGetArrayPointer(yp)
        rv => FN_VGetArrayPointer(r)
        call dae_residual(problem%eq, t, yv, ypv, rv, error)
        ierr = int(problem%keep_failure(error), c_int)
    end function residual

    integer(c_int) function jacobian(t, cj, y, yp, r, jac, user_data, tmp1, tmp2, tmp3) &
            & result(ierr) bind(c, name="rollcon_ida_jacobian")
        real(c_double), value :: t, cj
        type(N_Vector) :: y, yp, r, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), ypv(:), data(:), matrix(:, :)
        type(error_type), allocatable :: error

        call c_f_pointer(user_data, problem)
        yv => FN_VGetArrayPointer(y)
        ypv => FN_VGetArrayPointer(yp)
        data => FSUNDenseMatrix_Data(jac)
        call c_f_pointer(c_loc(data(1)), matrix, [size(yv), size(yv)])
        call dae_jacobian(problem%eq, t, cj, yv, ypv, matrix, error)
        ierr = int(problem%keep_failure(error), c_int)
    end function jacobian

    integer(c_int) function events(t, y, yp, gout, user_data) result(ierr) &
            & bind(c, name="rollcon_ida_events")
        real(c_double), value :: t
        type(N_Vector) :: y, yp
        real(c_double) :: gout(*)
        type(c_ptr), value :: user_data
        type(problem_type), pointer :: problem
        real(c_double), pointer :: yv(:)
        integer :: n, nroots

        call c_f_pointer(user_data, problem)
        yv => FN_VGetArrayPointer(y)
        n = problem%eq%n
        nroots = problem%root_count()
        ierr = int(problem%root_values(t, yv(:n), yv(n + 1:2*n), gout(:nroots), &
            & yv(2*n + 1:2*n + problem%eq%nc)), c_int)
    end function events

end module rollcon_ida
