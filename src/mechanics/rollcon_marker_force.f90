! SPDX-License-Identifier: MIT
!> Forces between markers with expression magnitudes, as ADAMS's SFORCE, VFORCE and GFORCE
!> statements state them (docs/datasets-model.md):
!>
!> - translational SFORCE: the value along the line from J to I, on I at its origin (positive
!>   pushes I away from J); the reaction on J at J's origin;
!> - rotational SFORCE: a torque of the value about J's z axis on I's part; the reaction on J's;
!> - ACTIONONLY: on I only (translational: along J's z axis);
!> - VFORCE: (FX, FY, FZ) in RM's axes at I's origin; the reaction on JFLOAT's part at the same
!>   point;
!> - GFORCE: the same, and the torque (TX, TY, TZ) in RM's axes; the reaction on JFLOAT's part
!>   (a VTORQUE is a GFORCE of TX, TY, TZ alone);
!> - SPRINGDAMPER and BUSHING: rollcon_spring_force's force and torque on I's part at I's
!>   origin; the reaction on J's part at the same point.
!>
!> The expressions are in the dataset's units: their TIME and measures are converted
!> from SI before evaluation and their values to N and N m after (time_unit, length_unit,
!> force_unit: the size of a dataset unit in SI). A load on ground (part 0) is not applied.
!>
!> A statement with FUNCTION=USER(...) has no expressions: its values are those its user's
!> routine gave at the state last set by rollcon_user_forces' evaluate_user_forces (these
!> procedures are pure, the routine is not), which the equations call before every use.
module rollcon_marker_force
    use rollcon_kinds, only : wp
    use rollcon_rotation, only : times, cross
    use rollcon_expression, only : expression_type, evaluate_expression, max_inputs, &
        & switch_values
    use rollcon_marker, only : marker_type, marker_motion
    use rollcon_measures, only : expression_input_values
    use rollcon_diff_inputs, only : diff_inputs
    use rollcon_spring_force, only : spring_type, spring_loads, spring_translational
    implicit none
    private

    public :: marker_force_type, marker_force_loads, marker_force_values, markers_coincide
    public :: marker_force_switches, marker_force_action
    public :: kind_translation, kind_rotation, kind_vector, kind_general, kind_spring

    !> Kinds: SFORCE translational or rotational, VFORCE, GFORCE (and VTORQUE), a
    !> SPRINGDAMPER or BUSHING (kind_spring: its constants in `spring`)
    integer, parameter :: kind_translation = 1, kind_rotation = 2, kind_vector = 3, &
        & kind_general = 4, kind_spring = 5

    !> One force statement
    type :: marker_force_type
        integer :: kind = kind_translation
        !> The statement's id in the dataset (0: none)
        integer :: id = 0
        !> Leave out the reaction (SFORCE ACTIONONLY)
        logical :: action_only = .false.
        !> The marker it acts at, the reaction marker (J or JFLOAT; a ground marker when none),
        !> the marker of the components' axes (RM; ground axes when none)
        type(marker_type) :: i, j, rm
        !> FX, FY, FZ, TX, TY, TZ (an SFORCE's FUNCTION in the first), dataset units
        type(expression_type) :: functions(6)
        !> Which of them are given (the rest are zero)
        logical :: given(6) = .false.
        !> Every marker the expressions read, by id
        type(marker_type), allocatable :: markers(:)
        !> Size of the dataset's time [s], length [m] and force [N] units
        real(wp) :: time_unit = 1.0_wp, length_unit = 1.0_wp, force_unit = 1.0_wp
        !> kind_spring: the SPRINGDAMPER's or BUSHING's constants, SI
        type(spring_type) :: spring
        !> FUNCTION=USER: the entry of the user's routine (rollcon_user_forces' table) serving
        !> it, 0 for expressions
        integer :: routine = 0
        !> FUNCTION=USER: its constants (PAR; the routine's ID is the statement's id)
        real(wp), allocatable :: par(:)
        !> FUNCTION=USER: the routine's values at the last state it was called at, as
        !> marker_force_values gives them (SI; rollcon_user_forces' evaluate_user_forces)
        real(wp) :: user_values(6) = 0.0_wp
        !> FUNCTION=USER: the markers its initialisation call's SYSFNC and SYSARY calls named
        !> (by id), and whether they read rates, and accelerations (SYSARY('TACC'|'RACC'),
        !> SYSFNC('ACCX' ... 'WDTM'): the routine's values then enter the equations of motion
        !> with the accelerations, rollcon_equations' and rollcon_dae's algebraic loop)
        integer, allocatable :: declared_markers(:)
        logical :: declared_rates = .false., declared_accelerations = .false.
        !> FUNCTION=USER: its initialisation call read a VARSUB's value (SYSFNC('VARVAL')): its
        !> difference calls evaluate the VARSUBs at the shifted state
        logical :: declared_variables = .false.
        !> FUNCTION=USER: its initialisation call read a force measure (SYSFNC('FX' ... 'TM'),
        !> or an element's force, SYSFNC('JOINT' ... 'SPDP')), and the constraint rows (model
        !> order) whose multipliers those measures sum (a JOINT's or JPRIM's reaction): its
        !> values then enter the equations with the multipliers, rollcon_equations' and
        !> rollcon_dae's algebraic loop (rollcon_force_measures)
        logical :: declared_forces = .false.
        integer, allocatable :: declared_rows(:)
        !> FUNCTION=USER: the model parts of those markers (ground left out), whose coordinates
        !> (and rates, when declared_rates) its partials are differenced over
        !> (rollcon_user_force_partials)
        integer, allocatable :: declared_parts(:)
        !> The DIFFs its expressions read (DIF, DIF1): their ids and their state last set
        !> (rollcon_model's set_diff_state): (k, 1) DIF, (k, 2) DIF1, user's units; not
        !> allocated when the model has no DIFF
        integer, allocatable :: dif_ids(:)
        real(wp), allocatable :: dif(:, :)
    end type marker_force_type

contains

    !> The six expression values at (t, q, u), in SI: force [N] (1:3) and torque [N m] (4:6).
    pure function marker_force_values(self, time, q, u) result(values)
        type(marker_force_type), intent(in) :: self
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: values(6)
        real(wp) :: inputs(max_inputs)
        integer :: k, n

        values = 0.0_wp
        if (self%routine > 0) then
            ! a user's routine, called where its state was set (rollcon_user_forces)
            values = self%user_values
            return
        end if
        do k = 1, 6
            if (.not. self%given(k)) cycle
            n = size(self%functions(k)%inputs)
            call input_values(self, self%functions(k), q, u, inputs(:n))
            values(k) = evaluate_expression(self%functions(k), time/self%time_unit, inputs(:n))
        end do
        values(1:3) = values(1:3)*self%force_unit
        values(4:6) = values(4:6)*(self%force_unit*self%length_unit)
    end function marker_force_values

    !> The switch functions of expression k's watched switches (kinds: switch_kinds of it) at
    !> (t, q, u), into g (switch_count of them; rollcon_expression's switch_values), in the
    !> dataset's units. Allocates nothing.
    pure subroutine marker_force_switches(self, k, time, q, u, kinds, g)
        type(marker_force_type), intent(in) :: self
        !> Which expression: FX, FY, FZ, TX, TY, TZ (1 to 6)
        integer, intent(in) :: k
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts
        real(wp), intent(in) :: q(:), u(:)
        integer, intent(in) :: kinds(:)
        real(wp), intent(out) :: g(:)
        real(wp) :: inputs(max_inputs)
        integer :: n

        n = size(self%functions(k)%inputs)
        call input_values(self, self%functions(k), q, u, inputs(:n))
        call switch_values(self%functions(k), time/self%time_unit, inputs(:n), kinds, g)
    end subroutine marker_force_switches

    !> The measures an expression reads, in the dataset's units (rollcon_measures).
    pure subroutine input_values(self, expression, q, u, values)
        type(marker_force_type), intent(in) :: self
        type(expression_type), intent(in) :: expression
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: values(:)

        ! a marker the force was not given (the builder gives every one): NaN
        call expression_input_values(expression, self%markers, self%length_unit, &
            & self%time_unit, q, u, values)
        if (allocated(self%dif_ids)) call diff_inputs(expression, self%dif_ids, &
            & self%dif(:, 1), self%dif(:, 2), values)
    end subroutine input_values

    !> A translational SFORCE (not ACTIONONLY) or SPRINGDAMPER whose I and J markers are at one
    !> point: its line of action, from J to I, is not defined there.
    pure logical function markers_coincide(self, q)
        type(marker_force_type), intent(in) :: self
        real(wp), intent(in) :: q(:)
        real(wp) :: r_i(3), r_j(3), v(3), axes(3, 3), w(3), u(size(q))

        markers_coincide = .false.
        if (self%kind == kind_spring) then
            if (self%spring%kind /= spring_translational) return
        else if (self%kind /= kind_translation .or. self%action_only) then
            return
        end if
        u = 0.0_wp
        call marker_motion(self%i, q, u, r_i, v, axes, w)
        call marker_motion(self%j, q, u, r_j, v, axes, w)
        markers_coincide = all(r_i == r_j)
    end function markers_coincide

    !> Add this force's loads on part p to force [N] and moment about p's centre of mass
    !> [N m], ground components.
    pure subroutine marker_force_loads(self, p, time, q, u, force, moment)
        type(marker_force_type), intent(in) :: self
        !> Part index
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(inout) :: force(3), moment(3)
        real(wp) :: values(6), r_i(3), r_j(3), axes_j(3, 3), axes_rm(3, 3)
        real(wp) :: f(3), torque(3), line(3), r(3), v(3), w(3)
        logical :: on_i, on_j

        on_i = self%i%part == p
        on_j = self%j%part == p .and. .not. self%action_only
        if (.not. (on_i .or. on_j)) return
        if (self%kind == kind_spring) then
            call spring_loads(self%spring, self%i, self%j, q, u, f, torque)
            call marker_motion(self%i, q, u, r_i, v, axes_rm, w)
            if (on_i) call add_load(p, q, r_i, f, force, moment)
            if (on_i) moment = moment + torque
            if (on_j) call add_load(p, q, r_i, -f, force, moment)
            if (on_j) moment = moment - torque
            return
        end if
        values = marker_force_values(self, time, q, u)
        ! the markers' velocities and angular velocities are not needed here
        call marker_motion(self%i, q, u, r_i, v, axes_rm, w)
        call marker_motion(self%j, q, u, r_j, v, axes_j, w)
        select case (self%kind)
        case (kind_translation)
            if (self%action_only) then
                line = axes_j(:, 3)
            else
                line = r_i - r_j
                line = line/norm2(line)
            end if
            f = values(1)*line
            if (on_i) call add_load(p, q, r_i, f, force, moment)
            if (on_j) call add_load(p, q, r_j, -f, force, moment)
        case (kind_rotation)
            ! the value is a torque: its unit is force times length
            torque = values(1)*self%length_unit*axes_j(:, 3)
            if (on_i) moment = moment + torque
            if (on_j) moment = moment - torque
        case default
            call marker_motion(self%rm, q, u, r, v, axes_rm, w)
            f = times(axes_rm, values(1:3))
            torque = times(axes_rm, values(4:6))
            ! VFORCE and GFORCE: the reaction acts at I's origin on JFLOAT's part
            if (on_i) call add_load(p, q, r_i, f, force, moment)
            if (on_i) moment = moment + torque
            if (on_j) call add_load(p, q, r_i, -f, force, moment)
            if (on_j) moment = moment - torque
        end select
    end subroutine marker_force_loads

    !> The statement's force [N] and torque [N m] on I's part, at I's origin, ground components
    !> (its reaction, unless ACTIONONLY, is the opposite force and torque on J's part: at J's
    !> origin for a translational SFORCE, whose force lies along the line from J to I, at I's
    !> origin for the others). The one place each element's force and torque are computed
    !> from the state, for outputs and requests.
    pure subroutine marker_force_action(self, time, q, u, force, torque)
        type(marker_force_type), intent(in) :: self
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts
        real(wp), intent(in) :: q(:), u(:)
        real(wp), intent(out) :: force(3), torque(3)
        real(wp) :: values(6), r_i(3), r_j(3), axes_j(3, 3), axes(3, 3), r(3), v(3), w(3)

        force = 0.0_wp
        torque = 0.0_wp
        if (self%kind == kind_spring) then
            call spring_loads(self%spring, self%i, self%j, q, u, force, torque)
            return
        end if
        values = marker_force_values(self, time, q, u)
        call marker_motion(self%i, q, u, r_i, v, axes, w)
        call marker_motion(self%j, q, u, r_j, v, axes_j, w)
        select case (self%kind)
        case (kind_translation)
            if (self%action_only) then
                force = values(1)*axes_j(:, 3)
            else
                force = values(1)*(r_i - r_j)/norm2(r_i - r_j)
            end if
        case (kind_rotation)
            torque = values(1)*self%length_unit*axes_j(:, 3)
        case default
            call marker_motion(self%rm, q, u, r, v, axes, w)
            force = times(axes, values(1:3))
            torque = times(axes, values(4:6))
        end select
    end subroutine marker_force_action

    !> A force f at ground point r on part p: the force, and its moment about p's centre.
    pure subroutine add_load(p, q, r, f, force, moment)
        integer, intent(in) :: p
        real(wp), intent(in) :: q(:), r(3), f(3)
        real(wp), intent(inout) :: force(3), moment(3)
        real(wp) :: arm(3)

        force = force + f
        ! through a local array: an expression of a section would be a heap temporary
        arm = r - q(6*(p - 1) + 1:6*(p - 1) + 3)
        moment = moment + cross(arm, f)
    end subroutine add_load

end module rollcon_marker_force
