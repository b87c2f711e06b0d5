! SPDX-License-Identifier: MIT
!> A model built in code (docs/library.md) as a job's model source (rollcon_model_source): the
!> model as setup_model left it, its start, its run settings and what it watches. Its UCONs
!> carry their routines already (add_ucon), so the job's routine serves none of them.
module rollcon_built_model
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_model, only : model_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_problem, only : problem_type
    use rollcon_watch, only : watch_type, watch_slot_type, append_watch
    use rollcon_model_source, only : model_source_type
    implicit none
    private

    public :: built_model_source_type, new_model_source

    type, extends(model_source_type) :: built_model_source_type
        type(model_type) :: model
        !> The start: coordinates and rates of every part [m, rad, m/s, rad/s]
        real(wp), allocatable :: q0(:), u0(:)
        !> What the run watches (none unless added)
        type(watch_slot_type), allocatable :: watches(:)
    contains
        procedure :: build
        procedure :: add_watch
    end type built_model_source_type

contains

    !> The source of model (set up: setup_model), named name (the stem of its outputs),
    !> started at (q0, u0) and run with settings.
    function new_model_source(name, model, q0, u0, settings) result(source)
        character(len=*), intent(in) :: name
        type(model_type), intent(in) :: model
        real(wp), intent(in) :: q0(:), u0(:)
        type(run_settings_type), intent(in) :: settings
        type(built_model_source_type) :: source

        source%name = name
        source%path = ""
        source%kind = "model"
        source%model = model
        source%q0 = q0
        source%u0 = u0
        source%settings = settings
        allocate(source%watches(0))
    end function new_model_source

    !> Watch this too in its runs.
    subroutine add_watch(self, watch)
        class(built_model_source_type), intent(inout) :: self
        class(watch_type), intent(in) :: watch

        call append_watch(self%watches, watch)
    end subroutine add_watch

    !> The problem of the model as it is; the start as given (no analysis).
    subroutine build(self, ucosub, problem, q0, u0, report, error)
        class(built_model_source_type), intent(inout) :: self
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        report = ""
        call problem%init(self%model)
        problem%settings = self%settings
        do k = 1, size(self%watches)
            call problem%add_watch(self%watches(k)%watch)
        end do
        q0 = self%q0
        u0 = self%u0
    end subroutine build

end module rollcon_built_model
