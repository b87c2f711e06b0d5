! SPDX-License-Identifier: MIT
!> rollcon: simulate a disk scene (default: the paper's coin) or print the UCOSUB's table.
program rollcon_main
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : wp, error_type, disk_nvars, fatal_error, stat_input, &
        & default_call_timeout, user_ucosub_type, new_user_ucosub, run_summary_type, &
        & status_inaccurate, use_one_blas_thread, ucosub_interface, find_builtin_ucosub, &
        & builtin_ucosub_names
    use rollcon_command_line, only : real_option_list, real_option
    use rollcon_command_table, only : print_table, default_state, default_radius
    use rollcon_command_run, only : run_scene
    use rollcon_command_bench, only : bench_command
    use rollcon_command_plot, only : plot_command
    use rollcon_command_animate, only : animate_command
    use rollcon_command_run_vtk, only : write_run_vtk
    use rollcon_command_check, only : check_command, call_timeout_option
    use rollcon_command_run_isolated, only : run_user_scene
    use rollcon_command_sweep, only : sweep_command
    use rollcon_command_bench_sweep, only : bench_sweep_command
    implicit none
    type(error_type), allocatable :: error
    type(run_summary_type) :: summary
    real(wp) :: state(disk_nvars), radius, vtk_fps
    character(len=:), allocatable :: command, scene, output_dir
    logical :: quiet, allow_large_output
    integer :: argument_index
    !> rollcon check's verdict (0 clean, 1 mismatches); run --ucosub: the user's file, loaded
    integer :: check_status
    !> rollcon sweep: 0 when every case is in the CSV
    integer :: sweep_status
    character(len=:), allocatable :: ucosub_path
    type(user_ucosub_type) :: user
    procedure(ucosub_interface), pointer :: builtin => null()
    !> run --ucosub: longest one call of the user's routine may take [s]
    real(wp) :: call_timeout = default_call_timeout
    !> The threaded BLAS set to one thread ("" for reference BLAS)
    character(len=:), allocatable :: blas_library

    ! dozen-unknown systems gain nothing from BLAS threads (rollcon_lapack)
    call use_one_blas_thread(blas_library)
    call read_command_line(error)
    if (allocated(error)) call fail(error)
    select case (command)
    case ("bench")
        if (bench_sweep()) then
            call bench_sweep_command(argument_index + 2, error)
        else
            call bench_command(argument_index + 1, error)
        end if
        if (allocated(error)) call fail(error)
    case ("help")
        call print_help()
    case ("sweep")
        call sweep_command(argument_index + 1, sweep_status, error)
        if (allocated(error)) call fail(error)
        if (sweep_status /= 0) stop 1, quiet=.true.
    case ("table")
        call print_table(state, radius, error)
        if (allocated(error)) call fail(error)
    case ("run")
        call choose_ucosub(error)
        if (allocated(error)) call fail(error)
        if (allocated(ucosub_path) .and. .not. associated(builtin)) then
            call new_user_ucosub(user, ucosub_path, error)
            if (allocated(error)) call fail(error)
            if (.not. quiet) write(output_unit, '(a)') "UCOSUB: " // ucosub_path // " (" &
                & // user%library // merge(", from the cache", ", compiled now  ", &
                & user%from_cache) // ")"
            call run_user_scene(scene, output_dir, user%ucosub, quiet, call_timeout, error, &
                & allow_large_output)
        else
            call run_scene(scene, output_dir, builtin, quiet, summary, error, &
                & allow_large_output)
        end if
        if (allocated(error)) call fail(error)
        if (vtk_fps > 0.0_wp) call write_run_vtk(scene, output_dir, vtk_fps, error)
        if (allocated(error)) call fail(error)
        ! results beyond what the tolerances promise: outputs written, but not a success
        if (summary%status == status_inaccurate) then
            write(error_unit, '(a)') "rollcon: warning: " // summary%message
            stop 3, quiet=.true.
        end if
    case ("plot")
        call plot_command(scene, output_dir, error)
        if (allocated(error)) call fail(error)
    case ("animate")
        call animate_command(scene, output_dir, error)
        if (allocated(error)) call fail(error)
    case ("check")
        call check_command(argument_index + 1, check_status, error)
        ! Exit status 1 is a verdict (mismatches), 2 a failure; no backtrace, no STOP line.
        if (allocated(error)) then
            write(error_unit, '(a)') "rollcon: error: " // error%message
            stop 2, quiet=.true.
        end if
        if (check_status /= 0) stop 1, quiet=.true.
    end select

