! SPDX-License-Identifier: MIT
!> The output rows of a run: where and how often they are written, how many a request plans
!> (refused beyond a size limit), their columns, the CSV header naming them, and the rows kept
!> in memory (history) for tests and benchmarks. What fills a row is rollcon_simulation's.
module rollcon_output_rows
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_csv_writer, only : csv_row_bytes
    implicit none
    private

    public :: run_options_type, planned_rows, history_type, csv_header

    !> Default limit of a planned CSV [bytes], 100 GB: ten thousand times the coin's run
    real(wp), parameter, public :: default_max_csv_bytes = 1.0e11_wp

    !> Where and how often to report
    type :: run_options_type
        !> Start and end time, output interval [s]
        real(wp) :: t0 = 0.0_wp, end_time = 1.0_wp, output_step = 0.01_wp
        !> CSV file to write (none when unallocated)
        character(len=:), allocatable :: csv_path
        !> Progress lines on stderr for runs longer than a second
        logical :: progress = .true.
        !> Largest CSV a run may plan to write [bytes]: a request beyond it is refused before
        !> the run (raise it to override; the default is far beyond a useful time history)
        real(wp) :: max_csv_bytes = default_max_csv_bytes
    end type run_options_type

    !> Columns of the output rows (CSV and history)
    integer, parameter, public :: column_time = 1, column_x = 2, column_y = 3, column_z = 4, &
        & column_psi = 5, column_theta = 6, column_phi = 7, column_xdot = 8, column_ydot = 9, &
        & column_zdot = 10, column_psidot = 11, column_thetadot = 12, column_phidot = 13, &
        & column_energy = 14, column_fx = 15, column_fy = 16, column_fz = 17, &
        & column_normal = 18, column_mu = 19, column_residual = 20

    !> The output rows kept in memory (the CSV's columns), for tests and benchmarks
    type :: history_type
        !> rows(:, i) is output row i; only the first count rows are filled
        real(wp), allocatable :: rows(:, :)
        integer :: count = 0
    contains
        procedure :: add => history_add
        procedure :: column => history_column
    end type history_type

contains

    !> Append a row, growing the storage geometrically.
    pure subroutine history_add(self, row)
        class(history_type), intent(inout) :: self
        real(wp), intent(in) :: row(:)
        real(wp), allocatable :: grown(:, :)

        if (.not. allocated(self%rows)) allocate(self%rows(size(row), 256))
        if (self%count == size(self%rows, 2)) then
            allocate(grown(size(row), 2*self%count))
            grown(:, :self%count) = self%rows(:, :self%count)
            call move_alloc(grown, self%rows)
        end if
        self%count = self%count + 1
        self%rows(:, self%count) = row
    end subroutine history_add

    !> Column j over the filled rows.
    pure function history_column(self, j) result(values)
        class(history_type), intent(in) :: self
        integer, intent(in) :: j
        real(wp), allocatable :: values(:)

        values = self%rows(j, :self%count)
    end function history_column

    !> Column names of the CSV: time, part 1's coordinates and rates (SI units, radians),
    !> energy, constraint force on part 1, its normal part, the friction coefficient it needs,
    !> each UCON's residual, and the watched part's height residual Z - R sin(theta) [m] when
    !> the problem has a contact radius.
    function csv_header(problem) result(header)
        type(problem_type), intent(in) :: problem
        character(len=16), allocatable :: header(:)
        integer :: k

        header = [character(len=16) :: "t", "X", "Y", "Z", "psi", "theta", "phi", "Xdot", &
            & "Ydot", "Zdot", "psidot", "thetadot", "phidot", "E", "Fx", "Fy", "Fz", "Fn", &
            & "mu_needed"]
        do k = 1, problem%ucon_count()
            header = [character(len=16) :: header, "F" // to_text(problem%ucon_id(k))]
        end do
        if (problem%events%contact_radius > 0.0_wp) &
            & header = [character(len=16) :: header, "height_residual"]
    end function csv_header


    !> Number of output steps after the first row (64 bits); refused when the CSV they would
    !> fill is larger than options%max_csv_bytes, or the count does not fit in 64 bits.
    subroutine planned_rows(options, columns, n_output, error)
        type(run_options_type), intent(in) :: options
        !> Columns of a row
        integer, intent(in) :: columns
        integer(int64), intent(out) :: n_output
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: steps, bytes
        character(len=:), allocatable :: rows, bytes_text

        ! 1e-9: an end time a rounding short of a whole number of steps adds no step.
        steps = max(1.0_wp, ceiling_real((options%end_time - options%t0)/options%output_step &
            & - 1.0e-9_wp))
        bytes = (steps + 1.0_wp)*real(csv_row_bytes(columns), wp)
        n_output = 1
        rows = to_text(steps + 1.0_wp)
        bytes_text = to_text(bytes)
        if (steps < 1.0e18_wp) rows = to_text(int(steps, int64) + 1_int64)
        ! exact while it fits in 64 bits (huge(int64) ~ 9.2e18)
        if (bytes < 9.0e18_wp) bytes_text = to_text((int(steps, int64) + 1_int64) &
            & *int(csv_row_bytes(columns), int64))
        if (allocated(options%csv_path) .and. bytes > options%max_csv_bytes) then
            call fatal_error(error, "the output request (end_time " // to_text(options%end_time) &
                & // " s, output_step " // to_text(options%output_step) // " s) means " &
                & // rows // " rows, " // bytes_text &
                & // " bytes of CSV, beyond the limit of " // to_text(options%max_csv_bytes) &
                & // " bytes: raise output_step or lower end_time (or lift the limit " &
                & // "explicitly, rollcon run --allow-large-output)", stat_input)
        else if (.not. steps < real(huge(n_output), wp)/2.0_wp) then
            call fatal_error(error, "the output request (end_time " // to_text(options%end_time) &
                & // " s, output_step " // to_text(options%output_step) // " s) means " &
                & // rows // " rows, more than a 64-bit count holds", stat_input)
        else
            n_output = int(steps, int64)
        end if
    end subroutine planned_rows

    !> ceiling of a real of any size, as a real (no integer overflow).
    elemental function ceiling_real(x) result(c)
        real(wp), intent(in) :: x
        real(wp) :: c

        c = aint(x)
        if (c < x) c = c + 1.0_wp
    end function ceiling_real

end module rollcon_output_rows
