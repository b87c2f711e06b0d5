! SPDX-License-Identifier: MIT
!> The benchmark bicycle's reduced ODE (the Whipple bicycle of Meijaard et al. 2007 in minimal
!> coordinates, ucon/reduced/bicycle.py): the limit and reference of the benchmark on
!> data/bicycle.adm. Its parameters are the table the dataset is written from
!> (data/bicycle/benchmark.txt, read here); its state y = (roll, steer, roll rate, steer rate,
!> rear wheel rate, yaw, x, y) of the paper's axes (x forward, y right, z down) [rad, rad/s, m]:
!> the pitch is solved from the front contact's condition at each evaluation, the dependent
!> speeds (yaw, pitch, front wheel rates) from the front contact's no-slip, and Kane's equations
!> of the six speeds (rollcon_reduced_bicycle_rhs) are projected on the independent ones.
!>
!> The quantities compared with the full model are the roll and steer angles [rad] and the rear
!> contact point's ground position [m], in the dataset's axes (x forward, y left, z up): roll
!> (> 0 leaning to the right) is the rear wheel's theta - pi/2; steer is the front frame's turn
!> relative to the rear frame about the steer axis (pointing down and forward, > 0 turning
!> right); the rear contact point is the rear wheel's lowest rim point.
module rollcon_reduced_bicycle
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error, input_error, stat_io, stat_input
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix
    use rollcon_run_settings, only : run_settings_type
    use rollcon_force, only : pulse_stops
    use rollcon_simulation, only : run_summary_type, history_type
    use rollcon_output_layout, only : output_layout_type, new_output_layout, name_length, &
        & coord_x, coord_y, coord_z, coord_psi, coord_theta, coord_phi
    use rollcon_reduced_bicycle_rhs, only : bicycle_parameter_count, bicycle_contact_height, &
        & bicycle_constraint, bicycle_terms, bicycle_contact_velocity, bicycle_energy
    use rollcon_reduced_cvode, only : reduced_system_type, simulate_reduced
    implicit none
    private

    public :: bicycle_table_type, read_bicycle_table, bicycle_state_size, bicycle_pitch
    public :: bicycle_rate, reduced_bicycle_type, simulate_reduced_bicycle, bicycle_measures
    public :: bicycle_distance, bicycle_measure_count, bicycle_start

    !> Reduced states: roll, steer, roll rate, steer rate, rear wheel rate, yaw, x, y
    integer, parameter :: bicycle_state_size = 8
    !> Quantities compared: roll, steer [rad], the rear contact's X, Y [m]
    integer, parameter :: bicycle_measure_count = 4
    !> The part ids of data/bicycle/write_adm.py's datasets: rear wheel, rear frame, front frame
    integer, parameter :: rear_wheel_id = 2, rear_frame_id = 3, front_frame_id = 4
    !> The speeds of rollcon_reduced_bicycle_rhs: dependent (yaw, pitch, front wheel rates) and
    !> independent (roll, rear wheel, steer rates)
    integer, parameter :: dependent(3) = [1, 3, 6], independent(3) = [2, 4, 5]
    !> Newton's iterations on the pitch: at most, and the step below which it has converged
    !> (the next step would be its square's size, below a rounding) [rad]
    integer, parameter :: most_pitch_iterations = 30
    real(wp), parameter :: pitch_step_converged = 1.0e-10_wp
    !> The table's names: Meijaard et al.'s Table 1 in the order of par
    !> (rollcon_reduced_bicycle_rhs), then the run's; and the unit each is written in
    character(len=*), parameter :: table_names(bicycle_parameter_count + 6) = &
        & [character(len=11) :: "w", "c", "lambda", "g", "r_R", "m_R", "I_Rxx", "I_Ryy", "x_B", &
        & "z_B", "m_B", "I_Bxx", "I_Byy", "I_Bzz", "I_Bxz", "x_H", "z_H", "m_H", "I_Hxx", &
        & "I_Hyy", "I_Hzz", "I_Hxz", "r_F", "m_F", "I_Fxx", "I_Fyy", "v", "push", "push_time", &
        & "push_length", "end_time", "steps"]
    character(len=*), parameter :: table_units(bicycle_parameter_count + 6) = &
        & [character(len=6) :: "m", "m", "rad", "m/s^2", "m", "kg", "kg m^2", "kg m^2", "m", &
        & "m", "kg", "kg m^2", "kg m^2", "kg m^2", "kg m^2", "m", "m", "kg", "kg m^2", &
        & "kg m^2", "kg m^2", "kg m^2", "m", "kg", "kg m^2", "kg m^2", "m/s", "N s", "s", "s", &
        & "s", "1"]

    !> A bicycle's table (data/bicycle/benchmark.txt documents its format)
    type :: bicycle_table_type
        !> Meijaard et al.'s Table 1, in the order of rollcon_reduced_bicycle_rhs's par [SI]
        real(wp) :: par(bicycle_parameter_count) = 0.0_wp
        !> Forward speed at the start [m/s]
        real(wp) :: speed = 0.0_wp
        !> The push: its impulse [N s], start [s] and length [s] (a half-sine pulse)
        real(wp) :: push = 0.0_wp, push_time = 0.0_wp, push_length = 1.0_wp
        !> The run: end time [s] and output steps
        real(wp) :: end_time = 0.0_wp
        integer :: steps = 0
    end type bicycle_table_type

    !> The reduced bicycle as CVODE integrates it
    type, extends(reduced_system_type) :: reduced_bicycle_type
        type(bicycle_table_type) :: table
    contains
        procedure :: state_size
        procedure :: pack_state
        procedure :: unpack_state
        procedure :: ode_rhs
        procedure :: ode_jacobian
        procedure :: root_count
        procedure :: roots
        procedure :: failure_text
        procedure :: row_layout
        procedure :: row
        procedure :: stops
        procedure :: corners
    end type reduced_bicycle_type

contains

    !> Read a bicycle's table: `name value unit` lines, `#` comments, each name once, every
    !> name of Meijaard et al.'s Table 1 and of the run (v, push, push_time, push_length,
    !> end_time, steps) present, lambda in rad or deg. Refusals name the file and line.
    subroutine read_bicycle_table(path, table, error)
        character(len=*), intent(in) :: path
        type(bicycle_table_type), intent(out) :: table
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: line
        character(len=64) :: name, written, unit_text
        logical :: seen(size(table_names))
        real(wp) :: value
        integer :: unit, stat, number, k, first, second

        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot read the bicycle's table", stat_io)
            return
        end if
        seen = .false.
        number = 0
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            number = number + 1
            if (index(line, "#") > 0) line = line(:index(line, "#") - 1)
            if (len_trim(line) == 0) cycle
            line = adjustl(line)
            first = index(line, " ")
            name = line(:first - 1)
            line = adjustl(line(first:))
            second = index(line, " ")
            written = line(:second - 1)
            unit_text = adjustl(line(second:))
            read(written, *, iostat=stat) value
            if (stat /= 0 .or. len_trim(unit_text) == 0 .or. .not. ieee_is_finite(value)) then
                call input_error(error, path, number, trim(name), "expected 'name value " &
                    & // "unit' with a finite number")
                exit
            end if
            if (trim(name) == "lambda" .and. trim(unit_text) == "deg") then
                value = value*pi/180.0_wp
                unit_text = "rad"
            end if
            k = findloc(table_names, name(:11), 1)
            if (k == 0 .or. len_trim(name) > 11) then
                call input_error(error, path, number, trim(name), "is not a parameter of the " &
                    & // "bicycle's table (data/bicycle/benchmark.txt)")
                exit
            end if
            if (seen(k)) then
                call input_error(error, path, number, trim(name), "is given twice")
                exit
            end if
            seen(k) = .true.
            if (trim(unit_text) /= trim(table_units(k))) then
                call input_error(error, path, number, trim(name), "is in " &
                    & // trim(table_units(k)) // ", got '" // trim(unit_text) // "'")
                exit
            end if
            select case (k - bicycle_parameter_count)
            case (:0)
                table%par(k) = value
            case (1)
                table%speed = value
            case (2)
                table%push = value
            case (3)
                table%push_time = value
            case (4)
                table%push_length = value
            case (5)
                table%end_time = value
            case (6)
                table%steps = nint(value)
            end select
        end do
        close(unit)
        if (allocated(error)) return
        if (.not. all(seen)) then
            k = findloc(seen, .false., 1)
            call fatal_error(error, path // ": missing " // trim(table_names(k)), stat_input)
            return
        end if
        if (.not. (table%push_length > 0.0_wp .and. table%end_time > 0.0_wp &
            & .and. table%steps > 0)) call fatal_error(error, path // ": push_length, " &
            & // "end_time and steps must be positive", stat_input)
    end subroutine read_bicycle_table

    !> The pitch [rad] that puts the front contact on the ground at this roll and steer
    !> (Newton's method from the upright reference's 0); NaN when it does not converge.
    pure function bicycle_pitch(roll, steer, par) result(pitch)
        real(wp), intent(in) :: roll, steer, par(bicycle_parameter_count)
        real(wp) :: pitch, height, slope, step
        integer :: k

        pitch = 0.0_wp
        do k = 1, most_pitch_iterations
            call bicycle_contact_height([0.0_wp, roll, pitch, steer], par, height, slope)
            step = height/slope
            pitch = pitch - step
            if (abs(step) <= pitch_step_converged) return
        end do
        pitch = ieee_value(pitch, ieee_quiet_nan)
    end function bicycle_pitch

    !> y' of the reduced bicycle at y (module header), with the push on the rear frame [N]
    !> along the dataset's +Y; speeds (when given) gets the six speeds of
    !> rollcon_reduced_bicycle_rhs and angles the four angles. Non-finite where the pitch has no
    !> solution or the contact conditions are singular.
    pure subroutine bicycle_rate(y, par, push, rate, speeds, angles)
        real(wp), intent(in) :: y(bicycle_state_size), par(bicycle_parameter_count), push
        real(wp), intent(out) :: rate(bicycle_state_size)
        real(wp), intent(out), optional :: speeds(6), angles(4)
        real(wp) :: at(4), u(6), mass(6, 6), forcing(6), constraint(3, 6), constraint_rate(3)
        real(wp) :: lu(3, 3), solved(3, 4), shift(6), transfer(6, 3), reduced(3, 3)
        real(wp) :: reduced_force(3), accelerations(3), velocity(2), dependent_shift(3)
        integer :: pivots(3), i, j

        at = [y(6), y(1), bicycle_pitch(y(1), y(2), par), y(2)]
        u = 0.0_wp
        u(independent) = [y(3), y(5), y(4)]
        call bicycle_constraint(at, par, constraint)
        ! dependent speeds and Kane's nonholonomic partial velocities: B_dep X = -B_ind
        lu = constraint(:, dependent)
        call factor3(lu, pivots)
        solved(:, 1:3) = -constraint(:, independent)
        solved(:, 4) = matmul(solved(:, 1:3), u(independent))
        do j = 1, 4
            call solve3(lu, pivots, solved(:, j))
        end do
        u(dependent) = solved(:, 4)
        call bicycle_terms(at, u, par, push, mass, forcing, constraint_rate)
        do j = 1, 6
            do i = j + 1, 6
                mass(i, j) = mass(j, i)
            end do
        end do
        ! u' = transfer u'_ind + shift, shift the dependent accelerations B u' + B' u = 0 needs
        ! at u'_ind = 0
        transfer = 0.0_wp
        do i = 1, 3
            transfer(independent(i), i) = 1.0_wp
            transfer(dependent(i), :) = solved(i, 1:3)
        end do
        dependent_shift = -constraint_rate
        call solve3(lu, pivots, dependent_shift)
        shift = 0.0_wp
        shift(dependent) = dependent_shift
        reduced = matmul(transpose(transfer), matmul(mass, transfer))
        reduced_force = matmul(transpose(transfer), forcing - matmul(mass, shift))
        call factor3(reduced, pivots)
        accelerations = reduced_force
        call solve3(reduced, pivots, accelerations)
        call bicycle_contact_velocity(at, u, par, velocity)
        rate = [y(3), y(4), accelerations(1), accelerations(3), accelerations(2), u(1), &
            & velocity]
        if (present(speeds)) speeds = u
        if (present(angles)) angles = at
    end subroutine bicycle_rate

    !> LU factors of a 3 x 3 matrix with partial pivoting (in place); a zero pivot leaves
    !> infinities that the caller's finiteness check catches.
    pure subroutine factor3(a, pivots)
        real(wp), intent(inout) :: a(3, 3)
        integer, intent(out) :: pivots(3)
        real(wp) :: swap(3)
        integer :: k, p, i

        do k = 1, 3
            p = k - 1 + maxloc(abs(a(k:, k)), 1)
            pivots(k) = p
            if (p /= k) then
                swap = a(k, :)
                a(k, :) = a(p, :)
                a(p, :) = swap
            end if
            do i = k + 1, 3
                a(i, k) = a(i, k)/a(k, k)
                a(i, k + 1:) = a(i, k + 1:) - a(i, k)*a(k, k + 1:)
            end do
        end do
    end subroutine factor3

    !> Solve with factor3's factors, b overwritten: the row interchanges first (factor3 swaps
    !> whole rows, its multipliers' too), then the two triangles.
    pure subroutine solve3(lu, pivots, b)
        real(wp), intent(in) :: lu(3, 3)
        integer, intent(in) :: pivots(3)
        real(wp), intent(inout) :: b(3)
        real(wp) :: swap
        integer :: k

        do k = 1, 3
            if (pivots(k) == k) cycle
            swap = b(k)
            b(k) = b(pivots(k))
            b(pivots(k)) = swap
        end do
        do k = 1, 2
            b(k + 1:) = b(k + 1:) - lu(k + 1:, k)*b(k)
        end do
        do k = 3, 1, -1
            b(k) = (b(k) - dot_product(lu(k, k + 1:), b(k + 1:)))/lu(k, k)
        end do
    end subroutine solve3

    !> The push at time t [N] along the dataset's +Y: the table's half-sine pulse of impulse
    !> push, pi push / (2 push_length) at its peak.
    pure real(wp) function push_at(table, time) result(force)
        type(bicycle_table_type), intent(in) :: table
        real(wp), intent(in) :: time

        force = 0.0_wp
        if (time >= table%push_time .and. time <= table%push_time + table%push_length) &
            & force = pi*table%push/(2.0_wp*table%push_length) &
            & *sin(pi*(time - table%push_time)/table%push_length)
    end function push_at

    !> The upright, straight start at the table's speed: the rear wheel turns at -v/r_R.
    pure function bicycle_start(table) result(y)
        type(bicycle_table_type), intent(in) :: table
        real(wp) :: y(bicycle_state_size)

        y = 0.0_wp
        y(5) = -table%speed/table%par(5)
    end function bicycle_start

    !> bicycle_state_size: (roll, steer, roll rate, steer rate, rear wheel rate, yaw, x, y).
    integer function state_size(self)
        class(reduced_bicycle_type), intent(in) :: self

        state_size = bicycle_state_size
    end function state_size

    !> The state of the bicycle's minimal coordinates q = (roll, steer, yaw, x, y) [rad, m]
    !> and independent speeds u = (roll rate, steer rate, rear wheel rate) [rad/s]; y' is not
    !> used (0).
    subroutine pack_state(self, q, u, y, yp)
        class(reduced_bicycle_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: y(:), yp(:)

        y = [q(1), q(2), u(1), u(2), u(3), q(3), q(4), q(5)]
        yp = 0.0_wp
    end subroutine pack_state

    !> The minimal coordinates q(5) and independent speeds u(3) of the state y (pack_state's
    !> order); never fails.
    subroutine unpack_state(self, time, y, q, u, error)
        class(reduced_bicycle_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        q(:5) = [y(1), y(2), y(6), y(7), y(8)]
        u(:3) = y(3:5)
    end subroutine unpack_state

    !> No analytic Jacobian: the reduced bicycle runs with CVODE's difference quotients or
    !> fixed-point iteration (simulate_reduced_bicycle); asked for one, it fails (-1, unrecoverable)
    !> and failure_text says why.
    integer function ode_jacobian(self, time, y, matrix) result(ierr)
        class(reduced_bicycle_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: matrix(:, :)

        matrix = 0.0_wp
        ierr = -1
    end function ode_jacobian

    !> No event functions.
    integer function root_count(self)
        class(reduced_bicycle_type), intent(in) :: self

        root_count = 0
    end function root_count

    !> No event functions: g is empty.
    integer function roots(self, time, y, g, ydot) result(ierr)
        class(reduced_bicycle_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)

        ierr = 0
    end function roots

    !> The one unrecoverable failure: an analytic Jacobian asked for.
    function failure_text(self) result(text)
        class(reduced_bicycle_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = "the reduced bicycle has no analytic Jacobian (JACOBIAN=dq or none)"
    end function failure_text

    !> y'; a state where the pitch or the contact conditions have no solution is recoverable
    !> (1): CVODE cuts the step.
    integer function ode_rhs(self, time, y, ydot) result(ierr)
        class(reduced_bicycle_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)

        call bicycle_rate(y, self%table%par, push_at(self%table, time), ydot)
        ierr = 0
        if (.not. all(ieee_is_finite(ydot))) ierr = 1
    end function ode_rhs

    !> The rows: time, energy, then roll, steer, the rear contact's X and Y in the dataset's
    !> axes, the heading and the pitch.
    function row_layout(self) result(layout)
        class(reduced_bicycle_type), intent(in) :: self
        type(output_layout_type) :: layout

        layout = new_output_layout([integer ::], [integer ::], [character(len=name_length) :: &
            & "roll", "steer", "X_contact", "Y_contact", "heading", "pitch"])
    end function row_layout

    !> The row of a state: the dataset's axes (the paper's y and z reversed; the heading about
    !> +Z is minus the yaw).
    function row(self, time, y) result(values)
        class(reduced_bicycle_type), intent(in) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), allocatable :: values(:)
        real(wp) :: rate(bicycle_state_size), speeds(6), angles(4)

        call bicycle_rate(y, self%table%par, 0.0_wp, rate, speeds, angles)
        values = [time, bicycle_energy(angles, speeds, self%table%par), y(1), y(2), y(7), &
            & -y(8), -y(6), angles(3)]
    end function row

    !> The full model's stops in the push (rollcon_force's pulse_stops: a pulse between two of
    !> an integrator's steps would go unseen).
    function stops(self) result(times)
        class(reduced_bicycle_type), intent(in) :: self
        real(wp), allocatable :: times(:)

        times = pulse_stops(self%table%push_time, self%table%push_time + self%table%push_length)
    end function stops

    !> The push's start and end, corners of the force where the integrator starts again, as
    !> the full model's does (docs/design.md §7).
    function corners(self) result(times)
        class(reduced_bicycle_type), intent(in) :: self
        real(wp), allocatable :: times(:)

        times = [self%table%push_time, self%table%push_time + self%table%push_length]
    end function corners

    !> Run the reduced bicycle of table from its upright start with settings (method, Jacobian
    !> 'dq' or 'none': there is no analytic one, rtol, atol, max_steps), a row every output_step
    !> up to end_time.
    subroutine simulate_reduced_bicycle(table, settings, end_time, output_step, history, &
            & summary, error)
        type(bicycle_table_type), intent(in) :: table
        type(run_settings_type), intent(in) :: settings
        !> End and output interval [s]
        real(wp), intent(in) :: end_time, output_step
        !> Rows in row_layout's columns
        type(history_type), intent(inout) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(reduced_bicycle_type), target :: bicycle

        bicycle%table = table
        bicycle%settings = settings
        call simulate_reduced(bicycle, bicycle_start(table), 0.0_wp, end_time, output_step, &
            & history, summary, error)
    end subroutine simulate_reduced_bicycle

    !> For each row of a run, the compared quantities (roll, steer [rad], the rear contact's X,
    !> Y [m], dataset's axes): read from a reduced run's columns, or worked out from a full
    !> run of a dataset of data/bicycle/write_adm.py (parts 2, 3, 4: rear wheel, rear frame,
    !> front frame), its first row at the upright reference; lambda: the steer axis' tilt [rad],
    !> r_rear: the rear wheel's radius [m].
    function bicycle_measures(run, lambda, r_rear) result(measures)
        type(history_type), intent(in) :: run
        real(wp), intent(in) :: lambda, r_rear
        real(wp), allocatable :: measures(:, :)
        real(wp) :: rear(3, 3), front(3, 3), relative0(3, 3), turn(3, 3), axis(3), tilt(3)
        integer :: i, p_wheel, p_rear, p_front, roll_column

        allocate(measures(bicycle_measure_count, run%count))
        roll_column = run%layout%column("roll")
        if (roll_column > 0) then
            measures = run%rows(roll_column:roll_column + 3, :run%count)
            return
        end if
        p_wheel = run%layout%part_index(rear_wheel_id)
        p_rear = run%layout%part_index(rear_frame_id)
        p_front = run%layout%part_index(front_frame_id)
        if (min(p_wheel, p_rear, p_front) == 0 .or. run%count == 0) then
            measures = ieee_value(0.0_wp, ieee_quiet_nan)
            return
        end if
        rear = frame_of(p_rear, 1)
        front = frame_of(p_front, 1)
        relative0 = matmul(transpose(rear), front)
        ! the steer axis, down and forward, in the rear frame's principal axes
        axis = matmul(transpose(rear), [sin(lambda), 0.0_wp, -cos(lambda)])
        do i = 1, run%count
            associate (s => run%rows(:, i), layout => run%layout)
                measures(1, i) = s(layout%part_column(p_wheel, coord_theta)) - 0.5_wp*pi
                rear = frame_of(p_rear, i)
                front = frame_of(p_front, i)
                turn = matmul(matmul(transpose(rear), front), transpose(relative0))
                ! the turn's angle about the axis: sine from its skew part, cosine from its trace
                measures(2, i) = atan2(0.5_wp*dot_product(axis, [turn(3, 2) - turn(2, 3), &
                    & turn(1, 3) - turn(3, 1), turn(2, 1) - turn(1, 2)]), &
                    & 0.5_wp*(turn(1, 1) + turn(2, 2) + turn(3, 3) - 1.0_wp))
                ! the lowest rim point: the centre less r times the tilted frame's y
                tilt = [-sin(s(layout%part_column(p_wheel, coord_psi))) &
                    & *cos(s(layout%part_column(p_wheel, coord_theta))), &
                    & cos(s(layout%part_column(p_wheel, coord_psi))) &
                    & *cos(s(layout%part_column(p_wheel, coord_theta))), &
                    & sin(s(layout%part_column(p_wheel, coord_theta)))]
                measures(3, i) = s(layout%part_column(p_wheel, coord_x)) - r_rear*tilt(1)
                measures(4, i) = s(layout%part_column(p_wheel, coord_y)) - r_rear*tilt(2)
            end associate
        end do

    contains

        !> The rotation of part p's principal axes in row i.
        pure function frame_of(p, i) result(r)
            integer, intent(in) :: p, i
            real(wp) :: r(3, 3)

            r = rotation_matrix(run%rows(run%layout%part_column(p, coord_psi), i), &
                & run%rows(run%layout%part_column(p, coord_theta), i), &
                & run%rows(run%layout%part_column(p, coord_phi), i))
        end function frame_of

    end function bicycle_measures

    !> Largest difference between two runs over the output times both reached: the largest of
    !> |roll difference|, |steer difference| [rad] and the rear contact points' distance [m].
    function bicycle_distance(run, reference, lambda, r_rear) result(distance)
        type(history_type), intent(in) :: run, reference
        !> The steer axis' tilt [rad] and the rear wheel's radius [m]
        real(wp), intent(in) :: lambda, r_rear
        real(wp) :: distance
        real(wp), allocatable :: a(:, :), b(:, :)
        integer :: i

        a = bicycle_measures(run, lambda, r_rear)
        b = bicycle_measures(reference, lambda, r_rear)
        distance = 0.0_wp
        do i = 1, min(run%count, reference%count)
            if (abs(run%rows(1, i) - reference%rows(1, i)) > 1.0e-9_wp) exit
            distance = max(distance, abs(a(1, i) - b(1, i)), abs(a(2, i) - b(2, i)), &
                & norm2(a(3:4, i) - b(3:4, i)))
        end do
        if (.not. ieee_is_finite(distance)) distance = huge(1.0_wp)
    end function bicycle_distance

end module rollcon_reduced_bicycle
