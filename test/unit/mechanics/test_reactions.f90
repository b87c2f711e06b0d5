! SPDX-License-Identifier: MIT
!> Reactions as columns (suite reactions, docs/outputs.md "Reactions"): the force and torque a
!> JOINT or JPRIM exerts on the part of its marker I, at I, in ground axes, against cases done
!> by hand: a pendulum's hinge force along the bar, m (g cos(theta) + L theta'^2), at every row;
!> parts held still against gravity by an ATPOINT at the centre of mass (m g up) and by a
!> FIXED joint off it (m g up and the torque that balances the weight's), each with marker I
!> on the part and on the ground (the ground then feels the opposite); and the row's sites that
!> share a part (its attitude made once a row) as each site alone. Datasets: test/reactions/,
!> data/bicycle.adm.
module test_reactions
    use, intrinsic :: iso_fortran_env, only : int64
    use, intrinsic :: ieee_arithmetic, only : ieee_value, ieee_quiet_nan, ieee_is_nan
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_text, only : to_text
    use rollcon_load, only : load_job
    use rollcon_job, only : job_type
    use rollcon_run_job, only : run_job, job_result_type
    use rollcon_simulation, only : history_type, status_completed
    use rollcon_adm_model, only : adm_model_type
    use rollcon_adm_reader, only : read_adm
    use rollcon_adm_build, only : build_adm_problem
    use rollcon_problem, only : problem_type
    use rollcon_reaction_watch, only : reaction_watch_type
    use rollcon_reactions, only : reaction_site_type, body_moment
    use rollcon_rotation, only : rotation_matrix, times, cross
    use rollcon_model, only : model_type
    use rollcon_constraint_matrix, only : constraint_matrix_type
    use rollcon_testing, only : unittest_type, new_unittest, check
    implicit none
    private

    public :: collect_reactions

    !> Gravity of the datasets [m/s^2]
    real(wp), parameter :: g = 9.81_wp

contains

    subroutine collect_reactions(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        tests = [new_unittest("pendulum-hinge-force-along-the-bar", test_pendulum), &
            & new_unittest("parts-held-against-gravity", test_held), &
            & new_unittest("force-requests-answered", test_force_requests), &
            & new_unittest("shared-part-sites-as-alone", test_shared_part)]
    end subroutine collect_reactions

    !> test/reactions/pendulum.adm: a bar of m = 2 kg, centre of mass L = 0.8 m below a REVOLUTE
    !> hinge at the origin about ground Y, released at rest at 70 degrees. Along the bar, from
    !> the centre of mass towards the hinge, Newton's law for the centre of mass on its circle:
    !> F - m g cos(theta) = m L theta'^2, so F = m (g cos(theta) + L theta'^2), theta from the
    !> downward vertical (cos(theta) = -Z/L, L theta' = |v|): joint1_fx, _fz (the hinge's force
    !> on the bar, marker I on it, at the hinge) at every row. The hinge holds the bar in its
    !> plane with no moment: joint1_tx ... _tz are rounding, and _fy is zero.
    subroutine test_pendulum(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: mass = 2.0_wp, length = 0.8_wp
        !> IDA at ERROR = 1e-10: the radial force within 2.7e-9 N of the closed form from the
        !> row's own state (forces up to 45 N; measured); 2e-8 catches a tenfold loss. The
        !> moments and the force out of the plane are rounding of 45 N times a metre (2.4e-13
        !> measured)
        real(wp), parameter :: tol_force = 2.0e-8_wp, tol_zero = 1.0e-10_wp
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: x, z, speed_squared, along
        integer :: k

        call run_dataset("test/reactions/pendulum.adm", result, rows, error)
        if (allocated(error)) return
        associate (layout => rows%layout)
            call check(error, rows%count == 601 .and. layout%column("joint1_fx") > 0 .and. &
                & layout%column("joint1_tz") == layout%column("joint1_fx") + 5, &
                & to_text(rows%count) // " rows, joint1_fx in column " &
                & // to_text(layout%column("joint1_fx")))
            if (allocated(error)) return
            do k = 1, rows%count
                x = rows%rows(layout%column("X_2"), k)
                z = rows%rows(layout%column("Z_2"), k)
                speed_squared = rows%rows(layout%column("Xdot_2"), k)**2 &
                    & + rows%rows(layout%column("Zdot_2"), k)**2
                along = -(x*rows%rows(layout%column("joint1_fx"), k) &
                    & + z*rows%rows(layout%column("joint1_fz"), k))/length
                call check(error, along, mass*(g*(-z/length) + speed_squared/length), &
                    & "the hinge's force along the bar at t = " // to_text(rows%rows(1, k)) &
                    & // " s [N]", abs_tol=tol_force)
                if (allocated(error)) return
                call check(error, maxval(abs([rows%rows(layout%column("joint1_fy"), k), &
                    & rows%rows(layout%column("joint1_tx"):layout%column("joint1_tz"), k)])) &
                    & <= tol_zero, "the hinge's force out of the plane or its moment at t = " &
                    & // to_text(rows%rows(1, k)) // " s is not zero")
                if (allocated(error)) return
            end do
        end associate
    end subroutine test_pendulum

    !> test/reactions/pendulum.adm's REQUEST/id, FORCE statements: REQUEST/1 names the hinge's
    !> markers in the joint's order, so req1_fx ... _tz are joint1_fx ... _tz to the bit;
    !> REQUEST/2 names them the other way round, the force on the ground at its marker: equal and
    !> opposite, its moment about J: -T - d x F, d = r_I - r_J the hinge's ATPOINT residual
    !> (F_1 ... F_3: I's origin from J's, ground axes; 1e-13 m here, as met by IDA), so the
    !> moment carried over is that of the joint's own gap. REQUEST/3 gives RM = MARKER/10 (on
    !> the ground, its x, y, z along ground -X, Z, Y: REULER 180D, 90D, 0D): REQUEST/1's
    !> force and torque in those fixed axes, A^T F; the dataset's warning names no REQUEST.
    subroutine test_force_requests(error)
        type(error_type), allocatable, intent(out) :: error
        type(job_result_type) :: result
        type(history_type) :: rows
        type(job_type) :: job
        character(len=*), parameter :: path = "test/reactions/pendulum.adm"
        !> The moment about J against -T - d x F: rounding of the markers' origins in ground
        !> (2e-16 m) times forces below 45 N, 1e-14 N m; the term d x F itself reaches 1.1e-12
        !> N m (measured), so a wrong sign is caught; a moment about the wrong point, 0.8 m off,
        !> by far
        real(wp), parameter :: tol_moment = 5.0e-14_wp
        !> REQUEST/3 against REQUEST/1 turned: rounding of 45 N (the axes' entries are cosines
        !> of right angles, 6e-17 off zero)
        real(wp), parameter :: tol_turned = 1.0e-13_wp
        real(wp) :: joint(6), first(6), second(6), gap(3), carried(3), turned(6), axes(3, 3)
        integer :: k

        ! MARKER/10's axes in ground: Rz(180 deg) Rx(90 deg) Rz(0)
        axes = reshape([-1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
            & 0.0_wp], [3, 3])
        call run_dataset(path, result, rows, error)
        if (allocated(error)) return
        associate (layout => rows%layout)
            call check(error, layout%column("req1_fx") > 0 .and. layout%column("req2_tz") > 0 &
                & .and. layout%column("req3_fx") > 0, "columns req1_fx " &
                & // to_text(layout%column("req1_fx")) // ", req2_tz " &
                & // to_text(layout%column("req2_tz")) // ", req3_fx " &
                & // to_text(layout%column("req3_fx")))
            if (allocated(error)) return
            do k = 1, rows%count
                joint = rows%rows(layout%column("joint1_fx"):layout%column("joint1_tz"), k)
                first = rows%rows(layout%column("req1_fx"):layout%column("req1_tz"), k)
                second = rows%rows(layout%column("req2_fx"):layout%column("req2_tz"), k)
                gap = [rows%rows(layout%column("F_1"), k), rows%rows(layout%column("F_2"), k), &
                    & rows%rows(layout%column("F_3"), k)]
                carried = [gap(2)*joint(3) - gap(3)*joint(2), gap(3)*joint(1) &
                    & - gap(1)*joint(3), gap(1)*joint(2) - gap(2)*joint(1)]
                ! the same numbers, and the force's negative: exact
                call check(error, all(first == joint) .and. all(second(1:3) == -joint(1:3)) &
                    & .and. all(abs(second(4:6) + joint(4:6) + carried) <= tol_moment), &
                    & "REQUEST/1 and /2 against JOINT/1 at t = " // to_text(rows%rows(1, k)) &
                    & // " s")
                if (allocated(error)) return
                turned = rows%rows(layout%column("req3_fx"):layout%column("req3_tz"), k)
                call check(error, turned, [matmul(transpose(axes), first(1:3)), &
                    & matmul(transpose(axes), first(4:6))], "REQUEST/3 (RM = MARKER/10) at t = " &
                    & // to_text(rows%rows(1, k)) // " s [N, N m]", abs_tol=tol_turned)
                if (allocated(error)) return
            end do
        end associate
        call load_job(path, job, error)
        if (allocated(error)) return
        call check(error, index(job%source%warning, "REQUEST") == 0, "the warning: " &
            & // job%source%warning)
    end subroutine test_force_requests

    !> test/reactions/held_parts.adm, four parts held still under gravity (-Z): JPRIM/1
    !> ATPOINT at PART/2's centre (3 kg), marker I on the part: (0, 0, m g) and no moment;
    !> JPRIM/2 the same on PART/3 (2 kg) with marker I on the ground: the ground is pushed down,
    !> (0, 0, -m g); JOINT/3 FIXED at I, 0.4 m along +X from PART/4's centre (1.5 kg), marker I
    !> on the part: (0, 0, m g) and, about I, the torque that balances the weight's moment
    !> there, (-0.4 X) x (-m g Z) = -0.4 m g Y: (0, 0.4 m g, 0); JOINT/4 the same on PART/5
    !> (2.5 kg) with marker I on the ground: (0, 0, -m g) and (0, -0.4 m g, 0). At every row.
    subroutine test_held(error)
        type(error_type), allocatable, intent(out) :: error
        !> A still state: the multipliers from the saddle-point solve, rounding of weights of
        !> 30 N (measured: exact to the last bit but for 1e-15)
        real(wp), parameter :: tol_still = 1.0e-10_wp
        character(len=*), parameter :: stems(4) = ["jprim1", "jprim2", "joint3", "joint4"]
        real(wp), parameter :: masses(4) = [3.0_wp, 2.0_wp, 1.5_wp, 2.5_wp], &
            & signs(4) = [1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp], arms(4) = [0.0_wp, 0.0_wp, &
            & 0.4_wp, 0.4_wp]
        type(job_result_type) :: result
        type(history_type) :: rows
        real(wp) :: expected(6)
        integer :: k, s

        call run_dataset("test/reactions/held_parts.adm", result, rows, error)
        if (allocated(error)) return
        associate (layout => rows%layout)
            do s = 1, size(stems)
                expected = signs(s)*[0.0_wp, 0.0_wp, masses(s)*g, 0.0_wp, &
                    & arms(s)*masses(s)*g, 0.0_wp]
                do k = 1, rows%count
                    call check(error, rows%rows(layout%column(trim(stems(s)) // "_fx"): &
                        & layout%column(trim(stems(s)) // "_tz"), k), expected, trim(stems(s)) &
                        & // "'s force and torque at t = " // to_text(rows%rows(1, k)) &
                        & // " s [N, N m]", abs_tol=tol_still)
                    if (allocated(error)) return
                end do
            end do
        end associate
        call check(error, index(result%summary%watch_lines, "JOINT/3 (line 28) 1.4715E+01 N, " &
            & // "5.8860E+00 N m") > 0, "the summary's largest reactions: " &
            & // result%summary%watch_lines)
    end subroutine test_held

    !> data/bicycle.adm at its initial state, each part's angles turned: the reaction watch makes
    !> each part's attitude once a row for all its sites (rollcon_reactions' part_attitude) and
    !> reads the sites' rows of C in place; every site's six columns must be, bit for bit, the
    !> wrench as the definition makes it for the site alone (reference_wrench), with the
    !> multipliers reported, and again with one multiplier NaN (a failed least-norm split):
    !> every site holding that row then NaN in all six, as the dense product makes it, the
    !> others unchanged. Several sites share a part there (checked: the sharing is what is
    !> tested).
    subroutine test_shared_part(error)
        type(error_type), allocatable, intent(out) :: error
        type(adm_model_type) :: adm
        type(problem_type), target :: problem
        real(wp), allocatable :: q0(:), u0(:), lambda(:), values(:), first(:)
        real(wp) :: alone(6)
        logical :: same, shared, holds
        integer :: k, i, nan_row, checked

        call read_adm("data/bicycle.adm", adm, error)
        if (allocated(error)) return
        call build_adm_problem(adm, problem=problem, q0=q0, u0=u0, error=error)
        if (allocated(error)) return
        call problem%prepare(error)
        if (allocated(error)) return
        ! every Euler angle turned off its start (many are 0 or a right angle there, whose sines
        ! and cosines would hide an attitude's wrong entry)
        do i = 1, size(q0)/6
            q0(6*i - 2:6*i) = q0(6*i - 2:6*i) + 0.1_wp*real(i, wp)*[0.3_wp, 0.2_wp, 0.7_wp]
        end do
        call problem%accelerations(0.0_wp, q0, u0, error)
        if (allocated(error)) return
        checked = 0
        do k = 1, size(problem%watches)
            select type (watch => problem%watches(k)%watch)
            type is (reaction_watch_type)
                allocate(lambda(problem%eq%nc))
                call problem%eq%reported_multipliers(problem%lambda, lambda, error)
                if (allocated(error)) return
                allocate(values(6*(size(watch%sites) + size(watch%request_sites))))
                call watch%fill_columns(problem%eq, 0.0_wp, q0, u0, lambda, values)
                first = values
                shared = .false.
                same = .true.
                do i = 1, size(watch%sites)
                    shared = shared .or. count(watch%site_part == watch%site_part(i)) > 1
                    alone = reference_wrench(problem%eq%model, watch%sites(i), problem%eq%c, &
                        & lambda, q0)
                    same = same .and. all(bits(values(6*i - 5:6*i)) == bits(alone))
                end do
                call check(error, size(watch%sites) > 1 .and. shared .and. same, &
                    & "bicycle: " // to_text(size(watch%sites)) // " sites, a part shared: " &
                    & // merge("yes", "no ", shared) // ", every site's columns as the site "&
                    & // "alone makes them: " // merge("yes", "no ", same))
                if (allocated(error)) return
                ! a multiplier of the first site's, NaN
                nan_row = watch%sites(1)%rows(1)
                lambda(nan_row) = ieee_value(1.0_wp, ieee_quiet_nan)
                call watch%fill_columns(problem%eq, 0.0_wp, q0, u0, lambda, values)
                same = .true.
                do i = 1, size(watch%sites)
                    holds = any(watch%sites(i)%rows == nan_row)
                    if (holds) then
                        same = same .and. all(ieee_is_nan(values(6*i - 5:6*i)))
                    else
                        same = same .and. all(bits(values(6*i - 5:6*i)) &
                            & == bits(first(6*i - 5:6*i)))
                    end if
                end do
                call check(error, same, "bicycle, multiplier " // to_text(nan_row) // " NaN: " &
                    & // "the sites holding its row not NaN in all six, or another site's " &
                    & // "columns changed")
                if (allocated(error)) return
                checked = checked + 1
            end select
        end do
        call check(error, checked == 1, "bicycle: " // to_text(checked) // " reaction watches")
    end subroutine test_shared_part

    !> A site's wrench as the definition gives it, each quantity made anew (docs/outputs.md,
    !> "Reactions"): the generalised forces sum_k lambda_k C(k, :) on the part's six coordinates
    !> (C's dense rows), the force their first three, the moment about the centre of mass
    !> R B^-T of the last three (R and B from the part's angles), about marker I for a JOINT or
    !> JPRIM (the opposite pair for marker I on the ground).
    pure function reference_wrench(model, site, c, lambda, q) result(wrench)
        type(model_type), intent(in) :: model
        type(reaction_site_type), intent(in) :: site
        type(constraint_matrix_type), intent(in) :: c
        real(wp), intent(in) :: lambda(:), q(:)
        real(wp) :: wrench(6)
        real(wp) :: generalised(6), row(6), rotation(3, 3), force(3), moment(3)
        integer :: i0, i

        i0 = 6*(site%part - 1)
        generalised = 0.0_wp
        do i = 1, size(site%rows)
            call c%gather(site%rows(i), i0 + 1, row)
            generalised = generalised + lambda(site%rows(i))*row
        end do
        rotation = rotation_matrix(q(i0 + 4), q(i0 + 5), q(i0 + 6))
        force = generalised(1:3)
        moment = times(rotation, body_moment(q(i0 + 5), q(i0 + 6), generalised(4:6)))
        if (site%at_marker) then
            associate (marker => model%statements(site%statement)%i)
                if (site%on_ground) then
                    moment = -(moment + cross(q(i0 + 1:i0 + 3) - marker%point, force))
                    force = -force
                else
                    moment = moment - cross(times(rotation, marker%point), force)
                end if
            end associate
        end if
        wrench(1:3) = force
        wrench(4:6) = moment
    end function reference_wrench

    !> The bits of each number (a comparison that tells -0 from 0 and compares NaNs).
    pure function bits(x) result(b)
        real(wp), intent(in) :: x(:)
        integer(int64) :: b(size(x))

        b = transfer(x, 0_int64, size(x))
    end function bits

    !> Run a dataset without files, its rows kept; a run that does not complete is an error.
    subroutine run_dataset(path, result, rows, error)
        character(len=*), intent(in) :: path
        type(job_result_type), intent(out) :: result
        type(history_type), intent(out) :: rows
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job

        call load_job(path, job, error)
        if (allocated(error)) return
        job%output_dir = ""
        job%quiet = .true.
        call run_job(job, result, error, rows)
        if (allocated(error)) return
        call check(error, result%summary%status == status_completed, path // ": status " &
            & // to_text(result%summary%status) // ": " // result%summary%watch_lines)
    end subroutine run_dataset

end module test_reactions
