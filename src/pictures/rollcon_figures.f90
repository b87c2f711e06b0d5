! SPDX-License-Identifier: MIT
!> The plots of a run, as PNG files drawn by gnuplot from an output CSV. The CSV of one part
!> rolling on a rim, with its rim contact's columns (a disk scene's), gets the contact's figures
!> (paths on the ground, theta, the precession and spin rates, energy drift, constraint
!> residuals, contact force and the friction coefficient it needs: rollcon_contact_figures);
!> any other model's gets a set for any parts (paths and heights of the centres of mass, Euler
!> angles, energy drift, UCON residuals and multipliers), the path of a part a CONTACT holds
!> coloured by the contact's mode as the contact's figures colour theirs.
module rollcon_figures
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_run_record, only : run_record_type, read_run, rolls_on_rim, read_friction, &
        & contact_part
    use rollcon_output_layout, only : coord_x, coord_y, coord_phi
    use rollcon_part_shapes, only : shape_extent
    use rollcon_contact_figures, only : contact_figure_names, write_contact_data, &
        & contact_script, path_modes, mode_path, mode_switches, mode_title, mode_colour, &
        & switch_colour
    use rollcon_singularity_figure, only : has_singularity, write_singularity_data, &
        & singularity_script, singularity_figure_name
    use rollcon_figure_text, only : drift, residual_floor, title, output, figure_preamble, &
        & path_axis_ranges
    use rollcon_gnuplot, only : require_gnuplot, run_gnuplot, gnuplot_string, base_name, &
        & remove_file
    use rollcon_text, only : to_text
    use rollcon_output_files, only : close_checked
    use rollcon_figure_rows, only : write_figure_rows
    implicit none
    private

    public :: plot_output, figure_file, figure_names, model_figure_names, figures_of, &
        & write_model_data, model_script

    !> The figures of a part rolling on a rim, each written as DIR/<base>_<name>.png
    character(len=*), parameter :: figure_names(7) = contact_figure_names
    !> The figures of any other model, each written as DIR/<base>_<name>.png
    character(len=*), parameter :: model_figure_names(6) = [character(len=11) :: "path", &
        & "height", "angles", "energy", "residuals", "multipliers"]
    !> The multipliers' axis: λ_k carries the power (velocity UCON) or work (position UCON) per
    !> unit of F_k, as its generalised force is λ_k ∂F_k/∂q̇ (or ∂F_k/∂q): a force for F in m/s
    !> or m (the coin's λ_1, λ_2, λ_3 are its contact force), a moment for F in rad/s or rad
    character(len=*), parameter :: multiplier_label = &
        & "λ_k [N for F_k in m/s or m; N m for F_k in rad/s or rad]"

contains

    !> Draw the figures of an output CSV into output_dir (which must exist), as
    !> output_dir/<base>_<figure>.png, <base> the CSV's file name less '.csv': figure_names for
    !> the CSV of a part rolling on a rim, model_figure_names for any other. The gnuplot script
    !> and its data (<base>_plots.gp, .dat) are removed when gnuplot succeeds and kept when it
    !> fails.
    subroutine plot_output(csv_path, output_dir, error, files, script)
        !> Output CSV of `rollcon run` (its part shapes beside it, rollcon_run_record)
        character(len=*), intent(in) :: csv_path
        !> Folder for the PNG files
        character(len=*), intent(in) :: output_dir
        type(error_type), allocatable, intent(out) :: error
        !> The PNG files written
        character(len=:), allocatable, intent(out), optional :: files(:)
        !> The gnuplot script given to gnuplot (what <base>_plots.gp held)
        character(len=:), allocatable, intent(out), optional :: script
        type(run_record_type) :: run
        character(len=:), allocatable :: prefix, data_path, script_path, names(:), text
        real(wp) :: friction(2)
        logical :: has_friction
        integer :: i, unit, stat, size_bytes, length

        call read_run(csv_path, run, error)
        if (allocated(error)) return
        call require_gnuplot(error)
        if (allocated(error)) return
        prefix = output_dir // "/" // base_name(csv_path, ".csv")
        data_path = prefix // "_plots.dat"
        script_path = prefix // "_plots.gp"
        call remove_figures(csv_path, output_dir)
        names = figures_of(run)
        if (rolls_on_rim(run)) then
            call write_contact_data(data_path, run, error)
            call read_friction(csv_path, friction, has_friction)
            if (.not. allocated(error) .and. has_friction) text = contact_script(base_name( &
                & csv_path, ".csv"), prefix, data_path, run, friction)
            if (.not. allocated(error) .and. .not. has_friction) text = contact_script( &
                & base_name(csv_path, ".csv"), prefix, data_path, run)
            ! a disk settling to its finite-time singularity: Omega against t0 - t
            if (.not. allocated(error) .and. has_singularity(run)) then
                call write_singularity_data(prefix // "_singularity.dat", run, error)
                if (.not. allocated(error)) text = text // singularity_script(base_name( &
                    & csv_path, ".csv"), prefix, prefix // "_singularity.dat", run)
            end if
        else
            call write_model_data(data_path, run, error)
            if (.not. allocated(error)) text = model_script(base_name(csv_path, ".csv"), &
                & prefix, data_path, run)
        end if
        if (allocated(error)) return
        if (present(script)) script = text
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
        do i = 1, size(names)
            if (allocated(error)) exit
            inquire(file=figure_file(csv_path, output_dir, names(i)), size=size_bytes)
            if (size_bytes <= 0) then
                call fatal_error(error, figure_file(csv_path, output_dir, names(i)) &
                    & // ": gnuplot reported success but " &
                    & // "did not write this PNG file (see " // script_path // ")", stat_io)
            end if
        end do
        if (allocated(error)) then
            ! No figure of a failed set is left behind (gnuplot may have opened them all).
            call remove_figures(csv_path, output_dir)
            return
        end if
        call remove_file(script_path)
        call remove_file(data_path)
        call remove_file(prefix // "_singularity.dat")
        if (present(files)) then
            length = 0
            do i = 1, size(names)
                length = max(length, len(figure_file(csv_path, output_dir, names(i))))
            end do
            allocate(character(len=length) :: files(size(names)))
            do i = 1, size(names)
                files(i) = figure_file(csv_path, output_dir, names(i))
            end do
        end if
    end subroutine plot_output

    !> The names of the figures of a run: figure_names for a disk scene (and the singularity's
    !> for one settling to it, rollcon_singularity_figure), else model_figure_names.
    pure function figures_of(run) result(names)
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: names(:)

        if (rolls_on_rim(run)) then
            names = figure_names
            if (has_singularity(run)) names = [character(len=max(len(names), &
                & len(singularity_figure_name))) :: names, singularity_figure_name]
        else
            names = model_figure_names
        end if
    end function figures_of

    !> Remove every figure either set may have left for this CSV.
    subroutine remove_figures(csv_path, output_dir)
        character(len=*), intent(in) :: csv_path, output_dir
        integer :: i

        do i = 1, size(figure_names)
            call remove_file(figure_file(csv_path, output_dir, figure_names(i)))
        end do
        do i = 1, size(model_figure_names)
            call remove_file(figure_file(csv_path, output_dir, model_figure_names(i)))
        end do
        call remove_file(figure_file(csv_path, output_dir, singularity_figure_name))
    end subroutine remove_figures

    !> The PNG file of a figure: output_dir/<base>_<figure>.png, <base> the CSV's file name
    !> less '.csv'.
    pure function figure_file(csv_path, output_dir, figure) result(path)
        !> Output CSV
        character(len=*), intent(in) :: csv_path
        !> Folder of the figures
        character(len=*), intent(in) :: output_dir
        !> One of figure_names or model_figure_names
        character(len=*), intent(in) :: figure
        character(len=:), allocatable :: path

        path = output_dir // "/" // base_name(csv_path, ".csv") // "_" // trim(figure) // ".png"
    end function figure_file

    !> The data of the model figures, one row per output row: t; X, Y, Z, psi, theta, phi of
    !> each part; |E - E(t0)|/|E(t0)|, |E - E(t_end)|/|E(t_end)|; |F_k| of each UCON (at least
    !> residual_floor); lambda_k of each UCON; with the contact's mode (a `mode` column), the Y
    !> of the contact's part (contact_part) in each mode present (path_modes, in that order:
    !> mode_path) and at each switch (mode_switches), NaN elsewhere.
    subroutine write_model_data(path, run, error)
        !> Data file to write
        character(len=*), intent(in) :: path
        !> A run read by read_run
        type(run_record_type), intent(in) :: run
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: row(:), data(:, :), wider(:, :)
        logical, allocatable :: paired(:)
        integer, allocatable :: modes(:), present(:)
        character(len=256) :: message
        integer :: unit, stat, j, p, n, nucons, np, c, k

        n = run%history%count
        nucons = size(run%layout%ucon_ids)
        message = "a write failed"
        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the plot data: " // trim(message), &
                & stat_io)
            return
        end if
        np = size(run%layout%part_ids)
        allocate(data(3 + 6*np + 2*nucons, n))
        associate (rows => run%history%rows, energy => run%layout%energy_column())
            do j = 1, n
                row = [rows(1, j)]
                do p = 1, np
                    row = [row, rows(run%layout%part_column(p, coord_x):run%layout%part_column(p, &
                        & coord_phi), j)]
                end do
                row = [row, drift(rows(energy, j), rows(energy, 1)), drift(rows(energy, j), &
                    & rows(energy, n))]
                if (nucons > 0) row = [row, max(abs(rows(run%layout%residual_column(1): &
                    & run%layout%residual_column(nucons), j)), residual_floor), &
                    & rows(run%layout%multiplier_column(1):run%layout%multiplier_column(nucons), j)]
                data(:, j) = row
            end do
        end associate
        ! thinned to what a figure shows; each part's X and Y (its path) by their own rows
        paired = [(c > 1 .and. c <= 1 + 6*np .and. mod(c - 2, 6) < 2, c = 1, size(data, 1))]
        ! the contact's part's Y in each mode present and at each switch, paired with its X
        call path_modes(run, modes, present)
        p = contact_part(run)
        if (size(present) > 0 .and. p > 0) then
            allocate(wider(size(data, 1) + size(present) + 1, n))
            wider(:size(data, 1), :) = data
            do k = 1, size(present)
                wider(size(data, 1) + k, :) = mode_path(modes, data(1 + 6*(p - 1) + 2, :), &
                    & present(k))
            end do
            wider(size(data, 1) + size(present) + 1, :) = mode_switches(modes, &
                & data(1 + 6*(p - 1) + 2, :))
            call move_alloc(wider, data)
            paired = [paired, spread(.true., 1, size(present) + 1)]
        end if
        call write_figure_rows(unit, data, paired, stat)
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the plot data: " &
            & // trim(message), stat_io)
    end subroutine write_model_data

    !> The gnuplot script of the model figures (data columns as write_model_data writes them).
    !> The path's axes span at least path_axis_ranges's for the largest part (a straight path
    !> drawn straight); the contact's part's path is drawn a line per mode, its switches marked.
    pure function model_script(name, prefix, data_path, run) result(text)
        !> The run's name, the figures' path less _<figure>.png, the data file
        character(len=*), intent(in) :: name, prefix, data_path
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        character(len=*), parameter :: angle_names(3) = [character(len=5) :: "ψ", "θ", "φ"]
        character(len=:), allocatable :: data, ranges
        integer :: c

        data = gnuplot_string(data_path)
        ranges = path_ranges(run)
        text = figure_preamble(name) // output(prefix, "path") &
            & // title(name // ": paths of the centres of mass (equal axes)") &
            & // "set xlabel 'X [m]'" // nl // "set ylabel 'Y [m]'" // nl &
            & // "set size ratio -1" // nl // ranges &
            & // "plot" // part_curves(data, run, 1, 2, " centre of mass") // nl &
            & // "set size noratio" // nl // "set xlabel 't [s]'" // nl
        if (len(ranges) > 0) text = text // "set autoscale xy" // nl
        text = text // output(prefix, "height") &
            & // title(name // ": height Z of the centres of mass") &
            & // "set ylabel 'Z [m]'" // nl // "plot" // part_curves(data, run, 0, 3, "") // nl
        text = text // output(prefix, "angles") &
            & // "set multiplot layout 3,1 title " // gnuplot_string(name // ": Euler angles " &
            & // "ψ, θ, φ (body-fixed 3-1-3, not wrapped)") // nl // "unset title" // nl
        do c = 1, 3
            text = text // "set ylabel '" // trim(angle_names(c)) // " [rad]'" // nl &
                & // "plot" // part_curves(data, run, 0, 3 + c, "") // nl
        end do
        text = text // "unset multiplot" // nl // ucon_figures(name, prefix, data, run)
    end function model_script

    !> The lines that give the paths' figure its least span (path_axis_ranges): over every
    !> part's centre of mass, the largest part's size the floor.
    pure function path_ranges(run) result(text)
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: text
        real(wp), allocatable :: x(:), y(:)
        real(wp) :: extent
        integer :: p, n

        n = run%history%count
        allocate(x(0), y(0))
        do p = 1, size(run%layout%part_ids)
            x = [x, run%history%rows(run%layout%part_column(p, coord_x), :n)]
            y = [y, run%history%rows(run%layout%part_column(p, coord_y), :n)]
        end do
        extent = 0.0_wp
        if (size(run%shapes) > 0) extent = maxval(shape_extent(run%shapes))
        text = path_axis_ranges(x, y, extent)
    end function path_ranges

    !> The curves of a quantity of every part, for a plot command: data column x against data
    !> column y of each part's X, Y, Z, psi, theta, phi (1 .. 6; 0 is t), titled 'part <id>'
    !> and what.
    pure function part_curves(data, run, x, y, what) result(curves)
        character(len=*), intent(in) :: data
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: x, y
        character(len=*), intent(in) :: what
        character(len=:), allocatable :: curves
        integer :: p

        integer, allocatable :: modes(:), present(:)
        integer :: k, contact, first

        curves = ""
        call path_modes(run, modes, present)
        contact = 0
        ! the path (X, Y) of the contact's part by mode: the columns after the multipliers
        if (x == 1 .and. y == 2 .and. size(present) > 0) contact = contact_part(run)
        first = 4 + 6*size(run%layout%part_ids) + 2*size(run%layout%ucon_ids)
        do p = 1, size(run%layout%part_ids)
            if (p /= contact) then
                curves = curves // merge(", ", "  ", p > 1) // data // " using " &
                    & // to_text(column(p, x)) // ":" // to_text(column(p, y)) &
                    & // " with lines lw 1.5 title " &
                    & // gnuplot_string("part " // to_text(run%layout%part_ids(p)) // what)
                cycle
            end if
            do k = 1, size(present)
                curves = curves // merge(", ", "  ", p > 1 .or. k > 1) // data // " using " &
                    & // to_text(column(p, x)) // ":" // to_text(first + k - 1) &
                    & // " with lines lw 2 lc rgb '" // mode_colour(present(k)) &
                    & // "' title " // gnuplot_string("part " &
                    & // to_text(run%layout%part_ids(p)) // what // ", " &
                    & // mode_title(present(k)))
            end do
            curves = curves // ", " // data // " using " // to_text(column(p, x)) // ":" &
                & // to_text(first + size(present)) // " with points pt 7 ps 0.6 lc rgb '" &
                & // switch_colour // "' title 'mode switch (first row after)'"
        end do
    contains
        !> Data column of part p's coordinate c (write_model_data); t for c = 0.
        pure integer function column(p, c)
            integer, intent(in) :: p, c

            column = 1
            if (c > 0) column = 1 + 6*(p - 1) + c
        end function column
    end function part_curves

    !> The energy, residual and multiplier figures of the model figures.
    pure function ucon_figures(name, prefix, data, run) result(text)
        !> The run's name, the figures' path less _<figure>.png, the data file as a gnuplot
        !> string
        character(len=*), intent(in) :: name, prefix, data
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        character(len=:), allocatable :: residuals, multipliers
        integer :: k, nucons, drift_column

        nucons = size(run%layout%ucon_ids)
        drift_column = 2 + 6*size(run%layout%part_ids)
        residuals = ""
        multipliers = ""
        do k = 1, nucons
            residuals = residuals // merge(", ", "  ", k > 1) // data // " using 1:" &
                & // to_text(drift_column + 1 + k) // " with lines lw 1.2 title " &
                & // gnuplot_string("|F_" // to_text(run%layout%ucon_ids(k)) // "|")
            multipliers = multipliers // merge(", ", "  ", k > 1) // data // " using 1:" &
                & // to_text(drift_column + 1 + nucons + k) // " with lines lw 1.2 title " &
                & // gnuplot_string("λ_" // to_text(run%layout%ucon_ids(k)))
        end do
        ! gnuplot refuses a plot with no defined point: a model without UCONs gets flat lines
        if (nucons == 0) then
            residuals = " " // data // " using 1:(" // to_text(residual_floor) &
                & // ") with lines title 'no UCON'"
            multipliers = " " // data // " using 1:(0) with lines title 'no UCON'"
        end if
        text = output(prefix, "energy") &
            & // title(name // ": energy drift (an applied force changes E on purpose)") &
            & // "set ylabel 'relative change of E'" // nl // "set logscale y" // nl &
            & // "set format y '%.0e'" // nl &
            & // "plot " // data // " using 1:" // to_text(drift_column) // " with lines " &
            & // "lw 1.5 title '|E - E(start)|/|E(start)|', " // data // " using 1:" &
            & // to_text(drift_column + 1) // " with lines lw 1.5 title '|E - E(end)|/|E(end)|'" &
            & // nl
        text = text // output(prefix, "residuals") &
            & // title(name // ": UCON residuals (zero drawn at " // to_text(residual_floor) &
            & // ")") // "set ylabel '|F_k| (each UCON in its own unit)'" // nl &
            & // "plot" // residuals // nl &
            & // "unset logscale y" // nl // "set format y '% h'" // nl
        text = text // output(prefix, "multipliers") &
            & // title(name // ": UCON multipliers (the constraint forces' size)") &
            & // "set ylabel " // gnuplot_string(multiplier_label) // nl &
            & // "plot" // multipliers // nl // "unset output" // nl
    end function ucon_figures

end module rollcon_figures
