! SPDX-License-Identifier: MIT
!> The saddle-point system of constrained motion, solved through its structure
!> (docs/design.md §4):
!>
!>     [M  -C^T] [a     ]   [r1]        S = C M^-1 C^T (rows x rows)
!>     [C   0  ] [lambda] = [r2],       S lambda = r2 - C M^-1 r1,  a = M^-1 (r1 + C^T lambda).
!>
!> M is block diagonal, one 6 x 6 block per part, and each block is m I (translation) beside
!> the 3 x 3 rotational block B^T J B (principal axes at the centre of mass: no coupling). So
!> M^-1 costs a division and a 3 x 3 Cholesky solve per part (LAPACK dpotf2/dpotrs) and only
!> the small Schur complement S is factored with pivoting (LAPACK dgetf2/dgetrs), in place of
!> the whole (n + nc) x (n + nc) matrix. Given the constraints' blocks (rollcon_constraint_blocks:
!> UCONs that share no part do not couple), S is block diagonal and every step goes block by
!> block, each row over its block's coordinates only, so N independent disks cost N times one:
!> the sums are those of the dense path without its terms that are exact zeros, in the same
!> order, and the blocks' LU factors those of the dense S: the same numbers, except that an
!> exact zero may keep the sign the dense path's added zeros took from it (-0 for +0, with two
!> blocks or more). Nothing here allocates after init.
module rollcon_saddle_point
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    use rollcon_lapack, only : dgetf2, dgetrs, dpotf2, dpotrs, lapack_info_error
    use rollcon_constraint_blocks, only : constraint_blocks_type
    implicit none
    private

    public :: saddle_point_type

    !> Factors of one saddle-point matrix and the workspace to solve with them
    type :: saddle_point_type
        !> Coordinates, largest number of constraint rows, parts
        integer :: n = 0, nc = 0, parts = 0
        !> Constraint rows of the current factorisation (<= nc)
        integer :: rows = 0
        !> Translational mass of each part [kg]
        real(wp), allocatable :: part_mass(:)
        !> Cholesky factor (lower) of each part's rotational mass block (3, 3, parts)
        real(wp), allocatable :: rotational(:, :, :)
        !> M^-1 C^T (n, nc), columns 1..rows in use
        real(wp), allocatable :: minv_ct(:, :)
        !> LU factors of S (leading dimension nc) and their pivots
        real(wp), allocatable :: schur(:, :)
        integer, allocatable :: pivots(:)
        !> Factorisations done since init: one per saddle-point solve of a new matrix
        integer :: factorisations = 0
        !> The constraints' blocks, when given to init (then the factorisations of all nc rows
        !> go block by block; those of fewer rows, the projection's, stay dense)
        logical :: blocked = .false.
        type(constraint_blocks_type) :: blocks
        !> Each block's LU factors of S, packed (offset of block b: schur_start(b)), and the
        !> right-hand sides of one block gathered (most_rows, up to 2 n columns)
        real(wp), allocatable :: block_schur(:), gathered(:, :)
        integer, allocatable :: schur_start(:)
        !> Whether the current factorisation went block by block
        logical :: by_blocks = .false.
        !> For each part, whether a block holds it (a part no UCON touches is in none)
        logical, allocatable :: part_blocked(:)
        !> The rotational rows of one part's right-hand sides gathered for one dpotrs:
        !> (3, 1 + most_rows)
        real(wp), allocatable :: rotational_rows(:, :)
    contains
        procedure :: init
        procedure :: factor
        procedure :: solve
        procedure :: apply_inverse_mass
    end type saddle_point_type

