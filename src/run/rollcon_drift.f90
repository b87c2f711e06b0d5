! SPDX-License-Identifier: MIT
!> What a run's tolerances promise of its energy drift (docs/outputs.md, "Drift").
!>
!> Each step's error test holds the local error of every component y_i of the state to
!> rtol |y_i| + atol; so one step may change the energy E (kinetic plus gravitational) by up to
!> e = sum_i |dE/dy_i| (rtol |y_i| + atol) (rollcon_equations energy_tolerance), which is never
!> 0 under gravity or motion and holds atol as well as rtol. Over a conserved stretch the drift
!> is the sum of the steps' energy errors (the exact flow conserves E), and errors of varying
!> sign add up like a random walk: after N steps about sqrt(N) e, e the mean over the judged
!> output rows. Allowed: K_E sqrt(N) e. Measured in these units (docs/outputs.md), the data/
!> scenes and datasets reach at most 0.77 and the pendulums of test/drift/ at ERROR 1e-5 ...
!> 1e-10 at most 2.0; CVODE without drift control 1.6 over 10 s and 7.8 over 30 s; K_E = 10.
!>
!> Whatever the tolerances, a run whose energy wanders by more than energy_fraction of the
!> energy it exchanges (the energy scale: the larger of the largest kinetic energy and the
!> potential energy's range over the judged rows, neither of which depends on where the
!> potential's zero is) is no simulation of the model to engineering accuracy: that is the
!> bound at loose tolerances, where one step's allowance is itself a large part of the energy
!> (ERROR = 1e-3 on a 2 m pendulum released level: 0.042 J a step on average, 20 J exchanged).
module rollcon_drift
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: energy_allowance, energy_fraction, work_fraction, energy_bound

    !> K_E of the bound [-]
    real(wp), parameter :: energy_allowance = 10.0_wp
    !> The largest energy drift any run may have, as a fraction of its energy scale [-]
    real(wp), parameter :: energy_fraction = 1.0e-2_wp
    !> Constraints whose explicit work (a moving constraint's: rollcon_problem
    !> constraint_power) exceeds this fraction of the drift allowed change the energy by more
    !> than the integration may: the energy is then not conserved, and not judged [-]
    real(wp), parameter :: work_fraction = 0.1_wp

contains

    !> The energy drift allowed after steps integrator steps [J]: the smaller of K_E sqrt(N)
    !> step_tolerance and energy_fraction scale (only the first when scale is 0).
    pure function energy_bound(steps, step_tolerance, scale) result(bound)
        integer, intent(in) :: steps
        !> The mean over the judged rows of what one step's error test allows the energy [J]
        real(wp), intent(in) :: step_tolerance
        !> The energy scale [J] >= 0
        real(wp), intent(in) :: scale
        real(wp) :: bound

        bound = energy_allowance*sqrt(real(max(1, steps), wp))*step_tolerance
        if (scale > 0.0_wp) bound = min(bound, energy_fraction*scale)
    end function energy_bound

end module rollcon_drift
