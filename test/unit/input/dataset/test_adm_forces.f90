! SPDX-License-Identifier: MIT
!> Force statements between markers (rollcon_marker, rollcon_marker_force, rollcon_force):
!> every state function against values found another way, each kind of force against its
!> force and moment worked out by hand, the units of an expression, and the breakpoints.
module test_adm_forces
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_rotation, only : rotation_matrix
    use rollcon_expression, only : quantity_dx, quantity_vx, quantity_wx, quantity_psi
    use rollcon_adm_expression_parser, only : compile_expression
    use rollcon_marker, only : marker_type, marker_quantity
    use rollcon_marker_force, only : marker_force_type, kind_translation, kind_rotation, &
        & kind_vector, kind_general, kind_spring
    use rollcon_force, only : applied_force_type, force_and_moment, force_breakpoints, &
        & pulse_stops, profile_statement, profile_half_sine
    use rollcon_spring_force, only : spring_type, spring_bushing, spring_translational
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use, intrinsic :: iso_c_binding, only : c_int, c_long
    implicit none
    private

    public :: collect_adm_forces

    !> Hand values of a few operations on numbers of order 1: a few ulp
    real(wp), parameter :: tol = 1.0e-14_wp
    !> Central differences of a position with h = 1e-6 s: O(h^2) ~ 1e-12 plus eps/h ~ 1e-10
    real(wp), parameter :: tol_fd = 1.0e-9_wp
    !> A state of two parts: part 1 at (1, 2, 3) turned by (0.3, 1.1, -0.4), part 2 at (0, 3, 0)
    !> turned by psi = pi/2 (its axes x, y, z along ground Y, -X, Z); rates of part 1 only
    real(wp), parameter :: q(12) = [1.0_wp, 2.0_wp, 3.0_wp, 0.3_wp, 1.1_wp, -0.4_wp, &
        & 0.0_wp, 3.0_wp, 0.0_wp, 0.5_wp*pi, 0.0_wp, 0.0_wp]
    real(wp), parameter :: u(12) = [0.5_wp, -0.2_wp, 0.1_wp, 0.7_wp, -0.3_wp, 1.2_wp, &
        & 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]

    interface
        !> Calls to malloc, calloc and realloc so far (malloc_counter.c)
        function malloc_count() result(count) bind(c, name="rollcon_malloc_count")
            import :: c_long
            integer(c_long) :: count
        end function malloc_count

        !> 1 when the allocator is interposed, 0 when the counts mean nothing
        function malloc_counting() result(counting) bind(c, name="rollcon_malloc_counting")
            import :: c_int
            integer(c_int) :: counting
        end function malloc_counting
    end interface

