! SPDX-License-Identifier: MIT
!> Fuzz test of the dataset reader (read_adm): seeded mutations of the shipped datasets and of
!> two written ones must each give a clean refusal (an input error naming the file and a line,
!> in visible characters) or a clean read whose values are finite and within the documented
!> ranges (docs/datasets.md); never a crash or a hang. Every so often a clean read is also
!> built into a problem, which must be refused cleanly or have a finite start. The inputs the
!> fuzzer found bugs with are kept as deterministic tests.
module test_adm_fuzz
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, stat_input
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : line_type
    use rollcon_adm_lexer, only : read_dataset_lines
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm, read_adm_lines
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_disk_reference, only : rolling_disk_ucosub
    use rollcon_problem, only : problem_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use adm_datasets, only : base, check_refusals
    use fuzz_mutations, only : seed_fuzz, mutate_lines, write_lines, printable
    use expression_checks, only : check_expression_program
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: collect_adm_fuzz

    !> Mutated datasets read (in memory, but every disk_every-th from a file)
    integer, parameter :: mutation_count = 10000
    !> Every this many, the mutated dataset is written under build/ and read with read_adm
    integer, parameter :: disk_every = 500
    !> Every this many clean reads, the problem is built too (no integration)
    integer, parameter :: build_every = 20
    !> Least share of each outcome: a reader that refuses or accepts everything fails
    real(wp), parameter :: least_share = 0.05_wp
    !> Seed of the mutations: the same datasets on every run
    integer, parameter :: seed = 20260522
    !> The shipped datasets (those with a CONTACT among them: one contact, several, on a
    !> turntable)
    character(len=*), parameter :: shipped(*) = [character(len=25) :: "ball_on_turntable", &
        & "ball_tumbling", "chaplygin_sled", "coin", "disk_and_sphere", "disk_height", &
        & "turntable_disk", "sliding_coin", "sphere_bounce", "sphere_thrown", &
        & "two_spheres_thrown", "ball_and_coin", "ball_dropped_on_turntable"]
    !> A dataset with every statement and keyword of the subset, in millimetres
    character(len=76), parameter :: every_statement(*) = [character(len=76) :: &
        & "every statement: each keyword of the subset once", &
        & "! lengths in millimetres, so that every value is converted", &
        & "UNITS/SYSTEM=MMKS, TIME=SECOND", &
        & "PART/1, GROUND", &
        & "MARKER/10, PART=1, QP=0, 0, 0", &
        & "MARKER/11, PART=1, QP=100, 0, 0, REULER=0D, 0D, 0D", &
        & "PART/2, MASS=1, CM=20, IP=2000, 2000, 3000, 0, 0, 0", &
        & ", QG=0, 0, 100, REULER=0, 0, 0, VX=10, VY=0, VZ=0", &
        & ", WX=0, WY=0.5, WZ=-0.1, EXACT=X:Y:PSI", &
        & "MARKER/20, PART=2, REULER=0D, 90D, 0D", &
        & "MARKER/21, PART=2, QP=0, 0, 50", &
        & "UCON/1, FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, 26, 100, 1)", &
        & "ACCGRAV/IGRAV=0, JGRAV=0, KGRAV=-9810", &
        & "SFORCE/1, I=21, J=10, TRANSLATION, FUNCTION=STEP(TIME, 0, 0, 1, 5)*DX(21)", &
        & "SFORCE/2, I=20, J=11, ROTATION, ACTIONONLY", &
        & ", FUNCTION=-0.1*WZ(20) + HAVSIN(TIME, 0, 0, 1D, 1)", &
        & "VFORCE/3, I=21, JFLOAT=10, RM=11, FX=0, FY=SIN(TIME)*1e-3", &
        & ", FZ=MAX(0, 1 - DZ(21))", &
        & "GFORCE/4, I=20, JFLOAT=10, RM=11, FX=0, FY=0, FZ=PI*DTOR", &
        & ", TX=ATAN2(VY(20), VX(20)), TY=SQRT(ABS(THETA(20)))", &
        & ", TZ=IF(TIME - 0.5: 0, LOG(2), EXP(-TIME))\", &
        & "SIMULATE/DYNAMIC, END=1, DTOUT=0.01", &
        & "INTEGRATOR/FORMULATION=CVODE, METHOD=ADAMS, DRIFT=BAUMGARTE, BAUMGARTE=20", &
        & ", RTOL=1e-7, ATOL=1e-9, MAXSTEPS=10000, JACOBIAN=DQ", &
        & "OUTPUT/", &
        & "END"]
    !> A dataset in units larger than SI (kilometre, megagram, millisecond, kilonewton): a huge
    !> value that is finite as written must not become infinite in SI
    character(len=*), parameter :: large_units(*) = [character(len=76) :: &
        & "large units: kilometres, megagrams, milliseconds, kilonewtons", &
        & "UNITS/FORCE=KNEWTON, MASS=MEGAGRAM, LENGTH=KILOMETER, TIME=MILLISECOND", &
        & "PART/1, GROUND", &
        & "PART/2, MASS=1e-3, CM=3, IP=1e-9, 1e-9, 2e-9, QG=0, 0, 1e-4", &
        & ", VX=1e-7, VY=0, WX=0, WZ=-1e-3", &
        & "MARKER/3, PART=2, QP=0, 0, 0, REULER=0D, 90D, 0D", &
        & "MARKER/4, PART=1, QP=1, 2, 3", &
        & "UCON/1, FUNCTION=USER(2, 21, 22, 23, 14, 15, 24, 25, 26, 0.1, 1)", &
        & "ACCGRAV/KGRAV=-9.81e-9", &
        & "SFORCE/5, I=3, J=4, FUNCTION=1e-3*SIN(TIME)", &
        & "SIMULATE/DYNAMIC, END=1000, STEPS=10", &
        & "END"]
    !> Words a mutation may insert: statement names, keywords, choices, expression names
    character(len=*), parameter :: words(*) = [character(len=12) :: "PART", "MARKER", "UCON", &
        & "SFORCE", "VFORCE", "GFORCE", "ACCGRAV", "SIMULATE", "INTEGRATOR", "UNITS", "OUTPUT", &
        & "END", "JOINT", "GROUND", "MASS=", "CM=", "IP=", "QG=", "REULER=", "VX=", "WZ=", &
        & "EXACT=", "X:Y:Z", "QP=", "PART=", "FUNCTION=", "USER(", "ROUTINE=", "disk", "I=", &
        & "J=", "JFLOAT=", "RM=", "FX=", "TZ=", "ROTATION", "ACTIONONLY", "TIME", "PI", "DTOR", &
        & "IF(", "STEP(", "HAVSIN(", "SIN(", "LOG(", "DX(3)", "THETA(", "SYSTEM=", "CGS", &
        & "LENGTH=", "INCH", "KILOMETER", "TIME=HOUR", "ERROR=", "FORMULATION=", "CVODE", &
        & "DYNAMIC", "END=", "STEPS=", "DTOUT=", "MAXSTEPS=", "CONTACT", "GRAPHICS", &
        & "IGEOM=", "JGEOM=", "ELLIPSOID", "CYLINDER", "PLANE", "MU_STATIC=", "MU_DYNAMIC=", &
        & "RESTITUTION=", "ROLLING_RES=", "AIR_VISC=", "REVOLUTE", "MOTION", "/", "\", "!"]

contains

    !> Tests of this suite.
    subroutine collect_adm_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("mutated-datasets", test_mutated_datasets), &
            & new_unittest("found-inputs-refused", test_found_inputs), &
            & new_unittest("nesting-over-continuation-lines", test_deep_continuation)]
    end subroutine collect_adm_fuzz

    subroutine test_mutated_datasets(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: bases(:, :), lines(:)
        integer, allocatable :: lengths(:)
        type(adm_model_type) :: model
        type(error_type), allocatable :: found
        character(len=:), allocatable :: path
        integer :: m, f, refused, accepted

        call base_datasets(bases, lengths, error)
        if (allocated(error)) return
        refused = 0
        accepted = 0
        call seed_fuzz(seed)
        do m = 1, mutation_count
            f = 1 + mod(m - 1, size(lengths))
            lines = bases(:lengths(f), f)
            call mutate_lines(lines, words)
            if (mod(m, disk_every) == 0) then
                path = "build/test_adm_fuzz.adm"
                call write_lines(path, lines)
                call read_adm(path, model, found)
            else
                path = "fuzz/" // base_name(f) // ".adm"
                call read_adm_lines(path, lines, model, found)
            end if
            if (allocated(found)) then
                refused = refused + 1
                call check_refusal(found, path, m, error)
            else
                accepted = accepted + 1
                call check_clean(model, m, error)
                if (.not. allocated(error) .and. mod(accepted, build_every) == 0) &
                    & call check_built(model, path, m, error)
            end if
            if (allocated(error)) return
        end do
        call check(error, min(refused, accepted) >= least_share*mutation_count, &
            & "outcomes too one-sided: " // to_text(refused) // " refused, " &
            & // to_text(accepted) // " accepted")
    end subroutine test_mutated_datasets

    !> The mutations that crashed the reader or were read with a value that is not finite,
    !> each refused now with its message (a line of adm_datasets' base replaced).
    subroutine test_found_inputs(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: nines = repeat("9", 314) // ".5"
        character(len=800) :: replaced(3), expected(3)

        ! FUNCTION without a value: a substring of the empty text out of bounds (a crash)
        replaced(1) = "UCON/1, FUNCTION"
        expected(1) = ":8: UCON/1 FUNCTION: expected USER(r1, ..., r30) (a UCON is served by " &
            & // "the model's UCOSUB), got ''"
        ! finite as written, infinite in SI (-1e314 m/s): accepted as -Infinity
        replaced(2) = "UNITS/LENGTH=KILOMETER, TIME=MILLISECOND|PART/9, MASS=1, CM=3, " &
            & // "IP=2, 2, 3, VX=-1e308"
        expected(2) = ":3: PART/9 VX: '-1e308' is not a finite number once converted to SI " &
            & // "(the dataset's unit is 1000000 times SI's)"
        ! a constant beyond the largest double: compiled as Infinity
        replaced(3) = "SFORCE/5, I=3, J=4, TRANSLATION, FUNCTION=TIME - " // nines
        expected(3) = ":10: SFORCE/5 FUNCTION: '" // nines // "' is not a finite number at " &
            & // "column 8 of 'TIME - " // nines // "'"
        call check_refusals(error, [8, 2, 10], replaced, expected)
    end subroutine test_found_inputs

    !> An expression continued over 301 lines of 4000 parentheses each (and as many closing
    !> them) drove the expression compiler's recursion through the stack (a segmentation
    !> fault): refused at its 201st level of nesting.
    subroutine test_deep_continuation(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(adm_model_type) :: model
        type(error_type), allocatable :: found
        integer :: i

        lines = as_lines(base)
        lines(10)%text = "SFORCE/5, I=3, J=4, TRANSLATION, FUNCTION=" // repeat("(", 4000)
        ! balanced, so that the statement splits: the expression is the compiler's to refuse
        lines = [lines(:10), [(line_type(", " // repeat("(", 4000)), i = 1, 300)], &
            & line_type(", 1"), [(line_type(", " // repeat(")", 4000)), i = 1, 301)], &
            & lines(11:)]
        call read_adm_lines("deep.adm", lines, model, found)
        call check(error, allocated(found), "an expression nested 1.2 million deep was read")
        if (allocated(error)) return
        call check(error, index(found%message, "deep.adm:10: SFORCE/5 FUNCTION: nested too " &
            & // "deeply (more than 200 levels of parentheses, signs and powers) at column " &
            & // "201 of '((((") == 1, found%message(:min(300, len(found%message))))
    end subroutine test_deep_continuation

    !> The lines of every base dataset (column f: dataset f, its first lengths(f) lines), each
    !> of which must read cleanly as it is.
    subroutine base_datasets(bases, lengths, error)
        type(line_type), allocatable, intent(out) :: bases(:, :)
        integer, allocatable, intent(out) :: lengths(:)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(adm_model_type) :: model
        integer :: f

        allocate(bases(200, size(shipped) + 3), lengths(size(shipped) + 3))
        do f = 1, size(lengths)
            if (f <= size(shipped)) then
                call read_dataset_lines("data/" // trim(shipped(f)) // ".adm", lines, error)
                if (allocated(error)) return
            else if (f == size(shipped) + 1) then
                lines = as_lines(every_statement)
            else if (f == size(shipped) + 2) then
                lines = as_lines(large_units)
            else
                lines = as_lines(base)
            end if
            lengths(f) = size(lines)
            bases(:size(lines), f) = lines
            call read_adm_lines("fuzz/" // base_name(f) // ".adm", lines, model, error)
            if (allocated(error)) return
        end do
    end subroutine base_datasets

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

    !> Name of base dataset f.
    pure function base_name(f) result(name)
        integer, intent(in) :: f
        character(len=:), allocatable :: name

        if (f <= size(shipped)) then
            name = trim(shipped(f))
        else if (f == size(shipped) + 1) then
            name = "every_statement"
        else if (f == size(shipped) + 2) then
            name = "large_units"
        else
            name = "refusal_base"
        end if
    end function base_name

    !> An input error that starts with 'path:LINE: ' (LINE >= 1), or 'path: ' for the
    !> dataset as a whole, says something after it, shows only printable ASCII, and never says
    !> that a value follows NaN or Inf (they are a list's entries that are not finite). A refusal
    !> of several statements outside the subset (rollcon_adm_reader) gives each a line of its
    !> own after the first: '  path:LINE: ...', printable too.
    subroutine check_refusal(found, path, m, error)
        type(error_type), intent(in) :: found
        character(len=*), intent(in) :: path
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: rest, first, next
        integer :: j, line, stat

        call check(error, found%stat == stat_input .and. allocated(found%message), &
            & "mutation " // to_text(m) // ": not an input error")
        if (allocated(error)) return
        first = found%message
        j = index(first, new_line("a"))
        if (j > 0) then
            rest = first(j + 1:)
            first = first(:j - 1)
            do while (len(rest) > 0)
                j = index(rest, new_line("a"))
                if (j == 0) j = len(rest) + 1
                next = rest(:j - 1)
                rest = rest(min(j + 1, len(rest) + 1):)
                call check(error, printable(next) .and. index(next, "  " // path // ":") == 1, &
                    & "mutation " // to_text(m) // ": a line of a refusal of several " &
                    & // "statements is not '  " // path // ":LINE: ...' or shows an " &
                    & // "invisible character: " // found%message)
                if (allocated(error)) return
            end do
        end if
        call check(error, printable(first), "mutation " // to_text(m) &
            & // ": invisible character in: " // found%message)
        if (allocated(error)) return
        ! NaN or Inf among a list's numbers is that list's entry that is not finite, never a
        ! word a value 'follows' (rollcon_adm_lexer's is_nonfinite_text)
        call check(error, index(first, "follows NAN,") == 0 .and. index(first, &
            & "follows INF,") == 0 .and. index(first, "follows -INF") == 0 .and. &
            & index(first, "follows INFINITY,") == 0, "mutation " // to_text(m) &
            & // ": a value said to follow NaN or Inf: " // found%message)
        if (allocated(error)) return
        call check(error, index(first, path // ":") == 1, "mutation " // to_text(m) &
            & // ": message does not start with the file: " // found%message)
        if (allocated(error)) return
        rest = first(len(path) + 2:)
        if (len(rest) > 0) then
            if (rest(1:1) == " " .and. len_trim(rest) > 10) return
        end if
        j = index(rest, ": ")
        line = 0
        stat = 1
        if (j > 1) read(rest(:j - 1), *, iostat=stat) line
        call check(error, stat == 0 .and. line >= 1 .and. len_trim(rest(j + 1:)) > 10, &
            & "mutation " // to_text(m) // ": message does not name a line and what was " &
            & // "expected: " // found%message)
    end subroutine check_refusal

    !> A clean read: one ground part; every other part with a mass and principal moments > 0
    !> that meet the triangle inequality; every value finite; every marker on a part; UCONs
    !> with 1 to 30 finite constants; every CONTACT's coefficients within their documented
    !> ranges (MU_STATIC in (0, 100], MU_DYNAMIC in (0, MU_STATIC], the restitution in [0, 1],
    !> the dissipation's >= 0 and finite) and its GRAPHICS' sizes finite; the run within the
    !> ranges of &run; every expression a program of finite constants that leaves one value.
    subroutine check_clean(model, m, error)
        type(adm_model_type), intent(in) :: model
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        !> Slack of the triangle inequality of the moments (the reader's own)
        real(wp), parameter :: triangle_slack = 1.0e-12_wp
        logical :: ok
        integer :: i, k

        ok = count(model%parts%ground) == 1 .and. all(ieee_is_finite(model%gravity))
        do i = 1, size(model%parts)
            associate (p => model%parts(i))
                ok = ok .and. all(ieee_is_finite([p%mass, p%ip, p%qg, p%reuler, p%velocity, &
                    & p%angular_velocity]))
                if (.not. p%ground) ok = ok .and. p%mass > 0.0_wp .and. all(p%ip > 0.0_wp) &
                    & .and. all(p%ip <= (sum(p%ip) - p%ip)*(1.0_wp + triangle_slack)) &
                    & .and. any(model%markers%id == p%cm)
            end associate
        end do
        do i = 1, size(model%markers)
            associate (k_marker => model%markers(i))
                ok = ok .and. all(ieee_is_finite([k_marker%qp, k_marker%reuler])) &
                    & .and. any(model%parts%id == k_marker%part)
            end associate
        end do
        do i = 1, size(model%ucons)
            ok = ok .and. size(model%ucons(i)%par) >= 1 .and. size(model%ucons(i)%par) <= 30 &
                & .and. all(ieee_is_finite(model%ucons(i)%par))
        end do
        if (allocated(model%contacts)) then
            do i = 1, size(model%contacts)
                associate (c => model%contacts(i))
                    ok = ok .and. c%mu_static > 0.0_wp .and. c%mu_static <= 100.0_wp &
                        & .and. c%mu_dynamic > 0.0_wp .and. c%mu_dynamic <= c%mu_static &
                        & .and. c%restitution >= 0.0_wp .and. c%restitution <= 1.0_wp &
                        & .and. c%rolling_resistance >= 0.0_wp .and. c%air_viscosity >= 0.0_wp &
                        & .and. ieee_is_finite(c%rolling_resistance) &
                        & .and. ieee_is_finite(c%air_viscosity)
                end associate
            end do
        end if
        if (allocated(model%graphics)) then
            do i = 1, size(model%graphics)
                ok = ok .and. all(ieee_is_finite([model%graphics(i)%radius, &
                    & model%graphics(i)%length, model%graphics(i)%scales]))
            end do
        end if
        associate (r => model%run%settings)
            ok = ok .and. r%end_time >= 1.0e-9_wp .and. r%end_time <= 1.0e9_wp &
                & .and. r%output_step >= 1.0e-9_wp .and. r%output_step <= r%end_time &
                & .and. r%rtol >= 1.0e-15_wp .and. r%rtol < 1.0_wp .and. r%atol >= 1.0e-20_wp &
                & .and. r%atol <= 1.0e3_wp .and. r%max_steps >= 1 .and. r%baumgarte_rate > 0.0_wp &
                & .and. r%baumgarte_rate <= 1.0e6_wp
        end associate
        call check(error, ok, "mutation " // to_text(m) // ": a clean read holds a value that " &
            & // "is not finite or out of its range")
        if (allocated(error)) return
        do i = 1, size(model%forces)
            do k = 1, 6
                if (.not. model%forces(i)%given(k)) cycle
                call check_expression_program(model%forces(i)%functions(k), "mutation " &
                    & // to_text(m) // ": force " // to_text(i) // " expression " // to_text(k), &
                    & error)
                if (allocated(error)) return
            end do
        end do
    end subroutine check_clean

    !> The problem of a clean read: refused with a message naming the file, or built with a
    !> finite start.
    subroutine check_built(model, path, m, error)
        type(adm_model_type), intent(in) :: model
        character(len=*), intent(in) :: path
        integer, intent(in) :: m
        type(error_type), allocatable, intent(out) :: error
        type(problem_type), target :: problem
        type(error_type), allocatable :: found
        procedure(ucosub_interface), pointer :: disk
        real(wp), allocatable :: q0(:), u0(:)

        disk => rolling_disk_ucosub
        call build_adm_problem(model, disk, problem, q0, u0, found)
        if (allocated(found)) then
            call check(error, printable(found%message) .and. (index(found%message, path // ":") &
                & == 1 .or. index(found%message, "UCON/") == 1), "mutation " // to_text(m) &
                & // ": a build refused without the file or the UCON: " // found%message)
            return
        end if
        call check(error, all(ieee_is_finite([q0, u0])), "mutation " // to_text(m) &
            & // ": a built problem starts from a state that is not finite")
    end subroutine check_built

end module test_adm_fuzz
