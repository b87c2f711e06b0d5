! SPDX-License-Identifier: MIT
!> The partials of the momentum residual M a - f - C^T lambda in the coordinates q and the
!> rates u (dm/dq, dm/du: n x n, n = 6 parts), held as what they are: each force element and
!> each UCON writes only the rows of the parts it loads by the columns of the parts it reads,
!> so the matrices are 6 x 6 blocks on pairs of parts (a part with itself, the two parts of a
!> SPRINGDAMPER or BUSHING, a force statement's loaded part with each part it reads: rollcon_
!> force's force_couplings, and every two parts of one UCON). Held as those blocks
!> (`init_blocks`: memory linear in the model, docs/design.md §4 "Memory"), or dense
!> (`init_dense`: n x n, for a caller that wants every entry, e.g. the partials in the
!> accelerations of rollcon_user_force_partials). Each entry is written with the same
!> operations in the same order either way, so the numbers are the same bit for bit; an entry
!> of no pair is an exact zero. A write to a pair not held (a part a user's routine declared
!> at its first call, after the pairs were gathered) is noted (`missed`): the caller adds the
!> pairs (`grow`) and writes again, so that no partial is lost.
module rollcon_momentum_partials
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: momentum_partials_type, part_run_end

    !> dm/dq and dm/du, dense or on pairs of parts
    type :: momentum_partials_type
        !> Coordinates (6 per part) and parts
        integer :: n = 0, parts = 0
        !> Held on pairs of parts (else dense)
        logical :: blocked = .false.
        !> Dense: dm/dq and dm/du (n, n)
        real(wp), allocatable :: dq(:, :), du(:, :)
        !> On pairs: block e is rows of part row_part(e) by columns of part pair_part(e), (6, 6,
        !> pairs); part a's pairs are pair_start(a) : pair_start(a + 1) - 1, their column parts
        !> ascending
        real(wp), allocatable :: block_q(:, :, :), block_u(:, :, :)
        integer, allocatable :: pair_start(:), pair_part(:)
        !> Pairs written to but not held since the last grow (2, missed_count)
        integer :: missed_count = 0
        integer, allocatable :: missed(:, :)
    contains
        procedure :: init_dense
        procedure :: init_blocks
        procedure :: clear
        procedure :: grow
        procedure :: pair
        procedure :: set_part
        procedure :: subtract_q
        procedure :: subtract_u
        procedure :: subtract_q_entry
        procedure :: subtract_q_over
        procedure :: q_block
        procedure :: u_block
        procedure :: q_at
        procedure :: u_at
        procedure :: scatter_negated
    end type momentum_partials_type

contains

    !> Dense n x n matrices, zero (n = 6 parts).
    subroutine init_dense(self, n)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: n

        call forget(self)
        self%n = n
        self%parts = n/6
        self%blocked = .false.
        allocate(self%dq(n, n), self%du(n, n), source=0.0_wp)
    end subroutine init_dense

    !> Blocks on every part with itself and on the pairs of parts given (2 x m, model indices;
    !> either order, repeats and parts outside 1..parts ignored), both ways round; zero.
    subroutine init_blocks(self, parts, pairs)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: parts
        integer, intent(in) :: pairs(:, :)
        integer, allocatable :: count(:), column(:), start(:)
        integer :: k, a, b, e, first, last, kept, i, j, held

        call forget(self)
        self%n = 6*parts
        self%parts = parts
        self%blocked = .true.
        ! each part's column parts (itself and both ends of each pair), by counting
        allocate(count(parts), source=1)
        do k = 1, size(pairs, 2)
            a = pairs(1, k)
            b = pairs(2, k)
            if (a < 1 .or. b < 1 .or. a > parts .or. b > parts .or. a == b) cycle
            count(a) = count(a) + 1
            count(b) = count(b) + 1
        end do
        allocate(start(parts + 1))
        start(1) = 1
        do a = 1, parts
            start(a + 1) = start(a) + count(a)
        end do
        allocate(column(start(parts + 1) - 1))
        count = 0
        do a = 1, parts
            column(start(a)) = a
            count(a) = 1
        end do
        do k = 1, size(pairs, 2)
            a = pairs(1, k)
            b = pairs(2, k)
            if (a < 1 .or. b < 1 .or. a > parts .or. b > parts .or. a == b) cycle
            column(start(a) + count(a)) = b
            count(a) = count(a) + 1
            column(start(b) + count(b)) = a
            count(b) = count(b) + 1
        end do
        ! each part's list ascending (insertion: a few each) and each once
        allocate(self%pair_start(parts + 1))
        self%pair_start(1) = 1
        kept = 0
        do a = 1, parts
            first = start(a)
            last = start(a + 1) - 1
            do i = first + 1, last
                held = column(i)
                j = i - 1
                do while (j >= first)
                    if (column(j) <= held) exit
                    column(j + 1) = column(j)
                    j = j - 1
                end do
                column(j + 1) = held
            end do
            do i = first, last
                if (i > first) then
                    if (column(i) == column(i - 1)) cycle
                end if
                kept = kept + 1
                column(kept) = column(i)
            end do
            self%pair_start(a + 1) = kept + 1
        end do
        self%pair_part = column(:kept)
        e = kept
        allocate(self%block_q(6, 6, e), self%block_u(6, 6, e), source=0.0_wp)
    end subroutine init_blocks

    !> Pair (a, b) was written to but is not held.
    pure subroutine note_missed(self, a, b)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: a, b
        integer, allocatable :: more(:, :)

        if (.not. allocated(self%missed)) allocate(self%missed(2, 4))
        if (self%missed_count == size(self%missed, 2)) then
            allocate(more(2, 2*self%missed_count))
            more(:, :self%missed_count) = self%missed
            call move_alloc(more, self%missed)
        end if
        self%missed_count = self%missed_count + 1
        self%missed(:, self%missed_count) = [a, b]
    end subroutine note_missed

    !> The pairs held and those missed since (blocks on pairs only), zero: once a write has
    !> missed a pair, before writing again.
    subroutine grow(self)
        class(momentum_partials_type), intent(inout) :: self
        integer, allocatable :: pairs(:, :)
        integer :: a, e, m

        if (.not. self%blocked .or. self%missed_count == 0) return
        allocate(pairs(2, size(self%pair_part) + self%missed_count))
        m = 0
        do a = 1, self%parts
            do e = self%pair_start(a), self%pair_start(a + 1) - 1
                m = m + 1
                pairs(:, m) = [a, self%pair_part(e)]
            end do
        end do
        pairs(:, m + 1:) = self%missed(:, :self%missed_count)
        self%missed_count = 0
        call self%init_blocks(self%parts, pairs)
    end subroutine grow

    !> Free everything.
    pure subroutine forget(self)
        type(momentum_partials_type), intent(inout) :: self

        if (allocated(self%dq)) deallocate(self%dq, self%du)
        if (allocated(self%block_q)) deallocate(self%block_q, self%block_u)
        if (allocated(self%pair_start)) deallocate(self%pair_start, self%pair_part)
    end subroutine forget

    !> Every entry zero.
    pure subroutine clear(self)
        class(momentum_partials_type), intent(inout) :: self

        if (self%blocked) then
            self%block_q = 0.0_wp
            self%block_u = 0.0_wp
        else
            self%dq = 0.0_wp
            self%du = 0.0_wp
        end if
    end subroutine clear

    !> The block of rows of part a by columns of part b (bisection of a's pairs), 0 where the
    !> pair holds none.
    pure integer function pair(self, a, b) result(e)
        class(momentum_partials_type), intent(in) :: self
        integer, intent(in) :: a, b
        integer :: low, high, middle

        e = 0
        if (a < 1 .or. a > self%parts) return
        low = self%pair_start(a)
        high = self%pair_start(a + 1) - 1
        do while (low <= high)
            middle = (low + high)/2
            if (self%pair_part(middle) == b) then
                e = middle
                return
            else if (self%pair_part(middle) < b) then
                low = middle + 1
            else
                high = middle - 1
            end if
        end do
    end function pair

    !> Part p's own 6 x 6 blocks set to dq and du.
    pure subroutine set_part(self, p, dq, du)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: p
        real(wp), intent(in) :: dq(6, 6), du(6, 6)
        integer :: i0, e

        if (self%blocked) then
            e = self%pair(p, p)
            self%block_q(:, :, e) = dq
            self%block_u(:, :, e) = du
        else
            i0 = 6*(p - 1)
            self%dq(i0 + 1:i0 + 6, i0 + 1:i0 + 6) = dq
            self%du(i0 + 1:i0 + 6, i0 + 1:i0 + 6) = du
        end if
    end subroutine set_part

    !> dm/dq's rows first .. first + size(values) - 1 of part a (1..6) in column k (1..6) of
    !> part b, less values. Nothing where the pair holds no block (no element writes there).
    pure subroutine subtract_q(self, a, b, k, first, values)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: a, b, k, first
        real(wp), intent(in) :: values(:)

        call subtract_pair(self, a, b, k, first, values, .false.)
    end subroutine subtract_q

    !> dm/du's, as subtract_q.
    pure subroutine subtract_u(self, a, b, k, first, values)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: a, b, k, first
        real(wp), intent(in) :: values(:)

        call subtract_pair(self, a, b, k, first, values, .true.)
    end subroutine subtract_u

    !> subtract_q's work (of_u false) and subtract_u's (of_u true).
    pure subroutine subtract_pair(self, a, b, k, first, values, of_u)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: a, b, k, first
        real(wp), intent(in) :: values(:)
        logical, intent(in) :: of_u
        integer :: e, last, i0, j

        last = first + size(values) - 1
        if (self%blocked) then
            e = self%pair(a, b)
            if (e == 0) then
                call note_missed(self, a, b)
                return
            end if
            if (of_u) then
                self%block_u(first:last, k, e) = self%block_u(first:last, k, e) - values
            else
                self%block_q(first:last, k, e) = self%block_q(first:last, k, e) - values
            end if
        else
            i0 = 6*(a - 1)
            j = 6*(b - 1) + k
            if (of_u) then
                self%du(i0 + first:i0 + last, j) = self%du(i0 + first:i0 + last, j) - values
            else
                self%dq(i0 + first:i0 + last, j) = self%dq(i0 + first:i0 + last, j) - values
            end if
        end if
    end subroutine subtract_pair

    !> dm/dq's entry (i, j) (coordinate numbers) less value.
    pure subroutine subtract_q_entry(self, i, j, value)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: i, j
        real(wp), intent(in) :: value
        integer :: e

        if (self%blocked) then
            e = self%pair((i - 1)/6 + 1, (j - 1)/6 + 1)
            if (e == 0) then
                call note_missed(self, (i - 1)/6 + 1, (j - 1)/6 + 1)
                return
            end if
            associate (entry => self%block_q(mod(i - 1, 6) + 1, mod(j - 1, 6) + 1, e))
                entry = entry - value
            end associate
        else
            self%dq(i, j) = self%dq(i, j) - value
        end if
    end subroutine subtract_q_entry

    !> dm/dq's entries (at(ii), at(jj)) (coordinate numbers: a UCON's own coordinates, each
    !> once, ascending) less weight*second(ii, jj), or weight*second(jj, ii) when transposed
    !> (second: at least size(at) square): subtract_q_entry's operations on every pair of at,
    !> each entry's once, with each pair of parts' block found once per pair of runs of at's
    !> coordinates in one part (part_run_end) rather than per entry. A pair not held is noted
    !> (missed).
    pure subroutine subtract_q_over(self, at, weight, second, transposed)
        class(momentum_partials_type), intent(inout) :: self
        integer, intent(in) :: at(:)
        real(wp), intent(in) :: weight, second(:, :)
        logical, intent(in) :: transposed
        real(wp) :: value
        integer :: ii, jj, a, b, e, first_a, last_a, first_b, last_b, m

        m = size(at)
        if (.not. self%blocked) then
            do jj = 1, m
                do ii = 1, m
                    if (transposed) then
                        value = weight*second(jj, ii)
                    else
                        value = weight*second(ii, jj)
                    end if
                    self%dq(at(ii), at(jj)) = self%dq(at(ii), at(jj)) - value
                end do
            end do
            return
        end if
        ! the columns first_b .. last_b (part b) by the rows first_a .. last_a (part a)
        first_b = 1
        do while (first_b <= m)
            b = (at(first_b) - 1)/6 + 1
            last_b = part_run_end(at, first_b)
            first_a = 1
            do while (first_a <= m)
                a = (at(first_a) - 1)/6 + 1
                last_a = part_run_end(at, first_a)
                e = self%pair(a, b)
                if (e == 0) then
                    call note_missed(self, a, b)
                else
                    associate (block => self%block_q(:, :, e))
                        do jj = first_b, last_b
                            do ii = first_a, last_a
                                if (transposed) then
                                    value = weight*second(jj, ii)
                                else
                                    value = weight*second(ii, jj)
                                end if
                                block(at(ii) - 6*(a - 1), at(jj) - 6*(b - 1)) &
                                    & = block(at(ii) - 6*(a - 1), at(jj) - 6*(b - 1)) - value
                            end do
                        end do
                    end associate
                end if
                first_a = last_a + 1
            end do
            first_b = last_b + 1
        end do
    end subroutine subtract_q_over

    !> The last of the run of coordinates at(first:) in first's part (at ascending: a UCON's
    !> own coordinates): at(first : part_run_end) are all the part's in at.
    pure integer function part_run_end(at, first) result(last)
        integer, intent(in) :: at(:), first

        last = first
        do while (last < size(at))
            if ((at(last + 1) - 1)/6 /= (at(first) - 1)/6) exit
            last = last + 1
        end do
    end function part_run_end

    !> dm/dq's 6 x 6 block of rows of part a by columns of part b (zeros off the pairs).
    pure subroutine q_block(self, a, b, block)
        class(momentum_partials_type), intent(in) :: self
        integer, intent(in) :: a, b
        real(wp), intent(out) :: block(6, 6)

        call pair_block(self, a, b, self%block_q, self%dq, block)
    end subroutine q_block

    !> dm/du's block, as q_block.
    pure subroutine u_block(self, a, b, block)
        class(momentum_partials_type), intent(in) :: self
        integer, intent(in) :: a, b
        real(wp), intent(out) :: block(6, 6)

        call pair_block(self, a, b, self%block_u, self%du, block)
    end subroutine u_block

    !> q_block's and u_block's block of rows of part a by columns of part b: from the pairs'
    !> blocks (by_pairs) when the partials are held by blocks, else from the dense matrix.
    pure subroutine pair_block(self, a, b, by_pairs, dense, block)
        class(momentum_partials_type), intent(in) :: self
        integer, intent(in) :: a, b
        real(wp), allocatable, intent(in) :: by_pairs(:, :, :), dense(:, :)
        real(wp), intent(out) :: block(6, 6)
        integer :: e

        if (self%blocked) then
            e = self%pair(a, b)
            if (e > 0) then
                block = by_pairs(:, :, e)
            else
                block = 0.0_wp
            end if
        else
            block = dense(6*(a - 1) + 1:6*a, 6*(b - 1) + 1:6*b)
        end if
    end subroutine pair_block

    !> dm/dq's entry (i, j) (coordinate numbers; 0 off the pairs).
    pure real(wp) function q_at(self, i, j) result(value)
        class(momentum_partials_type), intent(in) :: self
        integer, intent(in) :: i, j
        integer :: e

        if (self%blocked) then
            value = 0.0_wp
            e = self%pair((i - 1)/6 + 1, (j - 1)/6 + 1)
            if (e > 0) value = self%block_q(mod(i - 1, 6) + 1, mod(j - 1, 6) + 1, e)
        else
            value = self%dq(i, j)
        end if
    end function q_at

    !> dm/du's entry (i, j), as q_at.
    pure real(wp) function u_at(self, i, j) result(value)
        class(momentum_partials_type), intent(in) :: self
        integer, intent(in) :: i, j
        integer :: e

        if (self%blocked) then
            value = 0.0_wp
            e = self%pair((i - 1)/6 + 1, (j - 1)/6 + 1)
            if (e > 0) value = self%block_u(mod(i - 1, 6) + 1, mod(j - 1, 6) + 1, e)
        else
            value = self%du(i, j)
        end if
    end function u_at

    !> (-dm/dq, -dm/du) into the n x 2n array x, every entry written (an entry off the pairs
    !> -0, as negating the dense zero gives).
    pure subroutine scatter_negated(self, x)
        class(momentum_partials_type), intent(in) :: self
        real(wp), intent(inout) :: x(:, :)
        integer :: a, e, i0, j0, n

        n = self%n
        if (.not. self%blocked) then
            x(:, :n) = -self%dq
            x(:, n + 1:2*n) = -self%du
            return
        end if
        x(:, :2*n) = -0.0_wp
        do a = 1, self%parts
            i0 = 6*(a - 1)
            do e = self%pair_start(a), self%pair_start(a + 1) - 1
                j0 = 6*(self%pair_part(e) - 1)
                x(i0 + 1:i0 + 6, j0 + 1:j0 + 6) = -self%block_q(:, :, e)
                x(i0 + 1:i0 + 6, n + j0 + 1:n + j0 + 6) = -self%block_u(:, :, e)
            end do
        end do
    end subroutine scatter_negated

end module rollcon_momentum_partials
