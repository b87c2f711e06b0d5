! SPDX-License-Identifier: MIT
!> A dataset's REQUESTs of velocity, acceleration, force (those no JOINT or JPRIM answers) and
!> expressions F1 ... F8, made the columns of rollcon_request_answers: their markers as the
!> model holds them, each expression compiled (a syntax error names the file, line, REQUEST and
!> Fk, as the reader found it) and every id it reads checked: a marker the dataset lacks, or
!> an element function naming a statement that is not there (`JOINT(7, 0, 2, 0)`: no
!> JOINT/7), is refused with the statement and line. Each VARVAL(id) stands for VARIABLE/id's
!> FUNCTION (a VARSUB's value is read as the routine gives it) and each AKISPL and CUBSPL reads
!> its SPLINE's curve, put in place as in the forces' expressions (rollcon_adm_variables'
!> substitute_variables and give_splines; a VARIABLE or SPLINE the dataset lacks is refused
!> the same way). The elements the force functions read are every JOINT and JPRIM the model
!> holds, MOTION, SFORCE, VFORCE, VTORQUE, GFORCE, BUSHING and SPRINGDAMPER. A REQUEST with
!> FUNCTION=USER(...) is served by the user's REQSUB (the model's own, or the one its
!> ROUTINE= names; refused with the statement and line when there is none).
module rollcon_adm_requests
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, place
    use rollcon_marker, only : marker_type
    use rollcon_expression, only : expression_type, quantity_kind, quantity_names, &
        & kind_element_force, quantity_varval, quantity_dif, quantity_dif1
    use rollcon_measures, only : input_text
    use rollcon_model, only : model_type, statement_joint, statement_jprim
    use rollcon_force, only : profile_statement
    use rollcon_problem, only : problem_type
    use rollcon_request_answers, only : answered_request_type, request_element_type, &
        & new_request_answer_watch, element_kind_of, answer_velocity, answer_acceleration, &
        & answer_force, answer_expressions, answer_user, element_joint, element_jprim, &
        & element_motion, element_sforce, element_vforce, element_gforce, element_vtorque, &
        & element_bushing, element_springdamper
    use rollcon_adm_model, only : adm_model_type, force_sforce, force_vforce, force_vtorque, &
        & force_bushing, force_springdamper, request_velocity, request_acceleration, &
        & request_force, request_expressions, request_user
    use rollcon_adm_variables, only : substitute_variables, give_splines
    use rollcon_system_routine_contract, only : routine_reqsub, request_routine_name
    use rollcon_user_ucosubs, only : find_named_routine
    use rollcon_adm_markers, only : adm_marker, marker_index
    use rollcon_adm_expression_parser, only : compile_expression
    implicit none
    private

    public :: add_request_answers

