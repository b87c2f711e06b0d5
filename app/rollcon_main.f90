! SPDX-License-Identifier: MIT
!> rollcon: simulate a scene or an ADAMS dataset (default: the paper's coin), check a user's
!> UCOSUB, draw a run, measure speed against accuracy, run parameter studies. The command line
!> is read once (rollcon_cli); each command is a module of its own; the work is the library's.
program rollcon_main
    use, intrinsic :: iso_fortran_env, only : output_unit, error_unit
    use rollcon, only : error_type, use_one_blas_thread
    use rollcon_cli, only : cli_request_type, parse_command_line
    use rollcon_command_run, only : run_command
    use rollcon_command_table, only : table_command
    use rollcon_command_plot, only : plot_command, animate_command
    use rollcon_command_check, only : check_command
    use rollcon_command_bench, only : bench_command
    use rollcon_command_bench_sweep, only : bench_sweep_command
    use rollcon_command_bench_scaling, only : bench_scaling_command
    use rollcon_sweep_program, only : run_sweep_program
    use rollcon_sweep_help, only : print_sweep_help
    use rollcon_command_linear, only : linear_command, print_linear_help
    use rollcon, only : version_text
    implicit none
    type(cli_request_type) :: request
    type(error_type), allocatable :: error
    !> The exit status a command asks for besides a failure (check: 1 on findings; sweep: 1
    !> when cases are missing; run: 3 when inaccurate)
    integer :: status
    !> The threaded BLAS set to one thread ("" for reference BLAS)
    character(len=:), allocatable :: blas_library

    ! dozen-unknown systems gain nothing from BLAS threads (rollcon_lapack)
    call use_one_blas_thread(blas_library)
    call parse_command_line(request, error)
    if (allocated(error)) call fail(error, 1)
    status = 0
    select case (request%command)
    case ("help")
        call print_help()
    case ("version")
        write(output_unit, '(a)') version_text()
    case ("run")
        if (request%has("--help")) then
            call print_help()
        else
            call run_command(request, status, error)
        end if
    case ("table", "plot", "animate")
        if (request%has("--help")) then
            call print_help()
        else if (request%command == "table") then
            call table_command(request, error)
        else if (request%command == "plot") then
            call plot_command(request, error)
        else
            call animate_command(request, error)
        end if
    case ("check")
        call check_command(request, status, error)
        ! exit status 1 is a verdict (findings), 2 a failure
        if (allocated(error)) call fail(error, 2)
    case ("bench")
        call bench_command(request, error)
    case ("bench sweep")
        call bench_sweep_command(request, error)
    case ("bench scaling")
        call bench_scaling_command(request, error)
    case ("sweep")
        ! the study program, which alone loads Open MPI: rollcon-sweep, beside this one
        if (request%has("--help")) then
            call print_sweep_help()
        else
            call run_sweep_program(error)
        end if
    case ("linear")
        if (request%has("--help")) then
            call print_linear_help()
        else
            call linear_command(request, error)
        end if
    end select
    if (allocated(error)) call fail(error, 1)
    if (status /= 0) stop status, quiet=.true.

contains

    subroutine print_help()
        write(output_unit, '(a)') &
            & "usage: rollcon [run] [SCENE] [--output DIR] [--quiet] [--vtk FPS]", &
            & "                     [--allow-large-output]", &
            & "       rollcon plot|animate [CSV|SCENE] [--output DIR]", &
            & "       rollcon table [--radius R] [--state XD,YD,ZD,PSI,THETA,PSID,THETAD,PHID]", &
            & "       rollcon bench [--quick] [...]     (rollcon bench --help)", &
            & "       rollcon bench sweep [...]         (rollcon bench sweep --help)", &
            & "       rollcon bench scaling [...]       (rollcon bench scaling --help)", &
            & "       rollcon [run] MODEL.adm [--ucosub FILE|NAME] [...]  (an ADAMS dataset)", &
            & "       rollcon [run] MODEL.adm --end T --steps N|--dtout DT  (its run given)", &
            & "       rollcon [run] MODEL.acf [...]  (an ADAMS command file: the dataset it", &
            & "               names, run as its SIMULATE commands say)", &
            & "       rollcon [run] [SCENE] --ucosub FILE|NAME  (your own UCOSUB, see below)", &
            & "       rollcon check FILE --ucon ID:PAR1,PAR2,...  (rollcon check --help)", &
            & "       rollcon check FILE --model MODEL.adm", &
            & "       [mpirun -np N] rollcon sweep STUDY.nml [--output DIR]  (a parameter", &
            & "               study, one CSV row per case, and its map: rollcon sweep --help)", &
            & "       rollcon linear MODEL.adm [--output DIR] [--speeds FROM,TO,COUNT]", &
            & "               (eigenvalues on the constraint manifold at the start, or", &
            & "               against speed: rollcon linear --help)", &
            & "       rollcon --help | --version", &
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
            & "  gravity and the run, any number of parts; outputs DIR/MODEL.adm.csv (every", &
            & "  part's 12 coordinates named by part id, E, each UCON's residual and", &
            & "  multiplier), DIR/MODEL.adm.summary.txt and DIR/MODEL.adm.parts (the parts'", &
            & "  shapes for the pictures): the name keeps .adm, so data/coin.adm and the scene", &
            & "  coin (data/coin.nml) keep their own outputs.", &
            & "  The run is the dataset's SIMULATE, or an ADAMS command file's: MODEL.acf,", &
            & "  whose first line names the dataset (from the command file's folder), its", &
            & "  second the output name (DIR/NAME.csv; blank: MODEL.adm), then", &
            & "  SIMULATE/DYNAMIC, END=t, STEPS=n (several in a row continue one run),", &
            & "  INTEGRATOR/..., OUTPUT/..., STOP.", &
            & "  --end T, --steps N, --dtout DT  the run's end and output steps (T and DT in", &
            & "               the dataset's time unit), in place of the SIMULATE of the", &
            & "               dataset or command file; what is not given is kept from it", &
            & "  A UCON naming ROUTINE=NAME is served by that built-in routine; the others by", &
            & "  the model's UCOSUB: --ucosub FILE|NAME, or rollcon's hand-checked disk.", &
            & "  --allow-large-output  run even when the CSV would pass 100 GB (refused", &
            & "               otherwise, with the row count and the bytes it would write)", &
            & "  Progress goes to stderr for runs longer than a second unless --quiet.", &
            & "  --ucosub FILE  serve the disk's no-slip UCONs (a scene) or the UCONs naming no", &
            & "               ROUTINE (a dataset) with your own UCOSUB (.f, .f90 or .o; a", &
            & "               scene's PAR as in the paper: part id, 8 codes, R, component),", &
            & "               compiled with gfortran and cached (see rollcon check --help);", &
            & "               your routine runs in a child process that only computes (this", &
            & "               process writes every output), so a crash, a STOP or a call", &
            & "               longer than --call-timeout SECONDS (default 10) of the", &
            & "               routine ends with an error naming the UCON and the call;", &
            & "               the run checks your routine's partials at its consistent", &
            & "               start, before the first step: a wrong one is named and the", &
            & "               run is not started", &
            & "  --no-check   skip that check and run anyway", &
            & "               The file may also hold SFOSUB, VFOSUB, GFOSUB: they serve the", &
            & "               SFORCE, VFORCE, GFORCE with FUNCTION=USER(...); --ucosub", &
            & "               given again adds files, ROUTINE=FILE::SFOSUB picks one's", &
            & "               routine (docs/datasets.md, User force routines)", &
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
            & "  A SCENE or MODEL.adm means the CSV its run wrote, DIR/SCENE.csv or", &
            & "  DIR/MODEL.adm.csv (default coin). The parts' shapes come from", &
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

    !> A refusal or a failure: the message alone and the exit status (no backtrace, no STOP
    !> line; backtraces are for real crashes).
    subroutine fail(error, status)
        type(error_type), intent(in) :: error
        integer, intent(in) :: status

        write(error_unit, '(a)') "rollcon: error: " // error%message
        flush(error_unit)
        stop status, quiet=.true.
    end subroutine fail

end program rollcon_main
