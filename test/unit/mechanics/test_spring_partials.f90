! SPDX-License-Identifier: MIT
!> The Newton matrices of a model held by SPRINGDAMPERs and a BUSHING (suite spring-partials;
!> src/mechanics/rollcon_spring_partials.f90): two parts in general position and motion, a
!> BUSHING between markers off their centres, a translational SPRINGDAMPER from one to the
!> ground and a rotational one between them, under gravity. The ODE Jacobian (CVODE's) and
!> the DAE Jacobian (IDA's) against central differences of the right-hand side and of the
!> residual, entry by entry; the parts' coupling is in both (its entries far from zero), in
!> the DAE's sparse pattern and in CVODE's blocks.
module test_spring_partials
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_dae, only : dae_size, dae_residual, dae_jacobian
    use rollcon_newton_pattern, only : newton_pattern_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_build, only : build_adm_problem
    use adm_datasets, only : read_dataset
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_spring_partials

    !> Central differences of step h_fd: their truncation error h^2 f'''/6 and rounding
    !> eps f/h_fd are below 1e-8 of the matrix's largest entry here; tol_fd, 1e-6 of it,
    !> stands a hundred times above them, and a missing partial (a stiffness of 50 to 300 over
    !> masses of 1.5 to 2) is 1e-2 of it or more.
    real(wp), parameter :: tol_fd = 1.0e-6_wp, h_fd = 1.0e-6_wp
    character(len=160), parameter :: lines(15) = [character(len=160) :: &
        & "springs and a bushing", &
        & "UNITS/SYSTEM = SI", &
        & "PART/1, GROUND", &
        & "MARKER/10, PART = 1, QP = 0.1, 0.2, 0.3, REULER = 10D, 20D, 30D", &
        & "PART/2, MASS = 2, CM = 20, IP = 1, 2, 2.5, QG = 0.3, -0.2, 0.5, REULER = 40D, 70D, " &
        & // "-20D, VX = 0.2, VY = -0.1, VZ = 0.3, WX = 0.3, WY = -0.5, WZ = 0.7", &
        & "MARKER/20, PART = 2|MARKER/21, PART = 2, QP = 0.1, 0.05, -0.2, REULER = 15D, 35D, 5D", &
        & "PART/3, MASS = 1.5, CM = 30, IP = 0.8, 1.1, 1.3, QG = -0.4, 0.3, 0.1, REULER = " &
        & // "-30D, 50D, 60D, VX = -0.3, VZ = 0.1, WX = -0.4, WY = 0.2, WZ = 0.9", &
        & "MARKER/30, PART = 3|MARKER/31, PART = 3, QP = -0.1, 0.2, 0.1, REULER = 5D, 25D, 45D", &
        & "BUSHING/1, I = 21, J = 31, K = 100, 200, 300, C = 0.8, 1.2, 2, KT = 50, 60, 80, " &
        & // "CT = 0.4, 0.6, 0.8, FORCE = 2, -3, 4, TORQUE = 0.1, 0.2, -0.3", &
        & "SPRINGDAMPER/2, TRANSLATIONAL, I = 20, J = 10, K = 150, C = 3, LENGTH = 0.2, " &
        & // "FORCE = 5", &
        & "SPRINGDAMPER/3, ROTATIONAL, I = 31, J = 21, KT = 70, CT = 0.9, ANGLE = 20D, " &
        & // "TORQUE = 0.4", &
        & "ACCGRAV/KGRAV = -9.81", &
        & "INTEGRATOR/ERROR = 1e-8", &
        & "SIMULATE/DYNAMIC, END = 1, STEPS = 10", &
        & "END"]

contains

    subroutine collect_spring_partials(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("ode-jacobian-against-differences", test_ode), &
            & new_unittest("dae-jacobian-against-differences-and-its-pattern", test_dae)]
    end subroutine collect_spring_partials

    !> The model, built from the dataset, at its start (q0, u0).
    subroutine build(problem, q0, u0, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine
        type(adm_model_type) :: adm

        routine => rolling_disk_ucosub
        call read_dataset("spring_partials.adm", lines, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, routine, problem, q0, u0, error)
        if (allocated(error)) return
        call problem%prepare(error)
    end subroutine build

    !> d(q', u')/d(q, u) from the partials against central differences of (u, a(q, u)); the
    !> accelerations of part 2 depend on the coordinates and rates of part 3; parts 2 and 3
    !> share CVODE's block.
    subroutine test_ode(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(error_type), allocatable :: failure
        real(wp), allocatable :: q0(:), u0(:), y(:), yh(:), jac(:, :), fp(:), fm(:)
        integer, allocatable :: blocks(:)
        real(wp) :: scale
        integer :: j, ierr, n

        call build(problem, q0, u0, error)
        if (allocated(error)) return
        call ode%init(problem)
        n = size(q0)
        y = [q0, u0]
        allocate(yh(2*n), jac(2*n, 2*n), fp(2*n), fm(2*n))
        call problem%eq%ode_jacobian(0.0_wp, q0, u0, problem%settings%baumgarte(), jac, failure)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        scale = maxval(abs(jac))
        do j = 1, 2*n
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
        ! the accelerations of part 2 (rows n + 1:n + 6) by the coordinates of part 3
        call check(error, maxval(abs(jac(n + 1:n + 6, 7:12))) > 1.0_wp, "part 2's " &
            & // "accelerations depend on part 3's coordinates: largest partial " &
            & // to_text(maxval(abs(jac(n + 1:n + 6, 7:12)))))
        if (allocated(error)) return
        blocks = ode%state_blocks(2*n)
        call check(error, all(blocks == blocks(1)), "parts 2 and 3 share CVODE's block")
        call problem%release()
    end subroutine test_ode

    !> dr/dy of the DAE residual (cj = 0) against central differences in y, and dr/dy' (the
    !> mass matrix and the identity, cj = 1 less cj = 0) against those in y'; every entry not
    !> zero is in the sparse pattern.
    subroutine test_dae(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(dae_form_type) :: dae
        type(newton_pattern_type) :: pattern
        type(error_type), allocatable :: failure
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:), yh(:), jac(:, :), jac1(:, :), &
            & rp(:), rm(:)
        logical, allocatable :: kept(:, :)
        real(wp) :: scale
        integer :: j, n, m, k

        call build(problem, q0, u0, error)
        if (allocated(error)) return
        call dae%init(problem)
        n = size(q0)
        m = dae_size(problem%eq)
        y = [q0, u0]
        ! an acceleration of no particular meaning: the residual is linear in it
        yp = [u0, [(0.1_wp*k - 0.5_wp, k = 1, n)]]
        allocate(jac(m, m), jac1(m, m), rp(m), rm(m), yh(m))
        call dae_jacobian(problem%eq, 0.0_wp, 0.0_wp, y, yp, jac, failure)
        if (.not. allocated(failure)) call dae_jacobian(problem%eq, 0.0_wp, 1.0_wp, y, yp, &
            & jac1, failure)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        scale = maxval(abs(jac))
        do j = 1, m
            yh = y
            yh(j) = y(j) + h_fd
            call dae_residual(problem%eq, 0.0_wp, yh, yp, rp, failure)
            yh(j) = y(j) - h_fd
            if (.not. allocated(failure)) call dae_residual(problem%eq, 0.0_wp, yh, yp, rm, &
                & failure)
            if (allocated(failure)) then
                call move_alloc(failure, error)
                return
            end if
            call check(error, jac(:, j), (rp - rm)/(2.0_wp*h_fd), "DAE dr/dy column " &
                & // to_text(j), abs_tol=tol_fd*scale)
            if (allocated(error)) return
            yh = yp
            yh(j) = yp(j) + h_fd
            call dae_residual(problem%eq, 0.0_wp, y, yh, rp, failure)
            yh(j) = yp(j) - h_fd
            if (.not. allocated(failure)) call dae_residual(problem%eq, 0.0_wp, y, yh, rm, &
                & failure)
            if (allocated(failure)) then
                call move_alloc(failure, error)
                return
            end if
            call check(error, jac1(:, j) - jac(:, j), (rp - rm)/(2.0_wp*h_fd), "DAE " &
                & // "dr/dy' column " // to_text(j), abs_tol=tol_fd*scale)
            if (allocated(error)) return
        end do
        call check(error, maxval(abs(jac(n + 1:n + 6, 7:12))) > 1.0_wp, "part 2's momentum " &
            & // "rows depend on part 3's coordinates")
        if (allocated(error)) return
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
        call problem%release()
    end subroutine test_dae

end module test_spring_partials
