! SPDX-License-Identifier: MIT
!> How to integrate a run: the one settings type that a scene's &run, a dataset's INTEGRATOR and
!> SIMULATE, a study's parameters and the benchmark's methods all fill (their keys: the table of
!> rollcon_run_keys), with the integer codes of its choices and the settings in words.
module rollcon_run_settings
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    implicit none
    private

    public :: run_settings_type
    public :: formulation_cvode, formulation_ida, formulation_speeds, method_bdf, method_adams
    public :: drift_none, drift_projection, drift_baumgarte, jacobian_analytic, jacobian_dq, &
        & jacobian_none
    public :: linear_dense, linear_sparse, linear_auto
    public :: analysis_dynamic, analysis_kinematic, analysis_static

    !> Formulations: CVODE on the ODE form, IDA on the DAE form, CVODE on the coordinates and
    !> independent speeds (docs/design.md §4)
    integer, parameter :: formulation_cvode = 1, formulation_ida = 2, formulation_speeds = 3
    !> CVODE's linear multistep methods
    integer, parameter :: method_bdf = 1, method_adams = 2
    !> Drift control of the ODE form: none, projection onto the constraints, Baumgarte
    integer, parameter :: drift_none = 0, drift_projection = 1, drift_baumgarte = 2
    !> Newton matrices: from the UCOSUBs' partials, or SUNDIALS' difference quotients; or none:
    !> CVODE's fixed-point (functional) iteration instead of Newton's method
    integer, parameter :: jacobian_analytic = 1, jacobian_dq = 2, jacobian_none = 0
    !> The Newton matrices: dense LU (LAPACK-style, SUNDIALS' dense solver), sparse LU
    !> (SUNDIALS' KLU) over the entries the model's structure leaves (docs/design.md §4), or
    !> whichever of the two the matrix's size and entries make cheaper (sparse_newton)
    integer, parameter :: linear_dense = 1, linear_sparse = 2, linear_auto = 3
    !> Analyses (SIMULATE/DYNAMIC, /KINEMATIC, /STATIC): run_settings_type%analysis
    integer, parameter :: analysis_dynamic = 1, analysis_kinematic = 2, analysis_static = 3
    !> linear_auto's choice: KLU from this many states on, when the entries kept are at most
    !> auto_sparse_fill of the matrix. Measured (docs/benchmark.md "Cost as models grow"):
    !> KLU and the dense LU cost the same per step on one disk (15 states on IDA) and on one
    !> link (22), KLU 10 to 25 % less from 24 to 44 states; on IDA's matrices 74 % full
    !> (data/bicycle.adm, 86 states, and a chain of 4 links, 88, under the broader pattern of
    !> every state of neighbouring parts; IDA's exact one is 23 % full) KLU's whole run is 21
    !> and 29 % cheaper; on a
    !> full matrix (CVODE's on a chain, one block) KLU costs the same at 48 states and more
    !> from 96 on (60 % more at 768). 32 keeps every shipped scene and dataset of one or two
    !> parts (at most 30 states) on the dense matrix
    integer, parameter :: auto_sparse_states = 32
    real(wp), parameter :: auto_sparse_fill = 0.8_wp

    !> How to integrate, and over which times
    type :: run_settings_type
        !> End time and output step [s]
        real(wp) :: end_time = 10.0_wp, output_step = 0.01_wp
        !> The output times after the start [s], ascending, the last at end_time, when they
        !> are not every output_step (a command file's several SIMULATE commands, each with its
        !> own: rollcon_adm_run); unallocated: every output_step
        real(wp), allocatable :: output_times(:)
        !> formulation_ida (DAE), formulation_cvode (ODE) or formulation_speeds (ODE in
        !> independent speeds)
        integer :: formulation = formulation_ida
        !> method_bdf or method_adams (CVODE only: 'cvode' and 'maggi')
        integer :: method = method_bdf
        !> drift_projection, drift_baumgarte or drift_none (the last two CVODE only)
        integer :: drift = drift_projection
        !> jacobian_analytic, jacobian_dq, or jacobian_none (fixed-point iteration, CVODE only)
        integer :: jacobian = jacobian_analytic
        !> linear_auto, linear_dense or linear_sparse (the last with an analytic Jacobian only)
        integer :: linear_solver = linear_auto
        !> Relative and absolute tolerances [-, state units]
        real(wp) :: rtol = 1.0e-8_wp, atol = 1.0e-10_wp
        !> Baumgarte rate alpha [1/s]: F' = -alpha F (velocity), F'' = -2 alpha F' - alpha^2 F
        real(wp) :: baumgarte_rate = 10.0_wp
        !> Most internal steps per output interval
        integer :: max_steps = 500000
        !> The analysis the output times are for: analysis_dynamic (integration),
        !> analysis_kinematic (a model with no degree of freedom, solved at each output time) or
        !> analysis_static (the static equilibrium alone, one row)
        integer :: analysis = analysis_dynamic
        !> A static equilibrium at the start, before the dynamic run (SIMULATE/STATIC then
        !> SIMULATE/DYNAMIC): the dynamic run starts from it at rest
        logical :: static_first = .false.
        !> The static equilibrium's limits (ADAMS's EQUILIBRIUM statement and its defaults):
        !> ERROR, the largest relative correction of a converged iteration [-]; IMBALANCE, the
        !> largest force [N] and moment [N m] left unbalanced; TLIMIT and ALIMIT, the largest
        !> translation [m] and angle [rad] an iteration may move a coordinate; MAXIT, the most
        !> Newton iterations
        real(wp) :: equilibrium_error = 1.0e-4_wp, equilibrium_imbalance = 1.0e-4_wp
        real(wp) :: equilibrium_tlimit = 20.0_wp, equilibrium_alimit = 0.17453292519943295_wp
        integer :: equilibrium_maxit = 25
    contains
        procedure :: baumgarte
        procedure :: analytic_jacobian
        procedure :: uses_cvode
        procedure :: sparse_newton
        procedure :: text
    end type run_settings_type

contains

    !> The Baumgarte rate in effect [1/s]: baumgarte_rate with drift_baumgarte, else 0.
    pure function baumgarte(self) result(alpha)
        class(run_settings_type), intent(in) :: self
        real(wp) :: alpha

        alpha = 0.0_wp
        if (self%drift == drift_baumgarte) alpha = self%baumgarte_rate
    end function baumgarte

    !> Newton matrices from the UCOSUBs' partials (else SUNDIALS' difference quotients).
    pure logical function analytic_jacobian(self)
        class(run_settings_type), intent(in) :: self

        analytic_jacobian = self%jacobian == jacobian_analytic
    end function analytic_jacobian

    !> The Newton matrix of `states` states, `entries` of them kept by the model's structure,
    !> is solved by KLU: linear_sparse, or linear_auto on a matrix of at least
    !> auto_sparse_states states at most auto_sparse_fill full; always with the analytic
    !> Jacobian (difference quotients fill a dense matrix).
    pure logical function sparse_newton(self, states, entries)
        class(run_settings_type), intent(in) :: self
        integer, intent(in) :: states, entries

        select case (self%linear_solver)
        case (linear_sparse)
            sparse_newton = .true.
        case (linear_auto)
            sparse_newton = states >= auto_sparse_states .and. &
                & real(entries, wp) <= auto_sparse_fill*real(states, wp)**2
        case default
            sparse_newton = .false.
        end select
        sparse_newton = sparse_newton .and. self%analytic_jacobian()
    end function sparse_newton

    !> CVODE integrates the run (the ODE forms, 'cvode' and 'maggi'); else IDA.
    pure logical function uses_cvode(self)
        class(run_settings_type), intent(in) :: self

        uses_cvode = self%formulation == formulation_cvode &
            & .or. self%formulation == formulation_speeds
    end function uses_cvode

    !> The integrator settings in words: "IDA (DAE form, index 2), analytic Jacobian, rtol
    !> 1e-8, atol 1e-10"; "static equilibrium, then IDA ..." after a SIMULATE/STATIC; a static
    !> or kinematic analysis alone integrates nothing, and says so.
    function text(self) result(words)
        class(run_settings_type), intent(in) :: self
        character(len=:), allocatable :: words
        character(len=*), parameter :: drifts(0:2) = [character(len=10) :: "none", &
            & "projection", "baumgarte"]

        if (self%uses_cvode()) then
            words = "CVODE (" // trim(merge("ODE form          ", "independent speeds", &
                & self%formulation == formulation_cvode)) // ", " &
                & // trim(merge("Adams", "BDF  ", self%method == method_adams)) // ", drift " &
                & // trim(drifts(self%drift)) // ")"
        else
            words = "IDA (DAE form, index 2)"
        end if
        if (self%jacobian == jacobian_none) then
            words = words // ", fixed-point iteration (no Jacobian)"
        else
            words = words // ", " // trim(merge("analytic", "dq      ", &
                & self%analytic_jacobian())) // " Jacobian"
        end if
        words = words // ", rtol " // to_text(self%rtol) // ", atol " // to_text(self%atol)
        if (self%linear_solver == linear_sparse) words = words // ", sparse Newton matrix (KLU)"
        select case (self%analysis)
        case (analysis_static)
            words = "static equilibrium (Newton's method on the forces at rest; no integrator)"
        case (analysis_kinematic)
            words = "kinematic analysis (positions, velocities and accelerations solved at " &
                & // "each output time; no integrator)"
        case default
            if (self%static_first) words = "static equilibrium, then " // words
        end select
    end function text

end module rollcon_run_settings
