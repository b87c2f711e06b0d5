! SPDX-License-Identifier: MIT
!> The check of a user's UCOSUB at the start of a run (`rollcon run MODEL.adm --ucosub FILE`):
!> in the child process that runs the routine, after the start is made consistent and before
!> the first step, every UCON the routine serves is checked entry by entry at that start
!> (rollcon_partials_check: each partial against sixth-order differences of the routine's own
!> outputs), so that a wrong partial is named before the run instead of showing only as an
!> integrator that takes thousands of times the steps or stops (a wrong Newton matrix slows or
!> stops the Newton iteration while the residuals it solves stay right). One state, the run's
!> own: the differences step 1e-3 of each variable (and of the time) around it, so the routine
!> is called nowhere the run does not go, beyond those steps.
module rollcon_run_check
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_problem, only : problem_type
    use rollcon_output_layout, only : coordinate_names
    use rollcon_model, only : served_by_model_ucosub
    use rollcon_user_ucosubs, only : find_user_ucosub, user_ucosub_source
    use rollcon_user_library, only : loaded_source
    use rollcon_partials_check, only : ucon_check_options_type, ucon_check_result_type, &
        & check_ucon_state
    implicit none
    private

    public :: check_at_start

    !> UCOVAR codes standing for a variable's kind (the velocity rule needs only which are
    !> rates): a coordinate (X) and a rate (Xdot)
    integer, parameter :: code_coordinate = 11, code_rate = 21

