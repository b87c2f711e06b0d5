! SPDX-License-Identifier: MIT
!> Helpers of the picture tests: hand-made runs written as an output CSV through the output
!> layout (a disk scene's, with its contact columns, and a model of two parts), scratch folders
!> under build/, and a reader of the VTK files we write that counts what they hold.
module picture_files
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_testing, only : check
    use rollcon_output_layout, only : new_output_layout, name_length, coord_x
    use rollcon_watch_columns, only : contact_names
    use rollcon_part_shapes, only : write_part_shapes, parts_path, shape_disk, shape_ellipsoid
    use rollcon_run_record, only : run_record_type
    use rollcon_scene, only : scene_type
    use motion_runs, only : default_scene
    implicit none
    private

    public :: picture_scene, disk_run, two_part_run, falling_run, write_run, make_folder, &
        & remove_folder, write_lines
    public :: vtu_piece_type, read_vtu, read_pvd, command_available, expect_message, &
        & file_starts_with

    !> Disk radius and thickness of the hand-made runs [m]
    real(wp), parameter, public :: disk_radius = 0.1_wp, disk_thickness = 0.003_wp
    !> Semi-axes of the two-part run's ellipsoid, part 7 [m]
    real(wp), parameter, public :: ellipsoid_axes(3) = [0.05_wp, 0.04_wp, 0.03_wp]
    !> Rows of the hand-made runs: 0 to 0.5 s every 0.01 s
    integer, parameter, public :: run_rows = 51
    !> Time between rows [s]
    real(wp), parameter :: row_step = 0.01_wp

    !> What one <Piece> of a .vtu file declares and holds
    type :: vtu_piece_type
        !> NumberOfPoints and NumberOfCells of the piece
        integer :: declared_points = -1, declared_cells = -1
        !> Values in the Points, connectivity, offsets, types, colour and part arrays
        integer :: point_values = 0, connectivity_values = 0, offset_values = 0, &
            & type_values = 0, colour_values = 0, part_values = 0
        !> The points, the connectivity, the offsets and the part ids of the cells
        real(wp), allocatable :: points(:, :)
        integer, allocatable :: connectivity(:), offsets(:), parts(:)
    end type vtu_piece_type

contains

    !> A disk tilted, turning and spinning, 0.5 s, a row every 0.01 s.
    function picture_scene() result(scene)
        type(scene_type) :: scene

        scene = default_scene()
        scene%name = "picture"
        scene%initial%theta = 1.2_wp
        scene%initial%psidot = 2.0_wp
        scene%initial%phidot = -6.0_wp
        scene%run%end_time = 0.5_wp
        scene%run%output_step = 0.01_wp
    end function picture_scene

    !> A disk scene's run (the contact columns, UCONs 1, 2, 3): the disk of radius disk_radius
    !> at constant tilt theta = 1.2 rad precessing at 2 rad/s and spinning at -6 rad/s, its
    !> contact point on a circle of radius 0.3 m and its centre at Z = R sin(theta), as the
    !> contact requires. Energy, residuals, multipliers and forces are smooth made-up numbers.
    function disk_run() result(run)
        type(run_record_type) :: run
        real(wp), parameter :: theta = 1.2_wp, omega = 2.0_wp, spin = -6.0_wp, circle = 0.3_wp
        real(wp) :: row(26), t, psi, e_y2(3), e_y2_dot(3)
        integer :: j, k

        run%layout = new_output_layout([1], [1, 2, 3], contact_names)
        allocate(run%shapes(1))
        run%shapes(1)%id = 1
        run%shapes(1)%kind = shape_disk
        run%shapes(1)%radius = disk_radius
        run%shapes(1)%thickness = disk_thickness
        do j = 1, run_rows
            t = row_step*real(j - 1, wp)
            psi = omega*t
            e_y2 = [-cos(theta)*sin(psi), cos(theta)*cos(psi), sin(theta)]
            e_y2_dot = omega*[-cos(theta)*cos(psi), -cos(theta)*sin(psi), 0.0_wp]
            row = 0.0_wp
            row(1) = t
            associate (c => run%layout%part_column(1, coord_x))
                row(c:c + 2) = circle*[sin(psi), 1.0_wp - cos(psi), 0.0_wp] + disk_radius*e_y2
                row(c + 3:c + 5) = [psi, theta, spin*t]
                row(c + 6:c + 8) = circle*omega*[cos(psi), sin(psi), 0.0_wp] &
                    & + disk_radius*e_y2_dot
                row(c + 9:c + 11) = [omega, 0.0_wp, spin]
            end associate
            row(run%layout%energy_column()) = 0.7_wp + 1.0e-9_wp*t
            do k = 1, 3
                row(run%layout%residual_column(k)) = 1.0e-10_wp*sin(real(k, wp)*t)
                row(run%layout%multiplier_column(k)) = 0.5_wp*real(k, wp)*cos(t)
            end do
            row(run%layout%column("Fx")) = -0.3_wp*sin(psi)
            row(run%layout%column("Fy")) = 0.3_wp*cos(psi)
            row(run%layout%column("Fz")) = 7.2_wp
            row(run%layout%column("Fn")) = 7.2_wp
            row(run%layout%column("mu_needed")) = 0.3_wp/7.2_wp
            row(run%layout%column("height_residual")) = 1.0e-12_wp*t
            call run%history%add(row)
        end do
    end function disk_run

    !> A model of two parts and two UCONs (ids 3 and 5), no contact columns: part 1 a disk
    !> rolling upright along X at 0.2 m/s, part 7 the ellipsoid ellipsoid_axes circling the
    !> origin at 2 rad/s while it bobs, nods and spins.
    function two_part_run() result(run)
        type(run_record_type) :: run
        real(wp) :: row(2 + 24 + 4), t
        integer :: j, c

        run%layout = new_output_layout([1, 7], [3, 5])
        allocate(run%shapes(2))
        run%shapes(1)%id = 1
        run%shapes(1)%kind = shape_disk
        run%shapes(1)%radius = disk_radius
        run%shapes(1)%thickness = disk_thickness
        run%shapes(2)%id = 7
        run%shapes(2)%kind = shape_ellipsoid
        run%shapes(2)%semi_axes = ellipsoid_axes
        do j = 1, run_rows
            t = row_step*real(j - 1, wp)
            row = 0.0_wp
            row(1) = t
            c = run%layout%part_column(1, coord_x)
            row(c:c + 11) = [0.2_wp*t, 0.0_wp, disk_radius, 0.0_wp, 2.0_wp*atan(1.0_wp), &
                & -2.0_wp*t, 0.2_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -2.0_wp]
            c = run%layout%part_column(2, coord_x)
            row(c:c + 5) = [0.3_wp*cos(2.0_wp*t), 0.3_wp*sin(2.0_wp*t), &
                & 0.2_wp + 0.05_wp*sin(3.0_wp*t), 2.0_wp*t, 1.0_wp + 0.2_wp*sin(t), 5.0_wp*t]
            row(c + 6:c + 11) = [-0.6_wp*sin(2.0_wp*t), 0.6_wp*cos(2.0_wp*t), &
                & 0.15_wp*cos(3.0_wp*t), 2.0_wp, 0.2_wp*cos(t), 5.0_wp]
            row(run%layout%energy_column()) = 1.5_wp - 2.0e-9_wp*t
            row(run%layout%residual_column(1)) = 3.0e-11_wp*t
            row(run%layout%residual_column(2)) = 0.0_wp
            row(run%layout%multiplier_column(1)) = -0.4_wp
            row(run%layout%multiplier_column(2)) = 1.2_wp*sin(t)
            call run%history%add(row)
        end do
    end function two_part_run

    !> A model of one part (id 2, the ellipsoid ellipsoid_axes) and no UCON, falling freely from
    !> Z = 1 m and turning about its body z axis.
    function falling_run() result(run)
        type(run_record_type) :: run
        real(wp), parameter :: g = 9.81_wp
        real(wp) :: row(14), t
        integer :: j

        run%layout = new_output_layout([2], [integer ::])
        allocate(run%shapes(1))
        run%shapes(1)%id = 2
        run%shapes(1)%kind = shape_ellipsoid
        run%shapes(1)%semi_axes = ellipsoid_axes
        do j = 1, run_rows
            t = row_step*real(j - 1, wp)
            row = [t, 0.0_wp, 0.0_wp, 1.0_wp - 0.5_wp*g*t**2, 0.0_wp, 1.0_wp, 3.0_wp*t, &
                & 0.0_wp, 0.0_wp, -g*t, 0.0_wp, 0.0_wp, 3.0_wp, 1.0_wp]
            call run%history%add(row)
        end do
    end function falling_run

    !> Write a run's CSV as `rollcon run` does (the layout's header, 17 significant digits),
    !> and, when parts is true, its part shapes beside it (DIR/NAME.parts).
    subroutine write_run(csv_path, run, parts, error)
        character(len=*), intent(in) :: csv_path
        type(run_record_type), intent(in) :: run
        logical, intent(in) :: parts
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: header
        character(len=name_length), allocatable :: names(:)
        integer :: unit, j, k

        names = run%layout%header()
        header = trim(names(1))
        do k = 2, size(names)
            header = header // "," // trim(names(k))
        end do
        open(newunit=unit, file=csv_path, status="replace", action="write")
        write(unit, '(a)') header
        do j = 1, run%history%count
            write(unit, '(*(es24.16e3, :, ","))') run%history%rows(:, j)
        end do
        close(unit)
        if (parts) call write_part_shapes(parts_path(csv_path), run%shapes, error)
    end subroutine write_run

    !> True when a shell command (e.g. 'python3') is on the PATH.
    function command_available(name) result(available)
        character(len=*), intent(in) :: name
        logical :: available
        integer :: stat, command_stat

        stat = 1
        call execute_command_line("command -v " // name // " > /dev/null 2>&1", &
            & exitstat=stat, cmdstat=command_stat)
        available = command_stat == 0 .and. stat == 0
    end function command_available

    !> Create a scratch folder (and build/ above it).
    subroutine make_folder(folder)
        character(len=*), intent(in) :: folder

        call execute_command_line("mkdir -p " // folder)
    end subroutine make_folder

    !> Remove a scratch folder and everything in it.
    subroutine remove_folder(folder)
        character(len=*), intent(in) :: folder

        call execute_command_line("rm -rf " // folder)
    end subroutine remove_folder

    !> Write a text file of the given lines (trailing blanks trimmed).
    subroutine write_lines(path, lines)
        character(len=*), intent(in) :: path, lines(:)
        integer :: unit, i

        open(newunit=unit, file=path, status="replace", action="write")
        do i = 1, size(lines)
            write(unit, '(a)') trim(lines(i))
        end do
        close(unit)
    end subroutine write_lines

    !> The timesteps and files of a .pvd collection, in order.
    subroutine read_pvd(path, times, files, error)
        character(len=*), intent(in) :: path
        real(wp), allocatable, intent(out) :: times(:)
        character(len=64), allocatable, intent(out) :: files(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: line
        integer :: unit, stat

        allocate(times(0), files(0))
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot open")
            return
        end if
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, "<DataSet") == 0) cycle
            times = [times, real_attribute(line, "timestep")]
            files = [character(len=64) :: files, text_attribute(line, "file")]
        end do
        close(unit)
    end subroutine read_pvd

    !> Read a .vtu frame: each piece's declared sizes and every value of its data arrays.
    !> Relies on our layout: each DataArray's start and end tag on a line of its own.
    subroutine read_vtu(path, pieces, error)
        character(len=*), intent(in) :: path
        type(vtu_piece_type), allocatable, intent(out) :: pieces(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: line
        character(len=:), allocatable :: name, values
        real(wp), allocatable :: numbers(:)
        type(vtu_piece_type) :: piece
        integer :: unit, stat, count
        logical :: in_piece

        allocate(pieces(0))
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot open")
            return
        end if
        in_piece = .false.
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, "<Piece") > 0) then
                in_piece = .true.
                piece = vtu_piece_type()
                piece%declared_points = nint(real_attribute(line, "NumberOfPoints"))
                piece%declared_cells = nint(real_attribute(line, "NumberOfCells"))
            end if
            if (index(line, "</Piece>") > 0) then
                in_piece = .false.
                pieces = [pieces, piece]
            end if
            if (.not. in_piece .or. index(line, "<DataArray") == 0) cycle
            name = text_attribute(line, "Name")
            if (index(line, "NumberOfComponents=""3""") > 0) name = "Points"
            values = ""
            do
                read(unit, '(a)', iostat=stat) line
                if (stat /= 0 .or. index(line, "</DataArray>") > 0) exit
                values = values // " " // trim(line)
            end do
            count = token_count(values)
            allocate(numbers(count))
            read(values, *, iostat=stat) numbers
            if (stat /= 0) then
                call fatal_error(error, path // ": array " // name // " holds a non-number")
                exit
            end if
            select case (name)
            case ("Points")
                piece%point_values = count
                piece%points = reshape(numbers, [3, count/3])
            case ("connectivity")
                piece%connectivity_values = count
                piece%connectivity = nint(numbers)
            case ("offsets")
                piece%offset_values = count
                piece%offsets = nint(numbers)
            case ("types")
                piece%type_values = count
            case ("colour")
                piece%colour_values = count
            case ("part")
                piece%part_values = count
                piece%parts = nint(numbers)
            end select
            deallocate(numbers)
        end do
        close(unit)
    end subroutine read_vtu

    !> Number of blank-separated tokens of a text.
    pure function token_count(text) result(count)
        character(len=*), intent(in) :: text
        integer :: count, i
        logical :: in_token

        count = 0
        in_token = .false.
        do i = 1, len(text)
            if (text(i:i) /= " " .and. .not. in_token) count = count + 1
            in_token = text(i:i) /= " "
        end do
    end function token_count

    !> The value of attribute key="..." on a line, or "" when absent.
    pure function text_attribute(line, key) result(value)
        character(len=*), intent(in) :: line, key
        character(len=:), allocatable :: value
        integer :: start, length

        value = ""
        start = index(line, " " // key // "=""")
        if (start == 0) return
        start = start + len(key) + 3
        length = index(line(start:), """") - 1
        if (length >= 0) value = line(start:start + length - 1)
    end function text_attribute

    !> The value of attribute key="..." read as a real; -1 when absent or not a number.
    function real_attribute(line, key) result(value)
        character(len=*), intent(in) :: line, key
        real(wp) :: value
        character(len=:), allocatable :: text
        integer :: stat

        text = text_attribute(line, key)
        read(text, *, iostat=stat) value
        if (stat /= 0) value = -1.0_wp
    end function real_attribute

    !> Fail unless failure is set and its message holds text and, if given, also_text.
    subroutine expect_message(error, failure, text, also_text)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable, intent(in) :: failure
        character(len=*), intent(in) :: text
        character(len=*), intent(in), optional :: also_text

        call check(error, allocated(failure), "no error reported")
        if (allocated(error)) return
        call check(error, index(failure%message, text) > 0, "message '" // failure%message &
            & // "' lacks '" // text // "'")
        if (allocated(error) .or. .not. present(also_text)) return
        call check(error, index(failure%message, also_text) > 0, "message '" &
            & // failure%message // "' lacks '" // also_text // "'")
    end subroutine expect_message

    !> True when the file exists and starts with the given bytes.
    function file_starts_with(path, magic) result(starts)
        character(len=*), intent(in) :: path, magic
        logical :: starts
        character(len=len(magic)) :: head
        integer :: unit, stat

        starts = .false.
        open(newunit=unit, file=path, access="stream", form="unformatted", status="old", &
            & action="read", iostat=stat)
        if (stat /= 0) return
        read(unit, iostat=stat) head
        close(unit)
        starts = stat == 0 .and. head == magic
    end function file_starts_with

end module picture_files
