! SPDX-License-Identifier: MIT
!> GCON as a UCON (suite gcon): a constraint written as an expression gives the driver the same
!> numbers as the routine the generator writes for the same constraint (F, dF/dq, dF/du,
!> d2F/dq dq, d2F/dq du over the system, at seeded states in general position): DZ(i) - c and
!> DZ(i, j, j) against the INPLANE primitive to ground, a knife edge written as an expression
!> of velocities against the knife_edge routine; its time partials against hand values; and
!> what a GCON may not read (accelerations, forces, velocities not linearly, no moving part)
!> refused with why.
module test_gcon
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_par
    use rollcon_rotation, only : rotation_matrix
    use rollcon_body, only : part_type
    use rollcon_marker, only : marker_type
    use rollcon_expression, only : expression_type
    use rollcon_model, only : model_type, setup_model
    use rollcon_constraints, only : constraint_state_type, need_value, need_first, need_second, &
        & need_time
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_gcon

    !> The generated routine's partials are SymPy's closed forms in double precision, the
    !> GCON's the chain rule through the markers' kinematics: both a few roundings of order-one
    !> terms apart (1e-15); 1e-12 catches any wrong term (of order one)
    real(wp), parameter :: tol = 1.0e-12_wp
    !> Seeded states each comparison is made at
    integer, parameter :: state_count = 200

