! SPDX-License-Identifier: MIT
!> An animated GIF of a run, drawn headlessly by gnuplot from an output CSV: every part in its
!> pose (a disk with a marked sector, any other part as its inertia ellipsoid with a marked
!> lune), over the ground, with each part's path so far (a disk's contact point, another part's
!> centre of mass).
module rollcon_gif
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_output_files, only : close_checked
    use rollcon_output_layout, only : coord_z, name_length
    use rollcon_run_record, only : run_record_type, read_run, pose, path_point, ground_bounds, &
        & contact_part
    use rollcon_watch_columns, only : contact_prefixes
    use rollcon_figure_rows, only : path_stride
    use rollcon_contact_figures, only : path_modes, mode_colour_values
    use rollcon_part_shapes, only : shape_disk, shape_extent
    use rollcon_disk_mesh, only : disk_points, face_triangle, is_marked, disk_sides, &
        & disk_point_count
    use rollcon_ellipsoid_mesh, only : ellipsoid_points, ellipsoid_triangle, &
        & is_marked_triangle, equator_point, ellipsoid_point_count, ellipsoid_triangle_count, &
        & ellipsoid_sides
    use rollcon_animation_rows, only : frame_rows
    use rollcon_gnuplot, only : require_gnuplot, run_gnuplot, gnuplot_string, base_name, &
        & remove_file
    implicit none
    private

    public :: animate_output

    !> Frames per second of the GIF: a frame lasts 5 GIF delay units (1/100 s)
    integer, parameter, public :: gif_fps = 20
    !> Most frames: a longer run is shown faster than real time
    integer, parameter, public :: max_frames = 300
    !> Size of the picture [pixels]
    character(len=*), parameter :: gif_size = "480,360"
    !> Margin round the motion, in the largest part's half size
    real(wp), parameter :: margin = 1.3_wp
    !> Colours (RGB) of a part, its marked sector or lune, its rim or equator and its path
    character(len=*), parameter :: colour_face = "#8FA6BF", colour_sector = "#E8871E", &
        & colour_rim = "#2C3E50", colour_path = "#C0392B"
    !> Format of a point in the data files
    character(len=*), parameter :: point_format = '(2(es16.8e3, 1x), es16.8e3)'

