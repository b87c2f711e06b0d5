! SPDX-License-Identifier: MIT
!> The checks the generated modules share (rollcon_ucosub_helpers), on the cases no spec of
!> ucon/specs/ reaches: a single code, two components, a parameter that need only be finite,
!> and the edges of the part-id and selector checks.
!>
!> Not a suite: test_generated collects these tests.
module generated_helpers
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_helpers, only : selectors_valid, is_whole, read_par_head, &
        & check_parameter, read_component
    use rollcon_testing, only : check
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_positive_inf
    implicit none
    private

    public :: test_helper_messages, test_helper_edges

contains

    !> Each check's message, word for word, and silence when PAR is right.
    subroutine test_helper_messages(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: message
        integer :: part, component

        call read_par_head([3.0_wp, 13.0_wp], 2, 2, [13], "one needs NPAR >= 2, got NPAR =", &
            & part, message)
        call check(error, .not. allocated(message) .and. part == 3, "a right PAR is refused")
        if (allocated(error)) return
        call read_par_head([3.0_wp, 13.0_wp], 1, 2, [13], "one needs NPAR >= 2, got NPAR =", &
            & part, message)
        call expect(error, message, "one needs NPAR >= 2, got NPAR = 1")
        if (allocated(error)) return
        call read_par_head([3.0_wp, 14.0_wp], 2, 2, [13], "unused", part, message)
        call expect(error, message, "PAR(2) must be code 13 (codes 13 in PAR(2)), got 14")
        if (allocated(error)) return
        call read_par_head([3.0_wp, 21.0_wp, 21.0_wp], 3, 3, [21, 22], "unused", part, message)
        call expect(error, message, "PAR(3) must be code 22 (codes 21 22 in PAR(2:3)), got 21")
        if (allocated(error)) return
        call read_par_head([0.0_wp, 13.0_wp], 2, 2, [13], "unused", part, message)
        call expect(error, message, "PAR(1) (part id) must be a positive whole number, got 0")
        if (allocated(error)) return
        call check(error, part == 0, "part set from a bad PAR(1)")
        if (allocated(error)) return
        call check_parameter([1.0_wp, -2.5_wp], 2, "offset a [m]", .false., message)
        call check(error, .not. allocated(message), "a finite negative offset is refused")
        if (allocated(error)) return
        call check_parameter([1.0_wp, -2.5_wp], 2, "radius R [m]", .true., message)
        call expect(error, message, "PAR(2) (radius R [m]) must be positive and finite, got -2.5")
        if (allocated(error)) return
        call check_parameter([ieee_value(1.0_wp, ieee_positive_inf)], 1, "offset a [m]", &
            & .false., message)
        call check(error, allocated(message), "an infinite offset is accepted")
        if (allocated(error)) return
        call check(error, index(message, "PAR(1) (offset a [m]) must be finite, got ") == 1, &
            & "message '" // message // "'")
        if (allocated(error)) return
        call read_component([2.0_wp], 1, 2, "wheel", component, message)
        call check(error, .not. allocated(message) .and. component == 2, &
            & "component 2 of 2 is refused")
        if (allocated(error)) return
        call read_component([3.0_wp], 1, 2, "wheel", component, message)
        call expect(error, message, "PAR(1) (wheel) must be 1 or 2, got 3")
        if (allocated(error)) return
        call check(error, component == 0, "component set from a bad PAR")
        if (allocated(error)) return
        call read_component([0.5_wp], 1, 4, "leg", component, message)
        call expect(error, message, "PAR(1) (leg) must be 1, 2, 3 or 4, got 0.5")
    end subroutine test_helper_messages

    !> is_whole and selectors_valid at their edges.
    subroutine test_helper_edges(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: nan, inf

        nan = ieee_value(1.0_wp, ieee_quiet_nan)
        inf = ieee_value(1.0_wp, ieee_positive_inf)
        call check(error, all(is_whole([1.0_wp, -7.0_wp, 0.0_wp, real(huge(1) - 1, wp)])), &
            & "a whole number is not whole")
        if (allocated(error)) return
        call check(error, .not. any(is_whole([0.5_wp, nan, inf, -inf, real(huge(1), wp), &
            & 1.0e30_wp])), "a fraction, a non-finite or an out-of-range value is whole")
        if (allocated(error)) return
        call check(error, selectors_valid([0, 0, 0]) .and. selectors_valid([4, 2, 1]), &
            & "a selector at the edge of the table is refused")
        if (allocated(error)) return
        call check(error, .not. (selectors_valid([5, 0, 0]) .or. selectors_valid([0, 3, 0]) &
            & .or. selectors_valid([0, 0, 2]) .or. selectors_valid([-1, 0, 0]) &
            & .or. selectors_valid([0, -1, 0]) .or. selectors_valid([0, 0, -1])), &
            & "a selector outside the table is accepted")
    end subroutine test_helper_edges

    !> The message is allocated and equals expected.
    subroutine expect(error, message, expected)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable, intent(in) :: message
        character(len=*), intent(in) :: expected

        if (.not. allocated(message)) then
            call check(error, .false., "no message; expected '" // expected // "'")
            return
        end if
        call check(error, message == expected, "message '" // message // "', expected '" &
            & // expected // "'")
    end subroutine expect

end module generated_helpers
