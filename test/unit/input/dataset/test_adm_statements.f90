! SPDX-License-Identifier: MIT
!> The dataset reader's acceptance: every keyword of every statement in any case and
!> abbreviated, continuation lines, comments and degrees; INTEGRATOR settings as a scene's
!> &run; UCON ROUTINE for every built-in UCOSUB; UNITS SYSTEM with overrides; a model of two
!> parts and six UCONs; the principal-axes rule met by a part's REULER.
module test_adm_statements
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi, degree
    use rollcon_error, only : error_type
    use rollcon_adm_model, only : adm_model_type, force_sforce, force_vforce, force_gforce
    use rollcon_expression, only : evaluate_expression
    use rollcon_adm_state, only : part_state
    use rollcon_scene_type, only : scene_run_type, formulation_cvode, formulation_ida, &
        & method_bdf, method_adams, drift_projection, drift_baumgarte, drift_none, &
        & jacobian_analytic, jacobian_dq
    use rollcon_ucosub_catalog, only : builtin_ucosub_names
    use rollcon_text, only : upper_case
    use rollcon_testing, only : unittest_type, new_unittest, check
    use adm_datasets, only : read_dataset
    implicit none
    private

    public :: collect_adm_statements

    !> Values are decimal literals converted once, or products of a few of them: a few ulp
    real(wp), parameter :: tol = 1.0e-14_wp

    !> Every keyword of every statement, in lower and mixed case, abbreviated
    character(len=80), parameter :: every_keyword(21) = [character(len=80) :: &
        & "every keyword, any case", &
        & "un/sys=si, fo=newt, ma=kilo, le=met, ti=sec", &
        & "part/1, gr   ! the ground", &
        & "Part/2, Mass=2.5, Cm=20, Ip=0.3, 0.4, 0.5, 0, 0, 0  ! zero products are allowed", &
        & "  , qg = 1, -2, 3", &
        & "  , reu=10d, 20D, 30d", &
        & ", vx=0.1, vy=-0.2, vz=0.3, wx=1, wy=-2, wz=3", &
        & "mar/20, pa=2, qp=0.01, 0.02, 0.03, reu=0, 1.5, 0", &
        & "MARKER/30, PART=1", &
        & "marker/31, part=1, qp=0, 0, 0", &
        & "ucon/7, fun=user(1, 2.5, -3e-2), rout=Rolling_Sphere", &
        & "acc/igrav=0.1, jgrav=-0.2, kgrav=-9.81", &
        & "sf/40, i=20, j=30, trans, func=2*time", &
        & "SFORCE/41, I=20, J=30, ROTATION, ACTIONONLY, FUNCTION=HAVSIN(TIME, 0, 0, 1, 1)", &
        & "vf/42, i=20, jf=31, rm=30, fx=1, fy=2, fz=3", &
        & "gforce/43, i=20, jfloat=31, rm=31, fx=1, fy=2, fz=3, tx=4, ty=5, tz=6", &
        & "UCON/8, FUNCTION=USER(4)", &
        & "sim/dyn, end=2, dtout=0.5", &
        & "int/err=1e-7, form=cvode, meth=bdf, dri=baum, jac=dq, maxs=1000, baum=20", &
        & "out/", &
        & "end"]

