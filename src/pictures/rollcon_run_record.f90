! SPDX-License-Identifier: MIT
!> A run as its pictures see it: the CSV's layout and rows, and the shape of every part, from
!> the .parts file beside the CSV (rollcon_part_shapes) or, for the CSV of one part rolling on
!> a rim (a rim contact's columns, rollcon_contact_watch) without one, the rim's radius
!> recovered from the contact (docs/pictures.md).
module rollcon_run_record
    use rollcon_kinds, only : wp
    use rollcon_error, only : error_type, fatal_error, input_error, stat_io
    use rollcon_text, only : to_text
    use rollcon_history, only : history_type
    use rollcon_output_layout, only : output_layout_type, coord_x, coord_z, coord_theta, coord_phi
    use rollcon_csv_reader, only : read_output_csv, largest_value
    use rollcon_part_shapes, only : part_shape_type, read_part_shapes, parts_path, shape_disk
    use rollcon_disk_mesh, only : contact_point
    use rollcon_watch_columns, only : contact_names
    use rollcon_rotation, only : rotation_matrix, euler_angles
    use rollcon_rebasing, only : own_axes_rotation
    implicit none
    private

    public :: run_record_type, read_run, pose, rolls_on_rim, path_point, ground_bounds
    public :: read_friction, contact_part

    !> A run's output, ready to draw
    type :: run_record_type
        !> The CSV's columns
        type(output_layout_type) :: layout
        !> Its rows
        type(history_type) :: history
        !> Shape of each part, in the layout's (model) order
        type(part_shape_type), allocatable :: shapes(:)
        !> Where the shapes came from: the .parts file, or the CSV's first row (a disk scene
        !> without one)
        character(len=:), allocatable :: shapes_source
    end type run_record_type

