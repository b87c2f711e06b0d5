! SPDX-License-Identifier: MIT
!> The dataset reader: every statement and keyword of the subset, abbreviations, units, degrees,
!> and one refusal per kind with its message.
module test_adm_reader
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_adm_model, only : adm_model_type, force_sforce, force_gforce
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_units, only : units_type, set_unit
    use rollcon_expression, only : evaluate_expression
    use rollcon_adm_state, only : part_state
    use rollcon_rotation, only : rotation_matrix, rate_matrix, euler_angles
    use rollcon_run_settings, only : formulation_cvode, method_adams, drift_baumgarte
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_adm_reader

    character(len=*), parameter :: work_dir = "build/rollcon-test"
    !> Values are decimal literals converted once: a few ulp
    real(wp), parameter :: tol = 1.0e-14_wp

    !> A disk of the coin's size as an ADAMS user writes it, with abbreviations and mixed case
    character(len=72), parameter :: coin(19) = [character(len=72) :: &
        & "rolling disk, rollcon test", &
        & "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=METER, TIME=SECOND", &
        & "part/1, ground", &
        & "PART/2, MASS=0.7351, CM=3, IP=0.001838, 0.001838, 0.003676", &
        & ", QG=0, 0, 0.1  ! the centre, one radius up", &
        & ", VX=0.1, WZ=-1", &
        & "MARK/3, PART=2, REU=0D, 90D, 0D", &
        & "MARKER/4, PART=2, QP=0, 0.1, 0", &
        & "MARKER/5, PART=1", &
        & "UCON/1, FUNCTION=USER(2, 21,22,23,14,15,24,25,26, 0.1, 1)", &
        & "UCON/2, FUNCTION=USER(2, 21,22,23,14,15,24,25,26, 0.1, 2)", &
        & "ACCGRAV/KGRAV=-9.81", &
        & "VFORCE/6, I=4, JFLOAT=5, RM=5, FX=0, FZ=0", &
        & ", FY=HAVSIN(TIME, 2, 0, 2.005, 1) - HAVSIN(TIME, 2.005, 0, 2.01, 1)\", &
        & "SFORCE/7, I=4, J=5, ROT, ACTION, FUNC=0.01*TIME", &
        & "SIM/DYN, END=10, STEPS=1000", &
        & "INTEG/ERR=1e-9, FORM=cvode, METH=adams, DRIFT=baum", &
        & "OUTPUT", &
        & "END"]

