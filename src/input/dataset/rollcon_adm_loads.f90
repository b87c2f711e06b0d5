! SPDX-License-Identifier: MIT
!> Dataset statements of loads and constraints: UCON, ACCGRAV, the SFORCE, VFORCE, GFORCE and
!> VTORQUE statements with their function expressions, and the SPRINGDAMPER and BUSHING
!> statements with their constants.
module rollcon_adm_loads
    use rollcon_physical_ranges, only : gravity_max
    use rollcon_text, only : to_text
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_adm_lexer, only : adm_statement_type, adm_argument_type
    use rollcon_adm_keywords, only : read_reals, read_integer, argument_key, arg_place, &
        & name_index, argument_text
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_adm_model, only : adm_model_type, adm_ucon_type, adm_force_type, force_sforce, &
        & force_vforce, force_gforce, force_springdamper, force_bushing, force_vtorque
    use rollcon_adm_units, only : units_type
    implicit none
    private

    public :: read_ucon, read_accgrav, read_force, read_spring, read_user_list

    character(len=*), parameter :: ucon_keys(2) = [character(len=8) :: "FUNCTION", "ROUTINE"]
    character(len=*), parameter :: accgrav_keys(3) = ["IGRAV", "JGRAV", "KGRAV"]
    !> SFORCE's keywords; TRANSLATIONAL and ROTATIONAL are ADAMS's other spellings of
    !> TRANSLATION and ROTATION (ADAMS/View writes them)
    character(len=*), parameter :: sforce_keys(9) = [character(len=13) :: "I", "J", &
        & "TRANSLATION", "ROTATION", "ACTIONONLY", "FUNCTION", "TRANSLATIONAL", "ROTATIONAL", &
        & "ROUTINE"]
    character(len=*), parameter :: gforce_keys(9) = [character(len=6) :: "I", "JFLOAT", "RM", &
        & "FX", "FY", "FZ", "TX", "TY", "TZ"]
    character(len=*), parameter :: vtorque_keys(6) = [character(len=6) :: "I", "JFLOAT", "RM", &
        & "TX", "TY", "TZ"]
    !> SPRINGDAMPER's keywords: its markers, its kind, and its constants
    character(len=*), parameter :: springdamper_keys(12) = [character(len=13) :: "I", "J", &
        & "TRANSLATIONAL", "ROTATIONAL", "K", "C", "LENGTH", "FORCE", "KT", "CT", "ANGLE", &
        & "TORQUE"]
    !> BUSHING's keywords: its markers, and its constants in the order of adm_force_type's
    !> constants
    character(len=*), parameter :: bushing_keys(8) = [character(len=6) :: "I", "J", "K", "C", &
        & "KT", "CT", "FORCE", "TORQUE"]
    !> VFORCE's, GFORCE's and VTORQUE's keywords beside their components: a user's routine serves it
    character(len=*), parameter :: user_keys(2) = [character(len=8) :: "FUNCTION", "ROUTINE"]

