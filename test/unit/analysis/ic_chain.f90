! SPDX-License-Identifier: MIT
!> The initial-conditions analysis of a long chain (rollcon_link_chain's dataset) on the sparse
!> way (SuiteSparseQR's least squares and verdict, velocities given held part by part;
!> rollcon_ic_rows' sparse_ic_columns): a start off its joints, positions and rates disturbed,
!> some velocities given, is made consistent with the given ones kept and the same least
!> weighted change as the SVD's; a contradictory start is refused naming the same statements
!> and lines as the SVD's verdict.
module ic_chain
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_adm_initial, only : adm_ic_options
    use rollcon_initial_conditions, only : ic_options_type, analyse_initial_conditions
    use rollcon_ic_rows, only : sparse_ic_columns
    use rollcon_ic_report, only : ic_report_type, ic_report_text
    use rollcon_link_chain, only : link_chain_dataset
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_chain_sparse_start, test_chain_sparse_contradiction

    !> Scratch folder of these tests
    character(len=*), parameter :: scratch = "build/test_initial_conditions"
    !> Links of the chain: 102 parts, 612 coordinates, 609 rates free with three held exact:
    !> both levels take the sparse way by default (sparse_ic_columns = 600), and the SVD's way
    !> still runs beside it
    integer, parameter :: links = 102
    !> The disturbance of the start: every coordinate by up to 2 mm or 2 mrad, every rate by up
    !> to 0.05 m/s or rad/s (a start visibly off its 500 joint rows, near enough for Newton)
    real(wp), parameter :: dq = 2.0e-3_wp, du = 5.0e-2_wp
    !> Sparse against dense: both are Gauss-Newton from the same start (5 iterations, then one
    !> velocity step, in both) with the same least-norm steps and the same stopping test, so
    !> they differ only by the rounding of different factorisations (QR against SVD, each
    !> backward stable) amplified by the condition of the chain's 510 unit rows. Measured:
    !> 3.5e-14 [m, rad] on changes up to 3.5e-2, and 5.6e-13 [m/s, rad/s] on changes up to 2.1
    !> (~1e-12 and ~3e-13 of the change, cond ~ 1e3). About ten times these: a tenfold loss of
    !> either path's accuracy, or a change that is not the least weighted one, exceeds them
    real(wp), parameter :: tol_positions = 4.0e-13_wp, tol_rates = 6.0e-12_wp
    !> A given velocity is held exactly by the reduced coordinates (du = W Z dz, (held W) Z = 0
    !> to rounding of O(1) entries): its value moves by rounding of the O(1) rates only
    real(wp), parameter :: tol_given = 1.0e-13_wp

contains

    !> The chain of `links` links (with `extra` statements before its ACCGRAV) written, read
    !> and built: the problem, its start (q, u) and its dataset's options.
    subroutine chain_problem(name, extra, problem, q, u, options, error)
        character(len=*), intent(in) :: name, extra
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q(:), u(:)
        type(ic_options_type), intent(out) :: options
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        character(len=:), allocatable :: text
        integer :: unit, at

        text = link_chain_dataset(links, 0.1_wp, 0.05_wp, "FORMULATION=IDA")
        at = index(text, "ACCGRAV/")
        text = text(:at - 1) // extra // text(at:)
        call execute_command_line("mkdir -p " // scratch)
        open(newunit=unit, file=scratch // "/" // name, status="replace", action="write", &
            & access="stream", form="unformatted")
        write(unit) text
        close(unit)
        call read_adm(scratch // "/" // name, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q, u0=u, error=error)
        if (allocated(error)) return
        options = adm_ic_options(adm, problem)
    end subroutine chain_problem

    !> The chain disturbed off its joints (every coordinate and rate), with VX given on every
    !> fourth link and VZ on every fourth from the second (ground axes), and the X rate of
    !> links 1, 5 and 9 held exact: the sparse way (the default at this size) meets every UCON
    !> (a second analysis of its result takes no step), keeps the given and exact velocities,
    !> and moves the start by the same least weighted change as the SVD's way (sparse_columns
    !> beyond the model) within tol_positions and tol_rates.
    subroutine test_chain_sparse_start(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ic_options_type) :: options, dense
        type(ic_report_type) :: report, again, report_dense
        real(wp), allocatable :: q(:), u(:), q_sparse(:), u_sparse(:), q_dense(:), u_dense(:), &
            & u_start(:), q_again(:), u_again(:)
        integer :: j, p

        call chain_problem("chain_sparse.adm", "", problem, q, u, options, error)
        if (allocated(error)) return
        call check(error, size(q) >= sparse_ic_columns, "the chain takes the sparse way: " &
            & // to_text(size(q)) // " coordinates")
        if (allocated(error)) return
        do j = 1, size(q)
            q(j) = q(j) + dq*sin(1.7_wp*j)
            u(j) = u(j) + du*cos(1.3_wp*j)
        end do
        do p = 1, links
            options%given_velocity(:, p) = .false.
            if (mod(p, 4) == 0) options%given_velocity(1, p) = .true.
            if (mod(p, 4) == 2) options%given_velocity(3, p) = .true.
            ! the X rate held exact on links 1, 5 and 9 (a rate row of its own part)
            if (mod(p, 4) == 1 .and. p <= 9) options%exact_u(6*(p - 1) + 1) = .true.
        end do
        call check(error, count(.not. options%exact_u) >= sparse_ic_columns, "the rates take " &
            & // "the sparse way: " // to_text(count(.not. options%exact_u)) // " free")
        if (allocated(error)) return
        u_start = u
        q_sparse = q
        u_sparse = u
        call analyse_initial_conditions(problem, 0.0_wp, q_sparse, u_sparse, options, report, &
            & error)
        if (allocated(error)) return
        call check(error, report%newton_iterations > 0 .and. report%velocity_steps > 0 .and. &
            & .not. report%given_moved, "the disturbed start is moved, the given velocities " &
            & // "kept: " // to_text(report%newton_iterations) // " iterations, " &
            & // to_text(report%velocity_steps) // " velocity steps")
        if (allocated(error)) return
        do p = 1, links
            do j = 1, 3
                if (.not. (options%given_velocity(j, p) .or. options%exact_u(6*(p - 1) + j))) &
                    & cycle
                call check(error, u_sparse(6*(p - 1) + j), u_start(6*(p - 1) + j), &
                    & "given or exact velocity " // to_text(j) // " of link " // to_text(p), &
                    & abs_tol=tol_given)
                if (allocated(error)) return
            end do
        end do
        ! every UCON met to its tolerance: a second analysis finds nothing to do
        q_again = q_sparse
        u_again = u_sparse
        call analyse_initial_conditions(problem, 0.0_wp, q_again, u_again, options, again, &
            & error)
        if (allocated(error)) return
        call check(error, again%newton_iterations == 0 .and. again%velocity_steps == 0 .and. &
            & size(again%changes) == 0, "the result meets every UCON: " // ic_report_text(again))
        if (allocated(error)) return
        dense = options
        dense%sparse_columns = huge(1)
        q_dense = q
        u_dense = u
        call analyse_initial_conditions(problem, 0.0_wp, q_dense, u_dense, dense, &
            & report_dense, error)
        if (allocated(error)) return
        call check(error, maxval(abs(q_sparse - q_dense)) <= tol_positions, "positions, sparse " &
            & // "against dense: " // to_text(maxval(abs(q_sparse - q_dense))))
        if (allocated(error)) return
        call check(error, maxval(abs(u_sparse - u_dense)) <= tol_rates, "rates, sparse " &
            & // "against dense: " // to_text(maxval(abs(u_sparse - u_dense))))
    end subroutine test_chain_sparse_start

    !> The chain with a second REVOLUTE hinging link 1's lower end at the ground hinge too (its
    !> ends are a link apart): refused on the sparse way as contradictory, naming JOINT/1 and
    !> the added joint with their lines, the same words as the SVD's verdict up to its
    !> residuals.
    subroutine test_chain_sparse_contradiction(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem, problem_dense
        type(ic_options_type) :: options, dense
        type(ic_report_type) :: report
        type(error_type), allocatable :: refused, refused_dense
        real(wp), allocatable :: q(:), u(:), q0(:), u0(:)
        character(len=*), parameter :: said = " are contradictory at position level"
        character(len=:), allocatable :: text, text_dense
        integer :: line, j

        call chain_problem("chain_contradiction.adm", "JOINT/9999, REVOLUTE, I=202, J=10" &
            & // new_line("a") // new_line("a"), problem, q, u, options, error)
        if (allocated(error)) return
        text = link_chain_dataset(links, 0.1_wp, 0.05_wp, "FORMULATION=IDA")
        text = text(:index(text, "ACCGRAV/") - 1)
        line = count([(text(j:j) == new_line("a"), j = 1, len(text))]) + 1
        q0 = q
        u0 = u
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, refused)
        call check(error, allocated(refused), "the contradictory chain is refused")
        if (allocated(error)) return
        call check(error, index(refused%message, said) > 0 .and. index(refused%message, &
            & "JOINT/1 (line ") > 0 .and. index(refused%message, "JOINT/9999 (line " &
            & // to_text(line) // ")") > 0, refused%message)
        if (allocated(error)) return
        call check(error, all(q == q0) .and. all(u == u0), "a refused start is left unchanged")
        if (allocated(error)) return
        call chain_problem("chain_contradiction.adm", "JOINT/9999, REVOLUTE, I=202, J=10" &
            & // new_line("a") // new_line("a"), problem_dense, q, u, dense, error)
        if (allocated(error)) return
        dense%sparse_columns = huge(1)
        call analyse_initial_conditions(problem_dense, 0.0_wp, q, u, dense, report, &
            & refused_dense)
        call check(error, allocated(refused_dense), "the SVD's way refuses it too")
        if (allocated(error)) return
        text = refused%message(:index(refused%message, "; least-squares") - 1)
        text_dense = refused_dense%message(:index(refused_dense%message, "; least-squares") - 1)
        call check(error, text == text_dense, "sparse: " // refused%message // new_line("a") &
            & // "dense: " // refused_dense%message)
    end subroutine test_chain_sparse_contradiction

end module ic_chain
