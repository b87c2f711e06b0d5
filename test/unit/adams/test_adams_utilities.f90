! SPDX-License-Identifier: MIT
!> Tests of the ADAMS utilities of pure arithmetic a user's routine calls (suite
!> adams-utilities): RCNVRT against rotations worked by hand and through every system and
!> back; STEP at points worked by hand and its refusals. (STEP, AKISPL, CUBSPL and RCNVRT
!> called from a user's SFOSUB against the expression functions: suite user-forces.)
module test_adams_utilities
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rollcon_adams_utilities, only : step_utility, convert_rotation, rotation_size, &
        & rotation_systems, rcnvrt_success, rcnvrt_failure
    implicit none
    private

    public :: collect_adams_utilities

    !> Largest difference allowed from a value worked by hand, on values of size 1: each
    !> conversion is a few tens of roundings of sines, cosines, square roots and atan2
    !> (1.1e-16 each), so 1e-14 holds them with room; a wrong sign or axis is 0.1 or more.
    real(wp), parameter :: tolerance = 1.0e-14_wp
    real(wp), parameter :: quarter_turn = 0.5_wp*acos(-1.0_wp)

contains

    subroutine collect_adams_utilities(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("rcnvrt-euler-to-cosines", test_euler_cosines), &
            & new_unittest("rcnvrt-euler-to-eulpar", test_euler_eulpar), &
            & new_unittest("rcnvrt-third-turn", test_third_turn), &
            & new_unittest("rcnvrt-every-system-and-back", test_round_trip), &
            & new_unittest("rcnvrt-refusals", test_rcnvrt_refusals), &
            & new_unittest("step-by-hand", test_step)]
    end subroutine collect_adams_utilities

    !> EULER (90 deg, 0, 0): a quarter turn about z, whose axes are x' = y, y' = -x, z' = z:
    !> COSINES, by columns, (0, 1, 0, -1, 0, 0, 0, 0, 1).
    subroutine test_euler_cosines(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: cosines(9)
        integer :: istat

        call convert_rotation("EULER", [quarter_turn, 0.0_wp, 0.0_wp], "cosines", cosines, &
            & istat)
        call expect(cosines, [0.0_wp, 1.0_wp, 0.0_wp, -1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, &
            & 0.0_wp, 1.0_wp], istat, "EULER (90D, 0, 0) as COSINES", error)
    end subroutine test_euler_cosines

    !> EULER (0, 90 deg, 0): a quarter turn about x; EULPAR (cos 45, sin 45, 0, 0).
    subroutine test_euler_eulpar(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: e(4)
        integer :: istat

        call convert_rotation("EULER", [0.0_wp, quarter_turn, 0.0_wp], "EULPAR", e, istat)
        call expect(e, [sqrt(0.5_wp), sqrt(0.5_wp), 0.0_wp, 0.0_wp], istat, &
            & "EULER (0, 90D, 0) as EULPAR", error)
    end subroutine test_euler_eulpar

    !> A third of a turn about (1, 1, 1)/sqrt(3), EULPAR (1/2, 1/2, 1/2, 1/2), takes x to y,
    !> y to z and z to x: COSINES (0, 1, 0, 0, 0, 1, 1, 0, 0); RODPAR (1, 1, 1); as YPR (body
    !> 3-2-1) a quarter turn about z after a quarter turn about x, (90D, 0, 90D); as S123 the
    !> same angles reversed, (90D, 0, 90D).
    subroutine test_third_turn(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: e(4) = [0.5_wp, 0.5_wp, 0.5_wp, 0.5_wp]
        real(wp) :: cosines(9), rodrigues(3), angles(3)
        integer :: istat

        call convert_rotation("EULPAR", e, "COSINES", cosines, istat)
        call expect(cosines, [0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, &
            & 0.0_wp, 0.0_wp], istat, "EULPAR (1/2, 1/2, 1/2, 1/2) as COSINES", error)
        if (allocated(error)) return
        call convert_rotation("EULPAR", e, "RODPAR", rodrigues, istat)
        call expect(rodrigues, [1.0_wp, 1.0_wp, 1.0_wp], istat, "as RODPAR", error)
        if (allocated(error)) return
        call convert_rotation("COSINES", cosines, "YPR", angles, istat)
        call expect(angles, [quarter_turn, 0.0_wp, quarter_turn], istat, "COSINES as YPR", &
            & error)
        if (allocated(error)) return
        call convert_rotation(" rodpar ", rodrigues, "S123", angles, istat)
        call expect(angles, [quarter_turn, 0.0_wp, quarter_turn], istat, "RODPAR as S123", &
            & error)
    end subroutine test_third_turn

    !> A rotation of no symmetry, EULPAR normalised from (0.9, 0.3, -0.2, 0.25), through each
    !> system RCNVRT knows and back to EULPAR: the same parameters. A sequence's angles read
    !> with the wrong formula (a sign, an axis) come back as another rotation.
    subroutine test_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: e(4), through(9), back(4)
        integer :: k, istat, n

        e = [0.9_wp, 0.3_wp, -0.2_wp, 0.25_wp]
        e = e/norm2(e)
        do k = 1, size(rotation_systems)
            n = rotation_size(rotation_systems(k))
            call convert_rotation("EULPAR", e, rotation_systems(k), through, istat)
            if (istat /= rcnvrt_success) then
                call fatal_error(error, "RCNVRT refused EULPAR to " &
                    & // trim(rotation_systems(k)) // ": ISTAT = " // to_text(istat))
                return
            end if
            call convert_rotation(rotation_systems(k), through(:n), "EULPAR", back, istat)
            call expect(back, e, istat, "EULPAR through " // trim(rotation_systems(k)), error)
            if (allocated(error)) return
        end do
    end subroutine test_round_trip

    !> A name RCNVRT does not know, AXAYAZ, and RODPAR of a half turn: ISTAT = -10, COORD2 0.
    subroutine test_rcnvrt_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: out(4)
        integer :: unknown, axayaz, half_turn

        call convert_rotation("EULAR", [0.1_wp, 0.2_wp, 0.3_wp], "EULPAR", out, unknown)
        call convert_rotation("EULER", [0.1_wp, 0.2_wp, 0.3_wp], "AXAYAZ", out, axayaz)
        call convert_rotation("EULER", [0.0_wp, 2.0_wp*quarter_turn, 0.0_wp], "RODPAR", out, &
            & half_turn)
        call check(error, all([unknown, axayaz, half_turn] == rcnvrt_failure) .and. &
            & all(out == 0.0_wp), "ISTAT: unknown " // to_text(unknown) // ", AXAYAZ " &
            & // to_text(axayaz) // ", half turn " // to_text(half_turn))
    end subroutine test_rcnvrt_refusals

    !> STEP(x, 1, 2, 3, 6, ...): at x = 1.5 (s = 1/4) the value 2 + 4 (1/16)(5/2) = 2.625,
    !> the slope 4 * 6 (1/4)(3/4)/2 = 2.25, the curvature 4 * 6 (1/2)/4 = 3; h0 before x0 and
    !> h1 after x1 with zero derivatives; ERRFLG for x1 <= x0 and IORD = 3.
    subroutine test_step(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: got(7)
        logical :: flags(7), reversed, order

        call step_utility(1.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 0, got(1), flags(1))
        call step_utility(1.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 1, got(2), flags(2))
        call step_utility(1.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 2, got(3), flags(3))
        call step_utility(0.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 0, got(4), flags(4))
        call step_utility(0.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 1, got(5), flags(5))
        call step_utility(3.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 0, got(6), flags(6))
        call step_utility(3.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 2, got(7), flags(7))
        call expect(got, [2.625_wp, 2.25_wp, 3.0_wp, 2.0_wp, 0.0_wp, 6.0_wp, 0.0_wp], &
            & merge(rcnvrt_failure, rcnvrt_success, any(flags)), "STEP", error)
        if (allocated(error)) return
        call step_utility(1.5_wp, 3.0_wp, 2.0_wp, 1.0_wp, 6.0_wp, 0, got(1), reversed)
        call step_utility(1.5_wp, 1.0_wp, 2.0_wp, 3.0_wp, 6.0_wp, 3, got(2), order)
        call check(error, reversed .and. order .and. all(got(1:2) == 0.0_wp), &
            & "ERRFLG: x1 < x0 " // merge("T", "F", reversed) // ", IORD = 3 " &
            & // merge("T", "F", order))
    end subroutine test_step

    !> got must equal expected to tolerance, with istat rcnvrt_success.
    subroutine expect(got, expected, istat, what, error)
        real(wp), intent(in) :: got(:), expected(:)
        integer, intent(in) :: istat
        character(len=*), intent(in) :: what
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: text
        integer :: k

        if (istat == rcnvrt_success .and. maxval(abs(got - expected)) <= tolerance) return
        text = ""
        do k = 1, size(got)
            text = text // " " // to_text(got(k))
        end do
        call fatal_error(error, what // ": ISTAT " // to_text(istat) // ", got" // text)
    end subroutine expect

end module test_adams_utilities
