! SPDX-License-Identifier: MIT
!> The reduced ODE of the disk (ucon/reduced/, rollcon_reduced_cvode) against the full
!> formulations, and the benchmark's use of it as reference and limit.
module test_reduced
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene, choice_code
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_disk_scene, only : build_disk_problem, disk_mass_properties
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_simulation, only : history_type, run_summary_type
    use rollcon_output_layout, only : time_column, coord_x, coord_z, coord_theta
    use rollcon_reduced_disk_rhs, only : reduced_size, reduced_rate, reduced_jacobian, &
        & reduced_energy, reduced_to_full, full_to_reduced
    use rollcon_reduced_scene, only : simulate_reduced_scene
    use rollcon_benchmark, only : method_type, benchmark_methods, benchmark_row_type, &
        & benchmark_scene
    use rollcon_bench_costs, only : part_costs_type, measure_part_costs
    use rollcon_bench_summary, only : accuracy_ratio
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory
    use disk_states, only : seed_random
    implicit none
    private

    public :: collect_reduced

    ! Position tolerances at rtol 1e-10: on stable motion the global error of each solution is
    ! a few hundred local errors of ~rtol*R = 1e-11 m (measured: <= 8.3e-9 m, CVODE on the coin;
    ! IDA on long_run 5.2e-9 m, 1.2e-7 m at a Newton coefficient of 0.033, docs/design.md §7);
    ! tol_stable leaves a factor 3.6, so that a tenfold loss fails. Where
    ! the motion is unstable or neutrally stable the errors grow (see each). IDA's error on
    ! long_run is decided by the last bits: 4.9e-9 to 7.2e-8 m from CVODE at 1e-13 over eight
    ! starts whose tilt moves by k 1e-15 rad (CVODE's own 6.9e-10 to 9.6e-10), so the bound
    ! holds for this code's rounding, not for every rounding (docs/design.md, "Speed").
    real(wp), parameter :: tol_stable = 3.0e-8_wp

contains

    subroutine collect_reduced(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("rate-equals-full-model", test_rate_equals_full), &
            & new_unittest("jacobian-vs-central-differences", test_jacobian), &
            & new_unittest("state-maps-round-trip", test_round_trip), &
            & new_unittest("coin", test_coin), &
            & new_unittest("tipping_coin", test_tipping_coin), &
            & new_unittest("steady_circle", test_steady_circle), &
            & new_unittest("fast_upright", test_fast_upright), &
            & new_unittest("spinning_coin", test_spinning_coin), &
            & new_unittest("near_flat", test_near_flat), &
            & new_unittest("long_run", test_long_run), &
            & new_unittest("fixed-point-iteration", test_fixed_point), &
            & new_unittest("benchmark-ratio-same-run", test_benchmark_ratio), &
            & new_unittest("accuracy-ratio-cheapest-within-target", test_accuracy_ratio)]
    end subroutine collect_reduced

    !> The coin's disk: par = (A, C, m, R, g).
    function coin_par(scene) result(par)
        type(scene_type), intent(in) :: scene
        real(wp) :: par(5), mass, inertia(3)

        call disk_mass_properties(scene, mass, inertia)
        par = [inertia(1), inertia(3), mass, scene%disk%radius, scene%environment%gravity]
    end function coin_par

    !> At seeded random states, inside the coin's strike pulse, the reduced accelerations equal
    !> the full ODE's (the saddle-point system with the UCOSUB's constraints, solved by LAPACK):
    !> two derivations, one by Kane's method in minimal coordinates, one by Lagrange multipliers.
    subroutine test_rate_equals_full(error)
        type(error_type), allocatable, intent(out) :: error
        ! both exact up to rounding; the saddle-point solve loses a few digits (condition ~1e4)
        real(wp), parameter :: tol = 1.0e-9_wp
        ! mid-pulse: the strike force is at its peak, so its generalized force is tested too
        real(wp), parameter :: time = 2.005_wp
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        real(wp) :: q0(6), u0(6), y(reduced_size), rate(reduced_size), q(6), u(6), draw(8)
        real(wp) :: full(12), spin_rate, force
        integer :: k, ierr

        call read_scene("data/coin.nml", scene, error)
        if (allocated(error)) return
        scene%run%formulation = choice_code("formulation", "cvode")
        scene%run%drift = choice_code("drift", "none")
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        call ode%init(problem)
        force = 0.5_wp*pi*scene%strike%impulse/scene%strike%duration
        call seed_random(13)
        do k = 1, 20
            call random_number(draw)
            y = [0.2_wp + (pi - 0.4_wp)*draw(1), 4.0_wp*draw(2) - 2.0_wp, &
                & 20.0_wp*draw(3) - 10.0_wp, 40.0_wp*draw(4) - 20.0_wp, 2.0_wp*pi*draw(5), &
                & 2.0_wp*pi*draw(6), draw(7) - 0.5_wp, draw(8) - 0.5_wp]
            call reduced_rate(y, coin_par(scene), force, rate)
            call reduced_to_full(y, coin_par(scene), q, u)
            ierr = ode%ode_rhs(time, [q, u], full)
            call check(error, ierr == 0, "full right-hand side failed")
            if (allocated(error)) return
            associate (a => full(7:12))
                spin_rate = a(6) + a(4)*cos(y(1)) - u(4)*u(5)*sin(y(1))
                call check(error, rate(2:4), [a(5), a(4), spin_rate], "state " // to_text(k) &
                    & // ": (thetaddot, psiddot, omega3dot)", abs_tol=tol, rel_tol=tol)
                if (allocated(error)) return
                call check(error, rate(7:8), u(1:2), "state " // to_text(k) // ": (Xdot, Ydot)", &
                    & abs_tol=tol)
                if (allocated(error)) return
            end associate
        end do
    end subroutine test_rate_equals_full

    !> The generated Jacobian against central differences of the generated rate.
    subroutine test_jacobian(error)
        type(error_type), allocatable, intent(out) :: error
        ! central difference, h = 1e-6: truncation O(h^2) ~ 1e-12 times third derivatives of
        ! size ~1e3 at these rates, rounding eps/h ~ 1e-10 times rates ~1e2
        real(wp), parameter :: h = 1.0e-6_wp, tol = 1.0e-6_wp
        type(scene_type) :: scene
        real(wp) :: y(reduced_size), jacobian(reduced_size, reduced_size), plus(reduced_size)
        real(wp) :: minus(reduced_size), step(reduced_size), draw(8)
        integer :: k, j

        call read_scene("data/coin.nml", scene, error)
        if (allocated(error)) return
        call seed_random(17)
        do k = 1, 10
            call random_number(draw)
            y = [0.2_wp + (pi - 0.4_wp)*draw(1), 4.0_wp*draw(2) - 2.0_wp, &
                & 20.0_wp*draw(3) - 10.0_wp, 40.0_wp*draw(4) - 20.0_wp, 2.0_wp*pi*draw(5), &
                & 2.0_wp*pi*draw(6), draw(7) - 0.5_wp, draw(8) - 0.5_wp]
            call reduced_jacobian(y, coin_par(scene), 0.3_wp, jacobian)
            do j = 1, reduced_size
                step = 0.0_wp
                step(j) = h
                call reduced_rate(y + step, coin_par(scene), 0.3_wp, plus)
                call reduced_rate(y - step, coin_par(scene), 0.3_wp, minus)
                call check(error, jacobian(:, j), (plus - minus)/(2.0_wp*h), "state " &
                    & // to_text(k) // ", column " // to_text(j), abs_tol=tol, rel_tol=tol)
                if (allocated(error)) return
            end do
        end do
    end subroutine test_jacobian

    !> full_to_reduced(reduced_to_full(y)) = y, and the energy equals the full model's.
    subroutine test_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tol = 1.0e-13_wp  ! a few roundings of O(1) numbers
        type(scene_type) :: scene
        type(problem_type), target :: problem
        real(wp) :: q0(6), u0(6), y(reduced_size), back(reduced_size), q(6), u(6)

        call read_scene("data/spinning_coin.nml", scene, error)
        if (allocated(error)) return
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        call full_to_reduced(q0, u0, y)
        call reduced_to_full(y, coin_par(scene), q, u)
        call check(error, [q, u], [q0, u0], "full state of the reduced state", abs_tol=tol, &
            & rel_tol=tol)
        if (allocated(error)) return
        call full_to_reduced(q, u, back)
        call check(error, back, y, "reduced state", abs_tol=tol, rel_tol=tol)
        if (allocated(error)) return
        call check(error, reduced_energy(y, coin_par(scene)), problem%eq%energy(q0, u0), &
            & "energy", rel_tol=tol)
    end subroutine test_round_trip

    subroutine test_coin(error)
        type(error_type), allocatable, intent(out) :: error
        ! straight rolling, the strike at 2 s, the start of the fall; afterwards the fall
        ! through fast precession turns phase errors into large position differences.
        ! Measured up to 3 s: IDA 3.1e-9 m, CVODE 8.3e-9 m, each started again at the
        ! strike's ends (IDA 1.75e-7 m at its default Newton coefficient, going on across the
        ! strike's corners on its history: docs/design.md §7)
        call compare_scene(error, "coin", 10.0_wp, 3.0_wp, tol_stable)
    end subroutine test_coin

    subroutine test_tipping_coin(error)
        type(error_type), allocatable, intent(out) :: error
        ! upright rolling at 0.1 m/s is unstable: differences grow like exp(t) with a rate of a
        ! few per second from the start (measured 2e-7 m at 1.5 s, 9e-6 m by CVODE at 2 s)
        call compare_scene(error, "tipping_coin", 10.0_wp, 1.5_wp, 1.0e-6_wp)
    end subroutine test_tipping_coin

    subroutine test_steady_circle(error)
        type(error_type), allocatable, intent(out) :: error
        ! neutrally stable: an error in the precession rate shifts the phase linearly in time
        ! (measured 8.4e-8 m at 5 s by CVODE, 2.2e-8 m by IDA)
        call compare_scene(error, "steady_circle", 5.0_wp, 5.0_wp, 10.0_wp*tol_stable)
    end subroutine test_steady_circle

    subroutine test_fast_upright(error)
        type(error_type), allocatable, intent(out) :: error
        call compare_scene(error, "fast_upright", 10.0_wp, 10.0_wp, tol_stable)
    end subroutine test_fast_upright

    subroutine test_spinning_coin(error)
        type(error_type), allocatable, intent(out) :: error
        call compare_scene(error, "spinning_coin", 3.0_wp, 3.0_wp, tol_stable)
    end subroutine test_spinning_coin

    subroutine test_near_flat(error)
        type(error_type), allocatable, intent(out) :: error
        call compare_scene(error, "near_flat", 2.0_wp, 2.0_wp, tol_stable)
    end subroutine test_near_flat

    subroutine test_long_run(error)
        type(error_type), allocatable, intent(out) :: error
        ! the first 20 of 200 s: the test suite's time is limited
        call compare_scene(error, "long_run", 20.0_wp, 20.0_wp, tol_stable)
    end subroutine test_long_run

    !> CVODE Adams with fixed-point iteration (jacobian = 'none'), the full model with Baumgarte's
    !> stabilisation and the reduced ODE alike, on fast_upright at rtol 1e-10: no Newton matrix
    !> is ever formed, and the two centres agree within tol_stable (measured by the benchmark:
    !> 6e-11 m and 1e-9 m from the reference) over the scene's 10 s.
    subroutine test_fixed_point(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: full, reduced
        type(run_summary_type) :: summary, reduced_summary
        real(wp) :: distance, a(12), b(12)
        integer :: i, n

        call read_scene("data/fast_upright.nml", scene, error)
        if (allocated(error)) return
        scene%run%formulation = choice_code("formulation", "cvode")
        scene%run%method = choice_code("method", "adams")
        scene%run%drift = choice_code("drift", "baumgarte")
        scene%run%jacobian = choice_code("jacobian", "none")
        scene%run%rtol = 1.0e-10_wp
        scene%run%atol = 1.0e-12_wp
        call simulate_reduced_scene(scene, reduced, reduced_summary, error)
        if (allocated(error)) return
        call run_in_memory(scene, full, summary, error)
        if (allocated(error)) return
        call check(error, summary%steps > 0 .and. summary%jacobians == 0 .and. &
            & reduced_summary%jacobians == 0, "Newton matrices formed: " &
            & // to_text(summary%jacobians) // " and " // to_text(reduced_summary%jacobians))
        if (allocated(error)) return
        n = min(full%count, reduced%count)
        call check(error, n == full%count .and. n > 10, "rows: " // to_text(full%count) &
            & // " and " // to_text(reduced%count))
        if (allocated(error)) return
        distance = 0.0_wp
        do i = 1, n
            a = full%part_state(1, i)
            b = reduced%part_state(1, i)
            distance = max(distance, norm2(a(coord_x:coord_z) - b(coord_x:coord_z)))
        end do
        call check(error, distance <= tol_stable, "fixed-point iteration: centres differ by " &
            & // to_text(distance) // " m")
    end subroutine test_fixed_point

    !> The scene (cut at end_time) by IDA, by CVODE (BDF, projection) and by the reduced ODE,
    !> all at rtol 1e-10: the centres agree within tol_position up to horizon; over the whole
    !> run each full solution keeps the reduced one's energy and Z = R sin(theta).
    subroutine compare_scene(error, name, end_time, horizon, tol_position)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: end_time, horizon, tol_position
        real(wp), parameter :: rtol = 1.0e-10_wp
        ! energy: each solution's drift is ~rtol per unit time over ~1e4 steps, relative
        real(wp), parameter :: tol_energy = 1.0e-7_wp
        ! Z - R sin(theta) of the full runs: F3 is integrated as a velocity constraint, held to
        ! the local tolerance atol = 1e-12 m per step; 1e-9 m bounds its drift over a run
        real(wp), parameter :: tol_height = 1.0e-9_wp
        character(len=5), parameter :: formulations(2) = ["ida  ", "cvode"]
        type(scene_type) :: scene
        type(history_type) :: full, reduced
        type(run_summary_type) :: summary
        real(wp) :: distance, energy_error, height_error, worst, a(12), b(12)
        integer :: f, i, n

        call read_scene("data/" // name // ".nml", scene, error)
        if (allocated(error)) return
        scene%run%end_time = min(scene%run%end_time, end_time)
        scene%run%rtol = rtol
        scene%run%atol = 1.0e-2_wp*rtol
        call simulate_reduced_scene(scene, reduced, summary, error)
        if (allocated(error)) return
        do f = 1, size(formulations)
            scene%run%formulation = choice_code("formulation", trim(formulations(f)))
            call run_in_memory(scene, full, summary, error)
            if (allocated(error)) return
            n = min(full%count, reduced%count)
            call check(error, n > 10, name // ": " // trim(formulations(f)) // " kept only " &
                & // to_text(n) // " rows")
            if (allocated(error)) return
            distance = 0.0_wp
            worst = 0.0_wp
            energy_error = 0.0_wp
            height_error = 0.0_wp
            do i = 1, n
                call check(error, full%rows(time_column, i), reduced%rows(time_column, i), &
                    & name // ": output times", abs_tol=1.0e-12_wp)
                if (allocated(error)) return
                a = full%part_state(1, i)
                b = reduced%part_state(1, i)
                if (full%rows(time_column, i) <= horizon &
                    & .and. norm2(a(coord_x:coord_z) - b(coord_x:coord_z)) > distance) then
                    distance = norm2(a(coord_x:coord_z) - b(coord_x:coord_z))
                    worst = full%rows(time_column, i)
                end if
                energy_error = max(energy_error, abs(full%rows(full%layout%energy_column(), i) &
                    & - reduced%rows(reduced%layout%energy_column(), i)) &
                    & /abs(reduced%rows(reduced%layout%energy_column(), 1)))
                height_error = max(height_error, abs(a(coord_z) &
                    & - scene%disk%radius*sin(a(coord_theta))))
            end do
            call check(error, distance <= tol_position, name // ": " // trim(formulations(f)) &
                & // " centre differs from the reduced ODE's by " // to_text(distance) &
                & // " m at t = " // to_text(worst) // " s (<= " // to_text(horizon) // " s)")
            if (allocated(error)) return
            call check(error, energy_error <= tol_energy, name // ": " &
                & // trim(formulations(f)) // " energy differs by " // to_text(energy_error))
            if (allocated(error)) return
            call check(error, height_error <= tol_height, name // ": " &
                & // trim(formulations(f)) // " |Z - R sin(theta)| up to " &
                & // to_text(height_error) // " m")
            if (allocated(error)) return
        end do
    end subroutine compare_scene

    !> Every row's ratio is its CPU time over the reduced ODE's, both measured in the same
    !> call: the reduced-bdf row at the same rtol carries exactly that reduced CPU time; the
    !> per-part split adds up to the row's CPU time, its event functions at their cost as the
    !> row's integrator calls them (IDA: given the multipliers; CVODE: given the
    !> accelerations).
    subroutine test_benchmark_ratio(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tol = 1.0e-12_wp  ! one division and three subtractions
        type(job_type) :: job
        type(benchmark_row_type), allocatable :: rows(:)
        type(method_type) :: all_methods(size(benchmark_methods()))
        type(part_costs_type) :: costs
        integer :: i, j

        call load_job("tipping_coin", job, error)
        if (allocated(error)) return
        job%source%settings%end_time = 0.5_wp
        call measure_part_costs(job, 100, "build/test_reduced_costs.csv", costs, error)
        if (allocated(error)) return
        all_methods = benchmark_methods()
        call benchmark_scene(job, [all_methods(1), all_methods(3), &
            & all_methods(7), all_methods(9)], [1.0e-5_wp, 1.0e-7_wp], 1.0e-10_wp, 1, rows, &
            & error, costs=costs)
        if (allocated(error)) return
        call check(error, size(rows), 8, "rows")
        if (allocated(error)) return
        do i = 1, size(rows)
            associate (row => rows(i))
                call check(error, ieee_is_finite(row%cpu) .and. row%cpu > 0.0_wp .and. &
                    & ieee_is_finite(row%reduced_cpu) .and. row%reduced_cpu > 0.0_wp, &
                    & trim(row%method) // ": CPU times " // to_text(row%cpu) // ", " &
                    & // to_text(row%reduced_cpu))
                if (allocated(error)) return
                call check(error, row%ratio, row%cpu/row%reduced_cpu, trim(row%method) &
                    & // ": ratio", rel_tol=tol)
                if (allocated(error)) return
                if (trim(row%method) == "reduced-bdf") cycle
                call check(error, row%rhs_cpu + row%roots_cpu + row%output_cpu &
                    & + row%sundials_cpu, row%cpu, trim(row%method) // ": parts", &
                    & rel_tol=tol, abs_tol=tol)
                if (allocated(error)) return
                call check(error, row%rhs_cpu > 0.0_wp .and. row%output_cpu > 0.0_wp .and. &
                    & row%output_rows > 0, trim(row%method) // ": no part costs")
                if (allocated(error)) return
                call check(error, row%roots_cpu, row%root_evaluations*merge( &
                    & costs%root_given_multipliers, costs%root_given_rates, &
                    & row%method(:3) == "ida"), trim(row%method) // ": event functions' CPU", &
                    & rel_tol=tol)
                if (allocated(error)) return
                if (trim(row%method) == "cvode-adams-baumgarte") cycle
                do j = 1, size(rows)
                    if (trim(rows(j)%method) /= "reduced-bdf" .or. rows(j)%rtol /= row%rtol) cycle
                    call check(error, row%reduced_cpu == rows(j)%cpu, trim(row%method) &
                        & // ": reduced CPU " // to_text(row%reduced_cpu) // " is not the " &
                        & // "reduced-bdf row's " // to_text(rows(j)%cpu))
                    if (allocated(error)) return
                end do
            end associate
        end do
    end subroutine test_benchmark_ratio

    !> The headline ratio takes the cheapest completed run within the target for each side,
    !> the reduced side from either multistep method.
    subroutine test_accuracy_ratio(error)
        type(error_type), allocatable, intent(out) :: error
        type(benchmark_row_type) :: rows(6)
        real(wp) :: cpu, reduced_cpu
        logical :: found

        rows%scene = "s"
        rows(1:3)%method = "ida"
        rows(4:5)%method = "reduced-bdf"
        rows(6)%method = "reduced-adams"
        rows%cpu = [1.0_wp, 2.0_wp, 4.0_wp, 0.5_wp, 1.5_wp, 1.2_wp]
        rows%position_error = [1.0e-4_wp, 1.0e-7_wp, 1.0e-9_wp, 1.0e-5_wp, 1.0e-8_wp, 1.0e-9_wp]
        rows(1)%status = "completed"
        rows(2)%status = "completed"
        rows(3)%status = "completed"
        rows(4)%status = "completed"
        rows(5)%status = "completed"
        rows(6)%status = "completed"
        call accuracy_ratio(rows, "s", "ida", 1.0e-6_wp, cpu, reduced_cpu, found)
        call check(error, found .and. cpu == 2.0_wp .and. reduced_cpu == 1.2_wp, &
            & "picked " // to_text(cpu) // " s and " // to_text(reduced_cpu) // " s")
        if (allocated(error)) return
        rows(2)%status = "failed: x"
        call accuracy_ratio(rows, "s", "ida", 1.0e-6_wp, cpu, reduced_cpu, found)
        call check(error, found .and. cpu == 4.0_wp, "a failed run was picked")
        if (allocated(error)) return
        call accuracy_ratio(rows, "s", "ida", 1.0e-10_wp, cpu, reduced_cpu, found)
        call check(error, .not. found, "found a run within 1e-10 m")
    end subroutine test_accuracy_ratio

end module test_reduced
