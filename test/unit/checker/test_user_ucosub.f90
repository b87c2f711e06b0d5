! SPDX-License-Identifier: MIT
!> A user's own UCOSUB, loaded at run time: the generated fixed-form disk routine passes the
!> check and simulates like the built-in one; each planted mistake of test/faulty_ucosubs/ is
!> caught with the right finding; files that cannot serve give clear errors.
module test_user_ucosub
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_par, only : disk_par, disk_codes
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_gen_rolling_disk, only : generated_disk_ucosub => rolling_disk_ucosub
    use rollcon_user_library, only : user_ucosub_type
    use rollcon_partials_check, only : ucon_check_options_type, ucon_check_result_type, &
        & check_ucon_state
    use rollcon_ucosub_audit, only : ucon_request_type, user_check_options_type, &
        & user_check_report_type, check_user_ucosub
    use rollcon_scene, only : scene_type, read_scene, scene_path
    use rollcon_simulation, only : history_type, run_summary_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use motion_runs, only : run_in_memory
    use user_ucosub_support, only : faulty, disk_source, test_states, load, listing, &
        & check_disk_file, expect_group, expect_clean, expect_in
    use user_ucosub_reports, only : test_report, test_report_exponent
    use user_ucosub_loading, only : test_does_not_compile, test_no_ucosub, test_missing_file, &
        & test_free_form, test_object
    implicit none
    private

    public :: collect_user_ucosub

