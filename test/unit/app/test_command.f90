! SPDX-License-Identifier: MIT
!> Tests of the `rollcon` program as a user runs it: refusals (message and exit status alone),
!> extra arguments, a full disk, a failed run beside an earlier one, concurrent runs into one
!> folder, numbers that read back, and the version it gives.
module test_command
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type
    use rollcon_output_layout, only : output_layout_type, coord_z
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_version, only : rollcon_version_number, version_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count, &
        & mount_small, unmount
    implicit none
    private

    public :: collect_command

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_command"
    !> Z of an upright disk rolling fast stays R sin(theta) with theta within a few 1e-2 rad of
    !> its start: rows of the 0.05 m disk are at least 40% off the 0.1 m disk's Z
    real(wp), parameter :: tol_same_disk = 0.1_wp

contains

    !> Tests of this suite.
    subroutine collect_command(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("refusal-is-message-alone", test_refusal), &
            & new_unittest("extra-arguments-refused", test_extra_arguments), &
            & new_unittest("table-exponents-read-back", test_exponents), &
            & new_unittest("failed-run-keeps-earlier-files", test_failed_run), &
            & new_unittest("interrupted-run-keeps-earlier-files", test_interrupted), &
            & new_unittest("killed-run-leaves-valid-prefix", test_killed), &
            & new_unittest("concurrent-runs-do-not-splice", test_concurrent), &
            & new_unittest("full-disk-is-a-failure", test_full_disk), &
            & new_unittest("version-is-fpm-toml-version", test_version), &
            & new_unittest("empty-values-refused", test_empty_values), &
            & new_unittest("numbers-out-of-range-refused", test_numbers_out_of_range)]
    end subroutine collect_command

    !> A refusal prints one line, the message, and exits 1: no backtrace, no STOP line.
    subroutine test_refusal(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "no_such_scene -o " // scratch // "/out", scratch &
            & // "/refusal.out", scratch // "/refusal.err", status)
        err = file_text(scratch // "/refusal.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
            & "rollcon: error: data/no_such_scene.nml: ") == 1, "exit status " &
            & // to_text(status) // ", stderr: " // err)
    end subroutine test_refusal

    !> An empty value (a shell variable not set) is a mistake, never the option's default: every
    !> option that takes a value, and the positional argument of every command that takes one,
    !> given '' is refused with one line naming it, exit status 1, nothing written. (Before,
    !> `run coin --output ''` wrote nothing and exited 0, `--ucosub ''` ran the built-in disk.)
    subroutine test_empty_values(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: lines(27) = [character(len=64) :: &
            & "run coin --output ''", "run coin -o ''", "run coin --vtk ''", &
            & "run coin --ucosub ''", "run coin --call-timeout ''", &
            & "table --radius ''", "table --state ''", "check x.f --ucon ''", &
            & "check x.f --model ''", "check x.f --states ''", "check x.f --seed ''", &
            & "check x.f --json ''", "check x.f --call-timeout ''", "bench --scenes ''", &
            & "bench --repeats ''", "bench --end-time ''", "bench scaling --end-time ''", &
            & "bench sweep --study ''", "linear data/coin.adm --speeds ''", &
            & "linear data/coin.adm --ucosub ''", "plot x.csv --output ''", &
            & "run ''", "linear ''", "plot ''", "animate ''", "check ''", "sweep ''"]
        character(len=:), allocatable :: program, err, expected
        integer :: status, i, at

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        do i = 1, size(lines)
            ! the option's name, or the command's for an empty positional argument
            at = index(lines(i), " -", back=.true.)
            if (at > 0) then
                expected = lines(i)(at + 1:index(lines(i), " ''") - 1)
                if (expected == "-o") expected = "--output"
                expected = expected // " was given an empty value"
            else
                expected = "an empty argument was given to rollcon"
            end if
            call run_rollcon(program, trim(lines(i)) // " -o " // scratch // "/out", scratch &
                & // "/empty.out", scratch // "/empty.err", status)
            err = file_text(scratch // "/empty.err")
            call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
                & expected) > 0 .and. .not. file_exists(scratch // "/out"), "rollcon " &
                & // trim(lines(i)) // ": exit status " // to_text(status) // ", stderr: " &
                & // err)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_empty_values

    !> Numbers outside what an option can take are refused by name before anything runs:
    !> frames per second beyond 1e6 (1e300 wrote an empty VTK series), end times no scene or
    !> dataset of the benchmarks can take (`bench scaling` ran datasets whose DTOUT exceeded END
    !> below 0.1 s, and its --end-time was never checked).
    subroutine test_numbers_out_of_range(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: lines(6) = [character(len=64) :: &
            & "run coin --vtk 1e300", "run coin --vtk 0", "bench --end-time 1e-300", &
            & "bench scaling --end-time 1e-9", "bench scaling --end-time -2", &
            & "bench scaling --end-time nan"]
        character(len=*), parameter :: expected(6) = [character(len=40) :: &
            & "--vtk needs a number of frames", "--vtk needs a number of frames", &
            & "--end-time expects a time from 1e-9", "--end-time expects a time from 1e-8", &
            & "--end-time expects a time from 1e-8", "--end-time expects one finite number"]
        character(len=:), allocatable :: program, err
        integer :: status, i

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        do i = 1, size(lines)
            call run_rollcon(program, trim(lines(i)) // " -o " // scratch // "/out", &
                & scratch // "/range.out", scratch // "/range.err", status)
            err = file_text(scratch // "/range.err")
            call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
                & trim(expected(i))) > 0 .and. .not. file_exists(scratch // "/out"), "rollcon " &
                & // trim(lines(i)) // ": exit status " // to_text(status) // ", stderr: " // err)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_numbers_out_of_range

    !> A second positional argument is refused and names itself, for run, plot and table; after
    !> a word that is neither a file nor a scene (a mistyped command, `plto x.csv`) the message
    !> says that word is not a command, and after a scene's name it does not.
    subroutine test_extra_arguments(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: commands(4) = [character(len=40) :: &
            & "coin tipping_coin", "plot a.csv b.csv", "table coin", "plto x.csv"]
        character(len=*), parameter :: extras(4) = [character(len=14) :: "'tipping_coin'", &
            & "'b.csv'", "'coin'", "'x.csv'"]
        logical, parameter :: mistyped(4) = [.false., .false., .false., .true.]
        character(len=:), allocatable :: program, err
        integer :: status, i

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        do i = 1, size(commands)
            call run_rollcon(program, trim(commands(i)) // " -o " // scratch // "/out", &
                & scratch // "/extra.out", scratch // "/extra.err", status)
            err = file_text(scratch // "/extra.err")
            call check(error, status == 1 .and. line_count(err) == 1 .and. index(err, &
                & "unexpected argument " // trim(extras(i))) > 0 .and. .not. &
                & file_exists(scratch // "/out") .and. ((index(err, "'plto' is not a command " &
                & // "(run, table, plot,") > 0) .eqv. mistyped(i)), "rollcon " &
                & // trim(commands(i)) &
                & // ": exit status " // to_text(status) // ", stderr: " // err)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_extra_arguments

    !> A number with a three-digit exponent is printed with its E, so it reads back.
    subroutine test_exponents(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "table --state 0.1,0.02,-0.01,0.3,1.2,1e-301,-0.2,-1", &
            & scratch // "/table.out", scratch // "/table.err", status)
        out = file_text(scratch // "/table.out")
        call remove_folder(scratch)
        call check(error, status == 0 .and. index(out, "1.0000000000000001E-301") > 0, &
            & "psidot = 1e-301 printed as: " // out(index(out, "psidot"):min(len(out), &
            & index(out, "psidot") + 40)))
    end subroutine test_exponents

    !> A run that fails leaves the earlier run's CSV and summary as they were, and its own
    !> rows under a name that says they are partial.
    subroutine test_failed_run(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, csv, summary, err, partial
        integer :: status, start

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch // "/good")
        call make_folder(scratch // "/bad")
        call write_lines(scratch // "/good/s.nml", [character(len=40) :: "&initial", &
            & "theta = 1.2, psidot = 2.0, phidot = -6.0", "/", "&run", "end_time = 0.2", "/"])
        call write_lines(scratch // "/bad/s.nml", [character(len=40) :: "&initial", &
            & "theta = 1.2, psidot = 2.0, phidot = -6.0", "/", "&run", "end_time = 5.0", &
            & "formulation = 'ida', rtol = 1e-10", "max_steps = 20", "/"])
        call run_rollcon(program, "-q " // scratch // "/good/s.nml -o " // scratch // "/out", &
            & scratch // "/good.out", scratch // "/good.err", status)
        csv = file_text(scratch // "/out/s.csv")
        summary = file_text(scratch // "/out/s.summary.txt")
        call check(error, status == 0 .and. len(csv) > 0 .and. index(summary, "completed") > 0, &
            & "the first run failed: " // file_text(scratch // "/good.err"))
        if (.not. allocated(error)) then
            call run_rollcon(program, "-q " // scratch // "/bad/s.nml -o " // scratch &
                & // "/out", scratch // "/bad.out", scratch // "/bad.err", status)
            err = file_text(scratch // "/bad.err")
            start = index(err, scratch // "/out/s.partial-")
            partial = ""
            if (start > 0) partial = err(start:start - 1 + index(err(start:), ".csv") + 3)
            call check(error, status == 1 .and. file_text(scratch // "/out/s.csv") == csv &
                & .and. file_text(scratch // "/out/s.summary.txt") == summary &
                & .and. len(partial) > 0 .and. index(file_text(scratch // "/bad.out"), &
                & "completed") == 0, "exit status " // to_text(status) // "; the earlier " &
                & // "files changed or no partial CSV named: " // err)
        end if
        if (.not. allocated(error)) then
            call check(error, file_exists(partial) .and. index(file_text(partial), &
                & "t,X_1,Y_1,Z_1,") == 1, "partial CSV " // partial &
                & // " missing or without header")
        end if
        call remove_folder(scratch)
    end subroutine test_failed_run

    !> A run killed after two seconds leaves the earlier run's CSV and summary as they were
    !> (not the CSV replaced and the old summary left beside it).
    subroutine test_interrupted(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, csv, summary
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch // "/short")
        call make_folder(scratch // "/long")
        call write_lines(scratch // "/short/s.nml", [character(len=40) :: "&run", &
            & "end_time = 0.2", "/"])
        call write_lines(scratch // "/long/s.nml", [character(len=40) :: "&run", &
            & "end_time = 10000.0", "/"])
        call run_rollcon(program, "-q " // scratch // "/short/s.nml -o " // scratch // "/out", &
            & scratch // "/short.out", scratch // "/short.err", status)
        csv = file_text(scratch // "/out/s.csv")
        summary = file_text(scratch // "/out/s.summary.txt")
        call check(error, status == 0 .and. len(csv) > 0 .and. len(summary) > 0, &
            & "the first run failed: " // file_text(scratch // "/short.err"))
        if (.not. allocated(error)) then
            call run_rollcon(program, "-q " // scratch // "/long/s.nml -o " // scratch &
                & // "/out > /dev/null 2>&1 & sleep 2; kill $!; wait", scratch // "/long.out", &
                & scratch // "/long.err", status)
            call check(error, file_text(scratch // "/out/s.csv") == csv .and. &
                & file_text(scratch // "/out/s.summary.txt") == summary, "the interrupted " &
                & // "run changed the earlier run's CSV or summary")
        end if
        call remove_folder(scratch)
    end subroutine test_interrupted

    !> A run killed by SIGKILL (no handler can run) three seconds in leaves its partial CSV a
    !> valid prefix of the run (docs/outputs.md): the header whole, then whole lines only (the
    !> file ends with a line end), each row as many numbers as the header has columns, every
    !> one of them read back, times strictly increasing; and rows are there (written at least
    !> once a second of wall time: three seconds give two writes at the least).
    subroutine test_killed(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, text, header, partial
        character(len=*), parameter :: folder = scratch // "/killed"
        real(wp), allocatable :: row(:)
        real(wp) :: last_time
        integer :: status, start, finish, columns, rows, stat, k, torn
        type(output_layout_type) :: layout
        type(history_type) :: history

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(folder)
        call write_lines(folder // "/s.nml", [character(len=40) :: "&run", &
            & "end_time = 100000.0", "/"])
        call run_rollcon(program, "-q " // folder // "/s.nml -o " // folder &
            & // "/out > /dev/null 2>&1 & sleep 3; kill -KILL $!; wait; ls " // folder &
            & // "/out/s.partial-*.csv", folder // "/ls.out", folder // "/ls.err", status)
        partial = trim(adjustl(file_text(folder // "/ls.out")))
        if (len(partial) > 0) then
            if (partial(len(partial):) == new_line("a")) partial = partial(:len(partial) - 1)
        end if
        call check(error, file_exists(partial), "no partial CSV after the kill: " &
            & // file_text(folder // "/ls.out") // file_text(folder // "/ls.err"))
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        text = file_text(partial)
        finish = index(text, new_line("a"))
        call check(error, finish > 0 .and. index(text, "t,X_1,Y_1,Z_1,") == 1, &
            & "header cut or missing: " // text(:min(len(text), 200)))
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        header = text(:finish - 1)
        columns = count([(header(k:k) == ",", k = 1, len(header))]) + 1
        ! a kill inside the kernel's copy of a write (page by page) leaves the last line without
        ! its end (docs/outputs.md): that tail must be the start of one row (at most the
        ! columns' commas less one: a row's length depends on its numbers, so no length bound
        ! says it), and rollcon's reader must drop it and give every whole row
        torn = 0
        if (text(len(text):) /= new_line("a")) then
            torn = len(text) - index(text, new_line("a"), back=.true.)
            call check(error, count([(text(k:k) == ",", k = len(text) - torn + 1, len(text))]) &
                & <= columns - 1, "a last line without its end holds more than one row: " &
                & // text(len(text) - torn + 1:))
            text = text(:len(text) - torn)
        end if
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        allocate(row(columns))
        rows = 0
        last_time = -huge(1.0_wp)
        start = finish + 1
        do while (start <= len(text))
            finish = start - 1 + index(text(start:), new_line("a"))
            ! each row: exactly columns numbers, read back, and its time after the last
            read(text(start:finish - 1), *, iostat=stat) row
            if (stat /= 0 .or. count([(text(k:k) == ",", k = start, finish - 1)]) &
                & /= columns - 1) then
                call check(error, .false., "row " // to_text(rows + 1) // " does not read " &
                    & // "as " // to_text(columns) // " numbers: " // text(start:finish - 1))
                exit
            end if
            if (.not. row(1) > last_time) then
                call check(error, .false., "row " // to_text(rows + 1) // ": time " &
                    & // to_text(row(1)) // " not after " // to_text(last_time))
                exit
            end if
            last_time = row(1)
            rows = rows + 1
            start = finish + 1
        end do
        if (.not. allocated(error)) call check(error, rows >= 1, "no row written in three " &
            & // "seconds before the kill")
        ! rollcon's reader (plot, animate) reads the killed run's file: every whole row
        if (.not. allocated(error)) call read_output_csv(partial, layout, history, error)
        if (.not. allocated(error)) call check(error, history%count == rows, "the reader " &
            & // "gives " // to_text(history%count) // " rows of the " // to_text(rows) &
            & // " whole ones (a torn last line of " // to_text(torn) // " characters)")
        call remove_folder(scratch)
    end subroutine test_killed

    !> Two runs of scenes with one name into one folder at once: the CSV is one run's, whole.
    subroutine test_concurrent(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, command
        type(history_type) :: history
        type(output_layout_type) :: layout
        integer :: status, z

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch // "/a")
        call make_folder(scratch // "/b")
        ! Upright, rolling at 2 m/s: stable, so Z stays near the radius (0.1 m and 0.05 m).
        call write_lines(scratch // "/a/s.nml", [character(len=48) :: "&disk", &
            & "radius = 0.1", "/", "&initial", "phidot = -20.0", "/", "&run", &
            & "end_time = 2.0, output_step = 0.001", "/"])
        call write_lines(scratch // "/b/s.nml", [character(len=48) :: "&disk", &
            & "radius = 0.05", "/", "&initial", "phidot = -40.0", "/", "&run", &
            & "end_time = 2.0, output_step = 0.001", "/"])
        command = "-q " // scratch // "/a/s.nml -o " // scratch // "/out > /dev/null 2>&1 & " &
            & // program // " -q " // scratch // "/b/s.nml -o " // scratch // "/out " &
            & // "> /dev/null 2>&1; wait"
        call run_rollcon(program, command, scratch // "/both.out", scratch // "/both.err", &
            & status)
        call read_output_csv(scratch // "/out/s.csv", layout, history, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        z = layout%part_column(1, coord_z)
        call check(error, history%count == 2001 .and. all(abs(history%rows(z, &
            & :history%count) - history%rows(z, 1)) <= tol_same_disk &
            & *history%rows(z, 1)), "rows " // to_text(history%count) // " of 2001; Z " &
            & // to_text(minval(history%rows(z, :history%count))) // " to " &
            & // to_text(maxval(history%rows(z, :history%count))) // " m")
    end subroutine test_concurrent

    !> On a 512 KiB filesystem the coin's CSV (about 550 kB) does not fit: the run fails,
    !> names the file and says nothing is completed.
    subroutine test_full_disk(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: mount_point = scratch // "/small"
        character(len=:), allocatable :: program, out, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call mount_small(mount_point, "512k", error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        call run_rollcon(program, "-q coin -o " // mount_point, scratch // "/full.out", &
            & scratch // "/full.err", status)
        call unmount(mount_point)
        out = file_text(scratch // "/full.out")
        err = file_text(scratch // "/full.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. index(out, "completed") == 0 .and. index(err, &
            & "rollcon: error: " // mount_point // "/coin.partial-") > 0 .and. index(err, &
            & "No space left on device") > 0, "exit status " // to_text(status) &
            & // "; stdout: " // out // "; stderr: " // err(max(1, index(err, "rollcon:")):))
    end subroutine test_full_disk

    !> The version the program prints and every summary records is fpm.toml's `version`.
    subroutine test_version(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: line
        character(len=:), allocatable :: version
        integer :: unit, stat, first, last

        version = ""
        open(newunit=unit, file="fpm.toml", status="old", action="read", iostat=stat)
        call check(error, stat == 0, "fpm.toml is readable from the tests' folder")
        if (allocated(error)) return
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(adjustl(line), "version") /= 1) cycle
            first = index(line, '"')
            last = index(line, '"', back=.true.)
            if (first > 0 .and. last > first) version = line(first + 1:last - 1)
            exit
        end do
        close(unit)
        call check(error, version == rollcon_version_number, "fpm.toml's version '" // version &
            & // "', rollcon_version_number '" // rollcon_version_number // "'")
        if (allocated(error)) return
        call check(error, version_text() == "rollcon " // version, "version_text: " &
            & // version_text())
    end subroutine test_version

end module test_command
