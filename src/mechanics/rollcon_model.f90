! SPDX-License-Identifier: MIT
!> A multibody model: rigid parts, UCON statements served by one UCOSUB, joints and joint
!> primitives (as UCONs of the generated primitive routines, rollcon_joint_primitives),
!> applied forces, gravity.
!>
!> A UCON that names no routine of its own is served by the model's UCOSUB (ADAMS's rule: one
!> UCOSUB per model serves every UCON that names no ROUTINE); served_by_model_ucosub is that
!> rule, written here only, and setup_model acts on it.
!>
!> The model keeps the statements as its user wrote them (model%statements: a UCON, a JOINT,
!> a JPRIM, with its dataset line and a joint's marker I) beside the UCONs the driver evaluates:
!> a JOINT or JPRIM is several UCONs of generated routines, each knowing its statement and
!> which of its equations it is, so that every message and column speaks of the statement and
!> the line the user wrote ("JOINT/3 (line 40), its rotation about J's x"), never of an id the
!> program generated (row_words, statement_name).
!>
!> setup_model makes the initialisation call of every UCON (IFLAG = 3), validates the UCOVAR
!> declarations and maps each declared variable onto the system's coordinates: part p's
!> coordinate c (X, Y, Z, psi, theta, phi) is number 6 (p - 1) + c of q, and its rate the same
!> number of u.
module rollcon_model
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, ucon_error, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface, max_ucon_par, is_velocity_code, &
        & code_coordinate, &
        & code_name
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_ucon_call, only : declare_ucon
    use rollcon_ucosub_units, only : ucosub_units_type, variable_scales, value_scale
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type, profile_statement, frame_tilt
    use rollcon_marker, only : marker_type, turn_marker
    use rollcon_joint_primitives, only : primitive_ucon_type, joint_ucons
    use rollcon_ucosub_catalog, only : builtin_ucosub_name
    use rollcon_rebasing, only : rebased_inertia, to_new_basis
    use rollcon_expression, only : expression_type
    use rollcon_gcon, only : gcon_type, new_gcon, gcon_codes, turn_gcon_markers
    use rollcon_measures, only : count_turns
    use rollcon_spring_force, only : count_spring_turns
    use rollcon_motion, only : motion_type
    use rollcon_diff, only : diff_set_type
    use rollcon_motion_geometry, only : motion_ucon, motion_rotation, motion_b1, motion_b2, &
        & motion_b3
    use rollcon_id_index, only : id_index_type, new_id_index
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: model_type, ucon_statement_type, statement_type, setup_model, served_by_model_ucosub
    public :: statement_ucon, statement_joint, statement_jprim, statement_element
    public :: force_request_type

    !> The kinds of statement a model's UCONs come from: a UCON; a JOINT or JPRIM (its
    !> equations, each a UCON of a generated routine, its reaction at its marker I); an element
    !> of one equation the program serves, named by its own words (a GCON, a MOTION, a
    !> coupling: COUPLER, GEAR, a RACKPIN or SCREW JOINT), its reaction at each part's centre
    integer, parameter :: statement_ucon = 1, statement_joint = 2, statement_jprim = 3, &
        & statement_element = 4

    !> A statement as its user wrote it: a UCON, or a JOINT or JPRIM (whose equations are UCONs
    !> of generated routines), or an element of one equation (a GCON, a MOTION, a coupling)
    type :: statement_type
        !> statement_ucon, statement_joint, statement_jprim or statement_element
        integer :: kind = statement_ucon
        !> Its id ("JOINT/3": 3)
        integer :: id = 0
        !> An element's name as its user wrote it ("MOTION/1", "COUPLER/2"; "" for the others)
        character(len=:), allocatable :: name
        !> The line of the dataset it was written on (0: a model built in code, no line)
        integer :: line = 0
        !> A JOINT's, JPRIM's or MOTION's markers I and J as the model holds them (part 0: the
        !> ground; their origins and axes in the part's principal axes, turned with the part at
        !> each re-basing), and the part of its marker J (model order, 0: the ground)
        type(marker_type) :: i, j
        integer :: j_part = 0
    end type statement_type

    !> A request for the force and torque between a JOINT's or JPRIM's two markers (a
    !> dataset's REQUEST/id, FORCE, I=, J= naming them): ADAMS's force and torque on the
    !> request's marker I, at I, in ground axes (rollcon_reaction_watch's req<id>_fx ... _tz)
    type :: force_request_type
        !> The request's id ("REQUEST/2": 2)
        integer :: id = 0
        !> The statement whose reaction it is (model%statements)
        integer :: statement = 0
        !> The request's I is the statement's J (and its J the statement's I)
        logical :: swapped = .false.
    end type force_request_type

    !> One UCON/id, FUNCTION=USER(par) statement and, after setup, where its variables live
    type :: ucon_statement_type
        !> Statement id
        integer :: id = 0
        !> Constants r1, ..., r30
        real(wp), allocatable :: par(:)
        !> Number of declared variables
        integer :: nvars = 0
        !> System coordinate number of each variable
        integer, allocatable :: coordinate(:)
        !> True where the variable is a rate (codes 21-26)
        logical, allocatable :: velocity(:)
        !> True when no variable is a rate: a position (holonomic) constraint
        logical :: holonomic = .false.
        !> True when F has no explicit time: dF/dt, d2F/dt2, d2F/dt dq and f(t) are identically
        !> zero and the driver never asks for them (default false: "may depend on time", ask)
        logical :: time_free = .false.
        !> The routine serving this statement: its own when given, else (from setup_model on)
        !> the model's UCOSUB
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
        !> The name of its own routine, for the record ("" when it has none: the model's UCOSUB
        !> serves it, served_by_model_ucosub)
        character(len=:), allocatable :: routine
        !> The routine works in the model's units, not SI (rollcon_ucosub_units): then each
        !> variable is passed as scales(i) * its SI value, the time as time_scale * t, and F
        !> comes back as F_SI = value_scale * F
        logical :: converted = .false.
        real(wp), allocatable :: scales(:)
        real(wp) :: time_scale = 1.0_wp, value_scale = 1.0_wp
        !> Geometry the driver owns (a joint's markers, docs/datasets.md "JOINT and JPRIM"):
        !> the PAR indices where 3-vectors fixed in a part start (an origin or an axis, in the
        !> part's principal axes), and that part (model order); each is turned with its part
        !> when the part is re-based
        integer, allocatable :: geometry_par(:), geometry_parts(:)
        !> A constraint written as an expression (GCON, and the couplers made of one): served
        !> by rollcon_gcon's evaluate_gcon instead of a UCOSUB
        type(gcon_type), allocatable :: gcon
        !> A MOTION's time part (rollcon_motion), allocated for a MOTION's UCON only: F is then
        !> s(q) - h(t), s the routine's value, and the time partials are the motion's
        !> (rollcon_constraints); the UCON computes in SI whatever the model's units
        type(motion_type), allocatable :: motion
        !> The statement it is (a UCON) or one equation of (a JOINT or JPRIM): its number in
        !> model%statements (set by add_ucon, add_joint and add_jprim; setup_model gives a UCON
        !> put in the list by hand a statement of its own)
        integer :: statement = 0
        !> Which equation of its JOINT or JPRIM it is, in words ("translation along ground X");
        !> "" for a UCON statement
        character(len=:), allocatable :: equation
    end type ucon_statement_type

    !> The model
    type :: model_type
        !> Rigid parts
        type(part_type), allocatable :: parts(:)
        !> UCONs: the UCON statements and the equations of the JOINTs and JPRIMs
        type(ucon_statement_type), allocatable :: ucons(:)
        !> The statements as their user wrote them, in the order they were added
        type(statement_type), allocatable :: statements(:)
        !> Report each statement's reaction (the force and torque it exerts on its part) in the
        !> rows (rollcon_reaction_watch); a disk scene, whose rim contact watch reports the
        !> contact's force, leaves it off
        logical :: report_reactions = .true.
        !> Requests for a JOINT's or JPRIM's reaction between its markers, reported as columns
        !> beside the statements' own (rollcon_reaction_watch)
        type(force_request_type), allocatable :: force_requests(:)
        !> The UCOSUB serving every UCON of the model
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
        !> Applied forces
        type(applied_force_type), allocatable :: forces(:)
        !> The units every UCOSUB of the model computes in (a dataset's UNITS; SI by default)
        type(ucosub_units_type) :: ucosub_units
        !> Gravitational acceleration, ground components [m/s^2]
        real(wp) :: gravity(3) = [0.0_wp, 0.0_wp, -9.81_wp]
        !> What the UCOSUB declared
        type(ucovar_registry_type) :: registry
        !> Number of coordinates (6 per part), of constraints, of holonomic constraints
        integer :: n = 0, nc = 0, nh = 0
        !> For each UCON, its number among the holonomic ones (0 when it is a velocity UCON)
        integer, allocatable :: holonomic_number(:)
        !> A dataset's DIFFs (user differential equations, rollcon_diff) and their state last
        !> set (set_diff_state); none in a model without them
        type(diff_set_type) :: diffs
        !> While additions are open (open_additions to close_additions: a builder adding many
        !> statements), how many of ucons and statements are the model's (past them, spare
        !> capacity, doubled when full: n additions then copy O(n) elements in all, not the
        !> O(n^2) of arrays grown by one at each), and the largest UCON id so far; -1 when
        !> closed: ucons and statements are then exactly the model's, as everywhere else
        integer :: open_ucons = -1, open_statements = 0, open_largest_id = 0
    contains
        procedure :: open_additions
        procedure :: close_additions
        procedure :: ucon_count
        procedure :: statement_count
        procedure :: add_part
        procedure :: add_ucon
        procedure :: add_joint
        procedure :: add_jprim
        procedure :: add_force
        procedure :: add_gcon
        procedure :: add_element_ucons
        procedure :: count_turns => count_model_turns
        procedure :: add_motion
        procedure :: turn_part_axes
        procedure :: turn_ucon_geometry
        procedure :: set_diff_state
        procedure :: statement_name
        procedure :: row_words
        procedure :: rows_text
    end type model_type

contains

    !> Append a part.
    subroutine add_part(self, part)
        class(model_type), intent(inout) :: self
        type(part_type), intent(in) :: part

        if (.not. allocated(self%parts)) allocate(self%parts(0))
        self%parts = [self%parts, part]
    end subroutine add_part

    !> Append a UCON statement.
    subroutine add_ucon(self, id, par, ucosub, time_free, routine, line)
        class(model_type), intent(inout) :: self
        !> Statement id
        integer, intent(in) :: id
        !> Its constants
        real(wp), intent(in) :: par(:)
        !> A routine of its own (ADAMS has one UCOSUB per model; rollcon allows one per UCON);
        !> without it, the model's UCOSUB serves the UCON
        procedure(ucosub_interface), optional :: ucosub
        !> The routine's F has no explicit time (a generated module's `<spec>_time_free`): the
        !> time partials are then taken as zero without calling it. Default false; a UCON the
        !> model's UCOSUB serves takes it from setup_model when that routine is a built-in one.
        logical, intent(in), optional :: time_free
        !> The name of the routine given as ucosub, for the run's record (a built-in's name;
        !> "its own" when not given)
        character(len=*), intent(in), optional :: routine
        !> The dataset line of the statement, for messages (default 0: no line)
        integer, intent(in), optional :: line
        type(ucon_statement_type) :: ucon
        type(statement_type) :: statement

        statement%kind = statement_ucon
        statement%id = id
        if (present(line)) statement%line = line
        call push_statement(self, statement)
        ucon%statement = self%statement_count()
        ucon%equation = ""
        ucon%id = id
        ucon%par = par
        ucon%routine = ""
        if (present(ucosub)) then
            ucon%ucosub => ucosub
            ucon%routine = "its own"
            if (present(routine)) then
                if (len_trim(routine) > 0) ucon%routine = trim(routine)
            end if
        end if
        if (present(time_free)) ucon%time_free = time_free
        call push_ucon(self, ucon)
    end subroutine add_ucon

    !> True when the model's UCOSUB serves a UCON whose own routine is named `routine` (""
    !> when it names none): ADAMS's rule, one UCOSUB per model serves every UCON that names no
    !> ROUTINE; rollcon lets a UCON name its own. The one statement of the rule: setup_model
    !> gives such a UCON the model's routine, a run's record and a dataset's assembly ask here.
    pure logical function served_by_model_ucosub(routine)
        !> The name of the UCON's own routine (ucon_statement_type's routine, a dataset's
        !> ROUTINE=), "" for none
        character(len=*), intent(in) :: routine

        served_by_model_ucosub = len_trim(routine) == 0
    end function served_by_model_ucosub

    !> Append JOINT/id, a joint of type kind (REVOLUTE, SPHERICAL, UNIVERSAL, CYLINDRICAL,
    !> TRANSLATIONAL, FIXED, PLANAR, HOOKE, CONVEL: rollcon_joint_types) between marker i and
    !> marker j, as the UCONs of its primitives (rollcon_joint_primitives): they take the ids
    !> after the largest UCON id of the model, in the order of the primitives and their
    !> components, and the model's length unit (ucosub_units). Add the parts first. Refused: an
    !> unknown type, markers on parts the model does not have, or both on one part.
    subroutine add_joint(self, id, kind, i, j, error, line)
        class(model_type), intent(inout) :: self
        !> The joint's id, for messages ("JOINT/3")
        integer, intent(in) :: id
        !> Its type, in capitals and in full
        character(len=*), intent(in) :: kind
        !> Marker I and marker J: their part (model order, 0 for the ground), origin and axes
        !> in the part's principal axes (rollcon_marker's part_marker)
        type(marker_type), intent(in) :: i, j
        type(error_type), allocatable, intent(out) :: error
        !> The dataset line of the statement, for messages (default 0: no line)
        integer, intent(in), optional :: line
        integer :: at

        at = 0
        if (present(line)) at = line
        call add_primitives(self, .false., id, kind, i, j, at, error)
    end subroutine add_joint

    !> Append JPRIM/id, a joint primitive of type kind (ATPOINT, INLINE, INPLANE,
    !> PARALLEL_AXES, PERPENDICULAR, ORIENTATION) between marker i and marker j, as add_joint
    !> does. An INLINE or INPLANE with marker I on the ground is refused (it is not symmetric
    !> in I and J, and the routines hold the part of I).
    subroutine add_jprim(self, id, kind, i, j, error, line)
        class(model_type), intent(inout) :: self
        !> The primitive's id, for messages ("JPRIM/3")
        integer, intent(in) :: id
        !> Its type, in capitals and in full
        character(len=*), intent(in) :: kind
        !> Marker I and marker J (part 0: the ground)
        type(marker_type), intent(in) :: i, j
        type(error_type), allocatable, intent(out) :: error
        !> The dataset line of the statement, for messages (default 0: no line)
        integer, intent(in), optional :: line
        integer :: at

        at = 0
        if (present(line)) at = line
        call add_primitives(self, .true., id, kind, i, j, at, error)
    end subroutine add_jprim

    !> The UCONs of a JOINT (primitive false) or JPRIM, appended, and its statement.
    subroutine add_primitives(self, primitive, id, kind, i, j, line, error)
        class(model_type), intent(inout) :: self
        logical, intent(in) :: primitive
        integer, intent(in) :: id
        character(len=*), intent(in) :: kind
        type(marker_type), intent(in) :: i, j
        integer, intent(in) :: line
        type(error_type), allocatable, intent(out) :: error
        type(primitive_ucon_type), allocatable :: ucons(:)
        type(statement_type) :: statement
        type(ucon_statement_type) :: ucon
        integer, allocatable :: part_ids(:)
        integer :: k, next_id

        if (.not. allocated(self%parts)) allocate(self%parts(0))
        if (.not. allocated(self%ucons)) allocate(self%ucons(0))
        part_ids = self%parts%id
        call joint_ucons(primitive, id, kind, i, j, part_ids, self%ucosub_units%length, ucons, &
            & error)
        if (allocated(error)) return
        statement%kind = merge(statement_jprim, statement_joint, primitive)
        statement%id = id
        statement%line = line
        statement%i = i
        statement%j = j
        statement%j_part = j%part
        call push_statement(self, statement)
        next_id = largest_ucon_id(self)
        do k = 1, size(ucons)
            next_id = next_id + 1
            ucon%id = next_id
            ucon%par = ucons(k)%par
            ucon%ucosub => ucons(k)%ucosub
            ucon%routine = ucons(k)%routine
            ucon%time_free = .true.
            ucon%geometry_par = ucons(k)%geometry_par
            ucon%geometry_parts = ucons(k)%geometry_parts
            ucon%statement = self%statement_count()
            ucon%equation = ucons(k)%equation
            call push_ucon(self, ucon)
        end do
    end subroutine add_primitives

    !> Append GCON/id, the constraint expression = 0 (rollcon_gcon): a UCON whose F and
    !> partials come from the expression, reading `markers` (every marker its measures name,
    !> as the model holds them; add the parts first), its reaction reported at marker
    !> `reaction`. The expression is in the model's units (ucosub_units). It takes the id after
    !> the largest UCON id of the model, as a joint's UCONs do, and is named `name` in the
    !> run's record ("GCON/1"; default "GCON/id"). Refused, with why: a FUNCTION that reads an
    !> acceleration, a force or another statement's value, or no moving part, or more than 30
    !> variables, or velocities in a way that is not linear (rollcon_gcon's new_gcon). line:
    !> the statement's line in the dataset (default 0: none), for the user's words ("GCON/1
    !> (line 12)"; the UCON's own id is never shown).
    subroutine add_gcon(self, id, expression, markers, reaction, error, name, line)
        class(model_type), intent(inout) :: self
        !> The statement's id, for messages
        integer, intent(in) :: id
        !> F, compiled (rollcon_adm_expression_parser's compile_expression)
        type(expression_type), intent(in) :: expression
        type(marker_type), intent(in) :: markers(:), reaction
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: name
        integer, intent(in), optional :: line
        type(ucon_statement_type) :: ucon
        character(len=:), allocatable :: problem

        if (.not. allocated(self%ucons)) allocate(self%ucons(0))
        allocate(ucon%gcon)
        call new_gcon(id, expression, markers, reaction, self%ucosub_units%length, &
            & self%ucosub_units%time, ucon%gcon, problem)
        if (len(problem) > 0) then
            call fatal_error(error, "GCON/" // to_text(id) // " FUNCTION: " // problem, &
                & stat_input)
            return
        end if
        ucon%id = 1
        if (self%ucon_count() > 0) ucon%id = largest_ucon_id(self) + 1
        ucon%par = [real(wp) :: ]
        ucon%routine = "GCON/" // to_text(id)
        if (present(name)) ucon%routine = name
        ucon%time_free = .not. expression%uses_time
        call add_element(self, ucon, ucon%routine, id, line)
        call push_ucon(self, ucon)
    end subroutine add_gcon

    !> Append the equations of one element its user wrote as one statement (a dataset's
    !> CONTACT: its three no-slip rows), each a UCON served by ucosub with its constants
    !> par(:, k) and named by equations(k) in the user's words, all under one statement of
    !> kind statement_element named `name` ("CONTACT/1") at `line`. They take the ids after the
    !> largest UCON id of the model, as a joint's UCONs do; their rows follow the model's
    !> UCONs so far, in order.
    subroutine add_element_ucons(self, name, id, line, ucosub, routine, time_free, par, &
            & equations)
        class(model_type), intent(inout) :: self
        character(len=*), intent(in) :: name
        !> The statement's id and line (0: none)
        integer, intent(in) :: id, line
        procedure(ucosub_interface) :: ucosub
        !> The routine's name (a built-in's), and whether its F is free of time
        character(len=*), intent(in) :: routine
        logical, intent(in) :: time_free
        !> Constants of each equation (columns)
        real(wp), intent(in) :: par(:, :)
        character(len=*), intent(in) :: equations(:)
        type(ucon_statement_type) :: ucon
        integer :: k, next_id, statement

        if (.not. allocated(self%ucons)) allocate(self%ucons(0))
        next_id = largest_ucon_id(self)
        do k = 1, size(par, 2)
            ucon%id = next_id + k
            ucon%par = par(:, k)
            ucon%ucosub => ucosub
            ucon%routine = routine
            ucon%time_free = time_free
            if (k == 1) then
                call add_element(self, ucon, name, id, line)
                statement = ucon%statement
            end if
            ucon%statement = statement
            ucon%equation = trim(equations(k))
            call push_ucon(self, ucon)
        end do
    end subroutine add_element_ucons

    !> Give ucon, one equation of an element (a GCON, a MOTION, a coupling), a statement of its
    !> own: kind statement_element, named `name` ("MOTION/1"), at `line` (absent: 0).
    pure subroutine add_element(self, ucon, name, id, line)
        class(model_type), intent(inout) :: self
        type(ucon_statement_type), intent(inout) :: ucon
        character(len=*), intent(in) :: name
        integer, intent(in) :: id
        integer, intent(in), optional :: line
        type(statement_type) :: statement

        statement%kind = statement_element
        statement%id = id
        statement%name = name
        if (present(line)) statement%line = line
        call push_statement(self, statement)
        ucon%statement = self%statement_count()
        ucon%equation = ""
    end subroutine add_element

    !> Count the whole turns of every AX, AY, AZ the model's expressions read (its force
    !> statements' and GCONs') and of its rotational SPRINGDAMPERs' angles at (q, u):
    !> rollcon_measures' count_turns. A run makes it at its
    !> start (restart true: each angle on its branch in (-pi, pi]) and at every output row.
    pure subroutine count_model_turns(self, q, u, restart)
        class(model_type), intent(inout) :: self
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        logical, intent(in) :: restart
        integer :: i, k

        if (allocated(self%forces)) then
            do i = 1, size(self%forces)
                if (self%forces(i)%profile /= profile_statement) cycle
                associate (s => self%forces(i)%statement)
                    ! a rotational SPRINGDAMPER's AZ (rollcon_spring_force)
                    call count_spring_turns(s%spring, s%i, s%j, q, u, restart)
                    if (.not. allocated(s%markers)) cycle
                    do k = 1, 6
                        if (s%given(k)) call count_turns(s%functions(k), s%markers, &
                            & s%length_unit, s%time_unit, q, u, restart)
                    end do
                end associate
            end do
        end if
        call self%diffs%count_turns(q, u, restart)
        if (.not. allocated(self%ucons)) return
        do k = 1, size(self%ucons)
            if (.not. allocated(self%ucons(k)%gcon)) cycle
            associate (g => self%ucons(k)%gcon)
                call count_turns(g%expression, g%markers, g%length_unit, g%time_unit, q, u, &
                    & restart)
            end associate
        end do
    end subroutine count_model_turns

    !> Append MOTION/motion%id, driving `component` (rollcon_motion_geometry's motion_x ...
    !> motion_rotation) of marker i from marker j by its time part `motion`: a UCON F = s(q) -
    !> h(t) (rollcon_motion), its id after the largest UCON id of the model, served by the
    !> generated routine of s (motion_ucon), in SI. joint: the MOTION is on a joint (its
    !> TRANSLATION may then be served from J's part when I is on the ground). Add the parts
    !> first. Refused as motion_ucon refuses, naming motion%name. Its statement is
    !> "MOTION/id" at `line` (default 0: none) in every message and column (its UCON's id is
    !> never shown).
    subroutine add_motion(self, motion, component, joint, i, j, error, line)
        class(model_type), intent(inout) :: self
        !> The time part: its id, name, function and form (motion%rotational is set here)
        type(motion_type), intent(in) :: motion
        integer, intent(in) :: component
        logical, intent(in) :: joint
        !> Marker I and marker J (part 0: the ground), as part_marker places them
        type(marker_type), intent(in) :: i, j
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: line
        type(primitive_ucon_type) :: ucon
        integer, allocatable :: part_ids(:)
        integer :: next_id

        if (.not. allocated(self%parts)) allocate(self%parts(0))
        if (.not. allocated(self%ucons)) allocate(self%ucons(0))
        part_ids = self%parts%id
        call motion_ucon(motion%name, component, joint, i, j, part_ids, ucon, error)
        if (allocated(error)) return
        next_id = largest_ucon_id(self)
        ! its own time partials: not time-free (rollcon_constraints asks the motion for them)
        call self%add_ucon(next_id + 1, ucon%par, ucon%ucosub, time_free=.false., &
            & routine=ucon%routine)
        associate (added => self%ucons(self%ucon_count()))
            added%geometry_par = ucon%geometry_par
            added%geometry_parts = ucon%geometry_parts
            allocate(added%motion, source=motion)
            added%motion%rotational = any(component == [motion_rotation, motion_b1, motion_b2, &
                & motion_b3])
            associate (statement => self%statements(added%statement))
                statement%kind = statement_element
                statement%id = motion%id
                statement%name = "MOTION/" // to_text(motion%id)
                if (present(line)) statement%line = line
                ! its markers, where its reaction acts (rollcon_force_measures)
                statement%i = i
                statement%j = j
                statement%j_part = j%part
            end associate
        end associate
    end subroutine add_motion
    !> Append a statement (element by element: gfortran 12 may mishandle an array constructor
    !> of a type with allocatable components).
    pure subroutine append_statement(statements, statement)
        type(statement_type), allocatable, intent(inout) :: statements(:)
        type(statement_type), intent(in) :: statement
        type(statement_type), allocatable :: grown(:)
        integer :: k

        if (.not. allocated(statements)) allocate(statements(0))
        allocate(grown(size(statements) + 1))
        do k = 1, size(statements)
            grown(k) = statements(k)
        end do
        grown(size(grown)) = statement
        call move_alloc(grown, statements)
    end subroutine append_statement

    !> Open the model to many additions (a dataset's builder adding its UCONs and joints): from
    !> here to close_additions, add_ucon, add_joint, add_jprim, add_gcon, add_element_ucons
    !> and add_motion grow model%ucons and model%statements by doubling their capacity, so that
    !> n of them cost O(n) in all (docs/design.md §4, "Many parts": start-up). Meanwhile only
    !> ucon_count() and statement_count() tell how many there are (the arrays hold spare
    !> entries past them): close the additions before anything else reads the model.
    !> setup_model closes them if they are open. Opening them again while open does nothing.
    pure subroutine open_additions(self)
        class(model_type), intent(inout) :: self

        if (self%open_ucons >= 0) return
        if (.not. allocated(self%ucons)) allocate(self%ucons(0))
        if (.not. allocated(self%statements)) allocate(self%statements(0))
        self%open_ucons = size(self%ucons)
        self%open_statements = size(self%statements)
        self%open_largest_id = 0
        if (size(self%ucons) > 0) self%open_largest_id = maxval(self%ucons%id)
    end subroutine open_additions

    !> Close the additions open_additions opened: model%ucons and model%statements cut to the
    !> model's own (one copy of each). Nothing when they are not open.
    pure subroutine close_additions(self)
        class(model_type), intent(inout) :: self
        type(ucon_statement_type), allocatable :: ucons(:)
        type(statement_type), allocatable :: statements(:)
        integer :: k

        if (self%open_ucons < 0) return
        if (size(self%ucons) /= self%open_ucons) then
            allocate(ucons(self%open_ucons))
            do k = 1, self%open_ucons
                ucons(k) = self%ucons(k)
            end do
            call move_alloc(ucons, self%ucons)
        end if
        if (size(self%statements) /= self%open_statements) then
            allocate(statements(self%open_statements))
            do k = 1, self%open_statements
                statements(k) = self%statements(k)
            end do
            call move_alloc(statements, self%statements)
        end if
        self%open_ucons = -1
        self%open_statements = 0
        self%open_largest_id = 0
    end subroutine close_additions

    !> The model's UCONs so far (size(model%ucons) once the additions are closed).
    pure integer function ucon_count(self) result(count)
        class(model_type), intent(in) :: self

        if (self%open_ucons >= 0) then
            count = self%open_ucons
        else if (allocated(self%ucons)) then
            count = size(self%ucons)
        else
            count = 0
        end if
    end function ucon_count

    !> The model's statements so far (size(model%statements) once the additions are closed).
    pure integer function statement_count(self) result(count)
        class(model_type), intent(in) :: self

        if (self%open_ucons >= 0) then
            count = self%open_statements
        else if (allocated(self%statements)) then
            count = size(self%statements)
        else
            count = 0
        end if
    end function statement_count

    !> The largest UCON id of the model so far (0 without UCONs): a joint's UCONs take the ids
    !> after it.
    pure integer function largest_ucon_id(self) result(id)
        class(model_type), intent(in) :: self

        id = 0
        if (self%open_ucons >= 0) then
            id = self%open_largest_id
        else if (allocated(self%ucons)) then
            if (size(self%ucons) > 0) id = maxval(self%ucons%id)
        end if
    end function largest_ucon_id

    !> Append a UCON: one more entry, or with the additions open, the next of the spare ones
    !> (the capacity doubled first when none is left).
    pure subroutine push_ucon(self, ucon)
        class(model_type), intent(inout) :: self
        type(ucon_statement_type), intent(in) :: ucon
        type(ucon_statement_type), allocatable :: grown(:)
        integer :: k

        if (.not. allocated(self%ucons)) allocate(self%ucons(0))
        if (self%open_ucons < 0) then
            allocate(grown(size(self%ucons) + 1))
            do k = 1, size(self%ucons)
                grown(k) = self%ucons(k)
            end do
            grown(size(grown)) = ucon
            call move_alloc(grown, self%ucons)
            return
        end if
        if (self%open_ucons == size(self%ucons)) then
            allocate(grown(max(8, 2*size(self%ucons))))
            do k = 1, self%open_ucons
                grown(k) = self%ucons(k)
            end do
            call move_alloc(grown, self%ucons)
        end if
        self%open_ucons = self%open_ucons + 1
        self%ucons(self%open_ucons) = ucon
        self%open_largest_id = max(self%open_largest_id, ucon%id)
    end subroutine push_ucon

    !> Append a statement, as push_ucon appends a UCON.
    pure subroutine push_statement(self, statement)
        class(model_type), intent(inout) :: self
        type(statement_type), intent(in) :: statement
        type(statement_type), allocatable :: grown(:)
        integer :: k

        if (self%open_ucons < 0) then
            call append_statement(self%statements, statement)
            return
        end if
        if (self%open_statements == size(self%statements)) then
            allocate(grown(max(8, 2*size(self%statements))))
            do k = 1, self%open_statements
                grown(k) = self%statements(k)
            end do
            call move_alloc(grown, self%statements)
        end if
        self%open_statements = self%open_statements + 1
        self%statements(self%open_statements) = statement
    end subroutine push_statement

    !> "JOINT/3 (line 40)", "UCON/5" (no line for a model built in code) of statement s.
    pure function statement_name(self, s) result(name)
        class(model_type), intent(in) :: self
        !> Its number in self%statements
        integer, intent(in) :: s
        character(len=:), allocatable :: name

        associate (statement => self%statements(s))
            select case (statement%kind)
            case (statement_joint)
                name = "JOINT/"
            case (statement_jprim)
                name = "JPRIM/"
            case default
                name = "UCON/"
            end select
            name = name // to_text(statement%id)
            if (statement%kind == statement_element) name = statement%name
            if (statement%line > 0) name = name // " (line " // to_text(statement%line) // ")"
        end associate
    end function statement_name

    !> UCON k (model order) in the user's words: its statement, and for an equation of a JOINT
    !> or JPRIM which one ("JOINT/3 (line 40), its rotation about J's x"; "UCON/5 (line 12)").
    pure function row_words(self, k) result(words)
        class(model_type), intent(in) :: self
        integer, intent(in) :: k
        character(len=:), allocatable :: words

        words = self%statement_name(self%ucons(k)%statement)
        if (allocated(self%ucons(k)%equation)) then
            if (len(self%ucons(k)%equation) > 0) words = words // ", its " &
                & // self%ucons(k)%equation
        end if
    end function row_words

    !> The flagged UCONs (model order, flagged(k) for UCON k) in the user's words, each
    !> statement once, in the order of its first flagged UCON, with the equations of a JOINT or
    !> JPRIM flagged: "JOINT/1 (line 14: translation along ground Z), UCON/2 and JOINT/3 (line
    !> 16: rotation about J's x, rotation about J's y)".
    pure function rows_text(self, flagged) result(text)
        class(model_type), intent(in) :: self
        logical, intent(in) :: flagged(:)
        character(len=:), allocatable :: text, item
        integer, allocatable :: order(:)
        integer :: k, l, n, s

        allocate(order(0))
        do k = 1, size(flagged)
            if (flagged(k) .and. .not. any(order == self%ucons(k)%statement)) &
                & order = [order, self%ucons(k)%statement]
        end do
        text = ""
        do n = 1, size(order)
            s = order(n)
            item = self%statement_name(s)
            if (any(self%statements(s)%kind == [statement_joint, statement_jprim])) then
                if (self%statements(s)%line > 0) then
                    item = item(:len(item) - 1) // ": "
                else
                    item = item // " ("
                end if
                k = 0
                do l = 1, size(flagged)
                    if (.not. flagged(l) .or. self%ucons(l)%statement /= s) cycle
                    if (k > 0) item = item // ", "
                    item = item // self%ucons(l)%equation
                    k = k + 1
                end do
                item = item // ")"
            end if
            if (n > 1 .and. n == size(order)) then
                text = text // " and "
            else if (n > 1) then
                text = text // ", "
            end if
            text = text // item
        end do
    end function rows_text

    !> Append an applied force.
    subroutine add_force(self, force)
        class(model_type), intent(inout) :: self
        type(applied_force_type), intent(in) :: force

        if (.not. allocated(self%forces)) allocate(self%forces(0))
        self%forces = [self%forces, force]
    end subroutine add_force

    !> The DIFFs' state: DIF x and DIF1 w of each [the user's units, per the dataset's time
    !> unit], kept in diffs and given to every force statement that reads them (its dif).
    pure subroutine set_diff_state(self, x, w)
        class(model_type), intent(inout) :: self
        real(wp), intent(in) :: x(:), w(:)
        integer :: i

        if (self%diffs%count() == 0) return
        self%diffs%x = x
        self%diffs%w = w
        if (.not. allocated(self%forces)) return
        do i = 1, size(self%forces)
            associate (statement => self%forces(i)%statement)
                if (.not. allocated(statement%dif_ids)) cycle
                statement%dif(:, 1) = x
                statement%dif(:, 2) = w
            end associate
        end do
    end subroutine set_diff_state

    !> Re-base part p (model order) on its principal axes turned by `turn` (rollcon_rebasing's
    !> turn_about_x or turn_about_y): its principal moments permuted, and every body-fixed
    !> quantity of the part (the markers of force statements, the points of fixed-direction
    !> forces) given in the new axes. A CM marker then no longer has the part's principal axes
    !> (its angles are computed from its axes). A force applied in a disk's tilt frame cannot
    !> be turned: refused.
    subroutine turn_part_axes(self, p, turn, error)
        class(model_type), intent(inout) :: self
        !> Part index (model order)
        integer, intent(in) :: p
        !> The turn
        integer, intent(in) :: turn
        type(error_type), allocatable, intent(out) :: error
        integer :: i, k

        do i = 1, size(self%forces)
            associate (force => self%forces(i))
                if (force%profile == profile_statement) then
                    call turn_marker(force%statement%i, p, turn)
                    call turn_marker(force%statement%j, p, turn)
                    call turn_marker(force%statement%rm, p, turn)
                    if (allocated(force%statement%markers)) then
                        do k = 1, size(force%statement%markers)
                            call turn_marker(force%statement%markers(k), p, turn)
                        end do
                    end if
                else if (force%part == p) then
                    if (force%frame == frame_tilt) then
                        call fatal_error(error, "part " // to_text(self%parts(p)%id) &
                            & // " cannot be re-based: force " // to_text(i) &
                            & // " is applied in its tilt frame, which has no meaning in " &
                            & // "other principal axes", stat_input)
                        return
                    end if
                    force%point = to_new_basis(force%point, turn)
                end if
            end associate
        end do
        call self%turn_ucon_geometry(p, turn)
        call self%diffs%part_rebased(p, turn)
        do k = 1, size(self%ucons)
            if (allocated(self%ucons(k)%gcon)) call turn_gcon_markers(self%ucons(k)%gcon, p, &
                & turn)
        end do
        if (allocated(self%statements)) then
            do k = 1, size(self%statements)
                call turn_marker(self%statements(k)%i, p, turn)
                call turn_marker(self%statements(k)%j, p, turn)
            end do
        end if
        self%parts(p)%inertia = rebased_inertia(self%parts(p)%inertia, turn)
    end subroutine turn_part_axes

    !> The PAR entries of every UCON that hold geometry fixed in part p (a joint's marker
    !> origins and axes, in the part's principal axes) given in the part's turned axes, so that
    !> the UCON's F stays the same across a re-basing (docs/rebasing.md).
    subroutine turn_ucon_geometry(self, p, turn)
        class(model_type), intent(inout) :: self
        !> Part index (model order)
        integer, intent(in) :: p
        !> The re-basing's turn (rollcon_rebasing's turn_about_x or turn_about_y)
        integer, intent(in) :: turn
        integer :: k, i, s

        if (.not. allocated(self%ucons)) return
        do k = 1, size(self%ucons)
            associate (ucon => self%ucons(k))
                if (.not. allocated(ucon%geometry_par)) cycle
                do i = 1, size(ucon%geometry_par)
                    if (ucon%geometry_parts(i) /= p) cycle
                    s = ucon%geometry_par(i)
                    ucon%par(s:s + 2) = to_new_basis(ucon%par(s:s + 2), turn)
                end do
            end associate
        end do
    end subroutine turn_ucon_geometry

    !> Initialise every UCON (IFLAG = 3), validate the declarations, map variables to coordinates.
    subroutine setup_model(model, error)
        type(model_type), target, intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: model_name
        logical :: model_time_free
        integer :: k, i, p, entry, previous
        integer, allocatable :: declared_parts(:), declared_codes(:), part_ids(:)
        !> The model's parts and UCONs by id (found in constant time: the set-up is linear in
        !> the model's size, docs/design.md §4 "Many parts": start-up)
        type(id_index_type) :: parts_by_id, ucons_by_id

        call model%close_additions()
        if (.not. allocated(model%parts)) allocate(model%parts(0))
        if (.not. allocated(model%ucons)) allocate(model%ucons(0))
        if (.not. allocated(model%forces)) allocate(model%forces(0))
        if (.not. allocated(model%statements)) allocate(model%statements(0))
        ! a UCON put in the list by hand is a statement of its own
        do k = 1, size(model%ucons)
            if (model%ucons(k)%statement > 0) cycle
            call append_statement(model%statements, statement_type(kind=statement_ucon, &
                & id=model%ucons(k)%id))
            model%ucons(k)%statement = size(model%statements)
            model%ucons(k)%equation = ""
        end do
        if (size(model%parts) == 0) then
            call fatal_error(error, "the model has no part", stat_input)
            return
        end if
        ! the model's UCOSUB serves every UCON that names no routine of its own; a built-in
        ! one whose F has no explicit time spares the driver the time partials
        model_time_free = .false.
        if (associated(model%ucosub)) model_name = builtin_ucosub_name(model%ucosub, &
            & model_time_free)
        do k = 1, size(model%ucons)
            associate (ucon => model%ucons(k))
                if (.not. allocated(ucon%routine)) ucon%routine = ""
                ! a GCON is served by its expression
                if (allocated(ucon%gcon)) cycle
                if (served_by_model_ucosub(ucon%routine)) then
                    ucon%ucosub => model%ucosub
                    ucon%time_free = ucon%time_free .or. model_time_free
                end if
                if (.not. associated(ucon%ucosub)) then
                    call ucon_error(error, ucon%id, "no UCOSUB serves this statement")
                    return
                end if
            end associate
        end do
        do i = 1, size(model%parts)
            if (model%parts(i)%mass <= 0.0_wp .or. any(model%parts(i)%inertia <= 0.0_wp)) then
                call fatal_error(error, "part " // to_text(model%parts(i)%id) &
                    & // " needs a positive mass and positive principal moments", stat_input)
                return
            end if
        end do
        model%n = 6*size(model%parts)
        model%nc = size(model%ucons)
        model%registry = ucovar_registry_type()
        parts_by_id = new_id_index(size(model%parts))
        do p = 1, size(model%parts)
            ! a later part of an id already held is not stored: the first one is found
            call parts_by_id%add(int(model%parts(p)%id, int64), p, previous)
        end do
        ucons_by_id = new_id_index(model%nc)
        allocate(model%holonomic_number(model%nc), source=0)
        model%nh = 0
        do k = 1, model%nc
            associate (ucon => model%ucons(k))
                if (size(ucon%par) > max_ucon_par) then
                    call ucon_error(error, ucon%id, "has " // to_text(size(ucon%par)) &
                        & // " constants; at most " // to_text(max_ucon_par))
                    return
                end if
                call ucons_by_id%add(int(ucon%id, int64), k, previous)
                if (previous > 0) then
                    call ucon_error(error, ucon%id, "the id is used by two UCON statements")
                    return
                end if
                if (allocated(ucon%gcon)) then
                    part_ids = model%parts%id
                    call gcon_codes(ucon%gcon, part_ids, declared_parts, declared_codes)
                    call model%registry%declare(ucon%id, size(declared_parts), &
                        & declared_parts, size(declared_codes), declared_codes, error)
                else
                    call declare_ucon(ucon%ucosub, ucon%id, ucon%par, model%registry, error)
                end if
                if (allocated(error)) return
                entry = model%registry%find(ucon%id)
                associate (declared => model%registry%entries(entry))
                    ucon%nvars = size(declared%codes)
                    ucon%velocity = is_velocity_code(declared%codes)
                    allocate(ucon%coordinate(ucon%nvars))
                    do i = 1, ucon%nvars
                        p = parts_by_id%find(int(declared%parts(i), int64))
                        if (p == 0) then
                            call ucon_error(error, ucon%id, "UCOVAR variable " // to_text(i) &
                                & // " (" // code_name(declared%codes(i)) // ") belongs to part " &
                                & // to_text(declared%parts(i)) &
                                & // ", which the model does not have")
                            return
                        end if
                        ucon%coordinate(i) = 6*(p - 1) + code_coordinate(declared%codes(i))
                    end do
                end associate
                ucon%holonomic = .not. any(ucon%velocity)
                ! a GCON takes SI variables and converts its expression's measures itself
                ucon%converted = .not. model%ucosub_units%is_si() .and. &
                    & .not. allocated(ucon%gcon)
                ! a MOTION's UCON computes in SI (rollcon_motion_geometry)
                ucon%converted = .not. model%ucosub_units%is_si() .and. .not. &
                    & allocated(ucon%motion)
                if (ucon%converted) then
                    ucon%scales = variable_scales(model%ucosub_units, &
                        & model%registry%entries(entry)%codes)
                    ucon%time_scale = 1.0_wp/model%ucosub_units%time
                    ucon%value_scale = value_scale(model%ucosub_units, ucon%holonomic)
                end if
                if (ucon%holonomic) then
                    model%nh = model%nh + 1
                    model%holonomic_number(k) = model%nh
                end if
            end associate
        end do
    end subroutine setup_model

end module rollcon_model
