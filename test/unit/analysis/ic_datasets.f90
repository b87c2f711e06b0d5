! SPDX-License-Identifier: MIT
!> The initial-conditions analysis of datasets: PART's EXACT keyword read and refused, the
!> analysis holding a dataset's exact coordinates, and `rollcon run MODEL.adm` printing its
!> report (not with -q) or refusing a start it cannot make consistent.
module ic_datasets
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_adm_initial, only : adm_ic_options
    use rollcon_initial_conditions, only : analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type, ic_report_text
    use rollcon_body, only : body_angular_velocity
    use command_runs, only : rollcon_program, run_rollcon, file_text
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_exact_read, test_exact_refused, test_dataset_exact, test_dataset_run
    public :: test_given_kept, test_defaulted_moved, test_given_contradicted

    !> Scratch folder of these tests
    character(len=*), parameter :: scratch = "build/test_initial_conditions"
    !> Lines of data/coin.adm the tests replace
    character(len=*), parameter :: part_line = "PART/2, MASS=0.73513268094001172, CM=3", &
        & height_line = ", QG=0, 0, 0.1          ! the centre one radius above the ground: " &
        & // "in contact", f3_line = "UCON/3, FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, " &
        & // "26, 0.1, 3)", run_line = "SIMULATE/DYNAMIC, END=10, STEPS=1000"
    !> The height as a position UCON, served by the generated disk_height routine
    character(len=*), parameter :: height_ucon = "UCON/3, FUNCTION=USER(2, 13, 15, 0.1), " &
        & // "ROUTINE=disk_height"
    !> Z recovered: it enters Z - R sin(theta) linearly with theta held (see the suite's
    !> tol_recovered)
    real(wp), parameter :: tol_recovered = 1.0e-12_wp
    !> The velocity level is one linear least-squares solve: its values to rounding of the
    !> wheel's rates (5 rad/s, 1.5 m/s)
    real(wp), parameter :: tol_velocity = 1.0e-12_wp
    !> The wheel of test/initial/wheel_spin_only.adm: its radius [m], and its velocities line
    real(wp), parameter :: wheel_radius = 0.3_wp
    character(len=*), parameter :: wheel_line = ", QG = 0.2, 0.2, 0.3, WX = 1, WY = 0, WZ = -5"

