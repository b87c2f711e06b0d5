! SPDX-License-Identifier: MIT
!> The figures of a run of one part rolling on a rim, the columns of its rim contact among its
!> rows (rollcon_contact_watch): paths of the centre and the contact point, theta, the
!> precession and spin rates, energy drift, constraint residuals with the height residual, the
!> contact force and the friction coefficient it needs. A run whose rows carry the contact's
!> mode (Coulomb friction: the `mode` column) gets its contact point's path coloured by mode,
!> with its switches marked, and, given the contact's friction coefficients, its friction
!> figure the lines of mu_static and mu_kinetic. Path figures of any run colour the contact's
!> part by mode through path_modes, mode_path, mode_switches and mode_title.
module rollcon_contact_figures
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : coord_x, coord_y, coord_theta, coord_psidot, &
        & coord_phidot
    use rollcon_run_record, only : run_record_type, path_point
    use rollcon_part_shapes, only : shape_extent
    use rollcon_figure_text, only : drift, residual_floor, title, output, figure_preamble, &
        & path_axis_ranges
    use rollcon_gnuplot, only : gnuplot_string
    use rollcon_output_files, only : close_checked
    use rollcon_figure_rows, only : write_figure_rows
    use rollcon_watch_columns, only : contact_mode_words
    implicit none
    private

    public :: write_contact_data, contact_script, path_modes, mode_path, mode_switches, &
        & mode_colour_values, mode_title, mode_colour, switch_colour, friction_lines

    !> The figures, each written as DIR/<base>_<name>.png
    character(len=*), parameter, public :: contact_figure_names(7) = [character(len=11) :: "path", &
        & "theta", "rates", "energy", "residuals", "force", "friction"]
    !> Columns of the data file written for gnuplot, before one |F_k| column per UCON and the
    !> height residual
    integer, parameter :: data_columns = 13
    !> Colours of the contact point's path in each mode, by the mode's number (0 rolling, 1
    !> sliding, then again from the first past the last), and of the switches' marks
    character(len=*), parameter :: mode_colours(0:3) = [character(len=7) :: "#1f77b4", &
        & "#d62728", "#ff7f0e", "#9467bd"]
    character(len=*), parameter :: switch_colour = "#000000"

