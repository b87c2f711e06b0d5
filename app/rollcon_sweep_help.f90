! SPDX-License-Identifier: MIT
!> `rollcon sweep --help`: printed by rollcon itself, so that it works without the study
!> program rollcon-sweep, and by rollcon-sweep.
module rollcon_sweep_help
    use, intrinsic :: iso_fortran_env, only : output_unit
    implicit none
    private

    public :: print_sweep_help

contains

    !> The usage, the study file, what is written, ranks and exit status.
    subroutine print_sweep_help()
        write(output_unit, "(a)") &
            & "usage: rollcon sweep STUDY.nml [--output DIR] [--quiet] [--no-map]", &
            & "                     [--ucosub FILE|NAME]... [--no-check] [--call-timeout S]", &
            & "       mpirun --oversubscribe -np N rollcon sweep STUDY.nml [...]", &
            & "", &
            & "Run a parameter study (docs/studies.md): the study file names a base scene (or", &
            & "an ADAMS dataset, .adm), the keys to vary (&grid 'from to count', or &random", &
            & "'from to' samples; group%key of a scene, statement%id%keyword of a dataset), the", &
            & "rules that class each case (&classify) and the map's axes (&map). Every case", &
            & "is the ordinary simulation of its scene.", &
            & "", &
            & "--ucosub FILE|NAME gives every case the routines rollcon run --ucosub does: a", &
            & "file of your own (given again for more files) compiled once into the cache", &
            & "before the first case and run apart in every case, with the check of its", &
            & "UCOSUB's partials at each case's start (--no-check: none) and the time limit", &
            & "per call (--call-timeout, default 10 s); or a built-in routine by name.", &
            & "", &
            & "Writes DIR/STUDY.csv (DIR defaults to ./output): one row per case, written and", &
            & "flushed as the case ends, with its parameters, outcome (completed, theta_limit,", &
            & "liftoff, inaccurate, failed, refused), class, SUNDIALS' flag when it failed, and", &
            & "measures: t_reached [s], theta_min, theta_max, tilt_max [rad], mu_max [-],", &
            & "fn_min [N], t_fn_negative [s], energy_drift [-], residual_max, steps, cpu_s [s].", &
            & "A case that fails is recorded; it never stops the study. Run the same command", &
            & "again to resume: cases already in the CSV (same parameters) are skipped.", &
            & "Then draws the map, DIR/STUDY.png (and its gnuplot script DIR/STUDY.gp): every", &
            & "case at its two parameters (&map x and y), coloured by class (--no-map: none).", &
            & "", &
            & "Under mpirun, rank 0 hands out the cases and writes the rows, the other ranks run", &
            & "cases; rank 0 sleeps between messages, so start one rank more than cores", &
            & "(--oversubscribe). The rows do not depend on the number of ranks, except cpu_s.", &
            & "As root, mpirun needs OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1", &
            & "(.ci/env sets them). rollcon sweep runs the program rollcon-sweep, which fpm", &
            & "builds and installs beside rollcon: it alone loads Open MPI.", &
            & "", &
            & "Exit status: 0 when every case is in the CSV, 1 on bad input or a failure."
    end subroutine print_sweep_help

end module rollcon_sweep_help
