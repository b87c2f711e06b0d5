! SPDX-License-Identifier: MIT
!> UCOVAR, ERRMES, SYSFNC, SYSARY, TIMGET, STEP, RCNVRT, AKISPL, CUBSPL, GTSTRG, GTARAY,
!> ISTRNG and RSTRNG for a user's
!> routine loaded at run time: the forwarding shim compiled into the user's shared library,
!> and the host's side of it.
!>
!> rollcon's programs are not linked with -rdynamic, so a shared library cannot resolve the
!> user's calls to UCOVAR and ERRMES against them. The shim (source text below, written to the
!> cache and compiled next to the user's routine) defines both and forwards each call through a
!> C function pointer. Right after dlopen the host looks up the shim's bind(c) setter and hands
!> it the addresses of host_ucovar and host_errmes, which call rollcon's own external UCOVAR and
!> ERRMES: a loaded routine then behaves exactly like one linked into the program.
!> ERRMES's character arguments cross the C boundary as (characters, length) pairs.
module rollcon_user_shim
    use, intrinsic :: iso_c_binding, only : c_ptr, c_funptr, c_int, c_size_t, c_char, &
        & c_double, c_funloc, c_associated, c_f_procpointer
    use rollcon_user_forces, only : system_function, system_array, system_time, system_spline
    use rollcon_adams_utilities, only : step_utility, convert_rotation, rotation_size, &
        & rcnvrt_success, rcnvrt_failure
    use rollcon_spline, only : method_akima, method_cubic
    use rollcon_user_data, only : string_data, array_data
    use rollcon_error, only : error_type, fatal_error, stat_ucon
    use rollcon_ucosub_contract, only : ucovar, errmes, max_ucon_vars
    use rollcon_dlopen, only : library_symbol
    implicit none
    private

    public :: shim_source_lines, shim_install_symbol, install_host_hooks

    !> Name of the shim's setter, as exported by the shared library
    character(len=*), parameter :: shim_install_symbol = "rollcon_shim_install"
    !> Name of the shim's setter of SYSFNC, SYSARY and TIMGET
    character(len=*), parameter :: shim_system_symbol = "rollcon_shim_install_system"
    !> Name of the shim's setter of STEP, RCNVRT, AKISPL and CUBSPL
    character(len=*), parameter :: shim_utilities_symbol = "rollcon_shim_install_utilities"
    !> Name of the shim's setter of GTSTRG and GTARAY
    character(len=*), parameter :: shim_data_symbol = "rollcon_shim_install_data"

    !> Source of the shim, free form; the host writes it to the cache as rollcon_shim.f90
    character(len=*), parameter :: shim_source_lines(*) = [character(len=96) :: &
        & "! rollcon forwarding shim: UCOVAR and ERRMES for a UCOSUB loaded at run time.", &
        & "! Written by rollcon and compiled into the same shared library as the user's routine;", &
        & "! the host installs the targets with rollcon_shim_install right after dlopen.", &
        & "module rollcon_shim_targets", &
        & "    use, intrinsic :: iso_c_binding, only : c_funptr, c_null_funptr, c_int, &", &
        & "        & c_size_t, c_char, c_double", &
        & "    implicit none", &
        & "    type(c_funptr), save :: ucovar_target = c_null_funptr", &
        & "    type(c_funptr), save :: errmes_target = c_null_funptr", &
        & "    type(c_funptr), save :: sysfnc_target = c_null_funptr", &
        & "    type(c_funptr), save :: sysary_target = c_null_funptr", &
        & "    type(c_funptr), save :: timget_target = c_null_funptr", &
        & "    type(c_funptr), save :: step_target = c_null_funptr", &
        & "    type(c_funptr), save :: rcnvrt_target = c_null_funptr", &
        & "    type(c_funptr), save :: spline_target = c_null_funptr", &
        & "    type(c_funptr), save :: gtstrg_target = c_null_funptr", &
        & "    type(c_funptr), save :: gtaray_target = c_null_funptr", &
        & "    abstract interface", &
        & "        subroutine ucovar_hook(id, nparts, lparts, nvars, lvars) bind(c)", &
        & "            import :: c_int", &
        & "            integer(c_int), intent(in) :: id, nparts, nvars, lparts(*), lvars(*)", &
        & "        end subroutine ucovar_hook", &
        & "        subroutine errmes_hook(errflg, mesage, mesage_length, id, endflg, &", &
        & "                & endflg_length) bind(c)", &
        & "            import :: c_int, c_size_t, c_char", &
        & "            integer(c_int), value :: errflg", &
        & "            character(kind=c_char), intent(in) :: mesage(*), endflg(*)", &
        & "            integer(c_size_t), value :: mesage_length, endflg_length", &
        & "            integer(c_int), intent(in) :: id", &
        & "        end subroutine errmes_hook", &
        & "        subroutine sysfnc_hook(name, name_length, ipar, nsize, value, errflg) bind(c)", &
        & "            import :: c_int, c_size_t, c_char, c_double", &
        & "            character(kind=c_char), intent(in) :: name(*)", &
        & "            integer(c_size_t), value :: name_length", &
        & "            integer(c_int), intent(in) :: ipar(*), nsize", &
        & "            real(c_double), intent(out) :: value", &
        & "            integer(c_int), intent(out) :: errflg", &
        & "        end subroutine sysfnc_hook", &
        & "        subroutine sysary_hook(name, name_length, ipar, nsize, states, nstates, &", &
        & "                & errflg) bind(c)", &
        & "            import :: c_int, c_size_t, c_char, c_double", &
        & "            character(kind=c_char), intent(in) :: name(*)", &
        & "            integer(c_size_t), value :: name_length", &
        & "            integer(c_int), intent(in) :: ipar(*), nsize", &
        & "            real(c_double), intent(out) :: states(3)", &
        & "            integer(c_int), intent(out) :: nstates, errflg", &
        & "        end subroutine sysary_hook", &
        & "        subroutine timget_hook(time) bind(c)", &
        & "            import :: c_double", &
        & "            real(c_double), intent(out) :: time", &
        & "        end subroutine timget_hook", &
        & "        subroutine step_hook(x, x0, h0, x1, h1, iord, value, errflg) bind(c)", &
        & "            import :: c_int, c_double", &
        & "            real(c_double), intent(in) :: x, x0, h0, x1, h1", &
        & "            integer(c_int), intent(in) :: iord", &
        & "            real(c_double), intent(out) :: value", &
        & "            integer(c_int), intent(out) :: errflg", &
        & "        end subroutine step_hook", &
        & "        subroutine rcnvrt_hook(sys1, sys1_length, coord1, sys2, sys2_length, &", &
        & "                & coord2, ncoord, istat) bind(c)", &
        & "            import :: c_int, c_size_t, c_char, c_double", &
        & "            character(kind=c_char), intent(in) :: sys1(*), sys2(*)", &
        & "            integer(c_size_t), value :: sys1_length, sys2_length", &
        & "            real(c_double), intent(in) :: coord1(*)", &
        & "            real(c_double), intent(out) :: coord2(9)", &
        & "            integer(c_int), intent(out) :: ncoord, istat", &
        & "        end subroutine rcnvrt_hook", &
        & "        subroutine spline_hook(method, xval, zval, id, iord, array, errflg) &", &
        & "                & bind(c)", &
        & "            import :: c_int, c_double", &
        & "            integer(c_int), value :: method", &
        & "            real(c_double), intent(in) :: xval, zval", &
        & "            integer(c_int), intent(in) :: id, iord", &
        & "            real(c_double), intent(out) :: array(3)", &
        & "            integer(c_int), intent(out) :: errflg", &
        & "        end subroutine spline_hook", &
        & "        subroutine gtstrg_hook(id, string, capacity, nchars, istat) bind(c)", &
        & "            import :: c_int, c_size_t, c_char", &
        & "            integer(c_int), intent(in) :: id", &
        & "            character(kind=c_char), intent(inout) :: string(*)", &
        & "            integer(c_size_t), value :: capacity", &
        & "            integer(c_int), intent(out) :: nchars, istat", &
        & "        end subroutine gtstrg_hook", &
        & "        subroutine gtaray_hook(id, array, number, istat) bind(c)", &
        & "            import :: c_int, c_double", &
        & "            integer(c_int), intent(in) :: id", &
        & "            real(c_double), intent(inout) :: array(*)", &
        & "            integer(c_int), intent(out) :: number, istat", &
        & "        end subroutine gtaray_hook", &
        & "    end interface", &
        & "end module rollcon_shim_targets", &
        & "", &
        & "subroutine rollcon_shim_install(ucovar_address, errmes_address) &", &
        & "        & bind(c, name='rollcon_shim_install')", &
        & "    use rollcon_shim_targets, only : c_funptr, ucovar_target, errmes_target", &
        & "    implicit none", &
        & "    type(c_funptr), value :: ucovar_address, errmes_address", &
        & "    ucovar_target = ucovar_address", &
        & "    errmes_target = errmes_address", &
        & "end subroutine rollcon_shim_install", &
        & "", &
        & "subroutine rollcon_shim_install_system(sysfnc_address, sysary_address, &", &
        & "        & timget_address) bind(c, name='rollcon_shim_install_system')", &
        & "    use rollcon_shim_targets, only : c_funptr, sysfnc_target, sysary_target, &", &
        & "        & timget_target", &
        & "    implicit none", &
        & "    type(c_funptr), value :: sysfnc_address, sysary_address, timget_address", &
        & "    sysfnc_target = sysfnc_address", &
        & "    sysary_target = sysary_address", &
        & "    timget_target = timget_address", &
        & "end subroutine rollcon_shim_install_system", &
        & "", &
        & "subroutine rollcon_shim_install_utilities(step_address, rcnvrt_address, &", &
        & "        & spline_address) bind(c, name='rollcon_shim_install_utilities')", &
        & "    use rollcon_shim_targets, only : c_funptr, step_target, rcnvrt_target, &", &
        & "        & spline_target", &
        & "    implicit none", &
        & "    type(c_funptr), value :: step_address, rcnvrt_address, spline_address", &
        & "    step_target = step_address", &
        & "    rcnvrt_target = rcnvrt_address", &
        & "    spline_target = spline_address", &
        & "end subroutine rollcon_shim_install_utilities", &
        & "", &
        & "subroutine rollcon_shim_install_data(gtstrg_address, gtaray_address) &", &
        & "        & bind(c, name='rollcon_shim_install_data')", &
        & "    use rollcon_shim_targets, only : c_funptr, gtstrg_target, gtaray_target", &
        & "    implicit none", &
        & "    type(c_funptr), value :: gtstrg_address, gtaray_address", &
        & "    gtstrg_target = gtstrg_address", &
        & "    gtaray_target = gtaray_address", &
        & "end subroutine rollcon_shim_install_data", &
        & "", &
        & "subroutine ucovar(id, nparts, lparts, nvars, lvars)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, ucovar_target, ucovar_hook", &
        & "    implicit none", &
        & "    integer(c_int), intent(in) :: id, nparts, nvars, lparts(*), lvars(*)", &
        & "    procedure(ucovar_hook), pointer :: forward_ucovar", &
        & "    if (.not. c_associated(ucovar_target)) return", &
        & "    call c_f_procpointer(ucovar_target, forward_ucovar)", &
        & "    call forward_ucovar(id, nparts, lparts, nvars, lvars)", &
        & "end subroutine ucovar", &
        & "", &
        & "subroutine errmes(errflg, mesage, id, endflg)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_size_t, errmes_target, errmes_hook", &
        & "    implicit none", &
        & "    logical, intent(in) :: errflg", &
        & "    character(len=*), intent(in) :: mesage, endflg", &
        & "    integer(c_int), intent(in) :: id", &
        & "    procedure(errmes_hook), pointer :: forward_errmes", &
        & "    if (.not. c_associated(errmes_target)) return", &
        & "    call c_f_procpointer(errmes_target, forward_errmes)", &
        & "    call forward_errmes(merge(1_c_int, 0_c_int, errflg), mesage, &", &
        & "        & len(mesage, kind=c_size_t), &", &
        & "        & id, endflg, len(endflg, kind=c_size_t))", &
        & "end subroutine errmes", &
        & "", &
        & "subroutine sysfnc(fncnam, ipar, nsize, value, errflg)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_size_t, c_double, sysfnc_target, &", &
        & "        & sysfnc_hook", &
        & "    implicit none", &
        & "    character(len=*), intent(in) :: fncnam", &
        & "    integer(c_int), intent(in) :: ipar(*), nsize", &
        & "    real(c_double), intent(out) :: value", &
        & "    logical, intent(out) :: errflg", &
        & "    procedure(sysfnc_hook), pointer :: forward_sysfnc", &
        & "    integer(c_int) :: failed", &
        & "    value = 0", &
        & "    errflg = .true.", &
        & "    if (.not. c_associated(sysfnc_target)) return", &
        & "    call c_f_procpointer(sysfnc_target, forward_sysfnc)", &
        & "    call forward_sysfnc(fncnam, len(fncnam, kind=c_size_t), ipar, nsize, value, &", &
        & "        & failed)", &
        & "    errflg = failed /= 0", &
        & "end subroutine sysfnc", &
        & "", &
        & "subroutine sysary(fncnam, ipar, nsize, states, nstates, errflg)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_size_t, c_double, sysary_target, &", &
        & "        & sysary_hook", &
        & "    implicit none", &
        & "    character(len=*), intent(in) :: fncnam", &
        & "    integer(c_int), intent(in) :: ipar(*), nsize", &
        & "    real(c_double), intent(out) :: states(*)", &
        & "    integer(c_int), intent(out) :: nstates", &
        & "    logical, intent(out) :: errflg", &
        & "    procedure(sysary_hook), pointer :: forward_sysary", &
        & "    real(c_double) :: values(3)", &
        & "    integer(c_int) :: failed", &
        & "    nstates = 0", &
        & "    errflg = .true.", &
        & "    if (.not. c_associated(sysary_target)) return", &
        & "    call c_f_procpointer(sysary_target, forward_sysary)", &
        & "    call forward_sysary(fncnam, len(fncnam, kind=c_size_t), ipar, nsize, values, &", &
        & "        & nstates, failed)", &
        & "    if (nstates > 0) states(1:nstates) = values(1:nstates)", &
        & "    errflg = failed /= 0", &
        & "end subroutine sysary", &
        & "", &
        & "subroutine timget(time)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_double, timget_target, timget_hook", &
        & "    implicit none", &
        & "    real(c_double), intent(out) :: time", &
        & "    procedure(timget_hook), pointer :: forward_timget", &
        & "    time = 0", &
        & "    if (.not. c_associated(timget_target)) return", &
        & "    call c_f_procpointer(timget_target, forward_timget)", &
        & "    call forward_timget(time)", &
        & "end subroutine timget", &
        & "", &
        & "subroutine step(x, x0, h0, x1, h1, iord, value, errflg)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_double, step_target, step_hook", &
        & "    implicit none", &
        & "    real(c_double), intent(in) :: x, x0, h0, x1, h1", &
        & "    integer(c_int), intent(in) :: iord", &
        & "    real(c_double), intent(out) :: value", &
        & "    logical, intent(out) :: errflg", &
        & "    procedure(step_hook), pointer :: forward_step", &
        & "    integer(c_int) :: failed", &
        & "    value = 0", &
        & "    errflg = .true.", &
        & "    if (.not. c_associated(step_target)) return", &
        & "    call c_f_procpointer(step_target, forward_step)", &
        & "    call forward_step(x, x0, h0, x1, h1, iord, value, failed)", &
        & "    errflg = failed /= 0", &
        & "end subroutine step", &
        & "", &
        & "subroutine rcnvrt(sys1, coord1, sys2, coord2, istat)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_size_t, c_double, rcnvrt_target, &", &
        & "        & rcnvrt_hook", &
        & "    implicit none", &
        & "    character(len=*), intent(in) :: sys1, sys2", &
        & "    real(c_double), intent(in) :: coord1(*)", &
        & "    real(c_double), intent(out) :: coord2(*)", &
        & "    integer(c_int), intent(out) :: istat", &
        & "    procedure(rcnvrt_hook), pointer :: forward_rcnvrt", &
        & "    real(c_double) :: values(9)", &
        & "    integer(c_int) :: n", &
        & "    istat = -10", &
        & "    if (.not. c_associated(rcnvrt_target)) return", &
        & "    call c_f_procpointer(rcnvrt_target, forward_rcnvrt)", &
        & "    call forward_rcnvrt(sys1, len(sys1, kind=c_size_t), coord1, sys2, &", &
        & "        & len(sys2, kind=c_size_t), values, n, istat)", &
        & "    if (n > 0) coord2(1:n) = values(1:n)", &
        & "end subroutine rcnvrt", &
        & "", &
        & "subroutine akispl(xval, zval, id, iord, array, errflg)", &
        & "    use rollcon_shim_targets, only : c_int, c_double", &
        & "    implicit none", &
        & "    real(c_double), intent(in) :: xval, zval", &
        & "    integer(c_int), intent(in) :: id, iord", &
        & "    real(c_double), intent(out) :: array(3)", &
        & "    logical, intent(out) :: errflg", &
        & "    call rollcon_shim_spline(1_c_int, xval, zval, id, iord, array, errflg)", &
        & "end subroutine akispl", &
        & "", &
        & "subroutine cubspl(xval, zval, id, iord, array, errflg)", &
        & "    use rollcon_shim_targets, only : c_int, c_double", &
        & "    implicit none", &
        & "    real(c_double), intent(in) :: xval, zval", &
        & "    integer(c_int), intent(in) :: id, iord", &
        & "    real(c_double), intent(out) :: array(3)", &
        & "    logical, intent(out) :: errflg", &
        & "    call rollcon_shim_spline(2_c_int, xval, zval, id, iord, array, errflg)", &
        & "end subroutine cubspl", &
        & "", &
        & "subroutine rollcon_shim_spline(method, xval, zval, id, iord, array, errflg)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_double, spline_target, spline_hook", &
        & "    implicit none", &
        & "    integer(c_int), intent(in) :: method, id, iord", &
        & "    real(c_double), intent(in) :: xval, zval", &
        & "    real(c_double), intent(out) :: array(3)", &
        & "    logical, intent(out) :: errflg", &
        & "    procedure(spline_hook), pointer :: forward_spline", &
        & "    integer(c_int) :: failed", &
        & "    array = 0", &
        & "    errflg = .true.", &
        & "    if (.not. c_associated(spline_target)) return", &
        & "    call c_f_procpointer(spline_target, forward_spline)", &
        & "    call forward_spline(method, xval, zval, id, iord, array, failed)", &
        & "    errflg = failed /= 0", &
        & "end subroutine rollcon_shim_spline", &
        & "", &
        & "subroutine gtstrg(id, string, nchars, istat)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_size_t, gtstrg_target, gtstrg_hook", &
        & "    implicit none", &
        & "    integer(c_int), intent(in) :: id", &
        & "    character(len=*), intent(out) :: string", &
        & "    integer(c_int), intent(out) :: nchars, istat", &
        & "    procedure(gtstrg_hook), pointer :: forward_gtstrg", &
        & "    string = ' '", &
        & "    nchars = 0", &
        & "    istat = -2", &
        & "    if (.not. c_associated(gtstrg_target)) return", &
        & "    call c_f_procpointer(gtstrg_target, forward_gtstrg)", &
        & "    call forward_gtstrg(id, string, len(string, kind=c_size_t), nchars, istat)", &
        & "end subroutine gtstrg", &
        & "", &
        & "subroutine gtaray(id, array, number, istat)", &
        & "    use, intrinsic :: iso_c_binding, only : c_associated, c_f_procpointer", &
        & "    use rollcon_shim_targets, only : c_int, c_double, gtaray_target, gtaray_hook", &
        & "    implicit none", &
        & "    integer(c_int), intent(in) :: id", &
        & "    real(c_double), intent(inout) :: array(*)", &
        & "    integer(c_int), intent(out) :: number, istat", &
        & "    procedure(gtaray_hook), pointer :: forward_gtaray", &
        & "    number = 0", &
        & "    istat = -2", &
        & "    if (.not. c_associated(gtaray_target)) return", &
        & "    call c_f_procpointer(gtaray_target, forward_gtaray)", &
        & "    call forward_gtaray(id, array, number, istat)", &
        & "end subroutine gtaray", &
        & "", &
        & "subroutine istrng(number, string, length, istat)", &
        & "    implicit none", &
        & "    integer, intent(in) :: number", &
        & "    character(len=*), intent(out) :: string", &
        & "    integer, intent(out) :: length, istat", &
        & "    character(len=24) :: text", &
        & "    write(text, '(i0)') number", &
        & "    length = len_trim(text)", &
        & "    string = text(:length)", &
        & "    istat = 0", &
        & "    if (length > len(string)) istat = -1", &
        & "end subroutine istrng", &
        & "", &
        & "subroutine rstrng(reel, string, length, istat)", &
        & "    implicit none", &
        & "    double precision, intent(in) :: reel", &
        & "    character(len=*), intent(out) :: string", &
        & "    integer, intent(out) :: length, istat", &
        & "    character(len=32) :: text", &
        & "    write(text, '(es24.16e3)') reel", &
        & "    text = adjustl(text)", &
        & "    length = len_trim(text)", &
        & "    string = text(:length)", &
        & "    istat = 0", &
        & "    if (length > len(string)) istat = -1", &
        & "end subroutine rstrng"]

    abstract interface
        !> The shim's setter (rollcon_shim_install in the source above)
        subroutine install_interface(ucovar_address, errmes_address) bind(c)
            import :: c_funptr
            !> Address of host_ucovar
            type(c_funptr), value :: ucovar_address
            !> Address of host_errmes
            type(c_funptr), value :: errmes_address
        end subroutine install_interface
        !> The shim's setter of the force routines' utilities (rollcon_shim_install_system)
        subroutine install_system_interface(sysfnc_address, sysary_address, timget_address) &
                & bind(c)
            import :: c_funptr
            !> Addresses of host_sysfnc, host_sysary, host_timget
            type(c_funptr), value :: sysfnc_address, sysary_address, timget_address
        end subroutine install_system_interface
        !> The shim's setter of STEP, RCNVRT, AKISPL and CUBSPL
        !> (rollcon_shim_install_utilities)
        subroutine install_utilities_interface(step_address, rcnvrt_address, spline_address) &
                & bind(c)
            import :: c_funptr
            !> Addresses of host_step, host_rcnvrt, host_spline
            type(c_funptr), value :: step_address, rcnvrt_address, spline_address
        end subroutine install_utilities_interface
        !> The shim's setter of GTSTRG and GTARAY (rollcon_shim_install_data)
        subroutine install_data_interface(gtstrg_address, gtaray_address) bind(c)
            import :: c_funptr
            !> Addresses of host_gtstrg, host_gtaray
            type(c_funptr), value :: gtstrg_address, gtaray_address
        end subroutine install_data_interface
    end interface

