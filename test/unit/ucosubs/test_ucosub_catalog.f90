! SPDX-License-Identifier: MIT
!> Tests of the built-in UCOSUB catalog (rollcon_ucosub_catalog over the generated
!> rollcon_gen_catalog): every listed name resolves to its routine, in any case; each routine
!> declares its variables for a PAR the catalog builds; unknown names and bad PAR requests are
!> refused with their messages; the list names every spec under ucon/specs/.
module test_ucosub_catalog
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_ucon_call, only : declare_ucon
    use rollcon_disk_par, only : disk_codes, disk_par
    use rollcon_disk_reference, only : hand_disk_ucosub => rolling_disk_ucosub
    use rollcon_gen_rolling_sphere, only : rolling_sphere_ucosub, rolling_sphere_codes
    use rollcon_gen_turntable_disk, only : turntable_disk_time_free
    use rollcon_gen_catalog, only : generated_count, generated_names, generated_codes, &
        & generated_npar, generated_ncomponents, generated_time_free, generated_routine, &
        & generated_first_part_nvars
    use rollcon_ucosub_catalog, only : find_builtin_ucosub, builtin_ucosub_names, &
        & builtin_ucosub_par, builtin_ucosub_summary, builtin_ucosubs_for_par
    use rollcon_text, only : upper_case, to_text
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_ucosub_catalog

    !> Where the test writes the listing of ucon/specs/
    character(len=*), parameter :: listing = "build/rollcon-test/ucon-specs.txt"

