! SPDX-License-Identifier: MIT
!> A scene: the disk, its initial state, gravity, an optional strike, and how to run it, read
!> from a namelist file in data/ (docs/design.md §6, docs/scenes.md) and checked before
!> anything uses it.
module rollcon_scene
    use rollcon_error, only : error_type, input_error
    use rollcon_namelist_lexer, only : line_type, group_type, assignment_type, read_lines, &
        & scan_groups
    use rollcon_text, only : to_text
    use rollcon_namelist_bytes, only : check_bytes, visible
    use rollcon_keys, only : key_type
    use rollcon_scene_keys, only : bind_keys, scene_groups, choice_code, choice_name
    use rollcon_key_values, only : store_values
    use rollcon_scene_check, only : check_scene, key_line
    use rollcon_scene_type, only : scene_type, formulation_cvode, formulation_ida, method_bdf, &
        & method_adams, drift_none, drift_projection, drift_baumgarte, jacobian_analytic, &
        & jacobian_dq, height_velocity, height_position
    implicit none
    private

    public :: scene_type, read_scene, read_scene_lines, scene_path, choice_code, choice_name
    public :: scene_override_type
    public :: formulation_cvode, formulation_ida, method_bdf, method_adams
    public :: drift_none, drift_projection, drift_baumgarte
    public :: jacobian_analytic, jacobian_dq, height_velocity, height_position

    !> A key set apart from the file (a parameter study's case, rollcon_study): it replaces
    !> the key's value in the file, or is added to its group (a group the file lacks is added
    !> too: an added &strike enables the strike)
    type :: scene_override_type
        !> Group and key, lowercase, as in the file
        character(len=:), allocatable :: group, key
        !> Value as it would be written in the file
        character(len=:), allocatable :: value
    end type scene_override_type

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
    !> into groups of `key = value` (rollcon_namelist_lexer), each value is converted and checked
    !> by its key's entry of the table (rollcon_scene_keys), then the checks that involve
    !> several keys run (rollcon_scene_check). On error the scene holds only defaults.
    !> With overrides, their values replace the file's (a message about an overridden key
    !> points at its group's line, or at line 1 for a group the file lacks).
    subroutine read_scene_lines(path, lines, scene, error, overrides)
        !> File the lines come from: messages name it, the scene takes its name from it
        character(len=*), intent(in) :: path
        !> Lines of the file, without line ends
        type(line_type), intent(in) :: lines(:)
        !> The scene read
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        !> Keys set apart from the file
        type(scene_override_type), intent(in), optional :: overrides(:)
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
        if (present(overrides)) call apply_overrides(overrides, groups)
        call bind_keys(new, keys)
        call store_values(path, groups, keys, error)
        if (allocated(error)) return
        call spin_from_speed(path, groups, new, error)
        if (allocated(error)) return
        new%strike%enabled = any([(groups(k)%name == "strike", k = 1, size(groups))])
        new%contact%enabled = any([(groups(k)%name == "contact", k = 1, size(groups))])
        new%dissipation%enabled = any([(groups(k)%name == "dissipation", k = 1, size(groups))])
        if (key_line(groups, "contact", "mu_kinetic") == 0) &
            & new%contact%mu_kinetic = new%contact%mu_static
        new%contact%flight = key_line(groups, "contact", "restitution") > 0
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

    !> Replace or add each override's assignment in its group, adding the group if missing.
    pure subroutine apply_overrides(overrides, groups)
        type(scene_override_type), intent(in) :: overrides(:)
        type(group_type), allocatable, intent(inout) :: groups(:)
        type(assignment_type) :: assignment
        type(group_type) :: added
        integer :: k, g, a

        do k = 1, size(overrides)
            g = 0
            do a = 1, size(groups)
                if (groups(a)%name == overrides(k)%group) g = a
            end do
            if (g == 0) then
                added%name = overrides(k)%group
                added%line = 1
                allocate(added%assignments(0))
                groups = [groups, added]
                deallocate(added%assignments)
                g = size(groups)
            end if
            ! component by component: gfortran 12 loses deferred-length components passed to
            ! a structure constructor
            assignment%key = overrides(k)%key
            assignment%value = overrides(k)%value
            assignment%quoted = .false.
            assignment%line = groups(g)%line
            do a = size(groups(g)%assignments), 1, -1
                if (groups(g)%assignments(a)%key == overrides(k)%key) exit
            end do
            if (a > 0) then
                assignment%line = groups(g)%assignments(a)%line
                groups(g)%assignments(a) = assignment
            else
                groups(g)%assignments = [groups(g)%assignments, assignment]
            end if
        end do
    end subroutine apply_overrides

    !> &initial speed, when given, sets phidot so that the centre rolls at that speed along
    !> the heading: phidot = -speed/radius - psidot cos(theta) (docs/design.md §5). It
    !> cannot be given with phidot.
    subroutine spin_from_speed(path, groups, scene, error)
        character(len=*), intent(in) :: path
        type(group_type), intent(in) :: groups(:)
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        integer :: line

        line = key_line(groups, "initial", "speed")
        if (line == 0) return
        if (key_line(groups, "initial", "phidot") > 0) then
            call input_error(error, visible(path), line, "speed", "in &initial cannot be " &
                & // "given with 'phidot' (line " // to_text(key_line(groups, "initial", &
                & "phidot")) // "): both set the spin; give one")
            return
        end if
        associate (i => scene%initial)
            i%phidot = -i%speed/scene%disk%radius - i%psidot*cos(i%theta)
        end associate
    end subroutine spin_from_speed

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
