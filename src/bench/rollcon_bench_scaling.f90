! SPDX-License-Identifier: MIT
!> Cost as models grow (`rollcon bench scaling`, docs/benchmark.md): N independent rolling
!> disks (rollcon_disk_fleet) for N = 1, 2, 4, ..., 64, each run as a dataset through the one
!> route (load_job, run_job, no files) on each formulation, and the CPU time per step and per
!> part against N = 1's. A benchmark, not a test: the ratios are what it reports.
module rollcon_bench_scaling
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_files, only : write_text_file
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_disk_fleet, only : disk_fleet_dataset
    implicit none
    private

    public :: scaling_row_type, scaling_methods, measure_scaling, scaling_header, scaling_csv_row

    !> One (method, N) measured
    type :: scaling_row_type
        character(len=24) :: method = ""
        !> Parts (disks) and the integrator's states
        integer :: parts = 0, states = 0
        integer :: steps = 0, functions = 0, jacobians = 0
        !> CPU time of the integration [s], per step and part [us], and that over N = 1's
        real(wp) :: cpu = 0.0_wp, per_step_part = 0.0_wp, ratio = 0.0_wp
        character(len=:), allocatable :: status
    end type scaling_row_type

contains

    !> The methods measured: their names and their INTEGRATOR keywords (rtol 1e-8, atol 1e-10,
    !> as the coin's run): IDA, CVODE Adams on the ODE form and in independent speeds, the last
    !> two also with the sparse Newton matrix (KLU).
    subroutine scaling_methods(names, keywords)
        character(len=24), allocatable, intent(out) :: names(:)
        character(len=96), allocatable, intent(out) :: keywords(:)

        names = [character(len=24) :: "ida", "cvode-adams-baumgarte", "maggi-adams", &
            & "cvode-adams-klu", "maggi-adams-klu"]
        keywords = [character(len=96) :: "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10", &
            & "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10", &
            & "FORMULATION=MAGGI, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10", &
            & "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, " &
            & // "SOLVER=SPARSE", &
            & "FORMULATION=MAGGI, METHOD=ADAMS, DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, " &
            & // "SOLVER=SPARSE"]
    end subroutine scaling_methods

    !> Run every method on N = counts(:) disks, 0.5 m apart, to end_time [s]; the datasets are
    !> written to folder (disk_fleet_<N>.adm). Rows in method order, then N.
    subroutine measure_scaling(folder, counts, end_time, rows, error)
        character(len=*), intent(in) :: folder
        integer, intent(in) :: counts(:)
        real(wp), intent(in) :: end_time
        type(scaling_row_type), allocatable, intent(out) :: rows(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=24), allocatable :: names(:)
        character(len=96), allocatable :: keywords(:)
        character(len=:), allocatable :: path
        type(job_type) :: job
        type(job_result_type) :: ran
        integer :: m, k, r

        call scaling_methods(names, keywords)
        allocate(rows(size(names)*size(counts)))
        r = 0
        do m = 1, size(names)
            do k = 1, size(counts)
                r = r + 1
                path = folder // "/disk_fleet_" // to_text(counts(k)) // "_" // trim(names(m)) &
                    & // ".adm"
                call write_text_file(path, disk_fleet_dataset(counts(k), 0.5_wp, end_time, &
                    & 0.1_wp, trim(keywords(m))), error)
                if (allocated(error)) return
                call load_job(path, job, error)
                if (allocated(error)) return
                job%output_dir = ""
                job%quiet = .true.
                call run_job(job, ran, error)
                if (allocated(error)) return
                associate (row => rows(r), s => ran%summary)
                    row%method = names(m)
                    row%parts = counts(k)
                    row%states = states_of(trim(names(m)), counts(k))
                    row%steps = s%steps
                    row%functions = s%functions
                    row%jacobians = s%jacobians
                    row%cpu = s%cpu_seconds
                    row%per_step_part = 1.0e6_wp*s%cpu_seconds/real(max(s%steps, 1)*counts(k), wp)
                    row%ratio = row%per_step_part/rows(r - k + 1)%per_step_part
                    row%status = s%message
                    if (len(row%status) == 0) row%status = "completed"
                end associate
            end do
        end do
    end subroutine measure_scaling

    !> The integrator's states of a method on N disks: 12 N (q, u) for CVODE's ODE form, 15 N
    !> with IDA's multipliers, 9 N in independent speeds.
    pure integer function states_of(method, parts) result(states)
        character(len=*), intent(in) :: method
        integer, intent(in) :: parts

        select case (method)
        case ("ida")
            states = 15*parts
        case ("maggi-adams", "maggi-adams-klu")
            states = 9*parts
        case default
            states = 12*parts
        end select
    end function states_of

    !> Header of the scaling CSV.
    pure function scaling_header() result(header)
        character(len=:), allocatable :: header

        header = "method,parts,states,steps,function_evaluations,jacobian_evaluations,cpu_s," &
            & // "cpu_per_step_part_us,ratio_to_one_part,status"
    end function scaling_header

    !> One CSV row.
    function scaling_csv_row(row) result(line)
        type(scaling_row_type), intent(in) :: row
        character(len=:), allocatable :: line

        line = trim(row%method) // "," // to_text(row%parts) // "," // to_text(row%states) &
            & // "," // to_text(row%steps) // "," // to_text(row%functions) // "," &
            & // to_text(row%jacobians) // "," // to_text(row%cpu) // "," &
            & // to_text(row%per_step_part) // "," // to_text(row%ratio) // "," // row%status
    end function scaling_csv_row

end module rollcon_bench_scaling
