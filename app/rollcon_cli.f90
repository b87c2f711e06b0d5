! SPDX-License-Identifier: MIT
!> The command line of rollcon: one table of the commands and one table of the options (which
!> command takes which, with or without a value), and the one loop that reads the arguments
!> against them. Each command then asks the parsed request for its values, read as numbers
!> with messages that name the option.
module rollcon_cli
    use rollcon, only : wp, error_type, fatal_error, stat_input
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: cli_request_type, parse_command_line, command_names

    !> A command: its name, and its positional argument ("" when it takes none)
    type :: command_spec_type
        character(len=16) :: name = ""
        character(len=24) :: positional = ""
    end type command_spec_type

    !> An option: long and short form, the name of its value ("" for a flag), whether it may
    !> be given more than once, and the commands that take it (" name name ")
    type :: option_spec_type
        character(len=20) :: name = ""
        character(len=3) :: short = ""
        character(len=16) :: value = ""
        logical :: repeated = .false.
        character(len=64) :: commands = ""
    end type option_spec_type

    !> The commands; `run` is the one meant when the first argument names none
    type(command_spec_type), parameter :: commands(*) = [ &
        & command_spec_type("run", "SCENE, MODEL.adm or .acf"), &
        & command_spec_type("table", ""), &
        & command_spec_type("plot", "CSV or SCENE"), &
        & command_spec_type("animate", "CSV or SCENE"), &
        & command_spec_type("check", "FILE"), &
        & command_spec_type("bench", ""), &
        & command_spec_type("bench sweep", ""), &
        & command_spec_type("bench scaling", ""), &
        & command_spec_type("sweep", "STUDY.nml"), &
        & command_spec_type("linear", "MODEL.adm"), &
        & command_spec_type("help", ""), &
        & command_spec_type("version", "")]

    !> The options
    type(option_spec_type), parameter :: options(*) = [ &
        & option_spec_type("--help", "-h", "", .false., " all "), &
        & option_spec_type("--output", "-o", "DIR", .false., &
        & " run plot animate bench bench-sweep bench-scaling sweep linear "), &
        & option_spec_type("--quiet", "-q", "", .false., " run sweep linear "), &
        & option_spec_type("--vtk", "", "FPS", .false., " run "), &
        & option_spec_type("--allow-large-output", "", "", .false., " run "), &
        & option_spec_type("--end", "", "T", .false., " run "), &
        & option_spec_type("--steps", "", "N", .false., " run "), &
        & option_spec_type("--dtout", "", "DT", .false., " run "), &
        & option_spec_type("--ucosub", "", "FILE|NAME", .true., " run linear sweep check "), &
        & option_spec_type("--no-check", "", "", .false., " run linear sweep "), &
        & option_spec_type("--call-timeout", "", "SECONDS", .false., " run check linear sweep "), &
        & option_spec_type("--radius", "", "R", .false., " table "), &
        & option_spec_type("--state", "", "LIST", .false., " table "), &
        & option_spec_type("--ucon", "", "ID:PAR,...", .true., " check "), &
        & option_spec_type("--model", "", "MODEL.adm", .false., " check "), &
        & option_spec_type("--states", "", "N", .false., " check "), &
        & option_spec_type("--seed", "", "N", .false., " check "), &
        & option_spec_type("--json", "", "FILE", .false., " check "), &
        & option_spec_type("--quick", "", "", .false., " bench "), &
        & option_spec_type("--scenes", "", "A,B,...", .false., " bench "), &
        & option_spec_type("--repeats", "", "N", .false., " bench "), &
        & option_spec_type("--end-time", "", "T", .false., " bench bench-scaling "), &
        & option_spec_type("--study", "", "STUDY.nml", .false., " bench-sweep "), &
        & option_spec_type("--no-map", "", "", .false., " sweep "), &
        & option_spec_type("--speeds", "", "FROM,TO,COUNT", .false., " linear "), &
        & option_spec_type("--version", "", "", .false., " version ")]

    !> One option as given, with its value
    type :: given_type
        character(len=:), allocatable :: name, value
    end type given_type

    !> The command line, read
    type :: cli_request_type
        !> The command ("run", "bench sweep", ...)
        character(len=:), allocatable :: command
        !> The positional argument ("" when none was given)
        character(len=:), allocatable :: positional
        type(given_type), allocatable :: given(:)
    contains
        procedure :: has
        procedure :: text
        procedure :: count
        procedure :: nth
        procedure :: real_value
        procedure :: real_list
        procedure :: integer_value
    end type cli_request_type

