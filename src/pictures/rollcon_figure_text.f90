! SPDX-License-Identifier: MIT
!> What the figure scripts share: the floors of their log axes, the energy drift they draw, the
!> gnuplot lines that start a figure, and the least span of a path's equal axes.
module rollcon_figure_text
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_gnuplot, only : gnuplot_string
    implicit none
    private

    public :: drift, title, output, figure_preamble, path_axis_ranges

    !> Relative energy drifts below round-off are drawn at this level (a log axis has no zero)
    real(wp), parameter, public :: drift_floor = epsilon(1.0_wp)
    !> Constraint residuals below this are drawn at it, in each UCON's unit (a log axis has no
    !> zero)
    real(wp), parameter, public :: residual_floor = 1.0e-20_wp
    !> The least span of either axis of a path's figure, as a fraction of the other axis's
    !> span: a straight path is drawn as a straight line, not as its round-off magnified
    real(wp), parameter, public :: path_span_fraction = 0.1_wp

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

    !> The gnuplot lines that give a path's figure (equal axes) a span of at least `least` on
    !> each axis: least = max(path_span_fraction times the larger span, 2 extent), centred on
    !> the points; an axis already that wide is left to autoscale (no line). A path along X has
    !> a Y spread of round-off (1e-16 m), which gnuplot's autoscale would magnify into a
    !> zigzag with overlapping tick labels; with the part's size as a floor, a part that does
    !> not move is drawn at its own scale.
    pure function path_axis_ranges(x, y, extent) result(text)
        !> The X and Y of every point the figure draws [m]
        real(wp), intent(in) :: x(:), y(:)
        !> Half the size of the largest part drawn [m] (>= 0)
        real(wp), intent(in) :: extent
        character(len=:), allocatable :: text
        real(wp) :: least

        text = ""
        if (size(x) == 0 .or. size(y) == 0) return
        least = max(path_span_fraction*max(maxval(x) - minval(x), maxval(y) - minval(y)), &
            & 2.0_wp*extent)
        if (least <= 0.0_wp) least = 1.0_wp
        text = text // axis_line("x", x) // axis_line("y", y)
    contains
        !> "set xrange [low:high]" when the axis spans less than least, else nothing.
        pure function axis_line(axis, values) result(line)
            character(len=*), intent(in) :: axis
            real(wp), intent(in) :: values(:)
            character(len=:), allocatable :: line
            real(wp) :: middle

            line = ""
            if (maxval(values) - minval(values) >= least) return
            middle = 0.5_wp*(maxval(values) + minval(values))
            line = "set " // axis // "range [" // to_text(middle - 0.5_wp*least) // ":" &
                & // to_text(middle + 0.5_wp*least) // "]" // new_line("a")
        end function axis_line
    end function path_axis_ranges

end module rollcon_figure_text
