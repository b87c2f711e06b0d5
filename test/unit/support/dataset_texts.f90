! SPDX-License-Identifier: MIT
!> A dataset's text written to the tests' folder and run in memory, as the suites of the
!> dataset's statements do (motions, couplers, springs, analyses, joint motions).
module dataset_texts
    use rollcon_error, only : error_type
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type
    implicit none
    private

    public :: run_text, write_text, texts_dir

    !> Where the texts are written
    character(len=*), parameter :: texts_dir = "build/rollcon-test"

contains

    !> Write the dataset to texts_dir/name and run it with its rows kept, no output files; a
    !> run that fails returns its summary in result and why in error.
    subroutine run_text(name, text, result, rows, error)
        character(len=*), intent(in) :: name, text
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(error_type), allocatable :: failure

        call write_text(name, text)
        call load_job(texts_dir // "/" // name, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, failure, rows)
        if (allocated(failure)) call move_alloc(failure, error)
    end subroutine run_text

    !> Write text to texts_dir/name (the folder made first).
    subroutine write_text(name, text)
        character(len=*), intent(in) :: name, text
        integer :: unit

        call execute_command_line("mkdir -p " // texts_dir)
        open(newunit=unit, file=texts_dir // "/" // name, status="replace", action="write")
        write(unit, '(a)') text
        close(unit)
    end subroutine write_text

end module dataset_texts
