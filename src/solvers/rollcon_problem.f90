! SPDX-License-Identifier: MIT
!> What the integrators' callbacks work on: the model (held here, once), its equations, solver
!> settings, event limits, scratch arrays, and the first failure a callback met (callbacks
!> never print or stop).
module rollcon_problem
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_model, only : model_type
    use rollcon_body, only : part_type
    use rollcon_force, only : applied_force_type
    use rollcon_equations, only : equations_type
    use rollcon_constraints, only : need_value
    implicit none
    private

    public :: problem_type, solver_settings_type, event_settings_type
    public :: formulation_cvode, formulation_ida, method_bdf, method_adams
    public :: drift_none, drift_projection, drift_baumgarte

    !> Formulations: CVODE on the ODE form, IDA on the DAE form
    integer, parameter :: formulation_cvode = 1, formulation_ida = 2
    !> CVODE's linear multistep methods
    integer, parameter :: method_bdf = 1, method_adams = 2
    !> Drift control of the ODE form: none, projection onto the constraints, Baumgarte
    integer, parameter :: drift_none = 0, drift_projection = 1, drift_baumgarte = 2
    !> How to integrate
    type :: solver_settings_type
        integer :: formulation = formulation_ida
        integer :: method = method_bdf
        !> Newton matrix from the UCOSUB's partials (true) or SUNDIALS' difference quotients
        logical :: analytic_jacobian = .true.
        !> Relative and absolute tolerances [-, state units]
        real(wp) :: rtol = 1.0e-8_wp, atol = 1.0e-10_wp
        !> Most internal steps per output interval
        integer :: max_steps = 500000
        !> Drift control of the ODE form: drift_none, drift_projection or drift_baumgarte
        integer :: drift = drift_projection
        !> Baumgarte rate alpha [1/s]: F' = -alpha F (velocity), F'' = -2 alpha F' - alpha^2 F
        real(wp) :: baumgarte_rate = 10.0_wp
    contains
        procedure :: baumgarte
    end type solver_settings_type

    !> What a run watches: when to stop it early, and the watched contact of a disk scene
    type :: event_settings_type
        !> Stop when any part's theta comes within theta_min of flat on either side, 0 or pi:
        !> one root of sin(theta) - sin(theta_min) per part [rad] (disabled when negative)
        real(wp) :: theta_min = -1.0_wp
        !> At the theta limit, re-base the part on its principal axes turned by 90 degrees and
        !> go on (docs/rebasing.md) instead of stopping: a dataset's model. A disk scene keeps
        !> its theta_min as a stop (false, the default).
        logical :: rebase = .false.
        !> The model has a watched contact (the disk scenes): the part `part` touches the
        !> ground as a rim of radius contact_radius. Then, and only then, the rows carry the
        !> contact columns, the height residual is measured and the lift-off may be watched.
        logical :: has_contact = .false.
        !> Index (model order) of the part in contact
        integer :: part = 1
        !> Stop when the normal (ground Z) component of the constraint force on the part in
        !> contact falls below -liftoff_force: a real lift-off, not the rounding noise of a
        !> force that is zero (only with has_contact)
        logical :: stop_on_liftoff = .false.
        !> Lift-off threshold [N] >= 0, a small fraction of the scene's force scale
        real(wp) :: liftoff_force = 0.0_wp
        !> Rim radius of the part in contact [m] > 0: its height residual Z - R sin(theta)
        !> is the position-level form of a disk's contact
        real(wp) :: contact_radius = 0.0_wp
    contains
        procedure :: watches_liftoff
    end type event_settings_type

    !> The integrators' user data. `eq` refers to `model`: a problem is set up in place (init)
    !> in a variable with the target attribute, and is not copied afterwards.
    type :: problem_type
        !> The model, set up: the one copy
        type(model_type) :: model
        !> Its equations (pointing at `model`)
        type(equations_type) :: eq
        type(solver_settings_type) :: settings
        type(event_settings_type) :: events
        !> Scratch: accelerations and multipliers
        real(wp), allocatable :: a(:), lambda(:)
        !> The first failure inside a callback, for the caller to report
        type(error_type), allocatable :: failure
        !> Event-function evaluations so far (the benchmark's per-part costs)
        integer :: root_evaluations = 0
        !> For each part (model order), the number of the principal basis its coordinates are
        !> in: 0 for its own axes, then one more at each re-basing of the run
        integer, allocatable :: bases(:)
        !> The parts and forces in their own principal axes, as prepare found them: a run that
        !> re-based parts leaves the model turned (its last state is in the turned bases);
        !> the next prepare gives the model back its own axes
        type(part_type), allocatable :: own_parts(:)
        type(applied_force_type), allocatable :: own_forces(:)
    contains
        procedure :: init
        procedure :: prepare
        procedure :: accelerations
        procedure :: ucon_count
        procedure :: ucon_id
        procedure :: constraint_values
        procedure :: ode_rhs
        procedure :: root_count
        procedure :: theta_root_part
        procedure :: root_values
        procedure :: keep_failure
        procedure :: ucons_do_no_work
    end type problem_type

contains

    !> The Baumgarte rate in effect [1/s]: baumgarte_rate with drift_baumgarte, else 0.
    pure function baumgarte(self) result(alpha)
        class(solver_settings_type), intent(in) :: self
        real(wp) :: alpha

        alpha = 0.0_wp
        if (self%drift == drift_baumgarte) alpha = self%baumgarte_rate
    end function baumgarte

    !> Keep a model that setup_model has prepared (the problem's copy is the only one the
    !> run uses: the equations refer to it) and set up its equations on it.
    subroutine init(self, model)
        class(problem_type), intent(inout), target :: self
        type(model_type), intent(in) :: model

        self%model = model
        call self%eq%init(self%model)
    end subroutine init

    !> Accelerations and multipliers at (t, q, u) into self%a and self%lambda, with the
    !> settings' drift control.
    subroutine accelerations(self, time, q, u, error)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        type(error_type), allocatable, intent(out) :: error

        call self%eq%accelerations(time, q, u, self%settings%baumgarte(), self%a, self%lambda, &
            & error)
    end subroutine accelerations

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

    !> Each UCON's residual F_k at the last evaluation.
    pure function constraint_values(self) result(values)
        class(problem_type), intent(in) :: self
        real(wp) :: values(self%eq%nc)

        values = self%eq%constraints%value
    end function constraint_values

    !> Size scratch arrays (once); every part in its own principal axes (basis 0).
    subroutine prepare(self)
        class(problem_type), intent(inout) :: self

        if (allocated(self%bases) .and. allocated(self%own_parts)) then
            if (any(self%bases /= 0)) then
                self%model%parts = self%own_parts
                self%model%forces = self%own_forces
            end if
        end if
        if (self%events%rebase) then
            self%own_parts = self%model%parts
            self%own_forces = self%model%forces
        end if

        if (allocated(self%a)) deallocate(self%a)
        if (allocated(self%lambda)) deallocate(self%lambda)
        allocate(self%a(self%eq%n), self%lambda(self%eq%nc), source=0.0_wp)
        if (allocated(self%bases)) deallocate(self%bases)
        allocate(self%bases(size(self%model%parts)), source=0)
    end subroutine prepare

    !> y' = (u, a) for y = (q, u); ierr 0 on success, -1 on failure (kept in self%failure).
    function ode_rhs(self, time, y, ydot) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, y(:)
        real(wp), intent(out) :: ydot(:)
        integer :: ierr
        type(error_type), allocatable :: error

        associate (n => self%eq%n)
            call self%accelerations(time, y(:n), y(n + 1:), error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            ydot(:n) = y(n + 1:)
            ydot(n + 1:) = self%a
        end associate
    end function ode_rhs

    !> The lift-off is watched: asked for, and the model has a contact.
    pure logical function watches_liftoff(self)
        class(event_settings_type), intent(in) :: self

        watches_liftoff = self%has_contact .and. self%stop_on_liftoff
    end function watches_liftoff

    !> Number of event functions: one theta limit per part (when theta_min >= 0), then the
    !> lift-off of the part in contact (when watched).
    pure integer function root_count(self)
        class(problem_type), intent(in) :: self

        root_count = 0
        if (self%events%theta_min >= 0.0_wp) root_count = size(self%model%parts)
        if (self%events%watches_liftoff()) root_count = root_count + 1
    end function root_count

    !> Index (model order) of the part whose theta limit is event function `root`; 0 when
    !> `root` is the lift-off.
    pure integer function theta_root_part(self, root)
        class(problem_type), intent(in) :: self
        integer, intent(in) :: root

        theta_root_part = 0
        if (self%events%theta_min >= 0.0_wp .and. root <= size(self%model%parts)) &
            & theta_root_part = root
    end function theta_root_part

    !> Event functions at (t, q, u), root_count() of them: for every part p,
    !> sin(theta_p) - sin(theta_min), which guards both sides of flat; then the normal force
    !> on the part in contact + liftoff_force. The normal force comes from the multipliers
    !> when a DAE state gives them (IDA), else from the accelerations when the integrator
    !> gives them (CVODE's interpolating polynomial: no UCOSUB call and no solve), else from a
    !> saddle-point solve as in a right-hand side.
    function root_values(self, time, q, u, g, lambda, a) result(ierr)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:), u(:)
        !> Event function values, root_count() of them
        real(wp), intent(out) :: g(:)
        !> Multipliers at (t, q, u), when known
        real(wp), intent(in), optional :: lambda(:)
        !> Accelerations at (t, q, u), when known
        real(wp), intent(in), optional :: a(:)
        integer :: ierr
        type(error_type), allocatable :: error
        real(wp) :: force(3)
        integer :: p, nroots

        ierr = 0
        self%root_evaluations = self%root_evaluations + 1
        nroots = 0
        if (self%events%theta_min >= 0.0_wp) then
            do p = 1, size(self%model%parts)
                g(p) = sin(q(6*(p - 1) + 5)) - sin(self%events%theta_min)
            end do
            nroots = size(self%model%parts)
        end if
        if (.not. self%events%watches_liftoff()) return
        if (present(lambda)) then
            ! only C is needed: first partials, no saddle-point solve
            call self%eq%constraint_matrix_at(time, q, u, error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            force = self%eq%constraint_force(self%events%part, lambda)
        else if (present(a)) then
            force = self%eq%reaction_from_accelerations(self%events%part, time, q, u, a)
        else
            call self%accelerations(time, q, u, error)
            ierr = self%keep_failure(error)
            if (ierr /= 0) return
            force = self%eq%constraint_force(self%events%part, self%lambda)
        end if
        g(nroots + 1) = force(3) + self%events%liftoff_force
    end function root_values

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

    !> True when the UCONs do no work at the start (t, q), so that they leave the energy
    !> alone: every velocity UCON's F vanishes at zero rates (F = C(q) u: every term carries a
    !> rate, as for a disk rolling on fixed ground) and no position UCON changes with time alone
    !> (F at t and at t + 1 s equal). A moving constraint (a turntable, a driven motion) fails
    !> this, and its constraint forces do work. The check is made at the one state given; a
    !> UCOSUB that cannot be evaluated at zero rates leaves the answer true (the run itself
    !> then reports its error). The UCONs are evaluated, so call this before the run's first
    !> evaluation.
    function ucons_do_no_work(self, time, q) result(no_work)
        class(problem_type), intent(inout) :: self
        real(wp), intent(in) :: time, q(:)
        logical :: no_work
        !> A homogeneous form gives exact zeros (every term is a product with a rate that is 0),
        !> and a time-free one the same value twice; a moving constraint's terms are of the size
        !> of its motion, many orders above this
        real(wp), parameter :: tol_work = 1.0e-12_wp
        real(wp) :: still(size(q)), now(self%eq%nc)
        type(error_type), allocatable :: error
        integer :: k

        no_work = .true.
        if (self%eq%nc == 0) return
        still = 0.0_wp
        call self%eq%constraints%evaluate(self%model, time, q, still, need_value, error)
        if (allocated(error)) return
        now = self%eq%constraints%value
        call self%eq%constraints%evaluate(self%model, time + 1.0_wp, q, still, need_value, error)
        if (allocated(error)) return
        do k = 1, self%eq%nc
            if (self%model%ucons(k)%holonomic) then
                if (abs(self%eq%constraints%value(k) - now(k)) > tol_work) no_work = .false.
            else
                if (abs(now(k)) > tol_work .or. abs(self%eq%constraints%value(k)) > tol_work) &
                    & no_work = .false.
            end if
        end do
    end function ucons_do_no_work

end module rollcon_problem
