! SPDX-License-Identifier: MIT
!> `rollcon run MODEL.adm` on a part whose IP gives products of inertia, against the same part
!> written by hand on its principal axes (its CM marker already turned onto them, IP the
!> principal moments, WX, WY, WZ about those axes): the same start, the same motion of its
!> principal axes and of a marker on it pushed by a body-fixed force; the principal moments
!> and axes found from the tensor, and given in the startup report.
module test_inertia_command
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix, euler_angles
    use rollcon_output_layout, only : output_layout_type, coord_x, coord_phidot
    use rollcon_simulation, only : history_type
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder
    use command_runs, only : rollcon_program, run_rollcon, file_text
    implicit none
    private

    public :: collect_inertia_command

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_inertia_command"
    !> The principal moments [kg m^2], all different (a tumbling body with no symmetry)
    real(wp), parameter :: moments(3) = [0.05_wp, 0.07_wp, 0.09_wp]
    !> 3-1-3 angles [rad] of the principal axes in the CM marker's axes: a turn of about 0.5
    !> rad, so the closest assignment of eigenvectors to x, y, z is this one
    real(wp), parameter :: turn(3) = [0.3_wp, 0.2_wp, 0.1_wp]
    !> 3-1-3 angles [rad] of the CM marker in the part frame
    real(wp), parameter :: cm_angles(3) = [0.17_wp, 0.87_wp, -0.35_wp]
    !> Angular velocity at the start about the CM marker's axes [rad/s]
    real(wp), parameter :: omega_cm(3) = [1.5_wp, -2.0_wp, 3.0_wp]
    !> The two datasets start from one state up to the round-off of the eigenvectors (1e-16)
    !> and of the Euler angles read back, and each run is integrated with ERROR=1e-10, so their
    !> steps differ: the largest difference of any coordinate, rate or request column over the
    !> 2 s was measured at 4.2e-8 (a rate, of size 3 rad/s). 1e-6 is 25 times that, and 1e6
    !> times below what a wrong mapping gives: WX..WZ left in the CM marker's axes moves a
    !> column by 5.7 in 2 s
    real(wp), parameter :: tol_same_motion = 1.0e-6_wp
    !> The principal moments and axes found from the written tensor (moments below 0.1 kg m^2,
    !> written to 18 digits): measured off by 1.4e-17 kg m^2 and 1.1e-16 in an axis'
    !> components, dsyev's few eps; the bounds leave room for another LAPACK's rounding
    real(wp), parameter :: tol_moments = 1.0e-15_wp, tol_axes = 1.0e-14_wp

