! SPDX-License-Identifier: MIT
!> Tests of the pictures of a run: frame choice, reading the CSV back (and refusing a bad one),
!> the VTK time series for ParaView, and the gnuplot PNG figures and GIF.
module test_pictures
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type
    use rollcon_simulation, only : history_type, column_time, column_x, column_z, column_phi
    use rollcon_animation_rows, only : frame_rows
    use rollcon_csv_reader, only : read_output_csv, standard_columns, name_length
    use rollcon_disk_mesh, only : contact_point, disk_point_count
    use rollcon_vtk, only : write_vtk_series, frame_file_name
    use rollcon_figures, only : plot_output, figure_file, figure_names
    use rollcon_gif, only : animate_output
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : picture_scene, run_to_csv, make_folder, remove_folder, &
        & write_lines, vtu_contents_type, read_vtu, read_pvd, command_available
    implicit none
    private

    public :: collect_pictures

    !> Scratch folder of the suite, removed by every test that makes it
    character(len=*), parameter :: scratch = "build/test_pictures"
    !> The CSV carries 17 significant digits: values read back are the values written
    real(wp), parameter :: tol_exact = 0.0_wp
    !> Mean of the disk's mesh points against its centre: a few roundings of 1 m [m]
    real(wp), parameter :: tol_centre = 1.0e-12_wp
    !> Frame rate of the VTK tests [1/s]: 0.5 s of motion gives 6 frames
    real(wp), parameter :: fps = 10.0_wp

