! SPDX-License-Identifier: MIT
!> The map of a parameter study (docs/studies.md) as a PNG drawn by gnuplot: each case of the
!> study's CSV at its two map parameters in the colour of its class (a filled cell of the grid,
!> or a dot for random samples), and the analytic critical speed of upright rolling
!> (docs/design.md §5) over them when &map asks for it.
module rollcon_study_map
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_io, stat_input
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene_lines, scene_override_type
    use rollcon_scene_state, only : upright_critical_speed
    use rollcon_study_type, only : study_type, study_parameter_type, sampling_grid
    use rollcon_study_measures, only : outcome_words, outcome_failed, outcome_refused
    use rollcon_study_map_cases, only : map_cases_type, map_classes, read_map_cases
    use rollcon_gnuplot, only : require_gnuplot, run_gnuplot, gnuplot_string, remove_file, &
        & require_written
    implicit none
    private

    public :: draw_study_map, map_script_path, critical_speed_curve

    !> Points of the critical speed curve across the range of the x parameter
    integer, parameter, public :: curve_points = 200
    !> Title of the critical speed curve in the key
    character(len=*), parameter, public :: curve_title = &
        & "analytic critical speed v_c of straight rolling"
    !> Colours of the rules' classes in rule order (again from the first past the last), of
    !> the class of cases no rule fits, of failed and of refused cases
    character(len=*), parameter :: rule_colours(7) = [character(len=7) :: "#d62728", &
        & "#ff7f0e", "#1f77b4", "#9467bd", "#8c564b", "#e377c2", "#17becf"]
    character(len=*), parameter :: otherwise_colour = "#2ca02c", failed_colour = "#202020", &
        & refused_colour = "#a0a0a0"
    !> Filled point shapes of the classes of random samples (circle, square, triangles,
    !> diamond, pentagon), again from the first past the last
    integer, parameter :: point_types(6) = [7, 5, 9, 11, 13, 15]
    !> Margin around the range of random samples, a fraction of the range
    real(wp), parameter :: sample_margin = 0.02_wp
    !> Format of the numbers in the script's data: 17 digits read back as the values written
    character(len=*), parameter :: number_format = '(es24.16e3, 1x, es24.16e3)'
    character(len=*), parameter :: nl = new_line("a")

