! SPDX-License-Identifier: MIT
!> rollcon-sweep: the program of `rollcon sweep` (a parameter study, docs/studies.md), the one
!> that links Open MPI. rollcon replaces itself by it (app/rollcon_sweep_program.f90) with the
!> same arguments, so it reads the same command line, `sweep STUDY.nml [...]`, and its
!> messages are rollcon's; under mpirun every rank does so. Every other command stays in
!> rollcon, which therefore starts without loading MPI's libraries.
program rollcon_sweep_main
    use, intrinsic :: iso_fortran_env, only : error_unit
    use rollcon, only : error_type, fatal_error, stat_input, use_one_blas_thread
    use rollcon_cli, only : cli_request_type, parse_command_line
    use rollcon_command_sweep, only : sweep_command
    implicit none
    type(cli_request_type) :: request
    type(error_type), allocatable :: error
    !> 0 when every case of the study is in its CSV, 1 otherwise
    integer :: status
    !> The threaded BLAS set to one thread ("" for reference BLAS)
    character(len=:), allocatable :: blas_library

    ! dozen-unknown systems gain nothing from BLAS threads (rollcon_lapack)
    call use_one_blas_thread(blas_library)
    call parse_command_line(request, error)
    if (.not. allocated(error) .and. request%command /= "sweep") call fatal_error(error, &
        & "rollcon-sweep runs parameter studies only, as 'rollcon sweep STUDY.nml [...]' runs " &
        & // "it (its arguments: sweep STUDY.nml [...]); the other commands are rollcon's", &
        & stat_input)
    if (.not. allocated(error)) call sweep_command(request, status, error)
    if (allocated(error)) then
        write(error_unit, '(a)') "rollcon: error: " // error%message
        flush(error_unit)
        stop 1, quiet=.true.
    end if
    if (status /= 0) stop status, quiet=.true.
end program rollcon_sweep_main
