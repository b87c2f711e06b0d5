! SPDX-License-Identifier: MIT
!> A dataset's CONTACT (rollcon_adm_contacts, rollcon_adm_contact) and the sphere in the
!> contact watch (rollcon_contact_watch): a ball thrown along the ground without spin slides,
!> its slip's direction fixed, and rolls at (5/7) v0 after 2 v0 / (7 mu g); a ball dropped with
!> restitution e bounces to e^2 of its drop height, no impact raising the energy; the coin as a
!> dataset CONTACT on its rim gives the numbers of data/sliding_coin.nml; what rollcon cannot
!> honour is refused with the CONTACT's line and key, and ADAMS's regularisation is named as
!> not used.
module test_contact_datasets
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_contacts, only : graphics_ellipsoid, graphics_cylinder, graphics_plane
    use rollcon_adm_contact, only : contact_shape_type, contact_shape
    use rollcon_dataset_source, only : dataset_source_type, new_dataset_source
    use rollcon_scene, only : scene_type, read_scene
    use rollcon_simulation, only : run_options_type, simulate, history_type, run_summary_type, &
        & status_completed
    use rollcon_output_layout, only : coord_x, coord_z, coord_xdot, coord_ydot, &
        & coord_zdot
    use rollcon_output_files, only : write_text_file, make_folders
    use rollcon_input_files, only : read_input_file, text_input_limit
    use rollcon_contact_watch, only : contact_watch_type, mode_rolling, mode_sliding, &
        & mode_flight
    use test_contact_modes, only : run_scene
    use contact_dissipation_runs, only : test_rim_beside_ball
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_contact_datasets

    !> Where the refusals' datasets are written
    character(len=*), parameter :: folder = "build/test_contact_datasets"

