! SPDX-License-Identifier: MIT
!> The check of a user's UCOSUB before a dataset's run (`rollcon run MODEL.adm --ucosub FILE`):
!> the routine is checked as `rollcon check FILE --model MODEL.adm` checks it (each UCON it
!> serves, in a child process, every partial against sixth-order differences of its own
!> outputs: rollcon_partials_check), at fewer random states, so that a wrong partial is named
!> before the run instead of showing only as an integrator that takes thousands of steps or
!> stops (a wrong Newton matrix slows or stops the Newton iteration; the residuals it solves
!> stay right, so the motion may still be right, only slow to find).
module rollcon_run_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_load, only : is_command_file
    use rollcon_acf_reader, only : acf_type, read_acf
    use rollcon_user_library, only : user_ucosub_type, new_user_ucosub
    use rollcon_ucon_request, only : dataset_ucon_requests
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type
    use rollcon_isolated_audit, only : check_user_ucosub_isolated
    implicit none
    private

    public :: check_before_run, run_check_states

    !> Random states per UCON in the check before a run: a wrong term of a partial shows at
    !> almost every state (the field's wrong Coriolis factor: 25 of 25), so eight find it
    !> while adding little to the run (the check's 25 are for `rollcon check`)
    integer, parameter :: run_check_states = 8

contains

    !> Check the user's UCOSUB at ucosub_path on the UCONs of the dataset at model_path (an
    !> ADAMS dataset, or a command file, whose dataset is checked) that it serves (those naming
    !> no ROUTINE), at run_check_states random states each. checked is false, and report
    !> empty, when no UCON names the model's UCOSUB. call_timeout: the longest one call may
    !> take [s]. Errors: the command file or dataset cannot be read, the routine cannot be
    !> built or loaded (the run's own loading reports the same first).
    subroutine check_before_run(model_path, ucosub_path, call_timeout, report, checked, error)
        character(len=*), intent(in) :: model_path, ucosub_path
        real(wp), intent(in) :: call_timeout
        type(user_check_report_type), intent(out) :: report
        logical, intent(out) :: checked
        type(error_type), allocatable, intent(out) :: error
        type(ucon_request_type), allocatable :: requests(:)
        type(user_check_options_type) :: options
        type(user_ucosub_type) :: user
        type(acf_type) :: acf
        type(error_type), allocatable :: none_served
        character(len=:), allocatable :: dataset, note

        checked = .false.
        dataset = model_path
        if (is_command_file(model_path)) then
            call read_acf(model_path, acf, error)
            if (allocated(error)) return
            dataset = acf%dataset
        end if
        allocate(requests(0))
        ! the run has read this dataset already: the one refusal left is that no UCON names
        ! the model's UCOSUB, and then there is nothing to check
        call dataset_ucon_requests(dataset, requests, note, none_served)
        if (allocated(none_served) .or. size(requests) == 0) return
        call new_user_ucosub(user, ucosub_path, error)
        if (allocated(error)) return
        options%states = run_check_states
        call check_user_ucosub_isolated(user%ucosub, requests, options, call_timeout, report, &
            & error)
        call user%destroy()
        checked = .not. allocated(error)
    end subroutine check_before_run

end module rollcon_run_check
