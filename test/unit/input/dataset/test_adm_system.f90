! SPDX-License-Identifier: MIT
!> A dataset's system and data elements read (suite adm-system): SPLINE's curves read back
!> through AKISPL and CUBSPL at the knots, between them and beyond the ends against values
!> worked by hand; VARVAL put in place, its value and its exact partials those of the
!> expression it names; an algebraic loop among VARIABLEs refused naming each statement and
!> line; PINPUT and POUTPUT checked and named in the warning; a DIF of no DIFF, a DIFF's bad
!> IC and what cannot be read refused by name.
module test_adm_system
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_jet, only : jet_type, jet_variable
    use rollcon_expression, only : evaluate_expression, quantity_varval
    use rollcon_expression_jet, only : evaluate_expression_jet
    use rollcon_adm_model, only : adm_model_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use adm_datasets, only : read_dataset
    implicit none
    private

    public :: collect_adm_system

    !> Values of a cubic on a handful of numbers of order 1: a few roundings
    real(wp), parameter :: tol_value = 1.0e-14_wp

    !> Points (0, 0), (1, 1), (2, 0), (3, 1); SFORCE/5 reads their natural cubic spline,
    !> VARIABLE/7 their Akima curve, VARIABLE/8 the curve of the same points extended along its
    !> end tangents, all at x = TIME
    character(len=64), parameter :: curves(14) = [character(len=64) :: &
        & "curves", &
        & "PART/1, GROUND", &
        & "PART/2, MASS=1, CM=3, IP=2, 2, 3", &
        & "MARKER/3, PART=2", &
        & "MARKER/4, PART=1", &
        & "SPLINE/1, X=0, 1, 2, 3, Y=0, 1, 0, 1", &
        & "SPL/2, X=0, 1, 2, 3, Y=0, 1, 0, 1, LINEAR", &
        & "SFORCE/5, I=3, J=4, TRANSLATION, FUNCTION=CUBSPL(TIME, 0, 1)", &
        & "VAR/7, FUNCTION=AKISPL(TIME, 0, 1)", &
        & "VARIABLE/8, FUNCTION=AKISPL(TIME, 0, 2)", &
        & "VARIABLE/9, FUNCTION=CUBSPL(TIME, 0, 1, 1)", &
        & "PINPUT/1, VARIABLES=7", &
        & "SIMULATE/DYNAMIC, END=1, STEPS=10", &
        & "END"]

