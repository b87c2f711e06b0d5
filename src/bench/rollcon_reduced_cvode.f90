! SPDX-License-Identifier: MIT
!> A reduced (minimal-coordinate) ODE as a system CVODE integrates (rollcon_cvode, the same
!> integrator as the full model's): the benchmark's reference and limit. reduced_system_type is
!> what every reduced ODE shares (the full model's run settings, its force stops, an output row
!> of a state); simulate_reduced integrates one with output rows at the full model's times.
!> The rolling disk's (ucon/reduced/, rollcon_reduced_disk_rhs) is reduced_problem_type: the
!> same method, tolerances, Jacobian choice and force stops as the full CVODE runs, its rows in
!> the layout of a one-part model without UCONs (rollcon_output_layout: time, the disk's q and u,
!> energy), the first columns of the full model's rows. The bicycle's is
!> rollcon_reduced_bicycle's.
module rollcon_reduced_cvode
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_force, only : applied_force_type, force_and_moment, force_breakpoints, &
        & force_corners
    use rollcon_run_settings, only : run_settings_type
    use rollcon_dynamic_system, only : ode_system_type
    use rollcon_cvode, only : cvode_integrator_type
    use rollcon_simulation, only : run_summary_type, history_type, status_failed, status_stopped
    use rollcon_output_layout, only : output_layout_type, new_output_layout, coord_x, coord_phi, &
        & coord_xdot, coord_phidot
    use rollcon_reduced_disk_rhs, only : reduced_size, reduced_rate, reduced_jacobian, &
        & reduced_energy, reduced_to_full, full_to_reduced
    implicit none
    private

    public :: reduced_system_type, reduced_problem_type, simulate_reduced

    !> What simulate_reduced needs of a reduced ODE besides its right-hand side
    type, abstract, extends(ode_system_type) :: reduced_system_type
        !> Method, Jacobian, tolerances and step limit (the full model's run settings)
        type(run_settings_type) :: settings
    contains
        !> The columns of its output rows (an energy column among them)
        procedure(row_layout_interface), deferred :: row_layout
        !> The output row of a state
        procedure(row_interface), deferred :: row
        !> Times the integrator must not step over (the force pulses' kinks) [s]
        procedure(stops_interface), deferred :: stops
        !> Among the stops, the inputs' corners, where the integrator also starts again [s]
        procedure :: corners
        !> Why the event function stopped the run, at time [s]
        procedure :: stop_message
    end type reduced_system_type

    abstract interface
        function row_layout_interface(self) result(layout)
            import :: reduced_system_type, output_layout_type
            class(reduced_system_type), intent(in) :: self
            type(output_layout_type) :: layout
        end function row_layout_interface

        function row_interface(self, time, y) result(values)
            import :: reduced_system_type, wp
            class(reduced_system_type), intent(in) :: self
            real(wp), intent(in) :: time, y(:)
            real(wp), allocatable :: values(:)
        end function row_interface

        function stops_interface(self) result(times)
            import :: reduced_system_type, wp
            class(reduced_system_type), intent(in) :: self
            real(wp), allocatable :: times(:)
        end function stops_interface
    end interface

    !> The reduced disk with its loads and solver settings
    type, extends(reduced_system_type) :: reduced_problem_type
        !> (A, C, m, R, g) [kg m^2, kg m^2, kg, m, m/s^2]
        real(wp) :: par(5) = 0.0_wp
        !> Strike forces: along +Y at the top of the rim (rollcon_force's profiles)
        type(applied_force_type), allocatable :: forces(:)
        !> Stop when theta falls below this [rad] (disabled when negative)
        real(wp) :: theta_min = -1.0_wp
        !> Part id of the disk, for the rows' column names
        integer :: part_id = 1
    contains
        procedure :: state_size
        procedure :: pack_state
        procedure :: unpack_state
        procedure :: ode_rhs
        procedure :: ode_jacobian
        procedure :: root_count
        procedure :: roots
        procedure :: failure_text
        procedure :: row_layout => disk_row_layout
        procedure :: row => disk_row
        procedure :: stops => disk_stops
        procedure :: corners => disk_corners
        procedure :: stop_message => disk_stop_message
    end type reduced_problem_type

contains

    !> Integrate the reduced system from y0 at t0 to end_time, a history row every output_step.
    !> The one loop over output times, with its internal procedures (the next force stop, a row)
    !> that share its state.
    subroutine simulate_reduced(problem, y0, t0, end_time, output_step, history, summary, error)
        class(reduced_system_type), intent(inout), target :: problem
        !> The reduced state at t0
        real(wp), intent(in) :: y0(:)
        !> Start, end, output interval [s]
        real(wp), intent(in) :: t0, end_time, output_step
        type(history_type), intent(inout) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(cvode_integrator_type), target :: cvode
        real(wp) :: values(size(y0)), unused(size(y0))
        real(wp), allocatable :: breaks(:), corners(:)
        real(wp) :: t, t_out, start, finish, t_reference
        integer :: k_output, n_output, root
        logical :: have_reference

        breaks = problem%stops()
        ! energy is conserved once the last pulse is over (as in rollcon_simulation)
        t_reference = maxval([t0, breaks])
        breaks = pack(breaks, breaks > t0 .and. breaks < end_time)
        ! a pulse's ends: CVODE starts again there, as the full runs do (rollcon_simulation)
        corners = problem%corners()
        history%layout = problem%row_layout()
        summary%layout = history%layout
        values = y0
        unused = 0.0_wp
        have_reference = .false.
        t = t0
        call record(t)
        call cpu_time(start)
        call cvode%start(problem, problem%settings, t0, values, unused, next_stop(t), error)
        n_output = max(1, ceiling((end_time - t0)/output_step - 1.0e-9_wp))
        k_output = 1
        do while (k_output <= n_output .and. .not. allocated(error))
            t_out = min(t0 + k_output*output_step, end_time)
            ! an output time within the time's round-off after a restart: the same state
            if (t_out - t <= 4.0_wp*epsilon(1.0_wp)*(abs(t) + abs(t_out))) then
                t = t_out
                root = 0
            else
                call cvode%advance(t_out, next_stop(t), t, values, unused, root, error)
            end if
            if (allocated(error)) then
                summary%status = status_failed
                error%message = "reduced ODE: " // error%message
                summary%message = error%message
                exit
            end if
            if (root /= 0) then
                call record(t)
                summary%status = status_stopped
                summary%message = problem%stop_message(t)
                exit
            end if
            if (any(corners == t)) call cvode%restart(t, values, unused, error)
            if (allocated(error)) exit
            if (t < t_out) cycle
            call record(t)
            k_output = k_output + 1
        end do
        call cpu_time(finish)
        summary%cpu_seconds = finish - start
        associate (counts => cvode%statistics())
            summary%steps = counts%steps
            summary%functions = counts%functions
            summary%jacobians = counts%jacobians
        end associate
        call cvode%destroy()

    contains

        !> The next time not to step past: a pulse stop or the end.
        pure function next_stop(time) result(stop_time)
            real(wp), intent(in) :: time
            real(wp) :: stop_time

            stop_time = end_time
            if (any(breaks > time)) stop_time = minval(breaks, mask=breaks > time)
        end function next_stop

        !> A history row and the summary's energy drift (after every pulse).
        subroutine record(time)
            real(wp), intent(in) :: time
            real(wp), allocatable :: row(:)
            real(wp) :: energy

            row = problem%row(time, values)
            energy = row(history%layout%energy_column())
            if (time >= t_reference) then
                if (.not. have_reference) summary%energy_reference = energy
                have_reference = .true.
                summary%energy_drift = max(summary%energy_drift, &
                    & abs(energy - summary%energy_reference)/abs(summary%energy_reference))
            end if
            summary%t_reached = time
            summary%rows = summary%rows + 1
            call history%add(row)
        end subroutine record

    end subroutine simulate_reduced

    !> The inputs' corners among the stops [s], where the integrator starts again with no
    !> history (docs/design.md §7). Default: none.
    function corners(self) result(times)
        class(reduced_system_type), intent(in) :: self
        real(wp), allocatable :: times(:)

        allocate(times(0))
    end function corners

    !> Why the event functions stopped a run at time [s] (a system with event functions says).
    function stop_message(self, time) result(message)
        class(reduced_system_type), intent(in) :: self
        real(wp), intent(in) :: time
        character(len=:), allocatable :: message

        message = "stopped by an event at t = " // to_text(time) // " s"
    end function stop_message

    !> The disk's rows: one part without UCONs (time, q, u, energy).
    function disk_row_layout(self) result(layout)
        class(reduced_problem_type), intent(in) :: self
        type(output_layout_type) :: layout

        layout = new_output_layout([self%part_id], [integer ::])
    end function disk_row_layout

    !> A disk row (t, q, u, E).
    function disk_row(self, time, y) result(values)
        class(reduced_problem_type), intent(in) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), allocatable :: values(:)
        real(wp) :: q(6), u(6)
        type(output_layout_type) :: layout

        layout = self%row_layout()
        allocate(values(layout%columns()))
        call reduced_to_full(y, self%par, q, u)
        values(1) = time
        values(layout%part_column(1, coord_x):layout%part_column(1, coord_phi)) = q
        values(layout%part_column(1, coord_xdot):layout%part_column(1, coord_phidot)) = u
        values(layout%energy_column()) = reduced_energy(y, self%par)
    end function disk_row

    !> The strike pulses' kinks.
    function disk_stops(self) result(times)
        class(reduced_problem_type), intent(in) :: self
        real(wp), allocatable :: times(:)

        if (allocated(self%forces)) then
            times = force_breakpoints(self%forces)
        else
            allocate(times(0))
        end if
    end function disk_stops

    !> The strike pulses' starts and ends (force_corners).
    function disk_corners(self) result(times)
        class(reduced_problem_type), intent(in) :: self
        real(wp), allocatable :: times(:)

        if (allocated(self%forces)) then
            times = force_corners(self%forces)
        else
            allocate(times(0))
        end if
    end function disk_corners

    !> The theta limit's message.
    function disk_stop_message(self, time) result(message)
        class(reduced_problem_type), intent(in) :: self
        real(wp), intent(in) :: time
        character(len=:), allocatable :: message

        message = "theta fell to " // to_text(self%theta_min) // " rad at t = " &
            & // to_text(time) // " s"
    end function disk_stop_message

    !> The strike force along +Y at time t [N] (rollcon_force's profile, the model's forces).
    pure function strike_at(problem, time, state) result(strike)
        class(reduced_problem_type), intent(in) :: problem
        real(wp), intent(in) :: time, state(reduced_size)
        real(wp) :: strike, force(3), moment(3)
        integer :: k

        strike = 0.0_wp
        if (.not. allocated(problem%forces)) return
        if (size(problem%forces) == 0) return
        call force_and_moment(problem%forces, 1, time, [0.0_wp, 0.0_wp, 0.0_wp, state(5), &
            & state(1), state(6)], [(0.0_wp, k = 1, 6)], force, moment)
        strike = force(2)
    end function strike_at

    !> reduced_size: (theta, thetadot, psidot, omega3, psi, phi, X, Y).
    integer function state_size(self)
        class(reduced_problem_type), intent(in) :: self

        state_size = reduced_size
    end function state_size

    !> The reduced state of the disk's (q, u) (rollcon_reduced_disk_rhs); y' is not used (0).
    subroutine pack_state(self, q, u, y, yp)
        class(reduced_problem_type), intent(inout) :: self
        !> The disk's coordinates and rates [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)

        call full_to_reduced(q(:6), u(:6), y)
        yp = 0.0_wp
    end subroutine pack_state

    !> The disk's (q, u) at the reduced state y (rollcon_reduced_disk_rhs).
    subroutine unpack_state(self, time, y, q, u, error)
        class(reduced_problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        call reduced_to_full(y, self%par, q, u)
    end subroutine unpack_state

    !> y' of the reduced ODE; a flat disk (sin theta = 0) is outside it: recoverable (1),
    !> CVODE cuts the step.
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(reduced_problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)

        call reduced_rate(y, self%par, strike_at(self, time, y), ydot)
        ierr = 0
        if (.not. all(ieee_is_finite(ydot))) ierr = 1
    end function ode_rhs

    !> The generated Jacobian of the reduced ODE.
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(reduced_problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)

        call reduced_jacobian(y, self%par, strike_at(self, time, y), matrix)
        ierr = 0
        if (.not. all(ieee_is_finite(matrix))) ierr = 1
    end function ode_jacobian

    !> The theta limit, when set.
    integer function root_count(self)
        class(reduced_problem_type), intent(in) :: self

        root_count = merge(1, 0, self%theta_min >= 0.0_wp)
    end function root_count

    !> theta - theta_min.
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(reduced_problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)

        g(1) = y(1) - self%theta_min
        ierr = 0
    end function roots

    !> No callback keeps a reason: the only failure, a flat disk, is recoverable ("").
    function failure_text(self) result(text)
        class(reduced_problem_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
    end function failure_text

end module rollcon_reduced_cvode
