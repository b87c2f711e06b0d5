! SPDX-License-Identifier: MIT
!> IDA's first step (suite ida-first-step): a chain of 64 links of 0.1 kg released from rest,
!> at rtol 1e-8, atol 1e-10, failed at t = 0 (IDA_CONV_FAIL: the first step IDA chose, 1.4e-11
!> s, left its index-2 Newton matrix unsolvable, and it only shrank it); rollcon_ida tries the
!> first step once more from the same state with a larger one, and the run completes. Its
!> motion must be the 1 kg chain's: scaling every mass and inertia by one factor scales the
!> joint forces and leaves a chain falling under gravity moving the same way.
module test_ida_first_step
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type
    use rollcon_link_chain, only : link_chain_dataset
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_dataset_text
    use command_runs, only : count_of
    implicit none
    private

    public :: collect_ida_first_step

    !> Where the datasets are written
    character(len=*), parameter :: folder = "build/rollcon-test/ida-first-step"

contains

    subroutine collect_ida_first_step(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("light-chain-starts", test_light_chain)]
    end subroutine collect_ida_first_step

    !> The 64-link chain over 0.02 s at 1 kg and at 0.1 kg a link (IDA, rtol 1e-8, atol 1e-10,
    !> the default Newton matrix): both complete, with the same number of rows, and every
    !> part's coordinates [m, rad] and rates [m/s, rad/s] in the light chain's rows within tol
    !> of the heavy chain's, on the scale of each (its largest magnitude, at least 1).
    subroutine test_light_chain(error)
        type(error_type), allocatable, intent(out) :: error
        !> The two runs take their own steps (the light one's first step is IDA's second try),
        !> each with its own global error at rtol 1e-8: on a column's scale (its largest
        !> magnitude, at least 1 in its SI unit) they differ by 2.3e-7 at most (measured: the
        !> spin rates of the top two links, 1.4 and 0.43 rad/s); nine times that. A start that
        !> went wrong, or mass entering the motion, moves the chain by far more
        real(wp), parameter :: tol = 2.0e-6_wp
        character(len=*), parameter :: heavy_ip = "IP=0.0008333333333333335, " &
            & // "0.0008333333333333335, 0.0008333333333333335"
        character(len=*), parameter :: light_ip = "IP=8.333333333333335E-5, " &
            & // "8.333333333333335E-5, 8.333333333333335E-5"
        character(len=:), allocatable :: heavy, light
        type(history_type) :: heavy_rows, light_rows
        real(wp) :: worst
        integer :: p, c

        heavy = link_chain_dataset(64, 0.02_wp, 0.01_wp, "FORMULATION=IDA, RTOL=1e-8, ATOL=1e-10")
        call check(error, count_of(heavy, "MASS=1,") == 64 .and. count_of(heavy, heavy_ip) == 64, &
            & "the generator's parts are no longer 'MASS=1, ... " // heavy_ip // "'")
        if (allocated(error)) return
        light = replaced(replaced(heavy, "MASS=1,", "MASS=0.1,"), heavy_ip, light_ip)
        call run_dataset_text(folder, "chain_64_heavy", heavy, heavy_rows, error)
        if (allocated(error)) return
        call run_dataset_text(folder, "chain_64_light", light, light_rows, error)
        if (allocated(error)) return
        call check(error, light_rows%count == heavy_rows%count, "rows: " &
            & // to_text(light_rows%count) // " against " // to_text(heavy_rows%count))
        if (allocated(error)) return
        worst = 0.0_wp
        do p = 1, 64
            do c = 1, 12
                worst = max(worst, maxval(abs(light_rows%part_values(p, c) &
                    & - heavy_rows%part_values(p, c)))/max(1.0_wp, &
                    & maxval(abs(heavy_rows%part_values(p, c)))))
            end do
        end do
        call check(error, worst <= tol, "the light chain moves otherwise than the heavy one by " &
            & // to_text(worst))
    end subroutine test_light_chain

    !> text with every old replaced by new.
    pure function replaced(text, old, new) result(out)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: out
        integer :: at, found

        out = ""
        at = 1
        do
            found = index(text(at:), old)
            if (found == 0) exit
            out = out // text(at:at + found - 2) // new
            at = at + found - 1 + len(old)
        end do
        out = out // text(at:)
    end function replaced

end module test_ida_first_step
