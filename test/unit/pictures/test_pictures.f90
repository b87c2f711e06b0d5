! SPDX-License-Identifier: MIT
!> Tests of the pictures of a run: frame choice, reading the CSV back through the output layout
!> (and refusing a bad one), and the gnuplot PNG figures and GIF, for a disk scene's CSV and
!> for a model of two parts (a disk and an ellipsoid). The VTK series: test_picture_vtk.
module test_pictures
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type
    use rollcon_output_layout, only : output_layout_type, read_layout, name_length, &
        & new_output_layout, coord_psidot
    use rollcon_animation_rows, only : frame_rows
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_run_record, only : run_record_type
    use rollcon_figures, only : plot_output, figure_file, figure_names, model_figure_names
    use rollcon_singularity_figure, only : singularity_figure_name
    use rollcon_gif, only : animate_output
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_watch_columns, only : answer_column_patterns, &
        & element_reaction_column_patterns, element_force_column_patterns
    use rollcon_watch_columns, only : contact_names, contact_mode_names, request_column_patterns, &
        & motion_column_patterns, reaction_column_patterns, variable_column_patterns, &
        & diff_column_patterns, dissipation_names, contact_column_patterns
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : disk_run, two_part_run, falling_run, write_run, make_folder, &
        & remove_folder, write_lines, expect_message, file_starts_with
    implicit none
    private

    public :: collect_pictures

    !> Scratch folder of the suite, removed by every test that makes it
    character(len=*), parameter :: scratch = "build/test_pictures"
    !> The CSV carries 17 significant digits: values read back are the values written
    real(wp), parameter :: tol_exact = 0.0_wp