contains

    !> Tests of this suite.
    subroutine collect_inertia_command(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("products-as-hand-rotated-part", test_hand_rotated)]
    end subroutine collect_inertia_command

    !> Both datasets run; their parts' 12 columns and the request on marker 21 agree to
    !> tol_same_motion at every row; the products' run reports the principal moments.
    subroutine test_hand_rotated(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, report
        type(output_layout_type) :: layouts(2)
        type(history_type) :: rows(2)
        type(adm_model_type) :: adm
        real(wp) :: p(3, 3), tensor(3, 3), hand_angles(3), difference
        integer :: status(2), k, first, last
        character(len=*), parameter :: names(2) = [character(len=5) :: "prods", "hand"]

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        p = rotation_matrix(turn(1), turn(2), turn(3))
        ! the tensor in the CM marker's axes: P diag(moments) P^T
        tensor = matmul(p, matmul(diagonal(moments), transpose(p)))
        ! ADAMS's products are the positive integrals: Ixy = -T(1, 2), and so on
        call write_dataset(scratch // "/prods.adm", [tensor(1, 1), tensor(2, 2), tensor(3, 3), &
            & -tensor(1, 2), -tensor(1, 3), -tensor(2, 3)], cm_angles, omega_cm)
        ! by hand: the CM marker turned onto the principal axes, WX..WZ about them
        hand_angles = euler_angles(matmul(rotation_matrix(cm_angles(1), cm_angles(2), &
            & cm_angles(3)), p))
        call write_dataset(scratch // "/hand.adm", moments, hand_angles, &
            & matmul(transpose(p), omega_cm))
        ! the same principal moments, on the same axes
        call read_adm(scratch // "/prods.adm", adm, error)
        if (allocated(error)) return
        call check(error, all(abs(adm%parts(2)%ip - moments) <= tol_moments) .and. &
            & all(abs(adm%parts(2)%principal - p) <= tol_axes), "principal moments " &
            & // to_text(adm%parts(2)%ip(1)) // ", " // to_text(adm%parts(2)%ip(2)) // ", " &
            & // to_text(adm%parts(2)%ip(3)) // " kg m^2; axes off by " &
            & // to_text(maxval(abs(adm%parts(2)%principal - p))))
        if (allocated(error)) return
        do k = 1, 2
            call run_rollcon(program, "run " // scratch // "/" // trim(names(k)) // ".adm -o " &
                & // scratch, scratch // "/" // trim(names(k)) // ".out", &
                & scratch // "/" // trim(names(k)) // ".err", status(k))
        end do
        report = file_text(scratch // "/prods.out")
        call check(error, all(status == 0), "exit statuses " // to_text(status(1)) // ", " &
            & // to_text(status(2)) // ": " // file_text(scratch // "/prods.err") &
            & // file_text(scratch // "/hand.err"))
        if (.not. allocated(error)) call check(error, index(report, "principal axes of " &
            & // "PART/2 (IP with products of inertia): moments ") > 0 .and. index(file_text( &
            & scratch // "/hand.out"), "principal axes of") == 0 .and. index(file_text(scratch &
            & // "/prods.adm.summary.txt"), "principal axes of PART/2 (IP with products of " &
            & // "inertia): moments ") > 0, "startup reports and the summary: " // report)
        do k = 1, 2
            if (.not. allocated(error)) call read_output_csv(scratch // "/" // trim(names(k)) &
                & // ".adm.csv", layouts(k), rows(k), error)
        end do
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, rows(1)%count == 201 .and. rows(2)%count == 201, "row counts " &
            & // to_text(rows(1)%count) // ", " // to_text(rows(2)%count))
        if (allocated(error)) return
        first = layouts(1)%part_column(1, coord_x)
        last = layouts(1)%part_column(1, coord_phidot)
        difference = maxval(abs(rows(1)%rows(first:last, :201) - rows(2)%rows(first:last, :201)))
        first = layouts(1)%column("req1_x")
        difference = max(difference, maxval(abs(rows(1)%rows(first:first + 5, :201) &
            & - rows(2)%rows(first:first + 5, :201))))
        call check(error, first > 0 .and. layouts(2)%column("req1_x") == first .and. &
            & difference <= tol_same_motion, "largest difference of the parts' columns and " &
            & // "the request's " // to_text(difference) // " (allowed " &
            & // to_text(tol_same_motion) // ")")
    end subroutine test_hand_rotated

    !> A tumbling body under gravity: its CM marker (20) with the given angles, IP and WX..WZ,
    !> marker 21 off the centre with a body-fixed force and torque on it (RM=21), and a
    !> displacement request on 21. The part frame and marker 21 are the same in both datasets.
    subroutine write_dataset(path, ip, angles, omega)
        character(len=*), intent(in) :: path
        real(wp), intent(in) :: ip(:), angles(3), omega(3)
        integer :: unit, k

        open(newunit=unit, file=path, status="replace", action="write")
        write(unit, '(a)') "a tumbling body, pushed at a marker"
        write(unit, '(a)') "UNITS/SYSTEM=SI"
        write(unit, '(a)') "PART/1, GROUND"
        write(unit, '(a)', advance="no") "PART/2, MASS=2, CM=20, IP="
        do k = 1, size(ip)
            write(unit, '(es25.17e3,a)', advance="no") ip(k), trim(merge(", ", "  ", &
                & k < size(ip)))
        end do
        write(unit, '(a)') ""
        write(unit, '(a)') ", QG=0.1, -0.2, 1, REULER=20D, 30D, 40D, VX=0.3, VY=-0.1, VZ=2"
        write(unit, '(a,es25.17e3,a,es25.17e3,a,es25.17e3)') ", WX=", omega(1), ", WY=", &
            & omega(2), ", WZ=", omega(3)
        write(unit, '(a,es25.17e3,a,es25.17e3,a,es25.17e3)') &
            & "MARKER/20, PART=2, QP=0.01, 0.02, -0.03, REULER=", angles(1), ", ", angles(2), &
            & ", ", angles(3)
        write(unit, '(a)') "MARKER/21, PART=2, QP=0.2, 0.05, -0.1, REULER=5D, 15D, 25D"
        write(unit, '(a)') "ACCGRAV/KGRAV=-9.81"
        write(unit, '(a)') "GFORCE/1, I=21, RM=21, FX=0.5, FY=0, FZ=1, TX=0, TY=0.02, TZ=0"
        write(unit, '(a)') "REQUEST/1, DISPLACEMENT, I=21"
        write(unit, '(a)') "SIMULATE/DYNAMIC, END=2, STEPS=200"
        write(unit, '(a)') "INTEGRATOR/ERROR=1e-10"
        write(unit, '(a)') "END"
        close(unit)
    end subroutine write_dataset

    pure function diagonal(values) result(m)
        real(wp), intent(in) :: values(3)
        real(wp) :: m(3, 3)
        integer :: k

        m = 0.0_wp
        do k = 1, 3
            m(k, k) = values(k)
        end do
    end function diagonal

end module test_inertia_command
