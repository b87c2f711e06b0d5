! SPDX-License-Identifier: MIT
!> load_job: a path (and --ucosub) made a job (rollcon_job). `MODEL.adm` is an ADAMS dataset
!> (docs/datasets.md); `MODEL.acf` an ADAMS command file, which names the dataset and gives
!> its run (docs/datasets.md, "The command file"); anything else a namelist scene (`coin` is
!> data/coin.nml; docs/scenes.md). A dataset's run may be given apart from it, as
!> `rollcon run --end T --steps N` does (run_times_type).
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
    use rollcon_adm_run, only : run_times_type, apply_run_times
    use rollcon_acf_reader, only : acf_type, read_acf, apply_acf
    use rollcon_dataset_source, only : new_dataset_source
    use rollcon_job, only : job_type, user_file_type
    implicit none
    private

    public :: load_job, add_user_file, input_override_type, is_dataset, output_name, &
        & is_command_file
    public :: outputs_name_of
    public :: run_times_type

    !> A value set apart from the input file: name as the input writes it (strike%impulse,
    !> part%2%vx), value as the file would write it
    type :: input_override_type
        character(len=:), allocatable :: name, value
    end type input_override_type

contains

    !> Read and check the input at path (a scene name or path, MODEL.adm, or MODEL.acf) with
    !> its overrides, and make it a job whose UCONs without a routine of their own are served
    !> by ucosub: a file (run apart), a built-in routine's name when no such file exists, or
    !> (absent or "") rollcon's hand-checked disk. times (a dataset's or a command file's
    !> only) replace the SIMULATE of either. Refusals name the file, line and key.
    subroutine load_job(path, job, error, ucosub, overrides, times)
        character(len=*), intent(in) :: path
        type(job_type), intent(out) :: job
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: ucosub
        type(input_override_type), intent(in), optional :: overrides(:)
        !> The run's times given apart from the input (rollcon run --end, --steps, --dtout)
        type(run_times_type), intent(in), optional :: times
        type(input_override_type), allocatable :: given(:)
        type(run_times_type) :: run_times

        allocate(given(0))
        if (present(overrides)) given = overrides
        if (present(times)) run_times = times
        if (is_command_file(path)) then
            call load_command_file(path, given, run_times, job, error)
        else if (is_dataset(path)) then
            call load_dataset(path, given, run_times, job, error)
            if (.not. allocated(error)) job%name = output_name(path)
        else
            if (run_times%end_given .or. run_times%steps_given .or. run_times%dtout_given) then
                call fatal_error(error, "--end, --steps and --dtout give the run of a dataset " &
                    & // "(MODEL.adm) or a command file (MODEL.acf); a scene's run is its &run " &
                    & // "end_time and output_step (docs/scenes.md)", stat_input)
                return
            end if
            call load_scene(scene_path(path), given, job, error)
            if (.not. allocated(error)) job%name = output_name(path)
        end if
        if (allocated(error)) return
        job%user_file = ""
        allocate(job%more_files(0))
        job%routine_name = "disk"
        job%command_line = ""
        job%output_dir = "output"
        ! a command file's job keeps its dataset's path, the file rollcon check --model reads
        if (.not. allocated(job%input_path)) job%input_path = path
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

    !> The name of the outputs `load_job(path, ...)` gives its job, for any input: a command
    !> file's second line, else its dataset's output_name (the command file read: refused as
    !> load_job refuses it); a scene's or a dataset's output_name. `rollcon plot MODEL.acf`
    !> finds the CSV `rollcon run MODEL.acf` wrote by it.
    subroutine outputs_name_of(path, name, error)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: name
        type(error_type), allocatable, intent(out) :: error
        type(acf_type) :: acf

        if (.not. is_command_file(path)) then
            name = output_name(path)
            return
        end if
        call read_acf(path, acf, error)
        if (allocated(error)) return
        name = acf%output_name
        if (len(name) == 0) name = output_name(acf%dataset)
    end subroutine outputs_name_of

    !> True when path is an ADAMS command file: it ends in .acf (any case).
    pure logical function is_command_file(path)
        character(len=*), intent(in) :: path
        integer :: n

        n = len_trim(path)
        is_command_file = .false.
        if (n > 4) is_command_file = lower_case(path(n - 3:n)) == ".acf"
    end function is_command_file

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

    !> The dataset at path, its run replaced by times when they are given.
    subroutine load_dataset(path, overrides, times, job, error)
        character(len=*), intent(in) :: path
        type(input_override_type), intent(in) :: overrides(:)
        type(run_times_type), intent(in) :: times
        type(job_type), intent(inout) :: job
        type(error_type), allocatable, intent(out) :: error
        type(adm_override_type), allocatable :: set(:)
        type(adm_model_type) :: adm
        logical :: apart

        call dataset_overrides(path, overrides, set, error)
        if (allocated(error)) return
        apart = times%end_given .or. times%steps_given .or. times%dtout_given
        call read_adm(path, adm, error, set, run_given=apart)
        if (allocated(error)) return
        call apply_run_times(path, times, adm%units, adm%run, error)
        if (allocated(error)) return
        allocate(job%source, source=new_dataset_source(adm, path))
    end subroutine load_dataset

    !> The command file at path: the dataset it names, read with the overrides, then the
    !> file's commands and times applied; the outputs named by its second line (blank: the
    !> dataset's output_name).
    subroutine load_command_file(path, overrides, times, job, error)
        character(len=*), intent(in) :: path
        type(input_override_type), intent(in) :: overrides(:)
        type(run_times_type), intent(in) :: times
        type(job_type), intent(inout) :: job
        type(error_type), allocatable, intent(out) :: error
        type(adm_override_type), allocatable :: set(:)
        type(adm_model_type) :: adm
        type(acf_type) :: acf
        logical :: exists

        call read_acf(path, acf, error)
        if (allocated(error)) return
        inquire(file=acf%dataset, exist=exists)
        if (.not. exists) then
            call fatal_error(error, path // ":1: no dataset " // acf%dataset // " (the first " &
                & // "line names it, from the command file's folder; .adm is added to a name " &
                & // "without an extension)", stat_input)
            return
        end if
        call dataset_overrides(acf%dataset, overrides, set, error)
        if (allocated(error)) return
        call read_adm(acf%dataset, adm, error, set, run_given=.true.)
        if (allocated(error)) return
        call apply_acf(acf, adm, error)
        if (allocated(error)) return
        call apply_run_times(path, times, adm%units, adm%run, error)
        if (allocated(error)) return
        if (.not. allocated(adm%run%segments)) then
            call fatal_error(error, path // ": no SIMULATE command, and " // acf%dataset &
                & // " has no SIMULATE statement: add SIMULATE/DYNAMIC, END=t, STEPS=n to the " &
                & // "command file (before STOP), or give rollcon run " // path // " --end T " &
                & // "--steps N", stat_input)
            return
        end if
        allocate(job%source, source=new_dataset_source(adm, acf%dataset))
        job%name = acf%output_name
        if (len(job%name) == 0) job%name = output_name(acf%dataset)
        job%input_path = acf%dataset
    end subroutine load_command_file

    !> The overrides of a dataset (statement%id%keyword[%k]) as the reader takes them.
    subroutine dataset_overrides(path, overrides, set, error)
        character(len=*), intent(in) :: path
        type(input_override_type), intent(in) :: overrides(:)
        type(adm_override_type), allocatable, intent(out) :: set(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: group, key
        integer :: k

        allocate(set(size(overrides)))
        do k = 1, size(overrides)
            call parse_override_name(overrides(k)%name, set(k), group, key)
            if (len(group) == 0) then
                call input_error(error, path, 0, overrides(k)%name, "is not a value of the " &
                    & // "dataset; name one as statement%id%keyword or statement%id%keyword%k")
                return
            end if
            set(k)%value = overrides(k)%value
        end do
    end subroutine dataset_overrides

    !> One more file of user routines (--ucosub given again): run in the child process of the
    !> job's first file, whose routines come first (rollcon_user_library's load_user_routines).
    !> Refused when the job's routine is not a user's file or path is no file.
    subroutine add_user_file(job, path, error)
        type(job_type), intent(inout) :: job
        !> The file (.f, .f90, .o)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        logical :: exists

        inquire(file=path, exist=exists)
        if (.not. exists) then
            call fatal_error(error, "--ucosub " // path // ": no such file; a second --ucosub " &
                & // "names a file of user routines", stat_input)
            return
        end if
        if (len(job%user_file) == 0) then
            call fatal_error(error, "--ucosub " // path // ": more files of user routines go " &
                & // "with a first one, and the first --ucosub names none here (a built-in " &
                & // "routine, or a model that uses no user routine)", stat_input)
            return
        end if
        if (.not. allocated(job%more_files)) allocate(job%more_files(0))
        job%more_files = [job%more_files, user_file_type(path)]
    end subroutine add_user_file

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
            if (job%source%no_ucons) then
                unused = "--ucosub " // trim(name) // " is not used: the model has no UCON " &
                    & // "and no force served by a user routine"
            else
                unused = "--ucosub " // trim(name) // " is not used: every UCON of the model " &
                    & // "names its ROUTINE"
            end if
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