contains

    subroutine collect_contact_datasets(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("sphere-thrown-rolls-at-five-sevenths", test_sphere_thrown), &
            & new_unittest("sphere-thrown-with-side-spin-slips-straight", test_side_spin), &
            & new_unittest("sphere-bounces-to-e-squared", test_sphere_bounce), &
            & new_unittest("sphere-thrown-and-bounced-on-ida", test_spheres_on_ida), &
            & new_unittest("coin-contact-dataset-as-its-scene", test_coin_dataset), &
            & new_unittest("two-spheres-each-rolls-at-its-own-t-star", test_two_spheres), &
            & new_unittest("ball-and-coin-each-as-its-own-dataset", test_ball_and_coin), &
            & new_unittest("contact-geometries-read", test_geometries), &
            & new_unittest("contact-refusals-name-line-and-key", test_refusals), &
            & new_unittest("contact-rolling-resistance-decelerates-the-rim", &
            & test_rolling_resistance), &
            & new_unittest("rim-dissipation-beside-a-ball-as-each-alone", test_rim_beside_ball)]
    end subroutine collect_contact_datasets

    !> Read and build a dataset (initial conditions as rollcon run makes them), run it to its
    !> SIMULATE's end with every row kept, and copy its contact watch (of several, the
    !> which-th: its CONTACT's, in the dataset's order).
    subroutine run_contact_dataset(path, adm, history, contact, error, which)
        character(len=*), intent(in) :: path
        type(adm_model_type), intent(out) :: adm
        type(history_type), intent(out) :: history
        type(contact_watch_type), intent(out) :: contact
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: which
        type(dataset_source_type) :: source
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: summary
        procedure(ucosub_interface), pointer :: none
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report
        integer :: k, seen, wanted

        wanted = 1
        if (present(which)) wanted = which
        none => null()
        call read_adm(path, adm, error)
        if (allocated(error)) return
        source = new_dataset_source(adm, path)
        call source%build(none, problem, q0, u0, report, error)
        if (allocated(error)) return
        options%end_time = adm%run%settings%end_time
        options%output_step = adm%run%settings%output_step
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error, history)
        if (allocated(error)) return
        if (summary%status /= status_completed) then
            call fatal_error(error, path // " did not complete: " // summary%message)
            return
        end if
        seen = 0
        do k = 1, size(problem%watches)
            select type (watch => problem%watches(k)%watch)
            type is (contact_watch_type)
                seen = seen + 1
                if (seen == wanted) contact = watch
            end select
        end do
        call problem%release()
    end subroutine run_contact_dataset

    !> data/sphere_thrown.adm: a uniform ball (I = 2 m R^2 / 5) thrown along +X at v0 = 1 m/s
    !> without spin, mu = 0.3. Sliding, v = v0 - mu g t and R omega = (5/2) mu g t, so the slip
    !> stops at t* = 2 v0 / (7 mu g), at (5/7) v0, after (12/49) v0^2 / (mu g), with m v0^2 / 7
    !> dissipated; the friction acts along -X alone, so the slip's direction stays +X. It
    !> then rolls uniformly, so the end state gives the state at t*.
    subroutine test_sphere_thrown(error)
        type(error_type), allocatable, intent(out) :: error

        call sphere_thrown("data/sphere_thrown.adm", error)
    end subroutine test_sphere_thrown

    !> The thrown ball's checks on the dataset at path (test_sphere_thrown): of several
    !> CONTACTs the which-th's ball (model part which, its columns "contact<id>_...", the
    !> energy lost every ball's).
    subroutine sphere_thrown(path, error, which)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: which
        ! Switch time [s]: the slip falls at (7/2) mu g = 10.3 m/s^2 and is known to its
        ! integration error at rtol 1e-10 and the stop's guard, ~1e-10 m/s: ~1e-11 s;
        ! measured 7.0e-12 s, bound 5e-11 s (a tenfold loss, 7e-11 s, fails)
        real(wp), parameter :: time_tol = 5.0e-11_wp
        ! Speed after the switch [m/s]: sliding keeps the angular momentum about the contact
        ! point (friction acts there), m v R + I omega, so the rolling speed is (5/7) v0
        ! whenever the switch fires; only integration error moves it: measured 2.2e-16,
        ! bound 1e-13
        real(wp), parameter :: speed_tol = 1.0e-13_wp
        ! Distance slid [m]: the switch time's error times (5/7) v0; measured 5.0e-12 at
        ! v0 = 1 m/s, bound 3e-11 per m/s of v0 (at 2 m/s and mu = 0.2, measured 3.9e-11)
        real(wp), parameter :: distance_tol = 3.0e-11_wp
        ! Energy lost [J]: fixed by the speeds before and after; measured 2.8e-16 J, bound
        ! 1e-13 J
        real(wp), parameter :: energy_tol = 1.0e-13_wp
        ! The slip across its direction at the start, |slip_y| / |slip| while sliding: nothing
        ! acts across it, so only rounding turns it; measured 1.7e-14, bound 1e-12
        real(wp), parameter :: turn_tol = 1.0e-12_wp
        type(adm_model_type) :: adm
        type(history_type) :: history
        type(contact_watch_type) :: contact
        real(wp) :: v0, mu, g, t_star, t_end, slid, lost
        real(wp), allocatable :: time(:), energy(:), slip_x(:), slip_y(:), mode(:)
        character(len=:), allocatable :: prefix
        integer :: k, e, c, p

        c = 1
        if (present(which)) c = which
        call run_contact_dataset(path, adm, history, contact, error, c)
        if (allocated(error)) return
        ! the c-th CONTACT's ball: model part c (the ground is the dataset's first PART)
        p = c
        prefix = ""
        if (size(adm%contacts) > 1) prefix = "contact" // to_text(adm%contacts(c)%id) // "_"
        v0 = adm%parts(p + 1)%velocity(1)
        mu = adm%contacts(c)%mu_dynamic
        g = -adm%gravity(3)
        lost = sum(adm%parts(2:)%mass*adm%parts(2:)%velocity(1)**2)/7.0_wp
        t_star = 2.0_wp*v0/(7.0_wp*mu*g)
        call check(error, contact%sphere .and. contact%radius == 0.05_wp, "a sphere of " &
            & // "radius 0.05 m (GRAPHICS/2, XSCALE = 0.1)")
        if (allocated(error)) return
        call check(error, contact%initial_mode, mode_sliding, "the thrown ball starts sliding")
        if (allocated(error)) return
        call check(error, size(contact%switch_times), 1, "one switch")
        if (allocated(error)) return
        call check(error, contact%switch_modes(1), mode_rolling, "the switch is to rolling")
        if (allocated(error)) return
        call check(error, contact%switch_times(1), t_star, "t* = 2 v0/(7 mu g) [s]", &
            & abs_tol=time_tol)
        if (allocated(error)) return
        associate (last => history%count)
            t_end = history%rows(1, last)
            call check(error, history%rows(history%layout%part_column(p, coord_xdot), last), &
                & 5.0_wp*v0/7.0_wp, "speed after the switch, (5/7) v0 [m/s]", &
                & abs_tol=speed_tol)
            if (allocated(error)) return
            slid = history%rows(history%layout%part_column(p, coord_x), last) &
                & - 5.0_wp*v0/7.0_wp*(t_end - contact%switch_times(1))
            call check(error, slid, 12.0_wp/49.0_wp*v0**2/(mu*g), "distance slid, " &
                & // "(12/49) v0^2/(mu g) [m]", abs_tol=distance_tol*max(1.0_wp, abs(v0)))
            if (allocated(error)) return
            e = history%layout%energy_column()
            call check(error, history%rows(e, 1) - history%rows(e, last), lost, &
                & "energy lost, m v0^2/7 (each ball's) [J]", abs_tol=energy_tol)
            if (allocated(error)) return
        end associate
        time = history%column(1)
        energy = history%column(history%layout%energy_column())
        mode = history%column(history%layout%column(prefix // "mode"))
        slip_x = history%column(history%layout%column(prefix // "slip_x"))
        slip_y = history%column(history%layout%column(prefix // "slip_y"))
        do k = 1, history%count
            if (nint(mode(k)) /= mode_sliding) cycle
            call check(error, slip_x(k) > 0.0_wp .and. abs(slip_y(k)) <= turn_tol &
                & *abs(slip_x(k)), "the slip along +X while sliding, t = " // to_text(time(k)) &
                & // " s: (" // to_text(slip_x(k)) // ", " // to_text(slip_y(k)) // ") m/s")
            if (allocated(error)) return
        end do
        call check(error, count(nint(mode) == mode_sliding), int(t_star/0.001_wp) + 1, &
            & "rows sliding (t = 0 to t*)")
    end subroutine sphere_thrown

    !> A ball thrown with a side spin, so that its slip is not along its centre's velocity and
    !> the slip's direction could turn (data/sphere_thrown.adm's ball, m = 1 kg, R = 0.05 m,
    !> I = 2 m R^2 / 5, mu = 0.3, thrown along +X at v0 = 1 m/s with omega0 = (10, 0, 20)
    !> rad/s in ground axes: a spin about the throw's own axis and one about the vertical).
    !> The contact point is at r = -R Z from the centre, so the slip is v_s = v + omega x r
    !> = (v_x - R omega_y, v_y + R omega_x): v_s0 = (1, 0.5) m/s, at 26.6 degrees to v0
    !> (omega_z slips nothing). Sliding, the friction F = -mu m g s_hat (s_hat = v_s/|v_s|)
    !> gives m v' = F and I omega' = r x F, so (omega' x r) = ((r x F) x r)/I = R^2 F/I
    !> (r normal to F), and v_s' = F/m + R^2 F/I = -(1 + 5/2) mu g s_hat = -(7/2) mu g s_hat:
    !> the slip shrinks along its own direction, which stays s_hat0, and vanishes at
    !> t* = |v_s0|/((7/2) mu g) = 0.108542 s; the centre then moves at v0 - mu g t* s_hat0
    !> = v0 - (2/7) v_s0 = (5/7, -1/7) m/s and rolls on at it (rolling on a level plane keeps
    !> the centre's velocity: the friction that rolling needs is zero). omega_z is kept
    !> (the friction's moment about the centre, r x F, is horizontal).
    subroutine test_side_spin(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: nl = new_line("a")
        ! The bounds are the integration's global error at rtol 1e-10: unlike the planar
        ! throw's, whose every coordinate is a polynomial in t that BDF integrates nearly
        ! exactly, this ball's orientation turns about a tilting axis (the Euler angles are
        ! not polynomials), so the speeds carry an error of ~1e-9 m/s; at RTOL=1e-11 every
        ! measured error below fell 3 to 25 times (measured, so it is that error, not the law).
        ! Switch time [s]: the slip's error over its deceleration (7/2) mu g = 10.3 m/s^2;
        ! measured 4.7e-10 s, bound 2e-9 s (a tenfold loss fails)
        real(wp), parameter :: time_tol = 2.0e-9_wp
        ! Velocity after the switch [m/s]: sliding keeps the angular momentum about the
        ! contact point, so the rolling velocity is v0 - (2/7) v_s0 whenever the switch
        ! fires; measured 4.4e-10 (X) and 1.5e-9 (Y), bound 5e-9 (a tenfold loss fails)
        real(wp), parameter :: speed_tol = 5.0e-9_wp
        ! The slip's turn while sliding, |s_hat0 x v_s| / |v_s|: nothing turns it; the slip's
        ! error across s_hat0, ~1e-9 m/s, over the least slip of a sliding row, (7/2) mu g
        ! (t* - 0.108 s) = 5.6e-3 m/s; measured 1.4e-7 (at that row), bound 5e-7 (a slip
        ! turning at a thousandth of its angle to v0, 5e-4 rad, fails a thousandfold)
        real(wp), parameter :: turn_tol = 5.0e-7_wp
        real(wp), parameter :: v0(2) = [1.0_wp, 0.0_wp], omega0(3) = [10.0_wp, 0.0_wp, &
            & 20.0_wp], radius = 0.05_wp, mu = 0.3_wp, g = 9.81_wp
        character(len=:), allocatable :: path
        type(adm_model_type) :: adm
        type(history_type) :: history
        type(contact_watch_type) :: contact
        real(wp) :: slip0(2), s_hat(2), t_star, v_end(2), turn
        real(wp), allocatable :: time(:), mode(:), slip_x(:), slip_y(:)
        integer :: k, sliding_rows

        slip0 = [v0(1) - radius*omega0(2), v0(2) + radius*omega0(1)]
        s_hat = slip0/norm2(slip0)
        t_star = norm2(slip0)/(3.5_wp*mu*g)
        v_end = v0 - 2.0_wp/7.0_wp*slip0
        call make_folders(folder, error)
        if (allocated(error)) return
        path = folder // "/side_spin.adm"
        ! the CM marker turned 90 degrees about x, as data/sphere_thrown.adm's: its axes are
        ! ground (X, Z, -Y), so WX, WY, WZ about them are omega0's X, Z and -Y components
        call write_text_file(path, "sphere thrown with a side spin" // nl &
            & // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl // "MARKER/1, PART=1" // nl &
            & // "PART/2, MASS=1, CM=21, IP=1.0E-3, 1.0E-3, 1.0E-3, QG=0, 0, 0.05" // nl &
            & // ", VX=1, WX=10, WY=20, WZ=0" // nl &
            & // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // nl // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "GRAPHICS/1, PLANE, RM=1, XMIN=-1, XMAX=1, YMIN=-1, YMAX=1" // nl &
            & // "GRAPHICS/2, ELLIPSOID, CM=21, XSCALE=0.1, YSCALE=0.1, ZSCALE=0.1" // nl &
            & // "CONTACT/1, IGEOM=2, JGEOM=1, POISSON, RESTITUTION_COEFFICIENT=0.5" // nl &
            & // ", COULOMB_FRICTION=ON, MU_STATIC=0.3, MU_DYNAMIC=0.3" // nl &
            & // "SIMULATE/DYNAMIC, END=0.3, DTOUT=0.001" // nl &
            & // "INTEGRATOR/FORMULATION=CVODE, RTOL=1.0E-10, ATOL=1.0E-12" // nl // "END" // nl, &
            & error)
        if (allocated(error)) return
        call run_contact_dataset(path, adm, history, contact, error)
        if (allocated(error)) return
        call check(error, contact%initial_mode, mode_sliding, "the thrown ball starts sliding")
        if (allocated(error)) return
        call check(error, size(contact%switch_times), 1, "one switch")
        if (allocated(error)) return
        call check(error, contact%switch_modes(1), mode_rolling, "the switch is to rolling")
        if (allocated(error)) return
        call check(error, contact%switch_times(1), t_star, "t* = |v_s0|/((7/2) mu g) [s]", &
            & abs_tol=time_tol)
        if (allocated(error)) return
        associate (last => history%count)
            call check(error, history%rows(history%layout%part_column(1, coord_xdot), last), &
                & v_end(1), "X velocity after the switch, v0 - (2/7) v_s0 [m/s]", &
                & abs_tol=speed_tol)
            if (allocated(error)) return
            call check(error, history%rows(history%layout%part_column(1, coord_ydot), last), &
                & v_end(2), "Y velocity after the switch, -(2/7) v_s0_y [m/s]", &
                & abs_tol=speed_tol)
            if (allocated(error)) return
        end associate
        time = history%column(1)
        mode = history%column(history%layout%column("mode"))
        slip_x = history%column(history%layout%column("slip_x"))
        slip_y = history%column(history%layout%column("slip_y"))
        sliding_rows = 0
        do k = 1, history%count
            if (nint(mode(k)) /= mode_sliding) cycle
            sliding_rows = sliding_rows + 1
            ! the slip's component across s_hat0, relative to its size; and along it, positive
            turn = abs(s_hat(1)*slip_y(k) - s_hat(2)*slip_x(k))/hypot(slip_x(k), slip_y(k))
            call check(error, s_hat(1)*slip_x(k) + s_hat(2)*slip_y(k) > 0.0_wp .and. turn &
                & <= turn_tol, "the slip along s_hat0 = (" // to_text(s_hat(1)) // ", " &
                & // to_text(s_hat(2)) // ") while sliding, t = " // to_text(time(k)) &
                & // " s: (" // to_text(slip_x(k)) // ", " // to_text(slip_y(k)) // ") m/s")
            if (allocated(error)) return
        end do
        call check(error, sliding_rows, int(t_star/0.001_wp) + 1, "rows sliding (t = 0 to t*)")
    end subroutine test_side_spin

    !> data/sphere_bounce.adm: a ball let go at rest with its lowest point h = 0.1 m up, e =
    !> 0.8. It lands at t = sqrt(2 h / g) and leaves at e times its landing speed, so in its
    !> first flight after the impact z - R + zdot^2 / (2 g) (the apex of a ballistic flight,
    !> the same at every row of it) is e^2 h. Every impact's rebound is -e times its approach
    !> until the capture, and none raises the energy; the ball ends on the ground, rolling.
    subroutine test_sphere_bounce(error)
        type(error_type), allocatable, intent(out) :: error

        call sphere_bounce("data/sphere_bounce.adm", error)
    end subroutine test_sphere_bounce

    !> The dropped ball's checks on the dataset at path (test_sphere_bounce): of several
    !> CONTACTs the which-th's ball (model part which), and its contact watch. The landing's
    !> and the apex's bounds grow as the square root of the model's parts: the integrator's
    !> error test is a root mean square over every part's states, so beside a part whose
    !> error is small the ball's may grow by that factor (the local error per component
    !> that the norm allows).
    subroutine sphere_bounce(path, error, which, watch)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in), optional :: which
        type(contact_watch_type), intent(out), optional :: watch
        ! Landing time [s]: the touchdown's root to the event tolerance (~1e-11 s at rtol
        ! 1e-10); measured 2.1e-11 s, bound 1e-10 s (the first apex below would shift by
        ! 2 g h e^2 dt / v ~ 1e-11 m)
        real(wp), parameter :: time_tol = 1.0e-10_wp
        ! First apex [m]: the flight is integrated to rtol 1e-10 and the impact applied at the
        ! located root, where the height is off by ~1e-12 m and the speed by g dt ~ 1e-10 m/s;
        ! measured 6.3e-11 m at the worst of its 229 rows, bound 1e-10 m (a tenfold loss fails);
        ! beside data/ball_and_coin.adm's coin 1.06e-10 m, bound 1.4e-10 m (share, below)
        real(wp), parameter :: apex_tol = 1.0e-10_wp
        ! Rebound over approach [-]: the impact law's Poisson restitution, exact up to rounding
        ! of the impulse's solve; bound 1e-12
        real(wp), parameter :: ratio_tol = 1.0e-12_wp
        type(adm_model_type) :: adm
        type(history_type) :: history
        type(contact_watch_type) :: contact
        real(wp) :: h, e, g, radius, apex, share
        real(wp), allocatable :: time(:), z(:), zdot(:)
        integer :: k, flights, c

        c = 1
        if (present(which)) c = which
        call run_contact_dataset(path, adm, history, contact, error, c)
        if (allocated(error)) return
        if (present(watch)) watch = contact
        share = sqrt(real(count(.not. adm%parts%ground), wp))
        radius = contact%radius
        h = adm%parts(c + 1)%qg(3) - radius
        e = adm%contacts(c)%restitution
        g = -adm%gravity(3)
        call check(error, contact%initial_mode, mode_flight, "the ball starts in flight")
        if (allocated(error)) return
        call check(error, size(contact%switch_times) >= 2, "at least two bounces, got " &
            & // to_text(size(contact%switch_times)) // " switches")
        if (allocated(error)) return
        call check(error, contact%switch_times(1), sqrt(2.0_wp*h/g), "first landing, " &
            & // "sqrt(2 h/g) [s]", abs_tol=time_tol*share)
        if (allocated(error)) return
        do k = 1, size(contact%switch_times)
            associate (d => contact%switch_details(k))
                call check(error, d%impact, "switch " // to_text(k) // " is an impact")
                if (allocated(error)) return
                call check(error, d%energy_after <= d%energy_before, "impact " // to_text(k) &
                    & // " raises no energy: " // to_text(d%energy_before) // " J -> " &
                    & // to_text(d%energy_after) // " J")
                if (allocated(error)) return
                if (d%captured) cycle
                call check(error, -d%rebound/d%approach, e, "impact " // to_text(k) &
                    & // ": rebound / approach = e", abs_tol=ratio_tol)
                if (allocated(error)) return
            end associate
        end do
        call check(error, contact%switch_modes(size(contact%switch_modes)), mode_rolling, &
            & "the last impact is captured: the ball rests on the ground")
        if (allocated(error)) return
        time = history%column(1)
        z = history%column(history%layout%part_column(c, coord_z))
        zdot = history%column(history%layout%part_column(c, coord_zdot))
        flights = 0
        do k = 1, history%count
            if (time(k) <= contact%switch_times(1)) cycle
            if (time(k) >= contact%switch_times(2)) exit
            flights = flights + 1
            apex = z(k) - radius + zdot(k)**2/(2.0_wp*g)
            call check(error, apex, e**2*h, "first apex, e^2 h, from the row at t = " &
                & // to_text(time(k)) // " s [m]", abs_tol=apex_tol*share)
            if (allocated(error)) return
        end do
        call check(error, flights > 100, "the first flight spans rows, got " // to_text(flights))
    end subroutine sphere_bounce

    !> The thrown and the dropped ball in the DAE form (INTEGRATOR/FORMULATION=IDA, the
    !> datasets otherwise as shipped): the same closed forms to the same bounds (IDA's
    !> residual carries sliding's friction from the normal multiplier, flight's rows dropped:
    !> rollcon_dae; each switch restarts IDA from the consistent state).
    subroutine test_spheres_on_ida(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: names(3) = [character(len=18) :: "sphere_thrown", &
            & "sphere_bounce", "two_spheres_thrown"]
        character(len=:), allocatable :: text, path
        integer :: k

        call make_folders(folder, error)
        if (allocated(error)) return
        do k = 1, size(names)
            call read_input_file("data/" // trim(names(k)) // ".adm", "dataset", &
                & text_input_limit, text, error)
            if (allocated(error)) return
            path = folder // "/" // trim(names(k)) // "_ida.adm"
            call write_text_file(path, replaced(text, "FORMULATION=CVODE", "FORMULATION=IDA"), &
                & error)
            if (allocated(error)) return
            if (k == 1) call sphere_thrown(path, error)
            if (k == 2) call sphere_bounce(path, error)
            if (k == 3) then
                ! two contacts: each ball's mode, friction and switch in the DAE's residual
                call sphere_thrown(path, error, 1)
                if (.not. allocated(error)) call sphere_thrown(path, error, 2)
            end if
            if (allocated(error)) then
                error%message = "on IDA: " // error%message
                return
            end if
        end do
    end subroutine test_spheres_on_ida

    !> data/two_spheres_thrown.adm: two balls thrown side by side, each on its own CONTACT
    !> (PART/2 at 1 m/s with mu = 0.3, PART/3 at 2 m/s with mu = 0.2): each slides and rolls
    !> at (5/7) v0 from its own t* = 2 v0 / (7 mu g), to the single ball's bounds
    !> (sphere_thrown, on the contact's own columns contact<id>_mode, _slip_x, _slip_y; the
    !> energy lost both balls'), the two switches 0.19 s apart, each contact's mode its own.
    subroutine test_two_spheres(error)
        type(error_type), allocatable, intent(out) :: error
        integer :: c

        do c = 1, 2
            call sphere_thrown("data/two_spheres_thrown.adm", error, c)
            if (allocated(error)) then
                error%message = "CONTACT " // to_text(c) // " of two: " // error%message
                return
            end if
        end do
    end subroutine test_two_spheres

    !> data/ball_and_coin.adm: data/sphere_bounce.adm's ball (CONTACT/1) and
    !> data/sliding_coin.adm's coin (CONTACT/2) in one model. The ball gives its dataset's
    !> closed forms to their bounds (sphere_bounce: first landing, first apex e^2 h, rebound
    !> over approach e, no impact adding energy, captured at the end) and its dataset's
    !> impacts, as many and the first at the same time; the coin its dataset's (t* =
    !> v0 / (3 mu g), (2/3) v0 after it, the distance slid, test_coin_dataset's bounds), at
    !> every row after its switch while the ball's 43 impacts come and go (an impact of one
    !> part leaves the other's velocity alone); the energy lost is the coin's m v0^2 / 6 and
    !> the ball's impacts' losses.
    subroutine test_ball_and_coin(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = "data/ball_and_coin.adm"
        ! The coin's bounds are test_coin_dataset's (measured there 7.6e-12 s, 2e-16 m/s,
        ! 5.2e-12 m); the speed at every row after the switch: upright straight rolling keeps
        ! it to rounding (measured 0 at every row), bound 1e-13
        real(wp), parameter :: time_tol = 1.0e-10_wp, speed_tol = 1.0e-13_wp, &
            & distance_tol = 5.0e-11_wp
        ! The ball's first impact against its own dataset's [s]: both within the event
        ! tolerance of sqrt(2 h/g) (sphere_bounce's 1e-10 s, sqrt 2 of it beside the coin);
        ! measured 4.4e-11 s, bound 1e-10 s
        real(wp), parameter :: same_tol = 1.0e-10_wp
        ! Energy lost [J]: E0 - E_end against the coin's m v0^2 / 6 and the impacts' losses;
        ! the energy judge's drift at rtol 1e-10 allows 5.2e-8 J over the run (measured
        ! |E + W - E0| 2.2e-8 J, and 2.18e-8 J here), bound 1e-7 J
        real(wp), parameter :: energy_tol = 1.0e-7_wp
        type(adm_model_type) :: adm
        type(history_type) :: history
        type(contact_watch_type) :: ball, alone, coin
        real(wp) :: v0, mu, g, t_star, slid, lost
        real(wp), allocatable :: time(:), xdot(:)
        integer :: k, e

        ! the ball: its closed forms, and its dataset's impacts
        call sphere_bounce(path, error, 1, ball)
        if (allocated(error)) then
            error%message = "the ball (CONTACT/1): " // error%message
            return
        end if
        call run_contact_dataset("data/sphere_bounce.adm", adm, history, alone, error)
        if (allocated(error)) return
        call check(error, size(ball%switch_times), size(alone%switch_times), "the ball's " &
            & // "impacts, as many as on its own")
        if (allocated(error)) return
        call check(error, ball%switch_times(1), alone%switch_times(1), "the ball's first " &
            & // "impact against its own dataset's [s]", abs_tol=same_tol)
        if (allocated(error)) return
        ! the coin
        call run_contact_dataset(path, adm, history, coin, error, 2)
        if (allocated(error)) return
        v0 = adm%parts(3)%velocity(1)
        mu = adm%contacts(2)%mu_dynamic
        g = -adm%gravity(3)
        t_star = v0/(3.0_wp*mu*g)
        call check(error, .not. coin%sphere .and. coin%part == 2, "CONTACT/2 is the coin's " &
            & // "rim, model part 2")
        if (allocated(error)) return
        call check(error, size(coin%switch_times), 1, "the coin switches once")
        if (allocated(error)) return
        call check(error, coin%switch_times(1), t_star, "the coin's t* = v0/(3 mu g) [s]", &
            & abs_tol=time_tol)
        if (allocated(error)) return
        time = history%column(1)
        xdot = history%column(history%layout%part_column(2, coord_xdot))
        do k = 1, history%count
            if (time(k) <= coin%switch_times(1)) cycle
            call check(error, xdot(k), 2.0_wp*v0/3.0_wp, "the coin's speed, (2/3) v0, at t = " &
                & // to_text(time(k)) // " s [m/s]", abs_tol=speed_tol)
            if (allocated(error)) return
        end do
        associate (last => history%count)
            slid = history%rows(history%layout%part_column(2, coord_x), last) &
                & - 2.0_wp*v0/3.0_wp*(time(last) - coin%switch_times(1))
            call check(error, slid, 5.0_wp/6.0_wp*v0*t_star, "the coin's distance slid [m]", &
                & abs_tol=distance_tol)
            if (allocated(error)) return
            e = history%layout%energy_column()
            lost = adm%parts(3)%mass*v0**2/6.0_wp + sum(ball%switch_details%energy_before &
                & - ball%switch_details%energy_after)
            call check(error, history%rows(e, 1) - history%rows(e, last), lost, "energy " &
                & // "lost, the coin's m v0^2/6 and the ball's impacts' [J]", abs_tol=energy_tol)
        end associate
    end subroutine test_ball_and_coin

    !> data/sliding_coin.adm, the coin as a dataset CONTACT on its rim (a CYLINDER about its
    !> axis), thrown along its plane at 1 m/s without spin, mu = 0.3: it rolls at
    !> t* = v0 / (3 mu g) = 0.113263 s, at (2/3) v0, having slid (5/6) v0 t* = 0.0943859 m and
    !> lost m v0^2 / 6 (test_contact_modes derives them), and its switch is the scene's
    !> (data/sliding_coin.nml) switch: the same equations, routine and tolerances.
    subroutine test_coin_dataset(error)
        type(error_type), allocatable, intent(out) :: error
        ! The closed forms' bounds are test_contact_modes' test_sliding_coin's (measured there
        ! 7.6e-12 s, 2e-16 m/s, 5.2e-12 m, 1.2e-16 J)
        real(wp), parameter :: time_tol = 1.0e-10_wp, speed_tol = 1.0e-13_wp, &
            & distance_tol = 5.0e-11_wp, energy_tol = 1.0e-13_wp
        ! Against the scene's own run [s]: the same model, so the same steps; measured 0, bound
        ! 1e-13 s (rounding of a different order of assembly)
        real(wp), parameter :: same_tol = 1.0e-13_wp
        type(adm_model_type) :: adm
        type(history_type) :: history, scene_history
        type(contact_watch_type) :: contact, scene_contact
        type(scene_type) :: scene
        type(run_summary_type) :: scene_summary
        real(wp) :: v0, mu, g, t_star, mass, t_end, slid
        integer :: e

        call run_contact_dataset("data/sliding_coin.adm", adm, history, contact, error)
        if (allocated(error)) return
        v0 = adm%parts(2)%velocity(1)
        mu = adm%contacts(1)%mu_dynamic
        g = -adm%gravity(3)
        mass = adm%parts(2)%mass
        t_star = v0/(3.0_wp*mu*g)
        call check(error, .not. contact%sphere .and. contact%radius == 0.1_wp, "a rim of " &
            & // "radius 0.1 m (GRAPHICS/2, CYLINDER)")
        if (allocated(error)) return
        call check(error, size(contact%switch_times), 1, "one switch")
        if (allocated(error)) return
        call check(error, contact%switch_times(1), t_star, "t* = v0/(3 mu g) [s]", &
            & abs_tol=time_tol)
        if (allocated(error)) return
        associate (last => history%count)
            t_end = history%rows(1, last)
            call check(error, history%rows(history%layout%part_column(1, coord_xdot), last), &
                & 2.0_wp*v0/3.0_wp, "speed after the switch, (2/3) v0 [m/s]", abs_tol=speed_tol)
            if (allocated(error)) return
            slid = history%rows(history%layout%part_column(1, coord_x), last) &
                & - 2.0_wp*v0/3.0_wp*(t_end - contact%switch_times(1))
            call check(error, slid, 5.0_wp/6.0_wp*v0*t_star, "distance slid [m]", &
                & abs_tol=distance_tol)
            if (allocated(error)) return
            e = history%layout%energy_column()
            call check(error, history%rows(e, 1) - history%rows(e, last), mass*v0**2/6.0_wp, &
                & "energy lost, m v0^2/6 [J]", abs_tol=energy_tol)
            if (allocated(error)) return
        end associate
        call read_scene("data/sliding_coin.nml", scene, error)
        if (allocated(error)) return
        call run_scene(scene, scene_history, scene_summary, scene_contact, error)
        if (allocated(error)) return
        call check(error, contact%switch_times(1), scene_contact%switch_times(1), "the " &
            & // "dataset's switch against the scene's [s]", abs_tol=same_tol)
    end subroutine test_coin_dataset

    !> The GRAPHICS a CONTACT names are read with their shapes and sizes in SI (a dataset in
    !> millimetres: RADIUS=100 is 0.1 m), and the contact's part and radius follow from them.
    subroutine test_geometries(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(contact_shape_type) :: shape
        integer :: k

        call read_adm("data/sphere_thrown.adm", adm, error)
        if (allocated(error)) return
        call check(error, size(adm%graphics), 2, "two GRAPHICS kept")
        if (allocated(error)) return
        call check(error, adm%graphics(1)%shape == graphics_plane .and. &
            & adm%graphics(2)%shape == graphics_ellipsoid, "a PLANE and an ELLIPSOID")
        if (allocated(error)) return
        call contact_shape(adm, adm%contacts(1), shape, error)
        if (allocated(error)) return
        call check(error, shape%sphere .and. shape%part_id == 2 .and. shape%part == 1 .and. &
            & shape%radius == 0.05_wp, "PART/2's sphere of radius 0.05 m, first in model order")
        if (allocated(error)) return
        call check(error, index(adm%warning, "CONTACT PENALTY (line 37)") > 0 .and. &
            & index(adm%warning, "GRAPHICS") == 0, "PENALTY named as not used, the GRAPHICS " &
            & // "the CONTACT uses not: " // adm%warning)
        if (allocated(error)) return
        call make_folders(folder, error)
        if (allocated(error)) return
        call write_text_file(folder // "/millimetres.adm", coin_text("UNITS/FORCE=NEWTON, " &
            & // "MASS=KILOGRAM, LENGTH=MILLIMETER, TIME=SECOND", "", "100", "0"), error)
        if (allocated(error)) return
        call read_adm(folder // "/millimetres.adm", adm, error)
        if (allocated(error)) return
        k = findloc(adm%graphics%id, 2, dim=1)
        call check(error, adm%graphics(k)%shape == graphics_cylinder, "a CYLINDER")
        if (allocated(error)) return
        call check(error, adm%graphics(k)%radius, 0.1_wp, "RADIUS=100 mm in metres", &
            & rel_tol=1.0e-15_wp)
    end subroutine test_geometries

    !> A coin dataset on a CONTACT (its lines: the CONTACT's 13 and 14, GRAPHICS/1's 11) with a
    !> UNITS statement, extra CONTACT keys, its cylinder's RADIUS and its plane's RM marker's Z
    !> as written (the numbers are SI's: a dataset in other units is only read).
    function coin_text(units, keys, radius, plane_z) result(text)
        character(len=*), intent(in) :: units, keys, radius, plane_z
        character(len=:), allocatable :: text
        character(len=*), parameter :: nl = new_line("a")

        text = "coin on a contact" // nl // units // nl &
            & // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART=1, QP=0, 0, " // plane_z // nl &
            & // "PART/2, MASS=0.73513268094001172, CM=3" // nl &
            & // ", IP=1.8383830518607345E-3, 1.8383830518607345E-3, 3.6756634047000595E-3" // nl &
            & // ", QG=0, 0, 0.1" // nl &
            & // ", VX=1, WX=0, WY=0, WZ=0" // nl &
            & // "MARKER/3, PART=2, REULER=0D, 90D, 0D" // nl &
            & // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "GRAPHICS/1, PLANE, RM=1, XMIN=-1, XMAX=1, YMIN=-1, YMAX=1" // nl &
            & // "GRAPHICS/2, CYLINDER, CM=3, RADIUS=" // radius // ", LENGTH=3" // nl &
            & // "CONTACT/7, IGEOM=2, JGEOM=1, POISSON, RESTITUTION_COEFFICIENT=0.5" // nl &
            & // ", COULOMB_FRICTION=ON, MU_STATIC=0.3, MU_DYNAMIC=0.3" // keys // nl &
            & // "SIMULATE/DYNAMIC, END=0.01, DTOUT=0.001" // nl &
            & // "INTEGRATOR/FORMULATION=CVODE" // nl // "END" // nl
    end function coin_text

    !> What rollcon cannot honour is refused with the file, the CONTACT's line, the key and
    !> why: a user-written normal law, frictionless sliding, a plane off Z = 0, MAGGI (the
    !> contact's modes are the ODE and DAE forms'), a second CONTACT on the same part, and a
    !> second rim's dissipation in a dataset of several CONTACTs (one rim's is modelled).
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: path

        path = folder // "/refused.adm"
        call expect_refusal(coin_text("UNITS/SYSTEM=SI", ", NORMAL_FUNCTION=USER(1)", "0.1", &
            & "0"), "refused.adm:14: CONTACT/7 NORMAL_FUNCTION: not supported", error)
        if (allocated(error)) return
        call expect_refusal(replaced(coin_text("UNITS/SYSTEM=SI", "", "0.1", "0"), &
            & "COULOMB_FRICTION=ON", "COULOMB_FRICTION=OFF"), &
            & "refused.adm:14: CONTACT/7 COULOMB_FRICTION=OFF: not supported", error)
        if (allocated(error)) return
        call expect_refusal(coin_text("UNITS/SYSTEM=SI", "", "0.1", "0.01"), &
            & "refused.adm:11: GRAPHICS/1: CONTACT/7's plane must be the ground plane Z = 0", &
            & error)
        if (allocated(error)) return
        call expect_refusal(replaced(coin_text("UNITS/SYSTEM=SI", "", "0.1", "0"), &
            & "FORMULATION=CVODE", "FORMULATION=MAGGI"), "refused.adm:13: CONTACT/7: a " &
            & // "CONTACT's modes (rolling, sliding, flight) are integrated in the ODE form " &
            & // "(CVODE) and the DAE form (IDA), not in independent speeds", error)
        if (allocated(error)) return
        ! several CONTACTs: a second on the coin's part, and a second rim's dissipation
        call expect_refusal(replaced(coin_text("UNITS/SYSTEM=SI", "", "0.1", "0"), &
            & "SIMULATE/", "CONTACT/8, IGEOM=2, JGEOM=1, MU_STATIC=0.3" // new_line("a") &
            & // "SIMULATE/"), "refused.adm:13: CONTACT/7: PART/2 is constrained by " &
            & // "CONTACT/8", error)
        if (allocated(error)) return
        call expect_refusal(replaced(coin_text("UNITS/SYSTEM=SI", ", ROLLING_RESISTANCE=1E-5", &
            & "0.1", "0"), "SIMULATE/", "PART/4, MASS=0.73513268094001172, CM=41, " &
            & // "IP=1.8383830518607345E-3, 1.8383830518607345E-3, 3.6756634047000595E-3, " &
            & // "QG=0, 0.5, 0.1" // new_line("a") // "MARKER/41, PART=4, REULER=0D, 90D, 0D" &
            & // new_line("a") // "GRAPHICS/5, CYLINDER, CM=41, RADIUS=0.1, LENGTH=3" &
            & // new_line("a") // "CONTACT/8, IGEOM=5, JGEOM=1, MU_STATIC=0.3, " &
            & // "AIR_VISCOSITY=1.8E-5" // new_line("a") // "SIMULATE/"), "refused.adm:18: " &
            & // "CONTACT/8: ROLLING_RESISTANCE and AIR_VISCOSITY are modelled on one CONTACT " &
            & // "of a dataset (the equations hold one rim's dissipation: docs/design.md " &
            & // "section 5, Dissipation), and CONTACT/7 (line 13) gives them already", error)

    contains

        !> Write text to path, read and build it: the error must contain expected.
        subroutine expect_refusal(text, expected, error)
            character(len=*), intent(in) :: text, expected
            type(error_type), allocatable, intent(out) :: error
            type(error_type), allocatable :: refused
            type(adm_model_type) :: adm
            type(dataset_source_type) :: source
            type(problem_type), target :: problem
            procedure(ucosub_interface), pointer :: none
            real(wp), allocatable :: q0(:), u0(:)
            character(len=:), allocatable :: report

            call make_folders(folder, error)
            if (allocated(error)) return
            call write_text_file(path, text, error)
            if (allocated(error)) return
            call read_adm(path, adm, refused)
            if (.not. allocated(refused)) then
                none => null()
                source = new_dataset_source(adm, path)
                call source%build(none, problem, q0, u0, report, refused)
            end if
            call check(error, allocated(refused), "refused: " // expected)
            if (allocated(error)) return
            call check(error, index(refused%message, expected) > 0, "the refusal says '" &
                & // expected // "': " // refused%message)
        end subroutine expect_refusal
    end subroutine test_refusals

    !> rollcon's own key ROLLING_RESISTANCE=delta on a rim's CONTACT: the coin upright, rolling
    !> straight along +X at v0 = 1 m/s (phidot = -v0/R), takes the moment Q_phi = -delta F_n
    !> sign(phidot) = delta m g (rollcon_rim_dissipation), so (C + m R^2) phidot' = delta m g
    !> with C = m R^2 / 2: the centre slows at (2/3) delta g / R, uniformly (the friction this
    !> needs, (2/3) delta m g / R, is 7e-4 of the weight: it keeps rolling). On a sphere the key
    !> is refused (a rim's law).
    subroutine test_rolling_resistance(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: refused
        ! Speed at every row against v0 - (2/3) delta g t / R [m/s]: a linear solution the
        ! integrator at rtol 1e-8 (the default) follows to its local error times the steps;
        ! measured 1.1e-14, bound 1e-10 (the law's own size over 0.5 s is 3.3e-3 m/s)
        real(wp), parameter :: speed_tol = 1.0e-10_wp
        real(wp), parameter :: delta = 1.0e-4_wp, radius = 0.1_wp, g = 9.81_wp
        type(adm_model_type) :: adm
        type(history_type) :: history
        type(contact_watch_type) :: contact
        character(len=:), allocatable :: text, path
        real(wp), allocatable :: time(:), xdot(:), mode(:)
        integer :: k

        call make_folders(folder, error)
        if (allocated(error)) return
        text = replaced(replaced(coin_text("UNITS/SYSTEM=SI", ", ROLLING_RESISTANCE=1.0E-4", &
            & "0.1", "0"), "WZ=0", "WZ=-10"), "END=0.01", "END=0.5")
        path = folder // "/rolling_resistance.adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
        call run_contact_dataset(path, adm, history, contact, error)
        if (allocated(error)) return
        time = history%column(1)
        xdot = history%column(history%layout%part_column(1, coord_xdot))
        mode = history%column(history%layout%column("mode"))
        call check(error, all(nint(mode) == mode_rolling), "it rolls throughout")
        if (allocated(error)) return
        do k = 1, history%count
            call check(error, xdot(k), 1.0_wp - 2.0_wp/3.0_wp*delta*g/radius*time(k), &
                & "speed at t = " // to_text(time(k)) // " s [m/s]", abs_tol=speed_tol)
            if (allocated(error)) return
        end do
        call check(error, history%layout%column("rolling_power") > 0, "the dissipation's " &
            & // "columns are in the rows")
        if (allocated(error)) return
        path = folder // "/sphere_resistance.adm"
        text = "ball" // new_line("a") // "UNITS/SYSTEM=SI" // new_line("a") &
            & // "PART/1, GROUND" // new_line("a") // "MARKER/1, PART=1" // new_line("a") &
            & // "PART/2, MASS=1, CM=21, IP=1.0E-3, 1.0E-3, 1.0E-3, QG=0, 0, 0.05" &
            & // new_line("a") // "MARKER/21, PART=2, REULER=0D, 90D, 0D" // new_line("a") &
            & // "GRAPHICS/1, PLANE, RM=1" // new_line("a") &
            & // "GRAPHICS/2, ELLIPSOID, CM=21, XSCALE=0.1, YSCALE=0.1, ZSCALE=0.1" &
            & // new_line("a") // "CONTACT/3, IGEOM=2, JGEOM=1, MU_STATIC=0.3, " &
            & // "ROLLING_RESISTANCE=1.0E-4" // new_line("a") &
            & // "SIMULATE/DYNAMIC, END=0.01, DTOUT=0.001" // new_line("a") &
            & // "INTEGRATOR/FORMULATION=CVODE" // new_line("a") // "END" // new_line("a")
        call write_text_file(path, text, error)
        if (allocated(error)) return
        call run_contact_dataset(path, adm, history, contact, refused)
        call check(error, allocated(refused), "ROLLING_RESISTANCE on a sphere refused")
        if (allocated(error)) return
        call check(error, index(refused%message, "CONTACT/3: ROLLING_RESISTANCE and " &
            & // "AIR_VISCOSITY are a rim's laws") > 0, "the refusal names CONTACT/3 and why: " &
            & // refused%message)
    end subroutine test_rolling_resistance

    !> text with its first `old` replaced by `new`.
    pure function replaced(text, old, new) result(out)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: out
        integer :: at

        at = index(text, old)
        out = text
        if (at > 0) out = text(:at - 1) // new // text(at + len(old):)
    end function replaced

end module test_contact_datasets
