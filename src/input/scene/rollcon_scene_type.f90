! SPDX-License-Identifier: MIT
!> The scene type: one nested type per group of a scene file (`scene%disk%radius`,
!> `scene%run%rtol`), with the documented defaults, and the integer codes of the choices.
!> A new key is a component here and one line in rollcon_scene_keys (docs/scenes.md).
module rollcon_scene_type
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, formulation_ida, &
        & method_bdf, method_adams, drift_none, drift_projection, drift_baumgarte, &
        & jacobian_analytic, jacobian_dq
    implicit none
    private

    public :: scene_type, scene_disk_type, scene_environment_type, scene_initial_type
    public :: scene_strike_type, scene_run_type, scene_limits_type, scene_contact_type
    public :: scene_dissipation_type
    public :: formulation_cvode, formulation_ida, method_bdf, method_adams
    public :: drift_none, drift_projection, drift_baumgarte
    public :: jacobian_analytic, jacobian_dq, height_velocity, height_position

    !> &run height: F3 as a velocity constraint, or Z - R sin(theta) = 0 (docs/design.md §5)
    integer, parameter :: height_velocity = 1, height_position = 2

    !> &disk: a uniform disk (docs/design.md §5)
    type :: scene_disk_type
        !> Radius [m]
        real(wp) :: radius = 0.1_wp
        !> Thickness [m]; enters the inertia only
        real(wp) :: thickness = 0.003_wp
        !> Density [kg/m^3]
        real(wp) :: density = 7800.0_wp
    end type scene_disk_type

    !> &environment
    type :: scene_environment_type
        !> Gravity along -Z [m/s^2]
        real(wp) :: gravity = 9.81_wp
    end type scene_environment_type

    !> &initial: the state at t = 0
    type :: scene_initial_type
        !> 3-1-3 Euler angles of the principal axes [rad]
        real(wp) :: psi = 0.0_wp, theta = pi/2, phi = 0.0_wp
        !> Euler-angle rates [rad/s]
        real(wp) :: psidot = 0.0_wp, thetadot = 0.0_wp, phidot = 0.0_wp
        !> Rolling speed [m/s] of the centre along the heading (cos psi, sin psi, 0), when
        !> given instead of phidot: phidot = -speed/radius - psidot cos(theta)
        real(wp) :: speed = 0.0_wp
        !> Centre position [m]; z is R sin(theta) after a read, given or not, unless given
        !> above it with flight modelled (&contact restitution: the disk starts in flight)
        real(wp) :: x = 0.0_wp, y = 0.0_wp, z = 0.0_wp
        !> Centre velocity [m/s]; the no-slip value after a read, given or not (with &contact
        !> xdot and ydot may slip; a start in flight has the values given, 0 if not)
        real(wp) :: xdot = 0.0_wp, ydot = 0.0_wp, zdot = 0.0_wp
        !> z was given in the file
        logical :: z_given = .false.
        !> xdot, ydot, zdot were given in the file
        logical :: velocity_given = .false.
    end type scene_initial_type

    !> &strike: a half-sine force pulse along +Y at the top of the rim
    type :: scene_strike_type
        !> The file has a &strike group
        logical :: enabled = .false.
        !> Start of the pulse [s]
        real(wp) :: time = 2.0_wp
        !> Length of the pulse [s]
        real(wp) :: duration = 0.01_wp
        !> Impulse carried [N s]
        real(wp) :: impulse = 0.01_wp
    end type scene_strike_type

    !> &contact: Coulomb friction at the rim's contact (docs/design.md §5, "Contact modes").
    !> Without the group the disk rolls without slip whatever force that takes.
    type :: scene_contact_type
        !> The file has a &contact group
        logical :: enabled = .false.
        !> Static friction coefficient [-]: rolling holds while |F_t| < mu_static F_n
        real(wp) :: mu_static = 0.0_wp
        !> Kinetic friction coefficient [-] (mu_static when not given): sliding's friction force
        !> is mu_kinetic F_n against the slip velocity
        real(wp) :: mu_kinetic = 0.0_wp
        !> Restitution given: the disk may leave the ground (flight) and come down on it (an
        !> impact); without it a lift-off ends the run as &limits stop_on_liftoff says
        logical :: flight = .false.
        !> Poisson's coefficient of restitution of an impact [-], 0 <= e <= 1: the normal
        !> impulse of restitution is e times that of compression (docs/design.md §5)
        real(wp) :: restitution = 0.0_wp
    end type scene_contact_type

    !> &dissipation: rolling resistance and the air layer under the rim (docs/design.md §5,
    !> "Dissipation"). Without the group (or with both zero) the rim dissipates nothing.
    type :: scene_dissipation_type
        !> The file has a &dissipation group
        logical :: enabled = .false.
        !> Rolling resistance's lever arm delta [m] >= 0: the energy lost per length rolled
        !> is delta F_n / R
        real(wp) :: rolling_resistance = 0.0_wp
        !> Dynamic viscosity of the air under the disk [Pa s] >= 0 (Moffatt's air layer)
        real(wp) :: air_viscosity = 0.0_wp
    end type scene_dissipation_type

    !> &run: how to integrate (rollcon_run_settings), and the form of the contact's height
    type, extends(run_settings_type) :: scene_run_type
        !> height_velocity or height_position
        integer :: height = height_velocity
    end type scene_run_type

    !> &limits: when to stop early
    type :: scene_limits_type
        !> Stop when theta falls below [rad]
        real(wp) :: theta_min = 0.05_wp
        !> Stop when the normal force turns negative
        logical :: stop_on_liftoff = .true.
    end type scene_limits_type

    !> A scene: where it was read from, and one component per group
    type :: scene_type
        !> File it was read from
        character(len=:), allocatable :: path
        !> File base name without .nml
        character(len=:), allocatable :: name
        type(scene_disk_type) :: disk
        type(scene_environment_type) :: environment
        type(scene_initial_type) :: initial
        type(scene_strike_type) :: strike
        type(scene_run_type) :: run
        type(scene_limits_type) :: limits
        type(scene_contact_type) :: contact
        type(scene_dissipation_type) :: dissipation
    end type scene_type

end module rollcon_scene_type
