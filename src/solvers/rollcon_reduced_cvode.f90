! SPDX-License-Identifier: MIT
!> CVODE on the rolling disk's reduced ODE (ucon/reduced/, rollcon_reduced_disk_rhs): the same
!> method, tolerances, Jacobian choice and force stops as the full CVODE runs, output rows at
!> the same times and in the layout of a one-part model without UCONs (rollcon_output_layout:
!> time, the disk's q and u, energy), the first columns of the full model's rows.
module rollcon_reduced_cvode
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_long, c_int64_t, &
        & c_double, c_funloc, c_loc, c_f_pointer, c_associated
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_text, only : to_text
    use rollcon_force, only : applied_force_type, force_and_moment, force_breakpoints
    use rollcon_problem, only : method_bdf, method_adams
    use rollcon_simulation, only : run_summary_type, history_type, status_failed, status_stopped
    use rollcon_output_layout, only : new_output_layout, coord_x, coord_phi, coord_xdot, &
        & coord_phidot
    use rollcon_reduced_disk_rhs, only : reduced_size, reduced_rate, reduced_jacobian, &
        & reduced_energy, reduced_to_full
    use fsundials_context_mod, only : FSUNContext_Create, FSUNContext_Free
    use fsundials_nvector_mod, only : N_Vector, FN_VDestroy, FN_VGetArrayPointer
    use fsundials_matrix_mod, only : SUNMatrix, FSUNMatDestroy
    use fsundials_linearsolver_mod, only : SUNLinearSolver, FSUNLinSolFree
    use fnvector_serial_mod, only : FN_VMake_Serial
    use fsunmatrix_dense_mod, only : FSUNDenseMatrix, FSUNDenseMatrix_Data
    use fsunlinsol_dense_mod, only : FSUNLinSol_Dense
    use fcvode_mod, only : FCVodeCreate, FCVodeInit, FCVodeSStolerances, FCVodeSetUserData, &
        & FCVodeSetLinearSolver, FCVodeSetJacFn, FCVodeSetMaxNumSteps, FCVodeSetStopTime, &
        & FCVode, FCVodeRootInit, FCVodeFree, FCVodeGetNumSteps, FCVodeGetNumRhsEvals, &
        & FCVodeGetNumJacEvals, FCVodeGetNumLinRhsEvals, CV_BDF, CV_ADAMS, CV_NORMAL, &
        & CV_SUCCESS, CV_ROOT_RETURN, CV_TSTOP_RETURN
    implicit none
    private

    public :: reduced_problem_type, simulate_reduced

    !> The reduced disk with its loads and solver settings
    type :: reduced_problem_type
        !> (A, C, m, R, g) [kg m^2, kg m^2, kg, m, m/s^2]
        real(wp) :: par(5) = 0.0_wp
        !> Strike forces: along +Y at the top of the rim (rollcon_force's profiles)
        type(applied_force_type), allocatable :: forces(:)
        !> method_bdf or method_adams
        integer :: method = method_bdf
        !> Newton matrix from the generated Jacobian (true) or CVODE's difference quotients
        logical :: analytic_jacobian = .true.
        real(wp) :: rtol = 1.0e-8_wp, atol = 1.0e-10_wp
        !> Most steps per output interval
        integer :: max_steps = 500000
        !> Stop when theta falls below this [rad] (disabled when negative)
        real(wp) :: theta_min = -1.0_wp
        !> Part id of the disk, for the rows' column names
        integer :: part_id = 1
    end type reduced_problem_type

contains

    !> Integrate the reduced state y0 from t0 to end_time, a history row every output_step.
    !> About 90 lines: CVODE's set-up calls, each checked, and the one loop over output times.
    subroutine simulate_reduced(problem, y0, t0, end_time, output_step, history, summary, error)
        type(reduced_problem_type), intent(inout), target :: problem
        !> (theta, thetadot, psidot, omega3, psi, phi, X, Y) at t0
        real(wp), intent(in) :: y0(reduced_size)
        !> Start, end, output interval [s]
        real(wp), intent(in) :: t0, end_time, output_step
        type(history_type), intent(inout) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(c_ptr) :: context, memory
        type(N_Vector), pointer :: y
        type(SUNMatrix), pointer :: matrix
        type(SUNLinearSolver), pointer :: solver
        real(c_double), target :: values(reduced_size)
        real(c_double) :: t_return(1)
        real(wp), allocatable :: breaks(:)
        real(wp) :: t, t_out, start, finish, t_reference
        integer(c_int) :: flag
        integer :: k_output, n_output
        logical :: have_reference

        if (.not. allocated(problem%forces)) allocate(problem%forces(0))
        breaks = force_breakpoints(problem%forces)
        ! energy is conserved once the last pulse is over (as in rollcon_simulation)
        t_reference = maxval([t0, breaks])
        breaks = pack(breaks, breaks > t0 .and. breaks < end_time)
        history%layout = new_output_layout([problem%part_id], [integer ::], .false.)
        summary%layout = history%layout
        memory = c_null_ptr
        nullify(y, matrix, solver)
        values = y0
        have_reference = .false.
        t = t0
        call record(t)
        call cpu_time(start)
        flag = FSUNContext_Create(c_null_ptr, context)
        if (check(flag, "SUNContext_Create")) return
        y => FN_VMake_Serial(int(reduced_size, c_int64_t), values, context)
        memory = FCVodeCreate(merge(CV_ADAMS, CV_BDF, problem%method == method_adams), context)
        flag = FCVodeInit(memory, c_funloc(rate_callback), t0, y)
        if (check(flag, "CVodeInit")) return
        flag = FCVodeSetUserData(memory, c_loc(problem))
        if (check(flag, "CVodeSetUserData")) return
        flag = FCVodeSStolerances(memory, problem%rtol, problem%atol)
        if (check(flag, "CVodeSStolerances")) return
        flag = FCVodeSetMaxNumSteps(memory, int(problem%max_steps, c_long))
        if (check(flag, "CVodeSetMaxNumSteps")) return
        matrix => FSUNDenseMatrix(int(reduced_size, c_int64_t), int(reduced_size, c_int64_t), &
            & context)
        solver => FSUNLinSol_Dense(y, matrix, context)
        flag = FCVodeSetLinearSolver(memory, solver, matrix)
        if (check(flag, "CVodeSetLinearSolver")) return
        if (problem%analytic_jacobian) then
            flag = FCVodeSetJacFn(memory, c_funloc(jacobian_callback))
            if (check(flag, "CVodeSetJacFn")) return
        end if
        if (problem%theta_min >= 0.0_wp) then
            flag = FCVodeRootInit(memory, 1_c_int, c_funloc(theta_callback))
            if (check(flag, "CVodeRootInit")) return
        end if
        n_output = max(1, ceiling((end_time - t0)/output_step - 1.0e-9_wp))
        k_output = 1
        do while (k_output <= n_output)
            t_out = min(t0 + k_output*output_step, end_time)
            flag = FCVodeSetStopTime(memory, next_stop(t))
            if (check(flag, "CVodeSetStopTime")) return
            flag = FCVode(memory, t_out, y, t_return, CV_NORMAL)
            t = t_return(1)
            if (flag == CV_ROOT_RETURN) then
                call record(t)
                summary%status = status_stopped
                summary%message = "theta fell to " // to_text(problem%theta_min) // " rad at t = " &
                    & // to_text(t) // " s"
                exit
            end if
            if (flag /= CV_SUCCESS .and. flag /= CV_TSTOP_RETURN) then
                summary%status = status_failed
                call fatal_error(error, "reduced ODE: CVODE failed at t = " // to_text(t) &
                    & // " s with flag " // to_text(int(flag)), stat_solver)
                summary%message = error%message
                exit
            end if
            if (t < t_out) cycle
            call record(t)
            k_output = k_output + 1
        end do
        call cpu_time(finish)
        summary%cpu_seconds = finish - start
        call statistics()
        call release()

    contains

        !> The next time not to step past: a pulse stop or the end.
        pure function next_stop(time) result(stop_time)
            real(wp), intent(in) :: time
            real(wp) :: stop_time

            stop_time = end_time
            if (any(breaks > time)) stop_time = minval(breaks, mask=breaks > time)
        end function next_stop

        !> A history row (t, q, u, E) and the summary's energy drift (after every pulse).
        subroutine record(time)
            real(wp), intent(in) :: time
            real(wp) :: q(6), u(6), energy
            real(wp), allocatable :: row(:)

            call reduced_to_full(values, problem%par, q, u)
            energy = reduced_energy(values, problem%par)
            if (time >= t_reference) then
                if (.not. have_reference) summary%energy_reference = energy
                have_reference = .true.
                summary%energy_drift = max(summary%energy_drift, &
                    & abs(energy - summary%energy_reference)/abs(summary%energy_reference))
            end if
            summary%t_reached = time
            summary%q = q
            summary%u = u
            summary%rows = summary%rows + 1
            associate (layout => history%layout)
                allocate(row(layout%columns()))
                row(1) = time
                row(layout%part_column(1, coord_x):layout%part_column(1, coord_phi)) = q
                row(layout%part_column(1, coord_xdot):layout%part_column(1, coord_phidot)) = u
                row(layout%energy_column()) = energy
            end associate
            call history%add(row)
        end subroutine record

        subroutine statistics()
            integer(c_long) :: count(1), extra(1)

            if (.not. c_associated(memory)) return
            flag = FCVodeGetNumSteps(memory, count)
            summary%steps = int(count(1))
            flag = FCVodeGetNumRhsEvals(memory, count)
            flag = FCVodeGetNumLinRhsEvals(memory, extra)
            summary%functions = int(count(1) + extra(1))
            flag = FCVodeGetNumJacEvals(memory, count)
            summary%jacobians = int(count(1))
        end subroutine statistics

        !> True (error set, memory freed) when a SUNDIALS call did not succeed.
        function check(code, routine) result(failed)
            integer(c_int), intent(in) :: code
            character(len=*), intent(in) :: routine
            logical :: failed

            failed = code /= 0
            if (.not. failed) return
            call fatal_error(error, "reduced ODE: " // routine // " returned flag " &
                & // to_text(int(code)), stat_solver)
            call release()
        end function check

        subroutine release()
            integer(c_int) :: status

            if (c_associated(memory)) call FCVodeFree(memory)
            if (associated(solver)) status = FSUNLinSolFree(solver)
            if (associated(matrix)) call FSUNMatDestroy(matrix)
            if (associated(y)) call FN_VDestroy(y)
            if (c_associated(context)) status = FSUNContext_Free(context)
            memory = c_null_ptr
            context = c_null_ptr
            nullify(solver, matrix, y)
        end subroutine release

    end subroutine simulate_reduced

    !> The strike force along +Y at time t [N] (rollcon_force's profile, the model's forces).
    pure function strike_at(problem, time, state) result(strike)
        type(reduced_problem_type), intent(in) :: problem
        real(wp), intent(in) :: time, state(reduced_size)
        real(wp) :: strike, force(3), moment(3)
        integer :: k

        strike = 0.0_wp
        if (size(problem%forces) == 0) return
        call force_and_moment(problem%forces, 1, time, [0.0_wp, 0.0_wp, 0.0_wp, state(5), &
            & state(1), state(6)], [(0.0_wp, k = 1, 6)], force, moment)
        strike = force(2)
    end function strike_at

    integer(c_int) function rate_callback(t, y, ydot, user_data) result(ierr) &
            & bind(c, name="rollcon_reduced_rate")
        real(c_double), value :: t
        type(N_Vector) :: y, ydot
        type(c_ptr), value :: user_data
        type(reduced_problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), ydv(:)

        call c_f_pointer(user_data, problem)
        yv => FN_VGetArrayPointer(y)
        ydv => FN_VGetArrayPointer(ydot)
        call reduced_rate(yv, problem%par, strike_at(problem, t, yv), ydv)
        ! a flat disk (sin theta = 0) is outside the reduced ODE: recoverable, CVODE cuts the step
        ierr = 0
        if (.not. all(ieee_is_finite(ydv))) ierr = 1
    end function rate_callback

    integer(c_int) function jacobian_callback(t, y, fy, jac, user_data, tmp1, tmp2, tmp3) &
            & result(ierr) bind(c, name="rollcon_reduced_jacobian")
        real(c_double), value :: t
        type(N_Vector) :: y, fy, tmp1, tmp2, tmp3
        type(SUNMatrix) :: jac
        type(c_ptr), value :: user_data
        type(reduced_problem_type), pointer :: problem
        real(c_double), pointer :: yv(:), data(:), matrix(:, :)

        call c_f_pointer(user_data, problem)
        yv => FN_VGetArrayPointer(y)
        data => FSUNDenseMatrix_Data(jac)
        call c_f_pointer(c_loc(data(1)), matrix, [reduced_size, reduced_size])
        call reduced_jacobian(yv, problem%par, strike_at(problem, t, yv), matrix)
        ierr = 0
        if (.not. all(ieee_is_finite(matrix))) ierr = 1
    end function jacobian_callback

    integer(c_int) function theta_callback(t, y, gout, user_data) result(ierr) &
            & bind(c, name="rollcon_reduced_theta")
        real(c_double), value :: t
        type(N_Vector) :: y
        real(c_double) :: gout(*)
        type(c_ptr), value :: user_data
        type(reduced_problem_type), pointer :: problem
        real(c_double), pointer :: yv(:)

        call c_f_pointer(user_data, problem)
        yv => FN_VGetArrayPointer(y)
        gout(1) = yv(1) - problem%theta_min
        ierr = 0
    end function theta_callback

end module rollcon_reduced_cvode
