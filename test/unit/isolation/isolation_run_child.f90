! SPDX-License-Identifier: MIT
!> The isolation suite's run in a child as `rollcon run --ucosub` does it: a call task that
!> declares and evaluates one guarded UCON, and the test of its outcomes.
module isolation_run_child
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_user_library, only : user_ucosub_type, user_build_options_type, new_user_ucosub
    use rollcon_testing, only : check
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_ucon_call, only : declare_ucon, evaluate_ucon
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_child_process, only : isolated_task_type, call_record_type, &
        & isolation_outcome_type, run_in_child, outcome_finished, outcome_signal
    use rollcon_isolation_text, only : outcome_text
    use rollcon_ucosub_guard, only : install_guard, attach_call_record, guarded_ucosub
    use user_ucosub_support, only : test_cache, faulty, expect_in
    implicit none
    private

    public :: test_run_child

    !> What a run does with a user's routine, in a child: declare UCON 1, evaluate it once
    type, extends(isolated_task_type) :: call_task
        procedure(ucosub_interface), pointer, nopass :: ucosub => null()
    contains
        procedure :: run => run_call_task
    end type call_task

    !> Time limit per call where no call hangs [s] (the default of the command line)
    real(wp), parameter :: usual_timeout = 10.0_wp

contains

    !> As a run does it (rollcon run --ucosub): a write outside ARRAY(30) is an error of the
    !> run, passed back from the child; a SIGFPE ends the child with the call on record.
    subroutine test_run_child(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(user_build_options_type) :: build
        type(call_task) :: task
        type(isolation_outcome_type) :: outcome
        type(error_type), allocatable :: run_error
        character(len=*), parameter :: stderr_path = "build/rollcon-test-isolation.stderr"

        build%cache_dir = test_cache
        call new_user_ucosub(user, faulty // "array_31.f", error, build)
        if (allocated(error)) return
        task%ucosub => user%ucosub
        call run_in_child(task, usual_timeout, outcome, run_error, stderr_path)
        call user%destroy()
        call check(error, outcome%kind == outcome_finished .and. allocated(run_error), &
            & "array_31.f: the run's child did not finish with an error")
        if (allocated(error)) return
        call expect_in(error, run_error%message, "UCON/1: the UCOSUB wrote ARRAY(31) = 0.5")
        if (allocated(error)) return
        call new_user_ucosub(user, faulty // "divide_by_zero.f", error, build)
        if (allocated(error)) return
        task%ucosub => user%ucosub
        call run_in_child(task, usual_timeout, outcome, run_error, stderr_path)
        call user%destroy()
        call check(error, outcome%kind == outcome_signal .and. outcome%signal == 8, &
            & "divide_by_zero.f: the run's child was not killed by SIGFPE (8)")
        if (allocated(error)) return
        call expect_in(error, outcome_text(outcome), "UCON/1: the process was killed by " &
            & // "SIGFPE")
        if (allocated(error)) return
        call expect_in(error, outcome_text(outcome), "inside UCOSUB call 2: IFLAG = 0, " &
            & // "IDRSEL = (1, 1, 0), TIME = 0.5")
    end subroutine test_run_child

    !> In the child: declare UCON 1 (part 3, height 0.25) and evaluate it once at Z = 1 m,
    !> t = 0.5 s, with the outputs guarded as in a run.
    subroutine run_call_task(self, record, error)
        class(call_task), intent(inout) :: self
        type(call_record_type), pointer, intent(in) :: record
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        real(wp) :: q(30), scalar, array(30), xmatrx(30, 30)

        call attach_call_record(record)
        call install_guard(self%ucosub, as_errors=.true.)
        call declare_ucon(guarded_ucosub, 1, [3.0_wp, 0.25_wp], registry, error)
        if (allocated(error)) return
        q = 0.0_wp
        q(1) = 1.0_wp
        call evaluate_ucon(guarded_ucosub, 1, 0.5_wp, q, [3.0_wp, 0.25_wp], [1, 1, 0], scalar, &
            & array, xmatrx, error, nvars=1)
    end subroutine run_call_task

end module isolation_run_child
