! SPDX-License-Identifier: MIT
!> Runs a generated fixed-form ucosub.f outside fpm and compares it with the free-form module
!> (the generated suite's test fixed-form-matches-module).
!>
!> The file is compiled alone with `gfortran -std=legacy -c` (it must need nothing but UCOVAR
!> and ERRMES), linked with the FORTRAN 77 driver and stub utilities of test/fixed_form/, and
!> run on cases this module writes; the outputs it prints at full precision (ES25.17, 18
!> significant digits, which read back exactly) are compared with the module's.
module generated_fixed_form
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_ucon_call, only : declare_ucon
    use rollcon_ucovar_registry, only : ucovar_registry_type
    use rollcon_adams_runtime, only : take_ucon_error
    use rollcon_testing, only : check, skip_test
    use disk_states, only : seed_random
    use generated_specs_list, only : generated_spec_type, generated_specs, random_state, &
        & random_parameters, spec_par
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    implicit none
    private

    public :: test_fixed_form

    !> Where the tests leave logs and build products (under fpm's build directory)
    character(len=*), parameter :: work_dir = "build/rollcon-test"

    !> Every output starts as this value in driver.f (SENTIN) and here
    real(wp), parameter :: sentinel = 12345.0_wp
    !> Part id used in the valid cases
    integer, parameter :: part = 2

    !> One call of the routine
    type :: case_type
        integer :: iflag = 0
        integer :: idrsel(3) = 0
        real(wp) :: time = 0.0_wp
        real(wp), allocatable :: par(:)
        real(wp) :: q(30) = 0.0_wp
    end type case_type

    !> What the driver printed for one case
    type :: printed_type
        integer :: errors = 0, error_id = 0, declared = 0, declared_id = 0, outside = 0
        character(len=240) :: message = " "
        integer :: parts(30) = 0, codes(30) = 0
        real(wp) :: scalar = 0.0_wp, array(30) = 0.0_wp, xmatrx(30, 30) = 0.0_wp
    end type printed_type

contains

    !> Each ucon/adams/<spec>/ucosub.f, compiled alone with gfortran -std=legacy and run by
    !> test/fixed_form/driver.f, gives what the free-form module gives (see run_fixed_form).
    subroutine test_fixed_form(error)
        type(error_type), allocatable, intent(out) :: error
        type(generated_spec_type), allocatable :: specs(:)
        integer :: stat, command_stat, s

        call execute_command_line("gfortran --version > /dev/null 2>&1", exitstat=stat, &
            & cmdstat=command_stat)
        if (command_stat /= 0 .or. stat /= 0) then
            call skip_test(error, "gfortran not found: the fixed-form ucosub.f files were not " &
                & // "compiled")
            return
        end if
        allocate(specs(0))  ! silences gfortran -Wmaybe-uninitialized
        call generated_specs(specs)
        call seed_random(8008)
        do s = 1, size(specs)
            call run_fixed_form(specs(s), work_dir // "/fixed-form/" // specs(s)%name, error)
            if (allocated(error)) return
        end do
    end subroutine test_fixed_form

    !> Compile, run and compare one spec's ucosub.f in directory dir (created if needed).
    subroutine run_fixed_form(spec, dir, error)
        !> The spec, with its module routine
        type(generated_spec_type), intent(in) :: spec
        !> Scratch directory for the object, driver, cases and results
        character(len=*), intent(in) :: dir
        type(error_type), allocatable, intent(out) :: error
        type(case_type), allocatable :: cases(:)
        character(len=:), allocatable :: source
        integer :: stat, command_stat

        source = "ucon/adams/" // spec%name // "/ucosub.f"
        call execute_command_line("mkdir -p " // dir, exitstat=stat, cmdstat=command_stat)
        call execute_command_line("gfortran -std=legacy -c " // source // " -o " // dir &
            & // "/ucosub.o > " // dir // "/build.log 2>&1 && gfortran -std=legacy " // dir &
            & // "/ucosub.o test/fixed_form/driver.f test/fixed_form/stubs.f -o " // dir &
            & // "/driver >> " // dir // "/build.log 2>&1", exitstat=stat, cmdstat=command_stat)
        call check(error, command_stat == 0 .and. stat == 0, "compiling " // source &
            & // " with gfortran -std=legacy (and the driver) failed; see " // dir // "/build.log")
        if (allocated(error)) return
        call make_cases(spec, cases)
        call write_cases(cases, size(spec%codes), dir // "/cases.txt", error)
        if (allocated(error)) return
        call execute_command_line(dir // "/driver < " // dir // "/cases.txt > " // dir &
            & // "/results.txt 2> " // dir // "/run.log", exitstat=stat, cmdstat=command_stat)
        call check(error, command_stat == 0 .and. stat == 0, "running the driver of " &
            & // spec%name // " failed; see " // dir // "/run.log")
        if (allocated(error)) return
        call compare_results(spec, cases, dir // "/results.txt", error)
    end subroutine run_fixed_form

    !> The cases: an initialisation call, 60 random states in several IDRSEL selections
    !> (all 30 in turn, plus (1,1,1) and (4,2,0)), and each kind of bad call.
    subroutine make_cases(spec, cases)
        type(generated_spec_type), intent(in) :: spec
        type(case_type), allocatable, intent(out) :: cases(:)
        real(wp), allocatable :: values(:)
        type(case_type) :: one, valid
        integer :: k, c, n, component

        n = size(spec%codes)
        call random_parameters(spec, values)
        allocate(cases(0))
        one%iflag = 3
        one%par = spec_par(spec, part, values, 1)
        cases = [cases, one]
        do k = 1, 60
            component = mod(k - 1, spec%ncomponents) + 1
            one = case_type()
            one%par = spec_par(spec, part, values, component)
            call random_state(k, spec%codes, one%q(:n))
            call random_number(one%time)
            one%time = 10.0_wp*one%time
            c = mod(k - 1, 30)
            one%idrsel = [mod(c, 5), mod(c/5, 3), c/15]
            cases = [cases, one]
            one%idrsel = [1, 1, 1]
            cases = [cases, one]
            one%idrsel = [4, 2, 0]
            cases = [cases, one]
        end do
        valid = cases(size(cases))
        valid%idrsel = [1, 1, 1]
        one = valid
        one%par = one%par(:size(one%par) - 1)
        cases = [cases, one]
        one%iflag = 3
        cases = [cases, one]
        one = valid
        one%par(1) = 0.0_wp
        cases = [cases, one]
        one = valid
        one%par(2) = one%par(2) + 1.0_wp
        cases = [cases, one]
        if (size(values) > 0) then
            one = valid
            ! the first parameter: after the part ids and codes
            one%par(size(one%par) - size(values) - merge(1, 0, spec%ncomponents > 1) + 1) = &
                & ieee_value(1.0_wp, ieee_quiet_nan)
            cases = [cases, one]
        end if
        if (spec%first_part_nvars > 0) then
            ! a second part id equal to the first's, then one that is not whole
            one = valid
            one%par(spec%first_part_nvars + 2) = one%par(1)
            cases = [cases, one]
            one%par(spec%first_part_nvars + 2) = 2.5_wp
            cases = [cases, one]
        end if
        if (spec%ncomponents > 1) then
            one = valid
            one%par(size(one%par)) = 0.0_wp
            cases = [cases, one]
        end if
        one = valid
        one%iflag = 1
        cases = [cases, one]
        one%iflag = 0
        one%idrsel = [5, 0, 0]
        cases = [cases, one]
        one%idrsel = [0, 0, 2]
        cases = [cases, one]
    end subroutine make_cases

    !> Write the cases in the list-directed layout driver.f reads; the case number is the ID.
    subroutine write_cases(cases, n, path, error)
        type(case_type), intent(in) :: cases(:)
        integer, intent(in) :: n
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, stat, k

        open(newunit=unit, file=path, status="replace", action="write", iostat=stat)
        call check(error, stat == 0, "cannot write " // path)
        if (allocated(error)) return
        write(unit, '(i0)') size(cases)
        do k = 1, size(cases)
            write(unit, '(4(i0, 1x))') k, cases(k)%iflag, size(cases(k)%par), n
            write(unit, '(3(i0, 1x))') cases(k)%idrsel
            write(unit, '(es25.17)') cases(k)%time
            write(unit, '(*(es25.17, :, 1x))') cases(k)%par
            write(unit, '(*(es25.17, :, 1x))') cases(k)%q(:n)
        end do
        close(unit)
    end subroutine write_cases

    !> Read one case's records as driver.f prints them.
    subroutine read_printed(unit, n, printed, stat)
        integer, intent(in) :: unit, n
        type(printed_type), intent(out) :: printed
        integer, intent(out) :: stat
        real(wp) :: matrix(n*n)

        read(unit, *, iostat=stat) printed%errors, printed%error_id, printed%declared, &
            & printed%declared_id, printed%outside
        if (stat /= 0) return
        read(unit, '(a)', iostat=stat) printed%message
        if (stat /= 0) return
        read(unit, *, iostat=stat) printed%parts(:max(printed%declared, 0))
        if (stat /= 0) return
        read(unit, *, iostat=stat) printed%codes(:max(printed%declared, 0))
        if (stat /= 0) return
        read(unit, *, iostat=stat) printed%scalar
        if (stat /= 0) return
        read(unit, *, iostat=stat) printed%array(:n)
        if (stat /= 0) return
        read(unit, *, iostat=stat) matrix
        printed%xmatrx(:n, :n) = reshape(matrix, [n, n])
    end subroutine read_printed

    !> True when the fixed form's value equals the module's: both untouched, or within 2 ulp.
    !> Both files are printed from the same common-subexpression program, operation for
    !> operation, and neither is compiled with value-changing optimisations, so they agree
    !> bit for bit (as measured); 2 ulp only allows a compiler to contract a multiply-add in
    !> one build and not in the other.
    elemental function same_value(fixed, module) result(same)
        real(wp), intent(in) :: fixed, module
        logical :: same

        if ((fixed == sentinel) .or. (module == sentinel)) then
            same = fixed == module
        else
            same = abs(fixed - module) <= 2.0_wp*spacing(max(abs(fixed), abs(module)))
        end if
    end function same_value

    !> Call the module on every case and compare with what the driver printed.
    subroutine compare_results(spec, cases, path, error)
        type(generated_spec_type), intent(in) :: spec
        type(case_type), intent(in) :: cases(:)
        character(len=*), intent(in) :: path
        type(error_type), allocatable, intent(out) :: error
        type(printed_type) :: printed
        type(error_type), allocatable :: reported
        type(ucovar_registry_type) :: registry
        real(wp) :: scalar, array(30), xmatrx(30, 30)
        character(len=:), allocatable :: where, expected
        integer :: unit, stat, k, n, cut

        n = size(spec%codes)
        open(newunit=unit, file=path, status="old", action="read", iostat=stat)
        call check(error, stat == 0, "cannot read " // path)
        if (allocated(error)) return
        do k = 1, size(cases)
            where = spec%name // ", case " // to_text(k) // " of " // path
            call read_printed(unit, n, printed, stat)
            call check(error, stat == 0, where // ": cannot read the driver's output")
            if (allocated(error)) exit
            scalar = sentinel
            array = sentinel
            xmatrx = sentinel
            if (cases(k)%iflag == 3) then
                registry = ucovar_registry_type()
                call declare_ucon(spec%ucosub, k, cases(k)%par, registry, reported)
            else
                call spec%ucosub(k, cases(k)%time, cases(k)%q, cases(k)%par, size(cases(k)%par), &
                    & cases(k)%idrsel, cases(k)%iflag, scalar, array, xmatrx)
                call take_ucon_error(reported)
            end if
            call check(error, (printed%errors > 0) .eqv. allocated(reported), where &
                & // ": ERRMES called " // to_text(printed%errors) // " times by ucosub.f, " &
                & // "module error: " // merge("yes", "no ", allocated(reported)))
            if (allocated(error)) exit
            call check(error, printed%outside == 0, where // ": ucosub.f wrote " &
                & // to_text(printed%outside) // " entries outside the declared block")
            if (allocated(error)) exit
            if (allocated(reported)) then
                ! Same words up to the number, which the two forms format differently.
                cut = index(printed%message, "got", back=.true.)
                expected = trim(printed%message)
                if (cut > 0) expected = printed%message(:cut + 2)
                call check(error, index(reported%message, expected) > 0 &
                    & .and. printed%error_id == k, where // ": ucosub.f reported '" // expected &
                    & // "' for ID " // to_text(printed%error_id) // ", the module '" &
                    & // reported%message // "'")
                if (allocated(error)) exit
            end if
            if (cases(k)%iflag == 3 .and. .not. allocated(reported)) then
                associate (declared => registry%entries(1))
                    call check(error, printed%declared == n .and. printed%declared_id == k &
                        & .and. all(printed%codes(:n) == declared%codes) &
                        & .and. all(printed%parts(:n) == declared%parts), where &
                        & // ": UCOVAR declarations differ")
                end associate
                if (allocated(error)) exit
            end if
            call check(error, same_value(printed%scalar, scalar) &
                & .and. all(same_value(printed%array(:n), array(:n))) &
                & .and. all(same_value(printed%xmatrx(:n, :n), xmatrx(:n, :n))), where &
                & // ": outputs differ (IDRSEL " // to_text(cases(k)%idrsel(1)) // "," &
                & // to_text(cases(k)%idrsel(2)) // "," // to_text(cases(k)%idrsel(3)) // ")")
            if (allocated(error)) exit
        end do
        close(unit)
    end subroutine compare_results

end module generated_fixed_form