contains

    subroutine collect_adm_reader(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("coin-as-a-user-writes-it", test_coin), &
            & new_unittest("units-converted", test_units), &
            & new_unittest("unit-factors-from-definitions", test_unit_factors), &
            & new_unittest("euler-angles-round-trip", test_euler_round_trip), &
            & new_unittest("coin-initial-state", test_coin_state), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_adm_reader

    subroutine read_lines(name, lines, model, error)
        character(len=*), intent(in) :: name, lines(:)
        type(adm_model_type), intent(out) :: model
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, i

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        do i = 1, size(lines)
            write(unit, '(a)') trim(lines(i))
        end do
        close(unit)
        call read_adm(work_dir // "/" // name, model, error)
    end subroutine read_lines

    subroutine test_coin(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model

        call read_lines("coin_test.adm", coin, model, error)
        if (allocated(error)) return
        call check(error, size(model%parts) == 2 .and. size(model%markers) == 3 &
            & .and. size(model%ucons) == 2 .and. size(model%forces) == 2, "counts")
        if (allocated(error)) return
        associate (disk => model%parts(2))
            call check(error, disk%id == 2 .and. disk%cm == 3 .and. .not. disk%ground &
                & .and. model%parts(1)%ground, "parts")
            if (allocated(error)) return
            call check(error, [disk%mass, disk%ip, disk%qg], [0.7351_wp, 0.001838_wp, &
                & 0.001838_wp, 0.003676_wp, 0.0_wp, 0.0_wp, 0.1_wp], "mass, IP, QG", abs_tol=tol)
            if (allocated(error)) return
            call check(error, disk%velocity_given(1) .and. .not. any(disk%velocity_given(2:3)) &
                & .and. disk%angular_velocity_given(3) .and. disk%velocity(1) == 0.1_wp &
                & .and. disk%angular_velocity(3) == -1.0_wp, "VX, WZ")
            if (allocated(error)) return
        end associate
        call check(error, model%markers(1)%reuler, [0.0_wp, 0.5_wp*pi, 0.0_wp], "REULER in D", &
            & abs_tol=tol)
        if (allocated(error)) return
        call check(error, model%ucons(2)%par, [2.0_wp, 21.0_wp, 22.0_wp, 23.0_wp, 14.0_wp, &
            & 15.0_wp, 24.0_wp, 25.0_wp, 26.0_wp, 0.1_wp, 2.0_wp], "UCON/2 PAR", abs_tol=tol)
        if (allocated(error)) return
        call check(error, model%gravity, [0.0_wp, 0.0_wp, -9.81_wp], "ACCGRAV", abs_tol=tol)
        if (allocated(error)) return
        associate (push => model%forces(1), torque => model%forces(2))
            call check(error, push%kind /= force_sforce .and. push%kind /= force_gforce &
                & .and. push%i == 4 .and. push%j == 5 .and. push%rm == 5 &
                & .and. all(push%given(1:3)), "VFORCE")
            if (allocated(error)) return
            ! the two haversines make a pulse that peaks at 1 halfway
            call check(error, evaluate_expression(push%functions(2), 2.005_wp), 1.0_wp, &
                & "FY at the peak", abs_tol=tol)
            if (allocated(error)) return
            call check(error, torque%kind == force_sforce .and. .not. torque%translation &
                & .and. torque%action_only .and. &
                & evaluate_expression(torque%functions(1), 3.0_wp) == 0.03_wp, "SFORCE")
            if (allocated(error)) return
        end associate
        call check(error, model%run%settings%end_time == 10.0_wp &
            & .and. model%run%settings%rtol == 1.0e-9_wp &
            & .and. model%run%settings%formulation == formulation_cvode &
            & .and. model%run%settings%method == method_adams &
            & .and. model%run%settings%drift == drift_baumgarte, "run")
        if (allocated(error)) return
        call check(error, model%run%settings%output_step, 0.01_wp, "STEPS", rel_tol=tol)
    end subroutine test_coin

    !> CGS: lengths in cm, masses in g, times in s; one hour of end time in HOUR units.
    subroutine test_units(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        character(len=72) :: lines(size(coin))

        lines = coin
        lines(2) = "UNITS/SYSTEM=CGS"
        call read_lines("cgs_test.adm", lines, model, error)
        if (allocated(error)) return
        call check(error, [model%parts(2)%mass, model%parts(2)%ip(3), model%parts(2)%qg(3), &
            & model%parts(2)%velocity(1), model%gravity(3)], [0.7351e-3_wp, 0.003676e-7_wp, &
            & 0.1e-2_wp, 0.1e-2_wp, -9.81e-2_wp], "CGS to SI", rel_tol=tol)
        if (allocated(error)) return
        lines(2) = "UNITS/LENGTH=MILLIMETER, TIME=MINUTE"
        call read_lines("mm_test.adm", lines, model, error)
        if (allocated(error)) return
        call check(error, [model%parts(2)%velocity(1), model%parts(2)%angular_velocity(3), &
            & model%run%settings%end_time], [0.1e-3_wp/60.0_wp, -1.0_wp/60.0_wp, 600.0_wp], &
            & "mm and minutes to SI", rel_tol=tol)
    end subroutine test_units

    !> Every unit name's factor to SI against its definition: the international pound
    !> (0.45359237 kg), standard gravity (9.80665 m/s^2) and inch (0.0254 m) are exact; the
    !> pound-force is a pound under standard gravity, the slug the mass a pound-force
    !> accelerates at a foot per second squared, the dyne a gram at a centimetre per second
    !> squared. SYSTEM sets all four factors, whatever came before.
    subroutine test_unit_factors(error)
        type(error_type), allocatable, intent(out) :: error
        !> Products and quotients of exact decimal constants: a rounding or two each
        real(wp), parameter :: tol_definition = 4.0_wp*epsilon(1.0_wp)
        !> The table writes the slug to 14 significant digits (14.593902937206): 2.5e-14 from
        !> the pound-force over a foot
        real(wp), parameter :: tol_slug = 5.0e-14_wp
        real(wp), parameter :: pound = 0.45359237_wp, g_n = 9.80665_wp, inch = 0.0254_wp
        character(len=14), parameter :: forces(6) = [character(len=14) :: "NEWTON", &
            & "KNEWTON", "MILLINEWTON", "DYNE", "KILOGRAM_FORCE", "POUND_FORCE"]
        character(len=10), parameter :: masses(4) = [character(len=10) :: "KILOGRAM", "GRAM", &
            & "MEGAGRAM", "POUND_MASS"]
        character(len=10), parameter :: lengths(6) = [character(len=10) :: "METER", &
            & "MILLIMETER", "CENTIMETER", "KILOMETER", "INCH", "FOOT"]
        character(len=11), parameter :: times(4) = [character(len=11) :: "SECOND", &
            & "MILLISECOND", "MINUTE", "HOUR"]
        real(wp) :: expected_forces(6), expected_masses(4), expected_lengths(6), &
            & expected_times(4), got(6)
        type(units_type) :: units
        integer :: k

        expected_forces = [1.0_wp, 1.0e3_wp, 1.0e-3_wp, 1.0e-3_wp*1.0e-2_wp, g_n, pound*g_n]
        expected_masses = [1.0_wp, 1.0e-3_wp, 1.0e3_wp, pound]
        expected_lengths = [1.0_wp, 1.0e-3_wp, 1.0e-2_wp, 1.0e3_wp, inch, 12.0_wp*inch]
        expected_times = [1.0_wp, 1.0e-3_wp, 60.0_wp, 3600.0_wp]
        do k = 1, size(forces)
            call set_unit(units, "FORCE", trim(forces(k)), "test.adm:2", error)
            if (allocated(error)) return
            got(k) = units%force
        end do
        call check(error, got, expected_forces, "force units", rel_tol=tol_definition)
        if (allocated(error)) return
        do k = 1, size(masses)
            call set_unit(units, "MASS", trim(masses(k)), "test.adm:2", error)
            if (allocated(error)) return
            got(k) = units%mass
        end do
        call check(error, got(:4), expected_masses, "mass units", rel_tol=tol_definition)
        if (allocated(error)) return
        call set_unit(units, "MASS", "SLUG", "test.adm:2", error)
        if (allocated(error)) return
        call check(error, units%mass, pound*g_n/(12.0_wp*inch), "the slug", rel_tol=tol_slug)
        if (allocated(error)) return
        do k = 1, size(lengths)
            call set_unit(units, "LENGTH", trim(lengths(k)), "test.adm:2", error)
            if (allocated(error)) return
            got(k) = units%length
        end do
        call check(error, got, expected_lengths, "length units", rel_tol=tol_definition)
        if (allocated(error)) return
        do k = 1, size(times)
            call set_unit(units, "TIME", trim(times(k)), "test.adm:2", error)
            if (allocated(error)) return
            got(k) = units%time
        end do
        call check(error, got(:4), expected_times, "time units", rel_tol=tol_definition)
        if (allocated(error)) return

        ! units is now (pound-force, slug, foot, hour): each system replaces all four
        call set_unit(units, "SYSTEM", "CGS", "test.adm:2", error)
        if (allocated(error)) return
        call check(error, [units%force, units%mass, units%length, units%time], &
            & [1.0e-5_wp, 1.0e-3_wp, 1.0e-2_wp, 1.0_wp], "CGS", rel_tol=tol_definition)
        if (allocated(error)) return
        call set_unit(units, "SYSTEM", "MMKS", "test.adm:2", error)
        if (allocated(error)) return
        call check(error, [units%force, units%mass, units%length, units%time], &
            & [1.0_wp, 1.0_wp, 1.0e-3_wp, 1.0_wp], "MMKS", rel_tol=tol_definition)
        if (allocated(error)) return
        call set_unit(units, "SYSTEM", "MKS", "test.adm:2", error)
        if (allocated(error)) return
        call check(error, [units%force, units%mass, units%length, units%time], &
            & [1.0_wp, 1.0_wp, 1.0_wp, 1.0_wp], "MKS", rel_tol=tol_definition)
    end subroutine test_unit_factors

    !> One line of the coin replaced: the exact message each refusal must give.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: n = 14
        integer :: lines_at(n), i
        character(len=72) :: replaced(n)
        character(len=320) :: expected(n)
        character(len=72) :: lines(size(coin))
        type(adm_model_type) :: model
        type(error_type), allocatable :: refused
        character(len=*), parameter :: file = work_dir // "/refused.adm:"

        lines_at = [3, 4, 6, 7, 7, 10, 12, 13, 16, 16, 17, 6, 18, 11]
        replaced(1) = "PTCV/9, I=4, J=5"
        expected(1) = file // "3: 'PTCV' is not a statement of the supported subset (ACCGRAV, " &
            & // "ARRAY, BUSHING, CONTACT, COUPLER, DIFF, END, GCON, GEAR, GFORCE, INTEGRATOR, " &
            & // "JOINT, JPRIM, MARKER, MOTION, OUTPUT, PART, PINPUT, POUTPUT, SFORCE, SIMULATE, " &
            & // "SPLINE, SPRINGDAMPER, STRING, UCON, UNITS, VARIABLE, VFORCE, VTORQUE)"
        replaced(2) = "PART/2, MASS=0.7351, CM=3, IP=1, 1, 1, 1.5, 0, 0"
        expected(2) = file // "4: PART/2 IP: the inertia tensor [[xx, -xy, -xz], [-xy, yy, -yz]"
        replaced(3) = ", VX=0.1, W=-1"
        expected(3) = file // "6: PART/2: 'W' is too short an abbreviation of a PART argument"
        ! the CM marker's z-axis along ground z: read, the part starts in turned axes
        replaced(4) = "MARKER/3, PART=2"
        expected(4) = ""
        replaced(5) = "MARKER/3, PART=2, REULER=0, 90, 0"
        expected(5) = ""
        replaced(6) = "UCON/1, FUNCTION=USER(2, 21,,23, 0.1, 1)"
        expected(6) = file // "10: UCON/1 FUNCTION USER: '' is not a number"
        replaced(7) = "ACCGRAV/KGRAV=-9.81D"
        expected(7) = file // "12: ACCGRAV KGRAV: '-9.81D': D (degrees) is for angles only"
        replaced(8) = "VFORCE/6, I=4, JFLOAT=8, RM=5, FX=0, FZ=0"
        expected(8) = file // "13: VFORCE/6 JFLOAT: no MARKER/8"
        replaced(9) = "SIM/STATICS, END=10"
        expected(9) = file // "16: SIMULATE: 'STATICS' is not a SIMULATE argument"
        replaced(10) = "SIM/DYN, END=10"
        expected(10) = file // "16: SIMULATE: give one of STEPS=n and DTOUT=dt"
        replaced(11) = "INTEG/ERR=1e-9, FORM=ode"
        expected(11) = file // "17: INTEGRATOR FORMULATION: 'ode' is not a formulation"
        replaced(12) = ", VX=0.1, WZ=-1, WZ=2"
        expected(12) = file // "6: PART/2: WZ is given twice"
        replaced(13) = "OUTPUT/REQSAVE=1"
        expected(13) = file // "18: OUTPUT REQSAVE takes no value"
        replaced(14) = "UCON/1, FUNCTION=USER(2, 21)"
        expected(14) = file // "11: UCON/1: a second UCON with this id"
        do i = 1, n
            lines = coin
            lines(lines_at(i)) = replaced(i)
            call read_lines("refused.adm", lines, model, refused)
            if (len_trim(expected(i)) == 0) then
                ! REULER=0, 90, 0 is 90 radians, not degrees: the axis is turned, so accepted;
                ! an axis along ground z starts in turned axes (docs/rebasing.md), so accepted
                call check(error, .not. allocated(refused), trim(replaced(i)))
            else
                call check(error, allocated(refused), trim(replaced(i)) // " accepted")
                if (allocated(error)) return
                call check(error, index(refused%message, trim(expected(i))) == 1, &
                    & refused%message)
            end if
            if (allocated(error)) return
            if (allocated(refused)) deallocate(refused)
        end do
    end subroutine test_refusals

    !> Angles -> matrix -> angles on a grid away from sin(theta) = 0, every quadrant of psi, phi.
    subroutine test_euler_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        !> atan2 of exact-to-rounding matrix entries: a few ulp of pi
        real(wp), parameter :: tol_angle = 1.0e-14_wp
        real(wp) :: angles(3)
        integer :: i, j, k

        do i = -3, 3
            do j = 1, 5
                do k = -3, 3
                    angles = [0.9_wp*i, 0.5_wp*j + 0.1_wp, 0.95_wp*k]
                    call check(error, euler_angles(rotation_matrix(angles(1), angles(2), &
                        & angles(3))), angles, "round trip", abs_tol=tol_angle)
                    if (allocated(error)) return
                end do
            end do
        end do
    end subroutine test_euler_round_trip

    !> The coin's CM marker turned 90 degrees about x, VX = 0.1 m/s, WZ = -1 rad/s: upright
    !> (theta = pi/2, psi = 0, axis along -Y), centre at (0, 0, R), rolling along +X with
    !> phidot = -v/R (docs/design.md §5).
    subroutine test_coin_state(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        real(wp) :: q(6), u(6)

        call read_lines("coin_state.adm", coin, model, error)
        if (allocated(error)) return
        call part_state(model, model%parts(2), q, u)
        call check(error, q, [0.0_wp, 0.0_wp, 0.1_wp, 0.0_wp, 0.5_wp*pi, 0.0_wp], "q", &
            & abs_tol=tol)
        if (allocated(error)) return
        call check(error, u, [0.1_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, -1.0_wp], "u", abs_tol=tol)
        if (allocated(error)) return
        ! any pose and angular velocity: the rates map back to the body components given
        model%parts(2)%reuler = [0.3_wp, -1.1_wp, 2.0_wp]
        model%parts(2)%angular_velocity = [1.5_wp, -2.0_wp, 0.25_wp]
        call part_state(model, model%parts(2), q, u)
        call check(error, matmul(rate_matrix(q(5), q(6)), u(4:6)), [1.5_wp, -2.0_wp, 0.25_wp], &
            & "omega' = B u", abs_tol=tol)
    end subroutine test_coin_state

end module test_adm_reader
