! SPDX-License-Identifier: MIT
!> The unit of a UCON's multiplier (suite multiplier-units, docs/outputs.md): a velocity UCON in
!> m/s has its multiplier in newtons, like a position UCON in m. The coin's lambda_1, lambda_2,
!> lambda_3 are the contact force Fx, Fy, Fz over a run with the push, and lambda_3 of rolling
!> upright is the weight m g; the multipliers figure's axis says N.
module test_multiplier_units
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_load, only : load_job, input_override_type
    use rollcon_job, only : job_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type
    use rollcon_figures, only : plot_output
    use rollcon_gnuplot, only : gnuplot_available
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    use picture_files, only : two_part_run, write_run, make_folder, remove_folder
    implicit none
    private

    public :: collect_multiplier_units

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_multiplier_units"
    !> The coin (data/coin.nml) runs past its push at 2 s to this time [s]
    character(len=*), parameter :: coin_end = "2.5"
    !> Fx is sum_k lambda_k dF_k/dXdot with dF_k/dXdot = 1, 0, 0 (likewise Fy, Fz): equal up to
    !> rounding of the multipliers' size
    real(wp), parameter :: tol_same = 1.0e-12_wp
    !> lambda_3 at the start comes from the saddle-point solve (condition ~1e3, eps ~1e-16)
    real(wp), parameter :: tol_weight = 1.0e-10_wp
    !> The coin's disk (data/coin.nml): radius, thickness [m], density [kg/m^3], gravity [m/s^2]
    real(wp), parameter :: radius = 0.1_wp, thickness = 0.003_wp, density = 7800.0_wp, &
        & gravity = 9.81_wp

contains

    subroutine collect_multiplier_units(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("coin-multipliers-are-the-contact-force", test_coin_force), &
            & new_unittest("multipliers-figure-in-newtons", test_figure_label)]
    end subroutine collect_multiplier_units

    !> The coin to 2.5 s (rolling upright, pushed at 2 s, tipping): in every row lambda_k of
    !> UCON k (the contact point's velocity along X, Y, Z [m/s]) equals the contact force's
    !> component Fx, Fy, Fz [N]; at t = 0, rolling upright at constant speed, lambda_3 is the
    !> disk's weight m g [N].
    subroutine test_coin_force(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=2), parameter :: force_names(3) = ["Fx", "Fy", "Fz"]
        type(job_type) :: job
        type(job_result_type) :: result
        type(history_type) :: history
        real(wp) :: scale, weight
        integer :: k

        call load_job("coin", job, error, overrides=[input_override_type("run%end_time", &
            & coin_end)])
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, history)
        if (allocated(error)) return
        associate (layout => history%layout, n => history%count)
            call check(error, n > 200 .and. layout%column("Fx") > 0, to_text(n) // " rows, " &
                & // "Fx in column " // to_text(layout%column("Fx")))
            if (allocated(error)) return
            scale = maxval(abs(history%rows(layout%column("Fx"):layout%column("Fz"), :n)))
            do k = 1, 3
                call check(error, history%rows(layout%multiplier_column(k), :n), &
                    & history%rows(layout%column(force_names(k)), :n), "lambda_" &
                    & // to_text(k) // " against " // force_names(k) // " [N]", &
                    & abs_tol=tol_same*scale)
                if (allocated(error)) return
            end do
            weight = density*pi*radius**2*thickness*gravity
            call check(error, history%rows(layout%multiplier_column(3), 1), weight, &
                & "lambda_3 at t = 0, rolling upright: the weight m g [N]", rel_tol=tol_weight)
        end associate
    end subroutine test_coin_force

    !> The multipliers figure of a model (the two-part run): its y axis says N (and N m for a
    !> UCON on an angle), never N s/m (skipped without gnuplot).
    subroutine test_figure_label(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: expected = "set ylabel " &
            & // "'λ_k [N for F_k in m/s or m; N m for F_k in rad/s or rad]'"
        character(len=:), allocatable :: script

        if (.not. gnuplot_available()) then
            call skip_test(error, "gnuplot not found (Debian gnuplot-nox; bash .ci/setup)")
            return
        end if
        call make_folder(scratch)
        call write_run(scratch // "/two.csv", two_part_run(), .true., error)
        if (.not. allocated(error)) call plot_output(scratch // "/two.csv", scratch, error, &
            & script=script)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, index(script, expected) > 0 .and. index(script, "N s/m") == 0, &
            & "the multipliers figure's axis is not labelled " // expected)
    end subroutine test_figure_label

end module test_multiplier_units