contains

    !> Read a run's CSV and its part shapes. When DIR/NAME.parts is missing, a CSV with the
    !> contact columns and one part is drawn as a disk of radius R = Z/sin(theta) from its first
    !> row (the contact constraint, docs/design.md §5) and no thickness; any other CSV is refused,
    !> naming the missing file.
    subroutine read_run(csv_path, run, error)
        !> Output CSV of `rollcon run`
        character(len=*), intent(in) :: csv_path
        type(run_record_type), intent(out) :: run
        type(error_type), allocatable, intent(out) :: error
        type(part_shape_type), allocatable :: shapes(:)
        character(len=:), allocatable :: parts
        logical :: exists

        call read_output_csv(csv_path, run%layout, run%history, error)
        if (allocated(error)) return
        parts = parts_path(csv_path)
        inquire(file=parts, exist=exists)
        if (exists) then
            call read_part_shapes(parts, shapes, error)
            if (allocated(error)) return
            call match_shapes(parts, shapes, run%layout, run%shapes, error)
            run%shapes_source = parts
        else if (has_contact_columns(run%layout) .and. size(run%layout%part_ids) == 1) then
            call disk_from_contact(csv_path, run, error)
            run%shapes_source = csv_path // " (radius from Z/sin(theta) of the first row)"
        else
            call fatal_error(error, parts // ": missing: the shapes of the parts of " // csv_path &
                & // " (written by rollcon run beside the CSV) are needed to draw them; " &
                & // "only a CSV of one part with a rim contact's columns is drawn without it", &
                & stat_io)
        end if
    end subroutine read_run

    !> The shapes in the layout's order: one for every part of the CSV, none more.
    subroutine match_shapes(path, shapes, layout, ordered, error)
        character(len=*), intent(in) :: path
        type(part_shape_type), intent(in) :: shapes(:)
        type(output_layout_type), intent(in) :: layout
        type(part_shape_type), allocatable, intent(out) :: ordered(:)
        type(error_type), allocatable, intent(out) :: error
        integer :: p, s

        allocate(ordered(size(layout%part_ids)))
        do s = 1, size(shapes)
            if (layout%part_index(shapes(s)%id) == 0) then
                call input_error(error, path, 0, "", "describes part " // to_text(shapes(s)%id) &
                    & // ", which the CSV does not hold (parts " // id_list(layout%part_ids) &
                    & // "): the file belongs to another run")
                return
            end if
            ordered(layout%part_index(shapes(s)%id)) = shapes(s)
        end do
        do p = 1, size(layout%part_ids)
            if (any(shapes%id == layout%part_ids(p))) cycle
            call input_error(error, path, 0, "", "has no shape for part " &
                & // to_text(layout%part_ids(p)) // " of the CSV (parts " &
                & // id_list(layout%part_ids) // ")")
            return
        end do
    end subroutine match_shapes

    !> The disk of a disk scene's CSV: R = Z/sin(theta) of the first row.
    subroutine disk_from_contact(csv_path, run, error)
        character(len=*), intent(in) :: csv_path
        type(run_record_type), intent(inout) :: run
        type(error_type), allocatable, intent(out) :: error

        allocate(run%shapes(1))
        run%shapes(1)%id = run%layout%part_ids(1)
        run%shapes(1)%kind = shape_disk
        associate (z => run%history%rows(run%layout%part_column(1, coord_z), 1), &
            & theta => run%history%rows(run%layout%part_column(1, coord_theta), 1))
            ! Divide only when the quotient is a positive length no larger than largest_value,
            ! so no floating-point exception is raised.
            if (z > 0.0_wp .and. sin(theta) > 0.0_wp .and. z <= sin(theta)*largest_value) then
                run%shapes(1)%radius = z/sin(theta)
            else
                call input_error(error, csv_path, 2, "", "cannot infer the disk radius (no " &
                    & // "part shapes file beside the CSV): Z/sin(theta) must be a positive " &
                    & // "length, got Z = " // to_text(z) // " m, theta = " // to_text(theta) &
                    & // " rad")
            end if
        end associate
    end subroutine disk_from_contact

    !> X, Y, Z [m], psi, theta, phi [rad] of part p (layout order) in output row j; the angles
    !> of the part's own principal axes (its CM marker's, in which its shape is given) also
    !> in a row after a re-basing.
    pure function pose(run, p, j) result(q)
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: p, j
        real(wp) :: q(6)

        integer :: basis, column

        q = run%history%rows(run%layout%part_column(p, coord_x):run%layout%part_column(p, &
            & coord_phi), j)
        column = run%layout%column("basis_" // to_text(run%layout%part_ids(p)))
        if (column == 0) return
        ! a re-based row: the angles of the part's own axes, in which its shape is given
        ! (docs/rebasing.md)
        basis = nint(run%history%rows(column, j))
        if (basis /= 0) q(4:6) = euler_angles(own_axes_rotation(rotation_matrix(q(4), &
            & q(5), q(6)), basis))
    end function pose

    !> The point whose path the pictures draw for part p at output row j [m]: a disk's contact
    !> point (docs/design.md §5), any other part's centre of mass.
    pure function path_point(run, p, j) result(point)
        type(run_record_type), intent(in) :: run
        integer, intent(in) :: p, j
        real(wp) :: point(3)

        if (run%shapes(p)%kind == shape_disk) then
            point = contact_point(run%shapes(p)%radius, pose(run, p, j))
        else
            point = run%history%rows(run%layout%part_column(p, coord_x):run%layout%part_column(p, &
                & coord_z), j)
        end if
    end function path_point

    !> The smallest X-Y box holding every part's centre and path point over the whole run [m].
    pure subroutine ground_bounds(run, low, high)
        type(run_record_type), intent(in) :: run
        real(wp), intent(out) :: low(2), high(2)
        real(wp) :: point(3)
        integer :: p, j

        low = run%history%rows(run%layout%part_column(1, coord_x):run%layout%part_column(1, &
            & coord_x) + 1, 1)
        high = low
        do p = 1, size(run%layout%part_ids)
            do j = 1, run%history%count
                point = path_point(run, p, j)
                low = min(low, point(1:2), pose_xy(p, j))
                high = max(high, point(1:2), pose_xy(p, j))
            end do
        end do
    contains
        pure function pose_xy(p, j) result(xy)
            integer, intent(in) :: p, j
            real(wp) :: xy(2)

            xy = run%history%rows(run%layout%part_column(p, coord_x):run%layout%part_column(p, &
                & coord_x) + 1, j)
        end function pose_xy
    end subroutine ground_bounds

    !> True for the CSV of a part rolling on a rim: a rim contact's columns (its force, the
    !> friction it needs, its height residual: rollcon_contact_watch), and part 1 drawn as a
    !> disk. Such a run gets the contact's figures (rollcon_contact_figures).
    pure logical function rolls_on_rim(run)
        type(run_record_type), intent(in) :: run

        rolls_on_rim = has_contact_columns(run%layout) .and. size(run%shapes) >= 1
        if (rolls_on_rim) rolls_on_rim = run%shapes(1)%kind == shape_disk
    end function rolls_on_rim

    !> The layout has every column of a rim contact.
    pure logical function has_contact_columns(layout)
        type(output_layout_type), intent(in) :: layout
        integer :: k

        has_contact_columns = .true.
        do k = 1, size(contact_names)
            if (layout%column(trim(contact_names(k))) == 0) has_contact_columns = .false.
        end do
    end function has_contact_columns

    !> The contact's friction coefficients, mu_static and mu_kinetic, from the summary the run
    !> wrote beside its CSV (DIR/NAME.summary.txt for DIR/NAME.csv), whose line
    !> 'contact: starts rolling (mu_static 0.5, mu_kinetic 0.4), 10 switches' gives them
    !> (docs/outputs.md), or, given contact_id, the line of that CONTACT of several
    !> ('CONTACT/2 (line 40): starts ...'); found is false without that file or that line (a
    !> run without friction), and for numbers that do not read as 0 < mu_kinetic <= mu_static.
    subroutine read_friction(csv_path, friction, found, contact_id)
        !> Output CSV of `rollcon run`
        character(len=*), intent(in) :: csv_path
        !> mu_static, mu_kinetic [-]
        real(wp), intent(out) :: friction(2)
        logical, intent(out) :: found
        !> Of a dataset's several CONTACTs, this one's id: its line
        !> 'CONTACT/2 (line 40): starts sliding (mu_static 0.2, mu_kinetic 0.2), ...'
        integer, intent(in), optional :: contact_id
        !> The line, and what comes before each number: "(mu_static 0.5, mu_kinetic 0.4)"
        character(len=*), parameter :: start = "contact: starts ", &
            & keys(2) = [character(len=12) :: "(mu_static", ", mu_kinetic"]
        character(len=:), allocatable :: summary, marker
        character(len=4096) :: line
        integer :: unit, stat, k, at, finish

        found = .false.
        friction = 0.0_wp
        summary = csv_path
        if (len(csv_path) >= 4) then
            if (csv_path(len(csv_path) - 3:) == ".csv") summary = csv_path(:len(csv_path) - 4)
        end if
        summary = summary // ".summary.txt"
        open(newunit=unit, file=summary, status="old", action="read", iostat=stat)
        if (stat /= 0) return
        do
            read(unit, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (present(contact_id)) then
                if (index(line, "CONTACT/" // to_text(contact_id) // " (") /= 1 &
                    & .or. index(line, "): starts ") == 0) cycle
            else if (index(line, start) /= 1) then
                cycle
            end if
            found = .true.
            do k = 1, size(keys)
                marker = trim(keys(k)) // " "
                at = index(line, marker)
                if (at == 0) then
                    found = .false.
                    exit
                end if
                at = at + len(marker)
                finish = scan(line(at:), ",)")
                stat = 1
                if (finish > 1) read(line(at:at + finish - 2), *, iostat=stat) friction(k)
                if (stat /= 0) found = .false.
            end do
            exit
        end do
        close(unit)
        if (found) found = friction(2) > 0.0_wp .and. friction(2) <= friction(1)
        if (.not. found) friction = 0.0_wp
    end subroutine read_friction

    !> The part (model order) a run's contact holds on the ground, 0 for a run without the
    !> contact's columns. The contact's height_residual is its part's lowest point (a disk's
    !> rim's, an ellipsoid's centre less its semi-axis c, a sphere's radius) less the plane's
    !> height (the ground's 0, a turntable's top), so the part's lowest point less it is the
    !> same at every row, to rounding: of the parts for which it is (all parts when none is),
    !> the one whose difference at the first row is nearest zero; of parts equally near (two
    !> balls on the same ground), the one whose lowest point's velocity v_G + omega x (r_C -
    !> r_G) is nearest the contact's slip (slip_x, slip_y) over the rows. prefix: of a
    !> dataset's several CONTACTs, the one whose columns start so ("contact2_": its
    !> contact2_height_residual).
    pure integer function contact_part(run, prefix)
        type(run_record_type), intent(in) :: run
        character(len=*), intent(in), optional :: prefix
        !> Rounding of the heights' difference [m]: the CSV's shortest round-trip numbers and
        !> the .parts file's 17 digits give it to 1e-16 of the heights; 1e-9 m
        real(wp), parameter :: same_height = 1.0e-9_wp
        character(len=:), allocatable :: start
        real(wp) :: gap(size(run%shapes)), spread(size(run%shapes)), slip(size(run%shapes))
        real(wp) :: low, high, difference, nearest
        logical :: steady(size(run%shapes)), tied(size(run%shapes))
        integer :: p, j, height, slip_x, slip_y

        contact_part = 0
        start = ""
        if (present(prefix)) start = trim(prefix)
        height = run%layout%column(start // "height_residual")
        if (run%history%count < 1 .or. height == 0 .or. size(run%shapes) == 0) return
        if (.not. present(prefix) .and. .not. has_contact_columns(run%layout)) return
        do p = 1, size(run%shapes)
            low = huge(1.0_wp)
            high = -huge(1.0_wp)
            do j = 1, run%history%count
                difference = lowest_point(p, j) - run%history%rows(height, j)
                if (j == 1) gap(p) = abs(difference)
                low = min(low, difference)
                high = max(high, difference)
            end do
            spread(p) = high - low
        end do
        steady = spread <= same_height
        if (.not. any(steady)) steady = .true.
        nearest = minval(gap, mask=steady)
        tied = steady .and. gap <= nearest + same_height
        contact_part = findloc(tied, .true., dim=1)
        slip_x = run%layout%column(start // "slip_x")
        slip_y = run%layout%column(start // "slip_y")
        if (count(tied) < 2 .or. slip_x == 0 .or. slip_y == 0) return
        slip = huge(1.0_wp)
        do p = 1, size(run%shapes)
            if (.not. tied(p)) cycle
            slip(p) = 0.0_wp
            do j = 1, run%history%count
                slip(p) = slip(p) + norm2(point_velocity(p, j) &
                    & - [run%history%rows(slip_x, j), run%history%rows(slip_y, j)])
            end do
        end do
        contact_part = minloc(slip, dim=1)

    contains

        !> Part p's lowest point's height at row j [m].
        pure real(wp) function lowest_point(p, j)
            integer, intent(in) :: p, j
            real(wp) :: point(3)

            point = path_point(run, p, j)
            if (run%shapes(p)%kind /= shape_disk) point(3) = point(3) &
                & - run%shapes(p)%semi_axes(3)
            lowest_point = point(3)
        end function lowest_point

        !> The ground X and Y velocity of part p's material point at its lowest point at row j
        !> [m/s]: v_G + omega x (r_C - r_G), omega from the row's 3-1-3 angles and rates (the
        !> physical angular velocity, whatever basis the row's angles are in).
        pure function point_velocity(p, j) result(velocity)
            integer, intent(in) :: p, j
            real(wp) :: velocity(2)
            real(wp) :: q(12), omega(3), arm(3), centre(3), v(3)

            q = run%history%rows(run%layout%part_column(p, coord_x):run%layout%part_column(p, &
                & coord_x) + 11, j)
            omega = q(10)*[0.0_wp, 0.0_wp, 1.0_wp] + q(11)*[cos(q(4)), sin(q(4)), 0.0_wp] &
                & + q(12)*[sin(q(5))*sin(q(4)), -sin(q(5))*cos(q(4)), cos(q(5))]
            centre = q(1:3)
            if (run%shapes(p)%kind == shape_disk) then
                arm = path_point(run, p, j) - centre
            else
                arm = [0.0_wp, 0.0_wp, -run%shapes(p)%semi_axes(3)]
            end if
            v = q(7:9) + [omega(2)*arm(3) - omega(3)*arm(2), omega(3)*arm(1) &
                & - omega(1)*arm(3), omega(1)*arm(2) - omega(2)*arm(1)]
            velocity = v(1:2)
        end function point_velocity
    end function contact_part

    !> "1, 2, 7"
    pure function id_list(ids) result(text)
        integer, intent(in) :: ids(:)
        character(len=:), allocatable :: text
        integer :: i

        text = ""
        do i = 1, size(ids)
            if (i > 1) text = text // ", "
            text = text // to_text(ids(i))
        end do
    end function id_list

end module rollcon_run_record