contains

    subroutine collect_gcon(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("dz-minus-c-is-the-inplane-primitive", test_inplane_origin), &
            & new_unittest("dz-of-two-markers-is-the-inplane-primitive", test_inplane_markers), &
            & new_unittest("knife-edge-expression-is-the-knife-edge", test_knife_edge), &
            & new_unittest("time-partials", test_time), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_gcon

    !> One part (id 7) and marker 11 on it, away from the centre and turned.
    subroutine one_part(model, i)
        type(model_type), intent(out) :: model
        type(marker_type), intent(out) :: i

        call model%add_part(part_type(id=7, mass=1.0_wp, inertia=[1.0_wp, 1.5_wp, 2.0_wp]))
        i = marker_type(id=11, part=1, point=[0.1_wp, -0.2_wp, 0.3_wp], &
            & axes=rotation_matrix(0.3_wp, 1.1_wp, -0.4_wp))
    end subroutine one_part

    !> Append GCON/id = text reading `markers`.
    subroutine add(model, id, text, markers, error)
        type(model_type), intent(inout) :: model
        integer, intent(in) :: id
        character(len=*), intent(in) :: text
        type(marker_type), intent(in) :: markers(:)
        type(error_type), allocatable, intent(out) :: error
        type(expression_type) :: expression

        call compile_expression(text, "test: GCON/" // to_text(id) // " FUNCTION", expression, &
            & error)
        if (allocated(error)) return
        call model%add_gcon(id, expression, markers, markers(1), error)
    end subroutine add

    !> JPRIM INPLANE to a ground J at (0, 0, 0.3) with ground axes, and GCON DZ(11) - 0.3.
    subroutine test_inplane_origin(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, j

        call one_part(model, i)
        j = marker_type(id=10, part=0, point=[0.0_wp, 0.0_wp, 0.3_wp])
        call model%add_jprim(1, "INPLANE", i, j, error)
        if (allocated(error)) return
        call add(model, 2, "DZ(11) - 0.3", [i], error)
        if (allocated(error)) return
        call compare_ucons(model, 1, 2, .false., error)
    end subroutine test_inplane_origin

    !> JPRIM INPLANE to a turned ground J away from the origin, and GCON DZ(11, 10, 10): d . z_j.
    subroutine test_inplane_markers(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, j

        call one_part(model, i)
        j = marker_type(id=10, part=0, point=[0.4_wp, -0.1_wp, 0.3_wp], &
            & axes=rotation_matrix(-0.7_wp, 0.6_wp, 0.2_wp))
        call model%add_jprim(1, "INPLANE", i, j, error)
        if (allocated(error)) return
        call add(model, 2, "DZ(11, 10, 10)", [i, j], error)
        if (allocated(error)) return
        call compare_ucons(model, 1, 2, .false., error)
    end subroutine test_inplane_markers

    !> The knife_edge routine on part 7 (F = -Xdot sin psi + Ydot cos psi) and the same
    !> constraint as an expression of its CM marker 12 (the principal axes: PSI(12) is psi).
    subroutine test_knife_edge(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i, cm
        procedure(ucosub_interface), pointer :: knife
        real(wp), allocatable :: par(:)
        logical :: time_free, found

        call one_part(model, i)
        call find_builtin_ucosub("knife_edge", knife, time_free, found)
        call builtin_ucosub_par("knife_edge", 7, [real(wp) ::], 1, par, error)
        if (allocated(error)) return
        call model%add_ucon(1, par, knife, time_free=time_free, routine="knife_edge")
        cm = marker_type(id=12, part=1, principal=.true.)
        call add(model, 2, "-VX(12)*SIN(PSI(12)) + VY(12)*COS(PSI(12))", [cm], error)
        if (allocated(error)) return
        call compare_ucons(model, 1, 2, .true., error)
    end subroutine test_knife_edge

    !> UCON a (a generated routine's) and UCON b (a GCON) give the same F and partials over
    !> the system at seeded states; velocity: rates too.
    subroutine compare_ucons(model, a, b, velocity, error)
        type(model_type), intent(inout) :: model
        integer, intent(in) :: a, b
        logical, intent(in) :: velocity
        type(error_type), allocatable, intent(out) :: error
        type(constraint_state_type) :: state
        real(wp) :: q(6), u(6), hqq_a(6, 6), hqq_b(6, 6), hqu_a(6, 6), hqu_b(6, 6)
        real(wp) :: row_a(6), row_b(6)
        integer :: k

        call setup_model(model, error)
        if (allocated(error)) return
        call check(error, model%ucons(b)%holonomic .neqv. velocity, "UCON " // to_text(b) &
            & // " should be a " // merge("velocity", "position", velocity) // " constraint")
        if (allocated(error)) return
        call state%allocate(model)
        do k = 1, state_count
            call seeded_state(k, q, u)
            call state%evaluate(model, 0.3_wp, q, u, need_value + need_first + need_second + &
                & need_time, error)
            if (allocated(error)) return
            call check(error, state%value(b), state%value(a), "F at state " // to_text(k), &
                & abs_tol=tol)
            if (allocated(error)) return
            call state%fill_grad_q_row(a, row_a)
            call state%fill_grad_q_row(b, row_b)
            call check(error, row_b, row_a, "dF/dq at state " &
                & // to_text(k), abs_tol=tol)
            if (allocated(error)) return
            call state%fill_grad_u_row(a, row_a)
            call state%fill_grad_u_row(b, row_b)
            call check(error, row_b, row_a, "dF/du at state " &
                & // to_text(k), abs_tol=tol)
            if (allocated(error)) return
            call square(state, a, hqq_a, hqu_a)
            call square(state, b, hqq_b, hqu_b)
            call check(error, reshape(hqq_b, [36]), reshape(hqq_a, [36]), "d2F/dq dq at " &
                & // "state " // to_text(k), abs_tol=tol)
            if (allocated(error)) return
            call check(error, reshape(hqu_b, [36]), reshape(hqu_a, [36]), "d2F/dq du at " &
                & // "state " // to_text(k), abs_tol=tol)
            if (allocated(error)) return
            call check(error, [state%dt(b), state%dtt(b)], [0.0_wp, 0.0_wp], "no time in F")
            if (allocated(error)) return
        end do
    end subroutine compare_ucons

    !> UCON k's second partials over the part's six coordinates (rollcon_constraints keeps
    !> them over each UCON's own coordinates, in ascending order).
    subroutine square(state, k, hqq, hqu)
        type(constraint_state_type), intent(in) :: state
        integer, intent(in) :: k
        real(wp), intent(out) :: hqq(6, 6), hqu(6, 6)
        integer :: a, b

        hqq = 0.0_wp
        hqu = 0.0_wp
        do b = 1, state%local_count(k)
            do a = 1, state%local_count(k)
                hqq(state%local(a, k), state%local(b, k)) = state%hqq(a, b, k)
                hqu(state%local(a, k), state%local(b, k)) = state%hqu(a, b, k)
            end do
        end do
    end subroutine square

    !> State k of a sequence with no relation to the geometry: coordinates in (-2, 2) m and
    !> rad (theta in (0.2, 2.9), off the singularity), rates in (-3, 3).
    pure subroutine seeded_state(k, q, u)
        integer, intent(in) :: k
        real(wp), intent(out) :: q(6), u(6)
        integer :: c

        do c = 1, 6
            q(c) = 2.0_wp*sin(1.7_wp*k + 0.91_wp*c*c)
            u(c) = 3.0_wp*cos(0.37_wp*k*c + 2.3_wp*c)
        end do
        q(5) = 1.55_wp + 1.35_wp*sin(0.77_wp*k)
    end subroutine seeded_state

    !> GCON DX(11) - SIN(2 TIME): dF/dt = -2 cos(2 t), d2F/dt2 = 4 sin(2 t), d2F/dt dq = 0.
    subroutine test_time(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(marker_type) :: i
        type(constraint_state_type) :: state
        real(wp) :: q(6), u(6)

        call one_part(model, i)
        call add(model, 1, "DX(11) - SIN(2*TIME)", [i], error)
        if (allocated(error)) return
        call setup_model(model, error)
        if (allocated(error)) return
        call check(error, .not. model%ucons(1)%time_free, "a GCON reading TIME is not time-free")
        if (allocated(error)) return
        call state%allocate(model)
        call seeded_state(3, q, u)
        call state%evaluate(model, 0.7_wp, q, u, need_value + need_first + need_time, error)
        if (allocated(error)) return
        call check(error, [state%dt(1), state%dtt(1)], [-2.0_wp*cos(1.4_wp), &
            & 4.0_wp*sin(1.4_wp)], "dF/dt, d2F/dt2", abs_tol=tol)
        if (allocated(error)) return
        ! over the UCON's own coordinates (zero off them by construction, not stored)
        call check(error, state%dt_grad_q(:state%local_count(1), 1), &
            & spread(0.0_wp, 1, state%local_count(1)), "d2F/dt dq", abs_tol=tol)
    end subroutine test_time

    !> Each refused with its reason: an acceleration, a force of another element, velocities
    !> squared, nothing of a moving part; a product of a velocity and a position is linear in
    !> the rates and accepted.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: texts(5) = [character(len=32) :: "ACCX(11) - 1", &
            & "JOINT(3, 0, 2, 0)", "VX(11)**2 - 1", "DX(10) - 1", "VARVAL(2)"]
        character(len=*), parameter :: expected(5) = [character(len=120) :: &
            & "GCON/1 FUNCTION: ACCX(11): an acceleration, which rollcon knows only once it", &
            & "GCON/1 FUNCTION: JOINT(3, 0, 2, 0): a force, which rollcon solves for", &
            & "GCON/1 FUNCTION: it reads velocities, but F is not linear in them", &
            & "GCON/1 FUNCTION: it reads no marker of a moving part: F = DX(10) - 1", &
            & "GCON/1 FUNCTION: VARVAL(2): a VARIABLE's value, which a dataset's reader puts in"]
        type(model_type) :: model
        type(marker_type) :: i, ground
        integer :: k
        type(error_type), allocatable :: refused

        ground = marker_type(id=10, part=0)
        do k = 1, size(texts)
            call one_part(model, i)
            call add(model, 1, trim(texts(k)), [i, ground], refused)
            call check(error, allocated(refused), trim(texts(k)) // " accepted")
            if (allocated(error)) return
            call check(error, index(refused%message, trim(expected(k))) == 1, refused%message)
            if (allocated(error)) return
            deallocate(refused)
        end do
        call one_part(model, i)
        call add(model, 1, "VX(11)*DX(11) + WZ(11)*DM(11)", [i], error)
    end subroutine test_refusals

end module test_gcon