contains

    !> Check each UCON of problem's model that the model's UCOSUB serves (a user's file in a
    !> run apart: rollcon_job's start_check) at the consistent start (time [s], q, u: system
    !> numbering, SI; each UCON gets its variables and the time in its own units, as in the
    !> run). Any finding is an error (stat_input) listing each wrong entry (UCON/id, output,
    !> entry, the value returned and the differences' value), the command of the full check
    !> (rollcon check user_file [--ucosub MORE]... --model input_path, the run's files in the
    !> order loaded) and the option that runs anyway
    !> (--no-check). Errors of the routine itself (ERRMES, a non-finite output) pass through.
    subroutine check_at_start(user_file, input_path, problem, time, q, u, error)
        character(len=*), intent(in) :: user_file, input_path
        type(problem_type), intent(inout), target :: problem
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_options_type) :: options
        type(ucon_check_result_type) :: result
        character(len=:), allocatable :: found, whole, statement, files, source, prefix
        real(wp), allocatable :: values(:)
        integer, allocatable :: codes(:)
        real(wp) :: ucon_time
        integer :: k, i, m, before, named, line

        found = ""
        files = ""
        do k = 1, problem%model%nc
            associate (ucon => problem%model%ucons(k))
                ! the model's UCOSUB, or a user's routine its ROUTINE=FILE::NAME names
                named = 0
                if (.not. served_by_model_ucosub(ucon%routine)) then
                    named = find_user_ucosub(ucon%routine)
                    if (named == 0) cycle
                end if
                line = 0
                if (ucon%statement > 0) line = problem%model%statements(ucon%statement)%line
                statement = "UCON/" // to_text(ucon%id)
                source = user_file
                if (named > 0) source = user_ucosub_source(named)
                if (line > 0 .and. named > 0) then
                    statement = statement // " (line " // to_text(line) // ", ROUTINE=" &
                        & // ucon%routine // " of " // source // ")"
                else if (line > 0) then
                    statement = statement // " (line " // to_text(line) // ")"
                else if (named > 0) then
                    statement = statement // " (ROUTINE=" // ucon%routine // " of " // source &
                        & // ")"
                end if
                values = [(merge(u(ucon%coordinate(i)), q(ucon%coordinate(i)), &
                    & ucon%velocity(i)), i = 1, ucon%nvars)]
                codes = merge(code_rate, code_coordinate, ucon%velocity(:ucon%nvars))
                ucon_time = time
                if (ucon%converted) then
                    values = ucon%scales*values
                    ucon_time = ucon%time_scale*time
                end if
                before = 0
                if (allocated(result%mismatches)) before = size(result%mismatches)
                call check_ucon_state(ucon%ucosub, ucon%id, ucon%par, codes, ucon_time, &
                    & values, options, result, error)
                if (allocated(error)) then
                    ! the guard's message names the UCON already: its words after that name
                    prefix = "UCON/" // to_text(ucon%id) // ": "
                    if (index(error%message, prefix) == 1) &
                        & error%message = error%message(len(prefix) + 1:)
                    error%message = statement // ": " // error%message // " (in the check of " &
                        & // "the routine at the run's consistent start; --no-check skips it)"
                    return
                end if
                if (size(result%mismatches) > before .and. index(", " // files // ",", ", " &
                    & // source // ",") == 0) then
                    if (len(files) > 0) files = files // ", "
                    files = files // source
                end if
                do m = before + 1, size(result%mismatches)
                    associate (wrong => result%mismatches(m))
                        found = found // new_line("a") // "  " // statement &
                            & // " " // entry_text(problem, ucon%coordinate, ucon%velocity, &
                            & wrong%output, wrong%row, wrong%column) &
                            & // " [" // wrong%rule // "]: returned " &
                            & // to_text(wrong%returned) // ", differences give " &
                            & // to_text(wrong%expected)
                    end associate
                end do
            end associate
        end do
        if (len(found) == 0) return
        ! a dataset's UCONs are named by --model, with the run's files as the run takes them
        ! (the check finds each UCON's routine as the run does); a scene's by --ucon
        ! (docs/checker.md)
        whole = files // " --ucon ID:PAR1,PAR2,..."
        if (len(input_path) > 4) then
            if (input_path(len(input_path) - 3:) == ".adm") then
                whole = user_file
                k = 1
                do
                    k = k + 1
                    source = loaded_source(k)
                    if (len(source) == 0) exit
                    if (source /= user_file) whole = whole // " --ucosub " // source
                end do
                whole = whole // " --model " // input_path
            end if
        end if
        call fatal_error(error, files // " fails its check at the model's consistent " &
            & // "start (t = " // to_text(time) // " s), so the analysis was not started: a " &
            & // "wrong partial slows the integrators or stops them, and makes a linear " &
            & // "analysis's eigenvalues wrong" // found // new_line("a") // "  the " &
            & // "whole routine, at random states: rollcon check " // whole &
            & // "; to run anyway: --no-check", stat_input)
    end subroutine check_at_start

    !> "ARRAY(2) = dF/d(Y_2)", "XMATRX(1,2) = d2F/d(X_2) d(Y_2)", "ARRAY(2) = d2F/dt d(Y_2)"
    !> or "SCALAR (dF/dt)": an output's entry with its variables named as the CSV's columns
    !> (coordinate or rate, part id), from the UCON's coordinate and velocity lists.
    function entry_text(problem, coordinate, velocity, output, row, column) result(text)
        type(problem_type), intent(in) :: problem
        integer, intent(in) :: coordinate(:), row, column
        logical, intent(in) :: velocity(:)
        character(len=*), intent(in) :: output
        character(len=:), allocatable :: text

        select case (output)
        case ("ARRAY (dF/dq)")
            text = "ARRAY(" // to_text(row) // ") = dF/d(" // variable(row) // ")"
        case ("XMATRX (d2F/dq dq)")
            text = "XMATRX(" // to_text(row) // "," // to_text(column) // ") = d2F/d(" &
                & // variable(row) // ") d(" // variable(column) // ")"
        case ("ARRAY (d2F/dt dq)")
            text = "ARRAY(" // to_text(row) // ") = d2F/dt d(" // variable(row) // ")"
        case default
            text = output
        end select
    contains
        !> The i-th declared variable's column name ("Y_2", "psidot_3"); "?" out of range.
        function variable(i) result(name)
            integer, intent(in) :: i
            character(len=:), allocatable :: name
            integer :: part, kind

            name = "?"
            if (i < 1 .or. i > size(coordinate)) return
            part = (coordinate(i) - 1)/6 + 1
            kind = mod(coordinate(i) - 1, 6) + 1 + merge(6, 0, velocity(i))
            if (part > size(problem%model%parts)) return
            name = trim(coordinate_names(kind)) // "_" // to_text(problem%model%parts(part)%id)
        end function variable
    end function entry_text

end module rollcon_run_check