contains

    subroutine collect_adm_system(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("spline-at-its-knots-between-and-beyond", test_spline), &
            & new_unittest("varval-in-place-value-and-partials", test_varval), &
            & new_unittest("algebraic-loop-refused-naming-the-statements", test_loop), &
            & new_unittest("pinput-poutput-named-in-the-warning", test_plants), &
            & new_unittest("refusals", test_refusals)]
    end subroutine collect_adm_system

    !> The natural cubic spline of the points has second derivatives 0, -4, 4, 0 at the knots
    !> (its tridiagonal system: 4 s2 + s3 = -12, s2 + 4 s3 = 12), so S(0.5) = 0.5 + (1/6)
    !> (0.125 - 0.5)(-4) = 0.75, S(1.5) = 0.5, S'(0) = 1 - (-4)/6 = 5/3. Akima's slopes are
    !> 2 at x = 0 (the chords 5, 3, 1, -1 beyond and at the end, weights 2 and 2) and 0 at
    !> x = 1, so A(0.5) = 2 h10(0.5) + h01(0.5) = 0.25 + 0.5 = 0.75 and, beyond the first
    !> point, the end cubic 2 s - s^2 gives A(-1) = -3 where the tangent line gives -2.
    subroutine test_spline(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        real(wp), parameter :: knots(4) = [0.0_wp, 1.0_wp, 2.0_wp, 3.0_wp], &
            & heights(4) = [0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp]
        real(wp) :: value
        integer :: k

        call read_dataset("curves.adm", curves, model, error)
        if (allocated(error)) return
        do k = 1, 4
            call expect(model, 0, knots(k), heights(k), "CUBSPL at knot " // to_text(k), error)
            if (allocated(error)) return
            call expect(model, 7, knots(k), heights(k), "AKISPL at knot " // to_text(k), error)
            if (allocated(error)) return
        end do
        call expect(model, 0, 0.5_wp, 0.75_wp, "CUBSPL(0.5)", error)
        if (allocated(error)) return
        call expect(model, 0, 1.5_wp, 0.5_wp, "CUBSPL(1.5)", error)
        if (allocated(error)) return
        call expect(model, 9, 0.0_wp, 5.0_wp/3.0_wp, "CUBSPL(0, iord 1)", error)
        if (allocated(error)) return
        call expect(model, 7, 0.5_wp, 0.75_wp, "AKISPL(0.5)", error)
        if (allocated(error)) return
        call expect(model, 7, -1.0_wp, -3.0_wp, "AKISPL(-1), the end cubic", error)
        if (allocated(error)) return
        call expect(model, 8, -1.0_wp, -2.0_wp, "AKISPL(-1), LINEAR_EXTRAPOLATE", error)
        if (allocated(error)) return
        ! beyond the last point: the tangent there, Akima's slope 2 (the chords 1, -1, 1
        ! and beyond the end 3, 5: weights |5 - 3| and |1 - (-1)|, (2*1 + 2*3)/4)
        call expect(model, 8, 4.0_wp, 3.0_wp, "AKISPL(4), LINEAR_EXTRAPOLATE", error)
        if (allocated(error)) return
        value = evaluate_expression(model%variables(2)%function, 2.0_wp)
        call check(error, abs(value) <= tol_value, "AKISPL of the extended curve at a knot: " &
            & // to_text(value))
    end subroutine test_spline

    !> The value at x of SFORCE/5's FUNCTION (variable 0) or VARIABLE/id's.
    subroutine expect(model, id, x, wanted, what, error)
        type(adm_model_type), intent(in) :: model
        integer, intent(in) :: id
        real(wp), intent(in) :: x, wanted
        character(len=*), intent(in) :: what
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: value
        integer :: v

        if (id == 0) then
            value = evaluate_expression(model%forces(1)%functions(1), x)
        else
            v = findloc(model%variables%id, id, dim=1)
            value = evaluate_expression(model%variables(v)%function, x)
        end if
        call check(error, abs(value - wanted) <= tol_value, what // ": " // to_text(value) &
            & // ", by hand " // to_text(wanted))
    end subroutine expect

    !> A force reading VARVAL(1) = 3 VARVAL(2) + TIME and VARVAL(2) = DX(3)**2: no VARVAL is
    !> left, its value is 3 x^2 + t - 1, and its jet's partials in t and x are 1 and 6 x (and
    !> d2/dx2 = 6), those of the expression it names, exactly.
    subroutine test_varval(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=64) :: lines(size(curves))
        type(adm_model_type) :: model
        type(jet_type) :: value, time, inputs(1)
        real(wp), parameter :: x = 0.7_wp, t = 0.3_wp

        lines = curves
        lines(8) = "SFORCE/5, I=3, J=4, TRANSLATION, FUNCTION=VARVAL(1) - 1"
        lines(9) = "VARIABLE/1, FUNCTION=3*VARVAL(2) + TIME, IC=0"
        lines(10) = "VARIABLE/2, FUNCTION=DX(3)**2"
        lines(11) = "VARIABLE/9, FUNCTION=VARVAL(1)"
        lines(12) = "POUTPUT/3, VARIABLES=1, 2"
        call read_dataset("varval.adm", lines, model, error)
        if (allocated(error)) return
        associate (f => model%forces(1)%functions(1))
            call check(error, size(f%inputs) == 1, "the force reads one measure, DX(3); " &
                & // "it reads " // to_text(size(f%inputs)))
            if (allocated(error)) return
            call check(error, .not. any(f%inputs%quantity == quantity_varval), "a VARVAL left")
            if (allocated(error)) return
            time = jet_variable(t, 1, 2, .true.)
            inputs(1) = jet_variable(x, 2, 2, .true.)
            value = evaluate_expression_jet(f, time, inputs)
            call check(error, abs(value%v - (3.0_wp*x**2 + t - 1.0_wp)) <= tol_value .and. &
                & abs(value%g(1) - 1.0_wp) <= tol_value .and. abs(value%g(2) - 6.0_wp*x) &
                & <= tol_value .and. abs(value%h(2, 2) - 6.0_wp) <= tol_value .and. &
                & all(abs([value%h(1, 1), value%h(1, 2), value%h(2, 1)]) <= tol_value), &
                & "value, partials in t and x, second partials: " // to_text(value%v) // ", " &
                & // to_text(value%g(1)) // ", " // to_text(value%g(2)) // ", " &
                & // to_text(value%h(2, 2)) // "; by hand " &
                & // to_text(3.0_wp*x**2 + t - 1.0_wp) // ", 1, " // to_text(6.0_wp*x) // ", 6")
            if (allocated(error)) return
        end associate
        value = evaluate_expression_jet(model%variables(3)%function, time, inputs)
        call check(error, abs(value%v - (3.0_wp*x**2 + t)) <= tol_value, "VARIABLE/9 reads " &
            & // "VARIABLE/1 through VARIABLE/2: " // to_text(value%v))
    end subroutine test_varval

    !> VARIABLE/1 -> 2 -> 9 -> 1: refused, each statement of the loop named with its line.
    subroutine test_loop(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=64) :: lines(size(curves))
        type(adm_model_type) :: model
        type(error_type), allocatable :: refused
        character(len=*), parameter :: file = "build/rollcon-test/loop.adm"

        lines = curves
        lines(8) = "SFORCE/5, I=3, J=4, TRANSLATION, FUNCTION=VARVAL(2)"
        lines(9) = "VARIABLE/1, FUNCTION=VARVAL(2) + 1"
        lines(10) = "VARIABLE/2, FUNCTION=DX(3) + VARVAL(9)"
        lines(11) = "VARIABLE/9, FUNCTION=2*VARVAL(1)"
        call read_dataset("loop.adm", lines, model, refused)
        call check(error, allocated(refused), "an algebraic loop accepted")
        if (allocated(error)) return
        call check(error, refused%message == file // ":9: VARIABLE/1 reads VARVAL(2); " &
            & // file // ":10: VARIABLE/2 reads VARVAL(9); " // file // ":11: VARIABLE/9 " &
            & // "reads VARVAL(1); an algebraic loop among VARIABLEs, which rollcon does not " &
            & // "solve: write one of them without the others (docs/datasets.md, VARIABLE)", &
            & "got '" // refused%message // "'")
    end subroutine test_loop

    !> PINPUT/1 names VARIABLE/7: the warning names it with its line and VARIABLEs.
    subroutine test_plants(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model

        call read_dataset("curves.adm", curves, model, error)
        if (allocated(error)) return
        call check(error, index(model%warning, "PINPUT/1 (line 12; VARIABLES 7): a controls " &
            & // "plant's inputs and outputs, read and checked; they do nothing in a " &
            & // "stand-alone run") > 0, "warning: '" // model%warning // "'")
    end subroutine test_plants

    !> What cannot be read, each refused with its file, line, statement and why.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: file = "build/rollcon-test/refused.adm"
        character(len=64), parameter :: replaced(11) = [character(len=64) :: &
            & "SPLINE/1, X=0, 1, 1, 3, Y=0, 1, 0, 1", &
            & "SPLINE/1, X=0, 1, 2, Y=0, 1, 0, 1", &
            & "SPLINE/1, X=0, 1, 2, 3, Y=0, 1, 0, 1, Z=1", &
            & "PINPUT/1, VARIABLES=3", &
            & "VARIABLE/7, FUNCTION=ACCX(3)", &
            & "VARIABLE/7, FUNCTION=VARVAL(4)", &
            & "VARIABLE/7, FUNCTION=DX(33)", &
            & "DIFF/7, FUNCTION=-DIF(8), IC=1", &
            & "DIFF/7, FUNCTION=-DIF(7), IC=1, 2, 3", &
            & "VARIABLE/7, FUNCTION=1, ROUTINE=v::VARSUB", &
            & "SPLINE/2, X=0, 1, 2, Y=0, 1, 0"]
        integer, parameter :: at(size(replaced)) = [6, 6, 6, 12, 9, 9, 9, 9, 9, 9, 7]
        character(len=320), parameter :: expected(size(replaced)) = [character(len=320) :: &
            & ":6: SPLINE/1 X: x must increase strictly from point to point, but x3 = 1 " &
            & // "follows x2 = 1", &
            & ":6: SPLINE/1: X gives 3 values and Y 4; a SPLINE's points take one y for " &
            & // "each x", &
            & ":6: SPLINE/1 Z: a SPLINE of a surface (Z= with a Y= list for each z) is not " &
            & // "supported; AKISPL and CUBSPL read curves of X= and Y= alone", &
            & ":12: PINPUT/1 VARIABLES: no VARIABLE/3 in the dataset", &
            & ":9: VARIABLE/7 FUNCTION: ACCX(3): an acceleration, which rollcon knows only " &
            & // "once it has solved for the forces; read in a VARIABLE's FUNCTION (which " &
            & // "gives a force or a constraint) it makes an algebraic loop rollcon does not " &
            & // "solve", &
            & ":9: VARIABLE/7 FUNCTION: VARVAL(4): no VARIABLE/4 in the dataset", &
            & ":9: VARIABLE/7 FUNCTION: DX(33): no MARKER/33 in the dataset", &
            & ":9: DIFF/7 FUNCTION: DIF(8): no DIFF/8 in the dataset", &
            & ":9: DIFF/7 IC: expected one or two numbers (IC=r1[, r2]: the initial DIF and, " &
            & // "for an IMPLICIT DIFF, the first guess of the initial DIF1)", &
            & ":9: VARIABLE/7 ROUTINE: names a VARSUB, which serves a FUNCTION=USER(r1, " &
            & // "..., r30) only", &
            & ":8: SFORCE/5: CUBSPL reads SPLINE/2 (line 7), of 3 points; a cubic spline " &
            & // "needs at least 4"]
        character(len=64) :: lines(size(curves))
        type(adm_model_type) :: model
        type(error_type), allocatable :: refused
        character(len=:), allocatable :: want
        integer :: i, star
        logical :: same

        do i = 1, size(replaced)
            lines = curves
            lines(at(i)) = replaced(i)
            if (i == size(replaced)) lines(8) = "SFORCE/5, I=3, J=4, TRANSLATION, " &
                & // "FUNCTION=CUBSPL(TIME, 0, 2)"
            call read_dataset("refused.adm", lines, model, refused)
            call check(error, allocated(refused), trim(replaced(i)) // ": accepted")
            if (allocated(error)) return
            want = file // trim(expected(i))
            star = index(want, "*")
            if (star == 0) then
                same = refused%message == want
            else
                same = index(refused%message, want(:star - 1)) == 1 .and. &
                    & len(refused%message) >= len(want) - 1
                if (same) same = refused%message(len(refused%message) - (len(want) - star) &
                    & + 1:) == want(star + 1:)
            end if
            call check(error, same, trim(replaced(i)) // ": got '" // refused%message &
                & // "', expected '" // want // "'")
            if (allocated(error)) return
            deallocate(refused)
        end do
    end subroutine test_refusals

end module test_adm_system
