! SPDX-License-Identifier: MIT
!> load_job: a path (and --ucosub) made a job (rollcon_job). `MODEL.adm` is an ADAMS dataset
!> (docs/datasets.md); anything else a namelist scene (`coin` is data/coin.nml; docs/scenes.md).
!> Overrides set values apart from the file, as a study's case does (docs/studies.md): a
!> scene's `group%key`, a dataset's `statement%id%keyword[%k]`.
module rollcon_load
    use rollcon_error, only : error_type, fatal_error, input_error, stat_input
    use rollcon_text, only : lower_case
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names
    use rollcon_scene, only : scene_type, read_scene, read_scene_lines, scene_path, &
        & scene_override_type
    use rollcon_namelist_lexer, only : line_type, read_lines
    use rollcon_scene_source, only : new_scene_source
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_overrides, only : adm_override_type, parse_override_name
    use rollcon_dataset_source, only : new_dataset_source
    use rollcon_job, only : job_type
    implicit none
    private

    public :: load_job, input_override_type, is_dataset, output_name

    !> A value set apart from the input file: name as the input writes it (strike%impulse,
    !> part%2%vx), value as the file would write it
    type :: input_override_type
        character(len=:), allocatable :: name, value
    end type input_override_type

contains

    !> Read and check the input at path (a scene name or path, or MODEL.adm) with its
    !> overrides, and make it a job whose UCONs without a routine of their own are served by
    !> ucosub: a file (run apart), a built-in routine's name when no such file exists, or
    !> (absent or "") rollcon's hand-checked disk. Refusals name the file, line and key.
    subroutine load_job(path, job, error, ucosub, overrides)
        character(len=*), intent(in) :: path
        type(job_type), intent(out) :: job
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: ucosub
        type(input_override_type), intent(in), optional :: overrides(:)
        type(input_override_type), allocatable :: given(:)

        allocate(given(0))
        if (present(overrides)) given = overrides
        if (is_dataset(path)) then
            call load_dataset(path, given, job, error)
        else
            call load_scene(scene_path(path), given, job, error)
        end if
        if (allocated(error)) return
        job%name = output_name(path)
        job%user_file = ""
        job%routine_name = "disk"
        job%command_line = ""
        job%output_dir = "output"
        if (present(ucosub)) call choose_ucosub(ucosub, job, error)
    end subroutine load_job

    !> The name of the outputs of the input at path (DIR/NAME.csv, .summary.txt, .parts, and
    !> the pictures drawn from them), decided here only: a dataset's file name with its
    !> extension (data/coin.adm: coin.adm), a scene's name (coin, or data/coin.nml: coin). So a
    !> scene and a dataset of one name keep their own outputs side by side.
    pure function output_name(path) result(name)
        !> A scene's name or path, or a dataset's path
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: name
        integer :: n

        name = trim(path)
        name = name(index(name, "/", back=.true.) + 1:)
        if (is_dataset(path)) return
        n = len(name)
        if (n >= 4) then
            if (name(n - 3:) == ".nml") name = name(:n - 4)
        end if
    end function output_name

    !> True when path is a dataset: it ends in .adm (any case).
    pure logical function is_dataset(path)
        character(len=*), intent(in) :: path
        integer :: n

        n = len_trim(path)
        is_dataset = .false.
        if (n > 4) is_dataset = lower_case(path(n - 3:n)) == ".adm"
    end function is_dataset

    subroutine load_scene(path, overrides, job, error)
        character(len=*), intent(in) :: path
        type(input_override_type), intent(in) :: overrides(:)
        type(job_type), intent(inout) :: job
        type(error_type), allocatable, intent(out) :: error
        type(scene_override_type) :: set(size(overrides))
        type(line_type), allocatable :: lines(:)
        type(scene_type) :: scene
        integer :: k, cut

        do k = 1, size(overrides)
            cut = index(overrides(k)%name, "%")
            set(k)%group = overrides(k)%name(:cut - 1)
            set(k)%key = overrides(k)%name(cut + 1:)
            set(k)%value = overrides(k)%value
        end do
        if (size(overrides) == 0) then
            call read_scene(path, scene, error)
        else
            call read_lines(path, lines, error)
            if (.not. allocated(error)) call read_scene_lines(path, lines, scene, error, set)
        end if
        if (allocated(error)) return
        allocate(job%source, source=new_scene_source(scene))
    end subroutine load_scene

    subroutine load_dataset(path, overrides, job, error)
        character(len=*), intent(in) :: path
        type(input_override_type), intent(in) :: overrides(:)
        type(job_type), intent(inout) :: job
        type(error_type), allocatable, intent(out) :: error
        type(adm_override_type) :: set(size(overrides))
        type(adm_model_type) :: adm
        character(len=:), allocatable :: group, key
        integer :: k

        do k = 1, size(overrides)
            call parse_override_name(overrides(k)%name, set(k), group, key)
            if (len(group) == 0) then
                call input_error(error, path, 0, overrides(k)%name, "is not a value of the " &
                    & // "dataset; name one as statement%id%keyword or statement%id%keyword%k")
                return
            end if
            set(k)%value = overrides(k)%value
        end do
        call read_adm(path, adm, error, set)
        if (allocated(error)) return
        allocate(job%source, source=new_dataset_source(adm, path))
    end subroutine load_dataset

    !> --ucosub NAME: a file when one exists (compiled and run apart), else a built-in
    !> routine's name; "" keeps the hand-checked disk. A model whose every UCON names its own
    !> ROUTINE has no use for it: it is then neither compiled nor named in the run's record,
    !> and the input's warning says so (a file that serves nothing must not look as if it did).
    subroutine choose_ucosub(name, job, error)
        character(len=*), intent(in) :: name
        type(job_type), intent(inout) :: job
        type(error_type), allocatable, intent(out) :: error
        procedure(ucosub_interface), pointer :: builtin
        logical :: exists, time_free, found
        character(len=:), allocatable :: unused

        if (len_trim(name) == 0) return
        if (job%source%own_routines) then
            unused = "--ucosub " // trim(name) // " is not used: every UCON of the model " &
                & // "names its ROUTINE"
            if (len(job%source%input_warning()) > 0) then
                job%source%warning = job%source%input_warning() // "; " // unused
            else
                job%source%warning = unused
            end if
            return
        end if
        inquire(file=name, exist=exists)
        if (exists) then
            job%user_file = name
            return
        end if
        call find_builtin_ucosub(name, builtin, time_free, found)
        if (.not. found) then
            call fatal_error(error, "--ucosub " // name // ": no such file, and not a built-in " &
                & // "routine (" // builtin_ucosub_names() // ")", stat_input)
            return
        end if
        job%routine => builtin
        job%routine_name = name
    end subroutine choose_ucosub

end module rollcon_load
