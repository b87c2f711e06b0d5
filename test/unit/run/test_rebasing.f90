! SPDX-License-Identifier: MIT
!> Re-basing a part's principal axes during a run (docs/rebasing.md): both turns keep the
!> physical state and the UCONs' F, and the rule turns the spin axis into the new z; a sphere
!> whose CM-marker axes tumble through theta = 0 every half turn is re-based once by the rule,
!> and, with the turn about x forced, carried through more than a hundred re-basings with the
!> trajectory and energy of the same sphere spinning about its body z, which is never
!> re-based, counted in the summary and marked in the CSV; the disk's routine, which takes
!> body z as the axle, is refused at a re-basing with the part, the UCON and the time named.
!> CVODE and IDA.
module test_rebasing
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_rotation, only : rotation_matrix, rate_matrix, times
    use rollcon_body, only : part_type, kinetic_energy
    use rollcon_rebasing, only : rebased_state, rebased_inertia, basis_turns, own_axes_rotation, &
        & turn_about_x, turn_about_y, chosen_turn, next_basis, basis_axes, turns_from_own
    use rollcon_problem, only : problem_type
    use rollcon_adm_model, only : adm_model_type
    use rollcon_rebase_step, only : compare_bases, basis_difference_type
    use rollcon_constraints, only : need_value
    use rollcon_simulation, only : run_summary_type, history_type, status_completed, &
        & status_failed, status_stopped
    use rollcon_summary_text, only : run_summary_text
    use rollcon_output_layout, only : output_layout_type, new_output_layout, read_layout, &
        & name_length, coord_x, coord_z, coord_xdot, coord_zdot, coord_theta
    use rollcon_csv_reader, only : read_output_csv
    use rollcon_output_files, only : delete_file
    use rollcon_run_record, only : run_record_type, pose
    use rollcon_watch_columns, only : contact_names
    use rollcon_testing, only : unittest_type, new_unittest, check
    use rebasing_models, only : run_dataset, build_dataset, tumbling_sphere, spinning_sphere, &
        & falling_disk, sphere_end, sphere_near_flat, users_disk
    implicit none
    private

    public :: collect_rebasing

    !> Round-off of a rotation matrix, angular velocity and energy recomputed through other
    !> Euler angles near the old singularity: a few eps, divided by sin(theta) >= 0.99 in the
    !> rates; 1e-14 relative to quantities of order one
    real(wp), parameter :: tol_maths = 1.0e-14_wp
    !> The fewest re-basings the tumbling sphere must go through (the issue's hundred; it
    !> turns about 32 times in 20 s, four re-basings a turn)
    integer, parameter :: least_rebasings = 100
    !> Centre trajectory of the tumbling sphere against the spinning one [m, m/s]: both are
    !> integrated at ERROR = 1e-10 (atol 1e-10) over 400 output rows of a uniform motion, and
    !> the re-initialisation restarts from the same state to round-off. The spinning sphere's
    !> angles move uniformly (integrated exactly); the tumbling one's rates reach
    !> |omega|/sin(0.05) = 200 rad/s near each re-basing, so local errors of ERROR times them
    !> give r 2e-8 = 1e-9 m/s of sideways velocity, 2e-8 m over 20 s (measured: CVODE 1.5e-8 m
    !> in Y, 2.1e-9 m/s in Ydot; IDA 2e-14). A rate recomputed wrongly is refused by the
    !> contract check; an inertia permuted wrongly changes the energy (checked below)
    real(wp), parameter :: tol_centre = 1.0e-7_wp
    !> Energy drift of each run (no applied force, rolling does no work): within the run's own
    !> bound (rollcon_drift) and below 1e-8 relative
    real(wp), parameter :: tol_energy = 1.0e-8_wp
    !> The rebased sphere's theta keeps away from flat: sin(theta) of every row at least
    !> sin(0.05 rad) (the datasets' threshold) less the integrator's crossing tolerance
    real(wp), parameter :: least_sin_theta = 0.049_wp
    !> The tumbling sphere's spin axis, its new z after the rule's re-basing, stays
    !> horizontal: |cos(theta)| the integration error of a steady spin at ERROR = 1e-10 over
    !> 20 s (a stable spin about the largest moment), far below 1e-6; a spin axis tilting
    !> away from the horizontal (a wrong turn of the moments) reaches 1e-2 within a turn
    real(wp), parameter :: tol_horizontal = 1.0e-6_wp

contains

    subroutine collect_rebasing(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))  ! silences gfortran -Wmaybe-uninitialized
        tests = [new_unittest("same-physical-state", test_same_state), &
            & new_unittest("turn-rule-and-bases", test_turn_rule), &
            & new_unittest("both-turns-keep-ucons-f", test_turns_keep_f), &
            & new_unittest("sphere-rule-rebases-once", test_sphere_rule), &
            & new_unittest("sphere-hundred-rebasings-ida", test_sphere_ida), &
            & new_unittest("sphere-hundred-rebasings-cvode", test_sphere_cvode), &
            & new_unittest("sphere-pushed-at-a-marker", test_sphere_pushed), &
            & new_unittest("disk-falls-ida", test_disk_ida), &
            & new_unittest("disk-falls-cvode", test_disk_cvode), &
            & new_unittest("users-axis-routine-refused", test_users_disk), &
            & new_unittest("start-below-threshold", test_start_below), &
            & new_unittest("basis-columns", test_basis_columns), &
            & new_unittest("pictures-own-axes", test_pictures_pose)]
    end subroutine collect_rebasing

    !> Near the singularity (theta = 0.04 rad, and pi - 0.04), by either turn, the new
    !> coordinates give the same rotation turned by T, the same angular velocity in ground, and
    !> with the permuted moments the same kinetic energy; the new theta is within 0.04 of pi/2;
    !> the own axes come back from the basis number of the turn.
    subroutine test_same_state(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: thetas(2) = [0.04_wp, 3.1_wp]
        real(wp) :: q_old(6), u_old(6), q_new(6), u_new(6), r_old(3, 3), r_new(3, 3)
        real(wp) :: omega_old(3), omega_new(3)
        type(part_type) :: old_part, new_part
        integer :: i, turn

        old_part = part_type(id=1, mass=2.0_wp, inertia=[0.3_wp, 0.5_wp, 0.7_wp])
        do turn = turn_about_x, turn_about_y
            new_part = part_type(id=1, mass=2.0_wp, inertia=rebased_inertia(old_part%inertia, &
                & turn))
            do i = 1, size(thetas)
                q_old = [0.1_wp, -0.2_wp, 0.3_wp, 7.0_wp, thetas(i), -13.0_wp]
                u_old = [0.4_wp, 0.5_wp, -0.6_wp, 1.3_wp, -0.7_wp, 2.9_wp]
                call rebased_state(q_old, u_old, q_new, u_new, turn)
                r_old = rotation_matrix(q_old(4), q_old(5), q_old(6))
                r_new = rotation_matrix(q_new(4), q_new(5), q_new(6))
                omega_old = times(r_old, times(rate_matrix(q_old(5), q_old(6)), u_old(4:6)))
                omega_new = times(r_new, times(rate_matrix(q_new(5), q_new(6)), u_new(4:6)))
                call check(error, reshape(r_new, [9]), reshape(matmul(r_old, &
                    & basis_turns(:, :, turn)), [9]), "R_new = R_old T", abs_tol=tol_maths)
                if (allocated(error)) return
                call check(error, reshape(own_axes_rotation(r_new, next_basis(0, turn)), [9]), &
                    & reshape(r_old, [9]), "the own axes' rotation from the turn's basis", &
                    & abs_tol=tol_maths)
                if (allocated(error)) return
                call check(error, omega_new, omega_old, "angular velocity in ground", &
                    & abs_tol=tol_maths*10.0_wp)
                if (allocated(error)) return
                call check(error, kinetic_energy(new_part, q_new, u_new), &
                    & kinetic_energy(old_part, q_old, u_old), "kinetic energy", &
                    & rel_tol=tol_maths)
                if (allocated(error)) return
                call check(error, [q_new(1:3), u_new(1:3)], [q_old(1:3), u_old(1:3)], &
                    & "centre and its velocity", abs_tol=0.0_wp)
                if (allocated(error)) return
                call check(error, abs(q_new(5) - 2.0_wp*atan(1.0_wp)) <= min(thetas(i), &
                    & 3.2_wp - thetas(i)) .and. abs(q_new(4) - q_old(4)) <= 4.0_wp*atan(1.0_wp) &
                    & .and. abs(q_new(6) - q_old(6)) <= 4.0_wp*atan(1.0_wp), "new theta " &
                    & // to_text(q_new(5)) // " near pi/2, psi " // to_text(q_new(4)) &
                    & // " and phi " // to_text(q_new(6)) // " within pi of the old ones")
                if (allocated(error)) return
            end do
        end do
    end subroutine test_same_state

    !> The rule: omega' mostly along body x makes old x the new z (a turn about y), mostly
    !> along body y or tied a turn about x (new z = old y); either way the new z is the old
    !> axis nearer omega, whose body component in the new basis is then omega'_z. The 24 bases:
    !> each number's axes distinct, a turn from basis b gives basis_axes(b) T, and
    !> turns_from_own's turns (at most 5, the diameter of the bases' graph) reach the basis
    !> they name.
    subroutine test_turn_rule(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: omegas(3, 3) = reshape([12.5_wp, 1.0_wp, -0.3_wp, &
            & 0.2_wp, -9.0_wp, 4.0_wp, 3.0_wp, -3.0_wp, 1.0_wp], [3, 3])
        integer, parameter :: expected(3) = [turn_about_y, turn_about_x, turn_about_x]
        real(wp) :: omega_new(3), axes(3, 3)
        integer :: i, b, c, turn, reached
        integer, allocatable :: turns(:)

        do i = 1, size(expected)
            turn = chosen_turn(omegas(:, i))
            omega_new = matmul(transpose(basis_turns(:, :, turn)), omegas(:, i))
            call check(error, turn == expected(i) .and. abs(omega_new(3)) &
                & == maxval(abs(omegas(1:2, i))), "omega' " // to_text(omegas(1, i)) // ", " &
                & // to_text(omegas(2, i)) // ": turn " // to_text(turn) // ", new omega'_z " &
                & // to_text(omega_new(3)))
            if (allocated(error)) return
        end do
        do b = 0, 23
            do c = 0, b - 1
                call check(error, maxval(abs(basis_axes(b) - basis_axes(c))) > 0.5_wp, &
                    & "bases " // to_text(b) // " and " // to_text(c) // " differ")
                if (allocated(error)) return
            end do
            do turn = turn_about_x, turn_about_y
                axes = matmul(basis_axes(b), basis_turns(:, :, turn))
                call check(error, maxval(abs(basis_axes(next_basis(b, turn)) - axes)) == 0.0_wp, &
                    & "basis " // to_text(b) // " turned by " // to_text(turn))
                if (allocated(error)) return
            end do
            turns = turns_from_own(b)
            reached = 0
            do i = 1, size(turns)
                reached = next_basis(reached, turns(i))
            end do
            call check(error, reached == b .and. size(turns) <= 5, "turns_from_own(" &
                & // to_text(b) // ") reaches " // to_text(reached))
            if (allocated(error)) return
        end do
        call check(error, next_basis(0, turn_about_x) == 1 .and. next_basis(0, turn_about_y) &
            & == 20 .and. next_basis(next_basis(next_basis(next_basis(0, turn_about_x), &
            & turn_about_x), turn_about_x), turn_about_x) == 0, "the numbers of the turns' bases")
    end subroutine test_turn_rule

    !> At the same physical state near flat, the UCONs' F of the rolling sphere (its three
    !> no-slip velocity UCONs, indifferent to the basis) are the same in the old basis and in
    !> the basis of either turn, with test velocities that make F non-zero; the disk's
    !> routine (body z its axle) gives another F after either turn, so the comparison can fail.
    subroutine test_turns_keep_f(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: sphere, disk
        type(basis_difference_type) :: found
        real(wp), allocatable :: q0(:), u0(:), q(:), u(:), q_new(:), u_new(:)
        integer :: turn

        call build_dataset("keep-f-sphere", tumbling_sphere("IDA"), adm, sphere, q0, u0, error)
        if (allocated(error)) return
        q = q0
        u = u0
        q(4:6) = [0.7_wp, 0.04_wp, -1.1_wp]
        u = [0.5_wp, -0.2_wp, 0.1_wp, 30.0_wp, 4.0_wp, -25.0_wp]
        do turn = turn_about_x, turn_about_y
            q_new = q
            u_new = u
            call rebased_state(q, u, q_new, u_new, turn)
            call sphere%eq%constraints%evaluate(sphere%model, 0.0_wp, q, u, need_value, error)
            if (allocated(error)) return
            call check(error, maxval(abs(sphere%eq%constraints%value)) > 0.1_wp, &
                & "the test velocities break the no-slip UCONs: F is not 0")
            if (allocated(error)) return
            call compare_bases(sphere, 1, 0.0_wp, q, u, q_new, u_new, turn, found, error)
            if (allocated(error)) return
            call check(error, found%k == 0, "turn " // to_text(turn) // ": UCON " &
                & // to_text(found%k) // " gives " // to_text(found%f_old) // " and " &
                & // to_text(found%f_new))
            if (allocated(error)) return
        end do
        call build_dataset("keep-f-disk", falling_disk("IDA"), adm, disk, q0, u0, error)
        if (allocated(error)) return
        q = q0
        u = u0
        q(5) = 0.04_wp
        u(4:6) = [0.3_wp, -0.5_wp, 2.0_wp]
        do turn = turn_about_x, turn_about_y
            q_new = q
            u_new = u
            call rebased_state(q, u, q_new, u_new, turn)
            call compare_bases(disk, 1, 0.0_wp, q, u, q_new, u_new, turn, found, error)
            if (allocated(error)) return
            call check(error, found%k > 0, "turn " // to_text(turn) // ": the disk's F "&
                & // "the same in the turned basis")
            if (allocated(error)) return
        end do
    end subroutine test_turns_keep_f

    !> The tumbling sphere (spin about body x, horizontal) by the rule: one re-basing, about
    !> y, its spin axis the new z, which stays horizontal to the end; the trajectory of the
    !> spinning sphere, never re-based.
    subroutine test_sphere_rule(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: tumbling, spinning
        type(history_type) :: tumbling_rows, spinning_rows
        real(wp), allocatable :: basis(:), theta(:)
        real(wp) :: distance
        integer :: c

        call run_dataset("tumbling-rule", tumbling_sphere("IDA"), tumbling, tumbling_rows, &
            & error)
        if (allocated(error)) return
        call run_dataset("spinning-rule", spinning_sphere("IDA"), spinning, spinning_rows, &
            & error)
        if (allocated(error)) return
        basis = tumbling_rows%column(tumbling_rows%layout%column("basis_2"))
        theta = tumbling_rows%part_values(1, coord_theta)
        call check(error, tumbling%status == status_completed .and. tumbling%rebasings(1) == 1 &
            & .and. basis(tumbling_rows%count) == 20.0_wp .and. maxval(abs(cos(theta)), &
            & mask=basis == 20.0_wp) <= tol_horizontal, "status " // to_text(tumbling%status) &
            & // ", re-basings " // to_text(tumbling%rebasings(1)) // ", last basis " &
            & // to_text(basis(tumbling_rows%count)) // ", largest cos(theta) in basis 20 " &
            & // to_text(maxval(abs(cos(theta)), mask=basis == 20.0_wp)))
        if (allocated(error)) return
        distance = 0.0_wp
        do c = coord_x, coord_z
            distance = max(distance, maxval(abs(tumbling_rows%part_values(1, c) &
                & - spinning_rows%part_values(1, c))))
        end do
        call check(error, distance, 0.0_wp, "largest difference of the centres [m]", &
            & abs_tol=tol_centre)
    end subroutine test_sphere_rule

    subroutine test_sphere_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call sphere_against_reference("IDA", error)
    end subroutine test_sphere_ida

    subroutine test_sphere_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call sphere_against_reference("CVODE", error)
    end subroutine test_sphere_cvode

    !> Pushed at a point fixed in it after its first re-basing, the tumbling sphere still
    !> follows the spinning one: the force's marker was turned with the axes, about y by the
    !> rule (one re-basing), and about x at each of the re-basings when that turn is forced.
    subroutine test_sphere_pushed(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: tumbling, spinning
        type(history_type) :: tumbling_rows, spinning_rows
        real(wp) :: distance
        integer :: forced

        call run_dataset("spinning-pushed", spinning_sphere("IDA", pushed=.true.), spinning, &
            & spinning_rows, error)
        if (allocated(error)) return
        do forced = 0, turn_about_x
            call run_dataset("tumbling-pushed", tumbling_sphere("IDA", pushed=.true.), &
                & tumbling, tumbling_rows, error, rebase_turn=forced)
            if (allocated(error)) return
            call check(error, tumbling%status == status_completed .and. spinning%status &
                & == status_completed .and. (forced == 0 .and. tumbling%rebasings(1) == 1 &
                & .or. forced == turn_about_x .and. tumbling%rebasings(1) >= least_rebasings), &
                & "both runs complete, statuses " // to_text(tumbling%status) // " and " &
                & // to_text(spinning%status) // ", re-basings " &
                & // to_text(tumbling%rebasings(1)))
            if (allocated(error)) return
            ! the push changed the speed: the runs would agree without it, trivially
            call check(error, abs(spinning%u(1) - 0.5_wp) > 1.0e-3_wp, "the push changed the " &
                & // "speed to " // to_text(spinning%u(1)) // " m/s")
            if (allocated(error)) return
            distance = maxval(abs(tumbling_rows%part_values(1, coord_x) &
                & - spinning_rows%part_values(1, coord_x)))
            call check(error, distance, 0.0_wp, "largest difference of the centres' X [m]", &
                & abs_tol=tol_centre)
            if (allocated(error)) return
        end do
    end subroutine test_sphere_pushed

    !> The tumbling sphere, its turn about x forced (the rule would re-base it once), re-based
    !> at least least_rebasings times, against the spinning one (never re-based): the same
    !> centre trajectory, energy conserved, the count in the summary and its text, the basis
    !> column of the CSV stepping through the turn's bases 0, 1, 2, 3.
    subroutine sphere_against_reference(formulation, error)
        character(len=*), intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: tumbling, spinning
        type(history_type) :: tumbling_rows, spinning_rows
        character(len=:), allocatable :: csv_path, text
        real(wp) :: distance
        integer :: c

        csv_path = "build/rebasing-sphere-" // formulation // ".csv"
        call run_dataset("tumbling", tumbling_sphere(formulation), tumbling, tumbling_rows, &
            & error, csv_path, rebase_turn=turn_about_x)
        if (allocated(error)) return
        call run_dataset("spinning", spinning_sphere(formulation), spinning, spinning_rows, error)
        if (allocated(error)) return
        call check(error, tumbling%status == status_completed .and. spinning%status &
            & == status_completed .and. tumbling%t_reached == sphere_end &
            & .and. tumbling_rows%count == spinning_rows%count, "both runs complete, statuses " &
            & // to_text(tumbling%status) // " and " // to_text(spinning%status))
        if (allocated(error)) return
        ! every stretch between re-basings takes steps: the counters are summed over them
        call check(error, tumbling%rebasings(1) >= least_rebasings .and. spinning%rebasings(1) &
            & == 0 .and. tumbling%steps > tumbling%rebasings(1), "re-basings " &
            & // to_text(tumbling%rebasings(1)) // " and " // to_text(spinning%rebasings(1)) &
            & // ", steps " // to_text(tumbling%steps))
        if (allocated(error)) return
        distance = 0.0_wp
        do c = coord_x, coord_z
            distance = max(distance, maxval(abs(tumbling_rows%part_values(1, c) &
                & - spinning_rows%part_values(1, c))))
        end do
        do c = coord_xdot, coord_zdot
            distance = max(distance, maxval(abs(tumbling_rows%part_values(1, c) &
                & - spinning_rows%part_values(1, c))))
        end do
        call check(error, distance, 0.0_wp, "largest difference of the centres' positions " &
            & // "and velocities [m, m/s]", abs_tol=tol_centre)
        if (allocated(error)) return
        call check(error, minval(abs(sin(tumbling_rows%part_values(1, coord_theta)))) &
            & >= least_sin_theta, "the tumbling sphere's theta kept away from flat")
        if (allocated(error)) return
        call check(error, tumbling%energy_drift <= tumbling%energy_bound .and. &
            & max(tumbling%energy_drift, spinning%energy_drift) <= tol_energy, &
            & "energy drifts " // to_text(tumbling%energy_drift) // " and " &
            & // to_text(spinning%energy_drift))
        if (allocated(error)) return
        call check(error, tumbling%energy_reference, spinning%energy_reference, &
            & "the two runs' energies [J]", rel_tol=tol_energy)
        if (allocated(error)) return
        text = run_summary_text("tumbling sphere", csv_path, tumbling)
        call check(error, index(text, "re-basings of the principal axes (docs/rebasing.md): " &
            & // "part 2: " // to_text(tumbling%rebasings(1)) // " (" &
            & // to_text(tumbling%rebasings(1)) // " about x, 0 about y)" // new_line("a")) > 0, &
            & "the summary text counts the re-basings: " // text)
        if (allocated(error)) return
        call check_basis_column(csv_path, tumbling%rebasings(1), error)
    end subroutine sphere_against_reference

    !> The CSV's basis_2 column of a part turned about x alone: 0 in the first row, the count
    !> modulo 4 in the last, each change one turn on (at most one re-basing between rows).
    subroutine check_basis_column(csv_path, count, error)
        character(len=*), intent(in) :: csv_path
        integer, intent(in) :: count
        type(error_type), allocatable, intent(out) :: error
        type(output_layout_type) :: layout
        type(history_type) :: rows
        type(error_type), allocatable :: delete_error
        character(len=name_length), allocatable :: names(:)
        real(wp), allocatable :: basis(:)

        call read_output_csv(csv_path, layout, rows, error)
        call delete_file(csv_path, delete_error)
        if (allocated(error)) return
        ! the theta watch's column right after the multipliers (the reactions' come last)
        call check(error, layout%column("basis_2") &
            & == layout%multiplier_column(size(layout%ucon_ids)) + 1, &
            & "the basis column follows the multipliers")
        if (allocated(error)) return
        names = layout%header()
        basis = rows%column(layout%column("basis_2"))
        call check(error, names(layout%column("basis_2")) == "basis_2" .and. basis(1) == 0.0_wp &
            & .and. basis(size(basis)) == real(modulo(count, 4), wp) .and. all(basis(2:) == &
            & basis(:size(basis) - 1) .or. basis(2:) == modulo(basis(:size(basis) - 1) + 1, &
            & 4.0_wp)), "basis_2 from 0 to " // to_text(modulo(count, 4)) // ", got " &
            & // names(layout%column("basis_2")) // " from " // to_text(basis(1)) // " to " &
            & // to_text(basis(size(basis))))
    end subroutine check_basis_column

    subroutine test_disk_ida(error)
        type(error_type), allocatable, intent(out) :: error

        call disk_falls("IDA", error)
    end subroutine test_disk_ida

    subroutine test_disk_cvode(error)
        type(error_type), allocatable, intent(out) :: error

        call disk_falls("CVODE", error)
    end subroutine test_disk_cvode

    !> The disk falls flat; at the theta limit its built-in routine, a contact about body z
    !> (its axle), gives another F in the turned basis: the disk lies on the ground, a state
    !> the model cannot pass. The run stops there, never re-based (status stopped, limit
    !> "fall"), saying what fell, when, its tilt and height, and the UCON; the rows up to the
    !> limit stay, the last at sin(theta) = sin(0.05).
    subroutine disk_falls(formulation, error)
        character(len=*), intent(in) :: formulation
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary
        type(history_type) :: rows
        character(len=:), allocatable :: expected

        call run_dataset("disk", falling_disk(formulation), summary, rows, error)
        if (allocated(error)) return
        expected = "part 2 fell: it lies flat at t = " // to_text(summary%t_reached) &
            & // " s, its principal z-axis "
        call check(error, summary%status == status_stopped .and. summary%limit == "fall" &
            & .and. summary%t_reached < 3.0_wp .and. summary%rebasings(1) == 0 .and. &
            & index(summary%message, expected) == 1 .and. index(summary%message, &
            & " (disk), a contact about that axis") > 0, "stopped at the fall with the " &
            & // "part, its tilt and height and the UCON; got status " &
            & // to_text(summary%status) // ": " // summary%message)
        if (allocated(error)) return
        call check(error, sin(summary%q(5)), sin(0.05_wp), "sin(theta) at the stop", &
            & abs_tol=1.0e-6_wp)
    end subroutine disk_falls

    !> The same disk served by a user's routine (the model's UCOSUB, no built-in one): rollcon
    !> cannot tell a contact about body z from a routine that breaks the contract, so the run
    !> fails there, never re-based, naming part 2, the UCON and the time, and saying both.
    subroutine test_users_disk(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary
        type(history_type) :: rows
        character(len=:), allocatable :: expected
        type(error_type), allocatable :: refused

        call run_dataset("users-disk", falling_disk("IDA", ""), summary, rows, refused, &
            & default_ucosub=users_disk)
        expected = "part 2: its principal axes cannot be re-based at t = " &
            & // to_text(summary%t_reached) // " s (theta = "
        ! a failure: the run cannot go on as asked; simulate returns the error, and the rows up
        ! to the limit stay
        call check(error, allocated(refused), "the run was not refused")
        if (allocated(error)) return
        call check(error, summary%status == status_failed .and. summary%t_reached < 3.0_wp &
            & .and. summary%rebasings(1) == 0 .and. index(refused%message, expected) == 1 &
            & .and. index(refused%message, "): UCON/2 (line 10) gives") > 0 .and. &
            & index(refused%message, &
            & "its UCOSUB depends on which principal axis is which") > 0 .and. &
            & index(refused%message, "the model fell") > 0 &
            & .and. summary%message == refused%message, &
            & "failed at the re-basing with the part, UCON and time; got status " &
            & // to_text(summary%status) // ": " // refused%message)
        if (allocated(error)) return
        call check(error, sin(summary%q(5)), sin(0.05_wp), "sin(theta) at the stop", &
            & abs_tol=1.0e-6_wp)
    end subroutine test_users_disk

    !> A sphere starting 2 degrees from flat, spinning about body x, is re-based before its
    !> first row: that row is in basis 20 (the rule's turn about y), its theta near pi/2, its
    !> centre and energy the start's, and it rolls on.
    subroutine test_start_below(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_summary_type) :: summary
        type(history_type) :: rows
        real(wp), allocatable :: basis(:), theta(:), x(:)

        call run_dataset("near-flat", sphere_near_flat("IDA"), summary, rows, error)
        if (allocated(error)) return
        basis = rows%column(rows%layout%column("basis_" // to_text(rows%layout%part_ids(1))))
        theta = rows%part_values(1, coord_theta)
        x = rows%part_values(1, coord_x)
        call check(error, summary%status == status_completed .and. basis(1) == 20.0_wp &
            & .and. abs(cos(theta(1))) <= sin(0.05_wp) .and. summary%rebasings(1) >= 1, &
            & "status " // to_text(summary%status) // ", first basis " // to_text(basis(1)) &
            & // ", first theta " // to_text(theta(1)))
        if (allocated(error)) return
        call check(error, x(rows%count), 0.5_wp, "X after 1 s at 0.5 m/s [m]", &
            & abs_tol=tol_centre)
    end subroutine test_start_below

    !> The pictures draw a part in its own axes from a re-based row: the pose of a row in
    !> basis 1 or 20 (a turn about x or y) has the rotation of the state before the re-basing.
    subroutine test_pictures_pose(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run
        real(wp) :: q_old(6), u_old(6), q_new(6), u_new(6), drawn(6)
        integer :: turn

        q_old = [0.1_wp, -0.2_wp, 0.3_wp, 7.0_wp, 0.04_wp, -13.0_wp]
        u_old = [0.4_wp, 0.5_wp, -0.6_wp, 1.3_wp, -0.7_wp, 2.9_wp]
        do turn = turn_about_x, turn_about_y
            call rebased_state(q_old, u_old, q_new, u_new, turn)
            run = run_record_type()
            run%layout = new_output_layout([4], [integer ::], ["basis_4"])
            run%history%layout = run%layout
            call run%history%add([0.0_wp, q_new, u_new, 1.0_wp, &
                & real(next_basis(0, turn), wp)])
            drawn = pose(run, 1, 1)
            call check(error, reshape(rotation_matrix(drawn(4), drawn(5), drawn(6)), [9]), &
                & reshape(rotation_matrix(q_old(4), q_old(5), q_old(6)), [9]), &
                & "the drawn rotation is the own axes'", abs_tol=tol_maths)
            if (allocated(error)) return
            call check(error, drawn(1:3), q_old(1:3), "the drawn centre", abs_tol=0.0_wp)
            if (allocated(error)) return
        end do
    end subroutine test_pictures_pose

    !> The basis columns close the header, after the contact columns, and read back.
    subroutine test_basis_columns(error)
        type(error_type), allocatable, intent(out) :: error
        type(output_layout_type) :: layouts(2), read_back
        character(len=name_length), allocatable :: names(:)
        character(len=:), allocatable :: message
        integer :: i

        layouts = [new_output_layout([2, 5], [11, 12], [character(len=name_length) :: &
            & "basis_2", "basis_5"]), new_output_layout([1], [1, 2, 3], &
            & [character(len=name_length) :: contact_names, "basis_1"])]
        do i = 1, size(layouts)
            names = layouts(i)%header()
            call check(error, names(size(names)) == "basis_" &
                & // to_text(layouts(i)%part_ids(size(layouts(i)%part_ids))) &
                & .and. size(names) == layouts(i)%columns(), "basis columns last: " &
                & // names(size(names)))
            if (allocated(error)) return
            call read_layout(names, read_back, message)
            if (allocated(message)) then
                call check(error, .false., "read_layout: " // message)
                return
            end if
            call check(error, all(read_back%extra == layouts(i)%extra) &
                & .and. all(read_back%part_ids == layouts(i)%part_ids) &
                & .and. all(read_back%ucon_ids == layouts(i)%ucon_ids), "layout read back")
            if (allocated(error)) return
        end do
    end subroutine test_basis_columns

end module test_rebasing
