! SPDX-License-Identifier: MIT
!> Tests of the rigid-body equations and the Newton matrices built from the UCOSUB's partials,
!> and of the integrator each formulation gets; and of a UCOSUB's second partials placed over
!> its own coordinates whatever the order of its variables.
module test_dynamics
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_body, only : part_type, body_residual, body_residual_jacobian, body_mass_matrix, &
        & kinetic_energy, body_mass_and_force
    use rollcon_lapack, only : factor_dense, solve_factored
    use rollcon_problem, only : problem_type
    use rollcon_run_settings, only : drift_none, drift_baumgarte, formulation_cvode, &
        & formulation_ida, formulation_speeds
    use rollcon_dynamic_system, only : dynamic_system_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_speeds_form, only : speeds_form_type
    use rollcon_formulation_choice, only : new_formulation
    use rollcon_integrator, only : integrator_type
    use rollcon_integrator_choice, only : start_integrator
    use rollcon_cvode, only : cvode_integrator_type
    use rollcon_ida, only : ida_integrator_type
    use rollcon_dae, only : dae_size, dae_residual, dae_jacobian
    use rollcon_scene, only : scene_type
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_disk_par, only : disk_par
    use rollcon_model, only : model_type, setup_model
    use rollcon_saddle_point, only : saddle_point_type
    use rollcon_ucosub_contract, only : ucovar, iflag_init, xmatrx_dqdq
    use rollcon_constraints, only : constraint_state_type, need_value, need_second
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_dynamics

    !> Central differences with h = 1e-6 on O(1) functions: truncation ~h^2 = 1e-12 and
    !> round-off ~eps/h = 2e-10 relative to the function's scale; 1e-6 leaves a margin for
    !> the larger rates used, while a wrong term (O(1) of the scale) is far above it.
    real(wp), parameter :: tol_fd = 1.0e-6_wp
    real(wp), parameter :: h_fd = 1.0e-6_wp
    !> Two factorisations of the same well-conditioned system (condition ~1e3): they agree to
    !> round-off times the condition number
    real(wp), parameter :: tol_solve = 1.0e-11_wp

