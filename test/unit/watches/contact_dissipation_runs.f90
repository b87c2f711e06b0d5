! SPDX-License-Identifier: MIT
!> A rim's dissipation (ROLLING_RESISTANCE, AIR_VISCOSITY) on one of a dataset's several
!> CONTACTs (rollcon_adm_contact: the dissipating rim's mode is the equations' contact, the
!> others their more_contacts), for the suite contact-datasets: a coin rolling against its
!> rolling resistance beside a ball thrown to slide, each as it runs alone.
module contact_dissipation_runs
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_dataset_source, only : dataset_source_type, new_dataset_source
    use rollcon_simulation, only : run_options_type, simulate, history_type, run_summary_type, &
        & status_completed
    use rollcon_output_layout, only : coord_x, coord_xdot
    use rollcon_output_files, only : write_text_file, make_folders
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_rim_beside_ball

    !> Where the datasets are written
    character(len=*), parameter :: folder = "build/test_contact_dissipation"
    character(len=*), parameter :: nl = new_line("a")
    !> The coin (PART/2, R = 0.1 m, upright, rolling at 1 m/s) under CONTACT/7 with rolling
    !> resistance delta = 1e-4 m (test_rolling_resistance's), and its ground plane
    character(len=*), parameter :: coin_lines = &
        & "PART/2, MASS=0.73513268094001172, CM=3" // nl &
        & // ", IP=1.8383830518607345E-3, 1.8383830518607345E-3, 3.6756634047000595E-3" // nl &
        & // ", QG=0, 0, 0.1, VX=1, WX=0, WY=0, WZ=-10" // nl &
        & // "MARKER/3, PART=2, REULER=0D, 90D, 0D" // nl &
        & // "GRAPHICS/2, CYLINDER, CM=3, RADIUS=0.1, LENGTH=0.003" // nl &
        & // "CONTACT/7, IGEOM=2, JGEOM=1, MU_STATIC=0.3, ROLLING_RESISTANCE=1.0E-4" // nl
    !> The ball (PART/4, m = 1 kg, R = 0.05 m, 0.5 m from the coin along Y) thrown along X at
    !> 1 m/s without spin under CONTACT/1, mu = 0.3: it slides until t* = 2 v0 / (7 mu g)
    !> (data/sphere_thrown.adm's ball)
    character(len=*), parameter :: ball_lines = &
        & "PART/4, MASS=1, CM=41, IP=1.0E-3, 1.0E-3, 1.0E-3, QG=0, 0.5, 0.05" // nl &
        & // ", VX=1, VY=0, VZ=0, WX=0, WY=0, WZ=0" // nl &
        & // "MARKER/41, PART=4, REULER=0D, 90D, 0D" // nl &
        & // "GRAPHICS/5, ELLIPSOID, CM=41, XSCALE=0.1, YSCALE=0.1, ZSCALE=0.1" // nl &
        & // "CONTACT/1, IGEOM=5, JGEOM=1, MU_STATIC=0.3, MU_DYNAMIC=0.3" // nl

contains

    !> The dataset's text: its title, the ground and its plane, gravity, the given parts and
    !> CONTACTs, 0.5 s at rows 1 ms apart in the given formulation, rtol 1e-10.
    pure function dataset(parts, formulation) result(text)
        character(len=*), intent(in) :: parts, formulation
        character(len=:), allocatable :: text

        text = "rim and ball" // nl // "UNITS/SYSTEM=SI" // nl // "PART/1, GROUND" // nl &
            & // "MARKER/1, PART=1" // nl // "ACCGRAV/KGRAV=-9.81" // nl &
            & // "GRAPHICS/1, PLANE, RM=1, XMIN=-1, XMAX=1, YMIN=-1, YMAX=1" // nl // parts &
            & // "SIMULATE/DYNAMIC, END=0.5, DTOUT=0.001" // nl &
            & // "INTEGRATOR/FORMULATION=" // formulation // ", RTOL=1.0E-10, ATOL=1.0E-12" &
            & // nl // "END" // nl
    end function dataset

    !> Write, read, build and run a dataset (every row kept); it must complete.
    subroutine run_text(name, text, history, summary, error)
        character(len=*), intent(in) :: name, text
        type(history_type), intent(out) :: history
        type(run_summary_type), intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(dataset_source_type) :: source
        type(problem_type), target :: problem
        type(run_options_type) :: options
        procedure(ucosub_interface), pointer :: none
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report, path

        call make_folders(folder, error)
        if (allocated(error)) return
        path = folder // "/" // name // ".adm"
        call write_text_file(path, text, error)
        if (allocated(error)) return
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
        call problem%release()
        if (allocated(error)) return
        if (summary%status /= status_completed) call fatal_error(error, path &
            & // " did not complete: " // summary%message)
    end subroutine run_text

    !> The coin with rolling resistance (CONTACT/7) and the thrown ball (CONTACT/1, first in
    !> the file, so that the rim's is not the first CONTACT) in one dataset: each part's 12
    !> coordinates and rates at every row as in its own one-contact dataset, the coin's
    !> `dissipated` column as its alone, the ball's switch listed under its CONTACT, and the
    !> coin's speed v0 - (2/3) delta g t / R (test_rolling_resistance's law), on CVODE; on
    !> IDA the pair is refused, naming the rim's CONTACT and FORMULATION=CVODE. While the
    !> ball slides (to 0.097 s) its friction acts beside the rim's resistance: with either
    !> left out, or the resistance coupled to the ball's normal force, a part would leave its
    !> alone run by 1e-3 (the law over 0.1 s) to 0.3 m/s.
    subroutine test_rim_beside_ball(error)
        type(error_type), allocatable, intent(out) :: error
        ! A coordinate or rate against the part's run alone [SI]: both runs integrate the same
        ! equations of the part (the contacts do not couple) at rtol 1e-10, to different steps
        ! (the pair's steps and restarts are both parts'); measured 5.0e-10 (the coin's, over
        ! coordinates up to 5 rad) and 5.0e-12 (the ball's); bound 1e-9, where leaving out the
        ! ball's friction or the rim's law moves a part by 1e-3 to 0.3
        real(wp), parameter :: same_tol = 1.0e-9_wp
        ! The coin's energy dissipated [J] against its run alone: integrated with the state to
        ! the integrator's tolerance, rtol 1e-10 of 3.6e-3 J; measured 4e-19 J; bound 1e-12 J
        real(wp), parameter :: work_tol = 1.0e-12_wp
        ! The coin's speed against the law [m/s]: test_rolling_resistance's bound
        real(wp), parameter :: speed_tol = 1.0e-10_wp
        real(wp), parameter :: delta = 1.0e-4_wp, radius = 0.1_wp, g = 9.81_wp
        character(len=*), parameter :: formulations(1) = [character(len=5) :: "CVODE"]
        type(history_type) :: pair, coin, ball
        type(run_summary_type) :: summary
        character(len=:), allocatable :: form
        type(error_type), allocatable :: refused
        real(wp) :: worst
        integer :: f, k, j, p_pair, p_alone

        do f = 1, size(formulations)
            form = trim(formulations(f))
            call run_text("pair_" // form, dataset(ball_lines // coin_lines, form), pair, &
                & summary, error)
            if (allocated(error)) return
            call check(error, index(summary%watch_lines, "CONTACT/7 (line 17): dissipation: " &
                & // "rolling resistance delta = 0.0001 m") > 0 .and. index(summary%watch_lines, &
                & "CONTACT/1 (line 11): t = ") > 0, form // ": the pair's summary has no " &
                & // "dissipation or no switch of the ball: " // summary%watch_lines)
            if (allocated(error)) return
            call run_text("coin_" // form, dataset(coin_lines, form), coin, summary, error)
            if (allocated(error)) return
            call run_text("ball_" // form, dataset(ball_lines, form), ball, summary, error)
            if (allocated(error)) return
            call check(error, pair%count == coin%count .and. pair%count == ball%count, &
                & form // ": rows " // to_text(pair%count) // ", " // to_text(coin%count) &
                & // ", " // to_text(ball%count))
            if (allocated(error)) return
            ! each part against its run alone, every coordinate and rate at every row
            worst = 0.0_wp
            p_pair = pair%layout%part_index(2)
            p_alone = coin%layout%part_index(2)
            do j = 1, pair%count
                do k = 0, 11
                    worst = max(worst, abs(pair%rows(pair%layout%part_column(p_pair, &
                        & coord_x) + k, j) - coin%rows(coin%layout%part_column(p_alone, &
                        & coord_x) + k, j)))
                end do
            end do
            call check(error, worst <= same_tol, form // ": the coin beside the ball " &
                & // "leaves its run alone by " // to_text(worst))
            if (allocated(error)) return
            worst = 0.0_wp
            p_pair = pair%layout%part_index(4)
            p_alone = ball%layout%part_index(4)
            do j = 1, pair%count
                do k = 0, 11
                    worst = max(worst, abs(pair%rows(pair%layout%part_column(p_pair, &
                        & coord_x) + k, j) - ball%rows(ball%layout%part_column(p_alone, &
                        & coord_x) + k, j)))
                end do
            end do
            call check(error, worst <= same_tol, form // ": the ball beside the coin " &
                & // "leaves its run alone by " // to_text(worst))
            if (allocated(error)) return
            call check(error, pair%rows(pair%layout%column("dissipated"), pair%count), &
                & coin%rows(coin%layout%column("dissipated"), coin%count), form &
                & // ": the coin's energy dissipated against its run alone [J]", &
                & abs_tol=work_tol)
            if (allocated(error)) return
            p_pair = pair%layout%part_index(2)
            do j = 1, pair%count
                call check(error, pair%rows(pair%layout%part_column(p_pair, coord_xdot), &
                    & j), 1.0_wp - 2.0_wp/3.0_wp*delta*g/radius*pair%rows(1, j), form &
                    & // ": the coin's speed at t = " // to_text(pair%rows(1, j)) &
                    & // " s [m/s]", abs_tol=speed_tol)
                if (allocated(error)) return
            end do
        end do
        call run_text("pair_IDA", dataset(ball_lines // coin_lines, "IDA"), pair, summary, &
            & refused)
        call check(error, allocated(refused), "the pair on IDA was run")
        if (allocated(error)) return
        call check(error, index(refused%message, "pair_IDA.adm:17: CONTACT/7: " &
            & // "ROLLING_RESISTANCE and AIR_VISCOSITY beside other CONTACTs are integrated " &
            & // "in the ODE form: write INTEGRATOR/FORMULATION=CVODE") > 0, "the refusal on " &
            & // "IDA: " // refused%message)
    end subroutine test_rim_beside_ball

end module contact_dissipation_runs
