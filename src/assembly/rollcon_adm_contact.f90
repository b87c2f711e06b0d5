! SPDX-License-Identifier: MIT
!> A dataset's CONTACT (rollcon_adm_contacts) as the model holds it: a part's sphere or rim on
!> the ground's plane, its three no-slip rows served by a built-in routine (a sphere:
!> rolling_sphere; a rim: the hand-checked disk, the scenes' routine) under the user's
!> CONTACT/id, and the contact's watch (rollcon_contact_watch) with its Coulomb friction,
!> restitution and modes, as a disk scene builds it (rollcon_disk_scene's disk_contact_watch);
!> or on a turntable's top (rollcon_adm_turntable), its rows relative to the table
!> (turntable_ball, turntable_disk). docs/datasets.md, "CONTACT" and "CONTACT on a turntable",
!> says what is read and what is refused.
module rollcon_adm_contact
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, place
    use rollcon_rotation, only : rotation_matrix
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_par
    use rollcon_model, only : model_type
    use rollcon_problem, only : problem_type
    use rollcon_sliding_contact, only : sliding_contact_type
    use rollcon_watch_columns, only : contact_column_prefix
    use rollcon_run_settings, only : formulation_speeds, formulation_ida
    use rollcon_contact_watch, only : contact_watch_type, mode_sliding, mode_flight
    use rollcon_dissipation_watch, only : dissipation_watch_type
    use rollcon_rim_dissipation, only : air_coefficient
    use rollcon_adm_model, only : adm_model_type, adm_part_type, adm_marker_type
    use rollcon_adm_contacts, only : adm_contact_type, adm_graphics_type, graphics_ellipsoid, &
        & graphics_cylinder, graphics_plane
    use rollcon_adm_turntable, only : turntable_type, find_turntable
    implicit none
    private

    public :: contact_shape_type, contact_shape, add_contact_ucons, add_contact_watch

    !> Geometric tolerance of the checks, relative to the radius (or 1 m for the plane's
    !> height): the numbers a dataset writes to full precision agree to rounding (1e-16), and a
    !> geometry off by more than 1e-9 of its size is not the one rollcon models
    real(wp), parameter :: geometry_tolerance = 1.0e-9_wp
    !> Lift-off threshold as a fraction of the force scale, and per unit rtol (the disk
    !> scenes' rule, rollcon_disk_scene)
    real(wp), parameter :: liftoff_fraction = 1.0e-5_wp, liftoff_per_rtol = 100.0_wp
    !> The routines of the no-slip rows: a sphere's, a rim's
    character(len=*), parameter :: sphere_routine = "rolling_sphere", rim_routine = "disk"
    !> The routines of the no-slip rows relative to a turntable: a sphere's, a rim's
    character(len=*), parameter :: sphere_table_routine = "turntable_ball", &
        & rim_table_routine = "turntable_disk"

    !> What a CONTACT is, as rollcon models it
    type :: contact_shape_type
        !> "file:line: CONTACT/id", the start of messages, and "CONTACT/id"
        character(len=:), allocatable :: where, name
        !> The part in contact: its id and its place in model order (ground not counted)
        integer :: part_id = 0, part = 0
        !> A sphere (else a rim), its radius [m]
        logical :: sphere = .false.
        real(wp) :: radius = 0.0_wp
        !> The plane is a turntable's top (else the ground's), and the table
        logical :: on_table = .false.
        type(turntable_type) :: table
    end type contact_shape_type

contains

    !> The contact's part and shape from its IGEOM and JGEOM: one a PLANE on the ground whose
    !> RM has its origin at Z = 0 and its z along ground +Z (rollcon's ground plane), or on a
    !> turntable (find_turntable: the table's errors with its JOINT or MOTION), the other
    !> on a part: an ELLIPSOID of equal XSCALE, YSCALE, ZSCALE (a sphere of radius XSCALE/2)
    !> centred at the part's centre of mass, or a CYLINDER whose axis (its CM marker's z) is
    !> the part's principal z-axis through the centre of mass (a rim of radius RADIUS in the
    !> section through the centre of mass: the rolling disk of docs/design.md §5). Errors, with
    !> the GRAPHICS and why: a GRAPHICS that is not there or not of these shapes, two planes
    !> or none, a plane elsewhere, a sphere off centre or not round, a cylinder off axis.
    subroutine contact_shape(adm, contact, shape, error)
        type(adm_model_type), intent(in) :: adm
        type(adm_contact_type), intent(in) :: contact
        type(contact_shape_type), intent(out) :: shape
        type(error_type), allocatable, intent(out) :: error
        type(adm_graphics_type) :: body, plane
        integer :: g(2), k, found(2), p, m, cm
        real(wp) :: origin(3), axis(3), centre(3), principal_z(3), offset(3), part_axes(3, 3)

        shape%name = "CONTACT/" // to_text(contact%id)
        shape%where = place(adm%file, contact%line) // ": " // shape%name
        g = [contact%igeom, contact%jgeom]
        do k = 1, 2
            found(k) = 0
            if (allocated(adm%graphics)) found(k) = findloc(adm%graphics%id, g(k), dim=1)
            if (found(k) == 0) then
                call fatal_error(error, place(adm%file, merge(contact%igeom_line, &
                    & contact%jgeom_line, k == 1)) // ": " // shape%name // " " &
                    & // trim(merge("IGEOM", "JGEOM", k == 1)) // ": GRAPHICS/" &
                    & // to_text(g(k)) // " is not an ELLIPSOID, CYLINDER or PLANE of the " &
                    & // "dataset (rollcon's contact is a part's sphere or rim on the " &
                    & // "ground's plane)", stat_input)
                return
            end if
        end do
        if (count(adm%graphics(found)%shape == graphics_plane) /= 1) then
            call fatal_error(error, shape%where // ": IGEOM and JGEOM must name one PLANE (the " &
                & // "ground's) and one ELLIPSOID or CYLINDER (the part's), got " &
                & // to_text(count(adm%graphics(found)%shape == graphics_plane)) // " planes", &
                & stat_input)
            return
        end if
        if (adm%graphics(found(1))%shape == graphics_plane) then
            plane = adm%graphics(found(1))
            body = adm%graphics(found(2))
        else
            plane = adm%graphics(found(2))
            body = adm%graphics(found(1))
        end if
        ! the plane: on the ground, through Z = 0, its normal +Z
        call marker_in_ground(adm, plane%marker, origin, axis, p, error)
        if (allocated(error)) then
            error%message = graphics_at(plane) // " RM: " // error%message
            return
        end if
        if (.not. adm%parts(p)%ground) then
            ! a plane on a moving part: a turntable's top (rollcon_adm_turntable)
            shape%on_table = .true.
            call find_turntable(adm, shape%where, plane%marker, plane%line, p, shape%table, &
                & error)
            if (allocated(error)) return
        else if (abs(origin(3)) > geometry_tolerance &
            & .or. axis(3) < 1.0_wp - geometry_tolerance) then
            call fatal_error(error, graphics_at(plane) // ": " // shape%name // "'s plane " &
                & // "must be the ground plane Z = 0 with its normal +Z: a PLANE on the " &
                & // "ground whose RM marker has its origin at Z = 0 and its z along ground " &
                & // "+Z (rollcon's rolling routines hold a contact on that plane); RM is at " &
                & // "Z = " // to_text(origin(3)) // " with z = (" // to_text(axis(1)) // ", " &
                & // to_text(axis(2)) // ", " // to_text(axis(3)) // ")", stat_input)
            return
        end if
        ! the body: its part, centre of mass and principal z-axis in ground
        call marker_in_ground(adm, body%marker, origin, axis, p, error)
        if (allocated(error)) then
            error%message = graphics_at(body) // " CM: " // error%message
            return
        end if
        if (adm%parts(p)%ground) then
            call fatal_error(error, graphics_at(body) // ": " // shape%name // "'s sphere or " &
                & // "cylinder is on the ground; it must be on a moving part", stat_input)
            return
        end if
        if (shape%on_table .and. p == shape%table%part) then
            call fatal_error(error, graphics_at(body) // ": " // shape%name // "'s sphere or " &
                & // "cylinder is on the turntable PART/" // to_text(shape%table%part_id) &
                & // " whose top is its plane; it must be on another part", stat_input)
            return
        end if
        shape%part_id = adm%parts(p)%id
        shape%part = count(.not. adm%parts(:p)%ground)
        cm = adm%parts(p)%cm
        call marker_in_ground(adm, cm, centre, principal_z, m, error)
        if (allocated(error)) return
        m = findloc(adm%markers%id, cm, dim=1)
        part_axes = matmul(rotation_matrix(adm%parts(p)%reuler(1), adm%parts(p)%reuler(2), &
            & adm%parts(p)%reuler(3)), rotation_matrix(adm%markers(m)%reuler(1), &
            & adm%markers(m)%reuler(2), adm%markers(m)%reuler(3)))
        principal_z = matmul(part_axes, adm%parts(p)%principal(:, 3))
        offset = origin - centre
        select case (body%shape)
        case (graphics_ellipsoid)
            shape%sphere = .true.
            shape%radius = 0.5_wp*body%scales(1)
            if (.not. shape%radius > 0.0_wp .or. any(abs(body%scales - body%scales(1)) &
                & > geometry_tolerance*body%scales(1))) then
                call fatal_error(error, graphics_at(body) // ": " // shape%name // " takes " &
                    & // "an ELLIPSOID that is a sphere (XSCALE = YSCALE = ZSCALE > 0, its " &
                    & // "diameter), got " // to_text(body%scales(1)) // ", " &
                    & // to_text(body%scales(2)) // ", " // to_text(body%scales(3)), stat_input)
                return
            end if
            if (norm2(offset) > geometry_tolerance*shape%radius) then
                call fatal_error(error, graphics_at(body) // ": " // shape%name // "'s " &
                    & // "sphere must be centred at the part's centre of mass (its CM " &
                    & // "marker at PART/" // to_text(shape%part_id) // "'s CM): the rolling " &
                    & // "sphere's contact point is G - R Z; it is " // to_text(norm2(offset)) &
                    & // " m from it", stat_input)
                return
            end if
        case (graphics_cylinder)
            shape%radius = body%radius
            if (.not. shape%radius > 0.0_wp) then
                call fatal_error(error, graphics_at(body) // ": " // shape%name // " takes " &
                    & // "a CYLINDER of RADIUS > 0, got " // to_text(body%radius), stat_input)
                return
            end if
            if (norm2(cross(axis, principal_z)) > geometry_tolerance .or. &
                & norm2(offset - dot_product(offset, principal_z)*principal_z) &
                & > geometry_tolerance*shape%radius) then
                call fatal_error(error, graphics_at(body) // ": " // shape%name // "'s " &
                    & // "cylinder must have its axis (its CM marker's z) along PART/" &
                    & // to_text(shape%part_id) // "'s principal z-axis through its centre " &
                    & // "of mass: rollcon models it as the rim of the section through the " &
                    & // "centre of mass (the rolling disk, docs/design.md section 5)", stat_input)
                return
            end if
        case default
            call fatal_error(error, graphics_at(body) // ": " // shape%name // " takes an " &
                & // "ELLIPSOID (a sphere) or a CYLINDER (a rim) on the part", stat_input)
        end select

    contains

        !> "file:line: GRAPHICS/id".
        function graphics_at(graphics) result(text)
            type(adm_graphics_type), intent(in) :: graphics
            character(len=:), allocatable :: text

            text = place(adm%file, graphics%line) // ": GRAPHICS/" // to_text(graphics%id)
        end function graphics_at

        pure function cross(a, b) result(c)
            real(wp), intent(in) :: a(3), b(3)
            real(wp) :: c(3)

            c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
        end function cross
    end subroutine contact_shape

    !> Marker id's origin [m] and z-axis in ground at the dataset's start, and its part's place
    !> in adm%parts. An error when there is no such marker.
    subroutine marker_in_ground(adm, id, origin, axis, p, error)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: id
        real(wp), intent(out) :: origin(3), axis(3)
        integer, intent(out) :: p
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: frame(3, 3)
        integer :: m

        origin = 0.0_wp
        axis = 0.0_wp
        p = 0
        m = 0
        if (id > 0) m = findloc(adm%markers%id, id, dim=1)
        if (m == 0) then
            call fatal_error(error, "MARKER/" // to_text(id) // " is not in the dataset", &
                & stat_input)
            return
        end if
        p = findloc(adm%parts%id, adm%markers(m)%part, dim=1)
        associate (part => adm%parts(p), marker => adm%markers(m))
            frame = rotation_matrix(part%reuler(1), part%reuler(2), part%reuler(3))
            origin = part%qg + matmul(frame, marker%qp)
            axis = matmul(matmul(frame, rotation_matrix(marker%reuler(1), marker%reuler(2), &
                & marker%reuler(3))), [0.0_wp, 0.0_wp, 1.0_wp])
        end associate
    end subroutine marker_in_ground

    !> Each CONTACT's three no-slip rows (its point's velocity along ground X, Y, and its
    !> height's rate), appended to the model's UCONs as CONTACT/id's equations: the routine
    !> computes in the dataset's units (its radius in them, as a UCON's PAR); on a turntable
    !> the rows are relative to the table (table_routine). shapes: each CONTACT's, in the
    !> dataset's order; rows(:, c): CONTACT c's rows' numbers in model order (tangential X, Y,
    !> normal). Each contact has its own mode (the equations' contact for the first, their
    !> more_contacts for the others: add_contact_watch).
    subroutine add_contact_ucons(adm, model, shapes, rows, error)
        type(adm_model_type), intent(in) :: adm
        type(model_type), intent(inout) :: model
        type(contact_shape_type), allocatable, intent(out) :: shapes(:)
        integer, allocatable, intent(out) :: rows(:, :)
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: par(:), pars(:, :), parameters(:)
        character(len=:), allocatable :: name
        logical :: time_free, found
        integer :: k, c

        allocate(shapes(0), rows(3, 0))
        if (.not. allocated(adm%contacts)) return
        deallocate(shapes, rows)
        allocate(shapes(size(adm%contacts)), rows(3, size(adm%contacts)))
        do c = 1, size(adm%contacts)
            call contact_shape(adm, adm%contacts(c), shapes(c), error)
            if (allocated(error)) return
            associate (shape => shapes(c))
                name = merge(sphere_routine, rim_routine // "          ", shape%sphere)
                name = trim(name)
                parameters = [shape%radius/adm%units%length]
                if (shape%on_table) call table_routine(shape, adm%units%length, name, parameters)
                call find_builtin_ucosub(name, routine, time_free, found)
                do k = 1, 3
                    call builtin_ucosub_par(name, shape%part_id, parameters, k, par, error)
                    if (allocated(error)) return
                    if (k == 1) then
                        if (allocated(pars)) deallocate(pars)
                        allocate(pars(size(par), 3))
                    end if
                    pars(:, k) = par
                end do
                rows(:, c) = model%ucon_count() + [1, 2, 3]
                call model%add_element_ucons(shape%name, adm%contacts(c)%id, &
                    & adm%contacts(c)%line, routine, name, time_free, pars, &
                    & [character(len=40) :: "no slip along ground X", &
                    & "no slip along ground Y", "height held (its rate)"])
            end associate
        end do
    end subroutine add_contact_ucons

    !> The routine of a contact's rows on a turntable and its physical parameters, in the
    !> dataset's units (length: its length unit [m]; the rate per its time unit): a sphere's
    !> turntable_ball (radius, rate, the axis' X and Y), a rim's turntable_disk (radius, the
    !> axis' X and Y, the mean rate, no ripple) (ucon/specs/turntable_ball.py,
    !> turntable_disk.py): the no-slip rows relative to the table.
    pure subroutine table_routine(shape, length, name, parameters)
        type(contact_shape_type), intent(in) :: shape
        real(wp), intent(in) :: length
        character(len=:), allocatable, intent(out) :: name
        real(wp), allocatable, intent(out) :: parameters(:)

        associate (table => shape%table)
            if (shape%sphere) then
                name = sphere_table_routine
                parameters = [shape%radius/length, table%dataset_rate, table%axis/length]
            else
                name = rim_table_routine
                parameters = [shape%radius/length, table%axis/length, table%dataset_rate, &
                    & 0.0_wp, 0.0_wp]
            end if
        end associate
    end subroutine table_routine

    !> The contact's watch on the problem (after problem%init), its start's mode set in the
    !> equations for the initial-conditions analysis (a sliding start's tangential rows, a
    !> flying start's three, are not made to hold). The start slides where its slip is above
    !> its integration error (atol + rtol (|v_G| + R |omega|)), flies where flight is modelled
    !> (RESTITUTION_COEFFICIENT) and the sphere or rim is above the ground. Refused, with
    !> CONTACT/id and why: FORMULATION=MAGGI (the contact's modes are the ODE and DAE
    !> forms'), a start below the ground or above it without a restitution, a part the
    !> dataset constrains otherwise, and rolling resistance or an air layer on a sphere.
    !> Several CONTACTs: each its own mode (the equations' contact for the one whose rim
    !> dissipates, else for the first; the others their more_contacts, in the dataset's order),
    !> its own watch, its columns' names starting "contact<id>_" and its summary's lines
    !> "CONTACT/id (line n)"; ROLLING_RESISTANCE and AIR_VISCOSITY on one of them (a second
    !> refused: the equations hold one rim's dissipation), in the ODE form (CVODE; refused on
    !> IDA). shapes and rows as add_contact_ucons made them.
    subroutine add_contact_watch(adm, shapes, rows, problem, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        type(contact_shape_type), intent(in) :: shapes(:)
        integer, intent(in) :: rows(:, :)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: c, rim, slots(size(shapes))

        if (size(shapes) == 0) return
        if (allocated(problem%eq%more_contacts)) deallocate(problem%eq%more_contacts)
        if (size(shapes) > 1) allocate(problem%eq%more_contacts(size(shapes) - 1))
        ! the CONTACT whose rim dissipates, if any: at most one (the equations hold one rim's
        ! rolling resistance and air layer, with the contact's mode: docs/design.md §5)
        rim = 0
        do c = 1, size(shapes)
            if (.not. (adm%contacts(c)%rolling_resistance > 0.0_wp &
                & .or. adm%contacts(c)%air_viscosity > 0.0_wp)) cycle
            if (rim > 0) then
                call fatal_error(error, shapes(c)%where // ": ROLLING_RESISTANCE and " &
                    & // "AIR_VISCOSITY are modelled on one CONTACT of a dataset (the " &
                    & // "equations hold one rim's dissipation: docs/design.md section 5, " &
                    & // "Dissipation), and " // shapes(rim)%name // " (line " &
                    & // to_text(adm%contacts(rim)%line) // ") gives them already", stat_input)
                return
            end if
            rim = c
        end do
        if (rim > 0 .and. size(shapes) > 1 .and. &
            & problem%settings%formulation == formulation_ida) then
            ! beside further contacts the DAE form's Newton iteration has not been made to
            ! converge with the rim's laws (IDA stalls at the start): CVODE integrates them
            call fatal_error(error, shapes(rim)%where // ": ROLLING_RESISTANCE and " &
                & // "AIR_VISCOSITY beside other CONTACTs are integrated in the ODE form: " &
                & // "write INTEGRATOR/FORMULATION=CVODE (the DAE form, IDA, takes them on a " &
                & // "dataset's only CONTACT)", stat_input)
            return
        end if
        ! each CONTACT's mode in the equations: the dissipating rim's is their contact (slot
        ! 0), whose mode its rolling resistance couples to; the others their more_contacts in
        ! the dataset's order
        slots = [(c - 1, c = 1, size(shapes))]
        if (rim > 1) slots = [(merge(0, merge(c, c - 1, c < rim), c == rim), &
            & c = 1, size(shapes))]
        do c = 1, size(shapes)
            call add_one_contact_watch(adm, c, slots(c), shapes(c), rows(:, c), problem, q0, &
                & u0, error)
            if (allocated(error)) return
        end do
    end subroutine add_contact_watch

    !> CONTACT c's watch (add_contact_watch), its mode the equations' contact (slot 0) or
    !> more_contacts(slot).
    subroutine add_one_contact_watch(adm, c, slot, shape, rows, problem, q0, u0, error)
        type(adm_model_type), intent(in) :: adm
        integer, intent(in) :: c, slot
        type(contact_shape_type), intent(in) :: shape
        integer, intent(in) :: rows(3)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(contact_watch_type) :: watch
        real(wp) :: slip(2), height, tolerance, force_scale, omega(3)
        integer :: i0, k, j

        associate (contact => adm%contacts(c), settings => problem%settings)
            if (settings%formulation == formulation_speeds) then
                call fatal_error(error, shape%where // ": a CONTACT's modes (rolling, " &
                    & // "sliding, flight) are integrated in the ODE form (CVODE) and the DAE " &
                    & // "form (IDA), not in independent speeds: write " &
                    & // "INTEGRATOR/FORMULATION=CVODE or IDA", stat_input)
                return
            end if
            ! the part is the contact's alone: the contact's force is the part's constraint
            ! force, and an impact's impulse acts on the free part
            do k = 1, size(problem%model%ucons)
                if (any(rows == k)) cycle
                if (.not. allocated(problem%model%ucons(k)%coordinate)) cycle
                do j = 1, size(problem%model%ucons(k)%coordinate)
                    if ((problem%model%ucons(k)%coordinate(j) - 1)/6 + 1 /= shape%part) cycle
                    call fatal_error(error, shape%where // ": PART/" // to_text(shape%part_id) &
                        & // " is constrained by " // problem%model%row_words(k) // " too; " &
                        & // "rollcon's contact holds a part that nothing else constrains " &
                        & // "(its force is the part's constraint force, an impact acts on " &
                        & // "the free part)", stat_input)
                    return
                end do
            end do
            i0 = 6*(shape%part - 1)
            watch%slot = slot
            if (size(adm%contacts) > 1) then
                watch%label = shape%name // " (line " // to_text(contact%line) // ")"
                ! contact_column_prefix, "contact<n>_", with the CONTACT's id
                k = index(contact_column_prefix, "<n>")
                watch%column_prefix = contact_column_prefix(:k - 1) // to_text(contact%id) &
                    & // contact_column_prefix(k + 3:)
            end if
            watch%part = shape%part
            watch%radius = shape%radius
            watch%sphere = shape%sphere
            watch%mu_static = contact%mu_static
            watch%mu_kinetic = contact%mu_dynamic
            watch%tangential = rows(1:2)
            watch%normal = rows(3)
            watch%flight = contact%restitution_given
            watch%restitution = contact%restitution
            watch%stop_on_liftoff = .not. watch%flight
            if (shape%on_table) then
                ! the plane is a turntable's top: heights from it, slips relative to it
                watch%plane_height = shape%table%height
                watch%table_rate = shape%table%rate
                watch%table_axis = shape%table%axis
            end if
            ! force scale: the weight plus the centripetal force of the initial spin
            omega = watch%angular_velocity(q0, u0)
            force_scale = problem%model%parts(shape%part)%mass*(norm2(adm%gravity) &
                & + shape%radius*dot_product(omega, omega))
            watch%liftoff_force = max(liftoff_fraction, liftoff_per_rtol*settings%rtol) &
                & *force_scale
            tolerance = settings%atol + settings%rtol*shape%radius
            height = watch%height_residual(q0)
            if (height < -tolerance .or. (.not. watch%flight .and. height > tolerance)) then
                call fatal_error(error, shape%where // ": PART/" // to_text(shape%part_id) &
                    & // " starts with its " // trim(merge("sphere", "rim   ", shape%sphere)) &
                    & // "'s lowest point at Z = " // to_text(height) // " m: it must start " &
                    & // "on the ground (within " // to_text(tolerance) // " m), or above it " &
                    & // "with RESTITUTION_COEFFICIENT (flight modelled)", stat_input)
                return
            end if
            slip = watch%slip_velocity(q0, u0)
            if (norm2(slip) > settings%atol + settings%rtol*(norm2(u0(i0 + 1:i0 + 3)) &
                & + shape%radius*norm2(u0(i0 + 4:i0 + 6)))) then
                watch%initial_mode = mode_sliding
                watch%initial_direction = slip/norm2(slip)
            end if
            if (watch%flight .and. height > tolerance) watch%initial_mode = mode_flight
            ! the start's mode, for the initial-conditions analysis (the watch sets it again
            ! when the run starts)
            if (slot == 0) then
                call start_mode(problem%eq%contact)
            else
                call start_mode(problem%eq%more_contacts(slot))
            end if
            call problem%add_watch(watch)
            if (contact%rolling_resistance > 0.0_wp .or. contact%air_viscosity > 0.0_wp) then
                if (shape%sphere) then
                    call fatal_error(error, shape%where // ": ROLLING_RESISTANCE and " &
                        & // "AIR_VISCOSITY are a rim's laws (docs/design.md section 5, " &
                        & // "Dissipation); a sphere takes neither", stat_input)
                    return
                end if
                ! the rim's rolling resistance and air layer, as a disk scene's
                problem%eq%dissipation%part = shape%part
                problem%eq%dissipation%normal = rows(3)
                problem%eq%dissipation%height_column = i0 + 3
                problem%eq%dissipation%rolling_resistance = contact%rolling_resistance
                problem%eq%dissipation%air = air_coefficient(contact%air_viscosity, &
                    & shape%radius)
                if (size(adm%contacts) > 1) then
                    call problem%add_watch(dissipation_watch_type(part=shape%part, &
                        & label=shape%name // " (line " // to_text(contact%line) // ")"))
                else
                    call problem%add_watch(dissipation_watch_type(part=shape%part))
                end if
            end if
        end associate

    contains

        !> The start's mode in the equations' contact.
        subroutine start_mode(mode)
            type(sliding_contact_type), intent(inout) :: mode

            mode%tangential = rows(1:2)
            mode%normal = rows(3)
            mode%sliding = watch%initial_mode == mode_sliding
            mode%flying = watch%initial_mode == mode_flight
        end subroutine start_mode
    end subroutine add_one_contact_watch

end module rollcon_adm_contact
