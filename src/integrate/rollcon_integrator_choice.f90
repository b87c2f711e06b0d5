! SPDX-License-Identifier: MIT
!> The integrator a system's form takes, set up on it: CVODE on an ODE system (the ODE form and
!> the independent speeds), IDA on a DAE system (the DAE form). The formulation itself is
!> chosen once, where the run makes its system (rollcon_formulation_choice); the integrator
!> follows from the type of that system.
module rollcon_integrator_choice
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_solver
    use rollcon_run_settings, only : run_settings_type
    use rollcon_dynamic_system, only : dynamic_system_type, ode_system_type, dae_system_type
    use rollcon_integrator, only : integrator_type
    use rollcon_cvode, only : cvode_integrator_type
    use rollcon_ida, only : ida_integrator_type
    implicit none
    private

    public :: start_integrator

contains

    !> A new integrator of the system's form set up on it from (t0, y0, yp0), every setting from
    !> settings, watching the system's event functions, never stepping past t_stop. The
    !> integrator is allocated even when its start fails (its destroy frees what it made).
    subroutine start_integrator(system, settings, t0, y0, yp0, t_stop, integrator, error)
        class(dynamic_system_type), intent(inout), target :: system
        type(run_settings_type), intent(in) :: settings
        !> Start time [s], state and its derivative there, stop time [s]
        real(wp), intent(in) :: t0, y0(:), yp0(:), t_stop
        class(integrator_type), allocatable, intent(out), target :: integrator
        type(error_type), allocatable, intent(out) :: error
        type(cvode_integrator_type), allocatable, target :: cvode
        type(ida_integrator_type), allocatable, target :: ida

        ! the integrator keeps pointers to its own parts and to the system: move_alloc moves
        ! it to a target without copying, so they stay associated
        select type (system)
        class is (ode_system_type)
            allocate(cvode)
            call cvode%start(system, settings, t0, y0, yp0, t_stop, error)
            call move_alloc(cvode, integrator)
        class is (dae_system_type)
            allocate(ida)
            call ida%start(system, settings, t0, y0, yp0, t_stop, error)
            call move_alloc(ida, integrator)
        class default
            ! every system rollcon makes is one of the two: an error only for a new kind
            call fatal_error(error, "no integrator takes a system that is neither an ODE " &
                & // "(ode_system_type) nor a DAE (dae_system_type)", stat_solver)
        end select
    end subroutine start_integrator

end module rollcon_integrator_choice
