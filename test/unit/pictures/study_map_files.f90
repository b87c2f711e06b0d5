! SPDX-License-Identifier: MIT
!> Helpers of the study map tests: a grid study of disk thickness by rolling speed over
!> data/upright.nml with its hand-written CSV, and readers of what a map leaves behind (the
!> PNG's signature, the script's inline data blocks).
module study_map_files
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_study_type, only : study_type
    use rollcon_study_reader, only : read_study
    use rollcon_study_csv, only : study_header
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_testing, only : check, skip_test
    use picture_files, only : make_folder, write_lines, file_starts_with
    implicit none
    private

    public :: have_gnuplot, grid_study, grid_point, count_classes, measures, png_file, &
        & block_size, read_block

    !> Scratch folder of the study map tests
    character(len=*), parameter, public :: scratch = "build/test_study_map"
    !> Grid of the test study: thickness from 0.003 m to 0.03 m, speed from 0.2 to 1 m/s
    integer, parameter, public :: thickness_count = 4, speed_count = 5
    real(wp), parameter, public :: thickness_range(2) = [0.003_wp, 0.03_wp], &
        & speed_range(2) = [0.2_wp, 1.0_wp]
    !> The failed and the refused case of the test CSV
    integer, parameter, public :: failed_case = 7, refused_case = 18
    !> Width of the lines of the test files
    integer, parameter, public :: width = 320
    !> The test CSV classes a case stable from this speed up [m/s]
    real(wp), parameter :: stable_speed = 0.6_wp

contains

    !> True when gnuplot is there; else the test is skipped.
    logical function have_gnuplot(error)
        type(error_type), allocatable, intent(out) :: error

        have_gnuplot = gnuplot_available()
        if (.not. have_gnuplot) call skip_test(error, "gnuplot not found (Debian " &
            & // "gnuplot-nox; bash .ci/setup)")
    end function have_gnuplot

    !> Write scratch/grid.nml (thickness by speed, classes falls_over and stable, the critical
    !> speed curve) and read it; write scratch/grid.csv: every case, stable from stable_speed up,
    !> one failed with a quoted message holding commas and quotes, one refused, and a last
    !> line cut short (a case being written).
    subroutine grid_study(study, error)
        type(study_type), intent(out) :: study
        type(error_type), allocatable, intent(out) :: error
        character(len=width) :: rows(thickness_count*speed_count + 1)
        real(wp) :: point(2)
        integer :: i, unit

        call make_folder(scratch)
        call write_lines(scratch // "/grid.nml", [character(len=width) :: &
            & "&study scene = 'data/upright.nml', title = 'Upright stability (test map)' /", &
            & "&grid disk%thickness = '0.003 0.03 4', initial%speed = '0.2 1.0 5' /", &
            & "&classify falls_over = 'tilt_max > 1', otherwise = 'stable' /", &
            & "&map x = 'disk%thickness', y = 'initial%speed', curve = 'critical_speed' /"])
        call read_study(scratch // "/grid.nml", study, error)
        if (allocated(error)) return
        rows(1) = study_header(study)
        do i = 1, thickness_count*speed_count
            point = grid_point(i)
            rows(i + 1) = to_text(i) // "," // to_text(point(1)) // "," // to_text(point(2))
            if (i == failed_case) then
                rows(i + 1) = trim(rows(i + 1)) // ",failed,failed,-3,1.5" // repeat(",", 14) &
                    & // ',"IDASolve failed, flag -3 at t = 1.5: ""error test"", again"'
            else if (i == refused_case) then
                rows(i + 1) = trim(rows(i + 1)) // ",refused,refused,0" // repeat(",", 15) &
                    & // ',"disk%thickness: out of range, 0.003 to 0.03"'
            else
                rows(i + 1) = trim(rows(i + 1)) // ",completed," &
                    & // trim(merge("stable    ", "falls_over", point(2) >= stable_speed)) // ",0" &
                    & // measures() // ',""'
            end if
        end do
        call write_lines(scratch // "/grid.csv", rows)
        open(newunit=unit, file=scratch // "/grid.csv", access="stream", position="append", &
            & status="old", action="write")
        write(unit) "21,0.03,1.2,completed,sta"
        close(unit)
    end subroutine grid_study

    !> Thickness [m] and speed [m/s] of case i of the grid study (thickness varies slowest).
    pure function grid_point(i) result(point)
        integer, intent(in) :: i
        real(wp) :: point(2)
        integer :: it, iv

        it = (i - 1)/speed_count
        iv = mod(i - 1, speed_count)
        point(1) = thickness_range(1) + (thickness_range(2) - thickness_range(1)) &
            & *real(it, wp)/real(thickness_count - 1, wp)
        point(2) = speed_range(1) + (speed_range(2) - speed_range(1))*real(iv, wp) &
            & /real(speed_count - 1, wp)
    end function grid_point

    !> The cases of grid.csv that fall and that stay upright.
    pure subroutine count_classes(falls, stable)
        integer, intent(out) :: falls, stable
        real(wp) :: point(2)
        integer :: i

        falls = 0
        stable = 0
        do i = 1, thickness_count*speed_count
            if (i == failed_case .or. i == refused_case) cycle
            point = grid_point(i)
            if (point(2) >= stable_speed) then
                stable = stable + 1
            else
                falls = falls + 1
            end if
        end do
    end subroutine count_classes

    !> The measures of a completed case, made up, t_fn_negative and the contact's modes' empty
    !> (a scene without friction; a comma before each).
    pure function measures() result(fields)
        character(len=:), allocatable :: fields

        fields = ",10,1.5,1.6,0.07,0.12,3.1,,,,,,1e-9,2e-12,812,0.41"
    end function measures

    !> The file exists and starts with the PNG signature.
    function png_file(path) result(is_png)
        character(len=*), intent(in) :: path
        logical :: is_png

        is_png = file_starts_with(path, achar(137) // "PNG" // achar(13) // achar(10) &
            & // achar(26) // achar(10))
    end function png_file

    !> Lines of the script's inline data block $name (-1 when there is none).
    function block_size(script, name) result(lines)
        character(len=*), intent(in) :: script, name
        integer :: lines
        real(wp), allocatable :: points(:, :)

        call read_block(script, name, points, lines)
    end function block_size

    !> The (x, y) lines of the script's inline data block $name as points(:, k); none when
    !> there is no such block (found -1).
    subroutine read_block(script, name, points, found)
        character(len=*), intent(in) :: script, name
        real(wp), allocatable, intent(out) :: points(:, :)
        integer, intent(out), optional :: found
        character(len=width) :: line
        real(wp) :: point(2)
        integer :: unit, stat, n
        logical :: inside

        allocate(points(2, 0))
        n = -1
        inside = .false.
        open(newunit=unit, file=script, status="old", action="read", iostat=stat)
        if (stat /= 0) then
            if (present(found)) found = n
            return
        end if
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (trim(line) == "$" // name // " << EOD") then
                inside = .true.
                n = 0
            else if (inside .and. trim(line) == "EOD") then
                exit
            else if (inside) then
                read(line, *, iostat=stat) point
                points = reshape([points, point], [2, size(points, 2) + 1])
                n = n + 1
            end if
        end do
        close(unit)
        if (present(found)) found = n
    end subroutine read_block

end module study_map_files
