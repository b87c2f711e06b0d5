! SPDX-License-Identifier: MIT
!> Dataset statement MOTION (docs/datasets.md, "MOTION"): a displacement, velocity or
!> acceleration prescribed as a function of time, on a joint (`JOINT=id, TRANSLATION|ROTATION`)
!> or between two markers (`I=id, J=id, X|Y|Z|B1|B2|B3`), read and checked as the text states
!> it; `FUNCTION=USER(r1, ...)[, ROUTINE=name]` is served by a MOTSUB (a function of any
!> form, with ADAMS's IORD; the USER(...) argument kept for rollcon_adm_variables to read its
!> constants). The model makes each one a UCON with an explicit time part (model%add_motion),
!> which also judges the markers' parts; the assembly finds the joint's markers and type.
module rollcon_adm_motions
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_expression, only : expression_type, quantity_varval
    use rollcon_adm_lexer, only : adm_statement_type, adm_argument_type, upper_case
    use rollcon_adm_keywords, only : argument_key, arg_place, read_integer, read_reals, &
        & argument_text
    use rollcon_adm_units, only : units_type
    use rollcon_adm_expression_parser, only : compile_expression
    implicit none
    private

    public :: adm_motion_type, read_motion, motion_keys
    public :: motion_displacement_form, motion_velocity_form, motion_acceleration_form

    !> What FUNCTION gives
    integer, parameter :: motion_displacement_form = 1, motion_velocity_form = 2, &
        & motion_acceleration_form = 3
    !> MOTION's keywords; TRANSLATIONAL and ROTATIONAL are the spellings ADAMS/View writes
    character(len=*), parameter :: motion_keys(20) = [character(len=13) :: "JOINT", "I", "J", &
        & "TRANSLATION", "ROTATION", "TRANSLATIONAL", "ROTATIONAL", "X", "Y", "Z", "B1", "B2", &
        & "B3", "DISPLACEMENT", "VELOCITY", "ACCELERATION", "FUNCTION", "ICDISP", "ICVEL", &
        & "ROUTINE"]
    !> The components: on a joint, or between markers
    character(len=*), parameter :: joint_components(2) = [character(len=11) :: "TRANSLATION", &
        & "ROTATION"]
    character(len=*), parameter :: marker_components(6) = [character(len=2) :: "X", "Y", "Z", &
        & "B1", "B2", "B3"]

    !> MOTION/id
    type :: adm_motion_type
        integer :: id = 0, line = 0
        !> JOINT=id (0: between markers), and I=id, J=id (0: on a joint)
        integer :: joint = 0, i = 0, j = 0
        !> TRANSLATION or ROTATION (on a joint), X, Y, Z, B1, B2 or B3 (between markers)
        character(len=:), allocatable :: component
        !> motion_displacement_form (default), motion_velocity_form, motion_acceleration_form
        integer :: form = motion_displacement_form
        !> FUNCTION, an expression of TIME, in the dataset's units
        type(expression_type) :: function
        !> ICDISP [m or rad] and ICVEL [m/s or rad/s], SI
        real(wp) :: initial_displacement = 0.0_wp, initial_velocity = 0.0_wp
        !> FUNCTION=USER(r1, ..., rn): served by a MOTSUB (function then unused), the USER(...)
        !> argument as written and where ("file:line: MOTION/3 FUNCTION"), its constants once
        !> read (resolve_variables), and ROUTINE= as written ("" when not given)
        logical :: user = .false.
        type(adm_argument_type) :: user_argument
        character(len=:), allocatable :: user_at, routine
        real(wp), allocatable :: par(:)
    end type adm_motion_type

