! SPDX-License-Identifier: MIT
!> Fuzz test of the study reader (read_study): seeded mutations of the shipped study files and
!> of written ones (random samples; a dataset's parameters) must each give a clean refusal (an
!> input error naming the file and a line, or the file for what concerns it whole, in visible
!> characters) or a clean read whose values are finite and within the documented ranges
!> (docs/studies.md); never a crash or a hang. The inputs the fuzzer found bugs with are kept
!> as deterministic tests.
module test_study_fuzz
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : line_type, read_lines
    use rollcon_study_type, only : study_type, sampling_grid, sampling_random
    use rollcon_study_reader, only : read_study
    use rollcon_study_parameters, only : case_count
    use rollcon_study_measures, only : measure_index
    use rollcon_testing, only : unittest_type, new_unittest, check
    use fuzz_mutations, only : seed_fuzz, mutate_lines, write_lines, printable
    use study_texts, only : expect_study_error
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: collect_study_fuzz

    !> Mutated study files read
    integer, parameter :: mutation_count = 10000
    !> Least share of each outcome: a reader that refuses or accepts everything fails
    real(wp), parameter :: least_share = 0.05_wp
    !> Seed of the mutations
    integer, parameter :: seed = 20260525
    !> The shipped studies
    character(len=*), parameter :: shipped(*) = [character(len=30) :: &
        & "data/upright_stability.nml", "data/no_slip_validity.nml", "data/bench_sweep.nml", &
        & "data/friction_needed.nml"]
    !> A study by random samples, with every key of its groups
    character(len=*), parameter :: random_study(*) = [character(len=60) :: &
        & "! random samples of the coin's speed and tilt", &
        & "&study scene = 'coin', title = 'Random coin starts' /", &
        & "&random", &
        & "    samples = 40, seed = 7", &
        & "    initial%speed = '0.1 2.0'", &
        & "    initial%theta = '0.5 1.5' /", &
        & "&classify", &
        & "    tips = 'theta_min <= 0.2'", &
        & "    slow = 'energy_drift < 1e-6'", &
        & "    otherwise = 'rolls' /", &
        & "&map x = 'initial%theta', y = 'initial%speed' /"]
    !> A study of a dataset's values
    character(len=*), parameter :: dataset_study(*) = [character(len=60) :: &
        & "&study", "    scene = 'data/coin.adm' /", "&grid", &
        & "    part%2%vx = '0.1 0.2 2'", "    marker%3%qp%3 = '0 0.01 2'", &
        & "    accgrav%kgrav = '-9.81 -5 2' /"]
    !> Words a mutation may insert: groups, keys, measures, relations, values
    character(len=*), parameter :: words(*) = [character(len=16) :: "&study", "&grid", &
        & "&random", "&classify", "&map", "/", "scene", "title", "samples", "seed", &
        & "disk%thickness", "initial%speed", "strike%impulse", "run%max_steps", "otherwise", &
        & "x", "y", "curve", "critical_speed", "tilt_max", "fn_min", "mu_max", ">", "<=", "'", &
        & "=", "!", "%", "'0 1 3'", "'1 1 1'", "data/coin.adm", "part%2%vx", "marker%3%qp%3", &
        & "2147483647", "nan", "1e999"]

