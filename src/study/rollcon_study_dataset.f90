! SPDX-License-Identifier: MIT
!> Studies whose base is an ADAMS dataset (docs/studies.md): a parameter names one value of one
!> statement's argument, `statement%id%keyword` or `statement%id%keyword%k` (the k-th value of
!> a list; `statement%keyword` for a statement without id, as ACCGRAV), and a case runs the
!> dataset as `rollcon run MODEL.adm` does (rollcon_load, rollcon_run_job), with the
!> hand-checked disk serving UCONs without ROUTINE=.
module rollcon_study_dataset
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text, upper_case
    use rollcon_namelist_lexer, only : assignment_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm_lines
    use rollcon_adm_overrides, only : adm_override_type, parse_override_name
    use rollcon_study_type, only : study_type, study_parameter_type
    implicit none
    private

    public :: read_dataset_parameter, dataset_override, check_dataset_parameters

contains

    !> The statement and argument of a parameter line (`part%2%vx = '...'`): group is the
    !> statement with its id (`part%2`), key the keyword with its element (`vx`, `qp%3`).
    subroutine read_dataset_parameter(file, group_name, a, parameter, error)
        character(len=*), intent(in) :: file, group_name
        type(assignment_type), intent(in) :: a
        type(study_parameter_type), intent(inout) :: parameter
        type(error_type), allocatable, intent(out) :: error
        type(adm_override_type) :: o

        call parse_override_name(a%key, o, parameter%group, parameter%key)
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

        call parse_override_name(parameter%group // "%" // parameter%key, o, group, key)
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

        call read_adm_lines(study%scene_path, study%scene_lines, adm, error)
        if (allocated(error)) then
            message = error%message
            call input_error(error, file, 0, "", "its base dataset is refused: " // message)
            return
        end if
        do k = 1, size(study%parameters)
            associate (p => study%parameters(k))
                call read_adm_lines(study%scene_path, study%scene_lines, adm, error, &
                    & [dataset_override(p, to_text(p%lower))])
                if (allocated(error)) then
                    message = error%message
                    call input_error(error, file, p%line, p%group // "%" // p%key, "at " &
                        & // to_text(p%lower) // ": the base dataset is refused: " // message)
                    return
                end if
            end associate
        end do
    end subroutine check_dataset_parameters

end module rollcon_study_dataset
