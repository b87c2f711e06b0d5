! SPDX-License-Identifier: MIT
!> The namelist scenes' consistency rules as a special case of the initial-conditions analysis:
!> from a scene's X, Y, angles and rates held exact, the analysis gives the start the scene
!> reader derives (rollcon_scene_state disk_initial_state: Z = R sin(theta), the centre
!> velocity from no slip), for every scene shipped in data/.
module ic_scene_starts
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_problem, only : problem_type
    use rollcon_scene, only : scene_type, read_scene, height_position, height_velocity
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of, &
        & analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type
    use rollcon_testing, only : check
    implicit none
    private

    public :: test_scene_starts, test_scene_velocities

    !> The scenes of data/
    character(len=*), parameter :: scenes(7) = [character(len=13) :: "coin", "tipping_coin", &
        & "steady_circle", "fast_upright", "spinning_coin", "near_flat", "long_run"]
    !> The scene's formulas and the analysis agree to 1e-12 (the item's demand): the free values
    !> enter linearly once the angles and rates are held (Z in Z - R sin(theta), the centre
    !> velocity in F1, F2, F3), so one least-squares step solves them up to the rounding of
    !> terms of size R |omega| <= 2 m/s in these scenes (~1e-16)
    real(wp), parameter :: tol_scene = 1.0e-12_wp

contains

    !> Each scene with the height as a position UCON: from Z = 0 and a centre at rest, the
    !> analysis finds the scene's Z and centre velocity.
    subroutine test_scene_starts(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_scenes(height_position, error)
    end subroutine test_scene_starts

    !> Each scene as it runs (F3 at velocity level, so Z is no UCON's and is given): from a
    !> centre at rest, the analysis finds the scene's centre velocity.
    subroutine test_scene_velocities(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_scenes(height_velocity, error)
    end subroutine test_scene_velocities

    !> Every scene of data/ with the given form of the height.
    subroutine compare_scenes(height, error)
        integer, intent(in) :: height
        type(error_type), allocatable, intent(out) :: error
        integer :: s

        do s = 1, size(scenes)
            call compare_scene(trim(scenes(s)), height, error)
            if (allocated(error)) return
        end do
    end subroutine compare_scenes

    !> One scene: the analysis from X, Y, the angles and rates held, against the scene's start.
    subroutine compare_scene(name, height, error)
        character(len=*), intent(in) :: name
        integer, intent(in) :: height
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene
        type(problem_type), target :: problem
        type(ic_options_type) :: options
        type(ic_report_type) :: report
        real(wp) :: q0(6), u0(6), q(6), u(6)

        call read_scene("data/" // name // ".nml", scene, error)
        if (allocated(error)) return
        scene%run%height = height
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        q = q0
        u = u0
        u(1:3) = 0.0_wp
        if (height == height_position) q(3) = 0.0_wp
        options = ic_options_of(problem)
        options%exact_q = [.true., .true., .false., .true., .true., .true.]
        options%exact_u = [.false., .false., .false., .true., .true., .true.]
        call analyse_initial_conditions(problem, 0.0_wp, q, u, options, report, error)
        if (allocated(error)) return
        call check(error, q, q0, name // ": coordinates", abs_tol=tol_scene)
        if (allocated(error)) return
        call check(error, u, u0, name // ": rates", abs_tol=tol_scene)
    end subroutine compare_scene

end module ic_scene_starts
