! SPDX-License-Identifier: MIT
!> The integrator a run's settings choose: CVODE for the ODE forms (the ODE form and the
!> independent speeds), IDA for the DAE form.
module rollcon_integrator_choice
    use rollcon_run_settings, only : run_settings_type
    use rollcon_integrator, only : integrator_type
    use rollcon_cvode, only : cvode_integrator_type
    use rollcon_ida, only : ida_integrator_type
    implicit none
    private

    public :: new_integrator

contains

    !> A new integrator of the settings' formulation (not yet started).
    subroutine new_integrator(settings, integrator)
        type(run_settings_type), intent(in) :: settings
        class(integrator_type), allocatable, intent(out) :: integrator

        if (settings%uses_cvode()) then
            allocate(cvode_integrator_type :: integrator)
        else
            allocate(ida_integrator_type :: integrator)
        end if
    end subroutine new_integrator

end module rollcon_integrator_choice
