! SPDX-License-Identifier: MIT
!> The contact point's path coloured by the contact's mode (suite mode-path): a run whose rows
!> carry the `mode` column (Coulomb friction) has its path split by that column into one line
!> per mode, each stretch joined to the next, and its switches marked, and the animation's path
!> takes each point's mode's colour; a run without it keeps the one line of the contact point.
!> A sphere's CONTACT (a dataset's, its part an ellipsoid: the model figures) gets its part's
!> path coloured the same way; a straight path's axes span at least the part's size; the
!> friction figure draws the contact's mu_static and mu_kinetic, read from the summary. A
!> dataset's two CONTACTs (columns contact1_..., contact2_...) each colour their own part's path
!> by their own mode, and the friction figure draws each one's mu_needed and coefficients.
module test_mode_path
    use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : new_output_layout, coord_x, name_length
    use rollcon_watch_columns, only : contact_names, contact_mode_names
    use rollcon_run_record, only : run_record_type, read_friction, contact_part
    use rollcon_contact_figures, only : mode_path, mode_switches, write_contact_data, &
        & contact_script, mode_colour_values
    use rollcon_figures, only : write_model_data, model_script, plot_output, &
        & drawn_contact_type, drawn_contacts
    use rollcon_part_shapes, only : shape_ellipsoid
    use rollcon_gif, only : animate_output
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_figure_text, only : residual_floor, path_axis_ranges
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use command_runs, only : count_of
    use picture_files, only : disk_run, make_folder, remove_folder, run_rows, write_run, &
        & write_lines, disk_radius
    implicit none
    private

    public :: collect_mode_path

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_mode_path"
    !> Columns of the figures' data before those of the modes: 13, one per UCON (3), the
    !> height residual (rollcon_contact_figures)
    integer, parameter :: before_modes = 13 + 3 + 1
    !> The sphere run's radius [m], speed along X [m/s] and rows sliding (the rest rolling)
    real(wp), parameter :: sphere_radius = 0.05_wp, sphere_speed = 0.5_wp
    integer, parameter :: sliding_rows = 10
    !> Columns of the model figures' data before those of the modes: t, 6 of the part, 2
    !> drifts, 3 residuals, 3 multipliers (rollcon_figures' write_model_data)
    integer, parameter :: model_before_modes = 1 + 6 + 2 + 3 + 3

contains

    subroutine collect_mode_path(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("split-follows-mode-column", test_split), &
            & new_unittest("figure-data-by-mode", test_data), &
            & new_unittest("script-lines-by-mode", test_script), &
            & new_unittest("animation-path-by-mode", test_animation), &
            & new_unittest("sphere-contact-path-by-mode", test_sphere_path), &
            & new_unittest("straight-path-least-span", test_straight_path), &
            & new_unittest("friction-lines-from-summary", test_friction_lines), &
            & new_unittest("every-contact-path-and-friction", test_two_contacts)]
    end subroutine collect_mode_path

    !> Modes 0 0 1 1 1 0 2 2 0 over values 1 to 9: each mode's line holds its own rows and the
    !> row after each of its stretches (where the next mode's line starts), and nothing else;
    !> the switches are the rows whose mode differs from the row before's.
    subroutine test_split(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: modes(9) = [0, 0, 1, 1, 1, 0, 2, 2, 0]
        real(wp), parameter :: values(9) = [1, 2, 3, 4, 5, 6, 7, 8, 9]
        logical, parameter :: rolling(9) = [.true., .true., .true., .false., .false., .true., &
            & .true., .false., .true.]
        logical, parameter :: sliding(9) = [.false., .false., .true., .true., .true., .true., &
            & .false., .false., .false.]
        logical, parameter :: flight(9) = [.false., .false., .false., .false., .false., &
            & .false., .true., .true., .true.]
        logical, parameter :: switches(9) = [.false., .false., .true., .false., .false., &
            & .true., .true., .false., .true.]

        call expect(mode_path(modes, values, 0), rolling, "rolling")
        if (allocated(error)) return
        call expect(mode_path(modes, values, 1), sliding, "sliding")
        if (allocated(error)) return
        call expect(mode_path(modes, values, 2), flight, "mode 2")
        if (allocated(error)) return
        call expect(mode_switches(modes, values), switches, "the switches")

    contains

        subroutine expect(drawn, drawn_rows, what)
            real(wp), intent(in) :: drawn(:)
            logical, intent(in) :: drawn_rows(:)
            character(len=*), intent(in) :: what
            integer :: j

            do j = 1, size(drawn)
                if (drawn_rows(j)) then
                    call check(error, drawn(j) == values(j), what // ": row " // to_text(j) &
                        & // " drawn at " // to_text(drawn(j)) // ", not its value " &
                        & // to_text(values(j)))
                else
                    call check(error, ieee_is_nan(drawn(j)), what // ": row " // to_text(j) &
                        & // " drawn (" // to_text(drawn(j)) // "), not in that mode's line")
                end if
                if (allocated(error)) return
            end do
        end subroutine expect

    end subroutine test_split

    !> The figures' data of the disk run with a mode column (rows 11 to 20 sliding, the rest
    !> rolling), read back: its rolling and sliding columns are the contact point's y exactly
    !> where the mode column puts them (and the row after a stretch), NaN elsewhere; the
    !> switches at rows 11 and 21; the height residual before them in its own column.
    subroutine test_data(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        real(wp) :: row(before_modes + 3)
        integer :: modes(run_rows), unit, j, stat
        character(len=:), allocatable :: path
        logical :: in_rolling, in_sliding, switched

        run = mode_run(modes)
        call make_folder(scratch)
        path = scratch // "/data.dat"
        call write_contact_data(path, run, error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        do j = 1, run_rows
            read(unit, *, iostat=stat) row
            call check(error, stat == 0, path // ": row " // to_text(j) // " does not hold " &
                & // to_text(size(row)) // " numbers")
            if (allocated(error)) exit
            in_rolling = modes(j) == 0
            in_sliding = modes(j) == 1
            switched = .false.
            if (j > 1) then
                in_rolling = in_rolling .or. modes(j - 1) == 0
                in_sliding = in_sliding .or. modes(j - 1) == 1
                switched = modes(j) /= modes(j - 1)
            end if
            call check(error, same(row(before_modes + 1), in_rolling) &
                & .and. same(row(before_modes + 2), in_sliding) &
                & .and. same(row(before_modes + 3), switched), "row " // to_text(j) &
                & // " (mode " // to_text(modes(j)) // "): rolling, sliding, switch columns " &
                & // to_text(row(before_modes + 1)) // ", " // to_text(row(before_modes + 2)) &
                & // ", " // to_text(row(before_modes + 3)) // ", contact y " // to_text(row(5)))
            if (allocated(error)) exit
            associate (height => run%history%rows(run%layout%column("height_residual"), j))
                call check(error, row(before_modes) == max(abs(height), residual_floor), &
                    & "row " // to_text(j) // ": the height residual's column holds " &
                    & // to_text(row(before_modes)) // ", not " // to_text(abs(height)))
            end associate
            if (allocated(error)) exit
        end do
        close(unit)
        call remove_folder(scratch)

    contains

        !> Drawn there (the contact point's y) or not (NaN)
        logical function same(value, drawn)
            real(wp), intent(in) :: value
            logical, intent(in) :: drawn

            if (drawn) then
                same = value == row(5)
            else
                same = ieee_is_nan(value)
            end if
        end function same

    end subroutine test_data

    !> The path's plot: without a mode column the contact point's one line as ever; with it a
    !> line per mode present, titled by the mode, from the columns after the height residual,
    !> and the switches as points.
    subroutine test_script(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        integer :: modes(run_rows)

        text = contact_script("disk", "out/disk", "out/disk.dat", disk_run())
        call check(error, index(text, "using 4:5 with lines lw 1.5 title 'contact point'") > 0 &
            & .and. index(text, "contact point, rolling") == 0, "the path of a run without " &
            & // "modes is not the contact point's one line")
        if (allocated(error)) return
        text = contact_script("disk", "out/disk", "out/disk.dat", mode_run(modes))
        call check(error, index(text, "using 4:" // to_text(before_modes + 1) &
            & // " with lines lw 2 lc rgb '#1f77b4' title 'contact point, rolling'") > 0 &
            & .and. index(text, "using 4:" // to_text(before_modes + 2) &
            & // " with lines lw 2 lc rgb '#d62728' title 'contact point, sliding'") > 0 &
            & .and. index(text, "using 4:" // to_text(before_modes + 3) &
            & // " with points") > 0 .and. index(text, "using 4:5 ") == 0, &
            & "the path's plot does not draw a line per mode: " &
            & // text(index(text, "paths on the ground"):))
    end subroutine test_script

    !> The animation's path: each point takes its mode's colour, the figure's (#1f77b4 rolling,
    !> #d62728 sliding) as gnuplot's rgb number, so equal modes give equal colours and a change
    !> of mode a change of colour; the GIF of a run with a mode column draws its path in those
    !> (lc rgb variable), one without it in one colour (skipped without gnuplot).
    subroutine test_animation(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: modes(5) = [0, 1, 1, 0, 2]
        integer :: colours(5), frames, modes_of_run(run_rows)
        character(len=:), allocatable :: script, plain

        colours = mode_colour_values(modes)
        call check(error, colours(1) == int(z'1f77b4') .and. colours(2) == int(z'd62728') &
            & .and. colours(3) == colours(2) .and. colours(4) == colours(1) &
            & .and. all(colours(5) /= colours(:4)), "the path's colours do not follow the " &
            & // "modes 0 1 1 0 2: " // to_text(colours(1)) // " " // to_text(colours(2)) &
            & // " " // to_text(colours(3)) // " " // to_text(colours(4)) // " " &
            & // to_text(colours(5)))
        if (allocated(error)) return
        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        call write_run(scratch // "/modes.csv", mode_run(modes_of_run), .true., error)
        if (.not. allocated(error)) call animate_output(scratch // "/modes.csv", scratch &
            & // "/modes.gif", frames, error, script)
        if (.not. allocated(error)) call write_run(scratch // "/plain.csv", disk_run(), .true., &
            & error)
        if (.not. allocated(error)) call animate_output(scratch // "/plain.csv", scratch &
            & // "/plain.gif", frames, error, plain)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, index(script, "using 1:2:3:4 with lines lw 2 lc rgb variable") > 0 &
            & .and. index(plain, "lc rgb variable") == 0 .and. index(plain, &
            & "using 1:2:3 with lines lw 2 lc rgb") > 0, "the GIF's path is not coloured by " &
            & // "mode with a mode column, in one colour without")
    end subroutine test_animation

    !> A sphere's CONTACT drawn by the model figures: the contact's part is found (the one
    !> part, its lowest point at the height residual), its path's data holds its Y in the
    !> sliding column on the sliding rows and the row after, in the rolling column from the
    !> switch on, NaN elsewhere, the switch at the first rolling row; the path plot draws a
    !> line per mode in the disk figures' colours with the legend's words, the switch as
    !> points, and not the part's one plain line; and gnuplot draws the set (skipped without
    !> it).
    subroutine test_sphere_path(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        real(wp) :: row(model_before_modes + 3)
        character(len=:), allocatable :: path, text
        character(len=:), allocatable :: files(:)
        integer :: unit, j, stat
        logical :: rolling, sliding, switched

        run = sphere_run()
        call check(error, contact_part(run) == 1, "the contact's part is " &
            & // to_text(contact_part(run)) // ", not the run's one part")
        if (allocated(error)) return
        call make_folder(scratch)
        path = scratch // "/model.dat"
        call write_model_data(path, run, error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        do j = 1, run_rows
            read(unit, *, iostat=stat) row
            call check(error, stat == 0, path // ": row " // to_text(j) // " does not hold " &
                & // to_text(size(row)) // " numbers")
            if (allocated(error)) exit
            sliding = j <= sliding_rows + 1
            rolling = j > sliding_rows
            switched = j == sliding_rows + 1
            call check(error, drawn(row(model_before_modes + 1), rolling) &
                & .and. drawn(row(model_before_modes + 2), sliding) &
                & .and. drawn(row(model_before_modes + 3), switched), "row " // to_text(j) &
                & // ": rolling, sliding, switch columns " &
                & // to_text(row(model_before_modes + 1)) // ", " &
                & // to_text(row(model_before_modes + 2)) // ", " &
                & // to_text(row(model_before_modes + 3)) // ", Y " // to_text(row(3)))
            if (allocated(error)) exit
        end do
        close(unit)
        if (allocated(error)) return
        text = model_script("sphere", "out/sphere", "out/sphere.dat", run)
        call check(error, index(text, "using 2:" // to_text(model_before_modes + 1) &
            & // " with lines lw 2 lc rgb '#1f77b4' title 'part 2 centre of mass, rolling'") &
            & > 0 .and. index(text, "using 2:" // to_text(model_before_modes + 2) &
            & // " with lines lw 2 lc rgb '#d62728' title 'part 2 centre of mass, sliding'") &
            & > 0 .and. index(text, "using 2:" // to_text(model_before_modes + 3) &
            & // " with points") > 0 .and. index(text, "using 2:3 ") == 0, &
            & "the sphere's path is not drawn a line per mode: " &
            & // text(:index(text, "set size noratio")))
        if (allocated(error)) return
        if (.not. gnuplot_available()) then
            call remove_folder(scratch)
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call write_run(scratch // "/sphere.csv", run, .true., error)
        if (.not. allocated(error)) call plot_output(scratch // "/sphere.csv", scratch, error, &
            & files)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, size(files) == 7, "the sphere run drew " // to_text(size(files)) &
            & // " figures, not the model's 6 and the friction figure")

    contains

        !> Drawn there (the part's Y) or not (NaN)
        logical function drawn(value, there)
            real(wp), intent(in) :: value
            logical, intent(in) :: there

            if (there) then
                drawn = value == row(3)
            else
                drawn = ieee_is_nan(value)
            end if
        end function drawn

    end subroutine test_sphere_path

    !> A path along X (1e-16 of round-off in Y, as a sliding coin's) gets a Y axis spanning
    !> the part's diameter, centred on the path, and keeps X's autoscaled; a circle far wider
    !> than its part gets neither axis set; the disk run's arc, narrower than the disk along
    !> Y, gets Y widened to the disk's diameter.
    subroutine test_straight_path(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        real(wp) :: low, high, angles(100)
        integer :: j
        character(len=:), allocatable :: text

        run = sphere_run()
        ! round-off in Y, as a run straight along X has
        do j = 1, run%history%count
            run%history%rows(run%layout%part_column(1, coord_x) + 1, j) = &
                & 1.0e-16_wp*real(modulo(j, 3) - 1, wp)
        end do
        angles = [(0.0628_wp*real(j, wp), j = 1, size(angles))]
        text = model_script("sphere", "out/sphere", "out/sphere.dat", run)
        call axis_range(text, "y", low, high)
        ! the X path spans 0.25 m: a tenth of it (0.025 m) is below the diameter, 0.1 m; the
        ! middle of the Y values is 0 to their round-off
        call check(error, abs(high - low - 2.0_wp*sphere_radius) <= 1.0e-15_wp &
            & .and. abs(high + low) <= 1.0e-15_wp .and. index(text, "set xrange") == 0, &
            & "the straight path's Y axis is [" // to_text(low) // ":" // to_text(high) &
            & // "], not the diameter about 0, or X is set: " &
            & // text(:index(text, "set size noratio")))
        if (allocated(error)) return
        call check(error, index(text, "set autoscale xy") > index(text, "set yrange"), &
            & "the figures after the path do not autoscale again")
        if (allocated(error)) return
        ! a circle of radius 1 m drawn for a part of 0.1 m: both axes wide enough, none set
        call check(error, len(path_axis_ranges(cos(angles), sin(angles), 0.1_wp)) == 0, &
            & "a circle of 1 m got an axis range: " // path_axis_ranges(cos(angles), &
            & sin(angles), 0.1_wp))
        if (allocated(error)) return
        ! the disk run's arc, 0.25 m along X and 0.14 m along Y, its contact point and centre
        ! both counted: Y is widened to the disk's diameter (0.2 m), X is not
        text = contact_script("disk", "out/disk", "out/disk.dat", disk_run())
        call axis_range(text, "y", low, high)
        call check(error, abs(high - low - 2.0_wp*disk_radius) <= 1.0e-12_wp .and. &
            & index(text, "set xrange") == 0, "the disk run's Y axis is [" // to_text(low) &
            & // ":" // to_text(high) // "], not the disk's diameter, or X is set: " &
            & // text(:index(text, "set size noratio")))
    end subroutine test_straight_path

    !> The friction figure: mu_static and mu_kinetic read from the run's summary line (the
    !> documented "contact: starts ... (mu_static 0.5, mu_kinetic 0.4)") and drawn as a
    !> dashed and a dotted line, one line when they are equal; none without friction (a
    !> summary without the line, or no summary); a summary whose mu_kinetic exceeds
    !> mu_static is not read.
    subroutine test_friction_lines(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: friction(2)
        logical :: found
        character(len=:), allocatable :: text

        call make_folder(scratch)
        call write_lines(scratch // "/run.summary.txt", [character(len=80) :: &
            & "status: completed", "contact: starts rolling (mu_static 0.5, mu_kinetic 0.4), " &
            & // "10 switches", "  time rolling 2.5 s, sliding 1.2 s"])
        call read_friction(scratch // "/run.csv", friction, found)
        call check(error, found .and. all(friction == [0.5_wp, 0.4_wp]), "the summary's " &
            & // "friction read as " // to_text(friction(1)) // ", " // to_text(friction(2)))
        if (allocated(error)) return
        call write_lines(scratch // "/bounce.summary.txt", [character(len=90) :: &
            & "contact: starts in flight (mu_static 0.3, mu_kinetic 0.3, restitution 0.5), " &
            & // "1 switch"])
        call read_friction(scratch // "/bounce.csv", friction, found)
        call check(error, found .and. all(friction == 0.3_wp), "the flight summary's " &
            & // "friction read as " // to_text(friction(1)) // ", " // to_text(friction(2)))
        if (allocated(error)) return
        call write_lines(scratch // "/plain.summary.txt", [character(len=40) :: &
            & "status: completed"])
        call read_friction(scratch // "/plain.csv", friction, found)
        call check(error, .not. found, "a summary without friction gave some")
        if (allocated(error)) return
        call write_lines(scratch // "/wrong.summary.txt", [character(len=80) :: &
            & "contact: starts rolling (mu_static 0.4, mu_kinetic 0.5), 1 switch"])
        call read_friction(scratch // "/wrong.csv", friction, found)
        call check(error, .not. found, "mu_kinetic above mu_static was read")
        if (allocated(error)) return
        call read_friction(scratch // "/none.csv", friction, found)
        call remove_folder(scratch)
        call check(error, .not. found, "no summary gave friction")
        if (allocated(error)) return
        text = contact_script("disk", "out/disk", "out/disk.dat", disk_run(), [0.5_wp, 0.4_wp])
        call check(error, index(text, ", 0.5 with lines dashtype 2") > 0 .and. index(text, &
            & ", 0.4 with lines dashtype 3") > 0 .and. index(text, "title 'μs = 0.5") > 0 &
            & .and. index(text, "title 'μk = 0.4") > 0 .and. index(text, "title 'μ needed'") &
            & < index(text, ", 0.5 with lines dashtype 2"), "the friction figure does not " &
            & // "draw μs and μk: " // text(index(text, "friction coefficient"):))
        if (allocated(error)) return
        text = contact_script("disk", "out/disk", "out/disk.dat", disk_run(), [0.3_wp, 0.3_wp])
        call check(error, index(text, "title 'μs = μk = 0.3'") > 0 .and. index(text, &
            & "dashtype 3") == 0, "equal μs and μk are not one line")
        if (allocated(error)) return
        text = contact_script("disk", "out/disk", "out/disk.dat", disk_run())
        call check(error, index(text, "dashtype 2 lw 1.5") == 0, "a run without friction " &
            & // "draws friction lines")
    end subroutine test_friction_lines

    !> Two balls (parts 2 and 3, r = sphere_radius, on the ground at Y = 0 and 0.5 m, sliding
    !> along X without spin at 0.5 and 1 m/s) under CONTACT/1 and CONTACT/2, whose columns are
    !> contact1_... and contact2_...: CONTACT/1 slides over rows 1 to 10 and rolls after,
    !> CONTACT/2 rolls over rows 1 to 5 and slides after, its slip 1 m/s and CONTACT/1's 0.5
    !> m/s. Each contact finds its own part, though both lie at the same height, by its slip:
    !> the part whose lowest point moves so; the model figures' data holds each part's Y in its
    !> own contact's mode columns (part 3's Y, 0.5, in CONTACT/2's sliding column from row 6
    !> on, NaN before), then each contact's mu_needed; the path draws a line per mode of each
    !> contact's part, the switches' marks one legend entry; the friction figure each
    !> contact's mu_needed and its mu_static and mu_kinetic, read from its summary line; and
    !> gnuplot draws the seven figures (skipped without it).
    subroutine test_two_contacts(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: speeds(2) = [0.5_wp, 1.0_wp], sides(2) = [0.0_wp, 0.5_wp], &
            & mus(2) = [0.3_wp, 0.2_wp]
        !> Columns of the data before the modes: t, 6 of each part, 2 drifts, 6 residuals, 6
        !> multipliers
        integer, parameter :: before = 1 + 12 + 2 + 6 + 6
        type(run_record_type) :: run
        type(drawn_contact_type), allocatable :: contacts(:)
        character(len=name_length), allocatable :: names(:)
        character(len=:), allocatable :: path, text, files(:)
        real(wp), allocatable :: row(:)
        real(wp) :: t, data(before + 8), friction(2)
        integer :: j, k, c, unit, stat, mode(2)
        logical :: found

        allocate(names(0))
        do c = 1, 2
            do k = 1, size(contact_names)
                names = [character(len=name_length) :: names, "contact" // to_text(c) // "_" &
                    & // trim(contact_names(k))]
            end do
            do k = 1, size(contact_mode_names)
                names = [character(len=name_length) :: names, "contact" // to_text(c) // "_" &
                    & // trim(contact_mode_names(k))]
            end do
        end do
        run%layout = new_output_layout([2, 3], [1, 2, 3, 4, 5, 6], names)
        allocate(run%shapes(2))
        do c = 1, 2
            run%shapes(c)%id = c + 1
            run%shapes(c)%kind = shape_ellipsoid
            run%shapes(c)%semi_axes = sphere_radius
        end do
        allocate(row(size(run%layout%header())))
        do j = 1, run_rows
            t = 0.01_wp*real(j - 1, wp)
            row = 0.0_wp
            row(1) = t
            mode = [merge(1, 0, j <= sliding_rows), merge(1, 0, j > 5)]
            do c = 1, 2
                associate (x => run%layout%part_column(c, coord_x), &
                        & prefix => "contact" // to_text(c) // "_")
                    row(x:x + 2) = [speeds(c)*t, sides(c), sphere_radius]
                    row(x + 4) = 2.0_wp*atan(1.0_wp)
                    row(x + 6) = speeds(c)
                    row(run%layout%column(prefix // "Fz")) = 9.81_wp
                    row(run%layout%column(prefix // "Fn")) = 9.81_wp
                    row(run%layout%column(prefix // "mode")) = real(mode(c), wp)
                    row(run%layout%column(prefix // "mu_needed")) = mus(c)*real(mode(c), wp)
                    row(run%layout%column(prefix // "slip_x")) = speeds(c)
                end associate
            end do
            row(run%layout%energy_column()) = 0.625_wp
            call run%history%add(row)
        end do
        contacts = drawn_contacts(run)
        call check(error, size(contacts) == 2, "contacts found: " // to_text(size(contacts)))
        if (allocated(error)) return
        call check(error, contacts(1)%id == 1 .and. contacts(2)%id == 2 .and. &
            & contacts(1)%part == 1 .and. contacts(2)%part == 2, "CONTACT/" &
            & // to_text(contacts(1)%id) // " holds part number " // to_text(contacts(1)%part) &
            & // ", CONTACT/" // to_text(contacts(2)%id) // " part number " &
            & // to_text(contacts(2)%part) // ", not 1 and 2 by their slips")
        if (allocated(error)) return
        call check(error, contacts(1)%first == before + 1 .and. contacts(2)%first == before + 4 &
            & .and. contacts(1)%mu_column == before + 7 .and. contacts(2)%mu_column &
            & == before + 8, "the contacts' data columns: " // to_text(contacts(1)%first) &
            & // ", " // to_text(contacts(2)%first) // ", " // to_text(contacts(1)%mu_column) &
            & // ", " // to_text(contacts(2)%mu_column))
        if (allocated(error)) return
        call make_folder(scratch)
        path = scratch // "/two.dat"
        call write_model_data(path, run, error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        do j = 1, run_rows
            read(unit, *, iostat=stat) data
            call check(error, stat == 0, path // ": row " // to_text(j) // " does not hold " &
                & // to_text(size(data)) // " numbers")
            if (allocated(error)) exit
            ! CONTACT/1's sliding column: part 2's Y (0) on its sliding rows and the row after;
            ! CONTACT/2's: part 3's (0.5) from row 6 on; their mu_needed
            call check(error, same(data(before + 2), 0.0_wp, j <= sliding_rows + 1) &
                & .and. same(data(before + 5), 0.5_wp, j > 5) &
                & .and. same(data(before + 4), 0.5_wp, j <= 6) &
                & .and. data(before + 7) == mus(1)*merge(1.0_wp, 0.0_wp, j <= sliding_rows) &
                & .and. data(before + 8) == mus(2)*merge(1.0_wp, 0.0_wp, j > 5), "row " &
                & // to_text(j) // ": columns " // to_text(data(before + 2)) // ", " &
                & // to_text(data(before + 4)) // ", " // to_text(data(before + 5)) // ", " &
                & // to_text(data(before + 7)) // ", " // to_text(data(before + 8)))
            if (allocated(error)) exit
        end do
        close(unit)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        text = model_script("two", "out/two", "out/two.dat", run, reshape([0.3_wp, 0.3_wp, &
            & 0.2_wp, 0.1_wp], [2, 2]))
        call check(error, index(text, "using 2:" // to_text(before + 2) // " with lines lw 2 " &
            & // "lc rgb '#d62728' title 'part 2 centre of mass, sliding'") > 0 .and. &
            & index(text, "using 8:" // to_text(before + 5) // " with lines lw 2 lc rgb " &
            & // "'#d62728' title 'part 3 centre of mass, sliding'") > 0 .and. &
            & index(text, "using 8:" // to_text(before + 4) // " with lines lw 2 lc rgb " &
            & // "'#1f77b4' title 'part 3 centre of mass, rolling'") > 0 .and. &
            & index(text, "using 2:3 ") == 0 .and. index(text, "using 8:9 ") == 0 .and. &
            & count_of(text, "title 'mode switch") == 1, &
            & "each part's path is not drawn a line per mode of its own contact: " &
            & // text(:index(text, "set size noratio")))
        if (allocated(error)) return
        call check(error, index(text, "using 1:" // to_text(before + 7) // " with lines lw 1.5 " &
            & // "lt 1 title 'CONTACT/1 (part 2): μ needed'") > 0 .and. index(text, &
            & "using 1:" // to_text(before + 8) // " with lines lw 1.5 lt 2 title " &
            & // "'CONTACT/2 (part 3): μ needed'") > 0 .and. index(text, ", 0.3 with lines " &
            & // "dashtype 2 lw 1.2 lt 1 title 'CONTACT/1 (part 2): μs = 0.3'") > 0 .and. &
            & index(text, "CONTACT/1 (part 2): μk") == 0 .and. index(text, ", 0.1 with " &
            & // "lines dashtype 3 lw 1.2 lt 2 title 'CONTACT/2 (part 3): μk = 0.1'") > 0, &
            & "the friction figure does not draw each contact's: " &
            & // text(index(text, "friction coefficient"):))
        if (allocated(error)) return
        ! each contact's coefficients from its own summary line
        call write_run(scratch // "/two.csv", run, .true., error)
        if (allocated(error)) return
        call write_lines(scratch // "/two.summary.txt", [character(len=120) :: &
            & "CONTACT/1 (line 38): starts sliding (mu_static 0.3, mu_kinetic 0.3, " &
            & // "restitution 0.5), 1 switch (0 impacts)", &
            & "  CONTACT/1 (line 38): t = 0.1 s: sliding → rolling", &
            & "CONTACT/2 (line 40): starts rolling (mu_static 0.2, mu_kinetic 0.1), 1 switch"])
        do c = 1, 2
            call read_friction(scratch // "/two.csv", friction, found, c)
            if (c == 1) call check(error, found .and. friction(1) == 0.3_wp .and. friction(2) &
                & == 0.3_wp, "CONTACT/1's friction read as " // to_text(friction(1)) // ", " &
                & // to_text(friction(2)))
            if (c == 2) call check(error, found .and. friction(1) == 0.2_wp .and. friction(2) &
                & == 0.1_wp, "CONTACT/2's friction read as " // to_text(friction(1)) // ", " &
                & // to_text(friction(2)))
            if (allocated(error)) exit
        end do
        if (.not. allocated(error)) call read_friction(scratch // "/two.csv", friction, found, 3)
        if (.not. allocated(error)) call check(error, .not. found, "CONTACT/3's friction found")
        if (allocated(error) .or. .not. gnuplot_available()) then
            call remove_folder(scratch)
            if (.not. allocated(error)) call skip_test(error, "gnuplot not found (Debian " &
                & // "gnuplot-nox; bash .ci/setup)")
            return
        end if
        call plot_output(scratch // "/two.csv", scratch, error, files, text)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, size(files) == 7 .and. index(text, "CONTACT/2 (part 3): μk = 0.1") &
            & > 0, "the two contacts' run drew " // to_text(size(files)) // " figures (not " &
            & // "the model's 6 and the friction figure), or not from the summary's friction")

    contains

        !> Drawn there with this value, or not (NaN)
        logical function same(value, expected, there)
            real(wp), intent(in) :: value, expected
            logical, intent(in) :: there

            if (there) then
                same = value == expected
            else
                same = ieee_is_nan(value)
            end if
        end function same
    end subroutine test_two_contacts

    !> The value range of "set <axis>range [low:high]" in a script (both 0 when absent).
    subroutine axis_range(text, axis, low, high)
        character(len=*), intent(in) :: text, axis
        real(wp), intent(out) :: low, high
        integer :: at, colon, close, stat

        low = 0.0_wp
        high = 0.0_wp
        at = index(text, "set " // axis // "range [")
        if (at == 0) return
        at = at + len("set " // axis // "range [")
        colon = at + index(text(at:), ":") - 1
        close = at + index(text(at:), "]") - 1
        read(text(at:colon - 1), *, iostat=stat) low
        read(text(colon + 1:close - 1), *, iostat=stat) high
    end subroutine axis_range

    !> A ball of radius sphere_radius (part 2, an ellipsoid of equal semi-axes) on a CONTACT
    !> (the contact's columns with its modes, 3 UCONs) moving along X at sphere_speed, its
    !> centre at Z = R (height residual 0): sliding for the first sliding_rows rows, then
    !> rolling.
    function sphere_run() result(run)
        type(run_record_type) :: run
        real(wp), allocatable :: row(:)
        real(wp) :: t
        integer :: j

        run%layout = new_output_layout([2], [1, 2, 3], [contact_names, contact_mode_names])
        allocate(run%shapes(1))
        run%shapes(1)%id = 2
        run%shapes(1)%kind = shape_ellipsoid
        run%shapes(1)%semi_axes = sphere_radius
        allocate(row(size(run%layout%header())))
        do j = 1, run_rows
            t = 0.01_wp*real(j - 1, wp)
            row = 0.0_wp
            row(1) = t
            associate (c => run%layout%part_column(1, coord_x))
                row(c:c + 2) = [sphere_speed*t, 0.0_wp, sphere_radius]
                row(c + 4) = 2.0_wp*atan(1.0_wp)
                row(c + 6) = sphere_speed
            end associate
            row(run%layout%energy_column()) = 0.125_wp
            row(run%layout%column("Fz")) = 9.81_wp
            row(run%layout%column("Fn")) = 9.81_wp
            row(run%layout%column("mode")) = merge(1.0_wp, 0.0_wp, j <= sliding_rows)
            call run%history%add(row)
        end do
    end function sphere_run

    !> disk_run with the contact's mode columns: rows 11 to 20 sliding, the others rolling
    !> (modes), the slip zero.
    function mode_run(modes) result(run)
        integer, intent(out) :: modes(run_rows)
        type(run_record_type) :: run
        type(run_record_type) :: plain
        real(wp), allocatable :: row(:)
        integer :: j, mode

        plain = disk_run()
        run%shapes = plain%shapes
        run%layout = new_output_layout([1], [1, 2, 3], [contact_names, contact_mode_names])
        modes = 0
        modes(11:20) = 1
        mode = run%layout%column("mode")
        do j = 1, plain%history%count
            row = [plain%history%rows(:, j), 0.0_wp, 0.0_wp, 0.0_wp]
            row(mode) = real(modes(j), wp)
            call run%history%add(row)
        end do
    end function mode_run

end module test_mode_path
