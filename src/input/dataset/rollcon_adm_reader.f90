! SPDX-License-Identifier: MIT
!> Reads an ADAMS dataset into an adm_model_type: every statement and argument of the subset
!> checked and converted to SI; the statements of ADAMS's outputs and solver choices read and
!> checked as strictly (rollcon_adm_outputs); every statement outside both refused, all of them
!> in one message, with file, line, statement and why. References between statements are
!> checked by rollcon_adm_checks.
module rollcon_adm_reader
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text, comma_list
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_namelist_lexer, only : line_type
    use rollcon_adm_lexer, only : adm_text_type, adm_statement_type, adm_argument_type, &
        & lex_adm_lines, read_dataset_lines
    use rollcon_id_index, only : id_index_type, new_id_index
    use rollcon_adm_keywords, only : resolve_keyword, statement_names, argument_key, &
        & arg_place, place, name_index
    use rollcon_adm_units, only : units_type, set_unit, unit_keywords
    use rollcon_adm_model, only : adm_model_type, force_names
    use rollcon_adm_bodies, only : read_part, read_marker
    use rollcon_adm_loads, only : read_ucon, read_accgrav, read_force, read_spring
    use rollcon_adm_run, only : read_simulate, read_integrator
    use rollcon_adm_checks, only : check_references
    use rollcon_adm_joints, only : read_joint
    use rollcon_adm_couplers, only : read_gcon, read_coupler, read_gear
    use rollcon_adm_motions, only : read_motion
    use rollcon_adm_system, only : read_variable, read_spline, read_plant, read_diff
    use rollcon_adm_data, only : read_string, read_array
    use rollcon_adm_contacts, only : read_contact
    use rollcon_adm_variables, only : resolve_variables, add_plant_warning
    use rollcon_adm_outside, only : outside_reason
    use rollcon_adm_outputs, only : output_statement_names, output_needs_id, &
        & read_output_statement, unused_warning, answer_force_requests, record_unused
    use rollcon_adm_overrides, only : adm_override_type, apply_adm_overrides
    implicit none
    private

    public :: read_adm, read_adm_lines