contains

    !> Draw the animation of an output CSV as gif_path: gif_fps frames per second, in real time
    !> up to max_frames/gif_fps seconds of motion and faster beyond (max_frames frames); each
    !> frame is the output row nearest to its time (rollcon_animation_rows). The parts' shapes
    !> come from the .parts file beside the CSV (rollcon_run_record). The gnuplot script and its
    !> data (gif_path less '.gif' + '_gif.gp', '_gif.dat', '_gif_path.dat') are removed when
    !> gnuplot succeeds and kept when it fails.
    subroutine animate_output(csv_path, gif_path, frames, error, script_text)
        !> Output CSV of `rollcon run`
        character(len=*), intent(in) :: csv_path
        !> GIF file to write (its folder must exist)
        character(len=*), intent(in) :: gif_path
        !> Number of frames drawn
        integer, intent(out) :: frames
        type(error_type), allocatable, intent(out) :: error
        !> The gnuplot script given to gnuplot (what <base>_gif.gp held)
        character(len=:), allocatable, intent(out), optional :: script_text
        type(run_record_type) :: run
        integer, allocatable :: rows(:)
        character(len=:), allocatable :: prefix, script_path, frames_path, path_path, text
        real(wp) :: duration, interval
        integer :: unit, stat, size_bytes

        frames = 0
        call read_run(csv_path, run, error)
        if (allocated(error)) return
        call require_gnuplot(error)
        if (allocated(error)) return
        prefix = gif_path(:len(gif_path) - len(base_name(gif_path, ""))) &
            & // base_name(gif_path, ".gif")
        script_path = prefix // "_gif.gp"
        frames_path = prefix // "_gif.dat"
        path_path = prefix // "_gif_path.dat"
        duration = run%history%rows(1, run%history%count) - run%history%rows(1, 1)
        interval = max(1.0_wp/gif_fps, duration/(max_frames - 1))
        rows = frame_rows(run%history%column(1), interval)
        call write_frames(frames_path, run, rows, error)
        if (.not. allocated(error)) call write_paths(path_path, run, error)
        if (allocated(error)) return
        call remove_file(gif_path)
        text = script(base_name(csv_path, ".csv"), gif_path, frames_path, path_path, run, rows)
        if (present(script_text)) script_text = text
        open(newunit=unit, file=script_path, status="replace", action="write", iostat=stat)
        if (stat == 0) then
            write(unit, '(a)', iostat=stat) text
            close(unit)
        end if
        if (stat /= 0) then
            call fatal_error(error, script_path // ": cannot write the gnuplot script", stat_io)
            return
        end if
        call run_gnuplot(script_path, error)
        if (.not. allocated(error)) then
            inquire(file=gif_path, size=size_bytes)
            if (size_bytes <= 0) call fatal_error(error, gif_path // ": gnuplot reported " &
                & // "success but did not write the GIF (see " // script_path // ")", stat_io)
        end if
        if (allocated(error)) then
            ! No GIF of a failed animation is left behind.
            call remove_file(gif_path)
            return
        end if
        frames = size(rows)
        call remove_file(script_path)
        call remove_file(frames_path)
        call remove_file(path_path)
    end subroutine animate_output

    !> The data of the frames: for frame k and part p (CSV order), of P parts, data set
    !> 3 (P (k - 1) + p - 1) holds the part's surface as triangles (x, y, z) outside its marked
    !> sector or lune, the next data set those inside it, and the next its rim (a disk) or
    !> equator (an ellipsoid) as a closed line.
    subroutine write_frames(path, run, rows, error)
        character(len=*), intent(in) :: path
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: rows(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, k, p

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the animation data", stat_io)
            return
        end if
        do k = 1, size(rows)
            do p = 1, size(run%shapes)
                if (stat /= 0) exit
                if (run%shapes(p)%kind == shape_disk) then
                    call write_disk(unit, run%shapes(p)%radius, pose(run, p, rows(k)), stat)
                else
                    call write_ellipsoid(unit, run%shapes(p)%semi_axes, pose(run, p, rows(k)), &
                        & stat)
                end if
            end do
        end do
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the animation data", &
            & stat_io)
    end subroutine write_frames

    !> A disk's three data sets (face, sector, rim), of no thickness: at the scale of a motion
    !> a coin's 3 mm would not show.
    subroutine write_disk(unit, radius, q, stat)
        integer, intent(in) :: unit
        real(wp), intent(in) :: radius, q(6)
        integer, intent(inout) :: stat
        real(wp) :: points(3, disk_point_count)
        integer :: set, i, j, ids(3)

        points = disk_points(radius, 0.0_wp, q)
        do set = 1, 2
            do i = 1, disk_sides
                if (is_marked(i) .neqv. set == 2) cycle
                ids = face_triangle(1, i) + 1
                do j = 1, 3
                    if (stat == 0) write(unit, point_format, iostat=stat) points(:, ids(j))
                end do
                if (stat == 0) write(unit, '(a)', iostat=stat) ""
            end do
            if (stat == 0) write(unit, '(a)', iostat=stat) ""
        end do
        do i = 0, disk_sides
            if (stat == 0) write(unit, point_format, iostat=stat) &
                & points(:, modulo(i, disk_sides) + 1)
        end do
        if (stat == 0) write(unit, '(a, /)', iostat=stat) ""
    end subroutine write_disk

    !> An ellipsoid's three data sets (surface, lune, equator).
    subroutine write_ellipsoid(unit, semi_axes, q, stat)
        integer, intent(in) :: unit
        real(wp), intent(in) :: semi_axes(3), q(6)
        integer, intent(inout) :: stat
        real(wp) :: points(3, ellipsoid_point_count)
        integer :: set, t, j, ids(3)

        points = ellipsoid_points(semi_axes, q)
        do set = 1, 2
            do t = 1, ellipsoid_triangle_count
                if (is_marked_triangle(t) .neqv. set == 2) cycle
                ids = ellipsoid_triangle(t) + 1
                do j = 1, 3
                    if (stat == 0) write(unit, point_format, iostat=stat) points(:, ids(j))
                end do
                if (stat == 0) write(unit, '(a)', iostat=stat) ""
            end do
            if (stat == 0) write(unit, '(a)', iostat=stat) ""
        end do
        do t = 1, ellipsoid_sides + 1
            if (stat == 0) write(unit, point_format, iostat=stat) &
                & points(:, equator_point(t) + 1)
        end do
        if (stat == 0) write(unit, '(a, /)', iostat=stat) ""
    end subroutine write_ellipsoid

    !> The path of every part over every row, data set p - 1 for part p; with a contact's
    !> mode (a `mode` column, or contact<id>_mode of several), a fourth column: the colour of
    !> each point's mode for the part that contact holds (contact_part; each contact its own
    !> part's), grey for a part no contact holds.
    subroutine write_paths(path, run, error)
        character(len=*), intent(in) :: path
        type(run_record_type), intent(in) :: run
        type(error_type), allocatable, intent(out) :: error
        !> The colour of a part no contact holds, as gnuplot's `lc rgb variable` takes it
        integer, parameter :: grey = 128*65536 + 128*256 + 128
        character(len=name_length), allocatable :: prefixes(:)
        integer, allocatable :: modes(:), present(:), colours(:, :)
        logical :: by_mode
        integer :: unit, stat, p, j, stride, c, held

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the animation data", stat_io)
            return
        end if
        ! every path_stride-th row (rollcon_figure_rows): the frames draw the path up to theirs;
        ! with the contact's mode, each point's colour after it (the disk in contact: one part)
        stride = path_stride(run%history%count)
        allocate(colours(run%history%count, size(run%shapes)), source=grey)
        by_mode = .false.
        prefixes = contact_prefixes(run%layout)
        do c = 1, size(prefixes)
            call path_modes(run, modes, present, trim(prefixes(c)))
            held = contact_part(run, trim(prefixes(c)))
            if (size(present) == 0 .or. held == 0) cycle
            by_mode = .true.
            colours(:, held) = mode_colour_values(modes)
        end do
        do p = 1, size(run%shapes)
            do j = 1, run%history%count, stride
                if (by_mode) then
                    if (stat == 0) write(unit, '(3(es16.8e3, 1x), i0)', iostat=stat) &
                        & path_point(run, p, j), colours(j, p)
                else
                    if (stat == 0) write(unit, point_format, iostat=stat) path_point(run, p, j)
                end if
            end do
            if (stat == 0) write(unit, '(a, /)', iostat=stat) ""
        end do
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the animation data", &
            & stat_io)
    end subroutine write_paths

    !> Some contact's part's path is coloured by its mode (write_paths' fourth column).
    pure logical function modes_drawn(run)
        type(run_record_type), intent(in) :: run
        character(len=name_length), allocatable :: prefixes(:)
        integer, allocatable :: modes(:), present(:)
        integer :: c

        modes_drawn = .false.
        prefixes = contact_prefixes(run%layout)
        do c = 1, size(prefixes)
            call path_modes(run, modes, present, trim(prefixes(c)))
            if (size(present) > 0 .and. contact_part(run, trim(prefixes(c))) > 0) &
                & modes_drawn = .true.
        end do
    end function modes_drawn

    !> The gnuplot script drawing the frames, with fixed axes round the whole motion.
    function script(name, gif_path, frames_path, path_path, run, rows) result(text)
        character(len=*), intent(in) :: name, gif_path, frames_path, path_path
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: rows(:)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        real(wp) :: low(2), high(2), z_low, z_high, extent
        character(len=:), allocatable :: times, last_rows, parts, set, optimize, shading, &
            & path_style
        character(len=32) :: buffer
        integer :: k, p

        call ground_bounds(run, low, high)
        extent = maxval(shape_extent(run%shapes))
        low = low - margin*extent
        high = high + margin*extent
        z_low = 0.0_wp
        z_high = 0.0_wp
        do p = 1, size(run%shapes)
            associate (z => run%history%rows(run%layout%part_column(p, coord_z), &
                & :run%history%count))
                z_low = min(z_low, minval(z) - shape_extent(run%shapes(p)))
                z_high = max(z_high, maxval(z) + shape_extent(run%shapes(p)))
            end associate
        end do
        times = ""
        last_rows = ""
        do k = 1, size(rows)
            write(buffer, '(f0.3)') run%history%rows(1, rows(k))
            buffer = adjustl(buffer)
            if (buffer(1:1) == ".") buffer = "0" // buffer(:len(buffer) - 1)
            if (buffer(1:2) == "-.") buffer = "-0" // buffer(2:)
            times = times // merge(", ", "  ", k > 1) // trim(buffer)
            last_rows = last_rows // merge(", ", "  ", k > 1) &
                & // to_text((rows(k) - 1)/path_stride(run%history%count))
        end do
        parts = to_text(size(run%shapes))
        ! the path in one colour, or with the contact's mode in its mode's (write_paths)
        path_style = "using 1:2:3 with lines lw 2 lc rgb '" // colour_path // "'"
        if (modes_drawn(run)) path_style = "using 1:2:3:4 with lines lw 2 lc rgb variable"
        ! An ellipsoid is shaded (pm3d lighting) so that its shape reads in 3-D; gnuplot's GIF
        ! palette optimisation blackens shaded facets, so it is kept for disks alone (unshaded,
        ! as their faces are flat).
        optimize = "optimize "
        shading = ""
        if (any(run%shapes%kind /= shape_disk)) then
            optimize = ""
            shading = "set pm3d lighting primary 0.4 specular 0.0" // nl
        end if
        ! data set of part p's surface in frame k (write_frames)
        set = "(3*(" // parts // "*(k - 1) + p - 1))"
        text = "# Animation of " // name // ", written by rollcon animate." // nl &
            & // "set terminal gif animate delay " // to_text(100/gif_fps) // " loop 0 " &
            & // optimize // "size " // gif_size // " font 'DejaVu Sans,8' noenhanced" // nl &
            & // "set output " // gnuplot_string(gif_path) // nl &
            & // "unset key" // nl // "unset colorbox" // nl &
            & // "set view 60, 12, 1.9" // nl // "set view equal xyz" // nl &
            & // "set origin 0, 0.06" // nl // "set border 15" // nl // "unset ztics" // nl &
            & // "set xrange [" // to_text(low(1)) // ":" // to_text(high(1)) // "]" // nl &
            & // "set yrange [" // to_text(low(2)) // ":" // to_text(high(2)) // "]" // nl &
            & // "set zrange [" // to_text(z_low - 0.05_wp*extent) // ":" &
            & // to_text(z_high + 0.1_wp*extent) // "]" // nl &
            & // "set xyplane at " // to_text(z_low) // nl // "set grid xtics ytics" // nl &
            & // "set pm3d depthorder" // nl &
            & // shading &
            & // "array frame_time[" // to_text(size(rows)) // "] = [" // times // "]" // nl &
            & // "array last_row[" // to_text(size(rows)) // "] = [" // last_rows // "]" // nl &
            & // "do for [k = 1:" // to_text(size(rows)) // "] {" // nl &
            & // "    set label 1 sprintf(" &
            & // gnuplot_string(name // "   t = %5.2f s   (X, Y in m)") &
            & // ", frame_time[k]) at screen 0.04, 0.93" // nl &
            & // "    splot for [p = 1:" // parts // "] " // gnuplot_string(path_path) &
            & // " index (p - 1) every ::0::last_row[k] " // path_style // ", \" // nl &
            & // "        for [p = 1:" // parts // "] " // gnuplot_string(frames_path) &
            & // " index " // set // " using 1:2:3 with polygons fillstyle solid 1.0 " &
            & // "fillcolor rgb '" // colour_face // "', \" // nl &
            & // "        for [p = 1:" // parts // "] " // gnuplot_string(frames_path) &
            & // " index (" // set // " + 1) using 1:2:3 with polygons fillstyle solid 1.0 " &
            & // "fillcolor rgb '" // colour_sector // "', \" // nl &
            & // "        for [p = 1:" // parts // "] " // gnuplot_string(frames_path) &
            & // " index (" // set // " + 2) using 1:2:3 with lines lw 1.5 lc rgb '" &
            & // colour_rim // "'" // nl &
            & // "}" // nl // "unset output" // nl
    end function script

end module rollcon_gif
