! SPDX-License-Identifier: MIT
!> The chain of N links (rollcon_link_chain), the second model of the cost benchmark, and the
!> sparse Newton matrix of IDA: the chain reads as one block, starts where it is written and
!> meets its joints; the DAE's pattern (dae_pattern) holds every nonzero of the analytic
!> Newton matrix and keeps O(N) of a chain's entries, and the Newton matrix written over it
!> (dae_sparse_jacobian) is the dense one's bit for bit; IDA with KLU moves the chain and the disks
!> as the dense matrix does; linear_solver = 'auto' picks KLU on large sparse matrices only;
!> the saddle-point system's Schur complement goes sparse (KLU) on a long chain's block only,
!> with the dense path's accelerations; `rollcon bench` prints the per-part scaling table; the
!> memory a run takes per link is flat in the chain's length.
module test_link_chain
    use, intrinsic :: iso_c_binding, only : c_associated
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_files, only : write_text_file, make_folders
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_link_chain, only : link_chain_dataset
    use rollcon_bench_scaling, only : scaling_row_type, measure_scaling
    use rollcon_disk_fleet, only : disk_fleet_dataset
    use rollcon_constraint_blocks, only : constraint_blocks_type
    use rollcon_problem, only : problem_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_speeds_form, only : speeds_form_type
    use rollcon_newton_pattern, only : newton_pattern_type, pattern_of_blocks
    use rollcon_saddle_point, only : saddle_point_type, sparse_schur_rows
    use rollcon_run_settings, only : run_settings_type, linear_auto, linear_dense, &
        & linear_sparse, jacobian_dq
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_dataset_text
    use command_runs, only : rollcon_program, run_rollcon, file_text
    implicit none
    private

    public :: collect_link_chain

    !> Where the tests write their datasets
    character(len=*), parameter :: folder = "build/rollcon-test/link-chain"
    !> The chain's links [m] and start angle from the vertical [rad] (rollcon_link_chain)
    real(wp), parameter :: link = 0.1_wp, start = 60.0_wp*acos(-1.0_wp)/180.0_wp