contains

    !> Tests of this suite.
    subroutine collect_study_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("mutated-studies", test_mutated_studies), &
            & new_unittest("found-inputs-refused", test_found_inputs)]
    end subroutine collect_study_fuzz

    subroutine test_mutated_studies(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: bases(:, :), lines(:)
        integer, allocatable :: lengths(:)
        type(study_type) :: study
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path
        integer :: m, f, refused, accepted
        logical :: memory

        ! in memory when possible: 10 000 files replaced on a disk cost seconds of I/O
        inquire(file="/dev/shm/.", exist=memory)
        path = "build/test_study_fuzz.nml"
        if (memory) path = "/dev/shm/rollcon_test_study_fuzz_" // to_text(getpid()) // ".nml"
        call base_studies(path, bases, lengths, error)
        if (allocated(error)) return
        refused = 0
        accepted = 0
        call seed_fuzz(seed)
        do m = 1, mutation_count
            f = 1 + mod(m - 1, size(lengths))
            lines = bases(:lengths(f), f)
            call mutate_lines(lines, words)
            call write_lines(path, lines)
            call read_study(path, study, found)
            if (allocated(found)) then
                refused = refused + 1
                call check_refusal(found, path, m, error)
            else
                accepted = accepted + 1
                call check_clean(study, m, error)
            end if
            if (allocated(error)) then
                error%message = error%message // " (study " // path // ")"
                return
            end if
        end do
        call delete(path)
        call check(error, min(refused, accepted) >= least_share*mutation_count, &
            & "outcomes too one-sided: " // to_text(refused) // " refused, " &
            & // to_text(accepted) // " accepted")
    end subroutine test_mutated_studies

    !> The mutations that were read with a value that is not finite, a count that overflows,
    !> or refused with a control character in the message: each refused now, visibly.
    subroutine test_found_inputs(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: head(2) = [character(len=60) :: &
            & "&study scene = 'data/upright.nml' /", "&grid disk%thickness = '0.01 0.2 20'"]

        ! a bound beyond the largest double: read as Infinity, and NaN: both taken as bounds
        call expect_study_error(error, "test_study_fuzz_bound", [character(len=60) :: head, &
            & "    initial%speed = '0.4 1.0 61' /", "&classify falls = 'tilt_max > 1e309' /"], &
            & [character(len=120) :: "@:4: 'falls' reads 'measure relation number': '1e309' " &
            & // "is not a finite number"])
        if (allocated(error)) return
        call expect_study_error(error, "test_study_fuzz_nan", [character(len=60) :: head, &
            & "    initial%speed = '0.4 1.0 61' /", "&classify falls = 'tilt_max > nan' /"], &
            & [character(len=120) :: "@:4: 'falls' reads 'measure relation number': 'nan' " &
            & // "is not a finite number"])
        if (allocated(error)) return
        ! 20 x 2147483647 cases: the case count, a default integer, overflowed to a negative;
        ! refused, counted without wrap-round, at the grid's line (check_case_count)
        call expect_study_error(error, "test_study_fuzz_cases", [character(len=60) :: head, &
            & "    initial%speed = '0.4 1.0 2147483647' /"], [character(len=120) :: &
            & "@:2: the study has 42949672940 cases (&grid: 20 x 2147483647); a study may " &
            & // "have at most 2000000"])
        if (allocated(error)) return
        ! a tab in the base scene's path was copied raw into the message
        call expect_study_error(error, "test_study_fuzz_tab", [character(len=60) :: &
            & "&study scene = 'data/up" // achar(9) // "right.nml' /", head(2), &
            & "    initial%speed = '0.4 1.0 61' /"], [character(len=120) :: "@:1: 'scene' names " &
            & // "a base scene that cannot be read: data/up\x09right.nml: no such scene file"])
    end subroutine test_found_inputs

    !> The lines of every base study (column f: study f, its first lengths(f) lines), each of
    !> which must read cleanly as it is (written to path).
    subroutine base_studies(path, bases, lengths, error)
        character(len=*), intent(in) :: path
        type(line_type), allocatable, intent(out) :: bases(:, :)
        integer, allocatable, intent(out) :: lengths(:)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(study_type) :: study
        integer :: f

        allocate(bases(100, size(shipped) + 2), lengths(size(shipped) + 2))
        do f = 1, size(lengths)
            if (f <= size(shipped)) then
                call read_lines(trim(shipped(f)), lines, error)
                if (allocated(error)) return
            else if (f == size(shipped) + 1) then
                lines = as_lines(random_study)
            else
                lines = as_lines(dataset_study)
            end if
            lengths(f) = size(lines)
            bases(:size(lines), f) = lines
            call write_lines(path, lines)
            call read_study(path, study, error)
            if (allocated(error)) return
        end do
    end subroutine base_studies

    !> Texts as lines, trailing blanks dropped.
    pure function as_lines(texts) result(lines)
        character(len=*), intent(in) :: texts(:)
        type(line_type), allocatable :: lines(:)
        integer :: j

        allocate(lines(size(texts)))
        do j = 1, size(texts)
            lines(j)%text = trim(texts(j))
        end do
    end function as_lines

    !> An input error that starts with 'path:LINE: ' (LINE >= 1), or 'path: ' for the study as
    !> a whole, says something after it, and shows only printable ASCII.
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
        call check(error, printable(found%message), "mutation " // to_text(m) &
            & // ": invisible character in: " // found%message)
        if (allocated(error)) return
        call check(error, index(found%message, path // ":") == 1, "mutation " // to_text(m) &
            & // ": message does not start with the file: " // found%message)
        if (allocated(error)) return
        rest = found%message(len(path) + 2:)
        if (len(rest) > 0) then
            if (rest(1:1) == " " .and. len_trim(rest) > 10) return
        end if
        j = index(rest, ":")
        line = 0
        stat = 1
        if (j > 1) read(rest(:j - 1), *, iostat=stat) line
        call check(error, stat == 0 .and. line >= 1 .and. len_trim(rest(j + 1:)) > 10, &
            & "mutation " // to_text(m) // ": message does not name a line and what was " &
            & // "expected: " // found%message)
    end subroutine check_refusal

    !> A clean read: a base scene; at least one parameter, each a finite range with a count of
    !> at least 1 on a grid (one point: from = to) or a non-empty range (from < to) sampled at
    !> least once; a case count that is the product of the counts (no overflow); rules on known
    !> measures with finite bounds; a map on two different parameters when it has axes.
    subroutine check_clean(study, m, error)
        type(study_type), intent(in) :: study
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        real(wp) :: cases
        integer :: k
        logical :: ok

        ok = allocated(study%scene_path) .and. allocated(study%parameters) .and. &
            & allocated(study%rules) .and. allocated(study%otherwise)
        if (ok) ok = size(study%parameters) >= 1
        if (.not. ok) then
            call check(error, .false., "mutation " // to_text(m) // ": a clean read without " &
                & // "its scene, parameters or rules")
            return
        end if
        cases = 1.0_wp
        do k = 1, size(study%parameters)
            associate (p => study%parameters(k))
                ok = ok .and. ieee_is_finite(p%lower) .and. ieee_is_finite(p%upper) .and. &
                    & p%line >= 1
                if (study%sampling == sampling_grid) then
                    ! a grid may run down (from > to); one point has from = to
                    ok = ok .and. p%count >= 1 .and. (p%count > 1 .or. p%lower == p%upper)
                    cases = cases*real(p%count, wp)
                else
                    ok = ok .and. study%sampling == sampling_random .and. p%lower < p%upper
                end if
            end associate
        end do
        if (study%sampling == sampling_random) then
            ok = ok .and. study%samples >= 1
            cases = real(study%samples, wp)
        end if
        ok = ok .and. real(case_count(study), wp) == cases
        do k = 1, size(study%rules)
            ok = ok .and. measure_index(study%rules(k)%measure) > 0 .and. &
                & ieee_is_finite(study%rules(k)%bound)
        end do
        if (study%map%x /= 0 .or. study%map%y /= 0) ok = ok .and. study%map%x >= 1 .and. &
            & study%map%y >= 1 .and. study%map%x /= study%map%y .and. &
            & max(study%map%x, study%map%y) <= size(study%parameters)
        call check(error, ok, "mutation " // to_text(m) // ": a clean read holds a value " &
            & // "that is not finite or out of its range, or " // to_text(cases) // " cases " &
            & // "counted as " // to_text(case_count(study)))
    end subroutine check_clean

    !> Remove a file.
    subroutine delete(path)
        character(len=*), intent(in) :: path
        integer :: unit, stat

        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete")
    end subroutine delete

end module test_study_fuzz
