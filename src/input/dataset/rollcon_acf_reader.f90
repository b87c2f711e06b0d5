! SPDX-License-Identifier: MIT
!> An ADAMS/Solver command file (.acf), read as ADAMS reads one (docs/datasets.md, "The
!> command file"): its first line names the dataset (with or without `.adm`; relative to the
!> command file's folder), its second the name of the outputs (blank: the dataset's), then
!> commands, one a statement as in a dataset (continuation lines start with a comma, or the
!> line before ends with `&`; `!` comments), up to STOP or the end of the file:
!>
!>     SIMULATE/DYNAMIC, END=t | DURATION=t, STEPS=n | DTOUT=dt   (or /KINEMATIC)
!>     SIMULATE/STATIC     (the static equilibrium: before the first DYNAMIC, or alone)
!>     INTEGRATOR/...      (rollcon's and ADAMS's keywords, as the statement; before the
!>                          first SIMULATE: one run has one integrator)
!>     EQUILIBRIUM/...     (its ERROR, IMBALANCE, MAXIT, TLIMIT, ALIMIT honoured, as the
!>                          statement's; the rest warned)
!>     OUTPUT/...          (and DEBUG, PREFERENCES, IC, KINEMATICS: read, warned)
!>     STOP
!>
!> Several SIMULATE commands in a row continue one run, each with its own output times
!> (rollcon_adm_run); they replace the dataset's SIMULATE. Any other command is refused, all
!> of them in one message, with the file and line. read_acf reads the file; apply_acf applies
!> its commands to the dataset it names, once that is read.
module rollcon_acf_reader
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, comma_list
    use rollcon_namelist_lexer, only : line_type, read_lines
    use rollcon_adm_lexer, only : adm_text_type, adm_statement_type, lex_adm_lines, upper_case
    use rollcon_adm_keywords, only : resolve_keyword, place
    use rollcon_adm_model, only : adm_model_type, adm_segment_type
    use rollcon_adm_run, only : read_segment, set_run_times
    use rollcon_adm_integrator, only : read_integrator
    use rollcon_adm_outputs, only : read_output_statement, unused_warning
    implicit none
    private

    public :: acf_type, read_acf, apply_acf

    !> The commands rollcon reads from a command file
    character(len=*), parameter :: acf_command_names(9) = [character(len=11) :: "SIMULATE", &
        & "INTEGRATOR", "OUTPUT", "STOP", "DEBUG", "PREFERENCES", "EQUILIBRIUM", "IC", &
        & "KINEMATICS"]
    !> The UTF-8 encoding of U+FEFF, the byte-order mark
    character(len=*), parameter :: byte_order_mark = achar(239) // achar(187) // achar(191)

    !> A command file, read
    type :: acf_type
        !> The command file, for messages
        character(len=:), allocatable :: file
        !> The dataset it names: its path as the run opens it (from the command file's folder)
        character(len=:), allocatable :: dataset
        !> The name of the outputs its second line gives ("": the dataset's)
        character(len=:), allocatable :: output_name
        !> The commands up to STOP, and each one's name in full
        type(adm_text_type) :: commands
        character(len=11), allocatable :: names(:)
    end type acf_type

contains

    !> Read the command file at `path`: the dataset, the output name and the commands, each
    !> command's name checked (the others refused together, a line each), INTEGRATOR before
    !> the first SIMULATE. The commands' arguments are read by apply_acf.
    subroutine read_acf(path, acf, error)
        character(len=*), intent(in) :: path
        type(acf_type), intent(out) :: acf
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        character(len=:), allocatable :: name, folder

        acf%file = path
        acf%output_name = ""
        allocate(acf%names(0))
        call read_lines(path, lines, error, "command file")
        if (allocated(error)) return
        name = ""
        if (size(lines) >= 1) name = code_of(lines(1)%text, .true.)
        if (len(name) == 0) then
            call fatal_error(error, path // ":1: the first line of a command file names the " &
                & // "dataset (MODEL or MODEL.adm, from the command file's folder), got " &
                & // trim(merge("an empty line", "no line      ", size(lines) >= 1)), stat_input)
            return
        end if
        folder = path(:index(path, "/", back=.true.))
        ! ADAMS takes the extension .adm when the name has none
        if (index(name(index(name, "/", back=.true.) + 1:), ".") == 0) name = name // ".adm"
        acf%dataset = name
        if (name(1:1) /= "/") acf%dataset = folder // name
        if (size(lines) >= 2) acf%output_name = code_of(lines(2)%text, .false.)
        if (index(acf%output_name, "/") > 0) then
            call fatal_error(error, path // ":2: the output name '" // acf%output_name &
                & // "' holds a folder; rollcon writes its outputs into --output DIR " &
                & // "(output/ by default): give a name only", stat_input)
            return
        end if
        call lex_commands(path, lines, acf, error)
    end subroutine read_acf

    !> The commands of the file's lines from the third on, to STOP: lexed as statements
    !> (`&` at a line's end joins the next line), their names checked.
    subroutine lex_commands(path, lines, acf, error)
        character(len=*), intent(in) :: path
        type(line_type), intent(in) :: lines(:)
        type(acf_type), intent(inout) :: acf
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: kept(:)
        type(error_type), allocatable :: refused
        character(len=:), allocatable :: name, refusals, first
        integer :: i, count, simulated, cut, stop_at

        allocate(kept(size(lines)))
        kept(1)%text = "command file"
        do i = 2, size(lines)
            kept(i)%text = lines(i)%text
        end do
        if (size(kept) >= 2) kept(2)%text = ""
        ! the command language's `&`: the line goes on on the next one
        do i = 3, size(kept) - 1
            cut = len_trim(code_of(kept(i)%text, .false.))
            if (cut == 0) cycle
            if (kept(i)%text(cut:cut) /= "&") cycle
            kept(i)%text = trim(kept(i)%text(:cut - 1))
            if (len(kept(i)%text) == 0) kept(i)%text = ","
            if (kept(i)%text(len(kept(i)%text):) /= ",") kept(i)%text = kept(i)%text // ","
            if (verify(kept(i + 1)%text, " ") > 0) then
                if (kept(i + 1)%text(verify(kept(i + 1)%text, " "):verify(kept(i + 1)%text, &
                    & " ")) /= ",") kept(i + 1)%text = "," // kept(i + 1)%text
            end if
        end do
        ! ADAMS stops reading at STOP: the lines after it are not lexed
        do i = 3, size(kept)
            if (is_stop(code_of(kept(i)%text, .false.))) then
                kept = kept(:i)
                exit
            end if
        end do
        call lex_adm_lines(path, kept, acf%commands, error)
        if (allocated(error)) return
        count = 0
        simulated = 0
        stop_at = 0
        refusals = ""
        do i = 1, size(acf%commands%statements)
            associate (command => acf%commands%statements(i))
                call resolve_keyword(command%name, acf_command_names, "command", "command", &
                    & place(path, command%line), name, refused)
                if (allocated(refused)) then
                    count = count + 1
                    if (count == 1) first = refused%message // command_reason(command%name)
                    refusals = refusals // new_line("a") // "  " // refused%message &
                        & // command_reason(command%name)
                    deallocate(refused)
                    cycle
                end if
                if (name == "STOP") then
                    ! ADAMS stops here: what follows is not read
                    stop_at = i
                    exit
                end if
                if (name == "SIMULATE") simulated = simulated + 1
                if (name == "INTEGRATOR" .and. simulated > 0) then
                    count = count + 1
                    refused_text: block
                        character(len=:), allocatable :: text
                        text = place(path, command%line) // ": INTEGRATOR after a SIMULATE: " &
                            & // "rollcon runs the SIMULATE commands as one run with one " &
                            & // "integrator; give INTEGRATOR before the first SIMULATE"
                        if (count == 1) first = text
                        refusals = refusals // new_line("a") // "  " // text
                    end block refused_text
                end if
                acf%names = [character(len=11) :: acf%names, name]
            end associate
        end do
        if (count == 1) then
            call fatal_error(error, first, stat_input)
        else if (count > 1) then
            call fatal_error(error, path // ": " // to_text(count) // " commands are not " &
                & // "read by rollcon (" // comma_list(acf_command_names) // "); nothing was run:" &
                & // refusals, stat_input)
        end if
        if (allocated(error)) return
        if (stop_at > 0) acf%commands%statements = acf%commands%statements(:stop_at - 1)
    end subroutine lex_commands

    !> Apply the command file's commands to the dataset it names, once read: its INTEGRATOR
    !> settings after the dataset's, its SIMULATE commands in place of the dataset's (the
    !> run's times from them), OUTPUT and the other commands of ADAMS's outputs and analyses
    !> recorded for the warning (named with the command file).
    subroutine apply_acf(acf, model, error)
        type(acf_type), intent(in) :: acf
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        type(adm_segment_type), allocatable :: segments(:)
        type(adm_segment_type) :: segment
        character(len=:), allocatable :: where, stem, name
        integer :: i, before, k, first_line

        allocate(segments(0))
        first_line = 0
        stem = acf%file(index(acf%file, "/", back=.true.) + 1:)
        do i = 1, size(acf%names)
            name = trim(acf%names(i))
            associate (command => acf%commands%statements(i))
                where = place(acf%file, command%line) // ": " // name
                if (command%has_id) then
                    call fatal_error(error, where // " takes no id (write " // name &
                        & // "/ARG=...)", stat_input)
                    return
                end if
                before = model%unused_count
                select case (name)
                case ("SIMULATE")
                    call read_segment(acf%file, where, command, model%units, segment, error)
                    if (allocated(error)) return
                    call append_segment(segments, segment)
                    if (first_line == 0) first_line = command%line
                case ("INTEGRATOR")
                    call read_integrator(acf%file, where, command, model%run, model%unused, &
                        & model%unused_count, error)
                case default
                    call read_output_statement(acf%file, where, name, command, .false., model, &
                        & error)
                end select
                if (allocated(error)) return
                ! what the command file holds and the run does not use, named with its file
                do k = before + 1, model%unused_count
                    model%unused(k)%what = stem // ": " // model%unused(k)%what
                end do
            end associate
        end do
        ! the dataset's warning, read with it, names the command file's unused commands too
        model%warning = unused_warning(model)
        if (size(segments) == 0) return
        model%run%segments = segments
        model%run%line = first_line
        call set_run_times(model%run, error)
    end subroutine apply_acf

    !> A command line that is STOP (abbreviated as ADAMS does: STO, STOP), alone or with
    !> arguments after a slash or comma.
    pure logical function is_stop(code)
        character(len=*), intent(in) :: code
        character(len=:), allocatable :: word
        integer :: cut

        cut = scan(code, "/, ")
        word = upper_case(code)
        if (cut > 0) word = upper_case(code(:cut - 1))
        is_stop = len(word) >= 3 .and. len(word) <= 4
        if (is_stop) is_stop = index("STOP", word) == 1
    end function is_stop

    !> Append segment to segments (each copied whole: no array constructor of a type with
    !> allocatable components).
    subroutine append_segment(segments, segment)
        type(adm_segment_type), allocatable, intent(inout) :: segments(:)
        type(adm_segment_type), intent(in) :: segment
        type(adm_segment_type), allocatable :: grown(:)
        integer :: k

        allocate(grown(size(segments) + 1))
        do k = 1, size(segments)
            grown(k) = segments(k)
        end do
        grown(size(grown)) = segment
        call move_alloc(grown, segments)
    end subroutine append_segment

    !> A line's text before its `!` comment, without blanks around it (`bom`: a byte-order
    !> mark at its start dropped).
    function code_of(text, bom) result(code)
        character(len=*), intent(in) :: text
        logical, intent(in) :: bom
        character(len=:), allocatable :: code

        code = text
        if (bom .and. index(code, byte_order_mark) == 1) code = code(len(byte_order_mark) + 1:)
        if (index(code, "!") > 0) code = code(:index(code, "!") - 1)
        code = trim(adjustl(code))
        ! a tab or a carriage return is a blank
        code = trim(adjustl(blanks(code)))
    end function code_of

    !> The text with tabs and carriage returns as blanks.
    pure function blanks(text) result(clean)
        character(len=*), intent(in) :: text
        character(len=len(text)) :: clean
        integer :: i

        clean = text
        do i = 1, len(text)
            if (text(i:i) == achar(9) .or. text(i:i) == achar(13)) clean(i:i) = " "
        end do
    end function blanks

    !> Why a well-known ADAMS command is not read (after "; "), or "".
    pure function command_reason(written) result(reason)
        character(len=*), intent(in) :: written
        character(len=:), allocatable :: reason
        character(len=:), allocatable :: word

        word = upper_case(trim(written))
        reason = ""
        if (len(word) < 3) return
        if (index("FILE", word) == 1) then
            reason = "; a command file runs the one dataset its first line names"
        else if (index("SAVE", word) == 1 .or. index("RELOAD", word) == 1) then
            reason = "; a run is not saved and reloaded"
        else if (index("ACTIVATE", word) == 1 .or. index("DEACTIVATE", word) == 1) then
            reason = "; a command that changes the model during the run is not supported: " &
                & // "change the dataset"
        else if (index("LINEAR", word) == 1) then
            reason = "; rollcon's linear analysis is the command rollcon linear MODEL.adm"
        end if
    end function command_reason

end module rollcon_acf_reader