contains

    !> data/coin.adm with lines replaced (old(i) by new(i)), written to scratch/name.
    subroutine write_variant(name, old, new, error)
        character(len=*), intent(in) :: name, old(:), new(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=4096) :: buffer
        integer :: in, out, stat, i, replaced

        call execute_command_line("mkdir -p " // scratch)
        open(newunit=in, file="data/coin.adm", status="old", action="read")
        open(newunit=out, file=scratch // "/" // name, status="replace", action="write")
        replaced = 0
        do
            read(in, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            do i = 1, size(old)
                if (trim(buffer) == trim(old(i))) exit
            end do
            if (i <= size(old)) then
                write(out, '(a)') trim(new(i))
                replaced = replaced + 1
            else
                write(out, '(a)') trim(buffer)
            end if
        end do
        close(in)
        close(out)
        if (replaced /= size(old)) call fatal_error(error, "data/coin.adm: only " &
            & // to_text(replaced) // " of the " // to_text(size(old)) // " lines found")
    end subroutine write_variant

    !> test/initial/wheel_spin_only.adm with its velocities line replaced by line, built with
    !> its routines and analysed: the start (q, u) and the report.
    subroutine wheel_start(name, line, q, u, report, error)
        character(len=*), intent(in) :: name, line
        real(wp), allocatable, intent(out) :: q(:), u(:)
        type(ic_report_type), intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        character(len=4096) :: buffer
        integer :: in, out, stat

        call execute_command_line("mkdir -p " // scratch)
        open(newunit=in, file="test/initial/wheel_spin_only.adm", status="old", action="read")
        open(newunit=out, file=scratch // "/" // name, status="replace", action="write")
        do
            read(in, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            if (trim(buffer) == wheel_line) buffer = line
            write(out, '(a)') trim(buffer)
        end do
        close(in)
        close(out)
        call read_adm(scratch // "/" // name, adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q, u0=u, error=error)
        if (allocated(error)) return
        call analyse_initial_conditions(problem, 0.0_wp, q, u, adm_ic_options(adm, problem), &
            & report, error)
    end subroutine wheel_start

    !> A rolling wheel given only its lean rate WX = 1 and spin WZ = -5 (and WY = 0): ADAMS keeps
    !> a velocity the dataset gives and moves a defaulted one, an "inexact" zero. The angular
    !> velocity stays as given, about the CM marker's axes, and the centre's velocity comes from
    !> the no-slip UCONs: omega x (0, 0, r) = (1.5, -0.3, 0) m/s, the only values moved. (The
    !> analysis weighed given and defaulted alike and halved them: phidot -5 -> -2.27 rad/s,
    !> with 0.68 m/s of centre velocity invented.)
    subroutine test_given_kept(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:), u(:)
        type(ic_report_type) :: report

        call wheel_start("wheel_given.adm", wheel_line, q, u, report, error)
        if (allocated(error)) return
        call check(error, body_angular_velocity(q(1:6), u(1:6)), [1.0_wp, 0.0_wp, -5.0_wp], &
            & "the angular velocity about the CM marker's axes", abs_tol=tol_velocity)
        if (allocated(error)) return
        call check(error, u(1:3), [5.0_wp*wheel_radius, -1.0_wp*wheel_radius, 0.0_wp], &
            & "the centre's velocity [m/s]", abs_tol=tol_velocity)
        if (allocated(error)) return
        call check(error, size(report%changes) == 2 .and. .not. report%given_moved, &
            & ic_report_text(report))
        if (allocated(error)) return
        call check(error, report%changes(1)%name() == "Xdot_2" .and. report%changes(2)%name() &
            & == "Ydot_2", ic_report_text(report))
    end subroutine test_given_kept

    !> Given VX = 1.5 m/s and the lean rate WX = 1 alone: the spin WZ, a defaulted zero, moves
    !> to what rolling at 1.5 m/s needs, -VX/r = -5 rad/s, VY to -WX r; VX and WX stay; the
    !> heading rate WY, which no UCON fixes, stays 0.
    subroutine test_defaulted_moved(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:), u(:)
        type(ic_report_type) :: report

        call wheel_start("wheel_vx.adm", ", QG = 0.2, 0.2, 0.3, VX = 1.5, WX = 1", q, u, &
            & report, error)
        if (allocated(error)) return
        call check(error, body_angular_velocity(q(1:6), u(1:6)), [1.0_wp, 0.0_wp, &
            & -1.5_wp/wheel_radius], "the angular velocity about the CM marker's axes", &
            & abs_tol=tol_velocity)
        if (allocated(error)) return
        call check(error, u(1:3), [1.5_wp, -1.0_wp*wheel_radius, 0.0_wp], &
            & "the centre's velocity [m/s]", abs_tol=tol_velocity)
        if (allocated(error)) return
        call check(error, .not. report%given_moved, ic_report_text(report))
    end subroutine test_defaulted_moved

    !> Every velocity given, and the centre's at rest against the spin: the UCONs cannot be met
    !> with them held, so they are moved with the rest (as ADAMS moves an EXACT value that
    !> contradicts a joint), the report says so, and the start meets the UCONs.
    subroutine test_given_contradicted(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: q(:), u(:)
        type(ic_report_type) :: report
        real(wp) :: omega(3)

        call wheel_start("wheel_all.adm", ", QG = 0.2, 0.2, 0.3, VX = 0, VY = 0, VZ = 0, " &
            & // "WX = 1, WY = 0, WZ = -5", q, u, report, error)
        if (allocated(error)) return
        call check(error, report%given_moved .and. index(ic_report_text(report), &
            & "cannot all be kept with the UCONs met") > 0, ic_report_text(report))
        if (allocated(error)) return
        ! rolling without slip: the centre moves as omega x (0, 0, r), omega in ground =
        ! (WX, -WZ, WY) for the CM marker's axes x = X, y = Z, z = -Y
        omega = body_angular_velocity(q(1:6), u(1:6))
        call check(error, u(1:2), [-omega(3)*wheel_radius, -omega(1)*wheel_radius], &
            & "no slip", abs_tol=tol_velocity)
    end subroutine test_given_contradicted

    !> EXACT=x:Phi:THETA (any case, any order) marks X, theta and phi of the part.
    subroutine test_exact_read(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm

        call write_variant("exact.adm", [character(len=80) :: part_line], &
            & [character(len=80) :: part_line // ", EXACT=x:Phi:THETA"], error)
        if (allocated(error)) return
        call read_adm(scratch // "/exact.adm", adm, error)
        if (allocated(error)) return
        call check(error, all(adm%parts(2)%exact .eqv. [.true., .false., .false., .false., &
            & .true., .true.]) .and. .not. any(adm%parts(1)%exact), "exact flags")
    end subroutine test_exact_read

    !> EXACT=X:W: refused with the file, line, key and the names it takes.
    subroutine test_exact_refused(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(error_type), allocatable :: refused

        call write_variant("exact_bad.adm", [character(len=80) :: part_line], &
            & [character(len=80) :: part_line // ", EXACT=X:W"], error)
        if (allocated(error)) return
        call read_adm(scratch // "/exact_bad.adm", adm, refused)
        call check(error, allocated(refused), "EXACT=X:W read")
        if (allocated(error)) return
        call check(error, refused%message == scratch // "/exact_bad.adm:23: PART/2 EXACT: 'W' " &
            & // "is not a coordinate; expected X, Y, Z, PSI, THETA or PHI, separated by colons", &
            & refused%message)
    end subroutine test_exact_refused

    !> The coin 1 mm high with the height as a position UCON. With X, Y and the angles EXACT,
    !> Z alone moves, back to R; with Z EXACT too, the refusal names UCON/3.
    subroutine test_dataset_exact(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem, held
        type(ic_report_type) :: report
        type(error_type), allocatable :: refused
        procedure(ucosub_interface), pointer :: disk
        real(wp), allocatable :: q0(:), u0(:)

        disk => rolling_disk_ucosub
        call write_variant("high.adm", [character(len=80) :: part_line, height_line, f3_line], &
            & [character(len=80) :: part_line // ", EXACT=X:Y:PSI:THETA:PHI", ", QG=0, 0, 0.101", &
            & height_ucon], error)
        if (allocated(error)) return
        call read_adm(scratch // "/high.adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, problem, q0, u0, error)
        if (allocated(error)) return
        call analyse_initial_conditions(problem, 0.0_wp, q0, u0, adm_ic_options(adm, problem), &
            & report, error)
        if (allocated(error)) return
        call check(error, size(report%changes) == 1, "one value moved")
        if (allocated(error)) return
        call check(error, report%changes(1)%name() == "Z_2", report%changes(1)%name())
        if (allocated(error)) return
        call check(error, q0(3), 0.1_wp, "Z", abs_tol=tol_recovered)
        if (allocated(error)) return
        adm%parts(2)%exact(3) = .true.
        call build_adm_problem(adm, disk, held, q0, u0, error)
        if (allocated(error)) return
        call analyse_initial_conditions(held, 0.0_wp, q0, u0, adm_ic_options(adm, held), &
            & report, refused)
        call check(error, allocated(refused), "Z held too: not refused")
        if (allocated(error)) return
        call check(error, index(refused%message, "initial conditions: UCON/3 cannot be met") &
            & == 1, refused%message)
    end subroutine test_dataset_exact

    !> `rollcon run` on the high coin (0.1 s) prints the report naming Z_2; with -q it does
    !> not; and a dataset whose height is held 1 mm off exits 1 naming the file and UCON/3.
    subroutine test_dataset_run(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, out, quiet_out, err
        integer :: status, quiet_status, refused_status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call write_variant("run_high.adm", [character(len=80) :: part_line, height_line, &
            & f3_line, run_line], [character(len=80) :: part_line // ", EXACT=X:Y:PSI:THETA:PHI", &
            & ", QG=0, 0, 0.101", height_ucon, "SIMULATE/DYNAMIC, END=0.1, STEPS=10"], error)
        if (allocated(error)) return
        call write_variant("run_held.adm", [character(len=80) :: part_line, height_line, &
            & f3_line], [character(len=80) :: part_line // ", EXACT=Z:THETA", &
            & ", QG=0, 0, 0.101", height_ucon], error)
        if (allocated(error)) return
        call run_rollcon(program, "run " // scratch // "/run_high.adm -o " // scratch, &
            & scratch // "/run.out", scratch // "/run.err", status)
        out = file_text(scratch // "/run.out")
        call run_rollcon(program, "run " // scratch // "/run_high.adm -q -o " // scratch, &
            & scratch // "/quiet.out", scratch // "/quiet.err", quiet_status)
        quiet_out = file_text(scratch // "/quiet.out")
        call run_rollcon(program, "run " // scratch // "/run_held.adm -q -o " // scratch, &
            & scratch // "/held.out", scratch // "/held.err", refused_status)
        err = file_text(scratch // "/held.err")
        call check(error, status == 0 .and. index(out, "part 2: Z_2 0.101 m -> 0.1") > 0 .and. &
            & index(out, "status: completed") > 0, "exit status " // to_text(status) // ": " &
            & // out // file_text(scratch // "/run.err"))
        if (allocated(error)) return
        call check(error, quiet_status == 0 .and. index(quiet_out, "initial conditions") == 0, &
            & "with -q: " // quiet_out)
        if (allocated(error)) return
        call check(error, refused_status == 1 .and. index(err, "rollcon: error: " // scratch &
            & // "/run_held.adm: initial conditions: UCON/3 cannot be met at position level") &
            & == 1 .and. index(file_text(scratch // "/held.out"), "completed") == 0, &
            & "exit status " // to_text(refused_status) // ": " // err)
    end subroutine test_dataset_run

end module ic_datasets
