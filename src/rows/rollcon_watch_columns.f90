! SPDX-License-Identifier: MIT
!> The names of the columns rollcon's own watches add to a run's rows (rollcon_output_layout):
!> written by the watches, recognised by a reader of the CSV. A rim contact's six
!> (rollcon_contact_watch), a rim's dissipation's three (rollcon_dissipation_watch), the basis
!> of every part a re-basing run records (rollcon_theta_watch), the six of each displacement
!> request (rollcon_request_watch), the force or torque of each MOTION (rollcon_motion_watch),
!> the value of each VARIABLE (rollcon_variable_watch), those of the other requests
!> (rollcon_request_answers), the six of each statement's reaction and of each force request
!> (rollcon_reaction_watch), and the six of each SPRINGDAMPER and BUSHING
!> (rollcon_element_force_watch).
module rollcon_watch_columns
    use rollcon_output_layout, only : output_layout_type, name_length
    implicit none
    private

    public :: contact_names, contact_mode_names, contact_mode_words, dissipation_names, &
        & basis_pattern, contact_column_prefix, contact_column_patterns, contact_prefixes
    public :: request_column_patterns
    public :: motion_column_patterns
    public :: variable_column_patterns, diff_column_patterns
    public :: reaction_suffixes, reaction_column_patterns, answer_column_patterns
    public :: element_reaction_column_patterns, element_force_column_patterns

    !> A rim contact's columns, in order: the constraint force on the part Fx, Fy, Fz [N]
    !> (ground components), its normal part Fn [N], the friction coefficient rolling needs
    !> |F_tangential| / Fn [-] (0 when Fn <= 0) and the height residual Z - R sin(theta) [m]
    character(len=*), parameter :: contact_names(6) = [character(len=15) :: "Fx", "Fy", "Fz", &
        & "Fn", "mu_needed", "height_residual"]
    !> A rim contact's columns with friction (&contact), after those six: the mode (0 rolling,
    !> 1 sliding, 2 flight) and the contact point's slip velocity, ground X and Y [m/s] (in
    !> flight the rim's lowest point's horizontal velocity)
    character(len=*), parameter :: contact_mode_names(3) = [character(len=15) :: "mode", &
        & "slip_x", "slip_y"]
    !> Where a model has several contacts (a dataset's CONTACTs), each contact's columns are
    !> contact_names and contact_mode_names after this prefix ("<n>": its CONTACT's id)
    character(len=*), parameter :: contact_column_prefix = "contact<n>_"
    character(len=*), parameter :: contact_column_patterns(9) = [character(len=26) :: &
        & "contact<n>_Fx", "contact<n>_Fy", "contact<n>_Fz", "contact<n>_Fn", &
        & "contact<n>_mu_needed", "contact<n>_height_residual", "contact<n>_mode", &
        & "contact<n>_slip_x", "contact<n>_slip_y"]
    !> A rim's dissipation's columns (&dissipation, rollcon_dissipation_watch): the power
    !> rolling resistance and the air layer dissipate [W] and the energy both have dissipated
    !> since the start [J]
    character(len=*), parameter :: dissipation_names(3) = [character(len=15) :: &
        & "rolling_power", "air_power", "dissipated"]
    !> The contact's modes in words, by the number the `mode` column writes (0 rolling, 1
    !> sliding, 2 flight): the summary's, a study's measures' (t_rolling, t_sliding, t_flight)
    !> and the pictures' legend's. A mode is the next number and the next word here.
    character(len=*), parameter :: contact_mode_words(0:2) = [character(len=7) :: "rolling", &
        & "sliding", "flight"]
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

    !> A VARIABLE's column ("<n>": the VARIABLE's id): its FUNCTION's value, in the dataset's
    !> units (rollcon_variable_watch)
    character(len=*), parameter :: variable_column_patterns(1) = [character(len=6) :: "var<n>"]

    !> A DIFF's columns ("<n>": the DIFF's id): DIF(id), its state, in its user's units, and
    !> DIF1(id), its rate, in those units per the dataset's time unit (rollcon_diff_watch)
    character(len=*), parameter :: diff_column_patterns(2) = [character(len=11) :: &
        & "diff<n>", "diff<n>_dot"]

    !> A reaction's columns after its stem: force fx, fy, fz [N] and torque tx, ty, tz [N m],
    !> ground axes
    character(len=*), parameter :: reaction_suffixes(6) = [character(len=3) :: "_fx", "_fy", &
        & "_fz", "_tx", "_ty", "_tz"]
    !> Each statement's reaction columns ("<n>": the statement's id, "<id>": a part's id): a
    !> JOINT's and a JPRIM's on the part of marker I at I, a UCON's on its part at its centre
    !> of mass (on each of several parts: ucon<n>_part<id>_...)
    !> and a force request's (a REQUEST/n, FORCE between a JOINT's or JPRIM's markers: on the
    !> part of the request's marker I, at I)
    character(len=*), parameter :: reaction_column_patterns(30) = [character(len=22) :: &
        & "joint<n>_fx", "joint<n>_fy", "joint<n>_fz", "joint<n>_tx", "joint<n>_ty", &
        & "joint<n>_tz", "jprim<n>_fx", "jprim<n>_fy", "jprim<n>_fz", "jprim<n>_tx", &
        & "jprim<n>_ty", "jprim<n>_tz", "ucon<n>_fx", "ucon<n>_fy", "ucon<n>_fz", "ucon<n>_tx", &
        & "ucon<n>_ty", "ucon<n>_tz", "ucon<n>_part<id>_fx", "ucon<n>_part<id>_fy", &
        & "ucon<n>_part<id>_fz", "ucon<n>_part<id>_tx", "ucon<n>_part<id>_ty", &
        & "ucon<n>_part<id>_tz", "req<n>_fx", "req<n>_fy", "req<n>_fz", "req<n>_tx", &
        & "req<n>_ty", "req<n>_tz"]
    !> The reaction columns of the statements of one equation the program serves, as
    !> rollcon_reactions names them (the statement's name in lower case without its slash: a
    !> GCON, a MOTION, a COUPLER, a GEAR; "<n>": its id, "<id>": a part's id): on the part it
    !> holds, at its centre of mass, as a UCON's; on each of several parts
    !> (gcon<n>_part<id>_fx ..., and a RACKPIN's or SCREW JOINT's joint<n>_part<id>_fx ...)
    character(len=*), parameter :: element_reaction_column_patterns(54) = &
        & [character(len=22) :: &
        & "gcon<n>_fx", "gcon<n>_fy", "gcon<n>_fz", "gcon<n>_tx", "gcon<n>_ty", "gcon<n>_tz", &
        & "motion<n>_fx", "motion<n>_fy", "motion<n>_fz", "motion<n>_tx", "motion<n>_ty", &
        & "motion<n>_tz", "coupler<n>_fx", "coupler<n>_fy", "coupler<n>_fz", "coupler<n>_tx", &
        & "coupler<n>_ty", "coupler<n>_tz", "gear<n>_fx", "gear<n>_fy", "gear<n>_fz", &
        & "gear<n>_tx", "gear<n>_ty", "gear<n>_tz", "gcon<n>_part<id>_fx", &
        & "gcon<n>_part<id>_fy", "gcon<n>_part<id>_fz", "gcon<n>_part<id>_tx", &
        & "gcon<n>_part<id>_ty", "gcon<n>_part<id>_tz", "motion<n>_part<id>_fx", &
        & "motion<n>_part<id>_fy", "motion<n>_part<id>_fz", "motion<n>_part<id>_tx", &
        & "motion<n>_part<id>_ty", "motion<n>_part<id>_tz", "coupler<n>_part<id>_fx", &
        & "coupler<n>_part<id>_fy", "coupler<n>_part<id>_fz", "coupler<n>_part<id>_tx", &
        & "coupler<n>_part<id>_ty", "coupler<n>_part<id>_tz", "gear<n>_part<id>_fx", &
        & "gear<n>_part<id>_fy", "gear<n>_part<id>_fz", "gear<n>_part<id>_tx", &
        & "gear<n>_part<id>_ty", "gear<n>_part<id>_tz", "joint<n>_part<id>_fx", &
        & "joint<n>_part<id>_fy", "joint<n>_part<id>_fz", "joint<n>_part<id>_tx", &
        & "joint<n>_part<id>_ty", "joint<n>_part<id>_tz"]
    !> A SPRINGDAMPER's and a BUSHING's columns ("<n>": its id): the force and torque on the
    !> part of its marker I, at I's origin, ground axes (rollcon_element_force_watch)
    character(len=*), parameter :: element_force_column_patterns(12) = &
        & [character(len=18) :: &
        & "springdamper<n>_fx", "springdamper<n>_fy", "springdamper<n>_fz", &
        & "springdamper<n>_tx", "springdamper<n>_ty", "springdamper<n>_tz", "bushing<n>_fx", &
        & "bushing<n>_fy", "bushing<n>_fz", "bushing<n>_tx", "bushing<n>_ty", "bushing<n>_tz"]
    !> The other requests' columns ("<n>": the request's id): a VELOCITY's vx, vy, vz [m/s]
    !> and wx, wy, wz [rad/s], an ACCELERATION's accx, accy, accz [m/s^2] and wdtx, wdty,
    !> wdtz [rad/s^2] (in RM's axes), each expression F1 ... F8 given (the dataset's units); a
    !> FORCE's are req<n>_fx ... req<n>_tz, as a force request's above
    character(len=*), parameter :: answer_column_patterns(20) = [character(len=12) :: &
        & "req<n>_vx", "req<n>_vy", "req<n>_vz", "req<n>_wx", "req<n>_wy", "req<n>_wz", &
        & "req<n>_accx", "req<n>_accy", "req<n>_accz", "req<n>_wdtx", "req<n>_wdty", &
        & "req<n>_wdtz", "req<n>_f1", "req<n>_f2", "req<n>_f3", "req<n>_f4", "req<n>_f5", &
        & "req<n>_f6", "req<n>_f7", "req<n>_f8"]

