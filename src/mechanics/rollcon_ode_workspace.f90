! SPDX-License-Identifier: MIT
!> Scratch arrays of the ODE form's evaluations (right-hand side, Jacobian, projection), sized
!> once so that no evaluation allocates (automatic arrays would be allocated on the heap at
!> every call). The equations own one; nothing outside the mechanics layer reads it.
module rollcon_ode_workspace
    use rollcon_kinds, only : wp
    use rollcon_momentum_partials, only : momentum_partials_type
    implicit none
    private

    public :: ode_workspace_type

    !> Work arrays of one set of equations
    type :: ode_workspace_type
        !> Applied moment about each part's centre, ground components [N m] (3, parts)
        real(wp), allocatable :: moments(:, :)
        !> The rows the position projection solves (nc): the active position UCONs' (the
        !> others are set aside in its factorisation of C)
        logical, allocatable :: projection_rows(:)
        !> Right-hand sides of the Jacobian's and the projection's solves: momentum rows (n, 2n)
        !> and constraint rows (nc, 2n) for the Jacobian, one column of each for the projection
        !> (sized by the ODE forms' init, size_ode_form, else by a first use: IDA's runs form
        !> no ODE Jacobian)
        real(wp), allocatable :: rhs_top(:, :), rhs_bottom(:, :)
        !> Jacobian blocks of the momentum rows d(M a - f - C^T lambda)/d(q, u), dm/dq and
        !> dm/du, on the pairs of parts the elements join (rollcon_momentum_partials: memory
        !> linear in the model, no n x n array)
        type(momentum_partials_type) :: dm
        !> d(M a - f)/da: the mass matrix's part of it left out, the partials of the forces
        !> whose user routines read accelerations (rollcon_equations' algebraic loop; allocated
        !> by its first evaluation, none where no routine reads accelerations); and the LU
        !> factors (with pivots) of that loop's saddle-point matrix, (n + nc) square
        real(wp), allocatable :: dm_da(:, :), loop_matrix(:, :)
        integer, allocatable :: loop_pivots(:)
        !> The loop's last accelerations and multipliers, where its next solve starts
        !> (allocated by it)
        real(wp), allocatable :: loop_a(:), loop_lambda(:)
        !> d(M a - f)/dlambda (n x nc): the partials of the forces whose user routines read a
        !> constraint's reaction (SYSFNC's force measures) in its multipliers (allocated by the
        !> loop, or the DAE's Newton matrix, when a routine reads them)
        real(wp), allocatable :: dm_dlambda(:, :)
        !> Accelerations, multipliers, projected coordinates
        real(wp), allocatable :: a(:), lambda(:), q(:)
        !> The ODE form's Jacobian block by block (rollcon_equations' ode_jacobian_blocks, CVODE's
        !> sparse Newton matrix), in place of rhs_top and rhs_bottom: one block's right-hand
        !> sides, momentum rows (its most coordinates x twice those) and constraint rows (its
        !> most UCONs x the same), sized by a first use to the largest block (memory linear in
        !> the model where the blocks are bounded, docs/design.md §4 "Memory")
        real(wp), allocatable :: block_top(:, :), block_bottom(:, :)
        !> Each coordinate's constraints' block (0: a part no UCON holds), its row in its
        !> block's right-hand sides, and the block it was last placed in (its first
        !> coordinate); one block's coordinates, and its constraints' blocks (n, n, n, n,
        !> blocks: allocated by a first use)
        integer, allocatable :: coordinate_block(:), block_place(:), block_mark(:), &
            & block_coordinates(:), block_list(:)
        logical, allocatable :: block_seen(:)
    contains
        procedure :: init
        procedure :: size_right_hand_sides
        procedure :: size_ode_form
    end type ode_workspace_type

contains

    !> Size the arrays for n coordinates, nc constraints of which nh are position UCONs, and
    !> the given number of parts, dm/dq and dm/du on every part and the pairs of parts given
    !> (2 x m: those a force element or a UCON joins).
    subroutine init(self, n, nc, nh, parts, pairs)
        class(ode_workspace_type), intent(out) :: self
        integer, intent(in) :: n, nc, nh, parts
        integer, intent(in) :: pairs(:, :)

        allocate(self%moments(3, parts), source=0.0_wp)
        call self%dm%init_blocks(parts, pairs)
        allocate(self%a(n), self%lambda(nc), self%q(n), source=0.0_wp)
        allocate(self%projection_rows(nc), source=.false.)
    end subroutine init

    !> The arrays of the ODE form's Jacobian and projection (CVODE's forms, which form them at
    !> every step; IDA's, which does not, leaves them to a first use): with `jacobian` the
    !> right-hand sides' 2 n columns of the dense Jacobian (ode_jacobian; else they are sized
    !> by a first use, the projection's one column, and the sparse one, ode_jacobian_blocks,
    !> never holds them). Once, before a run.
    subroutine size_ode_form(self, n, nc, jacobian)
        class(ode_workspace_type), intent(inout) :: self
        integer, intent(in) :: n, nc
        logical, intent(in) :: jacobian

        if (jacobian) call self%size_right_hand_sides(n, nc, 2*n)
    end subroutine size_ode_form

    !> rhs_top (n x columns) and rhs_bottom (nc x columns), zero, unless they hold as many
    !> columns already: the Jacobian's 2 n, or the projection's 1. Allocates on a first use
    !> only (and once more where a run projects before it forms an ODE Jacobian).
    subroutine size_right_hand_sides(self, n, nc, columns)
        class(ode_workspace_type), intent(inout) :: self
        integer, intent(in) :: n, nc, columns

        if (allocated(self%rhs_top)) then
            if (size(self%rhs_top, 2) >= columns) return
            deallocate(self%rhs_top, self%rhs_bottom)
        end if
        allocate(self%rhs_top(n, columns), self%rhs_bottom(nc, columns), source=0.0_wp)
    end subroutine size_right_hand_sides

end module rollcon_ode_workspace
