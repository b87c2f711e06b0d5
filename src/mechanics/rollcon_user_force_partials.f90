! SPDX-License-Identifier: MIT
!> The partials of a force served by a user's routine (SFOSUB, VFOSUB, GFOSUB, VTOSUB:
!> rollcon_user_forces) for the integrators' Newton matrices, as ADAMS/Solver forms them: the
!> routine's initialisation call (IFLAG = .TRUE.) declares, by the SYSFNC and SYSARY calls it
!> makes, which markers' measures it reads and whether it reads rates; its values are
!> differenced over the coordinates (and, when it declared rates, the rates) of those markers'
!> parts only, each difference a call with DFLAG = .TRUE. A routine is code rollcon cannot
!> see into, so differences are the only way to its partials; the rest of the load (the line
!> of action, RM's axes, the arm about each part's centre) is the statement's own geometry,
!> in jets (rollcon_force_partials), exact.
!>
!> The differences are central, of step eps^(1/3) max(|y|, 1) (rollcon_central_differences,
!> which VARSUBs and DIFSUBs are differenced with too). Two calls per declared entry: 24 for a
!> routine reading the coordinates and rates of one moving part, once per Newton matrix
!> (CVODE and IDA form one every several steps), a cost the calls of the residuals dwarf.
!>
!> What the routine reads beyond its declaration is left out of its partials, as ADAMS leaves
!> it; each such read is noted (rollcon_user_forces' system_notes, which `rollcon check`
!> reports). A difference call that fails (an ERRMES, a value that is not finite) leaves its
!> error for take_user_force_error and its entry out.
!>
!> The partials in the accelerations, where a routine reads them (the algebraic loop of
!> rollcon_equations and rollcon_dae), are differenced the same way: a force routine's over
!> the accelerations of its declared parts (add_user_force_acceleration_partials), a VARSUB's
!> chained through an expression force's exact partials in VARVAL
!> (add_variable_acceleration_partials).
module rollcon_user_force_partials
    use rollcon_kinds, only : wp
    use rollcon_momentum_partials, only : momentum_partials_type
    use rollcon_jet, only : jet_type, jet_constant
    use rollcon_measures, only : state_jets_type
    use rollcon_force, only : applied_force_type, profile_statement
    use rollcon_marker_force, only : marker_force_type
    use rollcon_force_partials, only : statement_parts, statement_state_jets, &
        & add_statement_load_partials, add_expression_force_partials
    use rollcon_expression, only : quantity_varval
    use rollcon_user_variable_values, only : set_user_variable_partials, &
        & clear_user_variable_partials
    use rollcon_user_forces, only : difference_call, acceleration_difference_call, &
        & multiplier_difference_call
    use rollcon_central_differences, only : central_differences
    implicit none
    private

    public :: add_user_force_partials, add_user_force_acceleration_partials
    public :: add_variable_acceleration_partials, add_variable_multiplier_partials
    public :: add_user_force_multiplier_partials

