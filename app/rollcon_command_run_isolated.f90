! SPDX-License-Identifier: MIT
!> `rollcon run --ucosub FILE`: the run with a user's routine, in a child process, so that a
!> crash, an endless call or a STOP in the routine ends with a clear error instead of taking
!> rollcon down (rollcon_child_process); the routine's outputs are guarded
!> (rollcon_ucosub_guard), a write outside ARRAY(30) or XMATRX(30,30) being an error.
module rollcon_command_run_isolated
    use, intrinsic :: iso_c_binding, only : c_double
    use rollcon, only : wp, error_type, fatal_error, stat_ucon, ucosub_interface, &
        & run_summary_type, isolated_task_type, call_record_type, isolation_outcome_type, &
        & run_in_child, outcome_finished, outcome_text, install_guard, attach_call_record, &
        & guarded_ucosub
    use rollcon_command_run, only : run_scene
    implicit none
    private

    public :: run_user_scene

    !> The run, as the child does it
    type, extends(isolated_task_type) :: scene_run_task
        character(len=:), allocatable :: name, output_dir
        logical :: quiet = .false., allow_large_output = .false.
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
    contains
        procedure :: run => run_scene_task
    end type scene_run_task

contains

    !> run_scene with the user's routine, in a child process; each UCOSUB call limited to
    !> call_timeout seconds.
    subroutine run_user_scene(name, output_dir, ucosub, quiet, call_timeout, error, &
            & allow_large_output)
        !> Scene name or path
        character(len=*), intent(in) :: name
        !> Folder for the outputs
        character(len=*), intent(in) :: output_dir
        !> The user's routine (loaded from a file)
        procedure(ucosub_interface) :: ucosub
        !> No progress lines
        logical, intent(in) :: quiet
        !> Longest one UCOSUB call may take [s]
        real(wp), intent(in) :: call_timeout
        !> The run's error, or what ended its process
        type(error_type), allocatable, intent(out) :: error
        !> Lift the limit on the size of the CSV a run may plan (default: keep it)
        logical, intent(in), optional :: allow_large_output
        type(scene_run_task) :: task
        type(isolation_outcome_type) :: outcome

        task%name = name
        task%output_dir = output_dir
        task%quiet = quiet
        task%ucosub => ucosub
        if (present(allow_large_output)) task%allow_large_output = allow_large_output
        call run_in_child(task, real(call_timeout, c_double), outcome, error)
        if (allocated(error)) return
        if (outcome%kind /= outcome_finished) then
            call fatal_error(error, outcome_text(outcome) // "; the run did not complete (the " &
                & // "CSV rows written before stay valid)", stat_ucon)
        end if
    end subroutine run_user_scene

    !> In the child: the run, every call recorded and guarded.
    subroutine run_scene_task(self, record, error)
        class(scene_run_task), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary
        procedure(ucosub_interface), pointer :: guarded

        call attach_call_record(record)
        call install_guard(self%ucosub, as_errors=.true.)
        guarded => guarded_ucosub
        call run_scene(self%name, self%output_dir, guarded, self%quiet, summary, error, &
            & self%allow_large_output)
    end subroutine run_scene_task

end module rollcon_command_run_isolated