contains

    !> The watch answering the dataset's other requests (adm%other_requests but FUNCTION=USER),
    !> added to the problem when there is one; the problem's model is set up.
    subroutine add_request_answers(adm, problem, error)
        type(adm_model_type), intent(in) :: adm
        type(problem_type), intent(inout) :: problem
        type(error_type), allocatable, intent(out) :: error
        type(answered_request_type), allocatable :: requests(:)
        type(request_element_type), allocatable :: elements(:)
        type(marker_type), allocatable :: markers(:)
        type(answered_request_type) :: request
        character(len=:), allocatable :: where
        integer :: r, k, n

        if (.not. allocated(adm%other_requests)) return
        allocate(requests(0), markers(0))
        elements = model_elements(adm, problem%model)
        do r = 1, size(adm%other_requests)
            associate (given => adm%other_requests(r))
                where = place(adm%file, given%line) // ": REQUEST/" // to_text(given%id)
                request = answered_request_type(id=given%id)
                select case (given%kind)
                case (request_velocity)
                    request%kind = answer_velocity
                case (request_acceleration)
                    request%kind = answer_acceleration
                case (request_force)
                    request%kind = answer_force
                case (request_expressions)
                    request%kind = answer_expressions
                case (request_user)
                    request%kind = answer_user
                    call user_request(given%routine, where, request%routine, error)
                    if (allocated(error)) return
                    request%par = given%par
                    request%name = where
                case default
                    cycle
                end select
                if (given%i /= 0) request%i = adm_marker(adm, given%i)
                if (given%j /= 0) request%j = adm_marker(adm, given%j)
                if (given%rm /= 0) request%rm = adm_marker(adm, given%rm)
                if (request%kind == answer_expressions) then
                    do k = 1, 8
                        if (len(given%columns(k)%text) == 0) cycle
                        call compile_expression(given%columns(k)%text, where // " F" &
                            & // to_text(k), request%functions(k), error)
                        if (allocated(error)) return
                        call substitute_variables(adm, request%functions(k), where // " F" &
                            & // to_text(k), error)
                        if (allocated(error)) return
                        call give_splines(adm, request%functions(k), where // " F" &
                            & // to_text(k), error)
                        if (allocated(error)) return
                        call check_inputs(adm, elements, request%functions(k), where // " F" &
                            & // to_text(k), markers, error)
                        if (allocated(error)) return
                        request%given(k) = .true.
                    end do
                end if
                n = size(requests)
                requests = [requests, request]
            end associate
        end do
        if (size(requests) == 0) return
        call problem%add_watch(new_request_answer_watch(requests, elements, markers, &
            & adm%units%length, adm%units%time, adm%units%force))
    end subroutine add_request_answers

    !> The entry of the REQSUB serving a REQUEST's FUNCTION=USER (rollcon_user_forces' table):
    !> the model's own, or the one ROUTINE= names. Refused when there is none, naming the
    !> statement and what to give.
    subroutine user_request(routine, where, entry, error)
        !> ROUTINE= as written ("" when not given)
        character(len=*), intent(in) :: routine
        !> "data/x.adm:12: REQUEST/5"
        character(len=*), intent(in) :: where
        integer, intent(out) :: entry
        type(error_type), allocatable, intent(out) :: error

        entry = find_named_routine(routine_reqsub, routine)
        if (entry > 0) return
        if (len(routine) == 0) then
            call fatal_error(error, where // " FUNCTION=USER(...): no " // request_routine_name &
                & // " serves it; give the file that defines SUBROUTINE " &
                & // request_routine_name // " (rollcon run MODEL --ucosub FILE; it runs in a " &
                & // "process of its own)", stat_input)
        else
            call fatal_error(error, where // " ROUTINE=" // routine // ": no " &
                & // request_routine_name // " of that name among the user's files; " &
                & // "ROUTINE=FILE::" // request_routine_name // " names the routine of FILE " &
                & // "(given with --ucosub FILE; FILE as given, or its name without folder " &
                & // "and extension)", stat_input)
        end if
    end subroutine user_request

    !> The elements whose forces the force functions read, with their markers as the model
    !> holds them (module header).
    function model_elements(adm, model) result(elements)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(in) :: model
        type(request_element_type), allocatable :: elements(:)
        type(request_element_type) :: element
        integer :: s, k, f, joint

        allocate(elements(0))
        if (allocated(model%statements)) then
            do s = 1, size(model%statements)
                associate (statement => model%statements(s))
                    if (statement%kind /= statement_joint .and. statement%kind &
                        & /= statement_jprim) cycle
                    element = request_element_type(kind=merge(element_joint, element_jprim, &
                        & statement%kind == statement_joint), id=statement%id, &
                        & i=statement%i, j=statement%j, place=s)
                    elements = [elements, element]
                end associate
            end do
        end if
        if (allocated(adm%motions) .and. allocated(model%ucons)) then
            do k = 1, size(model%ucons)
                if (.not. allocated(model%ucons(k)%motion)) cycle
                associate (id => model%ucons(k)%motion%id)
                    f = findloc(adm%motions%id, id, dim=1)
                    if (f == 0) cycle
                    element = request_element_type(kind=element_motion, id=id, place=k)
                    associate (motion => adm%motions(f))
                        if (motion%joint /= 0) then
                            joint = findloc(adm%joints%id, motion%joint, dim=1, &
                                & mask=.not. adm%joints%primitive)
                            element%i = adm_marker(adm, adm%joints(joint)%i)
                            element%j = adm_marker(adm, adm%joints(joint)%j)
                        else
                            element%i = adm_marker(adm, motion%i)
                            if (motion%j /= 0) element%j = adm_marker(adm, motion%j)
                        end if
                    end associate
                    elements = [elements, element]
                end associate
            end do
        end if
        ! the dataset's SFORCE, VFORCE, VTORQUE, GFORCE, SPRINGDAMPER and BUSHING statements
        ! are the model's first forces of a statement, in the order of the file
        ! (rollcon_adm_build)
        if (.not. allocated(adm%forces) .or. .not. allocated(model%forces)) return
        f = 0
        do k = 1, size(model%forces)
            if (model%forces(k)%profile /= profile_statement) cycle
            f = f + 1
            if (f > size(adm%forces)) exit
            associate (statement => adm%forces(f))
                select case (statement%kind)
                case (force_sforce)
                    element%kind = element_sforce
                case (force_vforce)
                    element%kind = element_vforce
                case (force_vtorque)
                    element%kind = element_vtorque
                case (force_bushing)
                    element%kind = element_bushing
                case (force_springdamper)
                    element%kind = element_springdamper
                case default
                    element%kind = element_gforce
                end select
                element%id = statement%id
                element%place = k
                element%i = model%forces(k)%statement%i
                element%j = model%forces(k)%statement%j
                if (statement%j == 0) element%j = marker_type()
            end associate
            elements = [elements, element]
        end do
    end function model_elements

    !> Every id an expression of a REQUEST reads exists (module header); the markers it reads
    !> added to `markers` (once each); a DIF(id) or DIF1(id) names a DIFF of the dataset.
    !> `where`: "file:line: REQUEST/id Fk". What rollcon has no statement for (BEAM(...)) the
    !> reader took out of the request and named in the warning (rollcon_adm_outputs).
    subroutine check_inputs(adm, elements, expression, where, markers, error)
        type(adm_model_type), intent(in) :: adm
        type(request_element_type), intent(in) :: elements(:)
        type(expression_type), intent(in) :: expression
        character(len=*), intent(in) :: where
        type(marker_type), allocatable, intent(inout) :: markers(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: statement
        integer :: n, m, ids(4), kind

        do n = 1, size(expression%inputs)
            associate (input => expression%inputs(n))
                ! a VARSUB's VARIABLE (VARVAL(id) left in place): no marker
                if (input%quantity == quantity_varval) cycle
                if (input%quantity == quantity_dif .or. input%quantity == quantity_dif1) then
                    if (any(adm%diffs%id == input%marker)) cycle
                    call fatal_error(error, where // ": " // input_text(input) // ": no DIFF/" &
                        & // to_text(input%marker) // " in the dataset", stat_input)
                    return
                end if
                ids = [input%marker, input%j, input%k, input%l]
                if (quantity_kind(input%quantity) == kind_element_force) then
                    kind = element_kind_of(input%quantity)
                    if (.not. any(elements%kind == kind .and. elements%id == input%marker)) then
                        statement = trim(quantity_names(input%quantity))
                        if (kind == element_springdamper) statement = "SPRINGDAMPER"
                        call fatal_error(error, where // ": " // input_text(input) // ": no " &
                            & // statement // "/" // to_text(input%marker) // " whose force " &
                            & // "rollcon reports in the dataset", stat_input)
                        if (kind == element_joint) error%message = error%message // " (a " &
                            & // "RACKPIN or SCREW joint is a coupling, not reported)"
                        return
                    end if
                    ids = [0, 0, 0, input%l]
                end if
                do m = 1, 4
                    if (ids(m) == 0) cycle
                    if (marker_index(adm, ids(m)) == 0) then
                        call fatal_error(error, where // ": " // input_text(input) &
                            & // ": no MARKER/" // to_text(ids(m)) // " in the dataset", &
                            & stat_input)
                        return
                    end if
                    if (.not. any(markers%id == ids(m))) &
                        & markers = [markers, adm_marker(adm, ids(m))]
                end do
            end associate
        end do
    end subroutine check_inputs

end module rollcon_adm_requests
