! SPDX-License-Identifier: MIT
!> The model's units at the UCOSUB boundary (suite ucosub-units, rollcon_ucosub_units): a
!> routine in a dataset with UNITS other than SI gets the state, the time and PAR in the
!> dataset's units, as ADAMS hands them, and what it returns is turned back to SI. Checked two
!> ways: (1) at the constraint level, two routines with explicit time (a position and a
!> velocity UCON) in millimetres and minutes give the SI routine's F and every partial, to
!> round-off; (2) through the program, a dataset written in mm (the coin, by the user's own
!> fixed-form file and by the built-in routines; the coin with a position UCON) or in cm, g,
!> dyne and minutes (a ball on a turntable) runs as its SI twin does, multipliers included.
module test_ucosub_units
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucovar, scalar_value, scalar_dt, scalar_dtt, array_dq, &
        & array_dtdq, xmatrx_dqdq, iflag_init
    use rollcon_ucosub_units, only : ucosub_units_type
    use rollcon_body, only : part_type
    use rollcon_model, only : model_type, setup_model
    use rollcon_constraints, only : constraint_state_type, need_value, need_first, &
        & need_second, need_time
    use rollcon_history, only : history_type
    use rollcon_output_layout, only : output_layout_type
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub
    use rollcon_audit_report, only : report_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    use command_runs, only : rollcon_program, run_rollcon, file_text
    implicit none
    private

    public :: collect_ucosub_units

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_ucosub_units"
    !> The units of the converted models: millimetres and minutes
    real(wp), parameter :: mm = 1.0e-3_wp, minute = 60.0_wp
    !> The routines' constants in SI: height h [m], amplitude A [m], speed B [m/s], rate w
    !> [rad/s]
    real(wp), parameter :: h_si = 0.1_wp, a_si = 0.02_wp, b_si = 0.3_wp, w_si = 2.5_wp
    !> F and its partials in the two unit systems are the same numbers through factors of 1e3
    !> and 60: they agree to a few ulps of the largest entry
    real(wp), parameter :: tol_round_off = 1.0e-13_wp
    !> The twin runs solve the same equations up to the round-off of the unit factors; the
    !> integrator's step choices amplify it to the order of its own error. Measured (worst
    !> coordinate, m or rad): coin 1.4e-6 over 3 s at rtol 1e-8, where the SI coin itself differs
    !> from a run 1000 times tighter by 3.5e-5; the ball at ERROR = 1e-10: 1.3e-8. A rate or a
    !> multiplier is compared relative to its column's largest value. Before the units were
    !> converted, the coin in mm ended 7.6e-2 m from its twin
    real(wp), parameter :: tol_twin = 1.0e-5_wp
    !> Largest |X|, |Xdot| and time the recording routine was evaluated at
    real(wp) :: seen(3) = 0.0_wp