contains

    !> The data the figures need, one row per output row (thinned: rollcon_figure_rows): t, X, Y,
    !> contact x, y, theta, psidot,
    !> phidot, |E - E(t0)|/|E(t0)|, |E - E(t_end)|/|E(t_end)|, normal and tangential force,
    !> mu_needed, then |F_k| for each UCON and |height_residual| (at least residual_floor);
    !> with a `mode` column, then the contact point's y in each mode present (path_modes, in
    !> that order: mode_path) and at each switch (mode_switches), NaN elsewhere.
    subroutine write_contact_data(path, run, error)
        !> Data file to write
        character(len=*), intent(in) :: path
        !> A run of one part on a rim (rollcon_run_record's rolls_on_rim)
        type(run_record_type), intent(in) :: run
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: c(3), first_energy, last_energy
        real(wp), allocatable :: data(:, :), by_mode(:, :), wider(:, :)
        logical, allocatable :: paired(:)
        integer, allocatable :: modes(:), present(:)
        character(len=256) :: message
        integer :: unit, stat, j, k, n, fx, fy, fz, mu, height

        n = run%history%count
        fx = run%layout%column("Fx")
        fy = run%layout%column("Fy")
        fz = run%layout%column("Fz")
        mu = run%layout%column("mu_needed")
        height = run%layout%column("height_residual")
        associate (layout => run%layout)
            first_energy = run%history%rows(layout%energy_column(), 1)
            last_energy = run%history%rows(layout%energy_column(), n)
            message = "a write failed"
            open(newunit=unit, file=path, status="replace", action="write", access="stream", &
                & form="formatted", iostat=stat, iomsg=message)
            if (stat /= 0) then
                call fatal_error(error, path // ": cannot write the plot data: " &
                    & // trim(message), stat_io)
                return
            end if
            allocate(data(data_columns + size(layout%ucon_ids) + 1, n))
            do j = 1, n
                associate (r => run%history%rows(:, j))
                    c = path_point(run, 1, j)
                    data(:, j) = [r(1), r(layout%part_column(1, coord_x)), &
                        & r(layout%part_column(1, coord_y)), c(1:2), &
                        & r(layout%part_column(1, coord_theta)), &
                        & r(layout%part_column(1, coord_psidot)), &
                        & r(layout%part_column(1, coord_phidot)), &
                        & drift(r(layout%energy_column()), first_energy), &
                        & drift(r(layout%energy_column()), last_energy), &
                        & r(fz), norm2([r(fx), r(fy)]), r(mu), &
                        & [(max(abs(r(layout%residual_column(k))), residual_floor), &
                        & k = 1, size(layout%ucon_ids))], &
                        & max(abs(r(height)), residual_floor)]
                end associate
            end do
            ! thinned to what a figure shows; the paths (columns 2 to 5, and the contact
            ! point's by mode) by their own rows
            paired = [(k >= 2 .and. k <= 5, k = 1, size(data, 1))]
            call path_modes(run, modes, present)
            if (size(present) > 0) then
                allocate(by_mode(size(present) + 1, n))
                do k = 1, size(present)
                    by_mode(k, :) = mode_path(modes, data(5, :), present(k))
                end do
                by_mode(size(present) + 1, :) = mode_switches(modes, data(5, :))
                allocate(wider(size(data, 1) + size(by_mode, 1), n))
                wider(:size(data, 1), :) = data
                wider(size(data, 1) + 1:, :) = by_mode
                call move_alloc(wider, data)
                paired = [paired, spread(.true., 1, size(by_mode, 1))]
            end if
            call write_figure_rows(unit, data, paired, stat)
        end associate
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the plot data: " &
            & // trim(message), stat_io)
    end subroutine write_contact_data

    !> The contact's mode at each row (the `mode` column, rounded) and the modes present, in
    !> increasing order; none of either when the run has no `mode` column (no friction).
    !> prefix: of a dataset's several CONTACTs, the one whose columns start so ("contact2_":
    !> its contact2_mode).
    pure subroutine path_modes(run, modes, modes_present, prefix)
        type(run_record_type), intent(in) :: run
        integer, allocatable, intent(out) :: modes(:), modes_present(:)
        character(len=*), intent(in), optional :: prefix
        integer :: column, m

        allocate(modes_present(0))
        if (present(prefix)) then
            column = run%layout%column(trim(prefix) // "mode")
        else
            column = run%layout%column("mode")
        end if
        if (column == 0) then
            allocate(modes(0))
            return
        end if
        modes = nint(run%history%rows(column, :run%history%count))
        do m = minval(modes), maxval(modes)
            if (any(modes == m)) modes_present = [modes_present, m]
        end do
    end subroutine path_modes

    !> The colour of each row's mode (mode_colours) as the number gnuplot's `lc rgb variable`
    !> takes (256^2 red + 256 green + blue): the animation's path coloured by mode.
    pure function mode_colour_values(modes) result(values)
        !> The mode at each row (path_modes)
        integer, intent(in) :: modes(:)
        integer :: values(size(modes))
        integer :: j, red, green, blue

        do j = 1, size(modes)
            associate (hex => mode_colours(modulo(modes(j), size(mode_colours))))
                read(hex(2:3), '(z2)') red
                read(hex(4:5), '(z2)') green
                read(hex(6:7), '(z2)') blue
            end associate
            values(j) = 65536*red + 256*green + blue
        end do
    end function mode_colour_values

    !> values (a path's coordinate at each row) where the path is drawn in mode `wanted`: at
    !> the rows in that mode and at the row after each of its stretches, so that the stretch
    !> joins the next mode's where that begins; NaN elsewhere (gnuplot breaks a line there).
    pure function mode_path(modes, values, wanted) result(drawn)
        !> The mode at each row, and the coordinate
        integer, intent(in) :: modes(:)
        real(wp), intent(in) :: values(:)
        integer, intent(in) :: wanted
        real(wp) :: drawn(size(values))
        integer :: j

        drawn = ieee_value(1.0_wp, ieee_quiet_nan)
        do j = 1, size(values)
            if (modes(j) == wanted) then
                drawn(j) = values(j)
            else if (j > 1) then
                if (modes(j - 1) == wanted) drawn(j) = values(j)
            end if
        end do
    end function mode_path

    !> values at the first row of each mode after a switch (its mode differs from the row
    !> before's), NaN elsewhere: a switch lies between that row and the one before.
    pure function mode_switches(modes, values) result(marked)
        integer, intent(in) :: modes(:)
        real(wp), intent(in) :: values(:)
        real(wp) :: marked(size(values))
        integer :: j

        marked = ieee_value(1.0_wp, ieee_quiet_nan)
        do j = 2, size(values)
            if (modes(j) /= modes(j - 1)) marked(j) = values(j)
        end do
    end function mode_switches

    !> The mode's word in the legend: rolling, sliding, flight (contact_mode_words), or
    !> 'mode N' for a number it has no word for.
    pure function mode_title(mode) result(word)
        integer, intent(in) :: mode
        character(len=:), allocatable :: word

        if (mode >= lbound(contact_mode_words, 1) .and. mode <= ubound(contact_mode_words, 1)) &
            & then
            word = trim(contact_mode_words(mode))
        else
            word = "mode " // to_text(mode)
        end if
    end function mode_title

    !> The colour of a mode's stretches of a path ("#rrggbb": rolling blue, sliding red, ...).
    pure function mode_colour(mode) result(colour)
        integer, intent(in) :: mode
        character(len=7) :: colour

        colour = mode_colours(modulo(mode, size(mode_colours)))
    end function mode_colour

    !> The plot of the paths: the contact point (one line per mode present, with the
    !> switches marked, when the rows carry the mode) and the centre.
    pure function path_plot(data, run) result(text)
        character(len=*), intent(in) :: data
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: text
        integer, allocatable :: modes(:), present(:)
        integer :: k, first

        call path_modes(run, modes, present)
        if (size(present) == 0) then
            text = "plot " // data // " using 4:5 with lines lw 1.5 title 'contact point', " &
                & // data // " using 2:3 with lines lw 1.5 title 'centre'"
            return
        end if
        ! the columns after the residuals (write_contact_data)
        first = data_columns + size(run%layout%ucon_ids) + 2
        text = "plot "
        do k = 1, size(present)
            text = text // data // " using 4:" // to_text(first + k - 1) &
                & // " with lines lw 2 lc rgb '" // mode_colour(present(k)) // "' title " &
                & // gnuplot_string("contact point, " // mode_title(present(k))) // ", "
        end do
        text = text // data // " using 4:" // to_text(first + size(present)) &
            & // " with points pt 7 ps 0.6 lc rgb '" // switch_colour // "' title " &
            & // "'mode switch (first row after)', " &
            & // data // " using 2:3 with lines lw 1.5 lc rgb 'gray50' title 'centre'"
    end function path_plot

    !> The gnuplot script drawing every figure from the data file. Long because it is the
    !> figures' text, one figure after the other. The path's axes span at least
    !> path_axis_ranges's (a straight path drawn straight); with the contact's friction
    !> coefficients the friction figure draws them as lines, what mu_needed may reach while
    !> rolling (mu_static) and what it is while sliding (mu_kinetic).
    pure function contact_script(name, prefix, data_path, run, friction) result(text)
        !> The run's name, the figures' path less _<figure>.png, the data file
        character(len=*), intent(in) :: name, prefix, data_path
        type(run_record_type), intent(in) :: run
        !> The contact's mu_static and mu_kinetic (the run's summary: rollcon_run_record's
        !> read_friction), when it has friction
        real(wp), intent(in), optional :: friction(2)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        character(len=:), allocatable :: data, residuals, ranges
        real(wp), allocatable :: x(:), y(:)
        real(wp) :: point(3)
        integer :: k, nucons

        data = gnuplot_string(data_path)
        ! every point the path's figure draws: the centre and the contact point
        allocate(x(2*run%history%count), y(2*run%history%count))
        do k = 1, run%history%count
            point = path_point(run, 1, k)
            x(2*k - 1:2*k) = [run%history%rows(run%layout%part_column(1, coord_x), k), point(1)]
            y(2*k - 1:2*k) = [run%history%rows(run%layout%part_column(1, coord_y), k), point(2)]
        end do
        ranges = ""
        if (size(run%shapes) >= 1) ranges = path_axis_ranges(x, y, shape_extent(run%shapes(1)))
        text = figure_preamble(name)
        text = text // output(prefix, "path") &
            & // title(name // ": paths on the ground (equal axes)") &
            & // "set xlabel 'X [m]'" // nl // "set ylabel 'Y [m]'" // nl &
            & // "set size ratio -1" // nl // ranges &
            & // path_plot(data, run) // nl &
            & // "set size noratio" // nl // "set xlabel 't [s]'" // nl
        if (len(ranges) > 0) text = text // "set autoscale xy" // nl
        text = text // output(prefix, "theta") &
            & // title(name // ": tilt θ (π/2 upright, 0 and π flat)") &
            & // "set ylabel 'θ [rad]'" // nl &
            & // "plot " // data // " using 1:6 with lines lw 1.5 title 'θ', pi/2 with " &
            & // "lines dashtype 2 lc 'gray40' title 'upright'" // nl
        text = text // output(prefix, "rates") &
            & // title(name // ": precession and spin rates") &
            & // "set ylabel 'rate [rad/s]'" // nl &
            & // "plot " // data // " using 1:7 with lines lw 1.5 title 'dψ/dt (precession)', " &
            & // data // " using 1:8 with lines lw 1.5 title 'dφ/dt (spin)'" // nl
        text = text // output(prefix, "energy") &
            & // title(name // ": energy drift (a push changes E on purpose)") &
            & // "set ylabel 'relative change of E'" // nl // "set logscale y" // nl &
            & // "set format y '%.0e'" // nl &
            & // "plot " // data // " using 1:9 with lines lw 1.5 title " &
            & // "'|E - E(start)|/|E(start)|', " &
            & // data // " using 1:10 with lines lw 1.5 title '|E - E(end)|/|E(end)|'" // nl
        residuals = ""
        nucons = size(run%layout%ucon_ids)
        do k = 1, nucons + 1
            if (k > 1) residuals = residuals // ", "
            residuals = residuals // data // " using 1:" // to_text(data_columns + k) &
                & // " with lines lw 1.2 title "
            if (k <= nucons) then
                residuals = residuals // gnuplot_string("|F_" &
                    & // to_text(run%layout%ucon_ids(k)) // "|")
            else
                residuals = residuals // "'|height_residual|'"
            end if
        end do
        text = text // output(prefix, "residuals") &
            & // title(name // ": constraint residuals (zero drawn at " &
            & // to_text(residual_floor) // ")") &
            & // "set ylabel '|F_k| [m/s]; |height_residual| [m]'" // nl &
            & // "plot " // residuals // nl &
            & // "unset logscale y" // nl // "set format y '% h'" // nl
        text = text // output(prefix, "force") &
            & // title(name // ": contact force on the disk") &
            & // "set ylabel 'force [N]'" // nl &
            & // "plot " // data // " using 1:11 with lines lw 1.5 title 'normal', " &
            & // data // " using 1:12 with lines lw 1.5 title 'tangential'" // nl
        text = text // output(prefix, "friction") &
            & // title(name // ": friction coefficient needed to roll (|tangential|/normal)") &
            & // "set ylabel 'μ needed'" // nl
        ! room above mu_static's line, which would lie on the frame at the autoscaled top
        if (present(friction)) text = text // "set offsets 0, 0, graph 0.08, 0" // nl
        text = text // "plot " // data // " using 1:13 with lines lw 1.5 title 'μ needed'"
        if (present(friction)) text = text // friction_lines(friction) // nl // "unset offsets"
        text = text // nl // "unset output" // nl
    end function contact_script

    !> The friction figure's lines of the contact's coefficients, to follow its plot command:
    !> mu_static dashed, mu_kinetic dotted (one line when they are equal). Rows are often
    !> farther apart than a rise of mu_needed to mu_static takes (a few ms), so the curve
    !> alone need not show where rolling gave way.
    pure function friction_lines(friction) result(text)
        !> mu_static, mu_kinetic
        real(wp), intent(in) :: friction(2)
        character(len=:), allocatable :: text

        if (friction(2) == friction(1)) then
            text = ", " // to_text(friction(1)) // " with lines dashtype 2 lw 1.5 lc rgb '" &
                & // mode_colour(1) // "' title " // gnuplot_string("μs = μk = " &
                & // to_text(friction(1)))
            return
        end if
        text = ", " // to_text(friction(1)) // " with lines dashtype 2 lw 1.5 lc rgb '" &
            & // mode_colour(0) // "' title " // gnuplot_string("μs = " // to_text(friction(1)) &
            & // " (static: rolling holds below)") // ", " // to_text(friction(2)) &
            & // " with lines dashtype 3 lw 1.5 lc rgb '" // mode_colour(1) // "' title " &
            & // gnuplot_string("μk = " // to_text(friction(2)) // " (kinetic: sliding)")
    end function friction_lines

end module rollcon_contact_figures
