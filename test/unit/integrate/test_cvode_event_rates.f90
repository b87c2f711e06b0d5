! SPDX-License-Identifier: MIT
!> The y' CVODE's event functions are given (suite cvode-event-rates): read off the Nordsieck
!> array at the end of a step (rollcon_cvode's step_end_rates) it is CVodeGetDky(t, 1)'s, to
!> the last bit, at every evaluation of whole runs of the tipping coin with its lift-off
!> event (the event reads the accelerations in y').
module test_cvode_event_rates
    use, intrinsic :: iso_c_binding, only : c_ptr, c_null_ptr, c_int, c_double, c_int64_t, &
        & c_associated
    use fsundials_nvector_mod, only : N_Vector, FN_VDestroy
    use fnvector_serial_mod, only : FN_VMake_Serial
    use fcvode_mod, only : FCVodeGetDky, FCVodeGetCurrentTime, CV_SUCCESS
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_ode_form, only : ode_form_type
    use rollcon_cvode, only : cvode_integrator_type, step_end_rates
    use rollcon_scene_type, only : scene_type
    use rollcon_run_keys, only : choice_code
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_cvode_event_rates

    !> The ODE form of the coin, its event functions checked at every evaluation against
    !> CVodeGetDky on the integrator's memory
    type, extends(ode_form_type) :: checked_form_type
        type(c_ptr) :: memory = c_null_ptr
        !> CVodeGetDky(t, 1) and its storage; step_end_rates' y'
        type(N_Vector), pointer :: dky => null()
        real(c_double), allocatable :: dky_values(:), read_off(:)
        !> Evaluations given y'; of those, at t_n after a step; of all, read off by
        !> step_end_rates
        integer :: with_rates = 0, at_step_end = 0, read = 0
        !> Evaluations whose y' was not CVodeGetDky's bit for bit (given, read off)
        integer :: given_differing = 0, read_differing = 0
        real(wp) :: first_differing = -1.0_wp
    contains
        procedure :: roots => checked_roots
    end type checked_form_type

contains

    subroutine collect_cvode_event_rates(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("step-end-rates-are-getdky-adams", test_adams), &
            & new_unittest("step-end-rates-are-getdky-bdf-projection", test_bdf)]
    end subroutine collect_cvode_event_rates

    !> The tipping coin (the paper's disk 0.01 rad off upright, phidot = -1 rad/s) under CVODE
    !> Adams, Newton, Baumgarte, rtol 1e-11, atol 1e-13.
    subroutine test_adams(error)
        type(error_type), allocatable, intent(out) :: error

        call checked_run("adams", "baumgarte", error)
    end subroutine test_adams

    !> The same under BDF with the projection (CVODE applies its correction to zn as it
    !> completes a step).
    subroutine test_bdf(error)
        type(error_type), allocatable, intent(out) :: error

        call checked_run("bdf", "projection", error)
    end subroutine test_bdf

    !> 2 s of the coin in 0.01 s outputs (CVODE steps past an output and interpolates back:
    !> evaluations inside a step besides those of the step ends), every event evaluation's y'
    !> compared bit for bit with CVodeGetDky's at the same t, and step_end_rates' too wherever
    !> it reads y' off.
    subroutine checked_run(method, drift, error)
        character(len=*), intent(in) :: method, drift
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(checked_form_type), target :: form
        type(cvode_integrator_type), target :: cvode
        real(wp) :: q(6), u(6), y(12), yp(12), t
        integer :: k, root

        scene%run%formulation = choice_code("formulation", "cvode")
        scene%run%method = choice_code("method", method)
        scene%run%drift = choice_code("drift", drift)
        scene%run%rtol = 1.0e-11_wp
        scene%run%atol = 1.0e-13_wp
        scene%initial%theta = acos(-1.0_wp)/2.0_wp - 0.01_wp
        scene%initial%phidot = -1.0_wp
        scene%limits%stop_on_liftoff = .true.
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q, u, error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        call form%init(problem)
        call check(error, form%roots_use_rates(), "the coin's events do not use y' (lift-off)")
        if (allocated(error)) return
        y = [q, u]
        yp = 0.0_wp
        call cvode%start(form, problem%settings, 0.0_wp, y, yp, 2.0_wp, error)
        if (allocated(error)) return
        ! CVODE evaluates the events first in its first call (at t0, before any step), so
        ! from there on every evaluation is checked
        allocate(form%dky_values(12), form%read_off(12), source=0.0_c_double)
        form%dky => FN_VMake_Serial(12_c_int64_t, form%dky_values, cvode%context)
        form%memory = cvode%memory
        root = 0
        do k = 1, 200
            if (allocated(error) .or. root /= 0) exit
            call cvode%advance(0.01_wp*k, 2.0_wp, t, y, yp, root, error)
        end do
        call FN_VDestroy(form%dky)
        call cvode%destroy()
        if (allocated(error)) return
        call check(error, root == 0 .and. t == 2.0_wp, method // ": the coin stopped at " &
            & // to_text(t) // " s, root " // to_text(root))
        if (allocated(error)) return
        call check(error, form%given_differing == 0 .and. form%read_differing == 0, method &
            & // ": y' not CVodeGetDky's bit for bit at " // to_text(form%given_differing) &
            & // " evaluations (given to the events), " // to_text(form%read_differing) &
            & // " (read off at a step end), the first at t = " &
            & // to_text(form%first_differing) // " s")
        if (allocated(error)) return
        ! Most evaluations are at step ends (CVODE evaluates at the end of every step, and
        ! inside one only at an output time it passed or in a root search), and there y' is
        ! read off unless an entry of zn[1] is exactly 0, which none is in these runs: measured
        ! 1022 step ends of 1221 evaluations (Adams), 3266 of 3465 (BDF), all read off
        call check(error, form%at_step_end > form%with_rates/2 .and. form%read &
            & == form%at_step_end, method // ": " // to_text(form%with_rates) &
            & // " evaluations with y', " // to_text(form%at_step_end) // " at a step end, " &
            & // to_text(form%read) // " read off there")
    end subroutine checked_run

    !> The coin's event functions, and y' compared with CVodeGetDky's: the y' given and, at
    !> the end of the last step, step_end_rates'.
    integer function checked_roots(self, time, y, g, ydot) result(ierr)
        class(checked_form_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: ydot(:)
        real(c_double) :: t_n(1)

        ierr = self%ode_form_type%roots(time, y, g, ydot)
        if (.not. c_associated(self%memory) .or. .not. present(ydot)) return
        self%with_rates = self%with_rates + 1
        if (FCVodeGetDky(self%memory, time, 1_c_int, self%dky) /= CV_SUCCESS) then
            call differs(self%given_differing)
            return
        end if
        if (.not. same_bits(ydot, self%dky_values)) call differs(self%given_differing)
        if (FCVodeGetCurrentTime(self%memory, t_n) /= CV_SUCCESS) return
        if (time /= t_n(1)) return
        ! t0 is t_n before the first step too, where no step was taken to read y' off
        if (time > 0.0_wp) self%at_step_end = self%at_step_end + 1
        if (.not. step_end_rates(self%memory, time, self%read_off)) return
        self%read = self%read + 1
        if (.not. same_bits(self%read_off, self%dky_values)) call differs(self%read_differing)

    contains

        subroutine differs(count)
            integer, intent(inout) :: count

            count = count + 1
            if (self%first_differing < 0.0_wp) self%first_differing = time
        end subroutine differs

    end function checked_roots

    !> The two arrays hold the same bits (a zero's sign and all).
    logical function same_bits(a, b)
        real(wp), intent(in) :: a(:), b(:)

        same_bits = size(a) == size(b)
        if (same_bits) same_bits = all(transfer(a, 0_c_int64_t, size(a)) &
            & == transfer(b, 0_c_int64_t, size(b)))
    end function same_bits

end module test_cvode_event_rates
