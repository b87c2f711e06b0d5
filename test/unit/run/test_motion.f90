! SPDX-License-Identifier: MIT
!> Physics of simulated motions: conserved energy, held constraints, analytic steady motions,
!> the stability threshold and wobble frequency of upright rolling, the strike's momentum,
!> agreement of the ODE (CVODE) and DAE (IDA) formulations. Events: test_events; drift: test_drift.
module test_motion
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene, choice_code, formulation_cvode, &
        & height_position
    use rollcon_problem, only : problem_type
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : run_options_type, simulate
    use rollcon_model, only : model_type, setup_model
    use rollcon_body, only : part_type
    use rollcon_disk_par, only : disk_par
    use rollcon_disk_scene, only : disk_initial_state
    use rollcon_disk_scene, only : disk_mass_properties
    use rollcon_simulation, only : history_type, run_summary_type
    use rollcon_output_layout, only : time_column, coord_x, coord_y, coord_psi, coord_theta, &
        & coord_phi, coord_xdot, coord_zdot, coord_thetadot
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory, default_scene, tipping_coin
    use motion_run_variants, only : test_solver_failure, test_generated_trajectory
    implicit none
    private

    public :: collect_motion

contains

    subroutine collect_motion(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("energy-tipping-coin-ida", test_energy_ida), &
            & new_unittest("energy-tipping-coin-cvode", test_energy_cvode), &
            & new_unittest("energy-drift-shrinks-with-tolerance", test_energy_tolerance), &
            & new_unittest("steady-circle", test_steady_circle), &
            & new_unittest("upright-0.8-stays-upright", test_upright_stable), &
            & new_unittest("upright-0.5-tips", test_upright_tips), &
            & new_unittest("wobble-frequency-2-m-s", test_wobble), &
            & new_unittest("cvode-agrees-with-ida", test_formulations_agree), &
            & new_unittest("strike-momentum", test_strike_momentum), &
            & new_unittest("solver-failure-keeps-valid-csv", test_solver_failure), &
            & new_unittest("generated-ucosub-same-trajectory", test_generated_trajectory), &
            & new_unittest("two-parts-six-ucons", test_two_parts)]
    end subroutine collect_motion

    !> Energy without forcing drifts by at most 1000 rtol over the tipping coin's 10 s (it
    !> falls to theta ~ 0.12 rad and rises again: the hardest stretch for the integrators;
    !> measured drifts are 30-150 rtol), and the constraints hold at the tolerance's level:
    !> 100 rtol [m/s] for velocities of order 1 m/s.
    subroutine check_energy(error, formulation)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: formulation
        real(wp), parameter :: rtol = 1.0e-8_wp
        type(history_type) :: history
        type(run_summary_type) :: summary

        call run_in_memory(tipping_coin(formulation, rtol), history, summary, error)
        if (allocated(error)) return
        call check(error, summary%t_reached, 10.0_wp, "end time", abs_tol=1.0e-12_wp)
        if (allocated(error)) return
        call check(error, minval(history%part_values(1, coord_theta)) < 0.5_wp, &
            & "the coin did not tip (min theta " &
            & // to_text(minval(history%part_values(1, coord_theta))) // ")")
        if (allocated(error)) return
        call check(error, summary%energy_drift, 0.0_wp, formulation // " energy drift", &
            & abs_tol=1.0e3_wp*rtol)
        if (allocated(error)) return
        call check(error, summary%residual_max, 0.0_wp, formulation // " constraint residual", &
            & abs_tol=1.0e2_wp*rtol)
    end subroutine check_energy

    subroutine test_energy_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_energy(error, "ida")
    end subroutine test_energy_ida

    subroutine test_energy_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_energy(error, "cvode")
    end subroutine test_energy_cvode

    !> A hundredfold tighter tolerance gives at least a tenfold smaller drift, both ways.
    subroutine test_energy_tolerance(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=5), parameter :: formulations(2) = ["ida  ", "cvode"]
        type(history_type) :: history
        type(run_summary_type) :: loose, tight
        integer :: i

        do i = 1, 2
            call run_in_memory(tipping_coin(trim(formulations(i)), 1.0e-6_wp), history, loose, &
                & error)
            if (allocated(error)) return
            call run_in_memory(tipping_coin(trim(formulations(i)), 1.0e-8_wp), history, tight, &
                & error)
            if (allocated(error)) return
            call check(error, tight%energy_drift < 0.1_wp*loose%energy_drift, &
                & trim(formulations(i)) // ": drift " // to_text(tight%energy_drift) &
                & // " at rtol 1e-8 against " // to_text(loose%energy_drift) // " at 1e-6")
            if (allocated(error)) return
        end do
    end subroutine test_energy_tolerance

    !> Steady motion at theta = 60 deg, phidot = -20 rad/s, psidot the slow root of
    !> A W^2 s c - (C + m R^2) W (phidot + W c) s = m g R c (docs/design.md §5).
    subroutine test_steady_circle(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        real(wp) :: mass, inertia(3), s, c, qa, qb, qc, root1, root2, omega, radius_path
        real(wp) :: cx(3), cy(3), centre(2), d, distance
        real(wp), allocatable :: px(:), py(:)
        integer :: i, k(3)

        scene = default_scene()
        call disk_mass_properties(scene, mass, inertia)
        scene%initial%theta = pi/3.0_wp
        scene%initial%phidot = -20.0_wp
        s = sin(scene%initial%theta)
        c = cos(scene%initial%theta)
        associate (a => inertia(1), cc => inertia(3), r => scene%disk%radius, &
                & g => scene%environment%gravity)
            qa = s*c*(a - cc - mass*r**2)
            qb = -(cc + mass*r**2)*scene%initial%phidot*s
            qc = -mass*g*r*c
        end associate
        root1 = (-qb + sqrt(qb**2 - 4.0_wp*qa*qc))/(2.0_wp*qa)
        root2 = (-qb - sqrt(qb**2 - 4.0_wp*qa*qc))/(2.0_wp*qa)
        omega = merge(root1, root2, abs(root1) < abs(root2))
        scene%initial%psidot = omega
        scene%run%end_time = 5.0_wp
        scene%run%output_step = 0.01_wp
        scene%run%rtol = 1.0e-11_wp
        scene%run%atol = 1.0e-13_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        ! theta within 1e-8 rad: an exact steady solution, so only the integration error moves
        ! it; at rtol 1e-11 that is ~1e-10 rad over 5 s.
        call check(error, maxval(abs(history%part_values(1, coord_theta) - pi/3.0_wp)), 0.0_wp, &
            & "largest |theta - 60 deg| [rad]", abs_tol=1.0e-8_wp)
        if (allocated(error)) return
        ! Contact point G - R e_y2, on the ground.
        px = history%part_values(1, coord_x) + scene%disk%radius &
            & *cos(history%part_values(1, coord_theta))*sin(history%part_values(1, coord_psi))
        py = history%part_values(1, coord_y) - scene%disk%radius &
            & *cos(history%part_values(1, coord_theta))*cos(history%part_values(1, coord_psi))
        k = [1, history%count/3, (2*history%count)/3]
        cx = px(k)
        cy = py(k)
        ! circumcentre of three contact points
        d = 2.0_wp*(cx(1)*(cy(2) - cy(3)) + cx(2)*(cy(3) - cy(1)) + cx(3)*(cy(1) - cy(2)))
        centre(1) = ((cx(1)**2 + cy(1)**2)*(cy(2) - cy(3)) + (cx(2)**2 + cy(2)**2)*(cy(3) - cy(1)) &
            & + (cx(3)**2 + cy(3)**2)*(cy(1) - cy(2)))/d
        centre(2) = ((cx(1)**2 + cy(1)**2)*(cx(3) - cx(2)) + (cx(2)**2 + cy(2)**2)*(cx(1) - cx(3)) &
            & + (cx(3)**2 + cy(3)**2)*(cx(2) - cx(1)))/d
        radius_path = scene%disk%radius*abs(scene%initial%phidot/omega)
        do i = 1, history%count
            distance = hypot(px(i) - centre(1), py(i) - centre(2))
            ! 1e-8 relative: the path radius is ~0.1 m; positions are integrated to ~1e-11.
            call check(error, distance, radius_path, "contact point's distance from the " &
                & // "circle's centre at t = " // to_text(history%rows(time_column, i)), &
                & rel_tol=1.0e-8_wp)
            if (allocated(error)) return
        end do
    end subroutine test_steady_circle

    !> Upright less 0.01 rad, rolling straight in +X at speed v (phidot = -v/R).
    function upright(speed, end_time) result(scene)
        real(wp), intent(in) :: speed, end_time
        type(scene_type) :: scene

        scene = default_scene()
        scene%initial%theta = 0.5_wp*pi - 0.01_wp
        scene%initial%phidot = -speed/scene%disk%radius
        scene%run%end_time = end_time
        scene%run%output_step = 0.01_wp
    end function upright

    !> Above the critical speed (0.572 m/s for this disk, docs/design.md §5) a small tilt stays
    !> small: |theta - pi/2| below 5 times the initial 0.01 rad over 10 s.
    subroutine test_upright_stable(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(run_summary_type) :: summary

        call run_in_memory(upright(0.8_wp, 10.0_wp), history, summary, error)
        if (allocated(error)) return
        call check(error, maxval(abs(history%part_values(1, coord_theta) - 0.5_wp*pi)), 0.0_wp, &
            & "largest tilt at 0.8 m/s [rad]", abs_tol=0.05_wp)
    end subroutine test_upright_stable

    !> Below it the tilt grows: the disk leans past 0.3 rad within 10 s.
    subroutine test_upright_tips(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: history
        type(run_summary_type) :: summary

        call run_in_memory(upright(0.5_wp, 10.0_wp), history, summary, error)
        if (allocated(error)) return
        call check(error, maxval(abs(history%part_values(1, coord_theta) - 0.5_wp*pi)) > 0.3_wp, &
            & "at 0.5 m/s the largest tilt is only " &
            & // to_text(maxval(abs(history%part_values(1, coord_theta) - 0.5_wp*pi))) // " rad")
    end subroutine test_upright_tips

    !> Small wobble of upright rolling at 2 m/s: (A + m R^2) e'' + (C (C + m R^2) W^2 / A - m g R) e
    !> = const, W = v/R, so its angular frequency is sqrt((C (C + mR^2) W^2/A - mgR)/(A + mR^2)).
    !> Measured from the times thetadot crosses zero downwards (maxima of theta), over 10 s,
    !> with a 1e-4 rad tilt so that the amplitude's own frequency shift (~1e-8) does not count.
    subroutine test_wobble(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        real(wp) :: mass, inertia(3), spin, linear, measured, t_first, t_last
        real(wp), allocatable :: t(:), rate(:)
        integer :: i, crossings

        scene = upright(2.0_wp, 10.0_wp)
        scene%initial%theta = 0.5_wp*pi - 1.0e-4_wp
        scene%run%output_step = 1.0e-3_wp
        scene%run%rtol = 1.0e-10_wp
        scene%run%atol = 1.0e-12_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call disk_mass_properties(scene, mass, inertia)
        spin = 2.0_wp/scene%disk%radius
        associate (a => inertia(1), c => inertia(3), r => scene%disk%radius)
            linear = sqrt((c*(c + mass*r**2)*spin**2/a - mass*scene%environment%gravity*r) &
                & /(a + mass*r**2))
        end associate
        t = history%column(time_column)
        rate = history%part_values(1, coord_thetadot)
        crossings = 0
        do i = 2, size(t)
            if (rate(i - 1) > 0.0_wp .and. rate(i) <= 0.0_wp) then
                ! linear interpolation of the crossing: error ~ (dt w)^2 ~ 1e-4 of dt
                t_last = t(i - 1) + (t(i) - t(i - 1))*rate(i - 1)/(rate(i - 1) - rate(i))
                if (crossings == 0) t_first = t_last
                crossings = crossings + 1
            end if
        end do
        call check(error, crossings >= 3, "fewer than three wobbles in 10 s")
        if (allocated(error)) return
        measured = 2.0_wp*pi*real(crossings - 1, wp)/(t_last - t_first)
        call check(error, measured, linear, "wobble angular frequency [rad/s]", rel_tol=5.0e-3_wp)
    end subroutine test_wobble

    !> Over the first second of the tipping coin (before it falls towards flat, where the motion
    !> amplifies any difference some 1e5-fold), the two formulations' coordinates agree to
    !> 1e3 rtol, for two tolerances: the difference follows the tolerance.
    subroutine test_formulations_agree(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: ida, cvode
        type(run_summary_type) :: summary
        type(scene_type) :: scene
        real(wp) :: rtol, difference, a(12), b(12)
        integer :: i, k

        do i = 1, 2
            rtol = 10.0_wp**(-6 - 2*i)
            scene = tipping_coin("ida", rtol)
            scene%run%end_time = 1.0_wp
            call run_in_memory(scene, ida, summary, error)
            if (allocated(error)) return
            scene%run%formulation = formulation_cvode
            call run_in_memory(scene, cvode, summary, error)
            if (allocated(error)) return
            difference = 0.0_wp
            do k = 1, min(ida%count, cvode%count)
                a = ida%part_state(1, k)
                b = cvode%part_state(1, k)
                difference = max(difference, maxval(abs(a(:6) - b(:6))))
            end do
            call check(error, difference, 0.0_wp, "largest coordinate difference at rtol " &
                & // to_text(rtol), abs_tol=1.0e3_wp*rtol)
            if (allocated(error)) return
        end do
    end subroutine test_formulations_agree

    !> During the strike, m dv = strike impulse + contact impulse + gravity impulse, with the
    !> contact force from the multipliers integrated by the trapezoidal rule over 100 output
    !> intervals (quadrature error ~ (pi h/T)^2/12 ~ 1e-4 of the impulses).
    subroutine test_strike_momentum(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        real(wp) :: mass, inertia(3), contact(3), change(3), expected(3), dt
        integer :: i, first, last, fx, fz, xdot, zdot

        scene = default_scene()
        scene%initial%phidot = -1.0_wp
        scene%strike%enabled = .true.
        scene%strike%time = 0.01_wp
        scene%strike%duration = 0.01_wp
        scene%strike%impulse = 0.01_wp
        scene%run%end_time = 0.03_wp
        scene%run%output_step = 1.0e-4_wp
        scene%run%rtol = 1.0e-10_wp
        scene%run%atol = 1.0e-12_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call disk_mass_properties(scene, mass, inertia)
        fx = history%layout%column("Fx")
        fz = history%layout%column("Fz")
        xdot = history%layout%part_column(1, coord_xdot)
        zdot = history%layout%part_column(1, coord_zdot)
        first = minloc(abs(history%column(time_column) - scene%strike%time), dim=1)
        last = minloc(abs(history%column(time_column) - scene%strike%time &
            & - scene%strike%duration), dim=1)
        contact = 0.0_wp
        do i = first, last - 1
            dt = history%rows(time_column, i + 1) - history%rows(time_column, i)
            contact = contact + 0.5_wp*dt*(history%rows(fx:fz, i) + history%rows(fx:fz, i + 1))
        end do
        change = mass*(history%rows(xdot:zdot, last) - history%rows(xdot:zdot, first))
        expected = contact + [0.0_wp, scene%strike%impulse, &
            & -mass*scene%environment%gravity*scene%strike%duration]
        call check(error, change, expected, "momentum change over the pulse [N s]", &
            & abs_tol=1.0e-3_wp*scene%strike%impulse)
        if (allocated(error)) return
        call check(error, abs(change(2)) > 0.1_wp*scene%strike%impulse, &
            & "the strike barely changed the Y momentum")
    end subroutine test_strike_momentum

    !> Two disks in one model, parts 7 and 3, six UCONs in one UCOSUB, declared in an order that
    !> interleaves them: the driver maps each variable to its part, and each disk moves as it
    !> does alone. Final states agree with the single-disk runs to 1e3 rtol (the integrators
    !> take different steps on the larger system).
    subroutine test_two_parts(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: first, second
        type(history_type) :: history
        type(run_summary_type) :: alone(2), together
        type(model_type), target :: model
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(part_type) :: part
        real(wp) :: q(12), u(12)
        integer :: k

        first = tipping_coin("ida", 1.0e-10_wp)
        first%run%end_time = 1.0_wp
        second = upright(0.8_wp, 1.0_wp)
        second%run%rtol = 1.0e-10_wp
        second%run%atol = 1.0e-12_wp
        second%initial%psi = 0.7_wp
        call run_in_memory(first, history, alone(1), error)
        if (allocated(error)) return
        call run_in_memory(second, history, alone(2), error)
        if (allocated(error)) return

        part%id = 7
        call disk_mass_properties(first, part%mass, part%inertia)
        call model%add_part(part)
        part%id = 3
        call model%add_part(part)
        model%gravity = [0.0_wp, 0.0_wp, -first%environment%gravity]
        model%ucosub => rolling_disk_ucosub
        do k = 1, 3
            call model%add_ucon(10 + k, disk_par(3, second%disk%radius, k))
            call model%add_ucon(20 + k, disk_par(7, first%disk%radius, k))
        end do
        call setup_model(model, error)
        if (allocated(error)) return
        call problem%init(model)
        problem%settings%rtol = 1.0e-10_wp
        problem%settings%atol = 1.0e-12_wp
        call disk_initial_state(first, q(1:6), u(1:6))
        call disk_initial_state(second, q(7:12), u(7:12))
        options%end_time = 1.0_wp
        options%output_step = 0.05_wp
        options%progress = .false.
        call simulate(problem, q, u, options, together, error)
        if (allocated(error)) return
        call check(error, together%q(1:6), alone(1)%q, "part 7 (first) coordinates", &
            & abs_tol=1.0e3_wp*first%run%rtol)
        if (allocated(error)) return
        call check(error, together%q(7:12), alone(2)%q, "part 3 (second) coordinates", &
            & abs_tol=1.0e3_wp*second%run%rtol)
    end subroutine test_two_parts

end module test_motion