contains

    subroutine collect_adm_statements(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("every-keyword-any-case", test_every_keyword), &
            & new_unittest("integrator-settings", test_integrator_settings), &
            & new_unittest("ucon-routine-every-builtin", test_ucon_routines), &
            & new_unittest("units-system-then-overrides", test_units_system), &
            & new_unittest("two-parts-six-ucons", test_two_parts), &
            & new_unittest("principal-axes-by-part-reuler", test_part_reuler)]
    end subroutine collect_adm_statements

    !> Each keyword's value lands where it belongs, in SI and radians.
    subroutine test_every_keyword(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model

        call read_dataset("every_keyword.adm", every_keyword, model, error)
        if (allocated(error)) return
        call check(error, size(model%parts) == 2 .and. size(model%markers) == 3 &
            & .and. size(model%ucons) == 2 .and. size(model%forces) == 4, "counts")
        if (allocated(error)) return
        call check(error, [model%units%force, model%units%mass, model%units%length, &
            & model%units%time], [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], "UNITS", abs_tol=tol)
        if (allocated(error)) return
        associate (part => model%parts(2))
            call check(error, model%parts(1)%ground .and. .not. part%ground .and. part%cm == 20 &
                & .and. all(part%velocity_given) .and. all(part%angular_velocity_given), "PART")
            if (allocated(error)) return
            call check(error, [part%mass, part%ip, part%qg, part%reuler, part%velocity, &
                & part%angular_velocity], [2.5_wp, 0.3_wp, 0.4_wp, 0.5_wp, 1.0_wp, -2.0_wp, &
                & 3.0_wp, 10*degree, 20*degree, 30*degree, 0.1_wp, -0.2_wp, 0.3_wp, 1.0_wp, &
                & -2.0_wp, 3.0_wp], "PART values", abs_tol=tol)
            if (allocated(error)) return
        end associate
        associate (m => model%markers)
            call check(error, m(1)%id == 20 .and. m(1)%part == 2 .and. m(2)%part == 1 &
                & .and. m(3)%id == 31 .and. m(3)%part == 1, "MARKER ids and parts")
            if (allocated(error)) return
            call check(error, [m(1)%qp, m(1)%reuler, m(3)%qp], [0.01_wp, 0.02_wp, 0.03_wp, &
                & 0.0_wp, 1.5_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], "MARKER values", abs_tol=tol)
            if (allocated(error)) return
        end associate
        call check(error, model%ucons(1)%id == 7 .and. model%ucons(1)%routine == "Rolling_Sphere" &
            & .and. model%ucons(2)%id == 8 .and. model%ucons(2)%routine == "", "UCON ROUTINE")
        if (allocated(error)) return
        call check(error, [model%ucons(1)%par, model%ucons(2)%par], [1.0_wp, 2.5_wp, -0.03_wp, &
            & 4.0_wp], "UCON PAR", abs_tol=tol)
        if (allocated(error)) return
        call check(error, model%gravity, [0.1_wp, -0.2_wp, -9.81_wp], "ACCGRAV", abs_tol=tol)
        if (allocated(error)) return
        call check_forces(error, model)
        if (allocated(error)) return
        associate (settings => model%run%settings)
            call check(error, [settings%end_time, settings%output_step, settings%rtol, &
                & settings%atol, settings%baumgarte_rate], &
                & [2.0_wp, 0.5_wp, 1.0e-7_wp, 1.0e-7_wp, 20.0_wp], &
                & "SIMULATE and INTEGRATOR values", abs_tol=tol)
            if (allocated(error)) return
            call check(error, settings%formulation == formulation_cvode .and. settings%method &
                & == method_bdf .and. settings%drift == drift_baumgarte .and. settings%jacobian &
                & == jacobian_dq .and. settings%max_steps == 1000, "INTEGRATOR choices")
        end associate
    end subroutine test_every_keyword

    !> The four force statements of every_keyword: kinds, markers, flags, functions at t.
    subroutine check_forces(error, model)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type), intent(in) :: model
        integer :: k

        associate (f => model%forces)
            call check(error, f(1)%kind == force_sforce .and. f(1)%translation .and. .not. &
                & f(1)%action_only .and. f(1)%i == 20 .and. f(1)%j == 30 .and. f(2)%kind == &
                & force_sforce .and. .not. f(2)%translation .and. f(2)%action_only, "SFORCE")
            if (allocated(error)) return
            call check(error, f(3)%kind == force_vforce .and. f(3)%i == 20 .and. f(3)%j == 31 &
                & .and. f(3)%rm == 30 .and. all(f(3)%given(1:3)) .and. f(4)%kind == force_gforce &
                & .and. f(4)%j == 31 .and. f(4)%rm == 31 .and. all(f(4)%given), "VFORCE, GFORCE")
            if (allocated(error)) return
            ! FUNCTION=2*TIME at t = 0.25; the haversine from 0 at t = 0 to 1 at t = 1 is 1/2
            ! halfway
            call check(error, [evaluate_expression(f(1)%functions(1), 0.25_wp), &
                & evaluate_expression(f(2)%functions(1), 0.5_wp)], [0.5_wp, 0.5_wp], &
                & "SFORCE functions", abs_tol=tol)
            if (allocated(error)) return
            call check(error, [(evaluate_expression(f(3)%functions(k), 0.0_wp), k = 1, 3), &
                & (evaluate_expression(f(4)%functions(k), 0.0_wp), k = 1, 6)], [1.0_wp, 2.0_wp, &
                & 3.0_wp, 1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp, 5.0_wp, 6.0_wp], &
                & "VFORCE and GFORCE components", abs_tol=tol)
        end associate
    end subroutine check_forces

    !> INTEGRATOR: the scene's defaults when absent; ERROR sets ATOL unless ATOL is given (in
    !> either order); RTOL and ATOL apart; every choice by name and abbreviation.
    subroutine test_integrator_settings(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=80), parameter :: statements(5) = [character(len=80) :: &
            & "! no INTEGRATOR", "INTEGRATOR/ERROR=1e-6", "INTEGRATOR/ATOL=1e-12, ERROR=1e-6", &
            & "INTEG/RTOL=1e-9, ATOL=1e-11, FORM=IDA, METH=BDF, DRIFT=PROJ, JAC=ANALYTIC", &
            & "integrator/formulation=Cvode, method=Adams, drift=None"]
        type(scene_run_type), parameter :: defaults = scene_run_type()
        real(wp), parameter :: tolerances(2, 5) = reshape([defaults%rtol, defaults%atol, &
            & 1.0e-6_wp, 1.0e-6_wp, 1.0e-6_wp, 1.0e-12_wp, 1.0e-9_wp, 1.0e-11_wp, &
            & defaults%rtol, defaults%atol], [2, 5])
        integer, parameter :: choices(3, 5) = reshape([formulation_ida, method_bdf, &
            & drift_projection, formulation_ida, method_bdf, drift_projection, formulation_ida, &
            & method_bdf, drift_projection, formulation_ida, method_bdf, drift_projection, &
            & formulation_cvode, method_adams, drift_none], [3, 5])
        character(len=80) :: lines(8)
        type(adm_model_type) :: model
        integer :: i

        do i = 1, size(statements)
            lines = base_run()
            lines(6) = statements(i)
            call read_dataset("integrator.adm", lines, model, error)
            if (allocated(error)) return
            associate (s => model%run%settings)
                call check(error, [s%rtol, s%atol], tolerances(:, i), trim(statements(i)), &
                    & rel_tol=tol)
                if (allocated(error)) return
                call check(error, all([s%formulation, s%method, s%drift] == choices(:, i)) &
                    & .and. s%jacobian == jacobian_analytic .and. s%max_steps == &
                    & defaults%max_steps, trim(statements(i)) // ": choices")
                if (allocated(error)) return
            end associate
        end do
    end subroutine test_integrator_settings

    !> A small model for the tests that change one statement (line 6: INTEGRATOR or UNITS)
    pure function base_run()
        character(len=80) :: base_run(8)

        base_run = [character(len=80) :: "base", "PART/1, GROUND", &
            & "PART/2, MASS=1, CM=3, IP=2, 2, 3", "MARKER/3, PART=2, REULER=0D, 90D, 0D", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "! line 6", "UCON/1, FUNCTION=USER(1)", "END"]
    end function base_run

    !> ROUTINE names every built-in UCOSUB, in upper case too; the name is kept as written.
    subroutine test_ucon_routines(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: names, name
        character(len=80) :: lines(8)
        type(adm_model_type) :: model
        integer :: comma, count

        names = builtin_ucosub_names() // ","
        count = 0
        do while (len(names) > 0)
            comma = index(names, ",")
            name = trim(adjustl(names(:comma - 1)))
            names = names(comma + 1:)
            lines = base_run()
            lines(7) = "UCON/1, FUNCTION=USER(1), ROUTINE=" // upper_case(name)
            call read_dataset("routine.adm", lines, model, error)
            if (allocated(error)) return
            call check(error, model%ucons(1)%routine == upper_case(name), name)
            if (allocated(error)) return
            count = count + 1
        end do
        ! the hand disk routine and the five generated specs
        call check(error, count >= 6, "built-in routines tried")
    end subroutine test_ucon_routines


    !> SYSTEM sets all four units, the others override it wherever they stand.
    subroutine test_units_system(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=80) :: lines(8)
        type(adm_model_type) :: model

        lines = base_run()
        lines(6) = "UNITS/TIME=MINUTE, SYSTEM=MMKS, MASS=GRAM"
        call read_dataset("units_system.adm", lines, model, error)
        if (allocated(error)) return
        call check(error, [model%units%force, model%units%mass, model%units%length, &
            & model%units%time], [1.0_wp, 1.0e-3_wp, 1.0e-3_wp, 60.0_wp], "MMKS, minutes, grams", &
            & rel_tol=tol)
        if (allocated(error)) return
        ! one hour of end time, one minute per output step
        call check(error, [model%run%settings%end_time, model%run%settings%output_step], &
            & [60.0_wp, 6.0_wp], "SIMULATE in minutes", rel_tol=tol)
    end subroutine test_units_system

    !> A disk and a sphere, three UCONs each with a built-in routine, read as written: ids,
    !> routines and PAR, and both initial states (docs/design.md §3, §5).
    subroutine test_two_parts(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=80), parameter :: lines(17) = [character(len=80) :: &
            & "a disk and a sphere", &
            & "PART/1, GROUND", &
            & "PART/2, MA=0.7351, CM=20, IP=0.001838, 0.001838, 0.003676, QG=0, 0, 0.1", &
            & ", VX=0.1, WZ=-1", &
            & "MARKER/20, PART=2, REULER=0D, 90D, 0D  ! the disk axis along -Y", &
            & "PART/3, MA=4.1888, CM=30, IP=0.016755, 0.016755, 0.016755, QG=1, 0, 0.1", &
            & ", VX=0.2, WY=2", &
            & "MARKER/30, PART=3, REULER=0D, 90D, 0D", &
            & "UCON/1, FUNCTION=USER(2, 21,22,23,14,15,24,25,26, 0.1, 1), ROUTINE=disk", &
            & "UCON/2, FUNCTION=USER(2, 21,22,23,14,15,24,25,26, 0.1, 2), ROUTINE=disk", &
            & "UCON/3, FUNCTION=USER(2, 21,22,23,14,15,24,25,26, 0.1, 3), ROUTINE=disk", &
            & "UCON/11, FUNCTION=USER(3, 0.1, 1), ROUTINE=rolling_sphere", &
            & "UCON/12, FUNCTION=USER(3, 0.1, 2), ROUTINE=rolling_sphere", &
            & "UCON/13, FUNCTION=USER(3, 0.1, 3), ROUTINE=rolling_sphere", &
            & "ACCGRAV/KGRAV=-9.81", &
            & "SIM/DYN, END=1, STEPS=100", &
            & "END"]
        type(adm_model_type) :: model
        real(wp) :: q(6), u(6)
        integer :: k

        call read_dataset("two_parts.adm", lines, model, error)
        if (allocated(error)) return
        call check(error, size(model%parts) == 3 .and. size(model%ucons) == 6 &
            & .and. all(model%ucons%id == [1, 2, 3, 11, 12, 13]), "parts and UCON ids")
        if (allocated(error)) return
        call check(error, all([(model%ucons(k)%routine == "disk", k = 1, 3)]) .and. &
            & all([(model%ucons(k)%routine == "rolling_sphere", k = 4, 6)]), "routines")
        if (allocated(error)) return
        call check(error, [(model%ucons(k)%par(size(model%ucons(k)%par)), k = 1, 6), &
            & model%ucons(1)%par(1), model%ucons(4)%par(1)], [1.0_wp, 2.0_wp, 3.0_wp, 1.0_wp, &
            & 2.0_wp, 3.0_wp, 2.0_wp, 3.0_wp], "PAR", abs_tol=tol)
        if (allocated(error)) return
        ! the disk upright on its rim, rolling along +X with phidot = -v/R
        call part_state(model, model%parts(2), q, u)
        call check(error, [q, u], [0.0_wp, 0.0_wp, 0.1_wp, 0.0_wp, 0.5_wp*pi, 0.0_wp, 0.1_wp, &
            & 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -1.0_wp], "disk state", abs_tol=tol)
        if (allocated(error)) return
        ! the sphere: omega' = (0, 2, 0) at theta = pi/2, phi = 0 is psidot = 2
        call part_state(model, model%parts(3), q, u)
        call check(error, [q, u], [1.0_wp, 0.0_wp, 0.1_wp, 0.0_wp, 0.5_wp*pi, 0.0_wp, 0.2_wp, &
            & 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp], "sphere state", abs_tol=tol)
    end subroutine test_two_parts

    !> The part's REULER, not its CM marker, turns the principal z-axis off ground z: accepted,
    !> and the state is upright (theta = pi/2).
    subroutine test_part_reuler(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=80) :: lines(8)
        type(adm_model_type) :: model
        real(wp) :: q(6), u(6)

        lines = base_run()
        lines(3) = "PART/2, MASS=1, CM=3, IP=2, 2, 3, REULER=0D, 90D, 0D"
        lines(4) = "MARKER/3, PART=2"
        call read_dataset("part_reuler.adm", lines, model, error)
        if (allocated(error)) return
        call part_state(model, model%parts(2), q, u)
        call check(error, q(4:6), [0.0_wp, 0.5_wp*pi, 0.0_wp], "psi, theta, phi", abs_tol=tol)
    end subroutine test_part_reuler

end module test_adm_statements
