! SPDX-License-Identifier: MIT
!> Tests of `rollcon linear MODEL.adm` as a user runs it (docs/linear.md): the coin's
!> eigenvalue CSV read back equals the library's linearisation of the same dataset, with its
!> record, header and table; a scene and a missing argument are refused with the reason and
!> write nothing; a user's file of routines (a UCOSUB, force routines) gives the eigenvalues of
!> the built-in routine or of the expressions it stands for, and its faults and wrong partials
!> are named as in a run; --help gives the usage.
module test_linear_command
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_linearisation, only : linear_result_type
    use rollcon_linear_job, only : linearise_job
    use rollcon_provenance, only : user_file_record
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists
    implicit none
    private

    public :: collect_linear_command

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_linear_command"
    !> The CSV holds 17 significant digits (es24.16e3), which read back to the same double;
    !> the program and this tester run the same library code on the same input, so the values
    !> agree to the last bit: 1e-15 of the largest allows only a rounding of the text
    real(wp), parameter :: tol_csv = 1.0e-15_wp

contains

    subroutine collect_linear_command(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("coin-eigen-csv", test_coin_csv), &
            & new_unittest("refusals-write-nothing", test_refusals), &
            & new_unittest("speeds-csv-and-figure", test_speeds), &
            & new_unittest("bicycle-benchmark-eigenvalues", test_bicycle), &
            & new_unittest("ucosub-name-same-eigenvalues", test_ucosub_name), &
            & new_unittest("speeds-refused", test_speeds_refused), &
            & new_unittest("user-ucosub-same-eigenvalues", test_user_ucosub), &
            & new_unittest("user-ucosub-speeds", test_user_speeds), &
            & new_unittest("user-force-routines-same-eigenvalues", test_user_forces), &
            & new_unittest("user-routines-record-as-run", test_user_record), &
            & new_unittest("user-routine-fault-named", test_user_fault), &
            & new_unittest("user-wrong-partial-stopped", test_wrong_partial), &
            & new_unittest("help", test_help)]
    end subroutine collect_linear_command

    !> `rollcon linear data/coin.adm -o DIR` prints the table and writes DIR/coin.eigen.csv:
    !> two record lines and a line of what it holds (# comments), the header real,imag and the
    !> nine eigenvalues the library finds, no partial file left.
    subroutine test_coin_csv(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, text, out
        type(job_type) :: job
        type(linear_result_type) :: expected
        character(len=:), allocatable :: report
        real(wp), allocatable :: re(:), im(:)
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "linear data/coin.adm -q -o " // scratch // "/out", &
            & scratch // "/linear.out", scratch // "/linear.err", status)
        out = file_text(scratch // "/linear.out")
        text = file_text(scratch // "/out/coin.eigen.csv")
        call check(error, status == 0 .and. index(out, "linear analysis of data/coin.adm at " &
            & // "t = 0 s: 9 independent states") == 1 .and. index(out, "zero eigenvalues") > 0 &
            & .and. index(out, "output: " // scratch // "/out/coin.eigen.csv") > 0, &
            & "exit status " // to_text(status) // "; stdout: " // out // "; stderr: " &
            & // file_text(scratch // "/linear.err"))
        if (allocated(error)) return
        call check(error, index(text, "# rollcon ") == 1 .and. index(text, new_line("a") &
            & // "# the model's UCOSUB: disk (built in)" // new_line("a") // "# eigenvalues " &
            & // "[1/s]") > 0 .and. index(text, new_line("a") // "real,imag" // new_line("a")) &
            & > 0, "the CSV's head: " // text)
        if (allocated(error)) return
        call read_eigen_rows(text, re, im, error)
        if (allocated(error)) return
        call load_job("data/coin.adm", job, error)
        if (allocated(error)) return
        call linearise_job(job, expected, report, error)
        if (allocated(error)) return
        call check(error, size(re) == expected%reduced, "rows: " // to_text(size(re)) &
            & // ", eigenvalues: " // to_text(expected%reduced))
        if (allocated(error)) return
        associate (largest => maxval(hypot(expected%real_part, expected%imag_part)))
            call check(error, maxval(abs(re - expected%real_part) + abs(im &
                & - expected%imag_part)), 0.0_wp, "CSV against the library [1/s]", &
                & abs_tol=tol_csv*largest)
        end associate
        if (allocated(error)) return
        call check(error, count_partials(scratch // "/out") == 0, "a partial file is left in " &
            & // scratch // "/out")
        call remove_folder(scratch)
    end subroutine test_coin_csv

    !> The rows after the header `real,imag`, each two numbers.
    subroutine read_eigen_rows(text, re, im, error)
        character(len=*), intent(in) :: text
        real(wp), allocatable, intent(out) :: re(:), im(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: rest, line
        real(wp) :: pair(2)
        integer :: cut, stat

        allocate(re(0), im(0))
        rest = text(index(text, "real,imag" // new_line("a")) + 10:)
        do while (len(rest) > 0)
            cut = index(rest, new_line("a"))
            if (cut == 0) cut = len(rest) + 1
            line = rest(:cut - 1)
            rest = rest(min(cut + 1, len(rest) + 1):)
            if (len_trim(line) == 0) cycle
            read(line, *, iostat=stat) pair
            call check(error, stat == 0, "not two numbers: '" // line // "'")
            if (allocated(error)) return
            re = [re, pair(1)]
            im = [im, pair(2)]
        end do
    end subroutine read_eigen_rows

    !> How many files named *.partial-* a folder holds (through ls; 0 when none).
    integer function count_partials(folder)
        character(len=*), intent(in) :: folder
        integer :: stat

        call execute_command_line("ls " // folder // " | grep -q partial", exitstat=stat)
        count_partials = merge(1, 0, stat == 0)
    end function count_partials

    !> A scene and no argument are refused (exit status 1, the reason on stderr), and no CSV
    !> is written.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        character(len=*), parameter :: arguments(2) = [character(len=80) :: &
            & "linear data/coin.nml", "linear"]
        character(len=*), parameter :: messages(2) = [character(len=120) :: &
            & "rollcon: error: data/coin.nml: not a dataset: rollcon linear takes an ADAMS " &
            & // "dataset", "rollcon: error: rollcon linear needs a dataset, MODEL.adm"]
        character(len=:), allocatable :: err
        integer :: k, status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        do k = 1, size(arguments)
            call run_rollcon(program, trim(arguments(k)) // " -o " // scratch // "/out", &
                & scratch // "/refused.out", scratch // "/refused.err", status)
            err = file_text(scratch // "/refused.err")
            call check(error, status == 1 .and. index(err, trim(messages(k))) == 1 .and. .not. &
                & file_exists(scratch // "/out/coin.eigen.csv"), "rollcon " // trim(arguments(k)) &
                & // ": exit status " // to_text(status) // ", stderr: " // err)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_refusals

    !> `rollcon linear data/coin.adm --speeds 0.5,0.7,5 -o DIR` prints the critical speed of
    !> docs/design.md §5 (0.571925 m/s to the 6 decimals printed) and writes
    !> DIR/coin.eigen-speed.csv (the change as a # line, the header of the two kept
    !> eigenvalues, five rows whose first column is the speed, to 17 digits: 0.7 is
    !> 6.9999999999999996E-001) and its figure, nothing partial.
    subroutine test_speeds(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out, text
        integer :: status, png_size

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "linear data/coin.adm --speeds 0.5,0.7,5 -q -o " // scratch &
            & // "/out", scratch // "/speeds.out", scratch // "/speeds.err", status)
        out = file_text(scratch // "/speeds.out")
        call check(error, status == 0 .and. index(out, "stability changes at 0.571925 m/s: " &
            & // "divergent") > 0 .and. index(out, "2 after 7 structural zeros taken out") > 0, &
            & "exit status " // to_text(status) // "; stdout: " // out // "; stderr: " &
            & // file_text(scratch // "/speeds.err"))
        if (allocated(error)) return
        text = file_text(scratch // "/out/coin.eigen-speed.csv")
        call check(error, index(text, "# stability changes at 5.719249") > 0 .and. index(text, &
            & new_line("a") // "speed,real_1,imag_1,real_2,imag_2" &
            & // new_line("a") // "5.0000000000000000E-001,") > 0 .and. index(text, &
            & new_line("a") // "6.9999999999999996E-001,") > 0, &
            & "the CSV: " // text)
        if (allocated(error)) return
        png_size = 0
        inquire(file=scratch // "/out/coin.eigen-speed.png", size=png_size)
        call check(error, png_size > 0 .and. count_partials(scratch // "/out") == 0, &
            & "the figure's size " // to_text(png_size) // ", or a partial file left")
        call remove_folder(scratch)
    end subroutine test_speeds

    !> `rollcon linear data/bicycle.adm -o DIR`, as the README shows it: the CSV holds the
    !> benchmark's four non-zero eigenvalues at 5 m/s (Meijaard et al. 2007, Table 2) to 1e-6
    !> relative, the issue's demand (the library's suite `bicycle` measures 3e-11), and six
    !> zeros.
    subroutine test_bicycle(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        real(wp), allocatable :: re(:), im(:)
        real(wp), parameter :: paper_re(4) = [-14.0783896927982_wp, -0.775341882195845_wp, &
            & -0.775341882195845_wp, -0.322866429004087_wp], paper_im(4) = [0.0_wp, &
            & 4.46486771378823_wp, -4.46486771378823_wp, 0.0_wp]
        integer :: status, k, nearest

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "linear data/bicycle.adm -q -o " // scratch // "/out", &
            & scratch // "/bicycle.out", scratch // "/bicycle.err", status)
        out = file_text(scratch // "/bicycle.out")
        call check(error, status == 0 .and. index(out, "zero eigenvalues") > 0, "exit status " &
            & // to_text(status) // "; stderr: " // file_text(scratch // "/bicycle.err"))
        if (allocated(error)) return
        call read_eigen_rows(file_text(scratch // "/out/bicycle.eigen.csv"), re, im, error)
        if (allocated(error)) return
        call check(error, size(re) == 10 .and. count(hypot(re, im) < 1.0e-6_wp) == 6, &
            & to_text(size(re)) // " eigenvalues, " // to_text(count(hypot(re, im) &
            & < 1.0e-6_wp)) // " of them zero; expected 10 and 6")
        do k = 1, 4
            if (allocated(error)) exit
            nearest = minloc(hypot(re - paper_re(k), im - paper_im(k)), 1)
            call check(error, hypot(re(nearest) - paper_re(k), im(nearest) - paper_im(k)) &
                & <= 1.0e-6_wp*hypot(paper_re(k), paper_im(k)), "the paper's " &
                & // to_text(paper_re(k)) // " + " // to_text(paper_im(k)) // " i: found " &
                & // to_text(re(nearest)) // " + " // to_text(im(nearest)) // " i")
        end do
        call remove_folder(scratch)
    end subroutine test_bicycle

    !> `--ucosub rolling_disk` (a built-in routine by name) serves data/coin.adm's UCONs, which
    !> name none: the eigenvalues are those of the hand-checked disk, the default, to 1e-12 of
    !> the largest (two routines of the same constraint, their round-off apart).
    subroutine test_ucosub_name(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        real(wp), allocatable :: re(:, :), im(:, :), r(:), i(:)
        character(len=*), parameter :: options(2) = [character(len=24) :: "", &
            & "--ucosub rolling_disk"]
        integer :: status, k

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        do k = 1, 2
            call run_rollcon(program, "linear data/coin.adm " // trim(options(k)) // " -q -o " &
                & // scratch // "/out", scratch // "/name.out", scratch // "/name.err", status)
            call check(error, status == 0, "linear data/coin.adm " // trim(options(k)) &
                & // ": exit status " // to_text(status) // ", stderr: " &
                & // file_text(scratch // "/name.err"))
            if (allocated(error)) exit
            call read_eigen_rows(file_text(scratch // "/out/coin.eigen.csv"), r, i, error)
            if (allocated(error)) exit
            if (k == 1) allocate(re(size(r), 2), im(size(r), 2))
            call check(error, size(r) == size(re, 1), "eigenvalue counts differ")
            if (allocated(error)) exit
            re(:, k) = r
            im(:, k) = i
        end do
        if (.not. allocated(error)) call check(error, maxval(abs(re(:, 1) - re(:, 2)) &
            & + abs(im(:, 1) - im(:, 2))), 0.0_wp, "disk against rolling_disk [1/s]", &
            & abs_tol=1.0e-12_wp*maxval(hypot(re(:, 1), im(:, 1))))
        call remove_folder(scratch)
    end subroutine test_ucosub_name

    !> A grid that is not FROM,TO,COUNT with 0 <= FROM < TO and a whole COUNT >= 2 is refused
    !> naming the option, and nothing is written.
    subroutine test_speeds_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        character(len=*), parameter :: grids(4) = [character(len=16) :: "0.5,0.7", &
            & "0.7,0.5,5", "0,1,2.5", "-1,1,3"]
        integer :: k, status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        do k = 1, size(grids)
            call run_rollcon(program, "linear data/coin.adm --speeds " // trim(grids(k)) &
                & // " -o " // scratch // "/out", scratch // "/bad.out", scratch // "/bad.err", &
                & status)
            err = file_text(scratch // "/bad.err")
            call check(error, status == 1 .and. index(err, "rollcon: error: --speeds expects") &
                & == 1 .and. .not. file_exists(scratch // "/out/coin.eigen-speed.csv"), &
                & "--speeds " // trim(grids(k)) // ": exit status " // to_text(status) &
                & // ", stderr: " // err)
            if (allocated(error)) exit
        end do
        call remove_folder(scratch)
    end subroutine test_speeds_refused

    !> `rollcon linear --help` prints the command's usage and exits 0.
    subroutine test_help(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "linear --help", scratch // "/help.out", scratch &
            & // "/help.err", status)
        out = file_text(scratch // "/help.out")
        call check(error, status == 0 .and. index(out, "usage: rollcon linear MODEL.adm " &
            & // "[--output DIR]") == 1 .and. index(out, "real,imag [1/s]") > 0, &
            & "exit status " // to_text(status) // ", stdout: " // out)
        call remove_folder(scratch)
    end subroutine test_help

    !> `rollcon linear ARGUMENTS -q -o DIR` (DIR under the scratch folder, named by tag): the
    !> eigenvalues of the CSV it writes, DIR/STEM.eigen.csv, and its stdout.
    subroutine linear_eigenvalues(program, arguments, stem, tag, re, im, out, error)
        character(len=*), intent(in) :: program, arguments, stem, tag
        real(wp), allocatable, intent(out) :: re(:), im(:)
        character(len=:), allocatable, intent(out) :: out
        type(error_type), allocatable, intent(out) :: error
        integer :: status

        call run_rollcon(program, "linear " // arguments // " -q -o " // scratch // "/" // tag, &
            & scratch // "/" // tag // ".out", scratch // "/" // tag // ".err", status)
        out = file_text(scratch // "/" // tag // ".out")
        call check(error, status == 0, "linear " // arguments // ": exit status " &
            & // to_text(status) // ", stderr: " // file_text(scratch // "/" // tag // ".err"))
        if (allocated(error)) return
        call read_eigen_rows(file_text(scratch // "/" // tag // "/" // stem // ".eigen.csv"), &
            & re, im, error)
    end subroutine linear_eigenvalues

    !> `rollcon linear data/coin.adm --ucosub ucon/adams/rolling_disk/ucosub.f`: the generated
    !> rolling disk as a user's file, compiled and run in a child process, gives the
    !> eigenvalues of the hand-checked built-in disk (the default) to 1e-10 of the largest: the
    !> two routines are one constraint, written apart and compiled with other flags, so their
    !> partials differ by rounding (1e-16 relative), which the linearisation's differences of
    !> relative step 2e-3 raise to about 1e-13 in A_red; its own error is about 1e-10 of the
    !> largest entry (docs/linear.md). The CSV's record names the file.
    subroutine test_user_ucosub(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        real(wp), allocatable :: re(:), im(:), re_file(:), im_file(:)

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call linear_eigenvalues(program, "data/coin.adm", "coin", "builtin", re, im, out, &
            & error)
        if (allocated(error)) return
        call linear_eigenvalues(program, "data/coin.adm --ucosub " &
            & // "ucon/adams/rolling_disk/ucosub.f", "coin", "file", re_file, im_file, out, error)
        if (allocated(error)) return
        call check(error, size(re_file) == size(re) .and. size(re) == 9, "eigenvalues: " &
            & // to_text(size(re_file)) // " with the file, " // to_text(size(re)) &
            & // " with the built-in disk; expected 9")
        if (allocated(error)) return
        call check(error, maxval(abs(re_file - re) + abs(im_file - im)), 0.0_wp, &
            & "user's file against the built-in disk [1/s]", &
            & abs_tol=1.0e-10_wp*maxval(hypot(re, im)))
        if (allocated(error)) return
        call check(error, index(file_text(scratch // "/file/coin.eigen.csv"), &
            & "ucon/adams/rolling_disk/ucosub.f") > 0, "the CSV's record does not name the file")
        call remove_folder(scratch)
    end subroutine test_user_ucosub

    !> `--speeds 0.5,0.7,5` with the user's file: the critical speed of docs/design.md §5 to
    !> the 6 decimals printed, as with the built-in disk (test_speeds).
    subroutine test_user_speeds(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "linear data/coin.adm --ucosub ucon/adams/rolling_disk/" &
            & // "ucosub.f --speeds 0.5,0.7,5 -q -o " // scratch // "/out", scratch &
            & // "/speeds.out", scratch // "/speeds.err", status)
        out = file_text(scratch // "/speeds.out")
        call check(error, status == 0 .and. index(out, "stability changes at 0.571925 m/s: " &
            & // "divergent") > 0 .and. index(out, "2 after 7 structural zeros taken out") > 0 &
            & .and. file_exists(scratch // "/out/coin.eigen-speed.csv"), "exit status " &
            & // to_text(status) // "; stdout: " // out // "; stderr: " &
            & // file_text(scratch // "/speeds.err"))
        call remove_folder(scratch)
    end subroutine test_user_speeds

    !> test/user_forces/user_forces.adm with its SFOSUB and GFOSUB (two files, run apart)
    !> linearised where it starts gives the eigenvalues of user_forces_expressions.adm, the same
    !> forces as FUNCTION expressions, to 1e-9 of the largest: the two compute one force to
    !> rounding, and the linearisation's differences raise that to about 1e-13 of A's scale;
    !> 1e-9 leaves room for the stiff spring (1000 N/m on 1 kg) against the GFORCE's bushing.
    subroutine test_user_forces(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        real(wp), allocatable :: re(:), im(:), re_user(:), im_user(:)

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call linear_eigenvalues(program, "test/user_forces/user_forces_expressions.adm", &
            & "user_forces_expressions", "expressions", re, im, out, error)
        if (allocated(error)) return
        call linear_eigenvalues(program, "test/user_forces/user_forces.adm --ucosub " &
            & // "test/user_forces/sforce_spring.f --ucosub test/user_forces/gforce_bushing.f", &
            & "user_forces", "routines", re_user, im_user, out, error)
        if (allocated(error)) return
        call check(error, size(re_user) == size(re) .and. size(re) > 0, "eigenvalues: " &
            & // to_text(size(re_user)) // " with the routines, " // to_text(size(re)) &
            & // " with the expressions")
        if (allocated(error)) return
        call check(error, maxval(abs(re_user - re) + abs(im_user - im)), 0.0_wp, &
            & "routines against expressions [1/s]", abs_tol=1.0e-9_wp*maxval(hypot(re, im)))
        call remove_folder(scratch)
    end subroutine test_user_forces

    !> `rollcon linear` with two files of force routines (user_forces.adm, no UCON) words its
    !> CSV's record as `rollcon run` words its summary's, each file by what the child found
    !> it defines: "the model's UCOSUB: none (the model has no UCON)", then "user routines:
    !> FILE (SFOSUB; size and hash)" and "(GFOSUB; ...)"; not the older wording that named the
    !> first file as the model's UCOSUB and the second "more user routines".
    subroutine test_user_record(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: spring = "test/user_forces/sforce_spring.f", &
            & bushing = "test/user_forces/gforce_bushing.f"
        character(len=1), parameter :: nl = new_line("a")
        character(len=:), allocatable :: program, files, lines(:), csv, summary
        integer :: status, k
        logical :: worded(2)

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        files = "test/user_forces/user_forces.adm --ucosub " // spring // " --ucosub " // bushing
        call run_rollcon(program, "linear " // files // " -q -o " // scratch // "/record", &
            & scratch // "/record.out", scratch // "/record.err", status)
        call check(error, status == 0, "linear: exit status " // to_text(status) &
            & // ", stderr: " // file_text(scratch // "/record.err"))
        if (allocated(error)) return
        call run_rollcon(program, "run " // files // " --end 0.01 --steps 1 -q -o " // scratch &
            & // "/record", scratch // "/run.out", scratch // "/run.err", status)
        call check(error, status == 0, "run: exit status " // to_text(status) // ", stderr: " &
            & // file_text(scratch // "/run.err"))
        if (allocated(error)) return
        lines = [character(len=200) :: "the model's UCOSUB: none (the model has no UCON)", &
            & "user routines: " // spring // " (SFOSUB; " // user_file_record(spring) // ")", &
            & "user routines: " // bushing // " (GFOSUB; " // user_file_record(bushing) // ")"]
        csv = file_text(scratch // "/record/user_forces.eigen.csv")
        summary = file_text(scratch // "/record/user_forces.adm.summary.txt")
        ! the lines in order, each whole: the summary's plain, the CSV's as # comments
        worded = .true.
        do k = 1, size(lines) - 1
            worded(1) = worded(1) .and. index(summary, nl // trim(lines(k)) // nl &
                & // trim(lines(k + 1)) // nl) > 0
            worded(2) = worded(2) .and. index(csv, nl // "# " // trim(lines(k)) // nl // "# " &
                & // trim(lines(k + 1)) // nl) > 0
        end do
        call check(error, worded(1), "the run's record is not worded as expected: " &
            & // summary(:min(len(summary), 600)))
        if (allocated(error)) return
        call check(error, worded(2) .and. index(csv, "more user routines") == 0, "the linear " &
            & // "CSV's record is not worded as the run's summary: " // csv(:min(len(csv), 600)))
        call remove_folder(scratch)
    end subroutine test_user_record

    !> A UCOSUB that stops the program (test/faulty_ucosubs/stops.f) ends the child process
    !> of the linear analysis, not rollcon: exit status 1, the message naming the routine's
    !> call and quoting its STOP, and no CSV.
    subroutine test_user_fault(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "linear data/coin.adm --ucosub test/faulty_ucosubs/stops.f " &
            & // "-q -o " // scratch // "/out", scratch // "/fault.out", scratch &
            & // "/fault.err", status)
        err = file_text(scratch // "/fault.err")
        call check(error, status == 1 .and. index(err, "rollcon: error: data/coin.adm: ") == 1 &
            & .and. index(err, "the linear analysis did not complete") > 0 .and. index(err, &
            & "UCON/") > 0 .and. .not. file_exists(scratch // "/out/coin.eigen.csv"), &
            & "exit status " // to_text(status) // ", stderr: " // err)
        call remove_folder(scratch)
    end subroutine test_user_fault

    !> test/turntable/turntable_half_coriolis.f (two partials halved) is checked at the
    !> consistent start, as a run's routine is: exit status 1 before any linearisation, both
    !> entries named with the values returned and differenced, the full check's command and
    !> --no-check; the right routine, test/turntable/turntable.f, passes and writes its CSV.
    subroutine test_wrong_partial(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, err
        integer :: status, status_right

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call run_rollcon(program, "linear test/turntable/turntable.adm --ucosub " &
            & // "test/turntable/turntable_half_coriolis.f -q -o " // scratch // "/wrong", &
            & scratch // "/wrong.out", scratch // "/wrong.err", status)
        call run_rollcon(program, "linear test/turntable/turntable.adm --ucosub " &
            & // "test/turntable/turntable.f -q -o " // scratch // "/right", &
            & scratch // "/right.out", scratch // "/right.err", status_right)
        err = file_text(scratch // "/wrong.err")
        call check(error, status == 1 .and. index(err, "UCON/1 (line 8) ARRAY(2) = dF/d(Y_2) " &
            & // "[derivative]: returned 1.75, differences give 3.5") > 0 .and. index(err, &
            & "UCON/2 (line 9) ARRAY(1) = dF/d(X_2) [derivative]: returned -1.75, differences " &
            & // "give -3.5") > 0 .and. index(err, "rollcon check test/turntable/turntable_half_" &
            & // "coriolis.f --model test/turntable/turntable.adm") > 0 .and. index(err, &
            & "--no-check") > 0 .and. .not. file_exists(scratch // "/wrong/turntable.eigen.csv"), &
            & "exit status " // to_text(status) // ", stderr: " // err)
        if (allocated(error)) return
        call check(error, status_right == 0 .and. file_exists(scratch &
            & // "/right/turntable.eigen.csv"), "the right routine: exit status " &
            & // to_text(status_right) // ", stderr: " // file_text(scratch // "/right.err"))
        call remove_folder(scratch)
    end subroutine test_wrong_partial

end module test_linear_command
