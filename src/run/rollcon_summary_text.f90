! SPDX-License-Identifier: MIT
!> A run's summary as text, for any model: a setting line given by the caller (a scene's or a
!> dataset's), the status, the final state of every part named by its id, the energy drift, the
!> largest residual of every UCON, the watches' lines and measures (the re-basings of a model
!> that re-bases, the height residual of a rim contact), the integrator's counters, the CPU
!> time and the output file.
module rollcon_summary_text
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text, es_text
    use rollcon_run_summary, only : run_summary_type, status_completed, status_stopped, &
        & status_inaccurate
    implicit none
    private

    public :: run_summary_text

    !> The 12 quantities of a part with their units, in the order of q and u
    character(len=16), parameter :: quantity_names(12) = [character(len=16) :: "X [m]", &
        & "Y [m]", "Z [m]", "psi [rad]", "theta [rad]", "phi [rad]", "Xdot [m/s]", &
        & "Ydot [m/s]", "Zdot [m/s]", "psidot [rad/s]", "thetadot [rad/s]", "phidot [rad/s]"]
    character(len=*), parameter :: nl = new_line("a")

contains

    !> The summary of a run as lines of text (no final new line).
    function run_summary_text(setting, csv_path, summary) result(text)
        !> First line: what was run and how (e.g. "scene coin (data/coin.nml): IDA ...")
        character(len=*), intent(in) :: setting
        !> The CSV the rows went to
        character(len=*), intent(in) :: csv_path
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text

        text = setting // nl
        select case (summary%status)
        case (status_completed)
            text = text // "status: completed at t = " // to_text(summary%t_reached) // " s" // nl
        case (status_stopped)
            text = text // "status: stopped: " // summary%message // nl
        case (status_inaccurate)
            text = text // "status: INACCURATE: " // summary%message // nl
        case default
            text = text // "status: FAILED: " // summary%message // nl
        end select
        if (allocated(summary%analysis_lines)) text = text // summary%analysis_lines
        text = text // final_state(summary)
        text = text // energy_line(summary) // nl
        text = text // residual_lines(summary)
        if (allocated(summary%routines)) then
            if (len(summary%routines) > 0) text = text // "routines: " // summary%routines // nl
        end if
        if (allocated(summary%watch_lines)) text = text // summary%watch_lines
        text = text // measure_lines(summary)
        text = text // "steps " // to_text(summary%steps) // ", function evaluations " &
            & // to_text(summary%functions) // ", Jacobian evaluations " &
            & // to_text(summary%jacobians) // ", error-test failures " &
            & // to_text(summary%failures)
        if (summary%sparse_newton) text = text // ", Newton matrix sparse (KLU)"
        if (summary%corner_restarts > 0) text = text // ", started again at " &
            & // to_text(summary%corner_restarts) // " corner(s) of the inputs"
        text = text // nl
        text = text // "CPU time: " // fixed(summary%cpu_seconds) // " s" // nl
        text = text // "output: " // csv_path // " (" // to_text(summary%rows) // " rows)"
    end function run_summary_text

    !> "energy drift: 7.708E-008 of the energy scale 1.226 J (largest |E - E0| 9.452E-008 J, E0 =
    !> -1.22625 J after the last applied force), allowed 7.5E-007" (rollcon_drift), or why it
    !> is not judged.
    function energy_line(summary) result(text)
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text

        if (summary%energy_scale > 0.0_wp .and. (summary%dissipated_work /= 0.0_wp .or. &
            & summary%drive_work /= 0.0_wp)) then
            ! a dissipation: the energy plus the work it took is what is conserved, less the
            ! work a turntable's drive did in the impacts on it (D)
            text = "energy drift: " // scientific(summary%energy_drift) &
                & // " of the energy scale " // scientific(summary%energy_scale) &
                & // " J (largest |E + W" // trim(merge(" - D", "    ", &
                & summary%drive_work /= 0.0_wp)) // " - E0| " &
                & // scientific(summary%energy_drift*summary%energy_scale) // " J, W the " &
                & // scientific(summary%dissipated_work) // " J dissipated" &
                & // dissipation_parts(summary)
            if (summary%drive_work /= 0.0_wp) text = text // ", D the " &
                & // scientific(summary%drive_work) // " J the table's drive did in the impacts"
            text = text // ", E0 = " &
                & // to_text(summary%energy_reference) // " J after the last applied force)" &
                & // allowed(summary%energy_bound, "")
        else if (summary%energy_scale > 0.0_wp) then
            text = "energy drift: " // scientific(summary%energy_drift) &
                & // " of the energy scale " // scientific(summary%energy_scale) &
                & // " J (largest |E - E0| " &
                & // scientific(summary%energy_drift*summary%energy_scale) // " J, E0 = " &
                & // to_text(summary%energy_reference) // " J after the last applied force)" &
                & // allowed(summary%energy_bound, "")
        else
            text = "energy drift: none to judge (nothing moved after the last applied force, " &
                & // "E0 = " // to_text(summary%energy_reference) // " J)"
        end if
        if (.not. summary%energy_conserved) then
            text = text // "; not judged: an applied force acting until the end, or a moving " &
                & // "constraint, does work"
        else if (.not. summary%dissipation_resolved) then
            text = text // "; not judged: the output rows do not resolve the dissipated " &
                & // "power (W known to " // scientific(summary%dissipation_uncertainty) &
                & // " J, more than the drift allowed; a finer output_step resolves it)"
        end if
    end function energy_line

    !> What W holds when a contact's friction or impacts took part of it: " by friction
    !> 1.234E-02 J, impacts 5.000E-03 J, rolling resistance and air 1.000E-04 J" (each part
    !> that is not 0); "" when W is a rim's rolling resistance and air alone.
    function dissipation_parts(summary) result(text)
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text
        real(wp) :: rim

        text = ""
        if (summary%friction_work == 0.0_wp .and. summary%impact_work == 0.0_wp) return
        rim = summary%dissipated_work - summary%friction_work - summary%impact_work
        if (summary%friction_work /= 0.0_wp) text = text // ", friction " &
            & // scientific(summary%friction_work) // " J"
        if (summary%impact_work /= 0.0_wp) text = text // ", impacts " &
            & // scientific(summary%impact_work) // " J"
        if (abs(rim) > 1.0e-12_wp*abs(summary%dissipated_work)) text = text &
            & // ", rolling resistance and air " // scientific(rim) // " J"
        text = " by" // text(2:)
    end function dissipation_parts

    !> "final state of part <id>:" and its coordinates beside their rates, for every part (built
    !> by append_text: linear in the parts, where text = text // line copied the text so far
    !> at every line, a sizeable share of a run of hundreds of parts).
    function final_state(summary) result(text)
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text, lines
        character(len=32) :: value
        integer :: p, i, i0, used

        text = ""
        if (.not. allocated(summary%q) .or. .not. allocated(summary%layout%part_ids)) return
        used = 0
        do p = 1, size(summary%layout%part_ids)
            call append_text(lines, used, "final state of part " &
                & // to_text(summary%layout%part_ids(p)) // ":" // nl)
            i0 = 6*(p - 1)
            do i = 1, 6
                value = es_text(summary%q(i0 + i), 23, 15)
                call append_text(lines, used, "  " // quantity_names(i) // trim(value))
                value = es_text(summary%u(i0 + i), 23, 15)
                call append_text(lines, used, "    " // quantity_names(6 + i) // trim(value) &
                    & // nl)
            end do
        end do
        if (used > 0) text = lines(:used)
    end function final_state

    !> The largest residual over the rows and UCONs, then each UCON's with its level (its
    !> label the next line of summary%ucon_labels, read once from start to end).
    function residual_lines(summary) result(text)
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text, lines, label
        integer :: k, used, first, last
        logical :: labelled

        if (.not. allocated(summary%ucon_residual_max)) then
            text = ""
            return
        end if
        if (size(summary%ucon_residual_max) == 0) then
            text = "largest constraint residual: none (the model has no UCON)" // nl
            return
        end if
        used = 0
        call append_text(lines, used, "largest constraint residual: " &
            & // scientific(summary%residual_max) &
            & // " (velocity level: its coordinates' units per s; position level: their units)" &
            & // nl)
        ! UCON k in the user's words: line k of summary%ucon_labels, else (no labels, or none
        ! left) "UCON <id>"
        labelled = allocated(summary%ucon_labels)
        first = 1
        do k = 1, size(summary%ucon_residual_max)
            label = "UCON " // to_text(summary%layout%ucon_ids(k))
            if (labelled) then
                last = index(summary%ucon_labels(first:), nl)
                if (last == 0) then
                    labelled = .false.
                else
                    last = first + last - 1
                    label = summary%ucon_labels(first:last - 1)
                    first = last + 1
                end if
            end if
            call append_text(lines, used, "  " // label // ": " &
                & // scientific(summary%ucon_residual_max(k)))
            if (summary%ucon_position(k)) then
                call append_text(lines, used, " (position level)" // nl)
            else
                call append_text(lines, used, " (velocity level)" // nl)
            end if
        end do
        text = lines(:used)
    end function residual_lines

    !> Append piece to text(:used), text's length doubled first when the piece does not fit:
    !> n pieces cost time linear in their total length.
    pure subroutine append_text(text, used, piece)
        character(len=:), allocatable, intent(inout) :: text
        integer, intent(inout) :: used
        character(len=*), intent(in) :: piece
        character(len=:), allocatable :: larger

        if (.not. allocated(text)) allocate(character(len=max(256, len(piece))) :: text)
        if (used + len(piece) > len(text)) then
            allocate(character(len=max(2*len(text), used + len(piece))) :: larger)
            larger(:used) = text(:used)
            call move_alloc(larger, text)
        end if
        text(used + 1:used + len(piece)) = piece
        used = used + len(piece)
    end subroutine append_text

    !> Each watch measure judged against a bound: "largest height residual |Z - R sin(theta)|:
    !> 1.2E-09 m, allowed 3.4E-08 m". A measure without a bound is for tables (a study's row,
    !> such as a contact's switches): the watch's own lines say it.
    function measure_lines(summary) result(text)
        type(run_summary_type), intent(in) :: summary
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        if (.not. allocated(summary%measures)) return
        do k = 1, size(summary%measures)
            associate (m => summary%measures(k))
                if (.not. m%bound > 0.0_wp) cycle
                text = text // m%label // ": " // scientific(m%value) // " " // m%unit &
                    & // allowed(m%bound, " " // m%unit) // nl
            end associate
        end do
    end function measure_lines

    !> ", allowed <bound><unit>" when the drift was judged (bound > 0).
    function allowed(bound, unit) result(phrase)
        real(wp), intent(in) :: bound
        character(len=*), intent(in) :: unit
        character(len=:), allocatable :: phrase
        character(len=32) :: value

        phrase = ""
        if (bound <= 0.0_wp) return
        value = es_text(bound, 10, 3)
        phrase = ", allowed " // trim(adjustl(value)) // unit
    end function allowed

    !> A measure in 4 significant digits, with a three-digit exponent kept (1.982E-08).
    function scientific(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: value

        value = es_text(x, 11, 3)
        text = trim(adjustl(value))
    end function scientific

    !> A time in seconds with 4 decimals.
    function fixed(x) result(text)
        real(wp), intent(in) :: x
        character(len=:), allocatable :: text
        character(len=32) :: value

        write(value, '(f12.4)') x
        text = trim(adjustl(value))
    end function fixed

end module rollcon_summary_text