contains

    subroutine collect_adm_forces(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("state-functions", test_state_functions), &
            & new_unittest("cm-marker-angles-continuous", test_principal_angles), &
            & new_unittest("sforce-translational", test_sforce_translation), &
            & new_unittest("sforce-rotational", test_sforce_rotation), &
            & new_unittest("sforce-action-only", test_sforce_action_only), &
            & new_unittest("vforce", test_vforce), &
            & new_unittest("gforce", test_gforce), &
            & new_unittest("units-of-an-expression", test_units), &
            & new_unittest("breakpoints", test_breakpoints), &
            & new_unittest("loads-allocate-nothing", test_no_allocation)]
    end subroutine collect_adm_forces

    !> A marker of part 1 at (0.1, -0.2, 0.3) in its principal axes, its axes turned by 0.2 rad
    !> about the principal z.
    function marker_on_part_1() result(marker)
        type(marker_type) :: marker

        marker%id = 7
        marker%part = 1
        marker%point = [0.1_wp, -0.2_wp, 0.3_wp]
        marker%axes = rotation_matrix(0.0_wp, 0.0_wp, 0.2_wp)
    end function marker_on_part_1

    !> DX..DZ from the rotation; VX..VZ as the position's central difference along the motion;
    !> WX..WZ from omega = psidot e_Z + thetadot e_x1 + phidot e_z2 (docs/design.md §3);
    !> PSI, THETA, PHI of axes R(q) Rz(0.2) = Rz(psi) Rx(theta) Rz(phi + 0.2).
    subroutine test_state_functions(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: h = 1.0e-6_wp
        type(marker_type) :: marker
        real(wp) :: expected(12), ahead(3), behind(3), got(12)
        integer :: k

        marker = marker_on_part_1()
        expected(1:3) = q(1:3) + matmul(rotation_matrix(q(4), q(5), q(6)), marker%point)
        do k = 1, 3
            ahead(k) = marker_quantity(marker, quantity_dx + k - 1, q + h*u, u)
            behind(k) = marker_quantity(marker, quantity_dx + k - 1, q - h*u, u)
        end do
        expected(4:6) = (ahead - behind)/(2.0_wp*h)
        associate (psi => q(4), theta => q(5), rates => u(4:6))
            expected(7:9) = rates(1)*[0.0_wp, 0.0_wp, 1.0_wp] &
                & + rates(2)*[cos(psi), sin(psi), 0.0_wp] &
                & + rates(3)*[sin(theta)*sin(psi), -sin(theta)*cos(psi), cos(theta)]
        end associate
        expected(10:12) = [q(4), q(5), q(6) + 0.2_wp]
        do k = 1, 12
            got(k) = marker_quantity(marker, k, q, u)
        end do
        call check(error, got(1:3), expected(1:3), "DX, DY, DZ [m]", abs_tol=tol)
        if (allocated(error)) return
        call check(error, got(4:6), expected(4:6), "VX, VY, VZ [m/s]", abs_tol=tol_fd)
        if (allocated(error)) return
        call check(error, got(7:9), expected(7:9), "WX, WY, WZ [rad/s]", abs_tol=tol)
        if (allocated(error)) return
        call check(error, got(10:12), expected(10:12), "PSI, THETA, PHI [rad]", abs_tol=tol)
        if (allocated(error)) return
        ! a ground marker: where it is, at rest
        marker = marker_type(id=1, part=0, point=[4.0_wp, 5.0_wp, 6.0_wp])
        do k = 1, 12
            got(k) = marker_quantity(marker, k, q, u)
        end do
        call check(error, got, [4.0_wp, 5.0_wp, 6.0_wp, (0.0_wp, k = 1, 9)], "ground marker", &
            & abs_tol=0.0_wp)
    end subroutine test_state_functions

    !> A CM marker's PSI, THETA, PHI are the part's coordinates themselves, not wrapped into
    !> (-pi, pi]: continuous as the part spins on; another marker's are wrapped.
    subroutine test_principal_angles(error)
        type(error_type), allocatable, intent(out) :: error
        type(marker_type) :: marker
        real(wp) :: spun(12)

        spun = q
        spun(4) = 7.0_wp
        marker = marker_type(id=3, part=1, principal=.true.)
        call check(error, marker_quantity(marker, quantity_psi, spun, u) == 7.0_wp, &
            & "CM marker PSI = psi")
        if (allocated(error)) return
        marker%principal = .false.
        call check(error, marker_quantity(marker, quantity_psi, spun, u), 7.0_wp - 2.0_wp*pi, &
            & "another marker's PSI, wrapped", abs_tol=tol)
    end subroutine test_principal_angles

    !> A force statement of `kind` with FUNCTION (or FX..TZ) texts.
    function statement_force(kind, texts) result(force)
        integer, intent(in) :: kind
        character(len=*), intent(in) :: texts(:)
        type(applied_force_type) :: force
        type(error_type), allocatable :: error
        integer :: k

        force%profile = profile_statement
        force%statement%kind = kind
        allocate(force%statement%markers(0))
        do k = 1, size(texts)
            if (len_trim(texts(k)) == 0) cycle
            call compile_expression(trim(texts(k)), "test", force%statement%functions(k), error)
            force%statement%given(k) = .not. allocated(error)
        end do
    end function statement_force

    !> Loads on both parts at the state above.
    subroutine loads(force, f1, m1, f2, m2)
        type(applied_force_type), intent(in) :: force
        real(wp), intent(out) :: f1(3), m1(3), f2(3), m2(3)

        call force_and_moment([force], 1, 0.0_wp, q, u, f1, m1)
        call force_and_moment([force], 2, 0.0_wp, q, u, f2, m2)
    end subroutine loads

    !> 5 N pushing I (on part 2 at (0, 1, 0) in its axes, so at (-1, 3, 0)) away from J at the
    !> ground origin: F = 5 (-1, 3, 0)/sqrt(10) on part 2, moment (-1, 0, 0) x F about its
    !> centre (0, 3, 0) = (0, 0, -15/sqrt(10)); the reaction on ground is not applied.
    subroutine test_sforce_translation(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        real(wp) :: f1(3), m1(3), f2(3), m2(3)
        integer :: k

        force = statement_force(kind_translation, ["5"])
        force%statement%i = marker_type(id=1, part=2, point=[0.0_wp, 1.0_wp, 0.0_wp])
        call loads(force, f1, m1, f2, m2)
        call check(error, [f2, m2], [-5.0_wp, 15.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -15.0_wp] &
            & /sqrt(10.0_wp), "on I's part", abs_tol=tol)
        if (allocated(error)) return
        call check(error, [f1, m1], [(0.0_wp, k = 1, 6)], "part 1 untouched", abs_tol=0.0_wp)
        if (allocated(error)) return
        ! J on part 1 at its centre (1, 2, 3): the line is (-2, 1, -3); reaction -F there
        force%statement%j = marker_type(id=2, part=1)
        call loads(force, f1, m1, f2, m2)
        call check(error, [f2, f1, m1], [-10.0_wp, 5.0_wp, -15.0_wp, 10.0_wp, -5.0_wp, 15.0_wp, &
            & 0.0_wp, 0.0_wp, 0.0_wp]/sqrt(14.0_wp), "action on I, reaction on J", abs_tol=tol)
    end subroutine test_sforce_translation

    !> A torque of 2 N m about J's z axis: J on part 2 with its axes those of part 2 turned by
    !> 90 degrees about x, so J's z is part 2's -y, which is ground +X: (2, 0, 0) on I's part 1,
    !> (-2, 0, 0) on part 2; no force.
    subroutine test_sforce_rotation(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        real(wp) :: f1(3), m1(3), f2(3), m2(3)

        force = statement_force(kind_rotation, ["2*TIME + 2"])
        force%statement%i = marker_type(id=1, part=1, point=[0.5_wp, 0.0_wp, 0.0_wp])
        force%statement%j = marker_type(id=2, part=2, axes=rotation_matrix(0.0_wp, 0.5_wp*pi, &
            & 0.0_wp))
        call loads(force, f1, m1, f2, m2)
        call check(error, [f1, m1, f2, m2], [0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, &
            & 0.0_wp, 0.0_wp, 0.0_wp, -2.0_wp, 0.0_wp, 0.0_wp], "torque and reaction", abs_tol=tol)
    end subroutine test_sforce_rotation

    !> ACTIONONLY, translational: 3 N on I along J's z axis (J on part 1, its axes turned so
    !> that z is ground +X), at I = part 2's (0, 0, 0.5) (part 2's z is ground Z): moment
    !> (0, 0, 0.5) x (3, 0, 0) = (0, 1.5, 0); nothing on J's part.
    subroutine test_sforce_action_only(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        real(wp) :: f1(3), m1(3), f2(3), m2(3)

        force = statement_force(kind_translation, ["3"])
        force%statement%action_only = .true.
        force%statement%i = marker_type(id=1, part=2, point=[0.0_wp, 0.0_wp, 0.5_wp])
        force%statement%j = marker_type(id=2, part=1, axes=matmul(transpose(rotation_matrix( &
            & q(4), q(5), q(6))), rotation_matrix(0.5_wp*pi, 0.5_wp*pi, 0.0_wp)))
        call loads(force, f1, m1, f2, m2)
        call check(error, [f2, m2], [3.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.5_wp, 0.0_wp], &
            & "along J's z, at I", abs_tol=tol)
        if (allocated(error)) return
        call check(error, [f1, m1], [0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp], &
            & "no reaction", abs_tol=0.0_wp)
    end subroutine test_sforce_action_only

    !> VFORCE (1, 2, 0) in RM's axes, RM = part 2's centre marker (x, y along ground Y, -X):
    !> (-2, 1, 0) in ground, at I = part 2's (1, 0, 0), ground (0, 4, 0); moment about part 2's
    !> centre (0, 1, 0) x (-2, 1, 0) = (0, 0, 2). Reaction on JFLOAT's part 1 at the same
    !> point: -(-2, 1, 0), moment ((0, 4, 0) - (1, 2, 3)) x (2, -1, 0) = (-3, -6, -3).
    subroutine test_vforce(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        real(wp) :: f1(3), m1(3), f2(3), m2(3)

        force = statement_force(kind_vector, ["1", "2", "0"])
        force%statement%i = marker_type(id=1, part=2, point=[1.0_wp, 0.0_wp, 0.0_wp])
        force%statement%j = marker_type(id=2, part=1, point=[0.3_wp, 0.3_wp, 0.3_wp])
        force%statement%rm = marker_type(id=3, part=2)
        call loads(force, f1, m1, f2, m2)
        call check(error, [f2, m2], [-2.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 2.0_wp], &
            & "action", abs_tol=tol)
        if (allocated(error)) return
        call check(error, [f1, m1], [2.0_wp, -1.0_wp, 0.0_wp, -3.0_wp, -6.0_wp, -3.0_wp], &
            & "reaction at I's point", abs_tol=tol)
    end subroutine test_vforce

    !> GFORCE: the VFORCE above and a torque (0, 0, 4) in RM's axes (ground Z as well):
    !> moments (0, 0, 6) on part 2 and (-3, -6, -7) on part 1.
    subroutine test_gforce(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        real(wp) :: f1(3), m1(3), f2(3), m2(3)

        force = statement_force(kind_general, ["1", "2", "0", "0", "0", "4"])
        force%statement%i = marker_type(id=1, part=2, point=[1.0_wp, 0.0_wp, 0.0_wp])
        force%statement%j = marker_type(id=2, part=1)
        force%statement%rm = marker_type(id=3, part=2)
        call loads(force, f1, m1, f2, m2)
        call check(error, [f2, m2, f1, m1], [-2.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 6.0_wp, &
            & 2.0_wp, -1.0_wp, 0.0_wp, -3.0_wp, -6.0_wp, -7.0_wp], "force and torque", &
            & abs_tol=tol)
    end subroutine test_gforce

    !> A dataset in mm, minutes and kN: FX = 2 DX(5) + VX(5) + TIME + WZ(5) with marker 5 the
    !> centre of part 2 moving at 0.2 m/s along X and turning at 0.5 rad/s, at t = 120 s:
    !> 2 * 0 + 0.2 * 60 / 1e-3 + 2 + 0.5 * 60 = 12032 kN; TX = 1 kN mm = 1 N m.
    subroutine test_units(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: force
        real(wp) :: state_u(12), f(3), m(3)

        force = statement_force(kind_general, [character(len=40) :: &
            & "2*DX(5) + VX(5) + TIME + WZ(5)", "0", "0", "1", "0", "0"])
        force%statement%i = marker_type(id=1, part=2)
        force%statement%markers = [marker_type(id=5, part=2, point=[0.0_wp, 0.0_wp, 0.0_wp])]
        force%statement%time_unit = 60.0_wp
        force%statement%length_unit = 1.0e-3_wp
        force%statement%force_unit = 1.0e3_wp
        state_u = 0.0_wp
        state_u(7) = 0.2_wp
        state_u(10) = 0.5_wp
        call force_and_moment([force], 2, 120.0_wp, [q(1:6), 0.0_wp, 0.0_wp, 0.0_wp, &
            & 0.0_wp, 0.0_wp, 0.0_wp], state_u, f, m)
        call check(error, [f, m], [12032.0e3_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp], &
            & "SI force and moment", rel_tol=tol, abs_tol=tol)
    end subroutine test_units

    !> One rule: a half-sine pulse and an expression switching at the same times stop the
    !> integrator at the same 21 times; a STEP in minutes switches at 60 s and 120 s; a single
    !> IF switch is one stop; a switch on a state function is none.
    subroutine test_breakpoints(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: pulse, expression
        real(wp), allocatable :: times(:), other(:)
        integer :: k

        pulse%profile = profile_half_sine
        pulse%start = 2.0_wp
        pulse%duration = 0.01_wp
        expression = statement_force(kind_vector, [character(len=60) :: &
            & "IF(TIME-2: 0, 0, IF(TIME-2.01: SIN(PI*(TIME-2)/0.01), 0, 0))", "0", "0"])
        times = force_breakpoints([pulse])
        other = force_breakpoints([expression])
        call check(error, size(times) == size(other) .and. all([(any(other == times(k)), &
            & k = 1, size(times))]), "the same stops, bit for bit")
        if (allocated(error)) return
        call check(error, times, [(2.0_wp + k*0.0005_wp, k = 0, 20)], "every 0.5 ms", &
            & abs_tol=tol)
        if (allocated(error)) return
        expression = statement_force(kind_vector, [character(len=40) :: "STEP(TIME, 1, 0, 2, 1)", &
            & "IF(TIME - 3: 0, 0, 1)", "IF(DX(1): 0, 1, 1)"])
        expression%statement%time_unit = 60.0_wp
        times = force_breakpoints([expression])
        call check(error, size(times) == 22, "21 stops of the STEP, 1 of the IF")
        if (allocated(error)) return
        call check(error, [minval(times), maxval(times), times(size(times))], [60.0_wp, &
            & 180.0_wp, 180.0_wp], "in seconds", abs_tol=0.0_wp)
        if (allocated(error)) return
        call check(error, pulse_stops(60.0_wp, 120.0_wp), [(60.0_wp + 3.0_wp*k, k = 0, 20)], &
            & "pulse_stops", abs_tol=tol)
    end subroutine test_breakpoints

    !> The loads of force statements, evaluated as every right-hand side does, call malloc
    !> not once: the expressions' inputs live in a fixed array (at most max_inputs), a
    !> SPRINGDAMPER's and a BUSHING's loads in fixed arrays.
    subroutine test_no_allocation(error)
        type(error_type), allocatable, intent(out) :: error
        type(applied_force_type) :: forces(4)
        real(wp) :: f(3), m(3), total
        integer(c_long) :: before
        integer :: k

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        forces(1) = statement_force(kind_general, [character(len=40) :: &
            & "2*DX(5) + VX(5) + TIME + WZ(5)", "PSI(5)", "0", "THETA(5)*STEP(TIME, 1, 0, 2, 1)", &
            & "0", "PHI(5)"])
        forces(1)%statement%i = marker_type(id=1, part=2)
        forces(1)%statement%markers = [marker_type(id=5, part=1, point=[0.1_wp, 0.0_wp, &
            & 0.0_wp])]
        forces(2) = statement_force(kind_translation, ["-3*(DX(5) - DX(6))"])
        forces(2)%statement%i = marker_type(id=5, part=1, point=[0.1_wp, 0.0_wp, 0.0_wp])
        forces(2)%statement%j = marker_type(id=6, part=2)
        forces(2)%statement%markers = [forces(2)%statement%i, forces(2)%statement%j]
        ! a BUSHING and a translational SPRINGDAMPER between the parts (rollcon_spring_force)
        forces(3:4) = forces(2)
        forces(3:4)%statement%kind = kind_spring
        forces(3)%statement%spring = spring_type(kind=spring_bushing, stiffness=[1.0_wp, &
            & 2.0_wp, 3.0_wp], damping=0.5_wp, torsional_stiffness=4.0_wp, &
            & torsional_damping=0.1_wp, preload=1.0_wp, preload_torque=-1.0_wp)
        forces(4)%statement%spring = spring_type(kind=spring_translational, stiffness=5.0_wp, &
            & damping=0.2_wp, reference=0.3_wp, preload=2.0_wp)
        total = 0.0_wp
        before = malloc_count()
        do k = 1, 100
            call force_and_moment(forces, 1 + mod(k, 2), 0.01_wp*k, q, u, f, m)
            total = total + sum(f) + sum(m)
        end do
        call check(error, malloc_count() - before == 0_c_long, "force_and_moment allocated " &
            & // "(total " // merge("finite    ", "not finite", abs(total) < huge(total)) // ")")
    end subroutine test_no_allocation

end module test_adm_forces
