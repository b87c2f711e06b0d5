! SPDX-License-Identifier: MIT
!> The physical ranges every input is held to, scenes and datasets alike (docs/scenes.md,
!> docs/datasets.md): beyond them a rigid body with SI tolerances is not a meaningful model, and
!> the arithmetic of its equations (squares in norms and Newton matrices) nears overflow.
module rollcon_physical_ranges
    use rollcon_kinds, only : wp
    implicit none
    private

    !> Speed of light [m/s]: the bound of every speed, rigid-body mechanics being Newtonian
    real(wp), parameter, public :: light = 299792458.0_wp
    !> Largest length [m] (1000 km) and smallest (1 um) of a body's dimension
    real(wp), parameter, public :: length_max = 1.0e6_wp, length_min = 1.0e-6_wp
    !> Largest position [m]: a start 1e9 m away still resolves 1e-7 m in a double
    real(wp), parameter, public :: position_max = 1.0e9_wp
    !> Largest angle [rad]: sin and cos of 1e6 rad still resolve 1e-10 rad
    real(wp), parameter, public :: angle_max = 1.0e6_wp
    !> Largest rate [rad/s]
    real(wp), parameter, public :: rate_max = 1.0e6_wp
    !> Largest gravity [m/s^2], 36 times the Sun's surface gravity
    real(wp), parameter, public :: gravity_max = 1.0e4_wp
    !> Largest mass [kg]: a cube of osmium 1 km on a side is 2.3e13 kg
    real(wp), parameter, public :: mass_max = 1.0e15_wp
    !> Largest principal moment [kg m^2]: the largest mass at the largest length
    real(wp), parameter, public :: inertia_max = mass_max*length_max**2
    !> Largest force [N] and moment [N m] a force statement may give: the weight of the largest
    !> mass at the largest gravity, at the largest length
    real(wp), parameter, public :: force_max = mass_max*gravity_max
    real(wp), parameter, public :: moment_max = force_max*length_max

end module rollcon_physical_ranges
