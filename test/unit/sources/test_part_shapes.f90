! SPDX-License-Identifier: MIT
!> Tests of the parts' shapes in the pictures: the inertia ellipsoid against its formulas, the
!> shapes of a model built in code, the .parts file (round trip, refusals with their exact
!> messages, a file that does not match its CSV), the disk scene's fallback without one, and
!> the ellipsoid mesh.
module test_part_shapes
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type
    use rollcon_body, only : part_type
    use rollcon_model, only : model_type
    use rollcon_rotation, only : rotation_matrix
    use rollcon_part_shapes, only : part_shape_type, ellipsoid_semi_axes, part_shapes_of, &
        & write_model_shapes, read_part_shapes, write_part_shapes, parts_path, shape_disk, &
        & shape_ellipsoid
    use rollcon_run_record, only : run_record_type, read_run
    use rollcon_ellipsoid_mesh, only : ellipsoid_points, ellipsoid_triangle, &
        & ellipsoid_point_count, ellipsoid_triangle_count
    use rollcon_problem, only : problem_type
    use rollcon_ucosub_contract, only : ucosub_interface
    use rollcon_job, only : job_type
    use rollcon_load, only : load_job
    use rollcon_testing, only : unittest_type, new_unittest, check
    use picture_files, only : disk_run, two_part_run, write_run, make_folder, remove_folder, &
        & write_lines, disk_radius, disk_thickness
    implicit none
    private

    public :: collect_part_shapes

    !> Scratch folder of the suite, removed by every test that makes it
    character(len=*), parameter :: scratch = "build/test_part_shapes"
    !> Semi-axes from exactly representable moments: a few roundings of sqrt(5 s/(2 m))
    real(wp), parameter :: tol_axes = 4.0_wp*epsilon(1.0_wp)
    !> The disk-like ellipsoid's c comes from 2 A - C = m h^2/6, a difference of terms
    !> 3 R^2/h^2 (about 3.3e3) times larger: that many roundings, halved by the square root
    real(wp), parameter :: tol_thin_axis = 1.0e4_wp*epsilon(1.0_wp)
    !> Mesh points of a unit-scale ellipsoid on its surface and round its centre: roundings of
    !> a rotation and a few trigonometric values
    real(wp), parameter :: tol_mesh = 1.0e-14_wp
    !> The .parts file carries 17 significant digits: values read back are the values written
    real(wp), parameter :: tol_exact = 0.0_wp

