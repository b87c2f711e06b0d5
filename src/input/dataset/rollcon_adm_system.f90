! SPDX-License-Identifier: MIT
!> Dataset statements of ADAMS's system and data elements (docs/datasets.md, "VARIABLE",
!> "SPLINE", "PINPUT and POUTPUT"), read and checked as the text states them:
!>
!> - `VARIABLE/id, FUNCTION=e[, IC=r]`: an algebraic variable, its value e (an expression in
!>   the dataset's units, read anywhere as VARVAL(id); rollcon_adm_variables puts it in place);
!> - `SPLINE/id, X=x1, ..., xn, Y=y1, ..., yn[, LINEAR_EXTRAPOLATE]`: a curve through the
!>   points (x_i, y_i), read by AKISPL and CUBSPL (rollcon_spline); plain numbers, in whatever
!>   units the expressions reading it give them;
!> - `PINPUT/id, VARIABLES=id1[, ...]` and `POUTPUT/id, VARIABLES=...`: a controls plant's
!>   inputs and outputs, the VARIABLEs an outside controller would set and read;
!> - `DIFF/id, FUNCTION=e, IC=r1[, r2][, IMPLICIT][, STATIC_HOLD]`: a user's differential
!>   equation, its state DIF(id) integrated with the parts' (rollcon_diff): d DIF/dt = e, or
!>   with IMPLICIT 0 = e, r1 the initial DIF and r2 the first guess of the initial DIF1.
module rollcon_adm_system
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_expression, only : expression_type
    use rollcon_adm_lexer, only : adm_statement_type, adm_argument_type, upper_case
    use rollcon_adm_keywords, only : argument_key, arg_place, read_reals, argument_text
    use rollcon_adm_expression_parser, only : compile_expression
    implicit none
    private

    public :: adm_variable_type, adm_spline_data_type, adm_plant_type, adm_diff_type
    public :: read_variable, read_spline, read_plant, read_diff
    public :: variable_keys, spline_keys, plant_keys, diff_keys

    !> The keywords of each statement
    character(len=*), parameter :: variable_keys(3) = [character(len=8) :: "FUNCTION", "IC", &
        & "ROUTINE"]
    character(len=*), parameter :: spline_keys(4) = [character(len=18) :: "X", "Y", "Z", &
        & "LINEAR_EXTRAPOLATE"]
    character(len=*), parameter :: plant_keys(1) = [character(len=9) :: "VARIABLES"]
    character(len=*), parameter :: diff_keys(5) = [character(len=11) :: "FUNCTION", "IC", &
        & "IMPLICIT", "STATIC_HOLD", "ROUTINE"]

    !> VARIABLE/id
    type :: adm_variable_type
        integer :: id = 0, line = 0
        !> FUNCTION, in the dataset's units (VARVAL(id) reads its value)
        type(expression_type) :: function
        !> IC: ADAMS's first guess of the value for its algebraic solution [the value's units];
        !> the value itself is the FUNCTION's
        real(wp) :: ic = 0.0_wp
        !> FUNCTION=USER(r1, ..., rn): a VARSUB's VARIABLE (its function then VARVAL(id),
        !> read from the routine's value; rollcon_adm_variables), the USER(...) argument as
        !> written and where ("file:line: VARIABLE/3 FUNCTION"), its constants once read
        !> (resolve_variables), and ROUTINE= as written ("" when not given)
        logical :: user = .false.
        type(adm_argument_type) :: user_argument
        character(len=:), allocatable :: user_at, routine
        real(wp), allocatable :: par(:)
    end type adm_variable_type

    !> SPLINE/id
    type :: adm_spline_data_type
        integer :: id = 0, line = 0
        !> The points, as written (x strictly increasing)
        real(wp), allocatable :: x(:), y(:)
        !> LINEAR_EXTRAPOLATE: beyond its end points the curve goes on along its end slopes
        logical :: linear_extrapolate = .false.
    end type adm_spline_data_type

    !> PINPUT/id or POUTPUT/id
    type :: adm_plant_type
        integer :: id = 0, line = 0
        !> POUTPUT (else PINPUT)
        logical :: output = .false.
        !> VARIABLES=: the VARIABLEs' ids, in order
        integer, allocatable :: variables(:)
    end type adm_plant_type

    !> DIFF/id
    type :: adm_diff_type
        integer :: id = 0, line = 0
        !> FUNCTION, in the dataset's units: d DIF(id)/dt (per the dataset's time unit), or
        !> with IMPLICIT the residual 0 = e
        type(expression_type) :: function
        !> IC: the initial DIF(id) [the user's units] and, for an IMPLICIT DIFF, the first
        !> guess of the initial DIF1(id) [the user's units per time unit] (0 when not given)
        real(wp) :: ic(2) = 0.0_wp
        logical :: implicit = .false., static_hold = .false.
        !> FUNCTION=USER(r1, ..., rn): a DIFSUB's DIFF (its function not compiled), the
        !> USER(...) argument as written and where, its constants once read
        !> (resolve_variables), and ROUTINE= as written ("" when not given)
        logical :: user = .false.
        type(adm_argument_type) :: user_argument
        character(len=:), allocatable :: user_at, routine
        real(wp), allocatable :: par(:)
    end type adm_diff_type

contains

    !> DIFF/id, FUNCTION=e, IC=r1[, r2][, IMPLICIT][, STATIC_HOLD] (ADAMS's DIFF statement):
    !> FUNCTION and IC required, IC one or two numbers (the second, DIF1's first guess, read by
    !> an IMPLICIT DIFF alone). FUNCTION=USER(r1, ...)[, ROUTINE=name] is a DIFSUB's: the
    !> USER(...) argument kept for resolve_variables to read.
    subroutine read_diff(path, where, statement, diff, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_diff_type), intent(out) :: diff
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, text
        real(wp), allocatable :: values(:)
        logical :: given, ic_given
        integer :: k

        diff%id = statement%id
        diff%line = statement%line
        diff%routine = ""
        given = .false.
        ic_given = .false.
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, diff_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("FUNCTION")
                if (.not. statement%arguments(k)%assigned) then
                    call fatal_error(error, at // ": expected one expression", stat_input)
                    return
                end if
                text = argument_text(statement%arguments(k))
                given = .true.
                if (index(upper_case(adjustl(text)), "USER") == 1) then
                    ! a DIFSUB's: its constants read as the dataset's VARIABLEs are resolved
                    diff%user = .true.
                    diff%user_argument = statement%arguments(k)
                    diff%user_at = at
                    cycle
                end if
                call compile_expression(text, at, diff%function, error)
            case ("IC")
                call read_reals(statement%arguments(k), at, 1, 2, .false., values, error)
                if (allocated(error)) then
                    deallocate(error)
                    call fatal_error(error, at // ": expected one or two numbers (IC=r1[, r2]: " &
                        & // "the initial DIF and, for an IMPLICIT DIFF, the first guess of " &
                        & // "the initial DIF1)", stat_input)
                    return
                end if
                diff%ic(:size(values)) = values
                ic_given = .true.
            case ("IMPLICIT", "STATIC_HOLD")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                    return
                end if
                if (key == "IMPLICIT") diff%implicit = .true.
                if (key == "STATIC_HOLD") diff%static_hold = .true.
            case ("ROUTINE")
                diff%routine = argument_text(statement%arguments(k))
            end select
            if (allocated(error)) return
        end do
        if (.not. given) then
            call fatal_error(error, where // ": FUNCTION=e is missing (the equation: d DIF/dt " &
                & // "= e, or with IMPLICIT 0 = e)", stat_input)
        else if (.not. ic_given) then
            call fatal_error(error, where // ": IC=r1 is missing (the initial value of " &
                & // "DIF(" // to_text(diff%id) // "))", stat_input)
        else if (len(diff%routine) > 0 .and. .not. diff%user) then
            call fatal_error(error, where // " ROUTINE: names a DIFSUB, which serves a " &
                & // "FUNCTION=USER(r1, ..., r30) only", stat_input)
        end if
    end subroutine read_diff

    !> VARIABLE/id, FUNCTION=e[, IC=r], or FUNCTION=USER(r1, ...)[, ROUTINE=name] (a VARSUB's:
    !> the USER(...) argument kept for resolve_variables to read).
    subroutine read_variable(path, where, statement, variable, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_variable_type), intent(out) :: variable
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, text
        real(wp), allocatable :: values(:)
        logical :: given
        integer :: k

        variable%id = statement%id
        variable%line = statement%line
        variable%routine = ""
        given = .false.
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, variable_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("FUNCTION")
                if (.not. statement%arguments(k)%assigned) then
                    call fatal_error(error, at // ": expected one expression", stat_input)
                    return
                end if
                text = argument_text(statement%arguments(k))
                given = .true.
                if (index(upper_case(adjustl(text)), "USER") == 1) then
                    ! a VARSUB's: its constants read as the dataset's VARIABLEs are resolved
                    variable%user = .true.
                    variable%user_argument = statement%arguments(k)
                    variable%user_at = at
                    cycle
                end if
                call compile_expression(text, at, variable%function, error)
            case ("IC")
                call read_reals(statement%arguments(k), at, 1, 1, .false., values, error)
                if (.not. allocated(error)) variable%ic = values(1)
            case ("ROUTINE")
                variable%routine = argument_text(statement%arguments(k))
            end select
            if (allocated(error)) return
        end do
        if (.not. given) then
            call fatal_error(error, where // ": FUNCTION=e is missing (the " &
                & // "variable's value as an expression)", stat_input)
        else if (len(variable%routine) > 0 .and. .not. variable%user) then
            call fatal_error(error, where // " ROUTINE: names a VARSUB, which serves a " &
                & // "FUNCTION=USER(r1, ..., r30) only", stat_input)
        end if
    end subroutine read_variable

    !> SPLINE/id, X=x1, ..., xn, Y=y1, ..., yn[, LINEAR_EXTRAPOLATE]: at least two points (four
    !> for CUBSPL, judged where it is read), as many x as y, x strictly increasing. The
    !> surface form (Z= with one Y= list per z) is refused, as are FILE= and BLOCK= (a curve
    !> read from another file).
    subroutine read_spline(path, where, statement, spline, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_spline_data_type), intent(out) :: spline
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        integer :: k, i

        spline%id = statement%id
        spline%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, spline_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("X")
                call read_reals(statement%arguments(k), at, 2, huge(1), .false., spline%x, error)
            case ("Y")
                call read_reals(statement%arguments(k), at, 2, huge(1), .false., spline%y, error)
            case ("Z")
                call fatal_error(error, at // ": a SPLINE of a surface (Z= with a Y= list " &
                    & // "for each z) is not supported; AKISPL and CUBSPL read curves of " &
                    & // "X= and Y= alone", stat_input)
            case ("LINEAR_EXTRAPOLATE")
                if (statement%arguments(k)%assigned) then
                    call fatal_error(error, at // " takes no value", stat_input)
                else
                    spline%linear_extrapolate = .true.
                end if
            end select
            if (allocated(error)) return
        end do
        if (.not. allocated(spline%x) .or. .not. allocated(spline%y)) then
            call fatal_error(error, where // ": " // trim(merge("X=x1, ..., xn", &
                & "Y=y1, ..., yn", .not. allocated(spline%x))) // " is missing (a SPLINE " &
                & // "is the points X=x1, ..., xn, Y=y1, ..., yn)", stat_input)
            return
        end if
        if (size(spline%x) /= size(spline%y)) then
            call fatal_error(error, where // ": X gives " // to_text(size(spline%x)) &
                & // " values and Y " // to_text(size(spline%y)) // "; a SPLINE's points " &
                & // "take one y for each x", stat_input)
            return
        end if
        do i = 2, size(spline%x)
            if (spline%x(i) > spline%x(i - 1)) cycle
            call fatal_error(error, where // " X: x must increase strictly from point to " &
                & // "point, but x" // to_text(i) // " = " // to_text(spline%x(i)) &
                & // " follows x" // to_text(i - 1) // " = " // to_text(spline%x(i - 1)), &
                & stat_input)
            return
        end do
    end subroutine read_spline

    !> PINPUT/id or POUTPUT/id (`output`), VARIABLES=id1[, ...]: ids of VARIABLEs (that they
    !> exist is checked once the file is read: rollcon_adm_variables).
    subroutine read_plant(path, where, statement, output, plant, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        logical, intent(in) :: output
        type(adm_plant_type), intent(out) :: plant
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: values(:)
        integer :: k

        plant%id = statement%id
        plant%line = statement%line
        plant%output = output
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, plant_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            call read_reals(statement%arguments(k), at, 1, huge(1), .false., values, error)
            if (allocated(error)) return
            if (any(values /= aint(values)) .or. any(values < 1.0_wp) .or. &
                & any(values > real(huge(1), wp))) then
                call fatal_error(error, at // ": expected ids of VARIABLEs (positive whole " &
                    & // "numbers)", stat_input)
                return
            end if
            plant%variables = nint(values)
        end do
        if (.not. allocated(plant%variables)) call fatal_error(error, where // ": " &
            & // "VARIABLES=id1[, ...] is missing (the VARIABLEs of the plant's " &
            & // trim(merge("outputs", "inputs ", output)) // ")", stat_input)
    end subroutine read_plant

end module rollcon_adm_system
