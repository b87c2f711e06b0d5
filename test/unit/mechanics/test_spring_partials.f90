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
    use newton_checks, only : check_ode_matrix, check_dae_matrix
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
        real(wp), allocatable :: q0(:), u0(:), jac(:, :)
        integer, allocatable :: blocks(:)
        integer :: n

        call build(problem, q0, u0, error)
        if (allocated(error)) return
        call check_ode_matrix(problem, q0, u0, h_fd, tol_fd, jac, blocks, error)
        if (allocated(error)) return
        n = size(q0)
        ! the accelerations of part 2 (rows n + 1:n + 6) by the coordinates of part 3
        call check(error, maxval(abs(jac(n + 1:n + 6, 7:12))) > 1.0_wp, "part 2's " &
            & // "accelerations depend on part 3's coordinates: largest partial " &
            & // to_text(maxval(abs(jac(n + 1:n + 6, 7:12)))))
        if (allocated(error)) return
        call check(error, all(blocks == blocks(1)), "parts 2 and 3 share CVODE's block")
        call problem%release()
    end subroutine test_ode

    !> dr/dy of the DAE residual (cj = 0) against central differences in y, and dr/dy' (the
    !> mass matrix and the identity, cj = 1 less cj = 0) against those in y'; every entry not
    !> zero is in the sparse pattern.
    subroutine test_dae(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:), jac(:, :)
        integer :: n

        call build(problem, q0, u0, error)
        if (allocated(error)) return
        call check_dae_matrix(problem, q0, u0, h_fd, tol_fd, jac, error)
        if (allocated(error)) return
        n = size(q0)
        call check(error, maxval(abs(jac(n + 1:n + 6, 7:12))) > 1.0_wp, "part 2's momentum " &
            & // "rows depend on part 3's coordinates")
        call problem%release()
    end subroutine test_dae

end module test_spring_partials
