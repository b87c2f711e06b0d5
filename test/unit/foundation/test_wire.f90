! SPDX-License-Identifier: MIT
!> What a child process hands its parent: values packed into bytes and read back
!> (rollcon_wire), a run's summary, layout and shapes among them (rollcon_run_wire), frames on a
!> pipe (rollcon_frames), a checked UCON's report through a file (rollcon_audit_transfer), and a
!> linear analysis and its eigenvalues against speed (rollcon_isolated_linear).
!> What is read back is what was written, bit for bit; bytes cut short are refused.
module test_wire
    use, intrinsic :: iso_c_binding, only : c_int, c_long, c_size_t, c_char
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_wire, only : wire_writer_type, wire_reader_type
    use rollcon_text, only : to_text
    use rollcon_run_wire, only : pack_summary, unpack_summary, pack_shapes, unpack_shapes
    use rollcon_run_summary, only : run_summary_type, status_inaccurate
    use rollcon_watch, only : watch_measure_type
    use rollcon_output_layout, only : new_output_layout
    use rollcon_part_shapes, only : part_shape_type, shape_disk, shape_ellipsoid
    use rollcon_frames, only : send_frame, frame_buffer_type
    use rollcon_ucosub_audit, only : ucon_report_type
    use rollcon_audit_transfer, only : pack_ucon_report, unpack_ucon_report
    use rollcon_linearisation, only : linear_result_type
    use rollcon_linear_speeds, only : speed_table_type, stability_change_type
    use rollcon_isolated_linear, only : pack_linear_result, unpack_linear_result, &
        & pack_speed_table, unpack_speed_table
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_wire

    !> The report file of the transfer test

    interface
        function c_pipe(fds) result(rc) bind(c, name="pipe")
            import :: c_int
            integer(c_int), intent(out) :: fds(2)
            integer(c_int) :: rc
        end function c_pipe

        function c_read(fd, buffer, count) result(got) bind(c, name="read")
            import :: c_int, c_long, c_size_t, c_char
            integer(c_int), value :: fd
            character(kind=c_char), intent(out) :: buffer(*)
            integer(c_size_t), value :: count
            integer(c_long) :: got
        end function c_read

        function c_close(fd) result(rc) bind(c, name="close")
            import :: c_int
            integer(c_int), value :: fd
            integer(c_int) :: rc
        end function c_close
    end interface

