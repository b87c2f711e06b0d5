! SPDX-License-Identifier: MIT
!> An animation for ParaView: a VTK time series (a .pvd collection of XML unstructured-grid
!> .vtu frames) of every part in its true pose (a disk as a cylinder, any other part as its
!> inertia ellipsoid), the ground and each part's path so far.
module rollcon_vtk
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_input
    use rollcon_text, only : to_text
    use rollcon_run_record, only : run_record_type, pose, path_point, ground_bounds
    use rollcon_part_shapes, only : shape_disk, shape_extent
    use rollcon_disk_mesh, only : disk_points, face_triangle, rim_quad, is_marked, disk_sides, &
        & disk_point_count
    use rollcon_ellipsoid_mesh, only : ellipsoid_points, ellipsoid_triangle, is_marked_triangle, &
        & ellipsoid_point_count, ellipsoid_triangle_count
    use rollcon_animation_rows, only : frame_rows
    use rollcon_output_files, only : close_checked
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: write_vtk_series, frame_file_name

    !> Values of the cell data array "colour": ground, part, marked sector (disk faces) or lune
    !> (ellipsoid), path
    integer, parameter, public :: colour_ground = 0, colour_disk = 1, colour_sector = 2, &
        & colour_path = 3
    !> Value of the cell data array "part" on the ground's piece (a part's piece holds its id)
    integer, parameter, public :: ground_part = -1

    !> VTK cell types
    integer, parameter :: vtk_vertex = 1, vtk_poly_line = 4, vtk_triangle = 5, vtk_quad = 9
    !> Margin of the ground square around the motion, in the largest part's half size
    real(wp), parameter :: ground_margin = 2.0_wp

    !> Integers per line in the connectivity, offsets, types and colour arrays
    integer, parameter :: per_line = 20

    !> One piece of a frame: points and cells
    type :: piece_type
        real(wp), allocatable :: points(:, :)
        integer, allocatable :: connectivity(:), offsets(:), types(:), colours(:)
        !> Part id of the piece's cells (ground_part for the ground)
        integer :: part = ground_part
    end type piece_type

