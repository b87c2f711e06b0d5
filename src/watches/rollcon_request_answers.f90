! SPDX-License-Identifier: MIT
!> The answers to a dataset's REQUESTs of velocity, acceleration, force and expressions
!> (docs/outputs.md, "The columns of a dataset's other requests"; docs/datasets.md,
!> "Accelerations and forces in a REQUEST"), taken at each output row once the state, the
!> multipliers and the accelerations are known (so that forces and accelerations are read with
!> no algebraic loop):
!>
!> - `REQUEST/id, VELOCITY, I=, J=[, RM=]`: `req<id>_vx, _vy, _vz` [m/s], v_I - v_J (ground
!>   frame derivative) in RM's axes, and `req<id>_wx, _wy, _wz` [rad/s], w_I - w_J in RM's
!>   axes: VX ... WZ(I, J, RM);
!> - `REQUEST/id, ACCELERATION, ...`: `req<id>_accx, _accy, _accz` [m/s^2] and
!>   `req<id>_wdtx, _wdty, _wdtz` [rad/s^2], ACCX ... WDTZ(I, J, RM, 0)
!>   (rollcon_marker_acceleration), from the equations of motion's accelerations at the row;
!> - `REQUEST/id, FORCE, I=[, J=][, RM=]` (those no JOINT or JPRIM answers,
!>   rollcon_reaction_watch): `req<id>_fx ... _tz` [N, N m], FX ... TZ(I, J, RM);
!> - `REQUEST/id, F1=e, ..., F8=e`: `req<id>_f<k>` for each expression given, its value in the
!>   dataset's units, with every measure, acceleration and force function of rollcon_expression,
!>   ORIENT, and DIF(id), DIF1(id): the DIFF's state at the row and its rate solved there (as
!>   its columns diff<id>, diff<id>_dot, rollcon_diff_watch);
!> - `REQUEST/id, FUNCTION=USER(r1, ...)`: `req<id>_f2, _f3, _f4, _f6, _f7, _f8`, its REQSUB's
!>   RESULT(2:4) and RESULT(6:8) as ADAMS writes them (rollcon_system_routine_contract), the
!>   routine called at each row through rollcon_user_forces (in the child process that runs it),
!>   its SYSARY('TACC'|'RACC') and SYSFNC('ACCX' ... 'WDTM') answered with the row's
!>   accelerations.
!>
!> The force functions, as ADAMS defines them: an element acts between its markers I and J (a
!> JOINT's or JPRIM's, a MOTION's, an SFORCE's, a VFORCE's or GFORCE's I and JFLOAT); its force
!> and torque at I (on I's part, the torque about I's origin) or at J (on J's part, about J's
!> origin), ground axes:
!>
!> - JOINT, JPRIM: the reaction (rollcon_reactions' site_wrench at I; swapped_wrench at J);
!> - MOTION: from its UCON's row and multiplier, on the part of the marker (or, on the ground,
!>   the opposite of the other part's, its moment carried to the marker);
!> - SFORCE: translational, f along J to I at I and -f at J (ACTIONONLY: along J's z at I,
!>   nothing at J); rotational, the torque about J's z at I and its opposite at J; VFORCE,
!>   VTORQUE, GFORCE: f and T in RM's axes at I, and at J the reaction on JFLOAT's part
!>   applied at I's origin: -f and -T - (r_I - r_J) x f;
!> - SPRINGDAMPER, BUSHING: f and T on I's part at I's origin (rollcon_marker_force's
!>   marker_force_action, the columns springdamper<id>_..., bushing<id>_...), and at J the
!>   same reaction, -f and -T - (r_I - r_J) x f.
!>
!> `JOINT(id, jflag, comp, rm)` (and JPRIM, MOTION, SFORCE, VFORCE, VTORQUE, GFORCE, BUSHING
!> (ADAMS's BUSH), SPDP): that element's
!> force (jflag 0: at I; 1: at J), comp 1 |F|, 2-4 F's x, y, z in rm's axes, 5 |T|, 6-8 T's.
!> `FX, FY, FZ(i[, j[, k]])`, `FM`, `TX, TY, TZ`, `TM`: the sum over the elements that act at
!> marker i (as their I or their J) and, when j is given, between i and j, in k's axes.
!> Values in the dataset's units (force, force times length; accelerations length per time
!> squared, radians per time squared), as every measure an expression reads.
!>
!> The markers are body-fixed: a re-basing of a part's principal axes (docs/rebasing.md) turns
!> the watch's markers on it as the model's own.
module rollcon_request_answers
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix, times, transpose_times, cross
    use rollcon_marker, only : marker_type, marker_motion, turn_marker
    use rollcon_expression, only : expression_type, expression_input_type, evaluate_expression, &
        & max_inputs, quantity_vx, quantity_wx, quantity_accx, quantity_wdtx, quantity_fx, &
        & quantity_fm, quantity_tx, quantity_tm, quantity_joint, quantity_kind, &
        & kind_acceleration, kind_angular_acceleration, kind_force, kind_torque, &
        & kind_element_force
    use rollcon_measures, only : measure_value, expression_input_values, input_markers, &
        & count_turns
    use rollcon_marker_acceleration, only : acceleration_measure
    use rollcon_force_measures, only : force_wrench, set_force_measure_model
    use rollcon_reactions, only : reaction_site_type, reaction_sites, site_wrench, &
        & swapped_wrench, body_moment
    use rollcon_equations, only : equations_type
    use rollcon_constraint_matrix, only : constraint_matrix_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch, only : watch_type
    use rollcon_system_routine_contract, only : request_results, request_columns
    use rollcon_user_forces, only : call_user_request, set_system_constraint_forces
    use rollcon_diff, only : diff_inputs
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: request_answer_watch_type, answered_request_type, request_element_type
    public :: new_request_answer_watch, element_kind_of
    public :: answer_velocity, answer_acceleration, answer_force, answer_expressions, &
        & answer_user
    public :: element_joint, element_jprim, element_motion, element_sforce, element_vforce, &
        & element_gforce, element_vtorque, element_bushing, element_springdamper

    !> What a request asks for
    integer, parameter :: answer_velocity = 1, answer_acceleration = 2, answer_force = 3, &
        & answer_expressions = 4, answer_user = 5
    !> The elements whose forces the force functions read (quantity_names' JOINT, JPRIM,
    !> MOTION, SFORCE, VFORCE, GFORCE, VTORQUE, BUSHING, and SPDP of a SPRINGDAMPER). A
    !> statement rollcon adds later becomes a kind here, its wrench at I and at J in
    !> element_wrench, and its function's name in element_kind_of.
    integer, parameter :: element_joint = 1, element_jprim = 2, element_motion = 3, &
        & element_sforce = 4, element_vforce = 5, element_gforce = 6, element_vtorque = 7, &
        & element_bushing = 8, element_springdamper = 9

    !> Column suffixes of each kind of request
    character(len=*), parameter :: velocity_suffixes(6) = [character(len=5) :: "_vx", "_vy", &
        & "_vz", "_wx", "_wy", "_wz"]
    character(len=*), parameter :: acceleration_suffixes(6) = [character(len=5) :: "_accx", &
        & "_accy", "_accz", "_wdtx", "_wdty", "_wdtz"]
    character(len=*), parameter :: force_suffixes(6) = [character(len=5) :: "_fx", "_fy", &
        & "_fz", "_tx", "_ty", "_tz"]

    !> One element the force functions read: its kind and id, its markers I and J (J: id 0,
    !> none), and where the model holds it
    type :: request_element_type
        integer :: kind = element_joint
        integer :: id = 0
        type(marker_type) :: i, j
        !> A JOINT's or JPRIM's statement (model%statements), a MOTION's UCON (model order), an
        !> SFORCE's, VFORCE's or GFORCE's force (model%forces)
        integer :: place = 0
    end type request_element_type

    !> One request answered here
    type :: answered_request_type
        integer :: id = 0
        !> answer_velocity ... answer_expressions
        integer :: kind = answer_velocity
        !> I, J (id 0: the ground origin and axes) and RM (id 0: ground axes)
        type(marker_type) :: i, j, rm
        !> F1 ... F8 (answer_expressions), compiled, and which are given
        type(expression_type) :: functions(8)
        logical :: given(8) = .false.
        !> answer_user: the REQSUB's entry in rollcon_user_forces' table, its constants, the
        !> statement for messages ("x.adm:12: REQUEST/5"), and what its initialisation call
        !> declared (not allocated until that call is made, at the first row)
        integer :: routine = 0
        real(wp), allocatable :: par(:)
        character(len=:), allocatable :: name
        integer, allocatable :: declared(:)
        logical :: declared_rates = .false.
    end type answered_request_type

    type, extends(watch_type) :: request_answer_watch_type
        !> The requests, elements and markers in the model's current axes, and as given (each
        !> part's own principal axes, basis 0)
        type(answered_request_type), allocatable :: requests(:), own_requests(:)
        type(request_element_type), allocatable :: elements(:), own_elements(:)
        !> Every marker the expressions read
        type(marker_type), allocatable :: markers(:), own_markers(:)
        !> Size of the dataset's length [m], time [s] and force [N] units
        real(wp) :: length_unit = 1.0_wp, time_unit = 1.0_wp, force_unit = 1.0_wp
        !> The statements' reaction sites (rollcon_reactions)
        type(reaction_site_type), allocatable :: sites(:)
        !> The accelerations at the row being filled (take_accelerations)
        real(wp), allocatable :: a(:)
    contains
        procedure :: prepare
        procedure :: part_rebased
        procedure :: column_names
        procedure :: take_accelerations
        procedure :: fill_columns
    end type request_answer_watch_type

contains

    !> A watch of these requests, reading these elements and markers (in their parts' own
    !> principal axes), in a dataset of these units [m, s, N].
    function new_request_answer_watch(requests, elements, markers, length_unit, time_unit, &
            & force_unit) result(watch)
        type(answered_request_type), intent(in) :: requests(:)
        type(request_element_type), intent(in) :: elements(:)
        type(marker_type), intent(in) :: markers(:)
        real(wp), intent(in) :: length_unit, time_unit, force_unit
        type(request_answer_watch_type) :: watch

        watch%own_requests = requests
        watch%own_elements = elements
        watch%own_markers = markers
        watch%requests = requests
        watch%elements = elements
        watch%markers = markers
        watch%length_unit = length_unit
        watch%time_unit = time_unit
        watch%force_unit = force_unit
    end function new_request_answer_watch

    !> The element kind of quantity code `quantity` (JOINT ... GFORCE, BUSHING, SPDP), 0 for an
    !> element function of a statement rollcon does not have.
    pure integer function element_kind_of(quantity) result(kind)
        integer, intent(in) :: quantity

        kind = 0
        select case (quantity - quantity_joint)
        case (0)
            kind = element_joint
        case (1)
            kind = element_jprim
        case (2)
            kind = element_motion
        case (3)
            kind = element_sforce
        case (4)
            kind = element_vforce
        case (5)
            kind = element_vtorque
        case (6)
            kind = element_gforce
        case (7)
            kind = element_bushing
        case (10)
            kind = element_springdamper
        end select
    end function element_kind_of

    !> The markers as given, the model's reaction sites, the accelerations' room.
    subroutine prepare(self, eq, settings, error)
        class(request_answer_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        self%requests = self%own_requests
        self%elements = self%own_elements
        self%markers = self%own_markers
        self%sites = reaction_sites(eq%model)
        if (allocated(self%a)) deallocate(self%a)
        allocate(self%a(eq%n), source=0.0_wp)
    end subroutine prepare

    !> Part p's principal axes were turned: its markers in the new axes, as the model's.
    subroutine part_rebased(self, p, turn)
        class(request_answer_watch_type), intent(inout) :: self
        !> The part (model order) and the re-basing's turn (rollcon_rebasing)
        integer, intent(in) :: p, turn
        integer :: k

        do k = 1, size(self%requests)
            call turn_marker(self%requests(k)%i, p, turn)
            call turn_marker(self%requests(k)%j, p, turn)
            call turn_marker(self%requests(k)%rm, p, turn)
        end do
        do k = 1, size(self%elements)
            call turn_marker(self%elements(k)%i, p, turn)
            call turn_marker(self%elements(k)%j, p, turn)
        end do
        do k = 1, size(self%markers)
            call turn_marker(self%markers(k), p, turn)
        end do
    end subroutine part_rebased

    !> Six columns per VELOCITY, ACCELERATION or FORCE request; one per expression given.
    subroutine column_names(self, eq, names)
        class(request_answer_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        character(len=:), allocatable :: stem
        integer :: r, k, n

        allocate(names(column_count(self)))
        n = 0
        do r = 1, size(self%own_requests)
            associate (request => self%own_requests(r))
                stem = "req" // to_text(request%id)
                select case (request%kind)
                case (answer_expressions)
                    do k = 1, 8
                        if (.not. request%given(k)) cycle
                        n = n + 1
                        names(n) = stem // "_f" // to_text(k)
                    end do
                case (answer_user)
                    do k = 1, size(request_columns)
                        n = n + 1
                        names(n) = stem // "_f" // to_text(request_columns(k))
                    end do
                case default
                    do k = 1, 6
                        n = n + 1
                        select case (request%kind)
                        case (answer_velocity)
                            names(n) = stem // trim(velocity_suffixes(k))
                        case (answer_acceleration)
                            names(n) = stem // trim(acceleration_suffixes(k))
                        case default
                            names(n) = stem // trim(force_suffixes(k))
                        end select
                    end do
                end select
            end associate
        end do
    end subroutine column_names

    !> The number of columns of the watch.
    pure integer function column_count(self) result(n)
        type(request_answer_watch_type), intent(in) :: self
        integer :: r

        n = 0
        do r = 1, size(self%own_requests)
            if (self%own_requests(r)%kind == answer_expressions) then
                n = n + count(self%own_requests(r)%given)
            else if (self%own_requests(r)%kind == answer_user) then
                n = n + size(request_columns)
            else
                n = n + 6
            end if
        end do
    end function column_count

    !> Keep the row's accelerations.
    subroutine take_accelerations(self, eq, a)
        class(request_answer_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: a(:)

        self%a = a
    end subroutine take_accelerations

    !> Each request's columns at the row (module header).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(request_answer_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        type(marker_type) :: markers(4)
        real(wp) :: wrench(6), inputs(max_inputs), result(request_results)
        real(wp), allocatable :: dif1(:)
        type(error_type), allocatable :: error
        integer :: r, k, n, m

        ! the DIFFs' rates at the row, solved from their equations there (as their columns,
        ! rollcon_diff_watch); NaN where they cannot be solved (the run has stopped on that)
        associate (diffs => eq%model%diffs)
            allocate(dif1(diffs%count()))
            if (diffs%count() > 0) then
                dif1 = diffs%w
                call diffs%solve_rates(time, q, u, diffs%x, dif1, error)
                if (allocated(error)) dif1 = nan()
            end if
        end associate
        n = 0
        do r = 1, size(self%requests)
            associate (request => self%requests(r))
                markers = [request%i, request%j, request%rm, marker_type()]
                select case (request%kind)
                case (answer_velocity)
                    do k = 1, 3
                        values(n + k) = measure_value(quantity_vx + k - 1, markers, q, u, &
                            & 0.0_wp)
                        values(n + 3 + k) = measure_value(quantity_wx + k - 1, markers, q, u, &
                            & 0.0_wp)
                    end do
                    n = n + 6
                case (answer_acceleration)
                    do k = 1, 3
                        values(n + k) = acceleration_measure(quantity_accx + k - 1, markers, q, &
                            & u, self%a)
                        values(n + 3 + k) = acceleration_measure(quantity_wdtx + k - 1, &
                            & markers, q, u, self%a)
                    end do
                    n = n + 6
                case (answer_force)
                    wrench = net_wrench(self, eq, request%i%id, request%j%id, time, q, u, &
                        & lambda)
                    values(n + 1:n + 6) = in_axes(request%rm, q, u, wrench)
                    n = n + 6
                case (answer_user)
                    ! the reactions its SYSFNC force measures read: the row's
                    call set_force_measure_model(eq%model)
                    call set_system_constraint_forces(eq%c, lambda)
                    call call_user_request(request%routine, request%id, request%name, &
                        & request%par, self%time_unit, time, q, u, request%declared, &
                        & request%declared_rates, result, accelerations=self%a)
                    values(n + 1:n + size(request_columns)) = result(request_columns)
                    n = n + size(request_columns)
                case default
                    do k = 1, 8
                        if (.not. request%given(k)) cycle
                        associate (expression => request%functions(k))
                            m = size(expression%inputs)
                            call count_turns(expression, self%markers, self%length_unit, &
                                & self%time_unit, q, u, .false.)
                            call input_values(self, eq, expression, time, q, u, lambda, &
                                & inputs(:m))
                            if (eq%model%diffs%count() > 0) call diff_inputs(expression, &
                                & eq%model%diffs%ids, eq%model%diffs%x, dif1, inputs(:m))
                            n = n + 1
                            values(n) = evaluate_expression(expression, time/self%time_unit, &
                                & inputs(:m))
                        end associate
                    end do
                end select
            end associate
        end do
    end subroutine fill_columns

    !> The values of an expression's inputs at the row, in the dataset's units: the measures of
    !> the state (rollcon_measures), and the accelerations and forces here.
    subroutine input_values(self, eq, expression, time, q, u, lambda, values)
        type(request_answer_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        type(expression_type), intent(in) :: expression
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        type(marker_type) :: chosen(4), rm
        logical :: found(4)
        real(wp) :: wrench(6), resolved(6)
        integer :: k, e, comp

        call expression_input_values(expression, self%markers, self%length_unit, &
            & self%time_unit, q, u, values)
        do k = 1, size(values)
            associate (input => expression%inputs(k))
                select case (quantity_kind(input%quantity))
                case (kind_acceleration, kind_angular_acceleration)
                    call input_markers(input, self%markers, chosen, found)
                    values(k) = acceleration_measure(input%quantity, chosen, q, u, self%a) &
                        & *self%time_unit**2
                    if (quantity_kind(input%quantity) == kind_acceleration) &
                        & values(k) = values(k)/self%length_unit
                case (kind_force, kind_torque)
                    call input_markers(input, self%markers, chosen, found)
                    wrench = net_wrench(self, eq, input%marker, input%j, time, q, u, lambda)
                    resolved = in_axes(chosen(3), q, u, wrench)
                    select case (input%quantity)
                    case (quantity_fx:quantity_fx + 2)
                        values(k) = resolved(input%quantity - quantity_fx + 1)
                    case (quantity_fm)
                        values(k) = norm2(wrench(1:3))
                    case (quantity_tx:quantity_tx + 2)
                        values(k) = resolved(input%quantity - quantity_tx + 4)
                    case default
                        values(k) = norm2(wrench(4:6))
                    end select
                    values(k) = values(k)/self%force_unit
                    if (input%quantity >= quantity_tx) values(k) = values(k)/self%length_unit
                case (kind_element_force)
                    values(k) = nan()
                    e = find_element(self, element_kind_of(input%quantity), input%marker)
                    if (e == 0) cycle
                    rm = marker_type()
                    if (input%l /= 0) rm = self%markers(findloc(self%markers%id, input%l, dim=1))
                    wrench = element_wrench(self, eq, e, input%j == 1, time, q, u, lambda)
                    resolved = in_axes(rm, q, u, wrench)
                    comp = input%k
                    select case (comp)
                    case (1)
                        values(k) = norm2(wrench(1:3))
                    case (2:4)
                        values(k) = resolved(comp - 1)
                    case (5)
                        values(k) = norm2(wrench(4:6))
                    case default
                        values(k) = resolved(comp - 2)
                    end select
                    values(k) = values(k)/self%force_unit
                    if (comp >= 5) values(k) = values(k)/self%length_unit
                end select
            end associate
        end do
    end subroutine input_values

    !> The place among the elements of the one of this kind and id (0: none).
    pure integer function find_element(self, kind, id) result(e)
        type(request_answer_watch_type), intent(in) :: self
        integer, intent(in) :: kind, id

        do e = 1, size(self%elements)
            if (self%elements(e)%kind == kind .and. self%elements(e)%id == id) return
        end do
        e = 0
    end function find_element

    !> A force and torque (ground axes) in marker rm's axes (rm: marker_type(), ground axes).
    pure function in_axes(rm, q, u, wrench) result(resolved)
        type(marker_type), intent(in) :: rm
        real(wp), intent(in) :: q(:), u(:), wrench(6)
        real(wp) :: resolved(6)
        real(wp) :: r(3), v(3), axes(3, 3), w(3)

        call marker_motion(rm, q, u, r, v, axes, w)
        resolved(1:3) = transpose_times(axes, wrench(1:3))
        resolved(4:6) = transpose_times(axes, wrench(4:6))
    end function in_axes

    !> FX ... TZ's vector: the sum of the forces and torques at marker `at` of the elements
    !> acting there (as their I or J) and, when `between` is not 0, between markers `at` and
    !> `between` [N, N m], ground axes, the torques about `at`'s origin.
    function net_wrench(self, eq, at, between, time, q, u, lambda) result(wrench)
        type(request_answer_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: at, between
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp) :: wrench(6)
        integer :: e

        wrench = 0.0_wp
        do e = 1, size(self%elements)
            associate (element => self%elements(e))
                if (element%i%id == at .and. (between == 0 .or. element%j%id == between)) &
                    & wrench = wrench + element_wrench(self, eq, e, .false., time, q, u, lambda)
                if (element%j%id == at .and. element%j%id /= 0 .and. (between == 0 .or. &
                    & element%i%id == between)) wrench = wrench + element_wrench(self, eq, e, &
                    & .true., time, q, u, lambda)
            end associate
        end do
    end function net_wrench

    !> The force and torque element e exerts at its marker I (at_j false) or J [N, N m], ground
    !> axes, on that marker's part, the torque about that marker's origin (module header).
    function element_wrench(self, eq, e, at_j, time, q, u, lambda) result(wrench)
        type(request_answer_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: e
        logical, intent(in) :: at_j
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp) :: wrench(6)
        integer :: s

        wrench = 0.0_wp
        associate (element => self%elements(e))
            select case (element%kind)
            case (element_joint, element_jprim)
                s = findloc(self%sites%statement, element%place, dim=1)
                if (s == 0) return
                wrench = site_wrench(eq%model, self%sites(s), eq%c, lambda, q)
                if (at_j) wrench = swapped_wrench(eq%model, self%sites(s), wrench, q)
            case (element_motion)
                if (at_j) then
                    wrench = rows_wrench(eq%c, lambda, element%place, element%j, element%i, q)
                else
                    wrench = rows_wrench(eq%c, lambda, element%place, element%i, element%j, q)
                end if
            case default
                wrench = force_wrench(eq%model%forces(element%place)%statement, at_j, time, q, u)
            end select
        end associate
    end function element_wrench

    !> The force and torque UCON row k's multiplier exerts on the part of `marker`, about its
    !> origin, ground axes (from the generalised force lambda_k c_k on the part's coordinates,
    !> as rollcon_reactions); a marker on the ground: the opposite of what it exerts on
    !> `other`'s part, its moment taken about `marker` (the row depends on the two markers'
    !> relative pose); both on the ground: zero. c: the constraint rows (C, nc x n, by rows over
    !> each UCON's coordinates), row k read on the part's six; lambda (nc), q (n).
    pure function rows_wrench(c, lambda, k, marker, other, q) result(wrench)
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: lambda(:)
        integer, intent(in) :: k
        type(marker_type), intent(in) :: marker, other
        real(wp), intent(in) :: q(:)
        real(wp) :: wrench(6)
        real(wp) :: generalised(6), row(6), rotation(3, 3), force(3), moment(3)
        integer :: p, i0

        wrench = 0.0_wp
        p = marker%part
        if (p == 0) p = other%part
        if (p == 0) return
        i0 = 6*(p - 1)
        call c%gather(k, i0 + 1, row)
        generalised = lambda(k)*row
        rotation = rotation_matrix(q(i0 + 4), q(i0 + 5), q(i0 + 6))
        force = generalised(1:3)
        moment = times(rotation, body_moment(q(i0 + 5), q(i0 + 6), generalised(4:6)))
        if (marker%part == 0) then
            moment = -(moment + cross(q(i0 + 1:i0 + 3) - marker%point, force))
            force = -force
        else
            moment = moment - cross(times(rotation, marker%point), force)
        end if
        wrench(1:3) = force
        wrench(4:6) = moment
    end function rows_wrench

    pure function nan()
        real(wp) :: nan

        nan = ieee_value(nan, ieee_quiet_nan)
    end function nan

end module rollcon_request_answers
