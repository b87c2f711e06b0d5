! SPDX-License-Identifier: MIT
!> The dataset as text, its size and its bytes: a generated dataset of 20 000 markers on 1000
!> parts reads correctly, and the bytes the reader asks of the allocator grow linearly with
!> the markers (a list grown by concatenation, the reader's quadratic part until now, asks for
!> quadratically many; the time is measured apart, never here); a UTF-8 byte-order mark at the
!> start and UTF-8 text in comments are accepted as in scenes, and CRLF line ends; non-ASCII
!> text outside comments, a mark elsewhere and control characters are refused with the line,
!> the column and the character shown visibly.
module test_adm_text
    use, intrinsic :: iso_c_binding, only : c_int, c_long_long
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_namelist_lexer, only : line_type
    use rollcon_adm_lexer, only : read_dataset_lines
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm, read_adm_lines
    use rollcon_testing, only : unittest_type, new_unittest, check, skip_test
    implicit none
    private

    public :: collect_adm_text

    interface
        !> Bytes asked of malloc, calloc and realloc since the program started
        function malloc_bytes() result(bytes) bind(c, name="rollcon_malloc_bytes")
            import :: c_long_long
            integer(c_long_long) :: bytes
        end function malloc_bytes

        !> 1 when the allocator is interposed (glibc), 0 when the counts mean nothing
        function malloc_counting() result(counting) bind(c, name="rollcon_malloc_counting")
            import :: c_int
            integer(c_int) :: counting
        end function malloc_counting
    end interface

    !> Markers of the large dataset, and of the small one it is compared with
    integer, parameter :: many_markers = 20000, few_markers = 2000
    !> Markers per part (one of them the part's CM marker)
    integer, parameter :: markers_per_part = 20
    !> Most the bytes allocated per marker may grow from few_markers to many_markers: lists
    !> that double when full allocate between 1 and 2 times their final size (the ratio is
    !> at most 2 whatever the sizes), while a list grown one element at a time allocates
    !> n^2/2 elements, ten times more per marker at ten times the markers
    real(wp), parameter :: growth_limit = 3.0_wp
    !> The UTF-8 encoding of the byte-order mark, theta, and a degree sign
    character(len=*), parameter :: bom = achar(239) // achar(187) // achar(191), &
        & theta = achar(206) // achar(184), degree_sign = achar(194) // achar(176)

contains

    !> Tests of this suite.
    subroutine collect_adm_text(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("twenty-thousand-markers", test_many_markers), &
            & new_unittest("allocation-linear-in-markers", test_linear_allocation), &
            & new_unittest("byte-order-mark-skipped", test_byte_order_mark), &
            & new_unittest("utf8-in-comments", test_utf8_comments), &
            & new_unittest("crlf-line-ends", test_crlf), &
            & new_unittest("bytes-refused-visibly", test_bytes_refused)]
    end subroutine collect_adm_text

    !> A dataset of `markers` markers, markers_per_part on each part (ids 7, 14, 21, ...: not
    !> their positions), the first of each its CM; an SFORCE between the first and last markers
    !> reading the position of the middle one.
    function generated_dataset(markers) result(lines)
        integer, intent(in) :: markers
        type(line_type), allocatable :: lines(:)
        integer :: parts, p, k, m, n

        parts = markers/markers_per_part
        allocate(lines(6 + 2*parts + markers))
        lines(1)%text = "generated: " // to_text(markers) // " markers"
        lines(2)%text = "UNITS/SYSTEM=SI"
        lines(3)%text = "PART/1, GROUND"
        n = 3
        m = 0
        do p = 1, parts
            n = n + 1
            lines(n)%text = "PART/" // to_text(p + 1) // ", MASS=" // to_text(p) // ", CM=" &
                & // to_text(marker_id(m + 1)) // ", IP=1, 1, 1.5"
            n = n + 1
            lines(n)%text = ", QG=" // to_text(p) // ", 0, 1, VX=0.5"
            do k = 1, markers_per_part
                m = m + 1
                n = n + 1
                if (k == 1) then
                    lines(n)%text = "MARKER/" // to_text(marker_id(m)) // ", PART=" &
                        & // to_text(p + 1) // ", REULER=0D, 90D, 0D"
                else
                    lines(n)%text = "MARKER/" // to_text(marker_id(m)) // ", PART=" &
                        & // to_text(p + 1) // ", QP=" // to_text(m) // ", 0, 0"
                end if
            end do
        end do
        lines(n + 1)%text = "SFORCE/1, I=" // to_text(marker_id(1)) // ", J=" &
            & // to_text(marker_id(markers)) // ", FUNCTION=DX(" &
            & // to_text(marker_id(markers/2)) // ")"
        lines(n + 2)%text = "SIMULATE/DYNAMIC, END=1, STEPS=10"
        lines(n + 3)%text = "END"
        lines = lines(:n + 3)
    end function generated_dataset

    !> Id of the m-th marker.
    pure integer function marker_id(m)
        integer, intent(in) :: m

        marker_id = 7*m
    end function marker_id

    !> Every part and marker of the generated dataset, in file order, with its values; the
    !> force's markers and input.
    subroutine test_many_markers(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        integer :: m, p

        call read_adm_lines("generated.adm", generated_dataset(many_markers), model, error)
        if (allocated(error)) return
        call check(error, size(model%markers) == many_markers .and. size(model%parts) == &
            & 1 + many_markers/markers_per_part .and. size(model%forces) == 1, "counts: " &
            & // to_text(size(model%markers)) // " markers, " // to_text(size(model%parts)) &
            & // " parts")
        if (allocated(error)) return
        call check(error, all([(model%markers(m)%id == marker_id(m), m = 1, many_markers)]) &
            & .and. all([(model%markers(m)%part == 2 + (m - 1)/markers_per_part, &
            & m = 1, many_markers)]), "marker ids or parts out of order")
        if (allocated(error)) return
        call check(error, all([(model%markers(m)%qp(1) == merge(0.0_wp, real(m, wp), &
            & mod(m - 1, markers_per_part) == 0), m = 1, many_markers)]), "marker positions")
        if (allocated(error)) return
        call check(error, all([(model%parts(p + 1)%cm == marker_id((p - 1)*markers_per_part &
            & + 1) .and. model%parts(p + 1)%mass == real(p, wp), p = 1, &
            & many_markers/markers_per_part)]), "parts' CM markers or masses")
        if (allocated(error)) return
        call check(error, model%forces(1)%i == marker_id(1) .and. model%forces(1)%j == &
            & marker_id(many_markers) .and. model%forces(1)%functions(1)%inputs(1)%marker == &
            & marker_id(many_markers/2), "the force's markers")
    end subroutine test_many_markers

    !> The bytes the reader asks for per marker, at 2000 and at 20 000 markers: not growing
    !> (lists allocated at their size or doubled, ids found through an index). Reading data
    !> sets of 5000 and 20 000 markers took 3.3 s and 56 s with lists grown one statement at a
    !> time; this is the structure that made it so, checked without a clock.
    subroutine test_linear_allocation(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: few(:), many(:)
        real(wp) :: per_marker_few, per_marker_many

        if (malloc_counting() == 0) then
            call skip_test(error, "malloc is not interposed on this C library")
            return
        end if
        few = generated_dataset(few_markers)
        many = generated_dataset(many_markers)
        call bytes_per_marker(few, few_markers, per_marker_few, error)
        if (allocated(error)) return
        call bytes_per_marker(many, many_markers, per_marker_many, error)
        if (allocated(error)) return
        call check(error, per_marker_many <= growth_limit*per_marker_few, "bytes allocated " &
            & // "per marker grow from " // to_text(per_marker_few) // " at " &
            & // to_text(few_markers) // " markers to " // to_text(per_marker_many) // " at " &
            & // to_text(many_markers))
    end subroutine test_linear_allocation

    !> Bytes asked of the allocator while reading lines, per marker.
    subroutine bytes_per_marker(lines, markers, per_marker, error)
        type(line_type), intent(in) :: lines(:)
        integer, intent(in) :: markers
        real(wp), intent(out) :: per_marker
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: model
        integer(c_long_long) :: start

        start = malloc_bytes()
        call read_adm_lines("generated.adm", lines, model, error)
        per_marker = real(malloc_bytes() - start, wp)/markers
    end subroutine bytes_per_marker

    !> data/coin.adm with a byte-order mark before its title reads as it is, the title without
    !> the mark; written to a file too.
    subroutine test_byte_order_mark(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(adm_model_type) :: plain, marked

        call read_dataset_lines("data/coin.adm", lines, error)
        if (allocated(error)) return
        call read_adm_lines("coin.adm", lines, plain, error)
        if (allocated(error)) return
        lines(1)%text = bom // lines(1)%text
        call read_adm_lines("coin.adm", lines, marked, error)
        if (allocated(error)) return
        call check(error, marked%title == plain%title .and. index(plain%title, "coin:") == 1, &
            & "title with the mark: " // marked%title)
        if (allocated(error)) return
        call check(error, same_model(marked, plain), "coin.adm with a mark reads otherwise")
        if (allocated(error)) return
        call write_file("build/test_adm_text_bom.adm", lines, new_line("a"))
        call read_adm("build/test_adm_text_bom.adm", marked, error)
        if (allocated(error)) return
        call check(error, marked%title == plain%title .and. same_model(marked, plain), &
            & "coin.adm with a mark, from a file")
    end subroutine test_byte_order_mark

    !> UTF-8 in comment lines and in comments after statements (theta, a degree sign) leaves
    !> the dataset as it is.
    subroutine test_utf8_comments(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(adm_model_type) :: plain, commented
        integer :: i

        call read_dataset_lines("data/coin.adm", lines, error)
        if (allocated(error)) return
        call read_adm_lines("coin.adm", lines, plain, error)
        if (allocated(error)) return
        do i = 2, size(lines)
            if (index(lines(i)%text, "!") == 1) then
                lines(i)%text = "! " // theta // " = 90" // degree_sign // ": " // lines(i)%text
            else if (len_trim(lines(i)%text) > 0) then
                lines(i)%text = lines(i)%text // "   ! " // theta // degree_sign
            end if
        end do
        call read_adm_lines("coin.adm", lines, commented, error)
        if (allocated(error)) return
        call check(error, same_model(commented, plain), "UTF-8 comments change coin.adm")
    end subroutine test_utf8_comments

    !> A file with CRLF line ends reads as with LF ends.
    subroutine test_crlf(error)
        type(error_type), allocatable, intent(out) :: error
        type(line_type), allocatable :: lines(:)
        type(adm_model_type) :: plain, crlf

        call read_dataset_lines("data/coin.adm", lines, error)
        if (allocated(error)) return
        call read_adm_lines("coin.adm", lines, plain, error)
        if (allocated(error)) return
        call write_file("build/test_adm_text_crlf.adm", lines, achar(13) // achar(10))
        call read_adm("build/test_adm_text_crlf.adm", crlf, error)
        if (allocated(error)) return
        call check(error, same_model(crlf, plain), "coin.adm with CRLF ends reads otherwise")
    end subroutine test_crlf

    !> Non-ASCII text outside comments (also in the title), a byte-order mark after the start,
    !> and control characters (also in comments) are refused with line, column and character.
    subroutine test_bytes_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: file = "bytes.adm"
        character(len=:), allocatable :: cases(:), expected(:)
        type(line_type), allocatable :: lines(:)
        type(adm_model_type) :: model
        type(error_type), allocatable :: found
        integer :: i

        cases = [character(len=60) :: "PART/1, GROUND, MASS=" // theta, &
            & bom // "PART/1, GROUND", "PART/1, GROUND ! a NUL " // achar(0), &
            & "PART/1," // achar(27) // " GROUND", "PART/1, GROUND" // achar(255)]
        expected = [character(len=160) :: ":2: non-ASCII character U+03B8 at column 22; " &
            & // "outside comments a dataset is ASCII (a byte-order mark is allowed at the " &
            & // "start only)", ":2: non-ASCII character U+FEFF at column 1; outside " &
            & // "comments a dataset is ASCII (a byte-order mark is allowed at the start only)", &
            & ":2: control character \x00 at column 24; a dataset is text (a tab is a blank)", &
            & ":2: control character \x1B at column 8; a dataset is text (a tab is a blank)", &
            & ":2: non-ASCII character \xFF at column 15; outside comments a dataset is ASCII " &
            & // "(a byte-order mark is allowed at the start only)"]
        do i = 1, size(cases)
            lines = [line_type("bytes"), line_type(trim(cases(i))), line_type("END")]
            call read_adm_lines(file, lines, model, found)
            call check(error, allocated(found), "case " // to_text(i) // " accepted")
            if (allocated(error)) return
            call check(error, found%message == file // trim(expected(i)), found%message)
            if (allocated(error)) return
            deallocate(found)
        end do
        lines = [line_type("coin " // theta), line_type("END")]
        call read_adm_lines(file, lines, model, found)
        call check(error, allocated(found), "a title in UTF-8 accepted")
        if (allocated(error)) return
        call check(error, found%message == file // ":1: non-ASCII character U+03B8 at column " &
            & // "6; outside comments a dataset is ASCII (a byte-order mark is allowed at the " &
            & // "start only)", found%message)
    end subroutine test_bytes_refused

    !> The same parts, markers, UCONs, forces, gravity and run (the values the fuzz and the
    !> reader's own suites check; this asks only that nothing moved).
    pure logical function same_model(a, b) result(same)
        type(adm_model_type), intent(in) :: a, b
        integer :: i, k

        same = size(a%parts) == size(b%parts) .and. size(a%markers) == size(b%markers) &
            & .and. size(a%ucons) == size(b%ucons) .and. size(a%forces) == size(b%forces)
        if (.not. same) return
        same = all(a%gravity == b%gravity) .and. a%run%settings%end_time == &
            & b%run%settings%end_time .and. a%run%settings%output_step == &
            & b%run%settings%output_step .and. a%run%settings%formulation == &
            & b%run%settings%formulation
        do i = 1, size(a%parts)
            same = same .and. a%parts(i)%id == b%parts(i)%id .and. a%parts(i)%mass == &
                & b%parts(i)%mass .and. all(a%parts(i)%ip == b%parts(i)%ip) .and. &
                & all(a%parts(i)%qg == b%parts(i)%qg) .and. all(a%parts(i)%velocity == &
                & b%parts(i)%velocity) .and. all(a%parts(i)%angular_velocity == &
                & b%parts(i)%angular_velocity) .and. a%parts(i)%cm == b%parts(i)%cm
        end do
        do i = 1, size(a%markers)
            same = same .and. a%markers(i)%id == b%markers(i)%id .and. all(a%markers(i)%qp &
                & == b%markers(i)%qp) .and. all(a%markers(i)%reuler == b%markers(i)%reuler)
        end do
        do i = 1, size(a%ucons)
            same = same .and. a%ucons(i)%id == b%ucons(i)%id .and. all(a%ucons(i)%par == &
                & b%ucons(i)%par)
        end do
        do i = 1, size(a%forces)
            same = same .and. all(a%forces(i)%given .eqv. b%forces(i)%given)
            if (.not. same) return
            do k = 1, 6
                if (a%forces(i)%given(k)) same = same .and. a%forces(i)%functions(k)%text == &
                    & b%forces(i)%functions(k)%text
            end do
        end do
    end function same_model

    !> Write lines, each ended by `ending`, byte for byte.
    subroutine write_file(path, lines, ending)
        character(len=*), intent(in) :: path, ending
        type(line_type), intent(in) :: lines(:)
        integer :: unit, i

        open(newunit=unit, file=path, status="replace", action="write", access="stream", &
            & form="unformatted")
        do i = 1, size(lines)
            write(unit) lines(i)%text // ending
        end do
        close(unit)
    end subroutine write_file

end module test_adm_text