contains

    subroutine collect_ucosub_units(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("partials-in-mm-and-minutes", test_partials), &
            & new_unittest("coin-mm-user-file", test_coin_user_file), &
            & new_unittest("coin-mm-built-in", test_coin_built_in), &
            & new_unittest("disk-height-mm", test_disk_height), &
            & new_unittest("ball-cgs-minutes", test_ball), &
            & new_unittest("check-states-in-model-units", test_check_units)]
    end subroutine collect_ucosub_units

    !> F, dF/dq, d2F/dq dq, dF/dt, d2F/dt dq and d2F/dt2 of the two UCONs: a model in mm and
    !> minutes (PAR converted as a user would write it) against the same model in SI, at a
    !> generic state and time.
    subroutine test_partials(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type), target :: si, converted
        type(constraint_state_type) :: a, b
        real(wp) :: q(6), u(6)
        integer, parameter :: needs = need_value + need_first + need_second + need_time

        q = [0.3_wp, -0.2_wp, 0.12_wp, 0.4_wp, 1.1_wp, -0.7_wp]
        u = [0.25_wp, 0.1_wp, -0.05_wp, 1.3_wp, -0.6_wp, 2.2_wp]
        call wave_model(ucosub_units_type(), 1.0_wp, 1.0_wp, si, error)
        if (allocated(error)) return
        call wave_model(ucosub_units_type(length=mm, time=minute), mm, minute, converted, error)
        if (allocated(error)) return
        call a%allocate(si)
        call b%allocate(converted)
        call a%evaluate(si, 1.3_wp, q, u, needs, error)
        if (allocated(error)) return
        call b%evaluate(converted, 1.3_wp, q, u, needs, error)
        if (allocated(error)) return
        call same("F", a%value, b%value, error)
        if (.not. allocated(error)) call same("dF/dq", pack(a%grad_q_local, .true.), &
            & pack(b%grad_q_local, .true.), error)
        if (.not. allocated(error)) call same("dF/du", pack(a%grad_u_local, .true.), &
            & pack(b%grad_u_local, .true.), error)
        if (.not. allocated(error)) call same("d2F/dq dq", pack(a%hqq, .true.), &
            & pack(b%hqq, .true.), error)
        if (.not. allocated(error)) call same("d2F/dq du", pack(a%hqu, .true.), &
            & pack(b%hqu, .true.), error)
        if (.not. allocated(error)) call same("dF/dt", a%dt, b%dt, error)
        if (.not. allocated(error)) call same("d2F/dt2", a%dtt, b%dtt, error)
        if (.not. allocated(error)) call same("d2F/dt dq", pack(a%dt_grad_q, .true.), &
            & pack(b%dt_grad_q, .true.), error)
        if (.not. allocated(error)) call same("d2F/dt du", pack(a%dt_grad_u, .true.), &
            & pack(b%dt_grad_u, .true.), error)
    end subroutine test_partials

    !> One part and the two UCONs of wave_ucosub, PAR written in units of length l [m] and time
    !> t [s], the routines computing in `units`.
    subroutine wave_model(units, l, t, model, error)
        type(ucosub_units_type), intent(in) :: units
        real(wp), intent(in) :: l, t
        type(model_type), target, intent(out) :: model
        type(error_type), allocatable, intent(out) :: error

        call model%add_part(part_type(id=7, mass=1.0_wp, inertia=[1.0_wp, 1.0_wp, 2.0_wp]))
        model%ucosub_units = units
        ! PAR: part, kind (1 position, 2 velocity), h, A or B, w
        call model%add_ucon(1, [7.0_wp, 1.0_wp, h_si/l, a_si/l, w_si*t], wave_ucosub)
        call model%add_ucon(2, [7.0_wp, 2.0_wp, h_si/l, b_si*t/l, w_si*t], wave_ucosub)
        call setup_model(model, error)
    end subroutine wave_model

    !> Two constraints with explicit time, in whatever units PAR and the state come in:
    !>     kind 1 (Z, theta):            F = Z - h sin(theta) - A sin(w t) cos(theta)
    !>     kind 2 (Xdot, theta, phidot): F = Xdot - h cos(theta) phidot - B cos(w t)
    !>                                       - h sin(w t) phidot
    subroutine wave_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(30)
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        integer, intent(in) :: idrsel(3)
        integer, intent(in) :: iflag
        real(wp), intent(inout) :: scalar
        real(wp), intent(inout) :: array(30)
        real(wp), intent(inout) :: xmatrx(30, 30)
        real(wp) :: h, c, w

        if (npar < 5) return
        h = par(3)
        c = par(4)
        w = par(5)
        if (nint(par(2)) == 1) then
            if (iflag == iflag_init) then
                call ucovar(id, 2, [nint(par(1)), nint(par(1))], 2, [13, 15])
                return
            end if
            select case (idrsel(1))
            case (scalar_value)
                scalar = q(1) - h*sin(q(2)) - c*sin(w*time)*cos(q(2))
            case (scalar_dt)
                scalar = -c*w*cos(w*time)*cos(q(2))
            case (scalar_dtt)
                scalar = c*w**2*sin(w*time)*cos(q(2))
            end select
            if (idrsel(2) == array_dq) array(:2) = [1.0_wp, -h*cos(q(2)) &
                & + c*sin(w*time)*sin(q(2))]
            if (idrsel(2) == array_dtdq) array(:2) = [0.0_wp, c*w*cos(w*time)*sin(q(2))]
            if (idrsel(3) == xmatrx_dqdq) xmatrx(2, 2) = h*sin(q(2)) + c*sin(w*time)*cos(q(2))
        else
            if (iflag == iflag_init) then
                call ucovar(id, 3, spread(nint(par(1)), 1, 3), 3, [21, 15, 26])
                return
            end if
            select case (idrsel(1))
            case (scalar_value)
                scalar = q(1) - h*cos(q(2))*q(3) - c*cos(w*time) - h*sin(w*time)*q(3)
            case (scalar_dt)
                scalar = c*w*sin(w*time) - h*w*cos(w*time)*q(3)
            case (scalar_dtt)
                scalar = c*w**2*cos(w*time) + h*w**2*sin(w*time)*q(3)
            end select
            if (idrsel(2) == array_dq) array(:3) = [1.0_wp, h*sin(q(2))*q(3), &
                & -h*cos(q(2)) - h*sin(w*time)]
            if (idrsel(2) == array_dtdq) array(:3) = [0.0_wp, 0.0_wp, -h*w*cos(w*time)]
            if (idrsel(3) == xmatrx_dqdq) then
                xmatrx(2, 2) = h*cos(q(2))*q(3)
                xmatrx(2, 3) = h*sin(q(2))
                xmatrx(3, 2) = h*sin(q(2))
            end if
        end if
    end subroutine wave_ucosub

    !> expected and actual agree to tol_round_off of the largest |entry|, and something is
    !> compared (not all zero).
    subroutine same(what, expected, actual, error)
        character(len=*), intent(in) :: what
        real(wp), intent(in) :: expected(:), actual(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: scale

        scale = maxval(abs(expected))
        call check(error, scale > 0.0_wp .and. maxval(abs(expected - actual)) <= &
            & tol_round_off*scale, what // ": largest difference " &
            & // to_text(maxval(abs(expected - actual))) // " of entries up to " &
            & // to_text(scale))
    end subroutine same

    !> The checker (check --model) calls a routine as a run does: in a dataset in mm and
    !> minutes, the random states drawn in SI's ranges (|X| < 1 m, |Xdot| < 1 m/s, time in
    !> [0, 10] s) reach it in mm, mm/min and minutes; in SI as drawn. 25 states: their largest
    !> |X| lies in (0.5, 1) m with probability 1 - 2**-25.
    subroutine test_check_units(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type) :: request
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        real(wp) :: si_seen(3)

        request%id = 4
        request%par = [3.0_wp]
        seen = 0.0_wp
        call check_user_ucosub(recording_ucosub, [request], options, report, error)
        if (allocated(error)) return
        si_seen = seen
        call check(error, si_seen(1) > 0.5_wp .and. si_seen(1) < 1.0_wp .and. si_seen(2) < &
            & 1.0_wp .and. si_seen(3) <= 10.0_wp .and. report%clean(), "in SI: |X| up to " &
            & // to_text(si_seen(1)) // ", |Xdot| up to " // to_text(si_seen(2)) &
            & // ", time up to " // to_text(si_seen(3)))
        if (allocated(error)) return
        request%units = ucosub_units_type(length=mm, time=minute)
        seen = 0.0_wp
        call check_user_ucosub(recording_ucosub, [request], options, report, error)
        if (allocated(error)) return
        ! the same seed draws the same states: only the units differ (to round-off)
        call check(error, abs(seen(1) - si_seen(1)/mm) <= 1.0e-12_wp*seen(1) .and. &
            & abs(seen(2) - si_seen(2)*minute/mm) <= 1.0e-12_wp*seen(2) .and. &
            & abs(seen(3) - si_seen(3)/minute) <= 1.0e-12_wp*seen(3) .and. report%clean(), &
            & "in mm and minutes: |X| up to " // to_text(seen(1)) // ", |Xdot| up to " &
            & // to_text(seen(2)) // ", time up to " // to_text(seen(3)) // " (in SI: " &
            & // to_text(si_seen(1)) // ", " // to_text(si_seen(2)) // ", " &
            & // to_text(si_seen(3)) // "); " &
            & // report_text(report, "the recording routine", "this test"))
    end subroutine test_check_units

    !> F = Xdot - X (PAR(1) the part): records the largest |X|, |Xdot| and time of the states
    !> it is checked at.
    subroutine recording_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(30)
        real(wp), intent(in) :: par(*)
        integer, intent(in) :: npar
        integer, intent(in) :: idrsel(3)
        integer, intent(in) :: iflag
        real(wp), intent(inout) :: scalar
        real(wp), intent(inout) :: array(30)
        real(wp), intent(inout) :: xmatrx(30, 30)

        if (npar < 1) return
        if (iflag == iflag_init) then
            call ucovar(id, 2, [nint(par(1)), nint(par(1))], 2, [11, 21])
            return
        end if
        ! the state drawn: the call that asks for XMATRX (the difference probes do not)
        if (idrsel(3) == xmatrx_dqdq) seen = max(seen, [abs(q(1)), abs(q(2)), time])
        if (idrsel(1) == scalar_value) scalar = q(2) - q(1)
        if (idrsel(2) == array_dq) array(:2) = [-1.0_wp, 1.0_wp]
        if (idrsel(3) == xmatrx_dqdq) xmatrx(:2, :2) = 0.0_wp
    end subroutine recording_ucosub

    !> data/coin.adm against test/units/coin_mmks.adm served by the user's own file, the
    !> generated rolling disk in fixed form (run in a child process).
    subroutine test_coin_user_file(error)
        type(error_type), allocatable, intent(out) :: error

        call twin_runs("data/coin.adm", "test/units/coin_mmks.adm --ucosub " &
            & // "ucon/adams/rolling_disk/ucosub.f", "coin.adm", "coin_mmks.adm", error)
    end subroutine test_coin_user_file

    !> The same served by rollcon's hand-checked disk (the model's UCOSUB by default).
    subroutine test_coin_built_in(error)
        type(error_type), allocatable, intent(out) :: error

        call twin_runs("data/coin.adm", "test/units/coin_mmks.adm", "coin.adm", "coin_mmks.adm", &
            & error)
    end subroutine test_coin_built_in

    !> The coin with its height as a position UCON (ROUTINE=disk_height, R = 100 mm): the
    !> initial-conditions analysis and the position-level conversion.
    subroutine test_disk_height(error)
        type(error_type), allocatable, intent(out) :: error

        call twin_runs("data/disk_height.adm", "test/units/disk_height_mmks.adm", &
            & "disk_height.adm", "disk_height_mmks.adm", error)
    end subroutine test_disk_height

    !> A ball on a turntable in cm, g, dyne and minutes (its table rate 210 rad/min).
    subroutine test_ball(error)
        type(error_type), allocatable, intent(out) :: error

        call twin_runs("test/units/ball_si.adm", "test/units/ball_cgs_minutes.adm", &
            & "ball_si.adm", "ball_cgs_minutes.adm", error)
    end subroutine test_ball

    !> Run both; every row the converted run wrote matches the SI run's row at the same time:
    !> each column within tol_twin of its largest |value| (at least 1, so coordinates are
    !> compared absolutely in m and rad).
    subroutine twin_runs(si_arguments, converted_arguments, si_name, converted_name, error)
        character(len=*), intent(in) :: si_arguments, converted_arguments, si_name, &
            & converted_name
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        type(output_layout_type) :: si_layout, converted_layout
        type(history_type) :: si_rows, converted_rows
        real(wp) :: worst, scale
        integer :: status(2), i, j, column

        call rollcon_program(program, error)
        if (allocated(error)) return
        call execute_command_line("rm -rf " // scratch // " && mkdir -p " // scratch)
        call run_rollcon(program, "run " // si_arguments // " -q -o " // scratch, scratch &
            & // "/si.out", scratch // "/si.err", status(1))
        call run_rollcon(program, "run " // converted_arguments // " -q -o " // scratch, &
            & scratch // "/converted.out", scratch // "/converted.err", status(2))
        call check(error, all(status == 0), "exit status " // to_text(status(1)) // " and " &
            & // to_text(status(2)) // ": " // file_text(scratch // "/si.err") &
            & // file_text(scratch // "/converted.err"))
        if (allocated(error)) return
        call read_output_csv(scratch // "/" // si_name // ".csv", si_layout, si_rows, error)
        if (allocated(error)) return
        call read_output_csv(scratch // "/" // converted_name // ".csv", converted_layout, &
            & converted_rows, error)
        if (allocated(error)) return
        call check(error, converted_rows%count > 100 .and. converted_rows%count <= &
            & si_rows%count .and. size(si_rows%rows, 1) == size(converted_rows%rows, 1), &
            & "the runs wrote " // to_text(si_rows%count) // " and " &
            & // to_text(converted_rows%count) // " rows of " // to_text(size(si_rows%rows, 1)) &
            & // " and " // to_text(size(converted_rows%rows, 1)) // " columns")
        if (allocated(error)) return
        do column = 1, size(si_rows%rows, 1)
            associate (a => si_rows%rows(column, :converted_rows%count), &
                & b => converted_rows%rows(column, :converted_rows%count))
                scale = max(1.0_wp, maxval(abs(a)))
                worst = maxval(abs(a - b))
                i = maxloc(abs(a - b), dim=1)
            end associate
            j = column
            call check(error, worst <= tol_twin*scale, "column " // to_text(j) // ": the " &
                & // "converted run differs by " // to_text(worst) // " at t = " &
                & // to_text(si_rows%rows(1, i)) // " (allowed " // to_text(tol_twin*scale) &
                & // ")")
            if (allocated(error)) return
        end do
    end subroutine twin_runs

end module test_ucosub_units
