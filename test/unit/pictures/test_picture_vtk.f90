! SPDX-License-Identifier: MIT
!> Tests of the VTK time series for ParaView of a model of two parts (a disk and an
!> ellipsoid): XML that parses, declared sizes that match, one piece per part and one for the
!> ground, every part in its pose and its path ending at the frame's row.
module test_picture_vtk
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_run_record, only : run_record_type, read_run, pose, path_point
    use rollcon_disk_mesh, only : disk_point_count
    use rollcon_ellipsoid_mesh, only : ellipsoid_point_count
    use rollcon_vtk, only : write_vtk_series, frame_file_name, ground_part
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : two_part_run, write_run, make_folder, remove_folder, &
        & vtu_piece_type, read_vtu, read_pvd, command_available
    implicit none
    private

    public :: collect_picture_vtk

    !> Scratch folder of the suite, removed by every test that makes it
    character(len=*), parameter :: scratch = "build/test_picture_vtk"
    !> Mean of a part's mesh points against its centre, and a path's end against its point:
    !> a few roundings of 1 m, and the 17 digits of the .vtu [m]
    real(wp), parameter :: tol_centre = 1.0e-12_wp
    !> Frame rate of the VTK tests [1/s]: 0.5 s of motion gives 6 frames
    real(wp), parameter :: fps = 10.0_wp

contains

    !> Tests of this suite.
    subroutine collect_picture_vtk(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("vtk-frames-are-xml", test_vtk_xml), &
            & new_unittest("vtk-declared-sizes", test_vtk_sizes), &
            & new_unittest("vtk-every-part-in-its-pose", test_vtk_poses)]
    end subroutine collect_picture_vtk

    !> Every file of the two-part series parses as XML (Python's parser; skipped without
    !> python3).
    subroutine test_vtk_xml(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        character(len=:), allocatable :: files
        integer :: frames, k, stat

        if (.not. command_available("python3")) then
            call skip_test(error, "python3 not found: the XML check needs its xml.etree")
            return
        end if
        call write_series(run, frames, error)
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

    !> Each frame holds a piece per part and one for the ground, each with as many points and
    !> cells as it declares, consistent cells, and the part id on every cell.
    subroutine test_vtk_sizes(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        type(vtu_piece_type), allocatable :: pieces(:)
        integer, parameter :: piece_parts(3) = [1, 7, ground_part]
        integer :: frames, k, i

        call write_series(run, frames, error)
        if (.not. allocated(error)) call check(error, frames == 6, "frames of 0.5 s at " &
            & // to_text(fps) // " per s: " // to_text(frames))
        do k = 0, frames - 1
            if (allocated(error)) exit
            call read_vtu(scratch // "/" // frame_file_name("picture", k), pieces, error)
            if (allocated(error)) exit
            call check(error, size(pieces) == 3, "frame " // to_text(k) // ": " &
                & // to_text(size(pieces)) // " pieces, expected parts 1 and 7 and the ground")
            do i = 1, size(pieces)
                if (allocated(error)) exit
                associate (piece => pieces(i), n => pieces(i)%declared_points, &
                    & m => pieces(i)%declared_cells)
                    call check(error, n > 0 .and. m > 0 .and. piece%point_values == 3*n &
                        & .and. piece%offset_values == m .and. piece%type_values == m &
                        & .and. piece%colour_values == m .and. piece%part_values == m, &
                        & "frame " // to_text(k) // ", piece " // to_text(i) // ": declared " &
                        & // "sizes do not match the arrays")
                    if (allocated(error)) exit
                    call check(error, piece%connectivity_values == piece%offsets(m) &
                        & .and. all(piece%connectivity >= 0 .and. piece%connectivity < n) &
                        & .and. all(piece%parts == piece_parts(i)), "frame " // to_text(k) &
                        & // ", piece " // to_text(i) // ": connectivity, offsets or part ids")
                end associate
            end do
        end do
        call remove_folder(scratch)
    end subroutine test_vtk_sizes

    !> In frame k each part's mesh is centred on its centre in the row at the frame's time, and
    !> its path ends at its path point there: the disk's contact point, on the ground, and the
    !> ellipsoid's centre.
    subroutine test_vtk_poses(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        type(vtu_piece_type), allocatable :: pieces(:)
        real(wp), allocatable :: times(:)
        character(len=64), allocatable :: files(:)
        integer, parameter :: mesh_points(2) = [disk_point_count, ellipsoid_point_count]
        real(wp) :: q(6)
        integer :: frames, k, j, p, last

        call write_series(run, frames, error)
        if (.not. allocated(error)) call read_pvd(scratch // "/picture.pvd", times, files, error)
        if (.not. allocated(error)) call check(error, size(times) == frames, "data sets in " &
            & // "the .pvd: " // to_text(size(times)))
        do k = 1, size(times)
            if (allocated(error)) exit
            j = findloc(run%history%rows(1, :run%history%count), times(k), dim=1)
            call check(error, j > 0, "no output row at the time of frame " // to_text(k - 1))
            if (allocated(error)) exit
            call read_vtu(scratch // "/" // trim(files(k)), pieces, error)
            do p = 1, 2
                if (allocated(error)) exit
                q = pose(run, p, j)
                associate (points => pieces(p)%points)
                    call check(error, sum(points(:, :mesh_points(p)), dim=2)/mesh_points(p), &
                        & q(1:3), "centre of part " &
                        & // to_text(run%layout%part_ids(p)) // " in frame " // to_text(k - 1), &
                        & abs_tol=tol_centre)
                    if (allocated(error)) exit
                    last = size(points, 2)
                    call check(error, last == mesh_points(p) + j .and. all(abs(points(:, last) &
                        & - path_point(run, p, j)) <= tol_centre), "end of the path of part " &
                        & // to_text(run%layout%part_ids(p)) // " in frame " // to_text(k - 1))
                end associate
            end do
            if (.not. allocated(error)) call check(error, abs(pieces(1)%points(3, &
                & size(pieces(1)%points, 2))) < tol_centre, "the disk's contact path is off " &
                & // "the ground in frame " // to_text(k - 1))
        end do
        call remove_folder(scratch)
    end subroutine test_vtk_poses

    !> Write the two-part run (with its .parts) and its VTK series into the scratch folder.
    subroutine write_series(run, frames, error)
        type(run_record_type), intent(out) :: run
        integer, intent(out) :: frames
        type(error_type), allocatable, intent(out) :: error

        frames = 0
        call make_folder(scratch)
        call write_run(scratch // "/picture.csv", two_part_run(), .true., error)
        if (.not. allocated(error)) call read_run(scratch // "/picture.csv", run, error)
        if (.not. allocated(error)) call write_vtk_series(scratch, "picture", run, fps, frames, &
            & error)
    end subroutine write_series

end module test_picture_vtk
