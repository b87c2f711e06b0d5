! SPDX-License-Identifier: MIT
!> `rollcon run MODEL.acf` and `rollcon run MODEL.adm --end T --steps N` through the program
!> (suite acf-command): the pendulum ADAMS/View exports (test/view, no SIMULATE of its own) run
!> from its command file against an independent integration of the pendulum's equation; the
!> same dataset run with --end and --steps; run with neither, refused saying both ways; and
!> the command file given from another folder, by a relative and by an absolute path; `rollcon
!> plot MODEL.acf` drawing the run `rollcon run MODEL.acf` wrote.
module test_acf_command
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_output_layout, only : output_layout_type
    use rollcon_simulation, only : history_type
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder, write_lines, command_available
    use command_runs, only : rollcon_program, run_rollcon, file_text, file_exists
    use rollcon_load, only : outputs_name_of
    implicit none
    private

    public :: collect_acf_command

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_acf_command"
    !> The pendulum (test/view/view_export_pendulum.adm): its part's CM at L = 2 m from the
    !> hinge, m = 1 kg, I = 0.1 kg m^2 about the hinge axis through the CM (IP's zz: the CM
    !> marker's z-axis, REULER = 180D, 90D, 180D, is ground y, the hinge axis), g = 9.80665
    real(wp), parameter :: length = 2.0_wp, mass = 1.0_wp, inertia = 0.1_wp, &
        & gravity = 9.80665_wp
    !> The run integrates with IDA at rtol 1e-8, atol 1e-10 (the dataset gives no INTEGRATOR):
    !> the CM's position against a fourth-order Runge-Kutta integration of the pendulum's
    !> equation at 1e-4 s (its own error 6e-12 rad at 5 s, halving the step) was measured off
    !> by 1.37e-6 m at most over the 5 s. 4e-6 m leaves a factor 3 for another platform's
    !> rounding and catches a tenfold loss of accuracy (at rtol 1e-7, atol 1e-9 the CM was
    !> measured off by 1.5e-5 m); the moment about the other axis (IP's xx, 0.04) in its place
    !> moves the CM by 0.19 m
    real(wp), parameter :: tol_position = 4.0e-6_wp
    !> The request's columns and the CM's are computed from the same state (a few roundings on
    !> numbers of size 2, 1e-15 m): 1e-12 m is far below any mistake of marker or axes
    real(wp), parameter :: tol_request = 1.0e-12_wp
    !> REQUEST/2's force against m g - m a from the row's own state: 1.23e-7 N of up to 29 N
    !> measured (the multipliers' accuracy at rtol 1e-8); 5e-7 N catches a tenfold loss, and the
    !> force on the bar in its place (the sign) is off by twice the force
    real(wp), parameter :: tol_force = 5.0e-7_wp
    !> The reference's Runge-Kutta step [s]
    real(wp), parameter :: rk_step = 1.0e-4_wp

contains

    subroutine collect_acf_command(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("view-pendulum-from-command-file", test_pendulum), &
            & new_unittest("end-and-steps-options", test_options), &
            & new_unittest("no-run-says-both-ways", test_no_run), &
            & new_unittest("command-file-from-another-folder", test_other_folder), &
            & new_unittest("plot-finds-the-command-file-run", test_plot)]
    end subroutine collect_acf_command

    !> rollcon run test/view/pendulum.acf: exit 0, the outputs named by the command file's
    !> second line, 501 rows to t = 5, the CM on the circle of the pendulum's equation
    !> theta'' = m g L cos(theta) / (I + m L^2) released level, and REQUEST/1's displacement
    !> (I = the CM, J = the hinge) the CM's own position; REQUEST/2's force (JOINT/1's markers,
    !> I the ground's: the hinge's force on the ground) answered, and not named in the warning:
    !> m g - m a of the CM, a = theta'' (Z, -X) - theta'^2 (X, Z) from the row's own state.
    subroutine test_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        type(output_layout_type) :: layout
        type(history_type) :: rows
        real(wp) :: theta, omega, t, worst, request_gap, force_gap, turn, rate_squared, &
            & accel(2)
        integer :: status, i, x, z

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch // "/pendulum")
        call make_folder(scratch // "/pendulum")
        call run_rollcon(program, "run test/view/pendulum.acf -q -o " // scratch // "/pendulum", &
            & scratch // "/pendulum.out", scratch // "/pendulum.err", status)
        call check(error, status == 0 .and. file_exists(scratch // "/pendulum/pendulum.csv"), &
            & "exit status " // to_text(status) // ": " // file_text(scratch // "/pendulum.err"))
        if (allocated(error)) return
        call check(error, index(file_text(scratch // "/pendulum.err"), "REQUEST") == 0, &
            & "the warning: " // file_text(scratch // "/pendulum.err"))
        if (allocated(error)) return
        call read_output_csv(scratch // "/pendulum/pendulum.csv", layout, rows, error)
        if (allocated(error)) return
        call check(error, rows%count == 501 .and. rows%rows(1, rows%count) == 5.0_wp, &
            & to_text(rows%count) // " rows to t = " // to_text(rows%rows(1, rows%count)))
        if (allocated(error)) return
        x = layout%column("X_2")
        z = layout%column("Z_2")
        theta = 0.0_wp
        omega = 0.0_wp
        t = 0.0_wp
        worst = 0.0_wp
        request_gap = 0.0_wp
        force_gap = 0.0_wp
        do i = 1, rows%count
            call pendulum_to(rows%rows(1, i), t, theta, omega)
            worst = max(worst, hypot(rows%rows(x, i) - length*cos(theta), rows%rows(z, i) &
                & + length*sin(theta)))
            request_gap = max(request_gap, abs(rows%rows(layout%column("req1_x"), i) &
                & - rows%rows(x, i)), abs(rows%rows(layout%column("req1_z"), i) &
                & - rows%rows(z, i)))
            associate (px => rows%rows(x, i), pz => rows%rows(z, i))
                turn = mass*gravity*px/(inertia + mass*length**2)
                rate_squared = (rows%rows(layout%column("Xdot_2"), i)**2 &
                    & + rows%rows(layout%column("Zdot_2"), i)**2)/length**2
                accel = turn*[pz, -px] - rate_squared*[px, pz]
                force_gap = max(force_gap, abs(rows%rows(layout%column("req2_fx"), i) &
                    & + mass*accel(1)), abs(rows%rows(layout%column("req2_fz"), i) &
                    & - mass*(-gravity - accel(2))))
            end associate
        end do
        call check(error, worst <= tol_position, "the CM off the pendulum's equation by " &
            & // to_text(worst) // " m (allowed " // to_text(tol_position) // ")")
        if (allocated(error)) return
        ! the request measures marker 20 (the CM) from marker 10 (at the ground origin), in
        ! ground axes: the CM's own X and Z, computed from the same state
        call check(error, request_gap <= tol_request, "REQUEST/1 (D, C=...) against the CM: " &
            & // to_text(request_gap))
        if (allocated(error)) return
        call check(error, force_gap <= tol_force, "REQUEST/2 (F, C=JOINT FORCE) against m g - " &
            & // "m a: " // to_text(force_gap) // " N")
    end subroutine test_pendulum

    !> The pendulum's equation theta'' = m g L cos(theta) / (I + m L^2) integrated by the
    !> classical fourth-order Runge-Kutta method at rk_step from (t, theta, omega) to t_end.
    subroutine pendulum_to(t_end, t, theta, omega)
        real(wp), intent(in) :: t_end
        real(wp), intent(inout) :: t, theta, omega
        real(wp) :: h, k1(2), k2(2), k3(2), k4(2)

        do while (t < t_end - 1.0e-12_wp)
            h = min(rk_step, t_end - t)
            k1 = slope(theta, omega)
            k2 = slope(theta + 0.5_wp*h*k1(1), omega + 0.5_wp*h*k1(2))
            k3 = slope(theta + 0.5_wp*h*k2(1), omega + 0.5_wp*h*k2(2))
            k4 = slope(theta + h*k3(1), omega + h*k3(2))
            theta = theta + h*(k1(1) + 2*k2(1) + 2*k3(1) + k4(1))/6
            omega = omega + h*(k1(2) + 2*k2(2) + 2*k3(2) + k4(2))/6
            t = t + h
        end do
    end subroutine pendulum_to

    !> (theta', omega') of the pendulum.
    pure function slope(theta, omega) result(rates)
        real(wp), intent(in) :: theta, omega
        real(wp) :: rates(2)

        rates = [omega, mass*gravity*length*cos(theta)/(inertia + mass*length**2)]
    end function slope

    !> rollcon run test/view/view_export_pendulum.adm --end 1 --steps 100: 101 rows to t = 1
    !> in the dataset's outputs (MODEL.adm.csv); a command file's SIMULATE replaced the same
    !> way (--dtout 0.5: 11 rows to its END = 5).
    subroutine test_options(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program
        type(output_layout_type) :: layout
        type(history_type) :: rows
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch // "/options")
        call make_folder(scratch // "/options")
        call run_rollcon(program, "run test/view/view_export_pendulum.adm --end 1 --steps 100 " &
            & // "-q -o " // scratch // "/options", scratch // "/options.out", scratch &
            & // "/options.err", status)
        call check(error, status == 0, "exit status " // to_text(status) // ": " &
            & // file_text(scratch // "/options.err"))
        if (allocated(error)) return
        call read_output_csv(scratch // "/options/view_export_pendulum.adm.csv", layout, rows, &
            & error)
        if (allocated(error)) return
        call check(error, rows%count == 101 .and. rows%rows(1, rows%count) == 1.0_wp, &
            & to_text(rows%count) // " rows to t = " // to_text(rows%rows(1, rows%count)))
        if (allocated(error)) return
        call run_rollcon(program, "run test/view/pendulum.acf --dtout 0.5 -q -o " // scratch &
            & // "/options", scratch // "/options.out", scratch // "/options.err", status)
        call check(error, status == 0, "exit status " // to_text(status) // ": " &
            & // file_text(scratch // "/options.err"))
        if (allocated(error)) return
        call read_output_csv(scratch // "/options/pendulum.csv", layout, rows, error)
        if (allocated(error)) return
        call check(error, rows%count == 11 .and. rows%rows(1, rows%count) == 5.0_wp, &
            & to_text(rows%count) // " rows to t = " // to_text(rows%rows(1, rows%count)))
    end subroutine test_options

    !> rollcon run test/view/view_export_pendulum.adm alone: exit 1, a message naming both
    !> ways of giving the run, and no outputs.
    subroutine test_no_run(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, message
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch // "/none")
        call make_folder(scratch // "/none")
        call run_rollcon(program, "run test/view/view_export_pendulum.adm -q -o " // scratch &
            & // "/none", scratch // "/none.out", scratch // "/none.err", status)
        message = file_text(scratch // "/none.err")
        call check(error, status == 1 .and. index(message, "view_export_pendulum.adm: no " &
            & // "SIMULATE statement") > 0 .and. index(message, "rollcon run MODEL.acf") > 0 &
            & .and. index(message, "--end T --steps N") > 0 .and. .not. file_exists(scratch &
            & // "/none/view_export_pendulum.adm.csv"), "exit status " // to_text(status) &
            & // ": " // message)
    end subroutine test_no_run

    !> The command file run from another folder: by a path relative to there (the dataset
    !> found from the command file's folder, the outputs in the folder run from), and by an
    !> absolute path.
    subroutine test_other_folder(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, here
        character(len=4096) :: buffer
        integer :: status, length

        call rollcon_program(program, error)
        if (allocated(error)) return
        call get_environment_variable("PWD", buffer, length)
        here = buffer(:length)
        if (program(1:1) /= "/") program = here // "/" // program
        call remove_folder(scratch // "/away")
        call make_folder(scratch // "/away/models")
        call make_folder(scratch // "/away/run")
        call execute_command_line("cp test/view/view_export_pendulum.adm " // scratch &
            & // "/away/models/")
        call write_lines(scratch // "/away/models/short.acf", [character(len=40) :: &
            & "view_export_pendulum.adm", "short", "SIMULATE/DYNAMIC, END=0.5, STEPS=5", "STOP"])
        call execute_command_line("cd " // scratch // "/away/run && " // program &
            & // " run ../models/short.acf -q > out.txt 2> err.txt", exitstat=status)
        call check(error, status == 0 .and. file_exists(scratch // "/away/run/output/short.csv"), &
            & "relative: exit status " // to_text(status) // ": " // file_text(scratch &
            & // "/away/run/err.txt"))
        if (allocated(error)) return
        call execute_command_line("cd / && " // program // " run " // here // "/" // scratch &
            & // "/away/models/short.acf -q -o " // here // "/" // scratch // "/away/abs > " &
            & // here // "/" // scratch // "/away/abs.txt 2>&1", exitstat=status)
        call check(error, status == 0 .and. file_exists(scratch // "/away/abs/short.csv"), &
            & "absolute: exit status " // to_text(status) // ": " // file_text(scratch &
            & // "/away/abs.txt"))
    end subroutine test_other_folder

    !> The outputs of test/view/pendulum.acf are named by its second line, pendulum (not
    !> pendulum.acf, nor the dataset's view_export_pendulum.adm): outputs_name_of says so, and
    !> `rollcon plot test/view/pendulum.acf -o DIR` draws DIR/pendulum.csv, the CSV `rollcon
    !> run test/view/pendulum.acf -o DIR` wrote (where gnuplot is installed); a command file
    !> whose dataset's name is all it gives names its outputs as the dataset's run does.
    subroutine test_plot(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, name, folder
        integer :: status

        call outputs_name_of("test/view/pendulum.acf", name, error)
        if (allocated(error)) return
        call check(error, name == "pendulum", "the outputs of test/view/pendulum.acf: " // name)
        if (allocated(error)) return
        folder = scratch // "/plot"
        call remove_folder(folder)
        call make_folder(folder)
        call write_lines(folder // "/unnamed.acf", [character(len=64) :: &
            & "../../../test/view/view_export_pendulum", "", &
            & "SIMULATE/DYNAMIC, END=1, STEPS=10", "STOP"])
        call outputs_name_of(folder // "/unnamed.acf", name, error)
        if (allocated(error)) return
        call check(error, name == "view_export_pendulum.adm", "the outputs of a command file " &
            & // "with no output name: " // name)
        if (allocated(error)) return
        if (.not. command_available("gnuplot")) return
        call rollcon_program(program, error)
        if (allocated(error)) return
        call run_rollcon(program, "run test/view/pendulum.acf -q -o " // folder, scratch &
            & // "/plot_run.out", scratch // "/plot_run.err", status)
        call check(error, status == 0, "run: exit status " // to_text(status) // ": " &
            & // file_text(scratch // "/plot_run.err"))
        if (allocated(error)) return
        call run_rollcon(program, "plot test/view/pendulum.acf -o " // folder, scratch &
            & // "/plot.out", scratch // "/plot.err", status)
        call check(error, status == 0 .and. index(file_text(scratch // "/plot.out"), &
            & "plot: wrote " // folder // "/pendulum") > 0, "plot: exit status " &
            & // to_text(status) // ": " // file_text(scratch // "/plot.out") &
            & // file_text(scratch // "/plot.err"))
    end subroutine test_plot

end module test_acf_command
