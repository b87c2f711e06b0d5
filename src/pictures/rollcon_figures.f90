! SPDX-License-Identifier: MIT
!> The plots of a run, as PNG files drawn by gnuplot from an output CSV: paths on the ground,
!> theta, the precession and spin rates, energy drift, constraint residuals, contact force and
!> the friction coefficient it needs.
module rollcon_figures
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_simulation, only : history_type, column_time, column_x, column_y, column_phi, &
        & column_theta, column_psidot, column_phidot, column_energy, column_fx, column_fy, &
        & column_fz, column_mu, column_residual
    use rollcon_csv_reader, only : read_output_csv, name_length
    use rollcon_disk_mesh, only : contact_point
    use rollcon_gnuplot, only : require_gnuplot, run_gnuplot, gnuplot_string, base_name, &
        & remove_file
    use rollcon_text, only : to_text
    use rollcon_output_files, only : close_checked
    implicit none
    private

    public :: plot_output, figure_file

    !> The figures, each written as DIR/<base>_<name>.png
    character(len=*), parameter, public :: figure_names(7) = [character(len=9) :: "path", &
        & "theta", "rates", "energy", "residuals", "force", "friction"]

    !> Relative energy drifts below round-off are drawn at this level (a log axis has no zero)
    real(wp), parameter :: drift_floor = epsilon(1.0_wp)
    !> Constraint residuals below this are drawn at it [m/s] (a log axis has no zero)
    real(wp), parameter :: residual_floor = 1.0e-20_wp
    !> Columns of the data file written for gnuplot, before one |F_k| column per UCON
    integer, parameter :: data_columns = 13

