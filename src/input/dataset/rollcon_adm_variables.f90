! SPDX-License-Identifier: MIT
!> A dataset's VARIABLEs put in place, its SPLINEs given to the expressions that read them,
!> its PINPUTs and POUTPUTs checked (docs/datasets.md, "VARIABLE", "SPLINE", "PINPUT and
!> POUTPUT"), once every statement is read.
!>
!> VARVAL(id) stands for VARIABLE/id's FUNCTION: each VARVAL of an expression is replaced by
!> that expression's own program (variable_program), its inputs merged with the reader's. The
!> value of every expression is then the one ADAMS's algebraic variable gives, and its partials
!> are exact through it: the jets (rollcon_expression_jet) differentiate VARVAL(id) as the
!> expression it names. A VARIABLE that reads itself through others (an algebraic loop, which
!> ADAMS solves by Newton iterations) is refused, naming the statements and their lines.
module rollcon_adm_variables
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_expression, only : expression_type, expression_input_type, op_input, &
        & op_time, op_akispl, op_cubspl, quantity_varval, max_stack, max_inputs, &
        & operation_arity, spline_id_of, quantity_dif, quantity_dif1
    use rollcon_spline, only : spline_type, new_spline
    use rollcon_measures, only : is_state_measure, input_refusal, input_text
    use rollcon_adm_keywords, only : place
    use rollcon_id_index, only : id_index_type, new_id_index
    use rollcon_adm_model, only : adm_model_type, force_sforce, force_vforce
    use rollcon_adm_loads, only : read_user_list
    use rollcon_adm_expression_parser, only : compile_expression
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: resolve_variables, substitute_variables, give_splines, variable_program, &
        & add_plant_warning
    public :: check_diff_reads

    !> The state of a VARIABLE while they are put in place
    integer, parameter :: unresolved = 0, resolving = 1, resolved = 2
    !> Names of a force statement's expression slots
    character(len=*), parameter :: slot_names(6) = [character(len=2) :: "FX", "FY", "FZ", &
        & "TX", "TY", "TZ"]

contains

    !> Every VARVAL of the dataset's expressions (VARIABLEs', forces', MOTIONs', GCONs') read in
    !> place, the curves of its SPLINEs given to every AKISPL and CUBSPL, the VARIABLEs its
    !> PINPUTs and POUTPUTs name checked. Refused, naming the statement and line: a VARVAL of
    !> no VARIABLE; a VARIABLE reading what is not a measure of the state (an acceleration, a
    !> force, DIF or DIF1) or a marker the dataset lacks; an algebraic loop among VARIABLEs; a
    !> MOTION whose VARIABLEs read the state; an expression grown past rollcon_expression's
    !> max_stack or max_inputs; a SPLINE read that is not given, or too short for CUBSPL.
    subroutine resolve_variables(model, error)
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        type(id_index_type) :: ids, markers
        type(spline_type), allocatable :: curves(:)
        integer, allocatable :: state(:), path(:)
        character(len=:), allocatable :: where, key
        integer :: i, k, previous

        if (.not. allocated(model%variables)) allocate(model%variables(0))
        if (.not. allocated(model%splines)) allocate(model%splines(0))
        if (.not. allocated(model%plants)) allocate(model%plants(0))
        if (.not. allocated(model%diffs)) allocate(model%diffs(0))
        ids = new_id_index(size(model%variables))
        do i = 1, size(model%variables)
            call ids%add(int(model%variables(i)%id, int64), i, previous)
        end do
        markers = new_id_index(size(model%markers))
        do i = 1, size(model%markers)
            call markers%add(int(model%markers(i)%id, int64), i, previous)
        end do
        allocate(state(size(model%variables)), source=unresolved)
        do i = 1, size(model%variables)
            if (model%variables(i)%user) then
                ! a VARSUB's: VARVAL(id) stays in the expressions that read it, an input
                ! valued from the routine at run time
                call read_user_list(model%variables(i)%user_argument, &
                    & model%variables(i)%user_at, model%variables(i)%par, error, "VARSUB")
                if (allocated(error)) return
                call compile_expression("VARVAL(" // to_text(model%variables(i)%id) // ")", &
                    & model%variables(i)%user_at, model%variables(i)%function, error)
                if (allocated(error)) return
                state(i) = resolved
                cycle
            end if
            call check_variable(model, markers, i, error)
            if (allocated(error)) return
        end do
        allocate(path(0))
        do i = 1, size(model%variables)
            if (state(i) == resolved) cycle
            call resolve_one(model, ids, i, state, path, error)
            if (allocated(error)) return
        end do
        ! the expressions of the statements simulated
        do i = 1, size(model%forces)
            do k = 1, 6
                if (.not. model%forces(i)%given(k)) cycle
                key = slot_names(k)
                if (model%forces(i)%kind == force_sforce) key = "FUNCTION"
                where = place(model%file, model%forces(i)%line) // ": " &
                    & // force_name(model%forces(i)%kind) // "/" &
                    & // to_text(model%forces(i)%id) // " " // key
                call substitute(model, ids, model%forces(i)%functions(k), where, error)
                if (allocated(error)) return
            end do
        end do
        if (allocated(model%motions)) then
            do i = 1, size(model%motions)
                if (model%motions(i)%user) then
                    ! a MOTSUB's: its constants; it has no expression
                    call read_user_list(model%motions(i)%user_argument, &
                        & model%motions(i)%user_at, model%motions(i)%par, error, "MOTSUB")
                    if (allocated(error)) return
                    cycle
                end if
                where = place(model%file, model%motions(i)%line) // ": MOTION/" &
                    & // to_text(model%motions(i)%id) // " FUNCTION"
                call substitute(model, ids, model%motions(i)%function, where, error)
                if (allocated(error)) return
                call refuse_user_variables(model%motions(i)%function, where, "a MOTION's " &
                    & // "function, whose derivatives in time rollcon takes exactly", error)
                if (allocated(error)) return
                if (size(model%motions(i)%function%inputs) > 0) then
                    call fatal_error(error, where // ": a MOTION's function is an expression " &
                        & // "of TIME alone (ADAMS's rule: the motion it prescribes may not " &
                        & // "depend on the state), but through its VARIABLEs it reads " &
                        & // input_text(model%motions(i)%function%inputs(1)), stat_input)
                    return
                end if
            end do
        end if
        if (allocated(model%gcons)) then
            do i = 1, size(model%gcons)
                where = place(model%file, model%gcons(i)%line) // ": GCON/" &
                    & // to_text(model%gcons(i)%id) // " FUNCTION"
                call substitute(model, ids, model%gcons(i)%function, where, error)
                if (allocated(error)) return
                call refuse_user_variables(model%gcons(i)%function, where, "a GCON's " &
                    & // "function, a constraint whose partials rollcon takes exactly", error)
                if (allocated(error)) return
            end do
        end if
        ! the curves
        allocate(curves(size(model%splines)))
        do i = 1, size(model%splines)
            call fit(model, i, curves(i), error)
            if (allocated(error)) return
        end do
        do i = 1, size(model%variables)
            where = variable_place(model, i) // " FUNCTION"
            call give_curves(model, curves, model%variables(i)%function, where, error)
            if (allocated(error)) return
        end do
        do i = 1, size(model%forces)
            do k = 1, 6
                if (.not. model%forces(i)%given(k)) cycle
                where = place(model%file, model%forces(i)%line) // ": " &
                    & // force_name(model%forces(i)%kind) // "/" // to_text(model%forces(i)%id)
                call give_curves(model, curves, model%forces(i)%functions(k), where, error)
                if (allocated(error)) return
            end do
        end do
        if (allocated(model%gcons)) then
            do i = 1, size(model%gcons)
                where = place(model%file, model%gcons(i)%line) // ": GCON/" &
                    & // to_text(model%gcons(i)%id) // " FUNCTION"
                call give_curves(model, curves, model%gcons(i)%function, where, error)
                if (allocated(error)) return
            end do
        end if
        if (allocated(model%motions)) then
            do i = 1, size(model%motions)
                if (model%motions(i)%user) cycle
                where = place(model%file, model%motions(i)%line) // ": MOTION/" &
                    & // to_text(model%motions(i)%id) // " FUNCTION"
                call give_curves(model, curves, model%motions(i)%function, where, error)
                if (allocated(error)) return
            end do
        end if
        do i = 1, size(model%diffs)
            if (model%diffs(i)%user) then
                ! a DIFSUB's: its constants
                call read_user_list(model%diffs(i)%user_argument, model%diffs(i)%user_at, &
                    & model%diffs(i)%par, error, "DIFSUB")
                if (allocated(error)) return
                cycle
            end if
            where = place(model%file, model%diffs(i)%line) // ": DIFF/" &
                & // to_text(model%diffs(i)%id) // " FUNCTION"
            call substitute(model, ids, model%diffs(i)%function, where, error)
            if (allocated(error)) return
            call give_curves(model, curves, model%diffs(i)%function, where, error)
            if (allocated(error)) return
        end do
        call check_diff_reads(model, error)
        if (allocated(error)) return
        call check_plants(model, ids, error)
    end subroutine resolve_variables

    !> Every DIF(id) and DIF1(id) of the expressions simulated (forces', DIFFs', VARIABLEs')
    !> names a DIFF of the dataset; refused, naming the statement and line, when not.
    subroutine check_diff_reads(model, error)
        type(adm_model_type), intent(in) :: model
        type(error_type), allocatable, intent(out) :: error
        integer :: i, k

        do i = 1, size(model%diffs)
            call check_reads(model%diffs(i)%function, place(model%file, model%diffs(i)%line) &
                & // ": DIFF/" // to_text(model%diffs(i)%id) // " FUNCTION")
            if (allocated(error)) return
        end do
        do i = 1, size(model%variables)
            call check_reads(model%variables(i)%function, variable_place(model, i) &
                & // " FUNCTION")
            if (allocated(error)) return
        end do
        do i = 1, size(model%forces)
            do k = 1, 6
                if (.not. model%forces(i)%given(k)) cycle
                call check_reads(model%forces(i)%functions(k), place(model%file, &
                    & model%forces(i)%line) // ": " // force_name(model%forces(i)%kind) &
                    & // "/" // to_text(model%forces(i)%id) // " " // trim(merge("FUNCTION", &
                    & slot_names(k) // "      ", model%forces(i)%kind == force_sforce)))
                if (allocated(error)) return
            end do
        end do

    contains

        !> The DIFs of one expression, read at `where`.
        subroutine check_reads(expression, where)
            type(expression_type), intent(in) :: expression
            character(len=*), intent(in) :: where
            integer :: n

            if (.not. allocated(expression%inputs)) return
            do n = 1, size(expression%inputs)
                associate (input => expression%inputs(n))
                    if (input%quantity /= quantity_dif .and. input%quantity /= quantity_dif1) &
                        & cycle
                    if (any(model%diffs%id == input%marker)) cycle
                    call fatal_error(error, where // ": " // input_text(input) // ": no DIFF/" &
                        & // to_text(input%marker) // " in the dataset", stat_input)
                    return
                end associate
            end do
        end subroutine check_reads
    end subroutine check_diff_reads

    !> `expression` (read at `where`, "file:line: REQUEST/3 F2") with each VARVAL(id) replaced
    !> by VARIABLE/id's FUNCTION as variable_program gives it, the model's VARIABLEs already put
    !> in place (resolve_variables). For the expressions a dataset's reader compiles once
    !> resolve_variables has run.
    subroutine substitute_variables(model, expression, where, error)
        type(adm_model_type), intent(in) :: model
        type(expression_type), intent(inout) :: expression
        character(len=*), intent(in) :: where
        type(error_type), allocatable, intent(out) :: error
        type(id_index_type) :: ids
        integer :: i, previous

        if (.not. allocated(model%variables)) return
        ids = new_id_index(size(model%variables))
        do i = 1, size(model%variables)
            call ids%add(int(model%variables(i)%id, int64), i, previous)
        end do
        call substitute(model, ids, expression, where, error)
    end subroutine substitute_variables

    !> The curves every AKISPL and CUBSPL of `expression` (read at `where`, "file:line:
    !> REQUEST/3 F2") reads, fitted from the dataset's SPLINEs and given to it as
    !> resolve_variables gives them to the statements' expressions; refused as there: a SPLINE
    !> the dataset lacks, CUBSPL of fewer than four points. For the expressions a dataset's
    !> reader compiles once resolve_variables has run.
    subroutine give_splines(model, expression, where, error)
        type(adm_model_type), intent(in) :: model
        type(expression_type), intent(inout) :: expression
        character(len=*), intent(in) :: where
        type(error_type), allocatable, intent(out) :: error
        type(spline_type), allocatable :: curves(:)
        integer :: i

        if (.not. allocated(expression%op)) return
        if (.not. any(expression%op == op_akispl .or. expression%op == op_cubspl)) return
        allocate(curves(0))
        if (allocated(model%splines)) then
            deallocate(curves)
            allocate(curves(size(model%splines)))
            do i = 1, size(model%splines)
                call fit(model, i, curves(i), error)
                if (allocated(error)) return
            end do
        end if
        call give_curves(model, curves, expression, where, error)
    end subroutine give_splines

    !> The expression VARVAL(id) stands for: VARIABLE/id's FUNCTION, in the dataset's units,
    !> its own VARVALs in place (its VARIABLE is at `v` in model%variables). The one place a
    !> VARIABLE's value is defined: a VARIABLE of a user's routine (a VARSUB) gives VARVAL(id)
    !> itself, an input valued from the routine at run time.
    function variable_program(model, v) result(program)
        type(adm_model_type), intent(in) :: model
        integer, intent(in) :: v
        type(expression_type) :: program

        program = model%variables(v)%function
    end function variable_program

    !> An expression that needs exact derivatives (`what`: a MOTION's, a GCON's) reading a
    !> VARSUB's VARIABLE, whose derivatives rollcon does not know, is refused naming `where`.
    subroutine refuse_user_variables(expression, where, what, error)
        type(expression_type), intent(in) :: expression
        character(len=*), intent(in) :: where, what
        type(error_type), allocatable, intent(out) :: error
        integer :: n

        if (.not. allocated(expression%inputs)) return
        n = findloc(expression%inputs%quantity, quantity_varval, dim=1)
        if (n == 0) return
        call fatal_error(error, where // ": " // input_text(expression%inputs(n)) // " is " &
            & // "the value of a VARSUB (FUNCTION=USER(...)), whose derivatives rollcon does " &
            & // "not know, read in " // what // "; write that VARIABLE as a FUNCTION " &
            & // "expression", stat_input)
    end subroutine refuse_user_variables

    !> A VARIABLE's FUNCTION reads TIME, measures of the state of markers the dataset has, and
    !> other VARIABLEs.
    subroutine check_variable(model, markers, v, error)
        type(adm_model_type), intent(in) :: model
        !> The markers' ids
        type(id_index_type), intent(in) :: markers
        integer, intent(in) :: v
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: problem, where
        integer :: n, m, ids(4)

        where = variable_place(model, v) // " FUNCTION"
        associate (function => model%variables(v)%function)
            do n = 1, size(function%inputs)
                associate (input => function%inputs(n))
                    if (input%quantity == quantity_varval) cycle
                    problem = input_refusal(input, "a VARIABLE's FUNCTION")
                    if (len(problem) > 0) then
                        call fatal_error(error, where // ": " // problem, stat_input)
                        return
                    end if
                    if (input%quantity == quantity_dif .or. input%quantity == quantity_dif1) &
                        & cycle
                    ids = [input%marker, input%j, input%k, input%l]
                    do m = 1, 4
                        if (ids(m) == 0) cycle
                        if (markers%find(int(ids(m), int64)) /= 0) cycle
                        call fatal_error(error, where // ": " // input_text(input) &
                            & // ": no MARKER/" // to_text(ids(m)) // " in the dataset", &
                            & stat_input)
                        return
                    end do
                end associate
            end do
        end associate
    end subroutine check_variable

    !> VARIABLE v put in place, the VARIABLEs it reads first (depth first); `path` the ones
    !> being put in place, in order, for the message of a loop.
    recursive subroutine resolve_one(model, ids, v, state, path, error)
        type(adm_model_type), intent(inout) :: model
        type(id_index_type), intent(in) :: ids
        integer, intent(in) :: v
        integer, intent(inout) :: state(:)
        integer, allocatable, intent(inout) :: path(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: loop
        integer :: n, w, first, m, next

        state(v) = resolving
        path = [path, v]
        associate (inputs => model%variables(v)%function%inputs)
            do n = 1, size(inputs)
                if (inputs(n)%quantity /= quantity_varval) cycle
                w = ids%find(int(inputs(n)%marker, int64))
                if (w == 0) then
                    call fatal_error(error, variable_place(model, v) // " FUNCTION: " &
                        & // input_text(inputs(n)) // ": no VARIABLE/" &
                        & // to_text(inputs(n)%marker) // " in the dataset", stat_input)
                    return
                end if
                if (state(w) == resolving) then
                    first = findloc(path, w, dim=1)
                    loop = ""
                    do m = first, size(path)
                        next = w
                        if (m < size(path)) next = path(m + 1)
                        loop = loop // variable_place(model, path(m)) // " reads VARVAL(" &
                            & // to_text(model%variables(next)%id) // "); "
                    end do
                    call fatal_error(error, loop // "an algebraic loop among VARIABLEs, which " &
                        & // "rollcon does not solve: write one of them without the others " &
                        & // "(docs/datasets.md, VARIABLE)", stat_input)
                    return
                end if
                if (state(w) == unresolved) then
                    call resolve_one(model, ids, w, state, path, error)
                    if (allocated(error)) return
                end if
            end do
        end associate
        call substitute(model, ids, model%variables(v)%function, variable_place(model, v) &
            & // " FUNCTION", error)
        if (allocated(error)) return
        state(v) = resolved
        path = path(:size(path) - 1)
    end subroutine resolve_one

    !> Each VARVAL(id) of `expression` replaced by variable_program's expression, its inputs
    !> merged with the expression's (each distinct input once); the VARIABLEs read must be
    !> put in place already.
    subroutine substitute(model, ids, expression, where, error)
        type(adm_model_type), intent(in) :: model
        type(id_index_type), intent(in) :: ids
        type(expression_type), intent(inout) :: expression
        character(len=*), intent(in) :: where
        type(error_type), allocatable, intent(out) :: error
        type(expression_input_type), allocatable :: inputs(:)
        type(expression_type) :: inner
        integer, allocatable :: op(:)
        real(wp), allocatable :: constant(:)
        integer :: i, k, w, n, depth, top

        if (.not. allocated(expression%inputs)) return
        if (.not. any(expression%inputs%quantity == quantity_varval)) return
        allocate(op(0), constant(0), inputs(0))
        do i = 1, size(expression%op)
            if (expression%op(i) /= op_input) then
                op = [op, expression%op(i)]
                constant = [constant, expression%constant(i)]
                cycle
            end if
            associate (input => expression%inputs(nint(expression%constant(i))))
                if (input%quantity /= quantity_varval) then
                    op = [op, op_input]
                    constant = [constant, real(merged(inputs, input), wp)]
                    cycle
                end if
                w = ids%find(int(input%marker, int64))
                if (w == 0) then
                    call fatal_error(error, where // ": " // input_text(input) &
                        & // ": no VARIABLE/" // to_text(input%marker) // " in the dataset", &
                        & stat_input)
                    return
                end if
            end associate
            inner = variable_program(model, w)
            do k = 1, size(inner%op)
                op = [op, inner%op(k)]
                if (inner%op(k) == op_input) then
                    constant = [constant, real(merged(inputs, &
                        & inner%inputs(nint(inner%constant(k)))), wp)]
                else
                    constant = [constant, inner%constant(k)]
                end if
            end do
        end do
        ! the pending values of the stack program, at their most
        depth = 0
        top = 0
        do i = 1, size(op)
            n = operation_arity(op(i), constant(i))
            top = top - n + 1
            depth = max(depth, top)
        end do
        if (depth > max_stack .or. size(inputs) > max_inputs) then
            call fatal_error(error, where // ": with its VARIABLEs in place the expression " &
                & // "needs " // to_text(depth) // " pending values and " &
                & // to_text(size(inputs)) // " measures; rollcon takes at most " &
                & // to_text(max_stack) // " and " // to_text(max_inputs), stat_input)
            return
        end if
        expression%op = op
        expression%constant = constant
        expression%inputs = inputs
        expression%uses_time = any(op == op_time)
        if (allocated(expression%anchors)) deallocate(expression%anchors)
        allocate(expression%anchors(size(inputs)), source=0.0_wp)
    end subroutine substitute

    !> The place of `input` among `inputs`, added at their end when it is not there.
    integer function merged(inputs, input) result(k)
        type(expression_input_type), allocatable, intent(inout) :: inputs(:)
        type(expression_input_type), intent(in) :: input

        do k = 1, size(inputs)
            if (inputs(k)%marker == input%marker .and. inputs(k)%quantity == input%quantity &
                & .and. inputs(k)%j == input%j .and. inputs(k)%k == input%k .and. &
                & inputs(k)%l == input%l) return
        end do
        inputs = [inputs, input]
        k = size(inputs)
    end function merged

    !> SPLINE i's curve (its points checked as the reader did: rollcon_spline's own rules).
    subroutine fit(model, i, curve, error)
        type(adm_model_type), intent(in) :: model
        integer, intent(in) :: i
        type(spline_type), intent(out) :: curve
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: problem

        associate (spline => model%splines(i))
            call new_spline(spline%id, spline%x, spline%y, curve, problem, &
                & spline%linear_extrapolate)
            if (len(problem) > 0) call fatal_error(error, place(model%file, spline%line) &
                & // ": SPLINE/" // to_text(spline%id) // ": " // problem, stat_input)
        end associate
    end subroutine fit

    !> The curves every AKISPL and CUBSPL of `expression` reads, given to it; refused: a SPLINE
    !> the dataset lacks, CUBSPL of fewer than four points.
    subroutine give_curves(model, curves, expression, where, error)
        type(adm_model_type), intent(in) :: model
        type(spline_type), intent(in) :: curves(:)
        type(expression_type), intent(inout) :: expression
        character(len=*), intent(in) :: where
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name
        integer :: k, id, s

        if (.not. allocated(expression%op)) return
        do k = 1, size(expression%op)
            if (expression%op(k) /= op_akispl .and. expression%op(k) /= op_cubspl) cycle
            name = trim(merge("AKISPL", "CUBSPL", expression%op(k) == op_akispl))
            id = spline_id_of(expression%constant(k))
            s = 0
            if (size(curves) > 0) s = findloc(curves%id, id, dim=1)
            if (s == 0) then
                call fatal_error(error, where // ": " // name // " reads SPLINE/" &
                    & // to_text(id) // ", which the dataset lacks", stat_input)
                return
            end if
            if (expression%op(k) == op_cubspl .and. size(curves(s)%x) < 4) then
                call fatal_error(error, where // ": CUBSPL reads SPLINE/" // to_text(id) &
                    & // " (line " // to_text(model%splines(s)%line) // "), of " &
                    & // to_text(size(curves(s)%x)) // " points; a cubic spline needs at " &
                    & // "least 4", stat_input)
                return
            end if
            if (.not. allocated(expression%splines)) allocate(expression%splines(0))
            if (size(expression%splines) > 0) then
                if (any(expression%splines%id == id)) cycle
            end if
            expression%splines = [expression%splines, curves(s)]
        end do
    end subroutine give_curves

    !> Every VARIABLE a PINPUT or POUTPUT names exists.
    subroutine check_plants(model, ids, error)
        type(adm_model_type), intent(in) :: model
        type(id_index_type), intent(in) :: ids
        type(error_type), allocatable, intent(out) :: error
        integer :: i, k

        do i = 1, size(model%plants)
            associate (plant => model%plants(i))
                do k = 1, size(plant%variables)
                    if (ids%find(int(plant%variables(k), int64)) /= 0) cycle
                    call fatal_error(error, place(model%file, plant%line) // ": " &
                        & // trim(merge("POUTPUT", "PINPUT ", plant%output)) // "/" &
                        & // to_text(plant%id) // " VARIABLES: no VARIABLE/" &
                        & // to_text(plant%variables(k)) // " in the dataset", stat_input)
                    return
                end do
            end associate
        end do
    end subroutine check_plants

    !> The PINPUTs and POUTPUTs named in the model's warning: "PINPUT/1 (line 11; VARIABLES
    !> 1): a controls plant's inputs and outputs, which do nothing in a stand-alone run".
    subroutine add_plant_warning(model)
        type(adm_model_type), intent(inout) :: model
        character(len=:), allocatable :: text
        integer :: i, k

        if (.not. allocated(model%plants)) return
        if (size(model%plants) == 0) return
        text = ""
        do i = 1, size(model%plants)
            associate (plant => model%plants(i))
                if (i > 1) text = text // ", "
                text = text // trim(merge("POUTPUT", "PINPUT ", plant%output)) // "/" &
                    & // to_text(plant%id) // " (line " // to_text(plant%line) &
                    & // "; VARIABLES "
                do k = 1, size(plant%variables)
                    if (k > 1) text = text // ", "
                    text = text // to_text(plant%variables(k))
                end do
                text = text // ")"
            end associate
        end do
        text = text // ": a controls plant's inputs and outputs, read and checked; they do " &
            & // "nothing in a stand-alone run (its VARIABLEs are computed and written as " &
            & // "columns var<id>)"
        if (.not. allocated(model%warning)) model%warning = ""
        if (len(model%warning) == 0) then
            model%warning = model%file // ": " // text
        else
            model%warning = model%warning // "; " // text
        end if
    end subroutine add_plant_warning

    !> "file:line: VARIABLE/id" of VARIABLE v.
    function variable_place(model, v) result(text)
        type(adm_model_type), intent(in) :: model
        integer, intent(in) :: v
        character(len=:), allocatable :: text

        text = place(model%file, model%variables(v)%line) // ": VARIABLE/" &
            & // to_text(model%variables(v)%id)
    end function variable_place

    pure function force_name(kind) result(name)
        integer, intent(in) :: kind
        character(len=:), allocatable :: name

        select case (kind)
        case (force_sforce)
            name = "SFORCE"
        case (force_vforce)
            name = "VFORCE"
        case default
            name = "GFORCE"
        end select
    end function force_name

end module rollcon_adm_variables
