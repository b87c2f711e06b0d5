! SPDX-License-Identifier: MIT
!> Newton matrices against central differences, entry by entry, for the suites that check a
!> kind of partial (spring-partials, force-partials): CVODE's d(q', u')/d(q, u) against
!> differences of the ODE form's right-hand side, and IDA's dr/dy (cj = 0) and dr/dy' (cj = 1
!> less cj = 0) against differences of the DAE residual in y and in y', every entry that is
!> not zero kept by IDA's sparse pattern, the multipliers' columns (and the GGL multipliers')
!> among them. The caller chooses the step and the tolerance (its own model's scales) and
!> checks the couplings it expects in the matrices returned.
module newton_checks
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_dae, only : dae_size, dae_residual, dae_jacobian
    use rollcon_newton_pattern, only : newton_pattern_type
    use rollcon_testing, only : check
    implicit none
    private

    public :: check_ode_matrix, check_dae_matrix

contains

    !> CVODE's Newton matrix jac (2n x 2n) at (0, q0, u0) against central differences of step
    !> h of the right-hand side, each column to tol times the matrix's largest entry; blocks:
    !> CVODE's block of each state (ode_form's state_blocks).
    subroutine check_ode_matrix(problem, q0, u0, h, tol, jac, blocks, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:), h, tol
        real(wp), allocatable, intent(out) :: jac(:, :)
        integer, allocatable, intent(out) :: blocks(:)
        type(error_type), allocatable, intent(out) :: error
        type(ode_form_type) :: ode
        real(wp), allocatable :: y(:), yh(:), fp(:), fm(:)
        real(wp) :: scale
        integer :: j, ierr, n

        call ode%init(problem)
        n = size(q0)
        y = [q0, u0]
        allocate(jac(2*n, 2*n), yh(2*n), fp(2*n), fm(2*n))
        call problem%eq%ode_jacobian(0.0_wp, q0, u0, problem%settings%baumgarte(), jac, error)
        if (allocated(error)) return
        scale = maxval(abs(jac))
        do j = 1, 2*n
            yh = y
            yh(j) = y(j) + h
            ierr = ode%ode_rhs(0.0_wp, yh, fp)
            yh(j) = y(j) - h
            ierr = ierr + ode%ode_rhs(0.0_wp, yh, fm)
            call check(error, ierr == 0, "right-hand side failed")
            if (allocated(error)) return
            call check(error, jac(:, j), (fp - fm)/(2.0_wp*h), "ODE Jacobian column " &
                & // to_text(j), abs_tol=tol*scale)
            if (allocated(error)) return
        end do
        blocks = ode%state_blocks(2*n)
    end subroutine check_ode_matrix

    !> IDA's dr/dy (jac, m x m, cj = 0) at (0, y = (q0, u0, lambda, mu), y' = (u0, an
    !> acceleration of no particular meaning: the residual is linear in it, 0 for the
    !> multipliers)) against central differences of step h in y, and dr/dy' against those in
    !> y', each column to tol times dr/dy's largest entry: every column, the multipliers'
    !> included (lambda_k = 2 + k, away from a zero reaction, where a force measure |F| has a
    !> kink; mu = 0, as on a consistent state); every entry of dr/dy (cj = 1) that is not zero
    !> is in the DAE form's sparse pattern.
    subroutine check_dae_matrix(problem, q0, u0, h, tol, jac, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: q0(:), u0(:), h, tol
        real(wp), allocatable, intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error
        type(dae_form_type) :: dae
        type(newton_pattern_type) :: pattern
        real(wp), allocatable :: y(:), yp(:), yh(:), jac1(:, :), rp(:), rm(:)
        logical, allocatable :: kept(:, :)
        real(wp) :: scale
        integer :: j, n, m, k, nc

        call dae%init(problem)
        n = size(q0)
        m = dae_size(problem%eq)
        nc = problem%eq%nc
        y = [q0, u0, [(2.0_wp + k, k = 1, nc)], [(0.0_wp, k = 1, m - 2*n - nc)]]
        yp = [u0, [(0.1_wp*k - 0.5_wp, k = 1, n)], [(0.0_wp, k = 1, m - 2*n)]]
        allocate(jac(m, m), jac1(m, m), rp(m), rm(m), yh(m))
        call dae_jacobian(problem%eq, 0.0_wp, 0.0_wp, y, yp, jac, error)
        if (.not. allocated(error)) call dae_jacobian(problem%eq, 0.0_wp, 1.0_wp, y, yp, &
            & jac1, error)
        if (allocated(error)) return
        scale = maxval(abs(jac))
        do j = 1, m
            yh = y
            yh(j) = y(j) + h
            call dae_residual(problem%eq, 0.0_wp, yh, yp, rp, error)
            yh(j) = y(j) - h
            if (.not. allocated(error)) call dae_residual(problem%eq, 0.0_wp, yh, yp, rm, error)
            if (allocated(error)) return
            call check(error, jac(:, j), (rp - rm)/(2.0_wp*h), "DAE dr/dy column " &
                & // to_text(j), abs_tol=tol*scale)
            if (allocated(error)) return
            yh = yp
            yh(j) = yp(j) + h
            call dae_residual(problem%eq, 0.0_wp, y, yh, rp, error)
            yh(j) = yp(j) - h
            if (.not. allocated(error)) call dae_residual(problem%eq, 0.0_wp, y, yh, rm, error)
            if (allocated(error)) return
            call check(error, jac1(:, j) - jac(:, j), (rp - rm)/(2.0_wp*h), "DAE " &
                & // "dr/dy' column " // to_text(j), abs_tol=tol*scale)
            if (allocated(error)) return
        end do
        call dae%dae_pattern(m, pattern)
        allocate(kept(m, m), source=.false.)
        do j = 1, m
            do k = pattern%starts(j) + 1, pattern%starts(j + 1)
                kept(pattern%rows(k) + 1, j) = .true.
            end do
        end do
        call check(error, .not. any(jac1 /= 0.0_wp .and. .not. kept), "the DAE pattern " &
            & // "keeps every entry that is not zero: " // to_text(count(jac1 /= 0.0_wp &
            & .and. .not. kept)) // " left out")
    end subroutine check_dae_matrix

end module newton_checks
