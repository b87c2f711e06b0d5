! SPDX-License-Identifier: MIT
!> UCOVAR, ERRMES, SYSFNC, SYSARY and TIMGET for a user's routine loaded at run time: the
!> forwarding shim compiled into the user's shared library, and the host's side of it.
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
    use rollcon_user_forces, only : system_function, system_array, system_time
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
        & "end subroutine timget"]

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
    end subroutine install_host_hooks

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
