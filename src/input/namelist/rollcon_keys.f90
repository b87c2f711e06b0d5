! SPDX-License-Identifier: MIT
!> A table of keys: for each key of a namelist-style input (a scene's &group key = value, a
!> dataset's INTEGRATOR keyword, a study's parameter) its group, kind, unit, allowed range or
!> choices, and the component its value goes to (a pointer into the object being read). The
!> tables themselves: rollcon_run_keys (how to integrate) and rollcon_scene_keys (a scene).
module rollcon_keys
    use rollcon_kinds, only : wp
    use rollcon_text, only : lower_case
    implicit none
    private

    public :: key_type, option_type, real_key, integer_key, logical_key, choice_key
    public :: find_key, key_list, option_code, option_name
    public :: kind_real, kind_integer, kind_logical, kind_choice

    !> Value kinds
    integer, parameter :: kind_real = 1, kind_integer = 2, kind_logical = 3, kind_choice = 4

    !> One option of a choice key and its code
    type :: option_type
        character(len=12) :: name = ""
        integer :: code = 0
    end type option_type

    !> A key: where it belongs, what it takes, where its value goes
    type :: key_type
        character(len=11) :: group = ""
        character(len=24) :: name = ""
        integer :: kind = kind_real
        !> Unit, for messages and docs ("" when none)
        character(len=8) :: unit = ""
        !> Allowed range of a real or integer value; an open end excludes its bound
        real(wp) :: lower = -huge(1.0_wp), upper = huge(1.0_wp)
        logical :: lower_open = .false., upper_open = .false.
        !> Options of a choice key
        type(option_type), allocatable :: options(:)
        !> The scene component the value goes to (one, by kind)
        real(wp), pointer :: real_value => null()
        integer, pointer :: integer_value => null()
        logical, pointer :: logical_value => null()
    end type key_type

contains

    !> A real key with its range [lower, upper] (an open end excludes its bound).
    function real_key(group, name, value, unit, lower, upper, lower_open, upper_open) &
            & result(key)
        character(len=*), intent(in) :: group, name, unit
        real(wp), target, intent(inout) :: value
        real(wp), intent(in) :: lower, upper
        logical, intent(in), optional :: lower_open, upper_open
        type(key_type) :: key

        key = key_type(group, name, kind_real, unit, lower, upper)
        if (present(lower_open)) key%lower_open = lower_open
        if (present(upper_open)) key%upper_open = upper_open
        key%real_value => value
    end function real_key

    !> An integer key with its range [lower, upper].
    function integer_key(group, name, value, lower, upper) result(key)
        character(len=*), intent(in) :: group, name
        integer, target, intent(inout) :: value
        integer, intent(in) :: lower, upper
        type(key_type) :: key

        key = key_type(group, name, kind_integer, "", real(lower, wp), real(upper, wp))
        key%integer_value => value
    end function integer_key

    !> A logical key.
    function logical_key(group, name, value) result(key)
        character(len=*), intent(in) :: group, name
        logical, target, intent(inout) :: value
        type(key_type) :: key

        key = key_type(group, name, kind_logical)
        key%logical_value => value
    end function logical_key

    !> A choice: one of the options' names, stored as its code.
    function choice_key(group, name, value, options) result(key)
        character(len=*), intent(in) :: group, name
        integer, target, intent(inout) :: value
        type(option_type), intent(in) :: options(:)
        type(key_type) :: key

        key = key_type(group, name, kind_choice)
        key%options = options
        key%integer_value => value
    end function choice_key

    !> Code of the option named word (any case) of the choice key (group, name) of keys, 0
    !> when there is none.
    function option_code(keys, group, name, word) result(code)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: group, name, word
        integer :: code
        integer :: k, j

        code = 0
        k = find_key(keys, group, name)
        if (k == 0) return
        if (keys(k)%kind /= kind_choice) return
        do j = 1, size(keys(k)%options)
            if (keys(k)%options(j)%name == lower_case(word)) code = keys(k)%options(j)%code
        end do
    end function option_code

    !> Name of the option with this code of the choice key (group, name), "?" when none.
    function option_name(keys, group, name, code) result(word)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: group, name
        integer, intent(in) :: code
        character(len=:), allocatable :: word
        integer :: k, j

        word = "?"
        k = find_key(keys, group, name)
        if (k == 0) return
        if (keys(k)%kind /= kind_choice) return
        do j = 1, size(keys(k)%options)
            if (keys(k)%options(j)%code == code) word = trim(keys(k)%options(j)%name)
        end do
    end function option_name

    !> Index of key in the table of group, 0 when not there.
    pure integer function find_key(keys, group, name) result(k)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: group, name

        do k = 1, size(keys)
            if (keys(k)%group == group .and. keys(k)%name == name) return
        end do
        k = 0
    end function find_key

    !> Keys of a group, comma separated.
    pure function key_list(keys, group) result(list)
        type(key_type), intent(in) :: keys(:)
        character(len=*), intent(in) :: group
        character(len=:), allocatable :: list
        integer :: k

        list = ""
        do k = 1, size(keys)
            if (keys(k)%group /= group) cycle
            if (len(list) > 0) list = list // ", "
            list = list // trim(keys(k)%name)
        end do
    end function key_list

end module rollcon_keys
