! SPDX-License-Identifier: MIT
!> Wall-clock time, for progress lines and their pacing, and the CPU time of this process and of
!> its children (getrusage), for measures that must include the work done in child processes
!> (a user routine's runs, a benchmark's timed `rollcon run`).
module rollcon_clock
    use, intrinsic :: iso_c_binding, only : c_int, c_long
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: wall_seconds, cpu_seconds, cpu_self, cpu_children

    !> getrusage's who (Linux): this process; its terminated and waited-for children (and
    !> theirs)
    integer, parameter :: cpu_self = 0, cpu_children = -1

    !> struct timeval and struct rusage of Linux (x86_64 and other LP64 systems)
    type, bind(c) :: timeval_type
        integer(c_long) :: seconds, microseconds
    end type timeval_type
    type, bind(c) :: rusage_type
        type(timeval_type) :: user, system
        !> maxrss ... nivcsw, not read
        integer(c_long) :: rest(14)
    end type rusage_type

    interface
        function c_getrusage(who, usage) result(stat) bind(c, name="getrusage")
            import :: c_int, rusage_type
            integer(c_int), value :: who
            type(rusage_type), intent(out) :: usage
            integer(c_int) :: stat
        end function c_getrusage
    end interface

contains

    !> Wall-clock seconds since an arbitrary origin.
    function wall_seconds() result(seconds)
        real(wp) :: seconds
        integer(int64) :: count, rate

        call system_clock(count, rate)
        seconds = real(count, wp)/real(rate, wp)
    end function wall_seconds

    !> User + system CPU seconds (getrusage(2), microsecond resolution) since the start of this
    !> process (who = cpu_self) or spent by its children that have ended and been waited for
    !> (who = cpu_children: a child still running is not counted until it ends). 0 where
    !> getrusage fails (it does not for these two values on Linux).
    function cpu_seconds(who) result(seconds)
        integer, intent(in) :: who
        real(wp) :: seconds
        type(rusage_type) :: usage

        seconds = 0.0_wp
        if (c_getrusage(int(who, c_int), usage) /= 0) return
        seconds = timeval_seconds(usage%user) + timeval_seconds(usage%system)
    end function cpu_seconds

    pure real(wp) function timeval_seconds(time)
        type(timeval_type), intent(in) :: time

        timeval_seconds = real(time%seconds, wp) + 1.0e-6_wp*real(time%microseconds, wp)
    end function timeval_seconds

end module rollcon_clock
