! SPDX-License-Identifier: MIT
!> The rebasing suite's models, as the datasets an ADAMS user would write: a sphere rolling on
!> a straight line (a great circle of the sphere) whose CM-marker axes tumble through theta = 0
!> every half turn, the same sphere spinning about its body z (theta stays pi/2), and the
!> coin's disk falling flat from rest. Each is written to a file under build/, read, built and
!> run with the formulation asked for.
module rebasing_models
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_output_files, only : write_text_file, delete_file
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    implicit none
    private

    public :: run_dataset, build_dataset, tumbling_sphere, spinning_sphere, falling_disk
    public :: sphere_near_flat
    public :: sphere_radius, sphere_speed, sphere_end, users_disk

    !> Sphere radius [m], speed of its centre along +X [m/s], end of its runs [s]: 10 rad/s,
    !> a turn in 0.63 s, about 32 turns and four re-basings a turn
    real(wp), parameter :: sphere_radius = 0.05_wp, sphere_speed = 0.5_wp, sphere_end = 20.0_wp
    character(len=*), parameter :: nl = new_line("a")
    !> The sphere's no-slip UCONs (generated rolling_sphere: part, its 7 codes, r, component)
    character(len=*), parameter :: sphere_ucons = &
        & "UCON/1, FUNCTION=USER(2, 21, 22, 23, 14, 15, 25, 26, 0.05, 1), " &
        & // "ROUTINE=rolling_sphere" // nl &
        & // "UCON/2, FUNCTION=USER(2, 21, 22, 23, 14, 15, 25, 26, 0.05, 2), " &
        & // "ROUTINE=rolling_sphere" // nl &
        & // "UCON/3, FUNCTION=USER(2, 21, 22, 23, 14, 15, 25, 26, 0.05, 3), " &
        & // "ROUTINE=rolling_sphere" // nl

    !> A push of 0.2 N along ground +X from t = 0.3 s to 0.5 s at a point fixed in the sphere,
    !> MARKER/22, at the top of the sphere at t = 0 (QP in the part's frame, which is ground's
    !> at the start), after the tumbling sphere's first re-basing (at t = 0.15 s): the force's
    !> point must be turned with the axes. The reaction is on ground (not applied).
    character(len=*), parameter :: push_statements = "MARKER/1, PART=1" // nl &
        & // "MARKER/22, PART=2, QP=0, 0, 0.1" // nl &
        & // "VFORCE/5, I=22, JFLOAT=1, RM=1, FY=0, FZ=0" // nl &
        & // ", FX=IF(TIME - 0.3: 0, 0.2, IF(TIME - 0.5: 0.2, 0, 0))" // nl

