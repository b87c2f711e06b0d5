! SPDX-License-Identifier: MIT
!> The benchmark bicycle's reduced ODE (ucon/reduced/bicycle.py, rollcon_reduced_bicycle):
!> its linearisation against Meijaard et al.'s eigenvalues, its ride against rollcon's own runs
!> of data/bicycle.adm (two derivations, one by Kane's method in minimal coordinates, one by
!> UCONs on four free parts), its table, and the benchmark's use of it as reference and limit.
module test_reduced_bicycle
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_lapack, only : general_eigenvalues
    use rollcon_run_keys, only : choice_code
    use rollcon_run_settings, only : run_settings_type
    use rollcon_simulation, only : history_type, run_summary_type
    use rollcon_reduced_bicycle, only : bicycle_table_type, read_bicycle_table, &
        & bicycle_state_size, bicycle_rate, bicycle_start, bicycle_pitch, &
        & simulate_reduced_bicycle, bicycle_distance, bicycle_measures
    use rollcon_reduced_bicycle_rhs, only : bicycle_contact_height
    use rollcon_benchmark, only : method_type, benchmark_methods, benchmark_row_type, &
        & benchmark_scene
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_reduced_bicycle

    character(len=*), parameter :: table_path = "data/bicycle/benchmark.txt"
    character(len=*), parameter :: scratch = "build/test_reduced_bicycle"

