! SPDX-License-Identifier: MIT
!> The figure of eigenvalues against speed (docs/linear.md): the real and the imaginary parts
!> of the kept eigenvalues at each speed of the grid as points, and each speed where stability
!> changes as a vertical line labelled with its kind and its value, as the bicycle
!> benchmark's paper draws them. Drawn by gnuplot from a script written beside the PNG (kept,
!> with the data inline, so the figure can be restyled without the analysis).
module rollcon_eigen_speed_figure
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text, fixed_text
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type
    use rollcon_gnuplot, only : require_gnuplot, run_gnuplot, gnuplot_string, remove_file, &
        & require_written
    implicit none
    private

    public :: draw_eigen_speed_figure

    character(len=*), parameter :: nl = new_line("a")

contains

    !> Draw the figure as a PNG; its script is png_path with .gp for .png.
    subroutine draw_eigen_speed_figure(table, changes, title, png_path, error)
        type(speed_table_type), intent(in) :: table
        type(stability_change_type), intent(in) :: changes(:)
        !> The figure's title
        character(len=*), intent(in) :: title
        character(len=*), intent(in) :: png_path
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: script
        character(len=256) :: message
        integer :: unit, stat

        call require_gnuplot(error)
        if (allocated(error)) return
        script = png_path // ".gp"
        if (len(png_path) > 4) then
            if (png_path(len(png_path) - 3:) == ".png") script = png_path(:len(png_path) - 4) &
                & // ".gp"
        end if
        call remove_file(png_path)
        message = "a write failed"
        open(newunit=unit, file=script, status="replace", action="write", form="formatted", &
            & iostat=stat, iomsg=message)
        if (stat == 0) write(unit, '(a)', iostat=stat, iomsg=message) &
            & script_text(table, changes, title, png_path)
        if (stat == 0) close(unit, iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, script // ": cannot write the figure's gnuplot script: " &
                & // trim(message), stat_io)
            return
        end if
        call run_gnuplot(script, error)
        if (allocated(error)) return
        call require_written(png_path, script, error)
    end subroutine draw_eigen_speed_figure

    !> The whole script: settings, the data inline ($re and $im: speed and one column per
    !> eigenvalue), the change lines as arrows with labels, the plot.
    function script_text(table, changes, title, png_path) result(text)
        type(speed_table_type), intent(in) :: table
        type(stability_change_type), intent(in) :: changes(:)
        character(len=*), intent(in) :: title, png_path
        character(len=:), allocatable :: text
        real(wp) :: low, high
        integer :: k, n

        n = size(table%real_part, 1)
        low = -10.0_wp
        high = 10.0_wp
        if (n > 0 .and. size(table%speed) > 0) then
            low = min(-1.0_wp, minval(table%real_part), -maxval(abs(table%imag_part)))
            high = max(1.0_wp, maxval(table%real_part), maxval(abs(table%imag_part)))
        end if
        ! as the bicycle benchmark's figure: symmetric about 0, a fast stable real mode (the
        ! bicycle's castering) left below the frame rather than squeezing the rest
        low = max(low, -high)
        text = "# Eigenvalues against speed, drawn by rollcon (docs/linear.md); the data are " &
            & // "inline." // nl &
            & // "set terminal pngcairo size 900,640 font 'DejaVu Sans,10' noenhanced" // nl &
            & // "set output " // gnuplot_string(png_path) // nl &
            & // "set title " // gnuplot_string(title) // nl &
            & // "set xlabel 'speed v [m/s]'" // nl &
            & // "set ylabel 'eigenvalue lambda [1/s]: real part (dots), imaginary part " &
            & // "(crosses)'" // nl &
            & // "set xrange [" // to_text(minval(table%speed)) // ":" &
            & // to_text(maxval(table%speed)) // "]" // nl &
            & // "set yrange [" // to_text(low) // ":" // to_text(high) // "]" // nl &
            & // "set grid back lc rgb '#d0d0d0' lw 0.5" // nl // "set tics out" // nl &
            & // "set key outside bottom center horizontal" // nl &
            & // "set arrow from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#808080'" &
            & // nl // data_block("re", table%speed, table%real_part) &
            & // data_block("im", table%speed, abs(table%imag_part))
        do k = 1, size(changes)
            text = text // "set arrow from first " // to_text(changes(k)%speed) &
                & // ", graph 0 to first " // to_text(changes(k)%speed) // ", graph 1 " &
                & // "nohead dt 2 lw 1.5 lc rgb '#000000'" // nl &
                & // "set label " // gnuplot_string(change_label(changes(k))) // " at first " &
                & // to_text(changes(k)%speed) // ", graph " // to_text(1.0_wp - 0.05_wp*k) &
                & // " offset 0.5, 0 front" // nl
        end do
        text = text // "plot "
        if (n == 0) then
            text = text // "0 notitle" // nl // "unset output"
            return
        end if
        do k = 1, n
            if (k > 1) text = text // ", \" // nl // "    "
            text = text // "$re using 1:" // to_text(k + 1) // " with points pt 7 ps 0.5 " &
                & // "lc rgb '#1f5fa8' " // trim(merge("title 'real part'", "notitle          ", &
                & k == 1))
        end do
        do k = 1, n
            text = text // ", \" // nl // "    $im using 1:" // to_text(k + 1) &
                & // " with points pt 1 ps 0.6 lc rgb '#d9730d' " &
                & // trim(merge("title '|imaginary part|'", "notitle                 ", k == 1))
        end do
        text = text // nl // "unset output"
    end function script_text

    !> A block of inline data: the speed, then one column per eigenvalue.
    function data_block(name, speed, values) result(text)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: speed(:), values(:, :)
        character(len=:), allocatable :: text
        character(len=26) :: number
        integer :: k, i

        text = "$" // name // " << EOD" // nl
        do k = 1, size(speed)
            write(number, '(es25.16e3)') speed(k)
            text = text // trim(adjustl(number))
            do i = 1, size(values, 1)
                write(number, '(es25.16e3)') values(i, k)
                text = text // " " // trim(adjustl(number))
            end do
            text = text // nl
        end do
        text = text // "EOD" // nl
    end function data_block

    !> "weave-type 4.292383 m/s" or "capsize-type 6.024262 m/s".
    function change_label(change) result(label)
        type(stability_change_type), intent(in) :: change
        character(len=:), allocatable :: label

        if (change%oscillatory) then
            label = "oscillatory (weave) " // fixed_text(change%speed, 6) // " m/s"
        else
            label = "divergent (capsize) " // fixed_text(change%speed, 6) // " m/s"
        end if
    end function change_label

end module rollcon_eigen_speed_figure
