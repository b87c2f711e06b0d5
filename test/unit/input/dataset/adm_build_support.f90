! SPDX-License-Identifier: MIT
!> Datasets for the adm-build tests: data/coin.adm with one line replaced, written under
!> build/rollcon-test and read.
module adm_build_support
    use rollcon_error, only : error_type, fatal_error
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    implicit none
    private

    public :: write_lines, read_lines_model

    character(len=*), parameter :: work_dir = "build/rollcon-test"

contains

    !> Copy `source` to work_dir/name with the line `old` replaced by `new` (error: not found).
    subroutine write_lines(source, name, old, new, error)
        character(len=*), intent(in) :: source, name, old, new
        type(error_type), allocatable, intent(out) :: error
        character(len=4096) :: buffer
        integer :: in, out, stat
        logical :: replaced

        call execute_command_line("mkdir -p " // work_dir)
        open(newunit=in, file=source, status="old", action="read")
        open(newunit=out, file=work_dir // "/" // name, status="replace", action="write")
        replaced = .false.
        do
            read(in, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            if (trim(buffer) == old) then
                write(out, '(a)') new
                replaced = .true.
            else
                write(out, '(a)') trim(buffer)
            end if
        end do
        close(in)
        close(out)
        if (.not. replaced) call fatal_error(error, source // ": no line '" // old // "'")
    end subroutine write_lines

    !> data/coin.adm with the line `old` replaced by `new`, read.
    subroutine read_lines_model(name, old, new, adm, error)
        character(len=*), intent(in) :: name, old, new
        type(adm_model_type), intent(out) :: adm
        type(error_type), allocatable, intent(out) :: error

        call write_lines("data/coin.adm", name, old, new, error)
        if (allocated(error)) return
        call read_adm(work_dir // "/" // name, adm, error)
    end subroutine read_lines_model

end module adm_build_support
