! SPDX-License-Identifier: MIT
!> An animated GIF of a run, drawn headlessly by gnuplot from an output CSV: the disk in its
!> pose with a marked sector, over the ground, with the contact path so far.
module rollcon_gif
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_output_files, only : close_checked
    use rollcon_simulation, only : history_type, column_time, column_x, column_y, column_phi
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_disk_mesh, only : contact_point, disk_points, face_triangle, is_marked, &
        & disk_sides, disk_point_count
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
    !> Margin round the motion, in disk radii
    real(wp), parameter :: margin = 1.3_wp
    !> Colours (RGB) of the disk, its marked sector, its rim and the contact path
    character(len=*), parameter :: colour_face = "#8FA6BF", colour_sector = "#E8871E", &
        & colour_rim = "#2C3E50", colour_path = "#C0392B"

contains

    !> Draw the animation of an output CSV as gif_path: gif_fps frames per second, in real time
    !> up to max_frames/gif_fps seconds of motion and faster beyond (max_frames frames); each
    !> frame is the output row nearest to its time (rollcon_animation_rows). The gnuplot script and
    !> its data (gif_path less '.gif' + '_gif.gp', '_gif.dat', '_gif_path.dat') are removed
    !> when gnuplot succeeds and kept when it fails.
    subroutine animate_output(csv_path, gif_path, frames, error)
        !> Output CSV of `rollcon run`
        character(len=*), intent(in) :: csv_path
        !> GIF file to write (its folder must exist)
        character(len=*), intent(in) :: gif_path
        !> Number of frames drawn
        integer, intent(out) :: frames
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        integer, allocatable :: rows(:)
        character(len=:), allocatable :: prefix, script_path, frames_path, path_path
        real(wp) :: radius, duration, interval
        integer :: unit, stat, size_bytes

        frames = 0
        call read_output_csv(csv_path, history, radius, error)
        if (allocated(error)) return
        call require_gnuplot(error)
        if (allocated(error)) return
        prefix = gif_path(:len(gif_path) - len(base_name(gif_path, ""))) &
            & // base_name(gif_path, ".gif")
        script_path = prefix // "_gif.gp"
        frames_path = prefix // "_gif.dat"
        path_path = prefix // "_gif_path.dat"
        duration = history%rows(column_time, history%count) - history%rows(column_time, 1)
        interval = max(1.0_wp/gif_fps, duration/(max_frames - 1))
        rows = frame_rows(history%column(column_time), interval)
        call write_frames(frames_path, path_path, history, rows, radius, error)
        if (allocated(error)) return
        call remove_file(gif_path)
        open(newunit=unit, file=script_path, status="replace", action="write", iostat=stat)
        if (stat == 0) then
            write(unit, '(a)', iostat=stat) script(base_name(csv_path, ".csv"), gif_path, &
                & frames_path, path_path, history, rows, radius)
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

    !> The data of the frames: for frame k, data set 3k - 3 holds the disk's face as
    !> triangles (x, y, z) outside the marked sector, data set 3k - 2 those inside it, and data
    !> set 3k - 1 its rim as a closed line; and the contact point of every row in a second file.
    subroutine write_frames(frames_path, path_path, history, rows, radius, error)
        character(len=*), intent(in) :: frames_path, path_path
        type(history_type), intent(in) :: history
        integer, intent(in) :: rows(:)
        real(wp), intent(in) :: radius
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: points(3, disk_point_count), c(3)
        integer :: unit, stat, k, i, j, ids(3), set

        open(newunit=unit, file=frames_path, status="replace", action="write", &
            & access="stream", form="formatted", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, frames_path // ": cannot write the animation data", stat_io)
            return
        end if
        do k = 1, size(rows)
            if (stat /= 0) exit
            ! A disk of no thickness: at this scale the coin's 3 mm would not show.
            points = disk_points(radius, 0.0_wp, history%rows(column_x:column_phi, rows(k)))
            do set = 1, 2
                ! Set 1 is the face outside the marked sector, set 2 the sector.
                do i = 1, disk_sides
                    if (is_marked(i) .neqv. set == 2) cycle
                    ids = face_triangle(1, i) + 1
                    do j = 1, 3
                        if (stat == 0) write(unit, '(2(es16.8e3, 1x), es16.8e3)', &
                            & iostat=stat) points(:, ids(j))
                    end do
                    if (stat == 0) write(unit, '(a)', iostat=stat) ""
                end do
                if (stat == 0) write(unit, '(a)', iostat=stat) ""
            end do
            do i = 0, disk_sides
                if (stat == 0) write(unit, '(2(es16.8e3, 1x), es16.8e3)', iostat=stat) &
                    & points(:, modulo(i, disk_sides) + 1)
            end do
            if (stat == 0) write(unit, '(a, /)', iostat=stat) ""
        end do
        call close_checked(unit, frames_path, error)
        if (allocated(error)) return
        if (stat /= 0) then
            call fatal_error(error, frames_path // ": cannot write the animation data", stat_io)
            return
        end if
        open(newunit=unit, file=path_path, status="replace", action="write", &
            & access="stream", form="formatted", iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, path_path // ": cannot write the animation data", stat_io)
            return
        end if
        do j = 1, history%count
            if (stat /= 0) exit
            ! On the ground: the contact constraint's residual would put it a little below z = 0.
            c = contact_point(radius, history%rows(column_x:column_phi, j))
            write(unit, '(2(es16.8e3, 1x), f3.1)', iostat=stat) c(1:2), 0.0_wp
        end do
        call close_checked(unit, path_path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path_path // ": cannot write the animation " &
            & // "data", stat_io)
    end subroutine write_frames

    !> The gnuplot script drawing the frames, with fixed axes round the whole motion.
    function script(name, gif_path, frames_path, path_path, history, rows, radius) result(text)
        character(len=*), intent(in) :: name, gif_path, frames_path, path_path
        type(history_type), intent(in) :: history
        integer, intent(in) :: rows(:)
        real(wp), intent(in) :: radius
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        real(wp) :: low(2), high(2), c(3)
        character(len=:), allocatable :: times, last_rows
        character(len=32) :: buffer
        integer :: j, k

        low = history%rows(column_x:column_y, 1)
        high = low
        do j = 1, history%count
            c = contact_point(radius, history%rows(column_x:column_phi, j))
            low = min(low, c(1:2), history%rows(column_x:column_y, j))
            high = max(high, c(1:2), history%rows(column_x:column_y, j))
        end do
        low = low - margin*radius
        high = high + margin*radius
        times = ""
        last_rows = ""
        do k = 1, size(rows)
            write(buffer, '(f0.3)') history%rows(column_time, rows(k))
            buffer = adjustl(buffer)
            if (buffer(1:1) == ".") buffer = "0" // buffer
            times = times // merge(", ", "  ", k > 1) // trim(buffer)
            last_rows = last_rows // merge(", ", "  ", k > 1) // to_text(rows(k) - 1)
        end do
        text = "# Animation of " // name // ", written by rollcon animate." // nl &
            & // "set terminal gif animate delay " // to_text(100/gif_fps) // " loop 0 " &
            & // "optimize size " // gif_size // " font 'DejaVu Sans,8'" // nl &
            & // "set output " // gnuplot_string(gif_path) // nl &
            & // "unset key" // nl // "unset colorbox" // nl &
            & // "set view 60, 12, 1.9" // nl // "set view equal xyz" // nl &
            & // "set origin 0, 0.06" // nl // "set border 15" // nl // "unset ztics" // nl &
            & // "set xrange [" // to_text(low(1)) // ":" // to_text(high(1)) // "]" // nl &
            & // "set yrange [" // to_text(low(2)) // ":" // to_text(high(2)) // "]" // nl &
            & // "set zrange [" // to_text(-0.05_wp*radius) // ":" // to_text(2.1_wp*radius) &
            & // "]" // nl &
            & // "set xyplane at 0" // nl // "set grid xtics ytics" // nl &
            & // "set pm3d depthorder" // nl &
            & // "array frame_time[" // to_text(size(rows)) // "] = [" // times // "]" // nl &
            & // "array last_row[" // to_text(size(rows)) // "] = [" // last_rows // "]" // nl &
            & // "do for [k = 1:" // to_text(size(rows)) // "] {" // nl &
            & // "    set label 1 sprintf(" &
            & // gnuplot_string(name // "   t = %5.2f s   (X, Y in m)") &
            & // ", frame_time[k]) at screen 0.04, 0.93" // nl &
            & // "    splot " // gnuplot_string(path_path) // " every ::0::last_row[k] " &
            & // "using 1:2:3 with lines lw 2 lc rgb '" // colour_path // "', \" // nl &
            & // "        " // gnuplot_string(frames_path) // " index (3*k - 3) using " &
            & // "1:2:3 with polygons fillstyle solid 1.0 fillcolor rgb '" // colour_face &
            & // "', \" // nl // "        " // gnuplot_string(frames_path) // " index (3*k - 2) " &
            & // "using 1:2:3 with polygons fillstyle solid 1.0 fillcolor rgb '" &
            & // colour_sector // "', \" // nl &
            & // "        " // gnuplot_string(frames_path) // " index (3*k - 1) using " &
            & // "1:2:3 with lines lw 1.5 lc rgb '" // colour_rim // "'" // nl &
            & // "}" // nl // "unset output" // nl
    end function script

end module rollcon_gif
