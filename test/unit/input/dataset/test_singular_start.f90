! SPDX-License-Identifier: MIT
!> A dataset's part that starts at the Euler singularity (its CM marker's z-axis along ground
!> z) starts in its principal axes turned as a re-basing turns them (docs/rebasing.md): the
!> start in those axes, the model's part turned, the run counting one re-basing from its first
!> row, the pictures in the part's own axes; the same motion as the start written by hand with
!> the CM marker turned; a routine that depends on which axis is which refused.
module test_singular_start
    use rollcon_kinds, only : wp
    use rollcon_constants, only : pi
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix, rate_matrix, times
    use rollcon_rebasing, only : basis_turns, own_axes_rotation, rebased_inertia, chosen_turn, &
        & next_basis, turn_about_y
    use rollcon_output_layout, only : output_layout_type
    use rollcon_simulation, only : history_type, run_options_type, run_summary_type, simulate
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_run_record, only : run_record_type, read_run, pose
    use rollcon_part_shapes, only : ellipsoid_semi_axes
    use rollcon_output_files, only : write_text_file
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_state, only : part_state
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : make_folder, remove_folder
    use command_runs, only : rollcon_program, run_rollcon, file_text
    use singular_models, only : flat_ball, twin_ball, flat_body, twin_body, flat_disk, &
        & body_inertia, body_mass, body_rate
    implicit none
    private

    public :: collect_singular_start

    !> Scratch folder of the suite
    character(len=*), parameter :: scratch = "build/test_singular_start"
    !> Rounding of rotations and angular velocities built from angles of order pi [1]
    real(wp), parameter :: tol_maths = 1.0e-14_wp
    !> The ball against its hand-turned twin: two integrations of one motion in other
    !> coordinates (other steps, re-based at other times) at ERROR = 1e-10 over 5 s, so they
    !> differ by the integration error. Measured: centre 7.9e-9 m, its velocity 7.2e-9 m/s,
    !> the axes 2.5e-6; 2.5e-10 m, 3.0e-10 m/s and 1.3e-8 at ERROR = 1e-12. Each run's own error
    !> at 1e-10 (against its run at 1e-12) is up to 6.2e-8 m, 5.7e-8 m/s and 6.0e-6: the bounds
    !> are these, rounded up
    real(wp), parameter :: tol_ball_centre = 1.0e-7_wp, tol_ball_velocity = 1.0e-7_wp
    real(wp), parameter :: tol_ball_axes = 1.0e-5_wp
    !> The free body against its twin at ERROR = 1e-10 over 5 s (IDA; CVODE). Measured: centre
    !> 1.1e-11 m (8.5e-12), velocity 2.8e-12 m/s (1.6e-12), axes 9.9e-8 (7.2e-8); each run's
    !> own error (against ERROR = 1e-12): up to 1.4e-11 m (3.2e-10), 6.2e-12 m/s (5.9e-12),
    !> 1.5e-7 (3.8e-7). Bounds: those, rounded up
    real(wp), parameter :: tol_body_centre = 1.0e-9_wp, tol_body_velocity = 1.0e-10_wp
    real(wp), parameter :: tol_body_axes = 1.0e-6_wp
    !> The free body's changes, relative to their starting values: its energy (the column E,
    !> mostly m g Z and m v^2/2), its rotational energy and its angular momentum about the
    !> centre, from its own axes and moments. Measured (IDA; CVODE): 3.9e-10 (9.1e-10), 2.5e-8
    !> (4.2e-8), 4.7e-8 (1.1e-7), as the twin written by hand: 3.4e-10 (8.3e-10), 2.1e-8
    !> (3.7e-8), 6.4e-8 (1.1e-7); all thirty to forty times smaller at ERROR = 1e-12, so
    !> integration error. Bounds: about three times the largest
    real(wp), parameter :: tol_body_energy = 3.0e-9_wp, tol_body_spin_energy = 1.5e-7_wp
    real(wp), parameter :: tol_body_momentum = 3.0e-7_wp