contains

    !> The contacts whose columns a layout holds, each by the prefix of its columns, in column
    !> order: "" (blank) for a model's one contact (Fn, mode, ... unprefixed), "contact<id>_"
    !> (contact_column_prefix) for each of a dataset's several CONTACTs; none without a
    !> contact's columns. A contact is found by its normal force's column, `Fn` after its
    !> prefix.
    pure function contact_prefixes(layout) result(prefixes)
        type(output_layout_type), intent(in) :: layout
        character(len=name_length), allocatable :: prefixes(:)
        character(len=:), allocatable :: name, stem, id
        integer :: j

        allocate(prefixes(0))
        if (.not. allocated(layout%extra)) return
        ! "contact", the prefix before its "<n>"
        stem = contact_column_prefix(:index(contact_column_prefix, "<n>") - 1)
        do j = 1, size(layout%extra)
            name = trim(layout%extra(j))
            if (name == "Fn") then
                prefixes = [character(len=name_length) :: prefixes, ""]
            else if (len(name) > len(stem) + 3) then
                if (index(name, stem) /= 1 .or. name(len(name) - 2:) /= "_Fn") cycle
                id = name(len(stem) + 1:len(name) - 3)
                if (verify(id, "0123456789") /= 0) cycle
                prefixes = [character(len=name_length) :: prefixes, name(:len(name) - 2)]
            end if
        end do
    end function contact_prefixes

end module rollcon_watch_columns
