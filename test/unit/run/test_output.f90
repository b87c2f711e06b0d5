! SPDX-License-Identifier: MIT
!> Tests of the output files: the CSV writer (buffered, every failure seen, numbers that read
!> back), the refusal of an output request no disk holds, and no picture left by a failure.
module test_output
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf, &
        & ieee_negative_inf
    use rollcon_csv_writer, only : csv_writer_type, csv_row_bytes, row_text, fortran_row_text
    use rollcon_output_rows, only : output_layout
    use rollcon_output_layout, only : output_layout_type
    use rollcon_problem, only : problem_type
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : run_options_type, run_summary_type, simulate, &
        & default_max_csv_bytes
    use rollcon_scene, only : scene_type
    use rollcon_figures, only : plot_output, figure_file, figure_names
    use rollcon_gif, only : animate_output
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : picture_scene, make_folder, remove_folder, write_lines, disk_run, &
        & write_run
    use rollcon_run_record, only : run_record_type, read_run
    use command_runs, only : file_text, file_exists, line_count, mount_small, unmount
    use rollcon_vtk, only : write_vtk_series
    implicit none
    private

    public :: collect_output

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_output"

contains

    !> Tests of this suite.
    subroutine collect_output(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("csv-full-device-is-an-error", test_full_device), &
            & new_unittest("csv-buffered-then-whole", test_buffered), &
            & new_unittest("csv-extremes-read-back", test_extremes_read_back), &
            & new_unittest("csv-row-text-is-fortran-format", test_row_text), &
            & new_unittest("csv-row-text-exact-range", test_row_text_exact_range), &
            & new_unittest("csv-row-text-tiny-numbers", test_row_text_tiny), &
            & new_unittest("huge-output-refused", test_huge_output), &
            & new_unittest("output-limit-is-the-option", test_output_limit), &
            & new_unittest("failed-figures-leave-nothing", test_failed_figures), &
            & new_unittest("vtk-full-disk-is-an-error", test_vtk_full_disk)]
    end subroutine collect_output

    !> Writing to /dev/full (every write fails with ENOSPC) is an error naming the file.
    subroutine test_full_device(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: failure
        type(csv_writer_type) :: csv

        if (.not. file_exists("/dev/full")) then
            call skip_test(error, "no /dev/full on this system")
            return
        end if
        call csv%open("/dev/full", [character(len=1) :: "t", "x"], failure)
        if (.not. allocated(failure)) call csv%write_row([0.0_wp, 1.0_wp], failure)
        if (.not. allocated(failure)) call csv%close(failure)
        call csv%close()
        call check(error, allocated(failure), "writing to /dev/full reported no error")
        if (allocated(error)) return
        call check(error, index(failure%message, "/dev/full: write failed: ") == 1 .and. &
            & index(failure%message, "No space left on device") > 0, failure%message)
    end subroutine test_full_device

    !> Rows stay in the buffer (no write per row) and are all in the file after close.
    subroutine test_buffered(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/buffered.csv"
        type(csv_writer_type) :: csv
        integer :: i

        call make_folder(scratch)
        call csv%open(path, [character(len=1) :: "t", "x"], error)
        do i = 1, 10
            if (.not. allocated(error)) call csv%write_row([0.1_wp*i, -1.0_wp*i], error)
        end do
        if (allocated(error)) return
        ! The wall-clock flush comes after a second at the earliest: the rows are not written.
        call check(error, line_count(file_text(path)) == 1, "rows written one by one: " &
            & // to_text(line_count(file_text(path))) // " lines before close")
        call csv%close(error)
        if (allocated(error)) return
        call check(error, line_count(file_text(path)) == 11, "lines after close: " &
            & // to_text(line_count(file_text(path))))
        call remove_folder(scratch)
    end subroutine test_buffered

    !> A row made by the C library has the characters of Fortran's es24.16e3 (the CSVs stay
    !> bit for bit what they were): the extremes of the range, subnormals, both zeros, NaN,
    !> both infinities, rounding ties of the 17th digit, and 20000 numbers spread over every
    !> exponent with random digits. Exact comparison: a single differing character fails.
    subroutine test_row_text(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: special(16), values(40), draw(2)
        character(len=25*size(values)) :: line
        integer :: length, i, j

        special = [0.0_wp, -0.0_wp, huge(1.0_wp), -huge(1.0_wp), tiny(1.0_wp), 4.9e-324_wp, &
            & -2.5e-310_wp, 1.0_wp, -1.0_wp, 0.5_wp, 1.0e100_wp, 9.99999999999999999e99_wp, &
            & 1.25_wp, 0.1_wp, ieee_value(1.0_wp, ieee_quiet_nan), &
            & ieee_value(1.0_wp, ieee_positive_inf)]
        call row_text(special, line, length)
        call check(error, line(:length) == fortran_row_text(special), "special values: '" &
            & // line(:length) // "' against '" // fortran_row_text(special) // "'")
        if (allocated(error)) return
        call row_text([ieee_value(1.0_wp, ieee_negative_inf)], line, length)
        call check(error, line(:length) == fortran_row_text([ieee_value(1.0_wp, &
            & ieee_negative_inf)]), "-Infinity: '" // line(:length) // "'")
        if (allocated(error)) return
        call random_seed()
        do i = 1, 500
            do j = 1, size(values)
                call random_number(draw)
                ! mantissa in [1, 10), exponent over the whole range, either sign
                values(j) = sign((1.0_wp + 9.0_wp*draw(1)) &
                    & *10.0_wp**int(614.0_wp*draw(2) - 307.0_wp), draw(1) - 0.5_wp)
            end do
            call row_text(values, line, length)
            if (line(:length) /= fortran_row_text(values)) then
                call check(error, .false., "row " // to_text(i) // ": '" // line(:length) &
                    & // "' against '" // fortran_row_text(values) // "'")
                return
            end if
        end do
    end subroutine test_row_text

    !> The numbers the row text converts in integers (1e-16 <= |x| < 1e17, and zeros) and
    !> those just outside, which go to the C library, have the characters of Fortran's
    !> es24.16e3: every power of ten of the range and its neighbours, exact ties of the 17th
    !> digit (an 18-digit value ending in 5: to even, both ways), the largest double below
    !> 1e17, and 12000 rows of 40 doubles whose 52 significand
    !> bits are random and whose binary exponents span 2^-60 to 2^64. Exact comparison.
    subroutine test_row_text_exact_range(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: edges(:)
        real(wp) :: values(40), draw(4), power
        character(len=25*40) :: line
        character(len=:), allocatable :: expected
        integer(int64) :: bits
        integer :: i, j, length

        edges = [real(wp) ::]
        do i = -18, 18
            power = 10.0_wp**i
            edges = [edges, power, nearest(power, -1.0_wp), nearest(power, 1.0_wp), -power]
        end do
        ! ties: 999999999999999/8 = 124999999999999.875 to ...88 (odd 7 up), and
        ! 999999999999997/8 = 124999999999999.625 to ...62 (even 2 stays); 2^-1 .. 2^-3
        edges = [edges, 999999999999999.0_wp/8.0_wp, 999999999999997.0_wp/8.0_wp, &
            & -999999999999999.0_wp/8.0_wp, 0.5_wp, 0.25_wp, 0.125_wp, 1.0e16_wp - 2.0_wp, &
            & 99999999999999984.0_wp, 9.9999999999999998e-17_wp, 0.0_wp, -0.0_wp]
        do i = 1, size(edges), size(values)
            associate (part => edges(i:min(i + size(values) - 1, size(edges))))
                call row_text(part, line, length)
                expected = fortran_row_text(part)
                call check(error, line(:length) == expected, "edges: '" // line(:length) &
                    & // "' against '" // expected // "'")
                if (allocated(error)) return
            end associate
        end do
        call random_seed()
        do i = 1, 12000
            do j = 1, size(values)
                call random_number(draw)
                ! 52 random significand bits, a binary exponent from -60 to 64, a sign
                bits = ior(int(draw(1)*2.0_wp**26, int64), shiftl(int(draw(2)*2.0_wp**26, &
                    & int64), 26))
                bits = ior(bits, shiftl(int(1023 - 60 + int(125.0_wp*draw(3)), int64), 52))
                values(j) = sign(transfer(bits, 1.0_wp), draw(4) - 0.5_wp)
            end do
            call row_text(values, line, length)
            expected = fortran_row_text(values)
            if (line(:length) /= expected) then
                call check(error, .false., "row " // to_text(i) // ": '" // line(:length) &
                    & // "' against '" // expected // "'")
                return
            end if
        end do
    end subroutine test_row_text_exact_range

    !> Numbers below 1e-16, which the row text converts in multi-word integers (a residual of
    !> 1e-17, a subnormal), have the characters of Fortran's es24.16e3: the powers of ten from
    !> 1e-17 to 1e-323 and their neighbours, the smallest subnormal and normal numbers, exact
    !> ties of the 17th digit among short significands, and 12000 rows of 40 doubles whose
    !> significand bits are random (some cut short, to make ties) and whose binary exponents
    !> span 2^-1074 to 2^-54. Exact comparison.
    subroutine test_row_text_tiny(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: edges(:)
        real(wp) :: values(40), draw(5), power
        character(len=25*40) :: line
        character(len=:), allocatable :: expected
        integer(int64) :: bits
        integer :: i, j, length, exponent

        edges = [4.9e-324_wp, -4.9e-324_wp, 1.5e-323_wp, tiny(1.0_wp), &
            & nearest(tiny(1.0_wp), -1.0_wp), 1.0e-17_wp, 9.9999999999999998e-17_wp]
        do i = 17, 323
            power = 10.0_wp**(-i)
            edges = [edges, power, nearest(power, -1.0_wp), nearest(power, 1.0_wp), -power]
        end do
        do i = 1, size(edges), size(values)
            associate (part => edges(i:min(i + size(values) - 1, size(edges))))
                call row_text(part, line, length)
                expected = fortran_row_text(part)
                call check(error, line(:length) == expected, "edges: '" // line(:length) &
                    & // "' against '" // expected // "'")
                if (allocated(error)) return
            end associate
        end do
        call random_seed()
        do i = 1, 12000
            do j = 1, size(values)
                call random_number(draw)
                bits = ior(int(draw(1)*2.0_wp**26, int64), shiftl(int(draw(2)*2.0_wp**26, &
                    & int64), 26))
                ! a third of them with their last bits cleared: short significands, ties
                if (draw(5) < 1.0_wp/3.0_wp) bits = iand(bits, not(shiftl(1_int64, &
                    & int(52.0_wp*draw(5)*3.0_wp)) - 1_int64))
                ! biased exponents 0 (subnormals) to 969 (2^-54)
                exponent = int(970.0_wp*draw(3))
                bits = ior(bits, shiftl(int(exponent, int64), 52))
                values(j) = sign(transfer(bits, 1.0_wp), draw(4) - 0.5_wp)
            end do
            call row_text(values, line, length)
            expected = fortran_row_text(values)
            if (line(:length) /= expected) then
                call check(error, .false., "row " // to_text(i) // ": '" // line(:length) &
                    & // "' against '" // expected // "'")
                return
            end if
        end do
    end subroutine test_row_text_tiny

    !> Three-digit exponents, -0 and the extremes of the range read back exactly.
    subroutine test_extremes_read_back(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/extremes.csv"
        real(wp), parameter :: values(6) = [1.0e-301_wp, -1.0e-301_wp, huge(1.0_wp), &
            & -tiny(1.0_wp), 4.9e-324_wp, 123.456_wp]
        type(csv_writer_type) :: csv
        character(len=200) :: header
        real(wp) :: back(6)
        integer :: unit, stat

        call make_folder(scratch)
        call csv%open(path, [character(len=1) :: "a", "b", "c", "d", "e", "f"], error)
        if (.not. allocated(error)) call csv%write_row(values, error)
        if (.not. allocated(error)) call csv%close(error)
        if (allocated(error)) return
        open(newunit=unit, file=path, status="old", action="read")
        read(unit, '(a)') header
        read(unit, *, iostat=stat) back
        close(unit)
        call check(error, stat == 0 .and. index(file_text(path), "E-301") > 0 .and. &
            & all(back == values), "values read back: " // file_text(path))
        call remove_folder(scratch)
    end subroutine test_extremes_read_back

    !> end_time 1e9 s at output_step 1e-6 s is refused before the run, with the row count
    !> and the bytes (a 32-bit count would overflow and "complete" after one step).
    subroutine test_huge_output(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(error_type), allocatable :: failure
        real(wp) :: q0(6), u0(6)

        scene = picture_scene()
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        call make_folder(scratch)
        options%end_time = 1.0e9_wp
        options%output_step = 1.0e-6_wp
        options%progress = .false.
        options%csv_path = scratch // "/huge.csv"
        call simulate(problem, q0, u0, options, summary, failure)
        call check(error, allocated(failure), "the request was not refused; t reached " &
            & // to_text(summary%t_reached) // " s")
        if (.not. allocated(error)) call check(error, failure%stat == stat_input .and. &
            & index(failure%message, to_text(1000000000000001_int64) // " rows") > 0 .and. &
            & index(failure%message, "bytes") > 0 .and. summary%rows == 0 .and. .not. &
            & file_exists(options%csv_path), failure%message)
        call remove_folder(scratch)
    end subroutine test_huge_output

    !> The limit is options%max_csv_bytes: 0.1 s at 0.01 s (11 rows of 23 numbers of 25 bytes
    !> each with its comma or new line, 6325 bytes) is refused under a 1000-byte limit and runs
    !> under the default.
    subroutine test_output_limit(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        type(error_type), allocatable :: failure
        type(output_layout_type) :: layout
        real(wp) :: q0(6), u0(6)
        integer :: columns

        call build_disk_problem(picture_scene(), rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        ! the disk scene's rows: t, 12 coordinates, E, 3 residuals, 3 multipliers, 6 contact
        layout = output_layout(problem)
        columns = layout%columns()
        call check(error, columns, 26, "columns of the disk scene's rows")
        if (allocated(error)) return
        call make_folder(scratch)
        options%end_time = 0.1_wp
        options%output_step = 0.01_wp
        options%progress = .false.
        options%csv_path = scratch // "/limit.csv"
        options%max_csv_bytes = 1000.0_wp
        call simulate(problem, q0, u0, options, summary, failure)
        call check(error, allocated(failure), "11 rows fitted in 1000 bytes")
        if (.not. allocated(error)) call check(error, &
            & index(failure%message, "11 rows, " // to_text(11*csv_row_bytes(columns)) &
            & // " bytes") > 0, failure%message)
        if (.not. allocated(error)) then
            options%max_csv_bytes = default_max_csv_bytes
            call simulate(problem, q0, u0, options, summary, error)
        end if
        if (.not. allocated(error)) call check(error, summary%rows == 11_int64 .and. &
            & line_count(file_text(options%csv_path)) == 12, "rows " // to_text(summary%rows))
        call remove_folder(scratch)
    end subroutine test_output_limit

    !> A CSV holding X = 1e308: plot and animate both refuse it, and leave no PNG or GIF.
    subroutine test_failed_figures(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: plot_failure, animate_failure
        character(len=*), parameter :: path = scratch // "/huge.csv"
        integer :: frames, i
        logical :: left

        call make_folder(scratch)
        call write_lines(path, [character(len=200) :: "t,X_1,Y_1,Z_1,psi_1,theta_1,phi_1," &
            & // "Xdot_1,Ydot_1,Zdot_1,psidot_1,thetadot_1,phidot_1,E,F_1,lambda_1,Fx,Fy,Fz,Fn," &
            & // "mu_needed,height_residual", &
            & "0,0,0,0.1,0,1.5707963267948966,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0", &
            & "0.1,1e308,0,0.1,0,1.5707963267948966,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0"])
        call plot_output(path, scratch, plot_failure)
        call animate_output(path, scratch // "/huge.gif", frames, animate_failure)
        left = file_exists(scratch // "/huge.gif")
        do i = 1, size(figure_names)
            left = left .or. file_exists(figure_file(path, scratch, figure_names(i)))
        end do
        call remove_folder(scratch)
        call check(error, allocated(plot_failure) .and. allocated(animate_failure), &
            & "plot or animate accepted X = 1e308")
        if (allocated(error)) return
        call check(error, index(plot_failure%message, path // ":3: ") == 1 .and. &
            & animate_failure%message == plot_failure%message .and. .not. left, &
            & "plot: " // plot_failure%message // "; animate: " // animate_failure%message)
    end subroutine test_failed_figures

    !> VTK frames that do not fit on a 64 KiB filesystem: an error naming the file (gfortran
    !> itself reports no error when the disk is full).
    subroutine test_vtk_full_disk(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: mount_point = scratch // "/small"
        type(run_record_type) :: run
        type(error_type), allocatable :: failure
        integer :: frames

        call make_folder(scratch)
        call write_run(scratch // "/vtk.csv", disk_run(), .true., error)
        if (.not. allocated(error)) call read_run(scratch // "/vtk.csv", run, error)
        if (allocated(error)) return
        call mount_small(mount_point, "64k", error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        ! 0.5 s at 100 frames per second: 51 frames of about 30 kB each
        call write_vtk_series(mount_point, "vtk", run, 100.0_wp, frames, failure)
        call unmount(mount_point)
        call remove_folder(scratch)
        call check(error, allocated(failure), "wrote " // to_text(frames) // " frames on a " &
            & // "64 KiB filesystem without an error")
        if (allocated(error)) return
        call check(error, index(failure%message, mount_point // "/vtk_") == 1 .and. &
            & index(failure%message, "write failed") > 0, failure%message)
    end subroutine test_vtk_full_disk

end module test_output