contains

    subroutine collect_reduced_bicycle(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("eigenvalues-at-5-m-s", test_eigenvalues), &
            & new_unittest("pitch-on-the-ground", test_pitch), &
            & new_unittest("ride-equals-full-model", test_ride), &
            & new_unittest("energy-after-the-push", test_energy), &
            & new_unittest("table-refusals", test_table_refusals), &
            & new_unittest("benchmark-on-the-bicycle", test_benchmark)]
    end subroutine collect_reduced_bicycle

    !> The table of data/bicycle.adm.
    subroutine benchmark_table(table, error)
        type(bicycle_table_type), intent(out) :: table
        type(error_type), allocatable, intent(out) :: error

        call read_bicycle_table(table_path, table, error)
    end subroutine benchmark_table

    !> Settings of a reduced or full CVODE run: method, Jacobian, rtol (atol = 1e-2 rtol).
    function settings_of(method, jacobian, rtol) result(settings)
        character(len=*), intent(in) :: method, jacobian
        real(wp), intent(in) :: rtol
        type(run_settings_type) :: settings

        settings%method = choice_code("method", method)
        settings%jacobian = choice_code("jacobian", jacobian)
        settings%rtol = rtol
        settings%atol = 1.0e-2_wp*rtol
        settings%max_steps = 1000000
        settings%end_time = 10.0_wp
        settings%output_step = 0.01_wp
    end function settings_of

    !> Upright and straight at 5 m/s, the Jacobian of roll, steer and their rates by sixth-order
    !> central differences of the generated equations has Meijaard et al.'s eigenvalues (Table 2:
    !> castering, weave, capsize), the reduced ODE's independent check of rollcon linear's.
    subroutine test_eigenvalues(error)
        type(error_type), allocatable, intent(out) :: error
        ! h = 1e-5: truncation ~h^6, rounding ~eps |rate| / h ~ 1e-10 on rates of order 10;
        ! measured 1e-14 relative; the paper prints 15 digits
        real(wp), parameter :: h = 1.0e-5_wp, tol = 1.0e-10_wp
        ! Table 2 at v = 5 m/s: castering, weave (a pair), capsize
        real(wp), parameter :: castering = -14.0783896927982_wp, weave = -0.775341882195845_wp
        real(wp), parameter :: weave_frequency = 4.46486771378823_wp
        real(wp), parameter :: capsize = -0.322866429004087_wp
        type(bicycle_table_type) :: table
        real(wp) :: y(bicycle_state_size), f(bicycle_state_size, -3:3), jacobian(4, 4), step(8)
        real(wp) :: re(4), im(4)
        integer :: j, k

        call benchmark_table(table, error)
        if (allocated(error)) return
        call check(error, table%speed, 5.0_wp, "the table's speed")
        if (allocated(error)) return
        y = bicycle_start(table)
        do j = 1, 4
            do k = -3, 3
                step = 0.0_wp
                step(j) = k*h
                call bicycle_rate(y + step, table%par, 0.0_wp, f(:, k))
            end do
            jacobian(:, j) = (45.0_wp*(f(:4, 1) - f(:4, -1)) - 9.0_wp*(f(:4, 2) - f(:4, -2)) &
                & + (f(:4, 3) - f(:4, -3)))/(60.0_wp*h)
        end do
        call general_eigenvalues(jacobian, re, im, error)
        if (allocated(error)) return
        call check(error, minval(re), castering, "castering", rel_tol=tol)
        if (allocated(error)) return
        call check(error, maxval(re), capsize, "capsize", rel_tol=tol)
        if (allocated(error)) return
        do k = 1, 4
            if (im(k) == 0.0_wp) cycle
            call check(error, re(k), weave, "weave", rel_tol=tol)
            if (allocated(error)) return
            call check(error, abs(im(k)), weave_frequency, "weave frequency", rel_tol=tol)
            if (allocated(error)) return
        end do
        call check(error, count(im /= 0.0_wp), 2, "one complex pair")
    end subroutine test_eigenvalues

    !> The pitch solved at a lean and a steer puts the front contact on the ground, and is an
    !> even function of the two together (the bicycle is symmetric about its plane).
    subroutine test_pitch(error)
        type(error_type), allocatable, intent(out) :: error
        ! Newton's method converged: its last step below 1e-10 rad, the error below its square
        real(wp), parameter :: tol = 1.0e-15_wp
        type(bicycle_table_type) :: table
        real(wp) :: pitch, height, slope

        call benchmark_table(table, error)
        if (allocated(error)) return
        pitch = bicycle_pitch(0.3_wp, -0.5_wp, table%par)
        call bicycle_contact_height([0.0_wp, 0.3_wp, pitch, -0.5_wp], table%par, height, slope)
        call check(error, height, 0.0_wp, "front contact's height", abs_tol=tol)
        if (allocated(error)) return
        ! a lean and a steer lower the front: a visible pitch, not a rounding
        call check(error, abs(pitch) > 1.0e-3_wp, "pitch " // to_text(pitch) // " rad")
        if (allocated(error)) return
        call check(error, bicycle_pitch(-0.3_wp, 0.5_wp, table%par), pitch, "mirror", &
            & abs_tol=tol)
        if (allocated(error)) return
        call check(error, bicycle_pitch(0.0_wp, 0.0_wp, table%par), 0.0_wp, "upright", &
            & abs_tol=tol)
    end subroutine test_pitch

    !> Pushed at t = 1 s and ridden for 10 s at 5 m/s, the reduced ODE and rollcon's runs of
    !> data/bicycle.adm give the same roll, steer and rear contact point: IDA (the dataset's
    !> formulation) at rtol 1e-11 within 1e-7 (rad, m), CVODE Adams on the full model's ODE
    !> form at rtol 1e-11 within 1e-10.
    subroutine test_ride(error)
        type(error_type), allocatable, intent(out) :: error
        ! the two Adams runs, rtol 1e-11 and 1e-12: measured 4.3e-11 (the full model's error at
        ! its rtol); a tenfold loss fails
        real(wp), parameter :: tol_adams = 1.0e-10_wp
        ! IDA's BDF at rtol 1e-11, atol 1e-13: measured 2.2e-8 (at the dataset's ERROR = 1e-10,
        ! atol 1e-10: 3.6e-7)
        real(wp), parameter :: tol_ida = 1.0e-7_wp
        type(bicycle_table_type) :: table
        type(history_type) :: reduced, full, full_adams
        type(run_summary_type) :: summary
        type(job_type) :: job
        type(job_result_type) :: ran
        real(wp) :: distance
        real(wp), allocatable :: measures(:, :)

        call benchmark_table(table, error)
        if (allocated(error)) return
        call simulate_reduced_bicycle(table, settings_of("adams", "dq", 1.0e-12_wp), &
            & table%end_time, table%end_time/table%steps, reduced, summary, error)
        if (allocated(error)) return
        call check(error, reduced%count, table%steps + 1, "reduced rows")
        if (allocated(error)) return
        ! the push leans it: the ride is not the upright one
        measures = bicycle_measures(reduced, table%par(3), table%par(5))
        call check(error, maxval(abs(measures(1, :))) > 1.0e-3_wp, "largest roll " &
            & // to_text(maxval(abs(measures(1, :)))) // " rad")
        if (allocated(error)) return
        call load_job("data/bicycle.adm", job, error)
        if (allocated(error)) return
        job%quiet = .true.
        job%output_dir = ""
        job%source%settings%rtol = 1.0e-11_wp
        job%source%settings%atol = 1.0e-13_wp
        call run_job(job, ran, error, full)
        if (allocated(error)) return
        distance = bicycle_distance(full, reduced, table%par(3), table%par(5))
        call check(error, distance <= tol_ida, "IDA at rtol 1e-11: " // to_text(distance))
        if (allocated(error)) return
        job%source%settings%formulation = choice_code("formulation", "cvode")
        job%source%settings%method = choice_code("method", "adams")
        job%source%settings%drift = choice_code("drift", "baumgarte")
        call run_job(job, ran, error, full_adams)
        if (allocated(error)) return
        call check(error, full_adams%count, reduced%count, "full rows")
        if (allocated(error)) return
        distance = bicycle_distance(full_adams, reduced, table%par(3), table%par(5))
        call check(error, distance <= tol_adams, "CVODE Adams at rtol 1e-11: " &
            & // to_text(distance))
    end subroutine test_ride

    !> After the push the reduced ODE keeps its energy, and it is the full model's (the same
    !> kinetic energy and the same potential's zero, the ground).
    subroutine test_energy(error)
        type(error_type), allocatable, intent(out) :: error
        ! Adams at rtol 1e-10: a drift of a few 1e-12 relative (measured 8e-13)
        real(wp), parameter :: tol = 1.0e-10_wp
        type(bicycle_table_type) :: table
        type(history_type) :: reduced
        type(run_summary_type) :: summary

        call benchmark_table(table, error)
        if (allocated(error)) return
        call simulate_reduced_bicycle(table, settings_of("adams", "none", 1.0e-10_wp), &
            & table%end_time, 0.1_wp, reduced, summary, error)
        if (allocated(error)) return
        call check(error, summary%energy_drift <= tol, "energy drift " &
            & // to_text(summary%energy_drift))
        if (allocated(error)) return
        ! the full model's energy at the upright start (its summary's E0: 2014.3575952380954 J,
        ! the first row of data/bicycle.adm's run): kinetic at 5 m/s and potential
        call check(error, reduced%rows(2, 1), 2014.3575952380954_wp, "energy at the start", &
            & rel_tol=1.0e-14_wp)
    end subroutine test_energy

    !> A table that is not the bicycle's is refused with its file and line: a name that is not
    !> a parameter, one given twice, a wrong unit, one missing.
    subroutine test_table_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        type(bicycle_table_type) :: table
        character(len=*), parameter :: path = scratch // ".txt"
        character(len=512) :: line
        character(len=:), allocatable :: lines
        integer :: unit, in, stat

        call execute_command_line("mkdir -p build")
        call refused("wheelbase 1 m", "wheelbase", "is not a parameter")
        if (allocated(error)) return
        call refused("w 1 m", "w", "given twice")
        if (allocated(error)) return
        call refused("", "c", "is in m, got 'kg'", swap="c         0.08        m", &
            & by="c 0.08 kg")
        if (allocated(error)) return
        call refused("", "missing I_Fyy", "", swap="I_Fyy     0.28        kg m^2", by="")

    contains

        !> The benchmark table with `extra` appended (and the line swap replaced by `by`) is
        !> refused with a message holding both words.
        subroutine refused(extra, word, words, swap, by)
            character(len=*), intent(in) :: extra, word, words
            character(len=*), intent(in), optional :: swap, by
            type(error_type), allocatable :: failure

            open(newunit=in, file=table_path, status="old", action="read")
            open(newunit=unit, file=path, status="replace", action="write")
            do
                read(in, '(a)', iostat=stat) line
                if (stat /= 0) exit
                if (present(swap)) then
                    if (index(line, swap) == 1) line = by
                end if
                write(unit, '(a)') trim(line)
            end do
            if (len(extra) > 0) write(unit, '(a)') extra
            close(in)
            close(unit)
            call read_bicycle_table(path, table, failure)
            lines = "no refusal"
            if (allocated(failure)) lines = failure%message
            call check(error, allocated(failure) .and. index(lines, path) > 0 .and. &
                & index(lines, word) > 0 .and. index(lines, words) > 0, extra // ": " // lines)
            open(newunit=unit, file=path, status="old")
            close(unit, status="delete")
        end subroutine refused

    end subroutine test_table_refusals

    !> The benchmark on the bicycle over 2 s: rows of the full model and of the reduced ODE, the
    !> reduced ODE within its tolerance's reach of the reference, each ratio its CPU time over
    !> the reduced run's of the same rtol, multistep method and iteration.
    subroutine test_benchmark(error)
        type(error_type), allocatable, intent(out) :: error
        ! one division
        real(wp), parameter :: tol = 1.0e-12_wp
        type(job_type) :: job
        type(bicycle_table_type) :: table
        type(benchmark_row_type), allocatable :: rows(:)
        type(method_type) :: all_methods(size(benchmark_methods()))
        integer :: i

        call benchmark_table(table, error)
        if (allocated(error)) return
        call load_job("data/bicycle.adm", job, error)
        if (allocated(error)) return
        job%source%settings%end_time = 2.0_wp
        all_methods = benchmark_methods()
        call benchmark_scene(job, [all_methods(1), all_methods(8), all_methods(11)], &
            & [1.0e-6_wp, 1.0e-8_wp], 1.0e-11_wp, 1, rows, error, table=table)
        if (allocated(error)) return
        call check(error, size(rows), 6, "rows")
        if (allocated(error)) return
        do i = 1, size(rows)
            associate (row => rows(i))
                call check(error, trim(row%scene) == "bicycle", "scene " // trim(row%scene))
                if (allocated(error)) return
                call check(error, row%status == "completed", trim(row%method) // ": " &
                    & // row%status)
                if (allocated(error)) return
                call check(error, row%ratio, row%cpu/row%reduced_cpu, trim(row%method) &
                    & // ": ratio", rel_tol=tol)
                if (allocated(error)) return
                ! every way of solving close to the reference: a wrong comparison (an axis, a
                ! sign) would be of the ride's own size, the push's lean ~2e-3 rad and the
                ! contact's ~0.02 m sideways
                call check(error, row%position_error <= 1.0e-4_wp, trim(row%method) &
                    & // " at rtol " // to_text(row%rtol) // ": " &
                    & // to_text(row%position_error))
                if (allocated(error)) return
            end associate
        end do
    end subroutine test_benchmark

end module test_reduced_bicycle