contains

    !> Tests of this suite.
    subroutine collect_user_ucosub(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("generated-disk-clean", test_disk_clean), &
            & new_unittest("cache-reused", test_cache_reused), &
            & new_unittest("sign-error", test_sign_error), &
            & new_unittest("wrong-selector-guard", test_wrong_guard), &
            & new_unittest("missing-symmetric-entry", test_missing_symmetric), &
            & new_unittest("forgotten-ucovar", test_no_ucovar), &
            & new_unittest("part-id-not-in-par", test_hardcoded_part), &
            & new_unittest("quadratic-in-velocity", test_quadratic), &
            & new_unittest("errmes-reaches-rollcon", test_errmes), &
            & new_unittest("outside-block", test_outside_block), &
            & new_unittest("report-text-and-json", test_report), &
            & new_unittest("report-three-digit-exponent", test_report_exponent), &
            & new_unittest("does-not-compile", test_does_not_compile), &
            & new_unittest("no-ucosub", test_no_ucosub), &
            & new_unittest("missing-file", test_missing_file), &
            & new_unittest("free-form-source", test_free_form), &
            & new_unittest("object-file", test_object), &
            & new_unittest("coin-matches-hand-checked", test_trajectory_hand), &
            & new_unittest("tipping-coin-matches-generated", test_trajectory_generated)]
    end subroutine collect_user_ucosub

    subroutine test_disk_clean(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        integer :: k

        call check_disk_file(disk_source, report, error)
        if (allocated(error)) return
        do k = 1, 3
            call check(error, report%ucons(k)%declared, "UCON/" // to_text(k) // " not declared")
            if (allocated(error)) return
            call check(error, all(report%ucons(k)%codes == disk_codes) .and. &
                & all(report%ucons(k)%parts == 1), "declared codes or parts differ from the disk's")
            if (allocated(error)) return
            call check(error, report%ucons(k)%states, test_states, "states checked")
            if (allocated(error)) return
            call expect_clean(error, report, k)
            if (allocated(error)) return
        end do
        call check(error, report%clean(), "report not clean")
    end subroutine test_disk_clean

    !> An unchanged file is not rebuilt.
    subroutine test_cache_reused(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: first, second

        call load(disk_source, first, error)
        if (allocated(error)) return
        call load(disk_source, second, error)
        if (allocated(error)) return
        call check(error, second%from_cache, "the second load rebuilt " // second%library)
        if (allocated(error)) return
        call check(error, second%library == first%library, "two libraries for one file: " &
            & // first%library // ", " // second%library)
        call first%destroy()
        call second%destroy()
    end subroutine test_cache_reused

    subroutine test_sign_error(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        integer :: g

        call check_disk_file(faulty // "sign_error.f", report, error)
        if (allocated(error)) return
        call expect_group(error, report, 2, "derivative", "ARRAY (dF/dq)", 5, 0, g)
        if (allocated(error)) return
        call check(error, report%ucons(2)%groups(g)%count, test_states, "states with the finding")
        if (allocated(error)) return
        call expect_clean(error, report, 1)
        if (allocated(error)) return
        call expect_clean(error, report, 3)
    end subroutine test_sign_error

    subroutine test_wrong_guard(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        integer :: k

        call check_disk_file(faulty // "wrong_guard.f", report, error)
        if (allocated(error)) return
        do k = 1, 3
            call expect_group(error, report, k, "derivative", "XMATRX (d2F/dq dq)", 5, 5)
            if (allocated(error)) return
            call expect_selector(error, report, k)
            if (allocated(error)) return
        end do
    end subroutine test_wrong_guard

    !> UCON k has a selector-0 finding on XMATRX.
    subroutine expect_selector(error, report, k)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type), intent(in) :: report
        integer, intent(in) :: k
        integer :: g

        do g = 1, size(report%ucons(k)%groups)
            if (report%ucons(k)%groups(g)%rule == "selector-0" &
                & .and. report%ucons(k)%groups(g)%output == "XMATRX") return
        end do
        call check(error, .false., "UCON/" // to_text(k) // ": no [selector-0] XMATRX" &
            & // listing(report%ucons(k)))
    end subroutine expect_selector

    subroutine test_missing_symmetric(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report

        call check_disk_file(faulty // "missing_symmetric.f", report, error)
        if (allocated(error)) return
        call expect_group(error, report, 1, "symmetry", "XMATRX (d2F/dq dq)", 7, 5)
        if (allocated(error)) return
        call expect_clean(error, report, 2)
        if (allocated(error)) return
        call expect_clean(error, report, 3)
    end subroutine test_missing_symmetric

    subroutine test_no_ucovar(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        integer :: k

        call check_disk_file(faulty // "no_ucovar.f", report, error)
        if (allocated(error)) return
        do k = 1, 3
            call check(error, .not. report%ucons(k)%declared .and. report%ucons(k)%states == 0, &
                & "UCON/" // to_text(k) // " counted as declared or checked")
            if (allocated(error)) return
            call expect_group(error, report, k, "declaration", "UCOVAR", 0, 0)
            if (allocated(error)) return
            call expect_in(error, report%ucons(k)%groups(1)%message, "made no UCOVAR call")
            if (allocated(error)) return
        end do
    end subroutine test_no_ucovar

    subroutine test_hardcoded_part(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        integer :: g

        ! UCON 2 (PAR = 2, codes, 0.1, 2) does not mention part 1; UCON 1 does, by chance, as
        ! its component number PAR(11) = 1, and a free-form PAR cannot tell the two apart.
        call check_disk_file(faulty // "hardcoded_part.f", report, error, part=2)
        if (allocated(error)) return
        call expect_group(error, report, 2, "declaration", "UCOVAR", 1, 0, g)
        if (allocated(error)) return
        call expect_in(error, report%ucons(2)%groups(g)%message, &
            & "declares part id 1 (variable 1), which no PAR entry mentions")
        if (allocated(error)) return
        ! With the part the routine assumes, it is a correct disk.
        call check_disk_file(faulty // "hardcoded_part.f", report, error, part=1)
        if (allocated(error)) return
        call check(error, report%clean(), "hardcoded_part.f with part 1 has findings")
    end subroutine test_hardcoded_part

    subroutine test_quadratic(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_check_report_type) :: report
        integer :: g

        call check_disk_file(faulty // "quadratic_velocity.f", report, error)
        if (allocated(error)) return
        call expect_group(error, report, 3, "velocity-linear", "XMATRX (d2F/dq dq)", 3, 3)
        if (allocated(error)) return
        call expect_group(error, report, 3, "velocity-linear", "XMATRX (d2F/dq dq)", 7, 7)
        if (allocated(error)) return
        do g = 1, size(report%ucons(3)%groups)
            call check(error, report%ucons(3)%groups(g)%rule == "velocity-linear", &
                & "the partials are right, yet" // listing(report%ucons(3)))
            if (allocated(error)) return
        end do
        call expect_clean(error, report, 1)
    end subroutine test_quadratic

    !> The fixed-form routine's ERRMES call (a CHARACTER*120 message) crosses the shim intact:
    !> with NPAR = 2 its PAR check fails on the initialisation call.
    subroutine test_errmes(error)
        type(error_type), allocatable, intent(out) :: error
        type(user_ucosub_type) :: user
        type(ucon_request_type) :: request(1)
        type(user_check_options_type) :: options
        type(user_check_report_type) :: report
        integer :: g

        call load(disk_source, user, error)
        if (allocated(error)) return
        request(1)%id = 4
        request(1)%par = [1.0_wp, 21.0_wp]
        call check_user_ucosub(user%ucosub, request, options, report, error)
        call user%destroy()
        if (allocated(error)) return
        call expect_group(error, report, 1, "declaration", "UCOVAR", 0, 0, g)
        if (allocated(error)) return
        call expect_in(error, report%ucons(1)%groups(g)%message, "UCON/4: rolling disk needs " &
            & // "NPAR >= 11 (part id, 8 codes, disk radius R, no-slip component), got NPAR =")
    end subroutine test_errmes

    !> The disk routine that also writes past its 8 declared variables (the rule added to
    !> check_ucon_state for this suite's checker).
    subroutine outside_block_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        integer, intent(in) :: id, npar, idrsel(3), iflag
        real(wp), intent(in) :: time, q(30), par(*)
        real(wp), intent(inout) :: scalar, array(30), xmatrx(30, 30)

        call rolling_disk_ucosub(id, time, q, par, npar, idrsel, iflag, scalar, array, xmatrx)
        if (iflag /= 0) return
        if (idrsel(2) == 1) array(9) = 0.5_wp
        if (idrsel(3) == 1) xmatrx(2, 9) = 0.25_wp
    end subroutine outside_block_ucosub

    subroutine test_outside_block(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_check_options_type) :: options
        type(ucon_check_result_type) :: result
        integer :: i
        logical :: array_found, xmatrx_found

        call check_ucon_state(outside_block_ucosub, 1, disk_par(1, 0.1_wp, 1), disk_codes, &
            & 0.0_wp, [0.1_wp, 0.02_wp, -0.01_wp, 0.3_wp, 1.2_wp, 0.5_wp, -0.2_wp, -1.0_wp], &
            & options, result, error)
        if (allocated(error)) return
        array_found = .false.
        xmatrx_found = .false.
        do i = 1, size(result%mismatches)
            associate (m => result%mismatches(i))
                if (m%rule /= "outside-block") cycle
                array_found = array_found .or. (m%output == "ARRAY (dF/dq)" .and. m%row == 9)
                xmatrx_found = xmatrx_found .or. (m%output == "XMATRX (d2F/dq dq)" &
                    & .and. m%row == 2 .and. m%column == 9 .and. m%returned == 0.25_wp)
            end associate
        end do
        call check(error, array_found .and. xmatrx_found, "outside-block findings: ARRAY(9) " &
            & // merge("found  ", "missing", array_found) // ", XMATRX(2,9) " &
            & // merge("found  ", "missing", xmatrx_found))
    end subroutine test_outside_block

    !> The paper's coin over its first second (upright rolling at 0.1 m/s, before the strike),
    !> served by the generated ucosub.f loaded at run time, against the built-in hand-checked
    !> routine. The two compute the same constraint with differently arranged arithmetic, so a
    !> call may differ in the last bit, but on this motion every difference stays at round-off
    !> (measured: 0 in the coordinates, below 1e-28 in the near-zero columns); 1e-12 allows for
    !> that while a wrong partial anywhere would show at the integrator's tolerance (1e-8).
    subroutine test_trajectory_hand(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: tol_round_off = 1.0e-12_wp

        call compare_trajectories(error, "coin", rolling_disk_ucosub, tol_round_off)
    end subroutine test_trajectory_hand

    !> The tipping coin over 1 s (it falls to theta ~ 0.1 rad, precessing at up to 180 rad/s:
    !> every partial matters, and round-off differences grow to the tolerance's level, 1e-7,
    !> as the hand-checked routine shows), loaded ucosub.f against the built-in generated module
    !> it was generated with. Both run the same sequence of IEEE double operations (the same
    !> common subexpressions, in the same order; gfortran neither reassociates without
    !> -ffast-math nor fuses multiply-adds on x86-64 without -mfma, at -O0 or -O2), so the
    !> trajectories are identical, bit for bit.
    subroutine test_trajectory_generated(error)
        type(error_type), allocatable, intent(out) :: error

        call compare_trajectories(error, "tipping_coin", generated_disk_ucosub, 0.0_wp)
    end subroutine test_trajectory_generated

    !> Simulate scene over 1 s with the loaded disk routine and with reference; compare rows.
    subroutine compare_trajectories(error, name, reference, tolerance)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), intent(in) :: name
        procedure(ucosub_interface) :: reference
        real(wp), intent(in) :: tolerance
        type(user_ucosub_type) :: user
        type(scene_type) :: scene
        type(history_type) :: loaded, built_in
        type(run_summary_type) :: summary
        real(wp) :: largest

        call read_scene(scene_path(name), scene, error)
        if (allocated(error)) return
        scene%run%end_time = 1.0_wp
        call load(disk_source, user, error)
        if (allocated(error)) return
        call run_in_memory(scene, loaded, summary, error, user%ucosub)
        call user%destroy()
        if (allocated(error)) return
        call run_in_memory(scene, built_in, summary, error, reference)
        if (allocated(error)) return
        call check(error, loaded%count, built_in%count, name // ": output rows")
        if (allocated(error)) return
        call check(error, loaded%count > 100, name // ": only " // to_text(loaded%count) // " rows")
        if (allocated(error)) return
        largest = maxval(abs(loaded%rows(:, :loaded%count) - built_in%rows(:, :built_in%count)))
        call check(error, largest, 0.0_wp, name // ": largest difference of the trajectories", &
            & abs_tol=tolerance)
    end subroutine compare_trajectories

end module test_user_ucosub
