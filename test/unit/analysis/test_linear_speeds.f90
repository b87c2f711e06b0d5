! SPDX-License-Identifier: MIT
!> Tests of the eigenvalues against speed (src/analysis/rollcon_linear_speeds.f90,
!> docs/linear.md): structural zeros struck out of a matrix built by hand, and the upright
!> rolling disk's change of stability at the critical speed of docs/design.md §5 found by the
!> sweep from a grid, for the velocity-level and the position-level height.
module test_linear_speeds
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type, &
        & structural_zeros, kept_eigenvalues
    use rollcon_linear_job, only : linear_speeds_job
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_linear_speeds

    !> data/coin.adm's disk (as data/disk_height.adm's): m = 7800 pi R^2 h, A = m (3 R^2 +
    !> h^2)/12, C = m R^2/2 with R = 0.1 m, h = 0.003 m, as the dataset writes them
    real(wp), parameter :: mass = 0.73513268094001172_wp, radius = 0.1_wp, &
        & inertia_a = 1.8383830518607345e-3_wp, inertia_c = 3.6756634047000595e-3_wp, &
        & gravity = 9.81_wp
    !> The critical speed is bisected to 1e-9 m/s (speed_tolerance), and the eigenvalues
    !> near it are accurate to about 1e-10 relative (docs/linear.md): 1e-8 relative is what
    !> the issue asks and what is met with a margin of ten
    real(wp), parameter :: tol_critical = 1.0e-8_wp
    !> Eigenvalues of a matrix given exactly, by LAPACK: round-off only
    real(wp), parameter :: tol_exact = 1.0e-12_wp

contains

    subroutine collect_linear_speeds(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("structural-zeros-by-hand", test_by_hand), &
            & new_unittest("critical-speed-coin", test_critical_coin), &
            & new_unittest("critical-speed-position-height", test_critical_height), &
            & new_unittest("no-change-above-critical", test_no_change)]
    end subroutine collect_linear_speeds

    !> A 5 x 5 matrix with a zero column (index 1: a cyclic coordinate), a zero row (index 2:
    !> a conserved speed) and a row that is zero once column 2 is struck (index 5): 3 struck,
    !> and the kept 2 x 2 block [[0, 1], [-4, -1]] has the eigenvalues -1/2 +- i sqrt(15)/2
    !> (the whole matrix is block triangular: these and three zeros).
    subroutine test_by_hand(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: a(5, 5)
        logical, allocatable :: struck(:)
        real(wp), allocatable :: re(:), im(:)

        a = 0.0_wp
        a(3, 4) = 1.0_wp
        a(4, 3) = -4.0_wp
        a(4, 4) = -1.0_wp
        a(1, 5) = 2.0_wp
        a(5, 2) = 3.0_wp
        a(3, 5) = 7.0_wp
        struck = structural_zeros(a)
        call check(error, all(struck .eqv. [.true., .true., .false., .false., .true.]), &
            & "struck: " // merge("T", "F", struck(1)) // merge("T", "F", struck(2)) &
            & // merge("T", "F", struck(3)) // merge("T", "F", struck(4)) &
            & // merge("T", "F", struck(5)))
        if (allocated(error)) return
        call kept_eigenvalues(a, struck, 0, re, im, error)
        if (allocated(error)) return
        call check(error, size(re) == 2, "kept: " // to_text(size(re)))
        if (allocated(error)) return
        call check(error, maxval(abs(re + 0.5_wp)) + abs(im(1) - sqrt(15.0_wp)/2.0_wp) &
            & + abs(im(2) + sqrt(15.0_wp)/2.0_wp), 0.0_wp, "the kept eigenvalues [1/s]", &
            & abs_tol=tol_exact)
    end subroutine test_by_hand

    !> v_c^2 = m g R^3 A / (C (C + m R^2)) (docs/design.md §5) [m/s].
    pure real(wp) function critical_speed()
        critical_speed = sqrt(mass*gravity*radius**3*inertia_a/(inertia_c*(inertia_c &
            & + mass*radius**2)))
    end function critical_speed

    !> The sweep of a dataset over a grid of speeds.
    subroutine sweep(path, speeds, table, changes, error)
        character(len=*), intent(in) :: path
        real(wp), intent(in) :: speeds(:)
        type(speed_table_type), intent(out) :: table
        type(stability_change_type), allocatable, intent(out) :: changes(:)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        character(len=:), allocatable :: report

        call load_job(path, job, error)
        if (allocated(error)) return
        call linear_speeds_job(job, speeds, table, changes, report, error)
    end subroutine sweep

    !> One change between a grid's speeds, at v_c, the disk stable above it, found as a real
    !> pair (the disk falls over: a divergence); two eigenvalues kept, +-sqrt(s) of the closed
    !> form lambda (lambda^2 - s) (docs/linear.md): of the nine (eight) states the columns of
    !> X, Y, (Z,) psi, phi and the spin rate's row are struck, and the first integral of the
    !> heading rate, the zero of lambda (lambda^2 - s), is deflated.
    subroutine check_critical(path, error)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        type(speed_table_type) :: table
        type(stability_change_type), allocatable :: changes(:)
        integer :: k

        call sweep(path, [(0.1_wp*k, k = 0, 10)], table, changes, error)
        if (allocated(error)) return
        call check(error, size(changes) == 1, path // ": " // to_text(size(changes)) &
            & // " changes of stability between 0 and 1 m/s, expected 1")
        if (allocated(error)) return
        call check(error, changes(1)%speed, critical_speed(), path // ": critical speed " &
            & // "[m/s]", rel_tol=tol_critical)
        if (allocated(error)) return
        call check(error, changes(1)%stable_above .and. .not. changes(1)%oscillatory, path &
            & // ": expected stable above, a real pair")
        if (allocated(error)) return
        call check(error, size(table%real_part, 1) == 2 .and. table%deflations == 1, path &
            & // ": kept " // to_text(size(table%real_part, 1)) // " eigenvalues after " &
            & // to_text(table%deflations) // " deflations, expected 2 after 1")
    end subroutine check_critical

    !> data/coin.adm: the height at velocity level.
    subroutine test_critical_coin(error)
        type(error_type), allocatable, intent(out) :: error

        call check_critical("data/coin.adm", error)
    end subroutine test_critical_coin

    !> data/disk_height.adm: the height a position UCON.
    subroutine test_critical_height(error)
        type(error_type), allocatable, intent(out) :: error

        call check_critical("data/disk_height.adm", error)
    end subroutine test_critical_height

    !> Above v_c the upright disk is conservative: its wobble is an imaginary pair whose
    !> computed real part is the differences' error, which must not be taken for a change of
    !> stability on a fine grid.
    subroutine test_no_change(error)
        type(error_type), allocatable, intent(out) :: error
        type(speed_table_type) :: table
        type(stability_change_type), allocatable :: changes(:)
        integer :: k

        call sweep("data/coin.adm", [(0.6_wp + 0.02_wp*k, k = 0, 70)], table, changes, error)
        if (allocated(error)) return
        call check(error, size(changes) == 0, to_text(size(changes)) // " changes of " &
            & // "stability above the critical speed, expected none")
        if (allocated(error)) return
        call check(error, maxval(abs(table%real_part)) <= 1.0e-6_wp &
            & * maxval(abs(table%imag_part)), "a real part above the zero limit: " &
            & // to_text(maxval(abs(table%real_part))) // " 1/s")
    end subroutine test_no_change

end module test_linear_speeds
