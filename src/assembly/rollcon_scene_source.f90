! SPDX-License-Identifier: MIT
!> A namelist scene as a job's model source (rollcon_model_source): the disk, its UCONs, the
!> strike and the disk scene's watches (rollcon_disk_scene), with the scene's &run settings or
!> those a caller put in their place, and the disk's shape for the pictures.
module rollcon_scene_source
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_part_shapes, only : part_shape_type, part_shapes_of
    use rollcon_model_source, only : model_source_type
    use rollcon_scene_type, only : scene_type
    use rollcon_disk_scene, only : build_disk_problem, disk_part
    implicit none
    private

    public :: scene_source_type, new_scene_source

    type, extends(model_source_type) :: scene_source_type
        !> The scene as read (its &run settings are the source's `settings` from here on)
        type(scene_type) :: scene
    contains
        procedure :: build
        procedure :: shapes
    end type scene_source_type

contains

    !> The source of a scene that was read and checked.
    function new_scene_source(scene) result(source)
        type(scene_type), intent(in) :: scene
        type(scene_source_type) :: source

        source%scene = scene
        source%name = scene%name
        source%path = scene%path
        source%kind = "scene"
        source%settings = scene%run%run_settings_type
    end function new_scene_source

    !> The disk scene's problem with the source's settings; no analysis of the start (the
    !> scene's formulas give a consistent one: docs/initial-conditions.md).
    subroutine build(self, ucosub, problem, q0, u0, report, error)
        class(scene_source_type), intent(inout) :: self
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: routine

        report = ""
        self%scene%run%run_settings_type = self%settings
        allocate(q0(6), u0(6))
        ! a local pointer: gfortran 12 hands a procedure-pointer dummy given on for a procedure
        ! dummy by the pointer's own address, and the first call jumps there (SIGSEGV)
        routine => ucosub
        call build_disk_problem(self%scene, routine, problem, q0, u0, error)
    end subroutine build

    !> The disk as a disk.
    subroutine shapes(self, problem, found, error)
        class(scene_source_type), intent(in) :: self
        type(problem_type), intent(in) :: problem
        type(part_shape_type), allocatable, intent(out) :: found(:)
        type(error_type), allocatable, intent(out) :: error

        call part_shapes_of(problem%model, found, error, disk_radius=self%scene%disk%radius, &
            & disk_thickness=self%scene%disk%thickness, disk_part=disk_part)
    end subroutine shapes

end module rollcon_scene_source
