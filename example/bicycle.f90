! SPDX-License-Identifier: MIT
!> The benchmark bicycle of data/bicycle.adm built in code with the rollcon library
!> (docs/library.md, "A dataset's elements as library calls"), run, and checked against the
!> dataset itself: both are run through the library in this program and every output row must
!> be the dataset's to the last bit.
!>
!> Each statement of the dataset is one library call on the model, with the numbers the
!> dataset writes: a PART is model%add_part (its principal moments and axes from its IP by
!> principal_axes when it has products of inertia), a MARKER a marker_type placed by
!> part_marker, a UCON with ROUTINE= model%add_ucon with the built-in routine
!> find_builtin_ucosub finds, a JOINT model%add_joint, the GFORCE model%add_force of a
!> marker_force_type whose FY is compile_expression of the dataset's text, ACCGRAV
!> model%gravity, SIMULATE and INTEGRATOR a run_settings_type. A part's start is part_start of
!> its CM marker and velocities; the source watches the parts' theta limit as a dataset does
!> (re-basing at adm_theta_min) and makes the start consistent (consistent_start) as a
!> dataset's is.
!>
!> Exit status: 0 when every row is the dataset's bit for bit, 1 when a row, the layout or the
!> outcome differs or a run fails.
program bicycle
    use, intrinsic :: iso_fortran_env, only : error_unit, int64
    use rollcon, only : wp, error_type, fatal_error, stat_input, model_type, part_type, &
        & marker_type, part_marker, part_start, principal_axes, rotation_matrix, &
        & find_builtin_ucosub, ucosub_interface, &
        & applied_force_type, profile_statement, marker_force_type, kind_general, &
        & compile_expression, setup_model, run_settings_type, formulation_ida, &
        & built_model_source_type, new_model_source, new_theta_watch, adm_theta_min, job_type, &
        & new_job, load_job, run_job, job_result_type, history_type, use_one_blas_thread, &
        & to_text
    implicit none

    !> The dataset this program builds in code
    character(len=*), parameter :: dataset = "data/bicycle.adm"
    !> A quarter turn as the dataset writes it [rad]
    real(wp), parameter :: quarter = 1.5707963267948966_wp
    !> The identity: the principal axes of a part without products of inertia, in its CM
    !> marker's axes
    real(wp), parameter :: identity(3, 3) = reshape([1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, &
        & 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], [3, 3])
    !> The steer axis's marker (MARKER/32 on the rear frame, MARKER/41 on the front frame):
    !> origin [m] and 3-1-3 angles [rad] in ground
    real(wp), parameter :: steer_origin(3) = [0.9894982606238152_wp, 0.0_wp, &
        & 0.3400893841073147_wp]
    real(wp), parameter :: steer_angles(3) = [-1.5707963267948966_wp, 0.3141592653589793_wp, &
        & 1.5707963267948966_wp]

    type(error_type), allocatable :: error
    type(history_type) :: from_dataset, from_code
    type(job_result_type) :: dataset_result, code_result
    character(len=:), allocatable :: blas_library

    call use_one_blas_thread(blas_library)
    call run_dataset(from_dataset, dataset_result, error)
    if (allocated(error)) call fail(dataset // ": " // error%message)
    call run_code(from_code, code_result, error)
    if (allocated(error)) call fail("the bicycle in code: " // error%message)
    call compare(from_dataset, from_code, dataset_result, code_result)

contains

    !> data/bicycle.adm as rollcon runs it (load_job, run_job), its rows kept.
    subroutine run_dataset(rows, result, error)
        type(history_type), intent(out) :: rows
        type(job_result_type), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job

        call load_job(dataset, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
    end subroutine run_dataset

    !> The bicycle built in code, run as a job of its own, its rows kept.
    subroutine run_code(rows, result, error)
        type(history_type), intent(out) :: rows
        type(job_result_type), intent(out) :: result
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(built_model_source_type) :: source
        type(run_settings_type) :: settings
        type(job_type) :: job
        real(wp) :: q0(24), u0(24)

        call build_model(model, q0, u0, error)
        if (allocated(error)) return
        ! SIMULATE/DYNAMIC, END=10, STEPS=1000; INTEGRATOR/FORMULATION=IDA, ERROR=1E-10
        settings%formulation = formulation_ida
        settings%rtol = 1.0e-10_wp
        settings%atol = 1.0e-10_wp
        settings%end_time = 10.0_wp
        settings%output_step = 10.0_wp/1000.0_wp
        source = new_model_source("bicycle", model, q0, u0, settings)
        ! as for every dataset: a part near the Euler singularity is re-based, and the start
        ! is made consistent by the initial-conditions analysis
        call source%add_watch(new_theta_watch(adm_theta_min, rebase=.true.))
        source%consistent_start = .true.
        job = new_job(source)
        call run_job(job, result, error, rows)
    end subroutine run_code

    !> The model of data/bicycle.adm, statement by statement, and its start (q0, u0: four parts
    !> of 6 coordinates and 6 rates each, in the order added).
    subroutine build_model(model, q0, u0, error)
        type(model_type), intent(out) :: model
        real(wp), intent(out) :: q0(24), u0(24)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: frame_moments(3), frame_axes(3, 3), fork_moments(3), fork_axes(3, 3)
        type(marker_type) :: marker_21, marker_31, marker_32, marker_41, marker_42, marker_51
        integer :: k

        ! PART/3 and PART/4: IP with the product xz (xx, yy, zz, xy, xz, yz) [kg m^2]
        call principal_axes([9.2_wp, 11.0_wp, 2.8_wp, 0.0_wp, 2.4_wp, 0.0_wp], frame_moments, &
            & frame_axes, error)
        if (allocated(error)) return
        call principal_axes([0.05892_wp, 0.06_wp, 0.00708_wp, 0.0_wp, -0.00756_wp, 0.0_wp], &
            & fork_moments, fork_axes, error)
        if (allocated(error)) return
        ! the parts, in the dataset's order (the ground, PART/1, is not one): model parts 1 to 4
        call model%add_part(part_type(id=2, mass=2.0_wp, inertia=[0.0603_wp, 0.0603_wp, &
            & 0.12_wp]))
        call model%add_part(part_type(id=3, mass=85.0_wp, inertia=frame_moments))
        call model%add_part(part_type(id=4, mass=4.0_wp, inertia=fork_moments))
        call model%add_part(part_type(id=5, mass=3.0_wp, inertia=[0.1405_wp, 0.1405_wp, &
            & 0.28_wp]))
        ! each part's start from its CM marker (every part's frame is ground's) and VX, WZ
        call part_start([0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp, &
            & 0.3_wp], [0.0_wp, quarter, 0.0_wp], identity, [5.0_wp, 0.0_wp, 0.0_wp], &
            & [0.0_wp, 0.0_wp, -16.666666666666668_wp], q0(1:6), u0(1:6))
        call part_start([0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], [0.3_wp, 0.0_wp, &
            & 0.9_wp], [0.0_wp, 0.0_wp, 0.0_wp], frame_axes, [5.0_wp, 0.0_wp, 0.0_wp], &
            & [0.0_wp, 0.0_wp, 0.0_wp], q0(7:12), u0(7:12))
        call part_start([0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], [0.9_wp, 0.0_wp, &
            & 0.7_wp], [0.0_wp, 0.0_wp, 0.0_wp], fork_axes, [5.0_wp, 0.0_wp, 0.0_wp], &
            & [0.0_wp, 0.0_wp, 0.0_wp], q0(13:18), u0(13:18))
        call part_start([0.0_wp, 0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp, 0.0_wp], [1.02_wp, 0.0_wp, &
            & 0.35_wp], [0.0_wp, quarter, 0.0_wp], identity, [5.0_wp, 0.0_wp, 0.0_wp], &
            & [0.0_wp, 0.0_wp, -14.285714285714286_wp], q0(19:24), u0(19:24))
        ! the joints' markers, in their parts' principal axes
        marker_21 = part_marker(21, 1, [0.0_wp, 0.0_wp, 0.3_wp], rotation_matrix(0.0_wp, &
            & quarter, 0.0_wp), [0.0_wp, 0.0_wp, 0.3_wp], rotation_matrix(0.0_wp, quarter, &
            & 0.0_wp), identity)
        marker_31 = part_marker(31, 2, [0.0_wp, 0.0_wp, 0.3_wp], rotation_matrix(0.0_wp, &
            & quarter, 0.0_wp), [0.3_wp, 0.0_wp, 0.9_wp], rotation_matrix(0.0_wp, 0.0_wp, &
            & 0.0_wp), frame_axes)
        marker_32 = part_marker(32, 2, steer_origin, rotation_matrix(steer_angles(1), &
            & steer_angles(2), steer_angles(3)), [0.3_wp, 0.0_wp, 0.9_wp], &
            & rotation_matrix(0.0_wp, 0.0_wp, 0.0_wp), frame_axes)
        marker_41 = part_marker(41, 3, steer_origin, rotation_matrix(steer_angles(1), &
            & steer_angles(2), steer_angles(3)), [0.9_wp, 0.0_wp, 0.7_wp], &
            & rotation_matrix(0.0_wp, 0.0_wp, 0.0_wp), fork_axes)
        marker_42 = part_marker(42, 3, [1.02_wp, 0.0_wp, 0.35_wp], rotation_matrix(0.0_wp, &
            & quarter, 0.0_wp), [0.9_wp, 0.0_wp, 0.7_wp], rotation_matrix(0.0_wp, 0.0_wp, &
            & 0.0_wp), fork_axes)
        marker_51 = part_marker(51, 4, [1.02_wp, 0.0_wp, 0.35_wp], rotation_matrix(0.0_wp, &
            & quarter, 0.0_wp), [1.02_wp, 0.0_wp, 0.35_wp], rotation_matrix(0.0_wp, quarter, &
            & 0.0_wp), identity)
        ! UCON/1 to UCON/6: each wheel rolls without slip on the ground (PAR: part, codes, r)
        do k = 1, 2
            call add_builtin(model, k, [2.0_wp, 21.0_wp, 22.0_wp, 23.0_wp, 14.0_wp, 15.0_wp, &
                & 24.0_wp, 25.0_wp, 26.0_wp, 0.3_wp, real(k, wp)], "rolling_disk", error)
            if (allocated(error)) return
        end do
        call add_builtin(model, 3, [2.0_wp, 13.0_wp, 15.0_wp, 0.3_wp], "disk_height", error)
        if (allocated(error)) return
        do k = 1, 2
            call add_builtin(model, 3 + k, [5.0_wp, 21.0_wp, 22.0_wp, 23.0_wp, 14.0_wp, &
                & 15.0_wp, 24.0_wp, 25.0_wp, 26.0_wp, 0.35_wp, real(k, wp)], "rolling_disk", &
                & error)
            if (allocated(error)) return
        end do
        call add_builtin(model, 6, [5.0_wp, 13.0_wp, 15.0_wp, 0.35_wp], "disk_height", error)
        if (allocated(error)) return
        ! JOINT/1 to JOINT/3: the rear axle, the steer axis, the front axle (UCONs 7 to 21)
        call model%add_joint(1, "REVOLUTE", marker_21, marker_31, error)
        if (allocated(error)) return
        call model%add_joint(2, "REVOLUTE", marker_41, marker_32, error)
        if (allocated(error)) return
        call model%add_joint(3, "REVOLUTE", marker_51, marker_42, error)
        if (allocated(error)) return
        call add_push(model, frame_axes, error)
        if (allocated(error)) return
        ! ACCGRAV/KGRAV=-9.81 [m/s^2]
        model%gravity = [0.0_wp, 0.0_wp, -9.81_wp]
        call setup_model(model, error)
    end subroutine build_model

    !> UCON/id, FUNCTION=USER(par), ROUTINE=name.
    subroutine add_builtin(model, id, par, name, error)
        type(model_type), intent(inout) :: model
        integer, intent(in) :: id
        real(wp), intent(in) :: par(:)
        character(len=*), intent(in) :: name
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine
        logical :: time_free, found

        call find_builtin_ucosub(name, routine, time_free, found)
        if (.not. found) then
            call fatal_error(error, "no built-in routine " // name, stat_input)
            return
        end if
        call model%add_ucon(id, par, routine, time_free=time_free, routine=name)
    end subroutine add_builtin

    !> GFORCE/1, I=30, JFLOAT=2, RM=1, FX=0, FZ=0, TX=0, TY=0, TZ=0, FY=...: the push on the
    !> rear frame's centre of mass, in ground axes (markers 1 and 2 are ground's, at the
    !> origin).
    subroutine add_push(model, frame_axes, error)
        type(model_type), intent(inout) :: model
        !> The rear frame's principal axes in its CM marker's axes
        real(wp), intent(in) :: frame_axes(3, 3)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: fy = "IF(TIME - 1: 0, 0, IF(TIME - 1.1: " &
            & // "7.853981633974483*SIN(PI*(TIME - 1)/0.1), " &
            & // "7.853981633974483*SIN(PI*(TIME - 1)/0.1), 0))"
        type(applied_force_type) :: push
        type(marker_force_type) :: statement
        integer :: k

        statement%kind = kind_general
        ! I: the rear frame's CM marker, MARKER/30 (its IP has products: not the principal axes)
        statement%i = part_marker(30, 2, [0.3_wp, 0.0_wp, 0.9_wp], rotation_matrix(0.0_wp, &
            & 0.0_wp, 0.0_wp), [0.3_wp, 0.0_wp, 0.9_wp], rotation_matrix(0.0_wp, 0.0_wp, &
            & 0.0_wp), frame_axes)
        statement%j = marker_type(id=2)
        statement%rm = marker_type(id=1)
        do k = 1, 6
            if (k == 2) then
                call compile_expression(fy, "bicycle: GFORCE/1 FY", statement%functions(k), &
                    & error)
            else
                call compile_expression("0", "bicycle: GFORCE/1", statement%functions(k), error)
            end if
            if (allocated(error)) return
        end do
        statement%given = .true.
        allocate(statement%markers(0))
        push%profile = profile_statement
        push%statement = statement
        push%name = "bicycle: GFORCE/1"
        call model%add_force(push)
    end subroutine add_push

    !> Every row of the two runs the same to the last bit, with the same layout and outcome.
    subroutine compare(expected, actual, expected_result, actual_result)
        type(history_type), intent(in) :: expected, actual
        type(job_result_type), intent(in) :: expected_result, actual_result
        integer :: i, j, differ

        if (expected%count == 0 .or. actual%count /= expected%count .or. size(actual%rows, 1) &
            & /= size(expected%rows, 1)) call fail("rows: " // to_text(actual%count) // " of " &
            & // to_text(size(actual%rows, 1)) // " columns against the dataset's " &
            & // to_text(expected%count) // " of " // to_text(size(expected%rows, 1)))
        if (size(actual%layout%header()) /= size(expected%layout%header())) &
            & call fail("the columns are not the dataset's")
        if (any(actual%layout%header() /= expected%layout%header())) &
            & call fail("the columns are not the dataset's")
        if (actual_result%summary%status /= expected_result%summary%status) &
            & call fail("the run ended otherwise than the dataset's")
        differ = 0
        do i = 1, expected%count
            do j = 1, size(expected%rows, 1)
                if (transfer(actual%rows(j, i), 0_int64) /= transfer(expected%rows(j, i), &
                    & 0_int64)) then
                    differ = differ + 1
                    if (differ == 1) write(error_unit, '(a)') "bicycle: first difference: row " &
                        & // to_text(i) // ", column " // to_text(j) // ": " &
                        & // to_text(actual%rows(j, i)) // " against the dataset's " &
                        & // to_text(expected%rows(j, i))
                end if
            end do
        end do
        if (differ > 0) call fail(to_text(differ) // " values differ from the dataset's")
        write(*, '(a)') "bicycle: the model built in code gives data/bicycle.adm's " &
            & // to_text(expected%count) // " rows of " // to_text(size(expected%rows, 1)) &
            & // " columns, bit for bit"
    end subroutine compare

    subroutine fail(message)
        character(len=*), intent(in) :: message

        write(error_unit, '(a)') "bicycle: " // message
        error stop 1
    end subroutine fail

end program bicycle