contains

    !> Tests of this suite.
    subroutine collect_pictures(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("frame-rows-nearest-once", test_frame_rows), &
            & new_unittest("csv-reads-back-two-parts", test_csv_round_trip), &
            & new_unittest("csv-missing-file", test_csv_missing), &
            & new_unittest("csv-bad-header", test_csv_header), &
            & new_unittest("csv-bad-rows", test_csv_rows), &
            & new_unittest("csv-reads-every-documented-column", test_csv_documented), &
            & new_unittest("plot-disk-scene-figures", test_plot_disk), &
            & new_unittest("plot-settling-disk-singularity", test_plot_singularity), &
            & new_unittest("plot-two-part-figures", test_plot_model), &
            & new_unittest("plot-model-without-ucon", test_plot_no_ucon), &
            & new_unittest("plot-missing-csv", test_plot_missing), &
            & new_unittest("plot-malformed-csv", test_plot_malformed), &
            & new_unittest("animate-writes-gif", test_gif), &
            & new_unittest("animate-titles-not-enhanced", test_gif_noenhanced)]
    end subroutine collect_pictures

    !> Frames take the nearest row, each row once, and interpolate nothing.
    subroutine test_frame_rows(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: times(51)
        integer, allocatable :: rows(:)
        integer :: i

        times = [(0.01_wp*i, i = 0, 50)]
        rows = frame_rows(times, 0.1_wp)
        call check(error, size(rows) == 6 .and. all(rows == [1, 11, 21, 31, 41, 51]), &
            & "a frame every 0.1 s of rows every 0.01 s")
        if (allocated(error)) return
        rows = frame_rows(times, 0.004_wp)
        call check(error, size(rows) == 51 .and. all(rows == [(i, i = 1, 51)]), &
            & "frames closer than the rows: every row once")
        if (allocated(error)) return
        rows = frame_rows([0.0_wp, 0.3_wp, 0.35_wp, 1.0_wp], 0.25_wp)
        call check(error, size(rows) == 4 .and. all(rows == [1, 2, 3, 4]), &
            & "nearest rows to 0, 0.25, 0.5, 0.75, 1: " // to_text(size(rows)) // " frames")
    end subroutine test_frame_rows

    !> The reader gives back the layout and every value of a two-part CSV.
    subroutine test_csv_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: written
        type(output_layout_type) :: layout
        type(history_type) :: read_back

        call make_folder(scratch)
        written = two_part_run()
        call write_run(scratch // "/round.csv", written, .false., error)
        if (.not. allocated(error)) call read_output_csv(scratch // "/round.csv", layout, &
            & read_back, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, all(layout%part_ids == [1, 7]) .and. all(layout%ucon_ids == [3, 5]) &
            & .and. layout%column("Fn") == 0, "layout read back: parts " &
            & // to_text(size(layout%part_ids)) // ", UCONs " // to_text(size(layout%ucon_ids)))
        if (allocated(error)) return
        call check(error, read_back%count == written%history%count .and. &
            & size(read_back%rows, 1) == layout%columns(), "rows or columns read back: " &
            & // to_text(read_back%count))
        if (allocated(error)) return
        call check(error, reshape(read_back%rows(:, :read_back%count), [layout%columns() &
            & *read_back%count]), reshape(written%history%rows(:, :read_back%count), &
            & [layout%columns()*read_back%count]), "values read back", abs_tol=tol_exact)
    end subroutine test_csv_round_trip

    !> A missing CSV: the message names the file.
    subroutine test_csv_missing(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(output_layout_type) :: layout
        type(history_type) :: history

        call read_output_csv("build/no-such-run.csv", layout, history, failure)
        call expect_message(error, failure, "build/no-such-run.csv: cannot open")
    end subroutine test_csv_missing

    !> Headers that are not the layout's, each refused at line 1 with the reason: the output
    !> layout's own (its count of columns asked from read_layout itself, whose wording is its
    !> module's), a hint for the one-part header of older runs, a name too long for a column.
    subroutine test_csv_header(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/header.csv"
        character(len=*), parameter :: part = "X_1,Y_1,Z_1,psi_1,theta_1,phi_1,Xdot_1,Ydot_1," &
            & // "Zdot_1,psidot_1,thetadot_1,phidot_1"
        character(len=*), parameter :: prefix = "not the header 'rollcon run' writes: "
        character(len=4000) :: headers(5), expected(5)
        type(error_type), allocatable :: failure
        type(output_layout_type) :: layout
        type(history_type) :: history
        character(len=:), allocatable :: count_reason
        character(len=name_length), allocatable :: names(:)
        integer :: i

        names = [character(len=name_length) :: "t", "X_1", "Y_1", "Z_1", "psi_1", "theta_1", &
            & "phi_1", "Xdot_1", "Ydot_1", "Zdot_1", "psidot_1", "thetadot_1", "phidot_1", "E", &
            & "F_1", "lambda_1", "F_2"]
        call read_layout(names, layout, count_reason, [character(len=name_length) :: &
            & contact_names, contact_mode_names, dissipation_names, "basis_<id>", &
            & request_column_patterns, motion_column_patterns, &
            & answer_column_patterns, reaction_column_patterns, &
            & element_reaction_column_patterns, element_force_column_patterns, &
            & variable_column_patterns, diff_column_patterns, contact_column_patterns])
        call check(error, allocated(count_reason), "read_layout accepted 17 columns for one " &
            & // "part and one UCON")
        if (allocated(error)) return
        headers = [character(len=4000) :: "time,X,Y", &
            & "t,X,Y,Z,psi,theta,phi,Xdot,Ydot,Zdot,psidot,thetadot,phidot,E,Fx", &
            & "t," // part // ",E,F_1,lambda_1,F_2", &
            & "t," // part // ",E,F_1,lambda_2", &
            & "t," // part // "," // repeat("E", 40)]
        expected = [character(len=4000) :: prefix // "column 1 must be t, got 'time'", &
            & prefix // "column 2 must be X_<part id>, got 'X' (a CSV of an older rollcon, whose " &
            & // "columns did not name the part: run the scene again)", &
            & prefix // count_reason, &
            & prefix // "column 16 must be lambda_1, got 'lambda_2'", &
            & "column 14 of the header is not a column name 'rollcon run' writes (longer " &
            & // "than 32 characters): '" // repeat("E", 40) // "'"]
        call make_folder(scratch)
        do i = 1, size(headers)
            call write_lines(path, [character(len=200) :: headers(i), "0"])
            call read_output_csv(path, layout, history, failure)
            call check(error, allocated(failure), "header " // to_text(i) // " accepted")
            if (allocated(error)) exit
            call check(error, failure%message == path // ":1: " // trim(expected(i)), &
                & "header " // to_text(i) // ": " // failure%message)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_csv_header

    !> A header with one of each column docs/outputs.md documents after the multipliers (its
    !> tables: a rim contact's, its modes', the dissipation's, a part's basis, a displacement
    !> request's, a MOTION's force and torque, a VARIABLE's, a DIFF's, a SPRINGDAMPER's and a
    !> BUSHING's, the other requests' (VELOCITY, ACCELERATION, Fk, FORCE), and the reactions of
    !> a JOINT, a JPRIM, a UCON (on one part and on several) and of the elements of one
    !> equation, a GCON, a MOTION, a COUPLER, a GEAR and a RACKPIN or SCREW JOINT, on one part
    !> and on several) reads, every column found where it was written; the same header with a
    !> column outputs.md does not document (gcon_fx: no id; spring1_fx) is refused naming it.
    subroutine test_csv_documented(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/documented.csv"
        character(len=*), parameter :: suffixes(6) = [character(len=3) :: "_fx", "_fy", &
            & "_fz", "_tx", "_ty", "_tz"]
        character(len=*), parameter :: answers(12) = [character(len=5) :: "vx", "vy", "vz", &
            & "wx", "wy", "wz", "accx", "accy", "accz", "wdtx", "wdty", "wdtz"]
        character(len=*), parameter :: stems(16) = [character(len=16) :: "springdamper9", &
            & "bushing10", "req12", "joint13", "jprim14", "ucon15", "ucon16_part2", "gcon17", &
            & "motion18", "coupler19", "gear20", "joint21_part2", "gcon22_part2", &
            & "motion23_part2", "coupler24_part2", "gear25_part2"]
        character(len=name_length), allocatable :: names(:)
        character(len=:), allocatable :: header, row, lines(:)
        character(len=20) :: wrong(2)
        type(error_type), allocatable :: failure
        type(output_layout_type) :: layout
        type(history_type) :: history
        integer :: i, j, missing

        names = [character(len=name_length) :: "Fx", "Fy", "Fz", "Fn", "mu_needed", &
            & "height_residual", "mode", "slip_x", "slip_y", "rolling_power", "air_power", &
            & "dissipated", "basis_2", "req1_x", "req1_y", "req1_z", "req1_psi", "req1_theta", &
            & "req1_phi", "motion4_force", "motion5_torque", "var7", "diff8", "diff8_dot"]
        ! one name at a time (gfortran 12 miscomputes the length of a typed constructor's
        ! implied-do of concatenations)
        do i = 1, size(answers)
            call add("req11_" // trim(answers(i)))
        end do
        do i = 1, 8
            call add("req11_f" // to_text(i))
        end do
        do i = 1, size(stems)
            do j = 1, 6
                call add(trim(stems(i)) // suffixes(j))
            end do
        end do
        header = "t,X_2,Y_2,Z_2,psi_2,theta_2,phi_2,Xdot_2,Ydot_2,Zdot_2,psidot_2,thetadot_2," &
            & // "phidot_2,E,F_1,lambda_1"
        do i = 1, size(names)
            header = header // "," // trim(names(i))
        end do
        row = "0" // repeat(",0", 15 + size(names))
        call make_folder(scratch)
        ! (each line assigned apart: gfortran 12 writes past a typed constructor of
        ! concatenations of deferred length)
        allocate(character(len=len(header) + 30) :: lines(2))
        lines(1) = header
        lines(2) = row
        call write_lines(path, lines)
        call read_output_csv(path, layout, history, failure)
        if (allocated(failure)) then
            call check(error, .false., "a documented column refused: " // failure%message)
            return
        end if
        missing = 0
        do i = 1, size(names)
            if (layout%column(trim(names(i))) /= 16 + i) missing = i
        end do
        call check(error, missing == 0 .and. history%count == 1, "column " &
            & // to_text(missing + 16) // " not found where written")
        if (allocated(error)) return
        wrong = [character(len=20) :: "gcon_fx", "spring1_fx"]
        do i = 1, size(wrong)
            lines(1) = header // "," // trim(wrong(i))
            lines(2) = row // ",0"
            call write_lines(path, lines)
            call read_output_csv(path, layout, history, failure)
            call check(error, allocated(failure), trim(wrong(i)) // " accepted")
            if (allocated(error)) return
            call check(error, index(failure%message, "column " // to_text(17 + size(names)) &
                & // " must be one of ") > 0 .and. index(failure%message, "got '" &
                & // trim(wrong(i)) // "'") > 0, failure%message)
            if (allocated(error)) return
        end do
    contains
        !> Append name to names.
        subroutine add(name)
            character(len=*), intent(in) :: name
            character(len=name_length) :: one(1)

            one(1) = name
            names = [names, one]
        end subroutine add
    end subroutine test_csv_documented

    !> Rows with too few values, a NaN, a word, or no rows at all.
    subroutine test_csv_rows(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/rows.csv"
        character(len=:), allocatable :: header, good
        character(len=400) :: lines(3)
        character(len=60) :: bad(3), expected(3)
        type(error_type), allocatable :: failure
        type(output_layout_type) :: layout
        type(history_type) :: history
        integer :: i, unit

        header = "t,X_1,Y_1,Z_1,psi_1,theta_1,phi_1,Xdot_1,Ydot_1,Zdot_1,psidot_1,thetadot_1," &
            & // "phidot_1,E,F_1,lambda_1"
        good = "0,0,0,0.1,0,1.5707963267948966,0,0,0,0,0,0,0,0,0,0"
        bad = [character(len=60) :: "1,2,3", "0.1,0,0,0.1,0,1.57,0,0,0,0,0,0,0,0,NaN,0", &
            & "0.1,0,0,0.1,x,1.57,0,0,0,0,0,0,0,0,0,0"]
        expected = [character(len=60) :: ":3: expected 16 comma-separated values", &
            & ":3: value 15 must be a finite number", ":3: value 5 must be a finite number"]
        call make_folder(scratch)
        do i = 1, size(bad)
            lines(1) = header
            lines(2) = good
            lines(3) = bad(i)
            call write_lines(path, lines)
            call read_output_csv(path, layout, history, failure)
            call expect_message(error, failure, path // trim(expected(i)))
            if (allocated(error)) exit
        end do
        if (.not. allocated(error)) then
            call write_lines(path, lines(1:1))
            call read_output_csv(path, layout, history, failure)
            call expect_message(error, failure, path // ":1:", "at least one row")
        end if
        ! the same short row as the last line without its end: the torn tail of a run killed
        ! while it wrote, dropped; the whole row before it read (docs/outputs.md)
        if (.not. allocated(error)) then
            open(newunit=unit, file=path, status="replace", access="stream", &
                & form="unformatted")
            write(unit) header // new_line("a") // good // new_line("a") // "1,2,3"
            close(unit)
            call read_output_csv(path, layout, history, failure)
            if (allocated(failure)) then
                call check(error, .false., "a torn last line refused: " // failure%message)
            else
                call check(error, history%count == 1, "rows read before the torn line: " &
                    & // to_text(history%count))
            end if
        end if
        call remove_folder(scratch)
    end subroutine test_csv_rows

    !> A disk scene's CSV gets the disk's seven figures, non-empty PNG files (skipped without
    !> gnuplot).
    subroutine test_plot_disk(error)
        type(error_type), allocatable, intent(out) :: error

        call plot_and_check(error, disk_run(), "disk", figure_names)
    end subroutine test_plot_disk

    !> A disk scene's CSV with a rim's dissipation whose precession rate rises as
    !> 30 (t0 - t)^(-1/6) to its last row, t0 a thousandth of the rows' span after it (a run
    !> ending at its singularity), gets the singularity's figure too (skipped without gnuplot).
    subroutine test_plot_singularity(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: base, run
        real(wp), allocatable :: row(:)
        real(wp) :: t0
        integer :: j

        base = disk_run()
        t0 = base%history%rows(1, base%history%count) + 1.0e-3_wp &
            & *(base%history%rows(1, base%history%count) - base%history%rows(1, 1))
        run%layout = new_output_layout([1], [1, 2, 3], [character(len=name_length) :: &
            & contact_names, dissipation_names])
        run%shapes = base%shapes
        do j = 1, base%history%count
            associate (t => base%history%rows(1, j))
                row = [base%history%rows(:, j), 0.0_wp, 1.0e-3_wp, 1.0e-3_wp*t]
                row(run%layout%part_column(1, coord_psidot)) = 30.0_wp*(t0 - t) &
                    & **(-1.0_wp/6.0_wp)
            end associate
            call run%history%add(row)
        end do
        call plot_and_check(error, run, "settling", [character(len=11) :: figure_names, &
            & singularity_figure_name])
    end subroutine test_plot_singularity

    !> A model of two parts gets the figures for any parts (skipped without gnuplot).
    subroutine test_plot_model(error)
        type(error_type), allocatable, intent(out) :: error

        call plot_and_check(error, two_part_run(), "two", model_figure_names)
    end subroutine test_plot_model

    !> A model without UCONs gets the same figures, its residuals and multipliers flat lines
    !> labelled 'no UCON' (gnuplot refuses a plot of no point; skipped without gnuplot).
    subroutine test_plot_no_ucon(error)
        type(error_type), allocatable, intent(out) :: error

        call plot_and_check(error, falling_run(), "falling", model_figure_names)
    end subroutine test_plot_no_ucon

    !> Plot a run written as scratch/name.csv (with its .parts) and check the files: the names
    !> expected, each a PNG file.
    subroutine plot_and_check(error, run, name, expected)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type), intent(in) :: run
        character(len=*), intent(in) :: name, expected(:)
        character(len=:), allocatable :: files(:), csv
        integer :: i

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        csv = scratch // "/" // name // ".csv"
        call write_run(csv, run, .true., error)
        if (.not. allocated(error)) call plot_output(csv, scratch, error, files)
        if (.not. allocated(error)) call check(error, size(files) == size(expected), &
            & to_text(size(files)) // " figures, expected " // to_text(size(expected)))
        do i = 1, size(expected)
            if (allocated(error)) exit
            call check(error, files(i) == figure_file(csv, scratch, expected(i)) .and. &
                & file_starts_with(files(i), achar(137) // "PNG"), figure_file(csv, scratch, &
                & expected(i)) // " is missing or not a PNG file")
        end do
        call remove_folder(scratch)
    end subroutine plot_and_check

    !> plot on a missing CSV names the file; no gnuplot needed, reading fails first.
    subroutine test_plot_missing(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure

        call plot_output("build/no-such-run.csv", "build", failure)
        call expect_message(error, failure, "build/no-such-run.csv: cannot open")
    end subroutine test_plot_missing

    !> plot on a malformed CSV names the file and line and writes no figure.
    subroutine test_plot_malformed(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        logical :: exists

        call make_folder(scratch)
        call write_lines(scratch // "/bad.csv", [character(len=60) :: "t,X,Y,Z", "0,1,2,3"])
        call plot_output(scratch // "/bad.csv", scratch, failure)
        inquire(file=figure_file(scratch // "/bad.csv", scratch, "path"), exist=exists)
        call remove_folder(scratch)
        call expect_message(error, failure, scratch // "/bad.csv:1:", "not the header")
        if (.not. allocated(error)) call check(error, .not. exists, "a figure was written")
    end subroutine test_plot_malformed

    !> The animations of a disk scene and of the two-part model are GIFs with a frame every
    !> 0.05 s (skipped without gnuplot).
    subroutine test_gif(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: frames, i
        character(len=4), parameter :: names(2) = ["disk", "two "]

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        do i = 1, 2
            if (i == 1) call write_run(scratch // "/disk.csv", disk_run(), .true., error)
            if (i == 2) call write_run(scratch // "/two.csv", two_part_run(), .true., error)
            if (.not. allocated(error)) call animate_output(scratch // "/" // trim(names(i)) &
                & // ".csv", scratch // "/" // trim(names(i)) // ".gif", frames, error)
            if (.not. allocated(error)) call check(error, file_starts_with(scratch // "/" &
                & // trim(names(i)) // ".gif", "GIF89a") .and. frames == 11, "GIF of 0.5 s (" &
                & // trim(names(i)) // "): " // to_text(frames) // " frames, expected 11")
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_gif

    !> The GIF's script, of a run whose name has underscores (two_part_run.csv): its terminal is
    !> noenhanced, so the title label shows "two_part_run" as written, not with the letters
    !> after each underscore as subscripts (skipped without gnuplot).
    subroutine test_gif_noenhanced(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: script, terminal
        integer :: frames, start

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        call write_run(scratch // "/two_part_run.csv", two_part_run(), .true., error)
        if (.not. allocated(error)) call animate_output(scratch // "/two_part_run.csv", &
            & scratch // "/two_part_run.gif", frames, error, script)
        call remove_folder(scratch)
        if (allocated(error)) return
        start = index(script, "set terminal gif")
        terminal = ""
        if (start > 0) terminal = script(start:start - 2 + index(script(start:), new_line("a")))
        call check(error, index(terminal, " noenhanced") > 0, "the GIF's terminal line is '" &
            & // terminal // "', without noenhanced")
        if (.not. allocated(error)) call check(error, index(script, "set label 1 sprintf(" &
            & // "'two_part_run   t = ") > 0, "the GIF's title label does not name two_part_run")
    end subroutine test_gif_noenhanced

end module test_pictures
