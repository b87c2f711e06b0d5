! SPDX-License-Identifier: MIT
!> A run's results as bytes (rollcon_wire) and back: the summary, the rows' layout and the
!> parts' shapes, as a run in a child process hands them to its parent (rollcon_isolated_run).
!> Every field is packed; what is read back equals what was packed (a test holds it).
module rollcon_run_wire
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_wire, only : wire_writer_type, wire_reader_type
    use rollcon_output_layout, only : output_layout_type, new_output_layout, name_length
    use rollcon_run_summary, only : run_summary_type
    use rollcon_watch, only : watch_measure_type
    use rollcon_part_shapes, only : part_shape_type
    implicit none
    private

    public :: pack_summary, unpack_summary, pack_layout, unpack_layout, pack_shapes, &
        & unpack_shapes

contains

    !> The layout: part ids, UCON ids, the watches' column names.
    subroutine pack_layout(wire, layout)
        type(wire_writer_type), intent(inout) :: wire
        type(output_layout_type), intent(in) :: layout
        integer :: k

        call wire%put_ints(layout%part_ids)
        call wire%put_ints(layout%ucon_ids)
        call wire%put_int(int(size(layout%extra), int64))
        do k = 1, size(layout%extra)
            call wire%put_text(trim(layout%extra(k)))
        end do
    end subroutine pack_layout

    subroutine unpack_layout(wire, layout)
        type(wire_reader_type), intent(inout) :: wire
        type(output_layout_type), intent(out) :: layout
        integer, allocatable :: part_ids(:), ucon_ids(:)
        character(len=name_length), allocatable :: extra(:)
        integer(int64) :: count
        integer :: k

        call wire%get_ints(part_ids)
        call wire%get_ints(ucon_ids)
        count = wire%get_int()
        if (count < 0 .or. count > 100000) then
            wire%failed = .true.
            count = 0
        end if
        allocate(extra(count))
        do k = 1, size(extra)
            extra(k) = wire%get_text()
        end do
        layout = new_output_layout(part_ids, ucon_ids, extra)
    end subroutine unpack_layout

    !> Every field of the summary.
    subroutine pack_summary(wire, summary)
        type(wire_writer_type), intent(inout) :: wire
        type(run_summary_type), intent(in) :: summary
        integer :: k

        call wire%put_int(int(summary%status, int64))
        call wire%put_text(text_of(summary%message))
        call wire%put_text(text_of(summary%limit))
        call wire%put_int(int(summary%solver_flag, int64))
        call wire%put_real(summary%t_reached)
        call wire%put_reals(reals_of(summary%q))
        call wire%put_reals(reals_of(summary%u))
        call wire%put_real(summary%energy_reference)
        call wire%put_real(summary%energy_drift)
        call wire%put_real(summary%energy_scale)
        call wire%put_real(summary%energy_step)
        call wire%put_real(summary%constraint_work)
        call wire%put_real(summary%dissipated_work)
        call wire%put_real(summary%friction_work)
        call wire%put_real(summary%impact_work)
        call wire%put_real(summary%drive_work)
        call wire%put_real(summary%dissipation_uncertainty)
        call wire%put_logical(summary%dissipation_resolved)
        call wire%put_logical(summary%energy_conserved)
        call pack_layout(wire, summary%layout)
        call wire%put_real(summary%residual_max)
        call wire%put_reals(reals_of(summary%ucon_residual_max))
        if (allocated(summary%ucon_position)) then
            call wire%put_logicals(summary%ucon_position)
        else
            call wire%put_logicals([logical ::])
        end if
        call wire%put_real(summary%energy_bound)
        call wire%put_int(int(count_of_measures(summary), int64))
        do k = 1, count_of_measures(summary)
            call pack_measure(wire, summary%measures(k))
        end do
        call wire%put_text(text_of(summary%watch_lines))
        call wire%put_text(text_of(summary%routines))
        call wire%put_text(text_of(summary%ucon_labels))
        if (allocated(summary%rebasings)) then
            call wire%put_ints(summary%rebasings)
        else
            call wire%put_ints([integer ::])
        end if
        call wire%put_ints([summary%steps, summary%functions, summary%jacobians, &
            & summary%failures, summary%root_evaluations, merge(1, 0, summary%sparse_newton)])
        call wire%put_int(summary%rows)
        call wire%put_real(summary%cpu_seconds)
        call wire%put_text(text_of(summary%analysis_lines))
    end subroutine pack_summary

    subroutine unpack_summary(wire, summary)
        type(wire_reader_type), intent(inout) :: wire
        type(run_summary_type), intent(out) :: summary
        integer, allocatable :: counts(:)
        integer(int64) :: n
        integer :: k

        summary%status = int(wire%get_int())
        summary%message = wire%get_text()
        summary%limit = wire%get_text()
        summary%solver_flag = int(wire%get_int())
        summary%t_reached = wire%get_real()
        call wire%get_reals(summary%q)
        call wire%get_reals(summary%u)
        summary%energy_reference = wire%get_real()
        summary%energy_drift = wire%get_real()
        summary%energy_scale = wire%get_real()
        summary%energy_step = wire%get_real()
        summary%constraint_work = wire%get_real()
        summary%dissipated_work = wire%get_real()
        summary%friction_work = wire%get_real()
        summary%impact_work = wire%get_real()
        summary%drive_work = wire%get_real()
        summary%dissipation_uncertainty = wire%get_real()
        summary%dissipation_resolved = wire%get_logical()
        summary%energy_conserved = wire%get_logical()
        call unpack_layout(wire, summary%layout)
        summary%residual_max = wire%get_real()
        call wire%get_reals(summary%ucon_residual_max)
        call wire%get_logicals(summary%ucon_position)
        summary%energy_bound = wire%get_real()
        n = wire%get_int()
        if (n < 0 .or. n > 1000) then
            wire%failed = .true.
            n = 0
        end if
        allocate(summary%measures(n))
        do k = 1, size(summary%measures)
            call unpack_measure(wire, summary%measures(k))
        end do
        summary%watch_lines = wire%get_text()
        summary%routines = wire%get_text()
        summary%ucon_labels = wire%get_text()
        call wire%get_ints(summary%rebasings)
        call wire%get_ints(counts)
        if (size(counts) == 6) then
            summary%steps = counts(1)
            summary%functions = counts(2)
            summary%jacobians = counts(3)
            summary%failures = counts(4)
            summary%root_evaluations = counts(5)
            summary%sparse_newton = counts(6) == 1
        else
            wire%failed = .true.
        end if
        summary%rows = wire%get_int()
        summary%cpu_seconds = wire%get_real()
        summary%analysis_lines = wire%get_text()
    end subroutine unpack_summary

    subroutine pack_measure(wire, measure)
        type(wire_writer_type), intent(inout) :: wire
        type(watch_measure_type), intent(in) :: measure

        call wire%put_text(text_of(measure%name))
        call wire%put_text(text_of(measure%label))
        call wire%put_text(text_of(measure%unit))
        call wire%put_real(measure%value)
        call wire%put_real(measure%bound)
        call wire%put_text(text_of(measure%bound_rule))
        call wire%put_text(text_of(measure%remedy))
    end subroutine pack_measure

    subroutine unpack_measure(wire, measure)
        type(wire_reader_type), intent(inout) :: wire
        type(watch_measure_type), intent(out) :: measure

        measure%name = wire%get_text()
        measure%label = wire%get_text()
        measure%unit = wire%get_text()
        measure%value = wire%get_real()
        measure%bound = wire%get_real()
        measure%bound_rule = wire%get_text()
        measure%remedy = wire%get_text()
    end subroutine unpack_measure

    !> The parts' shapes: id, kind, radius, thickness, semi-axes of each.
    subroutine pack_shapes(wire, shapes)
        type(wire_writer_type), intent(inout) :: wire
        type(part_shape_type), intent(in) :: shapes(:)
        integer :: k

        call wire%put_int(int(size(shapes), int64))
        do k = 1, size(shapes)
            call wire%put_ints([shapes(k)%id, shapes(k)%kind])
            call wire%put_reals([shapes(k)%radius, shapes(k)%thickness, shapes(k)%semi_axes])
        end do
    end subroutine pack_shapes

    subroutine unpack_shapes(wire, shapes)
        type(wire_reader_type), intent(inout) :: wire
        type(part_shape_type), allocatable, intent(out) :: shapes(:)
        integer, allocatable :: codes(:)
        real(wp), allocatable :: lengths(:)
        integer(int64) :: n
        integer :: k

        n = wire%get_int()
        if (n < 0 .or. n > 100000) then
            wire%failed = .true.
            n = 0
        end if
        allocate(shapes(n))
        do k = 1, size(shapes)
            call wire%get_ints(codes)
            call wire%get_reals(lengths)
            if (size(codes) /= 2 .or. size(lengths) /= 5) then
                wire%failed = .true.
                return
            end if
            shapes(k)%id = codes(1)
            shapes(k)%kind = codes(2)
            shapes(k)%radius = lengths(1)
            shapes(k)%thickness = lengths(2)
            shapes(k)%semi_axes = lengths(3:5)
        end do
    end subroutine unpack_shapes

    pure function text_of(text) result(copy)
        character(len=:), allocatable, intent(in) :: text
        character(len=:), allocatable :: copy

        copy = ""
        if (allocated(text)) copy = text
    end function text_of

    pure function reals_of(values) result(copy)
        real(wp), allocatable, intent(in) :: values(:)
        real(wp), allocatable :: copy(:)

        allocate(copy(0))
        if (allocated(values)) copy = values
    end function reals_of

    pure integer function count_of_measures(summary) result(n)
        type(run_summary_type), intent(in) :: summary

        n = 0
        if (allocated(summary%measures)) n = size(summary%measures)
    end function count_of_measures

end module rollcon_run_wire
