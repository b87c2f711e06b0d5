! SPDX-License-Identifier: MIT
!> The checks every generated UCOSUB module shares: PAR, IDRSEL and the texts of their errors.
!>
!> Written once, by hand, and used by each src/ucosubs/generated/rollcon_gen_<spec>.f90, which
!> keeps only what is specific to its constraint (its PAR layout, its messages' words, its
!> expressions). Nothing here depends on a spec, so generating it would add nothing. The
!> fixed-form ucon/adams/<spec>/ucosub.f files do not use it: they must compile alone for ADAMS.
!> The texts are those of ucon/messages.py, which prints the same messages into ucosub.f
!> (ucon/tests checks that the two agree).
module rollcon_ucosub_helpers
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : scalar_none, scalar_dtt, array_none, array_dtdq, &
        & xmatrx_none, xmatrx_dqdq
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: selectors_valid, is_whole, read_par_head, check_parameter, read_component
    public :: read_second_part
    public :: idrsel_message, iflag_message, part_message
    ! public so that they stay out of line: inlined in the checks of every call, their text
    ! work made each check save and restore registers even when PAR is right. Their message
    ! is intent(inout), not intent(out): the check's own intent(out) has deallocated it, and
    ! a second deallocation in the check would cost the same saves
    public :: par_head_message, second_part_message, parameter_message, component_message

    !> Message of a call with an IDRSEL outside the table of docs/design.md §2
    character(len=*), parameter :: idrsel_message = "IDRSEL must be (0..4, 0..2, 0..1)"
    !> Message of a call with an IFLAG other than 3 or 0
    character(len=*), parameter :: iflag_message = "IFLAG must be 3 (initialise) or 0 (evaluate)"
    !> Start of the message of a bad part id; the value found follows
    character(len=*), parameter :: part_message = &
        & "PAR(1) (part id) must be a positive whole number, got"

