! SPDX-License-Identifier: MIT
!> Studies whose base is an ADAMS dataset (docs/studies.md): a parameter names one value of one
!> statement's argument, `statement%id%keyword` or `statement%id%keyword%k` (the k-th value of
!> a list; `statement%keyword` for a statement without id, as ACCGRAV), and a case runs the
!> dataset as `rollcon run MODEL.adm` does: read with the values set, the initial-conditions
!> analysis, the simulation, with the hand-checked disk serving UCONs without ROUTINE=.
module rollcon_study_dataset
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text, upper_case
    use rollcon_scene_lexer, only : assignment_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_simulation, only : run_options_type, run_summary_type, history_type, simulate
    use rollcon_initial_conditions, only : analyse_initial_conditions
    use rollcon_ic_report, only : ic_report_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_adm_initial, only : adm_ic_options
    use rollcon_adm_overrides, only : adm_override_type
    use rollcon_study_type, only : study_type, study_parameter_type
    implicit none
    private

    public :: read_dataset_parameter, dataset_override, check_dataset_parameters, &
        & simulate_dataset_case

contains

    !> The statement and argument of a parameter line (`part%2%vx = '...'`): group is the
    !> statement with its id (`part%2`), key the keyword with its element (`vx`, `qp%3`).
    subroutine read_dataset_parameter(file, group_name, a, parameter, error)
        character(len=*), intent(in) :: file, group_name
        type(assignment_type), intent(in) :: a
        type(study_parameter_type), intent(inout) :: parameter
        type(error_type), allocatable, intent(out) :: error
        type(adm_override_type) :: o

        call parse_key(a%key, o, parameter%group, parameter%key)
        if (len(parameter%group) == 0) call input_error(error, file, a%line, a%key, "in &" &
            & // group_name // " is not a value of the dataset; a parameter of a dataset " &
            & // "study is statement%id%keyword, or statement%id%keyword%k for the k-th " &
            & // "value of a list (part%2%vx, marker%3%qp%3, accgrav%kgrav)")
        parameter%unit = ""
    end subroutine read_dataset_parameter

    !> The override of a parameter at a value (its text).
    function dataset_override(parameter, value) result(o)
        type(study_parameter_type), intent(in) :: parameter
        character(len=*), intent(in) :: value
        type(adm_override_type) :: o
        character(len=:), allocatable :: group, key

        call parse_key(parameter%group // "%" // parameter%key, o, group, key)
        o%value = value
    end function dataset_override

    !> Each parameter must name a value the base dataset has (or an argument it can take),
    !> and the dataset must read with it at its lower end.
    subroutine check_dataset_parameters(file, study, error)
        character(len=*), intent(in) :: file
        type(study_type), intent(in) :: study
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        character(len=:), allocatable :: message
        integer :: k

        call read_adm(study%scene_path, adm, error)
        if (allocated(error)) then
            message = error%message
            call input_error(error, file, 0, "", "its base dataset is refused: " // message)
            return
        end if
        do k = 1, size(study%parameters)
            associate (p => study%parameters(k))
                call read_adm(study%scene_path, adm, error, [dataset_override(p, &
                    & to_text(p%lower))])
                if (allocated(error)) then
                    message = error%message
                    call input_error(error, file, p%line, p%group // "%" // p%key, "at " &
                        & // to_text(p%lower) // ": the base dataset is refused: " // message)
                    return
                end if
            end associate
        end do
    end subroutine check_dataset_parameters

    !> Run a dataset with overrides as `rollcon run MODEL.adm` runs it; error when it is
    !> refused (read, built or its start) or the run fails (summary then describes it).
    subroutine simulate_dataset_case(path, overrides, summary, history, error, refused)
        character(len=*), intent(in) :: path
        type(adm_override_type), intent(in) :: overrides(:)
        type(run_summary_type), intent(out) :: summary
        type(history_type), intent(inout) :: history
        type(error_type), allocatable, intent(out) :: error
        !> True when the case did not start (read, build, initial conditions)
        logical, intent(out) :: refused
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(ic_report_type) :: report
        type(run_options_type) :: options
        procedure(ucosub_interface), pointer :: hand_disk
        real(wp), allocatable :: q0(:), u0(:)

        refused = .true.
        call read_adm(path, adm, error, overrides)
        if (allocated(error)) return
        hand_disk => rolling_disk_ucosub
        call build_adm_problem(adm, hand_disk, problem, q0, u0, error)
        if (allocated(error)) return
        call analyse_initial_conditions(problem, 0.0_wp, q0, u0, adm_ic_options(adm, problem), &
            & report, error)
        if (allocated(error)) return
        refused = .false.
        options%end_time = adm%run%end_time
        options%output_step = adm%run%output_step
        options%progress = .false.
        call simulate(problem, q0, u0, options, summary, error, history)
    end subroutine simulate_dataset_case

    !> Split `name%id%keyword[%k]` or `name%keyword[%k]`; group and key empty when the key
    !> does not read so.
    pure subroutine parse_key(text, o, group, key)
        character(len=*), intent(in) :: text
        type(adm_override_type), intent(out) :: o
        character(len=:), allocatable, intent(out) :: group, key
        character(len=len(text)) :: parts(4)
        integer :: n, start, cut, stat, next

        n = 0
        start = 1
        group = ""
        key = ""
        do
            cut = index(text(start:), "%")
            if (n == size(parts)) return
            n = n + 1
            if (cut == 0) then
                parts(n) = text(start:)
                exit
            end if
            parts(n) = text(start:start + cut - 2)
            start = start + cut
        end do
        if (n < 2 .or. any(len_trim(parts(:n)) == 0)) return
        o%statement = upper_case(trim(parts(1)))
        next = 2
        read(parts(2), *, iostat=stat) o%id
        if (stat == 0 .and. verify(trim(parts(2)), "0123456789") == 0) then
            next = 3
        else
            o%id = 0
        end if
        if (n < next .or. n > next + 1) return
        o%keyword = upper_case(trim(parts(next)))
        if (verify(o%keyword, "ABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789") /= 0) return
        o%element = 1
        if (n == next + 1) then
            if (verify(trim(parts(n)), "0123456789") /= 0) return
            read(parts(n), *, iostat=stat) o%element
            if (stat /= 0 .or. o%element < 1) return
        end if
        group = trim(parts(1))
        if (next == 3) group = group // "%" // trim(parts(2))
        key = trim(parts(next))
        if (n == next + 1) key = key // "%" // trim(parts(n))
    end subroutine parse_key

end module rollcon_study_dataset
