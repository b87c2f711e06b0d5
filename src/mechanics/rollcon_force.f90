! SPDX-License-Identifier: MIT
!> Applied forces on parts: a fixed ground direction, a time profile, a point of application;
!> or a dataset's force statement between markers (rollcon_marker_force), whose magnitudes are
!> expressions of time and state.
module rollcon_force
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_rotation, only : rotation_matrix, cross, times
    use rollcon_expression, only : switching_times, evaluate_expression, max_inputs
    use rollcon_marker_force, only : marker_force_type, marker_force_loads, marker_force_values, &
        & markers_coincide, kind_spring
    use rollcon_text, only : to_text
    use rollcon_spring_partials, only : add_spring_partials
    use rollcon_momentum_partials, only : momentum_partials_type
    use rollcon_force_partials, only : add_expression_force_partials, statement_couplings
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: applied_force_type, force_and_moment, force_breakpoints, force_corners, pulse_stops
    public :: forces_idle_after, nonfinite_load, runaway_load, runaway_limit
    public :: add_force_partials, force_couplings, add_expression_partials
    public :: profile_constant, profile_half_sine, profile_statement, frame_body, frame_tilt

    !> Time profiles: constant magnitude, one half-sine pulse carrying a given impulse, or a
    !> force statement's expressions (`statement`: markers, directions and magnitudes)
    integer, parameter :: profile_constant = 1, profile_half_sine = 2, profile_statement = 3
    !> A load or rate beyond this is a runaway: its square (a power, an energy) overflows, so
    !> the run's rows cannot stay finite (sqrt(huge(1.0_wp)), 1.3e154)
    real(wp), parameter :: runaway_limit = 1.3407807929942596e154_wp
    !> Stops inside each pulse: the integrator stops at pulse_points + 1 equally spaced times
    !> from a pulse's start to its end (force_breakpoints)
    integer, parameter :: pulse_points = 20
    !> Frames the application point is given in: the body's principal axes, or the tilt frame
    !> Rz(psi) Rx(theta) (without the spin phi), where (0, R, 0) is the top of a disk's rim
    integer, parameter :: frame_body = 1, frame_tilt = 2


    !> A force of fixed ground direction acting on one part
    type :: applied_force_type
        !> Index of the part in the model
        integer :: part = 1
        !> Unit direction, ground components
        real(wp) :: direction(3) = [1.0_wp, 0.0_wp, 0.0_wp]
        !> profile_constant or profile_half_sine
        integer :: profile = profile_constant
        !> Magnitude of a constant force [N]
        real(wp) :: magnitude = 0.0_wp
        !> Pulse start [s], length [s] and impulse [N s]
        real(wp) :: start = 0.0_wp, duration = 1.0_wp, impulse = 0.0_wp
        !> frame_body or frame_tilt
        integer :: frame = frame_body
        !> Point of application relative to the centre of mass, in that frame [m]
        real(wp) :: point(3) = 0.0_wp
        !> profile_statement: the force statement (the fields above are then not used)
        type(marker_force_type) :: statement
        !> What the force is, for messages ("data/x.adm:12: VFORCE/7", "the strike")
        character(len=:), allocatable :: name
    end type applied_force_type

