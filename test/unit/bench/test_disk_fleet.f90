! SPDX-License-Identifier: MIT
!> The dataset of N independent rolling disks (rollcon_disk_fleet), the model of the cost
!> benchmark `rollcon bench scaling`: it reads as N parts with 3 N UCONs, spread apart as asked,
!> and its motion is N copies of the one-disk motion to round-off on every formulation.
module test_disk_fleet
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_files, only : write_text_file, make_folders
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_disk_fleet, only : disk_fleet_dataset
    use rollcon_bench_scaling, only : scaling_row_type, measure_scaling, scaling_header, &
        & scaling_csv_row
    use rollcon_constraint_blocks, only : constraint_blocks_type
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_summary_text, only : run_summary_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_dataset_text
    implicit none
    private

    public :: collect_disk_fleet

    !> Where the tests write their datasets
    character(len=*), parameter :: folder = "build/rollcon-test/disk-fleet"

contains

    subroutine collect_disk_fleet(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("copies-of-one-disk", test_copies), &
            & new_unittest("parts-spread-apart", test_spread), &
            & new_unittest("blocks-of-the-fleet", test_blocks), &
            & new_unittest("scaling-rows", test_scaling_rows), &
            & new_unittest("scaling-short-and-refused-end-times", test_scaling_end_times), &
            & new_unittest("summary-names-klu", test_summary_klu)]
    end subroutine collect_disk_fleet

    !> Run the fleet of count disks, spacing apart, to 1 s on the INTEGRATOR keywords.
    subroutine run_fleet(count, spacing, keywords, history, error)
        integer, intent(in) :: count
        real(wp), intent(in) :: spacing
        character(len=*), intent(in) :: keywords
        type(history_type), intent(out) :: history
        type(error_type), allocatable, intent(out) :: error

        call run_dataset_text(folder, "fleet_" // to_text(count), disk_fleet_dataset(count, &
            & spacing, 1.0_wp, 0.05_wp, keywords), history, error)
        if (allocated(error)) error%message = keywords // ": " // error%message
    end subroutine run_fleet

    !> The run's summary says when the Newton matrix was solved by KLU: four disks on IDA with
    !> the default solver ('auto': 60 states, the matrix a sixteenth full, past its threshold)
    !> say so, through the child process of a user's file too (the run's wire); one disk (15
    !> states) and four disks with SOLVER=DENSE do not.
    subroutine test_summary_klu(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: said = ", Newton matrix sparse (KLU)" // new_line("a")
        character(len=*), parameter :: keywords(3) = [character(len=40) :: &
            & "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10", "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10", &
            & "FORMULATION=IDA, SOLVER=DENSE"]
        integer, parameter :: counts(3) = [4, 1, 4]
        logical, parameter :: sparse(3) = [.true., .false., .false.]
        character(len=:), allocatable :: path, text
        type(job_result_type) :: ran
        integer :: k

        call make_folders(folder, error)
        if (allocated(error)) return
        do k = 1, size(keywords)
            path = folder // "/klu_" // to_text(k) // ".adm"
            call write_text_file(path, disk_fleet_dataset(counts(k), 0.5_wp, 0.05_wp, 0.05_wp, &
                & trim(keywords(k))), error)
            if (allocated(error)) return
            call run_one(path, "", ran, text, error)
            if (allocated(error)) return
            call check(error, ran%summary%status == status_completed .and. &
                & (ran%summary%sparse_newton .eqv. sparse(k)) .and. &
                & (index(text, said) > 0 .eqv. sparse(k)), to_text(counts(k)) // " disks, " &
                & // trim(keywords(k)) // ": " // text)
            if (allocated(error)) return
        end do
        ! through a user's file, run apart: the summary crosses the wire
        call run_one(folder // "/klu_1.adm", "ucon/adams/rolling_disk/ucosub.f", ran, text, error)
        if (allocated(error)) return
        call check(error, ran%summary%status == status_completed .and. &
            & ran%summary%sparse_newton .and. index(text, said) > 0, "4 disks with a user's " &
            & // "file: " // text)

    contains

        subroutine run_one(dataset, ucosub, result, summary_text, run_error)
            character(len=*), intent(in) :: dataset, ucosub
            type(job_result_type), intent(out) :: result
            character(len=:), allocatable, intent(out) :: summary_text
            type(error_type), allocatable, intent(out) :: run_error
            type(job_type) :: job
            type(history_type) :: history

            call load_job(dataset, job, run_error, ucosub=ucosub)
            if (allocated(run_error)) return
            job%output_dir = ""
            job%quiet = .true.
            call run_job(job, result, run_error, history)
            if (allocated(run_error)) return
            summary_text = run_summary_text(job%source%setting_line(), "x.csv", result%summary)
        end subroutine run_one
    end subroutine test_summary_klu

    !> Four disks on one spot (they do not touch one another in the model) against one, on IDA,
    !> CVODE's ODE form and the independent speeds, each with the dense Newton matrix named
    !> (four disks are past linear_solver = 'auto''s threshold) and with KLU: within the
    !> four-disk run every disk's 12 coordinates and rates equal the first's at every row, to
    !> round-off (measured: bit for bit); and they follow the one-disk run. The integrators'
    !> error norms are root mean squares over all states, the same for four copies of a state
    !> as for one up to their rounding, so the runs take the same steps unless a step's test
    !> falls the other way on that rounding; then the runs differ by their global errors.
    subroutine test_copies(error)
        type(error_type), allocatable, intent(out) :: error
        !> The copies within one run, relative to each column's scale: their equations are the
        !> same numbers in other rows, every block factored alone, so only round-off could part
        !> them (measured 0); a coupling between the copies moves them by the motion's size
        real(wp), parameter :: tol_among = 1.0e-14_wp
        !> Against the one-disk run, relative: CVODE's ODE form took the same steps (measured
        !> 2.5e-12: round-off, 1e-10 allowed); the independent speeds and IDA decided some step
        !> otherwise (measured 7.8e-8 and 1.1e-4 over 1 s of the tipping coin at rtol 1e-8,
        !> its global error near flat; IDA's 9.4e-8 on 2026-11-26). With the sparse Newton
        !> matrix (KLU), whose LU orders its sums by the pattern: CVODE's two forms 8.7e-10 and
        !> 1.1e-7, IDA (the last) 3.6e-5. Ten times those
        real(wp), parameter :: tol_copies(6) = [1.0e-3_wp, 1.0e-10_wp, 1.0e-6_wp, 1.0e-8_wp, &
            & 1.0e-6_wp, 4.0e-4_wp]
        character(len=*), parameter :: keywords(6) = [character(len=82) :: &
            & "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10, SOLVER=DENSE", &
            & "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, SOLVER=D", &
            & "FORMULATION=MAGGI, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, SOLVER=D", &
            & "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, SOLVER=S", &
            & "FORMULATION=MAGGI, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, SOLVER=S", &
            & "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10, SOLVER=SPARSE"]
        integer, parameter :: copies = 4
        type(history_type) :: one, many
        real(wp) :: largest, scale
        integer :: k, p, c

        do k = 1, size(keywords)
            call run_fleet(1, 0.0_wp, trim(keywords(k)), one, error)
            if (allocated(error)) return
            call run_fleet(copies, 0.0_wp, trim(keywords(k)), many, error)
            if (allocated(error)) return
            call check(error, many%count, one%count, "rows")
            if (allocated(error)) return
            largest = 0.0_wp
            do p = 1, copies
                do c = 1, 12
                    scale = max(1.0_wp, maxval(abs(one%rows(1 + c, :one%count))))
                    largest = max(largest, maxval(abs(many%rows(1 + 12*(p - 1) + c, &
                        & :many%count) - one%rows(1 + c, :one%count)))/scale)
                end do
            end do
            call check(error, among(many, copies) <= tol_among, trim(keywords(k)) &
                & // ": the copies differ from one another by " &
                & // to_text(among(many, copies)) // " (relative)")
            if (allocated(error)) return
            call check(error, largest <= tol_copies(k), trim(keywords(k)) // ": the copies " &
                & // "differ from the one disk by " // to_text(largest) // " (relative)")
            if (allocated(error)) return
        end do
    end subroutine test_copies

    !> Disks 0.5 m apart along Y: the fleet reads as N parts and 3 N UCONs, disk p's centre at
    !> Y = 0.5 (p - 1) m at the start, each on the ground (Z = R sin theta) with its UCONs held.
    subroutine test_spread(error)
        type(error_type), allocatable, intent(out) :: error
        !> The start's Y is the dataset's number as written, to its printed digits
        real(wp), parameter :: tol_start = 1.0e-12_wp
        type(history_type) :: history
        integer :: p

        call run_fleet(3, 0.5_wp, "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, " &
            & // "ERROR=1e-8", history, error)
        if (allocated(error)) return
        call check(error, size(history%layout%part_ids), 3, "parts")
        if (allocated(error)) return
        call check(error, size(history%layout%ucon_ids), 9, "UCONs")
        if (allocated(error)) return
        do p = 1, 3
            call check(error, history%rows(1 + 12*(p - 1) + 2, 1), 0.5_wp*(p - 1), "disk " &
                & // to_text(p) // "'s Y at the start, m", abs_tol=tol_start)
            if (allocated(error)) return
        end do
    end subroutine test_spread

    !> The fleet's constraints fall into one block per disk: its three UCONs and its six
    !> coordinates (what the saddle-point system and the partition factor alone).
    subroutine test_blocks(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(constraint_blocks_type) :: blocks
        procedure(ucosub_interface), pointer :: disk
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: path
        integer :: b, j

        call make_folders(folder, error)
        if (allocated(error)) return
        path = folder // "/fleet_blocks.adm"
        call write_text_file(path, disk_fleet_dataset(3, 0.5_wp, 1.0_wp, 0.05_wp, &
            & "FORMULATION=CVODE"), error)
        if (allocated(error)) return
        disk => rolling_disk_ucosub
        call read_adm(path, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, problem, q0, u0, error)
        if (allocated(error)) return
        call blocks%init(problem%model)
        call check(error, blocks%count, 3, "blocks")
        if (allocated(error)) return
        do b = 1, 3
            call check(error, all(blocks%block_rows(b) == [(3*(b - 1) + j, j = 1, 3)]) &
                & .and. all(blocks%block_coordinates(b) == [(6*(b - 1) + j, j = 1, 6)]), &
                & "block " // to_text(b) // ": its disk's UCONs and coordinates")
            if (allocated(error)) return
        end do
    end subroutine test_blocks

    !> The scaling benchmark's rows (never their times, which are the benchmark's to report):
    !> one per method and N, the states of each form (on the disks 15 N with IDA's
    !> multipliers, 12 N on CVODE's ODE form, 9 N in independent speeds; on the chain 22 N,
    !> 12 coordinates and rates, 5 multipliers and 5 GGL multipliers per link, 12 N, and 7 N
    !> in independent speeds, 12 coordinates less 5 dependent speeds per link), and
    !> on CVODE the same steps for 1 and 2 disks (their error norms agree: the copies differ
    !> only in Y).
    subroutine test_scaling_rows(error)
        type(error_type), allocatable, intent(out) :: error
        type(scaling_row_type), allocatable :: rows(:)
        integer :: k

        call make_folders(folder, error)
        if (allocated(error)) return
        call measure_scaling(folder, [1, 2], 0.2_wp, rows, error)
        if (allocated(error)) return
        call check(error, size(rows), 30, "rows: 15 methods, 2 sizes")
        if (allocated(error)) return
        call check(error, all(rows%states == [15, 30, 15, 30, 15, 30, 12, 24, 12, 24, 9, 18, &
            & 9, 18, 12, 24, 22, 44, 22, 44, 22, 44, 12, 24, 12, 24, 12, 24, 7, 14]), &
            & "states of the " &
            & // "default, IDA, CVODE (Newton, then fixed-point) and the independent speeds " &
            & // "on 1 and 2 disks and of the chain")
        if (allocated(error)) return
        call check(error, all(rows(:16)%model == "disks") .and. all(rows(17:)%model == "chain"), &
            & "the disks' rows, then the chain's")
        if (allocated(error)) return
        ! fixed-point iteration: no Newton matrix, so no Jacobian is ever evaluated
        call check(error, all(rows([15, 16, 27, 28, 29, 30])%jacobians == 0) .and. &
            & all(rows([15, 16, 27, 28, 29, 30])%steps > 0), "fixed-point rows: steps and " &
            & // "no Jacobian")
        if (allocated(error)) return
        ! the rest of a run (reading, building, initial conditions) is measured, not zero:
        ! even one disk's dataset takes more than cpu_time's tick of the process to read
        call check(error, all(rows%startup >= 0.0_wp) .and. sum(rows%startup) > 0.0_wp, &
            & "start-up CPU measured")
        if (allocated(error)) return
        call check(error, rows(7)%steps > 0 .and. rows(8)%steps == rows(7)%steps, &
            & "CVODE's steps on 1 and 2 disks: " // to_text(rows(7)%steps) // ", " &
            & // to_text(rows(8)%steps))
        if (allocated(error)) return
        call check(error, all([(rows(k)%status == "completed", k = 1, size(rows))]), &
            & "every run completed")
        if (allocated(error)) return
        call check(error, index(scaling_csv_row(rows(3)), "disks,ida,1,15,") == 1 .and. &
            & index(scaling_header(), "model,method,parts,") == 1 .and. &
            & index(scaling_header(), "cpu_per_step_part_us") > 0 .and. &
            & index(scaling_header(), ",startup_cpu_s,status") > 0, "the CSV row and header")
    end subroutine test_scaling_rows

    !> A short end time (0.05 s: the disks' output step then 0.05 s, the chain's 0.005 s, below
    !> the 0.1 s they take otherwise) runs: every method on one disk and one link completes;
    !> an end time no dataset can take (the chain's a tenth of it below SIMULATE's 1e-9 s, or
    !> none at all) is refused by name, before any dataset is written.
    subroutine test_scaling_end_times(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: refused(3) = [1.0e-9_wp, -1.0_wp, 2.0e9_wp]
        type(scaling_row_type), allocatable :: rows(:)
        character(len=:), allocatable :: message
        integer :: k

        call make_folders(folder, error)
        if (allocated(error)) return
        call measure_scaling(folder, [1], 0.05_wp, rows, error)
        if (allocated(error)) return
        call check(error, all([(rows(k)%status == "completed", k = 1, size(rows))]) .and. &
            & all(rows%steps > 0), "every run of 0.05 s completed")
        if (allocated(error)) return
        do k = 1, size(refused)
            call measure_scaling(folder, [1], refused(k), rows, error)
            if (.not. allocated(error)) then
                call check(error, .false., "end time " // to_text(refused(k)) // " s taken")
                return
            end if
            message = error%message
            call check(error, index(message, "--end-time expects a time from 1e-8 to 1e9 s") &
                & > 0, "end time " // to_text(refused(k)) // ": " // message)
            if (allocated(error)) return
        end do
    end subroutine test_scaling_end_times

    !> The largest difference between the copies of one run, relative to each column's scale.
    function among(history, copies) result(largest)
        type(history_type), intent(in) :: history
        integer, intent(in) :: copies
        real(wp) :: largest, scale
        integer :: p, c

        largest = 0.0_wp
        do p = 2, copies
            do c = 1, 12
                scale = max(1.0_wp, maxval(abs(history%rows(1 + c, :history%count))))
                largest = max(largest, maxval(abs(history%rows(1 + 12*(p - 1) + c, &
                    & :history%count) - history%rows(1 + c, :history%count)))/scale)
            end do
        end do
    end function among

end module test_disk_fleet