contains

    !> Draw the map of a study from its CSV as a PNG. The gnuplot script is written beside
    !> it (map_script_path) and kept: it holds the cases and the curve as inline data, so the
    !> map can be restyled without the study. A study with fewer than two parameters has no
    !> map: an error.
    subroutine draw_study_map(study, csv_path, png_path, error)
        !> The study, as read_study gives it
        type(study_type), intent(in) :: study
        !> The study's CSV
        character(len=*), intent(in) :: csv_path
        !> PNG file to write
        character(len=*), intent(in) :: png_path
        type(error_type), allocatable, intent(out) :: error
        type(map_cases_type) :: cases
        character(len=:), allocatable :: classes(:), script
        real(wp), allocatable :: curve_x(:), curve_speed(:)
        
        if (min(study%map%x, study%map%y) < 1 .or. study%map%x == study%map%y &
            & .or. max(study%map%x, study%map%y) > parameter_count(study)) then
            call fatal_error(error, name_of(study%path) // ": no map: a map needs two " &
                & // "parameters on its axes; the study varies " &
                & // to_text(parameter_count(study)), stat_input)
            return
        end if
        classes = map_classes(study)
        call read_map_cases(study, csv_path, classes, cases, error)
        if (allocated(error)) return
        call require_gnuplot(error)
        if (allocated(error)) return
        allocate(curve_x(0), curve_speed(0))
        if (text_of(study%map%curve) == "critical_speed") then
            call critical_speed_curve(study, curve_x, curve_speed, error)
            if (allocated(error)) return
        end if
        script = map_script_path(png_path)
        call remove_file(png_path)
        call write_map_script(script, study, png_path, classes, cases, curve_x, curve_speed, &
            & error)
        if (allocated(error)) return
        call run_gnuplot(script, error)
        if (allocated(error)) return
        call require_written(png_path, script, error)
    end subroutine draw_study_map

    !> The gnuplot script of a map: the PNG's path with .gp for .png (or .gp added).
    pure function map_script_path(png_path) result(path)
        !> PNG file of the map
        character(len=*), intent(in) :: png_path
        character(len=:), allocatable :: path
        integer :: n

        n = len(png_path) - len(".png")
        path = png_path // ".gp"
        if (n > 0) then
            if (png_path(n + 1:) == ".png") path = png_path(:n) // ".gp"
        end if
    end function map_script_path

    !> The analytic critical speed of upright rolling (docs/design.md §5) across the range of
    !> the map's x parameter: the base scene read with that parameter set, at curve_points
    !> evenly spaced values (each whole number once, for a whole-number parameter).
    subroutine critical_speed_curve(study, x, speed, error)
        !> The study, with x of its map set
        type(study_type), intent(in) :: study
        !> Values of the x parameter, in its unit, and the critical speed at each [m/s]
        real(wp), allocatable, intent(out) :: x(:), speed(:)
        type(error_type), allocatable, intent(out) :: error
        type(scene_override_type) :: override(1)
        type(scene_type) :: scene
        integer :: i, n

        associate (p => study%parameters(study%map%x))
            n = curve_points
            if (p%whole) n = min(n, nint(p%upper - p%lower) + 1)
            if (p%upper == p%lower) n = 1
            allocate(x(n), speed(n))
            do i = 1, n
                x(i) = p%upper
                if (i < n) x(i) = p%lower + (p%upper - p%lower)*real(i - 1, wp)/real(n - 1, wp)
                if (p%whole) x(i) = anint(x(i))
            end do
            override(1)%group = p%group
            override(1)%key = p%key
            do i = 1, n
                override(1)%value = to_text(x(i))
                call read_scene_lines(study%scene_path, study%scene_lines, scene, error, override)
                if (allocated(error)) then
                    error%message = name_of(study%path) // ": the critical speed curve at " &
                        & // p%group // "%" // p%key // " = " // override(1)%value // ": " &
                        & // error%message
                    return
                end if
                speed(i) = upright_critical_speed(scene)
                if (.not. ieee_is_finite(speed(i))) then
                    call fatal_error(error, name_of(study%path) // ": the critical speed at " &
                        & // p%group // "%" // p%key // " = " // override(1)%value &
                        & // " is not a finite number", stat_input)
                    return
                end if
            end do
        end associate
    end subroutine critical_speed_curve

    !> Write the script: the settings, each class's cases and the curve as inline data
    !> ($class_k and $curve), the plot.
    subroutine write_map_script(path, study, png_path, classes, cases, curve_x, curve_speed, &
            & error)
        character(len=*), intent(in) :: path, png_path, classes(:)
        type(study_type), intent(in) :: study
        type(map_cases_type), intent(in) :: cases
        real(wp), intent(in) :: curve_x(:), curve_speed(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: message
        integer :: unit, stat, k, i

        message = "a write failed"
        open(newunit=unit, file=path, status="replace", action="write", form="formatted", &
            & iostat=stat, iomsg=message)
        if (stat /= 0) then
            call fatal_error(error, path // ": cannot write the map's gnuplot script: " &
                & // trim(message), stat_io)
            return
        end if
        write(unit, '(a)', iostat=stat, iomsg=message) map_settings(study, png_path, cases)
        do k = 1, size(classes)
            if (stat /= 0 .or. .not. any(cases%class == k)) cycle
            write(unit, '(a)', iostat=stat, iomsg=message) "$class_" // to_text(k) // " << EOD"
            do i = 1, size(cases%class)
                if (stat /= 0) exit
                if (cases%class(i) == k) write(unit, number_format, iostat=stat, &
                    & iomsg=message) cases%x(i), cases%y(i)
            end do
            if (stat == 0) write(unit, '(a)', iostat=stat, iomsg=message) "EOD"
        end do
        if (size(curve_x) > 0 .and. stat == 0) then
            write(unit, '(a)', iostat=stat, iomsg=message) "$curve << EOD"
            do i = 1, size(curve_x)
                if (stat == 0) write(unit, number_format, iostat=stat, iomsg=message) &
                    & curve_x(i), curve_speed(i)
            end do
            if (stat == 0) write(unit, '(a)', iostat=stat, iomsg=message) "EOD"
        end if
        if (stat == 0) write(unit, '(a)', iostat=stat, iomsg=message) &
            & map_plot(study, classes, cases, size(curve_x) > 0) // nl // "unset output"
        close(unit)
        if (stat /= 0) call fatal_error(error, path // ": cannot write the map's gnuplot " &
            & // "script: " // trim(message), stat_io)
    end subroutine write_map_script

    !> The settings of the map: terminal, output, title, axes and their ranges, the key.
    pure function map_settings(study, png_path, cases) result(text)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: png_path
        type(map_cases_type), intent(in) :: cases
        character(len=:), allocatable :: text, grid
        real(wp) :: x_range(2), y_range(2)

        ! white lines over the cells of a grid; grey ones behind random points
        grid = "set grid back lc rgb '#d0d0d0' lw 0.5"
        if (half_cell(study, study%map%x) > 0.0_wp .and. half_cell(study, study%map%y) &
            & > 0.0_wp) grid = "set grid front lc rgb '#ffffff' lw 0.5"
        x_range = axis_range(study, study%map%x, cases%x)
        y_range = axis_range(study, study%map%y, cases%y)
        text = "# Map of the study " // name_of(study%path) // ", drawn by rollcon from its " &
            & // "CSV; the cases of each class and the curve are inline data." // nl &
            & // "set terminal pngcairo size 900,640 font 'DejaVu Sans,10' noenhanced" // nl &
            & // "set output " // gnuplot_string(png_path) // nl &
            & // "set title " // gnuplot_string(title_of(study)) // nl &
            & // "set xlabel " // gnuplot_string(axis_label(study%parameters(study%map%x))) &
            & // nl // "set ylabel " &
            & // gnuplot_string(axis_label(study%parameters(study%map%y))) // nl &
            & // "set xrange [" // to_text(x_range(1)) // ":" // to_text(x_range(2)) // "]" &
            & // nl // "set yrange [" // to_text(y_range(1)) // ":" // to_text(y_range(2)) &
            & // "]" // nl // "set format x '% g'" // nl // "set format y '% g'" // nl &
            & // "set tics out" // nl // grid // nl &
            & // "set key tmargin center horizontal Left reverse samplen 2" // nl
    end function map_settings

    !> The plot command: one element per class that occurs (filled cells of the grid's
    !> spacing, or filled points for random samples), titled with its name (legend_words) and
    !> count, then the curve.
    pure function map_plot(study, classes, cases, curve) result(text)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: classes(:)
        type(map_cases_type), intent(in) :: cases
        !> The script has the critical speed curve
        logical, intent(in) :: curve
        character(len=:), allocatable :: text, style, colour
        real(wp) :: half_x, half_y
        integer :: k, n

        half_x = half_cell(study, study%map%x)
        half_y = half_cell(study, study%map%y)
        text = "plot "
        n = 0
        do k = 1, size(classes)
            if (.not. any(cases%class == k)) cycle
            colour = "rgb '" // class_colour(study, classes, k) // "'"
            if (half_x > 0.0_wp .and. half_y > 0.0_wp) then
                ! a border of the cell's colour closes the seams between neighbouring cells
                style = "using 1:2:(" // to_text(half_x) // "):(" // to_text(half_y) &
                    & // ") with boxxyerror lc " // colour // " fill solid 1.0 border lc " &
                    & // colour
            else
                style = "using 1:2 with points pt " &
                    & // to_text(point_types(modulo(n, size(point_types)) + 1)) // " ps " &
                    & // to_text(point_size(size(cases%class))) // " lc " // colour
            end if
            if (n > 0) text = text // ", \" // nl // "    "
            text = text // "$class_" // to_text(k) // " " // style // " title " &
                & // gnuplot_string(legend_words(trim(classes(k))) // " (" &
                & // to_text(count(cases%class == k)) // ")")
            n = n + 1
        end do
        if (curve) text = text // ", \" // nl // "    $curve using 1:2 with lines lw 2.5 " &
            & // "lc rgb '#000000' title " // gnuplot_string(curve_title)
    end function map_plot

    !> A class's name as the key writes it: its underscores as blanks (a rule's class is a
    !> namelist key, which holds none: `slides_then_rolls` reads "slides then rolls").
    pure function legend_words(class) result(words)
        character(len=*), intent(in) :: class
        character(len=len(class)) :: words
        integer :: i

        words = class
        do i = 1, len(words)
            if (words(i:i) == "_") words(i:i) = " "
        end do
    end function legend_words

    !> Half the grid spacing of parameter k, 0 when its cases are not on a grid of at
    !> least two points.
    pure real(wp) function half_cell(study, k)
        type(study_type), intent(in) :: study
        integer, intent(in) :: k

        half_cell = 0.0_wp
        associate (p => study%parameters(k))
            if (study%sampling == sampling_grid .and. p%count > 1) &
                & half_cell = 0.5_wp*(p%upper - p%lower)/real(p%count - 1, wp)
        end associate
    end function half_cell

    !> The range of an axis: the parameter's range with half a cell (grid) or a margin
    !> (random samples) either side, widened to hold every case.
    pure function axis_range(study, k, values) result(range)
        type(study_type), intent(in) :: study
        integer, intent(in) :: k
        real(wp), intent(in) :: values(:)
        real(wp) :: range(2), pad

        associate (p => study%parameters(k))
            range = [min(p%lower, minval(values)), max(p%upper, maxval(values))]
            pad = half_cell(study, k)
            if (pad == 0.0_wp) pad = sample_margin*(range(2) - range(1))
            if (pad == 0.0_wp) pad = max(0.5_wp*abs(range(1)), 0.5_wp)
            range = range + [-pad, pad]
        end associate
    end function axis_range

    !> Size of the points of random samples: smaller as they get more, within [0.3, 1.5].
    pure real(wp) function point_size(n)
        integer, intent(in) :: n

        point_size = min(1.5_wp, max(0.3_wp, 12.0_wp/sqrt(real(max(n, 1), wp))))
    end function point_size

    !> The colour of class k: failed, refused, the class no rule fits, or a rule's class by
    !> its place among them.
    pure function class_colour(study, classes, k) result(colour)
        type(study_type), intent(in) :: study
        character(len=*), intent(in) :: classes(:)
        integer, intent(in) :: k
        character(len=7) :: colour

        if (classes(k) == outcome_words(outcome_failed)) then
            colour = failed_colour
        else if (classes(k) == outcome_words(outcome_refused)) then
            colour = refused_colour
        else if (classes(k) == text_of(study%otherwise)) then
            colour = otherwise_colour
        else
            colour = rule_colours(modulo(k - 1, size(rule_colours)) + 1)
        end if
    end function class_colour

    !> The label of a parameter's axis: group%key [unit].
    pure function axis_label(parameter) result(label)
        type(study_parameter_type), intent(in) :: parameter
        character(len=:), allocatable :: label

        label = parameter%group // "%" // parameter%key
        if (len(text_of(parameter%unit)) > 0) label = label // " [" // parameter%unit // "]"
    end function axis_label

    !> The map's title: the study's title, else its name.
    pure function title_of(study) result(title)
        type(study_type), intent(in) :: study
        character(len=:), allocatable :: title

        title = text_of(study%title)
        if (len(title) == 0) title = text_of(study%name)
    end function title_of

    pure integer function parameter_count(study)
        type(study_type), intent(in) :: study

        parameter_count = 0
        if (allocated(study%parameters)) parameter_count = size(study%parameters)
    end function parameter_count

    !> The study file's path for a message ("study" when it has none).
    pure function name_of(path) result(name)
        character(len=:), allocatable, intent(in) :: path
        character(len=:), allocatable :: name

        name = "study"
        if (allocated(path)) name = path
    end function name_of

    !> A text component's value, "" when it is not allocated.
    pure function text_of(text) result(value)
        character(len=:), allocatable, intent(in) :: text
        character(len=:), allocatable :: value

        value = ""
        if (allocated(text)) value = text
    end function text_of

end module rollcon_study_map
