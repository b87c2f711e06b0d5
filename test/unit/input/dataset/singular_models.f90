! SPDX-License-Identifier: MIT
!> The singular-start suite's datasets, each in two writings of one physical start: with the
!> CM marker's z-axis along ground z at t = 0 (the Euler singularity: rollcon starts the part
!> in turned axes), and with the CM marker turned 90 degrees about x, IP and WX, WY, WZ given
!> in the turned axes, as a user had to write it by hand (the "twin"). Also the coin's disk
!> lying flat, served by the disk routine, which takes body z as the axle.
module singular_models
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: flat_ball, twin_ball, flat_body, twin_body, flat_disk, body_inertia, body_mass
    public :: body_rate

    character(len=*), parameter :: nl = new_line("a")
    !> The free body's mass [kg] and principal moments about the flat CM marker's axes, which
    !> are ground's at t = 0 [kg m^2] (three different; each at most the sum of the others)
    real(wp), parameter :: body_mass = 2.0_wp
    real(wp), parameter :: body_inertia(3) = [0.01_wp, 0.02_wp, 0.025_wp]
    !> Its angular velocity at t = 0, ground axes [rad/s]: mostly about its least axis (a
    !> stable spin), so that its z-axis passes ground z twice a turn and the run re-bases it
    real(wp), parameter :: body_rate(3) = [8.0_wp, 1.0_wp, 2.0_wp]
    !> The ball's rows: 5 s, a row every 0.05 s
    character(len=*), parameter :: ball_run = "SIMULATE/DYNAMIC, END=5, STEPS=100" // nl &
        & // "INTEGRATOR/FORMULATION=IDA, ERROR=1.0E-10" // nl // "END" // nl

contains

    !> data/ball_tumbling.adm's ball on its turntable (0.1 kg, r = 0.02 m, 12.5 rad/s along
    !> +X and 1 rad/s about +Z) for 5 s, its CM marker with ground's axes: z along ground Z.
    function flat_ball() result(text)
        character(len=:), allocatable :: text

        text = "ball flat" // nl // ball_part() // ", WX=12.5, WZ=1" // nl &
            & // "MARKER/21, PART=2" // nl // ball_tail()
    end function flat_ball

    !> The same ball with its CM marker turned 90 degrees about x (x along +X, y along +Z, z
    !> along -Y): its angular velocity (12.5, 0, 1) in ground is (12.5, 1, 0) in those axes.
    function twin_ball() result(text)
        character(len=:), allocatable :: text

        text = "ball twin" // nl // ball_part() // ", WX=12.5, WY=1" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl // ball_tail()
    end function twin_ball

    function ball_part() result(text)
        character(len=:), allocatable :: text

        text = "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=0.1, CM=21, IP=1.6E-5, 1.6E-5, 1.6E-5" // nl &
            & // ", QG=0.1, 0, 0.02" // nl // ", VY=0.1" // nl
    end function ball_part

    !> Gravity, the turntable's no-slip UCONs (ucon/specs/turntable_ball.py), the run.
    function ball_tail() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: par = "FUNCTION=USER(2, 11, 12, 21, 22, 23, 14, 15, " &
            & // "25, 26, 0.02, 3.5, 0, 0, "
        integer :: k

        text = "ACCGRAV/KGRAV=-9.81" // nl
        do k = 1, 3
            text = text // "UCON/" // achar(iachar("0") + k) // ", " // par &
                & // achar(iachar("0") + k) // "), ROUTINE=turntable_ball" // nl
        end do
        text = text // ball_run
    end function ball_tail

    !> A free body (no UCON, gravity only) thrown up at 2 m/s, three different principal
    !> moments, its CM marker with ground's axes, for 5 s.
    function flat_body(formulation) result(text)
        !> IDA or CVODE
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "free body flat" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=2, CM=21, IP=0.01, 0.02, 0.025, QG=0, 0, 1" // nl &
            & // ", VX=0.3, VZ=2, WX=8, WY=1, WZ=2" // nl // "MARKER/21, PART=2" // nl &
            & // body_tail(formulation)
    end function flat_body

    !> The same body with its CM marker turned 90 degrees about x: IP (Ixx, Izz, Iyy) and the
    !> angular velocity (8, 1, 2) in ground as (8, 2, -1) in the turned axes.
    function twin_body(formulation) result(text)
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "free body twin" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=2, CM=21, IP=0.01, 0.025, 0.02, QG=0, 0, 1" // nl &
            & // ", VX=0.3, VZ=2, WX=8, WY=2, WZ=-1" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl // body_tail(formulation)
    end function twin_body

    function body_tail(formulation) result(text)
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "ACCGRAV/KGRAV=-9.81" // nl // "SIMULATE/DYNAMIC, END=5, STEPS=250" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", ERROR=1.0E-10" // nl // "END" &
            & // nl
    end function body_tail

    !> The coin's disk (data/coin.adm's part 2) lying flat at rest, its CM marker's z, the
    !> axle of the hand-checked disk routine, along ground z.
    function flat_disk() result(text)
        character(len=:), allocatable :: text
        character(len=*), parameter :: par = "FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, " &
            & // "26, 0.1, "
        integer :: k

        text = "disk flat" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "PART/2, MASS=0.73513268094001172, CM=21" // nl &
            & // ", IP=1.8383830518607345E-3, 1.8383830518607345E-3, 3.6756634047000595E-3" &
            & // nl // ", QG=0, 0, 0.001" // nl // "MARKER/21, PART=2" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl
        do k = 1, 3
            text = text // "UCON/" // achar(iachar("0") + k) // ", " // par &
                & // achar(iachar("0") + k) // "), ROUTINE=disk" // nl
        end do
        text = text // "SIMULATE/DYNAMIC, END=1, DTOUT=0.01" // nl &
            & // "INTEGRATOR/FORMULATION=IDA, ERROR=1.0E-10" // nl // "END" // nl
    end function flat_disk

end module singular_models
