! SPDX-License-Identifier: MIT
!> Reads a study file (docs/studies.md): namelist groups as in a scene file, read by the
!> scene's own lexer so that every mistake is reported with file, line and key. The base
!> scene is read and checked too.
module rollcon_study_reader
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, input_error
    use rollcon_text, only : to_text, unquoted
    use rollcon_namelist_lexer, only : group_type, assignment_type, read_lines, scan_groups
    use rollcon_namelist_bytes, only : check_bytes, visible
    use rollcon_scene, only : scene_type, scene_path, read_scene_lines
    use rollcon_load, only : is_dataset
    use rollcon_study_type, only : study_type, study_parameter_type, sampling_grid, &
        & sampling_random
    use rollcon_study_parameters, only : read_parameter, check_case_count
    use rollcon_study_rules, only : read_rules, read_map
    use rollcon_study_dataset, only : check_dataset_parameters
    implicit none
    private

    public :: read_study

    !> Groups of a study file
    character(len=*), parameter :: study_groups(*) = [character(len=8) :: "study", "grid", &
        & "random", "classify", "map"]

contains

    !> Read and check a study file and its base scene. A message shows every character
    !> visibly: a tab in a quoted value, a control byte in the path of a base scene (`\x09`).
    subroutine read_study(path, study, error)
        character(len=*), intent(in) :: path
        type(study_type), intent(out) :: study
        type(error_type), allocatable, intent(out) :: error

        call read_study_file(path, study, error)
        if (allocated(error)) error%message = visible(error%message)
    end subroutine read_study

    !> read_study, its messages as they come.
    subroutine read_study_file(path, study, error)
        character(len=*), intent(in) :: path
        type(study_type), intent(out) :: study
        type(error_type), allocatable, intent(out) :: error
        type(group_type), allocatable :: groups(:)
        character(len=:), allocatable :: file
        integer :: g

        file = visible(path)
        study%path = path
        study%name = path(index(path, "/", back=.true.) + 1:)
        if (index(study%name, ".nml", back=.true.) == len(study%name) - 3 &
            & .and. len(study%name) > 4) study%name = study%name(:len(study%name) - 4)
        study%title = study%name
        block
            use rollcon_namelist_lexer, only : line_type
            type(line_type), allocatable :: lines(:)
            logical :: exists
            inquire(file=path, exist=exists)
            if (.not. exists) then
                call input_error(error, file, 0, "", "no such study file")
                return
            end if
            call read_lines(path, lines, error, "study file")
            if (allocated(error)) return
            call check_bytes(path, lines, error)
            if (allocated(error)) return
            call scan_groups(file, lines, study_groups, groups, error)
            if (allocated(error)) return
        end block
        g = group_index(groups, "study")
        if (g == 0) then
            call input_error(error, file, 0, "", "has no &study group; a study names its base " &
                & // "scene there: &study scene = 'data/coin.nml' /")
            return
        end if
        call read_study_group(file, groups(g), study, error)
        if (allocated(error)) return
        call read_sampling(file, groups, study, error)
        if (allocated(error)) return
        g = group_index(groups, "classify")
        call read_rules(file, groups, g, study, error)
        if (allocated(error)) return
        g = group_index(groups, "map")
        call read_map(file, groups, g, study, error)
        if (allocated(error)) return
        call check_base_scene(file, study, error)
    end subroutine read_study_file

    !> &study: scene (required: a namelist scene, or an ADAMS dataset ending in .adm) and title.
    subroutine read_study_group(file, group, study, error)
        character(len=*), intent(in) :: file
        type(group_type), intent(in) :: group
        type(study_type), intent(inout) :: study
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: message
        integer :: k

        do k = 1, size(group%assignments)
            associate (a => group%assignments(k))
                select case (a%key)
                case ("scene")
                    ! a dataset is a path as given; a scene may be a name (coin: data/coin.nml)
                    study%dataset = is_dataset(unquoted(a%value))
                    study%scene_path = unquoted(a%value)
                    if (.not. study%dataset) study%scene_path = scene_path(study%scene_path)
                    call read_lines(study%scene_path, study%scene_lines, error, &
                        & trim(merge("dataset   ", "scene file", study%dataset)))
                    if (allocated(error)) then
                        message = error%message
                        call input_error(error, file, a%line, "scene", "names a base scene " &
                            & // "that cannot be read: " // message)
                        return
                    end if
                case ("title")
                    study%title = unquoted(a%value)
                case default
                    call input_error(error, file, a%line, a%key, "is not a key of &study; " &
                        & // "its keys are scene, title")
                    return
                end select
            end associate
        end do
        if (.not. allocated(study%scene_path)) then
            call input_error(error, file, group%line, "scene", "is missing in &study: the " &
                & // "base scene, a path or a name in data/ (scene = 'coin')")
        end if
    end subroutine read_study_group

    !> &grid or &random (one of them): the parameters, and the samples and seed of &random.
    subroutine read_sampling(file, groups, study, error)
        character(len=*), intent(in) :: file
        type(group_type), intent(in) :: groups(:)
        type(study_type), intent(inout) :: study
        type(error_type), allocatable, intent(out) :: error
        type(study_parameter_type) :: parameter
        integer :: g, gr, k

        g = group_index(groups, "grid")
        gr = group_index(groups, "random")
        if (g > 0 .and. gr > 0) then
            call input_error(error, file, groups(gr)%line, "", "&grid (line " &
                & // to_text(groups(g)%line) // ") and &random both choose the cases; give one")
            return
        else if (g == 0 .and. gr == 0) then
            call input_error(error, file, 0, "", "has neither &grid nor &random: a study " &
                & // "varies scene keys, e.g. &grid disk%thickness = '0.003 0.2 12' /")
            return
        end if
        study%sampling = sampling_grid
        if (gr > 0) then
            study%sampling = sampling_random
            g = gr
        end if
        allocate(study%parameters(0))
        study%seed = 1
        do k = 1, size(groups(g)%assignments)
            associate (a => groups(g)%assignments(k))
                if (study%sampling == sampling_random .and. (a%key == "samples" &
                    & .or. a%key == "seed")) then
                    call read_count(file, a, study, error)
                else
                    call read_parameter(file, groups(g)%name, a, study%sampling, study%dataset, &
                        & parameter, error)
                    if (allocated(error)) return
                    ! the count of cases, checked once all are read (check_case_count)
                    study%parameters = [study%parameters, parameter]
                end if
            end associate
            if (allocated(error)) return
        end do
        if (size(study%parameters) == 0) then
            call input_error(error, file, groups(g)%line, "", "&" // groups(g)%name &
                & // " varies no scene key; give group%key = '...', e.g. " &
                & // "initial%speed = '0.4 1.0 61'")
        else if (study%sampling == sampling_random .and. study%samples == 0) then
            call input_error(error, file, groups(g)%line, "samples", "is missing in &random: " &
                & // "the number of cases to draw (at least 1)")
        else
            ! before any case is made: a plan of 1e9 cases would not fit in memory
            call check_case_count(file, groups(g)%line, study, error)
        end if
    end subroutine read_sampling

    !> samples (at least 1) or seed of &random.
    subroutine read_count(file, a, study, error)
        character(len=*), intent(in) :: file
        type(assignment_type), intent(in) :: a
        type(study_type), intent(inout) :: study
        type(error_type), allocatable, intent(out) :: error
        integer :: value, stat

        read(a%value, *, iostat=stat) value
        if (stat /= 0 .or. verify(a%value, "+-0123456789") /= 0) then
            call input_error(error, file, a%line, a%key, "must be a whole number, got " &
                & // a%value)
        else if (a%key == "samples" .and. value < 1) then
            call input_error(error, file, a%line, a%key, "must be at least 1 (the number of " &
                & // "cases to draw), got " // a%value)
        else if (a%key == "samples") then
            study%samples = value
        else
            study%seed = value
        end if
    end subroutine read_count

    !> The base scene must read as it is. A case whose parameters make it unreadable (a
    !> check across keys fails) is refused on its own, as a row (rollcon_study_run).
    subroutine check_base_scene(file, study, error)
        character(len=*), intent(in) :: file
        type(study_type), intent(in) :: study
        type(error_type), allocatable, intent(out) :: error
        type(scene_type) :: scene

        if (study%dataset) then
            call check_dataset_parameters(file, study, error)
            return
        end if
        call read_scene_lines(study%scene_path, study%scene_lines, scene, error)
        if (allocated(error)) error%message = file // ": its base scene is refused: " &
            & // error%message
    end subroutine check_base_scene

    pure integer function group_index(groups, name) result(g)
        type(group_type), intent(in) :: groups(:)
        character(len=*), intent(in) :: name

        do g = 1, size(groups)
            if (groups(g)%name == name) return
        end do
        g = 0
    end function group_index

    !> A value without its quotes.

end module rollcon_study_reader