contains

    !> Draw the figures of an output CSV into output_dir (which must exist), as
    !> output_dir/<base>_<figure>.png, <base> the CSV's file name less '.csv'. The gnuplot
    !> script and its data (<base>_plots.gp, .dat) are removed when gnuplot succeeds and kept
    !> when it fails.
    subroutine plot_output(csv_path, output_dir, error)
        !> Output CSV of `rollcon run`
        character(len=*), intent(in) :: csv_path
        !> Folder for the PNG files, figure_file(csv_path, output_dir, figure_names(i))
        character(len=*), intent(in) :: output_dir
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        character(len=name_length), allocatable :: names(:)
        character(len=:), allocatable :: prefix, data_path, script_path
        real(wp) :: radius
        integer :: i, unit, stat, size_bytes

        call read_output_csv(csv_path, history, radius, error, names)
        if (allocated(error)) return
        call require_gnuplot(error)
        if (allocated(error)) return
        prefix = output_dir // "/" // base_name(csv_path, ".csv")
        data_path = prefix // "_plots.dat"
        script_path = prefix // "_plots.gp"
        do i = 1, size(figure_names)
            call remove_file(figure_file(csv_path, output_dir, figure_names(i)))
        end do
        call write_data(data_path, history, radius, error)
        if (allocated(error)) return
        open(newunit=unit, file=script_path, status="replace", action="write", iostat=stat)
        if (stat == 0) then
            write(unit, '(a)', iostat=stat) script(base_name(csv_path, ".csv"), prefix, &
                & data_path, names(column_residual:))
            close(unit)
        end if
        if (stat /= 0) then
            call fatal_error(error, script_path // ": cannot write the gnuplot script", stat_io)
            return
        end if
        call run_gnuplot(script_path, error)
        do i = 1, size(figure_names)
            if (allocated(error)) exit
            inquire(file=figure_file(csv_path, output_dir, figure_names(i)), size=size_bytes)
            if (size_bytes <= 0) then
                call fatal_error(error, figure_file(csv_path, output_dir, figure_names(i)) &
                    & // ": gnuplot reported success but " &
                    & // "did not write this PNG file (see " // script_path // ")", stat_io)
            end if
        end do
        if (allocated(error)) then
            ! No figure of a failed set is left behind (gnuplot may have opened them all).
            do i = 1, size(figure_names)
                call remove_file(figure_file(csv_path, output_dir, figure_names(i)))
            end do
            return
        end if
        call remove_file(script_path)
        call remove_file(data_path)
    end subroutine plot_output

    !> The PNG file of a figure: output_dir/<base>_<figure>.png, <base> the CSV's file name
    !> less '.csv'.
    pure function figure_file(csv_path, output_dir, figure) result(path)
        !> Output CSV
        character(len=*), intent(in) :: csv_path
        !> Folder of the figures
        character(len=*), intent(in) :: output_dir
        !> One of figure_names
        character(len=*), intent(in) :: figure
        character(len=:), allocatable :: path

        path = output_dir // "/" // base_name(csv_path, ".csv") // "_" // trim(figure) // ".png"
    end function figure_file

    !> The data the figures need, one row per output row: t, X, Y, contact x, y, theta, psidot,
    !> phidot, |E - E(t0)|/|E(t0)|, |E - E(t_end)|/|E(t_end)|, normal and tangential force,
    !> mu_needed, then |F_k| for each UCON.
    subroutine write_data(path, history, radius, error)
        character(len=*), intent(in) :: path
        type(history_type), intent(in) :: history
        real(wp), intent(in) :: radius
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: c(3), first_energy, last_energy
        real(wp), allocatable :: row(:)
        character(len=256) :: message
        integer :: unit, stat, j, n

        n = history%count
        first_energy = history%rows(column_energy, 1)
        last_energy = history%rows(column_energy, n)
        message = "a write failed"
        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the plot data: " // trim(message), &
                & stat_io)
            return
        end if
        do j = 1, n
            if (stat /= 0) exit
            associate (r => history%rows(:, j))
                c = contact_point(radius, r(column_x:column_phi))
                row = [r(column_time), r(column_x), r(column_y), c(1:2), r(column_theta), &
                    & r(column_psidot), r(column_phidot), drift(r(column_energy), first_energy), &
                    & drift(r(column_energy), last_energy), r(column_fz), &
                    & norm2(r(column_fx:column_fy)), r(column_mu), &
                    & max(abs(r(column_residual:)), residual_floor)]
            end associate
            write(unit, '(*(es24.16e3, :, 1x))', iostat=stat) row
        end do
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the plot data: " &
            & // trim(message), stat_io)
    end subroutine write_data

    !> Relative change of the energy from a reference, at least drift_floor.
    pure function drift(energy, reference) result(relative)
        real(wp), intent(in) :: energy, reference
        real(wp) :: relative

        relative = drift_floor
        if (reference /= 0.0_wp) relative = max(abs(energy - reference)/abs(reference), &
            & drift_floor)
    end function drift

    !> The gnuplot script drawing every figure from the data file.
    function script(name, prefix, data_path, residual_names) result(text)
        character(len=*), intent(in) :: name, prefix, data_path
        !> Header names of the residual columns
        character(len=*), intent(in) :: residual_names(:)
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        character(len=:), allocatable :: data, residuals
        integer :: k

        data = gnuplot_string(data_path)
        text = "# Figures of " // name // ", written by rollcon plot." // nl &
            & // "set terminal pngcairo size 800,500 font 'DejaVu Sans,10' noenhanced" // nl &
            & // "set grid" // nl // "set key tmargin center horizontal" // nl &
            & // "set xlabel 't [s]'" // nl
        text = text // output(prefix, "path") &
            & // title(name // ": paths on the ground (equal axes)") &
            & // "set xlabel 'X [m]'" // nl // "set ylabel 'Y [m]'" // nl &
            & // "set size ratio -1" // nl &
            & // "plot " // data // " using 4:5 with lines lw 1.5 title 'contact point', " &
            & // data // " using 2:3 with lines lw 1.5 title 'centre'" // nl &
            & // "set size noratio" // nl // "set xlabel 't [s]'" // nl
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
        do k = 1, size(residual_names)
            if (k > 1) residuals = residuals // ", "
            residuals = residuals // data // " using 1:" // to_text(data_columns + k) &
                & // " with lines lw 1.2 title " // gnuplot_string("|" // trim(residual_names(k)) &
                & // "|")
        end do
        if (size(residual_names) == 0) residuals = "NaN title 'no constraint'"
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
            & // "set ylabel 'μ needed'" // nl &
            & // "plot " // data // " using 1:13 with lines lw 1.5 title 'μ needed'" // nl &
            & // "unset output" // nl
    end function script

    !> The line that sets a figure's title.
    function title(text) result(line)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: line

        line = "set title " // gnuplot_string(text) // new_line("a")
    end function title

    !> The line that starts a figure's file.
    function output(prefix, figure) result(line)
        character(len=*), intent(in) :: prefix, figure
        character(len=:), allocatable :: line

        line = "set output " // gnuplot_string(prefix // "_" // figure // ".png") &
            & // new_line("a")
    end function output

end module rollcon_figures
