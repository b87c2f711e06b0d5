! SPDX-License-Identifier: MIT
!> A partition of the rates u into dependent and independent speeds (coordinate partitioning,
!> docs/design.md §4): the velocity-level constraint matrix C (nc x n, full row rank) has nc
!> columns chosen by LAPACK's QR with column pivoting (dgeqp3), the dependent speeds; the
!> n - nc others are the independent speeds an integrator carries. With C_d the chosen
!> columns, C u = b gives u_d = C_d^-1 (b - C_i u_i), solved with C_d's LU factors (dgetf2,
!> dgetrs). How well the choice still suits the state is the growth of the dependent speeds,
!> the largest entry of C_d^-1 C_i (how much an error of an independent speed is amplified in
!> a dependent one; QR with pivoting keeps it small when it chooses), against its value at
!> the choice. Nothing here allocates after init.
module rollcon_speed_partition
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_lapack
    use rollcon_lapack, only : dgeqp3, dgetf2, dgetrs, lapack_info_error
    implicit none
    private

    public :: speed_partition_type, worn_ratio

    !> A partition is worn when the growth of its dependent speeds has risen above its value at
    !> the choice divided by this (and QR with pivoting would now choose other columns): the
    !> dependent speeds' errors grow with it. Measured on data/chaplygin_sled.adm (ERROR =
    !> 1e-10, the knife edge's columns turning with the sled), energy drift 3.2e-9 at 0.3
    !> against 1.5e-9 for the ODE form; with C_d's condition number as the measure instead,
    !> 1.4e-6 at a ratio of 1e-2, 8.8e-9 at 0.1, 4.3e-9 at 0.3
    real(wp), parameter :: worn_ratio = 0.3_wp

    !> The chosen partition, C_d's factors and the workspace of the choice
    type :: speed_partition_type
        !> Rates and constraint rows
        integer :: n = 0, nc = 0
        !> Numbers of the dependent (nc) and independent (n - nc) rates, each ascending
        integer, allocatable :: dependent(:), independent(:)
        !> LU factors of C_d (nc x nc) and their pivots
        real(wp), allocatable :: lu(:, :)
        integer, allocatable :: pivots(:)
        !> The growth max |C_d^-1 C_i| when the partition was chosen [-]
        real(wp) :: growth_chosen = 1.0_wp
        !> Partitions chosen since init
        integer :: choices = 0
        !> Workspace of dgeqp3 and of the growth, C_d^-1 C_i (nc x (n - nc))
        real(wp), allocatable :: qr(:, :), tau(:), work(:), basis(:, :)
        integer, allocatable :: jpvt(:)
        !> The dependent speeds before a trial choice (worn)
        integer, allocatable :: previous(:)
    contains
        procedure :: init
        procedure :: choose
        procedure :: factor
        procedure :: solve
        procedure :: growth
        procedure :: worn
    end type speed_partition_type

