! SPDX-License-Identifier: MIT
!> The groups and keys a scene file may hold, and the check of every value's type as written.
module rollcon_scene_keys
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text
    use rollcon_scene_lexer, only : group_type, assignment_type, to_lower
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: scene_groups, check_keys, key_line

    !> Groups of a scene file, in the order the documentation gives them
    character(len=*), parameter :: scene_groups(*) = [character(len=11) :: "disk", &
        & "environment", "initial", "strike", "run", "limits"]

    !> Value kinds
    integer, parameter :: kind_real = 1, kind_integer = 2, kind_logical = 3, kind_string = 4

    !> A key of a group and the kind of its value
    type :: key_type
        character(len=11) :: group
        character(len=15) :: name
        integer :: kind
    end type key_type

    type(key_type), parameter :: scene_keys(*) = [ &
        & key_type("disk", "radius", kind_real), &
        & key_type("disk", "thickness", kind_real), &
        & key_type("disk", "density", kind_real), &
        & key_type("environment", "gravity", kind_real), &
        & key_type("initial", "psi", kind_real), &
        & key_type("initial", "theta", kind_real), &
        & key_type("initial", "phi", kind_real), &
        & key_type("initial", "psidot", kind_real), &
        & key_type("initial", "thetadot", kind_real), &
        & key_type("initial", "phidot", kind_real), &
        & key_type("initial", "x", kind_real), &
        & key_type("initial", "y", kind_real), &
        & key_type("initial", "z", kind_real), &
        & key_type("initial", "xdot", kind_real), &
        & key_type("initial", "ydot", kind_real), &
        & key_type("initial", "zdot", kind_real), &
        & key_type("strike", "time", kind_real), &
        & key_type("strike", "duration", kind_real), &
        & key_type("strike", "impulse", kind_real), &
        & key_type("run", "end_time", kind_real), &
        & key_type("run", "output_step", kind_real), &
        & key_type("run", "formulation", kind_string), &
        & key_type("run", "method", kind_string), &
        & key_type("run", "drift", kind_string), &
        & key_type("run", "jacobian", kind_string), &
        & key_type("run", "height", kind_string), &
        & key_type("run", "rtol", kind_real), &
        & key_type("run", "atol", kind_real), &
        & key_type("run", "baumgarte_rate", kind_real), &
        & key_type("run", "max_steps", kind_integer), &
        & key_type("limits", "theta_min", kind_real), &
        & key_type("limits", "stop_on_liftoff", kind_logical)]

contains

    !> Every key must belong to its group and its value must read as the key's kind; reals
    !> must be finite.
    subroutine check_keys(path, groups, error)
        !> Scene file, for messages
        character(len=*), intent(in) :: path
        !> Groups as scanned
        type(group_type), intent(in) :: groups(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: i, j, k

        do i = 1, size(groups)
            do j = 1, size(groups(i)%assignments)
                associate (assignment => groups(i)%assignments(j))
                    k = find_key(groups(i)%name, assignment%key)
                    if (k == 0) then
                        call input_error(error, path, assignment%line, assignment%key, &
                            & "is not a key of &" // groups(i)%name // "; keys are " &
                            & // key_list(groups(i)%name))
                        return
                    end if
                    call check_value(path, groups(i)%name, assignment, scene_keys(k)%kind, &
                        & error)
                    if (allocated(error)) return
                end associate
            end do
        end do
    end subroutine check_keys

    !> Line where key is given in group, 0 when it is not given.
    pure integer function key_line(groups, group, key) result(line)
        !> Groups as scanned
        type(group_type), intent(in) :: groups(:)
        !> Group and key, lowercase
        character(len=*), intent(in) :: group, key
        integer :: i, j

        line = 0
        do i = 1, size(groups)
            if (groups(i)%name /= group) cycle
            do j = 1, size(groups(i)%assignments)
                if (groups(i)%assignments(j)%key == key) line = groups(i)%assignments(j)%line
            end do
        end do
    end function key_line

    !> The value must be one item of the expected kind (no repeat count).
    subroutine check_value(path, group, assignment, kind, error)
        character(len=*), intent(in) :: path, group
        type(assignment_type), intent(in) :: assignment
        integer, intent(in) :: kind
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: expected
        real(wp) :: real_value
        integer :: integer_value, stat
        logical :: ok

        select case (kind)
        case (kind_real)
            expected = "a real number"
            ok = .not. assignment%quoted .and. scan(assignment%value, "*") == 0
            if (ok) then
                read(assignment%value, *, iostat=stat) real_value
                ok = stat == 0
            end if
            if (ok .and. .not. ieee_is_finite(real_value)) then
                call input_error(error, path, assignment%line, assignment%key, "in &" // group &
                    & // " must be a finite number, got " // assignment%value)
                return
            end if
        case (kind_integer)
            expected = "an integer"
            ok = .not. assignment%quoted .and. scan(assignment%value, "*") == 0
            if (ok) then
                read(assignment%value, *, iostat=stat) integer_value
                ok = stat == 0
            end if
        case (kind_logical)
            expected = ".true. or .false."
            select case (to_lower(assignment%value))
            case (".true.", ".false.", "t", "f", ".t.", ".f.", "true", "false")
                ok = .true.
            case default
                ok = .false.
            end select
        case default
            expected = "a quoted string, as in 'ida'"
            ok = assignment%quoted
        end select
        if (.not. ok) then
            call input_error(error, path, assignment%line, assignment%key, "in &" // group &
                & // " must be " // expected // ", got " // assignment%value)
        end if
    end subroutine check_value

    !> Index of key in the table of group, 0 when not there.
    pure integer function find_key(group, key) result(k)
        character(len=*), intent(in) :: group, key

        do k = 1, size(scene_keys)
            if (scene_keys(k)%group == group .and. scene_keys(k)%name == key) return
        end do
        k = 0
    end function find_key

    !> Keys of a group, comma separated.
    pure function key_list(group) result(list)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: list
        integer :: k

        list = ""
        do k = 1, size(scene_keys)
            if (scene_keys(k)%group /= group) cycle
            if (len(list) > 0) list = list // ", "
            list = list // trim(scene_keys(k)%name)
        end do
    end function key_list

end module rollcon_scene_keys