contains

    !> Write folder/name.pvd and one folder/name_NNNN.vtu per frame, with a frame every 1/fps
    !> seconds of simulated time: each frame is the output row nearest to that time (nothing is
    !> interpolated; see rollcon_animation_rows), and the .pvd gives it that row's time. A frame
    !> holds one piece per part, in the CSV's order, then one for the ground. Frame files left by
    !> an earlier, longer series are removed. The folder must exist.
    subroutine write_vtk_series(folder, name, run, fps, frames, error)
        !> Folder of the series
        character(len=*), intent(in) :: folder
        !> Base name of the files
        character(len=*), intent(in) :: name
        !> The run: rows and part shapes
        type(run_record_type), intent(in) :: run
        !> Frames per second of simulated time [1/s], > 0
        real(wp), intent(in) :: fps
        !> Number of frames written
        integer, intent(out) :: frames
        type(error_type), allocatable, intent(out) :: error
        integer, allocatable :: rows(:)
        real(wp) :: ground(3, 4)
        character(len=256) :: message
        integer :: k, unit, stat
        logical :: exists

        frames = 0
        message = "a write failed"
        if (.not. (fps > 0.0_wp .and. ieee_is_finite(fps))) then
            call fatal_error(error, "VTK output: the frame rate must be a positive finite " &
                & // "number of frames per second, got " // to_text(fps), stat_input)
            return
        end if
        if (run%history%count < 1 .or. .not. allocated(run%shapes)) then
            call fatal_error(error, "VTK output " // folder // "/" // name // ": needs at " &
                & // "least one output row and the shape of every part", stat_input)
            return
        end if
        rows = frame_rows(run%history%column(1), 1.0_wp/fps)
        ground = ground_square(run)
        do k = 1, size(rows)
            call write_frame(folder // "/" // frame_file_name(name, k - 1), run, rows(k), &
                & ground, error)
            if (allocated(error)) return
            frames = k
        end do

        open(newunit=unit, file=folder // "/" // name // ".pvd", status="replace", &
            & action="write", access="stream", form="formatted", iostat=stat, iomsg=message)
        if (stat == 0) then
            write(unit, '(a)', iostat=stat) '<?xml version="1.0"?>', '<VTKFile type=' &
                & // '"Collection" version="0.1" byte_order="LittleEndian">', '  <Collection>'
            do k = 1, size(rows)
                if (stat == 0) write(unit, '(a)', iostat=stat) '    <DataSet timestep="' &
                    & // to_text(run%history%rows(1, rows(k))) // '" file="' &
                    & // frame_file_name(name, k - 1) // '"/>'
            end do
            if (stat == 0) write(unit, '(a)', iostat=stat) '  </Collection>', '</VTKFile>'
            call close_checked(unit, folder // "/" // name // ".pvd", error)
            if (allocated(error)) return
        end if
        if (stat /= 0) then
            call fatal_error(error, folder // "/" // name // ".pvd: cannot write: " &
                & // trim(message), stat_io)
            return
        end if

        k = size(rows)
        do
            inquire(file=folder // "/" // frame_file_name(name, k), exist=exists)
            if (.not. exists) exit
            open(newunit=unit, file=folder // "/" // frame_file_name(name, k), status="old", &
                & iostat=stat)
            if (stat == 0) close(unit, status="delete", iostat=stat)
            if (stat /= 0) exit
            k = k + 1
        end do
    end subroutine write_vtk_series

    !> File name of frame k (from 0): name_0000.vtu, name_0001.vtu, ...
    pure function frame_file_name(name, k) result(file)
        !> Base name
        character(len=*), intent(in) :: name
        !> Frame number, from 0
        integer, intent(in) :: k
        character(len=:), allocatable :: file
        character(len=16) :: digits

        write(digits, '(i4.4)') k
        file = name // "_" // trim(digits) // ".vtu"
    end function frame_file_name

    !> The ground square at Z = 0 around every part's centre and path of the run, corners
    !> counter-clockwise seen from above [m].
    pure function ground_square(run) result(corners)
        type(run_record_type), intent(in) :: run
        real(wp) :: corners(3, 4)
        real(wp) :: low(2), high(2), middle(2), half

        call ground_bounds(run, low, high)
        middle = 0.5_wp*(low + high)
        half = 0.5_wp*maxval(high - low) + ground_margin*maxval(shape_extent(run%shapes))
        corners(:, 1) = [middle(1) - half, middle(2) - half, 0.0_wp]
        corners(:, 2) = [middle(1) + half, middle(2) - half, 0.0_wp]
        corners(:, 3) = [middle(1) + half, middle(2) + half, 0.0_wp]
        corners(:, 4) = [middle(1) - half, middle(2) + half, 0.0_wp]
    end function ground_square

    !> The piece of part p at output row `row`: its mesh, then its path over rows 1..row.
    pure function part_piece(run, p, row) result(piece)
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: p, row
        type(piece_type) :: piece
        integer :: i, j, first

        piece%part = run%layout%part_ids(p)
        allocate(piece%connectivity(0), piece%offsets(0), piece%types(0), piece%colours(0))
        associate (shape => run%shapes(p))
            if (shape%kind == shape_disk) then
                first = disk_point_count
                allocate(piece%points(3, first + row))
                piece%points(:, :first) = disk_points(shape%radius, shape%thickness, &
                    & pose(run, p, row))
                do i = 1, disk_sides
                    call add_cell(piece, [face_triangle(1, i)], vtk_triangle, &
                        & merge(colour_sector, colour_disk, is_marked(i)))
                    call add_cell(piece, [face_triangle(2, i)], vtk_triangle, &
                        & merge(colour_sector, colour_disk, is_marked(i)))
                    call add_cell(piece, [rim_quad(i)], vtk_quad, colour_disk)
                end do
            else
                first = ellipsoid_point_count
                allocate(piece%points(3, first + row))
                piece%points(:, :first) = ellipsoid_points(shape%semi_axes, pose(run, p, row))
                do i = 1, ellipsoid_triangle_count
                    call add_cell(piece, [ellipsoid_triangle(i)], vtk_triangle, &
                        & merge(colour_sector, colour_disk, is_marked_triangle(i)))
                end do
            end if
        end associate
        do j = 1, row
            piece%points(:, first + j) = path_point(run, p, j)
        end do
        call add_cell(piece, [(first + j, j = 0, row - 1)], merge(vtk_poly_line, vtk_vertex, &
            & row > 1), colour_path)
    end function part_piece

    !> Append a cell of the given zero-based point indices, type and colour.
    pure subroutine add_cell(piece, ids, type, colour)
        type(piece_type), intent(inout) :: piece
        integer, intent(in) :: ids(:), type, colour

        piece%connectivity = [piece%connectivity, ids]
        piece%offsets = [piece%offsets, size(piece%connectivity)]
        piece%types = [piece%types, type]
        piece%colours = [piece%colours, colour]
    end subroutine add_cell

    !> One frame: every part at output row `row` with its path of rows 1..row, then the ground.
    subroutine write_frame(path, run, row, ground, error)
        character(len=*), intent(in) :: path
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: row
        real(wp), intent(in) :: ground(3, 4)
        type(error_type), allocatable, intent(out) :: error
        type(piece_type) :: piece
        character(len=256) :: message
        integer :: unit, stat, p

        message = "a write failed"
        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat, iomsg=message)
        if (stat == 0) then
            write(unit, '(a)', iostat=stat) '<?xml version="1.0"?>', &
                & '<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">', &
                & '  <UnstructuredGrid>', '    <FieldData>', '      <DataArray type="Float64"' &
                & // ' Name="TimeValue" NumberOfTuples="1" format="ascii">' &
                & // to_text(run%history%rows(1, row)) // '</DataArray>', '    </FieldData>'
            do p = 1, size(run%shapes)
                piece = part_piece(run, p, row)
                call write_piece(unit, piece, stat)
            end do
            piece = piece_type(ground, [0, 1, 2, 3], [4], [vtk_quad], [colour_ground], &
                & ground_part)
            call write_piece(unit, piece, stat)
            if (stat == 0) write(unit, '(a)', iostat=stat) '  </UnstructuredGrid>', '</VTKFile>'
            call close_checked(unit, path, error)
            if (allocated(error)) return
        end if
        if (stat /= 0) call fatal_error(error, path // ": cannot write the VTK frame: " &
            & // trim(message), stat_io)
    end subroutine write_frame

    !> One <Piece>: points, cells, and the cell data "colour" and "part"; nothing once stat is
    !> non-zero.
    subroutine write_piece(unit, piece, stat)
        integer, intent(in) :: unit
        type(piece_type), intent(in) :: piece
        integer, intent(inout) :: stat
        integer :: j

        if (stat /= 0) return
        write(unit, '(a)', iostat=stat) '    <Piece NumberOfPoints="' &
            & // to_text(size(piece%points, 2)) // '" NumberOfCells="' &
            & // to_text(size(piece%types)) // '">', '      <Points>', &
            & '        <DataArray type="Float64" NumberOfComponents="3" format="ascii">'
        do j = 1, size(piece%points, 2)
            if (stat == 0) write(unit, '(8x, 2(es24.16e3, 1x), es24.16e3)', iostat=stat) &
                & piece%points(:, j)
        end do
        if (stat == 0) write(unit, '(a)', iostat=stat) '        </DataArray>', &
            & '      </Points>', '      <Cells>'
        call write_integers(unit, "Int64", "connectivity", piece%connectivity, stat)
        call write_integers(unit, "Int64", "offsets", piece%offsets, stat)
        call write_integers(unit, "UInt8", "types", piece%types, stat)
        if (stat == 0) write(unit, '(a)', iostat=stat) '      </Cells>', &
            & '      <CellData Scalars="colour">'
        call write_integers(unit, "Int32", "colour", piece%colours, stat)
        call write_integers(unit, "Int32", "part", [(piece%part, j = 1, size(piece%types))], &
            & stat)
        if (stat == 0) write(unit, '(a)', iostat=stat) '      </CellData>', '    </Piece>'
    end subroutine write_piece

    !> A DataArray of integers, per_line to a line; nothing once stat is non-zero.
    subroutine write_integers(unit, type, name, values, stat)
        integer, intent(in) :: unit
        !> VTK type name (Int32, Int64, UInt8) and array name
        character(len=*), intent(in) :: type, name
        integer, intent(in) :: values(:)
        integer, intent(inout) :: stat
        integer :: i

        if (stat /= 0) return
        write(unit, '(a)', iostat=stat) '        <DataArray type="' // type // '" Name="' &
            & // name // '" format="ascii">'
        do i = 1, size(values), per_line
            if (stat == 0) write(unit, '(8x, *(i0, :, 1x))', iostat=stat) &
                & values(i:min(i + per_line - 1, size(values)))
        end do
        if (stat == 0) write(unit, '(a)', iostat=stat) '        </DataArray>'
    end subroutine write_integers

end module rollcon_vtk
