! SPDX-License-Identifier: MIT
!> Dataset statements GCON, COUPLER and GEAR (docs/datasets.md, "GCON", "Couplers"), read and
!> checked as the text states them: a GCON's marker I and its FUNCTION (compiled), a COUPLER's
!> joints, their types and scales, a GEAR's two joints and its common-velocity marker. That the
!> markers and joints exist, and the joints' types suit, is judged once the file is read
!> (rollcon_adm_checks) and where the dataset is assembled (rollcon_adm_build).
module rollcon_adm_couplers
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_expression, only : expression_type
    use rollcon_adm_lexer, only : adm_statement_type, upper_case
    use rollcon_adm_keywords, only : argument_key, arg_place, read_integer, read_reals, &
        & argument_text
    use rollcon_adm_expression_parser, only : compile_expression
    implicit none
    private

    public :: adm_gcon_type, adm_coupler_type, adm_gear_type, read_gcon, read_coupler, read_gear

    character(len=*), parameter :: gcon_keys(2) = [character(len=8) :: "I", "FUNCTION"]
    character(len=*), parameter :: coupler_keys(5) = [character(len=8) :: "JOINTS", "TYPE", &
        & "SCALES", "FUNCTION", "ROUTINE"]
    character(len=*), parameter :: gear_keys(2) = [character(len=6) :: "JOINTS", "CV"]

    !> GCON/id, I=id, FUNCTION=e
    type :: adm_gcon_type
        integer :: id = 0, line = 0
        !> The marker the reaction is reported at
        integer :: i = 0
        !> F, in the dataset's units
        type(expression_type) :: function
        !> "file:line: GCON/1 FUNCTION", for the assembly's messages
        character(len=:), allocatable :: function_at
    end type adm_gcon_type

    !> COUPLER/id, JOINTS=j1, j2[, j3], TYPE=t1:t2[:t3], SCALES=[r1,] r2[, r3]
    type :: adm_coupler_type
        integer :: id = 0, line = 0
        !> The JOINTs coupled (2 or 3)
        integer, allocatable :: joints(:)
        !> Each joint's displacement: "T" (translation) or "R" (rotation); " " when TYPE does
        !> not give it (then the joint's type decides)
        character(len=1), allocatable :: types(:)
        !> The scale of each joint's displacement (r1 = 1 when SCALES gives one fewer)
        real(wp), allocatable :: scales(:)
    end type adm_coupler_type

    !> GEAR/id, JOINTS=j1, j2, CV=id
    type :: adm_gear_type
        integer :: id = 0, line = 0
        integer :: joints(2) = 0
        !> The common-velocity marker: its origin the point of contact, its z axis the
        !> direction of the common velocity
        integer :: cv = 0
    end type adm_gear_type

contains

    !> GCON/id, I=id, FUNCTION=e (both required).
    subroutine read_gcon(path, where, statement, gcon, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_gcon_type), intent(out) :: gcon
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        integer :: k

        gcon%id = statement%id
        gcon%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, gcon_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            if (key == "I") then
                call read_integer(statement%arguments(k), at, gcon%i, error)
            else
                if (.not. statement%arguments(k)%assigned) then
                    call fatal_error(error, at // ": expected one expression", stat_input)
                    return
                end if
                call compile_expression(argument_text(statement%arguments(k)), at, &
                    & gcon%function, error)
                gcon%function_at = at
            end if
            if (allocated(error)) return
        end do
        if (gcon%i == 0) then
            call fatal_error(error, where // ": I=id is missing (the marker where the " &
                & // "constraint's reaction is reported)", stat_input)
        else if (.not. allocated(gcon%function_at)) then
            call fatal_error(error, where // ": FUNCTION=e is missing (the expression the " &
                & // "constraint holds at zero)", stat_input)
        end if
    end subroutine read_gcon

    !> COUPLER/id, JOINTS=j1, j2[, j3], TYPE=t1:t2[:t3], SCALES=[r1,] r2[, r3]: ADAMS's
    !> linear coupler; its FUNCTION=USER() and ROUTINE= (a COUSUB) are refused.
    subroutine read_coupler(path, where, statement, coupler, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_coupler_type), intent(out) :: coupler
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at, types_at, text, word
        real(wp), allocatable :: scales(:)
        character(len=1) :: letter
        integer :: k, n, colon

        coupler%id = statement%id
        coupler%line = statement%line
        allocate(coupler%joints(0), coupler%types(0))
        allocate(scales(0))
        types_at = ""
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, coupler_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            associate (argument => statement%arguments(k))
                select case (key)
                case ("JOINTS")
                    if (.not. argument%assigned .or. size(argument%values) < 2 &
                        & .or. size(argument%values) > 3) then
                        call fatal_error(error, at // ": expected 2 or 3 JOINT ids", stat_input)
                        return
                    end if
                    deallocate(coupler%joints)
                    allocate(coupler%joints(size(argument%values)))
                    do n = 1, size(argument%values)
                        call read_id(argument%values(n)%text, at, coupler%joints(n), error)
                        if (allocated(error)) return
                    end do
                case ("TYPE")
                    types_at = at
                    text = ""
                    if (argument%assigned .and. size(argument%values) == 1) &
                        & text = upper_case(trim(adjustl(argument%values(1)%text))) // ":"
                    deallocate(coupler%types)
                    allocate(coupler%types(0))
                    do while (len(text) > 0)
                        colon = index(text, ":")
                        word = trim(adjustl(text(:colon - 1)))
                        text = text(colon + 1:)
                        if (word /= "T" .and. word /= "R") then
                            call fatal_error(error, at // ": expected T or R for each joint, " &
                                & // "separated by colons (TYPE=T:R), got '" // word // "'", &
                                & stat_input)
                            return
                        end if
                        letter = word(1:1)
                        coupler%types = [character(len=1) :: coupler%types, letter]
                    end do
                    if (size(coupler%types) == 0) then
                        call fatal_error(error, at // ": expected T or R for each joint, " &
                            & // "separated by colons (TYPE=T:R)", stat_input)
                        return
                    end if
                case ("SCALES")
                    call read_reals(argument, at, 1, 3, .false., scales, error)
                    if (allocated(error)) return
                case default
                    call fatal_error(error, at // ": a coupler of your own (COUSUB) is not " &
                        & // "supported: give its joints' relation as SCALES, or as a GCON " &
                        & // "expression", stat_input)
                    return
                end select
            end associate
        end do
        n = size(coupler%joints)
        if (n == 0) then
            call fatal_error(error, where // ": JOINTS=j1, j2[, j3] is missing (the joints " &
                & // "coupled)", stat_input)
            return
        end if
        if (size(scales) == 0) then
            call fatal_error(error, where // ": SCALES=[r1,] r2[, r3] is missing (the relation " &
                & // "r1 q1 + r2 q2 + r3 q3 = 0)", stat_input)
            return
        end if
        ! ADAMS: one fewer scale than joints gives r2 (and r3), r1 being 1
        if (size(scales) == n - 1) scales = [1.0_wp, scales]
        if (size(scales) /= n) then
            call fatal_error(error, where // " SCALES: expected " // to_text(n - 1) // " or " &
                & // to_text(n) // " numbers for " // to_text(n) // " joints, got " &
                & // to_text(size(scales)), stat_input)
            return
        end if
        if (any(scales == 0.0_wp)) then
            call fatal_error(error, where // " SCALES: a joint whose scale is 0 is not " &
                & // "coupled; leave it out of JOINTS", stat_input)
            return
        end if
        coupler%scales = scales
        if (size(coupler%types) == 0) then
            deallocate(coupler%types)
            allocate(coupler%types(n), source=" ")
        else if (size(coupler%types) /= n) then
            call fatal_error(error, types_at // ": expected " // to_text(n) // " types for " &
                & // to_text(n) // " joints, got " // to_text(size(coupler%types)), stat_input)
            return
        end if
    end subroutine read_coupler

    !> GEAR/id, JOINTS=j1, j2, CV=id (all required).
    subroutine read_gear(path, where, statement, gear, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_gear_type), intent(out) :: gear
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        integer :: k, n

        gear%id = statement%id
        gear%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, gear_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            associate (argument => statement%arguments(k))
                if (key == "CV") then
                    call read_integer(argument, at, gear%cv, error)
                else
                    if (.not. argument%assigned .or. size(argument%values) /= 2) then
                        call fatal_error(error, at // ": expected 2 JOINT ids", stat_input)
                        return
                    end if
                    do n = 1, 2
                        call read_id(argument%values(n)%text, at, gear%joints(n), error)
                        if (allocated(error)) return
                    end do
                end if
            end associate
            if (allocated(error)) return
        end do
        if (gear%joints(1) == 0) then
            call fatal_error(error, where // ": JOINTS=j1, j2 is missing (the two joints " &
                & // "geared)", stat_input)
        else if (gear%cv == 0) then
            call fatal_error(error, where // ": CV=id is missing (the common-velocity marker " &
                & // "at the point of contact)", stat_input)
        end if
    end subroutine read_gear

    !> One id (a positive whole number) from its text.
    subroutine read_id(text, at, id, error)
        character(len=*), intent(in) :: text, at
        integer, intent(out) :: id
        type(error_type), allocatable, intent(out) :: error
        integer :: stat

        id = 0
        read(text, *, iostat=stat) id
        if (stat /= 0 .or. id <= 0 .or. verify(trim(adjustl(text)), "0123456789") /= 0) then
            call fatal_error(error, at // ": expected an id (a positive integer), got '" &
                & // trim(adjustl(text)) // "'", stat_input)
            id = 0
        end if
    end subroutine read_id

end module rollcon_adm_couplers
