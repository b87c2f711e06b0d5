! SPDX-License-Identifier: MIT
!> A disk scene solved by the reduced ODE (rollcon_reduced_cvode): the benchmark's independent
!> reference and its limit. Same disk, start, strike, output times and theta limit as the full
!> model of the scene; the no-slip start is the full model's own.
module rollcon_reduced_scene
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_scene, only : scene_type
    use rollcon_disk_scene, only : build_disk_problem, disk_mass_properties
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_summary_type, history_type
    use rollcon_reduced_cvode, only : reduced_problem_type, simulate_reduced
    use rollcon_reduced_disk_rhs, only : reduced_size
    implicit none
    private

    public :: simulate_reduced_scene

contains

    !> Run the scene's reduced ODE with the scene's method ('bdf' or 'adams'), Jacobian
    !> ('analytic' or 'dq'), rtol, atol and max_steps.
    subroutine simulate_reduced_scene(scene, history, summary, error)
        type(scene_type), intent(in) :: scene
        !> Output rows in the layout of one part without UCONs (time, q, u, energy): the first
        !> 14 columns of the full model's rows
        type(history_type), intent(inout) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: full
        type(reduced_problem_type), target :: reduced
        real(wp) :: q0(6), u0(6), y0(reduced_size), unused(reduced_size), mass, inertia(3)

        ! the full problem only lends its forces and start, so both solve the same scene
        call build_disk_problem(scene, rolling_disk_ucosub, full, q0, u0, error)
        if (allocated(error)) return
        call disk_mass_properties(scene, mass, inertia)
        reduced%par = [inertia(1), inertia(3), mass, scene%disk%radius, scene%environment%gravity]
        if (allocated(full%model%forces)) reduced%forces = full%model%forces
        ! CVODE with the scene's method, Jacobian, tolerances and step limit
        reduced%settings = scene%run%run_settings_type
        reduced%theta_min = scene%limits%theta_min
        call reduced%pack_state(q0, u0, y0, unused)
        call simulate_reduced(reduced, y0, 0.0_wp, scene%run%end_time, scene%run%output_step, &
            & history, &
            & summary, error)
    end subroutine simulate_reduced_scene

end module rollcon_reduced_scene
