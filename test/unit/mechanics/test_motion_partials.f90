! SPDX-License-Identifier: MIT
!> A MOTION's UCON as the model serves it (suite motion-partials; src/mechanics/
!> rollcon_motion.f90, rollcon_motion_geometry.f90): for every direction (X, Y, Z, B1, B2, B3
!> between two parts, and with J on the ground; a joint's ROTATION), F = s(q) - h(t) against
!> the closed form of s in the markers' ground frames, and every partial the constraints ask
!> for checked entry by entry: dF/dq against fourth-order central differences of F in each
!> coordinate, d2F/dq dq against those of dF/dq, dF/dt and d2F/dt2 against those in t,
!> d2F/dt dq zero. (The angles' routines are checked here, at a state away from the pole of
!> atan2, rather than at the generic test's random states: generated_specs_list's
!> pole_free.) The same motion given as a VELOCITY and as an ACCELERATION (with ICDISP and
!> ICVEL) gives the same F and time partials: the quadratures of its time part agree with the
!> closed form.
module test_motion_partials
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix
    use rollcon_body, only : part_type
    use rollcon_marker, only : marker_type, marker_motion
    use rollcon_expression, only : expression_type
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_motion, only : motion_type, prepare_motion, motion_form_displacement, &
        & motion_form_velocity, motion_form_acceleration
    use rollcon_motion_geometry, only : motion_x, motion_y, motion_z, motion_b1, motion_b2, &
        & motion_b3, motion_rotation
    use rollcon_model, only : model_type, setup_model
    use rollcon_constraints, only : constraint_state_type, need_value, need_first, need_second, &
        & need_time
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_motion_partials

    !> A state of two parts in general position [m, rad, m/s, rad/s]
    real(wp), parameter :: q_state(12) = [0.1_wp, -0.2_wp, 0.3_wp, 0.4_wp, 1.1_wp, -0.3_wp, &
        & -0.15_wp, 0.25_wp, 0.05_wp, -0.6_wp, 0.8_wp, 0.9_wp]
    !> The time of the check [s]
    real(wp), parameter :: t_check = 0.4_wp
    !> h(t) = 0.1 sin 3t + 0.02 t^2, and its derivatives written out
    character(len=*), parameter :: displacement = "0.1*SIN(3*TIME) + 0.02*TIME**2", &
        & velocity = "0.3*COS(3*TIME) + 0.04*TIME", acceleration = "-0.9*SIN(3*TIME) + 0.04"

contains

    subroutine collect_motion_partials(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("every-direction-against-its-closed-form-and-differences", &
            & test_directions), &
            & new_unittest("velocity-and-acceleration-forms-integrate-to-the-displacement", &
            & test_forms)]
    end subroutine collect_motion_partials

    !> Each direction, between two parts and with J on the ground (not X, Y, Z: refused with I
    !> on the ground only), and a joint's ROTATION.
    subroutine test_directions(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: components(7) = [motion_x, motion_y, motion_z, motion_b1, &
            & motion_b2, motion_b3, motion_rotation]
        character(len=*), parameter :: names(7) = [character(len=8) :: "X", "Y", "Z", "B1", &
            & "B2", "B3", "ROTATION"]
        type(model_type) :: model
        type(constraint_state_type) :: state
        type(marker_type) :: i, j
        real(wp) :: expected, h
        integer :: c, ground

        do ground = 0, 1
            do c = 1, size(components)
                call two_part_model(model, i, j, ground == 1)
                call model%add_motion(new_motion(displacement, motion_form_displacement), &
                    & components(c), components(c) == motion_rotation, i, j, error)
                if (allocated(error)) return
                call setup_model(model, error)
                if (allocated(error)) return
                call state%allocate(model)
                call state%evaluate(model, t_check, q_state, 0.0_wp*q_state, need_value &
                    & + need_first + need_second + need_time, error)
                if (allocated(error)) return
                h = 0.1_wp*sin(3.0_wp*t_check) + 0.02_wp*t_check**2
                expected = closed_form(components(c), i, j) - h
                ! the closed forms from the same frames: rounding of a few operations
                call check(error, state%value(1), expected, names(c) // " F, ground " &
                    & // to_text(ground), abs_tol=1.0e-13_wp)
                if (allocated(error)) return
                call check_partials(model, state, trim(names(c)) // ", ground " &
                    & // to_text(ground), error)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_directions

    !> The motion as a VELOCITY (ICDISP = h(0) = 0) and as an ACCELERATION (ICDISP = 0,
    !> ICVEL = h'(0) = 0.3) gives the displacement form's F, dF/dt and d2F/dt2.
    subroutine test_forms(error)
        type(error_type), allocatable, intent(out) :: error
        !> The quadratures to 1e-14 relative of their panels' integral of |f|: measured 1e-16;
        !> 1e-13 is a thousandth of a wrong ICVEL's 0.3 t by one in 1e9
        real(wp), parameter :: tol = 1.0e-13_wp
        type(model_type) :: model
        type(constraint_state_type) :: state
        type(marker_type) :: i, j
        type(motion_type) :: motion
        real(wp) :: reference(3)
        integer :: form

        do form = motion_form_displacement, motion_form_acceleration
            call two_part_model(model, i, j, .false.)
            select case (form)
            case (motion_form_velocity)
                motion = new_motion(velocity, form)
            case (motion_form_acceleration)
                motion = new_motion(acceleration, form)
                motion%initial_velocity = 0.3_wp
            case default
                motion = new_motion(displacement, form)
            end select
            call prepare_motion(motion, 1.0_wp)
            call model%add_motion(motion, motion_z, .false., i, j, error)
            if (allocated(error)) return
            call setup_model(model, error)
            if (allocated(error)) return
            call state%allocate(model)
            call state%evaluate(model, t_check, q_state, 0.0_wp*q_state, need_value &
                & + need_time, error)
            if (allocated(error)) return
            if (form == motion_form_displacement) then
                reference = [state%value(1), state%dt(1), state%dtt(1)]
                cycle
            end if
            call check(error, maxval(abs([state%value(1), state%dt(1), state%dtt(1)] &
                & - reference)) <= tol, "form " // to_text(form) // ": F, dF/dt, d2F/dt2 " &
                & // "differ from the displacement form's by " // to_text(maxval(abs( &
                & [state%value(1), state%dt(1), state%dtt(1)] - reference))))
            if (allocated(error)) return
        end do
    end subroutine test_forms

    !> dF/dq against fourth-order central differences of F in each of the twelve coordinates,
    !> d2F/dq dq (over the UCON's own coordinates) against those of dF/dq, dF/dt and d2F/dt2
    !> against those in t, d2F/dt dq zero.
    subroutine check_partials(model, state, what, error)
        type(model_type), intent(in) :: model
        type(constraint_state_type), intent(in) :: state
        character(len=*), intent(in) :: what
        type(error_type), allocatable, intent(out) :: error
        !> Fourth-order differences with step 1e-3 (rad or m): truncation ~ step^4 |F^(5)|,
        !> about 1e-12 here; rounding ~ 1e-16/step = 1e-13; 1e-9 is a thousandth of any
        !> partial's size that matters (a wrong sign or a missing term is order 0.1)
        real(wp), parameter :: step = 1.0e-3_wp, tol = 1.0e-9_wp
        type(constraint_state_type) :: probe
        real(wp) :: q(12), f(-2:2), difference, second, g(12, -2:2)
        integer :: n, k, a, b

        call probe%allocate(model)
        do n = 1, 12
            do k = -2, 2
                q = q_state
                q(n) = q(n) + k*step
                call probe%evaluate(model, t_check, q, 0.0_wp*q, need_value, error)
                if (allocated(error)) return
                f(k) = probe%value(1)
            end do
            difference = (f(-2) - 8.0_wp*f(-1) + 8.0_wp*f(1) - f(2))/(12.0_wp*step)
            call check(error, state%grad_q_entry(1, n), difference, what // " dF/dq(" &
                & // to_text(n) // ")", abs_tol=tol)
            if (allocated(error)) return
        end do
        ! d2F/dq dq column by column over the UCON's own coordinates
        do b = 1, state%local_count(1)
            n = state%local(b, 1)
            do k = -2, 2
                q = q_state
                q(n) = q(n) + k*step
                call probe%evaluate(model, t_check, q, 0.0_wp*q, need_first, error)
                if (allocated(error)) return
                call probe%fill_grad_q_row(1, g(:, k))
            end do
            do a = 1, state%local_count(1)
                associate (m => state%local(a, 1))
                    difference = (g(m, -2) - 8.0_wp*g(m, -1) + 8.0_wp*g(m, 1) - g(m, 2)) &
                        & /(12.0_wp*step)
                    call check(error, state%hqq(a, b, 1), difference, what // " d2F/dq dq(" &
                        & // to_text(m) // "," // to_text(n) // ")", abs_tol=tol)
                    if (allocated(error)) return
                end associate
            end do
        end do
        do k = -2, 2
            call probe%evaluate(model, t_check + k*step, q_state, 0.0_wp*q_state, need_value, &
                & error)
            if (allocated(error)) return
            f(k) = probe%value(1)
        end do
        difference = (f(-2) - 8.0_wp*f(-1) + 8.0_wp*f(1) - f(2))/(12.0_wp*step)
        second = (-f(-2) + 16.0_wp*f(-1) - 30.0_wp*f(0) + 16.0_wp*f(1) - f(2)) &
            & /(12.0_wp*step**2)
        call check(error, state%dt(1), difference, what // " dF/dt", abs_tol=tol)
        if (allocated(error)) return
        ! the second difference divides rounding by step^2: 1e-16/1e-6 = 1e-10, and 1e-7
        call check(error, state%dtt(1), second, what // " d2F/dt2", abs_tol=1.0e-7_wp)
        if (allocated(error)) return
        call check(error, all(state%dt_grad_q(:, 1) == 0.0_wp), what // " d2F/dt dq is zero")
    end subroutine check_partials

    !> s(q) at q_state from the markers' ground frames (docs/datasets.md, "MOTION").
    function closed_form(component, i, j) result(s)
        integer, intent(in) :: component
        type(marker_type), intent(in) :: i, j
        real(wp) :: s
        real(wp) :: r_i(3), r_j(3), a_i(3, 3), a_j(3, 3), v(3), w(3)

        call marker_motion(i, q_state, 0.0_wp*q_state, r_i, v, a_i, w)
        call marker_motion(j, q_state, 0.0_wp*q_state, r_j, v, a_j, w)
        select case (component)
        case (motion_x, motion_y, motion_z)
            s = dot_product(r_i - r_j, a_j(:, component))
        case (motion_b1)
            s = atan2(-dot_product(a_i(:, 3), a_j(:, 2)), dot_product(a_i(:, 3), a_j(:, 3)))
        case (motion_b2)
            s = atan2(dot_product(a_i(:, 3), a_j(:, 1)), sqrt(dot_product(a_i(:, 3), &
                & a_j(:, 2))**2 + dot_product(a_i(:, 3), a_j(:, 3))**2))
        case (motion_b3)
            s = atan2(-dot_product(a_i(:, 2), a_j(:, 1)), dot_product(a_i(:, 1), a_j(:, 1)))
        case default
            s = atan2(dot_product(a_i(:, 1), a_j(:, 2)), dot_product(a_i(:, 1), a_j(:, 1)))
        end select
    end function closed_form

    !> Parts 7 and 9 (the second is the ground's place when ground: J on the ground), markers
    !> in general position.
    subroutine two_part_model(model, i, j, ground)
        type(model_type), intent(out) :: model
        type(marker_type), intent(out) :: i, j
        logical, intent(in) :: ground

        call model%add_part(part_type(id=7, mass=1.0_wp, inertia=[1.0_wp, 1.5_wp, 2.0_wp]))
        call model%add_part(part_type(id=9, mass=2.0_wp, inertia=[1.0_wp, 1.0_wp, 1.5_wp]))
        i = marker_type(id=21, part=1, point=[0.1_wp, -0.2_wp, 0.3_wp], &
            & axes=rotation_matrix(0.3_wp, 1.1_wp, -0.4_wp))
        j = marker_type(id=31, part=merge(0, 2, ground), point=[-0.05_wp, 0.15_wp, 0.25_wp], &
            & axes=rotation_matrix(-0.7_wp, 0.6_wp, 0.2_wp))
    end subroutine two_part_model

    !> MOTION/1 with function `text` of the form given, in SI.
    function new_motion(text, form) result(motion)
        character(len=*), intent(in) :: text
        integer, intent(in) :: form
        type(motion_type) :: motion
        type(error_type), allocatable :: error

        motion%id = 1
        motion%name = "MOTION/1"
        motion%form = form
        call compile_expression(text, "MOTION/1 FUNCTION", motion%function, error)
    end function new_motion

end module test_motion_partials
