! SPDX-License-Identifier: MIT
!> A dataset of N independent rolling disks (docs/benchmark.md "Cost as
!> models grow"): each disk its own part with its three rolling UCONs served by the model's
!> UCOSUB (rollcon's hand-checked disk), each started as the tipping coin (the paper's steel
!> disk, 0.1 m radius, upright less 0.2 rad, rolling at 0.1 m/s), the disks `spacing` apart
!> along Y. The study's other model, a chain of parts with joints, is rollcon_link_chain.
module rollcon_disk_fleet
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    implicit none
    private

    public :: disk_fleet_dataset

    !> The paper's steel disk: radius [m], mass [kg], principal moments [kg m^2]
    real(wp), parameter :: radius = 0.1_wp, mass = 0.73513268094001172_wp
    real(wp), parameter :: axial = 3.6756634047000595e-3_wp, diametral = 1.8383830518607345e-3_wp
    !> The start: tilt from upright [deg], speed along X [m/s]
    real(wp), parameter :: tilt_deg = 11.459155902616464_wp, speed = 0.1_wp

contains

    !> The dataset text of `count` disks, `spacing` [m] apart along Y (0: every disk on the
    !> same spot: they do not touch one another in the model, so each moves as alone), run to
    !> end_time [s] with output every output_step [s] on the given INTEGRATOR keywords.
    function disk_fleet_dataset(count, spacing, end_time, output_step, integrator) result(text)
        integer, intent(in) :: count
        real(wp), intent(in) :: spacing, end_time, output_step
        !> INTEGRATOR keywords after the slash ("FORMULATION=CVODE, ERROR=1e-8")
        character(len=*), intent(in) :: integrator
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")
        real(wp) :: theta
        integer :: p, part, marker, k

        theta = (90.0_wp - tilt_deg)*acos(-1.0_wp)/180.0_wp
        text = to_text(count) // " rolling disks, independent (rollcon_disk_fleet)" // nl // nl &
            & // "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND" // nl // nl &
            & // "PART/1, GROUND" // nl // "MARKER/1, PART=1" // nl // nl
        do p = 1, count
            part = p + 1
            marker = 10*part
            ! the centre R sin(theta) above the ground; rolling along X at v, spinning at -v/R
            ! about the disk axis (the CM marker's z, tilted by tilt_deg from ground Y)
            text = text // "PART/" // to_text(part) // ", MASS=" // to_text(mass) // ", CM=" &
                & // to_text(marker) // nl // ", IP=" // to_text(diametral) // ", " &
                & // to_text(diametral) // ", " // to_text(axial) // nl // ", QG=0, " &
                & // to_text(spacing*(p - 1)) // ", " // to_text(radius*sin(theta)) // nl &
                & // ", VX=" // to_text(speed) // nl // ", WZ=" // to_text(-speed/radius) // nl &
                & // "MARKER/" // to_text(marker) // ", PART=" // to_text(part) &
                & // ", QP=0, 0, 0, REULER=0D, " // to_text(90.0_wp - tilt_deg) // "D, 0D" // nl
            do k = 1, 3
                text = text // "UCON/" // to_text(3*(p - 1) + k) // ", FUNCTION=USER(" &
                    & // to_text(part) // ", 21, 22, 23, 14, 15, 24, 25, 26, " &
                    & // to_text(radius) // ", " // to_text(k) // ")" // nl
            end do
            text = text // nl
        end do
        text = text // "ACCGRAV/KGRAV=-9.81" // nl // nl // "SIMULATE/DYNAMIC, END=" &
            & // to_text(end_time) // ", DTOUT=" // to_text(output_step) // nl &
            & // "INTEGRATOR/" // integrator // nl // nl // "END" // nl
    end function disk_fleet_dataset

end module rollcon_disk_fleet
