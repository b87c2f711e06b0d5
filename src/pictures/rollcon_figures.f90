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
        & switch_colour, friction_lines
    use rollcon_watch_columns, only : contact_prefixes, contact_column_prefix
    use rollcon_output_layout, only : name_length
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
        & write_model_data, model_script, drawn_contact_type, drawn_contacts, &
        & model_friction_figure

    !> The figures of a part rolling on a rim, each written as DIR/<base>_<name>.png
    character(len=*), parameter :: figure_names(7) = contact_figure_names
    !> The figures of any other model, each written as DIR/<base>_<name>.png
    character(len=*), parameter :: model_figure_names(6) = [character(len=11) :: "path", &
        & "height", "angles", "energy", "residuals", "multipliers"]
    !> The figure a model with contacts adds: the friction coefficient each needs
    character(len=*), parameter :: model_friction_figure = "friction"

    !> A contact of a run's rows (contact_prefixes), as the model figures draw it: the prefix
    !> of its columns ("" for a model's one contact), its CONTACT's id (0 for the one
    !> contact), its part (contact_part; 0: none found), its mode at each row and the modes
    !> present (path_modes), the data column of its part's Y in its first mode present
    !> (write_model_data; the others and the switches after it; 0: not drawn by mode) and of
    !> its mu_needed (0: none)
    type :: drawn_contact_type
        character(len=name_length) :: prefix = ""
        integer :: id = 0, part = 0, first = 0, mu_column = 0
        integer, allocatable :: modes(:), present(:)
    end type drawn_contact_type

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
                & prefix, data_path, run, contact_frictions(csv_path, run))
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
    !> for one settling to it, rollcon_singularity_figure), else model_figure_names, and the
    !> friction figure (model_friction_figure) for a model with contacts.
    pure function figures_of(run) result(names)
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: names(:)

        if (rolls_on_rim(run)) then
            names = figure_names
            if (has_singularity(run)) names = [character(len=max(len(names), &
                & len(singularity_figure_name))) :: names, singularity_figure_name]
        else
            names = model_figure_names
            if (size(contact_prefixes(run%layout)) > 0) names = [character(len=max(len(names), &
                & len(model_friction_figure))) :: names, model_friction_figure]
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
    !> residual_floor); lambda_k of each UCON; for each contact with its mode (a `mode`
    !> column, or contact<id>_mode of several), the Y of the contact's part (contact_part) in
    !> each mode present (path_modes, in that order: mode_path) and at each switch
    !> (mode_switches), NaN elsewhere; then each contact's mu_needed (drawn_contacts).
    subroutine write_model_data(path, run, error)
        !> Data file to write
        character(len=*), intent(in) :: path
        !> A run read by read_run
        type(run_record_type), intent(in) :: run
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: row(:), data(:, :), wider(:, :)
        logical, allocatable :: paired(:)
        type(drawn_contact_type), allocatable :: contacts(:)
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
        ! each contact's part's Y in each mode present and at each switch, paired with its X,
        ! then each contact's mu_needed (drawn_contacts: the columns in that order)
        contacts = drawn_contacts(run)
        do c = 1, size(contacts)
            p = contacts(c)%part
            if (contacts(c)%first == 0) cycle
            associate (modes => contacts(c)%modes, present => contacts(c)%present)
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
            end associate
        end do
        do c = 1, size(contacts)
            if (contacts(c)%mu_column == 0) cycle
            allocate(wider(size(data, 1) + 1, n))
            wider(:size(data, 1), :) = data
            wider(size(data, 1) + 1, :) = run%history%rows(run%layout%column( &
                & trim(contacts(c)%prefix) // "mu_needed"), :n)
            call move_alloc(wider, data)
            paired = [paired, .false.]
        end do
        call write_figure_rows(unit, data, paired, stat)
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the plot data: " &
            & // trim(message), stat_io)
    end subroutine write_model_data

    !> The gnuplot script of the model figures (data columns as write_model_data writes them).
    !> The path's axes span at least path_axis_ranges's for the largest part (a straight path
    !> drawn straight); the contact's part's path is drawn a line per mode, its switches marked.
    pure function model_script(name, prefix, data_path, run, frictions) result(text)
        !> The run's name, the figures' path less _<figure>.png, the data file
        character(len=*), intent(in) :: name, prefix, data_path
        type(run_record_type), intent(in) :: run
        !> Each contact's mu_static and mu_kinetic (drawn_contacts' order; 0, 0 where the
        !> summary does not give them: contact_frictions)
        real(wp), intent(in), optional :: frictions(:, :)
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
        if (present(frictions)) then
            text = text // friction_figure(name, prefix, data, run, frictions)
        else
            text = text // friction_figure(name, prefix, data, run, &
                & reshape([real(wp) :: ], [2, 0]))
        end if
    end function model_script

    !> The friction figure of a model with contacts: each contact's mu_needed (|F_t| / F_n)
    !> against t, titled by its CONTACT where there are several, and its mu_static and
    !> mu_kinetic where frictions gives them (one contact: the contact figures' lines,
    !> friction_lines; several: each contact's dashed and dotted in its curve's colour).
    !> Empty for a model without contacts.
    pure function friction_figure(name, prefix, data, run, frictions) result(text)
        character(len=*), intent(in) :: name, prefix, data
        type(run_record_type), intent(in) :: run
        real(wp), intent(in) :: frictions(:, :)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        type(drawn_contact_type), allocatable :: contacts(:)
        character(len=:), allocatable :: curves, label
        real(wp) :: f(2)
        logical :: known
        integer :: c

        text = ""
        contacts = drawn_contacts(run)
        if (size(contacts) == 0) return
        curves = ""
        do c = 1, size(contacts)
            if (contacts(c)%mu_column == 0) cycle
            f = 0.0_wp
            if (size(frictions, 2) >= c) f = frictions(:, c)
            known = f(1) > 0.0_wp .and. f(2) > 0.0_wp
            if (contacts(c)%id == 0) then
                curves = curves // merge(", ", "  ", len(curves) > 0) // data // " using 1:" &
                    & // to_text(contacts(c)%mu_column) // " with lines lw 1.5 title 'μ needed'"
                if (known) curves = curves // friction_lines(f)
                cycle
            end if
            label = "CONTACT/" // to_text(contacts(c)%id)
            if (contacts(c)%part > 0) label = label // " (part " &
                & // to_text(run%layout%part_ids(contacts(c)%part)) // ")"
            curves = curves // merge(", ", "  ", len(curves) > 0) // data // " using 1:" &
                & // to_text(contacts(c)%mu_column) // " with lines lw 1.5 lt " // to_text(c) &
                & // " title " // gnuplot_string(label // ": μ needed")
            if (.not. known) cycle
            curves = curves // ", " // to_text(f(1)) // " with lines dashtype 2 lw 1.2 lt " &
                & // to_text(c) // " title " // gnuplot_string(label // ": μs = " &
                & // to_text(f(1)))
            if (f(2) /= f(1)) curves = curves // ", " // to_text(f(2)) // " with lines " &
                & // "dashtype 3 lw 1.2 lt " // to_text(c) // " title " &
                & // gnuplot_string(label // ": μk = " // to_text(f(2)))
        end do
        ! gnuplot refuses a plot with no defined point: no contact's mu_needed column
        if (len(curves) == 0) curves = " " // data // " using 1:(0) with lines title " &
            & // "'no mu_needed column'"
        text = output(prefix, model_friction_figure) &
            & // title(name // ": friction coefficient each contact needs to roll " &
            & // "(|tangential|/normal)") // "set ylabel 'μ needed'" // nl &
            & // "set offsets 0, 0, graph 0.08, 0" // nl // "plot" // curves // nl &
            & // "unset offsets" // nl // "unset output" // nl
    end function friction_figure

    !> The contacts of a run's rows as the model figures draw them (drawn_contact_type), in
    !> the order of their columns: the data columns after the multipliers hold each drawn
    !> contact's modes present and switches in turn, then each one's mu_needed.
    pure function drawn_contacts(run) result(contacts)
        type(run_record_type), intent(in) :: run
        type(drawn_contact_type), allocatable :: contacts(:)
        character(len=name_length), allocatable :: prefixes(:)
        integer :: c, column, stem

        prefixes = contact_prefixes(run%layout)
        allocate(contacts(size(prefixes)))
        column = 4 + 6*size(run%layout%part_ids) + 2*size(run%layout%ucon_ids)
        stem = index(contact_column_prefix, "<n>") - 1
        do c = 1, size(prefixes)
            contacts(c)%prefix = prefixes(c)
            if (len_trim(prefixes(c)) > stem + 1) read(prefixes(c)(stem + 1:len_trim( &
                & prefixes(c)) - 1), *) contacts(c)%id
            contacts(c)%part = contact_part(run, trim(prefixes(c)))
            call path_modes(run, contacts(c)%modes, contacts(c)%present, trim(prefixes(c)))
            if (size(contacts(c)%present) > 0 .and. contacts(c)%part > 0) then
                contacts(c)%first = column
                column = column + size(contacts(c)%present) + 1
            end if
        end do
        do c = 1, size(prefixes)
            if (run%layout%column(trim(prefixes(c)) // "mu_needed") == 0) cycle
            contacts(c)%mu_column = column
            column = column + 1
        end do
    end function drawn_contacts

    !> Each contact's mu_static and mu_kinetic (drawn_contacts' order) from the run's summary
    !> beside its CSV (read_friction); 0, 0 for a contact it does not give them.
    function contact_frictions(csv_path, run) result(frictions)
        character(len=*), intent(in) :: csv_path
        type(run_record_type), intent(in) :: run
        real(wp), allocatable :: frictions(:, :)
        type(drawn_contact_type), allocatable :: contacts(:)
        logical :: found
        integer :: c

        contacts = drawn_contacts(run)
        allocate(frictions(2, size(contacts)), source=0.0_wp)
        do c = 1, size(contacts)
            if (contacts(c)%id == 0) then
                call read_friction(csv_path, frictions(:, c), found)
            else
                call read_friction(csv_path, frictions(:, c), found, contacts(c)%id)
            end if
        end do
    end function contact_frictions

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
    !> and what; the path (X, Y) of each part a contact holds a line per mode of that
    !> contact's, its switches marked (one legend entry for all).
    pure function part_curves(data, run, x, y, what) result(curves)
        character(len=*), intent(in) :: data
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: x, y
        character(len=*), intent(in) :: what
        character(len=:), allocatable :: curves
        integer :: p

        type(drawn_contact_type), allocatable :: contacts(:)
        integer :: k, c, found
        logical :: switch_titled

        curves = ""
        ! the path (X, Y) of each contact's part by its mode: the columns after the
        ! multipliers (drawn_contacts)
        allocate(contacts(0))
        if (x == 1 .and. y == 2) contacts = drawn_contacts(run)
        switch_titled = .false.
        do p = 1, size(run%layout%part_ids)
            found = 0
            do c = 1, size(contacts)
                if (contacts(c)%part == p .and. contacts(c)%first > 0) found = c
            end do
            if (found == 0) then
                curves = curves // merge(", ", "  ", p > 1) // data // " using " &
                    & // to_text(column(p, x)) // ":" // to_text(column(p, y)) &
                    & // " with lines lw 1.5 title " &
                    & // gnuplot_string("part " // to_text(run%layout%part_ids(p)) // what)
                cycle
            end if
            associate (present => contacts(found)%present, first => contacts(found)%first)
                do k = 1, size(present)
                    curves = curves // merge(", ", "  ", p > 1 .or. k > 1) // data &
                        & // " using " // to_text(column(p, x)) // ":" &
                        & // to_text(first + k - 1) // " with lines lw 2 lc rgb '" &
                        & // mode_colour(present(k)) // "' title " // gnuplot_string("part " &
                        & // to_text(run%layout%part_ids(p)) // what // ", " &
                        & // mode_title(present(k)))
                end do
                ! the switches' marks, one legend entry for every contact's
                curves = curves // ", " // data // " using " // to_text(column(p, x)) // ":" &
                    & // to_text(first + size(present)) // " with points pt 7 ps 0.6 lc rgb '" &
                    & // switch_colour // "' "
                if (switch_titled) then
                    curves = curves // "notitle"
                else
                    curves = curves // "title 'mode switch (first row after)'"
                end if
                switch_titled = .true.
            end associate
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