contains

    !> `rollcon bench sweep`: the scaling benchmark of studies, not the work-precision one.
    logical function bench_sweep()
        character(len=16) :: word

        bench_sweep = .false.
        if (argument_index + 1 > command_argument_count()) return
        call get_command_argument(argument_index + 1, word)
        bench_sweep = word == "sweep"
    end function bench_sweep

    !> --ucosub NAME names a built-in routine when no file NAME exists: builtin points at it
    !> (null otherwise: no --ucosub, or a file to compile and run apart).
    subroutine choose_ucosub(error)
        type(error_type), allocatable, intent(out) :: error
        logical :: exists, time_free, found

        builtin => null()
        if (.not. allocated(ucosub_path)) return
        inquire(file=ucosub_path, exist=exists)
        if (exists) return
        call find_builtin_ucosub(ucosub_path, builtin, time_free, found)
        if (.not. found) call fatal_error(error, "--ucosub " // ucosub_path // ": no such file, " &
            & // "and not a built-in routine (" // builtin_ucosub_names() // ")", stat_input)
    end subroutine choose_ucosub

    !> Long because it is one flat select over every option of every command (a table in
    !> code); splitting it would scatter the options' checks.
    subroutine read_command_line(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=512) :: argument
        !> The positional argument (scene or CSV), when one was given
        character(len=:), allocatable :: positional
        integer :: i

        command = "run"
        scene = "coin"
        output_dir = "output"
        quiet = .false.
        allow_large_output = .false.
        vtk_fps = 0.0_wp
        state = default_state
        radius = default_radius
        i = 1
        do while (i <= command_argument_count())
            call get_command_argument(i, argument)
            select case (trim(argument))
            case ("-h", "--help", "help")
                command = "help"
                return
            case ("table", "run", "plot", "animate")
                command = trim(argument)
            case ("bench")
                ! the rest of the command line is bench's
                command = "bench"
                argument_index = i
                return
            case ("check")
                ! the rest of the command line is check's (app/rollcon_command_check.f90)
                command = "check"
                argument_index = i
                return
            case ("sweep")
                ! the rest of the command line is sweep's (app/rollcon_command_sweep.f90)
                command = "sweep"
                argument_index = i
                return
            case ("--ucosub")
                i = i + 1
                if (i > command_argument_count()) then
                    call fatal_error(error, "--ucosub needs a file (.f, .f90 or .o)", stat_input)
                    return
                end if
                call get_command_argument(i, argument)
                ucosub_path = trim(argument)
            case ("--call-timeout")
                i = i + 1
                call call_timeout_option(i, call_timeout, error)
                if (allocated(error)) return
            case ("--quiet", "-q")
                quiet = .true.
            case ("--allow-large-output")
                allow_large_output = .true.
            case ("--output", "-o")
                i = i + 1
                if (i > command_argument_count()) then
                    call fatal_error(error, "--output needs a folder", stat_input)
                    return
                end if
                call get_command_argument(i, argument)
                output_dir = trim(argument)
            case ("--radius")
                i = i + 1
                call real_option("--radius", i, radius, error)
                if (allocated(error)) return
                if (.not. (radius > 0.0_wp .and. radius < huge(1.0_wp))) then
                    call fatal_error(error, "--radius must be a positive finite length [m]", &
                        & stat_input)
                    return
                end if
            case ("--vtk")
                i = i + 1
                call real_option("--vtk", i, vtk_fps, error)
                if (allocated(error)) return
                if (.not. vtk_fps > 0.0_wp) then
                    call fatal_error(error, "--vtk needs a positive number of frames per " &
                        & // "second", stat_input)
                    return
                end if
            case ("--state")
                i = i + 1
                call real_option_list("--state", i, state, error)
                if (allocated(error)) return
            case default
                if (argument(1:1) == "-") then
                    call fatal_error(error, "unknown option '" // trim(argument) &
                        & // "'; run 'rollcon --help' for the usage", stat_input)
                    return
                end if
                if (allocated(positional)) then
                    call fatal_error(error, "unexpected argument '" // trim(argument) &
                        & // "' after '" // positional // "': give one SCENE (or CSV); " &
                        & // "run 'rollcon --help' for the usage", stat_input)
                    return
                end if
                positional = trim(argument)
                scene = positional
            end select
            i = i + 1
        end do
        if (command == "table" .and. allocated(positional)) then
            call fatal_error(error, "unexpected argument '" // positional // "': table takes " &
                & // "only --radius and --state; run 'rollcon --help' for the usage", stat_input)
        end if
    end subroutine read_command_line

    subroutine print_help()
        write(output_unit, '(a)') &
            & "usage: rollcon [run] [SCENE] [--output DIR] [--quiet] [--vtk FPS]", &
            & "                     [--allow-large-output]", &
            & "       rollcon plot|animate [CSV|SCENE] [--output DIR]", &
            & "       rollcon table [--radius R] [--state XD,YD,ZD,PSI,THETA,PSID,THETAD,PHID]", &
            & "       rollcon bench [--quick] [...]     (rollcon bench --help)", &
            & "       rollcon bench sweep [...]         (rollcon bench sweep --help)", &
            & "       rollcon [run] MODEL.adm [--ucosub FILE|NAME] [...]  (an ADAMS dataset)", &
            & "       rollcon [run] [SCENE] --ucosub FILE      (your own UCOSUB, see below)", &
            & "       rollcon check FILE --ucon ID:PAR1,PAR2,...  (rollcon check --help)", &
            & "       rollcon check FILE --model MODEL.adm", &
            & "       [mpirun -np N] rollcon sweep STUDY.nml [--output DIR]  (a parameter", &
            & "               study, one CSV row per case, and its map: rollcon sweep --help)", &
            & "       rollcon --help", &
            & "", &
            & "run (the default): simulate a rolling-disk scene, the paper's coin unless SCENE", &
            & "  names another: coin, tipping_coin, steady_circle, fast_upright, spinning_coin,", &
            & "  near_flat, long_run (files data/SCENE.nml), or a path to a namelist file.", &
            & "  Writes DIR/SCENE.csv (one row per output step; SI units, radians) and", &
            & "  DIR/SCENE.summary.txt; DIR defaults to ./output. The run writes", &
            & "  DIR/SCENE.partial-PID.csv (written out at least once a second) and renames it", &
            & "  into place when it succeeds; a failed or interrupted run leaves that partial", &
            & "  file (and its .partial-PID.summary.txt), and the earlier run's files as they", &
            & "  were.", &
            & "  MODEL.adm: an ADAMS dataset (docs/datasets.md): parts, markers, UCONs, forces,", &
            & "  gravity and the run, any number of parts; outputs DIR/MODEL.csv (every part's", &
            & "  12 coordinates named by part id, E, each UCON's residual and multiplier),", &
            & "  DIR/MODEL.summary.txt and DIR/MODEL.parts (the parts' shapes for the pictures).", &
            & "  A UCON naming ROUTINE=NAME is served by that built-in routine; the others by", &
            & "  the model's UCOSUB: --ucosub FILE|NAME, or rollcon's hand-checked disk.", &
            & "  --allow-large-output  run even when the CSV would pass 100 GB (refused", &
            & "               otherwise, with the row count and the bytes it would write)", &
            & "  Progress goes to stderr for runs longer than a second unless --quiet.", &
            & "  --ucosub FILE  serve the disk's no-slip UCONs with your own UCOSUB (.f, .f90", &
            & "               or .o; PAR as in the paper: part id, 8 codes, R, component),", &
            & "               compiled with gfortran and cached (see rollcon check --help);", &
            & "               the run goes in a child process, so a crash, a STOP or a", &
            & "               call longer than --call-timeout SECONDS (default 10) of the", &
            & "               routine ends with an error naming the UCON and the call", &
            & "  --ucosub NAME  a built-in routine instead (when no file NAME exists): disk,", &
            & "               rolling_disk, and the other generated specs (docs/generator.md)", &
            & "  --vtk FPS    also write DIR/SCENE_vtk/SCENE.pvd, a VTK time series for", &
            & "               ParaView: FPS frames per simulated second, each frame the", &
            & "               output row nearest to its time (nothing is interpolated)", &
            & "", &
            & "plot: draw the figures of a run's CSV with gnuplot, NAME the CSV's file name less", &
            & "  .csv. A disk scene: DIR/NAME_path.png, _theta, _rates, _energy, _residuals,", &
            & "  _force and _friction.png. Any other model: DIR/NAME_path.png, _height,", &
            & "  _angles, _energy, _residuals and _multipliers.png, every part and UCON by id.", &
            & "  A SCENE name means DIR/SCENE.csv (default coin). The parts' shapes come from", &
            & "  DIR/NAME.parts, which run writes beside the CSV (docs/pictures.md).", &
            & "animate: draw DIR/NAME.gif, every part moving (a disk as a disk, other parts as", &
            & "  their inertia ellipsoids), 20 frames per second (real time up to 15 s of", &
            & "  motion, faster beyond), with gnuplot.", &
            & "", &
            & "table: evaluate the hand-checked rolling-disk UCOSUB through the ADAMS calling", &
            & "  sequence and print F and every non-zero first and second partial of its three", &
            & "  components with their count (49 at a generic state).", &
            & "  --radius R   disk radius [m], default 0.1", &
            & "  --state ...  Xdot, Ydot, Zdot [m/s], psi, theta [rad], psidot, thetadot, phidot", &
            & "               [rad/s]; default 0.1,0.02,-0.01,0.3,1.2,0.5,-0.2,-1", &
            & "", &
            & "Exit status: 0 when the run completed or stopped at a limit the scene sets,", &
            & "1 on bad input or a failure (the CSV rows written before it stay valid),", &
            & "3 when the run's energy or height drifted beyond what rtol and atol promise", &
            & "(status INACCURATE; the outputs are written, and the summary gives the bounds)."
    end subroutine print_help

    !> A refusal or a failure: the message alone and exit status 1 (no backtrace, no STOP line;
    !> backtraces are for real crashes).
    subroutine fail(error)
        type(error_type), intent(in) :: error

        write(error_unit, '(a)') "rollcon: error: " // error%message
        flush(error_unit)
        stop 1, quiet=.true.
    end subroutine fail

end program rollcon_main