contains

    !> Tests of this suite.
    subroutine collect_ucosub_catalog(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))  ! silences gfortran -Wmaybe-uninitialized
        tests = [new_unittest("every-name-resolves", test_every_name_resolves), &
            & new_unittest("routines-declare", test_routines_declare), &
            & new_unittest("unknown-name", test_unknown_name), &
            & new_unittest("par-refusals", test_par_refusals), &
            & new_unittest("names-every-spec", test_names_every_spec), &
            & new_unittest("routines-a-par-suits", test_par_suits)]
    end subroutine collect_ucosub_catalog

    !> The names of builtin_ucosub_names(), split at ", ".
    function listed_names() result(names)
        character(len=32), allocatable :: names(:)
        character(len=:), allocatable :: rest
        integer :: comma

        allocate(names(0))
        rest = builtin_ucosub_names()
        do
            comma = index(rest, ", ")
            if (comma == 0) exit
            names = [character(len=32) :: names, rest(:comma - 1)]
            rest = rest(comma + 2:)
        end do
        names = [character(len=32) :: names, rest]
    end function listed_names

    !> "disk" and "rolling_disk" first, then the other generated routines in the generated
    !> catalog's order, each once; each name, in lower and upper case, gives its own routine and
    !> time-free flag.
    subroutine test_every_name_resolves(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=32), allocatable :: names(:)
        procedure(ucosub_interface), pointer :: ucosub, upper, expected
        logical :: time_free, upper_time_free, found
        integer :: i, entry, previous

        names = listed_names()
        call check(error, size(names), 1 + generated_count, "number of built-in names")
        if (allocated(error)) return
        call check(error, names(1) == "disk" .and. names(2) == "rolling_disk", "the disk " &
            & // "routines come first, got '" // trim(names(1)) // "', '" // trim(names(2)) // "'")
        if (allocated(error)) return
        previous = 0
        do i = 1, size(names)
            call find_builtin_ucosub(names(i), ucosub, time_free, found)
            call check(error, found .and. associated(ucosub), trim(names(i)) // " not found")
            if (allocated(error)) return
            call find_builtin_ucosub(upper_case(names(i)), upper, upper_time_free, found)
            call check(error, found .and. associated(upper, ucosub) &
                & .and. (upper_time_free .eqv. time_free), upper_case(names(i)) &
                & // " does not give the routine of " // trim(names(i)))
            if (allocated(error)) return
            if (i == 1) then
                expected => hand_disk_ucosub
                call check(error, associated(ucosub, expected) .and. time_free, &
                    & "disk is not the hand-checked, time-free routine")
            else
                entry = catalog_entry(names(i))
                call check(error, entry > 0 .and. (i == 2 .or. entry > previous), &
                    & trim(names(i)) // " is not in the generated catalog, or out of its order")
                if (allocated(error)) return
                if (i > 2) previous = entry
                call generated_routine(entry, expected)
                call check(error, associated(ucosub, expected) &
                    & .and. (time_free .eqv. generated_time_free(entry)), trim(names(i)) &
                    & // " gives another routine or time-free flag than its catalog entry")
            end if
            if (allocated(error)) return
        end do
        ! two entries checked against their modules, not only against the catalog
        call find_builtin_ucosub("rolling_sphere", ucosub, time_free, found)
        expected => rolling_sphere_ucosub
        call check(error, associated(ucosub, expected), "rolling_sphere is not its module's")
        if (allocated(error)) return
        call find_builtin_ucosub("turntable_disk", ucosub, time_free, found)
        call check(error, (time_free .eqv. turntable_disk_time_free) .and. .not. time_free, &
            & "turntable_disk depends on the time: it must not be time-free")
        if (allocated(error)) return
        call check(error, index(builtin_ucosub_summary("Rolling_Sphere"), "sphere") > 0 &
            & .and. index(builtin_ucosub_summary("disk"), "hand-checked") > 0, &
            & "summaries: '" // builtin_ucosub_summary("rolling_sphere") // "', '" &
            & // builtin_ucosub_summary("disk") // "'")
    end subroutine test_every_name_resolves

    !> The generated catalog's entry called name; 0 when there is none.
    pure integer function catalog_entry(name) result(entry)
        character(len=*), intent(in) :: name
        integer :: j

        entry = 0
        do j = 1, generated_count
            if (generated_names(j) == name) entry = j
        end do
    end function catalog_entry

    !> Each routine's initialisation call (IFLAG = 3, through declare_ucon) accepts the PAR
    !> builtin_ucosub_par builds, for every component, and declares its codes for that part.
    subroutine test_routines_declare(error)
        type(error_type), allocatable, intent(out) :: error
        !> Part the UCONs constrain, and a value every physical parameter takes (positive, so
        !> that radii pass; offsets and rates accept any finite value) [m or rad/s]
        integer, parameter :: part = 7
        real(wp), parameter :: parameter_value = 0.25_wp
        character(len=32), allocatable :: names(:)
        type(ucovar_registry_type) :: registry
        procedure(ucosub_interface), pointer :: ucosub
        real(wp), allocatable :: par(:)
        integer, allocatable :: codes(:), parts(:)
        integer :: i, component, ncomponents, id, entry, nparameters, declared_entry, first
        logical :: time_free, found

        names = listed_names()
        id = 0
        first = 0
        do i = 1, size(names)
            call find_builtin_ucosub(names(i), ucosub, time_free, found)
            if (i == 1) then
                codes = disk_codes
                ncomponents = 3
                nparameters = 1
            else
                entry = catalog_entry(names(i))
                codes = generated_codes(entry)
                ncomponents = generated_ncomponents(entry)
                ! PAR: part id, codes (two parts: then the second part's id and codes),
                ! parameters, then the component when there are several
                first = generated_first_part_nvars(entry)
                nparameters = generated_npar(entry) - 1 - size(codes) - merge(1, 0, first > 0)
                if (ncomponents > 1) nparameters = nparameters - 1
            end if
            parts = spread(part, 1, size(codes))
            if (first > 0) parts(first + 1:) = part + 1
            do component = 1, ncomponents
                call builtin_ucosub_par(names(i), part, spread(parameter_value, 1, nparameters), &
                    & component, par, error, part_j=part + 1)
                if (allocated(error)) return
                id = id + 1
                call declare_ucon(ucosub, id, par, registry, error)
                if (allocated(error)) return
                declared_entry = registry%find(id)
                call check(error, declared_entry > 0, trim(names(i)) // ": nothing declared")
                if (allocated(error)) return
                associate (declared => registry%entries(declared_entry))
                    call check(error, size(declared%codes) == size(codes), trim(names(i)) &
                        & // ": wrong number of variables declared")
                    if (allocated(error)) return
                    call check(error, all(declared%codes == codes) .and. all(declared%parts &
                        & == parts), trim(names(i)) // ": declared codes or parts differ")
                    if (allocated(error)) return
                end associate
            end do
        end do
        call builtin_ucosub_par("disk", part, [parameter_value], 2, par, error)
        if (allocated(error)) return
        call check(error, size(par) == size(disk_par(part, parameter_value, 2)) .and. &
            & all(par == disk_par(part, parameter_value, 2)), "disk PAR differs from disk_par")
        if (allocated(error)) return
        call builtin_ucosub_par("rolling_sphere", part, [parameter_value], 3, par, error)
        if (allocated(error)) return
        call check(error, all(par == [real(part, wp), real(rolling_sphere_codes, wp), &
            & parameter_value, 3.0_wp]), "rolling_sphere PAR: part, codes, R, component")
    end subroutine test_routines_declare

    !> A name that is not built in is not found (no routine, not time-free), and PAR for it is
    !> refused with the list of built-in names.
    subroutine test_unknown_name(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: unknown(4) = [character(len=13) :: "no_such_thing", &
            & "disk2", "", "rolling"]
        procedure(ucosub_interface), pointer :: ucosub
        real(wp), allocatable :: par(:)
        logical :: time_free, found
        integer :: i

        do i = 1, size(unknown)
            ucosub => hand_disk_ucosub
            time_free = .true.
            call find_builtin_ucosub(unknown(i), ucosub, time_free, found)
            call check(error, .not. found .and. .not. associated(ucosub) .and. .not. time_free, &
                & "'" // trim(unknown(i)) // "' must not be found")
            if (allocated(error)) return
        end do
        call check(error, builtin_ucosub_summary("no_such_thing") == "", "summary of nothing")
        if (allocated(error)) return
        call builtin_ucosub_par("no_such_thing", 1, [0.1_wp], 1, par, error)
        call check_message(error, "no built-in UCOSUB is called 'no_such_thing'; the " &
            & // "built-in routines are " // builtin_ucosub_names())
    end subroutine test_unknown_name

    !> Too many or too few parameters, and a component out of range, are refused.
    subroutine test_par_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), allocatable :: par(:)

        call builtin_ucosub_par("rolling_disk", 1, [0.1_wp, 0.2_wp], 1, par, error)
        call check_message(error, "the built-in UCOSUB 'rolling_disk' takes 1 physical " &
            & // "parameter(s) (PAR(10) on), got 2")
        if (allocated(error)) return
        call builtin_ucosub_par("knife_edge", 1, [0.1_wp], 1, par, error)
        call check_message(error, "the built-in UCOSUB 'knife_edge' takes 0 physical " &
            & // "parameter(s) (PAR(5) on), got 1")
        if (allocated(error)) return
        call builtin_ucosub_par("jp_atpoint", 1, spread(0.1_wp, 1, 6), 1, par, error)
        call check_message(error, "the built-in UCOSUB 'jp_atpoint' constrains two parts: give " &
            & // "the second part's id (part_j)")
        if (allocated(error)) return
        ! a PAR of two parts suits the routine of two parts
        call builtin_ucosub_par("jp_atpoint", 2, spread(0.1_wp, 1, 6), 3, par, error, part_j=5)
        if (allocated(error)) return
        call check(error, builtin_ucosubs_for_par(par) == "jp_atpoint" .and. par(8) == 5.0_wp, &
            & "jp_atpoint's PAR suits '" // builtin_ucosubs_for_par(par) // "'")
        if (allocated(error)) return
        call builtin_ucosub_par("disk", 1, [0.1_wp], 4, par, error)
        call check_message(error, "the built-in UCOSUB 'disk' has 3 component(s); component " &
            & // "must be 1 to 3, got 4")
        if (allocated(error)) return
        call builtin_ucosub_par("disk_height", 1, [0.1_wp], 2, par, error)
        call check_message(error, "the built-in UCOSUB 'disk_height' has 1 component(s); " &
            & // "component must be 1 to 1, got 2")
    end subroutine test_par_refusals

    !> Turn "the call failed with this message" into a test result.
    subroutine check_message(error, expected)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: expected
        type(error_type), allocatable :: outcome

        if (.not. allocated(error)) then
            call check(outcome, .false., "not refused; expected: " // expected)
        else
            call check(outcome, error%message == expected, "message '" // error%message &
                & // "', expected '" // expected // "'")
        end if
        call move_alloc(outcome, error)
    end subroutine check_message

    !> The generated names are exactly the spec files of ucon/specs/ (not starting with "_").
    subroutine test_names_every_spec(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=256) :: line
        character(len=32), allocatable :: files(:)
        integer :: unit, stat, command_stat, i, j
        logical :: listed

        call execute_command_line("mkdir -p build/rollcon-test && cd ucon/specs && ls *.py > " &
            & // "../../" // listing // " 2> /dev/null", exitstat=stat, cmdstat=command_stat)
        call check(error, stat == 0 .and. command_stat == 0, "cannot list ucon/specs/*.py")
        if (allocated(error)) return
        allocate(files(0))
        open(newunit=unit, file=listing, status="old", action="read", iostat=stat)
        call check(error, stat == 0, "cannot read " // listing)
        if (allocated(error)) return
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (line(1:1) == "_") cycle
            files = [character(len=32) :: files, line(:len_trim(line) - 3)]
        end do
        close(unit)
        call check(error, size(files), generated_count, "spec files vs generated routines")
        if (allocated(error)) return
        do i = 1, size(files)
            listed = .false.
            do j = 1, generated_count
                listed = listed .or. files(i) == generated_names(j)
            end do
            call check(error, listed, "ucon/specs/" // trim(files(i)) // ".py is not in the " &
                & // "catalog: run python3 -m ucon write")
            if (allocated(error)) return
        end do
    end subroutine test_names_every_spec


    !> builtin_ucosubs_for_par names the routines whose PAR layout a PAR list fits: the disk's
    !> PAR both disk routines, the data/ datasets' PAR their own routine; a PAR a routine
    !> cannot read (a part id 0, a component out of range, a code out of place, one constant
    !> short) none.
    subroutine test_par_suits(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: ball(15) = [2.0_wp, 11.0_wp, 12.0_wp, 21.0_wp, 22.0_wp, &
            & 23.0_wp, 14.0_wp, 15.0_wp, 25.0_wp, 26.0_wp, 0.02_wp, 3.5_wp, 0.0_wp, 0.0_wp, &
            & 1.0_wp]
        real(wp), parameter :: blade(6) = [2.0_wp, 21.0_wp, 22.0_wp, 14.0_wp, 24.0_wp, 0.1_wp]
        real(wp), parameter :: hold(6) = [2.0_wp, 13.0_wp, 15.0_wp, 16.0_wp, 0.05_wp, 3.0_wp]
        real(wp) :: wrong(11)

        call expect_suits(error, disk_par(2, 0.1_wp, 3), "disk, rolling_disk")
        if (.not. allocated(error)) call expect_suits(error, ball, "turntable_ball")
        if (.not. allocated(error)) call expect_suits(error, blade, "chaplygin_sled")
        if (.not. allocated(error)) call expect_suits(error, hold, "planar_hold")
        if (.not. allocated(error)) call expect_suits(error, [0.0_wp, hold(2:)], "")
        if (.not. allocated(error)) call expect_suits(error, [hold(:5), 4.0_wp], "")
        if (.not. allocated(error)) call expect_suits(error, blade(:5), "")
        wrong = disk_par(2, 0.1_wp, 1)
        wrong(3) = 21.0_wp
        if (.not. allocated(error)) call expect_suits(error, wrong, "")
    end subroutine test_par_suits

    subroutine expect_suits(error, par, expected)
        type(error_type), allocatable, intent(out) :: error
        real(wp), intent(in) :: par(:)
        character(len=*), intent(in) :: expected

        call check(error, builtin_ucosubs_for_par(par) == expected, "a PAR of " &
            & // to_text(size(par)) // " constants suits '" // builtin_ucosubs_for_par(par) &
            & // "', expected '" // expected // "'")
    end subroutine expect_suits

end module test_ucosub_catalog
