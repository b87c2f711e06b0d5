! SPDX-License-Identifier: MIT
!> Checks a dataset as a whole once every statement is read: one ground part, the values a part
!> needs, every reference to a part or marker (those of the joints and of the statements read
!> and not used too), the forces' expressions, the run, and the
!> principal-axes rule at t = 0 (a part whose CM marker's z-axis is parallel to ground z starts
!> at the singularity of its 3-1-3 Euler angles: it starts in turned axes, without EXACT angles).
module rollcon_adm_checks
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_physical_ranges, only : mass_max, inertia_max, position_max, light, rate_max
    use rollcon_part_frames, only : principal_frame, min_sin_theta
    use rollcon_adm_keywords, only : place
    use rollcon_adm_model, only : adm_model_type, adm_part_type, adm_marker_type, &
        & adm_force_type, force_sforce, force_vforce, refers_to_marker, refers_to_part, &
        & force_springdamper, force_bushing, force_vtorque, force_names
    use rollcon_adm_joints, only : adm_joint_type
    use rollcon_adm_motions, only : adm_motion_type
    use rollcon_id_index, only : id_index_type, new_id_index
    use rollcon_adm_run, only : no_simulate_message
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: check_references

contains

    !> The checks of the whole dataset, in time linear in its statements (each reference found
    !> through an index of the ids).
    subroutine check_references(model, error, simulate_needed)
        type(adm_model_type), intent(in) :: model
        type(error_type), allocatable, intent(out) :: error
        !> The dataset must hold its SIMULATE (default); false when the run is given apart
        !> from it (a command file, or `rollcon run --end T --steps N`)
        logical, intent(in), optional :: simulate_needed
        type(id_index_type) :: parts, markers, forces
        integer :: i, previous
        logical :: simulation_needed

        parts = new_id_index(size(model%parts))
        do i = 1, size(model%parts)
            call parts%add(int(model%parts(i)%id, int64), i, previous)
        end do
        markers = new_id_index(size(model%markers))
        do i = 1, size(model%markers)
            call markers%add(int(model%markers(i)%id, int64), i, previous)
        end do
        ! an SFORCE and a GFORCE may share an id: a reference names either
        forces = new_id_index(size(model%forces))
        do i = 1, size(model%forces)
            call forces%add(int(model%forces(i)%id, int64), i, previous)
        end do
        if (count(model%parts%ground) /= 1) then
            call fatal_error(error, model%file // ": a dataset needs exactly one PART with " &
                & // "GROUND, found " // to_text(count(model%parts%ground)), stat_input)
            return
        end if
        do i = 1, size(model%markers)
            if (parts%find(int(model%markers(i)%part, int64)) == 0) then
                call fatal_error(error, place(model%file, model%markers(i)%line) // ": MARKER/" &
                    & // to_text(model%markers(i)%id) // " PART: no PART/" &
                    & // to_text(model%markers(i)%part), stat_input)
                return
            end if
        end do
        do i = 1, size(model%parts)
            call check_part(model, markers, model%parts(i), error)
            if (allocated(error)) return
        end do
        do i = 1, size(model%forces)
            call check_force(model, markers, model%forces(i), error)
            if (allocated(error)) return
        end do
        if (allocated(model%references)) then
            do i = 1, size(model%references)
                call check_reference(model, parts, markers, forces, i, error)
                if (allocated(error)) return
            end do
        end if
        if (model%run%line == 0) then
            simulation_needed = .true.
            if (present(simulate_needed)) simulation_needed = simulate_needed
            if (simulation_needed) then
                call fatal_error(error, no_simulate_message(model%file), stat_input)
                return
            end if
        end if
        if (.not. allocated(model%joints)) return
        do i = 1, size(model%joints)
            call check_joint(model, markers, model%joints(i), error)
            if (allocated(error)) return
        end do
        call check_couplers(model, markers, error)
        if (allocated(error)) return
        if (.not. allocated(model%motions)) return
        do i = 1, size(model%motions)
            call check_motion(model, markers, model%motions(i), error)
            if (allocated(error)) return
        end do
    end subroutine check_references

    !> A GCON's marker I, a GEAR's marker CV, and the JOINTs a COUPLER or GEAR names exist
    !> (which types of joint they may couple, and the markers a GCON's FUNCTION reads, are
    !> judged by the assembly).
    subroutine check_couplers(model, markers, error)
        type(adm_model_type), intent(in) :: model
        type(id_index_type), intent(in) :: markers
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        integer :: i, k

        if (allocated(model%gcons)) then
            do i = 1, size(model%gcons)
                associate (gcon => model%gcons(i))
                    if (markers%find(int(gcon%i, int64)) == 0) call fatal_error(error, &
                        & place(model%file, gcon%line) // ": GCON/" // to_text(gcon%id) &
                        & // " I: no MARKER/" // to_text(gcon%i), stat_input)
                end associate
                if (allocated(error)) return
            end do
        end if
        if (allocated(model%couplers)) then
            do i = 1, size(model%couplers)
                where = place(model%file, model%couplers(i)%line) // ": COUPLER/" &
                    & // to_text(model%couplers(i)%id) // " JOINTS"
                do k = 1, size(model%couplers(i)%joints)
                    call check_joint_id(model, model%couplers(i)%joints(k), where, error)
                    if (allocated(error)) return
                end do
            end do
        end if
        if (.not. allocated(model%gears)) return
        do i = 1, size(model%gears)
            where = place(model%file, model%gears(i)%line) // ": GEAR/" &
                & // to_text(model%gears(i)%id)
            if (markers%find(int(model%gears(i)%cv, int64)) == 0) then
                call fatal_error(error, where // " CV: no MARKER/" &
                    & // to_text(model%gears(i)%cv), stat_input)
                return
            end if
            do k = 1, 2
                call check_joint_id(model, model%gears(i)%joints(k), where // " JOINTS", error)
                if (allocated(error)) return
            end do
        end do
    end subroutine check_couplers

    !> A JOINT with id `id` exists (a JPRIM does not count).
    subroutine check_joint_id(model, id, where, error)
        type(adm_model_type), intent(in) :: model
        integer, intent(in) :: id
        character(len=*), intent(in) :: where
        type(error_type), allocatable, intent(out) :: error

        if (any(model%joints%id == id .and. .not. model%joints%primitive)) return
        call fatal_error(error, where // ": no JOINT/" // to_text(id), stat_input)
    end subroutine check_joint_id

    !> A MOTION's JOINT is a JOINT of the dataset (not a JPRIM), or its markers I and J are
    !> MARKERs (which types of joint take which motion is the assembly's to judge).
    subroutine check_motion(model, markers, motion, error)
        type(adm_model_type), intent(in) :: model
        !> Positions of the markers by id
        type(id_index_type), intent(in) :: markers
        type(adm_motion_type), intent(in) :: motion
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        integer :: k

        where = place(model%file, motion%line) // ": MOTION/" // to_text(motion%id)
        if (motion%joint /= 0) then
            do k = 1, size(model%joints)
                if (model%joints(k)%id == motion%joint .and. .not. model%joints(k)%primitive) &
                    & return
            end do
            call fatal_error(error, where // " JOINT: no JOINT/" // to_text(motion%joint), &
                & stat_input)
        else if (markers%find(int(motion%i, int64)) == 0) then
            call fatal_error(error, where // " I: no MARKER/" // to_text(motion%i), stat_input)
        else if (markers%find(int(motion%j, int64)) == 0) then
            call fatal_error(error, where // " J: no MARKER/" // to_text(motion%j), stat_input)
        end if
    end subroutine check_motion

    !> A JOINT's or JPRIM's markers I and J are MARKERs (which parts they join is the model's
    !> to judge: model%add_joint, model%add_jprim).
    subroutine check_joint(model, markers, joint, error)
        type(adm_model_type), intent(in) :: model
        !> Positions of the markers by id
        type(id_index_type), intent(in) :: markers
        type(adm_joint_type), intent(in) :: joint
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where

        where = place(model%file, joint%line) // ": " // trim(merge("JPRIM", "JOINT", &
            & joint%primitive)) // "/" // to_text(joint%id)
        if (markers%find(int(joint%i, int64)) == 0) then
            call fatal_error(error, where // " I: no MARKER/" // to_text(joint%i), stat_input)
        else if (markers%find(int(joint%j, int64)) == 0) then
            call fatal_error(error, where // " J: no MARKER/" // to_text(joint%j), stat_input)
        end if
    end subroutine check_joint

    !> Reference i of a statement read and not used: its marker, part or force exists
    !> (found through the indexes of their ids).
    subroutine check_reference(model, parts, markers, forces, i, error)
        type(adm_model_type), intent(in) :: model
        !> Positions of the parts, markers and forces (of any kind) by id
        type(id_index_type), intent(in) :: parts, markers, forces
        integer, intent(in) :: i
        type(error_type), allocatable, intent(out) :: error

        associate (reference => model%references(i))
            if (reference%kind == refers_to_marker) then
                if (markers%find(int(reference%id, int64)) == 0) call fatal_error(error, &
                    & reference%at // ": no MARKER/" // to_text(reference%id), stat_input)
            else if (reference%kind == refers_to_part) then
                if (parts%find(int(reference%id, int64)) == 0) call fatal_error(error, &
                    & reference%at // ": no PART/" // to_text(reference%id), stat_input)
            else if (forces%find(int(reference%id, int64)) == 0) then
                call fatal_error(error, reference%at // ": no SFORCE, VFORCE, GFORCE, VTORQUE, " &
                    & // "SPRINGDAMPER or BUSHING with id " &
                    & // to_text(reference%id), stat_input)
            end if
        end associate
    end subroutine check_reference

    subroutine check_part(model, markers, part, error)
        type(adm_model_type), intent(in) :: model
        !> Positions of the markers by id
        type(id_index_type), intent(in) :: markers
        type(adm_part_type), intent(in) :: part
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where
        integer :: m

        where = place(model%file, part%line) // ": PART/" // to_text(part%id)
        if (part%ground) then
            ! ground is the Newtonian frame, at rest: its frame is the ground frame
            if (part%mass /= 0.0_wp .or. part%cm /= 0 .or. any(part%ip /= 0.0_wp) &
                & .or. any(part%velocity_given) .or. any(part%angular_velocity_given) &
                & .or. any(part%qg /= 0.0_wp) .or. any(part%reuler /= 0.0_wp)) &
                & call fatal_error(error, where // ": the ground part takes no MASS, CM, IP, " &
                & // "QG, REULER or velocities (it is the ground frame, at rest)", stat_input)
            return
        end if
        if (.not. part%mass > 0.0_wp) then
            call fatal_error(error, where // " MASS must be > 0 [kg], got " &
                & // to_text(part%mass), stat_input)
            return
        end if
        if (.not. all(part%ip > 0.0_wp)) then
            call fatal_error(error, where // " IP: three principal moments > 0 [kg m^2] are " &
                & // "needed", stat_input)
            return
        end if
        ! a rigid body's principal moments satisfy the triangle inequality (equality: a lamina)
        if (any(part%ip > (sum(part%ip) - part%ip)*(1.0_wp + 1.0e-12_wp))) then
            if (all(part%products == 0.0_wp)) then
                call fatal_error(error, where // " IP: no rigid body has these principal " &
                    & // "moments (each must be at most the sum of the other two)", stat_input)
            else
                call fatal_error(error, where // " IP: no rigid body has this inertia tensor: " &
                    & // "its principal moments " // to_text(part%ip(1)) // ", " &
                    & // to_text(part%ip(2)) // ", " // to_text(part%ip(3)) // " kg m^2 break " &
                    & // "the triangle inequality (each must be at most the sum of the other " &
                    & // "two)", stat_input)
            end if
            return
        end if
        call check_part_ranges(where, part, error)
        if (allocated(error)) return
        m = markers%find(int(part%cm, int64))
        if (part%cm == 0) then
            call fatal_error(error, where // " CM: a MARKER on this part must give the centre " &
                & // "of mass (CM=id)", stat_input)
            return
        end if
        if (m == 0) then
            call fatal_error(error, where // " CM: no MARKER/" // to_text(part%cm) &
                & // " (the centre-of-mass marker must be a MARKER on this part)", stat_input)
            return
        end if
        if (model%markers(m)%part /= part%id) then
            call fatal_error(error, where // " CM: MARKER/" // to_text(part%cm) // " is on PART/" &
                & // to_text(model%markers(m)%part) // ", not on this part", stat_input)
            return
        end if
        call check_principal_axes(where, part, model%markers(m), error)
    end subroutine check_part

    !> The principal-axes rule at t = 0 (docs/rebasing.md): a part whose CM marker's z-axis,
    !> turned by the part's REULER and its own, is parallel to ground z starts in its principal
    !> axes turned 90 degrees about x (rollcon_part_frames), where EXACT angles mean nothing.
    subroutine check_principal_axes(where, part, marker, error)
        !> "file:line: PART/id"
        character(len=*), intent(in) :: where
        type(adm_part_type), intent(in) :: part
        type(adm_marker_type), intent(in) :: marker
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: angles(3) = [character(len=5) :: "PSI", "THETA", "PHI"]
        real(wp) :: r(3, 3), sin_theta

        r = principal_frame(part%reuler, marker%reuler, part%principal)
        sin_theta = hypot(r(1, 3), r(2, 3))
        if (sin_theta >= min_sin_theta .or. .not. any(part%exact(4:6))) return
        call fatal_error(error, where // " EXACT=" // trim(angles(findloc(part%exact(4:6), &
            & .true., dim=1))) // ": the z-axis of its principal axes (its CM marker, MARKER/" &
            & // to_text(marker%id) // ") is parallel to ground z at t = 0 (sin(theta) = " &
            & // to_text(sin_theta) // " < " // to_text(min_sin_theta) // "), so the part " &
            & // "starts in those axes turned 90 degrees about x (docs/rebasing.md), whose " &
            & // "Euler angles are not the CM marker's: hold only X, Y, Z, or turn the CM " &
            & // "marker off ground z", stat_input)
    end subroutine check_principal_axes

    !> A part's values within the physical ranges (rollcon_physical_ranges), in SI after the
    !> dataset's units: MASS, IP, QG, the speed (VX, VY, VZ) below light's, WX..WZ.
    subroutine check_part_ranges(where, part, error)
        !> "file:line: PART/id"
        character(len=*), intent(in) :: where
        type(adm_part_type), intent(in) :: part
        type(error_type), allocatable, intent(out) :: error

        if (.not. part%mass <= mass_max) then
            call fatal_error(error, where // " MASS must be at most " // to_text(mass_max) &
                & // " [kg], got " // to_text(part%mass) // " kg", stat_input)
        else if (.not. all(part%ip <= inertia_max)) then
            call fatal_error(error, where // " IP must be at most " // to_text(inertia_max) &
                & // " [kg m^2] each, got " // to_text(maxval(part%ip)) // " kg m^2", stat_input)
        else if (.not. all(abs(part%qg) <= position_max)) then
            call fatal_error(error, where // " QG must be within " // to_text(position_max) &
                & // " m of the origin in each axis, got " // to_text(maxval(abs(part%qg))) &
                & // " m", stat_input)
        else if (.not. norm2(part%velocity) < light) then
            call fatal_error(error, where // " VX, VY, VZ: the speed must be below the speed " &
                & // "of light " // to_text(light) // " [m/s] (the mechanics is Newtonian), " &
                & // "got " // to_text(norm2(part%velocity)) // " m/s", stat_input)
        else if (.not. all(abs(part%angular_velocity) <= rate_max)) then
            call fatal_error(error, where // " WX, WY, WZ must be at most " // to_text(rate_max) &
                & // " [rad/s] each, got " // to_text(maxval(abs(part%angular_velocity))) &
                & // " rad/s", stat_input)
        end if
    end subroutine check_part_ranges

    subroutine check_force(model, markers, force, error)
        type(adm_model_type), intent(in) :: model
        !> Positions of the markers by id
        type(id_index_type), intent(in) :: markers
        type(adm_force_type), intent(in) :: force
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where, name
        integer :: needed

        name = trim(force_names(force%kind))
        where = place(model%file, force%line) // ": " // name // "/" // to_text(force%id)
        if (force%i == 0) then
            call fatal_error(error, where // " I: a marker id is needed (I=id of an existing " &
                & // "MARKER)", stat_input)
            return
        end if
        call require_marker(force%i, "I")
        call require_marker(force%j, trim(merge("J     ", "JFLOAT", &
            & any(force%kind == [force_sforce, force_springdamper, force_bushing]))))
        call require_marker(force%rm, "RM")
        if (allocated(error)) return
        if (any(force%kind == [force_sforce, force_springdamper, force_bushing]) &
            & .and. force%j == 0) then
            call fatal_error(error, where // " J: " &
                & // trim(merge("an", "a ", force%kind == force_sforce)) // " " // name &
                & // " acts between I and J (J=id)", stat_input)
            return
        end if
        if (any(force%kind == [force_springdamper, force_bushing])) return
        if (force%kind == force_vtorque) then
            if (.not. all(force%given(4:6)) .and. .not. force%user) call fatal_error(error, &
                & where // ": TX=e, TY=e, TZ=e (or FUNCTION=USER(r1, ..., r30)) is needed", &
                & stat_input)
            return
        end if
        needed = merge(1, merge(3, 6, force%kind == force_vforce), force%kind == force_sforce)
        if (force%user) return
        if (.not. all(force%given(:needed))) then
            call fatal_error(error, where // ": " // trim(merge("FUNCTION=e          ", &
                & merge("FX=e, FY=e, FZ=e    ", "FX..FZ and TX..TZ=e ", &
                & force%kind == force_vforce), force%kind == force_sforce)) // " is needed", &
                & stat_input)
        end if

    contains

        !> A marker id given (not 0) must name a MARKER.
        subroutine require_marker(id, key)
            integer, intent(in) :: id
            character(len=*), intent(in) :: key

            if (allocated(error) .or. id == 0) return
            if (markers%find(int(id, int64)) == 0) call fatal_error(error, where // " " // key &
                & // ": no MARKER/" // to_text(id), stat_input)
        end subroutine require_marker

    end subroutine check_force

end module rollcon_adm_checks
