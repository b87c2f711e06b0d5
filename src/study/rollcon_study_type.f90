! SPDX-License-Identifier: MIT
!> A parameter study (docs/studies.md): a base scene, the scene keys it varies (on a grid or
!> by seeded random samples), the rules that class each case, and how its map is drawn.
module rollcon_study_type
    use rollcon_kinds, only : wp
    use rollcon_namelist_lexer, only : line_type
    use rollcon_job, only : user_file_type, start_check_interface
    implicit none
    private

    public :: study_type, study_parameter_type, study_rule_type, study_map_type
    public :: sampling_grid, sampling_random
    public :: relation_less, relation_less_equal, relation_greater, relation_greater_equal
    public :: relation_words

    !> How the cases are chosen: every point of a grid, or seeded uniform random samples
    integer, parameter :: sampling_grid = 1, sampling_random = 2

    !> Relations a rule may test, and how they are written
    integer, parameter :: relation_less = 1, relation_less_equal = 2, relation_greater = 3, &
        & relation_greater_equal = 4
    character(len=*), parameter :: relation_words(4) = [character(len=2) :: "<", "<=", ">", ">="]

    !> One scene key the study varies
    type :: study_parameter_type
        !> Its scene group and key, lowercase (`disk`, `thickness`)
        character(len=:), allocatable :: group, key
        !> Its unit, from the scene's key table ("" when none)
        character(len=:), allocatable :: unit
        !> Range [lower, upper]: a grid includes both ends; random samples are uniform in it
        real(wp) :: lower = 0.0_wp, upper = 0.0_wp
        !> Grid points (1 for a single value); 0 for random samples
        integer :: count = 0
        !> An integer key: its values are whole numbers
        logical :: whole = .false.
        !> Line of the study file that gives it
        integer :: line = 0
    end type study_parameter_type

    !> A rule of &classify: the case is of this class when `measure relation bound` holds
    type :: study_rule_type
        character(len=:), allocatable :: class, measure
        integer :: relation = relation_greater
        real(wp) :: bound = 0.0_wp
        integer :: line = 0
    end type study_rule_type

    !> &map: the parameters on its axes (indices into the parameters) and an analytic curve
    type :: study_map_type
        integer :: x = 0, y = 0
        !> Curve drawn over the classes: "" (none) or "critical_speed" (docs/design.md §5)
        character(len=:), allocatable :: curve
    end type study_map_type

    !> A study as read from its file
    type :: study_type
        !> Study file, and its name (file name without directory and .nml)
        character(len=:), allocatable :: path, name
        !> Title of the map
        character(len=:), allocatable :: title
        !> The base scene's path and its lines: every case is this file with its parameters
        !> set (rollcon_scene's overrides)
        character(len=:), allocatable :: scene_path
        type(line_type), allocatable :: scene_lines(:)
        !> The base is an ADAMS dataset (.adm), not a namelist scene (rollcon_study_dataset)
        logical :: dataset = .false.
        integer :: sampling = sampling_grid
        !> Random samples and the seed they are drawn with
        integer :: samples = 0, seed = 0
        type(study_parameter_type), allocatable :: parameters(:)
        !> Rules in file order (the first that holds gives the class), and the class of a case
        !> that none fits
        type(study_rule_type), allocatable :: rules(:)
        character(len=:), allocatable :: otherwise
        type(study_map_type) :: map
        !> The routines every case's job takes, as `rollcon run --ucosub` gives them (not read
        !> from the study file: `rollcon sweep --ucosub`): the first a file run apart or a
        !> built-in routine's name ("" for the hand-checked disk), the others more files of
        !> user routines (rollcon_load's add_user_file)
        type(user_file_type), allocatable :: routines(:)
        !> Longest one call of a user's routine may take [s] (0: the job's own default)
        real(wp) :: call_timeout = 0.0_wp
        !> The check of a user's UCOSUB at each case's consistent start (rollcon_job's
        !> start_check; null: none)
        procedure(start_check_interface), pointer, nopass :: start_check => null()
    end type study_type

end module rollcon_study_type
