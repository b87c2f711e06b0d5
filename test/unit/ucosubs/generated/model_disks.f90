! SPDX-License-Identifier: MIT
!> models/turntable-disk-* and models/disk-height-*: the coin's disk upright on a turntable
!> against the steady motion of docs/models.md, and data/disk_height.adm (the coin with its
!> height as a position UCON) against data/coin.adm (the velocity form), on CVODE and IDA.
module model_disks
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use model_runs, only : run_model, model_run_type, formulation_cvode, formulation_ida
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_turntable_disk_ida, test_turntable_disk_cvode
    public :: test_disk_height_ida, test_disk_height_cvode

    !> data/turntable_disk.adm: table rate Omega [rad/s], radius of the centre's circle [m]
    real(wp), parameter :: table_rate = 3.0_wp, circle_radius = 0.5_wp
    !> The steady motion is exact; the integration error (ERROR = 1e-10) over two turns of the
    !> circle, measured 1.9e-7 (IDA; 1.1e-6 at IDA's default Newton coefficient,
    !> docs/design.md §7) and 1.6e-7 (CVODE) in the worst of X, Y [m], theta [rad], psidot and
    !> phidot [rad/s]; 6e-7, so that a tenfold loss fails. The rows are compared with the motion
    !> itself, so a rate other than C Omega / (C + m R^2) (a ring's, C = m R^2, gives Omega/2:
    !> 0.5 rad/s more) or a disk that tilts away from upright fails at once
    real(wp), parameter :: tol_steady = 6.0e-7_wp
    !> The coin to 3 s (1 s past the strike) in its two forms, both at rtol = atol = 1e-10.
    !> The forms are the same equations on the constraint manifold, but the integrators walk
    !> different Newton paths, so each run carries its own integration error, which the coin's
    !> instability after the strike amplifies (test_adm_build). Measured difference: 5.6e-6
    !> (IDA), 5.2e-6 (CVODE) in state units, and 100 times more at the dataset's 1e-8: it is
    !> integration error. The coin at 1e-8 against itself at 1e-10 differs by 1.2e-4 (IDA) and
    !> 8e-4 (CVODE); 5e-5 lies between, so a difference of the forms as large as the
    !> integrators' own error at 1e-8 fails
    real(wp), parameter :: tol_same_motion = 5.0e-5_wp
    !> Tolerance both forms run at [1]: tighter than the dataset's 1e-8, so that their
    !> difference measures the forms and not the integrators
    real(wp), parameter :: run_tolerance = 1.0e-10_wp
    !> Time the two forms of the coin are compared to [s]
    real(wp), parameter :: compare_until = 3.0_wp

contains

    subroutine test_turntable_disk_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_turntable_disk(formulation_ida, error)
    end subroutine test_turntable_disk_ida

    subroutine test_turntable_disk_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_turntable_disk(formulation_cvode, error)
    end subroutine test_turntable_disk_cvode

    !> Every row on the steady motion: centre at circle_radius (sin w t, -cos w t, R), upright,
    !> precessing at w = C Omega / (C + m R^2) and spinning at (Omega - w) circle_radius / R.
    subroutine check_turntable_disk(formulation, error)
        integer, intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        type(model_run_type) :: run
        real(wp) :: rate, spin, worst
        integer :: i

        call run_model("turntable_disk", formulation, run, error)
        if (allocated(error)) return
        associate (c => run%inertia(3), m => run%mass, radius => run%history%rows(4, 1))
            rate = c*table_rate/(c + m*radius**2)
            spin = (table_rate - rate)*circle_radius/radius
        end associate
        call check(error, rate, table_rate/3.0_wp, "w = Omega/3 for a uniform disk", &
            & rel_tol=1.0e-12_wp)
        if (allocated(error)) return
        worst = 0.0_wp
        do i = 1, run%history%count
            associate (row => run%history%rows(:, i))
                worst = max(worst, abs(row(2) - circle_radius*sin(rate*row(1))), &
                    & abs(row(3) + circle_radius*cos(rate*row(1))), abs(row(6) - 0.5_wp*pi), &
                    & abs(row(11) - rate), abs(row(13) - spin))
            end associate
        end do
        call check(error, worst, 0.0_wp, "largest departure from the steady motion", &
            & abs_tol=tol_steady)
    end subroutine check_turntable_disk

    subroutine test_disk_height_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_disk_height(formulation_ida, error)
    end subroutine test_disk_height_ida

    subroutine test_disk_height_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_disk_height(formulation_cvode, error)
    end subroutine test_disk_height_cvode

    !> The coin with the holonomic height and with the velocity form: the same rows to 3 s,
    !> after the strike has tipped it.
    subroutine check_disk_height(formulation, error)
        integer, intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        type(model_run_type) :: position_form, velocity_form
        real(wp) :: worst
        integer :: i

        call run_model("disk_height", formulation, position_form, error, compare_until, &
            & run_tolerance)
        if (allocated(error)) return
        call run_model("coin", formulation, velocity_form, error, compare_until, &
            & run_tolerance)
        if (allocated(error)) return
        call check(error, position_form%history%count == velocity_form%history%count, &
            & "as many rows")
        if (allocated(error)) return
        ! the strike tipped the disk by more than 0.1 rad: the comparison is not of two
        ! straight rolls
        call check(error, maxval(abs(velocity_form%history%rows(6, :velocity_form%history%count) &
            & - 0.5_wp*pi)) > 0.1_wp, "the strike tips the coin")
        if (allocated(error)) return
        worst = 0.0_wp
        do i = 1, velocity_form%history%count
            worst = max(worst, maxval(abs(position_form%history%rows(2:13, i) &
                & - velocity_form%history%rows(2:13, i))))
        end do
        call check(error, worst, 0.0_wp, "largest difference of the two forms' states", &
            & abs_tol=tol_same_motion)
    end subroutine check_disk_height

end module model_disks
