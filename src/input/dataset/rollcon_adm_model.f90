! SPDX-License-Identifier: MIT
!> What a dataset states, in SI units and radians, before it becomes a model to simulate:
!> parts, markers, UCON statements, forces with their expressions, gravity and the run; the
!> displacement requests it honours as output columns, its other requests, and the statements
!> (or keywords) of ADAMS's outputs and solver choices it read and checked but does not use.
module rollcon_adm_model
    use rollcon_kinds, only : wp
    use rollcon_expression, only : expression_type
    use rollcon_adm_units, only : units_type
    use rollcon_run_settings, only : run_settings_type, analysis_dynamic
    use rollcon_adm_joints, only : adm_joint_type
    use rollcon_adm_couplers, only : adm_gcon_type, adm_coupler_type, adm_gear_type
    use rollcon_adm_motions, only : adm_motion_type
    use rollcon_adm_data, only : adm_string_type, adm_array_type
    use rollcon_adm_contacts, only : adm_contact_type, adm_graphics_type
    use rollcon_adm_system, only : adm_variable_type, adm_spline_data_type, adm_plant_type, &
        & adm_diff_type
    implicit none
    private

    public :: adm_part_type, adm_marker_type, adm_ucon_type, adm_force_type, adm_run_type
    public :: adm_segment_type
    public :: adm_model_type, force_sforce, force_vforce, force_gforce, force_springdamper
    public :: force_bushing, force_vtorque, force_names
    public :: adm_request_type, adm_unused_type, adm_reference_type
    public :: refers_to_marker, refers_to_part, refers_to_force
    public :: adm_request_column_type, request_displacement, request_velocity, &
        & request_acceleration, request_force, request_expressions, request_user

    !> Kinds of force statement
    integer, parameter :: force_sforce = 1, force_vforce = 2, force_gforce = 3, &
        & force_springdamper = 4, force_bushing = 5, force_vtorque = 6
    !> Their statements' names, by kind
    character(len=*), parameter :: force_names(6) = [character(len=12) :: "SFORCE", "VFORCE", &
        & "GFORCE", "SPRINGDAMPER", "BUSHING", "VTORQUE"]
    !> What a REQUEST asks for
    integer, parameter :: request_displacement = 1, request_velocity = 2, &
        & request_acceleration = 3, request_force = 4, request_expressions = 5, request_user = 6
    !> What a reference of a statement read and not used names
    integer, parameter :: refers_to_marker = 1, refers_to_part = 2, refers_to_force = 3

    !> PART/id
    type :: adm_part_type
        integer :: id = 0
        !> Line of the statement
        integer :: line = 0
        logical :: ground = .false.
        !> Mass [kg]
        real(wp) :: mass = 0.0_wp
        !> Centre-of-mass marker id
        integer :: cm = 0
        !> Principal moments [kg m^2]: IP's xx, yy, zz when it gives no products, else the
        !> eigenvalues of its tensor (rollcon_inertia_axes), along the columns of `principal`
        real(wp) :: ip(3) = 0.0_wp
        !> IP's products xy, xz, yz as written (ADAMS's positive integrals) [kg m^2]
        real(wp) :: products(3) = 0.0_wp
        !> The principal axes: columns x, y, z in the CM marker's axes (the identity when IP
        !> gives no products: the CM marker's axes are the principal axes)
        real(wp) :: principal(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
            & 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
        !> Part frame in ground: origin [m] and 3-1-3 Euler angles [rad]
        real(wp) :: qg(3) = 0.0_wp, reuler(3) = 0.0_wp
        !> Initial velocity of the CM marker, ground axes [m/s], and angular velocity, CM
        !> marker axes (ADAMS's WX, WY, WZ; not the principal axes) [rad/s]; only the components
        !> given (the rest are left to the model)
        real(wp) :: velocity(3) = 0.0_wp, angular_velocity(3) = 0.0_wp
        logical :: velocity_given(3) = .false., angular_velocity_given(3) = .false.
        !> EXACT=X:Y:Z:PSI:THETA:PHI: the principal axes' coordinates the initial-conditions
        !> analysis must hold as given (X, Y, Z, psi, theta, phi; docs/initial-conditions.md)
        logical :: exact(6) = .false.
    end type adm_part_type

    !> MARKER/id
    type :: adm_marker_type
        integer :: id = 0, line = 0
        !> Part the marker is fixed on
        integer :: part = 0
        !> Origin [m] and 3-1-3 Euler angles [rad] in the part frame
        real(wp) :: qp(3) = 0.0_wp, reuler(3) = 0.0_wp
    end type adm_marker_type

    !> UCON/id, FUNCTION=USER(par)[, ROUTINE=name]
    type :: adm_ucon_type
        integer :: id = 0, line = 0
        real(wp), allocatable :: par(:)
        !> ROUTINE=name as written: the built-in UCOSUB (rollcon_ucosub_catalog) serving this
        !> UCON; empty when not given (the model's UCOSUB serves it, as in ADAMS)
        character(len=:), allocatable :: routine
        !> Where ROUTINE= was written, for the assembly's messages ("file:line: UCON/1 ROUTINE")
        character(len=:), allocatable :: routine_at
    end type adm_ucon_type

    !> SFORCE, VFORCE, GFORCE or VTORQUE: markers and up to six expressions (FUNCTION is the
    !> first); SPRINGDAMPER or BUSHING: markers and constants
    type :: adm_force_type
        integer :: kind = force_sforce
        integer :: id = 0, line = 0
        !> Marker the force acts at, reaction marker (0: none), marker of the axes (0: ground)
        integer :: i = 0, j = 0, rm = 0
        !> SFORCE, SPRINGDAMPER: translational (along I-J) or rotational (about the J z-axis)
        logical :: translation = .true.
        !> SFORCE: the reaction on J is left out
        logical :: action_only = .false.
        !> FX, FY, FZ, TX, TY, TZ (SFORCE: FUNCTION in the first); in dataset units
        type(expression_type) :: functions(6)
        logical :: given(6) = .false.
        !> SPRINGDAMPER, BUSHING, SI: K (1:3), C (4:6), KT (7:9), CT (10:12), FORCE (13:15),
        !> TORQUE (16:18) along or about J's x, y, z (a translational SPRINGDAMPER's K, C,
        !> FORCE in the first of each, a rotational one's KT, CT, TORQUE in the third)
        !> [N/m, N s/m, N m/rad, N m s/rad, N, N m]
        real(wp) :: constants(18) = 0.0_wp
        !> SPRINGDAMPER: LENGTH [m] or ANGLE [rad]
        real(wp) :: reference = 0.0_wp
        !> FUNCTION=USER(r1, ..., r30): served by a user's routine (SFOSUB, VFOSUB, GFOSUB) with
        !> these constants (PAR), the one ROUTINE= names ("" for the model's own)
        logical :: user = .false.
        real(wp), allocatable :: par(:)
        character(len=:), allocatable :: routine
    end type adm_force_type

    !> One SIMULATE/DYNAMIC: a dataset's statement, a command of a command file, or the
    !> options of `rollcon run` (rollcon_adm_run). Each goes on from where the one before ended
    !> (the first from t = 0).
    type :: adm_segment_type
        !> The analysis: analysis_dynamic, analysis_kinematic or analysis_static
        !> (rollcon_run_settings); a static one has no times
        integer :: analysis = analysis_dynamic
        !> END=t [s] (by_duration false), or DURATION=t [s] from the segment's start
        real(wp) :: end_time = 0.0_wp, duration = 0.0_wp
        logical :: by_duration = .false.
        !> STEPS=n (by_steps: n output steps over the segment, a whole number >= 1), or
        !> DTOUT=dt [s]
        real(wp) :: steps = 0.0_wp, dtout = 0.0_wp
        logical :: by_steps = .true.
        !> For messages: "file:line: SIMULATE" where END (or DURATION), and where STEPS (or
        !> DTOUT) was written
        character(len=:), allocatable :: end_at, output_at
    end type adm_segment_type

    !> SIMULATE and INTEGRATOR
    type :: adm_run_type
        !> End time [s] and output step [s] (SIMULATE's END, and STEPS or DTOUT; with several
        !> SIMULATE commands, every output time), and the solver settings (INTEGRATOR), in the
        !> run settings' one type (rollcon_run_settings)
        type(run_settings_type) :: settings
        !> Line of the SIMULATE statement (0: none)
        integer :: line = 0
        !> The SIMULATE statement, or the SIMULATE commands of a command file, or the options
        !> that replaced them, in order (none before any is read)
        type(adm_segment_type), allocatable :: segments(:)
    end type adm_run_type

    !> One column of a REQUEST given by an expression (F1 ... F8), as written
    type :: adm_request_column_type
        !> The expression ("" when the column is not given)
        character(len=:), allocatable :: text
    end type adm_request_column_type

    !> REQUEST/id: what it asks for (request_displacement ... request_user), its markers and
    !> its text. A DISPLACEMENT is honoured as output columns (rollcon_request_watch); the
    !> others are read and kept here and answered by the assembly (rollcon_adm_requests) but a
    !> FUNCTION=USER one, named in the run's warning.
    type :: adm_request_type
        integer :: id = 0, line = 0
        !> request_displacement, request_velocity, request_acceleration, request_force,
        !> request_expressions (F1 ... F8) or request_user (FUNCTION=USER(...))
        integer :: kind = request_displacement
        !> The marker measured (or where the force acts), the one it is measured from (0: the
        !> ground origin; a force's reaction marker) and the one whose axes resolve x, y, z
        !> (0: ground axes)
        integer :: i = 0, j = 0, rm = 0
        !> COMMENT (`C=`) as written ("" when not given): ADAMS's title of the request's output
        character(len=:), allocatable :: comment
        !> F1 ... F8 as written, each "" when not given (request_expressions)
        type(adm_request_column_type) :: columns(8)
        !> FUNCTION=USER(...) (its value, USER(...)) and ROUTINE= as written (request_user), ""
        !> when not given
        character(len=:), allocatable :: user, routine
        !> The constants of FUNCTION=USER(r1, ..., rn) (request_user), the REQSUB's PAR
        real(wp), allocatable :: par(:)
        !> A FORCE between a JOINT's or JPRIM's two markers: that statement (its place in
        !> model%joints; 0: none), and whether the request's I is the statement's J
        integer :: joint = 0
        logical :: swapped = .false.
    end type adm_request_type

    !> A statement, or a keyword of one, read and checked but not used: ADAMS's own outputs
    !> and solver choices (rollcon_adm_outputs), named in the run's one warning
    type :: adm_unused_type
        !> What it is, grouped by in the warning: "GRAPHICS", "REQUEST VELOCITY", "INTEGRATOR
        !> GSTIFF", "OUTPUT REQSAVE"; for a keyword rollcon does not know, the statement and
        !> the keyword as written ("GRAPHICS LD")
        character(len=:), allocatable :: what
        integer :: line = 0
        !> False for a keyword of a statement of ADAMS's outputs that rollcon does not know:
        !> not read, and named apart in the warning
        logical :: known = .true.
    end type adm_unused_type

    !> A reference of a statement read and not used (a GRAPHICS's CM, a REQUEST's I), checked
    !> once the whole file is read, as those of the statements simulated
    type :: adm_reference_type
        !> "file:line: REQUEST/3 I", the start of its message
        character(len=:), allocatable :: at
        !> refers_to_marker, refers_to_part or refers_to_force (an SFORCE, VFORCE or GFORCE)
        integer :: kind = refers_to_marker
        integer :: id = 0
    end type adm_reference_type

    !> A whole dataset
    type :: adm_model_type
        character(len=:), allocatable :: file, title
        type(units_type) :: units
        type(adm_part_type), allocatable :: parts(:)
        type(adm_marker_type), allocatable :: markers(:)
        type(adm_ucon_type), allocatable :: ucons(:)
        type(adm_force_type), allocatable :: forces(:)
        !> JOINT and JPRIM statements, in the order of the file (rollcon_adm_joints)
        type(adm_joint_type), allocatable :: joints(:)
        !> GCON, COUPLER and GEAR statements, each in the order of the file
        !> (rollcon_adm_couplers)
        type(adm_gcon_type), allocatable :: gcons(:)
        type(adm_coupler_type), allocatable :: couplers(:)
        type(adm_gear_type), allocatable :: gears(:)
        !> MOTION statements, in the order of the file (rollcon_adm_motions)
        type(adm_motion_type), allocatable :: motions(:)
        !> VARIABLE, SPLINE, and PINPUT and POUTPUT statements, each in the order of the file
        !> (rollcon_adm_system); the expressions above read the VARIABLEs' in place
        !> (rollcon_adm_variables)
        type(adm_variable_type), allocatable :: variables(:)
        type(adm_spline_data_type), allocatable :: splines(:)
        type(adm_plant_type), allocatable :: plants(:)
        !> DIFF statements, in the order of the file (rollcon_adm_system), their VARIABLEs read
        !> in place (rollcon_adm_variables)
        type(adm_diff_type), allocatable :: diffs(:)
        !> STRING and ARRAY statements, each in the order of the file (rollcon_adm_data): the
        !> data user routines read with GTSTRG and GTARAY
        type(adm_string_type), allocatable :: strings(:)
        type(adm_array_type), allocatable :: arrays(:)
        !> CONTACT statements, in the order of the file (rollcon_adm_contacts), and the
        !> GRAPHICS of the shapes a CONTACT can name (ELLIPSOID, CYLINDER, PLANE), in the order
        !> of the file
        type(adm_contact_type), allocatable :: contacts(:)
        type(adm_graphics_type), allocatable :: graphics(:)
        !> Gravitational acceleration, ground axes [m/s^2] (zero without ACCGRAV)
        real(wp) :: gravity(3) = 0.0_wp
        type(adm_run_type) :: run
        !> REQUEST/id, DISPLACEMENT statements, in the order of the file
        type(adm_request_type), allocatable :: requests(:)
        !> REQUEST/id, FORCE statements between a JOINT's or JPRIM's two markers (either way
        !> round, no RM): answered by that statement's reaction, in the order of the file
        type(adm_request_type), allocatable :: force_requests(:)
        !> The other REQUEST statements (VELOCITY, ACCELERATION, FORCE, F1 ... F8,
        !> FUNCTION=USER), in the order of the file: read and kept, answered where the dataset
        !> is assembled (rollcon_adm_requests; FUNCTION=USER is not)
        type(adm_request_type), allocatable :: other_requests(:)
        !> What was read and not used, in the order of the file
        type(adm_unused_type), allocatable :: unused(:)
        !> The references of the statements read and not used
        type(adm_reference_type), allocatable :: references(:)
        !> The one warning naming what was read and not used, with its lines ("" for nothing:
        !> rollcon_adm_outputs' unused_warning)
        character(len=:), allocatable :: warning
        !> While the dataset is read, the entries of requests, unused and references that hold
        !> one (each list grows by doubling, so that reading stays linear in the dataset's size;
        !> the reader cuts it to its count once every statement is read)
        integer :: request_count = 0, unused_count = 0, reference_count = 0
        integer :: other_request_count = 0
    end type adm_model_type

end module rollcon_adm_model
