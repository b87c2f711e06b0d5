! SPDX-License-Identifier: MIT
!> A dataset becomes a problem that runs: data/coin.adm against data/coin.nml (the same
!> equations, so the same history bit for bit and the same stops), a disk and a sphere from one
!> dataset (data/disk_and_sphere.adm), and the refusals of build_adm_problem.
!> (The two-part run's checks are in adm_build_two_parts.)
module test_adm_build
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_ucosub_catalog, only : builtin_ucosub_names
    use rollcon_force, only : force_breakpoints
    use rollcon_problem, only : problem_type
    use rollcon_theta_watch, only : theta_watch_type
    use rollcon_run_settings, only : formulation_ida
    use rollcon_scene, only : scene_type, read_scene
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & status_completed
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem, adm_theta_min
    use adm_build_support, only : read_lines_model
    use adm_build_two_parts, only : test_disk_and_sphere
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_adm_build

    !> coin.adm and coin.nml describe the same equations: evaluated by the same operations in the
    !> same order (the strike's force and moment are the scene's to the last bit, see
    !> data/coin.adm), their accelerations and multipliers agree bit for bit at any time and
    !> state, inside the strike's pulse too; from the same initial state and with the same stops
    !> the runs agree bit for bit up to the strike (t = 2 s). Past it their Newton matrices
    !> differ (the dataset's GFORCE carries its exact partials, the scene's strike none), so the
    !> two histories part at round-off, and nothing looser than bit equality of the equations
    !> would mean "the same equations": the coin at 0.1 m/s is unstable and the integrator's
    !> adaptive steps amplify, so a one-ulp change of the initial theta and phidot alone moves
    !> the history by 5e-4 relative at t = 3 s (measured)
    real(wp), parameter :: tol_same_run = 0.0_wp
    !> Initial states: the dataset's angles come from the CM marker's rotation matrix, the
    !> scene's are written; they agree exactly for the coin (the 3-1-3 angles of a 90 degree
    !> turn about x are recovered exactly)
    real(wp), parameter :: tol_same_start = 0.0_wp

