! SPDX-License-Identifier: MIT
!> Fuzz test of the CSV reader: seeded mutations of a disk scene's CSV (bytes
!> flipped, lines cut, duplicated, swapped, deleted, numbers replaced by extremes), each of
!> which must be refused cleanly (an error naming the file and line) or read cleanly (finite
!> values of bounded size, times in order, a layout of the disk's columns); never a crash or a
!> hang.
module test_csv_fuzz
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_simulation, only : history_type
    use rollcon_output_layout, only : output_layout_type
    use rollcon_csv_reader, only : read_output_csv, largest_value
    use rollcon_run_record, only : run_record_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : disk_run, write_run, make_folder, remove_folder
    use, intrinsic :: ieee_arithmetic, only : ieee_is_finite
    implicit none
    private

    public :: collect_csv_fuzz

    !> Scratch folder of the suite (kept when a case fails, with the failing file)
    character(len=*), parameter :: scratch = "build/test_csv_fuzz"
    !> Number of mutated files read
    integer, parameter :: cases = 10000
    !> Seed of the mutations: the same files on every run
    integer, parameter :: seed = 20261123
    !> Texts a number is replaced by: extremes, specials and near-numbers
    character(len=*), parameter :: extremes(24) = [character(len=24) :: "1e308", "-1e308", &
        & "1.8e308", "-0", "-0.0", "NaN", "nan", "Inf", "-Infinity", "1e-400", "1e99999", &
        & "4.9e-324", "2.2250738585072014E-308", "1e", "+", "-", "", " ", "1d300", &
        & "1.0E+400", "0x1p3", "T", ".", "1e100"]

    !> One line of the file
    type :: line_type
        character(len=:), allocatable :: text
    end type line_type

contains

    !> Tests of this suite.
    subroutine collect_csv_fuzz(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("reader-survives-mutations", test_mutations)]
    end subroutine collect_csv_fuzz

    !> Every mutated file is either refused with file:line or read as a sane history.
    subroutine test_mutations(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: base_path = scratch // "/base.csv"
        character(len=:), allocatable :: path
        type(run_record_type) :: run
        type(output_layout_type) :: layout
        type(history_type) :: history
        type(line_type), allocatable :: base(:), lines(:)
        type(error_type), allocatable :: failure
        integer, allocatable :: seed_values(:)
        integer :: k, n_seed, refused
        logical :: memory

        call make_folder(scratch)
        ! In memory when possible: 10 000 files replaced on a disk cost a minute of I/O.
        inquire(file="/dev/shm/.", exist=memory)
        path = scratch // "/mutated.csv"
        if (memory) path = "/dev/shm/rollcon_test_csv_fuzz_" // process_text() // ".csv"
        ! four rows: 0 to 0.03 s
        run = disk_run()
        run%history%count = 4
        call write_run(base_path, run, .false., error)
        if (allocated(error)) return
        call read_lines(base_path, base)
        call random_seed(size=n_seed)
        allocate(seed_values(n_seed))
        seed_values = seed + [(37*k, k = 1, n_seed)]
        call random_seed(put=seed_values)
        refused = 0
        do k = 1, cases
            lines = base
            call mutate(lines)
            call write_file(path, lines)
            call read_output_csv(path, layout, history, failure)
            if (allocated(failure)) then
                refused = refused + 1
                call check(error, index(failure%message, path // ":") == 1 .and. &
                    & verify(failure%message(len(path) + 2:len(path) + 2), "0123456789") &
                    & == 0, "case " // to_text(k) // ": refusal without file:line: " &
                    & // failure%message)
            else
                call check_history(error, k, layout, history)
            end if
            if (allocated(error)) then
                ! the failing file is kept for a look
                error%message = error%message // " (file " // path // ")"
                return
            end if
        end do
        call remove_folder(scratch)
        call delete(path)
        ! Mutations of every kind both break and spare files: some of each must occur.
        call check(error, refused > 0 .and. refused < cases, to_text(refused) // " of " &
            & // to_text(cases) // " mutated files refused")
    end subroutine test_mutations

    !> A history read cleanly: finite values within bounds, times in order, and a layout of
    !> the columns a disk scene writes (a mutation that changes a name is refused).
    subroutine check_history(error, k, layout, history)
        type(error_type), allocatable, intent(out) :: error
        integer, intent(in) :: k
        type(output_layout_type), intent(in) :: layout
        type(history_type), intent(in) :: history

        associate (rows => history%rows(:, :history%count))
            call check(error, history%count >= 1 .and. all(ieee_is_finite(rows)) .and. &
                & all(abs(rows) <= largest_value), "case " // to_text(k) &
                & // ": accepted a value that is not finite or beyond " &
                & // to_text(largest_value))
            if (allocated(error)) return
            call check(error, all(rows(1, 2:) >= rows(1, :history%count - 1)), "case " &
                & // to_text(k) // ": times out of order")
            if (allocated(error)) return
        end associate
        call check(error, all(layout%part_ids == [1]) .and. size(layout%ucon_ids) == 3 .and. &
            & layout%column("Fn") > 0 .and. size(history%rows, 1) == layout%columns(), "case " &
            & // to_text(k) // ": a layout other than the disk scene's was accepted")
    end subroutine check_history

    !> One to three random mutations.
    subroutine mutate(lines)
        type(line_type), allocatable, intent(inout) :: lines(:)
        integer :: count, i, j

        count = random_integer(3)
        do i = 1, count
            if (size(lines) == 0) return
            select case (random_integer(8))
            case (1)
                call flip_byte(lines(random_integer(size(lines)))%text)
            case (2)
                j = random_integer(size(lines))
                lines(j)%text = lines(j)%text(:random_integer(len(lines(j)%text) + 1) - 1)
            case (3)
                lines = duplicated(lines, random_integer(size(lines)))
            case (4)
                call swap(lines, random_integer(size(lines)), random_integer(size(lines)))
            case (5)
                lines = without(lines, random_integer(size(lines)))
            case (6, 7)
                call replace_field(lines(random_integer(size(lines)))%text, &
                    & trim(extremes(random_integer(size(extremes)))))
            case default
                lines = lines(:random_integer(size(lines)))
            end select
        end do
    end subroutine mutate

    !> A random byte of text set to a random value (any of the 256).
    subroutine flip_byte(text)
        character(len=:), allocatable, intent(inout) :: text

        if (len(text) == 0) return
        associate (i => random_integer(len(text)))
            text(i:i) = achar(random_integer(256) - 1)
        end associate
    end subroutine flip_byte

    !> A random comma-separated field of text replaced by value.
    subroutine replace_field(text, value)
        character(len=:), allocatable, intent(inout) :: text
        character(len=*), intent(in) :: value
        integer :: field, start, i, finish

        field = random_integer(22)
        start = 1
        do i = 2, field
            if (index(text(start:), ",") == 0) exit
            start = start + index(text(start:), ",")
        end do
        finish = index(text(start:), ",")
        if (finish == 0) then
            text = text(:start - 1) // value
        else
            text = text(:start - 1) // value // text(start + finish - 1:)
        end if
    end subroutine replace_field

    !> lines with line i twice.
    function duplicated(lines, i) result(longer)
        type(line_type), intent(in) :: lines(:)
        integer, intent(in) :: i
        type(line_type), allocatable :: longer(:)

        longer = [lines(:i), lines(i:)]
    end function duplicated

    !> lines without line i.
    function without(lines, i) result(shorter)
        type(line_type), intent(in) :: lines(:)
        integer, intent(in) :: i
        type(line_type), allocatable :: shorter(:)

        shorter = [lines(:i - 1), lines(i + 1:)]
    end function without

    !> Exchange lines i and j.
    subroutine swap(lines, i, j)
        type(line_type), intent(inout) :: lines(:)
        integer, intent(in) :: i, j
        type(line_type) :: kept

        kept = lines(i)
        lines(i) = lines(j)
        lines(j) = kept
    end subroutine swap

    !> A random integer in 1..n.
    integer function random_integer(n)
        integer, intent(in) :: n
        real(wp) :: u

        call random_number(u)
        random_integer = min(n, 1 + int(u*n))
    end function random_integer

    !> This process's id as text (a private file name in a shared folder).
    function process_text() result(text)
        character(len=:), allocatable :: text

        text = to_text(getpid())  ! gfortran's GETPID
    end function process_text

    !> Remove a file.
    subroutine delete(path)
        character(len=*), intent(in) :: path
        integer :: unit, stat

        open(newunit=unit, file=path, status="old", iostat=stat)
        if (stat == 0) close(unit, status="delete")
    end subroutine delete

    !> The lines of a text file.
    subroutine read_lines(path, lines)
        character(len=*), intent(in) :: path
        type(line_type), allocatable, intent(out) :: lines(:)
        character(len=4096) :: buffer
        integer :: unit, stat

        allocate(lines(0))
        open(newunit=unit, file=path, status="old", action="read")
        do
            read(unit, '(a)', iostat=stat) buffer
            if (stat /= 0) exit
            lines = [lines, line_type(trim(buffer))]
        end do
        close(unit)
    end subroutine read_lines

    !> Write lines, each ended by a line feed, byte for byte.
    subroutine write_file(path, lines)
        character(len=*), intent(in) :: path
        type(line_type), intent(in) :: lines(:)
        integer :: unit, i

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="unformatted")
        do i = 1, size(lines)
            write(unit) lines(i)%text // new_line("a")
        end do
        close(unit)
    end subroutine write_file

end module test_csv_fuzz
