! SPDX-License-Identifier: MIT
!> Helper of the models suite: run one of the example datasets of data/ on the formulation a
!> test asks for, and hand back its history.
module model_runs
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_run_settings, only : formulation_cvode, formulation_ida
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate, &
        & status_completed
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_testing, only : check
    implicit none
    private

    public :: run_model, model_run_type, formulation_cvode, formulation_ida

    !> What a run of a model hands back
    type :: model_run_type
        !> Mass [kg] and principal moments [kg m^2] of the model's first part
        real(wp) :: mass = 0.0_wp, inertia(3) = 0.0_wp
        !> The run's summary and its rows (one part: t, the 12 coordinates and rates, E, ...)
        type(run_summary_type) :: summary
        type(history_type) :: history
    end type model_run_type

contains

    !> Run data/<name>.adm on the given formulation to end_time [s] (the dataset's end when
    !> absent), with rtol = atol = tolerance when present (the dataset's otherwise). The run
    !> must reach its end, completed.
    subroutine run_model(name, formulation, run, error, end_time, tolerance, rebase_turn)
        character(len=*), intent(in) :: name
        integer, intent(in) :: formulation
        type(model_run_type), intent(out) :: run
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in), optional :: end_time, tolerance
        !> The turn of every re-basing (problem%rebase_turn; default 0, the rule's)
        integer, intent(in), optional :: rebase_turn
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(run_options_type) :: options
        real(wp), allocatable :: q0(:), u0(:)
        procedure(ucosub_interface), pointer :: disk
        logical :: completed

        ! the model's UCOSUB, for UCONs that name no ROUTINE (data/coin.adm's): rollcon's
        ! hand-checked disk, as rollcon run gives them
        disk => rolling_disk_ucosub
        call read_adm("data/" // name // ".adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, disk, problem, q0, u0, error)
        if (allocated(error)) return
        problem%settings%formulation = formulation
        if (present(rebase_turn)) problem%rebase_turn = rebase_turn
        if (present(tolerance)) then
            problem%settings%rtol = tolerance
            problem%settings%atol = tolerance
        end if
        run%mass = problem%model%parts(1)%mass
        run%inertia = problem%model%parts(1)%inertia
        options%end_time = adm%run%settings%end_time
        if (present(end_time)) options%end_time = end_time
        options%output_step = adm%run%settings%output_step
        options%progress = .false.
        call simulate(problem, q0, u0, options, run%summary, error, run%history)
        if (allocated(error)) return
        completed = run%summary%status == status_completed
        call check(error, completed .and. abs(run%summary%t_reached - options%end_time) &
            & <= 1.0e-9_wp*options%end_time, name // ": the run stopped at t = " &
            & // to_text(run%summary%t_reached) // " s, status " // to_text(run%summary%status))
    end subroutine run_model

end module model_runs
