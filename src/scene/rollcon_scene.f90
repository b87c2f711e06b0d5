! SPDX-License-Identifier: MIT
!> A scene: the disk, its initial state, gravity, an optional strike, and how to run it, read
!> from a namelist file in data/ (DESIGN.md section 6) and checked before anything uses it.
module rollcon_scene
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_scene_lexer, only : line_type, group_type, read_lines, scan_groups, to_lower
    use rollcon_scene_keys, only : scene_groups, check_keys, key_line
    use rollcon_scene_type, only : scene_type, check_scene
    implicit none
    private

    public :: scene_type, read_scene, scene_path

    !> Length of the character variables of the namelist reads
    integer, parameter :: choice_length = 64

contains

    !> Read and check a scene file. On error the scene holds only defaults.
    !> The file is first scanned as text (rollcon_scene_lexer), so that stray text, an unknown
    !> group or key, or a value of the wrong kind is reported at its line; each group's checked
    !> assignments are then read by a namelist read of an internal file.
    subroutine read_scene(path, scene, error)
        !> Scene file
        character(len=*), intent(in) :: path
        !> The scene read
        type(scene_type), intent(out) :: scene
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(group_type), allocatable :: groups(:)
        type(scene_type) :: new
        character(len=:), allocatable :: record
        integer :: i

        scene%path = path
        scene%name = base_name(path)
        call set_choice_defaults(scene)
        call read_lines(path, lines, error)
        if (allocated(error)) return
        call scan_groups(path, lines, scene_groups, groups, error)
        if (allocated(error)) return
        call check_keys(path, groups, error)
        if (allocated(error)) return

        call set_choice_defaults(new)
        do i = 1, size(groups)
            record = group_record(groups(i))
            select case (groups(i)%name)
            case ("disk")
                call read_disk(path, groups(i), record, new, error)
            case ("environment")
                call read_environment(path, groups(i), record, new, error)
            case ("initial")
                call read_initial(path, groups(i), record, new, error)
            case ("strike")
                call read_strike(path, groups(i), record, new, error)
            case ("run")
                call read_run(path, groups(i), record, new, error)
            case ("limits")
                call read_limits(path, groups(i), record, new, error)
            end select
            if (allocated(error)) return
        end do
        new%has_strike = has_group(groups, "strike")
        new%z_given = key_line(groups, "initial", "z") > 0
        new%velocity_given = key_line(groups, "initial", "xdot") > 0 &
            & .or. key_line(groups, "initial", "ydot") > 0 &
            & .or. key_line(groups, "initial", "zdot") > 0
        call check_scene(path, groups, new, error)
        if (allocated(error)) return
        new%path = path
        new%name = base_name(path)
        scene = new
    end subroutine read_scene

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

    !> The group is in the file.
    pure logical function has_group(groups, name)
        type(group_type), intent(in) :: groups(:)
        character(len=*), intent(in) :: name
        integer :: i

        has_group = .false.
        do i = 1, size(groups)
            if (groups(i)%name == name) has_group = .true.
        end do
    end function has_group

    subroutine set_choice_defaults(scene)
        type(scene_type), intent(inout) :: scene

        scene%formulation = "ida"
        scene%method = "bdf"
        scene%drift = "projection"
        scene%jacobian = "analytic"
        scene%height = "velocity"
    end subroutine set_choice_defaults

    !> The group as the one record of an internal file: `&name key = value, ... /`.
    pure function group_record(group) result(record)
        type(group_type), intent(in) :: group
        character(len=:), allocatable :: record
        integer :: j

        record = "&" // group%name
        do j = 1, size(group%assignments)
            record = record // " " // group%assignments(j)%key // " = " &
                & // group%assignments(j)%value // ","
        end do
        record = record // " /"
    end function group_record

    !> Turn a failed namelist read into an input error at the group's line.
    subroutine namelist_error(path, group, stat, message, error)
        character(len=*), intent(in) :: path
        type(group_type), intent(in) :: group
        integer, intent(in) :: stat
        character(len=*), intent(in) :: message
        type(error_type), allocatable, intent(out) :: error

        character(len=*), parameter :: no_match = "Cannot match namelist object name"
        character(len=:), allocatable :: key
        integer :: j

        if (stat == 0) return
        ! gfortran's words for an unknown key; check_keys should have caught it first
        if (index(message, no_match) > 0) then
            key = to_lower(trim(adjustl(message(index(message, no_match) + len(no_match):))))
            do j = 1, size(group%assignments)
                if (group%assignments(j)%key /= key) cycle
                call input_error(error, path, group%assignments(j)%line, key, "is not a key " &
                    & // "of &" // group%name)
                return
            end do
        end if
        call input_error(error, path, group%line, "", "cannot read group '&" // group%name &
            & // "': " // trim(message))
    end subroutine namelist_error

    subroutine read_disk(path, group, record, scene, error)
        character(len=*), intent(in) :: path
        !> The group as an internal file
        character(len=*), intent(in) :: record
        type(group_type), intent(in) :: group
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: radius, thickness, density
        character(len=512) :: message
        integer :: stat
        namelist /disk/ radius, thickness, density

        radius = scene%radius
        thickness = scene%thickness
        density = scene%density
        read(record, nml=disk, iostat=stat, iomsg=message)
        call namelist_error(path, group, stat, message, error)
        if (allocated(error)) return
        scene%radius = radius
        scene%thickness = thickness
        scene%density = density
    end subroutine read_disk

    subroutine read_environment(path, group, record, scene, error)
        character(len=*), intent(in) :: path
        !> The group as an internal file
        character(len=*), intent(in) :: record
        type(group_type), intent(in) :: group
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: gravity
        character(len=512) :: message
        integer :: stat
        namelist /environment/ gravity

        gravity = scene%gravity
        read(record, nml=environment, iostat=stat, iomsg=message)
        call namelist_error(path, group, stat, message, error)
        if (allocated(error)) return
        scene%gravity = gravity
    end subroutine read_environment

    subroutine read_initial(path, group, record, scene, error)
        character(len=*), intent(in) :: path
        !> The group as an internal file
        character(len=*), intent(in) :: record
        type(group_type), intent(in) :: group
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: psi, theta, phi, psidot, thetadot, phidot, x, y, z, xdot, ydot, zdot
        character(len=512) :: message
        integer :: stat
        namelist /initial/ psi, theta, phi, psidot, thetadot, phidot, x, y, z, xdot, ydot, zdot

        psi = scene%psi
        theta = scene%theta
        phi = scene%phi
        psidot = scene%psidot
        thetadot = scene%thetadot
        phidot = scene%phidot
        x = scene%x
        y = scene%y
        z = scene%z
        xdot = scene%xdot
        ydot = scene%ydot
        zdot = scene%zdot
        read(record, nml=initial, iostat=stat, iomsg=message)
        call namelist_error(path, group, stat, message, error)
        if (allocated(error)) return
        scene%psi = psi
        scene%theta = theta
        scene%phi = phi
        scene%psidot = psidot
        scene%thetadot = thetadot
        scene%phidot = phidot
        scene%x = x
        scene%y = y
        scene%z = z
        scene%xdot = xdot
        scene%ydot = ydot
        scene%zdot = zdot
    end subroutine read_initial

    subroutine read_strike(path, group, record, scene, error)
        character(len=*), intent(in) :: path
        !> The group as an internal file
        character(len=*), intent(in) :: record
        type(group_type), intent(in) :: group
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: time, duration, impulse
        character(len=512) :: message
        integer :: stat
        namelist /strike/ time, duration, impulse

        time = scene%strike_time
        duration = scene%strike_duration
        impulse = scene%strike_impulse
        read(record, nml=strike, iostat=stat, iomsg=message)
        call namelist_error(path, group, stat, message, error)
        if (allocated(error)) return
        scene%strike_time = time
        scene%strike_duration = duration
        scene%strike_impulse = impulse
    end subroutine read_strike

    subroutine read_run(path, group, record, scene, error)
        character(len=*), intent(in) :: path
        !> The group as an internal file
        character(len=*), intent(in) :: record
        type(group_type), intent(in) :: group
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: end_time, output_step, rtol, atol, baumgarte_rate
        character(len=choice_length) :: formulation, method, drift, jacobian, height
        integer :: max_steps
        character(len=512) :: message
        integer :: stat
        namelist /run/ end_time, output_step, formulation, method, drift, jacobian, height, &
            & rtol, atol, baumgarte_rate, max_steps

        end_time = scene%end_time
        output_step = scene%output_step
        formulation = scene%formulation
        method = scene%method
        drift = scene%drift
        jacobian = scene%jacobian
        height = scene%height
        rtol = scene%rtol
        atol = scene%atol
        baumgarte_rate = scene%baumgarte_rate
        max_steps = scene%max_steps
        read(record, nml=run, iostat=stat, iomsg=message)
        call namelist_error(path, group, stat, message, error)
        if (allocated(error)) return
        scene%end_time = end_time
        scene%output_step = output_step
        ! choices are case-insensitive and kept lowercase
        scene%formulation = trim(adjustl(to_lower(formulation)))
        scene%method = trim(adjustl(to_lower(method)))
        scene%drift = trim(adjustl(to_lower(drift)))
        scene%jacobian = trim(adjustl(to_lower(jacobian)))
        scene%height = trim(adjustl(to_lower(height)))
        scene%rtol = rtol
        scene%atol = atol
        scene%baumgarte_rate = baumgarte_rate
        scene%max_steps = max_steps
    end subroutine read_run

    subroutine read_limits(path, group, record, scene, error)
        character(len=*), intent(in) :: path
        !> The group as an internal file
        character(len=*), intent(in) :: record
        type(group_type), intent(in) :: group
        type(scene_type), intent(inout) :: scene
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: theta_min
        logical :: stop_on_liftoff
        character(len=512) :: message
        integer :: stat
        namelist /limits/ theta_min, stop_on_liftoff

        theta_min = scene%theta_min
        stop_on_liftoff = scene%stop_on_liftoff
        read(record, nml=limits, iostat=stat, iomsg=message)
        call namelist_error(path, group, stat, message, error)
        if (allocated(error)) return
        scene%theta_min = theta_min
        scene%stop_on_liftoff = stop_on_liftoff
    end subroutine read_limits

end module rollcon_scene
