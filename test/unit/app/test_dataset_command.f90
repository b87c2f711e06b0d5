! SPDX-License-Identifier: MIT
!> Tests of `rollcon run MODEL.adm` as an ADAMS user runs it: the coin's dataset gives the
!> coin scene's rows, with the hand routine named on the command line or the user's own
!> ucosub.f compiled and run apart; the model's routine checked with `check --model`; a dataset
!> of two parts run, plotted and animated; refusals of a missing or unknown routine.
module test_dataset_command
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : output_layout_type, coord_x, coord_phidot
    use rollcon_simulation, only : history_type
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists, line_count
    implicit none
    private

    public :: collect_dataset_command

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_dataset_command"
    !> The generated rolling disk's ADAMS-ready routine: a user's ucosub.f
    character(len=*), parameter :: user_file = "ucon/adams/rolling_disk/ucosub.f"
    !> The user's fixed-form routine and the hand routine compute the same no-slip constraint
    !> with other arithmetic (and the user's is asked for the time partials the hand routine
    !> skips), so the integrators take other steps: the rows agree to the run's accuracy, not to
    !> round-off. The coin's motion after the strike amplifies small differences (it tips and
    !> recovers twice a second): measured on the release build, the centre paths of the two
    !> routines differ by 8.9e-5 m over the 10 s, and those of rtol 1e-8 and 1e-9 by 1.7e-4 m.
    !> 2e-3 m is ten times that, and a hundred times below the 0.25 m the centre swerves: a
    !> routine with a wrong entry puts the disk on another path
    real(wp), parameter :: tol_other_routine = 2.0e-3_wp