contains

    !> Size for n rates and nc constraint rows (nc <= n); the identity partition (the last
    !> n - nc rates independent) until the first choice.
    subroutine init(self, n, nc)
        class(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: n, nc
        real(wp) :: query(1)
        integer :: info, j, lwork

        self%n = n
        self%nc = nc
        self%choices = 0
        self%growth_chosen = 1.0_wp
        if (allocated(self%dependent)) deallocate(self%dependent, self%independent, self%lu, &
            & self%pivots, self%qr, self%tau, self%work, self%jpvt, self%basis, self%previous)
        allocate(self%dependent(nc), self%independent(n - nc), self%previous(nc))
        self%dependent = [(j, j = 1, nc)]
        self%independent = [(j, j = nc + 1, n)]
        allocate(self%lu(max(nc, 1), max(nc, 1)), self%qr(max(nc, 1), n), source=0.0_wp)
        allocate(self%pivots(max(nc, 1)), self%jpvt(n), source=0)
        allocate(self%basis(max(nc, 1), max(n - nc, 1)), source=0.0_wp)
        allocate(self%tau(max(min(nc, n), 1)), source=0.0_wp)
        ! workspace query of dgeqp3 (lwork = -1)
        lwork = 3*n + 1
        if (nc > 0) then
            call dgeqp3(nc, n, self%qr, nc, self%jpvt, self%tau, query, -1, info)
            if (info == 0) lwork = max(lwork, int(query(1)))
        end if
        allocate(self%work(max(lwork, 1)), source=0.0_wp)
    end subroutine init

    !> Choose the partition for the constraint matrix c (nc x n): the first nc columns of
    !> QR with column pivoting are the dependent speeds; then factor C_d. An error when c has
    !> not full row rank (the dependent block is singular).
    subroutine choose(self, c, error)
        class(speed_partition_type), intent(inout) :: self
        !> Velocity-level constraint rows [UCON unit per rate unit]
        real(wp), intent(in) :: c(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer :: info

        self%choices = self%choices + 1
        if (self%nc == 0) return
        self%qr(:self%nc, :) = c(:self%nc, :)
        self%jpvt = 0
        call dgeqp3(self%nc, self%n, self%qr, self%nc, self%jpvt, self%tau, self%work, &
            & size(self%work), info)
        call lapack_info_error("dgeqp3 (speed partition)", info, error)
        if (allocated(error)) return
        ! ascending order within each set: the state's columns read as the rates' own
        self%dependent = sorted(self%jpvt(:self%nc))
        call set_independent(self)
        call self%factor(c, error)
        if (allocated(error)) return
        self%growth_chosen = self%growth(c)
    end subroutine choose

    !> LU factors of C_d = c(:, dependent).
    subroutine factor(self, c, error)
        class(speed_partition_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer :: info, k

        if (self%nc == 0) return
        do k = 1, self%nc
            self%lu(:self%nc, k) = c(:self%nc, self%dependent(k))
        end do
        call dgetf2(self%nc, self%nc, self%lu, size(self%lu, 1), self%pivots, info)
        if (info > 0) then
            call fatal_error(error, "the constraint rows are dependent where the speeds " &
                & // "were partitioned (a singular block C_d: dgetf2 info > 0)", stat_lapack)
            return
        end if
        call lapack_info_error("dgetf2 (dependent speeds)", info, error)
    end subroutine factor

    !> x := C_d^-1 x for m columns of x (leading dimension nc), with the last factors.
    subroutine solve(self, x, m, error)
        class(speed_partition_type), intent(inout) :: self
        integer, intent(in) :: m
        real(wp), intent(inout) :: x(self%nc, m)
        type(error_type), allocatable, intent(out) :: error
        integer :: info

        if (self%nc == 0) return
        call dgetrs("N", self%nc, m, self%lu, size(self%lu, 1), self%pivots, x, self%nc, info)
        call lapack_info_error("dgetrs (dependent speeds)", info, error)
    end subroutine solve

    !> The growth max |C_d^-1 C_i| for the matrix c, with the factors of the last factor call,
    !> which must be of this c (0 without independent speeds; huge when the solve fails).
    function growth(self, c) result(largest)
        class(speed_partition_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        real(wp) :: largest
        type(error_type), allocatable :: error
        integer :: j, ni

        largest = 0.0_wp
        ni = self%n - self%nc
        if (self%nc == 0 .or. ni == 0) return
        do j = 1, ni
            self%basis(:self%nc, j) = c(:self%nc, self%independent(j))
        end do
        call self%solve(self%basis, ni, error)
        largest = huge(1.0_wp)
        if (.not. allocated(error)) largest = maxval(abs(self%basis(:self%nc, :ni)))
    end function growth

    !> True when the partition no longer suits c: C_d (factored again here) singular, or its
    !> growth above the choice's divided by worn_ratio while QR with pivoting would now choose
    !> other columns. When it would choose the same, the partition stays, with the growth of
    !> now as its reference. The partition itself is never changed
    !> here (the integrator's state is in its speeds): a worn one is chosen again by choose.
    function worn(self, c) result(is_worn)
        class(speed_partition_type), intent(inout) :: self
        real(wp), intent(in) :: c(:, :)
        logical :: is_worn
        type(error_type), allocatable :: error
        real(wp) :: now, old_growth
        integer :: old_choices

        is_worn = .false.
        if (self%nc == 0) return
        call self%factor(c, error)
        is_worn = allocated(error)
        if (is_worn) return
        now = self%growth(c)
        if (worn_ratio*now <= self%growth_chosen) return
        self%previous = self%dependent
        old_growth = self%growth_chosen
        old_choices = self%choices
        call self%choose(c, error)
        self%choices = old_choices
        is_worn = allocated(error) .or. any(self%dependent /= self%previous)
        if (.not. is_worn) then
            self%growth_chosen = now
            return
        end if
        ! back to the partition the state is in
        self%dependent = self%previous
        call set_independent(self)
        self%growth_chosen = old_growth
        call self%factor(c, error)
    end function worn

    !> The independent speeds: the rates not dependent, ascending.
    subroutine set_independent(self)
        type(speed_partition_type), intent(inout) :: self
        integer :: j, m

        m = 0
        do j = 1, self%n
            if (any(self%dependent == j)) cycle
            m = m + 1
            self%independent(m) = j
        end do
    end subroutine set_independent

    !> The values in ascending order (insertion sort: nc is small).
    pure function sorted(values) result(ordered)
        integer, intent(in) :: values(:)
        integer :: ordered(size(values))
        integer :: i, j, key

        ordered = values
        do i = 2, size(ordered)
            key = ordered(i)
            j = i - 1
            do while (j >= 1)
                if (ordered(j) <= key) exit
                ordered(j + 1) = ordered(j)
                j = j - 1
            end do
            ordered(j + 1) = key
        end do
    end function sorted

end module rollcon_speed_partition
