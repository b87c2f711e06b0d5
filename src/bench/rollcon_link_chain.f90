! SPDX-License-Identifier: MIT
!> A dataset of a chain of N links joined by REVOLUTE joints (docs/benchmark.md "Cost as
!> models grow"): a many-link pendulum. Link 1 is hinged to the ground at the origin,
!> link k + 1 to the lower end of link k, every hinge axis along ground Y; the chain starts
!> straight, at rest, 60 degrees from the vertical (the start of data/pendulum.adm), and falls
!> under gravity in the X-Z plane. Each joint is five position UCONs between two neighbours
!> (rollcon_joint_primitives), so the whole chain is one block of the constraints
!> (rollcon_constraint_blocks).
module rollcon_link_chain
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    implicit none
    private

    public :: link_chain_dataset

    !> A link: length [m], mass [kg], each principal moment about its centre [kg m^2] (a thin
    !> rod's m l^2/12 about every axis: the motion stays in the plane, where only the moment
    !> about the hinge axis counts). 1 kg, as data/pendulum.adm's bob: with 0.1 kg links IDA
    !> failed its first step at rtol 1e-8 from 60 links on (IDA_CONV_FAIL at t = 0, dense and
    !> sparse alike), and with 1 kg links it does not: the motion is the same, but the
    !> algebraic components' tolerance is set on the forces' scale (rollcon_ida), and the
    !> GGL multipliers mu, which do not grow with the mass, get ten times more room
    real(wp), parameter :: link_length = 0.1_wp, link_mass = 1.0_wp
    real(wp), parameter :: link_moment = link_mass*link_length**2/12.0_wp
    !> The start: the chain's angle from the vertical [deg]
    real(wp), parameter :: start_deg = 60.0_wp

contains

    !> The dataset text of a chain of `count` links, run to end_time [s] with output every
    !> output_step [s] on the given INTEGRATOR keywords.
    function link_chain_dataset(count, end_time, output_step, integrator) result(text)
        integer, intent(in) :: count
        real(wp), intent(in) :: end_time, output_step
        !> INTEGRATOR keywords after the slash ("FORMULATION=IDA, ERROR=1e-8")
        character(len=*), intent(in) :: integrator
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        !> Every hinge marker's axes in its part's frame: z along ground Y (data/pendulum.adm)
        character(len=*), parameter :: hinge_axes = "REULER=180D, 90D, 0D"
        real(wp) :: along(3)
        integer :: k, part

        ! the chain's direction, from the hinge down: the part frame (REULER=90D, 60D, -90D,
        ! turned start_deg about ground +Y) carries its z axis onto -along
        along = [-sin(start_deg*acos(-1.0_wp)/180.0_wp), 0.0_wp, &
            & -cos(start_deg*acos(-1.0_wp)/180.0_wp)]
        text = to_text(count) // " links hinged in a chain (rollcon_link_chain)" // nl // nl &
            & // "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND" // nl // nl &
            & // "PART/1, GROUND" // nl // "MARKER/10, PART=1, " // hinge_axes // nl // nl
        do k = 1, count
            part = k + 1
            ! the part frame at the link's upper end; its centre l/2 below, its lower end l
            text = text // "PART/" // to_text(part) // ", MASS=" // to_text(link_mass) &
                & // ", CM=" // to_text(100*part) // nl // ", IP=" // to_text(link_moment) &
                & // ", " // to_text(link_moment) // ", " // to_text(link_moment) // nl &
                & // ", QG=" // to_text(link_length*(k - 1)*along(1)) // ", 0, " &
                & // to_text(link_length*(k - 1)*along(3)) // nl &
                & // ", REULER=90D, " // to_text(start_deg) // "D, -90D" // nl &
                & // "MARKER/" // to_text(100*part) // ", PART=" // to_text(part) &
                & // ", QP=0, 0, " // to_text(-0.5_wp*link_length) // ", REULER=0, 90D, 0" &
                & // nl // "MARKER/" // to_text(100*part + 1) // ", PART=" // to_text(part) &
                & // ", " // hinge_axes // nl // "MARKER/" // to_text(100*part + 2) &
                & // ", PART=" // to_text(part) // ", QP=0, 0, " // to_text(-link_length) &
                & // ", " // hinge_axes // nl
            ! hinged at its upper end to the ground (link 1) or to the lower end of link k - 1
            text = text // "JOINT/" // to_text(k) // ", REVOLUTE, I=" // to_text(100*part + 1) &
                & // ", J=" // to_text(merge(10, 100*(part - 1) + 2, k == 1)) // nl // nl
        end do
        text = text // "ACCGRAV/KGRAV=-9.81" // nl // nl // "SIMULATE/DYNAMIC, END=" &
            & // to_text(end_time) // ", DTOUT=" // to_text(output_step) // nl &
            & // "INTEGRATOR/" // integrator // nl // nl // "END" // nl
    end function link_chain_dataset

end module rollcon_link_chain
