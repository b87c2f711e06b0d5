! SPDX-License-Identifier: MIT
!> Dataset statements that hold data for a user's routines (docs/datasets.md, "STRING and
!> ARRAY"), read as the text states them:
!>
!> - `STRING/id, STRING=text`: a line of text a routine reads with GTSTRG(id, ...) (a file
!>   name, a mode, a label); the text as written, its pieces between commas joined by commas;
!> - `ARRAY/id[, IC][, SIZE=n], NUMBERS=r1[, ...]`: numbers a routine reads with
!>   GTARAY(id, ...) (ADAMS's IC array). ADAMS's other arrays (X, Y: the states and outputs
!>   of an LSE, GSE or TFSISO; U: their inputs) belong to statements rollcon has not, and are
!>   refused.
module rollcon_adm_data
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_adm_lexer, only : adm_statement_type
    use rollcon_adm_keywords, only : argument_key, arg_place, read_reals
    implicit none
    private

    public :: adm_string_type, adm_array_type, read_string, read_array
    public :: string_keys, array_keys

    !> The keywords of each statement
    character(len=*), parameter :: string_keys(1) = [character(len=6) :: "STRING"]
    character(len=*), parameter :: array_keys(7) = [character(len=9) :: "IC", "SIZE", &
        & "NUMBERS", "X", "Y", "U", "VARIABLES"]

    !> STRING/id
    type :: adm_string_type
        integer :: id = 0, line = 0
        !> The text, as written
        character(len=:), allocatable :: text
    end type adm_string_type

    !> ARRAY/id (an IC array)
    type :: adm_array_type
        integer :: id = 0, line = 0
        !> NUMBERS, as written (no units: the routine gives them their meaning)
        real(wp), allocatable :: numbers(:)
    end type adm_array_type

contains

    !> STRING/id, STRING=text. Errors: no STRING=, STRING without text.
    subroutine read_string(path, where, statement, string, error)
        !> The dataset's path; "file:line: STRING/id", the start of messages
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_string_type), intent(out) :: string
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key
        integer :: k, i

        string%id = statement%id
        string%line = statement%line
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, string_keys, key, error)
            if (allocated(error)) return
            associate (argument => statement%arguments(k))
                if (.not. argument%assigned) exit
                string%text = ""
                do i = 1, size(argument%values)
                    if (i > 1) string%text = string%text // ","
                    string%text = string%text // trim(adjustl(argument%values(i)%text))
                end do
            end associate
        end do
        if (.not. allocated(string%text)) then
            call fatal_error(error, where // ": STRING=text is missing (a STRING holds the " &
                & // "text a user's routine reads with GTSTRG)", stat_input)
        else if (len(string%text) == 0) then
            call fatal_error(error, where // " STRING: the text is empty", stat_input)
        end if
    end subroutine read_string

    !> ARRAY/id[, IC][, SIZE=n], NUMBERS=r1, ...: at least one number, finite; SIZE, when
    !> given, the count of NUMBERS. Errors: X, Y, U, VARIABLES (the arrays of LSE, GSE and
    !> TFSISO), no NUMBERS, a SIZE that is not their count.
    subroutine read_array(path, where, statement, array, error)
        character(len=*), intent(in) :: path, where
        type(adm_statement_type), intent(in) :: statement
        type(adm_array_type), intent(out) :: array
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: key, at
        real(wp), allocatable :: size_value(:)
        integer :: k, size_given

        array%id = statement%id
        array%line = statement%line
        size_given = -1
        do k = 1, size(statement%arguments)
            call argument_key(path, where, statement, k, array_keys, key, error)
            if (allocated(error)) return
            at = arg_place(path, where, statement%arguments(k)) // " " // key
            select case (key)
            case ("IC")
                if (statement%arguments(k)%assigned) call fatal_error(error, at &
                    & // " takes no value (the numbers are NUMBERS=r1, ...)", stat_input)
            case ("SIZE")
                call read_reals(statement%arguments(k), at, 1, 1, .false., size_value, error)
                if (allocated(error)) return
                if (size_value(1) < 1.0_wp .or. size_value(1) /= aint(size_value(1))) then
                    call fatal_error(error, at // ": expected a positive integer, got " &
                        & // to_text(size_value(1)), stat_input)
                    return
                end if
                size_given = nint(size_value(1))
            case ("NUMBERS")
                call read_reals(statement%arguments(k), at, 1, huge(1), .false., &
                    & array%numbers, error)
            case default
                call fatal_error(error, at // ": an ARRAY of the inputs, states or outputs " &
                    & // "of an LSE, GSE or TFSISO (X, Y, U, VARIABLES) is not supported: " &
                    & // "those statements are not in the subset; an ARRAY here holds " &
                    & // "NUMBERS=r1, ... for a user's routine (GTARAY)", stat_input)
            end select
            if (allocated(error)) return
        end do
        if (.not. allocated(array%numbers)) then
            call fatal_error(error, where // ": NUMBERS=r1, ... is missing (an ARRAY holds " &
                & // "the numbers a user's routine reads with GTARAY)", stat_input)
        else if (size_given >= 0 .and. size_given /= size(array%numbers)) then
            call fatal_error(error, where // ": SIZE=" // to_text(size_given) &
                & // " but NUMBERS gives " // to_text(size(array%numbers)) // " values", &
                & stat_input)
        end if
    end subroutine read_array

end module rollcon_adm_data