contains

    !> MOTION/id as written: its joint or its markers and component, its form, FUNCTION (an
    !> expression of TIME alone) and ICDISP, ICVEL (VELOCITY and ACCELERATION only; ICVEL with
    !> ACCELERATION only). That the joint and markers exist is checked once the file is read
    !> (rollcon_adm_checks); which types of joint take which component, by the assembly.
    subroutine read_motion(path, where, statement, units, motion, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(units_type), intent(in) :: units
        type(adm_motion_type), intent(out) :: motion
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, form_at, at_icdisp, at_icvel, routine_at
        real(wp), allocatable :: values(:)
        integer :: k, icdisp, icvel
        logical :: given_function, angle
        real(wp) :: factor

        motion%id = statement%id
        motion%line = statement%line
        motion%routine = ""
        icdisp = 0
        icvel = 0
        form_at = ""
        given_function = .false.
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, motion_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            if (key == "TRANSLATIONAL") key = "TRANSLATION"
            if (key == "ROTATIONAL") key = "ROTATION"
            select case (key)
            case ("JOINT")
                call read_integer(statement%arguments(k), at, motion%joint, error)
            case ("I")
                call read_integer(statement%arguments(k), at, motion%i, error)
            case ("J")
                call read_integer(statement%arguments(k), at, motion%j, error)
            case ("TRANSLATION", "ROTATION", "X", "Y", "Z", "B1", "B2", "B3")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                else if (allocated(motion%component)) then
                    call fatal_error(error, at // ": the motion's direction is given twice (" &
                        & // motion%component // " and " // key // ")", stat_input)
                else
                    motion%component = key
                end if
            case ("DISPLACEMENT", "VELOCITY", "ACCELERATION")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                else if (len(form_at) > 0) then
                    call fatal_error(error, at // ": DISPLACEMENT, VELOCITY and ACCELERATION " &
                        & // "are given together; a MOTION is one of them", stat_input)
                else
                    form_at = at
                    motion%form = merge(motion_displacement_form, merge(motion_velocity_form, &
                        & motion_acceleration_form, key == "VELOCITY"), key == "DISPLACEMENT")
                end if
            case ("FUNCTION")
                given_function = .true.
                if (statement%arguments(k)%assigned) then
                    if (index(upper_case(adjustl(argument_text(statement%arguments(k)))), &
                        & "USER") == 1) then
                        ! a MOTSUB's: its constants read with the dataset's VARIABLEs
                        motion%user = .true.
                        motion%user_argument = statement%arguments(k)
                        motion%user_at = at
                        cycle
                    end if
                end if
                call read_function(statement, k, at, motion%function, error)
            case ("ROUTINE")
                motion%routine = argument_text(statement%arguments(k))
                routine_at = at
            case ("ICDISP")
                icdisp = k
                at_icdisp = at
            case ("ICVEL")
                icvel = k
                at_icvel = at
            end select
            if (allocated(error)) return
        end do
        call check_choice(where, motion, error)
        if (allocated(error)) return
        if (.not. given_function) then
            call fatal_error(error, where // ": FUNCTION=e is missing (the displacement, " &
                & // "velocity or acceleration as an expression of TIME)", stat_input)
            return
        end if
        if (len(motion%routine) > 0 .and. .not. motion%user) then
            call fatal_error(error, routine_at // ": names a MOTSUB, which serves a " &
                & // "FUNCTION=USER(r1, ..., r30) only", stat_input)
            return
        end if
        ! the initial conditions, in the units of the direction's coordinate
        angle = any(motion%component == ["ROTATION", "B1      ", "B2      ", "B3      "])
        factor = merge(1.0_wp, units%length, angle)
        if (icdisp > 0) then
            if (motion%form == motion_displacement_form) then
                call fatal_error(error, at_icdisp // ": a DISPLACEMENT motion's function is " &
                    & // "its displacement; ICDISP is for VELOCITY and ACCELERATION", stat_input)
                return
            end if
            call read_reals(statement%arguments(icdisp), at_icdisp, 1, 1, angle, values, error, &
                & factor)
            if (allocated(error)) return
            motion%initial_displacement = values(1)
        end if
        if (icvel > 0) then
            if (motion%form /= motion_acceleration_form) then
                call fatal_error(error, at_icvel // ": ICVEL is for an ACCELERATION motion " &
                    & // "(a VELOCITY motion's function is its velocity)", stat_input)
                return
            end if
            call read_reals(statement%arguments(icvel), at_icvel, 1, 1, angle, values, error, &
                & factor/units%time)
            if (allocated(error)) return
            motion%initial_velocity = values(1)
        end if
    end subroutine read_motion

    !> FUNCTION=e: an expression of TIME alone (ADAMS's rule for a MOTION), VARVAL(id) of a
    !> VARIABLE of TIME alone among it (USER(...), a MOTSUB's, is read by read_motion).
    subroutine read_function(statement, k, at, function, error)
        type(adm_statement_type), intent(in) :: statement
        integer, intent(in) :: k
        character(len=*), intent(in) :: at
        type(expression_type), intent(out) :: function
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text

        if (.not. statement%arguments(k)%assigned) then
            call fatal_error(error, at // ": expected one expression of TIME", stat_input)
            return
        end if
        text = argument_text(statement%arguments(k))
        call compile_expression(text, at, function, error)
        if (allocated(error)) return
        ! a VARIABLE it reads is judged once every VARIABLE is read (rollcon_adm_variables)
        if (any(function%inputs%quantity /= quantity_varval)) then
            call fatal_error(error, at // ": a MOTION's function is an expression of TIME " &
                & // "alone (ADAMS's rule: the motion it prescribes may not depend on the " &
                & // "state), but it reads " &
                & // to_text(count(function%inputs%quantity /= quantity_varval)) &
                & // " state function(s)", stat_input)
        end if
    end subroutine read_function

    !> On a joint (JOINT=, TRANSLATION or ROTATION, no I or J) or between markers (I=, J=, one
    !> of X, Y, Z, B1, B2, B3, no JOINT).
    subroutine check_choice(where, motion, error)
        character(len=*), intent(in) :: where
        type(adm_motion_type), intent(in) :: motion
        type(error_type), allocatable, intent(out) :: error

        if (motion%joint /= 0 .and. (motion%i /= 0 .or. motion%j /= 0)) then
            call fatal_error(error, where // ": JOINT= and I=, J= are given together; a " &
                & // "MOTION is on a joint (JOINT=id, TRANSLATION or ROTATION) or between " &
                & // "two markers (I=id, J=id, X, Y, Z, B1, B2 or B3)", stat_input)
        else if (motion%joint == 0 .and. motion%i == 0 .and. motion%j == 0) then
            call fatal_error(error, where // ": JOINT=id, or I=id and J=id, is missing (what " &
                & // "the motion drives)", stat_input)
        else if (motion%joint == 0 .and. (motion%i == 0 .or. motion%j == 0)) then
            call fatal_error(error, where // ": " // trim(merge("I=id", "J=id", &
                & motion%i == 0)) // " is missing (a MOTION between markers drives marker I " &
                & // "from marker J)", stat_input)
        else if (.not. allocated(motion%component)) then
            if (motion%joint /= 0) then
                call fatal_error(error, where // ": TRANSLATION or ROTATION is missing (which " &
                    & // "of the joint's motions is driven)", stat_input)
            else
                call fatal_error(error, where // ": the direction is missing (one of X, Y, Z, " &
                    & // "B1, B2, B3)", stat_input)
            end if
        else if (motion%joint /= 0 .and. .not. any(motion%component == joint_components)) then
            call fatal_error(error, where // ": " // motion%component // " is a direction " &
                & // "between markers (I=, J=); on a joint, write TRANSLATION or ROTATION", &
                & stat_input)
        else if (motion%joint == 0 .and. .not. any(motion%component == marker_components)) then
            call fatal_error(error, where // ": " // motion%component // " is a motion of a " &
                & // "joint (JOINT=id); between markers, write X, Y, Z, B1, B2 or B3", stat_input)
        end if
    end subroutine check_choice

end module rollcon_adm_motions
