! SPDX-License-Identifier: MIT
!> SPRINGDAMPER, BUSHING and VTORQUE statements as read (suite adm-springs;
!> src/input/dataset/rollcon_adm_loads.f90): their constants in SI from the dataset's units
!> (a stiffness in N/mm is 1000 N/m; an ANGLE in degrees), their minimum abbreviations, and
!> what they may not say, refused by name and line.
module test_adm_springs
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_adm_model, only : adm_model_type, force_springdamper, force_bushing, &
        & force_vtorque
    use adm_datasets, only : check_refusals, read_dataset, base
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_adm_springs

contains

    subroutine collect_adm_springs(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("constants-in-si", test_constants), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_adm_springs

    !> In millimetres (mm, kg, s, N) a stiffness K = 2 N/mm is
    !> 2000 N/m, a damping C = 0.5 N s/mm 500 N s/m, LENGTH = 300 mm 0.3 m, KT = 4 N mm/rad
    !> 0.004 N m/rad, TORQUE = 7 N mm 0.007 N m, ANGLE = 30D pi/6 rad; abbreviated as ADAMS
    !> takes them (SPR, TR, R, L, F, A, TO; BU; VT).
    subroutine test_constants(error)
        type(error_type), allocatable, intent(out) :: error
        !> Conversions by powers of ten of numbers given to two digits: rounding only
        real(wp), parameter :: tol = 1.0e-15_wp
        character(len=140) :: lines(size(base) + 3)
        type(adm_model_type) :: model
        integer :: k

        lines(:size(base)) = base
        lines(2) = "UNITS/FORCE=NEWTON, MASS=KILOGRAM, LENGTH=MILLIMETER, TIME=SECOND"
        lines(size(base) + 1:) = lines(size(base) - 2:size(base))
        lines(size(base) - 2) = "SPR/6, I=3, J=4, TR, K=2, C=0.5, L=300, F=-1.5"
        lines(size(base) - 1) = "SPRINGDAMPER/7, I=3, J=4, R, KT=4, CT=0.25, A=30D, TO=7"
        lines(size(base)) = "BU/8, I=3, J=4, K=1, 2, 3, C=4, 5, 6, KT=7, 8, 9, CT=1, 2, 3, " &
            & // "F=1, 2, 3, T=4, 5, 6|VT/9, I=3, JF=4, TX=1, TY=2, TZ=TIME"
        call read_dataset("springs.adm", lines, model, error)
        if (allocated(error)) return
        call check(error, size(model%forces) == 5, "five forces read")
        if (allocated(error)) return
        associate (f => model%forces(2))
            call check(error, f%kind == force_springdamper .and. f%translation .and. f%id == 6, &
                & "SPR/6 is a translational SPRINGDAMPER")
            if (allocated(error)) return
            call check(error, [f%constants(1), f%constants(4), f%reference, f%constants(13)], &
                & [2000.0_wp, 500.0_wp, 0.3_wp, -1.5_wp], "SPR/6 K, C, LENGTH, FORCE in SI", &
                & rel_tol=tol)
            if (allocated(error)) return
        end associate
        associate (f => model%forces(3))
            call check(error, f%kind == force_springdamper .and. .not. f%translation, &
                & "SPRINGDAMPER/7 is rotational")
            if (allocated(error)) return
            call check(error, [f%constants(9), f%constants(12), f%reference, f%constants(18)], &
                & [0.004_wp, 0.00025_wp, pi/6.0_wp, 0.007_wp], "SPRINGDAMPER/7 KT, CT, ANGLE, " &
                & // "TORQUE in SI, about J's z", rel_tol=tol)
            if (allocated(error)) return
        end associate
        associate (f => model%forces(4))
            call check(error, f%kind == force_bushing, "BU/8 is a BUSHING")
            if (allocated(error)) return
            call check(error, f%constants, [1.0e3_wp, 2.0e3_wp, 3.0e3_wp, 4.0e3_wp, 5.0e3_wp, &
                & 6.0e3_wp, 7.0e-3_wp, 8.0e-3_wp, 9.0e-3_wp, 1.0e-3_wp, 2.0e-3_wp, 3.0e-3_wp, &
                & 1.0_wp, 2.0_wp, 3.0_wp, 4.0e-3_wp, 5.0e-3_wp, 6.0e-3_wp], "BU/8 K, C, KT, " &
                & // "CT, FORCE, TORQUE in SI", rel_tol=tol)
            if (allocated(error)) return
        end associate
        associate (f => model%forces(5))
            call check(error, f%kind == force_vtorque .and. f%j == 4 .and. &
                & all(f%given .eqv. [.false., .false., .false., .true., .true., .true.]), &
                & "VT/9 is a VTORQUE of TX, TY, TZ with JFLOAT 4")
            if (allocated(error)) return
        end associate
        do k = 1, 3
            call check(error, model%forces(k + 1)%i == 3 .and. model%forces(k + 1)%j == 4, &
                & "markers I = 3, J = 4")
            if (allocated(error)) return
        end do
    end subroutine test_constants

    !> Each statement replacing the base's SFORCE (line 10), refused.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=120) :: replaced(11)
        character(len=300) :: expected(11)

        replaced(1) = "SPRINGDAMPER/5, I=3, J=4, K=10"
        expected(1) = ":10: SPRINGDAMPER/5: TRANSLATIONAL or ROTATIONAL is missing (a " &
            & // "SPRINGDAMPER is one of them)"
        replaced(2) = "SPRINGDAMPER/5, I=3, J=4, ROTATIONAL, KT=1, K=10"
        expected(2) = ":10: SPRINGDAMPER/5 K: a ROTATIONAL SPRINGDAMPER takes KT, CT, ANGLE " &
            & // "and TORQUE (K, C, LENGTH and FORCE are a TRANSLATIONAL one's)"
        replaced(3) = "SPRINGDAMPER/5, I=3, J=4, ANGLE=10D, TRANSLATIONAL"
        expected(3) = ":10: SPRINGDAMPER/5 ANGLE: a TRANSLATIONAL SPRINGDAMPER takes K, C, " &
            & // "LENGTH and FORCE (KT, CT, ANGLE and TORQUE are a ROTATIONAL one's)"
        replaced(4) = "SPRINGDAMPER/5, I=3, J=4, TRANSLATIONAL, ROTATIONAL"
        expected(4) = ":10: SPRINGDAMPER/5 ROTATIONAL: TRANSLATIONAL and ROTATIONAL are given " &
            & // "together; a SPRINGDAMPER is one of them"
        replaced(5) = "SPRINGDAMPER/5, I=3, J=4, TRANSLATIONAL, K=-1"
        expected(5) = ":10: SPRINGDAMPER/5 K: expected a value >= 0, got -1"
        replaced(6) = "BUSHING/5, I=3, J=4, K=1, 2"
        expected(6) = ":10: BUSHING/5 K: expected 3 numbers, got 2"
        replaced(7) = "BUSHING/5, I=3, K=1, 2, 3"
        expected(7) = ":10: BUSHING/5 J: a BUSHING acts between I and J (J=id)"
        replaced(8) = "VTORQUE/5, I=3, JFLOAT=4, TX=1"
        expected(8) = ":10: VTORQUE/5: TX=e, TY=e, TZ=e (or FUNCTION=USER(r1, ..., r30)) " &
            & // "is needed"
        replaced(9) = "VTORQUE/5, I=3, JFLOAT=4, FX=1, TX=1, TY=0, TZ=0"
        expected(9) = ":10: VTORQUE/5: 'FX' is not a VTORQUE argument*"
        replaced(10) = "SPRINGDAMPER/5, I=3, J=4, T, K=1"
        expected(10) = ":10: SPRINGDAMPER/5: 'T' is too short an abbreviation of a " &
            & // "SPRINGDAMPER argument*"
        replaced(11) = "BUSHING/5, I=3, J=4, CT=1, -2, 3"
        expected(11) = ":10: BUSHING/5 CT: expected a value >= 0, got -2"
        call check_refusals(error, [10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10], replaced, &
            & expected)
    end subroutine test_refusals

end module test_adm_springs
