! SPDX-License-Identifier: MIT
!> Helpers of the picture tests: a short run written to a CSV, scratch folders under build/,
!> and a reader of the VTK files we write that counts what they hold.
module picture_files
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_scene, only : scene_type
    use rollcon_problem, only : problem_type
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & csv_header
    use motion_runs, only : default_scene
    implicit none
    private

    public :: picture_scene, run_to_csv, make_folder, remove_folder, write_lines
    public :: vtu_contents_type, read_vtu, read_pvd, command_available

    !> What a .vtu file declares and holds
    type :: vtu_contents_type
        !> NumberOfPoints and NumberOfCells of the piece
        integer :: declared_points = -1, declared_cells = -1
        !> Values in the Points, connectivity, offsets, types and colour arrays
        integer :: point_values = 0, connectivity_values = 0, offset_values = 0, &
            & type_values = 0, colour_values = 0
        !> The points, the connectivity and the offsets
        real(wp), allocatable :: points(:, :)
        integer, allocatable :: connectivity(:), offsets(:)
    end type vtu_contents_type

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

    !> Simulate scene, writing csv_path, and keep the rows; header gets the CSV's columns.
    subroutine run_to_csv(scene, csv_path, history, header, error)
        type(scene_type), intent(in) :: scene
        character(len=*), intent(in) :: csv_path
        type(history_type), intent(out) :: history
        character(len=16), allocatable, intent(out) :: header(:)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        real(wp) :: q0(6), u0(6)

        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        options%end_time = scene%run%end_time
        options%output_step = scene%run%output_step
        options%progress = .false.
        options%csv_path = csv_path
        header = csv_header(problem)
        call simulate(problem, q0, u0, options, summary, error, history)
    end subroutine run_to_csv

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

    !> Read a .vtu frame: the piece's declared sizes and every value of its data arrays.
    !> Relies on our layout: each DataArray's start and end tag on a line of its own.
    subroutine read_vtu(path, vtu, error)
        character(len=*), intent(in) :: path
        type(vtu_contents_type), intent(out) :: vtu
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: line
        character(len=:), allocatable :: name, values
        real(wp), allocatable :: numbers(:)
        integer :: unit, stat, count
        logical :: in_piece

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
                vtu%declared_points = nint(real_attribute(line, "NumberOfPoints"))
                vtu%declared_cells = nint(real_attribute(line, "NumberOfCells"))
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
                vtu%point_values = count
                vtu%points = reshape(numbers, [3, count/3])
            case ("connectivity")
                vtu%connectivity_values = count
                vtu%connectivity = nint(numbers)
            case ("offsets")
                vtu%offset_values = count
                vtu%offsets = nint(numbers)
            case ("types")
                vtu%type_values = count
            case ("colour")
                vtu%colour_values = count
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

end module picture_files