contains

    subroutine collect_link_chain(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("chain-one-block", test_one_block), &
            & new_unittest("chain-start", test_start), &
            & new_unittest("sparse-schur-as-dense", test_sparse_schur), &
            & new_unittest("pattern-holds-the-jacobian", test_pattern), &
            & new_unittest("sparse-newton-matrix-by-places", test_places), &
            & new_unittest("cvode-sparse-jacobian-as-dense", test_cvode_blocks), &
            & new_unittest("speeds-sparse-jacobian-as-dense", test_speeds_blocks), &
            & new_unittest("ida-klu-same-motion", test_klu_motion), &
            & new_unittest("auto-solver-choice", test_auto), &
            & new_unittest("bench-prints-scaling-table", test_bench_table), &
            & new_unittest("memory-per-link-flat", test_memory_flat)]
    end subroutine collect_link_chain

    !> Write the dataset text as name.adm, run it, keep its history.
    subroutine run_text(name, text, history, error)
        character(len=*), intent(in) :: name, text
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error

        call run_dataset_text(folder, name, text, history, error)
    end subroutine run_text

    !> The problem of a dataset text, set up (its equations, blocks), with its start.
    subroutine problem_of(name, text, problem, q0, u0, error)
        character(len=*), intent(in) :: name, text
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        procedure(ucosub_interface), pointer :: disk
        character(len=:), allocatable :: path

        call make_folders(folder, error)
        if (allocated(error)) return
        path = folder // "/" // name // ".adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
        disk => rolling_disk_ucosub
        call read_adm(path, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, problem, q0, u0, error)
    end subroutine problem_of

    !> Three links: three parts, 15 UCONs (five per REVOLUTE), all of one block holding the
    !> 18 coordinates: each joint shares a part with the next.
    subroutine test_one_block(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(constraint_blocks_type) :: blocks
        real(wp), allocatable :: q0(:), u0(:)
        integer :: j

        call problem_of("chain_blocks", link_chain_dataset(3, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), problem, q0, u0, error)
        if (allocated(error)) return
        call check(error, size(problem%model%parts) == 3 .and. problem%model%nc == 15 &
            & .and. problem%model%nh == 15, "3 parts, 15 position UCONs: " &
            & // to_text(size(problem%model%parts)) // ", " // to_text(problem%model%nc) &
            & // ", " // to_text(problem%model%nh))
        if (allocated(error)) return
        call blocks%init(problem%model)
        call check(error, blocks%count, 1, "blocks")
        if (allocated(error)) return
        call check(error, all(blocks%block_coordinates(1) == [(j, j = 1, 18)]), &
            & "the block holds every coordinate")
    end subroutine test_one_block

    !> The saddle-point solve of a chain of 12 links (one block of 60 rows: sparse, KLU on S's
    !> nonzeros) against the whole dense Schur complement (LAPACK LU, no blocks) at three
    !> generic states: the same accelerations and multipliers, and the same solutions for two
    !> more right-hand sides, to round-off. A chain of 2 links (10 rows) stays dense.
    subroutine test_sparse_schur(error)
        type(error_type), allocatable, intent(out) :: error
        !> Both are backward-stable LU solves (KLU's partial pivoting, LAPACK's) of the same S
        !> in double precision: they differ by about cond(S) eps relative to the solution, and
        !> the chain's S (masses 1 kg, lengths 0.1 m, 12 links) is well conditioned: the
        !> largest relative difference seen is below 1e-13; 1e-10 leaves room and still catches
        !> a wrong entry of S or a missed coupling (differences of order one)
        real(wp), parameter :: tol = 1.0e-10_wp
        type(problem_type), target :: problem, small
        type(saddle_point_type) :: dense
        real(wp), allocatable :: q0(:), u0(:), q(:), u(:), a(:), lambda(:), r1(:, :), r2(:, :), &
            & s1(:, :), s2(:, :)
        real(wp) :: worst
        integer :: n, nc, state, i

        call problem_of("chain_small", link_chain_dataset(2, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), small, q0, u0, error)
        if (allocated(error)) return
        call small%prepare(error)
        if (allocated(error)) return
        call small%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        call check(error, small%eq%saddle%by_blocks .and. small%eq%blocks%most_rows == 10 &
            & .and. .not. any(small%eq%saddle%block_sparse), "2 links (10 rows, fewer than " &
            & // to_text(sparse_schur_rows) // "): the dense path by blocks")
        if (allocated(error)) return
        call problem_of("chain_sparse", link_chain_dataset(12, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), problem, q0, u0, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        n = problem%model%n
        nc = problem%model%nc
        call dense%init(n, nc)
        allocate(r1(n, 2), r2(nc, 2), s1(n, 2), s2(nc, 2))
        worst = 0.0_wp
        do state = 1, 3
            ! a generic state near the start: every coordinate and rate moved
            q = q0 + [(0.05_wp*sin(1.7_wp*i + state), i = 1, n)]
            u = u0 + [(0.8_wp*cos(0.9_wp*i*state), i = 1, n)]
            call problem%accelerations(0.0_wp, q, u, error)
            if (allocated(error)) return
            call check(error, problem%eq%saddle%by_blocks .and. problem%eq%blocks%count == 1 &
                & .and. problem%eq%blocks%most_rows == 60 .and. problem%eq%saddle%block_sparse(1), &
                & "12 links (one block of 60 rows): the sparse path")
            if (allocated(error)) return
            call dense%factor(problem%eq%mass, problem%eq%c, nc, error)
            if (allocated(error)) return
            a = problem%eq%force
            lambda = problem%eq%gamma
            call dense%solve(problem%eq%c, a, lambda, 1, error)
            if (allocated(error)) return
            worst = max(worst, maxval(abs(problem%a - a))/maxval(abs(a)), &
                & maxval(abs(problem%lambda - lambda))/maxval(abs(lambda)))
            do i = 1, n
                r1(i, :) = [0.3_wp*i - 1.0_wp, sin(real(i*state, wp))]
            end do
            do i = 1, nc
                r2(i, :) = [0.2_wp*i, cos(real(i + state, wp))]
            end do
            s1 = r1
            s2 = r2
            call problem%eq%saddle%solve(problem%eq%c, r1, r2, 2, error)
            if (allocated(error)) return
            call dense%solve(problem%eq%c, s1, s2, 2, error)
            if (allocated(error)) return
            worst = max(worst, maxval(abs(r1 - s1))/maxval(abs(s1)), &
                & maxval(abs(r2 - s2))/maxval(abs(s2)))
        end do
        call check(error, worst < tol, "sparse and dense saddle-point solves differ by " &
            & // to_text(worst) // " (relative)")
        if (allocated(error)) return
        ! the KLU factors live outside Fortran's memory: release frees them (a study's cases)
        call check(error, c_associated(problem%eq%saddle%sparse(1)%handle), "no KLU factors held")
        if (allocated(error)) return
        call problem%release()
        call check(error, .not. c_associated(problem%eq%saddle%sparse(1)%handle), &
            & "release left the KLU factors held")
    end subroutine test_sparse_schur

    !> The chain starts straight, 60 degrees from the vertical, at rest: link k's centre at
    !> (k - 1/2) l (-sin 60, 0, -cos 60) in the first row, and the run of 0.1 s keeps the
    !> hinges: the first link's centre l/2 from the ground hinge at every row.
    subroutine test_start(error)
        type(error_type), allocatable, intent(out) :: error
        !> The start is the dataset's numbers as written (17 digits) through the markers'
        !> rotations: round-off of a few ulp of 0.1 m
        real(wp), parameter :: tol_start = 1.0e-14_wp
        !> IDA holds the position UCONs directly (GGL): their residual is the Newton
        !> iteration's (the summary's largest on the 3-link chain over 1 s at rtol 1e-8:
        !> 5.9e-11 m), and the centre is l/2 from the hinge when they hold
        real(wp), parameter :: tol_hinge = 1.0e-8_wp
        type(history_type) :: history
        real(wp) :: largest
        integer :: k

        call run_text("chain_start", link_chain_dataset(3, 0.1_wp, 0.01_wp, "ERROR=1e-8"), &
            & history, error)
        if (allocated(error)) return
        do k = 1, 3
            call check(error, history%rows(1 + 12*(k - 1) + 1, 1), -(k - 0.5_wp)*link &
                & *sin(start), "link " // to_text(k) // "'s X at the start, m", &
                & abs_tol=tol_start)
            if (allocated(error)) return
            call check(error, history%rows(1 + 12*(k - 1) + 3, 1), -(k - 0.5_wp)*link &
                & *cos(start), "link " // to_text(k) // "'s Z at the start, m", &
                & abs_tol=tol_start)
            if (allocated(error)) return
        end do
        largest = maxval(abs(hypot(history%rows(2, :history%count), &
            & history%rows(4, :history%count)) - 0.5_wp*link))
        call check(error, largest <= tol_hinge, "the first link's centre from the hinge " &
            & // "differs from l/2 by " // to_text(largest) // " m")
        if (allocated(error)) return
        call check(error, maxval(abs(history%rows(2, :history%count) &
            & - history%rows(2, 1))) > 1.0e-3_wp, "the chain falls")
    end subroutine test_start

    !> The DAE's pattern holds every entry of the analytic Newton matrix that is not zero, at a
    !> state with every velocity and multiplier nonzero, on chains of 8 and 16 links (one block),
    !> on 3 disks (three blocks) and on data/bicycle.adm, and keeps no more than the blocks; a
    !> chain's grows as N (a band: each part meets its two neighbours), where its block grows as
    !> N^2; gathered from the elements' blocks, it keeps exactly the entries the n x n relation
    !> of the same blocks kept; the Newton matrix written over it is the dense one's.
    subroutine test_pattern(error)
        type(error_type), allocatable, intent(out) :: error
        !> Entries of the chain of 16 over the chain of 8's: 2 for a band (the ground hinge's
        !> fewer entries make it a little more), 4 for a full block
        real(wp), parameter :: most_growth = 2.2_wp
        !> Entries of the chain's pattern per link: 504 for a link between two (a hinge's two
        !> parts' 6 by 6 blocks, its five UCONs over 12 coordinates), fewer at the ground
        integer, parameter :: most_per_link = 504
        !> The entries of the chain of 8's pattern when it was gathered n x n from the same
        !> blocks (what a pattern gathered otherwise must keep, no more, no fewer)
        integer, parameter :: entries_of_eight = 3800
        integer :: eight, sixteen, disks, bicycle

        call check_pattern("chain_pattern_8", link_chain_dataset(8, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), eight, error)
        if (allocated(error)) return
        call check_pattern("chain_pattern_16", link_chain_dataset(16, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), sixteen, error)
        if (allocated(error)) return
        call check(error, real(sixteen, wp) <= most_growth*real(eight, wp), "the chain's " &
            & // "pattern: " // to_text(eight) // " entries at 8 links, " // to_text(sixteen) &
            & // " at 16")
        if (allocated(error)) return
        ! the entries the Newton matrix is written in, not every state of neighbouring parts by
        ! every other (which kept 13288 at 8 links, 1661 a link, and made KLU's factorisations
        ! of a long chain about twice as dear): 3800 at 8 links, 475 a link
        call check(error, eight <= most_per_link*8, "the chain's pattern at 8 links keeps " &
            & // to_text(eight) // " entries, at most " // to_text(most_per_link) // " a link")
        if (allocated(error)) return
        ! gathered from the elements' blocks, the pattern is the one the n x n relation of
        ! the same blocks kept (3800 entries at 8 links)
        call check(error, eight, entries_of_eight, "the chain's pattern at 8 links")
        if (allocated(error)) return
        call check_pattern("bicycle_pattern", file_text("data/bicycle.adm"), bicycle, error)
        if (allocated(error)) return
        call check_pattern("fleet_pattern", disk_fleet_dataset(3, 0.5_wp, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), disks, error)
    end subroutine test_pattern

    !> The pattern of the dataset's DAE holds the Newton matrix's nonzeros and keeps no more
    !> than its blocks; the Newton matrix written over the pattern (dae_sparse_jacobian) is the
    !> dense one's, bit for bit; its entries.
    subroutine check_pattern(name, text, entries, error)
        character(len=*), intent(in) :: name, text
        integer, intent(out) :: entries
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(dae_form_type) :: dae
        type(newton_pattern_type) :: pattern, blocks
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:), matrix(:, :), values(:)
        logical, allocatable :: kept(:, :)
        integer :: n, i, j, e, ierr, missed

        entries = 0
        call problem_of(name, text, problem, q0, u0, error)
        if (allocated(error)) return
        call dae%init(problem)
        n = dae%state_size()
        allocate(y(n), yp(n), matrix(n, n), source=0.0_wp)
        allocate(kept(n, n), source=.false.)
        ! every velocity, multiplier and acceleration nonzero: the entries zero at rest appear
        y(:size(q0)) = q0
        y(size(q0) + 1:) = [(0.1_wp*sin(real(i, wp)), i = 1, n - size(q0))]
        yp = [(0.2_wp*cos(real(i, wp)), i = 1, n)]
        ierr = dae%dae_jacobian(0.0_wp, 1.0e3_wp, y, yp, matrix)
        call check(error, ierr, 0, name // ": the Newton matrix")
        if (allocated(error)) return
        call dae%dae_pattern(n, pattern)
        do j = 1, n
            do e = pattern%starts(j) + 1, pattern%starts(j + 1)
                kept(pattern%rows(e) + 1, j) = .true.
            end do
        end do
        missed = count(matrix /= 0.0_wp .and. .not. kept)
        call check(error, missed, 0, name // ": nonzero entries outside the pattern")
        if (allocated(error)) return
        ! the same matrix written straight over the pattern (IDA's sparse path, no n x n
        ! array): every entry the dense one's, bit for bit (the same operations)
        allocate(values(pattern%entries()))
        ierr = dae%dae_sparse_jacobian(0.0_wp, 1.0e3_wp, y, yp, pattern%starts, pattern%rows, &
            & values)
        call check(error, ierr, 0, name // ": the sparse Newton matrix")
        if (allocated(error)) return
        missed = 0
        do j = 1, n
            do e = pattern%starts(j) + 1, pattern%starts(j + 1)
                if (.not. same_bits(values(e), matrix(pattern%rows(e) + 1, j))) &
                    & missed = missed + 1
            end do
        end do
        call check(error, missed, 0, name // ": entries of the sparse Newton matrix not the " &
            & // "dense one's")
        if (allocated(error)) return
        blocks = pattern_of_blocks(dae%state_blocks(n))
        entries = pattern%entries()
        call check(error, entries <= blocks%entries(), name // ": the pattern keeps " &
            & // to_text(entries) // " of " // to_text(n*n) // " entries, the blocks " &
            & // to_text(blocks%entries()))
    end subroutine check_pattern

    !> IDA's sparse Newton matrix written again by the places of its last evaluation's writes
    !> (rollcon_dae's newton_places_type, held by the DAE form): at a second state and cj, on
    !> data/bicycle.adm and on 3 disks, every entry the dense matrix's, bit for bit; over a
    !> pattern that lacks an entry the matrix writes, the places are checked against that
    !> pattern: the error names the entry; over the whole pattern again, the dense one's.
    subroutine test_places(error)
        type(error_type), allocatable, intent(out) :: error

        call check_places("bicycle_places", file_text("data/bicycle.adm"), error)
        if (allocated(error)) return
        call check_places("fleet_places", disk_fleet_dataset(3, 0.5_wp, 0.1_wp, 0.05_wp, &
            & "FORMULATION=IDA"), error)
    end subroutine test_places

    !> test_places on one dataset.
    subroutine check_places(name, text, error)
        character(len=*), intent(in) :: name, text
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(dae_form_type) :: dae
        type(newton_pattern_type) :: pattern
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:), matrix(:, :), values(:)
        integer, allocatable :: starts(:), rows(:)
        integer :: n, nq, i, e, ierr, pass, left_out
        character(len=:), allocatable :: expected

        call problem_of(name, text, problem, q0, u0, error)
        if (allocated(error)) return
        call dae%init(problem)
        n = dae%state_size()
        nq = size(q0)
        call dae%dae_pattern(n, pattern)
        allocate(y(n), yp(n), matrix(n, n), values(pattern%entries()))
        ! the first pass learns the places, the second writes by them, at another state
        do pass = 1, 2
            y(:nq) = q0
            y(nq + 1:) = [(0.1_wp*pass*sin(real(i*pass, wp)), i = 1, n - nq)]
            yp = [(0.2_wp*cos(real(i + pass, wp)), i = 1, n)]
            call compare(1.0e3_wp*pass, pattern%starts, pattern%rows, "pass " &
                & // to_text(pass))
            if (allocated(error)) return
        end do
        ! the pattern without entry (nq + 1, 1) (part 1's first momentum row by its first
        ! coordinate: its block's), which the matrix writes
        left_out = 0
        do e = pattern%starts(1) + 1, pattern%starts(2)
            if (pattern%rows(e) == nq) left_out = e
        end do
        call check(error, left_out > 0, name // ": the pattern keeps entry (" &
            & // to_text(nq + 1) // ", 1)")
        if (allocated(error)) return
        rows = [pattern%rows(:left_out - 1), pattern%rows(left_out + 1:)]
        starts = pattern%starts
        starts(2:) = starts(2:) - 1
        deallocate(values)
        allocate(values(size(rows)))
        ierr = dae%dae_sparse_jacobian(0.0_wp, 1.0e3_wp, y, yp, starts, rows, values)
        expected = "the DAE's Newton matrix has entry (" // to_text(nq + 1) // ", 1) outside " &
            & // "its sparse pattern"
        call check(error, ierr /= 0 .and. index(dae%failure_text(), expected) > 0, name &
            & // ": over a pattern without an entry, '" // expected // "' expected, ierr " &
            & // to_text(ierr) // ", '" // dae%failure_text() // "'")
        if (allocated(error)) return
        deallocate(values)
        allocate(values(pattern%entries()))
        call compare(3.0e3_wp, pattern%starts, pattern%rows, "the whole pattern again")

    contains

        !> The sparse Newton matrix at (y, yp, cj) over (starts, rows) against the dense one,
        !> bit for bit.
        subroutine compare(cj, starts, rows, what)
            real(wp), intent(in) :: cj
            integer, intent(in) :: starts(:), rows(:)
            character(len=*), intent(in) :: what
            integer :: j, differ

            ierr = dae%dae_jacobian(0.0_wp, cj, y, yp, matrix)
            if (ierr == 0) ierr = dae%dae_sparse_jacobian(0.0_wp, cj, y, yp, starts, rows, &
                & values)
            call check(error, ierr, 0, name // ", " // what // ": the Newton matrices")
            if (allocated(error)) return
            differ = 0
            do j = 1, n
                do e = starts(j) + 1, starts(j + 1)
                    if (.not. same_bits(values(e), matrix(rows(e) + 1, j))) differ = differ + 1
                end do
            end do
            call check(error, differ, 0, name // ", " // what // ": entries of the sparse " &
                & // "Newton matrix not the dense one's")
        end subroutine compare
    end subroutine check_places

    !> CVODE's sparse Newton matrix of the ODE form, formed block by block (ode_sparse_jacobian:
    !> the equations' ode_jacobian_blocks, no n x 2n array) over the pattern of its state
    !> blocks, against the dense one (ode_jacobian) at a generic state: every entry the same,
    !> bit for bit (the same operations in the same order: the blocks leave out only exact
    !> zeros), and the dense matrix zero outside the pattern. On 3 disks, two of them joined by
    !> a SPRINGDAMPER (a state block of two constraints' blocks beside one of one), a chain of
    !> 3 links (one block, S dense) and of 9 (45 rows: S sparse, KLU).
    subroutine test_cvode_blocks(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: cvode = "FORMULATION=CVODE, METHOD=ADAMS, " &
            & // "DRIFT=BAUMGARTE, SOLVER=SPARSE"
        character(len=:), allocatable :: disks
        integer :: at

        disks = disk_fleet_dataset(3, 0.5_wp, 0.2_wp, 0.1_wp, cvode)
        at = index(disks, "ACCGRAV/")
        disks = disks(:at - 1) // "SPRINGDAMPER/1, TRANSLATIONAL, I = 20, J = 30, K = 200, " &
            & // "C = 4, LENGTH = 0.5" // new_line("a") // disks(at:)
        call check_ode_blocks("fleet_spring", disks, 2, error)
        if (allocated(error)) return
        call check_ode_blocks("chain_ode_3", link_chain_dataset(3, 0.1_wp, 0.05_wp, cvode), 1, &
            & error)
        if (allocated(error)) return
        call check_ode_blocks("chain_ode_9", link_chain_dataset(9, 0.1_wp, 0.05_wp, cvode), 1, &
            & error)
    end subroutine test_cvode_blocks

    !> The ODE form's sparse Newton matrix against its dense one (test_cvode_blocks), on a
    !> dataset whose states fall in `blocks` blocks.
    subroutine check_ode_blocks(name, text, blocks, error)
        character(len=*), intent(in) :: name, text
        integer, intent(in) :: blocks
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(newton_pattern_type) :: pattern
        real(wp), allocatable :: q0(:), u0(:), y(:), matrix(:, :), values(:)
        logical, allocatable :: kept(:, :)
        integer, allocatable :: state_blocks(:)
        integer :: n, i, j, e, ierr, missed

        call problem_of(name, text, problem, q0, u0, error)
        if (allocated(error)) return
        call ode%init(problem)
        n = ode%state_size()
        state_blocks = ode%state_blocks(n)
        call check(error, size(unique(state_blocks)), blocks, name // ": state blocks")
        if (allocated(error)) return
        ! every rate nonzero and the coordinates moved off the start: a generic state
        allocate(y(n), matrix(n, n), kept(n, n))
        y(:size(q0)) = q0 + [(1.0e-3_wp*cos(real(i, wp)), i = 1, size(q0))]
        y(size(q0) + 1:) = u0 + [(0.1_wp*sin(real(i, wp)), i = 1, size(u0))]
        ierr = ode%ode_jacobian(0.0_wp, y, matrix)
        call check(error, ierr, 0, name // ": the dense Newton matrix " // ode%failure_text())
        if (allocated(error)) return
        pattern = pattern_of_blocks(state_blocks)
        allocate(values(pattern%entries()))
        values = huge(1.0_wp)
        ierr = ode%ode_sparse_jacobian(0.0_wp, y, pattern%starts, pattern%rows, values)
        call check(error, ierr, 0, name // ": the sparse Newton matrix " // ode%failure_text())
        if (allocated(error)) return
        call check_as_dense(name, pattern, values, matrix, kept, error)
        if (allocated(error)) return
        ! no n x 2n right-hand sides held for it (the dense matrix's first evaluation sized
        ! them: a form whose first is sparse never does, cvode-sparse-holds-no-square)
        call check(error, allocated(problem%eq%work%block_top) .and. &
            & size(problem%eq%work%block_top, 1) <= 6*maxval(block_sizes(state_blocks)), &
            & name // ": the blocks' right-hand sides larger than the largest block")
    end subroutine check_ode_blocks

    !> The independent speeds' sparse Newton matrix (ode_sparse_jacobian: rollcon_independent_
    !> speeds' jacobian_blocks, no n_y x n_y array) against their dense one at a generic state,
    !> as test_cvode_blocks: bit for bit over the state blocks' pattern, zero outside it; on
    !> the same three models in FORMULATION=MAGGI.
    subroutine test_speeds_blocks(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: maggi = "FORMULATION=MAGGI, METHOD=ADAMS, " &
            & // "DRIFT=BAUMGARTE, SOLVER=SPARSE"
        character(len=:), allocatable :: disks
        integer :: at

        disks = disk_fleet_dataset(3, 0.5_wp, 0.2_wp, 0.1_wp, maggi)
        at = index(disks, "ACCGRAV/")
        disks = disks(:at - 1) // "SPRINGDAMPER/1, TRANSLATIONAL, I = 20, J = 30, K = 200, " &
            & // "C = 4, LENGTH = 0.5" // new_line("a") // disks(at:)
        call check_speeds_blocks("fleet_spring_maggi", disks, 2, error)
        if (allocated(error)) return
        call check_speeds_blocks("chain_maggi_3", link_chain_dataset(3, 0.1_wp, 0.05_wp, maggi), &
            & 1, error)
        if (allocated(error)) return
        call check_speeds_blocks("chain_maggi_9", link_chain_dataset(9, 0.1_wp, 0.05_wp, maggi), &
            & 1, error)
    end subroutine test_speeds_blocks

    !> The independent speeds' sparse Newton matrix against their dense one
    !> (test_speeds_blocks), on a dataset whose states fall in `blocks` blocks.
    subroutine check_speeds_blocks(name, text, blocks, error)
        character(len=*), intent(in) :: name, text
        integer, intent(in) :: blocks
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(speeds_form_type) :: speeds
        type(newton_pattern_type) :: pattern
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:), matrix(:, :), values(:)
        logical, allocatable :: kept(:, :)
        integer, allocatable :: state_blocks(:)
        integer :: n, i, j, e, ierr, missed

        call problem_of(name, text, problem, q0, u0, error)
        if (.not. allocated(error)) call problem%prepare(error)
        if (allocated(error)) return
        call speeds%init(problem)
        call problem%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        n = speeds%state_size()
        allocate(y(n), yp(n), matrix(n, n), kept(n, n))
        call speeds%pack_state(q0, u0, y, yp)
        state_blocks = speeds%state_blocks(n)
        call check(error, size(unique(state_blocks)), blocks, name // ": state blocks")
        if (allocated(error)) return
        ! the coordinates moved off the start and every speed changed: a generic state
        y(:size(q0)) = y(:size(q0)) + [(1.0e-3_wp*cos(real(i, wp)), i = 1, size(q0))]
        y(size(q0) + 1:) = y(size(q0) + 1:) + [(0.1_wp*sin(real(i, wp)), i = 1, n - size(q0))]
        ierr = speeds%ode_jacobian(0.0_wp, y, matrix)
        call check(error, ierr, 0, name // ": the dense Newton matrix " // speeds%failure_text())
        if (allocated(error)) return
        pattern = pattern_of_blocks(state_blocks)
        allocate(values(pattern%entries()))
        values = huge(1.0_wp)
        ierr = speeds%ode_sparse_jacobian(0.0_wp, y, pattern%starts, pattern%rows, values)
        call check(error, ierr, 0, name // ": the sparse Newton matrix " &
            & // speeds%failure_text())
        if (allocated(error)) return
        call check_as_dense(name, pattern, values, matrix, kept, error)
        if (allocated(error)) return
        call check(error, .not. allocated(speeds%dense_jacobian), name // ": the sparse " &
            & // "matrix went through the dense one")
    end subroutine check_speeds_blocks

    !> The distinct values of v.
    pure function unique(v) result(kept)
        integer, intent(in) :: v(:)
        integer, allocatable :: kept(:)
        integer :: i

        allocate(kept(0))
        do i = 1, size(v)
            if (.not. any(kept == v(i))) kept = [kept, v(i)]
        end do
    end function unique

    !> Each block's parts (a block's states: 12 per part, the coordinates and their rates).
    pure function block_sizes(v) result(sizes)
        integer, intent(in) :: v(:)
        integer, allocatable :: sizes(:)
        integer, allocatable :: ids(:)
        integer :: i

        ids = unique(v)
        allocate(sizes(size(ids)))
        do i = 1, size(ids)
            sizes(i) = count(v == ids(i))/12
        end do
    end function block_sizes

    !> IDA with the sparse Newton matrix (KLU) against the dense one, on a chain of 4 links
    !> over 0.2 s and on 2 disks over 0.3 s: the same motion. Only the Newton matrix's LU
    !> differs (its sums in another order), so the runs differ by where a step's tests fall:
    !> measured 3.2e-8 m or rad (chain) and 8.7e-12 (disks), the largest over every
    !> coordinate and row, at rtol 1e-8. Ten times those, rounded up.
    subroutine test_klu_motion(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tol_chain = 4.0e-7_wp, tol_disks = 1.0e-10_wp
        type(history_type) :: dense, sparse
        character(len=*), parameter :: ida = "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10, SOLVER="

        call run_text("chain_dense", link_chain_dataset(4, 0.2_wp, 0.01_wp, ida // "DENSE"), &
            & dense, error)
        if (allocated(error)) return
        call run_text("chain_sparse", link_chain_dataset(4, 0.2_wp, 0.01_wp, ida // "SPARSE"), &
            & sparse, error)
        if (allocated(error)) return
        call compare("chain of 4", dense, sparse, 4, tol_chain, error)
        if (allocated(error)) return
        call run_text("fleet_dense", disk_fleet_dataset(2, 0.5_wp, 0.3_wp, 0.05_wp, &
            & ida // "DENSE"), dense, error)
        if (allocated(error)) return
        call run_text("fleet_sparse", disk_fleet_dataset(2, 0.5_wp, 0.3_wp, 0.05_wp, &
            & ida // "SPARSE"), sparse, error)
        if (allocated(error)) return
        call compare("2 disks", dense, sparse, 2, tol_disks, error)
    end subroutine test_klu_motion

    !> Every part's six coordinates of two runs, row by row.
    subroutine compare(what, one, other, parts, tolerance, error)
        character(len=*), intent(in) :: what
        type(history_type), intent(in) :: one, other
        integer, intent(in) :: parts
        real(wp), intent(in) :: tolerance
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: largest
        integer :: p, c

        call check(error, other%count, one%count, what // ": rows")
        if (allocated(error)) return
        largest = 0.0_wp
        do p = 1, parts
            do c = 1, 6
                largest = max(largest, maxval(abs(one%rows(1 + 12*(p - 1) + c, :one%count) &
                    & - other%rows(1 + 12*(p - 1) + c, :one%count))))
            end do
        end do
        call check(error, largest <= tolerance, what // ": KLU and dense differ by " &
            & // to_text(largest) // " (m or rad)")
    end subroutine compare

    !> linear_solver = 'auto' (the default) keeps the dense matrix on a disk (15 states) and on
    !> two parts (30), on the chain of 64 links on CVODE (768 states in one block: every entry
    !> kept) and on a matrix 0.6 full (the bicycle's DAE: four parts, three of the six pairs
    !> apart); it takes KLU from 32 states on a sparse matrix: 64 disks' DAE (960 states in
    !> blocks of 15) and the chain's (1408 states, about 1/30 full); 'dense' and 'sparse' are
    !> obeyed, and difference quotients are always dense.
    subroutine test_auto(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_settings_type) :: settings

        call check(error, settings%linear_solver == linear_auto, "the default is 'auto'")
        if (allocated(error)) return
        call check(error, .not. settings%sparse_newton(15, 225) .and. &
            & .not. settings%sparse_newton(30, 2*15**2) .and. &
            & .not. settings%sparse_newton(768, 768**2) .and. &
            & .not. settings%sparse_newton(84, 85*84**2/100) .and. &
            & settings%sparse_newton(32, 32**2/2) .and. &
            & settings%sparse_newton(86, 5476) .and. &
            & settings%sparse_newton(960, 64*15**2) .and. &
            & settings%sparse_newton(1408, 1408**2/30), &
            & "auto: dense on small or full matrices, KLU on large sparse ones")
        if (allocated(error)) return
        settings%linear_solver = linear_dense
        call check(error, .not. settings%sparse_newton(960, 64*15**2), "'dense' obeyed")
        if (allocated(error)) return
        settings%linear_solver = linear_sparse
        call check(error, settings%sparse_newton(15, 225), "'sparse' obeyed")
        if (allocated(error)) return
        settings%jacobian = jacobian_dq
        call check(error, .not. settings%sparse_newton(15, 225), "dq Jacobians are dense")
    end subroutine test_auto

    !> `rollcon bench --quick` ends with the per-part scaling table: its header, and one line
    !> for each of the default on the disks and on the chain at N = 1 and 2, each completed
    !> with a ratio of exactly 1 at N = 1 and a start-up time in ms (the table's shape; never
    !> its times).
    subroutine test_bench_table(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: scratch = "build/test_link_chain_bench"
        character(len=:), allocatable :: program, out, line
        character(len=*), parameter :: expected(4) = [character(len=20) :: &
            & "disks   default", "disks   default", "chain   chain-defaul", "chain   chain-defaul"]
        integer, parameter :: parts(4) = [1, 2, 1, 2]
        integer :: status, at, k, next, n
        character(len=:), allocatable :: figures
        real(wp) :: per_step, ratio, startup

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folders(scratch, error)
        if (allocated(error)) return
        call run_rollcon(program, "bench --quick --end-time 0.05 --output " // scratch, &
            & scratch // "/bench.out", scratch // "/bench.err", status)
        out = file_text(scratch // "/bench.out")
        at = index(out, "  model   method                            N  states   steps" &
            & // "  us/step/part  ratio to N = 1  start-up [ms]")
        call check(error, status == 0 .and. at > 0, "exit status " // to_text(status) &
            & // "; the table's header in stdout: " // out // file_text(scratch // "/bench.err"))
        if (allocated(error)) return
        at = at + index(out(at:), new_line("a"))
        do k = 1, 4
            next = index(out(at:), new_line("a"))
            call check(error, next > 0, "row " // to_text(k) // " of the table")
            if (allocated(error)) return
            line = out(at:at + next - 2)
            at = at + next
            read(line(41:45), *) n
            figures = line(62:)
            read(figures, *) per_step, ratio, startup
            call check(error, index(line, trim(expected(k))) == 3 .and. n == parts(k) .and. &
                & index(line, "completed") > 0 .and. (k == 2 .or. k == 4 .or. &
                & abs(ratio - 1.0_wp) < 1.0e-12_wp) .and. per_step > 0.0_wp .and. &
                & startup >= 0.0_wp, &
                & "row " // to_text(k) // ": " // line)
            if (allocated(error)) return
        end do
    end subroutine test_bench_table

    !> The two numbers have the same bits (a +0 and a -0 differ).
    pure logical function same_bits(a, b)
        real(wp), intent(in) :: a, b

        same_bits = transfer(a, 1_int64) == transfer(b, 1_int64)
    end function same_bits

    !> What a run of the chain takes per link is flat (`bench scaling`'s measure: the run's peak
    !> resident memory over what the process held before it, per link, the heap's free memory
    !> returned first), on the default (IDA, KLU at this size) from 128 to 512 links. Measured
    !> (release build, 2026-11-30): 97 kB a link at 128, 98 at 256, 83 at 640; a storage of
    !> 30 N^2 reals (C when it was dense, nc x n) adds 240 N bytes a link, 31 kB at 128 and
    !> 123 at 512, so 512's figure would be 1.7 times 128's; any array of nc x n or n x n
    !> grows at least so. 1.3 times lets the per-run overhead and the allocator's rounding vary
    !> and catches such a term. Memory does not depend on the machine's load.
    subroutine test_memory_flat(error)
        type(error_type), allocatable, intent(out) :: error
        type(scaling_row_type), allocatable :: rows(:)

        call make_folders(folder // "/memory", error)
        if (allocated(error)) return
        call measure_scaling(folder // "/memory", [128, 512], 0.2_wp, rows, error, &
            & only=[character(len=30) :: "chain-default"])
        if (allocated(error)) return
        call check(error, size(rows) == 2, "two runs measured, got " // to_text(size(rows)))
        if (allocated(error)) return
        call check(error, rows(1)%memory_per_part > 0.0_wp .and. rows(2)%memory_per_part > &
            & 0.0_wp .and. rows(2)%memory_per_part <= 1.3_wp*rows(1)%memory_per_part, &
            & "memory per link " // to_text(rows(1)%memory_per_part) // " kB at 128 links, " &
            & // to_text(rows(2)%memory_per_part) // " kB at 512")
        if (allocated(error)) return
        call check(error, rows(1)%status == "completed" .and. rows(2)%status == "completed", &
            & "the chains' runs: " // rows(1)%status // "; " // rows(2)%status)
    end subroutine test_memory_flat

    !> A sparse Newton matrix (values over pattern, compressed columns, 0-based) against the
    !> dense one: each entry its dense twin bit for bit, no nonzero of the dense matrix outside
    !> the pattern; kept (n x n) marks the pattern's places.
    subroutine check_as_dense(name, pattern, values, matrix, kept, error)
        character(len=*), intent(in) :: name
        type(newton_pattern_type), intent(in) :: pattern
        real(wp), intent(in) :: values(:), matrix(:, :)
        logical, intent(out) :: kept(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer :: j, e, missed

        kept = .false.
        missed = 0
        do j = 1, size(matrix, 2)
            do e = pattern%starts(j) + 1, pattern%starts(j + 1)
                kept(pattern%rows(e) + 1, j) = .true.
                if (.not. same_bits(values(e), matrix(pattern%rows(e) + 1, j))) &
                    & missed = missed + 1
            end do
        end do
        call check(error, missed, 0, name // ": entries of the sparse Newton matrix not the " &
            & // "dense one's (of " // to_text(pattern%entries()) // ")")
        if (allocated(error)) return
        call check(error, count(matrix /= 0.0_wp .and. .not. kept), 0, name &
            & // ": nonzero entries of the dense matrix outside the blocks")
    end subroutine check_as_dense

end module test_link_chain
