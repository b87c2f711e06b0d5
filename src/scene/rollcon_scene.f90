! SPDX-License-Identifier: MIT
!> A scene: the disk, its initial state, gravity, an optional strike, and how to run it, read
!> from a namelist file in data/ (docs/design.md §6, docs/scenes.md) and checked before
!> anything uses it.
module rollcon_scene
    use rollcon_error, only : error_type
    use rollcon_scene_lexer, only : line_type, group_type, read_lines, scan_groups
    use rollcon_scene_bytes, only : check_bytes, visible
    use rollcon_scene_keys, only : key_type, bind_keys, scene_groups, choice_code, choice_name
    use rollcon_scene_values, only : store_values
    use rollcon_scene_check, only : check_scene, key_line
    use rollcon_scene_type, only : scene_type, formulation_cvode, formulation_ida, method_bdf, &
        & method_adams, drift_none, drift_projection, drift_baumgarte, jacobian_analytic, &
        & jacobian_dq, height_velocity, height_position
    implicit none
    private

    public :: scene_type, read_scene, read_scene_lines, scene_path, choice_code, choice_name
    public :: formulation_cvode, formulation_ida, method_bdf, method_adams
    public :: drift_none, drift_projection, drift_baumgarte
    public :: jacobian_analytic, jacobian_dq, height_velocity, height_position

contains

    !> Read and check a scene file. On error the scene holds only defaults.
    subroutine read_scene(path, scene, error)
        !> Scene file
        character(len=*), intent(in) :: path
        !> The scene read
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)

        scene%path = path
        scene%name = base_name(path)
        call read_lines(path, lines, error)
        if (allocated(error)) return
        call read_scene_lines(path, lines, scene, error)
    end subroutine read_scene

    !> Read and check a scene given as lines: the bytes are checked, the lexer splits the lines
    !> into groups of `key = value` (rollcon_scene_lexer), each value is converted and checked
    !> by its key's entry of the table (rollcon_scene_keys), then the checks that involve
    !> several keys run (rollcon_scene_check). On error the scene holds only defaults.
    subroutine read_scene_lines(path, lines, scene, error)
        !> File the lines come from: messages name it, the scene takes its name from it
        character(len=*), intent(in) :: path
        !> Lines of the file, without line ends
        type(line_type), intent(in) :: lines(:)
        !> The scene read
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: text(:)
        type(group_type), allocatable :: groups(:)
        type(key_type), allocatable :: keys(:)
        type(scene_type), target :: new
        integer :: k

        scene%path = path
        scene%name = base_name(path)
        text = lines
        call check_bytes(path, text, error)
        if (allocated(error)) return
        call scan_groups(visible(path), text, scene_groups, groups, error)
        if (allocated(error)) return
        call bind_keys(new, keys)
        call store_values(path, groups, keys, error)
        if (allocated(error)) return
        new%strike%enabled = any([(groups(k)%name == "strike", k = 1, size(groups))])
        new%initial%z_given = key_line(groups, "initial", "z") > 0
        new%initial%velocity_given = key_line(groups, "initial", "xdot") > 0 &
            & .or. key_line(groups, "initial", "ydot") > 0 &
            & .or. key_line(groups, "initial", "zdot") > 0
        call check_scene(path, groups, new, error)
        if (allocated(error)) return
        new%path = path
        new%name = base_name(path)
        scene = new
    end subroutine read_scene_lines

    !> Path of a scene: 'coin' is data/coin.nml; a name with '/' or ending in '.nml' is a path.
    pure function scene_path(name) result(path)
        !> Scene name or path
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: path

        if (index(name, "/") > 0 .or. ends_with(name, ".nml")) then
            path = name
        else
            path = "data/" // name // ".nml"
        end if
    end function scene_path

    !> File name without directory and without '.nml'.
    pure function base_name(path) result(name)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: name

        name = path(index(path, "/", back=.true.) + 1:)
        if (ends_with(name, ".nml")) name = name(:len(name) - 4)
    end function base_name

    pure logical function ends_with(text, tail)
        character(len=*), intent(in) :: text, tail

        ends_with = .false.
        if (len(text) >= len(tail)) ends_with = text(len(text) - len(tail) + 1:) == tail
    end function ends_with

end module rollcon_scene
