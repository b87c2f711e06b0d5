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
!> the whole (n + nc) x (n + nc) matrix. Nothing here allocates after init.
module rollcon_saddle_point
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_text, only : to_text
    use rollcon_lapack, only : dgetf2, dgetrs, dpotf2, dpotrs, lapack_info_error
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
    contains
        procedure :: init
        procedure :: factor
        procedure :: solve
        procedure :: apply_inverse_mass
    end type saddle_point_type

contains

    !> Size the workspace for n coordinates (6 per part) and at most nc constraint rows.
    subroutine init(self, n, nc)
        class(saddle_point_type), intent(inout) :: self
        integer, intent(in) :: n, nc

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
    end subroutine init

    !> Factor the saddle-point matrix of mass (n x n, block structure above) and the first
    !> `rows` rows of c (rows x n, leading dimension nc).
    subroutine factor(self, mass, c, rows, error)
        class(saddle_point_type), intent(inout) :: self
        !> Mass matrix [kg, kg m^2]
        real(wp), intent(in) :: mass(:, :)
        !> Constraint rows
        real(wp), intent(in) :: c(:, :)
        !> How many rows of c take part
        integer, intent(in) :: rows
        !> Set when a mass block is not positive definite or the constraints are dependent
        type(error_type), allocatable, intent(out) :: error
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
    subroutine solve(self, c, r1, r2, m, error)
        class(saddle_point_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        !> Number of right-hand sides
        integer, intent(in) :: m
        !> Momentum rows on entry, accelerations on exit (leading dimension n)
        real(wp), intent(inout) :: r1(self%n, m)
        !> Constraint rows on entry, multipliers on exit (leading dimension rows)
        real(wp), intent(inout) :: r2(self%rows, m)
        type(error_type), allocatable, intent(out) :: error
        integer :: j, k, info

        call self%apply_inverse_mass(r1, m, error)
        if (allocated(error)) return
        if (self%rows == 0) return
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
