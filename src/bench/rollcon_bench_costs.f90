! SPDX-License-Identifier: MIT
!> Unit costs of the parts of a full-model step, measured in the running process: one ODE
!> right-hand side, one DAE residual, one event-function evaluation (alone, and as CVODE's ODE
!> form and IDA call them), one output row (as the benchmark's runs keep it in memory) and,
!> apart, its CSV line (what `rollcon run` adds; and, for comparison, the same line by Fortran's
!> formatted write, which rollcon_row_text.c replaced). The benchmark multiplies them by a run's
!> counts; what is left of the run's CPU time is SUNDIALS' own work (with the Jacobians and
!> linear solves).
module rollcon_bench_costs
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_dae, only : dae_size, dae_residual
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_speeds_form, only : speeds_form_type
    use rollcon_job, only : job_type
    use rollcon_simulation, only : history_type
    use rollcon_output_layout, only : output_layout_type
    use rollcon_output_rows, only : output_layout, output_row
    use rollcon_csv_writer, only : csv_writer_type, fortran_row_text
    implicit none
    private

    public :: part_costs_type, measure_part_costs

    !> CPU seconds of one evaluation of each part [s]
    type :: part_costs_type
        real(wp) :: rhs = 0.0_wp, residual = 0.0_wp, root = 0.0_wp
        !> One right-hand side in independent speeds (formulation 'maggi': the dependent speeds
        !> solved, then the saddle-point system)
        real(wp) :: rhs_speeds = 0.0_wp
        !> The event functions as the integrators call them: given the accelerations (CVODE's
        !> ODE form: y' from its polynomial, whose interpolation is SUNDIALS' own work) and
        !> given the multipliers (IDA: its state holds them); root is the evaluation alone,
        !> with a saddle-point solve, as in independent speeds
        real(wp) :: root_given_rates = 0.0_wp, root_given_multipliers = 0.0_wp
        !> One output row as the benchmark's runs make it (no file) and one CSV line of it
        real(wp) :: output = 0.0_wp, csv_line = 0.0_wp
        !> The same row's text by Fortran's formatted write (es24.16e3), no file
        real(wp) :: fortran_line = 0.0_wp
    end type part_costs_type

contains

    !> Mean CPU time of count evaluations of each part at the job's start (its model built with
    !> its routine); the output rows' CSV lines go to scratch_csv (deleted afterwards).
    subroutine measure_part_costs(job, count, scratch_csv, costs, error)
        type(job_type), intent(inout) :: job
        integer, intent(in) :: count
        character(len=*), intent(in) :: scratch_csv
        type(part_costs_type), intent(out) :: costs
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(speeds_form_type) :: speeds
        type(history_type) :: history
        type(csv_writer_type) :: csv
        type(output_layout_type) :: layout
        procedure(ucosub_interface), pointer :: routine
        real(wp) :: start, finish, checksum
        real(wp), allocatable :: g(:), q0(:), u0(:)
        real(wp), allocatable :: y(:), ydot(:), yd(:), ypd(:), r(:)
        character(len=:), allocatable :: report
        integer :: i, ierr, unit, n

        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        n = size(q0)
        layout = output_layout(problem)
        call ode%init(problem)
        allocate(g(problem%root_count()))
        y = [q0, u0]
        allocate(ydot(size(y)))
        checksum = 0.0_wp
        call cpu_time(start)
        do i = 1, count
            ierr = ode%ode_rhs(0.0_wp, y, ydot)
            checksum = checksum + ydot(n + 1)
        end do
        call cpu_time(finish)
        costs%rhs = (finish - start)/count
        allocate(yd(dae_size(problem%eq)), ypd(dae_size(problem%eq)), r(dae_size(problem%eq)), &
            & source=0.0_wp)
        yd(:2*n) = y
        ypd(:2*n) = ydot
        call cpu_time(start)
        do i = 1, count
            call dae_residual(problem%eq, 0.0_wp, yd, ypd, r, error)
            if (allocated(error)) return
            checksum = checksum + r(1)
        end do
        call cpu_time(finish)
        costs%residual = (finish - start)/count
        call cpu_time(start)
        do i = 1, count
            ierr = problem%root_values(0.0_wp, q0, u0, g)
            checksum = checksum + sum(g)
        end do
        call cpu_time(finish)
        costs%root = (finish - start)/count
        call problem%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        call cpu_time(start)
        do i = 1, count
            ierr = problem%root_values(0.0_wp, q0, u0, g, a=problem%a)
            checksum = checksum + sum(g)
        end do
        call cpu_time(finish)
        costs%root_given_rates = (finish - start)/count
        call cpu_time(start)
        do i = 1, count
            ierr = problem%root_values(0.0_wp, q0, u0, g, lambda=problem%lambda)
            checksum = checksum + sum(g)
        end do
        call cpu_time(finish)
        costs%root_given_multipliers = (finish - start)/count
        ! what rollcon_simulation's record does for a row: accelerations, then the row
        call cpu_time(start)
        do i = 1, count
            call problem%accelerations(0.0_wp, q0, u0, error)
            if (allocated(error)) return
            call history%add(output_row(problem, layout, 0.0_wp, q0, u0))
        end do
        call cpu_time(finish)
        costs%output = (finish - start)/count
        ! and, for `rollcon run`, the row's CSV line
        call csv%open(scratch_csv, layout%header(), error)
        if (allocated(error)) return
        call cpu_time(start)
        do i = 1, count
            call csv%write_row(history%rows(:, i), error)
            if (allocated(error)) return
        end do
        call cpu_time(finish)
        call csv%close()
        costs%csv_line = (finish - start)/count
        call cpu_time(start)
        do i = 1, count
            checksum = checksum + len(fortran_row_text(history%rows(:, i)))
        end do
        call cpu_time(finish)
        costs%fortran_line = (finish - start)/count
        ! the right-hand side in independent speeds, on the same model and start
        call problem%prepare(error)
        if (allocated(error)) return
        call speeds%init(problem)
        call problem%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        deallocate(y, ydot)
        allocate(y(speeds%state_size()), ydot(speeds%state_size()))
        call speeds%pack_state(q0, u0, y, ydot)
        call cpu_time(start)
        do i = 1, count
            ierr = speeds%ode_rhs(0.0_wp, y, ydot)
            checksum = checksum + ydot(n + 1)
        end do
        call cpu_time(finish)
        costs%rhs_speeds = (finish - start)/count
        open(newunit=unit, file=scratch_csv, status="old", iostat=ierr)
        if (ierr == 0) close(unit, status="delete")
        ! keep the loops from being optimised away
        if (checksum /= checksum) costs%rhs = -1.0_wp
        call speeds%release()
    end subroutine measure_part_costs

end module rollcon_bench_costs
