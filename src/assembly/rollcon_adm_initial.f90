! SPDX-License-Identifier: MIT
!> The initial-conditions analysis of a dataset (docs/initial-conditions.md): the options of its
!> problem with every part's EXACT coordinates held and its given velocities kept.
module rollcon_adm_initial
    use rollcon_kinds, only : wp
    use rollcon_rebasing, only : basis_axes
    use rollcon_problem, only : problem_type
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of
    use rollcon_adm_model, only : adm_model_type
    implicit none
    private

    public :: adm_ic_options

contains

    !> The run's tolerances, the coordinates marked EXACT and the velocities given, in the
    !> problem's numbering (the non-ground parts in dataset order, as build_adm_problem adds
    !> them). As in ADAMS, a velocity the dataset gives (VX, VY, VZ; WX, WY, WZ about the CM
    !> marker's axes) is kept unless the UCONs cannot be met with it, and one it leaves out is
    !> an "inexact" zero, free to move: the analysis holds the given ones
    !> (ic_options_type's given_velocity, with the CM marker's axes in the principal axes the
    !> model holds the part in: its principal axes, turned to the basis it starts in,
    !> problem%start_bases).
    pure function adm_ic_options(adm, problem) result(options)
        type(adm_model_type), intent(in) :: adm
        type(problem_type), intent(in) :: problem
        type(ic_options_type) :: options
        real(wp) :: axes(3, 3)
        integer :: i, p

        options = ic_options_of(problem)
        allocate(options%given_velocity(6, size(problem%model%parts)), source=.false.)
        allocate(options%given_axes(3, 3, size(problem%model%parts)), source=0.0_wp)
        p = 0
        do i = 1, size(adm%parts)
            if (adm%parts(i)%ground) cycle
            p = p + 1
            options%exact_q(6*p - 5:6*p) = adm%parts(i)%exact
            options%given_velocity(1:3, p) = adm%parts(i)%velocity_given
            options%given_velocity(4:6, p) = adm%parts(i)%angular_velocity_given
            ! omega in the CM marker's axes = principal omega_0 = principal T omega_1
            axes = adm%parts(i)%principal
            axes = matmul(axes, basis_axes(problem%start_bases(p)))
            options%given_axes(:, :, p) = axes
        end do
    end function adm_ic_options

end module rollcon_adm_initial
