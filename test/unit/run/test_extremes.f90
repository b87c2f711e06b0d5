! SPDX-License-Identifier: MIT
!> Numerical stability at the extremes (issue: speed against accuracy): each run completes with
!> bounded error or stops with a clear diagnostic, never a NaN. Also the benchmark's quick mode.
module test_extremes
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_scene, only : scene_type, read_scene, choice_code
    use rollcon_simulation, only : history_type, run_summary_type, status_completed, &
        & status_inaccurate, status_stopped
    use rollcon_output_layout, only : coord_theta, coord_psidot
    use rollcon_benchmark, only : benchmark_methods, benchmark_row_type, benchmark_scene, &
        & benchmark_header, write_benchmark_row
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory, default_scene
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: collect_extremes


contains

    subroutine collect_extremes(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("near-flat-fast-precession", test_near_flat), &
            & new_unittest("spinning-coin", test_spinning_coin), &
            & new_unittest("tiny-disk-1-mm", test_tiny_disk), &
            & new_unittest("huge-disk-10-m", test_huge_disk), &
            & new_unittest("loosest-tolerance", test_loosest), &
            & new_unittest("tightest-tolerance", test_tightest), &
            & new_unittest("start-near-flat-refused", test_flat_start_refused), &
            & new_unittest("error-decreases-with-tolerance", test_error_decreases), &
            & new_unittest("benchmark-quick-mode", test_benchmark_quick)]
    end subroutine collect_extremes

    !> Every output row finite; the run completed or stopped at a scene limit.
    subroutine check_sane(error, history, summary, what)
        type(error_type), allocatable, intent(out) :: error
        type(history_type), intent(in) :: history
        type(run_summary_type), intent(in) :: summary
        character(len=*), intent(in) :: what

        call check(error, all(ieee_is_finite(history%rows(:, :history%count))), &
            & what // ": a non-finite value in the output")
        if (allocated(error)) return
        call check(error, summary%status == status_completed .or. summary%status == &
            & status_stopped, what // ": status " // to_text(summary%status))
    end subroutine check_sane

    !> near_flat: the disk falls from 15 deg towards flat; as theta shrinks the precession rate
    !> grows (psidot ~ theta^-1/2). With theta_min = 0.05 rad (about 3 deg) the run either
    !> reaches it, with precession over 200 rad/s and a clear stop, or completes; energy holds.
    subroutine test_near_flat(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        call read_scene("data/near_flat.nml", scene, error)
        if (allocated(error)) return
        scene%limits%theta_min = 0.05_wp
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check_sane(error, history, summary, "near_flat")
        if (allocated(error)) return
        call check(error, minval(history%part_values(1, coord_theta)) < 0.06_wp, &
            & "theta only fell to " // to_text(minval(history%part_values(1, coord_theta))))
        if (allocated(error)) return
        call check(error, maxval(abs(history%part_values(1, coord_psidot))) > 200.0_wp, &
            & "precession only reached " &
            & // to_text(maxval(abs(history%part_values(1, coord_psidot)))))
        if (allocated(error)) return
        ! energy over the fall: 1e3 rtol, as for the tipping coin
        call check(error, summary%energy_drift, 0.0_wp, "energy drift", &
            & abs_tol=1.0e3_wp*scene%run%rtol)
    end subroutine test_near_flat

    subroutine test_spinning_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        call read_scene("data/spinning_coin.nml", scene, error)
        if (allocated(error)) return
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check_sane(error, history, summary, "spinning_coin")
        if (allocated(error)) return
        call check(error, summary%energy_drift, 0.0_wp, "energy drift", &
            & abs_tol=1.0e3_wp*scene%run%rtol)
    end subroutine test_spinning_coin

    !> The coin scaled by s in every length (radius, thickness): the motion scales too, with
    !> time by sqrt(s). Tolerances scale with the lengths (atol in metres).
    subroutine scaled_coin(error, scale)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: scale
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary

        scene = default_scene()
        scene%disk%radius = 0.1_wp*scale
        scene%disk%thickness = 0.003_wp*scale
        scene%initial%theta = 0.5_wp*pi - 0.01_wp
        scene%initial%phidot = -1.0_wp/sqrt(scale)
        scene%run%end_time = 5.0_wp*sqrt(scale)
        scene%run%output_step = 0.01_wp*sqrt(scale)
        scene%run%atol = 1.0e-10_wp*scale
        call run_in_memory(scene, history, summary, error)
        if (allocated(error)) return
        call check_sane(error, history, summary, "scale " // to_text(scale))
        if (allocated(error)) return
        call check(error, summary%energy_drift, 0.0_wp, "energy drift at scale " &
            & // to_text(scale), abs_tol=1.0e3_wp*scene%run%rtol)
        if (allocated(error)) return
        ! residuals scale with the velocities, sqrt(scale) m/s
        call check(error, summary%residual_max, 0.0_wp, "residual at scale " // to_text(scale), &
            & abs_tol=1.0e2_wp*scene%run%rtol*sqrt(scale))
    end subroutine scaled_coin

    subroutine test_tiny_disk(error)
        type(error_type), allocatable, intent(out) :: error

        call scaled_coin(error, 1.0e-2_wp)
    end subroutine test_tiny_disk

    subroutine test_huge_disk(error)
        type(error_type), allocatable, intent(out) :: error

        call scaled_coin(error, 1.0e2_wp)
    end subroutine test_huge_disk

    !> The ladder's ends, 1e-3 and 1e-12, on the tipping coin's first 2 s, both formulations.
    subroutine ladder_end(error, rtol)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: rtol
        character(len=5), parameter :: formulations(2) = ["ida  ", "cvode"]
        type(scene_type) :: scene
        type(history_type) :: history
        type(run_summary_type) :: summary
        integer :: i

        do i = 1, 2
            scene = default_scene()
            scene%initial%theta = 0.5_wp*pi - 0.01_wp
            scene%initial%phidot = -1.0_wp
            scene%run%end_time = 2.0_wp
            scene%run%formulation = choice_code("formulation", formulations(i))
            scene%run%rtol = rtol
            scene%run%atol = 1.0e-2_wp*rtol
            call run_in_memory(scene, history, summary, error)
            if (allocated(error)) return
            if (summary%status == status_inaccurate) then
                ! a verdict is a promise: at the loosest rung a run may drift beyond what its
                ! tolerance promises (CVODE at 1e-3: 1.7e-2 of the energy scale against the
                ! 1e-2 allowed), and then it must reach the end with its rows whole and say so
                ! truly: its drift beyond its bound
                call check(error, summary%t_reached >= scene%run%end_time .and. &
                    & all(ieee_is_finite(history%rows(:, :history%count))) .and. &
                    & summary%energy_drift > summary%energy_bound, trim(formulations(i)) &
                    & // " at rtol " // to_text(rtol) // ": INACCURATE with drift " &
                    & // to_text(summary%energy_drift) // " against its bound " &
                    & // to_text(summary%energy_bound) // " at t = " &
                    & // to_text(summary%t_reached) // " s")
            else
                call check_sane(error, history, summary, trim(formulations(i)) // " at rtol " &
                    & // to_text(rtol))
            end if
            if (allocated(error)) return
            ! residual: 100 rtol [m/s] (velocities ~0.1 m/s), floored at 1e-13 for round-off
            call check(error, summary%residual_max, 0.0_wp, trim(formulations(i)) &
                & // " residual at rtol " // to_text(rtol), abs_tol=max(1.0e2_wp*rtol, 1.0e-13_wp))
            if (allocated(error)) return
        end do
    end subroutine ladder_end

    subroutine test_loosest(error)
        type(error_type), allocatable, intent(out) :: error

        call ladder_end(error, 1.0e-3_wp)
    end subroutine test_loosest

    subroutine test_tightest(error)
        type(error_type), allocatable, intent(out) :: error

        call ladder_end(error, 1.0e-12_wp)
    end subroutine test_tightest

    !> A disk started within 1e-3 rad of flat is refused, with the reason.
    subroutine test_flat_start_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = "build/test_extremes_flat.nml"
        type(scene_type) :: scene
        type(error_type), allocatable :: found
        integer :: unit

        open(newunit=unit, file=path, status="replace", action="write")
        write(unit, '(a)') "&initial", "    theta = 0.0005", "    psidot = 10.0", "/"
        close(unit)
        call read_scene(path, scene, found)
        open(newunit=unit, file=path, status="old")
        close(unit, status="delete")
        if (.not. allocated(found)) then
            call check(error, .false., "a start 5e-4 rad from flat was accepted")
            return
        end if
        call check(error, found%stat == stat_input .and. index(found%message, path // ":2:") == 1 &
            & .and. index(found%message, "'theta'") > 0 .and. &
            & index(found%message, "Euler angles are singular") > 0, "message: " // found%message)
    end subroutine test_flat_start_refused

    !> Error against a tight reference falls as the tolerance tightens, for every method, on
    !> fast_upright (first 2 s, rtol 1e-4, 1e-6, 1e-8): each rung at least 3x better.
    subroutine test_error_decreases(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(benchmark_row_type), allocatable :: rows(:)
        integer :: i

        call load_job("fast_upright", job, error)
        if (allocated(error)) return
        job%source%settings%end_time = 2.0_wp
        call benchmark_scene(job, benchmark_methods(), &
            & [1.0e-4_wp, 1.0e-6_wp, 1.0e-8_wp], 1.0e-12_wp, 1, rows, error)
        if (allocated(error)) return
        do i = 1, size(rows), 3
            call check(error, rows(i + 1)%position_error < rows(i)%position_error/3.0_wp &
                & .and. rows(i + 2)%position_error < rows(i + 1)%position_error/3.0_wp, &
                & trim(rows(i)%method) // ": errors " // to_text(rows(i)%position_error) // ", " &
                & // to_text(rows(i + 1)%position_error) // ", " &
                & // to_text(rows(i + 2)%position_error))
            if (allocated(error)) return
        end do
    end subroutine test_error_decreases

    !> The benchmark's quick mode (tipping coin over 1 s, two tolerances, as `rollcon bench
    !> --quick` runs it): every method gives a completed row whose CSV line has the header's
    !> columns and finite values.
    subroutine test_benchmark_quick(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(benchmark_row_type), allocatable :: rows(:)
        character(len=:), allocatable :: line, header
        integer :: i

        call load_job("tipping_coin", job, error)
        if (allocated(error)) return
        job%source%settings%end_time = 1.0_wp
        call benchmark_scene(job, benchmark_methods(), &
            & [1.0e-4_wp, 1.0e-6_wp], 1.0e-10_wp, 1, rows, error)
        if (allocated(error)) return
        call check(error, size(rows), 2*size(benchmark_methods()), "rows")
        if (allocated(error)) return
        header = benchmark_header()
        do i = 1, size(rows)
            line = write_benchmark_row(rows(i))
            call check(error, count_commas(line) == count_commas(header) &
                & .and. index(line, ",completed") > 0 .and. index(line, "NaN") == 0 &
                & .and. index(line, "Infinity") == 0, "row: " // line)
            if (allocated(error)) return
        end do
    end subroutine test_benchmark_quick

    pure integer function count_commas(text)
        character(len=*), intent(in) :: text
        integer :: i

        count_commas = 0
        do i = 1, len(text)
            if (text(i:i) == ",") count_commas = count_commas + 1
        end do
    end function count_commas

end module test_extremes
