! SPDX-License-Identifier: MIT
!> Force statements served by a user's routine (FUNCTION=USER(r1, ...): SFOSUB, VFOSUB,
!> GFOSUB, VTOSUB; rollcon_force_routine_contract), and the utilities those routines call: SYSFNC,
!> SYSARY and TIMGET, answering from the state the routine is called at (docs/datasets.md,
!> "User force routines"), and the accelerations from those set_system_accelerations gave last
!> (the equations' iterate of the algebraic loop a force or VARSUB reading them makes, or
!> IDA's u': rollcon_equations' loop_accelerations, rollcon_dae; the accelerations solved
!> before a DIFSUB's rates, rollcon_problem; the output row's for a REQSUB: docs/datasets.md,
!> "Accelerations read by a force routine" and "... by the other user routines"; a MOTSUB
!> reads none: ADAMS's rule, call_user_motion refuses it), and the force measures (FX ... TM,
!> an element's force JOINT ... SPDP) from the multipliers set_system_constraint_forces gave
!> last (the same loop's iterate, IDA's unknowns), summed by rollcon_force_measures through a
!> hook (force_measure; docs/datasets.md, "Force measures read by a user's routine"), to a
!> force routine, a VARSUB (its partials in the multipliers differenced,
!> difference_variable_multipliers), a DIFSUB and a REQSUB; a MOTSUB reads none.
!>
!> ADAMS's utilities take no handle, so what they read is module state, as
!> rollcon_adams_runtime's: the table of routines the model may use (register_force_routine:
!> the model's own SFOSUB, VFOSUB, GFOSUB, and those a ROUTINE=library::name names), the
!> markers of the model (set_system_markers), and during a call the time and state. One model
!> per process: a user's routines run in a child process of their own (rollcon_isolated_run).
!>
!> - declare_user_force makes the initialisation call (IFLAG = .TRUE.): the markers its
!>   SYSFNC and SYSARY calls name, and whether they read rates, are the force's declared
!>   dependencies (marker_force_type's declared_markers, declared_rates);
!> - evaluate_user_forces calls each routine at (t, q, u) and keeps its values in SI
!>   (marker_force_type's user_values), which the pure force procedures then read; a routine
!>   that reports an error (ERRMES), returns a value that is not finite or reads what it did
!>   not declare leaves an error for take_user_force_error.
!>
!> The same table serves REQSUBs (call_user_request, at each output row), VARSUBs
!> (evaluate_user_variables, before the forces at each evaluation; their values are what
!> VARVAL reads, rollcon_user_variable_values, and their differences over their declared
!> state, difference_user_variables, the partials VARVAL's jets carry, and over the
!> accelerations, difference_variable_accelerations, for the algebraic loop), MOTSUBs
!> (call_user_motion, when the constraints are evaluated: a MOTION's displacement and its
!> TIME derivatives) and DIFSUBs (declare_diff_routine, call_diff_routine: the equations of
!> rollcon_diff). SYSFNC('DIF') and SYSFNC('DIF1') answer from the DIFFs' state of the call
!> (set_system_diff_state).
!>
!> Every call goes through the call hook (set_force_call_hook), which a child process points at
!> its guard (rollcon_force_routine_guard: time limit, copies of the inputs, canaries).
module rollcon_user_forces
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon, stat_input
    use rollcon_text, only : to_text, upper_case, number_list
    use rollcon_force_routine_contract, only : force_routine_interface, routine_names, &
        & routine_results, routine_kinds, routine_statements, routine_vtosub
    use rollcon_system_routine_contract, only : request_routine_interface, routine_reqsub, &
        & request_routine_name, request_results, variable_routine_interface, routine_varsub, &
        & variable_routine_name, motion_routine_interface, routine_motsub, motion_routine_name, &
        & motion_orders, routine_difsub, diff_routine_name
    use rollcon_user_variable_values, only : set_user_variable_values, &
        & set_user_variable_partials, clear_user_variable_partials, set_user_variable_parts
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_marker, only : marker_type
    use rollcon_measures, only : measure_value, is_state_measure, reads_rates, quantity_scale
    use rollcon_expression, only : quantity_names, quantity_psi, quantity_wx, quantity_vx, &
        & quantity_vm, quantity_vr, quantity_accm, quantity_wdtm, quantity_least_markers, &
        & quantity_most_markers, quantity_dx, quantity_dif, quantity_dif1, quantity_varval
    use rollcon_force, only : applied_force_type, profile_statement
    use rollcon_spline, only : spline_type, spline_derivatives, method_akima, method_cubic
    use rollcon_central_differences, only : central_differences
    use rollcon_marker_acceleration, only : acceleration_measure
    use rollcon_expression, only : quantity_kind, kind_acceleration, kind_angular_acceleration, &
        & quantity_accx, quantity_wdtx, kind_force, kind_torque, kind_element_force, &
        & quantity_fx, quantity_fm, quantity_tx
    use rollcon_marker, only : marker_motion
    use rollcon_rotation, only : transpose_times
    use rollcon_constraint_matrix, only : constraint_matrix_type
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite, ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: force_call_interface, register_force_routine, clear_force_routines
    public :: find_force_routine, force_routine_label, set_force_call_hook, direct_force_call
    public :: set_system_markers, declare_user_force, evaluate_user_forces
    public :: take_user_force_error, has_user_forces, routine_kind_of
    public :: system_function, system_array, system_time, system_notes, clear_system_notes
    public :: get_force_routine, report_call_problem, difference_call
    public :: set_system_splines, system_spline
    public :: register_request_routine, get_request_routine, call_user_request, routine_name_of
    public :: register_variable_routine, get_variable_routine, user_variable_type
    public :: set_user_variables, declare_user_variables, evaluate_user_variables
    public :: evaluate_user_variable, user_variable_list
    public :: register_motion_routine, get_motion_routine, user_motion_order, user_motion_type
    public :: set_user_motions, call_user_motion, check_user_motions, user_motion_list
    public :: difference_user_variables, clear_user_variable_partials
    public :: register_diff_routine, routine_declaration_type, set_system_diff_state
    public :: declare_diff_routine, call_diff_routine
    public :: set_system_accelerations, reads_accelerations, acceleration_difference_call
    public :: variables_read_accelerations, variables_reading_accelerations
    public :: difference_variable_accelerations, system_accelerations
    public :: variables_read_constraint_forces, difference_variable_multipliers
    public :: declare_variable_rows
    public :: force_measure_interface, set_force_measure_hook, set_system_constraint_forces
    public :: reads_constraint_forces, multiplier_difference_call
    public :: set_system_multipliers, system_multipliers

    !> A routine the model may use
    type :: routine_entry_type
        !> routine_sfosub ... (rollcon_force_routine_contract)
        integer :: kind = 0
        !> "" for the model's own (served to every statement naming no ROUTINE), else the
        !> ROUTINE= text that names it ("library::name")
        character(len=:), allocatable :: name
        !> The file it came from, for messages
        character(len=:), allocatable :: source
        procedure(force_routine_interface), pointer, nopass :: routine => null()
        !> A REQSUB (kind routine_reqsub; rollcon_system_routine_contract)
        procedure(request_routine_interface), pointer, nopass :: request => null()
        !> A VARSUB (kind routine_varsub)
        procedure(variable_routine_interface), pointer, nopass :: variable => null()
        !> A MOTSUB (kind routine_motsub)
        procedure(motion_routine_interface), pointer, nopass :: motion => null()
    end type routine_entry_type

    !> A MOTION served by a MOTSUB
    type :: user_motion_type
        integer :: id = 0
        !> Its MOTSUB's entry in the table
        integer :: routine = 0
        !> The constants of USER(r1, ..., rn)
        real(wp), allocatable :: par(:)
        !> "x.adm:7: MOTION/3", for messages
        character(len=:), allocatable :: name
        !> Its initialisation call (IFLAG = .TRUE.) has been made
        logical :: initialised = .false.
        !> The highest IORD it is called with (ADAMS's): 2 for a DISPLACEMENT, 1 for a
        !> VELOCITY (f, f'), 0 for an ACCELERATION (f)
        integer :: highest = motion_orders
    end type user_motion_type
    !> What a routine's initialisation call (IFLAG = .TRUE.) declared it reads through SYSFNC
    !> and SYSARY: markers (and their model parts), whether rates and accelerations, and the
    !> DIFFs whose DIF and DIF1 it reads (ids)
    type :: routine_declaration_type
        integer, allocatable :: markers(:), parts(:), difs(:), dif1s(:)
        logical :: rates = .false., accelerations = .false.
        !> The constraint rows whose reactions its force measures summed (SYSFNC('JOINT'), FX
        !> ... TM over a JOINT: a DIFSUB's value then depends on those rows' multipliers)
        integer, allocatable :: rows(:)
    end type routine_declaration_type

    !> A VARIABLE served by a VARSUB
    type :: user_variable_type
        integer :: id = 0
        !> Its VARSUB's entry in the table
        integer :: routine = 0
        !> The constants of USER(r1, ..., rn)
        real(wp), allocatable :: par(:)
        !> "x.adm:7: VARIABLE/3", for messages
        character(len=:), allocatable :: name
        !> What its initialisation call declared (allocated once that call is made)
        integer, allocatable :: declared(:)
        logical :: declared_rates = .false.
        !> Its initialisation call read accelerations (SYSARY('TACC'|'RACC'), SYSFNC('ACCX'
        !> ... 'WDTM')): a force that reads it closes the algebraic loop a force routine
        !> reading accelerations does (reads_accelerations)
        logical :: declared_accelerations = .false.
        !> The constraint rows whose reactions its initialisation call's force measures summed
        !> (SYSFNC('JOINT'), FX ... TM over a JOINT: its value then depends on the multipliers,
        !> an algebraic loop with the forces that read it; allocated once that call is made)
        integer, allocatable :: declared_rows(:)
        !> Its value at the state last evaluated, in the dataset's units
        real(wp) :: value = 0.0_wp
    end type user_variable_type

    abstract interface
        !> How a routine of the table is called: entry (its index), the statement's id, time
        !> (dataset units), par(:npar), dflag, iflag, and result (n values).
        subroutine force_call_interface(entry, id, time, par, npar, dflag, iflag, result, n)
            import :: wp
            integer, intent(in) :: entry, id, npar, n
            real(wp), intent(in) :: time, par(:)
            logical, intent(in) :: dflag, iflag
            real(wp), intent(inout) :: result(n)
        end subroutine force_call_interface

        !> How a force measure is answered (rollcon_force_measures, which knows the model):
        !> quantity FX ... TM (ids: the markers I and J, J 0 for none) or an element's force
        !> JOINT ... SPDP (ids: the element's id and JFLAG), for the force named caller ("" for
        !> a REQSUB), at (t, q, u) [SI] with the constraint rows c (C, nc x n, by rows over each
        !> UCON's coordinates) and multipliers lambda (nc): wrench, the force and torque
        !> [N, N m] in ground axes on the part of the marker (the torque about its origin), rows
        !> the constraint rows whose multipliers it sums, read_markers the markers of the forces
        !> it sums (their state is what it depends on); problem "" or why it cannot be
        !> answered.
        subroutine force_measure_interface(quantity, ids, caller, time, q, u, c, lambda, &
                & wrench, rows, read_markers, problem)
            import :: wp, constraint_matrix_type
            integer, intent(in) :: quantity, ids(2)
            character(len=*), intent(in) :: caller
            real(wp), intent(in) :: time, q(:), u(:), lambda(:)
            type(constraint_matrix_type), intent(in) :: c
            real(wp), intent(out) :: wrench(6)
            integer, allocatable, intent(out) :: rows(:), read_markers(:)
            character(len=:), allocatable, intent(out) :: problem
        end subroutine force_measure_interface
    end interface

    !> The routines, table(:table_count); the table grows by doubling (append_entry)
    type(routine_entry_type), allocatable, save :: table(:)
    integer, save :: table_count = 0
    !> The model's VARIABLEs served by VARSUBs, and the dataset's time unit [s]
    type(user_variable_type), allocatable, save :: variables(:)
    real(wp), save :: variables_time_unit = 1.0_wp
    !> The model's MOTIONs served by MOTSUBs, the dataset's time unit [s], and the IORD of the
    !> MOTSUB call under way (user_motion_order)
    type(user_motion_type), allocatable, save :: motions(:)
    real(wp), save :: motions_time_unit = 1.0_wp
    integer, save :: motion_order = 0
    !> A MOTSUB's call is under way (what it reads through SYSFNC and SYSARY is refused)
    logical, save :: motion_calling = .false.
    procedure(force_call_interface), pointer, save :: call_hook => direct_force_call
    !> The model's markers (every one a routine may name), the dataset's units
    type(marker_type), allocatable, save :: markers(:)
    real(wp), save :: length_unit = 1.0_wp, time_unit = 1.0_wp, force_unit = 1.0_wp
    !> Who answers the force measures (rollcon_force_measures), null until the equations set
    !> it; the constraint rows [per m or rad, or s] (C by rows over each UCON's coordinates)
    !> and multipliers they read, as set_system_constraint_forces gave them last (an iterate of
    !> the algebraic loop, IDA's unknowns, the solve at an output row; none before the first)
    procedure(force_measure_interface), pointer, save :: measure_hook => null()
    type(constraint_matrix_type), save :: c_now
    real(wp), allocatable, save :: lambda_now(:)
    !> The force whose routine is called ("data/x.adm:12: SFORCE/3"; "" for any other call),
    !> and whether a REQSUB's call is under way (a force measure is answered to these alone)
    character(len=:), allocatable, save :: caller_now
    logical, save :: request_call = .false.
    !> A VARSUB's or a DIFSUB's call is under way (a force measure is answered to these too)
    logical, save :: variable_calling = .false., diff_calling = .false.
    !> The constraint rows whose reactions the DIFSUBs' initialisation calls read (their
    !> values then depend on the multipliers, which the equations then solve for at every
    !> state: reads_constraint_forces)
    integer, allocatable, save :: diff_rows(:)
    !> An initialisation call's force measures: whether it read any, the constraint rows they
    !> summed; the rows of the declaration in force during an evaluation
    logical, save :: named_forces = .false.
    integer, allocatable, save :: named_rows(:), allowed_rows(:)
    !> The model's SPLINEs, the curves AKISPL and CUBSPL read
    type(spline_type), allocatable, save :: curves(:)
    !> The state of the call under way [SI]
    real(wp), allocatable, save :: q_now(:), u_now(:)
    !> The accelerations SYSARY('TACC'|'RACC') and SYSFNC('ACCX' ... 'WDTM') answer from [SI]:
    !> those set_system_accelerations gave last (an iterate of the algebraic loop's solve, or
    !> IDA's u'), zero before any
    real(wp), allocatable, save :: a_now(:)
    !> A force routine's call is under way
    logical, save :: force_call = .false.
    real(wp), save :: time_now = 0.0_wp
    !> The DIFFs' state SYSFNC('DIF') and SYSFNC('DIF1') answer from: ids, DIF and DIF1 [the
    !> user's units, per the dataset's time unit]
    integer, allocatable, save :: diff_ids(:)
    real(wp), allocatable, save :: diff_x(:), diff_w(:)
    !> An initialisation call is under way: the markers (and DIFFs) named are collected
    logical, save :: declaring = .false.
    integer, allocatable, save :: named(:), named_difs(:), named_dif1s(:)
    !> A DIFSUB's declaration in force during its call (allowed_difs allocated then)
    integer, allocatable, save :: allowed_difs(:), allowed_dif1s(:)
    logical, save :: named_rates = .false., named_accelerations = .false.
    !> The initialisation call under way read a VARSUB's value (SYSFNC('VARVAL'))
    logical, save :: named_variables = .false.
    !> The declaration of the statement whose routine is being called (an evaluation)
    integer, allocatable, save :: allowed(:)
    logical, save :: allowed_rates = .true., allowed_accelerations = .true.
    !> What the utilities found wrong in the call under way ("" for nothing), and the notes
    !> of every call since clear_system_notes (for rollcon check)
    character(len=:), allocatable, save :: problem, notes
    !> First error not yet taken
    type(error_type), allocatable, save :: pending

contains

    !> Add a routine to the table the model's statements are served from.
    subroutine register_force_routine(kind, name, source, routine)
        !> routine_sfosub, routine_vfosub, routine_gfosub or routine_vtosub
        integer, intent(in) :: kind
        !> "" for the model's own; else the ROUTINE= text that names it
        character(len=*), intent(in) :: name
        !> The file it was built from
        character(len=*), intent(in) :: source
        procedure(force_routine_interface) :: routine
        type(routine_entry_type) :: entry

        entry%routine => routine
        call append_entry(entry, kind, name, source)
    end subroutine register_force_routine

    !> Append entry (its routine pointer set) to the table as a routine of kind, under name
    !> ("" for the model's own), built from the file source. The table grows by doubling, as
    !> the code's growing arrays do (docs/design.md §4), its entries' strings moved
    !> (move_alloc) and pointers copied: never a reallocating assignment of the whole table,
    !> which copies every entry's allocatable components at each append, in whichever process
    !> (a forked child's too) appends.
    subroutine append_entry(entry, kind, name, source)
        type(routine_entry_type), intent(in) :: entry
        integer, intent(in) :: kind
        character(len=*), intent(in) :: name, source
        type(routine_entry_type), allocatable :: grown(:)
        integer :: k

        if (.not. allocated(table)) then
            allocate(table(0))
            table_count = 0
        end if
        if (table_count == size(table)) then
            allocate(grown(max(8, 2*size(table))))
            do k = 1, table_count
                grown(k)%kind = table(k)%kind
                call move_alloc(table(k)%name, grown(k)%name)
                call move_alloc(table(k)%source, grown(k)%source)
                grown(k)%routine => table(k)%routine
                grown(k)%request => table(k)%request
                grown(k)%variable => table(k)%variable
                grown(k)%motion => table(k)%motion
            end do
            call move_alloc(grown, table)
        end if
        table_count = table_count + 1
        associate (added => table(table_count))
            added%kind = kind
            added%name = name
            added%source = source
            added%routine => entry%routine
            added%request => entry%request
            added%variable => entry%variable
            added%motion => entry%motion
        end associate
    end subroutine append_entry

    !> Add a REQSUB to the table (kind routine_reqsub), under name ("" for the model's own).
    subroutine register_request_routine(name, source, routine)
        character(len=*), intent(in) :: name
        !> The file it was built from
        character(len=*), intent(in) :: source
        procedure(request_routine_interface) :: routine
        type(routine_entry_type) :: entry

        entry%request => routine
        call append_entry(entry, routine_reqsub, name, source)
    end subroutine register_request_routine

    !> Add a VARSUB to the table (kind routine_varsub), under name ("" for the model's own).
    subroutine register_variable_routine(name, source, routine)
        character(len=*), intent(in) :: name
        !> The file it was built from
        character(len=*), intent(in) :: source
        procedure(variable_routine_interface) :: routine
        type(routine_entry_type) :: entry

        entry%variable => routine
        call append_entry(entry, routine_varsub, name, source)
    end subroutine register_variable_routine

    !> Add a DIFSUB to the table (kind routine_difsub), under name ("" for the model's own); it
    !> is called as a VARSUB is.
    subroutine register_diff_routine(name, source, routine)
        character(len=*), intent(in) :: name
        !> The file it was built from
        character(len=*), intent(in) :: source
        procedure(variable_routine_interface) :: routine
        type(routine_entry_type) :: entry

        entry%variable => routine
        call append_entry(entry, routine_difsub, name, source)
    end subroutine register_diff_routine

    !> The VARSUB (or DIFSUB) of entry, for a guard that calls it.
    subroutine get_variable_routine(entry, routine)
        integer, intent(in) :: entry
        procedure(variable_routine_interface), pointer, intent(out) :: routine

        routine => table(entry)%variable
    end subroutine get_variable_routine

    !> The model's VARIABLEs served by VARSUBs (each with its entry, constants and name), in a
    !> dataset of this time unit [s]; their values start NaN until evaluated.
    subroutine set_user_variables(list, time_unit)
        type(user_variable_type), intent(in) :: list(:)
        real(wp), intent(in) :: time_unit
        real(wp), allocatable :: values(:)
        integer, allocatable :: ids(:)

        variables = list
        variables_time_unit = time_unit
        allocate(values(size(list)), source=ieee_value(0.0_wp, ieee_quiet_nan))
        ! (copies: a component of an array of a derived type is not contiguous)
        ids = variables%id
        call set_user_variable_values(ids, values)
    end subroutine set_user_variables

    !> The initialisation call (IFLAG = .TRUE.) of every VARSUB at (t, q, u): what its SYSFNC
    !> and SYSARY calls name is the VARIABLE's declared dependencies (their parts given to
    !> rollcon_user_variable_values). An ERRMES or a utility's refusal is an error naming the
    !> VARIABLE.
    subroutine declare_user_variables(time, q, u, error)
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value(1)
        logical, allocatable :: parts_read(:, :)
        integer, allocatable :: parts(:)
        integer :: v

        if (.not. allocated(variables)) return
        do v = 1, size(variables)
            associate (variable => variables(v))
                call begin_call(time, q, u)
                declaring = .true.
                named = [integer ::]
                named_rates = .false.
                named_accelerations = .false.
                named_forces = .false.
                named_rows = [integer ::]
                value = 0.0_wp
                variable_calling = .true.
                caller_now = variable%name
                call call_hook(variable%routine, variable%id, time/variables_time_unit, &
                    & variable%par, size(variable%par), .false., .true., value, 1)
                caller_now = ""
                variable_calling = .false.
                declaring = .false.
                variable%declared = named
                variable%declared_rows = named_rows
                variable%declared_rates = named_rates
                variable%declared_accelerations = named_accelerations
                call variable_problem(variable, "the initialisation call (IFLAG = .TRUE.)", &
                    & time, error)
                if (allocated(error)) return
            end associate
        end do
        allocate(parts_read(size(variables), size(q)/6), source=.false.)
        do v = 1, size(variables)
            parts = parts_of(variables(v)%declared)
            parts_read(v, parts) = .true.
        end do
        call set_user_variable_parts(parts_read)
    end subroutine declare_user_variables

    !> Call every VARSUB at (t, q, u), in the order of the dataset, and keep the values for
    !> VARVAL (rollcon_user_variable_values); the first failure (an ERRMES, a utility's
    !> refusal, a value not finite) is kept for take_user_force_error.
    subroutine evaluate_user_variables(time, q, u)
        real(wp), intent(in) :: time, q(:), u(:)
        integer :: v

        if (.not. allocated(variables)) return
        do v = 1, size(variables)
            call evaluate_user_variable(v, time, q, u)
        end do
    end subroutine evaluate_user_variables

    !> Call the VARSUB of the v-th user VARIABLE (user_variable_list's order) at (t, q, u) and
    !> keep its value for VARVAL; a failure is kept for take_user_force_error, as
    !> evaluate_user_variables keeps it.
    subroutine evaluate_user_variable(v, time, q, u)
        integer, intent(in) :: v
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable :: values(:)
        real(wp) :: value
        integer, allocatable :: ids(:)
        logical :: failed

        call variable_call(variables(v), time, q, u, .false., value, failed)
        variables(v)%value = value
        ids = variables%id
        values = variables%value
        call set_user_variable_values(ids, values)
    end subroutine evaluate_user_variable

    !> The model's VARIABLEs served by VARSUBs (set_user_variables' list, with what their
    !> initialisation calls declared and their last values), none before it is set.
    function user_variable_list() result(list)
        type(user_variable_type), allocatable :: list(:)

        allocate(list(0))
        if (allocated(variables)) list = variables
    end function user_variable_list

    !> The MOTIONs served by a MOTSUB (set_user_motions's), for rollcon check.
    function user_motion_list() result(list)
        type(user_motion_type), allocatable :: list(:)

        allocate(list(0))
        if (allocated(motions)) list = motions
    end function user_motion_list

    !> One call of a VARSUB at (t, q, u) (DFLAG dflag), its value in the dataset's units and
    !> whether it failed (an ERRMES, a utility's refusal, a value not finite: the failure kept
    !> for take_user_force_error).
    subroutine variable_call(variable, time, q, u, dflag, value, failed)
        type(user_variable_type), intent(in) :: variable
        real(wp), intent(in) :: time, q(:), u(:)
        logical, intent(in) :: dflag
        real(wp), intent(out) :: value
        logical, intent(out) :: failed
        type(error_type), allocatable :: error
        real(wp) :: result(1)
        character(len=:), allocatable :: call_name

        call begin_call(time, q, u)
        if (allocated(variable%declared)) then
            allowed = variable%declared
            allowed_rates = variable%declared_rates
            allowed_accelerations = variable%declared_accelerations
        else if (allocated(allowed)) then
            deallocate(allowed)
        end if
        if (allocated(variable%declared_rows)) allowed_rows = variable%declared_rows
        result = 0.0_wp
        variable_calling = .true.
        caller_now = variable%name
        call call_hook(variable%routine, variable%id, time/variables_time_unit, variable%par, &
            & size(variable%par), dflag, .false., result, 1)
        caller_now = ""
        variable_calling = .false.
        if (allocated(allowed)) deallocate(allowed)
        if (allocated(allowed_rows)) deallocate(allowed_rows)
        allowed_rates = .true.
        allowed_accelerations = .true.
        value = result(1)
        call_name = ""
        if (dflag) call_name = " in a call with DFLAG = .TRUE."
        if (.not. ieee_is_finite(value)) then
            call fatal_error(error, variable%name // ": its " &
                & // force_routine_label(variable%routine) // " returned VALUE = " &
                & // to_text(value) // call_name // " at TIME = " &
                & // to_text(time/variables_time_unit) // ": a VARIABLE's value must be " &
                & // "finite", stat_ucon)
        else if (dflag) then
            call variable_problem(variable, "a call with DFLAG = .TRUE.", time, error)
        else
            call variable_problem(variable, "the call", time, error)
        end if
        failed = allocated(error)
        if (allocated(error)) then
            if (.not. allocated(pending)) call move_alloc(error, pending)
        end if
    end subroutine variable_call

    !> The partials of every VARSUB's value at (t, q, u) [dataset's units per m, rad, m/s,
    !> rad/s], by central differences (rollcon_central_differences) over the coordinates of
    !> the parts its initialisation call declared (and their rates when it declared rates),
    !> each call with DFLAG = .TRUE.; given to rollcon_user_variable_values, where VARVAL's
    !> jets read them (clear_user_variable_partials forgets them). The values VARVAL reads
    !> are left as evaluate_user_variables set them. A failed call leaves its entry 0 and its
    !> error for take_user_force_error.
    subroutine difference_user_variables(time, q, u)
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), allocatable :: dv_dq(:, :), dv_du(:, :), block(:, :)
        integer, allocatable :: entries(:), parts(:), ids(:)
        integer :: v, k, c

        if (.not. allocated(variables)) return
        if (size(variables) == 0) return
        allocate(dv_dq(size(variables), size(q)), dv_du(size(variables), size(u)), &
            & source=0.0_wp)
        do v = 1, size(variables)
            if (.not. allocated(variables(v)%declared)) cycle
            parts = parts_of(variables(v)%declared)
            entries = [((6*(parts(k) - 1) + c, c = 1, 6), k = 1, size(parts))]
            if (size(entries) == 0) cycle
            allocate(block(size(entries), 1), source=0.0_wp)
            call central_differences(q, entries, coordinates_moved, block)
            dv_dq(v, entries) = block(:, 1)
            if (variables(v)%declared_rates) then
                block = 0.0_wp
                call central_differences(u, entries, rates_moved, block)
                dv_du(v, entries) = block(:, 1)
            end if
            deallocate(block)
        end do
        ids = variables%id
        call set_user_variable_partials(ids, dv_dq, dv_du)

    contains

        subroutine coordinates_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call variable_call(variables(v), time, shifted, u, .true., values(1), failed)
        end subroutine coordinates_moved

        subroutine rates_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call variable_call(variables(v), time, q, shifted, .true., values(1), failed)
        end subroutine rates_moved

    end subroutine difference_user_variables

    !> The initialisation call (IFLAG = .TRUE.) of the DIFSUB of entry for DIFF/id at (t, q, u)
    !> and the DIFFs' state (ids, x, w): what its SYSFNC and SYSARY calls name (markers, DIF
    !> and DIF1 of DIFFs) is its declaration. An ERRMES or a utility's refusal is an error
    !> naming `name` ("DIFF/3 (line 12)").
    subroutine declare_diff_routine(entry, id, name, par, time_unit, time, q, u, ids, x, w, &
            & declaration, error)
        integer, intent(in) :: entry, id
        character(len=*), intent(in) :: name
        !> The constants of USER(r1, ..., rn); the dataset's time unit [s]
        real(wp), intent(in) :: par(:), time_unit
        !> Time [s], coordinates and rates of all parts [SI]
        real(wp), intent(in) :: time, q(:), u(:)
        !> The DIFFs' ids, DIF and DIF1 [the user's units, per the dataset's time unit]
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)
        type(routine_declaration_type), intent(out) :: declaration
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: result(1)
        integer :: k

        call begin_call(time, q, u)
        call set_system_diff_state(ids, x, w)
        declaring = .true.
        named = [integer ::]
        named_difs = [integer ::]
        named_dif1s = [integer ::]
        named_rates = .false.
        named_accelerations = .false.
        named_forces = .false.
        named_rows = [integer ::]
        result = 0.0_wp
        diff_calling = .true.
        caller_now = ""
        call call_hook(entry, id, time/time_unit, par, size(par), .false., .true., result, 1)
        diff_calling = .false.
        declaring = .false.
        if (.not. allocated(diff_rows)) diff_rows = [integer ::]
        diff_rows = [diff_rows, pack(named_rows, [(.not. any(diff_rows == named_rows(k)), &
            & k = 1, size(named_rows))])]
        declaration%markers = named
        declaration%parts = parts_of(named)
        declaration%rates = named_rates
        declaration%accelerations = named_accelerations
        declaration%difs = named_difs
        declaration%dif1s = named_dif1s
        declaration%rows = named_rows
        call diff_problem(entry, name, "the initialisation call (IFLAG = .TRUE.)", &
            & time/time_unit, error)
    end subroutine declare_diff_routine

    !> A call of the DIFSUB of entry for DIFF/id at (t, q, u) and the DIFFs' state (ids, x, w),
    !> with DFLAG dflag: VALUE (the rate d DIF/dt per the dataset's time unit, or an IMPLICIT
    !> DIFF's residual) and whether the call failed (an ERRMES, a utility's refusal, a VALUE
    !> not finite: the error, naming `name`, kept for take_user_force_error). What it reads
    !> beyond its declaration is noted (system_notes).
    subroutine call_diff_routine(entry, id, name, par, time_unit, time, q, u, ids, x, w, &
            & dflag, declaration, value, failed)
        integer, intent(in) :: entry, id
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: par(:), time_unit, time, q(:), u(:)
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)
        logical, intent(in) :: dflag
        type(routine_declaration_type), intent(in) :: declaration
        real(wp), intent(out) :: value
        logical, intent(out) :: failed
        type(error_type), allocatable :: error
        real(wp) :: result(1)
        character(len=:), allocatable :: call_name

        call_name = "the call"
        if (dflag) call_name = "a call with DFLAG = .TRUE."
        call begin_call(time, q, u)
        call set_system_diff_state(ids, x, w)
        if (allocated(declaration%markers)) then
            allowed = declaration%markers
            allowed_rates = declaration%rates
            allowed_accelerations = declaration%accelerations
            allowed_difs = declaration%difs
            allowed_dif1s = declaration%dif1s
        end if
        if (allocated(declaration%rows)) then
            if (size(declaration%rows) > 0) allowed_rows = declaration%rows
        end if
        result = 0.0_wp
        diff_calling = .true.
        caller_now = ""
        call call_hook(entry, id, time/time_unit, par, size(par), dflag, .false., result, 1)
        diff_calling = .false.
        if (allocated(allowed_rows)) deallocate(allowed_rows)
        if (allocated(allowed)) deallocate(allowed)
        if (allocated(allowed_difs)) deallocate(allowed_difs, allowed_dif1s)
        allowed_rates = .true.
        allowed_accelerations = .true.
        value = result(1)
        if (.not. ieee_is_finite(value)) then
            call fatal_error(error, name // ": its " // force_routine_label(entry) &
                & // " returned VALUE = " // to_text(value) // " in " // call_name &
                & // " at TIME = " // to_text(time/time_unit) // ": a DIFF's equation must " &
                & // "be finite", stat_ucon)
        else
            call diff_problem(entry, name, call_name, time/time_unit, error)
        end if
        failed = allocated(error)
        if (allocated(error)) then
            if (.not. allocated(pending)) call move_alloc(error, pending)
        end if
    end subroutine call_diff_routine

    !> After a DIFSUB's call: an ERRMES it made, or a utility's refusal, as an error naming the
    !> DIFF (name) and the routine; time in the dataset's unit.
    subroutine diff_problem(entry, name, call_name, time, error)
        integer, intent(in) :: entry
        character(len=*), intent(in) :: name, call_name
        real(wp), intent(in) :: time
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: reported
        character(len=:), allocatable :: message
        integer :: colon

        call take_ucon_error(reported)
        if (allocated(reported)) then
            message = reported%message
            colon = index(message, ": ")
            if (index(message, "UCON/") == 1 .and. colon > 0) message = message(colon + 2:)
            ! the utility's refusal that the routine's ERRMES reports, when there is one
            if (len(problem) > 0) message = message // " (" // problem // ")"
            call fatal_error(error, name // ": its " // force_routine_label(entry) &
                & // " reported an error in " // call_name // " at TIME = " // to_text(time) &
                & // ": " // message, stat_ucon)
        else if (len(problem) > 0) then
            call fatal_error(error, name // ": its " // force_routine_label(entry) // ", in " &
                & // call_name // " at TIME = " // to_text(time) // ": " // problem, stat_ucon)
        end if
    end subroutine diff_problem

    !> The DIFFs' state SYSFNC('DIF', id) and SYSFNC('DIF1', id) answer from (rollcon_diff's
    !> DIF and DIF1 of the DIFFs of these ids) [the user's units, per the dataset's time unit].
    subroutine set_system_diff_state(ids, x, w)
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: x(:), w(:)

        diff_ids = ids
        diff_x = x
        diff_w = w
    end subroutine set_system_diff_state

    !> After a VARSUB's call: an ERRMES it made, or a utility's refusal, as an error naming the
    !> VARIABLE.
    subroutine variable_problem(variable, call_name, time, error)
        type(user_variable_type), intent(in) :: variable
        character(len=*), intent(in) :: call_name
        real(wp), intent(in) :: time
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: reported
        character(len=:), allocatable :: message
        integer :: colon

        call take_ucon_error(reported)
        if (allocated(reported)) then
            message = reported%message
            colon = index(message, ": ")
            if (index(message, "UCON/") == 1 .and. colon > 0) message = message(colon + 2:)
            ! the utility's refusal that the routine's ERRMES reports, when there is one
            if (len(problem) > 0) message = message // " (" // problem // ")"
            call fatal_error(error, variable%name // ": its " &
                & // force_routine_label(variable%routine) // " reported an error in " &
                & // call_name // " at TIME = " // to_text(time/variables_time_unit) // ": " &
                & // message, stat_ucon)
        else if (len(problem) > 0) then
            call fatal_error(error, variable%name // ": its " &
                & // force_routine_label(variable%routine) // ", in " // call_name &
                & // " at TIME = " // to_text(time/variables_time_unit) // ": " // problem, &
                & stat_ucon)
        end if
    end subroutine variable_problem

    !> Add a MOTSUB to the table (kind routine_motsub), under name ("" for the model's own).
    subroutine register_motion_routine(name, source, routine)
        character(len=*), intent(in) :: name
        !> The file it was built from
        character(len=*), intent(in) :: source
        procedure(motion_routine_interface) :: routine
        type(routine_entry_type) :: entry

        entry%motion => routine
        call append_entry(entry, routine_motsub, name, source)
    end subroutine register_motion_routine

    !> The MOTSUB of entry, for a guard that calls it.
    subroutine get_motion_routine(entry, routine)
        integer, intent(in) :: entry
        procedure(motion_routine_interface), pointer, intent(out) :: routine

        routine => table(entry)%motion
    end subroutine get_motion_routine

    !> The IORD of the MOTSUB call under way (0 outside one), for a guard that makes it.
    integer function user_motion_order() result(iord)
        iord = motion_order
    end function user_motion_order

    !> The model's MOTIONs served by MOTSUBs (each with its entry, constants and name), in a
    !> dataset of this time unit [s]; none initialised yet.
    subroutine set_user_motions(list, time_unit)
        type(user_motion_type), intent(in) :: list(:)
        real(wp), intent(in) :: time_unit

        motions = list
        motions_time_unit = time_unit
    end subroutine set_user_motions

    !> The MOTSUB of MOTION/id at time [s] for each IORD of orders (0, 1, 2): values(iord), in
    !> the dataset's units (a length or an angle per time unit to the power IORD, and one more
    !> for a VELOCITY motion's, two more for an ACCELERATION motion's); the entries
    !> not asked for are NaN. The first call for a MOTION is preceded by its initialisation
    !> call (IFLAG = .TRUE.). A MOTION is a function of TIME alone (ADAMS's rule): a call that
    !> reads the state through SYSFNC or SYSARY (at IFLAG, a declared dependency) is an error,
    !> as are an ERRMES, a utility's refusal and a value that is not finite, each naming the
    !> MOTION (its file and line), the routine, the call and the TIME. (t, q, u) [SI] are the
    !> state the utilities would answer from.
    subroutine call_user_motion(id, time, q, u, orders, values, error)
        integer, intent(in) :: id
        real(wp), intent(in) :: time, q(:), u(:)
        integer, intent(in) :: orders(:)
        real(wp), intent(out) :: values(0:motion_orders)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value(1)
        integer :: m, k

        values = ieee_value(0.0_wp, ieee_quiet_nan)
        m = 0
        if (allocated(motions)) m = findloc(motions%id, id, dim=1)
        if (m == 0) then
            call fatal_error(error, "MOTION/" // to_text(id) // ": no MOTSUB was given for " &
                & // "it (set_user_motions)", stat_ucon)
            return
        end if
        associate (motion => motions(m))
            if (.not. motion%initialised) then
                call motion_call(motion, 0, .true., value, error)
                if (allocated(error)) return
                motion%initialised = .true.
            end if
            do k = 1, size(orders)
                call motion_call(motion, orders(k), .false., value, error)
                if (allocated(error)) return
                values(orders(k)) = value(1)
            end do
        end associate
    contains
        !> One call of the MOTION's routine, with IORD = iord, and what went wrong in it.
        subroutine motion_call(motion, iord, iflag, value, error)
            type(user_motion_type), intent(in) :: motion
            integer, intent(in) :: iord
            logical, intent(in) :: iflag
            real(wp), intent(out) :: value(1)
            type(error_type), allocatable, intent(out) :: error
            type(error_type), allocatable :: reported
            character(len=:), allocatable :: call_name, message, at
            integer :: colon

            call begin_call(time, q, u)
            ! what the call reads is collected, and refused below
            declaring = .true.
            named = [integer ::]
            named_rates = .false.
            motion_order = iord
            motion_calling = .true.
            named_accelerations = .false.
            value = 0.0_wp
            call call_hook(motion%routine, motion%id, time/motions_time_unit, motion%par, &
                & size(motion%par), .false., iflag, value, 1)
            declaring = .false.
            motion_calling = .false.
            motion_order = 0
            call_name = "the call with IORD = " // to_text(iord)
            if (iflag) call_name = "the initialisation call (IFLAG = .TRUE.)"
            at = motion%name // ": its " // force_routine_label(motion%routine)
            call take_ucon_error(reported)
            if (allocated(reported)) then
                message = reported%message
                colon = index(message, ": ")
                if (index(message, "UCON/") == 1 .and. colon > 0) message = message(colon + 2:)
                ! the utility's refusal that the routine's ERRMES reports, when there is one
                if (len(problem) > 0) message = message // " (" // problem // ")"
                call fatal_error(error, at // " reported an error in " // call_name &
                    & // " at TIME = " // to_text(time/motions_time_unit) // ": " // message, &
                    & stat_ucon)
            else if (len(problem) > 0) then
                call fatal_error(error, at // ", in " // call_name // " at TIME = " &
                    & // to_text(time/motions_time_unit) // ": " // problem, stat_ucon)
            else if (named_accelerations) then
                call fatal_error(error, at // ", in " // call_name // " at TIME = " &
                    & // to_text(time/motions_time_unit) // ", read accelerations through " &
                    & // "SYSFNC or SYSARY (markers " // number_list(named) // "): a MOTSUB " &
                    & // "may not call SYSFNC or SYSARY (ADAMS's rule: a MOTION is a " &
                    & // "function of TIME alone, and the accelerations it would read are " &
                    & // "those the motion it prescribes determines); compute it from TIME " &
                    & // "and PAR", stat_ucon)
            else if (size(named) > 0 .or. named_rates) then
                call fatal_error(error, at // ", in " // call_name // " at TIME = " &
                    & // to_text(time/motions_time_unit) // ", read the state through " &
                    & // "SYSFNC or SYSARY (markers " // number_list(named) // "): a MOTION is " &
                    & // "a function of TIME alone (ADAMS's rule: the motion it prescribes " &
                    & // "may not depend on the state); compute it from TIME and PAR", &
                    & stat_ucon)
            else if (.not. iflag .and. .not. ieee_is_finite(value(1))) then
                call fatal_error(error, at // " returned VALUE = " // to_text(value(1)) &
                    & // " in " // call_name // " at TIME = " &
                    & // to_text(time/motions_time_unit) // ": a MOTION's displacement and " &
                    & // "its TIME derivatives must be finite", stat_ucon)
            end if
        end subroutine motion_call
    end subroutine call_user_motion

    !> The check of every MOTSUB at a run's start (time [s], q, u [SI]), before the first step:
    !> its IORD = 1 and IORD = 2 values against sixth-order central differences (step h and
    !> h/4, h = 1e-3 of the dataset's time unit) of its own IORD = 0 and IORD = 1 values (a
    !> UCOSUB's partials are judged otherwise, against the differences' estimated truncation and
    !> round-off: rollcon_partials_check): the fine difference's own error
    !> is estimated as |coarse - fine|/(4^6 - 1), and an entry is wrong when it differs from the
    !> fine difference by more than 1e-8 and more than ten times that estimate, relative to
    !> the largest of the value and the values differenced. A wrong entry is an error naming
    !> the MOTION and its line, the IORD, the value returned and the differences' value, and
    !> the option that runs anyway (--no-check); a failing call's error passes through.
    subroutine check_user_motions(time, q, u, error)
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        !> The difference step [dataset time units], its refinement, the tolerance
        real(wp), parameter :: step = 1.0e-3_wp, rel_tol = 1.0e-8_wp
        integer, parameter :: refinement = 4
        !> Sixth-order central first-difference weights at -3h .. 3h, over 60 h
        real(wp), parameter :: weights(-3:3) = [-1.0_wp, 9.0_wp, -45.0_wp, 0.0_wp, 45.0_wp, &
            & -9.0_wp, 1.0_wp]/60.0_wp
        real(wp) :: values(0:motion_orders), line(-3:3), fine_line(-3:3), returned, coarse, &
            & fine, scale, deviation, truncation, unit_time, h
        character(len=:), allocatable :: found
        integer :: m, iord, j

        if (.not. allocated(motions)) return
        found = ""
        unit_time = motions_time_unit
        h = step*unit_time
        do m = 1, size(motions)
            do iord = 1, motions(m)%highest
                call call_user_motion(motions(m)%id, time, q, u, [iord], values, error)
                if (allocated(error)) return
                returned = values(iord)
                do j = -3, 3
                    call call_user_motion(motions(m)%id, time + j*h, q, u, [iord - 1], values, &
                        & error)
                    if (allocated(error)) return
                    line(j) = values(iord - 1)
                    call call_user_motion(motions(m)%id, time + j*h/refinement, q, u, &
                        & [iord - 1], values, error)
                    if (allocated(error)) return
                    fine_line(j) = values(iord - 1)
                end do
                coarse = dot_product(weights, line)/step
                fine = dot_product(weights, fine_line)/(step/refinement)
                scale = max(abs(returned), maxval(abs(line)), tiny(1.0_wp))
                deviation = abs(returned - fine)/scale
                truncation = abs(coarse - fine)/scale/(real(refinement, wp)**6 - 1.0_wp)
                if (deviation <= max(rel_tol, 10.0_wp*truncation)) cycle
                found = found // new_line("a") // "  " // motions(m)%name // ": its " &
                    & // force_routine_label(motions(m)%routine) // " returned VALUE = " &
                    & // to_text(returned) // " at IORD = " // to_text(iord) // ", TIME = " &
                    & // to_text(time/unit_time) // ", where differences of its IORD = " &
                    & // to_text(iord - 1) // " values give " // to_text(fine)
            end do
        end do
        if (len(found) == 0) return
        call fatal_error(error, "the check at the start found MOTSUB values that are not the " &
            & // "TIME derivatives of its function (IORD = 1 the rate of IORD = 0, IORD " &
            & // "= 2 the rate of IORD = 1):" // found // new_line("a") // "The MOTION's " &
            & // "position and velocity equations would disagree. Run anyway with " &
            & // "--no-check.", stat_input)
    end subroutine check_user_motions

    !> The name of a kind of routine: "SFOSUB" ... "VTOSUB", "REQSUB".
    pure function routine_name_of(kind) result(name)
        integer, intent(in) :: kind
        character(len=:), allocatable :: name

        if (kind >= 1 .and. kind <= routine_kinds) then
            name = trim(routine_names(kind))
        else if (kind == routine_reqsub) then
            name = request_routine_name
        else if (kind == routine_varsub) then
            name = variable_routine_name
        else if (kind == routine_motsub) then
            name = motion_routine_name
        else if (kind == routine_difsub) then
            name = diff_routine_name
        else
            name = "a user routine"
        end if
    end function routine_name_of

    !> Empty the table (the direct call hook again; the DIFSUBs' rows forgotten).
    subroutine clear_force_routines()
        if (allocated(table)) deallocate(table)
        allocate(table(0))
        table_count = 0
        call_hook => direct_force_call
        diff_rows = [integer ::]
    end subroutine clear_force_routines

    !> The entry serving a statement of kind that names routine ("" for the model's own): its
    !> index, 0 when the table holds none. A name is matched in any case; "library::name"
    !> also matches an entry registered as the same library and name.
    function find_force_routine(kind, routine) result(entry)
        integer, intent(in) :: kind
        character(len=*), intent(in) :: routine
        integer :: entry
        integer :: k

        entry = 0
        if (.not. allocated(table)) return
        do k = 1, table_count
            if (table(k)%kind /= kind) cycle
            if (upper_case(trim(table(k)%name)) /= upper_case(trim(routine))) cycle
            entry = k
            return
        end do
    end function find_force_routine

    !> "SFOSUB of u.f" for messages.
    function force_routine_label(entry) result(label)
        integer, intent(in) :: entry
        character(len=:), allocatable :: label

        label = "a user routine"
        if (.not. allocated(table)) return
        if (entry < 1 .or. entry > table_count) return
        label = routine_name_of(table(entry)%kind) // " of " // table(entry)%source
        if (len(table(entry)%name) > 0) label = label // " (ROUTINE=" // table(entry)%name &
            & // ")"
    end function force_routine_label

    !> The kind of routine a statement needs: "SFORCE" gives routine_sfosub, and so on; 0 for
    !> none.
    pure integer function routine_kind_of(statement) result(kind)
        character(len=*), intent(in) :: statement

        kind = findloc(routine_statements, statement, dim=1)
        if (kind < 1 .or. kind > routine_kinds) kind = 0
    end function routine_kind_of

    !> Route every call through hook (a guard); null: the direct call.
    subroutine set_force_call_hook(hook)
        procedure(force_call_interface), pointer, intent(in) :: hook

        if (associated(hook)) then
            call_hook => hook
        else
            call_hook => direct_force_call
        end if
    end subroutine set_force_call_hook

    !> Call the routine of entry as it is.
    subroutine direct_force_call(entry, id, time, par, npar, dflag, iflag, result, n)
        integer, intent(in) :: entry, id, npar, n
        real(wp), intent(in) :: time, par(:)
        logical, intent(in) :: dflag, iflag
        real(wp), intent(inout) :: result(n)

        if (table(entry)%kind == routine_reqsub) then
            call table(entry)%request(id, time, par, npar, iflag, result)
        else if (table(entry)%kind == routine_varsub .or. table(entry)%kind == routine_difsub) &
            & then
            call table(entry)%variable(id, time, par, npar, dflag, iflag, result(1))
        else if (table(entry)%kind == routine_motsub) then
            call table(entry)%motion(id, time, par, npar, motion_order, iflag, result(1))
        else
            call table(entry)%routine(id, time, par, npar, dflag, iflag, result)
        end if
    end subroutine direct_force_call

    !> The REQSUB of entry, for a guard that calls it.
    subroutine get_request_routine(entry, routine)
        integer, intent(in) :: entry
        procedure(request_routine_interface), pointer, intent(out) :: routine

        routine => table(entry)%request
    end subroutine get_request_routine

    !> Call the REQSUB of entry for REQUEST/id at (t, q, u) (through the call hook): its
    !> RESULT(8) in result. The first call for a request (declared not allocated) is preceded
    !> by the initialisation call (IFLAG = .TRUE.), whose SYSFNC and SYSARY calls set declared
    !> and declared_rates; later calls' reads are compared with them (system_notes). An ERRMES,
    !> a utility's refusal or a RESULT not finite leaves an error naming `name` ("x.adm:12:
    !> REQUEST/5") for take_user_force_error, and result NaN. The accelerations its SYSARY
    !> ('TACC', 'RACC') and SYSFNC ('ACCX' ... 'WDTM') calls read are those of the output row,
    !> known there (accelerations: all parts' [SI]; absent: those set_system_accelerations
    !> gave last); those set before are restored after the call.
    subroutine call_user_request(entry, id, name, par, time_unit, time, q, u, declared, &
            & declared_rates, result, accelerations)
        integer, intent(in) :: entry, id
        character(len=*), intent(in) :: name
        !> The constants of USER(r1, ..., rn)
        real(wp), intent(in) :: par(:)
        !> The dataset's time unit [s]
        real(wp), intent(in) :: time_unit
        !> Time [s], coordinates and rates of all parts [SI]
        real(wp), intent(in) :: time, q(:), u(:)
        integer, allocatable, intent(inout) :: declared(:)
        logical, intent(inout) :: declared_rates
        real(wp), intent(out) :: result(request_results)
        real(wp), intent(in), optional :: accelerations(:)
        type(error_type), allocatable :: error
        character(len=:), allocatable :: label
        real(wp), allocatable :: kept(:)

        if (present(accelerations)) then
            if (allocated(a_now)) kept = a_now
            a_now = accelerations
        end if
        label = routine_name_of(routine_reqsub)
        if (entry >= 1 .and. entry <= table_count) label = force_routine_label(entry)
        if (.not. allocated(declared)) then
            call begin_call(time, q, u)
            declaring = .true.
            named = [integer ::]
            named_rates = .false.
            result = 0.0_wp
            request_call = .true.
            call call_hook(entry, id, time/time_unit, par, size(par), .false., .true., result, &
                & request_results)
            request_call = .false.
            declaring = .false.
            declared = named
            declared_rates = named_rates
            call request_problem("the initialisation call (IFLAG = .TRUE.)", error)
            if (allocated(error)) then
                result = ieee_value(0.0_wp, ieee_quiet_nan)
                if (.not. allocated(pending)) call move_alloc(error, pending)
                call restore_accelerations()
                return
            end if
        end if
        call begin_call(time, q, u)
        allowed = declared
        allowed_rates = declared_rates
        result = 0.0_wp
        request_call = .true.
        call call_hook(entry, id, time/time_unit, par, size(par), .false., .false., result, &
            & request_results)
        request_call = .false.
        deallocate(allowed)
        allowed_rates = .true.
        if (.not. all(ieee_is_finite(result))) then
            call fatal_error(error, name // ": its " // label // " returned RESULT = (" &
                & // number_list(result) // ") at TIME = " // to_text(time/time_unit) &
                & // ": a request's values must be finite", stat_ucon)
        else
            call request_problem("the call", error)
        end if
        if (allocated(error)) then
            result = ieee_value(0.0_wp, ieee_quiet_nan)
            if (.not. allocated(pending)) call move_alloc(error, pending)
        end if
        call restore_accelerations()
    contains
        !> The accelerations set before the call again (those given were for it alone).
        subroutine restore_accelerations()
            if (.not. present(accelerations)) return
            if (allocated(kept)) then
                a_now = kept
            else
                deallocate(a_now)
            end if
        end subroutine restore_accelerations

        subroutine request_problem(call_name, error)
            character(len=*), intent(in) :: call_name
            type(error_type), allocatable, intent(out) :: error
            type(error_type), allocatable :: reported
            character(len=:), allocatable :: message
            integer :: colon

            call take_ucon_error(reported)
            if (allocated(reported)) then
                message = reported%message
                colon = index(message, ": ")
                if (index(message, "UCON/") == 1 .and. colon > 0) message = message(colon + 2:)
                call fatal_error(error, name // ": its " // label // " reported an error in " &
                    & // call_name // " at TIME = " // to_text(time/time_unit) // ": " &
                    & // message, stat_ucon)
            else if (len(problem) > 0) then
                call fatal_error(error, name // ": its " // label // ", in " // call_name &
                    & // " at TIME = " // to_text(time/time_unit) // ": " // problem, stat_ucon)
            end if
        end subroutine request_problem
    end subroutine call_user_request

    !> The routine of entry and its kind (routine_sfosub ...), for a guard that calls it.
    subroutine get_force_routine(entry, routine, kind)
        integer, intent(in) :: entry
        procedure(force_routine_interface), pointer, intent(out) :: routine
        integer, intent(out) :: kind

        routine => table(entry)%routine
        kind = table(entry)%kind
    end subroutine get_force_routine

    !> What a guard found wrong with the call under way (a write outside RESULT, a changed
    !> argument): the call's error says it, naming the statement and the routine.
    subroutine report_call_problem(why)
        character(len=*), intent(in) :: why

        call refuse(why)
    end subroutine report_call_problem

    !> The markers SYSFNC and SYSARY may name (every marker of the model) and the dataset's
    !> units [m, s, N] the routines compute in (force absent: 1 N); a new model's (the
    !> DIFSUBs' rows forgotten).
    subroutine set_system_markers(all_markers, length, time, force)
        type(marker_type), intent(in) :: all_markers(:)
        real(wp), intent(in) :: length, time
        real(wp), intent(in), optional :: force

        markers = all_markers
        length_unit = length
        time_unit = time
        force_unit = 1.0_wp
        if (present(force)) force_unit = force
        ! a new model: its DIFSUBs have read no reaction yet
        diff_rows = [integer ::]
    end subroutine set_system_markers

    !> Who answers SYSFNC's force measures (rollcon_force_measures' answer; null: nobody, and
    !> they are refused).
    subroutine set_force_measure_hook(hook)
        procedure(force_measure_interface), pointer, intent(in) :: hook

        measure_hook => hook
    end subroutine set_force_measure_hook

    !> The constraint rows c (C, nc x n: dF/du, or dF/dq for a position UCON, by rows over each
    !> UCON's coordinates) and multipliers lambda (nc) [the rows' units] SYSFNC's force
    !> measures read a JOINT's or JPRIM's reaction from until the next call of this
    !> (rollcon_equations' iterates of its algebraic loop, rollcon_dae's unknowns, an output
    !> row's solve). Called at every evaluation on those paths: the rows' pattern is copied
    !> when it changes (the first call, or another model's equations), otherwise only their
    !> values, into arrays of the same size (nothing allocated).
    subroutine set_system_constraint_forces(c, lambda)
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: lambda(:)

        if (same_pattern(c_now, c)) then
            c_now%value = c%value
        else
            c_now = c
        end if
        lambda_now = lambda
    end subroutine set_system_constraint_forces

    !> True when a and b hold the same pattern (sizes, row starts and columns), so that b's
    !> values may be copied into a's array as they are.
    pure logical function same_pattern(a, b)
        type(constraint_matrix_type), intent(in) :: a, b
        integer :: x

        same_pattern = .false.
        if (a%n /= b%n .or. a%nc /= b%nc) return
        if (.not. (allocated(a%start) .and. allocated(a%column) .and. allocated(a%value) &
            & .and. allocated(b%start) .and. allocated(b%column) .and. allocated(b%value))) &
            & return
        if (size(a%start) /= size(b%start) .or. size(a%column) /= size(b%column) .or. &
            & size(a%value) /= size(b%value)) return
        do x = 1, size(a%start)
            if (a%start(x) /= b%start(x)) return
        end do
        do x = 1, size(a%column)
            if (a%column(x) /= b%column(x)) return
        end do
        same_pattern = .true.
    end function same_pattern

    !> The multipliers the force measures read, the constraint rows kept (a DIFSUB's partials
    !> in them are differenced with the rows of the state: rollcon_diff's
    !> multiplier_partials).
    subroutine set_system_multipliers(lambda)
        real(wp), intent(in) :: lambda(:)

        lambda_now = lambda
    end subroutine set_system_multipliers

    !> The multipliers the force measures read (set_system_constraint_forces' or
    !> set_system_multipliers'; zeros of size nc before any).
    function system_multipliers(nc) result(lambda)
        integer, intent(in) :: nc
        real(wp) :: lambda(nc)

        lambda = 0.0_wp
        if (allocated(lambda_now)) then
            if (size(lambda_now) == nc) lambda = lambda_now
        end if
    end function system_multipliers

    !> True when a force of the model is served by a routine whose initialisation call read
    !> a force measure summing a constraint's reaction (its values then depend on the
    !> multipliers: an algebraic loop), or a VARSUB's or a DIFSUB's did (the equations then
    !> give the routines the multipliers at every state: the loop of the forces reading the
    !> VARIABLE, the reaction a DIFF integrates).
    pure logical function reads_constraint_forces(forces)
        type(applied_force_type), intent(in) :: forces(:)
        integer :: i

        reads_constraint_forces = variables_read_constraint_forces()
        if (allocated(diff_rows)) then
            if (size(diff_rows) > 0) reads_constraint_forces = .true.
        end if
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine == 0) cycle
            if (.not. allocated(forces(i)%statement%declared_rows)) cycle
            if (size(forces(i)%statement%declared_rows) > 0) reads_constraint_forces = .true.
        end do
    end function reads_constraint_forces

    !> True when a VARSUB's initialisation call read a force measure summing a constraint's
    !> reaction (user_variable_type's declared_rows).
    pure logical function variables_read_constraint_forces() result(reads)
        integer :: v

        reads = .false.
        if (.not. allocated(variables)) return
        do v = 1, size(variables)
            if (.not. allocated(variables(v)%declared_rows)) cycle
            if (size(variables(v)%declared_rows) > 0) reads = .true.
        end do
    end function variables_read_constraint_forces

    !> dv_dlambda(v, k): the partial of the v-th user VARIABLE (user_variable_list's order) in
    !> the multiplier of row k at (t, q, u, lambda), by central differences
    !> (rollcon_central_differences) over the rows its initialisation call's force measures
    !> summed (declared_rows), each call with DFLAG = .TRUE.; zero elsewhere and for the
    !> VARIABLEs that read no reaction. The multipliers and values set before are restored.
    subroutine difference_variable_multipliers(time, q, u, lambda, dv_dlambda)
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: dv_dlambda(:, :)
        real(wp), allocatable :: kept(:), block(:, :), values(:)
        integer :: v

        dv_dlambda = 0.0_wp
        if (.not. allocated(variables)) return
        if (allocated(lambda_now)) then
            kept = lambda_now
        else
            allocate(kept(size(lambda)), source=0.0_wp)
        end if
        values = variables%value
        do v = 1, size(variables)
            if (.not. allocated(variables(v)%declared_rows)) cycle
            if (size(variables(v)%declared_rows) == 0) cycle
            allocate(block(size(variables(v)%declared_rows), 1), source=0.0_wp)
            call central_differences(lambda, variables(v)%declared_rows, multipliers_moved, &
                & block)
            dv_dlambda(v, variables(v)%declared_rows) = block(:, 1)
            deallocate(block)
        end do
        lambda_now = kept
        variables%value = values

    contains

        subroutine multipliers_moved(shifted, moved, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: moved(:)
            logical, intent(out) :: failed

            lambda_now = shifted
            call variable_call(variables(v), time, q, u, .true., moved(1), failed)
        end subroutine multipliers_moved

    end subroutine difference_variable_multipliers

    !> The constraint rows whose reactions the VARSUBs of the VARIABLEs an expression force
    !> reads (VARVAL) summed, as the force's declared_rows (the DAE form's sparse pattern
    !> keeps the momentum rows of the parts it loads by those rows' multipliers); a force
    !> served by a routine has them from its initialisation call.
    subroutine declare_variable_rows(forces)
        type(applied_force_type), intent(inout) :: forces(:)
        integer, allocatable :: rows(:)
        integer :: i, k, m, v, r

        if (.not. allocated(variables)) return
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            associate (s => forces(i)%statement)
                if (s%routine > 0) cycle
                rows = [integer ::]
                do k = 1, 6
                    if (.not. s%given(k)) cycle
                    if (.not. allocated(s%functions(k)%inputs)) cycle
                    do m = 1, size(s%functions(k)%inputs)
                        if (s%functions(k)%inputs(m)%quantity /= quantity_varval) cycle
                        v = findloc(variables%id, s%functions(k)%inputs(m)%marker, dim=1)
                        if (v == 0) cycle
                        if (.not. allocated(variables(v)%declared_rows)) cycle
                        do r = 1, size(variables(v)%declared_rows)
                            if (.not. any(rows == variables(v)%declared_rows(r))) &
                                & rows = [rows, variables(v)%declared_rows(r)]
                        end do
                    end do
                end do
                if (size(rows) > 0) s%declared_rows = rows
            end associate
        end do
    end subroutine declare_variable_rows

    !> difference_call at (t, q, u) with the multipliers lambda its force measures read; the
    !> multipliers set before are restored after it.
    subroutine multiplier_difference_call(force, time, q, u, lambda, values, failed)
        type(applied_force_type), intent(in) :: force
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(6)
        logical, intent(out) :: failed
        real(wp), allocatable :: kept(:)

        if (allocated(lambda_now)) then
            kept = lambda_now
        else
            allocate(kept(size(lambda)), source=0.0_wp)
        end if
        lambda_now = lambda
        call difference_call(force, time, q, u, values, failed)
        lambda_now = kept
    end subroutine multiplier_difference_call

    !> The curves AKISPL and CUBSPL may read: every SPLINE of the model, fitted.
    subroutine set_system_splines(all_curves)
        type(spline_type), intent(in) :: all_curves(:)

        curves = all_curves
    end subroutine set_system_splines

    !> AKISPL(XVAL, ZVAL, ID, IORD, ARRAY, ERRFLG) (method_akima) and CUBSPL(...)
    !> (method_cubic): SPLINE/id's curve at xval (Akima's fit, or the natural cubic spline),
    !> or its derivative of order iord (0, 1, 2) in x, as the expression functions AKISPL and
    !> CUBSPL read it (rollcon_spline), into array(1); array(2) and array(3), a surface's
    !> derivatives in z, are 0 (a SPLINE is a curve; zval is unused). Values in the units the
    !> SPLINE's numbers carry. ERRFLG set, and array 0, for a SPLINE the model lacks, an iord
    !> not 0, 1 or 2, and CUBSPL of fewer than 4 points.
    subroutine system_spline(method, xval, zval, id, iord, array, errflg)
        integer, intent(in) :: method
        real(wp), intent(in) :: xval, zval
        integer, intent(in) :: id, iord
        real(wp), intent(out) :: array(3)
        logical, intent(out) :: errflg
        character(len=:), allocatable :: name
        real(wp) :: values(0:3)
        integer :: k, found

        array = 0.0_wp
        errflg = .true.
        name = trim(merge("AKISPL", "CUBSPL", method == method_akima))
        if (.not. allocated(curves)) allocate(curves(0))
        found = 0
        do k = 1, size(curves)
            if (curves(k)%id == id) found = k
        end do
        if (found == 0) then
            call refuse(name // " names SPLINE/" // to_text(id) // ", which the model has not")
            return
        end if
        if (iord < 0 .or. iord > 2) then
            call refuse(name // " with IORD = " // to_text(iord) // ": it gives the value " &
                & // "(0) or the first or second derivative (1, 2)")
            return
        end if
        if (method == method_cubic .and. size(curves(found)%x) < 4) then
            call refuse("CUBSPL of SPLINE/" // to_text(id) // ", which has " &
                & // to_text(size(curves(found)%x)) // " points: the cubic spline needs 4")
            return
        end if
        values = spline_derivatives(curves(found), method, xval)
        array(1) = values(iord)
        errflg = .false.
    end subroutine system_spline

    !> True when a force of the model is served by a user's routine.
    pure logical function has_user_forces(forces)
        type(applied_force_type), intent(in) :: forces(:)
        integer :: i

        has_user_forces = .false.
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine > 0) has_user_forces = .true.
        end do
    end function has_user_forces

    !> The initialisation call (IFLAG = .TRUE.) of a force's routine at (t, q, u): the markers
    !> its SYSFNC and SYSARY calls name become its declaration. An error names the statement
    !> (force%name), the routine and what went wrong.
    subroutine declare_user_force(force, time, q, u, error)
        type(applied_force_type), intent(inout) :: force
        !> Time [s], coordinates and rates of all parts [SI]
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: result(6)
        integer :: n

        associate (s => force%statement)
            n = routine_results(table(s%routine)%kind)
            call begin_call(time, q, u)
            declaring = .true.
            named = [integer ::]
            named_rates = .false.
            named_accelerations = .false.
            named_variables = .false.
            named_forces = .false.
            named_rows = [integer ::]
            result = 0.0_wp
            force_call = .true.
            caller_now = force%name
            call call_hook(s%routine, s%id, time/s%time_unit, s%par, size(s%par), .false., &
                & .true., result(:n), n)
            caller_now = ""
            force_call = .false.
            declaring = .false.
            s%declared_forces = named_forces
            s%declared_rows = named_rows
            s%declared_markers = named
            s%declared_rates = named_rates
            s%declared_accelerations = named_accelerations
            s%declared_variables = named_variables
            s%declared_parts = parts_of(named)
            call after_call(force, "the initialisation call (IFLAG = .TRUE.)", time, error)
        end associate
    end subroutine declare_user_force

    !> Call every user routine of forces at (t, q, u) and keep its values (SI) for the pure
    !> force procedures; the first failure is kept for take_user_force_error. The routines
    !> that read force measures are called after the others (the forces they sum are then
    !> those at this state; rollcon_force_measures refuses one force measure reading another
    !> such routine's force).
    subroutine evaluate_user_forces(forces, time, q, u)
        ! (a target: the force measures read the forces through the model while they change)
        type(applied_force_type), intent(inout), target :: forces(:)
        !> Time [s], coordinates and rates of all parts [SI]
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable :: error
        real(wp) :: result(6), values(6)
        integer :: i, pass, n, kind

        ! the routines reading no force measure first (pass 0), in the dataset's order, then
        ! those that read them (pass 1): no order array, an evaluation allocates nothing
        do pass = 0, 1
            do i = 1, size(forces)
                if (forces(i)%statement%declared_forces .neqv. pass == 1) cycle
                if (forces(i)%profile /= profile_statement) cycle
                associate (s => forces(i)%statement)
                    if (s%routine == 0) cycle
                    kind = table(s%routine)%kind
                    n = routine_results(kind)
                    call begin_call(time, q, u)
                    if (allocated(s%declared_markers)) then
                        allowed = s%declared_markers
                        allowed_rates = s%declared_rates
                        allowed_accelerations = s%declared_accelerations
                    else if (allocated(allowed)) then
                        ! not declared yet: nothing to compare with
                        deallocate(allowed)
                    end if
                    if (allocated(s%declared_rows)) allowed_rows = s%declared_rows
                    result = 0.0_wp
                    force_call = .true.
                    caller_now = forces(i)%name
                    call call_hook(s%routine, s%id, time/s%time_unit, s%par, size(s%par), &
                        & .false., .false., result(:n), n)
                    caller_now = ""
                    force_call = .false.
                    if (allocated(allowed)) deallocate(allowed)
                    if (allocated(allowed_rows)) deallocate(allowed_rows)
                    allowed_rates = .true.
                    allowed_accelerations = .true.
                    values = 0.0_wp
                    select case (n)
                    case (1)
                        values(1) = result(1)*s%force_unit
                    case (3)
                        if (kind == routine_vtosub) then
                            ! a VTOSUB's RESULT is the torque TX, TY, TZ
                            values(4:6) = result(1:3)*s%force_unit*s%length_unit
                        else
                            values(1:3) = result(1:3)*s%force_unit
                        end if
                    case default
                        values(1:3) = result(1:3)*s%force_unit
                        values(4:6) = result(4:6)*s%force_unit*s%length_unit
                    end select
                    s%user_values = values
                    if (.not. all(ieee_is_finite(result(:n)))) then
                        call fatal_error(error, forces(i)%name // ": its " &
                            & // force_routine_label(s%routine) // " returned RESULT = (" &
                            & // number_list(result(:n)) // ") at TIME = " &
                            & // to_text(time/s%time_unit) &
                            & // ": a force must be finite", stat_ucon)
                    else
                        call after_call(forces(i), "the call", time, error)
                    end if
                    if (allocated(error)) then
                        if (.not. allocated(pending)) call move_alloc(error, pending)
                    end if
                end associate
            end do
        end do
    end subroutine evaluate_user_forces

    !> A call of a force's routine with DFLAG = .TRUE. at (t, q, u), one of the differences
    !> its partials are formed from (rollcon_user_force_partials): its values in SI (as
    !> user_values holds them, which this call leaves as they are) and whether the call
    !> failed (an ERRMES, a utility's refusal, a value that is not finite), the failure kept
    !> for take_user_force_error. What it reads beyond its declaration is noted as in any
    !> call (system_notes).
    subroutine difference_call(force, time, q, u, values, failed)
        type(applied_force_type), intent(in) :: force
        !> Time [s], coordinates and rates of all parts [SI]
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: values(6)
        logical, intent(out) :: failed
        type(error_type), allocatable :: error
        real(wp) :: result(6)
        real(wp), allocatable :: kept(:)
        integer, allocatable :: ids(:)
        integer :: n

        associate (s => force%statement)
            n = routine_results(table(s%routine)%kind)
            ! the VARSUBs its SYSFNC('VARVAL') reads, at the shifted state (their values at
            ! the state itself restored after)
            if (s%declared_variables .and. allocated(variables)) then
                kept = variables%value
                call evaluate_user_variables(time, q, u)
            end if
            call begin_call(time, q, u)
            if (allocated(s%declared_markers)) then
                allowed = s%declared_markers
                allowed_rates = s%declared_rates
                allowed_accelerations = s%declared_accelerations
            else if (allocated(allowed)) then
                deallocate(allowed)
            end if
            if (allocated(s%declared_rows)) allowed_rows = s%declared_rows
            result = 0.0_wp
            force_call = .true.
            caller_now = force%name
            call call_hook(s%routine, s%id, time/s%time_unit, s%par, size(s%par), .true., &
                & .false., result(:n), n)
            caller_now = ""
            force_call = .false.
            if (allocated(allowed)) deallocate(allowed)
            if (allocated(allowed_rows)) deallocate(allowed_rows)
            allowed_rates = .true.
            allowed_accelerations = .true.
            if (allocated(kept)) then
                variables%value = kept
                ids = variables%id
                call set_user_variable_values(ids, kept)
            end if
            values = 0.0_wp
            if (table(s%routine)%kind == routine_vtosub) then
                ! a VTOSUB's RESULT is the torque TX, TY, TZ (as evaluate_user_forces keeps it)
                values(4:6) = result(1:3)*s%force_unit*s%length_unit
            else
                values(1:min(n, 3)) = result(1:min(n, 3))*s%force_unit
                if (n == 6) values(4:6) = result(4:6)*s%force_unit*s%length_unit
            end if
            failed = .not. all(ieee_is_finite(result(:n)))
            if (failed) then
                call fatal_error(error, force%name // ": its " &
                    & // force_routine_label(s%routine) // " returned RESULT = (" &
                    & // number_list(result(:n)) // ") in a call with DFLAG = .TRUE. at TIME = " &
                    & // to_text(time/s%time_unit) // ": a force must be finite", stat_ucon)
            else
                call after_call(force, "a call with DFLAG = .TRUE.", time, error)
                failed = allocated(error)
            end if
            if (allocated(error)) then
                if (.not. allocated(pending)) call move_alloc(error, pending)
            end if
        end associate
    end subroutine difference_call

    !> The model parts of the markers ids (the table's markers; ground and repeats left out).
    function parts_of(ids) result(parts)
        integer, intent(in) :: ids(:)
        integer, allocatable :: parts(:)
        integer :: k, m

        allocate(parts(0))
        if (.not. allocated(markers)) return
        do k = 1, size(ids)
            do m = 1, size(markers)
                if (markers(m)%id /= ids(k)) cycle
                if (markers(m)%part > 0 .and. .not. any(parts == markers(m)%part)) &
                    & parts = [parts, markers(m)%part]
                exit
            end do
        end do
    end function parts_of

    !> Move the first failure of a user routine, if any, to the caller.
    subroutine take_user_force_error(error)
        type(error_type), allocatable, intent(out) :: error

        if (allocated(pending)) call move_alloc(pending, error)
    end subroutine take_user_force_error

    !> The notes the utilities made since clear_system_notes (calls that named what the
    !> routine had not declared, names they do not know), one a line.
    function system_notes() result(text)
        character(len=:), allocatable :: text

        text = ""
        if (allocated(notes)) text = notes
    end function system_notes

    !> Forget the notes.
    subroutine clear_system_notes()
        notes = ""
    end subroutine clear_system_notes

    !> Set the state the utilities answer from.
    subroutine begin_call(time, q, u)
        real(wp), intent(in) :: time, q(:), u(:)

        time_now = time
        q_now = q
        u_now = u
        problem = ""
        if (.not. allocated(markers)) allocate(markers(0))
        if (.not. allocated(notes)) notes = ""
    end subroutine begin_call

    !> After a call: an ERRMES it made, or a utility's refusal, as an error naming the force.
    subroutine after_call(force, call_name, time, error)
        type(applied_force_type), intent(in) :: force
        character(len=*), intent(in) :: call_name
        real(wp), intent(in) :: time
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: reported
        character(len=:), allocatable :: message
        integer :: colon

        call take_ucon_error(reported)
        if (allocated(reported)) then
            message = reported%message
            ! ERRMES keeps its message as a UCON's: "UCON/2: ..."
            colon = index(message, ": ")
            if (index(message, "UCON/") == 1 .and. colon > 0) message = message(colon + 2:)
            ! the utility's refusal that the routine's ERRMES reports, when there is one
            if (len(problem) > 0) message = message // " (" // problem // ")"
            call fatal_error(error, force%name // ": its " &
                & // force_routine_label(force%statement%routine) // " reported an error in " &
                & // call_name // " at TIME = " // to_text(time/force%statement%time_unit) &
                & // ": " // message, stat_ucon)
            return
        end if
        if (len(problem) > 0) then
            call fatal_error(error, force%name // ": its " &
                & // force_routine_label(force%statement%routine) // ", in " // call_name &
                & // " at TIME = " // to_text(time/force%statement%time_unit) // ": " // problem, &
                & stat_ucon)
        end if
    end subroutine after_call

    !> SYSFNC(FNCNAM, IPAR, NSIZE, VALUE, ERRFLG): one measure of markers IPAR(1:NSIZE) at the
    !> call's state, in the dataset's units: DX, DY, DZ, DM, VX, VY, VZ, VM, VR, WX, WY, WZ,
    !> WM, AX, AY, AZ, PSI, THETA, PHI, YAW, PITCH, ROLL with the markers as a FUNCTION
    !> expression takes them (docs/datasets.md, "Measures of markers"), the accelerations
    !> ACCX, ACCY, ACCZ, ACCM, WDTX, WDTY, WDTZ, WDTM (rollcon_marker_acceleration) from the
    !> accelerations set_system_accelerations gave (the algebraic loop a force reading them
    !> makes is solved by the equations: rollcon_equations, rollcon_dae; a MOTSUB's read is
    !> recorded for call_user_motion's refusal, ERRFLG clear), and DIF(id), DIF1(id)
    !> of a DIFF (IPAR(1) = id; NSIZE = 1) from set_system_diff_state's, and the force
    !> measures FX ... TM and an element's force JOINT ... SPDP (force_measure). ERRFLG is
    !> set, and VALUE 0, for a name rollcon does not know or a marker the model has not.
    subroutine system_function(name, ipar, value, errflg)
        character(len=*), intent(in) :: name
        integer, intent(in) :: ipar(:)
        real(wp), intent(out) :: value
        logical, intent(out) :: errflg
        integer :: quantity

        value = 0.0_wp
        errflg = .true.
        quantity = findloc(quantity_names, upper_case(trim(adjustl(name))), dim=1)
        if (quantity == 0) then
            call refuse("SYSFNC('" // trim(name) // "'): not a function rollcon's SYSFNC " &
                & // "knows (DX, DY, DZ, DM, VX, VY, VZ, VM, VR, WX, WY, WZ, WM, AX, AY, AZ, " &
                & // "PSI, THETA, PHI, YAW, PITCH, ROLL, ACCX, ACCY, ACCZ, ACCM, WDTX, WDTY, " &
                & // "WDTZ, WDTM, DIF, DIF1, VARVAL)")
            return
        end if
        if (quantity == quantity_dif .or. quantity == quantity_dif1) then
            call diff_measure(quantity, ipar, value, errflg)
            return
        end if
        if (quantity == quantity_varval) then
            call variable_measure(ipar, value, errflg)
            return
        end if
        if (any(quantity_kind(quantity) == [kind_force, kind_torque, kind_element_force])) then
            call force_measure(quantity, ipar, value, errflg)
            return
        end if
        if (.not. is_state_measure(quantity) .and. .not. is_acceleration(quantity)) then
            call refuse("SYSFNC('" // trim(name) // "'): not a function rollcon's SYSFNC " &
                & // "answers")
            return
        end if
        if (size(ipar) < quantity_least_markers(quantity) .or. size(ipar) &
            & > quantity_most_markers(quantity)) then
            call refuse("SYSFNC('" // trim(name) // "') with NSIZE = " // to_text(size(ipar)) &
                & // ": it takes " // to_text(quantity_least_markers(quantity)) // " to " &
                & // to_text(quantity_most_markers(quantity)) // " marker ids")
            return
        end if
        call measure(quantity, ipar, "SYSFNC('" // trim(name) // "')", value, errflg)
    end subroutine system_function

    !> SYSFNC's force measures, in the dataset's units (force; force times length), as a
    !> REQUEST's expression reads them (docs/datasets.md, "Force measures read by a user's
    !> routine"): FX, FY, FZ, FM, TX, TY, TZ, TM (IPAR = i[, j[, k]]): the force and torque at
    !> marker i of the elements acting there (as their I or J) and, with j, between i and j,
    !> in k's axes (ground's when none); an element's force JOINT, JPRIM, SFORCE, VFORCE,
    !> VTORQUE, GFORCE, BUSHING, SPDP (IPAR = id, jflag[, comp[, rm]]: at its I (jflag 0) or J
    !> (1); comp 1 |F|, 2-4 F's x, y, z in rm's axes, 5 |T|, 6-8 T's; comp absent: 1). The
    !> sums are rollcon_force_measures' (the hook), from the multipliers and constraint rows
    !> set_system_constraint_forces gave; answered to a force routine and a REQSUB alone. At
    !> the initialisation call the constraint rows summed and the markers of the forces summed
    !> are declared (the force's dependencies; named_forces).
    subroutine force_measure(quantity, ipar, value, errflg)
        integer, intent(in) :: quantity, ipar(:)
        real(wp), intent(out) :: value
        logical, intent(out) :: errflg
        character(len=:), allocatable :: call_name, why
        integer, allocatable :: rows(:), read_markers(:)
        real(wp) :: wrench(6), resolved(6), r(3), v(3), axes(3, 3), w(3)
        integer :: ids(4), element_ids(2), comp, axes_marker, m, k
        logical :: element, found

        value = 0.0_wp
        errflg = .true.
        call_name = "SYSFNC('" // trim(quantity_names(quantity)) // "')"
        element = quantity_kind(quantity) == kind_element_force
        if (.not. (force_call .or. request_call .or. variable_calling .or. diff_calling)) then
            call refuse(call_name // ": a force, which rollcon answers to a force routine " &
                & // "(SFOSUB, VFOSUB, VTOSUB, GFOSUB), a VARSUB, a DIFSUB and a REQSUB; a " &
                & // "MOTSUB's MOTION is a function of TIME alone")
            return
        end if
        if (.not. associated(measure_hook) .or. .not. allocated(c_now%value)) then
            call refuse(call_name // ": a force, which rollcon answers once the model's " &
                & // "equations are set up (a force routine in a run and in rollcon check's " &
                & // "probes, a REQSUB at a run's output rows); here they are not")
            return
        end if
        if (element) then
            if (size(ipar) < 2 .or. size(ipar) > 4) then
                call refuse(call_name // " with NSIZE = " // to_text(size(ipar)) // ": it " &
                    & // "takes 2 to 4 values (id, jflag[, comp[, rm]])")
                return
            end if
            comp = 1
            if (size(ipar) >= 3) comp = ipar(3)
            axes_marker = 0
            if (size(ipar) >= 4) axes_marker = ipar(4)
            if (ipar(2) < 0 .or. ipar(2) > 1 .or. comp < 1 .or. comp > 8) then
                call refuse(call_name // " with jflag = " // to_text(ipar(2)) // ", comp = " &
                    & // to_text(comp) // ": jflag is 0 (at I) or 1 (at J), comp 1 to 8")
                return
            end if
            element_ids = ipar(1:2)
            ids = [axes_marker, 0, 0, 0]
        else
            if (size(ipar) < 1 .or. size(ipar) > 3) then
                call refuse(call_name // " with NSIZE = " // to_text(size(ipar)) // ": it " &
                    & // "takes 1 to 3 marker ids")
                return
            end if
            ids = 0
            ids(:size(ipar)) = ipar
            if (ids(1) == 0) then
                call refuse(call_name // ": IPAR(1) must name a marker, got 0")
                return
            end if
            element_ids = ids(1:2)
            axes_marker = ids(3)
            comp = 0
        end if
        ! every marker named must be the model's
        do m = 1, 4
            if (ids(m) == 0) cycle
            found = .false.
            do k = 1, size(markers)
                if (markers(k)%id == ids(m)) found = .true.
            end do
            if (.not. found) then
                call refuse(call_name // " names marker " // to_text(ids(m)) &
                    & // ", which the model has not")
                return
            end if
        end do
        if (.not. allocated(caller_now)) caller_now = ""
        if (.not. allocated(lambda_now)) allocate(lambda_now(c_now%nc), source=0.0_wp)
        call measure_hook(quantity, element_ids, caller_now, time_now, q_now, u_now, c_now, &
            & lambda_now, wrench, rows, read_markers, why)
        if (len(why) > 0) then
            call refuse(call_name // ": " // why)
            return
        end if
        call note_reads(ids, .false., call_name)
        if (declaring) then
            if (.not. allocated(named_rows)) named_rows = [integer ::]
            named_forces = .true.
            do m = 1, size(rows)
                if (.not. any(named_rows == rows(m))) named_rows = [named_rows, rows(m)]
            end do
            do m = 1, size(read_markers)
                if (.not. any(named == read_markers(m))) named = [named, read_markers(m)]
            end do
            ! the forces summed may read rates
            if (size(read_markers) > 0) named_rates = .true.
        else if (allocated(allowed_rows)) then
            if (any([(.not. any(allowed_rows == rows(m)), m = 1, size(rows))])) &
                & call add_note(call_name // " read a constraint's reaction the " &
                & // "initialisation call (IFLAG = .TRUE.) did not read")
        end if
        resolved = wrench
        if (axes_marker /= 0) then
            do k = 1, size(markers)
                if (markers(k)%id /= axes_marker) cycle
                call marker_motion(markers(k), q_now, u_now, r, v, axes, w)
                resolved(1:3) = transpose_times(axes, wrench(1:3))
                resolved(4:6) = transpose_times(axes, wrench(4:6))
                exit
            end do
        end if
        if (element) then
            select case (comp)
            case (1)
                value = norm2(wrench(1:3))
            case (2:4)
                value = resolved(comp - 1)
            case (5)
                value = norm2(wrench(4:6))
            case default
                value = resolved(comp - 2)
            end select
            value = value/force_unit
            if (comp >= 5) value = value/length_unit
        else
            select case (quantity)
            case (quantity_fx:quantity_fx + 2)
                value = resolved(quantity - quantity_fx + 1)
            case (quantity_fm)
                value = norm2(wrench(1:3))
            case (quantity_tx:quantity_tx + 2)
                value = resolved(quantity - quantity_tx + 4)
            case default
                value = norm2(wrench(4:6))
            end select
            value = value/force_unit
            if (quantity >= quantity_tx) value = value/length_unit
        end if
        errflg = .false.
    end subroutine force_measure

    !> SYSFNC('VARVAL', [id]): the value of VARIABLE/id, served by a VARSUB, as evaluated at the
    !> state of the call (evaluate_user_variables: a run's and rollcon check's evaluations
    !> call the VARSUBs first, a difference call at its shifted state), in its own units. An
    !> initialisation call that reads it declares the VARSUB's markers and rates as its own
    !> (its value depends on them); a VARIABLE no VARSUB serves is refused.
    subroutine variable_measure(ipar, value, errflg)
        integer, intent(in) :: ipar(:)
        real(wp), intent(out) :: value
        logical, intent(out) :: errflg
        integer :: k, m

        value = 0.0_wp
        errflg = .true.
        if (size(ipar) /= 1) then
            call refuse("SYSFNC('VARVAL') with NSIZE = " // to_text(size(ipar)) // ": it " &
                & // "takes one id, the VARIABLE's")
            return
        end if
        k = 0
        if (allocated(variables)) k = findloc(variables%id, ipar(1), dim=1)
        if (k == 0) then
            call refuse("SYSFNC('VARVAL') names VARIABLE/" // to_text(ipar(1)) // ", which " &
                & // "no VARSUB serves (rollcon's SYSFNC answers a VARSUB's VARIABLE; a " &
                & // "routine computes an expression's value itself)")
            return
        end if
        if (declaring) then
            named_variables = .true.
            if (allocated(variables(k)%declared)) then
                do m = 1, size(variables(k)%declared)
                    if (.not. any(named == variables(k)%declared(m))) &
                        & named = [named, variables(k)%declared(m)]
                end do
                named_rates = named_rates .or. variables(k)%declared_rates
                named_accelerations = named_accelerations &
                    & .or. variables(k)%declared_accelerations
            end if
            ! the reactions it reads: the force's values depend on their multipliers
            if (allocated(variables(k)%declared_rows)) then
                if (.not. allocated(named_rows)) named_rows = [integer ::]
                do m = 1, size(variables(k)%declared_rows)
                    if (.not. any(named_rows == variables(k)%declared_rows(m))) &
                        & named_rows = [named_rows, variables(k)%declared_rows(m)]
                end do
            end if
        end if
        value = variables(k)%value
        errflg = .false.
    end subroutine variable_measure

    !> SYSFNC('DIF', [id]) (quantity_dif) or SYSFNC('DIF1', [id]): DIF or DIF1 of DIFF/id
    !> from the state set_system_diff_state gave; the DIFF recorded (a declaration) or
    !> compared with a DIFSUB's declaration (an evaluation).
    subroutine diff_measure(quantity, ipar, value, errflg)
        integer, intent(in) :: quantity, ipar(:)
        real(wp), intent(out) :: value
        logical, intent(out) :: errflg
        character(len=:), allocatable :: call_name
        integer :: k

        value = 0.0_wp
        errflg = .true.
        call_name = "SYSFNC('" // trim(merge("DIF ", "DIF1", quantity == quantity_dif)) // "')"
        if (size(ipar) /= 1) then
            call refuse(call_name // " with NSIZE = " // to_text(size(ipar)) // ": it takes " &
                & // "one id, the DIFF's")
            return
        end if
        k = 0
        if (allocated(diff_ids)) k = findloc(diff_ids, ipar(1), dim=1)
        if (k == 0) then
            call refuse(call_name // " names DIFF/" // to_text(ipar(1)) // ", which the model " &
                & // "has not")
            return
        end if
        if (declaring) then
            if (.not. allocated(named_difs)) named_difs = [integer ::]
            if (.not. allocated(named_dif1s)) named_dif1s = [integer ::]
            if (quantity == quantity_dif .and. .not. any(named_difs == ipar(1))) &
                & named_difs = [named_difs, ipar(1)]
            if (quantity == quantity_dif1 .and. .not. any(named_dif1s == ipar(1))) &
                & named_dif1s = [named_dif1s, ipar(1)]
        else if (allocated(allowed_difs)) then
            if (quantity == quantity_dif .and. .not. any(allowed_difs == ipar(1)) .or. &
                & quantity == quantity_dif1 .and. .not. any(allowed_dif1s == ipar(1))) &
                & call add_note(call_name // " named DIFF/" // to_text(ipar(1)) // ", which " &
                & // "the initialisation call (IFLAG = .TRUE.) did not name")
        end if
        if (quantity == quantity_dif) then
            value = diff_x(k)
        else
            value = diff_w(k)
        end if
        errflg = .false.
    end subroutine diff_measure

    !> SYSARY(FNCNAM, IPAR, NSIZE, STATES, NSTATES, ERRFLG): TDISP(i[, j[, k]]) = (DX, DY, DZ),
    !> TVEL(i[, j[, k[, l]]]) = (VX, VY, VZ), RVEL(i[, j[, k]]) = (WX, WY, WZ) and
    !> RDISP(i[, j]) = (PSI, THETA, PHI), TACC(i[, j[, k[, l]]]) = (ACCX, ACCY, ACCZ) and
    !> RACC(i[, j[, k[, l]]]) = (WDTX, WDTY, WDTZ), in the dataset's units; NSTATES = 3. The
    !> accelerations are those set_system_accelerations gave (system_function). A name rollcon
    !> does not know is refused: ERRFLG set, NSTATES = 0.
    subroutine system_array(name, ipar, states, nstates, errflg)
        character(len=*), intent(in) :: name
        integer, intent(in) :: ipar(:)
        real(wp), intent(out) :: states(3)
        integer, intent(out) :: nstates
        logical, intent(out) :: errflg
        character(len=:), allocatable :: word
        integer :: first, most, c

        states = 0.0_wp
        nstates = 0
        errflg = .true.
        word = upper_case(trim(adjustl(name)))
        select case (word)
        case ("TDISP")
            first = quantity_dx
            most = 3
        case ("TVEL")
            first = quantity_vx
            most = 4
        case ("RVEL")
            first = quantity_wx
            most = 3
        case ("RDISP")
            first = quantity_psi
            most = 2
        case ("TACC")
            first = quantity_accx
            most = 4
        case ("RACC")
            first = quantity_wdtx
            most = 4
        case default
            call refuse("SYSARY('" // trim(name) // "'): not an array rollcon's SYSARY knows " &
                & // "(TDISP, TVEL, RDISP, RVEL, TACC, RACC)")
            return
        end select
        if (size(ipar) < 1 .or. size(ipar) > most) then
            call refuse("SYSARY('" // word // "') with NSIZE = " // to_text(size(ipar)) &
                & // ": it takes 1 to " // to_text(most) // " marker ids")
            return
        end if
        do c = 1, 3
            call measure(first + c - 1, ipar, "SYSARY('" // word // "')", states(c), errflg)
            if (errflg) then
                states = 0.0_wp
                return
            end if
        end do
        nstates = 3
    end subroutine system_array

    !> True for ACCX ... ACCM and WDTX ... WDTM (quantity codes of rollcon_expression).
    elemental logical function is_acceleration(quantity)
        integer, intent(in) :: quantity

        is_acceleration = .false.
        if (quantity < 1 .or. quantity > size(quantity_kind)) return
        is_acceleration = quantity_kind(quantity) == kind_acceleration &
            & .or. quantity_kind(quantity) == kind_angular_acceleration
    end function is_acceleration

    !> The accelerations of all parts [m/s^2, rad/s^2; SI] that SYSARY('TACC'|'RACC') and
    !> SYSFNC('ACCX' ... 'WDTM') answer from until the next call of this (rollcon_equations'
    !> iterates of its algebraic loop, rollcon_dae's u').
    subroutine set_system_accelerations(a)
        real(wp), intent(in) :: a(:)

        a_now = a
    end subroutine set_system_accelerations

    !> The accelerations the utilities answer from [SI] (set_system_accelerations'; zeros of
    !> size n before any).
    function system_accelerations(n) result(a)
        integer, intent(in) :: n
        real(wp) :: a(n)

        a = 0.0_wp
        if (allocated(a_now)) then
            if (size(a_now) == n) a = a_now
        end if
    end function system_accelerations

    !> True when a force of the model is served by a routine whose initialisation call read
    !> accelerations, or a VARSUB's did (variables_read_accelerations): the forces' values
    !> then depend on the accelerations, an algebraic loop (a force routine's directly, an
    !> expression's or routine's through VARVAL).
    pure logical function reads_accelerations(forces)
        type(applied_force_type), intent(in) :: forces(:)
        integer :: i

        reads_accelerations = variables_read_accelerations()
        if (reads_accelerations) return
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine == 0) cycle
            if (forces(i)%statement%declared_accelerations) reads_accelerations = .true.
        end do
    end function reads_accelerations

    !> True when the initialisation call of a VARSUB of the model read accelerations.
    pure logical function variables_read_accelerations() result(reads)
        reads = .false.
        if (.not. allocated(variables)) return
        reads = any(variables%declared_accelerations)
    end function variables_read_accelerations

    !> "VARIABLE/3 (line 12), ...": the VARIABLEs whose VARSUBs read accelerations, for the
    !> messages of the algebraic loop they make ("" for none).
    function variables_reading_accelerations() result(names)
        character(len=:), allocatable :: names
        integer :: v

        names = ""
        if (.not. allocated(variables)) return
        do v = 1, size(variables)
            if (.not. variables(v)%declared_accelerations) cycle
            if (len(names) > 0) names = names // ", "
            names = names // variables(v)%name
        end do
    end function variables_reading_accelerations

    !> The partials of every VARSUB's value in the accelerations a [SI] at (t, q, u, a):
    !> dv_da(v, j) = d VALUE_v/d a(j) [dataset's units per m/s^2, rad/s^2], by central
    !> differences (rollcon_central_differences) over the accelerations of the parts of the
    !> markers its initialisation call named, for the VARSUBs whose initialisation call read
    !> accelerations (the other rows 0); each call with DFLAG = .TRUE. and the shifted
    !> accelerations answered to its SYSARY and SYSFNC calls, those set before restored after.
    !> The values VARVAL reads are left as they were. A failed call leaves its entry 0 and its
    !> error for take_user_force_error.
    subroutine difference_variable_accelerations(time, q, u, a, dv_da)
        real(wp), intent(in) :: time, q(:), u(:), a(:)
        real(wp), intent(out) :: dv_da(:, :)
        real(wp), allocatable :: kept(:), block(:, :)
        integer, allocatable :: entries(:), parts(:)
        integer :: v, k, c

        dv_da = 0.0_wp
        if (.not. allocated(variables)) return
        if (allocated(a_now)) then
            kept = a_now
        else
            allocate(kept(size(a)), source=0.0_wp)
        end if
        do v = 1, size(variables)
            if (.not. variables(v)%declared_accelerations) cycle
            parts = parts_of(variables(v)%declared)
            entries = [((6*(parts(k) - 1) + c, c = 1, 6), k = 1, size(parts))]
            if (size(entries) == 0) cycle
            allocate(block(size(entries), 1), source=0.0_wp)
            call central_differences(a, entries, accelerations_moved, block)
            dv_da(v, entries) = block(:, 1)
            deallocate(block)
        end do
        a_now = kept

    contains

        subroutine accelerations_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            a_now = shifted
            call variable_call(variables(v), time, q, u, .true., values(1), failed)
        end subroutine accelerations_moved

    end subroutine difference_variable_accelerations

    !> difference_call at (t, q, u) with the accelerations a [SI] its SYSARY and SYSFNC calls
    !> read; the accelerations set before are restored after it.
    subroutine acceleration_difference_call(force, time, q, u, a, values, failed)
        type(applied_force_type), intent(in) :: force
        real(wp), intent(in) :: time, q(:), u(:), a(:)
        real(wp), intent(out) :: values(6)
        logical, intent(out) :: failed
        real(wp), allocatable :: kept(:)

        if (allocated(a_now)) then
            kept = a_now
        else
            allocate(kept(size(a)), source=0.0_wp)
        end if
        a_now = a
        call difference_call(force, time, q, u, values, failed)
        a_now = kept
    end subroutine acceleration_difference_call

    !> TIMGET(TIME): the time of the call, in the dataset's unit.
    function system_time() result(time)
        real(wp) :: time

        time = time_now/time_unit
    end function system_time

    !> A measure of markers ipar at the call's state in the dataset's units; the markers named
    !> recorded (a declaration) or compared with the declaration (an evaluation).
    subroutine measure(quantity, ipar, call_name, value, errflg)
        integer, intent(in) :: quantity, ipar(:)
        character(len=*), intent(in) :: call_name
        real(wp), intent(out) :: value
        logical, intent(out) :: errflg
        type(marker_type) :: chosen(4)
        integer :: ids(4), m, s
        logical :: found
        real(wp) :: scale

        value = 0.0_wp
        errflg = .true.
        ! outside a call (no model set): no marker is known
        if (.not. allocated(markers)) allocate(markers(0))
        ids = 0
        ids(:size(ipar)) = ipar
        ! VM, VR, ACCM, WDTM are written (i, j, l)
        if (any(quantity == [quantity_vm, quantity_vr, quantity_accm, quantity_wdtm])) &
            & ids = [ids(1), ids(2), 0, ids(3)]
        do m = 1, 4
            chosen(m) = marker_type()
            if (ids(m) == 0) cycle
            found = .false.
            do s = 1, size(markers)
                if (markers(s)%id /= ids(m)) cycle
                chosen(m) = markers(s)
                found = .true.
                exit
            end do
            if (.not. found) then
                call refuse(call_name // " names marker " // to_text(ids(m)) &
                    & // ", which the model has not")
                return
            end if
        end do
        if (ids(1) == 0) then
            call refuse(call_name // ": IPAR(1) must name a marker, got 0")
            return
        end if
        if (is_acceleration(quantity) .and. motion_calling) then
            ! a MOTSUB's call: recorded, and refused by call_user_motion (ADAMS's rule)
            call note_reads(ids, .true., call_name, accelerations=.true.)
            errflg = .false.
            return
        else if (is_acceleration(quantity)) then
            call note_reads(ids, .true., call_name, accelerations=.true.)
            if (.not. allocated(a_now)) allocate(a_now(size(u_now)), source=0.0_wp)
            if (size(a_now) /= size(u_now)) a_now = [(0.0_wp, m = 1, size(u_now))]
            value = acceleration_measure(quantity, chosen, q_now, u_now, a_now)*time_unit**2
            if (quantity_kind(quantity) == kind_acceleration) value = value/length_unit
            errflg = .false.
            return
        end if
        call note_reads(ids, reads_rates(quantity), call_name)
        scale = 1.0_wp
        if (quantity < quantity_psi) scale = 1.0_wp/length_unit
        if (quantity < quantity_psi .and. quantity >= quantity_wx) scale = time_unit
        if (quantity < quantity_wx .and. quantity >= quantity_vx) scale = time_unit/length_unit
        if (quantity > quantity_psi + 2) scale = quantity_scale(quantity, length_unit, time_unit)
        value = scale*measure_value(quantity, chosen, q_now, u_now, 0.0_wp)
        errflg = .false.
    end subroutine measure

    !> Record the markers and rates a call reads (initialisation), or note what it reads that
    !> its initialisation call did not name (an evaluation: ADAMS would leave it out of the
    !> force's dependencies).
    subroutine note_reads(ids, rates, call_name, accelerations)
        integer, intent(in) :: ids(4)
        logical, intent(in) :: rates
        character(len=*), intent(in) :: call_name
        !> The call reads accelerations (absent: not)
        logical, intent(in), optional :: accelerations
        integer :: m
        logical :: reads_a

        reads_a = .false.
        if (present(accelerations)) reads_a = accelerations
        if (declaring) then
            do m = 1, 4
                if (ids(m) == 0) cycle
                if (.not. any(named == ids(m))) named = [named, ids(m)]
            end do
            named_rates = named_rates .or. rates
            named_accelerations = named_accelerations .or. reads_a
            return
        end if
        if (.not. allocated(allowed)) return
        do m = 1, 4
            if (ids(m) == 0) cycle
            if (any(allowed == ids(m))) cycle
            call add_note(call_name // " named marker " // to_text(ids(m)) // ", which the " &
                & // "initialisation call (IFLAG = .TRUE.) did not name")
        end do
        if (rates .and. .not. allowed_rates) call add_note(call_name // " read velocities, " &
            & // "which the initialisation call (IFLAG = .TRUE.) did not read")
        if (reads_a .and. .not. allowed_accelerations) call add_note(call_name // " read " &
            & // "accelerations, which the initialisation call (IFLAG = .TRUE.) did not read")
    end subroutine note_reads

    !> A utility refuses a call: ERRFLG is set, and the call's error says why.
    subroutine refuse(why)
        character(len=*), intent(in) :: why

        if (.not. allocated(problem)) problem = ""
        if (len(problem) == 0) problem = why
        call add_note(why)
    end subroutine refuse

    !> A note for rollcon check, each once.
    subroutine add_note(text)
        character(len=*), intent(in) :: text

        if (.not. allocated(notes)) notes = ""
        if (index(notes, text // new_line("a")) > 0) return
        notes = notes // text // new_line("a")
    end subroutine add_note


end module rollcon_user_forces