contains

    subroutine collect_adm_build(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("coin-adm-as-coin-nml", test_coin_same_run), &
            & new_unittest("coin-adm-same-stops", test_coin_same_stops), &
            & new_unittest("coin-adm-model", test_coin_model), &
            & new_unittest("no-routine-refused", test_no_routine), &
            & new_unittest("builtin-in-millimetres-refused", test_builtin_units), &
            & new_unittest("missing-marker-refused", test_missing_marker), &
            & new_unittest("force-not-finite-refused", test_force_not_finite), &
            & new_unittest("disk-and-sphere", test_disk_and_sphere), &
            & new_unittest("working-force-not-judged", test_working_force)]
    end subroutine collect_adm_build

    !> The problem of data/coin.adm with the hand-checked disk routine.
    subroutine coin_adm_problem(problem, q0, u0, error)
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        procedure(ucosub_interface), pointer :: disk

        disk => rolling_disk_ucosub
        call read_adm("data/coin.adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, problem, q0, u0, error)
    end subroutine coin_adm_problem

    !> Both runs to t = 3 s: every row's time, state and energy agree bit for bit up to the
    !> strike; the two problems' accelerations and multipliers agree bit for bit at times
    !> inside and after the strike's pulse, at the start and at a tipped state.
    subroutine test_coin_same_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: from_adm, from_nml
        type(scene_type) :: scene
        type(run_options_type) :: options
        type(run_summary_type) :: summary_adm, summary_nml
        type(history_type) :: history_adm, history_nml
        real(wp), allocatable :: q0(:), u0(:), a_adm(:), a_nml(:), lambda_adm(:), lambda_nml(:)
        real(wp) :: q6(6), u6(6), q(6), time
        integer :: i, k, tipped

        call coin_adm_problem(from_adm, q0, u0, error)
        if (allocated(error)) return
        call read_scene("data/coin.nml", scene, error)
        if (allocated(error)) return
        call build_disk_problem(scene, rolling_disk_ucosub, from_nml, q6, u6, error)
        if (allocated(error)) return
        call check(error, from_adm%settings%formulation == formulation_ida &
            & .and. from_adm%settings%rtol == from_nml%settings%rtol &
            & .and. from_adm%settings%atol == from_nml%settings%atol, "solver settings")
        if (allocated(error)) return
        call check(error, q0, q6, "initial coordinates", abs_tol=tol_same_start)
        if (allocated(error)) return
        call check(error, u0, u6, "initial rates", abs_tol=tol_same_start)
        if (allocated(error)) return
        options%end_time = 3.0_wp
        options%output_step = 0.01_wp
        options%progress = .false.
        call simulate(from_adm, q0, u0, options, summary_adm, error, history_adm)
        if (allocated(error)) return
        call simulate(from_nml, q6, u6, options, summary_nml, error, history_nml)
        if (allocated(error)) return
        call check(error, summary_adm%status == status_completed .and. &
            & summary_nml%status == status_completed .and. history_adm%count == 301 &
            & .and. history_nml%count == 301, "both runs reach t = 3 s with 301 rows")
        if (allocated(error)) return
        ! the strike tipped the disk: theta left upright by more than 0.1 rad (else the
        ! equations' strike terms would be checked at a trivial state)
        call check(error, maxval(abs(history_adm%rows(6, :301) - history_adm%rows(6, 1))) &
            & > 0.1_wp, "the strike tips the disk")
        if (allocated(error)) return
        ! rows 1..201: t <= 2 s, up to the strike
        do i = 1, 201
            ! columns 1..14: t, the part's 12 coordinates and rates, E (one part)
            call check(error, history_adm%rows(:14, i), history_nml%rows(:14, i), "row " &
                & // to_text(i) // " (t = " // to_text(history_nml%rows(1, i)) // " s)", &
                & abs_tol=tol_same_run)
            if (allocated(error)) return
        end do
        ! the equations: at the start's state and at the start's with theta set to the run's
        ! most tipped value (columns 2..7: X, Y, Z, psi, theta, phi), at times before, inside
        ! (every millisecond of the 10 ms pulse) and after the strike
        tipped = maxloc(abs(history_adm%rows(6, :301) - history_adm%rows(6, 1)), 1)
        allocate(a_adm(from_adm%eq%n), a_nml(from_nml%eq%n), lambda_adm(from_adm%eq%nc), &
            & lambda_nml(from_nml%eq%nc))
        do k = 0, 13
            q = q6
            if (k >= 7) q(5) = history_adm%rows(6, tipped)
            time = 1.9995_wp + 0.002_wp*real(mod(k, 7), wp)
            call from_adm%eq%accelerations(time, q, u6, 0.0_wp, a_adm, lambda_adm, error)
            if (allocated(error)) return
            call from_nml%eq%accelerations(time, q, u6, 0.0_wp, a_nml, lambda_nml, error)
            if (allocated(error)) return
            call check(error, all(a_adm == a_nml) .and. all(lambda_adm == lambda_nml), &
                & "the accelerations or multipliers differ at t = " // to_text(time) &
                & // " s, theta = " // to_text(q(5)) // " rad")
            if (allocated(error)) return
        end do
        ! inside the pulse the strike acts (the equations differ from those just before it)
        call from_adm%eq%accelerations(1.9995_wp, q6, u6, 0.0_wp, a_nml, lambda_nml, error)
        if (allocated(error)) return
        call from_adm%eq%accelerations(2.0055_wp, q6, u6, 0.0_wp, a_adm, lambda_adm, error)
        if (allocated(error)) return
        call check(error, any(a_adm /= a_nml), "the strike does not act at t = 2.0055 s")
    end subroutine test_coin_same_run

    !> The GFORCE's IF pulse stops the integrator where the scene's half-sine does: the same
    !> 21 times from 2 s to 2.01 s, bit for bit; and the energy reference follows the last.
    subroutine test_coin_same_stops(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: from_adm, from_nml
        type(scene_type) :: scene
        real(wp), allocatable :: q0(:), u0(:), stops_adm(:), stops_nml(:)
        real(wp) :: q6(6), u6(6)
        integer :: k

        call coin_adm_problem(from_adm, q0, u0, error)
        if (allocated(error)) return
        call read_scene("data/coin.nml", scene, error)
        if (allocated(error)) return
        call build_disk_problem(scene, rolling_disk_ucosub, from_nml, q6, u6, error)
        if (allocated(error)) return
        stops_adm = force_breakpoints(from_adm%model%forces)
        stops_nml = force_breakpoints(from_nml%model%forces)
        call check(error, size(stops_adm) == 21 .and. size(stops_nml) == 21, "21 stops each, " &
            & // "got " // to_text(size(stops_adm)) // " and " // to_text(size(stops_nml)))
        if (allocated(error)) return
        do k = 1, 21
            call check(error, any(stops_adm == stops_nml(k)), "stop " // to_text(stops_nml(k)) &
                & // " s of coin.nml missing from coin.adm's")
            if (allocated(error)) return
        end do
        call check(error, minval(stops_adm) == 2.0_wp .and. maxval(stops_adm) == 2.01_wp, &
            & "first and last stop")
    end subroutine test_coin_same_stops

    !> What coin.adm becomes: one part with the coin's mass and inertia, three time-free UCONs,
    !> gravity, one force statement, the default theta limit, no lift-off watch.
    subroutine test_coin_model(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)

        call coin_adm_problem(problem, q0, u0, error)
        if (allocated(error)) return
        associate (model => problem%model)
            call check(error, size(model%parts) == 1 .and. model%parts(1)%id == 2 &
                & .and. size(model%ucons) == 3 .and. size(model%forces) == 1, "counts")
            if (allocated(error)) return
            call check(error, all(model%ucons%time_free) .and. all(model%ucons%id == [1, 2, 3]), &
                & "UCONs served by the hand disk routine, time-free")
            if (allocated(error)) return
            ! 7800 pi R^2 h and m R^2 / 2, as written in the dataset
            call check(error, [model%parts(1)%mass, model%parts(1)%inertia(3)], &
                & [7800.0_wp*acos(-1.0_wp)*0.01_wp*0.003_wp, &
                & 0.5_wp*7800.0_wp*acos(-1.0_wp)*0.01_wp*0.003_wp*0.01_wp], "mass and C", &
                & rel_tol=1.0e-15_wp)
            if (allocated(error)) return
            call check(error, model%gravity, [0.0_wp, 0.0_wp, -9.81_wp], "gravity", &
                & abs_tol=0.0_wp)
            if (allocated(error)) return
        end associate
        ! one watch: every part's theta limit, re-basing there (no contact, no lift-off)
        call check(error, size(problem%watches) == 1 .and. problem%root_count() == 1, "watches")
        if (allocated(error)) return
        select type (watch => problem%watches(1)%watch)
        type is (theta_watch_type)
            call check(error, watch%theta_min == adm_theta_min .and. watch%rebase, &
                & "the theta watch: re-basing at adm_theta_min")
        class default
            call check(error, .false., "the watch is not a theta watch")
        end select
    end subroutine test_coin_model

    !> A UCON without ROUTINE= and no model routine: refused, naming the UCON, its line and the
    !> fix.
    subroutine test_no_routine(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)
        type(error_type), allocatable :: refused

        call read_adm("data/coin.adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q0, u0=u0, error=refused)
        call check(error, allocated(refused), "built without a routine")
        if (allocated(error)) return
        call check(error, refused%message == "data/coin.adm:38: UCON/1: no UCOSUB serves this " &
            & // "UCON: name a built-in routine with ROUTINE=name (" // builtin_ucosub_names() &
            & // ") or give the model's UCOSUB (rollcon run MODEL.adm --ucosub FILE|NAME)", &
            & refused%message)
    end subroutine test_no_routine

    !> The coin with UNITS/LENGTH=MILLIMETER, served by the built-in disk routine: built, every
    !> UCON computing in the dataset's units (the runs are compared in suite ucosub-units):
    !> the velocities passed in mm/s (scale 1000 per m/s), the rates and angles as they are, F
    !> (a velocity) turned back to m/s (1e-3).
    subroutine test_builtin_units(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)
        procedure(ucosub_interface), pointer :: disk

        call read_lines_model("coin_mm.adm", "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER" &
            & // ", TIME=SECOND", "UNITS/LENGTH=MILLIMETER", adm, error)
        if (allocated(error)) return
        disk => rolling_disk_ucosub
        call build_adm_problem(adm, disk, problem, q0, u0, error)
        if (allocated(error)) return
        associate (ucon => problem%model%ucons(1))
            ! the coin's PAR(2:9): Xdot, Ydot, Zdot, psi, theta, psidot, thetadot, phidot
            call check(error, ucon%converted .and. all(ucon%scales == [1.0e3_wp, 1.0e3_wp, &
                & 1.0e3_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp]) .and. ucon%value_scale &
                & == 1.0e-3_wp .and. ucon%time_scale == 1.0_wp, "the UCON's unit factors")
        end associate
    end subroutine test_builtin_units

    !> A state function of a marker the dataset does not have: refused with the statement, the
    !> key, the function and the id.
    subroutine test_missing_marker(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)
        type(error_type), allocatable :: refused
        procedure(ucosub_interface), pointer :: disk

        call read_lines_model("coin_marker.adm", ", TX=-(SIN(THETA(3))*0.1)*IF(TIME - 2: 0, 0", &
            & ", TX=-(SIN(THETA(7))*0.1)*IF(TIME - 2: 0, 0", adm, error)
        if (allocated(error)) return
        disk => rolling_disk_ucosub
        call build_adm_problem(adm, disk, problem, q0, u0, refused)
        call check(error, allocated(refused), "built with a missing marker")
        if (allocated(error)) return
        call check(error, refused%message == "build/rollcon-test/coin_marker.adm:51: GFORCE/5 " &
            & // "TX: THETA(7): no MARKER/7 in the dataset", refused%message)
    end subroutine test_missing_marker

    !> A force expression that is NaN at the start (LOG of DZ - 1 < 0): refused with the
    !> statement and key.
    subroutine test_force_not_finite(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:)
        type(error_type), allocatable :: refused
        procedure(ucosub_interface), pointer :: disk

        call read_lines_model("coin_nan.adm", "GFORCE/5, I=3, JFLOAT=2, RM=1, FX=0, FZ=0, TY=0", &
            & "GFORCE/5, I=3, JFLOAT=2, RM=1, FX=LOG(DZ(3) - 1), FZ=0, TY=0", adm, error)
        if (allocated(error)) return
        disk => rolling_disk_ucosub
        call build_adm_problem(adm, disk, problem, q0, u0, refused)
        call check(error, allocated(refused), "built with a NaN force")
        if (allocated(error)) return
        call check(error, refused%message == "build/rollcon-test/coin_nan.adm:51: GFORCE/5 FX: " &
            & // "the expression is not finite at t = 0 (NaN): a function outside its domain, " &
            & // "or a division by zero", refused%message)
    end subroutine test_force_not_finite

    !> A force acting until the end does work: the energy is then not conserved and its change
    !> is not judged as drift (the run completes, not INACCURATE); the coin's strike, which ends
    !> at 2.01 s, leaves the energy judged after it.
    subroutine test_working_force(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: pushed, struck
        type(run_options_type) :: options
        type(run_summary_type) :: summary_pushed, summary_struck
        real(wp), allocatable :: q0(:), u0(:)
        procedure(ucosub_interface), pointer :: disk

        disk => rolling_disk_ucosub
        ! 0.05 N along +X at the centre throughout; the drift is measured after the strike's end
        ! (2.01 s), and the push's work over the 0.09 s left, F v dt ~ 5e-4 J of the coin's
        ! 0.73 J, is far beyond any drift bound
        call read_lines_model("pushed.adm", "GFORCE/5, I=3, JFLOAT=2, RM=1, FX=0, FZ=0, TY=0", &
            & "GFORCE/5, I=3, JFLOAT=2, RM=1, FX=0.05, FZ=0, TY=0", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, pushed, q0, u0, error)
        if (allocated(error)) return
        options%end_time = 2.1_wp
        options%output_step = 0.01_wp
        options%progress = .false.
        call simulate(pushed, q0, u0, options, summary_pushed, error)
        if (allocated(error)) return
        call read_adm("data/coin.adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, struck, q0, u0, error)
        if (allocated(error)) return
        call simulate(struck, q0, u0, options, summary_struck, error)
        if (allocated(error)) return
        call check(error, .not. summary_pushed%energy_conserved .and. summary_pushed%status &
            & == status_completed .and. summary_pushed%energy_bound == 0.0_wp &
            & .and. summary_pushed%energy_drift > 1.0e-4_wp, "pushed: energy conserved " &
            & // merge("T", "F", summary_pushed%energy_conserved) // ", status " &
            & // to_text(summary_pushed%status) // ", drift " &
            & // to_text(summary_pushed%energy_drift))
        if (allocated(error)) return
        call check(error, summary_struck%energy_conserved .and. summary_struck%energy_bound &
            & > 0.0_wp, "struck: the energy after the strike is judged")
    end subroutine test_working_force

end module test_adm_build
