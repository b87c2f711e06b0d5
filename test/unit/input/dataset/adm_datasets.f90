! SPDX-License-Identifier: MIT
!> Helpers of the dataset suites: write lines to a file under build/ and read it; a small
!> dataset that reads cleanly, and the check that each one-line change of it is refused with
!> exactly the message expected.
module adm_datasets
    use rollcon_error, only : error_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_testing, only : check
    implicit none
    private

    public :: read_dataset, check_refusals, base, base_file

    character(len=*), parameter :: work_dir = "build/rollcon-test"
    !> The file the refusal checks write; messages start with it
    character(len=*), parameter :: base_file = work_dir // "/refusal.adm"

    !> A dataset that reads cleanly; the refusal tables change one line of it
    character(len=48), parameter :: base(14) = [character(len=48) :: &
        & "refusal base", &
        & "UNITS/SYSTEM=SI", &
        & "PART/1, GROUND", &
        & "PART/2, MASS=1, CM=3, IP=2, 2, 3", &
        & ", QG=0, 0, 1, VX=0.5", &
        & "MARKER/3, PART=2, REULER=0D, 90D, 0D", &
        & "MARKER/4, PART=1", &
        & "UCON/1, FUNCTION=USER(2, 21, 1)", &
        & "ACCGRAV/KGRAV=-9.81", &
        & "SFORCE/5, I=3, J=4, TRANSLATION, FUNCTION=TIME", &
        & "SIMULATE/DYNAMIC, END=1, STEPS=10", &
        & "INTEGRATOR/ERROR=1e-8", &
        & "OUTPUT", &
        & "END"]

contains

    !> Write lines (a '|' inside one starts a new line) to build/rollcon-test/name; read it.
    subroutine read_dataset(name, lines, model, error)
        character(len=*), intent(in) :: name, lines(:)
        type(adm_model_type), intent(out) :: model
        type(error_type), allocatable, intent(out) :: error
        integer :: unit, i, bar
        character(len=:), allocatable :: rest

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=unit, file=work_dir // "/" // name, status="replace", action="write")
        do i = 1, size(lines)
            rest = trim(lines(i))
            bar = index(rest, "|")
            do while (bar > 0)
                write(unit, '(a)') rest(:bar - 1)
                rest = rest(bar + 1:)
                bar = index(rest, "|")
            end do
            write(unit, '(a)') rest
        end do
        close(unit)
        call read_adm(work_dir // "/" // name, model, error)
    end subroutine read_dataset

    !> For each case: line at(i) of the base replaced by replaced(i) must be refused with
    !> exactly base_file // expected(i). A '*' in expected stands for any text (a rounding
    !> residue printed in full).
    subroutine check_refusals(error, at, replaced, expected)
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in) :: at(:)
        character(len=*), intent(in) :: replaced(:), expected(:)
        character(len=len(base) + len(replaced)) :: lines(size(base))
        type(adm_model_type) :: model
        type(error_type), allocatable :: refused
        character(len=:), allocatable :: want
        integer :: i, star
        logical :: same

        do i = 1, size(at)
            lines = base
            lines(at(i)) = replaced(i)
            call read_dataset("refusal.adm", lines, model, refused)
            call check(error, allocated(refused), trim(replaced(i)) // ": accepted")
            if (allocated(error)) return
            want = base_file // trim(expected(i))
            star = index(want, "*")
            if (star == 0) then
                same = refused%message == want
            else
                same = len(refused%message) >= len(want) - 1
                if (same) same = refused%message(:star - 1) == want(:star - 1) &
                    & .and. refused%message(len(refused%message) - (len(want) - star) + 1:) &
                    & == want(star + 1:)
            end if
            call check(error, same, trim(replaced(i)) // ": got '" // refused%message &
                & // "', expected '" // want // "'")
            if (allocated(error)) return
            deallocate(refused)
        end do
    end subroutine check_refusals

end module adm_datasets