contains

    !> True when every selector is one the contract defines.
    pure function selectors_valid(idrsel) result(valid)
        !> Output selectors
        integer, intent(in) :: idrsel(3)
        logical :: valid

        valid = idrsel(1) >= scalar_none .and. idrsel(1) <= scalar_dtt &
            & .and. idrsel(2) >= array_none .and. idrsel(2) <= array_dtdq &
            & .and. idrsel(3) >= xmatrx_none .and. idrsel(3) <= xmatrx_dqdq
    end function selectors_valid

    !> True for a finite real with no fractional part, small enough for a default integer.
    elemental function is_whole(value) result(whole)
        !> Value to test
        real(wp), intent(in) :: value
        logical :: whole

        whole = whole_number(value)
    end function is_whole

    !> is_whole of one value, for the checks of this module to inline.
    pure function whole_number(value) result(whole)
        real(wp), intent(in) :: value
        logical :: whole

        whole = ieee_is_finite(value)
        ! below huge(1) in magnitude, int truncates as aint does, and exactly (no library call)
        if (whole) whole = abs(value) < real(huge(1), wp)
        if (whole) whole = value == real(int(value), wp)
    end function whole_number

    !> Check the part of PAR every spec shares: NPAR, the part id in PAR(1), the codes in
    !> PAR(2:m+1). message is allocated, and says what was expected, when one is wrong.
    pure subroutine read_par_head(par, npar, npar_needed, codes, npar_text, part, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> Number of constants
        integer, intent(in) :: npar
        !> Number of constants the spec needs
        integer, intent(in) :: npar_needed
        !> Codes the spec declares, in UCOVAR order (PAR(2:) must hold them)
        integer, contiguous, intent(in) :: codes(:)
        !> Start of the message of a short PAR (what NPAR must be and why); NPAR follows
        character(len=*), intent(in) :: npar_text
        !> Part id of every variable; 0 when PAR(1) is not one
        integer, intent(out) :: part
        !> Allocated when PAR is wrong
        character(len=:), allocatable, intent(out) :: message
        integer :: i

        ! every generated UCOSUB's every call: PAR as it should be settles it here, and only
        ! a wrong one goes on to par_head_message (part and message as it sets them)
        if (npar >= npar_needed) then
            if (whole_number(par(1))) then
                if (par(1) >= 1.0_wp) then
                    do i = 1, size(codes)
                        if (par(1 + i) /= real(codes(i), wp)) exit
                    end do
                    if (i > size(codes)) then
                        ! PAR(1) is whole: int is nint
                        part = int(par(1))
                        return
                    end if
                end if
            end if
        end if
        call par_head_message(par, npar, npar_needed, codes, npar_text, part, message)
    end subroutine read_par_head

    !> read_par_head's answer for a PAR that fails one of its checks: part as far as the
    !> checks got, message saying what was expected.
    pure subroutine par_head_message(par, npar, npar_needed, codes, npar_text, part, message)
        !> Constants of the UCON statement, NPAR of them, the spec needing npar_needed
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar, npar_needed
        !> Codes the spec declares, in UCOVAR order
        integer, intent(in) :: codes(:)
        !> Start of the message of a short PAR; NPAR follows
        character(len=*), intent(in) :: npar_text
        !> Part id: PAR(1) once it is one, else 0
        integer, intent(out) :: part
        !> What was expected (allocated unless PAR passes every check; unallocated on entry)
        character(len=:), allocatable, intent(inout) :: message
        integer :: i

        part = 0
        if (npar < npar_needed) then
            message = npar_text // " " // to_text(npar)
            return
        end if
        if (.not. is_whole(par(1)) .or. par(1) < 1.0_wp) then
            message = part_message // " " // to_text(par(1))
            return
        end if
        part = nint(par(1))
        do i = 1, size(codes)
            if (par(1 + i) /= real(codes(i), wp)) then
                message = "PAR(" // to_text(1 + i) // ") must be code " // to_text(codes(i)) &
                    & // " (codes " // codes_text(codes) // " in " // codes_range(size(codes)) &
                    & // "), got " // to_text(par(1 + i))
                return
            end if
        end do
    end subroutine par_head_message

    !> Check the head of a two-part spec's second part (ucon/spec.py): its part id at
    !> PAR(index), a positive whole number other than the first part's, and its codes in
    !> PAR(index + 1:). message is allocated, and says what was expected, when one is wrong.
    pure subroutine read_second_part(par, index, codes, part, part_j, message)
        !> Constants of the UCON statement (NPAR already checked by read_par_head)
        real(wp), intent(in) :: par(*)
        !> PAR index of the second part's id
        integer, intent(in) :: index
        !> Codes of the second part's variables, in UCOVAR order
        integer, contiguous, intent(in) :: codes(:)
        !> The first part's id (PAR(1))
        integer, intent(in) :: part
        !> The second part's id; 0 when PAR(index) is not one
        integer, intent(out) :: part_j
        !> Allocated when PAR is wrong
        character(len=:), allocatable, intent(out) :: message
        integer :: i

        ! at every call of a two-part routine (a joint's): as read_par_head, a right PAR
        ! settles it here, a wrong one goes on to second_part_message
        if (whole_number(par(index))) then
            if (par(index) >= 1.0_wp .and. par(index) /= real(part, wp)) then
                do i = 1, size(codes)
                    if (par(index + i) /= real(codes(i), wp)) exit
                end do
                if (i > size(codes)) then
                    ! PAR(index) is whole: int is nint
                    part_j = int(par(index))
                    return
                end if
            end if
        end if
        call second_part_message(par, index, codes, part, part_j, message)
    end subroutine read_second_part

    !> read_second_part's answer for a PAR that fails one of its checks: part_j as far as the
    !> checks got, message saying what was expected.
    pure subroutine second_part_message(par, index, codes, part, part_j, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> PAR index of the second part's id
        integer, intent(in) :: index
        !> Codes of the second part's variables, in UCOVAR order
        integer, intent(in) :: codes(:)
        !> The first part's id (PAR(1))
        integer, intent(in) :: part
        !> The second part's id: PAR(index) once it is one, else 0
        integer, intent(out) :: part_j
        !> What was expected (allocated unless PAR passes every check; unallocated on entry)
        character(len=:), allocatable, intent(inout) :: message
        character(len=:), allocatable :: range
        integer :: i

        part_j = 0
        if (.not. is_whole(par(index)) .or. par(index) < 1.0_wp &
            & .or. par(index) == real(part, wp)) then
            message = "PAR(" // to_text(index) // ") (second part id) must be a positive " &
                & // "whole number other than PAR(1), got " // to_text(par(index))
            return
        end if
        part_j = nint(par(index))
        do i = 1, size(codes)
            if (par(index + i) /= real(codes(i), wp)) then
                ! the message's text only when it is needed (building it at every call of a
                ! joint's routine cost a quarter of a chain's run: docs/benchmark.md "Cost as
                ! models grow")
                range = "PAR(" // to_text(index + 1) // ")"
                if (size(codes) > 1) range = "PAR(" // to_text(index + 1) // ":" &
                    & // to_text(index + size(codes)) // ")"
                message = "PAR(" // to_text(index + i) // ") must be code " &
                    & // to_text(codes(i)) // " (codes " // codes_text(codes) // " in " &
                    & // range // "), got " // to_text(par(index + i))
                return
            end if
        end do
    end subroutine second_part_message

    !> Check one physical parameter: finite, and positive when asked.
    pure subroutine check_parameter(par, index, description, positive, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> PAR index of the parameter
        integer, intent(in) :: index
        !> Its meaning with units, e.g. "disk radius R [m]"
        character(len=*), intent(in) :: description
        !> True when it must be > 0 as well as finite
        logical, intent(in) :: positive
        !> Allocated when the value fails the check
        character(len=:), allocatable, intent(out) :: message

        ! a good value returns at once; the message is made apart (parameter_message), so the
        ! check is all the call costs
        if (ieee_is_finite(par(index))) then
            if (.not. positive) return
            if (par(index) > 0.0_wp) return
        end if
        call parameter_message(par, index, description, positive, message)
    end subroutine check_parameter

    !> check_parameter's message for a value that fails its check.
    pure subroutine parameter_message(par, index, description, positive, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> PAR index of the parameter
        integer, intent(in) :: index
        !> Its meaning with units
        character(len=*), intent(in) :: description
        !> True when it must be > 0 as well as finite
        logical, intent(in) :: positive
        !> What was expected, and the value found (unallocated on entry)
        character(len=:), allocatable, intent(inout) :: message

        if (positive) then
            message = "positive and finite"
        else
            message = "finite"
        end if
        message = "PAR(" // to_text(index) // ") (" // description // ") must be " // message &
            & // ", got " // to_text(par(index))
    end subroutine parameter_message

    !> Read the component number of a spec with several components: 1, 2, ... ncomponents.
    pure subroutine read_component(par, index, ncomponents, meaning, component, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> PAR index of the component number
        integer, intent(in) :: index
        !> Number of components
        integer, intent(in) :: ncomponents
        !> What the number selects, e.g. "no-slip component"
        character(len=*), intent(in) :: meaning
        !> The component; 0 when PAR(index) is not one
        integer, intent(out) :: component
        !> Allocated when PAR(index) is not a component number
        character(len=:), allocatable, intent(out) :: message
        integer :: k

        component = 0
        do k = 1, ncomponents
            if (par(index) == real(k, wp)) component = k
        end do
        if (component > 0) return
        call component_message(par, index, ncomponents, meaning, message)
    end subroutine read_component

    !> read_component's message for a PAR(index) that is not a component number (made apart,
    !> so a good one costs only its comparisons).
    pure subroutine component_message(par, index, ncomponents, meaning, message)
        !> Constants of the UCON statement
        real(wp), intent(in) :: par(*)
        !> PAR index of the component number, and the number of components
        integer, intent(in) :: index, ncomponents
        !> What the number selects
        character(len=*), intent(in) :: meaning
        !> What was expected, and the value found (unallocated on entry)
        character(len=:), allocatable, intent(inout) :: message

        message = "PAR(" // to_text(index) // ") (" // meaning // ") must be " &
            & // choices_text(ncomponents) // ", got " // to_text(par(index))
    end subroutine component_message

    !> "13 15" for the codes [13, 15].
    pure function codes_text(codes) result(text)
        !> Codes
        integer, intent(in) :: codes(:)
        character(len=:), allocatable :: text
        integer :: i

        text = to_text(codes(1))
        do i = 2, size(codes)
            text = text // " " // to_text(codes(i))
        end do
    end function codes_text

    !> "PAR(2:9)" for eight codes, "PAR(2)" for one.
    pure function codes_range(count) result(text)
        !> Number of codes
        integer, intent(in) :: count
        character(len=:), allocatable :: text

        if (count == 1) then
            text = "PAR(2)"
        else
            text = "PAR(2:" // to_text(1 + count) // ")"
        end if
    end function codes_range

    !> "1, 2 or 3" for three components, "1 or 2" for two.
    pure function choices_text(count) result(text)
        !> Number of components
        integer, intent(in) :: count
        character(len=:), allocatable :: text
        integer :: k

        text = "1"
        do k = 2, count - 1
            text = text // ", " // to_text(k)
        end do
        if (count > 1) text = text // " or " // to_text(count)
    end function choices_text

end module rollcon_ucosub_helpers
