! SPDX-License-Identifier: MIT
!> A rim or a sphere rolling on the ground: the contact of a part that touches the ground plane
!> Z = 0 as a rim of radius R about its body z-axis (a rolling disk, a coin, a wheel), its
!> lowest point R e_y2 below the centre, or as a sphere of radius R about its centre of mass,
!> its lowest point G - R e_Z (a ball: a dataset's CONTACT, rollcon_adm_contact). The watch
!> adds the constraint force on the part, its normal part, the friction coefficient rolling
!> needs and the height residual (a rim's Z - R sin(theta), a sphere's Z - R) to every output
!> row; it may stop the run where the normal force turns negative (the part would leave the
!> ground, which a rolling constraint cannot represent); and it judges the height residual,
!> the position-level form of the contact that a velocity-level UCON holds only through its
!> integral, against what the tolerances promise.
!>
!> With Coulomb friction (mu_static > 0) it also owns the contact's mode (the equations'
!> sliding_contact_type, docs/design.md §5 "Contact modes"): rolling until |F_t| reaches
!> mu_static F_n, sliding until the slip velocity's component along its direction at the last
!> switch falls to zero; with a restitution (flight modelled) also flight, from where the
!> normal force falls to zero to where the rim's lowest point comes down to the ground, and
!> there an impact (rollcon_contact_impact). Each switch is an event located by the
!> integrator's root finding, after which the run restarts the integrator (action_restart).
!> It then adds the mode and the slip velocity to the rows, and lists the switches, the
!> impacts and the time in each mode in the summary.
module rollcon_contact_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_sliding_contact, only : sliding_contact_type
    use rollcon_contact_impact, only : impact_type, contact_impact
    use rollcon_run_settings, only : run_settings_type, formulation_speeds
    use rollcon_output_layout, only : name_length
    !> The columns it adds, in order (named where a CSV reader finds them too)
    use rollcon_watch_columns, only : contact_names, contact_mode_names, contact_mode_words
    use rollcon_watch, only : watch_type, watch_event_type, watch_measure_type, action_stop, &
        & action_restart
    implicit none
    private

    public :: contact_watch_type, height_allowance

    !> K_H of the height residual's bound K_H sqrt(N) (atol + rtol R) after N steps: independent
    !> local errors add up like a random walk (rollcon_drift); measured on the data/ scenes,
    !> sound runs reach at most 0.82 of sqrt(N) (atol + rtol R), drift = 'none' 4.8 to 7800
    real(wp), parameter :: height_allowance = 3.0_wp
    !> The guards of a stop, in units of the slip's integration error e = atol + rtol s,
    !> s = |v_G| + R |omega| (slip_error): the first, at 500 e, where the reference is aimed
    !> at the slip's direction again, so that its component's root is the stop; the second, at
    !> e/2, the stop itself should the integrator not reach that root first (in 3-D it cannot
    !> step past the stop, where the friction's direction turns over). A slip within e of zero
    !> is zero: the slip is not known better, so neither is the stop's time (e over the slip's
    !> deceleration: 7.6e-12 s in data/sliding_coin.nml, ~2e-8 s in data/coin_slipping.nml)
    real(wp), parameter :: guard_first = 500.0_wp, guard_second = 0.5_wp
    !> Modes, as the `mode` column writes them
    integer, parameter, public :: mode_rolling = 0, mode_sliding = 1, mode_flight = 2
    !> The capture rule, in units of the height's integration error atol + rtol R: an impact
    !> whose rebound would lift the rim's lowest point less than capture_factor times it (its
    !> normal speed v after the impact and that point's normal acceleration a in flight there,
    !> a < 0: v^2 / (2 |a|)) is plastic instead (e = 0), and the contact goes on on the ground.
    !> A flight that low is not resolved: the root of its landing is uncertain by the height's
    !> error over the speed, which is 1/(4 capture_factor) of the flight's time at the capture
    !> height, and a ball's bounces below it would be infinitely many in a finite time
    real(wp), parameter, public :: capture_factor = 100.0_wp
    !> The lead of the touchdown's event function while the rim's lowest point rises [s]
    !> (roots): any positive time keeps it positive there and continuous at the apex
    real(wp), parameter :: rising_lead = 1.0_wp

    !> What a switch did besides changing the mode: an impact's impulse and energies, and the
    !> value of the event function where it fired (a touchdown's height of the rim's lowest
    !> point [m], a lift-off's normal force [N]; 0 for the friction's switches)
    type, public :: contact_switch_type
        !> The switch is an impact (a touchdown), and it was captured (plastic, e = 0)
        logical :: impact = .false., captured = .false.
        !> Restitution applied [-], normal and tangential impulse [N s]
        real(wp) :: restitution = 0.0_wp, normal_impulse = 0.0_wp, tangential_impulse = 0.0_wp
        !> The rim's lowest point's normal velocity before the impact [m/s] (< 0) and after
        real(wp) :: approach = 0.0_wp, rebound = 0.0_wp
        !> Energy (kinetic plus potential) before and after the impact [J], in the ground's
        !> frame
        real(wp) :: energy_before = 0.0_wp, energy_after = 0.0_wp
        !> On a turntable, the work of the impulse P at the table's material velocity V there,
        !> V . P [J] (0 on the ground): the table's drive's share of the ground-frame change,
        !> so that the change in the table's frame is energy_after - energy_before - drive
        real(wp) :: drive = 0.0_wp
        !> The event function's value at the switch (height [m] or normal force [N])
        real(wp) :: event_value = 0.0_wp
    end type contact_switch_type

    type, extends(watch_type) :: contact_watch_type
        !> The part in contact (model order) and its rim's (or sphere's) radius [m] > 0
        integer :: part = 1
        real(wp) :: radius = 0.0_wp
        !> The part touches the ground as a sphere about its centre of mass (else as a rim)
        logical :: sphere = .false.
        !> Stop where the normal force falls below -liftoff_force: a real lift-off, not the
        !> rounding noise of a force that is zero
        logical :: stop_on_liftoff = .false.
        !> Lift-off threshold [N] >= 0, a small fraction of the model's force scale
        real(wp) :: liftoff_force = 0.0_wp
        !> The plane's height Z [m] (the ground's 0, a turntable's top), and a turntable's rate
        !> about ground +Z [rad/s] and its axis' X and Y [m]: the plane's material point at r
        !> moves at table_rate e_Z x (r - axis) (0: the ground)
        real(wp) :: plane_height = 0.0_wp, table_rate = 0.0_wp, table_axis(2) = 0.0_wp
        !> Largest |Z - R sin(theta)| over the output rows so far [m]
        real(wp) :: height_residual_max = 0.0_wp
        !> Scratch of an event function that must solve for the multipliers
        real(wp), allocatable :: a(:), lambda(:)
        !> Coulomb friction at the contact: modes watched (mu_static > 0) [-]
        real(wp) :: mu_static = 0.0_wp, mu_kinetic = 0.0_wp
        !> Flight and impacts are modelled (with friction only), with this restitution [-]:
        !> a lift-off is then a switch to flight, never a stop
        logical :: flight = .false.
        real(wp) :: restitution = 0.0_wp
        !> The contact's rows in model order: tangential (X, Y) and normal
        integer :: tangential(2) = [1, 2], normal = 3
        !> Mode at the start, and the slip's direction there when sliding (unit, X and Y)
        integer :: initial_mode = mode_rolling
        real(wp) :: initial_direction(2) = [1.0_wp, 0.0_wp]
        !> The slip's direction at the last switch (or re-reference): its component along it
        !> is the event function of sliding
        real(wp) :: slip_reference(2) = [1.0_wp, 0.0_wp]
        !> The slip speed within which the friction's direction turns to slip_reference [m/s]:
        !> guard_second times the slip's integration error where the reference was last set
        !> (rollcon_sliding_contact's slip_floor; 0 before any)
        real(wp) :: slip_floor = 0.0_wp
        !> The guard of a stop in effect (guard_first or guard_second)
        real(wp) :: guard = guard_first
        !> A slide is starting from rest: its slip not yet past the first guard (no stop is
        !> looked for until it is)
        logical :: starting = .false.
        !> The tolerances of the run and its Baumgarte rate in effect [1/s] (prepare)
        real(wp) :: rtol = 0.0_wp, atol = 0.0_wp, baumgarte = 0.0_wp
        !> The switches so far: times [s], the modes entered (an impact that bounces enters
        !> flight again) and what each did
        real(wp), allocatable :: switch_times(:)
        integer, allocatable :: switch_modes(:)
        type(contact_switch_type), allocatable :: switch_details(:)
        !> Time spent in each mode up to the last switch [s], the mode's start and the time of
        !> the last output row [s]
        real(wp) :: mode_time(0:2) = 0.0_wp, mode_since = 0.0_wp, last_time = 0.0_wp
        logical :: started = .false.
        !> Its mode in the equations: 0 their contact, k their more_contacts(k) (a dataset's
        !> further CONTACTs)
        integer :: slot = 0
        !> The user's statement, "CONTACT/2 (line 44)", where a model has several contacts: it
        !> names the summary's lines, and "contact<id>_" (column_prefix) starts the columns'
        !> and the measures' names; empty for one contact (the names as they are)
        character(len=:), allocatable :: label, column_prefix
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: roots_use_accelerations
        procedure :: fired
        procedure :: column_names
        procedure :: fill_columns
        procedure :: measures
        procedure :: height_residual
        procedure :: restart_problem
        procedure :: summary_lines
        procedure :: time_in_modes
        procedure :: friction
        procedure :: slip_velocity
        procedure :: table_velocity
        procedure :: angular_velocity
        procedure :: switch_to
        procedure :: current_mode
        procedure :: slip_error
        procedure :: begin_sliding
        procedure :: aim_sliding
        procedure :: normal_velocity
        procedure :: touchdown
        procedure :: settle
        procedure :: normal_root
        procedure :: prepare_contact
        procedure :: prefix
        procedure :: named
        procedure :: sliding_in
        procedure :: flying_in
        procedure :: friction_in
        procedure :: set_mode_flags
        procedure :: set_reference
        procedure :: add_impact_loss
    end type contact_watch_type

contains

    !> The part must be one of the model's and the radius positive.
    subroutine prepare(self, eq, settings, error)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error

        if (self%part < 1 .or. self%part > size(eq%model%parts)) then
            call fatal_error(error, "the part in contact is number " // to_text(self%part) &
                & // " in model order; the model has " // to_text(size(eq%model%parts)) &
                & // " parts", stat_input)
            return
        else if (.not. self%radius > 0.0_wp) then
            call fatal_error(error, "the contact of part " &
                & // to_text(eq%model%parts(self%part)%id) // " needs a rim radius > 0 [m], " &
                & // "got " // to_text(self%radius), stat_input)
            return
        end if
        if (allocated(self%a)) deallocate(self%a)
        if (allocated(self%lambda)) deallocate(self%lambda)
        allocate(self%a(eq%n), self%lambda(eq%nc), source=0.0_wp)
        self%height_residual_max = 0.0_wp
        if (allocated(self%switch_times)) deallocate(self%switch_times, self%switch_modes)
        if (allocated(self%switch_details)) deallocate(self%switch_details)
        allocate(self%switch_times(0), self%switch_modes(0), self%switch_details(0))
        self%mode_time = 0.0_wp
        self%started = .false.
        if (.not. self%friction()) return
        if (settings%formulation == formulation_speeds) then
            ! sliding's friction is coupled in the ODE form's accelerations (rollcon_equations)
            ! and the DAE form's residual (rollcon_dae), the modes' rows dropped in both
            call fatal_error(error, "a contact with Coulomb friction (mu_static > 0) is " &
                & // "integrated in the ODE or DAE form: formulation = 'cvode' or 'ida'", &
                & stat_input)
            return
        end if
        if (eq%nc < 3 .or. any(self%tangential > eq%nc) .or. self%normal > eq%nc) then
            call fatal_error(error, "the contact's rows " // to_text(self%tangential(1)) // ", " &
                & // to_text(self%tangential(2)) // " and " // to_text(self%normal) &
                & // " are not all among the model's " // to_text(eq%nc) // " constraints", &
                & stat_input)
            return
        end if
        self%rtol = settings%rtol
        self%atol = settings%atol
        self%baumgarte = settings%baumgarte()
        self%slip_reference = self%initial_direction
        self%slip_floor = 0.0_wp
        self%guard = guard_first
        self%starting = .false.
        if (self%slot == 0) then
            call self%prepare_contact(eq%contact, eq%n, eq%nc)
        else if (.not. allocated(eq%more_contacts)) then
            error = no_slot()
        else if (self%slot > size(eq%more_contacts)) then
            error = no_slot()
        else
            call self%prepare_contact(eq%more_contacts(self%slot), eq%n, eq%nc)
        end if

    contains

        function no_slot() result(made)
            type(error_type), allocatable :: made

            call fatal_error(made, "the contact's mode is the equations' further contact " &
                & // to_text(self%slot) // ", which they do not hold", stat_input)
        end function no_slot
    end subroutine prepare

    !> The contact's mode in the equations (eq's contact, or one of its more_contacts) at the
    !> start: its rows, its part's height coordinate, mu_kinetic, the initial mode and slip
    !> direction, no impact loss, and the scratch of its unit response (n accelerations, nc
    !> multipliers).
    subroutine prepare_contact(self, contact, n, nc)
        class(contact_watch_type), intent(in) :: self
        type(sliding_contact_type), intent(inout) :: contact
        integer, intent(in) :: n, nc

        contact%tangential = self%tangential
        contact%normal = self%normal
        contact%height_column = 6*(self%part - 1) + 3
        contact%mu = self%mu_kinetic
        contact%reference = self%initial_direction
        contact%slip_floor = self%slip_floor
        contact%sliding = self%initial_mode == mode_sliding
        contact%flying = self%initial_mode == mode_flight
        contact%impact_loss = 0.0_wp
        contact%impact_drive_work = 0.0_wp
        if (allocated(contact%unit_a)) deallocate(contact%unit_a, contact%unit_lambda)
        allocate(contact%unit_a(n), contact%unit_lambda(nc), source=0.0_wp)
    end subroutine prepare_contact

    !> Its contact slides (the equations' contact, or more_contacts(slot)).
    pure logical function sliding_in(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        if (self%slot == 0) then
            sliding_in = eq%contact%sliding
        else
            sliding_in = eq%more_contacts(self%slot)%sliding
        end if
    end function sliding_in

    !> Its contact flies.
    pure logical function flying_in(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        if (self%slot == 0) then
            flying_in = eq%contact%flying
        else
            flying_in = eq%more_contacts(self%slot)%flying
        end if
    end function flying_in

    !> Its contact's sliding friction on the part at the last solve [N], ground X and Y.
    pure function friction_in(self, eq) result(friction)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        real(wp) :: friction(2)

        if (self%slot == 0) then
            friction = eq%contact%friction
        else
            friction = eq%more_contacts(self%slot)%friction
        end if
    end function friction_in

    !> Set its contact's mode: sliding, flying (both false: rolling).
    pure subroutine set_mode_flags(self, eq, sliding, flying)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(inout) :: eq
        logical, intent(in) :: sliding, flying

        if (self%slot == 0) then
            eq%contact%sliding = sliding
            eq%contact%flying = flying
        else
            eq%more_contacts(self%slot)%sliding = sliding
            eq%more_contacts(self%slot)%flying = flying
        end if
    end subroutine set_mode_flags

    !> Its contact's slip direction at zero slip, and the floor within which the friction's
    !> direction turns to it: the watch's slip_reference and slip_floor.
    pure subroutine set_reference(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(inout) :: eq

        if (self%slot == 0) then
            eq%contact%reference = self%slip_reference
            eq%contact%slip_floor = self%slip_floor
        else
            eq%more_contacts(self%slot)%reference = self%slip_reference
            eq%more_contacts(self%slot)%slip_floor = self%slip_floor
        end if
    end subroutine set_reference

    !> Add an impact's loss of energy [J] >= 0 and the work its table's drive did in it [J]
    !> (signed; 0 on the ground) to its contact's.
    pure subroutine add_impact_loss(self, eq, loss, drive)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: loss, drive

        if (self%slot == 0) then
            eq%contact%impact_loss = eq%contact%impact_loss + loss
            eq%contact%impact_drive_work = eq%contact%impact_drive_work + drive
        else
            associate (contact => eq%more_contacts(self%slot))
                contact%impact_loss = contact%impact_loss + loss
                contact%impact_drive_work = contact%impact_drive_work + drive
            end associate
        end if
    end subroutine add_impact_loss

    !> Modes are watched: the contact has Coulomb friction.
    pure logical function friction(self)
        class(contact_watch_type), intent(in) :: self

        friction = self%mu_static > 0.0_wp
    end function friction

    !> Velocity of the part's material point at the contact, ground X and Y [m/s], relative to
    !> the plane's there: v_G + omega x r_GC with r_GC = -R e_y2 for a rim, written out in the
    !> 3-1-3 angles (docs/design.md §5, the no-slip constraint's F1 and F2), and r_GC = -R e_Z
    !> for a sphere: (v_x - R omega_Y, v_y + R omega_X) (ucon/specs/rolling_sphere.py's F1 and
    !> F2); on a turntable less the table's velocity there (table_velocity: the F1 and F2 of
    !> ucon/specs/turntable_ball.py, turntable_disk.py).
    pure function slip_velocity(self, q, u) result(slip)
        class(contact_watch_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: slip(2)
        real(wp) :: spin, omega(3)
        integer :: i0

        i0 = 6*(self%part - 1)
        if (self%sphere) then
            omega = self%angular_velocity(q, u)
            slip = [u(i0 + 1) - self%radius*omega(2), u(i0 + 2) + self%radius*omega(1)]
        else
            associate (psi => q(i0 + 4), theta => q(i0 + 5), psidot => u(i0 + 4), &
                    & thetadot => u(i0 + 5), phidot => u(i0 + 6), r => self%radius)
                spin = phidot + psidot*cos(theta)
                slip(1) = u(i0 + 1) + r*cos(psi)*spin - r*thetadot*sin(psi)*sin(theta)
                slip(2) = u(i0 + 2) + r*sin(psi)*spin + r*thetadot*cos(psi)*sin(theta)
            end associate
        end if
        if (self%table_rate /= 0.0_wp) slip = slip - self%table_velocity(q)
    end function slip_velocity

    !> The plane's material velocity at the contact point, ground X and Y [m/s]: a turntable's
    !> Omega e_Z x (r_C - c) = Omega (-(Y_C - c_Y), X_C - c_X), r_C the sphere's G - R e_Z or
    !> the rim's G - R e_y2 (its horizontal part G + R cos(theta) (sin(psi), -cos(psi))); the
    !> ground's 0.
    pure function table_velocity(self, q) result(velocity)
        class(contact_watch_type), intent(in) :: self
        real(wp), intent(in) :: q(:)
        real(wp) :: velocity(2)
        real(wp) :: point(2)
        integer :: i0

        velocity = 0.0_wp
        if (self%table_rate == 0.0_wp) return
        i0 = 6*(self%part - 1)
        point = q(i0 + 1:i0 + 2) - self%table_axis
        if (.not. self%sphere) point = point + self%radius*cos(q(i0 + 5)) &
            & *[sin(q(i0 + 4)), -cos(q(i0 + 4))]
        velocity = self%table_rate*[-point(2), point(1)]
    end function table_velocity

    !> The part's angular velocity, ground components [rad/s]: omega = psidot e_Z + thetadot e_x1
    !> + phidot e_z2 (docs/design.md §3).
    pure function angular_velocity(self, q, u) result(omega)
        class(contact_watch_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: omega(3)
        integer :: i0

        i0 = 6*(self%part - 1)
        associate (psi => q(i0 + 4), theta => q(i0 + 5), psidot => u(i0 + 4), &
                & thetadot => u(i0 + 5), phidot => u(i0 + 6))
            omega = [thetadot*cos(psi) + phidot*sin(theta)*sin(psi), &
                & thetadot*sin(psi) - phidot*sin(theta)*cos(psi), psidot + phidot*cos(theta)]
        end associate
    end function angular_velocity

    !> The lift-off, when watched (a stop) or flight is modelled (a switch, and in flight the
    !> touchdown): the first; with friction two more, the mode's (last but one) and the
    !> guard of a stop (last).
    pure integer function root_count(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = merge(1, 0, self%normal_root()) + merge(2, 0, self%friction())
    end function root_count

    !> The first event function is the normal one: the lift-off's, or in flight the touchdown's.
    pure logical function normal_root(self)
        class(contact_watch_type), intent(in) :: self

        normal_root = self%stop_on_liftoff .or. self%flight
    end function normal_root

    !> The normal force on the part + liftoff_force. The normal force comes from the multipliers
    !> when a DAE state gives them (IDA), else from the accelerations when the integrator gives
    !> them (CVODE's polynomial: no UCOSUB call and no solve), else from a saddle-point solve as
    !> in a right-hand side. With friction, rolling: mu_static F_n - |F_t| and a positive
    !> constant, F from a saddle-point solve; sliding: v_s . s_ref and |v_s| - guard times the
    !> slip's integration error (a slide starting from rest: a positive constant and |v_s| -
    !> the first guard) (docs/design.md §5, "Contact modes"). With flight modelled the normal
    !> force itself (its zero a lift-off), and in flight the height of the rim's lowest point
    !> Z - R sin(theta), led while it rises by rising_lead times its normal velocity (its zero
    !> a touchdown), and two positive constants.
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)
        real(wp) :: force(3), slip(2)
        integer :: m

        if (self%friction()) then
            m = self%root_count(eq) - 1
            g(m:m + 1) = 1.0_wp
        end if
        if (self%flying_in(eq)) then
            ! the rim's lowest point's height above the ground, led while it rises by its
            ! normal velocity over rising_lead: the same function where it falls (the
            ! touchdown's root), positive from a rebound on, where the height is zero to
            ! rounding (IDA, started again there, would report that zero again at each start)
            g(1) = self%height_residual(q) + rising_lead*max(0.0_wp, &
                & self%normal_velocity(q, u))
            return
        end if
        if (self%friction() .and. self%sliding_in(eq)) then
            ! sliding: the slip's component along its direction at the last switch, and its
            ! speed above its guard
            slip = self%slip_velocity(q, u)
            if (self%starting) then
                ! a slide starting from rest: its slip growing past the first guard
                g(m + 1) = norm2(slip) - guard_first*self%slip_error(u)
            else
                g(m) = dot_product(slip, self%slip_reference)
                g(m + 1) = norm2(slip) - self%guard*self%slip_error(u)
            end if
            if (.not. self%normal_root()) return
        end if
        if (self%friction()) then
            ! the friction rolling needs from the equations at this very state: the
            ! integrator's interpolated accelerations are off by its local error (6e-7 of
            ! mu_static in data/coin_slipping.nml), which would move the switch
            call eq%accelerations(time, q, u, settings%baumgarte(), self%a, self%lambda, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, self%lambda)
        else if (present(lambda)) then
            ! only C is needed: first partials, no saddle-point solve
            call eq%constraint_matrix_at(time, q, u, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, lambda)
        else if (present(a)) then
            force = eq%reaction_from_accelerations(self%part, time, q, u, a)
        else
            call eq%accelerations(time, q, u, settings%baumgarte(), self%a, self%lambda, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, self%lambda)
        end if
        if (self%stop_on_liftoff) g(1) = force(3) + self%liftoff_force
        ! flight modelled: the lift-off is where the normal force reaches zero itself
        if (self%flight) g(1) = force(3)
        ! rolling: the friction that static friction can give less the friction rolling needs
        if (self%friction() .and. .not. self%sliding_in(eq)) g(m) = self%mu_static*force(3) &
            & - norm2(force(1:2))
    end subroutine roots

    !> The lift-off's normal force comes from the accelerations when they are given.
    pure logical function roots_use_accelerations(self, eq)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        roots_use_accelerations = self%stop_on_liftoff .and. .not. self%friction()
    end function roots_use_accelerations

    !> The lift-off: the run stops; with flight modelled, or a mode's event: the contact
    !> switches (restart_problem).
    function fired(self, eq, k, time, q, u) result(event)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event
        integer :: p

        p = self%part
        if ((self%friction() .and. k >= self%root_count(eq) - 1) .or. (self%flight .and. k &
            & == 1)) then
            ! the mode's event: restart_problem decides and switches
            event%action = action_restart
            event%limit = "contact_mode"
            event%message = "the contact's mode event at t = " // to_text(time) // " s"
            return
        end if
        event%action = action_stop
        event%limit = "liftoff"
        event%message = "the normal contact force turned negative (below -" &
            & // to_text(self%liftoff_force) // " N) at t = " // to_text(time) &
            & // " s (theta = " // to_text(q(6*p - 1)) // " rad, thetadot = " &
            & // to_text(u(6*p - 1)) // " rad/s): the disk would leave the " &
            & // "ground, which a rolling constraint cannot represent"
        if (self%sphere) event%message = "the normal contact force turned negative (below -" &
            & // to_text(self%liftoff_force) // " N) at t = " // to_text(time) &
            & // " s (Z = " // to_text(q(6*p - 3)) // " m, Zdot = " // to_text(u(6*p - 3)) &
            & // " m/s): the sphere would leave the ground, which a rolling constraint " &
            & // "cannot represent (a restitution models its flight)"
    end function fired

    subroutine column_names(self, eq, names)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)
        integer :: k

        if (self%friction()) then
            allocate(names(size(contact_names) + size(contact_mode_names)))
            names(size(contact_names) + 1:) = contact_mode_names
        else
            allocate(names(size(contact_names)))
        end if
        names(:size(contact_names)) = contact_names
        if (len(self%prefix()) > 0) names = [character(len=name_length) :: &
            & (self%prefix() // trim(names(k)), k = 1, size(names))]
    end subroutine column_names

    !> The start of its columns' and measures' names: column_prefix ("contact<id>_") where a
    !> model has several contacts, else empty.
    pure function prefix(self) result(text)
        class(contact_watch_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
        if (allocated(self%column_prefix)) text = self%column_prefix
    end function prefix

    !> The start of its summary's lines: label and ": " where a model has several contacts.
    pure function named(self) result(text)
        class(contact_watch_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
        if (allocated(self%label)) text = self%label // ": "
    end function named

    !> Force, normal force, friction needed, height residual (and its largest magnitude, on the
    !> ground: in flight it is the rim's lowest point's height); with friction the mode and the
    !> slip velocity (in flight the lowest point's horizontal velocity).
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        real(wp) :: force(3), height

        force = eq%constraint_force(self%part, lambda)
        ! sliding: the friction is a force of the contact's too (rollcon_sliding_contact)
        if (self%sliding_in(eq)) force(1:2) = force(1:2) + self%friction_in(eq)
        height = self%height_residual(q)
        if (.not. self%flying_in(eq)) self%height_residual_max = max(self%height_residual_max, &
            & abs(height))
        values(1:3) = force
        values(4) = force(3)
        values(5) = 0.0_wp
        if (force(3) > 0.0_wp) values(5) = norm2(force(1:2))/force(3)
        values(6) = height
        if (.not. self%started) self%mode_since = time
        self%started = .true.
        self%last_time = time
        if (.not. self%friction()) return
        values(7) = merge(mode_sliding, mode_rolling, self%sliding_in(eq))
        if (self%flying_in(eq)) values(7) = mode_flight
        values(8:9) = self%slip_velocity(q, u)
    end subroutine fill_columns

    !> The mode's event fired at (t, q, u). Rolling: |F_t| reached mu_static F_n, so the
    !> contact slides, its slip starting against the friction rolling needed (-F_t / |F_t|).
    !> Sliding from rest, its slip past the first guard: stops are looked for from now on.
    !> Sliding otherwise, a slip above its integration error e: the reference is aimed at the
    !> slip's direction (its direction turned by 90 degrees, or the first guard), the second
    !> guard watching below the first. A slip within e of zero is a stop: the contact rolls if
    !> rolling's friction is admissible there (|F_t| <= mu_static F_n), else it slides on
    !> against the friction rolling would need. An error when the sliding equations are
    !> ill-posed there (Painlevé: rollcon_equations). With flight modelled: on the ground, a
    !> normal force that is no longer positive is a lift-off (the part flies); in flight, the
    !> rim's lowest point on the ground approaching it is a touchdown, an impact (touchdown),
    !> and u the rates after it.
    subroutine restart_problem(self, eq, time, q, u, error)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(error_type), allocatable, intent(out) :: error
        type(contact_switch_type) :: detail
        real(wp) :: force(3), slip(2)

        if (.not. self%friction()) return
        if (self%flying_in(eq)) then
            call self%touchdown(eq, time, q, u, error)
            return
        end if
        if (self%flight) then
            call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, self%lambda)
            if (.not. force(3) > 0.0_wp) then
                ! the normal force reached zero: the part leaves the ground
                call self%set_mode_flags(eq, .false., .true.)
                self%starting = .false.
                detail%event_value = force(3)
                call self%switch_to(mode_flight, time, detail)
                return
            end if
        end if
        if (.not. self%sliding_in(eq)) then
            ! rolling, |F_t| reached mu_static F_n: it slides
            call self%begin_sliding(eq, time, q, u, error)
            return
        end if
        if (self%starting) then
            ! the starting slide's slip has grown past the first guard
            self%starting = .false.
            return
        end if
        slip = self%slip_velocity(q, u)
        if (norm2(slip) > self%slip_error(u)) then
            ! not a stop: the direction turned by 90 degrees, or the first guard; the
            ! reference aimed at the slip's direction now, and below the first guard the
            ! second one watches
            call self%aim_sliding(eq, slip, u)
            return
        end if
        call self%set_mode_flags(eq, .false., .false.)
        ! the slip stopped: rolling, if the friction it needs is admissible here
        call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
        if (allocated(error)) return
        force = eq%constraint_force(self%part, self%lambda)
        if (norm2(force(1:2)) <= self%mu_static*force(3)) then
            call self%switch_to(mode_rolling, time)
            return
        end if
        call self%begin_sliding(eq, time, q, u, error)
    end subroutine restart_problem

    !> Sliding with the slip slip (ground X, Y) [m/s] above its integration error at the rates
    !> u: the reference aimed at the slip's direction, the first guard above it and the second
    !> below (no switch recorded).
    subroutine aim_sliding(self, eq, slip, u)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: slip(2), u(:)

        self%slip_reference = slip/norm2(slip)
        self%slip_floor = guard_second*self%slip_error(u)
        call self%set_reference(eq)
        self%guard = merge(guard_second, guard_first, norm2(slip) <= guard_first &
            & *self%slip_error(u))
    end subroutine aim_sliding

    !> Slide from (t, q, u), rolling there (its contact not sliding), against the friction
    !> rolling needs there (s_ref = -F_t / |F_t|); a switch unless it was sliding already (a
    !> stop where rolling is not admissible) or record is false. An error when sliding is
    !> ill-posed there.
    subroutine begin_sliding(self, eq, time, q, u, error, record)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        logical, intent(in), optional :: record
        real(wp) :: force(3)

        call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
        if (allocated(error)) return
        force = eq%constraint_force(self%part, self%lambda)
        if (norm2(force(1:2)) > 0.0_wp) then
            self%slip_reference = -force(1:2)/norm2(force(1:2))
        end if
        self%slip_floor = guard_second*self%slip_error(u)
        call self%set_reference(eq)
        call self%set_mode_flags(eq, .true., .false.)
        self%guard = guard_first
        self%starting = .true.
        ! Painlevé's refusal, here rather than at the integrator's first evaluation
        call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
        if (allocated(error)) return
        if (present(record)) then
            if (.not. record) return
        end if
        if (self%current_mode() /= mode_sliding) call self%switch_to(mode_sliding, time)
    end subroutine begin_sliding

    !> The normal velocity of the lowest point: a rim's Z' - R cos(theta) theta' (the no-slip
    !> constraint's F3: docs/design.md §5), a sphere's Z' [m/s].
    pure real(wp) function normal_velocity(self, q, u)
        class(contact_watch_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        integer :: i0

        i0 = 6*(self%part - 1)
        if (self%sphere) then
            normal_velocity = u(i0 + 3)
            return
        end if
        normal_velocity = u(i0 + 3) - self%radius*cos(q(i0 + 5))*u(i0 + 5)
    end function normal_velocity

    !> In flight, the rim's lowest point reached the ground at (t, q, u). Approaching it
    !> (normal velocity < 0): the impact's impulse P at that point (rollcon_contact_impact:
    !> W = J M^-1 J^T from the contact's three rows J, mu_kinetic, the restitution) changes the
    !> rates to u + M^-1 J^T P. A rebound that would lift that point less than the capture
    !> height (capture_factor) is captured: compression's impulse alone (e = 0). After a
    !> rebound the part flies on; otherwise it settles on the ground (settle). Not approaching
    !> (a rise through the ground level after a lift-off just below it): nothing changes.
    subroutine touchdown(self, eq, time, q, u, error)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(error_type), allocatable, intent(out) :: error
        type(contact_switch_type) :: detail
        type(impact_type) :: impact
        real(wp) :: jacobian(3, eq%n), minv_jt(eq%n, 3), w(3, 3), rebound(size(u)), fall
        real(wp) :: apex, table(3), drive, applied(3)
        integer :: rows(3), i0, i

        detail%event_value = self%height_residual(q)
        detail%approach = self%normal_velocity(q, u)
        if (.not. detail%approach < 0.0_wp) return
        ! the saddle-point factors at this state: M^-1 by parts (every row dropped in flight)
        call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
        if (allocated(error)) return
        rows = [self%tangential(1), self%tangential(2), self%normal]
        ! the contact's three rows of C (held by rows over each UCON's coordinates), dense
        do i = 1, 3
            call eq%c%fill_row(rows(i), jacobian(i, :))
        end do
        minv_jt = transpose(jacobian)
        call eq%saddle%apply_inverse_mass(minv_jt, 3, error)
        if (allocated(error)) return
        w = matmul(jacobian, minv_jt)
        w = 0.5_wp*(w + transpose(w))
        ! the point's velocity relative to the plane (a turntable's moves: its rows are
        ! J u - (V_table, 0), and its impulse acts on the part alone, the table's motion
        ! prescribed)
        table = [self%table_velocity(q), 0.0_wp]
        call contact_impact(w, matmul(jacobian, u) - table, self%mu_kinetic, self%restitution, &
            & impact, error)
        if (allocated(error)) then
            error%message = "at t = " // to_text(time) // " s " // error%message
            return
        end if
        detail%impact = .true.
        detail%energy_before = eq%energy(q, u)
        rebound = u + matmul(minv_jt, impact%impulse)
        detail%captured = .not. impact%velocity(3) > 0.0_wp
        if (.not. detail%captured) then
            ! the capture rule: the rebound's height, from the lowest point's normal
            ! acceleration in flight after the impact
            call eq%accelerations(time, q, rebound, self%baumgarte, self%a, self%lambda, error)
            if (allocated(error)) return
            i0 = 6*(self%part - 1)
            fall = self%a(i0 + 3)
            if (.not. self%sphere) fall = fall - self%radius*(cos(q(i0 + 5))*self%a(i0 + 5) &
                & - sin(q(i0 + 5))*rebound(i0 + 5)**2)
            if (fall < 0.0_wp) then
                apex = impact%velocity(3)**2/(2.0_wp*abs(fall))
                detail%captured = apex <= capture_factor*(self%atol + self%rtol*self%radius)
            end if
        end if
        if (detail%captured .and. self%restitution > 0.0_wp) then
            u = u + matmul(minv_jt, impact%compression)
            applied = impact%compression
            detail%normal_impulse = impact%compression(3)
            detail%tangential_impulse = norm2(impact%compression(1:2))
            detail%restitution = 0.0_wp
        else
            u = rebound
            applied = impact%impulse
            detail%normal_impulse = impact%impulse(3)
            detail%tangential_impulse = norm2(impact%impulse(1:2))
            detail%restitution = self%restitution
        end if
        detail%captured = detail%captured .and. self%restitution > 0.0_wp
        detail%rebound = self%normal_velocity(q, u)
        detail%energy_after = eq%energy(q, u)
        ! the loss relative to the plane: on a turntable the energy's change is that loss
        ! less the table's velocity at the point times the impulse (the drive's work: the
        ! part's velocity there is the relative one plus the table's)
        drive = 0.0_wp
        if (self%table_rate /= 0.0_wp) drive = dot_product(table, applied)
        detail%drive = drive
        call self%add_impact_loss(eq, max(0.0_wp, detail%energy_before - detail%energy_after &
            & + drive), drive)
        if (detail%restitution > 0.0_wp) then
            ! a rebound: it flies on
            call self%switch_to(mode_flight, time, detail)
            return
        end if
        call self%settle(eq, time, q, u, detail, error)
    end subroutine touchdown

    !> After an impact that leaves the rim's lowest point at rest normally (e = 0 or
    !> captured), at (t, q, u): the contact on the ground, sliding where the impact left a slip
    !> above its integration error, else rolling where rolling's friction is admissible
    !> (|F_t| <= mu_static F_n), else sliding against the friction rolling would need; flight
    !> again where that mode's normal force is not positive (the ground cannot hold the part).
    !> The switch recorded with the impact's detail.
    subroutine settle(self, eq, time, q, u, detail, error)
        class(contact_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:), u(:)
        type(contact_switch_type), intent(in) :: detail
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: force(3), slip(2)
        integer :: mode

        call self%set_mode_flags(eq, .false., .false.)
        self%starting = .false.
        slip = self%slip_velocity(q, u)
        if (norm2(slip) > self%slip_error(u)) then
            call self%set_mode_flags(eq, .true., .false.)
            call self%aim_sliding(eq, slip, u)
        else
            call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
            if (allocated(error)) return
            force = eq%constraint_force(self%part, self%lambda)
            if (norm2(force(1:2)) > self%mu_static*force(3)) then
                call self%begin_sliding(eq, time, q, u, error, record=.false.)
                if (allocated(error)) return
            end if
        end if
        call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
        if (allocated(error)) return
        force = eq%constraint_force(self%part, self%lambda)
        mode = merge(mode_sliding, mode_rolling, self%sliding_in(eq))
        if (.not. force(3) > 0.0_wp) then
            call self%set_mode_flags(eq, .false., .true.)
            self%starting = .false.
            mode = mode_flight
        end if
        call self%switch_to(mode, time, detail)
    end subroutine settle

    !> The slip's integration error [m/s]: atol + rtol s, s = |v_G| + R |omega| (|omega|
    !> bounded by the Euler-angle rates' norm) at the rates u.
    pure real(wp) function slip_error(self, u)
        class(contact_watch_type), intent(in) :: self
        real(wp), intent(in) :: u(:)
        integer :: i0

        i0 = 6*(self%part - 1)
        slip_error = self%atol + self%rtol*(norm2(u(i0 + 1:i0 + 3)) &
            & + self%radius*norm2(u(i0 + 4:i0 + 6)))
    end function slip_error

    !> The mode the contact is in: the last switch's, or the initial one.
    pure integer function current_mode(self)
        class(contact_watch_type), intent(in) :: self

        current_mode = self%initial_mode
        if (allocated(self%switch_modes)) then
            if (size(self%switch_modes) > 0) current_mode = self%switch_modes(size( &
                & self%switch_modes))
        end if
    end function current_mode

    !> Record a switch into mode at time [s] (with what it did, detail), and the time spent in
    !> the mode it leaves.
    subroutine switch_to(self, mode, time, detail)
        class(contact_watch_type), intent(inout) :: self
        integer, intent(in) :: mode
        real(wp), intent(in) :: time
        type(contact_switch_type), intent(in), optional :: detail
        type(contact_switch_type) :: made

        if (present(detail)) made = detail
        self%mode_time(self%current_mode()) = self%mode_time(self%current_mode()) + time &
            & - self%mode_since
        self%mode_since = time
        self%switch_times = [self%switch_times, time]
        self%switch_modes = [self%switch_modes, mode]
        self%switch_details = [self%switch_details, made]
    end subroutine switch_to

    !> With friction: every switch, "t = 0.113263 s: sliding → rolling", an impact's with its
    !> restitution, impulses and energy change (kinetic plus potential) [J]; on a turntable
    !> that change in the table's frame, where the impact's loss is (the part's velocities
    !> relative to the table: the ground frame's change less the drive's work V . P), with
    !> the ground frame's after it; and the time spent in each mode up to the last row.
    function summary_lines(self, eq) result(text)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=:), allocatable :: text
        real(wp) :: spent(0:2)
        integer :: k, from, impacts

        text = ""
        if (.not. self%friction()) return
        from = self%initial_mode
        text = "contact: starts "
        if (allocated(self%label)) text = self%label // ": starts "
        text = text // trim(merge("in flight", contact_mode_words(from) // "  ", &
            & from == mode_flight)) // " (mu_static " // to_text(self%mu_static) &
            & // ", mu_kinetic " // to_text(self%mu_kinetic)
        if (self%flight) text = text // ", restitution " // to_text(self%restitution)
        text = text // "), " // to_text(size(self%switch_times)) // " switch" &
            & // trim(merge("  ", "es", size(self%switch_times) == 1))
        if (self%flight) then
            impacts = count(self%switch_details%impact)
            text = text // " (" // to_text(impacts) // " impact" // trim(merge("  ", "s ", &
                & impacts == 1)) // ")"
        end if
        text = text // new_line("a")
        do k = 1, size(self%switch_times)
            text = text // "  " // self%named() // "t = " // to_text(self%switch_times(k)) &
                & // " s: " &
                & // trim(contact_mode_words(from)) // " → " &
                & // trim(contact_mode_words(self%switch_modes(k)))
            associate (d => self%switch_details(k))
                if (d%impact) then
                    text = text // " (impact" // trim(merge(", captured", "          ", &
                        & d%captured)) // ": e " // to_text(d%restitution) &
                        & // ", normal impulse " // to_text(d%normal_impulse) &
                        & // " N s, tangential " // to_text(d%tangential_impulse) // " N s, "
                    if (self%table_rate /= 0.0_wp) then
                        ! the loss is the table frame's: the ground frame's change holds
                        ! the table's drive's work V . P as well
                        text = text // "energy in the table's frame " // to_text(d%energy_after &
                            & - d%energy_before - d%drive) // " J (in the ground's " &
                            & // to_text(d%energy_after - d%energy_before) // " J))"
                    else
                        text = text // "energy " // to_text(d%energy_after - d%energy_before) &
                            & // " J)"
                    end if
                end if
            end associate
            text = text // new_line("a")
            from = self%switch_modes(k)
        end do
        spent = self%time_in_modes()
        text = text // "  " // self%named() // "time rolling " // to_text(spent(mode_rolling)) &
            & // " s, sliding " // to_text(spent(mode_sliding)) // " s"
        if (self%flight) text = text // ", flight " // to_text(spent(mode_flight)) // " s"
        text = text // new_line("a")
    end function summary_lines

    !> Time spent in each mode [s], by mode number, up to the last output row.
    pure function time_in_modes(self) result(spent)
        class(contact_watch_type), intent(in) :: self
        real(wp) :: spent(lbound(self%mode_time, 1):ubound(self%mode_time, 1))

        spent = self%mode_time
        spent(self%current_mode()) = spent(self%current_mode()) &
            & + max(0.0_wp, self%last_time - self%mode_since)
    end function time_in_modes

    !> The height of the lowest point of the part in contact above the plane [m]: a rim's
    !> Z - R sin(theta) - h, a sphere's Z - R - h, h the plane's height (0: the ground).
    pure real(wp) function height_residual(self, q)
        class(contact_watch_type), intent(in) :: self
        !> Coordinates of every part
        real(wp), intent(in) :: q(:)
        integer :: i0

        i0 = 6*(self%part - 1)
        if (self%sphere) then
            height_residual = q(i0 + 3) - self%radius - self%plane_height
            return
        end if
        height_residual = q(i0 + 3) - self%radius*sin(q(i0 + 5)) - self%plane_height
    end function height_residual

    !> The largest height residual, bound K_H sqrt(N) (atol + rtol R).
    function measures(self, eq, settings, steps) result(taken)
        class(contact_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        type(run_settings_type), intent(in) :: settings
        integer, intent(in) :: steps
        type(watch_measure_type), allocatable :: taken(:)
        real(wp), allocatable :: spent(:)
        integer :: k

        allocate(taken(1))
        taken(1)%name = "height_residual"
        taken(1)%label = "largest height residual |Z - R sin(theta)|"
        if (self%sphere) taken(1)%label = "largest height residual |Z - R|"
        taken(1)%unit = "m"
        taken(1)%value = self%height_residual_max
        taken(1)%bound = height_allowance*sqrt(real(max(1, steps), wp)) &
            & *(settings%atol + settings%rtol*self%radius)
        taken(1)%bound_rule = to_text(height_allowance) // " sqrt(N) (atol + rtol R)"
        taken(1)%remedy = "height = 'position'"
        if (.not. self%friction()) then
            call name_them()
            return
        end if
        ! with friction, for tables (a study's row), not judged: the switches and the time in
        ! each mode (time_rolling, time_sliding), as the summary's lines say them
        taken = [taken, watch_measure_type(name="switches", label="contact mode switches", &
            & unit="", value=real(size(self%switch_times), wp))]
        spent = self%time_in_modes()
        do k = 1, size(spent)
            taken = [taken, watch_measure_type(name="time_" // trim(contact_mode_words(k - 1)), &
                & label="time " // trim(contact_mode_words(k - 1)), unit="s", value=spent(k))]
        end do
        call name_them()

    contains

        !> Several contacts: each measure's name and label its contact's.
        subroutine name_them()
            integer :: j

            if (len(self%prefix()) == 0) return
            do j = 1, size(taken)
                taken(j)%name = self%prefix() // taken(j)%name
                taken(j)%label = self%named() // taken(j)%label
            end do
        end subroutine name_them
    end function measures

end module rollcon_contact_watch
