! SPDX-License-Identifier: MIT
!> The initial-conditions analysis of a dataset (docs/initial-conditions.md): the options of its
!> problem with every part's EXACT coordinates held.
module rollcon_adm_initial
    use rollcon_problem, only : problem_type
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of
    use rollcon_adm_model, only : adm_model_type
    implicit none
    private

    public :: adm_ic_options

contains

    !> The run's tolerances and the coordinates marked EXACT, in the problem's numbering (the
    !> non-ground parts in dataset order, as build_adm_problem adds them). Rates are never held:
    !> VX ... WZ are initial values the analysis may change, as in ADAMS.
    pure function adm_ic_options(adm, problem) result(options)
        type(adm_model_type), intent(in) :: adm
        type(problem_type), intent(in) :: problem
        type(ic_options_type) :: options
        integer :: i, p

        options = ic_options_of(problem)
        p = 0
        do i = 1, size(adm%parts)
            if (adm%parts(i)%ground) cycle
            p = p + 1
            options%exact_q(6*p - 5:6*p) = adm%parts(i)%exact
        end do
    end function adm_ic_options

end module rollcon_adm_initial
