! SPDX-License-Identifier: MIT
!> A rim's dissipation (rollcon_rim_dissipation) watched: the power rolling resistance and the
!> air layer dissipate and the energy dissipated since the start (integrated with the state by
!> CVODE and IDA; by the trapezoidal rule over the rows on an integrator that does not), as
!> columns of every row; in the
!> summary the energy each law dissipated and, for a disk settling to its finite-time
!> singularity (Euler's disk), the fit of its precession rate Omega = |psidot| to
!> Omega ~ (t0 - t)^(-n) (fit_singularity; docs/design.md §5, "Dissipation").
!>
!> Rolling resistance's law Q_phi = -delta F_n sign(phidot) switches at phidot = 0, where it is
!> set-valued (|Q_phi| <= delta F_n): the watch's event function is phidot, its root located
!> by the integrator, and there (and at a start at phidot = 0) the law's sign is decided from
!> the equations at that state and held until the next root (decide_rolling_sign): phidot
!> leaves zero in the direction it would take without the resistance when the resistance
!> cannot hold it; when it can, phidot is held at zero by the moment it needs (the equations'
!> held_coupling) and the event function is delta F_n less that moment's size, whose root
!> releases it in the direction the moment held. Held while the contact slides is not
!> modelled: the run stops there.
module rollcon_dissipation_watch
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_equations, only : equations_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_output_layout, only : name_length
    use rollcon_watch_columns, only : dissipation_names
    use rollcon_watch, only : watch_type, watch_event_type, action_stop, action_restart
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: dissipation_watch_type, fit_singularity, singularity_fit_type

    !> Fraction of the rows' time span left out at its start by the fit: the start's own
    !> transient (a state near, not at, steady precession nutates before it settles)
    real(wp), parameter :: skipped_fraction = 0.1_wp
    !> Fewest rows a fit takes
    integer, parameter :: fit_rows_min = 8
    !> The range of t0 - t_end searched, as fractions of the fitted rows' time span: from a
    !> millionth (a run that ends right at the singularity) to the span itself
    real(wp), parameter :: gap_min_fraction = 1.0e-6_wp, gap_max_fraction = 1.0_wp
    !> When a fit is the run's singularity (singularity_fit_type%settles): the rows end within
    !> this fraction of the fitted rows' span after the largest rate (the run stopped at the
    !> breakdown: the flat limit theta_min or a lift-off, not run on past a peak), the rate
    !> grew over the fitted rows by at least this factor, the rms residual of ln Omega is at
    !> most this, and t0 lies inside the searched range, not at its near end (a fit that
    !> runs to that end has no minimum: the rates do not diverge). data/euler_disk.nml:
    !> 0.001 of the span, growth 3.0, residual 0.0074, t0 - t_end = 9.6e-3 s (8e-4 of span);
    !> a spinning coin that bounces on (/work/tools/combo.nml's kind): rows 0.69 of the span
    !> past the peak, t0 at the range's end
    real(wp), parameter :: settle_tail_fraction = 0.05_wp, settle_growth_min = 2.0_wp, &
        & settle_residual_max = 0.05_wp
    !> The kinds of rolling resistance's switches (dissipation_watch_type%switch_kinds)
    integer, parameter, public :: switch_sign = 1, switch_hold = 2, switch_release = 3
    !> The law's switches the summary lists one by one (the rest are counted): a coin whose
    !> phidot changes sign again and again has hundreds
    integer, parameter :: listed_switches = 50

    !> A fit of Omega ~ (t0 - t)^(-n)
    type :: singularity_fit_type
        !> A fit was made (enough rows, all rates positive and finite)
        logical :: made = .false.
        !> The fit is a singularity the run ends at (the rule at settle_tail_fraction)
        logical :: settles = .false.
        !> The singular time [s], the exponent n [-], the rms residual of log Omega [-], the
        !> rows fitted and the decades of t0 - t they span
        real(wp) :: t0 = 0.0_wp, exponent = 0.0_wp, residual = 0.0_wp, decades = 0.0_wp
        integer :: rows = 0
        !> The line's prefactor C of Omega = C (t0 - t)^(-n) [rad/s^(1-n)]
        real(wp) :: prefactor = 0.0_wp
    end type singularity_fit_type

    type, extends(watch_type) :: dissipation_watch_type
        !> The part whose rim dissipates (model order)
        integer :: part = 1
        !> Of a dataset's several CONTACTs, the rim's ("CONTACT/7 (line 13)"), which starts
        !> the summary's lines
        character(len=:), allocatable :: label
        !> The rows so far: time [s] and Omega = |psidot| [rad/s] (grown by doubling)
        real(wp), allocatable :: times(:), rates(:)
        integer :: rows = 0
        !> The energy each law dissipated from the start to the last row [J] (its power
        !> integrated with the state: rollcon_rim_dissipation's rolling_work, air_work; from
        !> an integrator that does not integrate them, the trapezoidal rule over the rows),
        !> and the last row's powers [W]
        real(wp) :: rolling_work = 0.0_wp, air_work = 0.0_wp
        real(wp) :: last_rolling = 0.0_wp, last_air = 0.0_wp
        !> Baumgarte rate of the run [1/s]; scratch accelerations and multipliers
        real(wp) :: baumgarte = 0.0_wp
        real(wp), allocatable :: a(:), lambda(:)
        !> The law's switches: their times [s], phidot there [rad/s], the held moment's room
        !> delta F_n - |Q_phi| there [N m] (at a release; else 0) and kinds (switch_sign: a
        !> new sign at a root of phidot or the start, switch_hold, switch_release)
        real(wp), allocatable :: switch_times(:), switch_rates(:), switch_rooms(:)
        integer, allocatable :: switch_kinds(:)
        !> A held rolling resistance found (action_stop), else action_restart
        type(watch_event_type) :: held
    contains
        procedure :: prepare
        procedure :: root_count
        procedure :: roots
        procedure :: fired
        procedure :: restart_problem
        procedure :: start_problem
        procedure :: stop_request
        procedure :: decide_rolling_sign
        procedure :: note_switch
        procedure :: column_names
        procedure :: fill_columns
        procedure :: summary_lines
    end type dissipation_watch_type

contains

    !> The part must be one of the model's; the rows are sized for the run's output times.
    subroutine prepare(self, eq, settings, error)
        class(dissipation_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        type(error_type), allocatable, intent(out) :: error
        integer :: capacity

        if (self%part < 1 .or. self%part > size(eq%model%parts)) then
            call fatal_error(error, "the dissipating part is number " // to_text(self%part) &
                & // " in model order; the model has " // to_text(size(eq%model%parts)) &
                & // " parts", stat_input)
            return
        end if
        capacity = 64
        if (settings%output_step > 0.0_wp) capacity = capacity + nint(min(1.0e7_wp, &
            & settings%end_time/settings%output_step))
        if (allocated(self%times)) deallocate(self%times, self%rates)
        allocate(self%times(capacity), self%rates(capacity), source=0.0_wp)
        self%rows = 0
        self%rolling_work = 0.0_wp
        self%air_work = 0.0_wp
        self%last_rolling = 0.0_wp
        self%last_air = 0.0_wp
        eq%dissipation%rolling_work = 0.0_wp
        eq%dissipation%air_work = 0.0_wp
        self%baumgarte = settings%baumgarte()
        if (allocated(self%a)) deallocate(self%a, self%lambda)
        allocate(self%a(eq%n), self%lambda(eq%nc), source=0.0_wp)
        if (allocated(self%switch_times)) deallocate(self%switch_times, self%switch_rates, &
            & self%switch_rooms, self%switch_kinds)
        allocate(self%switch_times(0), self%switch_rates(0), self%switch_rooms(0), &
            & self%switch_kinds(0))
        self%held = watch_event_type(action=action_restart)
        eq%dissipation%sign_given = .false.
        eq%dissipation%rolling_sign = 0.0_wp
        eq%dissipation%held = .false.
        eq%dissipation%held_moment = 0.0_wp
    end subroutine prepare

    !> One event function while rolling resistance acts: phidot.
    pure integer function root_count(self, eq)
        class(dissipation_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq

        root_count = merge(1, 0, eq%dissipation%rolling_resistance > 0.0_wp)
    end function root_count

    !> phidot [rad/s], the rolling rate whose sign rolling resistance's law takes; while held,
    !> delta F_n - |Q_phi| [N m] from the equations at this state (the held moment's room).
    subroutine roots(self, eq, settings, time, q, u, g, error, lambda, a)
        class(dissipation_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        type(run_settings_type), intent(in) :: settings
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: lambda(:), a(:)

        if (eq%dissipation%held) then
            call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
            if (allocated(error)) return
            g(1) = eq%dissipation%rolling_resistance*eq%dissipation%normal_force &
                & - abs(eq%dissipation%held_moment)
            return
        end if
        g(1) = u(6*self%part)
    end subroutine roots

    !> phidot reached zero: the law's sign is decided there (restart_problem).
    function fired(self, eq, k, time, q, u) result(event)
        class(dissipation_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        integer, intent(in) :: k
        real(wp), intent(in) :: time, q(:), u(:)
        type(watch_event_type) :: event

        event%action = action_restart
        event%limit = "rolling_resistance"
        event%message = "phidot reached zero at t = " // to_text(time) // " s"
    end function fired

    !> At a root of phidot = 0: the law's sign decided (decide_rolling_sign); at the held
    !> moment's reaching delta F_n: released, the law's sign that of the departure, against
    !> the moment that held (phiddot's sign without it).
    subroutine restart_problem(self, eq, time, q, u, error)
        class(dissipation_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: u(:)
        type(error_type), allocatable, intent(out) :: error

        if (eq%dissipation%held) then
            call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
            if (allocated(error)) return
            eq%dissipation%held = .false.
            call self%note_switch(time, u, switch_release, eq%dissipation%rolling_resistance &
                & *eq%dissipation%normal_force - abs(eq%dissipation%held_moment))
            if (eq%dissipation%held_moment /= 0.0_wp) then
                eq%dissipation%rolling_sign = -sign(1.0_wp, eq%dissipation%held_moment)
                return
            end if
        end if
        call self%decide_rolling_sign(eq, time, q, u, error)
    end subroutine restart_problem

    !> A switch of the law at time [s] with the rates u, of a kind (switch_sign, ...), the
    !> held moment's room there [N m] (0 but at a release).
    subroutine note_switch(self, time, u, kind, room)
        class(dissipation_watch_type), intent(inout) :: self
        real(wp), intent(in) :: time, u(:)
        integer, intent(in) :: kind
        real(wp), intent(in) :: room

        self%switch_times = [self%switch_times, time]
        self%switch_rates = [self%switch_rates, u(6*self%part)]
        self%switch_kinds = [self%switch_kinds, kind]
        self%switch_rooms = [self%switch_rooms, room]
    end subroutine note_switch

    !> At the start, or after rates that jumped (an impact): the law's sign is phidot's, or
    !> decided at phidot = 0; not held.
    subroutine start_problem(self, eq, time, q, u, error)
        class(dissipation_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        if (.not. eq%dissipation%rolling_resistance > 0.0_wp) return
        eq%dissipation%held = .false.
        if (u(6*self%part) /= 0.0_wp) then
            eq%dissipation%sign_given = .true.
            eq%dissipation%rolling_sign = sign(1.0_wp, u(6*self%part))
            return
        end if
        call self%decide_rolling_sign(eq, time, q, u, error)
    end subroutine start_problem

    !> The held rolling resistance's stop, when decide_rolling_sign found one.
    function stop_request(self) result(event)
        class(dissipation_watch_type), intent(in) :: self
        type(watch_event_type) :: event

        event = self%held
    end function stop_request

    !> Rolling resistance's sign at a state (t, q, u) with phidot at zero (the start, or a
    !> root), where the law is set-valued (|Q_phi| <= delta F_n): phiddot_0 from the equations
    !> without it; s = sign(phiddot_0), then phiddot_s with the law Q_phi = -delta F_n s (its
    !> normal force coupled as in every solve). When s phiddot_s > 0 the moment needed to hold
    !> phidot = 0 exceeds delta F_n: phidot leaves zero with sign s, and s is held until the
    !> next root. Otherwise (phiddot_0 = 0 too) the resistance holds the rim's run still:
    !> held (the equations' held_coupling) while the contact rolls; while it slides that is
    !> not modelled, and held becomes a stop with its message (in flight the law is idle).
    !> A switch is noted (note_switch) where the law changes: a sign is taken where there was
    !> none, or held, or another; a root that leaves the sign in effect as it was (an
    !> integrator reporting again the root it restarted from) is none.
    subroutine decide_rolling_sign(self, eq, time, q, u, error)
        class(dissipation_watch_type), intent(inout) :: self
        type(equations_type), intent(inout) :: eq
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: free, resisted, s, previous
        logical :: kept
        integer :: i

        i = 6*self%part
        ! the sign in effect, where a root leaves it as it was (an integrator reporting again
        ! the root of phidot = 0 it restarted from: IDA after a release, where phidot leaves
        ! zero in the released direction) no new sign is taken
        previous = eq%dissipation%rolling_sign
        kept = eq%dissipation%sign_given .and. .not. eq%dissipation%held &
            & .and. previous /= 0.0_wp
        eq%dissipation%sign_given = .true.
        eq%dissipation%held = .false.
        eq%dissipation%rolling_sign = 0.0_wp
        call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
        if (allocated(error)) return
        free = self%a(i)
        resisted = 0.0_wp
        s = 0.0_wp
        if (free /= 0.0_wp) then
            s = sign(1.0_wp, free)
            eq%dissipation%rolling_sign = s
            call eq%accelerations(time, q, u, self%baumgarte, self%a, self%lambda, error)
            if (allocated(error)) return
            resisted = self%a(i)
            if (s*resisted > 0.0_wp) then
                if (.not. (kept .and. s == previous)) call self%note_switch(time, u, &
                    & switch_sign, 0.0_wp)
                return
            end if
        end if
        if (eq%contact%flying) then
            ! in flight F_n = 0: the law does not act, nothing holds phidot
            eq%dissipation%rolling_sign = s
            if (.not. (kept .and. s == previous)) call self%note_switch(time, u, switch_sign, &
                & 0.0_wp)
            return
        end if
        eq%dissipation%rolling_sign = 0.0_wp
        if (.not. eq%contact%sliding) then
            eq%dissipation%held = .true.
            call self%note_switch(time, u, switch_hold, 0.0_wp)
            return
        end if
        self%held%action = action_stop
        self%held%limit = "rolling_held"
        self%held%message = "rolling resistance holds the rim's run still at t = " &
            & // to_text(time) // " s (theta = " // to_text(q(i - 1)) // " rad, psidot = " &
            & // to_text(u(i - 2)) // " rad/s, phidot = " // to_text(u(i)) // " rad/s) " &
            & // "while the contact slides: phiddot would be " // to_text(free) &
            & // " rad/s^2 without it and " // to_text(resisted) // " rad/s^2 against it, " &
            & // "so the moment needed to hold phidot = 0 is within delta F_n; that held " &
            & // "state is not modelled, the run stops here"
    end subroutine decide_rolling_sign

    subroutine column_names(self, eq, names)
        class(dissipation_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=name_length), allocatable, intent(out) :: names(:)

        names = dissipation_names
    end subroutine column_names

    !> The powers of the last evaluation at this row [W] and the energy dissipated from the
    !> start [J] (integrated with the state: rollcon_rim_dissipation's works); the row's time
    !> and Omega kept for the fit.
    subroutine fill_columns(self, eq, time, q, u, lambda, values)
        class(dissipation_watch_type), intent(inout) :: self
        type(equations_type), intent(in) :: eq
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        real(wp), intent(out) :: values(:)
        real(wp), allocatable :: grown(:)
        real(wp) :: step

        associate (rolling => eq%dissipation%rolling_power, air => eq%dissipation%air_power)
            if (eq%dissipation%works_integrated) then
                self%rolling_work = eq%dissipation%rolling_work
                self%air_work = eq%dissipation%air_work
            else if (self%rows > 0) then
                step = time - self%times(self%rows)
                self%rolling_work = self%rolling_work + 0.5_wp*(rolling + self%last_rolling)*step
                self%air_work = self%air_work + 0.5_wp*(air + self%last_air)*step
            end if
            self%last_rolling = rolling
            self%last_air = air
            values(1) = rolling
            values(2) = air
            values(3) = self%rolling_work + self%air_work
        end associate
        if (self%rows == size(self%times)) then
            ! more rows than the output times (events' rows): twice the room
            allocate(grown(2*size(self%times)), source=0.0_wp)
            grown(:self%rows) = self%times(:self%rows)
            call move_alloc(grown, self%times)
            allocate(grown(2*size(self%rates)), source=0.0_wp)
            grown(:self%rows) = self%rates(:self%rows)
            call move_alloc(grown, self%rates)
        end if
        self%rows = self%rows + 1
        self%times(self%rows) = time
        self%rates(self%rows) = abs(u(6*(self%part - 1) + 4))
    end subroutine fill_columns

    !> The energy each law dissipated; the law's switches counted by kind, then each at its
    !> time, once (the first listed_switches of them); and the fit of the singularity.
    function summary_lines(self, eq) result(text)
        class(dissipation_watch_type), intent(in) :: self
        type(equations_type), intent(in) :: eq
        character(len=:), allocatable :: text
        type(singularity_fit_type) :: fit
        integer :: k

        text = ""
        if (allocated(self%label)) text = self%label // ": "
        text = text // "dissipation: rolling resistance delta = " &
            & // to_text(eq%dissipation%rolling_resistance) // " m dissipated " &
            & // to_text(self%rolling_work) // " J, the air layer (coefficient pi/4 mu R^3 = " &
            & // to_text(eq%dissipation%air) // " N m s) " // to_text(self%air_work) // " J" &
            & // new_line("a")
        if (allocated(self%switch_kinds)) then
            if (size(self%switch_kinds) > 0) then
                if (allocated(self%label)) text = text // self%label // ": "
                text = text // "rolling resistance's law: its sign taken at phidot = 0 " &
                    & // times(count(self%switch_kinds == switch_sign)) // ", held " &
                    & // times(count(self%switch_kinds == switch_hold)) // " (phidot = 0 " &
                    & // "under the moment it needs), released " &
                    & // times(count(self%switch_kinds == switch_release)) // new_line("a")
                ! each switch once, as the contact's summary lists its switches
                do k = 1, min(size(self%switch_kinds), listed_switches)
                    text = text // "  t = " // to_text(self%switch_times(k)) // " s: "
                    select case (self%switch_kinds(k))
                    case (switch_hold)
                        text = text // "held at phidot = 0"
                    case (switch_release)
                        text = text // "released, phidot leaving zero"
                    case default
                        text = text // "its sign taken at phidot = 0"
                    end select
                    text = text // new_line("a")
                end do
                if (size(self%switch_kinds) > listed_switches) text = text // "  … and " &
                    & // to_text(size(self%switch_kinds) - listed_switches) // " more" &
                    & // new_line("a")
            end if
        end if
        if (self%rows == 0) return
        fit = fit_singularity(self%times(:self%rows), self%rates(:self%rows))
        ! a fit only of a run that ends at its singularity (settles); else nothing to say
        if (.not. (fit%made .and. fit%settles)) return
        text = text // "finite-time singularity: Omega = |psidot| ~ (t0 - t)^(-n) fitted " &
            & // "over " // to_text(fit%rows) // " rows spanning " &
            & // to_text(real(nint(100.0_wp*fit%decades), wp)/100.0_wp) &
            & // " decades of t0 - t: t0 = " // to_text(fit%t0) // " s, n = " &
            & // to_text(fit%exponent) // " (rms residual of ln Omega " &
            & // to_text(fit%residual) // ")" // new_line("a")

    contains

        !> "1 time", "3 times".
        pure function times(n) result(words)
            integer, intent(in) :: n
            character(len=:), allocatable :: words

            words = to_text(n) // trim(merge(" time ", " times", n == 1))
        end function times
    end function summary_lines

    !> Fit of Omega ~ (t0 - t)^(-n) to rows (t_i, Omega_i), t ascending [s, rad/s]: the rows
    !> after the first tenth of their time span (the start's transient) up to the largest
    !> Omega (t_end; after it the disk falls flat, the law broken down), a straight line of
    !> ln Omega against ln(t0 - t) by weighted least squares, each row weighted by the span
    !> of ln(t0 - t) it stands for (its share of time over t0 - t_i, so that every decade
    !> counts alike, not only the many rows far from t0), and t0 > t_end the one that
    !> minimises the weighted mean square residual: a scan of 64 values of ln(t0 - t_end)
    !> over [ln(1e-6 T), ln T] (T the fitted rows' span) and a golden-section search about
    !> the best. Not made with fewer than fit_rows_min rows or a rate not positive and finite.
    !> settles: the rule at settle_tail_fraction (the rows end at the singularity).
    pure function fit_singularity(times, rates) result(fit)
        real(wp), intent(in) :: times(:), rates(:)
        type(singularity_fit_type) :: fit
        integer, parameter :: scan = 64, golden_steps = 60
        real(wp), parameter :: golden = 0.6180339887498949_wp
        real(wp) :: span, t_end, lo, hi, z, best, value, a, b, c, d, fc, fd, slope, intercept
        integer :: first, n, k, best_k

        ! up to the largest rate: after it the disk falls flat faster than it precesses
        ! (Moffatt's breakdown of the steady approximation), no part of the law
        if (size(times) < fit_rows_min) return
        n = maxloc(rates, dim=1)
        if (n < fit_rows_min) return
        t_end = times(n)
        span = t_end - times(1)
        if (.not. span > 0.0_wp) return
        first = 1
        do while (times(first) < times(1) + skipped_fraction*span)
            first = first + 1
        end do
        if (n - first + 1 < fit_rows_min) return
        if (.not. all(rates(first:) > 0.0_wp .and. ieee_is_finite(rates(first:)))) return
        span = t_end - times(first)
        lo = log(gap_min_fraction*span)
        hi = log(gap_max_fraction*span)
        best = huge(1.0_wp)
        best_k = 0
        do k = 0, scan
            z = lo + (hi - lo)*real(k, wp)/real(scan, wp)
            call line(z, value, slope, intercept)
            if (value < best) then
                best = value
                best_k = k
            end if
        end do
        a = lo + (hi - lo)*real(max(best_k - 1, 0), wp)/real(scan, wp)
        b = lo + (hi - lo)*real(min(best_k + 1, scan), wp)/real(scan, wp)
        c = b - golden*(b - a)
        d = a + golden*(b - a)
        call line(c, fc, slope, intercept)
        call line(d, fd, slope, intercept)
        do k = 1, golden_steps
            if (fc < fd) then
                b = d
                d = c
                fd = fc
                c = b - golden*(b - a)
                call line(c, fc, slope, intercept)
            else
                a = c
                c = d
                fc = fd
                d = a + golden*(b - a)
                call line(d, fd, slope, intercept)
            end if
        end do
        z = 0.5_wp*(a + b)
        call line(z, value, slope, intercept)
        fit%made = .true.
        fit%prefactor = exp(intercept)
        fit%t0 = t_end + exp(z)
        fit%exponent = -slope
        fit%residual = sqrt(value)
        fit%rows = n - first + 1
        fit%decades = log10((fit%t0 - times(first))/(fit%t0 - t_end))
        ! the run ends at this singularity: its rows stop soon after the peak, the rate grew,
        ! the line fits, t0 is a minimum inside the range searched
        fit%settles = times(size(times)) - t_end <= settle_tail_fraction*span &
            & .and. rates(n) >= settle_growth_min*rates(first) &
            & .and. fit%residual <= settle_residual_max &
            & .and. z > lo + 2.0_wp*(hi - lo)/real(scan, wp)

    contains

        !> The weighted mean square residual, the slope and the intercept of the line at
        !> t0 = t_end + e^z.
        pure subroutine line(z, residual, slope, intercept)
            real(wp), intent(in) :: z
            real(wp), intent(out) :: residual, slope, intercept
            real(wp) :: t0, w, x, y, sw, sx, sy, sxx, sxy, mean_x, mean_y
            integer :: i

            t0 = t_end + exp(z)
            sw = 0.0_wp
            sx = 0.0_wp
            sy = 0.0_wp
            sxx = 0.0_wp
            sxy = 0.0_wp
            do i = first, n
                w = weight(i, t0)
                x = log(t0 - times(i))
                y = log(rates(i))
                sw = sw + w
                sx = sx + w*x
                sy = sy + w*y
            end do
            mean_x = sx/sw
            mean_y = sy/sw
            do i = first, n
                w = weight(i, t0)
                x = log(t0 - times(i)) - mean_x
                y = log(rates(i)) - mean_y
                sxx = sxx + w*x*x
                sxy = sxy + w*x*y
            end do
            slope = sxy/sxx
            intercept = mean_y - slope*mean_x
            residual = 0.0_wp
            do i = first, n
                residual = residual + weight(i, t0)*(log(rates(i)) - intercept &
                    & - slope*log(t0 - times(i)))**2
            end do
            residual = residual/sw
        end subroutine line

        !> Row i's weight: half the time to its neighbours over t0 - t_i.
        pure real(wp) function weight(i, t0)
            integer, intent(in) :: i
            real(wp), intent(in) :: t0

            weight = 0.5_wp*(times(min(i + 1, n)) - times(max(i - 1, first)))/(t0 - times(i))
        end function weight
    end function fit_singularity

end module rollcon_dissipation_watch