contains

    !> Tests of this suite.
    subroutine collect_part_shapes(tests)
        type(unittest_type), allocatable, intent(out) :: tests(:)

        allocate(tests(0))
        tests = [new_unittest("ellipsoid-of-a-sphere", test_sphere), &
            & new_unittest("ellipsoid-of-a-thin-disk", test_thin_disk), &
            & new_unittest("ellipsoid-refuses-non-physical", test_refusals), &
            & new_unittest("shapes-of-a-model", test_model_shapes), &
            & new_unittest("wheels-of-a-dataset", test_wheels), &
            & new_unittest("parts-file-round-trip", test_round_trip), &
            & new_unittest("parts-file-refusals", test_file_refusals), &
            & new_unittest("parts-file-must-match-csv", test_mismatch), &
            & new_unittest("disk-csv-without-parts-file", test_fallback), &
            & new_unittest("model-csv-without-parts-file", test_missing_parts), &
            & new_unittest("ellipsoid-mesh-on-surface", test_mesh)]
    end subroutine collect_part_shapes

    !> A solid sphere, I = 2/5 m r^2 about every axis, is the ellipsoid a = b = c = r.
    subroutine test_sphere(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: mass = 2.0_wp, r = 0.25_wp
        character(len=:), allocatable :: message
        real(wp) :: axes(3)

        call ellipsoid_semi_axes(mass, spread(0.4_wp*mass*r**2, 1, 3), axes, message)
        call check(error, .not. allocated(message), "a sphere refused")
        if (allocated(error)) return
        call check(error, axes, [r, r, r], "semi-axes of a sphere of radius 0.25 m", &
            & rel_tol=tol_axes)
    end subroutine test_sphere

    !> The paper's disk, A = m (3 R^2 + h^2)/12 about a diameter and C = m R^2/2 about its axis:
    !> a = b = sqrt(5/4) R in its plane and c = sqrt(5/12) h along its axis.
    subroutine test_thin_disk(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: mass = 0.7351_wp, r = 0.1_wp, h = 0.003_wp
        character(len=:), allocatable :: message
        real(wp) :: axes(3), a, c

        a = mass*(3.0_wp*r**2 + h**2)/12.0_wp
        c = mass*r**2/2.0_wp
        call ellipsoid_semi_axes(mass, [a, a, c], axes, message)
        call check(error, .not. allocated(message), "the paper's disk refused")
        if (allocated(error)) return
        call check(error, axes(1:2), spread(sqrt(1.25_wp)*r, 1, 2), "in-plane semi-axes", &
            & rel_tol=tol_axes)
        if (allocated(error)) return
        call check(error, axes(3), sqrt(5.0_wp/12.0_wp)*h, "semi-axis along the disk axis", &
            & rel_tol=tol_thin_axis)
    end subroutine test_thin_disk

    !> No mass, a moment that is not positive, or one beyond the sum of the other two.
    subroutine test_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: message
        real(wp) :: axes(3)

        call ellipsoid_semi_axes(0.0_wp, [1.0_wp, 1.0_wp, 1.0_wp], axes, message)
        call expect_text(error, message, "the mass must be a positive number of kg, got 0")
        if (allocated(error)) return
        call ellipsoid_semi_axes(1.0_wp, [1.0_wp, -1.0_wp, 1.0_wp], axes, message)
        call expect_text(error, message, "the principal moments must be positive [kg m^2], " &
            & // "got (1, -1, 1)")
        if (allocated(error)) return
        call ellipsoid_semi_axes(1.0_wp, [1.0_wp, 1.0_wp, 2.5_wp], axes, message)
        call expect_text(error, message, "the principal moments (1, 1, 2.5) kg m^2 are not " &
            & // "those of a rigid body: I3 = 2.5 exceeds the sum of the other two")
    end subroutine test_refusals

    !> A model built in code: part 1 the disk of a disk scene, part 7 a sphere drawn as its
    !> ellipsoid; a part of impossible inertia is refused with its id.
    subroutine test_model_shapes(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(part_shape_type), allocatable :: shapes(:)

        call model%add_part(part_type(id=1, mass=0.7_wp, inertia=[1.0_wp, 1.0_wp, 1.5_wp]))
        call model%add_part(part_type(id=7, mass=2.0_wp, inertia=0.05_wp))
        call part_shapes_of(model, shapes, error, disk_radius=0.1_wp, disk_thickness=0.003_wp)
        if (allocated(error)) return
        call check(error, size(shapes) == 2 .and. all(shapes%id == [1, 7]) .and. &
            & shapes(1)%kind == shape_disk .and. shapes(2)%kind == shape_ellipsoid .and. &
            & shapes(1)%radius == 0.1_wp .and. shapes(1)%thickness == 0.003_wp, &
            & "part 1 the disk, part 7 an ellipsoid")
        if (allocated(error)) return
        call check(error, shapes(2)%semi_axes, spread(0.25_wp, 1, 3), "part 7: a sphere of " &
            & // "2 kg and 0.05 kg m^2 has radius 0.25 m", rel_tol=tol_axes)
        if (allocated(error)) return
        model%parts(1)%inertia = [1.0_wp, 1.0_wp, 2.5_wp]
        call part_shapes_of(model, shapes, error)
        call expect_error(error, "part 1: the principal moments (1, 1, 2.5) kg m^2 are not " &
            & // "those of a rigid body: I3 = 2.5 exceeds the sum of the other two")
    end subroutine test_model_shapes

    !> A part that a disk routine holds on the ground is drawn as a disk of the routine's
    !> radius: data/bicycle.adm's wheels (rolling_disk and disk_height, R = 0.3 and 0.35 m; a
    !> rim's moments, so the thickness is capped at R/10) between the frames' ellipsoids;
    !> data/disk_height.adm's coin (rolling_disk), whose moments are a uniform disk's 3 mm
    !> thick; data/coin.adm's coin stays its ellipsoid: its UCONs name no routine, and the
    !> model's UCOSUB (--ucosub) may be any.
    subroutine test_wheels(error)
        type(error_type), allocatable, intent(out) :: error
        type(part_shape_type), allocatable :: shapes(:)

        call dataset_shapes("data/bicycle.adm", shapes, error)
        if (allocated(error)) return
        call check(error, size(shapes) == 4 .and. all(shapes%kind == [shape_disk, &
            & shape_ellipsoid, shape_ellipsoid, shape_disk]), "the bicycle: disks, ellipsoids, " &
            & // "disk expected")
        if (allocated(error)) return
        call check(error, [shapes(1)%radius, shapes(1)%thickness, shapes(4)%radius, &
            & shapes(4)%thickness], [0.3_wp, 0.03_wp, 0.35_wp, 0.035_wp], "the wheels' radii " &
            & // "and thicknesses [m]", rel_tol=tol_axes)
        if (allocated(error)) return
        call dataset_shapes("data/coin.adm", shapes, error)
        if (allocated(error)) return
        call check(error, shapes(1)%kind == shape_ellipsoid, "data/coin.adm: an ellipsoid " &
            & // "expected")
        if (allocated(error)) return
        call dataset_shapes("data/disk_height.adm", shapes, error)
        if (allocated(error)) return
        ! h^2 = 12 A/m - 3 R^2 is 9e-6 m^2 out of terms of 0.03: 3e3 roundings, halved by the root
        call check(error, shapes(1)%kind == shape_disk .and. abs(shapes(1)%radius - 0.1_wp) &
            & <= tol_axes .and. abs(shapes(1)%thickness - 0.003_wp) <= tol_thin_axis*0.003_wp, &
            & "the coin: a disk 0.1 m by 3 mm expected")
    end subroutine test_wheels

    !> The part shapes of a dataset's model as a run gives them.
    subroutine dataset_shapes(path, shapes, error)
        character(len=*), intent(in) :: path
        type(part_shape_type), allocatable, intent(out) :: shapes(:)
        type(error_type), allocatable, intent(out) :: error
        type(job_type) :: job
        type(problem_type), target :: problem
        procedure(ucosub_interface), pointer :: routine
        real(wp), allocatable :: q0(:), u0(:)
        character(len=:), allocatable :: report

        call load_job(path, job, error)
        if (allocated(error)) return
        routine => job%routine
        call job%source%build(routine, problem, q0, u0, report, error)
        if (allocated(error)) return
        call part_shapes_of(problem%model, shapes, error, bases=problem%start_bases)
    end subroutine dataset_shapes

    !> write_model_shapes writes DIR/NAME.parts; read back, the shapes are the same numbers.
    subroutine test_round_trip(error)
        type(error_type), allocatable, intent(out) :: error
        type(model_type) :: model
        type(part_shape_type), allocatable :: shapes(:), written(:)

        call make_folder(scratch)
        call model%add_part(part_type(id=4, mass=0.7351_wp, inertia=[0.3_wp, 0.4_wp, 0.5_wp]))
        call model%add_part(part_type(id=12, mass=3.0_wp, inertia=[0.1_wp, 0.2_wp, 0.25_wp]))
        call part_shapes_of(model, written, error, disk_radius=0.1_wp, disk_thickness=0.003_wp, &
            & disk_part=2)
        if (.not. allocated(error)) call write_model_shapes(scratch // "/run.csv", model, &
            & error, disk_radius=0.1_wp, disk_thickness=0.003_wp)
        if (.not. allocated(error)) call write_part_shapes(scratch // "/other.parts", written, &
            & error)
        if (.not. allocated(error)) call read_part_shapes(scratch // "/other.parts", shapes, &
            & error)
        if (allocated(error)) then
            call remove_folder(scratch)
            return
        end if
        call check(error, size(shapes) == 2 .and. all(shapes%id == [4, 12]) .and. &
            & shapes(1)%kind == shape_ellipsoid .and. shapes(2)%kind == shape_disk .and. &
            & shapes(2)%radius == 0.1_wp .and. shapes(2)%thickness == 0.003_wp, &
            & "ids, kinds and the disk read back")
        if (.not. allocated(error)) call check(error, shapes(1)%semi_axes, &
            & written(1)%semi_axes, "semi-axes read back", abs_tol=tol_exact)
        if (.not. allocated(error)) call read_part_shapes(parts_path(scratch // "/run.csv"), &
            & shapes, error)
        if (.not. allocated(error)) call check(error, size(shapes) == 2 .and. &
            & shapes(1)%kind == shape_disk .and. shapes(2)%kind == shape_ellipsoid .and. &
            & parts_path(scratch // "/run.csv") == scratch // "/run.parts", "write_model_shapes: " &
            & // "part 1 the disk, in DIR/NAME.parts")
        call remove_folder(scratch)
    end subroutine test_round_trip

    !> Each kind of bad .parts file, with its exact message.
    subroutine test_file_refusals(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: path = scratch // "/bad.parts"
        character(len=*), parameter :: forms = "expected 'part <id> disk <radius> " &
            & // "<thickness>' or 'part <id> ellipsoid <a> <b> <c>' (lengths in m)"
        character(len=40) :: lines(6, 2)
        character(len=200) :: expected(6)
        type(part_shape_type), allocatable :: shapes(:)
        integer :: i

        lines(:, 1) = [character(len=40) :: "part 1 disk 0.1", "part 1 disk -0.1 0.003", &
            & "part 1 disk 0 0.003", "part 2 ellipsoid 0.1 0 0", "part 2 ellipsoid 1 1 1", &
            & "part 1 cube 1 1 1"]
        lines(:, 2) = [character(len=40) :: "", "", "", "", "part 2 ellipsoid 1 nan 1", ""]
        expected = [character(len=200) :: ":1: " // forms // ", got 'part 1 disk 0.1'", &
            & ":1: 'radius' must be a length >= 0 and at most 1e100 [m], got '-0.1'", &
            & ":1: 'radius' must be > 0 [m], got 0", &
            & ":1: an ellipsoid may have at most one zero semi-axis (a flat one), got " &
            & // "'part 2 ellipsoid 0.1 0 0'", &
            & ":2: 'b' must be a length >= 0 and at most 1e100 [m], got 'nan'", &
            & ":1: " // forms // ", got 'part 1 cube 1 1 1'"]
        call make_folder(scratch)
        do i = 1, size(expected)
            call write_lines(path, lines(i, :))
            call read_part_shapes(path, shapes, error)
            call expect_error(error, path // trim(expected(i)))
            if (allocated(error)) exit
        end do
        if (.not. allocated(error)) then
            call write_lines(path, [character(len=40) :: "# two parts", "part 2 disk 1 0", &
                & "part 2 ellipsoid 1 1 1"])
            call read_part_shapes(path, shapes, error)
            call expect_error(error, path // ":3: part 2 is described twice (first on line 2)")
        end if
        if (.not. allocated(error)) then
            call write_lines(path, [character(len=40) :: "# nothing", ""])
            call read_part_shapes(path, shapes, error)
            call expect_error(error, path // ": describes no part: " // forms)
        end if
        call remove_folder(scratch)
    end subroutine test_file_refusals

    !> A .parts file that lacks a part of its CSV, or names one the CSV does not hold.
    subroutine test_mismatch(error)
        type(error_type), allocatable, intent(out) :: error
        character(len=*), parameter :: csv = scratch // "/two.csv", parts = scratch // "/two.parts"
        type(run_record_type) :: run

        call make_folder(scratch)
        call write_run(csv, two_part_run(), .false., error)
        if (allocated(error)) return
        call write_lines(parts, [character(len=40) :: "part 1 disk 0.1 0.003"])
        call read_run(csv, run, error)
        call expect_error(error, parts // ": has no shape for part 7 of the CSV (parts 1, 7)")
        if (.not. allocated(error)) then
            call write_lines(parts, [character(len=40) :: "part 1 disk 0.1 0.003", &
                & "part 7 ellipsoid 1 1 1", "part 9 ellipsoid 1 1 1"])
            call read_run(csv, run, error)
            call expect_error(error, parts // ": describes part 9, which the CSV does not " &
                & // "hold (parts 1, 7): the file belongs to another run")
        end if
        call remove_folder(scratch)
    end subroutine test_mismatch

    !> A disk scene's CSV without its .parts file: the disk radius from Z/sin(theta), drawn
    !> with no thickness.
    subroutine test_fallback(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run

        call make_folder(scratch)
        call write_run(scratch // "/disk.csv", disk_run(), .false., error)
        if (.not. allocated(error)) call read_run(scratch // "/disk.csv", run, error)
        call remove_folder(scratch)
        if (allocated(error)) return
        call check(error, size(run%shapes) == 1 .and. run%shapes(1)%kind == shape_disk .and. &
            & run%shapes(1)%thickness == 0.0_wp, "one disk of no thickness")
        if (allocated(error)) return
        call check(error, run%shapes(1)%radius, disk_radius, "radius from Z/sin(theta)", &
            & rel_tol=tol_axes)
        if (allocated(error)) return
        ! with the file, its numbers win
        call make_folder(scratch)
        call write_run(scratch // "/disk.csv", disk_run(), .true., error)
        if (.not. allocated(error)) call read_run(scratch // "/disk.csv", run, error)
        call remove_folder(scratch)
        if (.not. allocated(error)) call check(error, run%shapes(1)%thickness == &
            & disk_thickness .and. run%shapes(1)%radius == disk_radius, "shapes of the file")
    end subroutine test_fallback

    !> Any other CSV without its .parts file is refused, naming the missing file.
    subroutine test_missing_parts(error)
        type(error_type), allocatable, intent(out) :: error
        type(run_record_type) :: run

        call make_folder(scratch)
        call write_run(scratch // "/two.csv", two_part_run(), .false., error)
        if (.not. allocated(error)) call read_run(scratch // "/two.csv", run, error)
        call remove_folder(scratch)
        call expect_error(error, scratch // "/two.parts: missing: the shapes of the parts of " &
            & // scratch // "/two.csv (written by rollcon run beside the CSV) are needed to " &
            & // "draw them; only a CSV of one part with a rim contact's columns is drawn " &
            & // "without it")
    end subroutine test_missing_parts

    !> Every mesh point lies on the ellipsoid in the part's pose, the points' mean is its centre,
    !> and every triangle's corners are distinct points of the mesh.
    subroutine test_mesh(error)
        type(error_type), allocatable, intent(out) :: error
        real(wp), parameter :: axes(3) = [0.5_wp, 0.8_wp, 0.3_wp]
        real(wp), parameter :: q(6) = [1.0_wp, -2.0_wp, 0.4_wp, 0.7_wp, 1.1_wp, -2.3_wp]
        real(wp) :: points(3, ellipsoid_point_count), body(3), r(3, 3)
        integer :: i, ids(3)

        points = ellipsoid_points(axes, q)
        r = rotation_matrix(q(4), q(5), q(6))
        do i = 1, ellipsoid_point_count
            body = matmul(transpose(r), points(:, i) - q(1:3))/axes
            call check(error, sum(body**2), 1.0_wp, "point " // trim(adjustl(int_text(i))) &
                & // " off the surface", abs_tol=tol_mesh)
            if (allocated(error)) return
        end do
        call check(error, sum(points, dim=2)/ellipsoid_point_count, q(1:3), "mean of the " &
            & // "mesh points", abs_tol=tol_mesh)
        do i = 1, ellipsoid_triangle_count
            if (allocated(error)) return
            ids = ellipsoid_triangle(i)
            call check(error, all(ids >= 0 .and. ids < ellipsoid_point_count) .and. &
                & ids(1) /= ids(2) .and. ids(2) /= ids(3) .and. ids(1) /= ids(3), "triangle " &
                & // trim(adjustl(int_text(i))) // " is not three distinct mesh points")
        end do
    contains
        pure function int_text(n) result(text)
            integer, intent(in) :: n
            character(len=12) :: text

            write(text, '(i0)') n
        end function int_text
    end subroutine test_mesh

    !> Fail unless message is allocated and equal to expected.
    subroutine expect_text(error, message, expected)
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable, intent(in) :: message
        character(len=*), intent(in) :: expected

        call check(error, allocated(message), "accepted; expected '" // expected // "'")
        if (allocated(error)) return
        call check(error, message == expected, "message '" // message // "', expected '" &
            & // expected // "'")
    end subroutine expect_text

    !> error, the outcome of a call, must hold exactly the message expected; it is replaced by
    !> the test's verdict.
    subroutine expect_error(error, expected)
        type(error_type), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: expected
        character(len=:), allocatable :: got

        if (.not. allocated(error)) then
            call check(error, .false., "accepted; expected '" // expected // "'")
            return
        end if
        got = error%message
        deallocate(error)
        call check(error, got == expected, "message '" // got // "', expected '" // expected &
            & // "'")
    end subroutine expect_error

end module test_part_shapes
