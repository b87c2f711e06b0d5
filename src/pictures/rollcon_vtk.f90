! SPDX-License-Identifier: MIT
!> An animation for ParaView: a VTK time series (a .pvd collection of XML unstructured-grid
!> .vtu frames) of the disk in its true pose, the ground and the contact path so far.
module rollcon_vtk
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_input
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type, column_time, column_x, column_phi
    use rollcon_disk_mesh, only : contact_point, disk_points, face_triangle, rim_quad, &
        & is_marked, disk_sides, disk_point_count
    use rollcon_animation_rows, only : frame_rows
    use rollcon_output_files, only : close_checked
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: write_vtk_series, frame_file_name

    !> Values of the cell data array "colour": ground, disk, marked sector of the disk's
    !> faces, contact path
    integer, parameter, public :: colour_ground = 0, colour_disk = 1, colour_sector = 2, &
        & colour_path = 3

    !> VTK cell types
    integer, parameter :: vtk_vertex = 1, vtk_poly_line = 4, vtk_triangle = 5, vtk_quad = 9
    !> Margin of the ground square around the motion, in disk radii
    real(wp), parameter :: ground_margin = 2.0_wp

    !> Integers per line in the connectivity, offsets, types and colour arrays
    integer, parameter :: per_line = 20

contains

    !> Write folder/name.pvd and one folder/name_NNNN.vtu per frame, with a frame every 1/fps
    !> seconds of simulated time: each frame is the output row nearest to that time (nothing is
    !> interpolated; see rollcon_animation_rows), and the .pvd gives it that row's time. Frame files
    !> left by an earlier, longer series are removed. The folder must exist.
    subroutine write_vtk_series(folder, name, history, radius, thickness, fps, frames, error)
        !> Folder of the series
        character(len=*), intent(in) :: folder
        !> Base name of the files
        character(len=*), intent(in) :: name
        !> Output rows, as rollcon_simulation keeps them
        type(history_type), intent(in) :: history
        !> Disk radius and thickness [m]
        real(wp), intent(in) :: radius, thickness
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
        if (history%count < 1 .or. .not. (radius > 0.0_wp .and. thickness > 0.0_wp)) then
            call fatal_error(error, "VTK output " // folder // "/" // name // ": needs at " &
                & // "least one output row and a positive radius and thickness", stat_input)
            return
        end if
        rows = frame_rows(history%column(column_time), 1.0_wp/fps)
        ground = ground_square(history, radius)
        do k = 1, size(rows)
            call write_frame(folder // "/" // frame_file_name(name, k - 1), history, rows(k), &
                & radius, thickness, ground, error)
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
                    & // to_text(history%rows(column_time, rows(k))) // '" file="' &
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

    !> The ground square at Z = 0 around every centre and contact point of the run, corners
    !> counter-clockwise seen from above [m].
    pure function ground_square(history, radius) result(corners)
        type(history_type), intent(in) :: history
        real(wp), intent(in) :: radius
        real(wp) :: corners(3, 4)
        real(wp) :: low(2), high(2), c(3), middle(2), half
        integer :: j

        low = history%rows(column_x:column_x + 1, 1)
        high = low
        do j = 1, history%count
            c = contact_point(radius, history%rows(column_x:column_phi, j))
            low = min(low, c(1:2), history%rows(column_x:column_x + 1, j))
            high = max(high, c(1:2), history%rows(column_x:column_x + 1, j))
        end do
        middle = 0.5_wp*(low + high)
        half = 0.5_wp*maxval(high - low) + ground_margin*radius
        corners(:, 1) = [middle(1) - half, middle(2) - half, 0.0_wp]
        corners(:, 2) = [middle(1) + half, middle(2) - half, 0.0_wp]
        corners(:, 3) = [middle(1) + half, middle(2) + half, 0.0_wp]
        corners(:, 4) = [middle(1) - half, middle(2) + half, 0.0_wp]
    end function ground_square

    !> One frame: the disk at output row `row`, the ground, and the contact path of rows 1..row.
    subroutine write_frame(path, history, row, radius, thickness, ground, error)
        character(len=*), intent(in) :: path
        type(history_type), intent(in) :: history
        integer, intent(in) :: row
        real(wp), intent(in) :: radius, thickness, ground(3, 4)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: points(3, disk_point_count + 4 + row)
        integer, allocatable :: connectivity(:), offsets(:), types(:), colours(:)
        character(len=256) :: message
        integer :: unit, stat, i, j, first

        points(:, :disk_point_count) = disk_points(radius, thickness, &
            & history%rows(column_x:column_phi, row))
        points(:, disk_point_count + 1:disk_point_count + 4) = ground
        do j = 1, row
            points(:, disk_point_count + 4 + j) = contact_point(radius, &
                & history%rows(column_x:column_phi, j))
        end do

        allocate(connectivity(0), offsets(0), types(0), colours(0))
        do i = 1, disk_sides
            call add_cell([face_triangle(1, i)], vtk_triangle, &
                & merge(colour_sector, colour_disk, is_marked(i)))
            call add_cell([face_triangle(2, i)], vtk_triangle, &
                & merge(colour_sector, colour_disk, is_marked(i)))
            call add_cell([rim_quad(i)], vtk_quad, colour_disk)
        end do
        call add_cell([(disk_point_count + i, i = 0, 3)], vtk_quad, colour_ground)
        first = disk_point_count + 4
        message = "a write failed"
        call add_cell([(first + j, j = 0, row - 1)], merge(vtk_poly_line, vtk_vertex, row > 1), &
            & colour_path)

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat, iomsg=message)
        if (stat == 0) then
            write(unit, '(a)', iostat=stat) '<?xml version="1.0"?>', &
                & '<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">', &
                & '  <UnstructuredGrid>', '    <FieldData>', '      <DataArray type="Float64"' &
                & // ' Name="TimeValue" NumberOfTuples="1" format="ascii">' &
                & // to_text(history%rows(column_time, row)) // '</DataArray>', &
                & '    </FieldData>', '    <Piece NumberOfPoints="' // to_text(size(points, 2)) &
                & // '" NumberOfCells="' // to_text(size(types)) // '">', '      <Points>', &
                & '        <DataArray type="Float64" NumberOfComponents="3" format="ascii">'
            do j = 1, size(points, 2)
                if (stat == 0) write(unit, '(8x, 2(es24.16e3, 1x), es24.16e3)', iostat=stat) &
                    & points(:, j)
            end do
            if (stat == 0) write(unit, '(a)', iostat=stat) '        </DataArray>', &
                & '      </Points>', '      <Cells>'
            call write_integers(unit, "Int64", "connectivity", connectivity, stat)
            call write_integers(unit, "Int64", "offsets", offsets, stat)
            call write_integers(unit, "UInt8", "types", types, stat)
            if (stat == 0) write(unit, '(a)', iostat=stat) '      </Cells>', &
                & '      <CellData Scalars="colour">'
            call write_integers(unit, "Int32", "colour", colours, stat)
            if (stat == 0) write(unit, '(a)', iostat=stat) '      </CellData>', '    </Piece>', &
                & '  </UnstructuredGrid>', '</VTKFile>'
            call close_checked(unit, path, error)
            if (allocated(error)) return
        end if
        if (stat /= 0) call fatal_error(error, path // ": cannot write the VTK frame: " &
            & // trim(message), stat_io)

    contains

        !> Append a cell of the given zero-based point indices, type and colour.
        subroutine add_cell(ids, type, colour)
            integer, intent(in) :: ids(:), type, colour

            connectivity = [connectivity, ids]
            offsets = [offsets, size(connectivity)]
            types = [types, type]
            colours = [colours, colour]
        end subroutine add_cell

    end subroutine write_frame

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
