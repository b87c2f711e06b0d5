! SPDX-License-Identifier: MIT
!> The integrators' hot path allocates nothing: right-hand side, residual, root functions,
!> Jacobians and projection, called alone and inside CVODE and IDA runs, make no call to
!> malloc, calloc or realloc (counted by test/malloc_counter.c, which interposes them). Array
!> temporaries, automatic arrays and reallocation on assignment all go through malloc, so
!> these tests catch every one of them, in any build. Also what else the hot path costs: the
!> lift-off event function no saddle-point solve under CVODE, a time-free UCON no time-partial
!> calls, a threaded BLAS no second thread.
module test_allocations
    use, intrinsic :: iso_c_binding, only : c_int, c_long, c_long_long, c_ptr, c_null_ptr, &
        & c_funptr, c_char, c_null_char, c_associated, c_f_procpointer
    use rollcon_lapack, only : use_one_blas_thread
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_speeds_form, only : speeds_form_type
    use rollcon_run_settings, only : method_adams, drift_baumgarte, drift_projection
    use rollcon_dae, only : dae_size, dae_residual, dae_jacobian
    use rollcon_user_forces, only : set_system_constraint_forces, system_multipliers
    use rollcon_cvode, only : cvode_integrator_type
    use rollcon_integrator, only : integrator_statistics_type
    use rollcon_ida, only : ida_integrator_type
    use rollcon_contact_watch, only : contact_watch_type
    use rollcon_model, only : model_type, setup_model
    use rollcon_body, only : part_type
    use rollcon_constraints, only : need_value, need_first, need_time
    use rollcon_scene_type, only : scene_type
    use rollcon_run_keys, only : choice_code
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_gen_turntable_disk, only : turntable_disk_ucosub, turntable_disk_par
    use rollcon_output_files, only : write_text_file, make_folders
    use rollcon_disk_fleet, only : disk_fleet_dataset
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    implicit none
    private

    public :: collect_allocations

    interface
        !> Calls to malloc, calloc and realloc since the program started
        function malloc_count() result(count) bind(c, name="rollcon_malloc_count")
            import :: c_long
            integer(c_long) :: count
        end function malloc_count

        !> 1 when the allocator is interposed (glibc), 0 when the counts mean nothing
        function malloc_counting() result(counting) bind(c, name="rollcon_malloc_counting")
            import :: c_int
            integer(c_int) :: counting
        end function malloc_counting

        !> The largest single request to malloc, calloc or realloc since the last reset [bytes]
        function malloc_largest() result(bytes) bind(c, name="rollcon_malloc_largest")
            import :: c_long_long
            integer(c_long_long) :: bytes
        end function malloc_largest

        !> Forget the largest request so far
        subroutine malloc_reset_largest() bind(c, name="rollcon_malloc_reset_largest")
        end subroutine malloc_reset_largest

        !> A symbol of the loaded libraries (POSIX; c_null_ptr is glibc's RTLD_DEFAULT)
        function dlsym(handle, symbol) result(address) bind(c, name="dlsym")
            import :: c_ptr, c_funptr, c_char
            type(c_ptr), value :: handle
            character(kind=c_char), intent(in) :: symbol(*)
            type(c_funptr) :: address
        end function dlsym
    end interface

    abstract interface
        !> openblas_get_num_threads()
        function get_threads_interface() result(count) bind(c)
            import :: c_int
            integer(c_int) :: count
        end function get_threads_interface
    end interface

    !> Evaluations per measured loop: enough that a per-call allocation cannot hide
    integer, parameter :: repeats = 20
    !> The normal force from CVODE's accelerations against the solved one at the same state:
    !> the same quantity by Newton's law for the centre of mass, equal to round-off of the
    !> saddle-point solve (condition ~1e3 here) on forces of ~7 N
    real(wp), parameter :: tol_reaction = 1.0e-10_wp

contains

    subroutine collect_allocations(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("evaluations-allocate-nothing", test_evaluations), &
            & new_unittest("cvode-run-allocates-nothing", test_cvode_run), &
            & new_unittest("ida-run-allocates-nothing", test_ida_run), &
            & new_unittest("independent-speeds-allocate-nothing", test_independent_speeds), &
            & new_unittest("cvode-sparse-holds-no-square", test_cvode_sparse_memory), &
            & new_unittest("dissipated-powers-allocate-nothing", test_powers), &
            & new_unittest("constraint-forces-set-allocate-nothing", test_constraint_forces), &
            & new_unittest("liftoff-root-without-solve", test_liftoff_root), &
            & new_unittest("event-rates-only-when-used", test_event_rates), &
            & new_unittest("time-free-ucon-skips-time-partials", test_time_free), &
            & new_unittest("blas-one-thread", test_blas_thread)]
    end subroutine collect_allocations

    !> The tipping coin (paper's disk, 0.01 rad off upright, 0.1 m/s), CVODE Adams + Baumgarte
    !> with the lift-off event on, at a generic state when `generic`; on a table with Coulomb
    !> friction and the rim's rolling resistance and air layer when `dissipating`.
    subroutine coin_problem(problem, q, u, generic, error, dissipating)
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(out) :: q(6), u(6)
        logical, intent(in) :: generic
        type(error_type), allocatable, intent(out) :: error
        logical, intent(in), optional :: dissipating
        type(scene_type) :: scene

        scene%run%formulation = choice_code("formulation", "cvode")
        scene%run%method = choice_code("method", "adams")
        scene%run%drift = choice_code("drift", "baumgarte")
        scene%run%jacobian = choice_code("jacobian", "analytic")
        scene%run%height = choice_code("height", "velocity")
        scene%initial%theta = acos(-1.0_wp)/2.0_wp - 0.01_wp
        scene%initial%phidot = -1.0_wp
        scene%limits%stop_on_liftoff = .true.
        scene%limits%theta_min = 0.05_wp
        if (generic) then
            scene%initial%theta = 1.1_wp
            scene%initial%psi = 0.4_wp
            scene%initial%phi = 0.7_wp
            scene%initial%psidot = 1.3_wp
            scene%initial%thetadot = -0.6_wp
            scene%initial%phidot = -4.0_wp
        end if
        if (present(dissipating)) then
            if (dissipating) then
                ! steel on a table (data/coin_slipping.nml), and data/euler_disk.nml's rim
                scene%contact%enabled = .true.
                scene%contact%mu_static = 0.5_wp
                scene%contact%mu_kinetic = 0.4_wp
                scene%dissipation%enabled = .true.
                scene%dissipation%rolling_resistance = 1.0e-4_wp
                scene%dissipation%air_viscosity = 1.8e-5_wp
            end if
        end if
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q, u, error)
        if (allocated(error)) return
        call problem%prepare(error)
    end subroutine coin_problem

    !> Fails with the number of allocations when there were any (count them before building
    !> the message: building it allocates).
    subroutine check_none(error, calls, what)
        type(error_type), allocatable, intent(out) :: error
        !> Allocations counted
        integer(c_long), intent(in) :: calls
        character(len=*), intent(in) :: what

        call check(error, calls == 0, what // " allocated " // to_text(int(calls)) // " times")
    end subroutine check_none

    subroutine test_evaluations(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(error_type), allocatable :: failure
        real(wp) :: q(6), u(6), y(12), ydot(12), jac(12, 12), g(2), dq(6), du(6)
        real(wp), allocatable :: yd(:), ypd(:), r(:), jd(:, :)
        integer(c_long) :: start, calls
        integer :: i, ierr, m

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call coin_problem(problem, q, u, .true., error)
        if (allocated(error)) return
        call ode%init(problem)
        y = [q, u]
        m = dae_size(problem%eq)
        allocate(yd(m), ypd(m), r(m), jd(m, m), source=0.0_wp)
        ! one call of each first: anything allocated on a first use only is not counted (the
        ! Jacobian's right-hand sides are sized by its first evaluation, rollcon_ode_form)
        ierr = ode%ode_rhs(0.0_wp, y, ydot)
        call problem%eq%ode_jacobian(0.0_wp, q, u, problem%settings%baumgarte(), jac, failure)
        if (.not. allocated(failure)) call problem%eq%project(0.0_wp, q, u, dq, du, failure)
        if (allocated(failure)) then
            call move_alloc(failure, error)
            return
        end if
        yd(:12) = y
        yd(13:) = problem%lambda
        ypd(:12) = ydot
        start = malloc_count()
        do i = 1, repeats
            ierr = ode%ode_rhs(0.0_wp, y, ydot)
            ierr = ierr + problem%root_values(0.0_wp, q, u, g)
            ierr = ierr + problem%root_values(0.0_wp, q, u, g, a=ydot(7:))
            ierr = ierr + problem%root_values(0.0_wp, q, u, g, lambda=yd(13:))
            call problem%eq%ode_jacobian(0.0_wp, q, u, problem%settings%baumgarte(), jac, &
                & failure)
            if (allocated(failure)) exit
            call problem%eq%project(0.0_wp, q, u, dq, du, failure)
            if (allocated(failure)) exit
            call dae_residual(problem%eq, 0.0_wp, yd, ypd, r, failure)
            if (allocated(failure)) exit
            call dae_jacobian(problem%eq, 0.0_wp, 10.0_wp, yd, ypd, jd, failure)
            if (allocated(failure)) exit
        end do
        calls = malloc_count() - start
        call check_none(error, calls, "rhs, roots, ODE Jacobian, projection, DAE residual " &
            & // "and Jacobian, " // to_text(repeats) // " times each,")
        if (allocated(error)) return
        if (allocated(failure)) call move_alloc(failure, error)
        if (allocated(error)) return
        call check(error, ierr == 0, "a callback failed")
    end subroutine test_evaluations

    subroutine test_cvode_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type), target :: ode
        type(cvode_integrator_type), target :: cvode
        real(wp) :: q(6), u(6), y(12), yp(12), t
        integer(c_long) :: start, calls
        integer :: k, root

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call coin_problem(problem, q, u, .false., error)
        if (allocated(error)) return
        call ode%init(problem)
        y = [q, u]
        yp = 0.0_wp
        call cvode%start(ode, problem%settings, 0.0_wp, y, yp, 2.0_wp, error)
        if (.not. allocated(error)) call cvode%advance(0.1_wp, 2.0_wp, t, y, yp, root, error)
        start = malloc_count()
        do k = 2, 20
            if (allocated(error) .or. root /= 0) exit
            call cvode%advance(0.1_wp*k, 2.0_wp, t, y, yp, root, error)
        end do
        calls = malloc_count() - start
        if (.not. allocated(error)) call check_none(error, calls, "CVODE Adams from t = 0.1 s " &
            & // "to " // to_text(t) // " s")
        call cvode%destroy()
    end subroutine test_cvode_run

    subroutine test_ida_run(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(dae_form_type), target :: dae
        type(ida_integrator_type), target :: ida
        real(wp) :: q(6), u(6), t
        real(wp), allocatable :: y(:), yp(:)
        integer(c_long) :: start, calls
        integer :: k, root

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call coin_problem(problem, q, u, .false., error)
        if (allocated(error)) return
        problem%settings%drift = drift_projection
        call dae%init(problem)
        call problem%accelerations(0.0_wp, q, u, error)
        if (allocated(error)) return
        allocate(y(dae%state_size()), yp(dae%state_size()))
        call dae%pack_state(q, u, y, yp)
        call ida%start(dae, problem%settings, 0.0_wp, y, yp, 2.0_wp, error)
        if (.not. allocated(error)) call ida%advance(0.1_wp, 2.0_wp, t, y, yp, root, error)
        start = malloc_count()
        do k = 2, 20
            if (allocated(error) .or. root /= 0) exit
            call ida%advance(0.1_wp*k, 2.0_wp, t, y, yp, root, error)
        end do
        calls = malloc_count() - start
        if (.not. allocated(error)) call check_none(error, calls, "IDA from t = 0.1 s to " &
            & // to_text(t) // " s")
        call ida%destroy()
    end subroutine test_ida_run

    !> In independent speeds (9 states): right-hand side, Newton matrix, event functions, the
    !> partition's check and a CVODE Adams run allocate nothing.
    subroutine test_independent_speeds(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(speeds_form_type), target :: speeds
        type(cvode_integrator_type), target :: cvode
        real(wp) :: q(6), u(6), y(9), yp(9), ydot(9), jac(9, 9), g(2), t
        integer(c_long) :: start, calls
        integer :: i, k, ierr, root
        logical :: worn

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call coin_problem(problem, q, u, .false., error)
        if (allocated(error)) return
        call speeds%init(problem)
        call problem%accelerations(0.0_wp, q, u, error)
        if (allocated(error)) return
        call speeds%pack_state(q, u, y, yp)
        ! one call of each first: the Newton matrix's arrays are sized by its first evaluation
        ierr = speeds%ode_rhs(0.0_wp, y, ydot)
        ierr = ierr + speeds%ode_jacobian(0.0_wp, y, jac)
        start = malloc_count()
        do i = 1, repeats
            ierr = ierr + speeds%ode_rhs(0.0_wp, y, ydot)
            ierr = ierr + speeds%ode_jacobian(0.0_wp, y, jac)
            ierr = ierr + speeds%roots(0.0_wp, y, g, ydot)
            worn = speeds%worn(0.0_wp, y)
        end do
        calls = malloc_count() - start
        call check_none(error, calls, "rhs, Jacobian, roots and the partition's check in " &
            & // "independent speeds, " // to_text(repeats) // " times each,")
        if (allocated(error)) return
        call check(error, ierr == 0 .and. .not. worn, "a callback failed, or the partition " &
            & // "wore at its own state: " // speeds%failure_text())
        if (allocated(error)) return
        call cvode%start(speeds, problem%settings, 0.0_wp, y, yp, 2.0_wp, error)
        if (.not. allocated(error)) call cvode%advance(0.1_wp, 2.0_wp, t, y, yp, root, error)
        start = malloc_count()
        do k = 2, 20
            if (allocated(error) .or. root /= 0) exit
            call cvode%advance(0.1_wp*k, 2.0_wp, t, y, yp, root, error)
        end do
        calls = malloc_count() - start
        if (.not. allocated(error)) call check_none(error, calls, "CVODE Adams in independent " &
            & // "speeds from t = 0.1 s to " // to_text(t) // " s")
        call cvode%destroy()
    end subroutine test_independent_speeds

    !> CVODE's sparse Newton matrix (KLU) on 64 independent disks (384 coordinates; 64 blocks
    !> of 12 states in the ODE form, 768 states, of 9 in independent speeds, 576) holds
    !> nothing that grows as the model's square: its Newton matrix formed block by block
    !> (rollcon_ode_form and the equations' ode_jacobian_blocks; rollcon_speeds_form and
    !> rollcon_independent_speeds' jacobian_blocks), no single request to the allocator while
    !> CVODE starts and steps reaches the bound of sparse_run; and its steps allocate nothing.
    subroutine test_cvode_sparse_memory(error)
        type(error_type), allocatable, intent(out) :: error

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call sparse_run("CVODE", error)
        if (allocated(error)) return
        call sparse_run("MAGGI", error)
    end subroutine test_cvode_sparse_memory

    !> One run of test_cvode_sparse_memory, in the FORMULATION given (CVODE: the ODE form,
    !> MAGGI: independent speeds).
    subroutine sparse_run(formulation, error)
        character(len=*), intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: disks = 64
        !> An eighth of the ODE form's n_y x n_y array of reals (n_y = 12 x 64 = 768: 590 kB).
        !> A run by blocks asks for at most 230 kB at once, linear in the model (115 kB with
        !> 32 disks, measured 2026-11-30: SUNDIALS' and KLU's arrays over the states and the
        !> blocks' entries); the dense ODE Jacobian's n x 2n right-hand sides (2.4 MB) are 4
        !> times the bound, its n_y x n_y matrix (4.7 MB) 8 times, the independent speeds'
        !> (576 square, 2.7 MB) 4.5 times and their ODE form's Jacobian (2n square) 8 times
        integer(c_long_long), parameter :: bound = 8_c_long_long*(12_c_long_long*disks)**2/8
        character(len=*), parameter :: folder = "build/rollcon-test/allocations"
        type(problem_type), target :: problem
        type(ode_form_type), target :: ode
        type(speeds_form_type), target :: speeds
        type(cvode_integrator_type), target :: cvode
        type(adm_model_type) :: adm
        procedure(ucosub_interface), pointer :: disk
        real(wp), allocatable :: q0(:), u0(:), y(:), yp(:)
        real(wp) :: t
        integer(c_long_long) :: largest
        integer(c_long) :: start, calls
        type(integrator_statistics_type) :: counts
        integer :: k, root
        logical :: in_speeds

        in_speeds = formulation == "MAGGI"
        call make_folders(folder, error)
        if (allocated(error)) return
        call write_text_file(folder // "/fleet_klu.adm", disk_fleet_dataset(disks, 0.5_wp, &
            & 1.0_wp, 0.05_wp, "FORMULATION=" // formulation // ", METHOD=ADAMS, " &
            & // "DRIFT=BAUMGARTE, RTOL=1e-8, ATOL=1e-10, SOLVER=SPARSE"), error)
        if (allocated(error)) return
        call read_adm(folder // "/fleet_klu.adm", adm, error)
        if (allocated(error)) return
        disk => rolling_disk_ucosub
        call build_adm_problem(adm, disk, problem, q0, u0, error)
        if (.not. allocated(error)) call problem%prepare(error)
        if (allocated(error)) return
        if (in_speeds) then
            call speeds%init(problem)
            call problem%accelerations(0.0_wp, q0, u0, error)
            if (allocated(error)) return
            allocate(y(speeds%state_size()), yp(speeds%state_size()), source=0.0_wp)
            call speeds%pack_state(q0, u0, y, yp)
        else
            call ode%init(problem)
            y = [q0, u0]
            allocate(yp(size(y)), source=0.0_wp)
        end if
        call malloc_reset_largest()
        if (in_speeds) then
            call cvode%start(speeds, problem%settings, 0.0_wp, y, yp, 1.0_wp, error)
        else
            call cvode%start(ode, problem%settings, 0.0_wp, y, yp, 1.0_wp, error)
        end if
        if (.not. allocated(error)) call cvode%advance(0.05_wp, 1.0_wp, t, y, yp, root, error)
        largest = malloc_largest()
        start = malloc_count()
        do k = 2, 4
            if (allocated(error) .or. root /= 0) exit
            call cvode%advance(0.05_wp*k, 1.0_wp, t, y, yp, root, error)
        end do
        calls = malloc_count() - start
        if (allocated(error)) return
        counts = cvode%statistics()
        call check(error, counts%sparse .and. counts%jacobians > 0, formulation // ": the " &
            & // "run formed no sparse Newton matrix")
        if (.not. allocated(error)) call check(error, largest < bound, formulation &
            & // " with KLU on " // to_text(disks) // " disks asked for " &
            & // to_text(int(largest)) // " bytes at once, bound " // to_text(int(bound)))
        if (.not. allocated(error)) call check_none(error, calls, formulation // " Adams " &
            & // "with KLU on " // to_text(disks) // " disks from t = 0.05 s to " &
            & // to_text(t) // " s")
        call cvode%destroy()
        call problem%release()
    end subroutine sparse_run

    !> The constraint rows and multipliers SYSFNC's force measures read, set at every
    !> evaluation of the algebraic loop's iterates and of IDA's residuals
    !> (set_system_constraint_forces): after the first call, a call with the same rows copies
    !> their values alone and allocates nothing.
    subroutine test_constraint_forces(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp) :: q(6), u(6)
        real(wp), allocatable :: lambda(:)
        integer(c_long) :: start, calls
        integer :: i

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call coin_problem(problem, q, u, .true., error)
        if (allocated(error)) return
        call problem%accelerations(0.0_wp, q, u, error)
        if (allocated(error)) return
        lambda = problem%lambda
        call check(error, size(lambda) == problem%eq%c%nc .and. size(lambda) > 0, &
            & "the coin's multipliers: " // to_text(size(lambda)) // ", its rows: " &
            & // to_text(problem%eq%c%nc))
        if (allocated(error)) return
        ! the first call takes the rows' pattern
        call set_system_constraint_forces(problem%eq%c, lambda)
        start = malloc_count()
        do i = 1, repeats
            lambda(1) = lambda(1) + 1.0_wp
            call set_system_constraint_forces(problem%eq%c, lambda)
        end do
        calls = malloc_count() - start
        call check_none(error, calls, "set_system_constraint_forces, " // to_text(repeats) &
            & // " times,")
        if (allocated(error)) return
        ! the multipliers the force measures read are the last ones given (exact copies)
        call check(error, all(system_multipliers(size(lambda)) == lambda), &
            & "the multipliers kept are not the last ones given")
    end subroutine test_constraint_forces

    !> The powers a dissipating coin's three forms integrate with their state (friction,
    !> rolling resistance, air: the one routine of rollcon_problem, state_powers) allocate
    !> nothing per call, and the three forms give the same powers at the same (q, u): the ODE
    !> and DAE forms read it from y exactly, the independent speeds solve the dependent rates
    !> from y = (q, v) to round-off of a solve of condition ~1e3 (tol_reaction's reasoning).
    subroutine test_powers(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(dae_form_type) :: dae
        type(speeds_form_type) :: speeds
        real(wp) :: q(6), u(6), y(12), powers(3, 3), ys(9), yps(9)
        real(wp), allocatable :: yd(:), ypd(:)
        integer(c_long) :: start, calls
        integer :: i, ierr

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        call coin_problem(problem, q, u, .true., error, dissipating=.true.)
        if (allocated(error)) return
        call ode%init(problem)
        call dae%init(problem)
        call speeds%init(problem)
        call check(error, ode%power_count() == 3 .and. dae%power_count() == 3 &
            & .and. speeds%power_count() == 3, "powers integrated by the ODE, DAE and " &
            & // "speeds forms: " // to_text(ode%power_count()) // ", " &
            & // to_text(dae%power_count()) // ", " // to_text(speeds%power_count()) &
            & // ", expected 3 each (friction, rolling resistance, air)")
        if (allocated(error)) return
        call problem%accelerations(0.0_wp, q, u, error)
        if (allocated(error)) return
        y = [q, u]
        allocate(yd(dae%state_size()), ypd(dae%state_size()))
        call dae%pack_state(q, u, yd, ypd)
        call speeds%pack_state(q, u, ys, yps)
        ! one call of each first: anything allocated on a first use only is not counted
        ierr = ode%powers(0.0_wp, y, powers(:, 1))
        ierr = ierr + dae%powers(0.0_wp, yd, powers(:, 2))
        ierr = ierr + speeds%powers(0.0_wp, ys, powers(:, 3))
        start = malloc_count()
        do i = 1, repeats
            ierr = ierr + ode%powers(0.0_wp, y, powers(:, 1))
            ierr = ierr + dae%powers(0.0_wp, yd, powers(:, 2))
            ierr = ierr + speeds%powers(0.0_wp, ys, powers(:, 3))
        end do
        calls = malloc_count() - start
        call check_none(error, calls, "the dissipated powers of the ODE, DAE and speeds " &
            & // "forms, " // to_text(repeats) // " times each,")
        if (allocated(error)) return
        call check(error, ierr == 0, "a powers callback failed: " // problem%failure_text())
        if (allocated(error)) return
        ! the rim presses on the table at the generic state: rolling resistance and air work
        call check(error, powers(2, 1) > 0.0_wp .and. powers(3, 1) > 0.0_wp, &
            & "rolling resistance's and air's powers at the generic state, W: " &
            & // to_text(powers(2, 1)) // ", " // to_text(powers(3, 1)))
        if (allocated(error)) return
        call check(error, all(powers(:, 2) == powers(:, 1)), "the DAE form's powers differ " &
            & // "from the ODE form's at the same (q, u)")
        if (allocated(error)) return
        do i = 1, 3
            call check(error, powers(i, 3), powers(i, 1), "power " // to_text(i) &
                & // " in independent speeds against the ODE form's, W", &
                & rel_tol=tol_reaction, abs_tol=tol_reaction*maxval(powers(:, 1)))
            if (allocated(error)) return
        end do
    end subroutine test_powers

    !> The CVODE event function given the accelerations: the normal force it returns (less the
    !> lift-off threshold the root adds) is the one a saddle-point solve gives at the same
    !> state, and it factors nothing.
    subroutine test_liftoff_root(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        real(wp) :: q(6), u(6), y(12), ydot(12), g(2), force(3)
        integer :: ierr, before

        call coin_problem(problem, q, u, .true., error)
        if (allocated(error)) return
        call ode%init(problem)
        y = [q, u]
        ierr = ode%ode_rhs(0.0_wp, y, ydot)
        force = problem%eq%constraint_force(1, problem%lambda)
        before = problem%eq%saddle%factorisations
        ierr = ierr + problem%root_values(0.0_wp, q, u, g, a=ydot(7:))
        call check(error, ierr == 0 .and. problem%eq%saddle%factorisations == before, &
            & "the event function given the accelerations factored " &
            & // to_text(problem%eq%saddle%factorisations - before) // " saddle-point matrices")
        if (allocated(error)) return
        call check(error, force(3) > 1.0_wp, "normal force at the generic state, N")
        if (allocated(error)) return
        select type (contact => problem%watches(2)%watch)
        type is (contact_watch_type)
            call check(error, g(problem%root_count()) - contact%liftoff_force, force(3), &
                & "normal force from the accelerations, N", rel_tol=tol_reaction)
        class default
            call check(error, .false., "the disk scene's second watch is not its contact")
        end select
    end subroutine test_liftoff_root

    !> CVODE interpolates y' for the event functions (a CVodeGetDky per evaluation) only when
    !> they use it: the ODE form with the lift-off watched (its normal force from the
    !> accelerations); not without the lift-off (the theta limit needs theta alone), not in
    !> independent speeds (y' carries no whole a). (IDA gives none: its system, a DAE, has no
    !> such binding; its state holds the multipliers.)
    subroutine test_event_rates(error)
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(ode_form_type) :: ode
        type(speeds_form_type) :: speeds
        real(wp) :: q(6), u(6)
        logical :: used(3)

        call coin_problem(problem, q, u, .true., error)
        if (allocated(error)) return
        call ode%init(problem)
        call speeds%init(problem)
        used(1) = ode%roots_use_rates()
        used(2) = speeds%roots_use_rates()
        select type (contact => problem%watches(2)%watch)
        type is (contact_watch_type)
            contact%stop_on_liftoff = .false.
        end select
        used(3) = ode%roots_use_rates()
        call check(error, all(used .eqv. [.true., .false., .false.]) &
            & .and. ode%root_count() == 1, "y' for the events (ODE form with lift-off, " &
            & // "independent speeds, ODE form without lift-off): " &
            & // trim(merge("T ", "F ", used(1))) // trim(merge("T ", "F ", used(2))) &
            & // trim(merge("T ", "F ", used(3))) &
            & // ", expected TFF with the theta limit's one event function left")
    end subroutine test_event_rates

    !> A UCON whose F has explicit time (the turntable) declared time-free is not asked for
    !> time partials: they stay zero; declared as it is, they are not.
    subroutine test_time_free(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type), target :: models(2)
        type(part_type) :: disk
        type(problem_type), target :: problems(2)
        real(wp) :: q(6), u(6), dt(2)
        integer :: pass

        q = [0.3_wp, 0.2_wp, 0.08_wp, 0.4_wp, 1.1_wp, 0.7_wp]
        u = [0.1_wp, -0.2_wp, 0.05_wp, 1.3_wp, -0.6_wp, -4.0_wp]
        do pass = 1, 2
            associate (model => models(pass), problem => problems(pass))
                disk%mass = 0.7_wp
                disk%inertia = [1.8e-3_wp, 1.8e-3_wp, 3.6e-3_wp]
                call model%add_part(disk)
                ! table turning at 0.5 + 0.2 sin(3 t) rad/s about (0.1, -0.2): dF/dt /= 0
                call model%add_ucon(1, turntable_disk_par(1, 0.1_wp, 0.1_wp, -0.2_wp, 0.5_wp, &
                    & 0.2_wp, 3.0_wp, 1), turntable_disk_ucosub, time_free=pass == 2)
                call setup_model(model, error)
                if (allocated(error)) return
                call problem%init(model)
                call problem%eq%constraints%evaluate(problem%model, 0.4_wp, q, u, need_value &
                    & + need_first + need_time, error)
                if (allocated(error)) return
                dt(pass) = abs(problem%eq%constraints%dt(1)) &
                    & + sum(abs(problem%eq%constraints%dt_grad_q(:, 1)))
            end associate
        end do
        call check(error, dt(1) > 1.0e-3_wp, "time partials of the turntable's F1 asked for: " &
            & // to_text(dt(1)))
        if (allocated(error)) return
        call check(error, dt(2) == 0.0_wp, "time partials of a time-free UCON: " &
            & // to_text(dt(2)))
    end subroutine test_time_free

    !> After use_one_blas_thread, a threaded BLAS runs one thread; reference BLAS (no threads,
    !> nothing to set) skips.
    subroutine test_blas_thread(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: library
        procedure(get_threads_interface), pointer :: get_threads
        type(c_funptr) :: address

        call use_one_blas_thread(library)
        address = dlsym(c_null_ptr, "openblas_get_num_threads" // c_null_char)
        if (.not. c_associated(address)) then
            call check(error, library /= "openblas", "OpenBLAS reported set, but not loaded")
            if (.not. allocated(error)) call skip_test(error, "the BLAS linked is not OpenBLAS " &
                & // "(reference BLAS has no threads)")
            return
        end if
        call c_f_procpointer(address, get_threads)
        call check(error, library == "openblas" .and. get_threads() == 1, &
            & "OpenBLAS threads after use_one_blas_thread: " // to_text(int(get_threads())))
    end subroutine test_blas_thread

end module test_allocations
