! SPDX-License-Identifier: MIT
!> The README's main command, `bash .ci/main` (suite main-script): after a run that ends
!> INACCURATE (exit status 3: its CSV and summary are written, and its figures are wanted most)
!> it draws the figures and the animation, and still exits 3; after a run that fails (exit 1)
!> it draws nothing; run from another folder on a command file there, it finds the dataset and
!> writes where it was asked; the struck coin on IDA with the generated rolling_disk (whose
!> switches' restarts were failing) runs to its end. Through the script itself, which builds
!> rollcon's release build (the first time this costs a few minutes; later runs reuse it).
module test_main_script
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use command_runs, only : file_text, file_exists
    implicit none
    private

    public :: collect_main_script

    !> Folder of the suite
    character(len=*), parameter :: scratch = "build/test_main_script"
    !> The tipping coin on CVODE without drift control, at loose tolerances: its height residual
    !> outgrows what rtol promises before 5 s (measured: 9.6e-4 m against 9.0e-4 m allowed at
    !> t = 5 s), so the run ends INACCURATE with exit status 3. 101 rows, a short animation.
    character(len=*), parameter :: inaccurate_scene = "&initial" // new_line("a") &
        & // "    theta = 1.5607963267948965" // new_line("a") // "    phidot = -1.0" &
        & // new_line("a") // "/" // new_line("a") // "&run" // new_line("a") &
        & // "    end_time = 5" // new_line("a") // "    output_step = 0.05" // new_line("a") &
        & // "    formulation = 'cvode'" // new_line("a") // "    drift = 'none'" &
        & // new_line("a") // "    rtol = 1e-4" // new_line("a") // "    atol = 1e-6" &
        & // new_line("a") // "/" // new_line("a")

contains

    subroutine collect_main_script(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("inaccurate-run-drawn-exit-3", test_inaccurate_drawn), &
            & new_unittest("failed-run-not-drawn", test_failed_not_drawn), &
            & new_unittest("command-file-from-its-folder", test_other_folder), &
            & new_unittest("struck-coin-slides-and-stops-on-ida", test_slides_on_ida)]
    end subroutine collect_main_script

    !> `bash .ci/main run SCENE -q -o DIR` on the inaccurate scene: exit status 3, the summary
    !> says INACCURATE, and DIR holds the figures (the path, the tilt) and the GIF.
    subroutine test_inaccurate_drawn(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: out = scratch // "/out"
        integer :: status

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot is not installed (bash .ci/setup installs it)")
            return
        end if
        call run_main(out, status)
        call check(error, status == 3 .and. index(file_text(out // "/inaccurate.summary.txt"), &
            & "status: INACCURATE") > 0 .and. file_exists(out // "/inaccurate_path.png") .and. &
            & file_exists(out // "/inaccurate_theta.png") .and. file_exists(out &
            & // "/inaccurate.gif"), "exit status " // to_text(status) // " (expected 3), " &
            & // "the figures and the GIF in " // out // ": " // last_lines(file_text(scratch &
            & // "/main.log")))
    end subroutine test_inaccurate_drawn

    !> A run refused at once (a scene with an unknown key) exits 1 and nothing is drawn.
    subroutine test_failed_not_drawn(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: out = scratch // "/failed"
        integer :: status, unit

        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        open(newunit=unit, file=scratch // "/broken.nml", status="replace", action="write")
        write(unit, '(a)') "&run", "    end_tme = 5", "/"
        close(unit)
        call execute_command_line("bash .ci/main run " // scratch // "/broken.nml -q -o " &
            & // out // " > " // scratch // "/main.log 2>&1", exitstat=status)
        call check(error, status == 1 .and. .not. file_exists(out // "/broken_path.png") &
            & .and. index(file_text(scratch // "/main.log"), "plot: wrote") == 0, &
            & "exit status " // to_text(status) // " (expected 1), and nothing drawn: " &
            & // last_lines(file_text(scratch // "/main.log")))
    end subroutine test_failed_not_drawn

    !> From the folder of a command file and its dataset (a copy of test/view's pendulum):
    !> `bash <repository>/.ci/main short.acf -q -o out` runs it (the dataset found from the
    !> command file, `out` the caller's folder), exits 0 and draws the run named by the
    !> command file's second line.
    subroutine test_other_folder(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: away = scratch // "/away"
        integer :: status, unit

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot is not installed (bash .ci/setup installs it)")
            return
        end if
        call execute_command_line("rm -rf " // away // " && mkdir -p " // away &
            & // " && cp test/view/view_export_pendulum.adm " // away // "/")
        open(newunit=unit, file=away // "/short.acf", status="replace", action="write")
        write(unit, '(a)') "view_export_pendulum", "short", "SIMULATE/DYNAMIC, END=0.5, STEPS=5", &
            & "STOP"
        close(unit)
        call execute_command_line("cd " // away // " && bash ../../../.ci/main short.acf -q -o " &
            & // "out > main.log 2>&1", exitstat=status)
        call check(error, status == 0 .and. file_exists(away // "/out/short.csv") .and. &
            & file_exists(away // "/out/short_path.png"), "exit status " // to_text(status) &
            & // " (expected 0), the CSV and the figures in " // away // "/out: " &
            & // last_lines(file_text(away // "/main.log")))
    end subroutine test_other_folder

    !> `bash .ci/main run SCENE --ucosub rolling_disk -q -o DIR` on data/coin_slipping.nml in
    !> the DAE form (IDA), with its strike as given and moved to 0.010000000000003 N s: each
    !> ends as the scene does (exit 0, theta at its limit after ten switches). Before the
    !> friction's direction had its floor the given strike failed right after a rolling ->
    !> sliding switch (IDA_CONV_FAIL), and before the careful start had its step budget the
    !> moved one failed after a sliding -> rolling one (IDA_TOO_MUCH_WORK, 500,000 steps within
    !> 1e-15 s of the stop).
    subroutine test_slides_on_ida(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: impulses(2) = ["0.01             ", &
            & "0.010000000000003"]
        character(len=:), allocatable :: out, summary
        integer :: k, status

        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        do k = 1, size(impulses)
            out = scratch // "/slides" // to_text(k)
            call execute_command_line("sed -e ""s/formulation = 'cvode'/formulation = 'ida'/"" " &
                & // "-e ""s/impulse = 0.01 /impulse = " // trim(impulses(k)) // " /"" " &
                & // "data/coin_slipping.nml > " // scratch // "/slides.nml", exitstat=status)
            call check(error, status == 0 .and. index(file_text(scratch // "/slides.nml"), &
                & "formulation = 'ida'") > 0 .and. index(file_text(scratch // "/slides.nml"), &
                & "impulse = " // trim(impulses(k)) // " ") > 0, "the scene was not written")
            if (allocated(error)) return
            status = -1
            call execute_command_line("bash .ci/main run " // scratch // "/slides.nml " &
                & // "--ucosub rolling_disk -q -o " // out // " > " // scratch &
                & // "/main.log 2>&1", exitstat=status)
            summary = ""
            if (file_exists(out // "/slides.summary.txt")) &
                & summary = file_text(out // "/slides.summary.txt")
            call check(error, status == 0 .and. index(summary, "status: stopped: theta fell " &
                & // "to the limit") > 0 .and. index(summary, "10 switches") > 0, "impulse " &
                & // trim(impulses(k)) // " N s: exit status " // to_text(status) // ": " &
                & // last_lines(file_text(scratch // "/main.log")))
            if (allocated(error)) return
        end do
    end subroutine test_slides_on_ida

    !> Write the inaccurate scene and run `bash .ci/main` on it into out.
    subroutine run_main(out, status)
        character(len=*), intent(in) :: out
        integer, intent(out) :: status
        integer :: unit

        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        open(newunit=unit, file=scratch // "/inaccurate.nml", status="replace", &
            & action="write", access="stream", form="unformatted")
        write(unit) inaccurate_scene
        close(unit)
        status = -1
        call execute_command_line("bash .ci/main run " // scratch // "/inaccurate.nml -q -o " &
            & // out // " > " // scratch // "/main.log 2>&1", exitstat=status)
    end subroutine run_main

    !> The last 600 characters of text, for a message.
    function last_lines(text) result(tail)
        character(len=*), intent(in) :: text
        character(len=:), allocatable :: tail

        tail = text(max(1, len(text) - 599):)
    end function last_lines

end module test_main_script
