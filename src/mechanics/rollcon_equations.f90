! SPDX-License-Identifier: MIT
!> Equations of motion of a model: the ODE form (accelerations from the saddle-point system,
!> its Jacobian, velocity projection) shared by every formulation (docs/design.md §4).
!>
!> M(q) a = f(q, u, t) + C^T lambda,  C a = gamma, where C_k = dF_k/du for a velocity UCON and
!> dF_k/dq for a position UCON, and gamma makes the constraint's time derivative vanish.
!>
!> Rows that repeat others (redundant equations) are set aside by the choice of `redundancy`
!> (rollcon_redundancy, choose_active): they keep their place in every array, their
!> multiplier is zero, and every solve here goes over the active rows only.
module rollcon_equations
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_model, only : model_type
    use rollcon_body, only : body_mass_and_force, body_residual_jacobian, kinetic_energy, &
        & energy_gradient
    use rollcon_force, only : force_and_moment, add_force_partials, force_couplings, &
        & add_expression_partials, profile_statement
    use rollcon_user_force_partials, only : add_user_force_partials, &
        & add_user_force_acceleration_partials, add_variable_acceleration_partials, &
        & add_user_force_multiplier_partials, add_variable_multiplier_partials
    use rollcon_user_forces, only : evaluate_user_forces, take_user_force_error, &
        & evaluate_user_variables, difference_user_variables, clear_user_variable_partials, &
        & set_system_diff_state, set_system_accelerations, reads_accelerations, &
        & variables_read_accelerations, variables_reading_accelerations, &
        & difference_variable_accelerations, user_variable_list, user_variable_type, &
        & reads_constraint_forces, set_system_constraint_forces, &
        & variables_read_constraint_forces, difference_variable_multipliers
    use rollcon_force_measures, only : set_force_measure_model
    use rollcon_lapack, only : factor_dense, solve_factored
    use rollcon_constraints, only : constraint_state_type, local_dot, need_value, need_first, &
        & need_second, need_time
    use rollcon_ucosub_contract, only : max_ucon_vars
    use rollcon_saddle_point, only : saddle_point_type
    use rollcon_constraint_blocks, only : constraint_blocks_type
    use rollcon_constraint_matrix, only : constraint_matrix_type
    use rollcon_ode_workspace, only : ode_workspace_type
    use rollcon_redundancy, only : redundancy_type
    use rollcon_redundancy_words, only : set_aside_words
    use rollcon_sliding_contact, only : sliding_contact_type, painleve_margin
    use rollcon_rim_dissipation, only : rim_dissipation_type
    use rollcon_text, only : to_text
    implicit none
    private

    public :: equations_type

    !> The equations of a model held elsewhere, and what evaluating them fills (allocated once,
    !> in init; no evaluation allocates). The saddle-point factors live in `saddle`, the scratch
    !> arrays in `work`. Drift control is the solver's: the Baumgarte rate in effect comes in as
    !> an argument (0 without Baumgarte terms).
    type :: equations_type
        !> The model, set up, owned by the caller of init (a target that outlives these
        !> equations; never copied here)
        type(model_type), pointer :: model => null()
        !> Constraint values and partials at the last evaluation
        type(constraint_state_type) :: constraints
        !> Sizes: coordinates, constraints, holonomic constraints
        integer :: n = 0, nc = 0, nh = 0
        !> The system as last assembled: mass matrix, applied and inertial forces f, gamma. M is
        !> block diagonal, one 6 x 6 block per part (the part's coordinates): mass(:, :, p) is
        !> part p's block, the others are zeros, not stored (memory linear in the model,
        !> docs/design.md §4 "Memory")
        real(wp), allocatable :: mass(:, :, :), force(:), gamma(:)
        !> The constraint matrix C (nc x n), held by rows over each UCON's own coordinates
        !> (rollcon_constraint_matrix; the other entries are exact zeros, not stored): filled
        !> by constraint_matrix
        type(constraint_matrix_type) :: c
        !> The constraints' blocks (UCONs sharing parts), and the saddle-point system's factors,
        !> as the last accelerations call left them
        type(constraint_blocks_type) :: blocks
        type(saddle_point_type) :: saddle
        !> Scratch arrays of the right-hand side, the Jacobian and the projection
        type(ode_workspace_type) :: work
        !> Which rows are active and which are set aside as redundant (all active until
        !> choose_active is called)
        type(redundancy_type) :: redundancy
        !> The pairs of parts a SPRINGDAMPER or BUSHING joins (2 x m, rollcon_force's
        !> force_couplings): their momentum rows' partials in each other's states
        integer, allocatable :: couplings(:, :)
        !> A contact's mode: while it slides its tangential rows are dropped (inactive, as rows
        !> set aside are) and its friction enters every solve (rollcon_sliding_contact)
        type(sliding_contact_type) :: contact
        !> The modes of a dataset's further contacts (its second CONTACT on), each its own
        !> (rollcon_contact_watch's slot k): dropped rows and friction as contact's
        type(sliding_contact_type), allocatable :: more_contacts(:)
        !> A rim's rolling resistance and air layer (rollcon_rim_dissipation): the air's force
        !> is applied (assemble), rolling resistance's coupled to the normal force in every
        !> solve (resistance_coupling)
        type(rim_dissipation_type) :: dissipation
        !> Scratch of rolling resistance's second right-hand side: accelerations (n) and
        !> multipliers (nc)
        real(wp), allocatable :: resistance_a(:), resistance_lambda(:)
    contains
        procedure :: release => release_equations
        procedure :: init
        procedure :: accelerations
        procedure :: ode_jacobian
        procedure :: ode_jacobian_blocks
        procedure :: prepare_jacobian_blocks
        procedure :: jacobian_block
        procedure :: size_ode_form
        procedure :: project
        procedure :: energy
        procedure :: potential_energy
        procedure :: energy_tolerance
        procedure :: constraint_force
        procedure :: reaction_from_accelerations
        procedure :: assemble
        procedure :: constraint_rows
        procedure :: constraint_matrix
        procedure :: constraint_matrix_at
        procedure :: momentum_jacobian
        procedure :: choose_active
        procedure :: choose_block_again
        procedure :: redundancy_margins
        procedure :: reported_multipliers
        procedure :: active_rows
        procedure :: active_rows_of
        procedure :: masked
        procedure :: friction_coupling
        procedure :: contacts_friction_coupling
        procedure :: mode_drops
        procedure :: more_sliding
        procedure :: more_flying
        procedure :: impact_losses
        procedure :: impact_drive_works
        procedure :: friction_powers
        procedure :: resistance_coupling
        procedure :: acceleration_partials
        procedure :: multiplier_partials
        procedure :: reads_loop
        procedure :: held_coupling
    end type equations_type

contains

    !> Refer to a model that setup_model has prepared (not a copy: the model must stay where it
    !> is while these equations are used) and size the arrays.
    subroutine init(self, model)
        class(equations_type), intent(inout) :: self
        type(model_type), intent(in), target :: model

        self%model => model
        self%n = model%n
        self%nc = model%nc
        self%nh = model%nh
        call self%constraints%allocate(model)
        call self%blocks%init(model)
        call self%saddle%init(self%n, self%nc, self%blocks)
        call self%c%init(self%n, self%nc, self%blocks%ucon_start, self%blocks%ucon_coordinates)
        associate (n => self%n, nc => self%nc)
            if (allocated(self%mass)) deallocate(self%mass, self%force, self%gamma)
            allocate(self%mass(6, 6, size(model%parts)), self%force(n), &
                & self%gamma(nc), source=0.0_wp)
        end associate
        if (allocated(model%forces)) then
            self%couplings = force_couplings(model%forces)
        else
            if (allocated(self%couplings)) deallocate(self%couplings)
            allocate(self%couplings(2, 0))
        end if
        call self%work%init(self%n, self%nc, self%nh, size(model%parts), &
            & joined_parts(self%couplings, self%blocks))
        call self%redundancy%init(self%nc, self%blocks)
        if (allocated(self%resistance_a)) deallocate(self%resistance_a, self%resistance_lambda)
        allocate(self%resistance_a(self%n), self%resistance_lambda(self%nc), source=0.0_wp)
        ! the force measures a user's routine (a force's, a VARSUB's, a DIFSUB's) reads
        ! through SYSFNC are this model's
        call set_force_measure_model(model, refresh=.true.)
    end subroutine init

    !> The pairs of parts (2 x m) where dm/dq and dm/du have entries outside the parts' own
    !> blocks: the force elements' couplings (rollcon_force's force_couplings) and every two
    !> parts of one UCON (its second partials in -d(C^T lambda)/dq, momentum_jacobian).
    pure function joined_parts(couplings, blocks) result(pairs)
        integer, intent(in) :: couplings(:, :)
        type(constraint_blocks_type), intent(in) :: blocks
        integer, allocatable :: pairs(:, :)
        integer :: k, i, j, m, a, b

        m = size(couplings, 2)
        do k = 1, size(blocks%ucon_start) - 1
            i = blocks%ucon_start(k + 1) - blocks%ucon_start(k)
            m = m + i*i
        end do
        allocate(pairs(2, m))
        m = size(couplings, 2)
        pairs(:, :m) = couplings
        do k = 1, size(blocks%ucon_start) - 1
            do i = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                a = (blocks%ucon_coordinates(i) - 1)/6 + 1
                do j = blocks%ucon_start(k), blocks%ucon_start(k + 1) - 1
                    b = (blocks%ucon_coordinates(j) - 1)/6 + 1
                    if (a >= b) cycle
                    ! (a repeat of the pair before it is dropped here; others by init_blocks)
                    if (m > size(couplings, 2)) then
                        if (pairs(1, m) == a .and. pairs(2, m) == b) cycle
                    end if
                    m = m + 1
                    pairs(:, m) = [a, b]
                end do
            end do
        end do
        pairs = pairs(:, :m)
    end function joined_parts

    !> A user's force routine reads what the equations solve for (accelerations, or a
    !> constraint's reaction): the algebraic loop of loop_accelerations.
    logical function reads_loop(self)
        class(equations_type), intent(in) :: self

        reads_loop = .false.
        if (.not. allocated(self%model%forces)) return
        reads_loop = reads_accelerations(self%model%forces) &
            & .or. reads_constraint_forces(self%model%forces)
    end function reads_loop

    !> Choose the rows to set aside at (t, q, u) (rollcon_redundancy's choose: every block's
    !> rank from the tolerance) and say which in the user's words (redundancy%words): leaves C
    !> and M assembled there, and the constraints evaluated (values, first and time partials).
    subroutine choose_active(self, time, q, u, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        call self%redundancy%init(self%nc, self%blocks)
        if (self%nc == 0) return
        call self%constraints%evaluate(self%model, time, q, u, need_value + need_first &
            & + need_time, error)
        if (allocated(error)) return
        call self%assemble(time, q, u)
        call self%constraint_matrix()
        call self%redundancy%choose(self%c, self%mass, self%blocks, &
            & self%model%holonomic_number > 0, error)
        if (allocated(error)) return
        self%redundancy%words = set_aside_words(self%model, self%redundancy, self%c, self%mass, &
            & self%blocks, self%redundancy%involved, error)
    end subroutine choose_active

    !> Choose block b's rows again at (t, q, u) with the ranks of the first choice (changed:
    !> other rows are set aside now).
    subroutine choose_block_again(self, b, time, q, u, changed, error)
        class(equations_type), intent(inout) :: self
        integer, intent(in) :: b
        real(wp), intent(in) :: time, q(:), u(:)
        logical, intent(out) :: changed
        type(error_type), allocatable, intent(out) :: error

        changed = .false.
        call self%constraint_matrix_at(time, q, u, error)
        if (allocated(error)) return
        call self%assemble(time, q, u)
        call self%redundancy%rechoose(b, self%c, self%mass, self%blocks, &
            & self%model%holonomic_number > 0, changed, error)
    end subroutine choose_block_again

    !> For every block with rows set aside, in block order, its margin at (t, q, u)
    !> (rollcon_redundancy: zero where its choice has worn), into g.
    subroutine redundancy_margins(self, time, q, u, g, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: g(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: b, i

        call self%constraint_matrix_at(time, q, u, error)
        if (allocated(error)) return
        call self%assemble(time, q, u)
        i = 0
        do b = 1, self%blocks%count
            if (.not. self%redundancy%redundant(b)) cycle
            i = i + 1
            g(i) = self%redundancy%margin(b, self%c, self%mass, self%blocks, error)
            if (allocated(error)) return
        end do
    end subroutine redundancy_margins

    !> The multipliers to report, with C and M as the last accelerations call left them: lambda
    !> itself, or where rows are set aside the split of least norm of the same constraint force
    !> (rollcon_redundancy's multipliers; a redundant joint's reaction is not unique).
    subroutine reported_multipliers(self, lambda, reported, error)
        class(equations_type), intent(in) :: self
        real(wp), intent(in) :: lambda(:)
        real(wp), intent(out) :: reported(:)
        type(error_type), allocatable, intent(out) :: error

        reported = lambda
        if (self%redundancy%set_aside == 0) return
        call self%redundancy%multipliers(self%c, self%mass, self%blocks, reported, error)
    end subroutine reported_multipliers

    !> Whether row k is active (every row is until a choice sets some aside).
    pure logical function active_rows_of(self, k)
        class(equations_type), intent(in) :: self
        integer, intent(in) :: k

        active_rows_of = .true.
        if (allocated(self%redundancy%active)) active_rows_of = self%redundancy%active(k)
        if (self%mode_drops(k)) active_rows_of = .false.
    end function active_rows_of

    !> Whether a contact's mode drops row k (rollcon_sliding_contact's dropped, over the
    !> contact and the further contacts).
    pure logical function mode_drops(self, k)
        class(equations_type), intent(in) :: self
        integer, intent(in) :: k
        integer :: j

        mode_drops = self%contact%dropped(k)
        if (mode_drops .or. .not. allocated(self%more_contacts)) return
        do j = 1, size(self%more_contacts)
            if (self%more_contacts(j)%dropped(k)) mode_drops = .true.
        end do
    end function mode_drops

    !> A further contact (more_contacts) slides.
    pure logical function more_sliding(self)
        class(equations_type), intent(in) :: self

        more_sliding = .false.
        if (allocated(self%more_contacts)) more_sliding = any(self%more_contacts%sliding)
    end function more_sliding

    !> A further contact (more_contacts) flies.
    pure logical function more_flying(self)
        class(equations_type), intent(in) :: self

        more_flying = .false.
        if (allocated(self%more_contacts)) more_flying = any(self%more_contacts%flying)
    end function more_flying

    !> Kinetic energy every contact's impacts have taken so far [J] >= 0.
    pure real(wp) function impact_losses(self)
        class(equations_type), intent(in) :: self

        impact_losses = self%contact%impact_loss
        if (allocated(self%more_contacts)) impact_losses = impact_losses &
            & + sum(self%more_contacts%impact_loss)
    end function impact_losses

    !> Work the drives of moving planes (turntables) have done on the parts in every contact's
    !> impacts so far [J], signed (sliding_contact_type's impact_drive_work; 0 on the ground).
    pure real(wp) function impact_drive_works(self)
        class(equations_type), intent(in) :: self
        integer :: k

        impact_drive_works = self%contact%impact_drive_work
        if (.not. allocated(self%more_contacts)) return
        do k = 1, size(self%more_contacts)
            impact_drive_works = impact_drive_works + self%more_contacts(k)%impact_drive_work
        end do
    end function impact_drive_works

    !> The power the sliding contacts' friction dissipates at the last solve [W] >= 0.
    pure real(wp) function friction_powers(self)
        class(equations_type), intent(in) :: self
        integer :: j

        friction_powers = 0.0_wp
        if (self%contact%sliding) friction_powers = self%contact%power
        if (.not. allocated(self%more_contacts)) return
        do j = 1, size(self%more_contacts)
            if (self%more_contacts(j)%sliding) friction_powers = friction_powers &
                & + self%more_contacts(j)%power
        end do
    end function friction_powers

    !> Some rows are inactive: set aside as redundant, or a contact's a sliding or flying
    !> part drops.
    pure logical function masked(self)
        class(equations_type), intent(in) :: self

        masked = self%redundancy%set_aside > 0 .or. self%contact%sliding &
            & .or. self%contact%flying .or. self%more_sliding() .or. self%more_flying()
    end function masked

    !> Which rows are active (all of them until a choice sets some aside).
    pure function active_rows(self) result(active)
        class(equations_type), intent(in) :: self
        logical :: active(self%nc)
        integer :: k

        active = .true.
        if (allocated(self%redundancy%active)) active = self%redundancy%active
        if (self%contact%sliding .or. self%contact%flying) &
            & active(self%contact%tangential) = .false.
        if (self%contact%flying) active(self%contact%normal) = .false.
        if (.not. allocated(self%more_contacts)) return
        do k = 1, size(self%more_contacts)
            associate (contact => self%more_contacts(k))
                if (contact%sliding .or. contact%flying) active(contact%tangential) = .false.
                if (contact%flying) active(contact%normal) = .false.
            end associate
        end do
    end function active_rows

    !> Mass matrix (its parts' blocks) and f = -(M a - f) at a = 0, part by part. A user's
    !> force routine that fails leaves its error for take_user_force_error
    !> (rollcon_user_forces).
    subroutine assemble(self, time, q, u)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: applied(3), part_mass(6, 6), part_force(6)
        integer :: p, i0

        ! the user's VARSUBs, then force routines at this state (FUNCTION=USER; a failure is
        ! taken by the caller, take_user_force_error): a force's VARVAL reads the former
        ! (their SYSFNC('DIF') and SYSFNC('DIF1') read the DIFFs' state last set)
        if (self%model%diffs%count() > 0) call set_system_diff_state(self%model%diffs%ids, &
            & self%model%diffs%x, self%model%diffs%w)
        call evaluate_user_variables(time, q, u)
        call evaluate_user_forces(self%model%forces, time, q, u)
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            call force_and_moment(self%model%forces, p, time, q, u, applied, &
                & self%work%moments(:, p))
            call body_mass_and_force(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), &
                & applied, self%work%moments(:, p), self%model%gravity, part_mass, part_force)
            self%mass(:, :, p) = part_mass
            self%force(i0 + 1:i0 + 6) = part_force
        end do
        ! the air layer under a rim: a generalised force on psi (rollcon_rim_dissipation)
        if (self%dissipation%air > 0.0_wp .and. self%dissipation%part > 0) then
            i0 = 6*(self%dissipation%part - 1)
            self%force(i0 + 4) = self%force(i0 + 4) + self%dissipation%air_force(q(i0 + 5), &
                & u(i0 + 4))
        end if
    end subroutine assemble

    !> C (velocity UCON: dF/du; position UCON: dF/dq) and gamma, from the last evaluation.
    subroutine constraint_rows(self, u, alpha)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: u(:)
        !> Baumgarte rate in effect [1/s]: F' = -alpha F (velocity), F'' = -2 alpha F' -
        !> alpha^2 F (position); 0 without Baumgarte terms
        real(wp), intent(in) :: alpha
        real(wp) :: rate
        ! u over UCON k's own coordinates, gathered once for its three sums
        real(wp) :: u_local(max_ucon_vars)
        integer :: k, first, count, i

        call self%constraint_matrix()
        ! sums over each UCON's own coordinates (ascending): the dense sums' terms that are
        ! not exact zeros, in their order (those of grad_q_dot and local_dot, on u gathered
        ! once: the same products in the same order)
        associate (cs => self%constraints, at => self%blocks%ucon_coordinates)
            do k = 1, self%nc
                first = self%blocks%ucon_start(k)
                count = self%blocks%ucon_start(k + 1) - first
                do i = 1, count
                    u_local(i) = u(at(first + i - 1))
                end do
                if (self%model%ucons(k)%holonomic) then
                    rate = gathered_dot(cs%grad_q_local(:, k), u_local, count) + cs%dt(k)
                    self%gamma(k) = -local_quadratic_form(cs%hqq(:, :, k), u_local, count) &
                        & - 2.0_wp*gathered_dot(cs%dt_grad_q(:, k), u_local, count) &
                        & - cs%dtt(k) - 2.0_wp*alpha*rate - alpha**2*cs%value(k)
                else
                    self%gamma(k) = -gathered_dot(cs%grad_q_local(:, k), u_local, count) &
                        & - cs%dt(k) - alpha*cs%value(k)
                end if
            end do
        end associate
    end subroutine constraint_rows

    !> C alone (velocity UCON: dF/du; position UCON: dF/dq), from first partials only: each
    !> row over its UCON's coordinates, the pattern C is held on.
    subroutine constraint_matrix(self)
        class(equations_type), intent(inout) :: self
        integer :: k, a, first, count

        ! entry first + a - 1 of row k is the UCON's own coordinate a (the same ascending list)
        do k = 1, self%nc
            first = self%blocks%ucon_start(k)
            count = self%blocks%ucon_start(k + 1) - first
            if (self%model%ucons(k)%holonomic) then
                do a = 1, count
                    self%c%value(first + a - 1) = self%constraints%grad_q_local(a, k)
                end do
            else
                do a = 1, count
                    self%c%value(first + a - 1) = self%constraints%grad_u_local(a, k)
                end do
            end if
        end do
    end subroutine constraint_matrix

    !> C at (t, q, u) from first partials alone: no saddle-point solve (for a constraint force
    !> from known multipliers).
    subroutine constraint_matrix_at(self, time, q, u, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        call self%constraints%evaluate(self%model, time, q, u, need_first, error)
        if (allocated(error)) return
        call self%constraint_matrix()
    end subroutine constraint_matrix_at

    !> Accelerations a and multipliers lambda at (t, q, u); leaves the saddle-point factors in
    !> `saddle` for the Jacobian.
    subroutine accelerations(self, time, q, u, baumgarte, a, lambda, error, second)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: baumgarte
        !> Accelerations [m/s^2, rad/s^2]
        real(wp), intent(out) :: a(self%n)
        !> Multipliers: the constraint forces' amplitudes
        real(wp), intent(out) :: lambda(self%nc)
        type(error_type), allocatable, intent(out) :: error
        !> Also evaluate second partials (needed by the Jacobian, or by position UCONs)
        logical, intent(in), optional :: second
        integer :: needs, n, nc

        n = self%n
        nc = self%nc
        needs = need_value + need_first + need_time
        if (self%nh > 0) needs = needs + need_second
        if (present(second)) then
            if (second .and. self%nh == 0) needs = needs + need_second
        end if
        call self%constraints%evaluate(self%model, time, q, u, needs, error)
        if (allocated(error)) return
        if (self%reads_loop()) then
            call loop_accelerations(self, time, q, u, baumgarte, a, lambda, error)
            return
        end if
        call self%assemble(time, q, u)
        call take_user_force_error(error)
        if (allocated(error)) return
        call self%constraint_rows(u, baumgarte)
        ! M^-1 f in the factorisation's own LAPACK calls (those of M^-1 C^T)
        a = self%force
        if (self%masked()) then
            call self%saddle%factor(self%mass, self%c, nc, error, a, self%active_rows())
        else
            call self%saddle%factor(self%mass, self%c, nc, error, a)
        end if
        if (allocated(error)) return
        lambda = self%gamma
        call self%saddle%solve(self%c, a, lambda, 1, error, scaled=.true.)
        if (allocated(error)) return
        if (self%dissipation%held .or. self%dissipation%rolling_resistance > 0.0_wp) then
            ! the rim's (the contact's) laws, then any further contact's sliding friction:
            ! each contact holds a part nothing else constrains, so they do not couple
            if (self%dissipation%held) then
                call self%held_coupling(time, q, a, lambda, error)
            else
                call self%resistance_coupling(time, q, u, a, lambda, error)
            end if
            if (allocated(error)) return
            if (self%more_sliding()) call self%contacts_friction_coupling(time, q, a, lambda, &
                & error, more_only=.true.)
        else if (self%more_sliding()) then
            call self%contacts_friction_coupling(time, q, a, lambda, error)
        else if (self%contact%sliding) then
            call self%friction_coupling(time, q, a, lambda, error)
        end if
    end subroutine accelerations

    !> Rolling resistance (rollcon_rim_dissipation), and a sliding contact's friction with it,
    !> in the accelerations a and multipliers lambda of the saddle-point system without them
    !> (factored): both are generalised forces -F_n G proportional to the normal force, G =
    !> delta sign(phidot) e_phi (+ mu_k (s_1 c_t1 + s_2 c_t2) while sliding), coupled exactly
    !> as friction_coupling couples the friction alone: the second right-hand side (G, 0)
    !> gives (a1, lambda1), F_n (1 + c_nz lambda1_n) = c_nz lambda0_n, a = a0 - F_n a1,
    !> lambda = lambda0 - F_n lambda1 (docs/design.md §5, "Dissipation"). Refused (stat_ucon)
    !> where 1 + c_nz lambda1_n < painleve_margin (no unique normal force).
    subroutine resistance_coupling(self, time, q, u, a, lambda, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(inout) :: a(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: s(2), c_nz, rolling, denominator, normal_force
        integer :: phi_column

        associate (diss => self%dissipation, contact => self%contact, n_row => &
                & self%dissipation%normal, t => self%contact%tangential, &
                & g => self%resistance_a, g_lambda => self%resistance_lambda)
            phi_column = 6*(diss%part - 1) + 6
            g = 0.0_wp
            rolling = diss%rolling_direction(u(phi_column))
            g(phi_column) = diss%rolling_resistance*rolling
            if (contact%sliding) then
                contact%slip = [self%constraints%value(t(1)), self%constraints%value(t(2))]
                s = contact%direction(contact%slip)
                call combine_rows(self%c, t, s, g, contact%mu)
            end if
            g_lambda = 0.0_wp
            call self%saddle%solve(self%c, g, g_lambda, 1, error)
            if (allocated(error)) return
            c_nz = self%c%entry(n_row, diss%height_column)
            denominator = 1.0_wp + c_nz*g_lambda(n_row)
            if (.not. denominator >= painleve_margin) then
                call fatal_error(error, "the normal force is ill-posed at t = " &
                    & // to_text(time) // " s (theta = " &
                    & // to_text(q(diss%height_column + 2)) // " rad): the forces " &
                    & // "proportional to it (rolling resistance, sliding friction) feed " &
                    & // "back into it with 1 + dFn/dFn = " // to_text(denominator) &
                    & // ", leaving it without a unique positive solution; the equations " &
                    & // "are not integrated", stat_ucon)
                return
            end if
            normal_force = c_nz*lambda(n_row)/denominator
            a = a - normal_force*g
            lambda = lambda - normal_force*g_lambda
            diss%normal_force = normal_force
            diss%rolling_power = diss%rolling_resistance*normal_force*rolling*u(phi_column)
            if (contact%sliding) then
                contact%denominator = denominator
                contact%normal_force = normal_force
                contact%friction = -contact%mu*normal_force*s
                contact%power = abs(dot_product(contact%friction, contact%slip))
            end if
        end associate
    end subroutine resistance_coupling
    !> The accelerations and multipliers of a model where a user's force routine reads
    !> accelerations (SYSARY('TACC'|'RACC'), SYSFNC('ACCX' ... 'WDTM')), or a VARSUB does
    !> (a force reading its VARVAL reads them through it), or a constraint's reaction
    !> (SYSFNC's force measures summing a JOINT's or JPRIM's, rollcon_force_measures):
    !> the algebraic loop M a - f(q, u, a, lambda, t) - C^T lambda = 0, C a = gamma, solved by
    !> Newton's method on (a, lambda) as ADAMS solves it, from the accelerations and
    !> multipliers the routines read last. Each iteration evaluates the forces at the iterate
    !> (a_k, lambda_k) (rollcon_user_forces' set_system_accelerations,
    !> set_system_constraint_forces), their partials in a and lambda by central differences
    !> over what each routine declared (rollcon_user_force_partials; the first iteration's
    !> serve every one), and solves
    !>
    !>     [M + dm/da, -C^T + dm/dlambda; C, 0] (a, lambda)
    !>         = (f(a_k, lambda_k) + dm/da a_k + dm/dlambda lambda_k, gamma)
    !>
    !> densely (LU, LAPACK; a row set aside: lambda_k = 0). Converged when no acceleration
    !> moved by more than 1e-10 max(|a|_inf, 1) [SI] and no multiplier by more than 1e-10
    !> max(|lambda|_inf, 1): the partials' relative error is about
    !> 4e-11 (rollcon_central_differences), so each iteration shrinks the error by that
    !> factor at least and the one that follows such a step would move a by some 1e-20 of
    !> it, below round-off; a force linear in a (a virtual mass) converges in two. At most
    !> 20 iterations, else an error naming the statements whose routines read accelerations.
    !> The LU factors stay in work%loop_matrix for ode_jacobian. A sliding contact (a scene's,
    !> never a dataset's) is not combined with it.
    subroutine loop_accelerations(self, time, q, u, baumgarte, a, lambda, error)
        type(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:), baumgarte
        real(wp), intent(out) :: a(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error
        integer, parameter :: most_iterations = 20
        real(wp), parameter :: settled = 1.0e-10_wp
        real(wp), allocatable :: x(:, :)
        real(wp) :: change, moved
        logical, allocatable :: active(:)
        logical :: multipliers
        integer :: n, nc, k, iteration, p, i0
        character(len=:), allocatable :: names

        n = self%n
        nc = self%nc
        if (.not. allocated(self%work%loop_matrix)) allocate(self%work%loop_matrix(n + nc, &
            & n + nc), self%work%loop_pivots(n + nc))
        allocate(x(n + nc, 1))
        active = self%active_rows()
        if (.not. allocated(self%work%loop_a)) allocate(self%work%loop_a(n), source=0.0_wp)
        if (.not. allocated(self%work%loop_lambda)) allocate(self%work%loop_lambda(nc), &
            & source=0.0_wp)
        if (.not. allocated(self%work%dm_dlambda)) allocate(self%work%dm_dlambda(n, nc), &
            & source=0.0_wp)
        a = self%work%loop_a
        lambda = merge(self%work%loop_lambda, 0.0_wp, active)
        multipliers = reads_constraint_forces(self%model%forces)
        ! the constraint rows the force measures read a reaction from (the constraints were
        ! evaluated at (t, q, u) by the caller)
        if (multipliers) call self%constraint_matrix()
        change = huge(1.0_wp)
        moved = huge(1.0_wp)
        do iteration = 1, most_iterations
            call set_system_accelerations(a)
            if (multipliers) call set_system_constraint_forces(self%c, lambda)
            call self%assemble(time, q, u)
            call take_user_force_error(error)
            if (allocated(error)) return
            if (iteration == 1) then
                call form_loop_matrix(self, time, q, u, a, lambda, active, multipliers, error)
                if (allocated(error)) return
                call self%constraint_rows(u, baumgarte)
            end if
            x(:n, 1) = self%force + matmul(self%work%dm_da, a)
            if (multipliers) x(:n, 1) = x(:n, 1) + matmul(self%work%dm_dlambda, lambda)
            x(n + 1:, 1) = merge(self%gamma, 0.0_wp, active)
            call solve_factored(self%work%loop_matrix, self%work%loop_pivots, x, error)
            if (allocated(error)) return
            change = maxval(abs(x(:n, 1) - a))
            moved = 0.0_wp
            if (nc > 0) moved = maxval(abs(x(n + 1:, 1) - lambda))
            a = x(:n, 1)
            lambda = x(n + 1:, 1)
            if (loop_settled()) exit
        end do
        ! the forces and the routines' accelerations and reactions at the solution
        call set_system_accelerations(a)
        if (multipliers) call set_system_constraint_forces(self%c, lambda)
        call self%assemble(time, q, u)
        call take_user_force_error(error)
        if (allocated(error)) return
        self%work%loop_a = a
        self%work%loop_lambda = lambda
        if (.not. loop_settled()) then
            names = loop_names(self)
            call fatal_error(error, names // ": the accelerations and constraint forces " &
                & // "these statements' routines read did not settle in " &
                & // to_text(most_iterations) // " Newton iterations at t = " // to_text(time) &
                & // " s (the last moved the accelerations by " // to_text(change) &
                & // " m/s^2 or rad/s^2, the multipliers by " // to_text(moved) // "): a " &
                & // "force or VARIABLE far from linear in what it reads", stat_ucon)
        end if

    contains

        logical function loop_settled()
            loop_settled = change <= settled*max(maxval(abs(a)), 1.0_wp)
            if (multipliers .and. nc > 0) loop_settled = loop_settled &
                & .and. moved <= settled*max(maxval(abs(lambda)), 1.0_wp)
        end function loop_settled
    end subroutine loop_accelerations

    !> The algebraic loop's saddle-point matrix [M + dm/da, -C^T + dm/dlambda; C, 0] at the
    !> iterate (a, lambda), the forces evaluated there (assemble) before and C at (t, q, u)
    !> (a row set aside, not active: lambda_k = 0), LU-factored into work%loop_matrix,
    !> work%loop_pivots; the forces' partials in a and lambda (acceleration_partials,
    !> multiplier_partials: the latter only when multipliers, a routine reading a reaction)
    !> into the work. A failed difference call's error, or a singular matrix's naming the
    !> statements whose routines read the unknowns, is returned.
    subroutine form_loop_matrix(self, time, q, u, a, lambda, active, multipliers, error)
        type(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:), a(:), lambda(:)
        logical, intent(in) :: active(:), multipliers
        type(error_type), allocatable, intent(out) :: error
        integer :: n, k, p, i0, j

        n = self%n
        call self%acceleration_partials(time, q, u, a, error)
        if (allocated(error)) return
        self%work%dm_dlambda = 0.0_wp
        if (multipliers) then
            call self%multiplier_partials(time, q, u, lambda, error)
            if (allocated(error)) return
        end if
        associate (m => self%work%loop_matrix)
            m = 0.0_wp
            ! (0 + dm/da off the parts' blocks: M's zeros added, as a dense M adds them)
            m(:n, :n) = 0.0_wp + self%work%dm_da
            do p = 1, size(self%model%parts)
                i0 = 6*(p - 1)
                m(i0 + 1:i0 + 6, i0 + 1:i0 + 6) = self%mass(:, :, p) &
                    & + self%work%dm_da(i0 + 1:i0 + 6, i0 + 1:i0 + 6)
            end do
            do k = 1, self%nc
                if (active(k)) then
                    call self%c%fill_row(k, m(n + k, :n))
                    do j = 1, n
                        m(j, n + k) = -m(n + k, j) + self%work%dm_dlambda(j, k)
                    end do
                else
                    m(n + k, n + k) = 1.0_wp
                end if
            end do
        end associate
        call factor_dense(self%work%loop_matrix, self%work%loop_pivots, error)
        if (allocated(error)) then
            error%message = loop_names(self) // ": the saddle-point matrix of the " &
                & // "equations with the accelerations they read, [M - df/da, -C^T; " &
                & // "C, 0], is singular at t = " // to_text(time) // " s: " // error%message
        end if
    end subroutine form_loop_matrix

    !> The statements whose user routines read accelerations, "SFORCE/3 (line 12), ...", then
    !> the VARIABLEs whose VARSUBs do.
    function loop_names(self) result(names)
        type(equations_type), intent(in) :: self
        character(len=:), allocatable :: names
        integer :: i

        names = ""
        do i = 1, size(self%model%forces)
            if (self%model%forces(i)%profile /= profile_statement) cycle
            if (self%model%forces(i)%statement%routine == 0) cycle
            if (.not. self%model%forces(i)%statement%declared_accelerations .and. .not. &
                & self%model%forces(i)%statement%declared_forces) cycle
            if (len(names) > 0) names = names // ", "
            names = names // self%model%forces(i)%name
        end do
        if (variables_read_accelerations()) then
            if (len(names) > 0) names = names // ", "
            names = names // variables_reading_accelerations()
        end if
    end function loop_names

    !> work%dm_da: the partials in the accelerations a of the momentum residual's forces (M a
    !> itself left out) at (t, q, u, a), the forces evaluated there (assemble) before: the
    !> forces whose routines read accelerations (directly, or through a VARSUB's VARVAL),
    !> differenced, and the expression forces reading VARVAL of a VARSUB that reads them, the
    !> VARSUB's partials differenced and chained through the expressions' exact ones
    !> (rollcon_user_force_partials). A failed difference call's error is returned.
    subroutine acceleration_partials(self, time, q, u, a, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:), a(:)
        type(error_type), allocatable, intent(out) :: error
        type(user_variable_type), allocatable :: variables(:)
        real(wp), allocatable :: dv_da(:, :)
        integer, allocatable :: ids(:)

        if (.not. allocated(self%work%dm_da)) allocate(self%work%dm_da(self%n, self%n))
        self%work%dm_da = 0.0_wp
        call add_user_force_acceleration_partials(self%model%forces, time, q, u, a, &
            & self%work%dm_da)
        if (variables_read_accelerations()) then
            variables = user_variable_list()
            ! (a copy: a component of an array of a derived type is not contiguous)
            ids = variables%id
            allocate(dv_da(size(variables), size(a)))
            call difference_variable_accelerations(time, q, u, a, dv_da)
            call add_variable_acceleration_partials(self%model%forces, time, q, u, ids, &
                & dv_da, self%work%dm_da)
        end if
        call take_user_force_error(error)
    end subroutine acceleration_partials

    !> work%dm_dlambda: the partials in the multipliers lambda of the momentum residual's
    !> forces at (t, q, u, lambda), the forces evaluated there (assemble) before: the forces
    !> whose routines read a constraint's reaction, differenced (rollcon_user_force_partials),
    !> and the expression forces reading VARVAL of a VARSUB that reads one, the VARSUB's
    !> partials differenced over the rows it declared and chained through the expressions'
    !> exact ones. A failed difference call's error is returned.
    subroutine multiplier_partials(self, time, q, u, lambda, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error
        type(user_variable_type), allocatable :: variables(:)
        real(wp), allocatable :: dv_dlambda(:, :)
        integer, allocatable :: ids(:)

        if (.not. allocated(self%work%dm_dlambda)) allocate(self%work%dm_dlambda(self%n, &
            & self%nc))
        self%work%dm_dlambda = 0.0_wp
        call add_user_force_multiplier_partials(self%model%forces, time, q, u, lambda, &
            & self%work%dm_dlambda)
        if (variables_read_constraint_forces()) then
            variables = user_variable_list()
            ! (a copy: a component of an array of a derived type is not contiguous)
            ids = variables%id
            allocate(dv_dlambda(size(variables), self%nc))
            call difference_variable_multipliers(time, q, u, lambda, dv_dlambda)
            call add_variable_multiplier_partials(self%model%forces, time, q, u, ids, &
                & dv_dlambda, self%work%dm_dlambda)
        end if
        call take_user_force_error(error)
    end subroutine multiplier_partials

    !> A held rolling resistance (rollcon_rim_dissipation: phidot held at zero by the moment
    !> it needs, within delta F_n) in the accelerations a and multipliers lambda of the
    !> saddle-point system without it (factored): the generalised force Q_phi on phi alone
    !> that makes phiddot = 0, from the second right-hand side (e_phi, 0) giving (a1, lambda1):
    !> Q_phi = -a0_phi / a1_phi, a = a0 + Q_phi a1, lambda = lambda0 + Q_phi lambda1 (the
    !> constraint phidot = 0 with Q_phi its multiplier); Q_phi and the normal force recorded.
    !> Refused (stat_ucon) while the contact slides or flies (not modelled: the friction's
    !> coupling to Q_phi through F_n) or where a1_phi is not positive.
    subroutine held_coupling(self, time, q, a, lambda, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: a(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: moment
        integer :: phi_column

        associate (diss => self%dissipation, g => self%resistance_a, &
                & g_lambda => self%resistance_lambda)
            phi_column = 6*(diss%part - 1) + 6
            if (self%contact%sliding .or. self%contact%flying) then
                call fatal_error(error, "at t = " // to_text(time) // " s rolling resistance " &
                    & // "holds phidot = 0 while the contact slides or flies, which is not " &
                    & // "modelled", stat_ucon)
                return
            end if
            g = 0.0_wp
            g(phi_column) = 1.0_wp
            g_lambda = 0.0_wp
            call self%saddle%solve(self%c, g, g_lambda, 1, error)
            if (allocated(error)) return
            if (.not. g(phi_column) > 0.0_wp) then
                call fatal_error(error, "at t = " // to_text(time) // " s (theta = " &
                    & // to_text(q(diss%height_column + 2)) // " rad) a moment on phi does " &
                    & // "not turn phi: the held rolling resistance is undetermined", stat_ucon)
                return
            end if
            moment = -a(phi_column)/g(phi_column)
            a = a + moment*g
            a(phi_column) = 0.0_wp
            lambda = lambda + moment*g_lambda
            diss%held_moment = moment
            diss%normal_force = self%c%entry(diss%normal, diss%height_column) &
                & *lambda(diss%normal)
            diss%rolling_power = 0.0_wp
        end associate
    end subroutine held_coupling

    !> A sliding contact's friction in the accelerations a and multipliers lambda of the
    !> saddle-point system without it (its tangential rows dropped, factored): the second
    !> right-hand side (D, 0), the normal force of the coupled system, and a and lambda with
    !> the friction -mu F_n D (rollcon_sliding_contact, docs/design.md §5 "Contact modes").
    !> Refused (stat_ucon) where the coupled system is singular or its normal force's
    !> coefficient has the wrong sign (Painlevé's paradox).
    subroutine friction_coupling(self, time, q, a, lambda, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: a(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: s(2), c_nz

        associate (contact => self%contact, t => self%contact%tangential, &
                & n_row => self%contact%normal)
            contact%slip = [self%constraints%value(t(1)), self%constraints%value(t(2))]
            s = contact%direction(contact%slip)
            call combine_rows(self%c, t, s, contact%unit_a)
            contact%unit_lambda = 0.0_wp
            call self%saddle%solve(self%c, contact%unit_a, contact%unit_lambda, 1, error)
            if (allocated(error)) return
            c_nz = self%c%entry(n_row, contact%height_column)
            contact%denominator = 1.0_wp + contact%mu*c_nz*contact%unit_lambda(n_row)
            if (.not. contact%denominator >= painleve_margin) then
                call fatal_error(error, "sliding is ill-posed at t = " // to_text(time) &
                    & // " s (theta = " // to_text(q(contact%height_column + 2)) // " rad): " &
                    & // "with mu_kinetic = " // to_text(contact%mu) // " the friction " &
                    & // "coupling 1 + mu dFn/dFt = " // to_text(contact%denominator) &
                    & // " leaves the normal force without a unique positive solution " &
                    & // "(Painlevé's paradox); the sliding equations are not integrated", &
                    & stat_ucon)
                return
            end if
            contact%normal_force = c_nz*lambda(n_row)/contact%denominator
            a = a - contact%mu*contact%normal_force*contact%unit_a
            lambda = lambda - contact%mu*contact%normal_force*contact%unit_lambda
            contact%friction = -contact%mu*contact%normal_force*s
            contact%power = abs(dot_product(contact%friction, contact%slip))
        end associate
    end subroutine friction_coupling

    !> Several sliding contacts' friction (the contact and more_contacts) in the accelerations a
    !> and multipliers lambda of the saddle-point system without it (factored): each sliding
    !> contact i its second right-hand side (D_i, 0) giving (a_i, lambda_i) (unit_response),
    !> and by linearity the normal forces of the coupled system solve
    !> F_n,i + sum_j mu_j c_nz,i lambda_j(n_i) F_n,j = c_nz,i lambda0(n_i), the single contact's
    !> F_n (1 + mu c_nz lambda1_n) = c_nz lambda0_n (friction_coupling) for one; then
    !> a = a0 - sum_j mu_j F_n,j a_j and lambda likewise (docs/design.md §5, "Contact modes").
    !> Contacts on parts nothing else joins do not couple (lambda_j(n_i) = 0 for i /= j).
    !> more_only: the further contacts alone, after a rim's laws coupled the contact's
    !> (resistance_coupling, held_coupling; a dataset's CONTACTs hold parts nothing else
    !> constrains, so this order is exact).
    !> Refused (stat_ucon) where a contact's own coefficient 1 + mu c_nz lambda_i(n_i) is
    !> below painleve_margin (Painlevé's paradox, as friction_coupling) or the coupled system
    !> is singular.
    subroutine contacts_friction_coupling(self, time, q, a, lambda, error, more_only)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:)
        real(wp), intent(inout) :: a(:), lambda(:)
        type(error_type), allocatable, intent(out) :: error
        !> The further contacts (more_contacts) alone: the contact's friction is already in a
        !> and lambda (resistance_coupling's, with a rim's rolling resistance)
        logical, intent(in), optional :: more_only
        real(wp) :: coupling(1 + size(self%more_contacts), 1 + size(self%more_contacts))
        real(wp) :: forces(1 + size(self%more_contacts)), c_nz(1 + size(self%more_contacts))
        real(wp) :: pivot, factor
        integer :: which(1 + size(self%more_contacts)), rows(1 + size(self%more_contacts))
        integer :: m, i, j, k, best
        logical :: only_more

        ! the sliding contacts: 0 the contact, j more_contacts(j)
        only_more = .false.
        if (present(more_only)) only_more = more_only
        m = 0
        if (self%contact%sliding .and. .not. only_more) then
            m = 1
            which(1) = 0
            call unit_response(self%contact, self%saddle, self%c, self%constraints%value, error)
            if (allocated(error)) return
        end if
        do j = 1, size(self%more_contacts)
            if (.not. self%more_contacts(j)%sliding) cycle
            m = m + 1
            which(m) = j
            call unit_response(self%more_contacts(j), self%saddle, self%c, &
                & self%constraints%value, error)
            if (allocated(error)) return
        end do
        do i = 1, m
            if (which(i) == 0) then
                rows(i) = self%contact%normal
                c_nz(i) = self%c%entry(rows(i), self%contact%height_column)
            else
                rows(i) = self%more_contacts(which(i))%normal
                c_nz(i) = self%c%entry(rows(i), self%more_contacts(which(i))%height_column)
            end if
            forces(i) = c_nz(i)*lambda(rows(i))
        end do
        do j = 1, m
            do i = 1, m
                if (which(j) == 0) then
                    coupling(i, j) = self%contact%mu*c_nz(i) &
                        & *self%contact%unit_lambda(rows(i))
                else
                    coupling(i, j) = self%more_contacts(which(j))%mu*c_nz(i) &
                        & *self%more_contacts(which(j))%unit_lambda(rows(i))
                end if
            end do
            coupling(j, j) = coupling(j, j) + 1.0_wp
        end do
        do i = 1, m
            if (which(i) == 0) then
                self%contact%denominator = coupling(i, i)
            else
                self%more_contacts(which(i))%denominator = coupling(i, i)
            end if
            if (.not. coupling(i, i) >= painleve_margin) then
                call fatal_error(error, "sliding is ill-posed at t = " // to_text(time) &
                    & // " s (Z = " // to_text(q(height_of(i))) // " m): the friction " &
                    & // "coupling 1 + mu dFn/dFt = " // to_text(coupling(i, i)) &
                    & // " of the contact of the part whose centre height is coordinate " &
                    & // to_text(height_of(i)) // " leaves the normal force without a " &
                    & // "unique positive solution (Painlevé's paradox); the sliding " &
                    & // "equations are not integrated", stat_ucon)
                return
            end if
        end do
        ! the m normal forces: Gaussian elimination with partial pivoting (m is small)
        do k = 1, m
            best = k - 1 + maxloc(abs(coupling(k:m, k)), dim=1)
            if (best /= k) then
                coupling([k, best], :) = coupling([best, k], :)
                forces([k, best]) = forces([best, k])
            end if
            pivot = coupling(k, k)
            if (.not. abs(pivot) >= painleve_margin) then
                call fatal_error(error, "sliding is ill-posed at t = " // to_text(time) &
                    & // " s: the sliding contacts' normal forces have no unique solution " &
                    & // "(their friction couplings make a singular system)", stat_ucon)
                return
            end if
            do i = k + 1, m
                factor = coupling(i, k)/pivot
                coupling(i, k:m) = coupling(i, k:m) - factor*coupling(k, k:m)
                forces(i) = forces(i) - factor*forces(k)
            end do
        end do
        do k = m, 1, -1
            forces(k) = (forces(k) - dot_product(coupling(k, k + 1:m), forces(k + 1:m))) &
                & /coupling(k, k)
        end do
        do i = 1, m
            if (which(i) == 0) then
                call apply_friction(self%contact, forces(i), a, lambda)
            else
                call apply_friction(self%more_contacts(which(i)), forces(i), a, lambda)
            end if
        end do

    contains

        !> Sliding contact i's centre height's coordinate.
        pure integer function height_of(i)
            integer, intent(in) :: i

            if (which(i) == 0) then
                height_of = self%contact%height_column
            else
                height_of = self%more_contacts(which(i))%height_column
            end if
        end function height_of
    end subroutine contacts_friction_coupling

    !> A sliding contact's slip (its tangential rows' values) and its response to a unit force
    !> along the slip's direction s at its point: (D, 0), D = s_1 c_t1 + s_2 c_t2, solved in
    !> the saddle-point factors into (unit_a, unit_lambda). An error when the solve fails.
    subroutine unit_response(contact, saddle, c, values, error)
        type(sliding_contact_type), intent(inout) :: contact
        type(saddle_point_type), intent(inout) :: saddle
        !> The constraints' matrix C (nc x n, by rows over each UCON's coordinates)
        type(constraint_matrix_type), intent(in) :: c
        !> The rows' values (nc)
        real(wp), intent(in) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: s(2)

        associate (t => contact%tangential)
            contact%slip = [values(t(1)), values(t(2))]
            s = contact%direction(contact%slip)
            call combine_rows(c, t, s, contact%unit_a)
        end associate
        contact%unit_lambda = 0.0_wp
        call saddle%solve(c, contact%unit_a, contact%unit_lambda, 1, error)
    end subroutine unit_response

    !> s(1) C(t(1), :) + s(2) C(t(2), :) over all n columns into y, or with f, f times it added
    !> to y: C by rows over each UCON's coordinates, both rows walked together (columns
    !> ascending) with the exact zeros off their patterns summed as the dense rows' are, so
    !> the numbers are those of the dense expression. No allocation.
    pure subroutine combine_rows(c, t, s, y, f)
        type(constraint_matrix_type), intent(in) :: c
        !> The two rows (a contact's tangential UCONs)
        integer, intent(in) :: t(2)
        !> Their coefficients
        real(wp), intent(in) :: s(2)
        !> The combination (n), or what it is added to with f
        real(wp), intent(inout) :: y(:)
        real(wp), intent(in), optional :: f
        real(wp) :: c1, c2
        integer :: j, x1, x2

        x1 = c%start(t(1))
        x2 = c%start(t(2))
        do j = 1, size(y)
            call c%entry_along(t(1), j, x1, c1)
            call c%entry_along(t(2), j, x2, c2)
            if (present(f)) then
                y(j) = y(j) + f*(s(1)*c1 + s(2)*c2)
            else
                y(j) = s(1)*c1 + s(2)*c2
            end if
        end do
    end subroutine combine_rows

    !> A sliding contact's friction -mu F_n D with normal force normal_force [N] added to the
    !> accelerations a and multipliers lambda (its unit response's), and its force and power.
    pure subroutine apply_friction(contact, normal_force, a, lambda)
        type(sliding_contact_type), intent(inout) :: contact
        real(wp), intent(in) :: normal_force
        real(wp), intent(inout) :: a(:), lambda(:)

        contact%normal_force = normal_force
        a = a - contact%mu*normal_force*contact%unit_a
        lambda = lambda - contact%mu*normal_force*contact%unit_lambda
        contact%friction = -contact%mu*normal_force*contact%direction(contact%slip)
        contact%power = abs(dot_product(contact%friction, contact%slip))
    end subroutine apply_friction

    !> d(M a - f - C^T lambda)/dq and /du at given a, lambda and time [s] (into work%dm: on the
    !> pairs of parts the elements and UCONs join).
    !> A user force routine's partials are differences of calls (rollcon_user_force_partials):
    !> a failure of one is left for take_user_force_error.
    subroutine momentum_jacobian(self, q, u, a, lambda, time)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp), intent(in) :: lambda(:)
        real(wp), intent(in) :: time
        integer :: attempt

        ! a user's routine that declared a part at its first call (after init gathered the
        ! pairs) writes a pair not held: held from then on, and written again
        do attempt = 1, 2
            call fill_momentum_jacobian(self, q, u, a, lambda, time)
            if (self%work%dm%missed_count == 0) exit
            call self%work%dm%grow()
        end do
    end subroutine momentum_jacobian

    !> momentum_jacobian's partials into work%dm as it holds its pairs.
    subroutine fill_momentum_jacobian(self, q, u, a, lambda, time)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp), intent(in) :: lambda(:)
        real(wp), intent(in) :: time
        real(wp) :: part_dq(6, 6), part_du(6, 6)
        integer :: p, i0, k

        call self%work%dm%clear()
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            call body_residual_jacobian(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), &
                & a(i0 + 1:i0 + 6), self%work%moments(:, p), part_dq, part_du)
            call self%work%dm%set_part(p, part_dq, part_du)
        end do
        ! the SPRINGDAMPERs' and BUSHINGs' partials, over both of each one's parts
        call add_force_partials(self%model%forces, q, u, self%work%dm)
        ! the force statements' expressions' (exact; a VARSUB's VARVAL with its differenced
        ! partials) and user routines' (differenced)
        call difference_user_variables(time, q, u)
        call add_expression_partials(self%model%forces, time, q, u, self%work%dm)
        call clear_user_variable_partials()
        call add_user_force_partials(self%model%forces, time, q, u, self%work%dm)
        ! -d(C^T lambda)/dq: second partials are why ADAMS asks a UCOSUB for XMATRX
        ! (docs/design.md §4); each UCON's over its own coordinates (the rest are zeros)
        do k = 1, self%nc
            associate (at => self%blocks%ucon_coordinates(self%blocks%ucon_start(k): &
                    & self%blocks%ucon_start(k + 1) - 1))
                if (self%model%ucons(k)%holonomic) then
                    call self%work%dm%subtract_q_over(at, lambda(k), &
                        & self%constraints%hqq(:, :, k), .false.)
                else
                    call self%work%dm%subtract_q_over(at, lambda(k), &
                        & self%constraints%hqu(:, :, k), .true.)
                end if
            end associate
        end do
    end subroutine fill_momentum_jacobian

    !> The arrays of the ODE form's Jacobian and projection (ode_jacobian, project), sized once
    !> by a formulation that forms them at every step (CVODE's); IDA's leaves them unallocated
    !> (n x 2n and more: a long chain's largest) unless it projects. With dense_jacobian false
    !> the dense Jacobian's n x 2n right-hand sides are left to its first evaluation: a run
    !> whose Newton matrix is sparse forms it by blocks (ode_jacobian_blocks) and never holds
    !> them.
    subroutine size_ode_form(self, dense_jacobian)
        class(equations_type), intent(inout) :: self
        !> Size the dense Jacobian's right-hand sides too (default true)
        logical, intent(in), optional :: dense_jacobian
        logical :: dense

        dense = .true.
        if (present(dense_jacobian)) dense = dense_jacobian
        call self%work%size_ode_form(self%n, self%nc, dense)
    end subroutine size_ode_form

    !> Jacobian of the ODE right-hand side (q, u)' = (u, a(q, u, t)): da/dy = -K^-1 dG/dy with
    !> G = (M a - f - C^T lambda, C a - gamma) at fixed (a, lambda). For position UCONs the
    !> third partials of F in dgamma/dq are not available and are left out.
    subroutine ode_jacobian(self, time, q, u, baumgarte, jac, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: baumgarte
        !> d(q', u')/d(q, u), 2n x 2n
        real(wp), intent(out) :: jac(:, :)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, j

        n = self%n
        call self%work%size_right_hand_sides(n, self%nc, 2*n)
        associate (w => self%work)
            call self%accelerations(time, q, u, baumgarte, w%a, w%lambda, error, second=.true.)
            if (allocated(error)) return
            call self%momentum_jacobian(q, u, w%a, w%lambda, time)
            call take_user_force_error(error)
            if (allocated(error)) return
            call w%dm%scatter_negated(w%rhs_top)
            call jacobian_constraint_rows(self, u, w%a, baumgarte)
            if (self%reads_loop()) then
                ! the algebraic loop's saddle-point matrix, with the forces' partials in a
                ! and lambda at the solution (the loop factored them at its first iterate,
                ! which a force nonlinear in what it reads, |F| of a reaction, makes another
                ! matrix), assembled there by the loop's last evaluation (C too)
                call form_loop_matrix(self, time, q, u, w%a, w%lambda, self%active_rows(), &
                    & reads_constraint_forces(self%model%forces), error)
                if (allocated(error)) return
                call loop_solve(self, error)
            else
                call self%saddle%solve(self%c, w%rhs_top, w%rhs_bottom, 2*n, error)
            end if
        end associate
        if (allocated(error)) return
        jac = 0.0_wp
        do j = 1, n
            jac(j, n + j) = 1.0_wp
        end do
        jac(n + 1:, :) = self%work%rhs_top
    end subroutine ode_jacobian

    !> ode_jacobian's matrix d(q', u')/d(q, u) over a pattern by the coordinates' blocks,
    !> compressed by columns (CVODE's sparse Newton matrix, rollcon_ode_form): column j's rows
    !> (0-based, ascending) rows(starts(j) + 1 : starts(j + 1)) are the coordinates of
    !> coordinate j's block then their rates (the same rows for the rate's column n + j), its
    !> values written in values at the same places. Formed block by block, with no n x 2 n
    !> array: each block's right-hand sides over its own coordinates' columns (dm/dq, dm/du on
    !> its pairs of parts, the constraint rows of its UCONs), solved by the saddle point over
    !> its own rows and parts (saddle_point_type's solve_local), into work%block_top and
    !> block_bottom (the largest block's size). A pattern's block holds every coordinate its
    !> entries can reach (rollcon_problem's coordinate_blocks: the constraints' blocks joined by
    !> the force elements'), so each entry is ode_jacobian's, bit for bit (the same operations
    !> in the same order). Not for the algebraic loop (reads_loop: its (n + nc)-square matrix
    !> is dense anyway): an error there, as for a pattern not by blocks.
    subroutine ode_jacobian_blocks(self, time, q, u, baumgarte, starts, rows, values, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: baumgarte
        !> The pattern (2 n + 1 column starts, 0-based; the rows, 0-based)
        integer, intent(in) :: starts(:), rows(:)
        !> The entries, in the pattern's places
        real(wp), intent(out) :: values(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, j, c, nb, listed, v0

        n = self%n
        call check_ode_pattern(self, starts, rows, error)
        if (allocated(error)) return
        call self%prepare_jacobian_blocks(time, q, u, baumgarte, error)
        if (allocated(error)) return
        associate (w => self%work)
            ! each block at its first coordinate (its column's first row)
            do j = 1, n
                if (rows(starts(j) + 1) + 1 /= j) cycle
                nb = (starts(j + 1) - starts(j))/2
                call self%jacobian_block(rows(starts(j) + 1:starts(j) + nb), u, baumgarte, &
                    & listed, error)
                if (allocated(error)) return
                ! q' = u: the identity in the rates' columns; a's rows the solution
                do c = 1, nb
                    v0 = starts(w%block_coordinates(c))
                    values(v0 + 1:v0 + nb) = 0.0_wp
                    values(v0 + nb + 1:v0 + 2*nb) = w%block_top(:nb, c)
                    v0 = starts(n + w%block_coordinates(c))
                    values(v0 + 1:v0 + nb) = 0.0_wp
                    values(v0 + c) = 1.0_wp
                    values(v0 + nb + 1:v0 + 2*nb) = w%block_top(:nb, nb + c)
                end do
            end do
        end associate
    end subroutine ode_jacobian_blocks

    !> The pattern of ode_jacobian_blocks checked: each coordinate's column and its rate's hold
    !> the same rows, the block's coordinates (whole parts) then their rates, the coordinate
    !> among them.
    subroutine check_ode_pattern(self, starts, rows, error)
        type(equations_type), intent(in) :: self
        integer, intent(in) :: starts(:), rows(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, j, i, nb

        n = self%n
        if (size(starts) /= 2*n + 1) then
            call fatal_error(error, "the ODE form's Jacobian by blocks: a pattern of " &
                & // to_text(size(starts) - 1) // " columns for " // to_text(2*n) &
                & // " states", stat_ucon)
            return
        end if
        do j = 1, n
            nb = (starts(j + 1) - starts(j))/2
            if (nb < 1 .or. 2*nb /= starts(j + 1) - starts(j) .or. starts(n + j + 1) &
                    & - starts(n + j) /= 2*nb .or. mod(nb, 6) /= 0) then
                call pattern_error()
                return
            end if
            if (.not. any(rows(starts(j) + 1:starts(j) + nb) == j - 1)) then
                call pattern_error()
                return
            end if
            do i = 1, nb
                if (rows(starts(j) + nb + i) /= rows(starts(j) + i) + n .or. &
                        & rows(starts(n + j) + i) /= rows(starts(j) + i) .or. &
                        & rows(starts(n + j) + nb + i) /= rows(starts(j) + nb + i)) then
                    call pattern_error()
                    return
                end if
            end do
        end do

    contains

        subroutine pattern_error()
            call fatal_error(error, "the ODE form's Jacobian by blocks: column " // to_text(j) &
                & // "'s pattern is not its coordinates' block and their rates", stat_ucon)
        end subroutine pattern_error

    end subroutine check_ode_pattern

    !> The first step of the ODE form's Jacobian by blocks (ode_jacobian_blocks, and the
    !> independent speeds' by blocks): the accelerations and multipliers at (t, q, u), the
    !> saddle point factored by blocks, the momentum rows' partials; then jacobian_block for
    !> each block. Not for the algebraic loop (reads_loop: its (n + nc)-square matrix is dense
    !> anyway): an error there.
    subroutine prepare_jacobian_blocks(self, time, q, u, baumgarte, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: baumgarte
        type(error_type), allocatable, intent(out) :: error
        integer :: b

        if (self%reads_loop()) then
            call fatal_error(error, "the ODE form's Jacobian by blocks does not serve an " &
                & // "algebraic loop (a force reading accelerations or reactions)", stat_ucon)
            return
        end if
        associate (w => self%work, bl => self%blocks)
            if (.not. allocated(w%coordinate_block)) then
                allocate(w%coordinate_block(self%n), w%block_place(self%n), &
                    & w%block_mark(self%n), w%block_coordinates(self%n), source=0)
                allocate(w%block_list(max(bl%count, 1)), source=0)
                allocate(w%block_seen(max(bl%count, 1)), source=.false.)
                do b = 1, bl%count
                    w%coordinate_block(bl%coordinates(bl%coordinate_start(b): &
                        & bl%coordinate_start(b + 1) - 1)) = b
                end do
            end if
            call self%accelerations(time, q, u, baumgarte, w%a, w%lambda, error, second=.true.)
            if (allocated(error)) return
            call self%momentum_jacobian(q, u, w%a, w%lambda, time)
            call take_user_force_error(error)
        end associate
    end subroutine prepare_jacobian_blocks

    !> One block of ode_jacobian's matrix, after prepare_jacobian_blocks: the block of the
    !> coordinates given 0-based (ascending, whole parts; a block of coordinate_blocks: every
    !> coordinate its entries reach) placed (work%block_coordinates(:nb), block_place, its
    !> constraints' blocks block_list(:listed), ascending), its right-hand sides over its own
    !> columns (block_right_hand_sides) solved by the saddle point over its rows and parts
    !> (solve_local): work%block_top(:nb, :nb) is da/dq and (:nb, nb + 1 : 2 nb) da/du over
    !> the block, ode_jacobian's entries bit for bit. The work arrays grow to a larger block
    !> (allocated by the first evaluations only).
    subroutine jacobian_block(self, coordinates, u, baumgarte, listed, error)
        class(equations_type), intent(inout) :: self
        integer, intent(in) :: coordinates(:)
        real(wp), intent(in) :: u(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: baumgarte
        integer, intent(out) :: listed
        type(error_type), allocatable, intent(out) :: error
        integer :: nb, m, first

        nb = size(coordinates)
        first = coordinates(1) + 1
        call place_block(self, first, coordinates, listed, m)
        associate (w => self%work)
            if (allocated(w%block_top)) then
                if (size(w%block_top, 1) < nb .or. size(w%block_bottom, 1) < max(m, 1)) &
                    & deallocate(w%block_top, w%block_bottom)
            end if
            if (.not. allocated(w%block_top)) allocate(w%block_top(nb, 2*nb), &
                & w%block_bottom(max(m, 1), 2*nb), source=0.0_wp)
            call block_right_hand_sides(self, first, nb, listed, u, w%a, baumgarte)
            call self%saddle%solve_local(self%c, w%block_coordinates(:nb), w%block_place, &
                & w%block_list(:listed), w%block_top, w%block_bottom, 2*nb, error)
        end associate
    end subroutine jacobian_block

    !> The block whose first coordinate is `first`, its coordinates given 0-based (ascending,
    !> whole parts): work%block_coordinates(:size(coordinates)), each one's place there
    !> (block_place, block_mark = first), its constraints' blocks (block_list(:listed),
    !> ascending) and their UCONs (m).
    subroutine place_block(self, first, coordinates, listed, m)
        type(equations_type), intent(inout) :: self
        integer, intent(in) :: first, coordinates(:)
        integer, intent(out) :: listed, m
        integer :: i, b, j

        associate (w => self%work, bl => self%blocks)
            listed = 0
            m = 0
            do i = 1, size(coordinates)
                j = coordinates(i) + 1
                w%block_coordinates(i) = j
                w%block_place(j) = i
                w%block_mark(j) = first
                b = w%coordinate_block(j)
                if (b == 0) cycle
                if (w%block_seen(b)) cycle
                w%block_seen(b) = .true.
                listed = listed + 1
                w%block_list(listed) = b
                m = m + bl%row_start(b + 1) - bl%row_start(b)
            end do
            do i = 1, listed
                w%block_seen(w%block_list(i)) = .false.
            end do
            ! ascending (insertion: a block joins few): their rows, UCON by UCON, in the
            ! order of the slots and rows of the whole model
            do i = 2, listed
                b = w%block_list(i)
                j = i - 1
                do while (j >= 1)
                    if (w%block_list(j) <= b) exit
                    w%block_list(j + 1) = w%block_list(j)
                    j = j - 1
                end do
                w%block_list(j + 1) = b
            end do
        end associate
    end subroutine place_block

    !> The right-hand sides of the block place_block placed (first coordinate `first`, nb
    !> coordinates, `listed` constraints' blocks), over its own columns (its coordinates, then
    !> their rates): work%block_top (nb x 2 nb) -dm/dq, -dm/du on its pairs of parts (-0
    !> elsewhere, as scatter_negated writes), block_bottom (its UCONs x 2 nb) the constraint
    !> rows of jacobian_constraint_rows (0 elsewhere).
    subroutine block_right_hand_sides(self, first, nb, listed, u, a, alpha)
        type(equations_type), intent(inout) :: self
        integer, intent(in) :: first, nb, listed
        real(wp), intent(in) :: u(:), a(:)
        real(wp), intent(in) :: alpha
        integer :: i, e, p, l0, j0, jb, b, r, k, jj, j, x

        associate (w => self%work, dm => self%work%dm, bl => self%blocks)
            w%block_top(:nb, :2*nb) = -0.0_wp
            do i = 1, nb, 6
                p = (w%block_coordinates(i) - 1)/6 + 1
                l0 = i - 1
                if (dm%blocked) then
                    do e = dm%pair_start(p), dm%pair_start(p + 1) - 1
                        jb = 6*(dm%pair_part(e) - 1) + 1
                        ! a pair outside the block (none that the pattern's blocks do not hold,
                        ! but a part a user's routine declared late) is not kept
                        if (w%block_mark(jb) /= first) cycle
                        j0 = w%block_place(jb) - 1
                        w%block_top(l0 + 1:l0 + 6, j0 + 1:j0 + 6) = -dm%block_q(:, :, e)
                        w%block_top(l0 + 1:l0 + 6, nb + j0 + 1:nb + j0 + 6) = -dm%block_u(:, :, e)
                    end do
                else
                    do j = 1, nb
                        jb = w%block_coordinates(j)
                        do x = 1, 6
                            w%block_top(l0 + x, j) = -dm%dq(w%block_coordinates(l0 + x), jb)
                            w%block_top(l0 + x, nb + j) = -dm%du(w%block_coordinates(l0 + x), jb)
                        end do
                    end do
                end if
            end do
            r = 0
            do i = 1, listed
                b = w%block_list(i)
                do x = bl%row_start(b), bl%row_start(b + 1) - 1
                    k = bl%rows(x)
                    r = r + 1
                    w%block_bottom(r, :2*nb) = 0.0_wp
                    do jj = 1, bl%ucon_start(k + 1) - bl%ucon_start(k)
                        j = w%block_place(bl%ucon_coordinates(bl%ucon_start(k) + jj - 1))
                        call constraint_row_partials(self, k, jj, u, a, alpha, &
                            & w%block_bottom(r, j), w%block_bottom(r, nb + j))
                    end do
                end do
            end do
        end associate
    end subroutine block_right_hand_sides

    !> Solve the algebraic loop's saddle-point system (loop_accelerations' factors) for the
    !> Jacobian's right-hand sides work%rhs_top, work%rhs_bottom (2n columns each), in place.
    subroutine loop_solve(self, error)
        type(equations_type), intent(inout) :: self
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: x(:, :)
        logical, allocatable :: active(:)
        integer :: n, k

        n = self%n
        active = self%active_rows()
        allocate(x(n + self%nc, 2*n))
        x(:n, :) = self%work%rhs_top
        x(n + 1:, :) = self%work%rhs_bottom
        do k = 1, self%nc
            if (.not. active(k)) x(n + k, :) = 0.0_wp
        end do
        call solve_factored(self%work%loop_matrix, self%work%loop_pivots, x, error)
        if (allocated(error)) return
        self%work%rhs_top = x(:n, :)
        self%work%rhs_bottom = x(n + 1:, :)
    end subroutine loop_solve

    !> Constraint rows of the Jacobian's right-hand sides, -d(C a - gamma)/d(q, u) at fixed a,
    !> into rhs_bottom.
    subroutine jacobian_constraint_rows(self, u, a, alpha)
        type(equations_type), intent(inout) :: self
        real(wp), intent(in) :: u(:), a(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: alpha
        integer :: n, k, j, jj

        n = self%n
        ! each UCON's row over its own coordinates; the rest are zeros (-(0) as the dense sums
        ! gave, written as +0 here)
        self%work%rhs_bottom = 0.0_wp
        do k = 1, self%nc
            do jj = 1, self%blocks%ucon_start(k + 1) - self%blocks%ucon_start(k)
                j = self%blocks%ucon_coordinates(self%blocks%ucon_start(k) + jj - 1)
                call constraint_row_partials(self, k, jj, u, a, alpha, &
                    & self%work%rhs_bottom(k, j), self%work%rhs_bottom(k, n + j))
            end do
        end do
    end subroutine jacobian_constraint_rows

    !> Row k's entries of -d(C a - gamma)/d(q, u) at fixed a in its jj-th coordinate (of its own,
    !> the blocks' ucon_coordinates): of_q in the coordinate, of_u in its rate.
    subroutine constraint_row_partials(self, k, jj, u, a, alpha, of_q, of_u)
        type(equations_type), intent(in) :: self
        integer, intent(in) :: k, jj
        real(wp), intent(in) :: u(:), a(:)
        !> Baumgarte rate in effect [1/s], 0 without Baumgarte terms
        real(wp), intent(in) :: alpha
        real(wp), intent(out) :: of_q, of_u

        associate (cs => self%constraints, at => self%blocks%ucon_coordinates( &
                & self%blocks%ucon_start(k):self%blocks%ucon_start(k + 1) - 1))
            if (self%model%ucons(k)%holonomic) then
                of_q = -local_dot(cs%hqq(:, jj, k), a, at) &
                    & - 2.0_wp*alpha*(local_dot(cs%hqq(:, jj, k), u, at) &
                    & + cs%dt_grad_q(jj, k)) - alpha**2*cs%grad_q_local(jj, k)
                of_u = -2.0_wp*local_dot(cs%hqq(:, jj, k), u, at) &
                    & - 2.0_wp*cs%dt_grad_q(jj, k) &
                    & - 2.0_wp*alpha*cs%grad_q_local(jj, k)
            else
                ! C a - gamma = dF/du a + dF/dq u + dF/dt + alpha F
                of_q = -(local_dot(cs%hqu(jj, :, k), a, at) &
                    & + local_dot(cs%hqq(:, jj, k), u, at) + cs%dt_grad_q(jj, k) &
                    & + alpha*cs%grad_q_local(jj, k))
                of_u = -(cs%grad_q_local(jj, k) &
                    & + local_dot(cs%hqu(:, jj, k), u, at) + cs%dt_grad_u(jj, k) &
                    & + alpha*cs%grad_u_local(jj, k))
            end if
        end associate
    end subroutine constraint_row_partials

    !> Correction (dq, du) that puts (q, u) back on the constraints: a mass-weighted least
    !> change, one Newton step for position UCONs, exact for velocity UCONs (linear in u).
    subroutine project(self, time, q, u, dq, du, error)
        class(equations_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        real(wp), intent(out) :: dq(:), du(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: n, k

        n = self%n
        dq = 0.0_wp
        ! (sized by size_ode_form in CVODE's forms; IDA's rebasing projects on a first use)
        call self%work%size_right_hand_sides(n, self%nc, 1)
        if (self%nh > 0) then
            call self%constraints%evaluate(self%model, time, q, u, need_value + need_first, error)
            if (allocated(error)) return
            call self%assemble(time, q, u)
            call self%constraint_matrix()
            ! only the active position UCONs constrain q: [M, -G^T; G, 0] (dq, nu) = (0, -F_h),
            ! G their rows of C (dF/dq); the other rows (velocity UCONs, rows set aside as
            ! repeating others, a flying contact's height) are set aside in the factorisation
            ! (rollcon_saddle_point: their rows and columns of S those of the identity, their
            ! multipliers zero), so G is solved by the constraints' blocks with C as held
            associate (held => self%work%projection_rows)
                do k = 1, self%nc
                    held(k) = self%model%holonomic_number(k) > 0 .and. self%active_rows_of(k)
                    self%work%rhs_bottom(k, 1) = 0.0_wp
                    if (held(k)) self%work%rhs_bottom(k, 1) = -self%constraints%value(k)
                end do
                call self%saddle%factor(self%mass, self%c, self%nc, error, active=held)
            end associate
            if (allocated(error)) return
            self%work%rhs_top(:, 1) = 0.0_wp
            call self%saddle%solve(self%c, self%work%rhs_top(:, 1), self%work%rhs_bottom(:, 1), &
                & 1, error)
            if (allocated(error)) return
            dq = self%work%rhs_top(:, 1)
        end if
        self%work%q = q + dq
        call self%constraints%evaluate(self%model, time, self%work%q, u, need_value + need_first &
            & + need_time, error)
        if (allocated(error)) return
        call self%assemble(time, self%work%q, u)
        call self%constraint_matrix()
        associate (cs => self%constraints)
            do k = 1, self%nc
                if (self%model%ucons(k)%holonomic) then
                    self%work%rhs_bottom(k, 1) = -(cs%grad_q_dot(k, u) + cs%dt(k))
                else
                    self%work%rhs_bottom(k, 1) = -cs%value(k)
                end if
            end do
        end associate
        if (self%masked()) then
            call self%saddle%factor(self%mass, self%c, self%nc, error, &
                & active=self%active_rows())
        else
            call self%saddle%factor(self%mass, self%c, self%nc, error)
        end if
        if (allocated(error)) return
        self%work%rhs_top(:, 1) = 0.0_wp
        call self%saddle%solve(self%c, self%work%rhs_top(:, 1), self%work%rhs_bottom(:, 1), 1, &
            & error)
        if (allocated(error)) return
        du = self%work%rhs_top(:, 1)
    end subroutine project

    !> u^T H u with H over a UCON's own coordinates (ascending; h(i, j) belongs to the i-th
    !> and j-th) and u_local u on them (its first count), summed as the dense quadratic form.
    pure function local_quadratic_form(h, u_local, count) result(value)
        real(wp), contiguous, intent(in) :: h(:, :), u_local(:)
        !> Number of the UCON's own coordinates
        integer, intent(in) :: count
        real(wp) :: value
        real(wp) :: column, next
        integer :: i, j

        ! local_dot of each column, written out (a call per column cost more than its sum),
        ! two columns in one pass over u_local: each column's sum and their order in value
        ! as one column at a time
        value = 0.0_wp
        do j = 1, count - 1, 2
            column = 0.0_wp
            next = 0.0_wp
            do i = 1, count
                column = column + h(i, j)*u_local(i)
                next = next + h(i, j + 1)*u_local(i)
            end do
            value = value + u_local(j)*column
            value = value + u_local(j + 1)*next
        end do
        if (mod(count, 2) == 1) then
            column = 0.0_wp
            do i = 1, count
                column = column + h(i, count)*u_local(i)
            end do
            value = value + u_local(count)*column
        end if
    end function local_quadratic_form

    !> h . x over a UCON's own coordinates, x on them (gathered): the first count terms summed
    !> in order from zero, as local_dot sums them.
    pure function gathered_dot(h, x, count) result(total)
        real(wp), contiguous, intent(in) :: h(:), x(:)
        !> Number of the UCON's own coordinates
        integer, intent(in) :: count
        real(wp) :: total
        integer :: i

        total = 0.0_wp
        do i = 1, count
            total = total + h(i)*x(i)
        end do
    end function gathered_dot

    !> Gravitational potential energy, sum of -m g . r over the parts [J] (zero at ground's
    !> origin).
    pure function potential_energy(self, q) result(e)
        class(equations_type), intent(in) :: self
        real(wp), intent(in) :: q(:)
        real(wp) :: e
        integer :: p, i0

        e = 0.0_wp
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            e = e - self%model%parts(p)%mass*dot_product(self%model%gravity, q(i0 + 1:i0 + 3))
        end do
    end function potential_energy

    !> Total energy: kinetic plus gravitational potential [J].
    pure function energy(self, q, u) result(e)
        class(equations_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        real(wp) :: e
        integer :: p, i0

        e = 0.0_wp
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            e = e + kinetic_energy(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6)) &
                & - self%model%parts(p)%mass*dot_product(self%model%gravity, q(i0 + 1:i0 + 3))
        end do
    end function energy

    !> The change of the energy (kinetic plus gravitational potential) that an error of the
    !> integrator's tolerance in every coordinate and rate could make [J]: the sum over them of
    !> |dE/dy_i| (rtol |y_i| + atol), the weights of the integrators' error test (rtol |y_i| +
    !> atol for each component y_i of the state). Never 0 under gravity (dE/dZ = m g).
    pure function energy_tolerance(self, q, u, rtol, atol) result(e)
        class(equations_type), intent(in) :: self
        real(wp), intent(in) :: q(:), u(:)
        !> The run's relative and absolute tolerances
        real(wp), intent(in) :: rtol, atol
        real(wp) :: e
        real(wp) :: d_q(6), d_u(6)
        integer :: p, i0

        e = 0.0_wp
        do p = 1, size(self%model%parts)
            i0 = 6*(p - 1)
            call energy_gradient(self%model%parts(p), q(i0 + 1:i0 + 6), u(i0 + 1:i0 + 6), &
                & self%model%gravity, d_q, d_u)
            e = e + sum(abs(d_q)*(rtol*abs(q(i0 + 1:i0 + 6)) + atol)) &
                & + sum(abs(d_u)*(rtol*abs(u(i0 + 1:i0 + 6)) + atol))
        end do
    end function energy_tolerance

    !> Constraint force on part p, ground components [N]: the translational rows of C^T lambda,
    !> with C (by rows over each UCON's coordinates) as left by the last accelerations call.
    pure function constraint_force(self, p, lambda) result(force)
        class(equations_type), intent(in) :: self
        integer, intent(in) :: p
        real(wp), intent(in) :: lambda(:)
        real(wp) :: force(3)
        real(wp) :: translational(3)
        integer :: k

        force = 0.0_wp
        do k = 1, size(lambda)
            call self%c%gather(k, 6*(p - 1) + 1, translational)
            force = force + lambda(k)*translational
        end do
    end function constraint_force

    !> Constraint force on part p, ground components [N], from its accelerations: m a minus
    !> gravity and the applied forces (Newton's law for the centre of mass). No UCOSUB call
    !> and no solve: for event functions given the accelerations by the integrator.
    pure function reaction_from_accelerations(self, p, time, q, u, a) result(force)
        class(equations_type), intent(in) :: self
        !> Part index
        integer, intent(in) :: p
        !> Time [s]
        real(wp), intent(in) :: time
        !> Coordinates, rates and accelerations of the whole system
        real(wp), intent(in) :: q(:), u(:), a(:)
        real(wp) :: force(3)
        real(wp) :: applied(3), moment(3)
        integer :: i0

        i0 = 6*(p - 1)
        call force_and_moment(self%model%forces, p, time, q, u, applied, moment)
        force = self%model%parts(p)%mass*(a(i0 + 1:i0 + 3) - self%model%gravity) - applied
    end function reaction_from_accelerations

    !> Free what the saddle-point solve holds outside Fortran's memory (KLU's factors of large
    !> blocks); called when the model's run is done.
    subroutine release_equations(self)
        class(equations_type), intent(inout) :: self

        call self%saddle%release()
    end subroutine release_equations

end module rollcon_equations
