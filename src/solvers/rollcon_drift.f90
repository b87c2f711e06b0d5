! SPDX-License-Identifier: MIT
!> What a run's tolerances promise of its drift: the position-level height residual of a disk
!> and the bounds its energy drift and height residual are judged against.
!>
!> The integrators keep each step's local error within rtol |y| + atol (their error test);
!> independent local errors add up like a random walk, to about sqrt(N) of them after N steps,
!> while a drift the formulation does not correct (CVODE with drift = 'none') grows like N.
!> Allowed: a relative energy drift of K_E sqrt(N) rtol and a height residual |Z - R sin(theta)|
!> of K_H sqrt(N) (atol + rtol R). Measured in these sqrt(N) units (the data/ scenes; the
!> tipping coin at rtol 1e-4..1e-8 over 10-30 s; coin and long_run over 2000 s): height, sound
!> runs at most 0.82, drift = 'none' 4.8-7800, hence K_H = 3; energy, sound runs at most 0.93
!> over 10 s but 7.1 for the coin over 2000 s under IDA (BDF's damping adds up like N),
!> drift = 'none' 4.8-9.2 over 10 s and 38 or more over 30 s, hence K_E = 10.
module rollcon_drift
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    implicit none
    private

    public :: height_residual, drift_bounds, drift_findings
    public :: energy_allowance, height_allowance

    !> K_E and K_H of the bounds [-]
    real(wp), parameter :: energy_allowance = 10.0_wp, height_allowance = 3.0_wp

contains

    !> Height residual Z - R sin(theta) of the watched part [m]: the position-level form of the
    !> disk's contact, which the velocity constraint F3 holds only through its integral; 0 when
    !> the problem has no watched contact.
    pure function height_residual(problem, q) result(height)
        type(problem_type), intent(in) :: problem
        !> Coordinates of every part
        real(wp), intent(in) :: q(:)
        real(wp) :: height(1)
        integer :: i0

        height = 0.0_wp
        if (.not. problem%events%has_contact) return
        i0 = 6*(problem%events%part - 1)
        height = q(i0 + 3) - problem%events%contact_radius*sin(q(i0 + 5))
    end function height_residual

    !> The bounds after steps integrator steps: relative energy drift [-], height residual [m]
    !> (0 when the problem has no watched contact).
    pure subroutine drift_bounds(problem, steps, energy_bound, height_bound)
        type(problem_type), intent(in) :: problem
        integer, intent(in) :: steps
        real(wp), intent(out) :: energy_bound, height_bound
        real(wp) :: root_steps

        root_steps = sqrt(real(max(1, steps), wp))
        associate (rtol => problem%settings%rtol, atol => problem%settings%atol, &
            & radius => problem%events%contact_radius)
            energy_bound = energy_allowance*root_steps*rtol
            height_bound = 0.0_wp
            if (problem%events%has_contact) height_bound = height_allowance*root_steps &
                & *(atol + rtol*radius)
        end associate
    end subroutine drift_bounds

    !> What exceeds its bound (a bound of 0 is not judged), with the remedy; "" when nothing.
    function drift_findings(steps, energy_drift, energy_bound, height, height_bound) &
        & result(findings)
        integer, intent(in) :: steps
        !> Measured relative energy drift and its bound [-]
        real(wp), intent(in) :: energy_drift, energy_bound
        !> Largest height residual and its bound [m]
        real(wp), intent(in) :: height, height_bound
        character(len=:), allocatable :: findings

        findings = ""
        if (energy_bound > 0.0_wp .and. .not. energy_drift <= energy_bound) findings = findings &
            & // "; energy drift " // to_text(energy_drift) // " > " // to_text(energy_bound) &
            & // " allowed"
        if (height_bound > 0.0_wp .and. .not. height <= height_bound) findings = findings &
            & // "; height residual |Z - R sin(theta)| " // to_text(height) // " m > " &
            & // to_text(height_bound) // " m allowed"
        if (len(findings) == 0) return
        findings = findings(3:) // " (bounds: " // to_text(energy_allowance) // " and " &
            & // to_text(height_allowance) // " sqrt(N) local errors after N = " &
            & // to_text(steps) // " steps; use drift = 'projection', height = 'position' or " &
            & // "a tighter rtol)"
    end function drift_findings

end module rollcon_drift