contains

    !> Tests of this suite.
    subroutine collect_singular_start(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("start-in-turned-axes", test_start_state), &
            & new_unittest("problem-turned-and-run-twice", test_problem), &
            & new_unittest("ball-as-hand-turned", test_ball), &
            & new_unittest("free-body-ida", test_body_ida), &
            & new_unittest("free-body-cvode", test_body_cvode), &
            & new_unittest("axis-dependent-routine-refused", test_disk_refused)]
    end subroutine collect_singular_start

    !> part_state of a part whose CM marker's z-axis is along ground +Z (theta = 0) or -Z
    !> (theta = pi): the basis of the rule's turn, about y for omega'_cm = (8, 1, 2) (basis
    !> 20), the rotation R_cm T with theta = pi/2, and the angle rates of the body angular
    !> velocity T^T omega'_cm.
    subroutine test_start_state(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: markers(2) = [character(len=40) :: &
            & "MARKER/21, PART=2", "MARKER/21, PART=2, REULER=30D, 180D, 0D"]
        type(adm_model_type) :: adm
        real(wp) :: q(6), u(6), r_cm(3, 3), omega_cm(3), turn(3, 3)
        integer :: i, basis

        do i = 1, size(markers)
            call read_text("state", replaced(flat_body("IDA"), "MARKER/21, PART=2", &
                & trim(markers(i))), adm, error)
            if (allocated(error)) return
            call part_state(adm, adm%parts(2), q, u, basis)
            r_cm = rotation_matrix(30.0_wp*pi/180.0_wp*(i - 1), pi*(i - 1), 0.0_wp)
            ! WX, WY, WZ: the CM marker's components
            omega_cm = body_rate
            turn = basis_turns(:, :, turn_about_y)
            call check(error, chosen_turn(omega_cm) == turn_about_y .and. basis == 20 .and. &
                & abs(q(5) - 0.5_wp*pi) <= tol_maths, "basis " // to_text(basis) &
                & // ", theta " // to_text(q(5)))
            if (allocated(error)) return
            call check(error, reshape(rotation_matrix(q(4), q(5), q(6)), [9]), &
                & reshape(matmul(r_cm, turn), [9]), "R = R_cm T", abs_tol=tol_maths)
            if (allocated(error)) return
            call check(error, times(rate_matrix(q(5), q(6)), u(4:6)), &
                & matmul(transpose(turn), omega_cm), "omega' = T^T omega'_cm", &
                & abs_tol=tol_maths*norm2(body_rate))
            if (allocated(error)) return
            call check(error, [q(1:3), u(1:3)], [0.0_wp, 0.0_wp, 1.0_wp, 0.3_wp, 0.0_wp, &
                & 2.0_wp], "centre and its velocity", abs_tol=0.0_wp)
            if (allocated(error)) return
        end do
    end subroutine test_start_state

    !> build_adm_problem turns the part (its moments permuted) and records basis 20 (the rule's
    !> turn about y); a run counts the re-basing before its first row (basis_2 = 20), and a
    !> second run of the same problem from the same start gives the same rows.
    subroutine test_problem(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        type(run_options_type) :: options
        type(run_summary_type) :: first, second
        type(history_type) :: rows(2)
        real(wp), allocatable :: q0(:), u0(:)
        integer :: basis

        call read_text("problem", flat_body("IDA"), adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q0, u0=u0, error=error)
        if (allocated(error)) return
        call check(error, all(problem%start_bases == [20]) .and. all(problem%model%parts(1) &
            & %inertia == rebased_inertia(body_inertia, turn_about_y)), "start basis and moments")
        if (allocated(error)) return
        options%end_time = 1.0_wp
        options%output_step = 0.1_wp
        options%progress = .false.
        call simulate(problem, q0, u0, options, first, error, rows(1))
        if (allocated(error)) return
        call simulate(problem, q0, u0, options, second, error, rows(2))
        if (allocated(error)) return
        basis = rows(1)%layout%column("basis_2")
        call check(error, rows(1)%rows(basis, 1) == 20.0_wp .and. first%rebasings(1) >= 1 &
            & .and. all(second%rebasings == first%rebasings), "first basis " &
            & // to_text(rows(1)%rows(basis, 1)) // ", re-basings " &
            & // to_text(first%rebasings(1)) // " and " // to_text(second%rebasings(1)))
        if (allocated(error)) return
        call check(error, rows(2)%count == rows(1)%count .and. all(rows(2)%rows(:, &
            & :rows(2)%count) == rows(1)%rows(:, :rows(1)%count)), "the second run's rows")
    end subroutine test_problem

    !> The ball of data/ball_tumbling.adm with its CM marker's z-axis along ground z runs and
    !> follows its hand-turned twin: the same centre, velocity and axes on every row; basis 20
    !> (its spin axis, body x, the new z) from the first row and never re-based again; the
    !> twin re-based once, by the same turn; drawn in its own axes.
    subroutine test_ball(error)
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: flat, twin
        type(output_layout_type) :: layout
        type(run_record_type) :: record
        character(len=:), allocatable :: summary
        real(wp) :: centre, velocity, axes, drawn(6)
        integer :: basis, count_flat, count_twin

        call run_pair("ball", flat_ball(), twin_ball(), layout, flat, twin, summary, error)
        if (allocated(error)) return
        basis = layout%column("basis_2")
        count_flat = count(flat%rows(basis, 2:flat%count) /= flat%rows(basis, &
            & 1:flat%count - 1))
        count_twin = count(twin%rows(basis, 2:twin%count) /= twin%rows(basis, &
            & 1:twin%count - 1))
        call check(error, flat%rows(basis, 1) == 20.0_wp .and. twin%rows(basis, 1) == 0.0_wp &
            & .and. twin%rows(basis, twin%count) == 20.0_wp .and. count_flat == 0 .and. &
            & count_twin == 1 .and. index(summary, "re-basings of the principal axes " &
            & // "(docs/rebasing.md): part 2: 1 (0 about x, 1 about y)") > 0, &
            & "first bases " // to_text(flat%rows(basis, 1)) // ", " &
            & // to_text(twin%rows(basis, 1)) // "; changes " // to_text(count_flat) &
            & // ", " // to_text(count_twin) // "; summary: " // summary)
        if (allocated(error)) return
        call differences(layout, flat, twin, centre, velocity, axes)
        call check(error, centre <= tol_ball_centre .and. velocity <= tol_ball_velocity &
            & .and. axes <= tol_ball_axes, "the flat ball against its twin: centre " &
            & // to_text(centre) // " m, velocity " // to_text(velocity) // " m/s, axes " &
            & // to_text(axes))
        if (allocated(error)) return
        call read_run(scratch // "/flat/flat.adm.csv", record, error)
        if (allocated(error)) return
        drawn = pose(record, 1, 1)
        call check(error, reshape(rotation_matrix(drawn(4), drawn(5), drawn(6)), [9]), &
            & [1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp], &
            & "the first row drawn in the CM marker's axes (ground's)", abs_tol=tol_maths)
        if (allocated(error)) return
        call check(error, record%shapes(1)%semi_axes, [0.02_wp, 0.02_wp, 0.02_wp], &
            & "the ball's semi-axes [m]", rel_tol=tol_maths)
        call remove_folder(scratch)
    end subroutine test_ball

    subroutine test_body_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call check_body("IDA", error)
    end subroutine test_body_ida

    subroutine test_body_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call check_body("CVODE", error)
    end subroutine test_body_cvode

    !> The free body started at the singularity, in basis 20 (the rule's turn) to the end: its
    !> energy and its angular momentum about the centre kept (gravity alone acts, at the
    !> centre), the motion of its hand-turned twin, the .parts semi-axes those of the moments
    !> as written (along the CM marker's axes).
    subroutine check_body(formulation, error)
        character(len=*), intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        type(history_type) :: flat, twin
        type(output_layout_type) :: layout
        type(run_record_type) :: record
        character(len=:), allocatable :: summary, message
        real(wp) :: centre, velocity, axes, energy, spin_energy, momentum, expected(3)
        integer :: basis

        call run_pair("body", flat_body(formulation), twin_body(formulation), layout, flat, &
            & twin, summary, error)
        if (allocated(error)) return
        basis = layout%column("basis_2")
        ! spinning mostly about body x (omega' = (8, 1, 2) rad/s), started with that axis as
        ! its z (the rule's turn about y), which stays away from the vertical: no re-basing
        call check(error, all(flat%rows(basis, :flat%count) == 20.0_wp), "bases " &
            & // to_text(flat%rows(basis, 1)) // " to " // to_text(flat%rows(basis, flat%count)))
        if (allocated(error)) return
        call conservation(layout, flat, energy, spin_energy, momentum)
        call check(error, energy <= tol_body_energy .and. spin_energy <= tol_body_spin_energy &
            & .and. momentum <= tol_body_momentum, formulation // ": relative changes of the " &
            & // "energy " // to_text(energy) // ", the rotational energy " &
            & // to_text(spin_energy) // ", the angular momentum " // to_text(momentum))
        if (allocated(error)) return
        call differences(layout, flat, twin, centre, velocity, axes)
        call check(error, centre <= tol_body_centre .and. velocity <= tol_body_velocity &
            & .and. axes <= tol_body_axes, formulation // ": against the twin: centre " &
            & // to_text(centre) // " m, velocity " // to_text(velocity) // " m/s, axes " &
            & // to_text(axes))
        if (allocated(error)) return
        call read_run(scratch // "/flat/flat.adm.csv", record, error)
        if (allocated(error)) return
        call ellipsoid_semi_axes(body_mass, body_inertia, expected, message)
        call check(error, record%shapes(1)%semi_axes, expected, "semi-axes along the CM " &
            & // "marker's axes [m]", rel_tol=tol_maths)
        call remove_folder(scratch)
    end subroutine check_body

    !> The coin's disk lying flat at rest, served by the disk routine (body z its axle): the
    !> turned axes would make it another disk, so the dataset is refused naming the part and
    !> the UCON; at rest its F is 0 in any basis, so the test velocities find it.
    subroutine test_disk_refused(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: program, message
        integer :: status

        call rollcon_program(program, error)
        if (allocated(error)) return
        call make_folder(scratch)
        call write_text_file(scratch // "/disk.adm", flat_disk(), error)
        if (allocated(error)) return
        call run_rollcon(program, "run " // scratch // "/disk.adm -q -o " // scratch &
            & // "/disk", scratch // "/disk.out", scratch // "/disk.err", status)
        message = file_text(scratch // "/disk.err")
        call remove_folder(scratch)
        call check(error, status == 1 .and. index(message, scratch // "/disk.adm:4: PART/2: " &
            & // "the z-axis of its principal axes (its CM marker) is parallel to ground z at " &
            & // "t = 0") > 0 .and. index(message, "; but UCON/1 (line 9) gives F = ") > 0 .and. &
            & index(message, "test velocities added; allowed difference") > 0 .and. &
            & index(message, "its UCOSUB depends on which principal axis is which") > 0, &
            & "exit status " // to_text(status) // ": " // message)
    end subroutine test_disk_refused

    !> The largest differences over the rows of two runs of one motion, flat against twin:
    !> of the centre [m], of its velocity [m/s], and of the material axes [1] (the flat part's
    !> own axes R_own; the twin's own axes turned back, R_own Rx(pi/2)^T).
    subroutine differences(layout, flat, twin, centre, velocity, axes)
        type(output_layout_type), intent(in) :: layout
        type(history_type), intent(in) :: flat, twin
        real(wp), intent(out) :: centre, velocity, axes
        real(wp) :: a(12), b(12), twin_turn(3, 3)
        integer :: i

        twin_turn = rotation_matrix(0.0_wp, 0.5_wp*pi, 0.0_wp)
        centre = 0.0_wp
        velocity = 0.0_wp
        axes = 0.0_wp
        if (flat%count /= twin%count) centre = huge(1.0_wp)
        do i = 1, min(flat%count, twin%count)
            a = flat%part_state(1, i)
            b = twin%part_state(1, i)
            centre = max(centre, maxval(abs(a(1:3) - b(1:3))))
            velocity = max(velocity, maxval(abs(a(7:9) - b(7:9))))
            axes = max(axes, maxval(abs(own_axes(layout, flat, i) &
                & - matmul(own_axes(layout, twin, i), transpose(twin_turn)))))
        end do
    end subroutine differences

    !> The largest relative changes over the rows of the energy (the column E), of the
    !> rotational energy omega^T J omega/2 and of the angular momentum about the centre
    !> L = J omega, with J = R_own diag(I) R_own^T (omega in ground, I the moments as written,
    !> about the CM marker's axes R_own).
    subroutine conservation(layout, rows, energy, spin_energy, momentum)
        type(output_layout_type), intent(in) :: layout
        type(history_type), intent(in) :: rows
        real(wp), intent(out) :: energy, spin_energy, momentum
        real(wp) :: state(12), r_own(3, 3), omega(3), l(3), l0(3), e0, spin, spin0
        integer :: i

        energy = 0.0_wp
        spin_energy = 0.0_wp
        momentum = 0.0_wp
        e0 = rows%rows(layout%energy_column(), 1)
        do i = 1, rows%count
            state = rows%part_state(1, i)
            omega = times(rotation_matrix(state(4), state(5), state(6)), &
                & times(rate_matrix(state(5), state(6)), state(10:12)))
            r_own = own_axes(layout, rows, i)
            l = matmul(r_own, body_inertia*matmul(transpose(r_own), omega))
            spin = 0.5_wp*dot_product(omega, l)
            if (i == 1) then
                l0 = l
                spin0 = spin
            end if
            energy = max(energy, abs(rows%rows(layout%energy_column(), i) - e0)/abs(e0))
            spin_energy = max(spin_energy, abs(spin - spin0)/spin0)
            momentum = max(momentum, norm2(l - l0)/norm2(l0))
        end do
    end subroutine conservation

    !> The rotation of part 1's own axes (its CM marker's) in row i: the row's, turned back by
    !> its basis_<id>.
    function own_axes(layout, rows, i) result(r)
        type(output_layout_type), intent(in) :: layout
        type(history_type), intent(in) :: rows
        integer, intent(in) :: i
        real(wp) :: r(3, 3)
        real(wp) :: state(12)

        state = rows%part_state(1, i)
        r = own_axes_rotation(rotation_matrix(state(4), state(5), state(6)), &
            & nint(rows%rows(layout%column("basis_" // to_text(layout%part_ids(1))), i)))
    end function own_axes

    !> Run the program on two datasets (flat and twin) under scratch, each with -q -o; both
    !> must succeed; their rows, the layout (the same for both) and the flat run's summary.
    subroutine run_pair(tag, flat_text, twin_text, layout, flat, twin, summary, error)
        character(len=*), intent(in) :: tag, flat_text, twin_text
        type(output_layout_type), intent(out) :: layout
        type(history_type), intent(out) :: flat, twin
        character(len=:), allocatable, intent(out) :: summary
        type(error_type), allocatable, intent(out) :: error
        type(output_layout_type) :: twin_layout
        character(len=:), allocatable :: program
        integer :: status(2)

        call rollcon_program(program, error)
        if (allocated(error)) return
        call remove_folder(scratch)
        call make_folder(scratch)
        call write_text_file(scratch // "/flat.adm", flat_text, error)
        if (.not. allocated(error)) call write_text_file(scratch // "/twin.adm", twin_text, error)
        if (allocated(error)) return
        call run_rollcon(program, "run " // scratch // "/flat.adm -q -o " // scratch // "/flat", &
            & scratch // "/flat.out", scratch // "/flat.err", status(1))
        call run_rollcon(program, "run " // scratch // "/twin.adm -q -o " // scratch // "/twin", &
            & scratch // "/twin.out", scratch // "/twin.err", status(2))
        summary = file_text(scratch // "/flat/flat.adm.summary.txt")
        call check(error, all(status == 0), tag // ": exit statuses " // to_text(status(1)) &
            & // ", " // to_text(status(2)) // ": " // file_text(scratch // "/flat.err") &
            & // file_text(scratch // "/twin.err"))
        if (.not. allocated(error)) call read_output_csv(scratch // "/flat/flat.adm.csv", layout, &
            & flat, error)
        if (.not. allocated(error)) call read_output_csv(scratch // "/twin/twin.adm.csv", &
            & twin_layout, twin, error)
        if (allocated(error)) call remove_folder(scratch)
    end subroutine run_pair

    !> Write text as scratch/<tag>.adm and read it.
    subroutine read_text(tag, text, adm, error)
        character(len=*), intent(in) :: tag, text
        type(adm_model_type), intent(out) :: adm
        type(error_type), allocatable, intent(out) :: error

        call make_folder(scratch)
        call write_text_file(scratch // "/" // tag // ".adm", text, error)
        if (.not. allocated(error)) call read_adm(scratch // "/" // tag // ".adm", adm, error)
        call remove_folder(scratch)
    end subroutine read_text

    !> text with its first occurrence of old replaced by new.
    pure function replaced(text, old, new) result(changed)
        character(len=*), intent(in) :: text, old, new
        character(len=:), allocatable :: changed
        integer :: at

        at = index(text, old)
        changed = text(:at - 1) // new // text(at + len(old):)
    end function replaced

end module test_singular_start
