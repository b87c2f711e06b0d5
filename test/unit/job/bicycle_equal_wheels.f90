! SPDX-License-Identifier: MIT
!> The benchmark bicycle with its front wheel made equal to its rear
!> (test/linear/bicycle_equal_wheels.adm, written by data/bicycle/write_adm.py from the table
!> beside it): the analysis against speed, whose independent coordinates are those of its
!> reference speed at every speed, against the direct linear analysis at one speed at a time,
!> which chooses its own (suite bicycle).
module bicycle_equal_wheels
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job, input_override_type
    use rollcon_linearisation, only : linear_result_type
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type, speed_tolerance
    use rollcon_linear_job, only : linearise_job, linear_speeds_job
    use rollcon_testing, only : check
    use override_lists, only : add_override
    implicit none
    private

    public :: test_equal_rows, test_equal_speeds

    character(len=*), parameter :: equal_dataset = "test/linear/bicycle_equal_wheels.adm"
    !> Both wheels' radius [m]
    real(wp), parameter :: wheel_radius = 0.3_wp
    !> The table's rows and the direct eigenvalues, relative to the largest |lambda|: measured
    !> 1.7e-14 at the nine speeds (the eigenvalues themselves are good to about 1e-11,
    !> docs/linear.md, but both analyses difference the same equations along nearly the same
    !> basis); a row of another system differs by order 1
    real(wp), parameter :: tol_row = 1.0e-12_wp
    !> An eigenvalue's error, as a fraction of the largest |lambda|, that a speed found from it
    !> may carry over its slope (docs/linear.md: about 1e-11; ten times that)
    real(wp), parameter :: eigen_error = 1.0e-10_wp

