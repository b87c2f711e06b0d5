! SPDX-License-Identifier: MIT
!> Fuzz test of the scene reader: seeded mutations of the shipped scenes must each give a clean
!> refusal (an input error naming the file and a line, in visible characters) or a clean read
!> whose values are finite and physical; never a crash.
module test_scene_fuzz
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : line_type, read_lines
    use rollcon_scene, only : scene_type, read_scene, read_scene_lines
    use rollcon_scene_state, only : disk_mass_properties, disk_initial_state
    use rollcon_disk_scene, only : build_disk_problem
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use disk_states, only : seed_random
    use scene_mutations, only : mutate
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: collect_scene_fuzz

    !> Mutated files read in memory
    integer, parameter :: mutation_count = 12000
    !> Every this many, the mutated file is also written under build/ and read from disk
    integer, parameter :: disk_every = 400
    !> Every this many clean reads, the problem is built too (no integration)
    integer, parameter :: build_every = 50
    !> Least share of each outcome: a reader that refuses or accepts everything fails
    real(wp), parameter :: least_share = 0.05_wp
    !> Relative tolerance of z = R sin(theta) after a read: one rounding of a product
    real(wp), parameter :: tol_contact = 1.0e-15_wp
    !> The shipped scenes
    character(len=*), parameter :: names(*) = [character(len=13) :: "coin", "fast_upright", &
        & "long_run", "near_flat", "spinning_coin", "steady_circle", "tipping_coin"]

contains

    !> Tests of this suite.
    subroutine collect_scene_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("mutated-scenes", test_mutated_scenes)]
    end subroutine collect_scene_fuzz

    subroutine test_mutated_scenes(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(scene_type) :: scene
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path
        integer :: m, f, refused, accepted

        refused = 0
        accepted = 0
        call seed_random(20261123)
        do m = 1, mutation_count
            f = 1 + mod(m - 1, size(names))
            call read_lines("data/" // trim(names(f)) // ".nml", lines, error)
            if (allocated(error)) return
            call mutate(lines)
            path = "fuzz/" // trim(names(f)) // ".nml"
            if (mod(m, disk_every) == 0) then
                path = "build/test_scene_fuzz.nml"
                call write_lines(path, lines)
                call read_scene(path, scene, found)
            else
                call read_scene_lines(path, lines, scene, found)
            end if
            if (allocated(found)) then
                refused = refused + 1
                call check_refusal(found, path, m, error)
            else
                accepted = accepted + 1
                call check_clean(scene, mod(accepted, build_every) == 0, m, error)
            end if
            if (allocated(error)) return
        end do
        call check(error, min(refused, accepted) >= least_share*mutation_count, &
            & "outcomes too one-sided: " // to_text(refused) // " refused, " &
            & // to_text(accepted) // " accepted")
    end subroutine test_mutated_scenes

    !> An input error that starts with 'path:LINE: ' (LINE >= 1), or 'path: ' for a default
    !> value, and shows only printable ASCII.
    subroutine check_refusal(found, path, m, error)
        type(error_type), intent(in) :: found
        character(len=*), intent(in) :: path
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: rest
        integer :: j, line, stat

        call check(error, found%stat == stat_input .and. allocated(found%message), &
            & "mutation " // to_text(m) // ": not an input error")
        if (allocated(error)) return
        call check(error, all([(iachar(found%message(j:j)) >= 32 .and. &
            & iachar(found%message(j:j)) < 127, j = 1, len(found%message))]), &
            & "mutation " // to_text(m) // ": invisible character in: " // found%message)
        if (allocated(error)) return
        call check(error, index(found%message, path // ":") == 1, "mutation " // to_text(m) &
            & // ": message does not start with the file: " // found%message)
        if (allocated(error)) return
        rest = found%message(len(path) + 2:)
        if (index(rest, "(the default of &") > 0 .and. rest(1:1) == " ") return
        j = index(rest, ":")
        line = 0
        stat = 1
        if (j > 1) read(rest(:j - 1), *, iostat=stat) line
        call check(error, stat == 0 .and. line >= 1, "mutation " // to_text(m) &
            & // ": message does not name a line: " // found%message)
    end subroutine check_refusal

    !> Every value finite and physical; z on the contact; mass, inertia, initial state finite;
    !> and when build, the problem built from it.
    subroutine check_clean(scene, build, m, error)
        type(scene_type), intent(in) :: scene
        logical, intent(in) :: build
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        real(wp) :: mass, inertia(3), q(6), u(6), q0(6), u0(6)
        logical :: physical

        call disk_mass_properties(scene, mass, inertia)
        call disk_initial_state(scene, q, u)
        associate (d => scene%disk, i => scene%initial, r => scene%run)
            physical = all(ieee_is_finite([d%radius, d%thickness, d%density, &
                & scene%environment%gravity, q, u, mass, inertia, scene%strike%time, &
                & scene%strike%duration, scene%strike%impulse, r%end_time, r%output_step, &
                & r%rtol, r%atol, r%baumgarte_rate, scene%limits%theta_min])) &
                & .and. d%radius > 0.0_wp .and. d%thickness > 0.0_wp .and. mass > 0.0_wp &
                & .and. minval(inertia) > 0.0_wp .and. scene%environment%gravity >= 0.0_wp &
                & .and. i%theta > 0.0_wp .and. i%theta < pi .and. r%end_time > 0.0_wp &
                & .and. r%output_step > 0.0_wp .and. r%output_step <= r%end_time &
                & .and. r%rtol > 0.0_wp .and. r%rtol < 1.0_wp .and. r%atol > 0.0_wp &
                & .and. r%max_steps > 0 .and. scene%strike%duration > 0.0_wp &
                & .and. scene%limits%theta_min < i%theta &
                & .and. abs(i%z - d%radius*sin(i%theta)) <= tol_contact*d%radius
        end associate
        call check(error, physical, "mutation " // to_text(m) // ": a clean read of " &
            & // scene%name // " holds a value that is not finite or not physical")
        if (allocated(error) .or. .not. build) return
        call build_disk_problem(scene, rolling_disk_ucosub, problem, q0, u0, error)
        if (allocated(error)) return
        ! the right-hand side is not evaluated: rollcon_equations' array temporaries would
        ! print runtime warnings into the test log (see the dynamics suite)
        call check(error, all(ieee_is_finite([q0, u0, problem%model%parts(1)%mass, &
            & problem%model%parts(1)%inertia, problem%model%gravity])), "mutation " &
            & // to_text(m) // ": the problem of a clean read is not finite")
        if (allocated(error)) return
        call check(error, all(abs(q0 - q) <= 0.0_wp) .and. all(abs(u0 - u) <= 0.0_wp), &
            & "mutation " // to_text(m) // ": the problem's initial state is not the scene's")
    end subroutine check_clean

    subroutine write_lines(path, lines)
        character(len=*), intent(in) :: path
        type(line_type), intent(in) :: lines(:)
        integer :: unit, i

        open(newunit=unit, file=path, status="replace", action="write")
        do i = 1, size(lines)
            write(unit, "(a)") lines(i)%text
        end do
        close(unit)
    end subroutine write_lines

end module test_scene_fuzz
