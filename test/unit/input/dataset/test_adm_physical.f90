! SPDX-License-Identifier: MIT
!> A dataset's values beyond physics, and loads that stop being finite during a run (suite
!> adm-physical): a speed of 1e300 m/s, a gravity of 1e300 m/s^2 and a mass of 1e308 kg are
!> refused by name (they ended in a garbage failure time or in dgesvd); a translational SFORCE
!> between coincident markers is refused by name (it failed as a UCOSUB's non-finite value); a
!> force expression that becomes infinite during the run fails it, naming the statement, and no
!> row that is not finite is written (such a row ended "completed", exit 0).
module test_adm_physical
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_adm_model, only : adm_model_type
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_failed
    use rollcon_testing, only : unittest_type, new_unittest, check
    use adm_build_support, only : write_lines, read_lines_model
    implicit none
    private

    public :: collect_adm_physical

contains

    subroutine collect_adm_physical(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("speed-beyond-light-refused", test_speed), &
            & new_unittest("gravity-beyond-range-refused", test_gravity), &
            & new_unittest("mass-beyond-range-refused", test_mass), &
            & new_unittest("coincident-sforce-markers-refused", test_coincident), &
            & new_unittest("infinite-force-fails-naming-it", test_infinite_force), &
            & new_unittest("runaway-force-fails-naming-it", test_runaway_force)]
    end subroutine collect_adm_physical

    subroutine test_speed(error)
        type(error_type), allocatable, intent(out) :: error

        call refused(", VX=0.1                ! rolling along +X at 0.1 m/s ...", &
            & ", VX=1e300", ":23: PART/2 VX, VY, VZ: the speed must be below the speed of " &
            & // "light 299792458 [m/s] (the mechanics is Newtonian), got 1e300 m/s", error)
    end subroutine test_speed

    subroutine test_gravity(error)
        type(error_type), allocatable, intent(out) :: error

        call refused("ACCGRAV/KGRAV=-9.81", "ACCGRAV/KGRAV=-1e300", ":31: ACCGRAV KGRAV must " &
            & // "be at most 10000 [m/s^2] in magnitude (36 times the Sun's surface gravity), " &
            & // "got -1e300 m/s^2", error)
    end subroutine test_gravity

    subroutine test_mass(error)
        type(error_type), allocatable, intent(out) :: error

        call refused("PART/2, MASS=0.73513268094001172, CM=3", "PART/2, MASS=1e308, CM=3", &
            & ":23: PART/2 MASS must be at most 1e15 [kg], got 1e308 kg", error)
    end subroutine test_mass

    !> An SFORCE from the coin's CM marker to a ground marker at the same point.
    subroutine test_coincident(error)
        type(error_type), allocatable, intent(out) :: error

        call run_refused("SIMULATE/DYNAMIC, END=10, STEPS=1000", "MARKER/9, PART=1, QP=0, " &
            & // "0, 0.1" // new_line("a") // "SFORCE/8, TRANSLATION, I=3, J=9, FUNCTION=1" &
            & // new_line("a") // "SIMULATE/DYNAMIC, END=1, STEPS=100", "coincident.adm", &
            & ": SFORCE/8: its I and J markers are at one point at the start, where a " &
            & // "translational SFORCE's line of action (from J to I) is not defined", error)
    end subroutine test_coincident

    !> A VFORCE on the coin whose FZ = 1/(TIME - 0.25) is not finite at t = 0.25 s, an output
    !> time: the run fails there, its error names VFORCE/7 and FZ, and every row kept is finite
    !> (the 25 before it).
    subroutine test_infinite_force(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result
        type(history_type) :: history
        type(error_type), allocatable :: failure

        call write_lines("data/coin.adm", "infinite_force.adm", &
            & "SIMULATE/DYNAMIC, END=10, STEPS=1000", "VFORCE/7, I=3, JFLOAT=2, RM=1, FX=0, " &
            & // "FY=0, FZ=1/(TIME-0.25)" // new_line("a") // "SIMULATE/DYNAMIC, END=1, " &
            & // "STEPS=100", error)
        if (allocated(error)) return
        call load_job("build/rollcon-test/infinite_force.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, history)
        call check(error, allocated(failure), "the run with an infinite force did not fail")
        if (allocated(error)) return
        call check(error, result%summary%status == status_failed .and. &
            & index(failure%message, ": VFORCE/7 FZ = ") > 0 .and. &
            & index(failure%message, "the load is not finite at t = 0.25 s") > 0, "message: " &
            & // failure%message)
        if (allocated(error)) return
        call check(error, history%count == 25 .and. all(ieee_is_finite(history%rows(:, &
            & :history%count))), to_text(history%count) // " rows kept (25 expected), all " &
            & // "finite: " // merge("yes", "no ", all(ieee_is_finite(history%rows(:, &
            & :history%count)))))
    end subroutine test_infinite_force

    !> A VFORCE on the coin whose FX = EXP(1000 TIME) is finite until t = 0.71 s but passes
    !> 1.3e154 at t = 0.36 s: the coin's speed, and with it the energy, overflow and the row at
    !> t = 0.37 s is not finite. The failure names VFORCE/7 and FX, with its value and the
    !> time, not "the accelerations are not finite (a singular mass matrix ...)", which they
    !> are not; every row kept is finite.
    subroutine test_runaway_force(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result
        type(history_type) :: history
        type(error_type), allocatable :: failure

        call write_lines("data/coin.adm", "runaway_force.adm", &
            & "SIMULATE/DYNAMIC, END=10, STEPS=1000", "VFORCE/7, I=3, JFLOAT=2, RM=1, " &
            & // "FX=EXP(1000*TIME), FY=0, FZ=0" // new_line("a") // "SIMULATE/DYNAMIC, END=1, " &
            & // "STEPS=100", error)
        if (allocated(error)) return
        call load_job("build/rollcon-test/runaway_force.adm", job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, history)
        call check(error, allocated(failure), "the run with a runaway force did not fail")
        if (allocated(error)) return
        call check(error, result%summary%status == status_failed .and. &
            & index(failure%message, ": VFORCE/7 FX = ") > 0 .and. &
            & index(failure%message, "has run away") > 0 .and. &
            & index(failure%message, "singular mass matrix") == 0, "message: " &
            & // failure%message)
        if (allocated(error)) return
        call check(error, history%count >= 1 .and. all(ieee_is_finite(history%rows(:, &
            & :history%count))), to_text(history%count) // " rows kept, all finite: " &
            & // merge("yes", "no ", all(ieee_is_finite(history%rows(:, :history%count)))))
    end subroutine test_runaway_force

    !> data/coin.adm with the line old replaced by new is refused by read_adm with a message
    !> that ends in expected (after the file name).
    subroutine refused(old, new, expected, error)
        character(len=*), intent(in) :: old, new, expected
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(error_type), allocatable :: failure

        call read_lines_model("physical.adm", old, new, adm, failure)
        call check(error, allocated(failure), "accepted: " // new)
        if (allocated(error)) return
        call check(error, index(failure%message, expected) > 0 .and. &
            & index(failure%message, "physical.adm") == index(failure%message, ":") - &
            & len("physical.adm"), "message '" // failure%message // "', expected '" &
            & // expected // "'")
    end subroutine refused

    !> data/coin.adm with the line old replaced by new reads, and its job is refused before it
    !> starts with a message holding expected.
    subroutine run_refused(old, new, name, expected, error)
        character(len=*), intent(in) :: old, new, name, expected
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(job_result_type) :: result
        type(error_type), allocatable :: failure

        call write_lines("data/coin.adm", name, old, new, error)
        if (allocated(error)) return
        call load_job("build/rollcon-test/" // name, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure)
        call check(error, allocated(failure) .and. .not. result%started, "not refused: " &
            & // new)
        if (allocated(error)) return
        call check(error, index(failure%message, expected) > 0, "message '" &
            & // failure%message // "', expected '" // expected // "'")
    end subroutine run_refused

end module test_adm_physical