contains

    !> The names of the commands, as a usage line lists them.
    function command_names() result(names)
        character(len=:), allocatable :: names
        integer :: k

        names = trim(commands(1)%name)
        do k = 2, size(commands)
            names = names // ", " // trim(commands(k)%name)
        end do
    end function command_names

    !> The one loop over the arguments: the command (run when the first argument names none),
    !> then options of that command with their values, and at most one positional argument.
    !> --help anywhere asks for the command's help (command "help" when none was named).
    subroutine parse_command_line(request, error)
        type(cli_request_type), intent(out) :: request
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: argument
        integer :: i, k, spec

        request%command = "run"
        request%positional = ""
        allocate(request%given(0))
        i = 1
        if (command_argument_count() >= 1) then
            argument = get_argument(1)
            k = command_index(argument)
            if (argument == "bench" .and. command_argument_count() >= 2) then
                if (get_argument(2) == "sweep") k = command_index("bench sweep")
                if (get_argument(2) == "scaling") k = command_index("bench scaling")
            end if
            if (argument == "--version") k = command_index("version")
            if (k > 0) then
                request%command = trim(commands(k)%name)
                i = 1 + merge(2, 1, request%command == "bench sweep" &
                    & .or. request%command == "bench scaling")
            end if
        end if
        do while (i <= command_argument_count())
            argument = get_argument(i)
            if (argument(1:min(1, len(argument))) == "-" .and. len(argument) > 1) then
                spec = option_index(argument)
                if (spec > 0) then
                    if (.not. takes(spec, request%command)) spec = 0
                end if
                if (spec == 0) then
                    call fatal_error(error, "unknown option '" // argument // "' for rollcon " &
                        & // request%command // "; run 'rollcon " // help_command(request) &
                        & // "--help' for the usage", stat_input)
                    return
                end if
                call take_option(request, spec, i, error)
                if (allocated(error)) return
            else
                call take_positional(request, argument, error)
                if (allocated(error)) return
            end if
            i = i + 1
        end do
        if (request%has("--help") .and. request%command == "run" .and. &
            & command_argument_count() >= 1) then
            if (get_argument(1) /= "run") request%command = "help"
        end if
    end subroutine parse_command_line

    !> "check " for `rollcon check --help`, "" for the main help.
    function help_command(request) result(text)
        type(cli_request_type), intent(in) :: request
        character(len=:), allocatable :: text

        ! the commands with a help of their own; the others are in the main help
        select case (request%command)
        case ("check", "bench", "bench sweep", "bench scaling", "sweep", "linear")
            text = request%command // " "
        case default
            text = ""
        end select
    end function help_command

    !> Option spec (an index into options) given at argument i, with its value when it takes
    !> one; given twice is refused unless the option repeats.
    subroutine take_option(request, spec, i, error)
        type(cli_request_type), intent(inout) :: request
        integer, intent(in) :: spec
        integer, intent(inout) :: i
        type(error_type), allocatable, intent(out) :: error
        type(given_type) :: option
        type(option_spec_type) :: o

        o = options(spec)
        option%name = trim(o%name)
        option%value = ""
        if (request%has(option%name) .and. .not. o%repeated) then
            call fatal_error(error, option%name // " is given twice; give it once", &
                & stat_input)
            return
        end if
        if (len_trim(o%value) > 0) then
            if (i + 1 > command_argument_count()) then
                call fatal_error(error, option%name // " needs a value (" // trim(o%value) &
                    & // ")", stat_input)
                return
            end if
            i = i + 1
            option%value = get_argument(i)
            ! an empty value is a mistake (a shell variable not set), never "the default"
            if (len_trim(option%value) == 0) then
                call fatal_error(error, option%name // " was given an empty value; it needs " &
                    & // trim(o%value) // " (a variable not set?)", stat_input)
                return
            end if
        end if
        request%given = [request%given, option]
    end subroutine take_option

    !> The command's one positional argument.
    subroutine take_positional(request, argument, error)
        type(cli_request_type), intent(inout) :: request
        character(len=*), intent(in) :: argument
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        k = command_index(request%command)
        ! an empty argument is a mistake (a shell variable not set), never "the default"
        if (len_trim(argument) == 0) then
            call fatal_error(error, "an empty argument was given to rollcon " // request%command &
                & // " (a variable not set?); run 'rollcon " // help_command(request) &
                & // "--help' for the usage", stat_input)
        else if (len_trim(commands(k)%positional) == 0) then
            call fatal_error(error, "unexpected argument '" // argument // "': rollcon " &
                & // request%command // " takes no " // trim(merge("SCENE   ", "argument", &
                & request%command == "table")) // "; run 'rollcon " // help_command(request) &
                & // "--help' for the usage", stat_input)
        else if (len(request%positional) > 0) then
            call fatal_error(error, "unexpected argument '" // argument // "' after '" &
                & // request%positional // "': give one " // trim(commands(k)%positional) &
                & // "; run 'rollcon " // help_command(request) // "--help' for the usage" &
                & // mistyped_command(request%positional), stat_input)
        else
            request%positional = argument
        end if
    end subroutine take_positional

    !> "; and 'word' is not a command (run, table, ...)" when word names neither a file nor a
    !> shipped scene (data/word.nml): most likely a command mistyped (`rollcon plto x.csv`).
    function mistyped_command(word) result(hint)
        character(len=*), intent(in) :: word
        character(len=:), allocatable :: hint
        logical :: file, scene

        hint = ""
        inquire(file=word, exist=file)
        inquire(file="data/" // word // ".nml", exist=scene)
        if (.not. (file .or. scene)) hint = "; and '" // word // "' is not a command (" &
            & // command_names() // ")"
    end function mistyped_command

    !> The option was given.
    pure logical function has(self, name)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k

        has = .false.
        do k = 1, size(self%given)
            if (self%given(k)%name == name) has = .true.
        end do
    end function has

    !> The option's value, or default when it was not given.
    function text(self, name, default) result(value)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name, default
        character(len=:), allocatable :: value
        integer :: k

        value = default
        do k = 1, size(self%given)
            if (self%given(k)%name == name) value = self%given(k)%value
        end do
    end function text

    !> How many times the option was given.
    pure integer function count(self, name)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k

        count = 0
        do k = 1, size(self%given)
            if (self%given(k)%name == name) count = count + 1
        end do
    end function count

    !> The value of the n-th time the option was given ("" when there is none).
    function nth(self, name, n) result(value)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name
        integer, intent(in) :: n
        character(len=:), allocatable :: value
        integer :: k, seen

        value = ""
        seen = 0
        do k = 1, size(self%given)
            if (self%given(k)%name /= name) cycle
            seen = seen + 1
            if (seen == n) value = self%given(k)%value
        end do
    end function nth

    !> The option's value as one finite number (default when not given).
    subroutine real_value(self, name, value, default, error)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name
        real(wp), intent(out) :: value
        real(wp), intent(in) :: default
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: values(1)

        value = default
        if (.not. self%has(name)) return
        call read_reals(name, self%text(name, ""), values, error)
        value = values(1)
    end subroutine real_value

    !> The option's value as exactly size(values) finite numbers separated by commas (values
    !> unchanged when it was not given).
    subroutine real_list(self, name, values, error)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name
        real(wp), intent(inout) :: values(:)
        type(error_type), allocatable, intent(out) :: error

        if (.not. self%has(name)) return
        call read_reals(name, self%text(name, ""), values, error)
    end subroutine real_list

    !> The option's value as a whole number >= minimum (default when not given).
    subroutine integer_value(self, name, value, default, minimum, error)
        class(cli_request_type), intent(in) :: self
        character(len=*), intent(in) :: name
        integer, intent(out) :: value
        integer, intent(in) :: default, minimum
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: given
        character(len=16) :: bound
        integer :: stat

        value = default
        if (.not. self%has(name)) return
        given = self%text(name, "")
        stat = 1
        if (len(given) > 0 .and. verify(given, "+-0123456789") == 0) &
            & read(given, *, iostat=stat) value
        if (stat /= 0 .or. value < minimum) then
            write(bound, '(i0)') minimum
            call fatal_error(error, name // " expects a whole number >= " // trim(bound) &
                & // ", got '" // given // "'", stat_input)
        end if
    end subroutine integer_value

    !> Exactly size(values) finite numbers separated by commas.
    subroutine read_reals(name, given, values, error)
        character(len=*), intent(in) :: name, given
        real(wp), intent(inout) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=64) :: extra
        integer :: stat

        read(given, *, iostat=stat) values
        if (stat == 0) then
            ! a further value means the list is too long
            read(given, *, iostat=stat) values, extra
            stat = merge(1, 0, stat == 0)
        end if
        if (stat /= 0 .or. .not. all(ieee_is_finite(values))) then
            if (size(values) == 1) then
                call fatal_error(error, name // " expects one finite number, got '" // given &
                    & // "'", stat_input)
            else
                write(extra, '(i0)') size(values)
                call fatal_error(error, name // " expects " // trim(extra) // " finite " &
                    & // "numbers separated by commas, got '" // given // "'", stat_input)
            end if
        end if
    end subroutine read_reals

    pure integer function command_index(name) result(k)
        character(len=*), intent(in) :: name

        do k = 1, size(commands)
            if (commands(k)%name == name) return
        end do
        k = 0
    end function command_index

    pure integer function option_index(name) result(k)
        character(len=*), intent(in) :: name

        do k = 1, size(options)
            if (options(k)%name == name .or. (len_trim(options(k)%short) > 0 &
                & .and. options(k)%short == name)) return
        end do
        k = 0
    end function option_index

    !> The command takes the option.
    pure logical function takes(spec, command)
        integer, intent(in) :: spec
        character(len=*), intent(in) :: command
        character(len=:), allocatable :: word

        word = command
        if (word == "bench sweep") word = "bench-sweep"
        if (word == "bench scaling") word = "bench-scaling"
        if (word == "help") word = "run"
        takes = index(options(spec)%commands, " all ") > 0 &
            & .or. index(options(spec)%commands, " " // word // " ") > 0
    end function takes

    !> Argument i, whole.
    function get_argument(i) result(argument)
        integer, intent(in) :: i
        character(len=:), allocatable :: argument
        integer :: length

        call get_command_argument(i, length=length)
        allocate(character(len=length) :: argument)
        if (length > 0) call get_command_argument(i, argument)
    end function get_argument

end module rollcon_cli
