! SPDX-License-Identifier: MIT
!> Calls a UCOSUB the way ADAMS does, and turns what it reports into an error_type.
module rollcon_ucon_call
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, ucon_error
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface, iflag_init, iflag_eval, max_ucon_vars, &
        & max_ucon_par
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_adams_runtime, only : begin_declaration, end_declaration, take_ucon_error, &
        & has_ucon_error
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: declare_ucon, evaluate_ucon, stat_non_finite

    !> error%stat of evaluate_ucon when a selected output is NaN or Infinity: a UCOSUB error of
    !> its own kind, so a checker tells it from an ERRMES call by the code, not the message
    integer, parameter :: stat_non_finite = 51

contains

    !> Make the initialisation call (IFLAG = 3) of UCON id and record its UCOVAR declaration.
    subroutine declare_ucon(ucosub, id, par, registry, error)
        !> The user-written constraint
        procedure(ucosub_interface) :: ucosub
        !> UCON statement id
        integer, intent(in) :: id
        !> Constants of the UCON statement (size = NPAR)
        real(wp), intent(in) :: par(:)
        !> Registry receiving the declaration
        type(ucovar_registry_type), target, intent(inout) :: registry
        !> Set when the routine declared nothing, declared wrongly, or reported an error
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: q(max_ucon_vars), array(max_ucon_vars), xmatrx(max_ucon_vars, max_ucon_vars)
        real(wp) :: scalar, par_copy(max_ucon_par)

        if (size(par) > max_ucon_par) then
            call ucon_error(error, id, "FUNCTION=USER has " // to_text(size(par)) &
                & // " constants; at most " // to_text(max_ucon_par) // " allowed")
            return
        end if
        q = 0.0_wp
        scalar = 0.0_wp
        array = 0.0_wp
        xmatrx = 0.0_wp
        par_copy = 0.0_wp
        par_copy(:size(par)) = par
        call begin_declaration(registry, id)
        call ucosub(id, 0.0_wp, q, par_copy, size(par), [0, 0, 0], iflag_init, scalar, array, &
            & xmatrx)
        call end_declaration(error)
    end subroutine declare_ucon

    !> Make one evaluation call (IFLAG = 0). The selected outputs are zeroed first over the
    !> nvars declared variables, since a UCOSUB may leave symbolically zero entries untouched;
    !> what was selected must come back finite. Entries past nvars, and outputs not selected,
    !> are neither zeroed nor read (the hot path of every integrator evaluation).
    subroutine evaluate_ucon(ucosub, id, time, q, par, idrsel, scalar, array, xmatrx, error, nvars)
        !> The user-written constraint
        procedure(ucosub_interface) :: ucosub
        !> UCON statement id
        integer, intent(in) :: id
        !> Simulation time [s]
        real(wp), intent(in) :: time
        !> Values of the declared variables (30 entries, as ADAMS passes them)
        real(wp), intent(in) :: q(max_ucon_vars)
        !> Constants of the UCON statement (padded to 30 entries)
        real(wp), intent(in) :: par(:)
        !> Output selectors
        integer, intent(in) :: idrsel(3)
        !> Selected scalar
        real(wp), intent(inout) :: scalar
        !> Selected first partials
        real(wp), intent(inout) :: array(max_ucon_vars)
        !> Selected second partials
        real(wp), intent(inout) :: xmatrx(max_ucon_vars, max_ucon_vars)
        !> Set when the routine reported an error or returned a non-finite value
        type(error_type), allocatable, intent(out) :: error
        !> Number of declared variables (default 30: everything is zeroed and checked)
        integer, intent(in), optional :: nvars
        integer :: n
        logical :: finite

        n = max_ucon_vars
        if (present(nvars)) n = nvars
        if (idrsel(1) /= 0) scalar = 0.0_wp
        if (idrsel(2) /= 0) array(:n) = 0.0_wp
        if (idrsel(3) /= 0) xmatrx(:n, :n) = 0.0_wp
        call ucosub(id, time, q, par, size(par), idrsel, iflag_eval, scalar, array, xmatrx)
        if (has_ucon_error()) then
            call take_ucon_error(error)
            return
        end if
        finite = .true.
        if (idrsel(1) /= 0) finite = ieee_is_finite(scalar)
        ! the sum is finite only when every entry is (all_finite's reasoning); else one by one
        if (idrsel(2) /= 0 .and. finite) then
            finite = ieee_is_finite(sum(array(:n)))
            if (.not. finite) finite = all(ieee_is_finite(array(:n)))
        end if
        if (idrsel(3) /= 0 .and. finite) finite = all_finite(xmatrx, n)
        if (.not. finite) then
            call ucon_error(error, id, "UCOSUB returned a non-finite value at time " &
                & // to_text(time) // " with IDRSEL = (" // to_text(idrsel(1)) // ", " &
                & // to_text(idrsel(2)) // ", " // to_text(idrsel(3)) // ")")
            error%stat = stat_non_finite
        end if
    end subroutine evaluate_ucon

    !> True when every entry of x(:n, :n) is finite: all(ieee_is_finite(x(:n, :n))), its
    !> verdict reached more cheaply (it runs at every evaluation that asks for XMATRX). The
    !> sum of the entries, taken as column sums of each row, is finite only when every entry
    !> is (an Infinity or a NaN among the terms leaves every partial sum it enters non-finite);
    !> when it is not (a non-finite entry, or finite ones whose sum overflows) the entries are
    !> tested one by one.
    pure function all_finite(x, n) result(finite)
        real(wp), intent(in) :: x(max_ucon_vars, max_ucon_vars)
        !> Order of the block tested
        integer, intent(in) :: n
        logical :: finite
        real(wp) :: rows(max_ucon_vars)
        integer :: j

        if (n < 2) then
            finite = .true.
            if (n == 1) finite = ieee_is_finite(x(1, 1))
            return
        end if
        rows(:n) = x(:n, 1) + x(:n, 2)
        do j = 3, n
            rows(:n) = rows(:n) + x(:n, j)
        end do
        finite = ieee_is_finite(sum(rows(:n)))
        if (.not. finite) finite = all(ieee_is_finite(x(:n, :n)))
    end function all_finite

end module rollcon_ucon_call
