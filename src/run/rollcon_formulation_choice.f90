! SPDX-License-Identifier: MIT
!> The formulation a problem's settings choose, made once where a run starts its integrator
!> (rollcon_simulation): the ODE form (rollcon_ode_form, 'cvode'), the DAE form
!> (rollcon_dae_form, 'ida') or the independent speeds (rollcon_speeds_form, 'maggi'), each a
!> dynamic system whose type says which integrator takes it (rollcon_integrator_choice). Nothing
!> else in a run asks which formulation it has.
module rollcon_formulation_choice
    use rollcon_run_settings, only : formulation_cvode, formulation_speeds
    use rollcon_dynamic_system, only : dynamic_system_type
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_dae_form, only : dae_form_type
    use rollcon_speeds_form, only : speeds_form_type
    implicit none
    private

    public :: new_formulation

contains

    !> The formulation of problem%settings%formulation on problem (prepared: rollcon_problem's
    !> prepare), which must outlive it.
    subroutine new_formulation(problem, system)
        type(problem_type), intent(inout), target :: problem
        class(dynamic_system_type), allocatable, intent(out) :: system
        type(ode_form_type), allocatable :: ode
        type(dae_form_type), allocatable :: dae
        type(speeds_form_type), allocatable :: speeds

        select case (problem%settings%formulation)
        case (formulation_cvode)
            allocate(ode)
            call ode%init(problem)
            call move_alloc(ode, system)
        case (formulation_speeds)
            allocate(speeds)
            call speeds%init(problem)
            call move_alloc(speeds, system)
        case default
            ! formulation_ida, the default
            allocate(dae)
            call dae%init(problem)
            call move_alloc(dae, system)
        end select
    end subroutine new_formulation

end module rollcon_formulation_choice
