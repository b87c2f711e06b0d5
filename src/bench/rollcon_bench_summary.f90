! SPDX-License-Identifier: MIT
!> The benchmark's headline: for a method, the cheapest run within a target distance of the
!> reference, next to the cheapest reduced-ODE run (any multistep method and iteration: the
!> limit) within it, both from the same rows, hence from the same process; with the whole
!> process of that run's setting (`rollcon run` as a child) when it was measured.
module rollcon_bench_summary
    use rollcon_kinds, only : wp
    use rollcon_text, only : to_text
    use rollcon_benchmark, only : benchmark_row_type
    implicit none
    private

    public :: accuracy_ratio, accuracy_line, cheapest_row

contains

    !> Index in rows of the cheapest completed row of method whose position error is at most
    !> target [m]; 0 when none. A method name ending in '*' matches every method it begins.
    pure function cheapest_row(rows, scene, method, target) result(best)
        type(benchmark_row_type), intent(in) :: rows(:)
        character(len=*), intent(in) :: scene, method
        real(wp), intent(in) :: target
        integer :: best
        integer :: i

        best = 0
        do i = 1, size(rows)
            if (trim(rows(i)%scene) /= scene .or. .not. matches(trim(rows(i)%method))) cycle
            if (rows(i)%status /= "completed") cycle
            if (.not. rows(i)%position_error <= target) cycle
            if (best == 0) then
                best = i
            else if (rows(i)%cpu < rows(best)%cpu) then
                best = i
            end if
        end do

    contains

        pure logical function matches(name)
            character(len=*), intent(in) :: name

            if (method(len(method):) == "*") then
                matches = index(name, method(:len(method) - 1)) == 1
            else
                matches = name == method
            end if
        end function matches

    end function cheapest_row

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
        integer :: best, limit

        best = cheapest_row(rows, scene, method, target)
        limit = cheapest_row(rows, scene, "reduced-*", target)
        found = best > 0 .and. limit > 0
        cpu = huge(1.0_wp)
        reduced_cpu = huge(1.0_wp)
        if (best > 0) cpu = rows(best)%cpu
        if (limit > 0) reduced_cpu = rows(limit)%cpu
    end subroutine accuracy_ratio

    !> "bench: SCENE: at <= 1e-6 m of the reference: METHOD (rtol 1e-11) 0.12 s, reduced ODE
    !> 0.06 s, CPU ratio 2.0; whole process 0.2 s, ratio 3.3" (or why not).
    function accuracy_line(rows, scene, method, target, unit) result(line)
        type(benchmark_row_type), intent(in) :: rows(:)
        character(len=*), intent(in) :: scene, method
        real(wp), intent(in) :: target
        !> The errors' unit (default m; the bicycle's "(rad, m)")
        character(len=*), intent(in), optional :: unit
        character(len=:), allocatable :: line
        real(wp) :: cpu, reduced_cpu
        logical :: found
        character(len=64) :: numbers
        integer :: best

        call accuracy_ratio(rows, scene, method, target, cpu, reduced_cpu, found)
        line = "bench: " // scene // ": at <= " // to_text(target) // " m of the reference: " &
            & // method
        if (present(unit)) line = "bench: " // scene // ": at <= " // to_text(target) // " " &
            & // trim(unit) // " of the reference: " // method
        if (.not. found) then
            line = line // ": no run (or no reduced run) that close"
            return
        end if
        best = cheapest_row(rows, scene, method, target)
        write(numbers, '(es11.3e3, a, es11.3e3, a, f8.3)') cpu, " s, reduced ODE ", reduced_cpu, &
            & " s, CPU ratio ", cpu/reduced_cpu
        line = line // " (rtol " // to_text(rows(best)%rtol) // ") " // trim(adjustl(numbers))
        if (rows(best)%process_cpu > 0.0_wp) then
            write(numbers, '(es11.3e3, a, f8.3)') rows(best)%process_cpu, " s, ratio ", &
                & rows(best)%process_cpu/reduced_cpu
            line = line // "; whole process 'rollcon run' " // trim(adjustl(numbers))
        end if
    end function accuracy_line

end module rollcon_bench_summary
