! SPDX-License-Identifier: MIT
!> A model as a run integrates it, whatever the formulation: the model (held here, once), its
!> equations, the run settings, the watches of the run, the accelerations and multipliers of
!> the last evaluation, and the first failure a callback met (callbacks never print or stop);
!> with what the three formulations share: the watches' event functions, each coordinate's
!> block, why an evaluation is not finite. The formulations themselves, each a dynamic system
!> an integrator takes (rollcon_dynamic_system), hold a pointer to the problem and their own
!> state: the ODE form (rollcon_ode_form), the DAE form (rollcon_dae_form) and the independent
!> speeds (rollcon_speeds_form), one of them chosen by the settings where the run starts its
!> integrator (rollcon_formulation_choice; docs/design.md §4).
module rollcon_problem
    use rollcon_kinds, only : wp
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_error, only : error_type, fatal_error, stat_ucon, stat_input
    use rollcon_text, only : to_text
    use rollcon_force, only : nonfinite_load, runaway_load, runaway_limit
    use rollcon_output_layout, only : coordinate_names
    use rollcon_model, only : model_type, served_by_model_ucosub, statement_ucon
    use rollcon_equations, only : equations_type
    use rollcon_sliding_contact, only : sliding_contact_type
    use rollcon_user_forces, only : set_system_accelerations
    use rollcon_run_settings, only : run_settings_type, drift_projection
    use rollcon_watch, only : watch_type, watch_slot_type, append_watch
    use rollcon_redundancy_watch, only : redundancy_watch_type
    use rollcon_reaction_watch, only : reaction_watch_type
    use rollcon_output_layout, only : name_length
    use rollcon_dynamic_system, only : dynamic_system_type
    implicit none
    private

    public :: problem_type

    type :: problem_type
        !> The model, set up: the one copy
        type(model_type) :: model
        !> Its equations (pointing at `model`)
        type(equations_type) :: eq
        type(run_settings_type) :: settings
        !> What the run watches besides parts, UCONs and forces, in order: their event
        !> functions and their columns follow one another in this order
        type(watch_slot_type), allocatable :: watches(:)
        !> The number of columns each watch adds (set by prepare)
        integer, allocatable :: watch_columns(:)
        !> Accelerations and multipliers of the last evaluation (accelerations, or a
        !> formulation's right-hand side)
        real(wp), allocatable :: a(:), lambda(:)
        !> The first failure inside a callback, for the caller to report
        type(error_type), allocatable :: failure
        !> For each part (model order), the basis its start and the model's part are given in
        !> (docs/rebasing.md; its number, rollcon_rebasing's basis_axes): 0, its own axes,
        !> unless the part starts where those are singular (a dataset's part flat at t = 0: 1
        !> or 20). A run counts the turns that reach it (turns_from_own) as re-basings before
        !> its first row. Set by init to 0
        integer, allocatable :: start_bases(:)
        !> The turn of every re-basing during a run: 0, the one rollcon_rebasing's chosen_turn
        !> picks at the part's state (docs/rebasing.md); turn_about_x or turn_about_y, that
        !> one at every re-basing (to measure what a re-basing costs where the choice would
        !> avoid it)
        integer :: rebase_turn = 0
        !> The rows the choice at the start set aside (choose_rows), in the user's words:
        !> "JOINT/3 (line 40): its rotation about J's x and rotation about J's y repeat JOINT/1
        !> (line 37), JOINT/2 (line 38) and JOINT/4 (line 39); set aside" ("" when none)
        character(len=:), allocatable :: set_aside_text
        !> The coordinates and rates the dissipated powers are evaluated at (state_powers;
        !> n each, sized by prepare): no evaluation of them allocates
        real(wp), allocatable :: power_q(:), power_u(:)
    contains
        procedure :: init
        procedure :: add_watch
        procedure :: prepare
        procedure :: accelerations
        procedure :: diff_rates
        procedure :: choose_rows
        procedure :: routines_text
        procedure :: ucon_labels
        procedure :: ucon_count
        procedure :: ucon_id
        procedure :: constraint_values
        procedure :: projection_asked
        procedure :: coordinate_blocks
        procedure :: root_count
        procedure :: root_values
        procedure :: root_owner
        procedure :: roots_use_accelerations
        procedure :: nonfinite_state
        procedure :: runaway_text
        procedure :: keep_failure
        procedure :: failure_text
        procedure :: constraint_power
        procedure :: dissipated_power
        procedure :: dissipates
        procedure :: powers_at
        procedure :: power_count
        procedure :: state_powers
        procedure :: release => release_problem
    end type problem_type

contains

    !> Keep a model that setup_model has prepared (the problem's copy is the only one the
    !> run uses: the equations refer to it) and set up its equations on it; no watches yet, every
    !> part's start in its own axes.
    subroutine init(self, model)
        class(problem_type), intent(inout), target :: self
        type(model_type), intent(in) :: model

        self%model = model
        call self%eq%init(self%model)
        if (allocated(self%watches)) deallocate(self%watches)
        allocate(self%watches(0))
        if (allocated(self%start_bases)) deallocate(self%start_bases)
        if (allocated(self%model%parts)) then
            allocate(self%start_bases(size(self%model%parts)), source=0)
        else
            allocate(self%start_bases(0))
        end if
    end subroutine init

    !> Watch this too (after the watches added before it).
    subroutine add_watch(self, watch)
        class(problem_type), intent(inout) :: self
        class(watch_type), intent(in) :: watch

        call append_watch(self%watches, watch)
    end subroutine add_watch

    !> Before a run: size the accelerations and multipliers, forget an earlier failure, add the
    !> watches every run has after those added before (once: the redundant rows' choice again,
    !> rollcon_redundancy_watch, which has no event function unless rows are set aside; and
    !> when the model reports reactions, rollcon_reaction_watch's columns), prepare every
    !> watch (it may refuse the model).
    subroutine prepare(self, error)
        class(problem_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        character(len=name_length), allocatable :: names(:)
        integer :: k

        if (allocated(self%a)) deallocate(self%a)
        if (allocated(self%lambda)) deallocate(self%lambda)
        allocate(self%a(self%eq%n), self%lambda(self%eq%nc), source=0.0_wp)
        if (allocated(self%power_q)) deallocate(self%power_q, self%power_u)
        allocate(self%power_q(self%eq%n), self%power_u(self%eq%n), source=0.0_wp)
        if (allocated(self%failure)) deallocate(self%failure)
        if (.not. allocated(self%watches)) allocate(self%watches(0))
        call add_own_watches(self)
        if (allocated(self%watch_columns)) deallocate(self%watch_columns)
        allocate(self%watch_columns(size(self%watches)))
        do k = 1, size(self%watches)
            call self%watches(k)%watch%prepare(self%eq, self%settings, error)
            if (allocated(error)) return
            call self%watches(k)%watch%column_names(self%eq, names)
            self%watch_columns(k) = size(names)
        end do
    end subroutine prepare

    !> The watches every run has (prepare), unless added already.
    subroutine add_own_watches(self)
        type(problem_type), intent(inout) :: self
        type(redundancy_watch_type) :: redundancy
        type(reaction_watch_type) :: reactions
        logical :: have_redundancy, have_reactions
        integer :: k

        have_redundancy = .false.
        have_reactions = .false.
        do k = 1, size(self%watches)
            select type (watch => self%watches(k)%watch)
            type is (redundancy_watch_type)
                have_redundancy = .true.
            type is (reaction_watch_type)
                have_reactions = .true.
            end select
        end do
        if (.not. have_redundancy) call self%add_watch(redundancy)
        if (.not. have_reactions .and. self%model%report_reactions .and. self%eq%nc > 0) &
            & call self%add_watch(reactions)
    end subroutine add_own_watches

    !> Accelerations and multipliers at (t, q, u) into self%a and self%lambda, with the
    !> settings' drift control. Where a DIFSUB reads accelerations or a constraint's
    !> reaction, the DIFFs' rates are solved again with the accelerations found (set for the
    !> utilities, rollcon_user_forces' set_system_accelerations) and the multipliers (the
    !> equations set them for the force measures): a force reading such a DIFF's DIF1 reads
    !> its rate at the accelerations last found.
    subroutine accelerations(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        call self%diff_rates(time, q, u, error)
        if (allocated(error)) return
        call self%eq%accelerations(time, q, u, self%settings%baumgarte(), self%a, self%lambda, &
            & error)
        if (allocated(error)) return
        if (self%model%diffs%count() == 0) return
        if (self%model%diffs%reads_accelerations()) then
            call set_system_accelerations(self%a)
        else if (.not. self%model%diffs%reads_constraint_forces()) then
            return
        end if
        call self%diff_rates(time, q, u, error)
    end subroutine accelerations

    !> The DIFFs' rates DIF1 at (t, q, u) and their state DIF last set (rollcon_diff's
    !> solve_rates, from the rates last found), set in the model for the forces that read
    !> them (rollcon_model's set_diff_state). Nothing without DIFFs.
    subroutine diff_rates(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: w(:)

        if (self%model%diffs%count() == 0) return
        w = self%model%diffs%w
        call self%model%diffs%solve_rates(time, q, u, self%model%diffs%x, w, error)
        if (allocated(error)) return
        call self%model%set_diff_state(self%model%diffs%x, w)
    end subroutine diff_rates

    !> Choose the rows to set aside as redundant at the start (t, q, u) (rollcon_redundancy,
    !> through the equations' choose_active) and say which in the user's words
    !> (set_aside_text). Refused (stat_input) as contradictory: a row set aside that is not met
    !> there, |F| (and, for a position UCON, |dF/dt|) above atol + rtol s, s the size of F's
    !> terms: it repeats the others' normals but asks for another value.
    subroutine choose_rows(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        self%set_aside_text = ""
        call self%eq%choose_active(time, q, u, error)
        if (allocated(error)) return
        if (self%eq%redundancy%set_aside == 0) return
        call check_set_aside(self, q, u, error)
        if (allocated(error)) return
        self%set_aside_text = self%eq%redundancy%words
    end subroutine choose_rows

    !> Every row set aside met at (q, u), as choose_rows says; the constraints evaluated there.
    subroutine check_set_aside(self, q, u, error)
        type(problem_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: position, rate, allowed_position, allowed_rate
        integer :: k

        associate (cs => self%eq%constraints, atol => self%settings%atol, &
                & rtol => self%settings%rtol)
            do k = 1, self%eq%nc
                if (self%eq%redundancy%active(k)) cycle
                if (self%model%ucons(k)%holonomic) then
                    position = cs%value(k)
                    allowed_position = atol + rtol*(abs_terms(cs%grad_q_local(:, k), q) &
                        & + abs(position - cs%grad_q_dot(k, q)))
                    rate = cs%grad_q_dot(k, u) + cs%dt(k)
                    allowed_rate = atol + rtol*(abs_terms(cs%grad_q_local(:, k), u) &
                        & + abs(cs%dt(k)))
                else
                    position = 0.0_wp
                    allowed_position = 1.0_wp
                    rate = cs%value(k)
                    allowed_rate = atol + rtol*(abs_terms(cs%grad_u_local(:, k), u) &
                        & + abs(rate - cs%grad_u_dot(k, u)))
                end if
                if (abs(position) <= allowed_position .and. abs(rate) <= allowed_rate) cycle
                call fatal_error(error, self%model%row_words(k) // " repeats the other " &
                    & // "constraints' equations (its row depends on theirs) but is not met " &
                    & // "where they are: |F| = " // to_text(abs(merge(position, rate, &
                    & abs(position) > allowed_position))) // " (allowed " &
                    & // to_text(merge(allowed_position, allowed_rate, abs(position) &
                    & > allowed_position)) // "): the constraints are contradictory", &
                    & stat_input)
                return
            end do
        end associate
    contains
        !> sum_a |row(a) v(i)|, i = local(a, k), over UCON k's own coordinates: the dense row's
        !> sum(abs(row v)) without its zero terms, in its order
        pure real(wp) function abs_terms(row, v) result(total)
            real(wp), intent(in) :: row(:), v(:)
            integer :: a

            total = 0.0_wp
            associate (cs => self%eq%constraints)
                do a = 1, cs%local_count(k)
                    total = total + abs(row(a)*v(cs%local(a, k)))
                end do
            end associate
        end function abs_terms
    end subroutine check_set_aside

    !> Which routine serves each statement, in words: "UCON 1: the model's UCOSUB, UCON 4:
    !> disk_height, JOINT/1: gnd_atpoint, gnd_parallel_axes" (a JOINT's or JPRIM's routines
    !> each once).
    function routines_text(self) result(text)
        class(problem_type), intent(in) :: self
        character(len=:), allocatable :: text, routine, listed
        integer :: s, k

        text = ""
        if (.not. allocated(self%model%statements)) return
        do s = 1, size(self%model%statements)
            listed = ""
            do k = 1, self%eq%nc
                associate (ucon => self%model%ucons(k))
                    if (ucon%statement /= s) cycle
                    if (served_by_model_ucosub(ucon%routine)) then
                        routine = "the model's UCOSUB"
                    else
                        routine = ucon%routine
                    end if
                    if (index(", " // listed // ",", ", " // routine // ",") > 0) cycle
                    if (len(listed) > 0) listed = listed // ", "
                    listed = listed // routine
                end associate
            end do
            if (len(listed) == 0) cycle
            if (len(text) > 0) text = text // ", "
            text = text // statement_label(self%model, s) // ": " // listed
        end do
    end function routines_text

    !> "UCON 3" of a UCON statement of a model without lines (a scene, a model built in code:
    !> the summary's words), else its statement and line: "UCON/3 (line 16)", "JOINT/1 (line
    !> 14)".
    pure function statement_label(model, s) result(label)
        type(model_type), intent(in) :: model
        integer, intent(in) :: s
        character(len=:), allocatable :: label

        if (model%statements(s)%kind == statement_ucon .and. model%statements(s)%line == 0) then
            label = "UCON " // to_text(model%statements(s)%id)
        else
            label = model%statement_name(s)
        end if
    end function statement_label

    !> Each UCON in the summary's words, one line each: "UCON 3" of a UCON statement without a
    !> line, "UCON/3 (line 16)" of a dataset's, "JOINT/1 (line 14), its translation along ground
    !> X" of a JOINT's or JPRIM's equation.
    function ucon_labels(self) result(text)
        class(problem_type), intent(in) :: self
        character(len=:), allocatable :: text
        integer :: k

        text = ""
        do k = 1, self%eq%nc
            associate (ucon => self%model%ucons(k))
                if (self%model%statements(ucon%statement)%kind == statement_ucon .and. &
                    & self%model%statements(ucon%statement)%line == 0) then
                    text = text // "UCON " // to_text(ucon%id) // new_line("a")
                else
                    text = text // self%model%row_words(k) // new_line("a")
                end if
            end associate
        end do
    end function ucon_labels

    !> Number of UCONs.
    pure integer function ucon_count(self)
        class(problem_type), intent(in) :: self

        ucon_count = self%eq%nc
    end function ucon_count

    !> Identifier of the k-th UCON (as in its UCON statement).
    pure integer function ucon_id(self, k)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: k

        ucon_id = self%model%ucons(k)%id
    end function ucon_id

    !> Each UCON's residual F_k at the last evaluation; zero for the rows a sliding or flying
    !> contact has dropped (their F is the slip velocity, or the contact point's velocity in
    !> flight, not a residual: rollcon_sliding_contact).
    pure function constraint_values(self) result(values)
        class(problem_type), intent(in) :: self
        real(wp) :: values(self%eq%nc)
        integer :: k

        values = self%eq%constraints%value
        do k = 1, self%eq%nc
            if (self%eq%mode_drops(k)) values(k) = 0.0_wp
        end do
    end function constraint_values

    !> The settings ask for the projection onto the constraints (drift 'projection') and there
    !> are UCONs to project onto (the ODE forms' projects).
    pure logical function projection_asked(self)
        class(problem_type), intent(in) :: self

        projection_asked = self%settings%drift == drift_projection .and. self%eq%nc > 0
    end function projection_asked

    !> Each coordinate's block (rollcon_constraint_blocks): the block of its UCONs, or its
    !> part's own past the blocks for a part that no UCON holds; the blocks of two parts a
    !> SPRINGDAMPER or BUSHING joins are one. A formulation's states are of their
    !> coordinate's block, or of their UCON's (its state_blocks).
    pure function coordinate_blocks(self) result(blocks)
        class(problem_type), intent(in) :: self
        integer :: blocks(self%eq%n)
        integer :: b, j, k, first, second

        associate (bl => self%eq%blocks)
            do j = 1, self%eq%n
                blocks(j) = bl%count + (j - 1)/6 + 1
            end do
            do b = 1, bl%count
                blocks(bl%coordinates(bl%coordinate_start(b):bl%coordinate_start(b + 1) - 1)) = b
            end do
        end associate
        ! the parts a SPRINGDAMPER or BUSHING joins share a block (the union of theirs): its
        ! partials couple their states (rollcon_equations' couplings)
        if (.not. allocated(self%eq%couplings)) return
        do k = 1, size(self%eq%couplings, 2)
            first = blocks(6*self%eq%couplings(1, k))
            second = blocks(6*self%eq%couplings(2, k))
            if (first /= second) where (blocks == second) blocks = first
        end do
    end function coordinate_blocks

    !> Number of event functions: every watch's, in watch order.
    integer function root_count(self)
        class(problem_type), intent(in) :: self
        integer :: k

        root_count = 0
        if (.not. allocated(self%watches)) return
        do k = 1, size(self%watches)
            root_count = root_count + self%watches(k)%watch%root_count(self%eq)
        end do
    end function root_count

    !> Every watch's event functions at (t, q, u), root_count() of them; lambda or a when the
    !> integrator knows them (rollcon_watch).
    function root_values(self, time, q, u, g, lambda, a) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        real(wp), intent(in), optional :: lambda(:), a(:)
        integer :: ierr
        type(error_type), allocatable :: error
        integer :: k, first, count

        ierr = 0
        first = 1
        do k = 1, size(self%watches)
            count = self%watches(k)%watch%root_count(self%eq)
            if (count == 0) cycle
            call self%watches(k)%watch%roots(self%eq, self%settings, time, q, u, &
                & g(first:first + count - 1), error, lambda, a)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            first = first + count
        end do
    end function root_values

    !> The watch whose event function `root` is (in root_values' order), and its own number
    !> there.
    pure subroutine root_owner(self, root, watch, k)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: root
        integer, intent(out) :: watch, k
        integer :: count

        k = root
        do watch = 1, size(self%watches)
            count = self%watches(watch)%watch%root_count(self%eq)
            if (k <= count) return
            k = k - count
        end do
        watch = 0
    end subroutine root_owner

    !> A watch's event functions use the accelerations when the integrator knows them (the
    !> ODE form's y', rollcon_watch).
    logical function roots_use_accelerations(self)
        class(problem_type), intent(in) :: self
        integer :: k

        roots_use_accelerations = .false.
        if (.not. allocated(self%watches)) return
        do k = 1, size(self%watches)
            if (self%watches(k)%watch%roots_use_accelerations(self%eq)) &
                & roots_use_accelerations = .true.
        end do
    end function roots_use_accelerations

    !> Why the equations or a row are not finite at (t, q, u), in words: a coordinate or rate
    !> that is not finite, a force statement's load that is not finite (named, with its
    !> expression), a UCON's value, a load that has run away (finite but beyond
    !> runaway_limit: its square, a power or the energy, overflows), a rate beyond it, or else
    !> the accelerations themselves.
    subroutine nonfinite_state(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: message
        integer :: k

        message = ""
        k = findloc(ieee_is_finite(q) .and. ieee_is_finite(u), .false., dim=1)
        if (k > 0) message = "part " // to_text(self%model%parts((k - 1)/6 + 1)%id) // "'s " &
            & // trim(merge(coordinate_names(mod(k - 1, 6) + 1), &
            & coordinate_names(mod(k - 1, 6) + 7), .not. ieee_is_finite(q(k)))) &
            & // " is not finite at t = " // to_text(time) // " s"
        if (len(message) == 0) message = nonfinite_load(self%model%forces, &
            & size(self%model%parts), time, q, u)
        if (len(message) == 0 .and. self%eq%nc > 0) then
            k = findloc(ieee_is_finite(self%eq%constraints%value), .false., dim=1)
            if (k > 0) message = self%model%row_words(k) // ": F is not " &
                & // "finite at t = " // to_text(time) // " s"
        end if
        if (len(message) == 0) message = self%runaway_text(time, q, u)
        if (len(message) == 0) message = "the accelerations are not finite at t = " &
            & // to_text(time) // " s (a singular mass matrix or constraint matrix?)"
        call fatal_error(error, message, stat_ucon)
    end subroutine nonfinite_state

    !> A load or a rate that has run away at (t, q, u), in words: the force statement whose
    !> component exceeds runaway_limit (its square, a power or the energy, overflows; with
    !> weight_times, also one that exceeds weight_times the parts' weight, the model's own force
    !> scale: the cause of an integrator's failure), else the part whose rate exceeds
    !> runaway_limit ("part 2's Xdot = 3.1E+157 m/s at t = ...: the motion has run away");
    !> "" when none does (rollcon_force runaway_load).
    function runaway_text(self, time, q, u, weight_times) result(text)
        class(problem_type), intent(in) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Loads beyond this many times the parts' weight have run away too [-]
        real(wp), intent(in), optional :: weight_times
        character(len=:), allocatable :: text
        real(wp) :: weight
        character(len=16) :: times, weight_text
        integer :: k

        weight = 0.0_wp
        if (present(weight_times)) weight = weight_times*sum(self%model%parts%mass) &
            & *norm2(self%model%gravity)
        if (weight > 0.0_wp .and. weight < runaway_limit) then
            write(times, '(es8.1)') weight_times
            write(weight_text, '(es10.3)') weight/weight_times
            text = runaway_load(self%model%forces, time, q, u, weight, "beyond " &
                & // trim(adjustl(times)) // " times the parts' weight, " &
                & // trim(adjustl(weight_text)) // " N")
        else
            text = runaway_load(self%model%forces, time, q, u, runaway_limit, "beyond 1.3e154, " &
                & // "whose square overflows")
        end if
        if (len(text) > 0) return
        k = findloc(abs(u) > runaway_limit, .true., dim=1)
        if (k == 0) return
        text = "part " // to_text(self%model%parts((k - 1)/6 + 1)%id) // "'s " &
            & // trim(coordinate_names(mod(k - 1, 6) + 7)) // " = " // to_text(u(k)) &
            & // " at t = " // to_text(time) // " s: the motion has run away (beyond 1.3e154)"
    end function runaway_text

    !> Keep the first failure; return the callback code (0 ok, -1 unrecoverable).
    function keep_failure(self, error) result(ierr)
        class(problem_type), intent(inout) :: self
        type(error_type), allocatable, intent(inout) :: error
        integer :: ierr

        ierr = 0
        if (.not. allocated(error)) return
        ierr = -1
        if (.not. allocated(self%failure)) call move_alloc(error, self%failure)
    end function keep_failure

    !> The first failure a callback kept ("" when none).
    function failure_text(self) result(text)
        class(problem_type), intent(in) :: self
        character(len=:), allocatable :: text

        text = ""
        if (allocated(self%failure)) text = self%failure%message
    end function failure_text

    !> The explicit power of the constraint forces at the last evaluation (accelerations), at
    !> the run's own state: sum over the UCONs of |lambda_k w_k| [W], w_k the part of F_k's
    !> rate that the motion does not make: dF_k/dt for a position UCON (its forces' power is
    !> -lambda_k dF_k/dq u = lambda_k dF_k/dt on the constraint), and F_k - dF_k/du u for a
    !> velocity UCON (F linear in u, F = C u + c: the forces' power lambda_k C u is -lambda_k c).
    !> Zero, up to rounding, for constraints fixed in space and time (a rolling contact on
    !> fixed ground: F = C(q) u, c = 0; a joint: no explicit time); a moving constraint's (a
    !> turntable, a driven motion) is of the size of the power it puts in. A sliding contact's
    !> friction is no constraint force: the power it dissipates, mu_k F_n |v_s| with v_s the
    !> slip relative to the plane, is dissipated_power's; on a moving plane (a turntable, whose
    !> tangential rows are F = C u + c, c minus the plane's velocity at the contact) the
    !> friction F_t also does the drive's work, its power on the part being F_t . C u =
    !> F_t . v_s - F_t . c: |F_t . c| is added (0 on the ground). Calls no UCOSUB.
    pure function constraint_power(self, u) result(power)
        class(problem_type), intent(in) :: self
        !> The rates of the last evaluation
        real(wp), intent(in) :: u(:)
        real(wp) :: power
        integer :: k

        power = 0.0_wp
        if (.not. allocated(self%lambda)) return
        associate (cs => self%eq%constraints)
            do k = 1, self%eq%nc
                if (self%model%ucons(k)%holonomic) then
                    power = power + abs(self%lambda(k)*cs%dt(k))
                else
                    power = power + abs(self%lambda(k)*(cs%value(k) &
                        & - cs%grad_u_dot(k, u)))
                end if
            end do
            if (self%eq%contact%sliding) power = power &
                & + abs(sliding_drive_power(self%eq, self%eq%contact, u))
            if (allocated(self%eq%more_contacts)) then
                do k = 1, size(self%eq%more_contacts)
                    if (self%eq%more_contacts(k)%sliding) power = power &
                        & + abs(sliding_drive_power(self%eq, self%eq%more_contacts(k), u))
                end do
            end if
        end associate
    end function constraint_power

    !> The power a sliding contact's friction takes from the motion of its plane at the last
    !> evaluation [W]: -F_t . c, c = F - C u of the two tangential rows (minus the plane's
    !> velocity at the contact; 0 on the ground, whose rows have none). contact: the
    !> equations' contact or one of their more_contacts.
    pure real(wp) function sliding_drive_power(eq, contact, u) result(power)
        type(equations_type), intent(in) :: eq
        type(sliding_contact_type), intent(in) :: contact
        !> The rates of the last evaluation
        real(wp), intent(in) :: u(:)
        integer :: j, k

        power = 0.0_wp
        do j = 1, 2
            k = contact%tangential(j)
            power = power - contact%friction(j)*(eq%constraints%value(k) &
                & - eq%constraints%grad_u_dot(k, u))
        end do
    end function sliding_drive_power

    !> The power dissipated at the last evaluation (accelerations) [W], each >= 0: a sliding
    !> contact's friction, mu_k F_n |v_slip| (rollcon_sliding_contact), and a rim's rolling
    !> resistance and air layer while the rim presses on the ground (rollcon_rim_dissipation);
    !> 0 without them. The energy judge adds their integral to the energy (rollcon_simulation).
    pure subroutine dissipated_power(self, friction, rim)
        class(problem_type), intent(in) :: self
        !> The friction's power and the rim's dissipation's [W]
        real(wp), intent(out) :: friction, rim

        friction = 0.0_wp
        friction = self%eq%friction_powers()
        rim = 0.0_wp
        if (self%eq%dissipation%active()) rim = self%eq%dissipation%power()
    end subroutine dissipated_power

    !> The model can dissipate: a contact with friction (it may slide) or a rim's dissipation.
    !> Its powers (powers_at) are then integrated with the state (rollcon_dynamic_system
    !> power_count).
    pure logical function dissipates(self)
        class(problem_type), intent(in) :: self

        dissipates = self%eq%contact%mu > 0.0_wp .or. self%eq%dissipation%active()
        if (allocated(self%eq%more_contacts)) dissipates = dissipates &
            & .or. any(self%eq%more_contacts%mu > 0.0_wp)
    end function dissipates

    !> The powers dissipated at (time [s], q, u), from an evaluation there (accelerations):
    !> values = (friction, rolling resistance, air layer) [W], each >= 0 (dissipated_power's
    !> parts). error: the evaluation's.
    subroutine powers_at(self, time, q, u, values, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Size 3
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: friction, rim

        values = 0.0_wp
        call self%accelerations(time, q, u, error)
        if (allocated(error)) return
        call self%dissipated_power(friction, rim)
        values(1) = friction
        if (rim /= 0.0_wp) values(2:3) = [self%eq%dissipation%rolling_power, &
            & self%eq%dissipation%air_power]
    end subroutine powers_at

    !> The number of powers a formulation of the problem integrates with its state
    !> (rollcon_dynamic_system's power_count): the three of powers_at when the problem can
    !> dissipate (dissipates), else none. The ODE, DAE and independent-speeds forms all answer
    !> with it.
    integer function power_count(self)
        class(problem_type), intent(in) :: self

        power_count = merge(3, 0, self%dissipates())
    end function power_count

    !> The powers dissipated at the state y of system, a formulation of this problem, at time
    !> [s] (rollcon_dynamic_system's powers): (q, u) read from y by the system's unpack_state
    !> into the problem's own arrays (sized by prepare: nothing is allocated), then powers_at
    !> [W], values of size 3. ierr 0, or -1 with the failure kept as the problem's
    !> (keep_failure). The ODE, DAE and independent-speeds forms all answer with it. self is a
    !> target: the system changes it through its pointer to the problem.
    integer function state_powers(self, system, time, y, values) result(ierr)
        class(problem_type), intent(inout), target :: self
        class(dynamic_system_type), intent(inout) :: system
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable :: error

        values = 0.0_wp
        if (.not. allocated(self%power_q)) then
            ! a problem evaluated without prepare: sized once, here
            allocate(self%power_q(self%eq%n), self%power_u(self%eq%n), source=0.0_wp)
        end if
        call system%unpack_state(time, y, self%power_q, self%power_u, error)
        if (.not. allocated(error)) call self%powers_at(time, self%power_q, self%power_u, &
            & values, error)
        ierr = self%keep_failure(error)
    end function state_powers

    !> Free what the problem holds outside Fortran's memory (its equations' KLU factors): a
    !> process running many models one after another (a study's cases) would keep every one's
    !> until it ends. (A formulation frees its own, release, when its run is done.)
    subroutine release_problem(self)
        class(problem_type), intent(inout) :: self

        call self%eq%release()
    end subroutine release_problem

end module rollcon_problem
