! SPDX-License-Identifier: MIT
!> Physics of the generated constraints, checked against independent formulas: the turntable
!> disk's vector form and time terms, the rolling sphere, the knife edge, the disk height.
!>
!> Not a suite: test_generated collects these tests.
module generated_physics
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_gen_turntable_disk, only : turntable_disk_ucosub, turntable_disk_par
    use rollcon_gen_rolling_sphere, only : rolling_sphere_ucosub, rolling_sphere_par
    use rollcon_gen_knife_edge, only : knife_edge_ucosub, knife_edge_par
    use rollcon_gen_disk_height, only : disk_height_ucosub, disk_height_par
    use rollcon_testing, only : check
    use disk_states, only : seed_random
    implicit none
    private

    public :: test_turntable, test_sphere, test_knife_edge, test_disk_height


contains

    !> The turntable's F against the vector form v_G + omega x r_GC - Omega(t) e_Z x (r_C - c)
    !> (ucon/specs/turntable_disk.py), f(t) against -b Omega(t) and a Omega(t), and the
    !> explicit time dependence present: dF/dt, d2F/dt2 and d2F/dt dq non-zero.
    subroutine test_turntable(error)
        type(error_type), allocatable, intent(out) :: error
        ! Vector and generated forms round differently: 1e-13 of the largest term.
        real(wp), parameter :: tol_rel = 1.0e-13_wp
        real(wp) :: q(30), state(10), radius, a, b, rate_mean, rate_ripple, nu, time, rate
        real(wp) :: omega(3), e_y2(3), r_gc(3), from_axis(3), slip(3), scalar, array(30)
        real(wp) :: xmatrx(30, 30), scale, f_time(3)
        integer :: k, component

        call seed_random(5005)
        q = 0.0_wp
        do k = 1, 200
            call random_number(state)
            state = 4.0_wp*state - 2.0_wp
            call random_number(time)
            time = 10.0_wp*time
            radius = 0.05_wp + 0.1_wp*abs(state(1))
            a = 0.3_wp*state(2)
            b = -0.2_wp*state(3)
            rate_mean = 2.0_wp + state(4)
            rate_ripple = 0.5_wp*state(5)
            nu = 3.0_wp + state(6)
            call random_number(state)
            state = 4.0_wp*state - 2.0_wp
            ! x, y, xdot, ydot, zdot, psi, theta, psidot, thetadot, phidot
            q(:10) = [state(1), state(2), state(3), state(4), state(5), pi*state(6)/2.0_wp, &
                & pi*(state(7) + 2.0_wp)/4.0_wp, 10.0_wp*state(8), 10.0_wp*state(9), &
                & 10.0_wp*state(10)]
            associate (psi => q(6), theta => q(7))
                e_y2 = [-cos(theta)*sin(psi), cos(theta)*cos(psi), sin(theta)]
                omega = q(8)*[0.0_wp, 0.0_wp, 1.0_wp] + q(9)*[cos(psi), sin(psi), 0.0_wp] &
                    & + q(10)*[sin(theta)*sin(psi), -sin(theta)*cos(psi), cos(theta)]
            end associate
            r_gc = -radius*e_y2
            from_axis = [q(1) - a, q(2) - b, 0.0_wp] + r_gc
            rate = rate_mean + rate_ripple*sin(nu*time)
            slip = q(3:5) + cross(omega, r_gc) - rate*[-from_axis(2), from_axis(1), 0.0_wp]
            f_time = [-b*rate, a*rate, 0.0_wp]
            scale = maxval(abs(q(3:5))) + radius*sum(abs(q(8:10))) &
                & + abs(rate)*(abs(q(1) - a) + abs(q(2) - b) + radius)
            do component = 1, 3
                associate (par => turntable_disk_par(1, radius, a, b, rate_mean, rate_ripple, &
                    & nu, component))
                    call evaluate_ucon(turntable_disk_ucosub, 1, time, q, par, [1, 0, 0], &
                        & scalar, array, xmatrx, error)
                    if (allocated(error)) return
                    call check(error, scalar, slip(component), "F" // to_text(component) &
                        & // " at state " // to_text(k), abs_tol=tol_rel*scale)
                    if (allocated(error)) return
                    call evaluate_ucon(turntable_disk_ucosub, 1, time, q, par, [2, 0, 0], &
                        & scalar, array, xmatrx, error)
                    if (allocated(error)) return
                    call check(error, scalar, f_time(component), "f(t) of F" &
                        & // to_text(component) // " at state " // to_text(k), &
                        & abs_tol=tol_rel*abs(rate)*(abs(a) + abs(b)))
                    if (allocated(error)) return
                    if (component == 3) cycle
                    call evaluate_ucon(turntable_disk_ucosub, 1, time, q, par, [3, 2, 0], &
                        & scalar, array, xmatrx, error)
                    if (allocated(error)) return
                    call check(error, scalar /= 0.0_wp .and. count(array /= 0.0_wp) == 3, &
                        & "dF/dt or d2F/dt dq (X or Y, psi, theta) vanish at state " // to_text(k))
                    if (allocated(error)) return
                    call evaluate_ucon(turntable_disk_ucosub, 1, time, q, par, [4, 0, 0], &
                        & scalar, array, xmatrx, error)
                    if (allocated(error)) return
                    call check(error, scalar /= 0.0_wp, "d2F/dt2 vanishes at state " // to_text(k))
                    if (allocated(error)) return
                end associate
            end do
        end do
    end subroutine test_turntable

    pure function cross(a, b) result(c)
        real(wp), intent(in) :: a(3), b(3)
        real(wp) :: c(3)

        c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
    end function cross

    !> The sphere's F against v_G + omega x (-R e_Z) on random states, and zero when rolling
    !> upright along +X (psi = 0, theta = pi/2, phidot = -v/R).
    subroutine test_sphere(error)
        type(error_type), allocatable, intent(out) :: error
        ! Vector and generated forms round differently: 1e-13 of the largest term.
        real(wp), parameter :: tol_rel = 1.0e-13_wp
        real(wp), parameter :: radius = 0.2_wp, speed = 1.5_wp
        real(wp) :: q(30), state(7), omega(3), slip(3), scalar, array(30), xmatrx(30, 30)
        real(wp) :: scale
        integer :: k, component

        call seed_random(6006)
        q = 0.0_wp
        do k = 1, 200
            ! xdot, ydot, zdot, psi, theta, thetadot, phidot
            call random_number(state)
            q(:7) = [4.0_wp*state(1:3) - 2.0_wp, pi*(2.0_wp*state(4) - 1.0_wp), pi*state(5), &
                & 20.0_wp*state(6:7) - 10.0_wp]
            associate (psi => q(4), theta => q(5))
                omega = q(6)*[cos(psi), sin(psi), 0.0_wp] &
                    & + q(7)*[sin(theta)*sin(psi), -sin(theta)*cos(psi), cos(theta)]
            end associate
            slip = q(1:3) + cross(omega, [0.0_wp, 0.0_wp, -radius])
            scale = maxval(abs(q(1:3))) + radius*sum(abs(q(6:7)))
            do component = 1, 3
                call evaluate_ucon(rolling_sphere_ucosub, 1, 0.0_wp, q, &
                    & rolling_sphere_par(1, radius, component), [1, 0, 0], scalar, array, &
                    & xmatrx, error)
                if (allocated(error)) return
                call check(error, scalar, slip(component), "F" // to_text(component) &
                    & // " at state " // to_text(k), abs_tol=tol_rel*scale)
                if (allocated(error)) return
            end do
        end do
        q = 0.0_wp
        q(:7) = [speed, 0.0_wp, 0.0_wp, 0.0_wp, 0.5_wp*pi, 0.0_wp, -speed/radius]
        do component = 1, 3
            call evaluate_ucon(rolling_sphere_ucosub, 1, 0.0_wp, q, &
                & rolling_sphere_par(1, radius, component), [1, 0, 0], scalar, array, xmatrx, &
                & error)
            if (allocated(error)) return
            ! sin(pi/2) and cos(0) are exact; cos(pi/2) multiplies zero rates.
            call check(error, scalar, 0.0_wp, "F" // to_text(component) // " of pure rolling", &
                & abs_tol=4.0_wp*epsilon(1.0_wp)*speed)
            if (allocated(error)) return
        end do
    end subroutine test_sphere

    !> Moving along the blade (cos psi, sin psi) satisfies the knife edge; across it,
    !> (-sin psi, cos psi), F is the speed.
    subroutine test_knife_edge(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: q(30), psi, speed, scalar, array(30), xmatrx(30, 30)
        integer :: k

        call seed_random(7007)
        q = 0.0_wp
        do k = 1, 100
            call random_number(psi)
            psi = pi*(2.0_wp*psi - 1.0_wp)
            speed = 0.1_wp*k
            q(:3) = [speed*cos(psi), speed*sin(psi), psi]
            call evaluate_ucon(knife_edge_ucosub, 1, 0.0_wp, q, knife_edge_par(1), [1, 0, 0], &
                & scalar, array, xmatrx, error)
            if (allocated(error)) return
            ! Two products of rounded numbers of size speed: a few eps of speed.
            call check(error, scalar, 0.0_wp, "F along the blade", &
                & abs_tol=4.0_wp*epsilon(1.0_wp)*speed)
            if (allocated(error)) return
            q(:3) = [-speed*sin(psi), speed*cos(psi), psi]
            call evaluate_ucon(knife_edge_ucosub, 1, 0.0_wp, q, knife_edge_par(1), [1, 0, 0], &
                & scalar, array, xmatrx, error)
            if (allocated(error)) return
            call check(error, scalar, speed, "F across the blade", &
                & abs_tol=4.0_wp*epsilon(1.0_wp)*speed)
            if (allocated(error)) return
        end do
    end subroutine test_knife_edge

    !> F = Z - R sin(theta) is zero on the ground for any tilt, and its partials are
    !> (1, -R cos(theta)) and d2F/dtheta2 = R sin(theta).
    subroutine test_disk_height(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: radius = 0.1_wp
        real(wp) :: q(30), theta, scalar, array(30), xmatrx(30, 30)
        integer :: k

        q = 0.0_wp
        do k = 0, 20
            theta = pi*k/20.0_wp
            q(:2) = [radius*sin(theta), theta]
            call evaluate_ucon(disk_height_ucosub, 1, 0.0_wp, q, disk_height_par(1, radius), &
                & [1, 1, 1], scalar, array, xmatrx, error)
            if (allocated(error)) return
            call check(error, scalar, 0.0_wp, "F on the ground", abs_tol=0.0_wp)
            if (allocated(error)) return
            call check(error, array(:2), [1.0_wp, -radius*cos(theta)], "dF/dq", &
                & rel_tol=epsilon(1.0_wp))
            if (allocated(error)) return
            call check(error, xmatrx(2, 2), radius*sin(theta), "d2F/dtheta2", &
                & rel_tol=epsilon(1.0_wp))
            if (allocated(error)) return
            call check(error, count(xmatrx /= 0.0_wp), merge(0, 1, k == 0), &
                & "non-zero entries of XMATRX")
            if (allocated(error)) return
        end do
    end subroutine test_disk_height

end module generated_physics
