! SPDX-License-Identifier: MIT
!> A model built in code (docs/library.md) as a job's model source (rollcon_model_source): the
!> model as setup_model left it, its start, its run settings and what it watches. Its UCONs
!> carry their routines already (add_ucon), so the job's routine serves none of them. Its
!> start is run as given, or, when asked (consistent_start), first made consistent by the
!> initial-conditions analysis as a dataset's is (docs/initial-conditions.md).
module rollcon_built_model
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_model, only : model_type
    use rollcon_run_settings, only : run_settings_type
    use rollcon_problem, only : problem_type
    use rollcon_watch, only : watch_type, watch_slot_type, append_watch
    use rollcon_initial_conditions, only : ic_options_type, ic_options_of, &
        & analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type, ic_report_text
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
        !> Make the start consistent before the run (the initial-conditions analysis with the
        !> run's tolerances, as for a dataset); false: run the start as given
        logical :: consistent_start = .false.
        !> With consistent_start: the coordinates the analysis holds as given (6 per part, in
        !> model order, as EXACT= in a dataset); unallocated: none
        logical, allocatable :: exact_q(:)
        !> The basis each part's start is in (model order; unallocated: all 0): its number
        !> (rollcon_rebasing's basis_axes), 1 or 20 for a part that starts in its principal
        !> axes turned as a re-basing turns them (part_start's basis, the model's part turned
        !> to match by model%turn_part_axes)
        integer, allocatable :: start_bases(:)
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

    !> The problem of the model as it is; the start as given, or made consistent
    !> (consistent_start: report says what the analysis moved).
    subroutine build(self, ucosub, problem, q0, u0, report, error)
        class(built_model_source_type), intent(inout) :: self
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(ic_options_type) :: options
        type(ic_report_type) :: analysis
        integer :: k

        report = ""
        call problem%init(self%model)
        problem%settings = self%settings
        do k = 1, size(self%watches)
            call problem%add_watch(self%watches(k)%watch)
        end do
        if (allocated(self%start_bases)) then
            if (size(self%start_bases) /= size(problem%start_bases)) then
                call fatal_error(error, "start_bases has " // to_text(size(self%start_bases)) &
                    & // " entries; the model has " // to_text(size(problem%start_bases)) &
                    & // " parts", stat_input)
                return
            end if
            problem%start_bases = self%start_bases
        end if
        q0 = self%q0
        u0 = self%u0
        if (.not. self%consistent_start) return
        options = ic_options_of(problem)
        if (allocated(self%exact_q)) then
            if (size(self%exact_q) /= size(options%exact_q)) then
                call fatal_error(error, "exact_q has " // to_text(size(self%exact_q)) &
                    & // " entries; the model has " // to_text(size(options%exact_q)) &
                    & // " coordinates (6 per part)", stat_input)
                return
            end if
            options%exact_q = self%exact_q
        end if
        call analyse_initial_conditions(problem, 0.0_wp, q0, u0, options, analysis, error)
        if (allocated(error)) return
        report = ic_report_text(analysis)
    end subroutine build

end module rollcon_built_model
