! SPDX-License-Identifier: MIT
!> The benchmark's headline: for a method, the cheapest run within a target distance of the
!> reference, next to the cheapest reduced-ODE run (BDF or Adams: the limit) within it, both
!> from the same rows, hence from the same process.
module rollcon_bench_summary
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_benchmark, only : benchmark_row_type
    implicit none
    private

    public :: accuracy_ratio, accuracy_line

contains

    !> Cheapest completed row of method, and of any reduced-ODE method, whose position error is
    !> at most target; found is false when either has none.
    pure subroutine accuracy_ratio(rows, scene, method, target, cpu, reduced_cpu, found)
        type(benchmark_row_type), intent(in) :: rows(:)
        character(len=*), intent(in) :: scene, method
        !> Largest position error accepted [m]
        real(wp), intent(in) :: target
        !> CPU times of the two cheapest runs [s]
        real(wp), intent(out) :: cpu, reduced_cpu
        logical, intent(out) :: found

        cpu = cheapest(method)
        reduced_cpu = min(cheapest("reduced-bdf"), cheapest("reduced-adams"))
        found = cpu < huge(1.0_wp) .and. reduced_cpu < huge(1.0_wp)

    contains

        pure function cheapest(name) result(seconds)
            character(len=*), intent(in) :: name
            real(wp) :: seconds
            integer :: i

            seconds = huge(1.0_wp)
            do i = 1, size(rows)
                if (trim(rows(i)%scene) /= scene .or. trim(rows(i)%method) /= name) cycle
                if (rows(i)%status /= "completed") cycle
                if (rows(i)%position_error <= target) seconds = min(seconds, rows(i)%cpu)
            end do
        end function cheapest

    end subroutine accuracy_ratio

    !> "bench: SCENE: at <= 1e-6 m: METHOD 0.12 s, reduced 0.06 s, ratio 2.0" (or why not).
    function accuracy_line(rows, scene, method, target) result(line)
        type(benchmark_row_type), intent(in) :: rows(:)
        character(len=*), intent(in) :: scene, method
        real(wp), intent(in) :: target
        character(len=:), allocatable :: line
        real(wp) :: cpu, reduced_cpu
        logical :: found
        character(len=64) :: numbers

        call accuracy_ratio(rows, scene, method, target, cpu, reduced_cpu, found)
        line = "bench: " // scene // ": at <= " // to_text(target) // " m of the reference: " &
            & // method
        if (.not. found) then
            line = line // ": no run (or no reduced run) that close"
            return
        end if
        write(numbers, '(es10.3e3, a, es10.3e3, a, f8.3)') cpu, " s, reduced ODE ", reduced_cpu, &
            & " s, CPU ratio ", cpu/reduced_cpu
        line = line // " " // trim(adjustl(numbers))
    end function accuracy_line

end module rollcon_bench_summary
