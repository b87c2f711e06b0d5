! SPDX-License-Identifier: MIT
!> The one table of the run settings' keys (rollcon_run_settings): a scene's &run keys, a
!> dataset's INTEGRATOR and SIMULATE keywords and a study's run parameters are all read and
!> checked against it, and its rule on combining the choices (run_choice_rule) is the only one.
!> A new run setting is a component of run_settings_type and one line here.
module rollcon_run_keys
    use rollcon_kinds, only : wp
    use rollcon_run_settings, only : run_settings_type, formulation_cvode, formulation_ida, &
        & formulation_speeds, method_bdf, method_adams, drift_none, drift_projection, &
        & drift_baumgarte, jacobian_analytic, jacobian_dq, jacobian_none, linear_dense, &
        & linear_sparse, linear_auto
    use rollcon_keys, only : key_type, option_type, real_key, integer_key, choice_key, &
        & option_code, option_name
    implicit none
    private

    public :: bind_run_keys, run_choice_rule, choice_code, choice_name
    public :: time_min, time_max

    !> Longest time [s] (about 32 years) and shortest (1 ns) a run, step or pulse may take
    real(wp), parameter :: time_max = 1.0e9_wp, time_min = 1.0e-9_wp
    !> Tightest rtol: SUNDIALS cannot meet a relative accuracy near the 2.2e-16 of doubles
    real(wp), parameter :: rtol_min = 1.0e-15_wp
    !> atol [state units]: below 1e-20 the error weights 1/atol approach overflow in the
    !> weighted norms' squares; above 1e3 nothing is resolved
    real(wp), parameter :: atol_min = 1.0e-20_wp, atol_max = 1.0e3_wp
    !> Largest Baumgarte rate [1/s]: its square multiplies the drift
    real(wp), parameter :: baumgarte_max = 1.0e6_wp
    !> The group the keys belong to in a scene
    character(len=*), parameter :: run_group = "run"

contains

    !> The keys of run settings, group "run", each pointing into settings (which must outlive
    !> the table).
    function bind_run_keys(settings) result(keys)
        type(run_settings_type), target, intent(inout) :: settings
        type(key_type), allocatable :: keys(:)

        associate (r => settings)
            keys = [ &
                & real_key(run_group, "end_time", r%end_time, "s", time_min, time_max), &
                & real_key(run_group, "output_step", r%output_step, "s", time_min, time_max), &
                & choice_key(run_group, "formulation", r%formulation, &
                & [option_type("ida", formulation_ida), option_type("cvode", formulation_cvode), &
                & option_type("maggi", formulation_speeds)]), &
                & choice_key(run_group, "method", r%method, [option_type("bdf", method_bdf), &
                & option_type("adams", method_adams)]), &
                & choice_key(run_group, "drift", r%drift, [option_type("projection", &
                & drift_projection), option_type("baumgarte", drift_baumgarte), &
                & option_type("none", drift_none)]), &
                & choice_key(run_group, "jacobian", r%jacobian, [option_type("analytic", &
                & jacobian_analytic), option_type("dq", jacobian_dq), option_type("none", &
                & jacobian_none)]), &
                & choice_key(run_group, "linear_solver", r%linear_solver, [option_type("auto", &
                & linear_auto), option_type("dense", linear_dense), option_type("sparse", &
                & linear_sparse)]), &
                & real_key(run_group, "rtol", r%rtol, "", rtol_min, 1.0_wp, upper_open=.true.), &
                & real_key(run_group, "atol", r%atol, "", atol_min, atol_max), &
                & real_key(run_group, "baumgarte_rate", r%baumgarte_rate, "1/s", 0.0_wp, &
                & baumgarte_max, .true.), &
                & integer_key(run_group, "max_steps", r%max_steps, 1, huge(1))]
        end associate
    end function bind_run_keys

    !> Code of the option named word (any case) of the run choice key name ('formulation',
    !> 'cvode'), 0 when none.
    function choice_code(name, word) result(code)
        character(len=*), intent(in) :: name, word
        integer :: code
        type(run_settings_type), target :: settings

        code = option_code(bind_run_keys(settings), run_group, name, word)
    end function choice_code

    !> Name of the option with this code of the run choice key name, "?" when none.
    function choice_name(name, code) result(word)
        character(len=*), intent(in) :: name
        integer, intent(in) :: code
        character(len=:), allocatable :: word
        type(run_settings_type), target :: settings

        word = option_name(bind_run_keys(settings), run_group, name, code)
    end function choice_name

    !> The first rule on the solver choices that settings break (key empty when none): the key
    !> at fault, what it must be and what it is. The scenes, the datasets' INTEGRATOR statement
    !> and the studies refuse the same combinations through it.
    subroutine run_choice_rule(settings, key, expected, got)
        type(run_settings_type), intent(in) :: settings
        !> 'method', 'drift' or 'jacobian', "" when the choices go together
        character(len=:), allocatable, intent(out) :: key
        !> What the key must be, and its value quoted
        character(len=:), allocatable, intent(out) :: expected, got

        key = ""
        expected = ""
        got = ""
        associate (run => settings)
            if (run%formulation == formulation_ida .and. run%method /= method_bdf) then
                key = "method"
                expected = "'bdf' with formulation 'ida' (IDA is a BDF code; 'adams' needs " &
                    & // "'cvode' or 'maggi')"
            else if (run%formulation == formulation_ida .and. run%drift /= drift_projection) then
                key = "drift"
                expected = "left out with formulation 'ida' (IDA has no drift; 'baumgarte' " &
                    & // "and 'none' are for 'cvode' and 'maggi')"
            else if (run%formulation == formulation_ida .and. run%jacobian == jacobian_none) then
                key = "jacobian"
                expected = "'analytic' or 'dq' with formulation 'ida' (IDA solves with " &
                    & // "Newton's method; 'none', fixed-point iteration, is for 'cvode' and " &
                    & // "'maggi')"
            else if (run%uses_cvode() .and. run%method == method_adams &
                    & .and. run%drift == drift_projection) then
                ! CVODE's projection works with BDF only (CVodeSetProjFn refuses Adams)
                key = "drift"
                expected = "'baumgarte' or 'none' with method = 'adams' (CVODE projects only " &
                    & // "with BDF)"
            else if (run%linear_solver == linear_sparse .and. run%jacobian /= jacobian_analytic) &
                    & then
                ! KLU needs the Newton matrix's entries: difference quotients are dense
                key = "linear_solver"
                expected = "'dense' or 'auto' unless jacobian = 'analytic' (the sparse Newton " &
                    & // "matrix is built from the UCOSUBs' partials)"
            end if
            select case (key)
            case ("method")
                got = "'" // choice_name(key, run%method) // "'"
            case ("drift")
                got = "'" // choice_name(key, run%drift) // "'"
            case ("jacobian")
                got = "'" // choice_name(key, run%jacobian) // "'"
            case ("linear_solver")
                got = "'sparse'"
            end select
        end associate
    end subroutine run_choice_rule

end module rollcon_run_keys
