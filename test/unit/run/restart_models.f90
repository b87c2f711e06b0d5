! SPDX-License-Identifier: MIT
!> The models of the rebasing-restarts suite, as the datasets an ADAMS user would write: a
!> Chaplygin ball (an anisotropic sphere rolling, pushed at a point fixed in it) and a ball
!> released at rest on a turntable, on which IDA failed right after a re-basing (IDA_ERR_FAIL)
!> before the restart was made consistent, and the tumbling ball of data/ball_tumbling.adm with
!> its axes turned so that they tumble on a cone clear of the Euler-angle singularity (the same
!> motion, never re-based). Each is written under build/, read, built with the
!> initial-conditions analysis (as `rollcon run` does) and run.
module restart_models
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_dataset_source, only : dataset_source_type, new_dataset_source
    use rollcon_output_files, only : write_text_file, delete_file
    implicit none
    private

    public :: chaplygin_ball, ball_released_on_turntable, ball_on_a_cone, build_dataset
    public :: run_analysed

    character(len=*), parameter :: nl = new_line("a")

contains

    !> A Chaplygin ball: a sphere of radius 0.05 m, mass 1 kg, its centre of mass at its centre
    !> and unequal principal moments 1.2e-3, 1.0e-3, 0.7e-3 kg m^2, rolling without slip
    !> (generated rolling_sphere), pushed by a constant 1 N along ground X and 0.3 N along Y at
    !> a point fixed in it 0.036 m from its centre (MARKER/22); started at 0.5 m/s along X
    !> spinning at 5 rad/s about two of its axes (the analysis makes the start roll). Its axes
    !> tumble and are re-based four times in 3.5 s. IDA failed at the first (t = 3.043 s) at
    !> ERROR = 1e-10, 1e-9 and 1e-8 alike.
    function chaplygin_ball(formulation) result(text)
        !> IDA or CVODE
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "chaplygin ball" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART=1" // nl &
            & // "PART/2, MASS=1, CM=21, IP=1.2E-3, 1.0E-3, 0.7E-3, QG=0, 0, 0.05" // nl &
            & // ", VX=0.5, WX=5, WZ=5" // nl // "MARKER/21, PART=2, REULER=90D, 90D, 0D" // nl &
            & // "MARKER/22, PART=2, QP=0.03, 0, 0.02" // nl &
            & // "VFORCE/5, I=22, JFLOAT=1, RM=1, FX=1, FY=0.3, FZ=0" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "UCON/1, FUNCTION=USER(2, 21, 22, 23, 14, 15, 25, 26, 0.05, 1), " &
            & // "ROUTINE=rolling_sphere" // nl &
            & // "UCON/2, FUNCTION=USER(2, 21, 22, 23, 14, 15, 25, 26, 0.05, 2), " &
            & // "ROUTINE=rolling_sphere" // nl &
            & // "UCON/3, FUNCTION=USER(2, 21, 22, 23, 14, 15, 25, 26, 0.05, 3), " &
            & // "ROUTINE=rolling_sphere" // nl &
            & // "SIMULATE/DYNAMIC, END=3.5, DTOUT=0.01" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", ERROR=1.0E-10" // nl // "END"
    end function chaplygin_ball

    !> data/ball_tumbling.adm's ball (m = 0.1 kg, r = 0.02 m, on a table turning at 3.5 rad/s
    !> about the origin) released at rest at (0.1, 0, r), for 13 s at ERROR = 1e-8: the
    !> analysis starts it rolling at 0.13125 m/s along Y, spinning at 10.9375 rad/s about X,
    !> and its centre circles at 1 rad/s about (-0.03125, 0); its axes are re-based four times,
    !> and IDA failed at the fourth (t = 12.115 s).
    function ball_released_on_turntable(formulation) result(text)
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "ball released on a turntable" // nl // "UNITS/SYSTEM=SI" // nl &
            & // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=0.1, CM=21, IP=1.6E-5, 1.6E-5, 1.6E-5, QG=0.1, 0, 0.02" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl // "ACCGRAV/KGRAV=-9.81" // nl &
            & // turntable_ucons() &
            & // "SIMULATE/DYNAMIC, END=13, DTOUT=0.05" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", ERROR=1.0E-8" // nl // "END"
    end function ball_released_on_turntable

    !> data/ball_tumbling.adm's motion (20 turns of the orbit at ERROR = 1e-10 on IDA) with the
    !> ball's CM marker turned by 30 degrees about ground Z from that dataset's (REULER=30D, 90D,
    !> 0D): its z axis makes 60 degrees with the spin axis, tumbles on a cone about it and keeps
    !> sin(theta) >= 0.5: never re-based. The same angular velocity, (12.5, 0, 1) rad/s in
    !> ground axes, in the marker's: (12.5 cos 30deg, 1, 12.5 sin 30deg).
    function ball_on_a_cone() result(text)
        character(len=:), allocatable :: text

        text = "ball on a cone" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=0.1, CM=21, IP=1.6E-5, 1.6E-5, 1.6E-5, QG=0.1, 0, 0.02" // nl &
            & // ", VY=0.1, WX=10.825317547305483, WY=1, WZ=6.25" // nl &
            & // "MARKER/21, PART=2, REULER=30D, 90D, 0D" // nl // "ACCGRAV/KGRAV=-9.81" // nl &
            & // turntable_ucons() &
            & // "SIMULATE/DYNAMIC, END=125.66370614359172, STEPS=2500" // nl &
            & // "INTEGRATOR/FORMULATION=IDA, ERROR=1.0E-10" // nl // "END"
    end function ball_on_a_cone

    !> The turntable ball's no-slip UCONs (generated turntable_ball): part 2, its 9 codes,
    !> r = 0.02 m, Omega = 3.5 rad/s about (0, 0), component.
    function turntable_ucons() result(text)
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, 3
            text = text // "UCON/" // achar(iachar("0") + k) // ", FUNCTION=USER(2, 11, 12, " &
                & // "21, 22, 23, 14, 15, 25, 26, 0.02, 3.5, 0, 0, " // achar(iachar("0") + k) &
                & // ")" // nl // ", ROUTINE=turntable_ball" // nl
        end do
    end function turntable_ucons

    !> Write text as build/restarts-<tag>.adm, read it and build its problem with the start of
    !> the initial-conditions analysis; the file is deleted.
    subroutine build_dataset(tag, text, problem, q0, u0, end_time, output_step, error)
        character(len=*), intent(in) :: tag, text
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        !> The dataset's end time and output step [s]
        real(wp), intent(out) :: end_time, output_step
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(dataset_source_type) :: source
        type(error_type), allocatable :: delete_error
        procedure(ucosub_interface), pointer :: none
        character(len=:), allocatable :: path, report

        end_time = 0.0_wp
        output_step = 0.0_wp
        path = "build/restarts-" // tag // ".adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
        call read_adm(path, adm, error)
        call delete_file(path, delete_error)
        if (allocated(error)) return
        ! every UCON names its ROUTINE: no model UCOSUB
        none => null()
        source = new_dataset_source(adm, path)
        call source%build(none, problem, q0, u0, report, error)
        if (allocated(error)) return
        end_time = adm%run%settings%end_time
        output_step = adm%run%settings%output_step
    end subroutine build_dataset

    !> Build the dataset of text (build_dataset) and run it, its rows kept in history.
    subroutine run_analysed(tag, text, summary, history, error, rebase_turn)
        character(len=*), intent(in) :: tag, text
        type(run_summary_type), intent(out) :: summary
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error
        !> The turn of every re-basing (problem%rebase_turn; default 0, the rule's)
        integer, intent(in), optional :: rebase_turn
        type(problem_type), target :: problem
        type(run_options_type) :: options
        real(wp), allocatable :: q0(:), u0(:)

        call build_dataset(tag, text, problem, q0, u0, options%end_time, options%output_step, &
            & error)
        if (allocated(error)) return
        options%progress = .false.
        if (present(rebase_turn)) problem%rebase_turn = rebase_turn
        call simulate(problem, q0, u0, options, summary, error, history)
    end subroutine run_analysed

end module restart_models