contains

    !> Read and check the dataset at `path`, with overrides (rollcon_adm_overrides) set first.
    subroutine read_adm(path, model, error, overrides, run_given)
        character(len=*), intent(in) :: path
        type(adm_model_type), intent(out) :: model
        type(error_type), allocatable, intent(out) :: error
        !> Values set apart from the file
        type(adm_override_type), intent(in), optional :: overrides(:)
        !> The run is given apart from the dataset (an ADAMS command file, or the options of
        !> `rollcon run`): it needs no SIMULATE statement (default false)
        logical, intent(in), optional :: run_given
        type(line_type), allocatable :: lines(:)

        call read_dataset_lines(path, lines, error)
        if (allocated(error)) return
        call read_adm_lines(path, lines, model, error, overrides, run_given)
    end subroutine read_adm

    !> Read and check a dataset given as its lines (read from `path`, which messages name),
    !> with overrides (rollcon_adm_overrides) set first. Linear in the size of the dataset:
    !> every list is allocated at its size and every id found through an index.
    subroutine read_adm_lines(path, lines, model, error, overrides, run_given)
        character(len=*), intent(in) :: path
        !> The dataset's lines, without line ends
        type(line_type), intent(in) :: lines(:)
        type(adm_model_type), intent(out) :: model
        type(error_type), allocatable, intent(out) :: error
        !> Values set apart from the file
        type(adm_override_type), intent(in), optional :: overrides(:)
        !> The run is given apart from the dataset: it needs no SIMULATE (default false)
        logical, intent(in), optional :: run_given
        type(adm_text_type) :: text
        logical :: needed

        call lex_adm_lines(path, lines, text, error)
        if (allocated(error)) return
        call refuse_outside(text, error)
        if (allocated(error)) return
        if (present(overrides)) then
            call override(text, overrides, error)
            if (allocated(error)) return
        end if
        model%file = path
        model%title = text%title
        allocate(model%parts(0), model%markers(0), model%ucons(0), model%forces(0))
        allocate(model%requests(0), model%other_requests(0), model%unused(0), &
            & model%references(0))
        ! UNITS first: every value of the dataset is in its units, wherever it stands
        call read_units(text, model%units, error)
        if (allocated(error)) return
        call read_statements(path, text, model, error)
        if (allocated(error)) return
        needed = .true.
        if (present(run_given)) needed = .not. run_given
        call check_references(model, error, simulate_needed=needed)
        if (allocated(error)) return
        ! VARVAL(id) read in place, the curves given to AKISPL and CUBSPL, PINPUT and POUTPUT
        call resolve_variables(model, error)
        if (allocated(error)) return
        call answer_force_requests(model)
        model%warning = unused_warning(model)
        call add_plant_warning(model)
    end subroutine read_adm_lines

    !> Every statement in file order, up to END; parts, markers, UCONs, forces, joints and the
    !> GCONs and couplers stored in
    !> lists allocated once and their ids checked through an index.
    subroutine read_statements(path, text, model, error)
        character(len=*), intent(in) :: path
        type(adm_text_type), intent(in) :: text
        type(adm_model_type), intent(inout) :: model
        type(error_type), allocatable, intent(out) :: error
        !> The statements' names in full
        character(len=max(len(statement_names), len(output_statement_names))) :: &
            & names(size(text%statements))
        character(len=:), allocatable :: name
        !> The ids of the parts, markers, UCONs and forces (list_of), and of the statements
        !> read and not used that take one (output_key)
        type(id_index_type) :: ids(16), output_ids
        integer :: i, n(16), k, previous
        logical :: seen(size(statement_names)), repeated

        do i = 1, size(text%statements)
            call statement_name(path, text%statements(i), name, error)
            if (allocated(error)) return
            names(i) = name
        end do
        ! the lists: parts, markers, UCONs, forces (an SFORCE and a GFORCE may share an id)
        deallocate(model%parts, model%markers, model%ucons, model%forces)
        allocate(model%parts(count(names == "PART")), model%markers(count(names == "MARKER")), &
            & model%ucons(count(names == "UCON")), model%forces(count(list_of(names) == 4)))
        allocate(model%joints(count(names == "JOINT" .or. names == "JPRIM")))
        allocate(model%gcons(count(names == "GCON")), model%couplers(count(names == "COUPLER")), &
            & model%gears(count(names == "GEAR")), model%motions(count(names == "MOTION")))
        allocate(model%variables(count(names == "VARIABLE")), &
            & model%splines(count(names == "SPLINE")), &
            & model%plants(count(names == "PINPUT" .or. names == "POUTPUT")), &
            & model%diffs(count(names == "DIFF")), model%strings(count(names == "STRING")), &
            & model%arrays(count(names == "ARRAY")))
        allocate(model%contacts(count(names == "CONTACT")))
        ids = [new_id_index(size(model%parts)), new_id_index(size(model%markers)), &
            & new_id_index(size(model%ucons)), new_id_index(size(model%forces)), &
            & new_id_index(size(model%joints)), new_id_index(size(model%gcons)), &
            & new_id_index(size(model%couplers)), new_id_index(size(model%gears)), &
            & new_id_index(size(model%motions)), new_id_index(size(model%variables)), &
            & new_id_index(size(model%splines)), new_id_index(size(model%plants)), &
            & new_id_index(size(model%diffs)), new_id_index(size(model%strings)), &
            & new_id_index(size(model%arrays)), new_id_index(size(model%contacts))]
        output_ids = new_id_index(count([(name_index(names(i), output_statement_names) > 0, &
            & i = 1, size(names))]))
        n = 0
        seen = .false.
        do i = 1, size(text%statements)
            associate (statement => text%statements(i))
                name = trim(names(i))
                if (once(name)) then
                    if (seen(name_index(name, statement_names))) then
                        call fatal_error(error, place(path, statement%line) // ": a second " &
                            & // name // " statement (a dataset has at most one)", stat_input)
                        return
                    end if
                    seen(name_index(name, statement_names)) = .true.
                end if
                if (name == "END") then
                    if (i < size(text%statements)) call fatal_error(error, place(path, &
                        & text%statements(i + 1)%line) // ": a statement after END", stat_input)
                    exit
                end if
                ! an earlier statement read and not used of this kind with this id (0: none)
                repeated = .false.
                if (name_index(name, output_statement_names) > 0) then
                    call output_ids%add(output_key(name, statement%id), i, previous)
                    repeated = previous /= 0
                end if
                call read_statement(path, name, statement, repeated, model, n, error)
                if (allocated(error)) return
                k = list_of(name)
                if (k == 0) cycle
                call ids(k)%add(list_key(name, statement%id), n(k), previous)
                if (previous /= 0) then
                    call fatal_error(error, place(path, statement%line) // ": " // name // "/" &
                        & // to_text(statement%id) // ": a second " // name // " with this id", &
                        & stat_input)
                    return
                end if
            end associate
        end do
        if (allocated(error)) return
        model%parts = model%parts(:n(1))
        model%markers = model%markers(:n(2))
        model%ucons = model%ucons(:n(3))
        model%forces = model%forces(:n(4))
        model%joints = model%joints(:n(5))
        model%gcons = model%gcons(:n(6))
        model%couplers = model%couplers(:n(7))
        model%gears = model%gears(:n(8))
        model%motions = model%motions(:n(9))
        model%variables = model%variables(:n(10))
        model%splines = model%splines(:n(11))
        model%plants = model%plants(:n(12))
        model%diffs = model%diffs(:n(13))
        model%strings = model%strings(:n(14))
        model%arrays = model%arrays(:n(15))
        model%contacts = model%contacts(:n(16))
        if (.not. allocated(model%graphics)) allocate(model%graphics(0))
        call note_contact_keys(model)
        model%requests = model%requests(:model%request_count)
        model%other_requests = model%other_requests(:model%other_request_count)
        model%unused = model%unused(:model%unused_count)
        model%references = model%references(:model%reference_count)
    end subroutine read_statements

    !> The list a statement's element goes to: 1 parts, 2 markers, 3 UCONs, 4 forces, 5 joints,
    !> 6 GCONs, 7 COUPLERs, 8 GEARs, 9 MOTIONs, 10 VARIABLEs, 11 SPLINEs, 12 PINPUTs and
    !> POUTPUTs, 13 DIFFs, 14 STRINGs, 15 ARRAYs, 16 CONTACTs; 0 none.
    elemental integer function list_of(name) result(k)
        character(len=*), intent(in) :: name

        select case (name)
        case ("PART")
            k = 1
        case ("MARKER")
            k = 2
        case ("UCON")
            k = 3
        case ("SFORCE", "VFORCE", "GFORCE", "VTORQUE", "SPRINGDAMPER", "BUSHING")
            k = 4
        case ("JOINT", "JPRIM")
            k = 5
        case ("GCON")
            k = 6
        case ("COUPLER")
            k = 7
        case ("GEAR")
            k = 8
        case ("MOTION")
            k = 9
        case ("VARIABLE")
            k = 10
        case ("SPLINE")
            k = 11
        case ("PINPUT", "POUTPUT")
            k = 12
        case ("DIFF")
            k = 13
        case ("STRING")
            k = 14
        case ("ARRAY")
            k = 15
        case ("CONTACT")
            k = 16
        case default
            k = 0
        end select
    end function list_of

    !> The key of a statement's id in its list's index: forces of different kinds may share an id.
    pure function list_key(name, id) result(key)
        character(len=*), intent(in) :: name
        integer, intent(in) :: id
        integer(int64) :: key

        ! a JOINT and a JPRIM, or forces of different kinds, may share an id
        key = 8_int64*int(id, int64) + name_index(name, force_names) &
            & + name_index(name, ["JOINT", "JPRIM"]) + name_index(name, ["PINPUT ", "POUTPUT"])
    end function list_key

    !> The key of a statement read and not used (one of output_statement_names) in its index:
    !> each kind has its own ids.
    pure function output_key(name, id) result(key)
        character(len=*), intent(in) :: name
        integer, intent(in) :: id
        integer(int64) :: key

        key = 16_int64*int(id, int64) + name_index(name, output_statement_names)
    end function output_key

    pure logical function once(name)
        character(len=*), intent(in) :: name

        once = any(name == [character(len=10) :: "ACCGRAV", "INTEGRATOR", "OUTPUT", &
            & "SIMULATE", "UNITS"])
    end function once

    !> One statement, name in full; a part, marker, UCON or force is stored at the end of its
    !> list (n: the lengths of the lists, as list_of numbers them); repeated: an earlier
    !> statement read and not used of this kind has its id (read_statements refuses that for
    !> the statements simulated).
    subroutine read_statement(path, name, statement, repeated, model, n, error)
        character(len=*), intent(in) :: path, name
        type(adm_statement_type), intent(in) :: statement
        logical, intent(in) :: repeated
        type(adm_model_type), intent(inout) :: model
        integer, intent(inout) :: n(16)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: where

        where = place(path, statement%line) // ": " // name
        if (needs_id(name) .neqv. statement%has_id) then
            if (statement%has_id) then
                call fatal_error(error, where // " takes no id (write " // name // "/ARG=...)", &
                    & stat_input)
            else
                call fatal_error(error, where // " needs an id (" // name // "/id, ...)", &
                    & stat_input)
            end if
            return
        end if
        if (statement%has_id) where = where // "/" // to_text(statement%id)
        select case (name)
        case ("PART")
            n(1) = n(1) + 1
            call read_part(path, where, statement, model%units, model%parts(n(1)), error)
        case ("MARKER")
            n(2) = n(2) + 1
            call read_marker(path, where, statement, model%units, model%markers(n(2)), error)
        case ("UCON")
            n(3) = n(3) + 1
            call read_ucon(path, where, statement, model%ucons(n(3)), error)
        case ("ACCGRAV")
            call read_accgrav(path, where, statement, model, error)
        case ("SFORCE", "VFORCE", "GFORCE", "VTORQUE")
            n(4) = n(4) + 1
            call read_force(path, where, name, statement, model%forces(n(4)), error)
        case ("SPRINGDAMPER", "BUSHING")
            n(4) = n(4) + 1
            call read_spring(path, where, name, statement, model%units, model%forces(n(4)), &
                & error)
        case ("JOINT", "JPRIM")
            n(5) = n(5) + 1
            call read_joint(path, where, name, statement, model%units, model%joints(n(5)), error)
        case ("GCON")
            n(6) = n(6) + 1
            call read_gcon(path, where, statement, model%gcons(n(6)), error)
        case ("COUPLER")
            n(7) = n(7) + 1
            call read_coupler(path, where, statement, model%couplers(n(7)), error)
        case ("GEAR")
            n(8) = n(8) + 1
            call read_gear(path, where, statement, model%gears(n(8)), error)
        case ("MOTION")
            n(9) = n(9) + 1
            call read_motion(path, where, statement, model%units, model%motions(n(9)), error)
        case ("VARIABLE")
            n(10) = n(10) + 1
            call read_variable(path, where, statement, model%variables(n(10)), error)
        case ("SPLINE")
            n(11) = n(11) + 1
            call read_spline(path, where, statement, model%splines(n(11)), error)
        case ("PINPUT", "POUTPUT")
            n(12) = n(12) + 1
            call read_plant(path, where, statement, name == "POUTPUT", model%plants(n(12)), &
                & error)
        case ("DIFF")
            n(13) = n(13) + 1
            call read_diff(path, where, statement, model%diffs(n(13)), error)
        case ("STRING")
            n(14) = n(14) + 1
            call read_string(path, where, statement, model%strings(n(14)), error)
        case ("ARRAY")
            n(15) = n(15) + 1
            call read_array(path, where, statement, model%arrays(n(15)), error)
        case ("CONTACT")
            n(16) = n(16) + 1
            call read_contact(path, where, statement, model%units%length, &
                & model%contacts(n(16)), error)
        case ("SIMULATE")
            call read_simulate(path, where, statement, model%units, model%run, error)
        case ("INTEGRATOR")
            call read_integrator(path, where, statement, model%run, model%unused, &
                & model%unused_count, error)
        case ("UNITS")
            ! read before every other statement (read_units)
        case default
            ! OUTPUT's arguments, and the statements read and not simulated
            call read_output_statement(path, where, name, statement, repeated, model, error)
        end select
    end subroutine read_statement

    !> Every statement outside the subset (simulated, or read and not used) refused at once,
    !> up to END: one alone with the message statement_name gives, several in one message of a
    !> line each.
    subroutine refuse_outside(text, error)
        type(adm_text_type), intent(in) :: text
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: refused
        character(len=:), allocatable :: name, first, lines
        integer :: i, count

        count = 0
        lines = ""
        do i = 1, size(text%statements)
            associate (statement => text%statements(i))
                call statement_name(text%file, statement, name, refused)
                if (.not. allocated(refused)) then
                    if (name == "END") exit
                    cycle
                end if
                count = count + 1
                if (count == 1) first = refused%message
                lines = lines // new_line("a") // "  " // outside_line(text%file, statement, &
                    & refused%message)
                deallocate(refused)
            end associate
        end do
        if (count == 0) return
        if (count == 1) then
            call fatal_error(error, first, stat_input)
            return
        end if
        call fatal_error(error, text%file // ": " // to_text(count) // " statements are " &
            & // "outside the supported subset (" // comma_list(statement_names) // "; read " &
            & // "and not used: " // comma_list(output_statement_names) // "); nothing was " &
            & // "run:" // lines, stat_input)
    end subroutine refuse_outside

    !> One statement outside the subset, in a line of refuse_outside's message: "file:7:
    !> JOINT/9: why" for a well-known statement, else the refusal itself without its list.
    function outside_line(path, statement, message) result(line)
        character(len=*), intent(in) :: path
        type(adm_statement_type), intent(in) :: statement
        !> statement_name's refusal
        character(len=*), intent(in) :: message
        character(len=:), allocatable :: line, reason

        reason = outside_reason(statement%name)
        if (len(reason) > 0) then
            line = place(path, statement%line) // ": " // statement%name
            if (statement%has_id) line = line // "/" // to_text(statement%id)
            line = line // ": " // reason
        else if (index(message, " (") > 0 .and. index(message, "is ambiguous") == 0 .and. &
            & index(message, "is too short") == 0) then
            line = message(:index(message, " (", back=.true.) - 1)
        else
            line = message
        end if
    end function outside_line

    !> The supported statement `statement` names (any case, abbreviated as ADAMS abbreviates
    !> it: rollcon_adm_abbreviations); a refusal says why for a well-known statement outside
    !> the subset (rollcon_adm_outside).
    subroutine statement_name(path, statement, name, error)
        character(len=*), intent(in) :: path
        type(adm_statement_type), intent(in) :: statement
        character(len=:), allocatable, intent(out) :: name
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: reason

        call resolve_keyword(statement%name, [character(len=12) :: statement_names, &
            & output_statement_names], "statement", "statement", place(path, statement%line), &
            & name, error)
        if (.not. allocated(error)) return
        if (index(error%message, "' is not a statement") > 0) then
            ! the list of a refusal: the statements simulated
            deallocate(error)
            call fatal_error(error, place(path, statement%line) // ": '" &
                & // trim(statement%name) // "' is not a statement of the supported subset (" &
                & // comma_list(statement_names) // ")", stat_input)
        end if
        reason = outside_reason(statement%name)
        if (len(reason) > 0) error%message = error%message // "; " // reason
    end subroutine statement_name

    !> Apply overrides, each statement named in full (abbreviations resolved).
    subroutine override(text, overrides, error)
        type(adm_text_type), intent(inout) :: text
        type(adm_override_type), intent(in) :: overrides(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name
        character(len=max(len(statement_names), len(output_statement_names))) :: &
            & names(size(text%statements))
        integer :: i

        do i = 1, size(text%statements)
            call statement_name(text%file, text%statements(i), name, error)
            if (allocated(error)) return
            names(i) = name
        end do
        call apply_adm_overrides(text, names, overrides, error)
    end subroutine override

    pure logical function needs_id(name)
        character(len=*), intent(in) :: name

        needs_id = any(name == [character(len=12) :: "PART", "MARKER", "UCON", "SFORCE", &
            & "VFORCE", "GFORCE", "JOINT", "JPRIM", "GCON", "COUPLER", "GEAR", "MOTION", &
            & "VTORQUE", "SPRINGDAMPER", "BUSHING", "VARIABLE", "SPLINE", "PINPUT", "POUTPUT", &
            & "DIFF", "STRING", "ARRAY", "CONTACT"]) &
            & .or. output_needs_id(name)
    end function needs_id

    !> UNITS, read before any other statement. SYSTEM sets all four units; FORCE, MASS, LENGTH
    !> and TIME given beside it override its choice, wherever they stand in the statement.
    subroutine read_units(text, units, error)
        type(adm_text_type), intent(in) :: text
        type(units_type), intent(out) :: units
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name, key, where
        integer :: i, k, pass

        do i = 1, size(text%statements)
            call statement_name(text%file, text%statements(i), name, error)
            if (allocated(error)) return
            if (name /= "UNITS") cycle
            where = place(text%file, text%statements(i)%line) // ": UNITS"
            do pass = 1, 2
                do k = 1, size(text%statements(i)%arguments)
                    associate (argument => text%statements(i)%arguments(k))
                        call argument_key(text%file, where, text%statements(i), k, &
                            & unit_keywords, key, error)
                        if (allocated(error)) return
                        if ((key == "SYSTEM") .neqv. (pass == 1)) cycle
                        if (.not. argument%assigned .or. size(argument%values) /= 1) then
                            call fatal_error(error, arg_place(text%file, where, argument) &
                                & // " " // key // ": expected one unit name", stat_input)
                            return
                        end if
                        call set_unit(units, key, argument%values(1)%text, &
                            & arg_place(text%file, where, argument) // " " // key, error)
                        if (allocated(error)) return
                    end associate
                end do
            end do
        end do
    end subroutine read_units

    !> The CONTACTs' keys read and not used (ADAMS's penalty force and friction
    !> regularisation: rollcon_adm_contacts) named in the run's warning, and the GRAPHICS a
    !> CONTACT names taken out of it (they are used: the contact's geometry).
    subroutine note_contact_keys(model)
        type(adm_model_type), intent(inout) :: model
        integer :: c, k, j, kept, g
        logical :: named

        do c = 1, size(model%contacts)
            do k = 1, size(model%contacts(c)%unused)
                call record_unused(model%unused, model%unused_count, &
                    & trim(model%contacts(c)%unused(k)), model%contacts(c)%unused_lines(k))
            end do
        end do
        if (size(model%contacts) == 0 .or. model%unused_count == 0) return
        kept = 0
        do j = 1, model%unused_count
            named = .false.
            if (model%unused(j)%what == "GRAPHICS") then
                do g = 1, size(model%graphics)
                    if (model%graphics(g)%line /= model%unused(j)%line) cycle
                    named = any(model%contacts%igeom == model%graphics(g)%id) &
                        & .or. any(model%contacts%jgeom == model%graphics(g)%id)
                end do
            end if
            if (named) cycle
            kept = kept + 1
            if (kept < j) model%unused(kept) = model%unused(j)
        end do
        model%unused_count = kept
    end subroutine note_contact_keys

end module rollcon_adm_reader
