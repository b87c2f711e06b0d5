! SPDX-License-Identifier: MIT
!> The contact point's path coloured by the contact's mode (suite mode-path): a run whose rows
!> carry the `mode` column (Coulomb friction) has its path split by that column into one line
!> per mode, each stretch joined to the next, and its switches marked, and the animation's path
!> takes each point's mode's colour; a run without it keeps the one line of the contact point.
module test_mode_path
    use, intrinsic :: ieee_arithmetic, only : ieee_is_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : new_output_layout
    use rollcon_watch_columns, only : contact_names, contact_mode_names
    use rollcon_run_record, only : run_record_type
    use rollcon_contact_figures, only : mode_path, mode_switches, write_contact_data, &
        & contact_script, mode_colour_values
    use rollcon_gif, only : animate_output
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_figure_text, only : residual_floor
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : disk_run, make_folder, remove_folder, run_rows, write_run
    implicit none
    private

    public :: collect_mode_path

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_mode_path"
    !> Columns of the figures' data before those of the modes: 13, one per UCON (3), the
    !> height residual (rollcon_contact_figures)
    integer, parameter :: before_modes = 13 + 3 + 1

contains

    subroutine collect_mode_path(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("split-follows-mode-column", test_split), &
            & new_unittest("figure-data-by-mode", test_data), &
            & new_unittest("script-lines-by-mode", test_script), &
            & new_unittest("animation-path-by-mode", test_animation)]
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