contains

    subroutine collect_dynamics(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("body-jacobian-vs-fd", test_body_jacobian), &
            & new_unittest("mass-matrix-from-energy", test_mass_matrix), &
            & new_unittest("ode-jacobian-vs-fd", test_ode_jacobian), &
            & new_unittest("ode-jacobian-baumgarte-vs-fd", test_ode_jacobian_baumgarte), &
            & new_unittest("dae-jacobian-vs-fd", test_dae_jacobian), &
            & new_unittest("mass-and-force-vs-residual", test_mass_and_force), &
            & new_unittest("saddle-point-vs-dense-lu", test_saddle_point), &
            & new_unittest("saddle-point-blocks-as-dense", test_saddle_blocks), &
            & new_unittest("equations-use-problem-model", test_problem_model), &
            & new_unittest("formulation-chooses-the-integrator", test_integrator_choice), &
            & new_unittest("second-partials-in-declared-order", test_hessian_places)]
    end subroutine collect_dynamics

    !> Two position UCONs whose variables are not in ascending order of their coordinates
    !> (three: theta, X, Z; four: phi, Z, X, psi): d2F/dq dq held over each UCON's own
    !> coordinates (ascending: X, Z, theta and X, Z, psi, phi) has XMATRX(i, j) at the places of
    !> variables i and j, every entry. The routine returns 10 i + j, so that any entry put in
    !> another's place, or transposed, or left out, shows; a placement is a copy: equal exactly.
    subroutine test_hessian_places(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(constraint_state_type) :: state
        real(wp) :: q(6), u(6)
        ! each variable's place among its UCON's own coordinates
        integer, parameter :: places_three(3) = [3, 1, 2], places_four(4) = [4, 2, 1, 3]
        integer :: i, j

        call model%add_part(part_type(id=7, mass=1.0_wp, inertia=[1.0_wp, 1.0_wp, 2.0_wp]))
        call model%add_ucon(1, [7.0_wp, 3.0_wp], shuffled_ucosub)
        call model%add_ucon(2, [7.0_wp, 4.0_wp], shuffled_ucosub)
        call setup_model(model, error)
        if (allocated(error)) return
        call state%allocate(model)
        q = [0.1_wp, 0.2_wp, 0.3_wp, 0.4_wp, 1.1_wp, 0.6_wp]
        u = 0.0_wp
        call state%evaluate(model, 0.0_wp, q, u, need_value + need_second, error)
        if (allocated(error)) return
        call check(error, all(state%local(:3, 1) == [1, 3, 5]) .and. all(state%local(:4, 2) &
            & == [1, 3, 4, 6]), "the UCONs' own coordinates")
        if (allocated(error)) return
        do j = 1, 3
            do i = 1, 3
                call check(error, state%hqq(places_three(i), places_three(j), 1) &
                    & == 10.0_wp*i + j, "three variables: XMATRX(" // to_text(i) // ", " &
                    & // to_text(j) // ") not in its place")
                if (allocated(error)) return
            end do
        end do
        do j = 1, 4
            do i = 1, 4
                call check(error, state%hqq(places_four(i), places_four(j), 2) &
                    & == 10.0_wp*i + j, "four variables: XMATRX(" // to_text(i) // ", " &
                    & // to_text(j) // ") not in its place")
                if (allocated(error)) return
            end do
        end do
    end subroutine test_hessian_places

    !> A position UCON on part PAR(1) over PAR(2) = 3 variables (theta, X, Z) or 4 (phi, Z, X,
    !> psi), in that order: F = 0 and XMATRX(i, j) = 10 i + j, entries told apart by their
    !> value (test_hessian_places).
    subroutine shuffled_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(30)
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        integer, intent(in) :: idrsel(3)
        integer, intent(in) :: iflag
        real(wp), intent(inout) :: scalar
        real(wp), intent(inout) :: array(30)
        real(wp), intent(inout) :: xmatrx(30, 30)
        integer :: n, i, j

        if (npar < 2) return
        n = nint(par(2))
        if (iflag == iflag_init) then
            if (n == 3) then
                call ucovar(id, 3, spread(nint(par(1)), 1, 3), 3, [15, 11, 13])
            else
                call ucovar(id, 4, spread(nint(par(1)), 1, 4), 4, [16, 13, 11, 14])
            end if
            return
        end if
        if (idrsel(1) /= 0) scalar = 0.0_wp
        if (idrsel(3) == xmatrx_dqdq) then
            do j = 1, n
                do i = 1, n
                    xmatrx(i, j) = 10.0_wp*i + j
                end do
            end do
        end if
    end subroutine shuffled_ucosub

    !> A generic state of the paper's disk: tilted, turning, no angle at a special value.
    subroutine generic_problem(problem, q, u, drift)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(out) :: q(6), u(6)
        integer, intent(in) :: drift
        type(scene_type) :: scene
        type(error_type), allocatable :: error

        scene%initial%theta = 1.1_wp
        scene%initial%psi = 0.4_wp
        scene%initial%phi = 0.7_wp
        scene%initial%psidot = 1.3_wp
        scene%initial%thetadot = -0.6_wp
        scene%initial%phidot = -4.0_wp
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q, u, error)
        if (allocated(error)) error stop "generic_problem: " // error%message
        problem%settings%drift = drift
        call problem%prepare(error)
        if (allocated(error)) error stop "generic_problem: " // error%message
    end subroutine generic_problem

    subroutine test_body_jacobian(error)
        type(error_type), allocatable, intent(out) :: error
        type(part_type) :: part
        real(wp) :: q(6), u(6), a(6), dq(6, 6), du(6, 6), fd(6), torque(3), force(3), g(3)
        real(wp) :: qh(6), uh(6)
        integer :: j

        part%mass = 2.0_wp
        part%inertia = [0.3_wp, 0.5_wp, 0.7_wp]
        q = [0.1_wp, -0.2_wp, 0.3_wp, 0.4_wp, 1.0_wp, -0.8_wp]
        u = [0.5_wp, 0.1_wp, -0.3_wp, 1.5_wp, -0.7_wp, 2.5_wp]
        a = [0.2_wp, -0.4_wp, 0.1_wp, 0.9_wp, 0.3_wp, -1.1_wp]
        force = [0.0_wp, 0.0_wp, 0.0_wp]
        torque = [0.0_wp, 0.0_wp, 0.0_wp]
        g = [0.0_wp, 0.0_wp, -9.81_wp]
        call body_residual_jacobian(part, q, u, a, torque, dq, du)
        do j = 1, 6
            qh = q
            qh(j) = q(j) + h_fd
            fd = body_residual(part, qh, u, a, force, torque, g)
            qh(j) = q(j) - h_fd
            fd = (fd - body_residual(part, qh, u, a, force, torque, g))/(2.0_wp*h_fd)
            call check(error, dq(:, j), fd, "d(M a - f)/dq column " // to_text(j), abs_tol=tol_fd)
            if (allocated(error)) return
            uh = u
            uh(j) = u(j) + h_fd
            fd = body_residual(part, q, uh, a, force, torque, g)
            uh(j) = u(j) - h_fd
            fd = (fd - body_residual(part, q, uh, a, force, torque, g))/(2.0_wp*h_fd)
            call check(error, du(:, j), fd, "d(M a - f)/du column " // to_text(j), abs_tol=tol_fd)
            if (allocated(error)) return
        end do
    end subroutine test_body_jacobian

    !> u^T M u = 2 T: the mass matrix and the kinetic energy are the same quadratic form.
    subroutine test_mass_matrix(error)
        type(error_type), allocatable, intent(out) :: error
        type(part_type) :: part
        real(wp) :: q(6), u(6)

        part%mass = 0.7_wp
        part%inertia = [1.8e-3_wp, 1.8e-3_wp, 3.6e-3_wp]
        q = [0.0_wp, 0.0_wp, 0.1_wp, 0.3_wp, 0.9_wp, 2.0_wp]
        u = [0.1_wp, 0.2_wp, -0.1_wp, 3.0_wp, -1.0_wp, 7.0_wp]
        call check(error, dot_product(u, matmul(body_mass_matrix(part, q), u)), &
            & 2.0_wp*kinetic_energy(part, q, u), "u^T M u against 2 T", rel_tol=1.0e-14_wp)
    end subroutine test_mass_matrix

    !> The ODE Jacobian from the UCOSUB's partials against central differences of the
    !> right-hand side (which solves the saddle-point system each time).
    subroutine check_ode_jacobian(error, drift)
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in) :: drift
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(error_type), allocatable :: failure
        real(wp) :: q(6), u(6), y(12), yh(12), jac(12, 12), fp(12), fm(12), scale
        integer :: j, ierr

        call generic_problem(problem, q, u, drift)
        call ode%init(problem)
        y = [q, u]
        call problem%eq%ode_jacobian(0.0_wp, q, u, problem%settings%baumgarte(), jac, failure)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        scale = maxval(abs(jac))
        do j = 1, 12
            yh = y
            yh(j) = y(j) + h_fd
            ierr = ode%ode_rhs(0.0_wp, yh, fp)
            yh(j) = y(j) - h_fd
            ierr = ierr + ode%ode_rhs(0.0_wp, yh, fm)
            call check(error, ierr == 0, "right-hand side failed")
            if (allocated(error)) return
            call check(error, jac(:, j), (fp - fm)/(2.0_wp*h_fd), "ODE Jacobian column " &
                & // to_text(j), abs_tol=tol_fd*scale)
            if (allocated(error)) return
        end do
    end subroutine check_ode_jacobian

    subroutine test_ode_jacobian(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ode_jacobian(error, drift_none)
    end subroutine test_ode_jacobian

    subroutine test_ode_jacobian_baumgarte(error)
        type(error_type), allocatable, intent(out) :: error

        call check_ode_jacobian(error, drift_baumgarte)
    end subroutine test_ode_jacobian_baumgarte

    !> IDA's Newton matrix dr/dy + cj dr/dy' against central differences of the residual.
    subroutine test_dae_jacobian(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(error_type), allocatable :: failure
        real(wp) :: q(6), u(6), cj, scale
        real(wp), allocatable :: y(:), yp(:), yh(:), rp(:), rm(:), jac(:, :), fd(:)
        integer :: m, j, jj

        call generic_problem(problem, q, u, drift_none)
        m = dae_size(problem%eq)
        allocate(y(m), yp(m), yh(m), rp(m), rm(m), fd(m), jac(m, m))
        call problem%accelerations(0.0_wp, q, u, failure)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        y = [q, u, problem%lambda]
        yp = [u, problem%a, [(0.0_wp, j = 1, problem%eq%nc)]]
        ! perturb the rates so the test does not sit on the consistent manifold only
        yp(1:6) = yp(1:6) + 0.05_wp
        cj = 37.0_wp
        call dae_jacobian(problem%eq, 0.0_wp, cj, y, yp, jac, failure)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        scale = maxval(abs(jac))
        do j = 1, m
            yh = y
            yh(j) = y(j) + h_fd
            call dae_residual(problem%eq, 0.0_wp, yh, yp + merge(cj*h_fd, 0.0_wp, &
                & [(j == jj, jj = 1, m)]), rp, failure)
            yh(j) = y(j) - h_fd
            call dae_residual(problem%eq, 0.0_wp, yh, yp - merge(cj*h_fd, 0.0_wp, &
                & [(j == jj, jj = 1, m)]), rm, failure)
            if (allocated(failure)) then
                call move_alloc(failure, error)
                return
            end if
            fd = (rp - rm)/(2.0_wp*h_fd)
            call check(error, jac(:, j), fd, "DAE Newton matrix column " // to_text(j), &
                & abs_tol=tol_fd*scale)
            if (allocated(error)) return
        end do
    end subroutine test_dae_jacobian

    !> The right-hand side's one-pass M and f against the mass matrix and the residual at a = 0,
    !> with an applied force and moment.
    subroutine test_mass_and_force(error)
        type(error_type), allocatable, intent(out) :: error
        type(part_type) :: part
        real(wp) :: q(6), u(6), m(6, 6), f(6), force(3), torque(3), g(3), zero(6)

        zero = 0.0_wp
        part%mass = 2.0_wp
        part%inertia = [0.3_wp, 0.5_wp, 0.7_wp]
        q = [0.1_wp, -0.2_wp, 0.3_wp, 0.4_wp, 1.0_wp, -0.8_wp]
        u = [0.5_wp, 0.1_wp, -0.3_wp, 1.5_wp, -0.7_wp, 2.5_wp]
        force = [0.3_wp, -1.0_wp, 2.0_wp]
        torque = [0.2_wp, 0.1_wp, -0.4_wp]
        g = [0.0_wp, 0.0_wp, -9.81_wp]
        call body_mass_and_force(part, q, u, force, torque, g, m, f)
        call check(error, reshape(m, [36]), reshape(body_mass_matrix(part, q), [36]), &
            & "mass matrix", rel_tol=1.0e-15_wp, abs_tol=1.0e-15_wp)
        if (allocated(error)) return
        call check(error, f, -body_residual(part, q, u, zero, force, torque, g), &
            & "generalised forces", rel_tol=1.0e-14_wp, abs_tol=1.0e-14_wp)
    end subroutine test_mass_and_force

    !> The structured (Schur complement) saddle-point solve against LU of the whole
    !> [M, -C^T; C, 0] matrix at a generic state: same accelerations and multipliers.
    subroutine test_saddle_point(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp) :: q(6), u(6), kkt(9, 9), b(9, 1), row(6)
        integer :: pivots(9), k

        call generic_problem(problem, q, u, drift_baumgarte)
        call problem%accelerations(0.0_wp, q, u, error)
        if (allocated(error)) return
        kkt = 0.0_wp
        kkt(:6, :6) = problem%eq%mass(:, :, 1)
        do k = 1, 3
            call problem%eq%c%fill_row(k, row)
            kkt(:6, 6 + k) = -row
            kkt(6 + k, :6) = row
        end do
        b(:6, 1) = problem%eq%force
        b(7:, 1) = problem%eq%gamma
        call factor_dense(kkt, pivots, error)
        if (allocated(error)) return
        call solve_factored(kkt, pivots, b, error)
        if (allocated(error)) return
        call check(error, problem%a, b(:6, 1), "accelerations", &
            & abs_tol=tol_solve*maxval(abs(b(:6, 1))))
        if (allocated(error)) return
        call check(error, problem%lambda, b(7:, 1), "multipliers", &
            & abs_tol=tol_solve*maxval(abs(b(7:, 1))))
    end subroutine test_saddle_point

    !> Two disks (parts 7 and 3) and a free part (5, no UCON) at generic states: the
    !> saddle-point system solved block by block, as every evaluation does (M^-1 f within the
    !> factorisation's LAPACK calls), gives the dense path's numbers exactly
    !> (rollcon_saddle_point: the same sums without their exact-zero terms; -0 and +0 compare
    !> equal), for the accelerations and for two more right-hand sides, whether each disk's
    !> UCONs come in one run (1, 2, 3 | 4, 5, 6: one LAPACK solve per part and run) or
    !> interleaved (1, 3, 5 | 2, 4, 6: runs of one). C as held by rows: check_constraint_rows.
    !> Rows 2 and 5 set aside (as the position projection sets aside every row but the active
    !> position UCONs'): the blocks' masked factorisation gives their multipliers zero and the
    !> other numbers of the KKT matrix of the four rows kept, to tol_solve.
    subroutine test_saddle_blocks(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type), target :: models(2)
        type(problem_type), target :: problems(2)
        type(part_type) :: part
        type(saddle_point_type) :: dense
        real(wp) :: q(18), u(18), a(18), lambda(6), r1(18, 2), r2(6, 2), s1(18, 2), s2(6, 2)
        real(wp) :: kkt(22, 22), b(22, 1), row(18)
        logical :: keep(6)
        integer :: order, k, i, pivots(22)

        do order = 1, 2
            associate (model => models(order), problem => problems(order))
                part%mass = 0.18_wp
                part%inertia = [4.6e-4_wp, 4.6e-4_wp, 9.1e-4_wp]
                part%id = 7
                call model%add_part(part)
                part%id = 3
                call model%add_part(part)
                part%id = 5
                call model%add_part(part)
                model%gravity = [0.0_wp, 0.0_wp, -9.81_wp]
                model%ucosub => rolling_disk_ucosub
                if (order == 1) then
                    do k = 1, 3
                        call model%add_ucon(10 + k, disk_par(7, 0.1_wp, k))
                    end do
                    do k = 1, 3
                        call model%add_ucon(20 + k, disk_par(3, 0.08_wp, k))
                    end do
                else
                    do k = 1, 3
                        call model%add_ucon(10 + k, disk_par(7, 0.1_wp, k))
                        call model%add_ucon(20 + k, disk_par(3, 0.08_wp, k))
                    end do
                end if
                call setup_model(model, error)
                if (allocated(error)) return
                call problem%init(model)
                call problem%prepare(error)
                if (allocated(error)) return
                q = [0.1_wp, -0.2_wp, 0.08_wp, 0.4_wp, 1.1_wp, 0.7_wp, &
                    & 0.5_wp, 0.3_wp, 0.07_wp, -0.9_wp, 1.9_wp, -0.3_wp, &
                    & -0.4_wp, 0.2_wp, 0.5_wp, 0.6_wp, 0.8_wp, 1.2_wp]
                u = [0.2_wp, 0.1_wp, -0.05_wp, 1.3_wp, -0.6_wp, -4.0_wp, &
                    & -0.1_wp, 0.3_wp, 0.02_wp, 0.8_wp, 0.4_wp, 3.0_wp, &
                    & 0.3_wp, -0.2_wp, 0.1_wp, -1.1_wp, 0.5_wp, 2.0_wp]
                call problem%accelerations(0.0_wp, q, u, error)
                if (allocated(error)) return
                call check(error, problem%eq%saddle%by_blocks .and. problem%eq%blocks%count == 2, &
                    & "the two disks' system was not solved by its two blocks")
                if (allocated(error)) return
                call check_constraint_rows(problem, error)
                if (allocated(error)) return
                call dense%init(18, 6)
                call dense%factor(problem%eq%mass, problem%eq%c, 6, error)
                if (allocated(error)) return
                a = problem%eq%force
                lambda = problem%eq%gamma
                call dense%solve(problem%eq%c, a, lambda, 1, error)
                if (allocated(error)) return
                call check(error, all(problem%a == a) .and. all(problem%lambda == lambda), &
                    & "accelerations or multipliers by blocks differ from the dense path's, " &
                    & // "order " // to_text(order) // ": largest difference " &
                    & // to_text(max(maxval(abs(problem%a - a)), &
                    & maxval(abs(problem%lambda - lambda)))))
                if (allocated(error)) return
                do i = 1, 18
                    r1(i, :) = [0.3_wp*i - 1.0_wp, sin(real(i, wp))]
                end do
                r2(:, 1) = [(0.2_wp*i, i = 1, 6)]
                r2(:, 2) = [(cos(real(i, wp)), i = 1, 6)]
                s1 = r1
                s2 = r2
                call problem%eq%saddle%solve(problem%eq%c, r1, r2, 2, error)
                if (allocated(error)) return
                call dense%solve(problem%eq%c, s1, s2, 2, error)
                if (allocated(error)) return
                call check(error, all(r1 == s1) .and. all(r2 == s2), "two right-hand sides by " &
                    & // "blocks differ from the dense path's, order " // to_text(order))
                if (allocated(error)) return
                keep = [(k /= 2 .and. k /= 5, k = 1, 6)]
                call problem%eq%saddle%factor(problem%eq%mass, problem%eq%c, 6, error, &
                    & active=keep)
                if (allocated(error)) return
                a = problem%eq%force
                lambda = problem%eq%gamma
                call problem%eq%saddle%solve(problem%eq%c, a, lambda, 1, error)
                if (allocated(error)) return
                kkt = 0.0_wp
                do i = 1, 3
                    kkt(6*i - 5:6*i, 6*i - 5:6*i) = problem%eq%mass(:, :, i)
                end do
                b(:18, 1) = problem%eq%force
                i = 18
                do k = 1, 6
                    if (.not. keep(k)) cycle
                    i = i + 1
                    call problem%eq%c%fill_row(k, row)
                    kkt(:18, i) = -row
                    kkt(i, :18) = row
                    b(i, 1) = problem%eq%gamma(k)
                end do
                call factor_dense(kkt, pivots, error)
                if (allocated(error)) return
                call solve_factored(kkt, pivots, b, error)
                if (allocated(error)) return
                call check(error, lambda(2) == 0.0_wp .and. lambda(5) == 0.0_wp, "a row set " &
                    & // "aside has a multiplier, order " // to_text(order))
                if (allocated(error)) return
                call check(error, a, b(:18, 1), "accelerations with rows set aside", &
                    & abs_tol=tol_solve*maxval(abs(b(:18, 1))))
                if (allocated(error)) return
                call check(error, pack(lambda, keep), b(19:, 1), "multipliers of the rows " &
                    & // "kept", abs_tol=tol_solve*maxval(abs(b(19:, 1))))
                if (allocated(error)) return
            end associate
        end do
    end subroutine test_saddle_blocks

    !> C as the equations hold it (rollcon_constraint_matrix: rows over each UCON's own
    !> coordinates) against the UCONs' first partials read densely (dF/du, or dF/dq for a
    !> position UCON: rollcon_constraints' fill rows, an independent accessor): every entry,
    !> exact zeros off a UCON's part included, and each row operation (entry, entry_along,
    !> gather, row_dot, add_row, times, transpose_times, dense) against the same sums on the
    !> dense rows. The
    !> entries agree exactly; the sums run over the same nonzero terms, in an order a vectorised
    !> dot_product or matmul may change: 1e-15 (products) and 1e-14 (sums of n terms) of their
    !> scale is rounding, a wrong or missing entry is O(1) of it.
    subroutine check_constraint_rows(problem, error)
        type(problem_type), intent(in) :: problem
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: rows(:, :), d(:, :), y(:), z(:)
        real(wp) :: v(problem%eq%n), w(problem%eq%nc), part_slice(6), along
        integer :: k, j, n, nc, x

        n = problem%eq%n
        nc = problem%eq%nc
        allocate(rows(nc, n), y(n), z(n))
        do k = 1, nc
            if (problem%model%ucons(k)%holonomic) then
                call problem%eq%constraints%fill_grad_q_row(k, y)
            else
                call problem%eq%constraints%fill_grad_u_row(k, y)
            end if
            rows(k, :) = y
        end do
        v = [(sin(1.3_wp*j) + 0.1_wp*j, j = 1, n)]
        w = [(cos(0.7_wp*j), j = 1, nc)]
        call problem%eq%c%dense(d)
        call check(error, all(d == rows), "C by rows differs from the UCONs' partials")
        if (allocated(error)) return
        call check(error, count(rows /= 0.0_wp) <= size(problem%eq%c%value) .and. &
            & size(problem%eq%c%value) < n*nc, "C by rows holds " &
            & // to_text(size(problem%eq%c%value)) // " entries for " &
            & // to_text(count(rows /= 0.0_wp)) // " nonzeros of " // to_text(n*nc))
        if (allocated(error)) return
        do k = 1, nc
            do j = 1, n
                call check(error, problem%eq%c%entry(k, j) == rows(k, j), "entry (" &
                    & // to_text(k) // ", " // to_text(j) // ")")
                if (allocated(error)) return
            end do
            x = problem%eq%c%start(k)
            do j = 1, n
                call problem%eq%c%entry_along(k, j, x, along)
                call check(error, along == rows(k, j), "entry_along (" // to_text(k) // ", " &
                    & // to_text(j) // ")")
                if (allocated(error)) return
            end do
            do j = 1, n/6
                call problem%eq%c%gather(k, 6*(j - 1) + 1, part_slice)
                call check(error, all(part_slice == rows(k, 6*j - 5:6*j)), "gather of row " &
                    & // to_text(k) // " at part " // to_text(j))
                if (allocated(error)) return
            end do
            call check(error, abs(problem%eq%c%row_dot(k, v) - dot_product(rows(k, :), v)) &
                & <= 1.0e-15_wp*sum(abs(rows(k, :)*v)), "row_dot of row " // to_text(k))
            if (allocated(error)) return
            call problem%eq%c%fill_row(k, y)
            call check(error, all(y == rows(k, :)), "fill_row of row " // to_text(k))
            if (allocated(error)) return
            y = v
            call problem%eq%c%add_row(k, 0.5_wp, y)
            call check(error, all(abs(y - (v + 0.5_wp*rows(k, :))) <= spacing(abs(y))), &
                & "add_row of row " // to_text(k))
            if (allocated(error)) return
        end do
        call problem%eq%c%times(v, w)
        call check(error, maxval(abs(w - matmul(rows, v))) <= 1.0e-14_wp*maxval(abs(rows)) &
            & *sum(abs(v)), "C v")
        if (allocated(error)) return
        w = [(cos(0.7_wp*j), j = 1, nc)]
        call problem%eq%c%transpose_times(w, z)
        call check(error, maxval(abs(z - matmul(w, rows))) <= 1.0e-14_wp*maxval(abs(rows)) &
            & *sum(abs(w)), "C^T lambda")
    end subroutine check_constraint_rows

    !> The equations evaluate the problem's own model, not a copy of it: gravity changed there
    !> after set-up changes the accelerations, affinely (a = M^-1 (f + C^T lambda) with gravity
    !> entering f alone, and gamma free of it). The problem names its UCONs: the coin's 1, 2, 3.
    subroutine test_problem_model(error)
        type(error_type), allocatable, intent(out) :: error
        !> Gravity's share of the accelerations is of order g = 9.81 m/s^2; at least a
        !> thousandth of it shows that the change reached the equations
        real(wp), parameter :: min_gravity_share = 1.0e-2_wp
        type(problem_type), target :: problem
        real(wp) :: q(6), u(6), g0(3), a(6, 3)
        integer :: pass

        call generic_problem(problem, q, u, drift_none)
        g0 = problem%model%gravity
        do pass = 1, 3
            ! gravity 0, g0, 2 g0
            problem%model%gravity = real(pass - 1, wp)*g0
            call problem%accelerations(0.0_wp, q, u, error)
            if (allocated(error)) return
            a(:, pass) = problem%a
        end do
        call check(error, maxval(abs(a(:, 2) - a(:, 1))) > min_gravity_share, &
            & "accelerations unchanged by the problem's gravity: the equations use a copy")
        if (allocated(error)) return
        call check(error, a(:, 3) - a(:, 2), a(:, 2) - a(:, 1), "gravity's share of a", &
            & abs_tol=tol_solve*maxval(abs(a)))
        if (allocated(error)) return
        call check(error, problem%ucon_count() == 3 .and. all([problem%ucon_id(1), &
            & problem%ucon_id(2), problem%ucon_id(3)] == [1, 2, 3]), "UCON count and ids " &
            & // to_text(problem%ucon_count()))
    end subroutine test_problem_model

    !> The settings' formulation makes the system (new_formulation, a run's one choice): the ODE
    !> form, the DAE form or the independent speeds; and the system's form takes its integrator
    !> (start_integrator): CVODE the two ODE forms, IDA the DAE form (docs/design.md §4). Each
    !> is packed at the disk's generic state and started on it.
    subroutine test_integrator_choice(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: formulations(3) = [formulation_cvode, formulation_ida, &
            & formulation_speeds]
        character(len=*), parameter :: names(3) = [character(len=5) :: "cvode", "ida", "maggi"]
        !> The system's type (1 ODE form, 2 DAE form, 3 independent speeds) and the
        !> integrator's (1 CVODE, 2 IDA) each formulation must give
        integer, parameter :: systems(3) = [1, 2, 3], integrators(3) = [1, 2, 1]
        type(problem_type), target :: problem
        class(dynamic_system_type), allocatable, target :: system
        class(integrator_type), allocatable, target :: integrator
        real(wp) :: q(6), u(6)
        real(wp), allocatable :: y(:), yp(:)
        integer :: k, got_system, got_integrator

        call generic_problem(problem, q, u, drift_none)
        do k = 1, size(formulations)
            problem%settings%formulation = formulations(k)
            call problem%accelerations(0.0_wp, q, u, error)
            if (allocated(error)) return
            call new_formulation(problem, system)
            select type (system)
            type is (ode_form_type)
                got_system = 1
            type is (dae_form_type)
                got_system = 2
            type is (speeds_form_type)
                got_system = 3
            class default
                got_system = 0
            end select
            if (allocated(y)) deallocate(y, yp)
            allocate(y(system%state_size()), yp(system%state_size()))
            call system%pack_state(q, u, y, yp)
            call start_integrator(system, problem%settings, 0.0_wp, y, yp, 1.0_wp, integrator, &
                & error)
            if (allocated(error)) return
            select type (integrator)
            type is (cvode_integrator_type)
                got_integrator = 1
            type is (ida_integrator_type)
                got_integrator = 2
            class default
                got_integrator = 0
            end select
            call integrator%destroy()
            call system%release()
            call check(error, got_system == systems(k) .and. got_integrator == integrators(k), &
                & "formulation '" // trim(names(k)) // "' made system " // to_text(got_system) &
                & // " on integrator " // to_text(got_integrator) // ", expected " &
                & // to_text(systems(k)) // " on " // to_text(integrators(k)))
            if (allocated(error)) return
        end do
    end subroutine test_integrator_choice

end module test_dynamics