contains

    !> Subtract the partials of every force served by a user's routine from dm (dm/dq, dm/du),
    !> the partials of the momentum residual M a - f (n x n, n = 6 parts: dense or on pairs of
    !> parts holding the force's, rollcon_momentum_partials), at (t, q, u): the
    !> routine's values differenced over its declared state entries (module doc), the loads'
    !> geometry exact. The values at (t, q, u) are those the last evaluation kept
    !> (marker_force_type's user_values, evaluate_user_forces at this state).
    subroutine add_user_force_partials(forces, time, q, u, dm)
        type(applied_force_type), intent(in) :: forces(:)
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        type(momentum_partials_type), intent(inout) :: dm
        type(state_jets_type) :: state
        type(jet_type) :: values(6)
        integer, allocatable :: parts(:)
        real(wp), allocatable :: gradients(:, :)
        integer :: i, k, np

        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine == 0) cycle
            associate (s => forces(i)%statement)
                parts = statement_parts(s)
                np = size(parts)
                if (np == 0) cycle
                state = statement_state_jets(parts, q, u, .true.)
                allocate(gradients(12*np, 6), source=0.0_wp)
                if (allocated(s%declared_parts)) call difference_values(forces(i), parts, &
                    & s%declared_parts, s%declared_rates, time, q, u, gradients)
                do k = 1, 6
                    values(k) = jet_constant(s%user_values(k))
                    if (all(gradients(:, k) == 0.0_wp)) cycle
                    values(k)%active = .true.
                    values(k)%g = gradients(:, k)
                end do
                call add_statement_load_partials(s, values, state, q, dm)
                deallocate(gradients)
            end associate
        end do
    end subroutine add_user_force_partials

    !> Subtract the partials in the accelerations a of every force whose routine read
    !> accelerations at its initialisation call (SYSARY('TACC'|'RACC'), SYSFNC('ACCX' ...
    !> 'WDTM')) from dm_da, the partials of the momentum residual M a - f in a (n x n), at
    !> (t, q, u, a): its values differenced over the accelerations of its declared parts
    !> (central differences, rollcon_central_differences, each call with DFLAG = .TRUE.), the
    !> load's geometry exact (rollcon_force_partials, which takes them where a rate's partials
    !> go: the geometry depends on q alone). The values at (t, q, u, a) are those the last
    !> evaluation kept (evaluate_user_forces with these accelerations set).
    subroutine add_user_force_acceleration_partials(forces, time, q, u, a, dm_da)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), intent(in) :: time
        !> Coordinates, rates and accelerations of all parts [SI]
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp), intent(inout) :: dm_da(:, :)
        type(state_jets_type) :: state
        type(jet_type) :: values(6)
        integer, allocatable :: parts(:), entries(:), rows(:)
        real(wp), allocatable :: gradients(:, :), block(:, :)
        type(momentum_partials_type) :: image
        integer :: i, k, np, d, p, c

        call image%init_dense(size(dm_da, 1))
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine == 0) cycle
            if (.not. forces(i)%statement%declared_accelerations) cycle
            associate (s => forces(i)%statement)
                parts = statement_parts(s)
                np = size(parts)
                if (np == 0 .or. .not. allocated(s%declared_parts)) cycle
                state = statement_state_jets(parts, q, u, .true.)
                allocate(gradients(12*np, 6), source=0.0_wp)
                entries = [integer ::]
                rows = [integer ::]
                do d = 1, size(s%declared_parts)
                    p = findloc(parts, s%declared_parts(d), dim=1)
                    if (p == 0) cycle
                    entries = [entries, [(6*(s%declared_parts(d) - 1) + c, c = 1, 6)]]
                    rows = [rows, [(6*np + 6*(p - 1) + c, c = 1, 6)]]
                end do
                allocate(block(size(entries), 6), source=0.0_wp)
                call central_differences(a, entries, accelerations_moved, block)
                gradients(rows, :) = block
                do k = 1, 6
                    values(k) = jet_constant(s%user_values(k))
                    if (all(gradients(:, k) == 0.0_wp)) cycle
                    values(k)%active = .true.
                    values(k)%g = gradients(:, k)
                end do
                ! the load's partials in the rates' slots are its partials in a
                image%dq = 0.0_wp
                image%du = dm_da
                call add_statement_load_partials(s, values, state, q, image)
                dm_da = image%du
                deallocate(gradients, block)
            end associate
        end do

    contains

        subroutine accelerations_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call acceleration_difference_call(forces(i), time, q, u, shifted, values, failed)
        end subroutine accelerations_moved

    end subroutine add_user_force_acceleration_partials

    !> Subtract from dm_da (n x n) the partials in the accelerations of every force written as
    !> an expression that reads VARVAL of a VARSUB whose initialisation call read
    !> accelerations: d(load)/d VARVAL (exact, the expression's jets: rollcon_force_partials)
    !> times d VARVAL/da (dv_da(k, j) for the VARIABLE ids(k): rollcon_user_forces'
    !> difference_variable_accelerations). VARVAL's jets carry dv_da in the rates' slots (and
    !> nothing in the coordinates'), so the statement's partials in the rates with them, less
    !> its partials in the rates without them, are that product (the jets are linear in their
    !> seeds); the load's geometry depends on q alone. The VARVAL partials set before are
    !> cleared (the equations set them where they form dm/dq and dm/du, and clear them after).
    !> A force routine reading VARVAL is served by add_user_force_acceleration_partials (the
    !> VARSUB's accelerations join its declaration).
    subroutine add_variable_acceleration_partials(forces, time, q, u, ids, dv_da, dm_da)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [SI]
        real(wp), intent(in) :: q(:), u(:)
        !> The user VARIABLEs' ids and their partials in the accelerations (size(ids) x n)
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: dv_da(:, :)
        real(wp), intent(inout) :: dm_da(:, :)
        real(wp), allocatable :: zero(:, :)
        type(momentum_partials_type) :: without, with
        integer :: i

        if (size(ids) == 0) return
        if (all(dv_da == 0.0_wp)) return
        allocate(zero(size(dv_da, 1), size(dv_da, 2)), source=0.0_wp)
        call without%init_dense(size(dm_da, 1))
        call with%init_dense(size(dm_da, 1))
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine > 0) cycle
            if (.not. reads_loop_variable(forces(i)%statement)) cycle
            call without%clear()
            call with%clear()
            call clear_user_variable_partials()
            call add_expression_force_partials(forces(i)%statement, time, q, u, without)
            call set_user_variable_partials(ids, zero, dv_da)
            call add_expression_force_partials(forces(i)%statement, time, q, u, with)
            dm_da = dm_da + (with%du - without%du)
        end do
        call clear_user_variable_partials()

    contains

        !> The statement's expressions read VARVAL of a VARIABLE whose dv_da row is not zero.
        logical function reads_loop_variable(statement) result(reads)
            type(marker_force_type), intent(in) :: statement
            integer :: k, m, v

            reads = .false.
            do k = 1, 6
                if (.not. statement%given(k)) cycle
                if (.not. allocated(statement%functions(k)%inputs)) cycle
                do m = 1, size(statement%functions(k)%inputs)
                    associate (input => statement%functions(k)%inputs(m))
                        if (input%quantity /= quantity_varval) cycle
                        v = findloc(ids, input%marker, dim=1)
                        if (v == 0) cycle
                        if (any(dv_da(v, :) /= 0.0_wp)) reads = .true.
                    end associate
                end do
            end do
        end function reads_loop_variable

    end subroutine add_variable_acceleration_partials
    !> Subtract from dm_dlambda (n x nc) the partials in the multipliers of every force written
    !> as an expression that reads VARVAL of a VARSUB whose initialisation call read a
    !> constraint's reaction: d(load)/d VARVAL (exact, the expression's jets) times
    !> d VARVAL/d lambda (dv_dlambda(k, r) for the VARIABLE ids(k): rollcon_user_forces'
    !> difference_variable_multipliers), as add_variable_acceleration_partials chains
    !> d VARVAL/da: VARVAL's jets carry the partials in up to n multipliers at a time in the
    !> rates' slots, and the statement's partials in the rates with them, less without them,
    !> are those columns. A force routine reading VARVAL is served by
    !> add_user_force_multiplier_partials (the VARSUB's rows join its declaration).
    subroutine add_variable_multiplier_partials(forces, time, q, u, ids, dv_dlambda, &
            & dm_dlambda)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [SI]
        real(wp), intent(in) :: q(:), u(:)
        !> The user VARIABLEs' ids and their partials in the multipliers (size(ids) x nc)
        integer, intent(in) :: ids(:)
        real(wp), intent(in) :: dv_dlambda(:, :)
        real(wp), intent(inout) :: dm_dlambda(:, :)
        real(wp), allocatable :: slots(:, :), partials(:, :)
        integer :: n, first, last

        if (size(ids) == 0) return
        if (all(dv_dlambda == 0.0_wp)) return
        n = size(dm_dlambda, 1)
        allocate(slots(size(ids), n), partials(n, n))
        do first = 1, size(dv_dlambda, 2), n
            last = min(first + n - 1, size(dv_dlambda, 2))
            if (all(dv_dlambda(:, first:last) == 0.0_wp)) cycle
            slots = 0.0_wp
            slots(:, :last - first + 1) = dv_dlambda(:, first:last)
            partials = 0.0_wp
            call add_variable_acceleration_partials(forces, time, q, u, ids, slots, partials)
            dm_dlambda(:, first:last) = dm_dlambda(:, first:last) &
                & + partials(:, :last - first + 1)
        end do
    end subroutine add_variable_multiplier_partials

    !> Subtract the partials in the multipliers lambda of every force whose routine read a
    !> constraint's reaction at its initialisation call (SYSFNC's force measures summing a
    !> JOINT's or JPRIM's reaction: marker_force_type's declared_rows) from dm_dlambda, the
    !> partials of the momentum residual M a - f in lambda (n x nc), at (t, q, u, lambda):
    !> its values differenced over the multipliers of the declared rows alone (central
    !> differences, rollcon_central_differences, each call with DFLAG = .TRUE.), each column
    !> carried to the momentum rows by the load's geometry (rollcon_force_partials, exact:
    !> the generalised force is linear in the values at fixed q, so the column is the
    !> geometry's image of the values' partials, taken where a rate's partials go). The values
    !> at (t, q, u, lambda) are those the last evaluation kept.
    subroutine add_user_force_multiplier_partials(forces, time, q, u, lambda, dm_dlambda)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [SI], multipliers
        real(wp), intent(in) :: q(:), u(:), lambda(:)
        real(wp), intent(inout) :: dm_dlambda(:, :)
        type(state_jets_type) :: state
        type(jet_type) :: values(6)
        integer, allocatable :: parts(:)
        real(wp), allocatable :: block(:, :)
        type(momentum_partials_type) :: image
        integer :: i, k, np, r, column

        call image%init_dense(size(dm_dlambda, 1))
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%routine == 0) cycle
            if (.not. allocated(forces(i)%statement%declared_rows)) cycle
            if (size(forces(i)%statement%declared_rows) == 0) cycle
            associate (s => forces(i)%statement, rows => forces(i)%statement%declared_rows)
                parts = statement_parts(s)
                np = size(parts)
                if (np == 0) cycle
                state = statement_state_jets(parts, q, u, .true.)
                allocate(block(size(rows), 6), source=0.0_wp)
                call central_differences(lambda, rows, multipliers_moved, block)
                ! the first part's first rate: the slot each column's partials are taken in
                column = 6*(parts(1) - 1) + 1
                do r = 1, size(rows)
                    do k = 1, 6
                        values(k) = jet_constant(s%user_values(k))
                        if (block(r, k) == 0.0_wp) cycle
                        values(k)%active = .true.
                        allocate(values(k)%g(12*np), source=0.0_wp)
                        values(k)%g(6*np + 1) = block(r, k)
                    end do
                    call image%clear()
                    call add_statement_load_partials(s, values, state, q, image)
                    dm_dlambda(:, rows(r)) = dm_dlambda(:, rows(r)) + image%du(:, column)
                end do
                deallocate(block)
            end associate
        end do

    contains

        subroutine multipliers_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call multiplier_difference_call(forces(i), time, q, u, shifted, values, failed)
        end subroutine multipliers_moved

    end subroutine add_user_force_multiplier_partials

    !> gradients(v, k): value k's partial in variable v of statement_state_jets(parts), by
    !> central differences (rollcon_central_differences) over the coordinates of the declared
    !> parts (and their rates when rates), each call with DFLAG = .TRUE.; the other entries
    !> are left as they are.
    subroutine difference_values(force, parts, declared, rates, time, q, u, gradients)
        type(applied_force_type), intent(in) :: force
        integer, intent(in) :: parts(:), declared(:)
        logical, intent(in) :: rates
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(inout) :: gradients(:, :)
        integer, allocatable :: entries(:), rows(:)
        real(wp), allocatable :: block(:, :)
        integer :: d, s, c, np

        np = size(parts)
        entries = [integer ::]
        rows = [integer ::]
        do d = 1, size(declared)
            s = findloc(parts, declared(d), dim=1)
            if (s == 0) cycle
            entries = [entries, [(6*(declared(d) - 1) + c, c = 1, 6)]]
            rows = [rows, [(6*(s - 1) + c, c = 1, 6)]]
        end do
        allocate(block(size(entries), 6))
        block = gradients(rows, :)
        call central_differences(q, entries, coordinates_moved, block)
        gradients(rows, :) = block
        if (.not. rates) return
        block = gradients(6*np + rows, :)
        call central_differences(u, entries, rates_moved, block)
        gradients(6*np + rows, :) = block

    contains

        subroutine coordinates_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call difference_call(force, time, shifted, u, values, failed)
        end subroutine coordinates_moved

        subroutine rates_moved(shifted, values, failed)
            real(wp), intent(in) :: shifted(:)
            real(wp), intent(out) :: values(:)
            logical, intent(out) :: failed

            call difference_call(force, time, q, shifted, values, failed)
        end subroutine rates_moved

    end subroutine difference_values

end module rollcon_user_force_partials