contains

    !> Point the shim of a freshly opened library at host_ucovar and host_errmes.
    subroutine install_host_hooks(handle, library, error)
        !> Handle of the user's shared library
        type(c_ptr), intent(in) :: handle
        !> Its path, for the message
        character(len=*), intent(in) :: library
        !> Set when the library holds no shim (it was not built by rollcon)
        type(error_type), allocatable, intent(out) :: error
        type(c_funptr) :: address
        procedure(install_interface), pointer :: install
        procedure(install_system_interface), pointer :: install_system
        procedure(install_utilities_interface), pointer :: install_utilities
        procedure(install_data_interface), pointer :: install_data

        address = library_symbol(handle, shim_install_symbol)
        if (.not. c_associated(address)) then
            call fatal_error(error, library // ": no symbol '" // shim_install_symbol &
                & // "'; the library was not built by rollcon (delete it to rebuild)", stat_ucon)
            return
        end if
        call c_f_procpointer(address, install)
        call install(c_funloc(host_ucovar), c_funloc(host_errmes))
        ! the utilities of force routines (a library built before the shim had them: none)
        address = library_symbol(handle, shim_system_symbol)
        if (.not. c_associated(address)) return
        call c_f_procpointer(address, install_system)
        call install_system(c_funloc(host_sysfnc), c_funloc(host_sysary), c_funloc(host_timget))
        address = library_symbol(handle, shim_utilities_symbol)
        if (.not. c_associated(address)) return
        call c_f_procpointer(address, install_utilities)
        call install_utilities(c_funloc(host_step), c_funloc(host_rcnvrt), &
            & c_funloc(host_spline))
        address = library_symbol(handle, shim_data_symbol)
        if (.not. c_associated(address)) return
        call c_f_procpointer(address, install_data)
        call install_data(c_funloc(host_gtstrg), c_funloc(host_gtaray))
    end subroutine install_host_hooks

    !> The shim's STEP lands here: rollcon_adams_utilities' step_utility.
    subroutine host_step(x, x0, h0, x1, h1, iord, value, errflg) bind(c)
        !> X, X0, H0, X1, H1 of the call
        real(c_double), intent(in) :: x, x0, h0, x1, h1
        !> Order of the derivative
        integer(c_int), intent(in) :: iord
        !> The step or its derivative
        real(c_double), intent(out) :: value
        !> 1 when the call was refused
        integer(c_int), intent(out) :: errflg
        logical :: failed

        call step_utility(x, x0, h0, x1, h1, int(iord), value, failed)
        errflg = merge(1_c_int, 0_c_int, failed)
    end subroutine host_step

    !> The shim's RCNVRT lands here: rollcon_adams_utilities' convert_rotation, reading
    !> rotation_size(SYS1) values of COORD1 and giving ncoord = rotation_size(SYS2) of COORD2
    !> (0 when refused).
    subroutine host_rcnvrt(sys1, sys1_length, coord1, sys2, sys2_length, coord2, ncoord, &
            & istat) bind(c)
        !> Characters of SYS1 and SYS2
        character(kind=c_char), intent(in) :: sys1(*), sys2(*)
        !> Their lengths
        integer(c_size_t), value :: sys1_length, sys2_length
        !> The coordinates to convert
        real(c_double), intent(in) :: coord1(*)
        !> The converted coordinates
        real(c_double), intent(out) :: coord2(9)
        !> Number of coordinates in coord2
        integer(c_int), intent(out) :: ncoord
        !> RCNVRT's ISTAT
        integer(c_int), intent(out) :: istat
        character(len=:), allocatable :: from, to
        integer :: n1, n2, status

        from = to_string(sys1, sys1_length)
        to = to_string(sys2, sys2_length)
        coord2 = 0.0_c_double
        ncoord = 0
        istat = int(rcnvrt_failure, c_int)
        n1 = rotation_size(from)
        n2 = rotation_size(to)
        if (n1 == 0 .or. n2 == 0) return
        call convert_rotation(from, coord1(:n1), to, coord2(:n2), status)
        istat = int(status, c_int)
        if (status == rcnvrt_success) ncoord = int(n2, c_int)
    end subroutine host_rcnvrt

    !> The shim's AKISPL (method 1) and CUBSPL (method 2) land here: rollcon_user_forces'
    !> system_spline.
    subroutine host_spline(method, xval, zval, id, iord, array, errflg) bind(c)
        !> 1 AKISPL, 2 CUBSPL
        integer(c_int), value :: method
        !> XVAL, ZVAL of the call
        real(c_double), intent(in) :: xval, zval
        !> SPLINE id and order of the derivative
        integer(c_int), intent(in) :: id, iord
        !> The value and the z derivatives
        real(c_double), intent(out) :: array(3)
        !> 1 when the call was refused
        integer(c_int), intent(out) :: errflg
        logical :: failed

        call system_spline(merge(method_akima, method_cubic, method == 1), xval, zval, &
            & int(id), int(iord), array, failed)
        errflg = merge(1_c_int, 0_c_int, failed)
    end subroutine host_spline

    !> The shim's GTSTRG lands here: rollcon_user_data's string_data, the text written into
    !> the caller's capacity characters.
    subroutine host_gtstrg(id, string, capacity, nchars, istat) bind(c)
        !> STRING id
        integer(c_int), intent(in) :: id
        !> The caller's STRING argument, and its length
        character(kind=c_char), intent(inout) :: string(*)
        integer(c_size_t), value :: capacity
        !> Length of the text [characters]; rollcon_user_data's istat
        integer(c_int), intent(out) :: nchars, istat
        character(len=max(0, int(min(capacity, int(huge(1), c_size_t))))) :: text
        integer :: i, n, status

        call string_data(int(id), text, n, status)
        do i = 1, len(text)
            string(i) = text(i:i)
        end do
        nchars = int(n, c_int)
        istat = int(status, c_int)
    end subroutine host_gtstrg

    !> The shim's GTARAY lands here: rollcon_user_data's array_data.
    subroutine host_gtaray(id, array, number, istat) bind(c)
        !> ARRAY id
        integer(c_int), intent(in) :: id
        !> The caller's storage, at least the ARRAY's size
        real(c_double), intent(inout) :: array(*)
        !> Number of values written; rollcon_user_data's istat
        integer(c_int), intent(out) :: number, istat
        integer :: n, status

        call array_data(int(id), array, n, status)
        number = int(n, c_int)
        istat = int(status, c_int)
    end subroutine host_gtaray

    !> The shim's SYSFNC lands here and goes on to rollcon_user_forces' system_function.
    subroutine host_sysfnc(name, name_length, ipar, nsize, value, errflg) bind(c)
        !> Characters of FNCNAM
        character(kind=c_char), intent(in) :: name(*)
        !> Its length
        integer(c_size_t), value :: name_length
        !> Marker ids, NSIZE of them
        integer(c_int), intent(in) :: ipar(*), nsize
        !> The measure, dataset units
        real(c_double), intent(out) :: value
        !> 1 when the call was refused
        integer(c_int), intent(out) :: errflg
        logical :: failed

        call system_function(to_string(name, name_length), int(ipar(:max(0, min(nsize, 4)))), &
            & value, failed)
        errflg = merge(1_c_int, 0_c_int, failed)
    end subroutine host_sysfnc

    !> The shim's SYSARY lands here and goes on to rollcon_user_forces' system_array.
    subroutine host_sysary(name, name_length, ipar, nsize, states, nstates, errflg) bind(c)
        !> Characters of FNCNAM
        character(kind=c_char), intent(in) :: name(*)
        !> Its length
        integer(c_size_t), value :: name_length
        !> Marker ids, NSIZE of them
        integer(c_int), intent(in) :: ipar(*), nsize
        !> The three values, dataset units
        real(c_double), intent(out) :: states(3)
        !> Number of values given (3, or 0 when refused)
        integer(c_int), intent(out) :: nstates
        !> 1 when the call was refused
        integer(c_int), intent(out) :: errflg
        logical :: failed
        integer :: n

        call system_array(to_string(name, name_length), int(ipar(:max(0, min(nsize, 4)))), &
            & states, n, failed)
        nstates = int(n, c_int)
        errflg = merge(1_c_int, 0_c_int, failed)
    end subroutine host_sysary

    !> The shim's TIMGET lands here: the time of the call, dataset units.
    subroutine host_timget(time) bind(c)
        !> The time
        real(c_double), intent(out) :: time

        time = system_time()
    end subroutine host_timget

    !> The shim's UCOVAR lands here and goes on to rollcon's external UCOVAR.
    subroutine host_ucovar(id, nparts, lparts, nvars, lvars) bind(c)
        !> UCON statement id
        integer(c_int), intent(in) :: id
        !> Number of part ids
        integer(c_int), intent(in) :: nparts
        !> Part id of each variable
        integer(c_int), intent(in) :: lparts(*)
        !> Number of codes
        integer(c_int), intent(in) :: nvars
        !> Code of each variable
        integer(c_int), intent(in) :: lvars(*)

        call ucovar(int(id), int(nparts), int(lparts(:max(0, min(nparts, max_ucon_vars)))), &
            & int(nvars), int(lvars(:max(0, min(nvars, max_ucon_vars)))))
    end subroutine host_ucovar

    !> The shim's ERRMES lands here and goes on to rollcon's external ERRMES.
    subroutine host_errmes(errflg, mesage, mesage_length, id, endflg, endflg_length) bind(c)
        !> 1 when there is an error to report, 0 otherwise
        integer(c_int), value :: errflg
        !> Characters of the message
        character(kind=c_char), intent(in) :: mesage(*)
        !> Length of the message
        integer(c_size_t), value :: mesage_length
        !> Id of the statement concerned
        integer(c_int), intent(in) :: id
        !> Characters of ENDFLG ("STOP" or anything else)
        character(kind=c_char), intent(in) :: endflg(*)
        !> Length of ENDFLG
        integer(c_size_t), value :: endflg_length

        call errmes(errflg /= 0, to_string(mesage, mesage_length), int(id), &
            & to_string(endflg, endflg_length))
    end subroutine host_errmes

    !> Fortran text of length characters (none when length is not positive).
    pure function to_string(chars, length) result(text)
        character(kind=c_char), intent(in) :: chars(*)
        integer(c_size_t), intent(in) :: length
        character(len=:), allocatable :: text
        integer :: i

        allocate(character(len=max(0, int(min(length, int(huge(1), c_size_t))))) :: text)
        do i = 1, len(text)
            text(i:i) = chars(i)
        end do
    end function to_string

end module rollcon_user_shim
