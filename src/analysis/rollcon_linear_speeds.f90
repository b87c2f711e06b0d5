! SPDX-License-Identifier: MIT
!> The linear analysis over a range of speeds (docs/linear.md, "Eigenvalues against speed"):
!> a steady motion whose velocities all scale with one speed (straight rolling: a disk, a
!> bicycle) linearised at each speed of a grid, its eigenvalues with the zero ones of the cyclic
!> coordinates and conserved speeds taken out, and the speeds where the motion changes
!> stability found to a set tolerance.
!>
!> Taking the zeros out. In independent coordinates, a coordinate that the equations do not
!> depend on (a position on the ground, a heading, a wheel's spin angle) has a zero column of
!> A_red, and a speed that the linearised equations keep constant a zero row. Either way the
!> matrix is block triangular after a permutation, and that index contributes one eigenvalue 0
!> and can be struck out (row and column) without changing the others. Struck out one after
!> the other until none is left, what remains (the kept block) has the eigenvalues that are not
!> zero by structure: a real eigenvalue passing through zero (a bicycle's capsize mode) is
!> then not mistaken for a cyclic zero, whose own computed value may be 1e-8 rather than 0
!> (docs/linear.md, accuracy). Which indices are struck is found once, at the reference speed,
!> and kept for every speed, so the kept block is the same system throughout.
module rollcon_linear_speeds
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_lapack, only : general_eigenvalues
    use rollcon_least_squares, only : left_null_space
    use rollcon_problem, only : problem_type
    use rollcon_linearisation, only : linear_options_type, linear_result_type, linearise, &
        & sort_eigenvalues
    implicit none
    private

    public :: speed_table_type, stability_change_type, reference_speed, structural_zeros, &
        & zero_deflations, kept_eigenvalues, speed_table, stability_changes, speed_tolerance

    !> An entry of A_red counts as zero when |a| <= zero_entry max|A_red|: the differences'
    !> error is about 1e-10 relative (docs/linear.md); the exact zeros of a cyclic coordinate's
    !> column are zero to round-off of its trigonometric terms (1e-16)
    real(wp), parameter :: zero_entry = 1.0e-9_wp
    !> Speeds where stability changes are found to this absolute tolerance [m/s]
    real(wp), parameter :: speed_tolerance = 1.0e-9_wp
    !> What the differences' error (about 1e-11 relative, docs/linear.md) leaves in a real
    !> part that is zero, relative to the largest |lambda|: while no eigenvalue is followed
    !> (stability_changes, step 1), a largest real part within it counts as 0
    real(wp), parameter :: noise_fraction = 1.0e-10_wp
    !> Step 1 of stability_changes narrows a bracket to this fraction of the grid's step
    !> before an eigenvalue is followed: 1e-6 of 0.05 m/s moves the bicycle's eigenvalues by
    !> 1e-8 1/s or less, far below their distances from each other
    real(wp), parameter :: narrow_fraction = 1.0e-6_wp
    !> Most doublings of the bracket into the stable side (stability_changes, step 2): the
    !> bias of step 1 is noise_fraction max|lambda| over the crossing's slope, 2.4e-8 m/s on
    !> the bicycle's capsize, a few widths of the narrowed bracket
    integer, parameter :: max_widenings = 40
    !> On the grid, a real part counts as positive only above this fraction of the largest
    !> |lambda|: a zero of multiplicity two (a conserved speed coupled to a first integral)
    !> spreads to about 1e-8 of it (docs/linear.md), the linear analysis's own zero limit
    real(wp), parameter :: grid_fraction = 1.0e-6_wp

    !> The eigenvalues of the kept block at each speed of a grid
    type :: speed_table_type
        !> Speeds [m/s]
        real(wp), allocatable :: speed(:)
        !> Eigenvalues [1/s], (kept, speeds), by decreasing real part (a pair adjacent)
        real(wp), allocatable :: real_part(:, :), imag_part(:, :)
        !> Indices of A_red struck out as structural zeros (found at the reference speed)
        logical, allocatable :: struck(:)
        !> The independent coordinates of A_red (numbers into y = (q, u)), those of the
        !> reference speed, taken at every speed: the struck indices name the same coordinates
        integer, allocatable :: independent(:)
        !> Zeros of the kept block deflated one by one by its null vectors (counted at the
        !> reference speed, the same number at every speed)
        integer :: deflations = 0
    end type speed_table_type

    !> A speed where the largest real part of the kept eigenvalues changes sign
    type :: stability_change_type
        !> The speed [m/s]
        real(wp) :: speed = 0.0_wp
        !> .true.: a complex pair crosses the imaginary axis (an oscillation: a bicycle's
        !> weave); .false.: a real eigenvalue passes through zero (a divergence: capsize)
        logical :: oscillatory = .false.
        !> The crossing pair's frequency there [1/s] (0 for a real one)
        real(wp) :: frequency = 0.0_wp
        !> .true. when the motion is stable above this speed, .false. when below it
        logical :: stable_above = .false.
    end type stability_change_type

contains

    !> The speed of the start that the grid's speeds scale: the speed of the centre of mass of
    !> the model's first part that moves [m/s]. An error when no part moves: there is nothing
    !> to scale.
    subroutine reference_speed(u, speed, error)
        !> Rates of every part, 6 each [m/s, rad/s]
        real(wp), intent(in) :: u(:)
        real(wp), intent(out) :: speed
        type(error_type), allocatable, intent(out) :: error
        integer :: p

        speed = 0.0_wp
        do p = 1, size(u)/6
            speed = norm2(u(6*(p - 1) + 1:6*(p - 1) + 3))
            if (speed > 0.0_wp) return
        end do
        call fatal_error(error, "eigenvalues against speed: no part's centre of mass moves at " &
            & // "the start, so there is no speed to scale; give the start the steady motion " &
            & // "(e.g. rolling at some speed) whose velocities all scale with the speed", &
            & stat_input)
    end subroutine reference_speed

    !> The indices of A_red that are structural zeros: a zero column (a coordinate the
    !> equations do not depend on) or a zero row (a rate they keep constant), struck out one
    !> after the other until none is left.
    pure function structural_zeros(a) result(struck)
        real(wp), intent(in) :: a(:, :)
        logical, allocatable :: struck(:)
        real(wp) :: limit
        integer :: j
        logical :: found

        allocate(struck(size(a, 1)), source=.false.)
        if (size(a) == 0) return
        limit = zero_entry*maxval(abs(a))
        found = .true.
        do while (found)
            found = .false.
            do j = 1, size(a, 1)
                if (struck(j)) cycle
                if (all(abs(pack(a(:, j), .not. struck)) <= limit) &
                    & .or. all(abs(pack(a(j, :), .not. struck)) <= limit)) then
                    struck(j) = .true.
                    found = .true.
                end if
            end do
        end do
    end function structural_zeros

    !> How many zero eigenvalues the block of A_red left by the struck indices still has: its
    !> null vectors deflated one by one (deflate) until it is regular, a singular value below
    !> zero_entry of the largest counting as zero. A combination of coordinates the equations
    !> do not depend on (the common heading of parts whose own headings are independent
    !> coordinates) or a first integral's mode gives such a zero without a zero row or column.
    subroutine zero_deflations(a, struck, count_found, error)
        real(wp), intent(in) :: a(:, :)
        logical, intent(in) :: struck(:)
        integer, intent(out) :: count_found
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: b(:, :), null(:, :)
        integer, allocatable :: keep(:)
        integer :: rank, k

        count_found = 0
        keep = pack([(k, k = 1, size(struck))], .not. struck)
        b = a(keep, keep)
        do while (size(b, 1) > 0)
            call left_null_space(transpose(b), zero_entry, rank, null, error)
            if (allocated(error)) return
            if (rank == size(b, 1)) exit
            call deflate(b, null(:, size(null, 2)))
            count_found = count_found + 1
        end do
    end subroutine zero_deflations

    !> Take one zero eigenvalue out of b by a null vector v (b v = 0): with j where |v_j| is
    !> largest, the basis change S = I + (v - e_j) e_j^T turns column j of S^-1 b S into
    !> S^-1 b v = 0, so row and column j are struck with the eigenvalue 0 they carry.
    pure subroutine deflate(b, v)
        real(wp), allocatable, intent(inout) :: b(:, :)
        real(wp), intent(in) :: v(:)
        real(wp), allocatable :: c(:, :)
        integer :: j, i, n

        n = size(b, 1)
        j = maxloc(abs(v), 1)
        c = b
        ! c = b S: column j becomes b v
        c(:, j) = matmul(b, v)
        ! c = S^-1 c: row j divided by v_j, then v_i/v_j times it taken from row i
        c(j, :) = c(j, :)/v(j)
        do i = 1, n
            if (i /= j) c(i, :) = c(i, :) - v(i)*c(j, :)
        end do
        b = c(pack([(i, i = 1, n)], [(i, i = 1, n)] /= j), &
            & pack([(i, i = 1, n)], [(i, i = 1, n)] /= j))
    end subroutine deflate

    !> The eigenvalues of A_red with the struck indices taken out and then deflations more
    !> zeros deflated by the null vectors of what is left (the smallest singular value's each
    !> time), by decreasing real part (for equal real parts by decreasing |imaginary part|, +
    !> first).
    subroutine kept_eigenvalues(a, struck, deflations, re, im, error)
        real(wp), intent(in) :: a(:, :)
        logical, intent(in) :: struck(:)
        integer, intent(in) :: deflations
        real(wp), allocatable, intent(out) :: re(:), im(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: b(:, :), null(:, :)
        integer, allocatable :: keep(:)
        integer :: k, rank

        keep = pack([(k, k = 1, size(struck))], .not. struck)
        b = a(keep, keep)
        do k = 1, min(deflations, size(b, 1))
            call left_null_space(transpose(b), zero_entry, rank, null, error)
            if (allocated(error)) return
            call deflate(b, null(:, size(null, 2)))
        end do
        allocate(re(size(b, 1)), im(size(b, 1)))
        call general_eigenvalues(b, re, im, error)
        if (allocated(error)) return
        call sort_eigenvalues(re, im)
    end subroutine kept_eigenvalues

    !> Linearise at every speed of a grid: the start's rates u scaled by speed/reference
    !> (reference_speed), at the start's coordinates q, and the kept eigenvalues at each. The
    !> structural zeros are found at the reference speed itself. The scaled start must meet the
    !> UCONs (it does when they are homogeneous in the rates: rolling without a moving ground);
    !> linearise refuses it otherwise, naming the speed.
    subroutine speed_table(problem, time, q, u, speeds, options, table, error)
        type(problem_type), intent(inout), target :: problem
        !> Time of the start [s]
        real(wp), intent(in) :: time
        !> The start [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        !> Speeds [m/s], 0 or more
        real(wp), intent(in) :: speeds(:)
        type(linear_options_type), intent(in) :: options
        type(speed_table_type), intent(out) :: table
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: result
        real(wp), allocatable :: re(:), im(:)
        real(wp) :: reference
        integer :: k, kept

        call reference_speed(u, reference, error)
        if (allocated(error)) return
        call linearise(problem, time, q, u, options, result, error)
        if (allocated(error)) return
        table%independent = result%independent
        table%struck = structural_zeros(result%reduced_matrix)
        call zero_deflations(result%reduced_matrix, table%struck, table%deflations, error)
        if (allocated(error)) return
        kept = count(.not. table%struck) - table%deflations
        table%speed = speeds
        allocate(table%real_part(kept, size(speeds)), table%imag_part(kept, size(speeds)))
        do k = 1, size(speeds)
            call eigenvalues_at(problem, time, q, u, reference, speeds(k), options, table, re, &
                & im, error)
            if (allocated(error)) return
            table%real_part(:, k) = re
            table%imag_part(:, k) = im
        end do
    end subroutine speed_table

    !> The kept eigenvalues at one speed.
    subroutine eigenvalues_at(problem, time, q, u, reference, speed, options, table, re, im, &
            & error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:), reference, speed
        type(linear_options_type), intent(in) :: options
        !> The struck indices and the deflations
        type(speed_table_type), intent(in) :: table
        real(wp), allocatable, intent(out) :: re(:), im(:)
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: result
        type(linear_options_type) :: fixed

        fixed = options
        fixed%independent = table%independent
        call linearise(problem, time, q, u*(speed/reference), fixed, result, error)
        if (allocated(error)) then
            error%message = "at " // to_text(speed) // " m/s: " // error%message
            return
        end if
        call kept_eigenvalues(result%reduced_matrix, table%struck, table%deflations, re, im, &
            & error)
    end subroutine eigenvalues_at

    !> The speeds within the table's range where the motion changes stability, each between
    !> the grid's speeds that bracket it, to speed_tolerance. On the grid a speed is stable when
    !> no kept eigenvalue has a real part above grid_fraction of the largest |lambda| (what a
    !> zero's computed value may be: docs/linear.md). Between two grid speeds that differ:
    !>
    !> 1. the bracket is bisected on the largest real part, unstable above noise_fraction of the
    !>    largest |lambda| (a conservative model's neutral pair has a computed real part of the
    !>    differences' error), down to narrow_fraction of the grid's step: no eigenvalue is
    !>    followed, so none can be mistaken for another where two are equal or close (two equal
    !>    wheels give a repeated one);
    !> 2. there the crossing eigenvalue is the most unstable at the unstable end and the nearest
    !>    to it at the other (the bracket so narrow that it has moved far less than its distance
    !>    to any other), and the bracket is bisected on that eigenvalue's own real part against
    !>    0, followed at each new speed as the one nearest to the value its bracket's ends
    !>    interpolate, down to speed_tolerance: the noise threshold of step 1 biases nothing.
    !>    The bracket is first widened into the stable side until that real part is <= 0 there
    !>    (step 1's threshold put the stable end up to noise_fraction max|lambda| / slope from
    !>    the crossing).
    !>
    !> Oscillatory when the followed eigenvalue is one of a complex pair at both ends. A grid
    !> too coarse to bracket two changes close together finds neither: the grid's spacing
    !> bounds what is found.
    subroutine stability_changes(problem, time, q, u, table, options, changes, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        type(speed_table_type), intent(in) :: table
        type(linear_options_type), intent(in) :: options
        type(stability_change_type), allocatable, intent(out) :: changes(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: re(:), im(:)
        real(wp) :: reference, speed(2), middle, weight, width, step
        complex(wp) :: followed(2), guess, found
        logical :: stable(2)
        integer :: k, side, stable_side, widenings

        allocate(changes(0))
        call reference_speed(u, reference, error)
        if (allocated(error)) return
        do k = 1, size(table%speed) - 1
            stable(1) = is_stable(table%real_part(:, k), table%imag_part(:, k), grid_fraction)
            stable(2) = is_stable(table%real_part(:, k + 1), table%imag_part(:, k + 1), &
                & grid_fraction)
            if (stable(1) .eqv. stable(2)) cycle
            speed = table%speed(k:k + 1)
            stable_side = merge(1, 2, stable(1))
            ! 1. the largest real part, no eigenvalue followed
            width = narrow_fraction*abs(speed(2) - speed(1))
            do while (abs(speed(2) - speed(1)) > max(width, speed_tolerance))
                middle = 0.5_wp*(speed(1) + speed(2))
                call eigenvalues_at(problem, time, q, u, reference, middle, options, table, re, &
                    & im, error)
                if (allocated(error)) return
                side = merge(3 - stable_side, stable_side, .not. is_stable(re, im, &
                    & noise_fraction))
                speed(side) = middle
            end do
            ! 2. the crossing eigenvalue: the most unstable at the unstable end, the nearest
            ! to it at the stable end
            call eigenvalues_at(problem, time, q, u, reference, speed(3 - stable_side), &
                & options, table, re, im, error)
            if (allocated(error)) return
            followed(3 - stable_side) = most_unstable(re, im)
            call eigenvalues_at(problem, time, q, u, reference, speed(stable_side), options, &
                & table, re, im, error)
            if (allocated(error)) return
            followed(stable_side) = nearest(re, im, followed(3 - stable_side))
            ! widen into the stable side until the followed real part is <= 0 there
            step = speed(stable_side) - speed(3 - stable_side)
            widenings = 0
            do while (real(followed(stable_side)) > 0.0_wp .and. widenings < max_widenings)
                widenings = widenings + 1
                guess = followed(stable_side)
                speed(stable_side) = speed(stable_side) + step
                step = 2.0_wp*step
                call eigenvalues_at(problem, time, q, u, reference, speed(stable_side), &
                    & options, table, re, im, error)
                if (allocated(error)) return
                followed(stable_side) = nearest(re, im, guess + (guess &
                    & - followed(3 - stable_side)))
            end do
            ! 3. the followed eigenvalue's real part against 0
            do while (abs(speed(2) - speed(1)) > speed_tolerance)
                middle = 0.5_wp*(speed(1) + speed(2))
                call eigenvalues_at(problem, time, q, u, reference, middle, options, table, re, &
                    & im, error)
                if (allocated(error)) return
                weight = (middle - speed(1))/(speed(2) - speed(1))
                guess = (1.0_wp - weight)*followed(1) + weight*followed(2)
                found = nearest(re, im, guess)
                side = merge(3 - stable_side, stable_side, real(found) > 0.0_wp)
                speed(side) = middle
                followed(side) = found
            end do
            changes = [changes, stability_change_type(speed=0.5_wp*sum(speed), &
                & oscillatory=abs(aimag(followed(1))) > grid_fraction*abs(followed(1)) &
                & .and. abs(aimag(followed(2))) > grid_fraction*abs(followed(2)), &
                & frequency=0.5_wp*abs(aimag(followed(1)) + aimag(followed(2))), &
                & stable_above=stable(2) .eqv. (table%speed(k + 1) > table%speed(k)))]
        end do
    end subroutine stability_changes

    !> Stable: no eigenvalue has a real part above fraction of the largest |lambda| (a pure
    !> oscillation, a conservative model's imaginary pair, and a zero have computed real parts
    !> of the differences' error, not exactly 0).
    pure logical function is_stable(re, im, fraction)
        real(wp), intent(in) :: re(:), im(:), fraction

        is_stable = .true.
        if (size(re) > 0) is_stable = maxval(re) <= fraction*maxval(hypot(re, im))
    end function is_stable

    !> The eigenvalue with the largest real part (the first of a pair: + imaginary part).
    pure complex(wp) function most_unstable(re, im)
        real(wp), intent(in) :: re(:), im(:)
        integer :: i

        i = maxloc(re, 1)
        most_unstable = cmplx(re(i), abs(im(i)), wp)
    end function most_unstable

    !> The eigenvalue nearest to a value, its imaginary part taken >= 0 (a pair moves together).
    pure complex(wp) function nearest(re, im, value)
        real(wp), intent(in) :: re(:), im(:)
        complex(wp), intent(in) :: value
        integer :: i

        i = minloc(hypot(re - real(value), abs(im) - aimag(value)), 1)
        nearest = cmplx(re(i), abs(im(i)), wp)
    end function nearest

end module rollcon_linear_speeds
