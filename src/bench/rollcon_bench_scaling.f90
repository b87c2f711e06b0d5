! SPDX-License-Identifier: MIT
!> Cost as models grow (`rollcon bench scaling`, docs/benchmark.md): N independent rolling
!> disks (rollcon_disk_fleet) and a chain of N links joined by REVOLUTE joints
!> (rollcon_link_chain) for N = 1, 2, 4, ..., 64, each run as a dataset through the one route
!> (load_job, run_job, no files) on each way of solving, and the CPU time per step and per part
!> against N = 1's, and the memory each run takes per part (the peak resident memory over what
!> the process held before it: Linux's VmHWM, reset before each run through
!> /proc/self/clear_refs). A benchmark, not a test: the ratios are what it reports.
module rollcon_bench_scaling
    use, intrinsic :: iso_c_binding, only : c_int, c_size_t
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_output_files, only : write_text_file
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_disk_fleet, only : disk_fleet_dataset
    use rollcon_link_chain, only : link_chain_dataset
    implicit none
    private

    public :: scaling_row_type, scaling_methods, measure_scaling, scaling_header, scaling_csv_row
    public :: chain_time_share, scaling_table, short_scaling_methods, check_scaling_end_time
    public :: long_chain_methods

    !> The chain runs this share of the disks' time (the programs say "a tenth"), to keep the
    !> benchmark near 2 minutes: over 0.2 s the chain takes 310 IDA steps at one link and 924
    !> at 64 (the disks 4444 over 2 s), and at 64 links the dense matrix's run takes 20 s
    real(wp), parameter :: chain_time_share = 0.1_wp
    !> The end times a benchmark may take [s]: the chain runs chain_time_share of it, and a
    !> dataset's END is 1e-9 s at least and 1e9 s at most (docs/datasets.md, SIMULATE)
    real(wp), parameter :: shortest_end = 1.0e-8_wp, longest_end = 1.0e9_wp
    !> Output step of the runs [s] (of the chain: chain_time_share of it), or the end time
    !> when that is shorter: SIMULATE's DTOUT may not exceed END
    real(wp), parameter :: output_step = 0.1_wp

    !> One (method, N) measured
    type :: scaling_row_type
        character(len=30) :: method = ""
        !> "disks" (rollcon_disk_fleet) or "chain" (rollcon_link_chain)
        character(len=8) :: model = ""
        !> Parts (disks) and the integrator's states
        integer :: parts = 0, states = 0
        integer :: steps = 0, functions = 0, jacobians = 0
        !> CPU time of the integration [s], per step and part [us], and that over N = 1's
        real(wp) :: cpu = 0.0_wp, per_step_part = 0.0_wp, ratio = 0.0_wp
        !> CPU time of the rest of the run [s]: reading the dataset, building the model, its
        !> initial conditions' analysis (what a user waits for before the first step)
        real(wp) :: startup = 0.0_wp
        !> The process's peak resident memory during the run [KiB], and what the run took over
        !> what the process held before it, per part [KiB] (-1: Linux's /proc not readable)
        integer :: peak_kib = -1
        real(wp) :: memory_per_part = -1.0_wp
        character(len=:), allocatable :: status
    end type scaling_row_type


    interface
        !> glibc's malloc_trim(3): the heap's free memory returned to the system (released:
        !> 1 when some was)
        function malloc_trim(pad) result(released) bind(c, name="malloc_trim")
            import :: c_int, c_size_t
            integer(c_size_t), value :: pad
            integer(c_int) :: released
        end function malloc_trim
    end interface

contains

    !> The methods measured: their names (a chain's begin with "chain-"), and their INTEGRATOR
    !> keywords (rtol 1e-8, atol 1e-10, as the coin's run): on the disks IDA and CVODE Adams on
    !> the ODE form and in independent speeds, each with the dense and the sparse Newton matrix
    !> (KLU), and CVODE Adams on the ODE form with fixed-point iteration (no Newton matrix);
    !> on the chain IDA and CVODE's ODE form, dense, sparse and fixed-point, and CVODE Adams in
    !> independent speeds by fixed-point iteration; on both, the default (IDA, the Newton
    !> matrix the size chooses: linear_solver = 'auto').
    subroutine scaling_methods(names, keywords)
        character(len=30), allocatable, intent(out) :: names(:)
        character(len=96), allocatable, intent(out) :: keywords(:)
        character(len=*), parameter :: tolerances = "RTOL=1e-8, ATOL=1e-10", &
            & cvode = "FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, " // tolerances, &
            & maggi = "FORMULATION=MAGGI, METHOD=ADAMS, DRIFT=BAUMGARTE, " // tolerances, &
            & ida = "FORMULATION=IDA, " // tolerances, dense = ", SOLVER=DENSE", &
            & sparse = ", SOLVER=SPARSE", fixed_point = ", JACOBIAN=NONE"

        names = [character(len=30) :: "default", "ida", "ida-klu", "cvode-adams-baumgarte", &
            & "cvode-adams-klu", "maggi-adams", "maggi-adams-klu", "cvode-adams-fixed-point", &
            & "chain-default", "chain-ida", "chain-ida-klu", "chain-cvode-adams", &
            & "chain-cvode-adams-klu", "chain-cvode-adams-fixed-point", &
            & "chain-maggi-adams-fixed-point"]
        keywords = [character(len=96) :: tolerances, ida // dense, ida // sparse, &
            & cvode // dense, cvode // sparse, maggi // dense, maggi // sparse, &
            & cvode // fixed_point, tolerances, ida // dense, ida // sparse, cvode // dense, &
            & cvode // sparse, cvode // fixed_point, maggi // fixed_point]
    end subroutine scaling_methods

    !> Refuse an end time the benchmark's datasets cannot take (shortest_end to longest_end, a
    !> finite number) [s], naming the option the programs read it from.
    subroutine check_scaling_end_time(end_time, error)
        real(wp), intent(in) :: end_time
        type(error_type), allocatable, intent(out) :: error

        if (end_time >= shortest_end .and. end_time <= longest_end) return
        call fatal_error(error, "bench scaling: --end-time expects a time from 1e-8 to 1e9 s " &
            & // "(the chain runs a tenth of it, and a dataset's END is from 1e-9 to 1e9 s), got " &
            & // to_text(end_time), stat_input)
    end subroutine check_scaling_end_time

    !> Run every method (or those named in `only`) on N = counts(:) disks, 0.5 m apart, to
    !> end_time [s], or on a chain of N links to chain_time_share of it; the datasets are
    !> written to folder (disk_fleet_<N>_<method>.adm, link_chain_<N>_<method>.adm). Rows in
    !> method order, then N.
    subroutine measure_scaling(folder, counts, end_time, rows, error, only)
        character(len=*), intent(in) :: folder
        integer, intent(in) :: counts(:)
        real(wp), intent(in) :: end_time
        type(scaling_row_type), allocatable, intent(out) :: rows(:)
        type(error_type), allocatable, intent(out) :: error
        !> The methods to run, by name (default: all of scaling_methods)
        character(len=*), intent(in), optional :: only(:)
        character(len=30), allocatable :: names(:)
        character(len=96), allocatable :: keywords(:)
        character(len=:), allocatable :: path
        type(job_type) :: job
        type(job_result_type) :: ran
        logical, allocatable :: chosen(:)
        logical :: chain
        integer :: m, k, r, resident_before
        real(wp) :: cpu_before, cpu_after

        call check_scaling_end_time(end_time, error)
        if (allocated(error)) return
        call scaling_methods(names, keywords)
        chosen = [(.true., m = 1, size(names))]
        if (present(only)) chosen = [(any(only == names(m)), m = 1, size(names))]
        allocate(rows(count(chosen)*size(counts)))
        ! warm-up, not measured: the first run of a process paid 60 % more per step than the
        ! same run after it (5.55 against 3.44 us on one disk: page faults, cold caches)
        path = folder // "/disk_fleet_warm_up.adm"
        call write_text_file(path, disk_fleet_dataset(1, 0.5_wp, end_time, &
            & min(output_step, end_time), &
            & trim(keywords(findloc(chosen, .true., dim=1)))), error)
        if (allocated(error)) return
        call run_dataset(path, job, ran, error)
        if (allocated(error)) return
        r = 0
        do m = 1, size(names)
            if (.not. chosen(m)) cycle
            chain = index(names(m), "chain-") == 1
            do k = 1, size(counts)
                r = r + 1
                if (chain) then
                    path = folder // "/link_chain_" // to_text(counts(k)) // "_" &
                        & // trim(names(m)) // ".adm"
                    call write_text_file(path, link_chain_dataset(counts(k), &
                        & chain_time_share*end_time, chain_time_share*min(output_step, &
                        & end_time), &
                        & trim(keywords(m))), error)
                else
                    path = folder // "/disk_fleet_" // to_text(counts(k)) // "_" &
                        & // trim(names(m)) // ".adm"
                    call write_text_file(path, disk_fleet_dataset(counts(k), 0.5_wp, end_time, &
                        & min(output_step, end_time), trim(keywords(m))), error)
                end if
                if (allocated(error)) return
                ! the last run's job and result freed first, outside the time taken (freeing
                ! a 64-part run's memory cost a following run of one disk 2 ms)
                job = job_type()
                ran = job_result_type()
                call reset_peak_memory()
                resident_before = memory_kib("VmRSS:")
                call cpu_time(cpu_before)
                call run_dataset(path, job, ran, error)
                if (allocated(error)) return
                call cpu_time(cpu_after)
                rows(r)%peak_kib = memory_kib("VmHWM:")
                if (rows(r)%peak_kib >= 0 .and. resident_before >= 0) rows(r)%memory_per_part &
                    & = real(rows(r)%peak_kib - resident_before, wp)/real(counts(k), wp)
                associate (row => rows(r), s => ran%summary)
                    row%method = names(m)
                    row%model = trim(merge("chain", "disks", chain))
                    row%parts = counts(k)
                    row%states = states_of(trim(keywords(m)), size(s%q), size(s%ucon_position), &
                        & count(s%ucon_position))
                    row%steps = s%steps
                    row%functions = s%functions
                    row%jacobians = s%jacobians
                    row%cpu = s%cpu_seconds
                    row%per_step_part = 1.0e6_wp*s%cpu_seconds/real(max(s%steps, 1)*counts(k), wp)
                    row%ratio = row%per_step_part/rows(r - k + 1)%per_step_part
                    row%startup = max(cpu_after - cpu_before - s%cpu_seconds, 0.0_wp)
                    row%status = s%message
                    if (len(row%status) == 0) row%status = "completed"
                end associate
            end do
        end do
    end subroutine measure_scaling

    !> The chain's methods `rollcon bench scaling` runs on long chains too (to 640 links): the
    !> sparse Newton matrix's (the default picks it there), whose memory grows as the model.
    pure function long_chain_methods() result(names)
        character(len=30) :: names(2)

        names = [character(len=30) :: "chain-default", "chain-ida-klu"]
    end function long_chain_methods

    !> Reset the process's peak resident memory (VmHWM) to what it holds now: Linux's
    !> /proc/self/clear_refs, "5" (proc(5)); nothing where that cannot be written. The heap's
    !> free memory is returned to the system first (glibc's malloc_trim): what the runs before
    !> freed would else stay resident and be reused, and a run would read low by what it
    !> reused (the chain's 640 links 50.7 kB a link where a fresh process's peak grows by 83).
    subroutine reset_peak_memory()
        integer :: unit, stat
        integer(c_int) :: released

        released = malloc_trim(0_c_size_t)

        open(newunit=unit, file="/proc/self/clear_refs", action="write", status="old", &
            & iostat=stat)
        if (stat /= 0) return
        write(unit, "(a)", iostat=stat) "5"
        close(unit, iostat=stat)
    end subroutine reset_peak_memory

    !> A memory figure of this process from /proc/self/status [KiB]: key "VmRSS:" (resident
    !> now) or "VmHWM:" (the peak since start or the last reset_peak_memory); -1 when it cannot
    !> be read.
    integer function memory_kib(key) result(kib)
        character(len=*), intent(in) :: key
        character(len=256) :: line
        integer :: unit, stat

        kib = -1
        open(newunit=unit, file="/proc/self/status", action="read", status="old", iostat=stat)
        if (stat /= 0) return
        do
            read(unit, "(a)", iostat=stat) line
            if (stat /= 0) exit
            if (index(line, key) /= 1) cycle
            read(line(len(key) + 1:), *, iostat=stat) kib
            if (stat /= 0) kib = -1
            exit
        end do
        close(unit, iostat=stat)
    end function memory_kib

    !> Load the dataset at path and run it through the one route, quietly and writing no files.
    subroutine run_dataset(path, job, ran, error)
        character(len=*), intent(in) :: path
        type(job_type), intent(inout) :: job
        type(job_result_type), intent(inout) :: ran
        type(error_type), allocatable, intent(out) :: error

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, ran, error)
    end subroutine run_dataset

    !> The integrator's states of a method (by its INTEGRATOR keywords) on a model of n
    !> coordinates, nc UCONs, nh of them position UCONs: 2 n (q, u) for CVODE's ODE form,
    !> 2 n + nc + nh with IDA's multipliers (the default), 2 n - nc in independent speeds.
    pure integer function states_of(keywords, n, nc, nh) result(states)
        character(len=*), intent(in) :: keywords
        integer, intent(in) :: n, nc, nh

        if (index(keywords, "FORMULATION=CVODE") > 0) then
            states = 2*n
        else if (index(keywords, "FORMULATION=MAGGI") > 0) then
            states = 2*n - nc
        else
            states = 2*n + nc + nh
        end if
    end function states_of

    !> The methods of the short table `rollcon bench` prints: the default way of solving on
    !> the disks and on the chain.
    pure function short_scaling_methods() result(names)
        character(len=30) :: names(2)

        names = [character(len=30) :: "default", "chain-default"]
    end function short_scaling_methods

    !> The rows as the table the benchmark prints: a header line, then one line per row (model,
    !> method, N, states, steps, us per step and part, ratio to N = 1, start-up [ms], the peak
    !> resident memory [MB] and the run's memory per part [kB], status), each ending in a new
    !> line.
    function scaling_table(rows) result(text)
        type(scaling_row_type), intent(in) :: rows(:)
        character(len=:), allocatable :: text
        character(len=180) :: line
        integer :: k

        text = "  model   method                            N  states   steps  us/step/part" &
            & // "  ratio to N = 1  start-up [ms]  peak [MB]  kB/part" // new_line("a")
        do k = 1, size(rows)
            write(line, "(2x, a8, a30, i5, i8, i8, f14.2, f16.2, f15.1, f11.1, f9.1, 2x, a)") &
                & rows(k)%model, rows(k)%method, rows(k)%parts, rows(k)%states, rows(k)%steps, &
                & rows(k)%per_step_part, rows(k)%ratio, 1.0e3_wp*rows(k)%startup, &
                & 1.024e-3_wp*real(rows(k)%peak_kib, wp), 1.024_wp*rows(k)%memory_per_part, &
                & trim(rows(k)%status)
            text = text // trim(line) // new_line("a")
        end do
    end function scaling_table

    !> Header of the scaling CSV.
    pure function scaling_header() result(header)
        character(len=:), allocatable :: header

        header = "model,method,parts,states,steps,function_evaluations,jacobian_evaluations," &
            & // "cpu_s,cpu_per_step_part_us,ratio_to_one_part,peak_resident_kib," &
            & // "memory_per_part_kib,startup_cpu_s,status"
    end function scaling_header

    !> One CSV row.
    function scaling_csv_row(row) result(line)
        type(scaling_row_type), intent(in) :: row
        character(len=:), allocatable :: line

        line = trim(row%model) // "," // trim(row%method) // "," // to_text(row%parts) // "," &
            & // to_text(row%states) &
            & // "," // to_text(row%steps) // "," // to_text(row%functions) // "," &
            & // to_text(row%jacobians) // "," // to_text(row%cpu) // "," &
            & // to_text(row%per_step_part) // "," // to_text(row%ratio) // "," &
            & // to_text(row%peak_kib) // "," // to_text(row%memory_per_part) // "," &
            & // to_text(row%startup) // "," // row%status
    end function scaling_csv_row

end module rollcon_bench_scaling