contains

    !> Tests of this suite.
    subroutine collect_pictures(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("frame-rows-nearest-once", test_frame_rows), &
            & new_unittest("csv-reads-back-a-run", test_csv_round_trip), &
            & new_unittest("csv-missing-file", test_csv_missing), &
            & new_unittest("csv-bad-header", test_csv_header), &
            & new_unittest("csv-bad-rows", test_csv_rows), &
            & new_unittest("vtk-frames-are-xml", test_vtk_xml), &
            & new_unittest("vtk-declared-sizes", test_vtk_sizes), &
            & new_unittest("vtk-disk-centre-and-path", test_vtk_centre), &
            & new_unittest("plot-writes-pngs", test_plot_pngs), &
            & new_unittest("plot-missing-csv", test_plot_missing), &
            & new_unittest("plot-malformed-csv", test_plot_malformed), &
            & new_unittest("animate-writes-gif", test_gif)]
    end subroutine collect_pictures

    !> Frames take the nearest row, each row once, and interpolate nothing.
    subroutine test_frame_rows(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: times(51)
        integer, allocatable :: rows(:)
        integer :: i

        times = [(0.01_wp*i, i = 0, 50)]
        rows = frame_rows(times, 0.1_wp)
        call check(error, size(rows) == 6 .and. all(rows == [1, 11, 21, 31, 41, 51]), &
            & "a frame every 0.1 s of rows every 0.01 s")
        if (allocated(error)) return
        rows = frame_rows(times, 0.004_wp)
        call check(error, size(rows) == 51 .and. all(rows == [(i, i = 1, 51)]), &
            & "frames closer than the rows: every row once")
        if (allocated(error)) return
        rows = frame_rows([0.0_wp, 0.3_wp, 0.35_wp, 1.0_wp], 0.25_wp)
        call check(error, size(rows) == 4 .and. all(rows == [1, 2, 3, 4]), &
            & "nearest rows to 0, 0.25, 0.5, 0.75, 1: " // to_text(size(rows)) // " frames")
    end subroutine test_frame_rows

    !> The reader gives back what simulate wrote, and its standard columns are simulate's.
    subroutine test_csv_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history, read_back
        type(scene_type) :: scene
        character(len=16), allocatable :: header(:)
        character(len=name_length), allocatable :: names(:)
        real(wp) :: radius
        integer :: i

        call make_folder(scratch)
        scene = picture_scene()
        call run_to_csv(scene, scratch // "/round.csv", history, header, error)
        if (.not. allocated(error)) call read_output_csv(scratch // "/round.csv", read_back, &
            & radius, error, names)
        call remove_folder(scratch)
        if (allocated(error)) return
        do i = 1, size(standard_columns)
            call check(error, header(i) == standard_columns(i) .and. names(i) == header(i), &
                & "column " // to_text(i) // ": simulate writes " // trim(header(i)) &
                & // ", the reader expects " // trim(standard_columns(i)))
            if (allocated(error)) return
        end do
        call check(error, read_back%count == history%count .and. size(names) == size(header), &
            & "rows or columns read back: " // to_text(read_back%count))
        if (allocated(error)) return
        call check(error, reshape(read_back%rows(:, :read_back%count), [size(header) &
            & *read_back%count]), reshape(history%rows(:, :history%count), &
            & [size(header)*history%count]), "values read back", abs_tol=tol_exact)
        if (allocated(error)) return
        call check(error, radius, scene%disk%radius, "radius inferred from Z/sin(theta)", &
            & rel_tol=4.0_wp*epsilon(1.0_wp))
    end subroutine test_csv_round_trip

    !> A missing CSV: the message names the file.
    subroutine test_csv_missing(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(history_type) :: history
        real(wp) :: radius

        call read_output_csv("build/no-such-run.csv", history, radius, failure)
        call expect_message(error, failure, "build/no-such-run.csv: cannot open")
    end subroutine test_csv_missing

    !> A header that does not start with the standard columns.
    subroutine test_csv_header(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(history_type) :: history
        real(wp) :: radius

        call make_folder(scratch)
        call write_lines(scratch // "/header.csv", [character(len=40) :: "time,X,Y", "0,0,0"])
        call read_output_csv(scratch // "/header.csv", history, radius, failure)
        call remove_folder(scratch)
        call expect_message(error, failure, scratch // "/header.csv:1:", &
            & "header must start with t,X,Y,Z,psi")
    end subroutine test_csv_header

    !> Rows with too few values, a NaN, a word, or no rows at all.
    subroutine test_csv_rows(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/rows.csv"
        character(len=:), allocatable :: header, good
        character(len=400) :: lines(3)
        character(len=60) :: bad(3), expected(3)
        type(error_type), allocatable :: failure
        type(history_type) :: history
        real(wp) :: radius
        integer :: i

        header = "t,X,Y,Z,psi,theta,phi,Xdot,Ydot,Zdot,psidot,thetadot,phidot,E,Fx,Fy,Fz,Fn," &
            & // "mu_needed,F1"
        good = "0,0,0,0.1,0,1.5707963267948966,0,0,0,0,0,0,0,0,0,0,0,0,0,0"
        bad = [character(len=60) :: "1,2,3", "0.1,0,0,0.1,0,1.57,0,0,0,0,0,0,0,0,0,0,0,0,NaN,0", &
            & "0.1,0,0,0.1,x,1.57,0,0,0,0,0,0,0,0,0,0,0,0,0,0"]
        expected = [character(len=60) :: ":3: expected 20 comma-separated values", &
            & ":3: value 19 must be a finite number", ":3: value 5 must be a finite number"]
        call make_folder(scratch)
        do i = 1, size(bad)
            lines(1) = header
            lines(2) = good
            lines(3) = bad(i)
            call write_lines(path, lines)
            call read_output_csv(path, history, radius, failure)
            call expect_message(error, failure, path // trim(expected(i)))
            if (allocated(error)) exit
        end do
        if (.not. allocated(error)) then
            call write_lines(path, lines(1:1))
            call read_output_csv(path, history, radius, failure)
            call expect_message(error, failure, path // ":1:", "at least one row")
        end if
        call remove_folder(scratch)
    end subroutine test_csv_rows

    !> Every file of the series parses as XML (Python's parser; skipped without python3).
    subroutine test_vtk_xml(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        character(len=:), allocatable :: files
        integer :: frames, k, stat

        if (.not. command_available("python3")) then
            call skip_test(error, "python3 not found: the XML check needs its xml.etree")
            return
        end if
        call write_series(scene, history, frames, error)
        if (allocated(error)) return
        files = scratch // "/picture.pvd"
        do k = 0, frames - 1
            files = files // " " // scratch // "/" // frame_file_name("picture", k)
        end do
        call execute_command_line("python3 -c ""import sys, xml.etree.ElementTree as E; " &
            & // "[E.parse(f) for f in sys.argv[1:]]"" " // files // " 2> /dev/null", &
            & exitstat=stat)
        call remove_folder(scratch)
        call check(error, stat == 0, "Python's XML parser refused a file of the series " &
            & // "(exit status " // to_text(stat) // ")")
    end subroutine test_vtk_xml

    !> Each frame holds as many points and cells as it declares, and its cells are consistent.
    subroutine test_vtk_sizes(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(vtu_contents_type) :: vtu
        integer :: frames, k

        call write_series(scene, history, frames, error)
        if (.not. allocated(error)) call check(error, frames == 6, "frames of 0.5 s at " &
            & // to_text(fps) // " per s: " // to_text(frames))
        do k = 0, frames - 1
            if (allocated(error)) exit
            call read_vtu(scratch // "/" // frame_file_name("picture", k), vtu, error)
            if (allocated(error)) exit
            associate (n => vtu%declared_points, m => vtu%declared_cells)
                call check(error, n > 0 .and. m > 0 .and. vtu%point_values == 3*n &
                    & .and. vtu%offset_values == m .and. vtu%type_values == m &
                    & .and. vtu%colour_values == m, "frame " // to_text(k) // " declares " &
                    & // to_text(n) // " points and " // to_text(m) // " cells but holds " &
                    & // to_text(vtu%point_values) // " coordinates, " &
                    & // to_text(vtu%offset_values) // " offsets, " // to_text(vtu%type_values) &
                    & // " types, " // to_text(vtu%colour_values) // " colours")
                if (allocated(error)) exit
                call check(error, vtu%connectivity_values == vtu%offsets(m) &
                    & .and. all(vtu%connectivity >= 0 .and. vtu%connectivity < n), &
                    & "frame " // to_text(k) // ": connectivity does not match the offsets " &
                    & // "or points outside the frame")
            end associate
        end do
        call remove_folder(scratch)
    end subroutine test_vtk_sizes

    !> In frame k the mean of the disk's mesh points is the centre of the row at the frame's
    !> time, and the contact path ends at that row's contact point, on the ground.
    subroutine test_vtk_centre(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(vtu_contents_type) :: vtu
        real(wp), allocatable :: times(:)
        character(len=64), allocatable :: files(:)
        real(wp) :: centre(3)
        integer :: frames, k, j

        call write_series(scene, history, frames, error)
        if (.not. allocated(error)) call read_pvd(scratch // "/picture.pvd", times, files, error)
        if (.not. allocated(error)) call check(error, size(times) == frames, "data sets in " &
            & // "the .pvd: " // to_text(size(times)))
        do k = 1, size(times)
            if (allocated(error)) exit
            j = findloc(history%rows(column_time, :history%count), times(k), dim=1)
            call check(error, j > 0, "no output row at the time of frame " // to_text(k - 1))
            if (allocated(error)) exit
            call read_vtu(scratch // "/" // trim(files(k)), vtu, error)
            if (allocated(error)) exit
            centre = sum(vtu%points(:, :disk_point_count), dim=2)/disk_point_count
            call check(error, centre, history%rows(column_x:column_z, j), "disk centre of " &
                & // "frame " // to_text(k - 1), abs_tol=tol_centre)
            if (allocated(error)) exit
            call check(error, vtu%points(:, size(vtu%points, 2)), contact_point(scene%disk%radius, &
                & history%rows(column_x:column_phi, j)), "end of the contact path in frame " &
                & // to_text(k - 1), abs_tol=tol_centre)
            if (allocated(error)) exit
            call check(error, abs(vtu%points(3, size(vtu%points, 2))) < 1.0e-8_wp, &
                & "the contact path is off the ground in frame " // to_text(k - 1))
        end do
        call remove_folder(scratch)
    end subroutine test_vtk_centre

    !> The figures of a short run are non-empty PNG files (skipped without gnuplot).
    subroutine test_plot_pngs(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        character(len=16), allocatable :: header(:)
        character(len=:), allocatable :: file
        integer :: i

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        call run_to_csv(picture_scene(), scratch // "/picture.csv", history, header, error)
        if (.not. allocated(error)) call plot_output(scratch // "/picture.csv", scratch, error)
        do i = 1, size(figure_names)
            if (allocated(error)) exit
            file = figure_file(scratch // "/picture.csv", scratch, figure_names(i))
            call check(error, file_starts_with(file, achar(137) // "PNG"), file &
                & // " is missing or not a PNG file")
        end do
        call remove_folder(scratch)
    end subroutine test_plot_pngs

    !> plot on a missing CSV names the file; no gnuplot needed, reading fails first.
    subroutine test_plot_missing(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure

        call plot_output("build/no-such-run.csv", "build", failure)
        call expect_message(error, failure, "build/no-such-run.csv: cannot open")
    end subroutine test_plot_missing

    !> plot on a malformed CSV names the file and line and writes no figure.
    subroutine test_plot_malformed(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        logical :: exists

        call make_folder(scratch)
        call write_lines(scratch // "/bad.csv", [character(len=60) :: "t,X,Y,Z", "0,1,2,3"])
        call plot_output(scratch // "/bad.csv", scratch, failure)
        inquire(file=figure_file(scratch // "/bad.csv", scratch, "path"), exist=exists)
        call remove_folder(scratch)
        call expect_message(error, failure, scratch // "/bad.csv:1:", "header must start with")
        if (.not. allocated(error)) call check(error, .not. exists, "a figure was written")
    end subroutine test_plot_malformed

    !> The animation of a short run is a GIF with a frame every 0.05 s (skipped without
    !> gnuplot).
    subroutine test_gif(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        character(len=16), allocatable :: header(:)
        integer :: frames

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        call run_to_csv(picture_scene(), scratch // "/picture.csv", history, header, error)
        if (.not. allocated(error)) call animate_output(scratch // "/picture.csv", &
            & scratch // "/picture.gif", frames, error)
        if (.not. allocated(error)) call check(error, file_starts_with(scratch &
            & // "/picture.gif", "GIF89a") .and. frames == 11, "GIF of 0.5 s: " &
            & // to_text(frames) // " frames, expected 11")
        call remove_folder(scratch)
    end subroutine test_gif

    !> Run the picture scene and write its VTK series into the scratch folder.
    subroutine write_series(scene, history, frames, error)
        type(scene_type), intent(out) :: scene
        type(history_type), intent(out) :: history
        integer, intent(out) :: frames
        type(error_type), allocatable, intent(out) :: error
        character(len=16), allocatable :: header(:)

        frames = 0
        call make_folder(scratch)
        scene = picture_scene()
        call run_to_csv(scene, scratch // "/picture.csv", history, header, error)
        if (allocated(error)) return
        call write_vtk_series(scratch, "picture", history, scene%disk%radius, &
            & scene%disk%thickness, fps, frames, error)
    end subroutine write_series

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

end module test_pictures