contains

    !> Magnitude of the force at time t [N].
    pure function force_magnitude(force, time) result(magnitude)
        type(applied_force_type), intent(in) :: force
        real(wp), intent(in) :: time
        real(wp) :: magnitude

        select case (force%profile)
        case (profile_half_sine)
            magnitude = 0.0_wp
            if (time >= force%start .and. time <= force%start + force%duration) then
                ! the integral of A sin(pi s / T) over one half period is 2 A T / pi
                magnitude = 0.5_wp*pi*force%impulse/force%duration &
                    & * sin(pi*(time - force%start)/force%duration)
            end if
        case default
            magnitude = force%magnitude
        end select
    end function force_magnitude

    !> Sum of the forces on part p and their moment about its centre, ground components.
    pure subroutine force_and_moment(forces, p, time, q, u, force, moment)
        !> All applied forces of the model
        type(applied_force_type), intent(in) :: forces(:)
        !> Part index
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s] (part p's coordinates are
        !> q(6 (p - 1) + 1 : 6 p)); the rates are read by force statements only
        real(wp), intent(in) :: q(:), u(:)
        !> Resultant force [N] and moment about the centre of mass [N m]
        real(wp), intent(out) :: force(3), moment(3)
        real(wp) :: f(3), arm(3), frame(3, 3)
        integer :: i, i0

        force = 0.0_wp
        moment = 0.0_wp
        i0 = 6*(p - 1)
        do i = 1, size(forces)
            if (forces(i)%profile == profile_statement) then
                call marker_force_loads(forces(i)%statement, p, time, q, u, force, moment)
                cycle
            end if
            if (forces(i)%part /= p) cycle
            f = force_magnitude(forces(i), time)*forces(i)%direction
            if (all(f == 0.0_wp)) cycle
            if (forces(i)%frame == frame_tilt) then
                frame = rotation_matrix(q(i0 + 4), q(i0 + 5), 0.0_wp)
            else
                frame = rotation_matrix(q(i0 + 4), q(i0 + 5), q(i0 + 6))
            end if
            arm = times(frame, forces(i)%point)
            force = force + f
            moment = moment + cross(arm, f)
        end do
    end subroutine force_and_moment

    !> Subtract the partials of the SPRINGDAMPERs' and BUSHINGs' generalised forces from
    !> dm (dm/dq, dm/du: rollcon_momentum_partials), the partials of the momentum residual
    !> M a - f (rollcon_spring_partials: exact, over both parts of each). A force statement's
    !> expressions are add_expression_partials', a user routine's
    !> rollcon_user_force_partials'; the fixed-direction forces' are not in the Newton
    !> matrices (their moment held at body components, rollcon_body's body_residual_jacobian).
    pure subroutine add_force_partials(forces, q, u, dm)
        type(applied_force_type), intent(in) :: forces(:)
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        !> n x n, dense or on pairs of parts holding force_couplings'
        type(momentum_partials_type), intent(inout) :: dm
        integer :: i

        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            associate (s => forces(i)%statement)
                if (s%kind == kind_spring) call add_spring_partials(s%spring, s%i, s%j, q, u, &
                    & dm)
            end associate
        end do
    end subroutine add_force_partials

    !> Subtract the partials of the force statements written as expressions (SFORCE, VFORCE,
    !> GFORCE, VTORQUE with FUNCTION=) from dm (dm/dq, dm/du) at time [s] (rollcon_force_partials:
    !> exact, forward mode over the expressions, over every part each one touches).
    pure subroutine add_expression_partials(forces, time, q, u, dm)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), intent(in) :: time
        !> Coordinates and rates of all parts [m, rad, m/s, rad/s]
        real(wp), intent(in) :: q(:), u(:)
        !> n x n, dense or on pairs of parts holding force_couplings'
        type(momentum_partials_type), intent(inout) :: dm
        integer :: i

        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            call add_expression_force_partials(forces(i)%statement, time, q, u, dm)
        end do
    end subroutine add_expression_partials

    !> The pairs of parts (model indices, 2 x m) a SPRINGDAMPER or BUSHING joins, and those a
    !> force statement's partials join (rollcon_force_partials' statement_couplings: a part it
    !> loads and a part whose state it reads), each pair once in either order, ground left
    !> out: where the partials are written outside the parts' own blocks, which a sparse
    !> Newton matrix keeps.
    pure function force_couplings(forces) result(pairs)
        type(applied_force_type), intent(in) :: forces(:)
        integer, allocatable :: pairs(:, :)
        integer, allocatable :: more(:, :)
        integer :: i, a, b, k, m
        logical :: known

        allocate(pairs(2, 0))
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            if (forces(i)%statement%kind /= kind_spring) then
                more = statement_couplings(forces(i)%statement)
                do m = 1, size(more, 2)
                    call add_pair(more(1, m), more(2, m))
                end do
                cycle
            end if
            a = min(forces(i)%statement%i%part, forces(i)%statement%j%part)
            b = max(forces(i)%statement%i%part, forces(i)%statement%j%part)
            if (a <= 0 .or. a == b) cycle
            known = .false.
            do k = 1, size(pairs, 2)
                if (pairs(1, k) == a .and. pairs(2, k) == b) known = .true.
            end do
            if (.not. known) pairs = reshape([pairs, a, b], [2, size(pairs, 2) + 1])
        end do

    contains

        !> The pair (a, b), a < b, unless known.
        pure subroutine add_pair(a, b)
            integer, intent(in) :: a, b
            integer :: k

            do k = 1, size(pairs, 2)
                if (pairs(1, k) == a .and. pairs(2, k) == b) return
            end do
            pairs = reshape([pairs, a, b], [2, size(pairs, 2) + 1])
        end subroutine add_pair

    end function force_couplings

    !> Why the loads at (t, q, u) are not finite: the first force whose force or moment on a
    !> part is not finite, named, with the expression slot at fault for a force statement;
    !> "" when every load is finite. For a failure's message (not on the hot path).
    function nonfinite_load(forces, nparts, time, q, u) result(message)
        type(applied_force_type), intent(in) :: forces(:)
        !> Number of parts of the model
        integer, intent(in) :: nparts
        real(wp), intent(in) :: time, q(:), u(:)
        character(len=:), allocatable :: message
        character(len=*), parameter :: slots(6) = ["FX", "FY", "FZ", "TX", "TY", "TZ"]
        character(len=:), allocatable :: kind
        real(wp) :: force(3), moment(3), values(6)
        integer :: i, p, k

        message = ""
        do i = 1, size(forces)
            do p = 1, nparts
                call force_and_moment(forces(i:i), p, time, q, u, force, moment)
                if (all(ieee_is_finite([force, moment]))) cycle
                message = "force " // to_text(i)
                if (allocated(forces(i)%name)) message = forces(i)%name
                if (forces(i)%profile == profile_statement) then
                    if (markers_coincide(forces(i)%statement, q)) then
                        ! the statement's own name: an SFORCE or a SPRINGDAMPER
                        kind = "SFORCE"
                        if (forces(i)%statement%kind == kind_spring) kind = "SPRINGDAMPER"
                        message = message // ": its I and J markers are at one point at t = " &
                            & // to_text(time) // " s, where a translational " // kind &
                            & // "'s line of action (from J to I) is not defined"
                        return
                    end if
                    values = marker_force_values(forces(i)%statement, time, q, u)
                    k = findloc(ieee_is_finite(values), .false., dim=1)
                    if (k > 0) message = message // " " // slots(k) // " = " &
                        & // to_text(values(k))
                end if
                message = message // ": the load is not finite at t = " // to_text(time) &
                    & // " s (an expression that divides by zero or overflows there)"
                return
            end do
        end do
    end function nonfinite_load

    !> The force statement whose expression has run away at (time, q, u): the first component
    !> FX ... TZ, over every statement, whose finite value exceeds limit (at most runaway_limit:
    !> an EXP of a growing argument, a finite overflow of the kind nonfinite_load cannot see),
    !> in words ("VFORCE/5 FX = 5.2E+160 at t = 0.37 s: ..."; why names what limit is: "beyond
    !> 1.3e154, whose square overflows"); "" when none does.
    function runaway_load(forces, time, q, u, limit, why) result(message)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), intent(in) :: time, q(:), u(:)
        !> The size beyond which a load has run away [N, N m]
        real(wp), intent(in) :: limit
        character(len=*), intent(in) :: why
        character(len=:), allocatable :: message
        character(len=*), parameter :: slots(6) = ["FX", "FY", "FZ", "TX", "TY", "TZ"]
        real(wp) :: values(6)
        integer :: i, k

        message = ""
        do i = 1, size(forces)
            if (forces(i)%profile /= profile_statement) cycle
            values = marker_force_values(forces(i)%statement, time, q, u)
            k = findloc(ieee_is_finite(values) .and. abs(values) > limit, .true., dim=1)
            if (k == 0) cycle
            message = "force " // to_text(i)
            if (allocated(forces(i)%name)) message = forces(i)%name
            message = message // " " // slots(k) // " = " // to_text(values(k)) // " at t = " &
                & // to_text(time) // " s: a load this large (" // why // ") has run away: " &
                & // "an expression that grows without bound there (an EXP of a growing " &
                & // "argument?)"
            return
        end do
    end function runaway_load

    !> Times the integrator must stop at [s]. An implicit step that jumps over a pulse samples
    !> the force only where it is zero, and a step-size limit set between steps takes effect
    !> only after the next step; stopping at points inside a pulse resolves its shape whatever
    !> the step size was. One rule for both kinds of force: a half-sine pulse stops at
    !> pulse_stops(start, start + duration); a force statement at every switching time of each
    !> of its expressions (switching_times) and, when an expression switches at two times or
    !> more, at pulse_stops(first, last). Each time once. The corners among them
    !> (force_corners: a pulse's ends, the switching times) are where the integrator also
    !> starts again; inside a pulse it only stops.
    pure function force_breakpoints(forces) result(times)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), allocatable :: times(:)
        real(wp), allocatable :: switches(:)
        integer :: i, k

        allocate(times(0))
        do i = 1, size(forces)
            if (forces(i)%profile == profile_half_sine) then
                call add_new(times, pulse_stops(forces(i)%start, &
                    & forces(i)%start + forces(i)%duration))
            else if (forces(i)%profile == profile_statement) then
                associate (statement => forces(i)%statement)
                    do k = 1, size(statement%functions)
                        if (.not. statement%given(k)) cycle
                        switches = switching_times(statement%functions(k))*statement%time_unit
                        call add_new(times, switches)
                        if (size(switches) < 2) cycle
                        if (maxval(switches) > minval(switches)) call add_new(times, &
                            & pulse_stops(minval(switches), maxval(switches)))
                    end do
                end associate
            end if
        end do
    end function force_breakpoints

    !> True when no force acts after time (up to end_time), so that the energy is conserved
    !> there: a constant force is zero, a pulse has ended, and a force statement's expressions
    !> are zero at idle_samples times spread over (time, end_time] for two unrelated sets of
    !> values of the state functions they read; a SPRINGDAMPER or BUSHING is never idle. A
    !> sampled check, conservative in one direction only: an expression that is zero at every
    !> sample but not in between (a pulse falling between samples) would pass, which no
    !> expression of one switching time can be.
    pure logical function forces_idle_after(forces, time, end_time) result(idle)
        type(applied_force_type), intent(in) :: forces(:)
        !> From this time [s] to end_time [s]
        real(wp), intent(in) :: time, end_time
        integer, parameter :: idle_samples = 16
        ! two sets of state-function values with no relation to each other or to a threshold
        real(wp), parameter :: sample_inputs(2) = [0.7310585786300049_wp, -1.3862943611198906_wp]
        real(wp) :: t, inputs(max_inputs)
        integer :: i, k, j, set

        idle = .true.
        do i = 1, size(forces)
            select case (forces(i)%profile)
            case (profile_half_sine)
                idle = forces(i)%impulse == 0.0_wp &
                    & .or. forces(i)%start + forces(i)%duration <= time
            case (profile_statement)
                ! a user's routine (FUNCTION=USER) may push at any time
                if (forces(i)%statement%routine > 0) idle = .false.
                associate (statement => forces(i)%statement)
                    ! a SPRINGDAMPER or BUSHING does work whenever its markers move apart
                    if (statement%kind == kind_spring) idle = .false.
                    do k = 1, size(statement%functions)
                        if (.not. statement%given(k)) cycle
                        do set = 1, size(sample_inputs)
                            inputs = sample_inputs(set)
                            do j = 1, idle_samples
                                t = time + (end_time - time)*real(j, wp)/idle_samples
                                if (evaluate_expression(statement%functions(k), &
                                    & t/statement%time_unit, inputs(:size( &
                                    & statement%functions(k)%inputs))) /= 0.0_wp) idle = .false.
                            end do
                        end do
                    end do
                end associate
            case default
                idle = forces(i)%magnitude == 0.0_wp
            end select
            if (.not. idle) return
        end do
    end function forces_idle_after

    !> Times where a force has a corner [s], each once: a half-sine pulse's start and end, and
    !> every switching time of a force statement's expressions (an IF, STEP, STEP5, HAVSIN,
    !> IMPACT or BISTOP on TIME - c, MIN, MAX, DIM, SIGN or ABS of TIME - c:
    !> switching_times). They are among force_breakpoints; an integrator stops there and
    !> starts again with no history, which would hold a force the solution no longer has
    !> (docs/design.md §7). A switch on the state is located by the run instead
    !> (rollcon_switch_watch).
    pure function force_corners(forces) result(times)
        type(applied_force_type), intent(in) :: forces(:)
        real(wp), allocatable :: times(:)
        integer :: i, k

        allocate(times(0))
        do i = 1, size(forces)
            if (forces(i)%profile == profile_half_sine) then
                call add_new(times, [forces(i)%start, forces(i)%start + forces(i)%duration])
            else if (forces(i)%profile == profile_statement) then
                associate (statement => forces(i)%statement)
                    do k = 1, size(statement%functions)
                        if (.not. statement%given(k)) cycle
                        call add_new(times, switching_times(statement%functions(k)) &
                            & *statement%time_unit)
                    end do
                end associate
            end if
        end do
    end function force_corners

    !> pulse_points + 1 equally spaced times from first to last [s], both included exactly.
    pure function pulse_stops(first, last) result(times)
        real(wp), intent(in) :: first, last
        real(wp) :: times(pulse_points + 1)
        integer :: k

        times = [(first + k*(last - first)/pulse_points, k = 0, pulse_points - 1), last]
    end function pulse_stops

    !> Append to times those of more that it does not hold yet.
    pure subroutine add_new(times, more)
        real(wp), allocatable, intent(inout) :: times(:)
        real(wp), intent(in) :: more(:)
        integer :: k

        do k = 1, size(more)
            if (.not. any(times == more(k))) times = [times, more(k)]
        end do
    end subroutine add_new

end module rollcon_force
