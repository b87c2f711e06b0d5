! SPDX-License-Identifier: MIT
!> The statements of a dataset that shape only ADAMS's own outputs or its choice of solver:
!> REQUEST, MREQUEST, GRAPHICS, RESULTS, DEBUG, PREFERENCES, LIST, NOLIST, the settings of
!> ADAMS's own solvers (KINEMATICS, IC), EQUILIBRIUM (its ERROR, IMBALANCE, TLIMIT, ALIMIT and
!> MAXIT honoured as the static equilibrium's limits, in the run settings, in SI; the rest
!> warned), and OUTPUT's arguments. Each
!> keyword rollcon knows is read as strictly as a simulated statement's (any case, ADAMS's
!> abbreviations, once each), the form of every value, and the markers, parts and forces it
!> names (checked with the rest once the file is read: rollcon_adm_checks). A keyword rollcon
!> does not know never stops a run over a statement that changes nothing it computes: it is
!> named in the one warning, not read. What rollcon has no equivalent of is recorded as read
!> and not used, and a run names it all in one warning (unused_warning); a REQUEST/id,
!> DISPLACEMENT is honoured as output columns (rollcon_request_watch), and every other
!> REQUEST is kept (its kind, markers, comment and expressions) for the assembly to answer
!> (rollcon_adm_requests), a FUNCTION=USER(...) one with its REQSUB's constants.
!> Values are not converted to SI (EQUILIBRIUM's honoured ones aside): nothing reads them.
module rollcon_adm_outputs
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type, adm_argument_type, upper_case
    use rollcon_adm_keywords, only : read_reals, argument_key, arg_place, name_index, &
        & argument_text, read_integer
    use rollcon_expression, only : expression_type, quantity_kind, quantity_names, &
        & kind_element, kind_element_force, quantity_varval, quantity_dif, quantity_dif1
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_adm_loads, only : read_user_list
    use rollcon_adm_contacts, only : adm_graphics_type, graphics_ellipsoid, graphics_cylinder, &
        & graphics_plane
    use rollcon_adm_model, only : adm_model_type, adm_request_type, adm_unused_type, &
        & adm_reference_type, refers_to_marker, refers_to_part, refers_to_force, &
        & request_displacement, request_velocity, request_acceleration, request_force, &
        & request_expressions, request_user
    implicit none
    private

    public :: output_statement_names, output_needs_id, read_output_statement, read_form
    public :: record_unused, unused_warning, answer_force_requests

    !> Forms of a value: a keyword alone; one number; one angle (D for degrees); numbers; a
    !> whole number >= 0; any text (a name, a comment, an expression: not read further); a
    !> marker id (0: none); marker ids; ALL or part ids; ALL or ids of SFORCE, VFORCE, GFORCE;
    !> ALL or ids of statements rollcon has none of (joints); names (a list whose further
    !> entries, names alone, follow on: REQUEST's CNAMES=MAG, X_COMP, Y_COMP)
    integer, parameter, public :: form_flag = 1, form_number = 2, form_angle = 3, &
        & form_numbers = 4, form_whole = 5, form_text = 6, form_marker = 7, form_markers = 8, &
        & form_parts = 9, form_forces = 10, form_ids = 11, form_texts = 12

    !> The statements read and not simulated (OUTPUT, simulated without arguments, is one of
    !> rollcon_adm_keywords' statement_names; its arguments are read here)
    character(len=*), parameter :: output_statement_names(11) = [character(len=11) :: &
        & "DEBUG", "EQUILIBRIUM", "GRAPHICS", "IC", "KINEMATICS", "LIST", "MREQUEST", &
        & "NOLIST", "PREFERENCES", "REQUEST", "RESULTS"]

    !> Keywords of one statement that share a form, separated by blanks
    type :: keyword_group_type
        character(len=11) :: statement
        integer :: form
        character(len=240) :: keywords
    end type keyword_group_type

    !> Every keyword of the statements read here, in the order a refusal lists them
    type(keyword_group_type), parameter :: groups(*) = [ &
        & keyword_group_type("REQUEST", form_flag, "DISPLACEMENT VELOCITY ACCELERATION FORCE"), &
        & keyword_group_type("REQUEST", form_marker, "I J RM"), &
        & keyword_group_type("REQUEST", form_text, "F1 F2 F3 F4 F5 F6 F7 F8 FUNCTION ROUTINE " &
        & // "COMMENT TITLE"), &
        & keyword_group_type("REQUEST", form_texts, "CNAMES CUNITS CLABELS"), &
        & keyword_group_type("REQUEST", form_text, "RESULTS_NAME"), &
        & keyword_group_type("MREQUEST", form_flag, "DISPLACEMENT VELOCITY ACCELERATION FORCE"), &
        & keyword_group_type("MREQUEST", form_parts, "PARTS"), &
        & keyword_group_type("MREQUEST", form_ids, "JOINTS JPRIMS"), &
        & keyword_group_type("MREQUEST", form_forces, "APPFORS"), &
        & keyword_group_type("MREQUEST", form_text, "COMMENT"), &
        & keyword_group_type("GRAPHICS", form_flag, "ARC BOX CIRCLE CURVE CYLINDER ELLIPSOID " &
        & // "EXTERNAL FORCE FRUSTUM PLANE POINT SPDP TORUS"), &
        & keyword_group_type("GRAPHICS", form_markers, "OUTLINE"), &
        & keyword_group_type("GRAPHICS", form_marker, "CM CORNER RM EMARKER I J"), &
        & keyword_group_type("GRAPHICS", form_number, "RADIUS LENGTH TOP BOTTOM X Y Z XSCALE " &
        & // "YSCALE ZSCALE XMIN XMAX YMIN YMAX MAJOR_RADIUS MINOR_RADIUS CRATIO DA DB DC DD " &
        & // "LA LB LC LD FACETING_TOLERANCE"), &
        & keyword_group_type("GRAPHICS", form_angle, "RANGLE"), &
        & keyword_group_type("GRAPHICS", form_whole, "SIDES SEG COILS"), &
        & keyword_group_type("GRAPHICS", form_text, "CID EID ETYPE FILE ELEMENT"), &
        & keyword_group_type("RESULTS", form_flag, "FORMATTED XRF NOACCELERATIONS " &
        & // "NOAPPLIEDFORCES NOCONTACTS NODATASTRUCTURES NOFLOATINGMARKERS NOLINEAR " &
        & // "NOREACTIONFORCES NOREQUESTS NOSYSTEMELEMENTS NOTIRES NOVELOCITIES ROUNDOFF " &
        & // "TRAILINGZEROS"), &
        & keyword_group_type("RESULTS", form_whole, "SIGFIGS"), &
        & keyword_group_type("RESULTS", form_number, "ZEROTHRESHOLD"), &
        & keyword_group_type("RESULTS", form_text, "COMMENT"), &
        & keyword_group_type("OUTPUT", form_flag, "DACSAVE GRSAVE NOPRINT NOSEPARATOR REQSAVE " &
        & // "SEPARATOR TELETYPE YPR"), &
        & keyword_group_type("DEBUG", form_flag, "DOF DUMP EPRINT JMDUMP REQDUMP RHSDUMP " &
        & // "TOPOLOGY VERBOSE"), &
        & keyword_group_type("PREFERENCES", form_number, "CONTACT_FACETING_TOLERANCE"), &
        & keyword_group_type("PREFERENCES", form_whole, "NTHREADS"), &
        & keyword_group_type("PREFERENCES", form_text, "CONTACT_GEOMETRY_LIBRARY " &
        & // "FLEX_LIMIT_CHECK FLEX_LIMIT_CHECK_ACTION LIBRARY_SEARCH_PATH SIMFAIL SOLVERBIAS " &
        & // "STATUS_MESSAGE"), &
        & keyword_group_type("EQUILIBRIUM", form_flag, "STATIC DYNAMIC"), &
        & keyword_group_type("EQUILIBRIUM", form_number, "ERROR IMBALANCE STABILITY TLIMIT " &
        & // "SETTLING_TIME GLOBAL_DAMPING"), &
        & keyword_group_type("EQUILIBRIUM", form_angle, "ALIMIT"), &
        & keyword_group_type("EQUILIBRIUM", form_whole, "MAXIT"), &
        & keyword_group_type("EQUILIBRIUM", form_text, "PATTERN METHOD"), &
        & keyword_group_type("KINEMATICS", form_number, "ERROR AERROR HMAX TLIMIT"), &
        & keyword_group_type("KINEMATICS", form_angle, "ALIMIT"), &
        & keyword_group_type("KINEMATICS", form_whole, "MAXIT AMAXIT"), &
        & keyword_group_type("KINEMATICS", form_text, "PATTERN APATTERN"), &
        & keyword_group_type("IC", form_number, "ERROR AERROR VERROR TLIMIT"), &
        & keyword_group_type("IC", form_angle, "ALIMIT"), &
        & keyword_group_type("IC", form_whole, "MAXIT AMAXIT"), &
        & keyword_group_type("IC", form_text, "PATTERN APATTERN")]
    !> GRAPHICS: the keywords that give its shape (one of them)
    character(len=*), parameter :: shapes(14) = [character(len=9) :: "ARC", "BOX", "CIRCLE", &
        & "CURVE", "CYLINDER", "ELLIPSOID", "EXTERNAL", "FORCE", "FRUSTUM", "PLANE", "POINT", &
        & "SPDP", "TORUS", "OUTLINE"]
    !> REQUEST: what it measures (one of them, or expressions)
    character(len=*), parameter :: measures(4) = [character(len=12) :: "DISPLACEMENT", &
        & "VELOCITY", "ACCELERATION", "FORCE"]
    !> REQUEST: the kind of request each of measures asks for
    integer, parameter :: measure_kinds(4) = [request_displacement, request_velocity, &
        & request_acceleration, request_force]
    !> REQUEST: the keywords of expressions
    character(len=*), parameter :: expression_keys(9) = [character(len=8) :: "F1", "F2", "F3", &
        & "F4", "F5", "F6", "F7", "F8", "FUNCTION"]
    !> Line numbers a warning lists of one kind before it counts the rest
    integer, parameter :: lines_listed = 8
    !> Entries a list of requests, unused statements or references starts with when it grows
    integer, parameter :: least_capacity = 16

contains

    !> The statements read here that take an id (unique among those of their kind).
    pure logical function output_needs_id(name)
        character(len=*), intent(in) :: name

        output_needs_id = any(name == [character(len=8) :: "GRAPHICS", "MREQUEST", "REQUEST"])
    end function output_needs_id

    !> Read statement `name` (one of output_statement_names, or OUTPUT): every keyword and
    !> value checked, its references kept for rollcon_adm_checks; a REQUEST/id, DISPLACEMENT
    !> becomes one of model%requests, anything else one of model%unused.
    subroutine read_output_statement(path, where, name, statement, repeated, model, error)
        character(len=*), intent(in) :: path
        !> "file:line: NAME/id"
        character(len=*), intent(in) :: where
        !> The statement's name in full
        character(len=*), intent(in) :: name
        type(adm_statement_type), intent(in) :: statement
        !> An earlier statement of this kind has this id
        logical, intent(in) :: repeated
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=26), allocatable :: keys(:)
        integer, allocatable :: forms(:), ids(:)
        logical, allocatable :: given(:)
        integer :: marker(3), k, slot
        character(len=:), allocatable :: key, at
        type(error_type), allocatable :: refused
        !> A keyword rollcon does not know was written; a list of names goes on
        logical :: unknown, names_open

        if (repeated) then
            call fatal_error(error, where // ": a second " // name // " with this id", stat_input)
            return
        end if
        call statement_keywords(name, keys, forms)
        allocate(given(size(keys)), source=.false.)
        marker = 0
        unknown = .false.
        names_open = .false.
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, keys, key, refused)
            if (allocated(refused) .and. names_open .and. .not. &
                & statement%arguments(k)%assigned) then
                ! a further entry of a list of names (CNAMES=MAG, X_COMP, Y_COMP)
                deallocate(refused)
                cycle
            end if
            names_open = .false.
            if (allocated(refused)) then
                ! not read: named in the warning, never a refusal (nothing rollcon computes
                ! depends on it)
                call record_unused(model%unused, model%unused_count, name // " " &
                    & // statement%arguments(k)%keyword, statement%arguments(k)%line, &
                    & known=.false.)
                unknown = .true.
                deallocate(refused)
                cycle
            end if
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            slot = name_index(key, keys)
            given(slot) = .true.
            names_open = forms(slot) == form_texts
            call read_form(statement%arguments(k), at, forms(slot), ids, error)
            if (allocated(error)) return
            call keep_references(model, at, forms(slot), ids)
            if (name == "REQUEST" .and. forms(slot) == form_marker .and. size(ids) > 0) &
                & marker(name_index(key, [character(len=2) :: "I", "J", "RM"])) = ids(1)
            if (name == "OUTPUT") call record_unused(model%unused, model%unused_count, &
                & "OUTPUT " // key, statement%line)
            if (name == "EQUILIBRIUM") then
                call read_equilibrium_limit(statement%arguments(k), at, key, model, error)
                if (allocated(error)) return
            end if
        end do
        select case (name)
        case ("REQUEST")
            call read_request(path, where, statement, keys, given, marker, unknown, model, error)
        case ("GRAPHICS")
            if (unknown .and. count(given .and. is_one_of(keys, shapes)) == 0) then
                ! its shape is a keyword rollcon does not know: named in the warning
                call record_unused(model%unused, model%unused_count, name, statement%line)
                return
            end if
            if (count(given .and. is_one_of(keys, shapes)) /= 1) call fatal_error(error, where &
                & // ": give one shape (ARC, BOX, CIRCLE, CURVE, CYLINDER, ELLIPSOID, EXTERNAL, " &
                & // "FORCE, FRUSTUM, PLANE, POINT, SPDP, TORUS or OUTLINE=ids), got " &
                & // to_text(count(given .and. is_one_of(keys, shapes))), stat_input)
            if (.not. allocated(error)) call record_unused(model%unused, model%unused_count, &
                & name, statement%line)
            ! a shape a CONTACT can name: kept for it (rollcon_adm_contacts)
            if (.not. allocated(error)) call keep_graphics(path, where, statement, keys, model, &
                & error)
        case ("OUTPUT", "EQUILIBRIUM")
        case default
            call record_unused(model%unused, model%unused_count, name, statement%line)
        end select
    end subroutine read_output_statement

    !> A GRAPHICS of ELLIPSOID, CYLINDER or PLANE kept in model%graphics with its marker (CM,
    !> or RM), RADIUS, LENGTH, XSCALE, YSCALE, ZSCALE (lengths in SI), for a CONTACT that names
    !> it; another shape is not kept. Its keys are checked already (read_output_statement).
    subroutine keep_graphics(path, where, statement, keys, model, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        !> GRAPHICS's keywords (statement_keywords)
        character(len=*), intent(in) :: keys(:)
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        type(adm_graphics_type) :: graphics
        type(error_type), allocatable :: refused
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        integer :: k

        graphics%id = statement%id
        graphics%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, keys, key, refused)
            if (allocated(refused)) then
                deallocate(refused)
                cycle
            end if
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("ELLIPSOID")
                graphics%shape = graphics_ellipsoid
            case ("CYLINDER")
                graphics%shape = graphics_cylinder
            case ("PLANE")
                graphics%shape = graphics_plane
            case ("CM", "RM")
                call read_integer(statement%arguments(k), at, graphics%marker, error)
            case ("RADIUS", "LENGTH", "XSCALE", "YSCALE", "ZSCALE")
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, &
                    & factor=model%units%length)
                if (allocated(error)) return
                select case (key)
                case ("RADIUS")
                    graphics%radius = values(1)
                case ("LENGTH")
                    graphics%length = values(1)
                case default
                    graphics%scales(name_index(key, ["XSCALE", "YSCALE", "ZSCALE"])) = values(1)
                end select
            end select
            if (allocated(error)) return
        end do
        if (graphics%shape == 0) return
        if (.not. allocated(model%graphics)) allocate(model%graphics(0))
        model%graphics = [model%graphics, graphics]
    end subroutine keep_graphics

    !> One argument of EQUILIBRIUM: ERROR, IMBALANCE (force units), TLIMIT (length units),
    !> ALIMIT (an angle) and MAXIT set the static equilibrium's limits (run settings, in SI);
    !> the others (STABILITY, PATTERN, METHOD, DYNAMIC, ...) are recorded as read and not used.
    subroutine read_equilibrium_limit(argument, at, key, model, error)
        type(adm_argument_type), intent(in) :: argument
        !> "file:line: EQUILIBRIUM KEY"
        character(len=*), intent(in) :: at
        !> The keyword in full
        character(len=*), intent(in) :: key
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:)

        select case (key)
        case ("ERROR", "IMBALANCE", "TLIMIT", "ALIMIT", "MAXIT")
        case default
            call record_unused(model%unused, model%unused_count, "EQUILIBRIUM " // key, &
                & argument%line)
            return
        end select
        call read_reals(argument, at, 1, 1, key == "ALIMIT", values, error)
        if (allocated(error)) return
        if (.not. values(1) > 0.0_wp) then
            call fatal_error(error, at // " must be > 0, got " // to_text(values(1)), stat_input)
            return
        end if
        associate (settings => model%run%settings)
            select case (key)
            case ("ERROR")
                settings%equilibrium_error = values(1)
            case ("IMBALANCE")
                settings%equilibrium_imbalance = values(1)*model%units%force
            case ("TLIMIT")
                settings%equilibrium_tlimit = values(1)*model%units%length
            case ("ALIMIT")
                settings%equilibrium_alimit = values(1)
            case ("MAXIT")
                if (values(1) /= aint(values(1)) .or. values(1) > 1.0e6_wp) then
                    call fatal_error(error, at // " must be a whole number of iterations from " &
                        & // "1 to 1000000, got " // to_text(values(1)), stat_input)
                    return
                end if
                settings%equilibrium_maxit = nint(values(1))
            end select
        end associate
    end subroutine read_equilibrium_limit

    !> A REQUEST asks for one thing: DISPLACEMENT, VELOCITY, ACCELERATION or FORCE of its I
    !> marker, or expressions (F1..F8, FUNCTION=USER(...)). A DISPLACEMENT is honoured; the
    !> others are kept (model%other_requests) for the assembly to answer, a FUNCTION=USER one
    !> named in the warning. A REQUEST whose kind is a keyword rollcon does not know is named
    !> in the warning.
    subroutine read_request(path, where, statement, keys, given, marker, unknown, model, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        character(len=*), intent(in) :: keys(:)
        logical, intent(in) :: given(:)
        !> I, J, RM (0: not given)
        integer, intent(in) :: marker(3)
        !> A keyword rollcon does not know was written (and named in the warning)
        logical, intent(in) :: unknown
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        logical :: measured(size(measures)), expressions
        type(adm_request_type) :: request
        integer :: m, user_argument

        do m = 1, size(measures)
            measured(m) = given(name_index(measures(m), keys))
        end do
        expressions = any(given .and. is_one_of(keys, expression_keys))
        if (unknown .and. count(measured) + merge(1, 0, expressions) == 0) return
        if (count(measured) + merge(1, 0, expressions) /= 1) then
            call fatal_error(error, where // ": a REQUEST asks for one of DISPLACEMENT, " &
                & // "VELOCITY, ACCELERATION, FORCE (of its I marker) or expressions (F1..F8, " &
                & // "FUNCTION=USER(...)), got " // to_text(count(measured) &
                & + merge(1, 0, expressions)), stat_input)
            return
        end if
        call request_text(path, where, statement, request, user_argument)
        request%id = statement%id
        request%line = statement%line
        request%i = marker(1)
        request%j = marker(2)
        request%rm = marker(3)
        if (expressions) then
            request%kind = request_expressions
            if (given(name_index("FUNCTION", keys))) then
                ! a REQSUB's: its constants
                request%kind = request_user
                call read_user_list(statement%arguments(user_argument), where // " FUNCTION", &
                    & request%par, error, "REQSUB")
                if (allocated(error)) return
            else
                call check_request_columns(where, request, model, error)
                if (allocated(error)) return
            end if
            call add_request(model%other_requests, model%other_request_count, request)
            return
        end if
        m = findloc(measured, .true., dim=1)
        if (marker(1) == 0) then
            call fatal_error(error, where // " I: " // trim(measures(m)) // " needs the marker " &
                & // "it measures (I=id of a MARKER)", stat_input)
            return
        end if
        request%kind = measure_kinds(m)
        if (m > 1) then
            call add_request(model%other_requests, model%other_request_count, request)
            return
        end if
        call add_request(model%requests, model%request_count, request)
    end subroutine read_request

    !> Each expression F1 ... F8 of a request compiled (a syntax error refused with `where`
    !> and Fk); one that reads what rollcon has no statement for (an element function of a
    !> statement other than JOINT, JPRIM, MOTION, SFORCE, VFORCE, VTORQUE, GFORCE, BUSHING and
    !> SPRINGDAMPER's SPDP) is not answered: its text is cleared and it is named in the
    !> warning ("REQUEST F1..F8 reading BEAM"), as is one it cannot read at all (a function it
    !> lacks, an ORIENT of a system it does not know; a slip in the text): a REQUEST never
    !> stops a run. VARVAL, AKISPL, CUBSPL, DIF, DIF1 and ORIENT are answered: the assembly
    !> puts the VARIABLEs and curves in place as for the forces' expressions
    !> (rollcon_adm_requests), the row's DIFF states and ORIENT's angles are read where the
    !> columns are filled (rollcon_request_answers). A statement rollcon adds is taken off
    !> that list here as it becomes answerable.
    subroutine check_request_columns(where, request, model, error)
        character(len=*), intent(in) :: where
        type(adm_request_type), intent(inout) :: request
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: answered(9) = [character(len=7) :: "JOINT", "JPRIM", &
            & "MOTION", "SFORCE", "VFORCE", "VTORQUE", "GFORCE", "BUSHING", "SPDP"]
        type(expression_type) :: expression
        character(len=:), allocatable :: missing
        integer :: k, n

        do k = 1, size(request%columns)
            if (len(request%columns(k)%text) == 0) cycle
            call compile_expression(request%columns(k)%text, where // " F" // to_text(k), &
                & expression, error)
            if (allocated(error)) then
                ! an expression rollcon cannot read (a function it lacks, an ORIENT system it
                ! does not know, or a slip in the text) only shapes ADAMS's output: named in
                ! the warning, not answered
                call record_unused(model%unused, model%unused_count, "REQUEST F" &
                    & // to_text(k) // " it cannot read (" // after_place(error%message, &
                    & where // " F" // to_text(k) // ": ") // ")", request%line)
                deallocate(error)
                request%columns(k)%text = ""
                cycle
            end if
            missing = ""
            do n = 1, size(expression%inputs)
                associate (quantity => expression%inputs(n)%quantity)
                    if (quantity_kind(quantity) == kind_element .and. .not. any(quantity &
                        & == [quantity_varval, quantity_dif, quantity_dif1])) &
                        & missing = trim(quantity_names(quantity))
                    if (quantity_kind(quantity) == kind_element_force) then
                        if (.not. any(answered == quantity_names(quantity))) &
                            & missing = trim(quantity_names(quantity))
                    end if
                end associate
            end do
            if (len(missing) == 0) cycle
            call record_unused(model%unused, model%unused_count, "REQUEST F1..F8 reading " &
                & // missing, request%line)
            request%columns(k)%text = ""
        end do
    end subroutine check_request_columns

    !> message without its leading place (where), when it starts with it.
    pure function after_place(message, where) result(text)
        character(len=*), intent(in) :: message, where
        character(len=:), allocatable :: text
        integer :: at

        at = index(message, where)
        if (at > 0) then
            text = message(at + len(where):)
        else
            text = message
        end if
    end function after_place

    !> A request's text as written: COMMENT, the expressions F1 ... F8, FUNCTION=USER(...)
    !> and ROUTINE ("" for each not given); the keywords rollcon does not know are skipped.
    subroutine request_text(path, where, statement, request, user_argument)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_request_type), intent(inout) :: request
        !> The place of FUNCTION= among the statement's arguments (0: not given)
        integer, intent(out), optional :: user_argument
        character(len=26), allocatable :: keys(:)
        integer, allocatable :: forms(:)
        type(error_type), allocatable :: refused
        character(len=:), allocatable :: key
        integer :: k, column

        if (present(user_argument)) user_argument = 0
        request%comment = ""
        request%user = ""
        request%routine = ""
        do k = 1, size(request%columns)
            request%columns(k)%text = ""
        end do
        call statement_keywords("REQUEST", keys, forms)
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, keys, key, refused)
            if (allocated(refused)) then
                deallocate(refused)
                cycle
            end if
            select case (key)
            case ("COMMENT")
                request%comment = argument_text(statement%arguments(k))
            case ("FUNCTION")
                request%user = argument_text(statement%arguments(k))
                if (present(user_argument)) user_argument = k
            case ("ROUTINE")
                request%routine = argument_text(statement%arguments(k))
            case ("F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8")
                read(key(2:2), '(i1)') column
                request%columns(column)%text = argument_text(statement%arguments(k))
            end select
        end do
    end subroutine request_text

    !> Append a request to requests(:count) (a dataset's requests or other_requests, and its
    !> count), grown by doubling.
    subroutine add_request(requests, count, request)
        type(adm_request_type), allocatable, intent(inout) :: requests(:)
        integer, intent(inout) :: count
        type(adm_request_type), intent(in) :: request
        type(adm_request_type), allocatable :: grown(:)

        if (.not. allocated(requests)) allocate(requests(0))
        if (count == size(requests)) then
            allocate(grown(max(2*count, least_capacity)))
            grown(:count) = requests(:count)
            call move_alloc(grown, requests)
        end if
        count = count + 1
        requests(count) = request
    end subroutine add_request

    !> One value of form `form` (form_flag ... form_ids) checked; ids: the ids it names (none
    !> for a value that names nothing, ALL included).
    subroutine read_form(argument, at, form, ids, error)
        type(adm_argument_type), intent(in) :: argument
        !> "file:line: STATEMENT/id KEYWORD"
        character(len=*), intent(in) :: at
        integer, intent(in) :: form
        integer, allocatable, intent(out) :: ids(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: values(:)
        integer :: n, i

        allocate(ids(0))
        n = 0
        if (argument%assigned) n = size(argument%values)
        select case (form)
        case (form_flag)
            if (argument%assigned) call fatal_error(error, at // " takes no value", stat_input)
        case (form_number, form_angle)
            call read_reals(argument, at, 1, 1, form == form_angle, values, error)
        case (form_numbers)
            call read_reals(argument, at, 1, huge(1), .false., values, error)
        case (form_whole)
            call read_reals(argument, at, 1, 1, .false., values, error)
            if (allocated(error)) return
            if (.not. (values(1) >= 0.0_wp .and. values(1) == aint(values(1)) .and. &
                & values(1) < real(huge(1), wp))) call fatal_error(error, at // " must be a " &
                & // "whole number >= 0, got " // to_text(values(1)), stat_input)
        case (form_text, form_texts)
            if (n == 0) then
                call fatal_error(error, at // ": expected a value (" // at(index(at, " ", &
                    & back=.true.) + 1:) // "=...)", stat_input)
            else if (len_trim(argument%values(1)%text) == 0) then
                call fatal_error(error, at // ": expected a value, got none", stat_input)
            end if
        case default
            if (n == 0) then
                call fatal_error(error, at // ": expected " // ids_wanted(form), stat_input)
                return
            end if
            if (form >= form_parts .and. n == 1) then
                if (upper_case(trim(argument%values(1)%text)) == "ALL") return
            end if
            if (form == form_marker .and. n > 1) then
                call fatal_error(error, at // ": expected one marker id, got " // to_text(n) &
                    & // " values", stat_input)
                return
            end if
            allocate(values(n))
            do i = 1, n
                values(i) = whole_id(argument%values(i)%text)
                if (values(i) < 0.0_wp .or. (values(i) == 0.0_wp .and. form /= form_marker)) &
                    & then
                    call fatal_error(error, at // ": expected " // ids_wanted(form) // ", got '" &
                        & // argument%values(i)%text // "'", stat_input)
                    return
                end if
            end do
            ids = pack(nint(values), values > 0.0_wp)
        end select
    end subroutine read_form

    !> What a value of an id form must be, in words.
    pure function ids_wanted(form) result(text)
        integer, intent(in) :: form
        character(len=:), allocatable :: text

        select case (form)
        case (form_marker)
            text = "a marker id (a whole number; 0: none)"
        case (form_markers)
            text = "marker ids (positive integers)"
        case default
            text = "ALL or ids (positive integers)"
        end select
    end function ids_wanted

    !> An id as written: its value, or -1 when it is not a whole number of at most 9 digits.
    pure real(wp) function whole_id(written)
        character(len=*), intent(in) :: written
        character(len=:), allocatable :: text
        integer :: stat, value

        whole_id = -1.0_wp
        text = trim(adjustl(written))
        if (len(text) == 0 .or. len(text) > 9 .or. verify(text, "0123456789") > 0) return
        read(text, *, iostat=stat) value
        if (stat == 0) whole_id = real(value, wp)
    end function whole_id

    !> The references of a value read (markers, parts, forces), for rollcon_adm_checks.
    subroutine keep_references(model, at, form, ids)
        type(adm_model_type), intent(inout) :: model
        character(len=*), intent(in) :: at
        integer, intent(in) :: form, ids(:)
        type(adm_reference_type), allocatable :: grown(:)
        integer :: kind, i, j

        select case (form)
        case (form_marker, form_markers)
            kind = refers_to_marker
        case (form_parts)
            kind = refers_to_part
        case (form_forces)
            kind = refers_to_force
        case default
            return
        end select
        if (.not. allocated(model%references)) allocate(model%references(0))
        do i = 1, size(ids)
            if (model%reference_count == size(model%references)) then
                allocate(grown(max(2*model%reference_count, least_capacity)))
                do j = 1, model%reference_count
                    call move_reference(model%references(j), grown(j))
                end do
                call move_alloc(grown, model%references)
            end if
            model%reference_count = model%reference_count + 1
            model%references(model%reference_count) = adm_reference_type(at=at, kind=kind, &
                & id=ids(i))
        end do
    end subroutine keep_references

    !> A reference moved to its place in a grown list (its text moved, not copied).
    subroutine move_reference(from, to)
        type(adm_reference_type), intent(inout) :: from
        type(adm_reference_type), intent(out) :: to

        call move_alloc(from%at, to%at)
        to%kind = from%kind
        to%id = from%id
    end subroutine move_reference

    !> Record `what` (a statement, or a statement and keyword) on `line` as read and not used
    !> (known false: a keyword rollcon does not know, not read): appended to unused(:count),
    !> which grows by doubling.
    subroutine record_unused(unused, count, what, line, known)
        !> A dataset's (adm_model_type's unused, and its unused_count)
        type(adm_unused_type), allocatable, intent(inout) :: unused(:)
        integer, intent(inout) :: count
        character(len=*), intent(in) :: what
        integer, intent(in) :: line
        logical, intent(in), optional :: known
        type(adm_unused_type), allocatable :: grown(:)
        integer :: j

        if (.not. allocated(unused)) allocate(unused(0))
        if (count == size(unused)) then
            allocate(grown(max(2*count, least_capacity)))
            do j = 1, count
                call move_alloc(unused(j)%what, grown(j)%what)
                grown(j)%line = unused(j)%line
                grown(j)%known = unused(j)%known
            end do
            call move_alloc(grown, unused)
        end if
        count = count + 1
        unused(count) = adm_unused_type(what=what, line=line)
        if (present(known)) unused(count)%known = known
    end subroutine record_unused

    !> A REQUEST/id, FORCE whose markers I and J are a JOINT's or JPRIM's (either way round)
    !> and which gives no RM asks for that statement's reaction, which rollcon reports: it
    !> becomes one of model%force_requests (its joint and which way round; the reaction's own
    !> columns, rollcon_reaction_watch). Called once the whole dataset is read (joints may
    !> follow).
    subroutine answer_force_requests(model)
        type(adm_model_type), intent(inout) :: model
        type(adm_request_type), allocatable :: kept(:), answered(:)
        integer :: r, k, n_kept, n_answered

        allocate(kept(0), answered(0))
        n_kept = 0
        n_answered = 0
        if (.not. allocated(model%joints)) allocate(model%joints(0))
        do r = 1, size(model%other_requests)
            associate (request => model%other_requests(r))
                if (request%kind == request_force .and. request%rm == 0) then
                    do k = 1, size(model%joints)
                        if (request%i == model%joints(k)%i .and. request%j &
                            & == model%joints(k)%j) then
                            request%joint = k
                        else if (request%i == model%joints(k)%j .and. request%j &
                            & == model%joints(k)%i) then
                            request%joint = k
                            request%swapped = .true.
                        end if
                        if (request%joint > 0) exit
                    end do
                end if
                if (request%joint == 0) then
                    call add_request(kept, n_kept, request)
                    cycle
                end if
                call add_request(answered, n_answered, request)
            end associate
        end do
        model%other_requests = kept(:n_kept)
        model%other_request_count = n_kept
        model%force_requests = answered(:n_answered)
    end subroutine answer_force_requests

    !> The one warning of a dataset's statements read and not used, each kind with its lines in
    !> the order of the file: "data/x.adm: read and checked but not used: GRAPHICS (lines 14,
    !> 15), INTEGRATOR GSTIFF (line 20); not known to rollcon, not read: GRAPHICS LD (line
    !> 14); rollcon ..."; "" when there is none.
    function unused_warning(model) result(text)
        type(adm_model_type), intent(in) :: model
        character(len=:), allocatable :: text
        character(len=:), allocatable :: known, unknown

        text = ""
        if (.not. allocated(model%unused)) return
        if (size(model%unused) == 0) return
        known = kinds_text(model%unused, .true.)
        unknown = kinds_text(model%unused, .false.)
        if (len(known) > 0) text = "read and checked but not used: " // known
        if (len(unknown) > 0) then
            if (len(text) > 0) text = text // "; "
            text = text // "not known to rollcon, not read: " // unknown
        end if
        text = model%file // ": " // text // "; rollcon writes its own outputs and integrates " &
            & // "with its own INTEGRATOR settings (docs/datasets.md)"
    end function unused_warning

    !> The entries of `unused` whose `known` is known, each kind once with its lines: "GRAPHICS
    !> (lines 14, 15), INTEGRATOR GSTIFF (line 20)"; "" when there is none.
    function kinds_text(unused, known) result(text)
        type(adm_unused_type), intent(in) :: unused(:)
        logical, intent(in) :: known
        character(len=:), allocatable :: text
        character(len=:), allocatable :: lines
        logical :: done(size(unused))
        integer :: i, j, n

        text = ""
        done = unused%known .neqv. known
        do i = 1, size(unused)
            if (done(i)) cycle
            if (len(text) > 0) text = text // ", "
            lines = ""
            n = 0
            do j = i, size(unused)
                if (done(j) .or. unused(j)%what /= unused(i)%what) cycle
                done(j) = .true.
                n = n + 1
                if (n > 1 .and. n <= lines_listed) lines = lines // ", "
                if (n <= lines_listed) lines = lines // to_text(unused(j)%line)
            end do
            if (n > lines_listed) lines = lines // ", ... " // to_text(n) // " in all"
            text = text // unused(i)%what // " (line" // trim(merge("s", " ", n > 1)) &
                & // " " // lines // ")"
        end do
    end function kinds_text

    !> The keywords of statement `name` and the form of each, in the table's order.
    subroutine statement_keywords(name, keys, forms)
        character(len=*), intent(in) :: name
        character(len=26), allocatable, intent(out) :: keys(:)
        integer, allocatable, intent(out) :: forms(:)
        character(len=:), allocatable :: words
        integer :: g, start, blank

        allocate(keys(0), forms(0))
        do g = 1, size(groups)
            if (groups(g)%statement /= name) cycle
            words = trim(groups(g)%keywords) // " "
            start = 1
            do while (start < len(words))
                blank = start + index(words(start:), " ") - 1
                keys = [character(len=26) :: keys, words(start:blank - 1)]
                forms = [forms, groups(g)%form]
                start = blank + 1
            end do
        end do
    end subroutine statement_keywords

    !> For each name, whether it is one of `set`.
    pure function is_one_of(names, set) result(found)
        character(len=*), intent(in) :: names(:), set(:)
        logical :: found(size(names))
        integer :: i

        do i = 1, size(names)
            found(i) = any(set == names(i))
        end do
    end function is_one_of

end module rollcon_adm_outputs