contains

    !> The tumbling sphere: principal moments 1.0e-3, 0.9e-3, 0.8e-3 kg m^2 (the spin about
    !> the largest, a stable rotation), CM marker x along ground +Y (REULER 90D, 90D, 0D: body
    !> z along ground +X, theta = pi/2), rolling along +X at 0.5 m/s: a spin of v/r = 10 rad/s
    !> about ground +Y, the CM marker's x (WX = 10). Body y and z turn in the XZ plane.
    function tumbling_sphere(formulation, pushed) result(text)
        !> IDA or CVODE
        character(len=*), intent(in) :: formulation
        !> With the push (push_statements); default false
        logical, intent(in), optional :: pushed
        character(len=:), allocatable :: text

        text = "tumbling sphere" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=1, CM=21, IP=1.0E-3, 0.9E-3, 0.8E-3, QG=0, 0, 0.05" // nl &
            & // ", VX=0.5, WX=10" // nl // "MARKER/21, PART=2, REULER=90D, 90D, 0D" // nl &
            & // tail(formulation, pushed)
    end function tumbling_sphere

    !> The tumbling sphere starting with its body z 2 degrees from ground +Z (REULER 90D, 2D,
    !> 0D: theta = 0.035 rad, below the threshold sin(0.05 rad), above the dataset's refusal
    !> at sin(theta) < 0.001), for 1 s.
    function sphere_near_flat(formulation) result(text)
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "sphere near flat" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=1, CM=21, IP=1.0E-3, 0.9E-3, 0.8E-3, QG=0, 0, 0.05" // nl &
            & // ", VX=0.5, WX=10" // nl // "MARKER/21, PART=2, REULER=90D, 2D, 0D" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl // sphere_ucons &
            & // "SIMULATE/DYNAMIC, END=1, DTOUT=0.05" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", ERROR=1.0E-10" // nl // "END"
    end function sphere_near_flat

    !> The same sphere with its spin axis as body z (REULER 0D, 90D, 0D: body z along ground
    !> -Y, so the spin of 10 rad/s about ground +Y is WZ = -10): theta stays pi/2.
    function spinning_sphere(formulation, pushed) result(text)
        character(len=*), intent(in) :: formulation
        logical, intent(in), optional :: pushed
        character(len=:), allocatable :: text

        text = "spinning sphere" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=1, CM=21, IP=0.9E-3, 0.8E-3, 1.0E-3, QG=0, 0, 0.05" // nl &
            & // ", VX=0.5, WZ=-10" // nl // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl &
            & // tail(formulation, pushed)
    end function spinning_sphere

    !> Gravity, the sphere's UCONs, the push when asked, the run of sphere_end s at 0.05 s and
    !> the formulation.
    function tail(formulation, pushed) result(text)
        character(len=*), intent(in) :: formulation
        logical, intent(in), optional :: pushed
        character(len=:), allocatable :: text

        text = ""
        if (present(pushed)) then
            if (pushed) text = push_statements
        end if
        text = text // "ACCGRAV/KGRAV=-9.81" // nl // sphere_ucons &
            & // "SIMULATE/DYNAMIC, END=20, DTOUT=0.05" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", ERROR=1.0E-10" // nl // "END"
    end function tail

    !> The coin's disk (data/coin.adm's part 2) at rest, tilted 60 degrees (its CM marker turned
    !> 60 degrees about x, centre at R sin(60 deg)), served by the hand-checked disk routine,
    !> whose F takes body z as the axle: it falls flat within a second.
    function falling_disk(formulation, routine) result(text)
        character(len=*), intent(in) :: formulation
        !> "ROUTINE=disk" (the default) or "" (the model's UCOSUB serves the UCONs)
        character(len=*), intent(in), optional :: routine
        character(len=:), allocatable :: text, named

        named = ", ROUTINE=disk"
        if (present(routine)) named = routine
        text = "falling disk" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=0.73513268094001172, CM=21" // nl &
            & // ", IP=1.8383830518607345E-3, 1.8383830518607345E-3, 3.6756634047000595E-3" &
            & // nl // ", QG=0, 0, 0.086602540378443865" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 60D, 0D" // nl // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "UCON/1, FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, 26, 0.1, 1)" // named &
            & // nl // "UCON/2, FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, 26, 0.1, 2)" &
            & // named // nl &
            & // "UCON/3, FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, 26, 0.1, 3)" // named &
            & // nl &
            & // "SIMULATE/DYNAMIC, END=3, DTOUT=0.01" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", ERROR=1.0E-12" // nl // "END"
    end function falling_disk

    !> Write text as build/rebasing-<tag>.adm, read and build it, run it (rows kept in
    !> history, and written to csv_path when given), and delete the dataset. rebase_turn: the
    !> problem's (0, the turn the rule picks, unless given).
    subroutine run_dataset(tag, text, summary, history, error, csv_path, default_ucosub, &
            & rebase_turn)
        character(len=*), intent(in) :: tag, text
        type(run_summary_type), intent(out) :: summary
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: csv_path
        !> The model's UCOSUB, serving the UCONs that name no ROUTINE
        procedure(ucosub_interface), optional :: default_ucosub
        integer, intent(in), optional :: rebase_turn
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(run_options_type) :: options
        real(wp), allocatable :: q0(:), u0(:)

        call build_dataset(tag, text, adm, problem, q0, u0, error, default_ucosub)
        if (allocated(error)) return
        if (present(rebase_turn)) problem%rebase_turn = rebase_turn
        options%end_time = adm%run%settings%end_time
        options%output_step = adm%run%settings%output_step
        options%progress = .false.
        if (present(csv_path)) options%csv_path = csv_path
        call simulate(problem, q0, u0, options, summary, error, history)
    end subroutine run_dataset

    !> Write text as build/rebasing-<tag>.adm, read and build it (its start q0, u0), and
    !> delete the dataset.
    subroutine build_dataset(tag, text, adm, problem, q0, u0, error, default_ucosub)
        character(len=*), intent(in) :: tag, text
        type(adm_model_type), intent(out) :: adm
        type(problem_type), target, intent(inout) :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        !> The model's UCOSUB, serving the UCONs that name no ROUTINE
        procedure(ucosub_interface), optional :: default_ucosub
        procedure(ucosub_interface), pointer :: model_ucosub
        type(error_type), allocatable :: delete_error
        character(len=:), allocatable :: path

        path = "build/rebasing-" // tag // ".adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
        call read_adm(path, adm, error)
        call delete_file(path, delete_error)
        if (allocated(error)) return
        model_ucosub => null()
        if (present(default_ucosub)) model_ucosub => default_ucosub
        call build_adm_problem(adm, model_ucosub, problem=problem, q0=q0, u0=u0, error=error)
    end subroutine build_dataset

    !> A user's rolling-disk UCOSUB (no built-in routine, for the driver): the hand-checked
    !> disk's F, which takes body z as the axle.
    subroutine users_disk(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(30)
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        integer, intent(in) :: idrsel(3)
        integer, intent(in) :: iflag
        real(wp), intent(inout) :: scalar
        real(wp), intent(inout) :: array(30)
        real(wp), intent(inout) :: xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
    end subroutine users_disk

end module rebasing_models