contains

    !> At speeds where the rows were another system's (3, 3.05, 3.15 and 3.4 m/s: the pivoted
    !> QR chose other independent coordinates there, so that the struck indices named others)
    !> and at others, every row of the table is the direct analysis's non-zero eigenvalues.
    subroutine test_equal_rows(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: speeds(9) = [0.5_wp, 3.0_wp, 3.05_wp, 3.1_wp, 3.15_wp, 3.4_wp, &
            & 5.0_wp, 7.0_wp, 9.0_wp]
        type(job_type) :: job
        type(speed_table_type) :: table
        type(stability_change_type), allocatable :: changes(:)
        character(len=:), allocatable :: report
        real(wp), allocatable :: re(:), im(:)
        real(wp) :: scale
        integer :: k, i, j

        call load_job(equal_dataset, job, error)
        if (allocated(error)) return
        call linear_speeds_job(job, speeds, table, changes, report, error)
        if (allocated(error)) return
        do k = 1, size(speeds)
            call direct_nonzero(speeds(k), re, im, error)
            if (allocated(error)) return
            call check(error, size(re) == size(table%real_part, 1), "at " // to_text(speeds(k)) &
                & // " m/s: " // to_text(size(re)) // " non-zero eigenvalues, the table keeps " &
                & // to_text(size(table%real_part, 1)))
            if (allocated(error)) return
            scale = maxval(hypot(re, im))
            do i = 1, size(re)
                j = minloc(hypot(re - table%real_part(i, k), im - table%imag_part(i, k)), 1)
                call check(error, hypot(re(j) - table%real_part(i, k), im(j) &
                    & - table%imag_part(i, k)) <= tol_row*scale, "at " // to_text(speeds(k)) &
                    & // " m/s the row's " // to_text(table%real_part(i, k)) // " + " &
                    & // to_text(table%imag_part(i, k)) // " i against the direct " &
                    & // to_text(re(j)) // " + " // to_text(im(j)) // " i")
                if (allocated(error)) return
            end do
        end do
    end subroutine test_equal_rows

    !> `rollcon linear test/linear/bicycle_equal_wheels.adm --speeds 0,10,21`: two changes of
    !> stability (there were dozens), the weave (a complex pair, stable above) and the capsize
    !> (a real eigenvalue, stable below), at the speeds the direct analysis gives: the weave's
    !> by the secant method on its pair's real part, the capsize's by the cubic through its
    !> eigenvalue at 2 and 4 mm/s on either side (which stays far from the zeros). Each to
    !> speed_tolerance plus what an eigenvalue's error moves it: eigen_error max|lambda| over
    !> the slope (measured: weave 3.2e-10 of 2.8e-9, capsize 4.5e-9 of 4.8e-8 m/s, its real
    !> eigenvalue's slope 0.071 1/s per m/s).
    subroutine test_equal_speeds(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(speed_table_type) :: table
        type(stability_change_type), allocatable :: changes(:)
        character(len=:), allocatable :: report
        real(wp) :: weave, weave_slope, capsize, capsize_slope, largest
        integer :: k

        call load_job(equal_dataset, job, error)
        if (allocated(error)) return
        call linear_speeds_job(job, [(0.5_wp*k, k = 0, 20)], table, changes, report, error)
        if (allocated(error)) return
        call check(error, size(changes) == 2, to_text(size(changes)) // " changes of " &
            & // "stability; expected 2")
        if (allocated(error)) return
        call check(error, changes(1)%oscillatory .and. changes(1)%stable_above .and. .not. &
            & changes(2)%oscillatory .and. .not. changes(2)%stable_above, "expected the weave " &
            & // "(a complex pair, stable above), then the capsize (a real eigenvalue, stable " &
            & // "below)")
        if (allocated(error)) return
        call weave_root(weave, weave_slope, largest, error)
        if (allocated(error)) return
        call check(error, changes(1)%speed, weave, "weave speed [m/s]", abs_tol=speed_tolerance &
            & + eigen_error*largest/abs(weave_slope))
        if (allocated(error)) return
        call capsize_root(capsize, capsize_slope, largest, error)
        if (allocated(error)) return
        call check(error, changes(2)%speed, capsize, "capsize speed [m/s]", &
            & abs_tol=speed_tolerance + eigen_error*largest/abs(capsize_slope))
    end subroutine test_equal_speeds

    !> The direct linear analysis of the dataset ridden at speed (every part's VX and both
    !> wheels' spins -v/r set): its eigenvalues above its zero limit.
    subroutine direct_nonzero(speed, re, im, error)
        real(wp), intent(in) :: speed
        real(wp), allocatable, intent(out) :: re(:), im(:)
        type(error_type), allocatable, intent(out) :: error
        type(input_override_type), allocatable :: set(:)
        type(job_type) :: job
        type(linear_result_type) :: result
        character(len=:), allocatable :: report
        logical, allocatable :: kept(:)
        integer :: p

        do p = 2, 5
            call add_override(set, "part%" // to_text(p) // "%vx", to_text(speed))
        end do
        call add_override(set, "part%2%wz", to_text(-speed/wheel_radius))
        call add_override(set, "part%5%wz", to_text(-speed/wheel_radius))
        call load_job(equal_dataset, job, error, overrides=set)
        if (allocated(error)) return
        call linearise_job(job, result, report, error)
        if (allocated(error)) return
        kept = hypot(result%real_part, result%imag_part) > result%zero_limit
        re = pack(result%real_part, kept)
        im = pack(result%imag_part, kept)
    end subroutine direct_nonzero

    !> The weave speed: the root of its pair's real part by the secant method from 5.1 and
    !> 5.25 m/s, and that real part's slope there [1/s per m/s]; largest: max|lambda| there.
    subroutine weave_root(speed, slope, largest, error)
        real(wp), intent(out) :: speed, slope, largest
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: v(2), f(2), next
        integer :: k

        v = [5.1_wp, 5.25_wp]
        do k = 1, 2
            call weave_real(v(k), f(k), largest, error)
            if (allocated(error)) return
        end do
        do k = 1, 40
            next = v(2) - f(2)*(v(2) - v(1))/(f(2) - f(1))
            v(1) = v(2)
            f(1) = f(2)
            v(2) = next
            call weave_real(v(2), f(2), largest, error)
            if (allocated(error)) return
            if (abs(v(2) - v(1)) < 1.0e-13_wp .or. f(2) == 0.0_wp) exit
        end do
        speed = v(2)
        slope = (f(2) - f(1))/(v(2) - v(1))
        if (.not. abs(slope) > 0.0_wp) slope = huge(1.0_wp)
    end subroutine weave_root

    !> The largest real part of a complex pair of the direct analysis at speed.
    subroutine weave_real(speed, value, largest, error)
        real(wp), intent(in) :: speed
        real(wp), intent(out) :: value, largest
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: re(:), im(:)

        call direct_nonzero(speed, re, im, error)
        if (allocated(error)) return
        largest = maxval(hypot(re, im))
        value = maxval(re, mask=abs(im) > 1.0e-6_wp*largest)
    end subroutine weave_real

    !> The capsize speed: its real eigenvalue (the non-zero real one nearest 0) found near its
    !> root by the secant method from 8.4 and 8.6 m/s, then the root of the cubic through it at
    !> 2 and 4 mm/s on either side (where it is 1.4e-4 1/s and more, far above the zeros'
    !> spread), and the cubic's slope there.
    subroutine capsize_root(speed, slope, largest, error)
        real(wp), intent(out) :: speed, slope, largest
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: h = 2.0e-3_wp
        real(wp) :: v(2), f(2), next, nodes(4), values(4), x, p, dp
        integer :: k, i

        v = [8.4_wp, 8.6_wp]
        do k = 1, 2
            call capsize_value(v(k), f(k), largest, error)
            if (allocated(error)) return
        end do
        do k = 1, 20
            next = v(2) - f(2)*(v(2) - v(1))/(f(2) - f(1))
            v(1) = v(2)
            f(1) = f(2)
            v(2) = next
            call capsize_value(v(2), f(2), largest, error)
            if (allocated(error)) return
            if (abs(v(2) - v(1)) < 1.0e-6_wp) exit
        end do
        nodes = v(2) + h*[-2.0_wp, -1.0_wp, 1.0_wp, 2.0_wp]
        do i = 1, 4
            call capsize_value(nodes(i), values(i), largest, error)
            if (allocated(error)) return
        end do
        x = v(2)
        do k = 1, 50
            call cubic(nodes, values, x, p, dp)
            x = x - p/dp
        end do
        call cubic(nodes, values, x, p, dp)
        speed = x
        slope = dp
    end subroutine capsize_root

    !> The capsize eigenvalue of the direct analysis at speed: the non-zero real one nearest 0.
    subroutine capsize_value(speed, value, largest, error)
        real(wp), intent(in) :: speed
        real(wp), intent(out) :: value, largest
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: re(:), im(:)
        integer :: k

        call direct_nonzero(speed, re, im, error)
        if (allocated(error)) return
        largest = maxval(hypot(re, im))
        k = minloc(abs(re), 1, mask=im == 0.0_wp)
        value = re(k)
    end subroutine capsize_value

    !> The Lagrange cubic through (nodes, values) and its derivative at x.
    pure subroutine cubic(nodes, values, x, p, dp)
        real(wp), intent(in) :: nodes(4), values(4), x
        real(wp), intent(out) :: p, dp
        real(wp) :: term, d
        integer :: i, j, m

        p = 0.0_wp
        dp = 0.0_wp
        do i = 1, 4
            term = values(i)
            do j = 1, 4
                if (j /= i) term = term*(x - nodes(j))/(nodes(i) - nodes(j))
            end do
            p = p + term
            ! d/dx of the product: the sum over m of the product with factor m differentiated
            do m = 1, 4
                if (m == i) cycle
                d = values(i)/(nodes(i) - nodes(m))
                do j = 1, 4
                    if (j /= i .and. j /= m) d = d*(x - nodes(j))/(nodes(i) - nodes(j))
                end do
                dp = dp + d
            end do
        end do
    end subroutine cubic

end module bicycle_equal_wheels
