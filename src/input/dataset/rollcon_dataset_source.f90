! SPDX-License-Identifier: MIT
!> An ADAMS dataset as a job's model source (rollcon_model_source): its parts, UCONs, forces and
!> run (rollcon_adm_build), with the dataset's INTEGRATOR and SIMULATE settings or those a
!> caller put in their place, and its start made consistent by the initial-conditions analysis
!> (docs/initial-conditions.md), as ADAMS does before a dynamic run. Its warning names the
!> statements of ADAMS's outputs and solver choices it read and does not use.
module rollcon_dataset_source
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_problem, only : problem_type
    use rollcon_model_source, only : model_source_type
    use rollcon_initial_conditions, only : analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type, ic_report_text
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_adm_initial, only : adm_ic_options
    use rollcon_adm_outputs, only : unused_warning
    implicit none
    private

    public :: dataset_source_type, new_dataset_source

    type, extends(model_source_type) :: dataset_source_type
        !> The dataset as read (its run settings are the source's `settings` from here on)
        type(adm_model_type) :: adm
    contains
        procedure :: build
    end type dataset_source_type

contains

    !> The source of a dataset that was read and checked, read from path.
    function new_dataset_source(adm, path) result(source)
        type(adm_model_type), intent(in) :: adm
        character(len=*), intent(in) :: path
        type(dataset_source_type) :: source
        integer :: slash

        source%adm = adm
        source%path = path
        slash = index(path, "/", back=.true.)
        source%name = path(slash + 1:len_trim(path) - 4)
        source%kind = "dataset"
        source%settings = adm%run%settings
        source%warning = unused_warning(adm)
    end function new_dataset_source

    !> The dataset's problem with the source's settings, and its start after the
    !> initial-conditions analysis (its report in report).
    subroutine build(self, ucosub, problem, q0, u0, report, error)
        class(dataset_source_type), intent(inout) :: self
        procedure(ucosub_interface), pointer, intent(in) :: ucosub
        type(problem_type), intent(inout), target :: problem
        real(wp), allocatable, intent(out) :: q0(:), u0(:)
        character(len=:), allocatable, intent(out) :: report
        type(error_type), allocatable, intent(out) :: error
        type(ic_report_type) :: analysis

        report = ""
        self%adm%run%settings = self%settings
        call build_adm_problem(self%adm, ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        ! as ADAMS before a dynamic run: the least change that meets every UCON
        call analyse_initial_conditions(problem, 0.0_wp, q0, u0, adm_ic_options(self%adm, &
            & problem), analysis, error)
        if (allocated(error)) then
            error%message = self%path // ": " // error%message
            return
        end if
        report = ic_report_text(analysis)
    end subroutine build

end module rollcon_dataset_source