contains

    !> Tests of this suite.
    subroutine collect_wire(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("values-read-back", test_values), &
            & new_unittest("bytes-cut-short-refused", test_cut_short), &
            & new_unittest("run-results-read-back", test_run_results), &
            & new_unittest("frames-whole-and-in-order", test_frames), &
            & new_unittest("frame-to-a-closed-pipe-is-an-error", test_closed_pipe), &
            & new_unittest("check-report-read-back", test_report), &
            & new_unittest("linear-results-read-back", test_linear_results)]
    end subroutine collect_wire

    !> Every kind of value, extremes included (the int64 range, -0, a subnormal, NaN, texts
    !> with NUL and byte 255, empty arrays, a text longer than the first allocation), read back
    !> bit for bit and in order, every byte consumed.
    subroutine test_values(error)
        type(error_type), allocatable, intent(out) :: error
        type(wire_writer_type) :: writer
        type(wire_reader_type) :: reader
        real(wp) :: reals(6)
        integer, allocatable :: ints(:)
        real(wp), allocatable :: back(:)
        logical, allocatable :: flags(:)
        character(len=:), allocatable :: text, long, got
        integer(int64) :: first, second
        real(wp) :: value
        logical :: yes, no
        integer :: k

        reals = [-0.0_wp, tiny(1.0_wp)/1024.0_wp, huge(1.0_wp), 0.1_wp, -1.0_wp/3.0_wp, &
            & ieee_value(1.0_wp, ieee_quiet_nan)]
        text = "a,b" // achar(0) // achar(255) // "z"
        long = repeat("0123456789", 100)
        call writer%put_int(-huge(1_int64) - 1_int64)
        call writer%put_int(huge(1_int64))
        call writer%put_ints([3, -7, 0, huge(1)])
        call writer%put_ints([integer ::])
        do k = 1, size(reals)
            call writer%put_real(reals(k))
        end do
        call writer%put_reals(reals)
        call writer%put_logical(.true.)
        call writer%put_logical(.false.)
        call writer%put_logicals([.true., .false., .true.])
        call writer%put_text("")
        call writer%put_text(text)
        call writer%put_text(long)

        reader%bytes = writer%packed()
        first = reader%get_int()
        second = reader%get_int()
        call check(error, first == -huge(1_int64) - 1_int64 .and. second == huge(1_int64), &
            & "the int64 extremes")
        if (allocated(error)) return
        call reader%get_ints(ints)
        call check(error, size(ints) == 4, "four integers")
        if (allocated(error)) return
        call check(error, all(ints == [3, -7, 0, huge(1)]), "the integers")
        if (allocated(error)) return
        call reader%get_ints(ints)
        call check(error, size(ints) == 0, "an empty array of integers")
        if (allocated(error)) return
        do k = 1, size(reals)
            value = reader%get_real()
            call check(error, same_bits([value], reals(k:k)), "real " // achar(48 + k))
            if (allocated(error)) return
        end do
        call reader%get_reals(back)
        call check(error, same_bits(back, reals), "the array of reals")
        if (allocated(error)) return
        yes = reader%get_logical()
        no = reader%get_logical()
        call check(error, yes .and. .not. no, "two logicals")
        if (allocated(error)) return
        call reader%get_logicals(flags)
        call check(error, size(flags) == 3, "three logicals")
        if (allocated(error)) return
        call check(error, flags(1) .and. .not. flags(2) .and. flags(3), "the logicals")
        if (allocated(error)) return
        got = reader%get_text()
        call check(error, len(got) == 0, "the empty text")
        if (allocated(error)) return
        got = reader%get_text()
        call check(error, got == text .and. len(got) == len(text), &
            & "the text with NUL and byte 255")
        if (allocated(error)) return
        got = reader%get_text()
        call check(error, got == long, "the long text")
        if (allocated(error)) return
        call check(error, .not. reader%failed .and. reader%at == len(reader%bytes) + 1, &
            & "every byte read, no failure")
    end subroutine test_values

    !> A reader that runs past the end, or meets a length the bytes left cannot hold (longer
    !> than the rest, negative), stays failed and gives zeros and empty values from then on.
    subroutine test_cut_short(error)
        type(error_type), allocatable, intent(out) :: error
        type(wire_writer_type) :: writer
        type(wire_reader_type) :: reader
        real(wp), allocatable :: reals(:)
        integer, allocatable :: ints(:)
        character(len=:), allocatable :: bytes, text
        integer(int64) :: value
        real(wp) :: real_value
        logical :: flag

        ! 8 bytes of 42, 8 + 12 of the text, 8 of 7: the last value loses its last byte
        call writer%put_int(42_int64)
        call writer%put_text("twelve bytes")
        call writer%put_int(7_int64)
        bytes = writer%packed()
        reader%bytes = bytes(:len(bytes) - 1)
        value = reader%get_int()
        call check(error, value == 42_int64 .and. .not. reader%failed, &
            & "the first value of bytes cut short")
        if (allocated(error)) return
        text = reader%get_text()
        call check(error, text == "twelve bytes" .and. .not. reader%failed, &
            & "the text before the cut")
        if (allocated(error)) return
        value = reader%get_int()
        call check(error, value == 0_int64 .and. reader%failed, &
            & "the value cut off gives 0 and fails")
        if (allocated(error)) return

        ! the text cut after 4 of its 12 bytes: nothing of it, and the reader stays failed
        reader = wire_reader_type(bytes=bytes(:20))
        value = reader%get_int()
        text = reader%get_text()
        call check(error, value == 42_int64 .and. len(text) == 0 .and. reader%failed, &
            & "a text cut short")
        if (allocated(error)) return
        reader%bytes = bytes
        value = reader%get_int()
        call check(error, value == 0_int64 .and. reader%failed, "a failed reader stays failed")
        if (allocated(error)) return

        ! lengths that cannot be: more values than the bytes left hold, and negative
        writer = wire_writer_type()
        call writer%put_int(3_int64)
        call writer%put_real(1.0_wp)
        call writer%put_real(2.0_wp)
        reader = wire_reader_type(bytes=writer%packed())
        call reader%get_reals(reals)
        call check(error, size(reals) == 0 .and. reader%failed, &
            & "three reals in the bytes of two refused")
        if (allocated(error)) return
        writer = wire_writer_type()
        call writer%put_int(-1_int64)
        call writer%put_int(5_int64)
        reader = wire_reader_type(bytes=writer%packed())
        call reader%get_ints(ints)
        call check(error, size(ints) == 0 .and. reader%failed, "a negative length refused")
        if (allocated(error)) return
        ! a count whose byte length overflows 64 bits (2**61 reals of 8 bytes wrap round to 0)
        writer = wire_writer_type()
        call writer%put_int(2_int64**61)
        call writer%put_real(1.0_wp)
        reader = wire_reader_type(bytes=writer%packed())
        call reader%get_reals(reals)
        call check(error, size(reals) == 0 .and. reader%failed, &
            & "2**61 reals in the bytes of one refused")
        if (allocated(error)) return

        ! no bytes at all
        reader = wire_reader_type()
        real_value = reader%get_real()
        flag = reader%get_logical()
        call check(error, real_value == 0.0_wp .and. .not. flag .and. reader%failed, &
            & "a reader without bytes")
    end subroutine test_cut_short

    !> A run's summary with every field set (two watch measures, a layout with watch columns,
    !> re-basings, counters, a row count past 2**31) and the shapes of a disk and an ellipsoid
    !> read back field by field; the summary cut in half is refused.
    subroutine test_run_results(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary, back
        type(part_shape_type) :: shapes(2)
        type(part_shape_type), allocatable :: shapes_back(:)
        type(wire_writer_type) :: writer
        type(wire_reader_type) :: reader
        character(len=:), allocatable :: bytes
        integer :: k

        summary%status = status_inaccurate
        summary%message = "the energy drift passes its bound"
        summary%limit = "theta_limit"
        summary%solver_flag = -3
        summary%t_reached = 2.75_wp
        summary%q = [0.1_wp, -0.2_wp, 0.05_wp, 1.0_wp, 1.5_wp, -7.0_wp]
        summary%u = [1.0e-300_wp, 0.0_wp, -0.0_wp, 3.0_wp, 4.0_wp, 5.0_wp]
        summary%energy_reference = -0.0123_wp
        summary%energy_drift = 3.5e-9_wp
        summary%energy_scale = 0.75_wp
        summary%energy_step = 2.5e-11_wp
        summary%constraint_work = 1.25e-3_wp
        summary%dissipated_work = 5.0e-2_wp
        summary%friction_work = 3.0e-2_wp
        summary%impact_work = 1.0e-2_wp
        summary%dissipation_uncertainty = 2.0e-3_wp
        summary%dissipation_resolved = .false.
        summary%energy_conserved = .false.
        summary%layout = new_output_layout([2, 5], [11, 12, 13], &
            & [character(len=16) :: "height_2", "normal_force_2"])
        summary%residual_max = 1.25e-12_wp
        summary%ucon_residual_max = [1.0e-12_wp, 1.25e-12_wp, 2.0e-13_wp]
        summary%ucon_position = [.false., .false., .true.]
        summary%energy_bound = 4.0e-8_wp
        allocate(summary%measures(2))
        summary%measures(1) = watch_measure_type("height_residual", "largest height residual", &
            & "m", 2.5e-11_wp, 1.0e-9_wp, "3 sqrt(N) (atol + rtol R)", "height = 'position'")
        summary%measures(2) = watch_measure_type("slip", "largest slip", "m/s", 0.0_wp, &
            & 0.0_wp, "", "")
        summary%watch_lines = "first line" // new_line("a") // "second line"
        summary%rebasings = [0, 117]
        summary%steps = 1234
        summary%functions = 5678
        summary%jacobians = 90
        summary%failures = 12
        summary%root_evaluations = 3456
        summary%rows = 2_int64**40 + 1_int64
        summary%cpu_seconds = 0.125_wp
        shapes(1) = part_shape_type(id=2, kind=shape_disk, radius=0.1_wp, thickness=0.003_wp)
        shapes(2) = part_shape_type(id=5, kind=shape_ellipsoid, semi_axes=[0.3_wp, 0.2_wp, &
            & 0.1_wp])

        call pack_summary(writer, summary)
        call pack_shapes(writer, shapes)
        bytes = writer%packed()
        reader%bytes = bytes
        call unpack_summary(reader, back)
        call unpack_shapes(reader, shapes_back)
        call check(error, .not. reader%failed .and. reader%at == len(bytes) + 1, &
            & "every byte read, no failure")
        if (allocated(error)) return
        call check(error, back%status == summary%status .and. back%message == summary%message &
            & .and. back%limit == summary%limit .and. back%solver_flag == summary%solver_flag &
            & .and. (back%energy_conserved .eqv. summary%energy_conserved), &
            & "status, message, limit, flag, energy conserved")
        if (allocated(error)) return
        call check(error, same_bits([back%t_reached, back%energy_reference, back%energy_drift, &
            & back%energy_scale, back%energy_step, back%constraint_work, back%dissipated_work, &
            & back%friction_work, back%impact_work, back%dissipation_uncertainty, &
            & back%residual_max, back%energy_bound, back%cpu_seconds], [summary%t_reached, &
            & summary%energy_reference, summary%energy_drift, summary%energy_scale, &
            & summary%energy_step, summary%constraint_work, summary%dissipated_work, &
            & summary%friction_work, summary%impact_work, summary%dissipation_uncertainty, &
            & summary%residual_max, summary%energy_bound, summary%cpu_seconds]) .and. &
            & (back%dissipation_resolved .eqv. summary%dissipation_resolved), &
            & "the scalar reals, W resolved")
        if (allocated(error)) return
        call check(error, same_bits(back%q, summary%q) .and. same_bits(back%u, summary%u) &
            & .and. same_bits(back%ucon_residual_max, summary%ucon_residual_max), &
            & "q, u and the UCONs' residuals")
        if (allocated(error)) return
        call check(error, all(back%ucon_position .eqv. summary%ucon_position), "position UCONs")
        if (allocated(error)) return
        call check(error, all(back%layout%part_ids == [2, 5]) .and. &
            & all(back%layout%ucon_ids == [11, 12, 13]) .and. size(back%layout%extra) == 2, &
            & "the layout's ids")
        if (allocated(error)) return
        call check(error, back%layout%extra(1) == "height_2" .and. &
            & back%layout%extra(2) == "normal_force_2", "the layout's watch columns")
        if (allocated(error)) return
        call check(error, size(back%measures) == 2, "two measures")
        if (allocated(error)) return
        do k = 1, 2
            associate (got => back%measures(k), put => summary%measures(k))
                call check(error, got%name == put%name .and. got%label == put%label .and. &
                    & got%unit == put%unit .and. got%bound_rule == put%bound_rule .and. &
                    & got%remedy == put%remedy .and. same_bits([got%value, got%bound], &
                    & [put%value, put%bound]), "measure " // put%name)
            end associate
            if (allocated(error)) return
        end do
        call check(error, back%watch_lines == summary%watch_lines .and. &
            & all(back%rebasings == summary%rebasings), "the watch lines and the re-basings")
        if (allocated(error)) return
        call check(error, back%steps == 1234 .and. back%functions == 5678 .and. &
            & back%jacobians == 90 .and. back%failures == 12 .and. &
            & back%root_evaluations == 3456 .and. back%rows == summary%rows, "the counters")
        if (allocated(error)) return
        call check(error, size(shapes_back) == 2, "two shapes")
        if (allocated(error)) return
        do k = 1, 2
            call check(error, shapes_back(k)%id == shapes(k)%id .and. &
                & shapes_back(k)%kind == shapes(k)%kind .and. same_bits([shapes_back(k)%radius, &
                & shapes_back(k)%thickness, shapes_back(k)%semi_axes], [shapes(k)%radius, &
                & shapes(k)%thickness, shapes(k)%semi_axes]), "shape of part " // achar(48 + k))
            if (allocated(error)) return
        end do

        reader = wire_reader_type(bytes=bytes(:len(bytes)/2))
        call unpack_summary(reader, back)
        call check(error, reader%failed, "a summary cut in half is refused")
    end subroutine test_run_results

    !> Frames sent on a pipe come out of the buffer whole and in order, however the bytes are
    !> cut on the way (after 1 byte, 23 and all: the first frame is 16 + 5 bytes); a frame past
    !> the buffer's first size grows it; a negative length gives kind -1 and empties it.
    subroutine test_frames(error)
        type(error_type), allocatable, intent(out) :: error
        type(frame_buffer_type) :: buffer
        integer(c_int) :: fds(2)
        character(len=:), allocatable :: received, payloads(:), payload, big
        character(len=8) :: field
        integer, parameter :: kinds(3) = [7, 8, 9], lengths(3) = [5, 0, 256]
        !> Frames whole after each cut
        integer, parameter :: whole(3) = [0, 1, 3]
        integer :: kind, taken, k, cuts(0:3)
        integer(c_int) :: closed
        logical :: found

        allocate(character(len=256) :: payloads(3))
        call check(error, c_pipe(fds) == 0, "a pipe")
        if (allocated(error)) return
        call send_frame(int(fds(2)), kinds(1), "hello", error)
        if (.not. allocated(error)) call send_frame(int(fds(2)), kinds(2), "", error)
        if (.not. allocated(error)) call send_frame(int(fds(2)), kinds(3), all_bytes(), error)
        closed = c_close(fds(2))
        if (allocated(error)) then
            closed = c_close(fds(1))
            return
        end if
        received = read_all(fds(1))
        closed = max(closed, c_close(fds(1)))
        call check(error, closed == 0, "closing the pipe")
        if (allocated(error)) return
        call check(error, len(received) == 3*16 + sum(lengths), "the bytes on the pipe")
        if (allocated(error)) return

        cuts = [0, 1, 23, len(received)]
        taken = 0
        do k = 1, 3
            call buffer%add(received(cuts(k - 1) + 1:cuts(k)))
            do
                call buffer%next(kind, payload, found)
                if (.not. found) exit
                taken = taken + 1
                call check(error, taken <= 3, "no more than three frames")
                if (allocated(error)) return
                call check(error, kind == kinds(taken) .and. len(payload) == lengths(taken), &
                    & "frame " // achar(48 + taken) // "'s kind and length")
                if (allocated(error)) return
                payloads(taken) = payload
            end do
            call check(error, taken == whole(k), "frames whole after cut " // achar(48 + k))
            if (allocated(error)) return
        end do
        call check(error, payloads(1)(:5) == "hello" .and. payloads(3) == all_bytes(), &
            & "the payloads")
        if (allocated(error)) return

        ! a frame longer than the buffer's first 64 KiB, added in two pieces
        big = repeat("rollcon", 20000)
        call buffer%add(transfer(3_int64, field) // transfer(int(len(big), int64), field) &
            & // big(:1000))
        call buffer%next(kind, payload, found)
        call check(error, .not. found, "a big frame is not whole before its last byte")
        if (allocated(error)) return
        call buffer%add(big(1001:))
        call buffer%next(kind, payload, found)
        call check(error, found .and. kind == 3 .and. payload == big, "the big frame")
        if (allocated(error)) return

        call buffer%add(transfer(4_int64, field) // transfer(-1_int64, field) // "junk")
        call buffer%next(kind, payload, found)
        call check(error, found .and. kind == -1, "a negative length gives kind -1")
        if (allocated(error)) return
        call buffer%next(kind, payload, found)
        call check(error, .not. found, "nothing left after a negative length")
    end subroutine test_frames

    !> Writing a frame where no pipe is (a closed descriptor) is an error saying so.
    subroutine test_closed_pipe(error)
        type(error_type), allocatable, intent(out) :: error
        type(error_type), allocatable :: sent

        call send_frame(-1, 1, "lost", sent)
        call check(error, allocated(sent), "a frame to descriptor -1 is an error")
        if (allocated(error)) return
        call check(error, sent%message == "cannot hand the results to the parent process " &
            & // "(its pipe is closed: did it end?)", "the message: " // sent%message)
    end subroutine test_closed_pipe

    !> A UCON's check report with declared variables and two finding groups (one with the
    !> worst state and a message, one without) packed and read back field by field; the bytes
    !> cut in half, or with one byte more, are an error.
    subroutine test_report(error)
        type(error_type), allocatable, intent(out) :: error
        type(ucon_report_type) :: ucon, back
        type(error_type), allocatable :: failed
        character(len=:), allocatable :: bytes
        type(wire_writer_type) :: writer
        integer :: g

        ucon%id = 13
        ucon%par = [2.0_wp, 11.0_wp, 12.0_wp, 0.1_wp, 3.0_wp]
        ucon%declared = .true.
        ucon%parts = [2, 2, 2]
        ucon%codes = [11, 15, 26]
        ucon%states = 300
        ucon%compared = 12345
        ucon%worst = 1.5e-3_wp
        allocate(ucon%groups(2))
        ucon%groups(1)%code = 4
        ucon%groups(1)%rule = "derivative"
        ucon%groups(1)%output = "ARRAY (dF/dq)"
        ucon%groups(1)%row = 1
        ucon%groups(1)%column = 3
        ucon%groups(1)%count = 2
        ucon%groups(1)%states = [17, 250]
        ucon%groups(1)%expected = 0.5_wp
        ucon%groups(1)%returned = -0.5_wp
        ucon%groups(1)%state = 250
        ucon%groups(1)%time = 7.25_wp
        ucon%groups(1)%q = [0.1_wp, 1.2_wp, -3.0_wp]
        ucon%groups(1)%message = "sign error?"
        ucon%groups(2)%code = 1
        ucon%groups(2)%rule = "declaration"
        ucon%groups(2)%output = "UCOVAR"
        ucon%groups(2)%count = 1
        ucon%groups(2)%states = [integer ::]

        writer = wire_writer_type()
        call pack_ucon_report(writer, ucon)
        bytes = writer%packed()
        call unpack_ucon_report(bytes, back, error)
        if (allocated(error)) return
        call check(error, back%id == 13 .and. back%declared .and. back%states == 300 .and. &
            & back%compared == 12345 .and. back%worst == ucon%worst, "the UCON's numbers")
        if (allocated(error)) return
        call check(error, same_bits(back%par, ucon%par) .and. all(back%parts == ucon%parts) &
            & .and. all(back%codes == ucon%codes), "PAR and the declared variables")
        if (allocated(error)) return
        call check(error, size(back%groups) == 2, "two groups")
        if (allocated(error)) return
        do g = 1, 2
            associate (got => back%groups(g), put => ucon%groups(g))
                call check(error, got%code == put%code .and. got%rule == put%rule .and. &
                    & got%output == put%output .and. got%row == put%row .and. &
                    & got%column == put%column .and. got%count == put%count .and. &
                    & got%state == put%state .and. size(got%states) == size(put%states) .and. &
                    & same_bits([got%expected, got%returned, got%time], [put%expected, &
                    & put%returned, put%time]) .and. (allocated(got%q) .eqv. allocated(put%q)) &
                    & .and. (allocated(got%message) .eqv. allocated(put%message)), &
                    & "group " // achar(48 + g))
            end associate
            if (allocated(error)) return
        end do
        call check(error, all(back%groups(1)%states == [17, 250]) .and. &
            & same_bits(back%groups(1)%q, ucon%groups(1)%q) .and. &
            & back%groups(1)%message == "sign error?", "the first group's states, q, message")
        if (allocated(error)) return

        call unpack_ucon_report(bytes(:len(bytes)/2), back, failed)
        call check(error, allocated(failed), "a report cut in half is an error")
        if (allocated(error)) return
        call check(error, failed%message == "the report of a UCON sent back by its checking " &
            & // "process is damaged (" // to_text(len(bytes)/2) // " bytes, not one whole " &
            & // "report)", "the message: " // failed%message)
        if (allocated(error)) return
        deallocate(failed)
        call unpack_ucon_report(bytes // "x", back, failed)
        call check(error, allocated(failed), "a report with a byte more is an error")
    end subroutine test_report

    !> Bytes 0 to 255.
    function all_bytes() result(bytes)
        character(len=256) :: bytes
        integer :: k

        do k = 0, 255
            bytes(k + 1:k + 1) = achar(k)
        end do
    end function all_bytes

    !> Everything a pipe gives until its write end is closed.
    function read_all(fd) result(bytes)
        integer(c_int), intent(in) :: fd
        character(len=:), allocatable :: bytes
        character(kind=c_char) :: chunk(4096)
        integer(c_long) :: got

        bytes = ""
        do
            got = c_read(fd, chunk, int(size(chunk), c_size_t))
            if (got <= 0) exit
            bytes = bytes // transfer(chunk(:got), repeat(" ", int(got)))
        end do
    end function read_all

    !> The same reals to the bit (so -0 is not 0, and NaN is the same NaN).
    pure logical function same_bits(a, b)
        real(wp), intent(in) :: a(:), b(:)

        same_bits = size(a) == size(b)
        if (same_bits) same_bits = all(transfer(a, [0_int64]) == transfer(b, [0_int64]))
    end function same_bits

    !> A linear result (a 3 x 2 basis, a 2 x 2 A_red, its eigenvalues, the independent
    !> coordinates, the invariance and the zeros) and a table against speed with two stability
    !> changes read back field by field, bit for bit, every byte consumed; cut short, refused.
    subroutine test_linear_results(error)
        type(error_type), allocatable, intent(out) :: error
        type(linear_result_type) :: result, back
        type(speed_table_type) :: table, table_back
        type(stability_change_type) :: changes(2)
        type(stability_change_type), allocatable :: changes_back(:)
        type(wire_writer_type) :: writer
        type(wire_reader_type) :: reader
        character(len=:), allocatable :: bytes

        result%time = 0.25_wp
        result%states = 3
        result%reduced = 2
        result%real_part = [1.5_wp, -0.0_wp]
        result%imag_part = [2.0_wp, -2.0_wp]
        result%reduced_matrix = reshape([1.0_wp, 2.0_wp, 3.0_wp, 4.0_wp], [2, 2])
        result%basis = reshape([1.0_wp, 0.0_wp, 0.5_wp, 0.0_wp, 1.0_wp, -0.5_wp], [3, 2])
        result%independent = [1, 3]
        result%invariance = 3.0e-12_wp
        result%invariant = .false.
        result%zero_limit = 1.0e-6_wp
        result%zeros = 1
        call pack_linear_result(writer, result)
        reader%bytes = writer%packed()
        call unpack_linear_result(reader, back)
        call check(error, .not. reader%failed .and. reader%at == len(reader%bytes) + 1 &
            & .and. back%time == result%time .and. back%states == 3 .and. back%reduced == 2 &
            & .and. all(back%real_part == result%real_part) .and. sign(1.0_wp, &
            & back%real_part(2)) < 0.0_wp .and. all(back%imag_part == result%imag_part) &
            & .and. all(shape(back%reduced_matrix) == [2, 2]) .and. all(back%reduced_matrix &
            & == result%reduced_matrix) .and. all(shape(back%basis) == [3, 2]) &
            & .and. all(back%basis == result%basis) .and. all(back%independent == [1, 3]) &
            & .and. back%invariance == result%invariance .and. .not. back%invariant &
            & .and. back%zero_limit == result%zero_limit .and. back%zeros == 1, &
            & "the linear result read back differs")
        if (allocated(error)) return
        table%speed = [0.5_wp, 0.6_wp, 0.7_wp]
        table%real_part = reshape([-1.0_wp, 0.5_wp, -2.0_wp, 0.1_wp, -3.0_wp, -0.2_wp], [2, 3])
        table%imag_part = reshape([0.0_wp, 1.0_wp, 0.0_wp, 1.5_wp, 0.0_wp, 2.0_wp], [2, 3])
        table%struck = [.true., .false., .false., .true.]
        table%independent = [2, 4, 5, 7]
        table%deflations = 2
        changes(1) = stability_change_type(0.65_wp, .true., 1.75_wp, .true.)
        changes(2) = stability_change_type(0.55_wp, .false., 0.0_wp, .false.)
        writer = wire_writer_type()
        call pack_speed_table(writer, table, changes)
        bytes = writer%packed()
        reader = wire_reader_type()
        reader%bytes = bytes
        call unpack_speed_table(reader, table_back, changes_back)
        call check(error, .not. reader%failed .and. reader%at == len(bytes) + 1 .and. &
            & all(table_back%speed == table%speed) .and. all(shape(table_back%real_part) &
            & == [2, 3]) .and. all(table_back%real_part == table%real_part) .and. &
            & all(table_back%imag_part == table%imag_part) .and. all(table_back%struck .eqv. &
            & table%struck) .and. all(table_back%independent == table%independent) .and. &
            & table_back%deflations == 2 .and. size(changes_back) == 2, &
            & "the table against speed read back differs")
        if (allocated(error)) return
        call check(error, changes_back(1)%speed == 0.65_wp .and. changes_back(1)%oscillatory &
            & .and. changes_back(1)%frequency == 1.75_wp .and. changes_back(1)%stable_above &
            & .and. changes_back(2)%speed == 0.55_wp .and. .not. changes_back(2)%oscillatory &
            & .and. .not. changes_back(2)%stable_above, "the stability changes read back differ")
        if (allocated(error)) return
        reader = wire_reader_type()
        reader%bytes = bytes(:len(bytes) - 3)
        call unpack_speed_table(reader, table_back, changes_back)
        call check(error, reader%failed, "a table cut short was read")
    end subroutine test_linear_results

end module test_wire
