! SPDX-License-Identifier: MIT
!> The force measures a user's routine reads through SYSFNC (rollcon_user_forces'
!> force_measure): FX ... TM(i[, j[, k]]), the force and torque at marker i of the elements
!> acting there (as their I or their J) and, with j, between i and j; and an element's force,
!> JOINT, JPRIM, SFORCE, VFORCE, VTORQUE, GFORCE, BUSHING, SPDP(id, jflag, ...), as a
!> REQUEST's expression reads them (rollcon_request_answers, docs/datasets.md, "Force
!> measures read by a user's routine"):
!>
!> - a JOINT's, JPRIM's or MOTION's reaction from the multipliers of its rows
!>   (rollcon_reactions' site_wrench at I, swapped_wrench at J; a MOTION's markers are its
!>   JOINT's, or its own I and J: the model's statement holds them), the multipliers those
!>   rollcon_user_forces' set_system_constraint_forces gave: the equations' iterate of the
!>   algebraic loop a force reading them makes (rollcon_equations' loop_accelerations), IDA's
!>   unknowns (rollcon_dae), the solve at an output row;
!> - a force statement's force and torque at its I or J (force_wrench), from its expressions
!>   at the state, or from the values its routine gave at this state (rollcon_user_forces
!>   calls the routines that read force measures after the others).
!>
!> A force routine's force measure that would sum the force of a routine that reads force
!> measures itself (its own included) is a cycle of forces this does not iterate (a REQSUB's,
!> read at an output row once every force is known, makes none, nor a DIFSUB's, called once
!> the forces and multipliers of the state are solved): refused, naming both statements,
!> unless that force's share of what is read is zero by its kind (a rotational SFORCE's or a
!> VTORQUE's force, a translational SFORCE's torque, a VFORCE's torque at its I), which is
!> left out. A VARSUB is called before every force (the forces may read its value): its
!> force measures sum the reactions (the multipliers are the loop's unknowns) and the forces
!> written as expressions that read no VARIABLE; a force served by a routine, or whose
!> expression reads a VARVAL, is refused the same way unless its share is zero by its kind.
!>
!> The model is the one the equations were set up with (set_force_measure_model, called by
!> rollcon_equations' init): one model per process, as rollcon_user_forces' utilities have.
module rollcon_force_measures
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_rotation, only : times, cross
    use rollcon_marker, only : marker_type, marker_motion
    use rollcon_marker_force, only : marker_force_type, marker_force_values, kind_translation, &
        & kind_rotation, kind_vector, kind_spring, marker_force_action
    use rollcon_force, only : profile_statement
    use rollcon_model, only : model_type, statement_joint, statement_jprim, statement_element
    use rollcon_reactions, only : reaction_site_type, reaction_sites, site_wrench, &
        & swapped_wrench
    use rollcon_expression, only : quantity_names, quantity_tx, quantity_kind, &
        & kind_element_force, quantity_varval
    use rollcon_user_forces, only : set_force_measure_hook, force_measure_interface
    use rollcon_constraint_matrix, only : constraint_matrix_type
    implicit none
    private

    public :: force_wrench, set_force_measure_model

    !> The model the measures are read from, and its reaction sites
    type(model_type), pointer, save :: measured => null()
    type(reaction_site_type), allocatable, save :: sites(:)

contains

    !> Read the force measures from model (a target that outlives its use: the equations'
    !> own) and answer SYSFNC's force measures through rollcon_user_forces' hook; the hook
    !> set again for the same model costs nothing, unless refresh (the equations' init: a new
    !> model may sit where an old one was) asks for its sites again.
    subroutine set_force_measure_model(model, refresh)
        type(model_type), intent(in), target :: model
        logical, intent(in), optional :: refresh
        procedure(force_measure_interface), pointer :: hook
        logical :: again

        again = .false.
        if (present(refresh)) again = refresh
        if (associated(measured, model) .and. .not. again) then
            ! the same model: its sites as they are (a REQSUB's rows set it at every row)
            if (allocated(sites)) return
        end if
        measured => model
        sites = reaction_sites(model)
        call add_motion_sites(model, sites)
        hook => answer_force_measure
        call set_force_measure_hook(hook)
    end subroutine set_force_measure_model

    !> A site at its markers for each MOTION of the model (reaction_sites gives a MOTION's
    !> reaction on each part it holds, at the centre of mass, as its columns report it): its
    !> force and torque on the part of its I at I, as a JOINT's (on the ground: minus the
    !> reaction on J's part, its moment carried to I).
    subroutine add_motion_sites(model, sites)
        type(model_type), intent(in) :: model
        type(reaction_site_type), allocatable, intent(inout) :: sites(:)
        type(reaction_site_type), allocatable :: grown(:)
        type(reaction_site_type) :: site
        integer :: s, k

        if (.not. allocated(model%statements)) return
        do s = 1, size(model%statements)
            if (.not. is_motion(s)) cycle
            associate (statement => model%statements(s))
                if (statement%i%part == 0 .and. statement%j_part == 0) cycle
                site%statement = s
                site%rows = pack([(k, k = 1, model%nc)], model%ucons(:model%nc)%statement == s)
                if (size(site%rows) == 0) cycle
                site%at_marker = .true.
                site%on_ground = statement%i%part == 0
                site%part = merge(statement%j_part, statement%i%part, site%on_ground)
                site%stem = "motion" // to_text(statement%id)
            end associate
            ! (element by element: gfortran 12 may mishandle an array constructor of a type
            ! with allocatable components)
            allocate(grown(size(sites) + 1))
            do k = 1, size(sites)
                grown(k) = sites(k)
            end do
            grown(size(grown)) = site
            call move_alloc(grown, sites)
        end do

    contains

        logical function is_motion(s)
            integer, intent(in) :: s

            is_motion = model%statements(s)%kind == statement_element
            if (.not. is_motion) return
            is_motion = index(model%statements(s)%name, "MOTION/") == 1
            if (is_motion) is_motion = model%statements(s)%i%id /= 0
        end function is_motion
    end subroutine add_motion_sites

    !> rollcon_user_forces' force_measure_interface (module header): the wrench [N, N m], ground
    !> axes, on the part of the marker read, the torque about its origin.
    subroutine answer_force_measure(quantity, ids, caller, time, q, u, c, lambda, wrench, rows, &
            & read_markers, problem)
        integer, intent(in) :: quantity, ids(2)
        character(len=*), intent(in) :: caller
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(out) :: wrench(6)
        integer, allocatable, intent(out) :: rows(:), read_markers(:)
        character(len=:), allocatable, intent(out) :: problem
        character(len=:), allocatable :: name
        logical :: torque_half, variable_caller
        integer :: s, f, at, between

        wrench = 0.0_wp
        allocate(rows(0), read_markers(0))
        problem = ""
        if (.not. associated(measured)) then
            problem = "no model's equations are set up"
            return
        end if
        name = trim(quantity_names(quantity))
        ! a VARSUB's call (module header)
        variable_caller = statement_word(caller) == "VARIABLE"
        if (quantity_kind(quantity) == kind_element_force) then
            call element_measure()
            return
        end if
        torque_half = quantity >= quantity_tx
        at = ids(1)
        between = ids(2)
        do s = 1, size(sites)
            if (.not. sites(s)%at_marker) cycle
            associate (statement => measured%statements(sites(s)%statement))
                if (statement%i%id == at .and. (between == 0 .or. statement%j%id == between)) &
                    & call add_site(s, .false.)
                if (statement%j%id == at .and. statement%j%id /= 0 .and. (between == 0 .or. &
                    & statement%i%id == between)) call add_site(s, .true.)
            end associate
        end do
        if (.not. allocated(measured%forces)) return
        do f = 1, size(measured%forces)
            if (measured%forces(f)%profile /= profile_statement) cycle
            associate (force => measured%forces(f)%statement)
                if (force%i%id == at .and. (between == 0 .or. force%j%id == between)) &
                    & call add_force(f, .false.)
                if (len(problem) > 0) return
                if (force%j%id == at .and. force%j%id /= 0 .and. (between == 0 .or. &
                    & force%i%id == between)) call add_force(f, .true.)
                if (len(problem) > 0) return
            end associate
        end do

    contains

        !> Add site s's reaction at its I (or J), and its rows.
        subroutine add_site(s, at_j)
            integer, intent(in) :: s
            logical, intent(in) :: at_j
            real(wp) :: reaction(6)

            reaction = site_wrench(measured, sites(s), c, lambda, q)
            if (at_j) reaction = swapped_wrench(measured, sites(s), reaction, q)
            wrench = wrench + reaction
            rows = [rows, sites(s)%rows]
        end subroutine add_site

        !> Add force f's force and torque at its I (or J), and the markers it reads; a cycle
        !> refused (module header).
        subroutine add_force(f, at_j)
            integer, intent(in) :: f
            logical, intent(in) :: at_j

            associate (force => measured%forces(f)%statement, other => measured%forces(f)%name)
                if (variable_caller) then
                    if (.not. known_before_variables(f)) then
                        if (zero_share(f, at_j)) return
                        problem = variable_refusal(f)
                        return
                    end if
                    wrench = wrench + force_wrench(force, at_j, time, q, u)
                    call add_markers(f)
                    return
                end if
                ! (a REQSUB and a DIFSUB, caller "", read every force of the state: no cycle)
                if (len(caller) > 0 .and. force%routine > 0 .and. force%declared_forces) then
                    if (other == caller .and. zero_share(f, at_j)) return
                    problem = "it sums the force of " // other // ", whose routine reads " &
                        & // "force measures too: a cycle of forces reading each other, which " &
                        & // "rollcon does not solve (give the routine markers of its own, " &
                        & // "or compute the force it reads itself)"
                    return
                end if
                wrench = wrench + force_wrench(force, at_j, time, q, u)
                call add_markers(f)
            end associate
        end subroutine add_force

        !> Force f's value is known when a VARSUB is called: written as an expression that
        !> reads no VARVAL (module header).
        logical function known_before_variables(f)
            integer, intent(in) :: f
            integer :: k, m

            associate (force => measured%forces(f)%statement)
                known_before_variables = force%routine == 0
                if (.not. known_before_variables) return
                if (.not. allocated(force%markers)) return
                do k = 1, 6
                    if (.not. force%given(k)) cycle
                    if (.not. allocated(force%functions(k)%inputs)) cycle
                    do m = 1, size(force%functions(k)%inputs)
                        if (force%functions(k)%inputs(m)%quantity == quantity_varval) &
                            & known_before_variables = .false.
                    end do
                end do
            end associate
        end function known_before_variables

        !> Why a VARSUB's force measure does not sum force f (module header).
        function variable_refusal(f) result(why)
            integer, intent(in) :: f
            character(len=:), allocatable :: why

            why = "it sums the force of " // measured%forces(f)%name // ", which rollcon " &
                & // "evaluates after the VARIABLEs (a force served by a routine, or reading " &
                & // "VARVAL, may read them): a VARSUB's force measures sum the reactions of " &
                & // "JOINTs, JPRIMs and MOTIONs and the forces written as expressions that " &
                & // "read no VARIABLE"
        end function variable_refusal

        !> Force f's share of what is read is zero by its kind (module header).
        logical function zero_share(f, at_j)
            integer, intent(in) :: f
            logical, intent(in) :: at_j
            character(len=:), allocatable :: word

            word = statement_word(measured%forces(f)%name)
            associate (force => measured%forces(f)%statement)
                if (torque_half) then
                    zero_share = force%kind == kind_translation .or. (force%kind == kind_vector &
                        & .and. .not. at_j)
                else
                    zero_share = force%kind == kind_rotation .or. word == "VTORQUE"
                end if
            end associate
        end function zero_share

        !> The markers force f's value depends on: its I, J and RM, and those its expressions
        !> or its routine's declaration read.
        subroutine add_markers(f)
            integer, intent(in) :: f
            integer :: m

            associate (force => measured%forces(f)%statement)
                read_markers = [read_markers, pack([force%i%id, force%j%id, force%rm%id], &
                    & [force%i%id, force%j%id, force%rm%id] /= 0)]
                if (force%routine > 0) then
                    if (allocated(force%declared_markers)) &
                        & read_markers = [read_markers, force%declared_markers]
                else if (allocated(force%markers)) then
                    do m = 1, size(force%markers)
                        read_markers = [read_markers, force%markers(m)%id]
                    end do
                end if
            end associate
        end subroutine add_markers

        !> An element's force: ids = (id, jflag).
        subroutine element_measure()
            character(len=:), allocatable :: wanted
            logical :: at_j

            at_j = ids(2) == 1
            if (name == "MOTION") then
                do s = 1, size(sites)
                    if (.not. sites(s)%at_marker) cycle
                    associate (statement => measured%statements(sites(s)%statement))
                        if (statement%kind /= statement_element) cycle
                        if (statement%name /= "MOTION/" // to_text(ids(1))) cycle
                    end associate
                    call add_site(s, at_j)
                    return
                end do
                problem = "no MOTION/" // to_text(ids(1)) // " in the model"
                return
            end if
            if (name == "JOINT" .or. name == "JPRIM") then
                do s = 1, size(sites)
                    if (.not. sites(s)%at_marker) cycle
                    associate (statement => measured%statements(sites(s)%statement))
                        if (statement%id /= ids(1)) cycle
                        if ((statement%kind == statement_joint) .neqv. name == "JOINT") cycle
                        if (statement%kind /= statement_joint .and. statement%kind &
                            & /= statement_jprim) cycle
                    end associate
                    call add_site(s, at_j)
                    return
                end do
                problem = "no " // name // "/" // to_text(ids(1)) // " whose force rollcon " &
                    & // "reports in the model (a RACKPIN or SCREW joint is a coupling, not " &
                    & // "reported)"
                return
            end if
            wanted = name
            if (name == "SPDP") wanted = "SPRINGDAMPER"
            if (.not. any(wanted == [character(len=12) :: "SFORCE", "VFORCE", "VTORQUE", &
                & "GFORCE", "BUSHING", "SPRINGDAMPER"])) then
                problem = "an element's force rollcon's SYSFNC does not answer (JOINT, JPRIM, " &
                    & // "MOTION, SFORCE, VFORCE, VTORQUE, GFORCE, BUSHING and SPDP are " &
                    & // "answered)"
                return
            end if
            if (allocated(measured%forces)) then
                do f = 1, size(measured%forces)
                    if (measured%forces(f)%profile /= profile_statement) cycle
                    if (measured%forces(f)%statement%id /= ids(1)) cycle
                    if (statement_word(measured%forces(f)%name) /= wanted) cycle
                    associate (force => measured%forces(f)%statement)
                        if (variable_caller .and. .not. known_before_variables(f)) then
                            problem = variable_refusal(f)
                            return
                        end if
                        if (len(caller) > 0 .and. .not. variable_caller .and. &
                            & force%routine > 0 .and. force%declared_forces) then
                            problem = "the force of " // measured%forces(f)%name // ", whose " &
                                & // "routine reads force measures: a cycle of forces " &
                                & // "reading each other, which rollcon does not solve"
                            return
                        end if
                        wrench = force_wrench(force, at_j, time, q, u)
                        call add_markers(f)
                    end associate
                    return
                end do
            end if
            problem = "no " // wanted // "/" // to_text(ids(1)) // " in the model"
        end subroutine element_measure
    end subroutine answer_force_measure

    !> The statement of a force's name, "x.adm:12: VTORQUE/3": "VTORQUE" ("" for none).
    pure function statement_word(name) result(word)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: word
        integer :: slash, start

        word = ""
        slash = index(name, "/", back=.true.)
        if (slash == 0) return
        start = index(name(:slash), " ", back=.true.) + 1
        word = name(start:slash - 1)
    end function statement_word

    !> An SFORCE's, VFORCE's, VTORQUE's, GFORCE's, SPRINGDAMPER's or BUSHING's force and
    !> torque at its I or J (module header).
    pure function force_wrench(force, at_j, time, q, u) result(wrench)
        type(marker_force_type), intent(in) :: force
        logical, intent(in) :: at_j
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp) :: wrench(6)
        real(wp) :: values(6), r_i(3), r_j(3), axes_i(3, 3), axes_j(3, 3), axes_rm(3, 3), &
            & v(3), w(3), r(3), f(3), torque(3)

        wrench = 0.0_wp
        if (at_j .and. force%action_only) return
        if (force%kind == kind_spring) then
            call marker_force_action(force, time, q, u, f, torque)
            call marker_motion(force%i, q, u, r_i, v, axes_i, w)
            call marker_motion(force%j, q, u, r_j, v, axes_j, w)
            if (at_j) then
                wrench(1:3) = -f
                wrench(4:6) = -torque - cross(r_i - r_j, f)
            else
                wrench(1:3) = f
                wrench(4:6) = torque
            end if
            return
        end if
        values = marker_force_values(force, time, q, u)
        call marker_motion(force%i, q, u, r_i, v, axes_i, w)
        call marker_motion(force%j, q, u, r_j, v, axes_j, w)
        select case (force%kind)
        case (kind_translation)
            if (force%action_only) then
                f = values(1)*axes_j(:, 3)
            else
                f = values(1)*(r_i - r_j)/norm2(r_i - r_j)
            end if
            wrench(1:3) = merge(-f, f, at_j)
        case (kind_rotation)
            torque = values(1)*force%length_unit*axes_j(:, 3)
            wrench(4:6) = merge(-torque, torque, at_j)
        case default
            call marker_motion(force%rm, q, u, r, v, axes_rm, w)
            f = times(axes_rm, values(1:3))
            torque = times(axes_rm, values(4:6))
            if (at_j) then
                wrench(1:3) = -f
                wrench(4:6) = -torque - cross(r_i - r_j, f)
            else
                wrench(1:3) = f
                wrench(4:6) = torque
            end if
        end select
    end function force_wrench

end module rollcon_force_measures