contains

    !> Size the workspace for n coordinates (6 per part) and at most nc constraint rows, with
    !> the constraints' blocks when given.
    subroutine init(self, n, nc, blocks)
        class(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: n, nc
        type(constraint_blocks_type), intent(in), optional :: blocks
        integer :: b, m

        self%n = n
        self%nc = nc
        self%parts = n/6
        self%rows = 0
        self%factorisations = 0
        if (allocated(self%part_mass)) deallocate(self%part_mass, self%rotational, self%minv_ct, &
            & self%schur, self%pivots)
        allocate(self%part_mass(self%parts), source=0.0_wp)
        allocate(self%rotational(3, 3, self%parts), source=0.0_wp)
        allocate(self%minv_ct(n, max(nc, 1)), source=0.0_wp)
        allocate(self%schur(max(nc, 1), max(nc, 1)), source=0.0_wp)
        allocate(self%pivots(max(nc, 1)), source=0)
        self%blocked = present(blocks)
        self%by_blocks = .false.
        if (allocated(self%block_schur)) deallocate(self%block_schur, self%gathered, &
            & self%schur_start, self%part_blocked, self%rotational_rows)
        if (.not. self%blocked) return
        self%blocks = blocks
        allocate(self%part_blocked(self%parts), source=.false.)
        do b = 1, blocks%count
            self%part_blocked((blocks%coordinates(blocks%coordinate_start(b): &
                & blocks%coordinate_start(b + 1) - 1) - 1)/6 + 1) = .true.
        end do
        allocate(self%rotational_rows(3, 1 + max(blocks%most_rows, 1)), source=0.0_wp)
        allocate(self%schur_start(blocks%count + 1))
        self%schur_start(1) = 1
        do b = 1, blocks%count
            m = blocks%row_start(b + 1) - blocks%row_start(b)
            self%schur_start(b + 1) = self%schur_start(b) + m*m
        end do
        allocate(self%block_schur(max(self%schur_start(blocks%count + 1) - 1, 1)), &
            & self%gathered(max(blocks%most_rows, 1), max(2*n, 1)), source=0.0_wp)
    end subroutine init

    !> Factor the saddle-point matrix of mass (n x n, block structure above) and the first
    !> `rows` rows of c (rows x n, leading dimension nc). With r1, the first step of a solve for
    !> one right-hand side is taken too, r1 := M^-1 r1, in the LAPACK calls that give M^-1 C^T
    !> (solve then with `scaled`): the numbers apply_inverse_mass gives, at one call per part
    !> fewer.
    subroutine factor(self, mass, c, rows, error, r1)
        class(saddle_point_type), intent(inout) :: self
        !> Mass matrix [kg, kg m^2]
        real(wp), intent(in) :: mass(:, :)
        !> Constraint rows
        real(wp), intent(in) :: c(:, :)
        !> How many rows of c take part
        integer, intent(in) :: rows
        !> Set when a mass block is not positive definite or the constraints are dependent
        type(error_type), allocatable, intent(out) :: error
        !> Momentum rows of one right-hand side (n) on entry, M^-1 times them on exit
        real(wp), intent(inout), optional :: r1(:)
        integer :: p, i0, k, j, info

        self%rows = rows
        self%factorisations = self%factorisations + 1
        do p = 1, self%parts
            i0 = 6*(p - 1)
            self%part_mass(p) = mass(i0 + 1, i0 + 1)
            self%rotational(:, :, p) = mass(i0 + 4:i0 + 6, i0 + 4:i0 + 6)
            call dpotf2("L", 3, self%rotational(1, 1, p), 3, info)
            if (info > 0) then
                call fatal_error(error, "the rotational mass matrix of part number " &
                    & // to_text(p) // " is singular (Euler angles at sin(theta) " &
                    & // "= 0?): dpotf2 info " // to_text(info), stat_lapack)
                return
            end if
            call lapack_info_error("dpotf2", info, error)
            if (allocated(error)) return
        end do
        self%by_blocks = self%blocked .and. rows == self%nc .and. rows > 0
        if (self%by_blocks) then
            call factor_blocks(self, c, error, r1)
            if (allocated(error) .or. .not. present(r1)) return
            ! the parts no UCON touches, alone
            do p = 1, self%parts
                if (self%part_blocked(p)) cycle
                call inverse_mass_of_part(self, p, r1, error)
                if (allocated(error)) return
            end do
            return
        end if
        if (present(r1)) then
            call self%apply_inverse_mass(r1, 1, error)
            if (allocated(error)) return
        end if
        if (rows == 0) return
        do k = 1, rows
            self%minv_ct(:, k) = c(k, :)
        end do
        call self%apply_inverse_mass(self%minv_ct, rows, error)
        if (allocated(error)) return
        do j = 1, rows
            do k = 1, rows
                self%schur(k, j) = dot_product(c(k, :), self%minv_ct(:, j))
            end do
        end do
        call dgetf2(rows, rows, self%schur, self%nc, self%pivots, info)
        call lapack_info_error("dgetf2 (constraint Schur complement)", info, error)
    end subroutine factor

    !> Solve for m right-hand sides: r1 (n x m) becomes a, r2 (rows x m) becomes lambda;
    !> c must be the matrix given to factor.
    subroutine solve(self, c, r1, r2, m, error, scaled)
        class(saddle_point_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        !> Number of right-hand sides
        integer, intent(in) :: m
        !> Momentum rows on entry, accelerations on exit (leading dimension n)
        real(wp), intent(inout) :: r1(self%n, m)
        !> Constraint rows on entry, multipliers on exit (leading dimension rows)
        real(wp), intent(inout) :: r2(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        !> r1 holds M^-1 times the momentum rows already (factor's r1)
        logical, intent(in), optional :: scaled
        integer :: j, k, info
        logical :: done

        done = .false.
        if (present(scaled)) done = scaled
        if (.not. done) then
            call self%apply_inverse_mass(r1, m, error)
            if (allocated(error)) return
        end if
        if (self%rows == 0) return
        if (self%by_blocks) then
            call solve_blocks(self, c, r1, r2, m, error)
            return
        end if
        do j = 1, m
            do k = 1, self%rows
                r2(k, j) = r2(k, j) - dot_product(c(k, :), r1(:, j))
            end do
        end do
        call dgetrs("N", self%rows, m, self%schur, self%nc, self%pivots, r2, self%rows, info)
        call lapack_info_error("dgetrs (constraint Schur complement)", info, error)
        if (allocated(error)) return
        do j = 1, m
            do k = 1, self%rows
                r1(:, j) = r1(:, j) + r2(k, j)*self%minv_ct(:, k)
            end do
        end do
    end subroutine solve

    !> The block path of factor: M^-1 C^T over each block's parts and rows (and M^-1 r1 there,
    !> with r1), each block's S from its rows and coordinates, and its LU factors (dgetf2).
    subroutine factor_blocks(self, c, error, r1)
        type(saddle_point_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(inout), optional :: r1(:)
        integer :: b, i, j, k, kj, m, first, last, p, i0, info, s0, col, extra

        extra = merge(1, 0, present(r1))
        associate (blocks => self%blocks, rot => self%rotational_rows)
            do b = 1, blocks%count
                first = blocks%coordinate_start(b)
                last = blocks%coordinate_start(b + 1) - 1
                ! M^-1 c_k^T over the block's parts (zero elsewhere, as the dense path leaves
                ! it): per part, the translational rows divided by the mass, the rotational
                ! rows of every UCON of the block (and of r1) in one dpotrs, column by column
                ! the solves of one call per UCON
                do j = first, last, 6
                    i0 = blocks%coordinates(j) - 1
                    p = i0/6 + 1
                    if (present(r1)) then
                        r1(i0 + 1:i0 + 3) = r1(i0 + 1:i0 + 3)/self%part_mass(p)
                        rot(:, 1) = r1(i0 + 4:i0 + 6)
                    end if
                    col = extra
                    do i = blocks%row_start(b), blocks%row_start(b + 1) - 1
                        k = blocks%rows(i)
                        self%minv_ct(i0 + 1:i0 + 3, k) = c(k, i0 + 1:i0 + 3)/self%part_mass(p)
                        col = col + 1
                        rot(:, col) = c(k, i0 + 4:i0 + 6)
                    end do
                    call dpotrs("L", 3, col, self%rotational(1, 1, p), 3, rot, 3, info)
                    call lapack_info_error("dpotrs", info, error)
                    if (allocated(error)) return
                    if (present(r1)) r1(i0 + 4:i0 + 6) = rot(:, 1)
                    col = extra
                    do i = blocks%row_start(b), blocks%row_start(b + 1) - 1
                        col = col + 1
                        self%minv_ct(i0 + 4:i0 + 6, blocks%rows(i)) = rot(:, col)
                    end do
                end do
                m = blocks%row_start(b + 1) - blocks%row_start(b)
                s0 = self%schur_start(b) - 1
                do j = 1, m
                    kj = blocks%rows(blocks%row_start(b) + j - 1)
                    do i = 1, m
                        k = blocks%rows(blocks%row_start(b) + i - 1)
                        self%block_schur(s0 + i + m*(j - 1)) = block_dot(c, k, &
                            & self%minv_ct(:, kj), blocks%coordinates(first:last))
                    end do
                end do
                call dgetf2(m, m, self%block_schur(self%schur_start(b)), m, &
                    & self%pivots(blocks%row_start(b)), info)
                call lapack_info_error("dgetf2 (constraint Schur complement, a block)", info, &
                    & error)
                if (allocated(error)) return
            end do
        end associate
    end subroutine factor_blocks

    !> The block path of solve, after r1 := M^-1 r1: lambda block by block, then a.
    subroutine solve_blocks(self, c, r1, r2, m, error)
        type(saddle_point_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        integer, intent(in) :: m
        real(wp), intent(inout) :: r1(self%n, m), r2(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        integer :: b, i, j, k, rows_b, first, last, col, info

        associate (blocks => self%blocks)
            do b = 1, blocks%count
                first = blocks%coordinate_start(b)
                last = blocks%coordinate_start(b + 1) - 1
                rows_b = blocks%row_start(b + 1) - blocks%row_start(b)
                do col = 1, m
                    do i = 1, rows_b
                        k = blocks%rows(blocks%row_start(b) + i - 1)
                        self%gathered(i, col) = r2(k, col) - block_dot(c, k, r1(:, col), &
                            & blocks%coordinates(first:last))
                    end do
                end do
                call dgetrs("N", rows_b, m, self%block_schur(self%schur_start(b)), rows_b, &
                    & self%pivots(blocks%row_start(b)), self%gathered, size(self%gathered, 1), &
                    & info)
                call lapack_info_error("dgetrs (constraint Schur complement, a block)", info, &
                    & error)
                if (allocated(error)) return
                do col = 1, m
                    do i = 1, rows_b
                        r2(blocks%rows(blocks%row_start(b) + i - 1), col) = self%gathered(i, col)
                    end do
                end do
            end do
            ! a = M^-1 (r1 + C^T lambda): each row's column of M^-1 C^T over its block, rows in
            ! ascending order as the dense path adds them
            do col = 1, m
                do k = 1, self%rows
                    b = blocks%row_block(k)
                    do j = blocks%coordinate_start(b), blocks%coordinate_start(b + 1) - 1
                        i = blocks%coordinates(j)
                        r1(i, col) = r1(i, col) + r2(k, col)*self%minv_ct(i, k)
                    end do
                end do
            end do
        end associate
    end subroutine solve_blocks

    !> Row k of c times x over the given coordinates (ascending): the dense dot product's
    !> terms that are not exact zeros, in its order.
    pure function block_dot(c, k, x, coordinates) result(total)
        real(wp), intent(in) :: c(:, :), x(:)
        integer, intent(in) :: k, coordinates(:)
        real(wp) :: total
        integer :: j

        total = 0.0_wp
        do j = 1, size(coordinates)
            total = total + c(k, coordinates(j))*x(coordinates(j))
        end do
    end function block_dot

    !> x := M^-1 x over part p's rows, for one column x (n).
    subroutine inverse_mass_of_part(self, p, x, error)
        type(saddle_point_type), intent(in) :: self
        integer, intent(in) :: p
        real(wp), intent(inout) :: x(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: rotational_rows(3)
        integer :: i0, info

        i0 = 6*(p - 1)
        x(i0 + 1:i0 + 3) = x(i0 + 1:i0 + 3)/self%part_mass(p)
        rotational_rows = x(i0 + 4:i0 + 6)
        call dpotrs("L", 3, 1, self%rotational(1, 1, p), 3, rotational_rows, 3, info)
        call lapack_info_error("dpotrs", info, error)
        x(i0 + 4:i0 + 6) = rotational_rows
    end subroutine inverse_mass_of_part

    !> x := M^-1 x for the m columns of x (leading dimension n), part by part.
    subroutine apply_inverse_mass(self, x, m, error)
        class(saddle_point_type), intent(in) :: self
        real(wp), intent(inout) :: x(self%n, *)
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        integer :: p, i0, info

        do p = 1, self%parts
            i0 = 6*(p - 1)
            x(i0 + 1:i0 + 3, :m) = x(i0 + 1:i0 + 3, :m)/self%part_mass(p)
            ! rows i0+4..i0+6 of every column: the element x(i0 + 4, 1) with leading dimension n
            ! hands LAPACK that strided block without a copy
            call dpotrs("L", 3, m, self%rotational(1, 1, p), 3, x(i0 + 4, 1), self%n, info)
            call lapack_info_error("dpotrs", info, error)
            if (allocated(error)) return
        end do
    end subroutine apply_inverse_mass

end module rollcon_saddle_point
