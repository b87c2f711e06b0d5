! SPDX-License-Identifier: MIT
!> Wall-clock time, for progress lines and their pacing (CPU times use cpu_time).
module rollcon_clock
    use, intrinsic :: iso_fortran_env, only : int64
    use rollcon_kinds, only : wp
    implicit none
    private

    public :: wall_seconds

contains

    !> Wall-clock seconds since an arbitrary origin.
    function wall_seconds() result(seconds)
        real(wp) :: seconds
        integer(int64) :: count, rate

        call system_clock(count, rate)
        seconds = real(count, wp)/real(rate, wp)
    end function wall_seconds

end module rollcon_clock
