! SPDX-License-Identifier: MIT
!> Datasets with VARIABLEs run (suite system-runs): a spring-damper's force written through
!> VARIABLEs gives the very rows of the force written inline, on CVODE and on IDA, its motion
!> the closed-form damped oscillation and its var<id> columns the values of their expressions;
!> the slider of test/system/motion_slider.adm (a MOTION, a VARIABLE, a PINPUT) follows its
!> motion with the force it takes; the spring-damper of test/system/springdamper_export.adm,
!> as ADAMS/View exports it, balances its energy against what its damper dissipates.
module test_system_runs
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_system_runs

    character(len=*), parameter :: work_dir = "build/rollcon-test"
    real(wp), parameter :: g = 9.80665_wp
    character(len=*), parameter :: nl = new_line("a")
    !> A VARIABLE's column is its expression at the row's own state: a few roundings of
    !> numbers of order 1
    real(wp), parameter :: tol_same = 1.0e-12_wp

contains

    subroutine collect_system_runs(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("variable-in-a-force-same-rows-as-inline-and-damped-oscillation", &
            & test_spring), &
            & new_unittest("motion-slider-field-dataset", test_slider), &
            & new_unittest("springdamper-export-field-dataset-energy-balance", test_export)]
    end subroutine collect_system_runs

    !> A 1 kg mass at (0, 2, 0) hung by an SFORCE from the ground origin, k = 100 N/m,
    !> c = 1 N s/m, free length 2 m, gravity -g along y (along the spring). Its height is
    !> y = y_e + x0 e^(-t/2) (cos(wd t) + sin(wd t)/(2 wd)), y_e = 2 - g/100, x0 = g/100,
    !> wd = sqrt(100 - 1/4) (x'' + x' + 100 x = 0). The force as
    !> -100*VARVAL(1) - VARVAL(2), VARIABLE/1 = DM(10,20) - 2 and VARIABLE/2 = VR(10,20),
    !> is the inline force's very program: the same rows to the last bit, on each formulation.
    subroutine test_spring(error)
        type(error_type), allocatable, intent(out) :: error
        !> The integrated height against the closed form at ERROR = 1e-10 over 3 s (five
        !> periods): measured 2.3e-8 m (CVODE) and 6.0e-9 m (IDA); 1e-7 m leaves a factor
        !> of 4.4 over CVODE's and is 1e-6 of the 0.1 m amplitude
        real(wp), parameter :: tol_motion = 1.0e-7_wp
        character(len=*), parameter :: head = "spring-damper" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/10, PART = 1" // nl // "PART/2, MASS = 1, CM = 20, IP = 0.04, 0.1, " &
            & // "0.1" // nl // "MARKER/20, PART = 2, QP = 0, 2, 0" // nl
        character(len=*), parameter :: inline = "SFORCE/1, TRANSLATION, I = 10, J = 20, " &
            & // "FUNCTION = -100.0*(DM(10,20)-2.0) - 1.0*VR(10,20)" // nl
        character(len=*), parameter :: through = "SFORCE/1, TRANSLATION, I = 10, J = 20, " &
            & // "FUNCTION = -100.0*VARVAL(1) - 1.0*VARVAL(2)" // nl &
            & // "VARIABLE/1, FUNCTION = DM(10,20)-2.0" // nl &
            & // "VARIABLE/2, FUNCTION = VR(10,20)" // nl
        character(len=*), parameter :: formulations(2) = ["CVODE", "IDA  "]
        type(job_result_type) :: result
        type(history_type) :: inline_rows, rows
        real(wp) :: t, y, worst, worst_var, wd, x0, ye, r(3), v(3)
        integer :: f, k, cx, cv, n

        wd = sqrt(100.0_wp - 0.25_wp)
        x0 = g/100.0_wp
        ye = 2.0_wp - x0
        do f = 1, size(formulations)
            call run_text("spring_inline.adm", head // inline // tail(formulations(f)), &
                & result, inline_rows, error)
            if (allocated(error)) return
            call run_text("spring_variables.adm", head // through // tail(formulations(f)), &
                & result, rows, error)
            if (allocated(error)) return
            call check(error, result%summary%status == status_completed .and. rows%count == &
                & 301 .and. inline_rows%count == 301, trim(formulations(f)) // ": both runs " &
                & // "complete with 301 rows")
            if (allocated(error)) return
            cx = result%summary%layout%column("X_2")
            cv = result%summary%layout%column("var1")
            call check(error, cx > 0 .and. cv > 0 .and. result%summary%layout%column("var2") &
                & == cv + 1, "columns X_2, var1 and var2")
            if (allocated(error)) return
            ! every column before var1 (var1 and var2 are the last two)
            n = cv - 1
            call check(error, all(rows%rows(:n, :rows%count) == inline_rows%rows(:n, &
                & :rows%count)), trim(formulations(f)) // ": the rows through VARIABLEs " &
                & // "differ from the inline force's by " // to_text(maxval(abs(rows%rows(:n, &
                & :rows%count) - inline_rows%rows(:n, :rows%count)))))
            if (allocated(error)) return
            worst = 0.0_wp
            worst_var = 0.0_wp
            do k = 1, rows%count
                t = rows%rows(1, k)
                y = ye + x0*exp(-0.5_wp*t)*(cos(wd*t) + 0.5_wp/wd*sin(wd*t))
                worst = max(worst, abs(rows%rows(cx + 1, k) - y))
                r = rows%rows(cx:cx + 2, k)
                v = rows%rows(cx + 6:cx + 8, k)
                worst_var = max(worst_var, abs(rows%rows(cv, k) - (norm2(r) - 2.0_wp)), &
                    & abs(rows%rows(cv + 1, k) - dot_product(r, v)/norm2(r)))
            end do
            call check(error, worst <= tol_motion, trim(formulations(f)) // ": largest " &
                & // "distance of the height from the damped oscillation " // to_text(worst) &
                & // " m")
            if (allocated(error)) return
            call check(error, worst_var <= tol_same, trim(formulations(f)) // ": var1, var2 " &
                & // "against DM - 2 and VR from the row: " // to_text(worst_var))
            if (allocated(error)) return
        end do
    end subroutine test_spring

    !> The end of the spring-damper's dataset: gravity along the spring, the formulation.
    pure function tail(formulation) result(text)
        character(len=*), intent(in) :: formulation
        character(len=:), allocatable :: text

        text = "ACCGRAV/JGRAV = -9.80665" // nl // "INTEGRATOR/ERROR = 1e-10, FORMULATION = " &
            & // trim(formulation) // nl // "SIMULATE/DYNAMIC, END = 3, STEPS = 300" // nl &
            & // "END"
    end function tail

    !> test/system/motion_slider.adm as written: the part's centre, 100 mm along the slider's
    !> axis (ground x) from marker 21, follows -150 + 10 sin(2 pi t) + 100 mm along x; the
    !> MOTION's force is m x'' (gravity is normal to the axis); var1 is the constant 72.
    subroutine test_slider(error)
        type(error_type), allocatable, intent(out) :: error
        !> The position is held by each step's Newton iteration: measured 6.8e-11 m, 1e-9 m
        !> leaves a factor of 15 (1e-7 of the 10 mm stroke); the force from the multiplier is
        !> exact up to roundings of the 0.4 N (measured 7.2e-16 N), 1e-12 N a few thousand
        !> roundings, a millionth of a missing m x''
        real(wp), parameter :: tol_position = 1.0e-9_wp, tol_force = 1.0e-12_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: t, worst, worst_force, worst_var
        integer :: k, cx, cf, cv

        call run_file("test/system/motion_slider.adm", result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 101, &
            & "the slider completes with 101 rows")
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        cf = result%summary%layout%column("motion1_force")
        cv = result%summary%layout%column("var1")
        call check(error, cx > 0 .and. cf > 0 .and. cv > 0, "columns X_2, motion1_force, var1")
        if (allocated(error)) return
        worst = 0.0_wp
        worst_force = 0.0_wp
        worst_var = 0.0_wp
        do k = 1, rows%count
            t = rows%rows(1, k)
            worst = max(worst, abs(rows%rows(cx, k) - (-0.05_wp + 0.01_wp*sin(2.0_wp*pi*t))), &
                & abs(rows%rows(cx + 1, k)), abs(rows%rows(cx + 2, k)))
            worst_force = max(worst_force, abs(rows%rows(cf, k) + 0.01_wp*(2.0_wp*pi)**2 &
                & *sin(2.0_wp*pi*t)))
            worst_var = max(worst_var, abs(rows%rows(cv, k) - 72.0_wp))
        end do
        call check(error, worst <= tol_position, "largest distance of the centre from its " &
            & // "motion " // to_text(worst) // " m")
        if (allocated(error)) return
        call check(error, worst_force <= tol_force, "largest difference of motion1_force " &
            & // "from m x'' " // to_text(worst_force) // " N")
        if (allocated(error)) return
        call check(error, worst_var == 0.0_wp, "var1 is 72 at every row; largest difference " &
            & // to_text(worst_var))
    end subroutine test_slider

    !> test/system/springdamper_export.adm as written: gravity along -z, normal to the spring
    !> at the start, so the mass swings as an elastic pendulum. var1 = DM(10,20) - 2 at every
    !> row, and the energy 1/2 m v^2 + m g Z + 1/2 k var1^2 falls by exactly what the damper
    !> dissipates, the integral of c VR^2 (Simpson's rule over the rows).
    subroutine test_export(error)
        type(error_type), allocatable, intent(out) :: error
        !> The balance, Simpson's rule over the 500 rows 0.01 s apart and the integration at
        !> the dataset's default tolerances together, measured 3.4e-6 J of the 0.67 J the
        !> damper takes; 2e-5 J leaves a factor of 6 and is 3e-5 of that energy (a damping
        !> 1 % off moves it by 7e-3 J)
        real(wp), parameter :: tol_energy = 2.0e-5_wp
        real(wp), parameter :: mass = 1.0_wp, k_spring = 100.0_wp, c = 1.0_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp), allocatable :: power(:), energy(:)
        real(wp) :: r(3), v(3), dissipated, worst, worst_var, h
        integer :: k, cx, cv

        call run_file("test/system/springdamper_export.adm", result, rows, error)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed .and. rows%count == 501, &
            & "the spring-damper completes with 501 rows")
        if (allocated(error)) return
        cx = result%summary%layout%column("X_2")
        cv = result%summary%layout%column("var1")
        call check(error, cx > 0 .and. cv > 0, "columns X_2 and var1")
        if (allocated(error)) return
        allocate(power(rows%count), energy(rows%count))
        worst_var = 0.0_wp
        do k = 1, rows%count
            r = rows%rows(cx:cx + 2, k)
            v = rows%rows(cx + 6:cx + 8, k)
            worst_var = max(worst_var, abs(rows%rows(cv, k) - (norm2(r) - 2.0_wp)))
            power(k) = c*(dot_product(r, v)/norm2(r))**2
            energy(k) = 0.5_wp*mass*dot_product(v, v) + mass*g*r(3) &
                & + 0.5_wp*k_spring*rows%rows(cv, k)**2
        end do
        call check(error, worst_var <= tol_same, "var1 against DM(10,20) - 2 from the row: " &
            & // to_text(worst_var))
        if (allocated(error)) return
        h = rows%rows(1, 2) - rows%rows(1, 1)
        dissipated = 0.0_wp
        worst = 0.0_wp
        do k = 3, rows%count, 2
            dissipated = dissipated + h/3.0_wp*(power(k - 2) + 4.0_wp*power(k - 1) + power(k))
            worst = max(worst, abs(energy(k) + dissipated - energy(1)))
        end do
        call check(error, worst <= tol_energy .and. dissipated > 0.1_wp, "energy plus what " &
            & // "the damper took, against the start: largest difference " // to_text(worst) &
            & // " J (dissipated " // to_text(dissipated) // " J)")
    end subroutine test_export

    !> Run the dataset at `path`, its rows kept in memory.
    subroutine run_file(path, result, rows, error)
        character(len=*), intent(in) :: path
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(error_type), allocatable :: failure

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, rows)
        if (allocated(failure)) call move_alloc(failure, error)
    end subroutine run_file

    !> Write text to work_dir/name and run it.
    subroutine run_text(name, text, result, rows, error)
        character(len=*), intent(in) :: name, text
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        integer :: unit

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
        call run_file(work_dir // "/" // name, result, rows, error)
    end subroutine run_text

end module test_system_runs
