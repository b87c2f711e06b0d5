! SPDX-License-Identifier: MIT
!> rollcon: user-defined kinematic constraints (ADAMS UCON/UCOSUB) for multibody dynamics.
module rollcon
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucon
    use rollcon_ucovar, only : ucon_variables_type, ucovar_registry_type
    use rollcon_adams_runtime, only : begin_declaration, end_declaration, take_ucon_error
    use rollcon_disk_par, only : disk_nvars, disk_npar, disk_codes, disk_par
    use rollcon_disk_hand, only : rolling_disk_ucosub, rolling_disk_evaluate
    use rollcon_ucon_call, only : declare_ucon, evaluate_ucon
    use rollcon_ucon_check, only : ucon_check_options_type, ucon_mismatch_type, &
        & ucon_check_result_type, check_ucon_state
    implicit none
    public
end module rollcon
