! SPDX-License-Identifier: MIT
!> The output rows of a run: where and how often they are written, how many a request plans
!> (refused beyond a size limit), the layout of a problem's rows (rollcon_output_layout, the one
!> place that says which quantity sits in which column) and what fills a row.
module rollcon_output_rows
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_csv_writer, only : csv_row_bytes
    use rollcon_output_layout, only : output_layout_type, new_output_layout, name_length, &
        & coord_x, coord_phi, coord_xdot, coord_phidot
    implicit none
    private

    public :: run_options_type, planned_rows, output_layout, output_row
    public :: output_time

    !> Default limit of a planned CSV [bytes], 100 GB: ten thousand times the coin's run
    real(wp), parameter, public :: default_max_csv_bytes = 1.0e11_wp

    !> Where and how often to report
    type :: run_options_type
        !> Start and end time, output interval [s]
        real(wp) :: t0 = 0.0_wp, end_time = 1.0_wp, output_step = 0.01_wp
        !> The output times after t0 [s], ascending, the last at end_time, when they are not
        !> every output_step (several SIMULATE commands of a command file); unallocated: every
        !> output_step
        real(wp), allocatable :: output_times(:)
        !> CSV file to write (none when unallocated)
        character(len=:), allocatable :: csv_path
        !> Progress lines on stderr for runs longer than a second
        logical :: progress = .true.
        !> Largest CSV a run may plan to write [bytes]: a request beyond it is refused before
        !> the run (raise it to override; the default is far beyond a useful time history)
        real(wp) :: max_csv_bytes = default_max_csv_bytes
    end type run_options_type

contains

    !> The layout of a problem's output rows: its parts and UCONs in model order, then the
    !> columns of its watches in watch order.
    function output_layout(problem) result(layout)
        type(problem_type), intent(in) :: problem
        type(output_layout_type) :: layout
        integer :: part_ids(size(problem%model%parts)), ucon_ids(problem%ucon_count()), k
        character(len=name_length), allocatable :: extra(:), names(:), grown(:)

        do k = 1, size(part_ids)
            part_ids(k) = problem%model%parts(k)%id
        end do
        do k = 1, size(ucon_ids)
            ucon_ids(k) = problem%ucon_id(k)
        end do
        allocate(extra(0))
        do k = 1, size(problem%watches)
            call problem%watches(k)%watch%column_names(problem%eq, names)
            ! element by element: gfortran 12 gives an array constructor of these a wrong length
            allocate(grown(size(extra) + size(names)))
            grown(:size(extra)) = extra
            grown(size(extra) + 1:) = names
            call move_alloc(grown, extra)
        end do
        layout = new_output_layout(part_ids, ucon_ids, extra)
    end function output_layout

    !> The output row at (time, q, u), in the columns of layout (output_layout(problem)), with
    !> the energy, each UCON's residual and multiplier as the last accelerations call left
    !> them at this state, and each watch's columns (the watches take their measures here, and
    !> the accelerations problem%a that call left).
    !> The multipliers are those reported (the equations' reported_multipliers: the split of
    !> least norm where rows are set aside as redundant; NaN, which the caller refuses, should
    !> that solve fail). The problem is prepared (problem%prepare).
    function output_row(problem, layout, time, q, u) result(row)
        type(problem_type), intent(inout) :: problem
        type(output_layout_type), intent(in) :: layout
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of every part [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: row(layout%columns())
        real(wp) :: lambda(size(problem%lambda))
        type(error_type), allocatable :: error
        integer :: p, k, i0, first, count

        call problem%eq%reported_multipliers(problem%lambda, lambda, error)
        if (allocated(error)) lambda = ieee_value(1.0_wp, ieee_quiet_nan)
        row(1) = time
        do p = 1, size(layout%part_ids)
            i0 = 6*(p - 1)
            row(layout%part_column(p, coord_x):layout%part_column(p, coord_phi)) = q(i0 + 1:i0 + 6)
            row(layout%part_column(p, coord_xdot):layout%part_column(p, coord_phidot)) &
                & = u(i0 + 1:i0 + 6)
        end do
        row(layout%energy_column()) = problem%eq%energy(q, u)
        do k = 1, size(layout%ucon_ids)
            row(layout%residual_column(k)) = problem%eq%constraints%value(k)
            row(layout%multiplier_column(k)) = lambda(k)
        end do
        first = layout%energy_column() + 2*size(layout%ucon_ids) + 1
        do k = 1, size(problem%watches)
            count = problem%watch_columns(k)
            call problem%watches(k)%watch%take_accelerations(problem%eq, problem%a)
            call problem%watches(k)%watch%fill_columns(problem%eq, time, q, u, lambda, &
                & row(first:first + count - 1))
            first = first + count
        end do
    end function output_row

    !> The k-th output time after t0 [s]: options%output_times(k) when given, else
    !> t0 + k output_step (at most end_time).
    pure real(wp) function output_time(options, k) result(t)
        type(run_options_type), intent(in) :: options
        integer(int64), intent(in) :: k

        if (allocated(options%output_times)) then
            t = options%output_times(k)
        else
            t = min(options%t0 + real(k, wp)*options%output_step, options%end_time)
        end if
    end function output_time

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
        if (allocated(options%output_times)) steps = real(size(options%output_times), wp)
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