contains

    !> Tests of this suite.
    subroutine collect_dataset_command(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("coin-adm-is-coin-nml", test_coin_adm), &
            & new_unittest("user-ucosub-file", test_user_file), &
            & new_unittest("check-model-routine", test_check_model), &
            & new_unittest("two-parts-run-and-pictures", test_two_parts), &
            & new_unittest("default-and-unknown-routine", test_refusals), &
            & new_unittest("forgotten-ucosub-hint", test_forgotten_ucosub), &
            & new_unittest("user-routine-checked-before-run", test_checked_before_run), &
            & new_unittest("contact-dataset-as-its-scene", test_contact_dataset)]
    end subroutine collect_dataset_command

    !> `run data/coin.adm --ucosub disk` writes the rows `run coin` writes, bit for bit, under
    !> the dataset's part id, with its summary and part shapes. Run into one folder, the two
    !> keep their own outputs: coin.adm.csv, .summary.txt, .parts beside coin.csv, ...
    subroutine test_coin_adm(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, summary
        type(output_layout_type) :: adm_layout, nml_layout
        type(history_type) :: adm_rows, nml_rows
        integer :: status_adm, status_nml

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run data/coin.adm --ucosub disk -q -o " // scratch // "/both", &
            & scratch // "/adm.out", scratch // "/adm.err", status_adm)
        call run_rollcon(program, "run coin -q -o " // scratch // "/both", scratch // "/nml.out", &
            & scratch // "/nml.err", status_nml)
        summary = file_text(scratch // "/both/coin.adm.summary.txt")
        ! after the provenance's two lines (rollcon_provenance)
        call check(error, status_adm == 0 .and. status_nml == 0 .and. index(summary, &
            & new_line("a") // "dataset coin (data/coin.adm): IDA") > 0 .and. index(summary, &
            & "status: completed at t = 10 s") > 0 .and. file_exists(scratch &
            & // "/both/coin.adm.parts") .and. file_exists(scratch // "/both/coin.parts") .and. &
            & index(file_text(scratch // "/both/coin.summary.txt"), "scene coin") > 0, &
            & "exit statuses " // to_text(status_adm) // ", " // to_text(status_nml) &
            & // "; summary: " // summary)
        if (.not. allocated(error)) call read_output_csv(scratch // "/both/coin.adm.csv", &
            & adm_layout, adm_rows, error)
        if (.not. allocated(error)) call read_output_csv(scratch // "/both/coin.csv", nml_layout, &
            & nml_rows, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, adm_layout%part_ids(1) == 2 .and. nml_layout%part_ids(1) == 1 &
            & .and. adm_rows%count == 1001 .and. adm_rows%count == nml_rows%count, &
            & "part ids and row counts")
        if (allocated(error)) return
        ! t, the part's 12 columns and E up to the strike (rows 1..201, t <= 2 s): the same
        ! equations, the same stops, the same steps. Past it the dataset's GFORCE gives the
        ! Newton matrix its exact partials and the scene's strike none, so the histories part
        ! at round-off (the equations themselves agree bit for bit: adm-build's
        ! coin-adm-as-coin-nml)
        call check(error, all(adm_rows%rows(:adm_layout%energy_column(), :201) &
            & == nml_rows%rows(:nml_layout%energy_column(), :201)) .and. &
            & adm_rows%rows(1, 201) == 2.0_wp, "data/coin.adm's rows differ from " &
            & // "data/coin.nml's before the strike")
    end subroutine test_coin_adm

    !> The ADAMS user's own ucosub.f, compiled and run in a child process, serves the dataset's
    !> UCONs: its rows are the built-in routine's to the run's accuracy.
    subroutine test_user_file(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        type(output_layout_type) :: user_layout, own_layout
        type(history_type) :: user_rows, own_rows
        integer :: status_user, status_own
        real(wp) :: distance

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run data/coin.adm --ucosub " // user_file // " -q -o " &
            & // scratch // "/user", scratch // "/user.out", scratch // "/user.err", status_user)
        call run_rollcon(program, "run data/coin.adm --ucosub disk -q -o " // scratch &
            & // "/own", scratch // "/own.out", scratch // "/own.err", status_own)
        call check(error, status_user == 0 .and. status_own == 0, "exit statuses " &
            & // to_text(status_user) // ", " // to_text(status_own) // "; stderr: " &
            & // file_text(scratch // "/user.err"))
        if (.not. allocated(error)) call read_output_csv(scratch // "/user/coin.adm.csv", &
            & user_layout, user_rows, error)
        if (.not. allocated(error)) call read_output_csv(scratch // "/own/coin.adm.csv", &
            & own_layout, own_rows, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, user_rows%count == own_rows%count, "row counts " &
            & // to_text(user_rows%count) // ", " // to_text(own_rows%count))
        if (allocated(error)) return
        associate (x => user_layout%part_column(1, coord_x))
            distance = maxval(abs(user_rows%rows(x:x + 2, :user_rows%count) &
                & - own_rows%rows(x:x + 2, :own_rows%count)))
        end associate
        call check(error, distance < tol_other_routine, "the centre paths differ by " &
            & // to_text(distance) // " m")
    end subroutine test_user_file

    !> `check FILE --model MODEL.adm` checks every UCON the model's routine serves, with the
    !> dataset's ids and PAR, each headed by its statement and line.
    subroutine test_check_model(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "check " // user_file // " --model data/coin.adm --states 5", &
            & scratch // "/check.out", scratch // "/check.err", status)
        out = file_text(scratch // "/check.out")
        call remove_folder(scratch)
        call check(error, status == 0 .and. index(out, "UCON/1 (line 38)  PAR = 2, 21, 22, 23, " &
            & // "14, 15, 24, 25, 26, 0.1, 1") > 0 .and. index(out, "UCON/3 (line 40)  PAR = " &
            & // "2,") > 0 .and. &
            & index(out, "verdict: CLEAN: 3 UCON(s) checked") > 0, "exit status " &
            & // to_text(status) // ", report: " // out)
    end subroutine test_check_model

    !> A dataset of two parts with built-in routines named by ROUTINE= runs with no --ucosub;
    !> its CSV, disk_and_sphere.adm.csv, holds both parts, and plot (given the dataset, as run
    !> was) and animate (given the CSV) draw it.
    subroutine test_two_parts(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, folder
        type(output_layout_type) :: layout
        type(history_type) :: rows
        integer :: status_run, status_plot, status_animate

        call rollcon_program(program, error)
        if (allocated(error)) return
        folder = scratch // "/two"
        call make_folder(scratch)
        call run_rollcon(program, "run data/disk_and_sphere.adm -q -o " // folder, scratch &
            & // "/run.out", scratch // "/run.err", status_run)
        call run_rollcon(program, "plot data/disk_and_sphere.adm -o " // folder, &
            & scratch // "/plot.out", scratch // "/plot.err", status_plot)
        call run_rollcon(program, "animate " // folder // "/disk_and_sphere.adm.csv -o " &
            & // folder, scratch // "/animate.out", scratch // "/animate.err", status_animate)
        call check(error, status_run == 0 .and. status_plot == 0 .and. status_animate == 0 &
            & .and. file_exists(folder // "/disk_and_sphere.adm_path.png") .and. &
            & file_exists(folder // "/disk_and_sphere.adm.gif"), "exit statuses " &
            & // to_text(status_run) // ", " &
            & // to_text(status_plot) // ", " // to_text(status_animate) // "; stderr: " &
            & // file_text(scratch // "/run.err") // file_text(scratch // "/plot.err") &
            & // file_text(scratch // "/animate.err"))
        if (.not. allocated(error)) call read_output_csv(folder // "/disk_and_sphere.adm.csv", &
            & layout, rows, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, all(layout%part_ids == [2, 3]) .and. size(layout%ucon_ids) == 6 &
            & .and. layout%column("Fn") == 0 .and. layout%part_column(2, coord_phidot) == 25, &
            & "layout of the two parts")
    end subroutine test_two_parts

    !> An unknown routine name is refused in one line with exit status 1, naming it and the
    !> built-in routines; with no --ucosub, a dataset's UCONs that name no ROUTINE are served
    !> by rollcon's own routine, the hand-checked disk, as a scene's are.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: names = "(disk, rolling_disk, chaplygin_sled, " &
            & // "disk_height, gnd_atpoint, gnd_homokinetic, gnd_inline, gnd_inplane, " &
            & // "gnd_motion_angle, gnd_orientation, gnd_parallel_axes, gnd_perpendicular, " &
            & // "jp_atpoint, jp_homokinetic, jp_inline, jp_inplane, jp_motion_angle, " &
            & // "jp_orientation, jp_parallel_axes, jp_perpendicular, knife_edge, planar_hold, " &
            & // "rolling_sphere, turntable_ball, turntable_disk)"
        character(len=:), allocatable :: program, unknown, summary
        integer :: status_default, status_unknown

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run data/coin.adm -q -o " // scratch // "/default", scratch &
            & // "/default.out", scratch // "/default.err", status_default)
        call run_rollcon(program, "run data/coin.adm --ucosub no_such_routine -q -o " &
            & // scratch // "/unknown", scratch // "/unknown.out", scratch // "/unknown.err", &
            & status_unknown)
        summary = file_text(scratch // "/default/coin.adm.summary.txt")
        unknown = file_text(scratch // "/unknown.err")
        call check(error, status_default == 0 .and. index(summary, "status: completed") > 0, &
            & "exit status " // to_text(status_default) // ", summary: " // summary)
        if (.not. allocated(error)) call check(error, status_unknown == 1 .and. &
            & line_count(unknown) == 1 .and. index(unknown, "rollcon: error: --ucosub " &
            & // "no_such_routine: no such file, and not a built-in routine " // names) == 1 &
            & .and. .not. file_exists(scratch // "/unknown"), "exit status " &
            & // to_text(status_unknown) // ", stderr: " // unknown)
        call remove_folder(scratch)
    end subroutine test_refusals

    !> The ball on a turntable with its ROUTINE=turntable_ball taken away (an ADAMS user's
    !> dataset, whose UCOSUB is given apart) and run without --ucosub: the hand-checked disk
    !> refuses UCON/1's PAR, and the one-line error adds that the model's UCOSUB served it, that
    !> its PAR suits the built-in turntable_ball, how to choose it, and the built-in routines.
    !> Following the hint (--ucosub turntable_ball) runs it.
    subroutine test_forgotten_ucosub(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: expected(4) = [character(len=100) :: &
            & "rollcon: error: UCON/1: PAR(2) must be code 21 (codes 21 22 23 14 15 24 25 26", &
            & "this UCON names no ROUTINE, so the model's UCOSUB served it, here the built-in", &
            & "its PAR suits the built-in turntable_ball: run with --ucosub turntable_ball", &
            & "(built-in routines: disk, rolling_disk, chaplygin_sled, disk_height, gnd_atpoint"]
        character(len=:), allocatable :: program, model, refused
        integer :: status_default, status_hinted, i
        logical :: complete

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        model = scratch // "/ball.adm"
        ! no ROUTINE lines; 0.2 s of the motion, not 20 turns
        call execute_command_line("sed -e '/^, ROUTINE=/d' -e 's|^SIMULATE.*|SIMULATE/" &
            & // "DYNAMIC, END=0.2, STEPS=20|' data/ball_on_turntable.adm > " // model)
        call run_rollcon(program, "run " // model // " -q -o " // scratch // "/default", &
            & scratch // "/default.out", scratch // "/default.err", status_default)
        call run_rollcon(program, "run " // model // " --ucosub turntable_ball -q -o " &
            & // scratch // "/hinted", scratch // "/hinted.out", scratch // "/hinted.err", &
            & status_hinted)
        refused = file_text(scratch // "/default.err")
        complete = index(file_text(scratch // "/hinted/ball.adm.summary.txt"), &
            & "status: completed") > 0
        call remove_folder(scratch)
        call check(error, status_default == 1 .and. line_count(refused) == 1, "exit status " &
            & // to_text(status_default) // ", stderr: " // refused)
        do i = 1, size(expected)
            if (allocated(error)) return
            call check(error, index(refused, trim(expected(i))) > 0, "the error lacks '" &
                & // trim(expected(i)) // "': " // refused)
        end do
        if (.not. allocated(error)) call check(error, status_hinted == 0 .and. complete, &
            & "with --ucosub turntable_ball: exit status " // to_text(status_hinted))
    end subroutine test_forgotten_ucosub

    !> `run MODEL.adm --ucosub FILE` checks the routine at the consistent start first:
    !> test/turntable/turntable.adm (a
    !> puck carried round at 3.5 rad/s by two velocity UCONs) with its right routine runs with
    !> nothing on stderr and ends, one turn later, where X = 0.1 cos(W t), Y = 0.1 sin(W t)
    !> put it, (0.1, 0) m: measured 2.2e-8 m off at rtol 1e-8 (the dataset's default), so
    !> 2e-7 m catches a tenfold loss. With the slipped twin (dF/dX, dF/dY half their value)
    !> the run is not started (exit 1, no CSV): stderr names both wrong entries and their
    !> values, the full check's command and --no-check, with which it runs (exit 0); on CVODE
    !> (test/turntable/turntable_cvode.adm) it stalls the steps, and the failure names the
    !> check's command.
    subroutine test_checked_before_run(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: model = "test/turntable/turntable.adm"
        character(len=*), parameter :: tol_turn = "2e-7 m"
        real(wp), parameter :: tol_end = 2.0e-7_wp
        character(len=:), allocatable :: program, right_err, slipped_err, unchecked_err
        type(output_layout_type) :: layout
        type(history_type) :: rows
        integer :: status_right, status_slipped, status_unchecked, x
        logical :: slipped_csv

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run " // model // " --ucosub test/turntable/turntable.f " &
            & // "-q -o " // scratch // "/right", scratch // "/right.out", scratch &
            & // "/right.err", status_right)
        call run_rollcon(program, "run " // model // " --ucosub " &
            & // "test/turntable/turntable_half_coriolis.f -q -o " // scratch // "/slipped", &
            & scratch // "/slipped.out", scratch // "/slipped.err", status_slipped)
        call run_rollcon(program, "run " // model // " --ucosub " &
            & // "test/turntable/turntable_half_coriolis.f --no-check -q -o " // scratch &
            & // "/unchecked", scratch // "/unchecked.out", scratch // "/unchecked.err", &
            & status_unchecked)
        right_err = file_text(scratch // "/right.err")
        slipped_err = file_text(scratch // "/slipped.err")
        unchecked_err = file_text(scratch // "/unchecked.err")
        slipped_csv = file_exists(scratch // "/slipped/turntable.adm.csv")
        call read_output_csv(scratch // "/right/turntable.adm.csv", layout, rows, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, status_right == 0 .and. len_trim(right_err) == 0, &
            & "the right routine: exit " // to_text(status_right) // ", stderr: " // right_err)
        if (allocated(error)) return
        x = layout%part_column(1, coord_x)
        call check(error, abs(rows%rows(x, rows%count) - 0.1_wp) <= tol_end .and. &
            & abs(rows%rows(x + 1, rows%count)) <= tol_end, "after one turn (X, Y) = (" &
            & // to_text(rows%rows(x, rows%count)) // ", " // to_text(rows%rows(x + 1, &
            & rows%count)) // ") m, not (0.1, 0) within " // tol_turn)
        if (allocated(error)) return
        call check(error, status_slipped /= 0 .and. index(slipped_err, "fails its check") > 0 &
            & .and. index(slipped_err, "UCON/1 (line 8) ARRAY(2) = dF/d(Y_2) [derivative]: " &
            & // "returned 1.75, differences give 3.5") > 0 .and. index(slipped_err, &
            & "UCON/2 (line 9) ARRAY(1) = dF/d(X_2)") > 0 .and. index(slipped_err, &
            & "rollcon check test/turntable/turntable_half_coriolis.f --model " // model) > 0 &
            & .and. index(slipped_err, "--no-check") > 0 .and. .not. slipped_csv, &
            & "the slipped routine: exit " // to_text(status_slipped) // ", stderr: " &
            & // slipped_err)
        if (allocated(error)) return
        call check(error, status_unchecked == 0 .and. len_trim(unchecked_err) == 0, &
            & "--no-check: exit " // to_text(status_unchecked) // ", stderr: " // unchecked_err)
        if (allocated(error)) return
        ! on CVODE the slipped routine's Newton matrix stalls the steps (CV_TOO_MUCH_WORK within
        ! the 2000 steps the dataset allows): the failure points at the check
        call make_folder(scratch)
        call run_rollcon(program, "run test/turntable/turntable_cvode.adm --ucosub " &
            & // "test/turntable/turntable_half_coriolis.f --no-check -q -o " // scratch &
            & // "/cvode", scratch // "/cvode.out", scratch // "/cvode.err", status_unchecked)
        unchecked_err = file_text(scratch // "/cvode.err")
        call remove_folder(scratch)
        call check(error, status_unchecked /= 0 .and. index(unchecked_err, "CVODE") > 0 .and. &
            & index(unchecked_err, "rollcon check test/turntable/turntable_half_coriolis.f " &
            & // "--model test/turntable/turntable_cvode.adm checks them at many states") > 0, &
            & "a failed run with a user's routine: exit " // to_text(status_unchecked) &
            & // ", stderr: " // unchecked_err)
    end subroutine test_checked_before_run

    !> `run data/sliding_coin.adm` (the coin on an ADAMS CONTACT) through the program completes
    !> and lists in its summary the one switch `run data/sliding_coin.nml` lists, at the same
    !> instant to every digit written (the same equations, routine and tolerances:
    !> contact-datasets measures 0 between them), both exiting 0.
    subroutine test_contact_dataset(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: switch = " s: sliding → rolling"
        character(len=:), allocatable :: program, adm, nml, line_adm, line_nml
        integer :: status_adm, status_nml

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call run_rollcon(program, "run data/sliding_coin.adm -q -o " // scratch // "/contact", &
            & scratch // "/adm.out", scratch // "/adm.err", status_adm)
        call run_rollcon(program, "run data/sliding_coin.nml -q -o " // scratch // "/contact", &
            & scratch // "/nml.out", scratch // "/nml.err", status_nml)
        adm = file_text(scratch // "/contact/sliding_coin.adm.summary.txt")
        nml = file_text(scratch // "/contact/sliding_coin.summary.txt")
        call remove_folder(scratch)
        line_adm = switch_line(adm)
        line_nml = switch_line(nml)
        call check(error, status_adm == 0 .and. status_nml == 0 .and. index(adm, &
            & "status: completed at t = 0.5 s") > 0 .and. len(line_adm) > 0 .and. line_adm &
            & == line_nml, "exit statuses " // to_text(status_adm) // ", " &
            & // to_text(status_nml) // "; the dataset's switch '" // line_adm &
            & // "', the scene's '" // line_nml // "'; summary: " // adm)

    contains

        !> The summary's line "  t = ... s: sliding → rolling" ("" if none).
        function switch_line(text) result(line)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: line
            integer :: at, first

            line = ""
            at = index(text, switch)
            if (at == 0) return
            first = index(text(:at), new_line("a"), back=.true.) + 1
            line = text(first:at + len(switch) - 1)
        end function switch_line

    end subroutine test_contact_dataset

end module test_dataset_command
