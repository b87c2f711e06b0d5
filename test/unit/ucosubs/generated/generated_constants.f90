! SPDX-License-Identifier: MIT
!> The constants each generated module publishes about its outputs (<spec>_time_free,
!> <spec>_holonomic and their per-component arrays) against what its routine returns.
!>
!> Not a suite: test_generated collects these tests.
module generated_constants
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucon_call, only : evaluate_ucon
    use rollcon_ucosub_contract, only : max_ucon_vars, is_velocity_code, scalar_none, scalar_dt, &
        & scalar_dtt, array_none, array_dq, array_dtdq, xmatrx_none
    use rollcon_testing, only : check
    use disk_states, only : seed_random
    use generated_specs_list, only : generated_spec_type, generated_specs, random_state, &
        & random_parameters, spec_par
    implicit none
    private

    public :: test_time_free, test_holonomic

    !> Seeded random states per spec and component: a component that is not time-free (or not
    !> holonomic) must show a non-zero on at least one of them
    integer, parameter :: states = 200

contains

    !> Where <spec>_component_time_free is true, dF/dt, d2F/dt2 and d2F/dt dq_j are exactly
    !> zero on every state (random time in [0, 10] s); where false, some state gives a
    !> non-zero. <spec>_time_free is true exactly when every component is time-free.
    subroutine test_time_free(error)
        type(error_type), allocatable, intent(out) :: error
        type(generated_spec_type), allocatable :: specs(:)
        real(wp), allocatable :: values(:)
        real(wp) :: q(max_ucon_vars), time, scalar, array(max_ucon_vars)
        real(wp) :: xmatrx(max_ucon_vars, max_ucon_vars)
        integer :: s, component, k
        logical :: non_zero

        allocate(specs(0))  ! silences gfortran -Wmaybe-uninitialized
        call generated_specs(specs)
        call seed_random(6006)
        q = 0.0_wp
        do s = 1, size(specs)
            associate (spec => specs(s))
                call check(error, spec%time_free .eqv. all(spec%component_time_free), &
                    & spec%name // "_time_free disagrees with its per-component array")
                if (allocated(error)) return
                do component = 1, spec%ncomponents
                    non_zero = .false.
                    do k = 1, states
                        call random_state(k, spec%codes, q(:size(spec%codes)))
                        call random_parameters(spec, values)
                        call random_number(time)
                        time = 10.0_wp*time
                        call evaluate_ucon(spec%ucosub, 1, time, q, spec_par(spec, 1, values, &
                            & component), [scalar_dt, array_dtdq, xmatrx_none], scalar, array, &
                            & xmatrx, error)
                        if (allocated(error)) return
                        non_zero = non_zero .or. scalar /= 0.0_wp .or. any(array /= 0.0_wp)
                        call evaluate_ucon(spec%ucosub, 1, time, q, spec_par(spec, 1, values, &
                            & component), [scalar_dtt, array_none, xmatrx_none], scalar, array, &
                            & xmatrx, error)
                        if (allocated(error)) return
                        non_zero = non_zero .or. scalar /= 0.0_wp
                        if (spec%component_time_free(component) .and. non_zero) exit
                    end do
                    call check(error, non_zero .neqv. spec%component_time_free(component), &
                        & spec%name // ", component " // to_text(component) // ": " &
                        & // verdict(spec%component_time_free(component), &
                        & "time-free, but dF/dt, d2F/dt2 or d2F/dt dq is non-zero", &
                        & "not time-free, yet every time derivative is zero"))
                    if (allocated(error)) return
                end do
            end associate
        end do
    end subroutine test_time_free

    !> Where <spec>_component_holonomic is true, dF/dq_j is exactly zero for every velocity
    !> code j on every state; where false, some state gives a non-zero one.
    !> <spec>_holonomic is true exactly when every component is holonomic, and then the spec
    !> declares no velocity code.
    subroutine test_holonomic(error)
        type(error_type), allocatable, intent(out) :: error
        type(generated_spec_type), allocatable :: specs(:)
        real(wp), allocatable :: values(:)
        real(wp) :: q(max_ucon_vars), scalar, array(max_ucon_vars)
        real(wp) :: xmatrx(max_ucon_vars, max_ucon_vars)
        integer :: s, component, k, n
        logical :: non_zero

        allocate(specs(0))  ! silences gfortran -Wmaybe-uninitialized
        call generated_specs(specs)
        call seed_random(7007)
        q = 0.0_wp
        do s = 1, size(specs)
            associate (spec => specs(s))
                n = size(spec%codes)
                call check(error, (spec%holonomic .eqv. all(spec%component_holonomic)) &
                    & .and. (spec%holonomic .eqv. .not. any(is_velocity_code(spec%codes))), &
                    & spec%name // "_holonomic disagrees with its per-component array or " &
                    & // "with its codes")
                if (allocated(error)) return
                do component = 1, spec%ncomponents
                    non_zero = .false.
                    do k = 1, states
                        call random_state(k, spec%codes, q(:n))
                        call random_parameters(spec, values)
                        call evaluate_ucon(spec%ucosub, 1, 0.0_wp, q, spec_par(spec, 1, values, &
                            & component), [scalar_none, array_dq, xmatrx_none], scalar, array, &
                            & xmatrx, error)
                        if (allocated(error)) return
                        non_zero = non_zero .or. any(array(:n) /= 0.0_wp &
                            & .and. is_velocity_code(spec%codes))
                        if (spec%component_holonomic(component) .and. non_zero) exit
                    end do
                    call check(error, non_zero .neqv. spec%component_holonomic(component), &
                        & spec%name // ", component " // to_text(component) // ": " &
                        & // verdict(spec%component_holonomic(component), &
                        & "holonomic, but dF/dq is non-zero for a velocity", &
                        & "not holonomic, yet dF/dq is zero for every velocity"))
                    if (allocated(error)) return
                end do
            end associate
        end do
    end subroutine test_holonomic

    !> The message for a constant that is true, or for one that is false.
    pure function verdict(flag, when_true, when_false) result(text)
        !> The constant
        logical, intent(in) :: flag
        !> Message when it is true
        character(len=*), intent(in) :: when_true
        !> Message when it is false
        character(len=*), intent(in) :: when_false
        character(len=:), allocatable :: text

        if (flag) then
            text = when_true
        else
            text = when_false
        end if
    end function verdict

end module generated_constants
