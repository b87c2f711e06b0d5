! SPDX-License-Identifier: MIT
!> What a job runs: anything that builds a problem (rollcon_problem) and its start, whatever
!> the input was (a namelist scene, an ADAMS dataset, a model built in code). A source knows
!> its name (the stem of its outputs), where it came from, its run settings (which a caller may
!> change before it builds: a benchmark's method, a study's parameters), the shapes of its
!> parts for the pictures, and how to build: with the routine that serves the UCONs that name
!> no routine of their own, a consistent start, and the report of what that start changed.
module rollcon_model_source
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_run_settings, only : run_settings_type
    use rollcon_problem, only : problem_type
    use rollcon_part_shapes, only : part_shape_type, part_shapes_of
    implicit none
    private

    public :: model_source_type

    type, abstract :: model_source_type
        !> The stem of the run's outputs (coin: output/coin.csv)
        character(len=:), allocatable :: name
        !> The input file ("" for a model built in code)
        character(len=:), allocatable :: path
        !> What it is, in a word: "scene", "dataset", "model"
        character(len=:), allocatable :: kind
        !> How to integrate, and over which times: the input's own, until a caller changes them
        type(run_settings_type) :: settings
        !> What the input holds that the run does not use, in one line (a dataset's statements
        !> of ADAMS's outputs and solver choices); unallocated or "" for nothing. `rollcon run`
        !> prints it on standard error, and the summary carries it
        character(len=:), allocatable :: warning
        !> What the model is made of that its summary states, in lines each ending with a new
        !> line (a dataset's principal axes turned from its CM markers'); unallocated or "" for
        !> nothing
        character(len=:), allocatable :: notes
        !> Every UCON names its own routine (a dataset's ROUTINE=, its joints'): the model's
        !> UCOSUB serves none, and the summary's record says so
        logical :: own_routines = .false.
        !> The model has no UCON statement at all (with own_routines: its UCOSUB serves nothing
        !> because there is nothing to serve, and the record says that instead)
        logical :: no_ucons = .false.
    contains
        procedure(build_interface), deferred :: build
        procedure :: shapes
        procedure :: setting_line
        procedure :: input_warning
        procedure :: model_notes
    end type model_source_type

    abstract interface
        !> The problem (set up in place: its equations refer to its model) with settings, and a
        !> consistent start (q0, u0) at t = 0. ucosub serves every UCON that names no routine of
        !> its own. report: what making the start consistent changed, in lines ("" when nothing
        !> was analysed); printed by the caller unless quiet.
        subroutine build_interface(self, ucosub, problem, q0, u0, report, error)
            import :: model_source_type, ucosub_interface, problem_type, wp, error_type
            class(model_source_type), intent(inout) :: self
            procedure(ucosub_interface), pointer, intent(in) :: ucosub
            type(problem_type), intent(inout), target :: problem
            real(wp), allocatable, intent(out) :: q0(:), u0(:)
            character(len=:), allocatable, intent(out) :: report
            type(error_type), allocatable, intent(out) :: error
        end subroutine build_interface
    end interface

contains

    !> The parts' shapes for the pictures: by default each part's inertia ellipsoid, along its
    !> own axes whatever basis its start is in.
    subroutine shapes(self, problem, found, error)
        class(model_source_type), intent(in) :: self
        type(problem_type), intent(in) :: problem
        type(part_shape_type), allocatable, intent(out) :: found(:)
        type(error_type), allocatable, intent(out) :: error

        call part_shapes_of(problem%model, found, error, bases=problem%start_bases)
    end subroutine shapes

    !> The first line of the run's summary: "scene coin (data/coin.nml): IDA (DAE form, index
    !> 2), analytic Jacobian, rtol 1e-8, atol 1e-10".
    function setting_line(self) result(line)
        class(model_source_type), intent(in) :: self
        character(len=:), allocatable :: line

        line = self%kind // " " // self%name
        if (len(self%path) > 0) line = line // " (" // self%path // ")"
        line = line // ": " // self%settings%text()
    end function setting_line

    !> The input's warning (component warning): "" for none.
    function input_warning(self) result(text)
        class(model_source_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
        if (allocated(self%warning)) text = self%warning
    end function input_warning

    !> The model's notes for the summary (component notes): "" for none.
    function model_notes(self) result(text)
        class(model_source_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
        if (allocated(self%notes)) text = self%notes
    end function model_notes

end module rollcon_model_source
