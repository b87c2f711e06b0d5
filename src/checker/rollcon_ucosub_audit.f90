! SPDX-License-Identifier: MIT
!> Checks a user's UCOSUB as a whole: the initialisation call and UCOVAR declaration of each
!> UCON, then check_ucon_state on random states drawn in documented ranges, with the findings
!> grouped by UCON, rule and entry (a count and the worst case of each group).
module rollcon_ucosub_audit
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_input
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface, max_ucon_par
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_ucon_call, only : declare_ucon, stat_non_finite
    use rollcon_check_rules, only : rule_declaration, rule_errmes, rule_finite, &
        & rule_outside_block, rule_changed_argument, rule_name
    use rollcon_ucosub_guard, only : install_guard, guarded_ucosub, declare_guarded_count, &
        & note_stage, take_guard_violations, guard_violation_type, violation_text, &
        & violation_argument
    use rollcon_partials_check, only : ucon_check_options_type, ucon_check_result_type, &
        & check_ucon_state
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_random_states, only : sampling_ranges, seed_state, draw_state
    use rollcon_ucosub_units, only : ucosub_units_type, variable_scales
    implicit none
    private

    public :: ucon_request_type, user_check_options_type, finding_group_type, ucon_report_type
    public :: user_check_report_type, check_user_ucosub, check_requests, sampling_ranges
    public :: states_refusal
    public :: finding, max_check_states

    !> Most random states per UCON a check makes. Each state costs some 60 calls of the
    !> routine (about 0.3 ms for the disk): 100000 states take half a minute for a cheap
    !> routine, and every mistake the check knows shows in the first few states. A larger
    !> count would only make a check that runs for hours, so it is refused.
    integer, parameter :: max_check_states = 100000

    !> One UCON statement to check: its id and FUNCTION=USER constants
    type :: ucon_request_type
        integer :: id = 0
        real(wp), allocatable :: par(:)
        !> The units the routine computes in (a dataset's, for --model): the random states are
        !> drawn in SI's ranges and passed in these units, as a run passes them
        type(ucosub_units_type) :: units
        !> The statement as its dataset names it, for the report ("UCON/2 (line 10,
        !> ROUTINE=u::CIRCLE of u.f)"); unallocated for a UCON given as --ucon ID:PAR
        character(len=:), allocatable :: statement
    end type ucon_request_type

    !> How many states, from which seed, compared how
    type :: user_check_options_type
        !> Random states per UCON
        integer :: states = 25
        !> Seed of the states; UCON id and seed fix a UCON's states
        integer :: seed = 1
        !> Difference step and tolerance of check_ucon_state
        type(ucon_check_options_type) :: compare
    end type user_check_options_type

    !> Findings of one kind (same UCON, rule, output and entry), with the worst of them
    type :: finding_group_type
        !> The rule (rollcon_check_rules): rule_declaration, rule_errmes, rule_finite, a rule
        !> of check_ucon_state (rule_derivative, ...), or how an isolated check ended
        !> (rule_signal, rule_timeout, rule_exit)
        integer :: code = 0
        !> The rule's name, rule_name(code), for messages
        character(len=:), allocatable :: rule
        !> Which output ("ARRAY (dF/dq)", ...), or "UCOVAR"
        character(len=:), allocatable :: output
        !> Entry in the numbering of the declared variables (0 when not applicable)
        integer :: row = 0, column = 0
        !> In how many states it was found (1 for a declaration finding)
        integer :: count = 0
        !> The states it was found in
        integer, allocatable :: states(:)
        !> The worst case: largest |returned - expected|
        real(wp) :: expected = 0.0_wp, returned = 0.0_wp
        !> State of the worst case (its number, time [s] and values; 0 for the declaration)
        integer :: state = 0
        real(wp) :: time = 0.0_wp
        real(wp), allocatable :: q(:)
        !> What the routine or the checker said, for declaration, errmes and finite findings
        character(len=:), allocatable :: message
    end type finding_group_type

    !> What was found for one UCON
    type :: ucon_report_type
        integer :: id = 0
        !> The request's statement, when it has one (the report's heading of the UCON)
        character(len=:), allocatable :: statement
        real(wp), allocatable :: par(:)
        !> True when the initialisation call declared its variables without a mistake
        logical :: declared = .false.
        !> Declared part ids and codes, in UCOVAR order
        integer, allocatable :: parts(:), codes(:)
        !> States checked and entries compared
        integer :: states = 0, compared = 0
        !> Compared entries whose differences' own error was too large to judge them
        !> (rollcon_partials_check's compare): not checkable at those states
        integer :: not_checkable = 0
        !> Largest relative deviation among the compared entries
        real(wp) :: worst = 0.0_wp
        type(finding_group_type), allocatable :: groups(:)
    end type ucon_report_type

    !> What was found for every UCON
    type :: user_check_report_type
        type(ucon_report_type), allocatable :: ucons(:)
        type(user_check_options_type) :: options
    contains
        !> True when nothing was found
        procedure :: clean => report_clean
        !> Number of findings over all groups
        procedure :: findings => report_findings
    end type user_check_report_type

contains

    !> Declare and check every requested UCON of ucosub, in this process, its outputs guarded
    !> (rollcon_ucosub_guard). Mistakes of the routine are findings in the report; the error is
    !> only for a request that cannot be checked. A routine that may crash or hang is checked
    !> with check_user_ucosub_isolated (rollcon_isolated_audit) instead.
    subroutine check_user_ucosub(ucosub, requests, options, report, error)
        !> The routine under test
        procedure(ucosub_interface) :: ucosub
        !> UCON statements to check (distinct ids)
        type(ucon_request_type), intent(in) :: requests(:)
        !> States, seed, tolerance
        type(user_check_options_type), intent(in) :: options
        !> Findings
        type(user_check_report_type), intent(out) :: report
        !> Set when there is nothing to check, ids repeat, PAR is too long or states < 1
        type(error_type), allocatable, intent(out) :: error
        type(ucovar_registry_type), target :: registry
        integer :: k

        call check_requests(requests, options, error)
        if (allocated(error)) return
        report%options = options
        allocate(report%ucons(size(requests)))
        call install_guard(ucosub, as_errors=.false.)
        do k = 1, size(requests)
            report%ucons(k)%id = requests(k)%id
            report%ucons(k)%par = requests(k)%par
            if (allocated(requests(k)%statement)) report%ucons(k)%statement = &
                & requests(k)%statement
            allocate(report%ucons(k)%groups(0))
            call note_stage(0)
            call declare(guarded_ucosub, requests(k), registry, report%ucons(k))
            call record_violations(report%ucons(k), 0, 0.0_wp, [real(wp) ::])
            if (report%ucons(k)%declared) call sample(guarded_ucosub, options, &
                & requests(k)%units, report%ucons(k))
        end do
    end subroutine check_user_ucosub

    !> Check that requests can be checked: at least one, distinct ids, PAR not too long.
    subroutine check_requests(requests, options, error)
        !> UCON statements to check
        type(ucon_request_type), intent(in) :: requests(:)
        !> States, seed, tolerance
        type(user_check_options_type), intent(in) :: options
        !> Set when there is nothing to check, ids repeat, PAR is too long or states < 1
        type(error_type), allocatable, intent(out) :: error
        integer :: k

        if (size(requests) == 0) then
            call fatal_error(error, "no UCON to check; give one or more --ucon ID:PAR1,PAR2,...", &
                & stat_input)
            return
        end if
        if (options%states < 1) then
            call fatal_error(error, "the number of states must be at least 1, got " &
                & // to_text(options%states), stat_input)
            return
        end if
        if (options%states > max_check_states) then
            call fatal_error(error, states_refusal(options%states), stat_input)
            return
        end if
        do k = 1, size(requests)
            if (size(requests(k)%par) > max_ucon_par) then
                call fatal_error(error, "UCON/" // to_text(requests(k)%id) // ": " &
                    & // to_text(size(requests(k)%par)) // " PAR entries; at most " &
                    & // to_text(max_ucon_par), stat_input)
                return
            end if
            if (any(requests(:k - 1)%id == requests(k)%id)) then
                call fatal_error(error, "UCON/" // to_text(requests(k)%id) // " is given twice; " &
                    & // "each UCON id once", stat_input)
                return
            end if
        end do
    end subroutine check_requests

    !> Why a number of states beyond max_check_states is refused.
    pure function states_refusal(states) result(message)
        !> The number asked for
        integer, intent(in) :: states
        character(len=:), allocatable :: message

        message = to_text(states) // " states per UCON asked for; at most " &
            & // to_text(max_check_states) // " (each state costs some 60 calls of the " &
            & // "routine: more would run for hours, and a mistake shows in the first " &
            & // "few states)"
    end function states_refusal

    !> The initialisation call: record what was declared, or the mistake; a part id that no
    !> PAR entry mentions is a finding too (UCON statements name their parts in PAR).
    subroutine declare(ucosub, request, registry, ucon)
        procedure(ucosub_interface) :: ucosub
        type(ucon_request_type), intent(in) :: request
        type(ucovar_registry_type), target, intent(inout) :: registry
        type(ucon_report_type), intent(inout) :: ucon
        type(error_type), allocatable :: error
        type(finding_group_type) :: group
        integer :: i, entry

        call take_ucon_error(error)
        call declare_ucon(ucosub, request%id, request%par, registry, error)
        if (allocated(error)) then
            group = finding(rule_declaration, "UCOVAR", error%message)
            ucon%groups = [ucon%groups, group]
            return
        end if
        entry = registry%find(request%id)
        ucon%declared = .true.
        ucon%parts = registry%entries(entry)%parts
        ucon%codes = registry%entries(entry)%codes
        call declare_guarded_count(request%id, size(ucon%codes))
        do i = 1, size(ucon%parts)
            if (any(ucon%parts(:i - 1) == ucon%parts(i))) cycle
            if (any(request%par == real(ucon%parts(i), wp))) cycle
            group = finding(rule_declaration, "UCOVAR", "UCON/" // to_text(request%id) &
                & // ": UCOVAR declares part id " // to_text(ucon%parts(i)) // " (variable " &
                & // to_text(i) // "), which no PAR entry mentions; take part ids from PAR")
            group%row = i
            ucon%groups = [ucon%groups, group]
        end do
    end subroutine declare

    !> check_ucon_state on options%states random states, findings grouped.
    subroutine sample(ucosub, options, units, ucon)
        procedure(ucosub_interface) :: ucosub
        type(user_check_options_type), intent(in) :: options
        !> The units the routine computes in
        type(ucosub_units_type), intent(in) :: units
        type(ucon_report_type), intent(inout) :: ucon
        type(ucon_check_result_type) :: result
        type(error_type), allocatable :: error
        type(finding_group_type) :: group
        real(wp), allocatable :: q(:)
        real(wp) :: time
        integer(int64) :: random
        integer :: s, m

        random = seed_state(options%seed, ucon%id)
        allocate(q(size(ucon%codes)))
        do s = 1, options%states
            call draw_state(random, ucon%codes, q, time)
            if (.not. units%is_si()) then
                q = variable_scales(units, ucon%codes)*q
                time = time/units%time
            end if
            call note_stage(s)
            result = ucon_check_result_type()
            call check_ucon_state(ucosub, ucon%id, ucon%par, ucon%codes, time, q, &
                & options%compare, result, error)
            ucon%states = ucon%states + 1
            ucon%compared = ucon%compared + result%compared
            ucon%not_checkable = ucon%not_checkable + result%not_checkable
            ucon%worst = max(ucon%worst, result%worst)
            call record_violations(ucon, s, time, q)
            if (allocated(error)) then
                ! evaluate_ucon reports ERRMES calls and non-finite outputs this way.
                if (error%stat == stat_non_finite) then
                    group = finding(rule_finite, "all outputs", error%message)
                else
                    group = finding(rule_errmes, "ERRMES", error%message)
                end if
                call take_ucon_error(error)
                call record(ucon, group, s, time, q)
            end if
            if (.not. allocated(result%mismatches)) cycle
            do m = 1, size(result%mismatches)
                associate (mismatch => result%mismatches(m))
                    group = finding(mismatch%code, mismatch%output)
                    group%row = mismatch%row
                    group%column = mismatch%column
                    group%expected = mismatch%expected
                    group%returned = mismatch%returned
                end associate
                call record(ucon, group, s, time, q)
            end do
        end do
    end subroutine sample

    !> Add one finding at state s to its group (a new group if none matches); keep the worst.
    subroutine record(ucon, found, s, time, q)
        type(ucon_report_type), intent(inout) :: ucon
        type(finding_group_type), intent(in) :: found
        integer, intent(in) :: s
        real(wp), intent(in) :: time, q(:)
        integer :: g
        logical :: worse

        do g = 1, size(ucon%groups)
            associate (group => ucon%groups(g))
                if (group%code /= found%code .or. group%output /= found%output &
                    & .or. group%row /= found%row .or. group%column /= found%column) cycle
                ! Counted once per state: a rule may report the same entry twice in one state.
                if (.not. any(group%states == s)) then
                    group%count = group%count + 1
                    group%states = [group%states, s]
                end if
                worse = .not. (abs(found%returned - found%expected) &
                    & <= abs(group%returned - group%expected))
                if (worse) call set_worst(group, found, s, time, q)
                return
            end associate
        end do
        ucon%groups = [ucon%groups, found]
        associate (group => ucon%groups(size(ucon%groups)))
            group%count = 1
            group%states = [s]
            call set_worst(group, found, s, time, q)
        end associate
    end subroutine record

    subroutine set_worst(group, found, s, time, q)
        type(finding_group_type), intent(inout) :: group
        type(finding_group_type), intent(in) :: found
        integer, intent(in) :: s
        real(wp), intent(in) :: time, q(:)

        group%expected = found%expected
        group%returned = found%returned
        if (allocated(found%message)) group%message = found%message
        group%state = s
        group%time = time
        group%q = q
    end subroutine set_worst

    !> The guard's violations since the last look, as findings at state s: outside-block for a
    !> write outside the block, changed-argument for a change of an argument to be read only.
    subroutine record_violations(ucon, s, time, q)
        type(ucon_report_type), intent(inout) :: ucon
        integer, intent(in) :: s
        real(wp), intent(in) :: time, q(:)
        type(guard_violation_type), allocatable :: found(:)
        type(finding_group_type) :: group
        integer :: v, code

        call take_guard_violations(found)
        do v = 1, size(found)
            code = rule_outside_block
            if (found(v)%kind == violation_argument) code = rule_changed_argument
            group = finding(code, trim(found(v)%output), "UCON/" // to_text(ucon%id) // ": " &
                & // violation_text(found(v)))
            group%row = found(v)%row
            group%column = found(v)%column
            group%returned = found(v)%value
            if (code == rule_changed_argument) group%expected = found(v)%before
            call record(ucon, group, s, time, q)
        end do
    end subroutine record_violations

    !> A finding of rule (a code of rollcon_check_rules) on output, counted once, with an
    !> optional message.
    pure function finding(code, output, message) result(group)
        !> Rule code
        integer, intent(in) :: code
        !> Which output
        character(len=*), intent(in) :: output
        !> What the routine or the checker said
        character(len=*), intent(in), optional :: message
        type(finding_group_type) :: group

        group%code = code
        group%rule = rule_name(code)
        group%output = output
        group%count = 1
        ! no state yet (record adds the states it is found in); defined, so it can be sent
        allocate(group%states(0))
        if (present(message)) group%message = message
    end function finding

    pure function report_clean(self) result(clean)
        class(user_check_report_type), intent(in) :: self
        logical :: clean

        clean = self%findings() == 0
    end function report_clean

    pure function report_findings(self) result(count)
        class(user_check_report_type), intent(in) :: self
        integer :: count
        integer :: k

        count = 0
        if (.not. allocated(self%ucons)) return
        do k = 1, size(self%ucons)
            count = count + sum(self%ucons(k)%groups%count)
        end do
    end function report_findings

end module rollcon_ucosub_audit
