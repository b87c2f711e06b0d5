! SPDX-License-Identifier: MIT
!> A dataset as a problem to simulate (docs/datasets-model.md): its parts (ground is not one),
!> UCONs with their routines, gravity, force statements between body-fixed markers, solver
!> settings, the theta limit, the requests' columns and the initial state.
!>
!> A part's principal axes are its CM marker's axes, and its inertia is the IP written there
!> (docs/design.md §2); an IP with products gives principal axes turned from the CM marker's
!> (rollcon_inertia_axes), in which the part moves and its markers are held. A UCON is served
!> by the built-in routine its ROUTINE= names (rollcon_ucosub_catalog), else by the model's
!> routine (the `--ucosub` one: rollcon_model's served_by_model_ucosub). A JOINT or JPRIM is
!> model%add_joint or model%add_jprim between its markers as the model holds them
!> (rollcon_adm_markers). As ADAMS does, a routine, built-in or the user's, computes in the
!> dataset's units: PAR as written, the state and the time converted at the boundary
!> (rollcon_ucosub_units).
module rollcon_adm_build
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, fatal_error, stat_input, stat_ucon
    use rollcon_text, only : to_text, place
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_units, only : ucosub_units_type
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names, &
        & builtin_ucosubs_for_par, builtin_ucosub_name
    use rollcon_marker, only : marker_type
    use rollcon_rotation, only : rotation_matrix
    use rollcon_body, only : part_type
    use rollcon_marker_force, only : kind_translation, kind_rotation, kind_vector, &
        & kind_general, kind_spring, marker_force_values, markers_coincide
    use rollcon_force, only : applied_force_type, profile_statement, force_couplings
    use rollcon_user_forces, only : routine_kind_of, set_system_markers, &
        & declare_user_force, evaluate_user_forces, take_user_force_error, set_system_splines, &
        & user_variable_type, set_user_variables, declare_user_variables, evaluate_user_variables, &
        & set_system_constraint_forces, declare_variable_rows
    use rollcon_user_forces, only : user_motion_type, set_user_motions
    use rollcon_system_routine_contract, only : routine_varsub, variable_routine_name, &
        & routine_difsub, diff_routine_name
    use rollcon_user_data, only : user_string_type, user_array_type, set_user_data
    use rollcon_system_routine_contract, only : routine_motsub, motion_routine_name
    use rollcon_spline, only : spline_type, new_spline
    use rollcon_force_routine_contract, only : routine_names
    use rollcon_user_ucosubs, only : find_named_routine, find_named_ucosub, bind_user_ucon, &
        & user_ucosub_entry, user_ucosub_files, find_user_ucosub, mark_user_ucosub_used, &
        & user_ucosub_unused, is_library_routine
    use rollcon_model, only : model_type, setup_model, served_by_model_ucosub, force_request_type
    use rollcon_problem, only : problem_type
    use rollcon_theta_watch, only : new_theta_watch
    use rollcon_request_watch, only : displacement_request_type, new_request_watch
    use rollcon_variable_watch, only : watched_variable_type, new_variable_watch
    use rollcon_motion_watch, only : motion_watch_type
    use rollcon_diff_watch, only : diff_watch_type
    use rollcon_expression, only : quantity_dif1
    use rollcon_element_force_watch, only : element_force_watch_type, watches_elements
    use rollcon_adm_requests, only : add_request_answers
    use rollcon_adm_model, only : adm_model_type, adm_force_type, force_sforce, force_vforce, &
        & force_springdamper, force_bushing, force_names, request_user
    use rollcon_spring_force, only : spring_translational, spring_rotational, spring_bushing
    use rollcon_adm_system, only : adm_diff_type
    use rollcon_adm_state, only : part_state
    use rollcon_adm_singular, only : start_singular_parts
    use rollcon_adm_contact, only : contact_shape_type, add_contact_ucons, add_contact_watch
    use rollcon_adm_markers, only : adm_marker, marker_index
    use rollcon_adm_constraints, only : add_expression_constraints, expression_markers
    use rollcon_adm_motions, only : motion_velocity_form, motion_acceleration_form
    use rollcon_motion, only : take_motion_error, motion_highest_order
    use rollcon_motion, only : motion_type, prepare_motion, motion_form_displacement, &
        & motion_form_velocity, motion_form_acceleration
    use rollcon_motion_geometry, only : motion_x, motion_y, motion_z, motion_b1, motion_b2, &
        & motion_b3, motion_rotation
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: build_adm_problem, adm_theta_min

    !> The theta limit of every part of a dataset's model [rad]: a run re-bases a part whose
    !> principal axes come this close to the Euler-angle singularity (theta = 0 or pi), the
    !> namelist scenes' default theta_min (a dataset has no key for it; docs/rebasing.md)
    real(wp), parameter :: adm_theta_min = 0.05_wp
    !> Names of the expression slots of each kind of force statement
    character(len=*), parameter :: slot_names(6) = [character(len=2) :: "FX", "FY", "FZ", &
        & "TX", "TY", "TZ"]

contains

    !> The problem of a dataset, set up in place, and its initial state.
    subroutine build_adm_problem(adm, default_ucosub, problem, q0, u0, error)
        !> The dataset, read and checked (rollcon_adm_reader)
        type(adm_model_type), intent(in) :: adm
        !> The routine serving every UCON that names no ROUTINE (ADAMS's one UCOSUB per model);
        !> absent or null: each UCON must name one
        procedure(ucosub_interface), pointer, intent(in), optional :: default_ucosub
        !> Set up in place: its equations refer to its model
        type(problem_type), intent(inout), target :: problem
        !> Coordinates and rates of all parts, in model order [m, rad, m/s, rad/s]
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        procedure(ucosub_interface), pointer :: fallback
        type(contact_shape_type), allocatable :: contact(:)
        integer, allocatable :: contact_rows(:, :)
        integer :: i, p

        fallback => null()
        if (present(default_ucosub)) fallback => default_ucosub
        allocate(model%parts(0), model%ucons(0), model%forces(0))
        do i = 1, size(adm%parts)
            if (adm%parts(i)%ground) cycle
            call model%add_part(part_type(id=adm%parts(i)%id, mass=adm%parts(i)%mass, &
                & inertia=adm%parts(i)%ip))
        end do
        ! every UCOSUB, built-in or the user's, computes in the dataset's units, as in ADAMS
        model%ucosub_units = ucosub_units_type(length=adm%units%length, time=adm%units%time)
        ! the UCONs, contacts and joints added with the model's arrays grown by doubling
        ! (model%open_additions: linear in their number), closed before anything reads them
        call model%open_additions()
        call add_ucons(adm, fallback, model, error)
        ! each CONTACT's no-slip rows, right after the UCONs (rollcon_adm_contact)
        if (.not. allocated(error)) call add_contact_ucons(adm, model, contact, contact_rows, &
            & error)
        if (.not. allocated(error)) call add_joints(adm, model, error)
        call model%close_additions()
        if (allocated(error)) return
        allocate(q0(6*size(model%parts)), u0(6*size(model%parts)))
        p = 0
        do i = 1, size(adm%parts)
            if (adm%parts(i)%ground) cycle
            p = p + 1
            call part_state(adm, adm%parts(i), q0(6*p - 5:6*p), u0(6*p - 5:6*p))
        end do
        ! GCONs and couplings, the latter measured from this start
        call add_expression_constraints(adm, model, q0, u0, error)
        if (allocated(error)) return
        call add_motions(adm, model, error)
        if (allocated(error)) return
        ! the VARIABLEs served by VARSUBs, valued before the forces that read them
        call add_user_variables(adm, error)
        if (allocated(error)) return
        do i = 1, size(adm%forces)
            call add_force_statement(adm, adm%forces(i), model, error)
            if (allocated(error)) return
        end do
        call add_diffs(adm, model, error)
        if (allocated(error)) return
        model%gravity = adm%gravity
        ! the routine of the UCONs that name none (ADAMS's one UCOSUB per model)
        model%ucosub => fallback
        call setup_model(model, error)
        if (allocated(error)) then
            call add_routine_hint(adm, fallback, error)
            return
        end if
        call problem%init(model)
        problem%settings = adm%run%settings
        ! a dataset's parts are re-based at the theta limit, not stopped (docs/rebasing.md)
        call problem%add_watch(new_theta_watch(adm_theta_min, rebase=.true.))
        if (allocated(adm%requests)) then
            if (size(adm%requests) > 0) call problem%add_watch(new_request_watch( &
                & displacement_requests(adm)))
        end if
        ! each MOTION's force or torque, a column (rollcon_motion_watch)
        if (allocated(adm%motions)) then
            if (size(adm%motions) > 0) call problem%add_watch(motion_watch_type())
        end if
        ! each VARIABLE's value, a column (rollcon_variable_watch)
        call add_variable_watch(adm, problem, error)
        if (allocated(error)) return
        ! each DIFF's DIF and DIF1, two columns (rollcon_diff_watch)
        if (problem%model%diffs%count() > 0) call problem%add_watch(diff_watch_type())
        ! each SPRINGDAMPER's and BUSHING's force and torque, six columns
        ! (rollcon_element_force_watch)
        if (watches_elements(problem%eq)) call problem%add_watch(element_force_watch_type())
        ! the other requests: velocity, acceleration, force, F1 ... F8 (rollcon_request_answers)
        call add_request_answers(adm, problem, error)
        if (allocated(error)) return
        ! a part flat at t = 0 starts in turned axes (docs/rebasing.md): its model part too
        call start_singular_parts(adm, problem, q0, u0, adm_theta_min, error)
        if (allocated(error)) return
        ! each CONTACT's modes, from this start (rollcon_adm_contact)
        call add_contact_watch(adm, contact, contact_rows, problem, q0, u0, error)
        if (allocated(error)) return
        call declare_user_forces(adm, problem, q0, u0, error)
        if (allocated(error)) return
        call check_forces_at_start(adm, problem, q0, u0, error)
    end subroutine build_adm_problem

    !> A column for each VARIABLE of the dataset (none without them), its markers as the model
    !> holds them.
    subroutine add_variable_watch(adm, problem, error)
        type(adm_model_type), intent(in) :: adm
        type(problem_type), intent(inout) :: problem
        type(error_type), allocatable, intent(out) :: error
        type(watched_variable_type), allocatable :: variables(:)
        integer :: k

        if (.not. allocated(adm%variables)) return
        if (size(adm%variables) == 0) return
        allocate(variables(size(adm%variables)))
        do k = 1, size(adm%variables)
            variables(k)%id = adm%variables(k)%id
            variables(k)%function = adm%variables(k)%function
            call expression_markers(adm, variables(k)%function, place(adm%file, &
                & adm%variables(k)%line) // ": VARIABLE/" // to_text(adm%variables(k)%id) &
                & // " FUNCTION", "a VARIABLE's FUNCTION", variables(k)%markers, error)
            if (allocated(error)) return
        end do
        call problem%add_watch(new_variable_watch(variables, adm%units%length, adm%units%time))
    end subroutine add_variable_watch

    !> The dataset's REQUEST/id, DISPLACEMENT statements with their markers as the model holds
    !> them; a J or RM not given is a marker at the ground origin with ground axes.
    function displacement_requests(adm) result(requests)
        type(adm_model_type), intent(in) :: adm
        type(displacement_request_type) :: requests(size(adm%requests))
        integer :: k

        do k = 1, size(adm%requests)
            requests(k)%id = adm%requests(k)%id
            requests(k)%i = adm_marker(adm, adm%requests(k)%i)
            if (adm%requests(k)%j /= 0) requests(k)%j = adm_marker(adm, adm%requests(k)%j)
            if (adm%requests(k)%rm /= 0) requests(k)%rm = adm_marker(adm, adm%requests(k)%rm)
        end do
    end function displacement_requests

    !> The initialisation call (IFLAG = .TRUE.) of every force's user routine at the start,
    !> which declares what it reads (rollcon_user_forces), then a first evaluation there, whose
    !> values check_forces_at_start reads. The markers SYSFNC and SYSARY may name are every
    !> marker of the dataset. The equations' couplings are found again with the declared
    !> parts (rollcon_force's force_couplings).
    subroutine declare_user_forces(adm, problem, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        type(problem_type), intent(inout) :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(marker_type), allocatable :: markers(:)
        integer :: i
        logical :: user_forces, user_requests, user_variables, user_diffs

        user_forces = .false.
        if (allocated(adm%forces)) user_forces = any(adm%forces%user)
        user_requests = .false.
        if (allocated(adm%other_requests)) user_requests = any(adm%other_requests%kind &
            & == request_user)
        user_variables = .false.
        if (allocated(adm%variables)) user_variables = any(adm%variables%user)
        user_diffs = .false.
        if (allocated(adm%diffs)) user_diffs = any(adm%diffs%user)
        if (.not. (user_forces .or. user_requests .or. user_variables .or. user_diffs)) return
        allocate(markers(size(adm%markers)))
        do i = 1, size(adm%markers)
            markers(i) = adm_marker(adm, adm%markers(i)%id)
        end do
        call set_system_markers(markers, adm%units%length, adm%units%time, adm%units%force)
        call give_splines(adm)
        call give_user_data(adm)
        ! the constraint rows at the start, which SYSFNC's force measures read a JOINT's
        ! reaction from in the initialisation calls (with no multipliers yet: the equations
        ! set them at every evaluation)
        call problem%eq%constraint_matrix_at(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        call set_system_constraint_forces(problem%eq%c, [(0.0_wp, i = 1, problem%eq%nc)])
        ! the VARSUBs first: a force may read their values
        if (user_variables) then
            call declare_user_variables(0.0_wp, q0, u0, error)
            if (allocated(error)) return
            call evaluate_user_variables(0.0_wp, q0, u0)
            call take_user_force_error(error)
            if (allocated(error)) return
            ! the parts a VARSUB declared join those of the forces that read its VARVAL, the
            ! reactions it read the expressions' declared rows
            if (allocated(problem%model%forces)) &
                & call declare_variable_rows(problem%model%forces)
            problem%eq%couplings = force_couplings(problem%model%forces)
        end if
        ! the DIFSUBs' declarations, at the DIFFs' ICs
        if (user_diffs) then
            call problem%model%diffs%declare_routines(0.0_wp, q0, u0, error)
            if (allocated(error)) return
        end if
        ! a REQSUB's calls come at the output rows (rollcon_request_answers)
        if (.not. user_forces) return
        do i = 1, size(problem%model%forces)
            if (problem%model%forces(i)%profile /= profile_statement) cycle
            if (problem%model%forces(i)%statement%routine == 0) cycle
            call declare_user_force(problem%model%forces(i), 0.0_wp, q0, u0, error)
            if (allocated(error)) return
        end do
        ! the declared parts join the parts each force loads in the Newton matrices' patterns
        problem%eq%couplings = force_couplings(problem%model%forces)
        call evaluate_user_forces(problem%model%forces, 0.0_wp, q0, u0)
        call take_user_force_error(error)
    end subroutine declare_user_forces

    !> Every force expression finite at the start (t = 0): a NaN or infinity there (a LOG of a
    !> negative number, a division by zero) is refused with the statement and key, not left for
    !> the integrator to fail on.
    subroutine check_forces_at_start(adm, problem, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        type(problem_type), intent(in) :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: values(6)
        character(len=:), allocatable :: key, name
        integer :: i, k

        do i = 1, size(adm%forces)
            name = trim(force_names(adm%forces(i)%kind))
            if (markers_coincide(problem%model%forces(i)%statement, q0)) then
                call fatal_error(error, place(adm%file, adm%forces(i)%line) // ": " // name &
                    & // "/" // to_text(adm%forces(i)%id) // ": its I and J markers are at one " &
                    & // "point at the start, where a translational " // name // "'s line of " &
                    & // "action (from J to I) is not defined; move one of them, or give the " &
                    & // "force as a VFORCE", stat_input)
                return
            end if
            values = marker_force_values(problem%model%forces(i)%statement, 0.0_wp, q0, u0)
            do k = 1, 6
                if (ieee_is_finite(values(k))) cycle
                key = slot_names(k)
                if (adm%forces(i)%kind == force_sforce) key = "FUNCTION"
                call fatal_error(error, place(adm%file, adm%forces(i)%line) // ": " &
                    & // name // "/" // to_text(adm%forces(i)%id) // " " &
                    & // key // ": the expression is not finite at t = 0 (" &
                    & // to_text(values(k)) // "): a function outside its domain, or a " &
                    & // "division by zero", stat_input)
                return
            end do
        end do
    end subroutine check_forces_at_start

    !> Each UCON with its routine: the built-in one ROUTINE=name names, else the user's
    !> subroutine ROUTINE=library::name names (any subroutine with UCOSUB's calling sequence
    !> in the `--ucosub` file library: rollcon_user_ucosubs), else the model's (none given, or
    !> several user files defining UCOSUB: refused). Refused too: a user file's UCOSUB that
    !> serves no UCON (a constraint given and not applied).
    subroutine add_ucons(adm, fallback, model, error)
        type(adm_model_type), intent(in) :: adm
        procedure(ucosub_interface), pointer, intent(in) :: fallback
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine
        character(len=:), allocatable :: files, unused
        logical :: time_free, found
        integer :: k, entry, defining

        call user_ucosub_files(files, defining)
        do k = 1, size(adm%ucons)
            associate (ucon => adm%ucons(k))
                if (served_by_model_ucosub(ucon%routine)) then
                    if (defining > 1) then
                        call fatal_error(error, place(adm%file, ucon%line) // ": UCON/" &
                            & // to_text(ucon%id) // " names no ROUTINE, and several files " &
                            & // "given define UCOSUB (" // files // "): name the one that " &
                            & // "serves it, ROUTINE=FILE::UCOSUB (FILE as given, or its name " &
                            & // "without folder and extension)", stat_input)
                        return
                    end if
                    if (.not. associated(fallback)) then
                        call fatal_error(error, place(adm%file, ucon%line) // ": UCON/" &
                            & // to_text(ucon%id) // ": no UCOSUB serves this UCON: name a " &
                            & // "built-in routine with ROUTINE=name (" // builtin_ucosub_names() &
                            & // ") or give the model's UCOSUB (rollcon run MODEL.adm --ucosub " &
                            & // "FILE|NAME)", stat_input)
                        return
                    end if
                    call mark_user_ucosub_used(find_user_ucosub(""))
                    call model%add_ucon(ucon%id, ucon%par, line=ucon%line)
                    cycle
                end if
                call find_builtin_ucosub(trim(ucon%routine), routine, time_free, found)
                if (found) then
                    call model%add_ucon(ucon%id, ucon%par, routine, time_free=time_free, &
                        & routine=trim(ucon%routine), line=ucon%line)
                    cycle
                end if
                entry = find_named_ucosub(trim(ucon%routine))
                if (entry == 0) then
                    if (is_library_routine(ucon%routine)) then
                        call fatal_error(error, ucon%routine_at // ": '" // trim(ucon%routine) &
                            & // "' is neither a built-in UCOSUB (" // builtin_ucosub_names() &
                            & // ") nor a subroutine of a user's file: ROUTINE=FILE::NAME " &
                            & // "names the subroutine NAME, with UCOSUB's calling sequence, " &
                            & // "of FILE given with rollcon run MODEL.adm --ucosub FILE (FILE " &
                            & // "as given, or its name without folder and extension)", &
                            & stat_input)
                    else
                        call fatal_error(error, ucon%routine_at // ": '" // trim(ucon%routine) &
                            & // "' is not a built-in UCOSUB (" // builtin_ucosub_names() &
                            & // "); a routine of your own is named ROUTINE=FILE::NAME, FILE " &
                            & // "given with rollcon run MODEL.adm --ucosub FILE", stat_input)
                    end if
                    return
                end if
                ! the user's routine runs behind the entry point (a child's guard), which
                ! finds it by the UCON's id
                call bind_user_ucon(ucon%id, entry)
                call user_ucosub_entry(routine)
                call model%add_ucon(ucon%id, ucon%par, routine, time_free=.false., &
                    & routine=trim(ucon%routine), line=ucon%line)
            end associate
        end do
        unused = user_ucosub_unused()
        if (len(unused) > 0) then
            call fatal_error(error, adm%file // ": " // unused // " defines a UCOSUB that " &
                & // "serves no UCON of the model (a constraint given and not applied): a UCON " &
                & // "names it with ROUTINE=" // library_name(unused) // "::UCOSUB, or one " &
                & // "naming no ROUTINE takes it when it is the only file defining UCOSUB; " &
                & // "leave the file out if the model does not use it", stat_input)
            return
        end if
    contains
        !> A file's name without folder and extension
        function library_name(path) result(stem)
            character(len=*), intent(in) :: path
            character(len=:), allocatable :: stem
            integer :: dot

            stem = path(index(path, "/", back=.true.) + 1:)
            dot = index(stem, ".", back=.true.)
            if (dot > 1) stem = stem(:dot - 1)
        end function library_name
    end subroutine add_ucons

    !> Each JOINT and JPRIM, in the order of the file, between its markers as the model holds
    !> them: its UCONs after the dataset's (model%add_joint, model%add_jprim). A refusal names
    !> the statement's line. A CONVEL whose markers' z axes start less than 90 degrees apart is
    !> refused: they point along its two shafts away from the joint's centre (ADAMS's rule),
    !> opposite when the shafts are in line, and with the axes the other way its equation
    !> turns the shafts in opposite senses and vanishes to first order when they come in line
    !> (ucon/specs/_joint.py). A REQUEST/id, FORCE answered by a joint's reaction
    !> (adm%force_requests) becomes one of model%force_requests, naming the joint's statement.
    subroutine add_joints(adm, model, error)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: cosine
        integer, allocatable :: statements(:)
        integer :: k

        allocate(model%force_requests(0))
        if (.not. allocated(adm%joints)) return
        allocate(statements(size(adm%joints)), source=0)
        do k = 1, size(adm%joints)
            associate (joint => adm%joints(k))
                ! a RACKPIN or SCREW couples motions: rollcon_adm_constraints
                if (joint%kind == "RACKPIN" .or. joint%kind == "SCREW") cycle
                if (.not. joint%primitive .and. joint%kind == "CONVEL") then
                    cosine = dot_product(start_z_axis(adm, joint%i), start_z_axis(adm, joint%j))
                    if (cosine >= 0.0_wp) then
                        call fatal_error(error, place(adm%file, joint%line) // ": JOINT/" &
                            & // to_text(joint%id) // ": a CONVEL's markers' z axes point " &
                            & // "along its two shafts, away from the joint's centre (opposite " &
                            & // "when the shafts are in line), but at the start I's (MARKER/" &
                            & // to_text(joint%i) // ") and J's (MARKER/" // to_text(joint%j) &
                            & // ") are " // to_text(nint(acos(min(cosine, 1.0_wp))*180.0_wp &
                            & /pi)) // " degrees apart, more than 90 degrees from opposite: turn " &
                            & // "one of them half a turn about its x axis", stat_input)
                        return
                    end if
                end if
                if (joint%primitive) then
                    call model%add_jprim(joint%id, joint%kind, adm_marker(adm, joint%i), &
                        & adm_marker(adm, joint%j), error, line=joint%line)
                else
                    call model%add_joint(joint%id, joint%kind, adm_marker(adm, joint%i), &
                        & adm_marker(adm, joint%j), error, line=joint%line)
                end if
                if (allocated(error)) then
                    error%message = place(adm%file, joint%line) // ": " // error%message
                    return
                end if
                statements(k) = model%statement_count()
            end associate
        end do
        if (.not. allocated(adm%force_requests)) return
        do k = 1, size(adm%force_requests)
            associate (request => adm%force_requests(k))
                model%force_requests = [model%force_requests, force_request_type(id=request%id, &
                    & statement=statements(request%joint), swapped=request%swapped)]
            end associate
        end do
    end subroutine add_joints

    !> Each MOTION, in the order of the file: a UCON with its time part (model%add_motion), after
    !> the joints' UCONs. On a joint, its markers are the joint's: TRANSLATION drives a
    !> TRANSLATIONAL or CYLINDRICAL joint along J's z axis, ROTATION a REVOLUTE or CYLINDRICAL
    !> one about it; between markers, X, Y, Z, B1, B2, B3 (rollcon_motion_geometry). The
    !> function's integrals (VELOCITY, ACCELERATION) are anchored over the run's span
    !> (prepare_motion). A MOTION of FUNCTION=USER(...) is served by a MOTSUB (add_user_motions).
    !> A refusal names the statement's line.
    subroutine add_motions(adm, model, error)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        type(motion_type) :: motion
        character(len=:), allocatable :: where
        integer :: k, i, j, component, joint
        real(wp) :: horizon

        if (.not. allocated(adm%motions)) return
        call add_user_motions(adm, error)
        if (allocated(error)) return
        horizon = adm%run%settings%end_time
        do k = 1, size(adm%motions)
            associate (statement => adm%motions(k))
                where = place(adm%file, statement%line) // ": MOTION/" // to_text(statement%id)
                i = statement%i
                j = statement%j
                select case (statement%component)
                case ("X")
                    component = motion_x
                case ("Y")
                    component = motion_y
                case ("Z")
                    component = motion_z
                case ("B1")
                    component = motion_b1
                case ("B2")
                    component = motion_b2
                case ("B3")
                    component = motion_b3
                case default
                    joint = findloc(adm%joints%id, statement%joint, dim=1, &
                        & mask=.not. adm%joints%primitive)
                    associate (kind => adm%joints(joint)%kind)
                        if (statement%component == "TRANSLATION" .and. all(kind /= &
                            & [character(len=13) :: "TRANSLATIONAL", "CYLINDRICAL"])) then
                            call fatal_error(error, where // ": JOINT/" &
                                & // to_text(statement%joint) // " is " // kind // "; a " &
                                & // "TRANSLATION drives a TRANSLATIONAL or CYLINDRICAL joint " &
                                & // "(along its z axis)", stat_input)
                            return
                        end if
                        if (statement%component == "ROTATION" .and. all(kind /= &
                            & [character(len=11) :: "REVOLUTE", "CYLINDRICAL"])) then
                            call fatal_error(error, where // ": JOINT/" &
                                & // to_text(statement%joint) // " is " // kind // "; a " &
                                & // "ROTATION drives a REVOLUTE or CYLINDRICAL joint (about " &
                                & // "its z axis)", stat_input)
                            return
                        end if
                    end associate
                    component = merge(motion_z, motion_rotation, &
                        & statement%component == "TRANSLATION")
                    i = adm%joints(joint)%i
                    j = adm%joints(joint)%j
                end select
                motion = motion_type(id=statement%id, name=where, function=statement%function, &
                    & form=motion_form(statement%form), time_unit=adm%units%time, &
                    & initial_displacement=statement%initial_displacement, &
                    & initial_velocity=statement%initial_velocity)
                if (any(component == [motion_x, motion_y, motion_z])) &
                    & motion%value_unit = adm%units%length
                motion%user = statement%user
                call prepare_motion(motion, horizon)
                ! a MOTSUB's VELOCITY or ACCELERATION called for the anchors of its integrals
                call take_motion_error(error)
                if (allocated(error)) return
                call model%add_motion(motion, component, statement%joint /= 0, &
                    & adm_marker(adm, i), adm_marker(adm, j), error, line=statement%line)
                if (allocated(error)) return
            end associate
        end do
    end subroutine add_motions

    !> The dataset's MOTIONs served by MOTSUBs (FUNCTION=USER), each with the entry of its
    !> routine (the model's own MOTSUB, or the one its ROUTINE= names), given to
    !> rollcon_user_forces with the markers SYSFNC and SYSARY may name (a MOTSUB that reads one
    !> is refused there, naming what it read); refused, naming the MOTION and its line, when no
    !> file serves it.
    subroutine add_user_motions(adm, error)
        type(adm_model_type), intent(in) :: adm
        type(error_type), allocatable, intent(out) :: error
        type(user_motion_type), allocatable :: list(:)
        type(marker_type), allocatable :: markers(:)
        character(len=:), allocatable :: where, routine
        integer :: k, n

        allocate(list(count(adm%motions%user)))
        if (size(list) == 0) return
        n = 0
        do k = 1, size(adm%motions)
            if (.not. adm%motions(k)%user) cycle
            n = n + 1
            where = place(adm%file, adm%motions(k)%line) // ": MOTION/" &
                & // to_text(adm%motions(k)%id)
            routine = ""
            if (allocated(adm%motions(k)%routine)) routine = adm%motions(k)%routine
            list(n)%id = adm%motions(k)%id
            list(n)%par = adm%motions(k)%par
            list(n)%name = where
            list(n)%highest = motion_highest_order(motion_form(adm%motions(k)%form))
            list(n)%routine = find_named_routine(routine_motsub, routine)
            if (list(n)%routine > 0) cycle
            if (len(routine) == 0) then
                call fatal_error(error, where // " FUNCTION=USER(...): no " &
                    & // motion_routine_name // " serves it; give the file that defines " &
                    & // "SUBROUTINE " // motion_routine_name // " (rollcon run MODEL " &
                    & // "--ucosub FILE; it runs in a process of its own)", stat_input)
            else
                call fatal_error(error, where // " ROUTINE=" // routine // ": no " &
                    & // motion_routine_name // " of that name among the user's files; " &
                    & // "ROUTINE=FILE::" // motion_routine_name // " names the routine " &
                    & // "of FILE (given with --ucosub FILE; FILE as given, or its name " &
                    & // "without folder and extension)", stat_input)
            end if
            return
        end do
        call set_user_motions(list, adm%units%time)
        allocate(markers(size(adm%markers)))
        do k = 1, size(adm%markers)
            markers(k) = adm_marker(adm, adm%markers(k)%id)
        end do
        call set_system_markers(markers, adm%units%length, adm%units%time, adm%units%force)
    end subroutine add_user_motions

    !> rollcon_motion's code of a MOTION's form as the reader gives it (rollcon_adm_motions).
    pure integer function motion_form(form)
        integer, intent(in) :: form

        motion_form = motion_form_displacement
        if (form == motion_velocity_form) motion_form = motion_form_velocity
        if (form == motion_acceleration_form) motion_form = motion_form_acceleration
    end function motion_form

    !> The z axis in ground of marker `id` at the start: its part's frame (PART's REULER)
    !> turned by its own REULER.
    function start_z_axis(adm, id) result(axis)
        type(adm_model_type), intent(in) :: adm
        !> Marker id (it exists: the reader checked the references)
        integer, intent(in) :: id
        real(wp) :: axis(3), turned(3, 3)
        integer :: m, p

        m = marker_index(adm, id)
        p = findloc(adm%parts%id, adm%markers(m)%part, dim=1)
        associate (part => adm%parts(p)%reuler, marker => adm%markers(m)%reuler)
            turned = matmul(rotation_matrix(part(1), part(2), part(3)), &
                & rotation_matrix(marker(1), marker(2), marker(3)))
        end associate
        axis = turned(:, 3)
    end function start_z_axis

    !> An error of a UCON that names no ROUTINE, from the model's UCOSUB that served it (a
    !> forgotten --ucosub leaves rollcon's hand-checked disk serving another routine's PAR):
    !> the message adds which routine served it and which built-in routines its PAR suits, or
    !> where a routine is chosen. Nothing is added when the routine that served it is one of
    !> those its PAR suits (the error is then in a value, not in the choice of routine).
    subroutine add_routine_hint(adm, fallback, error)
        type(adm_model_type), intent(in) :: adm
        procedure(ucosub_interface), pointer, intent(in) :: fallback
        type(error_type), intent(inout) :: error
        character(len=:), allocatable :: served, suits, first
        logical :: time_free
        integer :: k

        if (error%stat /= stat_ucon .or. .not. associated(fallback)) return
        do k = 1, size(adm%ucons)
            associate (ucon => adm%ucons(k))
                if (index(error%message, "UCON/" // to_text(ucon%id) // ":") /= 1) cycle
                if (.not. served_by_model_ucosub(ucon%routine)) return
                served = builtin_ucosub_name(fallback, time_free)
                suits = builtin_ucosubs_for_par(ucon%par)
                if (len(served) > 0) then
                    if (index(", " // suits // ", ", ", " // served // ", ") > 0) return
                    served = "the built-in " // served
                else
                    served = "a routine of your own"
                end if
                error%message = error%message // "; this UCON names no ROUTINE, so the " &
                    & // "model's UCOSUB served it, here " // served // " (rollcon run " &
                    & // "MODEL.adm --ucosub FILE|NAME chooses it; without --ucosub it is the " &
                    & // "hand-checked disk)"
                if (len(suits) > 0) then
                    first = suits
                    if (index(suits, ",") > 0) first = suits(:index(suits, ",") - 1)
                    error%message = error%message // "; its PAR suits the built-in " // suits &
                        & // ": run with --ucosub " // first // ", or write ROUTINE=" // first &
                        & // " on the UCON"
                else
                    error%message = error%message // "; give the routine its PAR is written " &
                        & // "for with --ucosub FILE|NAME, or ROUTINE=name on the UCON"
                end if
                error%message = error%message // " (built-in routines: " &
                    & // builtin_ucosub_names() // ")"
                return
            end associate
        end do
    end subroutine add_routine_hint

    !> A force statement as a force between body-fixed markers.
    subroutine add_force_statement(adm, statement, model, error)
        type(adm_model_type), intent(in) :: adm
        type(adm_force_type), intent(in) :: statement
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        type(marker_type), allocatable :: markers(:)
        character(len=:), allocatable :: where, key
        integer :: k, n

        force%profile = profile_statement
        associate (s => force%statement)
            s%id = statement%id
            if (any(statement%kind == [force_springdamper, force_bushing])) then
                call add_spring(adm, statement, model)
                return
            end if
            if (statement%kind == force_sforce) then
                s%kind = merge(kind_translation, kind_rotation, statement%translation)
                where = place(adm%file, statement%line) // ": SFORCE/" // to_text(statement%id)
            else if (statement%kind == force_vforce) then
                s%kind = kind_vector
                where = place(adm%file, statement%line) // ": VFORCE/" // to_text(statement%id)
            else
                ! a GFORCE, or a VTORQUE: a GFORCE of TX, TY, TZ alone
                s%kind = kind_general
                where = place(adm%file, statement%line) // ": " &
                    & // trim(force_names(statement%kind)) // "/" // to_text(statement%id)
            end if
            s%action_only = statement%action_only
            s%i = adm_marker(adm, statement%i)
            if (statement%j /= 0) s%j = adm_marker(adm, statement%j)
            if (statement%rm /= 0) s%rm = adm_marker(adm, statement%rm)
            s%functions = statement%functions
            s%given = statement%given
            ! for messages: "data/x.adm:12: VFORCE/7"
            force%name = where
            s%id = statement%id
            if (statement%user) then
                call user_routine(statement, where, s%routine, error)
                if (allocated(error)) return
                s%par = statement%par
            end if
            s%time_unit = adm%units%time
            s%length_unit = adm%units%length
            s%force_unit = adm%units%force
            allocate(s%markers(0))
            do k = 1, 6
                if (.not. statement%given(k)) cycle
                key = slot_names(k)
                if (statement%kind == force_sforce) key = "FUNCTION"
                call expression_markers(adm, statement%functions(k), where // " " // key, &
                    & "a force's FUNCTION", markers, error)
                if (allocated(error)) return
                do n = 1, size(markers)
                    if (.not. any(s%markers%id == markers(n)%id)) s%markers = [s%markers, &
                        & markers(n)]
                end do
            end do
            ! the DIFFs' state its expressions may read as DIF(id), DIF1(id) (rollcon_diff)
            if (allocated(adm%diffs) .and. .not. statement%user) then
                if (size(adm%diffs) > 0) then
                    s%dif_ids = adm%diffs%id
                    allocate(s%dif(size(adm%diffs), 2))
                    s%dif(:, 1) = adm%diffs%ic(1)
                    s%dif(:, 2) = adm%diffs%ic(2)
                end if
            end if
        end associate
        call model%add_force(force)
    end subroutine add_force_statement

    !> The dataset's DIFFs as the model's (rollcon_diff), their markers as the model holds
    !> them, their state at the ICs. Refused as expression_markers refuses (a DIFF's FUNCTION
    !> reads no acceleration or force: an algebraic loop) and an IMPLICIT DIFF whose FUNCTION
    !> reads no DIF1 (its equation cannot fix its rate). A DIFF of FUNCTION=USER(...) takes the
    !> entry of its DIFSUB (the model's own, or the one its ROUTINE= names), refused, naming
    !> the DIFF and its line, when no file serves it.
    subroutine add_diffs(adm, model, error)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        integer :: k

        if (.not. allocated(adm%diffs)) return
        if (size(adm%diffs) == 0) return
        model%diffs%length_unit = adm%units%length
        model%diffs%time_unit = adm%units%time
        allocate(model%diffs%diffs(size(adm%diffs)))
        do k = 1, size(adm%diffs)
            associate (diff => model%diffs%diffs(k), given => adm%diffs(k))
                diff%id = given%id
                ! in messages of a run: "DIFF/3 (line 12)"
                diff%name = "DIFF/" // to_text(given%id) // " (line " // to_text(given%line) &
                    & // ")"

                diff%function = given%function
                diff%implicit = given%implicit
                diff%static_hold = given%static_hold
                diff%ic = given%ic
                where = place(adm%file, given%line) // ": DIFF/" // to_text(given%id) &
                    & // " FUNCTION"
                if (given%user) then
                    call diff_routine(given, where, diff%routine, error)
                    if (allocated(error)) return
                    diff%par = given%par
                    allocate(diff%markers(0))
                    cycle
                end if
                call expression_markers(adm, diff%function, where, "a DIFF's FUNCTION", &
                    & diff%markers, error)
                if (allocated(error)) return
                if (diff%implicit .and. .not. any(diff%function%inputs%quantity &
                    & == quantity_dif1)) then
                    call fatal_error(error, where // ": an IMPLICIT DIFF's equation 0 = e " &
                        & // "must read DIF1 (its rate), else it cannot fix DIF1(" &
                        & // to_text(diff%id) // ") (de/dDIF1 = 0, singular); write d DIF/dt " &
                        & // "= e without IMPLICIT", stat_input)
                    return
                end if
            end associate
        end do
        call model%diffs%start()
        call model%set_diff_state(model%diffs%x, model%diffs%w)
    end subroutine add_diffs

    !> The entry of the DIFSUB serving a DIFF of FUNCTION=USER(...) (at `where`): the model's
    !> own, or the one its ROUTINE= names; refused, saying what to give, when none does.
    subroutine diff_routine(given, where, entry, error)
        type(adm_diff_type), intent(in) :: given
        character(len=*), intent(in) :: where
        integer, intent(out) :: entry
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: routine

        routine = ""
        if (allocated(given%routine)) routine = given%routine
        entry = find_named_routine(routine_difsub, routine)
        if (entry > 0) return
        if (len(routine) == 0) then
            call fatal_error(error, where // "=USER(...): no " // diff_routine_name &
                & // " serves it; give the file that defines SUBROUTINE " // diff_routine_name &
                & // " (rollcon run MODEL --ucosub FILE; it runs in a process of its own)", &
                & stat_input)
        else
            call fatal_error(error, where // " ROUTINE=" // routine // ": no " &
                & // diff_routine_name // " of that name among the user's files; " &
                & // "ROUTINE=FILE::" // diff_routine_name // " names the routine of FILE " &
                & // "(given with --ucosub FILE; FILE as given, or its name without folder " &
                & // "and extension)", stat_input)
        end if
    end subroutine diff_routine

    !> A SPRINGDAMPER or BUSHING as a force between its markers (rollcon_spring_force), its
    !> constants in SI as read.
    subroutine add_spring(adm, statement, model)
        type(adm_model_type), intent(in) :: adm
        type(adm_force_type), intent(in) :: statement
        type(model_type), intent(inout) :: model
        type(applied_force_type) :: force

        force%profile = profile_statement
        force%name = place(adm%file, statement%line) // ": " &
            & // trim(force_names(statement%kind)) // "/" // to_text(statement%id)
        associate (s => force%statement, spring => force%statement%spring, &
                & c => statement%constants)
            s%id = statement%id
            s%kind = kind_spring
            s%i = adm_marker(adm, statement%i)
            s%j = adm_marker(adm, statement%j)
            s%time_unit = adm%units%time
            s%length_unit = adm%units%length
            s%force_unit = adm%units%force
            allocate(s%markers(0))
            if (statement%kind == force_bushing) then
                spring%kind = spring_bushing
            else
                spring%kind = merge(spring_translational, spring_rotational, &
                    & statement%translation)
            end if
            spring%stiffness = c(1:3)
            spring%damping = c(4:6)
            spring%torsional_stiffness = c(7:9)
            spring%torsional_damping = c(10:12)
            spring%preload = c(13:15)
            spring%preload_torque = c(16:18)
            spring%reference = statement%reference
        end associate
        call model%add_force(force)
    end subroutine add_spring
    !> The model's SPLINEs, fitted, for a user routine's AKISPL and CUBSPL
    !> (rollcon_user_forces' set_system_splines); the reader has checked their points.
    subroutine give_splines(adm)
        type(adm_model_type), intent(in) :: adm
        type(spline_type), allocatable :: curves(:)
        character(len=:), allocatable :: problem
        integer :: i

        allocate(curves(0))
        if (allocated(adm%splines)) then
            deallocate(curves)
            allocate(curves(size(adm%splines)))
            do i = 1, size(adm%splines)
                call new_spline(adm%splines(i)%id, adm%splines(i)%x, adm%splines(i)%y, &
                    & curves(i), problem, adm%splines(i)%linear_extrapolate)
            end do
        end if
        call set_system_splines(curves)
    end subroutine give_splines

    !> The model's STRINGs and ARRAYs, for a user routine's GTSTRG and GTARAY
    !> (rollcon_user_data).
    subroutine give_user_data(adm)
        type(adm_model_type), intent(in) :: adm
        type(user_string_type), allocatable :: strings(:)
        type(user_array_type), allocatable :: arrays(:)
        integer :: i

        allocate(strings(0), arrays(0))
        if (allocated(adm%strings)) then
            deallocate(strings)
            allocate(strings(size(adm%strings)))
            do i = 1, size(adm%strings)
                strings(i)%id = adm%strings(i)%id
                strings(i)%text = adm%strings(i)%text
            end do
        end if
        if (allocated(adm%arrays)) then
            deallocate(arrays)
            allocate(arrays(size(adm%arrays)))
            do i = 1, size(adm%arrays)
                arrays(i)%id = adm%arrays(i)%id
                arrays(i)%numbers = adm%arrays(i)%numbers
            end do
        end if
        call set_user_data(strings, arrays)
    end subroutine give_user_data

    !> The dataset's VARIABLEs served by VARSUBs (FUNCTION=USER), each with the entry of its
    !> routine (the model's own VARSUB, or the one its ROUTINE= names), given to
    !> rollcon_user_forces; refused, naming the VARIABLE and its line, when no file serves it.
    subroutine add_user_variables(adm, error)
        type(adm_model_type), intent(in) :: adm
        type(error_type), allocatable, intent(out) :: error
        type(user_variable_type), allocatable :: list(:)
        character(len=:), allocatable :: where, routine
        integer :: k, n

        if (.not. allocated(adm%variables)) then
            allocate(list(0))
        else
            allocate(list(count(adm%variables%user)))
            n = 0
            do k = 1, size(adm%variables)
                if (.not. adm%variables(k)%user) cycle
                n = n + 1
                where = place(adm%file, adm%variables(k)%line) // ": VARIABLE/" &
                    & // to_text(adm%variables(k)%id)
                routine = ""
                if (allocated(adm%variables(k)%routine)) routine = adm%variables(k)%routine
                list(n)%id = adm%variables(k)%id
                list(n)%par = adm%variables(k)%par
                list(n)%name = where
                list(n)%routine = find_named_routine(routine_varsub, routine)
                if (list(n)%routine > 0) cycle
                if (len(routine) == 0) then
                    call fatal_error(error, where // " FUNCTION=USER(...): no " &
                        & // variable_routine_name // " serves it; give the file that defines " &
                        & // "SUBROUTINE " // variable_routine_name // " (rollcon run MODEL " &
                        & // "--ucosub FILE; it runs in a process of its own)", stat_input)
                else
                    call fatal_error(error, where // " ROUTINE=" // routine // ": no " &
                        & // variable_routine_name // " of that name among the user's files; " &
                        & // "ROUTINE=FILE::" // variable_routine_name // " names the routine " &
                        & // "of FILE (given with --ucosub FILE; FILE as given, or its name " &
                        & // "without folder and extension)", stat_input)
                end if
                return
            end do
        end if
        call set_user_variables(list, adm%units%time)
    end subroutine add_user_variables

    !> The entry of the user's routine serving a FUNCTION=USER force statement
    !> (rollcon_user_forces' table): the model's own SFOSUB, VFOSUB, GFOSUB or VTOSUB, or the
    !> one its ROUTINE= names. Refused when there is none, naming the statement and what to
    !> give.
    subroutine user_routine(statement, where, entry, error)
        type(adm_force_type), intent(in) :: statement
        !> "data/x.adm:12: SFORCE/2"
        character(len=*), intent(in) :: where
        integer, intent(out) :: entry
        type(error_type), allocatable, intent(out) :: error
        integer :: kind

        kind = routine_kind_of(trim(force_names(statement%kind)))
        entry = find_named_routine(kind, statement%routine)
        if (entry > 0) return
        if (len(statement%routine) == 0) then
            call fatal_error(error, where // " FUNCTION=USER(...): no " &
                & // trim(routine_names(kind)) // " serves it; give the file that defines " &
                & // "SUBROUTINE " // trim(routine_names(kind)) // " (rollcon run MODEL " &
                & // "--ucosub FILE; it runs in a process of its own)", stat_input)
        else
            call fatal_error(error, where // " ROUTINE=" // statement%routine // ": no " &
                & // trim(routine_names(kind)) // " of that name among the user's files; " &
                & // "ROUTINE=FILE::NAME names the subroutine NAME of FILE, with " &
                & // trim(routine_names(kind)) // "'s calling sequence (FILE given with " &
                & // "--ucosub FILE; as given, or its name without folder and extension)", &
                & stat_input)
        end if
    end subroutine user_routine

end module rollcon_adm_build
