! SPDX-License-Identifier: MIT
!> The names of the columns rollcon's own watches add to a run's rows (rollcon_output_layout):
!> written by the watches, recognised by a reader of the CSV. A rim contact's six
!> (rollcon_contact_watch), the basis of every part a re-basing run records
!> (rollcon_theta_watch), the six of each displacement request (rollcon_request_watch), and
!> the force or torque of each MOTION (rollcon_motion_watch).
module rollcon_watch_columns
    implicit none
    private

    public :: contact_names, basis_pattern, request_column_patterns, motion_column_patterns

    !> A rim contact's columns, in order: the constraint force on the part Fx, Fy, Fz [N]
    !> (ground components), its normal part Fn [N], the friction coefficient rolling needs
    !> |F_tangential| / Fn [-] (0 when Fn <= 0) and the height residual Z - R sin(theta) [m]
    character(len=*), parameter :: contact_names(6) = [character(len=15) :: "Fx", "Fy", "Fz", &
        & "Fn", "mu_needed", "height_residual"]
    !> The basis column of a part ("<id>": the part's id)
    character(len=*), parameter :: basis_pattern = "basis_<id>"
    !> A displacement request's columns ("<n>": the request's id): marker I from marker J,
    !> x, y, z [m] and the 3-1-3 angles psi, theta, phi [rad] in RM's axes
    character(len=*), parameter :: request_column_patterns(6) = [character(len=12) :: &
        & "req<n>_x", "req<n>_y", "req<n>_z", "req<n>_psi", "req<n>_theta", "req<n>_phi"]
    !> A MOTION's column ("<n>": the MOTION's id): the force [N] it exerts on marker I's part
    !> along the axis it drives, or the torque [N m] about it for an angle
    character(len=*), parameter :: motion_column_patterns(2) = [character(len=16) :: &
        & "motion<n>_force", "motion<n>_torque"]

end module rollcon_watch_columns
