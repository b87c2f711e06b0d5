! SPDX-License-Identifier: MIT
!> What the figure scripts share: the floors of their log axes, the energy drift they draw, and
!> the gnuplot lines that start a figure.
module rollcon_figure_text
    use rollcon_kinds, only : wp
    use rollcon_gnuplot, only : gnuplot_string
    implicit none
    private

    public :: drift, title, output, figure_preamble

    !> Relative energy drifts below round-off are drawn at this level (a log axis has no zero)
    real(wp), parameter, public :: drift_floor = epsilon(1.0_wp)
    !> Constraint residuals below this are drawn at it, in each UCON's unit (a log axis has no
    !> zero)
    real(wp), parameter, public :: residual_floor = 1.0e-20_wp

contains

    !> Relative change of the energy from a reference, at least drift_floor.
    pure function drift(energy, reference) result(relative)
        !> Energy and reference energy [J]
        real(wp), intent(in) :: energy, reference
        real(wp) :: relative

        relative = drift_floor
        if (reference /= 0.0_wp) relative = max(abs(energy - reference)/abs(reference), &
            & drift_floor)
    end function drift

    !> The first lines of a figure script: a comment naming the run, the PNG terminal, a grid,
    !> the key above the plot and t on the x axis.
    pure function figure_preamble(name) result(text)
        !> The run's name
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")

        text = "# Figures of " // name // ", written by rollcon plot." // nl &
            & // "set terminal pngcairo size 800,500 font 'DejaVu Sans,10' noenhanced" // nl &
            & // "set grid" // nl // "set key tmargin center horizontal" // nl &
            & // "set xlabel 't [s]'" // nl
    end function figure_preamble

    !> The line that sets a figure's title.
    pure function title(text) result(line)
        !> The title
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: line

        line = "set title " // gnuplot_string(text) // new_line("a")
    end function title

    !> The line that starts a figure's file: prefix_figure.png.
    pure function output(prefix, figure) result(line)
        !> Path of the figures less _<figure>.png, and the figure's name
        character(len=*), intent(in) :: prefix, figure
        character(len=:), allocatable :: line

        line = "set output " // gnuplot_string(prefix // "_" // figure // ".png") &
            & // new_line("a")
    end function output

end module rollcon_figure_text
