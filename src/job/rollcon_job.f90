! SPDX-License-Identifier: MIT
!> A job: what any input becomes before it runs (docs/design.md §1, "One route"). A namelist
!> scene, a dataset, a study's case, a benchmark's row and a model built in code are each a
!> model source (rollcon_model_source) with its run settings; the job adds which routine serves
!> the UCONs that name none of their own (the hand-checked disk, a built-in routine by name, or
!> a user's file run in a child process), where its outputs go and how it reports. load_job
!> makes a job of a path; run_job (rollcon_run_job) runs any job.
module rollcon_job
    use rollcon_kinds, only : wp
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_model_source, only : model_source_type
    use rollcon_output_rows, only : default_max_csv_bytes
    use rollcon_child_process, only : default_call_timeout
    use rollcon_user_build, only : user_build_options_type
    use rollcon_problem, only : problem_type
    use rollcon_error, only : error_type
    implicit none
    private

    public :: job_type, new_job, start_check_interface, user_file_type

    !> A file of user routines
    type :: user_file_type
        !> Its path, as given
        character(len=:), allocatable :: path
    end type user_file_type

    type :: job_type
        !> What to build and run
        class(model_source_type), allocatable :: source
        !> The stem of its outputs, DIR/NAME.csv, .summary.txt, .parts: its source's name, or
        !> for an input file its output_name (rollcon_load: a dataset's keeps its .adm, so that
        !> data/coin.adm and the scene data/coin.nml never write each other's files)
        character(len=:), allocatable :: name
        !> The routine of the UCONs that name none (ADAMS's one UCOSUB per model): a built-in
        !> routine, rollcon's hand-checked disk unless the job says otherwise
        procedure(ucosub_interface), pointer, nopass :: routine => rolling_disk_ucosub
        !> ... or a user's file (.f, .f90, .o), compiled, cached and run in a child process
        !> ("" for none): the child computes, this process writes every output
        character(len=:), allocatable :: user_file
        !> More files of user routines (--ucosub given again), run in the same child process:
        !> their force routines serve the statements whose ROUTINE=FILE::NAME names them, and
        !> those of a kind user_file does not define (rollcon_user_library)
        type(user_file_type), allocatable :: more_files(:)
        !> The name of the built-in routine, for the run's record
        character(len=:), allocatable :: routine_name
        !> The command that asked for the run, for its record ("" when a program built the job)
        character(len=:), allocatable :: command_line
        !> How a user's file is compiled and where the cache is
        type(user_build_options_type) :: build_options
        !> Longest one call of a user's routine may take [s]
        real(wp) :: call_timeout = real(default_call_timeout, wp)
        !> Folder of the outputs (DIR/NAME.csv, .summary.txt, .parts); "" for none: the rows
        !> go only to the caller's history
        character(len=:), allocatable :: output_dir
        !> No progress lines and no report of the start's analysis
        logical :: quiet = .false.
        !> Largest CSV the run may plan [bytes]
        real(wp) :: max_csv_bytes = default_max_csv_bytes
        !> The input file the job was loaded from ("" when a program built the job)
        character(len=:), allocatable :: input_path
        !> Called in the child process of a run whose routine is a user's file, at the
        !> consistent start and before the first step, when associated (the program sets it:
        !> rollcon_run_check's check_at_start); an error stops the run before it starts
        procedure(start_check_interface), pointer, nopass :: start_check => null()
    end type job_type

    abstract interface
        !> Check the routine serving a built problem at its consistent start: time [s], the
        !> coordinates q and rates u (system numbering, SI); user_file and input_path name
        !> the routine's file and the job's input for messages; error stops the run.
        subroutine start_check_interface(user_file, input_path, problem, time, q, u, error)
            import :: wp, problem_type, error_type
            character(len=*), intent(in) :: user_file, input_path
            type(problem_type), intent(inout), target :: problem
            real(wp), intent(in) :: time, q(:), u(:)
            type(error_type), allocatable, intent(out) :: error
        end subroutine start_check_interface
    end interface

contains

    !> A job of a source: the hand-checked disk serves its UCONs, no outputs but the
    !> caller's history, quiet.
    function new_job(source) result(job)
        class(model_source_type), intent(in) :: source
        type(job_type) :: job

        allocate(job%source, source=source)
        job%name = source%name
        job%user_file = ""
        allocate(job%more_files(0))
        job%routine_name = "disk"
        job%command_line = ""
        job%output_dir = ""
        job%input_path = ""
        job%quiet = .true.
    end function new_job

end module rollcon_job
