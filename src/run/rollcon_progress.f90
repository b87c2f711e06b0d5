! SPDX-License-Identifier: MIT
!> Progress of a long run on stderr, at most once a second of wall time: the fraction of the
!> simulated time done, the rate, and the time left at that rate, e.g. "rollcon: 82% of 10 s
!> simulated (t = 8.2 s), 14.5 simulated s per CPU s, about 0.1 s left". The rate is per CPU
!> second of this process, or per wall second where the work runs elsewhere (a child process).
module rollcon_progress
    use, intrinsic :: iso_fortran_env, only : error_unit
    use rollcon_kinds, only : wp
    use rollcon_clock, only : wall_seconds
    use rollcon_text, only : to_text
    implicit none
    private

    public :: progress_type

    type :: progress_type
        !> Lines are written (false: silent)
        logical :: enabled = .false.
        !> Count wall time instead of this process's CPU time
        logical :: wall = .false.
        real(wp) :: t0 = 0.0_wp, end_time = 1.0_wp
        real(wp) :: clock_start = 0.0_wp, wall_last = 0.0_wp
    contains
        procedure :: start
        procedure :: report
    end type progress_type

contains

    !> A run from t0 to end_time [s] starts now.
    subroutine start(self, enabled, t0, end_time, wall)
        class(progress_type), intent(inout) :: self
        logical, intent(in) :: enabled
        real(wp), intent(in) :: t0, end_time
        logical, intent(in), optional :: wall

        self%enabled = enabled
        self%t0 = t0
        self%end_time = end_time
        if (present(wall)) self%wall = wall
        self%clock_start = clock(self)
        self%wall_last = wall_seconds()
    end subroutine start

    !> The run reached time [s]: a line, when a second passed since the last one.
    subroutine report(self, time)
        class(progress_type), intent(inout) :: self
        real(wp), intent(in) :: time
        real(wp) :: now, fraction, left, spent

        if (.not. self%enabled) return
        now = wall_seconds()
        if (now - self%wall_last < 1.0_wp) return
        self%wall_last = now
        spent = clock(self) - self%clock_start
        fraction = (time - self%t0)/(self%end_time - self%t0)
        left = spent*(1.0_wp - fraction)/max(fraction, 1.0e-9_wp)
        write(error_unit, '(a, g0.3, a)') "rollcon: " &
            & // to_text(anint(1000.0_wp*fraction)/10.0_wp) // "% of " &
            & // to_text(self%end_time - self%t0) // " s simulated (t = " &
            & // to_text(anint(1000.0_wp*time)/1000.0_wp) // " s), ", &
            & (time - self%t0)/max(spent, 1.0e-9_wp), " simulated s per " &
            & // trim(merge("wall", "CPU ", self%wall)) // " s, about " &
            & // to_text(anint(10.0_wp*left)/10.0_wp) // " s left"
        flush(error_unit)
    end subroutine report

    !> CPU seconds of this process, or wall seconds.
    function clock(self) result(seconds)
        class(progress_type), intent(in) :: self
        real(wp) :: seconds

        if (self%wall) then
            seconds = wall_seconds()
        else
            call cpu_time(seconds)
        end if
    end function clock

end module rollcon_progress