contains

    !> UCON/id, FUNCTION=USER(r1, ..., r30)[, ROUTINE=name]: name, in any case, names a
    !> built-in UCOSUB (which one is the assembly's to find, rollcon_adm_build; without it the
    !> model's UCOSUB serves the UCON). (Whether its id is new is the reader's to check.)
    subroutine read_ucon(path, where, statement, ucon, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_ucon_type), intent(out) :: ucon
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        integer :: k

        ucon%id = statement%id
        ucon%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, ucon_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            if (key == "FUNCTION") then
                call read_user_list(statement%arguments(k), at, ucon%par, error)
            else
                call read_routine(statement%arguments(k), at, ucon%routine, error)
                ucon%routine_at = at
            end if
            if (allocated(error)) return
        end do
        if (.not. allocated(ucon%par)) then
            call fatal_error(error, where // ": FUNCTION=USER(r1, ..., r30) is missing (the " &
                & // "constants passed to the UCOSUB as PAR)", stat_input)
            return
        end if
        if (.not. allocated(ucon%routine)) ucon%routine = ""
    end subroutine read_ucon

    !> ROUTINE = name: one word, kept as written (the assembly finds the built-in UCOSUB it
    !> names, rollcon_adm_build).
    subroutine read_routine(argument, at, routine, error)
        type(adm_argument_type), intent(in) :: argument
        character(len=*), intent(in) :: at
        character(len=:), allocatable, intent(out) :: routine
        type(error_type), allocatable, intent(out) :: error

        if (argument%assigned .and. size(argument%values) == 1) then
            routine = trim(adjustl(argument%values(1)%text))
            if (len(routine) > 0) return
        end if
        call fatal_error(error, at // ": expected the name of a built-in UCOSUB (ROUTINE=name)", &
            & stat_input)
    end subroutine read_routine

    !> FUNCTION = USER(r1, ..., rn): 1 <= n <= 30, one number per field.
    subroutine read_user_list(argument, at, par, error, routine)
        type(adm_argument_type), intent(in) :: argument
        character(len=*), intent(in) :: at
        real(wp), allocatable, intent(out) :: par(:)
        type(error_type), allocatable, intent(out) :: error
        !> The routine the constants go to (default UCOSUB)
        character(len=*), intent(in), optional :: routine
        type(adm_argument_type) :: list
        character(len=:), allocatable :: text, inner, served
        integer :: open, i, n, start
        logical :: well_formed

        served = "UCOSUB"
        if (present(routine)) served = routine

        text = trim(argument_text(argument))
        open = index(text, "(")
        ! (each test apart: Fortran may evaluate every operand of .or., and text may be empty)
        well_formed = open > 1
        if (well_formed) well_formed = text(len(text):) == ")"
        if (well_formed) well_formed = is_user(text(:open - 1))
        if (.not. well_formed) then
            if (present(routine)) then
                call fatal_error(error, at // ": expected USER(r1, ..., r30) (the constants " &
                    & // "of its " // served // "), got '" // text // "'", stat_input)
            else
                call fatal_error(error, at // ": expected USER(r1, ..., r30) (a UCON is served " &
                    & // "by the model's UCOSUB), got '" // text // "'", stat_input)
            end if
            return
        end if
        inner = text(open + 1:len(text) - 1)
        if (len_trim(inner) == 0) then
            if (present(routine)) then
                call fatal_error(error, at // ": USER() holds no constant; 1 to 30 constants " &
                    & // "go to the " // served // " (PAR)", stat_input)
            else
                call fatal_error(error, at // ": USER() holds no constant; a UCON passes 1 to " &
                    & // "30 constants to its UCOSUB (PAR)", stat_input)
            end if
            return
        end if
        n = count([(inner(i:i) == ",", i = 1, len(inner))]) + 1
        list%assigned = .true.
        allocate(list%values(n))
        start = 1
        n = 0
        do i = 1, len(inner) + 1
            if (i <= len(inner)) then
                if (inner(i:i) /= ",") cycle
            end if
            n = n + 1
            list%values(n)%text = trim(adjustl(inner(start:i - 1)))
            start = i + 1
        end do
        call read_reals(list, at // " USER", 1, 30, .false., par, error)
    end subroutine read_user_list

    !> USER, in any case, alone before the parenthesis.
    pure logical function is_user(name)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: word

        word = trim(adjustl(name))
        is_user = len(word) == 4
        if (is_user) is_user = (word(1:1) == "U" .or. word(1:1) == "u") .and. &
            & (word(2:2) == "S" .or. word(2:2) == "s") .and. (word(3:3) == "E" &
            & .or. word(3:3) == "e") .and. (word(4:4) == "R" .or. word(4:4) == "r")
    end function is_user

    subroutine read_accgrav(path, where, statement, model, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        integer :: k, axis

        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, accgrav_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, &
                & model%units%length/model%units%time**2)
            if (allocated(error)) return
            axis = iachar(key(1:1)) - iachar("I") + 1
            ! in SI already (read_reals), where the physical range applies
            model%gravity(axis) = values(1)
            if (.not. abs(model%gravity(axis)) <= gravity_max) then
                call fatal_error(error, at // " must be at most " // to_text(gravity_max) &
                    & // " [m/s^2] in magnitude (36 times the Sun's surface gravity), got " &
                    & // to_text(model%gravity(axis)) // " m/s^2", stat_input)
                return
            end if
        end do
    end subroutine read_accgrav

    !> SFORCE, VFORCE, GFORCE or VTORQUE (name) as read (whether its id is new among the
    !> statements of its kind is the reader's to check). A VTORQUE is kept as a GFORCE of TX,
    !> TY, TZ alone, of kind force_vtorque.
    subroutine read_force(path, where, name, statement, force, error)
        character(len=*), intent(in) :: path, where, name
        type(adm_statement_type), intent(in) :: statement
        type(adm_force_type), intent(out) :: force
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        integer :: k, slot, sense

        sense = 0
        force%id = statement%id
        force%line = statement%line
        force%kind = merge(force_sforce, merge(force_vforce, force_gforce, name == "VFORCE"), &
            & name == "SFORCE")
        if (name == "VTORQUE") force%kind = force_vtorque
        do k = 1, size(statement%arguments)
            if (force%kind == force_sforce) then
                call argument_key(path, where, statement, k, sforce_keys, key, error)
            else if (force%kind == force_vtorque) then
                call argument_key(path, where, statement, k, [character(len=8) :: &
                    & vtorque_keys, user_keys], key, error)
            else if (force%kind == force_vforce) then
                call argument_key(path, where, statement, k, [character(len=8) :: &
                    & gforce_keys(1:6), user_keys], key, error)
            else
                call argument_key(path, where, statement, k, [character(len=8) :: gforce_keys, &
                    & user_keys], key, &
                    & error)
            end if
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("I")
                call read_integer(statement%arguments(k), at, force%i, error)
            case ("J", "JFLOAT")
                call read_integer(statement%arguments(k), at, force%j, error)
            case ("RM")
                call read_integer(statement%arguments(k), at, force%rm, error)
            case ("ROUTINE")
                call read_routine(statement%arguments(k), at, force%routine, error)
            case ("FUNCTION")
                if (.not. statement%arguments(k)%assigned) then
                    call fatal_error(error, at // ": expected one expression", stat_input)
                    return
                end if
                if (user_function(argument_text(statement%arguments(k)))) then
                    ! FUNCTION=USER(r1, ...): the statement's user routine (SFOSUB, ...)
                    call read_user_list(statement%arguments(k), at, force%par, error, &
                        & routine_of(name))
                    force%user = .true.
                else if (force%kind /= force_sforce) then
                    call fatal_error(error, at // ": a " // name // " gives its components as " &
                        & // trim(merge("TX=e, ...", "FX=e, ...", force%kind == force_vtorque)) &
                        & // " or is served by a user's routine, FUNCTION=USER(r1, " &
                        & // "..., r30); got '" // trim(argument_text(statement%arguments(k))) &
                        & // "'", stat_input)
                    return
                else
                    call compile_expression(argument_text(statement%arguments(k)), at, &
                        & force%functions(1), error)
                    force%given(1) = .true.
                end if
            case ("TRANSLATION", "ROTATION", "ACTIONONLY", "TRANSLATIONAL", "ROTATIONAL")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                    return
                end if
                if (key == "TRANSLATION" .or. key == "TRANSLATIONAL") sense = sense + 1
                if (key == "ROTATION" .or. key == "ROTATIONAL") then
                    force%translation = .false.
                    sense = sense + 1
                end if
                if (sense > 1) then
                    call fatal_error(error, at // ": TRANSLATION (TRANSLATIONAL) and ROTATION " &
                        & // "(ROTATIONAL) are given together; an SFORCE is one of them", &
                        & stat_input)
                    return
                end if
                if (key == "ACTIONONLY") force%action_only = .true.
            case default
                slot = max(1, name_index(key, gforce_keys(4:9)))
                if (.not. statement%arguments(k)%assigned) then
                    call fatal_error(error, at // ": expected one expression", stat_input)
                    return
                end if
                ! an expression goes on to a backslash or the statement's end, over comma
                ! lines at any depth (rollcon_adm_lexer)
                call compile_expression(argument_text(statement%arguments(k)), at, &
                    & force%functions(slot), error)
                force%given(slot) = .true.
            end select
            if (allocated(error)) return
        end do
        if (force%user .and. any(force%given)) then
            call fatal_error(error, where // ": FUNCTION=USER(...) and expressions are given " &
                & // "together; a " // name // " is served by its " // routine_of(name) &
                & // " or by expressions", stat_input)
            return
        end if
        if (allocated(force%routine) .and. .not. force%user) then
            call fatal_error(error, where // ": ROUTINE=" // force%routine // " names a " &
                & // routine_of(name) // ", which serves a FUNCTION=USER(r1, ..., r30) only", &
                & stat_input)
            return
        end if
        if (.not. allocated(force%routine)) force%routine = ""
    end subroutine read_force

    !> SPRINGDAMPER or BUSHING (name) as read, its constants in SI (units: the dataset's).
    !> A SPRINGDAMPER is TRANSLATIONAL (K, C, LENGTH, FORCE) or ROTATIONAL (KT, CT, ANGLE,
    !> TORQUE), one of them and only its own constants; a BUSHING takes three numbers for each
    !> of K, C, KT, CT, FORCE, TORQUE. Every constant defaults to 0; stiffnesses, dampings and
    !> LENGTH may not be negative.
    subroutine read_spring(path, where, name, statement, units, force, error)
        character(len=*), intent(in) :: path, where, name
        type(adm_statement_type), intent(in) :: statement
        type(units_type), intent(in) :: units
        type(adm_force_type), intent(out) :: force
        type(error_type), allocatable, intent(out) :: error
        ! where the first constant of a translational and of a rotational SPRINGDAMPER is
        character(len=:), allocatable :: key, at, translational_at, rotational_at
        real(wp), allocatable :: values(:)
        real(wp) :: factors(6)
        integer :: k, slot, sense

        ! K, C, KT, CT, FORCE, TORQUE: the size of a dataset unit of each in SI
        factors = [units%force/units%length, units%force*units%time/units%length, &
            & units%force*units%length, units%force*units%length*units%time, units%force, &
            & units%force*units%length]
        force%id = statement%id
        force%line = statement%line
        force%kind = merge(force_springdamper, force_bushing, name == "SPRINGDAMPER")
        sense = 0
        translational_at = ""
        rotational_at = ""
        do k = 1, size(statement%arguments)
            if (force%kind == force_springdamper) then
                call argument_key(path, where, statement, k, springdamper_keys, key, error)
            else
                call argument_key(path, where, statement, k, bushing_keys, key, error)
            end if
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("I")
                call read_integer(statement%arguments(k), at, force%i, error)
            case ("J")
                call read_integer(statement%arguments(k), at, force%j, error)
            case ("TRANSLATIONAL", "ROTATIONAL")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                    return
                end if
                sense = sense + 1
                if (sense > 1) then
                    call fatal_error(error, at // ": TRANSLATIONAL and ROTATIONAL are given " &
                        & // "together; a SPRINGDAMPER is one of them", stat_input)
                    return
                end if
                force%translation = key == "TRANSLATIONAL"
            case ("LENGTH")
                if (len(translational_at) == 0) translational_at = at
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, &
                    & units%length)
                if (allocated(error)) return
                force%reference = values(1)
                call refuse_negative(values, at, error)
            case ("ANGLE")
                if (len(rotational_at) == 0) rotational_at = at
                call read_reals(statement%arguments(k), at, 1, 1, .true., values, error)
                if (allocated(error)) return
                force%reference = values(1)
            case default
                ! K, C, KT, CT, FORCE, TORQUE: slot 1 to 6 of the constants' triples
                slot = name_index(key, bushing_keys(3:8))
                if (force%kind == force_springdamper) then
                    if (len(translational_at) == 0 .and. any(slot == [1, 2, 5])) &
                        & translational_at = at
                    if (len(rotational_at) == 0 .and. any(slot == [3, 4, 6])) &
                        & rotational_at = at
                    call read_reals(statement%arguments(k), at, 1, 1, .false., values, error, &
                        & factors(slot))
                    if (allocated(error)) return
                    ! a translational one's in the first of the triple, a rotational one's in
                    ! the third (about J's z axis)
                    if (any(slot == [1, 2, 5])) then
                        force%constants(3*slot - 2) = values(1)
                    else
                        force%constants(3*slot) = values(1)
                    end if
                else
                    call read_reals(statement%arguments(k), at, 3, 3, .false., values, error, &
                        & factors(slot))
                    if (allocated(error)) return
                    force%constants(3*slot - 2:3*slot) = values
                end if
                if (slot <= 4) call refuse_negative(values, at, error)
            end select
            if (allocated(error)) return
        end do
        if (force%kind /= force_springdamper) return
        if (sense == 0) then
            call fatal_error(error, where // ": TRANSLATIONAL or ROTATIONAL is missing (a " &
                & // "SPRINGDAMPER is one of them)", stat_input)
        else if (force%translation .and. len(rotational_at) > 0) then
            call fatal_error(error, rotational_at // ": a TRANSLATIONAL SPRINGDAMPER takes K, C, " &
                & // "LENGTH and FORCE (KT, CT, ANGLE and TORQUE are a ROTATIONAL one's)", &
                & stat_input)
        else if (.not. force%translation .and. len(translational_at) > 0) then
            call fatal_error(error, translational_at &
                & // ": a ROTATIONAL SPRINGDAMPER takes KT, CT, " &
                & // "ANGLE and TORQUE (K, C, LENGTH and FORCE are a TRANSLATIONAL one's)", &
                & stat_input)
        end if
    end subroutine read_spring

    !> A stiffness, damping or length is not negative.
    subroutine refuse_negative(values, at, error)
        real(wp), intent(in) :: values(:)
        character(len=*), intent(in) :: at
        type(error_type), allocatable, intent(out) :: error

        if (all(values >= 0.0_wp)) return
        call fatal_error(error, at // ": expected a value >= 0, got " &
            & // to_text(minval(values)), stat_input)
    end subroutine refuse_negative
    !> The user routine of a force statement: SFOSUB of SFORCE, and so on.
    pure function routine_of(name) result(routine)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: routine

        select case (name)
        case ("SFORCE")
            routine = "SFOSUB"
        case ("VFORCE")
            routine = "VFOSUB"
        case ("VTORQUE")
            routine = "VTOSUB"
        case default
            routine = "GFOSUB"
        end select
    end function routine_of

    !> True for "USER(...)" in any case, spaces aside.
    pure logical function user_function(text)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: word
        integer :: open

        word = trim(adjustl(text))
        open = index(word, "(")
        user_function = .false.
        if (open > 1) user_function = is_user(word(:open - 1))
    end function user_function

end module rollcon_adm_loads
