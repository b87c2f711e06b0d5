! SPDX-License-Identifier: MIT
!> The figure of a disk settling to its finite-time singularity (a run with a rim's
!> dissipation, its `dissipated` column among its rows: rollcon_dissipation_watch): the
!> precession rate Omega = |psidot| against t0 - t on logarithmic axes, t0 fitted as the
!> summary fits it (fit_singularity), with the fitted line Omega ~ (t0 - t)^(-n).
module rollcon_singularity_figure
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : coord_psidot
    use rollcon_run_record, only : run_record_type
    use rollcon_figure_text, only : title, output
    use rollcon_gnuplot, only : gnuplot_string
    use rollcon_output_files, only : close_checked
    use rollcon_dissipation_watch, only : fit_singularity, singularity_fit_type
    implicit none
    private

    public :: has_singularity, write_singularity_data, singularity_script

    !> The figure, written as DIR/<base>_<name>.png
    character(len=*), parameter, public :: singularity_figure_name = "singularity"

contains

    !> The run's rows have a rim's dissipation and its rates a fit of a singularity the run
    !> ends at (singularity_fit_type%settles).
    pure function has_singularity(run) result(has)
        type(run_record_type), intent(in) :: run
        logical :: has
        type(singularity_fit_type) :: fit

        has = .false.
        if (run%layout%column("dissipated") == 0) return
        fit = rows_fit(run)
        has = fit%made .and. fit%settles
    end function has_singularity

    !> The fit of the run's rows (t, |psidot| of its first part).
    pure function rows_fit(run) result(fit)
        type(run_record_type), intent(in) :: run
        type(singularity_fit_type) :: fit

        associate (rows => run%history%rows(:, :run%history%count))
            fit = fit_singularity(rows(1, :), abs(rows(run%layout%part_column(1, &
                & coord_psidot), :)))
        end associate
    end function rows_fit

    !> The data: t0 - t and Omega for every row before t0 with Omega > 0 (t0 fitted).
    subroutine write_singularity_data(path, run, error)
        character(len=*), intent(in) :: path
        type(run_record_type), intent(in) :: run
        type(error_type), allocatable, intent(out) :: error
        type(singularity_fit_type) :: fit
        character(len=256) :: message
        integer :: unit, stat, j

        fit = rows_fit(run)
        message = "a write failed"
        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="formatted", iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the plot data: " // trim(message), &
                & stat_io)
            return
        end if
        associate (rows => run%history%rows)
            do j = 1, run%history%count
                associate (t => rows(1, j), rate => abs(rows(run%layout%part_column(1, &
                        & coord_psidot), j)))
                    if (fit%t0 - t > 0.0_wp .and. rate > 0.0_wp .and. stat == 0) &
                        & write(unit, '(es24.16e3, 1x, es24.16e3)', iostat=stat) fit%t0 - t, rate
                end associate
            end do
        end associate
        call close_checked(unit, path, error)
        if (allocated(error)) return
        if (stat /= 0) call fatal_error(error, path // ": cannot write the plot data", stat_io)
    end subroutine write_singularity_data

    !> The gnuplot lines drawing the figure from the data file (after the run's other
    !> figures, whose preamble it shares), with the fitted line C (t0 - t)^(-n).
    pure function singularity_script(name, prefix, data_path, run) result(text)
        character(len=*), intent(in) :: name, prefix, data_path
        type(run_record_type), intent(in) :: run
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        type(singularity_fit_type) :: fit
        character(len=:), allocatable :: data

        fit = rows_fit(run)
        data = gnuplot_string(data_path)
        text = output(prefix, singularity_figure_name) &
            & // title(name // ": precession rate against the time left, t0 = " &
            & // to_text(real(nint(fit%t0*1.0e4_wp), wp)/1.0e4_wp) // " s fitted") &
            & // "set xlabel 't0 - t [s]'" // nl // "set ylabel 'Ω = |dψ/dt| [rad/s]'" // nl &
            & // "set logscale xy" // nl // "set format x '%g'" // nl &
            & // "set format y '%g'" // nl // "set key top right" // nl &
            & // "plot " // data // " using 1:2 with lines lw 1.5 title 'Ω (the run)', " &
            & // to_text(fit%prefactor) // "*x**(-" // to_text(fit%exponent) // ") with lines " &
            & // "dashtype 2 lw 1.2 title " // gnuplot_string("fit: (t0 - t)^(-" &
            & // to_text(real(nint(fit%exponent*1.0e4_wp), wp)/1.0e4_wp) // ")") // nl &
            & // "unset logscale xy" // nl // "unset output" // nl
    end function singularity_script

end module rollcon_singularity_figure
